/*
   The mixed basis of JRModes (JRModesMix): Ritz vectors of the stuck structure in the span of the stuck and
   free-interface modes and of the static correction vectors of the interface (the residual flexibility of the
   pairs' directions, compressed); and the basis check (JRModesCheckBasis).
*/
#include <jointrom/private/modelimpl.h>
#include <petscviewerhdf5.h>
#include <petscblaslapack.h>

/*
  JRModesSetMixed - these modes become a mixed basis (JRModesMix after JRModesSolve): a saved or loaded file holds the
  mixed basis whole, marked by the signature's sign, and the modes are saved once mixed, not when solved
*/
PetscErrorCode JRModesSetMixed(JRModes md)
{
  PetscFunctionBeginUser;
  if (md->mixed) PetscFunctionReturn(0);
  md->mixed = PETSC_TRUE;
  PetscCall(PetscStrncpy(md->save_mixed, md->save, sizeof(md->save_mixed)));
  md->save[0]  = 0;
  md->load_all = PETSC_TRUE;
  md->sig      = -md->sig - 1.0;
  md->sigraw   = -md->sigraw - 1.0;
  PetscFunctionReturn(0);
}

/*
  JRModesSetInterface - the interface's relative-displacement rows, for the static correction of a mixed basis
  (JRModesMix) and the basis check (JRModesCheckBasis): row i is b_i^T x = sum_k coef[i nper + k] x[dof[i nper + k]]
  (dof -1: no entry), e.g. (x_A - x_B) . t of a node-to-node pair (4.3), and k[i] > 0 its contact stiffness [N/m],
  which scales it. The same lists on every rank; copied.
*/
PetscErrorCode JRModesSetInterface(JRModes md, PetscInt n, PetscInt nper, const PetscInt dof[], const PetscReal coef[], const PetscReal k[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree3(md->irdof, md->ircoef, md->irk));
  md->nir  = n;
  md->nper = nper;
  PetscCall(PetscMalloc3(n * nper, &md->irdof, n * nper, &md->ircoef, n, &md->irk));
  PetscCall(PetscArraycpy(md->irdof, dof, n * nper));
  PetscCall(PetscArraycpy(md->ircoef, coef, n * nper));
  PetscCall(PetscArraycpy(md->irk, k, n));
  for (PetscInt i = 0; i < n; i++) PetscCheck(k[i] > 0, md->comm, PETSC_ERR_ARG_OUTOFRANGE, "Interface row %" PetscInt_FMT ": contact stiffness %g, must be positive", i, (double)k[i]);
  PetscFunctionReturn(0);
}

/* The interface DOFs' values gathered on every rank, and the rows' entries' places among them */
typedef struct {
  VecScatter sc;
  Vec        loc;
  PetscInt  *pos; /* nir nper: the entry's place in loc, -1 for none */
  PetscInt   lo, hi;
} Interface;

static PetscErrorCode InterfaceCreate(JRModes md, Vec x, Interface *c)
{
  const PetscInt ne = md->nir * md->nper;
  PetscInt      *all, nall = 0;
  IS             is;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(ne, &all));
  PetscCall(PetscMalloc1(ne, &c->pos));
  for (PetscInt k = 0; k < ne; k++)
    if (md->irdof[k] >= 0) all[nall++] = md->irdof[k];
  PetscCall(PetscSortRemoveDupsInt(&nall, all));
  for (PetscInt k = 0; k < ne; k++) {
    c->pos[k] = -1;
    if (md->irdof[k] >= 0) PetscCall(PetscFindInt(md->irdof[k], nall, all, &c->pos[k]));
  }
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nall, all, PETSC_COPY_VALUES, &is));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, nall, &c->loc));
  PetscCall(VecScatterCreate(x, is, c->loc, NULL, &c->sc));
  PetscCall(VecGetOwnershipRange(x, &c->lo, &c->hi));
  PetscCall(ISDestroy(&is));
  PetscCall(PetscFree(all));
  PetscFunctionReturn(0);
}

static PetscErrorCode InterfaceDestroy(Interface *c)
{
  PetscFunctionBeginUser;
  PetscCall(VecScatterDestroy(&c->sc));
  PetscCall(VecDestroy(&c->loc));
  PetscCall(PetscFree(c->pos));
  PetscFunctionReturn(0);
}

