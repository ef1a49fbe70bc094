/*
   jenkins_nv element (normal load variation, thesis 3.3): every one of the 13 single-harmonic
   motion sequences (full separation; P1-P3, N1-N3, E1-E4 of Table 3.2; slip without separation;
   full stick), each checked against an independent brute-force transient time march
   (tests/jrtest.h, 2^17 steps per cycle): the sequence the march goes through, named by the test's
   own table, must be the library's; the force and normal load harmonics must agree. Then: the AFT
   path on a fine grid, every analytic derivative vs central finite differences, kn -> 0 reduces to
   the jenkins element, and multi-harmonic motion (a third harmonic) vs the time march.
   Units: ku = kv = 1e8 N/m (100 kN/mm), lengths in um, n0 of order 100 N.
*/
#include "jrtest.h"

typedef struct {
  const char *name;
  double      a, b, phase_deg, mu, n0; /* u = a sin, v = b sin(theta + phase); a, b in um; n0 in units of 100 N */
} Case;

/* found by a random scan of the classifier, each far from the boundaries of its sequence */
static const Case cases[] = {
  {"full_separation",    3.4889, 0.3850, 7.21,   2.3385, -0.8107},
  {"P1",                 1.1333, 1.0574, 290.78, 1.3866, 1.0    },
  {"P2",                 2.2933, 2.2667, 18.70,  0.3209, 1.0    },
  {"P3",                 4.0094, 0.7787, 39.17,  5.0446, -0.3452},
  {"N1",                 2.3802, 1.0858, 109.54, 1.3442, 1.0    },
  {"N2",                 1.3454, 2.5431, 156.42, 0.1045, 1.0    },
  {"N3",                 8.0862, 3.9029, 247.51, 0.9271, -0.8658},
  {"E1",                 0.6267, 1.2028, 46.72,  0.2523, 1.0    },
  {"E2",                 1.1111, 1.6619, 171.86, 0.9804, 1.0    },
  {"E3",                 1.4364, 1.6575, 208.59, 0.7336, 1.0    },
  {"E4",                 0.2790, 2.8480, 189.36, 0.2205, 1.0    },
  {"slip_no_separation", 3.6466, 0.5927, 120.68, 1.1755, 1.0    },
  {"full_stick",         0.4127, 0.3782, 178.36, 1.1647, 1.0    }
};

static PetscErrorCode Make(const char *type, JRContactMethod method, PetscInt H, PetscInt N, double kt, double kn, double mu, double n0, JRContact *c)
{
  PetscFunctionBeginUser;
  PetscCall(JRContactCreate(PETSC_COMM_SELF, c));
  PetscCall(JRContactSetType(*c, type));
  PetscCall(JRContactSetHarmonics(*c, H, N));
  PetscCall(JRContactSetMethod(*c, method));
  PetscCall(JRContactSetElements(*c, 1, &kt, &kn, &mu, &n0));
  PetscCall(JRContactSetUp(*c));
  PetscFunctionReturn(0);
}

