/* JRHBM: harmonic balance in modal coordinates; EPMC and Hill stability on the same unknowns */
#if !defined(JOINTROM_HBM_H)
#define JOINTROM_HBM_H

#include <jointrom/modes.h>

/* ------------------------------------------------------------------------------------------ */
/* JRHBM: harmonic balance in modal coordinates (thesis 2.18, H harmonics + mean), SNES hbm_     */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRHBM *JRHBM;
typedef enum {
  JR_HBM_JACOBIAN_ANALYTIC,
  JR_HBM_JACOBIAN_FD
} JRHBMJacobianType;
PETSC_EXTERN const char *const JRHBMJacobianTypes[];
typedef enum {
  JR_HBM_BASIS_FREE,  /* the modes of K: the interface held by the bolts only */
  JR_HBM_BASIS_STUCK, /* the modes of K plus every element in contact at rest stuck */
  JR_HBM_BASIS_MIXED  /* Ritz vectors of the stuck structure in the span of the stuck and free-interface modes */
} JRHBMBasis;
PETSC_EXTERN const char *const JRHBMBases[];
/* -rom_joint_motion: how a joint's members move in the first reduction (4.4) */
typedef enum {
  JR_JOINT_MOTION_MEAN,   /* the joint's mean motion (the thesis) */
  JR_JOINT_MOTION_LINEAR, /* a linear field over the members' positions (JRElements pos) */
  JR_JOINT_MOTION_MODE,   /* ... and over their motions in the stuck mode of interest (JRElements phi) */
  JR_JOINT_MOTION_SHAPES  /* tangential: over their positions and tangential motions in the stuck mode of interest and
                             in released modes; normal: over their normal motion in it (JRElements pos, phi, phir) */
} JRJointMotion;
PETSC_EXTERN const char *const JRJointMotions[];

