/*
   CSV tables with a header line, read on rank 0 and broadcast so every rank parses the same text
   (and reports the same error). A UTF-8 byte-order mark, lines starting with '#' and blank lines are
   skipped; every row has as many fields as the header. Columns are found by header name; every error
   names the file, the line and the column.
*/
#include <jointrom.h>
#include <ctype.h>
#include <errno.h>

struct _p_JRTable {
  MPI_Comm  comm;  /* every rank holds the same table: its errors are raised on every rank */
  char     *file;
  PetscInt  ncol, nrow;
  char    **head;  /* ncol names */
  char    **cell;  /* nrow*ncol trimmed strings (point into text) */
  PetscInt *line;  /* file line number of each row */
  PetscInt  hline; /* and of the header */
  char     *text;
};

static char *Trim(char *s)
{
  char *e;
  while (*s && isspace((unsigned char)*s)) s++;
  e = s + strlen(s);
  while (e > s && isspace((unsigned char)e[-1])) *--e = 0;
  return s;
}

static PetscInt CountFields(const char *s)
{
  PetscInt n = 1;
  for (; *s; s++) n += (*s == ',');
  return n;
}

/* Split s at commas in place into fields[0..n-1] (trimmed) */
static void Split(char *s, char **fields)
{
  PetscInt k = 0;
  char    *p = s;
  while (1) {
    char *q = strchr(p, ',');
    if (q) *q = 0;
    fields[k++] = Trim(p);
    if (!q) break;
    p = q + 1;
  }
}

/* Read a CSV file (collective): header line, then one row per line */
PetscErrorCode JRTableRead(MPI_Comm comm, const char file[], JRTable *table)
{
  JRTable     t;
  PetscMPIInt rank;
  long        len = 0;
  char       *p;
  PetscInt    lineno = 0, cap = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscNew(&t));
  PetscCall(PetscStrallocpy(file, &t->file));
  t->comm = comm;
  if (rank == 0) {
    FILE *fp = fopen(file, "rb");
    if (fp) {
      if (fseek(fp, 0, SEEK_END) == 0) len = ftell(fp);
      rewind(fp);
    } else len = -1;
    if (len >= 0) {
      PetscCall(PetscMalloc1(len + 1, &t->text));
      if ((long)fread(t->text, 1, len, fp) != len) len = -2;
      else t->text[len] = 0;
    }
    if (fp) fclose(fp);
  }
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_LONG, 0, comm));
  PetscCheck(len != -1, comm, PETSC_ERR_FILE_OPEN, "Cannot open the CSV file %s", file);
  PetscCheck(len != -2, comm, PETSC_ERR_FILE_READ, "Cannot read the CSV file %s", file);
  if (rank) PetscCall(PetscMalloc1(len + 1, &t->text));
  PetscCallMPI(MPI_Bcast(t->text, (PetscMPIInt)(len + 1), MPI_CHAR, 0, comm));

  p = t->text;
  if (!strncmp(p, "\xEF\xBB\xBF", 3)) p += 3; /* a UTF-8 byte-order mark */
  for (; p && *p;) {
    char *s = p, *nl = strchr(p, '\n');
    if (nl) *nl = 0;
    p = nl ? nl + 1 : NULL;
    lineno++;
    s = Trim(s);
    if (!*s || *s == '#') continue;
    if (!t->head) {
      t->hline = lineno;
      t->ncol  = CountFields(s);
      PetscCall(PetscMalloc1(t->ncol, &t->head));
      Split(s, t->head);
      for (PetscInt k = 0; k < t->ncol; k++) {
        PetscCheck(t->head[k][0], comm, PETSC_ERR_FILE_UNEXPECTED, "CSV file %s line %" PetscInt_FMT ": column %" PetscInt_FMT " of the header has no name (the first line must name the columns, e.g. kt,kn,mu,n0)", file, lineno, k + 1);
        for (PetscInt j = 0; j < k; j++) PetscCheck(strcmp(t->head[j], t->head[k]), comm, PETSC_ERR_FILE_UNEXPECTED, "CSV file %s: column '%s' appears twice in the header", file, t->head[k]);
      }
      continue;
    }
    {
      const PetscInt nf = CountFields(s);
      PetscCheck(nf == t->ncol, comm, PETSC_ERR_FILE_UNEXPECTED, "CSV file %s line %" PetscInt_FMT ": %" PetscInt_FMT " fields, but the header has %" PetscInt_FMT " columns", file, lineno, nf, t->ncol);
    }
    if (t->nrow == cap) {
      char   **nc;
      PetscInt *nl;
      cap = cap ? 2 * cap : 64;
      PetscCall(PetscMalloc1(cap * t->ncol, &nc));
      PetscCall(PetscMalloc1(cap, &nl));
      if (t->nrow) {
        PetscCall(PetscArraycpy(nc, t->cell, t->nrow * t->ncol));
        PetscCall(PetscArraycpy(nl, t->line, t->nrow));
      }
      PetscCall(PetscFree(t->cell));
      PetscCall(PetscFree(t->line));
      t->cell = nc;
      t->line = nl;
    }
    Split(s, t->cell + t->nrow * t->ncol);
    t->line[t->nrow++] = lineno;
  }
  PetscCheck(t->head, comm, PETSC_ERR_FILE_UNEXPECTED, "CSV file %s is empty: it needs a header line naming the columns", file);
  *table = t;
  PetscFunctionReturn(0);
}

