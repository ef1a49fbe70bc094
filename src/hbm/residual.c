/*
   JRHBM's residual and analytic Jacobian (thesis 2.18 generalised to H harmonics): the contact elements' forces and
   derivatives projected onto the basis (JRHBMNonlinear) and the linear structure (Linear), or condensed onto the joints
   (src/hbm/condense.c); the SNES at fixed frequency (prefix hbm_) and the linearised solution.
*/
#include <jointrom/private/hbmimpl.h>

/* C (m x n) = alpha op(A) B + beta C for n <= 2 (JRGemm): BLAS packs its operands for any n, which costs more than
   the product itself at one or two columns (a condensed model's Jacobian products through the modes, the sine and
   cosine of a harmonic: 5 against 11 us on lap3's 138 modes x 84 rows); here A is read once, by columns (op(A) = A:
   axpys of its columns into C's) or by rows of op(A) (dot products with B's columns), both as SIMD loops. From
   three columns on BLAS is kept: loops up to four columns were not measurably faster there (node-to-node's
   projections onto the modes, 2H + 1 columns) */
static void GemmFewColumns(PetscBool at, PetscInt m, PetscInt n, PetscInt k, PetscReal alpha, const PetscReal *A, PetscInt lda, const PetscReal *B, PetscInt ldb, PetscReal beta, PetscReal *C, PetscInt ldc)
{
  if (!at) {
    for (PetscInt j = 0; j < n; j++) {
      PetscReal *c = C + j * ldc;
      if (beta == 0.0)
        for (PetscInt i = 0; i < m; i++) c[i] = 0.0;
      else if (beta != 1.0)
        for (PetscInt i = 0; i < m; i++) c[i] *= beta;
    }
    if (n == 2) {
      PetscReal *c0 = C, *c1 = C + ldc;
      for (PetscInt p = 0; p < k; p++) {
        const PetscReal *a = A + p * lda, b0 = alpha * B[p], b1 = alpha * B[p + ldb];
#pragma omp simd
        for (PetscInt i = 0; i < m; i++) {
          c0[i] += a[i] * b0;
          c1[i] += a[i] * b1;
        }
      }
      return;
    }
    for (PetscInt j = 0; j < n; j++) {
      PetscReal *c = C + j * ldc;
      for (PetscInt p = 0; p < k; p++) {
        const PetscReal *a = A + p * lda, b = alpha * B[p + j * ldb];
#pragma omp simd
        for (PetscInt i = 0; i < m; i++) c[i] += a[i] * b;
      }
    }
    return;
  }
  for (PetscInt i = 0; i < m; i++) {
    const PetscReal *a = A + i * lda;
    if (n == 2) {
      const PetscReal *x0 = B, *x1 = B + ldb;
      PetscReal        s0 = 0.0, s1 = 0.0;
#pragma omp simd reduction(+ : s0, s1)
      for (PetscInt p = 0; p < k; p++) {
        s0 += a[p] * x0[p];
        s1 += a[p] * x1[p];
      }
      C[i]       = alpha * s0 + (beta == 0.0 ? 0.0 : beta * C[i]);
      C[i + ldc] = alpha * s1 + (beta == 0.0 ? 0.0 : beta * C[i + ldc]);
      continue;
    }
    for (PetscInt j = 0; j < n; j++) {
      const PetscReal *x = B + j * ldb;
      PetscReal        s = 0.0;
#pragma omp simd reduction(+ : s)
      for (PetscInt p = 0; p < k; p++) s += a[p] * x[p];
      C[i + j * ldc] = alpha * s + (beta == 0.0 ? 0.0 : beta * C[i + j * ldc]);
    }
  }
}

/* C = alpha op(A) op(B) + beta C, column-major, by BLAS gemm (by GemmFewColumns for one or two columns of B not
   transposed); k = 0 only scales C (BLAS would not be called) */
PetscErrorCode JRGemm(const char *ta, const char *tb, PetscInt m, PetscInt n, PetscInt k, PetscReal alpha, const PetscReal *A, PetscInt lda, const PetscReal *B, PetscInt ldb, PetscReal beta, PetscReal *C, PetscInt ldc)
{
  PetscBLASInt bm, bn, bk, la, lb, lc;

  PetscFunctionBeginUser;
  if (!m || !n) PetscFunctionReturn(0);
  PetscCall(PetscBLASIntCast(m, &bm));
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCall(PetscBLASIntCast(k, &bk));
  PetscCall(PetscBLASIntCast(PetscMax(lda, 1), &la));
  PetscCall(PetscBLASIntCast(PetscMax(ldb, 1), &lb));
  PetscCall(PetscBLASIntCast(PetscMax(ldc, 1), &lc));
  if (!k) {
    if (beta != 1.0)
      for (PetscInt j = 0; j < n; j++)
        for (PetscInt i = 0; i < m; i++) C[i + j * ldc] *= beta;
    PetscFunctionReturn(0);
  }
  if (n <= 2 && (tb[0] == 'N' || tb[0] == 'n')) {
    GemmFewColumns((PetscBool)(ta[0] != 'N' && ta[0] != 'n'), m, n, k, alpha, A, lda, B, ldb, beta, C, ldc);
    PetscFunctionReturn(0);
  }
  PetscCallBLAS("BLASgemm", BLASgemm_(ta, tb, &bm, &bn, &bk, &alpha, A, &la, B, &lb, &beta, C, &lc));
  PetscFunctionReturn(0);
}

