/*
   Trust in the curves and their peaks (JRCont, JRHBMSolveResidual) against references that do not come from jointrom:
   - the exact single-harmonic (H = 1) frequency response of a 1-DOF and a 2-DOF system with a jenkins element to
     ground, from the element's closed-form describing function (below): the printed peaks within 1e-5 of its
     maximum, in amplitude and frequency, at every level from full stick to gross slip; every point of the curves
     on the describing-function relation; linear interpolation between consecutive points within 1% of the exact
     curve everywhere;
   - H = 15 against a direct time integration (RK4, slip projected each step) of the 1-DOF system, maximised over the
     frequency by golden section: the peak within 1e-4;
   - a point off the curve is not accepted: Newton told to stop on a loose test (-hbm_snes_rtol 0.9) reports
     convergence, JRHBMSolve does not;
   - the case where the step test once accepted non-solutions (H = 7, 1024 samples, -cont_step_max 0.02): the curve
     completes and every point meets the residual tolerance.
   Runs on 1 and 2 ranks (the elements split across ranks); the time integration, a serial reference, on 1.
*/
#include "jrtest_problem.h"
#include <slepcsys.h>
#include <complex.h>

/* the jenkins element's describing function: force = N(A) x for x = A cos(w t), N = Kr + i Ki (slip force fs) */
static double complex Describing(double kt, double fs, double A)
{
  double b, kr, ki;
  if (A <= fs / kt) return kt;
  b  = acos(1.0 - 2.0 * fs / (kt * A));
  kr = kt / M_PI * (b - 0.5 * sin(2.0 * b));
  ki = 4.0 * fs / (M_PI * A) * (1.0 - fs / (kt * A));
  return kr + I * ki;
}

/* a small n-DOF system with one jenkins element from DOF j to ground, force F at DOF 0 */
typedef struct {
  int           n, j;
  const double *K, *M, *C;
  double        kt, fs, F;
} Sys;

/* X = (K - w^2 M + i w C + N e_j e_j^T)^-1 F e_0, by Gaussian elimination (n <= 4) */
static void Solve(const Sys *s, double w, double complex N, double complex *X)
{
  double complex A[4][5];
  const int      n = s->n;
  for (int r = 0; r < n; r++) {
    for (int c = 0; c < n; c++) A[r][c] = s->K[r * n + c] - w * w * s->M[r * n + c] + I * w * s->C[r * n + c];
    A[r][n] = r == 0 ? s->F : 0.0;
  }
  A[s->j][s->j] += N;
  for (int p = 0; p < n; p++) {
    int q = p;
    for (int r = p + 1; r < n; r++)
      if (cabs(A[r][p]) > cabs(A[q][p])) q = r;
    for (int c = 0; c <= n; c++) {
      double complex t = A[p][c];
      A[p][c]          = A[q][c];
      A[q][c]          = t;
    }
    for (int r = p + 1; r < n; r++) {
      const double complex f = A[r][p] / A[p][p];
      for (int c = p; c <= n; c++) A[r][c] -= f * A[p][c];
    }
  }
  for (int r = n - 1; r >= 0; r--) {
    double complex t = A[r][n];
    for (int c = r + 1; c < n; c++) t -= A[r][c] * X[c];
    X[r] = t / A[r][r];
  }
}

/* |X_j(w; A)| - A: zero on the curve */
static double Gap(const Sys *s, double w, double A)
{
  double complex X[4];
  Solve(s, w, Describing(s->kt, s->fs, A), X);
  return cabs(X[s->j]) - A;
}

/* The exact H = 1 curve at w: the largest amplitude A at the element on it (the upper branch where the curve folds),
   and the amplitude at DOF o; bisection to round-off from a scan of A over 24 decades */
static double Curve(const Sys *s, double w, int o, double *Aj)
{
  double         lo = 0, hi = 0, glo, A, amax = 1e3;
  double complex X[4];
  glo = Gap(s, w, 1e-15);
  for (int i = 1; i <= 480; i++) {
    const double a = 1e-15 * pow(10.0, 18.0 * i / 480.0), g = Gap(s, w, a);
    if (a > amax) break;
    if ((g < 0) != (glo < 0)) {
      lo = 1e-15 * pow(10.0, 18.0 * (i - 1) / 480.0);
      hi = a;
    }
    glo = g;
  }
  if (hi == 0) return -1; /* no root: cannot happen for these systems */
  for (int it = 0; it < 200 && hi - lo > 1e-16 * hi; it++) {
    const double m = 0.5 * (lo + hi);
    if ((Gap(s, w, m) < 0) == (Gap(s, w, lo) < 0)) lo = m;
    else hi = m;
  }
  A = 0.5 * (lo + hi);
  Solve(s, w, Describing(s->kt, s->fs, A), X);
  if (Aj) *Aj = A;
  return cabs(X[o]);
}

