/*
   JRVerify: frequency-response points checked by direct time integration of the same modal equations.

   The harmonic balance solves, for the periodic part of the response, the modal equations (theory.md section 1)

     Mm q'' + (Cm + (gamma / w) Kg) q' + Km q - Kc q + sum_e r_e f_e(t) + sum_e s_e (n_e(t) - max(n0_e, 0))
       = F fm sin(w t),

   with the same basis (Km, Mm, Cm, Kg, the excitation fm and the output rows of the JRHBM), the same contact elements
   on their projection rows r_e, s_e (4.3) split across the ranks as in the harmonic balance (Kc: the stuck springs a
   stuck or mixed basis holds, which the elements replace), and each element marched in time with its own hysteretic
   state, the slip w_e (the play operator of theory.md section 2):

     jenkins     w <- clamp(w, u - mu n0 / kt, u + mu n0 / kt),  f = kt (u - w)
     jenkins_nv  n = max(0, n0 + kn v),  w <- clamp(w, u - mu n / kt, u + mu n / kt),  f = kt (u - w)
     cubic       f = kt u^3 (no state).

   Structural damping gamma Kg has no causal time-domain form; it enters as the viscous damping (gamma / w) Kg at the
   excitation frequency w, which is exactly the harmonic balance's for the first harmonic (harmonic h sees h times the
   harmonic balance's damping there: a small effect on the higher harmonics, never on the first harmonic compared).

   Time stepping: PETSc TS, explicit fourth-order Runge-Kutta (TSRK 4) with a fixed step T / steps
   (-frf_verify_steps per period, default 1000). The element forces are Lipschitz but not smooth (stick-slip
   transitions are kinks), so an adaptive error control would chase every kink and an implicit scheme would need
   Newton on a nonsmooth residual; a fixed explicit step of a thousandth of a period resolves every transition to
   round-off of the first harmonic (the kinks cost O(dt^2) per transition) and keeps the step count per period a
   user's choice. The slip is committed after every step at the new state; the stages in between see the slip of the
   step's start pushed by their own motion (a return mapping from the last committed state), exact while the motion
   within one step is monotone. The step must also be stable: dt w_max <= 2 (RK4's limit on the imaginary axis is
   2.83), w_max^2 an upper bound of the stiffest mode with every friction element stuck (LAPACK on mass-normalised
   modes, else power iterations); the
   steps per period are raised to that if needed. -frf_verify_ts_type / -frf_verify_ts_rk_type choose another
   explicit scheme (rk, ssp, euler); the step stays fixed.

   Start: the harmonic-balance solution's state at t = 0 (q and q' from the harmonic coefficients, the slip from one
   period of the prescribed element motion, as the alternating frequency-time march does), or -frf_verify_from_rest
   (rigid-body modes, which nothing holds, still start on the harmonic balance's motion so that they do not drift).
   The run stops when the state (q, q'/w) changed by less than -frf_verify_periodic_tol (relative) over each of the
   last two periods and the geometric extrapolation of the remaining transient (d rho / (1 - rho), rho the ratio
   of the last two changes) is also below it; at most -frf_verify_max_periods periods. The last period, sampled at
   every step, is Fourier-analysed at output 1: its first harmonic against the harmonic balance's, and the share
   of the motion in the higher harmonics, sqrt(var(x) - A1^2 / 2) / sqrt(var(x)) (Parseval), against the harmonic
   balance's own sqrt(sum_{h >= 2} A_h^2 / sum_{h >= 1} A_h^2).
*/
#include <jointrom/private/hbmimpl.h>
#include <petscts.h>

/* One element group's time-march state: this rank's elements of one type, as the JRHBM's group */
typedef enum {
  VERIFY_JENKINS,
  VERIFY_JENKINSNV,
  VERIFY_CUBIC
} VerifyType;

typedef struct {
  VerifyType       type;
  PetscInt         nloc;
  const PetscReal *kt, *kn, *mu, *n0;
  PetscReal       *w;          /* committed slip [m] */
  PetscReal       *u, *v, *f, *n; /* work: tangential and normal motion, force, dynamic normal load */
} VerifyGroup;

struct _p_JRVerify {
  MPI_Comm    comm;
  PetscMPIInt rank, size;
  JRHBM       hbm;
  /* options */
  PetscInt    npoints, steps, maxperiods;
  PetscReal   tol, ptol;
  PetscBool   rest, setupcalled, view, unstable;
  /* the modal equations */
  PetscInt     nm, H, nc;
  PetscBool    identity;  /* Mm = I */
  PetscReal   *Mlu;       /* LU of Mm (row-major copy) if not the identity */
  PetscBLASInt *piv;
  PetscReal   *Cv;        /* Cm + (gamma / w) Kg at the current w, row-major */
  PetscReal    wmax2;     /* bound of the stiffest eigenvalue, every friction element stuck [rad^2/s^2] */
  PetscInt     ngroups;
  VerifyGroup *g;
  PetscReal   *loc, *fn, *acc, *x; /* work: nm, nm, nm, one period of output 1 */
  PetscInt     nx;
  PetscReal   *qs, *sn, *cs; /* the current period's modal displacements (N x nm); sin, cos at the N angles */
  PetscReal   *ecoef;     /* harmonics 2..H of the last period's motion */
  PetscReal   *ecs;       /* structural damping's correction for harmonics 2..H: per h, gamma (1 - h) Kg as_h, Kg ac_h */
  PetscBool    corr;      /* gamma != 0 and H >= 2 */
  PetscReal    level, omega;
  TS           ts;
  Vec          y, yprev;
};

PetscErrorCode JRVerifyCreate(MPI_Comm comm, JRVerify *v)
{
  JRVerify r;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&r));
  r->comm       = comm;
  r->npoints    = 0;
  r->steps      = 1000;
  r->maxperiods = 2000;
  r->tol        = 1e-3;
  r->ptol       = 1e-6;
  PetscCallMPI(MPI_Comm_rank(comm, &r->rank));
  PetscCallMPI(MPI_Comm_size(comm, &r->size));
  *v = r;
  PetscFunctionReturn(0);
}

/* -frf_verify_points N (0: off), -frf_verify_tol, -frf_verify_steps, -frf_verify_periodic_tol,
   -frf_verify_max_periods, -frf_verify_from_rest, -frf_verify_unstable, -frf_verify_view (the TS's -frf_verify_ts_* are read at set-up) */
