/*
   Finite-element models and their modes, against independent truths:
   - patch test: on a mesh of distorted (non-affine) hexahedra read from a Gmsh file, the boundary nodes
     given a linear displacement field, the solved interior reproduces it exactly;
   - strain energy of a constant-strain field on a beam: u^T K u = V (lambda tr(e)^2 + 2 mu e:e);
   - the element kernel equals PETSc's generic PetscFE integration (K and M) on distorted hexahedra;
   - straight beams, free-free and cantilever: the first three bending frequencies in z against
     Euler-Bernoulli, decreasing monotonically under nested refinement (conforming Rayleigh-Ritz);
   - free-free: exactly 6 near-zero frequencies without the supplied rigid basis (beam and bolted lap),
     Phi^T M Phi = I, K times a rigid motion = 0 with the bolts in (both bolt ties);
   - total mass = density x volume of the geometry (closed form);
   - interface pairs: counts derived by hand for the lap grid (with and without holes) and the Gmsh
     mesh, pair distances, the pair tolerance;
   - bad input returns an error (missing file, missing physical group, bolt outside the lap, ...).
*/
#include "jrtest_gmsh.h"
#include <petscdmplex.h>
#include <petscksp.h>
#include <slepcsys.h>

/* set up a model expecting an error; returns the error code (0 if none) */
static PetscErrorCode ModelError(const char *opts)
{
  JRModel        m;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(Options(opts));
  PetscCall(JRModelCreate(PETSC_COMM_WORLD, &m));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = JRModelSetFromOptions(m);
  if (!ierr) ierr = JRModelSetUp(m);
  PetscCall(PetscPopErrorHandler());
  (void)JRModelDestroy(&m);
  return ierr;
}

/* the lowest nev modes; rigid: supply the model's rigid basis */
static PetscErrorCode Modes(JRModel m, PetscInt nev, PetscBool rigid, JRModes *md)
{
  Mat      K, M;
  PetscInt nrb = 0;
  Vec      rb[6];

  PetscFunctionBeginUser;
  PetscCall(JRModelGetMatrices(m, &K, &M, NULL));
  PetscCall(JRModesCreate(PETSC_COMM_WORLD, md));
  PetscCall(JRModesSetOperators(*md, K, M));
  PetscCall(JRModesSetNumber(*md, nev));
  if (rigid) {
    PetscCall(JRModelGetRigidBasis(m, &nrb, rb));
    PetscCall(JRModesSetRigidBasis(*md, nrb, rb));
    for (PetscInt i = 0; i < nrb; i++) PetscCall(VecDestroy(&rb[i]));
  }
  PetscCall(JRModesSolve(*md));
  PetscFunctionReturn(0);
}

/* share of a vector's squared entries in component c (x, y, z interleaved per node) */
static PetscErrorCode ComponentShare(Vec v, PetscInt c, PetscReal *share)
{
  const PetscScalar *a;
  PetscInt           n;
  PetscReal          s[2] = {0, 0};

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(VecGetArrayRead(v, &a));
  for (PetscInt i = 0; i < n; i++) {
    s[1] += PetscSqr(PetscRealPart(a[i]));
    if (i % 3 == c) s[0] += PetscSqr(PetscRealPart(a[i]));
  }
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s, 2, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  *share = s[0] / s[1];
  PetscFunctionReturn(0);
}

/* the first nb frequencies [Hz] of modes that move mostly in z (bending in the x-z plane), elastic only */
static PetscErrorCode ZBending(JRModes md, PetscInt nb, PetscReal *f, PetscInt *found)
{
  PetscInt         nm;
  const PetscReal *lam;
  Vec             *phi;

  PetscFunctionBeginUser;
  PetscCall(JRModesGetNumber(md, &nm));
  PetscCall(JRModesGetEigenvalues(md, &lam));
  PetscCall(JRModesGetVecs(md, &phi));
  *found = 0;
  for (PetscInt i = 0; i < nm && *found < nb; i++) {
    PetscReal share = 0;
    if (lam[i] < 1.0) continue; /* rigid */
    PetscCall(ComponentShare(phi[i], 2, &share));
    if (share > 0.9) f[(*found)++] = PetscSqrtReal(lam[i]) / (2 * PETSC_PI);
  }
  PetscFunctionReturn(0);
}

/* the node coordinates by PETSc's own projection of x -> x onto the displacement space */
static PetscErrorCode IdentityField(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar *u, void *ctx)
{
  (void)dim;
  (void)t;
  (void)ctx;
  for (PetscInt c = 0; c < Nc; c++) u[c] = x[c];
  return 0;
}

