/*
   Stability of every point of a level's curve by Hill's method (JRHBMFloquet, src/hbm/hill.c), and the folds and
   branch points along it (docs/theory.md, section 16), after the level is traced and its peaks inserted.

   fold:   the frequency is extreme at a point (consecutive steps change direction in w); located by golden-section
           search for the extreme frequency along the curve between the point's neighbours (LocateFold).
   branch: the determinant of the bordered Jacobian, sign(det J) sign(dw/ds) with dw/ds of the tangent at the point,
           changes sign and keeps its new sign for two points (kind simple); or the stability changes, for two
           points, with no change of det J between them: a complex pair crossing the imaginary axis (kind pair).
           Located by bisection along the curve between the two points (LocateBranch).
   Both to -cont_locate_tol in frequency, by harmonic-balance solves on planes across the curve (src/cont/peak.c),
   so that they do not depend on where the continuation put its points.
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

/* Point (w, a)'s stability decided as JRContStability decides the curve's points (*stable 1 or 0) and the sign of
   det(dR/da) (0 when not computed); hill: Hill's method runs for this model. Collective. */
static PetscErrorCode PointStability(JRCont c, PetscReal w, Vec a, PetscBool hill, PetscInt *stable, PetscInt *detsign)
{
  JRStabilityVerdict v;
  PetscReal          maxre = NAN;

  PetscFunctionBeginUser;
  PetscCall(JRHBMStabilityVerdict(c->hbm, a, c->stabdiss, &v));
  if (v == JR_STABILITY_HILL_HYSTERETIC && (c->stabtime || !hill)) v = JR_STABILITY_TIME; /* condensed: no Hill's method */
  *detsign = 0;
  switch (v) {
  case JR_STABILITY_DISSIPATIVE:
    if (hill) PetscCall(JRHBMJacobianSign(c->hbm, w, a, detsign));
    break;
  case JR_STABILITY_TIME:
    if (hill) {
      PetscCall(JRHBMJacobianSign(c->hbm, w, a, detsign));
      PetscCall(JRHBMFloquetTime(c->hbm, w, a, c->stabsteps, NULL, NULL, NULL, &maxre, NULL));
    } else { /* condensed onto the joints: on the point's modal unknowns (c->amod) */
      PetscCall(JRHBMExpand(c->hbm, w, a, c->amod));
      PetscCall(JRHBMFloquetTime(c->hbm, w, c->amod, c->stabsteps, NULL, NULL, NULL, &maxre, NULL));
    }
    break;
  default:
    PetscCall(JRHBMFloquet(c->hbm, w, a, c->stabsel, c->stabdense, NULL, NULL, NULL, &maxre, detsign));
  }
  *stable = v == JR_STABILITY_DISSIPATIVE || maxre < c->stabtol * w ? 1 : 0;
  PetscFunctionReturn(0);
}

/* The fold at the extreme point k (0 < k < np - 1): the extreme frequency along the curve between points k - 1 and
   k + 1, by golden-section search on the planes across the curve between them (JRContPlaneBegin), until the bound of
   a concave function through the bracket is below -cont_locate_tol of the frequency; where a solve fails, the vertex
   of the parabola through the three points (FoldFrequency) if it is further out than the best point found */
static PetscErrorCode LocateFold(JRCont c, JRContBranch *b, PetscInt k, PetscReal xs, PetscReal *wf, PetscInt *nits)
{
  const PetscInt  n = c->n, m = n + 1;
  const PetscReal sg = b->omega[k] > b->omega[k - 1] ? 1.0 : -1.0; /* +1: a largest frequency */
  PetscReal      *X, wp, sh;
  PetscBool       done = PETSC_FALSE;
  JRContGolden    g;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(4 * m, &X));
  for (PetscInt j = 0; j < 3; j++) {
    g.x[j] = X + j * m;
    for (PetscInt i = 0; i < n; i++) g.x[j][i] = b->x[(k - 1 + j) * n + i];
    g.x[j][n] = b->omega[k - 1 + j];
    g.f[j]    = sg * g.x[j][n];
  }
  g.xt = X + 3 * m;
  PetscCall(JRContPlaneBegin(c, b, k - 1, k + 1, &sh));
  g.s[0] = 0;
  g.s[1] = JRContPlaneCoordinate(c, g.x[1]);
  g.s[2] = sh;
  for (PetscInt it = 0; it < 100 && g.s[1] > g.s[0] && g.s[1] < g.s[2]; it++) {
    PetscReal st;
    PetscInt  its;
    PetscBool ok, right;
    Vec       a;
    if (JRContGoldenTrial(&g, n, &st, &right) <= c->ltol * PetscAbsReal(g.f[1])) {
      done = PETSC_TRUE;
      break;
    }
    PetscCall(JRContPlanePoint(c, st, g.xt, &a, &its, &ok));
    *nits += its;
    if (!ok) break;
    (void)JRContGoldenUpdate(&g, st, sg * g.xt[n], right);
  }
  *wf = sg * g.f[1];
  if (!done) {
    wp = FoldFrequency(c, b, k, xs);
    if (sg * wp > g.f[1]) *wf = wp;
  }
  PetscCall(PetscFree(X));
  PetscFunctionReturn(0);
}

