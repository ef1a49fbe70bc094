/*
   JRHBM's modal basis (-hbm_basis free, stuck or mixed; -hbm_physical) and its linear modal matrices, the excitation
   and the outputs in it, the element groups (one per contact type, split across the ranks) with their projection rows
   r_e = phi(a_e) - phi(b_e) (4.3) and the constant part of their Jacobian, the stuck springs a stuck basis holds, and
   the natural frequencies and modes of the stuck structure in the basis.
*/
#include <jointrom/private/hbmimpl.h>

/* Dense copy of a (small) distributed matrix on every rank, row-major */
static PetscErrorCode DenseAll(Mat A, PetscReal D[])
{
  Mat     *sub;
  IS       all;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(MatGetSize(A, &n, NULL));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, n, 0, 1, &all));
  PetscCall(MatCreateSubMatrices(A, 1, &all, &all, MAT_INITIAL_MATRIX, &sub));
  PetscCall(PetscArrayzero(D, n * n));
  for (PetscInt i = 0; i < n; i++) {
    PetscInt           nz;
    const PetscInt    *cols;
    const PetscScalar *v;
    PetscCall(MatGetRow(sub[0], i, &nz, &cols, &v));
    for (PetscInt k = 0; k < nz; k++) D[i * n + cols[k]] = PetscRealPart(v[k]);
    PetscCall(MatRestoreRow(sub[0], i, &nz, &cols, &v));
  }
  PetscCall(MatDestroySubMatrices(1, &sub));
  PetscCall(ISDestroy(&all));
  PetscFunctionReturn(0);
}


/* Physical coordinates (-hbm_physical): K, M and C dense on every rank */
static PetscErrorCode SetUpPhysical(JRHBM h, Mat K, Mat M, Mat C, PetscInt ndof)
{
  PetscFunctionBeginUser;
  PetscCheck(ndof <= 2000, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_physical is for small systems (%" PetscInt_FMT " DOFs here, at most 2000): use modes", ndof);
  PetscCheck(h->zeta == 0.0, h->comm, PETSC_ERR_ARG_INCOMP, "-hbm_zeta (modal damping) needs modal coordinates, not -hbm_physical: give a damping matrix with -model_damping");
  PetscCheck(h->basis == JR_HBM_BASIS_FREE, h->comm, PETSC_ERR_ARG_INCOMP, "-hbm_basis stuck needs modal coordinates, not -hbm_physical");
  h->nm = ndof;
  PetscCall(PetscCalloc3(h->nm * h->nm, &h->Km, h->nm * h->nm, &h->Mm, h->nm * h->nm, &h->Cm));
  PetscCall(DenseAll(K, h->Km));
  PetscCall(DenseAll(M, h->Mm));
  if (C) PetscCall(DenseAll(C, h->Cm));
  PetscCall(PetscMalloc1(0, &h->omega_r));
  PetscFunctionReturn(0);
}

/* The interface rows of the node-to-node friction elements (4.3), tangential and, for jenkins_nv, normal, with their
   springs kt, kn as weights: the static correction and the check of the basis (JRModesSetInterface). Elements on the
   same pair and direction (-interface_split) make one row, their springs summed (in parallel). */
static PetscErrorCode SetInterfaceRows(JRModes md, const JRElements *el)
{
  PetscInt  *dof, n = 0, *key, *perm, nu = 0;
  PetscReal *coef, *k;

  PetscFunctionBeginUser;
  if (el->members) el = el->members; /* a reduced model: the basis is that of the node-to-node elements */
  if (!el->vdof_a) PetscFunctionReturn(0);
  PetscCall(PetscMalloc3(12 * el->n, &dof, 12 * el->n, &coef, 2 * el->n, &k));
  for (PetscInt e = 0; e < el->n; e++) {
    const char     *ty = el->typename[el->type[e]];
    const PetscBool nv = (PetscBool)!strcmp(ty, JRCONTACTJENKINSNV);
    if (!nv && strcmp(ty, JRCONTACTJENKINS)) continue;
    for (PetscInt dir = 0; dir < (nv ? 2 : 1); dir++, n++) {
      const PetscReal *d = (dir ? el->ndir : el->tdir) + 3 * e;
      for (PetscInt c = 0; c < 3; c++) {
        dof[6 * n + c]      = el->vdof_a[3 * e + c];
        coef[6 * n + c]     = d[c];
        dof[6 * n + 3 + c]  = el->vdof_b[3 * e + c];
        coef[6 * n + 3 + c] = -d[c];
      }
      k[n] = dir ? el->kn[e] : el->kt[e];
    }
  }
  PetscCall(PetscMalloc2(n, &key, n, &perm));
  for (PetscInt r = 0; r < n; r++) {
    key[r]  = dof[6 * r];
    perm[r] = r;
  }
  PetscCall(PetscSortIntWithPermutation(n, key, perm));
  for (PetscInt i = 0, run = 0; i < n; i++) { /* rows in the order of their first DOF; equal rows merged into the first */
    const PetscInt r = perm[i];
    PetscInt       j;
    if (i && dof[6 * r] != dof[6 * perm[run]]) run = i;
    for (j = run; j < i; j++) {
      const PetscInt q = perm[j];
      PetscBool      same = (PetscBool)(k[q] > 0);
      for (PetscInt c = 0; c < 6 && same; c++) same = (PetscBool)(dof[6 * q + c] == dof[6 * r + c] && coef[6 * q + c] == coef[6 * r + c]);
      if (same) {
        k[q] += k[r];
        k[r] = 0.0;
        break;
      }
    }
  }
  for (PetscInt r = 0; r < n; r++) { /* compress, keeping the order */
    if (k[r] == 0.0) continue;
    for (PetscInt c = 0; c < 6; c++) {
      dof[6 * nu + c]  = dof[6 * r + c];
      coef[6 * nu + c] = coef[6 * r + c];
    }
    k[nu++] = k[r];
  }
  PetscCall(JRModesSetInterface(md, nu, 6, dof, coef, k));
  PetscCall(PetscFree2(key, perm));
  PetscCall(PetscFree3(dof, coef, k));
  PetscFunctionReturn(0);
}

/* The modes of the basis: of K (free), of K plus the stuck springs of the elements el (stuck), or the mixed basis made
   from those and the free-interface modes; -modes_* options, saved and loaded (-modes_save, -modes_load) */
static PetscErrorCode SolveModes(JRHBM h, Mat K, Mat M, const JRElements *el)
{
  PetscFunctionBeginUser;
  PetscCall(JRModesDestroy(&h->modes));
  PetscCall(JRModesCreate(h->comm, &h->modes));
  if (h->basis != JR_HBM_BASIS_FREE) {
    Mat       Ks, KK;
    PetscReal sig, sigraw;
    PetscCall(JRElementsCreateStuckStiffness(K, el, &Ks));
    PetscCall(JRElementsStuckSignature(h->model, el, &sig, &sigraw));
    PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &KK));
    PetscCall(MatAXPY(KK, 1.0, Ks, DIFFERENT_NONZERO_PATTERN));
    PetscCall(JRModesSetOperators(h->modes, KK, M));
    PetscCall(JRModesSetSignature(h->modes, sig, sigraw));
    PetscCall(MatDestroy(&KK));
    PetscCall(MatDestroy(&Ks));
  } else PetscCall(JRModesSetOperators(h->modes, K, M));
  PetscCall(JRModesSetNumber(h->modes, h->nm));
  PetscCall(JRModesSetFromOptions(h->modes));
  PetscCall(JRModesSetNumber(h->modes, h->nm)); /* -hbm_modes wins over -modes_nev */
  PetscCall(JRModesSetSaveDefault(h->modes, h->modes_file));
  PetscCall(JRModesSetModel(h->modes, h->model));
  if (el) PetscCall(SetInterfaceRows(h->modes, el));
  if (h->basis == JR_HBM_BASIS_MIXED) PetscCall(JRModesSetMixed(h->modes));
  PetscCall(JRModesSolve(h->modes));
  if (h->basis != JR_HBM_BASIS_MIXED) PetscCall(JRModesCheckBasis(h->modes));
  if (h->basis == JR_HBM_BASIS_MIXED) { /* the stuck modes and the free-interface ones, mixed (Ritz) */
    PetscInt nrb;
    Vec      rb[6];
    PetscCall(JRModelGetRigidBasis(h->model, &nrb, rb));
    PetscCall(JRModesMix(h->modes, K, h->nfree >= 0 ? h->nfree : h->nm, nrb, rb));
    for (PetscInt i = 0; i < nrb; i++) PetscCall(VecDestroy(&rb[i]));
  }
  PetscFunctionReturn(0);
}