PetscErrorCode JRVerifySetFromOptions(JRVerify v)
{
  PetscBool help;

  PetscFunctionBeginUser;
  PetscOptionsBegin(v->comm, NULL, "Time-integration check of the FRF points (-task frf; the scheme: -frf_verify_ts_type rk|ssp|euler, -frf_verify_ts_rk_type, default RK4)", "JRVerify");
  PetscCall(PetscOptionsInt("-frf_verify_points", "Points of each level checked by time integration (TS): the peak and N-1 on both sides of it; 0: off", "JRVerifyCurves", v->npoints, &v->npoints, NULL));
  PetscCall(PetscOptionsReal("-frf_verify_tol", "Warn when the first harmonics of time integration and harmonic balance differ by more than this (relative)", "JRVerifyCurves", v->tol, &v->tol, NULL));
  PetscCall(PetscOptionsInt("-frf_verify_steps", "Time steps per period (raised to the explicit scheme's stability limit if needed)", "JRVerifySolve", v->steps, &v->steps, NULL));
  PetscCall(PetscOptionsReal("-frf_verify_periodic_tol", "Steady state: relative change of the state over a period (and its extrapolated rest) below this", "JRVerifySolve", v->ptol, &v->ptol, NULL));
  PetscCall(PetscOptionsInt("-frf_verify_max_periods", "At most this many periods per point", "JRVerifySolve", v->maxperiods, &v->maxperiods, NULL));
  PetscCall(PetscOptionsBool("-frf_verify_view", "View the check's settings and the stiffest mode bound at set-up", "JRVerifyView", v->view, &v->view, NULL));
  PetscCall(PetscOptionsBool("-frf_verify_unstable", "Also the middle point of every stretch that -frf_stability flags unstable (at most 20 per level)", "JRVerifyCurves", v->unstable, &v->unstable, NULL));
  PetscCall(PetscOptionsBool("-frf_verify_from_rest", "Start from rest instead of the harmonic balance's state at t = 0", "JRVerifySolve", v->rest, &v->rest, NULL));
  PetscOptionsEnd();
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (help) PetscFunctionReturn(0);
  PetscCheck(v->npoints >= 0 && v->npoints <= 100, v->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_verify_points %" PetscInt_FMT ": give 0 (off) to 100 points per level", v->npoints);
  PetscCheck(PetscIsNormalReal(v->tol) && v->tol > 0, v->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_verify_tol %g: the tolerance must be positive", (double)v->tol);
  PetscCheck(v->steps >= 16 && v->steps <= 10000000, v->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_verify_steps %" PetscInt_FMT ": give 16 to 1e7 time steps per period (1000 resolves stick-slip to round-off of the first harmonic)", v->steps);
  PetscCheck(PetscIsNormalReal(v->ptol) && v->ptol > 0 && v->ptol < 1, v->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_verify_periodic_tol %g: the periodicity tolerance must be in (0, 1)", (double)v->ptol);
  PetscCheck(v->maxperiods >= 3, v->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_verify_max_periods %" PetscInt_FMT ": at least 3 periods", v->maxperiods);
  PetscFunctionReturn(0);
}

PetscErrorCode JRVerifyGetNumPoints(JRVerify v, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = v->npoints;
  PetscFunctionReturn(0);
}

/* What JRVerifySetUp made from the JRHBM */
static PetscErrorCode Reset(JRVerify v)
{
  PetscFunctionBeginUser;
  for (PetscInt t = 0; t < v->ngroups; t++) PetscCall(PetscFree5(v->g[t].w, v->g[t].u, v->g[t].v, v->g[t].f, v->g[t].n));
  PetscCall(PetscFree(v->g));
  v->ngroups = 0;
  if (v->Mlu) PetscCall(PetscFree2(v->Mlu, v->piv));
  if (v->Cv) PetscCall(PetscFree4(v->Cv, v->loc, v->fn, v->acc));
  PetscCall(PetscFree2(v->ecoef, v->ecs));
  PetscCall(PetscFree(v->x));
  PetscCall(PetscFree3(v->qs, v->sn, v->cs));
  v->nx = 0;
  PetscCall(TSDestroy(&v->ts));
  PetscCall(VecDestroy(&v->y));
  PetscCall(VecDestroy(&v->yprev));
  v->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The harmonic balance whose points are checked (set up before JRVerifySetUp); another one resets the check */
PetscErrorCode JRVerifySetHBM(JRVerify v, JRHBM h)
{
  PetscFunctionBeginUser;
  if (v->hbm != h) PetscCall(Reset(v));
  v->hbm = h;
  PetscFunctionReturn(0);
}

/* Sum of this rank's contributions over the ranks (as the harmonic balance: on rank 0, then broadcast, so every rank
   holds the same numbers bit for bit); not for a reduced model on every rank (h->repl) */
static PetscErrorCode SumRanks(JRVerify v, PetscReal *a, PetscInt n)
{
  JRHBM h = v->hbm;

  PetscFunctionBeginUser;
  if (h->size > 1 && !h->repl) {
    PetscMPIInt len;
    PetscCall(PetscMPIIntCast(n, &len));
    PetscCallMPI(MPI_Reduce(h->rank ? a : MPI_IN_PLACE, a, len, MPIU_REAL, MPIU_SUM, 0, h->comm));
    PetscCallMPI(MPI_Bcast(a, len, MPIU_REAL, 0, h->comm));
  }
  PetscFunctionReturn(0);
}

/* The elements' motions u = R q (and v = S q) of every group */
static PetscErrorCode Motions(JRVerify v, const PetscReal q[])
{
  JRHBM h = v->hbm;

  PetscFunctionBeginUser;
  for (PetscInt t = 0; t < v->ngroups; t++) {
    JRHBMGroup  *g  = &h->g[t];
    VerifyGroup *vg = &v->g[t];
    if (!vg->nloc) continue;
    PetscCall(JRGemm("N", "N", vg->nloc, 1, v->nm, 1.0, g->R, vg->nloc, q, v->nm, 0.0, vg->u, vg->nloc));
    if (g->normal) PetscCall(JRGemm("N", "N", vg->nloc, 1, v->nm, 1.0, g->S, vg->nloc, q, v->nm, 0.0, vg->v, vg->nloc));
  }
  PetscFunctionReturn(0);
}

static inline PetscReal Clamp(PetscReal w, PetscReal lo, PetscReal hi)
{
  return w < lo ? lo : (w > hi ? hi : w);
}

/* Half-width of element e's stick band [m]: the slip force over kt */
static inline PetscReal Band(const VerifyGroup *vg, PetscInt e, PetscReal vn)
{
  const PetscReal kt = vg->kt[e];
  PetscReal       n;
  if (vg->type == VERIFY_JENKINS) n = PetscMax(vg->n0[e], 0.0);
  else n = PetscMax(0.0, vg->n0[e] + vg->kn[e] * vn);
  return kt > 0 ? vg->mu[e] * n / kt : 0.0;
}

/* The nonlinear modal force at q, summed over the ranks: -Kc q + sum_e r_e f_e + s_e (n_e - max(n0_e, 0)), each
   friction element's slip pushed from its committed value by the motion (not committed) */
static PetscErrorCode NonlinearForce(JRVerify v, const PetscReal q[], PetscReal fn[])
{
  JRHBM          h  = v->hbm;
  const PetscInt nm = v->nm;

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(v->loc, nm));
  if (h->basis != JR_HBM_BASIS_FREE && h->Kc) PetscCall(JRGemm("N", "N", nm, 1, nm, -1.0, h->Kc, nm, q, nm, 0.0, v->loc, nm));
  PetscCall(Motions(v, q));
  for (PetscInt t = 0; t < v->ngroups; t++) {
    JRHBMGroup  *g  = &h->g[t];
    VerifyGroup *vg = &v->g[t];
    if (!vg->nloc) continue;
    switch (vg->type) {
    case VERIFY_CUBIC:
      for (PetscInt e = 0; e < vg->nloc; e++) vg->f[e] = vg->kt[e] * vg->u[e] * vg->u[e] * vg->u[e];
      break;
    case VERIFY_JENKINS:
    case VERIFY_JENKINSNV:
      for (PetscInt e = 0; e < vg->nloc; e++) {
        const PetscReal b = Band(vg, e, vg->type == VERIFY_JENKINSNV ? vg->v[e] : 0.0);
        const PetscReal w = Clamp(vg->w[e], vg->u[e] - b, vg->u[e] + b);
        vg->f[e]          = vg->kt[e] * (vg->u[e] - w);
        if (vg->type == VERIFY_JENKINSNV) vg->n[e] = PetscMax(0.0, vg->n0[e] + vg->kn[e] * vg->v[e]) - g->nstatic[e];
      }
      break;
    }
    PetscCall(JRGemm("T", "N", nm, 1, vg->nloc, 1.0, g->R, vg->nloc, vg->f, vg->nloc, 1.0, v->loc, nm));
    if (g->normal) PetscCall(JRGemm("T", "N", nm, 1, vg->nloc, 1.0, g->S, vg->nloc, vg->n, vg->nloc, 1.0, v->loc, nm));
    PetscCall(PetscLogFlops(4.0 * vg->nloc * nm * (g->normal ? 2 : 1)));
  }
  PetscCall(SumRanks(v, v->loc, nm));
  PetscCall(PetscArraycpy(fn, v->loc, nm));
  PetscFunctionReturn(0);
}

/* After a step: every friction element's slip committed at the new state (local, no communication) */
static PetscErrorCode CommitSlip(JRVerify v, const PetscReal q[])
{
  PetscFunctionBeginUser;
  PetscCall(Motions(v, q));
  for (PetscInt t = 0; t < v->ngroups; t++) {
    VerifyGroup *vg = &v->g[t];
    if (vg->type == VERIFY_CUBIC) continue;
    for (PetscInt e = 0; e < vg->nloc; e++) {
      const PetscReal b = Band(vg, e, vg->type == VERIFY_JENKINSNV ? vg->v[e] : 0.0);
      vg->w[e]          = Clamp(vg->w[e], vg->u[e] - b, vg->u[e] + b);
    }
  }
  PetscFunctionReturn(0);
}

/* y' = [p; Mm^-1 (F fm sin(w t) - Km q - Cv p - fn(q))] */
static PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec Y, Vec G, void *ctx)
{
  JRVerify          v  = (JRVerify)ctx;
  JRHBM             h  = v->hbm;
  const PetscInt    nm = v->nm;
  const PetscReal  *y, *q, *p;
  PetscReal        *gv;
  const PetscReal   s = v->level * PetscSinReal(v->omega * t);

  PetscFunctionBeginUser;
  (void)ts;
  PetscCall(VecGetArrayRead(Y, &y));
  PetscCall(VecGetArray(G, &gv));
  q = y;
  p = y + nm;
  PetscCall(NonlinearForce(v, q, v->fn));
  if (v->corr) { /* harmonics 2..H see gamma Kg as in the harmonic balance, not h gamma Kg: fn += sum_h es_h cos - ec_h sin */
    const PetscReal s1 = PetscSinReal(v->omega * t), c1 = PetscCosReal(v->omega * t);
    PetscReal       sh = s1, ch = c1;
    for (PetscInt hh = 2; hh <= v->H; hh++) {
      const PetscReal  sn = sh * c1 + ch * s1, cn = ch * c1 - sh * s1;
      const PetscReal *es = v->ecs + 2 * (hh - 2) * nm, *ec = es + nm;
      sh = sn;
      ch = cn;
      for (PetscInt i = 0; i < nm; i++) v->fn[i] += es[i] * ch - ec[i] * sh;
    }
  }
  for (PetscInt i = 0; i < nm; i++) {
    const PetscReal *k = h->Km + i * nm, *c = v->Cv + i * nm;
    PetscReal        r = s * h->fm[i] - v->fn[i];
    for (PetscInt j = 0; j < nm; j++) r -= k[j] * q[j] + c[j] * p[j];
    v->acc[i] = r;
  }
  if (!v->identity) {
    PetscBLASInt bn, one = 1, info;
    PetscCall(PetscBLASIntCast(nm, &bn));
    PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("T", &bn, &one, v->Mlu, &bn, v->piv, v->acc, &bn, &info)); /* Mlu holds Mm row-major: its transpose, column-major */
    PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK getrs: info %d", (int)info);
  }
  for (PetscInt i = 0; i < nm; i++) {
    gv[i]      = p[i];
    gv[nm + i] = v->acc[i];
  }
  PetscCall(PetscLogFlops(4.0 * nm * nm));
  PetscCall(VecRestoreArray(G, &gv));
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscFunctionReturn(0);
}

/* Upper bound of the stiffest eigenvalue of Mm^-1 (Km - Kc + sum_e kt r_e r_e^T + kn s_e s_e^T), every friction
   element stuck (jenkins_nv: also the open ones, which may close), by power iterations (x 1.05) */
static PetscErrorCode StiffestMode(JRVerify v)
{
  JRHBM          h  = v->hbm;
  const PetscInt nm = v->nm;
  PetscReal     *K, *x, *z, lam = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc3(nm * nm, &K, nm, &x, nm, &z));
  if (h->basis != JR_HBM_BASIS_FREE && h->Kc)
    for (PetscInt i = 0; i < nm * nm; i++) K[i] = -h->Kc[i];
  for (PetscInt t = 0; t < v->ngroups; t++) {
    JRHBMGroup  *g  = &h->g[t];
    VerifyGroup *vg = &v->g[t];
    PetscReal   *W;
    if (!vg->nloc || vg->type == VERIFY_CUBIC) continue;
    PetscCall(PetscMalloc1(vg->nloc * nm, &W));
    for (PetscInt q = 0; q < (g->normal ? 2 : 1); q++) {
      const PetscReal *X = q ? g->S : g->R;
      for (PetscInt i = 0; i < nm; i++)
        for (PetscInt e = 0; e < vg->nloc; e++) W[e + i * vg->nloc] = (q ? vg->kn[e] : (vg->type == VERIFY_JENKINS && vg->n0[e] <= 0 ? 0.0 : vg->kt[e])) * X[e + i * vg->nloc];
      PetscCall(JRGemm("T", "N", nm, nm, vg->nloc, 1.0, X, vg->nloc, W, vg->nloc, 1.0, K, nm));
    }
    PetscCall(PetscFree(W));
  }
  PetscCall(SumRanks(v, K, nm * nm));
  for (PetscInt i = 0; i < nm * nm; i++) K[i] += h->Km[i]; /* symmetric: row- or column-major alike */
  if (v->identity) { /* mass-normalised modes: the largest eigenvalue of K itself, by LAPACK (a static-correction
                        basis clusters the stiffest ones, where power iterations stop short of the top) */
    PetscBLASInt bn, lwork, info;
    PetscReal   *ev, *work;
    PetscCall(PetscBLASIntCast(nm, &bn));
    PetscCall(PetscBLASIntCast(PetscMax(1, 3 * nm), &lwork));
    PetscCall(PetscMalloc2(nm, &ev, 3 * nm + 1, &work));
    PetscCallBLAS("LAPACKsyev", LAPACKsyev_("N", "U", &bn, K, &bn, ev, work, &lwork, &info));
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev: info %d", (int)info);
    v->wmax2 = 1.05 * ev[nm - 1];
    PetscCall(PetscFree2(ev, work));
    PetscCall(PetscFree3(K, x, z));
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < nm; i++) x[i] = 1.0 + 0.1 * i / nm;
  for (PetscInt it = 0; it < 200; it++) {
    PetscReal nx = 0, l;
    for (PetscInt i = 0; i < nm; i++) nx += x[i] * x[i];
    nx = PetscSqrtReal(nx);
    if (nx == 0) break;
    for (PetscInt i = 0; i < nm; i++) x[i] /= nx;
    PetscCall(JRGemm("N", "N", nm, 1, nm, 1.0, K, nm, x, nm, 0.0, z, nm));
    if (!v->identity) {
      PetscBLASInt bn, one = 1, info;
      PetscCall(PetscBLASIntCast(nm, &bn));
      PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("T", &bn, &one, v->Mlu, &bn, v->piv, z, &bn, &info));
    }
    l = 0;
    for (PetscInt i = 0; i < nm; i++) l += z[i] * z[i];
    l = PetscSqrtReal(l);
    if (it > 20 && PetscAbsReal(l - lam) <= 1e-6 * l) {
      lam = l;
      break;
    }
    lam = l;
    PetscCall(PetscArraycpy(x, z, nm));
  }
  v->wmax2 = 1.05 * lam;
  PetscCall(PetscFree3(K, x, z));
  PetscFunctionReturn(0);
}

/* The modal equations of the JRHBM (set up), the element groups' time-march state and the TS */
PetscErrorCode JRVerifySetUp(JRVerify v)
{
  JRHBM          h = v->hbm;
  const JRElements *el;

  PetscFunctionBeginUser;
  if (v->setupcalled) PetscFunctionReturn(0);
  PetscCheck(h, v->comm, PETSC_ERR_ARG_WRONGSTATE, "JRVerifySetHBM() first");
  PetscCheck(h->setupcalled, v->comm, PETSC_ERR_ARG_WRONGSTATE, "JRVerifySetUp: the JRHBM is not set up");
  PetscCall(JRHBMGetElements(h, &el));
  v->nm = h->nm;
  v->H  = h->H;
  v->nc = h->nc;
  {
    const PetscInt nm = v->nm;
    v->identity       = PETSC_TRUE;
    for (PetscInt i = 0; i < nm && v->identity; i++)
      for (PetscInt j = 0; j < nm; j++)
        if (h->Mm[i * nm + j] != (i == j ? 1.0 : 0.0)) {
          v->identity = PETSC_FALSE;
          break;
        }
    if (!v->identity) {
      PetscBLASInt bn, info;
      PetscCall(PetscMalloc2(nm * nm, &v->Mlu, nm, &v->piv));
      PetscCall(PetscArraycpy(v->Mlu, h->Mm, nm * nm));
      PetscCall(PetscBLASIntCast(nm, &bn));
      PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, v->Mlu, &bn, v->piv, &info));
      PetscCheck(!info, v->comm, PETSC_ERR_ARG_WRONG, "JRVerifySetUp: the mass matrix in the basis is singular (LAPACK getrf info %d)", (int)info);
    }
    PetscCall(PetscMalloc4(nm * nm, &v->Cv, nm, &v->loc, nm, &v->fn, nm, &v->acc));
    v->corr = (PetscBool)(h->gamma != 0.0 && v->H >= 2);
    PetscCall(PetscMalloc2(2 * PetscMax(v->H - 1, 1) * nm, &v->ecoef, 2 * PetscMax(v->H - 1, 1) * nm, &v->ecs));
  }
  v->ngroups = h->ngroups;
  PetscCall(PetscCalloc1(v->ngroups, &v->g));
  for (PetscInt t = 0; t < v->ngroups; t++) {
    JRHBMGroup   *g  = &h->g[t];
    VerifyGroup  *vg = &v->g[t];
    JRContactType type;
    PetscInt      n;
    PetscCall(JRContactGetType(g->c, &type));
    PetscCall(JRContactGetElements(g->c, &n, &vg->kt, &vg->kn, &vg->mu, &vg->n0));
    PetscCheck(n == g->nloc, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Group %" PetscInt_FMT ": %" PetscInt_FMT " elements, %" PetscInt_FMT " rows", t, n, g->nloc);
    if (!strcmp(type, JRCONTACTJENKINS)) vg->type = VERIFY_JENKINS;
    else if (!strcmp(type, JRCONTACTJENKINSNV)) vg->type = VERIFY_JENKINSNV;
    else if (!strcmp(type, JRCONTACTCUBIC)) vg->type = VERIFY_CUBIC;
    else SETERRQ(v->comm, PETSC_ERR_SUP, "-frf_verify_points: no time march for contact elements of type %s", type);
    PetscCheck(!g->normal || vg->type == VERIFY_JENKINSNV, v->comm, PETSC_ERR_SUP, "-frf_verify_points: contact type %s with a normal motion", type);
    vg->nloc = g->nloc;
    PetscCall(PetscCalloc5(vg->nloc, &vg->w, vg->nloc, &vg->u, vg->nloc, &vg->v, vg->nloc, &vg->f, vg->nloc, &vg->n));
  }
  PetscCall(StiffestMode(v));
  /* the TS: explicit RK4 at a fixed step (see the top of this file); -frf_verify_ts_type may choose another explicit one */
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 2 * v->nm, &v->y));
  PetscCall(VecDuplicate(v->y, &v->yprev));
  PetscCall(TSCreate(PETSC_COMM_SELF, &v->ts));
  PetscCall(TSSetOptionsPrefix(v->ts, "frf_verify_"));
  PetscCall(TSSetProblemType(v->ts, TS_NONLINEAR));
  PetscCall(TSSetType(v->ts, TSRK));
  PetscCall(TSRKSetType(v->ts, TSRK4));
  PetscCall(TSSetRHSFunction(v->ts, NULL, RHSFunction, v));
  PetscCall(TSSetExactFinalTime(v->ts, TS_EXACTFINALTIME_STEPOVER));
  PetscCall(TSSetFromOptions(v->ts));
  {
    PetscBool explicit;
    TSType    tt;
    TSAdapt   adapt;
    PetscCall(PetscObjectTypeCompareAny((PetscObject)v->ts, &explicit, TSRK, TSSSP, TSEULER, ""));
    PetscCall(TSGetType(v->ts, &tt));
    PetscCheck(explicit, v->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_verify_ts_type %s: the check steps explicitly with a fixed step: rk, ssp or euler", tt);
    PetscCall(TSGetAdapt(v->ts, &adapt));
    PetscCall(TSAdaptSetType(adapt, TSADAPTNONE));
  }
  PetscCall(TSSetSolution(v->ts, v->y));
  v->setupcalled = PETSC_TRUE;
  if (v->view) PetscCall(JRVerifyView(v, NULL));
  PetscFunctionReturn(0);
}