/* The branch point between points k and k + 1, where q changes from ql to qh (the stability for kind pair, the sign of
   the bordered Jacobian's determinant sign(det J) sign(dw/ds) for kind simple): bisection on the planes across the
   curve between the two points (JRContPlaneBegin) until the bracket spans less than -cont_locate_tol of the
   frequency (-cont_locate_pair_tol for kind pair); its middle. A failed solve, or a point with neither value, ends it with the bracket so far. For kind pair,
   *real when det J changes sign at one of its points: a real exponent crosses there, and it is no branch point. */
static PetscErrorCode LocateBranch(JRCont c, JRContBranch *b, PetscInt k, PetscBool simple, PetscInt ql, PetscInt qh, PetscBool hill, PetscReal *wb, PetscBool *real, PetscInt *nits)
{
  const PetscInt n = c->n, m = n + 1;
  PetscReal     *X, *xl, *xh, *xt, sl = 0, sh;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(3 * m, &X));
  xl = X;
  xh = X + m;
  xt = X + 2 * m;
  for (PetscInt i = 0; i < n; i++) {
    xl[i] = b->x[k * n + i];
    xh[i] = b->x[(k + 1) * n + i];
  }
  xl[n] = b->omega[k];
  xh[n] = b->omega[k + 1];
  PetscCall(JRContPlaneBegin(c, b, k, k + 1, &sh));
  for (PetscInt it = 0; it < 200; it++) {
    const PetscReal st = 0.5 * (sl + sh);
    PetscInt        its, q = 0, ds, o;
    PetscBool       ok;
    Vec             a;
    if (PetscAbsReal(xh[n] - xl[n]) <= (simple ? c->ltol : c->ptolb) * PetscMax(PetscAbsReal(xl[n]), PetscAbsReal(xh[n])) || !(st > sl && st < sh)) break;
    for (PetscInt i = 0; i <= n; i++) xt[i] = 0.5 * (xl[i] + xh[i]);
    PetscCall(JRContPlanePoint(c, st, xt, &a, &its, &ok));
    *nits += its;
    if (!ok) break;
    if (simple) {
      PetscCall(JRContTangentSign(c, xt[n], a, &o, &ds));
      q = ds * o;
    } else {
      PetscCall(PointStability(c, xt[n], a, hill, &q, &ds));
      if (ds != b->detsign[k]) { /* det J changes in the bracket: a real exponent crosses (a fold), not a pair */
        *real = PETSC_TRUE;
        break;
      }
    }
    if (q == ql) {
      PetscReal *t = xl;
      xl           = xt;
      xt           = t;
      sl           = st;
    } else if (q == qh) {
      PetscReal *t = xh;
      xh           = xt;
      xt           = t;
      sh           = st;
    } else break;
  }
  *wb = 0.5 * (xl[n] + xh[n]);
  PetscCall(PetscFree(X));
  PetscFunctionReturn(0);
}

/* Folds and branch points of curve b into b->wfold, b->wbranch, each located by solves along the curve (LocateFold,
   LocateBranch) so that they do not depend on where the continuation put its points; a: work vector of the solve
   space; hill: Hill's method runs for this model. Collective; the same on every rank (the data are). */
