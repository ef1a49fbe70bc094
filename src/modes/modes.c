/*
   JRModes: the lowest modes of K phi = omega^2 M phi (generalised Hermitian), mass-normalised
   (phi^T M phi = 1), ascending. SLEPc EPS with prefix modes_: shift-and-invert about a target just
   below zero (so that a singular, free-free K is fine) with a sparse LDL^T factorisation (MUMPS); or every mode by
   dense LAPACK for small systems (-modes_nev equal to the number of DOFs).
   Options: -modes_nev n, -modes_target t [rad^2/s^2], -modes_view, and every -modes_eps_*, -modes_st_*;
   -modes_save FILE.h5 writes the modes for reuse, -modes_load FILE.h5 reads them instead of solving (the
   node coordinates saved with them must match the model's: same mesh, same number of ranks).
   The mixed basis (JRModesMix) of a model with interface rows (JRModesSetInterface) also holds static correction
   vectors of the interface (-modes_static n, -modes_static_tol t, -modes_static_max n; their solver
   -modes_static_ksp_*, -modes_static_pc_*) and gives the basis check (-modes_check, -modes_check_tol;
   JRModesCheckBasis for the other bases).
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
  PetscOptionsEnd();
  PetscCheck(md->nstatic >= -1, md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_static %" PetscInt_FMT ": a number of vectors, or -1 for those above -modes_static_tol", md->nstatic);
  PetscCheck(md->nstatic_max >= 0, md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_static_max %" PetscInt_FMT ": must be non-negative", md->nstatic_max);
  PetscCheck(md->static_tol > 0 && !PetscIsInfOrNanReal(md->static_tol), md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_static_tol %g: must be positive", (double)md->static_tol);
  PetscCheck(md->check_tol > 0 && !PetscIsInfOrNanReal(md->check_tol), md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_check_tol %g: must be positive", (double)md->check_tol);
  PetscCheck(md->nev >= 1, md->comm, PETSC_ERR_ARG_OUTOFRANGE, "-modes_nev %" PetscInt_FMT ": at least one mode", md->nev);
  if (md->load[0]) PetscCall(JRFileCheckHDF5(md->comm, "-modes_load", md->load, "/jointrom_modes", "write one with -modes_save"));
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

/* A number identifying stuck contact springs added to K (stuck basis), saved with the modes and checked on load */
PetscErrorCode JRModesSetSignature(JRModes md, PetscReal sig)
{
  PetscFunctionBeginUser;
  md->sig = sig;
  PetscFunctionReturn(0);
}

/* Write omega^2 and the modes (and the coordinates) to an HDF5 file, through a temporary name */
PetscErrorCode JRModesSave(JRModes md, const char file[])
{
  PetscViewer v;
  char        tmp[PETSC_MAX_PATH_LEN + 32];
  Vec         lam;
  PetscMPIInt rank, size;
  PetscInt    nm = md->nm, hasx = md->X ? 1 : 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(md->comm, &rank));
  PetscCallMPI(MPI_Comm_size(md->comm, &size));
  PetscCall(JRFileTempName(md->comm, file, tmp, sizeof(tmp)));
  PetscCall(PetscViewerHDF5Open(md->comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(PetscViewerHDF5PushGroup(v, "/jointrom_modes"));
  PetscCall(VecCreateMPI(md->comm, rank ? 0 : nm, nm, &lam));
  PetscCall(PetscObjectSetName((PetscObject)lam, "omega2"));
  if (!rank)
    for (PetscInt i = 0; i < nm; i++) PetscCall(VecSetValue(lam, i, md->lambda[i], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(lam));
  PetscCall(VecAssemblyEnd(lam));
  PetscCall(VecView(lam, v));
  PetscCall(VecDestroy(&lam));
  for (PetscInt i = 0; i < nm; i++) {
    char name[32];
    PetscCall(PetscSNPrintf(name, sizeof(name), "phi_%" PetscInt_FMT, i));
    PetscCall(PetscObjectSetName((PetscObject)md->phi[i], name));
    PetscCall(VecView(md->phi[i], v));
  }
  if (md->X) { /* a plain copy: a vector of a DMPlex would go to /fields */
    Vec y;
    PetscCall(MatCreateVecs(md->K, &y, NULL));
    PetscCall(VecCopy(md->X, y));
    PetscCall(PetscObjectSetName((PetscObject)y, "coordinates"));
    PetscCall(VecView(y, v));
    PetscCall(VecDestroy(&y));
  }
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "modes", PETSC_INT, &nm));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "ranks", PETSC_INT, &size));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "has_coordinates", PETSC_INT, &hasx));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "stuck_signature", PETSC_REAL, &md->sig));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "units", PETSC_STRING, "omega2: rad^2/s^2; phi_i: mass-normalised modes over every DOF (kg^-1/2) in the model's parallel DOF numbering; coordinates: m"));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(JRFileRename(md->comm, tmp, file));
  PetscFunctionReturn(0);
}

