/*
   JRHBM's autonomous system of the extended periodic motion concept (EPMC, Krack 2015): the harmonic balance of
   JRHBM without excitation and with a negative mass-proportional damping -xi M that makes the free motion of a
   damped structure periodic. Unknowns x = [a | w | xi] (n + 2): the harmonics a (the layout of JRHBM), the
   frequency w [rad/s] and xi [1/s]; equations (n + 2), per harmonic h >= 1 (and the mean as in JRHBM):
       R_s = (Km - (h w)^2 Mm) as - (gamma Kg + h w Cm) ac + xi h w Mm ac + Phi^T fN_s = 0
       R_c = (Km - (h w)^2 Mm) ac + (gamma Kg + h w Cm) as - xi h w Mm as + Phi^T fN_c = 0
   and the normalisation of the stuck mode of interest psi (M-normalised, in the basis) in the first harmonic:
       psi^T Mm as_1 = q   (its modal amplitude)      psi^T Mm ac_1 = 0   (its phase: x ~ q psi sin(w t))
   The damping ratio of the mode is D = xi / (2 w): for a linear mode, xi = psi^T (gamma Kg / w + Cm) psi.
*/
#include <jointrom/private/hbmimpl.h>

/*
  JRHBMSetEPMC - the harmonic balance becomes the EPMC's autonomous system of the k-th stuck mode of the basis (0-based
  in JRHBMStickFrequencies' order): no excitation, JRHBMComputeEPMC gives its residual and Jacobian. omega: the
  stuck mode's circular frequency [rad/s] (may be NULL). The EPMC's unknowns are the modal ones, which its
  normalisation needs: a reduced model condensed onto its joints by -hbm_condense auto goes back to them (the same
  equations; its later forced responses are not condensed either); -hbm_condense yes is an error. Collective.
*/
PetscErrorCode JRHBMSetEPMC(JRHBM h, PetscInt k, PetscReal *omega)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  if (h->cond) PetscCall(JRHBMCheckEPMC(h));
  if (h->cond) { /* back to the modal unknowns: the condensation's operators and the solver's sizes */
    const JRElements *el;
    h->condense = JR_HBM_CONDENSE_NO;
    PetscCall(JRHBMGetElements(h, &el));
    PetscCall(JRHBMCondenseSetUp(h, el));
    PetscCall(JRHBMSetUpSolver(h));
    PetscCall(PetscInfo(NULL, "EPMC: the reduced model's condensation onto its joints undone\n"));
  }
  PetscCheck(k >= 0 && k < h->nm, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "Nonlinear modes: stuck mode %" PetscInt_FMT " (0-based) of a basis of %" PetscInt_FMT, k, h->nm);
  PetscCall(PetscFree3(h->epsi, h->ep, h->ework));
  PetscCall(PetscMalloc3(h->nm, &h->epsi, h->nm, &h->ep, 2 * h->n + h->n * h->n, &h->ework));
  PetscCall(JRHBMStuckMode(h, k, &h->eomega, h->epsi));
  { /* a sign independent of LAPACK: the largest coefficient positive */
    PetscInt im = 0;
    for (PetscInt i = 1; i < h->nm; i++)
      if (PetscAbsReal(h->epsi[i]) > PetscAbsReal(h->epsi[im]) * (1 + 1e-12)) im = i;
    if (h->epsi[im] < 0)
      for (PetscInt i = 0; i < h->nm; i++) h->epsi[i] = -h->epsi[i];
  }
  for (PetscInt i = 0; i < h->nm; i++) {
    PetscReal s = 0;
    for (PetscInt j = 0; j < h->nm; j++) s += h->Mm[i * h->nm + j] * h->epsi[j];
    h->ep[i] = s;
  }
  h->epmc  = PETSC_TRUE;
  h->emode = k;
  if (omega) *omega = h->eomega;
  PetscFunctionReturn(0);
}

/*
  JRHBMCheckEPMC - whether the options read by JRHBMSetFromOptions allow the EPMC's system (JRHBMSetEPMC): an error
  naming the option if not (-hbm_condense yes), so that a run can fail before any work
*/
PetscErrorCode JRHBMCheckEPMC(JRHBM h)
{
  PetscFunctionBeginUser;
  PetscCheck(h->condense != JR_HBM_CONDENSE_YES, h->comm, PETSC_ERR_ARG_INCOMP, "-hbm_condense yes: nonlinear modes (EPMC) need the modal unknowns, not the joints' motions; leave -hbm_condense auto (or no)");
  PetscFunctionReturn(0);
}

/*
  JRHBMGetEPMCMode - the stuck mode of interest of JRHBMSetEPMC: its circular frequency [rad/s] and its coefficients
  in the basis (nm, M-normalised; may be NULL), and the linear equivalent viscous damping of the mode
  xi0 = psi^T (gamma Kg / omega + Cm) psi [1/s] (the EPMC's xi in the limit of a small amplitude without slip)
*/
PetscErrorCode JRHBMGetEPMCMode(JRHBM h, PetscReal *omega, const PetscReal **psi, PetscReal *xi0)
{
  PetscFunctionBeginUser;
  PetscCheck(h->epmc, h->comm, PETSC_ERR_ARG_WRONGSTATE, "JRHBMSetEPMC() first");
  if (omega) *omega = h->eomega;
  if (psi) *psi = h->epsi;
  if (xi0) {
    PetscReal s = 0;
    for (PetscInt i = 0; i < h->nm; i++)
      for (PetscInt j = 0; j < h->nm; j++) s += h->epsi[i] * (h->gamma * h->Kg[i * h->nm + j] / h->eomega + h->Cm[i * h->nm + j]) * h->epsi[j];
    *xi0 = s;
  }
  PetscFunctionReturn(0);
}

