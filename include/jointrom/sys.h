/* Package set-up, log stages and events, and the small utilities every stage uses: CSV tables, matrix files,
   atomic output files, dense Newton, aligned memory, plots, user errors, option checks */
#if !defined(JOINTROM_SYS_H)
#define JOINTROM_SYS_H

#include <petscsys.h>
#include <petscviewer.h>
#include <petscmat.h>
#include <petscsnes.h>
#include <petscdm.h>

#define JR_VERSION_MAJOR 0
#define JR_VERSION_MINOR 1
PETSC_EXTERN PetscErrorCode JRInitializePackage(void);
PETSC_EXTERN PetscErrorCode JRFinalizePackage(void);

/* Log stages, one per pipeline stage, and events, one per costly phase (see -log_view; src/sys/log.c) */
PETSC_EXTERN PetscLogStage  JR_StageModel, JR_StagePreload, JR_StageInterface, JR_StageModes, JR_StageReduce, JR_StageSolve, JR_StagePost;
PETSC_EXTERN PetscLogEvent  JR_InterfaceSetUp, JR_ReduceJoints, JR_ReduceSelect, JR_ReduceFit, JR_ReduceHBM, JR_Verify, JR_NLModesSolve;
PETSC_EXTERN PetscErrorCode JRLogRegister(void);
PETSC_EXTERN PetscClassId  JR_CONTACT_CLASSID, JR_MODEL_CLASSID, JR_HBM_CLASSID;
PETSC_EXTERN PetscLogEvent JR_ContactEval, JR_ContactSetUp, JR_ContactLoop, JR_ModelLoad, JR_ModesSolve, JR_ModesStatic, JR_PreloadSetUp, JR_PreloadSolve, JR_HBMResidual, JR_HBMJacobian, JR_HBMSolve, JR_ContStep, JR_DenseLU, JR_DenseGMRES;
PETSC_EXTERN PetscLogEvent JR_ContTangent, JR_ContChord, JR_ContPeak; /* the continuation's tangents, chord checks, peak refinements */
PETSC_EXTERN PetscLogEvent JR_HBMHill; /* Floquet exponents by Hill's method (src/hbm/hill.c) */
PETSC_EXTERN PetscLogEvent JR_HBMFloquetTime; /* Floquet exponents from the monodromy matrix (src/hbm/floquet.c) */

