/* Dense blocks over arbitrary global DOFs, assembled into a sparse matrix. */
#include <jointrom/private/modelimpl.h>

/* B: a matrix of K's layout holding the sum of nb dense blocks (block b: bn[b] global DOFs bdof[b], values
   bval[b] row-major); each rank adds the rows it owns. For couplings outside K's pattern (bolts, ties, pairs):
   K + B through MatAXPY(..., DIFFERENT_NONZERO_PATTERN). */
PetscErrorCode JRMatCreateFromBlocks(Mat K, PetscInt nb, const PetscInt *bn, const PetscInt *const *bdof, const PetscReal *const *bval, Mat *B)
{
  MPI_Comm  comm;
  PetscInt  rs, re, cs, ce, N, *dnz, *onz;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)K, &comm));
  PetscCall(MatGetSize(K, &N, NULL));
  PetscCall(MatGetOwnershipRange(K, &rs, &re));
  PetscCall(MatGetOwnershipRangeColumn(K, &cs, &ce));
  PetscCall(PetscCalloc2(re - rs, &dnz, re - rs, &onz));
  for (PetscInt b = 0; b < nb; b++)
    for (PetscInt r = 0; r < bn[b]; r++) {
      if (bdof[b][r] < rs || bdof[b][r] >= re) continue;
      for (PetscInt c = 0; c < bn[b]; c++) {
        if (bdof[b][c] >= cs && bdof[b][c] < ce) dnz[bdof[b][r] - rs]++;
        else onz[bdof[b][r] - rs]++;
      }
    }
  for (PetscInt r = 0; r < re - rs; r++) {
    dnz[r] = PetscMin(dnz[r], ce - cs);
    onz[r] = PetscMin(onz[r], N - (ce - cs));
  }
  PetscCall(MatCreate(comm, B));
  PetscCall(MatSetSizes(*B, re - rs, ce - cs, N, N));
  PetscCall(MatSetType(*B, MATAIJ));
  PetscCall(MatXAIJSetPreallocation(*B, 1, dnz, onz, NULL, NULL));
  PetscCall(MatSetOption(*B, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  for (PetscInt b = 0; b < nb; b++)
    for (PetscInt r = 0; r < bn[b]; r++)
      if (bdof[b][r] >= rs && bdof[b][r] < re) PetscCall(MatSetValues(*B, 1, &bdof[b][r], bn[b], bdof[b], bval[b] + r * bn[b], ADD_VALUES));
  PetscCall(MatAssemblyBegin(*B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*B, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree2(dnz, onz));
  PetscFunctionReturn(0);
}

/* see include/jointrom.h */
PetscErrorCode JRMatDenseAssemble(Mat A)
{
  PetscBool done;

  PetscFunctionBeginUser;
  PetscCall(MatAssembled(A, &done));
  if (!done) {
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  PetscFunctionReturn(0);
}
