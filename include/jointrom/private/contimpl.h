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
  PetscReal      *x, *res;     /* per point: the unknowns in the solve space (n), the relative residual (JRHBMResidualNorm) */
  PetscInt        retries, states[4];
  PetscBool       complete;
  char            why[256];     /* why an incomplete curve ended */
  PetscReal       seconds;
  PetscInt        newton;
  PetscInt        kpeak;        /* the point of largest amplitude at response 1 (after the peaks are refined: the peak itself) */
  PetscReal       wpeak, apeak; /* the peak of response 1: the maximum of the solution curve */
  PetscReal      *wpk, *apk;    /* every response's own peak (nout) */
  PetscInt        refine_its;   /* harmonic-balance solves spent refining the peaks */
  PetscReal       resmax;       /* the largest relative residual of the curve's points */
  PetscReal       zeta, ebal;   /* equivalent damping ratio at the peak; worst energy imbalance of the curve */
  JRContactState *estate;       /* every element's state at the peak (rank 0) */
  /* stability by Hill's method (src/cont/stability.c), per point after the level; NULL when not computed */
  PetscInt       *stable;       /* 1 stable, 0 unstable */
  PetscReal      *maxre;        /* the largest real part of the kept Floquet exponents [1/s] */
  PetscInt       *detsign;      /* the sign of det(dR/da) */
  PetscReal       stab_seconds; /* their wall time */
  PetscReal       stab_elem;    /* its part in the contact elements (JRHBMGetElementTime) */
  PetscInt        nhyst;        /* points decided by Hill's method with friction elements changing state */
  PetscInt        nfold, nbranch;
  PetscReal      *wfold, *wbranch; /* the folds' and branch points' frequencies [rad/s] */
} JRContBranch;

/* A continuation type (-cont_type): its create function fills these */
typedef struct _JRContOps *JRContOps;
struct _JRContOps {
  PetscErrorCode (*setfromoptions)(JRCont, PetscOptionItems *);
  PetscErrorCode (*setup)(JRCont);                                 /* at every JRContSolve, once the sizes are known: the type's work */
  PetscErrorCode (*solvelevel)(JRCont, PetscInt, JRContBranch *, Vec); /* level lev's curve over [wmin, wmax] (b->F set); a: work, size n */
  PetscErrorCode (*forget)(JRCont);                                /* drops the factors kept from earlier solves (may be NULL) */
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
  PetscBool         partial;                                    /* -cont_allow_partial: an incomplete curve is not an error */
  PetscReal         itol;                                       /* -cont_interp_tol: linear interpolation error between points */
  PetscReal         ptol;                                       /* -cont_peak_tol: the peaks' relative amplitude tolerance */
  PetscReal         ltol;                                       /* -cont_locate_tol: the folds' and branch points' relative frequency tolerance */
  PetscReal         ptolb;                                      /* -cont_locate_pair_tol: the same for branch points of kind pair */
  PetscInt          maxpts, target, monitor, nlev, npoints;
  PetscInt          n, nmod, nout; /* n: the solve space; nmod: modal; nout: outputs */
  PetscReal        *levels;
  JRContBranch     *br;
  char              out[PETSC_MAX_PATH_LEN];
  Vec               amod; /* work: the modal unknowns of one point */
  PetscReal        *ampw; /* work: the amplitudes and peak-to-peak of one point at the outputs (2 nout) */
  struct _JRContPlaneWork *pw; /* work: solves on planes across the curve (src/cont/peak.c) */
  PetscBool         stab;       /* -frf_stability: Floquet exponents, folds and branch points of every point */
  PetscBool         stabset;    /* -frf_stability given; else on where it is cheap (JRHBMStabilityCheap), decided once */
  JRHillSelect      stabsel;    /* -frf_stability_select */
  PetscReal         stabtol;    /* -frf_stability_tol: stable if every kept exponent has Re < tol w */
  PetscInt          stabdense;  /* -frf_stability_dense_max */
  PetscBool         stabtime;   /* -frf_stability_time: friction elements changing state, Floquet exponents in time */
  PetscInt          stabsteps;  /* -frf_stability_time_steps: their least steps per period */
  PetscInt          stablr;     /* -frf_stability_time_lowrank: 0 no, 1 auto, 2 yes (JRHBMSetFloquetLowRank) */
  PetscReal         stabfast;   /* -frf_stability_time_fast: modes above this x H w quasi-static there (0: none) */
  PetscBool         stabdiss;   /* -frf_stability_dissipative: the incremental-dissipativity certificate where it holds */
  PetscBool         levpar;     /* -cont_levels_parallel: a replicated model's levels shared out over the ranks */
  PetscBool         buffered;   /* the rank solves levels alone: JRContPrintf into text instead of to the output */
  char             *text;       /* its text (length tlen, allocated tcap) */
  size_t            tlen, tcap;
};

