/*
   Reduced-order joints, second reduction (thesis 4.2, cost 4.5; options prefix rom_).

   The first reduction (-rom_joints, src/reduce/reduce.c) lumps the node-to-node elements of a region into
   one joint: its members move with the joint's average relative motion (4.4) and its force is the sum of theirs
   (4.1-4.2). A member weighted by w (its motion over the joint's in the mode of interest; -rom_mode_weights) acts
   on the joint as the element (w^2 kt, |w| f). Here each joint's members are replaced by m elements (kt_i,
   f_i = mu N_i) by least squares (TAO, Gauss-Newton Hessian, bounds kt_i, f_i > 0) on
     - the loops under u = a cos(theta) at three amplitudes, each weighted by its own size (the cost 4.5): the
       slip displacements below which the fractions -rom_fit_fractions (0.25, 0.6, 0.95) of the slip force lie;
     - a stuck loop (the joint's stiffness), weighted 1e4: held (-rom_fit_stiffness_weight);
     - the energy dissipated per cycle, relative, at 6 amplitudes from the first slips (2% of the slip force) to
       the largest loop amplitude, weighted 0.05 each;
     - the joint's total slip force (gross slip), -rom_fit_gross_weight 1;
     - the case (amplitudes chosen from the joint's range of motion in the case at hand; JRROMCase from -task frf or
       compare): the modal amplitude of the mode of interest at resonance at every level by the energy balance of
       one cycle (pi F |phi.f| a = linear damping + the first-reduction joints' dissipation, stuck mode shape), and
       the energy per cycle at 24 amplitudes over each joint's range (its motion at the lowest level / 2 to the
       highest x 2), each error relative to all the energy dissipated at that amplitude: the share of the input
       the fit gets wrong, which is what moves the peak amplitude (-rom_fit_case_weight 10). After the fit, the
       error of all joints together at each level is printed (rom case level F dissipation_error).
   The slip displacements are chosen (-rom_fit_search) among a log grid over the members' range (down to a tenth of
   the case's smallest joint motion) and the log-width groups' own: every set of m (<= 20000 sets; else coordinate
   descent from the groups) scored by the non-negative least squares of its slip forces (every support of a Gram
   system: exact, deterministic). For the set found the slip forces f_i >= 0 are fitted by TAO: every residual is
   linear in f, so the problem is convex and its minimum unique (the same on any ranks); elements left without
   force are dropped. The "start" printed is the fit of the groups (sum f / sum kt of each log-width group of
   members, with their forces).
   -rom_fit_refine then frees the slip displacements (kt_i and f_i both): better loops, but not convex.
   Then, with a case, the fit coupled across joints (-rom_fit_total_weight 20; FitCoupled): the energy all joints
   together dissipate per cycle at the case's 24 amplitudes, relative to all the energy put in there, is added to
   every joint's own rows. Three kinks per joint cannot follow one joint's smooth energy curve over three decades of
   amplitude; the kinks of six joints, placed together, can follow their sum, which is what the peak amplitudes answer
   to. The slip displacements of all joints by coordinate descent (each element over its joint's candidates, every
   choice scored by the exact non-negative least squares of all forces, Lawson-Hanson), then all forces by TAO.
   Each joint's own loops may give way (the rom joint lines give each joint's own residual). Which total and case
   weights give the best peaks depends on the case; -rom_fit_select first (src/reduce/reduce.c) fits with several pairs
   and keeps the one whose reduced model's peaks come nearest the first reduction's (quiet: JRROMReduce's last
   argument).
   jenkins_nv joints (beyond the thesis): kt_i, f_i as above with the normal motion at rest (v = 0), n0_i = f_i / mu;
   then the normal stiffnesses kn_i (the thesis's kv) fitted to the joint's normal load-motion curve
   sum_e max(n0_e + kn_e v, 0) over v from the separation of every member to as much compression. With
   -rom_joint_motion mode the loops see each element under its normal load at rest; NormalVariation measures (AFT) what
   the normal load's variation in the mode changes in the energy per cycle, for the members and for the fit, prints
   the fit's error with it (rom case level F dissipation_error_normal_varying) and, with -rom_fit_normal_passes k,
   fits k more times with that change added to the targets (a defect correction; off by default: on lap3 it moved
   the peak amplitudes either way: docs/validation.md).
   This file: the case, the points of the joint fields, the coupled fit, the options and the passes (ReducePass,
   JRROMReduce); one joint's fit is in fitjoint.c, the least-squares problems in loops.c, their solvers (TAO, NNLS)
   in lsq.c.
   Saved and loaded with -rom_save / -rom_load (HDF5, /rom/...; src/reduce/io.c): the reduced elements and the members
   that define the joints' motion, with the members' node coordinates to check that the file fits the model.
*/
#include <jointrom/private/fitimpl.h>
#include <petscblaslapack.h>

/* An element list of n elements of one type with joints (and the node-to-node arrays if nodes), no DOFs */
PetscErrorCode JRROMElementsSetUp(JRElements *el, PetscInt n, const char type[], PetscBool nodes)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(el, sizeof(*el)));
  el->n      = n;
  el->ntypes = 1;
  PetscCall(PetscStrncpy(el->typename[0], type, sizeof(el->typename[0])));
  PetscCall(PetscMalloc5(n, &el->type, n, &el->dof_a, n, &el->dof_b, n, &el->ndof_a, n, &el->ndof_b));
  PetscCall(PetscMalloc4(n, &el->kt, n, &el->kn, n, &el->mu, n, &el->n0));
  PetscCall(PetscMalloc1(n, &el->joint));
  if (nodes) PetscCall(PetscMalloc4(3 * n, &el->vdof_a, 3 * n, &el->vdof_b, 3 * n, &el->tdir, 3 * n, &el->ndir));
  for (PetscInt e = 0; e < n; e++) {
    el->type[e]  = 0;
    el->dof_a[e] = el->dof_b[e] = el->ndof_a[e] = el->ndof_b[e] = -1;
  }
  PetscFunctionReturn(0);
}

int JRFitCompareDelta(const void *a, const void *b)
{
  const PetscReal x = ((const MemberDelta *)a)->delta, y = ((const MemberDelta *)b)->delta;
  return x < y ? -1 : x > y ? 1 : (((const MemberDelta *)a)->e < ((const MemberDelta *)b)->e ? -1 : 1);
}

/* Energy per cycle of a jenkins_nv element moving ut cos(theta) tangentially and vn cos(theta) normally (AFT a, one
   harmonic, ordered mean, sin, cos): W = pi (Us Fc - Uc Fs) with the force's first harmonic, all of it for a motion of
   one harmonic (JRHarmonicWork) */
static PetscReal EnergyNV(JRAFT *a, PetscReal kt, PetscReal kn, PetscReal mu, PetscReal n0, PetscReal ut, PetscReal vn)
{
  PetscReal    U[3] = {0, 0, ut}, V[3] = {0, 0, vn}, F[3] = {0, 0, 0};
  JRElementOut out;
  if (!(kt > 0) || !(mu > 0)) return 0;
  PetscMemzero(&out, sizeof(out));
  out.F = F;
  JRAFTElement(a, kt, kn, mu, n0, U, V, &out, NULL, NULL);
  return PETSC_PI * (U[1] * F[2] - U[2] * F[1]);
}

/* PetscPrintf unless quiet (the passes before the last of the fit with the normal-load variation) */
PetscErrorCode JRFitSay(PetscBool quiet, MPI_Comm comm, const char fmt[], ...)
{
  PetscMPIInt rank;
  va_list     ap;

  PetscFunctionBeginUser;
  if (quiet) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    va_start(ap, fmt);
    PetscCall((*PetscVFPrintf)(PETSC_STDOUT, fmt, ap));
    va_end(ap);
  }
  PetscFunctionReturn(0);
}

/* The case's modal amplitude l of NCASE, in equal ratios from half the lowest level's to twice the highest's */
PetscReal JRFitCaseAmplitude(const FitCtx *ctx, PetscInt l)
{
  return 0.5 * ctx->amin * PetscPowReal(4 * ctx->amax / ctx->amin, l / (PetscReal)(NCASE - 1));
}

/* The joints' dissipation at modal amplitude a of the case's mode: sum over members of the (weighted) Jenkins
   energy per cycle at their joint's motion |u_j| a */
PetscReal JRFitCaseDissipation(const FitCtx *ctx, PetscReal a)
{
  const JRElements *nn = ctx->nn;
  const PetscReal  *mk = ctx->mk, *mf = ctx->mf;
  PetscReal         D  = 0;
  for (PetscInt e = 0; e < nn->n; e++)
    if (mk[e] > 0 && mf[e] > 0) D += JRFitJenkinsEnergy(mk[e], mf[e], PetscAbsReal(ctx->cs->ujoint[nn->joint[e]]) * a, NULL, NULL);
  return D;
}

