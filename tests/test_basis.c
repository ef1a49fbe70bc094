/*
   The mixed basis with the static correction of the interface (JRModesMix, JRModesSetInterface), on a small bolted
   lap whose interface pairs carry stuck springs on half of them, against independent truths:
   - the static response K^+ (I - M R R^T) B W^1/2 w to a random pattern w of interface forces, solved here on
     statically determinate supports by LU (not the basis's shifted factorisation), lies in the basis when every
     pattern is kept: projection error at round-off;
   - the basis is M-orthonormal, Phi^T M Phi = I;
   - Rayleigh-Ritz: its omega^2 are at or above the stuck structure's (SLEPc, 40 modes), the stuck modes themselves are
     exact (they are in the span), and the static vectors lower the others (a larger span);
   - the basis check: the largest residual flexibility x stiffness outside the basis, 0 (round-off) with every pattern,
     and equal, without any, to the largest eigenvalue of W^1/2 B^T P K^+ P^T B W^1/2 (P = I - Phi Phi^T M, the
     interface's residual flexibility in units of the contact springs) formed here column by column with LU of the
     supported structure, and with 4 vectors equal to its fifth eigenvalue;
   - the basis enriched for a load (JRModesEnrich, -modes_adapt): the load's deformation outside the basis equals its
     Rayleigh quotient on that residual flexibility, its static response (LU) then lies in the basis, and the same load
     again adds nothing.
*/
#include "jrtest_gmsh.h"
#include <petscksp.h>
#include <petscblaslapack.h>
#include <slepcsys.h>

static const char *small = "-model_type lap -model_length_a 0.1 -model_length_b 0.1 -model_lap_length 0.04 -model_width 0.02 -model_height 0.02 -model_mesh_h 0.0067 -model_mesh_grade 2 -model_bolt_diameter 0.006 -model_hole_diameter 0.0065 -model_washer_diameter 0.012 -model_nbolts 1";

typedef struct {
  JRModel    m;
  Mat        K, M, Ks; /* Ks = K + the stuck springs */
  PetscInt   nrb, npair, nrow, sel[6]; /* sel: the supports (Supported) */
  Vec        rb[6];
  JRElements el;
  PetscInt  *dof;
  PetscReal *coef, *k;
} Lap;

static PetscErrorCode LapCreate(Lap *L)
{
  const JRPairs *P;
  Mat            S;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(L, sizeof(*L)));
  PetscCall(ModelCreate(small, &L->m));
  PetscCall(JRModelGetMatrices(L->m, &L->K, &L->M, NULL));
  PetscCall(JRModelGetRigidBasis(L->m, &L->nrb, L->rb));
  PetscCall(JRModelGetPairs(L->m, &P));
  L->npair = P->n;
  L->nrow  = 2 * P->n;
  /* jenkins_nv elements on every pair, the first half in contact at rest (stuck springs kt = kn = 1e8 N/m) */
  L->el.n      = P->n;
  L->el.ntypes = 1;
  PetscCall(PetscStrncpy(L->el.typename[0], JRCONTACTJENKINSNV, sizeof(L->el.typename[0])));
  PetscCall(PetscCalloc5(P->n, &L->el.type, P->n, &L->el.kt, P->n, &L->el.kn, P->n, &L->el.mu, P->n, &L->el.n0));
  PetscCall(PetscMalloc4(3 * P->n, &L->el.vdof_a, 3 * P->n, &L->el.vdof_b, 3 * P->n, &L->el.tdir, 3 * P->n, &L->el.ndir));
  PetscCall(PetscMalloc3(12 * P->n, &L->dof, 12 * P->n, &L->coef, 2 * P->n, &L->k));
  for (PetscInt e = 0; e < P->n; e++) {
    L->el.kt[e] = L->el.kn[e] = 1e8;
    L->el.mu[e]               = 0.1;
    L->el.n0[e]               = e < P->n / 2 ? 100.0 : -1.0;
    for (PetscInt c = 0; c < 3; c++) {
      L->el.vdof_a[3 * e + c] = P->dofA[3 * e + c];
      L->el.vdof_b[3 * e + c] = P->dofB[3 * e + c];
      L->el.tdir[3 * e + c]   = P->t[3 * e + c];
      L->el.ndir[3 * e + c]   = P->nrm[3 * e + c];
    }
    for (PetscInt d = 0; d < 2; d++) {
      const PetscInt   r  = 2 * e + d;
      const PetscReal *dr = d ? P->nrm : P->t;
      for (PetscInt c = 0; c < 3; c++) {
        L->dof[6 * r + c]      = P->dofA[3 * e + c];
        L->coef[6 * r + c]     = dr[3 * e + c];
        L->dof[6 * r + 3 + c]  = P->dofB[3 * e + c];
        L->coef[6 * r + 3 + c] = -dr[3 * e + c];
      }
      L->k[r] = 1e8;
    }
  }
  PetscCall(JRElementsCreateStuckStiffness(L->K, &L->el, &S));
  PetscCall(MatDuplicate(L->K, MAT_COPY_VALUES, &L->Ks));
  PetscCall(MatAXPY(L->Ks, 1.0, S, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatDestroy(&S));
  PetscFunctionReturn(0);
}

