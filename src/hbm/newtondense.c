/* SNESNEWTONDENSE ("newtondense"): Newton's method for the small dense systems of harmonic balance and of the
   continuation's bordered corrector, on one rank (PETSC_COMM_SELF; a distributed element set is summed inside the
   residual). The harmonic-balance unknowns number tens to a few hundred and a reduced model's a few tens: PETSc's
   newtonls + KSPPREONLY + PCLU then spends most of an iteration in per-call bookkeeping (options lookups in
   SNESComputeJacobian, matrix assembly, the factor object, the line-search object), not in the residual or the LU.
   This type does the same Newton iteration with LAPACK's LU on the Jacobian's array and a backtracking line search
   on ||F||^2 (sufficient decrease 1e-4, quadratic interpolation, as newtonls's default "bt"), and uses SNES's own
   tolerances, convergence test, monitors and reasons. -hbm_snes_type newtonls gives PETSc's Newton with its KSP/PC
   and line-search options; -hbm_snes_test_jacobian and -hbm_snes_compare_* route the Jacobian through
   SNESComputeJacobian, which runs them.

   The LU of one iteration's Jacobian stays as the preconditioner of the next solves (JRDenseLU, below): GMRES with
   it solves a later Jacobian in a few matrix-vector products where the Jacobian has changed little (the next
   iterations, the next points of a continuation) at a fraction of a new LU; it refactors when GMRES would need more
   than -snes_newtondense_reuse_its iterations (default 12, never more than n/16: the products then cost as much as
   the LU; 0: a new LU at every iteration). Each step is solved to 1e-3 of the residual at which the iteration stops,
   relative to the current one (at most 1e-2, at least 1e-12): its error is below anything the convergence test
   sees, so the iterations are those of the exact Newton method. A column that is a unit vector but for the last row
   (a model condensed onto its joints: a joint whose elements are all apart over the cycle, the gap elements of open
   pairs, moves no force) is eliminated before the LU, exactly: lap3's reduced model factors 163 of its 253 unknowns
   at its lower levels. */
#include <petsc/private/snesimpl.h>
#include <petscblaslapack.h>
#include <jointrom.h>

struct _n_JRDenseLU {
  PetscInt      n;        /* the size the arrays are allocated for */
  PetscScalar  *lu;       /* n x n, the LU factors of an earlier matrix */
  PetscBLASInt *piv;      /* n, LAPACK's pivots */
  PetscBool     factored; /* lu holds factors of an n x n matrix */
  PetscBool     eliminate; /* unit columns eliminated before the LU (-snes_newtondense_eliminate) */
  PetscInt      np, ns;   /* the factors are of the np x np matrix left when the ns unit columns are eliminated (ns 0: of the whole) */
  PetscInt     *ip, *is;  /* the rows and columns kept (np, the last row n - 1 last) and the unit ones (ns) */
  PetscScalar  *asp, *als; /* A's rows is at columns ip (ns x np, column-major), and its last row at columns is (ns) */
  PetscInt      maxit;    /* GMRES iterations before a new LU (0: a new LU every solve) */
  PetscReal     rtol;     /* GMRES's relative residual for the current solve */
  PetscScalar  *V, *Hs, *g, *cs, *sn, *b, *w, *z; /* Krylov basis n x (maxit + 1), Hessenberg, rotations, rhs, work (w: 2 n, z its second half) */
  PetscInt      vit;      /* the maxit V is allocated for */
  PetscInt      factorisations, solves, its;
};

