/*
   Second reduction (src/rom/rom.c), checked against independent evaluations:
   - a joint built from m known Jenkins elements, each split into identical members, is fitted back to those m
     elements by TAO from a start perturbed by 30% (the fit must recover kt and f to 1e-5);
   - the fitted elements' hysteresis loops, marched by the contact module's play operator (JRContactJointLoop,
     another code path), equal the members' loops at an amplitude not used by the fit;
   - mode-shape weights: a member moving w u is the element (w^2 kt, |w| f) moving u: JRROMReduce -rom_elements 0
     with weights gives elements whose force on u, times 1, equals w times the member's force on w u;
   - jenkins_nv joint: the normal stiffnesses of m known elements are recovered from the normal load curve;
   - the fit coupled across joints (a case given): two joints, each of 3 known elements, are fitted back exactly - the
     coupling must keep an exact fit - and their energy per cycle at the case's amplitudes equals the members'.
*/
#include "jrtest.h"

/* nj joints, each of m known elements (k, f; joint c: k (1 + c), f (1 + 2 c)) split into identical members */
static PetscErrorCode Members(const char *type, PetscInt m, const double k[], const double f[], const double kn[], PetscInt split, PetscInt nj, JRElements *nn)
{
  const PetscInt n = m * split * nj;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(nn, sizeof(*nn)));
  nn->n      = n;
  nn->ntypes = 1;
  PetscCall(PetscStrncpy(nn->typename[0], type, sizeof(nn->typename[0])));
  PetscCall(PetscMalloc5(n, &nn->type, n, &nn->dof_a, n, &nn->dof_b, n, &nn->ndof_a, n, &nn->ndof_b));
  PetscCall(PetscMalloc4(n, &nn->kt, n, &nn->kn, n, &nn->mu, n, &nn->n0));
  PetscCall(PetscMalloc1(n, &nn->joint));
  nn->njoints = nj;
  for (PetscInt e = 0; e < n; e++) {
    const PetscInt i = e % m, c = e % nj; /* interleaved: the order must not matter */
    nn->type[e]      = 0;
    nn->dof_a[e] = nn->dof_b[e] = nn->ndof_a[e] = nn->ndof_b[e] = -1;
    nn->kt[e]                                                   = k[i] * (1 + c) / split;
    nn->kn[e]                                                   = kn ? kn[i] / split : 0;
    nn->mu[e]                                                   = 0.2;
    nn->n0[e]                                                   = f[i] * (1 + 2 * c) / 0.2 / split;
    nn->joint[e]                                                = c;
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
  PetscCall(Members("jenkins", 3, k, f, NULL, 5, 1, &nn));
  PetscCall(JRROMReduce(PETSC_COMM_WORLD, &nn, 3, NULL, NULL, NULL, "", PETSC_FALSE, PETSC_FALSE, &rom));
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
    PetscCall(JRROMReduce(PETSC_COMM_WORLD, &nn, 0, w, NULL, NULL, "", PETSC_FALSE, PETSC_FALSE, &rom));
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
  PetscCall(Members("jenkins_nv", 3, k, f, kn, 4, 1, &nn));
  PetscCall(JRROMReduce(PETSC_COMM_WORLD, &nn, 3, NULL, NULL, NULL, "", PETSC_FALSE, PETSC_FALSE, &rom));
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
  /* 5. coupled across joints: 2 joints x 3 known elements (joint 1: k x 2, f x 3), a case of 4 levels moving joint 1
     0.6 times as much as joint 0; the stages: each joint alone (exact with the refinement), then the coupled search
     and TAO, which must stay there */
  {
    const PetscReal lev[4] = {0.3, 3, 30, 300}, uj[2] = {1.0, 0.6};
    JRROMCase       cs;
    double          worst = 0, ework = 0;
    PetscCall(PetscMemzero(&cs, sizeof(cs)));
    cs.nlev   = 4;
    cs.level  = lev;
    cs.force  = 1;
    cs.damp   = 3e5;
    cs.ujoint = uj;
    PetscCall(Members("jenkins", 3, k, f, NULL, 4, 2, &nn));
    PetscCall(JRROMReduce(PETSC_COMM_WORLD, &nn, 3, NULL, &cs, NULL, "", PETSC_FALSE, PETSC_FALSE, &rom));
    for (PetscInt i = 0; i < rom.n; i++) {
      const PetscInt c = rom.joint[i];
      PetscInt       b = 0;
      for (PetscInt q = 0; q < 3; q++) /* the known element of the same slip displacement */
        if (PetscAbsReal(PetscLogReal(rom.mu[i] * rom.n0[i] / rom.kt[i] * (1 + c) / (1 + 2 * c) * k[q] / f[q])) < PetscAbsReal(PetscLogReal(rom.mu[i] * rom.n0[i] / rom.kt[i] * (1 + c) / (1 + 2 * c) * k[b] / f[b]))) b = q;
      worst = PetscMax(worst, PetscAbsReal(rom.kt[i] / (k[b] * (1 + c)) - 1));
      worst = PetscMax(worst, PetscAbsReal(rom.mu[i] * rom.n0[i] / (f[b] * (1 + 2 * c)) - 1));
    }
    for (double a = 1e-7; a < 1e-3; a *= 1.7) { /* the energy per cycle of both joints, closed form 4 f (u - f / k) */
      double Em = 0, Er = 0;
      for (PetscInt e = 0; e < nn.n; e++) {
        const double u = uj[nn.joint[e]] * a, fe = nn.mu[e] * nn.n0[e];
        if (nn.kt[e] * u > fe) Em += 4 * fe * (u - fe / nn.kt[e]);
      }
      for (PetscInt e = 0; e < rom.n; e++) {
        const double u = uj[rom.joint[e]] * a, fe = rom.mu[e] * rom.n0[e];
        if (rom.kt[e] * u > fe) Er += 4 * fe * (u - fe / rom.kt[e]);
      }
      if (Em > 0) ework = PetscMax(ework, PetscAbsReal(Er / Em - 1));
    }
    CHECK(rom.n == 6 && worst < 1e-5 && ework < 1e-5, "coupled fit of 2 joints x 3 known elements: %d elements, worst relative error %.2e (< 1e-5); energy per cycle of both joints (closed form, 1e-7..1e-3 m) within %.2e", (int)rom.n, worst, ework);
    PetscCall(JRElementsDestroy(&rom));
    PetscCall(JRElementsDestroy(&nn));
  }
  PetscCall(PetscFinalize());
  return jr_fail ? 1 : 0;
}
