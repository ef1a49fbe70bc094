/* JRNLModes: nonlinear modes (EPMC backbones) */
#if !defined(JOINTROM_NLMODES_H)
#define JOINTROM_NLMODES_H

#include <jointrom/cont.h>

/* ------------------------------------------------------------------------------------------ */
/* JRNLModes: nonlinear modes by the extended periodic motion concept (EPMC), backbones of      */
/* frequency and damping ratio against amplitude, options -nlm_*                               */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRNLModes *JRNLModes;
PETSC_EXTERN PetscErrorCode JRNLModesCreate(MPI_Comm, JRNLModes *);
PETSC_EXTERN PetscErrorCode JRNLModesSetHBM(JRNLModes, JRHBM);
PETSC_EXTERN PetscErrorCode JRNLModesSetFromOptions(JRNLModes);
PETSC_EXTERN PetscErrorCode JRNLModesGetOutputBase(JRNLModes, const char **);
PETSC_EXTERN PetscErrorCode JRNLModesSetOutput(JRNLModes, const char[], PetscBool);
PETSC_EXTERN PetscErrorCode JRNLModesSetOptionsPrefix(JRNLModes, const char[]);
PETSC_EXTERN PetscErrorCode JRNLModesSetRange(JRNLModes, PetscReal, PetscReal);
PETSC_EXTERN PetscErrorCode JRNLModesGetRange(JRNLModes, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRNLModesSetUp(JRNLModes);
PETSC_EXTERN PetscErrorCode JRNLModesSolve(JRNLModes);
PETSC_EXTERN PetscErrorCode JRNLModesGetBackbone(JRNLModes, PetscInt *, const PetscReal **, const PetscReal **, const PetscReal **, const PetscReal **, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRNLModesGetStats(JRNLModes, PetscReal *, PetscInt *, PetscBool *);
PETSC_EXTERN PetscErrorCode JRNLModesInterpolate(JRNLModes, PetscReal, PetscReal *, PetscReal *, PetscReal *, PetscBool *);
PETSC_EXTERN PetscErrorCode JRNLModesWrite(JRNLModes);
PETSC_EXTERN PetscErrorCode JRNLModesView(JRNLModes, PetscViewer);
PETSC_EXTERN PetscErrorCode JRNLModesDestroy(JRNLModes *);

#endif