/* The linear modal matrices of the modes: Km = diag(omega_r^2), Mm = I, Cm = Phi^T C Phi + diag(2 zeta omega_r);
   rigid-body modes pinned */
static PetscErrorCode ModalMatrices(JRHBM h, Mat C)
{
  const PetscReal *lam;

  PetscFunctionBeginUser;
  h->nm = h->modes->nm;
  PetscCall(JRModesGetEigenvalues(h->modes, &lam));
  PetscCall(PetscCalloc3(h->nm * h->nm, &h->Km, h->nm * h->nm, &h->Mm, h->nm * h->nm, &h->Cm));
  PetscCall(PetscMalloc1(h->nm, &h->omega_r));
  PetscCall(PetscCalloc1(h->nm, &h->pin));
  for (PetscInt i = 0; i < h->nm; i++) {
    h->Km[i * h->nm + i] = lam[i];
    h->Mm[i * h->nm + i] = 1.0;
    h->omega_r[i]        = PetscSqrtReal(PetscMax(lam[i], 0.0));
  }
  /* A free-free structure's rigid-body modes stretch no element (their projection rows vanish) and no
     spring: their mean has no equation. It is zero (the excitation is harmonic), so pin it. */
  for (PetscInt i = 0; i < h->nm; i++)
    if (lam[i] <= 1e-8 * lam[h->nm - 1]) h->pin[i] = lam[h->nm - 1];
  if (C) PetscCall(JRModesProject(h->modes, C, h->Cm));
  for (PetscInt i = 0; i < h->nm; i++) h->Cm[i * h->nm + i] += 2.0 * h->zeta * h->omega_r[i];
  PetscFunctionReturn(0);
}

/* The linear part: the modes (or physical coordinates) and the modal matrices Km, Mm, Cm; h->nm is their number */
PetscErrorCode JRHBMSetUpBasis(JRHBM h, Mat K, Mat M, Mat C, PetscInt ndof, const JRElements *el)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree3(h->Km, h->Mm, h->Cm));
  PetscCall(PetscFree(h->omega_r));
  PetscCall(PetscFree(h->pin));
  if (h->physical) PetscCall(SetUpPhysical(h, K, M, C, ndof));
  else {
    h->nm = h->nmodes_opt > 0 ? h->nmodes_opt : (ndof <= 200 ? ndof : 10);
    PetscCheck(h->nm <= ndof, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_modes %" PetscInt_FMT ": the model has only %" PetscInt_FMT " DOFs", h->nm, ndof);
    if (!h->modes_shared) PetscCall(SolveModes(h, K, M, el));
    PetscCall(ModalMatrices(h, C));
  }
  PetscFunctionReturn(0);
}

/* The excitation shape in the basis, fm (-frf_dof or -frf_force_file: one value per DOF in the natural order of the
   model's DOFs, JRModelDOFsToNatural, as the coordinates of a -modes_save file), and the output DOFs' rows, Phiout */
