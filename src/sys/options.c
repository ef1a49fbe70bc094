/*
   Options a run did not use. JROptionsCheck runs after every object of a task has read its options and before any
   heavy work: an option of jointrom's own (-task, -model_*, -preload_*, -interface_*, -modes_*, -rom_*, -hbm_*,
   -cont_*, -frf_*, -element_*, -nlm_*, not the nested solvers' -hbm_snes_* and the like) that nothing read is an error
   naming it and, where one is close, the option it was probably meant to be. JROptionsWarnUnused, at the end of a
   run, warns about every other option nothing read (a nested solver's option is read only when that solver runs).
*/
#include <jointrom.h>
#include <slepceps.h>
#include <petsctao.h>

extern const char *const JROptionNames[]; /* generated from the sources by src/sys/optnames.sh */

/* jointrom's option groups, checked before the work; a nested solver's options inside them are read later */
static const char *const Groups[]  = {"task", "model_", "preload_", "interface_", "modes_", "rom_", "hbm_", "cont_", "frf_verify_", "frf_", "element_", "nlm_", NULL};
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
    if (strncmp(name, Groups[g], l)) continue;
    for (PetscInt k = 0; Nested[k]; k++)
      if (!strncmp(name + l, Nested[k], strlen(Nested[k]))) return PETSC_FALSE;
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

/* JROptionsWarnUnused - at the end of a run: a warning for every option nothing read (nested solvers' included) */
PetscErrorCode JROptionsWarnUnused(MPI_Comm comm)
{
  PetscInt n;
  char   **names, **values, line[512];

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n; i++) {
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