/* r = W^1/2 B^T x, on every rank (collective) */
static PetscErrorCode InterfaceRows(JRModes md, Interface *c, Vec x, PetscReal r[])
{
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(c->sc, x, c->loc, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(c->sc, x, c->loc, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(c->loc, &a));
  for (PetscInt i = 0; i < md->nir; i++) {
    PetscReal s = 0.0;
    for (PetscInt k = i * md->nper; k < (i + 1) * md->nper; k++)
      if (c->pos[k] >= 0) s += md->ircoef[k] * PetscRealPart(a[c->pos[k]]);
    r[i] = PetscSqrtReal(md->irk[i]) * s;
  }
  PetscCall(VecRestoreArrayRead(c->loc, &a));
  PetscFunctionReturn(0);
}

/* b = P^T B W^1/2 w = (I - M Q Q^T) B W^1/2 w (the load w on the interface, balanced by the inertia of the modes Q,
   M-orthonormal, MQ = M Q, BQ = W^1/2 B^T Q nir x nq col-major); d has room for nq */
static PetscErrorCode InterfaceLoad(JRModes md, Interface *c, const PetscReal w[], PetscInt nq, Vec MQ[], const PetscReal BQ[], PetscScalar d[], Vec b)
{
  PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(b));
  PetscCall(VecGetArray(b, &a));
  for (PetscInt i = 0; i < md->nir; i++) {
    if (w[i] == 0.0) continue;
    for (PetscInt k = i * md->nper; k < (i + 1) * md->nper; k++) {
      const PetscInt dof = md->irdof[k];
      if (dof >= c->lo && dof < c->hi) a[dof - c->lo] += PetscSqrtReal(md->irk[i]) * w[i] * md->ircoef[k];
    }
  }
  PetscCall(VecRestoreArray(b, &a));
  for (PetscInt q = 0; q < nq; q++) {
    PetscReal s = 0.0;
    for (PetscInt i = 0; i < md->nir; i++) s += BQ[i + q * md->nir] * w[i];
    d[q] = -s;
  }
  if (nq) PetscCall(VecMAXPY(b, nq, d, MQ));
  PetscFunctionReturn(0);
}

/* g = P g = (I - Q Q^T M) g: M-orthogonal to the modes Q */
static PetscErrorCode ProjectOut(PetscInt nq, Vec Q[], Vec MQ[], PetscScalar d[], Vec g)
{
  PetscFunctionBeginUser;
  if (!nq) PetscFunctionReturn(0);
  PetscCall(VecMDot(g, nq, MQ, d));
  for (PetscInt q = 0; q < nq; q++) d[q] = -d[q];
  PetscCall(VecMAXPY(g, nq, d, Q));
  PetscFunctionReturn(0);
}

/* The static solver: A = K - sigma M by a sparse LDL^T factorisation, MUMPS unless
   -modes_static_pc_factor_mat_solver_type says otherwise (-modes_static_ksp_*, -modes_static_pc_*). The shift sigma is
   -1e-6 times the lowest non-zero omega^2 of the modes (a free-free K is singular): on the loads, balanced by the
   modes' inertia, A^-1 is K^-1 to 1e-6 of that omega^2 over the response's own. */
