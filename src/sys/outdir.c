/* Output locations checked before the work: the directory of an output base name, created if missing */
#include <jointrom.h>
#include <errno.h>
#include <sys/stat.h>
#include <unistd.h>

/* dir exists, or is created if its parent exists (one level: a mistyped path does not grow a tree); 0 or an errno */
static int MakeDir(const char dir[])
{
  struct stat st;
  if (stat(dir, &st)) {
    if (mkdir(dir, 0777) && errno != EEXIST) return errno;
    if (stat(dir, &st)) return errno;
  }
  return S_ISDIR(st.st_mode) ? 0 : ENOTDIR;
}

/*
  JRFileCheckOutput - the directory of the output base name base (given by option opt, for the message) exists or
  is created (when its parent exists), and a file can be written in it; an empty base (no output) passes.
  Collective; rank 0 checks.
*/
PetscErrorCode JRFileCheckOutput(MPI_Comm comm, const char opt[], const char base[])
{
  PetscMPIInt rank;
  int         err = 0;
  char        dir[PETSC_MAX_PATH_LEN], probe[PETSC_MAX_PATH_LEN + 32];

  PetscFunctionBeginUser;
  if (!base || !base[0]) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscStrncpy(dir, base, sizeof(dir)));
  {
    char *slash = strrchr(dir, '/');
    if (slash) {
      if (slash == dir) slash[1] = 0;
      else *slash = 0;
    } else PetscCall(PetscStrncpy(dir, ".", sizeof(dir)));
  }
  if (!rank) {
    err = MakeDir(dir);
    if (!err) {
      FILE *fp;
      PetscCall(PetscSNPrintf(probe, sizeof(probe), "%s/.jointrom_probe%d", dir, (int)getpid()));
      fp = fopen(probe, "w");
      if (!fp) err = errno;
      else {
        fclose(fp);
        remove(probe);
      }
    }
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "%s %s: cannot write in the directory %s: %s", opt, base, dir, strerror(err));
  PetscFunctionReturn(0);
}

/* The same file: equal names once a leading "./" is dropped */
static PetscBool SameName(const char a[], const char b[])
{
  while (a[0] == '.' && a[1] == '/' && a[2] != '/') a += 2;
  while (b[0] == '.' && b[1] == '/' && b[2] != '/') b += 2;
  return (PetscBool)!strcmp(a, b);
}

/*
  JRFileCheckNotOutput - the file given by option opt is none of the result files the run writes under the output base
  (option baseopt): base followed by each of the NULL-terminated suffixes sfx (with its extension); a run would
  otherwise overwrite it with its results. An empty file or base passes. Collective (every rank has the options).
*/
PetscErrorCode JRFileCheckNotOutput(MPI_Comm comm, const char opt[], const char file[], const char baseopt[], const char base[], const char *const sfx[])
{
  char name[PETSC_MAX_PATH_LEN + 32];

  PetscFunctionBeginUser;
  if (!file || !file[0] || !base || !base[0]) PetscFunctionReturn(0);
  for (PetscInt i = 0; sfx[i]; i++) {
    PetscCall(PetscSNPrintf(name, sizeof(name), "%s%s", base, sfx[i]));
    PetscCheck(!SameName(file, name), comm, PETSC_ERR_ARG_INCOMP, "%s %s: this run writes its results to that file (%s %s); name another file", opt, file, baseopt, base);
  }
  PetscFunctionReturn(0);
}
