/*
   JRModes: the lowest modes of K phi = omega^2 M phi (generalised Hermitian), mass-normalised
   (phi^T M phi = 1), ascending. SLEPc EPS with prefix modes_: shift-and-invert about a target just
   below zero (so that a singular, free-free K is fine) with a sparse LDL^T factorisation (MUMPS); or every mode by
   dense LAPACK for small systems (-modes_nev equal to the number of DOFs).
   Options: -modes_nev n, -modes_target t [rad^2/s^2], -modes_view, and every -modes_eps_*, -modes_st_*;
   -modes_save FILE.h5 writes the modes for reuse, in the natural order of the DOFs (JRModesSetNaturalOrdering: the
   same on any number of ranks), -modes_load FILE.h5 reads them instead of solving (the node coordinates saved with
   them must match the model's: the same mesh).
   The mixed basis (JRModesMix) of a model with interface rows (JRModesSetInterface) also holds static correction
   vectors of the interface (-modes_static n, -modes_static_tol t, -modes_static_max n; their solver
   -modes_static_ksp_*, -modes_static_pc_*) and gives the basis check (-modes_check, -modes_check_tol;
   JRModesCheckBasis for the other bases).
   This file: the object, its options and the eigensolve; io.c the saved modes; mixed.c the mixed basis, the static
   correction and the basis check.
*/
#include <jointrom/private/modelimpl.h>
#include <petscviewerhdf5.h>
#include <petscblaslapack.h>

PetscErrorCode JRModesCreate(MPI_Comm comm, JRModes *modes)
{
  JRModes md;

  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(PetscNew(&md));
  md->comm   = comm;
  md->refct  = 1;
  md->nev         = 10;
  md->use_rb      = PETSC_TRUE;
  md->nstatic     = -1;
  md->nstatic_max = 60;
  md->static_tol  = 0.02;
  md->check       = PETSC_TRUE;
  md->check_tol   = 0.05;
  md->adapt       = 12;
  md->adapt_tol   = 5e-4;
  md->adapt_move  = 2e-3;
  md->rho0        = -1.0;
  md->rho         = -1.0;
  *modes          = md;
  PetscFunctionReturn(0);
}

/* The stiffness and mass matrices (references kept) */
PetscErrorCode JRModesSetOperators(JRModes md, Mat K, Mat M)
{
  PetscFunctionBeginUser;
  PetscCall(PetscObjectReference((PetscObject)K));
  PetscCall(PetscObjectReference((PetscObject)M));
  PetscCall(MatDestroy(&md->K));
  PetscCall(MatDestroy(&md->M));
  md->K = K;
  md->M = M;
  PetscFunctionReturn(0);
}

/* An exact rigid-body basis (free-free structures): M-orthonormalised here, deflated from the
   eigensolve, and returned as the first modes with omega = 0 (-modes_rigid_basis, default on) */
PetscErrorCode JRModesSetRigidBasis(JRModes md, PetscInt n, Vec rb[])
{
  Vec Mv;

  PetscFunctionBeginUser;
  PetscCheck(md->M, md->comm, PETSC_ERR_ARG_WRONGSTATE, "JRModesSetOperators() first");
  if (md->rb) PetscCall(VecDestroyVecs(md->nrb, &md->rb));
  md->nrb = n;
  if (!n) PetscFunctionReturn(0);
  PetscCall(VecDuplicateVecs(rb[0], n, &md->rb));
  PetscCall(VecDuplicate(rb[0], &Mv));
  for (PetscInt i = 0; i < n; i++) { /* modified Gram-Schmidt in the M inner product */
    PetscScalar d;
    PetscCall(VecCopy(rb[i], md->rb[i]));
    for (PetscInt j = 0; j < i; j++) {
      PetscCall(MatMult(md->M, md->rb[j], Mv));
      PetscCall(VecDot(md->rb[i], Mv, &d));
      PetscCall(VecAXPY(md->rb[i], -d, md->rb[j]));
    }
    PetscCall(MatMult(md->M, md->rb[i], Mv));
    PetscCall(VecDot(md->rb[i], Mv, &d));
    PetscCheck(PetscRealPart(d) > 0, md->comm, PETSC_ERR_ARG_WRONG, "Rigid-body vector %" PetscInt_FMT " is dependent on the others", i);
    PetscCall(VecScale(md->rb[i], 1.0 / PetscSqrtReal(PetscRealPart(d))));
  }
  PetscCall(VecDestroy(&Mv));
  PetscFunctionReturn(0);
}

