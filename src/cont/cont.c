/*
   JRCont: frequency-response curves of a JRHBM problem by continuation, for several excitation
   levels (thesis 2.4).

   natural (2.4.2): step in frequency from the response of the stuck, linearised structure away from
     resonance; predictor: the previous solution, or the secant through the last two; Newton (the
     JRHBM SNES) at each frequency; the step grows when Newton converges fast and shrinks when it is
     slow; a failed step is retried at half the step and reported.
   arclength (2.4.3): unknowns (a, w); tangent predictor from the bordered system
       [ dR/da  dR/dw ] t = [0]
       [   t_prev^T   ]     [1]
     corrector: an SNES (prefix hbm_) on the bordered system  R(a, w) = 0, g(a, w) = 0  with the
     pseudo-arclength constraint g = <x - x_pred, t> = 0 or the thesis's sphere (2.28)
     g = |x - x_k|^2 - ds^2 (-cont_constraint sphere). Lengths are measured in scaled units,
     a / a_ref and w / (w_max - w_min), with a_ref the largest response of the linearised (stuck) structure
     over the range, raised to the largest response met along the curve, so that amplitudes and frequency
     weigh alike. Step control from the Newton
     iteration count; turning points are passed; the last point lands exactly on the end of the range.
*/
#include <jointrom.h>
#include <petscviewerhdf5.h>

const char *const JRContTypes[]       = {"natural", "arclength", "JRContType", "JR_CONT_", NULL};
const char *const JRContConstraints[] = {"pseudo", "sphere", "JRContConstraint", "JR_CONT_", NULL};

typedef struct {
  PetscReal  F;
  PetscInt   np, cap;
  PetscReal *omega, *a, *amp, *pp, *step;
  PetscInt  *its;
  PetscInt   retries, states[4];
  PetscBool  complete;
  PetscReal  seconds;
  PetscInt   newton;
  PetscInt   kpeak;           /* the computed point of largest amplitude */
  PetscReal  wpeak, apeak;    /* the peak refined by a parabola through it and its neighbours */
  PetscReal  zeta, ebal;      /* equivalent damping ratio at the peak; worst energy imbalance of the curve */
  JRContactState *estate;     /* every element's state at the peak (rank 0) */
} Branch;

struct _p_JRCont {
  MPI_Comm         comm;
  JRHBM            hbm;
  JRContType       type;
  JRContConstraint constraint;
  PetscReal        wmin, wmax, step0, stepmin, stepmax;
  PetscBool        range_set, secant, plot, normalize, write;
  PetscBool        quiet; /* JRContSetQuiet(): no progress, peak lines or summary */
  PetscInt         maxpts, target, monitor, nlev, n, nmod, nout, nc, npoints; /* n: the solve space; nmod: modal */
  PetscReal       *levels;
  Branch          *br;
  char             out[PETSC_MAX_PATH_LEN];
  /* arclength work */
  SNES             bsnes;
  Mat              BJ, J;
  Vec              bx, br_, bt, Rw, a, r, amod;
  PetscReal        aref, wref, ds, wcur, aunit; /* aunit: the linearised response scale per unit level */
  PetscScalar     *tb, *tlu;                      /* the tangent's bordered matrix and its LU ((n+1) x (n+1)) */
  PetscBLASInt    *tpiv;
  Vec              xpred, xk, tk, dw; /* dw: work, size of xk */
};

PetscErrorCode JRContCreate(MPI_Comm comm, JRCont *cont)
{
  JRCont c;

  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(PetscNew(&c));
  c->comm       = comm;
  c->type       = JR_CONT_ARCLENGTH;
  c->constraint = JR_CONT_PSEUDO;
  c->maxpts     = 2000;
  c->target     = 4;
  c->monitor    = 1;
  c->secant     = PETSC_TRUE;
  c->plot       = PETSC_TRUE;
  c->write      = PETSC_TRUE;
  c->nlev       = 1;
  PetscCall(PetscMalloc1(1, &c->levels));
  c->levels[0] = 1.0;
  PetscCall(PetscStrncpy(c->out, "out/frf", sizeof(c->out)));
  *cont = c;
  PetscFunctionReturn(0);
}

