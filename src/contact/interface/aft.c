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

#define JR_CODE_RECONTACT 4 /* flag: first contact sample after separation */

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
  PetscCall(PetscMalloc1(N, &a->code));
  PetscCall(PetscMalloc6(nc, &a->S, nc * nc, &a->G, nc, &a->dXU, nc, &a->dXV, nc * nc, &a->DU, nc * nc, &a->DV));
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
  PetscCall(PetscFree(a->code));
  PetscCall(PetscFree6(a->S, a->G, a->dXU, a->dXV, a->DU, a->DV));
  PetscCall(PetscFree(a));
  *aft = NULL;
  PetscFunctionReturn(0);
}

static inline void Zero(PetscInt n, PetscReal *x)
{
  for (PetscInt i = 0; i < n; i++) x[i] = 0.0;
}

/* Sums of B_j (S) and of B_j B_j^T (G) over march positions t0..t1 (inclusive) starting at sample s */
static inline void Interval(const JRAFT *a, PetscInt s, PetscInt t0, PetscInt t1, PetscBool wantG)
{
  const PetscInt N = a->N, nc = a->nc, nc2 = nc * nc;
  PetscInt       p = s + t0, q = s + t1 + 1, k;

  if (p >= N) {
    p -= N;
    q -= N;
  }
  if (q <= N) {
    for (k = 0; k < nc; k++) a->S[k] = a->PB[q * nc + k] - a->PB[p * nc + k];
    if (wantG)
      for (k = 0; k < nc2; k++) a->G[k] = a->PG[(size_t)q * nc2 + k] - a->PG[(size_t)p * nc2 + k];
  } else {
    q -= N;
    for (k = 0; k < nc; k++) a->S[k] = a->PB[N * nc + k] - a->PB[p * nc + k] + a->PB[q * nc + k];
    if (wantG)
      for (k = 0; k < nc2; k++) a->G[k] = a->PG[(size_t)N * nc2 + k] - a->PG[(size_t)p * nc2 + k] + a->PG[(size_t)q * nc2 + k];
  }
}

/* D += alpha diag(w) G */
static inline void AddWG(PetscInt nc, const PetscReal *w, PetscReal alpha, const PetscReal *G, PetscReal *D)
{
  for (PetscInt k = 0; k < nc; k++) {
    const PetscReal s = alpha * w[k];
    for (PetscInt m = 0; m < nc; m++) D[k * nc + m] += s * G[k * nc + m];
  }
}

