/*
   Bolt preload (JRPreload) against independent truths:
   - flat punch: two blocks (distorted hexahedra inside) pressed together by a uniform pressure p on their
     outer faces, with consistent nodal forces from Simpson's rule written here: the contact pressure is p
     at every pair and the total is p x area (exact for Q2: uniaxial stress is a linear displacement field);
     the node areas equal the Simpson weights; penalty and augmented Lagrangian both;
   - a bolted lap: equilibrium (sum of pair loads = sum of pretensions), no tension, complementarity from the
     displacement itself (closed pairs touch, open pairs carry nothing and their gap is the opening), the two
     mirror symmetries of the geometry (y about the centre line; the 180-degree turn about the lap centre that
     swaps the two beams), the penalty result approaching the augmented-Lagrangian one as kp grows, the
     augmented result independent of kp, open and closed Newton starts giving the same answer, n0 (5.1);
   - the results written to CSV and HDF5 read back (-preload_load) equal; files that do not match the
     model's pairs, negative preloads, a wrong number of forces and a tied interface are errors.
*/
#include "jrtest_gmsh.h"
#include <slepcsys.h>

/* preload of model m with the options opts (added to the model's); results copied to N, gap (if given) */
static PetscErrorCode Preload(JRModel m, const char *opts, Vec fext, PetscInt nsup, const PetscInt *sdof, const PetscReal *sdir, JRPreload *pre)
{
  PetscFunctionBeginUser;
  PetscCall(Options(opts));
  PetscCall(JRPreloadCreate(PETSC_COMM_WORLD, pre));
  PetscCall(JRPreloadSetModel(*pre, m));
  if (fext) PetscCall(JRPreloadSetExternalForce(*pre, fext));
  for (PetscInt i = 0; i < nsup; i++) PetscCall(JRPreloadAddSupport(*pre, sdof[i], sdir + 3 * i));
  PetscCall(JRPreloadSetFromOptions(*pre));
  PetscCall(JRPreloadSolve(*pre));
  PetscFunctionReturn(0);
}

/* an error expected from set-up or solve; returns the error code */
static PetscErrorCode PreloadError(JRModel m, const char *opts)
{
  JRPreload      pre;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(Options(opts));
  PetscCall(JRPreloadCreate(PETSC_COMM_WORLD, &pre));
  PetscCall(JRPreloadSetModel(pre, m));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = JRPreloadSetFromOptions(pre);
  if (!ierr) ierr = JRPreloadSolve(pre);
  PetscCall(PetscPopErrorHandler());
  (void)JRPreloadDestroy(&pre);
  return ierr;
}

/* the first global DOF of the node at x (every rank; -1 if none) */
static PetscErrorCode NodeAt(Vec X, const PetscReal x[3], PetscInt *dof)
{
  const PetscScalar *a;
  PetscInt           n, rs, found = -1;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetOwnershipRange(X, &rs, NULL));
  PetscCall(VecGetArrayRead(X, &a));
  for (PetscInt i = 0; i < n; i += 3)
    if (PetscAbsReal(a[i] - x[0]) < 1e-12 && PetscAbsReal(a[i + 1] - x[1]) < 1e-12 && PetscAbsReal(a[i + 2] - x[2]) < 1e-12) found = rs + i;
  PetscCall(VecRestoreArrayRead(X, &a));
  PetscCallMPI(MPI_Allreduce(&found, dof, 1, MPIU_INT, MPI_MAX, PETSC_COMM_WORLD));
  PetscFunctionReturn(0);
}

/* Simpson (Q2) weight of a node at coordinate s on [0, L] cut into ne equal elements */
static PetscReal Simpson(PetscReal s, PetscReal L, PetscInt ne)
{
  const PetscReal h = L / ne;
  const PetscInt  k = (PetscInt)PetscFloorReal(s / (0.5 * h) + 0.5);
  return h / 6 * (k % 2 ? 4.0 : (k == 0 || k == 2 * ne) ? 1.0 : 2.0);
}

