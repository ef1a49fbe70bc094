/*
   JRHBM's condensation onto the joints (-hbm_condense): a reduced model's linear part solved exactly for the joints'
   motions, which become the unknowns. Per harmonic h, in complex form z = as + i ac, the linear part is
       Z_h(w) = Kg (1 + i gamma) - (h w)^2 Mm + i h w Cm   (the mean: Kg + pin),
   with Kg the structure's own stiffness (Km less the stuck springs that the stuck basis holds). When V^T Cm V is
   diagonal for the eigenvectors V of (Kg, Mm) (no viscous damping, or proportional), Z_h^-1 = V diag(1/z_k) V^T with
   z_k = lam_k (1 + i gamma) - (h w)^2 + i h w c_k. Every element of a reduced model moves with its joint: its rows are
   combinations of a few rows of the joint (JointRowSpace: 2 for a joint's mean motion, about 6 for a field linear in
   the members' positions), so with Q those nq rows, x = Q a the joints' motions and g(x) the elements' forces summed
   on them (through each element's coefficients), a = Z^-1 (F fm - Q^T g) and
       r_h(x) = x_h + G_h g_h(x) - F xF_h,   G_h = Q Z_h^-1 Q^T (nq x nq),  xF_1 = Q Z_1^-1 fm,
   the modal equations with the modes eliminated exactly: nq (2H+1) unknowns instead of nm (2H+1).
*/
#include <jointrom/private/hbmimpl.h>

/* 1/z_k and d(1/z_k)/dw (re, im) per harmonic at frequency w, kept */
static PetscErrorCode CondInverse(JRHBM h, PetscReal w)
{
  const PetscInt nm = h->nm;

  PetscFunctionBeginUser;
  if (h->wi_ok && h->wi == w) PetscFunctionReturn(0);
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    PetscReal      *ir = h->inv + 4 * (hh - 1) * nm, *ii = ir + nm, *dr = ii + nm, *di = dr + nm;
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
  }
  h->wi    = w;
  h->wi_ok = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* G_h = (Q V) diag(1/z_k) (Q V)^T (re, im; column-major, symmetric) at frequency w, kept: the Jacobian's blocks */
static PetscErrorCode CondBlocks(JRHBM h, PetscReal w)
{
  const PetscInt nq = h->nq, nm = h->nm;
  PetscReal     *W;

  PetscFunctionBeginUser;
  if (h->wq_ok && h->wq == w) PetscFunctionReturn(0);
  PetscCall(CondInverse(h, w));
  W = h->QQ; /* (Q V)^T scaled by 1/z_k, nm x nq */
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    PetscReal *Gr = h->Gb + 2 * (hh - 1) * nq * nq;
    for (PetscInt q = 0; q < 2; q++) {
      const PetscReal *d = h->inv + 4 * (hh - 1) * nm + q * nm;
      for (PetscInt r = 0; r < nq; r++)
        for (PetscInt k = 0; k < nm; k++) W[k + r * nm] = d[k] * h->QV[r * nm + k];
      PetscCall(JRGemm("T", "N", nq, nq, nm, 1.0, h->QV, nm, W, nm, 0.0, Gr + q * nq * nq, nq));
    }
  }
  PetscCall(PetscLogFlops(4.0 * h->H * nm * nq * nq));
  h->wq    = w;
  h->wq_ok = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* T = I + blockdiag(G) dg/dx (T: leading dimension ldt) with the blocks G_h of CondBlocks and dg/dx by its joints'
   blocks (Db): a column of joint j's unknowns is G's columns of the joint's rows times the block's column (plain loops,
   the inner one over the rows: a BLAS call costs more than its few-term product) */
