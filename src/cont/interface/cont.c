/*
   JRCont: frequency-response curves of a JRHBM problem by continuation, for several excitation
   levels (thesis 2.4), by one of the registered types (-cont_type):

   natural (2.4.2; src/cont/impls/natural/): step in frequency from the response of the stuck, linearised
     structure away from resonance, Newton (the JRHBM SNES) at each frequency.
   arclength (2.4.3; src/cont/impls/arclength/, the default): unknowns (a, w), a tangent predictor and a
     corrector on the bordered system with a pseudo-arclength or sphere constraint; passes turning points.

   This file: the object's life cycle and options, the level loop of JRContSolve, the steps the types share
   (the first point of a curve, adding a point, the progress line), the peak of each level and the summary table.
   JRPost writes the curves (JRPostWriteCurves, src/post/curves.c).
*/
#include <jointrom/private/contimpl.h>

PetscFunctionList JRContList = NULL;

/* Register a continuation type: its name (-cont_type) and the function that fills its ops */
PetscErrorCode JRContRegister(const char name[], PetscErrorCode (*create)(JRCont))
{
  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(PetscFunctionListAdd(&JRContList, name, create));
  PetscFunctionReturn(0);
}

/* Register the built-in types once (JRInitializePackage; JRFinalizePackage destroys the list) */
PetscErrorCode JRContRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (JRContList) PetscFunctionReturn(0);
  PetscCall(PetscFunctionListAdd(&JRContList, JRCONTNATURAL, JRContCreate_Natural));
  PetscCall(PetscFunctionListAdd(&JRContList, JRCONTARCLENGTH, JRContCreate_Arclength));
  PetscFunctionReturn(0);
}

/* Create a continuation: one level of 1 N, at most 2000 points per curve, output to out/frf; the type is set by
   JRContSetType, -cont_type, or arclength at JRContSolve */
PetscErrorCode JRContCreate(MPI_Comm comm, JRCont *cont)
{
  JRCont c;

  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(PetscNew(&c));
  c->comm    = comm;
  c->maxpts  = 2000;
  c->target  = 4;
  c->monitor = 1;
  c->secant  = PETSC_TRUE;
  c->plot    = PETSC_TRUE;
  c->write   = PETSC_TRUE;
  c->nlev    = 1;
  c->itol    = 0.008;
  c->ptol    = 1e-10;
  c->ltol    = 1e-8;
  c->ptolb   = 1e-5;
  c->stab      = PETSC_FALSE;
  c->stabsel   = JR_HILL_SELECT_VECTOR;
  c->stabtol   = 1e-6;
  c->stabdense = 400;
  c->stabdiss  = PETSC_TRUE;
  c->stabtime  = PETSC_TRUE;
  c->stabsteps = 64;
  c->stabfast  = 20;
  c->stablr    = 1;
  c->levpar    = PETSC_TRUE;
  PetscCall(PetscMalloc1(1, &c->levels));
  c->levels[0] = 1.0;
  PetscCall(PetscStrncpy(c->out, "out/frf", sizeof(c->out)));
  *cont = c;
  PetscFunctionReturn(0);
}