/* ---- flat punch ---- */
static PetscErrorCode TestFlatPunch(const char *dir)
{
  char            file[PETSC_MAX_PATH_LEN], opts[PETSC_MAX_PATH_LEN + 128];
  JRModel         m;
  Vec             X, f;
  const PetscReal p = 2e6; /* Pa */
  PetscInt        sdof[9];
  PetscReal       sdir[27];
  const JRPairs  *P;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(file, sizeof(file), "%s/blocks.msh", dir));
  PetscCall(WriteGmsh(file, PETSC_FALSE, 0.0, NULL));
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  PetscCall(PetscSNPrintf(opts, sizeof(opts), "-model_type gmsh -model_file %s -model_E 200e9 -model_nu 0.3 -model_rho 7800", file));
  PetscCall(ModelCreate(opts, &m));
  PetscCall(JRModelGetPairs(m, &P));
  { /* node areas = Simpson weights (computed here from the coordinates) */
    PetscReal err = 0.0, sum = 0.0;
    for (PetscInt i = 0; i < P->n; i++) {
      err = PetscMax(err, PetscAbsReal(P->area[i] - Simpson(P->x[3 * i], GM_LX, GM_NX) * Simpson(P->x[3 * i + 1], GM_LY, GM_NY)));
      sum += P->area[i];
    }
    CHECK(err < 1e-15 && PetscAbsReal(sum / (GM_LX * GM_LY) - 1) < 1e-13, "node areas of the interface = Simpson weights (largest difference %.1e m^2), sum %.15g = Lx Ly %.15g m^2", (double)err, (double)sum, (double)(GM_LX * GM_LY));
  }
  /* consistent forces of p on A's bottom (z = 0, pushing up) and B's top (z = 2c, pushing down) */
  PetscCall(JRModelGetCoordinates(m, &X));
  PetscCall(VecDuplicate(X, &f));
  {
    const PetscScalar *x;
    PetscScalar       *fa;
    PetscInt           n;
    PetscCall(VecGetLocalSize(X, &n));
    PetscCall(VecGetArrayRead(X, &x));
    PetscCall(VecGetArray(f, &fa));
    for (PetscInt i = 0; i < n; i += 3) {
      const PetscReal w = Simpson(x[i], GM_LX, GM_NX) * Simpson(x[i + 1], GM_LY, GM_NY);
      fa[i] = fa[i + 1] = fa[i + 2] = 0.0;
      if (PetscAbsReal(x[i + 2]) < 1e-12) fa[i + 2] = p * w;
      if (PetscAbsReal(x[i + 2] - 2 * GM_C) < 1e-12) fa[i + 2] = -p * w;
    }
    PetscCall(VecRestoreArray(f, &fa));
    PetscCall(VecRestoreArrayRead(X, &x));
  }
  { /* supports: A by 3-2-1 on its bottom corners; B's sliding (x, y, turn about z) on its top corners */
    const PetscReal at[5][3] = {
      {0,     0,     0       },
      {GM_LX, 0,     0       },
      {0,     GM_LY, 0       },
      {0,     0,     2 * GM_C},
      {GM_LX, 0,     2 * GM_C}
    };
    const PetscInt  node[9]    = {0, 0, 0, 1, 1, 2, 3, 3, 4};
    const PetscInt  comp[9]    = {0, 1, 2, 1, 2, 2, 0, 1, 1};
    PetscInt        d[5];
    for (int k = 0; k < 5; k++) PetscCall(NodeAt(X, at[k], &d[k]));
    for (int k = 0; k < 9; k++) {
      sdof[k] = d[node[k]];
      for (int c = 0; c < 3; c++) sdir[3 * k + c] = c == comp[k] ? 1.0 : 0.0;
    }
    CHECK(d[0] >= 0 && d[1] >= 0 && d[2] >= 0 && d[3] >= 0 && d[4] >= 0, "flat punch: the support nodes found");
  }
  for (int meth = 0; meth < 2; meth++) {
    JRPreload        pre;
    PetscInt         n;
    const PetscReal *N, *g;
    PetscReal        err = 0.0, tot = 0.0, gmax = 0.0;
    PetscCall(Preload(m, meth ? "-preload_support none -preload_method augmented" : "-preload_support none -preload_method penalty", f, 9, sdof, sdir, &pre));
    PetscCall(JRPreloadGetResults(pre, &n, &N, &g));
    for (PetscInt i = 0; i < n; i++) {
      err = PetscMax(err, PetscAbsReal(N[i] / P->area[i] / p - 1));
      tot += N[i];
      gmax = PetscMax(gmax, g[i]);
    }
    CHECK(err < 1e-8 && PetscAbsReal(tot / (p * GM_LX * GM_LY) - 1) < 1e-10 && gmax == 0.0, "flat punch (%s): contact pressure = p at every pair to %.1e, total %.10g N = p Lx Ly %.10g N, no gap", meth ? "augmented Lagrangian" : "penalty", (double)err, (double)tot, (double)(p * GM_LX * GM_LY));
    PetscCall(JRPreloadDestroy(&pre));
  }
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&X));
  PetscCall(JRModelDestroy(&m));
  PetscFunctionReturn(0);
}

