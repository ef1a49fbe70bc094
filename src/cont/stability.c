/*
   Stability of every point of a level's curve by Hill's method (JRHBMFloquet, src/hbm/hill.c), and the folds and
   branch points along it (docs/theory.md, section 15), after the level is traced and its peaks inserted.

   fold:   the frequency is extreme at a point (consecutive steps change direction in w); located at the vertex of the
           parabola w(s) through that point and its neighbours, s the scaled arclength (chord lengths in the unknowns
           over their largest norm and in w over the range).
   branch: the determinant of the bordered Jacobian, sign(det J) sign(dw/ds), changes sign and keeps its new sign for
           two points (kind simple); or the stability changes, for two points, with no fold and no real exponent
           crossing near: a complex pair crossing the imaginary axis (kind pair). Located where the largest real part
           crosses zero, by linear interpolation (the midpoint if it does not).
*/
#include <jointrom/private/contimpl.h>

/* Free a curve's stability arrays */
PetscErrorCode JRContBranchStabilityFree(JRContBranch *b)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree3(b->stable, b->maxre, b->detsign));
  PetscCall(PetscFree2(b->wfold, b->wbranch));
  b->nfold = b->nbranch = 0;
  PetscFunctionReturn(0);
}

/* Point k's unknowns (the solve space) into a */
static PetscErrorCode LoadPoint(JRCont c, JRContBranch *b, PetscInt k, Vec a)
{
  PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(a, &x));
  for (PetscInt i = 0; i < c->n; i++) x[i] = b->x[k * c->n + i];
  PetscCall(VecRestoreArray(a, &x));
  PetscFunctionReturn(0);
}

/* The fold near the extreme point k (0 < k < np - 1): the vertex of the parabola w(s) through k - 1, k, k + 1 */
static PetscReal FoldFrequency(JRCont c, JRContBranch *b, PetscInt k, PetscReal xs)
{
  PetscReal s[3] = {0, 0, 0}, w[3], d1, d2, d12, ss;

  for (PetscInt j = 0; j < 3; j++) w[j] = b->omega[k - 1 + j];
  for (PetscInt j = 1; j < 3; j++) {
    const PetscReal *x0 = b->x + (k - 2 + j) * c->n, *x1 = b->x + (k - 1 + j) * c->n;
    const PetscReal  dw = (w[j] - w[j - 1]) / (c->wmax - c->wmin);
    PetscReal        q  = dw * dw;
    for (PetscInt i = 0; i < c->n; i++) q += (x1[i] - x0[i]) * (x1[i] - x0[i]) / (xs * xs);
    s[j] = s[j - 1] + PetscSqrtReal(q);
  }
  if (!(s[1] > s[0] && s[2] > s[1])) return w[1];
  d1  = (w[1] - w[0]) / (s[1] - s[0]);
  d12 = (w[2] - w[1]) / (s[2] - s[1]);
  d2  = (d12 - d1) / (s[2] - s[0]);
  if (d2 == 0.0) return w[1];
  ss = 0.5 * (s[0] + s[1] - d1 / d2);
  ss = PetscMin(PetscMax(ss, s[0]), s[2]);
  return w[0] + d1 * (ss - s[0]) + d2 * (ss - s[0]) * (ss - s[1]);
}

/* Where the largest real part crosses zero between points k and k + 1 (linear in w), else their midpoint */
static PetscReal CrossingFrequency(JRContBranch *b, PetscInt k)
{
  const PetscReal r0 = b->maxre[k], r1 = b->maxre[k + 1], w0 = b->omega[k], w1 = b->omega[k + 1];

  if (r0 * r1 < 0) return w0 + (w1 - w0) * r0 / (r0 - r1);
  return 0.5 * (w0 + w1);
}

