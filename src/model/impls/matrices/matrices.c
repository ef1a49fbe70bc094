/*
   -model_type matrices: a structure given by its matrices, so that models from any FE code can be
   brought in and small systems checked. -model_stiffness FILE, -model_mass FILE, optional
   -model_damping FILE (viscous C), optional -model_elements FILE.csv. Formats by extension
   (src/sys/matio.c): .mtx, .bin, .h5 (groups K, M, C by default). K, M (and C) must be square, of
   one size, and symmetric; M positive definite, K positive semidefinite (checked by LDL^T inertia).
*/
#include <jointrom/private/modelimpl.h>

typedef struct {
  char K[PETSC_MAX_PATH_LEN], M[PETSC_MAX_PATH_LEN], C[PETSC_MAX_PATH_LEN], elements[PETSC_MAX_PATH_LEN];
} Model_Matrices;

static PetscErrorCode JRModelSetFromOptions_Matrices(JRModel m, PetscOptionItems *PetscOptionsObject)
{
  Model_Matrices *mm = (Model_Matrices *)m->data;

  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Model from matrix files (-model_type matrices)");
  PetscCall(PetscOptionsString("-model_stiffness", "Stiffness matrix K [N/m]: .mtx, .bin (PETSc binary) or .h5 (MATLAB v7.3 sparse, group K)", "JRModelSetUp", mm->K, mm->K, sizeof(mm->K), NULL));
  PetscCall(PetscOptionsString("-model_mass", "Mass matrix M [kg]: .mtx, .bin or .h5 (group M)", "JRModelSetUp", mm->M, mm->M, sizeof(mm->M), NULL));
  PetscCall(PetscOptionsString("-model_damping", "Optional viscous damping matrix C [N s/m]: .mtx, .bin or .h5 (group C)", "JRModelSetUp", mm->C, mm->C, sizeof(mm->C), NULL));
  PetscCall(PetscOptionsString("-model_elements", "Contact elements CSV: type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b", "JRModelSetUp", mm->elements, mm->elements, sizeof(mm->elements), NULL));
  PetscOptionsHeadEnd();
  PetscFunctionReturn(0);
}

/* A must be n x n and symmetric to a relative 1e-10 */
static PetscErrorCode CheckMatrix(JRModel m, Mat A, const char *what, const char *file, PetscInt n)
{
  PetscInt  r, c;
  PetscReal amax, dmax;
  Mat       At;

  PetscFunctionBeginUser;
  PetscCall(MatGetSize(A, &r, &c));
  PetscCheck(r == c, m->comm, PETSC_ERR_ARG_SIZ, "%s matrix %s is %" PetscInt_FMT " x %" PetscInt_FMT ", not square", what, file, r, c);
  PetscCheck(n < 0 || r == n, m->comm, PETSC_ERR_ARG_SIZ, "%s matrix %s is %" PetscInt_FMT " x %" PetscInt_FMT ", the stiffness matrix is %" PetscInt_FMT " x %" PetscInt_FMT, what, file, r, c, n, n);
  PetscCall(MatNorm(A, NORM_MAX, &amax));
  PetscCheck(!PetscIsInfOrNanReal(amax), m->comm, PETSC_ERR_FILE_UNEXPECTED, "%s matrix %s has entries that are not finite numbers", what, file);
  PetscCall(MatTranspose(A, MAT_INITIAL_MATRIX, &At));
  PetscCall(MatAXPY(At, -1.0, A, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatNorm(At, NORM_MAX, &dmax));
  PetscCall(MatDestroy(&At));
  PetscCheck(dmax <= 1e-10 * amax, m->comm, PETSC_ERR_ARG_WRONG, "%s matrix %s is not symmetric: max |A - A^T| = %g, max |A| = %g", what, file, (double)dmax, (double)amax);
  PetscFunctionReturn(0);
}

#if defined(PETSC_HAVE_MUMPS)
/* The inertia of A by an LDL^T factorisation (MUMPS, null pivots counted as zero eigenvalues) */
static PetscErrorCode Inertia(Mat A, PetscInt *nneg, PetscInt *nzero)
{
  Mat            F;
  MatFactorInfo  info;
  MatFactorError ferr;

  PetscFunctionBeginUser;
  PetscCall(MatGetFactor(A, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &F));
  PetscCall(MatMumpsSetIcntl(F, 13, 1)); /* the root front factorised on one rank: the inertia is exact in parallel */
  PetscCall(MatMumpsSetIcntl(F, 24, 1)); /* null pivots detected */
  PetscCall(MatFactorInfoInitialize(&info));
  PetscCall(MatCholeskyFactorSymbolic(F, A, NULL, &info));
  PetscCall(MatCholeskyFactorNumeric(F, A, &info));
  PetscCall(MatFactorGetError(F, &ferr));
  if (ferr) {
    *nneg  = 0;
    *nzero = 1;
  } else PetscCall(MatGetInertia(F, nneg, nzero, NULL));
  PetscCall(MatDestroy(&F));
  PetscFunctionReturn(0);
}
#endif

/* Before any work: M positive definite, and K positive semidefinite beyond round-off, i.e. no eigenvalue of
   K phi = omega^2 M phi below -1e-8 s, s = max_i |K_ii| / M_ii (at most the largest eigenvalue): by Sylvester's
   law of inertia, the negative pivots of LDL^T factorisations of M and of K + 1e-8 s M count them */
static PetscErrorCode CheckDefinite(JRModel m, const char *kfile, const char *mfile)
{
  Vec       dk, dm;
  PetscReal dmin, s;
  PetscInt  nneg = 0, nzero = 0;

  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(m->K, &dk, &dm));
  PetscCall(MatGetDiagonal(m->M, dm));
  PetscCall(VecMin(dm, NULL, &dmin));
  PetscCheck(dmin > 0, m->comm, PETSC_ERR_ARG_WRONG, "Mass matrix %s is not positive definite: a diagonal entry is %g (every DOF needs a positive mass)", mfile, (double)dmin);
#if defined(PETSC_HAVE_MUMPS)
  PetscCall(Inertia(m->M, &nneg, &nzero));
  PetscCheck(!nneg && !nzero, m->comm, PETSC_ERR_ARG_WRONG, "Mass matrix %s is not positive definite: %" PetscInt_FMT " negative and %" PetscInt_FMT " zero eigenvalues", mfile, nneg, nzero);
#endif
  PetscCall(MatGetDiagonal(m->K, dk));
  PetscCall(VecAbs(dk));
  PetscCall(VecPointwiseDivide(dk, dk, dm));
  PetscCall(VecMax(dk, NULL, &s));
  PetscCall(VecDestroy(&dk));
  PetscCall(VecDestroy(&dm));
#if defined(PETSC_HAVE_MUMPS)
  if (s > 0) {
    Mat A;
    PetscCall(MatDuplicate(m->K, MAT_COPY_VALUES, &A));
    PetscCall(MatAXPY(A, 1e-8 * s, m->M, DIFFERENT_NONZERO_PATTERN));
    PetscCall(Inertia(A, &nneg, &nzero));
    PetscCall(MatDestroy(&A));
  }
  PetscCheck(!nneg, m->comm, PETSC_ERR_ARG_WRONG, "Stiffness matrix %s is not positive semidefinite: %" PetscInt_FMT " eigenvalue%s of K phi = omega^2 M phi (M from %s) below -1e-8 x max |K_ii|/M_ii = %g rad^2/s^2", kfile, nneg, nneg > 1 ? "s" : "", mfile, (double)(-1e-8 * s));
#endif
  PetscFunctionReturn(0);
}

