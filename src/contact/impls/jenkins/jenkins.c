/*
   jenkins: 1D dry friction element with constant normal load (thesis 3.2, eqs 3.1-3.30).
   Tangential stiffness kt [N/m], friction coefficient mu [-], normal load n0 [N]; u relative
   tangential displacement [m]; f = kt (u - w), |f| <= mu n0.

   Single harmonic, closed form. For u = U0 + Us sin(theta) + Uc cos(theta) = U0 + A sin(theta + phi)
   (3.28)-(3.30), with the slip force r = mu n0:
   - full stick when kt A <= r (3.20): f = kt (u - w0), w0 the point of the stick band
     [U0 + A - r/kt, U0 - A + r/kt] nearest to 0 (w0 = 0 for a motion without mean);
   - stick-slip otherwise: with rho = r/(kt A), cos(beta) = 1 - 2 rho (beta = theta_sn - pi/2,
     3.18), the integrals (3.23)-(3.24) of the piecewise force (3.19) give in the local frame
       fs = (kt A/pi) (beta - cos(beta) sin(beta)),   fc = (4 r/pi) (1 - rho),
     i.e. equivalent stiffness g1 = fs/A and damping g2 = fc/A, rotated back by phi (3.26)-(3.27):
       Fs = g1 Us - g2 Uc,   Fc = g1 Uc + g2 Us,   F0 = 0.
     The energy dissipated per cycle is pi A fc = 4 r (A - r/kt).
   Derivatives: dg1/dA = -4 kt rho sin(beta)/(pi A), dg2/dA = -4 kt rho cos(beta)/(pi A).
*/
#include <jointrom/private/contactimpl.h>

/* One element, single harmonic: F[3], D[9] = dF/dU row-major; returns the contact state */
static inline JRContactState JenkinsAnalytic(PetscReal kt, PetscReal mu, PetscReal n0, PetscReal U0, PetscReal Us, PetscReal Uc, PetscReal F[3], PetscReal D[9])
{
  const PetscReal r  = mu * n0;
  const PetscReal A2 = Us * Us + Uc * Uc, A = PetscSqrtReal(A2);

  if (n0 <= 0.0) {
    for (int i = 0; i < 3; i++) F[i] = 0.0;
    for (int i = 0; i < 9; i++) D[i] = 0.0;
    return JR_CONTACT_FULL_SEPARATION;
  }
  if (kt * A <= r) {
    const PetscReal lo = U0 + A - r / kt, hi = U0 - A + r / kt;
    PetscReal       w0 = 0.0, dA = 0.0; /* dF0/dA from the clamped band edge */
    if (lo > 0.0) {
      w0 = lo;
      dA = -kt;
    } else if (hi < 0.0) {
      w0 = hi;
      dA = kt;
    }
    F[0] = kt * (U0 - w0);
    F[1] = kt * Us;
    F[2] = kt * Uc;
    D[0] = w0 == 0.0 ? kt : 0.0;
    D[1] = A > 0.0 ? dA * Us / A : 0.0;
    D[2] = A > 0.0 ? dA * Uc / A : 0.0;
    D[3] = 0.0;
    D[4] = kt;
    D[5] = 0.0;
    D[6] = 0.0;
    D[7] = 0.0;
    D[8] = kt;
    return JR_CONTACT_FULL_STICK;
  } else {
    const PetscReal rho = r / (kt * A), cb = 1.0 - 2.0 * rho, beta = PetscAcosReal(cb);
    const PetscReal sb  = 2.0 * PetscSqrtReal(rho * (1.0 - rho)); /* sin(beta) */
    const PetscReal ipi = 1.0 / PETSC_PI;
    const PetscReal g1 = kt * ipi * (beta - cb * sb), g2 = 4.0 * kt * ipi * rho * (1.0 - rho);
    const PetscReal iA = 1.0 / A, g1p = -4.0 * kt * ipi * rho * sb * iA, g2p = -4.0 * kt * ipi * rho * cb * iA;
    const PetscReal cs = Us * iA, cc = Uc * iA;
    const PetscReal P = g1p * Us - g2p * Uc, Q = g1p * Uc + g2p * Us;
    F[0] = 0.0;
    F[1] = g1 * Us - g2 * Uc;
    F[2] = g1 * Uc + g2 * Us;
    D[0] = 0.0;
    D[1] = 0.0;
    D[2] = 0.0;
    D[3] = 0.0;
    D[4] = g1 + P * cs;
    D[5] = -g2 + P * cc;
    D[6] = 0.0;
    D[7] = g2 + Q * cs;
    D[8] = g1 + Q * cc;
    return JR_CONTACT_STICK_SLIP;
  }
}