/* A dense solver for a sequence of slowly changing n x n matrices */
PetscErrorCode JRDenseLUCreate(JRDenseLU *d)
{
  PetscFunctionBegin;
  PetscCall(PetscNew(d));
  (*d)->maxit     = 12;
  (*d)->eliminate = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode JRDenseLUDestroy(JRDenseLU *d)
{
  PetscFunctionBegin;
  if (!*d) PetscFunctionReturn(0);
  PetscCall(PetscFree2((*d)->lu, (*d)->piv));
  PetscCall(PetscFree4((*d)->ip, (*d)->is, (*d)->asp, (*d)->als));
  PetscCall(PetscFree7((*d)->V, (*d)->Hs, (*d)->g, (*d)->cs, (*d)->sn, (*d)->b, (*d)->w));
  PetscCall(PetscFree(*d));
  PetscFunctionReturn(0);
}

/* Factorisations, solves and GMRES iterations so far */
PetscErrorCode JRDenseLUGetCounts(JRDenseLU d, PetscInt *factorisations, PetscInt *solves, PetscInt *its)
{
  PetscFunctionBegin;
  if (factorisations) *factorisations = d->factorisations;
  if (solves) *solves = d->solves;
  if (its) *its = d->its;
  PetscFunctionReturn(0);
}

/* Whether unit columns are eliminated before the LU (default yes; the same solution to round-off) */
PetscErrorCode JRDenseLUSetEliminate(JRDenseLU d, PetscBool eliminate)
{
  PetscFunctionBegin;
  d->eliminate = eliminate;
  PetscFunctionReturn(0);
}

PetscErrorCode JRDenseLUGetEliminate(JRDenseLU d, PetscBool *eliminate)
{
  PetscFunctionBegin;
  *eliminate = d->eliminate;
  PetscFunctionReturn(0);
}

/* The order of the matrix last factored: n, or less the unit columns eliminated */
PetscErrorCode JRDenseLUGetFactoredSize(JRDenseLU d, PetscInt *np)
{
  PetscFunctionBegin;
  *np = d->np;
  PetscFunctionReturn(0);
}

/* The factors are of no use for the next matrix (a different problem) */
PetscErrorCode JRDenseLUForget(JRDenseLU d)
{
  PetscFunctionBegin;
  d->factored = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* w <- M^-1 w, M the matrix factored (Factor): with unit columns eliminated, the kept unknowns from the matrix left,
   whose last row has taken the unit columns' entries, then the unit ones by their rows */
static PetscErrorCode ApplyFactors(JRDenseLU d, PetscInt n, PetscScalar *w)
{
  PetscBLASInt bn, one = 1, info;

  PetscFunctionBegin;
  if (!d->ns) {
    PetscCall(PetscBLASIntCast(n, &bn));
    PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bn, &one, d->lu, &bn, d->piv, w, &bn, &info));
    PetscFunctionReturn(0);
  }
  {
    const PetscInt np = d->np, ns = d->ns;
    PetscScalar   *wp = d->z, *ws = d->z + np, sone = 1.0, smone = -1.0;
    PetscBLASInt   bp, bs;
    for (PetscInt i = 0; i < np; i++) wp[i] = w[d->ip[i]];
    for (PetscInt i = 0; i < ns; i++) {
      ws[i] = w[d->is[i]];
      wp[np - 1] -= d->als[i] * ws[i];
    }
    PetscCall(PetscBLASIntCast(np, &bp));
    PetscCall(PetscBLASIntCast(ns, &bs));
    PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bp, &one, d->lu, &bp, d->piv, wp, &bp, &info));
    PetscCallBLAS("BLASgemv", BLASgemv_("N", &bs, &bp, &smone, d->asp, &bs, wp, &one, &sone, ws, &one));
    for (PetscInt i = 0; i < np; i++) w[d->ip[i]] = wp[i];
    for (PetscInt i = 0; i < ns; i++) w[d->is[i]] = ws[i];
  }
  PetscFunctionReturn(0);
}

/* LU factors of the n x n A (leading dimension lda) into d. A column j < n - 1 that is the unit vector e_j in every
   row but the last (a condensed model's joint whose elements are all apart: no force, no derivative) makes its unknown
   x_j = b_j - A_j. x an explicit function of the others, and only the matrix of the other columns is factored, its last
   row less A_{n-1,j} A_j. (the bordered systems' row; 0 otherwise): exact, and where joints are apart far smaller.
   *singular on an exactly zero pivot. */