PetscErrorCode JRHBMSetUpExcitation(JRHBM h, PetscInt ndof)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(h->fm));
  PetscCall(PetscCalloc1(h->nm, &h->fm));
  PetscCall(PetscFree(h->Phiout));
  PetscCall(PetscMalloc1(h->nout * h->nm, &h->Phiout));
  if (h->ffile[0]) {
    PetscReal *f;
    PetscCall(PetscMalloc1(ndof, &f));
    PetscCall(JRVecLoadFile(h->comm, h->ffile, ndof, f));
    if (h->physical) {
      PetscInt *nat;
      PetscCall(PetscMalloc1(ndof, &nat));
      for (PetscInt i = 0; i < ndof; i++) nat[i] = i;
      PetscCall(JRModelDOFsToNatural(h->model, ndof, nat, nat)); /* the file's order */
      for (PetscInt i = 0; i < ndof; i++) h->fm[i] = f[nat[i]];
      PetscCall(PetscFree(nat));
    } else {
      Vec          fv;
      PetscInt     lo, hi, *nat;
      PetscScalar *d;
      PetscCall(VecDuplicate(h->modes->phi[0], &fv));
      PetscCall(VecGetOwnershipRange(fv, &lo, &hi));
      PetscCall(PetscMalloc1(hi - lo + 1, &nat));
      for (PetscInt i = lo; i < hi; i++) nat[i - lo] = i;
      PetscCall(JRModelDOFsToNatural(h->model, hi - lo, nat, nat)); /* the file's order */
      for (PetscInt i = lo; i < hi; i++) PetscCall(VecSetValue(fv, i, f[nat[i - lo]], INSERT_VALUES));
      PetscCall(PetscFree(nat));
      PetscCall(VecAssemblyBegin(fv));
      PetscCall(VecAssemblyEnd(fv));
      PetscCall(PetscMalloc1(h->nm, &d));
      PetscCall(VecMDot(fv, h->nm, h->modes->phi, d));
      for (PetscInt i = 0; i < h->nm; i++) h->fm[i] = PetscRealPart(d[i]);
      PetscCall(PetscFree(d));
      PetscCall(VecDestroy(&fv));
    }
    PetscCall(PetscFree(f));
  } else if (h->physical) h->fm[h->fdof] = 1.0;
  else PetscCall(JRModesGetRows(h->modes, 1, &h->fdof, h->fm));
  if (h->physical) {
    PetscCall(PetscArrayzero(h->Phiout, h->nout * h->nm));
    for (PetscInt i = 0; i < h->nout; i++) h->Phiout[i * h->nm + h->outdof[i]] = 1.0;
  } else PetscCall(JRModesGetRows(h->modes, h->nout, h->outdof, h->Phiout));
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGroupDestroy(JRHBMGroup *g)
{
  PetscFunctionBeginUser;
  PetscCall(JRContactDestroy(&g->c));
  PetscCall(JRFreeAligned(&g->R));
  PetscCall(JRFreeAligned(&g->S));
  PetscCall(JRFreeAligned(&g->U));
  PetscCall(JRFreeAligned(&g->V));
  PetscCall(JRFreeAligned(&g->F));
  PetscCall(JRFreeAligned(&g->N));
  PetscCall(JRFreeAligned(&g->DU));
  PetscCall(JRFreeAligned(&g->DV));
  PetscCall(JRFreeAligned(&g->DN));
  PetscCall(JRFreeAligned(&g->W));
  PetscCall(PetscFree(g->nstatic));
  PetscCall(PetscFree(g->state));
  PetscCall(PetscFree2(g->Kst, g->Knn));
  PetscCall(PetscFree(g->sel));
  PetscCall(JRFreeAligned(&g->Rc));
  PetscCall(JRFreeAligned(&g->Sc));
  PetscCall(JRFreeAligned(&g->Dc));
  PetscCall(PetscFree4(g->kt, g->kn, g->pt, g->pn));
  PetscCall(PetscFree(g->eidx));
  PetscCall(PetscFree(g->Kc));
  PetscCall(PetscFree(g->R0));
  PetscCall(PetscFree(g->S0));
  PetscCall(PetscFree2(g->qo, g->qw));
  PetscCall(PetscFree2(g->Ct, g->Cn));
  PetscCall(PetscFree2(g->Kq, g->qb));
  PetscFunctionReturn(0);
}

/* Projection rows of a list of DOF pairs: rows[e*nm + i] = phi_i(a_e) - phi_i(b_e), col-major R */
static PetscErrorCode ProjectionRows(JRHBM h, PetscInt nloc, const PetscInt da[], const PetscInt db[], PetscReal R[])
{
  PetscInt  *dofs;
  PetscReal *rows;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(2 * nloc, &dofs, 2 * nloc * h->nm, &rows));
  for (PetscInt e = 0; e < nloc; e++) {
    dofs[2 * e]     = da[e];
    dofs[2 * e + 1] = db[e];
  }
  if (h->physical) {
    PetscCall(PetscArrayzero(rows, 2 * nloc * h->nm));
    for (PetscInt k = 0; k < 2 * nloc; k++)
      if (dofs[k] >= 0) rows[k * h->nm + dofs[k]] = 1.0;
  } else PetscCall(JRModesGetRows(h->modes, 2 * nloc, dofs, rows));
  for (PetscInt e = 0; e < nloc; e++)
    for (PetscInt i = 0; i < h->nm; i++) R[e + i * nloc] = rows[(2 * e) * h->nm + i] - rows[(2 * e + 1) * h->nm + i];
  PetscCall(PetscFree2(dofs, rows));
  PetscFunctionReturn(0);
}

/* Projection rows of node-to-node elements (4.3): R[e + i nloc] = sum_c dir_c (phi_i(A_c) - phi_i(B_c)) for the
   elements eidx[e] of the model's list, whose nodes' x, y, z DOFs are va[3 eidx..], vb[3 eidx..] */
PetscErrorCode JRHBMProjectionRowsDir(JRHBM h, PetscInt nloc, const PetscInt eidx[], const PetscInt va[], const PetscInt vb[], const PetscReal dir[], PetscReal R[])
{
  const PetscInt nm = h->nm, chunk = 8192; /* elements per gather: bounds the work arrays (6 chunk nm values) */
  PetscInt      *dofs, nch, nchmax;
  PetscReal     *rows;

  PetscFunctionBeginUser;
  nch = (nloc + chunk - 1) / chunk;
  PetscCall(MPIU_Allreduce(&nch, &nchmax, 1, MPIU_INT, MPI_MAX, h->comm)); /* the gather is collective */
  PetscCall(PetscMalloc2(6 * chunk, &dofs, 6 * chunk * nm, &rows));
  for (PetscInt c0 = 0, ch = 0; ch < PetscMax(nchmax, 1); ch++, c0 += chunk) {
    const PetscInt n = PetscMax(0, PetscMin(chunk, nloc - c0));
    for (PetscInt e = 0; e < n; e++)
      for (PetscInt c = 0; c < 3; c++) {
        dofs[6 * e + c]     = va[3 * eidx[c0 + e] + c];
        dofs[6 * e + 3 + c] = vb[3 * eidx[c0 + e] + c];
      }
    if (h->physical) {
      PetscCall(PetscArrayzero(rows, 6 * n * nm));
      for (PetscInt k = 0; k < 6 * n; k++)
        if (dofs[k] >= 0) rows[k * nm + dofs[k]] = 1.0;
    } else PetscCall(JRModesGetRows(h->modes, 6 * n, dofs, rows));
    for (PetscInt e = 0; e < n; e++) {
      const PetscReal *d = dir + 3 * eidx[c0 + e];
      for (PetscInt i = 0; i < nm; i++) {
        PetscReal r = 0.0;
        for (PetscInt c = 0; c < 3; c++) r += d[c] * (rows[(6 * e + c) * nm + i] - rows[(6 * e + 3 + c) * nm + i]);
        R[c0 + e + i * nloc] = r;
      }
    }
  }
  PetscCall(PetscFree2(dofs, rows));
  PetscFunctionReturn(0);
}


/* One group's set-up work: its elements' numbers in the model's list, DOF pairs and parameters */
typedef struct {
  PetscInt  *eidx, *ia, *ib;
  PetscReal *kt, *kn, *mu, *n0;
} GroupInput;