/* The vectors and dense Jacobian of the solve space (JRHBMGetSolveSize), sequential (either may be NULL) */
PetscErrorCode JRHBMCreateVecs(JRHBM h, Vec *x, Mat *J)
{
  PetscFunctionBeginUser;
  if (x) PetscCall(VecCreateSeq(PETSC_COMM_SELF, h->ns, x));
  if (J) {
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, h->ns, h->ns, NULL, J));
    PetscCall(MatSetOption(*J, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));
  }
  PetscFunctionReturn(0);
}

/* JRHBMGroupMotion - group g's element motions U (and V, with a normal direction) at the solve-space unknowns x:
   through their rows R (S) on the modal unknowns, or condensed through their coefficients on their joints' rows */
PetscErrorCode JRHBMGroupMotion(JRHBM h, JRHBMGroup *g, const PetscReal *x)
{
  const PetscInt nc = h->nc, nloc = g->nloc;

  PetscFunctionBeginUser;
  if (!h->cond) {
    PetscCall(JRGemm("N", "N", nloc, nc, h->nm, 1.0, g->R, nloc, x, h->nm, 0.0, g->U, nloc));
    if (g->normal) PetscCall(JRGemm("N", "N", nloc, nc, h->nm, 1.0, g->S, nloc, x, h->nm, 0.0, g->V, nloc));
    PetscFunctionReturn(0);
  }
  if (g->cw == 1) { /* one row per direction (a joint's mean motion) */
    for (PetscInt c = 0; c < nc; c++)
      for (PetscInt e = 0; e < nloc; e++) {
        g->U[e + c * nloc] = g->qw[2 * e] ? g->Ct[e] * x[g->qo[2 * e] + c * h->nq] : 0.0;
        if (g->normal) g->V[e + c * nloc] = g->qw[2 * e + 1] ? g->Cn[e] * x[g->qo[2 * e + 1] + c * h->nq] : 0.0;
      }
    PetscFunctionReturn(0);
  }
  for (PetscInt c = 0; c < nc; c++)
    for (PetscInt e = 0; e < nloc; e++) {
      const PetscReal *yt = x + g->qo[2 * e] + c * h->nq, *yn = x + g->qo[2 * e + 1] + c * h->nq;
      PetscReal        u = 0, v = 0;
      for (PetscInt r = 0; r < g->qw[2 * e]; r++) u += g->Ct[e + r * nloc] * yt[r];
      g->U[e + c * nloc] = u;
      if (!g->normal) continue;
      for (PetscInt r = 0; r < g->qw[2 * e + 1]; r++) v += g->Cn[e + r * nloc] * yn[r];
      g->V[e + c * nloc] = v;
    }
  PetscFunctionReturn(0);
}

/* The friction elements of g whose derivatives differ from their state at rest (dF/du = pt I, dF/dv = 0, dN/dv = pn
   I) into g->sel; their number */
static PetscInt SelectOutOfRest(JRHBMGroup *g, PetscInt nc)
{
  const PetscInt nloc = g->nloc;
  PetscInt       nsel = 0;

  for (PetscInt e = 0; e < nloc; e++) {
    const PetscReal tol = 1e-12 * g->kt[e], toln = 1e-12 * PetscMax(g->kn[e], g->kt[e]);
    PetscBool       rest = PETSC_TRUE;
    for (PetscInt q = 0; q < nc * nc && rest; q++) {
      const PetscBool diag = (PetscBool)(q / nc == q % nc);
      if (PetscAbsReal(g->DU[q * nloc + e] - (diag ? g->pt[e] : 0.0)) > tol) rest = PETSC_FALSE;
      if (g->normal && (PetscAbsReal(g->DV[q * nloc + e]) > toln || PetscAbsReal(g->DN[q * nloc + e] - (diag ? g->pn[e] : 0.0)) > toln)) rest = PETSC_FALSE;
    }
    if (!rest) g->sel[nsel++] = e;
  }
  return nsel;
}

/* Condensed, friction elements: their Jacobian at rest on the rows, Kq = sum_e pt_e c_e c_e^T + pn_e d_e d_e^T on each
   joint direction's block, and the blocks' widths qb (once per set-up) */
