/*
   -cont_type arclength: pseudo-arclength continuation (thesis 2.4.3). Unknowns x = (a, w); tangent predictor from
   the bordered system
       [ dR/da  dR/dw ] t = [0]
       [   t_prev^T   ]     [1]
   corrector: an SNES (the JRHBM's prefix, hbm_ by default) on the bordered system  R(a, w) = 0, g(a, w) = 0  with
   the pseudo-arclength constraint g = <x - x_pred, t> = 0 or the thesis's sphere (2.28) g = |x - x_k|^2 - ds^2
   (-cont_constraint sphere). Lengths are measured in scaled units, a / a_ref and w / (w_max - w_min), with a_ref
   the largest response of the linearised (stuck) structure over the range, raised to the largest response met
   along the curve, so that amplitudes and frequency weigh alike. Step control from the Newton iteration count and
   the turn of the plotted curve; turning points are passed; the last point lands exactly on the end of the range.
*/
#include <jointrom/private/contimpl.h>

const char *const JRContConstraints[] = {"pseudo", "sphere", "JRContConstraint", "JR_CONT_", NULL};

typedef struct {
  JRContConstraint constraint;
  SNES             snes;                    /* the corrector, on the bordered system */
  Mat              BJ, J;                   /* the bordered Jacobian ((n+1) x (n+1)); dR/da */
  Vec              a, r, Rw;                /* work, size n: the unknowns, R, dR/dw */
  Vec              G, xpred, xk, tk, d;     /* size n + 1: the bordered residual, the predictor, the last point and its tangent, work */
  PetscReal        aref, wref, ds, aunit;   /* aunit: the linearised response scale per unit level */
  PetscScalar     *tb;                      /* the tangent's bordered matrix ((n+1) x (n+1)), written for an LU only */
  JRContBordered   bj, tj;                  /* the corrector's and the tangent's bordered matrices by their products */
  PetscScalar     *brow, *trow;             /* their last rows (n + 1 each) */
  PetscBool        lazy;                    /* the corrector takes its Jacobian's products from bj: BJ written for an LU only */
  JRDenseLU        tlu;                     /* its solver: the corrector's, whose last factors are of a nearby matrix */
  PetscBool        towns;                   /* tlu is the tangent's own (the corrector is not newtondense) */
  PetscReal        dAk;                     /* d(amplitude at response 1)/d(scaled arclength) at x_k along t_k */
  PetscReal        Anew;                    /* the amplitude at response 1 of the candidate point */
  Vec              amodx;                   /* its modal unknowns (JRHBMExpand), kept for the branch if it is taken */
} JRCont_Arclength;

/* scaled inner product <x, y> over (a, w) */
static PetscErrorCode ScaledDot(JRCont c, Vec x, Vec y, PetscReal *d)
{
  JRCont_Arclength  *arc = (JRCont_Arclength *)c->data;
  const PetscScalar *u, *v;
  PetscReal          s = 0.0;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(x, &u));
  PetscCall(VecGetArrayRead(y, &v));
  for (PetscInt i = 0; i < c->n; i++) s += PetscRealPart(u[i] * v[i]) / (arc->aref * arc->aref);
  s += PetscRealPart(u[c->n] * v[c->n]) / (arc->wref * arc->wref);
  PetscCall(VecRestoreArrayRead(y, &v));
  PetscCall(VecRestoreArrayRead(x, &u));
  *d = s;
  PetscFunctionReturn(0);
}

/* split x = (a, w) into a (Vec of size n) and w */
static PetscErrorCode Split(JRCont c, Vec x, Vec a, PetscReal *w)
{
  const PetscScalar *u;
  PetscScalar       *v;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(x, &u));
  PetscCall(VecGetArray(a, &v));
  for (PetscInt i = 0; i < c->n; i++) v[i] = u[i];
  *w = PetscRealPart(u[c->n]);
  PetscCall(VecRestoreArray(a, &v));
  PetscCall(VecRestoreArrayRead(x, &u));
  PetscFunctionReturn(0);
}

/* join a and w into x = (a, w) */
static PetscErrorCode Join(JRCont c, Vec a, PetscReal w, Vec x)
{
  const PetscScalar *u;
  PetscScalar       *v;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(a, &u));
  PetscCall(VecGetArray(x, &v));
  for (PetscInt i = 0; i < c->n; i++) v[i] = u[i];
  v[c->n] = w;
  PetscCall(VecRestoreArray(x, &v));
  PetscCall(VecRestoreArrayRead(a, &u));
  PetscFunctionReturn(0);
}

