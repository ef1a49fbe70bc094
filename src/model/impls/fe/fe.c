/*
   Finite-element models of beams and bolted lap joints on DMPlex + PetscFE: the set-up.

   The mesh (geometry.c, gmsh.c), its distribution, the DOF layout (PetscFE on DMPlex), assembly into the
   parallel matrices and the output are PETSc's. JRFESetUp builds, in order:
     the displacement field and the elasticity Jacobian                JRFEDiscretise     (assemble.c)
     K and M, by the 27-node kernel or PETSc's integration             JRFEAssemble       (assemble.c)
     the bolts: beams tied to their washer footprints                  JRFEAddBolts       (bolts.c)
     the mass check, then for a lap joint the node-to-node pairs       JRFEFindPairs      (pairs.c)
     and, with -model_interface tied, their penalty springs            JRFETieInterface   (pairs.c)
     the rigid-body modes as K's near null space.
   Nodes, rigid-body motions and the nodes of labelled faces with their area weights are in nodes.c.
   Units SI.
*/
#include <jointrom/private/feimpl.h>

/* the volume from PETSc's cell geometry (independent of the element kernel; before the closure permutation) */
static PetscErrorCode ComputeVolume(MPI_Comm comm, Model_FE *fe)
{
  PetscReal vol = 0.0;
  PetscInt  cs, ce;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetHeightStratum(fe->dm, 0, &cs, &ce));
  for (PetscInt c = cs; c < ce; c++) {
    PetscReal v, cen[3]; /* no overlap: every cell is owned */
    PetscCall(DMPlexComputeCellGeometryFVM(fe->dm, c, &v, cen, NULL));
    vol += v;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &vol, 1, MPIU_REAL, MPIU_SUM, comm));
  fe->volume = vol;
  PetscFunctionReturn(0);
}

/* the total mass: a unit translation u_x = 1 gives u^T M u; a clamped end removes DOFs, so there the
   mass check is made free-free (density x volume) */
static PetscErrorCode TotalMass(JRModel m, Model_FE *fe)
{
  PetscFunctionBeginUser;
  if (!fe->clamp) { /* the x translation through M */
    Vec          u, Mu;
    PetscScalar *a;
    PetscInt     n;
    PetscCall(DMCreateGlobalVector(fe->dm, &u));
    PetscCall(VecDuplicate(u, &Mu));
    PetscCall(VecGetLocalSize(u, &n));
    PetscCall(VecGetArray(u, &a));
    for (PetscInt i = 0; i < n; i++) a[i] = i % 3 == 0 ? 1.0 : 0.0;
    PetscCall(VecRestoreArray(u, &a));
    PetscCall(MatMult(m->M, u, Mu));
    PetscCall(VecDot(u, Mu, &fe->mass));
    PetscCall(VecDestroy(&Mu));
    PetscCall(VecDestroy(&u));
  } else fe->mass = fe->rho * fe->volume;
  m->mass        = fe->mass;
  m->volume_mass = fe->rho * fe->volume;
  PetscFunctionReturn(0);
}

/* the rigid-body modes as K's near null space: algebraic multigrid (-modes_st_pc_type gamg) needs them */
static PetscErrorCode SetNearNullSpace(JRModel m, Model_FE *fe)
{
  Vec          X, Xb;
  MatNullSpace nsp;
  PetscInt     n;

  PetscFunctionBeginUser;
  PetscCall(DMCreateGlobalVector(fe->dm, &X));
  PetscCall(JRFENodalCoordinates(fe->dm, X));
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecCreateMPI(m->comm, n, PETSC_DETERMINE, &Xb));
  PetscCall(VecSetBlockSize(Xb, 3));
  PetscCall(VecCopy(X, Xb));
  PetscCall(MatNullSpaceCreateRigidBody(Xb, &nsp));
  PetscCall(MatSetNearNullSpace(m->K, nsp));
  PetscCall(MatNullSpaceDestroy(&nsp));
  PetscCall(VecDestroy(&Xb));
  PetscCall(VecDestroy(&X));
  PetscFunctionReturn(0);
}

/*
  JRFESetUp - the discretisation, K, M, the bolts and the interface pairs of an FE model whose mesh
  fe->dm is built; m->dm takes a reference to it. Options reaching it (read by the model's
  SetFromOptions): -model_E, -model_nu, -model_rho, -model_fe_order, -model_fe_assembly, -model_clamp,
  -model_bolt_tie, -model_pair_tol, -model_tangent, -model_interface.
*/
PetscErrorCode JRFESetUp(JRModel m, Model_FE *fe)
{
  PetscFunctionBeginUser;
  PetscCheck(fe->E > 0 && PetscIsNormalReal(fe->E), m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_E %g: Young's modulus must be positive [Pa]", (double)fe->E);
  PetscCheck(fe->nu > -1.0 && fe->nu < 0.5, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_nu %g: Poisson's ratio must be in (-1, 0.5)", (double)fe->nu);
  PetscCheck(fe->rho > 0 && PetscIsNormalReal(fe->rho), m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_rho %g: the density must be positive [kg/m^3]", (double)fe->rho);
  PetscCheck(fe->order >= 1 && fe->order <= 4, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_fe_order %" PetscInt_FMT ": 1 to 4", fe->order);
  PetscCall(JRFEDiscretise(m->comm, fe));
  PetscCall(ComputeVolume(m->comm, fe));
  PetscCall(DMSetUp(fe->dm));
  PetscCall(JRFEAssemble(m, fe));
  PetscCall(JRFEAddBolts(m, fe));
  PetscCall(TotalMass(m, fe));
  fe->nnodes = m->ndof / 3;
  if (fe->lap) PetscCall(JRFEFindPairs(m, fe));
  if (fe->lap && fe->tied) PetscCall(JRFETieInterface(m, fe));
  m->tied = fe->lap && fe->tied ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(SetNearNullSpace(m, fe));
  PetscCall(JRFENaturalOrdering(fe->dm, fe->orig, &m->nat));
  m->dm = fe->dm;
  PetscCall(PetscObjectReference((PetscObject)fe->dm));
  PetscFunctionReturn(0);
}
