/*
   JRHBM's condensation onto the joints (-hbm_condense): a reduced model's linear part solved exactly for the joints'
   motions, which become the unknowns. Per harmonic h, in complex form z = as + i ac, the linear part is
       Z_h(w) = Kg (1 + i gamma) - (h w)^2 Mm + i h w Cm   (the mean: Kg + pin),
   with Kg the structure's own stiffness (Km less the stuck springs that the stuck basis holds). When V^T Cm V is
   diagonal for the eigenvectors V of (Kg, Mm) (no viscous damping, or proportional), Z_h^-1 = V diag(1/z_k) V^T with
   z_k = lam_k (1 + i gamma) - (h w)^2 + i h w c_k. Every element of a reduced model moves with one of the nq
   condensed rows Q (its joint's), so with x = Q a the joints' motions and g(x) the elements' forces summed on those
   rows, a = Z^-1 (F fm - Q^T g) and
       r_h(x) = x_h + G_h g_h(x) - F xF_h,   G_h = Q Z_h^-1 Q^T (nq x nq),  xF_1 = Q Z_1^-1 fm,
   the modal equations with the modes eliminated exactly: nq (2H+1) unknowns instead of nm (2H+1).
*/
#include <jointrom/private/hbmimpl.h>

/* G_h, dG_h/dw, xF_h, dxF_h/dw (re, im; column-major, symmetric) and 1/z_k at frequency w, kept */
static PetscErrorCode CondBlocks(JRHBM h, PetscReal w)
{
  const PetscInt nq = h->nq, nm = h->nm, bs = 4 * nq * nq + 4 * nq, np = nq * (nq + 1) / 2 + nq;
  PetscReal     *dr, *di, *o;

  PetscFunctionBeginUser;
  if (h->wq_ok && h->wq == w) PetscFunctionReturn(0);
  if (!h->QQ) { /* once: the products of the joints' modal rows, pairs r <= c then each row with V^T fm */
    PetscCall(PetscMalloc2(nm * np, &h->QQ, 2 * nm + 4 * np, &h->cb));
    for (PetscInt k = 0; k < nm; k++) {
      PetscReal *q = h->QQ + k * np;
      for (PetscInt c = 0; c < nq; c++)
        for (PetscInt r = 0; r <= c; r++) *q++ = h->QV[r * nm + k] * h->QV[c * nm + k];
      for (PetscInt r = 0; r < nq; r++) *q++ = h->QV[r * nm + k] * h->VF[k];
    }
  }
  dr = h->cb;
  di = dr + nm;
  o  = di + nm; /* 4 x np: sums over the modes of the products times 1/z, d(1/z)/dw (re, im) */
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    PetscReal      *Gr = h->Gb + (hh - 1) * bs, *Gi = Gr + nq * nq, *dGr = Gi + nq * nq, *dGi = dGr + nq * nq;
    PetscReal      *xFr = dGi + nq * nq, *xFi = xFr + nq, *dxFr = xFi + nq, *dxFi = dxFr + nq;
    PetscReal      *ir = h->inv + 2 * (hh - 1) * nm, *ii = ir + nm;
    PetscReal      *o0 = o, *o1 = o + np, *o2 = o + 2 * np, *o3 = o + 3 * np;
    const PetscReal s  = hh * w;
    for (PetscInt k = 0; k < nm; k++) {
      const PetscReal zr = h->lamv[k] - s * s, zi = h->gamma * h->lamv[k] + s * h->cv[k], den = zr * zr + zi * zi;
      const PetscReal dzr = -2.0 * s * hh, dzi = hh * h->cv[k]; /* dz/dw */
      PetscReal       sr, si;
      ir[k] = zr / den;
      ii[k] = -zi / den;
      sr    = ir[k] * ir[k] - ii[k] * ii[k]; /* (1/z)^2 */
      si    = 2.0 * ir[k] * ii[k];
      dr[k] = -(sr * dzr - si * dzi); /* d(1/z)/dw = -(1/z)^2 dz/dw */
      di[k] = -(sr * dzi + si * dzr);
    }
    PetscCall(PetscArrayzero(o, 4 * np));
    for (PetscInt k = 0; k < nm; k++) { /* mode by mode: the inner loop runs over independent sums (vectorised) */
      const PetscReal *q = h->QQ + k * np, a = ir[k], b = ii[k], c = dr[k], d = di[k];
      for (PetscInt p = 0; p < np; p++) {
        o0[p] += q[p] * a;
        o1[p] += q[p] * b;
        o2[p] += q[p] * c;
        o3[p] += q[p] * d;
      }
    }
    for (PetscInt c = 0, p = 0; c < nq; c++)
      for (PetscInt r = 0; r <= c; r++, p++) {
        Gr[r + c * nq] = Gr[c + r * nq] = o0[p];
        Gi[r + c * nq] = Gi[c + r * nq] = o1[p];
        dGr[r + c * nq] = dGr[c + r * nq] = o2[p];
        dGi[r + c * nq] = dGi[c + r * nq] = o3[p];
      }
    for (PetscInt r = 0, p = nq * (nq + 1) / 2; r < nq; r++, p++) { /* the force enters the first harmonic only */
      xFr[r]  = hh == 1 ? o0[p] : 0.0;
      xFi[r]  = hh == 1 ? o1[p] : 0.0;
      dxFr[r] = hh == 1 ? o2[p] : 0.0;
      dxFi[r] = hh == 1 ? o3[p] : 0.0;
    }
  }
  PetscCall(PetscLogFlops(8.0 * h->H * nm * np));
  h->wq    = w;
  h->wq_ok = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Condensed: res holds g(x) on entry and r(x) on exit; jac (if not NULL) dg/dx on entry and I + G dg/dx on exit;
   dw (if not NULL) gets dr/dw */
