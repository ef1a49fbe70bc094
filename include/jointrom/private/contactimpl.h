/* Private: the JRContact struct, its ops table, and the shared element kernels. */
#if !defined(JOINTROM_CONTACTIMPL_H)
#define JOINTROM_CONTACTIMPL_H

#include <jointrom.h>

#define JR_MAX_HARMONICS 32
#define JR_MAX_NC        (2 * JR_MAX_HARMONICS + 1)

/* Per-sample codes of the time march */
typedef enum {
  JR_CODE_STICK = 0,
  JR_CODE_SLIPP = 1, /* positive slip, f = +mu n */
  JR_CODE_SLIPN = 2, /* negative slip, f = -mu n */
  JR_CODE_SEP   = 3  /* separated, f = n = 0 */
} JRSampleCode;

/* Output pointers of one evaluation; any may be NULL. Element-major dense blocks
   (F[nc], dFdU[nc*nc] row-major ...) for the single-element kernels. */
typedef struct {
  PetscReal     *F, *N, *dFdU, *dFdV, *dNdV;
  JRContactState state;
} JRElementOut;

/* Alternating frequency-time tables and scratch for H harmonics and N samples */
typedef struct {
  PetscInt   H, N, nc;
  PetscReal *Bt;   /* Bt[k*N + j]: basis function k at sample j (synthesis) */
  PetscReal *PB;   /* PB[j*nc + k]: sum_{i<j} B_ik, j = 0..N (prefix sums) */
  PetscReal *PG;   /* PG[j*nc*nc + k*nc + m]: sum_{i<j} B_ik B_im (prefix Gram) */
  PetscReal *wdft; /* DFT weights: 1/N for the mean, 2/N for the others */
  /* scratch, length N */
  PetscReal *u, *v, *g, *f, *lam, *Lb, *Ub, *uc; /* lam, uc: contact interpolation at first contact samples */
  PetscInt  *code, *rc;                          /* code by march position; rc[j]: j is a first contact sample */
  PetscReal *S, *wflat, *dXU, *dXV;      /* nc; nc*nc DFT weight of each row; nc; nc */
  PetscReal *DU, *DV, *DN;               /* nc*nc scratch */
} JRAFT;

PETSC_INTERN PetscErrorCode JRAFTCreate(PetscInt, PetscInt, JRAFT **);
PETSC_INTERN PetscErrorCode JRAFTDestroy(JRAFT **);
/* One element by AFT. Ue, Ve: nc coefficients (Ve NULL: constant normal load n0).
   If ftime is not NULL it receives the periodic force at the N samples (and ntime the normal load). */
PETSC_INTERN void JRAFTElement(JRAFT *, PetscReal, PetscReal, PetscReal, PetscReal, const PetscReal[], const PetscReal[], JRElementOut *, PetscReal[], PetscReal[]);

/* Single-harmonic closed forms (nc = 3: mean, sine, cosine) */
PETSC_INTERN void JRJenkinsAnalytic(PetscReal, PetscReal, PetscReal, const PetscReal[], JRElementOut *);
PETSC_INTERN int  JRJenkinsNVAnalytic(PetscReal, PetscReal, PetscReal, PetscReal, const PetscReal[], const PetscReal[], JRElementOut *, JRContactSequence *);

typedef struct _JRContactOps *JRContactOps;
struct _JRContactOps {
  PetscErrorCode (*setfromoptions)(JRContact, PetscOptionItems *);
  PetscErrorCode (*setup)(JRContact);
  /* evaluate elements [start, end) of the batch; SoA in/out as in JRContactEvaluate */
  PetscErrorCode (*evaluate)(JRContact, PetscInt, PetscInt, const PetscReal[], const PetscReal[], PetscReal[], PetscReal[], PetscReal[], PetscReal[], PetscReal[], JRContactState[]);
  /* evaluate element e of the batch for the motion Ue, Ve (nc each), dense outputs */
  PetscErrorCode (*element)(JRContact, PetscInt, const PetscReal[], const PetscReal[], JRElementOut *);
  PetscErrorCode (*view)(JRContact, PetscViewer);
  PetscErrorCode (*destroy)(JRContact);
};

struct _p_JRContact {
  MPI_Comm               comm;
  char                  *prefix;
  char                   type_name[64];
  struct _JRContactOps   ops[1];
  void                  *data;
  PetscBool              setupcalled;
  PetscBool              normal; /* the type uses the normal motion v */
  PetscBool              view;      /* -contact_view: view at set-up */
  PetscBool              signed_kt; /* kt may be negative (cubic: softening) */
  PetscInt               H, N, nc;
  JRContactMethod        method;
  PetscBool              method_set;
  PetscInt               n;                 /* elements in the batch (on this rank) */
  PetscReal             *kt, *kn, *mu, *n0; /* SoA element parameters */
  JRAFT                 *aft;
};

PETSC_INTERN PetscErrorCode JRContactRegisterAllReset(void);
PETSC_INTERN PetscErrorCode JRContactEvaluateChunked(JRContact, PetscInt, PetscInt, const PetscReal[], const PetscReal[], PetscReal[], PetscReal[], PetscReal[], PetscReal[], PetscReal[], JRContactState[]);
PETSC_INTERN PetscErrorCode JRContactCreate_Jenkins(JRContact);
PETSC_INTERN PetscErrorCode JRContactCreate_JenkinsNV(JRContact);
PETSC_INTERN PetscErrorCode JRContactCreate_Cubic(JRContact);

#endif