static PetscErrorCode Coordinates(JRModel m, Vec *X)
{
  DM dm;
  PetscErrorCode (*funcs[1])(PetscInt, PetscReal, const PetscReal[], PetscInt, PetscScalar *, void *) = {IdentityField};

  PetscFunctionBeginUser;
  PetscCall(JRModelGetDM(m, &dm));
  PetscCall(DMCreateGlobalVector(dm, X));
  PetscCall(DMProjectFunction(dm, 0.0, funcs, NULL, INSERT_ALL_VALUES, *X));
  PetscFunctionReturn(0);
}

/* u = G x (a linear field; G need not be symmetric) */
static PetscErrorCode LinearField(Vec X, const PetscReal G[9], Vec u)
{
  const PetscScalar *x;
  PetscScalar       *a;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(u, &a));
  for (PetscInt i = 0; i < n; i += 3)
    for (int r = 0; r < 3; r++) a[i + r] = G[3 * r] * x[i] + G[3 * r + 1] * x[i + 1] + G[3 * r + 2] * x[i + 2];
  PetscCall(VecRestoreArray(u, &a));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

/* Patch test: the nodes on the planes of the boxes' outer faces (and the interface plane z = c if
   interface) take u = G x; the rest is solved with K; returns max |u - G x| / max |G x| */
static PetscErrorCode PatchTest(JRModel m, PetscBool interface, PetscReal *relerr, PetscInt *nbtot, PetscInt *N)
{
  const PetscReal G[9] = {1e-3, 2e-4, -3e-4, 5e-4, -2e-3, 1e-4, -4e-4, 3e-4, 1.5e-3};
  Mat             K, A;
  Vec             X, ue, u, b;
  PetscInt        n, lo, nbnd = 0, *bnd;
  PetscReal       err, nrm;
  KSP             ksp;
  PC              pc;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetMatrices(m, &K, NULL, NULL));
  PetscCall(Coordinates(m, &X));
  PetscCall(VecDuplicate(X, &ue));
  PetscCall(VecDuplicate(X, &u));
  PetscCall(VecDuplicate(X, &b));
  PetscCall(LinearField(X, G, ue));
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetOwnershipRange(X, &lo, NULL));
  PetscCall(PetscMalloc1(n, &bnd));
  {
    const PetscScalar *x;
    const PetscReal    tol = 1e-12;
    PetscCall(VecGetArrayRead(X, &x));
    for (PetscInt i = 0; i < n; i += 3) {
      const PetscReal px = PetscRealPart(x[i]), py = PetscRealPart(x[i + 1]), pz = PetscRealPart(x[i + 2]);
      const PetscBool on = (PetscBool)(PetscAbsReal(px) < tol || PetscAbsReal(px - GM_LX) < tol || PetscAbsReal(py) < tol || PetscAbsReal(py - GM_LY) < tol || PetscAbsReal(pz) < tol || (interface && PetscAbsReal(pz - GM_C) < tol) || PetscAbsReal(pz - 2 * GM_C) < tol);
      if (on)
        for (int d = 0; d < 3; d++) bnd[nbnd++] = lo + i + d;
    }
    PetscCall(VecRestoreArrayRead(X, &x));
  }
  PetscCallMPI(MPI_Allreduce(&nbnd, nbtot, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &A));
  PetscCall(VecCopy(ue, u));
  PetscCall(VecZeroEntries(b));
  PetscCall(MatZeroRowsColumns(A, nbnd, bnd, 1.0, u, b)); /* b_I = -K_IB u_B, b_B = u_B */
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
#if defined(PETSC_HAVE_MUMPS)
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
#endif
  PetscCall(VecZeroEntries(u));
  PetscCall(KSPSolve(ksp, b, u));
  PetscCall(VecAXPY(u, -1.0, ue));
  PetscCall(VecNorm(u, NORM_INFINITY, &err));
  PetscCall(VecNorm(ue, NORM_INFINITY, &nrm));
  PetscCall(VecGetSize(X, N));
  *relerr = err / nrm;
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&A));
  PetscCall(PetscFree(bnd));
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&ue));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&b));
  PetscFunctionReturn(0);
}