PetscErrorCode JRContSetHBM(JRCont c, JRHBM hbm)
{
  PetscFunctionBeginUser;
  c->hbm = hbm;
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

/* Frequency range [rad/s] */
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

PetscErrorCode JRContSetRange(JRCont c, PetscReal wmin, PetscReal wmax)
{
  PetscFunctionBeginUser;
  PetscCheck(wmin > 0 && wmax > wmin, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Frequency range %g .. %g rad/s: need 0 < min < max", (double)wmin, (double)wmax);
  c->wmin      = wmin;
  c->wmax      = wmax;
  c->range_set = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Excitation levels F [N] */
PetscErrorCode JRContSetLevels(JRCont c, PetscInt n, const PetscReal F[])
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 1, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "At least one excitation level");
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
  Options: -cont_type natural|arclength, -cont_constraint pseudo|sphere, -cont_step, -cont_step_min,
  -cont_step_max, -cont_max_points, -cont_newton_target, -cont_predictor secant|previous,
  -cont_monitor 0|1|2; -frf_force F1,F2,.. [N], -frf_omega_min/-frf_omega_max [rad/s] or
  -frf_fmin/-frf_fmax [Hz], -frf_output_file BASE (BASE.h5, BASE.csv, BASE.png), -frf_plot,
  -frf_normalize (plot amplitude / force).
*/
PetscErrorCode JRContSetFromOptions(JRCont c)
{
  PetscInt  t = c->type, k = c->constraint, nl = 64, pred = c->secant ? 0 : 1;
  PetscReal lv[64], wmin = c->wmin, wmax = c->wmax, fmin = 0, fmax = 0;
  PetscBool f1, f2, f3, f4, fl;
  const char *preds[] = {"secant", "previous", "Predictor", "", NULL};

  PetscFunctionBeginUser;
  PetscOptionsBegin(c->comm, NULL, "Continuation (JRCont) and frequency-response output", "JRCont");
  PetscCall(PetscOptionsEList("-cont_type", "Continuation: natural (step in frequency) or arclength (pseudo-arclength, passes turning points)", "JRContSetFromOptions", JRContTypes, 2, JRContTypes[c->type], &t, NULL));
  PetscCall(PetscOptionsEList("-cont_constraint", "Arclength constraint: pseudo (orthogonal to the tangent) or sphere (thesis 2.28)", "JRContSetFromOptions", JRContConstraints, 2, JRContConstraints[c->constraint], &k, NULL));
  PetscCall(PetscOptionsReal("-cont_step", "First step: rad/s (natural) or scaled arclength (arclength); default: 1/100 of the range, 0.01", "JRContSetFromOptions", c->step0, &c->step0, NULL));
  PetscCall(PetscOptionsReal("-cont_step_min", "Smallest step (rad/s or scaled arclength)", "JRContSetStepBounds", c->stepmin, &c->stepmin, NULL));
  PetscCall(PetscOptionsReal("-cont_step_max", "Largest step (rad/s or scaled arclength)", "JRContSetStepBounds", c->stepmax, &c->stepmax, NULL));
  PetscCall(PetscOptionsInt("-cont_max_points", "Most points per curve", "JRContSetFromOptions", c->maxpts, &c->maxpts, NULL));
  PetscCall(PetscOptionsInt("-cont_points", "Natural continuation on this many equally spaced frequencies (no step adaptation; benchmarks)", "JRContSetFromOptions", c->npoints, &c->npoints, NULL));
  PetscCall(PetscOptionsInt("-cont_newton_target", "Newton iterations per point the step control aims at", "JRContSetFromOptions", c->target, &c->target, NULL));
  PetscCall(PetscOptionsEList("-cont_predictor", "Natural continuation predictor: secant or previous solution", "JRContSetFromOptions", preds, 2, preds[pred], &pred, NULL));
  PetscCall(PetscOptionsInt("-cont_monitor", "Progress: 0 none, 1 every 25th point and each level, 2 every point", "JRContSetFromOptions", c->monitor, &c->monitor, NULL));
  PetscCall(PetscOptionsRealArray("-frf_force", "Excitation levels F [N]: f(t) = F sin(w t) at -frf_dof", "JRContSetLevels", lv, &nl, &fl));
  PetscCall(PetscOptionsReal("-frf_omega_min", "Lowest frequency [rad/s]", "JRContSetRange", wmin, &wmin, &f1));
  PetscCall(PetscOptionsReal("-frf_omega_max", "Highest frequency [rad/s]", "JRContSetRange", wmax, &wmax, &f2));
  PetscCall(PetscOptionsReal("-frf_fmin", "Lowest frequency [Hz] (instead of -frf_omega_min)", "JRContSetRange", fmin, &fmin, &f3));
  PetscCall(PetscOptionsReal("-frf_fmax", "Highest frequency [Hz] (instead of -frf_omega_max)", "JRContSetRange", fmax, &fmax, &f4));
  PetscCall(PetscOptionsString("-frf_output_file", "Output base name: BASE.h5 (all points), BASE.csv, BASE.png ('' for none)", "JRContWrite", c->out, c->out, sizeof(c->out), NULL));
  PetscCall(PetscOptionsBool("-frf_plot", "Draw BASE.png", "JRContWrite", c->plot, &c->plot, NULL));
  PetscCall(PetscOptionsBool("-frf_normalize", "Plot the normalised displacement amplitude / force [m/N]", "JRContWrite", c->normalize, &c->normalize, NULL));
  PetscOptionsEnd();
  c->type       = (JRContType)t;
  c->constraint = (JRContConstraint)k;
  c->secant     = pred == 0 ? PETSC_TRUE : PETSC_FALSE;
  c->write      = c->out[0] ? PETSC_TRUE : PETSC_FALSE;
  if (fl) PetscCall(JRContSetLevels(c, nl, lv));
  PetscCheck(!(f1 && f3) && !(f2 && f4), c->comm, PETSC_ERR_ARG_INCOMP, "Give the range in rad/s (-frf_omega_min/max) or in Hz (-frf_fmin/fmax), not both");
  if (f3) wmin = 2.0 * PETSC_PI * fmin;
  if (f4) wmax = 2.0 * PETSC_PI * fmax;
  if (f1 || f2 || f3 || f4) {
    PetscCheck((f1 || f3) && (f2 || f4), c->comm, PETSC_ERR_ARG_INCOMP, "Give both ends of the frequency range (-frf_omega_min and -frf_omega_max, or -frf_fmin and -frf_fmax)");
    PetscCheck(PetscIsNormalReal(wmin) && PetscIsNormalReal(wmax) && wmin > 0 && wmax > wmin, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Frequency range %g .. %g rad/s (%g .. %g Hz): need 0 < min < max", (double)wmin, (double)wmax, (double)(wmin / (2 * PETSC_PI)), (double)(wmax / (2 * PETSC_PI)));
    PetscCall(JRContSetRange(c, wmin, wmax));
  }
  PetscCheck(c->npoints == 0 || (c->npoints >= 2 && c->type == JR_CONT_NATURAL), c->comm, PETSC_ERR_ARG_INCOMP, "-cont_points %" PetscInt_FMT ": at least 2, with -cont_type natural", c->npoints);
  PetscCheck(c->maxpts >= 2, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cont_max_points %" PetscInt_FMT ": at least 2", c->maxpts);
  PetscCheck(c->target >= 1, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cont_newton_target %" PetscInt_FMT ": at least 1", c->target);
  PetscCheck(c->step0 >= 0 && c->stepmin >= 0 && c->stepmax >= 0, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "-cont_step, -cont_step_min, -cont_step_max must be positive");
  PetscFunctionReturn(0);
}

static PetscErrorCode BranchAdd(JRCont c, Branch *b, PetscReal w, Vec a, PetscInt its, PetscReal step)
{
  const PetscScalar *x;

  PetscFunctionBeginUser;
  if (b->np == b->cap) {
    PetscInt   cap = b->cap ? 2 * b->cap : 128;
    PetscReal *o, *aa, *amp, *pp, *st;
    PetscInt  *it;
    PetscCall(PetscMalloc6(cap, &o, cap * c->nmod, &aa, cap * c->nout, &amp, cap * c->nout, &pp, cap, &st, cap, &it));
    if (b->np) {
      PetscCall(PetscArraycpy(o, b->omega, b->np));
      PetscCall(PetscArraycpy(aa, b->a, b->np * c->nmod));
      PetscCall(PetscArraycpy(amp, b->amp, b->np * c->nout));
      PetscCall(PetscArraycpy(pp, b->pp, b->np * c->nout));
      PetscCall(PetscArraycpy(st, b->step, b->np));
      PetscCall(PetscArraycpy(it, b->its, b->np));
    }
    PetscCall(PetscFree6(b->omega, b->a, b->amp, b->pp, b->step, b->its));
    b->omega = o;
    b->a     = aa;
    b->amp   = amp;
    b->pp    = pp;
    b->step  = st;
    b->its   = it;
    b->cap   = cap;
  }
  b->omega[b->np] = w;
  PetscCall(JRHBMExpand(c->hbm, w, a, c->amod)); /* the branch keeps the modal unknowns */
  PetscCall(VecGetArrayRead(c->amod, &x));
  for (PetscInt i = 0; i < c->nmod; i++) b->a[b->np * c->nmod + i] = PetscRealPart(x[i]);
  PetscCall(VecRestoreArrayRead(c->amod, &x));
  PetscCall(JRHBMResponse(c->hbm, c->amod, NULL, b->amp + b->np * c->nout, b->pp + b->np * c->nout));
  b->its[b->np]  = its;
  b->step[b->np] = step;
  b->newton += its;
  b->np++;
  PetscFunctionReturn(0);
}

static PetscErrorCode Monitor(JRCont c, PetscInt lev, Branch *b, PetscBool force)
{
  PetscFunctionBeginUser;
  if (!c->monitor || c->quiet || !b->np) PetscFunctionReturn(0);
  if (c->monitor >= 2 || force || (b->np - 1) % 25 == 0) {
    const PetscInt k = b->np - 1;
    PetscCall(PetscPrintf(c->comm, "cont: level %" PetscInt_FMT "/%" PetscInt_FMT " F %g N  point %4" PetscInt_FMT "  f %.6g Hz  amp %.4e m  newton %" PetscInt_FMT "  step %.3g\n", lev + 1, c->nlev, (double)b->F, k, (double)(b->omega[k] / (2 * PETSC_PI)), (double)b->amp[k * c->nout], b->its[k], (double)b->step[k]));
  }
  PetscFunctionReturn(0);
}

/* natural-parameter continuation over [wmin, wmax] at the current level */
static PetscErrorCode Natural(JRCont c, PetscInt lev, Branch *b, Vec a)
{
  const PetscReal range = c->wmax - c->wmin;
  PetscReal       dw    = c->step0 > 0 ? c->step0 : range / 100, dwmin = c->stepmin > 0 ? c->stepmin : 1e-7 * range, dwmax = c->stepmax > 0 ? c->stepmax : range / 10;
  if (c->npoints > 1) { /* equally spaced: the step never grows beyond the spacing */
    dw    = range / (c->npoints - 1);
    dwmax = dw;
  }
  PetscReal       w = c->wmin, wprev = 0.0;
  Vec             aprev, aprev2, guess;
  PetscInt        its;
  PetscBool       conv;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(a, &aprev));
  PetscCall(VecDuplicate(a, &aprev2));
  PetscCall(VecDuplicate(a, &guess));
  PetscCall(JRHBMLinearSolution(c->hbm, w, a));
  PetscCall(JRHBMSolve(c->hbm, w, a, &its, &conv));
  PetscCheck(conv, c->comm, PETSC_ERR_NOT_CONVERGED, "Level F = %g N: no solution at the start of the range, %g Hz (try a lower -frf_fmin, or -hbm_snes_* options)", (double)b->F, (double)(w / (2 * PETSC_PI)));
  PetscCall(BranchAdd(c, b, w, a, its, 0.0));
  PetscCall(Monitor(c, lev, b, PETSC_FALSE));
  while (w < c->wmax && b->np < c->maxpts) {
    PetscReal wn = PetscMin(w + dw, c->wmax);
    if (c->wmax - wn < 1e-3 * dw) wn = c->wmax; /* do not leave a sliver at the end */
    PetscCall(VecCopy(a, guess));
    if (c->secant && b->np >= 2) PetscCall(VecAXPY(guess, (wn - w) / (w - wprev), aprev2)); /* aprev2 holds a_k - a_{k-1} */
    PetscCall(VecCopy(guess, aprev));
    PetscCall(JRHBMSolve(c->hbm, wn, aprev, &its, &conv));
    if (!conv) {
      b->retries++;
      dw *= 0.5;
      if (c->monitor) PetscCall(PetscPrintf(c->comm, "cont: level %" PetscInt_FMT " F %g N: Newton failed at %.6g Hz, retrying with step %.3g rad/s\n", lev + 1, (double)b->F, (double)(wn / (2 * PETSC_PI)), (double)dw));
      if (dw < dwmin) {
        PetscCall(PetscPrintf(c->comm, "cont: level %" PetscInt_FMT " F %g N: stopped at %.6g Hz, the step fell below %.3g rad/s (-cont_step_min); the curve ends there\n", lev + 1, (double)b->F, (double)(w / (2 * PETSC_PI)), (double)dwmin));
        break;
      }
      continue;
    }
    PetscCall(VecWAXPY(aprev2, -1.0, a, aprev));
    PetscCall(VecCopy(aprev, a));
    wprev = w;
    w     = wn;
    PetscCall(BranchAdd(c, b, w, a, its, wn - wprev));
    PetscCall(Monitor(c, lev, b, PETSC_FALSE));
    if (its <= c->target / 2) dw = PetscMin(1.5 * dw, dwmax);
    else if (its > c->target) dw = PetscMax(0.7 * dw, dwmin);
  }
  b->complete = w >= c->wmax ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(VecDestroy(&aprev));
  PetscCall(VecDestroy(&aprev2));
  PetscCall(VecDestroy(&guess));
  PetscFunctionReturn(0);
}

/* scaled inner product <x, y> over (a, w) */
static PetscErrorCode ScaledDot(JRCont c, Vec x, Vec y, PetscReal *d)
{
  const PetscScalar *u, *v;
  PetscReal          s = 0.0;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(x, &u));
  PetscCall(VecGetArrayRead(y, &v));
  for (PetscInt i = 0; i < c->n; i++) s += PetscRealPart(u[i] * v[i]) / (c->aref * c->aref);
  s += PetscRealPart(u[c->n] * v[c->n]) / (c->wref * c->wref);
  PetscCall(VecRestoreArrayRead(y, &v));
  PetscCall(VecRestoreArrayRead(x, &u));
  *d = s;
  PetscFunctionReturn(0);
}

/* split x = (a, w) into a (Vec of size n) and w */
static PetscErrorCode Split(JRCont c, Vec x, Vec a, PetscReal *w)
{
  const PetscScalar *u;
  PetscScalar       *v;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(x, &u));
  PetscCall(VecGetArray(a, &v));
  for (PetscInt i = 0; i < c->n; i++) v[i] = u[i];
  *w = PetscRealPart(u[c->n]);
  PetscCall(VecRestoreArray(a, &v));
  PetscCall(VecRestoreArrayRead(x, &u));
  PetscFunctionReturn(0);
}

static PetscErrorCode Join(JRCont c, Vec a, PetscReal w, Vec x)
{
  const PetscScalar *u;
  PetscScalar       *v;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(a, &u));
  PetscCall(VecGetArray(x, &v));
  for (PetscInt i = 0; i < c->n; i++) v[i] = u[i];
  v[c->n] = w;
  PetscCall(VecRestoreArray(x, &v));
  PetscCall(VecRestoreArrayRead(a, &u));
  PetscFunctionReturn(0);
}

/* bordered residual G(x) = [R(a, w); g(x)] */
static PetscErrorCode BorderedFunction(SNES snes, Vec x, Vec G, void *ctx)
{
  JRCont    c = (JRCont)ctx;
  PetscReal w, g;
  Vec       d = c->dw;

  PetscFunctionBeginUser;
  (void)snes;
  PetscCall(Split(c, x, c->a, &w));
  PetscCall(JRHBMComputeResidual(c->hbm, w, c->a, c->r));
  if (c->constraint == JR_CONT_PSEUDO) {
    PetscCall(VecWAXPY(d, -1.0, c->xpred, x));
    PetscCall(ScaledDot(c, d, c->tk, &g));
  } else {
    PetscCall(VecWAXPY(d, -1.0, c->xk, x));
    PetscCall(ScaledDot(c, d, d, &g));
    g -= c->ds * c->ds;
  }
  PetscCall(Join(c, c->r, g, G));
  PetscFunctionReturn(0);
}

/* bordered Jacobian [J Rw; c^T d] */
static PetscErrorCode BorderedJacobian(SNES snes, Vec x, Mat BJ, Mat P, void *ctx)
{
  JRCont             c = (JRCont)ctx;
  PetscReal          w;
  const PetscScalar *j, *rw, *t, *xx, *xk;
  PetscScalar       *b;
  const PetscInt     n = c->n;

  PetscFunctionBeginUser;
  (void)snes;
  (void)P;
  PetscCall(Split(c, x, c->a, &w));
  PetscCall(JRHBMComputeJacobian(c->hbm, w, c->a, c->J, c->Rw));
  PetscCall(MatDenseGetArrayRead(c->J, &j));
  PetscCall(VecGetArrayRead(c->Rw, &rw));
  PetscCall(VecGetArrayRead(c->tk, &t));
  PetscCall(VecGetArrayRead(x, &xx));
  PetscCall(VecGetArrayRead(c->xk, &xk));
  PetscCall(MatDenseGetArrayWrite(BJ, &b));
  for (PetscInt col = 0; col < n; col++) {
    for (PetscInt row = 0; row < n; row++) b[row + col * (n + 1)] = j[row + col * n];
    b[n + col * (n + 1)] = c->constraint == JR_CONT_PSEUDO ? t[col] / (c->aref * c->aref) : 2.0 * (xx[col] - xk[col]) / (c->aref * c->aref);
  }
  for (PetscInt row = 0; row < n; row++) b[row + n * (n + 1)] = rw[row];
  b[n + n * (n + 1)] = c->constraint == JR_CONT_PSEUDO ? t[n] / (c->wref * c->wref) : 2.0 * (xx[n] - xk[n]) / (c->wref * c->wref);
  PetscCall(MatDenseRestoreArrayWrite(BJ, &b));
  PetscCall(VecRestoreArrayRead(c->xk, &xk));
  PetscCall(VecRestoreArrayRead(x, &xx));
  PetscCall(VecRestoreArrayRead(c->tk, &t));
  PetscCall(VecRestoreArrayRead(c->Rw, &rw));
  PetscCall(MatDenseRestoreArrayRead(c->J, &j));
  PetscCall(JRMatDenseAssemble(BJ));
  PetscFunctionReturn(0);
}

/* unit (scaled) tangent at x: [J Rw; tprev^T W] t = [0; 1], oriented along tprev */
static PetscErrorCode Tangent(JRCont c, Vec x, Vec tprev, Vec t)
{
  PetscReal          w, nrm;
  const PetscInt     n = c->n, m = n + 1;
  const PetscScalar *j, *rw, *tp;
  PetscScalar       *b, *tt;
  PetscBool          singular;

  PetscFunctionBeginUser;
  PetscCall(Split(c, x, c->a, &w));
  PetscCall(JRHBMComputeJacobian(c->hbm, w, c->a, c->J, c->Rw));
  if (!c->tb) PetscCall(PetscMalloc3(m * m, &c->tb, m * m, &c->tlu, m, &c->tpiv)); /* kept for the whole solve */
  b = c->tb;
  PetscCall(MatDenseGetArrayRead(c->J, &j));
  PetscCall(VecGetArrayRead(c->Rw, &rw));
  PetscCall(VecGetArrayRead(tprev, &tp));
  for (PetscInt col = 0; col < n; col++) {
    for (PetscInt row = 0; row < n; row++) b[row + col * m] = j[row + col * n];
    b[n + col * m] = tp[col] / (c->aref * c->aref);
  }
  for (PetscInt row = 0; row < n; row++) b[row + n * m] = rw[row];
  b[n + n * m] = tp[n] / (c->wref * c->wref);
  PetscCall(VecRestoreArrayRead(tprev, &tp));
  PetscCall(VecRestoreArrayRead(c->Rw, &rw));
  PetscCall(MatDenseRestoreArrayRead(c->J, &j));
  PetscCall(VecZeroEntries(t));
  PetscCall(VecGetArray(t, &tt));
  tt[n] = 1.0;
  PetscCall(JRDenseSolve(m, b, m, c->tlu, c->tpiv, tt, &singular));
  PetscCall(VecRestoreArray(t, &tt));
  PetscCheck(!singular, PETSC_COMM_SELF, PETSC_ERR_MAT_LU_ZRPVT, "Continuation: the bordered tangent system is singular at %g Hz (a zero pivot)", (double)(w / (2 * PETSC_PI)));
  PetscCall(ScaledDot(c, t, t, &nrm));
  PetscCall(VecScale(t, 1.0 / PetscSqrtReal(nrm)));
  PetscFunctionReturn(0);
}

/* pseudo-arclength continuation over [wmin, wmax] at the current level */
static PetscErrorCode Arclength(JRCont c, PetscInt lev, Branch *b, Vec a)
{
  const PetscInt n = c->n;
  PetscReal      ds = c->step0 > 0 ? c->step0 : 0.01, dsmin = c->stepmin > 0 ? c->stepmin : 1e-7, dsmax = c->stepmax > 0 ? c->stepmax : 0.05, w;
  PetscInt       its;
  PetscBool      conv;
  Vec            tnew, x;

  PetscFunctionBeginUser;
  /* first point: Newton at the start of the range from the linearised response */
  PetscCall(JRHBMLinearSolution(c->hbm, c->wmin, a));
  PetscCall(JRHBMSolve(c->hbm, c->wmin, a, &its, &conv));
  PetscCheck(conv, c->comm, PETSC_ERR_NOT_CONVERGED, "Level F = %g N: no solution at the start of the range, %g Hz (try a lower -frf_fmin, or -hbm_snes_* options)", (double)b->F, (double)(c->wmin / (2 * PETSC_PI)));
  PetscCall(BranchAdd(c, b, c->wmin, a, its, 0.0));
  PetscCall(Monitor(c, lev, b, PETSC_FALSE));
  PetscCall(Join(c, a, c->wmin, c->xk));
  PetscCall(VecDuplicate(c->xk, &tnew));
  PetscCall(VecDuplicate(c->xk, &x));
  PetscCall(VecZeroEntries(c->tk));
  PetscCall(VecSetValue(c->tk, n, 1.0, INSERT_VALUES)); /* start along increasing frequency */
  PetscCall(VecAssemblyBegin(c->tk));
  PetscCall(VecAssemblyEnd(c->tk));
  PetscCall(Tangent(c, c->xk, c->tk, tnew));
  PetscCall(VecCopy(tnew, c->tk));
  while (b->np < c->maxpts) {
    PetscReal           wk;
    SNESConvergedReason reason;
    PetscCall(Split(c, c->xk, c->a, &wk));
    c->ds = ds;
    PetscCall(VecWAXPY(c->xpred, ds, c->tk, c->xk));
    PetscCall(VecCopy(c->xpred, x));
    PetscCall(PetscLogEventBegin(JR_ContStep, 0, 0, 0, 0));
    PetscCall(SNESSolve(c->bsnes, NULL, x));
    PetscCall(PetscLogEventEnd(JR_ContStep, 0, 0, 0, 0));
    PetscCall(SNESGetConvergedReason(c->bsnes, &reason));
    PetscCall(SNESGetIterationNumber(c->bsnes, &its));
    PetscCall(Split(c, x, a, &w));
    if (reason <= 0 || PetscIsInfOrNanReal(w)) {
      b->retries++;
      ds *= 0.5;
      if (c->monitor) PetscCall(PetscPrintf(c->comm, "cont: level %" PetscInt_FMT " F %g N: corrector failed after %.6g Hz (%s), retrying with step %.3g\n", lev + 1, (double)b->F, (double)(wk / (2 * PETSC_PI)), SNESConvergedReasons[reason], (double)ds));
      if (ds < dsmin) {
        PetscCall(PetscPrintf(c->comm, "cont: level %" PetscInt_FMT " F %g N: stopped at %.6g Hz, the step fell below %.3g (-cont_step_min); the curve ends there\n", lev + 1, (double)b->F, (double)(wk / (2 * PETSC_PI)), (double)dsmin));
        break;
      }
      continue;
    }
    if (w >= c->wmax) { /* passed the end: land on it exactly by Newton at w_max from the interpolation */
      const PetscReal s = (c->wmax - wk) / (w - wk);
      Vec             ak;
      PetscCall(VecDuplicate(a, &ak));
      PetscCall(Split(c, c->xk, ak, &wk));
      PetscCall(VecAXPBY(a, 1.0 - s, s, ak)); /* a <- s a + (1 - s) a_k */
      PetscCall(VecDestroy(&ak));
      PetscCall(JRHBMSolve(c->hbm, c->wmax, a, &its, &conv));
      if (conv) {
        PetscCall(BranchAdd(c, b, c->wmax, a, its, ds));
        b->complete = PETSC_TRUE;
      } else PetscCall(PetscPrintf(c->comm, "cont: level %" PetscInt_FMT " F %g N: no solution exactly at the end of the range; the curve ends at %.6g Hz\n", lev + 1, (double)b->F, (double)(wk / (2 * PETSC_PI))));
      break;
    }
    PetscCall(BranchAdd(c, b, w, a, its, ds));
    PetscCall(Monitor(c, lev, b, PETSC_FALSE));
    { /* the amplitude scale follows the largest response met: slipping joints respond far more than stuck ones */
      PetscReal na;
      PetscCall(VecNorm(a, NORM_2, &na));
      if (na > c->aref) c->aref = na; /* the next tangent is normalised in the new metric */
    }
    if (w < c->wmin) {
      PetscCall(PetscPrintf(c->comm, "cont: level %" PetscInt_FMT " F %g N: the curve turned back below the start of the range at %.6g Hz; stopped\n", lev + 1, (double)b->F, (double)(w / (2 * PETSC_PI))));
      break;
    }
    PetscCall(Tangent(c, x, c->tk, tnew));
    {
      /* step control: Newton iterations against the target, and the turn of the response curve as plotted
         (frequency over the range, decades of amplitude at the first output) against 5 degrees per step, so
         that peaks and folds get points where the curve bends (the full tangent also turns with invisible
         harmonics and modes, at every stick-slip kink of the sampled elements) */
      const PetscInt k  = b->np - 1;
      PetscReal      fn = PetscSqrtReal((PetscReal)c->target / PetscMax(its, 1)), fa = 2.0;
      if (k >= 2 && b->amp[k * c->nout] > 0 && b->amp[(k - 1) * c->nout] > 0 && b->amp[(k - 2) * c->nout] > 0) {
        const PetscReal d1w = (b->omega[k - 1] - b->omega[k - 2]) / c->wref, d1a = PetscLog10Real(b->amp[(k - 1) * c->nout] / b->amp[(k - 2) * c->nout]);
        const PetscReal d2w = (b->omega[k] - b->omega[k - 1]) / c->wref, d2a = PetscLog10Real(b->amp[k * c->nout] / b->amp[(k - 1) * c->nout]);
        const PetscReal n1 = PetscSqrtReal(d1w * d1w + d1a * d1a), n2 = PetscSqrtReal(d2w * d2w + d2a * d2a);
        if (n1 > 0 && n2 > 0) {
          const PetscReal ang = PetscAcosReal(PetscMax(-1.0, PetscMin(1.0, (d1w * d2w + d1a * d2a) / (n1 * n2))));
          fa                  = (5.0 * PETSC_PI / 180.0) / PetscMax(ang, 1e-3);
        }
      }
      ds *= PetscMax(0.5, PetscMin(2.0, PetscMin(fn, fa)));
      ds = PetscMax(dsmin, PetscMin(dsmax, ds));
    }
    PetscCall(VecCopy(tnew, c->tk));
    PetscCall(VecCopy(x, c->xk));
  }
  if (b->np >= c->maxpts) PetscCall(PetscPrintf(c->comm, "cont: level %" PetscInt_FMT " F %g N: -cont_max_points %" PetscInt_FMT " reached before the end of the range\n", lev + 1, (double)b->F, c->maxpts));
  PetscCall(VecDestroy(&tnew));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

/* the response scale a_ref: the largest linearised response over the range */
static PetscErrorCode ResponseScale(JRCont c, PetscReal F, Vec a)
{
  PetscReal m = 0.0, nrm;

  PetscFunctionBeginUser;
  if (c->aunit <= 0 || F <= 0) { /* the linearised response is proportional to the level: sampled once */
    for (PetscInt k = 0; k <= 64; k++) {
      const PetscReal w = c->wmin + (c->wmax - c->wmin) * k / 64.0;
      PetscCall(JRHBMLinearSolution(c->hbm, w, a));
      PetscCall(VecNorm(a, NORM_2, &nrm));
      m = PetscMax(m, nrm);
    }
    if (F > 0) c->aunit = m / F;
  } else m = c->aunit * F;
  c->aref = m > 0 ? m : 1.0;
  c->wref = c->wmax - c->wmin;
  PetscFunctionReturn(0);
}

static PetscErrorCode Peak(JRCont, PetscInt, Vec);

/* Trace the frequency-response curve of every level */
PetscErrorCode JRContSolve(JRCont c)
{
  Vec a;

  PetscFunctionBeginUser;
  PetscCheck(c->hbm, c->comm, PETSC_ERR_ARG_WRONGSTATE, "JRContSetHBM() first");
  c->aunit = 0;
  PetscCall(PetscFree3(c->tb, c->tlu, c->tpiv)); /* sizes may differ from an earlier solve */
  PetscCall(JRHBMGetSizes(c->hbm, NULL, NULL, &c->nmod));
  PetscCall(JRHBMGetSolveSize(c->hbm, &c->n, NULL));
  PetscCall(JRHBMGetOutputs(c->hbm, &c->nout, NULL));
  if (!c->range_set) { /* around the first mode: 0.8 to 1.2 of its frequency */
    PetscInt         nm;
    const PetscReal *om;
    PetscCall(JRHBMGetModalFrequencies(c->hbm, &nm, &om));
    PetscCheck(nm > 0, c->comm, PETSC_ERR_ARG_WRONGSTATE, "Give the frequency range (-frf_fmin/-frf_fmax in Hz or -frf_omega_min/-frf_omega_max in rad/s)");
    for (PetscInt i = 0; i < nm; i++)
      if (om[i] > 1e-6 * om[nm - 1]) {
        PetscCall(JRContSetRange(c, 0.8 * om[i], 1.2 * om[i]));
        break;
      }
    PetscCheck(c->range_set, c->comm, PETSC_ERR_ARG_WRONGSTATE, "No elastic mode to centre the frequency range on: give -frf_fmin/-frf_fmax");
  }
  PetscCall(JRHBMCreateVecs(c->hbm, &a, &c->J));
  PetscCall(VecDestroy(&c->amod));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, c->nmod, &c->amod));
  PetscCall(VecDuplicate(a, &c->a));
  PetscCall(VecDuplicate(a, &c->r));
  PetscCall(VecDuplicate(a, &c->Rw));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, c->n + 1, &c->xk));
  PetscCall(VecDuplicate(c->xk, &c->xpred));
  PetscCall(VecDuplicate(c->xk, &c->tk));
  PetscCall(VecDuplicate(c->xk, &c->br_));
  PetscCall(VecDuplicate(c->xk, &c->dw));
  if (c->type == JR_CONT_ARCLENGTH) {
    KSP  ksp;
    PC   pc;
    SNES hs;
    PetscReal atol, rtol, stol;
    PetscInt  maxit, maxf;
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, c->n + 1, c->n + 1, NULL, &c->BJ));
    PetscCall(SNESCreate(PETSC_COMM_SELF, &c->bsnes));
    {
      const char *pre;
      PetscCall(JRHBMGetOptionsPrefix(c->hbm, &pre));
      PetscCall(SNESSetOptionsPrefix(c->bsnes, pre));
    }
    PetscCall(SNESSetFunction(c->bsnes, c->br_, BorderedFunction, c));
    PetscCall(SNESSetJacobian(c->bsnes, c->BJ, c->BJ, BorderedJacobian, c));
    PetscCall(SNESGetKSP(c->bsnes, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, PCLU));
    PetscCall(JRHBMGetSNES(c->hbm, &hs));
    PetscCall(SNESGetTolerances(hs, &atol, &rtol, &stol, &maxit, &maxf));
    PetscCall(SNESSetTolerances(c->bsnes, atol, rtol, stol, maxit, maxf));
    PetscCall(SNESSetType(c->bsnes, SNESNEWTONDENSE));
    PetscCall(SNESSetFromOptions(c->bsnes));
    {
      JRHBMJacobianType jt;
      PetscCall(JRHBMGetJacobianType(c->hbm, &jt));
      if (jt == JR_HBM_JACOBIAN_FD) PetscCall(SNESSetJacobian(c->bsnes, c->BJ, c->BJ, SNESComputeJacobianDefault, c));
    }
  }
  PetscCall(PetscFree(c->br));
  PetscCall(PetscCalloc1(c->nlev, &c->br));
  for (PetscInt lev = 0; lev < c->nlev; lev++) {
    Branch        *b = &c->br[lev];
    PetscLogDouble t0, t1;
    PetscCall(PetscTime(&t0));
    b->F = c->levels[lev];
    PetscCall(JRHBMSetForceLevel(c->hbm, b->F));
    if (c->type == JR_CONT_ARCLENGTH) {
      PetscReal atol;
      SNES      hs;
      PetscCall(JRHBMGetSNES(c->hbm, &hs));
      PetscCall(SNESGetTolerances(hs, &atol, NULL, NULL, NULL, NULL));
      PetscCall(SNESSetTolerances(c->bsnes, atol, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
      PetscCall(ResponseScale(c, b->F, a)); /* the response scale grows with the level */
      PetscCall(Arclength(c, lev, b, a));
    } else PetscCall(Natural(c, lev, b, a));
    PetscCall(PetscTime(&t1));
    b->seconds = t1 - t0;
    PetscCall(Peak(c, lev, c->amod));
    if (c->quiet) continue;
    if (c->monitor) PetscCall(PetscPrintf(c->comm, "cont: level %" PetscInt_FMT "/%" PetscInt_FMT " F %g N done: %" PetscInt_FMT " points, %" PetscInt_FMT " Newton iterations, %" PetscInt_FMT " retries, %.3g s%s\n", lev + 1, c->nlev, (double)b->F, b->np, b->newton, b->retries, (double)b->seconds, b->complete ? "" : " (incomplete: see above)"));
    PetscCall(PetscPrintf(c->comm, "peak level %g freq_hz %.8g amp %.8e amp_over_force %.8e\n", (double)b->F, (double)(b->wpeak / (2 * PETSC_PI)), (double)b->apeak, (double)(b->apeak / b->F)));
  }
  PetscCall(VecDestroy(&a));
  if (c->quiet) PetscFunctionReturn(0);
  /* summary, one row per level */
  PetscCall(PetscPrintf(c->comm, "frf summary (%s continuation; peak of response 1, refined by a parabola; zeta_eq = energy dissipated per cycle / (8 pi mean kinetic energy) at the peak;\n  energy balance: largest |W_in - W_damping - W_contact| / W_in over the curve; elements at the peak: full stick / stick-slip / separation with stick-slip / full separation)\n", JRContTypes[c->type]));
  PetscCall(PetscPrintf(c->comm, "  %10s %12s %13s %13s %10s %7s %7s %7s %9s %9s  %s\n", "F [N]", "peak [Hz]", "amp [m]", "amp/F [m/N]", "zeta_eq", "points", "newton", "retries", "time [s]", "balance", "states"));
  for (PetscInt lev = 0; lev < c->nlev; lev++) {
    Branch *b = &c->br[lev];
    PetscCall(PetscPrintf(c->comm, "  %10.4g %12.6g %13.5e %13.5e %10.4e %7" PetscInt_FMT " %7" PetscInt_FMT " %7" PetscInt_FMT " %9.3g %9.2e  %" PetscInt_FMT " / %" PetscInt_FMT " / %" PetscInt_FMT " / %" PetscInt_FMT "%s\n", (double)b->F, (double)(b->wpeak / (2 * PETSC_PI)), (double)b->apeak, (double)(b->apeak / b->F), (double)b->zeta, b->np, b->newton, b->retries, (double)b->seconds, (double)b->ebal, b->states[0], b->states[1], b->states[2], b->states[3], b->complete ? "" : "  (incomplete)"));
  }
  PetscFunctionReturn(0);
}

/* JRContSetQuiet - solve without printing progress, peak lines or the summary (a model solved as a means, e.g. to
   choose among candidates); warnings still print */
PetscErrorCode JRContSetQuiet(JRCont c, PetscBool quiet)
{
  PetscFunctionBeginUser;
  c->quiet = quiet;
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

/* Peak of the first output's amplitude on level lev [rad/s, m]: the computed point with the largest
   amplitude, refined by the parabola through it and its two neighbours when the frequencies are monotone
   there (not at a fold) */
PetscErrorCode JRContGetPeak(JRCont c, PetscInt lev, PetscReal *w, PetscReal *amp)
{
  PetscFunctionBeginUser;
  PetscCheck(c->br && lev >= 0 && lev < c->nlev, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "No level %" PetscInt_FMT, lev);
  *w   = c->br[lev].wpeak;
  *amp = c->br[lev].apeak;
  PetscFunctionReturn(0);
}

/* Peak, equivalent damping, energy balance, contact states (level lev done; a: work vector; collective) */
static PetscErrorCode Peak(JRCont c, PetscInt lev, Vec a)
{
  Branch  *b = &c->br[lev];
  PetscInt k = 0, nel;

  PetscFunctionBeginUser;
  for (PetscInt i = 1; i < b->np; i++)
    if (b->amp[i * c->nout] > b->amp[k * c->nout]) k = i;
  b->kpeak = k;
  b->wpeak = b->omega[k];
  b->apeak = b->amp[k * c->nout];
  if (k > 0 && k < b->np - 1) {
    const PetscReal x0 = b->omega[k - 1], x1 = b->omega[k], x2 = b->omega[k + 1];
    const PetscReal y0 = b->amp[(k - 1) * c->nout], y1 = b->amp[k * c->nout], y2 = b->amp[(k + 1) * c->nout];
    if ((x1 - x0) * (x2 - x1) > 0) {
      /* y = y1 + p (x - x1) + q (x - x1)^2 */
      const PetscReal d0 = x0 - x1, d2 = x2 - x1, s0 = (y0 - y1) / d0, s2 = (y2 - y1) / d2;
      const PetscReal q = (s2 - s0) / (d2 - d0), p = s0 - q * d0;
      if (q < 0) {
        const PetscReal dx = -p / (2 * q);
        if (PetscAbsReal(dx) <= PetscMax(PetscAbsReal(d0), PetscAbsReal(d2))) {
          b->wpeak = x1 + dx;
          b->apeak = y1 + p * dx + q * dx * dx;
        }
      }
    }
  }
  /* energies at every point, damping ratio at the peak */
  b->ebal = 0.0;
  for (PetscInt i = 0; i < b->np; i++) {
    PetscReal    win, ed, enl;
    PetscScalar *x;
    PetscCall(VecGetArray(a, &x));
    for (PetscInt j = 0; j < c->nmod; j++) x[j] = b->a[i * c->nmod + j];
    PetscCall(VecRestoreArray(a, &x));
    PetscCall(JRHBMEnergy(c->hbm, b->omega[i], a, &win, &ed, &enl));
    if (win > 0) b->ebal = PetscMax(b->ebal, PetscAbsReal(win - ed - enl) / win);
    if (i == k) {
      PetscReal T;
      PetscCall(JRHBMKineticEnergy(c->hbm, b->omega[i], a, &T));
      b->zeta = T > 0 ? (ed + enl) / (8 * PETSC_PI * T) : 0.0;
    }
  }
  {
    PetscScalar *x;
    PetscCall(VecGetArray(a, &x));
    for (PetscInt j = 0; j < c->nmod; j++) x[j] = b->a[k * c->nmod + j];
    PetscCall(VecRestoreArray(a, &x));
  }
  PetscCall(JRHBMContactStates(c->hbm, a, b->states));
  nel = b->states[0] + b->states[1] + b->states[2] + b->states[3];
  PetscCall(PetscFree(b->estate));
  PetscCall(PetscMalloc1(nel, &b->estate));
  PetscCall(JRHBMElementStates(c->hbm, a, b->estate));
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

/* One dataset written from rank 0: len values (reals r, or integers iv), block size bs (collective) */
static PetscErrorCode WriteRank0(MPI_Comm comm, PetscViewer v, const char name[], PetscInt len, PetscInt bs, const PetscReal r[], const PetscInt iv[])
{
  Vec          x;
  PetscScalar *xa;
  PetscMPIInt  rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank) len = 0;
  PetscCall(VecCreateMPI(comm, len, PETSC_DETERMINE, &x));
  if (bs > 1) PetscCall(VecSetBlockSize(x, bs));
  PetscCall(PetscObjectSetName((PetscObject)x, name));
  PetscCall(VecGetArray(x, &xa));
  for (PetscInt i = 0; i < len; i++) xa[i] = r ? r[i] : (PetscReal)iv[i];
  PetscCall(VecRestoreArray(x, &xa));
  PetscCall(VecView(x, v));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

/* Response o (0-based) in words: "response 1 along z at (x, y, z) m" at a point (JRHBMSetOutputPoints), else "response 1 at DOF d" */
static PetscErrorCode ResponseName(PetscInt o, const PetscReal xyz[], PetscInt dir, const PetscInt dofs[], char s[], size_t len)
{
  PetscFunctionBeginUser;
  if (xyz) PetscCall(PetscSNPrintf(s, len, "response %" PetscInt_FMT " along %c at (%g, %g, %g) m", o + 1, "xyz"[dir], (double)xyz[3 * o], (double)xyz[3 * o + 1], (double)xyz[3 * o + 2]));
  else PetscCall(PetscSNPrintf(s, len, "response %" PetscInt_FMT " at DOF %" PetscInt_FMT, o + 1, dofs[o]));
  PetscFunctionReturn(0);
}

/*
  JRContWrite - BASE.h5 (every point), BASE.csv (level,F_N,omega_rad_s,freq_hz,amp_1..amp_n[,pp_1..pp_n]: the
  responses by their index, 1-based) and BASE.png (response 1). The HDF5 group /response_<i> names response i:
  its point x_m, y_m, z_m and direction (JRHBMSetOutputPoints: an FE model) or its dof (a matrices model).
*/
PetscErrorCode JRContWrite(JRCont c)
{
  char             h5[PETSC_MAX_PATH_LEN + 8], csv[PETSC_MAX_PATH_LEN + 8], png[PETSC_MAX_PATH_LEN + 8], tmp[PETSC_MAX_PATH_LEN + 32], tmph5[PETSC_MAX_PATH_LEN + 32];
  const PetscInt  *dofs;
  const PetscReal *xyz;
  PetscInt         nm, H, nc, dir;
  FILE            *fp;
  PetscMPIInt      rank;
  const char      *damping;

  PetscFunctionBeginUser;
  if (!c->write) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(c->comm, &rank));
  PetscCall(JRHBMGetOutputs(c->hbm, &c->nout, &dofs));
  PetscCall(JRHBMGetOutputPoints(c->hbm, &xyz, &dir));
  PetscCall(JRHBMGetSizes(c->hbm, &nm, &H, NULL));
  PetscCall(JRHBMGetDampingDescription(c->hbm, &damping));
  nc = 2 * H + 1;
  PetscCall(PetscSNPrintf(h5, sizeof(h5), "%s.h5", c->out));
  PetscCall(PetscSNPrintf(csv, sizeof(csv), "%s.csv", c->out));
  PetscCall(PetscSNPrintf(png, sizeof(png), "%s.png", c->out));

  /* CSV */
  PetscCall(JRFileOpenTemp(c->comm, csv, &fp, tmp, sizeof(tmp)));
  if (fp) {
    fprintf(fp, "level,F_N,omega_rad_s,freq_hz");
    for (PetscInt o = 0; o < c->nout; o++) fprintf(fp, ",amp_%" PetscInt_FMT, o + 1);
    if (H > 1)
      for (PetscInt o = 0; o < c->nout; o++) fprintf(fp, ",pp_%" PetscInt_FMT, o + 1);
    fprintf(fp, "\n");
    for (PetscInt l = 0; l < c->nlev; l++) {
      Branch *b = &c->br[l];
      for (PetscInt k = 0; k < b->np; k++) {
        fprintf(fp, "%" PetscInt_FMT ",%.10g,%.12g,%.12g", l, (double)b->F, (double)b->omega[k], (double)(b->omega[k] / (2 * PETSC_PI)));
        for (PetscInt o = 0; o < c->nout; o++) fprintf(fp, ",%.10e", (double)b->amp[k * c->nout + o]);
        if (H > 1)
          for (PetscInt o = 0; o < c->nout; o++) fprintf(fp, ",%.10e", (double)b->pp[k * c->nout + o]);
        fprintf(fp, "\n");
      }
    }
  }
  PetscCall(JRFileCommit(c->comm, &fp, tmp, csv));

  /* HDF5: one group per level, with the run's options and units as attributes */
  {
    PetscViewer v;
    char       *opts;
    PetscCall(JRFileTempName(c->comm, h5, tmph5, sizeof(tmph5)));
    PetscCall(PetscViewerHDF5Open(c->comm, tmph5, FILE_MODE_WRITE, &v));
    PetscCall(PetscOptionsGetAll(NULL, &opts));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "options", PETSC_STRING, opts));
    PetscCall(PetscFree(opts));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "units", PETSC_STRING, "SI: omega rad/s, freq_hz Hz, amp m, force N; a: modal coordinates of mass-normalised modes (physical DOFs with -hbm_physical)"));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "damping", PETSC_STRING, damping));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "harmonics", PETSC_INT, &H));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "modes", PETSC_INT, &nm));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "layout_a", PETSC_STRING, "per point: [a0 | as_1 ac_1 | ... | as_H ac_H], each block over the modes"));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "continuation", PETSC_STRING, JRContTypes[c->type]));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "responses", PETSC_STRING, "amp and pp: one column per response, in order; /response_i: response i's point (x_m, y_m, z_m, direction) or, on a matrices model, its dof (0-based)"));
    for (PetscInt o = 0; o < c->nout; o++) {
      char grp[64], name[192];
      PetscCall(PetscSNPrintf(grp, sizeof(grp), "/response_%" PetscInt_FMT, o + 1));
      PetscCall(ResponseName(o, xyz, dir, dofs, name, sizeof(name)));
      PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "name", PETSC_STRING, name));
      if (xyz) {
        const char *xn[] = {"x_m", "y_m", "z_m"}, *dn[] = {"x", "y", "z"};
        for (PetscInt k = 0; k < 3; k++) PetscCall(PetscViewerHDF5WriteAttribute(v, grp, xn[k], PETSC_REAL, &xyz[3 * o + k]));
        PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "direction", PETSC_STRING, dn[dir]));
      } else PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "dof", PETSC_INT, &dofs[o]));
    }
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "peak_states", PETSC_STRING, "per level: every element's contact state at the peak, 0 full stick, 1 stick-slip without separation, 2 separation with stick-slip, 3 full separation"));
    for (PetscInt l = 0; l < c->nlev; l++) {
      Branch    *b = &c->br[l];
      char       grp[64];
      PetscInt   np = b->np;
      const struct {
        const char *name;
        PetscInt    bs;
        PetscReal  *data;
      } sets[] = {
        {"omega",      1,       b->omega},
        {"amp",        c->nout, b->amp  },
        {"pp",         c->nout, b->pp   },
        {"a",          c->nmod, b->a    },
        {"step",       1,       b->step }
      };
      PetscCall(PetscSNPrintf(grp, sizeof(grp), "/level_%" PetscInt_FMT, l));
      PetscCall(PetscViewerHDF5PushGroup(v, grp));
      for (size_t s = 0; s < sizeof(sets) / sizeof(sets[0]); s++) PetscCall(WriteRank0(c->comm, v, sets[s].name, np * sets[s].bs, sets[s].bs, sets[s].data, NULL));
      PetscCall(WriteRank0(c->comm, v, "newton_its", np, 1, NULL, b->its));
      PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "force_N", PETSC_REAL, &b->F));
      PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "points", PETSC_INT, &np));
      PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "seconds", PETSC_REAL, &b->seconds));
      PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "complete", PETSC_BOOL, &b->complete));
      {
        PetscReal fhz = b->wpeak / (2 * PETSC_PI), aof = b->apeak / b->F;
        PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "peak_freq_hz", PETSC_REAL, &fhz));
        PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "peak_amp_m", PETSC_REAL, &b->apeak));
        PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "peak_amp_over_force_m_per_N", PETSC_REAL, &aof));
        PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "zeta_eq", PETSC_REAL, &b->zeta));
        PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "energy_balance", PETSC_REAL, &b->ebal));
        PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "newton_total", PETSC_INT, &b->newton));
        PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "elements_full_stick", PETSC_INT, &b->states[0]));
        PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "elements_stick_slip", PETSC_INT, &b->states[1]));
        PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "elements_separation_stick_slip", PETSC_INT, &b->states[2]));
        PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "elements_full_separation", PETSC_INT, &b->states[3]));
      }
      {
        const PetscInt nel = b->states[0] + b->states[1] + b->states[2] + b->states[3];
        PetscInt      *st;
        PetscCall(PetscMalloc1(rank ? 0 : nel, &st));
        for (PetscInt i = 0; !rank && i < nel; i++) st[i] = (PetscInt)b->estate[i];
        PetscCall(WriteRank0(c->comm, v, "peak_states", nel, 1, NULL, st));
        PetscCall(PetscFree(st));
      }
      PetscCall(PetscViewerHDF5PopGroup(v));
    }
    PetscCall(PetscViewerDestroy(&v));
    PetscCall(JRFileRename(c->comm, tmph5, h5));
  }
  (void)nc;

  if (c->plot) {
    PetscBool made;
    char      vars[3 * PETSC_MAX_PATH_LEN], name[192];
    PetscCall(ResponseName(0, xyz, dir, dofs, name, sizeof(name)));
    PetscCall(PetscSNPrintf(vars, sizeof(vars), "data='%s'; nlev=%" PetscInt_FMT "; normalize=%d; ttl='%s (%s continuation, H = %" PetscInt_FMT ")'", csv, c->nlev, (int)c->normalize, name, JRContTypes[c->type], H));
    PetscCall(JRPlot(c->comm, "plot_frf.gp", png, vars, &made));
    PetscCall(PetscPrintf(c->comm, "frf: wrote %s, %s%s%s\n", h5, csv, made ? ", " : "", made ? png : ""));
  } else PetscCall(PetscPrintf(c->comm, "frf: wrote %s, %s\n", h5, csv));
  PetscFunctionReturn(0);
}

