/*
   JRPreload: the bolt preload, a nonlinear static contact analysis of the FE assembly (thesis 4.2, 5.1),
   giving every interface node pair's normal load N_static and gap v_gap, and n0 = N_static - kv v_gap (5.1).

   Bolts: each shank carries the pretension P (-preload_force, N) whatever its elongation, as a bolt load
   applied "by force" in Abaqus: the shank's axial stiffness is taken out of K and the structure is loaded
   by -P g (g: the shank's elongation over the footprint DOFs, JRBolts). The bending, shear and torsion of
   the shank stay. Later analyses use the whole K: the bolt held at its preloaded length.

   Contact: frictionless and unilateral between the facing nodes of each pair, the penetration
   w = (uA - uB) . n - gap0 resisted by a penalty spring k_i = kp area_i (kp in N/m^3: pressure per
   penetration, area_i the node's share of the surface, so that a uniform pressure is carried exactly).
   -preload_method augmented (default) adds augmented-Lagrangian (Uzawa) updates of the pair forces,
   lambda_i <- max(0, lambda_i + k_i w_i), until no force changes by more than -preload_rtol of the largest:
   the penetration then vanishes and the result does not depend on kp; -preload_method penalty stops after
   the first solve (the result converges to the exact one as kp grows; tests/test_preload.c shows it).
   An open pair keeps -preload_open_stiffness x k_i (1e-8: a force below 1e-8 of a closed pair's) so that
   K stays regular when a part is held by contact alone (the axial bolt stiffness is out).

   Each solve is a semi-smooth Newton method (SNES, prefix preload_) by one of the registered solvers
   (-preload_solver): condensed (default; src/preload/impls/condensed/), one sparse factorisation and Newton on the
   interface's dense flexibility, or full (src/preload/impls/full/), Newton on all DOFs whose Jacobian
   K + sum_closed k_i b_i b_i^T depends only on which pairs are closed, so it is refactored (sparse LDL^T, MUMPS) only
   when that set changes. Supports (-preload_support): minimal (default: 3-2-1 springs at three far-apart nodes,
   statically determinate, so the self-equilibrated bolt loads leave them unloaded), clamp (the end face x = 0
   fixed, "fix-free" as in the thesis), none (JRPreloadAddSupport only). Units SI.

   Files: preload.c the object's life cycle, options, solve, results and view; setup.c the system (supports, Kp,
   loads); io.c the results written (JRPreloadWrite) and read back (-preload_load); impls/ the solvers.
*/
#include <jointrom/private/preloadimpl.h>

const char *const JRPreloadMethods[]  = {"penalty", "augmented", "JRPreloadMethod", "JR_PRELOAD_", NULL};
const char *const JRPreloadSupports[] = {"minimal", "clamp", "none", "JRPreloadSupport", "JR_PRELOAD_SUPPORT_", NULL};

PetscFunctionList JRPreloadSolverList = NULL;

/* Register a preload solver: its name (-preload_solver) and the function that fills its ops */
PetscErrorCode JRPreloadSolverRegister(const char name[], PetscErrorCode (*create)(JRPreload))
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListAdd(&JRPreloadSolverList, name, create));
  PetscFunctionReturn(0);
}

/* Register the built-in solvers once (JRInitializePackage; JRFinalizePackage destroys the list) */
PetscErrorCode JRPreloadSolverRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (JRPreloadSolverList) PetscFunctionReturn(0);
  PetscCall(JRPreloadSolverRegister(JRPRELOADCONDENSED, JRPreloadSolverCreate_Condensed));
  PetscCall(JRPreloadSolverRegister(JRPRELOADFULL, JRPreloadSolverCreate_Full));
  PetscFunctionReturn(0);
}

PetscErrorCode JRPreloadCreate(MPI_Comm comm, JRPreload *pre)
{
  JRPreload p;

  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(PetscNew(&p));
  p->comm     = comm;
  p->nforce   = 1;
  p->force[0] = 11500.0;
  p->method   = JR_PRELOAD_AUGMENTED;
  p->support  = JR_PRELOAD_SUPPORT_MINIMAL;
  p->eps      = 1e-8;
  p->rtol     = 1e-6;
  p->maxit    = 100;
  p->open_gap = 1e-5;
  p->load_tol = 1e-6;
  *pre        = p;
  PetscFunctionReturn(0);
}

