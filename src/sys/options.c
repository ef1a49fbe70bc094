/*
   Options a run did not use. JROptionsCheck runs after every object of a task has read its options and before any
   heavy work: an option of jointrom's own (-task, -model_*, -preload_*, -interface_*, -modes_*, -rom_*, -hbm_*,
   -cont_*, -frf_*, -element_*, -nlm_*, not the nested solvers' -hbm_snes_* and the like) that nothing read is an error
   naming it and, where one is close, the option it was probably meant to be. JROptionsWarnUnused, at the end of a
   run, warns about every other option nothing read (a nested solver's option is read only when that solver runs).
   JROptionsCheckValues, at the start, stops a run given one of jointrom's options that take a number or a choice
   without a value (PETSc would keep the default), or a number option a value that is not a whole number.
*/
#include <jointrom.h>
#include <slepceps.h>
#include <petsctao.h>

extern const char *const JROptionNames[];     /* generated from the sources by src/sys/optnames.sh */
extern const char *const JROptionValued[][2]; /* the options that take a value: name, what the value is */

/* jointrom's option groups, checked before the work; a nested solver's options inside them are read later */
static const char *const Groups[]  = {"task", "model_", "preload_", "interface_", "modes_", "rom_", "hbm_", "cont_", "frf_verify_", "frf_", "element_", "nlm_", "compare_", NULL};
static const char *const Nested[]  = {"snes_", "ksp_", "ts_", "pc_", "eps_", "st_", "tao_", "bv_", "ds_", "rg_", "fn_", "mat_", "vec_", "dm_", "petsc", "mg_", "sub_", NULL};
static const char *const Viewers[] = {"view", "monitor", "converged_reason", "draw", NULL};

static size_t Distance(const char *a, const char *b)
{
  size_t la = strlen(a), lb = strlen(b), d[128];
  if (la > 120 || lb > 120) return 1000;
  for (size_t j = 0; j <= lb; j++) d[j] = j;
  for (size_t i = 1; i <= la; i++) {
    size_t prev = d[0];
    d[0]        = i;
    for (size_t j = 1; j <= lb; j++) {
      const size_t t = d[j];
      size_t       c = prev + (a[i - 1] != b[j - 1]);
      c              = PetscMin(c, d[j] + 1);
      c              = PetscMin(c, d[j - 1] + 1);
      d[j]           = c;
      prev           = t;
    }
  }
  return d[lb];
}

/* The known option nearest to name (with its '-'), or NULL if none is close */
static const char *Nearest(const char *name)
{
  const char *best = NULL;
  size_t      bd   = 1000, len = strlen(name);
  for (PetscInt i = 0; JROptionNames[i]; i++) {
    const size_t dd = Distance(name, JROptionNames[i]);
    if (dd < bd) {
      bd   = dd;
      best = JROptionNames[i];
    }
  }
  return bd > 0 && bd <= PetscMax(2, len / 5) ? best : NULL;
}