/* The elements of type t on this rank (a contiguous share of them; all of them if h->repl) and their contact batch */
static PetscErrorCode GroupElements(JRHBM h, const JRElements *el, PetscInt t, JRHBMGroup *g, GroupInput *in)
{
  PetscInt ntot = 0, nloc = PETSC_DECIDE, start = 0, k = 0;

  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < el->n; e++) ntot += el->type[e] == t;
  if (h->repl) nloc = ntot;
  else {
    PetscCall(PetscSplitOwnership(h->comm, &nloc, &ntot));
    PetscCallMPI(MPI_Scan(&nloc, &start, 1, MPIU_INT, MPI_SUM, h->comm));
    start -= nloc;
  }
  g->nloc = nloc;
  PetscCall(PetscMalloc4(nloc, &in->kt, nloc, &in->kn, nloc, &in->mu, nloc, &in->n0));
  PetscCall(PetscMalloc2(nloc, &in->ia, nloc, &in->ib));
  PetscCall(PetscMalloc1(nloc, &g->nstatic));
  PetscCall(PetscMalloc1(nloc, &g->state));
  PetscCall(PetscMalloc1(nloc, &in->eidx));
  for (PetscInt e = 0, cnt = 0; e < el->n; e++) {
    if (el->type[e] != t) continue;
    if (cnt >= start && cnt < start + nloc) {
      in->eidx[k]   = e;
      in->ia[k]     = el->dof_a[e];
      in->ib[k]     = el->dof_b[e];
      in->kt[k]     = el->kt[e];
      in->kn[k]     = el->kn[e];
      in->mu[k]     = el->mu[e];
      in->n0[k]     = el->n0[e];
      g->nstatic[k] = PetscMax(el->n0[e], 0.0);
      k++;
    }
    cnt++;
  }
  PetscCall(JRContactCreate(PETSC_COMM_SELF, &g->c));
  PetscCall(JRContactSetType(g->c, el->typename[t]));
  PetscCall(JRContactSetHarmonics(g->c, h->H, h->Ns));
  PetscCall(JRContactSetElements(g->c, nloc, in->kt, in->kn, in->mu, in->n0));
  PetscCall(JRContactSetUp(g->c));
  PetscCall(JRContactUsesNormal(g->c, &g->normal));
  PetscFunctionReturn(0);
}

/* The group's projection rows R (tangential) and, for elements with a normal direction, S: a reduced model's from its
   joints' fields (field), node-to-node elements' along their directions (4.3), others' of their DOF pairs; the members
   of joints (first reduction, 4.4) then move with their joint's field. Collective. */
static PetscErrorCode GroupRows(JRHBM h, const JRElements *el, JRHBMGroup *g, GroupInput *in, const PetscReal field[])
{
  const PetscInt nc = h->nc, nm = h->nm, nloc = g->nloc;

  PetscFunctionBeginUser;
  PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nm, &g->R));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nm, &g->W));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc, &g->U));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc, &g->F));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc * nc, &g->DU));
  if (el->members) PetscCall(JRJointFieldRows(h, el, nloc, in->eidx, field, 0, g->R));
  else if (el->vdof_a) PetscCall(JRHBMProjectionRowsDir(h, nloc, in->eidx, el->vdof_a, el->vdof_b, el->tdir, g->R));
  else PetscCall(ProjectionRows(h, nloc, in->ia, in->ib, g->R));
  if (g->normal) {
    for (PetscInt k = 0; k < nloc; k++) {
      in->ia[k] = el->ndof_a[in->eidx[k]];
      in->ib[k] = el->ndof_b[in->eidx[k]];
    }
    PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nm, &g->S));
    PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc, &g->V));
    PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc, &g->N));
    PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc * nc, &g->DV));
    PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc * nc, &g->DN));
    if (el->members) PetscCall(JRJointFieldRows(h, el, nloc, in->eidx, field, 1, g->S));
    else if (el->vdof_a) PetscCall(JRHBMProjectionRowsDir(h, nloc, in->eidx, el->vdof_a, el->vdof_b, el->ndir, g->S));
    else PetscCall(ProjectionRows(h, nloc, in->ia, in->ib, g->S));
  }
  if (el->joint && !el->members) {
    if (h->basis != JR_HBM_BASIS_FREE) { /* the basis holds the members' own stuck springs: Kc must cancel exactly those */
      PetscCall(PetscMalloc1(nloc * nm, &g->R0));
      PetscCall(PetscArraycpy(g->R0, g->R, nloc * nm));
      if (g->normal) {
        PetscCall(PetscMalloc1(nloc * nm, &g->S0));
        PetscCall(PetscArraycpy(g->S0, g->S, nloc * nm));
      }
    }
    PetscCall(JRJointAverage(h, el, nloc, in->eidx, g->R, g->normal ? g->S : NULL));
  }
  PetscFunctionReturn(0);
}

/* Friction elements (jenkins, jenkins_nv): the Jacobian of the elements in their state at rest, once,
   Kst = sum_e pt_e r_e r_e^T and Knn = sum_e pn_e s_e s_e^T; and the work arrays of the rest's projection */
static PetscErrorCode GroupRestJacobian(JRHBM h, const JRElements *el, PetscInt t, JRHBMGroup *g, const GroupInput *in)
{
  const PetscInt nm = h->nm, nloc = g->nloc;

  PetscFunctionBeginUser;
  g->split = (PetscBool)(!strcmp(el->typename[t], JRCONTACTJENKINS) || !strcmp(el->typename[t], JRCONTACTJENKINSNV));
  PetscCall(PetscCalloc2(nm * nm, &g->Kst, nm * nm, &g->Knn));
  PetscCall(PetscMalloc4(nloc, &g->kt, nloc, &g->kn, nloc, &g->pt, nloc, &g->pn));
  PetscCall(PetscArraycpy(g->kt, in->kt, nloc));
  PetscCall(PetscArraycpy(g->kn, in->kn, nloc));
  for (PetscInt e = 0; e < nloc; e++) {
    g->pt[e] = g->nstatic[e] > 0 ? in->kt[e] : 0.0;
    g->pn[e] = g->nstatic[e] > 0 ? in->kn[e] : 0.0;
  }
  PetscCall(PetscMalloc1(nloc, &g->sel));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nm, &g->Rc));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc, &g->Dc));
  if (g->normal) PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nm, &g->Sc));
  if (g->split && nloc) {
    for (PetscInt i = 0; i < nm; i++)
      for (PetscInt e = 0; e < nloc; e++) g->W[e + i * nloc] = g->pt[e] * g->R[e + i * nloc];
    PetscCall(JRGemm("T", "N", nm, nm, nloc, 1.0, g->R, nloc, g->W, nloc, 0.0, g->Kst, nm));
    if (g->normal) {
      for (PetscInt i = 0; i < nm; i++)
        for (PetscInt e = 0; e < nloc; e++) g->W[e + i * nloc] = g->pn[e] * g->S[e + i * nloc];
      PetscCall(JRGemm("T", "N", nm, nm, nloc, 1.0, g->S, nloc, g->W, nloc, 0.0, g->Knn, nm));
    }
  }
  PetscFunctionReturn(0);
}