/* Read the nev lowest modes from a -modes_save file */
static PetscErrorCode ModesLoad(JRModes md, const char file[])
{
  PetscViewer        v;
  PetscInt           nm = 0, ranks = 0, hasx = 0, n, nf;
  PetscMPIInt        size;
  PetscBool          has;
  Vec                lam, all, x;
  VecScatter         sc;
  const PetscScalar *l;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(md->comm, &size));
  PetscCall(PetscTestFile(file, 'r', &has));
  PetscCheck(has, md->comm, PETSC_ERR_FILE_OPEN, "-modes_load %s: cannot read the file", file);
  {
    char what[PETSC_MAX_PATH_LEN + 32];
    PetscCall(PetscSNPrintf(what, sizeof(what), "-modes_load %s", file));
    PetscCall(JRErrorContextPush(what));
    PetscCall(PetscViewerHDF5Open(md->comm, file, FILE_MODE_READ, &v));
    PetscCall(PetscViewerHDF5HasAttribute(v, "/jointrom_modes", "modes", &has));
    PetscCall(JRErrorContextPop());
  }
  PetscCheck(has, md->comm, PETSC_ERR_FILE_UNEXPECTED, "-modes_load %s: not a modes file of this program (no /jointrom_modes; write one with -modes_save)", file);
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "modes", PETSC_INT, NULL, &nm));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "ranks", PETSC_INT, NULL, &ranks));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "has_coordinates", PETSC_INT, NULL, &hasx));
  if (md->load_all) md->nev = nm; /* a mixed basis: every vector of the file */
  PetscCheck(nm >= md->nev, md->comm, PETSC_ERR_FILE_UNEXPECTED, "-modes_load %s holds %" PetscInt_FMT " modes, %" PetscInt_FMT " are asked for (-hbm_modes / -modes_nev)", file, nm, md->nev);
  PetscCheck(ranks == size, md->comm, PETSC_ERR_FILE_UNEXPECTED, "-modes_load %s was written on %" PetscInt_FMT " ranks, this run has %d: the FE DOF numbering depends on the partition; run on %" PetscInt_FMT " ranks or recompute the modes", file, ranks, (int)size, ranks);
  {
    PetscReal sig = 0;
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "stuck_signature", PETSC_REAL, NULL, &sig));
    PetscCall(PetscInfo(NULL, "stuck signature: file %.17g, this run %.17g\n", (double)sig, (double)md->sig));
    PetscCheck(PetscAbsReal(sig - md->sig) <= 1e-9 * PetscMax(PetscAbsReal(sig), PetscAbsReal(md->sig)), md->comm, PETSC_ERR_FILE_UNEXPECTED, "-modes_load %s: its modes are of %s, this run needs %s (-hbm_basis, -interface_*, preload): recompute them", file, sig == 0 ? "the free structure" : sig < 0 ? "a mixed basis (stuck + free)" : "a stuck interface", md->sig == 0 ? "the free structure's" : md->sig < 0 ? "a mixed basis of this interface" : "those of this stuck interface");
  }
  PetscCall(MatGetSize(md->K, &n, NULL));
  PetscCall(PetscViewerHDF5PushGroup(v, "/jointrom_modes"));
  PetscCall(MatCreateVecs(md->K, &x, NULL));
  if (md->X && hasx) {
    PetscReal d, s;
    PetscCall(PetscObjectSetName((PetscObject)x, "coordinates"));
    PetscCall(VecLoad(x, v));
    PetscCall(VecAXPY(x, -1.0, md->X));
    PetscCall(VecNorm(x, NORM_INFINITY, &d));
    PetscCall(VecNorm(md->X, NORM_INFINITY, &s));
    PetscCheck(d <= 1e-9 * s, md->comm, PETSC_ERR_FILE_UNEXPECTED, "-modes_load %s: its node coordinates differ from the model's by %g m: it was computed for another mesh (or DOF numbering)", file, (double)d);
  }
  PetscCall(VecCreateMPI(md->comm, PETSC_DECIDE, nm, &lam));
  PetscCall(PetscObjectSetName((PetscObject)lam, "omega2"));
  {
    char what[PETSC_MAX_PATH_LEN + 32];
    PetscCall(PetscSNPrintf(what, sizeof(what), "-modes_load %s", file));
    PetscCall(JRErrorContextPush(what)); /* a library's error on the datasets read below names the file */
  }
  PetscCall(VecLoad(lam, v));
  PetscCall(VecScatterCreateToAll(lam, &sc, &all));
  PetscCall(VecScatterBegin(sc, lam, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, lam, all, INSERT_VALUES, SCATTER_FORWARD));
  md->nm = md->nev;
  PetscCall(PetscMalloc1(md->nm, &md->lambda));
  PetscCall(VecGetArrayRead(all, &l));
  for (PetscInt i = 0; i < md->nm; i++) md->lambda[i] = PetscRealPart(l[i]);
  PetscCall(VecRestoreArrayRead(all, &l));
  for (PetscInt i = 0; i < md->nm; i++) PetscCheck(!PetscIsInfOrNanReal(md->lambda[i]), md->comm, PETSC_ERR_FILE_UNEXPECTED, "mode %" PetscInt_FMT " has omega^2 = %g rad^2/s^2, not a finite number", i + 1, (double)md->lambda[i]);
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&all));
  PetscCall(VecDestroy(&lam));
  PetscCall(VecDuplicateVecs(x, md->nm, &md->phi));
  for (PetscInt i = 0; i < md->nm; i++) {
    char name[32];
    PetscCall(PetscSNPrintf(name, sizeof(name), "phi_%" PetscInt_FMT, i));
    PetscCall(PetscObjectSetName((PetscObject)md->phi[i], name));
    PetscCall(VecGetSize(md->phi[i], &nf));
    PetscCall(VecLoad(md->phi[i], v));
    {
      PetscReal nrm;
      PetscCall(VecNorm(md->phi[i], NORM_INFINITY, &nrm));
      PetscCheck(!PetscIsInfOrNanReal(nrm), md->comm, PETSC_ERR_FILE_UNEXPECTED, "mode %" PetscInt_FMT " holds a value that is not a finite number", i + 1);
    }
  }
  PetscCall(JRErrorContextPop());
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(VecDestroy(&x));
  PetscCall(PetscInfo(NULL, "Read %" PetscInt_FMT " modes of %" PetscInt_FMT " DOFs from %s\n", md->nm, nf, file));
  PetscFunctionReturn(0);
}

