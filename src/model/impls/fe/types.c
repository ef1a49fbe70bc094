/*
   The FE model types: beam, lap (every dimension an option), and the presets brb (Brake-Reuss beam,
   thesis ch. 4), lap1 (single M8 bolt, thesis 5.2) and lap3 (three M8 bolts, thesis 5.3), and gmsh
   (import). Options take SI units: m, Pa, kg/m^3.

   lap1 and lap3: the thesis gives no drawing. The dimensions here are plausible bench specimens:
     lap1: two steel beams 400 mm long, 25 mm wide, 20 mm high, 50 mm lap, one M8 bolt (hole 9 mm,
           washer 16 mm), E = 190 GPa, nu = 0.32, rho = 7800 kg/m^3 (thesis first bending: 191 Hz);
     lap3: two beams 450 mm long, 30 mm wide, 20 mm high, 100 mm lap, three M8 bolts at 30 mm pitch,
           same steel (thesis first bending: 170 Hz).
*/
#include <jointrom/private/feimpl.h>

typedef enum {
  KIND_BEAM,
  KIND_LAP,
  KIND_GMSH
} Kind;

typedef struct {
  Model_FE fe;
  Kind     kind;
  char     preset[16];
} Model_FEType;

static PetscErrorCode JRModelSetFromOptions_FE(JRModel m, PetscOptionItems *PetscOptionsObject)
{
  Model_FEType *ft = (Model_FEType *)m->data;
  Model_FE     *fe = &ft->fe;

  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Finite-element model (SI units: m, Pa, kg/m^3)");
  PetscCall(PetscOptionsReal("-model_E", "Young's modulus [Pa]", "JRModelSetUp", fe->E, &fe->E, NULL));
  PetscCall(PetscOptionsReal("-model_nu", "Poisson's ratio [-]", "JRModelSetUp", fe->nu, &fe->nu, NULL));
  PetscCall(PetscOptionsReal("-model_rho", "Density [kg/m^3]", "JRModelSetUp", fe->rho, &fe->rho, NULL));
  PetscCall(PetscOptionsInt("-model_fe_order", "Lagrange order on hexahedra (2: 27-node quadratic elements)", "JRModelSetUp", fe->order, &fe->order, NULL));
  PetscCall(PetscOptionsBool("-model_clamp", "Clamp the end x = 0 (a cantilever)", "JRModelSetUp", fe->clamp, &fe->clamp, NULL));
  {
    const char *assm[] = {"jointrom", "petscfe", "Assembly", "", NULL};
    PetscInt    a      = fe->petscfe ? 1 : 0;
    PetscCall(PetscOptionsEList("-model_fe_assembly", "Element integration: jointrom (Q2 kernel, fast) or petscfe (PETSc's generic, slow)", "JRModelSetUp", assm, 2, assm[a], &a, NULL));
    fe->petscfe = a == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  if (ft->kind != KIND_GMSH) PetscCall(PetscOptionsReal("-model_mesh_h", "Element size [m] (over the lap; outside it times -model_mesh_grade)", "JRModelSetUp", fe->h, &fe->h, NULL));
  if (ft->kind != KIND_GMSH) PetscCall(PetscOptionsReal("-model_memory_limit", "Memory the model may need [GiB], estimated from the mesh parameters before the mesh is built (0: what the machine has available)", "JRModelSetUp", fe->memlimit, &fe->memlimit, NULL));
  if (ft->kind == KIND_BEAM) {
    PetscCall(PetscOptionsReal("-model_length", "Beam length along x [m]", "JRModelSetUp", fe->L1, &fe->L1, NULL));
    PetscCall(PetscOptionsReal("-model_width", "Beam width along y [m]", "JRModelSetUp", fe->W, &fe->W, NULL));
    PetscCall(PetscOptionsReal("-model_height", "Beam height along z [m]", "JRModelSetUp", fe->H, &fe->H, NULL));
  }
  if (ft->kind == KIND_LAP) {
    PetscCall(PetscOptionsReal("-model_length_a", "Length of beam A (x from 0) [m]", "JRModelSetUp", fe->L1, &fe->L1, NULL));
    PetscCall(PetscOptionsReal("-model_length_b", "Length of beam B [m]", "JRModelSetUp", fe->L2, &fe->L2, NULL));
    PetscCall(PetscOptionsReal("-model_width", "Width along y [m]", "JRModelSetUp", fe->W, &fe->W, NULL));
    PetscCall(PetscOptionsReal("-model_height", "Height along z [m] (each beam is half as high over the lap)", "JRModelSetUp", fe->H, &fe->H, NULL));
    PetscCall(PetscOptionsReal("-model_lap_length", "Overlap of the two beams [m]", "JRModelSetUp", fe->Llap, &fe->Llap, NULL));
    PetscCall(PetscOptionsInt("-model_nbolts", "Number of bolts, centred in the lap", "JRModelSetUp", fe->nbolts, &fe->nbolts, NULL));
    PetscCall(PetscOptionsReal("-model_bolt_pitch", "Distance between bolts along x [m]", "JRModelSetUp", fe->pitch, &fe->pitch, NULL));
    PetscCall(PetscOptionsReal("-model_hole_diameter", "Bolt hole diameter [m]", "JRModelSetUp", fe->dhole, &fe->dhole, NULL));
    PetscCall(PetscOptionsReal("-model_washer_diameter", "Washer outer diameter [m] (the footprint the bolt is tied to)", "JRModelSetUp", fe->dwasher, &fe->dwasher, NULL));
    PetscCall(PetscOptionsReal("-model_mesh_grade", "Element size outside the lap / inside", "JRModelSetUp", fe->grade, &fe->grade, NULL));
    PetscCall(PetscOptionsReal("-model_mesh_hz", "Element size through the height [m] (0: -model_mesh_h; at least two elements through each beam's half height)", "JRModelSetUp", fe->hz, &fe->hz, NULL));
  }
  if (ft->kind != KIND_BEAM) {
    {
      const char *ties[] = {"distributing", "rigid"};
      PetscInt    t      = fe->rigidtie ? 1 : 0;
      PetscCall(PetscOptionsEList("-model_bolt_tie", "How a bolt end holds its washer footprint: distributing (RBE3-like least-squares fit, the footprint deforms freely) or rigid (the footprint moves as a rigid washer)", "JRModelSetUp", ties, 2, ties[t], &t, NULL));
      fe->rigidtie = t == 1 ? PETSC_TRUE : PETSC_FALSE;
    }
    {
      const char *itf[] = {"free", "tied"};
      PetscInt    t     = fe->tied ? 1 : 0;
      PetscCall(PetscOptionsEList("-model_interface", "The contact interface for the linear model: free (only the bolts hold the parts together, as in the thesis's modal analysis) or tied (every facing pair joined: a stuck interface)", "JRModelSetUp", itf, 2, itf[t], &t, NULL));
      fe->tied = t == 1 ? PETSC_TRUE : PETSC_FALSE;
    }
    PetscCall(PetscOptionsReal("-model_bolt_diameter", "Bolt shank diameter [m]", "JRModelSetUp", fe->dbolt, &fe->dbolt, NULL));
    PetscCall(PetscOptionsReal("-model_pair_tol", "Distance within which two contact nodes face each other [m]", "JRModelSetUp", fe->pairtol, &fe->pairtol, NULL));
    PetscCall(PetscOptionsString("-model_tangent", "Tangential direction of the contact pairs: x (beam axis) or y", "JRModelSetUp", fe->tangent, fe->tangent, sizeof(fe->tangent), NULL));
  }
  if (ft->kind == KIND_GMSH) PetscCall(PetscOptionsString("-model_file", "Gmsh mesh (.msh) with physical groups contact_a, contact_b, bolt<i>_head, bolt<i>_nut", "JRModelSetUp", fe->file, fe->file, sizeof(fe->file), NULL));
  PetscOptionsHeadEnd();
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckPositive(MPI_Comm comm, const char *opt, PetscReal v)
{
  PetscFunctionBeginUser;
  PetscCheck(PetscIsNormalReal(v) && v > 0.0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s %g: must be positive and finite [m]", opt, (double)v);
  PetscFunctionReturn(0);
}

static PetscErrorCode JRModelSetUp_FE(JRModel m)
{
  Model_FEType *ft = (Model_FEType *)m->data;
  Model_FE     *fe = &ft->fe;

  PetscFunctionBeginUser;
  PetscCheck(fe->tangent[0] == 'x' || fe->tangent[0] == 'y', m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_tangent %s: x or y", fe->tangent);
  if (ft->kind != KIND_GMSH) PetscCall(CheckPositive(m->comm, "-model_mesh_h", fe->h));
  PetscCheck(fe->memlimit >= 0 && !PetscIsInfOrNanReal(fe->memlimit), m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_memory_limit %g: a size in GiB, or 0 for the memory available", (double)fe->memlimit);
  PetscCall(DMDestroy(&fe->dm));
  if (ft->kind == KIND_BEAM) {
    PetscCall(CheckPositive(m->comm, "-model_length", fe->L1));
    PetscCall(CheckPositive(m->comm, "-model_width", fe->W));
    PetscCall(CheckPositive(m->comm, "-model_height", fe->H));
    PetscCall(JRFEMeshCheckMemory(m->comm, fe, PETSC_FALSE));
    PetscCall(JRFEGeometryBeam(m->comm, fe, &fe->dm));
  } else if (ft->kind == KIND_LAP) {
    PetscCall(CheckPositive(m->comm, "-model_length_a", fe->L1));
    PetscCall(CheckPositive(m->comm, "-model_length_b", fe->L2));
    PetscCall(CheckPositive(m->comm, "-model_width", fe->W));
    PetscCall(CheckPositive(m->comm, "-model_height", fe->H));
    PetscCall(CheckPositive(m->comm, "-model_lap_length", fe->Llap));
    PetscCall(CheckPositive(m->comm, "-model_bolt_diameter", fe->dbolt));
    PetscCall(CheckPositive(m->comm, "-model_hole_diameter", fe->dhole));
    PetscCall(CheckPositive(m->comm, "-model_washer_diameter", fe->dwasher));
    PetscCall(CheckPositive(m->comm, "-model_mesh_grade", fe->grade));
    PetscCheck(fe->hz >= 0 && !PetscIsInfOrNanReal(fe->hz), m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_mesh_hz %g: an element size in m, or 0 for -model_mesh_h", (double)fe->hz);
    PetscCheck(fe->nbolts >= 0, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_nbolts %" PetscInt_FMT ": must be non-negative", fe->nbolts);
    PetscCheck(fe->nbolts <= 1 || fe->pitch >= fe->dwasher, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_bolt_pitch %g m: the washers (diameter %g m) would overlap", (double)fe->pitch, (double)fe->dwasher);
    PetscCall(JRFEMeshCheckMemory(m->comm, fe, PETSC_TRUE));
    PetscCall(JRFEGeometryLap(m->comm, fe, &fe->dm));
  } else PetscCall(JRFEGeometryGmsh(m->comm, fe, &fe->dm));
  PetscCall(JRFESetUp(m, fe));
  PetscFunctionReturn(0);
}

static PetscErrorCode JRModelView_FE(JRModel m, PetscViewer viewer)
{
  Model_FEType *ft = (Model_FEType *)m->data;
  Model_FE     *fe = &ft->fe;
  PetscInt      cs, ce, nc;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetHeightStratum(fe->dm, 0, &cs, &ce));
  nc = ce - cs;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nc, 1, MPIU_INT, MPI_SUM, m->comm));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  %s: %" PetscInt_FMT " hexahedra, order %" PetscInt_FMT ", %" PetscInt_FMT " nodes, %" PetscInt_FMT " DOFs%s\n", ft->preset, nc, fe->order, fe->nnodes, m->ndof, fe->clamp ? ", end x = 0 clamped" : ", free-free"));
  if (ft->kind != KIND_GMSH) {
    JRFEMeshSize est;
    MatInfo      info;
    PetscCall(JRFEMeshEstimate(fe, ft->kind == KIND_LAP ? PETSC_TRUE : PETSC_FALSE, &est));
    PetscCall(MatGetInfo(m->K, MAT_GLOBAL_SUM, &info));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  estimate before the mesh: %.0f nodes, %.0f nonzeros in K (it has %.0f), %.3g GiB for K and M, %.3g GiB in all with the eigensolver\n", (double)est.nodes, (double)est.nnz, (double)info.nz_used, (double)(est.km / 1073741824.0), (double)(est.total / 1073741824.0)));
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "  material: E %g Pa, nu %g, rho %g kg/m^3; volume %.6g m^3\n", (double)fe->E, (double)fe->nu, (double)fe->rho, (double)fe->volume));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  mass %.9g kg from M, density x volume %.9g kg (relative difference %.1e)\n", (double)m->mass, (double)m->volume_mass, (double)PetscAbsReal(m->mass / m->volume_mass - 1.0)));
  if (fe->lap || ft->kind == KIND_GMSH) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "  contact: %" PetscInt_FMT " nodes on surface A, %" PetscInt_FMT " on B, %" PetscInt_FMT " facing pairs (largest pair distance %.2g m; tangent %s, normal from A to B)\n", fe->ncontact[0], fe->ncontact[1], m->pairs.n, (double)fe->pairgap, fe->tangent));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  interface %s, area %g m^2\n", fe->tied ? "tied (every pair joined by a stiff spring)" : "free (no contact: the bolts hold the parts)", (double)fe->contact_area));
    if (m->pairs.n) PetscCall(PetscViewerASCIIPrintf(viewer, "  interface normal (%g, %g, %g), tangent (%g, %g, %g)\n", (double)m->pairs.nrm[0], (double)m->pairs.nrm[1], (double)m->pairs.nrm[2], (double)m->pairs.t[0], (double)m->pairs.t[1], (double)m->pairs.t[2]));
    for (PetscInt i = 0; i < fe->nbolts; i++) PetscCall(PetscViewerASCIIPrintf(viewer, "  bolt %" PetscInt_FMT ": at (%g, %g, %g) m, shank %g m long, diameter %g m, tied to %" PetscInt_FMT " head and %" PetscInt_FMT " nut footprint nodes (%s tie)\n", i + 1, (double)fe->bolt[i].x[0], (double)fe->bolt[i].x[1], (double)fe->bolt[i].x[2], (double)fe->bolt[i].axis, (double)fe->bolt[i].d, fe->bolt[i].nhead, fe->bolt[i].nnut, fe->rigidtie ? "rigid" : "distributing"));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode JRModelRigidBasis_FE(JRModel m, PetscInt *n, Vec rb[6])
{
  Model_FEType *ft = (Model_FEType *)m->data;

  PetscFunctionBeginUser;
  *n = 0;
  if (ft->fe.clamp) PetscFunctionReturn(0); /* a clamped model has no rigid-body modes */
  PetscCall(JRFERigidBasis(ft->fe.dm, rb));
  *n = 6;
  PetscFunctionReturn(0);
}

static PetscErrorCode JRModelCoordinates_FE(JRModel m, Vec *X)
{
  Model_FEType *ft = (Model_FEType *)m->data;

  PetscFunctionBeginUser;
  PetscCall(DMCreateGlobalVector(ft->fe.dm, X));
  PetscCall(JRFENodalCoordinates(ft->fe.dm, *X));
  PetscFunctionReturn(0);
}

static PetscErrorCode JRModelDestroy_FE(JRModel m)
{
  Model_FEType *ft = (Model_FEType *)m->data;

  PetscFunctionBeginUser;
  PetscCall(DMDestroy(&ft->fe.dm));
  PetscCall(PetscFree(ft->fe.bolt));
  PetscCall(PetscFree(ft->fe.orig));
  PetscCall(PetscFree(m->data));
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateFE(JRModel m, Kind kind, const char *preset, Model_FE **fe)
{
  Model_FEType *ft;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&ft));
  ft->kind = kind;
  PetscCall(PetscStrncpy(ft->preset, preset, sizeof(ft->preset)));
  ft->fe.order   = 2;
  ft->fe.E       = 210e9;
  ft->fe.nu      = 0.3;
  ft->fe.rho     = 7850.0;
  ft->fe.grade   = 2.5;
  ft->fe.pairtol = 1e-7;
  PetscCall(PetscStrncpy(ft->fe.tangent, "x", sizeof(ft->fe.tangent)));
  m->data                = ft;
  m->ops->setfromoptions = JRModelSetFromOptions_FE;
  m->ops->setup          = JRModelSetUp_FE;
  m->ops->view           = JRModelView_FE;
  m->ops->destroy        = JRModelDestroy_FE;
  m->ops->rigidbasis     = JRModelRigidBasis_FE;
  m->ops->coordinates    = JRModelCoordinates_FE;
  *fe                    = &ft->fe;
  PetscFunctionReturn(0);
}

/* a straight steel beam 800 x 40 x 20 mm */
PetscErrorCode JRModelCreate_Beam(JRModel m)
{
  Model_FE *fe = NULL;

  PetscFunctionBeginUser;
  PetscCall(CreateFE(m, KIND_BEAM, "beam", &fe));
  fe->L1 = 0.8;
  fe->W  = 0.04;
  fe->H  = 0.02;
  fe->h  = 0.01;
  PetscFunctionReturn(0);
}

static void LapDefaults(Model_FE *fe)
{
  fe->L1 = fe->L2 = 0.42;
  fe->W = fe->H = 0.0254;
  fe->Llap      = 0.12;
  fe->nbolts    = 3;
  fe->pitch     = 0.03;
  fe->dbolt     = 0.3125 * 0.0254;
  fe->dhole     = 8.5e-3;
  fe->dwasher   = 17.5e-3;
  fe->h         = 5e-3;
  fe->E         = 190e9;
  fe->nu        = 0.3;
  fe->rho       = 7900.0;
}

/* the lap joint with every dimension an option (defaults: the Brake-Reuss beam) */
PetscErrorCode JRModelCreate_Lap(JRModel m)
{
  Model_FE *fe = NULL;

  PetscFunctionBeginUser;
  PetscCall(CreateFE(m, KIND_LAP, "lap", &fe));
  LapDefaults(fe);
  PetscFunctionReturn(0);
}

/* Brake-Reuss beam (thesis ch. 4): halves of 420 mm, 25.4 x 25.4 mm, 120 mm lap, three 5/16 in bolts at 30 mm,
   holes 8.5 mm, washers 17.5 mm; E 190 GPa, nu 0.3, rho 7900 kg/m^3 */
PetscErrorCode JRModelCreate_BRB(JRModel m)
{
  Model_FE *fe = NULL;

  PetscFunctionBeginUser;
  PetscCall(CreateFE(m, KIND_LAP, "brb", &fe));
  LapDefaults(fe);
  PetscFunctionReturn(0);
}

/* single M8 bolt specimen (see the top of this file) */
PetscErrorCode JRModelCreate_Lap1(JRModel m)
{
  Model_FE *fe = NULL;

  PetscFunctionBeginUser;
  PetscCall(CreateFE(m, KIND_LAP, "lap1", &fe));
  LapDefaults(fe);
  fe->L1 = fe->L2 = 0.40;
  fe->W           = 0.025;
  fe->H           = 0.020;
  fe->Llap        = 0.05;
  fe->nbolts      = 1;
  fe->dbolt       = 8e-3;
  fe->dhole       = 9e-3;
  fe->dwasher     = 16e-3;
  fe->nu          = 0.32;
  fe->rho         = 7800.0;
  PetscFunctionReturn(0);
}

/* three M8 bolts specimen (see the top of this file) */
PetscErrorCode JRModelCreate_Lap3(JRModel m)
{
  Model_FE *fe = NULL;

  PetscFunctionBeginUser;
  PetscCall(CreateFE(m, KIND_LAP, "lap3", &fe));
  LapDefaults(fe);
  fe->L1 = fe->L2 = 0.45;
  fe->W           = 0.030;
  fe->H           = 0.020;
  fe->Llap        = 0.10;
  fe->nbolts      = 3;
  fe->pitch       = 0.03;
  fe->dbolt       = 8e-3;
  fe->dhole       = 9e-3;
  fe->dwasher     = 16e-3;
  fe->nu          = 0.32;
  fe->rho         = 7800.0;
  PetscFunctionReturn(0);
}

/* a Gmsh mesh */
PetscErrorCode JRModelCreate_Gmsh(JRModel m)
{
  Model_FE *fe = NULL;

  PetscFunctionBeginUser;
  PetscCall(CreateFE(m, KIND_GMSH, "gmsh", &fe));
  fe->dbolt = 8e-3;
  PetscFunctionReturn(0);
}
