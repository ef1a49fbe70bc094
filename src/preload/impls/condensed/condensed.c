/*
   -preload_solver condensed (the default): with K0 = Kp + sum_i k_i b_i b_i^T (every pair closed; regular) and
   s_i(w) = c_i(w) - k_i (w_i + gap0_i), the equilibrium Kp u + B c(w) = f is K0 u = f - B s(w), so the penetrations
   solve the interface equations
     F(w) = w + gap0 - yf + G s(w) = 0,   G = B^T K0^-1 B (n x n, the interface flexibility),  yf = B^T K0^-1 f,
   with the Jacobian I + G diag(c_i' - k_i) (columns of closed pairs are unit vectors). One sparse factorisation
   of K0 and n solves (blocks of right-hand sides) give G; the Newton iterations are dense and cheap.
*/
#include <jointrom/private/preloadimpl.h>

typedef struct {
  KSP        ksp0;   /* K0, factored once */
  PetscReal *G, *yf; /* the interface flexibility (n x n, symmetric) and B^T K0^-1 f, on every rank */
  SNES       csnes;  /* Newton on the penetrations w (PETSC_COMM_SELF) */
  Mat        cJ;
  Vec        cw;
} JRPreload_Condensed;

/* y_i = (x_A - x_B) . n_i for every pair, from the gathered pair DOFs of x */
static PetscErrorCode PairValues(JRPreload p, const JRPairs *P, Vec x, PetscReal *y)
{
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(p->sc, x, p->useq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(p->sc, x, p->useq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(p->useq, &a));
  for (PetscInt i = 0; i < p->np; i++) {
    y[i] = 0.0;
    for (int d = 0; d < 3; d++) y[i] += (PetscRealPart(a[6 * i + d]) - PetscRealPart(a[6 * i + 3 + d])) * P->nrm[3 * i + d];
  }
  PetscCall(VecRestoreArrayRead(p->useq, &a));
  PetscFunctionReturn(0);
}

/* r = sum_i s_i b_i (rows owned here) */
static PetscErrorCode PairLoads(JRPreload p, const JRPairs *P, const PetscReal *sv, Vec r)
{
  PetscScalar *ra;
  PetscInt     rs, re;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(r));
  PetscCall(VecGetOwnershipRange(r, &rs, &re));
  PetscCall(VecGetArray(r, &ra));
  for (PetscInt i = 0; i < p->np; i++)
    for (int d = 0; d < 3; d++) {
      const PetscInt a = P->dofA[3 * i + d], b = P->dofB[3 * i + d];
      if (a >= rs && a < re) ra[a - rs] += sv[i] * P->nrm[3 * i + d];
      if (b >= rs && b < re) ra[b - rs] -= sv[i] * P->nrm[3 * i + d];
    }
  PetscCall(VecRestoreArray(r, &ra));
  PetscFunctionReturn(0);
}

/* The penetrations w and the closed set from the unknowns */
static PetscErrorCode CondensedState(JRPreload p, const JRPairs *P, Vec w)
{
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(w, &a));
  for (PetscInt i = 0; i < p->np; i++) {
    p->w[i]      = PetscRealPart(a[i]);
    p->closed[i] = p->lam[i] + p->k[i] * p->w[i] >= 0.0;
  }
  PetscCall(VecRestoreArrayRead(w, &a));
  (void)P;
  PetscFunctionReturn(0);
}

/* F(w) = w + gap0 - yf + G s(w) */
static PetscErrorCode CondensedFunction(SNES snes, Vec w, Vec F, void *ctx)
{
  JRPreload            p = (JRPreload)ctx;
  JRPreload_Condensed *c = (JRPreload_Condensed *)p->data;
  const JRPairs       *P;
  PetscScalar         *fa;
  PetscReal           *sv;
  const PetscInt       n = p->np;

  PetscFunctionBeginUser;
  (void)snes;
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(CondensedState(p, P, w));
  PetscCall(PetscMalloc1(n, &sv));
  for (PetscInt j = 0; j < n; j++) sv[j] = JRPreloadPairForce(p, j) - p->k[j] * (p->w[j] + P->gap0[j]);
  PetscCall(VecGetArray(F, &fa));
  for (PetscInt i = 0; i < n; i++) fa[i] = p->w[i] + P->gap0[i] - c->yf[i];
  for (PetscInt j = 0; j < n; j++) /* G is symmetric: column j = row j, contiguous */
    for (PetscInt i = 0; i < n; i++) fa[i] += c->G[(size_t)j * n + i] * sv[j];
  PetscCall(VecRestoreArray(F, &fa));
  PetscCall(PetscFree(sv));
  PetscFunctionReturn(0);
}