static PetscErrorCode JRModelSetUp_Matrices(JRModel m)
{
  Model_Matrices *mm = (Model_Matrices *)m->data;

  PetscFunctionBeginUser;
  if (!m->K) { /* from files, unless JRModelSetMatrices() gave them */
    PetscCheck(mm->K[0], m->comm, PETSC_ERR_USER_INPUT, "-model_type matrices needs -model_stiffness FILE (and -model_mass FILE)");
    PetscCheck(mm->M[0], m->comm, PETSC_ERR_USER_INPUT, "-model_type matrices needs -model_mass FILE (and -model_stiffness FILE)");
    PetscCall(JRMatLoadFile(m->comm, mm->K, "K", &m->K));
    PetscCall(CheckMatrix(m, m->K, "Stiffness", mm->K, -1));
    PetscCall(MatGetSize(m->K, &m->ndof, NULL));
    PetscCall(JRMatLoadFile(m->comm, mm->M, "M", &m->M));
    PetscCall(CheckMatrix(m, m->M, "Mass", mm->M, m->ndof));
    if (mm->C[0]) {
      PetscCall(JRMatLoadFile(m->comm, mm->C, "C", &m->C));
      PetscCall(CheckMatrix(m, m->C, "Damping", mm->C, m->ndof));
    }
    PetscCall(CheckDefinite(m, mm->K, mm->M));
  } else {
    PetscCall(CheckMatrix(m, m->K, "Stiffness", "(given)", -1));
    PetscCall(CheckMatrix(m, m->M, "Mass", "(given)", m->ndof));
    if (m->C) PetscCall(CheckMatrix(m, m->C, "Damping", "(given)", m->ndof));
    PetscCall(CheckDefinite(m, "(given)", "(given)"));
  }
  if (mm->elements[0]) PetscCall(JRElementsReadCSV(m->comm, mm->elements, m->ndof, &m->el));
  for (PetscInt e = 0; e < m->el.n; e++) {
    const PetscInt d[4] = {m->el.dof_a[e], m->el.dof_b[e], m->el.ndof_a[e], m->el.ndof_b[e]};
    for (int k = 0; k < 4; k++) PetscCheck(d[k] >= -1 && d[k] < m->ndof, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "Element %" PetscInt_FMT ": DOF %" PetscInt_FMT " out of range 0..%" PetscInt_FMT " (-1 = ground)", e, d[k], m->ndof - 1);
  }
  PetscCall(PetscObjectSetName((PetscObject)m->K, "K"));
  PetscCall(PetscObjectSetName((PetscObject)m->M, "M"));
  PetscFunctionReturn(0);
}

static PetscErrorCode JRModelView_Matrices(JRModel m, PetscViewer viewer)
{
  Model_Matrices *mm = (Model_Matrices *)m->data;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "  K from %s, M from %s%s%s%s%s\n", mm->K, mm->M, mm->C[0] ? ", C from " : "", mm->C, mm->elements[0] ? ", elements from " : "", mm->elements));
  PetscFunctionReturn(0);
}

static PetscErrorCode JRModelDestroy_Matrices(JRModel m)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(m->data));
  PetscFunctionReturn(0);
}

PetscErrorCode JRModelCreate_Matrices(JRModel m)
{
  Model_Matrices *mm;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&mm));
  m->data                = mm;
  m->ops->setfromoptions = JRModelSetFromOptions_Matrices;
  m->ops->setup          = JRModelSetUp_Matrices;
  m->ops->view           = JRModelView_Matrices;
  m->ops->destroy        = JRModelDestroy_Matrices;
  PetscFunctionReturn(0);
}
