/*
   Floquet exponents of a harmonic-balance solution by Hill's method (docs/theory.md, section 16): exact up to truncation
   for smooth elements; for friction elements, whose force remembers the last reversal, J + lambda D1 + lambda^2 D2 is
   not the linearisation (floquet.c marches it instead).

   A perturbation exp(lambda t) p(t) of the periodic solution, p over the same harmonics, satisfies

     (J + lambda D1 + lambda^2 D2) p = 0,

   J the harmonic-balance Jacobian dR/da at the point, D2 the mass on every harmonic block, and D1 = 2 M nabla + C on
   the layout [a0 | as_1 ac_1 | ... | as_H ac_H]: the derivative of as_h sin(h w t) + ac_h cos(h w t) has sine
   coefficient -h w ac_h and cosine coefficient h w as_h, so D1 holds -2 h w M in (sine row, cosine column) and
   +2 h w M in (cosine row, sine column), and C on the diagonal blocks. Structural damping gamma Kg, a
   frequency-domain term, is taken as the viscous damping (gamma / w) Kg that it equals at the response frequency
   (the time-integration check's choice, section 14): (gamma / w) Kg in D1 and h gamma Kg on harmonic h of J.

   The quadratic problem is linearised, [0 I; -J -D1] z = lambda [I 0; 0 D2] z, and solved by LAPACK (QZ, dggev)
   or, above -frf_stability_dense_max unknowns, by SLEPc's PEP for the exponents nearest the origin. Of its
   2 n exponents (n = nm (2H + 1), rigid-body modes left out) the 2 nm physical ones are kept: those whose
   eigenvectors are centred on the mean harmonic, ties (energy centroids within 1/2 of each other) to the smaller
   |Im lambda| (JR_HILL_SELECT_VECTOR, the default), or those with |Im lambda| <= w / 2 (JR_HILL_SELECT_IMAG).
*/
#include <jointrom/private/hbmimpl.h>
#include <slepcpep.h>
#include <slepcblaslapack.h>

const char *const JRHillSelects[] = {"vector", "imag", "JRHillSelect", "JR_HILL_SELECT_", NULL};

struct _JRHill {
  PetscInt      nk, *keep;         /* the modes kept: all but the rigid-body ones (pinned mean, section 1) */
  PetscInt      N;                 /* nk (2H + 1) */
  Mat           J;                 /* dR/da (N x N, dense) */
  PetscReal    *JH, *D1, *D2;      /* N x N column-major: J with the structural damping of section 16, D1, D2 */
  PetscReal    *A, *B, *VR, *work; /* 2N x 2N pencil, its right eigenvectors, LAPACK work */
  PetscReal    *ar, *ai, *be, *key, *lu;
  PetscInt     *idx;
  PetscBLASInt *piv, lwork;
  PEP           pep;
  Mat           P[3];
};

/* The work of Hill's method for N unknowns (again if N changed) */
static PetscErrorCode HillWork(JRHBM h)
{
  struct _JRHill *w;
  PetscInt        N, nk = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < h->nm; i++)
    if (!h->pin || h->pin[i] == 0.0) nk++;
  N = nk * h->nc;
  if (h->hill && h->hill->N == N) PetscFunctionReturn(0);
  PetscCall(JRHBMHillDestroy(h));
  PetscCall(PetscNew(&w));
  PetscCall(PetscMalloc1(nk, &w->keep));
  for (PetscInt i = 0; i < h->nm; i++)
    if (!h->pin || h->pin[i] == 0.0) w->keep[w->nk++] = i;
  w->N = N;
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, h->n, h->n, NULL, &w->J));
  PetscCall(PetscMalloc4(N * N, &w->JH, N * N, &w->D1, N * N, &w->D2, h->n * h->n, &w->lu));
  PetscCall(PetscMalloc2(h->n, &w->piv, 2 * N, &w->idx));
  PetscCall(PetscMalloc4(2 * N, &w->ar, 2 * N, &w->ai, 2 * N, &w->be, 2 * N, &w->key));
  h->hill = w;
  PetscFunctionReturn(0);
}

