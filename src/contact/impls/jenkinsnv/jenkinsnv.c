/*
   jenkins_nv: 1D dry friction element with normal load variation (thesis 3.3, eqs 3.31-3.84).
   Tangential stiffness kt = k_u [N/m], normal stiffness kn = k_v [N/m], friction coefficient mu,
   initial normal load n0 [N] (negative for an initial gap, n0 = N_static - kv v_gap (5.1)).
   f = kt (u - w), n = max(0, n0 + kn v) (3.32), |f| <= mu n; stick, positive and negative slip,
   separation.

   Single harmonic, closed form. With u = U0 + Us sin + Uc cos, v = V0 + Vs sin + Vc cos, the
   stick band of the slip w is  L(theta) <= w <= U(theta),  L, U = u -+ (mu/kt)(n0 + kn v), both
   sinusoids while in contact. Every transition of the thesis is then a root of
   a0 + as sin(theta) + ac cos(theta) = level:
     positive slip -> stick at the maximum of L      (theta_E^P, 3.44-3.45, 3.59)
     negative slip -> stick at the minimum of U      (theta_E^N, 3.46-3.47, 3.60)
     stick -> negative slip when U falls to w        (P_theta_N^E, 3.39-3.40, 3.63-3.66)
     stick -> positive slip when L rises to w        (N_theta_P^E, 3.37-3.38, 3.67-3.70)
     contact -> separation when n0 + kn v = 0, v' < 0 (theta_S^*, 3.41-3.42, 3.71-3.73)
     separation -> contact when n0 + kn v = 0, v' > 0 (theta_*^S, 3.48-3.49, 3.74); the state after
       contact is positive slip, negative slip or stick by (3.53)-(3.55), i.e. by the signs of L', U'
       (S_theta_P^E and S_theta_N^E, 3.75-3.82, are then the stick -> slip roots above).
   The cycle is marched from an angle whose state is known (the end of separation; else the
   maximum of L, where positive slip ends; else the element sticks all cycle), which yields one
   of the 13 sequences of 3.3 / Table 3.2. On each segment the force is alpha + beta sin + gamma cos,
   so the Fourier integrals (2.10)-(2.11) are closed form.
   Derivatives: f is continuous at every transition, so the moving limits contribute nothing and
   only the segment formulas are differentiated; a stick segment's slip w comes from its anchor:
   the extremum of L or U (whose angle derivative vanishes because L' = 0 there) or the contact
   point u(theta_c), whose angle moves with v: d theta_c = -dg/g'(theta_c).
*/
#include <jointrom/private/contactimpl.h>

#define NV_MAXSEG      32
#define NV_TOL_ANGLE   1e-12 /* events closer than this to the current angle are the current one */
#define NV_TOL_END     1e-9  /* events this close to the end of the cycle close it */
#define NV_TOL_TANGENT 1e-12 /* |q| above 1 - this: the sinusoid only touches the level */
#define TWO_PI         (2.0 * PETSC_PI)

typedef struct {
  PetscReal a0, as, ac, R, psi; /* a0 + as sin + ac cos = a0 + R sin(theta + psi) */
} Sinus;

typedef struct {
  char      type;   /* 'E' stick, 'P' positive slip, 'N' negative slip, 'S' separated */
  PetscReal a, b;   /* angles */
  PetscReal sa, ca; /* sin(a), cos(a): each transition angle's sine and cosine are computed once */
  PetscReal W, dW[6];
} Segment;

typedef struct {
  PetscReal kt, kn, mu, n0, r, c; /* r = mu/kt, c = mu kn/kt */
  PetscReal U[3], V[3];
  Sinus     g, L, Up;
  PetscBool sep;
  PetscInt  nseg;
  Segment   seg[NV_MAXSEG];
} NVCycle;

static inline void SinusSet(Sinus *s, PetscReal a0, PetscReal as, PetscReal ac)
{
  s->a0  = a0;
  s->as  = as;
  s->ac  = ac;
  s->R   = PetscSqrtReal(as * as + ac * ac);
  s->psi = PetscAtan2Real(ac, as);
}

/* derivative of the sinusoid at an angle given by its sine sn and cosine cs */
static inline PetscReal SinusDeriv(const Sinus *s, PetscReal sn, PetscReal cs)
{
  return s->as * cs - s->ac * sn;
}