PetscErrorCode JRTableGetSize(JRTable t, PetscInt *nrow, PetscInt *ncol)
{
  PetscFunctionBeginUser;
  if (nrow) *nrow = t->nrow;
  if (ncol) *ncol = t->ncol;
  PetscFunctionReturn(0);
}

PetscErrorCode JRTableHasColumn(JRTable t, const char name[], PetscBool *has)
{
  PetscFunctionBeginUser;
  *has = PETSC_FALSE;
  for (PetscInt k = 0; k < t->ncol; k++)
    if (!strcmp(t->head[k], name)) *has = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The trimmed text of a cell (empty string if the column is absent) */
PetscErrorCode JRTableGetString(JRTable t, const char name[], PetscInt row, const char **str)
{
  PetscFunctionBeginUser;
  PetscCheck(row >= 0 && row < t->nrow, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Row %" PetscInt_FMT " outside the %" PetscInt_FMT " rows of %s", row, t->nrow, t->file);
  *str = "";
  for (PetscInt k = 0; k < t->ncol; k++)
    if (!strcmp(t->head[k], name)) *str = t->cell[row * t->ncol + k];
  PetscFunctionReturn(0);
}

/* The name of column k */
PetscErrorCode JRTableGetHeader(JRTable t, PetscInt k, const char **name)
{
  PetscFunctionBeginUser;
  PetscCheck(k >= 0 && k < t->ncol, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Column %" PetscInt_FMT " outside the %" PetscInt_FMT " columns of %s", k, t->ncol, t->file);
  *name = t->head[k];
  PetscFunctionReturn(0);
}

/* The file line number of a row (row -1: the header), for error messages */
PetscErrorCode JRTableGetLine(JRTable t, PetscInt row, PetscInt *line)
{
  PetscFunctionBeginUser;
  PetscCheck(row >= -1 && row < t->nrow, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Row %" PetscInt_FMT " outside the %" PetscInt_FMT " rows of %s", row, t->nrow, t->file);
  *line = row < 0 ? t->hline : t->line[row];
  PetscFunctionReturn(0);
}

PetscErrorCode JRTableGetFileName(JRTable t, const char **file)
{
  PetscFunctionBeginUser;
  *file = t->file;
  PetscFunctionReturn(0);
}

/* Numeric column by name: every cell a finite number (strtod taking the whole cell; no nan, inf or overflow).
   required: the column and every cell must be present; otherwise a missing column or an empty cell gives def. */
PetscErrorCode JRTableGetColumn(JRTable t, const char name[], PetscBool required, PetscReal def, PetscReal vals[])
{
  PetscInt col = -1;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < t->ncol; k++)
    if (!strcmp(t->head[k], name)) col = k;
  if (col < 0) {
    PetscCheck(!required, t->comm, PETSC_ERR_FILE_UNEXPECTED, "CSV file %s has no column '%s' (its header names %" PetscInt_FMT " columns, first '%s')", t->file, name, t->ncol, t->head[0]);
    for (PetscInt i = 0; i < t->nrow; i++) vals[i] = def;
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < t->nrow; i++) {
    const char *s = t->cell[i * t->ncol + col];
    char       *end;
    double      x;
    if (!*s) {
      PetscCheck(!required, t->comm, PETSC_ERR_FILE_UNEXPECTED, "CSV file %s line %" PetscInt_FMT ": column '%s' is empty", t->file, t->line[i], name);
      vals[i] = def;
      continue;
    }
    x = strtod(s, &end);
    PetscCheck(end != s && !*end && isfinite(x), t->comm, PETSC_ERR_FILE_UNEXPECTED, "CSV file %s line %" PetscInt_FMT ", column %" PetscInt_FMT " ('%s'): '%s' is not a finite number", t->file, t->line[i], col + 1, name, s);
    vals[i] = (PetscReal)x;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode JRTableDestroy(JRTable *table)
{
  JRTable t = *table;

  PetscFunctionBeginUser;
  if (!t) PetscFunctionReturn(0);
  PetscCall(PetscFree(t->file));
  PetscCall(PetscFree(t->head));
  PetscCall(PetscFree(t->cell));
  PetscCall(PetscFree(t->line));
  PetscCall(PetscFree(t->text));
  PetscCall(PetscFree(t));
  *table = NULL;
  PetscFunctionReturn(0);
}