/* Free the work of Hill's method (JRHBMDestroy) */
PetscErrorCode JRHBMHillDestroy(JRHBM h)
{
  struct _JRHill *w = h->hill;

  PetscFunctionBeginUser;
  if (!w) PetscFunctionReturn(0);
  PetscCall(MatDestroy(&w->J));
  PetscCall(PetscFree(w->keep));
  PetscCall(PetscFree4(w->JH, w->D1, w->D2, w->lu));
  PetscCall(PetscFree2(w->piv, w->idx));
  PetscCall(PetscFree4(w->ar, w->ai, w->be, w->key));
  PetscCall(PetscFree3(w->A, w->B, w->VR));
  PetscCall(PetscFree(w->work));
  PetscCall(PEPDestroy(&w->pep));
  for (PetscInt k = 0; k < 3; k++) PetscCall(MatDestroy(&w->P[k]));
  PetscCall(PetscFree(h->hill));
  PetscFunctionReturn(0);
}

/* JH, D1, D2 of the quadratic problem at frequency w from J (column-major, n x n), on the modes kept */
static PetscErrorCode HillMatrices(JRHBM h, PetscReal w, const PetscReal *J)
{
  struct _JRHill *hw = h->hill;
  const PetscInt  nm = h->nm, nk = hw->nk, N = hw->N, n = h->n, *kp = hw->keep;
  PetscReal      *JH = hw->JH, *D1 = hw->D1, *D2 = hw->D2;

  PetscFunctionBeginUser;
  for (PetscInt bj = 0; bj < h->nc; bj++)
    for (PetscInt j = 0; j < nk; j++)
      for (PetscInt bi = 0; bi < h->nc; bi++)
        for (PetscInt i = 0; i < nk; i++) JH[(bi * nk + i) + (bj * nk + j) * N] = J[(bi * nm + kp[i]) + (bj * nm + kp[j]) * n];
  PetscCall(PetscArrayzero(D1, N * N));
  PetscCall(PetscArrayzero(D2, N * N));
  for (PetscInt b = 0; b < h->nc; b++) { /* C + (gamma / w) Kg and M on every diagonal block */
    const PetscInt o = b * nk;
    for (PetscInt i = 0; i < nk; i++)
      for (PetscInt j = 0; j < nk; j++) {
        const PetscInt q = kp[i] * nm + kp[j];
        D1[(o + i) + (o + j) * N] = h->Cm[q] + h->gamma / w * h->Kg[q];
        D2[(o + i) + (o + j) * N] = h->Mm[q];
      }
  }
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    const PetscInt  os = (2 * hh - 1) * nk, oc = 2 * hh * nk;
    const PetscReal hw2 = 2.0 * hh * w, dg = (hh - 1) * h->gamma;
    for (PetscInt i = 0; i < nk; i++)
      for (PetscInt j = 0; j < nk; j++) {
        const PetscInt q = kp[i] * nm + kp[j];
        D1[(os + i) + (oc + j) * N] = -hw2 * h->Mm[q];
        D1[(oc + i) + (os + j) * N] = hw2 * h->Mm[q];
        JH[(os + i) + (oc + j) * N] -= dg * h->Kg[q]; /* gamma Kg -> h gamma Kg: (gamma / w) Kg at h w */
        JH[(oc + i) + (os + j) * N] += dg * h->Kg[q];
      }
  }
  PetscFunctionReturn(0);
}

