/*
   JRModes in files: -modes_save writes the modes (HDF5) with the node coordinates and the signature of the stuck
   springs they were computed with; -modes_load reads them back instead of solving, after checking both.
*/
#include <jointrom/private/modelimpl.h>
#include <petscviewerhdf5.h>
#include <petscblaslapack.h>

/* The scatter between the DOF layout (x) and a vector in the natural order (*y, PETSc's layout of its size): NULL
   where the modes have no other order (md->nat NULL) */
static PetscErrorCode NaturalScatter(JRModes md, Vec x, Vec *y, VecScatter *sc)
{
  PetscInt N, n, rs;
  IS       ig;

  PetscFunctionBeginUser;
  *y  = NULL;
  *sc = NULL;
  if (!md->nat) PetscFunctionReturn(0); /* none, or the DOFs' own */
  PetscCall(VecGetSize(x, &N));
  PetscCall(VecGetLocalSize(x, &n));
  PetscCall(VecGetOwnershipRange(x, &rs, NULL));
  PetscCall(VecCreateMPI(md->comm, PETSC_DECIDE, N, y));
  PetscCall(ISCreateStride(md->comm, n, rs, 1, &ig));
  PetscCall(VecScatterCreate(x, ig, *y, md->nat, sc));
  PetscCall(ISDestroy(&ig));
  PetscFunctionReturn(0);
}

/* x written (load: read) under its name, in the natural order where there is one (sc, y from NaturalScatter) */
static PetscErrorCode NaturalIO(PetscViewer v, Vec x, Vec y, VecScatter sc, PetscBool load)
{
  const char *name;

  PetscFunctionBeginUser;
  if (!sc) {
    PetscCall(load ? VecLoad(x, v) : VecView(x, v));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscObjectGetName((PetscObject)x, &name));
  PetscCall(PetscObjectSetName((PetscObject)y, name));
  if (load) PetscCall(VecLoad(y, v));
  PetscCall(VecScatterBegin(sc, load ? y : x, load ? x : y, INSERT_VALUES, load ? SCATTER_REVERSE : SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, load ? y : x, load ? x : y, INSERT_VALUES, load ? SCATTER_REVERSE : SCATTER_FORWARD));
  if (!load) PetscCall(VecView(y, v));
  PetscFunctionReturn(0);
}

/* Write omega^2 and the modes (and the coordinates) to an HDF5 file, through a temporary name: the vectors in the
   natural order of the DOFs (JRModesSetNaturalOrdering), which does not depend on the number of ranks */
PetscErrorCode JRModesSave(JRModes md, const char file[])
{
  PetscViewer v;
  char        tmp[PETSC_MAX_PATH_LEN + 32];
  Vec         lam, y0;
  VecScatter  sc;
  PetscMPIInt rank, size;
  PetscInt    nm = md->nm, hasx = md->X ? 1 : 0;

  PetscFunctionBeginUser;
  PetscCall(NaturalScatter(md, md->phi[0], &y0, &sc));
  PetscCallMPI(MPI_Comm_rank(md->comm, &rank));
  PetscCallMPI(MPI_Comm_size(md->comm, &size));
  PetscCall(JRFileTempName(md->comm, file, tmp, sizeof(tmp)));
  PetscCall(PetscViewerHDF5Open(md->comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(PetscViewerHDF5PushGroup(v, "/jointrom_modes"));
  PetscCall(VecCreateMPI(md->comm, rank ? 0 : nm, nm, &lam));
  PetscCall(PetscObjectSetName((PetscObject)lam, "omega2"));
  if (!rank)
    for (PetscInt i = 0; i < nm; i++) PetscCall(VecSetValue(lam, i, md->lambda[i], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(lam));
  PetscCall(VecAssemblyEnd(lam));
  PetscCall(VecView(lam, v));
  PetscCall(VecDestroy(&lam));
  for (PetscInt i = 0; i < nm; i++) {
    char name[32];
    PetscCall(PetscSNPrintf(name, sizeof(name), "phi_%" PetscInt_FMT, i));
    PetscCall(PetscObjectSetName((PetscObject)md->phi[i], name));
    PetscCall(NaturalIO(v, md->phi[i], y0, sc, PETSC_FALSE));
  }
  if (md->X) { /* a plain copy: a vector of a DMPlex would go to /fields */
    Vec y;
    PetscCall(MatCreateVecs(md->K, &y, NULL));
    PetscCall(VecCopy(md->X, y));
    PetscCall(PetscObjectSetName((PetscObject)y, "coordinates"));
    PetscCall(NaturalIO(v, y, y0, sc, PETSC_FALSE));
    PetscCall(VecDestroy(&y));
  }
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "modes", PETSC_INT, &nm));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "ranks", PETSC_INT, &size));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "has_coordinates", PETSC_INT, &hasx));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "stuck_signature", PETSC_REAL, md->natset ? &md->sig : &md->sigraw));
  if (md->natset) PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "dof_order", PETSC_STRING, "natural"));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "units", PETSC_STRING, md->natset ? "omega2: rad^2/s^2; phi_i: mass-normalised modes over every DOF (kg^-1/2), in the natural order of the DOFs (an FE model's: by mesh point as built, then component; the same on any number of ranks); coordinates: m" : "omega2: rad^2/s^2; phi_i: mass-normalised modes over every DOF (kg^-1/2) in the model's parallel DOF numbering; coordinates: m"));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&y0));
  PetscCall(JRFileRename(md->comm, tmp, file));
  PetscFunctionReturn(0);
}

