/*
   Matrices and vectors from files, chosen by extension:
     .mtx             Matrix Market, coordinate real/integer, general or symmetric (read on rank 0,
                      broadcast, each rank inserts its rows with exact preallocation)
     .bin .dat .petsc PETSc binary (MatLoad / VecLoad)
     .h5  .hdf5       HDF5 in the MATLAB v7.3 sparse layout that PETSc's MatLoad reads: a group with
                      datasets jc, ir, data and attribute MATLAB_sparse = size, taken as compressed rows
                      (jc row pointers, ir column indices). MATLAB itself stores compressed columns, so a
                      matrix saved by MATLAB arrives transposed: the same matrix for the symmetric K, M, C.
                      "file.h5:/name" picks the group; the default name is given by the caller (K, M, C).
   Vectors (forces): .bin, .h5 (dataset "f" or file.h5:/name), or text (.csv, .txt): one value per
   line, '#' comments, an optional header line.
*/
#include <jointrom.h>
#include <petscviewerhdf5.h>
#include <hdf5.h>
#include <errno.h>
#include <ctype.h>

static PetscErrorCode Extension(const char file[], char ext[], size_t len)
{
  const char *dot = strrchr(file, '.'), *slash = strrchr(file, '/');

  PetscFunctionBeginUser;
  ext[0] = 0;
  if (dot && (!slash || dot > slash)) {
    PetscCall(PetscStrncpy(ext, dot + 1, len));
    for (char *c = ext; *c; c++) *c = (char)tolower((unsigned char)*c);
    {
      char *colon = strchr(ext, ':'); /* file.h5:/group */
      if (colon) *colon = 0;
    }
  }
  PetscFunctionReturn(0);
}