static PetscErrorCode CondJacobian(JRHBM h, PetscReal *T, PetscInt ldt)
{
  const PetscInt nq = h->nq, ns = h->ns;

  PetscFunctionBeginUser;
  for (PetscInt j = 0; j < h->njb; j++) {
    const PetscInt  *ix = h->jidx + h->jio[j], b = h->jio[j + 1] - h->jio[j];
    const PetscReal *D  = h->Db + h->dbo[j];
    for (PetscInt c = 0; c < b; c++) {
      PetscReal *tc = T + ix[c] * ldt;
      PetscCall(PetscArrayzero(tc, ns));
      for (PetscInt r = 0; r < b; r++) {
        const PetscReal v = D[r + c * b];
        const PetscInt  comp = ix[r] / nq, q = ix[r] % nq, hh = (comp + 1) / 2;
        if (v == 0.0) continue;
        if (!comp) {
          for (PetscInt i = 0; i < nq; i++) tc[i] += h->G0[i + q * nq] * v;
        } else {
          const PetscReal *Gr = h->Gb + 2 * (hh - 1) * nq * nq + q * nq, *Gi = Gr + nq * nq;
          PetscReal       *ts = tc + (2 * hh - 1) * nq, *tcc = tc + 2 * hh * nq;
          if (comp % 2) /* sin: (Gr + i Gi) v */
            for (PetscInt i = 0; i < nq; i++) {
              ts[i] += Gr[i] * v;
              tcc[i] += Gi[i] * v;
            }
          else /* cos: (Gr + i Gi) i v */
            for (PetscInt i = 0; i < nq; i++) {
              ts[i] -= Gi[i] * v;
              tcc[i] += Gr[i] * v;
            }
        }
      }
      tc[ix[c]] += 1.0;
    }
    PetscCall(PetscLogFlops(4.0 * b * b * nq));
  }
  PetscFunctionReturn(0);
}

/* Condensed: res holds g(x) on entry and r(x) on exit; dw (if not NULL) gets dr/dw. Through the modes,
   (Q V) (d_k ((Q V)^T g_h)) (a few products of the nq x nm rows with vectors). */
PetscErrorCode JRHBMCondApply(JRHBM h, PetscReal w, const PetscReal *x, PetscReal *res, PetscReal *dw)
{
  const PetscInt nq = h->nq, nm = h->nm, ns = h->ns;
  PetscReal     *t = h->ctmp;

  PetscFunctionBeginUser;
  PetscCall(CondInverse(h, w));
  for (PetscInt r = 0; r < nq; r++) { /* the mean */
    PetscReal v = x[r];
    for (PetscInt c = 0; c < nq; c++) v += h->G0[r + c * nq] * res[c];
    t[r] = v;
    if (dw) dw[r] = 0.0;
  }
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    const PetscReal *ir = h->inv + 4 * (hh - 1) * nm, *ii = ir + nm, *dr = ii + nm, *di = dr + nm;
    const PetscInt   os = (2 * hh - 1) * nq, oc = 2 * hh * nq, nv = dw ? 4 : 2;
    PetscReal       *b = h->cb, *C = b + 2 * nm, *y = C + 4 * nm, *gg = y; /* (Q V)^T [gs gc]; coefficients; (Q V) C */
    const PetscReal  F = h->level;
    for (PetscInt r = 0; r < nq; r++) {
      gg[r]      = res[os + r];
      gg[nq + r] = res[oc + r];
    }
    PetscCall(JRGemm("N", "N", nm, 2, nq, 1.0, h->QV, nm, gg, nq, 0.0, b, nm));
    for (PetscInt k = 0; k < nm; k++) { /* (1/z) (bs + i bc) - F (1/z) VF on the first harmonic; and d/dw of both */
      const PetscReal bs = b[k], bc = b[nm + k], f = hh == 1 ? F * h->VF[k] : 0.0;
      C[k]      = ir[k] * (bs - f) - ii[k] * bc;
      C[nm + k] = ii[k] * (bs - f) + ir[k] * bc;
      if (dw) {
        C[2 * nm + k] = dr[k] * (bs - f) - di[k] * bc;
        C[3 * nm + k] = di[k] * (bs - f) + dr[k] * bc;
      }
    }
    PetscCall(JRGemm("T", "N", nq, nv, nm, 1.0, h->QV, nm, C, nm, 0.0, y, nq));
    for (PetscInt r = 0; r < nq; r++) {
      t[os + r] = x[os + r] + y[r];
      t[oc + r] = x[oc + r] + y[nq + r];
      if (dw) {
        dw[os + r] = y[2 * nq + r];
        dw[oc + r] = y[3 * nq + r];
      }
    }
  }
  PetscCall(PetscLogFlops(4.0 * h->H * nm * nq * (dw ? 3 : 2)));
  PetscCall(PetscArraycpy(res, t, ns));
  PetscFunctionReturn(0);
}