PetscErrorCode JRHBMCondApply(JRHBM h, PetscReal w, const PetscReal *x, PetscReal *res, PetscReal *jac, PetscReal *dw)
{
  const PetscInt nq = h->nq, ns = h->ns, bs = 4 * nq * nq + 4 * nq;
  PetscReal     *t = h->ctmp, *T = h->ctmp + ns;

  PetscFunctionBeginUser;
  PetscCall(CondBlocks(h, w));
  for (PetscInt r = 0; r < nq; r++) { /* the mean */
    PetscReal v = x[r];
    for (PetscInt c = 0; c < nq; c++) v += h->G0[r + c * nq] * res[c];
    t[r] = v;
    if (dw) dw[r] = 0.0;
  }
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    const PetscReal *Gr = h->Gb + (hh - 1) * bs, *Gi = Gr + nq * nq, *dGr = Gi + nq * nq, *dGi = dGr + nq * nq;
    const PetscReal *xFr = dGi + nq * nq, *xFi = xFr + nq, *dxFr = xFi + nq, *dxFi = dxFr + nq;
    const PetscInt   os = (2 * hh - 1) * nq, oc = 2 * hh * nq;
    const PetscReal *gs = res + os, *gc = res + oc;
    for (PetscInt r = 0; r < nq; r++) {
      PetscReal vs = x[os + r] - h->level * xFr[r], vc = x[oc + r] - h->level * xFi[r], ds = -h->level * dxFr[r], dc = -h->level * dxFi[r];
      for (PetscInt c = 0; c < nq; c++) {
        vs += Gr[r + c * nq] * gs[c] - Gi[r + c * nq] * gc[c];
        vc += Gi[r + c * nq] * gs[c] + Gr[r + c * nq] * gc[c];
        ds += dGr[r + c * nq] * gs[c] - dGi[r + c * nq] * gc[c];
        dc += dGi[r + c * nq] * gs[c] + dGr[r + c * nq] * gc[c];
      }
      t[os + r] = vs;
      t[oc + r] = vc;
      if (dw) {
        dw[os + r] = ds;
        dw[oc + r] = dc;
      }
    }
  }
  if (jac) { /* T = I + blockdiag(G) dg/dx, row blocks of dg/dx (leading dimension ns); blocks of a few joints:
                plain loops, the inner one over the rows (a BLAS call costs more than its 6 x 6 product) */
    for (PetscInt j = 0; j < ns; j++) {
      const PetscReal *jc = jac + j * ns;
      PetscReal       *tc = T + j * ns;
      for (PetscInt r = 0; r < nq; r++) tc[r] = 0.0;
      for (PetscInt c = 0; c < nq; c++) {
        const PetscReal v = jc[c];
        if (v != 0.0)
          for (PetscInt r = 0; r < nq; r++) tc[r] += h->G0[r + c * nq] * v;
      }
      for (PetscInt hh = 1; hh <= h->H; hh++) {
        const PetscReal *Gr = h->Gb + (hh - 1) * bs, *Gi = Gr + nq * nq;
        const PetscInt   os = (2 * hh - 1) * nq, oc = 2 * hh * nq;
        for (PetscInt r = 0; r < nq; r++) tc[os + r] = tc[oc + r] = 0.0;
        for (PetscInt c = 0; c < nq; c++) {
          const PetscReal vs = jc[os + c], vc = jc[oc + c];
          if (vs == 0.0 && vc == 0.0) continue;
          for (PetscInt r = 0; r < nq; r++) {
            tc[os + r] += Gr[r + c * nq] * vs - Gi[r + c * nq] * vc;
            tc[oc + r] += Gi[r + c * nq] * vs + Gr[r + c * nq] * vc;
          }
        }
      }
    }
    PetscCall(PetscLogFlops(4.0 * ns * nq * ns));
    for (PetscInt i = 0; i < ns; i++) T[i + i * ns] += 1.0;
    PetscCall(PetscArraycpy(jac, T, ns * ns));
  }
  PetscCall(PetscArraycpy(res, t, ns));
  PetscFunctionReturn(0);
}

