/* JRPreload: bolt preload, static frictionless contact analysis */
#if !defined(JOINTROM_PRELOAD_H)
#define JOINTROM_PRELOAD_H

#include <jointrom/model.h>

/* ------------------------------------------------------------------------------------------ */
/* JRPreload: bolt preload, static frictionless contact analysis (prefix preload_)              */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRPreload *JRPreload;
typedef enum {
  JR_PRELOAD_PENALTY,
  JR_PRELOAD_AUGMENTED
} JRPreloadMethod;
PETSC_EXTERN const char *const JRPreloadMethods[];
typedef enum {
  JR_PRELOAD_SUPPORT_MINIMAL, /* 3-2-1: statically determinate */
  JR_PRELOAD_SUPPORT_CLAMP,   /* the end face x = 0 fixed ("fix-free") */
  JR_PRELOAD_SUPPORT_NONE     /* only JRPreloadAddSupport() */
} JRPreloadSupport;
PETSC_EXTERN const char *const JRPreloadSupports[];
/* Solvers of the contact problem (-preload_solver), registered types */
typedef const char *JRPreloadSolverType;
#define JRPRELOADCONDENSED "condensed" /* one factorisation of K, Newton on the interface's dense flexibility */
#define JRPRELOADFULL      "full"      /* Newton on all DOFs, a factorisation per change of the closed set */
PETSC_EXTERN PetscFunctionList JRPreloadSolverList;
PETSC_EXTERN PetscErrorCode JRPreloadSolverRegister(const char[], PetscErrorCode (*)(JRPreload));
PETSC_EXTERN PetscErrorCode JRPreloadSolverRegisterAll(void);
typedef struct {
  PetscInt  pairs, in_contact, bolts, newton, updates, factorisations;
  PetscReal total_force, bolt_force_sum;        /* sum of the pairs' normal loads, of the pretensions [N] */
  PetscReal contact_area, interface_area;       /* [m^2] */
  PetscReal peak_pressure, peak_force, gap_max; /* [Pa], [N], [m] */
  PetscReal penalty, max_penetration, time;     /* [N/m^3], [m], [s] */
  PetscBool loaded;                             /* read with -preload_load instead of solved */
} JRPreloadSummary;
PETSC_EXTERN PetscErrorCode JRPreloadCreate(MPI_Comm, JRPreload *);
PETSC_EXTERN PetscErrorCode JRPreloadSetModel(JRPreload, JRModel);
PETSC_EXTERN PetscErrorCode JRPreloadSetForces(JRPreload, PetscInt, const PetscReal[]);
PETSC_EXTERN PetscErrorCode JRPreloadSetExternalForce(JRPreload, Vec);
PETSC_EXTERN PetscErrorCode JRPreloadAddSupport(JRPreload, PetscInt, const PetscReal[3]);
PETSC_EXTERN PetscErrorCode JRPreloadSetFromOptions(JRPreload);
PETSC_EXTERN PetscErrorCode JRPreloadSetSolverType(JRPreload, JRPreloadSolverType);
PETSC_EXTERN PetscErrorCode JRPreloadGetSolverType(JRPreload, JRPreloadSolverType *);
PETSC_EXTERN PetscErrorCode JRPreloadSolve(JRPreload);
PETSC_EXTERN PetscErrorCode JRPreloadGetResults(JRPreload, PetscInt *, const PetscReal **, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRPreloadGetN0(JRPreload, PetscReal, PetscReal[]);
PETSC_EXTERN PetscErrorCode JRPreloadGetSolution(JRPreload, Vec *);
PETSC_EXTERN PetscErrorCode JRPreloadGetSummary(JRPreload, JRPreloadSummary *);
PETSC_EXTERN PetscErrorCode JRPreloadWrite(JRPreload, const char[], PetscBool);
PETSC_EXTERN PetscErrorCode JRPreloadView(JRPreload, PetscViewer);
PETSC_EXTERN PetscErrorCode JRPreloadDestroy(JRPreload *);

#endif
