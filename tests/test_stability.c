/*
   Stability by Hill's method (JRHBMFloquet, JRContStability) against independent truths:
   - a linear 3-DOF system with viscous damping (no elements): the kept Floquet exponents are the eigenvalues of
     K + lambda C + lambda^2 M (LAPACK on the physical matrices, here) modulo i k w, to 1e-8; the eigenvector
     criterion gives them unshifted even for a mode above (H + 1/2) w; SLEPc's PEP path agrees;
   - a Duffing oscillator with two folds: the middle branch unstable, the outer branches stable; a direct time
     integration (RK4, here) from a middle-branch point's state leaves it, from stable points' states stays; the folds
     reported at the extremes of the single-harmonic relation's frequency (H = 1), to 1e-3;
   - a friction oscillator with a gap (jenkins_nv closing on impact: hardening, two folds): flags against the same
     time integration, the element marched as a play operator;
   - the Floquet exponents in time (JRHBMFloquetTime, the path of points with friction elements changing state)
     against the eigenvalues of the linear system and against Hill's method with every exponent computed (QZ) on the
     Duffing oscillator, where Hill's method is exact: the same largest real part and the same flag at every point;
   - a Jenkins oscillator (constant normal load): every point stable by incremental dissipativity; at its peak and
     where Hill's method differs most, the exponents in time against the monodromy matrix of an RK4 march of the
     element's play operator (by differences, on the orbit the march settles on); and through full stick and
     grazing slip the exponents in time flag no point unstable, as incremental dissipativity proves;
   - a symmetric 3-DOF system forced on its axis (cubic springs on the two equal outer masses), whose symmetric branch
     loses and regains its stability to antisymmetric motion: at H = 1 the two branch points reported within 1e-5 of
     where the single-harmonic Jacobian's antisymmetric block is singular (a closed form on the symmetric branch, solved
     here), none at a force where it never is; at H = 3 within 1e-5 of where the antisymmetric Floquet exponent of the
     full equations (RK4 monodromy about each point's motion, here) changes sign; the curve stays symmetric through
     them, its points unstable exactly between them, and RK4 of the full equations from the most unstable point's state
     with x1 - x2 perturbed grows at that point's largest real part (to 5%), 1% outside the branch points decays.
   Every rank checks the same numbers (also run on 2 ranks).
*/
#include "jrtest_problem.h"
#include <slepcsys.h>
#include <slepcblaslapack.h>

/* the exponents of K + l C + l^2 M (n x n, row-major, n <= 4) by QZ on [0 I; -K -C] z = l [I 0; 0 M] z */
static PetscErrorCode QEPEigenvalues(PetscInt n, const double *K, const double *C, const double *M, double *lr, double *li)
{
  PetscBLASInt N = (PetscBLASInt)(2 * n), one = 1, lw = 256, info;
  double       A[64] = {0}, B[64] = {0}, be[8], vl[1], vr[1], work[256];

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) {
    A[i + (n + i) * N] = 1.0;
    B[i + i * N]       = 1.0;
    for (PetscInt j = 0; j < n; j++) {
      A[(n + i) + j * N]       = -K[i * n + j];
      A[(n + i) + (n + j) * N] = -C[i * n + j];
      B[(n + i) + (n + j) * N] = M[i * n + j];
    }
  }
  PetscCallBLAS("LAPACKggev", LAPACKggev_("N", "N", &N, A, &N, B, &N, lr, li, be, vl, &one, vr, &one, work, &lw, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "ggev %d", (int)info);
  for (PetscInt i = 0; i < 2 * n; i++) {
    lr[i] /= be[i];
    li[i] /= be[i];
  }
  PetscFunctionReturn(0);
}

/* the worst, over the exponents kept (nk), of the distance to the nearest eigenvalue mu + i k w (|k| <= kmax), relative
   to |mu|; and the same the other way (every eigenvalue found) */
static double MatchError(PetscInt nk, const PetscReal *re, const PetscReal *im, PetscInt ne, const double *lr, const double *li, double w, PetscInt kmax)
{
  double worst = 0.0;
  for (int pass = 0; pass < 2; pass++) {
    const PetscInt na = pass ? ne : nk, nb = pass ? nk : ne;
    for (PetscInt i = 0; i < na; i++) {
      double best = PETSC_MAX_REAL;
      for (PetscInt j = 0; j < nb; j++)
        for (PetscInt k = -kmax; k <= kmax; k++) {
          const double xr = pass ? lr[i] : re[i], xi = pass ? li[i] : im[i], yr = pass ? re[j] : lr[j], yi = pass ? im[j] : li[j];
          const double d  = hypot(xr - yr, xi - yi - (pass ? -1 : 1) * k * w) / hypot(pass ? xr : yr, pass ? xi : yi);
          best            = fmin(best, d);
        }
      worst = fmax(worst, best);
    }
  }
  return worst;
}

/* one-DOF oscillator x'' + c x' + k x + g(x, state) = F sin(w t): a cubic spring k3 x^3, or a jenkins_nv element on the
   same motion (u = v = x) with gap: n = max(0, n0 + kn x), friction kt (x - s) with |.| <= mu n, its slip s committed
   after every step (the play operator) */
typedef struct {
  double m, c, k, F, k3, kt, kn, mu, n0;
  int    friction;
} Osc;

static double Force(const Osc *o, double x, double s)
{
  if (!o->friction) return o->k3 * x * x * x;
  {
    const double n = fmax(0.0, o->n0 + o->kn * x), r = o->mu * n / o->kt;
    const double sc = fmin(fmax(s, x - r), x + r);
    return n + o->kt * (x - sc);
  }
}

static double Slip(const Osc *o, double x, double s)
{
  const double n = fmax(0.0, o->n0 + o->kn * x), r = o->mu * n / o->kt;
  return fmin(fmax(s, x - r), x + r);
}

/* RK4 from the harmonic-balance point's state at t = 0 (a: [a0 | as_1 ac_1 | ...], H harmonics; the slip from one
   period of the point's motion marched as the play operator) over P periods at ns steps each: the first-harmonic
   amplitude of the last period, relative to the point's, minus 1 */
static double Integrate(const Osc *o, double w, PetscInt H, const PetscReal *a, PetscInt P, PetscInt ns)
{
  const double T = 2 * PETSC_PI / w, dt = T / ns;
  double       x = a[0], v = 0.0, s = 0.0, A0 = hypot(a[1], a[2]), fs = 0.0, fc = 0.0;

  for (PetscInt h = 1; h <= H; h++) {
    x += a[2 * h];
    v += h * w * a[2 * h - 1];
  }
  if (o->friction) { /* the slip at t = 0: two periods of the point's motion */
    for (PetscInt j = 0; j <= 2 * ns; j++) {
      double xj = a[0];
      for (PetscInt h = 1; h <= H; h++) xj += a[2 * h - 1] * sin(h * w * j * dt) + a[2 * h] * cos(h * w * j * dt);
      s = Slip(o, xj, s);
    }
  }
  for (PetscInt p = 0; p < P; p++) {
    fs = fc = 0.0;
    for (PetscInt j = 0; j < ns; j++) {
      const double t = j * dt;
      double       k1x, k1v, k2x, k2v, k3x, k3v, k4x, k4v;
#define ACC(tt, xx, vv) ((o->F * sin(w * (tt)) - o->c * (vv) - o->k * (xx) - Force(o, (xx), s)) / o->m)
      k1x = v;
      k1v = ACC(t, x, v);
      k2x = v + 0.5 * dt * k1v;
      k2v = ACC(t + 0.5 * dt, x + 0.5 * dt * k1x, v + 0.5 * dt * k1v);
      k3x = v + 0.5 * dt * k2v;
      k3v = ACC(t + 0.5 * dt, x + 0.5 * dt * k2x, v + 0.5 * dt * k2v);
      k4x = v + dt * k3v;
      k4v = ACC(t + dt, x + dt * k3x, v + dt * k3v);
#undef ACC
      fs += x * sin(w * t);
      fc += x * cos(w * t);
      x += dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      if (o->friction) s = Slip(o, x, s);
      if (!isfinite(x) || fabs(x) > 1e3 * A0) return PETSC_INFINITY;
    }
  }
  return hypot(2 * fs / ns, 2 * fc / ns) / A0 - 1.0;
}


/* The single-harmonic Duffing relation ((k - m w^2 + 3/4 k3 A^2)^2 + (c w)^2) A^2 = F^2: its higher frequency at
   amplitude A (0 where none) */
static double DuffingUpper(const Osc *o, double A)
{
  const double g = o->k + 0.75 * o->k3 * A * A, c2 = o->c * o->c / o->m, disc = (2 * g / o->m - c2) * (2 * g / o->m - c2) - 4 * (g * g / (o->m * o->m) - o->F * o->F / (o->m * o->m * A * A));
  if (disc < 0) return 0.0;
  return sqrt(0.5 * ((2 * g / o->m - c2) + sqrt(disc)));
}

