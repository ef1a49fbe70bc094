/* JRReduce: the reduced-order joints (first and second reduction), private struct */
#if !defined(JOINTROM_REDUCEIMPL_H)
#define JOINTROM_REDUCEIMPL_H
#include <jointrom.h>

/* A first-reduction joint as reported: its members, those in contact at rest (n0 > 0), the normal load they carry at
   rest [N], the members' centroid [m] (x, y, z), its zone (1 high-load, 0 low-load: -rom_joints zones; -1 none) and
   a description of its region */
typedef struct {
  PetscInt  members, contact, zone;
  PetscReal load, x[3];
  char      kind[64];
} JRJointInfo;

#define JR_REL_TOP 0.3 /* the largest share of the slip force a default released mode frees */
struct _p_JRReduce {
  MPI_Comm  comm;
  PetscBool setfromoptions;
  /* first reduction: the joints (-rom_joints ...) */
  PetscInt  joints; /* 0 none, 1 each, 2 strips, 3 bolts, 4 between, 5 sides, 6 zones, 7 boxes, 8 auto, 9 onset */
  PetscInt  rings;  /* -rom_auto_rings */
  PetscInt  bands;  /* -rom_onset_bands */
  PetscInt  obands; /* -rom_onset_open_bands */
  PetscReal upto;   /* -rom_onset_upto */
  PetscReal rel[JR_NREL]; /* -rom_release_fractions, or from the first members to slip to JR_REL_TOP (relauto) */
  PetscInt  nrel;
  PetscBool relauto;
  const PetscInt *pair; /* each element's pair (JRReduceAssignJoints' argument, kept for onset) */
  PetscInt  ncut, nbox;
  PetscReal cut[64], box[256], zone_fraction;
  PetscBool split_width;
  /* second reduction */
  PetscInt  m;            /* -rom_elements */
  PetscBool mode_weights; /* -rom_mode_weights */
  JRROMFit  fit;          /* -rom_fit_*, -rom_joint_motion */
  PetscInt  select;       /* -rom_fit_select: 0 none, 1 first */
  PetscInt  nst, nsc;     /* -rom_fit_select_total, -rom_fit_select_case */
  PetscReal swt[8], swc[8];
  PetscBool corr_on;      /* -rom_stiffness_correction */
  char      save[PETSC_MAX_PATH_LEN], load[PETSC_MAX_PATH_LEN];
  /* the case the reduced model is for, and where its excitation and responses are */
  PetscReal wmin, wmax;   /* frequency range [rad/s] (0: none) */
  PetscInt  nlev;
  PetscReal *lev;         /* excitation levels [N] */
  PetscInt  fdof, nout, odof[64];
  char      base[PETSC_MAX_PATH_LEN]; /* BASE_rom_loops.csv/.png ("" none) */
  PetscBool plot;
  /* the joints as reported (JRReduceAssignJoints) */
  PetscInt     nji;
  JRJointInfo *ji;
  /* results */
  PetscReal corr; /* the stiffness correction applied (1: none) */
};

/* An element list of n elements of one type with joints (and the node-to-node arrays if nodes), no DOFs: the second
   reduction's elements (src/reduce/fit.c) and a loaded model's (src/reduce/io.c) */
PETSC_INTERN PetscErrorCode JRROMElementsSetUp(JRElements *, PetscInt, const char[], PetscBool);
/* -rom_joints onset: the joints from the members' slip onsets in the stuck mode (their tangential motion u[]) */
PETSC_INTERN PetscErrorCode JRReduceAssignOnset(JRReduce, JRModel, JRElements *, const PetscReal[], const PetscReal[]);

/* The fit's least-squares solvers (src/reduce/lsq.c), on PETSC_COMM_SELF.
   JRLSQSolve: r(x) -> min 1/2 |r|^2 with x >= lo by TAO (prefix rom_); fn(ctx, x, r, J) gives r and J (nr x nx,
   column-major); rms0, rms: |r| before and after, x updated.
   JRGram: the Gram system G = C^T C, cg = C^T b of the columns C (ld rows, nc columns, column-major) against b.
   JRGramNNLS: the non-negative least squares of the columns sel[0..m) of a Gram system (G, c, bb = b.b), every
   support tried (m <= 8); cost: |C y - b|^2.
   JRActiveSetNNLS: min y^T A y - 2 c^T y over y >= 0 by the Lawson-Hanson active set, warm-started from y. */
typedef struct {
  PetscInt  nx, nr;
  PetscErrorCode (*fn)(void *, const PetscReal[], PetscReal[], PetscReal[]);
  void      *ctx;
  PetscReal *r, *J;
  PetscReal  fkeep; /* the objective at the last iteration that lowered it measurably */
  PetscInt   kkeep; /* that iteration */
} JRLSQ;
PETSC_INTERN PetscErrorCode JRLSQSolve(JRLSQ *, PetscReal[], PetscReal, PetscReal *, PetscReal *, PetscInt *);
PETSC_INTERN void           JRGram(PetscInt, PetscInt, const PetscReal[], const PetscReal[], PetscReal[], PetscReal[]);
PETSC_INTERN PetscErrorCode JRGramNNLS(PetscInt, const PetscReal[], const PetscReal[], PetscReal, PetscInt, const PetscInt[], PetscReal[], PetscReal *);
PETSC_INTERN PetscErrorCode JRActiveSetNNLS(PetscInt, const PetscReal[], const PetscReal[], PetscReal[], PetscReal *);
/* src/reduce/joints.c: the -rom_joints kinds and a joint in words (index, members, centroid, region) */
PETSC_INTERN const char *const JRReduceJointKinds[];
PETSC_INTERN PetscErrorCode JRReduceJointName(JRReduce, PetscInt, char[], size_t);
#endif