/*
  JRModesSaveAdaptation - records in the saved mixed basis (-modes_save or the default file, if written) how it was
  adapted to the peaks (the caller's rounds, JRModesEnrich): the rounds made, the vectors added, the last round's
  deformation of the interface by the peaks' loads in units of the springs' stretch, and whether that round added
  nothing. A run that reads the file (-modes_load) then reports them instead of checking the basis against every
  interface pattern, a test that such a basis need not pass (JRModesMix). Collective.
*/
PetscErrorCode JRModesSaveAdaptation(JRModes md, PetscInt rounds, PetscReal deform, PetscBool conv)
{
  PetscViewer v;
  PetscBool   has;
  PetscInt    c = conv ? 1 : 0;

  PetscFunctionBeginUser;
  if (!md->save_mixed[0] || !md->mixed) PetscFunctionReturn(0);
  PetscCall(PetscTestFile(md->save_mixed, 'r', &has));
  if (!has) PetscFunctionReturn(0);
  PetscCall(PetscViewerHDF5Open(md->comm, md->save_mixed, FILE_MODE_APPEND, &v));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "adapt_rounds", PETSC_INT, &rounds));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "adapt_vectors_added", PETSC_INT, &md->nadapt));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "adapt_peak_load_deformation", PETSC_REAL, &deform));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/jointrom_modes", "adapt_converged", PETSC_INT, &c));
  PetscCall(PetscViewerDestroy(&v));
  PetscFunctionReturn(0);
}

