/*
   The least-squares problems of the second reduction (src/reduce/fit.c): a Jenkins element's steady loop and energy
   per cycle, the residuals of a joint's tangential fit (free, and with the slip displacements fixed: convex), the
   search of the slip displacements, the fit coupled across joints, and the normal fit of jenkins_nv joints.
*/
#include <jointrom/private/fitimpl.h>
#include <petscblaslapack.h>

/* Steady Jenkins loop (spring k, slip force f) under u = a cos(theta_s), theta_s = 2 pi s / ns: F[s] += force,
   and, if not NULL, Fk[s] = dF/dk, Ff[s] = dF/df */
void JRFitJenkinsLoop(PetscReal k, PetscReal f, PetscReal a, PetscInt ns, PetscReal F[], PetscReal Fk[], PetscReal Ff[])
{
  for (PetscInt s = 0; s < ns; s++) {
    const PetscReal th = 2 * PETSC_PI * s / ns, u = a * PetscCosReal(th);
    PetscReal       F_, dk, df;
    if (k * a <= f) { /* never slips */
      F_ = k * u;
      dk = u;
      df = 0;
    } else if (2 * s <= ns) { /* u falls from a, where it slipped at +f */
      const PetscReal st = f - k * (a - u);
      if (st > -f) {
        F_ = st;
        dk = -(a - u);
        df = 1;
      } else {
        F_ = -f;
        dk = 0;
        df = -1;
      }
    } else { /* u rises from -a, where it slipped at -f */
      const PetscReal st = -f + k * (u + a);
      if (st < f) {
        F_ = st;
        dk = u + a;
        df = -1;
      } else {
        F_ = f;
        dk = 0;
        df = 1;
      }
    }
    F[s] += F_;
    if (Fk) Fk[s] = dk;
    if (Ff) Ff[s] = df;
  }
}

/* Energy dissipated per cycle by a Jenkins element at amplitude a, and its derivatives in k and f */
PetscReal JRFitJenkinsEnergy(PetscReal k, PetscReal f, PetscReal a, PetscReal *Ek, PetscReal *Ef)
{
  if (k * a <= f) {
    if (Ek) *Ek = 0;
    if (Ef) *Ef = 0;
    return 0;
  }
  if (Ek) *Ek = 4 * f * f / (k * k);
  if (Ef) *Ef = 4 * a - 8 * f / k;
  return 4 * f * (a - f / k);
}

PetscErrorCode JRFitTangentResidual(void *ctx, const PetscReal x[], PetscReal r[], PetscReal J[])
{
  TangentFit    *t  = (TangentFit *)ctx;
  const PetscInt ns = t->ns, nr = 4 * ns, ld = FitRows(t);
  PetscReal      fsum = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < ld * 2 * t->m; i++) J[i] = 0;
  for (PetscInt i = 0; i < nr; i++) r[i] = 0;
  for (PetscInt j = 0; j < 4; j++)
    for (PetscInt i = 0; i < t->m; i++) {
      JRFitJenkinsLoop(t->ks * x[i], t->fs * x[t->m + i], t->amp[j], ns, r + j * ns, t->Fk, t->Ff);
      for (PetscInt s = 0; s < ns; s++) {
        J[j * ns + s + i * ld]          = t->w[j] * t->ks * t->Fk[s];
        J[j * ns + s + (t->m + i) * ld] = t->w[j] * t->fs * t->Ff[s];
      }
    }
  for (PetscInt j = 0; j < 4; j++)
    for (PetscInt s = 0; s < ns; s++) r[j * ns + s] = t->w[j] * (r[j * ns + s] - t->target[j * ns + s]);
  for (PetscInt j = 0; j < t->ne; j++) {
    PetscReal E = 0;
    for (PetscInt i = 0; i < t->m; i++) {
      PetscReal Ek, Ef;
      E += JRFitJenkinsEnergy(t->ks * x[i], t->fs * x[t->m + i], t->ae[j], &Ek, &Ef);
      J[nr + j + i * ld]          = t->we[j] * t->ks * Ek / t->En[j];
      J[nr + j + (t->m + i) * ld] = t->we[j] * t->fs * Ef / t->En[j];
    }
    r[nr + j] = t->we[j] * (E - t->Et[j]) / t->En[j];
  }
  for (PetscInt i = 0; i < t->m; i++) { /* gross slip */
    fsum += t->fs * x[t->m + i];
    J[ld - 1 + (t->m + i) * ld] = t->wg * t->fs / t->ftot;
  }
  r[ld - 1] = t->wg * (fsum / t->ftot - 1);

  PetscFunctionReturn(0);
}