/* Back to no condensation: the solve space is the modal one; the operators of an earlier set-up freed */
static PetscErrorCode CondenseReset(JRHBM h)
{
  PetscFunctionBeginUser;
  h->cond        = PETSC_FALSE;
  h->ns          = h->n;
  h->wq_ok       = PETSC_FALSE;
  h->condinfo[0] = 0;
  PetscCall(PetscFree3(h->Q, h->QV, h->VF));
  PetscCall(PetscFree4(h->V, h->lamv, h->cv, h->G0));
  PetscCall(PetscFree2(h->Z0, h->piv0));
  PetscCall(PetscFree3(h->Gb, h->inv, h->ctmp));
  PetscCall(PetscFree2(h->QQ, h->cb)); /* products of the rows: rebuilt from the new ones */
  PetscCall(PetscFree(h->jres));       /* sized by the solve space */
  PetscCall(PetscFree2(h->llu, h->lpiv));
  PetscFunctionReturn(0);
}

/* The joints' rows Q (nq x nm, row-major: the nj tangential rows, then the nj normal ones if anyn), the average of
   their elements' rows (4.4); exact: every element's rows are its joint's, to 1e-10 of the largest (collective) */
static PetscErrorCode JointRowsQ(JRHBM h, const JRElements *el, PetscInt nq, PetscBool anyn, PetscBool *exact)
{
  const PetscInt nm = h->nm, nj = el->njoints, wdt = 2 * nm + 1;
  PetscReal     *loc, *sum, dev = 0, scale = 0, dd[2], da[2];

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc2(nj * wdt, &loc, nj * wdt, &sum));
  for (PetscInt t = 0; t < h->ngroups; t++) {
    JRHBMGroup *g = &h->g[t];
    for (PetscInt e = 0; e < g->nloc; e++) {
      PetscReal *r = loc + el->joint[g->eidx[e]] * wdt;
      for (PetscInt i = 0; i < nm; i++) r[i] += g->R[e + i * g->nloc];
      if (g->normal)
        for (PetscInt i = 0; i < nm; i++) r[nm + i] += g->S[e + i * g->nloc];
      r[wdt - 1] += 1.0;
    }
  }
  PetscCall(MPIU_Allreduce(loc, sum, nj * wdt, MPIU_REAL, MPIU_SUM, h->ecomm));
  PetscCall(PetscCalloc3(nq * nm, &h->Q, nq * nm, &h->QV, nm, &h->VF));
  for (PetscInt j = 0; j < nj; j++) {
    const PetscReal *r = sum + j * wdt;
    PetscCheck(r[wdt - 1] > 0, h->comm, PETSC_ERR_ARG_WRONG, "Joint %" PetscInt_FMT " has no element", j);
    for (PetscInt i = 0; i < nm; i++) {
      h->Q[j * nm + i] = r[i] / r[wdt - 1];
      if (anyn) h->Q[(nj + j) * nm + i] = r[nm + i] / r[wdt - 1];
    }
  }
  for (PetscInt i = 0; i < nq * nm; i++) scale = PetscMax(scale, PetscAbsReal(h->Q[i]));
  for (PetscInt t = 0; t < h->ngroups; t++) {
    JRHBMGroup *g = &h->g[t];
    for (PetscInt e = 0; e < g->nloc; e++) {
      const PetscInt j = el->joint[g->eidx[e]];
      for (PetscInt i = 0; i < nm; i++) {
        dev = PetscMax(dev, PetscAbsReal(g->R[e + i * g->nloc] - h->Q[j * nm + i]));
        if (g->normal) dev = PetscMax(dev, PetscAbsReal(g->S[e + i * g->nloc] - h->Q[(nj + j) * nm + i]));
      }
    }
  }
  PetscCall(PetscFree2(loc, sum));
  dd[0] = dev;
  dd[1] = scale;
  PetscCall(MPIU_Allreduce(dd, da, 2, MPIU_REAL, MPIU_MAX, h->comm));
  *exact = (PetscBool)!(da[0] > 1e-10 * da[1]);
  PetscFunctionReturn(0);
}

