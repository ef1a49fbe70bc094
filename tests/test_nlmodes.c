/*
   Nonlinear modes by the extended periodic motion concept (JRNLModes, JRHBMSetEPMC) against independent references:
   - H = 1: the describing function of the jenkins element in closed form gives the backbone of a one-DOF oscillator,
     w^2 = (k + Kr(A)) / m and xi = (c + Ki(A) / w) / m, D = xi / (2 w), with
       Kr = kt / pi (b - sin(2 b) / 2), Ki = 4 fs / (pi A) (1 - fs / (kt A)), cos b = 1 - 2 fs / (kt A) (A > fs / kt),
     and Kr = kt, Ki = 0 below; summed over elements in parallel;
   - H > 1: xi against the energy balance of the computed motion, the friction work by a fine time march of the element
     along x(t) rebuilt from the harmonics plus the viscous work, over the work of the unit negative damping;
   - the peaks of forced-response curves (JRCont) of the same oscillator, from full stick to gross slip, lie on the
     backbone: the backbone's frequency at the peak's amplitude, and the force the backbone's damping needs to hold
     that amplitude at resonance, F = xi w m A, against the level.
*/
#include <slepcsys.h>
#include "jrtest_problem.h"

/* The jenkins element's describing function (first harmonic of its force for u = A sin t): Kr + i Ki */
static void Describing(double kt, double fs, double A, double *Kr, double *Ki)
{
  if (A <= fs / kt) {
    *Kr = kt;
    *Ki = 0;
    return;
  }
  {
    const double b = acos(1 - 2 * fs / (kt * A));
    *Kr            = kt / PETSC_PI * (b - 0.5 * sin(2 * b));
    *Ki            = 4 * fs / (PETSC_PI * A) * (1 - fs / (kt * A));
  }
}

/* The friction work of a jenkins element (kt, fs) over one cycle of u(t) = u0 + sum_h us_h sin(h t) + uc_h cos(h t):
   two cycles marched from no slip at ns steps per cycle, the work f du of the second by the trapezoidal rule */
static double FrictionWork(double kt, double fs, PetscInt H, const double *u, PetscInt ns)
{
  double w = 0, f = 0, uprev = 0, fprev = 0, work = 0;

  for (PetscInt s = 0; s <= 2 * ns; s++) {
    const double t = 2 * PETSC_PI * s / ns;
    double       x = u[0], ft;
    for (PetscInt h = 1; h <= H; h++) x += u[2 * h - 1] * sin(h * t) + u[2 * h] * cos(h * t);
    if (!s) w = x; /* start without force */
    ft = kt * (x - w);
    if (ft > fs) {
      w  = x - fs / kt;
      ft = fs;
    } else if (ft < -fs) {
      w  = x + fs / kt;
      ft = -fs;
    }
    f = ft;
    if (s > ns) work += 0.5 * (f + fprev) * (x - uprev);
    uprev = x;
    fprev = f;
  }
  return work;
}

/* Backbone of a one-DOF oscillator (m, k, c) with jenkins elements (kt[e], fs[e]) to ground, options in opts */
typedef struct {
  double   m, k, c;
  PetscInt ne;
  double   kt[4], fs[4];
} Osc;

static PetscErrorCode CreateOsc(const Osc *o, const char *opts, Problem *p)
{
  const double K[1] = {o->k}, M[1] = {o->m}, C[1] = {o->c};
  El           e[4];

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < o->ne; i++) {
    El ei = {"jenkins", 0, -1, -1, -1, o->kt[i], 0, 1.0, o->fs[i]};
    e[i]  = ei;
  }
  PetscCall(Options(opts));
  PetscCall(ProblemCreate(1, K, M, C, o->ne, e, p));
  PetscFunctionReturn(0);
}

static PetscErrorCode Backbone(JRHBM hbm, JRNLModes *nlm)
{
  PetscFunctionBeginUser;
  PetscCall(JRNLModesCreate(PETSC_COMM_WORLD, nlm));
  PetscCall(JRNLModesSetHBM(*nlm, hbm));
  PetscCall(JRNLModesSetFromOptions(*nlm));
  PetscCall(JRNLModesSolve(*nlm));
  PetscFunctionReturn(0);
}

