/* Private: the JRCont struct, its types' ops table, and the curve of one excitation level (src/cont/). */
#if !defined(JOINTROM_CONTIMPL_H)
#define JOINTROM_CONTIMPL_H

#include <jointrom.h>

/* The frequency-response curve of one excitation level */
typedef struct {
  PetscReal       F;
  PetscInt        np, cap;
  PetscReal      *omega, *a, *amp, *pp, *step; /* per point: a over the nmod modal unknowns, amp and pp over the nout outputs */
  PetscInt       *its;
  PetscInt        retries, states[4];
  PetscBool       complete;
  PetscReal       seconds;
  PetscInt        newton;
  PetscInt        kpeak;        /* the computed point of largest amplitude */
  PetscReal       wpeak, apeak; /* the peak refined by a parabola through it and its neighbours */
  PetscReal       zeta, ebal;   /* equivalent damping ratio at the peak; worst energy imbalance of the curve */
  JRContactState *estate;       /* every element's state at the peak (rank 0) */
} JRContBranch;

/* A continuation type (-cont_type): its create function fills these */
typedef struct _JRContOps *JRContOps;
struct _JRContOps {
  PetscErrorCode (*setfromoptions)(JRCont, PetscOptionItems *);
  PetscErrorCode (*setup)(JRCont);                                 /* at every JRContSolve, once the sizes are known: the type's work */
  PetscErrorCode (*solvelevel)(JRCont, PetscInt, JRContBranch *, Vec); /* level lev's curve over [wmin, wmax] (b->F set); a: work, size n */
  PetscErrorCode (*destroy)(JRCont);                               /* frees data */
};

struct _p_JRCont {
  MPI_Comm          comm;
  JRHBM             hbm;
  char              type_name[64];
  struct _JRContOps ops[1];
  void             *data; /* the type's */
  PetscReal         wmin, wmax, step0, stepmin, stepmax;
  PetscBool         range_set, secant, plot, normalize, write;
  PetscBool         quiet;                                      /* JRContSetQuiet(): no progress, peak lines or summary */
  PetscInt          maxpts, target, monitor, nlev, npoints;
  PetscInt          n, nmod, nout; /* n: the solve space; nmod: modal; nout: outputs */
  PetscReal        *levels;
  JRContBranch     *br;
  char              out[PETSC_MAX_PATH_LEN];
  Vec               amod; /* work: the modal unknowns of one point */
};

PETSC_INTERN PetscErrorCode JRContCreate_Natural(JRCont);
PETSC_INTERN PetscErrorCode JRContCreate_Arclength(JRCont);

/* src/cont/interface/cont.c: the steps every type shares */
PETSC_INTERN PetscErrorCode JRContBranchStart(JRCont, PetscInt, JRContBranch *, Vec);
PETSC_INTERN PetscErrorCode JRContBranchAdd(JRCont, JRContBranch *, PetscReal, Vec, PetscInt, PetscReal);
PETSC_INTERN PetscErrorCode JRContMonitor(JRCont, PetscInt, JRContBranch *);
/* src/cont/output.c */
PETSC_INTERN PetscErrorCode JRContPrintSummary(JRCont);

#endif