/* D += alpha diag(w) S x^T */
static inline void AddWSx(PetscInt nc, const PetscReal *w, PetscReal alpha, const PetscReal *S, const PetscReal *x, PetscReal *D)
{
  for (PetscInt k = 0; k < nc; k++) {
    const PetscReal s = alpha * w[k] * S[k];
    for (PetscInt m = 0; m < nc; m++) D[k * nc + m] += s * x[m];
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

void JRAFTElement(JRAFT *a, PetscReal kt, PetscReal kn, PetscReal mu, PetscReal n0, const PetscReal Ue[], const PetscReal Ve[], JRElementOut *out, PetscReal ftime[], PetscReal ntime[])
{
  const PetscInt   N = a->N, nc = a->nc;
  const PetscReal *Bt = a->Bt, *wd = a->wdft;
  PetscReal       *u = a->u, *v = a->v, *g = a->g, *f = a->f, *lam = a->lam;
  PetscInt        *code   = a->code;
  const PetscReal  r      = mu / kt;
  const PetscBool  normal = Ve ? PETSC_TRUE : PETSC_FALSE;
  const PetscBool  wantJ  = (out->dFdU || out->dFdV || out->dNdV) ? PETSC_TRUE : PETSC_FALSE;
  PetscInt         j, k, t, nsep = 0, s = 0, jl = 0, jh = 0, anchor = 0; /* anchor for full stick: 0 none, 1 L, -1 U */
  PetscReal        w = 0.0, lo = PETSC_NINFINITY, hi = PETSC_INFINITY;
  PetscBool        fullstick = PETSC_FALSE, anyslip = PETSC_FALSE;

  /* synthesis u_j = B_j . U (and v_j), vectorised over samples */
  for (j = 0; j < N; j++) u[j] = Ue[0];
  for (k = 1; k < nc; k++) {
    const PetscReal  c   = Ue[k];
    const PetscReal *row = Bt + k * N;
    for (j = 0; j < N; j++) u[j] += c * row[j];
  }
  if (normal) {
    for (j = 0; j < N; j++) v[j] = Ve[0];
    for (k = 1; k < nc; k++) {
      const PetscReal  c   = Ve[k];
      const PetscReal *row = Bt + k * N;
      for (j = 0; j < N; j++) v[j] += c * row[j];
    }
    for (j = 0; j < N; j++) g[j] = n0 + kn * v[j];
  } else {
    for (j = 0; j < N; j++) g[j] = n0;
  }
  for (j = 0; j < N; j++) nsep += (g[j] <= 0.0);

  if (nsep == N) { /* full separation: no force at all */
    if (out->F) Zero(nc, out->F);
    if (out->N) Zero(nc, out->N);
    if (out->dFdU) Zero(nc * nc, out->dFdU);
    if (out->dFdV) Zero(nc * nc, out->dFdV);
    if (out->dNdV) Zero(nc * nc, out->dNdV);
    if (ftime) Zero(N, ftime);
    if (ntime) Zero(N, ntime);
    out->state = JR_CONTACT_FULL_SEPARATION;
    return;
  }

  /* where the periodic march starts, and in which state */
  if (nsep) {
    for (s = 0; s < N; s++) {
      PetscInt jp = s ? s - 1 : N - 1;
      if (g[s] > 0.0 && g[jp] <= 0.0) break;
    }
  } else {
    for (j = 0; j < N; j++) {
      const PetscReal L = u[j] - r * g[j], U = u[j] + r * g[j];
      if (L > lo) {
        lo = L;
        jl = j;
      }
      if (U < hi) {
        hi = U;
        jh = j;
      }
    }
    if (lo > hi) s = jl;
    else {
      fullstick = PETSC_TRUE;
      w         = 0.0;
      if (lo > 0.0) {
        w      = lo;
        anchor = 1;
      } else if (hi < 0.0) {
        w      = hi;
        anchor = -1;
      }
    }
  }

  if (fullstick) {
    for (j = 0; j < N; j++) f[j] = kt * (u[j] - w);
  } else {
    PetscBool prevsep = nsep ? PETSC_TRUE : PETSC_FALSE; /* the sample before s is separated */
    for (t = 0; t < N; t++) {
      PetscReal L, U, gj;
      j  = s + t;
      j  = j >= N ? j - N : j;
      gj = g[j];
      if (gj <= 0.0) {
        code[t] = JR_CODE_SEP;
        w       = u[j];
        f[j]    = 0.0;
        prevsep = PETSC_TRUE;
        continue;
      }
      L       = u[j] - r * gj;
      U       = u[j] + r * gj;
      code[t] = JR_CODE_STICK;
      if (prevsep) { /* first contact: slip at the interpolated contact point */
        PetscInt jp = j ? j - 1 : N - 1;
        lam[t]      = g[jp] / (g[jp] - gj);
        w           = u[jp] + lam[t] * (u[j] - u[jp]);
        code[t] |= JR_CODE_RECONTACT;
        prevsep = PETSC_FALSE;
      }
      if (t == 0 && !nsep) {
        w = L;
        code[t] |= JR_CODE_SLIPP;
      } else if (w < L) {
        w = L;
        code[t] |= JR_CODE_SLIPP;
      } else if (w > U) {
        w = U;
        code[t] |= JR_CODE_SLIPN;
      }
      f[j] = kt * (u[j] - w);
    }
  }

  /* DFT of the force (and of the normal load) */
  if (out->F) {
    for (k = 0; k < nc; k++) {
      const PetscReal *row = Bt + k * N;
      PetscReal        acc = 0.0;
      for (j = 0; j < N; j++) acc += f[j] * row[j];
      out->F[k] = wd[k] * acc;
    }
  }
  if (out->N) {
    if (normal) {
      for (k = 0; k < nc; k++) {
        const PetscReal *row = Bt + k * N;
        PetscReal        acc = 0.0;
        for (j = 0; j < N; j++) acc += PetscMax(g[j], 0.0) * row[j];
        out->N[k] = wd[k] * acc;
      }
    } else {
      Zero(nc, out->N);
      out->N[0] = n0;
    }
  }
  if (ftime)
    for (j = 0; j < N; j++) ftime[j] = f[j];
  if (ntime)
    for (j = 0; j < N; j++) ntime[j] = PetscMax(g[j], 0.0);

  /* contact state over the cycle */
  if (!fullstick)
    for (t = 0; t < N; t++)
      if ((code[t] & 3) == JR_CODE_SLIPP || (code[t] & 3) == JR_CODE_SLIPN) anyslip = PETSC_TRUE;
  out->state = nsep ? JR_CONTACT_SEPARATION_STICK_SLIP : (anyslip ? JR_CONTACT_STICK_SLIP : JR_CONTACT_FULL_STICK);

  if (!wantJ) return;
  {
    PetscReal *dFdU = out->dFdU, *dFdV = out->dFdV, *dNdV = out->dNdV;
    if (!dFdU) dFdU = a->DU;
    if (!dFdV) dFdV = a->DV;
    Zero(nc * nc, dFdU);
    Zero(nc * nc, dFdV);
    if (fullstick) {
      /* f_j = kt (u_j - w), w = 0 or an anchor at max L / min U: only the mean row sees the anchor */
      for (k = 0; k < nc; k++) dFdU[k * nc + k] = kt;
      if (anchor) {
        AnchorSlip(a, anchor > 0 ? jl : jh, anchor > 0 ? 1.0 : -1.0, r, kn, normal);
        for (k = 0; k < nc; k++) {
          dFdU[k] -= kt * a->dXU[k];
          dFdV[k] -= kt * a->dXV[k];
        }
      }
    } else {
      PetscInt t0 = 0;
      while (t0 < N) {
        const PetscInt c0 = code[t0] & 3;
        PetscInt       t1 = t0;
        while (t1 + 1 < N && (code[t1 + 1] & 3) == c0 && !(code[t1 + 1] & JR_CODE_RECONTACT)) t1++;
        if (c0 == JR_CODE_STICK) {
          /* anchor of this stick run: the sample before it in march order, or the contact point */
          if (code[t0] & JR_CODE_RECONTACT) {
            PetscInt  jc = s + t0, jp;
            PetscReal gp, gc, den, du;
            jc  = jc >= N ? jc - N : jc;
            jp  = jc ? jc - 1 : N - 1;
            gp  = g[jp];
            gc  = g[jc];
            den = gp - gc;
            du  = u[jc] - u[jp];
            for (k = 0; k < nc; k++) {
              a->dXU[k] = (1.0 - lam[t0]) * Bt[k * N + jp] + lam[t0] * Bt[k * N + jc];
              a->dXV[k] = normal ? du * kn * (gp * Bt[k * N + jc] - gc * Bt[k * N + jp]) / (den * den) : 0.0;
            }
          } else {
            const PetscInt ta = t0 - 1; /* t0 > 0: a stick run not at a contact follows a slip sample */
            PetscInt       ja = s + ta;
            ja                = ja >= N ? ja - N : ja;
            AnchorSlip(a, ja, (code[ta] & 3) == JR_CODE_SLIPP ? 1.0 : -1.0, r, kn, normal);
          }
          Interval(a, s, t0, t1, PETSC_TRUE);
          AddWG(nc, wd, kt, a->G, dFdU);
          AddWSx(nc, wd, -kt, a->S, a->dXU, dFdU);
          if (normal) AddWSx(nc, wd, -kt, a->S, a->dXV, dFdV);
        } else if (c0 != JR_CODE_SEP && normal) {
          Interval(a, s, t0, t1, PETSC_TRUE);
          AddWG(nc, wd, c0 == JR_CODE_SLIPP ? mu * kn : -mu * kn, a->G, dFdV);
        }
        t0 = t1 + 1;
      }
    }
    if (dNdV) {
      Zero(nc * nc, dNdV);
      if (normal) {
        for (k = 0; k < nc; k++) dNdV[k * nc + k] = kn;
        if (nsep) { /* dN/dV = kn W sum_contact B B^T = kn (I - W sum_separated B B^T) */
          PetscInt t0 = 0;
          while (t0 < N) {
            PetscInt t1 = t0;
            if ((code[t0] & 3) != JR_CODE_SEP) {
              t0++;
              continue;
            }
            while (t1 + 1 < N && (code[t1 + 1] & 3) == JR_CODE_SEP) t1++;
            Interval(a, s, t0, t1, PETSC_TRUE);
            AddWG(nc, wd, -kn, a->G, dNdV);
            t0 = t1 + 1;
          }
        }
      }
    }
  }
}