/* H = 1 against the describing function in closed form */
static PetscErrorCode CheckH1(const char *name, const Osc *o, const char *cont)
{
  Problem          p;
  JRNLModes        nlm;
  PetscInt         np;
  const PetscReal *q, *om, *xi, *amp;
  double           ew = 0, ed = 0, ea = 0, dmin = 1e300, dmax = 0, fmin = 1e300, fmax = 0;
  PetscBool        complete, natural = (PetscBool)!strcmp(cont, "natural");
  char             opts[256];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_harmonics 1 -hbm_samples 4096 -nlm_amp_min 1e-6 -nlm_amp_max 1e-1 -nlm_points 41 -nlm_continuation %s -nlm_output_file ''", cont));
  PetscCall(CreateOsc(o, opts, &p));
  PetscCall(Backbone(p.hbm, &nlm));
  PetscCall(JRNLModesGetBackbone(nlm, &np, &q, &om, &xi, &amp, NULL));
  PetscCall(JRNLModesGetStats(nlm, NULL, NULL, &complete));
  for (PetscInt i = 0; i < np; i++) {
    const double A = q[i] / sqrt(o->m); /* the mass-normalised mode is 1 / sqrt(m) */
    double       Kr = 0, Ki = 0, w, x, D;
    for (PetscInt e = 0; e < o->ne; e++) {
      double kr, ki;
      Describing(o->kt[e], o->fs[e], A, &kr, &ki);
      Kr += kr;
      Ki += ki;
    }
    w  = sqrt((o->k + Kr) / o->m);
    x  = (o->c + Ki / w) / o->m;
    D  = x / (2 * w);
    ew = PetscMax(ew, PetscAbsReal(om[i] / w - 1));
    ed = PetscMax(ed, PetscAbsReal(xi[i] / (2 * om[i]) / D - 1));
    ea = PetscMax(ea, PetscAbsReal(amp[i] / A - 1));
    dmin = PetscMin(dmin, D);
    dmax = PetscMax(dmax, D);
    fmin = PetscMin(fmin, w / (2 * PETSC_PI));
    fmax = PetscMax(fmax, w / (2 * PETSC_PI));
  }
  CHECK(complete && (natural ? np == 41 : np >= 41) && PetscAbsReal(q[0] / 1e-6 - 1) < 1e-12 && PetscAbsReal(q[np - 1] / 1e-1 - 1) < 1e-12 && ew <= 1e-6 && ed <= 1e-6 && ea <= 1e-12, "%s, H = 1, %s continuation: %" PetscInt_FMT " backbone points (%.5g .. %.5g Hz, damping ratio %.3e .. %.3e) against the describing function in closed form: frequency within %.1e, damping ratio within %.1e (<= 1e-6), response amplitude = q / sqrt(m) within %.1e", name, cont, np, fmin, fmax, dmin, dmax, ew, ed, ea);
  PetscCall(JRNLModesDestroy(&nlm));
  PetscCall(ProblemDestroy(&p));
  PetscFunctionReturn(0);
}

