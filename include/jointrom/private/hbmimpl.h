/* Private: the JRHBM struct, its element groups, and the functions its source files share (src/hbm/, and the
   reduced model's joint motion fields in src/reduce/fields.c). */
#if !defined(JOINTROM_HBMIMPL_H)
#define JOINTROM_HBMIMPL_H

#include <jointrom/private/contactimpl.h>
#include <jointrom/private/modelimpl.h>
#include <petscblaslapack.h>

/* -hbm_condense */
typedef enum {
  JR_HBM_CONDENSE_AUTO, /* when it is exact and smaller */
  JR_HBM_CONDENSE_YES,
  JR_HBM_CONDENSE_NO
} JRHBMCondense;
PETSC_INTERN const char *const JRHBMCondenseTypes[];



/* The elements of one contact type on this rank, with their projection rows */
typedef struct {
  JRContact  c;
  PetscBool  normal;
  PetscInt   nloc;
  PetscReal *R, *S;                         /* nloc x nm, column-major */
  PetscReal *U, *V, *F, *N, *DU, *DV, *DN; /* SoA work */
  PetscReal *W;                             /* nloc x nm scratch */
  PetscReal *nstatic;                       /* max(n0, 0) */
  JRContactState *state;
  /* Jacobian split: an element in its state at rest has dF/du = pt I (and dN/dv = pn I, dF/dv = 0) exactly, with
     (pt, pn) = (kt, kn) stuck if it is in contact at rest (n0 > 0) and 0 if open (a gap: no force while it stays
     open); that part, sum_e pt r_e r_e^T (x) I, is assembled once (Kst, Knn) and only the elements out of their state
     at rest are projected per iteration */
  PetscBool  split;
  PetscReal *Kst, *Knn;    /* nm x nm column-major, this rank's elements */
  PetscInt  *sel, nsel;    /* elements not in the stuck pattern */
  PetscReal *Rc, *Sc, *Dc; /* their projection rows (nsel x nm) and one derivative column */
  PetscReal *kt, *kn;
  PetscReal *pt, *pn;      /* the state at rest's dF/du and dN/dv: kt, kn if n0 > 0, else 0 */
  PetscInt  *eidx;         /* the model's element number of each local element */
  PetscReal *Kc;           /* stuck basis: the stuck springs of this rank's elements in contact at rest (nm x nm) */
  PetscReal *R0, *S0;      /* joints in a stuck basis: the members' own rows until Kc is formed */
  PetscInt  *qo, *qw;      /* condensed: per element (2 e: tangential, 2 e + 1: normal) the first of its joint's rows of
                              that direction among the nq condensed ones, and their number */
  PetscReal *Ct, *Cn;      /* condensed: its rows' coefficients on them (nloc x cw, column-major) */
  PetscInt   cw;           /* the most rows of a joint in one direction */
  PetscReal *Kq;           /* condensed, split: the elements' Jacobian at rest on the rows, sum pt c c^T and pn d d^T
                              (nq x nq, nonzero on each joint direction's block), formed on first use */
  PetscInt  *qb;           /* its blocks: qb[r] the width of the block that starts at row r, else 0 (nq) */
} JRHBMGroup;