/* phi + 2 pi k, the first such angle after th */
static inline PetscReal NextAfter(PetscReal phi, PetscReal th)
{
  return phi + TWO_PI * PetscCeilReal((th + NV_TOL_ANGLE - phi) / TWO_PI);
}

/* first angle after th where s crosses level upward (dir > 0) or downward (dir < 0) */
static inline PetscReal SinusCross(const Sinus *s, PetscReal level, int dir, PetscReal th)
{
  PetscReal q;
  if (!(s->R > 0.0)) return PETSC_INFINITY;
  q = (level - s->a0) / s->R;
  if (q <= -1.0 + NV_TOL_TANGENT || q >= 1.0 - NV_TOL_TANGENT) return PETSC_INFINITY;
  return NextAfter((dir > 0 ? PetscAsinReal(q) : PETSC_PI - PetscAsinReal(q)) - s->psi, th);
}

static inline PetscReal SinusMaxAfter(const Sinus *s, PetscReal th)
{
  if (!(s->R > 0.0)) return PETSC_INFINITY;
  return NextAfter(0.5 * PETSC_PI - s->psi, th);
}

static inline PetscReal SinusMinAfter(const Sinus *s, PetscReal th)
{
  if (!(s->R > 0.0)) return PETSC_INFINITY;
  return NextAfter(-0.5 * PETSC_PI - s->psi, th);
}

/* slip anchored at the extremum of L (sgn = +1) or U (sgn = -1) at the angle with sine s, cosine co:
   W = U0 -+ r n0 -+ c V0 + (Us -+ c Vs) sin + (Uc -+ c Vc) cos; dW over (U0,Us,Uc,V0,Vs,Vc) */
static inline void AnchorBand(const NVCycle *m, PetscReal sgn, PetscReal s, PetscReal co, PetscReal *W, PetscReal dW[6])
{
  const Sinus *b = sgn > 0 ? &m->L : &m->Up;
  *W                = b->a0 + b->as * s + b->ac * co;
  dW[0]             = 1.0;
  dW[1]             = s;
  dW[2]             = co;
  dW[3]             = -sgn * m->c;
  dW[4]             = -sgn * m->c * s;
  dW[5]             = -sgn * m->c * co;
}

/* slip anchored at the contact point: W = u(theta_c), theta_c moves with v (g(theta_c) = 0) */
static inline void AnchorContact(const NVCycle *m, PetscReal s, PetscReal co, PetscReal *W, PetscReal dW[6])
{
  const PetscReal up = m->U[1] * co - m->U[2] * s;                /* u'(theta_c) */
  const PetscReal gp = m->kn * (m->V[1] * co - m->V[2] * s);      /* g'(theta_c) > 0 */
  const PetscReal q  = gp > 0.0 ? -up * m->kn / gp : 0.0;         /* u' dtheta_c/dg-part */
  *W                 = m->U[0] + m->U[1] * s + m->U[2] * co;
  dW[0]              = 1.0;
  dW[1]              = s;
  dW[2]              = co;
  dW[3]              = q;
  dW[4]              = q * s;
  dW[5]              = q * co;
}

static inline void ZeroDW(PetscReal dW[6])
{
  for (int i = 0; i < 6; i++) dW[i] = 0.0;
}

/* state right after contact at th (3.53)-(3.55) */
static inline char ContactEntry(const NVCycle *m, PetscReal s, PetscReal co, PetscReal *W, PetscReal dW[6])
{
  if (SinusDeriv(&m->L, s, co) > 0.0) return 'P';
  if (SinusDeriv(&m->Up, s, co) < 0.0) return 'N';
  AnchorContact(m, s, co, W, dW);
  return 'E';
}