/* Folds and branch points of curve b into b->wfold, b->wbranch (the same on every rank: the data are) */
static PetscErrorCode Detect(JRCont c, JRContBranch *b)
{
  const PetscInt np = b->np;
  PetscReal      xs = 0.0;
  PetscBool     *fold;
  PetscInt      *sig;

  PetscFunctionBeginUser;
  PetscCall(PetscFree2(b->wfold, b->wbranch));
  PetscCall(PetscMalloc2(np, &b->wfold, np, &b->wbranch));
  PetscCall(PetscCalloc2(np, &fold, np, &sig));
  b->nfold = b->nbranch = 0;
  for (PetscInt k = 0; k < np; k++) {
    PetscReal q = 0.0;
    for (PetscInt i = 0; i < c->n; i++) q += b->x[k * c->n + i] * b->x[k * c->n + i];
    xs = PetscMax(xs, PetscSqrtReal(q));
  }
  if (xs == 0.0) xs = 1.0;
  for (PetscInt k = 1; k < np - 1; k++)
    if ((b->omega[k] - b->omega[k - 1]) * (b->omega[k + 1] - b->omega[k]) < 0) {
      fold[k]              = PETSC_TRUE;
      b->wfold[b->nfold++] = FoldFrequency(c, b, k, xs);
    }
  /* sigma_k = sign(det J) sign(dw) at point k (dw: the step to the next point): the sign of the bordered Jacobian's
     determinant. A change held for two points on each side is a branch point; single-point blips beside folds, where
     the two factors flip at neighbouring points, are not. */
  for (PetscInt k = 0; k < np; k++) {
    const PetscReal dw = k < np - 1 ? b->omega[k + 1] - b->omega[k] : b->omega[k] - b->omega[k - 1];
    sig[k]             = b->detsign[k] * (dw > 0 ? 1 : dw < 0 ? -1 : 0);
  }
  for (PetscInt k = 1; k + 2 < np; k++) {
    const PetscBool simple = (PetscBool)(sig[k] && sig[k - 1] == sig[k] && sig[k + 1] == sig[k + 2] && sig[k + 1] == -sig[k]);
    PetscBool       pair   = (PetscBool)(b->stable[k - 1] == b->stable[k] && b->stable[k + 1] == b->stable[k + 2] && b->stable[k] != b->stable[k + 1]);
    for (PetscInt j = k - 1; j <= k + 2 && pair; j++)
      if (fold[j] || (j < k + 2 && b->detsign[j] != b->detsign[j + 1])) pair = PETSC_FALSE; /* a fold or a real exponent explains it */
    if (!simple && !pair) continue;
    b->wbranch[b->nbranch] = CrossingFrequency(b, k);
    if (!c->quiet) PetscCall(PetscPrintf(c->comm, "branch level %g freq_hz %.8g kind %s\n", (double)b->F, (double)(b->wbranch[b->nbranch] / (2 * PETSC_PI)), simple ? "simple" : "pair"));
    b->nbranch++;
  }
  if (!c->quiet)
    for (PetscInt f = 0; f < b->nfold; f++) PetscCall(PetscPrintf(c->comm, "fold level %g freq_hz %.8g\n", (double)b->F, (double)(b->wfold[f] / (2 * PETSC_PI))));
  PetscCall(PetscFree2(fold, sig));
  PetscFunctionReturn(0);
}

/* JRContStability - level lev's points' stability (b->stable, b->maxre, b->detsign), its folds and branch points, and
   (unless quiet) their lines; a: work vector of the solve space. Each point is decided (JRHBMStabilityVerdict) by
   incremental dissipativity where it holds (stable, maxre NaN; -frf_stability_dissipative 0: never), by the
   monodromy matrix in time where friction elements change state (JRHBMFloquetTime; -frf_stability_time 0: Hill's
   method, whose flags there indicate rather than decide, counted and said), and by Hill's method (JRHBMFloquet) for
   smooth elements. Does nothing without -frf_stability; a model condensed onto its joints is analysed in time on its
   points' modal unknowns (JRHBMExpand), with a cubic spring only where incrementally dissipative at every point (else
   a note says so once). Collective. */