/* The harmonic-balance point's state at t = 0: q = a0 + sum_h ac_h, q' = sum_h h w as_h; and the slips from one
   period of the elements' prescribed motion (all-stick elements: the point of their common band nearest zero) */
static PetscErrorCode InitialState(JRVerify v, PetscReal omega, const PetscReal a[], PetscInt N)
{
  JRHBM           h  = v->hbm;
  const PetscInt  nm = v->nm, nc = v->nc;
  PetscReal      *y;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(v->y, &y));
  for (PetscInt i = 0; i < nm; i++) {
    PetscReal q = a[i], p = 0;
    for (PetscInt k = 1; k <= v->H; k++) {
      q += a[2 * k * nm + i];
      p += k * omega * a[(2 * k - 1) * nm + i];
    }
    const PetscBool rigid = (PetscBool)(h->pin && h->pin[i] != 0);
    y[i]      = v->rest && !rigid ? 0.0 : q;
    y[nm + i] = v->rest && !rigid ? 0.0 : p;
  }
  PetscCall(VecRestoreArray(v->y, &y));
  for (PetscInt t = 0; t < v->ngroups; t++) {
    JRHBMGroup     *g  = &h->g[t];
    VerifyGroup    *vg = &v->g[t];
    const PetscInt  nloc = vg->nloc;
    PetscReal      *U, *V = NULL, *lo, *hi, *bl, *bu;
    if (vg->type == VERIFY_CUBIC || !nloc) continue;
    if (v->rest) {
      PetscCall(PetscArrayzero(vg->w, nloc));
      continue;
    }
    PetscCall(PetscMalloc4(nloc * nc, &U, nloc * nc, &V, nloc, &lo, nloc, &hi));
    PetscCall(PetscMalloc2(nloc, &bl, nloc, &bu));
    PetscCall(JRGemm("N", "N", nloc, nc, nm, 1.0, g->R, nloc, a, nm, 0.0, U, nloc));
    if (g->normal) PetscCall(JRGemm("N", "N", nloc, nc, nm, 1.0, g->S, nloc, a, nm, 0.0, V, nloc));
    else PetscCall(PetscArrayzero(V, nloc * nc));
    for (PetscInt e = 0; e < nloc; e++) {
      lo[e] = -PETSC_MAX_REAL;
      hi[e] = PETSC_MAX_REAL;
    }
    /* pass 0: the common band (all-stick test); passes 1, 2: the play operator marched over two periods */
    for (PetscInt pass = 0; pass < 3; pass++) {
      if (pass == 1)
        for (PetscInt e = 0; e < nloc; e++) {
          bl[e] = lo[e];
          bu[e] = hi[e];
          if (lo[e] <= hi[e]) vg->w[e] = Clamp(0.0, lo[e], hi[e]);
          else vg->w[e] = PETSC_MAX_REAL; /* marched below */
        }
      for (PetscInt j = 1; j <= N; j++) {
        const PetscReal th = 2 * PETSC_PI * j / N;
        for (PetscInt e = 0; e < nloc; e++) {
          PetscReal u = U[e], vn = V[e], b;
          if (pass && bl[e] <= bu[e]) continue;
          for (PetscInt k = 1; k <= v->H; k++) {
            const PetscReal sk = PetscSinReal(k * th), ck = PetscCosReal(k * th);
            u += U[e + (2 * k - 1) * nloc] * sk + U[e + 2 * k * nloc] * ck;
            vn += V[e + (2 * k - 1) * nloc] * sk + V[e + 2 * k * nloc] * ck;
          }
          b = Band(vg, e, vn);
          if (!pass) {
            lo[e] = PetscMax(lo[e], u - b);
            hi[e] = PetscMin(hi[e], u + b);
          } else if (vg->w[e] == PETSC_MAX_REAL) vg->w[e] = Clamp(0.0, u - b, u + b);
          else vg->w[e] = Clamp(vg->w[e], u - b, u + b);
        }
      }
    }
    PetscCall(PetscFree4(U, V, lo, hi));
    PetscCall(PetscFree2(bl, bu));
  }
  PetscFunctionReturn(0);
}

