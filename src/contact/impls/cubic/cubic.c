/*
   cubic: a nonlinear spring f = kt u^3 (kt [N/m^3], either sign: hardening or softening), so that the
   solver and the continuation can be checked on Duffing-type folds with a known answer.
   Single harmonic, closed form: with u = U0 + Us sin + Uc cos and A^2 = Us^2 + Uc^2,
       F0 = kt (U0^3 + 3/2 U0 A^2),   (Fs, Fc) = kt (3 U0^2 + 3/4 A^2) (Us, Uc).
   H harmonics: sampled at Ns = max(N, 4H+1) points per cycle, which makes the harmonics up to H of
   u^3 and of its derivative 3 kt u^2 exact (no aliasing).
*/
#include <jointrom/private/contactimpl.h>

typedef struct {
  JRAFT *tab; /* basis tables at Ns = max(N, 4H+1) samples */
} Contact_Cubic;

static void CubicAnalytic(PetscReal kt, const PetscReal U[3], JRElementOut *out)
{
  const PetscReal U0 = U[0], Us = U[1], Uc = U[2], A2 = Us * Us + Uc * Uc, g = 3.0 * U0 * U0 + 0.75 * A2;

  if (out->F) {
    out->F[0] = kt * (U0 * U0 * U0 + 1.5 * U0 * A2);
    out->F[1] = kt * g * Us;
    out->F[2] = kt * g * Uc;
  }
  if (out->dFdU) {
    PetscReal *D = out->dFdU;
    D[0]         = kt * (3.0 * U0 * U0 + 1.5 * A2);
    D[1]         = 3.0 * kt * U0 * Us;
    D[2]         = 3.0 * kt * U0 * Uc;
    D[3]         = 6.0 * kt * U0 * Us;
    D[4]         = kt * (g + 1.5 * Us * Us);
    D[5]         = 1.5 * kt * Us * Uc;
    D[6]         = 6.0 * kt * U0 * Uc;
    D[7]         = 1.5 * kt * Us * Uc;
    D[8]         = kt * (g + 1.5 * Uc * Uc);
  }
}

static void CubicSampled(JRAFT *a, PetscReal kt, const PetscReal U[], JRElementOut *out)
{
  const PetscInt   N = a->N, nc = a->nc;
  const PetscReal *Bt = a->Bt;
  PetscReal       *u = a->u, *f = a->f, *g = a->g;

  for (PetscInt j = 0; j < N; j++) u[j] = U[0];
  for (PetscInt k = 1; k < nc; k++)
    for (PetscInt j = 0; j < N; j++) u[j] += U[k] * Bt[k * N + j];
  for (PetscInt j = 0; j < N; j++) {
    f[j] = kt * u[j] * u[j] * u[j];
    g[j] = 3.0 * kt * u[j] * u[j];
  }
  if (out->F)
    for (PetscInt k = 0; k < nc; k++) {
      PetscReal s = 0.0;
      for (PetscInt j = 0; j < N; j++) s += f[j] * Bt[k * N + j];
      out->F[k] = a->wdft[k] * s;
    }
  if (out->dFdU)
    for (PetscInt k = 0; k < nc; k++)
      for (PetscInt m = 0; m < nc; m++) {
        PetscReal s = 0.0;
        for (PetscInt j = 0; j < N; j++) s += g[j] * Bt[k * N + j] * Bt[m * N + j];
        out->dFdU[k * nc + m] = a->wdft[k] * s;
      }
}

static PetscErrorCode JRContactElement_Cubic(JRContact c, PetscInt e, const PetscReal Ue[], const PetscReal Ve[], JRElementOut *out)
{
  Contact_Cubic *cu = (Contact_Cubic *)c->data;
  const PetscInt nc = c->nc;

  PetscFunctionBeginUser;
  (void)Ve;
  if (c->method == JR_CONTACT_ANALYTIC) CubicAnalytic(c->kt[e], Ue, out);
  else CubicSampled(cu->tab, c->kt[e], Ue, out);
  if (out->N)
    for (PetscInt k = 0; k < nc; k++) out->N[k] = 0.0;
  for (PetscInt k = 0; k < nc * nc; k++) {
    if (out->dFdV) out->dFdV[k] = 0.0;
    if (out->dNdV) out->dNdV[k] = 0.0;
  }
  out->state = JR_CONTACT_FULL_STICK; /* an elastic spring: never slips nor separates */
  PetscFunctionReturn(0);
}

static PetscErrorCode JRContactEvaluate_Cubic(JRContact c, PetscInt start, PetscInt end, const PetscReal U[], const PetscReal V[], PetscReal F[], PetscReal N[], PetscReal dFdU[], PetscReal dFdV[], PetscReal dNdV[], JRContactState state[])
{
  PetscFunctionBeginUser;
  PetscCall(JRContactEvaluateChunked(c, start, end, U, V, F, N, dFdU, dFdV, dNdV, state));
  PetscFunctionReturn(0);
}

static PetscErrorCode JRContactSetUp_Cubic(JRContact c)
{
  Contact_Cubic *cu = (Contact_Cubic *)c->data;

  PetscFunctionBeginUser;
  PetscCall(JRAFTDestroy(&cu->tab));
  if (c->method == JR_CONTACT_AFT) PetscCall(JRAFTCreate(c->H, PetscMax(c->N, 4 * c->H + 1), &cu->tab));
  PetscFunctionReturn(0);
}

static PetscErrorCode JRContactDestroy_Cubic(JRContact c)
{
  Contact_Cubic *cu = (Contact_Cubic *)c->data;

  PetscFunctionBeginUser;
  PetscCall(JRAFTDestroy(&cu->tab));
  PetscCall(PetscFree(c->data));
  PetscFunctionReturn(0);
}

PetscErrorCode JRContactCreate_Cubic(JRContact c)
{
  Contact_Cubic *cu;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&cu));
  c->data          = cu;
  c->normal        = PETSC_FALSE;
  c->signed_kt     = PETSC_TRUE;
  c->ops->evaluate = JRContactEvaluate_Cubic;
  c->ops->element  = JRContactElement_Cubic;
  c->ops->setup    = JRContactSetUp_Cubic;
  c->ops->destroy  = JRContactDestroy_Cubic;
  PetscFunctionReturn(0);
}
