/* JRInterface: the node-to-node interface, one friction element per facing node pair */
#if !defined(JOINTROM_INTERFACE_H)
#define JOINTROM_INTERFACE_H

#include <jointrom/preload.h>

/* The node-to-node interface: one friction element per facing node pair (options -interface_*) */
typedef struct _p_JRInterface *JRInterface;
PETSC_EXTERN PetscErrorCode JRInterfaceCreate(MPI_Comm, JRInterface *);
PETSC_EXTERN PetscErrorCode JRInterfaceSetOptionsPrefix(JRInterface, const char[]);
PETSC_EXTERN PetscErrorCode JRInterfaceSetFromOptions(JRInterface);
PETSC_EXTERN PetscErrorCode JRInterfaceSetUp(JRInterface, JRModel, JRPreload);
PETSC_EXTERN PetscErrorCode JRInterfaceGetElements(JRInterface, const JRElements **, const PetscInt **);
PETSC_EXTERN PetscErrorCode JRInterfaceView(JRInterface, PetscViewer);
PETSC_EXTERN PetscErrorCode JRInterfaceDestroy(JRInterface *);

#endif