/* The state's change over a period relative to its size, velocities scaled by 1/w, rigid-body modes left out */
static PetscErrorCode Change(JRVerify v, PetscReal *d)
{
  const PetscReal *y, *yp;
  PetscReal        s = 0, n = 0;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(v->y, &y));
  PetscCall(VecGetArrayRead(v->yprev, &yp));
  for (PetscInt i = 0; i < 2 * v->nm; i++) {
    const PetscInt  r  = i % v->nm;
    const PetscReal sc = i < v->nm ? 1.0 : 1.0 / v->omega;
    if (v->hbm->pin && v->hbm->pin[r] != 0) continue; /* rigid-body modes: forced, periodic from the start; their large motion would hide the rest's change */
    s += PetscSqr(sc * (y[i] - yp[i]));
    n += PetscSqr(sc * y[i]);
  }
  PetscCall(VecRestoreArrayRead(v->yprev, &yp));
  PetscCall(VecRestoreArrayRead(v->y, &y));
  *d = n > 0 ? PetscSqrtReal(s / n) : PetscSqrtReal(s);
  PetscFunctionReturn(0);
}

/* Structural damping's correction from the harmonics 2..H of the modal motion, coef = [as_2 ac_2 | ... | as_H ac_H]
   (nm each, the harmonic balance's layout): ecs = gamma (1 - h) Kg [as_h ac_h], which turns the viscous (gamma / w) Kg
   (h gamma Kg on harmonic h) into the harmonic balance's gamma Kg on every harmonic up to H. It is taken from the last
   period (from the harmonic-balance point during the first): exact at the periodic steady state. */