/* The modal amplitude a of the case's mode at resonance at every level F, by the energy balance of one cycle
   (single-mode, stuck mode shape): pi F force a = damp a^2 + D(a), where D (the joints' dissipation) grows faster
   than a, so the root is unique (bisection). Every rank the same. amod (NULL if the excitation does not drive the
   mode), amin, amax. */
static PetscErrorCode CaseAmplitudes(FitCtx *ctx)
{
  const JRROMCase *cs = ctx->cs;
  PetscReal       *a;

  PetscFunctionBeginUser;
  if (!(cs->force > 0)) {
    PetscCall(JRFitSay(ctx->quiet, ctx->comm, "rom: WARNING the excitation does not drive the mode of interest (stuck mode nearest the middle of the frequency range): the fit does not use the case's amplitudes\n"));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscMalloc1(cs->nlev, &a));
  for (PetscInt l = 0; l < cs->nlev; l++) {
    const PetscReal win = PETSC_PI * PetscAbsReal(cs->level[l]) * cs->force; /* input per cycle / a */
    PetscReal       lo = 0, hi = cs->damp > 0 ? win / cs->damp : 1.0, umax = 0, D;
    for (PetscInt j = 0; j < ctx->nn->njoints; j++) umax = PetscMax(umax, PetscAbsReal(cs->ujoint[j]));
    if (!(cs->damp > 0)) { /* no linear damping: bounded only if the joints' friction can absorb the input */
      PetscInt k = 0;
      while (win * hi - JRFitCaseDissipation(ctx, hi) > 0 && k++ < 200) hi *= 2;
      PetscCheck(k < 200, ctx->comm, PETSC_ERR_ARG_OUTOFRANGE, "Level %g N: without linear damping (-hbm_gamma, -hbm_zeta) the joints' friction cannot bound the resonance: no amplitudes for the fit", (double)cs->level[l]);
    }
    for (PetscInt it = 0; it < 200 && hi - lo > 1e-14 * hi; it++) {
      const PetscReal mid = 0.5 * (lo + hi);
      if (win * mid - cs->damp * mid * mid - JRFitCaseDissipation(ctx, mid) > 0) lo = mid;
      else hi = mid;
    }
    a[l] = 0.5 * (lo + hi);
    D    = JRFitCaseDissipation(ctx, a[l]);
    PetscCall(JRFitSay(ctx->quiet, ctx->comm, "rom case level %g modal_amplitude %.5e joint_amplitude_m %.4e joint_dissipation_share %.4f\n", (double)cs->level[l], (double)a[l], (double)(umax * a[l]), (double)(a[l] > 0 ? D / (win * a[l]) : 0.0)));
  }
  ctx->amod = a;
  ctx->amin = ctx->amax = a[0];
  for (PetscInt l = 1; l < cs->nlev; l++) {
    ctx->amin = PetscMin(ctx->amin, a[l]);
    ctx->amax = PetscMax(ctx->amax, a[l]);
  }
  PetscFunctionReturn(0);
}

/* The members' shares of joint j's mj fitted elements (ctx->cnt on: k, f in ek, ef): the elements in order of slip
   displacement f / k, the members (d[], in order of theirs) by their weighted stiffness mk; each element takes the
   next share k / sum k of the members' stiffness, a member on a boundary shared in proportion. Calls add(ctx, e, g,
   fr, user) for member e's fraction fr in element g. */
static PetscErrorCode MemberShares(FitCtx *ctx, PetscInt j, PetscInt mj, PetscErrorCode (*add)(FitCtx *, PetscInt, PetscInt, PetscReal, void *), void *user)
{
  const MemberDelta *d  = ctx->md + ctx->joff[j];
  const PetscInt     nm = ctx->jn[j];
  const PetscReal   *mk = ctx->mk, *k = ctx->ek + ctx->cnt, *f = ctx->ef + ctx->cnt;
  PetscReal          ksum = 0, msum = 0, c0 = 0, *lo;
  PetscInt          *ord;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(mj + 1, &lo, mj, &ord));
  for (PetscInt g = 0; g < mj; g++) ord[g] = g;
  for (PetscInt a = 1; a < mj; a++) /* the elements by slip displacement (insertion sort: mj is small) */
    for (PetscInt b = a; b > 0 && f[ord[b]] * k[ord[b - 1]] < f[ord[b - 1]] * k[ord[b]]; b--) {
      const PetscInt t = ord[b];
      ord[b]           = ord[b - 1];
      ord[b - 1]       = t;
    }
  for (PetscInt g = 0; g < mj; g++) ksum += k[g];
  for (PetscInt i = 0; i < nm; i++) msum += mk[d[i].e];
  lo[0] = 0; /* element ord[a] takes the members' stiffness from lo[a] to lo[a + 1] (its share of theirs) */
  for (PetscInt a = 0; a < mj; a++) lo[a + 1] = lo[a] + (ksum > 0 ? k[ord[a]] / ksum : 1.0 / mj) * msum;
  lo[mj] = msum;
  for (PetscInt i = 0, a = 0; i < nm; i++) {
    const PetscInt  e  = d[i].e;
    const PetscReal c1 = c0 + mk[e]; /* the member's stiffness from c0 to c1 */
    while (a < mj - 1 && lo[a + 1] <= c0) a++;
    for (PetscInt b = a; b < mj && lo[b] < c1; b++) { /* the member's share in element ord[b] */
      const PetscReal fr = mk[e] > 0 ? (PetscMin(c1, lo[b + 1]) - PetscMax(c0, lo[b])) / mk[e] : (b == a ? 1.0 : 0.0);
      if (fr > 0) PetscCall(add(ctx, e, ord[b], fr, user));
    }
    c0 = c1;
  }
  PetscCall(PetscFree2(lo, ord));
  PetscFunctionReturn(0);
}

/* SpreadPoints' sums per element: weight, sum w p (3), sum w p p^T (9) */
static PetscErrorCode SpreadAdd(FitCtx *ctx, PetscInt e, PetscInt g, PetscReal fr, void *user)
{
  PetscReal       *acc = (PetscReal *)user + 13 * g;
  const PetscReal *p = ctx->nn->pos + 3 * e, w = fr * ctx->mk[e];

  PetscFunctionBeginUser;
  acc[0] += w;
  for (PetscInt a = 0; a < 3; a++) {
    acc[1 + a] += w * p[a];
    for (PetscInt b = 0; b < 3; b++) acc[4 + 3 * a + b] += w * p[a] * p[b];
  }
  PetscFunctionReturn(0);
}

/* -rom_joint_motion linear: where joint j's mj fitted elements take its linear motion field. Element g stands for the
   members whose stiffness it has (MemberShares: in slip order, each element the next share of the members'
   stiffness equal to its own); it is split into three equal parts at the points c + sqrt(2) (s1 cos t e1 + s2 sin t
   e2), t = 0, 2 pi/3, 4 pi/3, where c is the group's stiffness-weighted centroid and s_a^2, e_a the eigenpairs of its
   in-plane covariance: the three points have the group's centroid and second moment, so the parts carry the joint's
   rotation with the members' stiffness (parallel axis theorem) and, moved uniformly, act as the element itself. Into
   ep, JR_EP per element (three points; their positions only) */
PetscErrorCode JRFitSpreadPoints(FitCtx *ctx, PetscInt j, PetscInt mj)
{
  PetscReal *P = ctx->ep + JR_EP * ctx->cnt;
  PetscReal *acc; /* per element: weight, sum w p (3), sum w p p^T (9) */

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(13 * mj, &acc));
  PetscCall(MemberShares(ctx, j, mj, SpreadAdd, acc));
  for (PetscInt g = 0; g < mj; g++) {
    const PetscReal *r = acc + 13 * g;
    PetscReal        c[3] = {0, 0, 0}, C[9], lam[3], work[64];
    PetscBLASInt     n = 3, lwork = 64, info;
    if (r[0] > 0)
      for (PetscInt a = 0; a < 3; a++) c[a] = r[1 + a] / r[0];
    for (PetscInt a = 0; a < 3; a++)
      for (PetscInt b = 0; b < 3; b++) C[3 * a + b] = r[0] > 0 ? r[4 + 3 * a + b] / r[0] - c[a] * c[b] : 0.0;
    PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &n, C, &n, lam, work, &lwork, &info));
    PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed (%d)", (int)info);
    for (PetscInt k = 0; k < 3; k++) { /* the two largest spreads: the interface's plane (the third is ~0) */
      const PetscReal t = 2 * PETSC_PI * k / 3, s1 = PetscSqrtReal(2 * PetscMax(lam[2], 0)), s2 = PetscSqrtReal(2 * PetscMax(lam[1], 0));
      for (PetscInt a = 0; a < 3; a++) P[JR_EP * g + 5 * k + a] = c[a] + s1 * PetscCosReal(t) * C[6 + a] + s2 * PetscSinReal(t) * C[3 + a];
    }
  }
  PetscCall(PetscFree(acc));
  PetscFunctionReturn(0);
}

