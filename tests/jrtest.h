/*
   Test helpers: each check prints "ok - ..." or "not ok - ..." (TAP style; tests/run.sh counts them),
   and the program exits non-zero if any check failed.
   BruteForce() is the independent reference: a plain transient time march of one element from the
   unslipped state over several cycles with very many small steps (no periodic start, no contact
   interpolation, no prefix sums), with the Fourier coefficients of the last cycle by quadrature.
*/
#if !defined(JRTEST_H)
#define JRTEST_H
#include <jointrom.h>

#define JRT_NC 16 /* room for H <= 7 */

static int jr_pass = 0, jr_fail = 0;

/* rank 0 prints (every rank checks the same numbers; the suite also runs on 2 ranks) */
static int jr_rank = -1;
static inline int JRTestRank(void)
{
  int init = 0, fin = 0, rank = 0;
  if (jr_rank >= 0) return jr_rank;
  MPI_Initialized(&init);
  MPI_Finalized(&fin);
  if (init && !fin) {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    jr_rank = rank;
  }
  return rank;
}

#define CHECK(cond, ...) \
  do { \
    const int jr_r = JRTestRank(); \
    if (cond) { \
      jr_pass++; \
      if (!jr_r) printf("ok - "); \
    } else { \
      jr_fail++; \
      if (!jr_r) printf("not ok - "); \
    } \
    if (!jr_r) { \
      printf(__VA_ARGS__); \
      printf("\n"); \
      fflush(stdout); \
    } \
  } while (0)

/* |a - b|_max / scale over n entries */
static inline double RelDiff(int n, const double *a, const double *b, double scale)
{
  double m = 0.0;
  for (int i = 0; i < n; i++) m = fmax(m, fabs(a[i] - b[i]));
  return m / scale;
}

static inline double MaxAbs(int n, const double *a)
{
  double m = 0.0;
  for (int i = 0; i < n; i++) m = fmax(m, fabs(a[i]));
  return m;
}

/* x(theta) from nc = 2H+1 harmonic coefficients */
static inline double Synth(int nc, const double *X, double th)
{
  double x = X[0];
  for (int h = 1; 2 * h < nc; h++) x += X[2 * h - 1] * sin(h * th) + X[2 * h] * cos(h * th);
  return x;
}

/* Brute-force march: ncyc cycles of M steps from w = 0; F, N: nc harmonics of f and n over the
   last cycle; seq: run-length states of the last cycle ('E' stick, 'P'/'N' slip, 'S' separated).
   Runs shorter than 4 steps are dropped from seq: right after contact the march, which does not
   locate the contact instant within a step, can clip for one step at a tiny normal load (an O(h)
   artifact of the reference, not a phase of the motion). */
static inline void BruteForce(double kt, double kn, double mu, double n0, int nc, const double *U, const double *V, int M, int ncyc, double *F, double *N, char *seq, int seqlen)
{
  double w = 0.0;
  int    ns = 0, runlen[256];
  char   runst[256];
  for (int k = 0; k < nc; k++) F[k] = N[k] = 0.0;
  for (int cyc = 0; cyc < ncyc; cyc++) {
    for (int i = 0; i < M; i++) {
      const double th = 2.0 * M_PI * i / M, u = Synth(nc, U, th), v = V ? Synth(nc, V, th) : 0.0;
      const double n = n0 + kn * v;
      double       f;
      char         st;
      if (n <= 0.0) {
        f  = 0.0;
        w  = u;
        st = 'S';
      } else {
        const double trial = kt * (u - w), lim = mu * n;
        if (trial > lim) {
          w  = u - lim / kt;
          st = 'P';
        } else if (trial < -lim) {
          w  = u + lim / kt;
          st = 'N';
        } else st = 'E';
        f = kt * (u - w);
      }
      if (cyc == ncyc - 1) {
        const double nn = n > 0.0 ? n : 0.0;
        F[0] += f / M;
        N[0] += nn / M;
        for (int h = 1; 2 * h < nc; h++) {
          F[2 * h - 1] += 2.0 * f * sin(h * th) / M;
          F[2 * h] += 2.0 * f * cos(h * th) / M;
          N[2 * h - 1] += 2.0 * nn * sin(h * th) / M;
          N[2 * h] += 2.0 * nn * cos(h * th) / M;
        }
        if (ns && runst[ns - 1] == st) runlen[ns - 1]++;
        else if (ns < 256) {
          runst[ns]    = st;
          runlen[ns++] = 1;
        }
      }
    }
  }
  if (seq) {
    int m = 0;
    for (int i = 0; i < ns; i++)
      if (runlen[i] >= 4 && (m == 0 || seq[m - 1] != runst[i]) && m < seqlen - 1) seq[m++] = runst[i];
    if (m > 1 && seq[m - 1] == seq[0]) m--; /* cyclic: the last run continues the first */
    seq[m] = 0;
  }
}

/* Thesis name of a cyclic state sequence (section 3.3, Table 3.2), independent of the library */
static inline const char *SequenceName(const char *cyc)
{
  static const char *sepcases[][2] = {
    {"PENEPS", "P1"},
    {"PENS",   "P2"},
    {"PS",     "P3"},
    {"NEPENS", "N1"},
    {"NEPS",   "N2"},
    {"NS",     "N3"},
    {"EPENS",  "E1"},
    {"EPS",    "E2"},
    {"ENEPS",  "E3"},
    {"ENS",    "E4"}
  };
  char   rot[64];
  size_t n = strlen(cyc), s;
  if (n == 1 && cyc[0] == 'S') return "full_separation";
  if (n == 1 && cyc[0] == 'E') return "full_stick";
  if (!strchr(cyc, 'S')) {
    for (s = 0; s < n; s++) { /* rotate to start after positive slip */
      for (size_t i = 0; i < n; i++) rot[i] = cyc[(s + i) % n];
      rot[n] = 0;
      if (!strcmp(rot, "ENEP")) return "slip_no_separation";
    }
    return "other";
  }
  for (s = 0; s < n; s++)
    if (cyc[s] == 'S') break;
  for (size_t i = 0; i < n; i++) rot[i] = cyc[(s + 1 + i) % n]; /* start after the separation */
  rot[n] = 0;
  for (size_t i = 0; i < sizeof(sepcases) / sizeof(sepcases[0]); i++)
    if (!strcmp(rot, sepcases[i][0])) return sepcases[i][1];
  return "other";
}

static inline int TestSummary(const char *name)
{
  if (!JRTestRank()) printf("# %s: %d passed, %d failed\n", name, jr_pass, jr_fail);
  return jr_fail ? 1 : 0;
}
#endif
