/*
   One joint's fit in the second reduction (src/reduce/fit.c): its rows (loops, energies, stiffness), the start from
   the members' groups, the convex fit of the slip forces, the refinement, the elements kept, the normal fit of a
   jenkins_nv joint and the joint's report line.
*/
#include <jointrom/private/fitimpl.h>
#include <petscblaslapack.h>

/* Joint j's sums over its members, the fit's scales and its loops' amplitudes: from the slip-force distribution, the
   slip displacements below which the fractions -rom_fit_fractions of the slip force lie, and half the first (stuck) */
static PetscErrorCode JointSetUp(FitCtx *ctx, PetscInt j)
{
  const JRElements  *nn = ctx->nn;
  const MemberDelta *d  = ctx->md + ctx->joff[j];
  const PetscInt     nm = ctx->jn[j], mj = PetscMin(ctx->jm[j], nm);
  JointFit          *f  = &ctx->jf[j];
  TangentFit        *t  = &f->t;
  PetscReal          ftot = 0, ktot = 0, mu = 0, n0s = 0, knsum = 0, c = 0;
  PetscInt           k = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < nm; i++) {
    const PetscInt e = d[i].e;
    ftot += ctx->mf[e];
    ktot += ctx->mk[e];
    mu += nn->mu[e] * nn->n0[e];
    n0s += nn->n0[e];
    knsum += nn->kn[e];
  }
  mu /= n0s;
  PetscCall(PetscMemzero(f, sizeof(*f)));
  f->m    = mj;
  f->mu   = mu;
  f->kn   = knsum;
  t->m    = mj;
  t->ns   = ctx->fit->ns;
  t->ks   = ktot / mj;
  t->fs   = ftot / mj;
  t->ftot = ftot;
  t->wg   = ctx->fit->wgross;
  for (PetscInt a = 0; a < 3; a++) {
    while (k < nm - 1 && c + ctx->mf[d[k].e] < ctx->fit->fr[a] * ftot) {
      c += ctx->mf[d[k].e];
      k++;
    }
    t->amp[a] = d[k].delta;
  }
  t->amp[3] = 0.5 * d[0].delta;
  PetscFunctionReturn(0);
}

/* Joint j's energy rows: 6 over its own range, from the first slips (-rom_fit_energy_from) to its gross-slip
   amplitude, each relative to its own; with a case, NCASE over the joint's range of motion over the levels (and a
   factor 2 either side), each amplitude's error relative to all the energy dissipated there (= put in, at resonance) */
static PetscErrorCode TangentEnergyRows(FitCtx *ctx, PetscInt j)
{
  const MemberDelta *d  = ctx->md + ctx->joff[j];
  const PetscInt     nm = ctx->jn[j];
  const JRROMCase   *cs = ctx->cs;
  TangentFit        *t  = &ctx->jf[j].t;
  PetscReal          c = 0, a0;
  PetscInt           k = 0;

  PetscFunctionBeginUser;
  while (k < nm - 1 && c + ctx->mf[d[k].e] < ctx->fit->efrom * t->ftot) {
    c += ctx->mf[d[k].e];
    k++;
  }
  a0    = PetscMax(d[k].delta, 1.0001 * d[0].delta);
  t->ne = 6 + (ctx->amod ? NCASE : 0);
  PetscCall(PetscMalloc4(t->ne, &t->ae, t->ne, &t->Et, t->ne, &t->En, t->ne, &t->we));
  for (PetscInt i = 0; i < t->ne; i++) {
    if (i < 6) { /* relative, over the joint's range */
      t->ae[i] = a0 * PetscPowReal(t->amp[2] / a0, i / 5.0);
      t->we[i] = 0.05;
    } else { /* the case */
      const PetscReal uj = PetscAbsReal(cs->ujoint[j]), am = JRFitCaseAmplitude(ctx, i - 6);
      t->ae[i] = uj * am;
      t->we[i] = ctx->fit->wcase / PetscSqrtReal((PetscReal)NCASE);
      t->En[i] = cs->damp * am * am + JRFitCaseDissipation(ctx, am);
    }
    t->Et[i] = 0;
    for (PetscInt q = 0; q < nm; q++) t->Et[i] += JRFitJenkinsEnergy(ctx->mk[d[q].e], ctx->mf[d[q].e], t->ae[i], NULL, NULL);
    if (i < 6) t->En[i] = t->Et[i];
    else if (ctx->nvin) t->Et[i] += ctx->nvin[j * NCASE + i - 6]; /* the normal-load variation (JRFitNormalVariation) */
    if (!(t->En[i] > 0) || !(t->ae[i] > 0)) { /* nothing dissipated, nothing put in: no row */
      t->En[i] = 1;
      t->we[i] = 0;
    }
  }
  PetscFunctionReturn(0);
}