/* bordered residual G(x) = [R(a, w); g(x)] */
static PetscErrorCode BorderedFunction(SNES snes, Vec x, Vec G, void *ctx)
{
  JRCont            c   = (JRCont)ctx;
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;
  PetscReal         w, g;
  Vec               d = arc->d;

  PetscFunctionBeginUser;
  (void)snes;
  PetscCall(Split(c, x, arc->a, &w));
  PetscCall(JRHBMComputeResidual(c->hbm, w, arc->a, arc->r));
  if (arc->constraint == JR_CONT_PSEUDO) {
    PetscCall(VecWAXPY(d, -1.0, arc->xpred, x));
    PetscCall(ScaledDot(c, d, arc->tk, &g));
  } else {
    PetscCall(VecWAXPY(d, -1.0, arc->xk, x));
    PetscCall(ScaledDot(c, d, d, &g));
    g -= arc->ds * arc->ds;
  }
  PetscCall(Join(c, arc->r, g, G));
  PetscFunctionReturn(0);
}

/* bordered Jacobian [J Rw; c^T d]: the point set, and the matrix written unless the corrector takes its products
   (arc->lazy) */
static PetscErrorCode BorderedJacobian(SNES snes, Vec x, Mat BJ, Mat P, void *ctx)
{
  JRCont             c   = (JRCont)ctx;
  JRCont_Arclength  *arc = (JRCont_Arclength *)c->data;
  PetscReal          w;
  const PetscScalar *t, *xx, *xk;
  const PetscInt     n = c->n;

  PetscFunctionBeginUser;
  (void)snes;
  (void)P;
  PetscCall(Split(c, x, arc->a, &w));
  PetscCall(JRHBMJacobianSetPoint(c->hbm, w, arc->a, arc->J, arc->Rw));
  PetscCall(VecGetArrayRead(arc->tk, &t));
  PetscCall(VecGetArrayRead(x, &xx));
  PetscCall(VecGetArrayRead(arc->xk, &xk));
  for (PetscInt col = 0; col < n; col++) arc->brow[col] = arc->constraint == JR_CONT_PSEUDO ? t[col] / (arc->aref * arc->aref) : 2.0 * (xx[col] - xk[col]) / (arc->aref * arc->aref);
  arc->brow[n] = arc->constraint == JR_CONT_PSEUDO ? t[n] / (arc->wref * arc->wref) : 2.0 * (xx[n] - xk[n]) / (arc->wref * arc->wref);
  PetscCall(VecRestoreArrayRead(arc->xk, &xk));
  PetscCall(VecRestoreArrayRead(x, &xx));
  PetscCall(VecRestoreArrayRead(arc->tk, &t));
  if (!arc->lazy) {
    PetscScalar *b;
    PetscCall(MatDenseGetArrayWrite(BJ, &b));
    PetscCall(JRContBorderedForm(&arc->bj, b, n + 1));
    PetscCall(MatDenseRestoreArrayWrite(BJ, &b));
    PetscCall(JRMatDenseAssemble(BJ));
  }
  PetscFunctionReturn(0);
}