/* The mode vectors (borrowed, nm of them) */
PetscErrorCode JRModesGetVecs(JRModes md, Vec **phi)
{
  PetscFunctionBeginUser;
  *phi = md->phi;
  PetscFunctionReturn(0);
}

/* How many of the modes are the supplied rigid-body modes (0 with -modes_rigid_basis 0) */
PetscErrorCode JRModesGetNumRigid(JRModes md, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = md->use_rb ? md->nrb : 0;
  PetscFunctionReturn(0);
}

/* How many modes (the lowest); -modes_nev */
PetscErrorCode JRModesSetNumber(JRModes md, PetscInt nev)
{
  PetscFunctionBeginUser;
  PetscCheck(nev >= 1, md->comm, PETSC_ERR_ARG_OUTOFRANGE, "Number of modes %" PetscInt_FMT " must be at least 1", nev);
  md->nev = nev;
  PetscFunctionReturn(0);
}

PetscErrorCode JRModesSetFromOptions(JRModes md)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(md->comm, "modes_", "Linear modes (SLEPc EPS, prefix modes_)", "JRModes");
  PetscCall(PetscOptionsInt("-nev", "Number of modes (the lowest)", "JRModesSetNumber", md->nev, &md->nev, NULL));
  PetscCall(PetscOptionsReal("-target", "Shift for shift-and-invert [rad^2/s^2] (default: slightly below zero)", "JRModesSolve", md->target, &md->target, &md->target_set));
  PetscCall(PetscOptionsBool("-view", "Print the natural frequencies", "JRModesView", md->view, &md->view, NULL));
  PetscCall(PetscOptionsBool("-rigid_basis", "Free-free FE models: deflate the exact rigid-body modes and solve for the elastic ones", "JRModesSetRigidBasis", md->use_rb, &md->use_rb, NULL));
  PetscCall(PetscOptionsString("-load", "Read the modes from this HDF5 file (written by -modes_save) instead of solving", "JRModesSolve", md->load, md->load, sizeof(md->load), NULL));
  PetscCall(PetscOptionsString("-save", "Write the modes to this HDF5 file for -modes_load", "JRModesSolve", md->save, md->save, sizeof(md->save), NULL));
  PetscCall(PetscOptionsInt("-static", "Mixed basis of an FE model with contact pairs: static correction vectors of the interface added (-1: every pattern above -modes_static_tol, at most -modes_static_max; 0: none)", "JRModesMix", md->nstatic, &md->nstatic, NULL));
  PetscCall(PetscOptionsInt("-static_max", "At most this many static correction vectors with -modes_static -1", "JRModesMix", md->nstatic_max, &md->nstatic_max, NULL));
  PetscCall(PetscOptionsReal("-static_tol", "-modes_static -1: keep the interface patterns whose residual flexibility times contact stiffness is at least this [-]", "JRModesMix", md->static_tol, &md->static_tol, NULL));
  PetscCall(PetscOptionsBool("-check", "Basis check of an FE model with contact pairs: the largest residual flexibility times contact stiffness of an interface pattern outside the basis", "JRModesCheckBasis", md->check, &md->check, NULL));
  PetscCall(PetscOptionsReal("-check_tol", "Warn when the basis check exceeds this [-]", "JRModesCheckBasis", md->check_tol, &md->check_tol, NULL));
  PetscCall(PetscOptionsInt("-adapt", "FE models with contact pairs: at most this many rounds of solving the curves and adding the static responses of their peaks' contact forces outside the basis (0: none)", "JRModesEnrich", md->adapt, &md->adapt, NULL));
  PetscCall(PetscOptionsReal("-adapt_tol", "-modes_adapt: add the peaks' contact-force patterns whose deformation outside the basis exceeds this many times the springs' own stretch [-]", "JRModesEnrich", md->adapt_tol, &md->adapt_tol, NULL));
  PetscCall(PetscOptionsReal("-adapt_move", "-modes_adapt: also stop once a round moved every peak by less than this in amplitude and a twentieth of it in frequency (relative), the deformation below 100 times -modes_adapt_tol", "JRModesEnrich", md->adapt_move, &md->adapt_move, NULL));
  PetscOptionsEnd();
  PetscCheck(md->adapt_move > 0 && !PetscIsInfOrNanReal(md->adapt_move), md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_adapt_move %g: must be positive", (double)md->adapt_move);
  PetscCheck(md->adapt >= 0, md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_adapt %" PetscInt_FMT ": a number of rounds, 0 or more", md->adapt);
  PetscCheck(md->adapt_tol > 0 && !PetscIsInfOrNanReal(md->adapt_tol), md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_adapt_tol %g: must be positive", (double)md->adapt_tol);
  PetscCheck(md->nstatic >= -1, md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_static %" PetscInt_FMT ": a number of vectors, or -1 for those above -modes_static_tol", md->nstatic);
  PetscCheck(md->nstatic_max >= 0, md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_static_max %" PetscInt_FMT ": must be non-negative", md->nstatic_max);
  PetscCheck(md->static_tol > 0 && !PetscIsInfOrNanReal(md->static_tol), md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_static_tol %g: must be positive", (double)md->static_tol);
  PetscCheck(md->check_tol > 0 && !PetscIsInfOrNanReal(md->check_tol), md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_check_tol %g: must be positive", (double)md->check_tol);
  PetscCheck(md->nev >= 1, md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_nev %" PetscInt_FMT ": at least one mode", md->nev);
  if (md->load[0]) PetscCall(JRFileCheckHDF5(md->comm, "-modes_load", md->load, "/jointrom_modes", "write one with -modes_save"));
  PetscFunctionReturn(0);
}

/* The adaptation of the basis to computed solutions (-modes_adapt rounds, 0 for a basis read with -modes_load,
   -modes_adapt_tol, -modes_adapt_move), the vectors it added and their seconds (JRModesEnrich); any may be NULL */
PetscErrorCode JRModesGetAdapt(JRModes md, PetscInt *rounds, PetscReal *tol, PetscReal *move, PetscInt *nadd, PetscLogDouble *t)
{
  PetscFunctionBeginUser;
  if (rounds) *rounds = md->load[0] ? 0 : md->adapt; /* a basis read (-modes_load) is used as read */
  if (tol) *tol = md->adapt_tol;
  if (move) *move = md->adapt_move;
  if (nadd) *nadd = md->nadapt;
  if (t) *t = md->tadapt;
  PetscFunctionReturn(0);
}

static PetscErrorCode ClearModes(JRModes md)
{
  PetscFunctionBeginUser;
  if (md->phi) PetscCall(VecDestroyVecs(md->nm, &md->phi));
  PetscCall(PetscFree(md->lambda));
  md->nm = 0;
  PetscFunctionReturn(0);
}

/* The node coordinates in the DOF layout (reference kept): saved with the modes and compared on load */
PetscErrorCode JRModesSetCoordinates(JRModes md, Vec X)
{
  PetscFunctionBeginUser;
  if (X) PetscCall(PetscObjectReference((PetscObject)X));
  PetscCall(VecDestroy(&md->X));
  md->X = X;
  PetscFunctionReturn(0);
}

/* The order in which the modes are saved (JRModelGetNaturalOrdering; reference kept; NULL: the DOFs' own), so that a
   file written on some ranks reads back on others */
PetscErrorCode JRModesSetNaturalOrdering(JRModes md, IS nat)
{
  PetscFunctionBeginUser;
  if (nat) PetscCall(PetscObjectReference((PetscObject)nat));
  PetscCall(ISDestroy(&md->nat));
  md->nat    = nat;
  md->natset = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* JRModesSetModel - what the modes take from the model besides its matrices: its exact rigid-body modes (none for a
   matrices model), an FE model's node coordinates (checked against a loaded file) and the natural order of its DOFs
   (saved files read back on any number of ranks). Collective. */
PetscErrorCode JRModesSetModel(JRModes md, JRModel model)
{
  PetscInt nrb;
  Vec      rb[6];
  IS       nat;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetRigidBasis(model, &nrb, rb));
  PetscCall(JRModesSetRigidBasis(md, nrb, rb));
  for (PetscInt i = 0; i < nrb; i++) PetscCall(VecDestroy(&rb[i]));
  if (nrb) { /* an FE model */
    Vec X;
    PetscCall(JRModelGetCoordinates(model, &X));
    PetscCall(JRModesSetCoordinates(md, X));
    PetscCall(VecDestroy(&X));
  }
  PetscCall(JRModelGetNaturalOrdering(model, &nat));
  PetscCall(JRModesSetNaturalOrdering(md, nat));
  PetscFunctionReturn(0);
}

/* A number identifying stuck contact springs added to K (stuck basis), saved with the modes and checked on load: on
   the natural DOFs (sig) and on the DOFs' own numbers (sigraw, for files written before the natural order) */
PetscErrorCode JRModesSetSignature(JRModes md, PetscReal sig, PetscReal sigraw)
{
  PetscFunctionBeginUser;
  md->sig    = sig;
  md->sigraw = sigraw;
  PetscFunctionReturn(0);
}

PetscErrorCode JRModesDefaultShift_Private(JRModes md, PetscReal *sigma)
{
  PetscReal kd, md_;
  Vec       d;

  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(md->K, &d, NULL));
  PetscCall(MatGetDiagonal(md->K, d));
  PetscCall(VecNorm(d, NORM_1, &kd));
  PetscCall(MatGetDiagonal(md->M, d));
  PetscCall(VecNorm(d, NORM_1, &md_));
  PetscCall(VecDestroy(&d));
  *sigma = md_ > 0 ? -1e-6 * kd / md_ : -1.0;
  PetscFunctionReturn(0);
}

/* The eigensolver: dense LAPACK for small systems (or most of their modes), else shift-and-invert a little below
   zero (free-free structures have a singular K) with a Cholesky factorisation (MUMPS unless
   -modes_st_pc_factor_mat_solver_type says otherwise); -modes_eps_*, -modes_st_* */
static PetscErrorCode SetUpEPS(JRModes md, PetscInt n, PetscInt nrb, PetscBool dense)
{
  const PetscInt nel = md->nev - nrb; /* elastic modes to compute */
  ST             st;
  KSP            ksp;
  PC             pc;

  PetscFunctionBeginUser;
  PetscCall(EPSDestroy(&md->eps));
  PetscCall(EPSCreate(md->comm, &md->eps));
  PetscCall(EPSSetOptionsPrefix(md->eps, "modes_"));
  PetscCall(EPSSetOperators(md->eps, md->K, md->M));
  PetscCall(EPSSetProblemType(md->eps, EPS_GHEP));
  if (nrb) PetscCall(EPSSetDeflationSpace(md->eps, nrb, md->rb));
  if (dense) { /* every mode (or most of them) of a small system: dense LAPACK */
    PetscCall(EPSSetType(md->eps, EPSLAPACK));
    PetscCall(EPSSetWhichEigenpairs(md->eps, EPS_SMALLEST_REAL));
    PetscCall(EPSSetDimensions(md->eps, n, PETSC_DEFAULT, PETSC_DEFAULT));
  } else {
    if (!md->target_set) PetscCall(JRModesDefaultShift_Private(md, &md->target));
    PetscCall(EPSSetDimensions(md->eps, nel, PetscMax(2 * nel + 10, nel + 32), PETSC_DEFAULT));
    PetscCall(EPSSetTarget(md->eps, md->target));
    PetscCall(EPSSetWhichEigenpairs(md->eps, EPS_TARGET_MAGNITUDE));
    PetscCall(EPSGetST(md->eps, &st));
    PetscCall(STSetType(st, STSINVERT));
    PetscCall(STGetKSP(st, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, PCCHOLESKY)); /* K - sigma M is symmetric: LDL^T, half the memory of LU */
  }
  PetscCall(EPSSetFromOptions(md->eps));
#if defined(PETSC_HAVE_MUMPS)
  if (!dense) { /* MUMPS for the factorisation unless -modes_st_pc_factor_mat_solver_type says otherwise
                   (also after -modes_st_pc_type lu: PETSc's own sparse factorisation is sequential and slow) */
    PetscBool set, factor;
    PetscCall(EPSGetST(md->eps, &st));
    PetscCall(STGetKSP(st, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &factor, PCLU, PCCHOLESKY, ""));
    PetscCall(PetscOptionsHasName(NULL, "modes_st_", "-pc_factor_mat_solver_type", &set));
    if (factor && !set) PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  }
#endif
  if (!dense) {
    PetscCall(EPSGetST(md->eps, &st));
    PetscCall(STGetKSP(st, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(JRCheckFactorSolverType(pc, md->K, "modes_st_"));
  }
  PetscFunctionReturn(0);
}

/* The modes from the converged eigenpairs: the supplied rigid-body modes first (omega = 0), then the lowest elastic
   ones, ascending, mass-normalised */
static PetscErrorCode ExtractModes(JRModes md, PetscInt n, PetscInt nrb, PetscBool dense)
{
  PetscInt   nconv, *perm;
  Vec        x, Mx, *vecs;
  PetscReal *lam;

  PetscFunctionBeginUser;
  PetscCall(EPSGetConverged(md->eps, &nconv));
  PetscCheck(nconv >= md->nev - nrb, md->comm, PETSC_ERR_NOT_CONVERGED, "Only %" PetscInt_FMT " of %" PetscInt_FMT " modes converged (tune -modes_eps_* or -modes_target)", nconv, md->nev - nrb);
  nconv = PetscMin(nconv, dense ? n : nconv);
  PetscCall(PetscMalloc2(nconv, &lam, nconv, &perm));
  PetscCall(MatCreateVecs(md->K, &x, &Mx));
  PetscCall(VecDuplicateVecs(x, nconv, &vecs));
  for (PetscInt i = 0; i < nconv; i++) {
    PetscScalar kr;
    PetscCall(EPSGetEigenpair(md->eps, i, &kr, NULL, vecs[i], NULL));
    lam[i]  = PetscRealPart(kr);
    perm[i] = i;
  }
  PetscCall(PetscSortRealWithPermutation(nconv, lam, perm));
  if (nconv) { /* K positive semidefinite: no eigenvalue below round-off, -1e-6 of the mean K_ii / M_ii */
    PetscReal kd, md_;
    Vec       d;
    PetscCall(MatCreateVecs(md->K, &d, NULL));
    PetscCall(MatGetDiagonal(md->K, d));
    PetscCall(VecSum(d, &kd));
    PetscCall(MatGetDiagonal(md->M, d));
    PetscCall(VecSum(d, &md_));
    PetscCall(VecDestroy(&d));
    PetscCheck(md_ <= 0 || lam[perm[0]] >= -1e-6 * PetscAbsReal(kd) / md_, md->comm, PETSC_ERR_ARG_WRONG, "The stiffness matrix is not positive semidefinite: an eigenvalue omega^2 = %g rad^2/s^2 is below -1e-6 x the mean K_ii/M_ii (%g)", (double)lam[perm[0]], (double)(PetscAbsReal(kd) / md_));
  }
  md->nm = md->nev;
  PetscCall(PetscMalloc1(md->nm, &md->lambda));
  PetscCall(VecDuplicateVecs(x, md->nm, &md->phi));
  for (PetscInt i = 0; i < md->nm; i++) {
    PetscScalar mm;
    if (i < nrb) { /* the supplied rigid-body modes first, omega = 0 */
      md->lambda[i] = 0.0;
      PetscCall(VecCopy(md->rb[i], md->phi[i]));
      continue;
    }
    md->lambda[i] = lam[perm[i - nrb]];
    PetscCall(VecCopy(vecs[perm[i - nrb]], md->phi[i]));
    PetscCall(MatMult(md->M, md->phi[i], Mx));
    PetscCall(VecDot(md->phi[i], Mx, &mm));
    PetscCheck(PetscRealPart(mm) > 0.0, md->comm, PETSC_ERR_NOT_CONVERGED, "Mode %" PetscInt_FMT " has non-positive modal mass %g: is M positive definite?", i, (double)PetscRealPart(mm));
    PetscCall(VecScale(md->phi[i], 1.0 / PetscSqrtReal(PetscRealPart(mm))));
  }
  PetscCall(VecDestroyVecs(nconv, &vecs));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&Mx));
  PetscCall(PetscFree2(lam, perm));
  PetscFunctionReturn(0);
}

/* Solve for the nev lowest modes; mass-normalise and sort them (or read them: -modes_load) */
PetscErrorCode JRModesSolve(JRModes md)
{
  PetscInt  n, nrb;
  PetscBool dense;

  PetscFunctionBeginUser;
  PetscCheck(md->K && md->M, md->comm, PETSC_ERR_ARG_WRONGSTATE, "JRModesSetOperators() first");
  PetscCall(ClearModes(md));
  if (md->load[0]) {
    PetscCall(JRModesLoad_Private(md, md->load));
    if (md->view) PetscCall(JRModesView(md, NULL));
    PetscFunctionReturn(0);
  }
  PetscCall(MatGetSize(md->K, &n, NULL));
  PetscCheck(md->nev <= n, md->comm, PETSC_ERR_ARG_OUTOFRANGE, "%" PetscInt_FMT " modes requested (-modes_nev or -hbm_modes), the model has %" PetscInt_FMT " DOFs", md->nev, n);
  nrb = md->use_rb ? md->nrb : 0;
  PetscCheck(md->nev > nrb, md->comm, PETSC_ERR_ARG_OUTOFRANGE, "%" PetscInt_FMT " modes requested: more than the %" PetscInt_FMT " rigid-body modes are needed", md->nev, nrb);
  dense = (PetscBool)(2 * md->nev > n || n <= 64);
  PetscCall(PetscLogEventBegin(JR_ModesSolve, 0, 0, 0, 0));
  PetscCall(SetUpEPS(md, n, nrb, dense));
  PetscCall(EPSSolve(md->eps));
  PetscCall(ExtractModes(md, n, nrb, dense));
  PetscCall(PetscLogEventEnd(JR_ModesSolve, 0, 0, 0, 0));
  if (md->save[0]) PetscCall(JRModesSave(md, md->save));
  if (md->view) PetscCall(JRModesView(md, NULL));
  PetscFunctionReturn(0);
}

PetscErrorCode JRModesGetNumber(JRModes md, PetscInt *nm)
{
  PetscFunctionBeginUser;
  *nm = md->nm;
  PetscFunctionReturn(0);
}

/* omega_r^2 [rad^2/s^2], ascending (borrowed) */
PetscErrorCode JRModesGetEigenvalues(JRModes md, const PetscReal **lambda)
{
  PetscFunctionBeginUser;
  *lambda = md->lambda;
  PetscFunctionReturn(0);
}

/*
  JRModesGetRows - rows[i*nm + r] = phi_r[dofs[i]] for the nrows DOFs asked (0 for dof -1), on
  every rank for its own list (collective).
*/
PetscErrorCode JRModesGetRows(JRModes md, PetscInt nrows, const PetscInt dofs[], PetscReal rows[])
{
  PetscInt          *idx, nv = 0, *pos;
  IS                 is;
  Vec                loc;
  VecScatter         sc;
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(nrows, &idx, nrows, &pos));
  for (PetscInt i = 0; i < nrows; i++)
    if (dofs[i] >= 0) {
      pos[nv]   = i;
      idx[nv++] = dofs[i];
    }
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nv, idx, PETSC_USE_POINTER, &is));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, nv, &loc));
  PetscCall(VecScatterCreate(md->phi[0], is, loc, NULL, &sc));
  for (PetscInt i = 0; i < nrows * md->nm; i++) rows[i] = 0.0;
  for (PetscInt r = 0; r < md->nm; r++) {
    PetscCall(VecScatterBegin(sc, md->phi[r], loc, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sc, md->phi[r], loc, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(loc, &a));
    for (PetscInt k = 0; k < nv; k++) rows[pos[k] * md->nm + r] = PetscRealPart(a[k]);
    PetscCall(VecRestoreArrayRead(loc, &a));
  }
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&loc));
  PetscCall(ISDestroy(&is));
  PetscCall(PetscFree2(idx, pos));
  PetscFunctionReturn(0);
}

