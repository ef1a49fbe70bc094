/*
   SNESNEWTONDENSE, the default Newton of the harmonic-balance and continuation solves, against known roots:
   1. a cubic system with a chosen root x* (F = x^3 + A x - b, b from x*): converges to x* from 0 to round-off,
      in the same number of iterations as PETSc's newtonls + LU (the same Newton steps), to the same point;
   2. F_i = atan(x_i - c_i) from 3 away: undamped Newton diverges there (|x - c| grows at every step beyond
      1.39), the backtracking line search brings it to c;
   3. tolerances 0 (-snes_atol 0 -snes_rtol 0): the solve stops at round-off as converged, not as a failed
      line search;
   4. F = x^2 + 1 from 0 (singular Jacobian, no real root): DIVERGED_LINEAR_SOLVE, not an error;
   5. the LU kept as GMRES's preconditioner (JRDenseLU): on a random well-conditioned 160 x 160 matrix and its
      changes, every solution's residual, computed here, within the tolerance asked; a rank-1 change solved in at
      most 2 GMRES iterations (A M^-1 = I + u (M^-T v)^T has a minimal polynomial of degree 2) without a new LU;
      an unrelated matrix gets a new LU;
   6. the cubic system with 96 unknowns: the same root and the same number of iterations with the LU kept as
      with a new LU at every iteration (-snes_newtondense_reuse_its 0), and fewer LU than iterations;
   7. unit columns (a condensed model's joints whose elements are all apart, with a bordered row): a 160 x 160
      random matrix with 48 of its columns e_j but for a random last row; the solution's residual, computed here,
      within 1e-13, from a factored matrix of 112 (the unit columns eliminated); a rank-1 change of a kept column
      solved by GMRES on those factors in at most 2 iterations; those columns' 1 made 1.5: an LU of all 160, exact;
   8. the dense products (JRGemm; its loops for one or two columns, BLAS beyond) against a triple loop in long double:
      op(A) = A and A^T, 1-6 columns, beta 0 (C's NaN ignored, as BLAS does), 1 and -0.5, strided operands.
*/
#include "jrtest.h"

PETSC_INTERN PetscErrorCode JRGemm(const char *, const char *, PetscInt, PetscInt, PetscInt, PetscReal, const PetscReal *, PetscInt, const PetscReal *, PetscInt, PetscReal, PetscReal *, PetscInt);

typedef struct {
  PetscInt  kind, n;
  PetscReal A[96 * 96], b[96], c[96];
} Prob;

static PetscErrorCode Func(SNES snes, Vec X, Vec F, void *ctx)
{
  Prob              *p = (Prob *)ctx;
  const PetscScalar *x;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  (void)snes;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(F, &f));
  for (PetscInt i = 0; i < p->n; i++) {
    if (p->kind == 1) {
      f[i] = x[i] * x[i] * x[i] - p->b[i];
      for (PetscInt j = 0; j < p->n; j++) f[i] += p->A[i + j * p->n] * x[j];
    } else if (p->kind == 2) f[i] = PetscAtanReal(x[i] - p->c[i]);
    else f[i] = x[i] * x[i] + 1.0;
  }
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

static PetscErrorCode Jac(SNES snes, Vec X, Mat J, Mat P, void *ctx)
{
  Prob              *p = (Prob *)ctx;
  const PetscScalar *x;
  PetscScalar       *j;

  PetscFunctionBeginUser;
  (void)snes;
  (void)P;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(MatDenseGetArrayWrite(J, &j));
  for (PetscInt c = 0; c < p->n; c++)
    for (PetscInt r = 0; r < p->n; r++) {
      PetscReal v = 0.0;
      if (p->kind == 1) v = p->A[r + c * p->n] + (r == c ? 3.0 * x[r] * x[r] : 0.0);
      else if (r == c) v = p->kind == 2 ? 1.0 / (1.0 + (x[r] - p->c[r]) * (x[r] - p->c[r])) : 2.0 * x[r];
      j[r + c * p->n] = v;
    }
  PetscCall(MatDenseRestoreArrayWrite(J, &j));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(JRMatDenseAssemble(J));
  PetscFunctionReturn(0);
}