/* The Jacobian at a point (JRHBMJacobianSetPoint, JRHBMComputeJacobian): the elements' dg/dx at x kept by its joints'
   blocks (an element's force moves only with its joint's rows), the residual into jres and dr/dw into dw (may be
   NULL) */
PetscErrorCode JRHBMCondJacobianPoint(JRHBM h, PetscReal w, const PetscReal *x, PetscReal *dw)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMNonlinear(h, x, h->jres, h->Db));
  PetscCall(JRHBMCondApply(h, w, x, h->jres, dw));
  h->jw = w;
  PetscFunctionReturn(0);
}

/* y = J x at the point of JRHBMCondJacobianPoint, J = I + G dg/dx: dg/dx by its joints' blocks, G through the modes,
   (Q V) (d_k ((Q V)^T u_h)) per harmonic, as the residual */
PetscErrorCode JRHBMCondJacobianMult(JRHBM h, const PetscReal *x, PetscReal *y)
{
  const PetscInt nq = h->nq, nm = h->nm, ns = h->ns;
  PetscReal     *u = h->ju, *bb = h->cb, *C = bb + 2 * nm;

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(u, ns));
  for (PetscInt j = 0; j < h->njb; j++) {
    const PetscInt  *ix = h->jidx + h->jio[j], b = h->jio[j + 1] - h->jio[j];
    const PetscReal *D  = h->Db + h->dbo[j];
    for (PetscInt c = 0; c < b; c++) {
      const PetscReal v = x[ix[c]];
      if (v != 0.0)
        for (PetscInt r = 0; r < b; r++) u[ix[r]] += D[r + c * b] * v;
    }
    PetscCall(PetscLogFlops(2.0 * b * b));
  }
  PetscCall(CondInverse(h, h->jw));
  PetscCall(JRGemm("N", "N", nq, 1, nq, 1.0, h->G0, nq, u, nq, 0.0, y, nq));
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    const PetscReal *ir = h->inv + 4 * (hh - 1) * nm, *ii = ir + nm;
    const PetscInt   os = (2 * hh - 1) * nq; /* the sin then the cos block: an nq x 2 array */
    PetscCall(JRGemm("N", "N", nm, 2, nq, 1.0, h->QV, nm, u + os, nq, 0.0, bb, nm));
    for (PetscInt k = 0; k < nm; k++) {
      const PetscReal bs = bb[k], bc = bb[nm + k];
      C[k]      = ir[k] * bs - ii[k] * bc;
      C[nm + k] = ii[k] * bs + ir[k] * bc;
    }
    PetscCall(JRGemm("T", "N", nq, 2, nm, 1.0, h->QV, nm, C, nm, 0.0, y + os, nq));
  }
  for (PetscInt i = 0; i < ns; i++) y[i] += x[i];
  PetscCall(PetscLogFlops(2.0 * nq * nq + 8.0 * h->H * nm * nq));
  PetscFunctionReturn(0);
}

/* The Jacobian I + G dg/dx at the point of JRHBMCondJacobianPoint into A (leading dimension lda) */
PetscErrorCode JRHBMCondJacobianForm(JRHBM h, PetscReal *A, PetscInt lda)
{
  PetscFunctionBeginUser;
  PetscCall(CondBlocks(h, h->jw));
  PetscCall(CondJacobian(h, A, lda));
  PetscFunctionReturn(0);
}