static PetscErrorCode LapDestroy(Lap *L)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < L->nrb; i++) PetscCall(VecDestroy(&L->rb[i]));
  PetscCall(MatDestroy(&L->Ks));
  PetscCall(PetscFree5(L->el.type, L->el.kt, L->el.kn, L->el.mu, L->el.n0));
  PetscCall(PetscFree4(L->el.vdof_a, L->el.vdof_b, L->el.tdir, L->el.ndir));
  PetscCall(PetscFree3(L->dof, L->coef, L->k));
  PetscCall(JRModelDestroy(&L->m));
  PetscFunctionReturn(0);
}

/* The mixed basis: 6 + 6 stuck modes, 6 free-interface ones, nstatic static correction vectors (-1: the default) */
static PetscErrorCode MixedBasis(Lap *L, PetscInt nstatic, JRModes *md)
{
  char opt[64];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-modes_static %" PetscInt_FMT, nstatic));
  PetscCall(Options(opt));
  PetscCall(JRModesCreate(PETSC_COMM_WORLD, md));
  PetscCall(JRModesSetOperators(*md, L->Ks, L->M));
  PetscCall(JRModesSetFromOptions(*md));
  PetscCall(JRModesSetNumber(*md, 12));
  PetscCall(JRModesSetRigidBasis(*md, L->nrb, L->rb));
  PetscCall(JRModesSetInterface(*md, L->nrow, 6, L->dof, L->coef, L->k));
  PetscCall(JRModesSetMixed(*md));
  PetscCall(JRModesSolve(*md));
  PetscCall(JRModesMix(*md, L->K, 6, L->nrb, L->rb));
  PetscFunctionReturn(0);
}

/* Kc: K + the stuck springs with 6 DOFs held (row and column zeroed, 1 on the diagonal), chosen greedily so that the
   rigid-body modes' values there are independent: the supports of a statically determinate structure, whose reactions
   to a balanced load are those of the load on them (zeroed in the right-hand side) */
static PetscErrorCode Supported(Lap *L, Mat *Kc)
{
  PetscInt   *sel = L->sel, n;
  PetscReal  *R;
  Vec         loc;
  VecScatter  sc;

  PetscFunctionBeginUser;
  PetscCall(VecGetSize(L->rb[0], &n));
  PetscCall(PetscMalloc1(n * L->nrb, &R));
  PetscCall(VecScatterCreateToAll(L->rb[0], &sc, &loc));
  for (PetscInt i = 0; i < L->nrb; i++) {
    const PetscScalar *a;
    PetscCall(VecScatterBegin(sc, L->rb[i], loc, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sc, L->rb[i], loc, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(loc, &a));
    for (PetscInt d = 0; d < n; d++) R[d * L->nrb + i] = PetscRealPart(a[d]);
    PetscCall(VecRestoreArrayRead(loc, &a));
  }
  for (PetscInt k = 0; k < L->nrb; k++) { /* the DOF whose row of R, orthogonalised against the chosen ones, is largest */
    PetscReal best = -1;
    for (PetscInt d = 0; d < n; d++) {
      PetscReal s = 0;
      for (PetscInt i = 0; i < L->nrb; i++) s += R[d * L->nrb + i] * R[d * L->nrb + i];
      if (s > best) {
        best   = s;
        sel[k] = d;
      }
    }
    {
      PetscReal q[6], nq = PetscSqrtReal(best);
      for (PetscInt i = 0; i < L->nrb; i++) q[i] = R[sel[k] * L->nrb + i] / nq;
      for (PetscInt d = 0; d < n; d++) {
        PetscReal s = 0;
        for (PetscInt i = 0; i < L->nrb; i++) s += R[d * L->nrb + i] * q[i];
        for (PetscInt i = 0; i < L->nrb; i++) R[d * L->nrb + i] -= s * q[i];
      }
    }
  }
  PetscCall(MatDuplicate(L->Ks, MAT_COPY_VALUES, Kc));
  PetscCall(MatZeroRowsColumns(*Kc, L->nrb, sel, 1.0, NULL, NULL));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&loc));
  PetscCall(PetscFree(R));
  PetscFunctionReturn(0);
}

