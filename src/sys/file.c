/* Output files written atomically (temporary name beside the target, renamed when complete), and
   PNG plots made by gnuplot scripts in share/. Rank 0 writes; the others get fp = NULL.

   Every temporary name is registered from before its file is created until it is renamed or removed
   (JRFileTempName, JRFileTempDone): a run stopped by SIGTERM, SIGINT or SIGHUP removes the temporary
   files it was writing, then dies of the signal as it would have. The table is a fixed static array
   (a name is written before its slot is marked used) and the handler calls only unlink() and raise(),
   which are async-signal-safe. A signal ignored when the first name is registered (nohup; SIGINT in a
   background job) stays ignored. */
#include <jointrom.h>
#include <errno.h>
#include <signal.h>
#include <unistd.h>

#define JR_TEMP_MAX 8
static char                  jr_temp[JR_TEMP_MAX][PETSC_MAX_PATH_LEN + 32];
static volatile sig_atomic_t jr_temp_used[JR_TEMP_MAX];
static PetscBool             jr_temp_handlers = PETSC_FALSE;
static const int             jr_temp_signals[] = {SIGTERM, SIGINT, SIGHUP};

/* SA_RESETHAND has restored the default action: the raised signal is delivered when this returns */
static void TempSignal(int sig)
{
  for (int i = 0; i < JR_TEMP_MAX; i++)
    if (jr_temp_used[i]) unlink(jr_temp[i]);
  raise(sig);
}

/* the signals that could stop the run, blocked while the table changes */
static void TempBlock(PetscBool block, sigset_t *old)
{
  sigset_t set;

  if (!block) {
    sigprocmask(SIG_SETMASK, old, NULL);
    return;
  }
  sigemptyset(&set);
  for (size_t k = 0; k < sizeof(jr_temp_signals) / sizeof(jr_temp_signals[0]); k++) sigaddset(&set, jr_temp_signals[k]);
  sigprocmask(SIG_BLOCK, &set, old);
}

static PetscErrorCode TempInstall(void)
{
  PetscFunctionBeginUser;
  if (jr_temp_handlers) PetscFunctionReturn(0);
  jr_temp_handlers = PETSC_TRUE;
  for (size_t k = 0; k < sizeof(jr_temp_signals) / sizeof(jr_temp_signals[0]); k++) {
    struct sigaction sa, old;
    PetscCheck(!sigaction(jr_temp_signals[k], NULL, &old), PETSC_COMM_SELF, PETSC_ERR_SYS, "Cannot read the action of signal %d: %s", jr_temp_signals[k], strerror(errno));
    if (old.sa_handler == SIG_IGN) continue;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = TempSignal;
    sa.sa_flags   = SA_RESETHAND;
    sigemptyset(&sa.sa_mask);
    for (size_t j = 0; j < sizeof(jr_temp_signals) / sizeof(jr_temp_signals[0]); j++) sigaddset(&sa.sa_mask, jr_temp_signals[j]);
    PetscCheck(!sigaction(jr_temp_signals[k], &sa, NULL), PETSC_COMM_SELF, PETSC_ERR_SYS, "Cannot set the action of signal %d: %s", jr_temp_signals[k], strerror(errno));
  }
  PetscFunctionReturn(0);
}

/*
  JRFileTempName - the temporary name beside path, "path.tmp<pid of rank 0>", the same on every rank of comm
  (collective), registered on every rank for removal if the run is stopped before JRFileTempDone(tmp). Call it
  before the file is created.
*/
PetscErrorCode JRFileTempName(MPI_Comm comm, const char path[], char tmp[], size_t len)
{
  PetscMPIInt rank;
  sigset_t    old;
  int         slot = -1;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) PetscCall(PetscSNPrintf(tmp, len, "%s.tmp%d", path, (int)getpid()));
  PetscCallMPI(MPI_Bcast(tmp, (PetscMPIInt)len, MPI_CHAR, 0, comm));
  PetscCheck(strlen(tmp) < sizeof(jr_temp[0]), PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "The file name %s is too long", path);
  PetscCall(TempInstall());
  TempBlock(PETSC_TRUE, &old);
  for (int i = 0; i < JR_TEMP_MAX && slot < 0; i++)
    if (!jr_temp_used[i]) slot = i;
  if (slot >= 0) {
    strcpy(jr_temp[slot], tmp);
    jr_temp_used[slot] = 1;
  }
  TempBlock(PETSC_FALSE, &old);
  PetscCheck(slot >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "More than %d temporary files at once (writing %s)", JR_TEMP_MAX, path);
  PetscFunctionReturn(0);
}