/* I + G diag(c_i' - k_i); left as it is when the closed set is the one of the last assembly */
static PetscErrorCode CondensedJacobian(SNES snes, Vec w, Mat J, Mat Jp, void *ctx)
{
  JRPreload            p = (JRPreload)ctx;
  JRPreload_Condensed *c = (JRPreload_Condensed *)p->data;
  const JRPairs       *P;
  PetscScalar         *ja;
  PetscInt             same = 1;
  const PetscInt       n = p->np;

  PetscFunctionBeginUser;
  (void)snes;
  (void)J;
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(CondensedState(p, P, w));
  if (p->jvalid)
    for (PetscInt i = 0; i < n && same; i++) same = p->closed[i] == p->jclosed[i];
  if (p->jvalid && same) PetscFunctionReturn(0); /* the same closed set: the same matrix, no new LU */
  PetscCall(MatDenseGetArray(Jp, &ja));
  for (PetscInt j = 0; j < n; j++) {
    const PetscReal f = (p->closed[j] ? 1.0 : p->eps) * p->k[j] - p->k[j];
    for (PetscInt i = 0; i < n; i++) ja[(size_t)j * n + i] = (i == j ? 1.0 : 0.0) + c->G[(size_t)j * n + i] * f;
    p->jclosed[j] = p->closed[j];
  }
  PetscCall(MatDenseRestoreArray(Jp, &ja));
  PetscCall(MatAssemblyBegin(Jp, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Jp, MAT_FINAL_ASSEMBLY));
  p->jvalid = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* K0 factored (every pair closed), yf = B^T K0^-1 f and G = B^T K0^-1 B, on every rank */
static PetscErrorCode Flexibility(JRPreload p, const JRPairs *P)
{
  JRPreload_Condensed *c = (JRPreload_Condensed *)p->data;
  const PetscInt       n = p->np, chunk = 64;
  PC                   pc;
  Vec                  x;
  PetscInt             nloc, N;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) p->closed[i] = 1;
  PetscCall(JRPreloadAssembleJacobian(p, P, p->J));
  PetscCall(KSPCreate(p->comm, &c->ksp0));
  PetscCall(KSPSetOptionsPrefix(c->ksp0, "preload_"));
  PetscCall(KSPSetOperators(c->ksp0, p->J, p->J));
  PetscCall(KSPSetType(c->ksp0, KSPPREONLY));
  PetscCall(KSPGetPC(c->ksp0, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
#if defined(PETSC_HAVE_MUMPS)
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
#endif
  PetscCall(KSPSetFromOptions(c->ksp0));
  PetscCall(JRCheckFactorSolverType(pc, p->J, "preload_"));
  PetscCall(KSPSetUp(c->ksp0));
  p->factorisations++;
  PetscCall(PetscMalloc2((size_t)n * n, &c->G, n, &c->yf));
  PetscCall(VecDuplicate(p->u, &x));
  PetscCall(KSPSolve(c->ksp0, p->f, x));
  PetscCall(PairValues(p, P, x, c->yf));
  PetscCall(VecDestroy(&x));
  PetscCall(VecGetLocalSize(p->u, &nloc));
  PetscCall(VecGetSize(p->u, &N));
  for (PetscInt j0 = 0; j0 < n; j0 += chunk) {
    const PetscInt m = PetscMin(chunk, n - j0);
    Mat            R, X;
    PetscScalar   *ra;
    PetscInt       rs, re;
    PetscCall(MatCreateDense(p->comm, nloc, PETSC_DECIDE, N, m, NULL, &R));
    PetscCall(MatCreateDense(p->comm, nloc, PETSC_DECIDE, N, m, NULL, &X));
    PetscCall(MatGetOwnershipRange(R, &rs, &re));
    PetscCall(MatDenseGetArray(R, &ra)); /* local rows, column-major with leading dimension nloc */
    for (PetscInt k = 0; k < m; k++) {
      const PetscInt j = j0 + k;
      for (int d = 0; d < 3; d++) {
        const PetscInt a = P->dofA[3 * j + d], b = P->dofB[3 * j + d];
        if (a >= rs && a < re) ra[(size_t)k * nloc + a - rs] += P->nrm[3 * j + d];
        if (b >= rs && b < re) ra[(size_t)k * nloc + b - rs] -= P->nrm[3 * j + d];
      }
    }
    PetscCall(MatDenseRestoreArray(R, &ra));
    PetscCall(KSPMatSolve(c->ksp0, R, X));
    for (PetscInt k = 0; k < m; k++) {
      Vec col;
      PetscCall(MatDenseGetColumnVecRead(X, k, &col));
      PetscCall(PairValues(p, P, col, c->G + (size_t)(j0 + k) * n));
      PetscCall(MatDenseRestoreColumnVecRead(X, k, &col));
    }
    PetscCall(MatDestroy(&R));
    PetscCall(MatDestroy(&X));
  }
  for (PetscInt j = 0; j < n; j++) /* symmetrise (round-off) */
    for (PetscInt i = 0; i < j; i++) c->G[(size_t)j * n + i] = c->G[(size_t)i * n + j] = 0.5 * (c->G[(size_t)j * n + i] + c->G[(size_t)i * n + j]);
  PetscFunctionReturn(0);
}

/* The dense SNES on the penetrations (PETSC_COMM_SELF: every rank solves the same small system with the same data, so
   the ranks agree exactly), prefix preload_ */
static PetscErrorCode CreateSNES(JRPreload p)
{
  JRPreload_Condensed *c = (JRPreload_Condensed *)p->data;
  const PetscInt       n = p->np;
  KSP                  ksp;
  PC                   cpc;

  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, &c->cJ));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &c->cw));
  PetscCall(SNESCreate(PETSC_COMM_SELF, &c->csnes));
  PetscCall(SNESSetOptionsPrefix(c->csnes, "preload_"));
  PetscCall(SNESSetFunction(c->csnes, NULL, CondensedFunction, p));
  PetscCall(SNESSetJacobian(c->csnes, c->cJ, c->cJ, CondensedJacobian, p));
  PetscCall(SNESSetTolerances(c->csnes, PETSC_DEFAULT, 1e-12, PETSC_DEFAULT, 100, PETSC_DEFAULT));
  PetscCall(SNESSetDivergenceTolerance(c->csnes, -1.0));
  {
    SNESLineSearch ls;
    PetscCall(SNESGetLineSearch(c->csnes, &ls));
    PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
  }
  PetscCall(SNESGetKSP(c->csnes, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &cpc));
  PetscCall(PCSetType(cpc, PCLU));
  PetscCall(PCFactorSetMatSolverType(cpc, MATSOLVERPETSC));
  PetscCall(SNESSetFromOptions(c->csnes));
  PetscFunctionReturn(0);
}