static PetscErrorCode SetCorrection(JRVerify v, const PetscReal coef[])
{
  JRHBM          h  = v->hbm;
  const PetscInt nm = v->nm;

  PetscFunctionBeginUser;
  if (!v->corr) PetscFunctionReturn(0);
  PetscCall(JRGemm("N", "N", nm, 2 * (v->H - 1), nm, h->gamma, h->Kg ? h->Kg : h->Km, nm, coef, nm, 0.0, v->ecs, nm));
  for (PetscInt hh = 2; hh <= v->H; hh++)
    for (PetscInt i = 0; i < 2 * nm; i++) v->ecs[2 * (hh - 2) * nm + i] *= (PetscReal)(1 - hh);
  PetscFunctionReturn(0);
}

/* The harmonics 2..H of the last period's modal motion (N samples at the angles 2 pi j / N), into coef */
static PetscErrorCode PeriodHarmonics(JRVerify v, PetscInt N, const PetscReal sn[], const PetscReal cs[], PetscReal coef[])
{
  const PetscInt nm = v->nm;

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(coef, 2 * (v->H - 1) * nm));
  for (PetscInt hh = 2; hh <= v->H; hh++) {
    PetscReal *S = coef + 2 * (hh - 2) * nm, *C = S + nm;
    for (PetscInt j = 0; j < N; j++) {
      const PetscInt   m = (hh * j) % N;
      const PetscReal  ws = 2.0 / N * sn[m], wc = 2.0 / N * cs[m], *q = v->qs + j * nm;
      for (PetscInt i = 0; i < nm; i++) {
        S[i] += ws * q[i];
        C[i] += wc * q[i];
      }
    }
  }
  PetscCall(PetscLogFlops(4.0 * N * nm * (v->H - 1)));
  PetscFunctionReturn(0);
}

