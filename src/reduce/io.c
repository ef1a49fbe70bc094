/*
   Reduced models in files (-rom_save / -rom_load; HDF5, group /rom): the second reduction's elements and the members
   that define the joints' motion, with the members' node coordinates, so that a loaded file is checked against the
   FE model it is used with.
*/
#include <jointrom/private/reduceimpl.h>
#include <jointrom/private/modelimpl.h>
#include <petscviewerhdf5.h>

/* The coordinates of the members' nodes, xc[6 e + c] = x(vdof_a[3e + c]), x(vdof_b[3e + c]) on every rank (collective) */
static PetscErrorCode MemberCoordinates(JRModel model, const JRElements *mem, PetscReal xc[])
{
  Vec                X;
  const PetscScalar *x;
  PetscInt           lo, hi;
  PetscReal         *loc;
  MPI_Comm           comm;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetComm(model, &comm));
  PetscCall(JRModelGetCoordinates(model, &X));
  PetscCheck(X, comm, PETSC_ERR_ARG_WRONG, "A reduced model goes with an FE model (it needs node coordinates)");
  PetscCall(VecGetOwnershipRange(X, &lo, &hi));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(PetscCalloc1(6 * mem->n, &loc));
  for (PetscInt e = 0; e < mem->n; e++)
    for (PetscInt c = 0; c < 3; c++) {
      const PetscInt da = mem->vdof_a[3 * e + c], db = mem->vdof_b[3 * e + c];
      if (da >= lo && da < hi) loc[6 * e + c] = PetscRealPart(x[da - lo]);
      if (db >= lo && db < hi) loc[6 * e + 3 + c] = PetscRealPart(x[db - lo]);
    }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecDestroy(&X));
  PetscCall(MPIU_Allreduce(loc, xc, 6 * mem->n, MPIU_REAL, MPIU_SUM, comm));
  PetscCall(PetscFree(loc));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteSeq(PetscViewer v, const char name[], PetscInt n, PetscInt bs, const PetscReal a[])
{
  Vec          x;
  PetscScalar *xa;

  PetscFunctionBeginUser;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n * bs, &x));
  PetscCall(VecSetBlockSize(x, bs));
  PetscCall(PetscObjectSetName((PetscObject)x, name));
  PetscCall(VecGetArray(x, &xa));
  for (PetscInt i = 0; i < n * bs; i++) xa[i] = a[i];
  PetscCall(VecRestoreArray(x, &xa));
  PetscCall(VecView(x, v));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

/* The first six columns of a saved element or member: joint, kt, kn, mu, n0, type */
static void PutRow(const JRElements *el, PetscInt e, PetscReal r[])
{
  r[0] = el->joint[e];
  r[1] = el->kt[e];
  r[2] = el->kn[e];
  r[3] = el->mu[e];
  r[4] = el->n0[e];
  r[5] = el->type[e];
}

static void GetRow(JRElements *el, PetscInt e, const PetscReal r[])
{
  el->joint[e] = (PetscInt)r[0];
  el->kt[e]    = r[1];
  el->kn[e]    = r[2];
  el->mu[e]    = r[3];
  el->n0[e]    = r[4];
}

#define JR_ROM_EL  6  /* joint, kt, kn, mu, n0, type */
#define JR_ROM_MEM 24 /* joint, kt, kn, mu, n0, type, vdof_a[3], vdof_b[3], tdir[3], ndir[3], x_A[3], x_B[3] */