/* JRModesGetReadAdaptation - the adaptation recorded in the file read (-modes_load; rounds 0: none recorded) */
PetscErrorCode JRModesGetReadAdaptation(JRModes md, PetscInt *rounds, PetscInt *added, PetscReal *deform, PetscBool *conv)
{
  PetscFunctionBeginUser;
  if (rounds) *rounds = md->load[0] ? md->read_rounds : 0;
  if (added) *added = md->read_added;
  if (deform) *deform = md->read_deform;
  if (conv) *conv = md->load[0] ? md->read_conv : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Read the nev lowest modes from a -modes_save file */
PetscErrorCode JRModesLoad_Private(JRModes md, const char file[])
{
  PetscViewer        v;
  PetscInt           nm = 0, ranks = 0, hasx = 0, n, nf;
  PetscMPIInt        size;
  PetscBool          has, natural = PETSC_FALSE;
  Vec                lam, all, x, y = NULL;
  VecScatter         sc, scn = NULL;
  const PetscScalar *l;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(md->comm, &size));
  PetscCall(PetscTestFile(file, 'r', &has));
  PetscCheck(has, md->comm, PETSC_ERR_FILE_OPEN, "-modes_load %s: cannot read the file", file);
  {
    char what[PETSC_MAX_PATH_LEN + 32];
    PetscCall(PetscSNPrintf(what, sizeof(what), "-modes_load %s", file));
    PetscCall(JRErrorContextPush(what));
    PetscCall(PetscViewerHDF5Open(md->comm, file, FILE_MODE_READ, &v));
    PetscCall(PetscViewerHDF5HasAttribute(v, "/jointrom_modes", "modes", &has));
    PetscCall(JRErrorContextPop());
  }
  PetscCheck(has, md->comm, PETSC_ERR_FILE_UNEXPECTED, "-modes_load %s: not a modes file of this program (no /jointrom_modes; write one with -modes_save)", file);
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "modes", PETSC_INT, NULL, &nm));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "ranks", PETSC_INT, NULL, &ranks));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "has_coordinates", PETSC_INT, NULL, &hasx));
  if (md->load_all) md->nev = nm; /* a mixed basis: every vector of the file */
  PetscCheck(nm >= md->nev, md->comm, PETSC_ERR_FILE_UNEXPECTED, "-modes_load %s holds %" PetscInt_FMT " modes, %" PetscInt_FMT " are asked for (-hbm_modes / -modes_nev)", file, nm, md->nev);
  PetscCall(PetscViewerHDF5HasAttribute(v, "/jointrom_modes", "adapt_rounds", &has)); /* JRModesSaveAdaptation */
  md->read_rounds = md->read_added = 0;
  md->read_deform = -1.0;
  md->read_conv   = PETSC_FALSE;
  if (has) {
    PetscInt c = 0;
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "adapt_rounds", PETSC_INT, NULL, &md->read_rounds));
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "adapt_vectors_added", PETSC_INT, NULL, &md->read_added));
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "adapt_peak_load_deformation", PETSC_REAL, NULL, &md->read_deform));
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "adapt_converged", PETSC_INT, NULL, &c));
    md->read_conv = (PetscBool)(c != 0);
  }
  PetscCall(PetscViewerHDF5HasAttribute(v, "/jointrom_modes", "dof_order", &natural)); /* else in the DOFs of the ranks that wrote it */
  if (natural) {
    char *order = NULL, got[32];
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "dof_order", PETSC_STRING, NULL, &order));
    PetscCall(PetscStrncpy(got, order, sizeof(got)));
    PetscCall(PetscFree(order));
    natural = (PetscBool)!strcmp(got, "natural");
    PetscCheck(natural, md->comm, PETSC_ERR_FILE_UNEXPECTED, "-modes_load %s: DOF order '%s', not natural (a file of another program?)", file, got);
  }
  PetscCheck(natural || ranks == size, md->comm, PETSC_ERR_FILE_UNEXPECTED, "-modes_load %s was written on %" PetscInt_FMT " ranks in their DOF numbering (an older file), this run has %d: run on %" PetscInt_FMT " ranks or recompute the modes", file, ranks, (int)size, ranks);
  {
    PetscReal sig = 0;
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/jointrom_modes", "stuck_signature", PETSC_REAL, NULL, &sig));
    const PetscReal mine = natural ? md->sig : md->sigraw; /* the file's DOF numbers */
    PetscCall(PetscInfo(NULL, "stuck signature: file %.17g, this run %.17g\n", (double)sig, (double)mine));
    PetscCheck(PetscAbsReal(sig - mine) <= 1e-9 * PetscMax(PetscAbsReal(sig), PetscAbsReal(mine)), md->comm, PETSC_ERR_FILE_UNEXPECTED, "-modes_load %s: its modes are of %s, this run needs %s (-hbm_basis, -interface_*, preload): recompute them", file, sig == 0 ? "the free structure" : sig < 0 ? "a mixed basis (stuck + free)" : "a stuck interface", mine == 0 ? "the free structure's" : mine < 0 ? "a mixed basis of this interface" : "those of this stuck interface");
  }
  PetscCall(MatGetSize(md->K, &n, NULL));
  PetscCall(PetscViewerHDF5PushGroup(v, "/jointrom_modes"));
  PetscCall(MatCreateVecs(md->K, &x, NULL));
  PetscCheck(!natural || md->natset, md->comm, PETSC_ERR_ARG_WRONGSTATE, "-modes_load %s: the file is in the natural order of the DOFs, which this run did not set (JRModesSetNaturalOrdering)", file);
  if (natural) PetscCall(NaturalScatter(md, x, &y, &scn));
  if (md->X && hasx) {
    PetscReal d, s;
    PetscCall(PetscObjectSetName((PetscObject)x, "coordinates"));
    PetscCall(NaturalIO(v, x, y, scn, PETSC_TRUE));
    PetscCall(VecAXPY(x, -1.0, md->X));
    PetscCall(VecNorm(x, NORM_INFINITY, &d));
    PetscCall(VecNorm(md->X, NORM_INFINITY, &s));
    PetscCheck(d <= 1e-9 * s, md->comm, PETSC_ERR_FILE_UNEXPECTED, "-modes_load %s: its node coordinates differ from the model's by %g m: it was computed for another mesh", file, (double)d);
  }
  PetscCall(VecCreateMPI(md->comm, PETSC_DECIDE, nm, &lam));
  PetscCall(PetscObjectSetName((PetscObject)lam, "omega2"));
  {
    char what[PETSC_MAX_PATH_LEN + 32];
    PetscCall(PetscSNPrintf(what, sizeof(what), "-modes_load %s", file));
    PetscCall(JRErrorContextPush(what)); /* a library's error on the datasets read below names the file */
  }
  PetscCall(VecLoad(lam, v));
  PetscCall(VecScatterCreateToAll(lam, &sc, &all));
  PetscCall(VecScatterBegin(sc, lam, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, lam, all, INSERT_VALUES, SCATTER_FORWARD));
  md->nm = md->nev;
  PetscCall(PetscMalloc1(md->nm, &md->lambda));
  PetscCall(VecGetArrayRead(all, &l));
  for (PetscInt i = 0; i < md->nm; i++) md->lambda[i] = PetscRealPart(l[i]);
  PetscCall(VecRestoreArrayRead(all, &l));
  for (PetscInt i = 0; i < md->nm; i++) PetscCheck(!PetscIsInfOrNanReal(md->lambda[i]), md->comm, PETSC_ERR_FILE_UNEXPECTED, "mode %" PetscInt_FMT " has omega^2 = %g rad^2/s^2, not a finite number", i + 1, (double)md->lambda[i]);
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&all));
  PetscCall(VecDestroy(&lam));
  PetscCall(VecDuplicateVecs(x, md->nm, &md->phi));
  for (PetscInt i = 0; i < md->nm; i++) {
    char name[32];
    PetscCall(PetscSNPrintf(name, sizeof(name), "phi_%" PetscInt_FMT, i));
    PetscCall(PetscObjectSetName((PetscObject)md->phi[i], name));
    PetscCall(VecGetSize(md->phi[i], &nf));
    PetscCall(NaturalIO(v, md->phi[i], y, scn, PETSC_TRUE));
    {
      PetscReal nrm;
      PetscCall(VecNorm(md->phi[i], NORM_INFINITY, &nrm));
      PetscCheck(!PetscIsInfOrNanReal(nrm), md->comm, PETSC_ERR_FILE_UNEXPECTED, "mode %" PetscInt_FMT " holds a value that is not a finite number", i + 1);
    }
  }
  PetscCall(JRErrorContextPop());
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&y));
  PetscCall(VecScatterDestroy(&scn));
  PetscCall(PetscInfo(NULL, "Read %" PetscInt_FMT " modes of %" PetscInt_FMT " DOFs from %s\n", md->nm, nf, file));
  PetscFunctionReturn(0);
}

/* The default shift, a little below zero (free-free structures have a singular K): -1e-6 |diag K|_1 / |diag M|_1 */
