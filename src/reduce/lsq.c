/*
   The least-squares solvers of the second reduction's fit (src/reduce/fit.c): bounded nonlinear least squares by TAO
   (prefix rom_, Gauss-Newton Hessian), and non-negative least squares on a Gram system, by every support (m <= 8) or
   by the Lawson-Hanson active set. All on PETSC_COMM_SELF and deterministic: every rank computes the same fit.
*/
#include <jointrom/private/reduceimpl.h>
#include <petsctao.h>
#include <petscblaslapack.h>

static PetscErrorCode LSQObjective(Tao tao, Vec X, PetscReal *obj, Vec G, void *ctx)
{
  JRLSQ             *q = (JRLSQ *)ctx;
  const PetscScalar *x;
  PetscScalar       *g;

  PetscFunctionBeginUser;
  (void)tao;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(q->fn(q->ctx, x, q->r, q->J));
  PetscCall(VecRestoreArrayRead(X, &x));
  *obj = 0;
  for (PetscInt i = 0; i < q->nr; i++) *obj += 0.5 * q->r[i] * q->r[i];
  PetscCall(VecGetArray(G, &g));
  for (PetscInt j = 0; j < q->nx; j++) {
    PetscReal s = 0;
    for (PetscInt i = 0; i < q->nr; i++) s += q->J[i + j * q->nr] * q->r[i];
    g[j] = s;
  }
  PetscCall(VecRestoreArray(G, &g));
  PetscFunctionReturn(0);
}

