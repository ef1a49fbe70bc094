/* The second reduction's fit (src/reduce/fit.c, fitjoint.c, loops.c): the least-squares problems and the state of a fit,
   private */
#if !defined(JOINTROM_FITIMPL_H)
#define JOINTROM_FITIMPL_H
#include <jointrom/private/reduceimpl.h>
#include <jointrom/private/contactimpl.h>

/* The tangential fit: x = [k_i / ks, f_i / fs] */
typedef struct {
  PetscInt   m, ns;
  PetscReal  amp[4], w[4], ks, fs; /* amplitudes: microslip, microslip, gross slip, and stuck (the stiffness) */
  PetscReal *target;               /* 4 ns */
  PetscReal *Fk, *Ff;
  PetscInt   ne;                   /* amplitudes where the energy dissipated per cycle is matched */
  PetscReal *ae, *Et, *En, *we;    /* amplitude, target, scale and weight of each: residual we (E - Et) / En */
  PetscReal  ftot, wg;             /* the joint's slip force (gross slip), matched with weight wg (relative) */
  PetscReal *delta;                /* the fitted elements' slip displacements (kept where a force fitted to 0) */
} TangentFit;

#define FitRows(t) (4 * (t)->ns + (t)->ne + 1)

/* The convex stage: the slip displacements fixed at delta[i], the slip forces y_i = f_i / fs free (k_i = f_i / delta_i):
   every residual is linear in y, so the bounded least squares has one minimum, continuous in the data */
typedef struct {
  TangentFit *t;
  PetscReal  *delta, *x, *J2;
} FixedFit;

/* The fit coupled across joints (-rom_fit_total_weight): to every fitted joint's own rows (FixedFit, slip
   displacements fixed, forces y free) are added the energy all joints together dissipate per cycle at the case's
   amplitudes am[l] (joint j moving u[j] am[l]), relative to all the energy put in there (En[l]) - the sum the peak
   amplitudes answer to. Et: the first reduction's, less that of joints not fitted (their members are their elements). */
typedef struct {
  PetscInt    nj, na, n;      /* fitted joints, case amplitudes, elements of them all */
  PetscInt   *jl;             /* fitted joint k is joint jl[k] */
  FixedFit   *fx;             /* each fitted joint's rows (fx[k].t) and slip displacements (fx[k].delta) */
  PetscInt   *off, *roff;     /* joint k: forces y[off[k] .. off[k + 1]), rows from roff[k] */
  PetscReal  *u, *am, *Et, *En, w;
  PetscReal  *rj, *Jj;        /* scratch: one joint's rows and their Jacobian */
} CoupledFit;

#define CoupledRows(c) ((c)->roff[(c)->nj] + (c)->na)

/* The normal fit of jenkins_nv joints: x = kn_i / kns, n0_i given; target N(v_s) */
typedef struct {
  PetscInt   m, nv;
  PetscReal *n0, kns, w;
  PetscReal *v, *target;
} NormalFit;

typedef struct {
  PetscInt  e;
  PetscReal delta;
} MemberDelta;

#define JR_EP 15 /* per reduced element before the split: up to 3 points of 5 field coordinates (x, y, z [m], phi_t, phi_n) */

#define NCASE 24 /* the case's amplitudes: from half the lowest level's to twice the highest's (JRFitCaseAmplitude) */

/* One joint's fit (JRFitJoint): its tangential fit t and x = [k_i / ks, f_i / fs] (3 m long: JRFitJointElements drops the
   elements left without force in place) */
typedef struct {
  TangentFit t;
  PetscReal *x;
  PetscInt   m, its;          /* elements fitted, TAO iterations */
  PetscReal  rms, rms0;       /* the residual of the fit and of its start */
  PetscReal  mu, kn;          /* the members' friction coefficient (n0-weighted mean) and total normal stiffness */
  PetscReal  dlo, dhi;        /* the range of slip displacements searched */
  PetscReal  nrms, nrms0;     /* jenkins_nv (JRFitNormal): the normal fit's residual, after and at its start */
  PetscInt   nits;            /* and its TAO iterations */
} JointFit;