/* ------------------------------------------------------------------------------------------ */
/* Small utilities                                                                            */
/* ------------------------------------------------------------------------------------------ */
/* CSV tables with a header line; columns looked up by name */
typedef struct _p_JRTable *JRTable;
PETSC_EXTERN PetscErrorCode JRTableRead(MPI_Comm, const char[], JRTable *);
PETSC_EXTERN PetscErrorCode JRTableGetSize(JRTable, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRTableGetColumn(JRTable, const char[], PetscBool, PetscReal, PetscReal[]);
PETSC_EXTERN PetscErrorCode JRTableHasColumn(JRTable, const char[], PetscBool *);
PETSC_EXTERN PetscErrorCode JRTableGetString(JRTable, const char[], PetscInt, const char **);
PETSC_EXTERN PetscErrorCode JRTableGetLine(JRTable, PetscInt, PetscInt *);
PETSC_EXTERN PetscErrorCode JRTableGetHeader(JRTable, PetscInt, const char **);
PETSC_EXTERN PetscErrorCode JRTableGetFileName(JRTable, const char **);
PETSC_EXTERN PetscErrorCode JRTableDestroy(JRTable *);

/* Matrices and vectors from files: .mtx (Matrix Market), .bin (PETSc binary), .h5 (MATLAB v7.3 sparse) */
PETSC_EXTERN PetscErrorCode JRMatLoadFile(MPI_Comm, const char[], const char[], Mat *);
PETSC_EXTERN PetscErrorCode JRMatSaveFile(Mat, const char[], const char[]);
PETSC_EXTERN PetscErrorCode JRVecLoadFile(MPI_Comm, const char[], PetscInt, PetscReal[]);
PETSC_EXTERN PetscErrorCode JRFileCheckHDF5(MPI_Comm, const char[], const char[], const char[], const char[]);

/* The nearest of a set of points to a query point within a tolerance (src/sys/nearest.c) */
typedef struct _p_JRNearest *JRNearest;
PETSC_EXTERN PetscErrorCode JRNearestCreate(PetscInt, const PetscReal[], JRNearest *);
PETSC_EXTERN PetscErrorCode JRNearestFind(JRNearest, const PetscReal[3], PetscReal, PetscInt *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRNearestDestroy(JRNearest *);

/* Write a file atomically: open a temporary beside it, rename on close. Temporary names come from
   JRFileTempName (registered: removed if the run is stopped by SIGTERM, SIGINT or SIGHUP) and are
   released by JRFileTempDone once renamed or removed (JRFileRename, JRFileCommit do it) */
PETSC_EXTERN PetscErrorCode JRFileTempName(MPI_Comm, const char[], char[], size_t);
PETSC_EXTERN PetscErrorCode JRFileTempDone(const char[]);
PETSC_EXTERN PetscErrorCode JRFileRename(MPI_Comm, const char[], const char[]);
PETSC_EXTERN PetscErrorCode JRFileOpenTemp(MPI_Comm, const char[], FILE **, char[], size_t);
PETSC_EXTERN PetscErrorCode JRFileCommit(MPI_Comm, FILE **, const char[], const char[]);
PETSC_EXTERN PetscErrorCode JRViewerHDF5WriteRank0(MPI_Comm, PetscViewer, const char[], PetscInt, PetscInt, const PetscReal[], const PetscInt[]);

/* Newton's method for small dense systems on one rank: LAPACK LU, backtracking (src/hbm/newtondense.c); the
   default of the harmonic-balance and continuation solvers (-hbm_snes_type) */
#define SNESNEWTONDENSE "newtondense"
PETSC_EXTERN PetscErrorCode SNESCreate_NewtonDense(SNES);
PETSC_EXTERN PetscErrorCode JRDenseSolve(PetscInt, const PetscScalar *, PetscInt, PetscScalar *, PetscBLASInt *, PetscScalar *, PetscBool *);
/* A dense solver for a sequence of nearby matrices: GMRES preconditioned by an earlier one's LU, a new LU when it
   would cost more (src/hbm/newtondense.c) */
typedef struct _n_JRDenseLU *JRDenseLU;
PETSC_EXTERN PetscErrorCode JRDenseLUCreate(JRDenseLU *);
PETSC_EXTERN PetscErrorCode JRDenseLUDestroy(JRDenseLU *);
PETSC_EXTERN PetscErrorCode JRDenseLUForget(JRDenseLU);
PETSC_EXTERN PetscErrorCode JRDenseLUSolve(JRDenseLU, PetscInt, const PetscScalar *, PetscInt, PetscReal, PetscScalar *, PetscBool *);
/* A matrix by its products y = A x, and (form, may be NULL) a function that writes it into a dense array (leading
   dimension given) when it is factored */
typedef struct {
  PetscErrorCode (*mult)(void *, const PetscScalar *, PetscScalar *);
  PetscErrorCode (*form)(void *, PetscScalar *, PetscInt);
  void *ctx;
} JRDenseOp;
PETSC_EXTERN PetscErrorCode JRDenseLUSolveOp(JRDenseLU, PetscInt, const JRDenseOp *, PetscScalar *, PetscInt, PetscReal, PetscScalar *, PetscBool *);
PETSC_EXTERN PetscErrorCode JRDenseLUGetCounts(JRDenseLU, PetscInt *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRDenseLUGetFactoredSize(JRDenseLU, PetscInt *);
PETSC_EXTERN PetscErrorCode JRDenseLUSetEliminate(JRDenseLU, PetscBool);
PETSC_EXTERN PetscErrorCode JRDenseLUGetEliminate(JRDenseLU, PetscBool *);
PETSC_EXTERN PetscErrorCode SNESNewtonDenseGetDenseLU(SNES, JRDenseLU *);
PETSC_EXTERN PetscErrorCode SNESNewtonDenseSetOperator(SNES, const JRDenseOp *);
PETSC_EXTERN PetscErrorCode SNESNewtonDenseUsesOperator(SNES, PetscBool *);

/* A dense matrix written through its array: assembled once; later writes only raise its state (MatDenseRestoreArray),
   which is what a factorisation checks (MatAssemblyEnd's per-call options lookups cost more than a 19 x 19 LU) */
PETSC_EXTERN PetscErrorCode JRMatDenseAssemble(Mat);

/* 64-byte aligned allocations (whole cache lines) for large SoA batches */
PETSC_EXTERN PetscErrorCode JRMallocAligned(size_t, void *);
PETSC_EXTERN PetscErrorCode JRFreeAligned(void *);

/* Run a gnuplot script from share/ to make a PNG (temporary name, then rename) */
PETSC_EXTERN PetscErrorCode JRPlot(MPI_Comm, const char[], const char[], const char[], PetscBool *);

/* User errors: one message, once, without PETSc's traceback (src/sys/error.c); exit status of a failed run */
PETSC_EXTERN PetscErrorCode JRErrorHandlerPush(void);
PETSC_EXTERN int            JRErrorExit(PetscErrorCode);
PETSC_EXTERN PetscErrorCode JRErrorContextPush(const char[]);
PETSC_EXTERN PetscErrorCode JRErrorContextPop(void);
PETSC_EXTERN PetscErrorCode JRErrorCatchPush(void);
PETSC_EXTERN PetscErrorCode JRErrorCatchPop(char[], size_t);
/* Options nothing read: an error before the work (jointrom's own), a warning at the end (src/sys/options.c) */
PETSC_EXTERN PetscErrorCode JROptionsCheck(MPI_Comm, const char[]);
PETSC_EXTERN PetscErrorCode JROptionsCheckValues(MPI_Comm);
PETSC_EXTERN PetscErrorCode JRCheckFactorSolverType(PC, Mat, const char[]);
PETSC_EXTERN PetscErrorCode JROptionsWarnUnused(MPI_Comm);
PETSC_EXTERN PetscErrorCode JROptionsHelpSolvers(MPI_Comm, PetscBool, PetscBool, PetscBool, PetscBool);
/* The directory of an output base name exists (created if missing) and is writable, else an error naming option */
PETSC_EXTERN PetscErrorCode JRFileCheckOutput(MPI_Comm, const char[], const char[]);
PETSC_EXTERN PetscErrorCode JRFileCheckNotOutput(MPI_Comm, const char[], const char[], const char[], const char[], const char *const[]);

#endif