/* The samples of one period: N steps per period of the state, output 1 sampled at the angles 2 pi j / N, and with
   the damping correction the modal samples for the next period's */
static PetscErrorCode MarchPeriods(JRVerify v, PetscReal T, PetscInt N, JRVerifyResult *res)
{
  JRHBM          h  = v->hbm;
  const PetscInt nm = v->nm;
  PetscReal      dprev = -1, d = 0;
  PetscBool      done  = PETSC_FALSE;
  PetscInt       k;

  PetscFunctionBeginUser;
  PetscCall(TSSetTimeStep(v->ts, T / N));
  PetscCall(TSSetMaxTime(v->ts, (v->maxperiods + 1) * T));
  PetscCall(TSSetMaxSteps(v->ts, PETSC_MAX_INT));
  PetscCall(VecCopy(v->y, v->yprev));
  for (k = 1; k <= v->maxperiods && !done; k++) {
    PetscCall(TSSetTime(v->ts, (k - 1) * T)); /* no round-off creeping into the phase over many periods */
    PetscCall(TSSetStepNumber(v->ts, 0));
    for (PetscInt j = 1; j <= N; j++) {
      const PetscReal *y;
      PetscReal        x = 0;
      PetscCall(TSStep(v->ts));
      PetscCall(VecGetArrayRead(v->y, &y));
      PetscCall(CommitSlip(v, y));
      for (PetscInt i = 0; i < nm; i++) x += h->Phiout[i] * y[i];
      v->x[j % N] = x; /* sample at the angle 2 pi j / N */
      if (v->corr) PetscCall(PetscArraycpy(v->qs + (j % N) * nm, y, nm));
      PetscCall(VecRestoreArrayRead(v->y, &y));
    }
    if (v->corr) {
      PetscCall(PeriodHarmonics(v, N, v->sn, v->cs, v->ecoef));
      PetscCall(SetCorrection(v, v->ecoef));
    }
    PetscCall(Change(v, &d));
    PetscCall(VecCopy(v->y, v->yprev));
    if (k >= 3 && d <= v->ptol && dprev <= v->ptol) {
      const PetscReal rho = dprev > 0 ? d / dprev : 0;
      done                = (PetscBool)(rho >= 1 || d * rho / (1 - rho) <= v->ptol);
    }
    dprev = d;
  }
  res->periods  = k - 1;
  res->steps    = N;
  res->change   = d;
  res->periodic = done;
  PetscFunctionReturn(0);
}

/* Output 1 over the last period: its first harmonic (xs, xc) and the rest's share of the signal (Parseval) */
static void TimeHarmonics(JRVerify v, PetscInt N, PetscReal *xs, PetscReal *xc, JRVerifyResult *res)
{
  PetscReal mean = 0, var = 0;

  *xs = *xc = 0;
  for (PetscInt j = 0; j < N; j++) mean += v->x[j] / N;
  for (PetscInt j = 0; j < N; j++) {
    const PetscReal th = 2 * PETSC_PI * j / N;
    *xs += 2.0 / N * v->x[j] * PetscSinReal(th);
    *xc += 2.0 / N * v->x[j] * PetscCosReal(th);
    var += PetscSqr(v->x[j] - mean) / N;
  }
  res->amp_time    = PetscSqrtReal(*xs * *xs + *xc * *xc);
  res->higher_time = var > 0 ? PetscSqrtReal(PetscMax(0.0, var - 0.5 * res->amp_time * res->amp_time) / var) : 0.0;
}