/* ---- patch test and kernel check on the distorted Gmsh mesh ---- */
static PetscErrorCode TestGmsh(const char *dir)
{
  char      file[PETSC_MAX_PATH_LEN], opts[PETSC_MAX_PATH_LEN + 256];
  JRModel   m, mp;
  Mat       K, M, Kp, Mp;
  Vec       X, b;
  PetscReal err;
  PetscInt  n;
  PetscReal mass, rhov;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(file, sizeof(file), "%s/blocks.msh", dir));
  PetscCall(WriteGmsh(file, PETSC_TRUE, 0.0, NULL));
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  PetscCall(PetscSNPrintf(opts, sizeof(opts), "-model_type gmsh -model_file %s -model_E 200e9 -model_nu 0.3 -model_rho 7800 -model_bolt_diameter 0.006", file));
  PetscCall(ModelCreate(opts, &m));
  PetscCall(JRModelGetMatrices(m, &K, &M, NULL));
  PetscCall(JRModelGetMass(m, &mass, &rhov));
  CHECK(PetscAbsReal(mass / (7800 * GM_LX * GM_LY * 2 * GM_C) - 1) < 1e-12, "Gmsh blocks (distorted hexahedra): mass from M %.12g kg = density x volume of the two boxes %.12g kg", (double)mass, 7800 * GM_LX * GM_LY * 2 * GM_C);

  /* patch test: boundary nodes (the planes of the boxes' faces) take u = G x, the interior is solved */
  {
    PetscInt nbtot, N;
    PetscCall(PatchTest(m, PETSC_TRUE, &err, &nbtot, &N));
    CHECK(err < 1e-10 && nbtot < N, "patch test: distorted 27-node hexahedra, %" PetscInt_FMT " of %" PetscInt_FMT " DOFs on the boundary given a linear field, interior solved: max error %.2e of max |u| (bolt in)", nbtot, N, (double)err);
  }
  PetscCall(Coordinates(m, &X));
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecDuplicate(X, &b));
  /* the bolt ties must not resist a rigid motion of the whole assembly */
  {
    Vec       rb[6];
    PetscInt  nrb;
    PetscReal worst = 0, kn, rn;
    PetscCall(JRModelGetRigidBasis(m, &nrb, rb));
    PetscCall(MatNorm(K, NORM_INFINITY, &kn));
    for (PetscInt i = 0; i < nrb; i++) {
      PetscCall(MatMult(K, rb[i], b));
      PetscCall(VecNorm(b, NORM_INFINITY, &err));
      PetscCall(VecNorm(rb[i], NORM_INFINITY, &rn));
      worst = PetscMax(worst, err / (kn * rn));
      PetscCall(VecDestroy(&rb[i]));
    }
    CHECK(nrb == 6 && worst < 1e-12, "Gmsh blocks with a bolt: |K r| / (|K| |r|) = %.1e for the 6 rigid motions", (double)worst);
  }
  /* the rigid basis uses the same node coordinates as PETSc's projection: rotation about z = (-(y - yc), x - xc, 0) */
  {
    Vec                rb[6];
    PetscInt           nrb;
    const PetscScalar *x, *r;
    PetscReal          cmin[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL}, cmax[2] = {PETSC_MIN_REAL, PETSC_MIN_REAL};
    PetscCall(JRModelGetRigidBasis(m, &nrb, rb));
    PetscCall(VecGetArrayRead(X, &x));
    PetscCall(VecGetArrayRead(rb[5], &r));
    for (PetscInt i = 0; i < n; i += 3) {
      const PetscReal cx = PetscRealPart(x[i] - r[i + 1]), cy = PetscRealPart(x[i + 1] + r[i]);
      cmin[0] = PetscMin(cmin[0], cx), cmax[0] = PetscMax(cmax[0], cx);
      cmin[1] = PetscMin(cmin[1], cy), cmax[1] = PetscMax(cmax[1], cy);
    }
    PetscCall(VecRestoreArrayRead(rb[5], &r));
    PetscCall(VecRestoreArrayRead(X, &x));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, cmin, 2, MPIU_REAL, MPIU_MIN, PETSC_COMM_WORLD));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, cmax, 2, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
    CHECK(cmax[0] - cmin[0] < 1e-14 && cmax[1] - cmin[1] < 1e-14, "rigid basis node coordinates = PETSc's projection of x (spread of the implied centre %.1e, %.1e m)", (double)(cmax[0] - cmin[0]), (double)(cmax[1] - cmin[1]));
    for (PetscInt i = 0; i < nrb; i++) PetscCall(VecDestroy(&rb[i]));
  }
  /* interface pairs: one per grid node of the Q2 surface mesh */
  {
    const JRPairs *P;
    PetscReal      dz = 0;
    PetscCall(JRModelGetPairs(m, &P));
    for (PetscInt i = 0; i < P->n; i++) dz = PetscMax(dz, PetscAbsReal(P->x[3 * i + 2] - GM_C));
    CHECK(P->n == (2 * GM_NX + 1) * (2 * GM_NY + 1) && dz < 1e-14 && P->nrm[2] == 1.0 && P->t[0] == 1.0, "Gmsh interface: %" PetscInt_FMT " pairs (expected (2x%d+1)(2x%d+1) = %d), all on z = c, normal (%g, %g, %g) from A (below) into B", P->n, GM_NX, GM_NY, (2 * GM_NX + 1) * (2 * GM_NY + 1), (double)P->nrm[0], (double)P->nrm[1], (double)P->nrm[2]);
  }
  /* the element kernel against PETSc's generic integration, on the same distorted mesh */
  PetscCall(PetscSNPrintf(opts, sizeof(opts), "-model_type gmsh -model_file %s -model_E 200e9 -model_nu 0.3 -model_rho 7800 -model_bolt_diameter 0.006 -model_fe_assembly petscfe", file));
  PetscCall(ModelCreate(opts, &mp));
  PetscCall(JRModelGetMatrices(mp, &Kp, &Mp, NULL));
  {
    PetscReal nk, nm, dk, dm;
    Mat       D;
    PetscCall(MatNorm(K, NORM_FROBENIUS, &nk));
    PetscCall(MatNorm(M, NORM_FROBENIUS, &nm));
    PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &D));
    PetscCall(MatAXPY(D, -1.0, Kp, DIFFERENT_NONZERO_PATTERN));
    PetscCall(MatNorm(D, NORM_FROBENIUS, &dk));
    PetscCall(MatDestroy(&D));
    PetscCall(MatDuplicate(M, MAT_COPY_VALUES, &D));
    PetscCall(MatAXPY(D, -1.0, Mp, DIFFERENT_NONZERO_PATTERN));
    PetscCall(MatNorm(D, NORM_FROBENIUS, &dm));
    PetscCall(MatDestroy(&D));
    CHECK(dk / nk < 1e-12 && dm / nm < 1e-12, "Q2 kernel = PetscFE integration on distorted hexahedra: |K - K_petscfe| / |K| = %.1e, |M - M_petscfe| / |M| = %.1e", (double)(dk / nk), (double)(dm / nm));
  }
  PetscCall(JRModelDestroy(&mp));

  /* the tied interface carries the constant stress across: patch test with the interface nodes solved */
  PetscCall(PetscSNPrintf(file, sizeof(file), "%s/blocks0.msh", dir));
  PetscCall(WriteGmsh(file, PETSC_FALSE, 0.0, NULL));
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  {
    PetscReal e[2];
    PetscInt  nbtot, N;
    for (int tied = 0; tied < 2; tied++) {
      JRModel mt;
      PetscCall(PetscSNPrintf(opts, sizeof(opts), "-model_type gmsh -model_file %s -model_E 200e9 -model_nu 0.3 -model_rho 7800 -model_interface %s", file, tied ? "tied" : "free"));
      PetscCall(ModelCreate(opts, &mt));
      PetscCall(PatchTest(mt, PETSC_FALSE, &e[tied], &nbtot, &N));
      PetscCall(JRModelDestroy(&mt));
    }
    CHECK(e[1] < 1e-2 && e[0] > 1e-1, "patch test across the interface (its nodes solved, no bolt): tied interface error %.1e (the penalty springs' compliance), free interface %.1e (traction-free faces cannot carry the stress)", (double)e[1], (double)e[0]);
  }
  /* pair tolerance: B's interface nodes 1e-9 m off */
  PetscCall(PetscSNPrintf(file, sizeof(file), "%s/offset.msh", dir));
  PetscCall(WriteGmsh(file, PETSC_FALSE, 1e-9, NULL));
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  {
    JRModel        mo;
    const JRPairs *P;
    PetscCall(PetscSNPrintf(opts, sizeof(opts), "-model_type gmsh -model_file %s -model_pair_tol 1e-8", file));
    PetscCall(ModelCreate(opts, &mo));
    PetscCall(JRModelGetPairs(mo, &P));
    CHECK(P->n == (2 * GM_NX + 1) * (2 * GM_NY + 1), "interface 1e-9 m apart, -model_pair_tol 1e-8: all %" PetscInt_FMT " pairs found", P->n);
    PetscCall(JRModelDestroy(&mo));
    PetscCall(PetscSNPrintf(opts, sizeof(opts), "-model_type gmsh -model_file %s -model_pair_tol 1e-10", file));
    CHECK(ModelError(opts) != 0, "interface 1e-9 m apart, -model_pair_tol 1e-10: error (no pairs within the tolerance)");
  }
  /* missing groups, missing file */
  {
    const char *skip[3] = {"contact_a", "contact_b", "bolt1_nut"};
    for (int s = 0; s < 3; s++) {
      PetscCall(PetscSNPrintf(file, sizeof(file), "%s/skip%d.msh", dir, s));
      PetscCall(WriteGmsh(file, PETSC_TRUE, 0.0, skip[s]));
      PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
      PetscCall(PetscSNPrintf(opts, sizeof(opts), "-model_type gmsh -model_file %s", file));
      CHECK(ModelError(opts) != 0, "Gmsh file without the physical group %s: error", skip[s]);
    }
    PetscCall(PetscSNPrintf(opts, sizeof(opts), "-model_type gmsh -model_file %s/none.msh", dir));
    CHECK(ModelError(opts) != 0, "missing Gmsh file: error");
    CHECK(ModelError("-model_type gmsh") != 0, "-model_type gmsh without -model_file: error");
  }
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&b));
  PetscCall(JRModelDestroy(&m));
  PetscFunctionReturn(0);
}