static PetscErrorCode Detect(JRCont c, JRContBranch *b, Vec a, PetscBool hill)
{
  const PetscInt np = b->np;
  PetscReal      xs = 0.0;
  PetscInt      *sig, nits = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscFree2(b->wfold, b->wbranch));
  PetscCall(PetscMalloc2(np, &b->wfold, np, &b->wbranch));
  PetscCall(PetscCalloc1(np, &sig));
  b->nfold = b->nbranch = 0;
  for (PetscInt k = 0; k < np; k++) {
    PetscReal q = 0.0;
    for (PetscInt i = 0; i < c->n; i++) q += b->x[k * c->n + i] * b->x[k * c->n + i];
    xs = PetscMax(xs, PetscSqrtReal(q));
  }
  if (xs == 0.0) xs = 1.0;
  PetscCall(JRContPlaneScale(c, b));
  for (PetscInt k = 1; k < np - 1; k++)
    if ((b->omega[k] - b->omega[k - 1]) * (b->omega[k + 1] - b->omega[k]) < 0) {
      PetscCall(LocateFold(c, b, k, xs, &b->wfold[b->nfold++], &nits));
    }
  /* sigma_k = sign(det J) sign(dw/ds) at point k, dw/ds of the tangent there oriented along the curve (JRContTangentSign,
     the chord from the point before to the point after giving the direction): the sign of the bordered Jacobian's
     determinant, which a fold leaves as it is (both factors change there) and a simple branch point changes. A change
     held for two points on each side is a branch point. */
  for (PetscInt k = 0; k < np && np > 1 && hill; k++) { /* sign(det J) from the tangent's LU: b->detsign */
    PetscInt  o;
    PetscReal S;
    PetscCall(JRContPlaneBegin(c, b, PetscMax(k - 1, 0), PetscMin(k + 1, np - 1), &S));
    PetscCall(LoadPoint(c, b, k, a));
    PetscCall(JRContTangentSign(c, b->omega[k], a, &o, &b->detsign[k]));
    sig[k] = b->detsign[k] * o;
  }
  for (PetscInt k = 1; k + 2 < np; k++) {
    const PetscBool simple = (PetscBool)(sig[k] && sig[k - 1] == sig[k] && sig[k + 1] == sig[k + 2] && sig[k + 1] == -sig[k]);
    const PetscBool pair   = (PetscBool)(!simple && b->stable[k - 1] == b->stable[k] && b->stable[k + 1] == b->stable[k + 2] && b->stable[k] != b->stable[k + 1] && b->detsign[k] == b->detsign[k + 1]);
    PetscBool       real   = PETSC_FALSE;
    if (!simple && !pair) continue;
    PetscCall(LocateBranch(c, b, k, simple, simple ? sig[k] : b->stable[k], simple ? sig[k + 1] : b->stable[k + 1], hill, &b->wbranch[b->nbranch], &real, &nits));
    if (real) continue;
    if (!c->quiet) PetscCall(PetscPrintf(c->comm, simple ? "branch level %g freq_hz %.8g kind simple\n" : "branch level %g freq_hz %.6g kind pair\n", (double)b->F, (double)(b->wbranch[b->nbranch] / (2 * PETSC_PI)))); /* a pair to -cont_locate_pair_tol */
    b->nbranch++;
  }
  if (!c->quiet)
    for (PetscInt f = 0; f < b->nfold; f++) PetscCall(PetscPrintf(c->comm, "fold level %g freq_hz %.8g\n", (double)b->F, (double)(b->wfold[f] / (2 * PETSC_PI))));
  (void)nits; /* the Newton iterations spent locating them */
  PetscCall(PetscFree(sig));
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
  PetscLogDouble     t0, t1, e0, e1;
  JRStabilityVerdict v = JR_STABILITY_HILL, *verdict;
  PetscBool         *intime, any = PETSC_FALSE;
  PetscInt           nfast = 0, nrows = 0;

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
  PetscCall(JRHBMSetFloquetFast(c->hbm, c->stabfast));
  PetscCall(JRHBMSetFloquetLowRank(c->hbm, c->stablr));
  PetscCall(PetscTime(&t0));
  PetscCall(JRHBMGetElementTime(c->hbm, &e0, NULL, NULL));
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
    case JR_STABILITY_DISSIPATIVE: /* sign(det J) with the tangent's (Detect) */
      b->maxre[k]   = NAN;
      b->detsign[k] = 0;
      break;
    case JR_STABILITY_TIME: /* below, the points shared out over the ranks; sign(det J) as above */
      intime[k] = any = PETSC_TRUE;
      b->detsign[k] = 0;
      break;
    default:
      PetscCall(JRHBMFloquet(c->hbm, b->omega[k], a, c->stabsel, c->stabdense, NULL, NULL, NULL, &b->maxre[k], &b->detsign[k]));
    }
  }
  if (any) {
    PetscReal *X = b->x;
    PetscInt   n = c->n;
    if (!ok) { /* condensed onto the joints: the points' modal unknowns, expanded (in c->amod) */
      n = c->nmod;
      PetscCall(PetscCalloc1(b->np * n + 1, &X));
      for (PetscInt k = 0; k < b->np; k++) {
        const PetscScalar *xa;
        if (!intime[k]) continue;
        PetscCall(LoadPoint(c, b, k, a));
        PetscCall(JRHBMExpand(c->hbm, b->omega[k], a, c->amod));
        PetscCall(VecGetArrayRead(c->amod, &xa));
        PetscCall(PetscArraycpy(X + k * n, xa, n));
        PetscCall(VecRestoreArrayRead(c->amod, &xa));
      }
    }
    PetscCall(JRHBMFloquetTimePoints(c->hbm, b->np, b->omega, X, n, intime, c->stabsteps, b->maxre, &nfast));
    PetscCall(JRHBMGetFloquetLowRankRows(c->hbm, &nrows));
    if (X != b->x) PetscCall(PetscFree(X));
  }
  for (PetscInt k = 0; k < b->np; k++) {
    b->stable[k] = verdict[k] == JR_STABILITY_DISSIPATIVE || b->maxre[k] < c->stabtol * b->omega[k] ? 1 : 0;
    ncount[verdict[k]]++;
    if (!b->stable[k]) nun++;
  }
  PetscCall(PetscFree(verdict));
  PetscCall(PetscFree(intime));
  PetscCall(Detect(c, b, a, ok));
  PetscCall(PetscTime(&t1));
  PetscCall(JRHBMGetElementTime(c->hbm, &e1, NULL, NULL));
  b->stab_seconds = t1 - t0;
  b->stab_elem    = e1 - e0;
  b->nhyst        = ncount[JR_STABILITY_HILL_HYSTERETIC];
  if (!c->quiet) PetscCall(PetscPrintf(c->comm, "stability level %g unstable_points %" PetscInt_FMT " of %" PetscInt_FMT " folds %" PetscInt_FMT " branch_points %" PetscInt_FMT " seconds %.3g (curve %.3g) dissipative %" PetscInt_FMT " time %" PetscInt_FMT " hill %" PetscInt_FMT " hill_hysteretic %" PetscInt_FMT " fast_modes %" PetscInt_FMT " fast_rows %" PetscInt_FMT "\n", (double)b->F, nun, b->np, b->nfold, b->nbranch, (double)b->stab_seconds, (double)b->seconds, ncount[JR_STABILITY_DISSIPATIVE], ncount[JR_STABILITY_TIME], ncount[JR_STABILITY_HILL], ncount[JR_STABILITY_HILL_HYSTERETIC], nfast, nrows));
  if (!c->quiet && b->nhyst) PetscCall(PetscPrintf(c->comm, "stability level %g: %" PetscInt_FMT " points by Hill's method with friction elements changing state: its periodic Jacobian misses the slip's memory, so these flags indicate and do not decide (docs/theory.md section 16); -frf_verify_unstable checks the unstable ones by time integration\n", (double)b->F, b->nhyst));
  PetscFunctionReturn(0);
}

/* JRContGetStabilitySeconds - the wall time of the stability of every level [s] (0 where not computed) and its part
   in the contact elements (JRHBMGetElementTime; elem may be NULL) */
PetscErrorCode JRContGetStabilitySeconds(JRCont c, PetscReal *seconds, PetscReal *elem)
{
  PetscFunctionBeginUser;
  *seconds = 0.0;
  if (elem) *elem = 0.0;
  for (PetscInt l = 0; c->br && l < c->nlev; l++) {
    *seconds += c->br[l].stab_seconds;
    if (elem) *elem += c->br[l].stab_elem;
  }
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
