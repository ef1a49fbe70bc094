/*
   SNESNEWTONDENSE, the default Newton of the harmonic-balance and continuation solves, against known roots:
   1. a cubic system with a chosen root x* (F = x^3 + A x - b, b from x*): converges to x* from 0 to round-off,
      in the same number of iterations as PETSc's newtonls + LU (the same Newton steps), to the same point;
   2. F_i = atan(x_i - c_i) from 3 away: undamped Newton diverges there (|x - c| grows at every step beyond
      1.39), the backtracking line search brings it to c;
   3. tolerances 0 (-snes_atol 0 -snes_rtol 0): the solve stops at round-off as converged, not as a failed
      line search;
   4. F = x^2 + 1 from 0 (singular Jacobian, no real root): DIVERGED_LINEAR_SOLVE, not an error.
*/
#include "jrtest.h"

typedef struct {
  PetscInt  kind, n;
  PetscReal A[19 * 19], b[19], c[19];
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

/* solve from x0 (n values) with the given type and options prefix; x (n), iterations, reason */
static PetscErrorCode Solve(Prob *p, const char *type, const char *prefix, const PetscReal *x0, PetscReal *xout, PetscInt *its, SNESConvergedReason *reason)
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
  PetscCall(SNESDestroy(&snes));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&x));
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
  PetscCall(PetscFinalize());
  return TestSummary("test_newtondense");
}
