/*
   Second reduction (src/rom/rom.c), checked against independent evaluations:
   - a joint built from m known Jenkins elements, each split into identical members, is fitted back to those m
     elements by TAO from a start perturbed by 30% (the fit must recover kt and f to 1e-5);
   - the fitted elements' hysteresis loops, marched by the contact module's play operator (JRContactJointLoop,
     another code path), equal the members' loops at an amplitude not used by the fit;
   - mode-shape weights: a member moving w u is the element (w^2 kt, |w| f) moving u: JRROMReduce -rom_elements 0
     with weights gives elements whose force on u, times 1, equals w times the member's force on w u;
   - jenkins_nv joint: the normal stiffnesses of m known elements are recovered from the normal load curve.
*/
#include "jrtest.h"

static PetscErrorCode Members(const char *type, PetscInt m, const double k[], const double f[], const double kn[], PetscInt split, JRElements *nn)
{
  const PetscInt n = m * split;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(nn, sizeof(*nn)));
  nn->n      = n;
  nn->ntypes = 1;
  PetscCall(PetscStrncpy(nn->typename[0], type, sizeof(nn->typename[0])));
  PetscCall(PetscMalloc5(n, &nn->type, n, &nn->dof_a, n, &nn->dof_b, n, &nn->ndof_a, n, &nn->ndof_b));
  PetscCall(PetscMalloc4(n, &nn->kt, n, &nn->kn, n, &nn->mu, n, &nn->n0));
  PetscCall(PetscMalloc1(n, &nn->joint));
  nn->njoints = 1;
  for (PetscInt e = 0; e < n; e++) {
    const PetscInt i = e % m; /* interleaved: the order must not matter */
    nn->type[e]      = 0;
    nn->dof_a[e] = nn->dof_b[e] = nn->ndof_a[e] = nn->ndof_b[e] = -1;
    nn->kt[e]                                                   = k[i] / split;
    nn->kn[e]                                                   = kn ? kn[i] / split : 0;
    nn->mu[e]                                                   = 0.2;
    nn->n0[e]                                                   = f[i] / 0.2 / split;
    nn->joint[e]                                                = 0;
  }
  PetscFunctionReturn(0);
}

