/* JRReduce: reduced-order joints, the first and the second reduction; saved reduced models */
#if !defined(JOINTROM_REDUCE_H)
#define JOINTROM_REDUCE_H

#include <jointrom/hbm.h>

/* Reduced-order joints: second reduction (TAO fit of m elements per joint, options -rom_*), saved models */
/* The case a reduced model is for: the response of the mode of interest at each level, by energy balance at resonance */
typedef struct {
  PetscInt         nlev;
  const PetscReal *level;  /* excitation levels [N] */
  PetscReal        force;  /* |mode . force shape| per unit level */
  PetscReal        damp;   /* linear damping energy per cycle / (modal amplitude)^2 */
  const PetscReal *ujoint; /* each joint's (average) motion per unit modal amplitude [m] */
} JRROMCase;
/* The second reduction's fit options (prefix rom_), read once by JRROMFitSetFromOptions */
typedef struct {
  PetscReal fr[3];   /* -rom_fit_fractions */
  PetscReal efrom;   /* -rom_fit_energy_from */
  PetscBool refine;  /* -rom_fit_refine */
  PetscReal perturb; /* -rom_fit_perturb */
  PetscInt  ns;      /* -rom_fit_samples */
  PetscReal wcase;   /* -rom_fit_case_weight */
  PetscReal wtotal;  /* -rom_fit_total_weight */
  PetscReal wgross;  /* -rom_fit_gross_weight */
  PetscReal wstiff;  /* -rom_fit_stiffness_weight */
  PetscInt  npass;   /* -rom_fit_normal_passes */
  PetscInt  jmotion; /* -rom_joint_motion: 0 mean, 1 linear, 2 mode */
  PetscBool resid;   /* -rom_joint_residual: the members' stuck springs kept on their motion outside the joints' fields */
  PetscBool search;  /* -rom_fit_search */
  PetscInt  mmax;    /* -rom_fit_elements_max: a joint's elements grown to this while its loops fit worse than looptol (0: off) */
  PetscReal looptol; /* -rom_fit_loop_tol */
} JRROMFit;
PETSC_EXTERN PetscErrorCode JRROMFitSetFromOptions(MPI_Comm, JRROMFit *);
PETSC_EXTERN PetscErrorCode JRROMReduce(MPI_Comm, const JRElements *, PetscInt, const PetscReal[], const JRROMCase *, const JRROMFit *, const char[], PetscBool, PetscBool, JRElements *);
PETSC_EXTERN PetscErrorCode JRROMSave(JRModel, const JRElements *, PetscReal, PetscInt, const char[]);
PETSC_EXTERN PetscErrorCode JRROMLoad(JRModel, const char[], JRElements *, PetscReal *, PetscInt *);

/* ------------------------------------------------------------------------------------------ */
/* JRReduce: reduced-order joints, the first and the second reduction (prefix rom_)            */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRReduce *JRReduce;
PETSC_EXTERN PetscErrorCode JRReduceCreate(MPI_Comm, JRReduce *);
PETSC_EXTERN PetscErrorCode JRReduceSetFromOptions(JRReduce);
PETSC_EXTERN PetscErrorCode JRReduceGetRequest(JRReduce, PetscBool *, PetscInt *, PetscInt *, const char **, const char **);
PETSC_EXTERN PetscErrorCode JRReduceSetCase(JRReduce, PetscReal, PetscReal, PetscInt, const PetscReal[]);
PETSC_EXTERN PetscErrorCode JRReduceSetExcitation(JRReduce, PetscInt, PetscInt, const PetscInt[]);
PETSC_EXTERN PetscErrorCode JRReduceSetOutput(JRReduce, const char[], PetscBool);
PETSC_EXTERN PetscErrorCode JRReduceAssignJoints(JRReduce, JRModel, JRElements *, const PetscInt[]);
PETSC_EXTERN PetscErrorCode JRReduceSetUp(JRReduce, JRModel, JRHBM, JRElements *, JRElements *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRReduceCreateHBM(JRReduce, JRModel, JRHBM, PetscBool, JRElements *, JRHBM *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRReduceSave(JRReduce, JRModel, const JRElements *);
PETSC_EXTERN PetscErrorCode JRReduceLoad(JRReduce, JRModel, JRElements *);
PETSC_EXTERN PetscErrorCode JRReduceGetStiffnessCorrection(JRReduce, PetscReal *);
PETSC_EXTERN PetscErrorCode JRReduceView(JRReduce, PetscViewer);
PETSC_EXTERN PetscErrorCode JRReduceDestroy(JRReduce *);

#endif