/* Joint j's target loops, its members', at the four amplitudes, each weighted by its size; the stuck one by
   -rom_fit_stiffness_weight */
static PetscErrorCode TangentLoops(FitCtx *ctx, PetscInt j)
{
  const MemberDelta *d  = ctx->md + ctx->joff[j];
  const PetscInt     nm = ctx->jn[j];
  TangentFit        *t  = &ctx->jf[j].t;
  const PetscInt     ns = t->ns;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(4 * ns, &t->target));
  PetscCall(PetscMalloc2(ns, &t->Fk, ns, &t->Ff));
  for (PetscInt a = 0; a < 4; a++) {
    PetscReal fmax = 0;
    for (PetscInt i = 0; i < nm; i++) JRFitJenkinsLoop(ctx->mk[d[i].e], ctx->mf[d[i].e], t->amp[a], ns, t->target + a * ns, NULL, NULL);
    for (PetscInt s = 0; s < ns; s++) fmax = PetscMax(fmax, PetscAbsReal(t->target[a * ns + s]));
    t->w[a] = (a == 3 ? ctx->fit->wstiff : 1.0) / (fmax * PetscSqrtReal(4.0 * ns)); /* the stiffness weighs most */
  }
  PetscFunctionReturn(0);
}

/* Joint j's start: m groups of members in equal steps of log(delta) (from the first slips to gross slip), each group
   one element with the group's sums of kt and f: exact at full stick and at gross slip */
static PetscErrorCode TangentStart(FitCtx *ctx, PetscInt j)
{
  const MemberDelta *d  = ctx->md + ctx->joff[j];
  const PetscInt     nm = ctx->jn[j];
  JointFit          *f  = &ctx->jf[j];
  const TangentFit  *t  = &f->t;
  const PetscInt     mj = f->m;
  const PetscReal    l0 = PetscLogReal(d[0].delta), l1 = PetscLogReal(d[nm - 1].delta);
  PetscReal         *x;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(3 * mj, &x));
  for (PetscInt i = 0; i < nm; i++) {
    const PetscInt e = d[i].e;
    PetscInt       g = l1 > l0 ? (PetscInt)(mj * (PetscLogReal(d[i].delta) - l0) / (l1 - l0)) : (mj * i) / nm;
    g                = PetscMin(PetscMax(g, 0), mj - 1);
    if (nm <= ctx->jm[j]) g = i;
    x[g] += ctx->mk[e] / t->ks;
    x[mj + g] += ctx->mf[e] / t->fs;
  }
  for (PetscInt g = 0; g < mj; g++) /* an empty group: a small element between its neighbours */
    if (x[g] == 0) {
      const PetscReal dl = PetscExpReal(l0 + (g + 0.5) * (l1 - l0) / mj);
      x[mj + g]          = 1e-3;
      x[g]               = 1e-3 * t->fs / (dl * t->ks);
    }
  f->x = x;
  PetscFunctionReturn(0);
}

