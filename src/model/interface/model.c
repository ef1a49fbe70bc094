/*
   JRModel: the linear structure (stiffness K, mass M, optional viscous damping C, assembled MPIAIJ)
   and its contact elements. Types: matrices (files from any FE code); the built-in FE geometries
   come with later stages.
*/
#include <jointrom/private/modelimpl.h>

PetscFunctionList JRModelList = NULL;

PetscErrorCode JRModelRegister(const char name[], PetscErrorCode (*create)(JRModel))
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListAdd(&JRModelList, name, create));
  PetscFunctionReturn(0);
}

PetscErrorCode JRModelRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (JRModelList) PetscFunctionReturn(0);
  PetscCall(JRModelRegister(JRMODELMATRICES, JRModelCreate_Matrices));
  PetscCall(JRModelRegister(JRMODELBEAM, JRModelCreate_Beam));
  PetscCall(JRModelRegister(JRMODELLAP, JRModelCreate_Lap));
  PetscCall(JRModelRegister(JRMODELBRB, JRModelCreate_BRB));
  PetscCall(JRModelRegister(JRMODELLAP1, JRModelCreate_Lap1));
  PetscCall(JRModelRegister(JRMODELLAP3, JRModelCreate_Lap3));
  PetscCall(JRModelRegister(JRMODELGMSH, JRModelCreate_Gmsh));
  PetscFunctionReturn(0);
}

/* Create an empty model */
PetscErrorCode JRModelCreate(MPI_Comm comm, JRModel *model)
{
  JRModel m;

  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(PetscNew(&m));
  m->comm = comm;
  *model  = m;
  PetscFunctionReturn(0);
}