/* ---- bolted lap ---- */
#define LAP "-model_type lap -model_length_a 0.1 -model_length_b 0.1 -model_lap_length 0.05 -model_width 0.025 -model_height 0.02 -model_nbolts 1 -model_bolt_diameter 0.008 -model_hole_diameter 0.009 -model_washer_diameter 0.016 -model_mesh_h 0.005 -model_mesh_grade 2 "

/* penetration w_i of every pair from the displacement (independently of the solver's bookkeeping) */
static PetscErrorCode Penetration(JRPreload pre, const JRPairs *P, PetscReal *w)
{
  Vec                u, s;
  VecScatter         sc;
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(JRPreloadGetSolution(pre, &u));
  PetscCall(VecScatterCreateToAll(u, &sc, &s));
  PetscCall(VecScatterBegin(sc, u, s, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, u, s, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(s, &a));
  for (PetscInt i = 0; i < P->n; i++) {
    w[i] = -P->gap0[i];
    for (int d = 0; d < 3; d++) w[i] += (PetscRealPart(a[P->dofA[3 * i + d]]) - PetscRealPart(a[P->dofB[3 * i + d]])) * P->nrm[3 * i + d];
  }
  PetscCall(VecRestoreArrayRead(s, &a));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&s));
  PetscFunctionReturn(0);
}

/* the pair at the mirror image of pair i (y -> W - y, or the turn x -> 2 xc - x, y -> W - y); -1 if none */
static PetscInt Mirror(const JRPairs *P, PetscInt i, PetscReal W, PetscReal xc, PetscBool turn)
{
  const PetscReal xm = turn ? 2 * xc - P->x[3 * i] : P->x[3 * i], ym = W - P->x[3 * i + 1];
  for (PetscInt j = 0; j < P->n; j++)
    if (PetscAbsReal(P->x[3 * j] - xm) < 1e-9 && PetscAbsReal(P->x[3 * j + 1] - ym) < 1e-9) return j;
  return -1;
}