/* ---- straight beams ---- */
static PetscErrorCode TestBeams(void)
{
  const PetscReal L = 0.8, W = 0.04, H = 0.02, E = 210e9, nu = 0.3, rho = 7850;
  const PetscReal c = PetscSqrtReal(E * H * H / (12 * rho)) / (2 * PETSC_PI * L * L); /* f = (beta L)^2 c */
  const PetscReal bl[2][3] = {
    {4.730041, 7.853205, 10.995608}, /* free-free */
    {1.875104, 4.694091, 7.854757 }  /* cantilever */
  };
  const PetscReal hs[3] = {0.04, 0.02, 0.01};
  PetscReal       f[2][3][3];

  PetscFunctionBeginUser;
  for (int clamp = 0; clamp < 2; clamp++) {
    for (int r = 0; r < 3; r++) {
      JRModel  m;
      JRModes  md;
      char     opts[512];
      PetscInt found = 0;
      PetscCall(PetscSNPrintf(opts, sizeof(opts), "-model_type beam -model_length %g -model_width %g -model_height %g -model_mesh_h %g -model_E %g -model_nu %g -model_rho %g%s", (double)L, (double)W, (double)H, (double)hs[r], (double)E, (double)nu, (double)rho, clamp ? " -model_clamp" : ""));
      PetscCall(ModelCreate(opts, &m));
      PetscCall(Modes(m, clamp ? 8 : 14, (PetscBool)!clamp, &md));
      PetscCall(ZBending(md, 3, f[clamp][r], &found));
      CHECK(found == 3, "%s beam, h = %g m: three z-bending modes among the first %d", clamp ? "cantilever" : "free-free", (double)hs[r], clamp ? 8 : 14);
      if (r == 1 && !clamp) { /* Phi^T M Phi = I over all 14 modes, rigid included */
        Mat       K, M;
        Vec      *phi, Mv;
        PetscInt  nm;
        PetscReal worst = 0, mass, rhov;
        PetscCall(JRModelGetMatrices(m, &K, &M, NULL));
        PetscCall(JRModesGetNumber(md, &nm));
        PetscCall(JRModesGetVecs(md, &phi));
        PetscCall(VecDuplicate(phi[0], &Mv));
        for (PetscInt i = 0; i < nm; i++) {
          PetscCall(MatMult(M, phi[i], Mv));
          for (PetscInt j = 0; j <= i; j++) {
            PetscScalar d;
            PetscCall(VecDot(phi[j], Mv, &d));
            worst = PetscMax(worst, PetscAbsReal(PetscRealPart(d) - (i == j ? 1.0 : 0.0)));
          }
        }
        PetscCall(VecDestroy(&Mv));
        CHECK(worst < 1e-8, "free-free beam: Phi^T M Phi = I over %" PetscInt_FMT " modes (6 rigid), max deviation %.1e", nm, (double)worst);
        PetscCall(JRModelGetMass(m, &mass, &rhov));
        CHECK(PetscAbsReal(mass / (rho * L * W * H) - 1) < 1e-12 && PetscAbsReal(rhov / (rho * L * W * H) - 1) < 1e-12, "beam mass from M %.12g kg = rho L W H %.12g kg", (double)mass, (double)(rho * L * W * H));
        /* strain energy of a linear field u = G x: V (lambda tr(e)^2 + 2 mu e:e) */
        {
          const PetscReal G[9] = {1e-3, 2e-4, -3e-4, 5e-4, -2e-3, 1e-4, -4e-4, 3e-4, 1.5e-3};
          const PetscReal lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
          PetscReal       tr = G[0] + G[4] + G[8], ee = 0, wex, wfe;
          PetscScalar     d;
          Vec             X, u, Ku;
          for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) ee += PetscSqr(0.5 * (G[3 * a + b] + G[3 * b + a]));
          wex = L * W * H * (lam * tr * tr + 2 * mu * ee);
          PetscCall(Coordinates(m, &X));
          PetscCall(VecDuplicate(X, &u));
          PetscCall(VecDuplicate(X, &Ku));
          PetscCall(LinearField(X, G, u));
          PetscCall(MatMult(K, u, Ku));
          PetscCall(VecDot(u, Ku, &d));
          wfe = PetscRealPart(d);
          CHECK(PetscAbsReal(wfe / wex - 1) < 1e-10, "constant strain on the beam: u^T K u = %.12g J, V (lambda tr(e)^2 + 2 mu e:e) = %.12g J", (double)wfe, (double)wex);
          PetscCall(VecDestroy(&X));
          PetscCall(VecDestroy(&u));
          PetscCall(VecDestroy(&Ku));
        }
      }
      PetscCall(JRModesDestroy(&md));
      PetscCall(JRModelDestroy(&m));
    }
    for (int k = 0; k < 3; k++) {
      const PetscReal eb = bl[clamp][k] * bl[clamp][k] * c, e = f[clamp][2][k] / eb - 1;
      CHECK(PetscAbsReal(e) < 0.02, "%s beam 800 x 40 x 20 mm, h = 10 mm: z-bending mode %d %.2f Hz vs Euler-Bernoulli %.2f Hz (%+.2f%%)", clamp ? "cantilever" : "free-free", k + 1, (double)f[clamp][2][k], (double)eb, (double)(100 * e));
      CHECK(f[clamp][0][k] >= f[clamp][1][k] && f[clamp][1][k] >= f[clamp][2][k] && f[clamp][0][k] - f[clamp][1][k] > f[clamp][1][k] - f[clamp][2][k], "%s beam, z-bending mode %d under refinement h = 40, 20, 10 mm: %.3f, %.3f, %.3f Hz (decreasing, differences shrinking)", clamp ? "cantilever" : "free-free", k + 1, (double)f[clamp][0][k], (double)f[clamp][1][k], (double)f[clamp][2][k]);
    }
  }
  /* exactly 6 near-zero modes without the supplied basis */
  {
    JRModel          m;
    JRModes          md;
    const PetscReal *lam;
    PetscInt         nz = 0;
    PetscCall(ModelCreate("-model_type beam -model_mesh_h 0.02", &m));
    PetscCall(Modes(m, 10, PETSC_FALSE, &md));
    PetscCall(JRModesGetEigenvalues(md, &lam));
    for (PetscInt i = 0; i < 10; i++) nz += PetscSqrtReal(PetscAbsReal(lam[i])) / (2 * PETSC_PI) < 1.0;
    CHECK(nz == 6 && PetscSqrtReal(lam[6]) / (2 * PETSC_PI) > 100.0, "free-free beam, no rigid basis supplied: %" PetscInt_FMT " of 10 frequencies below 1 Hz (expected 6), the 7th %.2f Hz", nz, (double)(PetscSqrtReal(lam[6]) / (2 * PETSC_PI)));
    PetscCall(JRModesDestroy(&md));
    PetscCall(JRModelDestroy(&m));
  }
  PetscFunctionReturn(0);
}

