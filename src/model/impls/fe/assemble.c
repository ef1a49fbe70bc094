/*
   The discretisation of the FE models and the assembly of K and M.

   Isotropic linear elasticity on hexahedra with Lagrange elements of order -model_fe_order (default 2:
   27-node quadratic hexahedra, which do not lock in bending); the DOF layout is PETSc's (PetscFE on
   DMPlex). The order-2 element matrices (stiffness and consistent mass, 3x3x3 Gauss points on the
   trilinear geometry) come from a kernel in this file rather than from PETSc's generic PetscFE
   integration, which is two orders of magnitude slower on 81-DOF cells (15 ms a cell in PETSc 3.18: 10
   minutes for the Brake-Reuss beam instead of a second); equal element shapes are computed once.
   -model_fe_assembly petscfe selects PETSc's integration (DMPlexSNESComputeJacobianFEM,
   DMCreateMassMatrix) instead; the two agree to round-off (tests/test_fe.c). Units SI.
*/
#include <jointrom/private/feimpl.h>

/* ---- pointwise functions (PetscDS and DMProjectFunction signatures: most arguments unused) ---- */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
static void g3_elasticity(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, PetscReal u_tShift, const PetscReal x[], PetscInt numConstants, const PetscScalar constants[], PetscScalar g3[])
{
  const PetscReal lam = PetscRealPart(constants[0]), mu = PetscRealPart(constants[1]);
  for (PetscInt i = 0; i < dim; i++)
    for (PetscInt j = 0; j < dim; j++)
      for (PetscInt d = 0; d < dim; d++)
        for (PetscInt e = 0; e < dim; e++) g3[((i * dim + j) * dim + d) * dim + e] = (i == d && j == e ? lam : 0.0) + (i == j && d == e ? mu : 0.0) + (i == e && d == j ? mu : 0.0);
}

static PetscErrorCode zero_vector(PetscInt dim, PetscReal time, const PetscReal x[], PetscInt Nc, PetscScalar *u, void *ctx)
{
  for (PetscInt c = 0; c < Nc; c++) u[c] = 0.0;
  return 0;
}

#pragma GCC diagnostic pop

/* ---- element matrices: 27-node (Q2) hexahedra, trilinear geometry, 3 x 3 x 3 Gauss ----
   PETSc's generic pointwise integration takes ~15 ms per Q2 hexahedron (measured: 4.7 s for 320 cells),
   ten minutes for 10^6 DOFs; this kernel builds the same element matrices in ~0.1 ms, and a structured
   mesh reuses them (identical bricks are computed once). The closure is in tensor (lexicographic) order
   (DMPlexSetClosurePermutationTensor): node a + 3b + 9c at reference (a - 1, b - 1, c - 1), 3 components
   each. -model_fe_assembly petscfe uses DMPlexSNESComputeJacobianFEM instead (a test checks they agree). */
typedef struct {
  PetscReal rel[24]; /* vertex coordinates relative to vertex 0: the cell's shape */
  PetscReal K[81 * 81], M[81 * 81];
} ElemCache;

static void Lagrange1D(PetscReal x, PetscReal N[3], PetscReal dN[3])
{
  N[0]  = 0.5 * x * (x - 1.0);
  N[1]  = 1.0 - x * x;
  N[2]  = 0.5 * x * (x + 1.0);
  dN[0] = x - 0.5;
  dN[1] = -2.0 * x;
  dN[2] = x + 0.5;
}

/* Ke (81 x 81, stiffness) and Me (81 x 81, mass with density rho) of one hexahedron with vertices X
   (8 x 3, lexicographic: vertex i + 2j + 4k at reference (2i - 1, 2j - 1, 2k - 1)) */
