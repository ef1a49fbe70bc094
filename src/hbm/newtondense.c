/* SNESNEWTONDENSE ("newtondense"): Newton's method for the small dense systems of harmonic balance and of the
   continuation's bordered corrector, on one rank (PETSC_COMM_SELF; a distributed element set is summed inside the
   residual). The harmonic-balance unknowns number tens to a few hundred and a reduced model's a few tens: PETSc's
   newtonls + KSPPREONLY + PCLU then spends most of an iteration in per-call bookkeeping (options lookups in
   SNESComputeJacobian, matrix assembly, the factor object, the line-search object), not in the residual or the LU.
   This type does the same Newton iteration with LAPACK's LU on the Jacobian's array and a backtracking line search
   on ||F||^2 (sufficient decrease 1e-4, quadratic interpolation, as newtonls's default "bt"), and uses SNES's own
   tolerances, convergence test, monitors and reasons. -hbm_snes_type newtonls gives PETSc's Newton with its KSP/PC
   and line-search options; -hbm_snes_test_jacobian and -hbm_snes_compare_* route the Jacobian through
   SNESComputeJacobian, which runs them. */
#include <petsc/private/snesimpl.h>
#include <petscblaslapack.h>
#include <jointrom.h>

typedef struct {
  PetscScalar  *lu;       /* n x n, the LU factors of the Jacobian */
  PetscBLASInt *piv;      /* n, LAPACK's pivots */
  PetscInt      n;        /* the size they are allocated for */
  PetscBool     standard; /* the Jacobian through SNESComputeJacobian (its test and compare options) */
  PetscReal     alpha;    /* sufficient decrease of ||F||^2 / 2 per unit step */
  PetscReal     minlambda;
} SNES_NewtonDense;

static PetscErrorCode SNESSetUp_NewtonDense(SNES snes)
{
  SNES_NewtonDense *nd = (SNES_NewtonDense *)snes->data;
  PetscMPIInt       size;
  PetscInt          n;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)snes), &size));
  PetscCheck(size == 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_SUP, "-snes_type newtondense: a SNES on one rank (PETSC_COMM_SELF) only; use newtonls");
  PetscCheck(!snes->xl && !snes->xu && !snes->ops->computevariablebounds, PETSC_COMM_SELF, PETSC_ERR_SUP, "-snes_type newtondense: no variable bounds; use vinewtonrsls");
  {
    Mat       A;
    PetscBool dense = PETSC_FALSE;
    PetscCall(SNESGetJacobian(snes, &A, NULL, NULL, NULL));
    if (A) PetscCall(PetscObjectTypeCompare((PetscObject)A, MATSEQDENSE, &dense));
    PetscCheck(dense, PETSC_COMM_SELF, PETSC_ERR_SUP, "-snes_type newtondense: the Jacobian must be a MATSEQDENSE matrix (set with SNESSetJacobian()); use newtonls");
  }
  PetscCall(SNESSetWorkVecs(snes, 3)); /* the trial point, its residual, the Newton step */
  PetscCall(VecGetSize(snes->vec_sol, &n));
  if (n != nd->n) {
    PetscCall(PetscFree2(nd->lu, nd->piv));
    PetscCall(PetscMalloc2(n * n, &nd->lu, n, &nd->piv));
    nd->n = n;
  }
  PetscFunctionReturn(0);
}

/* x <- A^-1 x for a dense n x n A (column-major, leading dimension lda), by LAPACK's LU into lu (n x n) with pivots
   piv; *singular on an exactly zero pivot (x is then unchanged) */
PetscErrorCode JRDenseSolve(PetscInt n, const PetscScalar *A, PetscInt lda, PetscScalar *lu, PetscBLASInt *piv, PetscScalar *x, PetscBool *singular)
{
  PetscBLASInt bn, one = 1, info;

  PetscFunctionBegin;
  for (PetscInt j = 0; j < n; j++) PetscCall(PetscArraycpy(lu + j * n, A + j * lda, n));
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, lu, &bn, piv, &info));
  PetscCheck(info >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK getrf: argument %d", (int)-info);
  *singular = info > 0 ? PETSC_TRUE : PETSC_FALSE;
  if (*singular) PetscFunctionReturn(0);
  PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bn, &one, lu, &bn, piv, x, &bn, &info));
  PetscCall(PetscLogFlops(2.0 * n * n * n / 3.0 + 2.0 * n * n));
  PetscFunctionReturn(0);
}