PetscErrorCode JRContDestroy(JRCont *cont)
{
  JRCont c = *cont;

  PetscFunctionBeginUser;
  if (!c) PetscFunctionReturn(0);
  for (PetscInt l = 0; c->br && l < c->nlev; l++) {
    PetscCall(PetscFree6(c->br[l].omega, c->br[l].a, c->br[l].amp, c->br[l].pp, c->br[l].step, c->br[l].its));
    PetscCall(PetscFree(c->br[l].estate));
  }
  PetscCall(PetscFree(c->br));
  PetscCall(PetscFree(c->levels));
  PetscCall(SNESDestroy(&c->bsnes));
  PetscCall(MatDestroy(&c->BJ));
  PetscCall(MatDestroy(&c->J));
  PetscCall(PetscFree3(c->tb, c->tlu, c->tpiv));
  PetscCall(VecDestroy(&c->amod));
  PetscCall(VecDestroy(&c->a));
  PetscCall(VecDestroy(&c->r));
  PetscCall(VecDestroy(&c->Rw));
  PetscCall(VecDestroy(&c->xk));
  PetscCall(VecDestroy(&c->xpred));
  PetscCall(VecDestroy(&c->tk));
  PetscCall(VecDestroy(&c->br_));
  PetscCall(VecDestroy(&c->dw));
  PetscCall(PetscFree(c));
  *cont = NULL;
  PetscFunctionReturn(0);
}