/* unit (scaled) tangent at x: [J Rw; tprev^T W] t = [0; 1], oriented along tprev */
static PetscErrorCode Tangent(JRCont c, Vec x, Vec tprev, Vec t)
{
  JRCont_Arclength  *arc = (JRCont_Arclength *)c->data;
  PetscReal          w, nrm;
  const PetscInt     n = c->n, m = n + 1;
  const PetscScalar *tp;
  PetscScalar       *tt;
  PetscBool          singular;
  const JRDenseOp    op = {JRContBorderedMult, JRContBorderedForm, &arc->tj};

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(JR_ContTangent, 0, 0, 0, 0));
  PetscCall(Split(c, x, arc->a, &w));
  PetscCall(JRHBMJacobianSetPoint(c->hbm, w, arc->a, arc->J, arc->Rw));
  PetscCall(VecGetArrayRead(tprev, &tp));
  for (PetscInt col = 0; col < n; col++) arc->trow[col] = tp[col] / (arc->aref * arc->aref);
  arc->trow[n] = tp[n] / (arc->wref * arc->wref);
  PetscCall(VecRestoreArrayRead(tprev, &tp));
  PetscCall(VecZeroEntries(t));
  PetscCall(VecGetArray(t, &tt));
  tt[n] = 1.0;
  PetscCall(JRDenseLUSolveOp(arc->tlu, m, &op, arc->tb, m, 1e-8, tt, &singular)); /* a predictor's direction */
  PetscCall(VecRestoreArray(t, &tt));
  PetscCheck(!singular, PETSC_COMM_SELF, PETSC_ERR_MAT_LU_ZRPVT, "Continuation: the bordered tangent system is singular at %g Hz (a zero pivot)", (double)(w / (2 * PETSC_PI)));
  PetscCall(ScaledDot(c, t, t, &nrm));
  PetscCall(VecScale(t, 1.0 / PetscSqrtReal(nrm)));
  PetscCall(PetscLogEventEnd(JR_ContTangent, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* the response scale a_ref: the largest linearised response over the range */
static PetscErrorCode ResponseScale(JRCont c, PetscReal F, Vec a)
{
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;
  PetscReal         m   = 0.0, nrm;

  PetscFunctionBeginUser;
  if (arc->aunit <= 0 || F <= 0) { /* the linearised response is proportional to the level: sampled once, at 1 N (the
                                      same whichever level comes first: a level's curve does not depend on the others) */
    if (F > 0) PetscCall(JRHBMSetForceLevel(c->hbm, 1.0));
    for (PetscInt k = 0; k <= 64; k++) {
      const PetscReal w = c->wmin + (c->wmax - c->wmin) * k / 64.0;
      PetscCall(JRHBMLinearSolution(c->hbm, w, a));
      PetscCall(VecNorm(a, NORM_2, &nrm));
      m = PetscMax(m, nrm);
    }
    if (F > 0) {
      PetscCall(JRHBMSetForceLevel(c->hbm, F));
      arc->aunit = m;
    }
  }
  if (F > 0) m = arc->aunit * F;
  arc->aref = m > 0 ? m : 1.0;
  arc->wref = c->wmax - c->wmin;
  PetscFunctionReturn(0);
}

/* The first point of the curve (into a and x_k) and its tangent t_k, along increasing frequency; tnew: work */
static PetscErrorCode Start(JRCont c, PetscInt lev, JRContBranch *b, Vec a, Vec tnew)
{
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;

  PetscFunctionBeginUser;
  PetscCall(JRContBranchStart(c, lev, b, a));
  PetscCall(Join(c, a, c->wmin, arc->xk));
  PetscCall(VecZeroEntries(arc->tk));
  PetscCall(VecSetValue(arc->tk, c->n, 1.0, INSERT_VALUES)); /* start along increasing frequency */
  PetscCall(VecAssemblyBegin(arc->tk));
  PetscCall(VecAssemblyEnd(arc->tk));
  PetscCall(Tangent(c, arc->xk, arc->tk, tnew));
  PetscCall(VecCopy(tnew, arc->tk));
  PetscFunctionReturn(0);
}

/* The harmonic-balance part of the corrector's last residual, relative (JRHBMResidualNorm) */
static PetscErrorCode CorrectorResidual(JRCont c, PetscReal *rel)
{
  JRCont_Arclength  *arc = (JRCont_Arclength *)c->data;
  Vec                G;
  const PetscScalar *g;
  PetscScalar       *r;

  PetscFunctionBeginUser;
  PetscCall(SNESGetFunction(arc->snes, &G, NULL, NULL));
  PetscCall(VecGetArrayRead(G, &g));
  PetscCall(VecGetArray(arc->r, &r));
  for (PetscInt i = 0; i < c->n; i++) r[i] = g[i];
  PetscCall(VecRestoreArray(arc->r, &r));
  PetscCall(VecRestoreArrayRead(G, &g));
  PetscCall(JRHBMResidualNorm(c->hbm, arc->r, rel));
  PetscFunctionReturn(0);
}

/* Predictor x_k + ds t_k and corrector (Newton on the bordered system with the step ds): the new point x. It is a
   solution (*ok) only if the SNES converged and the residual meets -hbm_residual_tol: a Newton that stalls on its step
   test away from the curve is not one; a converged stop above the tolerance gets one more solve from where it is. */
static PetscErrorCode Correct(JRCont c, PetscReal ds, Vec x, PetscInt *its, SNESConvergedReason *reason, PetscReal *rel, PetscBool *ok)
{
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;
  PetscReal         tol;
  PetscInt          it;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetResidualTolerance(c->hbm, &tol));
  arc->ds = ds;
  *its    = 0;
  *rel    = PETSC_INFINITY;
  PetscCall(VecWAXPY(arc->xpred, ds, arc->tk, arc->xk));
  PetscCall(VecCopy(arc->xpred, x));
  PetscCall(PetscLogEventBegin(JR_ContStep, 0, 0, 0, 0));
  for (PetscInt pass = 0; pass < 2; pass++) {
    PetscCall(SNESSolve(arc->snes, NULL, x));
    PetscCall(SNESGetConvergedReason(arc->snes, reason));
    PetscCall(SNESGetIterationNumber(arc->snes, &it));
    *its += it;
    if (*reason <= 0) break;
    PetscCall(CorrectorResidual(c, rel));
    if (*rel <= tol) break;
  }
  PetscCall(PetscLogEventEnd(JR_ContStep, 0, 0, 0, 0));
  *ok = *reason > 0 && *rel <= tol ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* d(amplitude at response 1)/d(scaled arclength) at x along the unit tangent t, by a difference of 1e-7 */
static PetscErrorCode AmplitudeSlope(JRCont c, Vec x, Vec t, PetscReal A, PetscReal *dA)
{
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;
  const PetscReal   eps = 1e-7;
  PetscReal         w, Ae;

  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(arc->d, eps, t, x));
  PetscCall(Split(c, arc->d, arc->a, &w));
  PetscCall(JRContOutputAmplitude(c, w, arc->a, 0, &Ae));
  *dA = (Ae - A) / eps;
  PetscFunctionReturn(0);
}

/* The linear interpolation error between x_k and x (its tangent tnew, its amplitude A) for the step ds */
static PetscErrorCode StepError(JRCont c, JRContBranch *b, Vec x, Vec tnew, PetscReal ds, PetscReal *err, PetscReal *dA)
{
  JRCont_Arclength  *arc = (JRCont_Arclength *)c->data;
  const PetscInt     k   = b->np - 1;
  const PetscScalar *t0, *t1;
  PetscReal          w, A, L;

  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(arc->d, -1.0, arc->xk, x)); /* the parameter's length between the points: the chord, which exceeds ds where the corrector went far */
  PetscCall(ScaledDot(c, arc->d, arc->d, &L));
  L = PetscMax(ds, PetscSqrtReal(L));
  PetscCall(Split(c, x, arc->a, &w));
  PetscCall(JRContOutputAmplitude(c, w, arc->a, 0, &A));
  PetscCall(VecCopy(c->amod, arc->amodx)); /* a condensed model's expansion costs its elements' forces: done once */
  arc->Anew = A;
  PetscCall(AmplitudeSlope(c, x, tnew, A, dA));
  PetscCall(VecGetArrayRead(arc->tk, &t0));
  PetscCall(VecGetArrayRead(tnew, &t1));
  PetscCall(JRContInterpolationError(c, b->omega[k], b->amp[k * c->nout], L * PetscRealPart(t0[c->n]), L * arc->dAk, w, A, L * PetscRealPart(t1[c->n]), L * *dA, err));
  PetscCall(VecRestoreArrayRead(tnew, &t1));
  PetscCall(VecRestoreArrayRead(arc->tk, &t0));
  PetscFunctionReturn(0);
}

