/*
   The element table of a model (CSV, one element per row), header
     type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b
   type: jenkins, jenkins_nv or cubic; DOFs 0-based, -1 = ground; u = x[dof_a] - x[dof_b],
   v = x[ndof_a] - x[ndof_b] (jenkins_nv only, empty otherwise). kt [N/m] (cubic: [N/m^3], any sign),
   kn [N/m], mu [-], n0 [N]. Every error names the file and the line.
*/
#include <jointrom/private/modelimpl.h>
#include <errno.h>

static PetscErrorCode ParseDof(MPI_Comm comm, JRTable t, const char *col, PetscInt row, PetscInt ndof, PetscBool required, PetscInt *dof)
{
  const char *s, *file;
  char       *end;
  long        v;
  PetscInt    line;

  PetscFunctionBeginUser;
  PetscCall(JRTableGetString(t, col, row, &s));
  PetscCall(JRTableGetLine(t, row, &line));
  PetscCall(JRTableGetFileName(t, &file));
  if (!*s) {
    PetscCheck(!required, comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s line %" PetscInt_FMT ": column '%s' is empty", file, line, col);
    *dof = -1;
    PetscFunctionReturn(0);
  }
  errno = 0;
  v     = strtol(s, &end, 10);
  PetscCheck(end != s && !*end && !errno, comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s line %" PetscInt_FMT ": column '%s' is '%s', not a DOF number", file, line, col, s);
  PetscCheck(v >= -1 && v < ndof, comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s line %" PetscInt_FMT ": %s = %ld is out of range: DOFs are 0..%" PetscInt_FMT " (-1 = ground)", file, line, col, v, ndof - 1);
  *dof = (PetscInt)v;
  PetscFunctionReturn(0);
}

/* Read and check the element table against a model with ndof DOFs */
PetscErrorCode JRElementsReadCSV(MPI_Comm comm, const char file[], PetscInt ndof, JRElements *el)
{
  JRTable     t;
  PetscInt    n, line;
  const char *known[] = {JRCONTACTJENKINS, JRCONTACTJENKINSNV, JRCONTACTCUBIC};

  PetscFunctionBeginUser;
  PetscCall(JRElementsDestroy(el));
  PetscCall(JRTableRead(comm, file, &t));
  PetscCall(JRTableGetSize(t, &n, NULL));
  PetscCall(JRTableGetLine(t, -1, &line));
  PetscCheck(n > 0, comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s line %" PetscInt_FMT ": a header but no element rows after it (one element per row: type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b)", file, line);
  {
    const char *need[] = {"type", "dof_a", "dof_b", "kt", "mu", "n0"};
    for (size_t i = 0; i < sizeof(need) / sizeof(need[0]); i++) {
      PetscBool has;
      PetscCall(JRTableHasColumn(t, need[i], &has));
      PetscCheck(has, comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s has no column '%s' (header: type,dof_a,dof_b,kt,kn,mu,n0,ndof_a,ndof_b)", file, need[i]);
    }
  }
  el->n = n;
  PetscCall(PetscMalloc5(n, &el->type, n, &el->dof_a, n, &el->dof_b, n, &el->ndof_a, n, &el->ndof_b));
  PetscCall(PetscMalloc4(n, &el->kt, n, &el->kn, n, &el->mu, n, &el->n0));
  PetscCall(JRTableGetColumn(t, "kt", PETSC_TRUE, 0.0, el->kt));
  PetscCall(JRTableGetColumn(t, "kn", PETSC_FALSE, 0.0, el->kn));
  PetscCall(JRTableGetColumn(t, "mu", PETSC_FALSE, 0.0, el->mu));
  PetscCall(JRTableGetColumn(t, "n0", PETSC_FALSE, 0.0, el->n0));
  for (PetscInt e = 0; e < n; e++) {
    const char *ty;
    PetscInt    k = -1;
    PetscCall(JRTableGetLine(t, e, &line));
    PetscCall(JRTableGetString(t, "type", e, &ty));
    for (size_t i = 0; i < sizeof(known) / sizeof(known[0]); i++)
      if (!strcmp(ty, known[i])) k = (PetscInt)i;
    PetscCheck(k >= 0, comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s line %" PetscInt_FMT ": unknown element type '%s' (jenkins, jenkins_nv or cubic)", file, line, ty);
    /* index into the list of types present */
    {
      PetscInt idx = -1;
      for (PetscInt i = 0; i < el->ntypes; i++)
        if (!strcmp(el->typename[i], ty)) idx = i;
      if (idx < 0) {
        idx = el->ntypes++;
        PetscCall(PetscStrncpy(el->typename[idx], ty, sizeof(el->typename[idx])));
      }
      el->type[e] = idx;
    }
    PetscCall(ParseDof(comm, t, "dof_a", e, ndof, PETSC_TRUE, &el->dof_a[e]));
    PetscCall(ParseDof(comm, t, "dof_b", e, ndof, PETSC_TRUE, &el->dof_b[e]));
    PetscCheck(el->dof_a[e] != el->dof_b[e], comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s line %" PetscInt_FMT ": dof_a and dof_b are both %" PetscInt_FMT " (an element joins two different DOFs, or one DOF to ground -1)", file, line, el->dof_a[e]);
    PetscCall(ParseDof(comm, t, "ndof_a", e, ndof, PETSC_FALSE, &el->ndof_a[e]));
    PetscCall(ParseDof(comm, t, "ndof_b", e, ndof, PETSC_FALSE, &el->ndof_b[e]));
    if (k == 1) PetscCheck(el->ndof_a[e] != el->ndof_b[e], comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s line %" PetscInt_FMT ": a jenkins_nv element needs normal DOFs ndof_a, ndof_b (two different DOFs, or one and -1 = ground)", file, line);
    else PetscCheck(el->ndof_a[e] < 0 && el->ndof_b[e] < 0, comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s line %" PetscInt_FMT ": normal DOFs are only for jenkins_nv elements; leave ndof_a, ndof_b empty for %s", file, line, ty);
    PetscCheck(PetscIsNormalReal(el->kt[e]) && (el->kt[e] > 0.0 || k == 2), comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s line %" PetscInt_FMT ": kt = %g must be positive [N/m]", file, line, (double)el->kt[e]);
    PetscCheck(!PetscIsInfOrNanReal(el->kn[e]) && el->kn[e] >= 0.0, comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s line %" PetscInt_FMT ": kn = %g must be non-negative [N/m]", file, line, (double)el->kn[e]);
    PetscCheck(!PetscIsInfOrNanReal(el->mu[e]) && el->mu[e] >= 0.0, comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s line %" PetscInt_FMT ": mu = %g must be non-negative", file, line, (double)el->mu[e]);
    PetscCheck(!PetscIsInfOrNanReal(el->n0[e]) && (el->n0[e] >= 0.0 || k == 1), comm, PETSC_ERR_FILE_UNEXPECTED, "Element file %s line %" PetscInt_FMT ": n0 = %g must be finite%s [N]", file, line, (double)el->n0[e], k == 1 ? "" : " and non-negative (initial gaps need jenkins_nv)");
  }
  PetscCall(JRTableDestroy(&t));
  PetscFunctionReturn(0);
}

PetscErrorCode JRElementsDestroy(JRElements *el)
{
  PetscFunctionBeginUser;
  if (el->n || el->type) {
    PetscCall(PetscFree5(el->type, el->dof_a, el->dof_b, el->ndof_a, el->ndof_b));
    PetscCall(PetscFree4(el->kt, el->kn, el->mu, el->n0));
  }
  PetscCall(PetscFree4(el->vdof_a, el->vdof_b, el->tdir, el->ndir));
  PetscCall(PetscFree(el->joint));
  PetscCall(PetscFree(el->pos));
  PetscCall(PetscFree(el->phi));
  PetscCall(PetscFree(el->phir));
  if (el->members) {
    PetscCall(JRElementsDestroy(el->members));
    PetscCall(PetscFree(el->members));
  }
  PetscCall(PetscMemzero(el, sizeof(*el)));
  PetscFunctionReturn(0);
}

/* A deep copy of an element list (with its joints and members) into b (overwritten) */
PetscErrorCode JRElementsDuplicate(const JRElements *a, JRElements *b)
{
  const PetscInt n = a->n;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(b, sizeof(*b)));
  b->n      = n;
  b->ntypes = a->ntypes;
  for (PetscInt t = 0; t < a->ntypes; t++) PetscCall(PetscStrncpy(b->typename[t], a->typename[t], sizeof(b->typename[t])));
  PetscCall(PetscMalloc5(n, &b->type, n, &b->dof_a, n, &b->dof_b, n, &b->ndof_a, n, &b->ndof_b));
  PetscCall(PetscMalloc4(n, &b->kt, n, &b->kn, n, &b->mu, n, &b->n0));
  PetscCall(PetscArraycpy(b->type, a->type, n));
  PetscCall(PetscArraycpy(b->dof_a, a->dof_a, n));
  PetscCall(PetscArraycpy(b->dof_b, a->dof_b, n));
  PetscCall(PetscArraycpy(b->ndof_a, a->ndof_a, n));
  PetscCall(PetscArraycpy(b->ndof_b, a->ndof_b, n));
  PetscCall(PetscArraycpy(b->kt, a->kt, n));
  PetscCall(PetscArraycpy(b->kn, a->kn, n));
  PetscCall(PetscArraycpy(b->mu, a->mu, n));
  PetscCall(PetscArraycpy(b->n0, a->n0, n));
  if (a->joint) {
    b->njoints = a->njoints;
    PetscCall(PetscMalloc1(n, &b->joint));
    PetscCall(PetscArraycpy(b->joint, a->joint, n));
  }
  if (a->vdof_a) {
    PetscCall(PetscMalloc4(3 * n, &b->vdof_a, 3 * n, &b->vdof_b, 3 * n, &b->tdir, 3 * n, &b->ndir));
    PetscCall(PetscArraycpy(b->vdof_a, a->vdof_a, 3 * n));
    PetscCall(PetscArraycpy(b->vdof_b, a->vdof_b, 3 * n));
    PetscCall(PetscArraycpy(b->tdir, a->tdir, 3 * n));
    PetscCall(PetscArraycpy(b->ndir, a->ndir, 3 * n));
  }
  if (a->pos) {
    PetscCall(PetscMalloc1(3 * n, &b->pos));
    PetscCall(PetscArraycpy(b->pos, a->pos, 3 * n));
  }
  if (a->phi) {
    PetscCall(PetscMalloc1(2 * n, &b->phi));
    PetscCall(PetscArraycpy(b->phi, a->phi, 2 * n));
  }
  if (a->phir) {
    PetscCall(PetscMalloc1(JR_NREL * n, &b->phir));
    PetscCall(PetscArraycpy(b->phir, a->phir, JR_NREL * n));
  }
  if (a->members) {
    PetscCall(PetscNew(&b->members));
    PetscCall(JRElementsDuplicate(a->members, b->members));
  }
  PetscFunctionReturn(0);
}

/* Element e's stuck springs if it is a friction element in contact at rest (n0 > 0): its m DOFs d and their weights
   v in the tangential and normal motions (kt along t, kn along n for jenkins_nv); 0 otherwise */
static PetscInt StuckSprings(const JRElements *el, PetscInt e, PetscInt d[6], PetscReal v[6][2], PetscReal *kn)
{
  const char     *ty = el->typename[el->type[e]];
  const PetscBool nv = (PetscBool)!strcmp(ty, JRCONTACTJENKINSNV);
  PetscInt        m  = 0;

  *kn = nv ? el->kn[e] : 0.0;
  if (!(el->n0[e] > 0) || !(nv || !strcmp(ty, JRCONTACTJENKINS))) return 0;
  if (el->vdof_a) {
    for (PetscInt c = 0; c < 3; c++) {
      d[m]      = el->vdof_a[3 * e + c];
      v[m][0]   = el->tdir[3 * e + c];
      v[m++][1] = el->ndir[3 * e + c];
    }
    for (PetscInt c = 0; c < 3; c++) {
      d[m]      = el->vdof_b[3 * e + c];
      v[m][0]   = -el->tdir[3 * e + c];
      v[m++][1] = -el->ndir[3 * e + c];
    }
    return m;
  }
  {
    const PetscInt  dd[4]    = {el->dof_a[e], el->dof_b[e], nv ? el->ndof_a[e] : -1, nv ? el->ndof_b[e] : -1};
    const PetscReal wt[4][2] = {
      {1,  0 },
      {-1, 0 },
      {0,  1 },
      {0,  -1}
    };
    for (PetscInt k = 0; k < 4; k++) {
      PetscInt j;
      if (dd[k] < 0) continue;
      for (j = 0; j < m; j++)
        if (d[j] == dd[k]) break;
      if (j == m) {
        d[m]    = dd[k];
        v[m][0] = v[m][1] = 0.0;
        m++;
      }
      v[j][0] += wt[k][0];
      v[j][1] += wt[k][1];
    }
  }
  return m;
}

/*
  JRElementsCreateStuckStiffness - Ks: the springs of every friction element in contact at rest (n0 > 0) stuck,
  kt along its tangential direction and kn along its normal one (jenkins_nv), between its DOFs, as a
  matrix of K's layout (add it with MatAXPY(..., DIFFERENT_NONZERO_PATTERN)).
*/
PetscErrorCode JRElementsCreateStuckStiffness(Mat K, const JRElements *el, Mat *Ks)
{
  PetscInt  *bn, **bd, nb = 0;
  PetscReal **bv;

  PetscFunctionBeginUser;
  if (el->members) el = el->members; /* a reduced model: its basis is that of the node-to-node elements */
  PetscCall(PetscMalloc3(el->n, &bn, el->n, &bd, el->n, &bv));
  for (PetscInt e = 0; e < el->n; e++) {
    PetscInt  d[6], m;
    PetscReal v[6][2], kn;
    if (!(m = StuckSprings(el, e, d, v, &kn))) continue;
    bn[nb] = m;
    PetscCall(PetscMalloc2(m, &bd[nb], m * m, &bv[nb]));
    for (PetscInt i = 0; i < m; i++) {
      bd[nb][i] = d[i];
      for (PetscInt j = 0; j < m; j++) bv[nb][i * m + j] = el->kt[e] * v[i][0] * v[j][0] + kn * v[i][1] * v[j][1];
    }
    nb++;
  }
  PetscCall(JRMatCreateFromBlocks(K, nb, bn, (const PetscInt *const *)bd, (const PetscReal *const *)bv, Ks));
  for (PetscInt b = 0; b < nb; b++) PetscCall(PetscFree2(bd[b], bv[b]));
  PetscCall(PetscFree3(bn, bd, bv));
  PetscFunctionReturn(0);
}

/*
  JRElementsStuckSignature - a number that identifies the stuck springs of JRElementsCreateStuckStiffness in saved
  modes: the sum of the springs' stiffness over the elements and their DOFs, each DOF weighted by its natural number
  (JRModelDOFsToNatural), so that it does not depend on the number of ranks; sigraw (may be NULL) the same on the DOFs'
  own numbers, as files written before the natural order hold it. Collective.
*/
PetscErrorCode JRElementsStuckSignature(JRModel model, const JRElements *el, PetscReal *sig, PetscReal *sigraw)
{
  PetscReal sg = 0.0, sr = 0.0;

  PetscFunctionBeginUser;
  PetscCall(JRModelDOFsToNatural(model, 0, NULL, NULL)); /* its tables, on every rank */
  if (el->members) el = el->members;
  for (PetscInt e = 0; e < el->n; e++) {
    PetscInt  d[6], m;
    PetscReal v[6][2], kn;
    if (!(m = StuckSprings(el, e, d, v, &kn))) continue;
    for (PetscInt i = 0; i < m; i++) sr += (el->kt[e] + kn) * (1.0 + 1e-7 * (PetscReal)d[i]);
    PetscCall(JRModelDOFsToNatural(model, m, d, d));
    for (PetscInt i = 0; i < m; i++) sg += (el->kt[e] + kn) * (1.0 + 1e-7 * (PetscReal)d[i]);
  }
  *sig = sg;
  if (sigraw) *sigraw = sr;
  PetscFunctionReturn(0);
}