/* ModePoints' sums per element (JR_MODE_SUMS): sum f phi_t, sum kt, sum kt phi_t^2, sum kn, sum kn phi_n,
   sum kn phi_n^2, sum kt x (3), sum n0, sum kt phi_t, sum kt phi_t phi_n, then per released mode sum kt phi_r,
   sum kt phi_r phi_t */
#define JR_MODE_SUMS (12 + 2 * JR_NREL)
static PetscErrorCode ModeAdd(FitCtx *ctx, PetscInt e, PetscInt g, PetscReal fr, void *user)
{
  const JRElements *nn = ctx->nn;
  const PetscReal   pt = nn->phi[2 * e], pn = nn->phi[2 * e + 1];
  PetscReal        *r  = (PetscReal *)user + JR_MODE_SUMS * g;

  PetscFunctionBeginUser;
  r[0] += fr * nn->mu[e] * nn->n0[e] * pt;
  r[1] += fr * nn->kt[e];
  r[2] += fr * nn->kt[e] * pt * pt;
  r[3] += fr * nn->kn[e];
  r[4] += fr * nn->kn[e] * pn;
  r[5] += fr * nn->kn[e] * pn * pn;
  for (PetscInt x = 0; x < 3; x++) r[6 + x] += fr * nn->kt[e] * nn->pos[3 * e + x];
  r[9] += fr * PetscMax(nn->n0[e], 0);
  r[10] += fr * nn->kt[e] * pt;
  r[11] += fr * nn->kt[e] * pt * pn;
  for (PetscInt c = 0; nn->phir && c < JR_NREL; c++) { /* the released modes' phi_r: sum kt phi_r, sum kt phi_r phi_t */
    r[12 + 2 * c] += fr * nn->kt[e] * nn->phir[JR_NREL * e + c];
    r[13 + 2 * c] += fr * nn->kt[e] * nn->phir[JR_NREL * e + c] * pt;
  }
  PetscFunctionReturn(0);
}

/* -rom_joint_motion mode: where joint j's mj fitted elements take its field over the members' positions and stuck-mode
   motions (nn->phi: tangential phi_t, normal phi_n), and what they carry there. The fit saw the members weighted by
   phi_t / its mean over the members in contact at rest (w^2 kt, |w| f): elements k, f moving with that mean. Element g
   stands for the members whose stiffness it has: the elements in order of slip displacement f / k, the members in
   order of theirs, each element takes the next share k of the members' stiffness w^2 kt (a member on a boundary
   shared in proportion). It takes its group's place in the field, in two halves at the group's kt-weighted centroid
   and at its kt-weighted mean -/+ spread of phi_t and kn-weighted mean -/+ spread of phi_n (paired as they covary;
   jenkins: one point at the root mean square phi_t, rms). So it moves as its members do in every motion the field
   carries (a point off the members' coordinates would take the field's extrapolation there), and its springs
   k (mean / rms)^2 (the group's total kt) have the group's first and second moments: the stuck mode loads it as its
   members. Each half's slip force is in proportion to its |phi_t| (PartShare), so both slip at the same modal
   amplitude: in the mode the fitted element, slip force f |mean / rms|. Normally it is the group: its total kn
   (normal stiffness sum kn phi_n^2 and load change sum kn phi_n in the mode) and normal load N at rest, so it
   separates as its members do on average, with the friction coefficient that gives the fitted slip force,
   f |mean / rms| / N. For the elements from ctx->cnt on (fitted k, f in ek, ef): ep, JR_EP each (two points of 5
   coordinates); er: mean / rms (k becomes k er^2); ekn, en0, emu: the group's total kn and N, the friction
   coefficient */
PetscErrorCode JRFitModePoints(FitCtx *ctx, PetscInt j, PetscInt mj)
{
  const JRElements *nn = ctx->nn;
  const PetscReal  *f  = ctx->ef + ctx->cnt;
  PetscReal        *ratio = ctx->er + ctx->cnt, *kn = ctx->ekn + ctx->cnt, *n0 = ctx->en0 + ctx->cnt, *mu = ctx->emu + ctx->cnt, *P = ctx->ep + JR_EP * ctx->cnt;
  PetscReal         mean = 0, cnt = 0, umax = 0, *acc; /* per element: ModeAdd's sums */

  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < nn->n; e++) { /* the mean the weights were taken over (as in JRTaskFRF) */
    umax = PetscMax(umax, PetscAbsReal(nn->phi[2 * e]));
    if (nn->joint[e] == j && nn->n0[e] > 0) {
      mean += nn->phi[2 * e];
      cnt += 1;
    }
  }
  mean = cnt > 0 ? mean / cnt : 0;
  PetscCall(PetscCalloc1(JR_MODE_SUMS * mj, &acc));
  PetscCall(MemberShares(ctx, j, mj, ModeAdd, acc));
  for (PetscInt g = 0; g < mj; g++) {
    const PetscReal *r = acc + JR_MODE_SUMS * g, m = r[3] > 0 ? r[4] / r[3] : 0, s = r[3] > 0 ? PetscSqrtReal(PetscMax(r[5] / r[3] - m * m, 0)) : 0;
    const PetscReal  mt = r[1] > 0 ? r[10] / r[1] : 0, st = r[1] > 0 ? PetscSqrtReal(PetscMax(r[2] / r[1] - mt * mt, 0)) : 0;
    const PetscReal  ctn = r[1] > 0 ? r[11] / r[1] - mt * (r[3] > 0 ? r[4] / r[3] : 0) : 0; /* the sign of phi_t's and phi_n's covariance */
    PetscReal        psi = r[1] > 0 ? PetscSqrtReal(r[2] / r[1]) : 0;
    if (r[0] < 0) psi = -psi;
    if (!(PetscAbsReal(mean) > 1e-6 * umax) || !(PetscAbsReal(psi) > 1e-6 * umax)) psi = mean; /* no weights were used */
    ratio[g] = psi != 0 ? mean / psi : 1.0;
    kn[g]    = r[3];
    if (r[9] > 0) { /* the group's normal load; the friction coefficient that gives the fitted slip force */
      n0[g] = r[9] / PetscAbsReal(ratio[g]);
      mu[g] = f[g] * PetscAbsReal(ratio[g]) / r[9];
    }
    for (PetscInt h = 0; h < 2; h++) { /* two halves: phi_t and phi_n at their means -/+ spreads, paired as they covary */
      const PetscReal sg = h ? 1.0 : -1.0;
      for (PetscInt a = 0; a < 3; a++) P[JR_EP * g + 5 * h + a] = r[1] > 0 ? r[6 + a] / r[1] : 0;
      P[JR_EP * g + 5 * h + 3] = psi == mean || !ctx->nv ? psi : mt + sg * st;
      P[JR_EP * g + 5 * h + 4] = m + (ctn < 0 ? -sg : sg) * s;
      for (PetscInt c = 0; nn->phir && c < JR_NREL; c++) { /* released modes: each phi_r at its kt-weighted mean and
                                                               regression on phi_t (the group's covariance kept) */
        const PetscReal xm = r[1] > 0 ? r[12 + 2 * c] / r[1] : 0, cov = r[1] > 0 ? r[13 + 2 * c] / r[1] - xm * mt : 0;
        ctx->epr[2 * JR_NREL * (ctx->cnt + g) + JR_NREL * h + c] = xm + (st > 0 ? cov / (st * st) * (P[JR_EP * g + 5 * h + 3] - mt) : 0);
      }
    }
  }
  PetscCall(PetscFree(acc));
  PetscFunctionReturn(0);
}

/* -rom_joint_motion mode, jenkins_nv: a joint's open members od[] (n0 <= 0, sorted by gap -n0 / kn) in ng groups of
   equal count, each an element e0 + g with the group's total kt, kn and n0 (a gap that closes as
   the members' does on average) at the members' mean phi_t and, in two halves, at psi_n = m -/+ s (kn-weighted mean and
   spread of phi_n) */