/* march one cycle from th0 in the given state; returns nonzero if the segment table overflows */
static int March(NVCycle *m, PetscReal th0, PetscReal s0, PetscReal c0, char state, PetscReal W, const PetscReal dW0[6])
{
  const PetscReal end = th0 + TWO_PI;
  PetscReal       th = th0, sth = s0, cth = c0, dW[6];

  for (int i = 0; i < 6; i++) dW[i] = dW0[i];
  m->nseg = 0;
  while (1) {
    PetscReal t = PETSC_INFINITY, tS = PETSC_INFINITY;
    char      next = 0;
    Segment  *sg;
    if (m->sep && state != 'S') tS = SinusCross(&m->g, 0.0, -1, th);
    switch (state) {
    case 'E': {
      const PetscReal tP = SinusCross(&m->L, W, +1, th), tN = SinusCross(&m->Up, W, -1, th);
      t    = PetscMin(tP, tN);
      next = tP <= tN ? 'P' : 'N';
    } break;
    case 'P':
      t    = SinusMaxAfter(&m->L, th);
      next = 'E';
      break;
    case 'N':
      t    = SinusMinAfter(&m->Up, th);
      next = 'E';
      break;
    case 'S':
      t    = SinusCross(&m->g, 0.0, +1, th);
      next = 'C';
      break;
    }
    if (tS <= t) {
      t    = tS;
      next = 'S';
    }
    if (t > end - NV_TOL_END) t = end;
    if (m->nseg == NV_MAXSEG) return 1;
    sg       = &m->seg[m->nseg++];
    sg->type = state;
    sg->a    = th;
    sg->b    = t;
    sg->sa   = sth;
    sg->ca   = cth;
    sg->W    = W;
    for (int i = 0; i < 6; i++) sg->dW[i] = dW[i];
    if (t == end) break;
    sth = PetscSinReal(t);
    cth = PetscCosReal(t);
    if (next == 'E') AnchorBand(m, state == 'P' ? 1.0 : -1.0, sth, cth, &W, dW);
    else if (next == 'C') next = ContactEntry(m, sth, cth, &W, dW);
    state = next;
    th    = t;
  }
  return 0;
}

/* Fourier integrals over the segments: F, N (3 each) and derivatives (3 x 6, row-major) */
static void Integrate(const NVCycle *m, PetscReal F[3], PetscReal Nf[3], PetscReal dF[18], PetscReal dN[18])
{
  const PetscReal kt = m->kt, kn = m->kn, mu = m->mu;
  const PetscReal i2pi = 0.5 / PETSC_PI, ipi = 1.0 / PETSC_PI;

  for (int i = 0; i < 3; i++) F[i] = Nf[i] = 0.0;
  for (int i = 0; i < 18; i++) dF[i] = dN[i] = 0.0;
  for (PetscInt k = 0; k < m->nseg; k++) {
    const Segment  *sg = &m->seg[k], *nx = &m->seg[k + 1 < m->nseg ? k + 1 : 0]; /* the cycle closes at a + 2 pi */
    const PetscReal a = sg->a, b = sg->b;
    const PetscReal sa = sg->sa, ca = sg->ca, sb = nx->sa, cb = nx->ca;
    const PetscReal I1 = b - a, Is = ca - cb, Ic = sb - sa, s2 = sb * cb - sa * ca;
    const PetscReal Iss = 0.5 * (I1 - s2), Icc = 0.5 * (I1 + s2), Isc = 0.5 * (sb * sb - sa * sa);
    /* integrals of {1, sin, cos} against {mean, sin, cos} with their normalisations */
    const PetscReal T[3][3] = {
      {i2pi * I1, i2pi * Is,  i2pi * Ic },
      {ipi * Is,  ipi * Iss,  ipi * Isc },
      {ipi * Ic,  ipi * Isc,  ipi * Icc }
    };
    PetscReal alpha, beta, gamma, sgn;
    if (sg->type == 'S') continue;
    /* normal load n = n0 + kn v in contact */
    alpha = m->n0 + kn * m->V[0];
    beta  = kn * m->V[1];
    gamma = kn * m->V[2];
    for (int i = 0; i < 3; i++) {
      Nf[i] += T[i][0] * alpha + T[i][1] * beta + T[i][2] * gamma;
      for (int p = 0; p < 3; p++) dN[i * 6 + 3 + p] += kn * T[i][p];
    }
    if (sg->type == 'E') { /* f = kt (u - W) */
      alpha = kt * (m->U[0] - sg->W);
      beta  = kt * m->U[1];
      gamma = kt * m->U[2];
      for (int i = 0; i < 3; i++) {
        F[i] += T[i][0] * alpha + T[i][1] * beta + T[i][2] * gamma;
        for (int p = 0; p < 6; p++) dF[i * 6 + p] -= kt * T[i][0] * sg->dW[p];
        for (int p = 0; p < 3; p++) dF[i * 6 + p] += kt * T[i][p];
      }
    } else { /* f = +-mu (n0 + kn v) */
      sgn   = sg->type == 'P' ? 1.0 : -1.0;
      alpha = sgn * mu * (m->n0 + kn * m->V[0]);
      beta  = sgn * mu * kn * m->V[1];
      gamma = sgn * mu * kn * m->V[2];
      for (int i = 0; i < 3; i++) {
        F[i] += T[i][0] * alpha + T[i][1] * beta + T[i][2] * gamma;
        for (int p = 0; p < 3; p++) dF[i * 6 + 3 + p] += sgn * mu * kn * T[i][p];
      }
    }
  }
}