/* The corrector passed the end of the range at (a, w): land on it exactly, by Newton at w_max from the interpolation
   between x_k and (a, w) */
static PetscErrorCode LandOnEnd(JRCont c, PetscInt lev, JRContBranch *b, Vec a, PetscReal w, PetscReal ds)
{
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;
  PetscReal         wk, s;
  PetscInt          its;
  PetscBool         conv;
  PetscReal         res;
  Vec               ak;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(a, &ak));
  PetscCall(Split(c, arc->xk, ak, &wk));
  s = (c->wmax - wk) / (w - wk);
  PetscCall(VecAXPBY(a, 1.0 - s, s, ak)); /* a <- s a + (1 - s) a_k */
  PetscCall(VecDestroy(&ak));
  PetscCall(JRHBMSolveResidual(c->hbm, c->wmax, a, &its, &conv, &res));
  if (conv) {
    PetscCall(JRContBranchAdd(c, b, c->wmax, a, its, ds, res));
    b->complete = PETSC_TRUE;
  } else {
    PetscCall(PetscSNPrintf(b->why, sizeof(b->why), "no solution exactly at the end of the range; the curve ends at %.6g Hz", (double)(wk / (2 * PETSC_PI))));
    PetscCall(JRContPrintf(c, "cont: level %" PetscInt_FMT " F %g N: %s\n", lev + 1, (double)b->F, b->why));
  }
  PetscFunctionReturn(0);
}

/* A step rounded to the nearest of the steps 2^(j/8) (j integer): the factors below are continuous functions of the
   points, whose round-off (which differs with the number of ranks) the step control would otherwise feed back into
   the next point from step to step and grow until the curves' points part; rounded, the steps are the same unless a
   factor sits on the boundary between two of them */