/* Split "file.h5:/group" into file and group (group default def) */
static PetscErrorCode SplitGroup(const char spec[], const char def[], char file[], size_t flen, char group[], size_t glen)
{
  const char *colon = strstr(spec, ".h5:");
  size_t      cut;

  PetscFunctionBeginUser;
  if (!colon) colon = strstr(spec, ".hdf5:");
  if (colon) {
    cut = (size_t)(strchr(colon, ':') - spec);
    PetscCall(PetscStrncpy(file, spec, PetscMin(flen, cut + 1)));
    PetscCall(PetscStrncpy(group, strchr(colon, ':') + 1, glen));
    if (group[0] == '/') memmove(group, group + 1, strlen(group));
  } else {
    PetscCall(PetscStrncpy(file, spec, flen));
    PetscCall(PetscStrncpy(group, def, glen));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode FileReadable(MPI_Comm comm, const char file[], const char what[])
{
  PetscBool ok;

  PetscFunctionBeginUser;
  PetscCall(PetscTestFile(file, 'r', &ok));
  PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "Cannot open %s file %s", what, file);
  PetscFunctionReturn(0);
}

/*
  JRFileCheckHDF5 - before any work, that file (named by option) is an HDF5 file holding group (an absolute path, e.g.
  "/rom"): else an error naming the option and the file, hint saying how to make a good one. HDF5's own error
  stack is not printed (JRErrorHandlerPush).
*/
PetscErrorCode JRFileCheckHDF5(MPI_Comm comm, const char option[], const char file[], const char group[], const char hint[])
{
  PetscMPIInt rank;
  int         err = 0; /* 1 unreadable, 2 not HDF5, 3 does not open, 4 no group */

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    PetscBool ok;
    PetscCall(PetscTestFile(file, 'r', &ok));
    if (!ok) err = 1;
    else if (H5Fis_hdf5(file) <= 0) err = 2;
    else {
      hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
      if (f < 0) err = 3;
      else {
        if (H5Lexists(f, group, H5P_DEFAULT) <= 0) err = 4;
        H5Fclose(f);
      }
    }
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(err != 1, comm, PETSC_ERR_FILE_OPEN, "%s %s: cannot read the file", option, file);
  PetscCheck(err != 2 && err != 3, comm, PETSC_ERR_FILE_UNEXPECTED, "%s %s: not an HDF5 file, or a truncated or corrupt one (%s)", option, file, hint);
  PetscCheck(err != 4, comm, PETSC_ERR_FILE_UNEXPECTED, "%s %s: an HDF5 file without the group %s (%s)", option, file, group, hint);
  PetscFunctionReturn(0);
}

/* ---- Matrix Market ---- */

/* a Matrix Market file's contents: size, symmetry and the entries (0-based indices) */
typedef struct {
  PetscInt   m, n, nz, sym;
  PetscInt  *ii, *jj, *line; /* line: each entry's line in the file (rank 0) */
  PetscReal *vv;
} MtxData;

/* what went wrong reading the file on rank 0 (LoadMtx turns it into an error on every rank) */
enum {
  MTX_OK,
  MTX_OPEN,   /* the file does not open */
  MTX_EMPTY,  /* no first line */
  MTX_BANNER, /* the first line is not a coordinate-matrix banner */
  MTX_KIND,   /* complex or pattern, or neither general nor symmetric */
  MTX_SIZE,   /* a bad size line */
  MTX_ENTRY,  /* a bad entry line (what is wrong in msg) */
  MTX_SHORT,  /* fewer entries than the size line announces */
  MTX_LONG    /* more entries than the size line announces */
};

/* a line holding nothing but blanks */
static int Blank(const char *s)
{
  while (*s && isspace((unsigned char)*s)) s++;
  return !*s;
}

/* the whole of s (blanks around it allowed) as an integer; 0 if it is not one */
static int ParseLong(const char *s, long *v)
{
  char *end;
  errno = 0;
  *v    = strtol(s, &end, 10);
  return end != s && !*end && !errno;
}

/* the whole of s as a finite real; 0 if it is not one */
static int ParseReal(const char *s, double *v)
{
  char *end;
  *v = strtod(s, &end);
  return end != s && !*end && isfinite(*v);
}

/* The line's blank-separated fields (at most max; *n all of them) */
static void Fields(char *line, char *f[], int max, int *n)
{
  char *save = NULL;
  *n         = 0;
  for (char *t = strtok_r(line, " \t\r\n", &save); t; t = strtok_r(NULL, " \t\r\n", &save)) {
    if (*n < max) f[*n] = t;
    (*n)++;
  }
}

/* The banner line (%%MatrixMarket matrix coordinate real|integer general|symmetric, after a UTF-8 byte-order mark if
   there is one) and the size line (rows columns entries): d->sym, d->m, d->n, d->nz */
static PetscInt MtxReadHeader(FILE *fp, long *lineno, MtxData *d, char msg[], size_t len)
{
  char  line[1024], *b = line;
  char *f[4];
  int   nf;
  long  v[3];

  if (!fgets(line, sizeof(line), fp)) return MTX_EMPTY;
  *lineno = 1;
  if (!strncmp(b, "\xEF\xBB\xBF", 3)) b += 3;
  for (char *c = b; *c; c++) *c = (char)tolower((unsigned char)*c);
  if (strncmp(b, "%%matrixmarket", 14) || !strstr(b, "matrix") || !strstr(b, "coordinate")) return MTX_BANNER;
  if (strstr(b, "complex") || strstr(b, "pattern")) return MTX_KIND;
  if (strstr(b, "symmetric")) d->sym = 1;
  else if (!strstr(b, "general")) return MTX_KIND;
  while (fgets(line, sizeof(line), fp)) {
    (*lineno)++;
    if (line[0] == '%' || Blank(line)) continue;
    snprintf(msg, len, "%.200s", line);
    msg[strcspn(msg, "\r\n")] = 0;
    Fields(line, f, 4, &nf);
    if (nf != 3) return MTX_SIZE;
    for (int k = 0; k < 3; k++)
      if (!ParseLong(f[k], &v[k]) || v[k] < 0) return MTX_SIZE;
    d->m  = (PetscInt)v[0];
    d->n  = (PetscInt)v[1];
    d->nz = (PetscInt)v[2];
    return MTX_OK;
  }
  return MTX_SIZE;
}

/* The d->nz entry lines "i j value" (1-based indices within the size, finite values) into d->ii, jj, vv and their
   lines into d->line; then nothing but comments. A bad line's number in errline and what is wrong in msg */
static PetscInt MtxReadEntries(FILE *fp, long *lineno, MtxData *d, PetscInt *errline, char msg[], size_t len)
{
  char     line[1024], text[256];
  PetscInt k = 0;

  while (fgets(line, sizeof(line), fp)) {
    char       *f[4];
    int         nf;
    long        i, j;
    double      v;
    const char *what[3] = {"row", "column", "value"};
    (*lineno)++;
    if (line[0] == '%' || Blank(line)) continue;
    *errline = *lineno;
    snprintf(text, sizeof(text), "%.200s", line);
    text[strcspn(text, "\r\n")] = 0;
    if (k == d->nz) {
      snprintf(msg, len, "more entries than the %" PetscInt_FMT " the size line announces", d->nz);
      return MTX_LONG;
    }
    Fields(line, f, 4, &nf);
    if (nf != 3) {
      snprintf(msg, len, "bad entry '%s': %d fields, an entry is 'row column value'", text, nf);
      return MTX_ENTRY;
    }
    for (int c = 0; c < 3; c++) {
      const int ok = c < 2 ? ParseLong(f[c], c ? &j : &i) : ParseReal(f[c], &v);
      if (!ok) {
        snprintf(msg, len, "bad entry '%s': field %d (the %s) '%.64s' is not %s", text, c + 1, what[c], f[c], c < 2 ? "an integer" : "a finite number");
        return MTX_ENTRY;
      }
    }
    if (i < 1 || i > d->m || j < 1 || j > d->n) {
      snprintf(msg, len, "bad entry '%s': indices are 1-based within the size %" PetscInt_FMT " x %" PetscInt_FMT, text, d->m, d->n);
      return MTX_ENTRY;
    }
    d->ii[k]   = i - 1;
    d->jj[k]   = j - 1;
    d->vv[k]   = v;
    d->line[k] = *lineno;
    k++;
  }
  return k < d->nz ? MTX_SHORT : MTX_OK;
}

/* an entry's position (a symmetric file's entries by the triangle they stand for) and its line, to find duplicates */
typedef struct {
  PetscInt64 key;
  PetscInt   line;
} MtxKey;

static int MtxKeyCompare(const void *a, const void *b)
{
  const MtxKey *x = (const MtxKey *)a, *y = (const MtxKey *)b;
  return x->key < y->key ? -1 : x->key > y->key ? 1 : x->line < y->line ? -1 : x->line > y->line;
}

/* Every position given once (a symmetric file: (i, j) and (j, i) are the same entry) */
static PetscErrorCode MtxCheckDuplicates(const MtxData *d, PetscInt *err, PetscInt *errline, char msg[], size_t len)
{
  MtxKey *key;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(d->nz ? d->nz : 1, &key));
  for (PetscInt k = 0; k < d->nz; k++) {
    const PetscInt i = d->sym ? PetscMax(d->ii[k], d->jj[k]) : d->ii[k], j = d->sym ? PetscMin(d->ii[k], d->jj[k]) : d->jj[k];
    key[k].key  = (PetscInt64)i * d->n + j;
    key[k].line = d->line[k];
  }
  qsort(key, (size_t)d->nz, sizeof(*key), MtxKeyCompare);
  for (PetscInt k = 1; k < d->nz; k++) {
    if (key[k].key != key[k - 1].key) continue;
    *err     = MTX_ENTRY;
    *errline = key[k].line;
    snprintf(msg, len, "entry (%" PetscInt64_FMT ", %" PetscInt64_FMT ") is given again (first at line %" PetscInt_FMT ")%s", key[k].key / d->n + 1, key[k].key % d->n + 1, key[k - 1].line, d->sym ? "; a symmetric file holds one triangle" : "");
    break;
  }
  PetscCall(PetscFree(key));
  PetscFunctionReturn(0);
}

