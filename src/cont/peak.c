/*
   JRCont: the peaks of a curve and the interpolation error between its points.

   The peak of a response is the largest first-harmonic amplitude of the harmonic-balance solution curve, not of the
   points the continuation happened to compute: between the computed points on either side of the largest one, the
   curve is followed by exact solves on the hyperplanes  <x - x_{k-1}, d>_W = s  (x = (a, w), d = x_{k+1} - x_{k-1},
   W the continuation's scaling: amplitudes by the curve's largest, frequency by the range), a family that crosses
   the curve once between the two points whether the frequency is monotone there or the curve folds. The amplitude
   A(s) is maximised by golden-section search on s, which needs no smoothness (friction-limited tops have kinks),
   until the bound of a concave function through the bracket, max((A_m - A_lo)(hi - m)/(m - lo), (A_m - A_hi)(m -
   lo)/(hi - m)), is below -cont_peak_tol of A_m. The peak is inserted into the curve as a point of its own, so the
   written curve passes through it; every response has its own peak (JRContRefinePeaks).

   JRContInterpolationError estimates how far linear interpolation between two consecutive points is from the curve:
   the cubic Hermite curve through them with their tangents in the (frequency, amplitude) plane, at its middle, against
   the chord at the same frequency (relative to the amplitude); the step control keeps it below -cont_interp_tol.
*/
#include <jointrom/private/contimpl.h>

/* The first-harmonic amplitude at response o of the point (a, w), a in the solve space */
PetscErrorCode JRContOutputAmplitude(JRCont c, PetscReal w, Vec a, PetscInt o, PetscReal *A)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMExpand(c->hbm, w, a, c->amod));
  PetscCall(JRHBMResponse(c->hbm, c->amod, NULL, c->ampw, c->ampw + c->nout));
  *A = c->ampw[o];
  PetscFunctionReturn(0);
}

/* The relative error of linear interpolation between (w0, A0) and (w1, A1), given the derivatives (dw, dA) of the
   curve at both ends times the parameter's length between them: the middle of the cubic Hermite curve against the
   chord at its frequency (where the frequency is monotone), else against the chord's middle */
PetscErrorCode JRContInterpolationError(JRCont c, PetscReal w0, PetscReal A0, PetscReal dw0, PetscReal dA0, PetscReal w1, PetscReal A1, PetscReal dw1, PetscReal dA1, PetscReal *err)
{
  const PetscReal wh = 0.5 * (w0 + w1) + (dw0 - dw1) / 8, ah = 0.5 * (A0 + A1) + (dA0 - dA1) / 8;
  PetscReal       ac = 0.5 * (A0 + A1);

  PetscFunctionBeginUser;
  (void)c;
  if ((w1 - w0) * dw0 > 0 && (w1 - w0) * dw1 > 0) ac = A0 + (wh - w0) * (A1 - A0) / (w1 - w0);
  *err = PetscAbsReal(ah - ac) / PetscMax(PetscMax(PetscAbsReal(ah), PetscAbsReal(ac)), PETSC_SMALL * PetscMax(PetscAbsReal(A0), PetscAbsReal(A1)) + PETSC_MIN_REAL);
  PetscFunctionReturn(0);
}

/* The work of the solves on planes: the unknowns a, residual R, dR/dw, Jacobian J, the bordered matrix and its LU */
struct _JRContPlaneWork {
  PetscInt      n;
  Vec           a, R, Rw;
  Mat           J;
  PetscReal    *B, *lu, *dx, *W; /* (n+1)^2, (n+1)^2, n+1, n+1 (the scaling's weights) */
  PetscBLASInt *piv;
  PetscReal    *x0, *d, *xm;     /* the plane family's origin and normal; a point (n+1 each) */
  JRDenseLU     dlu;             /* the solves on planes: the last factors precondition the next (nearby) ones */
  PetscReal    *row;             /* the bordered matrix's last row W d (n+1) */
  JRContBordered bo;             /* the bordered matrix [J Rw; (W d)^T] by its products, B written for an LU only */
};
typedef struct _JRContPlaneWork PeakWork;