/* Am = Phi^T A Phi (nm x nm, row-major, on every rank) */
PetscErrorCode JRModesProject(JRModes md, Mat A, PetscReal Am[])
{
  Vec          y;
  PetscScalar *d;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(md->phi[0], &y));
  PetscCall(PetscMalloc1(md->nm, &d));
  for (PetscInt r = 0; r < md->nm; r++) {
    PetscCall(MatMult(A, md->phi[r], y));
    PetscCall(VecMDot(y, md->nm, md->phi, d));
    for (PetscInt s = 0; s < md->nm; s++) Am[s * md->nm + r] = PetscRealPart(d[s]);
  }
  PetscCall(PetscFree(d));
  PetscCall(VecDestroy(&y));
  PetscFunctionReturn(0);
}

/* Natural frequencies [Hz] */
PetscErrorCode JRModesView(JRModes md, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(md->comm, &viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "JRModes: %" PetscInt_FMT " modes, natural frequencies [Hz]:\n", md->nm));
  for (PetscInt r = 0; r < md->nm; r++) PetscCall(PetscViewerASCIIPrintf(viewer, "  mode %3" PetscInt_FMT "  %.6g\n", r + 1, (double)(PetscSqrtReal(PetscMax(md->lambda[r], 0.0)) / (2.0 * PETSC_PI))));
  PetscFunctionReturn(0);
}