PetscErrorCode JRFitFixedResidual(void *ctx, const PetscReal y[], PetscReal r[], PetscReal J[])
{
  FixedFit      *ff = (FixedFit *)ctx;
  TangentFit    *t  = ff->t;
  const PetscInt m = t->m, ld = FitRows(t);

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < m; i++) {
    ff->x[i]     = t->fs * y[i] / (ff->delta[i] * t->ks);
    ff->x[m + i] = y[i];
  }
  PetscCall(JRFitTangentResidual(t, ff->x, r, ff->J2));
  for (PetscInt i = 0; i < m; i++)
    for (PetscInt q = 0; q < ld; q++) J[q + i * ld] = ff->J2[q + i * ld] * t->fs / (ff->delta[i] * t->ks) + ff->J2[q + (m + i) * ld];
  PetscFunctionReturn(0);
}

/* The residual columns of single elements (y = 1) of joint fit t at the slip displacements dc[0..nc), as the Gram
   system of the residual C y - b: G = C^T C (nc x nc), cg = C^T b, bb = b.b */
static PetscErrorCode CandidateGram(TangentFit *t, PetscInt nc, const PetscReal dc[], PetscReal G[], PetscReal cg[], PetscReal *bb)
{
  const PetscInt ld = FitRows(t), mt = t->m;
  PetscReal     *C, *b, *J, x[2] = {0, 0};

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc3(ld * nc, &C, ld, &b, 2 * ld, &J));
  t->m = 1;
  PetscCall(JRFitTangentResidual(t, x, b, J)); /* r(0) = -b */
  *bb = 0;
  for (PetscInt q = 0; q < ld; q++) b[q] = -b[q];
  for (PetscInt q = 0; q < ld; q++) *bb += b[q] * b[q];
  for (PetscInt c = 0; c < nc; c++) {
    x[0] = t->fs / (dc[c] * t->ks);
    x[1] = 1;
    PetscCall(JRFitTangentResidual(t, x, C + c * ld, J));
    for (PetscInt q = 0; q < ld; q++) C[q + c * ld] += b[q];
  }
  t->m = mt;
  JRGram(ld, nc, C, b, G, cg);
  PetscCall(PetscFree3(C, b, J));
  PetscFunctionReturn(0);
}

/* The candidate slip displacements of a joint: its m current values, then a log grid of ngrid over [dmin, dmax] */
#define NGRID 32

static void CandidateDeltas(PetscInt m, const PetscReal delta[], PetscReal dmin, PetscReal dmax, PetscReal dc[])
{
  for (PetscInt i = 0; i < m; i++) dc[i] = delta[i];
  for (PetscInt i = 0; i < NGRID; i++) dc[m + i] = dmin * PetscPowReal(dmax / dmin, i / (PetscReal)(NGRID - 1));
}

/* The slip displacements of the convex fit, chosen among candidates: the m start values and a log grid over the
   members' range. For each candidate element (y = 1) its residual column; the best set by exhaustive search
   (<= 20000 sets) or else by coordinate descent from the start: each set scored by its NNLS (JRGramNNLS). Every
   step is deterministic: the same on any ranks. delta[] in: the start; out: the best set; y: its forces. */
PetscErrorCode JRFitSearchDelta(TangentFit *t, PetscReal dmin, PetscReal dmax, PetscInt m, PetscReal delta[], PetscReal y[], PetscReal *cost)
{
  const PetscInt ngrid = NGRID, nc = ngrid + m;
  PetscReal     *dc, *G, *cg, bb = 0, best, yy[8];
  PetscInt       sel[8] = {0}, bsel[8] = {0};
  double         combos = 1;

  PetscFunctionBeginUser;
  PetscCheck(m <= 8, PETSC_COMM_SELF, PETSC_ERR_SUP, "-rom_elements %" PetscInt_FMT ": at most 8 elements per joint", m);
  PetscCall(PetscMalloc3(nc, &dc, nc * nc, &G, nc, &cg));
  CandidateDeltas(m, delta, dmin, dmax, dc);
  PetscCall(CandidateGram(t, nc, dc, G, cg, &bb));
  for (PetscInt i = 0; i < m; i++) combos *= (double)(ngrid - i) / (i + 1);
  for (PetscInt i = 0; i < m; i++) bsel[i] = i;
  PetscCall(JRGramNNLS(nc, G, cg, bb, m, bsel, y, &best));
  if (combos <= 20000) { /* every set of m grid values */
    for (PetscInt i = 0; i < m; i++) sel[i] = m + i;
    while (1) {
      PetscReal v;
      PetscInt  i;
      PetscCall(JRGramNNLS(nc, G, cg, bb, m, sel, yy, &v));
      if (v < best) {
        best = v;
        for (PetscInt k = 0; k < m; k++) bsel[k] = sel[k];
      }
      for (i = m - 1; i >= 0 && sel[i] == nc - m + i; i--) { }
      if (i < 0) break;
      sel[i]++;
      for (PetscInt k = i + 1; k < m; k++) sel[k] = sel[k - 1] + 1;
    }
  } else { /* coordinate descent over the grid from the start */
    PetscBool improved = PETSC_TRUE;
    for (PetscInt sweep = 0; sweep < 50 && improved; sweep++) {
      improved = PETSC_FALSE;
      for (PetscInt i = 0; i < m; i++) {
        for (PetscInt k = 0; k < m; k++) sel[k] = bsel[k];
        for (PetscInt c = m; c < nc; c++) {
          PetscReal v;
          PetscBool used = PETSC_FALSE;
          for (PetscInt k = 0; k < m; k++) used = (PetscBool)(used || bsel[k] == c);
          if (used) continue;
          sel[i] = c;
          PetscCall(JRGramNNLS(nc, G, cg, bb, m, sel, yy, &v));
          if (v < best * (1 - 1e-12)) {
            best = v;
            bsel[i] = c;
            improved = PETSC_TRUE;
          }
        }
      }
    }
  }
  for (PetscInt i = 0; i < m; i++) delta[i] = dc[bsel[i]];
  PetscCall(JRGramNNLS(nc, G, cg, bb, m, bsel, y, &best));
  *cost = PetscSqrtReal(PetscMax(best, 0.0));
  PetscCall(PetscFree3(dc, G, cg));
  PetscFunctionReturn(0);
}