/* Back to no condensation: the solve space is the modal one; the operators of an earlier set-up freed */
static PetscErrorCode CondenseReset(JRHBM h)
{
  PetscFunctionBeginUser;
  h->cond        = PETSC_FALSE;
  h->ns          = h->n;
  h->wq_ok       = PETSC_FALSE;
  h->wi_ok       = PETSC_FALSE;
  h->condinfo[0] = 0;
  PetscCall(PetscFree3(h->Q, h->QV, h->VF));
  PetscCall(PetscFree4(h->V, h->lamv, h->cv, h->G0));
  PetscCall(PetscFree2(h->Z0, h->piv0));
  PetscCall(PetscFree3(h->Gb, h->inv, h->ctmp));
  PetscCall(PetscFree2(h->QQ, h->cb)); /* products of the rows: rebuilt from the new ones */
  PetscCall(PetscFree4(h->jidx, h->jio, h->dbo, h->Db));
  PetscCall(PetscFree2(h->qj, h->ql));
  PetscCall(PetscFree(h->ju));
  h->njb = 0;
  PetscCall(PetscFree(h->jres));       /* sized by the solve space */
  PetscCall(PetscFree2(h->llu, h->lpiv));
  PetscFunctionReturn(0);
}

/* The joints' rows Q (nq x nm, row-major, joint by joint, tangential then normal): an orthogonal basis of each joint's
   elements' tangential rows, and of their normal rows, by the SVD of their stack on every rank (singular values below
   1e-10 of the largest dropped), scaled to their root-mean-square row; a joint's elements that move with its mean give
   one row per direction, with a field linear in their coordinates 1 + the coordinates that vary. off (2 nj + 1):
   each joint's first tangential row (2 j) and normal row (2 j + 1), and the total; scale (2 nj). Collective. */
