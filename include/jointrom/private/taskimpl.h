/* Private: what the tasks' drivers share (src/task/). */
#if !defined(JOINTROM_TASKIMPL_H)
#define JOINTROM_TASKIMPL_H

#include <jointrom.h>

/* src/task/frf.c: the pipeline of -task frf (model, preload, interface, modes, harmonic balance), ending in the curves
   or, with nlmodes, in the backbone of a nonlinear mode */
PETSC_INTERN PetscErrorCode JRTaskFRFPipeline(MPI_Comm, PetscBool);
/* src/task/nlmodes.c: the backbone on the pipeline's harmonic balance, its outputs and summary */
PETSC_INTERN PetscErrorCode JRTaskNLModesSolve(MPI_Comm, JRNLModes, JRHBM);
PETSC_INTERN PetscErrorCode JRTaskNLModesCheckComplete(MPI_Comm, JRNLModes);

#endif