static PetscErrorCode Factor(JRDenseLU d, PetscInt n, const PetscScalar *A, PetscInt lda, PetscBool *singular)
{
  PetscBLASInt bp, info;
  PetscInt     np = 0, ns = 0;

  PetscFunctionBegin;
  if (!d->ip) PetscCall(PetscMalloc4(n, &d->ip, n, &d->is, n * n, &d->asp, n, &d->als));
  for (PetscInt j = 0; j < n - 1 && d->eliminate; j++) {
    const PetscScalar *a    = A + j * lda;
    PetscBool          unit = (PetscBool)(a[j] == 1.0);
    for (PetscInt i = 0; i < n - 1 && unit; i++) unit = (PetscBool)(i == j || a[i] == 0.0);
    if (unit) d->is[ns++] = j;
    else d->ip[np++] = j;
  }
  d->ip[np++] = n - 1;
  if (ns < n / 8 || !d->eliminate) { /* too few to gain: the whole matrix */
    np = n;
    ns = 0;
    for (PetscInt j = 0; j < n; j++) PetscCall(PetscArraycpy(d->lu + j * n, A + j * lda, n));
  } else {
    for (PetscInt q = 0; q < np; q++) {
      const PetscScalar *a = A + d->ip[q] * lda;
      PetscScalar       *l = d->lu + q * np;
      for (PetscInt p = 0; p < np; p++) l[p] = a[d->ip[p]];
      for (PetscInt i = 0; i < ns; i++) {
        d->asp[i + q * ns] = a[d->is[i]];
        l[np - 1] -= A[(n - 1) + d->is[i] * lda] * a[d->is[i]];
      }
    }
    for (PetscInt i = 0; i < ns; i++) d->als[i] = A[(n - 1) + d->is[i] * lda];
  }
  d->np = np;
  d->ns = ns;
  PetscCall(PetscBLASIntCast(np, &bp));
  PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bp, &bp, d->lu, &bp, d->piv, &info));
  PetscCheck(info >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK getrf: argument %d", (int)-info);
  *singular = info > 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscLogFlops(2.0 * np * np * np / 3.0 + 2.0 * ns * np));
  PetscFunctionReturn(0);
}

/* Right-preconditioned GMRES (classical Gram-Schmidt twice) on A y = b from y = 0, A applied by op, with the factors
   as preconditioner, at most m iterations: y = M^-1 V_k z; *conv when the true residual is within rtol ||b|| */