/* Its folds: along the curve the upper frequency falls with the amplitude (lower branch) to the left fold, rises
   (middle branch) to the right fold, then falls to the peak, where the two frequencies meet; the left fold by a scan and
   golden section, the right one by golden section between it and the peak (found by bisection) */
static double Golden(const Osc *o, double a, double b, int maximum)
{
  const double gr = 0.5 * (sqrt(5.0) - 1);
  for (int it = 0; it < 200; it++) {
    const double x1 = b - gr * (b - a), x2 = a + gr * (b - a), f1 = DuffingUpper(o, x1), f2 = DuffingUpper(o, x2);
    if (maximum ? f1 > f2 : f1 < f2) b = x2;
    else a = x1;
  }
  return 0.5 * (a + b);
}

static void DuffingFolds(const Osc *o, double *wright, double *wleft)
{
  double         lo = 1e-5, hi = 1.0, Al, Amin = 0, wmin = PETSC_MAX_REAL;
  const PetscInt n = 20000;
  for (int it = 0; it < 200; it++) { /* the peak: the largest amplitude with a solution */
    const double mid = 0.5 * (lo + hi);
    if (DuffingUpper(o, mid) > 0) lo = mid;
    else hi = mid;
  }
  for (PetscInt i = 1; i < n; i++) {
    const double A = lo * i / n, wv = DuffingUpper(o, A);
    if (wv > 0 && wv < wmin) {
      wmin = wv;
      Amin = A;
    }
  }
  Al      = Golden(o, Amin - lo / n, Amin + lo / n, 0);
  *wleft  = DuffingUpper(o, Al);
  *wright = DuffingUpper(o, Golden(o, Al, lo, 1));
}

/* The folded oscillator's checks: the middle branch's most unstable point leaves under time integration, a stable
   point on each outer branch stays; every rank has the same flags */
static PetscErrorCode FoldedCase(const char *name, const Osc *o, const char *opts, PetscInt H, double stay, PetscInt P, PetscInt ns, Problem *p)
{
  PetscInt         np, nf, nb, ku = -1, kup = -1, klo = -1, nun = 0, n;
  const PetscReal *om, *a, *amp, *mr, *wf;
  const PetscInt  *st;
  double           wmax = 0, dmid, dup, dlo;
  PetscMPIInt      size;

  PetscFunctionBeginUser;
  PetscCall(Options(opts));
  PetscCall(ProblemCreate(1, (double[]){o->k}, (double[]){o->m}, (double[]){o->c}, 1, (El[]){{o->friction ? "jenkins_nv" : "cubic", 0, -1, o->friction ? 0 : -1, -1, o->friction ? o->kt : o->k3, o->kn, o->mu, o->n0}}, p));
  PetscCall(JRContSolve(p->cont));
  PetscCall(JRContGetBranch(p->cont, 0, &np, &om, &a, &amp));
  PetscCall(JRContGetStability(p->cont, 0, &st, &mr, &nf, &wf, &nb, NULL));
  PetscCall(JRHBMGetSolveSize(p->hbm, &n, NULL));
  PetscCheck(st && mr, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%s: no stability computed", name);
  /* the folds along the curve: the largest frequency, then back; the middle branch between them */
  {
    PetscInt kf = 0, kmin = 0;
    for (PetscInt k = 1; k < np - 1 && !kf; k++)
      if (om[k] > om[k - 1] && om[k] >= om[k + 1]) kf = k;
    wmax = om[kf];
    kmin = kf;
    for (PetscInt k = kf; k < np - 1 && om[k + 1] < om[k]; k++) kmin = k + 1;
    for (PetscInt k = kf + 2; k < kmin - 1; k++) {
      if (!st[k]) nun++;
      if (ku < 0 || mr[k] > mr[ku]) ku = k;
    }
    /* stable references: on the upper branch at 97% of the right fold's frequency, on the lower branch there too */
    for (PetscInt k = 0; k < kf; k++)
      if (kup < 0 || fabs(om[k] - 0.97 * wmax) < fabs(om[kup] - 0.97 * wmax)) kup = k;
    for (PetscInt k = kmin; k < np; k++)
      if (klo < 0 || fabs(om[k] - 0.97 * wmax) < fabs(om[klo] - 0.97 * wmax)) klo = k;
    {
      PetscInt outer_unstable = 0;
      for (PetscInt k = 0; k < kf - 1; k++) outer_unstable += !st[k];
      for (PetscInt k = kmin + 2; k < np; k++) outer_unstable += !st[k];
      CHECK(nf == 2 && nun == kmin - kf - 3 && outer_unstable == 0, "%s: the stability analysis finds the %" PetscInt_FMT " middle-branch points between the %" PetscInt_FMT " folds unstable (%" PetscInt_FMT " of them flagged) and the outer branches stable (%" PetscInt_FMT " flagged unstable of %" PetscInt_FMT ")", name, kmin - kf - 3, nf, nun, outer_unstable, np - (kmin - kf) - 1);
    }
  }
  PetscCheck(ku >= 0 && kup >= 0 && klo >= 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%s: no middle branch", name);
  dmid = Integrate(o, om[ku], H, a + ku * n, P, ns);
  dup  = Integrate(o, om[kup], H, a + kup * n, P, ns);
  dlo  = Integrate(o, om[klo], H, a + klo * n, P, ns);
  CHECK(!st[ku] && fabs(dmid) > 0.1, "%s: middle branch at %.4f Hz (largest Re %.3g 1/s, flagged unstable): RK4 from its state, %" PetscInt_FMT " periods: the amplitude changes by %.3g (> 10%%)", name, om[ku] / (2 * PETSC_PI), mr[ku], P, dmid);
  CHECK(st[kup] && st[klo] && fabs(dup) < stay && fabs(dlo) < stay, "%s: upper and lower branch at %.4f and %.4f Hz (flagged stable, largest Re %.3g, %.3g 1/s): RK4 from their states stays (amplitude change %.1e, %.1e < %.0e)", name, om[kup] / (2 * PETSC_PI), om[klo] / (2 * PETSC_PI), mr[kup], mr[klo], dup, dlo, stay);
  {
    PetscInt sum = 0, smin, smax;
    for (PetscInt k = 0; k < np; k++) sum = sum * 3 + st[k];
    PetscCallMPI(MPI_Allreduce(&sum, &smin, 1, MPIU_INT, MPI_MIN, PETSC_COMM_WORLD));
    PetscCallMPI(MPI_Allreduce(&sum, &smax, 1, MPIU_INT, MPI_MAX, PETSC_COMM_WORLD));
    PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
    CHECK(smin == smax, "%s: the same %" PetscInt_FMT " flags on all %d ranks", name, np, (int)size);
  }
  PetscFunctionReturn(0);
}

/* A symmetric 3-DOF system: mass m0 (DOF 0, forced, viscous c0 and a spring k0 to ground) joined by springs kc to the
   equal masses m (DOFs 1, 2), each held to ground by a spring kg, a damper c and a cubic spring knl. The forcing keeps
   x1 = x2 (an invariant subspace). With one harmonic, x1 = Re(X e^{i w t}), x0 = Re(X0 e^{i w t}), s = |X|^2, the
   symmetric balance is
       D0 X0 - 2 kc X = F,   -kc X0 + (Da + 3/4 knl s) X = 0,   D0 = k0 + 2 kc - m0 w^2 + i c0 w,  Da = ka - m w^2 + i c w,
   ka = kc + kg, so that |alpha + beta s|^2 s = F^2 with alpha = D0 Da / kc - 2 kc, beta = 3/4 knl D0 / kc: a cubic in
   s. The antisymmetric motion y = x1 - x2 linearised about it, m y'' + c y' + ka y + 3 knl x1^2 y = 0, has the first
   harmonic P Y + Q conj(Y) = 0 (x1^2 y's first harmonic is s/2 Y + X^2/4 conj(Y)), P = Da + 3/2 knl s, |Q| = 3/4 knl s:
   the harmonic-balance Jacobian's antisymmetric block, Y -> P Y + Q conj(Y) as a real 2 x 2 map of determinant
   |P|^2 - |Q|^2, is singular where |P| = |Q|: the branch points, where the symmetric branch loses or regains its
   stability to antisymmetric motion. */
typedef struct {
  double m0, m, k0, kc, kg, c0, c, knl, F;
} Sym3;

/* s = |X1|^2 on the symmetric branch at w: the root of p(s) = |alpha + beta s|^2 s - F^2 by bisection; *single: it is
   the only root (p' = |alpha|^2 + 4 Re(alpha conj(beta)) s + 3 |beta|^2 s^2 has no positive root, or p's local maximum
   is below zero or its local minimum above), so that the branch has one point at w */
static double SymAmplitude(const Sym3 *o, double w, PetscBool *single)
{
  const double ka = o->kc + o->kg, d0r = o->k0 + 2 * o->kc - o->m0 * w * w, d0i = o->c0 * w, dar = ka - o->m * w * w, dai = o->c * w;
  const double ar = (d0r * dar - d0i * dai) / o->kc - 2 * o->kc, ai = (d0r * dai + d0i * dar) / o->kc;
  const double br = 0.75 * o->knl * d0r / o->kc, bi = 0.75 * o->knl * d0i / o->kc;
  const double a2 = ar * ar + ai * ai, ab = ar * br + ai * bi, b2 = br * br + bi * bi, F2 = o->F * o->F;
  double       lo = 0, hi = 1e-6;
#define P3(s) (((b2 * (s) + 2 * ab) * (s) + a2) * (s) - F2)
  *single = PETSC_TRUE;
  if (ab < 0 && 4 * ab * ab > 3 * a2 * b2) { /* p' = 0 at s1 < s2, both positive: a local maximum and minimum */
    const double s1 = (-2 * ab - PetscSqrtReal(4 * ab * ab - 3 * a2 * b2)) / (3 * b2), s2 = (-2 * ab + PetscSqrtReal(4 * ab * ab - 3 * a2 * b2)) / (3 * b2);
    *single = (PetscBool)(P3(s1) < 0 || P3(s2) > 0);
  }
  while (P3(hi) < 0) hi *= 2;
  for (int it = 0; it < 200; it++) {
    const double mid = 0.5 * (lo + hi);
    if (P3(mid) < 0) lo = mid;
    else hi = mid;
  }
#undef P3
  return 0.5 * (lo + hi);
}

/* (|P|^2 - |Q|^2) / ka^2 on the symmetric branch at w: negative inside the antisymmetric instability */
static double SymBranchFunction(const Sym3 *o, double w, PetscBool *single)
{
  const double s = SymAmplitude(o, w, single), ka = o->kc + o->kg, pr = ka - o->m * w * w + 1.5 * o->knl * s, pi = o->c * w, q = 0.75 * o->knl * s;
  return (pr * pr + pi * pi - q * q) / (ka * ka);
}

/* The reference branch points in [w1, w2]: sign changes of SymBranchFunction on n intervals, bisected; *single: the
   branch has no fold anywhere in the range */
static PetscInt SymBranchPoints(const Sym3 *o, double w1, double w2, PetscInt n, double *wb, PetscInt nmax, PetscBool *single)
{
  PetscInt  nb = 0;
  PetscBool one;
  double    wp = w1, hp = SymBranchFunction(o, w1, single);
  for (PetscInt i = 1; i <= n; i++) {
    const double w = w1 + (w2 - w1) * i / n, h = SymBranchFunction(o, w, &one);
    *single = (PetscBool)(*single && one);
    if (h * hp < 0 && nb < nmax) {
      double lo = wp, hi = w, hlo = hp;
      for (int it = 0; it < 200; it++) {
        const double mid = 0.5 * (lo + hi), hm = SymBranchFunction(o, mid, &one);
        if (hm * hlo > 0) {
          lo  = mid;
          hlo = hm;
        } else hi = mid;
      }
      wb[nb++] = 0.5 * (lo + hi);
    }
    wp = w;
    hp = h;
  }
  return nb;
}

/* RK4 of the full 3-DOF equations from point a's state (H harmonics; x(0) = a0 + sum ac_h, x'(0) = sum h w as_h) with
   x1, x2 pushed apart by +-e (e = 1e-6 |X1|), over P periods at ns steps each: the growth rate [1/s] of the
   antisymmetric perturbation, from the largest |x1 - x2| over period P/2 and over the last one */
static double SymAntisymmetricGrowth(const Sym3 *o, PetscInt H, double w, const PetscReal *a, PetscInt P, PetscInt ns)
{
  const double ka = o->kc + o->kg, dt = 2 * PETSC_PI / w / ns, e = 1e-6 * hypot(a[4], a[7]);
  double       x[3], v[3], ymid = 0.0, ymax = 0.0;

  for (int i = 0; i < 3; i++) {
    x[i] = a[i];
    v[i] = 0.0;
    for (PetscInt h = 1; h <= H; h++) {
      x[i] += a[6 * h + i];
      v[i] += h * w * a[6 * h - 3 + i];
    }
  }
  x[1] += e;
  x[2] -= e;
  for (PetscInt j = 0; j < P * ns; j++) {
    const double t = j * dt;
    double       kx[4][3], kv[4][3];
    for (int st = 0; st < 4; st++) {
      const double h = st == 0 ? 0 : st == 3 ? dt : 0.5 * dt;
      double       y[3], u[3];
      for (int i = 0; i < 3; i++) {
        y[i] = x[i] + (st ? h * kx[st - 1][i] : 0);
        u[i] = v[i] + (st ? h * kv[st - 1][i] : 0);
      }
      kv[st][0] = (o->F * sin(w * (t + h)) - o->c0 * u[0] - (o->k0 + 2 * o->kc) * y[0] + o->kc * (y[1] + y[2])) / o->m0;
      for (int i = 1; i < 3; i++) {
        kv[st][i] = (-o->c * u[i] - ka * y[i] + o->kc * y[0] - o->knl * y[i] * y[i] * y[i]) / o->m;
      }
      for (int i = 0; i < 3; i++) kx[st][i] = u[i];
    }
    for (int i = 0; i < 3; i++) {
      x[i] += dt / 6 * (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]);
      v[i] += dt / 6 * (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]);
    }
    if (j >= (P / 2 - 1) * ns && j < P / 2 * ns) ymid = fmax(ymid, fabs(x[1] - x[2]));
    if (j >= (P - 1) * ns) ymax = fmax(ymax, fabs(x[1] - x[2]));
  }
  return log(ymax / ymid) / ((P - P / 2) * dt * ns);
}