/* b = B W^1/2 w: the interface load w (in units of the contact springs), self-equilibrated */
static PetscErrorCode InterfaceLoad(Lap *L, const PetscReal w[], Vec b)
{
  PetscInt     lo, hi;
  PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(b));
  PetscCall(VecGetOwnershipRange(b, &lo, &hi));
  PetscCall(VecGetArray(b, &a));
  for (PetscInt r = 0; r < L->nrow; r++)
    for (PetscInt k = 0; k < 6; k++)
      if (L->dof[6 * r + k] >= lo && L->dof[6 * r + k] < hi) a[L->dof[6 * r + k] - lo] += PetscSqrtReal(L->k[r]) * w[r] * L->coef[6 * r + k];
  PetscCall(VecRestoreArray(b, &a));
  PetscFunctionReturn(0);
}

/* x = P K^+ P^T B W^1/2 w by the supported K (Supported), P = I - Phi Phi^T M for the modes of md
   (NULL: the rigid-body modes R): the static response to the interface load w balanced by the modes' inertia, minus
   the modes' share */
static PetscErrorCode StaticResponse(Lap *L, KSP ksp, const PetscReal w[], JRModes md, Vec x)
{
  Vec          b, *phi = L->rb, Mphi;
  PetscInt     lo, hi, nm = L->nrb;
  PetscScalar  d;

  PetscFunctionBeginUser;
  if (md) {
    PetscCall(JRModesGetNumber(md, &nm));
    PetscCall(JRModesGetVecs(md, &phi));
  }
  PetscCall(VecDuplicate(x, &b));
  PetscCall(VecDuplicate(x, &Mphi));
  PetscCall(InterfaceLoad(L, w, b));
  PetscCall(VecGetOwnershipRange(b, &lo, &hi));
  for (PetscInt i = 0; i < nm; i++) { /* balanced by the modes' inertia */
    PetscCall(VecDot(b, phi[i], &d));
    PetscCall(MatMult(L->M, phi[i], Mphi));
    PetscCall(VecAXPY(b, -d, Mphi));
  }
  for (PetscInt k = 0; k < L->nrb; k++) /* the supports carry their share of the load */
    if (L->sel[k] >= lo && L->sel[k] < hi) PetscCall(VecSetValue(b, L->sel[k], 0.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(b));
  PetscCall(VecAssemblyEnd(b));
  PetscCall(KSPSolve(ksp, b, x));
  for (PetscInt i = 0; i < nm; i++) {
    PetscCall(MatMult(L->M, phi[i], Mphi));
    PetscCall(VecDot(x, Mphi, &d));
    PetscCall(VecAXPY(x, -d, phi[i]));
  }
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&Mphi));
  PetscFunctionReturn(0);
}

/* |x - Phi Phi^T M x|_M / |x|_M */
static PetscErrorCode ProjectionError(JRModes md, Mat M, Vec x, PetscReal *err)
{
  Vec         *phi, Mx, y;
  PetscInt     nm;
  PetscScalar *c, a, b;

  PetscFunctionBeginUser;
  PetscCall(JRModesGetNumber(md, &nm));
  PetscCall(JRModesGetVecs(md, &phi));
  PetscCall(VecDuplicate(x, &Mx));
  PetscCall(VecDuplicate(x, &y));
  PetscCall(PetscMalloc1(nm, &c));
  PetscCall(MatMult(M, x, Mx));
  PetscCall(VecMDot(Mx, nm, phi, c));
  PetscCall(VecCopy(x, y));
  for (PetscInt i = 0; i < nm; i++) c[i] = -c[i];
  PetscCall(VecMAXPY(y, nm, c, phi));
  PetscCall(VecDot(x, Mx, &a));
  PetscCall(MatMult(M, y, Mx));
  PetscCall(VecDot(y, Mx, &b));
  *err = PetscSqrtReal(PetscAbsScalar(b) / PetscAbsScalar(a));
  PetscCall(PetscFree(c));
  PetscCall(VecDestroy(&Mx));
  PetscCall(VecDestroy(&y));
  PetscFunctionReturn(0);
}