PETSC_EXTERN PetscErrorCode JRHBMCreate(MPI_Comm, JRHBM *);
PETSC_EXTERN PetscErrorCode JRHBMSetModel(JRHBM, JRModel);
PETSC_EXTERN PetscErrorCode JRHBMSetElements(JRHBM, const JRElements *);
PETSC_EXTERN PetscErrorCode JRHBMGetElements(JRHBM, const JRElements **);
PETSC_EXTERN PetscErrorCode JRHBMSetFromOptions(JRHBM);
PETSC_EXTERN PetscErrorCode JRHBMSetUp(JRHBM);
PETSC_EXTERN PetscErrorCode JRHBMGetSizes(JRHBM, PetscInt *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMGetSolveSize(JRHBM, PetscInt *, const char **);
PETSC_EXTERN PetscErrorCode JRHBMExpand(JRHBM, PetscReal, Vec, Vec);
PETSC_EXTERN PetscErrorCode JRHBMSetForceLevel(JRHBM, PetscReal);
PETSC_EXTERN PetscErrorCode JRHBMGetModalFrequencies(JRHBM, PetscInt *, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRHBMComputeResidual(JRHBM, PetscReal, Vec, Vec);
PETSC_EXTERN PetscErrorCode JRHBMComputeJacobian(JRHBM, PetscReal, Vec, Mat, Vec);
PETSC_EXTERN PetscErrorCode JRHBMJacobianSetPoint(JRHBM, PetscReal, Vec, Mat, Vec);
PETSC_EXTERN PetscErrorCode JRHBMJacobianMult(JRHBM, Mat, const PetscScalar *, PetscScalar *);
PETSC_EXTERN PetscErrorCode JRHBMJacobianForm(JRHBM, Mat, PetscScalar *, PetscInt);
PETSC_EXTERN PetscErrorCode JRHBMCreateVecs(JRHBM, Vec *, Mat *);
PETSC_EXTERN PetscErrorCode JRHBMSolve(JRHBM, PetscReal, Vec, PetscInt *, PetscBool *);
PETSC_EXTERN PetscErrorCode JRHBMSolveResidual(JRHBM, PetscReal, Vec, PetscInt *, PetscBool *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMResidualNorm(JRHBM, Vec, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMGetResidualTolerance(JRHBM, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMLinearSolution(JRHBM, PetscReal, Vec);
PETSC_EXTERN PetscErrorCode JRHBMGetSNES(JRHBM, SNES *);
PETSC_EXTERN PetscErrorCode JRHBMForgetFactors(JRHBM);
PETSC_EXTERN PetscErrorCode JRHBMGetReplicated(JRHBM, PetscBool *);
PETSC_EXTERN PetscErrorCode JRHBMSetLocal(JRHBM, PetscBool);
PETSC_EXTERN PetscErrorCode JRHBMGetJacobianType(JRHBM, JRHBMJacobianType *);
PETSC_EXTERN PetscErrorCode JRHBMGetElementTime(JRHBM, PetscLogDouble *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMGetOutputs(JRHBM, PetscInt *, const PetscInt **);
PETSC_EXTERN PetscErrorCode JRHBMResponse(JRHBM, Vec, PetscReal[], PetscReal[], PetscReal[]);
PETSC_EXTERN PetscErrorCode JRHBMEnergy(JRHBM, PetscReal, Vec, PetscReal *, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMContactStates(JRHBM, Vec, PetscInt[4]);
PETSC_EXTERN PetscErrorCode JRHBMElementStates(JRHBM, Vec, JRContactState[]);
PETSC_EXTERN PetscErrorCode JRHBMElementDissipation(JRHBM, Vec, PetscReal[]);
PETSC_EXTERN PetscErrorCode JRHBMKineticEnergy(JRHBM, PetscReal, Vec, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMSetExcitationDof(JRHBM, PetscInt, PetscInt, const PetscInt[]);
PETSC_EXTERN PetscErrorCode JRHBMSetOutputPoints(JRHBM, PetscInt, const PetscReal[], PetscInt);
PETSC_EXTERN PetscErrorCode JRHBMGetOutputPoints(JRHBM, const PetscReal **, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMMatchStickFrequency(JRHBM, PetscInt, PetscReal, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMStuckModeMotion(JRHBM, PetscInt, PetscReal[], PetscReal[]);
PETSC_EXTERN PetscErrorCode JRHBMReleasedModeMotion(JRHBM, PetscInt, const PetscReal[], PetscReal[], PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMStuckMode(JRHBM, PetscInt, PetscReal *, PetscReal[]);
PETSC_EXTERN PetscErrorCode JRHBMStuckSpringEnergy(JRHBM, const PetscReal[], PetscReal[]);
PETSC_EXTERN PetscErrorCode JRHBMStuckModeBalance(JRHBM, PetscInt, PetscReal *, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMSetModes(JRHBM, JRHBM);
PETSC_EXTERN PetscErrorCode JRHBMGetModes(JRHBM, JRModes *);
PETSC_EXTERN PetscErrorCode JRHBMEnrichBasis(JRHBM, PetscInt, Vec[], PetscReal, PetscReal *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMSetBasis(JRHBM, JRHBMBasis);
PETSC_EXTERN PetscErrorCode JRHBMSetJointMotion(JRHBM, JRJointMotion);
PETSC_EXTERN PetscErrorCode JRHBMSetJointResidual(JRHBM, PetscBool);
PETSC_EXTERN PetscErrorCode JRHBMSetOptionsPrefix(JRHBM, const char[]);
PETSC_EXTERN PetscErrorCode JRHBMGetOptionsPrefix(JRHBM, const char **);
PETSC_EXTERN PetscErrorCode JRHBMSetModesFile(JRHBM, const char[]);
PETSC_EXTERN PetscErrorCode JRHBMGetBasis(JRHBM, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMGetBasisCheck(JRHBM, PetscReal *, PetscReal *, PetscReal *, PetscInt *, PetscLogDouble *);
PETSC_EXTERN PetscErrorCode JRHBMStickFrequencies(JRHBM, PetscInt *, PetscReal[]);
PETSC_EXTERN PetscErrorCode JRHBMGetDampingDescription(JRHBM, const char **);
PETSC_EXTERN PetscErrorCode JRHBMView(JRHBM, PetscViewer);
PETSC_EXTERN PetscErrorCode JRHBMDestroy(JRHBM *);
/* the extended periodic motion concept's autonomous system (src/hbm/epmc.c): unknowns [a | w | xi] */
PETSC_EXTERN PetscErrorCode JRHBMCheckEPMC(JRHBM);
PETSC_EXTERN PetscErrorCode JRHBMSetEPMC(JRHBM, PetscInt, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMGetEPMCMode(JRHBM, PetscReal *, const PetscReal **, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMComputeEPMC(JRHBM, PetscReal, Vec, Vec, Mat);
PETSC_EXTERN PetscErrorCode JRHBMEPMCWork(JRHBM, PetscReal, PetscReal, Vec, PetscReal *);
/* Stability by Hill's method (src/hbm/hill.c): which 2 nm of the 2 nm (2H + 1) exponents are the physical ones */
typedef enum {
  JR_HILL_SELECT_VECTOR, /* eigenvectors centred on the mean harmonic (symmetry criterion) */
  JR_HILL_SELECT_IMAG    /* |Im lambda| <= w / 2 (the fundamental strip) */
} JRHillSelect;
PETSC_EXTERN const char *const JRHillSelects[];
PETSC_EXTERN PetscErrorCode JRHBMFloquet(JRHBM, PetscReal, Vec, JRHillSelect, PetscInt, PetscInt *, PetscReal[], PetscReal[], PetscReal *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMHillSupported(JRHBM, PetscBool *);
PETSC_EXTERN PetscErrorCode JRHBMFloquetTime(JRHBM, PetscReal, Vec, PetscInt, PetscInt *, PetscReal[], PetscReal[], PetscReal *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMSetFloquetFast(JRHBM, PetscReal);
PETSC_EXTERN PetscErrorCode JRHBMFloquetTimeSupported(JRHBM, PetscBool *);
PETSC_EXTERN PetscErrorCode JRHBMSetFloquetLowRank(JRHBM, PetscInt);
PETSC_EXTERN PetscErrorCode JRHBMGetFloquetLowRankRows(JRHBM, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMSetFloquetUnread(JRHBM, PetscBool);
PETSC_EXTERN PetscErrorCode JRHBMGetFloquetUnreadSlips(JRHBM, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMSetFloquetWoodbury(JRHBM, PetscBool);
PETSC_EXTERN PetscErrorCode JRHBMGetFloquetWoodburyUpdates(JRHBM, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMFloquetTimePoints(JRHBM, PetscInt, const PetscReal[], const PetscScalar[], PetscInt, const PetscBool[], PetscInt, PetscReal[], PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMJacobianSign(JRHBM, PetscReal, Vec, PetscInt *);
/* What decides a point's stability (src/hbm/dissipative.c) */
typedef enum {
  JR_STABILITY_DISSIPATIVE, /* incrementally dissipative at the point: stable, no eigenproblem */
  JR_STABILITY_HILL,        /* smooth elements only: Hill's method, exact up to truncation */
  JR_STABILITY_HILL_HYSTERETIC, /* friction elements changing state: Hill's method indicates, it does not decide */
  JR_STABILITY_TIME         /* the same points decided by the monodromy matrix in time (JRHBMFloquetTime) */
} JRStabilityVerdict;
PETSC_EXTERN PetscErrorCode JRHBMStabilityVerdict(JRHBM, Vec, PetscBool, JRStabilityVerdict *);
PETSC_EXTERN PetscErrorCode JRHBMStabilityCheap(JRHBM, PetscBool *, PetscInt *);

#endif