/* Gauss-Newton Hessian J^T J (J from the last objective evaluation at this X), with a 1e-10 relative shift */
static PetscErrorCode LSQHessian(Tao tao, Vec X, Mat Hm, Mat Pm, void *ctx)
{
  JRLSQ       *q = (JRLSQ *)ctx;
  PetscScalar *a;
  PetscReal    tr = 0;

  PetscFunctionBeginUser;
  (void)tao;
  (void)Pm;
  {
    const PetscScalar *x;
    PetscCall(VecGetArrayRead(X, &x));
    PetscCall(q->fn(q->ctx, x, q->r, q->J));
    PetscCall(VecRestoreArrayRead(X, &x));
  }
  PetscCall(MatDenseGetArray(Hm, &a));
  for (PetscInt j = 0; j < q->nx; j++)
    for (PetscInt i = 0; i < q->nx; i++) {
      PetscReal v = 0;
      for (PetscInt k = 0; k < q->nr; k++) v += q->J[k + i * q->nr] * q->J[k + j * q->nr];
      a[i + j * q->nx] = v;
      if (i == j) tr += v;
    }
  for (PetscInt i = 0; i < q->nx; i++) a[i + i * q->nx] += 1e-10 * tr / q->nx;
  PetscCall(MatDenseRestoreArray(Hm, &a));
  PetscCall(MatAssemblyBegin(Hm, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Hm, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* TAO's gradient test, and a stall: the objective lowered by less than 1e-12 of itself over the last 5 iterations.
   A fit whose objective is at its round-off floor (refitted from its own solution, or the gradient not computable to
   the tolerance) would otherwise take steps along the directions the loops do not see until the iteration limit:
   up to 2,000 iterations that lower nothing. */
static PetscErrorCode LSQConverged(Tao tao, void *ctx)
{
  JRLSQ             *q = (JRLSQ *)ctx;
  PetscInt           it;
  PetscReal          f;
  TaoConvergedReason reason;

  PetscFunctionBeginUser;
  PetscCall(TaoDefaultConvergenceTest(tao, NULL));
  PetscCall(TaoGetSolutionStatus(tao, &it, &f, NULL, NULL, NULL, &reason));
  if (reason != TAO_CONTINUE_ITERATING) PetscFunctionReturn(0);
  if (f < q->fkeep * (1 - 1e-12)) {
    q->fkeep = f;
    q->kkeep = it;
  } else if (it - q->kkeep >= 5) PetscCall(TaoSetConvergedReason(tao, TAO_CONVERGED_USER));
  PetscFunctionReturn(0);
}

/* rms: sqrt(|r|^2) before (rms0) and after; x updated */
PetscErrorCode JRLSQSolve(JRLSQ *q, PetscReal x[], PetscReal lo, PetscReal *rms0, PetscReal *rms, PetscInt *its)
{
  Tao                tao;
  Vec                X, L, U;
  Mat                Hm;
  PetscScalar       *xa;
  TaoConvergedReason reason;
  PetscReal          jnorm = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(q->nr, &q->r, q->nr * q->nx, &q->J));
  PetscCall(q->fn(q->ctx, x, q->r, q->J));
  *rms0 = 0;
  for (PetscInt i = 0; i < q->nr; i++) *rms0 += q->r[i] * q->r[i];
  *rms0 = PetscSqrtReal(*rms0);
  for (PetscInt i = 0; i < q->nr * q->nx; i++) jnorm += q->J[i] * q->J[i];
  jnorm = PetscSqrtReal(jnorm);
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, q->nx, &X));
  PetscCall(VecDuplicate(X, &L));
  PetscCall(VecDuplicate(X, &U));
  PetscCall(VecSet(L, lo));
  PetscCall(VecSet(U, PETSC_INFINITY));
  PetscCall(VecGetArray(X, &xa));
  for (PetscInt j = 0; j < q->nx; j++) xa[j] = x[j];
  PetscCall(VecRestoreArray(X, &xa));
  PetscCall(TaoCreate(PETSC_COMM_SELF, &tao));
  PetscCall(TaoSetOptionsPrefix(tao, "rom_"));
  PetscCall(TaoSetType(tao, TAOBNLS)); /* bounded Newton line search on the Gauss-Newton Hessian */
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, q->nx, q->nx, NULL, &Hm));
  PetscCall(TaoSetHessian(tao, Hm, Hm, LSQHessian, q));
  PetscCall(TaoSetSolution(tao, X));
  PetscCall(TaoSetVariableBounds(tao, L, U));
  PetscCall(TaoSetObjectiveAndGradient(tao, NULL, LSQObjective, q));
  /* to round-off (the fit must not depend on the ranks): the gradient J^T r down to 1e-13 of |J| |r| at the start */
  PetscCall(TaoSetTolerances(tao, 1e-13 * jnorm * PetscMax(*rms0, 1e-13), 0, 0));
  PetscCall(TaoSetMaximumIterations(tao, 2000));
  PetscCall(TaoSetFunctionLowerBound(tao, 1e-26)); /* an exact fit stops there */
  PetscCall(TaoSetMaximumFunctionEvaluations(tao, 20000));
  q->fkeep = PETSC_MAX_REAL;
  q->kkeep = 0;
  PetscCall(TaoSetConvergenceTest(tao, LSQConverged, q));
  PetscCall(TaoSetFromOptions(tao));
  PetscCall(TaoSolve(tao));
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCall(TaoGetIterationNumber(tao, its));
  PetscCheck(reason > 0 || reason == TAO_DIVERGED_MAXITS || reason == TAO_DIVERGED_LS_FAILURE || reason == TAO_DIVERGED_MAXFCN || reason == TAO_DIVERGED_TR_REDUCTION, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "The joint fit (TAO, prefix rom_) failed: %s; try -rom_tao_type or -rom_tao_max_it", TaoConvergedReasons[reason]);
  PetscCall(VecGetArray(X, &xa));
  for (PetscInt j = 0; j < q->nx; j++) x[j] = PetscRealPart(xa[j]);
  PetscCall(VecRestoreArray(X, &xa));
  PetscCall(q->fn(q->ctx, x, q->r, q->J));
  *rms = 0;
  for (PetscInt i = 0; i < q->nr; i++) *rms += q->r[i] * q->r[i];
  *rms = PetscSqrtReal(*rms);
  PetscCall(TaoDestroy(&tao));
  PetscCall(MatDestroy(&Hm));
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&L));
  PetscCall(VecDestroy(&U));
  PetscCall(PetscFree2(q->r, q->J));
  PetscFunctionReturn(0);
}

