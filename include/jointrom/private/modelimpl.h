/* Private: the JRModel and JRModes structs. */
#if !defined(JOINTROM_MODELIMPL_H)
#define JOINTROM_MODELIMPL_H

#include <jointrom.h>
#include <slepceps.h>

typedef struct _JRModelOps *JRModelOps;
struct _JRModelOps {
  PetscErrorCode (*setfromoptions)(JRModel, PetscOptionItems *);
  PetscErrorCode (*setup)(JRModel);
  PetscErrorCode (*rigidbasis)(JRModel, PetscInt *, Vec[6]);
  PetscErrorCode (*coordinates)(JRModel, Vec *);
  PetscErrorCode (*view)(JRModel, PetscViewer);
  PetscErrorCode (*destroy)(JRModel);
};

struct _p_JRModel {
  MPI_Comm           comm;
  char               type_name[64];
  struct _JRModelOps ops[1];
  void              *data;
  PetscBool          setupcalled, view, el_given;
  PetscBool          tied;       /* FE: the interface pairs are tied (-model_interface tied) */
  Mat                K, M, C; /* C may be NULL */
  PetscInt           ndof;
  JRElements         el;
  JRPairs            pairs;
  JRBolts            bolts;
  DM                 dm;         /* the FE mesh and discretisation (NULL for matrices) */
  IS                 nat;        /* FE: each owned DOF's position in the partition-independent order (NULL: the DOFs' own) */
  PetscInt          *g2n, *n2g;  /* that order over every DOF, and its inverse, on every rank (JRModelDOFsToNatural) */
  PetscReal          mass, volume_mass; /* total mass from M, and density x volume */
};

PETSC_INTERN PetscErrorCode JRModelRegisterAll(void);
PETSC_INTERN PetscErrorCode JRModelCreate_Matrices(JRModel);
PETSC_INTERN PetscErrorCode JRModelCreate_Beam(JRModel);
PETSC_INTERN PetscErrorCode JRModelCreate_Lap(JRModel);
PETSC_INTERN PetscErrorCode JRModelCreate_BRB(JRModel);
PETSC_INTERN PetscErrorCode JRModelCreate_Lap1(JRModel);
PETSC_INTERN PetscErrorCode JRModelCreate_Lap3(JRModel);
PETSC_INTERN PetscErrorCode JRModelCreate_Gmsh(JRModel);
PETSC_INTERN PetscErrorCode JRPairsDestroy(JRPairs *);
PETSC_INTERN PetscErrorCode JRModesSave(JRModes, const char[]);
PETSC_INTERN PetscErrorCode JRBoltsDestroy(JRBolts *);
PETSC_INTERN PetscErrorCode JRMatCreateFromBlocks(Mat, PetscInt, const PetscInt *, const PetscInt *const *, const PetscReal *const *, Mat *);
PETSC_INTERN PetscErrorCode JRElementsReadCSV(MPI_Comm, const char[], PetscInt, JRElements *);

struct _p_JRModes {
  MPI_Comm   comm;
  PetscInt   refct;      /* references (JRModesReference); JRModesDestroy frees at the last */
  Mat        K, M;
  PetscInt   nev;        /* requested */
  PetscInt   nm;         /* computed and kept */
  PetscReal  target;     /* shift for shift-and-invert [rad^2/s^2] */
  PetscBool  target_set, view;
  EPS        eps;
  PetscReal *lambda;     /* omega_r^2, ascending */
  Vec       *phi;        /* mass-normalised */
  PetscInt   nrb;        /* exact rigid-body basis supplied (deflated; kept as the first modes) */
  Vec       *rb;
  PetscBool  use_rb;     /* -modes_rigid_basis */
  PetscReal  sig;        /* signature of the stuck springs added to K (0: none), saved and checked; on the natural DOFs */
  PetscReal  sigraw;     /* the same on the DOFs' own numbers: checks a file written before the natural order */
  Vec        X;          /* node coordinates in the DOF layout (optional): checks a loaded file's layout */
  IS         nat;        /* each owned DOF's position in the partition-independent order of saved modes (NULL: the DOFs' own) */
  PetscBool  natset;     /* JRModesSetNaturalOrdering() called: files are written in that order (else in the DOFs') */
  char       load[PETSC_MAX_PATH_LEN], save[PETSC_MAX_PATH_LEN]; /* -modes_load, -modes_save */
  PetscBool  load_all;   /* -modes_load reads every vector of the file (a mixed basis) */
  PetscBool  mixed;      /* JRModesSetMixed(): a mixed basis, made by JRModesMix */
  char       save_mixed[PETSC_MAX_PATH_LEN]; /* where JRModesMix saves it */
  /* static correction of the interface (JRModesSetInterface; JRModesMix) and the basis check */
  PetscInt   nir, nper;  /* interface rows: nir rows of nper (DOF, coefficient) entries, on every rank */
  PetscInt  *irdof;      /* DOFs (-1: none) */
  PetscReal *ircoef, *irk; /* coefficients; each row's contact stiffness [N/m] (the weights) */
  PetscInt   nstatic;    /* -modes_static: static correction vectors (-1: those above -modes_static_tol) */
  PetscInt   nstatic_max; /* -modes_static_max */
  PetscReal  static_tol; /* -modes_static_tol */
  PetscBool  check;      /* -modes_check: compute the basis check */
  PetscReal  check_tol;  /* -modes_check_tol: the check's threshold */
  PetscInt   nsadded;    /* static correction vectors added */
  PetscReal  rho0, rho;  /* the check: largest residual flexibility x stiffness outside the basis, before and after the static correction (-1: not computed) */
  PetscLogDouble tstatic; /* seconds spent on the static correction and the check */
  /* the basis adapted to computed solutions (JRModesEnrich) */
  PetscInt   adapt;      /* -modes_adapt: at most this many rounds (the caller's loop) */
  PetscReal  adapt_tol;  /* -modes_adapt_tol: the loads' deformation outside the basis, in units of the springs' stretch */
  PetscReal  adapt_move; /* -modes_adapt_move: the peaks' move between rounds below which the rounds may stop */
  PetscInt   nadapt;     /* vectors added */
  PetscLogDouble tadapt; /* their seconds */
  PetscInt   read_rounds, read_added; /* a basis read (-modes_load): the adaptation recorded in its file (JRModesSaveAdaptation; rounds 0: none) */
  PetscReal  read_deform; /* its last round's deformation of the interface by the peaks' loads (JRModesEnrich's lmax) */
  PetscBool  read_conv;  /* its last round added nothing */
  KSP        sksp;       /* the static solver of A = K - ssigma M, kept between rounds (JRModesEnrichEnd frees it) */
  Mat        sA;
  PetscReal  ssigma;
};
/* src/modes/: the saved modes read back (io.c), the default shift of the eigensolver and the static solves (modes.c) */
PETSC_INTERN PetscErrorCode JRModesLoad_Private(JRModes, const char[]);
PETSC_INTERN PetscErrorCode JRModesDefaultShift_Private(JRModes, PetscReal *);

#endif