/* Set the model type (-model_type matrices) */
PetscErrorCode JRModelSetType(JRModel m, JRModelType type)
{
  PetscErrorCode (*create)(JRModel) = NULL;
  PetscBool match;

  PetscFunctionBeginUser;
  PetscCall(JRModelRegisterAll());
  PetscCall(PetscStrcmp(m->type_name, type, &match));
  if (match) PetscFunctionReturn(0);
  PetscCall(PetscFunctionListFind(JRModelList, type, &create));
  PetscCheck(create, m->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown model type '%s' (-model_type): available: matrices, beam, lap, brb, lap1, lap3, gmsh", type);
  if (m->ops->destroy) PetscCall((*m->ops->destroy)(m));
  PetscCall(PetscMemzero(m->ops, sizeof(struct _JRModelOps)));
  m->data = NULL;
  PetscCall(PetscStrncpy(m->type_name, type, sizeof(m->type_name)));
  PetscCall((*create)(m));
  m->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Options: -model_type, -model_view, and the type's own */
/* The model's type name (JRMODELMATRICES, JRMODELBRB, ...; "" before JRModelSetType or JRModelSetFromOptions) */
PetscErrorCode JRModelGetType(JRModel m, JRModelType *type)
{
  PetscFunctionBeginUser;
  *type = m->type_name;
  PetscFunctionReturn(0);
}

PetscErrorCode JRModelSetFromOptions(JRModel m)
{
  char      type[64];
  PetscBool flg;

  PetscFunctionBeginUser;
  PetscCall(JRModelRegisterAll());
  PetscOptionsBegin(m->comm, NULL, "Structural model", "JRModel");
  PetscCall(PetscOptionsFList("-model_type", "Model: matrices (files), beam, lap, brb, lap1, lap3 (built-in FE geometries), gmsh (a .msh file)", "JRModelSetType", JRModelList, m->type_name[0] ? m->type_name : JRMODELMATRICES, type, sizeof(type), &flg));
  if (flg || !m->type_name[0]) PetscCall(JRModelSetType(m, flg ? type : JRMODELMATRICES));
  PetscCall(PetscOptionsBool("-model_view", "Print the model (DOFs, matrices, elements) after set-up", "JRModelView", m->view, &m->view, NULL));
  if (m->ops->setfromoptions) PetscCall((*m->ops->setfromoptions)(m, PetscOptionsObject));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/* Build or load the model; a second call does nothing */
PetscErrorCode JRModelSetUp(JRModel m)
{
  PetscFunctionBeginUser;
  if (m->setupcalled) PetscFunctionReturn(0);
  if (!m->type_name[0]) PetscCall(JRModelSetType(m, JRMODELMATRICES));
  PetscCall(PetscLogEventBegin(JR_ModelLoad, 0, 0, 0, 0));
  PetscCall((*m->ops->setup)(m));
  PetscCall(PetscLogEventEnd(JR_ModelLoad, 0, 0, 0, 0));
  m->setupcalled = PETSC_TRUE;
  if (m->view) PetscCall(JRModelView(m, NULL));
  PetscFunctionReturn(0);
}

/* Give K, M and optionally C directly (type matrices, instead of files); references are kept */
PetscErrorCode JRModelSetMatrices(JRModel m, Mat K, Mat M, Mat C)
{
  PetscInt nk, nm;

  PetscFunctionBeginUser;
  if (!m->type_name[0]) PetscCall(JRModelSetType(m, JRMODELMATRICES));
  PetscCall(MatGetSize(K, &nk, NULL));
  PetscCall(MatGetSize(M, &nm, NULL));
  PetscCheck(nk == nm, m->comm, PETSC_ERR_ARG_SIZ, "K is %" PetscInt_FMT " x %" PetscInt_FMT " but M is %" PetscInt_FMT " x %" PetscInt_FMT, nk, nk, nm, nm);
  PetscCall(PetscObjectReference((PetscObject)K));
  PetscCall(PetscObjectReference((PetscObject)M));
  if (C) PetscCall(PetscObjectReference((PetscObject)C));
  PetscCall(MatDestroy(&m->K));
  PetscCall(MatDestroy(&m->M));
  PetscCall(MatDestroy(&m->C));
  m->K    = K;
  m->M    = M;
  m->C    = C;
  m->ndof = nk;
  PetscFunctionReturn(0);
}

/* Copy an element table into the model (the DOFs are checked at set-up) */
PetscErrorCode JRModelSetElements(JRModel m, const JRElements *el)
{
  PetscFunctionBeginUser;
  PetscCall(JRElementsDestroy(&m->el));
  PetscCall(JRElementsDuplicate(el, &m->el));
  m->el_given = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Stiffness, mass and damping (NULL if none); borrowed references */
PetscErrorCode JRModelGetMatrices(JRModel m, Mat *K, Mat *M, Mat *C)
{
  PetscFunctionBeginUser;
  PetscCall(JRModelSetUp(m));
  if (K) *K = m->K;
  if (M) *M = m->M;
  if (C) *C = m->C;
  PetscFunctionReturn(0);
}

/* The facing node pairs of the contact surfaces (FE models; none for matrices) */
PetscErrorCode JRModelGetPairs(JRModel m, const JRPairs **pairs)
{
  PetscFunctionBeginUser;
  PetscCall(JRModelSetUp(m));
  *pairs = &m->pairs;
  PetscFunctionReturn(0);
}

/* The bolts of an FE model (none for matrices) */
PetscErrorCode JRModelGetBolts(JRModel m, const JRBolts **bolts)
{
  PetscFunctionBeginUser;
  PetscCall(JRModelSetUp(m));
  *bolts = &m->bolts;
  PetscFunctionReturn(0);
}

/* A new vector with the coordinates [m] of each DOF's node, laid out like the displacements (FE models) */
PetscErrorCode JRModelGetCoordinates(JRModel m, Vec *X)
{
  PetscFunctionBeginUser;
  PetscCall(JRModelSetUp(m));
  PetscCheck(m->ops->coordinates, m->comm, PETSC_ERR_SUP, "Model type %s has no node coordinates (an FE model has)", m->type_name);
  PetscCall((*m->ops->coordinates)(m, X));
  PetscFunctionReturn(0);
}

/*
  JRModelGetNaturalOrdering - the position of each DOF this rank owns (in the order of K's rows) in an order of all
  DOFs that does not depend on the number of ranks: NULL where the DOFs' own numbering does not (a matrices model).
  An FE model's DOFs are numbered by the partition; in this order (its mesh points as built, then the components) a
  vector written on some ranks reads back on others (-modes_save, -rom_save).
*/
PetscErrorCode JRModelGetNaturalOrdering(JRModel m, IS *nat)
{
  PetscFunctionBeginUser;
  PetscCall(JRModelSetUp(m));
  *nat = m->nat;
  PetscFunctionReturn(0);
}

/* Every DOF's natural position and its inverse, on every rank (m->g2n, m->n2g), from m->nat */
static PetscErrorCode NaturalTables(JRModel m)
{
  PetscInt        nloc, N;
  const PetscInt *idx;
  PetscMPIInt     size, nl, *cnt, *dsp;

  PetscFunctionBeginUser;
  if (m->g2n || !m->nat) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_size(m->comm, &size));
  PetscCall(ISGetLocalSize(m->nat, &nloc));
  PetscCall(ISGetSize(m->nat, &N));
  PetscCall(PetscMPIIntCast(nloc, &nl));
  PetscCall(PetscMalloc2(size, &cnt, size + 1, &dsp));
  PetscCallMPI(MPI_Allgather(&nl, 1, MPI_INT, cnt, 1, MPI_INT, m->comm));
  dsp[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) dsp[r + 1] = dsp[r] + cnt[r];
  PetscCall(PetscMalloc2(N + 1, &m->g2n, N + 1, &m->n2g));
  PetscCall(ISGetIndices(m->nat, &idx));
  PetscCallMPI(MPI_Allgatherv(idx, nl, MPIU_INT, m->g2n, cnt, dsp, MPIU_INT, m->comm));
  PetscCall(ISRestoreIndices(m->nat, &idx));
  for (PetscInt g = 0; g < N; g++) m->n2g[g] = -1;
  for (PetscInt g = 0; g < N; g++) {
    PetscCheck(m->g2n[g] >= 0 && m->g2n[g] < N && m->n2g[m->g2n[g]] < 0, m->comm, PETSC_ERR_PLIB, "The natural order of the DOFs is not a permutation (DOF %" PetscInt_FMT ")", g);
    m->n2g[m->g2n[g]] = g;
  }
  PetscCall(PetscFree2(cnt, dsp));
  PetscFunctionReturn(0);
}

/* n DOF numbers to their natural positions (tonat) or back, through the tables (none: the same numbers); a number
   outside 0..ndof-1 is returned as it is */
static PetscErrorCode MapDOFs(JRModel m, PetscBool tonat, PetscInt n, const PetscInt in[], PetscInt out[])
{
  const PetscInt *t;

  PetscFunctionBeginUser;
  PetscCall(JRModelSetUp(m));
  PetscCall(NaturalTables(m));
  t = tonat ? m->g2n : m->n2g;
  for (PetscInt i = 0; i < n; i++) out[i] = t && in[i] >= 0 && in[i] < m->ndof ? t[in[i]] : in[i];
  PetscFunctionReturn(0);
}

/* JRModelDOFsToNatural - n DOFs (any, on every rank) to their natural positions (JRModelGetNaturalOrdering); the same
   numbers where the model has no other order. in and out may be the same. Collective. */
PetscErrorCode JRModelDOFsToNatural(JRModel m, PetscInt n, const PetscInt in[], PetscInt out[])
{
  PetscFunctionBeginUser;
  PetscCall(MapDOFs(m, PETSC_TRUE, n, in, out));
  PetscFunctionReturn(0);
}

/* JRModelDOFsFromNatural - the inverse of JRModelDOFsToNatural (a number outside 0..ndof-1 is returned as it is, for
   the caller to refuse). Collective. */
PetscErrorCode JRModelDOFsFromNatural(JRModel m, PetscInt n, const PetscInt in[], PetscInt out[])
{
  PetscFunctionBeginUser;
  PetscCall(MapDOFs(m, PETSC_FALSE, n, in, out));
  PetscFunctionReturn(0);
}

PetscErrorCode JRModelGetComm(JRModel m, MPI_Comm *comm)
{
  PetscFunctionBeginUser;
  *comm = m->comm;
  PetscFunctionReturn(0);
}

/* The DMPlex of an FE model (NULL for matrices) */
PetscErrorCode JRModelGetDM(JRModel m, DM *dm)
{
  PetscFunctionBeginUser;
  PetscCall(JRModelSetUp(m));
  *dm = m->dm;
  PetscFunctionReturn(0);
}

/* Total mass from M [kg] and density x volume [kg] (equal for an FE model; mass twice for matrices) */
PetscErrorCode JRModelGetMass(JRModel m, PetscReal *mass, PetscReal *rhov)
{
  PetscFunctionBeginUser;
  PetscCall(JRModelSetUp(m));
  if (mass) *mass = m->mass;
  if (rhov) *rhov = m->volume_mass;
  PetscFunctionReturn(0);
}

/* The rigid-body motions of a free (unsupported) FE model: n = 6 vectors (translations x, y, z, rotations
   about x, y, z through the centroid) created here; n = 0 when the model has none (supported, or no node
   coordinates: matrices) */
PetscErrorCode JRModelGetRigidBasis(JRModel m, PetscInt *n, Vec rb[6])
{
  PetscFunctionBeginUser;
  PetscCall(JRModelSetUp(m));
  *n = 0;
  if (m->ops->rigidbasis) PetscCall((*m->ops->rigidbasis)(m, n, rb));
  PetscFunctionReturn(0);
}

PetscErrorCode JRModelGetNumDofs(JRModel m, PetscInt *n)
{
  PetscFunctionBeginUser;
  PetscCall(JRModelSetUp(m));
  *n = m->ndof;
  PetscFunctionReturn(0);
}

PetscErrorCode JRModelGetElements(JRModel m, const JRElements **el)
{
  PetscFunctionBeginUser;
  PetscCall(JRModelSetUp(m));
  *el = &m->el;
  PetscFunctionReturn(0);
}

/* Print DOFs, matrix sizes, the damping given, and the element counts per type */
PetscErrorCode JRModelView(JRModel m, PetscViewer viewer)
{
  PetscBool iascii;

  PetscFunctionBeginUser;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(m->comm, &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (!iascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "JRModel: type %s, %" PetscInt_FMT " DOFs, viscous damping matrix %s\n", m->type_name, m->ndof, m->C ? "given" : "none"));
  for (PetscInt t = 0; t < m->el.ntypes; t++) {
    PetscInt cnt = 0;
    for (PetscInt e = 0; e < m->el.n; e++) cnt += m->el.type[e] == t;
    PetscCall(PetscViewerASCIIPrintf(viewer, "  elements: %" PetscInt_FMT " %s\n", cnt, m->el.typename[t]));
  }
  if (!m->el.n) PetscCall(PetscViewerASCIIPrintf(viewer, "  elements: none (linear structure)\n"));
  if (m->ops->view) PetscCall((*m->ops->view)(m, viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode JRModelDestroy(JRModel *model)
{
  JRModel m = *model;

  PetscFunctionBeginUser;
  if (!m) PetscFunctionReturn(0);
  if (m->ops->destroy) PetscCall((*m->ops->destroy)(m));
  PetscCall(MatDestroy(&m->K));
  PetscCall(MatDestroy(&m->M));
  PetscCall(MatDestroy(&m->C));
  PetscCall(JRElementsDestroy(&m->el));
  PetscCall(JRPairsDestroy(&m->pairs));
  PetscCall(JRBoltsDestroy(&m->bolts));
  PetscCall(DMDestroy(&m->dm));
  PetscCall(ISDestroy(&m->nat));
  PetscCall(PetscFree2(m->g2n, m->n2g));
  PetscCall(PetscFree(m));
  *model = NULL;
  PetscFunctionReturn(0);
}