/* The work for the current sizes (JRContSolve's set-up) */
PetscErrorCode JRContPlaneWorkCreate(JRCont c)
{
  PeakWork *pw;

  PetscFunctionBeginUser;
  PetscCall(JRContPlaneWorkDestroy(c));
  PetscCall(PetscNew(&pw));
  pw->n = c->n;
  PetscCall(JRHBMCreateVecs(c->hbm, &pw->a, &pw->J));
  PetscCall(VecDuplicate(pw->a, &pw->R));
  PetscCall(VecDuplicate(pw->a, &pw->Rw));
  PetscCall(PetscMalloc6((c->n + 1) * (c->n + 1), &pw->B, (c->n + 1) * (c->n + 1), &pw->lu, c->n + 1, &pw->dx, c->n + 1, &pw->W, c->n + 1, &pw->x0, c->n + 1, &pw->d));
  PetscCall(PetscMalloc3(c->n + 1, &pw->piv, c->n + 1, &pw->xm, c->n + 1, &pw->row));
  PetscCall(JRDenseLUCreate(&pw->dlu));
  { /* as the harmonic-balance solver's (-hbm_snes_newtondense_eliminate) */
    SNES      hs;
    JRDenseLU hl = NULL;
    PetscBool el;
    PetscCall(JRHBMGetSNES(c->hbm, &hs));
    PetscCall(SNESNewtonDenseGetDenseLU(hs, &hl));
    if (hl) {
      PetscCall(JRDenseLUGetEliminate(hl, &el));
      PetscCall(JRDenseLUSetEliminate(pw->dlu, el));
    }
  }
  pw->bo = (JRContBordered){c->hbm, pw->J, pw->Rw, pw->row, c->n};
  c->pw = pw;
  PetscFunctionReturn(0);
}

/* The plane solves' kept factors dropped (JRContSolve, at each level) */
PetscErrorCode JRContPlaneWorkForget(JRCont c)
{
  PetscFunctionBeginUser;
  if (c->pw) PetscCall(JRDenseLUForget(c->pw->dlu));
  PetscFunctionReturn(0);
}

PetscErrorCode JRContPlaneWorkDestroy(JRCont c)
{
  PeakWork *pw = c->pw;

  PetscFunctionBeginUser;
  if (!pw) PetscFunctionReturn(0);
  PetscCall(PetscFree6(pw->B, pw->lu, pw->dx, pw->W, pw->x0, pw->d));
  PetscCall(PetscFree3(pw->piv, pw->xm, pw->row));
  PetscCall(JRDenseLUDestroy(&pw->dlu));
  PetscCall(VecDestroy(&pw->a));
  PetscCall(VecDestroy(&pw->R));
  PetscCall(VecDestroy(&pw->Rw));
  PetscCall(MatDestroy(&pw->J));
  PetscCall(PetscFree(c->pw));
  PetscFunctionReturn(0);
}

/* (a, w) of x[0..n] */
static PetscErrorCode Load(PeakWork *pw, const PetscReal *x, PetscReal *w)
{
  PetscScalar *v;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(pw->a, &v));
  for (PetscInt i = 0; i < pw->n; i++) v[i] = x[i];
  PetscCall(VecRestoreArray(pw->a, &v));
  *w = x[pw->n];
  PetscFunctionReturn(0);
}

/* <x - x0, d>_W */
static PetscReal PlaneCoordinate(PeakWork *pw, const PetscReal *x)
{
  PetscReal s = 0;
  for (PetscInt i = 0; i <= pw->n; i++) s += pw->W[i] * (x[i] - pw->x0[i]) * pw->d[i];
  return s;
}

/* Newton on R(a, w) = 0, <x - x0, d>_W = s from the guess x (n+1; the solution on return): *ok when the relative
   residual is below rtol, or below the acceptance tolerance with the last step negligible */