/* The energy column of an element (force fs y, slip displacement delta) of joint k in the rows of all joints: per unit y */
static PetscReal CoupledColumn(const CoupledFit *cf, PetscInt k, PetscReal delta, PetscInt l)
{
  const PetscReal a = cf->u[k] * cf->am[l];
  return a > delta ? cf->w * 4 * cf->fx[k].t->fs * (a - delta) / cf->En[l] : 0.0;
}

PetscErrorCode JRFitCoupledResidual(void *ctx, const PetscReal y[], PetscReal r[], PetscReal J[])
{
  CoupledFit    *cf = (CoupledFit *)ctx;
  const PetscInt nr = CoupledRows(cf);

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < nr * cf->n; i++) J[i] = 0;
  for (PetscInt k = 0; k < cf->nj; k++) {
    const PetscInt ld = FitRows(cf->fx[k].t), mk = cf->off[k + 1] - cf->off[k];
    PetscCall(JRFitFixedResidual(&cf->fx[k], y + cf->off[k], cf->rj, cf->Jj));
    for (PetscInt q = 0; q < ld; q++) {
      r[cf->roff[k] + q] = cf->rj[q];
      for (PetscInt i = 0; i < mk; i++) J[cf->roff[k] + q + (cf->off[k] + i) * nr] = cf->Jj[q + i * ld];
    }
  }
  for (PetscInt l = 0; l < cf->na; l++) {
    const PetscInt R = cf->roff[cf->nj] + l;
    r[R]             = -cf->w * cf->Et[l] / cf->En[l];
    for (PetscInt k = 0; k < cf->nj; k++)
      for (PetscInt e = cf->off[k]; e < cf->off[k + 1]; e++) {
        const PetscReal v = CoupledColumn(cf, k, cf->fx[k].delta[e - cf->off[k]], l);
        r[R] += v * y[e];
        J[R + e * nr] = v;
      }
  }
  PetscFunctionReturn(0);
}

/* The slip displacements of all fitted joints together, by coordinate descent: each element's in turn over its
   joint's candidates (its current value and the log grid over [dlo, dhi] of the joint), the others fixed, every
   choice scored by the NNLS of all forces (JRActiveSetNNLS); sweeps until none improves. On return fx[k].delta hold the
   choice, y its forces; cost0 and cost: the residual norm before and after */
