/*
   Element evaluations per second, with all derivatives, on a batch of elements split across the
   MPI ranks (-elements in total, default 10^6): jenkins and jenkins_nv, analytic (H = 1) and
   AFT (-harmonics 3, -samples 64 by default). Motions are drawn so that the batch mixes full stick, stick-slip,
   gross slip and (jenkins_nv) separation. Prints one line per case:
     bench <type> <path> H <H> N <N> ranks <p> elements <n> time_s <t> evals_per_s <r> per_core <r/p>
   Outputs are 64-byte aligned (JRMallocAligned), so whole SoA rows are streamed to memory.
   Timing is the best of -repeat runs, each bracketed by barriers (the slowest rank counts).
*/
#include <jointrom.h>

static PetscErrorCode Bench(MPI_Comm comm, const char *type, JRContactMethod method, PetscInt H, PetscInt N, PetscInt ntot, PetscInt repeat)
{
  PetscMPIInt    rank, size;
  PetscInt       n, nc = 2 * H + 1;
  PetscReal     *kt, *kn, *mu, *n0, *U, *V, *F, *Nf, *DU, *DV, *DN;
  JRContactState *st;
  JRContact      c;
  PetscBool      normal;
  double         best = 1e300;
  PetscInt       count[4] = {0, 0, 0, 0}, gcount[4];

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  n = ntot / size + (rank < ntot % size);
  PetscCall(JRContactCreate(comm, &c));
  PetscCall(JRContactSetType(c, type));
  PetscCall(JRContactSetHarmonics(c, H, N));
  PetscCall(JRContactSetMethod(c, method));
  PetscCall(JRContactUsesNormal(c, &normal));
  PetscCall(PetscMalloc4(n, &kt, n, &kn, n, &mu, n, &n0));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * n * nc, &U));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * n * nc, &V));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * n * nc, &F));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * n * nc, &Nf));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * n * nc * nc, &DU));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * n * nc * nc, &DV));
  PetscCall(JRMallocAligned(sizeof(PetscReal) * n * nc * nc, &DN));
  PetscCall(PetscMalloc1(n, &st));
  srand(1234 + rank);
  for (PetscInt e = 0; e < n; e++) {
    const double A0 = 0.12 * 100.0 / 1.0e8, amp = A0 * pow(10.0, -0.5 + 2.0 * rand() / RAND_MAX); /* 0.3 .. 30 x slip onset */
    const double ph = 2.0 * PETSC_PI * rand() / RAND_MAX, vph = 2.0 * PETSC_PI * rand() / RAND_MAX;
    kt[e] = 1.0e8;
    kn[e] = 1.0e8;
    mu[e] = 0.12;
    n0[e] = 100.0 * (0.2 + 1.8 * rand() / RAND_MAX);
    for (PetscInt k = 0; k < nc; k++) U[k * n + e] = V[k * n + e] = 0.0;
    U[1 * n + e] = amp * cos(ph);
    U[2 * n + e] = amp * sin(ph);
    V[1 * n + e] = 1.2 * A0 * 10.0 * rand() / RAND_MAX * cos(vph); /* up to 1.2 um normal motion: some separate */
    V[2 * n + e] = 1.2 * A0 * 10.0 * rand() / RAND_MAX * sin(vph);
    if (H >= 3) {
      U[5 * n + e] = 0.2 * amp * cos(2 * ph);
      V[5 * n + e] = 0.2 * V[1 * n + e];
    }
  }
  PetscCall(JRContactSetElements(c, n, kt, kn, mu, n0));
  PetscCall(JRContactSetUp(c));
  for (PetscInt r = 0; r < repeat; r++) {
    double t0, t1, tl, tmax;
    PetscCallMPI(MPI_Barrier(comm));
    t0 = MPI_Wtime();
    PetscCall(JRContactEvaluate(c, U, normal ? V : NULL, F, normal ? Nf : NULL, DU, normal ? DV : NULL, normal ? DN : NULL, st));
    t1 = MPI_Wtime();
    tl = t1 - t0;
    PetscCallMPI(MPI_Allreduce(&tl, &tmax, 1, MPI_DOUBLE, MPI_MAX, comm));
    best = PetscMin(best, tmax);
  }
  for (PetscInt e = 0; e < n; e++) count[st[e]]++;
  PetscCall(MPIU_Allreduce(count, gcount, 4, MPIU_INT, MPI_SUM, comm));
  PetscCall(PetscPrintf(comm, "bench %-10s %-8s H %" PetscInt_FMT " N %3" PetscInt_FMT " ranks %d elements %" PetscInt_FMT " time_s %.4f evals_per_s %.3e per_core %.3e  (stick %" PetscInt_FMT ", slip %" PetscInt_FMT ", separation %" PetscInt_FMT ", full sep %" PetscInt_FMT ")\n", type, JRContactMethods[method], H, method == JR_CONTACT_AFT ? N : 0, size, ntot, best, ntot / best, ntot / best / size, gcount[0], gcount[1], gcount[2], gcount[3]));
  PetscCall(PetscFree4(kt, kn, mu, n0));
  PetscCall(JRFreeAligned(&U));
  PetscCall(JRFreeAligned(&V));
  PetscCall(JRFreeAligned(&F));
  PetscCall(JRFreeAligned(&Nf));
  PetscCall(JRFreeAligned(&DU));
  PetscCall(JRFreeAligned(&DV));
  PetscCall(JRFreeAligned(&DN));
  PetscCall(PetscFree(st));
  PetscCall(JRContactDestroy(&c));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscInt ntot = 1000000, repeat = 3, H = 3, N = 64;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-elements", &ntot, NULL)); /* option names are case-insensitive */
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-repeat", &repeat, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-harmonics", &H, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-samples", &N, NULL));
  PetscCall(Bench(PETSC_COMM_WORLD, "jenkins", JR_CONTACT_ANALYTIC, 1, 64, ntot, repeat));
  PetscCall(Bench(PETSC_COMM_WORLD, "jenkins_nv", JR_CONTACT_ANALYTIC, 1, 64, ntot, repeat));
  PetscCall(Bench(PETSC_COMM_WORLD, "jenkins", JR_CONTACT_AFT, H, N, ntot, repeat));
  PetscCall(Bench(PETSC_COMM_WORLD, "jenkins_nv", JR_CONTACT_AFT, H, N, ntot, repeat));
  PetscCall(PetscFinalize());
  return 0;
}