/* The file the modes are saved to when neither -modes_load nor -modes_save names one ("": not saved) */
PetscErrorCode JRModesSetSaveDefault(JRModes md, const char file[])
{
  PetscFunctionBeginUser;
  if (file && file[0] && !md->load[0] && !md->save[0]) PetscCall(PetscStrncpy(md->save, file, sizeof(md->save)));
  PetscFunctionReturn(0);
}

PetscErrorCode JRModesReference(JRModes md)
{
  PetscFunctionBeginUser;
  md->refct++;
  PetscFunctionReturn(0);
}

/* Release a reference; the modes are freed with the last */
PetscErrorCode JRModesDestroy(JRModes *modes)
{
  JRModes md = *modes;

  PetscFunctionBeginUser;
  if (!md) PetscFunctionReturn(0);
  *modes = NULL;
  if (--md->refct > 0) PetscFunctionReturn(0);
  PetscCall(ClearModes(md));
  PetscCall(JRModesEnrichEnd(md));
  if (md->rb) PetscCall(VecDestroyVecs(md->nrb, &md->rb));
  PetscCall(PetscFree3(md->irdof, md->ircoef, md->irk));
  PetscCall(EPSDestroy(&md->eps));
  PetscCall(VecDestroy(&md->X));
  PetscCall(ISDestroy(&md->nat));
  PetscCall(MatDestroy(&md->K));
  PetscCall(MatDestroy(&md->M));
  PetscCall(PetscFree(md));
  *modes = NULL;
  PetscFunctionReturn(0);
}
