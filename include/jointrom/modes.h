/* JRModes: mass-normalised modes and the mixed and static-correction bases */
#if !defined(JOINTROM_MODES_H)
#define JOINTROM_MODES_H

#include <jointrom/interface.h>

/* ------------------------------------------------------------------------------------------ */
/* JRModes: mass-normalised modes of K phi = omega^2 M phi (SLEPc, prefix modes_)              */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRModes *JRModes;
PETSC_EXTERN PetscErrorCode JRModesCreate(MPI_Comm, JRModes *);
PETSC_EXTERN PetscErrorCode JRModesSetOperators(JRModes, Mat, Mat);
PETSC_EXTERN PetscErrorCode JRModesSetNumber(JRModes, PetscInt);
PETSC_EXTERN PetscErrorCode JRModesSetRigidBasis(JRModes, PetscInt, Vec[]);
PETSC_EXTERN PetscErrorCode JRModesSetCoordinates(JRModes, Vec);
PETSC_EXTERN PetscErrorCode JRModesSetNaturalOrdering(JRModes, IS);
PETSC_EXTERN PetscErrorCode JRModesSetModel(JRModes, JRModel);
PETSC_EXTERN PetscErrorCode JRModesSetSignature(JRModes, PetscReal, PetscReal);
PETSC_EXTERN PetscErrorCode JRModesGetVecs(JRModes, Vec **);
PETSC_EXTERN PetscErrorCode JRModesGetNumRigid(JRModes, PetscInt *);
PETSC_EXTERN PetscErrorCode JRModesSetFromOptions(JRModes);
PETSC_EXTERN PetscErrorCode JRModesSolve(JRModes);
PETSC_EXTERN PetscErrorCode JRModesGetNumber(JRModes, PetscInt *);
PETSC_EXTERN PetscErrorCode JRModesGetEigenvalues(JRModes, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRModesGetRows(JRModes, PetscInt, const PetscInt[], PetscReal[]);
PETSC_EXTERN PetscErrorCode JRModesProject(JRModes, Mat, PetscReal[]);
PETSC_EXTERN PetscErrorCode JRModesView(JRModes, PetscViewer);
PETSC_EXTERN PetscErrorCode JRModesSetSaveDefault(JRModes, const char[]);
PETSC_EXTERN PetscErrorCode JRModesSetMixed(JRModes);
PETSC_EXTERN PetscErrorCode JRModesMix(JRModes, Mat, PetscInt, PetscInt, Vec[]);
PETSC_EXTERN PetscErrorCode JRModesSetInterface(JRModes, PetscInt, PetscInt, const PetscInt[], const PetscReal[], const PetscReal[]);
PETSC_EXTERN PetscErrorCode JRModesCheckBasis(JRModes);
PETSC_EXTERN PetscErrorCode JRModesGetBasisCheck(JRModes, PetscReal *, PetscReal *, PetscReal *, PetscInt *, PetscLogDouble *);
PETSC_EXTERN PetscErrorCode JRModesEnrich(JRModes, PetscInt, Vec[], const PetscReal[], PetscReal, PetscReal *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRModesEnrichEnd(JRModes);
PETSC_EXTERN PetscErrorCode JRModesGetAdapt(JRModes, PetscInt *, PetscReal *, PetscReal *, PetscInt *, PetscLogDouble *);
PETSC_EXTERN PetscErrorCode JRModesSaveAdaptation(JRModes, PetscInt, PetscReal, PetscBool);
PETSC_EXTERN PetscErrorCode JRModesGetReadAdaptation(JRModes, PetscInt *, PetscInt *, PetscReal *, PetscBool *);
PETSC_EXTERN PetscErrorCode JRModesReference(JRModes);
PETSC_EXTERN PetscErrorCode JRModesDestroy(JRModes *);

#endif
