/*
   -cont_type natural: natural-parameter continuation (thesis 2.4.2). Steps in frequency from the response of the
   stuck, linearised structure away from resonance; predictor: the previous solution, or the secant through the
   last two (-cont_predictor); Newton (the JRHBM SNES) at each frequency; the step grows when Newton converges fast
   and shrinks when it is slow (-cont_newton_target); a failed step is retried at half the step and reported.
   -cont_points N: N equally spaced frequencies instead, the step never growing beyond their spacing.
*/
#include <jointrom/private/contimpl.h>

/* The first step and its bounds [rad/s]: -cont_step, -cont_step_min, -cont_step_max, or by default 1/100, 1e-7 and
   1/10 of the range; -cont_points fixes the step at the spacing */
static void StepBounds(JRCont c, PetscReal *dw, PetscReal *dwmin, PetscReal *dwmax)
{
  const PetscReal range = c->wmax - c->wmin;

  *dw    = c->step0 > 0 ? c->step0 : range / 100;
  *dwmin = c->stepmin > 0 ? c->stepmin : 1e-7 * range;
  *dwmax = c->stepmax > 0 ? c->stepmax : range / 10;
  if (c->npoints > 1) { /* equally spaced: the step never grows beyond the spacing */
    *dw    = range / (c->npoints - 1);
    *dwmax = *dw;
  }
}

/* Natural-parameter continuation over [wmin, wmax] at the current level. A step is taken when Newton gives a solution
   (JRHBMSolveResidual) and, with the secant predictor, when linear interpolation from the last point is within
   -cont_interp_tol: the secant's error at the new point, h (h + h0) A''/2 for the steps h0 and h, is (4 (h + h0) / h)
   times the chord's h^2 A''/8; else it is retried shorter. */
static PetscErrorCode JRContSolveLevel_Natural(JRCont c, PetscInt lev, JRContBranch *b, Vec a)
{
  PetscReal dw, dwmin, dwmax, w = c->wmin, wprev = 0.0;
  Vec       aprev, aprev2, guess;
  PetscInt  its;
  PetscBool conv;

  PetscFunctionBeginUser;
  StepBounds(c, &dw, &dwmin, &dwmax);
  PetscCall(VecDuplicate(a, &aprev));
  PetscCall(VecDuplicate(a, &aprev2));
  PetscCall(VecDuplicate(a, &guess));
  PetscCall(JRContBranchStart(c, lev, b, a));
  while (w < c->wmax && b->np < c->maxpts) {
    PetscReal wn = PetscMin(w + dw, c->wmax), res, err = 0;
    PetscBool secant = c->secant && b->np >= 2 ? PETSC_TRUE : PETSC_FALSE;
    if (c->wmax - wn < 1e-3 * dw) wn = c->wmax; /* do not leave a sliver at the end */
    PetscCall(VecCopy(a, guess));
    if (secant) PetscCall(VecAXPY(guess, (wn - w) / (w - wprev), aprev2)); /* aprev2 holds a_k - a_{k-1} */
    PetscCall(VecCopy(guess, aprev));
    PetscCall(JRHBMSolveResidual(c->hbm, wn, aprev, &its, &conv, &res));
    if (conv && secant && c->itol > 0 && c->npoints == 0) {
      PetscReal Ag, As;
      PetscCall(JRContOutputAmplitude(c, wn, guess, 0, &Ag));
      PetscCall(JRContOutputAmplitude(c, wn, aprev, 0, &As));
      err = PetscAbsReal(Ag - As) / PetscMax(As, PETSC_MIN_REAL) * (wn - w) / (4 * (wn - wprev));
      if (err > 2 * c->itol && dw > dwmin) {
        b->retries++;
        dw = PetscMax(dwmin, dw * PetscMax(0.2, 0.8 * PetscSqrtReal(c->itol / err)));
        if (c->monitor > 1) PetscCall(JRContPrintf(c, "cont: level %" PetscInt_FMT " F %g N: interpolation error %.2e above -cont_interp_tol %.2e at %.6g Hz, retrying with step %.3g rad/s\n", lev + 1, (double)b->F, (double)err, (double)c->itol, (double)(wn / (2 * PETSC_PI)), (double)dw));
        continue;
      }
    }
    if (!conv) {
      b->retries++;
      dw *= 0.5;
      if (c->monitor) PetscCall(JRContPrintf(c, "cont: level %" PetscInt_FMT " F %g N: Newton failed at %.6g Hz (relative residual %.2e), retrying with step %.3g rad/s\n", lev + 1, (double)b->F, (double)(wn / (2 * PETSC_PI)), (double)res, (double)dw));
      if (dw < dwmin) {
        PetscCall(PetscSNPrintf(b->why, sizeof(b->why), "Newton found no solution after %.6g Hz with steps down to %.3g rad/s (-cont_step_min)", (double)(w / (2 * PETSC_PI)), (double)dwmin));
        PetscCall(JRContPrintf(c, "cont: level %" PetscInt_FMT " F %g N: stopped: %s\n", lev + 1, (double)b->F, b->why));
        break;
      }
      continue;
    }
    PetscCall(VecWAXPY(aprev2, -1.0, a, aprev));
    PetscCall(VecCopy(aprev, a));
    wprev = w;
    w     = wn;
    PetscCall(JRContBranchAdd(c, b, w, a, its, wn - wprev, res));
    PetscCall(JRContMonitor(c, lev, b));
    if (its <= c->target / 2) dw = PetscMin(1.5 * dw, dwmax);
    else if (its > c->target) dw = PetscMax(0.7 * dw, dwmin);
    if (err > 0) dw = PetscMax(dwmin, PetscMin(dw, (wn - wprev) * 0.9 * PetscSqrtReal(c->itol / err)));
  }
  b->complete = w >= c->wmax ? PETSC_TRUE : PETSC_FALSE;
  if (!b->complete && b->np >= c->maxpts) PetscCall(PetscSNPrintf(b->why, sizeof(b->why), "-cont_max_points %" PetscInt_FMT " reached before the end of the range", c->maxpts));
  PetscCall(VecDestroy(&aprev));
  PetscCall(VecDestroy(&aprev2));
  PetscCall(VecDestroy(&guess));
  PetscFunctionReturn(0);
}

PetscErrorCode JRContCreate_Natural(JRCont c)
{
  PetscFunctionBeginUser;
  c->ops->solvelevel = JRContSolveLevel_Natural;
  PetscFunctionReturn(0);
}