/* The sign of det(J) by LU (0 if singular) */
static PetscErrorCode DetSign(JRHBM h, const PetscReal *J, PetscInt *sign)
{
  struct _JRHill *hw = h->hill;
  PetscBLASInt    bn, info;
  PetscInt        s = 1;

  PetscFunctionBeginUser;
  PetscCall(PetscBLASIntCast(h->n, &bn));
  PetscCall(PetscArraycpy(hw->lu, J, h->n * h->n));
  PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, hw->lu, &bn, hw->piv, &info));
  PetscCheck(info >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK getrf: argument %d", (int)-info);
  if (info > 0) s = 0;
  for (PetscInt i = 0; i < h->n && s; i++) {
    if (hw->lu[i + i * h->n] < 0) s = -s;
    if (hw->piv[i] != i + 1) s = -s;
  }
  *sign = s;
  PetscFunctionReturn(0);
}

/* Where the eigenvector v = vr + i vi (first N entries of the pencil's vector) lies on the complex harmonics
   exp(i k w t), k = -H..H: its energy-weighted mean k. Harmonic h's as sin + ac cos = c_+ e^{i h wt} + c_- e^{-i h wt},
   c_+- = (ac -+ i as) / 2. */
static PetscReal Centroid(JRHBM h, const PetscReal *vr, const PetscReal *vi)
{
  const PetscInt nm = h->hill->nk;
  PetscReal      num = 0.0, den = 0.0;

  for (PetscInt i = 0; i < nm; i++) den += vr[i] * vr[i] + (vi ? vi[i] * vi[i] : 0.0);
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    const PetscInt os = (2 * hh - 1) * nm, oc = 2 * hh * nm;
    for (PetscInt i = 0; i < nm; i++) {
      const PetscReal sr = vr[os + i], cr = vr[oc + i], si = vi ? vi[os + i] : 0.0, ci = vi ? vi[oc + i] : 0.0;
      const PetscReal ep = 0.25 * ((cr + si) * (cr + si) + (ci - sr) * (ci - sr));
      const PetscReal em = 0.25 * ((cr - si) * (cr - si) + (ci + sr) * (ci + sr));
      num += hh * (ep - em);
      den += ep + em;
    }
  }
  return den > 0 ? num / den : 0.0;
}

/* All 2N exponents by QZ (eigenvectors only for the vector criterion); key: the selection's measure of each (smaller
   is kept first) */
