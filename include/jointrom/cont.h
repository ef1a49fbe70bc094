/* JRCont: frequency-response curves by continuation, several force levels */
#if !defined(JOINTROM_CONT_H)
#define JOINTROM_CONT_H

#include <jointrom/reduce.h>

/* ------------------------------------------------------------------------------------------ */
/* JRCont: frequency-response curves by continuation (thesis 2.4.2-2.4.3), several force levels */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRCont *JRCont;
typedef const char       *JRContType;
#define JRCONTNATURAL   "natural"   /* natural-parameter: step in frequency (2.4.2) */
#define JRCONTARCLENGTH "arclength" /* pseudo-arclength: passes turning points (2.4.3) */
/* The arclength type's constraint (-cont_constraint): orthogonal to the tangent, or the sphere (2.28) */
typedef enum {
  JR_CONT_PSEUDO,
  JR_CONT_SPHERE
} JRContConstraint;
PETSC_EXTERN const char *const JRContConstraints[];

PETSC_EXTERN PetscFunctionList JRContList;
PETSC_EXTERN PetscErrorCode JRContRegister(const char[], PetscErrorCode (*)(JRCont));
PETSC_EXTERN PetscErrorCode JRContRegisterAll(void);

PETSC_EXTERN PetscErrorCode JRContCreate(MPI_Comm, JRCont *);
PETSC_EXTERN PetscErrorCode JRContSetType(JRCont, JRContType);
PETSC_EXTERN PetscErrorCode JRContGetType(JRCont, JRContType *);
PETSC_EXTERN PetscErrorCode JRContSetHBM(JRCont, JRHBM);
PETSC_EXTERN PetscErrorCode JRContGetHBM(JRCont, JRHBM *);
PETSC_EXTERN PetscErrorCode JRContSetFromOptions(JRCont);
PETSC_EXTERN PetscErrorCode JRContSetStepBounds(JRCont, PetscReal, PetscReal);
PETSC_EXTERN PetscErrorCode JRContSetRange(JRCont, PetscReal, PetscReal);
PETSC_EXTERN PetscErrorCode JRContGetRange(JRCont, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRContSetOutputBase(JRCont, const char[]);
PETSC_EXTERN PetscErrorCode JRContSetLevels(JRCont, PetscInt, const PetscReal[]);
PETSC_EXTERN PetscErrorCode JRContCheckComplete(JRCont);
PETSC_EXTERN PetscErrorCode JRContGetLevelComplete(JRCont, PetscInt, PetscBool *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRContSolve(JRCont);
PETSC_EXTERN PetscErrorCode JRContSetQuiet(JRCont, PetscBool);
PETSC_EXTERN PetscErrorCode JRContSetStability(JRCont, PetscBool);
PETSC_EXTERN PetscErrorCode JRContGetNumLevels(JRCont, PetscInt *);
PETSC_EXTERN PetscErrorCode JRContGetBranch(JRCont, PetscInt, PetscInt *, const PetscReal **, const PetscReal **, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRContGetPeak(JRCont, PetscInt, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRContGetLevel(JRCont, PetscInt, PetscReal *);
PETSC_EXTERN PetscErrorCode JRContGetPeakSolution(JRCont, PetscInt, Vec);
PETSC_EXTERN PetscErrorCode JRContGetPeakStates(JRCont, PetscInt, const JRContactState **);
PETSC_EXTERN PetscErrorCode JRContGetDamping(JRCont, PetscInt, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRContGetLevelStats(JRCont, PetscInt, PetscReal *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRContGetStabilitySeconds(JRCont, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRContGetStability(JRCont, PetscInt, const PetscInt **, const PetscReal **, PetscInt *, const PetscReal **, PetscInt *, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRContDestroy(JRCont *);

#endif