static PetscReal RoundStep(PetscReal ds)
{
  return ds > 0 ? PetscPowReal(2.0, round(8.0 * PetscLog2Real(ds)) / 8.0) : ds;
}

/* The next step from the last point's Newton iterations against the target, and the turn of the response curve as
   plotted (frequency over the range, decades of amplitude at the first output) against 5 degrees per step, so that
   peaks and folds get points where the curve bends (the full tangent also turns with invisible harmonics and modes,
   at every stick-slip kink of the sampled elements); within [dsmin, dsmax] */
static PetscReal NextStep(JRCont c, JRContBranch *b, PetscInt its, PetscReal err, PetscReal ds, PetscReal dsmin, PetscReal dsmax)
{
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;
  const PetscInt    k   = b->np - 1;
  PetscReal         fn  = PetscSqrtReal((PetscReal)c->target / PetscMax(its, 1)), fa = 2.0;

  if (c->itol > 0) fn = PetscMin(fn, 0.9 * PetscSqrtReal(c->itol / PetscMax(err, 1e-12))); /* the error grows as ds^2 */

  if (k >= 2 && b->amp[k * c->nout] > 0 && b->amp[(k - 1) * c->nout] > 0 && b->amp[(k - 2) * c->nout] > 0) {
    const PetscReal d1w = (b->omega[k - 1] - b->omega[k - 2]) / arc->wref, d1a = PetscLog10Real(b->amp[(k - 1) * c->nout] / b->amp[(k - 2) * c->nout]);
    const PetscReal d2w = (b->omega[k] - b->omega[k - 1]) / arc->wref, d2a = PetscLog10Real(b->amp[k * c->nout] / b->amp[(k - 1) * c->nout]);
    const PetscReal n1 = PetscSqrtReal(d1w * d1w + d1a * d1a), n2 = PetscSqrtReal(d2w * d2w + d2a * d2a);
    if (n1 > 0 && n2 > 0) {
      const PetscReal ang = PetscAcosReal(PetscMax(-1.0, PetscMin(1.0, (d1w * d2w + d1a * d2a) / (n1 * n2))));
      fa                  = (5.0 * PETSC_PI / 180.0) / PetscMax(ang, 1e-3);
    }
  }
  ds = RoundStep(ds * PetscMax(0.5, PetscMin(2.0, PetscMin(fn, fa))));
  return PetscMax(dsmin, PetscMin(dsmax, ds));
}

/* How far the corrector went from the predictor in the plane of the plot (frequency over the range, amplitude at
   response 1 over the largest met), per unit of the predictor's own step in that plane: about the tangent of the
   angle the plotted response turned by over the step (the full unknowns also jump with harmonics and modes nobody
   plots, at every stick-slip kink of the sampled elements) */
static PetscErrorCode PlotTurn(JRCont c, JRContBranch *b, PetscReal w, PetscReal *q)
{
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;
  const PetscInt    k   = b->np - 1;
  PetscReal         wp, Ap, Aref = PetscMax(arc->Anew, 0), dp, dc;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i <= k; i++) Aref = PetscMax(Aref, b->amp[i * c->nout]);
  Aref = Aref > 0 ? Aref : 1;
  PetscCall(Split(c, arc->xpred, arc->a, &wp));
  PetscCall(JRContOutputAmplitude(c, wp, arc->a, 0, &Ap));
  dp = PetscSqrtReal(PetscSqr((wp - b->omega[k]) / arc->wref) + PetscSqr((Ap - b->amp[k * c->nout]) / Aref));
  dc = PetscSqrtReal(PetscSqr((w - wp) / arc->wref) + PetscSqr((arc->Anew - Ap) / Aref));
  *q = dp > 0 ? dc / dp : 0;
  PetscFunctionReturn(0);
}

/* A rejected step: half the step (or what the interpolation error asks), and a message; *stop when it falls below
   the smallest step (b->why says where the curve ends) */
