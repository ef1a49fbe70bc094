/*
   jenkins element (constant normal load, thesis 3.2): closed form vs independent truths.
   - full stick: F = kt U exactly and no dissipation;
   - stick-slip: the energy identity D = 4 mu n0 (A - mu n0/kt) (area of the parallelogram loop);
   - brute-force transient time march with 65536 steps per cycle (tests/jrtest.h);
   - the full-slip limit: a square wave of height mu n0, Fc -> 4 mu n0/pi;
   - the AFT path on a fine grid, and multi-harmonic motion vs the time march;
   - every analytic derivative vs central finite differences.
   Units: kt = 1e8 N/m (100 kN/mm), mu = 0.12, n0 = 100 N; slip onset A0 = mu n0/kt = 0.12 um.
*/
#include "jrtest.h"

typedef struct {
  JRContact c;
  PetscInt  nc;
} Elem;

static PetscErrorCode ElemCreate(const char *type, JRContactMethod method, PetscInt H, PetscInt N, double kt, double kn, double mu, double n0, Elem *e)
{
  PetscFunctionBeginUser;
  PetscCall(JRContactCreate(PETSC_COMM_SELF, &e->c));
  PetscCall(JRContactSetType(e->c, type));
  PetscCall(JRContactSetHarmonics(e->c, H, N));
  PetscCall(JRContactSetMethod(e->c, method));
  PetscCall(JRContactSetElements(e->c, 1, &kt, &kn, &mu, &n0));
  PetscCall(JRContactSetUp(e->c));
  e->nc = 2 * H + 1;
  PetscFunctionReturn(0);
}

/* central-difference Jacobian of F over U (step h times the largest motion coefficient),
   compared with the analytic one: max error / max |J| */
