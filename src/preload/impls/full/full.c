/*
   -preload_solver full: semi-smooth Newton on all DOFs (SNES, prefix preload_). The residual is Kp u - f + B c(w), the
   Jacobian J = Kp + sum_i k_i b_i b_i^T (closed) or eps k_i (open), which depends only on which pairs are closed, so it
   is assembled and refactored (sparse LDL^T, MUMPS when present) only when that set changes.
*/
#include <jointrom/private/preloadimpl.h>

typedef struct {
  SNES snes;
} JRPreload_Full;

/* w_i (penetration) and the contact force c_i of every pair from the gathered pair DOFs */
static PetscErrorCode PairState(JRPreload p, const JRPairs *P, Vec u)
{
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(p->sc, u, p->useq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(p->sc, u, p->useq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(p->useq, &a));
  for (PetscInt i = 0; i < p->np; i++) {
    PetscReal v = 0.0;
    for (int d = 0; d < 3; d++) v += (PetscRealPart(a[6 * i + d]) - PetscRealPart(a[6 * i + 3 + d])) * P->nrm[3 * i + d];
    p->w[i]      = v - P->gap0[i];
    p->closed[i] = p->lam[i] + p->k[i] * p->w[i] >= 0.0; /* touching counts as closed: Newton starts from the closed state */
  }
  PetscCall(VecRestoreArrayRead(p->useq, &a));
  PetscFunctionReturn(0);
}

/* r = Kp u - f + sum_i c_i b_i (clamped rows: diag u) */
static PetscErrorCode FormFunction(SNES snes, Vec u, Vec r, void *ctx)
{
  JRPreload          p = (JRPreload)ctx;
  const JRPairs     *P;
  PetscScalar       *ra;
  const PetscScalar *ua;
  PetscInt           rs, re;

  PetscFunctionBeginUser;
  (void)snes;
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(MatMult(p->Kp, u, r));
  PetscCall(VecAXPY(r, -1.0, p->f));
  PetscCall(PairState(p, P, u));
  PetscCall(VecGetOwnershipRange(r, &rs, &re));
  PetscCall(VecGetArray(r, &ra));
  for (PetscInt i = 0; i < p->np; i++) {
    const PetscReal c = JRPreloadPairForce(p, i);
    for (int d = 0; d < 3; d++) {
      const PetscInt a = P->dofA[3 * i + d], b = P->dofB[3 * i + d];
      if (a >= rs && a < re) ra[a - rs] += c * P->nrm[3 * i + d];
      if (b >= rs && b < re) ra[b - rs] -= c * P->nrm[3 * i + d];
    }
  }
  PetscCall(VecGetArrayRead(u, &ua));
  for (PetscInt i = 0; i < p->nclamp; i++) ra[p->clamp[i] - rs] = p->diag * ua[p->clamp[i] - rs];
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(VecRestoreArray(r, &ra));
  PetscFunctionReturn(0);
}

/* J = Kp + sum_i k_i (closed) or eps k_i (open) b_i b_i^T; left untouched (no new factorisation) when the
   set of closed pairs is the one of the last assembly */
static PetscErrorCode FormJacobian(SNES snes, Vec u, Mat J, Mat Jp, void *ctx)
{
  JRPreload      p = (JRPreload)ctx;
  const JRPairs *P;
  PetscInt       same = 1;

  PetscFunctionBeginUser;
  (void)snes;
  (void)J;
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(PairState(p, P, u));
  if (p->jvalid)
    for (PetscInt i = 0; i < p->np && same; i++) same = p->closed[i] == p->jclosed[i];
  if (p->jvalid && same) PetscFunctionReturn(0);
  PetscCall(JRPreloadAssembleJacobian(p, P, Jp));
  p->jvalid = PETSC_TRUE;
  p->factorisations++;
  PetscFunctionReturn(0);
}

/* The SNES: Newton with sparse LDL^T (MUMPS when present), prefix preload_ */
static PetscErrorCode JRPreloadSetUp_Full(JRPreload p)
{
  JRPreload_Full *full = (JRPreload_Full *)p->data;
  KSP             ksp;
  PC              pc;

  PetscFunctionBeginUser;
  if (full->snes) PetscFunctionReturn(0);
  PetscCall(SNESCreate(p->comm, &full->snes));
  PetscCall(SNESSetOptionsPrefix(full->snes, "preload_"));
  PetscCall(SNESSetFunction(full->snes, NULL, FormFunction, p));
  PetscCall(SNESSetJacobian(full->snes, p->J, p->J, FormJacobian, p));
  PetscCall(SNESSetTolerances(full->snes, PETSC_DEFAULT, 1e-10, PETSC_DEFAULT, 50, PETSC_DEFAULT));
  PetscCall(SNESSetDivergenceTolerance(full->snes, -1.0)); /* from an open start the first step overshoots by far */
  { /* full Newton steps: on this piecewise-linear system they are active-set steps (11 iterations instead of 24
       with backtracking on the 67k-DOF lap of tests/test_preload.c at h = 2.5 mm) */
    SNESLineSearch ls;
    PetscCall(SNESGetLineSearch(full->snes, &ls));
    PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
  }
  PetscCall(SNESGetKSP(full->snes, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
#if defined(PETSC_HAVE_MUMPS)
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
#endif
  PetscCall(SNESSetFromOptions(full->snes));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(JRCheckFactorSolverType(pc, p->J, "preload_"));
  PetscFunctionReturn(0);
}

/* From u = 0, or with -preload_open_start every pair open (B's pair nodes moved along the normal, away from A) */
static PetscErrorCode JRPreloadSolve_Full(JRPreload p)
{
  JRPreload_Full *full = (JRPreload_Full *)p->data;
  const JRPairs  *P;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetPairs(p->model, &P));
  if (p->open_start) {
    PetscInt rs, re;
    PetscCall(VecGetOwnershipRange(p->u, &rs, &re));
    for (PetscInt i = 0; i < 3 * p->np; i++)
      if (P->dofB[i] >= rs && P->dofB[i] < re) PetscCall(VecSetValue(p->u, P->dofB[i], p->open_gap * P->nrm[i], INSERT_VALUES));
    PetscCall(VecAssemblyBegin(p->u));
    PetscCall(VecAssemblyEnd(p->u));
  }
  PetscCall(JRPreloadAugmentedLagrangian(p, full->snes, p->u, PairState));
  PetscFunctionReturn(0);
}

static PetscErrorCode JRPreloadDestroy_Full(JRPreload p)
{
  JRPreload_Full *full = (JRPreload_Full *)p->data;

  PetscFunctionBeginUser;
  PetscCall(SNESDestroy(&full->snes));
  PetscCall(PetscFree(p->data));
  PetscFunctionReturn(0);
}

PetscErrorCode JRPreloadSolverCreate_Full(JRPreload p)
{
  JRPreload_Full *full;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&full));
  p->data         = full;
  p->what         = "all DOFs";
  p->ops->setup   = JRPreloadSetUp_Full;
  p->ops->solve   = JRPreloadSolve_Full;
  p->ops->destroy = JRPreloadDestroy_Full;
  PetscFunctionReturn(0);
}
