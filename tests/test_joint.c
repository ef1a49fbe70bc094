/*
   Batches and joints.
   - The SoA batch evaluation of many elements with different parameters and motions equals the
     evaluation of each element alone (the batch layout is only a layout).
   - A joint (elements in parallel sharing one motion, (4.1)-(4.2), (5.2)-(5.5)) equals the sum of
     its members, for a subset of members too.
   - Energy balance of the joint's hysteresis loop: the loop area (trapezoidal integral of f du
     over the marched cycle) equals the dissipated energy from the force harmonics, and the normal
     load does no net work over a cycle (n is a function of v).
*/
#include "jrtest.h"

#define NE 24

int main(int argc, char **argv)
{
  const double k = 1.0e8, um = 1.0e-6;
  const char  *types[2] = {"jenkins", "jenkins_nv"};

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (int t = 0; t < 2; t++) {
    for (PetscInt H = 1; H <= 3; H += 2) {
      const PetscInt  nc = 2 * H + 1;
      JRContact       batch, one;
      double          kt[NE], kn[NE], mu[NE], n0[NE], U[NE * 7], V[NE * 7], F[NE * 7], N[NE * 7], DU[NE * 49], DV[NE * 49], DN[NE * 49];
      double          maxdiff = 0.0;
      JRContactState  st[NE];
      const char     *path = H == 1 ? "analytic" : "aft";
      srand(7 + t);
      for (int e = 0; e < NE; e++) {
        kt[e] = k * (0.5 + (double)rand() / RAND_MAX);
        kn[e] = k * (0.5 + (double)rand() / RAND_MAX);
        mu[e] = 0.1 + 0.5 * rand() / RAND_MAX;
        n0[e] = (t ? -50.0 : 0.0) + 200.0 * rand() / RAND_MAX;
        for (PetscInt c = 0; c < nc; c++) {
          U[c * NE + e] = um * (c ? 3.0 : 0.3) * (2.0 * rand() / RAND_MAX - 1.0) / (c > 2 ? 3.0 : 1.0);
          V[c * NE + e] = um * (c ? 1.5 : 0.3) * (2.0 * rand() / RAND_MAX - 1.0) / (c > 2 ? 3.0 : 1.0);
        }
      }
      PetscCall(JRContactCreate(PETSC_COMM_SELF, &batch));
      PetscCall(JRContactSetType(batch, types[t]));
      PetscCall(JRContactSetHarmonics(batch, H, 2048)); /* fine AFT grid: the loop energy check compares quadratures */
      PetscCall(JRContactSetElements(batch, NE, kt, kn, mu, n0));
      PetscCall(JRContactEvaluate(batch, U, V, F, N, DU, DV, DN, st));
      PetscCall(JRContactCreate(PETSC_COMM_SELF, &one));
      PetscCall(JRContactSetType(one, types[t]));
      PetscCall(JRContactSetHarmonics(one, H, 2048));
      for (int e = 0; e < NE; e++) {
        double         Ue[7], Ve[7], Fe[7], Ne[7], Du[49], Dv[49], Dn[49];
        JRContactState se;
        PetscCall(JRContactSetElements(one, 1, &kt[e], &kn[e], &mu[e], &n0[e]));
        for (PetscInt c = 0; c < nc; c++) {
          Ue[c] = U[c * NE + e];
          Ve[c] = V[c * NE + e];
        }
        PetscCall(JRContactEvaluate(one, Ue, Ve, Fe, Ne, Du, Dv, Dn, &se));
        for (PetscInt c = 0; c < nc; c++) maxdiff = fmax(maxdiff, fmax(fabs(Fe[c] - F[c * NE + e]), fabs(Ne[c] - N[c * NE + e])));
        for (PetscInt c = 0; c < nc * nc; c++) maxdiff = fmax(maxdiff, fmax(fabs(Du[c] - DU[c * NE + e]), fmax(fabs(Dv[c] - DV[c * NE + e]), fabs(Dn[c] - DN[c * NE + e]))));
        if (se != st[e]) maxdiff = INFINITY;
      }
      CHECK(maxdiff == 0.0, "%s %s H = %" PetscInt_FMT ": batch of %d elements (SoA) equals one-by-one evaluation (max difference %.1e)", types[t], path, H, NE, maxdiff);

      /* joint of members {1, 4, 5, 9, 17} under one motion = sum of the members */
      {
        const PetscInt members[5] = {1, 4, 5, 9, 17};
        double         Uj[7], Vj[7], Fj[7], Nj[7], Dj[49], Fs[7] = {0}, Ns[7] = {0}, Ds[49] = {0}, scale = 0.0, d;
        JRContactState sj;
        for (PetscInt c = 0; c < nc; c++) {
          Uj[c] = U[c * NE + 3];
          Vj[c] = V[c * NE + 3];
        }
        PetscCall(JRContactEvaluateJoint(batch, 5, members, Uj, Vj, Fj, Nj, Dj, NULL, NULL, &sj));
        for (int i = 0; i < 5; i++) {
          double Fe[7], Ne[7], De[49];
          PetscCall(JRContactSetElements(one, 1, &kt[members[i]], &kn[members[i]], &mu[members[i]], &n0[members[i]]));
          PetscCall(JRContactEvaluate(one, Uj, Vj, Fe, Ne, De, NULL, NULL, NULL));
          for (PetscInt c = 0; c < nc; c++) {
            Fs[c] += Fe[c];
            Ns[c] += Ne[c];
          }
          for (PetscInt c = 0; c < nc * nc; c++) Ds[c] += De[c];
        }
        scale = fmax(MaxAbs(nc, Fs), 1.0);
        d     = fmax(RelDiff(nc, Fj, Fs, scale), fmax(RelDiff(nc, Nj, Ns, fmax(MaxAbs(nc, Ns), 1.0)), RelDiff(nc * nc, Dj, Ds, fmax(MaxAbs(nc * nc, Ds), 1.0))));
        CHECK(d < 1e-14, "%s %s H = %" PetscInt_FMT ": joint of 5 elements = sum of its members (difference %.1e), joint state %s", types[t], path, H, d, JRContactStates[sj]);

        /* energy balance of the joint loop */
        {
          const PetscInt ns = 8192;
          double        *lu, *lv, *lf, *ln, area = 0.0, nwork = 0.0, D, nscale = 0.0;
          PetscCall(PetscMalloc4(ns, &lu, ns, &lv, ns, &lf, ns, &ln));
          PetscCall(JRContactJointLoop(batch, 5, members, Uj, Vj, ns, lu, lv, lf, ln));
          for (PetscInt j = 0; j < ns; j++) {
            const PetscInt jn = (j + 1) % ns;
            area += 0.5 * (lf[j] + lf[jn]) * (lu[jn] - lu[j]);
            nwork += 0.5 * (ln[j] + ln[jn]) * (lv[jn] - lv[j]);
            nscale += fabs(0.5 * (ln[j] + ln[jn]) * (lv[jn] - lv[j]));
          }
          PetscCall(JRHarmonicWork(nc, Uj, Fj, &D));
          CHECK(fabs(area - D) < 1e-4 * fabs(D) + 1e-12, "%s %s H = %" PetscInt_FMT ": joint loop area %.6g J = dissipated energy from the harmonics %.6g J", types[t], path, H, area, D);
          CHECK(t == 0 || fabs(nwork) < 1e-3 * nscale + 1e-15, "%s %s H = %" PetscInt_FMT ": normal load does no net work over the loop (%.2e J of %.2e J)", types[t], path, H, nwork, nscale);
          PetscCall(PetscFree4(lu, lv, lf, ln));
        }
      }
      PetscCall(JRContactDestroy(&batch));
      PetscCall(JRContactDestroy(&one));
    }
  }
  PetscCall(PetscFinalize());
  return TestSummary("test_joint");
}