static PetscErrorCode FDCheck(Elem *e, const double *U0, double hrel, double *err)
{
  const PetscInt nc = e->nc;
  double         U[JRT_NC], Fp[JRT_NC], Fm[JRT_NC], J[JRT_NC * JRT_NC], Jfd[JRT_NC * JRT_NC];

  const double   h = hrel * MaxAbs(nc, U0);

  PetscFunctionBeginUser;
  PetscCall(JRContactEvaluate(e->c, U0, NULL, Fp, NULL, J, NULL, NULL, NULL));
  for (PetscInt m = 0; m < nc; m++) {
    for (PetscInt k = 0; k < nc; k++) U[k] = U0[k];
    U[m] = U0[m] + h;
    PetscCall(JRContactEvaluate(e->c, U, NULL, Fp, NULL, NULL, NULL, NULL, NULL));
    U[m] = U0[m] - h;
    PetscCall(JRContactEvaluate(e->c, U, NULL, Fm, NULL, NULL, NULL, NULL, NULL));
    for (PetscInt k = 0; k < nc; k++) Jfd[k * nc + m] = (Fp[k] - Fm[k]) / (2.0 * h);
  }
  *err = RelDiff(nc * nc, J, Jfd, MaxAbs(nc * nc, J));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  const double kt = 1.0e8, mu = 0.12, n0 = 100.0, r = mu * n0, A0 = r / kt;
  const double ph = 35.0 * M_PI / 180.0;
  Elem         an, aft, aft3, aft3f;
  double       F[JRT_NC], Fa[JRT_NC], Fb[JRT_NC], Nb[JRT_NC], D, err;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(ElemCreate("jenkins", JR_CONTACT_ANALYTIC, 1, 64, kt, 0.0, mu, n0, &an));
  PetscCall(ElemCreate("jenkins", JR_CONTACT_AFT, 1, 4096, kt, 0.0, mu, n0, &aft));

  /* full stick */
  {
    const double   U[3] = {0.0, 0.5 * A0 * cos(ph), 0.5 * A0 * sin(ph)};
    JRContactState st;
    PetscCall(JRContactEvaluate(an.c, U, NULL, F, NULL, NULL, NULL, NULL, &st));
    PetscCall(JRHarmonicWork(3, U, F, &D));
    CHECK(fabs(F[0]) < 1e-15 && fabs(F[1] - kt * U[1]) < 1e-12 * r && fabs(F[2] - kt * U[2]) < 1e-12 * r, "jenkins full stick (A = 0.5 mu n0/kt): F = kt U (Fs %.6g, kt Us %.6g)", F[1], kt * U[1]);
    CHECK(fabs(D) < 1e-15 * r * A0 && st == JR_CONTACT_FULL_STICK, "jenkins full stick: no dissipation (D = %.3g J), state %s", D, JRContactStates[st]);
  }

  /* stick-slip: energy identity, brute-force march, AFT */
  {
    const double ratios[] = {1.01, 1.5, 3.0, 10.0, 100.0};
    for (size_t i = 0; i < sizeof(ratios) / sizeof(ratios[0]); i++) {
      const double   A = ratios[i] * A0, U[3] = {0.0, A * cos(ph), A * sin(ph)};
      const double   Dexact = 4.0 * r * (A - r / kt);
      JRContactState st;
      PetscCall(JRContactEvaluate(an.c, U, NULL, F, NULL, NULL, NULL, NULL, &st));
      PetscCall(JRHarmonicWork(3, U, F, &D));
      CHECK(fabs(D - Dexact) <= 1e-12 * Dexact && st == JR_CONTACT_STICK_SLIP, "jenkins A = %g A0: energy %.10g J vs 4 mu n0 (A - mu n0/kt) = %.10g J", ratios[i], D, Dexact);
      BruteForce(kt, 0.0, mu, n0, 3, U, NULL, 65536, 3, Fb, Nb, NULL, 0);
      err = RelDiff(3, F, Fb, r);
      CHECK(err < 1e-5, "jenkins A = %g A0: closed form vs brute-force time march, error %.2e (of mu n0)", ratios[i], err);
      PetscCall(JRContactEvaluate(aft.c, U, NULL, Fa, NULL, NULL, NULL, NULL, NULL));
      err = RelDiff(3, F, Fa, r);
      CHECK(err < 1e-5, "jenkins A = %g A0: closed form vs AFT (N = 4096), error %.2e (of mu n0)", ratios[i], err);
    }
  }

  /* full-slip limit: the force becomes a square wave of height mu n0 in phase with the velocity */
  {
    const double A = 1.0e6 * A0, U[3] = {0.0, A, 0.0};
    PetscCall(JRContactEvaluate(an.c, U, NULL, F, NULL, NULL, NULL, NULL, NULL));
    CHECK(fabs(F[2] - 4.0 * r / M_PI) < 1e-5 * r && fabs(F[1]) < 1e-2 * r, "jenkins gross slip (A = 1e6 A0): Fc = %.8g vs 4 mu n0/pi = %.8g, Fs = %.3g", F[2], 4.0 * r / M_PI, F[1]);
  }

  /* a mean displacement: inside the stick band it is carried elastically, outside the band the
     element shakes down to the band edge (the march from rest does the same) */
  {
    const double U1[3] = {0.3 * A0, 0.5 * A0, 0.0}, U2[3] = {3.0 * A0, 0.5 * A0 * cos(ph), 0.5 * A0 * sin(ph)}, U3[3] = {-2.0 * A0, 4.0 * A0, 0.0};
    const double *Us[3] = {U1, U2, U3};
    for (int i = 0; i < 3; i++) {
      PetscCall(JRContactEvaluate(an.c, Us[i], NULL, F, NULL, NULL, NULL, NULL, NULL));
      BruteForce(kt, 0.0, mu, n0, 3, Us[i], NULL, 65536, 3, Fb, Nb, NULL, 0);
      err = RelDiff(3, F, Fb, r);
      CHECK(err < 1e-5, "jenkins with mean U0 = %g A0, A = %g A0: closed form vs brute-force march, error %.2e (F0 %.6g vs %.6g N)", Us[i][0] / A0, hypot(Us[i][1], Us[i][2]) / A0, err, F[0], Fb[0]);
    }
  }

  /* analytic derivatives vs central finite differences */
  {
    const double cases[][3] = {
      {0.0,       0.5 * A0 * cos(ph), 0.5 * A0 * sin(ph)},
      {3.0 * A0,  0.5 * A0 * cos(ph), 0.5 * A0 * sin(ph)},
      {0.0,       1.5 * A0 * cos(ph), 1.5 * A0 * sin(ph)},
      {0.2 * A0,  3.0 * A0 * cos(ph), -3.0 * A0 * sin(ph)},
      {0.0,       100.0 * A0,         20.0 * A0         }
    };
    const char *names[] = {"full stick", "full stick, clamped mean", "stick-slip A = 1.5 A0", "stick-slip A = 3 A0 with mean", "gross slip A = 100 A0"};
    for (int i = 0; i < 5; i++) {
      PetscCall(FDCheck(&an, cases[i], 1e-6, &err));
      CHECK(err < 1e-6, "jenkins analytic dF/dU vs finite differences, %s: error %.2e", names[i], err);
    }
  }

  /* multi-harmonic: H = 3, motion with a third harmonic and a mean */
  PetscCall(ElemCreate("jenkins", JR_CONTACT_AFT, 3, 2048, kt, 0.0, mu, n0, &aft3f));
  PetscCall(ElemCreate("jenkins", JR_CONTACT_AFT, 3, 64, kt, 0.0, mu, n0, &aft3));
  {
    const double U[7] = {0.4 * A0, 2.0 * A0 * cos(ph), 2.0 * A0 * sin(ph), 0.1 * A0, -0.2 * A0, 0.6 * A0, 0.3 * A0};
    PetscCall(JRContactEvaluate(aft3f.c, U, NULL, F, NULL, NULL, NULL, NULL, NULL));
    BruteForce(kt, 0.0, mu, n0, 7, U, NULL, 1 << 17, 3, Fb, Nb, NULL, 0);
    err = RelDiff(7, F, Fb, r);
    CHECK(err < 1e-5, "jenkins H = 3 (third harmonic in the motion): AFT N = 2048 vs brute-force march, error %.2e (of mu n0)", err);
    PetscCall(JRContactEvaluate(aft3.c, U, NULL, F, NULL, NULL, NULL, NULL, NULL));
    err = RelDiff(7, F, Fb, r);
    CHECK(err < 2e-2, "jenkins H = 3: AFT N = 64 vs brute-force march, error %.2e (of mu n0; coarse grid)", err);
    PetscCall(FDCheck(&aft3, U, 1e-6, &err));
    CHECK(err < 1e-6, "jenkins AFT (H = 3, N = 64) dF/dU vs finite differences: error %.2e", err);
  }
  {
    const double U[7] = {0.0, 0.3 * A0, 0.2 * A0, 0.0, 0.0, 0.1 * A0, 0.0};
    JRContactState st;
    PetscCall(JRContactEvaluate(aft3.c, U, NULL, F, NULL, NULL, NULL, NULL, &st));
    CHECK(st == JR_CONTACT_FULL_STICK && RelDiff(7, F, (double[]){0.0, kt * U[1], kt * U[2], 0.0, 0.0, kt * U[5], 0.0}, r) < 1e-12, "jenkins AFT full stick with H = 3: F = kt U, state %s", JRContactStates[st]);
    PetscCall(FDCheck(&aft3, U, 1e-6, &err));
    CHECK(err < 1e-9, "jenkins AFT full stick dF/dU = kt I: error %.2e", err);
  }

  PetscCall(JRContactDestroy(&an.c));
  PetscCall(JRContactDestroy(&aft.c));
  PetscCall(JRContactDestroy(&aft3.c));
  PetscCall(JRContactDestroy(&aft3f.c));
  PetscCall(PetscFinalize());
  return TestSummary("test_jenkins");
}