PetscErrorCode JRContStability(JRCont c, PetscInt lev, Vec a)
{
  JRContBranch      *b = &c->br[lev];
  PetscBool          ok, okt;
  PetscInt           nun = 0, ncount[4] = {0, 0, 0, 0};
  PetscLogDouble     t0, t1;
  JRStabilityVerdict v = JR_STABILITY_HILL, *verdict;
  PetscBool         *intime, any = PETSC_FALSE;
  PetscInt           nfast = 0;

  PetscFunctionBeginUser;
  PetscCall(JRContBranchStabilityFree(b));
  if (!c->stabset) { /* the default, decided at the first level */
    PetscInt size;
    PetscCall(JRHBMStabilityCheap(c->hbm, &c->stab, &size));
    c->stabset = PETSC_TRUE;
    if (!c->stab && !c->quiet) PetscCall(PetscPrintf(c->comm, "stability: not computed by default for this model: each point's eigenproblem (the monodromy matrix in time, or Hill's problem) has %" PetscInt_FMT " unknowns and would cost several times the curve (docs/performance.md); -frf_stability computes it, -frf_stability 0 silences this line\n", size));
  }
  if (!c->stab) PetscFunctionReturn(0);
  PetscCall(JRHBMHillSupported(c->hbm, &ok));
  PetscCall(JRHBMFloquetTimeSupported(c->hbm, &okt));
  PetscCall(PetscTime(&t0));
  for (PetscInt k = 0; k < b->np && !ok && !okt; k++) { /* condensed with smooth elements: only the certificate, which must then hold at every point */
    PetscCall(LoadPoint(c, b, k, a));
    PetscCall(JRHBMStabilityVerdict(c->hbm, a, c->stabdiss, &v));
    if (v != JR_STABILITY_DISSIPATIVE) {
      if (lev == 0 && !c->quiet) PetscCall(PetscPrintf(c->comm, "stability: not computed, the model is condensed onto its joints, has a cubic spring and is not incrementally dissipative at every point (-hbm_condense no keeps the modal unknowns); the CSV's stable column is -1\n"));
      PetscFunctionReturn(0);
    }
  }
  PetscCall(PetscMalloc3(b->np, &b->stable, b->np, &b->maxre, b->np, &b->detsign));
  PetscCall(PetscMalloc1(b->np + 1, &verdict));
  PetscCall(PetscCalloc1(b->np + 1, &intime));
  for (PetscInt k = 0; k < b->np; k++) {
    PetscCall(LoadPoint(c, b, k, a));
    PetscCall(JRHBMStabilityVerdict(c->hbm, a, c->stabdiss, &v));
    if (v == JR_STABILITY_HILL_HYSTERETIC && (c->stabtime || !ok)) v = JR_STABILITY_TIME; /* condensed: no Hill's method */
    verdict[k] = v;
    switch (v) {
    case JR_STABILITY_DISSIPATIVE:
      b->maxre[k]   = NAN;
      b->detsign[k] = 0;
      if (ok) PetscCall(JRHBMJacobianSign(c->hbm, b->omega[k], a, &b->detsign[k]));
      break;
    case JR_STABILITY_TIME: /* below, the points shared out over the ranks */
      intime[k] = any = PETSC_TRUE;
      b->detsign[k] = 0;
      if (ok) PetscCall(JRHBMJacobianSign(c->hbm, b->omega[k], a, &b->detsign[k]));
      break;
    default:
      PetscCall(JRHBMFloquet(c->hbm, b->omega[k], a, c->stabsel, c->stabdense, NULL, NULL, NULL, &b->maxre[k], &b->detsign[k]));
    }
  }
  if (any) {
    PetscReal *X = b->x;
    PetscInt   n = c->n;
    PetscCall(JRHBMSetFloquetFast(c->hbm, c->stabfast));
    if (!ok) { /* condensed onto the joints: the points' modal unknowns, expanded */
      Vec am;
      PetscCall(JRHBMGetSizes(c->hbm, NULL, NULL, &n));
      PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &am));
      PetscCall(PetscCalloc1(b->np * n + 1, &X));
      for (PetscInt k = 0; k < b->np; k++) {
        const PetscScalar *xa;
        if (!intime[k]) continue;
        PetscCall(LoadPoint(c, b, k, a));
        PetscCall(JRHBMExpand(c->hbm, b->omega[k], a, am));
        PetscCall(VecGetArrayRead(am, &xa));
        PetscCall(PetscArraycpy(X + k * n, xa, n));
        PetscCall(VecRestoreArrayRead(am, &xa));
      }
      PetscCall(VecDestroy(&am));
    }
    PetscCall(JRHBMFloquetTimePoints(c->hbm, b->np, b->omega, X, n, intime, c->stabsteps, b->maxre, &nfast));
    if (X != b->x) PetscCall(PetscFree(X));
  }
  for (PetscInt k = 0; k < b->np; k++) {
    b->stable[k] = verdict[k] == JR_STABILITY_DISSIPATIVE || b->maxre[k] < c->stabtol * b->omega[k] ? 1 : 0;
    ncount[verdict[k]]++;
    if (!b->stable[k]) nun++;
  }
  PetscCall(PetscFree(verdict));
  PetscCall(PetscFree(intime));
  PetscCall(Detect(c, b));
  PetscCall(PetscTime(&t1));
  b->stab_seconds = t1 - t0;
  b->nhyst        = ncount[JR_STABILITY_HILL_HYSTERETIC];
  if (!c->quiet) PetscCall(PetscPrintf(c->comm, "stability level %g unstable_points %" PetscInt_FMT " of %" PetscInt_FMT " folds %" PetscInt_FMT " branch_points %" PetscInt_FMT " seconds %.3g (curve %.3g) dissipative %" PetscInt_FMT " time %" PetscInt_FMT " hill %" PetscInt_FMT " hill_hysteretic %" PetscInt_FMT " fast_modes %" PetscInt_FMT "\n", (double)b->F, nun, b->np, b->nfold, b->nbranch, (double)b->stab_seconds, (double)b->seconds, ncount[JR_STABILITY_DISSIPATIVE], ncount[JR_STABILITY_TIME], ncount[JR_STABILITY_HILL], ncount[JR_STABILITY_HILL_HYSTERETIC], nfast));
  if (!c->quiet && b->nhyst) PetscCall(PetscPrintf(c->comm, "stability level %g: %" PetscInt_FMT " points by Hill's method with friction elements changing state: its periodic Jacobian misses the slip's memory, so these flags indicate and do not decide (docs/theory.md section 16); -frf_verify_unstable checks the unstable ones by time integration\n", (double)b->F, b->nhyst));
  PetscFunctionReturn(0);
}