static PetscErrorCode TestLap(const char *dir)
{
  JRModel          m;
  JRPreload        pre;
  const JRPairs   *P;
  PetscInt         n, closed = 0;
  const PetscReal *N, *g;
  PetscReal       *Nal, *w, Nmax = 0.0, gmax = 0.0, tot = 0.0, kp0;
  const PetscReal  F = 8000.0, W = 0.025, xc = 0.1 - 0.025; /* the lap spans x in [0.05, 0.1] */
  JRPreloadSummary s;

  PetscFunctionBeginUser;
  PetscCall(ModelCreate(LAP, &m));
  PetscCall(JRModelGetPairs(m, &P));
  PetscCall(PetscMalloc2(P->n, &Nal, P->n, &w));
  PetscCall(Preload(m, "-preload_force 8000", NULL, 0, NULL, NULL, &pre));
  PetscCall(JRPreloadGetResults(pre, &n, &N, &g));
  PetscCall(JRPreloadGetSummary(pre, &s));
  kp0 = s.penalty;
  for (PetscInt i = 0; i < n; i++) {
    Nal[i] = N[i];
    tot += N[i];
    Nmax = PetscMax(Nmax, N[i]);
    gmax = PetscMax(gmax, g[i]);
    closed += N[i] > 0;
  }
  CHECK(PetscAbsReal(tot / F - 1) < 5e-3, "bolted lap, 8 kN: sum of the pair loads %.8g N = pretension %.8g N (relative %.1e; required 0.5%%)", (double)tot, (double)F, (double)PetscAbsReal(tot / F - 1));
  CHECK(closed > 0 && closed < n && gmax > 0, "bolted lap: %" PetscInt_FMT " of %" PetscInt_FMT " pairs closed, the lap ends open (largest gap %.3g um)", closed, n, (double)(gmax * 1e6));
  {
    PetscReal neg = 0.0, pen = 0.0, opn = 0.0;
    PetscCall(Penetration(pre, P, w));
    for (PetscInt i = 0; i < n; i++) {
      neg = PetscMin(neg, N[i]);
      if (N[i] > 0) pen = PetscMax(pen, PetscAbsReal(w[i])); /* closed: the surfaces touch */
      else opn = PetscMax(opn, PetscAbsReal(g[i] + w[i]));    /* open: the gap is the opening */
    }
    CHECK(neg >= 0.0, "bolted lap: no tension (smallest pair load %g N)", (double)neg);
    CHECK(pen < 1e-5 * gmax && opn < 1e-8 * gmax, "complementarity from the displacement: closed pairs |w| <= %.1e m (1e-5 of the largest gap), open pairs carry 0 N and their gap is the opening to %.1e m", (double)pen, (double)opn);
  }
  { /* symmetries */
    PetscReal ey = 0.0, et = 0.0;
    PetscInt  miss = 0;
    for (PetscInt i = 0; i < n; i++) {
      const PetscInt jy = Mirror(P, i, W, xc, PETSC_FALSE), jt = Mirror(P, i, W, xc, PETSC_TRUE);
      if (jy < 0 || jt < 0) {
        miss++;
        continue;
      }
      ey = PetscMax(ey, PetscAbsReal(N[i] - N[jy]) / Nmax);
      et = PetscMax(et, PetscAbsReal(N[i] - N[jt]) / Nmax);
    }
    CHECK(miss == 0 && ey < 1e-6 && et < 1e-6, "symmetric geometry, symmetric loads: mirror y -> W - y %.1e, half-turn about the lap centre %.1e (of the largest pair load)", (double)ey, (double)et);
  }
  {
    PetscReal n0[4096];
    PetscInt  bad = 0;
    PetscCheck(n <= 4096, PETSC_COMM_SELF, PETSC_ERR_PLIB, "too many pairs for the test");
    PetscCall(JRPreloadGetN0(pre, 1e8, n0));
    for (PetscInt i = 0; i < n; i++) bad += PetscAbsReal(n0[i] - (N[i] - 1e8 * g[i])) > 1e-12 * (Nmax + 1e8 * gmax);
    CHECK(bad == 0, "n0 = N_static - kv v_gap (5.1) with kv = 1e8 N/m");
  }
  /* write, read back */
  {
    char base[PETSC_MAX_PATH_LEN], opt[PETSC_MAX_PATH_LEN + 32];
    PetscCall(PetscSNPrintf(base, sizeof(base), "%s/lap", dir));
    PetscCall(JRPreloadWrite(pre, base, PETSC_FALSE));
    for (int k = 0; k < 2; k++) {
      JRPreload        rd;
      const PetscReal *N2, *g2;
      PetscInt         n2;
      PetscReal        e = 0.0;
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-preload_load %s.%s", base, k ? "h5" : "csv"));
      PetscCall(Preload(m, opt, NULL, 0, NULL, NULL, &rd));
      PetscCall(JRPreloadGetResults(rd, &n2, &N2, &g2));
      for (PetscInt i = 0; i < n2; i++) e = PetscMax(e, PetscMax(PetscAbsReal(N2[i] - N[i]) / Nmax, PetscAbsReal(g2[i] - g[i]) / gmax));
      CHECK(n2 == n && e < (k ? 1e-15 : 1e-9), "results written to %s and read back with -preload_load: equal to %.1e", k ? "HDF5" : "CSV", (double)e);
      PetscCall(JRPreloadDestroy(&rd));
    }
    { /* files that do not match the model */
      FILE *in, *out;
      char  line[512], bad[PETSC_MAX_PATH_LEN + 16];
      for (int k = 0; k < 3; k++) {
        PetscCall(PetscSNPrintf(bad, sizeof(bad), "%s/bad%d.csv", dir, k));
        if (!JRTestRank()) {
          int r = 0;
          in  = fopen(strcat(strcpy(line, base), ".csv"), "r");
          out = fopen(bad, "w");
          PetscCheck(in && out, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "test files");
          while (fgets(line, sizeof(line), in)) {
            r++;
            if (k == 0 && r == 5) continue; /* a row missing */
            if (k == 1 && r == 5) {          /* a row 1 mm off */
              int    id;
              double x, y, z, rest[6];
              sscanf(line, "%d,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &id, &x, &y, &z, &rest[0], &rest[1], &rest[2], &rest[3], &rest[4], &rest[5]);
              fprintf(out, "%d,%.10g,%.10g,%.10g,%g,%g,%g,%g,%g,%g\n", id, x + 1e-3, y, z, rest[0], rest[1], rest[2], rest[3], rest[4], rest[5]);
              continue;
            }
            if (k == 2 && r == 5) { /* a negative normal load */
              int    id;
              double x, y, z, rest[6];
              sscanf(line, "%d,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &id, &x, &y, &z, &rest[0], &rest[1], &rest[2], &rest[3], &rest[4], &rest[5]);
              fprintf(out, "%d,%.10g,%.10g,%.10g,%g,%g,%g,%g,%g,%g\n", id, x, y, z, rest[0], -1.0, rest[2], rest[3], rest[4], rest[5]);
              continue;
            }
            fputs(line, out);
          }
          fclose(in);
          fclose(out);
        }
        PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
        PetscCall(PetscSNPrintf(opt, sizeof(opt), "-preload_load %s", bad));
        CHECK(PreloadError(m, opt) != 0, "-preload_load with %s: error", k == 0 ? "a row missing" : k == 1 ? "a row 1 mm away from its pair" : "a negative N_static");
        }
    }
  }
  PetscCall(JRPreloadDestroy(&pre));
  /* the augmented Lagrangian does not depend on kp; the penalty approaches it as kp grows */
  {
    char      opt[256];
    PetscReal e[3], eal;
    for (int k = 0; k < 4; k++) {
      const PetscReal kp = kp0 * (k == 3 ? 10.0 : PetscPowReal(10.0, k));
      PetscReal       d  = 0.0;
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-preload_force 8000 -preload_method %s -preload_penalty %.17g", k == 3 ? "augmented" : "penalty", (double)kp));
      PetscCall(Preload(m, opt, NULL, 0, NULL, NULL, &pre));
      PetscCall(JRPreloadGetResults(pre, &n, &N, &g));
      for (PetscInt i = 0; i < n; i++) d += PetscSqr(N[i] - Nal[i]);
      d = PetscSqrtReal(d / n) / Nmax;
      if (k < 3) e[k] = d;
      else eal = d;
      PetscCall(JRPreloadDestroy(&pre));
    }
    CHECK(e[1] < 0.5 * e[0] && e[2] < 0.5 * e[1] && e[2] < 1e-2, "penalty -> augmented Lagrangian as kp grows: rms difference %.2e, %.2e, %.2e (kp x 1, 10, 100; of the largest load)", (double)e[0], (double)e[1], (double)e[2]);
    CHECK(eal < 1e-5, "augmented Lagrangian with 10 x kp: same loads to %.1e", (double)eal);
  }
  { /* Newton on all DOFs (a factorisation per closed set) against the condensed interface solve (the default) */
    PetscReal d = 0.0;
    PetscCall(Preload(m, "-preload_force 8000 -preload_solver full", NULL, 0, NULL, NULL, &pre));
    PetscCall(JRPreloadGetResults(pre, &n, &N, &g));
    for (PetscInt i = 0; i < n; i++) d = PetscMax(d, PetscAbsReal(N[i] - Nal[i]) / Nmax);
    CHECK(d < 1e-8, "Newton on all DOFs = Newton on the condensed interface: loads agree to %.1e", (double)d);
    PetscCall(JRPreloadDestroy(&pre));
  }
  for (int full = 0; full < 2; full++) { /* Newton from every pair open */
    PetscReal d = 0.0;
    PetscCall(Preload(m, full ? "-preload_force 8000 -preload_open_start -preload_solver full" : "-preload_force 8000 -preload_open_start", NULL, 0, NULL, NULL, &pre));
    PetscCall(JRPreloadGetResults(pre, &n, &N, &g));
    for (PetscInt i = 0; i < n; i++) d = PetscMax(d, PetscAbsReal(N[i] - Nal[i]) / Nmax);
    CHECK(d < 1e-5, "Newton from the open state (pairs 10 um apart, %s): same loads to %.1e", full ? "all DOFs" : "condensed", (double)d);
    PetscCall(JRPreloadDestroy(&pre));
  }
  { /* clamp support (fix-free) gives the same interface loads: the bolt loads are self-equilibrated */
    PetscReal d = 0.0;
    PetscCall(Preload(m, "-preload_force 8000 -preload_support clamp", NULL, 0, NULL, NULL, &pre));
    PetscCall(JRPreloadGetResults(pre, &n, &N, &g));
    for (PetscInt i = 0; i < n; i++) d = PetscMax(d, PetscAbsReal(N[i] - Nal[i]) / Nmax);
    CHECK(d < 1e-2, "clamped end (fix-free) instead of 3-2-1 supports: loads within %.1e of the largest", (double)d);
    PetscCall(JRPreloadDestroy(&pre));
  }
  /* bad input */
  CHECK(PreloadError(m, "-preload_force -100") != 0, "-preload_force -100: error");
  CHECK(PreloadError(m, "-preload_force 1000,2000") != 0, "-preload_force with 2 values for 1 bolt: error");
  CHECK(PreloadError(m, "-preload_force 1000 -preload_method none") != 0, "-preload_method none: error");
  PetscCall(JRModelDestroy(&m));
  PetscCall(ModelCreate(LAP "-model_interface tied", &m));
  CHECK(PreloadError(m, "-preload_force 1000") != 0, "a tied interface: error (the preload needs the free interface)");
  PetscCall(JRModelDestroy(&m));
  PetscCall(PetscFree2(Nal, w));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char dir[] = "/tmp/jrplXXXXXX";

  PetscCall(SlepcInitialize(&argc, &argv, NULL, NULL));
  if (!JRTestRank()) PetscCheck(mkdtemp(dir), PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "mkdtemp");
  PetscCallMPI(MPI_Bcast(dir, sizeof(dir), MPI_CHAR, 0, PETSC_COMM_WORLD));
  PetscCall(TestFlatPunch(dir));
  PetscCall(TestLap(dir));
  if (!JRTestRank()) {
    char cmd[64];
    PetscCall(PetscSNPrintf(cmd, sizeof(cmd), "rm -rf %s", dir));
    if (system(cmd)) printf("# could not remove %s\n", dir);
  }
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(SlepcFinalize());
  return jr_fail ? 1 : 0;
}