/* The (Kg, Mm) eigenvectors V and values lamv; the viscous damping V^T Cm V, which must be diagonal in them (else why
   says so); Q V, V^T fm, the mean block Z0 = Kg + pin LU-factored and G0 = Q Z0^-1 Q^T */
static PetscErrorCode CondenseOperators(JRHBM h, PetscInt nq, const char **why)
{
  const PetscInt nm = h->nm;
  PetscReal     *A, *B, *work, *Y, cmax = 0, coff = 0;
  PetscBLASInt   bn, bq, lwork, info, itype = 1;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc4(nm * nm, &h->V, nm, &h->lamv, nm, &h->cv, nq * nq, &h->G0));
  PetscCall(PetscMalloc4(nm * nm, &A, nm * nm, &B, 8 * nm, &work, nm * PetscMax(nm, nq), &Y));
  for (PetscInt i = 0; i < nm; i++)
    for (PetscInt j = 0; j < nm; j++) {
      h->V[i + j * nm] = 0.5 * (h->Kg[i * nm + j] + h->Kg[j * nm + i]);
      B[i + j * nm]    = 0.5 * (h->Mm[i * nm + j] + h->Mm[j * nm + i]);
    }
  PetscCall(PetscBLASIntCast(nm, &bn));
  PetscCall(PetscBLASIntCast(8 * nm, &lwork));
  PetscCallBLAS("LAPACKsygv", LAPACKsygv_(&itype, "V", "U", &bn, h->V, &bn, B, &bn, h->lamv, work, &lwork, &info));
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK sygv (condensation) failed: info %d", (int)info);
  /* C' = V^T Cm V */
  for (PetscInt i = 0; i < nm; i++)
    for (PetscInt j = 0; j < nm; j++) A[i + j * nm] = h->Cm[i * nm + j];
  PetscCall(JRGemm("N", "N", nm, nm, nm, 1.0, A, nm, h->V, nm, 0.0, Y, nm));
  PetscCall(JRGemm("T", "N", nm, nm, nm, 1.0, h->V, nm, Y, nm, 0.0, A, nm));
  for (PetscInt i = 0; i < nm; i++) {
    h->cv[i] = A[i + i * nm];
    for (PetscInt j = 0; j < nm; j++) {
      cmax = PetscMax(cmax, PetscAbsReal(A[i + j * nm]));
      if (i != j) coff = PetscMax(coff, PetscAbsReal(A[i + j * nm]));
    }
  }
  if (coff > 1e-9 * cmax) *why = "the viscous damping is not diagonal in the eigenvectors of the structure's stiffness and mass (use -hbm_gamma, or proportional damping)";
  else {
    /* Q V, V^T fm */
    PetscCall(JRGemm("T", "N", nm, nq, nm, 1.0, h->V, nm, h->Q, nm, 0.0, h->QV, nm)); /* (QV)^T col-major nm x nq = QV row-major */
    PetscCall(JRGemm("T", "N", nm, 1, nm, 1.0, h->V, nm, h->fm, nm, 0.0, h->VF, nm));
    /* the mean block Kg + pin, LU, and G0 = Q Z0^-1 Q^T */
    PetscCall(PetscMalloc2(nm * nm, &h->Z0, nm, &h->piv0));
    for (PetscInt i = 0; i < nm; i++)
      for (PetscInt j = 0; j < nm; j++) h->Z0[i + j * nm] = h->Kg[i * nm + j] + (i == j && h->pin ? h->pin[i] : 0.0);
    PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, h->Z0, &bn, h->piv0, &info));
    PetscCheck(!info, h->comm, PETSC_ERR_MAT_LU_ZRPVT, "Condensation: the static stiffness (mean block) is singular, info %d", (int)info);
    PetscCall(PetscArraycpy(Y, h->Q, nq * nm)); /* Q^T, col-major nm x nq */
    PetscCall(PetscBLASIntCast(nq, &bq));
    PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bn, &bq, h->Z0, &bn, h->piv0, Y, &bn, &info));
    PetscCall(JRGemm("T", "N", nq, nq, nm, 1.0, h->Q, nm, Y, nm, 0.0, h->G0, nq));
  }
  PetscCall(PetscFree4(A, B, work, Y));
  PetscFunctionReturn(0);
}