/* The maximum of the exact curve's amplitude at DOF o over [wa, wb]: a scan of 1500 frequencies, then golden
   section between the neighbours of the largest */
static void ExactPeak(const Sys *s, int o, double wa, double wb, double *wp, double *Ap)
{
  const int np = 1500;
  int       k  = 0;
  double    best = -1, a, b, x1, x2, f1, f2;
  for (int i = 0; i <= np; i++) {
    const double w = wa + (wb - wa) * i / np, A = Curve(s, w, o, NULL);
    if (A > best) {
      best = A;
      k    = i;
    }
  }
  a  = wa + (wb - wa) * (k > 0 ? k - 1 : 0) / np;
  b  = wa + (wb - wa) * (k < np ? k + 1 : np) / np;
  x1 = b - 0.618033988749895 * (b - a);
  x2 = a + 0.618033988749895 * (b - a);
  f1 = Curve(s, x1, o, NULL);
  f2 = Curve(s, x2, o, NULL);
  for (int it = 0; it < 200 && b - a > 1e-13 * b; it++) {
    if (f1 < f2) {
      a  = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + 0.618033988749895 * (b - a);
      f2 = Curve(s, x2, o, NULL);
    } else {
      b  = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - 0.618033988749895 * (b - a);
      f1 = Curve(s, x1, o, NULL);
    }
  }
  *wp = 0.5 * (a + b);
  *Ap = Curve(s, *wp, o, NULL);
}

/* The 1-DOF system marched in time (RK4, nstep steps per cycle, the slip projected after each step) from the state
   (x, v, slip) until the first harmonic changes by less than 1e-11 per cycle: its amplitude */
static double MarchAmplitude(double m, double c, double k, double kt, double fs, double F, double w, int nstep, double st[3])
{
  const double T = 2.0 * M_PI / w, dt = T / nstep;
  double       x = st[0], v = st[1], s = st[2], prev = -1, amp = 0;
  for (int cyc = 0; cyc < 4000; cyc++) {
    double sn = 0, cs = 0;
    for (int i = 0; i < nstep; i++) {
      const double t = i * dt; /* the phase within the cycle: the force is periodic */
      JenkinsOscillatorStep(m, c, k, kt, fs, F, w, t, dt, &x, &v, &s);
      sn += 2.0 * x * sin(w * (t + dt)) / nstep;
      cs += 2.0 * x * cos(w * (t + dt)) / nstep;
    }
    amp = sqrt(sn * sn + cs * cs);
    if (cyc > 20 && fabs(amp - prev) < 1e-11 * amp) break;
    prev = amp;
  }
  st[0] = x;
  st[1] = v;
  st[2] = s;
  return amp;
}

/* The time integration's first-harmonic amplitude at w, extrapolated to a zero step: the slip projected at the end of
   each step makes the march first-order accurate, so (4 A(4 nstep) - A(nstep)) / 3 (Richardson); st: the two marches'
   states, carried from one frequency to the next */
static double MarchExtrapolated(double m, double c, double k, double kt, double fs, double F, double w, int nstep, double st[6])
{
  const double a1 = MarchAmplitude(m, c, k, kt, fs, F, w, nstep, st), a4 = MarchAmplitude(m, c, k, kt, fs, F, w, 4 * nstep, st + 3);
  return (4 * a4 - a1) / 3;
}

