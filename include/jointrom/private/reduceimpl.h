/* JRReduce: the reduced-order joints (first and second reduction), private struct */
#if !defined(JOINTROM_REDUCEIMPL_H)
#define JOINTROM_REDUCEIMPL_H
#include <jointrom.h>

struct _p_JRReduce {
  MPI_Comm  comm;
  PetscBool setfromoptions;
  /* first reduction: the joints (-rom_joints ...) */
  PetscInt  joints; /* 0 none, 1 each, 2 strips, 3 bolts, 4 between, 5 sides, 6 zones, 7 boxes */
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
  /* results */
  PetscReal corr; /* the stiffness correction applied (1: none) */
};

/* An element list of n elements of one type with joints (and the node-to-node arrays if nodes), no DOFs: the second
   reduction's elements (src/reduce/fit.c) and a loaded model's (src/reduce/io.c) */
PETSC_INTERN PetscErrorCode JRROMElementsSetUp(JRElements *, PetscInt, const char[], PetscBool);
#endif