static PetscErrorCode SolveOnPlane(JRCont c, PeakWork *pw, PetscReal s, PetscReal rtol, PetscReal *x, PetscReal *res, PetscInt *its, PetscBool *ok)
{
  const PetscInt  n = pw->n, m = n + 1;
  PetscReal       tol, rel = PETSC_INFINITY, step = PETSC_INFINITY;
  const JRDenseOp op = {JRContBorderedMult, JRContBorderedForm, &pw->bo};

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetResidualTolerance(c->hbm, &tol));
  *ok  = PETSC_FALSE;
  *its = 0;
  for (PetscInt it = 0; it < 30; it++) {
    PetscReal          w, g;
    const PetscScalar *r;
    PetscBool          singular;
    PetscCall(Load(pw, x, &w));
    PetscCall(JRHBMComputeResidual(c->hbm, w, pw->a, pw->R));
    PetscCall(JRHBMResidualNorm(c->hbm, pw->R, &rel));
    g = PlaneCoordinate(pw, x) - s;
    if (rel <= rtol || (rel <= tol && step <= 1e-10)) {
      *ok = PETSC_TRUE;
      break;
    }
    if (PetscIsInfOrNanReal(rel)) break;
    PetscCall(JRHBMJacobianSetPoint(c->hbm, w, pw->a, pw->J, pw->Rw));
    for (PetscInt i = 0; i <= n; i++) pw->row[i] = pw->W[i] * pw->d[i];
    PetscCall(VecGetArrayRead(pw->R, &r));
    for (PetscInt i = 0; i < n; i++) pw->dx[i] = r[i];
    PetscCall(VecRestoreArrayRead(pw->R, &r));
    pw->dx[n] = g;
    PetscCall(JRDenseLUSolveOp(pw->dlu, m, &op, pw->B, m, PetscMax(1e-3 * rtol / rel, 1e-12), pw->dx, &singular)); /* to 1e-3 of the residual sought */
    if (singular) break;
    step = 0;
    for (PetscInt i = 0; i <= n; i++) {
      x[i] -= pw->dx[i];
      step += pw->W[i] * pw->dx[i] * pw->dx[i];
    }
    step = PetscSqrtReal(step);
    *its = it + 1;
  }
  *res = rel;
  PetscFunctionReturn(0);
}

/* Move the last point of the curve to index pos (the arrays rotated by one) */
static PetscErrorCode MoveLast(JRCont c, JRContBranch *b, PetscInt pos)
{
  const PetscInt last = b->np - 1;
  struct {
    PetscReal *p;
    PetscInt   bs;
  } arr[] = {
    {b->omega, 1      },
    {b->a,     c->nmod},
    {b->amp,   c->nout},
    {b->pp,    c->nout},
    {b->step,  1      },
    {b->x,     c->n   },
    {b->res,   1      }
  };
  PetscReal *tmp;
  PetscInt   it = b->its[last];

  PetscFunctionBeginUser;
  if (pos >= last) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(PetscMax(PetscMax(c->nmod, c->n), c->nout), &tmp));
  for (size_t k = 0; k < sizeof(arr) / sizeof(arr[0]); k++) {
    const PetscInt bs = arr[k].bs;
    PetscCall(PetscArraycpy(tmp, arr[k].p + last * bs, bs));
    PetscCall(PetscArraymove(arr[k].p + (pos + 1) * bs, arr[k].p + pos * bs, (last - pos) * bs));
    PetscCall(PetscArraycpy(arr[k].p + pos * bs, tmp, bs));
  }
  PetscCall(PetscArraymove(b->its + pos + 1, b->its + pos, last - pos));
  b->its[pos] = it;
  PetscCall(PetscFree(tmp));
  PetscFunctionReturn(0);
}

/* The scaling of the plane family: amplitudes by the largest of the curve's points, frequency by the range */
static void Weights(JRCont c, JRContBranch *b, PeakWork *pw)
{
  PetscReal aref = 0;
  for (PetscInt k = 0; k < b->np; k++) {
    PetscReal s = 0;
    for (PetscInt i = 0; i < c->n; i++) s += b->x[k * c->n + i] * b->x[k * c->n + i];
    aref = PetscMax(aref, s);
  }
  for (PetscInt i = 0; i < c->n; i++) pw->W[i] = aref > 0 ? 1.0 / aref : 1.0;
  pw->W[c->n] = 1.0 / ((c->wmax - c->wmin) * (c->wmax - c->wmin));
}

/* x (n+1) <- (x_k, w_k) of point k */
static void PointX(JRCont c, JRContBranch *b, PetscInt k, PetscReal *x)
{
  for (PetscInt i = 0; i < c->n; i++) x[i] = b->x[k * c->n + i];
  x[c->n] = b->omega[k];
}