static PetscErrorCode SolveDense(JRHBM h, PetscReal w, JRHillSelect sel, PetscInt *nev)
{
  struct _JRHill *hw = h->hill;
  const PetscInt  N = hw->N, N2 = 2 * N;
  PetscBLASInt    bn, info, one = 1;
  PetscReal       dummy;

  PetscFunctionBeginUser;
  if (!hw->A) {
    PetscReal q;
    PetscCall(PetscMalloc3(N2 * N2, &hw->A, N2 * N2, &hw->B, N2 * N2, &hw->VR));
    PetscCall(PetscBLASIntCast(N2, &bn));
    hw->lwork = -1;
    PetscCallBLAS("LAPACKggev", LAPACKggev_("N", "V", &bn, hw->A, &bn, hw->B, &bn, hw->ar, hw->ai, hw->be, &dummy, &one, hw->VR, &bn, &q, &hw->lwork, &info));
    hw->lwork = (PetscBLASInt)q;
    PetscCall(PetscMalloc1(hw->lwork, &hw->work));
  }
  PetscCall(PetscBLASIntCast(N2, &bn));
  PetscCall(PetscArrayzero(hw->A, N2 * N2));
  PetscCall(PetscArrayzero(hw->B, N2 * N2));
  for (PetscInt i = 0; i < N; i++) {
    hw->A[i + (N + i) * N2] = 1.0;
    hw->B[i + i * N2]       = 1.0;
  }
  for (PetscInt j = 0; j < N; j++)
    for (PetscInt i = 0; i < N; i++) {
      hw->A[(N + i) + j * N2]       = -hw->JH[i + j * N];
      hw->A[(N + i) + (N + j) * N2] = -hw->D1[i + j * N];
      hw->B[(N + i) + (N + j) * N2] = hw->D2[i + j * N];
    }
  PetscCallBLAS("LAPACKggev", LAPACKggev_("N", sel == JR_HILL_SELECT_VECTOR ? "V" : "N", &bn, hw->A, &bn, hw->B, &bn, hw->ar, hw->ai, hw->be, &dummy, &one, hw->VR, &bn, hw->work, &hw->lwork, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "Hill's method: LAPACK ggev failed (info %d) at %g Hz", (int)info, (double)(w / (2 * PETSC_PI)));
  for (PetscInt j = 0; j < N2; j++) {
    const PetscReal *v = hw->VR + j * N2;
    if (hw->be[j] == 0.0) { /* an infinite exponent (singular mass): never kept */
      hw->key[j] = PETSC_MAX_REAL;
      hw->ar[j] = hw->ai[j] = 0.0;
      continue;
    }
    hw->ar[j] /= hw->be[j];
    hw->ai[j] /= hw->be[j];
    if (sel == JR_HILL_SELECT_IMAG) hw->key[j] = PetscAbsReal(hw->ai[j]);
    else if (hw->ai[j] == 0.0) hw->key[j] = PetscAbsReal(Centroid(h, v, NULL));
    else if (j + 1 < N2 && hw->be[j + 1] != 0.0 && hw->ai[j] > 0) { /* a pair: columns j, j + 1 hold Re and Im of the first's vector */
      hw->key[j] = hw->key[j + 1] = PetscAbsReal(Centroid(h, v, v + N2));
      hw->ar[j + 1] = hw->ar[j];
      hw->ai[j + 1] = -hw->ai[j];
      j++;
    } else hw->key[j] = PetscAbsReal(Centroid(h, v, NULL));
  }
  if (sel == JR_HILL_SELECT_VECTOR) { /* ties (centroids within 1/2 of each other) go to the smaller |Im| */
    PetscReal imax = 0.0;
    for (PetscInt j = 0; j < N2; j++)
      if (hw->key[j] < PETSC_MAX_REAL) imax = PetscMax(imax, PetscAbsReal(hw->ai[j]));
    for (PetscInt j = 0; j < N2; j++)
      if (hw->key[j] < PETSC_MAX_REAL && imax > 0) hw->key[j] += 0.5 * PetscAbsReal(hw->ai[j]) / (imax * (1 + PETSC_SMALL));
  }
  *nev = N2;
  PetscFunctionReturn(0);
}

/* The exponents nearest the origin by SLEPc's PEP (shift-and-invert about -w/1000): the strip |Im| <= w/2 */
static PetscErrorCode SolvePEP(JRHBM h, PetscReal w, PetscInt *nev)
{
  struct _JRHill *hw = h->hill;
  const PetscInt  N = hw->N, want = PetscMin(2 * hw->nk + 8, 2 * N);
  PetscInt        nconv;
  PetscReal      *p;

  PetscFunctionBeginUser;
  if (!hw->pep) {
    ST          st;
    const char *pre;
    char        prefix[128];
    for (PetscInt k = 0; k < 3; k++) PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, N, N, NULL, &hw->P[k]));
    PetscCall(PEPCreate(PETSC_COMM_SELF, &hw->pep));
    PetscCall(JRHBMGetOptionsPrefix(h, &pre));
    PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "%shill_", pre));
    PetscCall(PEPSetOptionsPrefix(hw->pep, prefix));
    PetscCall(PEPSetProblemType(hw->pep, PEP_GENERAL));
    PetscCall(PEPSetWhichEigenpairs(hw->pep, PEP_TARGET_MAGNITUDE));
    PetscCall(PEPSetDimensions(hw->pep, want, PETSC_DEFAULT, PETSC_DEFAULT));
    PetscCall(PEPSetTolerances(hw->pep, 1e-10, PETSC_DEFAULT));
    PetscCall(PEPGetST(hw->pep, &st));
    PetscCall(STSetType(st, STSINVERT));
    PetscCall(PEPSetFromOptions(hw->pep));
  }
  for (PetscInt k = 0; k < 3; k++) {
    const PetscReal *src = k == 0 ? hw->JH : k == 1 ? hw->D1 : hw->D2;
    PetscCall(MatDenseGetArrayWrite(hw->P[k], &p));
    PetscCall(PetscArraycpy(p, src, N * N));
    PetscCall(MatDenseRestoreArrayWrite(hw->P[k], &p));
    PetscCall(MatAssemblyBegin(hw->P[k], MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(hw->P[k], MAT_FINAL_ASSEMBLY));
  }
  PetscCall(PEPSetOperators(hw->pep, 3, hw->P));
  PetscCall(PEPSetTarget(hw->pep, -1e-3 * w));
  PetscCall(PEPSolve(hw->pep));
  PetscCall(PEPGetConverged(hw->pep, &nconv));
  PetscCheck(nconv >= 2 * hw->nk, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "Hill's method: SLEPc PEP found %" PetscInt_FMT " of the %" PetscInt_FMT " exponents needed at %g Hz (-hbm_hill_pep_* options tune it, or raise -frf_stability_dense_max)", nconv, 2 * hw->nk, (double)(w / (2 * PETSC_PI)));
  nconv = PetscMin(nconv, 2 * N);
  for (PetscInt j = 0; j < nconv; j++) {
    PetscScalar kr, ki;
    PetscCall(PEPGetEigenpair(hw->pep, j, &kr, &ki, NULL, NULL));
    hw->ar[j]  = PetscRealPart(kr);
    hw->ai[j]  = PetscRealPart(ki);
    hw->key[j] = PetscAbsReal(hw->ai[j]);
  }
  *nev = nconv;
  PetscFunctionReturn(0);
}