/*
  JRHBMCondenseSetUp - decide on condensation (-hbm_condense auto: a reduced model whose elements all move with their
  joint's rows, fewer rows than modes, and damping diagonal with Kg) and build its operators (collective)
*/
PetscErrorCode JRHBMCondenseSetUp(JRHBM h, const JRElements *el)
{
  const PetscInt nm = h->nm, nc = h->nc;
  PetscInt       nj, nq;
  PetscBool      anyn = PETSC_FALSE, want = (PetscBool)(h->condense == JR_HBM_CONDENSE_YES), exact;
  const char    *why = NULL;

  PetscFunctionBeginUser;
  PetscCall(CondenseReset(h));
  if (h->condense == JR_HBM_CONDENSE_NO) PetscFunctionReturn(0);
  if (!el->joint || el->njoints < 1) PetscFunctionReturn(0); /* not a reduced model: nothing to condense onto */
  nj = el->njoints;
  for (PetscInt t = 0; t < h->ngroups; t++) anyn = (PetscBool)(anyn || h->g[t].normal);
  nq = anyn ? 2 * nj : nj;
  PetscCall(JointRowsQ(h, el, nq, anyn, &exact));
  if (!exact) why = "the elements of a joint do not all move with the joint's rows";
  else if (nq >= nm && !want) why = "at least as many joint rows as modes (nothing to gain; -hbm_condense yes forces it)";
  if (!why) PetscCall(CondenseOperators(h, nq, &why)); /* (Kg, Mm) eigenvectors; the viscous damping must be diagonal in them */
  if (why) {
    PetscCheck(!want, h->comm, PETSC_ERR_ARG_INCOMP, "-hbm_condense yes: cannot condense onto the joints: %s", why);
    PetscCall(PetscInfo(NULL, "No condensation: %s\n", why));
    PetscCall(PetscFree3(h->Q, h->QV, h->VF));
    PetscCall(PetscFree4(h->V, h->lamv, h->cv, h->G0));
    PetscCall(PetscFree2(h->Z0, h->piv0));
    PetscFunctionReturn(0);
  }
  /* every element's joint row (and normal row) */
  for (PetscInt t = 0; t < h->ngroups; t++) {
    JRHBMGroup    *g    = &h->g[t];
    const PetscInt nloc = g->nloc;
    PetscCall(PetscFree2(g->qt, g->qn));
    PetscCall(PetscMalloc2(nloc, &g->qt, nloc, &g->qn));
    for (PetscInt e = 0; e < nloc; e++) {
      const PetscInt j = el->joint[g->eidx[e]];
      g->qt[e]         = j;
      g->qn[e]         = g->normal ? nj + j : -1;
    }
  }
  h->nq = nq;
  h->ns = nq * nc;
  PetscCall(PetscMalloc3(h->H * (4 * nq * nq + 4 * nq), &h->Gb, 2 * h->H * nm, &h->inv, h->ns + h->ns * h->ns, &h->ctmp));
  h->cond = PETSC_TRUE;
  PetscCall(PetscSNPrintf(h->condinfo, sizeof(h->condinfo), "condensed onto %" PetscInt_FMT " joint motions: %" PetscInt_FMT " unknowns instead of %" PetscInt_FMT, nq, h->ns, h->n));
  PetscFunctionReturn(0);
}