/* H > 1: xi against the energy balance of the computed motion (time-marched friction work + viscous work) */
static PetscErrorCode CheckEnergy(const char *name, const Osc *o, PetscInt H)
{
  Problem          p;
  JRNLModes        nlm;
  PetscInt         np, nm, n;
  const PetscReal *q, *om, *xi, *a;
  double           worst = 0, hh = 0;
  char             opts[256];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_harmonics %" PetscInt_FMT " -hbm_samples 1024 -nlm_amp_min 1e-5 -nlm_amp_max 1e-2 -nlm_points 16 -nlm_output_file ''", H));
  PetscCall(CreateOsc(o, opts, &p));
  PetscCall(Backbone(p.hbm, &nlm));
  PetscCall(JRNLModesGetBackbone(nlm, &np, &q, &om, &xi, NULL, &a));
  PetscCall(JRHBMGetSizes(p.hbm, &nm, NULL, &n));
  for (PetscInt i = 0; i < np; i++) {
    double u[2 * JRT_NC + 1], v2 = 0, wf = 0, wv, xe, hi = 0;
    for (PetscInt k = 0; k < 2 * H + 1; k++) u[k] = a[i * n + k] / sqrt(o->m); /* x = phi a, phi = 1 / sqrt(m) */
    for (PetscInt h = 1; h <= H; h++) {
      v2 += PETSC_PI * om[i] * h * h * (u[2 * h - 1] * u[2 * h - 1] + u[2 * h] * u[2 * h]); /* integral of v^2 dt / omega... per cycle: pi w h^2 |u_h|^2 */
      if (h > 1) hi = PetscMax(hi, sqrt(u[2 * h - 1] * u[2 * h - 1] + u[2 * h] * u[2 * h]));
    }
    for (PetscInt e = 0; e < o->ne; e++) wf += FrictionWork(o->kt[e], o->fs[e], H, u, 200000);
    wv = o->c * v2;
    xe = (wf + wv) / (o->m * v2);
    worst = PetscMax(worst, PetscAbsReal(xe / xi[i] - 1));
    hh    = PetscMax(hh, hi / sqrt(u[1] * u[1] + u[2] * u[2]));
  }
  CHECK(np >= 16 && worst <= 2e-4 && hh > 1e-3, "%s, H = %" PetscInt_FMT ": at every one of %" PetscInt_FMT " points xi against the energy balance of the computed motion (friction work by a time march of 200000 steps a cycle + viscous work, over the work of the unit negative damping): within %.1e (<= 2e-4); higher harmonics up to %.1f%% of the first", name, H, np, worst, 100 * hh);
  PetscCall(JRNLModesDestroy(&nlm));
  PetscCall(ProblemDestroy(&p));
  PetscFunctionReturn(0);
}