/* solve from x0 (n values) with the given type and options prefix; x (n), iterations, reason; nlu (may be NULL): the
   LU factorisations of a newtondense solve */
static PetscErrorCode SolveLU(Prob *p, const char *type, const char *prefix, const PetscReal *x0, PetscReal *xout, PetscInt *its, SNESConvergedReason *reason, PetscInt *nlu)
{
  SNES               snes;
  Vec                x, r;
  Mat                J;
  KSP                ksp;
  PC                 pc;
  const PetscScalar *xa;

  PetscFunctionBeginUser;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, p->n, &x));
  PetscCall(VecDuplicate(x, &r));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, p->n, p->n, NULL, &J));
  PetscCall(SNESCreate(PETSC_COMM_SELF, &snes));
  PetscCall(SNESSetOptionsPrefix(snes, prefix));
  PetscCall(SNESSetFunction(snes, r, Func, p));
  PetscCall(SNESSetJacobian(snes, J, J, Jac, p));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(SNESSetTolerances(snes, 1e-14, 1e-12, 1e-14, 60, 10000));
  PetscCall(SNESSetType(snes, type));
  PetscCall(SNESSetFromOptions(snes));
  for (PetscInt i = 0; i < p->n; i++) PetscCall(VecSetValue(x, i, x0[i], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(x));
  PetscCall(VecAssemblyEnd(x));
  PetscCall(SNESSolve(snes, NULL, x));
  PetscCall(SNESGetIterationNumber(snes, its));
  PetscCall(SNESGetConvergedReason(snes, reason));
  PetscCall(VecGetArrayRead(x, &xa));
  for (PetscInt i = 0; i < p->n; i++) xout[i] = xa[i];
  PetscCall(VecRestoreArrayRead(x, &xa));
  if (nlu) {
    JRDenseLU lu;
    PetscCall(SNESNewtonDenseGetDenseLU(snes, &lu));
    *nlu = -1;
    if (lu) PetscCall(JRDenseLUGetCounts(lu, nlu, NULL, NULL));
  }
  PetscCall(SNESDestroy(&snes));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

static PetscErrorCode Solve(Prob *p, const char *type, const char *prefix, const PetscReal *x0, PetscReal *xout, PetscInt *its, SNESConvergedReason *reason)
{
  PetscFunctionBeginUser;
  PetscCall(SolveLU(p, type, prefix, x0, xout, its, reason, NULL));
  PetscFunctionReturn(0);
}

/* ||b - A x|| / ||b|| for a dense n x n A (column-major) */
static PetscReal Residual(PetscInt n, const PetscReal *A, const PetscReal *x, const PetscReal *b)
{
  PetscReal r2 = 0, b2 = 0;
  for (PetscInt i = 0; i < n; i++) {
    PetscReal v = b[i];
    for (PetscInt j = 0; j < n; j++) v -= A[i + j * n] * x[j];
    r2 += v * v;
    b2 += b[i] * b[i];
  }
  return PetscSqrtReal(r2 / b2);
}

/* 5. JRDenseLU on a sequence of matrices */
static PetscErrorCode DenseLUChecks(void)
{
  const PetscInt n = 160;
  PetscReal     *A, *B, *b, *x, *u, *v;
  PetscRandom    rnd;
  JRDenseLU      d;
  PetscBool      singular;
  PetscInt       f0, f1, s1, i0, i1;
  PetscReal      res;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc6(n * n, &A, n * n, &B, n, &b, n, &x, n, &u, n, &v));
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -1.0, 1.0));
  PetscCall(PetscRandomSetSeed(rnd, 7));
  PetscCall(PetscRandomSeed(rnd));
  for (PetscInt i = 0; i < n * n; i++) PetscCall(PetscRandomGetValueReal(rnd, &A[i]));
  for (PetscInt i = 0; i < n; i++) {
    A[i + i * n] += 2.0 * PetscSqrtReal((PetscReal)n); /* well conditioned */
    PetscCall(PetscRandomGetValueReal(rnd, &b[i]));
    PetscCall(PetscRandomGetValueReal(rnd, &u[i]));
    PetscCall(PetscRandomGetValueReal(rnd, &v[i]));
  }
  PetscCall(JRDenseLUCreate(&d));
  PetscCall(PetscArraycpy(x, b, n));
  PetscCall(JRDenseLUSolve(d, n, A, n, 0, x, &singular));
  res = Residual(n, A, x, b);
  PetscCall(JRDenseLUGetCounts(d, &f0, NULL, &i0));
  CHECK(!singular && f0 == 1 && res < 1e-13, "JRDenseLU: the first solve is an LU (%d), residual %.1e", (int)f0, (double)res);
  /* a rank-1 change: at most 2 GMRES iterations, no new LU */
  for (PetscInt j = 0; j < n; j++)
    for (PetscInt i = 0; i < n; i++) B[i + j * n] = A[i + j * n] + 0.5 * u[i] * v[j];
  PetscCall(PetscArraycpy(x, b, n));
  PetscCall(JRDenseLUSolve(d, n, B, n, 0, x, &singular));
  res = Residual(n, B, x, b);
  PetscCall(JRDenseLUGetCounts(d, &f1, &s1, &i1));
  CHECK(!singular && f1 == 1 && i1 - i0 <= 2 && res < 1e-12, "JRDenseLU: a rank-1 change solved by GMRES on the kept LU in %d iterations (<= 2), residual %.1e (< 1e-12), no new LU (%d in all)", (int)(i1 - i0), (double)res, (int)f1);
  /* a small dense change, to a loose tolerance: the residual within it */
  for (PetscInt i = 0; i < n * n; i++) {
    PetscReal e;
    PetscCall(PetscRandomGetValueReal(rnd, &e));
    B[i] = A[i] * (1.0 + 1e-3 * e);
  }
  PetscCall(PetscArraycpy(x, b, n));
  PetscCall(JRDenseLUSolve(d, n, B, n, 1e-6, x, &singular));
  res = Residual(n, B, x, b);
  PetscCall(JRDenseLUGetCounts(d, &f1, NULL, &i0));
  CHECK(!singular && f1 == 1 && res < 1e-6, "JRDenseLU: a 1e-3 change of every entry to 1e-6: residual %.1e in %d GMRES iterations, no new LU", (double)res, (int)(i0 - i1));
  /* an unrelated matrix: a new LU, exact */
  for (PetscInt i = 0; i < n * n; i++) PetscCall(PetscRandomGetValueReal(rnd, &B[i]));
  for (PetscInt i = 0; i < n; i++) B[i + i * n] += 2.0 * PetscSqrtReal((PetscReal)n);
  PetscCall(PetscArraycpy(x, b, n));
  PetscCall(JRDenseLUSolve(d, n, B, n, 0, x, &singular));
  res = Residual(n, B, x, b);
  PetscCall(JRDenseLUGetCounts(d, &f1, NULL, NULL));
  CHECK(!singular && f1 == 2 && res < 1e-13, "JRDenseLU: an unrelated matrix gets a new LU (%d in all), residual %.1e", (int)f1, (double)res);
  PetscCall(JRDenseLUDestroy(&d));
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(PetscFree6(A, B, b, x, u, v));
  PetscFunctionReturn(0);
}