/* JRContGoldenTrial - the bound of a concave function through the bracket g (its maximum's excess over the middle:
   the stopping test) and the next trial: its coordinate *st, the golden section of the larger side (*right: the high
   side), and its guess in g->xt (n + 1), linear between the bracket's points */
PetscReal JRContGoldenTrial(JRContGolden *g, PetscInt n, PetscReal *st, PetscBool *right)
{
  const PetscReal sl = g->s[0], sm = g->s[1], sh = g->s[2], fl = g->f[0], fm = g->f[1], fh = g->f[2];
  PetscReal       f;

  *right = (sh - sm) > (sm - sl) ? PETSC_TRUE : PETSC_FALSE;
  *st    = *right ? sm + 0.381966011250105 * (sh - sm) : sm - 0.381966011250105 * (sm - sl);
  f      = *right ? (*st - sm) / (sh - sm) : (*st - sl) / (sm - sl);
  for (PetscInt i = 0; i <= n; i++) g->xt[i] = *right ? (1 - f) * g->x[1][i] + f * g->x[2][i] : (1 - f) * g->x[0][i] + f * g->x[1][i];
  return PetscMax((fm - fl) * (sh - sm) / (sm - sl), (fm - fh) * (sm - sl) / (sh - sm));
}

/* JRContGoldenUpdate - the bracket g after the trial (st, ft) whose unknowns are in g->xt: the new middle where it is
   higher (PETSC_TRUE), the old middle becoming the end on the trial's side; else the new end on that side */
PetscBool JRContGoldenUpdate(JRContGolden *g, PetscReal st, PetscReal ft, PetscBool right)
{
  const PetscInt j = ft > g->f[1] ? (right ? 0 : 2) : (right ? 2 : 0);
  PetscReal     *t = g->x[j];

  if (ft > g->f[1]) {
    g->s[j] = g->s[1];
    g->f[j] = g->f[1];
    g->x[j] = g->x[1];
    g->x[1] = g->xt;
    g->s[1] = st;
    g->f[1] = ft;
    g->xt   = t;
    return PETSC_TRUE;
  }
  g->x[j] = g->xt;
  g->s[j] = st;
  g->f[j] = ft;
  g->xt   = t;
  return PETSC_FALSE;
}

/* Response o's local maximum at point k: golden-section search along the curve between k's neighbours (the maximum
   found is inserted into the curve at *ins, else *ins = -1); (*w, *A) that maximum. Not searched where the bound of a
   concave function through k and its neighbours does not exceed best (a larger maximum is already known). */
