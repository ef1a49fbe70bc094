/* Private: the JRNLModes struct (src/nlmodes/). */
#if !defined(JOINTROM_NLMODESIMPL_H)
#define JOINTROM_NLMODESIMPL_H

#include <jointrom.h>

struct _p_JRNLModes {
  MPI_Comm    comm;
  JRHBM       hbm;
  PetscBool   setupcalled, plot, view, complete;
  PetscInt    mode;             /* -nlm_mode: the elastic stuck mode, 1-based */
  PetscInt    kmode;            /* its index among the stuck modes of the basis (0-based) */
  PetscReal   amin, amax;       /* -nlm_amp_min, -nlm_amp_max: the modal amplitudes [m kg^1/2] (0: from the elements) */
  PetscInt    npts;             /* -nlm_points */
  PetscReal   dmax;             /* -nlm_step_max: the largest step in log10 q between solves */
  PetscInt    maxcuts;          /* -nlm_max_cuts: step halvings before the backbone stops */
  char        out[PETSC_MAX_PATH_LEN]; /* -nlm_output_file */
  char        prefix[64];       /* JRNLModesSetOptionsPrefix(): before nlm_ on the correctors' options */
  PetscInt    n, N, nout;       /* harmonic unknowns, with w and xi, responses */
  PetscReal   w0, xi0;          /* the stuck mode: circular frequency, linear equivalent damping [1/s] */
  PetscReal   q;                /* the modal amplitude the SNES solves at */
  PetscBool   arclength;        /* -nlm_continuation arclength (else natural in log q) */
  SNES        snes;             /* on every rank (PETSC_COMM_SELF), prefix nlm_, on the scaled unknowns */
  Vec         y, f, xr, rr, a;  /* scaled unknowns and residual; raw unknowns and residual; the harmonics (n) */
  Mat         J;
  SNES        snesa;            /* arclength: the same equations bordered by log q and the arclength constraint */
  Vec         z, fz, yv, fv;    /* [y | log q] and its residual (N + 1); views of their first N entries */
  Mat         Ja;
  PetscReal  *zp, *tz;          /* the predictor and the unit tangent (N + 1) */
  /* the backbone, one entry per point */
  PetscInt    np, cap;
  PetscReal  *qs, *omega, *xi, *amp, *as, *bal; /* amp: np x nout; as: np x n */
  PetscInt   *its;
  PetscInt    newton, solves;
  PetscReal   seconds;
};

#endif
