/* Points of an FE model found by position: its bounding box and the node nearest a point */
#include <jointrom/private/modelimpl.h>

/* Bounding box of the mesh [m] (collective) */
PetscErrorCode JRModelGetBoundingBox(JRModel model, PetscReal lo[3], PetscReal hi[3])
{
  Vec                X;
  const PetscScalar *x;
  PetscInt           rlo, rhi;
  PetscReal          l[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, h[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL};
  MPI_Comm           comm;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetComm(model, &comm));
  PetscCall(JRModelGetCoordinates(model, &X));
  PetscCheck(X, comm, PETSC_ERR_ARG_WRONG, "The model has no mesh coordinates (points are found by position only on FE models)");
  PetscCall(VecGetOwnershipRange(X, &rlo, &rhi));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt i = rlo; i < rhi; i++) {
    const PetscInt c = i % 3;
    l[c]             = PetscMin(l[c], PetscRealPart(x[i - rlo]));
    h[c]             = PetscMax(h[c], PetscRealPart(x[i - rlo]));
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecDestroy(&X));
  PetscCall(MPIU_Allreduce(l, lo, 3, MPIU_REAL, MPIU_MIN, comm));
  PetscCall(MPIU_Allreduce(h, hi, 3, MPIU_REAL, MPIU_MAX, comm));
  PetscFunctionReturn(0);
}

/*
  JRModelFindDof - the DOF of component comp (0 x, 1 y, 2 z) of the mesh node nearest to the point p [m],
  and that node's distance from it (collective; the same on every rank and on any number of ranks: of equally near
  nodes, the first in the natural order of JRModelDOFsToNatural).
  The DOFs of a node are consecutive x, y, z (PetscFE layout), so DOF i is component i % 3.
*/
PetscErrorCode JRModelFindDof(JRModel model, const PetscReal p[3], PetscInt comp, PetscInt *dof, PetscReal *dist)
{
  Vec                X;
  const PetscScalar *x;
  PetscInt           rlo, rhi, best = -1, nb = PETSC_MAX_INT;
  PetscReal          bd = PETSC_MAX_REAL, dmin;
  MPI_Comm           comm;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetComm(model, &comm));
  PetscCheck(comp >= 0 && comp < 3, comm, PETSC_ERR_ARG_OUTOFRANGE, "Component %" PetscInt_FMT ": 0 (x), 1 (y) or 2 (z)", comp);
  PetscCall(JRModelDOFsToNatural(model, 0, NULL, NULL)); /* its tables, on every rank */
  PetscCall(JRModelGetCoordinates(model, &X));
  PetscCheck(X, comm, PETSC_ERR_ARG_WRONG, "The model has no mesh coordinates (points are found by position only on FE models)");
  PetscCall(VecGetOwnershipRange(X, &rlo, &rhi));
  PetscCheck(rlo % 3 == 0 && (rhi - rlo) % 3 == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "DOFs are not in x, y, z triples");
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt i = 0; i < rhi - rlo; i += 3) { /* the nearest node; of equally near ones (two bodies' nodes at a
                                                  pair, a point midway), the first in the natural order, as on any ranks */
    PetscReal d = 0.0;
    PetscInt  g = rlo + i + comp, n;
    for (PetscInt c = 0; c < 3; c++) d += PetscSqr(PetscRealPart(x[i + c]) - p[c]);
    PetscCall(JRModelDOFsToNatural(model, 1, &g, &n));
    if (d < bd || (d == bd && n < nb)) {
      bd   = d;
      best = g;
      nb   = n;
    }
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecDestroy(&X));
  PetscCall(MPIU_Allreduce(&bd, &dmin, 1, MPIU_REAL, MPIU_MIN, comm));
  if (bd != dmin) nb = PETSC_MAX_INT;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nb, 1, MPIU_INT, MPI_MIN, comm));
  PetscCall(JRModelDOFsFromNatural(model, 1, &nb, &best));
  *dof = best;
  if (dist) *dist = PetscSqrtReal(dmin);
  PetscFunctionReturn(0);
}
