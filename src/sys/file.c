/* Output files written atomically (temporary name beside the target, renamed when complete), and
   PNG plots made by gnuplot scripts in share/. Rank 0 writes; the others get fp = NULL. */
#include <jointrom.h>
#include <errno.h>
#include <unistd.h>

/* Open a temporary file beside path on rank 0 (fp NULL elsewhere); tmp receives its name */
PetscErrorCode JRFileOpenTemp(MPI_Comm comm, const char path[], FILE **fp, char tmp[], size_t len)
{
  PetscMPIInt rank;
  int         err = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  *fp = NULL;
  PetscCall(PetscSNPrintf(tmp, len, "%s.tmp%d", path, (int)getpid()));
  if (rank == 0) {
    *fp = fopen(tmp, "w");
    if (!*fp) err = errno;
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_OPEN, "Cannot write the file %s: %s", path, strerror(err));
  PetscFunctionReturn(0);
}

/* Close the temporary file and rename it to path */
PetscErrorCode JRFileCommit(MPI_Comm comm, FILE **fp, const char tmp[], const char path[])
{
  PetscMPIInt rank;
  int         err = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0 && *fp) {
    if (fclose(*fp)) err = errno;
    else if (rename(tmp, path)) err = errno;
    if (err) remove(tmp);
  }
  *fp = NULL;
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "Cannot write the file %s: %s", path, strerror(err));
  PetscFunctionReturn(0);
}

/* The directory holding the plot script: $JOINTROM_SHARE if set; else ../share/jointrom beside the
   executable (an installed jointrom, found through /proc/self/exe) if it holds the script; else the
   source tree's share/ (JR_SHARE_DIR, fixed at compile time). */
static const char *ShareDir(const char script[], char dir[], size_t len)
{
  const char *env = getenv("JOINTROM_SHARE");
  char        f[PETSC_MAX_PATH_LEN], *s;
  ssize_t     n;

  if (env && env[0]) return env;
  n = readlink("/proc/self/exe", dir, len - 1);
  if (n > 0) {
    dir[n] = 0;
    for (int k = 0; k < 2 && (s = strrchr(dir, '/')); k++) *s = 0; /* <prefix>/bin/jointrom -> <prefix> */
    if (s && (size_t)snprintf(f, sizeof(f), "%s/share/jointrom/%s", dir, script) < sizeof(f) && !access(f, R_OK)) {
      strcat(dir, "/share/jointrom"); /* fits: f (longer) did */
      return dir;
    }
  }
  return JR_SHARE_DIR;
}

/* Run gnuplot on share/<script> to write the PNG png; the script reads the gnuplot variable 'out'
   (the output file) and any assignments in vars ("data='x.csv'; title='...'"). made: whether the
   PNG was written. A missing gnuplot is a warning, not an error: the data files are written anyway. */
PetscErrorCode JRPlot(MPI_Comm comm, const char script[], const char png[], const char vars[], PetscBool *made)
{
  PetscMPIInt rank;
  int         ok = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    char        tmp[PETSC_MAX_PATH_LEN], cmd[4 * PETSC_MAX_PATH_LEN], dir[PETSC_MAX_PATH_LEN];
    const char *share = ShareDir(script, dir, sizeof(dir));
    if (system("command -v gnuplot > /dev/null 2>&1") != 0) {
      PetscCall(PetscFPrintf(PETSC_COMM_SELF, stderr, "jointrom: gnuplot not found, %s not drawn (install gnuplot-nox, or run share/install-deps.sh)\n", png));
    } else {
      PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.tmp%d", png, (int)getpid()));
      PetscCall(PetscSNPrintf(cmd, sizeof(cmd), "gnuplot -e \"out='%s'; %s\" '%s/%s'", tmp, vars ? vars : "", share, script));
      if (system(cmd) == 0 && rename(tmp, png) == 0) ok = 1;
      else {
        remove(tmp);
        PetscCall(PetscFPrintf(PETSC_COMM_SELF, stderr, "jointrom: gnuplot failed on %s/%s, %s not drawn\n", share, script, png));
      }
    }
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm));
  if (made) *made = ok ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Allocate n bytes aligned to a 64-byte cache line (free with JRFreeAligned); for large SoA batches */
PetscErrorCode JRMallocAligned(size_t n, void *ptr)
{
  void *p = NULL;

  PetscFunctionBeginUser;
  PetscCheck(!posix_memalign(&p, 64, n ? n : 64), PETSC_COMM_SELF, PETSC_ERR_MEM, "Cannot allocate %zu bytes", n);
  *(void **)ptr = p;
  PetscFunctionReturn(0);
}

PetscErrorCode JRFreeAligned(void *ptr)
{
  PetscFunctionBeginUser;
  free(*(void **)ptr);
  *(void **)ptr = NULL;
  PetscFunctionReturn(0);
}