/*
  JRROMSave - write a reduced model (elements with members) to an HDF5 file: /rom/elements (joint, kt, kn, mu, n0,
  type per element), /rom/members (joint, kt, kn, mu, n0, type, the 6 DOFs, t, n and the nodes' coordinates per
  member; the DOFs in the model's natural order, JRModelDOFsToNatural, so that the file reads back on any number of
  ranks), attributes njoints, types, stiffness_correction, joint_motion (JRJointMotions[jmotion]). Written by rank 0
  to a temporary file, then renamed.
*/
PetscErrorCode JRROMSave(JRModel model, const JRElements *rom, PetscReal corr, PetscInt jmotion, const char file[])
{
  MPI_Comm          comm;
  PetscMPIInt       rank;
  const JRElements *mem = rom->members;
  PetscReal        *xc;
  PetscInt         *na, *nb;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetComm(model, &comm));
  PetscCheck(mem && rom->joint, comm, PETSC_ERR_ARG_WRONG, "-rom_save: only a second-reduction model (-rom_elements m) is saved");
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscMalloc1(6 * mem->n, &xc));
  PetscCall(MemberCoordinates(model, mem, xc));
  PetscCall(PetscMalloc2(3 * mem->n, &na, 3 * mem->n, &nb));
  PetscCall(JRModelDOFsToNatural(model, 3 * mem->n, mem->vdof_a, na)); /* the same on any number of ranks */
  PetscCall(JRModelDOFsToNatural(model, 3 * mem->n, mem->vdof_b, nb));
  if (!rank) {
    PetscViewer v;
    char        tmp[PETSC_MAX_PATH_LEN + 32];
    PetscReal  *a;
    PetscInt    nj = rom->njoints;
    PetscCall(JRFileTempName(PETSC_COMM_SELF, file, tmp, sizeof(tmp)));
    PetscCall(PetscViewerHDF5Open(PETSC_COMM_SELF, tmp, FILE_MODE_WRITE, &v));
    PetscCall(PetscViewerHDF5PushGroup(v, "/rom"));
    PetscCall(PetscMalloc1(JR_ROM_MEM * PetscMax(mem->n, rom->n), &a));
    for (PetscInt e = 0; e < rom->n; e++) {
      PutRow(rom, e, a + JR_ROM_EL * e);
    }
    PetscCall(WriteSeq(v, "elements", rom->n, JR_ROM_EL, a));
    for (PetscInt e = 0; e < mem->n; e++) {
      PetscReal *r = a + JR_ROM_MEM * e;
      PutRow(mem, e, r);
      for (PetscInt c = 0; c < 3; c++) {
        r[6 + c]  = na[3 * e + c];
        r[9 + c]  = nb[3 * e + c];
        r[12 + c] = mem->tdir[3 * e + c];
        r[15 + c] = mem->ndir[3 * e + c];
        r[18 + c] = xc[6 * e + c];
        r[21 + c] = xc[6 * e + 3 + c];
      }
    }
    PetscCall(WriteSeq(v, "members", mem->n, JR_ROM_MEM, a));
    if (rom->pos && mem->pos) { /* -rom_joint_motion linear, mode: the elements' points, then the members' */
      PetscReal *p;
      PetscCall(PetscMalloc1(3 * (rom->n + mem->n), &p));
      PetscCall(PetscArraycpy(p, rom->pos, 3 * rom->n));
      PetscCall(PetscArraycpy(p + 3 * rom->n, mem->pos, 3 * mem->n));
      PetscCall(WriteSeq(v, "positions", rom->n + mem->n, 3, p));
      if (rom->phi && mem->phi) { /* mode: their stuck-mode coordinates likewise */
        PetscCall(PetscArraycpy(p, rom->phi, 2 * rom->n));
        PetscCall(PetscArraycpy(p + 2 * rom->n, mem->phi, 2 * mem->n));
        PetscCall(WriteSeq(v, "mode_coordinates", rom->n + mem->n, 2, p));
      }
      PetscCall(PetscFree(p));
    }
    if (rom->phir && mem->phir) { /* released modes (shapes, or mode with them): their coordinates in them likewise */
      PetscReal *p;
      PetscCall(PetscMalloc1(JR_NREL * (rom->n + mem->n), &p));
      PetscCall(PetscArraycpy(p, rom->phir, JR_NREL * rom->n));
      PetscCall(PetscArraycpy(p + JR_NREL * rom->n, mem->phir, JR_NREL * mem->n));
      PetscCall(WriteSeq(v, "released_coordinates", rom->n + mem->n, JR_NREL, p));
      PetscCall(PetscFree(p));
    }
    PetscCall(PetscViewerHDF5WriteAttribute(v, "elements", "njoints", PETSC_INT, &nj));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "elements", "element_type", PETSC_STRING, rom->typename[0]));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "members", "element_type", PETSC_STRING, mem->typename[0]));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "members", "dof_order", PETSC_STRING, "natural"));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "elements", "stiffness_correction", PETSC_REAL, &corr));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "elements", "joint_motion", PETSC_STRING, JRJointMotions[jmotion]));
    PetscCall(PetscViewerHDF5PopGroup(v));
    PetscCall(PetscViewerDestroy(&v));
    PetscCall(PetscFree(a));
    PetscCall(JRFileRename(PETSC_COMM_SELF, tmp, file));
  }
  PetscCallMPI(MPI_Barrier(comm));
  PetscCall(PetscFree(xc));
  PetscCall(PetscFree2(na, nb));
  PetscCall(PetscPrintf(comm, "rom: saved %" PetscInt_FMT " elements in %" PetscInt_FMT " joints (%" PetscInt_FMT " members) to %s\n", rom->n, rom->njoints, mem->n, file));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadSeq(PetscViewer v, const char file[], const char name[], PetscInt bs, PetscInt *n, PetscReal **a)
{
  Vec                x;
  const PetscScalar *xa;
  PetscInt           len;
  PetscBool          has;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5HasDataset(v, name, &has));
  PetscCheck(has, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: no dataset /rom/%s (not a reduced model written by -rom_save)", file, name);
  PetscCall(VecCreate(PETSC_COMM_SELF, &x));
  PetscCall(VecSetBlockSize(x, bs));
  PetscCall(PetscObjectSetName((PetscObject)x, name));
  PetscCall(VecLoad(x, v));
  PetscCall(VecGetSize(x, &len));
  PetscCheck(len % bs == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: /rom/%s has %" PetscInt_FMT " values, not rows of %" PetscInt_FMT, file, name, len, bs);
  *n = len / bs;
  PetscCall(PetscMalloc1(len, a));
  PetscCall(VecGetArrayRead(x, &xa));
  for (PetscInt i = 0; i < len; i++) {
    (*a)[i] = PetscRealPart(xa[i]);
    PetscCheck(!PetscIsInfOrNanReal((*a)[i]), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: /rom/%s row %" PetscInt_FMT " holds %g, not a finite number", file, name, i / bs + 1, (double)(*a)[i]);
  }
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

/* A file written by JRROMSave, as read (every rank) */
typedef struct {
  const char *file;
  PetscInt    ne, nmem, nj, npos, nphi, nphir;
  PetscReal  *el, *mem;        /* rows of JR_ROM_EL and JR_ROM_MEM numbers */
  PetscReal  *pos, *phi, *phir; /* rows of 3, 2 and JR_NREL, one per element then one per member (NULL: not in the file) */
  char       *ty, *mty;  /* the elements' and the members' type */
  char       *jm;        /* the joint motion that saved it (NULL: the file does not say) */
  PetscReal   corr;      /* the stiffness correction (1 if the file has none) */
  PetscBool   natural;   /* the members' DOFs in the model's natural order (else in the DOFs of the ranks that wrote it) */
} ROMFile;

/* Every dataset and attribute of the file; the element type and the counts checked */
static PetscErrorCode ROMFileRead(MPI_Comm comm, const char file[], ROMFile *f)
{
  PetscViewer v;
  PetscBool   exists, haspos, hasphi, hasphir;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(f, sizeof(*f)));
  f->file = file;
  PetscCall(PetscTestFile(file, 'r', &exists));
  PetscCheck(exists, comm, PETSC_ERR_FILE_OPEN, "-rom_load %s: no such file (write one with -rom_save)", file);
  {
    char what[PETSC_MAX_PATH_LEN + 32];
    PetscCall(PetscSNPrintf(what, sizeof(what), "-rom_load %s", file));
    PetscCall(JRErrorContextPush(what));
    PetscCall(PetscViewerHDF5Open(PETSC_COMM_SELF, file, FILE_MODE_READ, &v));
    PetscCall(JRErrorContextPop());
  }
  PetscCall(PetscViewerHDF5PushGroup(v, "/rom"));
  PetscCall(ReadSeq(v, file, "elements", JR_ROM_EL, &f->ne, &f->el));
  PetscCall(ReadSeq(v, file, "members", JR_ROM_MEM, &f->nmem, &f->mem));
  PetscCall(PetscViewerHDF5HasDataset(v, "positions", &haspos));
  if (haspos) PetscCall(ReadSeq(v, file, "positions", 3, &f->npos, &f->pos));
  PetscCall(PetscViewerHDF5HasDataset(v, "mode_coordinates", &hasphi));
  if (hasphi) PetscCall(ReadSeq(v, file, "mode_coordinates", 2, &f->nphi, &f->phi));
  PetscCall(PetscViewerHDF5HasDataset(v, "released_coordinates", &hasphir));
  if (hasphir) PetscCall(ReadSeq(v, file, "released_coordinates", JR_NREL, &f->nphir, &f->phir));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "elements", "njoints", PETSC_INT, NULL, &f->nj));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "elements", "element_type", PETSC_STRING, NULL, &f->ty));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "members", "element_type", PETSC_STRING, NULL, &f->mty));
  {
    PetscBool has;
    PetscCall(PetscViewerHDF5HasAttribute(v, "elements", "joint_motion", &has));
    if (has) PetscCall(PetscViewerHDF5ReadAttribute(v, "elements", "joint_motion", PETSC_STRING, NULL, &f->jm));
  }
  f->corr = 1.0;
  PetscCall(PetscViewerHDF5ReadAttribute(v, "elements", "stiffness_correction", PETSC_REAL, &f->corr, &f->corr));
  PetscCall(PetscViewerHDF5HasAttribute(v, "members", "dof_order", &f->natural));
  if (f->natural) {
    char *order = NULL, got[32];
    PetscCall(PetscViewerHDF5ReadAttribute(v, "members", "dof_order", PETSC_STRING, NULL, &order));
    PetscCall(PetscStrncpy(got, order, sizeof(got)));
    PetscCall(PetscFree(order));
    PetscCheck(!strcmp(got, "natural"), comm, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: DOF order '%s', not natural (a file of another program?)", file, got);
  }
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerDestroy(&v));
  PetscCheck(!strcmp(f->ty, JRCONTACTJENKINS) || !strcmp(f->ty, JRCONTACTJENKINSNV), comm, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: element type '%s' (jenkins or jenkins_nv)", file, f->ty);
  PetscCheck(f->nj > 0 && f->ne > 0 && f->nmem > 0, comm, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: %" PetscInt_FMT " joints, %" PetscInt_FMT " elements, %" PetscInt_FMT " members: an empty model", file, f->nj, f->ne, f->nmem);
  PetscFunctionReturn(0);
}

static PetscErrorCode ROMFileDestroy(ROMFile *f)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(f->el));
  PetscCall(PetscFree(f->mem));
  PetscCall(PetscFree(f->pos));
  PetscCall(PetscFree(f->phi));
  PetscCall(PetscFree(f->phir));
  PetscCall(PetscFree(f->ty));
  PetscCall(PetscFree(f->mty));
  PetscCall(PetscFree(f->jm));
  PetscFunctionReturn(0);
}