/* Y = J^-1 F with J in A (dense) */
static PetscErrorCode NewtonStep(SNES_NewtonDense *nd, Mat A, Vec F, Vec Y, PetscBool *singular)
{
  const PetscScalar *a;
  PetscScalar       *y;
  PetscInt           lda;

  PetscFunctionBegin;
  PetscCall(VecCopy(F, Y));
  PetscCall(MatDenseGetLDA(A, &lda));
  PetscCall(MatDenseGetArrayRead(A, &a));
  PetscCall(VecGetArray(Y, &y));
  PetscCall(JRDenseSolve(nd->n, a, lda, nd->lu, nd->piv, y, singular));
  PetscCall(VecRestoreArray(Y, &y));
  PetscCall(MatDenseRestoreArrayRead(A, &a));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSolve_NewtonDense(SNES snes)
{
  SNES_NewtonDense *nd = (SNES_NewtonDense *)snes->data;
  Vec               X = snes->vec_sol, F = snes->vec_func, W = snes->work[0], G = snes->work[1], Y = snes->work[2];
  Mat               A, P;
  void             *jctx;
  PetscReal         fnorm, gnorm = 0, ynorm, xnorm;
  PetscErrorCode (*jac)(SNES, Vec, Mat, Mat, void *);

  PetscFunctionBegin;
  snes->numFailures            = 0;
  snes->numLinearSolveFailures = 0;
  snes->reason                 = SNES_CONVERGED_ITERATING;
  snes->iter                   = 0;
  snes->norm                   = 0;
  if (!snes->vec_func_init_set) PetscCall(SNESComputeFunction(snes, X, F));
  else snes->vec_func_init_set = PETSC_FALSE;
  PetscCall(VecNorm(F, NORM_2, &fnorm));
  SNESCheckFunctionNorm(snes, fnorm);
  snes->norm = fnorm;
  PetscCall(SNESLogConvergenceHistory(snes, fnorm, 0));
  PetscCall(SNESMonitor(snes, 0, fnorm));
  PetscUseTypeMethod(snes, converged, 0, 0.0, 0.0, fnorm, &snes->reason, snes->cnvP);
  if (snes->reason) PetscFunctionReturn(0);
  PetscCall(SNESGetJacobian(snes, &A, &P, &jac, &jctx));
  PetscCheck(jac, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONGSTATE, "-snes_type newtondense: set the Jacobian with SNESSetJacobian()");
  for (PetscInt it = 0; it < snes->max_its; it++) {
    PetscReal lambda = 1.0;
    PetscBool singular;
    if (nd->standard) PetscCall(SNESComputeJacobian(snes, X, A, P));
    else PetscCall((*jac)(snes, X, A, P, jctx));
    PetscCall(NewtonStep(nd, A, F, Y, &singular));
    if (singular) {
      snes->reason = SNES_DIVERGED_LINEAR_SOLVE;
      break;
    }
    /* backtracking along -Y: f(lambda) = ||F(X - lambda Y)||^2 / 2, f'(0) = -||F||^2 for the exact Newton step */
    {
      const PetscReal f0 = 0.5 * fnorm * fnorm, slope = -fnorm * fnorm;
      PetscBool       accepted = PETSC_FALSE;
      while (!accepted) {
        PetscReal f;
        PetscBool bad;
        PetscCall(VecWAXPY(W, -lambda, Y, X));
        PetscCall(SNESComputeFunction(snes, W, G));
        PetscCall(VecNorm(G, NORM_2, &gnorm));
        f   = 0.5 * gnorm * gnorm;
        bad = snes->domainerror || PetscIsInfOrNanReal(gnorm) ? PETSC_TRUE : PETSC_FALSE;
        snes->domainerror = PETSC_FALSE;
        if (!bad && f <= f0 + nd->alpha * lambda * slope) {
          accepted = PETSC_TRUE;
          break;
        }
        if (lambda == 1.0 && !bad) { /* the full step did not decrease ||F|| and is below the step tolerance: round-off */
          PetscReal ynorm0, xnorm0;
          PetscCall(VecNorm(Y, NORM_2, &ynorm0));
          PetscCall(VecNorm(X, NORM_2, &xnorm0));
          if (ynorm0 < snes->stol * xnorm0) {
            snes->reason = SNES_CONVERGED_SNORM_RELATIVE;
            break;
          }
        }
        if (bad) lambda *= 0.1; /* outside the residual's domain: a far shorter step */
        else { /* the minimum of the quadratic through f0, slope and f(lambda), kept within [0.1, 0.5] lambda */
          const PetscReal lt = -slope * lambda * lambda / (2.0 * (f - f0 - slope * lambda));
          lambda             = PetscMax(0.1 * lambda, PetscMin(0.5 * lambda, lt));
        }
        if (lambda < nd->minlambda) {
          snes->reason = SNES_DIVERGED_LINE_SEARCH;
          break;
        }
        if (snes->max_funcs >= 0 && snes->nfuncs >= snes->max_funcs) {
          snes->reason = SNES_DIVERGED_FUNCTION_COUNT;
          break;
        }
      }
      if (!accepted) break;
    }
    PetscCall(VecCopy(W, X));
    PetscCall(VecCopy(G, F));
    PetscCall(VecNorm(Y, NORM_2, &ynorm));
    ynorm *= lambda;
    PetscCall(VecNorm(X, NORM_2, &xnorm));
    fnorm       = gnorm;
    snes->iter  = it + 1;
    snes->norm  = fnorm;
    snes->xnorm = xnorm;
    snes->ynorm = ynorm;
    PetscCall(SNESLogConvergenceHistory(snes, fnorm, 0));
    PetscCall(SNESMonitor(snes, snes->iter, fnorm));
    PetscUseTypeMethod(snes, converged, snes->iter, xnorm, ynorm, fnorm, &snes->reason, snes->cnvP);
    if (snes->reason) break;
  }
  if (!snes->reason) snes->reason = SNES_DIVERGED_MAX_IT;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSetFromOptions_NewtonDense(SNES snes, PetscOptionItems *PetscOptionsObject)
{
  SNES_NewtonDense *nd = (SNES_NewtonDense *)snes->data;
  const char *const standard[] = {"-snes_test_jacobian", "-snes_test_jacobian_view", "-snes_compare_explicit", "-snes_compare_coloring", "-snes_compare_explicit_draw", "-snes_compare_explicit_contour"};

  PetscFunctionBegin;
  PetscOptionsHeadBegin(PetscOptionsObject, "SNES newtondense (dense LU, backtracking) options");
  PetscCall(PetscOptionsReal("-snes_newtondense_alpha", "Sufficient decrease of ||F||^2/2 per unit step", "SNESNEWTONDENSE", nd->alpha, &nd->alpha, NULL));
  PetscCall(PetscOptionsReal("-snes_newtondense_minlambda", "Smallest step length before the line search fails", "SNESNEWTONDENSE", nd->minlambda, &nd->minlambda, NULL));
  PetscOptionsHeadEnd();
  {
    const char *pre = ((PetscObject)snes)->prefix ? ((PetscObject)snes)->prefix : "";
    PetscCheck(nd->alpha > 0 && nd->alpha < 0.5, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-%ssnes_newtondense_alpha %g: give a value in (0, 0.5)", pre, (double)nd->alpha);
    PetscCheck(nd->minlambda > 0 && nd->minlambda < 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-%ssnes_newtondense_minlambda %g: give a value in (0, 1)", pre, (double)nd->minlambda);
  }
  nd->standard = PETSC_FALSE;
  for (size_t i = 0; i < sizeof(standard) / sizeof(standard[0]); i++) {
    PetscBool has;
    PetscCall(PetscOptionsHasName(((PetscObject)snes)->options, ((PetscObject)snes)->prefix, standard[i], &has));
    if (has) nd->standard = PETSC_TRUE;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESView_NewtonDense(SNES snes, PetscViewer viewer)
{
  SNES_NewtonDense *nd = (SNES_NewtonDense *)snes->data;
  PetscBool         iascii;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (iascii) PetscCall(PetscViewerASCIIPrintf(viewer, "  dense LU (LAPACK getrf) of the Jacobian's array; backtracking on ||F||^2/2: alpha %g, min step %g%s\n", (double)nd->alpha, (double)nd->minlambda, nd->standard ? "; Jacobian through SNESComputeJacobian" : ""));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESReset_NewtonDense(SNES snes)
{
  SNES_NewtonDense *nd = (SNES_NewtonDense *)snes->data;

  PetscFunctionBegin;
  PetscCall(PetscFree2(nd->lu, nd->piv));
  nd->n = 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESDestroy_NewtonDense(SNES snes)
{
  PetscFunctionBegin;
  PetscCall(SNESReset_NewtonDense(snes));
  PetscCall(PetscFree(snes->data));
  PetscFunctionReturn(0);
}

PetscErrorCode SNESCreate_NewtonDense(SNES snes)
{
  SNES_NewtonDense *nd;

  PetscFunctionBegin;
  snes->ops->setup                  = SNESSetUp_NewtonDense;
  snes->ops->solve                  = SNESSolve_NewtonDense;
  snes->ops->setfromoptions         = SNESSetFromOptions_NewtonDense;
  snes->ops->view                   = SNESView_NewtonDense;
  snes->ops->reset                  = SNESReset_NewtonDense;
  snes->ops->destroy                = SNESDestroy_NewtonDense;
  snes->usesksp                     = PETSC_FALSE;
  snes->usesnpc                     = PETSC_FALSE;
  snes->alwayscomputesfinalresidual = PETSC_TRUE;
  PetscCall(PetscNew(&nd));
  nd->alpha     = 1e-4;
  nd->minlambda = 1e-12;
  snes->data    = (void *)nd;
  PetscFunctionReturn(0);
}
