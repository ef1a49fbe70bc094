/*
   -model_type gmsh -model_file x.msh: a mesh from Gmsh (format 2 or 4, ASCII or binary, hexahedra),
   read by DMPlex with the physical groups as named labels. Required physical surfaces: contact_a and
   contact_b, the two contact surfaces (separate mesh entities whose nodes face each other); optional
   bolt1_head, bolt1_nut, bolt2_head, ...: the washer footprints a bolt is tied to (-model_bolt_diameter).
*/
#include <jointrom/private/feimpl.h>

/* copy every point of the named label into our label with value val; returns how many */
static PetscErrorCode CopyNamedLabel(DM dm, const char *name, const char *to, PetscInt val, PetscInt *count)
{
  DMLabel  l;
  PetscInt nloc = 0;
  MPI_Comm comm;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCall(DMGetLabel(dm, name, &l));
  if (l) {
    IS              vals;
    PetscInt        nv;
    const PetscInt *v;
    PetscCall(DMLabelGetValueIS(l, &vals));
    PetscCall(ISGetLocalSize(vals, &nv));
    PetscCall(ISGetIndices(vals, &v));
    for (PetscInt i = 0; i < nv; i++) {
      IS              pts;
      PetscInt        np;
      const PetscInt *p;
      PetscCall(DMLabelGetStratumIS(l, v[i], &pts));
      if (!pts) continue;
      PetscCall(ISGetLocalSize(pts, &np));
      PetscCall(ISGetIndices(pts, &p));
      for (PetscInt k = 0; k < np; k++) PetscCall(DMSetLabelValue(dm, to, p[k], val));
      nloc += np;
      PetscCall(ISRestoreIndices(pts, &p));
      PetscCall(ISDestroy(&pts));
    }
    PetscCall(ISRestoreIndices(vals, &v));
    PetscCall(ISDestroy(&vals));
  }
  PetscCallMPI(MPI_Allreduce(&nloc, count, 1, MPIU_INT, MPI_SUM, comm));
  PetscFunctionReturn(0);
}

PetscErrorCode JRFEGeometryGmsh(MPI_Comm comm, Model_FE *fe, DM *dm)
{
  PetscBool ok, given;
  PetscInt  na, nb, cs, ce;

  PetscFunctionBeginUser;
  PetscCheck(fe->file[0], comm, PETSC_ERR_USER_INPUT, "-model_type gmsh needs -model_file FILE.msh");
  PetscCall(PetscTestFile(fe->file, 'r', &ok));
  PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "Cannot open the Gmsh file %s (-model_file)", fe->file);
  PetscCall(PetscOptionsHasName(NULL, NULL, "-dm_plex_gmsh_use_regions", &given)); /* PETSc's reader takes the physical
                                                                                      groups as labels only from its options: set for the read, then cleared */
  if (!given) PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_use_regions", "true"));
  {
    char        what[PETSC_MAX_PATH_LEN + 64];
    PetscMPIInt size, rank;
    PetscCall(PetscSNPrintf(what, sizeof(what), "the Gmsh file %s (-model_file)", fe->file));
    PetscCall(JRErrorContextPush(what));
    PetscCallMPI(MPI_Comm_size(comm, &size));
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (size > 1) { /* rank 0 reads the file for every rank: a bad one read there first, alone, so that every rank
                       stops with its error */
      char msg[512] = "";
      if (!rank) {
        DM             trial = NULL;
        PetscErrorCode ierr;
        PetscCall(JRErrorCatchPush());
        ierr = DMPlexCreateFromFile(PETSC_COMM_SELF, fe->file, "jointrom", PETSC_FALSE, &trial);
        PetscCall(JRErrorCatchPop(msg, sizeof(msg)));
        if (!ierr) PetscCall(DMDestroy(&trial));
        else if (!msg[0]) PetscCall(PetscStrncpy(msg, "cannot be read", sizeof(msg)));
      }
      PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm));
      PetscCheck(!msg[0], comm, PETSC_ERR_FILE_UNEXPECTED, "%s", msg);
    }
    PetscCall(DMPlexCreateFromFile(comm, fe->file, "jointrom", PETSC_TRUE, dm));
    PetscCall(JRErrorContextPop());
    if (!given) PetscCall(PetscOptionsClearValue(NULL, "-dm_plex_gmsh_use_regions"));
  }
  PetscCall(DMCreateLabel(*dm, JR_LABEL_BODY));
  PetscCall(DMCreateLabel(*dm, JR_LABEL_CONTACT));
  PetscCall(DMCreateLabel(*dm, JR_LABEL_BOLT));
  PetscCall(DMCreateLabel(*dm, JR_LABEL_CLAMP));
  PetscCall(DMPlexGetHeightStratum(*dm, 0, &cs, &ce));
  for (PetscInt c = cs; c < ce; c++) PetscCall(DMSetLabelValue(*dm, JR_LABEL_BODY, c, 1));
  PetscCall(CopyNamedLabel(*dm, "contact_a", JR_LABEL_CONTACT, 1, &na));
  PetscCall(CopyNamedLabel(*dm, "contact_b", JR_LABEL_CONTACT, 2, &nb));
  PetscCheck(na > 0, comm, PETSC_ERR_FILE_UNEXPECTED, "Gmsh file %s has no physical group 'contact_a' (the first contact surface)", fe->file);
  PetscCheck(nb > 0, comm, PETSC_ERR_FILE_UNEXPECTED, "Gmsh file %s has no physical group 'contact_b' (the second contact surface)", fe->file);
  PetscCall(CopyNamedLabel(*dm, "clamp", JR_LABEL_CLAMP, 1, &na));
  fe->nbolts = 0;
  for (PetscInt i = 0;; i++) {
    char     head[32], nut[32];
    PetscInt nh, nn;
    PetscCall(PetscSNPrintf(head, sizeof(head), "bolt%" PetscInt_FMT "_head", i + 1));
    PetscCall(PetscSNPrintf(nut, sizeof(nut), "bolt%" PetscInt_FMT "_nut", i + 1));
    PetscCall(CopyNamedLabel(*dm, head, JR_LABEL_BOLT, 2 * i + 1, &nh));
    PetscCall(CopyNamedLabel(*dm, nut, JR_LABEL_BOLT, 2 * i + 2, &nn));
    if (!nh && !nn) break;
    PetscCheck(nh && nn, comm, PETSC_ERR_FILE_UNEXPECTED, "Gmsh file %s: bolt %" PetscInt_FMT " needs both physical groups %s and %s", fe->file, i + 1, head, nut);
    fe->nbolts++;
  }
  PetscCall(PetscFree(fe->bolt));
  PetscCall(PetscCalloc1(PetscMax(fe->nbolts, 1), &fe->bolt));
  for (PetscInt i = 0; i < fe->nbolts; i++) fe->bolt[i].d = fe->dbolt;
  fe->lap = PETSC_TRUE;
  PetscCall(JRFEDistribute(fe, dm));
  PetscFunctionReturn(0);
}