/* max |Phi^T M Phi - I| */
static PetscErrorCode Orthonormality(JRModes md, Mat M, PetscReal *err)
{
  Vec         *phi, y;
  PetscInt     nm;
  PetscScalar *c;

  PetscFunctionBeginUser;
  *err = 0;
  PetscCall(JRModesGetNumber(md, &nm));
  PetscCall(JRModesGetVecs(md, &phi));
  PetscCall(VecDuplicate(phi[0], &y));
  PetscCall(PetscMalloc1(nm, &c));
  for (PetscInt j = 0; j < nm; j++) {
    PetscCall(MatMult(M, phi[j], y));
    PetscCall(VecMDot(y, nm, phi, c));
    for (PetscInt i = 0; i < nm; i++) *err = PetscMax(*err, PetscAbsReal(PetscRealPart(c[i]) - (i == j ? 1.0 : 0.0)));
  }
  PetscCall(PetscFree(c));
  PetscCall(VecDestroy(&y));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  Lap              L;
  JRModes          m0, m4, mall, mref;
  KSP              ksp;
  PC               pc;
  Mat              Kc;
  Vec              x;
  PetscReal       *w, *w2, ww = 0, rq = 0, e0, eall, rho4, l5 = 0, orth, rho, rho0, rhoall, lmax = 0, worst = 0, stuckerr = 0, lower = 0;
  PetscInt         n0, n4, nall, nref, nsall;
  const PetscReal *l0, *l4, *lall, *lref;
  PetscRandom      rnd;
  PetscLogDouble   t;

  PetscCall(SlepcInitialize(&argc, &argv, NULL, NULL));
  PetscCall(LapCreate(&L));
  /* the independent static solver: K + the stuck springs supported at 6 DOFs that hold the rigid-body motions
     (statically determinate: a balanced load has no reactions), LU */
  PetscCall(Supported(&L, &Kc));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, Kc, Kc));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