/* The peaks of forced-response curves of the same oscillator lie on the backbone */
static PetscErrorCode CheckPeaks(const char *name, const Osc *o, PetscInt H, PetscInt nlev, const double *F)
{
  Problem          p;
  JRNLModes        nlm;
  PetscInt         np, n;
  const PetscReal *q, *om, *xi, *a;
  double           wf = 0, wa = 0;
  char             opts[512], lv[256] = "";

  PetscFunctionBeginUser;
  for (PetscInt l = 0; l < nlev; l++) PetscCall(PetscSNPrintf(lv + strlen(lv), sizeof(lv) - strlen(lv), "%s%g", l ? "," : "", F[l]));
  PetscCall(PetscSNPrintf(opts, sizeof(opts), "-hbm_harmonics %" PetscInt_FMT " -hbm_samples 256 -frf_dof 0 -frf_force %s -frf_fmin 14 -frf_fmax 26 -cont_type arclength -nlm_amp_min 1e-6 -nlm_amp_max 1e-1 -nlm_points 201 -nlm_output_file ''", H, lv));
  PetscCall(CreateOsc(o, opts, &p));
  PetscCall(JRContSolve(p.cont)); /* the curves first: JRHBMSetEPMC removes the excitation */
  PetscCall(Backbone(p.hbm, &nlm));
  PetscCall(JRNLModesGetBackbone(nlm, &np, &q, &om, &xi, NULL, &a));
  PetscCall(JRHBMGetSizes(p.hbm, NULL, NULL, &n));
  for (PetscInt l = 0; l < nlev; l++) {
    PetscReal w, A;
    double    lq, t, wb, xb, Fb, r[2];
    PetscInt  i = 0;
    PetscCall(JRContGetPeak(p.cont, l, &w, &A));
    lq = log(A * sqrt(o->m)); /* the peak's modal amplitude */
    while (i + 2 < np && log(q[i + 1]) < lq) i++;
    t  = (lq - log(q[i])) / (log(q[i + 1]) - log(q[i])); /* linear in log q */
    wb = (1 - t) * om[i] + t * om[i + 1];
    xb = (1 - t) * xi[i] + t * xi[i + 1];
    for (PetscInt k = 0; k < 2; k++) { /* sum_h h^2 |a_h|^2 / |a_1|^2: the higher harmonics' share of the dissipation */
      const PetscReal *ak = a + (i + k) * n;
      double           s2 = 0;
      for (PetscInt h = 1; 2 * h < n; h++) s2 += h * h * (ak[2 * h - 1] * ak[2 * h - 1] + ak[2 * h] * ak[2 * h]);
      r[k] = s2 / (ak[1] * ak[1] + ak[2] * ak[2]);
    }
    /* at resonance the excitation's work pi F A balances the dissipation pi xi w m sum_h h^2 A_h^2 */
    Fb = xb * wb * o->m * A * ((1 - t) * r[0] + t * r[1]);
    wf = PetscMax(wf, PetscAbsReal(w / wb - 1));
    wa = PetscMax(wa, PetscAbsReal(Fb / F[l] - 1));
    if (getenv("JR_DEBUG")) printf("# F %g peak %.8g Hz A %.6e backbone %.8g Hz, force for A %.6e\n", F[l], w / (2 * PETSC_PI), A, wb / (2 * PETSC_PI), Fb);
  }
  CHECK(wf <= 3e-3 && wa <= 3e-3, "%s, H = %" PetscInt_FMT ": the peaks of the forced responses at %s N (stick to gross slip) on the backbone: frequency within %.1e, level from the backbone's damping at the peak's amplitude within %.1e (<= 3e-3)", name, H, lv, wf, wa);
  PetscCall(JRNLModesDestroy(&nlm));
  PetscCall(ProblemDestroy(&p));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscCall(SlepcInitialize(&argc, &argv, NULL, NULL));
  { /* m = 1 kg, k = 1e4 N/m, jenkins kt = 1e4 N/m, slip force 1 N, c = 0.2 N s/m (0.07% stuck) */
    const Osc    o    = {1, 1e4, 0.2, 1, {1e4}, {1}};
    const Osc    o3   = {2, 1e4, 0.3, 3, {4e3, 3e3, 3e3}, {0.3, 0.5, 1.0}}; /* microslip: three elements in parallel */
    const double F[4] = {0.001, 0.5, 1.0, 1.25};
    PetscCall(CheckH1("1-DOF jenkins oscillator", &o, "natural"));
    PetscCall(CheckH1("1-DOF jenkins oscillator", &o, "arclength"));
    PetscCall(CheckH1("1-DOF, three jenkins elements (m = 2 kg)", &o3, "arclength"));
    PetscCall(CheckEnergy("1-DOF jenkins oscillator", &o, 5));
    PetscCall(CheckEnergy("1-DOF, three jenkins elements", &o3, 3));
    PetscCall(CheckPeaks("1-DOF jenkins oscillator", &o, 1, 4, F));
    PetscCall(CheckPeaks("1-DOF jenkins oscillator", &o, 3, 4, F));
  }
  { /* the option checks: one-line user errors */
    Problem   p;
    JRNLModes nlm;
    const Osc o = {1, 1e4, 0.2, 1, {1e4}, {1}};
    PetscCall(CreateOsc(&o, "-nlm_mode 2 -nlm_output_file ''", &p));
    PetscCall(JRNLModesCreate(PETSC_COMM_WORLD, &nlm));
    PetscCall(JRNLModesSetHBM(nlm, p.hbm));
    PetscCall(JRNLModesSetFromOptions(nlm));
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    {
      PetscErrorCode ierr = JRNLModesSetUp(nlm);
      CHECK(ierr == PETSC_ERR_ARG_OUTOFRANGE, "-nlm_mode 2 on a one-DOF oscillator: refused (PETSC_ERR_ARG_OUTOFRANGE, got %d)", (int)ierr);
    }
    PetscCall(PetscPopErrorHandler());
    PetscCall(JRNLModesDestroy(&nlm));
    PetscCall(ProblemDestroy(&p));
  }
  PetscCall(SlepcFinalize());
  return jr_fail ? 1 : 0;
}