/* Condensed: the modal unknowns a (n) of the joints' motions x (ns) at frequency w, a = Z^-1 (F fm - Q^T g(x)) */
static PetscErrorCode CondExpand(JRHBM h, PetscReal w, const PetscReal *x, PetscReal *a)
{
  const PetscInt nq = h->nq, nm = h->nm;
  PetscReal     *g, *br, *bi;
  PetscBLASInt   bn, one = 1, info;

  PetscFunctionBeginUser;
  PetscCall(CondBlocks(h, w));
  PetscCall(PetscMalloc3(h->ns, &g, nm, &br, nm, &bi));
  PetscCall(JRHBMNonlinear(h, x, g, NULL));
  for (PetscInt i = 0; i < nm; i++) { /* the mean: Z0 a0 = -Q^T g0 */
    PetscReal v = 0;
    for (PetscInt r = 0; r < nq; r++) v -= h->Q[r * nm + i] * g[r];
    a[i] = v;
  }
  PetscCall(PetscBLASIntCast(nm, &bn));
  PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bn, &one, h->Z0, &bn, h->piv0, a, &bn, &info));
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    const PetscInt   os = (2 * hh - 1) * nq, oc = 2 * hh * nq;
    const PetscReal *ir = h->inv + 2 * (hh - 1) * nm, *ii = ir + nm;
    for (PetscInt k = 0; k < nm; k++) { /* b = V^T (F fm - Q^T g), then z = b / z_k */
      PetscReal vr = hh == 1 ? h->level * h->VF[k] : 0.0, vi = 0.0;
      for (PetscInt r = 0; r < nq; r++) {
        vr -= h->QV[r * nm + k] * g[os + r];
        vi -= h->QV[r * nm + k] * g[oc + r];
      }
      br[k] = ir[k] * vr - ii[k] * vi;
      bi[k] = ir[k] * vi + ii[k] * vr;
    }
    PetscCall(JRGemm("N", "N", nm, 1, nm, 1.0, h->V, nm, br, nm, 0.0, a + (2 * hh - 1) * nm, nm));
    PetscCall(JRGemm("N", "N", nm, 1, nm, 1.0, h->V, nm, bi, nm, 0.0, a + 2 * hh * nm, nm));
  }
  PetscCall(PetscFree3(g, br, bi));
  PetscFunctionReturn(0);
}

/* JRHBMExpand - the modal unknowns a (JRHBMGetSizes n) of the solve-space unknowns x at frequency w: a copy, or
   condensed a = Z^-1 (F fm - Q^T g(x)) (collective: the elements are evaluated) */
PetscErrorCode JRHBMExpand(JRHBM h, PetscReal w, Vec x, Vec a)
{
  const PetscScalar *xx;
  PetscScalar       *aa;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  if (!h->cond) {
    PetscCall(VecCopy(x, a));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(x, &xx));
  PetscCall(VecGetArray(a, &aa));
  PetscCall(CondExpand(h, w, xx, aa));
  PetscCall(VecRestoreArray(a, &aa));
  PetscCall(VecRestoreArrayRead(x, &xx));
  PetscFunctionReturn(0);
}