static PetscErrorCode MtxAlloc(MtxData *d)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc4(d->nz ? d->nz : 1, &d->ii, d->nz ? d->nz : 1, &d->jj, d->nz ? d->nz : 1, &d->vv, d->nz ? d->nz : 1, &d->line));
  PetscFunctionReturn(0);
}

/* rank 0: the file into d; *err an MTX_ code */
static PetscErrorCode MtxRead(const char file[], MtxData *d, PetscInt *err, PetscInt *errline, char msg[], size_t len)
{
  FILE *fp     = fopen(file, "r");
  long  lineno = 0;

  PetscFunctionBeginUser;
  if (!fp) {
    *err = MTX_OPEN;
    PetscFunctionReturn(0);
  }
  *err = MtxReadHeader(fp, &lineno, d, msg, len);
  if (!*err) {
    PetscCall(MtxAlloc(d));
    *err = MtxReadEntries(fp, &lineno, d, errline, msg, len);
  }
  if (!*err) PetscCall(MtxCheckDuplicates(d, err, errline, msg, len));
  fclose(fp);
  PetscFunctionReturn(0);
}

/* rank 0's d on every rank */
static PetscErrorCode MtxBcast(MPI_Comm comm, PetscMPIInt rank, MtxData *d)
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&d->m, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&d->n, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&d->nz, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&d->sym, 1, MPIU_INT, 0, comm));
  if (rank) PetscCall(MtxAlloc(d));
  PetscCallMPI(MPI_Bcast(d->ii, (PetscMPIInt)d->nz, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(d->jj, (PetscMPIInt)d->nz, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(d->vv, (PetscMPIInt)d->nz, MPIU_REAL, 0, comm));
  PetscFunctionReturn(0);
}

/* d (on every rank) -> MPIAIJ: each rank inserts its rows (and, symmetric, the mirrored entries) with
   exact preallocation; duplicates are summed */
static PetscErrorCode MtxAssemble(MPI_Comm comm, const MtxData *d, Mat *A)
{
  const PetscInt  nz = d->nz, sym = d->sym, *ii = d->ii, *jj = d->jj;
  const PetscReal *vv = d->vv;
  PetscInt         rstart, rend, cstart, cend, *dnz, *onz;

  PetscFunctionBeginUser;
  PetscCall(MatCreate(comm, A));
  PetscCall(MatSetSizes(*A, PETSC_DECIDE, PETSC_DECIDE, d->m, d->n));
  PetscCall(MatSetType(*A, MATAIJ));
  PetscCall(MatSetUp(*A));
  PetscCall(MatGetOwnershipRange(*A, &rstart, &rend));
  PetscCall(MatGetOwnershipRangeColumn(*A, &cstart, &cend));
  PetscCall(PetscCalloc2(rend - rstart, &dnz, rend - rstart, &onz));
  for (PetscInt k = 0; k < nz; k++) {
    for (int t = 0; t < 1 + (sym && ii[k] != jj[k]); t++) {
      const PetscInt i = t ? jj[k] : ii[k], j = t ? ii[k] : jj[k];
      if (i >= rstart && i < rend) {
        if (j >= cstart && j < cend) dnz[i - rstart]++;
        else onz[i - rstart]++;
      }
    }
  }
  PetscCall(MatXAIJSetPreallocation(*A, 1, dnz, onz, NULL, NULL));
  PetscCall(MatSetOption(*A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE)); /* duplicates are summed */
  for (PetscInt k = 0; k < nz; k++) {
    if (ii[k] >= rstart && ii[k] < rend) PetscCall(MatSetValue(*A, ii[k], jj[k], vv[k], ADD_VALUES));
    if (sym && ii[k] != jj[k] && jj[k] >= rstart && jj[k] < rend) PetscCall(MatSetValue(*A, jj[k], ii[k], vv[k], ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree2(dnz, onz));
  PetscFunctionReturn(0);
}

/* Matrix Market coordinate file -> MPIAIJ (read on rank 0, broadcast) */
static PetscErrorCode LoadMtx(MPI_Comm comm, const char file[], Mat *A)
{
  PetscMPIInt rank;
  MtxData     d   = {0, 0, 0, 0, NULL, NULL, NULL, NULL};
  PetscInt    err = MTX_OK, errline = 0;
  char        msg[512] = "";

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) PetscCall(MtxRead(file, &d, &err, &errline, msg, sizeof(msg)));
  PetscCallMPI(MPI_Bcast(&err, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&errline, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm));
  if (err && d.ii) PetscCall(PetscFree4(d.ii, d.jj, d.vv, d.line));
  PetscCheck(err != MTX_OPEN, comm, PETSC_ERR_FILE_OPEN, "Cannot open the Matrix Market file %s", file);
  PetscCheck(err != MTX_EMPTY && err != MTX_BANNER, comm, PETSC_ERR_FILE_UNEXPECTED, "Matrix Market file %s: the first line must be '%%%%MatrixMarket matrix coordinate real general' (or symmetric)", file);
  PetscCheck(err != MTX_KIND, comm, PETSC_ERR_FILE_UNEXPECTED, "Matrix Market file %s: only real or integer coordinate matrices, general or symmetric, are supported", file);
  PetscCheck(err != MTX_SIZE, comm, PETSC_ERR_FILE_UNEXPECTED, "Matrix Market file %s: bad size line '%s' (expected 'rows columns entries', three non-negative integers)", file, msg);
  PetscCheck(err != MTX_ENTRY && err != MTX_LONG, comm, PETSC_ERR_FILE_UNEXPECTED, "Matrix Market file %s line %" PetscInt_FMT ": %s", file, errline, msg);
  PetscCheck(err != MTX_SHORT, comm, PETSC_ERR_FILE_UNEXPECTED, "Matrix Market file %s: fewer entries than the %" PetscInt_FMT " the size line announces", file, d.nz);
  PetscCall(MtxBcast(comm, rank, &d));
  PetscCall(MtxAssemble(comm, &d, A));
  PetscCall(PetscFree4(d.ii, d.jj, d.vv, d.line));
  PetscFunctionReturn(0);
}

/*
  JRMatLoadFile - load a matrix from file (format by extension, see the top of this file);
  group: the HDF5 group when the name does not say (file.h5:/group). Errors name the file.
*/
PetscErrorCode JRMatLoadFile(MPI_Comm comm, const char spec[], const char group[], Mat *A)
{
  char ext[16], file[PETSC_MAX_PATH_LEN], grp[256];

  PetscFunctionBeginUser;
  PetscCall(Extension(spec, ext, sizeof(ext)));
  PetscCall(SplitGroup(spec, group, file, sizeof(file), grp, sizeof(grp)));
  PetscCall(FileReadable(comm, file, "matrix"));
  if (!strcmp(ext, "mtx")) PetscCall(LoadMtx(comm, file, A));
  else if (!strcmp(ext, "bin") || !strcmp(ext, "dat") || !strcmp(ext, "petsc")) {
    PetscViewer v;
    char        what[PETSC_MAX_PATH_LEN + 32];
    PetscCall(PetscSNPrintf(what, sizeof(what), "the matrix file %s", file));
    PetscCall(JRErrorContextPush(what)); /* PETSc's error on a truncated or corrupt file names it */
    PetscCall(PetscViewerBinaryOpen(comm, file, FILE_MODE_READ, &v));
    PetscCall(MatCreate(comm, A));
    PetscCall(MatSetType(*A, MATAIJ));
    PetscCall(MatLoad(*A, v));
    PetscCall(PetscViewerDestroy(&v));
    PetscCall(JRErrorContextPop());
  } else if (!strcmp(ext, "h5") || !strcmp(ext, "hdf5")) {
    PetscViewer v;
    PetscBool   has;
    char        what[PETSC_MAX_PATH_LEN + 32];
    PetscCall(PetscSNPrintf(what, sizeof(what), "the matrix file %s", file));
    PetscCall(JRErrorContextPush(what));
    PetscCall(PetscViewerHDF5Open(comm, file, FILE_MODE_READ, &v));
    PetscCall(JRErrorContextPop());
    PetscCall(PetscViewerHDF5HasAttribute(v, grp, "MATLAB_sparse", &has));
    PetscCheck(has, comm, PETSC_ERR_FILE_UNEXPECTED, "HDF5 file %s: no sparse matrix in group /%s (expected MATLAB v7.3 sparse layout: attribute MATLAB_sparse, datasets jc, ir, data; name another group as %s:/group)", file, grp, file);
    PetscCall(MatCreate(comm, A));
    PetscCall(MatSetType(*A, MATAIJ));
    PetscCall(PetscObjectSetName((PetscObject)*A, grp));
    PetscCall(JRErrorContextPush(what));
    PetscCall(MatLoad(*A, v));
    PetscCall(JRErrorContextPop());
    PetscCall(PetscViewerDestroy(&v));
  } else SETERRQ(comm, PETSC_ERR_SUP, "Matrix file %s: unknown extension '.%s' (use .mtx Matrix Market, .bin PETSc binary or .h5 HDF5)", file, ext);
  PetscFunctionReturn(0);
}

/* Write A in the layout PETSc's MatLoad reads (compressed rows in jc, ir, data) to group grp of an HDF5
   file (rank 0, via a gather) */
static PetscErrorCode SaveH5(Mat A, const char file[], const char grp[])
{
  MPI_Comm    comm;
  PetscMPIInt rank;
  Mat        *sub;
  IS          rows, cols;
  PetscInt    m, n;
  int         ok = 1;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)A, &comm));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(MatGetSize(A, &m, &n));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, rank ? 0 : m, 0, 1, &rows));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, rank ? 0 : n, 0, 1, &cols));
  PetscCall(MatCreateSubMatrices(A, 1, &rows, &cols, MAT_INITIAL_MATRIX, &sub));
  if (rank == 0) {
    const PetscInt *ia, *ja;
    PetscInt        nr;
    PetscBool       done;
    PetscScalar    *a;
    hid_t           f, g, s, d, at;
    hsize_t         dim;
    long long      *jc, *ir, nnz, N = m;
    PetscCall(MatGetRowIJ(sub[0], 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
    PetscCall(MatSeqAIJGetArray(sub[0], &a));
    nnz = ia[nr];
    PetscCall(PetscMalloc2(nr + 1, &jc, nnz ? nnz : 1, &ir));
    for (PetscInt i = 0; i <= nr; i++) jc[i] = ia[i];
    for (long long k = 0; k < nnz; k++) ir[k] = ja[k];
    f = H5Fcreate(file, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (f < 0) ok = 0;
    else {
    g   = H5Gcreate2(f, grp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    s   = H5Screate(H5S_SCALAR);
    at  = H5Acreate2(g, "MATLAB_sparse", H5T_NATIVE_LLONG, s, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(at, H5T_NATIVE_LLONG, &N);
    H5Aclose(at);
    H5Sclose(s);
    dim = (hsize_t)(nr + 1);
    s   = H5Screate_simple(1, &dim, NULL);
    d   = H5Dcreate2(g, "jc", H5T_NATIVE_LLONG, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(d, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, jc);
    H5Dclose(d);
    H5Sclose(s);
    dim = (hsize_t)nnz;
    s   = H5Screate_simple(1, &dim, NULL);
    d   = H5Dcreate2(g, "ir", H5T_NATIVE_LLONG, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(d, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, ir);
    H5Dclose(d);
    d = H5Dcreate2(g, "data", H5T_NATIVE_DOUBLE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, a);
    H5Dclose(d);
    H5Sclose(s);
    H5Gclose(g);
    H5Fclose(f);
    }
    PetscCall(PetscFree2(jc, ir));
    PetscCall(MatSeqAIJRestoreArray(sub[0], &a));
    PetscCall(MatRestoreRowIJ(sub[0], 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
  }
  PetscCall(MatDestroySubMatrices(1, &sub));
  PetscCall(ISDestroy(&rows));
  PetscCall(ISDestroy(&cols));
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm)); /* the file is complete before anyone reads it */
  PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "Cannot write the HDF5 file %s", file);
  PetscFunctionReturn(0);
}

/* Write a matrix (Matrix Market, PETSc binary or HDF5 by extension; export and tests) */
PetscErrorCode JRMatSaveFile(Mat A, const char spec[], const char group[])
{
  MPI_Comm comm;
  char     ext[16], file[PETSC_MAX_PATH_LEN], grp[256];

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)A, &comm));
  PetscCall(Extension(spec, ext, sizeof(ext)));
  PetscCall(SplitGroup(spec, group, file, sizeof(file), grp, sizeof(grp)));
  if (!strcmp(ext, "mtx")) {
    PetscViewer v;
    PetscCall(PetscViewerASCIIOpen(comm, file, &v));
    PetscCall(PetscViewerPushFormat(v, PETSC_VIEWER_ASCII_MATRIXMARKET));
    PetscCall(MatView(A, v));
    PetscCall(PetscViewerPopFormat(v));
    PetscCall(PetscViewerDestroy(&v));
  } else if (!strcmp(ext, "bin") || !strcmp(ext, "dat") || !strcmp(ext, "petsc")) {
    PetscViewer v;
    PetscCall(PetscViewerBinaryOpen(comm, file, FILE_MODE_WRITE, &v));
    PetscCall(MatView(A, v));
    PetscCall(PetscViewerDestroy(&v));
  } else if (!strcmp(ext, "h5") || !strcmp(ext, "hdf5")) PetscCall(SaveH5(A, file, grp));
  else SETERRQ(comm, PETSC_ERR_SUP, "Matrix file %s: unknown extension '.%s' (use .mtx, .bin or .h5)", file, ext);
  PetscFunctionReturn(0);
}

/*
  JRVecLoadFile - a vector of length n (DOF order) from .bin, .h5 (dataset "f" or file.h5:/name) or
  text (.csv/.txt: one value per line, '#' comments, optional header). Returns an array of n values
  on every rank.
*/
PetscErrorCode JRVecLoadFile(MPI_Comm comm, const char spec[], PetscInt n, PetscReal vals[])
{
  char ext[16], file[PETSC_MAX_PATH_LEN], grp[256];

  PetscFunctionBeginUser;
  PetscCall(Extension(spec, ext, sizeof(ext)));
  PetscCall(SplitGroup(spec, "f", file, sizeof(file), grp, sizeof(grp)));
  PetscCall(FileReadable(comm, file, "force vector"));
  if (!strcmp(ext, "bin") || !strcmp(ext, "h5") || !strcmp(ext, "hdf5")) {
    PetscViewer        v;
    Vec                x, xs;
    VecScatter         sc;
    PetscInt           N;
    const PetscScalar *a;
    char               what[PETSC_MAX_PATH_LEN + 32];
    PetscCall(PetscSNPrintf(what, sizeof(what), "the force vector file %s", file));
    PetscCall(JRErrorContextPush(what)); /* PETSc's error on a truncated or corrupt file names it */
    if (!strcmp(ext, "bin")) PetscCall(PetscViewerBinaryOpen(comm, file, FILE_MODE_READ, &v));
    else PetscCall(PetscViewerHDF5Open(comm, file, FILE_MODE_READ, &v));
    PetscCall(VecCreate(comm, &x));
    PetscCall(PetscObjectSetName((PetscObject)x, grp));
    PetscCall(VecLoad(x, v));
    PetscCall(PetscViewerDestroy(&v));
    PetscCall(JRErrorContextPop());
    PetscCall(VecGetSize(x, &N));
    PetscCheck(N == n, comm, PETSC_ERR_FILE_UNEXPECTED, "Force vector %s has %" PetscInt_FMT " entries, the model has %" PetscInt_FMT " DOFs", file, N, n);
    PetscCall(VecScatterCreateToAll(x, &sc, &xs));
    PetscCall(VecScatterBegin(sc, x, xs, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sc, x, xs, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(xs, &a));
    for (PetscInt i = 0; i < n; i++) vals[i] = PetscRealPart(a[i]);
    PetscCall(VecRestoreArrayRead(xs, &a));
    PetscCall(VecScatterDestroy(&sc));
    PetscCall(VecDestroy(&xs));
    PetscCall(VecDestroy(&x));
  } else {
    JRTable  t;
    PetscInt rows, cols;
    PetscCall(JRTableRead(comm, file, &t));
    PetscCall(JRTableGetSize(t, &rows, &cols));
    /* a file of plain numbers has no header: its first line was taken as the column name */
    PetscCheck(cols == 1, comm, PETSC_ERR_FILE_UNEXPECTED, "Force vector %s: one value per line expected, found %" PetscInt_FMT " columns", file, cols);
    {
      /* without a header line the "column name" is the first value */
      const char *head;
      char       *end;
      double      first;
      PetscInt    off = 0;
      PetscCall(JRTableGetHeader(t, 0, &head));
      first = strtod(head, &end);
      if (end != head && !*end) {
        off     = 1;
        vals[0] = first;
      }
      PetscCheck(rows + off == n, comm, PETSC_ERR_FILE_UNEXPECTED, "Force vector %s has %" PetscInt_FMT " values, the model has %" PetscInt_FMT " DOFs", file, rows + off, n);
      PetscCall(JRTableGetColumn(t, head, PETSC_TRUE, 0.0, vals + off));
    }
    PetscCall(JRTableDestroy(&t));
  }
  for (PetscInt i = 0; i < n; i++) PetscCheck(PetscIsNormalReal(vals[i]) || vals[i] == 0.0, comm, PETSC_ERR_FILE_UNEXPECTED, "Force vector %s: entry %" PetscInt_FMT " is not finite", file, i);
  PetscFunctionReturn(0);
}