/* The continuation type: natural, arclength or a registered one (-cont_type) */
PetscErrorCode JRContSetType(JRCont c, JRContType type)
{
  PetscErrorCode (*create)(JRCont) = NULL;
  PetscBool match;

  PetscFunctionBeginUser;
  PetscCall(JRContRegisterAll());
  PetscCall(PetscStrcmp(c->type_name, type, &match));
  if (match) PetscFunctionReturn(0);
  PetscCall(PetscFunctionListFind(JRContList, type, &create));
  PetscCheck(create, c->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown continuation type '%s' (-cont_type): natural or arclength", type);
  if (c->ops->destroy) PetscCall((*c->ops->destroy)(c));
  PetscCall(PetscMemzero(c->ops, sizeof(struct _JRContOps)));
  c->data = NULL;
  PetscCall(PetscStrncpy(c->type_name, type, sizeof(c->type_name)));
  PetscCall((*create)(c));
  PetscFunctionReturn(0);
}

/* The continuation type's name; NULL before one is set */
PetscErrorCode JRContGetType(JRCont c, JRContType *type)
{
  PetscFunctionBeginUser;
  *type = c->type_name[0] ? c->type_name : NULL;
  PetscFunctionReturn(0);
}

PetscErrorCode JRContSetHBM(JRCont c, JRHBM hbm)
{
  PetscFunctionBeginUser;
  c->hbm = hbm;
  PetscFunctionReturn(0);
}

/* The harmonic balance whose curves c follows */
PetscErrorCode JRContGetHBM(JRCont c, JRHBM *hbm)
{
  PetscFunctionBeginUser;
  *hbm = c->hbm;
  PetscFunctionReturn(0);
}

/* Smallest and largest step: rad/s for natural, scaled arclength for arclength (-cont_step_min, -cont_step_max) */
PetscErrorCode JRContSetStepBounds(JRCont c, PetscReal smin, PetscReal smax)
{
  PetscFunctionBeginUser;
  PetscCheck(smin > 0 && smax >= smin, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Step bounds %g .. %g: need 0 < min <= max", (double)smin, (double)smax);
  c->stepmin = smin;
  c->stepmax = smax;
  PetscFunctionReturn(0);
}

/* The frequency range [rad/s] */
PetscErrorCode JRContGetRange(JRCont c, PetscReal *wmin, PetscReal *wmax)
{
  PetscFunctionBeginUser;
  if (wmin) *wmin = c->wmin;
  if (wmax) *wmax = c->wmax;
  PetscFunctionReturn(0);
}

/* The output base name (instead of -frf_output_file): BASE.h5, BASE.csv, BASE.png */
PetscErrorCode JRContSetOutputBase(JRCont c, const char base[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(c->out, base, sizeof(c->out)));
  c->write = c->out[0] ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The frequency range [rad/s] (-frf_omega_min/-frf_omega_max, or -frf_fmin/-frf_fmax in Hz); by default 0.8 to 1.2
   of the first elastic mode's frequency */
PetscErrorCode JRContSetRange(JRCont c, PetscReal wmin, PetscReal wmax)
{
  PetscFunctionBeginUser;
  PetscCheck(wmin > 0 && wmax > wmin, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Frequency range %g .. %g rad/s: need 0 < min < max", (double)wmin, (double)wmax);
  c->wmin      = wmin;
  c->wmax      = wmax;
  c->range_set = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The curves of every level and their arrays */
static PetscErrorCode BranchesDestroy(JRCont c)
{
  PetscFunctionBeginUser;
  for (PetscInt l = 0; c->br && l < c->nlev; l++) {
    PetscCall(PetscFree6(c->br[l].omega, c->br[l].a, c->br[l].amp, c->br[l].pp, c->br[l].step, c->br[l].its));
    PetscCall(PetscFree2(c->br[l].x, c->br[l].res));
    PetscCall(PetscFree2(c->br[l].wpk, c->br[l].apk));
    PetscCall(PetscFree(c->br[l].estate));
    PetscCall(JRContBranchStabilityFree(&c->br[l]));
  }
  PetscCall(PetscFree(c->br));
  PetscFunctionReturn(0);
}

/* Excitation levels F [N] (-frf_force); forgets the curves of the earlier levels */
PetscErrorCode JRContSetLevels(JRCont c, PetscInt n, const PetscReal F[])
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 1, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "At least one excitation level");
  PetscCall(BranchesDestroy(c));
  PetscCall(PetscFree(c->levels));
  PetscCall(PetscMalloc1(n, &c->levels));
  for (PetscInt i = 0; i < n; i++) {
    PetscCheck(PetscIsNormalReal(F[i]) && F[i] > 0, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_force %g: excitation levels must be positive and finite [N]", (double)F[i]);
    c->levels[i] = F[i];
  }
  c->nlev = n;
  PetscFunctionReturn(0);
}

/*
  Options: -cont_type natural|arclength (and the type's own: -cont_constraint pseudo|sphere for arclength),
  -cont_step, -cont_step_min, -cont_step_max, -cont_max_points, -cont_points (natural), -cont_newton_target,
  -cont_predictor secant|previous (natural), -cont_monitor 0|1|2; -frf_force F1,F2,.. [N],
  -frf_omega_min/-frf_omega_max [rad/s] or -frf_fmin/-frf_fmax [Hz], -frf_output_file BASE (BASE.h5, BASE.csv,
  BASE.png), -frf_plot, -frf_normalize (plot amplitude / force); -frf_stability 0|1 (Hill's method at every point,
  folds and branch points), -frf_stability_select vector|imag, -frf_stability_tol, -frf_stability_dense_max, -frf_stability_dissipative,
  -frf_stability_time, -frf_stability_time_steps, -frf_stability_time_fast.
*/
PetscErrorCode JRContSetFromOptions(JRCont c)
{
  char        type[64];
  PetscInt    nl = 64, pred = c->secant ? 0 : 1;
  PetscReal   lv[64], wmin = c->wmin, wmax = c->wmax, fmin = 0, fmax = 0;
  PetscBool   flg, f1, f2, f3, f4, fl, natural;
  const char *preds[] = {"secant", "previous", "Predictor", "", NULL};

  PetscFunctionBeginUser;
  PetscCall(JRContRegisterAll());
  for (PetscInt i = 0; i < nl; i++) lv[i] = i < c->nlev ? c->levels[i] : 0; /* -help shows the levels set */
  PetscOptionsBegin(c->comm, NULL, "Continuation (JRCont) and frequency-response output", "JRCont");
  PetscCall(PetscOptionsFList("-cont_type", "Continuation: natural (step in frequency) or arclength (pseudo-arclength, passes turning points)", "JRContSetType", JRContList, c->type_name[0] ? c->type_name : JRCONTARCLENGTH, type, sizeof(type), &flg));
  if (flg) PetscCall(JRContSetType(c, type));
  else if (!c->type_name[0]) PetscCall(JRContSetType(c, JRCONTARCLENGTH));
  if (c->ops->setfromoptions) PetscCall((*c->ops->setfromoptions)(c, PetscOptionsObject)); /* the type's own options, beside -cont_type in -help */
  PetscCall(PetscOptionsReal("-cont_step", "First step: rad/s (natural) or scaled arclength (arclength); default: 1/100 of the range, 0.01", "JRContSetFromOptions", c->step0, &c->step0, NULL));
  PetscCall(PetscOptionsReal("-cont_step_min", "Smallest step (rad/s or scaled arclength)", "JRContSetStepBounds", c->stepmin, &c->stepmin, NULL));
  PetscCall(PetscOptionsReal("-cont_step_max", "Largest step (rad/s or scaled arclength)", "JRContSetStepBounds", c->stepmax, &c->stepmax, NULL));
  PetscCall(PetscOptionsInt("-cont_max_points", "Most points per curve", "JRContSetFromOptions", c->maxpts, &c->maxpts, NULL));
  PetscCall(PetscOptionsInt("-cont_points", "Natural continuation on this many equally spaced frequencies (no step adaptation; benchmarks)", "JRContSetFromOptions", c->npoints, &c->npoints, NULL));
  PetscCall(PetscOptionsInt("-cont_newton_target", "Newton iterations per point the step control aims at", "JRContSetFromOptions", c->target, &c->target, NULL));
  PetscCall(PetscOptionsEList("-cont_predictor", "Natural continuation predictor: secant or previous solution", "JRContSetFromOptions", preds, 2, preds[pred], &pred, NULL));
  PetscCall(PetscOptionsBool("-cont_allow_partial", "A curve that cannot reach the end of its range (or turns back past its start) is written and reported, not an error", "JRContCheckComplete", c->partial, &c->partial, NULL));
  PetscCall(PetscOptionsReal("-cont_interp_tol", "Largest relative error of linear interpolation between consecutive points of a curve (its step control); 0: no control", "JRContSolve", c->itol, &c->itol, NULL));
  PetscCall(PetscOptionsReal("-cont_peak_tol", "Relative amplitude tolerance of the peaks, found by harmonic-balance solves along the curve", "JRContSolve", c->ptol, &c->ptol, NULL));
  PetscCall(PetscOptionsReal("-cont_locate_tol", "Relative frequency tolerance of the folds and branch points (-frf_stability), located by harmonic-balance solves along the curve", "JRContStability", c->ltol, &c->ltol, NULL));
  PetscCall(PetscOptionsReal("-cont_locate_pair_tol", "The same for branch points of kind pair (bisection on the stability, a monodromy matrix per step; the exponents' own error moves them more)", "JRContStability", c->ptolb, &c->ptolb, NULL));
  PetscCall(PetscOptionsInt("-cont_monitor", "Progress: 0 none, 1 every 25th point and each level, 2 every point", "JRContSetFromOptions", c->monitor, &c->monitor, NULL));
  PetscCall(PetscOptionsBool("-cont_levels_parallel", "A reduced model (its elements on every rank): its levels' curves shared out over the ranks, each solved by one rank; 0: every rank solves every level", "JRContSolve", c->levpar, &c->levpar, NULL));
  PetscCall(PetscOptionsRealArray("-frf_force", "Excitation levels F [N]: f(t) = F sin(w t) at -frf_dof", "JRContSetLevels", lv, &nl, &fl));
  PetscCall(PetscOptionsReal("-frf_omega_min", "Lowest frequency [rad/s]", "JRContSetRange", wmin, &wmin, &f1));
  PetscCall(PetscOptionsReal("-frf_omega_max", "Highest frequency [rad/s]", "JRContSetRange", wmax, &wmax, &f2));
  PetscCall(PetscOptionsReal("-frf_fmin", "Lowest frequency [Hz] (instead of -frf_omega_min)", "JRContSetRange", fmin, &fmin, &f3));
  PetscCall(PetscOptionsReal("-frf_fmax", "Highest frequency [Hz] (instead of -frf_omega_max)", "JRContSetRange", fmax, &fmax, &f4));
  PetscCall(PetscOptionsString("-frf_output_file", "Output base name: BASE.h5 (all points), BASE.csv, BASE.png ('' for none)", "JRPostWriteCurves", c->out, c->out, sizeof(c->out), NULL));
  PetscCall(PetscOptionsBool("-frf_plot", "Draw BASE.png", "JRPostWriteCurves", c->plot, &c->plot, NULL));
  PetscCall(PetscOptionsBool("-frf_normalize", "Plot the normalised displacement amplitude / force [m/N]", "JRPostWriteCurves", c->normalize, &c->normalize, NULL));
  PetscCall(PetscOptionsBool("-frf_stability", "Stability of every point (Floquet exponents), folds and branch points; default: on where it costs little next to the curve (JRHBMStabilityCheap)", "JRContStability", c->stab, &c->stab, &c->stabset));
  PetscCall(PetscOptionsEnum("-frf_stability_select", "Which exponents are the physical ones: vector (eigenvectors centred on the mean harmonic) or imag (|Im| <= w/2)", "JRHBMFloquet", JRHillSelects, (PetscEnum)c->stabsel, (PetscEnum *)&c->stabsel, NULL));
  PetscCall(PetscOptionsReal("-frf_stability_tol", "A point is stable if every kept exponent has Re < tol w", "JRContStability", c->stabtol, &c->stabtol, NULL));
  PetscCall(PetscOptionsBool("-frf_stability_dissipative", "Points whose elements make the response incrementally dissipative (jenkins; jenkins_nv stuck or separated over the cycle) are stable without an eigenproblem; 0: Hill's method everywhere", "JRContStability", c->stabdiss, &c->stabdiss, NULL));
  PetscCall(PetscOptionsBool("-frf_stability_time", "Points with friction elements changing state: Floquet exponents of the monodromy matrix marched over one period; 0: Hill's method, whose flags there indicate", "JRHBMFloquetTime", c->stabtime, &c->stabtime, NULL));
  PetscCall(PetscOptionsInt("-frf_stability_time_steps", "Least steps per period of the monodromy matrix (and at least -hbm_samples; with a cubic spring also dt w_max <= 0.5)", "JRHBMFloquetTime", c->stabsteps, &c->stabsteps, NULL));
  PetscCall(PetscOptionsReal("-frf_stability_time_fast", "Kept modes above this many times H w condensed quasi-statically in the monodromy matrix (their inertia dropped); 0: every mode marched", "JRHBMSetFloquetFast", c->stabfast, &c->stabfast, NULL));
  {
    const char *const lr[] = {"no", "auto", "yes"};
    PetscInt          v    = c->stablr;
    PetscCall(PetscOptionsEList("-frf_stability_time_lowrank", "Fast modes condensed through the elements' distinct rows (Woodbury; reduced models' joints): auto where at most half as many as the fast modes, yes where at most half the kept modes, no: the fast block's inverse at every step", "JRHBMSetFloquetLowRank", lr, 3, lr[v], &v, NULL));
    c->stablr = v;
  }
  PetscCall(PetscOptionsInt("-frf_stability_dense_max", "Largest nm (2H+1) solved by LAPACK's QZ; above it SLEPc's PEP (prefix hbm_hill_, strip selection)", "JRHBMFloquet", c->stabdense, &c->stabdense, NULL));
  PetscOptionsEnd();
  c->secant = pred == 0 ? PETSC_TRUE : PETSC_FALSE;
  c->write  = c->out[0] ? PETSC_TRUE : PETSC_FALSE;
  if (fl) PetscCall(JRContSetLevels(c, nl, lv));
  PetscCheck(!(f1 && f3) && !(f2 && f4), c->comm, PETSC_ERR_ARG_INCOMP, "Give the range in rad/s (-frf_omega_min/max) or in Hz (-frf_fmin/fmax), not both");
  if (f3) wmin = 2.0 * PETSC_PI * fmin;
  if (f4) wmax = 2.0 * PETSC_PI * fmax;
  if (f1 || f2 || f3 || f4) {
    PetscCheck((f1 || f3) && (f2 || f4), c->comm, PETSC_ERR_ARG_INCOMP, "Give both ends of the frequency range (-frf_omega_min and -frf_omega_max, or -frf_fmin and -frf_fmax)");
    PetscCheck(PetscIsNormalReal(wmin) && PetscIsNormalReal(wmax) && wmin > 0 && wmax > wmin, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Frequency range %g .. %g rad/s (%g .. %g Hz): need 0 < min < max", (double)wmin, (double)wmax, (double)(wmin / (2 * PETSC_PI)), (double)(wmax / (2 * PETSC_PI)));
    PetscCall(JRContSetRange(c, wmin, wmax));
  }
  PetscCall(PetscStrcmp(c->type_name, JRCONTNATURAL, &natural));
  PetscCheck(c->npoints == 0 || (c->npoints >= 2 && natural), c->comm, PETSC_ERR_ARG_INCOMP, "-cont_points %" PetscInt_FMT ": at least 2, with -cont_type natural", c->npoints);
  PetscCheck(c->maxpts >= 2, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cont_max_points %" PetscInt_FMT ": at least 2", c->maxpts);
  PetscCheck(c->target >= 1, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cont_newton_target %" PetscInt_FMT ": at least 1", c->target);
  PetscCheck(c->itol >= 0 && c->itol < 1, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cont_interp_tol %g: between 0 (no control) and 1", (double)c->itol);
  PetscCheck(c->ptol > 0 && c->ptol < 0.1, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cont_peak_tol %g: between 0 and 0.1", (double)c->ptol);
  PetscCheck(c->ltol > 0 && c->ltol < 0.1, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cont_locate_tol %g: between 0 and 0.1", (double)c->ltol);
  PetscCheck(c->ptolb > 0 && c->ptolb < 0.1, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cont_locate_pair_tol %g: between 0 and 0.1", (double)c->ptolb);
  PetscCheck(c->stabtol >= 0 && c->stabtol < 1, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_stability_tol %g: between 0 and 1 (relative to the frequency)", (double)c->stabtol);
  PetscCheck(c->stabsteps >= 4 && c->stabsteps <= 1000000, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_stability_time_steps %" PetscInt_FMT ": give 4 to 1e6 steps per period", c->stabsteps);
  PetscCheck(c->stabfast == 0 || c->stabfast >= 2, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_stability_time_fast %g: give 0 (every mode marched) or at least 2", (double)c->stabfast);
  PetscCheck(c->stabdense >= 0, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_stability_dense_max %" PetscInt_FMT ": not negative", c->stabdense);
  PetscCheck(c->step0 >= 0 && c->stepmin >= 0 && c->stepmax >= 0, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cont_step, -cont_step_min, -cont_step_max must be positive");
  PetscFunctionReturn(0);
}

/* y = [J Rw; row^T] x (a JRContBordered) */
PetscErrorCode JRContBorderedMult(void *ctx, const PetscScalar *x, PetscScalar *y)
{
  JRContBordered    *bo = (JRContBordered *)ctx;
  const PetscInt     n  = bo->n;
  const PetscScalar *rw;
  PetscScalar        s = 0;

  PetscFunctionBeginUser;
  PetscCall(JRHBMJacobianMult(bo->hbm, bo->J, x, y));
  PetscCall(VecGetArrayRead(bo->Rw, &rw));
  for (PetscInt i = 0; i < n; i++) y[i] += rw[i] * x[n];
  PetscCall(VecRestoreArrayRead(bo->Rw, &rw));
  for (PetscInt i = 0; i <= n; i++) s += bo->row[i] * x[i];
  y[n] = s;
  PetscCall(PetscLogFlops(4.0 * n));
  PetscFunctionReturn(0);
}

/* [J Rw; row^T] into A (leading dimension lda) */
PetscErrorCode JRContBorderedForm(void *ctx, PetscScalar *A, PetscInt lda)
{
  JRContBordered    *bo = (JRContBordered *)ctx;
  const PetscInt     n  = bo->n;
  const PetscScalar *rw;

  PetscFunctionBeginUser;
  PetscCall(JRHBMJacobianForm(bo->hbm, bo->J, A, lda));
  PetscCall(VecGetArrayRead(bo->Rw, &rw));
  for (PetscInt i = 0; i < n; i++) A[i + n * lda] = rw[i];
  PetscCall(VecRestoreArrayRead(bo->Rw, &rw));
  for (PetscInt c = 0; c <= n; c++) A[n + c * lda] = bo->row[c];
  PetscFunctionReturn(0);
}

/* Room for cap points on the curve b, its points so far kept */
static PetscErrorCode BranchReserve(JRCont c, JRContBranch *b, PetscInt cap)
{
  PetscReal *o, *aa, *amp, *pp, *st, *xs, *rs;
  PetscInt  *it;

  PetscFunctionBeginUser;
  if (cap <= b->cap) PetscFunctionReturn(0);
  PetscCall(PetscMalloc6(cap, &o, cap * c->nmod, &aa, cap * c->nout, &amp, cap * c->nout, &pp, cap, &st, cap, &it));
  PetscCall(PetscMalloc2(cap * c->n, &xs, cap, &rs));
  if (b->np) {
    PetscCall(PetscArraycpy(o, b->omega, b->np));
    PetscCall(PetscArraycpy(aa, b->a, b->np * c->nmod));
    PetscCall(PetscArraycpy(amp, b->amp, b->np * c->nout));
    PetscCall(PetscArraycpy(pp, b->pp, b->np * c->nout));
    PetscCall(PetscArraycpy(st, b->step, b->np));
    PetscCall(PetscArraycpy(it, b->its, b->np));
    PetscCall(PetscArraycpy(xs, b->x, b->np * c->n));
    PetscCall(PetscArraycpy(rs, b->res, b->np));
  }
  PetscCall(PetscFree6(b->omega, b->a, b->amp, b->pp, b->step, b->its));
  PetscCall(PetscFree2(b->x, b->res));
  if (!b->wpk) PetscCall(PetscCalloc2(c->nout, &b->wpk, c->nout, &b->apk));
  b->omega = o;
  b->a     = aa;
  b->amp   = amp;
  b->pp    = pp;
  b->step  = st;
  b->its   = it;
  b->x     = xs;
  b->res   = rs;
  b->cap   = cap;
  PetscFunctionReturn(0);
}

/* Append the point (w, a) to the curve: its unknowns, modal unknowns and responses at the outputs; res: its relative
   residual (JRHBMResidualNorm) */
PetscErrorCode JRContBranchAdd(JRCont c, JRContBranch *b, PetscReal w, Vec a, PetscInt its, PetscReal step, PetscReal res)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMExpand(c->hbm, w, a, c->amod)); /* the branch keeps the modal unknowns */
  PetscCall(JRContBranchAddExpanded(c, b, w, a, c->amod, its, step, res));
  PetscFunctionReturn(0);
}

/* The same with the point's modal unknowns amod given (JRHBMExpand of (w, a), computed by the caller) */
PetscErrorCode JRContBranchAddExpanded(JRCont c, JRContBranch *b, PetscReal w, Vec a, Vec amod, PetscInt its, PetscReal step, PetscReal res)
{
  const PetscScalar *x;

  PetscFunctionBeginUser;
  if (b->np == b->cap) PetscCall(BranchReserve(c, b, b->cap ? 2 * b->cap : 128));
  b->omega[b->np] = w;
  b->res[b->np]   = res;
  b->resmax       = PetscMax(b->resmax, res);
  PetscCall(VecGetArrayRead(a, &x));
  for (PetscInt i = 0; i < c->n; i++) b->x[b->np * c->n + i] = PetscRealPart(x[i]);
  PetscCall(VecRestoreArrayRead(a, &x));
  PetscCall(VecGetArrayRead(amod, &x));
  for (PetscInt i = 0; i < c->nmod; i++) b->a[b->np * c->nmod + i] = PetscRealPart(x[i]);
  PetscCall(VecRestoreArrayRead(amod, &x));
  PetscCall(JRHBMResponse(c->hbm, amod, NULL, b->amp + b->np * c->nout, b->pp + b->np * c->nout));
  b->its[b->np]  = its;
  b->step[b->np] = step;
  b->newton += its;
  b->np++;
  PetscFunctionReturn(0);
}

/* The progress line of the last point (-cont_monitor: 1 every 25th point, 2 every point) */
PetscErrorCode JRContMonitor(JRCont c, PetscInt lev, JRContBranch *b)
{
  PetscFunctionBeginUser;
  if (!c->monitor || c->quiet || !b->np) PetscFunctionReturn(0);
  if (c->monitor >= 2 || (b->np - 1) % 25 == 0) {
    const PetscInt k = b->np - 1;
    PetscCall(JRContPrintf(c, "cont: level %" PetscInt_FMT "/%" PetscInt_FMT " F %g N  point %4" PetscInt_FMT "  f %.6g Hz  amp %.4e m  newton %" PetscInt_FMT "  step %.3g\n", lev + 1, c->nlev, (double)b->F, k, (double)(b->omega[k] / (2 * PETSC_PI)), (double)b->amp[k * c->nout], b->its[k], (double)b->step[k]));
  }
  PetscFunctionReturn(0);
}

/* The first point of a curve: Newton at the start of the range from the linearised response, into a */
PetscErrorCode JRContBranchStart(JRCont c, PetscInt lev, JRContBranch *b, Vec a)
{
  PetscInt  its;
  PetscBool conv;
  PetscReal res;

  PetscFunctionBeginUser;
  PetscCall(JRHBMLinearSolution(c->hbm, c->wmin, a));
  PetscCall(JRHBMSolveResidual(c->hbm, c->wmin, a, &its, &conv, &res));
  PetscCheck(conv, c->comm, PETSC_ERR_NOT_CONVERGED, "Level F = %g N: no solution at the start of the range, %g Hz (relative residual %.2e; try a lower -frf_fmin, or -hbm_snes_* options)", (double)b->F, (double)(c->wmin / (2 * PETSC_PI)), (double)res);
  PetscCall(JRContBranchAdd(c, b, c->wmin, a, its, 0.0, res));
  PetscCall(JRContMonitor(c, lev, b));
  PetscFunctionReturn(0);
}

/* a <- the modal unknowns of point k */
static PetscErrorCode PointUnknowns(JRCont c, JRContBranch *b, PetscInt k, Vec a)
{
  PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(a, &x));
  for (PetscInt j = 0; j < c->nmod; j++) x[j] = b->a[k * c->nmod + j];
  PetscCall(VecRestoreArray(a, &x));
  PetscFunctionReturn(0);
}

/* The energies at every point: the worst imbalance b->ebal, and the equivalent damping ratio b->zeta at the peak */
static PetscErrorCode PeakDamping(JRCont c, JRContBranch *b, Vec a)
{
  PetscFunctionBeginUser;
  b->ebal = 0.0;
  for (PetscInt i = 0; i < b->np; i++) {
    PetscReal win, ed, enl;
    PetscCall(PointUnknowns(c, b, i, a));
    PetscCall(JRHBMEnergy(c->hbm, b->omega[i], a, &win, &ed, &enl));
    if (win > 0) b->ebal = PetscMax(b->ebal, PetscAbsReal(win - ed - enl) / win);
    if (i == b->kpeak) {
      PetscReal T;
      PetscCall(JRHBMKineticEnergy(c->hbm, b->omega[i], a, &T));
      b->zeta = T > 0 ? (ed + enl) / (8 * PETSC_PI * T) : 0.0;
    }
  }
  PetscFunctionReturn(0);
}

/* Peak, equivalent damping, energy balance, contact states (level lev done; a: work vector, modal; collective) */
static PetscErrorCode Peak(JRCont c, PetscInt lev, Vec a)
{
  JRContBranch *b = &c->br[lev];
  PetscInt      nel;

  PetscFunctionBeginUser;
  PetscCall(JRContRefinePeaks(c, b));
  PetscCall(PeakDamping(c, b, a));
  PetscCall(PointUnknowns(c, b, b->kpeak, a));
  PetscCall(JRHBMContactStates(c->hbm, a, b->states));
  nel = b->states[0] + b->states[1] + b->states[2] + b->states[3];
  PetscCall(PetscFree(b->estate));
  PetscCall(PetscMalloc1(nel, &b->estate));
  PetscCall(JRHBMElementStates(c->hbm, a, b->estate));
  PetscFunctionReturn(0);
}

/* No range given: 0.8 to 1.2 of the first elastic mode's frequency */
static PetscErrorCode DefaultRange(JRCont c)
{
  PetscInt         nm;
  const PetscReal *om;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetModalFrequencies(c->hbm, &nm, &om));
  PetscCheck(nm > 0, c->comm, PETSC_ERR_ARG_WRONGSTATE, "Give the frequency range (-frf_fmin/-frf_fmax in Hz or -frf_omega_min/-frf_omega_max in rad/s)");
  for (PetscInt i = 0; i < nm; i++)
    if (om[i] > 1e-6 * om[nm - 1]) {
      PetscCall(JRContSetRange(c, 0.8 * om[i], 1.2 * om[i]));
      break;
    }
  PetscCheck(c->range_set, c->comm, PETSC_ERR_ARG_WRONGSTATE, "No elastic mode to centre the frequency range on: give -frf_fmin/-frf_fmax");
  PetscFunctionReturn(0);
}

/* Before the levels: the sizes, the range, the work vectors (a: the solve space), the type's work, empty curves */
static PetscErrorCode SolveSetUp(JRCont c, Vec *a)
{
  PetscFunctionBeginUser;
  PetscCheck(c->hbm, c->comm, PETSC_ERR_ARG_WRONGSTATE, "JRContSetHBM() first");
  if (!c->type_name[0]) PetscCall(JRContSetType(c, JRCONTARCLENGTH));
  PetscCall(JRHBMGetSizes(c->hbm, NULL, NULL, &c->nmod));
  PetscCall(JRHBMGetSolveSize(c->hbm, &c->n, NULL));
  PetscCall(JRHBMGetOutputs(c->hbm, &c->nout, NULL));
  if (!c->range_set) PetscCall(DefaultRange(c));
  PetscCall(JRHBMCreateVecs(c->hbm, a, NULL));
  PetscCall(VecDestroy(&c->amod));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, c->nmod, &c->amod));
  PetscCall(PetscFree(c->ampw));
  PetscCall(PetscMalloc1(2 * c->nout, &c->ampw));
  PetscCall(JRContPlaneWorkCreate(c));
  if (c->ops->setup) PetscCall((*c->ops->setup)(c));
  PetscCall(BranchesDestroy(c));
  PetscCall(PetscCalloc1(c->nlev, &c->br));
  PetscFunctionReturn(0);
}

/* The factors kept from earlier solves dropped: what follows does not depend on the levels solved before, nor on
   which rank solved them */
static PetscErrorCode ForgetFactors(JRCont c)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMForgetFactors(c->hbm));
  PetscCall(JRContPlaneWorkForget(c));
  if (c->ops->forget) PetscCall((*c->ops->forget)(c));
  PetscFunctionReturn(0);
}

/* Level lev's curve by the type and its peak */
static PetscErrorCode CurveLevel(JRCont c, PetscInt lev, Vec a)
{
  JRContBranch  *b = &c->br[lev];
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  b->F = c->levels[lev];
  PetscCall(JRHBMSetForceLevel(c->hbm, b->F));
  PetscCall(ForgetFactors(c));
  PetscCall((*c->ops->solvelevel)(c, lev, b, a));
  PetscCall(PetscTime(&t1));
  b->seconds = t1 - t0;
  PetscCall(Peak(c, lev, c->amod));
  PetscFunctionReturn(0);
}

/* Level lev after its curve: the stability of its points and (unless quiet) its lines. Collective. */
static PetscErrorCode EndLevel(JRCont c, PetscInt lev, Vec a)
{
  JRContBranch *b = &c->br[lev];

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetForceLevel(c->hbm, b->F));
  PetscCall(ForgetFactors(c));
  PetscCall(JRContStability(c, lev, a));
  if (c->quiet) PetscFunctionReturn(0);
  if (c->monitor) PetscCall(PetscPrintf(c->comm, "cont: level %" PetscInt_FMT "/%" PetscInt_FMT " F %g N done: %" PetscInt_FMT " points, %" PetscInt_FMT " Newton iterations, %" PetscInt_FMT " retries, largest relative residual %.2e, %.3g s%s\n", lev + 1, c->nlev, (double)b->F, b->np, b->newton, b->retries, (double)b->resmax, (double)b->seconds, b->complete ? "" : " (incomplete: see above)"));
  PetscCall(PetscPrintf(c->comm, "peak level %g freq_hz %.8g amp %.8e amp_over_force %.8e\n", (double)b->F, (double)(b->wpeak / (2 * PETSC_PI)), (double)b->apeak, (double)(b->apeak / b->F)));
  for (PetscInt o = 1; o < c->nout; o++) PetscCall(PetscPrintf(c->comm, "response_peak level %g response %" PetscInt_FMT " freq_hz %.8g amp %.8e amp_over_force %.8e\n", (double)b->F, o + 1, (double)(b->wpk[o] / (2 * PETSC_PI)), (double)b->apk[o], (double)(b->apk[o] / b->F)));
  PetscFunctionReturn(0);
}

/* Print on rank 0 of c's communicator; while the rank solves levels alone (CurvesApart), into its text instead */
PetscErrorCode JRContPrintf(JRCont c, const char fmt[], ...)
{
  char    line[2048];
  size_t  len;
  va_list ap;

  PetscFunctionBeginUser;
  va_start(ap, fmt);
  PetscCall(PetscVSNPrintf(line, sizeof(line), fmt, &len, ap));
  va_end(ap);
  if (!c->buffered) {
    PetscCall(PetscPrintf(c->comm, "%s", line));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscStrlen(line, &len));
  if (c->tlen + len + 1 > c->tcap) {
    char *t;
    c->tcap = 2 * (c->tlen + len + 1) + 4096;
    PetscCall(PetscMalloc1(c->tcap, &t));
    if (c->tlen) PetscCall(PetscArraycpy(t, c->text, c->tlen));
    PetscCall(PetscFree(c->text));
    c->text = t;
  }
  PetscCall(PetscArraycpy(c->text + c->tlen, line, len));
  c->tlen += len;
  c->text[c->tlen] = 0;
  PetscFunctionReturn(0);
}

/* Level b's curve and peak, as the rank root computed them, on every rank of c's communicator */
static PetscErrorCode BranchBcast(JRCont c, JRContBranch *b, PetscMPIInt root)
{
  PetscMPIInt rank;
  PetscInt    ni[11];
  PetscReal   nr[7];
  MPI_Comm    comm = c->comm;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == root) {
    PetscInt k = 0;
    ni[k++] = b->np;
    ni[k++] = b->retries;
    for (PetscInt i = 0; i < 4; i++) ni[k++] = b->states[i];
    ni[k++] = b->complete;
    ni[k++] = b->newton;
    ni[k++] = b->kpeak;
    ni[k++] = b->refine_its;
    ni[k++] = b->estate ? 1 : 0;
    nr[0]   = b->F;
    nr[1]   = b->seconds;
    nr[2]   = b->wpeak;
    nr[3]   = b->apeak;
    nr[4]   = b->resmax;
    nr[5]   = b->zeta;
    nr[6]   = b->ebal;
  }
  PetscCallMPI(MPI_Bcast(ni, 11, MPIU_INT, root, comm));
  PetscCallMPI(MPI_Bcast(nr, 7, MPIU_REAL, root, comm));
  PetscCallMPI(MPI_Bcast(b->why, sizeof(b->why), MPI_CHAR, root, comm));
  if (rank != root) {
    const PetscInt np = ni[0], cap = PetscMax(np, 1);
    PetscInt       k  = 1;
    PetscCheck(!b->cap, PETSC_COMM_SELF, PETSC_ERR_PLIB, "BranchBcast: the level was solved here too");
    b->retries = ni[k++];
    for (PetscInt i = 0; i < 4; i++) b->states[i] = ni[k++];
    b->complete   = (PetscBool)ni[k++];
    b->newton     = ni[k++];
    b->kpeak      = ni[k++];
    b->refine_its = ni[k++];
    b->F          = nr[0];
    b->seconds    = nr[1];
    b->wpeak      = nr[2];
    b->apeak      = nr[3];
    b->resmax     = nr[4];
    b->zeta       = nr[5];
    b->ebal       = nr[6];
    PetscCall(BranchReserve(c, b, cap));
    b->np = np;
    if (ni[10]) PetscCall(PetscMalloc1(b->states[0] + b->states[1] + b->states[2] + b->states[3], &b->estate));
  }
  if (b->np) {
    PetscCallMPI(MPI_Bcast(b->omega, (PetscMPIInt)b->np, MPIU_REAL, root, comm));
    PetscCallMPI(MPI_Bcast(b->a, (PetscMPIInt)(b->np * c->nmod), MPIU_REAL, root, comm));
    PetscCallMPI(MPI_Bcast(b->amp, (PetscMPIInt)(b->np * c->nout), MPIU_REAL, root, comm));
    PetscCallMPI(MPI_Bcast(b->pp, (PetscMPIInt)(b->np * c->nout), MPIU_REAL, root, comm));
    PetscCallMPI(MPI_Bcast(b->step, (PetscMPIInt)b->np, MPIU_REAL, root, comm));
    PetscCallMPI(MPI_Bcast(b->its, (PetscMPIInt)b->np, MPIU_INT, root, comm));
    PetscCallMPI(MPI_Bcast(b->x, (PetscMPIInt)(b->np * c->n), MPIU_REAL, root, comm));
    PetscCallMPI(MPI_Bcast(b->res, (PetscMPIInt)b->np, MPIU_REAL, root, comm));
  }
  if (b->wpk) {
    PetscCallMPI(MPI_Bcast(b->wpk, (PetscMPIInt)c->nout, MPIU_REAL, root, comm));
    PetscCallMPI(MPI_Bcast(b->apk, (PetscMPIInt)c->nout, MPIU_REAL, root, comm));
  }
  if (ni[10]) PetscCallMPI(MPI_Bcast(b->estate, (PetscMPIInt)(b->states[0] + b->states[1] + b->states[2] + b->states[3]), MPI_INT, root, comm));
  PetscFunctionReturn(0);
}

/*
  The levels' curves and peaks of a replicated model (a reduced one: every rank holds all its elements) shared out
  over the ranks, level l on rank l mod size, each rank alone (JRHBMSetLocal), then every level's on every rank; the
  lines each rank printed for its levels, text[l], are for the caller to print in the levels' order. Every
  level starts from no kept factors (ForgetFactors) and samples its response scale at 1 N, so a level's curve is the
  same, to the bit, whichever rank solves it and after whichever levels.
*/
static PetscErrorCode CurvesApart(JRCont c, Vec a, char ***txt)
{
  MPI_Comm    comm = c->comm;
  PetscMPIInt rank, size;
  char      **text;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscCalloc1(c->nlev, &text));
  PetscCall(JRHBMSetLocal(c->hbm, PETSC_TRUE));
  c->comm     = PETSC_COMM_SELF;
  c->buffered = PETSC_TRUE;
  for (PetscInt lev = rank; lev < c->nlev; lev += size) {
    c->tlen = 0;
    if (c->text) c->text[0] = 0;
    PetscCall(CurveLevel(c, lev, a));
    PetscCall(PetscStrallocpy(c->text ? c->text : "", &text[lev]));
  }
  c->buffered = PETSC_FALSE;
  c->comm     = comm;
  PetscCall(JRHBMSetLocal(c->hbm, PETSC_FALSE));
  for (PetscInt lev = 0; lev < c->nlev; lev++) {
    const PetscMPIInt root = (PetscMPIInt)(lev % size);
    size_t            sl   = 0;
    PetscInt          len  = 0;
    PetscCall(BranchBcast(c, &c->br[lev], root));
    if (rank == root) PetscCall(PetscStrlen(text[lev], &sl));
    len = (PetscInt)sl;
    PetscCallMPI(MPI_Bcast(&len, 1, MPIU_INT, root, comm));
    if (rank != root) PetscCall(PetscMalloc1(len + 1, &text[lev]));
    PetscCallMPI(MPI_Bcast(text[lev], (PetscMPIInt)(len + 1), MPI_CHAR, root, comm));
  }
  *txt = text;
  PetscFunctionReturn(0);
}

/* Trace the frequency-response curve of every level, then (unless quiet) print the summary table */
PetscErrorCode JRContSolve(JRCont c)
{
  Vec         a;
  PetscBool   repl;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCall(SolveSetUp(c, &a));
  PetscCall(JRHBMGetReplicated(c->hbm, &repl));
  PetscCallMPI(MPI_Comm_size(c->comm, &size));
  if (repl && size > 1 && c->nlev > 1 && c->levpar) {
    char **text = NULL;
    PetscCall(CurvesApart(c, a, &text));
    for (PetscInt lev = 0; lev < c->nlev; lev++) {
      PetscCall(PetscPrintf(c->comm, "%s", text[lev]));
      PetscCall(PetscFree(text[lev]));
      PetscCall(EndLevel(c, lev, a));
    }
    PetscCall(PetscFree(text));
  } else
    for (PetscInt lev = 0; lev < c->nlev; lev++) {
      PetscCall(CurveLevel(c, lev, a));
      PetscCall(EndLevel(c, lev, a));
    }
  PetscCall(VecDestroy(&a));
  if (!c->quiet) PetscCall(JRContPrintSummary(c));
  PetscFunctionReturn(0);
}

/* JRContCheckComplete - an error, after the curves are written, if a curve did not reach the end of its range (or
   turned back past its start), unless -cont_allow_partial */
PetscErrorCode JRContCheckComplete(JRCont c)
{
  PetscFunctionBeginUser;
  for (PetscInt l = 0; c->br && l < c->nlev; l++) {
    JRContBranch *b = &c->br[l];
    if (b->complete || c->partial) continue;
    SETERRQ(c->comm, PETSC_ERR_NOT_CONVERGED, "level %" PetscInt_FMT " (F = %g N): the curve is incomplete: %s; the points computed are written (the peak is that of the part traced); -cont_step_min, -cont_max_points or -hbm_snes_* may help; -cont_allow_partial accepts partial curves", l + 1, (double)b->F, b->why[0] ? b->why : "it stopped before the end of the range");
  }
  PetscFunctionReturn(0);
}

/* JRContSetQuiet - solve without printing progress, peak lines or the summary (a model solved as a means, e.g. to
   choose among candidates); warnings still print */
PetscErrorCode JRContSetQuiet(JRCont c, PetscBool quiet)
{
  PetscFunctionBeginUser;
  c->quiet = quiet;
  if (quiet) c->monitor = 0; /* nor the retries */
  PetscFunctionReturn(0);
}

/* JRContSetStability - decide the stability of every point (JRContStability) or not, whatever the options say */
PetscErrorCode JRContSetStability(JRCont c, PetscBool stab)
{
  PetscFunctionBeginUser;
  c->stab    = stab;
  c->stabset = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode JRContGetNumLevels(JRCont c, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = c->nlev;
  PetscFunctionReturn(0);
}

/* The points of level lev: frequencies [rad/s], unknowns (np x n), first-harmonic amplitude at the outputs (np x nout) */
PetscErrorCode JRContGetBranch(JRCont c, PetscInt lev, PetscInt *np, const PetscReal **omega, const PetscReal **a, const PetscReal **amp)
{
  PetscFunctionBeginUser;
  PetscCheck(c->br && lev >= 0 && lev < c->nlev, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "No level %" PetscInt_FMT, lev);
  *np = c->br[lev].np;
  if (omega) *omega = c->br[lev].omega;
  if (a) *a = c->br[lev].a;
  if (amp) *amp = c->br[lev].amp;
  PetscFunctionReturn(0);
}

/* Peak of the first output's amplitude on level lev [rad/s, m]: the largest amplitude of the solution curve, found by
   harmonic-balance solves between the computed points around it (JRContRefinePeaks; on a folded curve, the largest
   of the branch) */
PetscErrorCode JRContGetPeak(JRCont c, PetscInt lev, PetscReal *w, PetscReal *amp)
{
  PetscFunctionBeginUser;
  PetscCheck(c->br && lev >= 0 && lev < c->nlev, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "No level %" PetscInt_FMT, lev);
  *w   = c->br[lev].wpeak;
  *amp = c->br[lev].apeak;
  PetscFunctionReturn(0);
}

/* The solution at level lev's peak, in the modal unknowns (a: JRHBMCreateVecs's size when not condensed) */
PetscErrorCode JRContGetPeakSolution(JRCont c, PetscInt lev, Vec a)
{
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCheck(c->br && lev >= 0 && lev < c->nlev && c->br[lev].np, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "No level %" PetscInt_FMT, lev);
  PetscCall(VecGetSize(a, &n));
  PetscCheck(n == c->nmod, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "JRContGetPeakSolution: a vector of %" PetscInt_FMT " modal unknowns, not %" PetscInt_FMT, c->nmod, n);
  PetscCall(PointUnknowns(c, &c->br[lev], c->br[lev].kpeak, a));
  PetscFunctionReturn(0);
}

/* The excitation level of level lev [N] */
PetscErrorCode JRContGetLevel(JRCont c, PetscInt lev, PetscReal *F)
{
  PetscFunctionBeginUser;
  PetscCheck(c->levels && lev >= 0 && lev < c->nlev, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "No level %" PetscInt_FMT, lev);
  *F = c->levels[lev];
  PetscFunctionReturn(0);
}

/* Every element's contact state at the peak of level lev (rank 0; NULL elsewhere), in the model's numbering */
PetscErrorCode JRContGetPeakStates(JRCont c, PetscInt lev, const JRContactState **st)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCheck(c->br && lev >= 0 && lev < c->nlev, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "No level %" PetscInt_FMT, lev);
  PetscCallMPI(MPI_Comm_rank(c->comm, &rank));
  *st = rank ? NULL : c->br[lev].estate;
  PetscFunctionReturn(0);
}

/* Equivalent damping ratio at the peak and the worst energy imbalance of level lev */
PetscErrorCode JRContGetDamping(JRCont c, PetscInt lev, PetscReal *zeta, PetscReal *ebal)
{
  PetscFunctionBeginUser;
  PetscCheck(c->br && lev >= 0 && lev < c->nlev, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "No level %" PetscInt_FMT, lev);
  if (zeta) *zeta = c->br[lev].zeta;
  if (ebal) *ebal = c->br[lev].ebal;
  PetscFunctionReturn(0);
}

/* Whether level lev's curve reached the end of its range, and the largest relative residual of its points */
PetscErrorCode JRContGetLevelComplete(JRCont c, PetscInt lev, PetscBool *complete, PetscReal *resmax)
{
  PetscFunctionBeginUser;
  PetscCheck(c->br && lev >= 0 && lev < c->nlev, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "No level %" PetscInt_FMT, lev);
  if (complete) *complete = c->br[lev].complete;
  if (resmax) *resmax = c->br[lev].resmax;
  PetscFunctionReturn(0);
}

/* A level's wall time [s] (continuation only), points and Newton iterations */
PetscErrorCode JRContGetLevelStats(JRCont c, PetscInt lev, PetscReal *seconds, PetscInt *points, PetscInt *newton)
{
  PetscFunctionBeginUser;
  PetscCheck(c->br && lev >= 0 && lev < c->nlev, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "No level %" PetscInt_FMT, lev);
  if (seconds) *seconds = c->br[lev].seconds;
  if (points) *points = c->br[lev].np;
  if (newton) *newton = c->br[lev].newton;
  PetscFunctionReturn(0);
}

PetscErrorCode JRContDestroy(JRCont *cont)
{
  JRCont c = *cont;

  PetscFunctionBeginUser;
  if (!c) PetscFunctionReturn(0);
  if (c->ops->destroy) PetscCall((*c->ops->destroy)(c));
  PetscCall(BranchesDestroy(c));
  PetscCall(PetscFree(c->levels));
  PetscCall(PetscFree(c->text));
  PetscCall(VecDestroy(&c->amod));
  PetscCall(PetscFree(c->ampw));
  PetscCall(JRContPlaneWorkDestroy(c));
  PetscCall(PetscFree(c));
  *cont = NULL;
  PetscFunctionReturn(0);
}

/* The summary table of JRContSolve: one row per level (peak, damping, points, Newton, retries, time, balance, states) */
PetscErrorCode JRContPrintSummary(JRCont c)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(c->comm, "frf summary (%s continuation; peak of response 1: the maximum of the solution curve; zeta_eq = energy dissipated per cycle / (8 pi mean kinetic energy) at the peak;\n  residual: largest ||R|| / ||F f|| of the curve's points; energy balance: largest |W_in - W_damping - W_contact| / W_in over the curve;\n  elements at the peak: full stick / stick-slip / separation with stick-slip / full separation)\n", c->type_name));
  PetscCall(PetscPrintf(c->comm, "  %10s %12s %13s %13s %10s %7s %7s %7s %9s %9s %9s  %s\n", "F [N]", "peak [Hz]", "amp [m]", "amp/F [m/N]", "zeta_eq", "points", "newton", "retries", "time [s]", "residual", "balance", "states"));
  for (PetscInt lev = 0; lev < c->nlev; lev++) {
    JRContBranch *b = &c->br[lev];
    PetscCall(PetscPrintf(c->comm, "  %10.4g %12.6g %13.5e %13.5e %10.4e %7" PetscInt_FMT " %7" PetscInt_FMT " %7" PetscInt_FMT " %9.3g %9.2e %9.2e  %" PetscInt_FMT " / %" PetscInt_FMT " / %" PetscInt_FMT " / %" PetscInt_FMT "%s\n", (double)b->F, (double)(b->wpeak / (2 * PETSC_PI)), (double)b->apeak, (double)(b->apeak / b->F), (double)b->zeta, b->np, b->newton, b->retries, (double)b->seconds, (double)b->resmax, (double)b->ebal, b->states[0], b->states[1], b->states[2], b->states[3], b->complete ? "" : "  (incomplete)"));
  }
  PetscFunctionReturn(0);
}