#if defined(PETSC_HAVE_MUMPS)
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
#endif
  /* the bases: without static correction, with 4 vectors, with every pattern */
  PetscCall(MixedBasis(&L, 0, &m0));
  PetscCall(MixedBasis(&L, 4, &m4));
  PetscCall(MixedBasis(&L, L.nrow, &mall));
  PetscCall(JRModesGetBasisCheck(m0, &rho, &rho0, NULL, NULL, NULL));
  PetscCall(JRModesGetBasisCheck(mall, &rhoall, NULL, NULL, &nsall, &t));
  /* a random interface load's static response */
  PetscCall(PetscMalloc2(L.nrow, &w, L.nrow, &w2));
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetSeed(rnd, 7));
  PetscCall(PetscRandomSeed(rnd));
  for (PetscInt r = 0; r < L.nrow; r++) PetscCall(PetscRandomGetValueReal(rnd, &w[r]));
  PetscCall(MatCreateVecs(L.K, &x, NULL));
  PetscCall(StaticResponse(&L, ksp, w, NULL, x));
  PetscCall(ProjectionError(mall, L.M, x, &eall));
  PetscCall(ProjectionError(m0, L.M, x, &e0));
  CHECK(eall < 1e-7 && e0 > 1e-3, "static correction with every one of the %" PetscInt_FMT " interface patterns (%" PetscInt_FMT " vectors, %.2g s): the static response to a random interface load (LU of the structure on statically determinate supports, independent) lies in the basis, projection error %.1e (< 1e-7; %.2g without static correction)", L.nrow, nsall, (double)t, (double)eall, (double)e0);
  PetscCall(Orthonormality(mall, L.M, &orth));
  CHECK(orth < 1e-10, "mixed basis with the static correction: max |Phi^T M Phi - I| = %.1e (< 1e-10)", (double)orth);
  /* Rayleigh-Ritz against the stuck structure's own modes (SLEPc, 40) */
  PetscCall(JRModesCreate(PETSC_COMM_WORLD, &mref));
  PetscCall(Options("-modes_static -1"));
  PetscCall(JRModesSetOperators(mref, L.Ks, L.M));
  PetscCall(JRModesSetNumber(mref, 40));
  PetscCall(JRModesSetRigidBasis(mref, L.nrb, L.rb));
  PetscCall(JRModesSolve(mref));
  PetscCall(JRModesGetNumber(mref, &nref));
  PetscCall(JRModesGetEigenvalues(mref, &lref));
  PetscCall(JRModesGetNumber(m0, &n0));
  PetscCall(JRModesGetNumber(m4, &n4));
  PetscCall(JRModesGetNumber(mall, &nall));
  PetscCall(JRModesGetEigenvalues(m0, &l0));
  PetscCall(JRModesGetEigenvalues(m4, &l4));
  PetscCall(JRModesGetEigenvalues(mall, &lall));
  for (PetscInt i = L.nrb; i < PetscMin(nall, nref); i++) worst = PetscMin(worst, lall[i] / lref[i] - 1);
  for (PetscInt i = L.nrb; i < 12; i++) stuckerr = PetscMax(stuckerr, PetscAbsReal(lall[i] / lref[i] - 1));
  for (PetscInt i = L.nrb; i < n0; i++) lower = PetscMax(lower, l4[i] / l0[i] - 1);
  CHECK(worst > -1e-9, "Rayleigh-Ritz: the basis's omega^2 at or above the stuck structure's (40 modes, SLEPc), smallest ratio - 1 = %.1e", (double)worst);
  CHECK(stuckerr < 1e-8, "the 6 elastic stuck modes in the basis keep their frequencies (%.6g .. %.6g Hz) to %.1e", (double)(PetscSqrtReal(lall[L.nrb]) / (2 * PETSC_PI)), (double)(PetscSqrtReal(lall[11]) / (2 * PETSC_PI)), (double)stuckerr);
  CHECK(lower < 1e-9 && n4 == n0 + 4, "4 static correction vectors: %" PetscInt_FMT " -> %" PetscInt_FMT " vectors, no omega^2 rises (largest ratio - 1 = %.1e)", n0, n4, (double)lower);
  /* the basis check without static correction, against W^1/2 B^T P K^+ P^T B W^1/2 formed column by column with the supported structure */
  {
    PetscReal   *S, *lam, *work;
    PetscBLASInt bn, lwork, info;
    Vec          loc;
    VecScatter   sc;
    PetscCall(PetscMalloc3(L.nrow * L.nrow, &S, L.nrow, &lam, 8 * L.nrow, &work));
    PetscCall(VecScatterCreateToAll(x, &sc, &loc));
    for (PetscInt j = 0; j < L.nrow; j++) {
      const PetscScalar *a;
      for (PetscInt i = 0; i < L.nrow; i++) w[i] = i == j;
      PetscCall(StaticResponse(&L, ksp, w, m0, x));
      PetscCall(VecScatterBegin(sc, x, loc, INSERT_VALUES, SCATTER_FORWARD));
      PetscCall(VecScatterEnd(sc, x, loc, INSERT_VALUES, SCATTER_FORWARD));
      PetscCall(VecGetArrayRead(loc, &a));
      for (PetscInt i = 0; i < L.nrow; i++) {
        PetscReal v = 0;
        for (PetscInt k = 0; k < 6; k++) v += L.coef[6 * i + k] * PetscRealPart(a[L.dof[6 * i + k]]);
        S[i + j * L.nrow] = PetscSqrtReal(L.k[i]) * v;
      }
      PetscCall(VecRestoreArrayRead(loc, &a));
    }
    PetscCall(VecScatterDestroy(&sc));
    PetscCall(VecDestroy(&loc));
    for (PetscInt j = 0; j < L.nrow; j++)
      for (PetscInt i = 0; i < j; i++) S[i + j * L.nrow] = S[j + i * L.nrow] = 0.5 * (S[i + j * L.nrow] + S[j + i * L.nrow]);
    PetscCall(PetscBLASIntCast(L.nrow, &bn));
    PetscCall(PetscBLASIntCast(8 * L.nrow, &lwork));
    PetscCallBLAS("LAPACKsyev", LAPACKsyev_("N", "U", &bn, S, &bn, lam, work, &lwork, &info));
    PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed: info %d", (int)info);
    lmax = lam[L.nrow - 1];
    l5   = lam[L.nrow - 5];
    PetscCall(PetscFree3(S, lam, work));
  }
  CHECK(PetscAbsReal(rho0 / lmax - 1) < 1e-4 && rho == rho0, "basis check without static correction %.6g = largest eigenvalue of W^1/2 B^T P K^+ P^T B W^1/2 (P = I - Phi Phi^T M) formed by LU %.6g (1e-4)", (double)rho0, (double)lmax);
  PetscCall(JRModesGetBasisCheck(m4, &rho4, NULL, NULL, NULL, NULL));
  CHECK(PetscAbsReal(rho4 / l5 - 1) < 1e-4 && rho4 < rho0, "basis check with 4 static correction vectors %.6g = the fifth largest eigenvalue %.6g (1e-4), below %.6g", (double)rho4, (double)l5, (double)rho0);
  CHECK(rhoall < 1e-7 * rho0, "basis check with every pattern: %.1e (round-off; %.3g without)", (double)rhoall, (double)rho0);
  { /* the basis enriched for one load f (JRModesEnrich): its ratio is f^T (K^+ - Phi (Phi^T Ks Phi)^-1 Phi^T) f / |w|^2
       (the energy of its static response outside the basis; K^+ f by LU above, Phi^T Ks Phi formed here), and its
       static response (LU) then lies in the basis */
    Vec          F, Kphi, *phi;
    PetscReal    lam1, lam2, e1, e1before, orth1;
    PetscInt     nadd1, nadd2, nm0, nm1;
    PetscScalar  fx, pf, pk;
    for (PetscInt r = 0; r < L.nrow; r++) {
      PetscCall(PetscRandomGetValueReal(rnd, &w2[r]));
      ww += w2[r] * w2[r];
    }
    PetscCall(VecDuplicate(x, &F));
    PetscCall(VecDuplicate(x, &Kphi));
    PetscCall(InterfaceLoad(&L, w2, F));
    PetscCall(StaticResponse(&L, ksp, w2, NULL, x));
    PetscCall(ProjectionError(m0, L.M, x, &e1before));
    PetscCall(VecDot(F, x, &fx));
    rq = PetscRealPart(fx);
    PetscCall(JRModesGetNumber(m0, &nm0));
    PetscCall(JRModesGetVecs(m0, &phi));
    for (PetscInt q = 0; q < nm0; q++) {
      PetscCall(MatMult(L.Ks, phi[q], Kphi));
      PetscCall(VecDot(phi[q], Kphi, &pk));
      PetscCall(VecDot(phi[q], F, &pf));
      if (PetscRealPart(pk) > 1e-8 * PetscRealPart(pk + 1.0)) rq -= PetscRealPart(pf * pf / pk);
    }
    rq /= ww;
    PetscCall(VecDestroy(&Kphi));
    PetscCall(JRModesEnrich(m0, 1, &F, &ww, 1e-6 * rq, &lam1, &nadd1));
    PetscCall(JRModesGetNumber(m0, &nm1));
    CHECK(PetscAbsReal(lam1 / rq - 1) < 1e-4 && nadd1 == 1 && nm1 == nm0 + 1, "basis enriched for a random interface load: its deformation outside the basis %.6g = f^T (K^+ - Phi (Phi^T Ks Phi)^-1 Phi^T) f / |w|^2 by LU %.6g (1e-4); %" PetscInt_FMT " -> %" PetscInt_FMT " vectors", (double)lam1, (double)rq, nm0, nm1);
    PetscCall(ProjectionError(m0, L.M, x, &e1));
    PetscCall(Orthonormality(m0, L.M, &orth1));
    CHECK(e1 < 1e-7 && e1before > 1e-3 && orth1 < 1e-10, "the load's static response (LU, independent) lies in the enriched basis: projection error %.1e (< 1e-7; %.2g before), max |Phi^T M Phi - I| = %.1e", (double)e1, (double)e1before, (double)orth1);
    PetscCall(JRModesEnrich(m0, 1, &F, &ww, 1e-6 * rq, &lam2, &nadd2));
    CHECK(lam2 < 1e-8 * lam1 && nadd2 == 0, "the same load again: deformation outside the basis %.1e (round-off; %.3g before), nothing added", (double)lam2, (double)lam1);
    PetscCall(JRModesEnrichEnd(m0));
    PetscCall(VecDestroy(&F));
  }
  PetscCall(PetscFree2(w, w2));
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(VecDestroy(&x));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&Kc));
  PetscCall(JRModesDestroy(&m0));
  PetscCall(JRModesDestroy(&m4));
  PetscCall(JRModesDestroy(&mall));
  PetscCall(JRModesDestroy(&mref));
  PetscCall(LapDestroy(&L));
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(SlepcFinalize());
  if (!JRTestRank()) printf("%d passed, %d failed\n", jr_pass, jr_fail);
  return jr_fail ? 1 : 0;
}