static PetscErrorCode CondensedRestJacobian(JRHBM h, JRHBMGroup *g)
{
  const PetscInt nq = h->nq, nloc = g->nloc;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc2(nq * nq, &g->Kq, nq, &g->qb));
  for (PetscInt e = 0; e < nloc; e++)
    for (PetscInt q = 0; q < 2; q++) {
      const PetscInt   o = g->qo[2 * e + q], w = g->qw[2 * e + q];
      const PetscReal  p = q ? g->pn[e] : g->pt[e], *C = q ? g->Cn : g->Ct;
      if (!w) continue;
      g->qb[o] = w;
      for (PetscInt l = 0; l < w; l++)
        for (PetscInt r = 0; r < w; r++) g->Kq[(o + r) + (o + l) * nq] += p * C[e + r * nloc] * C[e + l * nloc];
    }
  PetscFunctionReturn(0);
}

/* Condensed: every element of group g moves with its joint's few rows (its coefficients Ct, Cn on them): gathers and
   scatter-adds of its forces into loc (n) and, if jac, of its derivatives into its joint's block at loc + n (the
   joints' blocks, JRHBM Db's layout) */
static PetscErrorCode GroupCondensed(JRHBM h, JRHBMGroup *g, const PetscReal *a, PetscBool reuse, PetscBool derivs, PetscBool jac, PetscReal *loc)
{
  const PetscInt   nq = h->nq, nc = h->nc, n = h->ns, nloc = g->nloc;
  const PetscInt  *qo = g->qo, *qw = g->qw;
  const PetscReal *Ct = g->Ct, *Cn = g->Cn;

  PetscFunctionBeginUser;
  if (!reuse) {
    PetscCall(JRHBMGroupMotion(h, g, a));
    PetscCall(JRContactEvaluate(g->c, g->U, g->V, g->F, g->normal ? g->N : NULL, derivs ? g->DU : NULL, derivs && g->normal ? g->DV : NULL, derivs && g->normal ? g->DN : NULL, NULL));
    if (g->normal)
      for (PetscInt e = 0; e < nloc; e++) g->N[e] -= g->nstatic[e];
  }
  for (PetscInt c = 0; c < nc; c++)
    for (PetscInt e = 0; e < nloc; e++) {
      PetscReal      *yt = loc + qo[2 * e] + c * nq, *yn = loc + qo[2 * e + 1] + c * nq;
      const PetscReal f = g->F[e + c * nloc], fn = g->normal ? g->N[e + c * nloc] : 0.0;
      for (PetscInt r = 0; r < qw[2 * e]; r++) yt[r] += Ct[e + r * nloc] * f;
      for (PetscInt r = 0; r < qw[2 * e + 1]; r++) yn[r] += Cn[e + r * nloc] * fn;
    }
  if (jac) { /* c^T dF/du c, c^T dF/dv d, d^T dN/dv d on the joint's block of dg/dx (loc + n: the joints' blocks, JRHBM
                Db's layout), c and d the element's coefficients on its tangential and normal rows; for friction
                elements their part at rest (Kq) on every diagonal block and the rest only for the elements out of
                their state at rest, as GroupJacobian */
    PetscReal *D    = loc + n;
    PetscInt   nsel = 0;
    PetscCall(PetscLogEventBegin(JR_HBMJacobian, 0, 0, 0, 0));
    if (g->split) {
      if (!g->Kq) PetscCall(CondensedRestJacobian(h, g));
      for (PetscInt r0 = 0; r0 < nq; r0++) {
        const PetscInt w = g->qb[r0], j = h->qj[r0], bj = h->jio[j + 1] - h->jio[j], wj = bj / nc;
        if (!w) continue;
        for (PetscInt k = 0; k < nc; k++) {
          PetscReal *blk = D + h->dbo[j] + (k * wj + h->ql[r0]) * (1 + bj);
          for (PetscInt l = 0; l < w; l++)
            for (PetscInt r = 0; r < w; r++) blk[r + l * bj] += g->Kq[(r0 + r) + (r0 + l) * nq];
        }
      }
      nsel = SelectOutOfRest(g, nc);
    } else
      for (PetscInt e = 0; e < nloc; e++) g->sel[nsel++] = e;
    for (PetscInt k = 0; k < nc; k++)
      for (PetscInt m = 0; m < nc; m++) {
        const PetscReal *du = g->DU + (k * nc + m) * nloc, *dv = g->normal ? g->DV + (k * nc + m) * nloc : NULL, *dn = g->normal ? g->DN + (k * nc + m) * nloc : NULL;
        const PetscBool  diag = (PetscBool)(g->split && k == m);
        for (PetscInt s = 0; s < nsel; s++) {
          const PetscInt  e = g->sel[s], wt = qw[2 * e], wn = qw[2 * e + 1], j = h->qj[qo[2 * e]], bj = h->jio[j + 1] - h->jio[j], wj = bj / nc;
          const PetscInt  it = k * wj + h->ql[qo[2 * e]], jt = m * wj + h->ql[qo[2 * e]];
          const PetscReal dut = du[e] - (diag ? g->pt[e] : 0.0), dvt = wn ? dv[e] : 0.0, dnt = wn ? dn[e] - (diag ? g->pn[e] : 0.0) : 0.0;
          PetscReal      *Dj = D + h->dbo[j], *btt = Dj + it + jt * bj;
          for (PetscInt l = 0; l < wt; l++) {
            const PetscReal tu = dut * Ct[e + l * nloc];
            for (PetscInt r = 0; r < wt; r++) btt[r + l * bj] += Ct[e + r * nloc] * tu;
          }
          if (!wn) continue;
          {
            const PetscInt in = k * wj + h->ql[qo[2 * e + 1]], jn = m * wj + h->ql[qo[2 * e + 1]];
            PetscReal     *btn = Dj + it + jn * bj, *bnn = Dj + in + jn * bj;
            for (PetscInt l = 0; l < wn; l++) {
              const PetscReal tv = dvt * Cn[e + l * nloc], tn = dnt * Cn[e + l * nloc];
              for (PetscInt r = 0; r < wt; r++) btn[r + l * bj] += Ct[e + r * nloc] * tv;
              for (PetscInt r = 0; r < wn; r++) bnn[r + l * bj] += Cn[e + r * nloc] * tn;
            }
          }
        }
      }
    PetscCall(PetscLogFlops(2.0 * nsel * nc * nc * g->cw * g->cw * (g->normal ? 3 : 1)));
    PetscCall(PetscLogEventEnd(JR_HBMJacobian, 0, 0, 0, 0));
  }
  PetscFunctionReturn(0);
}