static PetscErrorCode JointRowSpace(JRHBM h, const JRElements *el, PetscBool anyn, PetscInt **off, PetscReal **scale)
{
  const PetscInt nm = h->nm, ne = el->n, nj = el->njoints, nr = anyn ? 2 : 1;
  PetscReal     *loc, *all, *A, *sv, *VT, *Qs = NULL, wq, *work;
  PetscInt      *cnt, mmax = 0;
  PetscBLASInt   bm, bn, lda, ldvt, lwork = -1, info, one = 1;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc2(ne * nr * nm, &loc, ne * nr * nm, &all));
  for (PetscInt t = 0; t < h->ngroups; t++) {
    const JRHBMGroup *g = &h->g[t];
    for (PetscInt e = 0; e < g->nloc; e++)
      for (PetscInt i = 0; i < nm; i++) {
        loc[(g->eidx[e] * nr) * nm + i] = g->R[e + i * g->nloc];
        if (g->normal) loc[(g->eidx[e] * nr + 1) * nm + i] = g->S[e + i * g->nloc];
      }
  }
  PetscCall(MPIU_Allreduce(loc, all, ne * nr * nm, MPIU_REAL, MPIU_SUM, h->ecomm));
  PetscCall(PetscCalloc1(nj, &cnt));
  PetscCall(PetscCalloc2(2 * nj + 1, off, 2 * nj, scale));
  for (PetscInt e = 0; e < ne; e++) cnt[el->joint[e]]++;
  for (PetscInt j = 0; j < nj; j++) mmax = PetscMax(mmax, cnt[j]);
  PetscCall(PetscMalloc3(mmax * nm + 1, &A, PetscMin(mmax, nm) + 1, &sv, PetscMin(mmax, nm) * nm + 1, &VT));
  PetscCall(PetscMalloc1(2 * nj * PetscMin(mmax, nm) * nm + 1, &Qs)); /* each joint's kept rows, unscaled */
  PetscCall(PetscBLASIntCast(nm, &bn));
  for (PetscInt j = 0; j < nj; j++) {
    PetscCheck(cnt[j] > 0, h->comm, PETSC_ERR_ARG_WRONG, "Joint %" PetscInt_FMT " has no element", j);
    for (PetscInt q = 0; q < 2; q++) {
      const PetscInt o = (*off)[2 * j + q], m = cnt[j], mn = PetscMin(m, nm);
      PetscInt       k = 0;
      (*off)[2 * j + q + 1] = o;
      if (q >= nr) continue;
      for (PetscInt e = 0, r = 0; e < ne; e++) /* the joint's rows of direction q, column-major m x nm */
        if (el->joint[e] == j) {
          for (PetscInt i = 0; i < nm; i++) A[r + i * m] = all[(e * nr + q) * nm + i];
          r++;
        }
      PetscCall(PetscBLASIntCast(m, &bm));
      PetscCall(PetscBLASIntCast(m, &lda));
      PetscCall(PetscBLASIntCast(mn, &ldvt));
      lwork = -1;
      PetscCallBLAS("LAPACKgesvd", LAPACKgesvd_("N", "S", &bm, &bn, A, &lda, sv, NULL, &one, VT, &ldvt, &wq, &lwork, &info));
      PetscCall(PetscBLASIntCast((PetscInt)wq + 1, &lwork));
      PetscCall(PetscMalloc1(lwork, &work));
      PetscCallBLAS("LAPACKgesvd", LAPACKgesvd_("N", "S", &bm, &bn, A, &lda, sv, NULL, &one, VT, &ldvt, work, &lwork, &info));
      PetscCall(PetscFree(work));
      PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK gesvd (the joints' rows) failed: info %d", (int)info);
      while (k < mn && sv[0] > 0 && sv[k] > 1e-10 * sv[0]) k++; /* none where every row is 0 (elements without a normal direction) */
      (*scale)[2 * j + q] = sv[0] / PetscSqrtReal((PetscReal)m);
      for (PetscInt r = 0; r < k; r++)
        for (PetscInt i = 0; i < nm; i++) Qs[(o + r) * nm + i] = VT[r + i * mn];
      (*off)[2 * j + q + 1] = o + k;
    }
  }
  h->nq = (*off)[2 * nj];
  PetscCall(PetscCalloc3(h->nq * nm + 1, &h->Q, h->nq * nm + 1, &h->QV, nm, &h->VF));
  for (PetscInt s = 0; s < 2 * nj; s++)
    for (PetscInt r = (*off)[s]; r < (*off)[s + 1]; r++)
      for (PetscInt i = 0; i < nm; i++) h->Q[r * nm + i] = (*scale)[s] * Qs[r * nm + i];
  PetscCall(PetscFree3(A, sv, VT));
  PetscCall(PetscFree(Qs));
  PetscCall(PetscFree(cnt));
  PetscCall(PetscFree2(loc, all));
  PetscFunctionReturn(0);
}

/* Every element's coefficients on its joint's rows Q_s of each direction (scale s_s: Q_s Q_s^T = s_s^2 I),
   c = Q_s r / s_s^2; exact: every element's rows are c^T Q_s to 1e-10 of the largest (collective) */