static PetscErrorCode StaticSolver(JRModes md, KSP *ksp, Mat *A, PetscReal *shift)
{
  PetscReal sigma = 0.0;
  PC        pc;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < md->nm && sigma == 0.0; i++)
    if (md->lambda[i] > 0) sigma = -1e-6 * md->lambda[i];
  if (sigma == 0.0) PetscCall(JRModesDefaultShift_Private(md, &sigma));
  *shift = sigma;
  PetscCall(MatDuplicate(md->K, MAT_COPY_VALUES, A));
  PetscCall(MatAXPY(*A, -sigma, md->M, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatSetOption(*A, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(KSPCreate(md->comm, ksp));
  PetscCall(KSPSetOptionsPrefix(*ksp, "modes_static_"));
  PetscCall(KSPSetOperators(*ksp, *A, *A));
  PetscCall(KSPSetType(*ksp, KSPPREONLY));
  PetscCall(KSPGetPC(*ksp, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
#if defined(PETSC_HAVE_MUMPS)
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
#endif
  PetscCall(KSPSetFromOptions(*ksp));
  PetscCall(JRCheckFactorSolverType(pc, *A, "modes_static_"));
  PetscCall(KSPSetUp(*ksp));
  PetscFunctionReturn(0);
}

/*
  The interface's residual flexibility outside the span of the modes Q (M-orthonormal, MQ = M Q), in units of the
  contact stiffness: S = W^1/2 B^T P A^-1 P^T B W^1/2 (nir x nir, col-major, on every rank), with B the interface rows,
  W = diag(k), P = I - Q Q^T M and A = K - sigma M. S is symmetric and its eigenvalues are dimensionless: a pattern of
  contact forces f = W^1/2 v deforms the interface, beyond what the modes carry, by v^T S v / |v|^2 times the contact
  springs' own stretch. The nir solves go in blocks of columns. With qa (the diagonal Q^T A Q of modes Q that are also
  A-orthogonal: eigenvectors, or Ritz vectors of (K, M)), S = W^1/2 B^T (A^-1 - Q (Q^T A Q)^-1 Q^T) B W^1/2, the
  flexibility outside the span in the energy of A, which the first form equals only for eigenvectors.
*/
static PetscErrorCode ResidualFlexibility(JRModes md, KSP ksp, Interface *c, PetscInt nq, Vec Q[], Vec MQ[], const PetscReal BQ[], const PetscReal qa[], PetscReal S[])
{
  const PetscInt nr = md->nir, bs = PetscMin(64, nr);
  PetscInt       nloc, N;
  Mat            B, X;
  Vec            g;
  PetscScalar   *d;
  PetscReal     *w, *r;
  PetscLogDouble t0, tl, t;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  tl = t0;
  PetscCall(VecGetLocalSize(Q[0], &nloc));
  PetscCall(VecGetSize(Q[0], &N));
  PetscCall(MatCreateDense(md->comm, nloc, PETSC_DECIDE, N, bs, NULL, &B));
  PetscCall(MatDuplicate(B, MAT_DO_NOT_COPY_VALUES, &X));
  PetscCall(VecDuplicate(Q[0], &g));
  PetscCall(PetscMalloc1(PetscMax(nq, 1), &d));
  PetscCall(PetscCalloc2(nr, &w, nr, &r));
  for (PetscInt c0 = 0; c0 < nr; c0 += bs) {
    const PetscInt nb = PetscMin(bs, nr - c0);
    for (PetscInt j = 0; j < bs; j++) {
      Vec b;
      PetscCall(MatDenseGetColumnVecWrite(B, j, &b));
      if (j < nb) {
        w[c0 + j] = 1.0;
        PetscCall(InterfaceLoad(md, c, w, qa ? 0 : nq, MQ, BQ, d, b));
        w[c0 + j] = 0.0;
      } else PetscCall(VecZeroEntries(b));
      PetscCall(MatDenseRestoreColumnVecWrite(B, j, &b));
    }
    PetscCall(KSPMatSolve(ksp, B, X));
    for (PetscInt j = 0; j < nb; j++) {
      Vec x;
      PetscCall(MatDenseGetColumnVecRead(X, j, &x));
      PetscCall(VecCopy(x, g));
      PetscCall(MatDenseRestoreColumnVecRead(X, j, &x));
      if (qa) { /* g - Q (Q^T A Q)^-1 Q^T b, Q^T b = BQ's row of this pattern */
        for (PetscInt q = 0; q < nq; q++) d[q] = -BQ[c0 + j + q * nr] / qa[q];
        if (nq) PetscCall(VecMAXPY(g, nq, d, Q));
      } else PetscCall(ProjectOut(nq, Q, MQ, d, g));
      PetscCall(InterfaceRows(md, c, g, r));
      for (PetscInt i = 0; i < nr; i++) S[i + (c0 + j) * nr] = r[i];
    }
    PetscCall(PetscTime(&t)); /* progress on a large interface (minutes): first rank's clock */
    if (t - tl >= 20.0 && c0 + nb < nr) {
      PetscCall(PetscPrintf(md->comm, "modes: the interface's residual flexibility (static correction, basis check): %" PetscInt_FMT " of %" PetscInt_FMT " patterns solved, %.0f s\n", c0 + nb, nr, (double)(t - t0)));
      tl = t;
    }
  }
  for (PetscInt j = 0; j < nr; j++)
    for (PetscInt i = 0; i < j; i++) S[i + j * nr] = S[j + i * nr] = 0.5 * (S[i + j * nr] + S[j + i * nr]);
  PetscCall(PetscFree2(w, r));
  PetscCall(PetscFree(d));
  PetscCall(VecDestroy(&g));
  PetscCall(MatDestroy(&B));
  PetscCall(MatDestroy(&X));
  PetscFunctionReturn(0);
}

/*
  The static correction of the modes Q (M-orthonormal, MQ = M Q) and the basis check: the interface's residual
  flexibility S (ResidualFlexibility), its largest eigenvalues lam_1 >= lam_2 >= ... (only as many as may be kept,
  and one more: LAPACK's syevx, which on lap3's 4,420 patterns takes 8 s where the whole spectrum took 100 s), and,
  for the ns largest (nwant >= 0: that many; -1: those above -modes_static_tol, at most -modes_static_max), the static
  responses g_k = P A^-1 P^T B W^1/2 v_k to their patterns v_k (residual flexibility modes: M-orthogonal to Q), in one
  block solve, returned in G (unnormalised; *G NULL if ns = 0). md->rho0 = lam_1 (the check before the correction),
  md->rho = lam_{ns+1} (after).
  modes: Q are md's modes (eigenvectors or Ritz vectors, A-orthogonal: S in the energy of A, ResidualFlexibility).
*/
static PetscErrorCode StaticCorrection(JRModes md, PetscInt nq, Vec Q[], Vec MQ[], PetscBool modes, PetscInt nwant, PetscInt *ns, Vec **G)
{
  const PetscInt nr = md->nir;
  PetscLogDouble t0, t1;
  Interface      c;
  KSP            ksp;
  Vec            b;
  PetscReal     *BQ, *S, *lam, *work, *w;
  PetscScalar   *d;
  PetscBLASInt   bn, lwork, info;
  PetscInt       n = 0, top = 0;
  PetscReal      sigma = 0.0, *qa = NULL, *Z = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(JR_ModesStatic, 0, 0, 0, 0));
  *ns = 0;
  *G  = NULL;
  PetscCall(InterfaceCreate(md, Q[0], &c));
  PetscCall(PetscMalloc3(nr * PetscMax(nq, 1), &BQ, nr * nr, &S, nr, &lam));
  PetscCall(PetscMalloc2(nr, &w, PetscMax(nq, 1), &d));
  for (PetscInt q = 0; q < nq; q++) PetscCall(InterfaceRows(md, &c, Q[q], BQ + q * nr));
  if (!md->sksp) PetscCall(StaticSolver(md, &md->sksp, &md->sA, &md->ssigma)); /* kept for -modes_adapt (JRModesEnrich) */
  ksp   = md->sksp;
  sigma = md->ssigma;
  if (modes) { /* Q = md's modes, A-orthogonal */
    PetscCall(PetscMalloc1(PetscMax(nq, 1), &qa));
    for (PetscInt q = 0; q < nq; q++) qa[q] = md->lambda[q] - sigma;
  }
  PetscCall(ResidualFlexibility(md, ksp, &c, nq, Q, MQ, BQ, qa, S));
  PetscCall(PetscFree(qa));
  { /* the kt largest eigenpairs of S only (a few of thousands: bisection and inverse iteration, not the whole
       spectrum), ascending in lam[0 .. kt-1], their vectors in Z */
    const PetscInt kt = PetscMin(nr, (nwant >= 0 ? nwant : md->nstatic_max) + 1);
    PetscBLASInt   bil, biu, m = 0, *iw, *ifail;
    PetscReal      vl = 0, vu = 0, abstol = 0, wq;
    PetscCall(PetscBLASIntCast(nr, &bn));
    PetscCall(PetscBLASIntCast(nr - kt + 1, &bil));
    PetscCall(PetscBLASIntCast(nr, &biu));
    PetscCall(PetscMalloc1(nr * kt, &Z));
    PetscCall(PetscMalloc2(5 * nr, &iw, nr, &ifail));
    lwork = -1;
    PetscCallBLAS("LAPACKsyevx", LAPACKsyevx_("V", "I", "U", &bn, S, &bn, &vl, &vu, &bil, &biu, &abstol, &m, lam, Z, &bn, &wq, &lwork, iw, ifail, &info));
    PetscCall(PetscBLASIntCast((PetscInt)wq, &lwork));
    PetscCall(PetscMalloc1(lwork, &work));
    PetscCallBLAS("LAPACKsyevx", LAPACKsyevx_("V", "I", "U", &bn, S, &bn, &vl, &vu, &bil, &biu, &abstol, &m, lam, Z, &bn, work, &lwork, iw, ifail, &info));
    PetscCheck(!info && m == kt, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syevx failed: info %d, %d of %" PetscInt_FMT " eigenpairs", (int)info, (int)m, kt);
    PetscCall(PetscFree2(iw, ifail));
    PetscCall(PetscFree(work));
    top = kt;
  }
  if (nwant >= 0) n = PetscMin(nwant, nr);
  else
    while (n < nr && n < md->nstatic_max && lam[top - 1 - n] >= md->static_tol) n++;
  md->rho0 = PetscMax(lam[top - 1], 0.0);
  md->rho  = n < nr ? PetscMax(lam[top - 1 - n], 0.0) : 0.0;
  if (n) { /* the k-th largest pattern's static response, residual to Q, for the n patterns in one block solve */
    Mat      Bn, Xn;
    PetscInt nloc, N;
    PetscCall(VecGetLocalSize(Q[0], &nloc));
    PetscCall(VecGetSize(Q[0], &N));
    PetscCall(MatCreateDense(md->comm, nloc, PETSC_DECIDE, N, n, NULL, &Bn));
    PetscCall(MatDuplicate(Bn, MAT_DO_NOT_COPY_VALUES, &Xn));
    for (PetscInt k = 0; k < n; k++) {
      for (PetscInt i = 0; i < nr; i++) w[i] = Z[i + (top - 1 - k) * nr];
      PetscCall(MatDenseGetColumnVecWrite(Bn, k, &b));
      PetscCall(InterfaceLoad(md, &c, w, nq, MQ, BQ, d, b));
      PetscCall(MatDenseRestoreColumnVecWrite(Bn, k, &b));
    }
    PetscCall(KSPMatSolve(ksp, Bn, Xn));
    PetscCall(VecDuplicateVecs(Q[0], n, G));
    for (PetscInt k = 0; k < n; k++) {
      PetscCall(MatDenseGetColumnVecRead(Xn, k, &b));
      PetscCall(VecCopy(b, (*G)[k]));
      PetscCall(MatDenseRestoreColumnVecRead(Xn, k, &b));
      PetscCall(ProjectOut(nq, Q, MQ, d, (*G)[k]));
    }
    PetscCall(MatDestroy(&Bn));
    PetscCall(MatDestroy(&Xn));
  }
  for (PetscInt k = 1; k <= top; k *= 2) PetscCall(PetscInfo(NULL, "Interface residual flexibility x stiffness: pattern %" PetscInt_FMT " of %" PetscInt_FMT ": %g\n", k, nr, (double)lam[top - k]));
  *ns = n;
  PetscCall(PetscInfo(NULL, "Interface residual flexibility x stiffness: %" PetscInt_FMT " patterns, largest %g, %" PetscInt_FMT " kept, next %g\n", nr, (double)md->rho0, n, (double)md->rho));
  if (!md->adapt) PetscCall(JRModesEnrichEnd(md));
  PetscCall(PetscFree3(BQ, S, lam));
  PetscCall(PetscFree(Z));
  PetscCall(PetscFree2(w, d));
  PetscCall(InterfaceDestroy(&c));
  PetscCall(PetscLogEventEnd(JR_ModesStatic, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  md->tstatic += t1 - t0;
  PetscFunctionReturn(0);
}

/*
  JRModesCheckBasis - the basis check of the modes as they are (a free or stuck basis, or a mixed one read with
  -modes_load): the largest residual flexibility times contact stiffness of an interface pattern outside their span
  (StaticCorrection; JRModesGetBasisCheck). Nothing without interface rows (JRModesSetInterface) or with -modes_check 0.
*/
PetscErrorCode JRModesCheckBasis(JRModes md)
{
  Vec     *MQ, *G;
  PetscInt ns;

  PetscFunctionBeginUser;
  if (!md->nir || !md->check || !md->nm) PetscFunctionReturn(0);
  PetscCall(VecDuplicateVecs(md->phi[0], md->nm, &MQ));
  for (PetscInt i = 0; i < md->nm; i++) PetscCall(MatMult(md->M, md->phi[i], MQ[i]));
  PetscCall(StaticCorrection(md, md->nm, md->phi, MQ, PETSC_TRUE, 0, &ns, &G));
  md->nsadded = 0;
  PetscCall(VecDestroyVecs(md->nm, &MQ));
  PetscFunctionReturn(0);
}

/*
  JRModesGetBasisCheck - the basis check (-1 if not computed): rho, the largest residual flexibility times contact
  stiffness of an interface pattern outside the basis, rho0 the same before the static correction; tol its threshold
  (-modes_check_tol); ns the static correction vectors in the basis; t the seconds they and the check took
*/
PetscErrorCode JRModesGetBasisCheck(JRModes md, PetscReal *rho, PetscReal *rho0, PetscReal *tol, PetscInt *ns, PetscLogDouble *t)
{
  PetscFunctionBeginUser;
  if (rho) *rho = md->rho;
  if (rho0) *rho0 = md->rho0;
  if (tol) *tol = md->check_tol;
  if (ns) *ns = md->nsadded;
  if (t) *t = md->tstatic;
  PetscFunctionReturn(0);
}

/* Append v to the M-orthonormal Q (MQ = M Q) by Gram-Schmidt in the M inner product, twice; dropped when dependent
   (its remainder below 1e-6 of it). v is copied. */
static PetscErrorCode AppendOrthonormal(Mat M, Vec v, Vec Q[], Vec MQ[], PetscInt *nq, Vec Mv, PetscScalar d[])
{
  PetscScalar nn;
  PetscReal   n0;
  Vec         q;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(v, &q));
  PetscCall(VecCopy(v, q));
  PetscCall(MatMult(M, q, Mv));
  PetscCall(VecDot(q, Mv, &nn));
  n0 = PetscSqrtReal(PetscRealPart(nn));
  for (PetscInt pass = 0; pass < 2 && *nq; pass++) {
    PetscCall(VecMDot(q, *nq, MQ, d));
    for (PetscInt j = 0; j < *nq; j++) d[j] = -d[j];
    PetscCall(VecMAXPY(q, *nq, d, Q));
  }
  PetscCall(MatMult(M, q, Mv));
  PetscCall(VecDot(q, Mv, &nn));
  if (!(PetscSqrtReal(PetscRealPart(nn)) >= 1e-6 * n0) || n0 == 0.0) {
    PetscCall(VecDestroy(&q));
    PetscFunctionReturn(0);
  }
  PetscCall(VecScale(q, 1.0 / PetscSqrtReal(PetscRealPart(nn))));
  PetscCall(VecDuplicate(q, &MQ[*nq]));
  PetscCall(VecAXPBY(MQ[*nq], 1.0 / PetscSqrtReal(PetscRealPart(nn)), 0.0, Mv));
  Q[(*nq)++] = q;
  PetscFunctionReturn(0);
}

/* The Ritz vectors of (K + Ks, M) in the span of the M-orthonormal Q[nq] replace md's modes, eigenvalues ascending (Mv:
   a work vector, d room for nq) */
static PetscErrorCode Ritz(JRModes md, PetscInt nq, Vec Q[], Vec Mv, PetscScalar d[])
{
  PetscReal   *A, *lam, *work;
  PetscBLASInt bn, lwork, info;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc3(nq * nq, &A, nq, &lam, 8 * nq, &work));
  for (PetscInt j = 0; j < nq; j++) {
    PetscCall(MatMult(md->K, Q[j], Mv));
    PetscCall(VecMDot(Mv, nq, Q, d));
    for (PetscInt i = 0; i < nq; i++) A[i + j * nq] = PetscRealPart(d[i]);
  }
  for (PetscInt j = 0; j < nq; j++)
    for (PetscInt i = 0; i < j; i++) A[i + j * nq] = A[j + i * nq] = 0.5 * (A[i + j * nq] + A[j + i * nq]);
  PetscCall(PetscBLASIntCast(nq, &bn));
  PetscCall(PetscBLASIntCast(8 * nq, &lwork));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &bn, A, &bn, lam, work, &lwork, &info));
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed: info %d", (int)info);
  if (md->phi) PetscCall(VecDestroyVecs(md->nm, &md->phi));
  PetscCall(PetscFree(md->lambda));
  PetscCall(VecDuplicateVecs(Q[0], nq, &md->phi));
  PetscCall(PetscMalloc1(nq, &md->lambda));
  for (PetscInt i = 0; i < nq; i++) {
    PetscCall(VecZeroEntries(md->phi[i]));
    for (PetscInt j = 0; j < nq; j++) d[j] = A[j + i * nq];
    PetscCall(VecMAXPY(md->phi[i], nq, d, Q));
    md->lambda[i] = PetscAbsReal(lam[i]) <= 1e-10 * PetscAbsReal(lam[nq - 1]) ? 0.0 : lam[i];
  }
  md->nm = nq;
  PetscCall(PetscFree3(A, lam, work));
  PetscFunctionReturn(0);
}

/*
  JRModesMix - the mixed basis (after JRModesSetMixed and JRModesSolve): md's stuck modes (operators K + Ks, M), the nf
  lowest elastic free-interface modes of (K, M) (the free structure, rigid basis rb[nrb]) and, with interface rows
  (JRModesSetInterface), the static correction vectors of the interface (StaticCorrection: the residual flexibility
  modes of the stuck structure for the interface patterns that the modes miss most, -modes_static*), M-orthonormalised
  (dependent vectors dropped), then the Ritz vectors of (K + Ks, M) in their span, which replace md's modes: exact for
  the stuck structure and for the structure with the interface free, and static-complete for the patterns kept. Saved
  (-modes_save or the default file) once mixed; when the modes were read (-modes_load: the file holds the mixed basis)
  only the basis check is made, and not even that for a basis whose file records its adaptation to the peaks as
  converged (JRModesSaveAdaptation) unless -modes_adapt 0.
*/
PetscErrorCode JRModesMix(JRModes md, Mat K, PetscInt nf, PetscInt nrb, Vec rb[])
{
  JRModes       fm;
  Mat           M = md->M;
  PetscInt      nq = 0, ncand, ns = 0;
  Vec           *Q, *MQ, *cand, *G = NULL, Mv;
  PetscScalar  *d;

  PetscFunctionBeginUser;
  PetscCheck(md->mixed, md->comm, PETSC_ERR_ARG_WRONGSTATE, "JRModesSetMixed() first");
  if (md->load[0]) { /* a basis adapted to its peaks until a round added nothing (JRModesSaveAdaptation) is not checked: it
                        answers to the peaks' loads, not to every interface pattern */
    if (!(md->adapt && md->read_rounds && md->read_conv)) PetscCall(JRModesCheckBasis(md));
    PetscFunctionReturn(0);
  }
  PetscCall(JRModesCreate(md->comm, &fm));
  PetscCall(JRModesSetOperators(fm, K, M));
  PetscCall(JRModesSetFromOptions(fm));
  fm->load[0] = fm->save[0] = 0;
  fm->view                  = PETSC_FALSE;
  PetscCall(JRModesSetNumber(fm, nf + nrb));
  PetscCall(JRModesSetRigidBasis(fm, nrb, rb));
  PetscCall(JRModesSolve(fm));
  ncand = md->nm + nf;
  PetscCall(PetscMalloc1(ncand, &cand));
  PetscCall(PetscMalloc2(ncand + md->nir, &Q, ncand + md->nir, &MQ));
  PetscCall(PetscMalloc1(ncand + md->nir, &d));
  for (PetscInt i = 0; i < md->nm; i++) cand[i] = md->phi[i];
  for (PetscInt i = 0; i < nf; i++) cand[md->nm + i] = fm->phi[nrb + i];
  PetscCall(VecDuplicate(md->phi[0], &Mv));
  for (PetscInt c = 0; c < ncand; c++) PetscCall(AppendOrthonormal(M, cand[c], Q, MQ, &nq, Mv, d));
  if (md->nir && (md->nstatic || md->check)) { /* the static correction of the interface, and the check */
    PetscCall(StaticCorrection(md, nq, Q, MQ, PETSC_FALSE, md->nstatic, &ns, &G));
    for (PetscInt k = 0; k < ns; k++) PetscCall(AppendOrthonormal(M, G[k], Q, MQ, &nq, Mv, d));
    md->nsadded = ns;
    if (ns) PetscCall(VecDestroyVecs(ns, &G));
  }
  PetscCall(Ritz(md, nq, Q, Mv, d));
  PetscCall(PetscInfo(NULL, "Mixed basis: %" PetscInt_FMT " stuck + %" PetscInt_FMT " free modes + %" PetscInt_FMT " static correction vectors -> %" PetscInt_FMT " Ritz vectors\n", md->nev, nf, ns, nq));
  PetscCall(PetscFree(d));
  PetscCall(VecDestroy(&Mv));
  for (PetscInt i = 0; i < nq; i++) {
    PetscCall(VecDestroy(&Q[i]));
    PetscCall(VecDestroy(&MQ[i]));
  }
  PetscCall(PetscFree2(Q, MQ));
  PetscCall(PetscFree(cand));
  PetscCall(JRModesDestroy(&fm));
  if (md->save_mixed[0]) PetscCall(JRModesSave(md, md->save_mixed));
  PetscFunctionReturn(0);
}

/* One more reference to md: a holder (a JRHBM sharing another's modes) releases it with JRModesDestroy */

/*
  JRModesEnrich - the basis enriched for given loads (a mixed basis, after JRModesMix): F[np] are FE load vectors (e.g.
  the contact forces' deviation from the stuck springs at computed solutions, one per harmonic) and D (np x np,
  col-major) their Gram matrix in the compliance of the contact springs (sum_e f_i f_j / k_e). Their static responses
  outside the basis, g = (A^-1 - Phi (Phi^T A Phi)^-1 Phi^T) f with A = K - sigma M (the residual flexibility, as the
  basis check's), give the generalized eigenproblem (F^T G) v = lam D v: lam is the deformation that a combination of
  the loads causes beyond the basis, in units of the springs' own stretch under it (the basis check's measure, for
  these loads only). The combinations with lam > tol have their responses added, then the Ritz vectors of (K + Ks, M)
  replace the modes. lmax: the largest lam (before); nadd: the vectors added. Saved again (-modes_save or the default
  file) if anything was added. The factorisation of A is kept for the next call (JRModesEnrichEnd frees it). Collective.
*/
PetscErrorCode JRModesEnrich(JRModes md, PetscInt np, Vec F[], const PetscReal D[], PetscReal tol, PetscReal *lmax, PetscInt *nadd)
{
  KSP           ksp;
  Vec          *G, *Q, *MQ, Mv, h;
  PetscScalar  *d;
  PetscReal    *Gm, *Dm, *sd, *ev, *T, *work, sigma, dmax = 0.0;
  PetscBLASInt  bn, bk, lwork, info;
  PetscInt      nk = 0, nq = 0, n0;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  *lmax = 0.0;
  *nadd = 0;
  if (!np || !md->nm) PetscFunctionReturn(0);
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(JR_ModesStatic, 0, 0, 0, 0));
  if (!md->sksp) PetscCall(StaticSolver(md, &md->sksp, &md->sA, &md->ssigma)); /* kept for the next rounds */
  ksp   = md->sksp;
  sigma = md->ssigma;
  PetscCall(VecDuplicateVecs(md->phi[0], np, &G));
  PetscCall(PetscMalloc1(PetscMax(md->nm, np) + np, &d));
  for (PetscInt j = 0; j < np; j++) { /* g_j = A^-1 f_j - sum_q phi_q (phi_q^T f_j) / (lam_q - sigma) */
    PetscCall(KSPSolve(ksp, F[j], G[j]));
    PetscCall(VecMDot(F[j], md->nm, md->phi, d));
    for (PetscInt q = 0; q < md->nm; q++) d[q] = -d[q] / (md->lambda[q] - sigma);
    PetscCall(VecMAXPY(G[j], md->nm, d, md->phi));
  }
  /* (F^T G) v = lam D v, D's null space dropped: D = U S U^T, T = U_k S_k^-1/2, eig of T^T (F^T G) T */
  PetscCall(PetscMalloc6(np * np, &Gm, np * np, &Dm, np, &sd, np, &ev, np * np, &T, 8 * np, &work));
  for (PetscInt j = 0; j < np; j++) {
    PetscCall(VecMDot(G[j], np, F, d));
    for (PetscInt i = 0; i < np; i++) Gm[i + j * np] = PetscRealPart(d[i]);
  }
  for (PetscInt j = 0; j < np; j++)
    for (PetscInt i = 0; i < j; i++) Gm[i + j * np] = Gm[j + i * np] = 0.5 * (Gm[i + j * np] + Gm[j + i * np]);
  PetscCall(PetscArraycpy(Dm, D, np * np));
  PetscCall(PetscBLASIntCast(np, &bn));
  PetscCall(PetscBLASIntCast(8 * np, &lwork));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &bn, Dm, &bn, sd, work, &lwork, &info));
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed: info %d", (int)info);
  for (PetscInt k = 0; k < np; k++) dmax = PetscMax(dmax, sd[k]);
  for (PetscInt k = 0; k < np; k++) {
    if (!(sd[k] > 1e-12 * dmax)) continue;
    for (PetscInt i = 0; i < np; i++) T[i + nk * np] = Dm[i + k * np] / PetscSqrtReal(sd[k]);
    nk++;
  }
  if (nk) {
    PetscReal *GT, *H;
    PetscCall(PetscMalloc2(np * nk, &GT, nk * nk, &H));
    for (PetscInt j = 0; j < nk; j++)
      for (PetscInt i = 0; i < np; i++) {
        PetscReal s = 0.0;
        for (PetscInt l = 0; l < np; l++) s += Gm[i + l * np] * T[l + j * np];
        GT[i + j * np] = s;
      }
    for (PetscInt j = 0; j < nk; j++)
      for (PetscInt i = 0; i < nk; i++) {
        PetscReal s = 0.0;
        for (PetscInt l = 0; l < np; l++) s += T[l + i * np] * GT[l + j * np];
        H[i + j * nk] = s;
      }
    PetscCall(PetscBLASIntCast(nk, &bk));
    PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &bk, H, &bk, ev, work, &lwork, &info));
    PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed: info %d", (int)info);
    *lmax = PetscMax(ev[nk - 1], 0.0);
    /* the combinations above tol, largest first: v = T w, their responses G v appended to the modes */
    n0 = md->nm;
    PetscCall(PetscMalloc2(n0 + nk, &Q, n0 + nk, &MQ));
    PetscCall(VecDuplicate(md->phi[0], &Mv));
    PetscCall(VecDuplicate(md->phi[0], &h));
    for (PetscInt q = 0; q < n0; q++) {
      PetscCall(VecDuplicate(md->phi[q], &Q[q]));
      PetscCall(VecCopy(md->phi[q], Q[q]));
      PetscCall(VecDuplicate(md->phi[q], &MQ[q]));
      PetscCall(MatMult(md->M, md->phi[q], MQ[q]));
    }
    nq = n0;
    for (PetscInt k = nk - 1; k >= 0 && ev[k] > tol; k--) {
      for (PetscInt i = 0; i < np; i++) {
        PetscReal s = 0.0;
        for (PetscInt l = 0; l < nk; l++) s += T[i + l * np] * H[l + k * nk];
        d[i] = s;
      }
      PetscCall(VecZeroEntries(h));
      PetscCall(VecMAXPY(h, np, d, G));
      PetscCall(AppendOrthonormal(md->M, h, Q, MQ, &nq, Mv, d));
    }
    *nadd = nq - n0;
    if (*nadd) {
      PetscScalar *dq;
      PetscCall(PetscMalloc1(nq, &dq));
      PetscCall(Ritz(md, nq, Q, Mv, dq));
      PetscCall(PetscFree(dq));
      md->nadapt += *nadd;
    }
    for (PetscInt q = 0; q < nq; q++) {
      PetscCall(VecDestroy(&Q[q]));
      PetscCall(VecDestroy(&MQ[q]));
    }
    PetscCall(PetscFree2(Q, MQ));
    PetscCall(VecDestroy(&Mv));
    PetscCall(VecDestroy(&h));
    PetscCall(PetscFree2(GT, H));
  }
  PetscCall(PetscFree6(Gm, Dm, sd, ev, T, work));
  PetscCall(PetscFree(d));
  PetscCall(VecDestroyVecs(np, &G));
  PetscCall(PetscLogEventEnd(JR_ModesStatic, 0, 0, 0, 0));
  PetscCall(PetscTime(&t1));
  md->tadapt += t1 - t0;
  if (*nadd && md->save_mixed[0]) PetscCall(JRModesSave(md, md->save_mixed));
  PetscFunctionReturn(0);
}

/* JRModesEnrichEnd - frees the factorisation that JRModesEnrich keeps between rounds */
PetscErrorCode JRModesEnrichEnd(JRModes md)
{
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&md->sksp));
  PetscCall(MatDestroy(&md->sA));
  PetscFunctionReturn(0);
}