static PetscErrorCode RefineAt(JRCont c, JRContBranch *b, PeakWork *pw, PetscInt o, PetscInt k, PetscReal best, PetscReal *wp, PetscReal *Ap, PetscInt *ins)
{
  const PetscInt n = c->n, m = n + 1;
  PetscInt       total = 0;
  PetscReal     *X, s1, res = 0, resm, tol;
  PetscBool      moved = PETSC_FALSE;
  JRContGolden   g;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetResidualTolerance(c->hbm, &tol));
  *wp  = b->omega[k];
  *Ap  = b->amp[k * c->nout + o];
  *ins = -1;
  if (k == 0 || k == b->np - 1) PetscFunctionReturn(0); /* the largest at an end of the range: the curve's maximum there */
  PetscCall(PetscMalloc1(4 * m, &X));
  for (PetscInt j = 0; j < 3; j++) g.x[j] = X + j * m;
  g.xt = X + 3 * m;
  PointX(c, b, k - 1, pw->x0);
  PointX(c, b, k + 1, g.x[2]);
  for (PetscInt i = 0; i <= n; i++) pw->d[i] = g.x[2][i] - pw->x0[i];
  PointX(c, b, k - 1, g.x[0]);
  PointX(c, b, k, g.x[1]);
  for (PetscInt j = 0; j < 3; j++) {
    g.s[j] = j ? PlaneCoordinate(pw, g.x[j]) : 0;
    g.f[j] = b->amp[(k - 1 + j) * c->nout + o];
  }
  s1   = g.s[1];
  resm = b->res[k];
  if (!(g.s[1] > g.s[0] && g.s[1] < g.s[2])) { /* the curve doubles back between the neighbours: keep the computed point */
    PetscCall(PetscFree(X));
    PetscFunctionReturn(0);
  }
  for (PetscInt it = 0; it < 80; it++) {
    PetscReal       st, At, wt;
    PetscInt        its = 0;
    PetscBool       ok, right;
    const PetscReal bound = JRContGoldenTrial(&g, n, &st, &right);
    if (bound <= c->ptol * g.f[1] || (!it && g.f[1] + bound <= best)) break;
    PetscCall(SolveOnPlane(c, pw, st, 1e-3 * tol, g.xt, &res, &its, &ok));
    total += its;
    if (!ok) break; /* no solution on this plane: the best so far stands */
    PetscCall(Load(pw, g.xt, &wt));
    PetscCall(JRContOutputAmplitude(c, wt, pw->a, o, &At));
    if (JRContGoldenUpdate(&g, st, At, right)) {
      resm  = res;
      moved = PETSC_TRUE;
    }
  }
  b->refine_its += total;
  /* a gain within the tolerance is no new point: the maximum is point k itself (a kink of the curve, or a peak that
     another response's refinement has inserted), and round-off alone would decide whether to add a twin */
  if (moved && g.f[1] - *Ap <= c->ptol * *Ap) moved = PETSC_FALSE;
  if (moved) { /* the peak as a point of the curve, between k - 1 and k or k and k + 1 */
    PetscReal w;
    PetscCall(Load(pw, g.x[1], &w));
    PetscCall(JRContBranchAdd(c, b, w, pw->a, total, 0.0, resm));
    *ins = g.s[1] < s1 ? k : k + 1;
    PetscCall(MoveLast(c, b, *ins));
    *wp = w;
    *Ap = g.f[1];
  }
  PetscCall(PetscFree(X));
  PetscFunctionReturn(0);
}

/* Response o's peak: the largest of its local maxima refined (RefineAt), every point that is a local maximum of the
   computed ones within 5% of the largest a candidate (on a folded or multi-peaked curve the largest point need not
   lie beside the largest maximum), the highest first and the others only where they may exceed the best so far */
static PetscErrorCode RefineOne(JRCont c, JRContBranch *b, PeakWork *pw, PetscInt o, PetscReal *wp, PetscReal *Ap)
{
  const PetscInt no = c->nout;
  PetscReal      amax = b->amp[o];
  PetscInt       k = 0, nc = 0, *cand;

  PetscFunctionBeginUser;
  for (PetscInt i = 1; i < b->np; i++)
    if (b->amp[i * no + o] > amax) {
      amax = b->amp[i * no + o];
      k    = i;
    }
  *wp = b->omega[k];
  *Ap = amax;
  PetscCall(PetscMalloc1(b->np + 1, &cand));
  for (PetscInt i = 1; i + 1 < b->np; i++) {
    const PetscReal ai = b->amp[i * no + o];
    if (ai >= 0.95 * amax && ai >= b->amp[(i - 1) * no + o] && ai >= b->amp[(i + 1) * no + o]) cand[nc++] = i;
  }
  for (PetscInt q = 0; q < nc; q++) { /* the highest candidate left first */
    PetscInt  j = q, ins = -1, t;
    PetscReal w = 0.0, A = 0.0;
    for (PetscInt r = q + 1; r < nc; r++)
      if (b->amp[cand[r] * no + o] > b->amp[cand[j] * no + o]) j = r;
    t       = cand[q];
    cand[q] = cand[j];
    cand[j] = t;
    PetscCall(RefineAt(c, b, pw, o, cand[q], q ? *Ap : -PETSC_MAX_REAL, &w, &A, &ins));
    if (A > *Ap) {
      *wp = w;
      *Ap = A;
    }
    for (PetscInt r = q + 1; r < nc && ins >= 0; r++) /* the inserted point moves the later ones */
      if (cand[r] >= ins) cand[r]++;
  }
  PetscCall(PetscFree(cand));
  PetscFunctionReturn(0);
}