static PetscErrorCode ElementCoefficients(JRHBM h, const JRElements *el, const PetscInt off[], const PetscReal scale[], PetscBool *exact)
{
  const PetscInt nm = h->nm;
  PetscReal      dd[2] = {0, 0}, da[2];
  PetscInt       cw = 0;

  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < 2 * el->njoints; s++) cw = PetscMax(cw, off[s + 1] - off[s]);
  for (PetscInt t = 0; t < h->ngroups; t++) {
    JRHBMGroup    *g    = &h->g[t];
    const PetscInt nloc = g->nloc;
    PetscCall(PetscFree2(g->qo, g->qw));
    PetscCall(PetscFree2(g->Ct, g->Cn));
    PetscCall(PetscFree2(g->Kq, g->qb)); /* of the old rows */
    PetscCall(PetscMalloc2(2 * nloc + 1, &g->qo, 2 * nloc + 1, &g->qw));
    PetscCall(PetscCalloc2(nloc * cw + 1, &g->Ct, g->normal ? nloc * cw + 1 : 1, &g->Cn));
    g->cw = cw;
    for (PetscInt e = 0; e < nloc; e++) {
      const PetscInt j = el->joint[g->eidx[e]];
      for (PetscInt q = 0; q < 2; q++) {
        const PetscInt   sidx = 2 * j + q, k = off[sidx + 1] - off[sidx];
        const PetscReal  s2 = scale[sidx] * scale[sidx];
        const PetscReal *X = q ? g->S : g->R;
        PetscReal       *C = q ? g->Cn : g->Ct;
        g->qo[2 * e + q] = off[sidx];
        g->qw[2 * e + q] = q && !g->normal ? 0 : k;
        if (q && !g->normal) continue;
        for (PetscInt r = 0; r < k; r++) {
          const PetscReal *qr = h->Q + (off[sidx] + r) * nm;
          PetscReal        c  = 0;
          for (PetscInt i = 0; i < nm; i++) c += qr[i] * X[e + i * nloc];
          C[e + r * nloc] = c / s2;
        }
        for (PetscInt i = 0; i < nm; i++) {
          PetscReal x = X[e + i * nloc];
          dd[1] = PetscMax(dd[1], PetscAbsReal(x));
          for (PetscInt r = 0; r < k; r++) x -= C[e + r * nloc] * h->Q[(off[sidx] + r) * nm + i];
          dd[0] = PetscMax(dd[0], PetscAbsReal(x));
        }
      }
    }
  }
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

/* The solve space's unknowns joint by joint (jidx, jio), each row's joint and place in it (qj, ql), and the offsets
   of the joints' blocks of dg/dx (dbo, Db):
   joint j's rows are off[2 j] .. off[2 j + 2] (tangential, then normal) in the mean and in each harmonic's sin and cos */
static PetscErrorCode JointBlocks(JRHBM h, PetscInt nj, const PetscInt off[])
{
  const PetscInt nq = h->nq, nc = h->nc;
  PetscInt       k = 0, nd = 0;

  PetscFunctionBeginUser;
  for (PetscInt j = 0; j < nj; j++) nd += PetscSqr(nc * (off[2 * j + 2] - off[2 * j]));
  PetscCall(PetscMalloc4(nc * nq, &h->jidx, nj + 1, &h->jio, nj + 1, &h->dbo, nd, &h->Db));
  PetscCall(PetscMalloc2(nq, &h->qj, nq, &h->ql));
  h->njb    = nj;
  h->jio[0] = h->dbo[0] = 0;
  for (PetscInt j = 0; j < nj; j++) {
    const PetscInt wj = off[2 * j + 2] - off[2 * j];
    for (PetscInt r = 0; r < wj; r++) {
      h->qj[off[2 * j] + r] = j;
      h->ql[off[2 * j] + r] = r;
    }
    for (PetscInt c = 0; c < nc; c++)
      for (PetscInt r = 0; r < wj; r++) h->jidx[k++] = c * nq + off[2 * j] + r;
    h->jio[j + 1] = k;
    h->dbo[j + 1] = h->dbo[j] + PetscSqr(nc * wj);
  }
  PetscFunctionReturn(0);
}

