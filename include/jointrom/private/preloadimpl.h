/* Private: the JRPreload struct, its solver's ops table, and the functions its source files share (src/preload/). */
#if !defined(JOINTROM_PRELOADIMPL_H)
#define JOINTROM_PRELOADIMPL_H

#include <jointrom/private/feimpl.h>

#define JR_PRELOAD_MAXBOLTS 256

/* A solver type (-preload_solver): its create function fills these */
typedef struct _JRPreloadOps *JRPreloadOps;
struct _JRPreloadOps {
  PetscErrorCode (*setup)(JRPreload);   /* once the system is set up (JRPreloadSetUpSystem): the solver's own operators */
  PetscErrorCode (*solve)(JRPreload);   /* from the start (-preload_open_start) to the displacement u and the pairs' w */
  PetscErrorCode (*destroy)(JRPreload); /* frees data */
};

struct _p_JRPreload {
  MPI_Comm             comm;
  JRModel              model;
  char                 type_name[64]; /* the solver type */
  struct _JRPreloadOps ops[1];
  void                *data;          /* the solver type's */
  const char          *what;          /* the solver in JRPreloadView's words ("condensed on the interface") */
  /* options */
  PetscInt             nforce;
  PetscReal            force[JR_PRELOAD_MAXBOLTS];
  JRPreloadMethod      method;
  JRPreloadSupport     support;
  PetscReal            kp, eps, rtol, kv, open_gap;
  PetscBool            kp_set, kv_set, open_start;
  PetscInt             maxit;
  char                 load[PETSC_MAX_PATH_LEN];
  PetscReal            load_tol;
  Vec                  fext;
  /* supports: nodes (first global DOF), directions, added to the automatic ones */
  PetscInt             nsup, supcap;
  PetscInt            *supdof;
  PetscReal           *supdir;
  /* the system: Kp (K without the bolts' axial stiffness, with the supports) in a pattern with the pair blocks, the
     loads f, the pair DOFs gathered on every rank (sc: u -> useq) */
  Mat                  Kp, J;
  Vec                  u, f, useq;
  VecScatter           sc;
  PetscInt             np;           /* pairs */
  PetscReal           *k, *lam, *w;  /* per pair: penalty stiffness [N/m], multiplier [N], penetration [m] */
  PetscInt            *closed, *jclosed, nclamp, *clamp;
  PetscReal            diag;
  PetscBool            jvalid;       /* J holds the closed set jclosed */
  /* results (every rank) */
  PetscReal           *N, *gap;
  PetscInt             newton, outer, factorisations;
  PetscReal            time, maxpen;
  PetscBool            solved, loaded;
};

/* The force pressing pair i together [N]: lam_i + k_i w_i when closed, eps times that when open */
static inline PetscReal JRPreloadPairForce(JRPreload p, PetscInt i)
{
  const PetscReal t = p->lam[i] + p->k[i] * p->w[i];
  return t > 0 ? t : p->eps * t;
}

PETSC_INTERN PetscErrorCode JRPreloadSolverCreate_Condensed(JRPreload);
PETSC_INTERN PetscErrorCode JRPreloadSolverCreate_Full(JRPreload);

/* src/preload/preload.c */
PETSC_INTERN PetscErrorCode JRPreloadClearResults(JRPreload);
PETSC_INTERN PetscErrorCode JRPreloadAugmentedLagrangian(JRPreload, SNES, Vec, PetscErrorCode (*)(JRPreload, const JRPairs *, Vec));
/* src/preload/setup.c */
PETSC_INTERN PetscErrorCode JRPreloadSetUpSystem(JRPreload);
PETSC_INTERN PetscErrorCode JRPreloadAssembleJacobian(JRPreload, const JRPairs *, Mat);
/* src/preload/io.c */
PETSC_INTERN PetscErrorCode JRPreloadLoadResults(JRPreload);
PETSC_INTERN PetscErrorCode JRPreloadCheckLoadFile(JRPreload);

#endif