/* The FE model (borrowed: keep it until JRPreloadDestroy()); its interface must be free */
PetscErrorCode JRPreloadSetModel(JRPreload p, JRModel m)
{
  PetscFunctionBeginUser;
  p->model = m;
  PetscFunctionReturn(0);
}

/* Pretension [N]: one value for every bolt (n = 1) or one per bolt */
PetscErrorCode JRPreloadSetForces(JRPreload p, PetscInt n, const PetscReal F[])
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 1 && n <= JR_PRELOAD_MAXBOLTS, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_force: %" PetscInt_FMT " values; give 1 (every bolt) to %d", n, JR_PRELOAD_MAXBOLTS);
  for (PetscInt i = 0; i < n; i++) PetscCheck(F[i] >= 0 && PetscIsNormalReal(F[i] + 1.0), p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_force: value %" PetscInt_FMT " is %g N; a pretension is a tension, zero or positive", i + 1, (double)F[i]);
  p->nforce = n;
  PetscCall(PetscArraycpy(p->force, F, n));
  PetscFunctionReturn(0);
}

/* An external load besides the bolts (a vector of the model's DOFs; a reference is kept) */
PetscErrorCode JRPreloadSetExternalForce(JRPreload p, Vec f)
{
  PetscFunctionBeginUser;
  PetscCall(PetscObjectReference((PetscObject)f));
  PetscCall(VecDestroy(&p->fext));
  p->fext = f;
  PetscFunctionReturn(0);
}

/* A support: the node whose x DOF is dof0 held along the unit direction dir (a stiff spring to ground) */
PetscErrorCode JRPreloadAddSupport(JRPreload p, PetscInt dof0, const PetscReal dir[3])
{
  const PetscReal len = PetscSqrtReal(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);

  PetscFunctionBeginUser;
  PetscCheck(len > 0, p->comm, PETSC_ERR_ARG_WRONG, "Support direction is zero");
  if (p->nsup == p->supcap) {
    PetscInt  *d;
    PetscReal *r;
    p->supcap = p->supcap ? 2 * p->supcap : 16;
    PetscCall(PetscMalloc2(p->supcap, &d, 3 * p->supcap, &r));
    if (p->nsup) {
      PetscCall(PetscArraycpy(d, p->supdof, p->nsup));
      PetscCall(PetscArraycpy(r, p->supdir, 3 * p->nsup));
    }
    PetscCall(PetscFree2(p->supdof, p->supdir));
    p->supdof = d;
    p->supdir = r;
  }
  p->supdof[p->nsup] = dof0;
  for (int d = 0; d < 3; d++) p->supdir[3 * p->nsup + d] = dir[d] / len;
  p->nsup++;
  PetscFunctionReturn(0);
}

