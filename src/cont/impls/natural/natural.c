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

/* Natural-parameter continuation over [wmin, wmax] at the current level */
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
    PetscReal wn = PetscMin(w + dw, c->wmax);
    if (c->wmax - wn < 1e-3 * dw) wn = c->wmax; /* do not leave a sliver at the end */
    PetscCall(VecCopy(a, guess));
    if (c->secant && b->np >= 2) PetscCall(VecAXPY(guess, (wn - w) / (w - wprev), aprev2)); /* aprev2 holds a_k - a_{k-1} */
    PetscCall(VecCopy(guess, aprev));
    PetscCall(JRHBMSolve(c->hbm, wn, aprev, &its, &conv));
    if (!conv) {
      b->retries++;
      dw *= 0.5;
      if (c->monitor) PetscCall(PetscPrintf(c->comm, "cont: level %" PetscInt_FMT " F %g N: Newton failed at %.6g Hz, retrying with step %.3g rad/s\n", lev + 1, (double)b->F, (double)(wn / (2 * PETSC_PI)), (double)dw));
      if (dw < dwmin) {
        PetscCall(PetscPrintf(c->comm, "cont: level %" PetscInt_FMT " F %g N: stopped at %.6g Hz, the step fell below %.3g rad/s (-cont_step_min); the curve ends there\n", lev + 1, (double)b->F, (double)(w / (2 * PETSC_PI)), (double)dwmin));
        break;
      }
      continue;
    }
    PetscCall(VecWAXPY(aprev2, -1.0, a, aprev));
    PetscCall(VecCopy(aprev, a));
    wprev = w;
    w     = wn;
    PetscCall(JRContBranchAdd(c, b, w, a, its, wn - wprev));
    PetscCall(JRContMonitor(c, lev, b));
    if (its <= c->target / 2) dw = PetscMin(1.5 * dw, dwmax);
    else if (its > c->target) dw = PetscMax(0.7 * dw, dwmin);
  }
  b->complete = w >= c->wmax ? PETSC_TRUE : PETSC_FALSE;
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