/* What the steps of one fit (ReducePass) share: the problem, set by JRROMReduce, and what the steps compute */
typedef struct {
  MPI_Comm          comm;
  const JRElements *nn;          /* the first-reduction model: the members, with their joints */
  PetscInt          m;           /* -rom_elements: elements per joint */
  const PetscReal  *wt;          /* the members' mode-shape weights (NULL: none) */
  const JRROMCase  *cs;          /* the case (NULL: none) */
  const JRROMFit   *fit;         /* the options */
  const char       *base;        /* BASE_rom_loops.csv (NULL or "": none) */
  PetscBool         plot, quiet; /* the loops' PNG too; print nothing */
  const PetscReal  *nvin;        /* added to the case's energy targets (NULL: none; JRFitNormalVariation) */
  /* the pass's own (FitCtxReset) */
  PetscInt          nj;                /* joints */
  PetscBool         nv, spread, modef; /* jenkins_nv; -rom_joint_motion linear; mode */
  PetscReal        *mk, *mf;           /* every member as an element on its joint's motion (w^2 kt, |w| f) */
  PetscReal        *amod, amin, amax;  /* the case's modal amplitude at each level, their range (NULL: no case) */
  MemberDelta      *md;                /* joint j's members in contact at rest: md[joff[j] .. joff[j] + jn[j]), by slip
                                          displacement */
  PetscInt         *jn, *joff;
  JointFit         *jf;                /* per joint */
  PetscInt         *nel;               /* per joint: its reduced elements (JRFitJointElements) */
  PetscInt         *jm;                /* per joint: the elements it is fitted with (-rom_elements, grown by JRFitJoint) */
  PetscInt          cnt;               /* the reduced elements of the joints before */
  PetscReal        *ek, *ef, *ekn, *en0, *emu; /* the reduced elements before the split: kt, f, kn, n0, mu */
  PetscReal        *ep, *er;           /* linear, mode: JR_EP per element (its points); mode: its ratio (JRFitModePoints) */
  PetscReal        *epr;               /* released modes: 2 JR_NREL per element, its two points' released-mode coordinates */
  FILE             *fp;                /* the loops' CSV (rank 0) */
  char              csv[PETSC_MAX_PATH_LEN + 32], tmp[PETSC_MAX_PATH_LEN + 48];
} FitCtx;

PETSC_INTERN void JRFitJenkinsLoop(PetscReal k, PetscReal f, PetscReal a, PetscInt ns, PetscReal F[], PetscReal Fk[], PetscReal Ff[]);
PETSC_INTERN PetscReal JRFitJenkinsEnergy(PetscReal k, PetscReal f, PetscReal a, PetscReal *Ek, PetscReal *Ef);
PETSC_INTERN PetscErrorCode JRFitTangentResidual(void *ctx, const PetscReal x[], PetscReal r[], PetscReal J[]);
PETSC_INTERN PetscErrorCode JRFitFixedResidual(void *ctx, const PetscReal y[], PetscReal r[], PetscReal J[]);
PETSC_INTERN PetscErrorCode JRFitSearchDelta(TangentFit *t, PetscReal dmin, PetscReal dmax, PetscInt m, PetscReal delta[], PetscReal y[], PetscReal *cost);
PETSC_INTERN PetscErrorCode JRFitCoupledResidual(void *ctx, const PetscReal y[], PetscReal r[], PetscReal J[]);
PETSC_INTERN PetscErrorCode JRFitCoupledSearch(CoupledFit *cf, const PetscReal dlo[], const PetscReal dhi[], PetscReal y[], PetscReal *cost0, PetscReal *cost, PetscInt *sweeps);
PETSC_INTERN PetscErrorCode JRFitNormalResidual(void *ctx, const PetscReal x[], PetscReal r[], PetscReal J[]);
PETSC_INTERN int JRFitCompareDelta(const void *a, const void *b);
PETSC_INTERN PetscErrorCode JRFitSay(PetscBool quiet, MPI_Comm comm, const char fmt[], ...);
PETSC_INTERN PetscReal JRFitCaseAmplitude(const FitCtx *ctx, PetscInt l);
PETSC_INTERN PetscReal JRFitCaseDissipation(const FitCtx *ctx, PetscReal a);
PETSC_INTERN PetscErrorCode JRFitSpreadPoints(FitCtx *ctx, PetscInt j, PetscInt mj);
PETSC_INTERN PetscErrorCode JRFitModePoints(FitCtx *ctx, PetscInt j, PetscInt mj);
PETSC_INTERN PetscErrorCode JRFitOpenPoints(FitCtx *ctx, const MemberDelta *od, PetscInt no, PetscInt ng, PetscInt e0);
PETSC_INTERN PetscErrorCode JRFitNormalVariation(const FitCtx *ctx, const JRElements *rom, PetscReal nv[], PetscReal *nvmax);
PETSC_INTERN PetscErrorCode JRFitJoint(FitCtx *ctx, PetscInt j);
PETSC_INTERN PetscErrorCode JRFitJointFitDestroy(JointFit *f);
PETSC_INTERN PetscErrorCode JRFitJointElements(FitCtx *ctx, PetscInt j);
PETSC_INTERN PetscErrorCode JRFitNormal(FitCtx *ctx, PetscInt j);
PETSC_INTERN PetscErrorCode JRFitJointReport(FitCtx *ctx, PetscInt j);
#endif