/* finite-difference check of dF/dU, dF/dV and dN/dV (= 0 for dN/dU) (steps hrel times the largest coefficient) */
static PetscErrorCode FDCheck(JRContact c, PetscInt nc, const double *U0, const double *V0, double hrel, double err[3])
{
  double U[JRT_NC], V[JRT_NC], Fp[JRT_NC], Fm[JRT_NC], Np[JRT_NC], Nm[JRT_NC];
  double JU[JRT_NC * JRT_NC], JV[JRT_NC * JRT_NC], JN[JRT_NC * JRT_NC], fU[JRT_NC * JRT_NC], fV[JRT_NC * JRT_NC], fN[JRT_NC * JRT_NC];
  double hu = hrel * MaxAbs(nc, U0), hv = hrel * MaxAbs(nc, V0), nu = 0.0;

  PetscFunctionBeginUser;
  if (hu == 0.0) hu = hv;
  if (hv == 0.0) hv = hu;
  PetscCall(JRContactEvaluate(c, U0, V0, Fp, Np, JU, JV, JN, NULL));
  for (PetscInt m = 0; m < nc; m++) {
    for (int side = 0; side < 2; side++) { /* side 0: perturb U, side 1: perturb V */
      const double h = side ? hv : hu;
      for (PetscInt k = 0; k < nc; k++) {
        U[k] = U0[k];
        V[k] = V0[k];
      }
      (side ? V : U)[m] += h;
      PetscCall(JRContactEvaluate(c, U, V, Fp, Np, NULL, NULL, NULL, NULL));
      (side ? V : U)[m] -= 2.0 * h;
      PetscCall(JRContactEvaluate(c, U, V, Fm, Nm, NULL, NULL, NULL, NULL));
      for (PetscInt k = 0; k < nc; k++) {
        if (side) {
          fV[k * nc + m] = (Fp[k] - Fm[k]) / (2.0 * h);
          fN[k * nc + m] = (Np[k] - Nm[k]) / (2.0 * h);
        } else {
          fU[k * nc + m] = (Fp[k] - Fm[k]) / (2.0 * h);
          nu = fmax(nu, fabs(Np[k] - Nm[k]) / (2.0 * h)); /* dN/du must vanish */
        }
      }
    }
  }
  {
    const double scale = fmax(MaxAbs(nc * nc, JU), fmax(MaxAbs(nc * nc, JV), MaxAbs(nc * nc, JN))); /* stiffness scale */
    err[0]             = scale > 0 ? RelDiff(nc * nc, JU, fU, scale) : MaxAbs(nc * nc, fU);
    err[1]             = scale > 0 ? RelDiff(nc * nc, JV, fV, scale) : MaxAbs(nc * nc, fV);
    err[2]             = scale > 0 ? RelDiff(nc * nc, JN, fN, scale) : MaxAbs(nc * nc, fN);
    err[2]             = fmax(err[2], scale > 0 ? nu / scale : nu);
  }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  const double       k = 1.0e8, um = 1.0e-6, nscale = 100.0;
  JRContact          an, aft;
  double             F[JRT_NC], Nf[JRT_NC], Fa[JRT_NC], Na[JRT_NC], Fb[JRT_NC], Nb[JRT_NC], err, e3[3];
  char               seq[64];
  int                reached[13] = {0};
  JRContactSequence  sq;
  JRContactState     st;
  const JRContactState expect_state[13] = {JR_CONTACT_FULL_SEPARATION, JR_CONTACT_SEPARATION_STICK_SLIP, JR_CONTACT_SEPARATION_STICK_SLIP, JR_CONTACT_SEPARATION_STICK_SLIP, JR_CONTACT_SEPARATION_STICK_SLIP, JR_CONTACT_SEPARATION_STICK_SLIP, JR_CONTACT_SEPARATION_STICK_SLIP, JR_CONTACT_SEPARATION_STICK_SLIP, JR_CONTACT_SEPARATION_STICK_SLIP, JR_CONTACT_SEPARATION_STICK_SLIP, JR_CONTACT_SEPARATION_STICK_SLIP, JR_CONTACT_STICK_SLIP, JR_CONTACT_FULL_STICK};

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (int i = 0; i < 13; i++) {
    const Case  *cs = &cases[i];
    const double ph = cs->phase_deg * M_PI / 180.0, n0 = cs->n0 * nscale;
    const double U[3] = {0.0, cs->a * um, 0.0}, V[3] = {0.0, cs->b * um * cos(ph), cs->b * um * sin(ph)};
    double       fscale, nsc;
    PetscCall(Make("jenkins_nv", JR_CONTACT_ANALYTIC, 1, 64, k, k, cs->mu, n0, &an));
    PetscCall(Make("jenkins_nv", JR_CONTACT_AFT, 1, 4096, k, k, cs->mu, n0, &aft));
    PetscCall(JRContactGetSequences(an, U, V, &sq));
    PetscCall(JRContactEvaluate(an, U, V, F, Nf, NULL, NULL, NULL, &st));
    BruteForce(k, k, cs->mu, n0, 3, U, V, 1 << 17, 4, Fb, Nb, seq, sizeof(seq));
    CHECK(!strcmp(JRContactSequences[sq], cs->name) && !strcmp(SequenceName(seq), cs->name), "jenkins_nv case %s: closed form gives %s, the brute-force march goes through %s = %s", cs->name, JRContactSequences[sq], seq, SequenceName(seq));
    reached[sq] = 1;
    CHECK(st == expect_state[i], "jenkins_nv case %s: contact state %s", cs->name, JRContactStates[st]);
    fscale = fmax(MaxAbs(3, Fb), 1e-3 * nscale);
    nsc    = fmax(MaxAbs(3, Nb), 1e-3 * nscale);
    err    = fmax(RelDiff(3, F, Fb, fscale), RelDiff(3, Nf, Nb, nsc));
    CHECK(err < 1e-4, "jenkins_nv case %s: closed-form f and n harmonics vs brute-force march, error %.2e (F = %.5g %.5g %.5g N)", cs->name, err, F[0], F[1], F[2]);
    PetscCall(JRContactEvaluate(aft, U, V, Fa, Na, NULL, NULL, NULL, NULL));
    err = fmax(RelDiff(3, F, Fa, fscale), RelDiff(3, Nf, Na, nsc));
    CHECK(err < 1e-5, "jenkins_nv case %s: closed form vs AFT (N = 4096), error %.2e", cs->name, err);
    if (i == 0) CHECK(MaxAbs(3, F) == 0.0 && MaxAbs(3, Nf) == 0.0 && MaxAbs(3, Fa) == 0.0 && MaxAbs(3, Na) == 0.0, "jenkins_nv full separation: zero force and zero normal load (both paths)");
    PetscCall(FDCheck(an, 3, U, V, 1e-6, e3));
    CHECK(fmax(e3[0], fmax(e3[1], e3[2])) < 1e-6, "jenkins_nv case %s: analytic dF/du %.1e, dF/dv %.1e, dN/dv %.1e vs finite differences", cs->name, e3[0], e3[1], e3[2]);
    /* the same motion with a mean normal displacement and a mean slip offset */
    {
      const double U2[3] = {0.2 * cs->a * um, U[1], U[2]}, V2[3] = {0.1 * cs->b * um, V[1], V[2]};
      PetscCall(JRContactEvaluate(an, U2, V2, F, Nf, NULL, NULL, NULL, NULL));
      BruteForce(k, k, cs->mu, n0, 3, U2, V2, 1 << 16, 4, Fb, Nb, NULL, 0);
      err = fmax(RelDiff(3, F, Fb, fscale), RelDiff(3, Nf, Nb, nsc));
      CHECK(err < 2e-4, "jenkins_nv case %s with means u0 = %.3g um, v0 = %.3g um: closed form vs brute-force march, error %.2e", cs->name, U2[0] / um, V2[0] / um, err);
    }
    PetscCall(JRContactDestroy(&an));
    PetscCall(JRContactDestroy(&aft));
  }
  {
    int n = 0;
    for (int i = 0; i < 13; i++) n += reached[i];
    CHECK(n == 13, "jenkins_nv: %d of the 13 motion sequences reached", n);
  }

  /* kn -> 0: the constant-normal-load element */
  {
    JRContact    jk, nv0, nvs;
    const double mu = 0.12, n0 = 100.0, A0 = mu * n0 / k, ph = 0.7;
    PetscCall(Make("jenkins", JR_CONTACT_ANALYTIC, 1, 64, k, 0.0, mu, n0, &jk));
    PetscCall(Make("jenkins_nv", JR_CONTACT_ANALYTIC, 1, 64, k, 0.0, mu, n0, &nv0));
    PetscCall(Make("jenkins_nv", JR_CONTACT_ANALYTIC, 1, 64, k, 1e-6 * k, mu, n0, &nvs));
    for (double r = 0.5; r < 50; r *= 2.3) {
      const double U[3] = {0.1 * A0, r * A0 * cos(ph), r * A0 * sin(ph)}, V[3] = {0.0, 0.3 * A0, -0.2 * A0};
      double       Fj[3], F0[3], Fs[3], Jj[9], J0[9];
      PetscCall(JRContactEvaluate(jk, U, NULL, Fj, NULL, Jj, NULL, NULL, NULL));
      PetscCall(JRContactEvaluate(nv0, U, V, F0, NULL, J0, NULL, NULL, NULL));
      PetscCall(JRContactEvaluate(nvs, U, V, Fs, NULL, NULL, NULL, NULL, NULL));
      CHECK(RelDiff(3, Fj, F0, mu * n0) < 1e-12 && RelDiff(9, Jj, J0, k) < 1e-10, "jenkins_nv with kn = 0 equals jenkins at A = %.3g A0: force %.1e, Jacobian %.1e", r, RelDiff(3, Fj, F0, mu * n0), RelDiff(9, Jj, J0, k));
      CHECK(RelDiff(3, Fj, Fs, mu * n0) < 1e-5, "jenkins_nv with kn = 1e-6 kt tends to jenkins at A = %.3g A0: difference %.1e of mu n0", r, RelDiff(3, Fj, Fs, mu * n0));
    }
    /* full stick with a mean outside the stick band: the slip sits at the band edge (max L or min U) */
    for (int sgn = -1; sgn <= 1; sgn += 2) {
      const double U[3] = {sgn * 3.0 * A0, 0.5 * A0 * cos(ph), 0.5 * A0 * sin(ph)}, V[3] = {0.2 * A0, 0.1 * A0, 0.05 * A0};
      double       Fj[3], F0[3], Fb[3], Nb[3];
      PetscCall(JRContactEvaluate(jk, U, NULL, Fj, NULL, NULL, NULL, NULL, NULL));
      PetscCall(JRContactEvaluate(nv0, U, V, F0, NULL, NULL, NULL, NULL, NULL));
      CHECK(RelDiff(3, Fj, F0, mu * n0) < 1e-12, "jenkins_nv (kn = 0) full stick, mean %+g A0 outside the band: equals jenkins (F0 = %.6g N)", sgn * 3.0, F0[0]);
      PetscCall(JRContactEvaluate(nvs, U, V, F0, NULL, NULL, NULL, NULL, NULL));
      BruteForce(k, 1e-6 * k, mu, n0, 3, U, V, 1 << 16, 3, Fb, Nb, NULL, 0);
      CHECK(RelDiff(3, F0, Fb, mu * n0) < 1e-6, "jenkins_nv full stick, mean %+g A0 outside the band: closed form vs brute-force march, error %.1e", sgn * 3.0, RelDiff(3, F0, Fb, mu * n0));
      PetscCall(FDCheck(nvs, 3, U, V, 1e-6, e3));
      CHECK(fmax(e3[0], fmax(e3[1], e3[2])) < 1e-6, "jenkins_nv full stick at the band edge: dF/du %.1e, dF/dv %.1e, dN/dv %.1e vs finite differences", e3[0], e3[1], e3[2]);
    }
    PetscCall(JRContactDestroy(&jk));
    PetscCall(JRContactDestroy(&nv0));
    PetscCall(JRContactDestroy(&nvs));
  }

  /* multi-harmonic motion: a third harmonic in u and v, with separation, H = 3 */
  {
    JRContact    fine, coarse;
    const double mu = 0.5, n0 = 100.0;
    const double U[7] = {0.1 * um, 2.0 * um, 0.5 * um, 0.0, 0.0, 0.6 * um, -0.2 * um};
    const double Vs[2][7] = {
      {0.05 * um, 0.9 * um, 0.8 * um, 0.0, 0.0, 0.3 * um, 0.2 * um}, /* separates */
      {0.0,       0.3 * um, 0.2 * um, 0.0, 0.0, 0.1 * um, 0.0     }  /* stays in contact */
    };
    const JRContactState expect[2] = {JR_CONTACT_SEPARATION_STICK_SLIP, JR_CONTACT_STICK_SLIP};
    const char          *label[2]  = {"with", "without"};
    PetscCall(Make("jenkins_nv", JR_CONTACT_AFT, 3, 2048, k, k, mu, n0, &fine));
    PetscCall(Make("jenkins_nv", JR_CONTACT_AFT, 3, 128, k, k, mu, n0, &coarse));
    for (int i = 0; i < 2; i++) {
      PetscCall(JRContactEvaluate(fine, U, Vs[i], F, Nf, NULL, NULL, NULL, &st));
      BruteForce(k, k, mu, n0, 7, U, Vs[i], 1 << 17, 4, Fb, Nb, seq, sizeof(seq));
      err = fmax(RelDiff(7, F, Fb, MaxAbs(7, Fb)), RelDiff(7, Nf, Nb, MaxAbs(7, Nb)));
      CHECK(err < 1e-4 && st == expect[i], "jenkins_nv H = 3 %s separation (march states %s): AFT N = 2048 vs brute-force march, error %.2e", label[i], seq, err);
      PetscCall(FDCheck(coarse, 7, U, Vs[i], 1e-6, e3));
      CHECK(fmax(e3[0], fmax(e3[1], e3[2])) < 1e-6, "jenkins_nv AFT (H = 3, N = 128) %s separation: dF/du %.1e, dF/dv %.1e, dN/dv %.1e vs finite differences", label[i], e3[0], e3[1], e3[2]);
    }
    PetscCall(JRContactDestroy(&fine));
    PetscCall(JRContactDestroy(&coarse));
  }
  PetscCall(PetscFinalize());
  return TestSummary("test_jenkins_nv");
}