/* The temporary file tmp of JRFileTempName is renamed or removed: no longer removed when the run stops (not collective) */
PetscErrorCode JRFileTempDone(const char tmp[])
{
  sigset_t old;

  PetscFunctionBeginUser;
  TempBlock(PETSC_TRUE, &old);
  for (int i = 0; i < JR_TEMP_MAX; i++)
    if (jr_temp_used[i] && !strcmp(jr_temp[i], tmp)) {
      jr_temp_used[i] = 0;
      break;
    }
  TempBlock(PETSC_FALSE, &old);
  PetscFunctionReturn(0);
}

/* Rename the temporary file tmp of JRFileTempName to path on rank 0 (collective); on failure tmp is removed and
   the error names path */
PetscErrorCode JRFileRename(MPI_Comm comm, const char tmp[], const char path[])
{
  PetscMPIInt rank;
  int         err = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank && rename(tmp, path)) {
    err = errno;
    remove(tmp);
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCall(JRFileTempDone(tmp));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "Cannot write the file %s: %s", path, strerror(err));
  PetscFunctionReturn(0);
}

/* Open a temporary file beside path on rank 0 (fp NULL elsewhere); tmp receives its name (JRFileTempName) */
PetscErrorCode JRFileOpenTemp(MPI_Comm comm, const char path[], FILE **fp, char tmp[], size_t len)
{
  PetscMPIInt rank;
  int         err = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  *fp = NULL;
  PetscCall(JRFileTempName(comm, path, tmp, len));
  if (rank == 0) {
    *fp = fopen(tmp, "w");
    if (!*fp) err = errno;
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  if (err) PetscCall(JRFileTempDone(tmp));
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
  PetscCall(JRFileTempDone(tmp));
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
   PNG was written. A missing gnuplot is a warning, not an error: the data files are written anyway.
   gnuplot draws to a pipe (out = /dev/stdout) and this process writes the temporary file, so that
   only this process creates it and a stopped run removes it (a gnuplot left behind dies of SIGPIPE). */
PetscErrorCode JRPlot(MPI_Comm comm, const char script[], const char png[], const char vars[], PetscBool *made)
{
  PetscMPIInt rank;
  int         ok = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    char        tmp[PETSC_MAX_PATH_LEN + 32], cmd[4 * PETSC_MAX_PATH_LEN], dir[PETSC_MAX_PATH_LEN];
    const char *share = ShareDir(script, dir, sizeof(dir));
    if (system("command -v gnuplot > /dev/null 2>&1") != 0) {
      PetscCall(PetscFPrintf(PETSC_COMM_SELF, stderr, "jointrom: gnuplot not found, %s not drawn (install gnuplot-nox, or run share/install-deps.sh)\n", png));
    } else {
      FILE *fp, *gp = NULL;
      int   wrote = 1;
      PetscCall(JRFileTempName(PETSC_COMM_SELF, png, tmp, sizeof(tmp)));
      PetscCall(PetscSNPrintf(cmd, sizeof(cmd), "gnuplot -e \"out='/dev/stdout'; %s\" '%s/%s'", vars ? vars : "", share, script));
      fp = fopen(tmp, "wb");
      if (fp) gp = popen(cmd, "r");
      if (gp) {
        char   buf[16384];
        size_t nr;
        while (wrote && (nr = fread(buf, 1, sizeof(buf), gp)) > 0) wrote = fwrite(buf, 1, nr, fp) == nr;
        ok = pclose(gp) == 0 && wrote;
      }
      if (fp && fclose(fp)) ok = 0;
      if (ok && rename(tmp, png)) ok = 0;
      if (!ok) {
        remove(tmp);
        PetscCall(PetscFPrintf(PETSC_COMM_SELF, stderr, "jointrom: gnuplot failed on %s/%s, %s not drawn\n", share, script, png));
      }
      PetscCall(JRFileTempDone(tmp));
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

/* JRViewerHDF5WriteRank0 - one dataset written from rank 0's array: len values (reals r, or integers iv as reals),
   block size bs; the other ranks' arrays are not read (collective) */
PetscErrorCode JRViewerHDF5WriteRank0(MPI_Comm comm, PetscViewer v, const char name[], PetscInt len, PetscInt bs, const PetscReal r[], const PetscInt iv[])
{
  Vec          x;
  PetscScalar *xa;
  PetscMPIInt  rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank) len = 0;
  PetscCall(VecCreateMPI(comm, len, PETSC_DETERMINE, &x));
  if (bs > 1) PetscCall(VecSetBlockSize(x, bs));
  PetscCall(PetscObjectSetName((PetscObject)x, name));
  PetscCall(VecGetArray(x, &xa));
  for (PetscInt i = 0; i < len; i++) xa[i] = r ? r[i] : (PetscReal)iv[i];
  PetscCall(VecRestoreArray(x, &xa));
  PetscCall(VecView(x, v));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}