static int CompareK(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

int main(int argc, char **argv)
{
  const double k[3] = {4e7, 2.5e7, 1e7}, f[3] = {40, 100, 250}, kn[3] = {6e7, 3e7, 2e7}; /* delta 1, 4, 25 um */
  JRElements   nn, rom;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-rom_fit_perturb", "0.3"));
  PetscCall(PetscOptionsSetValue(NULL, "-rom_fit_refine", "1")); /* the slip displacements free: exact recovery */
  /* 1. jenkins: recover the three elements */
  PetscCall(Members("jenkins", 3, k, f, NULL, 5, &nn));
  PetscCall(JRROMReduce(PETSC_COMM_WORLD, &nn, 3, NULL, NULL, "", PETSC_FALSE, &rom));
  {
    double pk[3][2], ex[3][2], worst = 0;
    CHECK(rom.n == 3 && rom.members && rom.members->n == 15, "second reduction of 15 members: 3 elements (%d), members kept", (int)rom.n);
    for (int i = 0; i < 3; i++) {
      pk[i][0] = rom.kt[i] * 0 + rom.mu[i] * rom.n0[i] / rom.kt[i]; /* sort by slip displacement */
      pk[i][1] = i;
      ex[i][0] = f[i] / k[i];
      ex[i][1] = i;
    }
    qsort(pk, 3, sizeof(pk[0]), CompareK);
    qsort(ex, 3, sizeof(ex[0]), CompareK);
    for (int i = 0; i < 3; i++) {
      const int a = (int)pk[i][1], b = (int)ex[i][1];
      worst       = PetscMax(worst, PetscAbsReal(rom.kt[a] / k[b] - 1));
      worst       = PetscMax(worst, PetscAbsReal(rom.mu[a] * rom.n0[a] / f[b] - 1));
    }
    CHECK(worst < 1e-5, "TAO recovers the 3 known elements from a 30%% perturbed start: worst relative error %.2e (< 1e-5)", worst);
    /* 2. the loops by the contact module's play operator, at an amplitude the fit did not use */
    {
      JRContact c1, c2;
      double    U[3] = {0, 0, 9e-6}, u[256], fa[256], fb[256], fmax = 0, d = 0;
      PetscCall(JRContactCreate(PETSC_COMM_SELF, &c1));
      PetscCall(JRContactSetType(c1, JRCONTACTJENKINS));
      PetscCall(JRContactSetHarmonics(c1, 1, 256));
      PetscCall(JRContactSetElements(c1, nn.n, nn.kt, nn.kn, nn.mu, nn.n0));
      PetscCall(JRContactCreate(PETSC_COMM_SELF, &c2));
      PetscCall(JRContactSetType(c2, JRCONTACTJENKINS));
      PetscCall(JRContactSetHarmonics(c2, 1, 256));
      PetscCall(JRContactSetElements(c2, rom.n, rom.kt, rom.kn, rom.mu, rom.n0));
      PetscCall(JRContactJointLoop(c1, 0, NULL, U, NULL, 256, u, NULL, fa, NULL));
      PetscCall(JRContactJointLoop(c2, 0, NULL, U, NULL, 256, u, NULL, fb, NULL));
      for (int j = 0; j < 256; j++) {
        fmax = PetscMax(fmax, PetscAbsReal(fa[j]));
        d    = PetscMax(d, PetscAbsReal(fa[j] - fb[j]));
      }
      CHECK(d < 1e-5 * fmax, "fitted loop = members' loop at 9 um by JRContactJointLoop: %.2e of the peak force %.4g N", d / fmax, fmax);
      PetscCall(JRContactDestroy(&c1));
      PetscCall(JRContactDestroy(&c2));
    }
    PetscCall(JRElementsDestroy(&rom));
  }
  /* 3. weights: member force w F(w u; k, f) = element force F(u; w^2 k, |w| f) */
  {
    double    w[15], U[3] = {0, 0, 7e-6}, u[128], fa[128], fb[128], d = 0, fmax = 0;
    JRContact c;
    for (int e = 0; e < 15; e++) w[e] = 0.4 + 0.1 * e * (e % 2 ? -0.3 : 1.0);
    PetscCall(JRROMReduce(PETSC_COMM_WORLD, &nn, 0, w, NULL, "", PETSC_FALSE, &rom));
    CHECK(rom.n == 15, "first reduction with weights: one element per member (%d)", (int)rom.n);
    PetscCall(JRContactCreate(PETSC_COMM_SELF, &c));
    PetscCall(JRContactSetType(c, JRCONTACTJENKINS));
    PetscCall(JRContactSetHarmonics(c, 1, 128));
    for (int j = 0; j < 128; j++) fa[j] = 0;
    for (int e = 0; e < 15; e++) { /* every member alone on w_e u, times w_e */
      double Ue[3] = {0, 0, w[e] * U[2]}, fe[128];
      PetscCall(JRContactSetElements(c, 1, &nn.kt[e], &nn.kn[e], &nn.mu[e], &nn.n0[e]));
      PetscCall(JRContactJointLoop(c, 0, NULL, Ue, NULL, 128, u, NULL, fe, NULL));
      for (int j = 0; j < 128; j++) fa[j] += w[e] * fe[j];
    }
    PetscCall(JRContactSetElements(c, rom.n, rom.kt, rom.kn, rom.mu, rom.n0));
    PetscCall(JRContactJointLoop(c, 0, NULL, U, NULL, 128, u, NULL, fb, NULL));
    for (int j = 0; j < 128; j++) {
      fmax = PetscMax(fmax, PetscAbsReal(fa[j]));
      d    = PetscMax(d, PetscAbsReal(fa[j] - fb[j]));
    }
    CHECK(d < 1e-12 * fmax, "weighted members = elements (w^2 kt, |w| f) on the joint motion: %.2e of %.4g N", d / fmax, fmax);
    PetscCall(JRContactDestroy(&c));
    PetscCall(JRElementsDestroy(&rom));
  }
  PetscCall(JRElementsDestroy(&nn));
  /* 4. jenkins_nv: kt, f and the normal stiffnesses */
  PetscCall(Members("jenkins_nv", 3, k, f, kn, 4, &nn));
  PetscCall(JRROMReduce(PETSC_COMM_WORLD, &nn, 3, NULL, NULL, "", PETSC_FALSE, &rom));
  {
    double worst = 0;
    for (int i = 0; i < 3; i++) {
      int b = 0;
      for (int q = 0; q < 3; q++)
        if (PetscAbsReal(rom.mu[i] * rom.n0[i] / rom.kt[i] - f[q] / k[q]) < PetscAbsReal(rom.mu[i] * rom.n0[i] / rom.kt[i] - f[b] / k[b])) b = q;
      worst = PetscMax(worst, PetscAbsReal(rom.kt[i] / k[b] - 1));
      worst = PetscMax(worst, PetscAbsReal(rom.kn[i] / kn[b] - 1));
      worst = PetscMax(worst, PetscAbsReal(rom.mu[i] * rom.n0[i] / f[b] - 1));
    }
    CHECK(rom.n == 3 && worst < 1e-4, "jenkins_nv: kt, f and kn of 3 known elements recovered: worst relative error %.2e (< 1e-4)", worst);
  }
  PetscCall(JRElementsDestroy(&rom));
  PetscCall(JRElementsDestroy(&nn));
  PetscCall(PetscFinalize());
  return jr_fail ? 1 : 0;
}