/* ---- lap joints ---- */
static PetscErrorCode TestLap(void)
{
  const char *small = "-model_type lap -model_length_a 0.1 -model_length_b 0.1 -model_lap_length 0.04 -model_width 0.02 -model_height 0.02 -model_mesh_h 0.005 -model_mesh_grade 2 -model_bolt_diameter 0.006 -model_hole_diameter 0.0065 -model_washer_diameter 0.012";
  char        opts[1024];
  PetscReal   f7[2] = {0, 0};

  PetscFunctionBeginUser;
  /* no bolts: two separate bodies; pairs on the lap grid: (2 x 8 + 1)(2 x 4 + 1) = 153 */
  {
    JRModel        m;
    const JRPairs *P;
    PetscReal      mass, dmax = 0;
    PetscBool      distinct = PETSC_TRUE;
    PetscCall(PetscSNPrintf(opts, sizeof(opts), "%s -model_nbolts 0", small));
    PetscCall(ModelCreate(opts, &m));
    PetscCall(JRModelGetPairs(m, &P));
    for (PetscInt i = 0; i < P->n; i++) {
      dmax = PetscMax(dmax, PetscAbsReal(P->x[3 * i + 2] - 0.01));
      if (P->x[3 * i] < 0.06 - 1e-12 || P->x[3 * i] > 0.1 + 1e-12) dmax = 1;
      for (int d = 0; d < 3; d++) distinct = (PetscBool)(distinct && P->dofA[3 * i + d] != P->dofB[3 * i + d] && P->dofA[3 * i + d] == P->dofA[3 * i] + d);
    }
    CHECK(P->n == 153 && dmax < 1e-14 && distinct, "lap 0.04 m x 0.02 m at h = 5 mm, no holes: %" PetscInt_FMT " pairs (expected 17 x 9 = 153), all on the plane z = H/2 inside the lap, distinct nodes", P->n);
    PetscCall(JRModelGetMass(m, &mass, NULL));
    CHECK(PetscAbsReal(mass / (7900 * 0.02 * 0.02 * 0.16) - 1) < 1e-12, "lap mass from M %.12g kg = rho W H (L_a + L_b - L_lap) %.12g kg", (double)mass, 7900 * 0.02 * 0.02 * 0.16);
    PetscCall(JRModelDestroy(&m));
  }
  /* one bolt, either tie: 6 rigid-body modes only (the bolt holds the bodies together), K r = 0 */
  for (int tie = 0; tie < 2; tie++) {
    JRModel          m;
    JRModes          md;
    const PetscReal *lam;
    PetscInt         nz = 0, nrb;
    Vec              rb[6], Kr;
    Mat              K;
    PetscReal        worst = 0, kn;
    PetscCall(PetscSNPrintf(opts, sizeof(opts), "%s -model_nbolts 1 -model_bolt_tie %s", small, tie ? "rigid" : "distributing"));
    PetscCall(ModelCreate(opts, &m));
    PetscCall(JRModelGetMatrices(m, &K, NULL, NULL));
    PetscCall(JRModelGetRigidBasis(m, &nrb, rb));
    PetscCall(MatNorm(K, NORM_INFINITY, &kn));
    PetscCall(VecDuplicate(rb[0], &Kr));
    for (PetscInt i = 0; i < nrb; i++) {
      PetscReal e, rn;
      PetscCall(MatMult(K, rb[i], Kr));
      PetscCall(VecNorm(Kr, NORM_INFINITY, &e));
      PetscCall(VecNorm(rb[i], NORM_INFINITY, &rn));
      worst = PetscMax(worst, e / (kn * rn));
      PetscCall(VecDestroy(&rb[i]));
    }
    PetscCall(VecDestroy(&Kr));
    CHECK(worst < 1e-12, "bolted lap (%s tie): |K r| / (|K| |r|) = %.1e for the 6 rigid motions", tie ? "rigid" : "distributing", (double)worst);
    PetscCall(Modes(m, 10, PETSC_FALSE, &md));
    PetscCall(JRModesGetEigenvalues(md, &lam));
    for (PetscInt i = 0; i < 10; i++) nz += PetscSqrtReal(PetscAbsReal(lam[i])) / (2 * PETSC_PI) < 1.0;
    f7[tie] = PetscSqrtReal(lam[6]) / (2 * PETSC_PI);
    CHECK(nz == 6 && f7[tie] > 100.0, "bolted lap (%s tie), no rigid basis supplied: %" PetscInt_FMT " frequencies below 1 Hz (expected 6: the bolt joins the bodies), first elastic %.1f Hz", tie ? "rigid" : "distributing", nz, (double)f7[tie]);
    PetscCall(JRModesDestroy(&md));
    PetscCall(JRModelDestroy(&m));
  }
  CHECK(f7[1] > f7[0], "the rigid tie (a penalty added to K) raises the first elastic frequency: %.2f > %.2f Hz", (double)f7[1], (double)f7[0]);
  /* tied interface: one body without bolts (6 rigid modes); tying adds stiffness, so no frequency falls */
  {
    JRModel          m;
    JRModes          md;
    const PetscReal *lam, *lamf;
    PetscInt         nz = 0;
    PetscReal        fall = 0;
    JRModes          mdf;
    JRModel          mf;
    PetscCall(PetscSNPrintf(opts, sizeof(opts), "%s -model_nbolts 0 -model_interface tied", small));
    PetscCall(ModelCreate(opts, &m));
    PetscCall(Modes(m, 10, PETSC_FALSE, &md));
    PetscCall(JRModesGetEigenvalues(md, &lam));
    for (PetscInt i = 0; i < 10; i++) nz += PetscSqrtReal(PetscAbsReal(lam[i])) / (2 * PETSC_PI) < 1.0;
    CHECK(nz == 6, "lap with a tied interface and no bolts: %" PetscInt_FMT " frequencies below 1 Hz (expected 6), first elastic %.1f Hz", nz, (double)(PetscSqrtReal(lam[6]) / (2 * PETSC_PI)));
    PetscCall(JRModesDestroy(&md));
    PetscCall(JRModelDestroy(&m));
    PetscCall(PetscSNPrintf(opts, sizeof(opts), "%s -model_nbolts 1 -model_interface tied", small));
    PetscCall(ModelCreate(opts, &m));
    PetscCall(Modes(m, 10, PETSC_TRUE, &md));
    PetscCall(PetscSNPrintf(opts, sizeof(opts), "%s -model_nbolts 1 -model_interface free", small));
    PetscCall(ModelCreate(opts, &mf));
    PetscCall(Modes(mf, 10, PETSC_TRUE, &mdf));
    PetscCall(JRModesGetEigenvalues(md, &lam));
    PetscCall(JRModesGetEigenvalues(mdf, &lamf));
    for (PetscInt i = 6; i < 10; i++) fall = PetscMax(fall, lamf[i] - lam[i]);
    CHECK(fall <= 0 && lam[6] > 1.5 * lamf[6], "bolted lap: tied interface >= free for the first 4 elastic frequencies (first %.1f vs %.1f Hz)", (double)(PetscSqrtReal(lam[6]) / (2 * PETSC_PI)), (double)(PetscSqrtReal(lamf[6]) / (2 * PETSC_PI)));
    PetscCall(JRModesDestroy(&md));
    PetscCall(JRModelDestroy(&m));
    PetscCall(JRModesDestroy(&mdf));
    PetscCall(JRModelDestroy(&mf));
  }
  /* the Brake-Reuss beam: lap 120 mm at 5 mm (24 cells), width 25.4 mm (6 cells); each 8.5 mm hole
     removes the 2 x 2 cells around its axis, so 3 x 9 interior Q2 nodes: (2 x 24 + 1)(2 x 6 + 1) - 27 */
  {
    JRModel        m;
    const JRPairs *P;
    PetscInt       nhole = 0;
    PetscCall(ModelCreate("-model_type brb", &m));
    PetscCall(JRModelGetPairs(m, &P));
    for (PetscInt i = 0; i < P->n; i++)
      for (int b = 0; b < 3; b++) nhole += PetscAbsReal(P->x[3 * i] - (0.33 + 0.03 * b)) < 0.005 - 1e-9 && PetscAbsReal(P->x[3 * i + 1] - 0.0127) < 0.0254 / 6 - 1e-9;
    CHECK(P->n == 49 * 13 - 27 && nhole == 0, "Brake-Reuss beam: %" PetscInt_FMT " interface pairs (expected 49 x 13 - 27 = 610), %" PetscInt_FMT " inside the removed cells", P->n, nhole);
    PetscCall(JRModelDestroy(&m));
  }
  /* bad input */
  PetscCall(PetscSNPrintf(opts, sizeof(opts), "%s -model_nbolts 3 -model_bolt_pitch 0.015", small));
  CHECK(ModelError(opts) != 0, "three bolts at 15 mm pitch on a 40 mm lap (washers reach outside the lap): error");
  CHECK(ModelError("-model_type brb -model_E -190e9") != 0, "negative Young's modulus: error");
  CHECK(ModelError("-model_type brb -model_width -0.01") != 0, "negative width: error");
  CHECK(ModelError("-model_type brb -model_lap_length 0.5") != 0, "lap longer than a beam: error");
  CHECK(ModelError("-model_type beam -model_nu 0.5") != 0, "Poisson's ratio 0.5: error");
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char dir[] = "/tmp/jrfeXXXXXX";

  PetscCall(SlepcInitialize(&argc, &argv, NULL, NULL));
  if (!JRTestRank()) PetscCheck(mkdtemp(dir), PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "mkdtemp");
  PetscCallMPI(MPI_Bcast(dir, sizeof(dir), MPI_CHAR, 0, PETSC_COMM_WORLD));
  PetscCall(TestGmsh(dir));
  PetscCall(TestLap());
  PetscCall(TestBeams());
  if (!JRTestRank()) {
    char cmd[64];
    PetscCall(PetscSNPrintf(cmd, sizeof(cmd), "rm -rf %s", dir));
    if (system(cmd)) printf("# could not remove %s\n", dir);
  }
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(SlepcFinalize());
  return jr_fail ? 1 : 0;
}