PetscErrorCode JRFitOpenPoints(FitCtx *ctx, const MemberDelta *od, PetscInt no, PetscInt ng, PetscInt e0)
{
  const JRElements *nn = ctx->nn;
  PetscReal        *k = ctx->ek + e0, *n0 = ctx->en0 + e0, *kn = ctx->ekn + e0, *mu = ctx->emu + e0, *P = ctx->ep + JR_EP * e0;

  PetscFunctionBeginUser;
  for (PetscInt g = 0; g < ng; g++) {
    const PetscInt i0 = g * no / ng, i1 = (g + 1) * no / ng;
    PetscReal      st = 0, sk = 0, skn = 0, sn0 = 0, smu = 0, s1 = 0, s2 = 0, sx[3] = {0, 0, 0}, m, s;
    for (PetscInt i = i0; i < i1; i++) {
      const PetscInt e = od[i].e;
      const PetscReal pn = nn->phi[2 * e + 1];
      st += nn->phi[2 * e];
      for (PetscInt a = 0; a < 3; a++) sx[a] += nn->pos[3 * e + a];
      sk += nn->kt[e];
      skn += nn->kn[e];
      sn0 += nn->n0[e];
      smu += nn->mu[e];
      s1 += nn->kn[e] * pn;
      s2 += nn->kn[e] * pn * pn;
    }
    m            = s1 / skn;
    s            = PetscSqrtReal(PetscMax(s2 / skn - m * m, 0));
    k[g]         = sk;
    kn[g]        = skn;
    n0[g]        = sn0;
    mu[g]        = smu / (i1 - i0);
    for (PetscInt h = 0; h < 2; h++) {
      for (PetscInt a = 0; a < 3; a++) P[JR_EP * g + 5 * h + a] = sx[a] / (i1 - i0);
      P[JR_EP * g + 5 * h + 3] = st / (i1 - i0);
      P[JR_EP * g + 5 * h + 4] = h ? m + s : m - s;
      for (PetscInt c = 0; nn->phir && c < JR_NREL; c++) { /* released modes: the members' mean motions in them */
        PetscReal x = 0;
        for (PetscInt i = i0; i < i1; i++) x += nn->phir[JR_NREL * od[i].e + c];
        ctx->epr[2 * JR_NREL * (e0 + g) + JR_NREL * h + c] = x / (i1 - i0);
      }
    }
  }
  PetscFunctionReturn(0);
}

/* The coupled fit's joints (CoupledFit): those with more members than elements (cf->nj of them, counted), from their
   own fits: slip displacements, forces y and the ranges dl, dh of their candidates */
static PetscErrorCode CoupledSetUp(FitCtx *ctx, CoupledFit *cf, PetscReal **y, PetscReal **dl, PetscReal **dh)
{
  PetscInt ldmax = 0, mmax = 0;

  PetscFunctionBeginUser;
  cf->na = NCASE;
  cf->w  = ctx->fit->wtotal / PetscSqrtReal((PetscReal)NCASE);
  PetscCall(PetscMalloc7(cf->nj, &cf->jl, cf->nj, &cf->fx, cf->nj + 1, &cf->off, cf->nj + 1, &cf->roff, cf->nj, &cf->u, cf->nj, dl, cf->nj, dh));
  cf->off[0] = cf->roff[0] = 0;
  for (PetscInt j = 0, k = 0; j < ctx->nj; j++) {
    const JointFit *f = &ctx->jf[j];
    if (!(ctx->jn[j] > ctx->jm[j])) continue;
    cf->jl[k]       = j;
    cf->u[k]        = PetscAbsReal(ctx->cs->ujoint[j]);
    (*dl)[k]        = f->dlo;
    (*dh)[k]        = f->dhi;
    cf->off[k + 1]  = cf->off[k] + f->m;
    cf->roff[k + 1] = cf->roff[k] + FitRows(&f->t);
    ldmax           = PetscMax(ldmax, FitRows(&f->t));
    mmax            = PetscMax(mmax, f->m);
    k++;
  }
  cf->n = cf->off[cf->nj];
  PetscCall(PetscMalloc6(cf->n, y, NCASE, &cf->am, NCASE, &cf->Et, NCASE, &cf->En, ldmax, &cf->rj, mmax * ldmax, &cf->Jj));
  for (PetscInt k = 0; k < cf->nj; k++) {
    JointFit      *f  = &ctx->jf[cf->jl[k]];
    const PetscInt mj = f->m;
    cf->fx[k].t       = &f->t;
    PetscCall(PetscMalloc3(mj, &cf->fx[k].delta, 2 * mj, &cf->fx[k].x, FitRows(&f->t) * 2 * mj, &cf->fx[k].J2));
    for (PetscInt i = 0; i < mj; i++) {
      cf->fx[k].delta[i]  = f->t.delta[i];
      (*y)[cf->off[k] + i] = f->x[mj + i];
    }
  }
  PetscFunctionReturn(0);
}

/* The rows of all joints: at the case's amplitudes (as the joints' own case rows) all the energy put in (En) and the
   target Et: the members' dissipation less that of the joints not fitted, plus the normal-load variation nvin */
static void CoupledTargets(const FitCtx *ctx, CoupledFit *cf)
{
  const JRElements *nn = ctx->nn;
  const JRROMCase  *cs = ctx->cs;
  const PetscReal  *mk = ctx->mk, *mf = ctx->mf;

  for (PetscInt l = 0; l < NCASE; l++) {
    const PetscReal am = JRFitCaseAmplitude(ctx, l), D = JRFitCaseDissipation(ctx, am);
    cf->am[l] = am;
    cf->En[l] = cs->damp * am * am + D;
    cf->Et[l] = D;
    for (PetscInt e = 0; e < nn->n; e++)
      if (!(ctx->jn[nn->joint[e]] > ctx->jm[nn->joint[e]]) && mk[e] > 0 && mf[e] > 0) cf->Et[l] -= JRFitJenkinsEnergy(mk[e], mf[e], PetscAbsReal(cs->ujoint[nn->joint[e]]) * am, NULL, NULL);
    for (PetscInt j = 0; ctx->nvin && j < ctx->nj; j++) /* the normal-load variation (JRFitNormalVariation) */
      if (ctx->jn[j] > ctx->jm[j]) cf->Et[l] += ctx->nvin[j * NCASE + l];
    if (!(cf->En[l] > 0)) cf->En[l] = 1;
  }
}

/* The coupled residual r at y (J its Jacobian) and its norms: of the joints' own rows and of the rows of all joints */
static PetscErrorCode CoupledNorms(CoupledFit *cf, const PetscReal y[], PetscReal r[], PetscReal J[], PetscReal *own, PetscReal *all)
{
  const PetscInt nr = CoupledRows(cf);
  PetscReal      o = 0, t = 0;

  PetscFunctionBeginUser;
  PetscCall(JRFitCoupledResidual(cf, y, r, J));
  for (PetscInt i = 0; i < nr; i++) {
    if (i < cf->roff[cf->nj]) o += r[i] * r[i];
    else t += r[i] * r[i];
  }
  *own = PetscSqrtReal(o);
  *all = PetscSqrtReal(t);
  PetscFunctionReturn(0);
}

/* The fit coupled across joints (CoupledFit): the joints with more members than elements, from their own fits,
   their slip displacements chosen together (JRFitCoupledSearch) and their forces fitted together by TAO; their x, rms (each
   joint's own rows) and its updated. Joints whose members are their elements stay as they are (their energy is
   taken off the target). Prints one line. */