/* JRContRefinePeaks - every response's peak on the curve b (b->wpk, b->apk), response 1's also in b->wpeak, b->apeak
   and b->kpeak; each peak inserted into the curve. The last response first, so that response 1's index holds. */
PetscErrorCode JRContRefinePeaks(JRCont c, JRContBranch *b)
{
  PeakWork *pw = c->pw;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(JR_ContPeak, 0, 0, 0, 0));
  b->refine_its = 0;
  Weights(c, b, pw);
  for (PetscInt o = c->nout - 1; o >= 0; o--) PetscCall(RefineOne(c, b, pw, o, &b->wpk[o], &b->apk[o]));
  PetscCall(PetscLogEventEnd(JR_ContPeak, 0, 0, 0, 0));
  b->kpeak = 0;
  for (PetscInt i = 1; i < b->np; i++)
    if (b->amp[i * c->nout] > b->amp[b->kpeak * c->nout]) b->kpeak = i;
  b->wpeak = b->wpk[0];
  b->apeak = b->apk[0];
  PetscFunctionReturn(0);
}

/* JRContChordError - the curve's point at the fraction t of the way from the last point of b to the candidate (a, w)
   (amplitude A at response 1), on the plane through that point of the chord normal to it, against linear
   interpolation of response 1 between the two (at its frequency where the frequency is monotone, else at the chord's
   point): the relative error; infinite when that point is not found. its: the Newton iterations spent. */
PetscErrorCode JRContChordError(JRCont c, JRContBranch *b, Vec a, PetscReal w, PetscReal A, PetscReal t, PetscReal *err, PetscInt *its)
{
  PeakWork          *pw = c->pw;
  const PetscInt     n = c->n, k = b->np - 1;
  const PetscScalar *x;
  PetscReal          n0 = 0, n1 = 0, s = 0, res, wm, Am, Ac, A0 = b->amp[k * c->nout], w0 = b->omega[k];
  PetscBool          ok;

  PetscFunctionBeginUser;
  PointX(c, b, k, pw->x0);
  PetscCall(VecGetArrayRead(a, &x));
  for (PetscInt i = 0; i < n; i++) {
    pw->d[i] = PetscRealPart(x[i]) - pw->x0[i];
    n0 += pw->x0[i] * pw->x0[i];
    n1 += PetscRealPart(x[i] * x[i]);
  }
  PetscCall(VecRestoreArrayRead(a, &x));
  pw->d[n] = w - w0;
  for (PetscInt i = 0; i < n; i++) pw->W[i] = 1.0 / PetscMax(PetscMax(n0, n1), PETSC_MIN_REAL);
  pw->W[n] = 1.0 / ((c->wmax - c->wmin) * (c->wmax - c->wmin));
  for (PetscInt i = 0; i <= n; i++) {
    s += pw->W[i] * pw->d[i] * pw->d[i];
    pw->xm[i] = pw->x0[i] + t * pw->d[i];
  }
  PetscCall(PetscLogEventBegin(JR_ContChord, 0, 0, 0, 0));
  PetscCall(SolveOnPlane(c, pw, t * s, 1e-6, pw->xm, &res, its, &ok)); /* the amplitude to about 1e-4: enough to judge the chord */
  PetscCall(PetscLogEventEnd(JR_ContChord, 0, 0, 0, 0));
  if (!ok) {
    *err = PETSC_INFINITY;
    PetscFunctionReturn(0);
  }
  PetscCall(Load(pw, pw->xm, &wm));
  PetscCall(JRContOutputAmplitude(c, wm, pw->a, 0, &Am));
  Ac = (1 - t) * A0 + t * A;
  if ((wm - w0) * (w - w0) > 0 && (w - wm) * (w - w0) > 0) Ac = A0 + (wm - w0) * (A - A0) / (w - w0);
  *err = PetscAbsReal(Am - Ac) / PetscMax(PetscMax(Am, Ac), PETSC_MIN_REAL);
  PetscFunctionReturn(0);
}

/* JRContPlaneScale - the scaling W of the planes of JRContPlaneBegin for curve b: the peaks' (amplitudes by the
   curve's largest, frequency by the range) */