static PetscErrorCode HexQ2(const PetscReal X[24], PetscReal lam, PetscReal mu, PetscReal rho, PetscReal *Ke, PetscReal *Me)
{
  const PetscReal g[3] = {-PetscSqrtReal(0.6), 0.0, PetscSqrtReal(0.6)}, gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 81 * 81; i++) Ke[i] = Me[i] = 0.0;
  for (int qz = 0; qz < 3; qz++)
    for (int qy = 0; qy < 3; qy++)
      for (int qx = 0; qx < 3; qx++) {
        const PetscReal xi[3] = {g[qx], g[qy], g[qz]}, w = gw[qx] * gw[qy] * gw[qz];
        PetscReal       N1[3][3], dN1[3][3], J[3][3] = {{0}}, Ji[3][3], det, N[27], dN[27][3];
        for (int d = 0; d < 3; d++) Lagrange1D(xi[d], N1[d], dN1[d]);
        /* geometry: x = sum_v M_v(xi) X_v, M_v = prod (1 +- xi_d)/2 */
        for (int v = 0; v < 8; v++) {
          const int       s[3] = {v & 1, (v >> 1) & 1, (v >> 2) & 1};
          PetscReal       m[3], dm[3];
          for (int d = 0; d < 3; d++) {
            m[d]  = 0.5 * (1.0 + (2 * s[d] - 1) * xi[d]);
            dm[d] = 0.5 * (2 * s[d] - 1);
          }
          const PetscReal dM[3] = {dm[0] * m[1] * m[2], m[0] * dm[1] * m[2], m[0] * m[1] * dm[2]};
          for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) J[a][b] += X[3 * v + a] * dM[b]; /* dx_a / dxi_b */
        }
        det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
        PetscCheck(det != 0.0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Degenerate hexahedron");
        Ji[0][0] = (J[1][1] * J[2][2] - J[1][2] * J[2][1]) / det;
        Ji[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / det;
        Ji[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / det;
        Ji[1][0] = (J[1][2] * J[2][0] - J[1][0] * J[2][2]) / det;
        Ji[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / det;
        Ji[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / det;
        Ji[2][0] = (J[1][0] * J[2][1] - J[1][1] * J[2][0]) / det;
        Ji[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / det;
        Ji[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / det;
        for (int c = 0; c < 3; c++)
          for (int b = 0; b < 3; b++)
            for (int a = 0; a < 3; a++) {
              const int       n      = a + 3 * b + 9 * c;
              const PetscReal dr[3]  = {dN1[0][a] * N1[1][b] * N1[2][c], N1[0][a] * dN1[1][b] * N1[2][c], N1[0][a] * N1[1][b] * dN1[2][c]};
              N[n]                   = N1[0][a] * N1[1][b] * N1[2][c];
              for (int d = 0; d < 3; d++) dN[n][d] = dr[0] * Ji[0][d] + dr[1] * Ji[1][d] + dr[2] * Ji[2][d];
            }
        {
          const PetscReal wd = w * PetscAbsReal(det);
          for (int p = 0; p < 27; p++)
            for (int q = 0; q < 27; q++) {
              const PetscReal gpq = dN[p][0] * dN[q][0] + dN[p][1] * dN[q][1] + dN[p][2] * dN[q][2];
              const PetscReal mpq = wd * rho * N[p] * N[q];
              for (int i = 0; i < 3; i++) {
                PetscReal *row = Ke + (3 * p + i) * 81 + 3 * q;
                for (int j = 0; j < 3; j++) row[j] += wd * (lam * dN[p][i] * dN[q][j] + mu * dN[p][j] * dN[q][i] + (i == j ? mu * gpq : 0.0));
                Me[(3 * p + i) * 81 + 3 * q + i] += mpq;
              }
            }
        }
      }
  PetscFunctionReturn(0);
}

/* K and M by the kernel above, element by element into the DMPlex matrices */
static PetscErrorCode AssembleHexQ2(DM dm, PetscReal E, PetscReal nu, PetscReal rho, Mat K, Mat M)
{
  const PetscReal lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  DM              cdm;
  Vec             coords;
  PetscInt        cs, ce, ncache = 0;
  ElemCache      *cache;
  PetscReal      *Ke, *Me;
  const PetscInt  maxcache = 32;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cs, &ce));
  PetscCall(PetscMalloc1(maxcache, &cache));
  PetscCall(PetscMalloc2(81 * 81, &Ke, 81 * 81, &Me));
  for (PetscInt c = cs; c < ce; c++) {
    PetscScalar *xc = NULL;
    PetscInt     nx, hit = -1;
    PetscReal    X[24], rel[24], scale = 0.0;
    PetscCall(DMPlexVecGetClosure(cdm, NULL, coords, c, &nx, &xc));
    PetscCheck(nx == 24, PETSC_COMM_SELF, PETSC_ERR_SUP, "The 27-node kernel needs hexahedra with 8 vertices (cell %" PetscInt_FMT " has %" PetscInt_FMT " coordinates); use -model_fe_assembly petscfe", c, nx);
    for (int k = 0; k < 24; k++) X[k] = PetscRealPart(xc[k]);
    PetscCall(DMPlexVecRestoreClosure(cdm, NULL, coords, c, &nx, &xc));
    for (int k = 0; k < 24; k++) {
      rel[k] = X[k] - X[k % 3];
      scale  = PetscMax(scale, PetscAbsReal(rel[k]));
    }
    for (PetscInt h = 0; h < ncache && hit < 0; h++) {
      PetscBool same = PETSC_TRUE;
      for (int k = 0; k < 24 && same; k++)
        if (PetscAbsReal(cache[h].rel[k] - rel[k]) > 1e-12 * scale) same = PETSC_FALSE;
      if (same) hit = h;
    }
    if (hit < 0) {
      PetscCall(HexQ2(X, lam, mu, rho, Ke, Me));
      if (ncache < maxcache) {
        for (int k = 0; k < 24; k++) cache[ncache].rel[k] = rel[k];
        PetscCall(PetscArraycpy(cache[ncache].K, Ke, 81 * 81));
        PetscCall(PetscArraycpy(cache[ncache].M, Me, 81 * 81));
        hit = ncache++;
      }
    }
    PetscCall(DMPlexMatSetClosure(dm, NULL, NULL, K, c, hit >= 0 ? cache[hit].K : Ke, ADD_VALUES));
    PetscCall(DMPlexMatSetClosure(dm, NULL, NULL, M, c, hit >= 0 ? cache[hit].M : Me, ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree2(Ke, Me));
  PetscCall(PetscFree(cache));
  PetscFunctionReturn(0);
}

/* The displacement field (Lagrange, order fe->order) on fe->dm, the clamp (-model_clamp) as an essential
   boundary condition, and the elasticity Jacobian with the Lame constants of fe->E, fe->nu (used by
   -model_fe_assembly petscfe and by every order other than 2) */
PetscErrorCode JRFEDiscretise(MPI_Comm comm, Model_FE *fe)
{
  PetscFE pfe;
  PetscDS ds;

  PetscFunctionBeginUser;
  PetscCall(PetscFECreateLagrange(comm, 3, 3, PETSC_FALSE, fe->order, PETSC_DETERMINE, &pfe));
  PetscCall(PetscObjectSetName((PetscObject)pfe, "displacement"));
  PetscCall(DMAddField(fe->dm, NULL, (PetscObject)pfe));
  PetscCall(PetscFEDestroy(&pfe));
  PetscCall(DMCreateDS(fe->dm));
  if (fe->clamp) { /* the end x = 0 fixed: a cantilever */
    DMLabel        label;
    const PetscInt val = 1;
    PetscCall(DMGetLabel(fe->dm, JR_LABEL_CLAMP, &label));
    PetscCall(DMAddBoundary(fe->dm, DM_BC_ESSENTIAL, "clamp", label, 1, &val, 0, 0, NULL, (void (*)(void))zero_vector, NULL, NULL, NULL));
  }
  PetscCall(DMGetDS(fe->dm, &ds));
  {
    const PetscReal   lam = fe->E * fe->nu / ((1 + fe->nu) * (1 - 2 * fe->nu)), mu = fe->E / (2 * (1 + fe->nu));
    const PetscScalar cst[2] = {lam, mu};
    PetscCall(PetscDSSetConstants(ds, 2, (PetscScalar *)cst));
  }
  PetscCall(PetscDSSetJacobian(ds, 0, 0, NULL, NULL, NULL, g3_elasticity));
  PetscFunctionReturn(0);
}

/* m->K and m->M (named "K", "M") and m->ndof on the set-up fe->dm: the Q2 kernel for order 2, PETSc's
   integration otherwise or with -model_fe_assembly petscfe */
PetscErrorCode JRFEAssemble(JRModel m, Model_FE *fe)
{
  PetscFunctionBeginUser;
  PetscCall(DMCreateMatrix(fe->dm, &m->K));
  if (fe->order == 2 && !fe->petscfe) {
    DM cdm;
    PetscCall(DMPlexSetClosurePermutationTensor(fe->dm, PETSC_DETERMINE, NULL));
    PetscCall(DMGetCoordinateDM(fe->dm, &cdm));
    PetscCall(DMPlexSetClosurePermutationTensor(cdm, PETSC_DETERMINE, NULL));
    PetscCall(MatDuplicate(m->K, MAT_DO_NOT_COPY_VALUES, &m->M)); /* K's pattern: half the preallocation time */
    PetscCall(AssembleHexQ2(fe->dm, fe->E, fe->nu, fe->rho, m->K, m->M));
  } else {
    Vec u; /* the Jacobian of a linear problem: at u = 0 */
    PetscCall(DMCreateGlobalVector(fe->dm, &u));
    PetscCall(VecZeroEntries(u));
    PetscCall(DMPlexSNESComputeJacobianFEM(fe->dm, u, m->K, m->K, NULL));
    PetscCall(VecDestroy(&u));
    PetscCall(DMCreateMassMatrix(fe->dm, fe->dm, &m->M));
    PetscCall(MatScale(m->M, fe->rho));
  }
  PetscCall(MatGetSize(m->K, &m->ndof, NULL));
  PetscCall(PetscObjectSetName((PetscObject)m->K, "K"));
  PetscCall(PetscObjectSetName((PetscObject)m->M, "M"));
  PetscFunctionReturn(0);
}