static PetscErrorCode FitCoupled(FitCtx *ctx)
{
  CoupledFit cf;
  PetscInt   sweeps = 0, its = 0, nr;
  PetscReal *y, *dl, *dh, *r, *J, cost0, cost, r0, r1, own0 = 0, own1 = 0, tot0 = 0, tot1 = 0;
  JRLSQ      q;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&cf, sizeof(cf)));
  for (PetscInt j = 0; j < ctx->nj; j++) cf.nj += ctx->jn[j] > ctx->jm[j];
  if (!cf.nj) PetscFunctionReturn(0);
  PetscCall(CoupledSetUp(ctx, &cf, &y, &dl, &dh));
  CoupledTargets(ctx, &cf);
  nr = CoupledRows(&cf);
  PetscCall(PetscMalloc2(nr, &r, nr * cf.n, &J));
  PetscCall(CoupledNorms(&cf, y, r, J, &own0, &tot0));
  PetscCall(JRFitCoupledSearch(&cf, dl, dh, y, &cost0, &cost, &sweeps));
  q.nx  = cf.n;
  q.nr  = nr;
  q.fn  = JRFitCoupledResidual;
  q.ctx = &cf;
  PetscCall(JRLSQSolve(&q, y, 0.0, &r0, &r1, &its));
  PetscCall(CoupledNorms(&cf, y, r, J, &own1, &tot1));
  for (PetscInt k = 0; k < cf.nj; k++) {
    JointFit      *f  = &ctx->jf[cf.jl[k]];
    const PetscInt mj = f->m, ld = FitRows(&f->t);
    PetscReal      s  = 0;
    for (PetscInt i = 0; i < mj; i++) {
      f->x[i]      = f->t.fs * y[cf.off[k] + i] / (cf.fx[k].delta[i] * f->t.ks);
      f->x[mj + i] = y[cf.off[k] + i];
    }
    for (PetscInt q = 0; q < ld; q++) s += r[cf.roff[k] + q] * r[cf.roff[k] + q];
    f->rms = PetscSqrtReal(s);
    f->its += its;
    PetscCall(PetscFree3(cf.fx[k].delta, cf.fx[k].x, cf.fx[k].J2));
  }
  PetscCall(JRFitSay(ctx->quiet, ctx->comm, "rom coupled joints %" PetscInt_FMT " elements %" PetscInt_FMT " all_joints_energy_residual %.3e each_alone %.3e own_rows_residual %.3e each_alone %.3e sweeps %" PetscInt_FMT " tao_its %" PetscInt_FMT "\n", cf.nj, cf.n, (double)tot1, (double)tot0, (double)own1, (double)own0, sweeps, its));
  PetscCall(PetscFree2(r, J));
  PetscCall(PetscFree6(y, cf.am, cf.Et, cf.En, cf.rj, cf.Jj));
  PetscCall(PetscFree7(cf.jl, cf.fx, cf.off, cf.roff, cf.u, dl, dh));
  PetscFunctionReturn(0);
}

/* -rom_joint_motion mode, jenkins_nv: the fit sees every element's loops under its normal load at rest (JRFitJenkinsLoop,
   JRFitJenkinsEnergy); in the model the normal load follows the normal motion, and separates. What that changes in the
   energy per cycle, at the case's amplitudes am_l (JRFitCaseAmplitude), for the members and for the reduced elements rom
   (each moving with its stuck-mode coordinates phi x the case's scale, by AFT, one harmonic, 256 samples):
     nv[j NCASE + l] = (D_members,nv - D_members,fixed) - (D_rom,nv - D_rom,fixed)   joint j
   The next fit adds it to its energy targets: its elements' fixed-load energy then aims at what, with their normal
   load varying, gives the members' energy with theirs varying (a defect correction: repeated, it converges when the
   rom's share changes little from fit to fit). nvmax: the largest |sum_j nv| at any am_l, relative to the input
   there. Unless quiet, prints the error of the rom's energy with the normal variation at the case's levels. */
PetscErrorCode JRFitNormalVariation(const FitCtx *ctx, const JRElements *rom, PetscReal nv[], PetscReal *nvmax)
{
  const JRElements *nn = ctx->nn;
  const JRROMCase  *cs = ctx->cs;
  const PetscInt    nj = nn->njoints, na = NCASE;
  PetscReal         sc = 0, best = 0;
  JRAFT            *af;

  PetscFunctionBeginUser;
  for (PetscInt j = 0; j < nj; j++) { /* phi is the mode's motion / its largest; the joints' motion in the case's units */
    PetscReal mp = 0, c = 0;
    for (PetscInt e = 0; e < nn->n; e++)
      if (nn->joint[e] == j && nn->n0[e] > 0) {
        mp += nn->phi[2 * e];
        c += 1;
      }
    mp = c > 0 ? mp / c : 0;
    if (PetscAbsReal(mp) > best) {
      best = PetscAbsReal(mp);
      sc   = PetscAbsReal(cs->ujoint[j] / mp);
    }
  }
  PetscCall(JRAFTCreate(1, 256, &af));
  *nvmax = 0;
  for (PetscInt l = 0; l < na; l++) {
    const PetscReal am = JRFitCaseAmplitude(ctx, l), a = sc * am;
    PetscReal       tot = 0, fixed = 0;
    for (PetscInt j = 0; j < nj; j++) nv[j * na + l] = 0;
    for (PetscInt e = 0; e < nn->n; e++) {
      const PetscReal d0 = EnergyNV(af, nn->kt[e], nn->kn[e], nn->mu[e], nn->n0[e], nn->phi[2 * e] * a, 0);
      nv[nn->joint[e] * na + l] += EnergyNV(af, nn->kt[e], nn->kn[e], nn->mu[e], nn->n0[e], nn->phi[2 * e] * a, nn->phi[2 * e + 1] * a) - d0;
      fixed += d0;
    }
    for (PetscInt r = 0; r < rom->n; r++)
      nv[rom->joint[r] * na + l] -= EnergyNV(af, rom->kt[r], rom->kn[r], rom->mu[r], rom->n0[r], rom->phi[2 * r] * a, rom->phi[2 * r + 1] * a) - EnergyNV(af, rom->kt[r], rom->kn[r], rom->mu[r], rom->n0[r], rom->phi[2 * r] * a, 0);
    for (PetscInt j = 0; j < nj; j++) tot += nv[j * na + l];
    *nvmax = PetscMax(*nvmax, PetscAbsReal(tot) / (cs->damp * am * am + fixed));
  }
  for (PetscInt l = 0; !ctx->quiet && l < cs->nlev; l++) {
    const PetscReal a = sc * ctx->amod[l];
    PetscReal       dm = 0, dr = 0;
    for (PetscInt e = 0; e < nn->n; e++) dm += EnergyNV(af, nn->kt[e], nn->kn[e], nn->mu[e], nn->n0[e], nn->phi[2 * e] * a, nn->phi[2 * e + 1] * a);
    for (PetscInt r = 0; r < rom->n; r++) dr += EnergyNV(af, rom->kt[r], rom->kn[r], rom->mu[r], rom->n0[r], rom->phi[2 * r] * a, rom->phi[2 * r + 1] * a);
    PetscCall(JRFitSay(ctx->quiet, ctx->comm, "rom case level %g dissipation_error_normal_varying %+.3e (of the input per cycle; members %.4f)\n", (double)cs->level[l], (double)((dr - dm) / (PETSC_PI * PetscAbsReal(cs->level[l]) * cs->force * ctx->amod[l])), (double)(dm / (PETSC_PI * PetscAbsReal(cs->level[l]) * cs->force * ctx->amod[l]))));
  }
  PetscCall(JRAFTDestroy(&af));
  PetscFunctionReturn(0);
}