/* The least squares on a support: A[idx, idx] z = c[idx] (A n x n column-major, k indices; B k x k scratch). info:
   LAPACK's (> 0: singular) */
static PetscErrorCode SupportSolve(PetscInt n, const PetscReal A[], const PetscReal c[], PetscInt k, const PetscInt idx[], PetscReal B[], PetscReal z[], PetscBLASInt piv[], PetscBLASInt *info)
{
  PetscBLASInt nb, one = 1;

  PetscFunctionBeginUser;
  *info = 0;
  for (PetscInt a = 0; a < k; a++) {
    for (PetscInt b = 0; b < k; b++) B[a + b * k] = A[idx[a] + idx[b] * n];
    z[a] = c[idx[a]];
  }
  PetscCall(PetscBLASIntCast(k, &nb));
  if (k) PetscCallBLAS("LAPACKgesv", LAPACKgesv_(&nb, &one, B, &nb, piv, z, &nb, info));
  PetscFunctionReturn(0);
}

/* NNLS of the columns sel[0..m) of the Gram system (G, c, bb: C^T C, C^T b, b.b of the residual C y - b): every
   support tried, the best non-negative least-squares solution (the NNLS minimum: m <= 8). cost: |C y - b|^2 */
PetscErrorCode JRGramNNLS(PetscInt nc, const PetscReal G[], const PetscReal c[], PetscReal bb, PetscInt m, const PetscInt sel[], PetscReal y[], PetscReal *cost)
{
  PetscReal    A[64], z[8];
  PetscInt     idx[8], pos[8];
  PetscBLASInt piv[8], info;

  PetscFunctionBeginUser;
  *cost = bb;
  for (PetscInt i = 0; i < m; i++) y[i] = 0;
  for (PetscInt S = 1; S < (1 << m); S++) {
    PetscInt  k = 0, ok = 1;
    PetscReal v = bb;
    for (PetscInt i = 0; i < m; i++)
      if (S & (1 << i)) {
        pos[k]   = i;
        idx[k++] = sel[i];
      }
    PetscCall(SupportSolve(nc, G, c, k, idx, A, z, piv, &info));
    if (info) continue; /* singular: a smaller support covers it */
    for (PetscInt a = 0; a < k; a++) {
      ok = ok && z[a] > 0;
      v -= z[a] * c[idx[a]];
    }
    if (ok && v < *cost) {
      *cost = v;
      for (PetscInt i = 0; i < m; i++) y[i] = 0;
      for (PetscInt a = 0; a < k; a++) y[pos[a]] = z[a];
    }
  }
  PetscFunctionReturn(0);
}

/* The Gram system of the columns C (ld rows, nc columns, column-major) against b: G = C^T C (nc x nc), cg = C^T b */
void JRGram(PetscInt ld, PetscInt nc, const PetscReal C[], const PetscReal b[], PetscReal G[], PetscReal cg[])
{
  for (PetscInt i = 0; i < nc; i++) {
    cg[i] = 0;
    for (PetscInt q = 0; q < ld; q++) cg[i] += C[q + i * ld] * b[q];
    for (PetscInt k = 0; k <= i; k++) {
      PetscReal v = 0;
      for (PetscInt q = 0; q < ld; q++) v += C[q + i * ld] * C[q + k * ld];
      G[i + k * nc] = G[k + i * nc] = v;
    }
  }
}

/* min y^T A y - 2 c^T y over y >= 0 (A n x n, symmetric positive semi-definite): the Lawson-Hanson active set on
   the Gram system, deterministic, warm-started from the support of y on entry if the least squares there is
   positive. val: that minimum */