/* The file's elements, each on one of its joints with kt, mu > 0 */
static PetscErrorCode ROMFileElements(MPI_Comm comm, const ROMFile *f, JRElements *rom)
{
  const PetscInt nj = f->nj;

  PetscFunctionBeginUser;
  PetscCall(JRROMElementsSetUp(rom, f->ne, f->ty, PETSC_FALSE));
  rom->njoints = nj;
  for (PetscInt e = 0; e < f->ne; e++) {
    GetRow(rom, e, f->el + JR_ROM_EL * e);
    PetscCheck(rom->joint[e] >= 0 && rom->joint[e] < nj && rom->kt[e] > 0 && rom->mu[e] > 0, comm, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: element %" PetscInt_FMT " has joint %" PetscInt_FMT " (0..%" PetscInt_FMT "), kt %g, mu %g: not a valid element", f->file, e, rom->joint[e], nj - 1, (double)rom->kt[e], (double)rom->mu[e]);
  }
  PetscFunctionReturn(0);
}

/* The file's members, each on one of its joints and between two of the model's DOFs */
static PetscErrorCode ROMFileMembers(JRModel model, const ROMFile *f, JRElements **members)
{
  MPI_Comm    comm;
  PetscInt    ndof;
  JRElements *mem;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetComm(model, &comm));
  PetscCall(JRModelGetNumDofs(model, &ndof));
  PetscCall(PetscNew(&mem));
  PetscCall(JRROMElementsSetUp(mem, f->nmem, f->mty, PETSC_TRUE));
  mem->njoints = f->nj;
  if (f->natural) PetscCall(JRModelDOFsFromNatural(model, 0, NULL, NULL)); /* its tables, on every rank */
  for (PetscInt e = 0; e < f->nmem; e++) {
    const PetscReal *r = f->mem + JR_ROM_MEM * e;
    GetRow(mem, e, r);
    PetscCheck(mem->joint[e] >= 0 && mem->joint[e] < f->nj, comm, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: member %" PetscInt_FMT " has joint %" PetscInt_FMT ", outside 0..%" PetscInt_FMT, f->file, e, mem->joint[e], f->nj - 1);
    for (PetscInt c = 0; c < 3; c++) {
      mem->vdof_a[3 * e + c] = (PetscInt)r[6 + c];
      mem->vdof_b[3 * e + c] = (PetscInt)r[9 + c];
      mem->tdir[3 * e + c]   = r[12 + c];
      mem->ndir[3 * e + c]   = r[15 + c];
    }
    if (f->natural) { /* to this run's DOFs (numbers out of range stay, and are refused below) */
      PetscCall(JRModelDOFsFromNatural(model, 3, mem->vdof_a + 3 * e, mem->vdof_a + 3 * e));
      PetscCall(JRModelDOFsFromNatural(model, 3, mem->vdof_b + 3 * e, mem->vdof_b + 3 * e));
    }
    for (PetscInt c = 0; c < 3; c++) {
      PetscCheck(mem->vdof_a[3 * e + c] >= 0 && mem->vdof_a[3 * e + c] < ndof && mem->vdof_b[3 * e + c] >= 0 && mem->vdof_b[3 * e + c] < ndof, comm, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: member %" PetscInt_FMT " has DOFs outside the model's 0..%" PetscInt_FMT ": the file is for another mesh", f->file, e, ndof - 1);
    }
  }
  *members = mem;
  PetscFunctionReturn(0);
}

/* The points of the elements and members, if the file has them: positions (-rom_joint_motion linear or mode) and
   stuck-mode coordinates (mode) */
static PetscErrorCode ROMFilePoints(MPI_Comm comm, const ROMFile *f, JRElements *rom, JRElements *mem)
{
  const PetscInt ne = f->ne, nmem = f->nmem;

  PetscFunctionBeginUser;
  if (f->pos) { /* a model reduced with -rom_joint_motion linear: the points where its elements and members sit */
    PetscCheck(f->npos == ne + nmem, comm, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: /rom/positions has %" PetscInt_FMT " points, not one per element and member (%" PetscInt_FMT ")", f->file, f->npos, ne + nmem);
    PetscCall(PetscMalloc1(3 * ne, &rom->pos));
    PetscCall(PetscMalloc1(3 * nmem, &mem->pos));
    PetscCall(PetscArraycpy(rom->pos, f->pos, 3 * ne));
    PetscCall(PetscArraycpy(mem->pos, f->pos + 3 * ne, 3 * nmem));
  }
  if (f->phi) { /* reduced with -rom_joint_motion mode: their coordinates in the stuck mode of interest */
    PetscCheck(f->pos && f->nphi == ne + nmem, comm, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: /rom/mode_coordinates has %" PetscInt_FMT " rows, not one per element and member (%" PetscInt_FMT ") with /rom/positions", f->file, f->nphi, ne + nmem);
    PetscCall(PetscMalloc1(2 * ne, &rom->phi));
    PetscCall(PetscMalloc1(2 * nmem, &mem->phi));
    PetscCall(PetscArraycpy(rom->phi, f->phi, 2 * ne));
    PetscCall(PetscArraycpy(mem->phi, f->phi + 2 * ne, 2 * nmem));
  }
  if (f->phir) { /* reduced with released modes: their coordinates in them */
    PetscCheck(f->phi && f->nphir == ne + nmem, comm, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: /rom/released_coordinates has %" PetscInt_FMT " rows, not one per element and member (%" PetscInt_FMT ") with /rom/mode_coordinates", f->file, f->nphir, ne + nmem);
    PetscCall(PetscMalloc1(JR_NREL * ne, &rom->phir));
    PetscCall(PetscMalloc1(JR_NREL * nmem, &mem->phir));
    PetscCall(PetscArraycpy(rom->phir, f->phir, JR_NREL * ne));
    PetscCall(PetscArraycpy(mem->phir, f->phir + JR_NREL * ne, JR_NREL * nmem));
  }
  PetscFunctionReturn(0);
}

/* Every member's nodes where the file puts them, within 1e-9 of the model's size (collective) */
static PetscErrorCode ROMFileCheckNodes(JRModel model, const ROMFile *f, const JRElements *mem)
{
  MPI_Comm   comm;
  PetscReal *xc, lo[3], hi[3], size = 0, worst = 0;
  PetscInt   bad = -1;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetComm(model, &comm));
  PetscCall(PetscMalloc1(6 * f->nmem, &xc));
  PetscCall(MemberCoordinates(model, mem, xc));
  PetscCall(JRModelGetBoundingBox(model, lo, hi));
  for (PetscInt c = 0; c < 3; c++) size = PetscMax(size, hi[c] - lo[c]);
  for (PetscInt e = 0; e < f->nmem; e++)
    for (PetscInt c = 0; c < 3; c++) {
      const PetscReal da = PetscAbsReal(xc[6 * e + c] - f->mem[JR_ROM_MEM * e + 18 + c]), db = PetscAbsReal(xc[6 * e + 3 + c] - f->mem[JR_ROM_MEM * e + 21 + c]);
      if (PetscMax(da, db) > worst) {
        worst = PetscMax(da, db);
        bad   = e;
      }
    }
  PetscCheck(worst <= 1e-9 * size, comm, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: member %" PetscInt_FMT "'s nodes are %g m from where the file puts them: the file is for another mesh%s", f->file, bad, (double)worst, f->natural ? "" : " or partition (an older file, in the DOFs of the ranks that wrote it: run on as many ranks)");
  PetscCall(PetscFree(xc));
  PetscFunctionReturn(0);
}

/*
  JRROMLoad - read a reduced model written by JRROMSave for this FE model: every member's nodes must be where the
  file says (within 1e-9 of the model's size), else an error naming the file; corr: its stiffness correction; jmotion:
  the joint motion that saved it (-1 if the file does not say).
*/
PetscErrorCode JRROMLoad(JRModel model, const char file[], JRElements *rom, PetscReal *corr, PetscInt *jmotion)
{
  MPI_Comm    comm;
  ROMFile     f;
  JRElements *mem = NULL;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetComm(model, &comm));
  PetscCall(ROMFileRead(comm, file, &f));
  *corr    = f.corr;
  *jmotion = -1;
  for (PetscInt i = 0; f.jm && i <= JR_JOINT_MOTION_SHAPES; i++)
    if (!strcmp(f.jm, JRJointMotions[i])) *jmotion = i;
  PetscCheck(!f.jm || *jmotion >= 0, comm, PETSC_ERR_FILE_UNEXPECTED, "-rom_load %s: joint motion '%s' (mean, linear, mode or shapes)", file, f.jm);
  PetscCall(ROMFileElements(comm, &f, rom));
  PetscCall(ROMFileMembers(model, &f, &mem));
  rom->members = mem;
  PetscCall(ROMFilePoints(comm, &f, rom, mem));
  PetscCall(ROMFileCheckNodes(model, &f, mem));
  PetscCall(PetscPrintf(comm, "rom: loaded %" PetscInt_FMT " %s elements in %" PetscInt_FMT " joints (%" PetscInt_FMT " members, stiffness correction %.6f) from %s\n", f.ne, f.ty, f.nj, f.nmem, (double)*corr, file));
  PetscCall(ROMFileDestroy(&f));
  PetscFunctionReturn(0);
}