static PetscErrorCode DenseGMRES(JRDenseLU d, PetscInt n, const JRDenseOp *op, PetscInt m, const PetscScalar *b, PetscScalar *y, PetscBool *conv, PetscInt *its)
{
  PetscBLASInt    bn, one = 1, bk;
  PetscReal       bnorm;
  PetscScalar     sone = 1.0, szero = 0.0, smone = -1.0;
  PetscScalar    *V = d->V, *H = d->Hs, *g = d->g, *w = d->w;
  const PetscInt  ldh = m + 1;
  PetscInt        k = 0;

  PetscFunctionBegin;
  *conv = PETSC_FALSE;
  *its  = 0;
  PetscCall(PetscBLASIntCast(n, &bn));
  bnorm = BLASnrm2_(&bn, b, &one);
  if (bnorm == 0) {
    PetscCall(PetscArrayzero(y, n));
    *conv = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < n; i++) V[i] = b[i] / bnorm;
  PetscCall(PetscArrayzero(g, m + 1));
  g[0] = bnorm;
  for (k = 0; k < m; k++) {
    PetscScalar *vk = V + k * n, *vn = V + (k + 1) * n, *h = H + k * ldh;
    PetscReal    hn;
    /* vn = A M^-1 vk */
    PetscCall(PetscArraycpy(w, vk, n));
    PetscCall(ApplyFactors(d, n, w));
    PetscCall((*op->mult)(op->ctx, w, vn));
    /* orthogonalised against V_k twice */
    PetscCall(PetscBLASIntCast(k + 1, &bk));
    PetscCall(PetscArrayzero(h, k + 2));
    for (PetscInt pass = 0; pass < 2; pass++) {
      PetscScalar c[64];
      PetscCallBLAS("BLASgemv", BLASgemv_("T", &bn, &bk, &sone, V, &bn, vn, &one, &szero, c, &one));
      PetscCallBLAS("BLASgemv", BLASgemv_("N", &bn, &bk, &smone, V, &bn, c, &one, &sone, vn, &one));
      for (PetscInt i = 0; i <= k; i++) h[i] += c[i];
    }
    hn       = BLASnrm2_(&bn, vn, &one);
    h[k + 1] = hn;
    if (hn > 0) for (PetscInt i = 0; i < n; i++) vn[i] /= hn;
    /* the earlier rotations on the new column, then one that zeroes h[k+1] */
    for (PetscInt i = 0; i < k; i++) {
      const PetscScalar t = d->cs[i] * h[i] + d->sn[i] * h[i + 1];
      h[i + 1]            = -d->sn[i] * h[i] + d->cs[i] * h[i + 1];
      h[i]                = t;
    }
    {
      const PetscReal r = PetscSqrtReal(h[k] * h[k] + h[k + 1] * h[k + 1]);
      if (r == 0) break; /* A M^-1 singular on the Krylov space */
      d->cs[k] = h[k] / r;
      d->sn[k] = h[k + 1] / r;
      h[k]     = r;
      h[k + 1] = 0;
      g[k + 1] = -d->sn[k] * g[k];
      g[k]     = d->cs[k] * g[k];
    }
    if (PetscAbsScalar(g[k + 1]) <= 0.1 * d->rtol * bnorm || hn == 0) {
      k++;
      break;
    }
    if (k >= 2) { /* at the mean rate so far it would not converge within m: a new LU costs less than going on */
      const PetscReal rate = PetscPowReal(PetscAbsScalar(g[k + 1]) / bnorm, 1.0 / (k + 1));
      if (PetscAbsScalar(g[k + 1]) * PetscPowReal(rate, (PetscReal)(m - k - 1)) > 10.0 * d->rtol * bnorm) {
        *its = k + 1;
        PetscCall(PetscLogFlops((2.0 * n * n + 8.0 * n * k) * k));
        PetscFunctionReturn(0);
      }
    }
  }
  *its = k;
  if (!k) PetscFunctionReturn(0);
  /* z = R^-1 g, y = M^-1 V_k z */
  for (PetscInt i = k - 1; i >= 0; i--) {
    for (PetscInt j = i + 1; j < k; j++) g[i] -= H[i + j * ldh] * g[j];
    g[i] /= H[i + i * ldh];
  }
  PetscCall(PetscBLASIntCast(k, &bk));
  PetscCallBLAS("BLASgemv", BLASgemv_("N", &bn, &bk, &sone, V, &bn, g, &one, &szero, y, &one));
  PetscCall(ApplyFactors(d, n, y));
  /* the true residual decides */
  PetscCall((*op->mult)(op->ctx, y, d->z));
  for (PetscInt i = 0; i < n; i++) w[i] = b[i] - d->z[i];
  *conv = BLASnrm2_(&bn, w, &one) <= d->rtol * bnorm ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscLogFlops((2.0 * n * n + 8.0 * n * k) * k + 2.0 * n * n));
  PetscFunctionReturn(0);
}

/* The products of a dense matrix held as an array */
typedef struct {
  const PetscScalar *A;
  PetscBLASInt       n, lda;
} DenseArray;