/* The residual norm of a fixed fit at y */
static PetscErrorCode FixedNorm(FixedFit *fx, const PetscReal y[], PetscReal *norm)
{
  const PetscInt ld = FitRows(fx->t);
  PetscReal     *r0, *J0, s = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(ld, &r0, ld * fx->t->m, &J0));
  PetscCall(JRFitFixedResidual(fx, y, r0, J0));
  for (PetscInt i = 0; i < ld; i++) s += r0[i] * r0[i];
  *norm = PetscSqrtReal(s);
  PetscCall(PetscFree2(r0, J0));
  PetscFunctionReturn(0);
}

/* Joint j's convex fit: the slip displacements of the start's groups (sum f / sum kt of each log-width group of
   members), or the best of the candidates over [dlo, dhi] (-rom_fit_search), fixed; the forces fitted. rms0: the
   residual of the groups it started from */
static PetscErrorCode FitConvex(FitCtx *ctx, PetscInt j)
{
  const MemberDelta *d  = ctx->md + ctx->joff[j];
  const PetscInt     nm = ctx->jn[j];
  const JRROMCase   *cs = ctx->cs;
  JointFit          *f  = &ctx->jf[j];
  TangentFit        *t  = &f->t;
  const PetscInt     mj = f->m;
  PetscReal         *x  = f->x, *y, rsearch, rms0, rms;
  PetscInt           its1 = 0;
  FixedFit           fx;
  JRLSQ              q;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc4(mj, &fx.delta, 2 * mj, &fx.x, FitRows(t) * 2 * mj, &fx.J2, mj, &y));
  fx.t = t;
  for (PetscInt i = 0; i < mj; i++) {
    fx.delta[i] = t->fs * x[mj + i] / (t->ks * x[i]);
    y[i]        = x[mj + i];
  }
  PetscCall(FixedNorm(&fx, y, &f->rms0));
  f->dlo = ctx->amod ? PetscMin(d[0].delta, 0.1 * PetscAbsReal(cs->ujoint[j]) * ctx->amin) : d[0].delta;
  f->dhi = PetscMin(d[nm - 1].delta, PetscMax(t->amp[2], ctx->amod ? 4 * PetscAbsReal(cs->ujoint[j]) * ctx->amax : 0.0));
  if (ctx->fit->search) PetscCall(JRFitSearchDelta(t, f->dlo, f->dhi, mj, fx.delta, y, &rsearch));
  for (PetscInt i = 0; i < mj; i++) y[i] *= 1 + ctx->fit->perturb * (i % 3 == 0 ? 1.0 : i % 3 == 1 ? -1.0 : 0.5);
  q.nx  = mj;
  q.nr  = FitRows(t);
  q.fn  = JRFitFixedResidual;
  q.ctx = &fx;
  PetscCall(JRLSQSolve(&q, y, 0.0, &rms0, &rms, &its1));
  for (PetscInt i = 0; i < mj; i++) {
    x[i]      = t->fs * y[i] / (fx.delta[i] * t->ks);
    x[mj + i] = y[i];
  }
  f->rms = rms;
  f->its = its1;
  PetscCall(PetscMalloc1(mj, &t->delta));
  PetscCall(PetscArraycpy(t->delta, fx.delta, mj));
  PetscCall(PetscFree4(fx.delta, fx.x, fx.J2, y));
  PetscFunctionReturn(0);
}

/* -rom_fit_refine: joint j's slip displacements free too, from its convex fit (not convex) */
static PetscErrorCode FitRefine(FitCtx *ctx, PetscInt j)
{
  JointFit      *f  = &ctx->jf[j];
  TangentFit    *t  = &f->t;
  const PetscInt mj = f->m;
  PetscReal     *x  = f->x, r1, rms;
  PetscInt       its1 = 0;
  JRLSQ          q;

  PetscFunctionBeginUser;
  for (PetscInt g = 0; g < mj; g++) {
    x[g]      = PetscMax(x[g], 1e-8);
    x[mj + g] = PetscMax(x[mj + g], 1e-8);
  }
  q.nx  = 2 * mj;
  q.nr  = FitRows(t);
  q.fn  = JRFitTangentResidual;
  q.ctx = t;
  PetscCall(JRLSQSolve(&q, x, 1e-10, &r1, &rms, &its1));
  f->rms = rms;
  f->its += its1;
  for (PetscInt g = 0; g < mj; g++) t->delta[g] = t->fs * x[mj + g] / (t->ks * x[g]);
  PetscFunctionReturn(0);
}

