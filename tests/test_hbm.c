/*
   Harmonic balance and continuation (JRHBM, JRCont) against independent truths:
   - no elements: every FRF point equals the exact complex linear solution (K(1 + i gamma) - w^2 M + i w C) X = F,
     in all modes and in physical coordinates;
   - one-DOF oscillator with a jenkins element: full stick equals the linear system with k + kt; the peak
     moves down towards sqrt(k/m) as the force grows; amplitude / force first drops then rises; energy
     balance (input = damping + friction) at every point; natural and arclength continuation agree;
   - Duffing oscillator (cubic element): arclength passes both folds and the single-harmonic
     amplitude-frequency relation holds at every point;
   - the analytic Jacobian and dR/dw vs central finite differences (jenkins, jenkins_nv with separation,
     cubic; H = 1 and 3);
   - the first reduction's joint fields (mean, linear) against stuck frequencies computed by hand;
   - H = 5 vs a long direct time integration of a friction oscillator (independent code below), and
     H = 1 close to H = 5.
   Runs on 1 and 2 ranks (elements are split across ranks).
*/
#include "jrtest_problem.h"
#include <slepcsys.h>
#include <petscviewerhdf5.h>
#include <complex.h>
#include <petscblaslapack.h>

/* a 4-DOF structure with every element type (jenkins, jenkins_nv with separation, cubic): the Jacobian checks. The
   first 6 elements; then two gaps (jenkins_nv open at rest, n0 < 0), one that closes during part of the cycle and
   one that stays open (the Jacobian's part at rest is then 0 for them, not the stuck springs) */
static const double K4[16] = {4e6, -1e6, 0, -1e6, -1e6, 3e6, -1e6, 0, 0, -1e6, 2e6, -5e5, -1e6, 0, -5e5, 3e6}, M4[16] = {1, 0, 0, 0, 0, 1.2, 0, 0, 0, 0, 0.8, 0, 0, 0, 0, 1.5};
static const El     E4[8]  = {
  {"jenkins",    0, -1, -1, -1, 1e6,  0,   0.1, 10   },
  {"jenkins",    1, 2,  -1, -1, 2e6,  0,   0.2, 5    },
  {"jenkins_nv", 2, -1, 3,  -1, 1e6,  1e6, 0.3, 2    },
  {"jenkins_nv", 3, 1,  0,  2,  5e5,  8e5, 0.2, 4    },
  {"cubic",      0, 3,  -1, -1, 1e11, 0,   0,   0    },
  {"jenkins",    3, -1, -1, -1, 1e6,  0,   0.1, 100  },
  {"jenkins_nv", 1, -1, 2,  -1, 1e6,  1e6, 0.3, -1   },
  {"jenkins_nv", 0, -1, 1,  -1, 1e6,  1e6, 0.3, -1000}
};

/* column j of dR/da at (a, w) by central finite differences (step h) into fd (n); ap, R1, R2: work */
static PetscErrorCode FDColumn(JRHBM hbm, Vec a, PetscInt j, double h, double w, Vec ap, Vec R1, Vec R2, double *fd)
{
  const PetscScalar *r1, *r2;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(VecGetSize(a, &n));
  PetscCall(VecCopy(a, ap));
  PetscCall(VecSetValue(ap, j, h, ADD_VALUES));
  PetscCall(VecAssemblyBegin(ap));
  PetscCall(VecAssemblyEnd(ap));
  PetscCall(JRHBMComputeResidual(hbm, w, ap, R1));
  PetscCall(VecSetValue(ap, j, -2 * h, ADD_VALUES));
  PetscCall(VecAssemblyBegin(ap));
  PetscCall(VecAssemblyEnd(ap));
  PetscCall(JRHBMComputeResidual(hbm, w, ap, R2));
  PetscCall(VecGetArrayRead(R1, &r1));
  PetscCall(VecGetArrayRead(R2, &r2));
  for (PetscInt i = 0; i < n; i++) fd[i] = (r1[i] - r2[i]) / (2 * h);
  PetscCall(VecRestoreArrayRead(R1, &r1));
  PetscCall(VecRestoreArrayRead(R2, &r2));
  PetscFunctionReturn(0);
}

/* the Jacobian and dR/dw of hbm at (a, w) against central finite differences (steps h in a, 1e-6 w in w): the largest
   differences ej, ew and the largest entries jmax, wmax; op (if not NULL): the Jacobian as the continuation's solves
   take it (JRHBMJacobianSetPoint, its products JRHBMJacobianMult on the unit vectors, its array JRHBMJacobianForm)
   against the same differences, relative to the largest entry: op[0] the products, op[1] the array, op[2] dR/dw */