/* Element groups, one per contact type, split across the ranks (or, if h->repl, all of a reduced model's elements on
   every rank): their contact batches, projection rows and constant Jacobian (field: a reduced model's joint fields).
   Collective. */
PetscErrorCode JRHBMSetUpGroups(JRHBM h, const JRElements *el, const PetscReal field[])
{
  PetscFunctionBeginUser;
  for (PetscInt t = 0; t < h->ngroups; t++) PetscCall(JRHBMGroupDestroy(&h->g[t]));
  PetscCall(PetscFree(h->g));
  h->ngroups = el->ntypes;
  PetscCall(PetscCalloc1(h->ngroups, &h->g));
  for (PetscInt t = 0; t < h->ngroups; t++) {
    JRHBMGroup *g = &h->g[t];
    GroupInput  in;
    PetscCall(GroupElements(h, el, t, g, &in));
    PetscCall(GroupRows(h, el, g, &in, field));
    PetscCall(GroupRestJacobian(h, el, t, g, &in));
    PetscCall(PetscFree4(in.kt, in.kn, in.mu, in.n0));
    PetscCall(PetscFree2(in.ia, in.ib));
    g->eidx = in.eidx;
  }
  PetscFunctionReturn(0);
}

/* Stuck basis: each element's stuck spring is in Km already, so the element adds F - kt u (its deviation from
   stuck); structural damping acts on the structure's own stiffness Kg = Km - Phi^T Ks Phi only. Kc: the stuck springs
   of this rank's elements (all of them if h->repl). Collective. */
PetscErrorCode JRHBMSetUpStuckSprings(JRHBM h, const JRElements *el)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(h->Kg));
  PetscCall(PetscMalloc1(h->nm * h->nm, &h->Kg));
  PetscCall(PetscArraycpy(h->Kg, h->Km, h->nm * h->nm));
  if (h->basis != JR_HBM_BASIS_FREE) {
    const PetscInt nm = h->nm;
    PetscReal     *loc, *all;
    PetscCall(PetscCalloc2(nm * nm, &loc, nm * nm, &all));
    for (PetscInt t = 0; t < h->ngroups && !el->members; t++) {
      JRHBMGroup *g = &h->g[t];
      PetscCall(PetscCalloc1(nm * nm, &g->Kc));
      if (!g->split || !g->nloc) continue;
      {
        const PetscReal *Rk = g->R0 ? g->R0 : g->R, *Sk = g->S0 ? g->S0 : g->S;
        for (PetscInt i = 0; i < nm; i++)
          for (PetscInt e = 0; e < g->nloc; e++) g->W[e + i * g->nloc] = (g->nstatic[e] > 0 ? g->kt[e] : 0.0) * Rk[e + i * g->nloc];
        PetscCall(JRGemm("T", "N", nm, nm, g->nloc, 1.0, Rk, g->nloc, g->W, g->nloc, 0.0, g->Kc, nm));
        if (g->normal) {
          for (PetscInt i = 0; i < nm; i++)
            for (PetscInt e = 0; e < g->nloc; e++) g->W[e + i * g->nloc] = (g->nstatic[e] > 0 ? g->kn[e] : 0.0) * Sk[e + i * g->nloc];
          PetscCall(JRGemm("T", "N", nm, nm, g->nloc, 1.0, Sk, g->nloc, g->W, g->nloc, 1.0, g->Kc, nm));
        }
      }
      PetscCall(PetscFree(g->R0));
      PetscCall(PetscFree(g->S0));
      for (PetscInt i = 0; i < nm * nm; i++) h->Kc[i] += g->Kc[i];
    }
    PetscCall(PetscArraycpy(loc, h->Kc, nm * nm));
    /* a reduced model's members are split over the ranks (JRJointRows), the elements with h->repl are not */
    PetscCall(MPIU_Allreduce(loc, all, nm * nm, MPIU_REAL, MPIU_SUM, el->members ? h->comm : h->ecomm));
    if (h->repl) PetscCall(PetscArraycpy(h->Kc, all, nm * nm)); /* every rank has every element: the whole sum */
    for (PetscInt i = 0; i < nm; i++)
      for (PetscInt j = 0; j < nm; j++) h->Kg[i * nm + j] -= all[i + j * nm];
    PetscCall(PetscFree2(loc, all));
  }
  PetscFunctionReturn(0);
}

/* The natural frequencies [Hz] of the structure with the elements in contact at rest stuck, their springs scaled by
   scale and each element's kt by ktf[e] (e in the model's element list; NULL: 1), in the basis; and, if vec is not
   NULL, the *kvec-th mode (M-normalised), or where near is given the mode most like near (the largest |near^T Mm q|),
   its index in *kvec */