static const struct {
  const char       *seq;
  JRContactSequence id;
} SeparationCases[] = {
  {"PENEPS", JR_SEQ_P1},
  {"PENS",   JR_SEQ_P2},
  {"PS",     JR_SEQ_P3},
  {"NEPENS", JR_SEQ_N1},
  {"NEPS",   JR_SEQ_N2},
  {"NS",     JR_SEQ_N3},
  {"EPENS",  JR_SEQ_E1},
  {"EPS",    JR_SEQ_E2},
  {"ENEPS",  JR_SEQ_E3},
  {"ENS",    JR_SEQ_E4}
};

int JRJenkinsNVAnalytic(PetscReal kt, PetscReal kn, PetscReal mu, PetscReal n0, const PetscReal Ue[], const PetscReal Ve[], JRElementOut *out, JRContactSequence *seq)
{
  NVCycle           m;
  PetscReal         F[3], Nf[3], dF[18], dN[18], dW[6], W = 0.0, G0, gmin, gmax;
  JRContactSequence sq = JR_SEQ_OTHER;
  char              str[NV_MAXSEG + 1];
  int               overflow = 0;

  m.kt = kt;
  m.kn = kn;
  m.mu = mu;
  m.n0 = n0;
  m.r  = mu / kt;
  m.c  = mu * kn / kt;
  for (int i = 0; i < 3; i++) {
    m.U[i] = Ue[i];
    m.V[i] = Ve[i];
  }
  G0 = n0 + kn * Ve[0];
  SinusSet(&m.g, G0, kn * Ve[1], kn * Ve[2]);
  SinusSet(&m.L, Ue[0] - m.r * G0, Ue[1] - m.c * Ve[1], Ue[2] - m.c * Ve[2]);
  SinusSet(&m.Up, Ue[0] + m.r * G0, Ue[1] + m.c * Ve[1], Ue[2] + m.c * Ve[2]);
  gmax  = G0 + m.g.R;
  gmin  = G0 - m.g.R;
  m.sep = gmin < 0.0 ? PETSC_TRUE : PETSC_FALSE;
  ZeroDW(dW);

  if (gmax <= 0.0) { /* full separation (3.83) */
    for (int i = 0; i < 3; i++) F[i] = Nf[i] = 0.0;
    for (int i = 0; i < 18; i++) dF[i] = dN[i] = 0.0;
    out->state = JR_CONTACT_FULL_SEPARATION;
    sq         = JR_SEQ_FULL_SEPARATION;
  } else if (m.sep) { /* separation (3.84): start at the end of separation theta_*^S */
    const PetscReal th0 = PetscAsinReal(-G0 / m.g.R) - m.g.psi, s0 = PetscSinReal(th0), c0 = PetscCosReal(th0);
    const char      st  = ContactEntry(&m, s0, c0, &W, dW);
    overflow            = March(&m, th0, s0, c0, st, W, dW);
    Integrate(&m, F, Nf, dF, dN);
    out->state = JR_CONTACT_SEPARATION_STICK_SLIP;
  } else {
    const PetscReal lo = m.L.a0 + m.L.R, hi = m.Up.a0 - m.Up.R;
    if (lo <= hi) { /* a stick-only cycle exists: full stick, slip at the band point nearest 0 */
      /* the maximum of L is at sin = cos(psi_L), cos = sin(psi_L); the minimum of U at minus those of psi_U */
      if (lo > 0.0) AnchorBand(&m, 1.0, m.L.as / m.L.R, m.L.ac / m.L.R, &W, dW);
      else if (hi < 0.0) AnchorBand(&m, -1.0, -m.Up.as / m.Up.R, -m.Up.ac / m.Up.R, &W, dW);
      m.nseg      = 1;
      m.seg[0].type = 'E';
      m.seg[0].a    = 0.0;
      m.seg[0].b    = TWO_PI;
      m.seg[0].sa   = 0.0;
      m.seg[0].ca   = 1.0;
      m.seg[0].W    = W;
      for (int i = 0; i < 6; i++) m.seg[0].dW[i] = dW[i];
      Integrate(&m, F, Nf, dF, dN);
      out->state = JR_CONTACT_FULL_STICK;
      sq         = JR_SEQ_FULL_STICK;
    } else { /* slip without separation: start where positive slip ends, theta_E^P (3.59) */
      const PetscReal th0 = 0.5 * PETSC_PI - m.L.psi, s0 = m.L.as / m.L.R, c0 = m.L.ac / m.L.R;
      AnchorBand(&m, 1.0, s0, c0, &W, dW);
      overflow = March(&m, th0, s0, c0, 'E', W, dW);
      Integrate(&m, F, Nf, dF, dN);
      out->state = JR_CONTACT_STICK_SLIP;
    }
  }
  if (sq == JR_SEQ_OTHER) {
    PetscInt k;
    for (k = 0; k < m.nseg; k++) str[k] = m.seg[k].type;
    str[k] = 0;
    if (m.sep) {
      for (size_t i = 0; i < sizeof(SeparationCases) / sizeof(SeparationCases[0]); i++)
        if (!strcmp(str, SeparationCases[i].seq)) sq = SeparationCases[i].id;
    } else if (!strcmp(str, "ENEP")) sq = JR_SEQ_SLIP_NO_SEPARATION;
  }
  if (seq) *seq = sq;
  for (int i = 0; i < 3; i++) {
    if (out->F) out->F[i] = F[i];
    if (out->N) out->N[i] = Nf[i];
    for (int p = 0; p < 3; p++) {
      if (out->dFdU) out->dFdU[i * 3 + p] = dF[i * 6 + p];
      if (out->dFdV) out->dFdV[i * 3 + p] = dF[i * 6 + 3 + p];
      if (out->dNdV) out->dNdV[i * 3 + p] = dN[i * 6 + 3 + p];
    }
  }
  return overflow;
}