/* A joint with no more members than elements: the members themselves (the start), exact; rms: its loops' residual */
static PetscErrorCode FitExact(FitCtx *ctx, PetscInt j)
{
  JointFit   *f = &ctx->jf[j];
  TangentFit *t = &f->t;
  PetscReal  *r, *J, rms = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(FitRows(t), &r, FitRows(t) * 2 * f->m, &J));
  PetscCall(JRFitTangentResidual(t, f->x, r, J));
  for (PetscInt i = 0; i < 4 * t->ns; i++) rms += r[i] * r[i];
  rms     = PetscSqrtReal(rms);
  f->rms  = rms;
  f->rms0 = rms;
  PetscCall(PetscFree2(r, J));
  PetscFunctionReturn(0);
}

/* Joint j's own fit (JointFit): kt_i, f_i of its elements */
/* The distinct slip displacements among joint j's members (sorted; equal to 1e-6): more elements than these would share
   slip displacements, and the split of force between such elements is not unique */
static PetscInt DistinctDeltas(const FitCtx *ctx, PetscInt j)
{
  const MemberDelta *d = ctx->md + ctx->joff[j];
  PetscInt           k = ctx->jn[j] > 0;
  for (PetscInt i = 1, l = 0; i < ctx->jn[j]; i++)
    if (d[i].delta > (1 + 1e-6) * d[l].delta) {
      l = i;
      k++;
    }
  return k;
}

PetscErrorCode JRFitJoint(FitCtx *ctx, PetscInt j)
{
  const PetscInt nd = ctx->fit->mmax ? DistinctDeltas(ctx, j) : 0;

  PetscFunctionBeginUser;
  for (;;) {
    PetscCall(JointSetUp(ctx, j));
    PetscCall(TangentEnergyRows(ctx, j));
    PetscCall(TangentLoops(ctx, j));
    PetscCall(TangentStart(ctx, j));
    if (ctx->jn[j] > ctx->jm[j]) {
      PetscCall(FitConvex(ctx, j));
      if (ctx->fit->refine) PetscCall(FitRefine(ctx, j));
    } else PetscCall(FitExact(ctx, j));
    /* -rom_fit_elements_max: one element more while the loops fit worse than -rom_fit_loop_tol, up to the members'
       distinct slip displacements */
    if (!(ctx->jf[j].rms > ctx->fit->looptol && ctx->jm[j] < ctx->fit->mmax && ctx->jm[j] < nd)) break;
    PetscCall(JRFitJointFitDestroy(&ctx->jf[j]));
    ctx->jm[j]++;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode JRFitJointFitDestroy(JointFit *f)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(f->x));
  PetscCall(PetscFree(f->t.target));
  PetscCall(PetscFree2(f->t.Fk, f->t.Ff));
  PetscCall(PetscFree4(f->t.ae, f->t.Et, f->t.En, f->t.we));
  PetscCall(PetscFree(f->t.delta));
  PetscFunctionReturn(0);
}

/* -rom_joint_motion mode, jenkins_nv: joint j's open members (a gap: n0 <= 0), which close at large amplitude: up to
   m elements by gap, after its fitted ones */
static PetscErrorCode OpenMembers(FitCtx *ctx, PetscInt j)
{
  const JRElements *nn = ctx->nn;
  const PetscInt    e0 = ctx->cnt + ctx->nel[j];
  PetscInt          no = 0, ng;
  MemberDelta      *od;

  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < nn->n; e++) no += (nn->joint[e] == j && !(nn->n0[e] > 0) && nn->kn[e] > 0);
  ng = PetscMin(ctx->m, no);
  if (!ng) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(no, &od));
  for (PetscInt e = 0, i = 0; e < nn->n; e++)
    if (nn->joint[e] == j && !(nn->n0[e] > 0) && nn->kn[e] > 0) {
      od[i].e       = e;
      od[i++].delta = -nn->n0[e] / nn->kn[e];
    }
  qsort(od, (size_t)no, sizeof(MemberDelta), JRFitCompareDelta);
  PetscCall(JRFitOpenPoints(ctx, od, no, ng, e0));
  for (PetscInt g = 0; g < ng; g++) { /* no slip force; at their own motion */
    ctx->ef[e0 + g] = 0;
    ctx->er[e0 + g] = 1;
  }
  PetscCall(PetscFree(od));
  ctx->nel[j] += ng;
  PetscFunctionReturn(0);
}