static PetscErrorCode StickEigF(JRHBM h, PetscReal scale, const PetscReal ktf[], PetscInt *nf, PetscReal freq[], PetscInt *kvec, PetscReal vec[], const PetscReal *near)
{
  const PetscInt nm = h->nm;
  PetscReal     *A, *B, *loc, *w, *work;
  PetscBLASInt   n, lwork, info, itype = 1;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(PetscCalloc5(nm * nm, &A, nm * nm, &B, nm * nm, &loc, nm, &w, 8 * nm, &work));
  for (PetscInt t = 0; t < h->ngroups; t++) { /* the elements in contact at rest (n0 > 0), stuck, on the structure's own Kg */
    JRHBMGroup *g = &h->g[t];
    PetscCheck(g->split || !g->nloc, PETSC_COMM_SELF, PETSC_ERR_SUP, "Stuck frequencies need friction elements (jenkins, jenkins_nv)");
    if (!g->nloc) continue;
    for (PetscInt i = 0; i < nm; i++)
      for (PetscInt e = 0; e < g->nloc; e++) g->W[e + i * g->nloc] = (g->nstatic[e] > 0 ? g->kt[e] * (ktf ? ktf[g->eidx[e]] : 1.0) : 0.0) * g->R[e + i * g->nloc];
    PetscCall(JRGemm("T", "N", nm, nm, g->nloc, scale, g->R, g->nloc, g->W, g->nloc, 1.0, loc, nm));
    if (g->normal) {
      for (PetscInt i = 0; i < nm; i++)
        for (PetscInt e = 0; e < g->nloc; e++) g->W[e + i * g->nloc] = (g->nstatic[e] > 0 ? g->kn[e] : 0.0) * g->S[e + i * g->nloc];
      PetscCall(JRGemm("T", "N", nm, nm, g->nloc, scale, g->S, g->nloc, g->W, g->nloc, 1.0, loc, nm));
    }
  }
  PetscCall(MPIU_Allreduce(loc, A, nm * nm, MPIU_REAL, MPIU_SUM, h->ecomm));
  for (PetscInt i = 0; i < nm; i++)
    for (PetscInt j = 0; j < nm; j++) {
      A[i + j * nm] += h->Kg[i * nm + j];
      B[i + j * nm] = h->Mm[i * nm + j];
    }
  PetscCall(PetscBLASIntCast(nm, &n));
  PetscCall(PetscBLASIntCast(8 * nm, &lwork));
  PetscCallBLAS("LAPACKsygv", LAPACKsygv_(&itype, vec ? "V" : "N", "U", &n, A, &n, B, &n, w, work, &lwork, &info));
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK sygv failed: info %d", (int)info);
  for (PetscInt i = 0; i < nm; i++) freq[i] = PetscSqrtReal(PetscMax(w[i], 0.0)) / (2 * PETSC_PI);
  if (vec && near) { /* the mode most like near */
    PetscReal best = -1, *Mn;
    PetscCall(PetscCalloc1(nm, &Mn));
    for (PetscInt i = 0; i < nm; i++)
      for (PetscInt j = 0; j < nm; j++) Mn[j] += near[i] * h->Mm[i * nm + j];
    for (PetscInt k = 0; k < nm; k++) {
      PetscReal d = 0;
      for (PetscInt j = 0; j < nm; j++) d += Mn[j] * A[j + k * nm];
      if (PetscAbsReal(d) > best) {
        best  = PetscAbsReal(d);
        *kvec = k;
      }
    }
    PetscCall(PetscFree(Mn));
  }
  if (vec)
    for (PetscInt i = 0; i < nm; i++) vec[i] = A[i + *kvec * nm];
  *nf = nm;
  PetscCall(PetscFree5(A, B, loc, w, work));
  PetscFunctionReturn(0);
}

/* StickEigF with every kt as it is, the kvec-th mode */
static PetscErrorCode StickEig(JRHBM h, PetscReal scale, PetscInt *nf, PetscReal freq[], PetscInt kvec, PetscReal vec[])
{
  PetscFunctionBeginUser;
  PetscCall(StickEigF(h, scale, NULL, nf, freq, &kvec, vec, NULL));
  PetscFunctionReturn(0);
}

/*
  JRHBMStickFrequencies - natural frequencies [Hz] of the linear structure with every element stuck
  (tangential springs kt and, for jenkins_nv, normal springs kn; only the elements in contact at rest,
  n0 > 0) in the modal basis of the HBM: eigenvalues of Phi^T (K + sum_e kt r_e r_e^T + kn s_e s_e^T) Phi
  (collective; freq has room for nm).
*/
PetscErrorCode JRHBMStickFrequencies(JRHBM h, PetscInt *nf, PetscReal freq[])
{
  PetscFunctionBeginUser;
  PetscCall(StickEig(h, 1.0, nf, freq, -1, NULL));
  PetscFunctionReturn(0);
}

/*
  JRHBMMatchStickFrequency - the factor c on every element's stiffness (kt, kn) that puts the k-th stuck natural
  frequency (JRHBMStickFrequencies) at target [Hz]: the stiffness correction of a reduced model, by a bracketed
  secant (Illinois) solve on the eigenvalue in the modal basis, to 1e-12 relative (collective; the model is not
  changed: scale its elements by c and set it up again). c = 0 if no factor in [1e-3, 1e3] reaches the target (the
  elements cannot carry that much stiffness in that mode).
*/
PetscErrorCode JRHBMMatchStickFrequency(JRHBM h, PetscInt k, PetscReal target, PetscReal *c)
{
  PetscReal *f, lo = 1.0, hi = 1.0, glo, ghi, x = 1.0, gx;
  PetscInt   nf, side = 0;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCheck(k >= 0 && k < h->nm, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "Stuck mode %" PetscInt_FMT ": the basis has %" PetscInt_FMT, k, h->nm);
  PetscCall(PetscMalloc1(h->nm, &f));
  PetscCall(StickEig(h, 1.0, &nf, f, -1, NULL));
  glo = ghi = f[k] - target;
  for (PetscInt it = 0; glo > 0 && it < 10; it++) {
    hi  = lo;
    ghi = glo;
    lo *= 0.5;
    PetscCall(StickEig(h, lo, &nf, f, -1, NULL));
    glo = f[k] - target;
  }
  for (PetscInt it = 0; ghi < 0 && it < 10; it++) {
    lo  = hi;
    glo = ghi;
    hi *= 2.0;
    PetscCall(StickEig(h, hi, &nf, f, -1, NULL));
    ghi = f[k] - target;
  }
  if (!(glo <= 0 && ghi >= 0)) {
    *c = 0;
    PetscCall(PetscFree(f));
    PetscFunctionReturn(0);
  }
  x = lo;
  for (PetscInt it = 0; it < 200 && hi - lo > 1e-13 * hi; it++) {
    x = (lo * ghi - hi * glo) / (ghi - glo);
    PetscCall(StickEig(h, x, &nf, f, -1, NULL));
    gx = f[k] - target;
    if (PetscAbsReal(gx) <= 1e-12 * target) break;
    if (gx < 0) {
      lo  = x;
      glo = gx;
      if (side == -1) ghi *= 0.5;
      side = -1;
    } else {
      hi  = x;
      ghi = gx;
      if (side == 1) glo *= 0.5;
      side = 1;
    }
  }
  *c = x;
  PetscCall(PetscFree(f));
  PetscFunctionReturn(0);
}

/* The modal coordinates q (in the basis) as every element's tangential relative motion u[e] and, if v is not NULL,
   normal relative motion v[e] (0 without a normal direction), e in the model's element list, on every rank */