static PetscErrorCode JRContactElement_JenkinsNV(JRContact c, PetscInt e, const PetscReal Ue[], const PetscReal Ve[], JRElementOut *out)
{
  PetscFunctionBeginUser;
  if (c->method == JR_CONTACT_ANALYTIC) {
    PetscCheck(!JRJenkinsNVAnalytic(c->kt[e], c->kn[e], c->mu[e], c->n0[e], Ue, Ve, out, NULL), PETSC_COMM_SELF, PETSC_ERR_PLIB, "jenkins_nv element %" PetscInt_FMT ": more than %d transitions in one cycle for u = (%g, %g, %g), v = (%g, %g, %g)", e, NV_MAXSEG, (double)Ue[0], (double)Ue[1], (double)Ue[2], (double)Ve[0], (double)Ve[1], (double)Ve[2]);
  } else JRAFTElement(c->aft, c->kt[e], c->kn[e], c->mu[e], c->n0[e], Ue, Ve, out, NULL, NULL);
  PetscFunctionReturn(0);
}

static PetscErrorCode JRContactEvaluate_JenkinsNV(JRContact c, PetscInt start, PetscInt end, const PetscReal U[], const PetscReal V[], PetscReal F[], PetscReal N[], PetscReal dFdU[], PetscReal dFdV[], PetscReal dNdV[], JRContactState state[])
{
  const PetscInt nc = c->nc;

  PetscFunctionBeginUser;
  PetscCall(JRContactEvaluateChunked(c, start, end, U, V, F, N, dFdU, dFdV, dNdV, state));
  if (c->method == JR_CONTACT_ANALYTIC) PetscCall(PetscLogFlops(600.0 * (end - start)));
  else PetscCall(PetscLogFlops((6.0 * nc * c->N + 10.0 * c->N + 16.0 * nc * nc) * (end - start)));
  PetscFunctionReturn(0);
}

PetscErrorCode JRContactCreate_JenkinsNV(JRContact c)
{
  PetscFunctionBeginUser;
  c->normal        = PETSC_TRUE;
  c->ops->evaluate = JRContactEvaluate_JenkinsNV;
  c->ops->element  = JRContactElement_JenkinsNV;
  PetscFunctionReturn(0);
}