static PetscErrorCode FDCheck(JRHBM hbm, Vec a, double h, double w, double *ej, double *jmax, double *ew, double *wmax, double *op)
{
  Vec                ap, R1, R2, Rw;
  Mat                J;
  PetscInt           n;
  const PetscScalar *Ja, *rw, *r1, *r2;
  const double       hw = 1e-6 * w;
  double            *fd, *fdw, fmaxj = 0;

  PetscFunctionBeginUser;
  *ej = *jmax = *ew = *wmax = 0.0;
  PetscCall(JRHBMCreateVecs(hbm, NULL, &J));
  PetscCall(VecDuplicate(a, &ap));
  PetscCall(VecDuplicate(a, &R1));
  PetscCall(VecDuplicate(a, &R2));
  PetscCall(VecDuplicate(a, &Rw));
  PetscCall(VecGetSize(a, &n));
  PetscCall(PetscMalloc2(n * n, &fd, n, &fdw));
  for (PetscInt j = 0; j < n; j++) PetscCall(FDColumn(hbm, a, j, h, w, ap, R1, R2, fd + j * n));
  for (PetscInt i = 0; i < n * n; i++) fmaxj = fmax(fmaxj, fabs(fd[i]));
  PetscCall(JRHBMComputeResidual(hbm, w + hw, a, R1));
  PetscCall(JRHBMComputeResidual(hbm, w - hw, a, R2));
  PetscCall(VecGetArrayRead(R1, &r1));
  PetscCall(VecGetArrayRead(R2, &r2));
  for (PetscInt i = 0; i < n; i++) fdw[i] = (r1[i] - r2[i]) / (2 * hw);
  PetscCall(VecRestoreArrayRead(R1, &r1));
  PetscCall(VecRestoreArrayRead(R2, &r2));
  PetscCall(JRHBMComputeJacobian(hbm, w, a, J, Rw));
  PetscCall(MatDenseGetArrayRead(J, &Ja));
  PetscCall(VecGetArrayRead(Rw, &rw));
  for (PetscInt i = 0; i < n * n; i++) {
    *ej   = fmax(*ej, fabs(Ja[i] - fd[i]));
    *jmax = fmax(*jmax, fabs(Ja[i]));
  }
  for (PetscInt i = 0; i < n; i++) {
    *ew   = fmax(*ew, fabs(rw[i] - fdw[i]));
    *wmax = fmax(*wmax, fabs(rw[i]));
  }
  PetscCall(VecRestoreArrayRead(Rw, &rw));
  PetscCall(MatDenseRestoreArrayRead(J, &Ja));
  if (op) {
    PetscScalar *e, *y, *A;
    double       wm = 0;
    op[0] = op[1] = op[2] = 0;
    PetscCall(PetscCalloc3(n, &e, n, &y, n * n, &A));
    PetscCall(JRHBMJacobianSetPoint(hbm, w, a, J, Rw));
    PetscCall(JRHBMJacobianForm(hbm, J, A, n));
    for (PetscInt j = 0; j < n; j++) {
      e[j] = 1.0;
      PetscCall(JRHBMJacobianMult(hbm, J, e, y));
      e[j] = 0.0;
      for (PetscInt i = 0; i < n; i++) {
        op[0] = fmax(op[0], fabs(y[i] - fd[i + j * n]));
        op[1] = fmax(op[1], fabs(A[i + j * n] - fd[i + j * n]));
      }
      if (j == 0) PetscCall(JRHBMComputeResidual(hbm, w + hw, a, R1)); /* the products after another evaluation: still at the point set */
    }
    PetscCall(VecGetArrayRead(Rw, &rw));
    for (PetscInt i = 0; i < n; i++) {
      op[2] = fmax(op[2], fabs(rw[i] - fdw[i]));
      wm    = fmax(wm, fabs(rw[i]));
    }
    PetscCall(VecRestoreArrayRead(Rw, &rw));
    op[0] /= fmaxj;
    op[1] /= fmaxj;
    op[2] /= wm;
    PetscCall(PetscFree3(e, y, A));
  }
  PetscCall(PetscFree2(fd, fdw));
  PetscCall(VecDestroy(&ap));
  PetscCall(VecDestroy(&R1));
  PetscCall(VecDestroy(&R2));
  PetscCall(VecDestroy(&Rw));
  PetscCall(MatDestroy(&J));
  PetscFunctionReturn(0);
}

/* The same model condensed onto its joints (p, -hbm_condense yes) and on the modal unknowns (q, no), H harmonics,
   structural damping 0.01, extra options before */
static PetscErrorCode CondensedPair(const char *extra, PetscInt H, PetscInt n, const double *K, const double *M, const double *C, PetscInt ne, const El *e, Problem *p, Problem *q)
{
  char opts[200];

  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < 2; c++) {
    PetscCall(PetscSNPrintf(opts, sizeof(opts), "%s -hbm_harmonics %" PetscInt_FMT " -hbm_samples 128 -hbm_gamma 0.01 -frf_force 1 -hbm_condense %s", extra, H, c ? "no" : "yes"));
    PetscCall(Options(opts));
    PetscCall(ProblemCreate(n, K, M, C, ne, e, c ? q : p));
  }
  PetscFunctionReturn(0);
}

/* The condensed model hc and the modal one hm solved at w from their linearised solutions (x: hc's solve space, its
   solution on exit): whether both converged, the largest difference of hc's solution expanded to the modes from hm's
   relative to hm's largest entry, and the contact states of hm's solution */
static PetscErrorCode CondensedVsModal(JRHBM hc, JRHBM hm, double w, Vec x, PetscBool *conv, double *rel, PetscInt cnt[4])
{
  Vec                a, ac;
  PetscInt           n, its;
  PetscBool          cc, cm;
  const PetscScalar *u, *v;
  double             da = 0, amax = 0;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetSizes(hm, NULL, NULL, &n));
  PetscCall(JRHBMLinearSolution(hc, w, x));
  PetscCall(JRHBMSolve(hc, w, x, &its, &cc));
  PetscCall(JRHBMCreateVecs(hm, &a, NULL));
  PetscCall(JRHBMLinearSolution(hm, w, a));
  PetscCall(JRHBMSolve(hm, w, a, &its, &cm));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &ac));
  PetscCall(JRHBMExpand(hc, w, x, ac));
  PetscCall(VecGetArrayRead(ac, &u));
  PetscCall(VecGetArrayRead(a, &v));
  for (PetscInt i = 0; i < n; i++) {
    da   = fmax(da, fabs(u[i] - v[i]));
    amax = fmax(amax, fabs(v[i]));
  }
  PetscCall(VecRestoreArrayRead(a, &v));
  PetscCall(VecRestoreArrayRead(ac, &u));
  PetscCall(JRHBMContactStates(hm, a, cnt));
  *conv = (PetscBool)(cc && cm);
  *rel  = da / amax;
  PetscCall(VecDestroy(&a));
  PetscCall(VecDestroy(&ac));
  PetscFunctionReturn(0);
}

/* point k of level l as a Vec */
static PetscErrorCode PointVec(Problem *p, PetscInt l, PetscInt k, Vec a)
{
  PetscInt         np, n;
  const PetscReal *A;
  PetscScalar     *x;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetSizes(p->hbm, NULL, NULL, &n));
  PetscCall(JRContGetBranch(p->cont, l, &np, NULL, &A, NULL));
  PetscCall(VecGetArray(a, &x));
  for (PetscInt i = 0; i < n; i++) x[i] = A[k * n + i];
  PetscCall(VecRestoreArray(a, &x));
  PetscFunctionReturn(0);
}

