/*
   jointrom: reduced-order models of bolted joints by harmonic balance with friction contact elements.
   Public API. Every object follows the PETSc life cycle
     JRXxxCreate -> JRXxxSetType -> JRXxxSetFromOptions -> JRXxxSetUp -> JRXxxEvaluate/Solve -> JRXxxView -> JRXxxDestroy.
   Equation numbers "(3.17)" refer to the thesis in ../shared/thesis-reduced-order-bolted-joints.txt.

   Conventions (fixed here, once):
   - Units are SI throughout: N, m, kg, s, rad.
   - A periodic signal with H harmonics and the mean is stored as nc = 2H+1 real coefficients
       x(theta) = x0 + sum_{h=1..H} [ xs_h sin(h theta) + xc_h cos(h theta) ],   theta = omega t   (2.7)
     in the order [x0, xs_1, xc_1, ..., xs_H, xc_H].
   - Element batches are structure-of-arrays: coefficient k of element e is X[k*n + e] (an n x nc
     column-major matrix); a derivative dY_k/dX_m of element e is D[(k*nc + m)*n + e].
   - Tangential relative motion u, normal relative motion v; positive v presses the surfaces
     together, n = max(0, n0 + kn v) (3.32).
*/
#if !defined(JOINTROM_H)
#define JOINTROM_H

#include <jointrom/post.h>

/* Driver tasks */
PETSC_EXTERN PetscErrorCode JRTaskElement(MPI_Comm);
PETSC_EXTERN PetscErrorCode JRTaskFRF(MPI_Comm);
PETSC_EXTERN PetscErrorCode JRTaskCompare(MPI_Comm);
PETSC_EXTERN PetscErrorCode JRTaskNLModes(MPI_Comm);
PETSC_EXTERN PetscErrorCode JRTaskModes(MPI_Comm);
PETSC_EXTERN PetscErrorCode JRTaskPreload(MPI_Comm);

#endif