static PetscErrorCode Retry(JRCont c, PetscInt lev, JRContBranch *b, PetscReal wk, PetscReal factor, const char what[], PetscReal *ds, PetscReal dsmin, PetscBool *stop)
{
  PetscFunctionBeginUser;
  b->retries++;
  *ds = RoundStep(*ds * factor) < dsmin && *ds * factor >= dsmin ? dsmin : RoundStep(*ds * factor); /* the least step is still tried */
  *stop = *ds < dsmin ? PETSC_TRUE : PETSC_FALSE;
  if (c->monitor && (!*stop || c->monitor > 1)) PetscCall(JRContPrintf(c, "cont: level %" PetscInt_FMT " F %g N: %s after %.6g Hz, retrying with step %.3g\n", lev + 1, (double)b->F, what, (double)(wk / (2 * PETSC_PI)), (double)*ds));
  if (*stop) {
    PetscCall(PetscSNPrintf(b->why, sizeof(b->why), "the corrector found no solution after %.6g Hz (%s) with steps down to %.3g (-cont_step_min)", (double)(wk / (2 * PETSC_PI)), what, (double)dsmin));
    PetscCall(JRContPrintf(c, "cont: level %" PetscInt_FMT " F %g N: stopped: %s\n", lev + 1, (double)b->F, b->why));
  }
  PetscFunctionReturn(0);
}

/* Pseudo-arclength continuation over [wmin, wmax] at the current level. A step is taken when the corrector gives a
   solution (Correct) and linear interpolation from the last point is within -cont_interp_tol; else it is retried
   shorter. */
