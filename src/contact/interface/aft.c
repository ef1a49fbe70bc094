/*
   Alternating frequency-time (AFT) evaluation of one friction element with H harmonics and N samples.

   The element is a play operator on the slip w (3.31)-(3.36): with n_j = max(0, n0 + kn v_j) and
   r = mu/kt, the stick band at sample j is  L_j = u_j - r n_j <= w <= U_j = u_j + r n_j, and
       w_j = clamp(w_{j-1}, L_j, U_j),   f_j = kt (u_j - w_j)
   (stick inside the band; positive slip w = L, f = +mu n; negative slip w = U, f = -mu n;
   separation n = 0 collapses the band, w = u, f = 0). The periodic steady state is marched
   directly in one cycle, without transient, from a sample whose state is known:
   - with separation: the first contact sample after a separated one (memory is erased there);
     the slip at first contact is the interpolated contact point u_c (second-order accurate);
   - without separation, when max L > min U (no stick-only cycle exists): at j* = argmax L the
     periodic orbit has w = L_{j*} (positive slip ends there: w never exceeds max L, never falls
     below L), so the march starts in positive slip at j*;
   - otherwise the element sticks all cycle; the slip is the point of the admissible band
     [max L, min U] nearest to zero (the state reached from an unslipped start).

   Jacobian, analytic through the march: each sample's slip equals that of an anchor sample a(j)
   (the last slip/separated sample, a virtual contact point, or none), so
       df_j = kt (du_j - dX_a),   dX_a = du_a -+ r dn_a   (slip),  du_c (contact point)
   and with the DFT F = diag(wdft) sum_j B_j f_j it becomes sums over runs of equal state,
       dF/dU = kt W [ sum_stick B_j B_j^T - (sum_run B_j) dX_a^T ],   dF/dV = +-mu kn W sum_slip B_j B_j^T - ...
   evaluated from prefix sums of B_j and of B_j B_j^T: O(runs * nc^2), not O(N nc^2).
*/
#include <jointrom/private/contactimpl.h>

#define JR_CODE_RECONTACT 4
#if defined(JR_COUNT_RUNS)
long jr_runs = 0, jr_elems = 0;
#endif /* flag: first contact sample after separation */