/* The antisymmetric Floquet exponent of the full equations about point a's motion (H harmonics): RK4 over one period
   (ns steps) of the symmetric motion (x0, x1 = x2 from a's state) and of two antisymmetric variations,
   m y'' + c y' + ka y + 3 knl x1^2 y = 0 from (y, y') = (1, 0) and (0, w); the largest log|rho| / T of the 2 x 2
   monodromy matrix's multipliers rho */
static double SymAntisymmetricExponent(const Sym3 *o, PetscInt H, double w, const PetscReal *a, PetscInt ns)
{
  const double ka = o->kc + o->kg, T = 2 * PETSC_PI / w, dt = T / ns;
  double       z[8] = {a[0], 0, a[1], 0, 1, 0, 0, w}, tr, det, disc;

  for (PetscInt h = 1; h <= H; h++) {
    z[0] += a[6 * h];
    z[1] += h * w * a[6 * h - 3];
    z[2] += a[6 * h + 1];
    z[3] += h * w * a[6 * h - 2];
  }
  for (PetscInt j = 0; j < ns; j++) {
    double k[4][8];
    for (int st = 0; st < 4; st++) {
      const double h = st == 0 ? 0 : st == 3 ? dt : 0.5 * dt;
      double       y[8];
      for (int i = 0; i < 8; i++) y[i] = z[i] + (st ? h * k[st - 1][i] : 0);
      k[st][0] = y[1];
      k[st][1] = (o->F * sin(w * (j * dt + h)) - o->c0 * y[1] - (o->k0 + 2 * o->kc) * y[0] + 2 * o->kc * y[2]) / o->m0;
      k[st][2] = y[3];
      k[st][3] = (-o->c * y[3] - ka * y[2] + o->kc * y[0] - o->knl * y[2] * y[2] * y[2]) / o->m;
      for (int c = 4; c < 8; c += 2) {
        k[st][c]     = y[c + 1];
        k[st][c + 1] = (-o->c * y[c + 1] - (ka + 3 * o->knl * y[2] * y[2]) * y[c]) / o->m;
      }
    }
    for (int i = 0; i < 8; i++) z[i] += dt / 6 * (k[0][i] + 2 * k[1][i] + 2 * k[2][i] + k[3][i]);
  }
  tr   = z[4] + z[7] / w; /* the monodromy matrix in (y, y' / w): [z4 z6; z5/w z7/w] */
  det  = z[4] * z[7] / w - z[6] * z[5] / w;
  disc = tr * tr - 4 * det;
  if (disc < 0) return log(det) / (2 * T); /* a complex pair: |rho|^2 = det */
  return log(fmax(fabs(tr + sqrt(disc)), fabs(tr - sqrt(disc))) / 2) / T;
}

/* The symmetric 3-DOF system at H harmonics, force o->F over [f1, f2] Hz, nexpect branch points in the reference: the
   branch points reported against the reference's (H = 1: SymBranchPoints; else where SymAntisymmetricExponent changes
   sign along the traced curve); the traced curve symmetric (x1 = x2: the symmetric subspace is invariant, so the
   continuation stays on it through the branch points); its points unstable exactly between the reference branch points;
   RK4 from the most unstable point's state with an antisymmetric perturbation grows at its largest real part, from
   stable points' 1% outside the branch points it decays */