static PetscErrorCode JRContSolveLevel_Arclength(JRCont c, PetscInt lev, JRContBranch *b, Vec a)
{
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;
  PetscReal         ds = c->step0 > 0 ? c->step0 : 0.01, dsmin = c->stepmin > 0 ? c->stepmin : 1e-7, dsmax = c->stepmax > 0 ? c->stepmax : 0.05, w, atol;
  SNES              hs;
  Vec               tnew, x;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetSNES(c->hbm, &hs)); /* the corrector's absolute tolerance: the harmonic-balance Newton's */
  PetscCall(SNESGetTolerances(hs, &atol, NULL, NULL, NULL, NULL));
  PetscCall(SNESSetTolerances(arc->snes, atol, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(ResponseScale(c, b->F, a)); /* the response scale grows with the level */
  PetscCall(VecDuplicate(arc->xk, &tnew));
  PetscCall(VecDuplicate(arc->xk, &x));
  PetscCall(Start(c, lev, b, a, tnew));
  PetscCall(AmplitudeSlope(c, arc->xk, arc->tk, b->amp[0], &arc->dAk));
  while (b->np < c->maxpts) {
    PetscReal           wk, na, res, err = 0, dA = 0;
    PetscInt            its = 0;
    PetscBool           ok = PETSC_FALSE, stop;
    SNESConvergedReason reason;
    PetscCall(Split(c, arc->xk, arc->a, &wk));
    PetscCall(Correct(c, ds, x, &its, &reason, &res, &ok));
    PetscCall(Split(c, x, a, &w));
    if (!ok || PetscIsInfOrNanReal(w)) {
      char what[96];
      if (reason > 0) PetscCall(PetscSNPrintf(what, sizeof(what), "corrector stopped at relative residual %.2e (%s)", (double)res, SNESConvergedReasons[reason]));
      else PetscCall(PetscSNPrintf(what, sizeof(what), "corrector failed (%s)", SNESConvergedReasons[reason]));
      PetscCall(Retry(c, lev, b, wk, 0.5, what, &ds, dsmin, &stop));
      if (stop) break;
      continue;
    }
    if (w >= c->wmax) {
      PetscCall(LandOnEnd(c, lev, b, a, w, ds));
      break;
    }
    PetscCall(Tangent(c, x, arc->tk, tnew));
    if (c->itol > 0) { /* the Hermite estimate; where it is not small, or the response as plotted turned by more than
                          about 10 degrees from the predictor (stick-slip onsets bend it sharply), the curve's point
                          halfway along the chord, solved for; past about 25 degrees also at a quarter and three
                          quarters, which see an S that the middle may not */
      PetscReal q = 0;
      PetscCall(StepError(c, b, x, tnew, ds, &err, &dA));
      PetscCall(PlotTurn(c, b, w, &q));
      if (err > 0.5 * c->itol || q > 0.35) {
        const PetscReal ts[3] = {0.5, 0.25, 0.75};
        PetscReal       e;
        PetscInt        mits;
        err = 0;
        for (PetscInt i = 0; i < (q > 0.5 ? 3 : 1) && err <= c->itol; i++) {
          PetscCall(JRContChordError(c, b, a, w, arc->Anew, ts[i], &e, &mits));
          b->newton += mits;
          err = PetscMax(err, e);
        }
      }
      if (err > c->itol && ds > dsmin) { /* too coarse to interpolate: shorter */
        char what[96];
        if (err >= PETSC_INFINITY) PetscCall(PetscSNPrintf(what, sizeof(what), "the curve's point on the chord not found (interpolation not checked)"));
        else PetscCall(PetscSNPrintf(what, sizeof(what), "interpolation error %.2e above -cont_interp_tol %.2e", (double)err, (double)c->itol));
        PetscCall(Retry(c, lev, b, wk, PetscMax(PetscMax(0.2, 0.8 * PetscSqrtReal(c->itol / err)), dsmin / ds), what, &ds, dsmin, &stop));
        continue;
      }
    }
    if (c->itol > 0) PetscCall(JRContBranchAddExpanded(c, b, w, a, arc->amodx, its, ds, res)); /* StepError's expansion of a */
    else PetscCall(JRContBranchAdd(c, b, w, a, its, ds, res));
    PetscCall(JRContMonitor(c, lev, b));
    PetscCall(VecNorm(a, NORM_2, &na)); /* the amplitude scale follows the largest response met: slipping joints respond far more than stuck ones */
    if (na > arc->aref) arc->aref = na; /* the next tangent is normalised in the new metric */
    if (w < c->wmin) {
      PetscCall(PetscSNPrintf(b->why, sizeof(b->why), "the curve turned back below the start of the range at %.6g Hz", (double)(w / (2 * PETSC_PI))));
      PetscCall(JRContPrintf(c, "cont: level %" PetscInt_FMT " F %g N: %s; stopped\n", lev + 1, (double)b->F, b->why));
      break;
    }
    if (na >= arc->aref) { /* the metric changed: the tangent renormalised, its amplitude slope with it */
      PetscCall(Tangent(c, x, arc->tk, tnew));
      if (c->itol > 0) PetscCall(AmplitudeSlope(c, x, tnew, b->amp[(b->np - 1) * c->nout], &dA));
    }
    ds = NextStep(c, b, its, err, ds, dsmin, dsmax);
    arc->dAk = dA;
    PetscCall(VecCopy(tnew, arc->tk));
    PetscCall(VecCopy(x, arc->xk));
  }
  if (b->np >= c->maxpts) {
    PetscCall(PetscSNPrintf(b->why, sizeof(b->why), "-cont_max_points %" PetscInt_FMT " reached before the end of the range", c->maxpts));
    PetscCall(JRContPrintf(c, "cont: level %" PetscInt_FMT " F %g N: %s\n", lev + 1, (double)b->F, b->why));
  }
  PetscCall(VecDestroy(&tnew));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

/* The corrector: Newton (newtondense, LU) on the bordered system under the JRHBM's prefix, with its tolerances */
static PetscErrorCode CreateCorrector(JRCont c)
{
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;
  KSP               ksp;
  PC                pc;
  SNES              hs;
  PetscReal         atol, rtol, stol;
  PetscInt          maxit, maxf;
  const char       *pre;
  JRHBMJacobianType jt;

  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, c->n + 1, c->n + 1, NULL, &arc->BJ));
  PetscCall(SNESCreate(PETSC_COMM_SELF, &arc->snes));
  PetscCall(JRHBMGetOptionsPrefix(c->hbm, &pre));
  PetscCall(SNESSetOptionsPrefix(arc->snes, pre));
  PetscCall(SNESSetFunction(arc->snes, arc->G, BorderedFunction, c));
  PetscCall(SNESSetJacobian(arc->snes, arc->BJ, arc->BJ, BorderedJacobian, c));
  PetscCall(SNESGetKSP(arc->snes, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(JRHBMGetSNES(c->hbm, &hs));
  PetscCall(SNESGetTolerances(hs, &atol, &rtol, &stol, &maxit, &maxf));
  PetscCall(SNESSetTolerances(arc->snes, atol, rtol, stol, maxit, maxf));
  PetscCall(SNESSetType(arc->snes, SNESNEWTONDENSE));
  PetscCall(SNESSetFromOptions(arc->snes));
  PetscCall(JRHBMGetJacobianType(c->hbm, &jt));
  arc->bj   = (JRContBordered){c->hbm, arc->J, arc->Rw, arc->brow, c->n};
  arc->tj   = (JRContBordered){c->hbm, arc->J, arc->Rw, arc->trow, c->n};
  arc->lazy = PETSC_FALSE;
  if (jt == JR_HBM_JACOBIAN_FD) PetscCall(SNESSetJacobian(arc->snes, arc->BJ, arc->BJ, SNESComputeJacobianDefault, c));
  else { /* Newton takes the Jacobian's products (a model condensed onto its joints forms it only for an LU) */
    const JRDenseOp op = {JRContBorderedMult, JRContBorderedForm, &arc->bj};
    PetscCall(SNESNewtonDenseSetOperator(arc->snes, &op));
    PetscCall(SNESNewtonDenseUsesOperator(arc->snes, &arc->lazy));
  }
  PetscCall(SNESNewtonDenseGetDenseLU(arc->snes, &arc->tlu));
  if (!arc->tlu) {
    PetscCall(JRDenseLUCreate(&arc->tlu));
    arc->towns = PETSC_TRUE;
  }
  PetscFunctionReturn(0);
}

/* The corrector's and the tangent's kept factors dropped */
static PetscErrorCode JRContForget_Arclength(JRCont c)
{
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;

  PetscFunctionBeginUser;
  if (arc->tlu) PetscCall(JRDenseLUForget(arc->tlu)); /* the corrector's own (newtondense), or the tangent's */
  PetscFunctionReturn(0);
}

/* The work of an earlier solve */
static PetscErrorCode Reset(JRCont_Arclength *arc)
{
  PetscFunctionBeginUser;
  PetscCall(SNESDestroy(&arc->snes));
  PetscCall(MatDestroy(&arc->BJ));
  PetscCall(MatDestroy(&arc->J));
  PetscCall(PetscFree3(arc->tb, arc->brow, arc->trow));
  if (arc->towns) PetscCall(JRDenseLUDestroy(&arc->tlu));
  arc->tlu   = NULL;
  arc->towns = PETSC_FALSE;
  PetscCall(VecDestroy(&arc->a));
  PetscCall(VecDestroy(&arc->r));
  PetscCall(VecDestroy(&arc->Rw));
  PetscCall(VecDestroy(&arc->G));
  PetscCall(VecDestroy(&arc->xpred));
  PetscCall(VecDestroy(&arc->xk));
  PetscCall(VecDestroy(&arc->tk));
  PetscCall(VecDestroy(&arc->d));
  PetscCall(VecDestroy(&arc->amodx));
  PetscFunctionReturn(0);
}

/* At every solve (the sizes may differ from an earlier one): the work vectors, the Jacobians and the corrector */
static PetscErrorCode JRContSetUp_Arclength(JRCont c)
{
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;

  PetscFunctionBeginUser;
  PetscCall(Reset(arc));
  arc->aunit = 0;
  PetscCall(JRHBMCreateVecs(c->hbm, &arc->a, &arc->J));
  PetscCall(VecDuplicate(arc->a, &arc->r));
  PetscCall(VecDuplicate(arc->a, &arc->Rw));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, c->n + 1, &arc->xk));
  PetscCall(VecDuplicate(arc->xk, &arc->xpred));
  PetscCall(VecDuplicate(arc->xk, &arc->tk));
  PetscCall(VecDuplicate(arc->xk, &arc->G));
  PetscCall(VecDuplicate(arc->xk, &arc->d));
  PetscCall(VecDuplicate(c->amod, &arc->amodx));
  PetscCall(PetscMalloc3((c->n + 1) * (c->n + 1), &arc->tb, c->n + 1, &arc->brow, c->n + 1, &arc->trow));
  PetscCall(CreateCorrector(c));
  PetscFunctionReturn(0);
}

