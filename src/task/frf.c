/*
   -task frf: frequency-response curves of a structure with contact elements.
   model (-model_type matrices: K, M, C and elements from files) -> modes -> harmonic balance
   (-hbm_*) -> continuation over the levels (-cont_*, -frf_*) -> BASE.h5, BASE.csv, BASE.png.
*/
#include <jointrom.h>

PetscErrorCode JRTaskFRF(MPI_Comm comm)
{
  JRModel     model;
  JRHBM       hbm;
  JRCont      cont;
  const char *damping;
  PetscInt    nm, H, n;

  PetscFunctionBeginUser;
  PetscCall(JRModelCreate(comm, &model));
  PetscCall(JRModelSetFromOptions(model));
  PetscCall(JRModelSetUp(model));
  PetscCall(JRHBMCreate(comm, &hbm));
  PetscCall(JRHBMSetModel(hbm, model));
  PetscCall(JRHBMSetFromOptions(hbm));
  PetscCall(JRContCreate(comm, &cont));
  PetscCall(JRContSetHBM(cont, hbm));
  PetscCall(JRContSetFromOptions(cont));
  PetscCall(JRHBMSetUp(hbm));
  PetscCall(JRHBMGetSizes(hbm, &nm, &H, &n));
  PetscCall(JRHBMGetDampingDescription(hbm, &damping));
  {
    PetscInt         nmod;
    const PetscReal *om;
    PetscCall(JRHBMGetModalFrequencies(hbm, &nmod, &om));
    if (nmod) PetscCall(PetscPrintf(comm, "frf: %" PetscInt_FMT " modes (%.6g .. %.6g Hz), %" PetscInt_FMT " harmonics + mean, %" PetscInt_FMT " unknowns; damping: %s\n", nm, (double)(om[0] / (2 * PETSC_PI)), (double)(om[nmod - 1] / (2 * PETSC_PI)), H, n, damping));
    else PetscCall(PetscPrintf(comm, "frf: %" PetscInt_FMT " physical coordinates, %" PetscInt_FMT " harmonics + mean, %" PetscInt_FMT " unknowns; damping: %s\n", nm, H, n, damping));
  }
  PetscCall(JRContSolve(cont));
  PetscCall(JRContWrite(cont));
  PetscCall(JRContDestroy(&cont));
  PetscCall(JRHBMDestroy(&hbm));
  PetscCall(JRModelDestroy(&model));
  PetscFunctionReturn(0);
}