/* 7. JRDenseLU with unit columns */
static PetscErrorCode UnitColumnChecks(void)
{
  const PetscInt n = 160, nu = 48;
  PetscReal     *A, *B, *b, *x, *u;
  PetscRandom    rnd;
  JRDenseLU      d;
  PetscBool      singular;
  PetscInt       f0, f1, i0, i1, np;
  PetscReal      res;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc5(n * n, &A, n * n, &B, n, &b, n, &x, n, &u));
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -1.0, 1.0));
  PetscCall(PetscRandomSetSeed(rnd, 11));
  PetscCall(PetscRandomSeed(rnd));
  for (PetscInt i = 0; i < n * n; i++) PetscCall(PetscRandomGetValueReal(rnd, &A[i]));
  for (PetscInt i = 0; i < n; i++) {
    A[i + i * n] += 2.0 * PetscSqrtReal((PetscReal)n);
    PetscCall(PetscRandomGetValueReal(rnd, &b[i]));
    PetscCall(PetscRandomGetValueReal(rnd, &u[i]));
  }
  for (PetscInt k = 0; k < nu; k++) { /* every third column from 1: e_j but for the last row */
    const PetscInt j = 1 + 3 * k;
    for (PetscInt i = 0; i < n - 1; i++) A[i + j * n] = i == j ? 1.0 : 0.0;
  }
  PetscCall(JRDenseLUCreate(&d));
  PetscCall(PetscArraycpy(x, b, n));
  PetscCall(JRDenseLUSolve(d, n, A, n, 0, x, &singular));
  res = Residual(n, A, x, b);
  PetscCall(JRDenseLUGetCounts(d, &f0, NULL, &i0));
  PetscCall(JRDenseLUGetFactoredSize(d, &np));
  CHECK(!singular && f0 == 1 && np == n - nu && res < 1e-13, "JRDenseLU, unit columns: an LU of %d (the %d unit columns eliminated from %d), residual %.1e", (int)np, (int)nu, (int)n, (double)res);
  /* a rank-1 change of a kept column (0): GMRES on the factors */
  PetscCall(PetscArraycpy(B, A, n * n));
  for (PetscInt i = 0; i < n; i++) B[i] += 0.5 * u[i];
  PetscCall(PetscArraycpy(x, b, n));
  PetscCall(JRDenseLUSolve(d, n, B, n, 0, x, &singular));
  res = Residual(n, B, x, b);
  PetscCall(JRDenseLUGetCounts(d, &f1, NULL, &i1));
  CHECK(!singular && f1 == 1 && i1 - i0 <= 2 && res < 1e-12, "JRDenseLU, unit columns: a rank-1 change solved by GMRES on those factors in %d iterations (<= 2), residual %.1e (< 1e-12), no new LU", (int)(i1 - i0), (double)res);
  /* no longer unit: every column kept, exact */
  PetscCall(JRDenseLUForget(d));
  for (PetscInt k = 0; k < nu; k++) A[(1 + 3 * k) * (n + 1)] = 1.5;
  PetscCall(PetscArraycpy(x, b, n));
  PetscCall(JRDenseLUSolve(d, n, A, n, 0, x, &singular));
  res = Residual(n, A, x, b);
  PetscCall(JRDenseLUGetFactoredSize(d, &np));
  CHECK(!singular && np == n && res < 1e-13, "JRDenseLU: the same columns with 1.5 on the diagonal: an LU of all %d, residual %.1e", (int)np, (double)res);
  PetscCall(JRDenseLUDestroy(&d));
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(PetscFree5(A, B, b, x, u));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  Prob                p;
  PetscReal           xs[19], x0[19], x1[19], x2[19];
  PetscInt            it1, it2;
  SNESConvergedReason r1, r2;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(JRInitializePackage());
  /* 1. cubic system, root x* chosen; A diagonally dominant, non-symmetric */
  p.kind = 1;
  p.n    = 19;
  for (PetscInt i = 0; i < p.n; i++) {
    xs[i] = 0.5 + 0.1 * i * PetscPowRealInt(-1.0, i);
    x0[i] = 0.0;
    for (PetscInt j = 0; j < p.n; j++) p.A[i + j * p.n] = i == j ? 4.0 : 0.3 / (1.0 + i + 2.0 * j);
  }
  for (PetscInt i = 0; i < p.n; i++) {
    p.b[i] = xs[i] * xs[i] * xs[i];
    for (PetscInt j = 0; j < p.n; j++) p.b[i] += p.A[i + j * p.n] * xs[j];
  }
  PetscCall(Solve(&p, SNESNEWTONDENSE, "a_", x0, x1, &it1, &r1));
  PetscCall(Solve(&p, SNESNEWTONLS, "b_", x0, x2, &it2, &r2));
  CHECK(r1 > 0 && RelDiff(19, x1, xs, MaxAbs(19, xs)) < 1e-13, "cubic system (19 unknowns): newtondense converges to the chosen root, error %.1e (%s, %d iterations)", RelDiff(19, x1, xs, MaxAbs(19, xs)), SNESConvergedReasons[r1], (int)it1);
  CHECK(r2 > 0 && it1 == it2 && RelDiff(19, x1, x2, MaxAbs(19, xs)) < 1e-14, "the same Newton steps as newtonls + LU: %d and %d iterations, solutions %.1e apart", (int)it1, (int)it2, RelDiff(19, x1, x2, MaxAbs(19, xs)));
  /* 3. the same with tolerances 0: ends at round-off, converged */
  PetscCall(PetscOptionsSetValue(NULL, "-c_snes_atol", "0"));
  PetscCall(PetscOptionsSetValue(NULL, "-c_snes_rtol", "0"));
  PetscCall(Solve(&p, SNESNEWTONDENSE, "c_", x0, x1, &it1, &r1));
  CHECK(r1 > 0 && RelDiff(19, x1, xs, MaxAbs(19, xs)) < 1e-14, "tolerances 0: stops at round-off as converged (%s after %d iterations), error %.1e", SNESConvergedReasons[r1], (int)it1, RelDiff(19, x1, xs, MaxAbs(19, xs)));
  /* 2. atan from 3 away: plain Newton diverges, the line search converges */
  p.kind = 2;
  p.n    = 3;
  for (PetscInt i = 0; i < p.n; i++) {
    p.c[i] = 0.2 * i - 0.1;
    x0[i]  = p.c[i] + (i % 2 ? -3.0 : 3.0);
  }
  {
    PetscReal e = 3.0; /* the undamped Newton map of atan: e <- e - (1 + e^2) atan(e) */
    for (int k = 0; k < 3; k++) e = e - (1 + e * e) * PetscAtanReal(e);
    PetscCall(Solve(&p, SNESNEWTONDENSE, "d_", x0, x1, &it1, &r1));
    CHECK(PetscAbsReal(e) > 1e3 && r1 > 0 && RelDiff(3, x1, p.c, 1.0) < 1e-14, "atan(x - c) from 3 away: undamped Newton diverges (|x - c| = %.1e after 3 steps), newtondense reaches c to %.1e (%s, %d iterations)", (double)PetscAbsReal(e), RelDiff(3, x1, p.c, 1.0), SNESConvergedReasons[r1], (int)it1);
  }
  /* 4. x^2 + 1 from 0: singular Jacobian */
  p.kind = 3;
  p.n    = 2;
  x0[0] = x0[1] = 0.0;
  PetscCall(Solve(&p, SNESNEWTONDENSE, "e_", x0, x1, &it1, &r1));
  CHECK(r1 == SNES_DIVERGED_LINEAR_SOLVE, "x^2 + 1 from 0 (zero Jacobian): %s", SNESConvergedReasons[r1]);
  PetscCall(DenseLUChecks());
  PetscCall(UnitColumnChecks());
  /* 6. the cubic system with 96 unknowns: the LU kept against a new one at every iteration */
  p.kind = 1;
  p.n    = 96;
  {
    PetscReal *ys, *y0, *y1, *y2;
    PetscInt   l1, l2;
    PetscCall(PetscMalloc4(p.n, &ys, p.n, &y0, p.n, &y1, p.n, &y2));
    for (PetscInt i = 0; i < p.n; i++) {
      ys[i] = 0.5 + 0.1 * (i % 19) * PetscPowRealInt(-1.0, i);
      y0[i] = 0.0;
      for (PetscInt j = 0; j < p.n; j++) p.A[i + j * p.n] = i == j ? 4.0 : 0.3 / (1.0 + i + 2.0 * j);
    }
    for (PetscInt i = 0; i < p.n; i++) {
      p.b[i] = ys[i] * ys[i] * ys[i];
      for (PetscInt j = 0; j < p.n; j++) p.b[i] += p.A[i + j * p.n] * ys[j];
    }
    PetscCall(PetscOptionsSetValue(NULL, "-g_snes_newtondense_reuse_its", "0"));
    PetscCall(SolveLU(&p, SNESNEWTONDENSE, "f_", y0, y1, &it1, &r1, &l1));
    PetscCall(SolveLU(&p, SNESNEWTONDENSE, "g_", y0, y2, &it2, &r2, &l2));
    CHECK(r1 > 0 && r2 > 0 && it1 == it2 && RelDiff(p.n, y1, ys, MaxAbs(p.n, ys)) < 1e-13 && RelDiff(p.n, y2, ys, MaxAbs(p.n, ys)) < 1e-13, "cubic system (96 unknowns): the LU kept and a new LU each iteration reach the root (errors %.1e, %.1e) in the same %d and %d iterations", RelDiff(p.n, y1, ys, MaxAbs(p.n, ys)), RelDiff(p.n, y2, ys, MaxAbs(p.n, ys)), (int)it1, (int)it2);
    CHECK(l2 == it2 && l1 < l2, "cubic system (96 unknowns): %d LU with the LU kept, %d with a new one each iteration", (int)l1, (int)l2);
    PetscCall(PetscFree4(ys, y0, y1, y2));
  }
  { /* 8. JRGemm against a triple loop */
    const PetscInt ms[3] = {1, 7, 138}, ks[3] = {1, 5, 84};
    const PetscReal betas[3] = {0.0, 1.0, -0.5};
    PetscReal      err = 0, *A, *B, *C, *R;
    PetscInt       ncase = 0;
    PetscCall(PetscMalloc4(141 * 141, &A, 141 * 8, &B, 141 * 8, &C, 141 * 8, &R));
    for (PetscInt i = 0; i < 141 * 141; i++) A[i] = PetscSinReal(0.37 * i + 0.1) + 0.01 * (i % 7);
    for (PetscInt i = 0; i < 141 * 8; i++) B[i] = PetscCosReal(0.53 * i + 0.2);
    for (PetscInt im = 0; im < 3; im++)
      for (PetscInt ik = 0; ik < 3; ik++)
        for (PetscInt n = 1; n <= 6; n++)
          for (PetscInt at = 0; at < 2; at++)
            for (PetscInt ib = 0; ib < 3; ib++) {
              const PetscInt  m = ms[im], k = ks[ik], lda = (at ? k : m) + 3, ldb = k + 1, ldc = m + 2;
              const PetscReal alpha = ib == 1 ? -2.0 : 1.5, beta = betas[ib];
              for (PetscInt j = 0; j < n; j++)
                for (PetscInt i = 0; i < m; i++) {
                  long double t = 0;
                  for (PetscInt q = 0; q < k; q++) t += (long double)(at ? A[q + i * lda] : A[i + q * lda]) * B[q + j * ldb];
                  C[i + j * ldc] = beta == 0.0 ? NAN : PetscSinReal(1.0 + i + 3.0 * j);
                  R[i + j * ldc] = (PetscReal)(alpha * t + (beta == 0.0 ? 0.0L : (long double)beta * C[i + j * ldc]));
                }
              PetscCall(JRGemm(at ? "T" : "N", "N", m, n, k, alpha, A, lda, B, ldb, beta, C, ldc));
              for (PetscInt j = 0; j < n; j++)
                for (PetscInt i = 0; i < m; i++) err = PetscIsNanReal(C[i + j * ldc]) ? PETSC_INFINITY : PetscMax(err, PetscAbsReal(C[i + j * ldc] - R[i + j * ldc]) / (1.0 + PetscAbsReal(R[i + j * ldc])));
              ncase++;
            }
    PetscCall(PetscFree4(A, B, C, R));
    CHECK(err < 1e-13, "dense products (JRGemm: loops for 1-2 columns, BLAS beyond; A and A^T; beta 0, 1, -0.5): %" PetscInt_FMT " cases within %.1e of a triple loop in long double (relative, < 1e-13)", ncase, err);
  }
  PetscCall(PetscFinalize());
  return TestSummary("test_newtondense");
}