/* Public single-element form, for joints and tests */
void JRJenkinsAnalytic(PetscReal kt, PetscReal mu, PetscReal n0, const PetscReal Ue[], JRElementOut *out)
{
  PetscReal F[3], D[9];

  out->state = JenkinsAnalytic(kt, mu, n0, Ue[0], Ue[1], Ue[2], F, D);
  for (int i = 0; i < 3; i++) {
    if (out->F) out->F[i] = F[i];
    if (out->N) out->N[i] = i == 0 ? PetscMax(n0, 0.0) : 0.0;
  }
  for (int i = 0; i < 9; i++) {
    if (out->dFdU) out->dFdU[i] = D[i];
    if (out->dFdV) out->dFdV[i] = 0.0;
    if (out->dNdV) out->dNdV[i] = 0.0;
  }
}

static PetscErrorCode JRContactEvaluate_Jenkins(JRContact c, PetscInt start, PetscInt end, const PetscReal U[], const PetscReal V[], PetscReal F[], PetscReal N[], PetscReal dFdU[], PetscReal dFdV[], PetscReal dNdV[], JRContactState state[])
{
  const PetscInt   n = c->n, nc = c->nc;
  const PetscReal *kt = c->kt, *mu = c->mu, *n0 = c->n0;
  PetscInt         e, k;

  PetscFunctionBeginUser;
  (void)V;
  if (c->method == JR_CONTACT_ANALYTIC) {
    for (e = start; e < end; e++) {
      PetscReal      Fe[3], De[9];
      JRContactState st = JenkinsAnalytic(kt[e], mu[e], n0[e], U[e], U[n + e], U[2 * n + e], Fe, De);
      if (F)
        for (k = 0; k < 3; k++) F[k * n + e] = Fe[k];
      if (dFdU)
        for (k = 0; k < 9; k++) dFdU[k * n + e] = De[k];
      if (state) state[e] = st;
    }
    PetscCall(PetscLogFlops(60.0 * (end - start)));
  } else {
    PetscCall(JRContactEvaluateChunked(c, start, end, U, NULL, F, NULL, dFdU, NULL, NULL, state));
    PetscCall(PetscLogFlops((4.0 * nc * c->N + 6.0 * c->N + 8.0 * nc * nc) * (end - start)));
  }
  /* constant normal load: N = n0, no dependence on v */
  if (N)
    for (e = start; e < end; e++) {
      N[e] = PetscMax(n0[e], 0.0);
      for (k = 1; k < nc; k++) N[k * n + e] = 0.0;
    }
  if (dFdV)
    for (k = 0; k < nc * nc; k++)
      for (e = start; e < end; e++) dFdV[k * n + e] = 0.0;
  if (dNdV)
    for (k = 0; k < nc * nc; k++)
      for (e = start; e < end; e++) dNdV[k * n + e] = 0.0;
  PetscFunctionReturn(0);
}

static PetscErrorCode JRContactElement_Jenkins(JRContact c, PetscInt e, const PetscReal Ue[], const PetscReal Ve[], JRElementOut *out)
{
  PetscFunctionBeginUser;
  (void)Ve;
  if (c->method == JR_CONTACT_ANALYTIC) JRJenkinsAnalytic(c->kt[e], c->mu[e], c->n0[e], Ue, out);
  else JRAFTElement(c->aft, c->kt[e], 0.0, c->mu[e], c->n0[e], Ue, NULL, out, NULL, NULL);
  PetscFunctionReturn(0);
}

PetscErrorCode JRContactCreate_Jenkins(JRContact c)
{
  PetscFunctionBeginUser;
  c->normal        = PETSC_FALSE;
  c->ops->evaluate = JRContactEvaluate_Jenkins;
  c->ops->element  = JRContactElement_Jenkins;
  PetscFunctionReturn(0);
}