static PetscErrorCode DenseArrayMult(void *ctx, const PetscScalar *x, PetscScalar *y)
{
  DenseArray  *da  = (DenseArray *)ctx;
  PetscScalar  one = 1.0, zero = 0.0;
  PetscBLASInt ione = 1;

  PetscFunctionBegin;
  PetscCallBLAS("BLASgemv", BLASgemv_("N", &da->n, &da->n, &one, da->A, &da->lda, x, &ione, &zero, y, &ione));
  PetscFunctionReturn(0);
}

/* x <- A^-1 x for a dense n x n A (column-major, leading dimension lda): by GMRES with the factors of an earlier
   matrix to the relative residual rtol (at most 1e-2; 0: 1e-12) where it gets there within the iterations allowed
   (at most n/16: beyond, a new LU costs less), else by a new LU, which the next solves then use; *singular on an
   exactly zero pivot (x is then unchanged) */
PetscErrorCode JRDenseLUSolve(JRDenseLU d, PetscInt n, const PetscScalar *A, PetscInt lda, PetscReal rtol, PetscScalar *x, PetscBool *singular)
{
  DenseArray da;
  JRDenseOp  op = {DenseArrayMult, NULL, &da};

  PetscFunctionBegin;
  da.A = A;
  PetscCall(PetscBLASIntCast(n, &da.n));
  PetscCall(PetscBLASIntCast(lda, &da.lda));
  PetscCall(JRDenseLUSolveOp(d, n, &op, (PetscScalar *)A, lda, rtol, x, singular));
  PetscFunctionReturn(0);
}

/* JRDenseLUSolve() for a matrix given by its products (op->mult) and written into A (leading dimension lda) by
   op->form only when a new LU is needed; op->form NULL: A holds the matrix already */
PetscErrorCode JRDenseLUSolveOp(JRDenseLU d, PetscInt n, const JRDenseOp *op, PetscScalar *A, PetscInt lda, PetscReal rtol, PetscScalar *x, PetscBool *singular)
{
  const PetscInt m = PetscMin(PetscMin(d->maxit, n / 16), 60);

  PetscFunctionBegin;
  *singular = PETSC_FALSE;
  d->rtol   = rtol > 0 ? PetscMin(rtol, 1e-2) : 1e-12;
  d->solves++;
  if (n != d->n) {
    PetscCall(PetscFree2(d->lu, d->piv));
    PetscCall(PetscFree4(d->ip, d->is, d->asp, d->als));
    PetscCall(PetscFree7(d->V, d->Hs, d->g, d->cs, d->sn, d->b, d->w));
    PetscCall(PetscMalloc2(n * n, &d->lu, n, &d->piv));
    d->n        = n;
    d->vit      = -1;
    d->factored = PETSC_FALSE;
  }
  if (m != d->vit) { /* m = 0: the work vectors alone (the factors' solve) */
    PetscCall(PetscFree7(d->V, d->Hs, d->g, d->cs, d->sn, d->b, d->w));
    PetscCall(PetscMalloc7(n * (m + 1), &d->V, (m + 1) * m, &d->Hs, m + 1, &d->g, m, &d->cs, m, &d->sn, n, &d->b, 2 * n, &d->w));
    d->z = d->w + n;
    d->vit = m;
  }
  if (d->factored && m > 0) {
    PetscBool conv;
    PetscInt  its;
    PetscCall(PetscArraycpy(d->b, x, n));
    PetscCall(PetscLogEventBegin(JR_DenseGMRES, 0, 0, 0, 0));
    PetscCall(DenseGMRES(d, n, op, m, d->b, x, &conv, &its));
    PetscCall(PetscLogEventEnd(JR_DenseGMRES, 0, 0, 0, 0));
    d->its += its;
    if (conv) PetscFunctionReturn(0);
    PetscCall(PetscArraycpy(x, d->b, n));
  }
  d->factored = PETSC_FALSE;
  d->factorisations++;
  if (op->form) PetscCall((*op->form)(op->ctx, A, lda));
  PetscCall(PetscLogEventBegin(JR_DenseLU, 0, 0, 0, 0));
  PetscCall(Factor(d, n, A, lda, singular));
  if (!*singular) PetscCall(ApplyFactors(d, n, x));
  PetscCall(PetscLogEventEnd(JR_DenseLU, 0, 0, 0, 0));
  d->factored = !*singular;
  PetscFunctionReturn(0);
}