/* Joint j's reduced elements (from ctx->cnt on) from its fit: those the fit left without force carry nothing and are
   dropped; with -rom_joint_motion linear or mode, their points; mode, jenkins_nv: the open members' elements */
PetscErrorCode JRFitJointElements(FitCtx *ctx, PetscInt j)
{
  JointFit        *f  = &ctx->jf[j];
  const TangentFit *t = &f->t;
  const PetscInt   m0 = f->m, e0 = ctx->cnt;
  PetscReal       *x  = f->x;
  PetscInt         mj = 0;

  PetscFunctionBeginUser;
  if (!ctx->jn[j]) { /* open pairs alone: their gap elements */
    ctx->nel[j] = 0;
    PetscCall(OpenMembers(ctx, j));
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < m0; i++)
    if (x[m0 + i] > 1e-9) {
      x[mj]          = x[i];
      x[2 * m0 + mj] = x[m0 + i]; /* forces behind the stiffnesses, shifted below */
      mj++;
    }
  for (PetscInt i = 0; i < mj; i++) x[mj + i] = x[2 * m0 + i];
  for (PetscInt i = 0; i < mj; i++) {
    ctx->ek[e0 + i]  = t->ks * x[i];
    ctx->ef[e0 + i]  = t->fs * x[mj + i];
    ctx->en0[e0 + i] = ctx->ef[e0 + i] / f->mu;
    ctx->emu[e0 + i] = f->mu;
    ctx->ekn[e0 + i] = 0;
  }
  ctx->nel[j] = mj;
  if (ctx->spread) PetscCall(JRFitSpreadPoints(ctx, j, mj));
  if (ctx->modef) PetscCall(JRFitModePoints(ctx, j, mj));
  if (ctx->modef && ctx->nv) PetscCall(OpenMembers(ctx, j));
  PetscFunctionReturn(0);
}

/* jenkins_nv (not mode): joint j's normal stiffnesses kn_i (the thesis's kv) fitted to its normal load-motion curve
   sum_e max(n0_e + kn_e v, 0) over v from the separation of every member to as much compression */