static PetscErrorCode ElementMotion(JRHBM h, const PetscReal q[], PetscReal u[], PetscReal v[])
{
  const JRElements *el;
  PetscReal        *loc;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetElements(h, &el));
  PetscCall(PetscCalloc1(2 * el->n, &loc));
  for (PetscInt t = 0; t < h->ngroups; t++) {
    JRHBMGroup *g = &h->g[t];
    for (PetscInt e = 0; e < g->nloc; e++) {
      PetscReal s = 0, sn = 0;
      for (PetscInt i = 0; i < h->nm; i++) s += g->R[e + i * g->nloc] * q[i];
      for (PetscInt i = 0; g->normal && i < h->nm; i++) sn += g->S[e + i * g->nloc] * q[i];
      loc[g->eidx[e]]         = s;
      loc[el->n + g->eidx[e]] = sn;
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, loc, (PetscMPIInt)(2 * el->n), MPIU_REAL, MPIU_SUM, h->ecomm));
  PetscCall(PetscArraycpy(u, loc, el->n));
  if (v) PetscCall(PetscArraycpy(v, loc + el->n, el->n));
  PetscCall(PetscFree(loc));
  PetscFunctionReturn(0);
}

/*
  JRHBMStuckModeMotion - the k-th stuck mode (JRHBMStickFrequencies, M-normalised in the basis) as every element's
  tangential relative motion u[e] (e in the model's element list, on every rank; collective) and, if v is not NULL,
  normal relative motion v[e] (0 for elements without a normal direction)
*/
PetscErrorCode JRHBMStuckModeMotion(JRHBM h, PetscInt k, PetscReal u[], PetscReal v[])
{
  PetscReal *q, omega;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(PetscMalloc1(h->nm, &q));
  PetscCall(JRHBMStuckMode(h, k, &omega, q));
  PetscCall(ElementMotion(h, q, u, v));
  PetscCall(PetscFree(q));
  PetscFunctionReturn(0);
}

/*
  JRHBMReleasedModeMotion - the stuck structure (JRHBMStickFrequencies) with each element's kt scaled by ktf[e] (0:
  freed; e in the model's element list, ktf on every rank): of its modes, the one most like the k-th stuck mode q_k
  (the largest |q^T Mm q_k|), as every element's tangential relative motion u[e] (on every rank), and its frequency
  *freq [Hz]. Collective.
*/
PetscErrorCode JRHBMReleasedModeMotion(JRHBM h, PetscInt k, const PetscReal ktf[], PetscReal u[], PetscReal *freq)
{
  PetscReal *f, *q, *qs;
  PetscInt   nf, kr = k;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCheck(k >= 0 && k < h->nm, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "Stuck mode %" PetscInt_FMT ": the basis has %" PetscInt_FMT, k, h->nm);
  PetscCall(PetscMalloc3(h->nm, &f, h->nm, &q, h->nm, &qs));
  PetscCall(StickEig(h, 1.0, &nf, f, k, qs));
  PetscCall(StickEigF(h, 1.0, ktf, &nf, f, &kr, q, qs));
  *freq = f[kr];
  PetscCall(ElementMotion(h, q, u, NULL));
  PetscCall(PetscFree3(f, q, qs));
  PetscFunctionReturn(0);
}

/* JRHBMStuckMode - the k-th stuck mode in the basis (M-normalised, nm coefficients q) and its circular frequency
   omega [rad/s] (collective) */
PetscErrorCode JRHBMStuckMode(JRHBM h, PetscInt k, PetscReal *omega, PetscReal q[])
{
  PetscReal *f;
  PetscInt   nf;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCheck(k >= 0 && k < h->nm, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "Stuck mode %" PetscInt_FMT ": the basis has %" PetscInt_FMT, k, h->nm);
  PetscCall(PetscMalloc1(h->nm, &f));
  PetscCall(StickEig(h, 1.0, &nf, f, k, q));
  *omega = 2 * PETSC_PI * f[k];
  PetscCall(PetscFree(f));
  PetscFunctionReturn(0);
}

/*
  JRHBMStuckSpringEnergy - the stuck springs' share of q^T K q for the modal coordinates q (nm, in this JRHBM's basis),
  per joint of its elements: E[j] = sum over the elements e of joint j in contact at rest (n0 > 0) of
  kt_e (r_e . q)^2 + kn_e (s_e . q)^2, with each element's rows as it moves (a reduced model's: its joint's field).
  For an M-normalised mode, E[j] / omega^2 is joint j's share of the mode's strain energy and 2x the relative
  sensitivity of omega to a factor on joint j's springs (d omega / omega = E[j] / (2 omega^2) dc / c). E has room for
  the elements' njoints (1 if none: the sum over all elements); on every rank. Collective.
*/
PetscErrorCode JRHBMStuckSpringEnergy(JRHBM h, const PetscReal q[], PetscReal E[])
{
  const JRElements *el;
  PetscInt          nj;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(JRHBMGetElements(h, &el));
  nj = el->joint ? el->njoints : 1;
  PetscCall(PetscArrayzero(E, nj));
  for (PetscInt t = 0; t < h->ngroups; t++) {
    JRHBMGroup *g = &h->g[t];
    PetscCheck(g->split || !g->nloc, PETSC_COMM_SELF, PETSC_ERR_SUP, "Stuck springs need friction elements (jenkins, jenkins_nv)");
    for (PetscInt e = 0; e < g->nloc; e++) {
      PetscReal s = 0, sn = 0;
      if (!(g->nstatic[e] > 0)) continue;
      for (PetscInt i = 0; i < h->nm; i++) s += g->R[e + i * g->nloc] * q[i];
      for (PetscInt i = 0; g->normal && i < h->nm; i++) sn += g->S[e + i * g->nloc] * q[i];
      E[el->joint ? el->joint[g->eidx[e]] : 0] += g->kt[e] * s * s + (g->normal ? g->kn[e] * sn * sn : 0.0);
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, E, (PetscMPIInt)nj, MPIU_REAL, MPIU_SUM, h->ecomm));
  PetscFunctionReturn(0);
}

/*
  JRHBMStuckModeBalance - the energy balance of the k-th stuck mode q (M-normalised) at resonance, for the modal
  amplitude a: per cycle the excitation of level F puts in pi F |q.fm| a and the linear damping takes out
  damp a^2 = pi (gamma q^T Kg q + omega q^T Cm q) a^2. omega [rad/s], force = |q.fm| (per unit level). Collective.
*/
PetscErrorCode JRHBMStuckModeBalance(JRHBM h, PetscInt k, PetscReal *omega, PetscReal *force, PetscReal *damp)
{
  PetscReal *q, fq = 0, kq = 0, cq = 0;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(PetscMalloc1(h->nm, &q));
  PetscCall(JRHBMStuckMode(h, k, omega, q));
  for (PetscInt i = 0; i < h->nm; i++) {
    fq += h->fm[i] * q[i];
    for (PetscInt j = 0; j < h->nm; j++) {
      kq += q[i] * h->Kg[i * h->nm + j] * q[j];
      cq += q[i] * h->Cm[i * h->nm + j] * q[j];
    }
  }
  *force = PetscAbsReal(fq);
  *damp  = PETSC_PI * (h->gamma * kq + *omega * cq);
  PetscCall(PetscFree(q));
  PetscFunctionReturn(0);
}