/* exact linear response at DOF out: (K (1 + i g) - w^2 M + i w C) X = e_fdof (n <= 4) */
static double complex LinearExact(PetscInt n, const double *K, const double *M, const double *C, double g, double w, PetscInt fdof, PetscInt out)
{
  double complex A[4][5];
  for (PetscInt i = 0; i < n; i++) {
    for (PetscInt j = 0; j < n; j++) A[i][j] = K[i * n + j] * (1.0 + I * g) - w * w * M[i * n + j] + I * w * (C ? C[i * n + j] : 0.0);
    A[i][n] = i == fdof ? 1.0 : 0.0;
  }
  for (PetscInt c = 0; c < n; c++) { /* Gauss-Jordan with partial pivoting */
    PetscInt piv = c;
    for (PetscInt r = c + 1; r < n; r++)
      if (cabs(A[r][c]) > cabs(A[piv][c])) piv = r;
    for (PetscInt j = 0; j <= n; j++) {
      double complex t = A[c][j];
      A[c][j]          = A[piv][j];
      A[piv][j]        = t;
    }
    for (PetscInt r = 0; r < n; r++)
      if (r != c) {
        double complex f = A[r][c] / A[c][c];
        for (PetscInt j = c; j <= n; j++) A[r][j] -= f * A[c][j];
      }
  }
  return A[out][n] / A[out][out];
}

/* Time integration of m x'' + c x' + k x + f = F sin(w t), f a jenkins element (kt, mu n0) to ground:
   RK4 on (x, x') with the slip updated after each step (play operator), dt = T/nstep, ncyc cycles;
   first and third harmonics of x over the last cycle. Independent of the library. */
static void TimeIntegrate(double m, double c, double k, double kt, double r, double F, double w, int nstep, int ncyc, double X[7])
{
  const double T = 2.0 * M_PI / w, dt = T / nstep;
  double       x = 0.0, v = 0.0, s = 0.0; /* slip */
  for (int i = 0; i < 7; i++) X[i] = 0.0;
  for (int cyc = 0; cyc < ncyc; cyc++) {
    for (int i = 0; i < nstep; i++) {
      const double t = (cyc * nstep + i) * dt;
      JenkinsOscillatorStep(m, c, k, kt, r, F, w, t, dt, &x, &v, &s);
      if (cyc == ncyc - 1) {
        const double th = w * (t + dt);
        X[0] += x / nstep;
        for (int h = 1; h <= 3; h++) {
          X[2 * h - 1] += 2.0 * x * sin(h * th) / nstep;
          X[2 * h] += 2.0 * x * cos(h * th) / nstep;
        }
      }
    }
  }
}