/*
  JRHBMComputeEPMC - the EPMC residual R (n + 2) at x = [a | w | xi] for the modal amplitude q and, if J is not NULL,
  its Jacobian dR/dx (dense (n + 2) x (n + 2), sequential). The elements' forces and derivatives are JRHBM's (split
  across the ranks, summed): every rank gets the same numbers. Collective.
*/
PetscErrorCode JRHBMComputeEPMC(JRHBM h, PetscReal q, Vec x, Vec R, Mat J)
{
  const PetscInt     nm = h->nm, n = h->n, N = n + 2;
  const PetscScalar *xa;
  PetscScalar       *r, *j = NULL;
  PetscReal         *res = h->ework, *jac = h->ework + n, *dw = h->ework + n + n * n, w, xi;

  PetscFunctionBeginUser;
  PetscCheck(h->epmc, h->comm, PETSC_ERR_ARG_WRONGSTATE, "JRHBMSetEPMC() first");
  PetscCall(VecGetArrayRead(x, &xa));
  w  = PetscRealPart(xa[n]);
  xi = PetscRealPart(xa[n + 1]);
  PetscCall(JRHBMNonlinear(h, xa, res, J ? jac : NULL));
  PetscCall(JRHBMLinear(h, w, xa, res, J ? jac : NULL, J ? dw : NULL));
  PetscCall(VecGetArray(R, &r));
  if (J) {
    PetscCall(MatDenseGetArrayWrite(J, &j));
    PetscCall(PetscArrayzero(j, N * N));
    for (PetscInt c = 0; c < n; c++) PetscCall(PetscArraycpy(j + c * N, jac + c * n, n));
  }
  for (PetscInt hh = 1; hh <= h->H; hh++) { /* the negative mass-proportional damping -xi Mm */
    const PetscInt   os = (2 * hh - 1) * nm, oc = 2 * hh * nm;
    const PetscReal  hw = hh * w;
    const PetscReal *as = xa + os, *ac = xa + oc;
    for (PetscInt i = 0; i < nm; i++) {
      PetscReal ms = 0, mc = 0;
      for (PetscInt k = 0; k < nm; k++) {
        const PetscReal mik = h->Mm[i * nm + k];
        ms += mik * as[k];
        mc += mik * ac[k];
        if (J) {
          j[(os + i) + (oc + k) * N] += xi * hw * mik;
          j[(oc + i) + (os + k) * N] -= xi * hw * mik;
        }
      }
      res[os + i] += xi * hw * mc;
      res[oc + i] -= xi * hw * ms;
      if (J) {
        j[(os + i) + n * N]       = dw[os + i] + xi * hh * mc;
        j[(oc + i) + n * N]       = dw[oc + i] - xi * hh * ms;
        j[(os + i) + (n + 1) * N] = hw * mc;
        j[(oc + i) + (n + 1) * N] = -hw * ms;
      }
    }
  }
  PetscCall(PetscArraycpy(r, res, n));
  { /* the normalisation: psi^T Mm as_1 = q, psi^T Mm ac_1 = 0 */
    PetscReal ps = 0, pc = 0;
    for (PetscInt i = 0; i < nm; i++) {
      ps += h->ep[i] * xa[nm + i];
      pc += h->ep[i] * xa[2 * nm + i];
      if (J) {
        j[n + (nm + i) * N]           = h->ep[i];
        j[(n + 1) + (2 * nm + i) * N] = h->ep[i];
      }
    }
    r[n]     = ps - q;
    r[n + 1] = pc;
  }
  PetscCall(VecRestoreArray(R, &r));
  PetscCall(VecRestoreArrayRead(x, &xa));
  if (J) {
    PetscCall(MatDenseRestoreArrayWrite(J, &j));
    PetscCall(JRMatDenseAssemble(J));
  }
  PetscFunctionReturn(0);
}

/*
  JRHBMEPMCWork - the work per cycle [J] that the negative damping -xi Mm puts into the motion a (n) at frequency w:
  the integral of xi v^T Mm v over a cycle, pi xi w sum_h h^2 (as^T Mm as + ac^T Mm ac); at a solution it equals the
  energy the structure's damping and the elements dissipate (JRHBMEnergy)
*/
PetscErrorCode JRHBMEPMCWork(JRHBM h, PetscReal w, PetscReal xi, Vec a, PetscReal *W)
{
  const PetscInt     nm = h->nm;
  const PetscScalar *x;
  PetscReal          s = 0;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(a, &x));
  for (PetscInt hh = 1; hh <= h->H; hh++)
    for (PetscInt b = 2 * hh - 1; b <= 2 * hh; b++) {
      const PetscScalar *ab = x + b * nm;
      for (PetscInt i = 0; i < nm; i++)
        for (PetscInt j = 0; j < nm; j++) s += hh * hh * PetscRealPart(ab[i]) * h->Mm[i * nm + j] * PetscRealPart(ab[j]);
    }
  PetscCall(VecRestoreArrayRead(a, &x));
  *W = PETSC_PI * xi * w * s;
  PetscFunctionReturn(0);
}