/* JRContGetStabilitySeconds - the wall time of the stability of every level [s] (0 where not computed) */
PetscErrorCode JRContGetStabilitySeconds(JRCont c, PetscReal *seconds)
{
  PetscFunctionBeginUser;
  *seconds = 0.0;
  for (PetscInt l = 0; c->br && l < c->nlev; l++) *seconds += c->br[l].stab_seconds;
  PetscFunctionReturn(0);
}

/* JRContGetStability - level lev's per-point stability (1 stable, 0 unstable) and largest real part of the kept Floquet
   exponents [1/s] (NULL if not computed: -frf_stability 0, or a condensed model), its folds and branch points [rad/s] */
PetscErrorCode JRContGetStability(JRCont c, PetscInt lev, const PetscInt **stable, const PetscReal **maxre, PetscInt *nfold, const PetscReal **wfold, PetscInt *nbranch, const PetscReal **wbranch)
{
  PetscFunctionBeginUser;
  PetscCheck(c->br && lev >= 0 && lev < c->nlev, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "No level %" PetscInt_FMT, lev);
  if (stable) *stable = c->br[lev].stable;
  if (maxre) *maxre = c->br[lev].maxre;
  if (nfold) *nfold = c->br[lev].nfold;
  if (wfold) *wfold = c->br[lev].wfold;
  if (nbranch) *nbranch = c->br[lev].nbranch;
  if (wbranch) *wbranch = c->br[lev].wbranch;
  PetscFunctionReturn(0);
}