/*
  JRHBMEnrichBasis - the modal basis of a node-to-node model enriched for the solutions a[ns] (e.g. the peaks of its
  curves): each solution's contact forces, harmonic by harmonic, less the stuck springs that the basis already holds
  (none in a free basis), are FE loads whose static responses outside the basis are added where they deform the
  interface by more than tol times the springs' own stretch (JRModesEnrich); a deviation below 1e-3 of the
  solution's dynamic contact forces (in the springs' compliance) does not count. h must then be set up again on its
  modes (JRHBMSetModes on a new JRHBM). lmax: the largest such deformation ratio before; nadd: the vectors added.
  Collective.
*/
PetscErrorCode JRHBMEnrichBasis(JRHBM h, PetscInt ns, Vec a[], PetscReal tol, PetscReal *lmax, PetscInt *nadd)
{
  const JRElements *el;
  const PetscInt    nc = h->nc, nm = h->nm, np = ns * nc;
  PetscInt          nloc = 0;
  Vec              *F;
  PetscReal        *Dt, *Dn, *D, *Dall, *T; /* T: each solution's dynamic contact forces in the springs' compliance */
  PetscBool         mine;                    /* this rank adds its elements' loads (every element on every rank: rank 0's) */

  PetscFunctionBeginUser;
  *lmax = 0.0;
  *nadd = 0;
  PetscCall(JRHBMSetUp(h));
  PetscCall(JRHBMGetElements(h, &el));
  if (!ns || h->physical || h->cond || !el || el->members || !el->vdof_a) PetscFunctionReturn(0);
  mine = (PetscBool)(!h->repl || !h->rank);
  for (PetscInt t = 0; t < h->ngroups && mine; t++) nloc += h->g[t].split ? h->g[t].nloc : 0;
  PetscCall(VecDuplicateVecs(h->modes->phi[0], np, &F));
  for (PetscInt p = 0; p < np; p++) PetscCall(VecZeroEntries(F[p]));
  PetscCall(PetscCalloc4(PetscMax(nloc * np, 1), &Dt, PetscMax(nloc * np, 1), &Dn, np * np, &D, np * np, &Dall));
  PetscCall(PetscCalloc1(ns, &T));
  h->cache_ok = PETSC_FALSE;
  for (PetscInt s = 0; s < ns; s++) {
    const PetscScalar *x;
    PetscInt           off = 0;
    PetscCall(VecGetArrayRead(a[s], &x));
    for (PetscInt t = 0; t < h->ngroups && mine; t++) {
      JRHBMGroup *g = &h->g[t];
      if (!g->split || !g->nloc) continue;
      PetscCall(JRGemm("N", "N", g->nloc, nc, nm, 1.0, g->R, g->nloc, x, nm, 0.0, g->U, g->nloc));
      if (g->normal) PetscCall(JRGemm("N", "N", g->nloc, nc, nm, 1.0, g->S, g->nloc, x, nm, 0.0, g->V, g->nloc));
      PetscCall(JRContactEvaluate(g->c, g->U, g->V, g->F, g->normal ? g->N : NULL, NULL, NULL, NULL, NULL));
      for (PetscInt e = 0; e < g->nloc; e++) {
        const PetscInt   ei = g->eidx[e];
        const PetscReal  kst = h->basis != JR_HBM_BASIS_FREE ? g->pt[e] : 0.0, ksn = h->basis != JR_HBM_BASIS_FREE ? g->pn[e] : 0.0;
        const PetscReal *td = el->tdir + 3 * ei, *nd = el->ndir + 3 * ei;
        for (PetscInt c = 0; c < nc; c++) {
          const PetscReal ft = g->F[e + c * g->nloc] - kst * g->U[e + c * g->nloc];
          const PetscReal fn = g->normal ? g->N[e + c * g->nloc] - (c ? 0.0 : g->nstatic[e]) - ksn * g->V[e + c * g->nloc] : 0.0;
          const PetscInt  p  = s * nc + c;
          PetscInt        idx[6];
          PetscScalar     val[6];
          const PetscReal nt = g->F[e + c * g->nloc], nn = g->normal ? g->N[e + c * g->nloc] - (c ? 0.0 : g->nstatic[e]) : 0.0;
          Dt[off + e + p * nloc] = ft / PetscSqrtReal(g->kt[e]);
          if (g->normal) Dn[off + e + p * nloc] = fn / PetscSqrtReal(g->kn[e]);
          T[s] += nt * nt / g->kt[e] + (g->normal ? nn * nn / g->kn[e] : 0.0);
          for (PetscInt k = 0; k < 3; k++) {
            idx[k]     = el->vdof_a[3 * ei + k];
            idx[3 + k] = el->vdof_b[3 * ei + k];
            val[k]     = ft * td[k] + fn * nd[k];
            val[3 + k] = -val[k];
          }
          PetscCall(VecSetValues(F[p], 6, idx, val, ADD_VALUES));
        }
      }
      off += g->nloc;
    }
    PetscCall(VecRestoreArrayRead(a[s], &x));
  }
  for (PetscInt p = 0; p < np; p++) {
    PetscCall(VecAssemblyBegin(F[p]));
    PetscCall(VecAssemblyEnd(F[p]));
  }
  if (nloc) {
    PetscCall(JRGemm("T", "N", np, np, nloc, 1.0, Dt, nloc, Dt, nloc, 0.0, D, np));
    PetscCall(JRGemm("T", "N", np, np, nloc, 1.0, Dn, nloc, Dn, nloc, 1.0, D, np));
  }
  PetscCall(MPIU_Allreduce(D, Dall, np * np, MPIU_REAL, MPIU_SUM, h->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, T, ns, MPIU_REAL, MPIU_SUM, h->comm));
  for (PetscInt p = 0; p < np; p++) Dall[p + p * np] += 1e-6 * T[p / nc]; /* a floor: deviations below 1e-3 of the forces do not count */
  PetscCall(JRModesEnrich(h->modes, np, F, Dall, tol, lmax, nadd));
  PetscCall(PetscFree4(Dt, Dn, D, Dall));
  PetscCall(PetscFree(T));
  PetscCall(VecDestroyVecs(np, &F));
  PetscFunctionReturn(0);
}

/* The modes of h's basis (NULL in physical coordinates); not a new reference */
PetscErrorCode JRHBMGetModes(JRHBM h, JRModes *md)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  *md = h->physical ? NULL : h->modes;
  PetscFunctionReturn(0);
}