static PetscErrorCode SymmetricCase(const Sym3 *o, PetscInt H, double f1, double f2, PetscInt nexpect)
{
  const double     ka = o->kc + o->kg, tol = 1e-5;
  const double     K[9] = {o->k0 + 2 * o->kc, -o->kc, -o->kc, -o->kc, ka, 0, -o->kc, 0, ka}, M[9] = {o->m0, 0, 0, 0, o->m, 0, 0, 0, o->m};
  const double     C[9] = {o->c0, 0, 0, 0, o->c, 0, 0, 0, o->c};
  const El         e[2] = {{"cubic", 1, -1, -1, -1, o->knl, 0, 0, 0}, {"cubic", 2, -1, -1, -1, o->knl, 0, 0, 0}};
  Problem          p;
  PetscInt         np, n, nf, nb, nref, bad = 0, nin = 0;
  const PetscReal *om, *a, *wb, *mr;
  const PetscInt  *st;
  double           wref[4], asym = 0.0, err = 0.0;
  PetscBool        single;
  char             opts[256], name[64];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(name, sizeof(name), "symmetric 3-DOF H = %d, F = %d N", (int)H, (int)o->F));
  PetscCall(PetscSNPrintf(opts, sizeof(opts), "-frf_stability -hbm_physical -hbm_harmonics %d -frf_dof 0 -frf_force %g -frf_fmin %g -frf_fmax %g -cont_step_max 0.005", (int)H, o->F, f1, f2));
  PetscCall(Options(opts));
  PetscCall(ProblemCreate(3, K, M, C, 2, e, &p));
  PetscCall(JRContSolve(p.cont));
  PetscCall(JRContGetBranch(p.cont, 0, &np, &om, &a, NULL));
  PetscCall(JRContGetStability(p.cont, 0, &st, &mr, &nf, NULL, &nb, &wb));
  PetscCall(JRHBMGetSolveSize(p.hbm, &n, NULL));
  PetscCheck(st && mr && n == 3 * (2 * H + 1), PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%s: no stability computed, or %" PetscInt_FMT " unknowns (%d expected)", name, n, (int)(3 * (2 * H + 1)));
  if (H == 1) {
    nref = SymBranchPoints(o, 2 * PETSC_PI * f1, 2 * PETSC_PI * f2, 4000, wref, 4, &single);
    PetscCheck(single && nref == nexpect, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%s: the reference has %" PetscInt_FMT " branch points (%" PetscInt_FMT " meant)%s", name, nref, nexpect, single ? "" : " and a fold");
  } else { /* where the full equations' antisymmetric exponent changes sign along the curve, linearly between its points */
    double ep = 0.0;
    nref = 0;
    for (PetscInt k = 0; k < np; k++) {
      const double ek = SymAntisymmetricExponent(o, H, om[k], a + k * n, 400);
      if (k > 0 && ek * ep < 0 && nref < 4) wref[nref++] = om[k - 1] + (om[k] - om[k - 1]) * ep / (ep - ek);
      ep = ek;
    }
    PetscCheck(nref == nexpect, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%s: the full equations' antisymmetric exponent changes sign %" PetscInt_FMT " times along the curve (%" PetscInt_FMT " meant)", name, nref, nexpect);
  }
  for (PetscInt i = 0; i < nb && i < nref; i++) err = fmax(err, fabs(wb[i] - wref[i]) / wref[i]);
  if (nref == 2) {
    CHECK(nb == 2 && err < tol, "%s: %" PetscInt_FMT " branch points reported at %.7g and %.7g Hz; %s at %.7g and %.7g Hz (relative error %.1e < %.0e)", name, nb, nb > 0 ? wb[0] / (2 * PETSC_PI) : 0, nb > 1 ? wb[1] / (2 * PETSC_PI) : 0, H == 1 ? "the single-harmonic reference (|P|^2 = |Q|^2 on the symmetric branch)" : "the full equations' antisymmetric Floquet exponent (RK4 monodromy about the points' motions) changes sign", wref[0] / (2 * PETSC_PI), wref[1] / (2 * PETSC_PI), err, tol);
  } else {
    CHECK(nb == 0, "%s: no branch point reported (%" PetscInt_FMT "), as the reference's |P|^2 - |Q|^2 keeps its sign over %g-%g Hz", name, nb, f1, f2);
  }
  /* x1 = x2 at every point: DOFs 1 and 2 in every block of 3 ([a0 | as_1 | ac_1 | ... | as_H | ac_H]) */
  for (PetscInt k = 0; k < np; k++)
    for (PetscInt j = 0; j < n / 3; j++) asym = fmax(asym, fabs(a[k * n + 3 * j + 1] - a[k * n + 3 * j + 2]) / hypot(a[k * n + 4], a[k * n + 7]));
  CHECK(asym < 1e-10 && nf == 0, "%s: the continuation traces the symmetric branch (|x1 - x2| / |x1| <= %.1e over %" PetscInt_FMT " points, no fold)", name, asym, np);
  /* the flags: unstable strictly between the reference branch points, stable elsewhere (each side's nearest point free) */
  for (PetscInt k = 0; k < np; k++) {
    const PetscBool inside = (PetscBool)(nref == 2 && om[k] > wref[0] && om[k] < wref[1]);
    PetscBool       near   = PETSC_FALSE;
    for (PetscInt i = 0; i < nref; i++)
      if ((k > 0 && (om[k - 1] - wref[i]) * (om[k] - wref[i]) <= 0) || (k < np - 1 && (om[k] - wref[i]) * (om[k + 1] - wref[i]) <= 0)) near = PETSC_TRUE;
    if (!near && st[k] == (PetscInt)inside) bad++;
    nin += inside;
  }
  CHECK(bad == 0, "%s: of the %" PetscInt_FMT " points, those between the reference branch points (%" PetscInt_FMT " of them) flagged unstable, the rest stable, the two beside each branch point aside (%" PetscInt_FMT " wrong)", name, np, nin, bad);
  if (nref == 2) { /* time integration: the most unstable point's antisymmetric perturbation grows; 1% outside, decays */
    PetscInt ku = 0, ko[2] = {-1, -1};
    double   gu, go[2];
    for (PetscInt k = 0; k < np; k++) {
      if (mr[k] > mr[ku]) ku = k;
      for (int i = 0; i < 2; i++) {
        const double wo = wref[i] * (i ? 1.01 : 0.99);
        if (ko[i] < 0 || fabs(om[k] - wo) < fabs(om[ko[i]] - wo)) ko[i] = k;
      }
    }
    gu = SymAntisymmetricGrowth(o, H, om[ku], a + ku * n, 40, 200);
    for (int i = 0; i < 2; i++) go[i] = SymAntisymmetricGrowth(o, H, om[ko[i]], a + ko[i] * n, 40, 200);
    CHECK(!st[ku] && st[ko[0]] && st[ko[1]] && fabs(gu - mr[ku]) < 0.05 * mr[ku] && go[0] < 0 && go[1] < 0, "%s: RK4 of the 3-DOF equations over 40 periods from the points' states, x1 - x2 pushed apart: at %.4f Hz (flagged unstable, largest Re %.4g 1/s) the perturbation grows at %.4g 1/s (within 5%%); at %.4f and %.4f Hz (1%% outside, flagged stable, largest Re %.3g and %.3g 1/s) it decays at %.3g and %.3g 1/s", name, om[ku] / (2 * PETSC_PI), mr[ku], gu, om[ko[0]] / (2 * PETSC_PI), om[ko[1]] / (2 * PETSC_PI), mr[ko[0]], mr[ko[1]], go[0], go[1]);
  }
  PetscCall(ProblemDestroy(&p));
  PetscFunctionReturn(0);
}

/* xv <- the curve's point q (aa: the points' unknowns, xv's size each) */
static PetscErrorCode PointVec(Vec xv, const PetscReal *aa, PetscInt q)
{
  PetscScalar *xa;
  PetscInt     n;

  PetscFunctionBeginUser;
  PetscCall(VecGetSize(xv, &n));
  PetscCall(VecGetArray(xv, &xa));
  for (PetscInt i = 0; i < n; i++) xa[i] = aa[q * n + i];
  PetscCall(VecRestoreArray(xv, &xa));
  PetscFunctionReturn(0);
}

/* Two lists of Floquet exponents (real parts re, imaginary im, largest first) of the same point at frequency w: the
   same where every exponent whose multiplier exp(re T) exceeds 1e-6 (the smaller ones are at the monodromy
   matrix's round-off) is in both, *err the largest difference of those, *ref the largest |real part| among them */
static PetscBool SameExponents(PetscInt m0, const PetscReal *r0, const PetscReal *i0, PetscInt m1, const PetscReal *r1, const PetscReal *i1, PetscReal w, double *err, double *ref)
{
  const PetscReal lo = PetscLogReal(1e-6) / (2 * PETSC_PI / w);
  PetscBool       same = (PetscBool)(m0 == m1);

  for (PetscInt i = 0; i < m0 && same; i++) {
    const PetscBool c0 = (PetscBool)(r0[i] > lo), c1 = (PetscBool)(r1[i] > lo);
    if (c0 != c1 && PetscAbsReal(r0[i] - r1[i]) > 1e-6 * PetscAbsReal(lo)) same = PETSC_FALSE;
    else if (c0 && c1) *err = PetscMax(*err, PetscMax(PetscAbsReal(r0[i] - r1[i]), PetscAbsReal(i0[i] - i1[i])));
    if (c0) *ref = PetscMax(*ref, PetscAbsReal(r0[i]));
  }
  return same;
}

/* The exponents (m0, r0, i0) of xv at w, with the fast block's inverse and the condensation updated by the Woodbury
   identity, against those with them formed at every step map (JRHBMSetFloquetWoodbury): SameExponents' err and ref;
   *nwoff += the updates made with them off (none expected) */
static PetscErrorCode AgainstFormed(JRHBM h, PetscReal w, Vec xv, PetscInt m0, const PetscReal *r0, const PetscReal *i0, double *err, double *ref, PetscInt *nwoff)
{
  PetscInt  m1, nw;
  PetscReal r1[64], i1[64], x1;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetFloquetWoodbury(h, PETSC_FALSE));
  PetscCall(JRHBMFloquetTime(h, w, xv, 0, &m1, r1, i1, &x1, NULL));
  PetscCall(JRHBMGetFloquetWoodburyUpdates(h, &nw));
  *nwoff += nw;
  PetscCall(JRHBMSetFloquetWoodbury(h, PETSC_TRUE));
  if (!SameExponents(m0, r0, i0, m1, r1, i1, w, err, ref)) *err = PETSC_INFINITY;
  PetscFunctionReturn(0);
}

/* A mass on a spring to ground and seven masses on stiff springs to it, six light (fast: above 20 H w, damped within
   a period) and mass 4 heavier (slow); three jenkins elements from light mass 1 to ground and two from light mass 2
   (two distinct rows), and two jenkins_nv elements on light mass 3 (tangential) and mass 4 (normal, preloaded,
   slipping in contact and separating): four distinct rows for seven elements. H = 3, its curve at 1 N over 6-14 Hz
   solved. */
static PetscErrorCode EightDofCurve(Problem *p, PetscBool coupled, PetscInt *np, const PetscReal **om, const PetscReal **aa, Vec *xv)
{
  const PetscInt n = 8;
  const double   k0 = pow(2 * PETSC_PI * 10, 2), ks = 2e4;
  double         K[64], M[64];

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(K, 64));
  PetscCall(PetscArrayzero(M, 64));
  K[0] = k0;
  M[0] = 1.0;
  for (PetscInt i = 1; i < n; i++) {
    K[0] += ks;
    K[i + i * n] = ks;
    K[i] = K[i * n] = -ks;
    M[i + i * n] = i == 4 ? 0.05 : 5e-4 * (1.0 + 0.1 * i);
  }
  PetscCall(Options("-hbm_physical -hbm_gamma 0.01 -hbm_harmonics 3 -frf_force 1.0 -frf_fmin 6 -frf_fmax 14"));
  if (coupled) /* each element between a light mass and the main one (rows over slow and fast modes), one normal load on
                  the slow DOF 4 opening */
    PetscCall(ProblemCreate(n, K, M, NULL, 5, (El[]){{"jenkins", 1, 0, -1, -1, 4e3, 0, 0.3, 0.3}, {"jenkins", 2, 0, -1, -1, 3e3, 0, 0.3, 0.5}, {"jenkins", 5, 0, -1, -1, 2e3, 0, 0.3, 1.0}, {"jenkins_nv", 3, 0, 4, -1, 3e3, 2e3, 0.3, 0.1}, {"jenkins_nv", 6, 0, 4, 0, 2e3, 2e3, 0.3, 0.05}}, p));
  else PetscCall(ProblemCreate(n, K, M, NULL, 7, (El[]){{"jenkins", 1, -1, -1, -1, 4e3, 0, 0.3, 0.3}, {"jenkins", 1, -1, -1, -1, 3e3, 0, 0.3, 0.6}, {"jenkins", 1, -1, -1, -1, 2e3, 0, 0.3, 1.0}, {"jenkins", 2, -1, -1, -1, 3e3, 0, 0.3, 0.5}, {"jenkins", 2, -1, -1, -1, 1e3, 0, 0.3, 1.2}, {"jenkins_nv", 3, -1, 4, -1, 3e3, 2e3, 0.3, 0.1}, {"jenkins_nv", 3, -1, 4, -1, 2e3, 2e3, 0.3, 0.2}}, p));
  PetscCall(JRContSolve(p->cont));
  PetscCall(JRContGetBranch(p->cont, 0, np, om, aa, NULL));
  PetscCall(JRHBMCreateVecs(p->hbm, xv, NULL));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscCall(SlepcInitialize(&argc, &argv, NULL, NULL));

  /* ---- linear 3-DOF: exponents = eigenvalues of K + l C + l^2 M (mod i k w) ---- */
  {
    const double K[9] = {3e5, -1e5, 0, -1e5, 2e5, -1e5, 0, -1e5, 1e5}, M[9] = {1.0, 0, 0, 0, 2.0, 0, 0, 0, 1.5};
    const double C[9] = {4.0, -1.0, 0, -1.0, 3.0, -1.0, 0, -1.0, 2.0};
    double       lr[6], li[6], wn = 0;
    PetscCall(QEPEigenvalues(3, K, C, M, lr, li));
    for (int i = 0; i < 6; i++) wn = fmax(wn, fabs(li[i]));
    for (int cs = 0; cs < 3; cs++) {
      /* w: every mode below (H + 1/2) w (strip), or the highest above it (vector) */
      const double       w   = cs == 1 ? wn / 5.0 : wn / 2.5;
      const JRHillSelect sel = cs == 1 ? JR_HILL_SELECT_VECTOR : JR_HILL_SELECT_IMAG;
      const PetscInt     H = 3, dmax = cs == 2 ? 0 : 400;
      Problem            p;
      Vec                a;
      PetscReal          re[6], im[6], mr;
      char               opts[256];
      PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_modes 3 -hbm_harmonics %d -frf_dof 1 -frf_force 2.5 -frf_fmin 10 -frf_fmax 80", (int)H));
      PetscCall(Options(opts));
      PetscCall(ProblemCreate(3, K, M, C, 0, NULL, &p));
      PetscCall(JRHBMCreateVecs(p.hbm, &a, NULL));
      PetscCall(JRHBMLinearSolution(p.hbm, w, a));
      PetscCall(JRHBMFloquet(p.hbm, w, a, sel, dmax, NULL, re, im, &mr, NULL));
      if (cs == 0) CHECK(MatchError(6, re, im, 6, lr, li, w, H) < 1e-8, "linear 3-DOF, viscous C, H = 3, all modes below (H + 1/2) w: Floquet exponents (strip |Im| <= w/2) = eigenvalues of K + l C + l^2 M mod i k w, relative error %.1e", MatchError(6, re, im, 6, lr, li, w, H));
      if (cs == 1) {
        CHECK(MatchError(6, re, im, 6, lr, li, w, 0) < 1e-8, "linear 3-DOF, highest mode at %.2f w: eigenvector criterion gives the eigenvalues themselves (k = 0), relative error %.1e", wn / w, MatchError(6, re, im, 6, lr, li, w, 0));
        PetscCall(JRHBMFloquet(p.hbm, w, a, JR_HILL_SELECT_IMAG, dmax, NULL, re, im, &mr, NULL));
        CHECK(MatchError(6, re, im, 6, lr, li, w, H) > 1e-3, "linear 3-DOF, highest mode at %.2f w > (H + 1/2) w: the strip criterion misses it (error %.1e), as documented", wn / w, MatchError(6, re, im, 6, lr, li, w, H));
      }
      if (cs == 2) CHECK(MatchError(6, re, im, 6, lr, li, w, H) < 1e-8, "linear 3-DOF: SLEPc PEP path (-frf_stability_dense_max 0), exponents nearest the origin = eigenvalues mod i k w, relative error %.1e", MatchError(6, re, im, 6, lr, li, w, H));
      if (cs == 0) {
        PetscInt ne, ns;
        PetscCall(JRHBMFloquetTime(p.hbm, w, a, 0, &ne, re, im, &mr, &ns));
        CHECK(ne == 6 && MatchError(6, re, im, 6, lr, li, w, 40) < 1e-8, "linear 3-DOF: Floquet exponents in time (monodromy, each step the Taylor polynomial of its exponential, %" PetscInt_FMT " steps per period) = eigenvalues of K + l C + l^2 M mod i k w, relative error %.1e", ns, MatchError(6, re, im, 6, lr, li, w, 40));
      }
      PetscCall(VecDestroy(&a));
      PetscCall(ProblemDestroy(&p));
    }
  }

  /* ---- Duffing oscillator: middle branch unstable, time integration, folds ---- */
  {
    const Osc o = {1.0, 0.4, pow(2 * PETSC_PI * 10, 2), 2.0, 6e6, 0, 0, 0, 0, 0};
    Problem   p;
    PetscCall(FoldedCase("Duffing H = 5", &o, "-frf_stability -hbm_physical -hbm_harmonics 5 -frf_force 2.0 -frf_fmin 5 -frf_fmax 25 -cont_max_points 3000", 5, 1e-3, 100, 400, &p));
    { /* the exponents in time against Hill's QZ with every exponent computed, at every point */
      PetscInt         np, n, bad = 0, nun = 0;
      const PetscReal *om, *aa;
      double           worst = 0.0;
      Vec              x;
      PetscCall(JRContGetBranch(p.cont, 0, &np, &om, &aa, NULL));
      PetscCall(JRHBMGetSolveSize(p.hbm, &n, NULL));
      PetscCall(JRHBMCreateVecs(p.hbm, &x, NULL));
      for (PetscInt k = 0; k < np; k++) {
        PetscReal    mh, mt, *xa;
        const double scale = 1e-3 * om[k];
        PetscCall(VecGetArray(x, &xa));
        for (PetscInt i = 0; i < n; i++) xa[i] = aa[k * n + i];
        PetscCall(VecRestoreArray(x, &xa));
        PetscCall(JRHBMFloquet(p.hbm, om[k], x, JR_HILL_SELECT_VECTOR, 1000, NULL, NULL, NULL, &mh, NULL));
        PetscCall(JRHBMFloquetTime(p.hbm, om[k], x, 0, NULL, NULL, NULL, &mt, NULL));
        worst = fmax(worst, fabs(mh - mt) / om[k]);
        if ((mh > scale && mt <= 0) || (mh < -scale && mt >= 0)) bad++;
        if (mt > 0) nun++;
      }
      CHECK(bad == 0 && worst < 2e-3 && nun > 10, "Duffing H = 5, %" PetscInt_FMT " points: the largest real part in time (monodromy) and by Hill's QZ agree within %.1e w (< 2e-3 w), the same sign at every point not within 1e-3 w of zero (%" PetscInt_FMT " differ; %" PetscInt_FMT " unstable)", np, worst, bad, nun);
      PetscCall(VecDestroy(&x));
    }
    PetscCall(ProblemDestroy(&p));
    /* the folds at H = 1 against the single-harmonic relation */
    {
      PetscInt         nf;
      const PetscReal *wf;
      const PetscInt  *st;
      double           w1, w2, e = PETSC_MAX_REAL;
      PetscCall(Options("-frf_stability -hbm_physical -hbm_harmonics 1 -frf_force 2.0 -frf_fmin 5 -frf_fmax 25 -cont_max_points 3000"));
      PetscCall(ProblemCreate(1, (double[]){o.k}, (double[]){o.m}, (double[]){o.c}, 1, (El[]){{"cubic", 0, -1, -1, -1, o.k3, 0, 0, 0}}, &p));
      PetscCall(JRContSolve(p.cont));
      PetscCall(JRContGetStability(p.cont, 0, &st, NULL, &nf, &wf, NULL, NULL));
      { /* the default (eigenvector) criterion at H = 1, where the mean block's exponents tie with the middle branch's */
        PetscInt         np, kf = 0, kmin, bad = 0;
        const PetscReal *om;
        PetscCall(JRContGetBranch(p.cont, 0, &np, &om, NULL, NULL));
        for (PetscInt k = 1; k < np - 1 && !kf; k++)
          if (om[k] > om[k - 1] && om[k] >= om[k + 1]) kf = k;
        for (kmin = kf; kmin < np - 1 && om[kmin + 1] < om[kmin]; kmin++) { }
        for (PetscInt k = 0; st && k < np; k++)
          if ((k > kf + 1 && k < kmin - 1 && st[k]) || ((k < kf - 1 || k > kmin + 1) && !st[k])) bad++;
        CHECK(st && kmin > kf + 3 && bad == 0, "Duffing H = 1, eigenvector criterion: the %" PetscInt_FMT " middle-branch points unstable, the rest stable (%" PetscInt_FMT " wrong)", kmin - kf - 3, bad);
      }
      DuffingFolds(&o, &w1, &w2);
      if (nf == 2) e = fmax(fabs(wf[0] - w1) / w1, fabs(wf[1] - w2) / w2);
      CHECK(nf == 2 && e < 1e-3, "Duffing H = 1: %" PetscInt_FMT " folds reported at %.6g and %.6g Hz; the single-harmonic relation's at %.6g and %.6g Hz (relative error %.1e)", nf, nf > 0 ? wf[0] / (2 * PETSC_PI) : 0, nf > 1 ? wf[1] / (2 * PETSC_PI) : 0, w1 / (2 * PETSC_PI), w2 / (2 * PETSC_PI), e);
      PetscCall(ProblemDestroy(&p));
    }
  }

  /* ---- friction oscillator with a gap: jenkins_nv closes on impact, a hardening fold ---- */
  {
    const double k = pow(2 * PETSC_PI * 10, 2);
    const Osc    o = {1.0, 0.4, k, 1.5, 0, 0.5 * k, k, 0.3, -k * 2e-3, 1};
    Problem      p;
    PetscCall(FoldedCase("friction with a gap (jenkins_nv) H = 7", &o, "-frf_stability -hbm_physical -hbm_harmonics 7 -hbm_samples 256 -frf_force 1.5 -frf_fmin 5 -frf_fmax 25 -cont_max_points 3000", 7, 0.02, 100, 2000, &p));
    PetscCall(ProblemDestroy(&p));
  }

  /* ---- Jenkins oscillator: incrementally dissipative; perturbed RK4 against the exponents in time ---- */
  {
    const double     m = 1.0, c = 0.4, k = pow(2 * PETSC_PI * 10, 2), kt = k, mu = 0.3, n0 = 1.0, F = 1.0;
    const PetscInt   ns = 4000;
    Problem          p;
    PetscInt         np, n, kp = 0;
    const PetscReal *om, *aa, *amp, *mr;
    const PetscInt  *st;
    PetscInt         nun = 0;
    const PetscInt   Hj = 5;
    char             opts[256];
    PetscCall(PetscSNPrintf(opts, sizeof(opts), "-frf_stability -hbm_physical -hbm_harmonics %d -hbm_samples %d -frf_force 1.0 -frf_fmin 8 -frf_fmax 20", (int)Hj, (int)(Hj > 8 ? 1024 : 256)));
    PetscCall(Options(opts));
    PetscCall(ProblemCreate(1, (double[]){k}, (double[]){m}, (double[]){c}, 1, (El[]){{"jenkins", 0, -1, -1, -1, kt, 0, mu, n0}}, &p));
    PetscCall(JRContSolve(p.cont));
    PetscCall(JRContGetBranch(p.cont, 0, &np, &om, &aa, &amp));
    PetscCall(JRContGetStability(p.cont, 0, &st, &mr, NULL, NULL, NULL, NULL));
    PetscCall(JRHBMGetSolveSize(p.hbm, &n, NULL));
    for (PetscInt q = 0; q < np; q++) {
      if (amp[q] > amp[kp]) kp = q;
      nun += !st[q];
    }
    CHECK(nun == 0, "Jenkins oscillator (constant normal load): every one of the %" PetscInt_FMT " points stable by incremental dissipativity (%" PetscInt_FMT " flagged unstable)", np, nun);
    /* two points: the peak, and the one where the exponents in time and Hill's method differ most */
    {
      Vec          xv;
      PetscScalar *xa;
      PetscInt     kd = 0;
      double       dmax = -1;
      PetscCall(JRHBMCreateVecs(p.hbm, &xv, NULL));
      for (PetscInt q = 0; q < np; q++) {
        PetscReal mt, mh;
        PetscCall(PointVec(xv, aa, q));
        PetscCall(JRHBMFloquetTime(p.hbm, om[q], xv, 0, NULL, NULL, NULL, &mt, NULL));
        PetscCall(JRHBMFloquet(p.hbm, om[q], xv, JR_HILL_SELECT_VECTOR, 1000, NULL, NULL, NULL, &mh, NULL));
        if (fabs(mt - mh) > dmax) {
          dmax = fabs(mt - mh);
          kd   = q;
        }
      }
      for (int pt = 0; pt < 2; pt++) {
        const PetscInt   q = pt ? kd : kp;
        const PetscReal *a = aa + q * n, w = om[q], T = 2 * PETSC_PI / w, dt = T / ns, fs = mu * n0;
        double           x0 = a[0], v0 = 0.0, s0 = 0.0, A = hypot(a[1], a[2]), rate;
        PetscReal        mt, mh;
        PetscInt         P;
        PetscCall(VecGetArray(xv, &xa));
        for (PetscInt i = 0; i < n; i++) xa[i] = a[i];
        PetscCall(VecRestoreArray(xv, &xa));
        PetscCall(JRHBMFloquetTime(p.hbm, w, xv, 0, NULL, NULL, NULL, &mt, NULL));
        PetscCall(JRHBMFloquet(p.hbm, w, xv, JR_HILL_SELECT_VECTOR, 1000, NULL, NULL, NULL, &mh, NULL));
        P = 30 + (PetscInt)(10.0 / (PetscMax(-mt, 1e-3) * T)); /* to the periodic orbit: a decay by about e^-10 */
        for (PetscInt h = 1; h <= Hj; h++) {
          x0 += a[2 * h];
          v0 += h * w * a[2 * h - 1];
        }
        for (PetscInt j = 0; j <= 2 * ns; j++) { /* the slip at t = 0: two periods of the point's motion (play operator) */
          double xj = a[0];
          for (PetscInt h = 1; h <= Hj; h++) xj += a[2 * h - 1] * sin(h * w * j * dt) + a[2 * h] * cos(h * w * j * dt);
          s0 = fmin(fmax(s0, xj - fs / kt), xj + fs / kt);
        }
        for (PetscInt c0 = 0; c0 < P; c0++)
          for (PetscInt j = 0; j < ns; j++) JenkinsOscillatorStep(m, c, k, kt, fs, F, w, j * dt, dt, &x0, &v0, &s0);
        { /* the march's own monodromy matrix on the orbit it reached, by differences in x, v / w, s */
          double       Mo[9], wr[3], wi[3], wk[64], dum, e = 1e-7 * A, base[3] = {x0, v0, s0}, end[3] = {0, 0, 0};
          PetscBLASInt n3 = 3, one = 1, lw = 64, info;
          for (int col = -1; col < 3; col++) {
            double y[3] = {base[0], base[1], base[2]};
            if (col >= 0) y[col] += col == 1 ? e * w : e;
            for (PetscInt j = 0; j < ns; j++) JenkinsOscillatorStep(m, c, k, kt, fs, F, w, j * dt, dt, &y[0], &y[1], &y[2]);
            if (col < 0) {
              for (int i = 0; i < 3; i++) end[i] = y[i];
              continue;
            }
            for (int i = 0; i < 3; i++) Mo[i + 3 * col] = (y[i] - end[i]) / e / (i == 1 ? w : 1.0);
          }
          PetscCallBLAS("LAPACKgeev", LAPACKgeev_("N", "N", &n3, Mo, &n3, wr, wi, &dum, &one, &dum, &one, wk, &lw, &info));
          rate = -PETSC_MAX_REAL;
          for (int i = 0; i < 3; i++) rate = fmax(rate, log(hypot(wr[i], wi[i])) / T);
        }
        CHECK(st[q] && rate < 0 && fabs(rate - mt) < 0.02 * fabs(mt), "Jenkins oscillator at %.3f Hz (%s, stick-slip): an RK4 march from the point's state settles on its orbit (%" PetscInt_FMT " periods); that march's monodromy matrix (differences of 1e-7 of the amplitude) has the largest exponent %.4f 1/s < 0, perturbations decay; the exponents in time: %.4f 1/s (Hill's method with the periodic Jacobian: %.4f 1/s)", w / (2 * PETSC_PI), pt ? "where Hill's method differs most" : "the peak", P, rate, mt, mh);
      }
      PetscCall(VecDestroy(&xv));
    }
    (void)mr;
    PetscCall(ProblemDestroy(&p));
  }

  /* ---- the exponents in time on a Jenkins oscillator through full stick and grazing slip: all stable (the theorem) ---- */
  {
    const double     k = pow(2 * PETSC_PI * 100, 2);
    Problem          p;
    PetscInt         np, nun = 0;
    const PetscReal *om;
    const PetscInt  *st;
    PetscCall(Options("-frf_stability -frf_stability_dissipative 0 -hbm_physical -hbm_gamma 0.01 -hbm_harmonics 1 -frf_force 0.2 -frf_fmin 80 -frf_fmax 170"));
    PetscCall(ProblemCreate(1, (double[]){k}, (double[]){1.0}, NULL, 1, (El[]){{"jenkins", 0, -1, -1, -1, k, 0, 0.1, 100}}, &p));
    PetscCall(JRContSolve(p.cont));
    PetscCall(JRContGetBranch(p.cont, 0, &np, &om, NULL, NULL));
    PetscCall(JRContGetStability(p.cont, 0, &st, NULL, NULL, NULL, NULL, NULL));
    for (PetscInt q = 0; q < np; q++) nun += !st[q];
    CHECK(np > 50 && nun == 0, "Jenkins oscillator (runs/oscillator_frf.opts at 0.2 N: full stick, then slip near the 141 Hz resonance), every point by the exponents in time (-frf_stability_dissipative 0): %" PetscInt_FMT " of %" PetscInt_FMT " unstable (incremental dissipativity: none)", nun, np);
    PetscCall(ProblemDestroy(&p));
  }

  /* ---- fast modes condensed quasi-statically in the monodromy: the exponents tend to the full march's as w_f grows ----
     a mass on a spring to ground, a light mass mu on a stiff spring ks to it, and a Jenkins element from the light one
     to ground, structural damping gamma: the light mass's own frequency sqrt(ks / mu) is fast (above 20 H w, decaying
     by e within a period), the other slow. At the points of the stick-slip resonance, the largest real part with the
     light mass condensed (-frf_stability_time_fast 20) and marched (0), 16384 steps per period (the steps' own error
     aside): they differ by e(mu, gamma) < 1e-3 of the largest |real part|, and e falls by 3-7 when mu / 4 doubles
     w_f (the neglected inertia, (w / w_f)^2), at gamma 1% and 0.25%; at the default steps the two differ by < 1%. */
  {
    const double   k0 = pow(2 * PETSC_PI * 10, 2), ks = 2e4, kt = 1e4, fs = 0.3;
    const PetscInt Hq = 3;
    double         err[5] = {0, 0, 0, 0, 0}, ref[4] = {0, 0, 0, 0};
    PetscInt       npq = 0, nfast = 0;
    for (int pass = 0; pass < 4; pass++) {
      const double     mu = pass % 2 ? 1.25e-4 : 5e-4, gam = pass / 2 ? 0.0025 : 0.01, K[4] = {k0 + ks, -ks, -ks, ks}, M[4] = {1.0, 0, 0, mu}, C[4] = {0.2, 0, 0, 0};
      Problem          p;
      PetscInt         np, n;
      const PetscReal *om, *aa;
      Vec              xv;
      char             opts[256];
      PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_physical -hbm_gamma %g -hbm_harmonics %d -frf_force 1.0 -frf_fmin 6 -frf_fmax 14", gam, (int)Hq));
      PetscCall(Options(opts));
      PetscCall(ProblemCreate(2, K, M, C, 1, (El[]){{"jenkins", 1, -1, -1, -1, kt, 0, 0.3, fs / 0.3}}, &p));
      PetscCall(JRContSolve(p.cont));
      PetscCall(JRContGetBranch(p.cont, 0, &np, &om, &aa, NULL));
      PetscCall(JRHBMGetSolveSize(p.hbm, &n, NULL));
      PetscCall(JRHBMCreateVecs(p.hbm, &xv, NULL));
      for (PetscInt q = 0; q < np; q += PetscMax(1, np / 40)) {
        PetscReal m0, m1;
        PetscCall(PointVec(xv, aa, q));
        for (int st = 0; st < (pass ? 1 : 2); st++) {
          PetscCall(JRHBMSetFloquetFast(p.hbm, 0));
          PetscCall(JRHBMFloquetTime(p.hbm, om[q], xv, st ? 0 : 16384, NULL, NULL, NULL, &m0, NULL));
          PetscCall(JRHBMSetFloquetFast(p.hbm, 20));
          PetscCall(JRHBMFloquetTime(p.hbm, om[q], xv, st ? 0 : 16384, NULL, NULL, NULL, &m1, NULL));
          err[st ? 4 : pass] = fmax(err[st ? 4 : pass], fabs(m1 - m0));
          if (!st) ref[pass] = fmax(ref[pass], fabs(m0));
        }
        npq++;
        nfast += (PetscInt)(ks / mu > pow(20.0 * Hq * om[q], 2) && gam / om[q] * ks / (2 * mu) >= om[q] / (2 * PETSC_PI));
      }
      PetscCall(VecDestroy(&xv));
      PetscCall(ProblemDestroy(&p));
    }
    CHECK(nfast == npq, "2-DOF with a light mass (own frequency %.0f and %.0f rad/s) on a stiff spring: above 20 H w and damped by e within a period at all %" PetscInt_FMT " points checked, so condensed", sqrt(ks / 5e-4), sqrt(ks / 1.25e-4), npq);
    for (int g = 0; g < 2; g++)
      CHECK(err[2 * g] < 1e-3 * ref[2 * g] && err[2 * g + 1] < 1e-3 * ref[2 * g + 1] && err[2 * g] / err[2 * g + 1] > 3 && err[2 * g] / err[2 * g + 1] < 7, "2-DOF, gamma %g: the largest real part with the light mass condensed against marched (16384 steps) differs by at most %.2e 1/s (largest |real part| %.3g 1/s), %.2e with w_f doubled: %.2f times less (3-7: (w / w_f)^2)", g ? 0.0025 : 0.01, err[2 * g], ref[2 * g], err[2 * g + 1], err[2 * g] / err[2 * g + 1]);
    CHECK(err[4] < 1e-2 * ref[0], "2-DOF, gamma 0.01, the default steps: condensed against marched differ by at most %.2e 1/s (< 1%% of %.3g 1/s)", err[4], ref[0]);
  }

  /* ---- EightDofCurve's system (four distinct rows for seven elements), at the points of its stick-slip resonance:
     every exponent whose multiplier exceeds 1e-6 (the smaller ones are at the monodromy matrix's round-off)
     - with the fast modes condensed through the distinct rows (Woodbury, -frf_stability_time_lowrank yes) equals the
       one by the fast block's inverse (every 30th point);
     - with the slips not read before their first commit left out of the march (JRHBMSetFloquetUnread, the default)
       equals the one with every tracked slip marched, the fast modes condensed and every mode marched (every point,
       with slips left out and not) --- to round-off */
  {
    double           err = 0, ref = 0, erru = 0, refu = 0, errw = 0, refw = 0;
    PetscInt         npq = 0, nslip = 0, nd0 = -1, nd2 = -1, npu = 0, nleft = 0, nslips = 0, badu = 0, nwood = 0, nwoff = 0, nwq;
    Problem          p;
    PetscInt         np;
    const PetscReal *om, *aa;
    Vec              xv;
    PetscCall(EightDofCurve(&p, PETSC_FALSE, &np, &om, &aa, &xv));
    for (PetscInt fast = 0; fast < 2; fast++) {
      PetscCall(JRHBMSetFloquetFast(p.hbm, fast ? 20 : 0));
      for (PetscInt q = 0; q < np; q++) {
        PetscInt  m0, m1, nl;
        PetscReal r0[64], r1[64], i0[64], i1[64], x0, x1;
        PetscCall(PointVec(xv, aa, q));
        if (fast && q % PetscMax(1, np / 30) == 0) { /* distinct rows against the fast block's inverse */
          PetscInt ndq, fin = 0;
          PetscCall(JRHBMSetFloquetLowRank(p.hbm, 0));
          PetscCall(JRHBMFloquetTime(p.hbm, om[q], xv, 0, &m0, r0, i0, &x0, NULL));
          PetscCall(JRHBMGetFloquetLowRankRows(p.hbm, &ndq));
          PetscCall(JRHBMGetFloquetWoodburyUpdates(p.hbm, &nwq));
          nd0 = PetscMax(nd0, ndq);
          nwood += nwq;
          PetscCall(AgainstFormed(p.hbm, om[q], xv, m0, r0, i0, &errw, &refw, &nwoff));
          PetscCall(JRHBMSetFloquetLowRank(p.hbm, 2));
          PetscCall(JRHBMFloquetTime(p.hbm, om[q], xv, 0, &m1, r1, i1, &x1, NULL));
          PetscCall(JRHBMGetFloquetLowRankRows(p.hbm, &ndq));
          nd2 = PetscMax(nd2, ndq);
          if (!SameExponents(m0, r0, i0, m1, r1, i1, om[q], &err, &ref)) err = PETSC_INFINITY;
          for (PetscInt i = 0; i < m0; i++) fin += r0[i] > PETSC_NINFINITY && r0[i] != 0.0; /* the main mass's pair and the tracked slips */
          nslip += fin > 2 * 1; /* more exponents than the main mass's pair: slips marched */
          npq++;
          PetscCall(JRHBMSetFloquetLowRank(p.hbm, 1));
        }
        /* the unread slips left out against every slip marched */
        PetscCall(JRHBMSetFloquetUnread(p.hbm, PETSC_TRUE));
        PetscCall(JRHBMFloquetTime(p.hbm, om[q], xv, 0, &m0, r0, i0, &x0, NULL));
        PetscCall(JRHBMGetFloquetUnreadSlips(p.hbm, &nl));
        PetscCall(JRHBMSetFloquetUnread(p.hbm, PETSC_FALSE));
        PetscCall(JRHBMFloquetTime(p.hbm, om[q], xv, 0, &m1, r1, i1, &x1, NULL));
        PetscCall(JRHBMSetFloquetUnread(p.hbm, PETSC_TRUE));
        if (!SameExponents(m0, r0, i0, m1, r1, i1, om[q], &erru, &refu)) badu++;
        nleft += nl > 0;
        nslips += nl;
        npu++;
      }
    }
    PetscCall(VecDestroy(&xv));
    PetscCall(ProblemDestroy(&p));
    CHECK(nd0 == 0 && nd2 == 4 && nslip > 0 && err <= 1e-9 * ref, "8 DOFs, 7 light masses condensed, 7 elements on 4 distinct rows: at %" PetscInt_FMT " points (%" PetscInt_FMT " with slips marched) every exponent through the distinct rows (%" PetscInt_FMT " used) equals the fast block's inverse's (%" PetscInt_FMT " rows) within %.2e 1/s (largest |real part| %.3g 1/s; <= 1e-9 of it)", npq, nslip, nd2, nd0, err, ref);
    CHECK(nwood > npq && nwoff == 0 && errw <= 1e-9 * refw, "8 DOFs, 7 light masses condensed by their block's inverse: at %" PetscInt_FMT " points every exponent with that inverse updated from the last step map's by the Woodbury identity (%" PetscInt_FMT " updates) equals the one with it inverted at every step map within %.2e 1/s (largest |real part| %.3g 1/s; <= 1e-9 of it)", npq, nwood, errw, refw);
    CHECK(!badu && nleft > 0 && nleft < npu && erru <= 1e-9 * refu, "8 DOFs, 7 elements, fast modes condensed and marched: at %" PetscInt_FMT " points (%" PetscInt_FMT " with %" PetscInt_FMT " slips in all left out of the march) every exponent equals the one with every tracked slip marched within %.2e 1/s (largest |real part| %.3g 1/s; <= 1e-9 of it)", npu, nleft, nslips, erru, refu);
  }

  /* ---- EightDofCurve's system with its elements between the light masses and the main one (their rows over the slow
     and the fast modes; a normal load on the slow DOF 4): at every point of its stick-slip resonance every exponent
     whose multiplier exceeds 1e-6 with the fast block's inverse, X = -Kff^-1 Kfs and Z = Kff^-T Ksf^T updated by the
     Woodbury identity equals the one with them formed at every step map, to round-off */
  {
    double           errw = 0, refw = 0;
    PetscInt         npq = 0, nwood = 0, nwq, nwoff = 0, nsep = 0, np;
    JRContactState   st[5] = {JR_CONTACT_FULL_STICK, JR_CONTACT_FULL_STICK, JR_CONTACT_FULL_STICK, JR_CONTACT_FULL_STICK, JR_CONTACT_FULL_STICK};
    Problem          p;
    const PetscReal *om, *aa;
    Vec              xv;
    PetscCall(EightDofCurve(&p, PETSC_TRUE, &np, &om, &aa, &xv));
    PetscCall(JRHBMSetFloquetFast(p.hbm, 20));
    PetscCall(JRHBMSetFloquetLowRank(p.hbm, 0));
    for (PetscInt q = 0; q < np; q++) {
      PetscInt  m0;
      PetscReal r0[64], i0[64], x0;
      PetscCall(PointVec(xv, aa, q));
      PetscCall(JRHBMFloquetTime(p.hbm, om[q], xv, 0, &m0, r0, i0, &x0, NULL));
      PetscCall(JRHBMGetFloquetWoodburyUpdates(p.hbm, &nwq));
      nwood += nwq;
      PetscCall(AgainstFormed(p.hbm, om[q], xv, m0, r0, i0, &errw, &refw, &nwoff));
      PetscCall(JRHBMElementStates(p.hbm, xv, st)); /* a normal load opening over part of the cycle: its row updated too */
      nsep += st[3] == JR_CONTACT_SEPARATION_STICK_SLIP || st[4] == JR_CONTACT_SEPARATION_STICK_SLIP;
      npq++;
    }
    PetscCallMPI(MPI_Bcast(&nsep, 1, MPIU_INT, 0, PETSC_COMM_WORLD)); /* the states are gathered on rank 0 */
    PetscCall(VecDestroy(&xv));
    PetscCall(ProblemDestroy(&p));
    CHECK(npq > 20 && nwood > npq && nwoff == 0 && nsep > 0 && errw <= 1e-9 * refw, "8 DOFs, 5 elements between the light masses and the main one: at %" PetscInt_FMT " points (%" PetscInt_FMT " with a contact opening) every exponent with the fast block's inverse and the condensation updated by the Woodbury identity (%" PetscInt_FMT " updates) equals the one with them formed at every step map within %.2e 1/s (largest |real part| %.3g 1/s; <= 1e-9 of it)", npq, nsep, nwood, errw, refw);
  }

  /* ---- a symmetric 3-DOF system forced on its axis: symmetry-breaking branch points at H = 1 and 3 ---- */
  { /* the symmetric resonance, its peak at 10.74 Hz and not folded at 20 N, is unstable to antisymmetric motion over
       10.41-10.89 Hz; at 5 N it is stable throughout */
    const double ka = pow(2 * PETSC_PI * 10, 2);
    Sym3         o  = {1.0, 1.0, 0.1 * ka, 0.2 * ka, 0.8 * ka, 40.0, 2.0, 4e6, 20.0};
    PetscCall(SymmetricCase(&o, 1, 8, 13, 2));
    PetscCall(SymmetricCase(&o, 3, 8, 13, 2));
    o.F = 5.0;
    PetscCall(SymmetricCase(&o, 1, 8, 13, 0));
  }

  PetscCall(SlepcFinalize());
  return TestSummary("test_stability");
}