/*
  JRHBMFloquet - the Floquet exponents of the solution a (solve space, modal) at frequency w by Hill's method
  (collective: the Jacobian is summed over the ranks; rank 0 solves and broadcasts, so every rank has the same numbers).

  Input: sel, the selection of the 2 nm physical exponents (JR_HILL_SELECT_VECTOR: eigenvectors centred on the mean
  harmonic; JR_HILL_SELECT_IMAG: |Im| <= w / 2); densemax: the largest nm (2H + 1) solved by LAPACK's QZ (above it,
  SLEPc's PEP with prefix <hbm prefix>hbm_hill_, whose exponents nearest the origin are selected by |Im|).
  Output: nexp = 2 ne, ne the modes other than rigid-body ones (whose mean is pinned: their exponents are the neutral
  double zero of free drift, left out); re, im (room for 2 nm each, may be NULL): the nexp exponents kept, largest real
  part first [1/s]; maxre: the largest real part; detsign: the sign of det(dR/da) (0 if singular). An error for a condensed model (JRHBMHillSupported()).
*/
PetscErrorCode JRHBMFloquet(JRHBM h, PetscReal w, Vec a, JRHillSelect sel, PetscInt densemax, PetscInt *nexp, PetscReal re[], PetscReal im[], PetscReal *maxre, PetscInt *detsign)
{
  struct _JRHill *hw;
  PetscInt        nk;
  PetscReal      *out;
  PetscBool       ok;

  PetscFunctionBeginUser;
  PetscCall(JRHBMHillSupported(h, &ok));
  PetscCheck(ok, h->comm, PETSC_ERR_SUP, "Stability by Hill's method needs the modal unknowns: this model is condensed onto its joints (-hbm_condense no keeps the modes)");
  PetscCall(HillWork(h));
  hw = h->hill;
  nk = 2 * hw->nk;
  if (nexp) *nexp = nk;
  if (!nk) { /* rigid-body modes only: neutral */
    *maxre = 0.0;
    if (detsign) *detsign = 1;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(JR_HBMHill, 0, 0, 0, 0));
  PetscCall(JRHBMComputeJacobian(h, w, a, hw->J, NULL));
  PetscCall(PetscMalloc1(2 + 2 * nk, &out));
  if (!h->rank) {
    const PetscReal *J;
    PetscInt         nev = 0, ds = 0;
    PetscCall(MatDenseGetArrayRead(hw->J, &J));
    PetscCall(HillMatrices(h, w, J));
    PetscCall(DetSign(h, J, &ds));
    PetscCall(MatDenseRestoreArrayRead(hw->J, &J));
    if (hw->N <= densemax) PetscCall(SolveDense(h, w, sel, &nev));
    else PetscCall(SolvePEP(h, w, &nev));
    /* keep the nk of smallest key (a stable order: ties keep LAPACK's, which holds conjugate pairs together) */
    for (PetscInt j = 0; j < nev; j++) hw->idx[j] = j;
    for (PetscInt j = 1; j < nev; j++) {
      const PetscInt t = hw->idx[j];
      PetscInt       i = j - 1;
      while (i >= 0 && hw->key[hw->idx[i]] > hw->key[t]) {
        hw->idx[i + 1] = hw->idx[i];
        i--;
      }
      hw->idx[i + 1] = t;
    }
    /* then the kept ones by real part, largest first */
    for (PetscInt j = 1; j < nk; j++) {
      const PetscInt t = hw->idx[j];
      PetscInt       i = j - 1;
      while (i >= 0 && hw->ar[hw->idx[i]] < hw->ar[t]) {
        hw->idx[i + 1] = hw->idx[i];
        i--;
      }
      hw->idx[i + 1] = t;
    }
    out[0] = hw->ar[hw->idx[0]];
    out[1] = (PetscReal)ds;
    for (PetscInt j = 0; j < nk; j++) {
      out[2 + j]      = hw->ar[hw->idx[j]];
      out[2 + nk + j] = hw->ai[hw->idx[j]];
    }
  }
  if (h->size > 1) PetscCallMPI(MPI_Bcast(out, (PetscMPIInt)(2 + 2 * nk), MPIU_REAL, 0, h->comm));
  *maxre = out[0];
  if (detsign) *detsign = (PetscInt)out[1];
  if (re) PetscCall(PetscArraycpy(re, out + 2, nk));
  if (im) PetscCall(PetscArraycpy(im, out + 2 + nk, nk));
  PetscCall(PetscFree(out));
  PetscCall(PetscLogEventEnd(JR_HBMHill, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* JRHBMJacobianSign - the sign of det(dR/da) at the solution a at frequency w (0 if singular), as JRHBMFloquet()
   gives it, without the eigenproblem. Collective; rank 0 factors and broadcasts. */
PetscErrorCode JRHBMJacobianSign(JRHBM h, PetscReal w, Vec a, PetscInt *detsign)
{
  PetscInt s = 0;

  PetscFunctionBeginUser;
  PetscCall(HillWork(h));
  PetscCall(JRHBMComputeJacobian(h, w, a, h->hill->J, NULL));
  if (!h->rank) {
    const PetscReal *J;
    PetscCall(MatDenseGetArrayRead(h->hill->J, &J));
    PetscCall(DetSign(h, J, &s));
    PetscCall(MatDenseRestoreArrayRead(h->hill->J, &J));
  }
  if (h->size > 1) PetscCallMPI(MPI_Bcast(&s, 1, MPIU_INT, 0, h->comm));
  *detsign = s;
  PetscFunctionReturn(0);
}

/* JRHBMHillSupported - whether JRHBMFloquet() can run: the solve space is the modal one (not condensed onto joints) */
PetscErrorCode JRHBMHillSupported(JRHBM h, PetscBool *ok)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  *ok = h->cond ? PETSC_FALSE : PETSC_TRUE;
  PetscFunctionReturn(0);
}