/* Tables and scratch for H harmonics and N samples */
PetscErrorCode JRAFTCreate(PetscInt H, PetscInt N, JRAFT **aft)
{
  JRAFT   *a;
  PetscInt nc = 2 * H + 1, j, k, m;

  PetscFunctionBeginUser;
  PetscCheck(H >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Number of harmonics H = %" PetscInt_FMT " must be at least 1", H);
  PetscCheck(N >= nc, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Number of time samples N = %" PetscInt_FMT " must be at least 2H+1 = %" PetscInt_FMT " for H = %" PetscInt_FMT " harmonics", N, nc, H);
  PetscCall(PetscNew(&a));
  a->H  = H;
  a->N  = N;
  a->nc = nc;
  PetscCall(PetscMalloc1(nc * N, &a->Bt));
  PetscCall(PetscMalloc1((N + 1) * nc, &a->PB));
  PetscCall(PetscMalloc1((size_t)(N + 1) * nc * nc, &a->PG));
  PetscCall(PetscMalloc1(nc, &a->wdft));
  PetscCall(PetscMalloc5(N, &a->u, N, &a->v, N, &a->g, N, &a->f, N, &a->lam));
  PetscCall(PetscMalloc2(N, &a->code, N, &a->rc));
  PetscCall(PetscMalloc3(N, &a->Lb, N, &a->Ub, N, &a->uc));
  PetscCall(PetscMalloc6(nc, &a->S, nc * nc, &a->wflat, nc, &a->dXU, nc, &a->dXV, nc * nc, &a->DU, nc * nc, &a->DV));
  PetscCall(PetscMalloc1(nc * nc, &a->DN));
  for (j = 0; j < N; j++) {
    PetscReal th = 2.0 * PETSC_PI * (PetscReal)j / (PetscReal)N;
    a->Bt[j] = 1.0;
    for (k = 1; k <= H; k++) {
      a->Bt[(2 * k - 1) * N + j] = PetscSinReal(k * th);
      a->Bt[(2 * k) * N + j]     = PetscCosReal(k * th);
    }
  }
  a->wdft[0] = 1.0 / N;
  for (k = 1; k < nc; k++) a->wdft[k] = 2.0 / N;
  for (k = 0; k < nc; k++)
    for (m = 0; m < nc; m++) a->wflat[k * nc + m] = a->wdft[k];
  for (k = 0; k < nc; k++) a->PB[k] = 0.0;
  for (k = 0; k < nc * nc; k++) a->PG[k] = 0.0;
  for (j = 0; j < N; j++) {
    for (k = 0; k < nc; k++) a->PB[(j + 1) * nc + k] = a->PB[j * nc + k] + a->Bt[k * N + j];
    for (k = 0; k < nc; k++)
      for (m = 0; m < nc; m++) a->PG[(size_t)(j + 1) * nc * nc + k * nc + m] = a->PG[(size_t)j * nc * nc + k * nc + m] + a->Bt[k * N + j] * a->Bt[m * N + j];
  }
  *aft = a;
  PetscFunctionReturn(0);
}

PetscErrorCode JRAFTDestroy(JRAFT **aft)
{
  JRAFT *a = *aft;

  PetscFunctionBeginUser;
  if (!a) PetscFunctionReturn(0);
  PetscCall(PetscFree(a->Bt));
  PetscCall(PetscFree(a->PB));
  PetscCall(PetscFree(a->PG));
  PetscCall(PetscFree(a->wdft));
  PetscCall(PetscFree5(a->u, a->v, a->g, a->f, a->lam));
  PetscCall(PetscFree2(a->code, a->rc));
  PetscCall(PetscFree3(a->Lb, a->Ub, a->uc));
  PetscCall(PetscFree6(a->S, a->wflat, a->dXU, a->dXV, a->DU, a->DV));
  PetscCall(PetscFree(a->DN));
  PetscCall(PetscFree(a));
  *aft = NULL;
  PetscFunctionReturn(0);
}

/* sum a_j b_j with 8 independent partial sums, so that it vectorises without reassociation flags */
static inline PetscReal Dot(PetscInt n, const PetscReal *restrict a, const PetscReal *restrict b)
{
  PetscReal acc[8] = {0, 0, 0, 0, 0, 0, 0, 0}, s = 0.0;
  PetscInt  j = 0;
  for (; j + 8 <= n; j += 8)
    for (int l = 0; l < 8; l++) acc[l] += a[j + l] * b[j + l];
  for (; j < n; j++) s += a[j] * b[j];
  return s + ((acc[0] + acc[4]) + (acc[1] + acc[5])) + ((acc[2] + acc[6]) + (acc[3] + acc[7]));
}

/* x_j = X0 + sum_k X_k B_kj: one vectorised pass over the samples per coefficient (x stays in L1) */
static inline void Synthesis(PetscInt N, PetscInt nc, const PetscReal *restrict Bt, const PetscReal *restrict X, PetscReal *restrict x)
{
  for (PetscInt j = 0; j < N; j++) x[j] = X[0];
  for (PetscInt k = 1; k < nc; k++) {
    const PetscReal  c   = X[k];
    const PetscReal *row = Bt + k * N;
    for (PetscInt j = 0; j < N; j++) x[j] += c * row[j];
  }
}

static inline void Zero(PetscInt n, PetscReal *x)
{
  for (PetscInt i = 0; i < n; i++) x[i] = 0.0;
}

/* M += alpha * sum of B_j B_j^T over march positions t0..t1 (inclusive) from sample s, from the prefix
   Gram table (flat nc^2 loops); with wantS also the sum of B_j into a->S */
static inline void GramAdd(const JRAFT *a, PetscInt s, PetscInt t0, PetscInt t1, PetscReal alpha, PetscReal *restrict M, PetscBool wantS)
{
  const PetscInt   N = a->N, nc = a->nc, nc2 = nc * nc;
  PetscInt         p = s + t0, q = s + t1 + 1, k;
  const PetscReal *Pp, *Pq;

  if (p >= N) {
    p -= N;
    q -= N;
  }
  Pp = a->PG + (size_t)p * nc2;
  if (q <= N) {
    Pq = a->PG + (size_t)q * nc2;
    for (k = 0; k < nc2; k++) M[k] += alpha * (Pq[k] - Pp[k]);
    if (wantS)
      for (k = 0; k < nc; k++) a->S[k] = a->PB[q * nc + k] - a->PB[p * nc + k];
  } else { /* wraps: [p, N) and [0, q - N) */
    const PetscReal *PN = a->PG + (size_t)N * nc2;
    q -= N;
    Pq = a->PG + (size_t)q * nc2;
    for (k = 0; k < nc2; k++) M[k] += alpha * (PN[k] - Pp[k] + Pq[k]);
    if (wantS)
      for (k = 0; k < nc; k++) a->S[k] = a->PB[N * nc + k] - a->PB[p * nc + k] + a->PB[q * nc + k];
  }
}

/* M += alpha S x^T and, if y, P += alpha S y^T */
static inline void Rank1(PetscInt nc, PetscReal alpha, const PetscReal *restrict S, const PetscReal *restrict x, PetscReal *restrict M, const PetscReal *restrict y, PetscReal *restrict P)
{
  for (PetscInt k = 0; k < nc; k++) {
    const PetscReal c = alpha * S[k];
    for (PetscInt m = 0; m < nc; m++) M[k * nc + m] += c * x[m];
    if (y)
      for (PetscInt m = 0; m < nc; m++) P[k * nc + m] += c * y[m];
  }
}

/* Anchor derivatives dX/dU (XU) and dX/dV (XV) of a slip sample j: X = u_j - sgn r n_j */
static inline void AnchorSlip(const JRAFT *a, PetscInt j, PetscReal sgn, PetscReal r, PetscReal kn, PetscBool normal)
{
  const PetscInt N = a->N, nc = a->nc;
  for (PetscInt k = 0; k < nc; k++) {
    a->dXU[k] = a->Bt[k * N + j];
    a->dXV[k] = normal ? -sgn * r * kn * a->Bt[k * N + j] : 0.0;
  }
}

/* The slip's stick band: u_j = B_j . U, the normal gap g_j = n0 + kn v_j (n0 without a normal motion) and
   L_j = u_j - r n_j <= w <= U_j = u_j + r n_j, n_j = max(g_j, 0), which collapses to w = u_j (f = 0) on
   separated samples. Returns the number of separated samples. */
static inline PetscInt StickBand(JRAFT *a, PetscReal r, PetscReal kn, PetscReal n0, const PetscReal Ue[], const PetscReal Ve[])
{
  const PetscInt N = a->N;
  PetscReal     *u = a->u, *v = a->v, *g = a->g, *Lb = a->Lb, *Ub = a->Ub;
  PetscInt       nsep = 0;

  Synthesis(N, a->nc, a->Bt, Ue, u); /* vectorised over samples */
  if (Ve) {
    Synthesis(N, a->nc, a->Bt, Ve, v);
    for (PetscInt j = 0; j < N; j++) g[j] = n0 + kn * v[j];
  } else {
    for (PetscInt j = 0; j < N; j++) g[j] = n0;
  }
  for (PetscInt j = 0; j < N; j++) {
    const PetscReal nj = PetscMax(g[j], 0.0);
    Lb[j]              = u[j] - r * nj;
    Ub[j]              = u[j] + r * nj;
    nsep += (g[j] <= 0.0);
  }
  return nsep;
}

/* full separation: no force at all */
static inline void ZeroOutputs(PetscInt N, PetscInt nc, JRElementOut *out, PetscReal ftime[], PetscReal ntime[])
{
  if (out->F) Zero(nc, out->F);
  if (out->N) Zero(nc, out->N);
  if (out->dFdU) Zero(nc * nc, out->dFdU);
  if (out->dFdV) Zero(nc * nc, out->dFdV);
  if (out->dNdV) Zero(nc * nc, out->dNdV);
  if (ftime) Zero(N, ftime);
  if (ntime) Zero(N, ntime);
  out->state = JR_CONTACT_FULL_SEPARATION;
}

/* where the periodic march starts, and in which state */
typedef struct {
  PetscInt  s;         /* the march's first sample */
  PetscInt  jl, jh;    /* without separation: argmax L, argmin U */
  PetscBool fullstick; /* the element sticks all cycle, at slip w ... */
  PetscReal w;
  PetscInt  anchor; /* ... anchored at max L (1), min U (-1) or nowhere (0, w = 0) */
} MarchStart;

static inline void FindMarchStart(JRAFT *a, PetscInt nsep, MarchStart *ms)
{
  const PetscInt   N = a->N;
  const PetscReal *u = a->u, *g = a->g, *Lb = a->Lb, *Ub = a->Ub;
  PetscReal        lo = PETSC_NINFINITY, hi = PETSC_INFINITY;

  ms->s = ms->jl = ms->jh = ms->anchor = 0;
  ms->fullstick                        = PETSC_FALSE;
  ms->w                                = 0.0;
  if (nsep) {
    /* first contact samples: the slip restarts from the interpolated contact point u_c */
    ms->s = -1;
    for (PetscInt j = 0; j < N; j++) {
      const PetscInt jp = j ? j - 1 : N - 1;
      a->rc[j]          = g[j] > 0.0 && g[jp] <= 0.0;
      if (a->rc[j]) {
        a->lam[j] = g[jp] / (g[jp] - g[j]);
        a->uc[j]  = u[jp] + a->lam[j] * (u[j] - u[jp]);
        if (ms->s < 0) ms->s = j;
      }
    }
    return;
  }
  for (PetscInt j = 0; j < N; j++) {
    if (Lb[j] > lo) {
      lo     = Lb[j];
      ms->jl = j;
    }
    if (Ub[j] < hi) {
      hi     = Ub[j];
      ms->jh = j;
    }
  }
  if (lo > hi) ms->s = ms->jl;
  else {
    ms->fullstick = PETSC_TRUE;
    if (lo > 0.0) {
      ms->w      = lo;
      ms->anchor = 1;
    } else if (hi < 0.0) {
      ms->w      = hi;
      ms->anchor = -1;
    }
  }
}

/* f_j over the cycle, and code[t] (state at march position t, from sample s) */
static inline void March(JRAFT *a, PetscReal kt, PetscInt nsep, const MarchStart *ms)
{
  const PetscInt   N = a->N, s = ms->s;
  const PetscReal *u = a->u, *g = a->g, *Lb = a->Lb, *Ub = a->Ub, *uc = a->uc;
  const PetscInt  *rc   = a->rc;
  PetscInt        *code = a->code, j, t;
  PetscReal       *f = a->f, w;

  if (ms->fullstick) {
    for (j = 0; j < N; j++) f[j] = kt * (u[j] - ms->w);
  } else if (!nsep) {
    /* branch-free march: w_j = clamp(w_{j-1}, L_j, U_j), from positive slip at s */
    w = Lb[s];
    for (t = 0, j = s; t < N; t++, j = j + 1 == N ? 0 : j + 1) {
      const PetscReal wn = PetscMin(PetscMax(w, Lb[j]), Ub[j]);
      code[t]            = (w < Lb[j]) | ((w > Ub[j]) << 1);
      f[j]               = kt * (u[j] - wn);
      w                  = wn;
    }
    code[0] = JR_CODE_SLIPP;
  } else {
    /* the same with separation: at a first contact the slip restarts from u_c */
    w = 0.0;
    for (t = 0, j = s; t < N; t++, j = j + 1 == N ? 0 : j + 1) {
      const PetscReal wp = rc[j] ? uc[j] : w;
      const PetscReal wn = PetscMin(PetscMax(wp, Lb[j]), Ub[j]);
      code[t]            = g[j] <= 0.0 ? JR_CODE_SEP : ((wp < Lb[j]) | ((wp > Ub[j]) << 1) | (rc[j] ? JR_CODE_RECONTACT : 0));
      f[j]               = kt * (u[j] - wn);
      w                  = wn;
    }
  }
}

/* DFT of the force (and of the normal load: without separation n = n0 + kn v exactly); the time series */
static inline void Transform(JRAFT *a, PetscReal kn, PetscReal n0, const PetscReal Ve[], PetscInt nsep, JRElementOut *out, PetscReal ftime[], PetscReal ntime[])
{
  const PetscInt   N = a->N, nc = a->nc;
  const PetscReal *Bt = a->Bt, *wd = a->wdft, *f = a->f, *g = a->g;
  PetscReal       *v = a->v;
  PetscInt         j, k;

  if (out->F)
    for (k = 0; k < nc; k++) out->F[k] = wd[k] * Dot(N, f, Bt + k * N);
  if (out->N) {
    if (Ve && nsep) {
      for (j = 0; j < N; j++) v[j] = PetscMax(g[j], 0.0); /* n_j; v is not needed any more */
      for (k = 0; k < nc; k++) out->N[k] = wd[k] * Dot(N, v, Bt + k * N);
    } else if (Ve) {
      out->N[0] = n0 + kn * Ve[0];
      for (k = 1; k < nc; k++) out->N[k] = kn * Ve[k];
    } else {
      Zero(nc, out->N);
      out->N[0] = n0;
    }
  }
  if (ftime)
    for (j = 0; j < N; j++) ftime[j] = f[j];
  if (ntime)
    for (j = 0; j < N; j++) ntime[j] = PetscMax(g[j], 0.0);
}

/* contact state over the cycle */
static inline JRContactState CycleState(const JRAFT *a, PetscInt nsep, PetscBool fullstick)
{
  PetscBool anyslip = PETSC_FALSE;

  if (!fullstick)
    for (PetscInt t = 0; t < a->N; t++)
      if ((a->code[t] & 3) == JR_CODE_SLIPP || (a->code[t] & 3) == JR_CODE_SLIPN) anyslip = PETSC_TRUE;
  return nsep ? JR_CONTACT_SEPARATION_STICK_SLIP : (anyslip ? JR_CONTACT_STICK_SLIP : JR_CONTACT_FULL_STICK);
}

/* Anchor derivatives of a first-contact sample jc: X = u_c, interpolated between jp = jc - 1 and jc at
   lam = g_p / (g_p - g_c) */
static inline void AnchorContact(const JRAFT *a, PetscInt jc, PetscReal kn, PetscBool normal)
{
  const PetscInt   N = a->N, nc = a->nc, jp = jc ? jc - 1 : N - 1;
  const PetscReal *Bt = a->Bt, gp = a->g[jp], gc = a->g[jc], den = gp - gc, du = a->u[jc] - a->u[jp];

  for (PetscInt k = 0; k < nc; k++) {
    a->dXU[k] = (1.0 - a->lam[jc]) * Bt[k * N + jp] + a->lam[jc] * Bt[k * N + jc];
    a->dXV[k] = normal ? du * kn * (gp * Bt[k * N + jc] - gc * Bt[k * N + jp]) / (den * den) : 0.0;
  }
}

/* full stick: f_j = kt (u_j - w), w = 0 or an anchor at max L / min U: dF/dU = kt (I - e0 dX^T) */
static inline void JacobianFullStick(JRAFT *a, PetscReal kt, PetscReal r, PetscReal kn, PetscBool normal, const MarchStart *ms)
{
  const PetscInt nc = a->nc, N = a->N;
  PetscReal     *MU = a->DU, *MV = a->DV;

  for (PetscInt k = 0; k < nc; k++) MU[k * nc + k] = kt / a->wdft[k];
  if (ms->anchor) {
    AnchorSlip(a, ms->anchor > 0 ? ms->jl : ms->jh, ms->anchor > 0 ? 1.0 : -1.0, r, kn, normal);
    for (PetscInt k = 0; k < nc; k++) {
      MU[k] -= kt * N * a->dXU[k];
      MV[k] -= kt * N * a->dXV[k];
    }
  }
}

/* march with slip or separation: the sums over runs of equal state, from the prefix tables */
static inline void JacobianRuns(JRAFT *a, PetscReal kt, PetscReal r, PetscReal kn, PetscReal mu, PetscBool normal, PetscInt s)
{
  const PetscInt  N = a->N, nc = a->nc;
  const PetscInt *code = a->code;
  PetscInt        t0   = 0;

  while (t0 < N) {
    const PetscInt c0 = code[t0] & 3;
    PetscInt       t1 = t0 + 1;
    while (t1 < N && code[t1] == c0) t1++; /* a first-contact sample carries a flag: it starts a run */
    t1--;
    if (c0 == JR_CODE_STICK) {
      /* anchor of this stick run: the sample before it in march order, or the contact point */
      if (code[t0] & JR_CODE_RECONTACT) AnchorContact(a, s + t0 >= N ? s + t0 - N : s + t0, kn, normal);
      else {
        const PetscInt ta = t0 - 1; /* t0 > 0: a stick run not at a contact follows a slip sample */
        PetscInt       ja = s + ta;
        ja                = ja >= N ? ja - N : ja;
        AnchorSlip(a, ja, (code[ta] & 3) == JR_CODE_SLIPP ? 1.0 : -1.0, r, kn, normal);
      }
      GramAdd(a, s, t0, t1, kt, a->DU, PETSC_TRUE);
      Rank1(nc, -kt, a->S, a->dXU, a->DU, normal ? a->dXV : NULL, a->DV);
    } else if (c0 == JR_CODE_SEP) {
      if (normal) GramAdd(a, s, t0, t1, -kn, a->DN, PETSC_FALSE);
    } else if (normal) {
      GramAdd(a, s, t0, t1, c0 == JR_CODE_SLIPP ? mu * kn : -mu * kn, a->DV, PETSC_FALSE);
    }
    t0 = t1 + 1;
#if defined(JR_COUNT_RUNS)
    jr_runs++;
#endif
  }
}

/* the derivatives: unweighted sums in a->DU, DV, DN, then dX/dY = diag(wdft) M;
   dN/dV = kn W sum_contact B B^T = kn (I - W sum_separated B B^T) */
static inline void Jacobian(JRAFT *a, PetscReal kt, PetscReal r, PetscReal kn, PetscReal mu, PetscBool normal, const MarchStart *ms, JRElementOut *out)
{
  const PetscInt nc = a->nc, nc2 = nc * nc;
  PetscInt       k;

  Zero(nc2, a->DU);
  Zero(nc2, a->DV);
  Zero(nc2, a->DN);
  if (ms->fullstick) JacobianFullStick(a, kt, r, kn, normal, ms);
  else JacobianRuns(a, kt, r, kn, mu, normal, ms->s);
  if (out->dFdU)
    for (k = 0; k < nc2; k++) out->dFdU[k] = a->wflat[k] * a->DU[k];
  if (out->dFdV)
    for (k = 0; k < nc2; k++) out->dFdV[k] = a->wflat[k] * a->DV[k];
  if (out->dNdV) {
    for (k = 0; k < nc2; k++) out->dNdV[k] = a->wflat[k] * a->DN[k];
    if (normal)
      for (k = 0; k < nc; k++) out->dNdV[k * nc + k] += kn;
  }
}

/*
  JRAFTElement - one friction element by AFT (see the top of this file): its force F and normal load N
  (harmonic coefficients), the derivatives dF/dU, dF/dV, dN/dV that out asks for (non-NULL), its contact
  state over the cycle, and if asked the force and normal load at the N samples (ftime, ntime).
  Ve NULL: a constant normal load n0 (kn unused).
*/
void JRAFTElement(JRAFT *a, PetscReal kt, PetscReal kn, PetscReal mu, PetscReal n0, const PetscReal Ue[], const PetscReal Ve[], JRElementOut *out, PetscReal ftime[], PetscReal ntime[])
{
  const PetscReal r      = mu / kt;
  const PetscBool normal = Ve ? PETSC_TRUE : PETSC_FALSE;
  PetscInt        nsep;
  MarchStart      ms;

  nsep = StickBand(a, r, kn, n0, Ue, Ve);
  if (nsep == a->N) {
    ZeroOutputs(a->N, a->nc, out, ftime, ntime);
    return;
  }
  FindMarchStart(a, nsep, &ms);
  March(a, kt, nsep, &ms);
  Transform(a, kn, n0, Ve, nsep, out, ftime, ntime);
  out->state = CycleState(a, nsep, ms.fullstick);
  if (!(out->dFdU || out->dFdV || out->dNdV)) return;
#if defined(JR_COUNT_RUNS)
  jr_elems++;
#endif
  Jacobian(a, kt, r, kn, mu, normal, &ms, out);
}