/* Its largest value over [wa, wb] by golden section */
static void MarchPeak(double m, double c, double k, double kt, double fs, double F, double wa, double wb, int nstep, double *wp, double *Ap)
{
  double st[6] = {0, 0, 0, 0, 0, 0}, a = wa, b = wb, x1, x2, f1, f2;
  x1 = b - 0.618033988749895 * (b - a);
  x2 = a + 0.618033988749895 * (b - a);
  f1 = MarchExtrapolated(m, c, k, kt, fs, F, x1, nstep, st);
  f2 = MarchExtrapolated(m, c, k, kt, fs, F, x2, nstep, st);
  for (int it = 0; it < 60 && b - a > 1e-7 * b; it++) {
    if (f1 < f2) {
      a  = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + 0.618033988749895 * (b - a);
      f2 = MarchExtrapolated(m, c, k, kt, fs, F, x2, nstep, st);
    } else {
      b  = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - 0.618033988749895 * (b - a);
      f1 = MarchExtrapolated(m, c, k, kt, fs, F, x1, nstep, st);
    }
  }
  *wp = 0.5 * (a + b);
  *Ap = MarchExtrapolated(m, c, k, kt, fs, F, *wp, nstep, st);
}

/* The H = 1 curves of a system at the levels F[] against the exact describing-function curve: peaks, every point on
   the relation |X_j| = A, linear interpolation at 1/4, 1/2, 3/4 between consecutive points */