static PetscBool Known(const char *name)
{
  for (PetscInt i = 0; JROptionNames[i]; i++)
    if (!strcmp(name, JROptionNames[i])) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* jointrom's own option (name without its '-'), not a nested solver's or a viewer's */
static PetscBool Ours(const char *name)
{
  for (PetscInt g = 0; Groups[g]; g++) {
    const size_t l = strlen(Groups[g]);
    const char  *rest;
    if (strncmp(name, Groups[g], l)) continue;
    rest = name + l;
    if (!strncmp(rest, "hbm_", 4) || !strncmp(rest, "nlm_", 4)) rest += 4; /* a solver's own prefix after its owner's: rom_nlm_snes_ */
    for (PetscInt k = 0; Nested[k]; k++)
      if (!strncmp(rest, Nested[k], strlen(Nested[k]))) return PETSC_FALSE;
    for (PetscInt k = 0; Viewers[k]; k++)
      if (strstr(name + l, Viewers[k]) && strcmp(name + l, "view") && !Known(name - 1)) return PETSC_FALSE;
    return PETSC_TRUE;
  }
  return PETSC_FALSE;
}

/* One line per unused option into msg: "-name (did you mean -other?)" or "-name (not used by <what>)" */
static PetscErrorCode Describe(const char *name, const char *what, char msg[], size_t len)
{
  char        opt[256];
  const char *near;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s", name));
  near = Nearest(opt);
  if (Known(opt)) PetscCall(PetscSNPrintf(msg, len, "%s is not used by %s", opt, what));
  else if (near) PetscCall(PetscSNPrintf(msg, len, "unknown option %s (did you mean %s?)", opt, near));
  else PetscCall(PetscSNPrintf(msg, len, "unknown option %s", opt));
  PetscFunctionReturn(0);
}

/* PETSc's names for default values, which its number parsers take */
static PetscBool PetscWord(const char *s)
{
  return (PetscBool)(!strncmp(s, "PETSC_", 6) || !strcmp(s, "DEFAULT") || !strcmp(s, "DECIDE") || !strcmp(s, "DETERMINE"));
}

/* s (one item of len characters) a whole number: a real, or an integer (in a list also a range a-b, b > a, as PETSc's
   integer lists take) */
static PetscBool ItemOK(const char *s, size_t len, PetscBool integer, PetscBool list)
{
  char  item[64], *end;
  if (!len || len >= sizeof(item)) return PETSC_FALSE;
  memcpy(item, s, len);
  item[len] = 0;
  if (PetscWord(item)) return PETSC_TRUE;
  if (integer) {
    const long long a = strtoll(item, &end, 10);
    if (end != item && list && *end == '-' && end[1]) { /* a range a-b: a, ..., b - 1 */
      const char     *b0 = end + 1;
      const long long b  = strtoll(b0, &end, 10);
      if (end == b0 || b <= a) return PETSC_FALSE;
    }
  } else (void)strtod(item, &end);
  return (PetscBool)(end != item && !*end);
}

/*
  JROptionsCheckValues - at the start of a run, before anything reads jointrom's options (every option is still
  unused then, so the database lists it with its value): an error for the first of jointrom's options that take a
  number (or a list of them) given without a value, which PETSc would take as the default, or with one that is not a
  whole number, which PETSc would refuse without naming the option. A choice without a value is an error too.
*/
PetscErrorCode JROptionsCheckValues(MPI_Comm comm)
{
  PetscInt n;
  char   **names, **values, msg[512] = "";

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n && !msg[0]; i++) {
    for (PetscInt k = 0; JROptionValued[k][0] && !msg[0]; k++) {
      const char *kind = JROptionValued[k][1], *v = values[i];
      PetscBool   integer, list, number;
      if (strcmp(names[i], JROptionValued[k][0] + 1)) continue;
      if (!v || !v[0]) {
        PetscCall(PetscSNPrintf(msg, sizeof(msg), "%s is given without a value: it takes %s", JROptionValued[k][0], kind));
        break;
      }
      integer = (PetscBool)!strncmp(kind, "an integer", 10);
      number  = (PetscBool)(integer || !strncmp(kind, "a number", 8));
      list    = (PetscBool)(strstr(kind, "list") != NULL);
      if (!number) break;
      for (const char *p = v;;) {
        const char  *c   = list ? strchr(p, ',') : NULL;
        const size_t len = c ? (size_t)(c - p) : strlen(p);
        if (!ItemOK(p, len, integer, list)) {
          PetscCall(PetscSNPrintf(msg, sizeof(msg), "%s %s: '%.*s' is not %s; it takes %s", JROptionValued[k][0], v, (int)PetscMin(len, 64), p, integer ? "an integer" : "a number", kind));
          break;
        }
        if (!c) break;
        p = c + 1;
      }
    }
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscCheck(!msg[0], comm, PETSC_ERR_USER_INPUT, "%s", msg);
  PetscFunctionReturn(0);
}

/*
  JROptionsCheck - after every object of the run has read its options (SetFromOptions), before the work: an error
  naming each of jointrom's options that nothing read. what: the run, as the message names it ("-task frf with a
  matrices model").
*/
PetscErrorCode JROptionsCheck(MPI_Comm comm, const char what[])
{
  PetscInt n, bad = 0;
  char   **names, **values, all[4096] = "", line[512];

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n; i++) {
    if (!Ours(names[i])) continue;
    PetscCall(Describe(names[i], what, line, sizeof(line)));
    if (bad++) PetscCall(PetscStrlcat(all, "; ", sizeof(all)));
    PetscCall(PetscStrlcat(all, line, sizeof(all)));
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscCheck(!bad, comm, PETSC_ERR_USER_INPUT, "%s; 'jointrom -task <task> -help' lists every option", all);
  PetscFunctionReturn(0);
}

/* JROptionsWarnUnused - at the end of a run: a warning for every option nothing read (nested solvers' included), but
   -options_left and -options_view, which PetscFinalize reads after it */
PetscErrorCode JROptionsWarnUnused(MPI_Comm comm)
{
  PetscInt n;
  char   **names, **values, line[512];

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n; i++) {
    if (!strcmp(names[i], "options_left") || !strcmp(names[i], "options_view")) continue;
    PetscCall(Describe(names[i], "this run", line, sizeof(line)));
    PetscCall(PetscPrintf(comm, "jointrom: warning: %s\n", line));
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscFunctionReturn(0);
}

/* -help: the options of the nested solvers of a task (prefixes "hbm_", "preload_", "modes_", "rom_" as it has them):
   a solver of each kind is made, reads its options (which -help lists) and is destroyed */
PetscErrorCode JROptionsHelpSolvers(MPI_Comm comm, PetscBool hbm, PetscBool preload, PetscBool modes, PetscBool rom)
{
  PetscFunctionBeginUser;
  if (hbm || preload) {
    const char *pre[3] = {"hbm_", "rom_hbm_", "preload_"};
    for (PetscInt i = 0; i < 3; i++) {
      SNES snes;
      if (!(i == 2 ? preload : i == 1 ? hbm && rom : hbm)) continue;
      PetscCall(SNESCreate(comm, &snes));
      PetscCall(SNESSetOptionsPrefix(snes, pre[i]));
      PetscCall(SNESSetFromOptions(snes));
      PetscCall(SNESDestroy(&snes));
    }
  }
  if (modes) {
    EPS eps;
    PetscCall(EPSCreate(comm, &eps));
    PetscCall(EPSSetOptionsPrefix(eps, "modes_"));
    PetscCall(EPSSetFromOptions(eps));
    PetscCall(EPSDestroy(&eps));
  }
  if (rom) {
    Tao tao;
    PetscCall(TaoCreate(comm, &tao));
    PetscCall(TaoSetOptionsPrefix(tao, "rom_"));
    PetscCall(TaoSetFromOptions(tao));
    PetscCall(TaoDestroy(&tao));
  }
  PetscFunctionReturn(0);
}

/* A factorisation preconditioner (LU or Cholesky, options prefix prefix) whose -pc_factor_mat_solver_type names a
   package that cannot factor A (a sequential one on several ranks, or an unknown name): one message naming the
   option, before the factorisation's own error deep in a solve */
PetscErrorCode JRCheckFactorSolverType(PC pc, Mat A, const char prefix[])
{
  PetscBool   factor, chol, set, avail = PETSC_FALSE, known = PETSC_FALSE;
  char        type[64];
  MatType     mt;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  if (!A) PetscFunctionReturn(0);
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &factor, PCLU, PCCHOLESKY, ""));
  if (!factor) PetscFunctionReturn(0);
  PetscCall(PetscOptionsGetString(NULL, prefix, "-pc_factor_mat_solver_type", type, sizeof(type), &set));
  if (!set) PetscFunctionReturn(0);
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCCHOLESKY, &chol));
  PetscCall(MatGetFactorAvailable(A, type, chol ? MAT_FACTOR_CHOLESKY : MAT_FACTOR_LU, &avail));
  if (avail) PetscFunctionReturn(0);
  PetscCall(MatGetType(A, &mt));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)A), &size));
  PetscCall(MatSolverTypeGet(type, mt, chol ? MAT_FACTOR_CHOLESKY : MAT_FACTOR_LU, &known, NULL, NULL));
  PetscCheck(known, PetscObjectComm((PetscObject)A), PETSC_ERR_USER_INPUT, "-%spc_factor_mat_solver_type %s: no such factorisation package in this PETSc; use mumps, the default", prefix, type);
  SETERRQ(PetscObjectComm((PetscObject)A), PETSC_ERR_USER_INPUT, "-%spc_factor_mat_solver_type %s: '%s' has no %s factorisation of this %s matrix%s", prefix, type, type, chol ? "Cholesky" : "LU", mt, size > 1 ? ": PETSc's own LU and Cholesky factor only sequential matrices, so on more than one rank use mumps, the default" : "; use mumps, the default");
  PetscFunctionReturn(0);
}