typedef struct {
  JRDenseLU     lu;       /* the Jacobian's factors, kept as the next solves' preconditioner */
  JRDenseOp     op;       /* SNESNewtonDenseSetOperator(): the Jacobian's products, and its array written only for an LU */
  PetscInt      n;        /* the size of the last solve */
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
  nd->n = n;
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

/* Y = J^-1 F with J in A (dense), or given by the operator (A then written only for an LU), to the relative
   residual rtol */
static PetscErrorCode NewtonStep(SNES_NewtonDense *nd, Mat A, Vec F, PetscReal rtol, Vec Y, PetscBool *singular)
{
  PetscScalar *a, *y;
  PetscInt     lda;

  PetscFunctionBegin;
  PetscCall(VecCopy(F, Y));
  PetscCall(MatDenseGetLDA(A, &lda));
  PetscCall(VecGetArray(Y, &y));
  if (nd->op.mult && !nd->standard) {
    PetscCall(MatDenseGetArray(A, &a));
    PetscCall(JRDenseLUSolveOp(nd->lu, nd->n, &nd->op, a, lda, rtol, y, singular));
    PetscCall(MatDenseRestoreArray(A, &a));
  } else {
    PetscCall(MatDenseGetArrayRead(A, (const PetscScalar **)&a));
    PetscCall(JRDenseLUSolve(nd->lu, nd->n, a, lda, rtol, y, singular));
    PetscCall(MatDenseRestoreArrayRead(A, (const PetscScalar **)&a));
  }
  PetscCall(VecRestoreArray(Y, &y));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSolve_NewtonDense(SNES snes)
{
  SNES_NewtonDense *nd = (SNES_NewtonDense *)snes->data;
  Vec               X = snes->vec_sol, F = snes->vec_func, W = snes->work[0], G = snes->work[1], Y = snes->work[2];
  Mat               A, P;
  void             *jctx;
  PetscReal         fnorm, gnorm = 0, ynorm, xnorm, stop;
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
  stop = PetscMax(snes->abstol, snes->rtol * fnorm);
  for (PetscInt it = 0; it < snes->max_its; it++) {
    PetscReal lambda = 1.0;
    PetscBool singular;
    if (nd->standard) PetscCall(SNESComputeJacobian(snes, X, A, P));
    else PetscCall((*jac)(snes, X, A, P, jctx));
    /* the step to 1e-3 of the residual that stops the iteration, relative to this one (an inexact Newton step whose
       error is below what the convergence test sees), at most 1e-2 */
    PetscCall(NewtonStep(nd, A, F, PetscMax(1e-3 * stop / fnorm, 1e-12), Y, &singular));
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
  PetscCall(PetscOptionsBool("-snes_newtondense_eliminate", "Eliminate the Jacobian's unit columns (a condensed model's joints whose elements are all apart) before its LU", "SNESNEWTONDENSE", nd->lu->eliminate, &nd->lu->eliminate, NULL));
  PetscCall(PetscOptionsInt("-snes_newtondense_reuse_its", "GMRES iterations preconditioned by an earlier Jacobian's LU before a new LU (0: a new LU at every iteration)", "SNESNEWTONDENSE", nd->lu->maxit, &nd->lu->maxit, NULL));
  PetscOptionsHeadEnd();
  {
    const char *pre = ((PetscObject)snes)->prefix ? ((PetscObject)snes)->prefix : "";
    PetscCheck(nd->alpha > 0 && nd->alpha < 0.5, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-%ssnes_newtondense_alpha %g: give a value in (0, 0.5)", pre, (double)nd->alpha);
    PetscCheck(nd->minlambda > 0 && nd->minlambda < 1, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-%ssnes_newtondense_minlambda %g: give a value in (0, 1)", pre, (double)nd->minlambda);
    PetscCheck(nd->lu->maxit >= 0 && nd->lu->maxit <= 60, PetscObjectComm((PetscObject)snes), PETSC_ERR_ARG_OUTOFRANGE, "-%ssnes_newtondense_reuse_its %" PetscInt_FMT ": give 0 (a new LU at every iteration) to 60", pre, nd->lu->maxit);
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
  if (iascii) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "  dense LU (LAPACK getrf) of the Jacobian's array; backtracking on ||F||^2/2: alpha %g, min step %g%s\n", (double)nd->alpha, (double)nd->minlambda, nd->standard ? "; Jacobian through SNESComputeJacobian" : ""));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  the LU kept for GMRES on the next Jacobians: up to %" PetscInt_FMT " iterations (at most n/16); %" PetscInt_FMT " LU for %" PetscInt_FMT " solves so far, %" PetscInt_FMT " GMRES iterations\n", nd->lu->maxit, nd->lu->factorisations, nd->lu->solves, nd->lu->its));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESReset_NewtonDense(SNES snes)
{
  SNES_NewtonDense *nd = (SNES_NewtonDense *)snes->data;

  PetscFunctionBegin;
  PetscCall(JRDenseLUForget(nd->lu));
  nd->n = 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESDestroy_NewtonDense(SNES snes)
{
  SNES_NewtonDense *nd = (SNES_NewtonDense *)snes->data;

  PetscFunctionBegin;
  PetscCall(SNESReset_NewtonDense(snes));
  PetscCall(JRDenseLUDestroy(&nd->lu));
  PetscCall(PetscFree(snes->data));
  PetscFunctionReturn(0);
}

/* The dense solver of a newtondense SNES, to share its factors with solves of nearby matrices (the continuation's
   tangent); NULL for another type */
PetscErrorCode SNESNewtonDenseGetDenseLU(SNES snes, JRDenseLU *lu)
{
  PetscBool is;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESNEWTONDENSE, &is));
  *lu = is ? ((SNES_NewtonDense *)snes->data)->lu : NULL;
  PetscFunctionReturn(0);
}

/* SNESNewtonDenseSetOperator - the Jacobian of the next iterations by its products and a function that writes it into
   the Jacobian matrix's array when a new LU is needed: the Jacobian callback then only sets the point (it may leave
   the matrix unwritten when SNESNewtonDenseUsesOperator() says so). NULL: the matrix as the callback writes it. */
PetscErrorCode SNESNewtonDenseSetOperator(SNES snes, const JRDenseOp *op)
{
  PetscBool is;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESNEWTONDENSE, &is));
  if (!is) PetscFunctionReturn(0);
  if (op) ((SNES_NewtonDense *)snes->data)->op = *op;
  else PetscCall(PetscMemzero(&((SNES_NewtonDense *)snes->data)->op, sizeof(JRDenseOp)));
  PetscFunctionReturn(0);
}

/* SNESNewtonDenseUsesOperator - whether the Newton steps take the Jacobian from the operator set by
   SNESNewtonDenseSetOperator() (not when another type, or -snes_test_jacobian and the like, which read the matrix) */
PetscErrorCode SNESNewtonDenseUsesOperator(SNES snes, PetscBool *uses)
{
  PetscBool is;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESNEWTONDENSE, &is));
  *uses = is && ((SNES_NewtonDense *)snes->data)->op.mult && !((SNES_NewtonDense *)snes->data)->standard ? PETSC_TRUE : PETSC_FALSE;
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
  PetscCall(JRDenseLUCreate(&nd->lu));
  snes->data = (void *)nd;
  PetscFunctionReturn(0);
}