struct _p_JRHBM {
  MPI_Comm          comm;
  PetscMPIInt       rank, size;
  JRModel           model;
  JRElements        el;           /* JRHBMSetElements(): the contact elements (a copy), else the model's */
  PetscBool         el_given;
  JRModes           modes;
  PetscBool         setupcalled, physical, view;
  PetscInt          H, Ns, nm, nc, n, nmodes_opt;
  PetscReal         gamma, zeta;
  PetscBool         has_C;
  PetscReal        *Km, *Mm, *Cm; /* nm x nm row-major */
  PetscReal        *omega_r;      /* natural frequencies of the modes kept [rad/s] */
  PetscReal        *pin;          /* rigid-body modes: the mean equation a0_r pin_r = 0 (else 0 = 0) */
  JRHBMBasis        basis;        /* -hbm_basis */
  char              prefix[64];   /* JRHBMSetOptionsPrefix(): before hbm_ on the nested solver's options */
  char              snesprefix[80]; /* prefix + "hbm_" */
  PetscInt          nfree;        /* mixed: free-interface modes added (-1: as many as stuck ones) */
  PetscBool         basis_set;
  PetscReal        *Kg;           /* the structure's own stiffness in the basis (structural damping gamma Kg) */
  PetscReal        *Kc;           /* stuck basis: the stuck springs in Km of this rank's elements (or members), nm x nm */
  PetscBool         jresid;       /* JRHBMSetJointResidual(): Kc leaves the members' springs on their residual motion */
  PetscBool         modes_shared; /* JRHBMSetModes(): the modes are another JRHBM's (a reference), not solved here */
  char              modes_file[PETSC_MAX_PATH_LEN]; /* JRHBMSetModesFile(): save the modes here unless -modes_load/-modes_save */
  PetscInt          fdof, nout, *outdof;
  PetscBool         fdof_set;      /* JRHBMSetExcitationDof() called: -frf_dof ignored */
  PetscInt          npts, ptdir;   /* JRHBMSetOutputPoints(): the response points, for naming the outputs */
  PetscReal        *ptxyz;        /* npts x 3 [m], NULL if none */
  char              ffile[PETSC_MAX_PATH_LEN];
  PetscReal        *fm, level;    /* modal force shape (unit level) and the level [N] */
  PetscReal         rscale;       /* the excitation's norm in the solve space (condensed: the joints' static motion under it) */
  PetscReal         acctol;       /* -hbm_residual_tol: a solution has ||R|| <= acctol rscale */
  PetscReal        *Phiout;       /* nout x nm */
  JRHBMJacobianType jtype;
  PetscInt          ngroups;
  JRHBMGroup       *g;
  SNES              snes;
  Mat               J;
  Vec               r;
  PetscReal         omega;        /* frequency seen by the SNES callbacks */
  PetscReal        *buf;          /* n + n*n reduction buffer */
  PetscReal        *cache_a;      /* the unknowns at which the groups' forces and derivatives were evaluated */
  PetscBool         cache_ok;
  PetscLogDouble    telem;        /* wall time in JRHBMNonlinear(): the elements' forces and Jacobians, with their sums over ranks */
  PetscInt          nelem, nelemjac; /* its calls, and those with a Jacobian */
  char              damping[256];
  /* condensation onto the joints (-hbm_condense): the linear part is solved exactly for the joints' motions */
  JRHBMCondense     condense;
  PetscBool         repl;         /* a reduced model on several ranks: every rank evaluates all its (few) elements, so
                                     the per-iteration sum over the ranks is not needed */
  MPI_Comm          ecomm;        /* the communicator of sums over the elements: h->comm, or PETSC_COMM_SELF if repl */
  MPI_Comm          gcomm;        /* JRHBMSetLocal(): h->comm while the rank works alone */
  PetscMPIInt       grank, gsize;
  PetscBool         local;
  PetscBool         replopt;      /* -hbm_elements_replicated */
  PetscLogDouble    telem0;       /* telem, nelem, nelemjac when local began */
  PetscInt          nelem0, nelemjac0;
  JRJointMotion     jmotion;      /* first reduction: how a joint's members move (-rom_joint_motion) */
  PetscBool         cond;         /* in use: the solve space is the joints' motions */
  PetscBool         jprod;        /* -hbm_condense_products: JRHBMJacobianSetPoint keeps a condensed Jacobian for its products */
  PetscInt          nq, ns;       /* condensed rows (a basis of each joint's elements' rows, joint by joint); solve-space size */
  PetscReal        *Q, *V, *lamv, *cv, *QV, *VF; /* rows (nq x nm row-major); (Kg, Mm) eigenvectors (col-major), values,
                                                     V^T Cm V (diagonal); Q V (nq x nm row-major); V^T fm */
  PetscReal        *Z0, *G0;      /* the mean block Kg + pin, LU-factored (nm x nm); Q Z0^-1 Q^T (nq x nq) */
  PetscBLASInt     *piv0;
  PetscReal        *Gb, *inv;     /* per harmonic: G (re, im) at frequency wq; 1/z_k and d(1/z_k)/dw (re, im) at wi */
  PetscReal        *QQ, *cb;      /* CondBlocks work: (Q V)^T scaled (nm x nq); JRHBMCondApply's products (6 nm + 4 nq) */
  PetscReal        *jres;         /* JRHBMComputeJacobian: the residual it also computes (ns) */
  PetscInt          njb, *jidx, *jio, *dbo; /* condensed: the joints; their unknowns joint by joint (each joint's rows in
                                     the mean, then in the sin and cos of each harmonic), jidx[jio[j]..jio[j+1]) joint j's;
                                     its block's offset in Db (njb + 1 each) */
  PetscInt         *qj, *ql;      /* condensed: each row's joint, and its place among the joint's rows (nq each) */
  PetscReal        *Db, *ju, jw;  /* condensed, the Jacobian at a point (JRHBMCondJacobianPoint): dg/dx by its joints' blocks
                                     (joint j's, b x b column-major on its unknowns jidx[jio[j]..], at dbo[j]), work (ns),
                                     the point's frequency */
  PetscReal        *pptab;        /* JRHBMResponse: sin, cos of each harmonic at 16 nc samples of a cycle */
  PetscReal         wq, wi;
  PetscBool         wq_ok, wi_ok;
  char              condinfo[256];
  PetscReal        *ctmp;         /* ns work */
  PetscReal        *llu;          /* JRHBMLinearSolution(): LU of the Jacobian (ns x ns) and its pivots */
  PetscBLASInt     *lpiv;
  /* the extended periodic motion concept (JRHBMSetEPMC, src/hbm/epmc.c): no excitation, a negative mass-proportional
     damping -xi Mm, the stuck mode of interest epsi (M-normalised, nm) and its mass-weighted row ep = Mm epsi */
  PetscBool         epmc;
  PetscInt          emode;
  PetscReal         eomega;
  PetscReal        *epsi, *ep, *ework; /* ework: n + n^2 + n */
  struct _JRHill   *hill;         /* JRHBMFloquet(): the work of Hill's method (src/hbm/hill.c) */
  struct _JRMonodromy *mono;      /* JRHBMFloquetTime(): the work of the time-domain Floquet exponents (src/hbm/floquet.c) */
  PetscInt          monond;       /* the distinct rows the last monodromy condensed the fast modes through (0: none) */
  PetscInt          monolr;       /* JRHBMSetFloquetLowRank(): the fast modes condensed through the distinct rows (0 no, 1 auto, 2 yes) */
  PetscReal         monofast;     /* JRHBMSetFloquetFast(): kept modes above monofast x H w quasi-static there (0: none) */
  PetscBool         monomarch;    /* JRHBMSetFloquetUnread(): the slips not read before their first commit marched too */
  PetscInt          mononp;       /* the slips JRHBMFloquetTime left out of the march at its last point */
  PetscBool         monowood;     /* JRHBMSetFloquetWoodbury(): the fast block's inverse updated from the last step map's */
  PetscInt          monowu;       /* the updates so at JRHBMFloquetTime's last point */
  PetscInt          dissip;       /* JRHBMStabilityVerdict(): 0 not yet known, 1 no certificate (smooth or other elements, or
                                     a linear part that is not dissipative), 2 every element jenkins, 3 jenkins and
                                     jenkins_nv (decided per point) */
  PetscBool         fric;         /* JRHBMStabilityVerdict(): the model has friction elements (jenkins, jenkins_nv) */
};