PetscErrorCode JRActiveSetNNLS(PetscInt n, const PetscReal A[], const PetscReal c[], PetscReal y[], PetscReal *val)
{
  PetscBool   *P, *skip;
  PetscReal   *z, *B, *w, cmax = 0;
  PetscInt    *idx;
  PetscBLASInt *piv, info = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc7(n, &P, n, &skip, n, &z, n * n, &B, n, &w, n, &idx, n, &piv));
  for (PetscInt i = 0; i < n; i++) {
    P[i]    = (PetscBool)(y[i] > 0);
    skip[i] = PETSC_FALSE;
    cmax    = PetscMax(cmax, PetscAbsReal(c[i]));
  }
  { /* the warm start: the least squares on the entry support, if it is positive */
    PetscInt  k   = 0;
    PetscBool pos = PETSC_TRUE;
    for (PetscInt i = 0; i < n; i++)
      if (P[i]) idx[k++] = i;
    PetscCall(SupportSolve(n, A, c, k, idx, B, z, piv, &info));
    for (PetscInt a = 0; a < k; a++) pos = (PetscBool)(pos && !info && z[a] > 0);
    for (PetscInt i = 0; i < n; i++) y[i] = 0;
    if (k && pos)
      for (PetscInt a = 0; a < k; a++) y[idx[a]] = z[a];
    else
      for (PetscInt i = 0; i < n; i++) P[i] = PETSC_FALSE;
  }
  for (PetscInt outer = 0; outer < 3 * n; outer++) {
    PetscInt  t  = -1;
    PetscReal wt = 1e-12 * cmax;
    for (PetscInt i = 0; i < n; i++) { /* the gradient's descent directions off the support */
      w[i] = c[i];
      for (PetscInt k = 0; k < n; k++) w[i] -= A[i + k * n] * y[k];
      if (!P[i] && !skip[i] && w[i] > wt) {
        wt = w[i];
        t  = i;
      }
    }
    if (t < 0) break;
    P[t] = PETSC_TRUE;
    for (PetscInt inner = 0; inner < 3 * n; inner++) {
      PetscInt  k = 0, hit = -1;
      PetscBool pos = PETSC_TRUE;
      PetscReal alpha = 1;
      for (PetscInt i = 0; i < n; i++)
        if (P[i]) idx[k++] = i;
      PetscCall(SupportSolve(n, A, c, k, idx, B, z, piv, &info));
      if (info) { /* t's column depends on the support's: left out */
        P[t] = PETSC_FALSE;
        skip[t] = PETSC_TRUE;
        break;
      }
      for (PetscInt a = 0; a < k; a++) pos = (PetscBool)(pos && z[a] > 0);
      if (pos) {
        for (PetscInt i = 0; i < n; i++) y[i] = 0;
        for (PetscInt a = 0; a < k; a++) y[idx[a]] = z[a];
        break;
      }
      for (PetscInt a = 0; a < k; a++) /* the step toward z stops where the first force reaches 0 */
        if (z[a] <= 0 && y[idx[a]] / (y[idx[a]] - z[a]) < alpha) {
          alpha = y[idx[a]] / (y[idx[a]] - z[a]);
          hit   = idx[a];
        }
      for (PetscInt a = 0; a < k; a++) {
        const PetscInt i = idx[a];
        y[i] += alpha * (z[a] - y[i]);
        if (i == hit || y[i] <= 0) {
          y[i] = 0;
          P[i] = PETSC_FALSE;
        }
      }
    }
  }
  *val = 0;
  for (PetscInt i = 0; i < n; i++) {
    PetscReal v = -2 * c[i];
    for (PetscInt k = 0; k < n; k++) v += A[i + k * n] * y[k];
    *val += v * y[i];
  }
  PetscCall(PetscFree7(P, skip, z, B, w, idx, piv));
  PetscFunctionReturn(0);
}