PetscErrorCode JRFitCoupledSearch(CoupledFit *cf, const PetscReal dlo[], const PetscReal dhi[], PetscReal y[], PetscReal *cost0, PetscReal *cost, PetscInt *sweeps)
{
  const PetscInt n = cf->n, na = cf->na;
  PetscInt      *nc, *coff, *sel, ncand = 0;
  PetscReal    **G, **cgj, *bbj, *dc, *H, *HH, *Hb, *bg, bbs = 0, *A, *c, best, v;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc7(cf->nj, &nc, cf->nj + 1, &coff, n, &sel, cf->nj, &G, cf->nj, &cgj, cf->nj, &bbj, na, &bg));
  coff[0] = 0;
  for (PetscInt k = 0; k < cf->nj; k++) {
    nc[k]       = cf->off[k + 1] - cf->off[k] + NGRID;
    coff[k + 1] = coff[k] + nc[k];
  }
  ncand = coff[cf->nj];
  PetscCall(PetscMalloc6(ncand, &dc, na * ncand, &H, ncand * ncand, &HH, ncand, &Hb, n * n, &A, n, &c));
  for (PetscInt k = 0; k < cf->nj; k++) { /* each joint's own rows: Gram system of its candidates */
    const PetscInt mk = cf->off[k + 1] - cf->off[k];
    CandidateDeltas(mk, cf->fx[k].delta, dlo[k], dhi[k], dc + coff[k]);
    PetscCall(PetscMalloc2(nc[k] * nc[k], &G[k], nc[k], &cgj[k]));
    PetscCall(CandidateGram(cf->fx[k].t, nc[k], dc + coff[k], G[k], cgj[k], &bbj[k]));
    bbs += bbj[k];
    for (PetscInt i = 0; i < mk; i++) sel[cf->off[k] + i] = i;
    for (PetscInt a = 0; a < nc[k]; a++)
      for (PetscInt l = 0; l < na; l++) H[l + (coff[k] + a) * na] = CoupledColumn(cf, k, dc[coff[k] + a], l);
  }
  for (PetscInt l = 0; l < na; l++) {
    bg[l] = cf->w * cf->Et[l] / cf->En[l];
    bbs += bg[l] * bg[l];
  }
  JRGram(na, ncand, H, bg, HH, Hb); /* the rows of all joints: every pair of candidates */
#define SCORE(val) \
  do { \
    for (PetscInt k = 0; k < cf->nj; k++) \
      for (PetscInt e = cf->off[k]; e < cf->off[k + 1]; e++) { \
        const PetscInt a = coff[k] + sel[e]; \
        c[e]             = cgj[k][sel[e]] + Hb[a]; \
        for (PetscInt k2 = 0; k2 < cf->nj; k2++) \
          for (PetscInt e2 = cf->off[k2]; e2 < cf->off[k2 + 1]; e2++) A[e + e2 * n] = HH[a + (coff[k2] + sel[e2]) * ncand] + (k2 == k ? G[k][sel[e] + sel[e2] * nc[k]] : 0.0); \
      } \
    PetscCall(JRActiveSetNNLS(n, A, c, y, &v)); \
    val = bbs + v; \
  } while (0)
  SCORE(best);
  *cost0 = PetscSqrtReal(PetscMax(best, 0.0));
  for (*sweeps = 0; *sweeps < 50;) {
    PetscBool improved = PETSC_FALSE;
    (*sweeps)++;
    for (PetscInt k = 0; k < cf->nj; k++)
      for (PetscInt e = cf->off[k]; e < cf->off[k + 1]; e++) {
        const PetscInt s0 = sel[e];
        PetscInt       bs = s0;
        for (PetscInt a = 0; a < nc[k]; a++) {
          PetscBool used = PETSC_FALSE;
          for (PetscInt e2 = cf->off[k]; e2 < cf->off[k + 1]; e2++) used = (PetscBool)(used || sel[e2] == a);
          if (used) continue;
          sel[e] = a;
          SCORE(v);
          if (v < best - 1e-12 * bbs) { /* round-off of the target does not count */
            best     = v;
            bs       = a;
            improved = PETSC_TRUE;
          }
        }
        sel[e] = bs;
      }
    if (!improved) break;
  }
  SCORE(best);
#undef SCORE
  *cost = PetscSqrtReal(PetscMax(best, 0.0));
  for (PetscInt k = 0; k < cf->nj; k++) {
    for (PetscInt e = cf->off[k]; e < cf->off[k + 1]; e++) cf->fx[k].delta[e - cf->off[k]] = dc[coff[k] + sel[e]];
    PetscCall(PetscFree2(G[k], cgj[k]));
  }
  PetscCall(PetscFree6(dc, H, HH, Hb, A, c));
  PetscCall(PetscFree7(nc, coff, sel, G, cgj, bbj, bg));
  PetscFunctionReturn(0);
}

PetscErrorCode JRFitNormalResidual(void *ctx, const PetscReal x[], PetscReal r[], PetscReal J[])
{
  NormalFit *t = (NormalFit *)ctx;

  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < t->nv; s++) {
    r[s] = -t->target[s];
    for (PetscInt i = 0; i < t->m; i++) {
      const PetscReal N = t->n0[i] + t->kns * x[i] * t->v[s];
      r[s] += PetscMax(N, 0.0);
      J[s + i * t->nv] = N > 0 ? t->w * t->kns * t->v[s] : 0.0;
    }
    r[s] *= t->w;
  }
  PetscFunctionReturn(0);
}