/* C = alpha op(A) op(B) + beta C, column-major (BLAS gemm; k = 0 only scales C) */
PETSC_INTERN PetscErrorCode JRGemm(const char *, const char *, PetscInt, PetscInt, PetscInt, PetscReal, const PetscReal *, PetscInt, const PetscReal *, PetscInt, PetscReal, PetscReal *, PetscInt);

/* src/hbm/basis.c: the modal basis, the element groups and their projection rows, the stuck structure */
PETSC_INTERN PetscErrorCode JRHBMSetUpBasis(JRHBM, Mat, Mat, Mat, PetscInt, const JRElements *);
PETSC_INTERN PetscErrorCode JRHBMSetUpExcitation(JRHBM, PetscInt);
PETSC_INTERN PetscErrorCode JRHBMSetUpGroups(JRHBM, const JRElements *, const PetscReal[]);
PETSC_INTERN PetscErrorCode JRHBMSetUpStuckSprings(JRHBM, const JRElements *);
PETSC_INTERN PetscErrorCode JRHBMGroupDestroy(JRHBMGroup *);
PETSC_INTERN PetscErrorCode JRHBMProjectionRowsDir(JRHBM, PetscInt, const PetscInt[], const PetscInt[], const PetscInt[], const PetscReal[], PetscReal[]);