/* The default shift, a little below zero (free-free structures have a singular K): -1e-6 |diag K|_1 / |diag M|_1 */
static PetscErrorCode DefaultShift(JRModes md, PetscReal *sigma)
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
    if (!md->target_set) PetscCall(DefaultShift(md, &md->target));
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
    PetscCall(ModesLoad(md, md->load));
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
static PetscErrorCode StaticSolver(JRModes md, KSP *ksp, Mat *A)
{
  PetscReal sigma = 0.0;
  PC        pc;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < md->nm && sigma == 0.0; i++)
    if (md->lambda[i] > 0) sigma = -1e-6 * md->lambda[i];
  if (sigma == 0.0) PetscCall(DefaultShift(md, &sigma));
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
  PetscCall(KSPSetUp(*ksp));
  PetscFunctionReturn(0);
}

/*
  The interface's residual flexibility outside the span of the modes Q (M-orthonormal, MQ = M Q), in units of the
  contact stiffness: S = W^1/2 B^T P A^-1 P^T B W^1/2 (nir x nir, col-major, on every rank), with B the interface rows,
  W = diag(k), P = I - Q Q^T M and A = K - sigma M. S is symmetric and its eigenvalues are dimensionless: a pattern of
  contact forces f = W^1/2 v deforms the interface, beyond what the modes carry, by v^T S v / |v|^2 times the contact
  springs' own stretch. The nir solves go in blocks of columns.
*/
static PetscErrorCode ResidualFlexibility(JRModes md, KSP ksp, Interface *c, PetscInt nq, Vec Q[], Vec MQ[], const PetscReal BQ[], PetscReal S[])
{
  const PetscInt nr = md->nir, bs = PetscMin(64, nr);
  PetscInt       nloc, N;
  Mat            B, X;
  Vec            g;
  PetscScalar   *d;
  PetscReal     *w, *r;

  PetscFunctionBeginUser;
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
        PetscCall(InterfaceLoad(md, c, w, nq, MQ, BQ, d, b));
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
      PetscCall(ProjectOut(nq, Q, MQ, d, g));
      PetscCall(InterfaceRows(md, c, g, r));
      for (PetscInt i = 0; i < nr; i++) S[i + (c0 + j) * nr] = r[i];
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
  flexibility S (ResidualFlexibility), its eigenvalues lam_1 >= lam_2 >= ..., and, for the ns largest (nwant >= 0:
  that many; -1: those above -modes_static_tol, at most -modes_static_max), the static responses
  g_k = P A^-1 P^T B W^1/2 v_k to their patterns v_k (residual flexibility modes: M-orthogonal to Q), returned in G
  (unnormalised; *G NULL if ns = 0). md->rho0 = lam_1 (the check before the correction), md->rho = lam_{ns+1} (after).
*/
static PetscErrorCode StaticCorrection(JRModes md, PetscInt nq, Vec Q[], Vec MQ[], PetscInt nwant, PetscInt *ns, Vec **G)
{
  const PetscInt nr = md->nir;
  PetscLogDouble t0, t1;
  Interface      c;
  KSP            ksp;
  Mat            A;
  Vec            b;
  PetscReal     *BQ, *S, *lam, *work, *w;
  PetscScalar   *d;
  PetscBLASInt   bn, lwork, info;
  PetscInt       n = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogEventBegin(JR_ModesStatic, 0, 0, 0, 0));
  *ns = 0;
  *G  = NULL;
  PetscCall(InterfaceCreate(md, Q[0], &c));
  PetscCall(PetscMalloc3(nr * PetscMax(nq, 1), &BQ, nr * nr, &S, nr, &lam));
  PetscCall(PetscMalloc3(8 * nr, &work, nr, &w, PetscMax(nq, 1), &d));
  for (PetscInt q = 0; q < nq; q++) PetscCall(InterfaceRows(md, &c, Q[q], BQ + q * nr));
  PetscCall(StaticSolver(md, &ksp, &A));
  PetscCall(ResidualFlexibility(md, ksp, &c, nq, Q, MQ, BQ, S));
  PetscCall(PetscBLASIntCast(nr, &bn));
  PetscCall(PetscBLASIntCast(8 * nr, &lwork));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &bn, S, &bn, lam, work, &lwork, &info));
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed: info %d", (int)info);
  if (nwant >= 0) n = PetscMin(nwant, nr);
  else
    while (n < nr && n < md->nstatic_max && lam[nr - 1 - n] >= md->static_tol) n++;
  md->rho0 = PetscMax(lam[nr - 1], 0.0);
  md->rho  = n < nr ? PetscMax(lam[nr - 1 - n], 0.0) : 0.0;
  if (n) PetscCall(VecDuplicateVecs(Q[0], n, G));
  PetscCall(VecDuplicate(Q[0], &b));
  for (PetscInt k = 0; k < n; k++) { /* the k-th largest pattern's static response, residual to Q */
    for (PetscInt i = 0; i < nr; i++) w[i] = S[i + (nr - 1 - k) * nr];
    PetscCall(InterfaceLoad(md, &c, w, nq, MQ, BQ, d, b));
    PetscCall(KSPSolve(ksp, b, (*G)[k]));
    PetscCall(ProjectOut(nq, Q, MQ, d, (*G)[k]));
  }
  PetscCall(VecDestroy(&b));
  for (PetscInt k = 1; k <= nr; k *= 2) PetscCall(PetscInfo(NULL, "Interface residual flexibility x stiffness: pattern %" PetscInt_FMT " of %" PetscInt_FMT ": %g\n", k, nr, (double)lam[nr - k]));
  *ns = n;
  PetscCall(PetscInfo(NULL, "Interface residual flexibility x stiffness: %" PetscInt_FMT " patterns, largest %g, %" PetscInt_FMT " kept, next %g\n", nr, (double)md->rho0, n, (double)md->rho));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&A));
  PetscCall(PetscFree3(BQ, S, lam));
  PetscCall(PetscFree3(work, w, d));
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
  PetscCall(StaticCorrection(md, md->nm, md->phi, MQ, 0, &ns, &G));
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