/* -cont_constraint pseudo|sphere */
static PetscErrorCode JRContSetFromOptions_Arclength(JRCont c, PetscOptionItems *PetscOptionsObject)
{
  JRCont_Arclength *arc = (JRCont_Arclength *)c->data;
  PetscInt          k   = arc->constraint;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsEList("-cont_constraint", "Arclength constraint: pseudo (orthogonal to the tangent) or sphere (thesis 2.28)", "JRContSetFromOptions", JRContConstraints, 2, JRContConstraints[arc->constraint], &k, NULL));
  arc->constraint = (JRContConstraint)k;
  PetscFunctionReturn(0);
}

static PetscErrorCode JRContDestroy_Arclength(JRCont c)
{
  PetscFunctionBeginUser;
  PetscCall(Reset((JRCont_Arclength *)c->data));
  PetscCall(PetscFree(c->data));
  PetscFunctionReturn(0);
}

PetscErrorCode JRContCreate_Arclength(JRCont c)
{
  JRCont_Arclength *arc;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&arc));
  arc->constraint        = JR_CONT_PSEUDO;
  c->data                = arc;
  c->ops->setfromoptions = JRContSetFromOptions_Arclength;
  c->ops->setup          = JRContSetUp_Arclength;
  c->ops->solvelevel     = JRContSolveLevel_Arclength;
  c->ops->forget         = JRContForget_Arclength;
  c->ops->destroy        = JRContDestroy_Arclength;
  PetscFunctionReturn(0);
}