/* src/hbm/residual.c: the residual and Jacobian, the solver at fixed frequency */
PETSC_INTERN PetscErrorCode JRHBMNonlinear(JRHBM, const PetscReal *, PetscReal *, PetscReal *);
PETSC_INTERN PetscErrorCode JRHBMGroupMotion(JRHBM, JRHBMGroup *, const PetscReal *);
PETSC_INTERN PetscErrorCode JRHBMSetUpSolver(JRHBM);
PETSC_INTERN PetscErrorCode JRHBMLinear(JRHBM, PetscReal, const PetscReal *, PetscReal *, PetscReal *, PetscReal *);

/* src/hbm/hill.c: Floquet exponents */
PETSC_INTERN PetscErrorCode JRHBMHillDestroy(JRHBM);
PETSC_INTERN PetscErrorCode JRHBMMonodromyDestroy(JRHBM);

/* src/hbm/condense.c: the condensation onto the joints */
PETSC_INTERN PetscErrorCode JRHBMCondenseSetUp(JRHBM, const JRElements *);
PETSC_INTERN PetscErrorCode JRHBMCondApply(JRHBM, PetscReal, const PetscReal *, PetscReal *, PetscReal *);
PETSC_INTERN PetscErrorCode JRHBMCondJacobianPoint(JRHBM, PetscReal, const PetscReal *, PetscReal *);
PETSC_INTERN PetscErrorCode JRHBMCondJacobianMult(JRHBM, const PetscReal *, PetscReal *);
PETSC_INTERN PetscErrorCode JRHBMCondJacobianForm(JRHBM, PetscReal *, PetscInt);

/* src/reduce/fields.c: the reduced model's joint motion fields. A joint's field is linear in JR_NF coordinates of its
   members: their position x, y, z [m] (-rom_joint_motion linear, mode), their tangential and normal motions in the
   stuck mode of interest (mode, shapes; JRElements phi) and their tangential motions in the released modes (shapes;
   JRElements phir, JR_NREL; shapes fits the tangential rows on the positions and the tangential motions, the normal
   rows on the normal motion). Its description, fw = 1 + nr (JR_NF + (1 + JR_NF) nm) numbers per
   joint: the members fitted, then per set of rows (tangential, then normal if nr = 2) the members' mean coordinates
   cbar, the mean rows (nm) and the gradient rows B (JR_NF nm, B[JR_NF i + c]) */
#define JR_NF (5 + JR_NREL)
#define JR_FIELD_WIDTH(nr, nm) (1 + (nr) * (JR_NF + (1 + JR_NF) * (nm)))
PETSC_INTERN PetscErrorCode JRJointAverage(JRHBM, const JRElements *, PetscInt, const PetscInt[], PetscReal[], PetscReal[]);
PETSC_INTERN PetscErrorCode JRJointRows(JRHBM, const JRElements *, PetscBool, PetscReal[], PetscReal[]);
PETSC_INTERN PetscErrorCode JRJointFieldRows(JRHBM, const JRElements *, PetscInt, const PetscInt[], const PetscReal[], PetscInt, PetscReal[]);

#endif
