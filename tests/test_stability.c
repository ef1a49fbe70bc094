#include "jrtest_problem.h"
#include <slepcsys.h>
int main(int argc, char **argv)
{
  PetscCall(SlepcInitialize(&argc, &argv, NULL, NULL));
  const double m = 1.0, k = pow(2 * M_PI * 10, 2), k3 = 6e6, c = 0.4;
  const double K[1] = {k}, M[1] = {m}, C[1] = {c};
  const El e[1] = {{"cubic", 0, -1, -1, -1, k3, 0, 0, 0}};
  Problem p; PetscInt np; const PetscReal *om, *a, *amp; Vec x;
  PetscCall(Options("-frf_force 2.0 -frf_fmin 5 -frf_fmax 25 -cont_max_points 3000 -hbm_harmonics 1 -cont_monitor 0"));
  PetscCall(PetscOptionsInsert(NULL, &argc, &argv, NULL));
  PetscCall(ProblemCreate(1, K, M, C, 1, e, &p));
  PetscCall(JRContSolve(p.cont));
  PetscCall(JRContGetBranch(p.cont, 0, &np, &om, &a, &amp));
  PetscCall(JRHBMCreateVecs(p.hbm, &x, NULL));
  PetscInt n; PetscCall(VecGetSize(x, &n));
  for (PetscInt i = 0; i < np; i += 5) {
    PetscReal re[2], im[2], mr; PetscInt ds; PetscScalar *xa;
    PetscCall(VecGetArray(x, &xa)); for (PetscInt j = 0; j < n; j++) xa[j] = a[i * n + j]; PetscCall(VecRestoreArray(x, &xa));
    PetscCall(JRHBMFloquet(p.hbm, om[i], x, JR_HILL_SELECT_VECTOR, 400, re, im, &mr, &ds));
    printf("%3d w %8.3f A %.4e det %d  V l1 %g %+gi  l2 %g %+gi", (int)i, om[i], amp[i], (int)ds, re[0], im[0], re[1], im[1]);
    PetscCall(JRHBMFloquet(p.hbm, om[i], x, JR_HILL_SELECT_IMAG, 400, re, im, &mr, &ds));
    printf("  I l1 %g %+gi  l2 %g %+gi\n", re[0], im[0], re[1], im[1]);
  }
  PetscCall(VecDestroy(&x));
  PetscCall(ProblemDestroy(&p));
  PetscCall(SlepcFinalize());
  return 0;
}