/* Once: factor K0, compute G and yf, create the dense SNES */
static PetscErrorCode JRPreloadSetUp_Condensed(JRPreload p)
{
  JRPreload_Condensed *c = (JRPreload_Condensed *)p->data;
  const JRPairs       *P;

  PetscFunctionBeginUser;
  if (c->G) PetscFunctionReturn(0);
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(Flexibility(p, P));
  PetscCall(CreateSNES(p));
  PetscFunctionReturn(0);
}

/* The displacement of the condensed solution: K0 u = f - B s(w) */
static PetscErrorCode CondensedDisplacement(JRPreload p, const JRPairs *P)
{
  JRPreload_Condensed *c = (JRPreload_Condensed *)p->data;
  PetscReal           *sv;
  Vec                  r;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(p->np, &sv));
  for (PetscInt j = 0; j < p->np; j++) sv[j] = JRPreloadPairForce(p, j) - p->k[j] * (p->w[j] + P->gap0[j]);
  PetscCall(VecDuplicate(p->f, &r));
  PetscCall(PairLoads(p, P, sv, r));
  PetscCall(VecAYPX(r, -1.0, p->f));
  PetscCall(KSPSolve(c->ksp0, r, p->u));
  PetscCall(VecDestroy(&r));
  PetscCall(PetscFree(sv));
  PetscFunctionReturn(0);
}

/* From w = 0 (every pair touching), or with -preload_open_start w = -open_gap; then the displacement */
static PetscErrorCode JRPreloadSolve_Condensed(JRPreload p)
{
  JRPreload_Condensed *c = (JRPreload_Condensed *)p->data;
  const JRPairs       *P;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(VecSet(c->cw, p->open_start ? -p->open_gap : 0.0));
  PetscCall(JRPreloadAugmentedLagrangian(p, c->csnes, c->cw, CondensedState));
  PetscCall(CondensedDisplacement(p, P));
  PetscFunctionReturn(0);
}

static PetscErrorCode JRPreloadDestroy_Condensed(JRPreload p)
{
  JRPreload_Condensed *c = (JRPreload_Condensed *)p->data;

  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&c->ksp0));
  PetscCall(SNESDestroy(&c->csnes));
  PetscCall(MatDestroy(&c->cJ));
  PetscCall(VecDestroy(&c->cw));
  PetscCall(PetscFree2(c->G, c->yf));
  PetscCall(PetscFree(p->data));
  PetscFunctionReturn(0);
}

PetscErrorCode JRPreloadSolverCreate_Condensed(JRPreload p)
{
  JRPreload_Condensed *c;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  p->data         = c;
  p->what         = "condensed on the interface";
  p->ops->setup   = JRPreloadSetUp_Condensed;
  p->ops->solve   = JRPreloadSolve_Condensed;
  p->ops->destroy = JRPreloadDestroy_Condensed;
  PetscFunctionReturn(0);
}