PetscErrorCode JRFitNormal(FitCtx *ctx, PetscInt j)
{
  const JRElements  *nn = ctx->nn;
  const MemberDelta *d  = ctx->md + ctx->joff[j];
  const PetscInt     nm = ctx->jn[j], mj = ctx->nel[j], ns = ctx->fit->ns;
  JointFit          *f  = &ctx->jf[j];
  const PetscReal    ftot = f->t.ftot;
  NormalFit          nf;
  PetscReal          vsep = 0, nmx = 0, c = 0, *xn;
  JRLSQ              q;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&nf, sizeof(nf)));
  for (PetscInt e = 0; e < nn->n; e++)
    if (nn->joint[e] == j && nn->kn[e] > 0) vsep = PetscMax(vsep, PetscAbsReal(nn->n0[e]) / nn->kn[e]);
  nf.m   = mj;
  nf.nv  = 2 * ns + 1;
  nf.n0  = ctx->en0 + ctx->cnt;
  nf.kns = f->kn / mj;
  PetscCall(PetscMalloc3(nf.nv, &nf.v, nf.nv, &nf.target, mj, &xn));
  for (PetscInt s = 0; s < nf.nv; s++) {
    nf.v[s]      = vsep * (2.0 * s / (nf.nv - 1) - 1.0);
    nf.target[s] = 0;
    for (PetscInt e = 0; e < nn->n; e++)
      if (nn->joint[e] == j) nf.target[s] += PetscMax(nn->n0[e] + nn->kn[e] * nf.v[s], 0.0);
    nmx = PetscMax(nmx, nf.target[s]);
  }
  nf.w = 1.0 / (nmx * PetscSqrtReal((PetscReal)nf.nv));
  for (PetscInt i = 0; i < mj; i++) xn[i] = 0;
  for (PetscInt i = 0; i < nm; i++) { /* start: the groups' normal stiffness, as for kt */
    const PetscInt e = d[i].e;
    PetscInt       g = nm <= ctx->m ? i : PetscMin(PetscMax((PetscInt)(mj * (c + 0.5 * ctx->mf[e]) / ftot), 0), mj - 1);
    xn[g] += nn->kn[e] / nf.kns;
    c += ctx->mf[e];
  }
  for (PetscInt g = 0; g < mj; g++) xn[g] = PetscMax(xn[g], 1e-3);
  q.nx  = mj;
  q.nr  = nf.nv;
  q.fn  = JRFitNormalResidual;
  q.ctx = &nf;
  PetscCall(JRLSQSolve(&q, xn, 1e-10, &f->nrms0, &f->nrms, &f->nits));
  for (PetscInt i = 0; i < mj; i++) ctx->ekn[ctx->cnt + i] = nf.kns * xn[i];
  PetscCall(PetscFree3(nf.v, nf.target, xn));
  PetscFunctionReturn(0);
}

/* Joint j's line (rom joint ...), and its loops at the three amplitudes in the CSV: the members' and its elements' */
PetscErrorCode JRFitJointReport(FitCtx *ctx, PetscInt j)
{
  const JointFit   *f  = &ctx->jf[j];
  const TangentFit *t  = &f->t;
  const PetscInt    ns = t->ns, mj = ctx->nel[j], e0 = ctx->cnt;
  PetscReal        *Fr;

  PetscFunctionBeginUser;
  if (!ctx->jn[j]) {
    PetscCall(JRFitSay(ctx->quiet, ctx->comm, "rom joint %" PetscInt_FMT " members 0 elements %" PetscInt_FMT " (open pairs alone: gap elements)\n", j, mj));
    PetscFunctionReturn(0);
  }
  PetscCall(JRFitSay(ctx->quiet, ctx->comm, "rom joint %" PetscInt_FMT " members %" PetscInt_FMT " elements %" PetscInt_FMT " amplitudes_m %.4e %.4e %.4e loop_residual %.3e start %.3e tao_its %" PetscInt_FMT, j, ctx->jn[j], mj, (double)t->amp[0], (double)t->amp[1], (double)t->amp[2], (double)f->rms, (double)f->rms0, f->its));
  if (ctx->nv) PetscCall(JRFitSay(ctx->quiet, ctx->comm, " normal_residual %.3e start %.3e tao_its %" PetscInt_FMT, (double)f->nrms, (double)f->nrms0, f->nits));
  PetscCall(JRFitSay(ctx->quiet, ctx->comm, "\n"));
  if (!ctx->fp) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(ns, &Fr));
  for (PetscInt a = 0; a < 3; a++) {
    for (PetscInt s = 0; s < ns; s++) Fr[s] = 0;
    for (PetscInt i = 0; i < mj; i++) JRFitJenkinsLoop(ctx->ek[e0 + i], ctx->ef[e0 + i], t->amp[a], ns, Fr, NULL, NULL);
    for (PetscInt s = 0; s <= ns; s++) fprintf(ctx->fp, "%" PetscInt_FMT ",%" PetscInt_FMT ",%.9e,%.9e,%.9e\n", j, a, (double)(t->amp[a] * PetscCosReal(2 * PETSC_PI * s / ns)), (double)t->target[a * ns + s % ns], (double)Fr[s % ns]);
  }
  PetscCall(PetscFree(Fr));
  PetscFunctionReturn(0);
}