/* The harmonic balance's output 1 for the coefficients a: its first harmonic (hs, hc) and the higher harmonics' share */
static void HBMHarmonics(JRVerify v, const PetscReal a[], PetscReal *hs, PetscReal *hc, JRVerifyResult *res)
{
  JRHBM          h  = v->hbm;
  const PetscInt nm = v->nm;
  PetscReal      hsum = 0;

  *hs = *hc = 0;
  for (PetscInt i = 0; i < nm; i++) {
    *hs += h->Phiout[i] * a[nm + i];
    *hc += h->Phiout[i] * a[2 * nm + i];
  }
  res->amp_hbm = PetscSqrtReal(*hs * *hs + *hc * *hc);
  for (PetscInt kk = 2; kk <= v->H; kk++) {
    PetscReal s = 0, c = 0;
    for (PetscInt i = 0; i < nm; i++) {
      s += h->Phiout[i] * a[(2 * kk - 1) * nm + i];
      c += h->Phiout[i] * a[2 * kk * nm + i];
    }
    hsum += s * s + c * c;
  }
  res->higher_hbm = hsum + res->amp_hbm * res->amp_hbm > 0 ? PetscSqrtReal(hsum / (hsum + res->amp_hbm * res->amp_hbm)) : 0.0;
}

/*
  JRVerifySolve - one harmonic-balance point checked by time integration: level F [N], frequency omega [rad/s], the
  point's modal harmonic coefficients a (nm (2H + 1), [a0 | as_1 ac_1 | ...]). Collective; every rank integrates the
  same small system, the element forces split across the ranks as in the harmonic balance.
*/
PetscErrorCode JRVerifySolve(JRVerify v, PetscReal F, PetscReal omega, const PetscReal a[], JRVerifyResult *res)
{
  JRHBM           h  = v->hbm;
  const PetscInt  nm = v->nm;
  const PetscReal T  = 2 * PETSC_PI / omega;
  PetscInt        N;
  PetscReal       xs, xc, hs, hc, dp;
  PetscLogDouble  t0, t1;

  PetscFunctionBeginUser;
  PetscCall(JRVerifySetUp(v));
  PetscCheck(PetscIsNormalReal(omega) && omega > 0, v->comm, PETSC_ERR_ARG_OUTOFRANGE, "JRVerifySolve: frequency %g rad/s", (double)omega);
  PetscCall(PetscLogEventBegin(JR_Verify, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  v->level = F;
  v->omega = omega;
  /* steps per period: the option's, or the stability limit dt w_max <= 2 */
  N = PetscMax(v->steps, (PetscInt)PetscCeilReal(T * PetscSqrtReal(v->wmax2) / 2.0));
  if (N > v->nx) {
    PetscCall(PetscFree(v->x));
    PetscCall(PetscFree3(v->qs, v->sn, v->cs));
    PetscCall(PetscMalloc1(N, &v->x));
    PetscCall(PetscMalloc3(v->corr ? N * nm : 1, &v->qs, N, &v->sn, N, &v->cs)); /* the modal samples only for the damping correction */
    v->nx = N;
  }
  for (PetscInt j = 0; j < N; j++) {
    v->sn[j] = PetscSinReal(2 * PETSC_PI * j / N);
    v->cs[j] = PetscCosReal(2 * PETSC_PI * j / N);
  }
  for (PetscInt i = 0; i < nm; i++)
    for (PetscInt j = 0; j < nm; j++) v->Cv[i * nm + j] = h->Cm[i * nm + j] + (h->gamma / omega) * (h->Kg ? h->Kg[i * nm + j] : h->Km[i * nm + j]);
  PetscCall(InitialState(v, omega, a, N));
  if (v->corr) {
    if (v->rest) PetscCall(PetscArrayzero(v->ecs, 2 * (v->H - 1) * nm));
    else PetscCall(SetCorrection(v, a + 3 * nm));
  }
  PetscCall(MarchPeriods(v, T, N, res));
  TimeHarmonics(v, N, &xs, &xc, res);
  HBMHarmonics(v, a, &hs, &hc, res);
  res->rel_diff = res->amp_hbm > 0 ? PetscAbsReal(res->amp_time - res->amp_hbm) / res->amp_hbm : PetscAbsReal(res->amp_time);
  dp            = PetscAtan2Real(xc, xs) - PetscAtan2Real(hc, hs);
  while (dp > PETSC_PI) dp -= 2 * PETSC_PI;
  while (dp < -PETSC_PI) dp += 2 * PETSC_PI;
  res->phase_deg = dp * 180 / PETSC_PI;
  PetscCall(PetscTime(&t1));
  res->seconds = t1 - t0;
  PetscCall(PetscLogEventEnd(JR_Verify, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Whether point k of a curve lies where the continuation runs forward in frequency: between two folds it runs back,
   and there (the middle branch of a fold pair, as in thesis 2.4.3's Duffing case) the response is unstable and the
   time integration would leave it */
static PetscBool Forward(PetscInt np, const PetscReal om[], PetscInt k)
{
  return (PetscBool)((k == 0 || om[k] >= om[k - 1]) && (k == np - 1 || om[k + 1] >= om[k]));
}

/* The points of a level's curve to check: the largest amplitude of output 1 (the peak; if it lies on a backward
   segment, the nearest point on a forward one), then alternately below and above it the first forward points whose
   amplitude has fallen to 2^(-m/2) of the peak's (m = 1, 2, ...: the half-power points first); n <= want distinct
   indices */
static PetscErrorCode PickPoints(PetscInt np, const PetscReal om[], const PetscReal amp[], PetscInt nout, PetscInt want, PetscInt idx[], PetscInt *npt)
{
  PetscInt kp = 0, n = 0, m = 1, side = 0, stall = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 1; i < np; i++)
    if (amp[i * nout] > amp[kp * nout]) kp = i;
  for (PetscInt d = 1; !Forward(np, om, kp) && d < np; d++) {
    if (kp - d >= 0 && Forward(np, om, kp - d)) kp -= d;
    else if (kp + d < np && Forward(np, om, kp + d)) kp += d;
  }
  idx[n++] = kp;
  while (n < want && n < np && stall < 4 * want + 8) {
    const PetscReal target = amp[kp * nout] * PetscPowReal(2.0, -0.5 * m);
    PetscInt        pick   = -1;
    if (side == 0) {
      for (PetscInt i = kp - 1; i >= 0 && pick < 0; i--)
        if (amp[i * nout] <= target && Forward(np, om, i)) pick = i;
    } else {
      for (PetscInt i = kp + 1; i < np && pick < 0; i++)
        if (amp[i * nout] <= target && Forward(np, om, i)) pick = i;
    }
    if (pick >= 0) {
      PetscBool dup = PETSC_FALSE;
      for (PetscInt i = 0; i < n; i++) dup = (PetscBool)(dup || idx[i] == pick);
      if (!dup) {
        idx[n++] = pick;
        stall    = 0;
      } else stall++;
    } else stall++;
    if (side == 1) m++;
    side = !side;
  }
  *npt = n;
  PetscFunctionReturn(0);
}

/*
  JRVerifyCurves - after the curves: on every level of cont, the peak and -frf_verify_points - 1 points around it
  checked by time integration of hbm's modal equations, one line per point

    verify level <F> freq_hz <f> amplitude_hbm <a> amplitude_time <b> rel_diff <d> higher_harmonics <s> periods <n>
      higher_harmonics_hbm <s> phase_deg <p> steps <N> change <c> seconds <t>

  and a warning when rel_diff exceeds -frf_verify_tol or the run did not become periodic. Nothing with 0 points.
*/
PetscErrorCode JRVerifyCurves(JRVerify v, JRHBM h, JRCont cont)
{
  PetscInt  nlev, nout;
  PetscReal worst = 0, tsum = 0;
  PetscInt  npts = 0;

  PetscFunctionBeginUser;
  if (!v || (!v->npoints && !v->unstable) || !cont) PetscFunctionReturn(0);
  PetscCall(JRVerifySetHBM(v, h));
  PetscCall(JRVerifySetUp(v));
  PetscCall(JRContGetNumLevels(cont, &nlev));
  nout = h->nout;
  for (PetscInt lev = 0; lev < nlev; lev++) {
    PetscInt         np, idx[100], n, npk;
    const PetscReal *om, *aa, *amp;
    PetscReal        F;
    PetscCall(JRContGetLevel(cont, lev, &F));
    PetscCall(JRContGetBranch(cont, lev, &np, &om, &aa, &amp));
    if (!np) continue;
    n = 0;
    if (v->npoints) PetscCall(PickPoints(np, om, amp, nout, v->npoints, idx, &n));
    npk = n;
    if (v->unstable) { /* the middle of each stretch flagged unstable */
      const PetscInt *st;
      PetscCall(JRContGetStability(cont, lev, &st, NULL, NULL, NULL, NULL, NULL));
      for (PetscInt k = 0; st && k < np && n < 100;) {
        PetscInt e = k;
        if (st[k]) {
          k++;
          continue;
        }
        while (e + 1 < np && !st[e + 1]) e++;
        if (n < npk + 20) idx[n++] = (k + e) / 2;
        k = e + 1;
      }
    }
    for (PetscInt i = 0; i < n; i++) {
      JRVerifyResult r;
      const PetscInt k = idx[i];
      const PetscReal fhz = om[k] / (2 * PETSC_PI);
      PetscCall(JRVerifySolve(v, F, om[k], aa + k * h->n, &r));
      if (i >= npk) PetscCall(PetscPrintf(v->comm, "verify: level %g freq_hz %.8g flagged unstable by -frf_stability\n", (double)F, (double)fhz));
      PetscCall(PetscPrintf(v->comm, "verify level %g freq_hz %.12g amplitude_hbm %.10e amplitude_time %.10e rel_diff %.3e higher_harmonics %.3e periods %" PetscInt_FMT " higher_harmonics_hbm %.3e phase_deg %.3e steps %" PetscInt_FMT " change %.2e seconds %.3g\n", (double)F, (double)fhz, (double)r.amp_hbm, (double)r.amp_time, (double)r.rel_diff, (double)r.higher_time, r.periods, (double)r.higher_hbm, (double)r.phase_deg, r.steps, (double)r.change, (double)r.seconds));
      if (!r.periodic) PetscCall(PetscPrintf(v->comm, "verify: WARNING level %g freq_hz %.8g: not periodic after %" PetscInt_FMT " periods (change over the last %.2e > -frf_verify_periodic_tol %g, or still decaying): raise -frf_verify_max_periods\n", (double)F, (double)fhz, r.periods, (double)r.change, (double)v->ptol));
      if (r.rel_diff > v->tol) PetscCall(PetscPrintf(v->comm, "verify: WARNING level %g freq_hz %.8g: the time integration's first harmonic differs from the harmonic balance's by %.3e (> -frf_verify_tol %g); higher harmonics %.3e of the response (%.3e in the harmonic balance)%s\n", (double)F, (double)fhz, (double)r.rel_diff, (double)v->tol, (double)r.higher_time, (double)r.higher_hbm, r.rel_diff > 0.5 ? ": the time integration settled on another response (the point is unstable, or near a fold where the harmonic balance's truncation moves it)" : ": the same modal equations, so the harmonic balance's truncation (-hbm_harmonics, -hbm_samples; the elements' motions may carry more higher harmonics than the response) or the time step (-frf_verify_steps)"));
      worst = PetscMax(worst, r.rel_diff);
      tsum += r.seconds;
      npts++;
    }
  }
  PetscCall(PetscPrintf(v->comm, "verify: %" PetscInt_FMT " points by time integration (TS), worst rel_diff %.3e, %.3g s\n", npts, (double)worst, (double)tsum));
  PetscFunctionReturn(0);
}

PetscErrorCode JRVerifyView(JRVerify v, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  if (!viewer) viewer = PETSC_VIEWER_STDOUT_(v->comm);
  PetscCall(PetscViewerASCIIPrintf(viewer, "JRVerify: %" PetscInt_FMT " points per level, %" PetscInt_FMT " steps per period, periodic to %g in at most %" PetscInt_FMT " periods, from %s, warn above %g\n", v->npoints, v->steps, (double)v->ptol, v->maxperiods, v->rest ? "rest" : "the harmonic balance's state", (double)v->tol));
  if (v->setupcalled) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "  %" PetscInt_FMT " modes, %" PetscInt_FMT " harmonics in the comparison, stiffest mode bound %g Hz (every friction element stuck)%s\n", v->nm, v->H, (double)(PetscSqrtReal(v->wmax2) / (2 * PETSC_PI)), v->corr ? "; structural damping on harmonics 2..H from the last period" : ""));
    PetscCall(PetscViewerASCIIPushTab(viewer));
    PetscCall(TSView(v->ts, viewer));
    PetscCall(PetscViewerASCIIPopTab(viewer));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode JRVerifyDestroy(JRVerify *vp)
{
  JRVerify v;

  PetscFunctionBeginUser;
  if (!vp || !*vp) PetscFunctionReturn(0);
  v = *vp;
  PetscCall(Reset(v));
  PetscCall(PetscFree(v));
  *vp = NULL;
  PetscFunctionReturn(0);
}