PetscErrorCode JRContPlaneScale(JRCont c, JRContBranch *b)
{
  PetscFunctionBeginUser;
  Weights(c, b, c->pw);
  PetscFunctionReturn(0);
}

/* JRContPlaneBegin - the family of planes <x - x_k0, d>_W = s across the curve b from its point k0 (s = 0) to its point
   k1 (s = *S), d = x_k1 - x_k0, W set by JRContPlaneScale */
PetscErrorCode JRContPlaneBegin(JRCont c, JRContBranch *b, PetscInt k0, PetscInt k1, PetscReal *S)
{
  PeakWork *pw = c->pw;

  PetscFunctionBeginUser;
  PointX(c, b, k0, pw->x0);
  PointX(c, b, k1, pw->xm);
  for (PetscInt i = 0; i <= c->n; i++) pw->d[i] = pw->xm[i] - pw->x0[i];
  *S = PlaneCoordinate(pw, pw->xm);
  PetscFunctionReturn(0);
}

/* JRContPlaneCoordinate - s of the point x = (a, w) (n + 1) in the family of JRContPlaneBegin */
PetscReal JRContPlaneCoordinate(JRCont c, const PetscReal *x)
{
  return PlaneCoordinate(c->pw, x);
}

/* JRContPlanePoint - the curve's point on the plane s of the family (JRContPlaneBegin) by Newton from the guess x (n + 1;
   the point on return, its unknowns also in *a, the plane work's vector, valid until the next solve); *ok when found.
   Collective. */
PetscErrorCode JRContPlanePoint(JRCont c, PetscReal s, PetscReal *x, Vec *a, PetscInt *its, PetscBool *ok)
{
  PeakWork *pw = c->pw;
  PetscReal tol, res, w;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetResidualTolerance(c->hbm, &tol));
  PetscCall(SolveOnPlane(c, pw, s, 1e-3 * tol, x, &res, its, ok));
  PetscCall(Load(pw, x, &w));
  *a = pw->a;
  PetscFunctionReturn(0);
}

/* JRContTangentSign - at the solution (a, w) (a not the plane work's vector, or it), the sign of dw/ds along the curve
   in the direction of the family's normal d (JRContPlaneBegin): the tangent is t = (-J^-1 R_w, 1) up to its
   orientation, which <t, d>_W > 0 fixes, so the sign is that of <(-J^-1 R_w, 1), d>_W; 0 where J is singular.
   With sign(det J) it gives the sign of the bordered Jacobian's determinant, which folds do not change; detsign (may
   be NULL): sign(det J), from the same LU (0 where singular). Collective. */
PetscErrorCode JRContTangentSign(JRCont c, PetscReal w, Vec a, PetscInt *sign, PetscInt *detsign)
{
  PeakWork          *pw = c->pw;
  const PetscInt     n  = pw->n;
  const PetscScalar *j, *rw;
  PetscReal          q = 0;
  PetscBool          singular;

  PetscFunctionBeginUser;
  PetscCall(JRHBMComputeJacobian(c->hbm, w, a, pw->J, pw->Rw));
  PetscCall(MatDenseGetArrayRead(pw->J, &j));
  PetscCall(VecGetArrayRead(pw->Rw, &rw));
  for (PetscInt i = 0; i < n * n; i++) pw->B[i] = j[i];
  for (PetscInt i = 0; i < n; i++) pw->dx[i] = -rw[i];
  PetscCall(VecRestoreArrayRead(pw->Rw, &rw));
  PetscCall(MatDenseRestoreArrayRead(pw->J, &j));
  PetscCall(JRDenseSolve(n, pw->B, n, pw->lu, pw->piv, pw->dx, &singular));
  if (detsign) {
    PetscInt ds = singular ? 0 : 1;
    for (PetscInt i = 0; i < n && ds; i++) {
      if (pw->lu[i + i * n] < 0) ds = -ds;
      if (pw->piv[i] != i + 1) ds = -ds;
    }
    *detsign = ds;
  }
  if (singular) {
    *sign = 0;
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < n; i++) q += pw->W[i] * pw->dx[i] * pw->d[i];
  q += pw->W[n] * pw->d[n];
  *sign = q > 0 ? 1 : q < 0 ? -1 : 0;
  PetscFunctionReturn(0);
}