/* The Jacobian of group g's elements, R^T diag(dF/dU) R blockwise (and the normal blocks), added to loc (n x n
   column-major): friction elements' part at rest (Kst, Knn) once per diagonal block, the rest projected for the
   elements out of their state at rest only */
static PetscErrorCode GroupJacobian(JRHBM h, JRHBMGroup *g, PetscReal *loc)
{
  const PetscInt   nm = h->nm, nc = h->nc, n = h->ns, nloc = g->nloc;
  const PetscReal *GR = g->R, *GS = g->S, *Kst = g->Kst, *Knn = g->Knn;
  PetscInt         nsel = nloc;
  const PetscReal *Rj = GR, *Sj = GS;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(JR_HBMJacobian, 0, 0, 0, 0));
  if (g->split) {
    nsel    = SelectOutOfRest(g, nc);
    g->nsel = nsel;
    for (PetscInt i = 0; i < nm; i++) {
      for (PetscInt s = 0; s < nsel; s++) g->Rc[s + i * nsel] = GR[g->sel[s] + i * nloc];
      if (g->normal)
        for (PetscInt s = 0; s < nsel; s++) g->Sc[s + i * nsel] = GS[g->sel[s] + i * nloc];
    }
    Rj = g->Rc;
    Sj = g->Sc;
    /* the part at rest: Kst and Knn on the diagonal blocks */
    for (PetscInt k = 0; k < nc; k++) {
      PetscReal *blk = loc + n + (k * nm) + (k * nm) * n;
      for (PetscInt j = 0; j < nm; j++)
        for (PetscInt i = 0; i < nm; i++) blk[i + j * n] += Kst[i + j * nm] + (g->normal ? Knn[i + j * nm] : 0.0);
    }
  }
  if (nsel)
    for (PetscInt k = 0; k < nc; k++)
      for (PetscInt m = 0; m < nc; m++) {
        PetscReal     *blk   = loc + n + (k * nm) + (m * nm) * n;
        const PetscInt which = g->normal ? 3 : 1;
        for (PetscInt q = 0; q < which; q++) {
          const PetscReal *dall = (q == 0 ? g->DU : q == 1 ? g->DV : g->DN) + (k * nc + m) * nloc;
          const PetscReal *left = q == 2 ? Sj : Rj, *right = q == 0 ? Rj : Sj;
          PetscReal       *d    = g->Dc, dmax = 0.0;
          /* the selected elements' derivative, less the stuck part already counted */
          for (PetscInt s = 0; s < nsel; s++) {
            const PetscInt e = g->split ? g->sel[s] : s;
            d[s]             = dall[e] - (g->split && k == m ? (q == 0 ? g->pt[e] : q == 2 ? g->pn[e] : 0.0) : 0.0);
            dmax             = PetscMax(dmax, PetscAbsReal(d[s]));
          }
          if (dmax == 0.0) continue;
          for (PetscInt i = 0; i < nm; i++) {
            const PetscReal *col = right + i * nsel;
            PetscReal       *w   = g->W + i * nsel;
            for (PetscInt s = 0; s < nsel; s++) w[s] = d[s] * col[s];
          }
          PetscCall(JRGemm("T", "N", nm, nm, nsel, 1.0, left, nsel, g->W, nsel, 1.0, blk, n));
        }
      }
  PetscCall(PetscLogFlops(2.0 * nsel * nm * nm * nc * nc * (g->normal ? 3 : 1)));
  PetscCall(PetscLogEventEnd(JR_HBMJacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*
  Nonlinear part: res (n) and, if jac, the Jacobian (n x n column-major; condensed, dg/dx by its joints' blocks in
  the layout of JRHBM's Db) summed over all elements of all ranks (identical on every rank). a: the unknowns (n). With the analytic Jacobian, every
  evaluation also computes the element derivatives and keeps them with a copy of a: the Jacobian that
  Newton asks for next, at the same a, then only assembles them.
*/
PetscErrorCode JRHBMNonlinear(JRHBM h, const PetscReal *a, PetscReal *res, PetscReal *jac)
{
  const PetscInt  nm = h->cond ? h->nq : h->nm, nc = h->nc, n = h->ns, nj = h->cond ? h->dbo[h->njb] : n * n, len = jac ? n + nj : n; /* nm: the rows' length; nj: the Jacobian's, condensed its joints' blocks */
  PetscReal      *loc    = h->buf;
  const PetscBool derivs = (PetscBool)(jac || h->jtype == JR_HBM_JACOBIAN_ANALYTIC);
  PetscBool       reuse  = PETSC_FALSE;

  PetscLogDouble  t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  if (h->cache_ok) reuse = (PetscBool)!memcmp(a, h->cache_a, sizeof(PetscReal) * n); /* forces and derivatives kept from a call at this a (the Jacobian after the residual, the expansion after the accepted residual) */
  PetscCall(PetscArrayzero(loc, len));
  if (h->basis != JR_HBM_BASIS_FREE && h->Kc && !h->cond) { /* stuck basis: less the stuck springs, which are in Km (this rank's share; all of them if repl) */
    PetscCall(JRGemm("N", "N", nm, nc, nm, -1.0, h->Kc, nm, a, nm, 1.0, loc, nm));
    if (jac)
      for (PetscInt k = 0; k < nc; k++) {
        PetscReal *blk = loc + n + (k * nm) + (k * nm) * n;
        for (PetscInt j = 0; j < nm; j++)
          for (PetscInt i = 0; i < nm; i++) blk[i + j * n] -= h->Kc[i + j * nm];
      }
  }
  for (PetscInt t = 0; t < h->ngroups; t++) {
    JRHBMGroup      *g    = &h->g[t];
    const PetscInt   nloc = g->nloc;
    const PetscReal *GR = g->R, *GS = g->S;
    if (!nloc) continue;
    if (h->cond) {
      PetscCall(GroupCondensed(h, g, a, reuse, derivs, (PetscBool)(jac != NULL), loc));
      continue;
    }
    if (!reuse) {
      PetscCall(JRHBMGroupMotion(h, g, a));
      PetscCall(JRContactEvaluate(g->c, g->U, g->V, g->F, g->normal ? g->N : NULL, derivs ? g->DU : NULL, derivs && g->normal ? g->DV : NULL, derivs && g->normal ? g->DN : NULL, NULL));
      if (g->normal)
        for (PetscInt e = 0; e < nloc; e++) g->N[e] -= g->nstatic[e]; /* the dynamic normal load */
    }
    PetscCall(JRGemm("T", "N", nm, nc, nloc, 1.0, GR, nloc, g->F, nloc, 1.0, loc, nm));
    if (g->normal) PetscCall(JRGemm("T", "N", nm, nc, nloc, 1.0, GS, nloc, g->N, nloc, 1.0, loc, nm));
    if (jac) PetscCall(GroupJacobian(h, g, loc));
    PetscCall(PetscLogFlops(4.0 * nloc * nm * nc * (g->normal ? 2 : 1)));
  }
  if (!reuse) {
    h->cache_ok = derivs;
    PetscCall(PetscArraycpy(h->cache_a, a, n));
  }
  /* sum over the ranks on rank 0, then everyone gets the same numbers */
  if (h->size > 1 && !h->repl) {
    PetscCallMPI(MPI_Reduce(h->rank ? loc : MPI_IN_PLACE, loc, (PetscMPIInt)len, MPIU_REAL, MPIU_SUM, 0, h->comm));
    PetscCallMPI(MPI_Bcast(loc, (PetscMPIInt)len, MPIU_REAL, 0, h->comm));
  }
  PetscCall(PetscArraycpy(res, loc, n));
  if (jac) PetscCall(PetscArraycpy(jac, loc + n, nj));
  PetscCall(PetscTime(&t1));
  h->telem += t1 - t0;
  h->nelem++;
  if (jac) h->nelemjac++;
  PetscFunctionReturn(0);
}

/* Linear part of the residual (added to res), of the Jacobian (added to jac, may be NULL) and the
   frequency derivative dR/dw (set, may be NULL); no excitation in the EPMC's autonomous system (JRHBMSetEPMC) */
PetscErrorCode JRHBMLinear(JRHBM h, PetscReal w, const PetscReal *a, PetscReal *res, PetscReal *jac, PetscReal *dw)
{
  const PetscInt nm = h->nm, n = h->n;

  PetscFunctionBeginUser;
  if (dw) PetscCall(PetscArrayzero(dw, n));
  for (PetscInt i = 0; i < nm; i++) { /* mean: K a0 */
    PetscReal s = 0.0;
    for (PetscInt j = 0; j < nm; j++) s += h->Km[i * nm + j] * a[j];
    if (h->pin) s += h->pin[i] * a[i];
    res[i] += s;
    if (jac) {
      for (PetscInt j = 0; j < nm; j++) jac[i + j * n] += h->Km[i * nm + j];
      if (h->pin) jac[i + i * n] += h->pin[i];
    }
  }
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    const PetscInt   os = (2 * hh - 1) * nm, oc = 2 * hh * nm;
    const PetscReal  hw = hh * w;
    const PetscReal *as = a + os, *ac = a + oc;
    for (PetscInt i = 0; i < nm; i++) {
      PetscReal ds = 0.0, dc = 0.0, bs = 0.0, bc = 0.0, ms = 0.0, mc = 0.0, cs = 0.0, cc = 0.0;
      for (PetscInt j = 0; j < nm; j++) {
        const PetscReal kij = h->Km[i * nm + j], mij = h->Mm[i * nm + j], cij = h->Cm[i * nm + j];
        const PetscReal dij = kij - hw * hw * mij, bij = h->gamma * h->Kg[i * nm + j] + hw * cij;
        ds += dij * as[j];
        dc += dij * ac[j];
        bs += bij * as[j];
        bc += bij * ac[j];
        ms += mij * as[j];
        mc += mij * ac[j];
        cs += cij * as[j];
        cc += cij * ac[j];
        if (jac) {
          jac[(os + i) + (os + j) * n] += dij;
          jac[(os + i) + (oc + j) * n] -= bij;
          jac[(oc + i) + (os + j) * n] += bij;
          jac[(oc + i) + (oc + j) * n] += dij;
        }
      }
      res[os + i] += ds - bc - (hh == 1 && !h->epmc ? h->level * h->fm[i] : 0.0);
      res[oc + i] += dc + bs;
      if (dw) {
        dw[os + i] = -2.0 * hh * hw * ms - hh * cc;
        dw[oc + i] = -2.0 * hh * hw * mc + hh * cs;
      }
    }
  }
  PetscFunctionReturn(0);
}

/* R(a, w): the harmonic-balance residual (collective) */
PetscErrorCode JRHBMComputeResidual(JRHBM h, PetscReal w, Vec a, Vec R)
{
  const PetscScalar *x;
  PetscScalar       *r;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(PetscLogEventBegin(JR_HBMResidual, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(a, &x));
  PetscCall(VecGetArray(R, &r));
  PetscCall(JRHBMNonlinear(h, x, r, NULL));
  if (h->cond) PetscCall(JRHBMCondApply(h, w, x, r, NULL));
  else PetscCall(JRHBMLinear(h, w, x, r, NULL, NULL));
  PetscCall(VecRestoreArray(R, &r));
  PetscCall(VecRestoreArrayRead(a, &x));
  PetscCall(PetscLogEventEnd(JR_HBMResidual, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* J = dR/da (analytic) and, if Rw is not NULL, dR/dw (collective) */
PetscErrorCode JRHBMComputeJacobian(JRHBM h, PetscReal w, Vec a, Mat J, Vec Rw)
{
  const PetscScalar *x;
  PetscScalar       *j, *rw = NULL;
  PetscReal         *res;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  if (!h->jres) PetscCall(PetscMalloc1(h->ns, &h->jres));
  res = h->jres;
  PetscCall(VecGetArrayRead(a, &x));
  PetscCall(MatDenseGetArrayWrite(J, &j));
  if (Rw) PetscCall(VecGetArray(Rw, &rw));
  if (h->cond) { /* the Jacobian at the point, then formed */
    PetscCall(JRHBMCondJacobianPoint(h, w, x, rw));
    PetscCall(JRHBMCondJacobianForm(h, j, h->ns));
  } else {
    PetscCall(JRHBMNonlinear(h, x, res, j));
    PetscCall(JRHBMLinear(h, w, x, res, j, rw));
  }
  if (Rw) PetscCall(VecRestoreArray(Rw, &rw));
  PetscCall(MatDenseRestoreArrayWrite(J, &j));
  PetscCall(VecRestoreArrayRead(a, &x));
  PetscCall(JRMatDenseAssemble(J));
  PetscFunctionReturn(0);
}

/* JRHBMJacobianSetPoint - the Jacobian J = dR/da at (w, a) for JRHBMJacobianMult() and JRHBMJacobianForm(), and, if
   Rw is not NULL, dR/dw: written into J (JRHBMComputeJacobian), except for a model condensed onto its joints, whose
   J = I + G dg/dx is kept as the elements' derivatives, block diagonal by joint, and applied through the modes: it is
   formed only when it is factored (-hbm_condense_products 0: written into J as the others) (collective) */
PetscErrorCode JRHBMJacobianSetPoint(JRHBM h, PetscReal w, Vec a, Mat J, Vec Rw)
{
  const PetscScalar *x;
  PetscScalar       *rw = NULL;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  if (!h->cond || !h->jprod) {
    PetscCall(JRHBMComputeJacobian(h, w, a, J, Rw));
    PetscFunctionReturn(0);
  }
  if (!h->jres) PetscCall(PetscMalloc1(h->ns, &h->jres));
  PetscCall(VecGetArrayRead(a, &x));
  if (Rw) PetscCall(VecGetArray(Rw, &rw));
  PetscCall(JRHBMCondJacobianPoint(h, w, x, rw));
  if (Rw) PetscCall(VecRestoreArray(Rw, &rw));
  PetscCall(VecRestoreArrayRead(a, &x));
  PetscFunctionReturn(0);
}

/* JRHBMJacobianMult - y = J x with the Jacobian of the last JRHBMJacobianSetPoint() (J: the matrix given to it; not
   collective) */
PetscErrorCode JRHBMJacobianMult(JRHBM h, Mat J, const PetscScalar *x, PetscScalar *y)
{
  const PetscScalar *j;
  PetscInt           lda;
  PetscBLASInt       bn, blda, one = 1;
  PetscScalar        sone = 1.0, szero = 0.0;

  PetscFunctionBeginUser;
  if (h->cond && h->jprod) {
    PetscCall(JRHBMCondJacobianMult(h, x, y));
    PetscFunctionReturn(0);
  }
  PetscCall(MatDenseGetLDA(J, &lda));
  PetscCall(PetscBLASIntCast(h->ns, &bn));
  PetscCall(PetscBLASIntCast(lda, &blda));
  PetscCall(MatDenseGetArrayRead(J, &j));
  PetscCallBLAS("BLASgemv", BLASgemv_("N", &bn, &bn, &sone, j, &blda, x, &one, &szero, y, &one));
  PetscCall(MatDenseRestoreArrayRead(J, &j));
  PetscCall(PetscLogFlops(2.0 * h->ns * h->ns));
  PetscFunctionReturn(0);
}

/* JRHBMJacobianForm - the Jacobian of the last JRHBMJacobianSetPoint() into A (leading dimension lda; not collective) */
PetscErrorCode JRHBMJacobianForm(JRHBM h, Mat J, PetscScalar *A, PetscInt lda)
{
  const PetscScalar *j;
  PetscInt           ldj;

  PetscFunctionBeginUser;
  if (h->cond && h->jprod) {
    PetscCall(JRHBMCondJacobianForm(h, A, lda));
    PetscFunctionReturn(0);
  }
  PetscCall(MatDenseGetLDA(J, &ldj));
  PetscCall(MatDenseGetArrayRead(J, &j));
  for (PetscInt c = 0; c < h->ns; c++) PetscCall(PetscArraycpy(A + c * lda, j + c * ldj, h->ns));
  PetscCall(MatDenseRestoreArrayRead(J, &j));
  PetscFunctionReturn(0);
}

static PetscErrorCode FormFunction(SNES snes, Vec a, Vec R, void *ctx)
{
  JRHBM h = (JRHBM)ctx;

  PetscFunctionBeginUser;
  (void)snes;
  PetscCall(JRHBMComputeResidual(h, h->omega, a, R));
  PetscFunctionReturn(0);
}

static PetscErrorCode FormJacobian(SNES snes, Vec a, Mat J, Mat P, void *ctx)
{
  JRHBM h = (JRHBM)ctx;

  PetscFunctionBeginUser;
  (void)snes;
  (void)P;
  PetscCall(JRHBMComputeJacobian(h, h->omega, a, J, NULL));
  PetscFunctionReturn(0);
}

/* The nonlinear solver at fixed frequency: SNES on every rank (PETSC_COMM_SELF), prefix hbm_, dense Newton with LU,
   the analytic Jacobian or finite differences (-hbm_jacobian fd) */
PetscErrorCode JRHBMSetUpSolver(JRHBM h)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(h->buf));
  PetscCall(PetscMalloc1(h->ns + h->ns * h->ns, &h->buf));
  PetscCall(PetscFree(h->cache_a));
  PetscCall(PetscMalloc1(h->ns, &h->cache_a));
  h->cache_ok = PETSC_FALSE;
  PetscCall(SNESDestroy(&h->snes));
  PetscCall(MatDestroy(&h->J));
  PetscCall(VecDestroy(&h->r));
  PetscCall(JRHBMCreateVecs(h, &h->r, &h->J));
  PetscCall(SNESCreate(PETSC_COMM_SELF, &h->snes));
  {
    const char *pre;
    PetscCall(JRHBMGetOptionsPrefix(h, &pre));
    PetscCall(SNESSetOptionsPrefix(h->snes, pre));
  }
  PetscCall(SNESSetFunction(h->snes, h->r, FormFunction, h));
  if (h->jtype == JR_HBM_JACOBIAN_FD) PetscCall(SNESSetJacobian(h->snes, h->J, h->J, SNESComputeJacobianDefault, h));
  else PetscCall(SNESSetJacobian(h->snes, h->J, h->J, FormJacobian, h));
  {
    KSP ksp;
    PC  pc;
    PetscCall(SNESGetKSP(h->snes, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, PCLU));
  }
  PetscCall(SNESSetTolerances(h->snes, PETSC_DEFAULT, 1e-10, 1e-12, 40, 10000));
  PetscCall(SNESSetType(h->snes, SNESNEWTONDENSE));
  PetscCall(SNESSetFromOptions(h->snes));
  PetscFunctionReturn(0);
}

/* JRHBMResidualNorm - ||R|| relative to the excitation in the solve space (||F f_m||; condensed: the joints' static
   motion under it), the measure -hbm_residual_tol bounds; R: a residual of JRHBMComputeResidual() */
PetscErrorCode JRHBMResidualNorm(JRHBM h, Vec R, PetscReal *rel)
{
  PetscReal nr;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  if (h->rscale <= 0) PetscCall(JRHBMSetForceLevel(h, h->level));
  PetscCall(VecNorm(R, NORM_2, &nr));
  *rel = PetscIsInfOrNanReal(nr) ? PETSC_INFINITY : nr / h->rscale;
  PetscFunctionReturn(0);
}

/* JRHBMGetResidualTolerance - -hbm_residual_tol: a point is a solution when JRHBMResidualNorm() <= tol */
PetscErrorCode JRHBMGetResidualTolerance(JRHBM h, PetscReal *tol)
{
  PetscFunctionBeginUser;
  *tol = h->acctol;
  PetscFunctionReturn(0);
}

/* Solve R(a, w) = 0 at fixed frequency w from the guess in a; its: Newton iterations. converged only if the SNES
   converged and the residual meets -hbm_residual_tol (JRHBMResidualNorm()): a Newton that stalls on its step test
   (SNORM_RELATIVE) far from a solution, or meets its relative test from a poor guess, is not a solution; such a
   stop is given one more solve from where it stopped. The relative residual of the result is in *res (may be NULL). */
PetscErrorCode JRHBMSolveResidual(JRHBM h, PetscReal w, Vec a, PetscInt *its, PetscBool *converged, PetscReal *res)
{
  SNESConvergedReason reason;
  PetscReal           rel = PETSC_INFINITY;
  PetscInt            it;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(PetscLogEventBegin(JR_HBMSolve, 0, 0, 0, 0));
  h->omega = w;
  *its     = 0;
  for (PetscInt pass = 0; pass < 2; pass++) {
    Vec R;
    PetscCall(SNESSolve(h->snes, NULL, a));
    PetscCall(SNESGetConvergedReason(h->snes, &reason));
    PetscCall(SNESGetIterationNumber(h->snes, &it));
    *its += it;
    if (reason <= 0) break;
    PetscCall(SNESGetFunction(h->snes, &R, NULL, NULL)); /* the residual at the final point */
    PetscCall(JRHBMResidualNorm(h, R, &rel));
    if (rel <= h->acctol) break;
  }
  *converged = reason > 0 && rel <= h->acctol ? PETSC_TRUE : PETSC_FALSE;
  if (res) *res = rel;
  PetscCall(PetscLogEventEnd(JR_HBMSolve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Solve R(a, w) = 0 at fixed frequency w from the guess in a (JRHBMSolveResidual() without the residual) */
PetscErrorCode JRHBMSolve(JRHBM h, PetscReal w, Vec a, PetscInt *its, PetscBool *converged)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSolveResidual(h, w, a, its, converged, NULL));
  PetscFunctionReturn(0);
}

/* The response of the structure with every element linearised about rest (stuck contacts):
   one Newton step from a = 0, exact when the elements stay in full stick */
PetscErrorCode JRHBMLinearSolution(JRHBM h, PetscReal w, Vec a)
{
  const PetscInt     n = h->ns;
  const PetscScalar *j;
  PetscScalar       *x;
  PetscBool          singular;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(VecZeroEntries(a));
  PetscCall(JRHBMComputeJacobian(h, w, a, h->J, NULL)); /* and the residual at a = 0, in jres */
  if (!h->llu) PetscCall(PetscMalloc2(n * n, &h->llu, n, &h->lpiv));
  PetscCall(VecGetArray(a, &x));
  for (PetscInt i = 0; i < n; i++) x[i] = -h->jres[i];
  PetscCall(MatDenseGetArrayRead(h->J, &j));
  PetscCall(JRDenseSolve(n, j, n, h->llu, h->lpiv, x, &singular));
  PetscCall(MatDenseRestoreArrayRead(h->J, &j));
  PetscCall(VecRestoreArray(a, &x));
  PetscCheck(!singular, h->comm, PETSC_ERR_MAT_LU_ZRPVT, "The linearised harmonic-balance system is singular at %g Hz (a zero pivot): an undamped resonance or a rigid-body mode without -hbm_gamma or a stuck basis", (double)(w / (2 * PETSC_PI)));
  PetscFunctionReturn(0);
}