/* The solver of the contact problem (-preload_solver): condensed or full */
PetscErrorCode JRPreloadSetSolverType(JRPreload p, JRPreloadSolverType type)
{
  PetscErrorCode (*create)(JRPreload) = NULL;
  PetscBool match;

  PetscFunctionBeginUser;
  PetscCall(JRPreloadSolverRegisterAll());
  PetscCall(PetscStrcmp(p->type_name, type, &match));
  if (match) PetscFunctionReturn(0);
  PetscCall(PetscFunctionListFind(JRPreloadSolverList, type, &create));
  PetscCheck(create, p->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown preload solver '%s' (-preload_solver): condensed or full", type);
  if (p->ops->destroy) PetscCall((*p->ops->destroy)(p));
  PetscCall(PetscMemzero(p->ops, sizeof(struct _JRPreloadOps)));
  p->data = NULL;
  p->what = NULL;
  PetscCall(PetscStrncpy(p->type_name, type, sizeof(p->type_name)));
  PetscCall((*create)(p));
  PetscFunctionReturn(0);
}

PetscErrorCode JRPreloadGetSolverType(JRPreload p, JRPreloadSolverType *type)
{
  PetscFunctionBeginUser;
  *type = p->type_name[0] ? p->type_name : NULL;
  PetscFunctionReturn(0);
}

/*
  Options (prefix preload_): -preload_force, -preload_method penalty|augmented, -preload_penalty, -preload_rtol,
  -preload_max_it, -preload_open_stiffness, -preload_solver condensed|full, -preload_support minimal|clamp|none,
  -preload_open_start, -preload_open_gap, -preload_kv, -preload_load, -preload_load_tol; the solvers' SNES, KSP and
  PC take -preload_snes_*, -preload_ksp_*, -preload_pc_*
*/
PetscErrorCode JRPreloadSetFromOptions(JRPreload p)
{
  PetscInt  m = JR_PRELOAD_MAXBOLTS;
  PetscReal F[JR_PRELOAD_MAXBOLTS];
  PetscBool set, flg;
  char      type[64];

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < m; i++) F[i] = i < p->nforce ? p->force[i] : 0; /* the defaults -help shows */
  PetscCall(JRPreloadSolverRegisterAll());
  PetscOptionsBegin(p->comm, "preload_", "Bolt preload: static contact analysis (prefix preload_)", "JRPreload");
  PetscCall(PetscOptionsRealArray("-force", "Bolt pretension [N]: one value for all bolts, or one per bolt (comma-separated)", "JRPreloadSetForces", F, &m, &set));
  if (set) PetscCall(JRPreloadSetForces(p, m, F));
  PetscCall(PetscOptionsEnum("-method", "Contact enforcement: penalty (penetration ~ pressure / kp) or augmented (Lagrangian updates until the penetration vanishes)", "JRPreloadSolve", JRPreloadMethods, (PetscEnum)p->method, (PetscEnum *)&p->method, NULL));
  PetscCall(PetscOptionsReal("-penalty", "Contact penalty kp [N/m^3] (pressure per penetration; default 10 x the structure's normal stiffness per area at the interface)", "JRPreloadSolve", p->kp, &p->kp, &p->kp_set));
  PetscCall(PetscOptionsReal("-rtol", "Augmented Lagrangian: stop when no pair force changes by more than rtol x the largest", "JRPreloadSolve", p->rtol, &p->rtol, NULL));
  PetscCall(PetscOptionsInt("-max_it", "Augmented Lagrangian: most updates", "JRPreloadSolve", p->maxit, &p->maxit, NULL));
  PetscCall(PetscOptionsReal("-open_stiffness", "Stiffness of an open pair, relative to a closed one", "JRPreloadSolve", p->eps, &p->eps, NULL));
  PetscCall(PetscOptionsFList("-solver", "condensed (one factorisation of K, Newton on the interface's dense flexibility) or full (Newton on all DOFs, a factorisation per change of the closed set)", "JRPreloadSetSolverType", JRPreloadSolverList, p->type_name[0] ? p->type_name : JRPRELOADCONDENSED, type, sizeof(type), &flg));
  if (flg) PetscCall(JRPreloadSetSolverType(p, type));
  else if (!p->type_name[0]) PetscCall(JRPreloadSetSolverType(p, JRPRELOADCONDENSED));
  PetscCall(PetscOptionsEnum("-support", "Supports: minimal (3-2-1, statically determinate), clamp (end x = 0 fixed, as in the thesis), none", "JRPreloadSolve", JRPreloadSupports, (PetscEnum)p->support, (PetscEnum *)&p->support, NULL));
  PetscCall(PetscOptionsBool("-open_start", "Start Newton from every pair open (by -preload_open_gap) instead of closed", "JRPreloadSolve", p->open_start, &p->open_start, NULL));
  PetscCall(PetscOptionsReal("-open_gap", "Opening of the pairs at an open start [m]", "JRPreloadSolve", p->open_gap, &p->open_gap, NULL));
  PetscCall(PetscOptionsReal("-kv", "Normal contact stiffness kv [N/m] for n0 = N_static - kv v_gap (5.1)", "JRPreloadGetN0", p->kv, &p->kv, &p->kv_set));
  PetscCall(PetscOptionsString("-load", "Read N_static and v_gap per pair from a file (CSV: x_m,y_m,z_m,N_static_N,v_gap_m; or this program's HDF5) instead of solving", "JRPreloadSolve", p->load, p->load, sizeof(p->load), NULL));
  PetscCall(PetscOptionsReal("-load_tol", "Distance within which a row of the -preload_load file matches a pair [m]", "JRPreloadSolve", p->load_tol, &p->load_tol, NULL));
  PetscOptionsEnd();
  PetscCheck(p->rtol > 0 && p->rtol < 1, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_rtol %g: in (0, 1)", (double)p->rtol);
  PetscCheck(p->maxit >= 1, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_max_it %" PetscInt_FMT ": at least 1", p->maxit);
  PetscCheck(p->eps > 0 && p->eps < 1, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_open_stiffness %g: in (0, 1)", (double)p->eps);
  PetscCheck(!p->kp_set || (p->kp > 0 && PetscIsNormalReal(p->kp)), p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_penalty %g: a positive stiffness per area [N/m^3]", (double)p->kp);
  PetscCheck(!p->kv_set || (p->kv >= 0 && PetscIsNormalReal(p->kv + 1.0)), p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_kv %g: zero or a positive stiffness [N/m]", (double)p->kv);
  PetscCheck(p->open_gap > 0 && PetscIsNormalReal(p->open_gap), p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_open_gap %g: a positive distance [m]", (double)p->open_gap);
  PetscCheck(p->load_tol > 0 && PetscIsNormalReal(p->load_tol), p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_load_tol %g: a positive distance [m]", (double)p->load_tol);
  if (p->load[0]) PetscCall(JRPreloadCheckLoadFile(p));
  PetscFunctionReturn(0);
}

/* No results: before a solve or a read */
PetscErrorCode JRPreloadClearResults(JRPreload p)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree2(p->N, p->gap));
  p->solved = p->loaded = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*
  JRPreloadAugmentedLagrangian - the contact problem for the solvers: Newton (snes) on x at fixed multipliers lam, then
  state(p, P, x) sets the pairs' penetrations w and closed set; with -preload_method augmented the multipliers are
  updated, lam <- max(0, lam + k w) (Uzawa), until no pair force changes by more than -preload_rtol of the largest
  (-preload_max_it updates at most); with penalty, one solve. Counts the Newton iterations and the solves.
*/
PetscErrorCode JRPreloadAugmentedLagrangian(JRPreload p, SNES snes, Vec x, PetscErrorCode (*state)(JRPreload, const JRPairs *, Vec))
{
  const JRPairs      *P;
  SNESConvergedReason reason;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetPairs(p->model, &P));
  for (PetscInt it = 0; it < p->maxit; it++) {
    PetscInt  its;
    PetscReal dmax = 0.0, fmax = 0.0;
    PetscCall(SNESSolve(snes, NULL, x));
    PetscCall(SNESGetConvergedReason(snes, &reason));
    PetscCall(SNESGetIterationNumber(snes, &its));
    p->newton += its;
    p->outer++;
    PetscCheck(reason > 0, p->comm, PETSC_ERR_NOT_CONVERGED, "preload: Newton did not converge (%s after %" PetscInt_FMT " iterations, update %" PetscInt_FMT "); see -preload_snes_monitor, raise -preload_snes_max_it, or try -preload_solver full", SNESConvergedReasons[reason], its, it + 1);
    PetscCall((*state)(p, P, x));
    if (p->method == JR_PRELOAD_PENALTY) break;
    for (PetscInt i = 0; i < p->np; i++) {
      const PetscReal l = PetscMax(0.0, p->lam[i] + p->k[i] * p->w[i]);
      dmax              = PetscMax(dmax, PetscAbsReal(l - p->lam[i]));
      fmax              = PetscMax(fmax, l);
      p->lam[i]         = l;
    }
    if (dmax <= p->rtol * fmax) break;
    PetscCheck(it + 1 < p->maxit, p->comm, PETSC_ERR_NOT_CONVERGED, "preload: the augmented Lagrangian did not converge in %" PetscInt_FMT " updates (-preload_max_it): largest force change %g N of %g N; raise -preload_penalty or -preload_rtol", p->maxit, (double)dmax, (double)fmax);
  }
  PetscFunctionReturn(0);
}

/* Solve the preload (or read it with -preload_load): the system set up once (JRPreloadSetUpSystem, the solver's
   setup), then the solver from the start, then N_static and v_gap per pair */
PetscErrorCode JRPreloadSolve(JRPreload p)
{
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscCheck(p->model, p->comm, PETSC_ERR_ARG_WRONGSTATE, "JRPreloadSetModel() first");
  PetscCall(PetscTime(&t0));
  if (p->load[0]) {
    PetscCall(JRPreloadLoadResults(p));
    PetscCall(PetscTime(&t1));
    p->time = t1 - t0;
    PetscFunctionReturn(0);
  }
  if (!p->type_name[0]) PetscCall(JRPreloadSetSolverType(p, JRPRELOADCONDENSED));
  PetscCall(PetscLogEventBegin(JR_PreloadSetUp, 0, 0, 0, 0));
  if (!p->Kp) PetscCall(JRPreloadSetUpSystem(p));
  PetscCall(JRPreloadClearResults(p));
  p->newton = p->outer = p->factorisations = 0;
  if (p->ops->setup) PetscCall((*p->ops->setup)(p));
  PetscCall(PetscLogEventEnd(JR_PreloadSetUp, 0, 0, 0, 0));
  PetscCall(PetscLogEventBegin(JR_PreloadSolve, 0, 0, 0, 0));
  PetscCall(VecZeroEntries(p->u));
  for (PetscInt i = 0; i < p->np; i++) p->lam[i] = 0.0;
  p->jvalid = PETSC_FALSE;
  PetscCall((*p->ops->solve)(p));
  PetscCall(PetscLogEventEnd(JR_PreloadSolve, 0, 0, 0, 0));
  /* results */
  PetscCall(PetscMalloc2(p->np, &p->N, p->np, &p->gap));
  p->maxpen = 0.0;
  for (PetscInt i = 0; i < p->np; i++) {
    const PetscReal t = p->lam[i] + (p->method == JR_PRELOAD_PENALTY ? p->k[i] * p->w[i] : 0.0);
    p->N[i]           = PetscMax(0.0, p->method == JR_PRELOAD_PENALTY ? t : p->lam[i]);
    p->gap[i]         = p->N[i] > 0 ? 0.0 : PetscMax(0.0, -p->w[i]);
    p->maxpen         = PetscMax(p->maxpen, p->w[i]);
  }
  p->solved = PETSC_TRUE;
  PetscCall(PetscTime(&t1));
  p->time = t1 - t0;
  PetscFunctionReturn(0);
}

/* Per pair (every rank, borrowed): normal load N_static [N] and gap v_gap [m] */
PetscErrorCode JRPreloadGetResults(JRPreload p, PetscInt *n, const PetscReal **N, const PetscReal **gap)
{
  PetscFunctionBeginUser;
  PetscCheck(p->solved || p->loaded, p->comm, PETSC_ERR_ARG_WRONGSTATE, "JRPreloadSolve() first");
  if (n) *n = p->np;
  if (N) *N = p->N;
  if (gap) *gap = p->gap;
  PetscFunctionReturn(0);
}

/* n0 = N_static - kv v_gap per pair (5.1), kv [N/m] */
PetscErrorCode JRPreloadGetN0(JRPreload p, PetscReal kv, PetscReal n0[])
{
  PetscInt         n;
  const PetscReal *N, *g;

  PetscFunctionBeginUser;
  PetscCall(JRPreloadGetResults(p, &n, &N, &g));
  for (PetscInt i = 0; i < n; i++) n0[i] = N[i] - kv * g[i];
  PetscFunctionReturn(0);
}

/* The displacement of the preload solve (borrowed; NULL after -preload_load) */
PetscErrorCode JRPreloadGetSolution(JRPreload p, Vec *u)
{
  PetscFunctionBeginUser;
  *u = p->solved ? p->u : NULL;
  PetscFunctionReturn(0);
}

PetscErrorCode JRPreloadGetSummary(JRPreload p, JRPreloadSummary *s)
{
  const JRPairs *P;
  const JRBolts *B;
  PetscInt       n;
  const PetscReal *N, *g;
  PetscReal      atot = 0.0;

  PetscFunctionBeginUser;
  PetscCall(JRPreloadGetResults(p, &n, &N, &g));
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(JRModelGetBolts(p->model, &B));
  PetscCall(PetscMemzero(s, sizeof(*s)));
  s->pairs = n;
  for (PetscInt i = 0; i < n; i++) {
    atot += P->area[i];
    s->total_force += N[i];
    s->gap_max = PetscMax(s->gap_max, g[i]);
    if (N[i] > 0) {
      s->in_contact++;
      s->contact_area += P->area[i];
      s->peak_force    = PetscMax(s->peak_force, N[i]);
      s->peak_pressure = PetscMax(s->peak_pressure, N[i] / P->area[i]);
    }
  }
  s->interface_area = atot;
  for (PetscInt b = 0; b < B->n; b++) s->bolt_force_sum += p->nforce == 1 ? p->force[0] : p->force[b];
  s->bolts            = B->n;
  s->newton           = p->newton;
  s->updates          = p->outer;
  s->factorisations   = p->factorisations;
  s->penalty          = p->kp;
  s->max_penetration  = p->maxpen;
  s->time             = p->time;
  s->loaded           = p->loaded;
  PetscFunctionReturn(0);
}

PetscErrorCode JRPreloadView(JRPreload p, PetscViewer viewer)
{
  JRPreloadSummary s;

  PetscFunctionBeginUser;
  if (!viewer) viewer = PETSC_VIEWER_STDOUT_(p->comm);
  PetscCall(JRPreloadGetSummary(p, &s));
  if (s.loaded) PetscCall(PetscViewerASCIIPrintf(viewer, "preload: read from %s (%" PetscInt_FMT " pairs)\n", p->load, s.pairs));
  else {
    PetscCall(PetscViewerASCIIPrintf(viewer, "preload: %" PetscInt_FMT " bolts, pretension %s%.6g N; %s contact, kp = %.3g N/m^3; supports %s\n", s.bolts, p->nforce > 1 ? "first " : "", (double)p->force[0], p->method == JR_PRELOAD_PENALTY ? "penalty" : "augmented-Lagrangian", (double)s.penalty, JRPreloadSupports[p->support]));
    PetscCall(PetscViewerASCIIPrintf(viewer, "preload: %" PetscInt_FMT " Newton iterations in %" PetscInt_FMT " solve%s (%s), %" PetscInt_FMT " sparse factorisations, %.3g s; largest penetration %.3g m\n", s.newton, s.updates, s.updates > 1 ? "s" : "", p->what ? p->what : p->type_name, s.factorisations, (double)s.time, (double)s.max_penetration));
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "preload: contact area %.4g mm^2 of %.4g mm^2 (%.1f%%), %" PetscInt_FMT " of %" PetscInt_FMT " pairs closed (%.1f%%)\n", (double)(s.contact_area * 1e6), (double)(s.interface_area * 1e6), (double)(100 * s.contact_area / s.interface_area), s.in_contact, s.pairs, (double)(100.0 * s.in_contact / PetscMax(s.pairs, 1))));
  PetscCall(PetscViewerASCIIPrintf(viewer, "preload: peak pressure %.4g MPa, mean over the contact area %.4g MPa, largest pair force %.4g N, largest gap %.3g um\n", (double)(s.peak_pressure * 1e-6), (double)(s.contact_area > 0 ? s.total_force / s.contact_area * 1e-6 : 0.0), (double)s.peak_force, (double)(s.gap_max * 1e6)));
  PetscFunctionReturn(0);
}

PetscErrorCode JRPreloadDestroy(JRPreload *pre)
{
  JRPreload p = *pre;

  PetscFunctionBeginUser;
  if (!p) PetscFunctionReturn(0);
  PetscCall(JRPreloadClearResults(p));
  if (p->ops->destroy) PetscCall((*p->ops->destroy)(p));
  PetscCall(MatDestroy(&p->Kp));
  PetscCall(MatDestroy(&p->J));
  PetscCall(VecDestroy(&p->u));
  PetscCall(VecDestroy(&p->f));
  PetscCall(VecDestroy(&p->useq));
  PetscCall(VecDestroy(&p->fext));
  PetscCall(VecScatterDestroy(&p->sc));
  if (p->k) PetscCall(PetscFree5(p->k, p->lam, p->w, p->closed, p->jclosed));
  PetscCall(PetscFree(p->clamp));
  PetscCall(PetscFree2(p->supdof, p->supdir));
  PetscCall(PetscFree(p));
  *pre = NULL;
  PetscFunctionReturn(0);
}