/*
  JRROMFitSetFromOptions - the second reduction's fit options (prefix rom_), read and checked once: -rom_fit_fractions,
  -rom_fit_energy_from, -rom_fit_refine, -rom_fit_perturb, -rom_fit_samples, -rom_fit_case_weight,
  -rom_fit_total_weight, -rom_fit_gross_weight, -rom_fit_stiffness_weight, -rom_fit_normal_passes, -rom_fit_search and
  -rom_joint_motion
*/
PetscErrorCode JRROMFitSetFromOptions(MPI_Comm comm, JRROMFit *f)
{
  PetscReal fr[3] = {0.25, 0.6, 0.95};
  PetscInt  nfr = 3;
  PetscBool frset, tolset;

  PetscFunctionBeginUser;
  f->efrom   = 0.02;
  f->refine  = PETSC_FALSE;
  f->perturb = 0;
  f->ns      = 128;
  f->wcase   = 10.0;
  f->wtotal  = 20.0;
  f->wgross  = 1.0;
  f->wstiff  = 1e4;
  f->npass   = 0;
  f->jmotion = 0;
  f->resid   = PETSC_FALSE;
  f->search  = PETSC_TRUE;
  f->mmax    = 0;
  f->looptol = 0.1;
  PetscOptionsBegin(comm, "rom_", "Second reduction: m elements per joint fitted to its hysteresis loops (prefix rom_)", "JRROMReduce");
  PetscCall(PetscOptionsRealArray("-fit_fractions", "Loop amplitudes: the slip displacements below which these fractions of the joint's slip force lie (microslip to gross slip)", "JRROMReduce", fr, &nfr, &frset));
  PetscCall(PetscOptionsReal("-fit_energy_from", "Energy per cycle matched from the amplitude where this fraction of the slip force has slipped", "JRROMReduce", f->efrom, &f->efrom, NULL));
  PetscCall(PetscOptionsBool("-fit_refine", "After the convex fit on fixed slip displacements, free them too (a non-convex refinement: better loops, but its minimum can move with round-off)", "JRROMReduce", f->refine, &f->refine, NULL));
  PetscCall(PetscOptionsReal("-fit_perturb", "Perturb the start of the fit by this fraction (tests: the fit must recover)", "JRROMReduce", f->perturb, &f->perturb, NULL));
  PetscCall(PetscOptionsInt("-fit_samples", "Samples per loop", "JRROMReduce", f->ns, &f->ns, NULL));
  PetscCall(PetscOptionsReal("-fit_case_weight", "Weight of the energy dissipated per cycle at each joint's amplitude in the case (relative to the input energy at that level; 0: not fitted)", "JRROMReduce", f->wcase, &f->wcase, NULL));
  PetscCall(PetscOptionsReal("-fit_total_weight", "Weight of the energy all joints together dissipate per cycle at the case's amplitudes (relative to the input energy; a fit coupled across joints; 0: each joint fitted alone)", "JRROMReduce", f->wtotal, &f->wtotal, NULL));
  PetscCall(PetscOptionsReal("-fit_gross_weight", "Weight of the joint's total slip force (gross slip), relative", "JRROMReduce", f->wgross, &f->wgross, NULL));
  PetscCall(PetscOptionsReal("-fit_stiffness_weight", "Weight of the joint's stuck stiffness (its stuck loop), relative to one loop", "JRROMReduce", f->wstiff, &f->wstiff, NULL));
  PetscCall(PetscOptionsInt("-fit_normal_passes", "-rom_joint_motion mode, jenkins_nv, with a case: fit again this many times, each with the change the normal-load variation makes to the energy per cycle (members' and the previous fit's) added to the energy targets (0: once, fixed normal loads)", "JRROMReduce", f->npass, &f->npass, NULL));
  {
    PetscCall(PetscOptionsEList("-joint_motion", "How a joint's members move: mean (4.4), linear (a field over their positions: each fitted element is spread over three points of its members' spread), mode (a field over their positions and motions in the stuck mode of interest: each fitted element sits at its members' motion) or shapes (the tangential rows over their positions and tangential motions in the stuck mode of interest and in released modes, -rom_release_fractions; the normal rows over their normal motion in it)", "JRROMReduce", JRJointMotions, 4, JRJointMotions[f->jmotion], &f->jmotion, NULL));
  }
  PetscCall(PetscOptionsBool("-joint_residual", "Keep each member's stuck springs, linear, on its motion outside its joint's field (the residual of the field's fit); the joints' elements replace only those on the field's motion, so the reduced model stuck is node-to-node stuck", "JRROMReduce", f->resid, &f->resid, NULL));
  PetscCall(PetscOptionsInt("-fit_elements_max", "A joint whose members' loops its -rom_elements elements fit worse than -rom_fit_loop_tol (its loop_residual) gets one element more, and again, up to this many (0: every joint -rom_elements)", "JRROMReduce", f->mmax, &f->mmax, NULL));
  PetscCall(PetscOptionsReal("-fit_loop_tol", "-rom_fit_elements_max: the loop residual a joint's elements are grown to reach", "JRROMReduce", f->looptol, &f->looptol, &tolset));
  PetscCall(PetscOptionsBool("-fit_search", "Choose the slip displacements among a grid over the members' range (best non-negative least squares of the forces); else those of the log-width groups of members", "JRROMReduce", f->search, &f->search, NULL));
  PetscOptionsEnd();
  PetscCheck(f->wgross >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_gross_weight %g: the weight must be non-negative", (double)f->wgross);
  PetscCheck(f->wtotal >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_total_weight %g: the weight must be non-negative (0: each joint fitted alone)", (double)f->wtotal);
  PetscCheck(f->wstiff > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_stiffness_weight %g: the weight must be positive", (double)f->wstiff);
  PetscCheck(f->npass >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_normal_passes %" PetscInt_FMT ": 0 or more", f->npass);
  PetscCheck(f->wcase >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_case_weight %g: the weight must be non-negative (0: the case is not fitted)", (double)f->wcase);
  if (!frset) nfr = 3;
  PetscCheck(nfr == 3 && fr[0] > 0 && fr[1] > fr[0] && fr[2] > fr[1] && fr[2] <= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_fractions: three increasing fractions in (0, 1] (default 0.25,0.6,0.95)");
  PetscCheck(f->mmax >= 0 && f->mmax <= 8, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_elements_max %" PetscInt_FMT ": 0 (off) or up to 8 elements per joint", f->mmax);
  PetscCheck(!tolset || f->mmax, comm, PETSC_ERR_ARG_INCOMP, "-rom_fit_loop_tol needs -rom_fit_elements_max (the most elements a joint may grow to)");
  PetscCheck(f->looptol > 0 && f->looptol < 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_loop_tol %g: a residual in (0, 1)", (double)f->looptol);
  PetscCheck(f->ns >= 8, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_samples %" PetscInt_FMT ": at least 8", f->ns);
  for (PetscInt i = 0; i < 3; i++) f->fr[i] = fr[i];
  PetscFunctionReturn(0);
}

/* The checks of a fit, and its kind: jenkins or jenkins_nv joints, -rom_joint_motion */
static PetscErrorCode FitCheck(FitCtx *ctx)
{
  const JRElements *nn = ctx->nn;
  MPI_Comm          comm = ctx->comm;

  PetscFunctionBeginUser;
  ctx->nj = nn->njoints;
  PetscCheck(nn->joint && ctx->nj > 0 && !nn->members, comm, PETSC_ERR_ARG_WRONG, "-rom_elements needs joints (the first reduction): -rom_joints strips|bolts|between|sides|zones");
  PetscCheck(ctx->m >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_elements %" PetscInt_FMT ": 0 (the members themselves) or more elements per joint", ctx->m);
  PetscCheck(nn->ntypes == 1, comm, PETSC_ERR_SUP, "The second reduction needs one element type in the interface");
  ctx->nv = (PetscBool)!strcmp(nn->typename[0], JRCONTACTJENKINSNV);
  PetscCheck(ctx->nv || !strcmp(nn->typename[0], JRCONTACTJENKINS), comm, PETSC_ERR_SUP, "The second reduction fits jenkins and jenkins_nv joints, not %s", nn->typename[0]);
  ctx->spread = (PetscBool)(ctx->fit->jmotion == 1);
  ctx->modef  = (PetscBool)(ctx->fit->jmotion == JR_JOINT_MOTION_MODE || ctx->fit->jmotion == JR_JOINT_MOTION_SHAPES);
  PetscCheck(!(ctx->spread || ctx->modef) || (nn->pos && (!ctx->modef || nn->phi)), comm, PETSC_ERR_ARG_WRONG, "-rom_joint_motion %s needs the members' coordinates (node-to-node elements of an FE model)", JRJointMotions[ctx->fit->jmotion]);
  PetscFunctionReturn(0);
}

/* Every member as an element on its joint's motion: with the mode-shape weight w_e (its motion / the joint's in the
   mode of interest), a Jenkins element moving w u is one moving u with w^2 kt and |w| f (same forces, same energy);
   w = 1 is the plain first reduction (4.4) */
static PetscErrorCode MemberSprings(FitCtx *ctx)
{
  const JRElements *nn = ctx->nn;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(nn->n, &ctx->mk, nn->n, &ctx->mf));
  for (PetscInt e = 0; e < nn->n; e++) {
    /* linear, and mode's first reduction: the members on their own coordinates in the field, no weights; mode's
       second reduction: weights for jenkins_nv too (the fit sees the members' loops in the mode) */
    const PetscReal w = ctx->wt && (!ctx->nv || ctx->modef) && !ctx->spread && !(ctx->modef && ctx->m == 0) ? ctx->wt[e] : 1.0;
    ctx->mk[e]        = w * w * nn->kt[e];
    ctx->mf[e]        = PetscAbsReal(w) * nn->mu[e] * PetscMax(nn->n0[e], 0.0);
  }
  PetscFunctionReturn(0);
}

/* -rom_elements 0, the first reduction itself: the members, weighted, as elements on their joints */
static PetscErrorCode FirstReduction(const FitCtx *ctx, JRElements *rom)
{
  const JRElements *nn = ctx->nn;
  const PetscBool   nv = ctx->nv;
  PetscInt          cnt0 = 0;

  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < nn->n; e++) cnt0 += (nv || ctx->mk[e] > 0);
  PetscCall(JRROMElementsSetUp(rom, cnt0, nn->typename[0], PETSC_FALSE));
  rom->njoints = ctx->nj;
  if (ctx->spread || ctx->modef) PetscCall(PetscMalloc1(3 * cnt0 + 1, &rom->pos));
  if (ctx->modef) PetscCall(PetscMalloc1(2 * cnt0 + 1, &rom->phi));
  if (ctx->modef && nn->phir) PetscCall(PetscMalloc1(JR_NREL * cnt0 + 1, &rom->phir));
  for (PetscInt e = 0, i = 0; e < nn->n; e++) {
    if (!(nv || ctx->mk[e] > 0)) continue;
    for (PetscInt c = 0; rom->pos && c < 3; c++) rom->pos[3 * i + c] = nn->pos[3 * e + c];
    for (PetscInt c = 0; rom->phi && c < 2; c++) rom->phi[2 * i + c] = nn->phi[2 * e + c];
    for (PetscInt c = 0; rom->phir && c < JR_NREL; c++) rom->phir[JR_NREL * i + c] = nn->phir[JR_NREL * e + c];
    rom->kt[i]      = nv ? nn->kt[e] : ctx->mk[e];
    rom->kn[i]      = nn->kn[e];
    rom->mu[i]      = nn->mu[e];
    rom->n0[i]      = nv ? nn->n0[e] : ctx->mf[e] / nn->mu[e];
    rom->joint[i++] = nn->joint[e];
  }
  PetscCall(PetscNew(&rom->members));
  PetscCall(JRElementsDuplicate(nn, rom->members));
  PetscFunctionReturn(0);
}

/* The members of each joint in contact at rest, sorted by slip displacement (md, jn, joff) */
static PetscErrorCode SortMembers(FitCtx *ctx)
{
  const JRElements *nn = ctx->nn;
  const PetscInt    nj = ctx->nj;
  PetscInt         *jn, *joff;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc2(nj, &ctx->jn, nj + 1, &ctx->joff));
  PetscCall(PetscMalloc1(nn->n, &ctx->md));
  jn   = ctx->jn;
  joff = ctx->joff;
  for (PetscInt e = 0; e < nn->n; e++)
    if (ctx->mf[e] > 0 && ctx->mk[e] > 0) jn[nn->joint[e]]++;
  for (PetscInt j = 0; j < nj; j++) joff[j + 1] = joff[j] + jn[j];
  for (PetscInt j = 0; j < nj; j++) jn[j] = 0;
  for (PetscInt e = 0; e < nn->n; e++) {
    const PetscInt j = nn->joint[e];
    if (!(ctx->mf[e] > 0 && ctx->mk[e] > 0)) continue;
    ctx->md[joff[j] + jn[j]].e     = e;
    ctx->md[joff[j] + jn[j]].delta = ctx->mf[e] / ctx->mk[e];
    jn[j]++;
  }
  for (PetscInt j = 0; j < nj; j++) {
    PetscInt nopen = 0; /* mode, jenkins_nv: a joint of open pairs alone gets their gap elements (OpenMembers) */
    for (PetscInt e = 0; !jn[j] && ctx->modef && ctx->nv && e < nn->n; e++) nopen += (nn->joint[e] == j && !(nn->n0[e] > 0) && nn->kn[e] > 0);
    PetscCheck(jn[j] > 0 || nopen > 0, ctx->comm, PETSC_ERR_ARG_WRONG, "Joint %" PetscInt_FMT " has no member in contact at rest: nothing to fit (change the regions; with jenkins_nv and -rom_joint_motion mode a joint of open pairs alone gets gap elements)", j);
    qsort(ctx->md + joff[j], (size_t)jn[j], sizeof(MemberDelta), JRFitCompareDelta);
  }
  PetscFunctionReturn(0);
}

/* Room for the joints' fits and their reduced elements; the loops' CSV opened (if base) */
static PetscErrorCode FitAllocate(FitCtx *ctx)
{
  const PetscInt nj = ctx->nj;
  PetscInt       cnt = 0, nmax;

  PetscFunctionBeginUser;
  for (PetscInt j = 0; j < nj; j++) cnt += PetscMin(PetscMax(ctx->m, ctx->fit->mmax), ctx->jn[j]);
  nmax = cnt + (ctx->modef && ctx->nv ? nj * ctx->m : 0); /* mode, jenkins_nv: up to m elements more per joint for its open members */
  PetscCall(PetscMalloc5(nmax, &ctx->ek, nmax, &ctx->ef, nmax, &ctx->ekn, nmax, &ctx->en0, nmax, &ctx->emu));
  if (ctx->spread || ctx->modef) PetscCall(PetscMalloc2(JR_EP * nmax + 1, &ctx->ep, nmax + 1, &ctx->er));
  if (ctx->modef && ctx->nn->phir) PetscCall(PetscCalloc1(2 * JR_NREL * nmax + 1, &ctx->epr));
  if (ctx->base && ctx->base[0]) {
    PetscCall(PetscSNPrintf(ctx->csv, sizeof(ctx->csv), "%s_rom_loops.csv", ctx->base));
    PetscCall(JRFileOpenTemp(ctx->comm, ctx->csv, &ctx->fp, ctx->tmp, sizeof(ctx->tmp)));
    if (ctx->fp) fprintf(ctx->fp, "joint,amplitude,u_m,f_first_reduction_N,f_rom_N\n");
  }
  PetscCall(PetscCalloc3(nj, &ctx->jf, nj, &ctx->nel, nj, &ctx->jm));
  for (PetscInt j = 0; j < nj; j++) ctx->jm[j] = ctx->m;
  ctx->cnt = 0;
  PetscFunctionReturn(0);
}

/* The fit at the case's estimated amplitudes: the error of all joints' dissipation at each level, relative to the
   input (rom case level F dissipation_error) */
static PetscErrorCode CaseErrors(const FitCtx *ctx)
{
  const JRROMCase *cs = ctx->cs;

  PetscFunctionBeginUser;
  for (PetscInt l = 0; l < cs->nlev; l++) {
    PetscReal err = 0;
    for (PetscInt j = 0, e = 0; j < ctx->nj; j++) {
      const PetscReal x = PetscAbsReal(cs->ujoint[j]) * ctx->amod[l];
      for (PetscInt i = 0; i < ctx->nel[j]; i++, e++) err += JRFitJenkinsEnergy(ctx->ek[e], ctx->ef[e], x, NULL, NULL);
    }
    err -= JRFitCaseDissipation(ctx, ctx->amod[l]);
    PetscCall(JRFitSay(ctx->quiet, ctx->comm, "rom case level %g dissipation_error %+.4f (of the input per cycle)\n", (double)cs->level[l], (double)(err / (PETSC_PI * PetscAbsReal(cs->level[l]) * cs->force * ctx->amod[l]))));
  }
  PetscFunctionReturn(0);
}

/* The loops' CSV in place, and its plot (BASE_rom_loops.png) */
static PetscErrorCode LoopsCommit(FitCtx *ctx)
{
  PetscFunctionBeginUser;
  if (!(ctx->base && ctx->base[0])) PetscFunctionReturn(0);
  PetscCall(JRFileCommit(ctx->comm, &ctx->fp, ctx->tmp, ctx->csv));
  if (ctx->plot) {
    char      png[PETSC_MAX_PATH_LEN + 32], vars[2 * PETSC_MAX_PATH_LEN + 256], js[192] = "";
    PetscBool made;
    size_t    len;
    for (PetscInt j = 0, k = 0; j < ctx->nj && k < 12; j++) { /* the first 12 joints with loops (members in contact) */
      if (!ctx->jn[j]) continue;
      PetscCall(PetscStrlen(js, &len));
      PetscCall(PetscSNPrintf(js + len, sizeof(js) - len, "%s%" PetscInt_FMT, k++ ? " " : "", j));
    }
    PetscCall(PetscSNPrintf(png, sizeof(png), "%s_rom_loops.png", ctx->base));
    PetscCall(PetscSNPrintf(vars, sizeof(vars), "data='%s'; js='%s'", ctx->csv, js));
    PetscCall(JRPlot(ctx->comm, "plot_rom_loops.gp", png, vars, &made));
    PetscCall(PetscPrintf(ctx->comm, "rom: wrote %s%s%s\n", ctx->csv, made ? ", " : "", made ? png : ""));
  } else PetscCall(PetscPrintf(ctx->comm, "rom: wrote %s\n", ctx->csv));
  PetscFunctionReturn(0);
}

/* mode: part c of an element of nc parts at the tangential motions psi_c (ep), its slip force's share times nc,
   |psi_c| / rms(psi): every part then slips at the same modal amplitude, as the fitted element */
static PetscReal PartShare(const PetscReal P[], PetscInt nc, PetscInt c)
{
  PetscReal s = 0;
  for (PetscInt i = 0; i < nc; i++) s += P[5 * i + 3] * P[5 * i + 3];
  s = PetscSqrtReal(s / nc);
  return s > 0 ? PetscAbsReal(P[5 * c + 3]) / s : 1.0;
}

/* The reduced elements, the first-reduction model as their members; linear: each a third at each of its points;
   mode (jenkins_nv): each a half at each of its two points, slip forces in proportion to their tangential motion */
static PetscErrorCode AssembleElements(const FitCtx *ctx, JRElements *rom)
{
  const PetscInt nc = ctx->spread ? 3 : (ctx->modef && ctx->nv ? 2 : 1), cnt = ctx->cnt;

  PetscFunctionBeginUser;
  PetscCall(JRROMElementsSetUp(rom, nc * cnt, ctx->nn->typename[0], PETSC_FALSE));
  if (ctx->spread || ctx->modef) PetscCall(PetscMalloc1(3 * nc * cnt, &rom->pos));
  if (ctx->modef) PetscCall(PetscMalloc1(2 * nc * cnt, &rom->phi));
  if (ctx->modef && ctx->epr) PetscCall(PetscMalloc1(JR_NREL * nc * cnt, &rom->phir));
  rom->njoints = ctx->nj;
  for (PetscInt j = 0, e = 0; j < ctx->nj; j++)
    for (PetscInt i = 0; i < ctx->nel[j]; i++, e++)
      for (PetscInt c = 0; c < nc; c++) {
        const PetscInt  r = nc * e + c;
        const PetscReal q = ctx->modef ? ctx->er[e] : 1.0; /* mode: the element moved to psi_t */
        rom->kt[r]        = ctx->ek[e] * q * q / nc;
        rom->kn[r]        = ctx->ekn[e] / nc;
        rom->mu[r]        = ctx->emu[e] * (ctx->modef ? PartShare(ctx->ep + JR_EP * e, nc, c) : 1.0);
        rom->n0[r]        = ctx->en0[e] * PetscAbsReal(q) / nc;
        rom->joint[r]     = j;
        for (PetscInt k = 0; rom->pos && k < 3; k++) rom->pos[3 * r + k] = ctx->ep[JR_EP * e + 5 * c + k];
        for (PetscInt k = 0; rom->phi && k < 2; k++) rom->phi[2 * r + k] = ctx->ep[JR_EP * e + 5 * c + 3 + k];
        for (PetscInt k = 0; rom->phir && k < JR_NREL; k++) rom->phir[JR_NREL * r + k] = ctx->epr[2 * JR_NREL * e + JR_NREL * c + k];
      }
  PetscCall(PetscNew(&rom->members));
  PetscCall(JRElementsDuplicate(ctx->nn, rom->members));
  PetscFunctionReturn(0);
}

/* Frees what a pass computed; the problem stays */
static PetscErrorCode FitCtxReset(FitCtx *ctx)
{
  PetscFunctionBeginUser;
  for (PetscInt j = 0; ctx->jf && j < ctx->nj; j++) PetscCall(JRFitJointFitDestroy(&ctx->jf[j]));
  PetscCall(PetscFree3(ctx->jf, ctx->nel, ctx->jm));
  PetscCall(PetscFree5(ctx->ek, ctx->ef, ctx->ekn, ctx->en0, ctx->emu));
  PetscCall(PetscFree2(ctx->ep, ctx->er));
  PetscCall(PetscFree(ctx->epr));
  PetscCall(PetscFree(ctx->md));
  PetscCall(PetscFree2(ctx->jn, ctx->joff));
  PetscCall(PetscFree2(ctx->mk, ctx->mf));
  PetscCall(PetscFree(ctx->amod));
  ctx->amin = ctx->amax = 0;
  ctx->cnt              = 0;
  PetscFunctionReturn(0);
}

/* One fit (JRROMReduce) of the problem in ctx: quiet, it prints nothing; ctx->nvin (NULL: none) is added to the case's
   energy targets; nvout (NULL: not wanted; mode, jenkins_nv, with a case) gets JRFitNormalVariation's correction of this
   fit, nvmax its size */
static PetscErrorCode ReducePass(FitCtx *ctx, PetscReal nvout[], PetscReal *nvmax, JRElements *rom)
{
  PetscFunctionBeginUser;
  PetscCall(FitCheck(ctx));
  PetscCall(MemberSprings(ctx));
  if (ctx->cs && ctx->cs->nlev > 0 && ctx->m > 0 && (!ctx->nv || ctx->modef)) PetscCall(CaseAmplitudes(ctx));
  if (ctx->m == 0) {
    PetscCall(FirstReduction(ctx, rom));
    PetscCall(FitCtxReset(ctx));
    PetscFunctionReturn(0);
  }
  PetscCall(SortMembers(ctx));
  PetscCall(FitAllocate(ctx));
  for (PetscInt j = 0; j < ctx->nj; j++)
    if (ctx->jn[j]) PetscCall(JRFitJoint(ctx, j));
  if (ctx->amod && ctx->fit->wtotal > 0 && (!ctx->nv || ctx->modef)) PetscCall(FitCoupled(ctx));
  for (PetscInt j = 0; j < ctx->nj; j++) {
    PetscCall(JRFitJointElements(ctx, j));
    if (ctx->nv && !ctx->modef) PetscCall(JRFitNormal(ctx, j));
    PetscCall(JRFitJointReport(ctx, j));
    ctx->cnt += ctx->nel[j];
    PetscCall(JRFitJointFitDestroy(&ctx->jf[j]));
  }
  if (ctx->amod) PetscCall(CaseErrors(ctx));
  PetscCall(LoopsCommit(ctx));
  PetscCall(AssembleElements(ctx, rom));
  if (nvout && ctx->amod && ctx->modef && ctx->nv) PetscCall(JRFitNormalVariation(ctx, rom, nvout, nvmax));
  PetscCall(FitCtxReset(ctx));
  PetscFunctionReturn(0);
}

/*
  JRROMReduce - the second reduction of the first-reduction model nn (node-to-node elements with joints): m elements
  per joint (fewer if a joint has fewer members in contact), fitted by TAO; rom gets the elements, with nn as their
  members. Every rank computes the same fit. base: if not empty, BASE_rom_loops.csv (+ .png if plot) with the
  loops of every joint, first reduction and fit, at the three amplitudes. Prints one line per joint (quiet: nothing,
  and no files).
  -rom_joint_motion mode, jenkins_nv, with a case: also prints the fit's error at every level with the normal loads
  varying (JRFitNormalVariation); -rom_fit_normal_passes k fits k more times, each with the previous fit's correction.
*/
PetscErrorCode JRROMReduce(MPI_Comm comm, const JRElements *nn, PetscInt m, const PetscReal wt[], const JRROMCase *cs, const JRROMFit *fitin, const char base[], PetscBool plot, PetscBool quiet, JRElements *rom)
{
  PetscInt  npass;
  PetscReal *nvin, *nvout, nvmax = 0;
  JRROMFit  own;
  FitCtx    ctx;

  PetscFunctionBeginUser;
  if (!fitin) { /* the options, read here */
    PetscCall(JRROMFitSetFromOptions(comm, &own));
    fitin = &own;
  }
  PetscCall(PetscMemzero(&ctx, sizeof(ctx)));
  ctx.comm = comm;
  ctx.nn   = nn;
  ctx.m    = m;
  ctx.wt   = wt;
  ctx.cs   = cs;
  ctx.fit  = fitin;
  ctx.plot = plot;
  npass    = fitin->npass;
  /* nn->phi, the members' stuck-mode coordinates, is set (JRTaskFRF) for -rom_joint_motion mode only */
  if (!(nn->phi && m > 0 && npass >= 0 && cs && cs->nlev > 0 && cs->force > 0 && nn->ntypes == 1 && !strcmp(nn->typename[0], JRCONTACTJENKINSNV))) {
    ctx.base  = quiet ? NULL : base;
    ctx.quiet = quiet;
    PetscCall(ReducePass(&ctx, NULL, &nvmax, rom));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscCalloc2(NCASE * nn->njoints, &nvin, NCASE * nn->njoints, &nvout));
  for (PetscInt p = 0; p <= npass; p++) {
    if (p) PetscCall(JRElementsDestroy(rom));
    ctx.base  = p == npass && !quiet ? base : NULL;
    ctx.quiet = (PetscBool)(quiet || p < npass);
    ctx.nvin  = p ? nvin : NULL;
    PetscCall(ReducePass(&ctx, nvout, &nvmax, rom));
    if (npass && !quiet) PetscCall(PetscPrintf(comm, "rom normal_variation pass %" PetscInt_FMT " of %" PetscInt_FMT " largest_share %.4f (of the input per cycle at the case's amplitudes, the fit's next correction)\n", p, npass, (double)nvmax));
    PetscCall(PetscArraycpy(nvin, nvout, NCASE * nn->njoints));
  }
  PetscCall(PetscFree2(nvin, nvout));
  PetscFunctionReturn(0);
}