PETSC_INTERN PetscErrorCode JRContCreate_Natural(JRCont);
PETSC_INTERN PetscErrorCode JRContCreate_Arclength(JRCont);

/* src/cont/interface/cont.c: the steps every type shares */
PETSC_INTERN PetscErrorCode JRContBranchStart(JRCont, PetscInt, JRContBranch *, Vec);
PETSC_INTERN PetscErrorCode JRContBranchAdd(JRCont, JRContBranch *, PetscReal, Vec, PetscInt, PetscReal, PetscReal);
PETSC_INTERN PetscErrorCode JRContBranchAddExpanded(JRCont, JRContBranch *, PetscReal, Vec, Vec, PetscInt, PetscReal, PetscReal);
PETSC_INTERN PetscErrorCode JRContOutputAmplitude(JRCont, PetscReal, Vec, PetscInt, PetscReal *);
PETSC_INTERN PetscErrorCode JRContInterpolationError(JRCont, PetscReal, PetscReal, PetscReal, PetscReal, PetscReal, PetscReal, PetscReal, PetscReal, PetscReal *);
PETSC_INTERN PetscErrorCode JRContRefinePeaks(JRCont, JRContBranch *);
PETSC_INTERN PetscErrorCode JRContChordError(JRCont, JRContBranch *, Vec, PetscReal, PetscReal, PetscReal, PetscReal *, PetscInt *);
/* The bordered matrix [J Rw; row^T] ((n + 1) x (n + 1)) of the continuation's solves, J and Rw from
   JRHBMJacobianSetPoint(): applied by its products, written out only for an LU (a JRDenseOp's context) */
typedef struct {
  JRHBM        hbm;
  Mat          J;
  Vec          Rw;
  PetscScalar *row; /* n + 1 */
  PetscInt     n;
} JRContBordered;
PETSC_INTERN PetscErrorCode JRContBorderedMult(void *, const PetscScalar *, PetscScalar *);
PETSC_INTERN PetscErrorCode JRContBorderedForm(void *, PetscScalar *, PetscInt);
PETSC_INTERN PetscErrorCode JRContPlaneWorkCreate(JRCont);
PETSC_INTERN PetscErrorCode JRContPlaneWorkDestroy(JRCont);
PETSC_INTERN PetscErrorCode JRContPlaneScale(JRCont, JRContBranch *);
PETSC_INTERN PetscErrorCode JRContPlaneBegin(JRCont, JRContBranch *, PetscInt, PetscInt, PetscReal *);
PETSC_INTERN PetscReal      JRContPlaneCoordinate(JRCont, const PetscReal *);
/* a golden-section bracket along the curve for a maximum (peaks, folds): the plane coordinates s, values f and unknowns
   x (n + 1: a, w) of its low, middle and high points, and the trial's work vector xt */
typedef struct {
  PetscReal  s[3], f[3];
  PetscReal *x[3], *xt;
} JRContGolden;
PETSC_INTERN PetscReal JRContGoldenTrial(JRContGolden *, PetscInt, PetscReal *, PetscBool *);
PETSC_INTERN PetscBool JRContGoldenUpdate(JRContGolden *, PetscReal, PetscReal, PetscBool);
PETSC_INTERN PetscErrorCode JRContPlanePoint(JRCont, PetscReal, PetscReal *, Vec *, PetscInt *, PetscBool *);
PETSC_INTERN PetscErrorCode JRContTangentSign(JRCont, PetscReal, Vec, PetscInt *, PetscInt *);
PETSC_INTERN PetscErrorCode JRContMonitor(JRCont, PetscInt, JRContBranch *);
PETSC_INTERN PetscErrorCode JRContPrintf(JRCont, const char[], ...) PETSC_ATTRIBUTE_FORMAT(2, 3);
PETSC_INTERN PetscErrorCode JRContPlaneWorkForget(JRCont);
/* src/cont/stability.c */
PETSC_INTERN PetscErrorCode JRContStability(JRCont, PetscInt, Vec);
PETSC_INTERN PetscErrorCode JRContBranchStabilityFree(JRContBranch *);
/* the summary table (src/cont/interface/cont.c) */
PETSC_INTERN PetscErrorCode JRContPrintSummary(JRCont);

#endif