/*
  JRHBMCondenseSetUp - decide on condensation (-hbm_condense auto: a reduced model whose elements all move with their
  joint's rows, fewer rows than modes, and damping diagonal with Kg) and build its operators (collective)
*/
PetscErrorCode JRHBMCondenseSetUp(JRHBM h, const JRElements *el)
{
  const PetscInt nm = h->nm, nc = h->nc;
  PetscInt      *off = NULL;
  PetscReal     *scale = NULL;
  PetscBool      anyn = PETSC_FALSE, want = (PetscBool)(h->condense == JR_HBM_CONDENSE_YES), exact;
  const char    *why = NULL;

  PetscFunctionBeginUser;
  PetscCall(CondenseReset(h));
  if (h->condense == JR_HBM_CONDENSE_NO) PetscFunctionReturn(0);
  if (!el->joint || el->njoints < 1) PetscFunctionReturn(0); /* not a reduced model: nothing to condense onto */
  for (PetscInt t = 0; t < h->ngroups; t++) anyn = (PetscBool)(anyn || h->g[t].normal);
  PetscCall(JointRowSpace(h, el, anyn, &off, &scale));
  PetscCall(ElementCoefficients(h, el, off, scale, &exact));
  if (exact) PetscCall(JointBlocks(h, el->njoints, off));
  PetscCall(PetscFree2(off, scale));
  if (!exact) why = "the elements of a joint do not all move with the joint's rows";
  else if (h->nq >= nm && !want) why = "at least as many joint rows as modes (nothing to gain; -hbm_condense yes forces it)";
  if (!why) PetscCall(CondenseOperators(h, h->nq, &why)); /* (Kg, Mm) eigenvectors; the viscous damping must be diagonal in them */
  if (why) {
    PetscCheck(!want, h->comm, PETSC_ERR_ARG_INCOMP, "-hbm_condense yes: cannot condense onto the joints: %s", why);
    PetscCall(PetscInfo(NULL, "No condensation: %s\n", why));
    PetscCall(PetscFree3(h->Q, h->QV, h->VF));
    PetscCall(PetscFree4(h->V, h->lamv, h->cv, h->G0));
    PetscCall(PetscFree2(h->Z0, h->piv0));
    for (PetscInt t = 0; t < h->ngroups; t++) {
      PetscCall(PetscFree2(h->g[t].qo, h->g[t].qw));
      PetscCall(PetscFree2(h->g[t].Ct, h->g[t].Cn));
      PetscCall(PetscFree2(h->g[t].Kq, h->g[t].qb));
    }
    PetscCall(PetscFree4(h->jidx, h->jio, h->dbo, h->Db));
    PetscCall(PetscFree2(h->qj, h->ql));
    h->njb = 0;
    h->nq  = 0;
    PetscFunctionReturn(0);
  }
  h->ns = h->nq * nc;
  PetscCall(PetscMalloc3(2 * h->H * h->nq * h->nq, &h->Gb, 4 * h->H * nm, &h->inv, h->ns, &h->ctmp));
  PetscCall(PetscMalloc2(nm * h->nq, &h->QQ, 6 * nm + 4 * h->nq, &h->cb)); /* CondBlocks's and JRHBMCondApply's work */
  PetscCall(PetscMalloc1(h->ns, &h->ju));
  h->cond = PETSC_TRUE;
  PetscCall(PetscSNPrintf(h->condinfo, sizeof(h->condinfo), "condensed onto %" PetscInt_FMT " joint motions: %" PetscInt_FMT " unknowns instead of %" PetscInt_FMT, h->nq, h->ns, h->n));
  PetscFunctionReturn(0);
}

/* Condensed: the modal unknowns a (n) of the joints' motions x (ns) at frequency w, a = Z^-1 (F fm - Q^T g(x)) */
static PetscErrorCode CondExpand(JRHBM h, PetscReal w, const PetscReal *x, PetscReal *a)
{
  const PetscInt nq = h->nq, nm = h->nm;
  PetscReal     *g, *br, *bi;
  PetscBLASInt   bn, one = 1, info;

  PetscFunctionBeginUser;
  PetscCall(CondInverse(h, w));
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
    const PetscReal *ir = h->inv + 4 * (hh - 1) * nm, *ii = ir + nm;
    PetscCall(JRGemm("N", "N", nm, 1, nq, -1.0, h->QV, nm, g + os, nq, 0.0, br, nm)); /* b = V^T (F fm - Q^T g) */
    PetscCall(JRGemm("N", "N", nm, 1, nq, -1.0, h->QV, nm, g + oc, nq, 0.0, bi, nm));
    for (PetscInt k = 0; k < nm; k++) { /* then z = b / z_k */
      const PetscReal vr = br[k] + (hh == 1 ? h->level * h->VF[k] : 0.0), vi = bi[k];
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