int main(int argc, char **argv)
{
  PetscCall(SlepcInitialize(&argc, &argv, NULL, NULL));

  /* ---- linear 3-DOF chain: exact complex solution at every point, modal and physical ---- */
  {
    const double K[9] = {3e5, -1e5, 0, -1e5, 2e5, -1e5, 0, -1e5, 1e5}, M[9] = {1.0, 0, 0, 0, 2.0, 0, 0, 0, 1.5};
    const double C[9] = {4.0, -1.0, 0, -1.0, 3.0, -1.0, 0, -1.0, 2.0}, g = 0.02;
    const char  *modes[2] = {"-hbm_modes 3", "-hbm_physical"};
    for (int md = 0; md < 2; md++) {
      Problem p;
      char    opts[256];
      double  err = 0.0;
      PetscInt np;
      Vec      a;
      const PetscReal *om;
      PetscCall(PetscSNPrintf(opts, sizeof(opts), "%s -hbm_gamma %g -frf_dof 1 -frf_output 2 -frf_force 2.5 -frf_fmin 10 -frf_fmax 80", modes[md], g));
      PetscCall(Options(opts));
      PetscCall(ProblemCreate(3, K, M, C, 0, NULL, &p));
      PetscCall(JRContSolve(p.cont));
      PetscCall(JRContGetBranch(p.cont, 0, &np, &om, NULL, NULL));
      PetscCall(JRHBMCreateVecs(p.hbm, &a, NULL));
      for (PetscInt k = 0; k < np; k++) {
        double         X[3];
        double complex Xe = 2.5 * LinearExact(3, K, M, C, g, om[k], 1, 2);
        PetscCall(PointVec(&p, 0, k, a));
        PetscCall(JRHBMResponse(p.hbm, a, X, NULL, NULL));
        err = fmax(err, cabs((X[1] + I * X[2]) - Xe) / cabs(Xe));
      }
      CHECK(err < 1e-10 && np > 20, "linear 3-DOF chain (%s, gamma + C damping): %" PetscInt_FMT " FRF points vs the exact complex solution, max relative error %.2e", md ? "physical coordinates" : "all 3 modes", np, err);
      PetscCall(VecDestroy(&a));
      PetscCall(ProblemDestroy(&p));
    }
  }

  /* ---- one-DOF oscillator with a jenkins element ---- */
  {
    const double m = 1.0, k = pow(2 * M_PI * 100, 2), kt = k, mu = 0.1, n0 = 100.0, r = mu * n0, g = 0.01;
    const double K[1] = {k}, M[1] = {m};
    const El     e[1] = {
      {"jenkins", 0, -1, -1, -1, kt, 0, mu, n0}
    };
    const double flin = sqrt((k + kt) / m) / (2 * M_PI), fslip = sqrt(k / m) / (2 * M_PI), A0 = r / kt;
    /* full stick: F such that the stuck peak F / (gamma k) stays below A0 = mu n0 / kt */
    {
      Problem          p;
      const double     F = 0.5 * A0 * g * k;
      PetscInt         np, kp = 0;
      const PetscReal *om, *amp;
      double           err = 0.0;
      char             opts[256];
      PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_gamma %g -frf_force %g -frf_fmin %g -frf_fmax %g", g, F, 0.8 * flin, 1.2 * flin));
      PetscCall(Options(opts));
      PetscCall(ProblemCreate(1, K, M, NULL, 1, e, &p));
      PetscCall(JRContSolve(p.cont));
      PetscCall(JRContGetBranch(p.cont, 0, &np, &om, NULL, &amp));
      for (PetscInt i = 0; i < np; i++) {
        const double ex = F / cabs(k + kt - m * om[i] * om[i] + I * g * k);
        err             = fmax(err, fabs(amp[i] - ex) / ex);
        if (amp[i] > amp[kp]) kp = i;
      }
      CHECK(err < 1e-9, "jenkins oscillator, full stick (F = %.3g N): %" PetscInt_FMT " points equal the linear system with k + kt, max error %.1e", F, np, err);
      CHECK(fabs(om[kp] / (2 * M_PI) - flin) < 2e-3 * flin && fabs(amp[kp] - F / (g * k)) < 2e-3 * F / (g * k), "jenkins oscillator, full stick: peak %.5g Hz vs sqrt((k+kt)/m) = %.5g Hz, amplitude %.5g vs F/(gamma k) = %.5g m", om[kp] / (2 * M_PI), flin, amp[kp], F / (g * k));
      PetscCall(ProblemDestroy(&p));
    }
    /* levels from microslip to gross slip: the peak moves down, amplitude/force drops then rises; energy balance */
    {
      Problem     p;
      const double Fs[6] = {0.5, 2.0, 5.0, 20.0, 100.0, 2000.0};
      double       fpk[6], apk[6], ebal = 0.0;
      char         opts[512];
      Vec          a;
      PetscBool    down = PETSC_TRUE;
      PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_gamma %g -frf_force %g,%g,%g,%g,%g,%g -frf_fmin %g -frf_fmax %g", g, Fs[0] * A0 * g * k, Fs[1] * A0 * g * k, Fs[2] * A0 * g * k, Fs[3] * A0 * g * k, Fs[4] * A0 * g * k, Fs[5] * A0 * g * k, 0.8 * fslip, 1.2 * flin));
      PetscCall(Options(opts));
      PetscCall(ProblemCreate(1, K, M, NULL, 1, e, &p));
      PetscCall(JRContSolve(p.cont));
      PetscCall(JRHBMCreateVecs(p.hbm, &a, NULL));
      for (int l = 0; l < 6; l++) {
        PetscReal        wp, ap;
        PetscInt         np;
        const PetscReal *om;
        PetscCall(JRContGetPeak(p.cont, l, &wp, &ap));
        fpk[l] = wp / (2 * M_PI);
        apk[l] = ap / (Fs[l] * A0 * g * k) * (g * k); /* amplitude / force in units of 1/(gamma k) */
        if (l && fpk[l] > fpk[l - 1] + 1e-6 * flin) down = PETSC_FALSE;
        PetscCall(JRContGetBranch(p.cont, l, &np, &om, NULL, NULL));
        for (PetscInt i = 0; i < np; i++) {
          PetscReal win, ed, enl;
          PetscCall(PointVec(&p, l, i, a));
          PetscCall(JRHBMSetForceLevel(p.hbm, Fs[l] * A0 * g * k));
          PetscCall(JRHBMEnergy(p.hbm, om[i], a, &win, &ed, &enl));
          ebal = fmax(ebal, fabs(win - ed - enl) / win);
        }
      }
      CHECK(down && fabs(fpk[5] - fslip) < 0.01 * fslip && fabs(fpk[0] - flin) > 0.0, "jenkins oscillator: peak frequency falls with the force, %.4g -> %.4g Hz, towards sqrt(k/m) = %.4g Hz (from sqrt((k+kt)/m) = %.4g Hz)", fpk[0], fpk[5], fslip, flin);
      CHECK(apk[2] < 0.8 * apk[0] && apk[5] > 1.5 * apk[2], "jenkins oscillator: peak amplitude / force (in units of 1/(gamma k)) %.3f, %.3f, %.3f, %.3f, %.3f, %.3f: drops with friction damping, then rises towards gross slip", apk[0], apk[1], apk[2], apk[3], apk[4], apk[5]);
      CHECK(ebal < 1e-8, "jenkins oscillator: energy balance (input = structural damping + friction) at every point of 6 levels, max relative error %.1e", ebal);
      PetscCall(VecDestroy(&a));
      PetscCall(ProblemDestroy(&p));
    }
    /* the HDF5 output holds the curve: read /level_0/omega back and compare with the branch */
    {
      Problem          p;
      char             opts[512], file[PETSC_MAX_PATH_LEN] = "/tmp/jr_test_hbm_frf";
      PetscInt         np, n5;
      const PetscReal *om;
      PetscViewer      v;
      Vec              x;
      PetscReal        F5, diff = 0.0;
      PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_gamma %g -frf_force %g -frf_fmin %g -frf_fmax %g -frf_plot 0", g, 5.0 * A0 * g * k, 0.8 * fslip, 1.2 * flin));
      PetscCall(Options(opts));
      PetscCall(PetscOptionsSetValue(NULL, "-frf_output_file", file));
      PetscCall(ProblemCreate(1, K, M, NULL, 1, e, &p));
      PetscCall(JRContSolve(p.cont));
      {
        JRPost post;
        PetscCall(JRPostCreate(PETSC_COMM_WORLD, &post));
        PetscCall(JRPostSetOutput(post, file, PETSC_FALSE));
        PetscCall(JRPostWriteCurves(post, p.cont));
        PetscCall(JRPostDestroy(&post));
      }
      PetscCall(JRContGetBranch(p.cont, 0, &np, &om, NULL, NULL));
      PetscCall(PetscViewerHDF5Open(PETSC_COMM_WORLD, "/tmp/jr_test_hbm_frf.h5", FILE_MODE_READ, &v));
      PetscCall(PetscViewerHDF5PushGroup(v, "/level_0"));
      PetscCall(VecCreate(PETSC_COMM_WORLD, &x));
      PetscCall(PetscObjectSetName((PetscObject)x, "omega"));
      PetscCall(VecLoad(x, v));
      PetscCall(VecGetSize(x, &n5));
      PetscCall(PetscViewerHDF5ReadAttribute(v, "/level_0", "force_N", PETSC_REAL, NULL, &F5));
      PetscCall(PetscViewerHDF5PopGroup(v));
      PetscCall(PetscViewerDestroy(&v));
      {
        Vec                xs;
        VecScatter         sc;
        const PetscScalar *xa;
        PetscCall(VecScatterCreateToAll(x, &sc, &xs));
        PetscCall(VecScatterBegin(sc, x, xs, INSERT_VALUES, SCATTER_FORWARD));
        PetscCall(VecScatterEnd(sc, x, xs, INSERT_VALUES, SCATTER_FORWARD));
        PetscCall(VecGetArrayRead(xs, &xa));
        for (PetscInt i = 0; i < PetscMin(np, n5); i++) diff = fmax(diff, fabs(xa[i] - om[i]));
        PetscCall(VecRestoreArrayRead(xs, &xa));
        PetscCall(VecScatterDestroy(&sc));
        PetscCall(VecDestroy(&xs));
      }
      CHECK(n5 == np && diff == 0.0 && F5 == 5.0 * A0 * g * k, "HDF5 output: /level_0/omega read back (%" PetscInt_FMT " of %" PetscInt_FMT " points, max difference %g) and its force_N attribute %g N", n5, np, diff, (double)F5);
      PetscCall(VecDestroy(&x));
      PetscCall(ProblemDestroy(&p));
    }
    /* natural and arclength continuation give the same curve (no folds here) */
    {
      Problem      p1, p2;
      const double F = 5.0 * A0 * g * k;
      char         opts[256];
      PetscReal    w1, a1, w2, a2;
      PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_gamma %g -frf_force %g -frf_fmin %g -frf_fmax %g -cont_type natural -cont_step_max 0.5", g, F, 0.8 * fslip, 1.2 * flin));
      PetscCall(Options(opts));
      PetscCall(ProblemCreate(1, K, M, NULL, 1, e, &p1));
      PetscCall(JRContSolve(p1.cont));
      PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_gamma %g -frf_force %g -frf_fmin %g -frf_fmax %g -cont_type arclength -cont_step_max 0.005", g, F, 0.8 * fslip, 1.2 * flin));
      PetscCall(Options(opts));
      PetscCall(ProblemCreate(1, K, M, NULL, 1, e, &p2));
      PetscCall(JRContSolve(p2.cont));
      PetscCall(JRContGetPeak(p1.cont, 0, &w1, &a1));
      PetscCall(JRContGetPeak(p2.cont, 0, &w2, &a2));
      CHECK(fabs(w1 - w2) < 2e-3 * w1 && fabs(a1 - a2) < 5e-3 * a1, "jenkins oscillator: natural and arclength continuation agree on the peak, %.5g vs %.5g Hz, %.5g vs %.5g m", w1 / (2 * M_PI), w2 / (2 * M_PI), a1, a2);
      PetscCall(ProblemDestroy(&p1));
      PetscCall(ProblemDestroy(&p2));
    }
  }

  /* ---- Duffing: arclength through both folds, amplitude-frequency relation at every point ---- */
  {
    const double m = 1.0, k = pow(2 * M_PI * 10, 2), k3 = 6e6, c = 0.4, F = 2.0; /* backbone peak near 18 Hz */
    const double K[1] = {k}, M[1] = {m}, C[1] = {c};
    const El     e[1] = {
      {"cubic", 0, -1, -1, -1, k3, 0, 0, 0}
    };
    Problem          p;
    PetscInt         np, turns = 0;
    const PetscReal *om, *amp;
    double           err = 0.0;
    PetscCall(Options("-frf_force 2.0 -frf_fmin 5 -frf_fmax 25 -cont_max_points 3000"));
    PetscCall(ProblemCreate(1, K, M, C, 1, e, &p));
    PetscCall(JRContSolve(p.cont));
    PetscCall(JRContGetBranch(p.cont, 0, &np, &om, NULL, &amp));
    for (PetscInt i = 0; i < np; i++) {
      const double A = amp[i], w = om[i], q = k - m * w * w + 0.75 * k3 * A * A;
      err = fmax(err, fabs((q * q + c * c * w * w) * A * A - F * F) / (F * F));
      if (i > 0 && i < np - 1 && (om[i] - om[i - 1]) * (om[i + 1] - om[i]) < 0) turns++;
    }
    CHECK(turns == 2, "Duffing oscillator: arclength passes %" PetscInt_FMT " turning points (2 expected) in %" PetscInt_FMT " points", turns, np);
    CHECK(err < 1e-8, "Duffing oscillator: single-harmonic relation ((k - m w^2 + 3/4 k3 A^2)^2 + (c w)^2) A^2 = F^2 at every point, max relative error %.1e", err);
    {
      PetscReal wp, ap;
      PetscCall(JRContGetPeak(p.cont, 0, &wp, &ap));
      /* the backbone: at the peak, k - m w^2 + 3/4 k3 A^2 = 0 and A = F / (c w) */
      CHECK(fabs(ap - F / (c * wp)) < 1e-3 * ap, "Duffing oscillator: peak amplitude %.6g m on the backbone F/(c w) = %.6g m", ap, F / (c * wp));
    }
    PetscCall(ProblemDestroy(&p));
  }

  /* ---- Jacobian and dR/dw vs finite differences, every element type, H = 1 and 3 ---- */
  for (PetscInt H = 1; H <= 3; H += 2) {
    const double *K = K4, *M = M4;
    const El     *e = E4;
    Problem   p;
    Vec       a;
    PetscInt  n;
    double    ej = 0.0, ew = 0.0, jmax = 0.0, wmax = 0.0, w = 2 * M_PI * 250;
    char      opts[128];
    PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_harmonics %" PetscInt_FMT " -hbm_samples 128 -hbm_gamma 0.01 -frf_force 1", H));
    PetscCall(Options(opts));
    PetscCall(ProblemCreate(4, K, M, NULL, 8, e, &p));
    PetscCall(JRHBMSetForceLevel(p.hbm, 3.0));
    PetscCall(JRHBMCreateVecs(p.hbm, &a, NULL));
    PetscCall(VecGetSize(a, &n));
    {
      PetscScalar *x;
      PetscCall(VecGetArray(a, &x));
      srand(3);
      for (PetscInt i = 0; i < n; i++) x[i] = 6e-6 * (2.0 * rand() / RAND_MAX - 1.0) / (1 + i / 4);
      PetscCall(VecRestoreArray(a, &x));
    }
    double eop[3];
    PetscCall(FDCheck(p.hbm, a, 1e-6 * 6e-6, w, &ej, &jmax, &ew, &wmax, eop));
    {
      PetscInt cnt[4];
      PetscCall(JRHBMContactStates(p.hbm, a, cnt));
      CHECK(ej < 1e-6 * jmax && ew < 1e-6 * wmax && cnt[2] >= 1 && cnt[3] >= 1, "HBM Jacobian, H = %" PetscInt_FMT ", 4 modes, jenkins + jenkins_nv + cubic, two gaps (states: %" PetscInt_FMT " stick, %" PetscInt_FMT " slip, %" PetscInt_FMT " separating part of the cycle, %" PetscInt_FMT " open throughout): dR/da %.1e, dR/dw %.1e relative to finite differences", H, cnt[0], cnt[1], cnt[2], cnt[3], ej / jmax, ew / wmax);
    }
    {
      const double em = eop[0], ef = eop[1], eo = eop[2];
      CHECK(em < 1e-6 && ef < 1e-6 && eo < 1e-6, "HBM Jacobian as the continuation takes it (modal unknowns), H = %" PetscInt_FMT ": its products on the unit vectors %.1e, its array %.1e, dR/dw %.1e relative to finite differences", H, em, ef, eo);
    }
    PetscCall(VecDestroy(&a));
    PetscCall(ProblemDestroy(&p));
  }

  /* ---- first reduction with a linear joint field (-rom_joint_motion linear): three grounded jenkins members on DOFs
     0, 1, 2 at x = 0, 1, 3 m on a line (y, z spread 0: the fit must drop those directions) form joint 0, a fourth on
     DOF 3 is joint 1 alone. By hand: the stuck members' rows are e_a; the least-squares line through them evaluated at
     x_e gives r_e = mean + (x_e - xbar) sum_f e_f (x_f - xbar) / sum_f (x_f - xbar)^2; the stuck frequencies are those
     of K + kt sum_e r_e r_e^T with M (LAPACK sygv here). The mean field (4.4) is the same without the slope; nested
     projections in the stiffness norm (equal kt) order the three: mean <= linear <= members on their own rows ---- */
  {
    const El       e3[4]    = {
      {"jenkins", 0, -1, -1, -1, 1e6, 0, 0.1, 10},
      {"jenkins", 1, -1, -1, -1, 1e6, 0, 0.1, 10},
      {"jenkins", 2, -1, -1, -1, 1e6, 0, 0.1, 10},
      {"jenkins", 3, -1, -1, -1, 1e6, 0, 0.1, 10}
    };
    const PetscInt joint[4] = {0, 0, 0, 1};
    const double   pos[12]  = {0, 0, 0, 1, 0, 0, 3, 0, 0, 7, 0, 0}, x[3] = {0, 1, 3};
    double         fl[4], fm[4], fo[4], err[2] = {0, 0};
    PetscInt       nf;
    for (PetscInt lin = 0; lin < 2; lin++) {
      double       A[16], B[16], w[4], work[64], xbar = 0, sxx = 0, R[3][4];
      PetscBLASInt n4 = 4, lwork = 64, info, itype = 1;
      Problem      p;
      for (PetscInt i = 0; i < 3; i++) xbar += x[i] / 3;
      for (PetscInt i = 0; i < 3; i++) sxx += (x[i] - xbar) * (x[i] - xbar);
      for (PetscInt i = 0; i < 3; i++)
        for (PetscInt d = 0; d < 4; d++) R[i][d] = d < 3 ? 1.0 / 3 + (lin ? (x[i] - xbar) * (x[d] - xbar) / sxx : 0.0) : 0.0;
      for (PetscInt i = 0; i < 16; i++) {
        A[i] = K4[i];
        B[i] = M4[i];
      }
      for (PetscInt i = 0; i < 3; i++)
        for (PetscInt c = 0; c < 4; c++)
          for (PetscInt d = 0; d < 4; d++) A[c + 4 * d] += e3[i].kt * R[i][c] * R[i][d];
      A[15] += e3[3].kt;
      PetscCallBLAS("LAPACKsygv", LAPACKsygv_(&itype, "N", "U", &n4, A, &n4, B, &n4, w, work, &lwork, &info));
      jr_joints  = joint;
      jr_njoints = 2;
      jr_pos     = pos;
      PetscCall(Options("-hbm_physical"));
      jr_jmotion = lin ? JR_JOINT_MOTION_LINEAR : JR_JOINT_MOTION_MEAN;
      PetscCall(ProblemCreate(4, K4, M4, NULL, 4, e3, &p));
      jr_jmotion = JR_JOINT_MOTION_MEAN;
      PetscCall(JRHBMStickFrequencies(p.hbm, &nf, lin ? fl : fm));
      PetscCall(ProblemDestroy(&p));
      for (PetscInt i = 0; i < 4; i++) err[lin] = PetscMax(err[lin], PetscAbsReal((lin ? fl : fm)[i] / (PetscSqrtReal(w[i]) / (2 * M_PI)) - 1));
    }
    jr_joints = NULL;
    jr_pos    = NULL;
    {
      Problem p;
      PetscCall(Options("-hbm_physical"));
      PetscCall(ProblemCreate(4, K4, M4, NULL, 4, e3, &p));
      PetscCall(JRHBMStickFrequencies(p.hbm, &nf, fo));
      PetscCall(ProblemDestroy(&p));
    }
    CHECK(nf == 4 && err[1] < 1e-12 && err[0] < 1e-12, "first reduction, 3 members on a line in one joint: stuck frequencies with the linear field (joint motion linear) = by hand within %.1e, with the mean within %.1e", err[1], err[0]);
    CHECK(fm[0] <= fl[0] * (1 + 1e-12) && fl[0] <= fo[0] * (1 + 1e-12) && fl[0] > fm[0] * (1 + 1e-6), "nested projections: first stuck frequency mean %.6g <= linear %.6g <= own rows %.6g Hz (linear strictly above the mean)", fm[0], fl[0], fo[0]);    { /* a third coordinate (-rom_joint_motion mode: the stuck-mode motion, here 0, 0, 1 on the three members) makes
         1, x, phi independent over the three: the least-squares field then interpolates, every member keeps its own row,
         and the stuck frequencies are the members' own */
      const double phi[8] = {0, 0, 0, 0, 1, 0, 0, 0};
      double       fp[4], dev = 0;
      Problem      p;
      jr_joints  = joint;
      jr_njoints = 2;
      jr_pos     = pos;
      jr_phi     = phi;
      PetscCall(Options("-hbm_physical"));
      jr_jmotion = JR_JOINT_MOTION_MODE;
      PetscCall(ProblemCreate(4, K4, M4, NULL, 4, e3, &p));
      jr_jmotion = JR_JOINT_MOTION_MEAN;
      PetscCall(JRHBMStickFrequencies(p.hbm, &nf, fp));
      PetscCall(ProblemDestroy(&p));
      jr_joints = NULL;
      jr_pos    = NULL;
      jr_phi    = NULL;
      for (PetscInt i = 0; i < 4; i++) dev = PetscMax(dev, PetscAbsReal(fp[i] / fo[i] - 1));
      CHECK(dev < 1e-12 && fp[0] > fl[0] * (1 + 1e-6), "first reduction, 3 members with 3 independent field coordinates (1, x, phi): the members' own stuck frequencies within %.1e (above the linear field's %.6g Hz: %.6g Hz)", dev, fl[0], fp[0]);
    }
  }

  /* ---- condensation onto the joints (-hbm_condense): the modal equations with the modes eliminated exactly ---- */
  for (PetscInt H = 1; H <= 3; H += 2) {
    const double  *K = K4, *M = M4;
    const El      *e = E4;
    const PetscInt joint[6] = {0, 0, 1, 1, 2, 0}; /* 3 joints: their members move with the average of their rows */
    double         C[16], ej = 0.0, ew = 0.0, jmax = 0.0, wmax = 0.0, w = 2 * M_PI * 250, da = 0.0;
    Problem        p, q;
    Vec            x;
    PetscInt       n, ns;
    PetscBool      conv;
    const char    *info;
    for (PetscInt i = 0; i < 16; i++) C[i] = 2.0 * M[i] + 1e-5 * K[i]; /* proportional: diagonal in the modes */
    jr_joints  = joint;
    jr_njoints = 3;
    PetscCall(CondensedPair("", H, 4, K, M, C, 6, e, &p, &q));
    jr_joints = NULL;
    PetscCall(JRHBMGetSolveSize(p.hbm, &ns, &info));
    PetscCall(JRHBMGetSizes(p.hbm, NULL, NULL, &n));
    CHECK(ns == 4 * (2 * H + 1) && n == 4 * (2 * H + 1) && info[0], "condensation, H = %" PetscInt_FMT ": 3 joints, one row each and a normal row for the one with jenkins_nv members = 4 rows, %" PetscInt_FMT " unknowns (modal: %" PetscInt_FMT "): %s", H, ns, n, info);
    PetscCall(JRHBMSetForceLevel(p.hbm, 3.0));
    PetscCall(JRHBMSetForceLevel(q.hbm, 3.0));
    PetscCall(JRHBMCreateVecs(p.hbm, &x, NULL));
    {
      PetscScalar *v;
      PetscCall(VecGetArray(x, &v));
      srand(5);
      for (PetscInt i = 0; i < ns; i++) v[i] = 6e-6 * (2.0 * rand() / RAND_MAX - 1.0) / (1 + i / 6);
      PetscCall(VecRestoreArray(x, &v));
    }
    double eop[3];
    PetscCall(FDCheck(p.hbm, x, 1e-6 * 6e-6, w, &ej, &jmax, &ew, &wmax, eop));
    CHECK(ej < 1e-6 * jmax && ew < 1e-6 * wmax, "condensed Jacobian, H = %" PetscInt_FMT ", jenkins + jenkins_nv + cubic on 3 joints, proportional viscous + structural damping: dr/dx %.1e, dr/dw %.1e relative to finite differences", H, ej / jmax, ew / wmax);
    {
      const double em = eop[0], ef = eop[1], eo = eop[2];
      CHECK(em < 1e-6 && ef < 1e-6 && eo < 1e-6, "condensed Jacobian as the continuation takes it, H = %" PetscInt_FMT ": its products through the modes (on the unit vectors) %.1e, its array formed for an LU %.1e, dr/dw %.1e relative to finite differences", H, em, ef, eo);
    }
    /* the same solution as the modal equations: solve both at 250 Hz at a level where elements slip, expand the
       joints' motions to modes */
    PetscCall(JRHBMSetForceLevel(p.hbm, 40.0));
    PetscCall(JRHBMSetForceLevel(q.hbm, 40.0));
    {
      PetscInt cnt[4];
      PetscCall(CondensedVsModal(p.hbm, q.hbm, w, x, &conv, &da, cnt));
      CHECK(conv && da < 1e-8, "condensed solution at 250 Hz, H = %" PetscInt_FMT ", expanded to the modes = the modal equations' solution within %.1e (relative; states %" PetscInt_FMT " stick, %" PetscInt_FMT " slip, %" PetscInt_FMT " separating)", H, da, cnt[0], cnt[1], cnt[2] + cnt[3]);
    }
    PetscCall(VecDestroy(&x));
    PetscCall(ProblemDestroy(&p));
    PetscCall(ProblemDestroy(&q));
  }

  /* ---- condensation onto the joints' row space: a 10-DOF chain whose 8 jenkins_nv members (some open at rest) form
     2 joints of 4, each at x = 0, 1, 2 or 3, 4 m on a line, moving with the joint's linear field (-rom_joint_motion
     linear): every member's tangential and normal rows are combinations of its joint's mean and slope rows, 2 + 2 per
     joint (by hand), so 8 condensed rows against 10 modes; the condensed Jacobian against finite differences and the
     condensed solution, expanded, against the modal equations' ---- */
  for (PetscInt H = 1; H <= 3; H += 2) {
    double         K[100], M[100], w = 2 * M_PI * 60, ej = 0, ew = 0, jmax = 0, wmax = 0, da = 0;
    const El       e[8]     = {
      {"jenkins_nv", 0, -1, 4, -1, 1e6, 1e6, 0.3, 2  },
      {"jenkins_nv", 1, -1, 5, -1, 1e6, 1e6, 0.3, 3  },
      {"jenkins_nv", 2, -1, 6, -1, 1e6, 1e6, 0.3, -1 },
      {"jenkins_nv", 3, -1, 7, -1, 1e6, 1e6, 0.3, 4  },
      {"jenkins_nv", 5, -1, 9, -1, 2e6, 1e6, 0.2, 5  },
      {"jenkins_nv", 6, -1, 8, -1, 2e6, 1e6, 0.2, 1  },
      {"jenkins_nv", 7, -1, 1, -1, 2e6, 1e6, 0.2, -2 },
      {"jenkins_nv", 8, -1, 2, -1, 2e6, 1e6, 0.2, 6  }
    };
    const PetscInt joint[8] = {0, 0, 0, 0, 1, 1, 1, 1};
    const double   pos[24]  = {0, 0, 0, 1, 0, 0, 2, 0, 0, 4, 0, 0, 0, 0, 0, 1, 0, 0, 3, 0, 0, 4, 0, 0};
    Problem        p, q;
    Vec            x;
    PetscInt       n, ns, cnt[4];
    PetscBool      conv;
    const char    *info;
    for (PetscInt i = 0; i < 100; i++) K[i] = M[i] = 0;
    for (PetscInt i = 0; i < 10; i++) { /* springs of 1e6 N/m between neighbours and to the ground at both ends */
      K[i + 10 * i] = 2e6;
      M[i + 10 * i] = 1.0 + 0.1 * i;
      if (i) K[i + 10 * (i - 1)] = K[(i - 1) + 10 * i] = -1e6;
    }
    jr_joints  = joint;
    jr_njoints = 2;
    jr_pos     = pos;
    jr_jmotion = JR_JOINT_MOTION_LINEAR;
    PetscCall(CondensedPair("-hbm_physical", H, 10, K, M, NULL, 8, e, &p, &q));
    jr_joints  = NULL;
    jr_pos     = NULL;
    jr_jmotion = JR_JOINT_MOTION_MEAN;
    PetscCall(JRHBMGetSolveSize(p.hbm, &ns, &info));
    PetscCall(JRHBMGetSizes(p.hbm, NULL, NULL, &n));
    CHECK(ns == 8 * (2 * H + 1) && n == 10 * (2 * H + 1), "row-space condensation, H = %" PetscInt_FMT ", 2 joints of 4 members on a line with a linear field: (2 + 2) x 2 = 8 rows, %" PetscInt_FMT " unknowns (modal: %" PetscInt_FMT "): %s", H, ns, n, info);
    PetscCall(JRHBMSetForceLevel(p.hbm, 2.0));
    PetscCall(JRHBMSetForceLevel(q.hbm, 2.0));
    PetscCall(JRHBMCreateVecs(p.hbm, &x, NULL));
    PetscCall(CondensedVsModal(p.hbm, q.hbm, w, x, &conv, &da, cnt));
    double eop[3];
    PetscCall(FDCheck(p.hbm, x, 1e-6 * 1e-5, w, &ej, &jmax, &ew, &wmax, eop));
    CHECK(ej < 1e-6 * jmax && ew < 1e-6 * wmax, "row-space condensed Jacobian, H = %" PetscInt_FMT ", at the solution at 60 Hz: dr/dx %.1e, dr/dw %.1e relative to finite differences", H, ej / jmax, ew / wmax);
    {
      const double em = eop[0], ef = eop[1], eo = eop[2];
      CHECK(em < 1e-6 && ef < 1e-6 && eo < 1e-6, "row-space condensed Jacobian as the continuation takes it, H = %" PetscInt_FMT ", at the solution at 60 Hz: its products through the modes (on the unit vectors) %.1e, its array formed for an LU %.1e, dr/dw %.1e relative to finite differences", H, em, ef, eo);
    }
    CHECK(conv && da < 1e-8 && cnt[1] > 0 && cnt[2] + cnt[3] > 0, "row-space condensed solution at 60 Hz, H = %" PetscInt_FMT ", expanded to the modes = the modal equations' within %.1e (relative; states %" PetscInt_FMT " stick, %" PetscInt_FMT " slip, %" PetscInt_FMT " separating or open)", H, da, cnt[0], cnt[1], cnt[2] + cnt[3]);
    PetscCall(VecDestroy(&x));
    PetscCall(ProblemDestroy(&p));
    PetscCall(ProblemDestroy(&q));
  }

  /* ---- H = 5 vs direct time integration; H = 1 vs H = 5 ---- */
  {
    const double m = 1.0, k = pow(2 * M_PI * 50, 2), kt = 0.5 * k, r = 20.0, c = 2.0, F = 12.0;
    const double K[1] = {k}, M[1] = {m}, C[1] = {c};
    const El     e[1] = {
      {"jenkins", 0, -1, -1, -1, kt, 0, 0.2, r / 0.2}
    };
    const double w = 2 * M_PI * 55.0;
    double       Xt[7], X5[11], X1[3];
    for (int H = 1; H <= 5; H += 4) {
      Problem   p;
      Vec       a;
      PetscInt  its;
      PetscBool conv;
      char      opts[128];
      PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_harmonics %d -hbm_samples 512 -frf_force %g", H, F));
      PetscCall(Options(opts));
      PetscCall(ProblemCreate(1, K, M, C, 1, e, &p));
      PetscCall(JRHBMSetForceLevel(p.hbm, F));
      PetscCall(JRHBMCreateVecs(p.hbm, &a, NULL));
      PetscCall(JRHBMLinearSolution(p.hbm, w, a));
      PetscCall(JRHBMSolve(p.hbm, w, a, &its, &conv));
      PetscCall(JRHBMResponse(p.hbm, a, H == 1 ? X1 : X5, NULL, NULL));
      CHECK(conv, "friction oscillator at 55 Hz, H = %d: Newton converged in %" PetscInt_FMT " iterations", H, its);
      PetscCall(VecDestroy(&a));
      PetscCall(ProblemDestroy(&p));
    }
    TimeIntegrate(m, c, k, kt, r, F, w, 20000, 400, Xt);
    {
      const double A1 = hypot(Xt[1], Xt[2]), e1 = hypot(X5[1] - Xt[1], X5[2] - Xt[2]) / A1, e3 = hypot(X5[5] - Xt[5], X5[6] - Xt[6]) / A1, e13 = hypot(X1[1] - X5[1], X1[2] - X5[2]) / A1;
      CHECK(e1 < 2e-3 && e3 < 2e-3, "friction oscillator at 55 Hz: H = 5 vs direct time integration (RK4, 20000 steps/cycle, 400 cycles): 1st harmonic error %.1e, 3rd harmonic (%.2e m, %.1f%% of the 1st) error %.1e, of the amplitude %.4g m", e1, hypot(Xt[5], Xt[6]), 100 * hypot(Xt[5], Xt[6]) / A1, e3, A1);
      CHECK(e13 < 0.03, "friction oscillator at 55 Hz: H = 1 first harmonic within %.1f%% of H = 5 (mildly nonlinear)", 100 * e13);
    }
  }

  PetscCall(SlepcFinalize());
  return TestSummary("test_hbm");
}