/*
  JRModesMix - the mixed basis (after JRModesSetMixed and JRModesSolve): md's stuck modes (operators K + Ks, M), the nf
  lowest elastic free-interface modes of (K, M) (the free structure, rigid basis rb[nrb]) and, with interface rows
  (JRModesSetInterface), the static correction vectors of the interface (StaticCorrection: the residual flexibility
  modes of the stuck structure for the interface patterns that the modes miss most, -modes_static*), M-orthonormalised
  (dependent vectors dropped), then the Ritz vectors of (K + Ks, M) in their span, which replace md's modes: exact for
  the stuck structure and for the structure with the interface free, and static-complete for the patterns kept. Saved
  (-modes_save or the default file) once mixed; when the modes were read (-modes_load: the file holds the mixed basis)
  only the basis check is made.
*/
PetscErrorCode JRModesMix(JRModes md, Mat K, PetscInt nf, PetscInt nrb, Vec rb[])
{
  JRModes       fm;
  Mat           M = md->M;
  PetscInt      nq = 0, ncand, ns = 0;
  Vec           *Q, *MQ, *cand, *G = NULL, Mv;
  PetscScalar  *d;
  PetscReal    *A, *lam, *work;
  PetscBLASInt  bn, lwork, info;

  PetscFunctionBeginUser;
  PetscCheck(md->mixed, md->comm, PETSC_ERR_ARG_WRONGSTATE, "JRModesSetMixed() first");
  if (md->load[0]) {
    PetscCall(JRModesCheckBasis(md));
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
    PetscCall(StaticCorrection(md, nq, Q, MQ, md->nstatic, &ns, &G));
    for (PetscInt k = 0; k < ns; k++) PetscCall(AppendOrthonormal(M, G[k], Q, MQ, &nq, Mv, d));
    md->nsadded = ns;
    if (ns) PetscCall(VecDestroyVecs(ns, &G));
  }
  /* Ritz: A = Q^T (K + Ks) Q, eigenvectors ascending */
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
  PetscCall(VecDestroyVecs(md->nm, &md->phi));
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
  PetscCall(PetscInfo(NULL, "Mixed basis: %" PetscInt_FMT " stuck + %" PetscInt_FMT " free modes + %" PetscInt_FMT " static correction vectors -> %" PetscInt_FMT " Ritz vectors\n", md->nev, nf, ns, nq));
  PetscCall(PetscFree3(A, lam, work));
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
  if (md->rb) PetscCall(VecDestroyVecs(md->nrb, &md->rb));
  PetscCall(PetscFree3(md->irdof, md->ircoef, md->irk));
  PetscCall(EPSDestroy(&md->eps));
  PetscCall(VecDestroy(&md->X));
  PetscCall(MatDestroy(&md->K));
  PetscCall(MatDestroy(&md->M));
  PetscCall(PetscFree(md));
  *modes = NULL;
  PetscFunctionReturn(0);
}