static PetscErrorCode CheckH1(const char *name, Sys s, int nlev, const double *F, double wa, double wb, const char *extra)
{
  Problem p;
  char    opts[512], lv[256] = "";
  double  worstpk = 0, worstw = 0, worstrel = 0, worstint = 0;
  PetscInt npts = 0;

  PetscFunctionBeginUser;
  for (int l = 0; l < nlev; l++) PetscCall(PetscSNPrintf(lv + strlen(lv), sizeof(lv) - strlen(lv), "%s%g", l ? "," : "", F[l]));
  PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_harmonics 1 -hbm_samples 4096 -frf_omega_min %.12g -frf_omega_max %.12g -frf_force %s -frf_output 0,%d %s", wa, wb, lv, s.j, extra));
  PetscCall(Options(opts));
  {
    const double zero[16] = {0};
    El           e        = {"jenkins", s.j, -1, -1, -1, s.kt, 0, 1.0, s.fs};
    PetscCall(ProblemCreate(s.n, s.K, s.M, s.C ? s.C : zero, 1, &e, &p));
  }
  PetscCall(JRContSolve(p.cont));
  for (int l = 0; l < nlev; l++) {
    PetscReal        w, A, wr, Ar;
    PetscInt         np;
    const PetscReal *om, *amp;
    s.F = F[l];
    PetscCall(JRContGetPeak(p.cont, l, &w, &A));
    ExactPeak(&s, 0, wa, wb, &wr, &Ar);
    worstpk = PetscMax(worstpk, PetscAbsReal(A / Ar - 1));
    worstw  = PetscMax(worstw, PetscAbsReal(w / wr - 1));
    PetscCall(JRContGetBranch(p.cont, l, &np, &om, NULL, &amp));
    npts += np;
    for (PetscInt i = 0; i < np; i++) { /* the point on the relation: |X_j(w; A_j)| = A_j with its own A_j */
      double complex X[4];
      Solve(&s, om[i], Describing(s.kt, s.fs, amp[2 * i + 1]), X);
      worstrel = PetscMax(worstrel, PetscAbsReal(cabs(X[s.j]) / amp[2 * i + 1] - 1));
      worstrel = PetscMax(worstrel, PetscAbsReal(cabs(X[0]) / amp[2 * i] - 1));
    }
    for (PetscInt i = 0; i + 1 < np; i++) { /* chords against the curve, where the frequency steps forward */
      if (om[i + 1] <= om[i]) continue;
      for (int q = 1; q <= 3; q++) {
        const double t = 0.25 * q, w = (1 - t) * om[i] + t * om[i + 1], li = (1 - t) * amp[2 * i] + t * amp[2 * i + 2];
        const double ex = Curve(&s, w, 0, NULL);
        if (ex > 0 && PetscAbsReal(li / ex - 1) > worstint) {
          worstint = PetscAbsReal(li / ex - 1);
          if (getenv("JR_DEBUG")) printf("# interp F %g between %.8g %.8g (amps %.6e %.6e) at %.8g: %.6e vs %.6e\n", s.F, om[i], om[i + 1], amp[2 * i], amp[2 * i + 2], w, li, ex);
        }
      }
    }
  }
  CHECK(worstpk <= 1e-5 && worstw <= 1e-5, "%s, H = 1, %d levels %s N: peaks vs the describing function's exact maximum: amplitude within %.1e, frequency within %.1e (<= 1e-5)", name, nlev, lv, worstpk, worstw);
  CHECK(worstrel <= 1e-6, "%s, H = 1: every one of %" PetscInt_FMT " points on the describing-function relation |X_j(w; N(A_j))| = A_j, and at the output: worst %.1e (<= 1e-6)", name, npts, worstrel);
  CHECK(worstint <= 0.01, "%s, H = 1: linear interpolation between consecutive points within %.2f%% of the exact curve (<= 1%%; %" PetscInt_FMT " points)", name, 100 * worstint, npts);
  PetscCall(ProblemDestroy(&p));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscCall(SlepcInitialize(&argc, &argv, NULL, NULL));
  { /* 1-DOF: m = 1 kg, k = 1e4 N/m, c = 0.5656854249 N s/m, jenkins kt = 1e4 N/m, slip force 1 N */
    const double K1[1] = {1e4}, M1[1] = {1}, C1[1] = {0.5656854249};
    const double F1[]  = {0.005, 0.05, 0.1, 0.5, 1.0, 1.2, 2.0};
    Sys          s     = {1, 0, K1, M1, C1, 1e4, 1.0, 0};
    PetscCall(CheckH1("1-DOF jenkins oscillator", s, 7, F1, 84.8528137424, 183.847763109, ""));
  }
  { /* 2-DOF chain: m1 = m2 = 1 kg, k1 = k2 = 1e4 N/m, jenkins kt = 5e3 N/m, slip force 0.5 N from m2 to ground,
       Rayleigh damping of 0.5% in both stuck modes, force on m1 */
    const double K2[4] = {2e4, -1e4, -1e4, 1e4}, M2[4] = {1, 0, 0, 1};
    double       C2[4], w1, w2, al, be;
    const double F2[] = {0.0005, 0.005, 0.05, 0.2, 0.5, 1.0, 3.0};
    { /* stuck modes: K + kt e2 e2^T = [2e4 -1e4; -1e4 1.5e4] */
      const double tr = 3.5e4, det = 2e4 * 1.5e4 - 1e8, d = sqrt(tr * tr / 4 - det);
      w1 = sqrt(tr / 2 - d);
      w2 = sqrt(tr / 2 + d);
    }
    al = 2 * 0.005 * w1 * w2 / (w1 + w2);
    be = 2 * 0.005 / (w1 + w2);
    C2[0] = al + be * 2e4;
    C2[1] = C2[2] = -be * 1e4;
    C2[3] = al + be * 1.5e4;
    {
      Sys s = {2, 1, K2, M2, C2, 5e3, 0.5, 0};
      PetscCall(CheckH1("2-DOF chain", s, 7, F2, 50, 100, ""));
    }
  }
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  if (size == 1) { /* H = 15 against time integration (1-DOF, microslip and near gross slip); a serial reference, run
                      once: on 2 ranks the curves' own checks above and below repeat */
    const double K1[1] = {1e4}, M1[1] = {1}, C1[1] = {0.5656854249}, F[] = {0.1, 1.0};
    Problem      p;
    El           e = {"jenkins", 0, -1, -1, -1, 1e4, 0, 1.0, 1.0};
    PetscCall(Options("-hbm_harmonics 15 -hbm_samples 1024 -frf_omega_min 84.8528137424 -frf_omega_max 183.847763109 -frf_force 0.1,1"));
    PetscCall(ProblemCreate(1, K1, M1, C1, 1, &e, &p));
    PetscCall(JRContSolve(p.cont));
    for (int l = 0; l < 2; l++) {
      PetscReal w, A;
      double    wt, At;
      PetscCall(JRContGetPeak(p.cont, l, &w, &A));
      double    st[6] = {0, 0, 0, 0, 0, 0}, Aw;
      MarchPeak(1, 0.5656854249, 1e4, 1e4, 1.0, F[l], 0.97 * w, 1.03 * w, 10000, &wt, &At);
      Aw = MarchExtrapolated(1, 0.5656854249, 1e4, 1e4, 1.0, F[l], w, 10000, st); /* on a flat top the frequency is loosely defined: the march at the HBM's */
      CHECK(PetscAbsReal(A / At - 1) <= 1e-4 && (PetscAbsReal(w / wt - 1) <= 1e-4 || Aw >= (1 - 1e-6) * At), "1-DOF jenkins oscillator, F = %g N, H = 15: peak %.7g rad/s, %.7e m vs time integration's (RK4, 10000 and 40000 steps per cycle extrapolated, golden section) %.7g rad/s, %.7e m: amplitude %.1e, frequency %.1e (<= 1e-4; or the march's amplitude at the HBM's peak frequency within 1e-6 of its maximum: %.1e)", F[l], (double)w, (double)A, wt, At, PetscAbsReal(A / At - 1), PetscAbsReal(w / wt - 1), 1 - Aw / At);
    }
    PetscCall(ProblemDestroy(&p));
  }
  { /* the step test once accepted non-solutions here: every point now a solution, the curve complete */
    const double K1[1] = {1e4}, M1[1] = {1}, C1[1] = {0.5656854249};
    Problem      p;
    El           e = {"jenkins", 0, -1, -1, -1, 1e4, 0, 1.0, 1.0};
    PetscInt     np;
    PetscReal    tol, worst = 0, w, A;
    PetscBool    complete;
    Vec          a, R;
    PetscCall(Options("-hbm_harmonics 7 -hbm_samples 1024 -frf_omega_min 84.8528137424 -frf_omega_max 183.847763109 -frf_force 0.1 -cont_step_max 0.02"));
    PetscCall(ProblemCreate(1, K1, M1, C1, 1, &e, &p));
    PetscCall(JRContSolve(p.cont));
    PetscCall(JRHBMGetResidualTolerance(p.hbm, &tol));
    PetscCall(JRHBMCreateVecs(p.hbm, &a, NULL));
    PetscCall(VecDuplicate(a, &R));
    {
      const PetscReal *om, *x;
      PetscCall(JRContGetBranch(p.cont, 0, &np, &om, &x, NULL));
      for (PetscInt i = 0; i < np; i++) { /* the residual of every point, evaluated afresh */
        PetscScalar *v;
        PetscReal    rel;
        PetscCall(VecGetArray(a, &v));
        for (PetscInt j = 0; j < 15; j++) v[j] = x[i * 15 + j];
        PetscCall(VecRestoreArray(a, &v));
        PetscCall(JRHBMComputeResidual(p.hbm, om[i], a, R));
        PetscCall(JRHBMResidualNorm(p.hbm, R, &rel));
        worst = PetscMax(worst, rel);
      }
    }
    PetscCall(JRContGetPeak(p.cont, 0, &w, &A));
    PetscCall(JRContGetLevelComplete(p.cont, 0, &complete, NULL));
    CHECK(worst <= tol && complete, "H = 7, -cont_step_max 0.02 (where the step test accepted points with residual 0.2): the curve completes, %" PetscInt_FMT " points, every residual <= %.0e: worst %.1e; peak %.6g rad/s", np, (double)tol, (double)worst, (double)w);
    { /* a point off the curve: Newton stopped by a loose step test says converged; JRHBMSolve does not accept it */
      PetscInt            its;
      PetscBool           conv;
      SNES                snes;
      SNESConvergedReason reason;
      PetscReal           res;
      const PetscReal *om, *x, *amp;
      PetscInt         kp = 0;
      PetscScalar     *v;
      PetscCall(JRContGetBranch(p.cont, 0, &np, &om, &x, &amp));
      for (PetscInt i = 1; i < np; i++)
        if (amp[i] > amp[kp]) kp = i;
      PetscCall(VecGetArray(a, &v));
      for (PetscInt j = 0; j < 15; j++) v[j] = 1.3 * x[kp * 15 + j]; /* the peak's unknowns, 30% off */
      PetscCall(VecRestoreArray(a, &v));
      PetscCall(JRHBMGetSNES(p.hbm, &snes));
      PetscCall(SNESSetTolerances(snes, 1e-300, 0.9, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
      PetscCall(JRHBMSolveResidual(p.hbm, om[kp], a, &its, &conv, &res));
      PetscCall(SNESGetConvergedReason(snes, &reason));
      CHECK(reason > 0 && !conv && res > tol, "a point perturbed off the curve, Newton with -hbm_snes_rtol 0.9 (stops once the residual fell by 10%%): the SNES says %s, the solve does not accept it (relative residual %.1e > %.0e)", SNESConvergedReasons[reason], (double)res, (double)tol);
    }
    PetscCall(VecDestroy(&a));
    PetscCall(VecDestroy(&R));
    PetscCall(ProblemDestroy(&p));
  }
  PetscCall(SlepcFinalize());
  return jr_fail ? 1 : 0;
}
