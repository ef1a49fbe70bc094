/*
   JRHBM: the harmonic-balance equations of a linear structure carrying contact elements, in modal
   coordinates (thesis 2.3, eq 2.18) generalised to H harmonics plus the mean.

   Unknowns: modal harmonic coefficients a, harmonic-major blocks over the nm modes,
       a = [a_0 | as_1 ac_1 | ... | as_H ac_H]  (n = nm (2H+1)),  x(t) = Phi (a_0 + sum as_h sin + ac_h cos).
   Residual, per harmonic h >= 1 (and h = 0 without damping and excitation):
       R_s = (Km - (h w)^2 Mm) as - (gamma Km + h w Cm) ac + Phi^T fN_s - fm_s
       R_c = (Km - (h w)^2 Mm) ac + (gamma Km + h w Cm) as + Phi^T fN_c
   with Km = diag(omega_r^2), Mm = I for mass-normalised modes (the full projected matrices in
   physical coordinates), structural damping gamma (H = gamma K, 2.17), viscous Cm = Phi^T C Phi
   and/or modal 2 zeta omega_r, excitation F sin(w t): fm_s = F Phi^T f for h = 1.
   Nonlinear forces: element e with tangential projection row r_e = phi(dof_a) - phi(dof_b) (4.3) sees
   U_e = A^T r_e (A = a as nm x nc) and gives back r_e F_e; jenkins_nv also s_e (normal DOFs) and its
   dynamic normal load N_e - max(n0, 0) (the static part is balanced by the preload).
   Modal basis (-hbm_basis): free, the modes of K; or stuck, the modes of K + Ks with Ks the springs of every
   friction element in contact at rest (n0 > 0) stuck: then Km holds them, each element adds its deviation
   from stuck R^T (F - kt U) (and S^T (N - n0 - kn V)), and the structural damping is gamma Phi^T K Phi (Kg),
   the structure's own stiffness only. Node-to-node elements (JRElements vdof_a) get rows (phi_A - phi_B) . t.
   Rigid-body modes (omega = 0) get the mean equation pin * a0 = 0: no spring or element holds their mean.
   Jacobian: element derivatives projected, blocks (k, m): sum_e r_e dF_km/dU r_e^T = R^T diag(d) R
   (BLAS gemm). The thesis's finite differences (2.23) remain as -hbm_jacobian fd.
   Parallel: elements are split across the ranks (each type in contiguous chunks); each rank sums its
   own into the residual and Jacobian; rank 0 adds the contributions and broadcasts them, so every
   rank holds the same small dense system and runs the same SNES (PETSC_COMM_SELF, prefix hbm_).

   Files: hbm.c the object's life cycle, options and set-up steps; basis.c the modal basis, the element groups and
   their projection rows, the stuck structure; residual.c the residual, Jacobian and the solver at fixed frequency;
   condense.c the condensation onto the joints; response.c responses, energies and contact states at a solution;
   newtondense.c the dense Newton SNES. The reduced model's joint motion fields are in src/reduce/fields.c.
*/
#include <jointrom/private/hbmimpl.h>

const char *const JRHBMJacobianTypes[] = {"analytic", "fd", "JRHBMJacobianType", "JR_HBM_JACOBIAN_", NULL};
const char *const JRHBMBases[]         = {"free", "stuck", "mixed", "JRHBMBasis", "JR_HBM_BASIS_", NULL};
const char *const JRHBMCondenseTypes[] = {"auto", "yes", "no", "JRHBMCondense", "JR_HBM_CONDENSE_", NULL};
const char *const JRJointMotions[]     = {"mean", "linear", "mode", "shapes", "JRJointMotion", "JR_JOINT_MOTION_", NULL};

PetscErrorCode JRHBMCreate(MPI_Comm comm, JRHBM *hbm)
{
  JRHBM h;

  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(PetscNew(&h));
  h->comm       = comm;
  h->ecomm      = comm;
  h->H          = 1;
  h->Ns         = 64;
  h->acctol     = 1e-8;
  h->jprod      = PETSC_TRUE;
  h->fdof       = 0;
  h->level      = 1.0;
  h->jtype      = JR_HBM_JACOBIAN_ANALYTIC;
  h->nmodes_opt = -1;
  h->nfree      = -1;
  h->monolr     = 1;
  h->monowood   = PETSC_TRUE;
  PetscCallMPI(MPI_Comm_rank(comm, &h->rank));
  PetscCallMPI(MPI_Comm_size(comm, &h->size));
  *hbm = h;
  PetscFunctionReturn(0);
}

/* The structure and its elements (reference kept) */
PetscErrorCode JRHBMSetModel(JRHBM h, JRModel model)
{
  PetscFunctionBeginUser;
  h->model       = model;
  h->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The contact elements (copied), instead of the model's own (a matrices model's element table): the node-to-node
   elements of an FE model, or a reduced model's */
PetscErrorCode JRHBMSetElements(JRHBM h, const JRElements *el)
{
  PetscFunctionBeginUser;
  PetscCall(JRElementsDestroy(&h->el));
  PetscCall(JRElementsDuplicate(el, &h->el));
  h->el_given    = PETSC_TRUE;
  h->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The contact elements of the harmonic balance: JRHBMSetElements's, else the model's */
PetscErrorCode JRHBMGetElements(JRHBM h, const JRElements **el)
{
  PetscFunctionBeginUser;
  if (h->el_given) *el = &h->el;
  else PetscCall(JRModelGetElements(h->model, el));
  PetscFunctionReturn(0);
}

/*
  Options: -hbm_harmonics H, -hbm_samples N, -hbm_modes m (default: all for small models, else 10),
  -hbm_physical, -hbm_gamma, -hbm_zeta, -hbm_jacobian analytic|fd, -hbm_view; the excitation
  -frf_dof i or -frf_force_file FILE, the responses -frf_output i,j,...; and -hbm_snes_*, -hbm_ksp_*,
  -hbm_pc_* on the nonlinear solver.
*/
PetscErrorCode JRHBMSetFromOptions(JRHBM h)
{
  PetscInt  nout = 64;
  PetscInt  out[64] = {0};
  PetscBool flg, nmset, nfset;

  PetscFunctionBeginUser;
  out[0] = h->fdof; /* the default shown by -help */
  PetscOptionsBegin(h->comm, NULL, "Harmonic balance (JRHBM)", "JRHBM");
  PetscCall(PetscOptionsInt("-hbm_harmonics", "Harmonics H (plus the mean) in the response", "JRHBMSetUp", h->H, &h->H, NULL));
  PetscCall(PetscOptionsInt("-hbm_samples", "Time samples per cycle N for alternating frequency-time (N >= 2H+1)", "JRHBMSetUp", h->Ns, &h->Ns, NULL));
  PetscCall(PetscOptionsInt("-hbm_modes", "Number of linear modes in the modal superposition (default: all up to 200 DOFs, else 10)", "JRHBMSetUp", h->nmodes_opt, &h->nmodes_opt, &nmset));
  PetscCall(PetscOptionsEnum("-hbm_basis", "Modal basis: free (modes of K: the interface held by the bolts only), stuck (modes of K plus every element in contact at rest stuck; the elements then add only their deviation from stuck) or mixed (Ritz vectors of the stuck structure in the span of both)", "JRHBMSetUp", JRHBMBases, (PetscEnum)h->basis, (PetscEnum *)&h->basis, &h->basis_set));
  PetscCall(PetscOptionsInt("-hbm_free_modes", "-hbm_basis mixed: free-interface modes added to the -hbm_modes stuck ones (default: as many)", "JRHBMSetUp", h->nfree, &h->nfree, &nfset));
  PetscCall(PetscOptionsEnum("-hbm_condense", "Reduced models: eliminate the modes and solve for the joints' motions only (auto: when it is exact and smaller)", "JRHBMSetUp", JRHBMCondenseTypes, (PetscEnum)h->condense, (PetscEnum *)&h->condense, NULL));
  PetscCall(PetscOptionsBool("-hbm_condense_products", "Condensed models: the continuation's Newton takes the Jacobian by its products through the modes and forms it only for an LU (0: formed at every iteration)", "JRHBMJacobianSetPoint", h->jprod, &h->jprod, NULL));
  PetscCall(PetscOptionsBool("-hbm_physical", "Physical coordinates instead of modes (small systems: checks modal truncation)", "JRHBMSetUp", h->physical, &h->physical, NULL));
  PetscCall(PetscOptionsReal("-hbm_gamma", "Structural damping H = gamma K (2.17) [-]", "JRHBMSetUp", h->gamma, &h->gamma, NULL));
  PetscCall(PetscOptionsReal("-hbm_zeta", "Modal viscous damping ratio, every mode [-]", "JRHBMSetUp", h->zeta, &h->zeta, NULL));
  PetscCall(PetscOptionsEnum("-hbm_jacobian", "Jacobian: analytic (element derivatives projected) or fd (finite differences, thesis 2.23)", "JRHBMSetUp", JRHBMJacobianTypes, (PetscEnum)h->jtype, (PetscEnum *)&h->jtype, NULL));
  PetscCall(PetscOptionsReal("-hbm_residual_tol", "A solution is accepted when ||R|| <= tol ||F f||: the residual against the excitation in the same space (condensed: the joints' static motion under it)", "JRHBMSolve", h->acctol, &h->acctol, NULL));
  PetscCall(PetscOptionsBool("-hbm_elements_replicated", "Every rank holds all the contact elements, as a reduced model's always: no sums over the ranks, and the levels' curves shared out over the ranks (-cont_levels_parallel); 0: split over the ranks", "JRHBMSetUp", h->replopt, &h->replopt, NULL));
  PetscCall(PetscOptionsBool("-hbm_view", "Print the harmonic-balance set-up", "JRHBMView", h->view, &h->view, NULL));
  if (!h->fdof_set) PetscCall(PetscOptionsInt("-frf_dof", "Excitation F sin(w t) at this DOF (0-based)", "JRHBMSetUp", h->fdof, &h->fdof, NULL));
  PetscCall(PetscOptionsString("-frf_force_file", "Excitation shape from a file instead (one value per DOF, in an FE model's natural order: that of the coordinates in a -modes_save file; .csv/.txt, .bin, .h5)", "JRHBMSetUp", h->ffile, h->ffile, sizeof(h->ffile), NULL));
  PetscCall(PetscOptionsIntArray("-frf_output", "Response DOFs (default: the excitation DOF)", "JRHBMResponse", out, &nout, &flg));
  PetscOptionsEnd();
  if (h->nout && h->fdof_set) flg = PETSC_FALSE; /* JRHBMSetExcitationDof() called */
  else PetscCall(PetscFree(h->outdof));
  if (flg) {
    PetscCheck(nout > 0, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_output needs at least one DOF");
    h->nout = nout;
    PetscCall(PetscMalloc1(nout, &h->outdof));
    PetscCall(PetscArraycpy(h->outdof, out, nout));
  } else if (!h->fdof_set) h->nout = 0;
  if (!h->modes_shared && !h->physical) { /* the modes' options (-modes_*), read and checked now: JRHBMSetUp makes the modes */
    JRModes md;
    PetscCall(JRModesCreate(h->comm, &md));
    PetscCall(JRModesSetFromOptions(md));
    PetscCall(JRModesDestroy(&md));
  }
  PetscCheck(!nmset || h->nmodes_opt >= 1, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_modes %" PetscInt_FMT ": at least 1 (unset: every mode up to 200 DOFs, else 10)", h->nmodes_opt);
  PetscCheck(!nfset || h->nfree >= 0, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_free_modes %" PetscInt_FMT ": 0 or more (unset: as many as -hbm_modes)", h->nfree);
  PetscCheck(h->H >= 1 && h->H <= JR_MAX_HARMONICS, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_harmonics %" PetscInt_FMT ": between 1 and %d", h->H, JR_MAX_HARMONICS);
  PetscCheck(h->Ns >= 2 * h->H + 1, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_samples %" PetscInt_FMT " must be at least 2H+1 = %" PetscInt_FMT " for -hbm_harmonics %" PetscInt_FMT, h->Ns, 2 * h->H + 1, h->H);
  PetscCheck(h->gamma >= 0.0 && !PetscIsInfOrNanReal(h->gamma), h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_gamma %g: the structural damping coefficient must be non-negative", (double)h->gamma);
  PetscCheck(h->zeta >= 0.0 && !PetscIsInfOrNanReal(h->zeta), h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_zeta %g: the modal damping ratio must be non-negative", (double)h->zeta);
  PetscCheck(h->acctol > 0.0 && h->acctol < 1.0, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_residual_tol %g: between 0 and 1 (relative to the excitation)", (double)h->acctol);
  h->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The excitation DOF and the response DOFs (default: the excitation DOF) in range */
static PetscErrorCode SetUpOutputs(JRHBM h, PetscInt ndof)
{
  PetscFunctionBeginUser;
  PetscCheck(h->fdof >= 0 && h->fdof < ndof, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_dof %" PetscInt_FMT " is out of range: DOFs are 0..%" PetscInt_FMT, h->fdof, ndof - 1);
  if (!h->nout) {
    h->nout = 1;
    PetscCall(PetscMalloc1(1, &h->outdof));
    h->outdof[0] = h->fdof;
  }
  for (PetscInt i = 0; i < h->nout; i++) PetscCheck(h->outdof[i] >= 0 && h->outdof[i] < ndof, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_output %" PetscInt_FMT " is out of range: DOFs are 0..%" PetscInt_FMT, h->outdof[i], ndof - 1);
  PetscFunctionReturn(0);
}

/* The description of the linear damping (JRHBMGetDampingDescription) */
static PetscErrorCode SetUpDampingDescription(JRHBM h, Mat C)
{
  char *d = h->damping;

  PetscFunctionBeginUser;
  d[0] = 0;
  if (h->gamma > 0) PetscCall(PetscSNPrintf(d + strlen(d), sizeof(h->damping) - strlen(d), "structural gamma = %g (H = gamma K); ", (double)h->gamma));
  if (h->zeta > 0) PetscCall(PetscSNPrintf(d + strlen(d), sizeof(h->damping) - strlen(d), "modal viscous zeta = %g; ", (double)h->zeta));
  if (C) PetscCall(PetscSNPrintf(d + strlen(d), sizeof(h->damping) - strlen(d), "viscous matrix C; "));
  if (!d[0]) PetscCall(PetscSNPrintf(d, sizeof(h->damping), "none (only the contact elements dissipate)"));
  else d[strlen(d) - 2] = 0;
  PetscFunctionReturn(0);
}

/*
  JRHBMSetUp - the modal basis (or physical coordinates) and the linear modal matrices, the excitation and the
  outputs in the basis, a reduced model's joint rows, the element groups split across the ranks with their
  projection rows, the stuck springs of a stuck basis, the condensation, the SNES; a second call does nothing
*/
PetscErrorCode JRHBMSetUp(JRHBM h)
{
  Mat               K, M, C;
  PetscInt          ndof;
  const JRElements *el;
  PetscReal        *field = NULL; /* reduced models: the joints' motion fields (src/reduce/fields.c) */

  PetscFunctionBeginUser;
  if (h->setupcalled) PetscFunctionReturn(0);
  PetscCheck(h->model, h->comm, PETSC_ERR_ARG_WRONGSTATE, "JRHBMSetModel() first");
  PetscCall(JRModelGetMatrices(h->model, &K, &M, &C));
  PetscCall(JRModelGetNumDofs(h->model, &ndof));
  PetscCall(JRHBMGetElements(h, &el));
  h->nc    = 2 * h->H + 1;
  PetscCall(PetscFree(h->pptab)); /* sized by nc */
  h->has_C = C ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(SetUpOutputs(h, ndof));
  /* the linear part: modes (or physical coordinates) */
  PetscCall(JRHBMSetUpBasis(h, K, M, C, ndof, el));
  h->n = h->nm * h->nc;
  PetscCall(SetUpDampingDescription(h, C));
  /* excitation shape in modal coordinates, outputs */
  PetscCall(JRHBMSetUpExcitation(h, ndof));
  /* reduced model: its joints' rows from their members (and, in a stuck basis, the members' springs to cancel) */
  PetscCall(PetscFree(h->Kc));
  PetscCall(PetscCalloc1(h->nm * h->nm, &h->Kc));
  if (el->members) {
    PetscCheck(el->joint && el->njoints == el->members->njoints, h->comm, PETSC_ERR_ARG_WRONG, "A reduced model needs a joint for every element, among its members' %" PetscInt_FMT " joints", el->members->njoints);
    PetscCall(PetscMalloc1(el->njoints * JR_FIELD_WIDTH(2, h->nm), &field));
    PetscCall(JRJointRows(h, el->members, (PetscBool)(el->pos != NULL), field, h->basis != JR_HBM_BASIS_FREE ? h->Kc : NULL));
  }
  /* element groups, one per type, split across the ranks; a reduced model's few elements (and with
     -hbm_elements_replicated any model's) are on every rank instead (each rank's Newton iteration then needs no sum
     over the ranks: the same numbers, bit for bit, everywhere; a rank can solve a level alone, JRHBMSetLocal) */
  h->repl  = (PetscBool)((el->members || h->replopt) && h->size > 1);
  h->ecomm = h->repl ? PETSC_COMM_SELF : h->comm;
  PetscCall(JRHBMSetUpGroups(h, el, field));
  /* stuck basis: the elements add their deviation from stuck; structural damping on the structure's own stiffness */
  PetscCall(JRHBMSetUpStuckSprings(h, el));
  PetscCall(PetscFree(field));
  /* a reduced model: the modes eliminated, the joints' motions the unknowns */
  PetscCall(JRHBMCondenseSetUp(h, el));
  /* the nonlinear solver at fixed frequency: SNES on every rank, prefix hbm_ */
  PetscCall(JRHBMSetUpSolver(h));
  h->setupcalled = PETSC_TRUE;
  if (h->view) PetscCall(JRHBMView(h, NULL));
  PetscFunctionReturn(0);
}

/* The excitation DOF and the response DOFs (nout >= 1) set in code, e.g. found by position on an FE
   mesh: -frf_dof and -frf_output are then ignored. Call before JRHBMSetFromOptions(). */
PetscErrorCode JRHBMSetExcitationDof(JRHBM h, PetscInt dof, PetscInt nout, const PetscInt out[])
{
  PetscFunctionBeginUser;
  PetscCheck(nout >= 1, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "At least one response DOF");
  h->fdof     = dof;
  h->fdof_set = PETSC_TRUE;
  PetscCall(PetscFree(h->outdof));
  h->nout = nout;
  PetscCall(PetscMalloc1(nout, &h->outdof));
  PetscCall(PetscArraycpy(h->outdof, out, nout));
  h->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*
  JRHBMSetOutputPoints - the positions [m] of the n response points (xyz: x, y, z of each) and the direction
  of the responses (0 x, 1 y, 2 z), in the order of the response DOFs of JRHBMSetExcitationDof(). They name
  the outputs (HDF5 attributes, plot titles) where a DOF number would depend on the partition of an FE
  mesh; they do not change the solution. Without them an output is named by its DOF.
*/
PetscErrorCode JRHBMSetOutputPoints(JRHBM h, PetscInt n, const PetscReal xyz[], PetscInt dir)
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 1 && dir >= 0 && dir < 3, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "JRHBMSetOutputPoints: %" PetscInt_FMT " points along direction %" PetscInt_FMT ": at least one point, direction 0 (x), 1 (y) or 2 (z)", n, dir);
  PetscCall(PetscFree(h->ptxyz));
  PetscCall(PetscMalloc1(3 * n, &h->ptxyz));
  PetscCall(PetscArraycpy(h->ptxyz, xyz, 3 * n));
  h->npts  = n;
  h->ptdir = dir;
  PetscFunctionReturn(0);
}

/* The response points of JRHBMSetOutputPoints() (xyz: 3 per response DOF, NULL if none were given) and their direction */
PetscErrorCode JRHBMGetOutputPoints(JRHBM h, const PetscReal **xyz, PetscInt *dir)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCheck(!h->ptxyz || h->npts == h->nout, h->comm, PETSC_ERR_ARG_SIZ, "JRHBMSetOutputPoints gave %" PetscInt_FMT " points for %" PetscInt_FMT " response DOFs", h->npts, h->nout);
  *xyz = h->ptxyz;
  if (dir) *dir = h->ptdir;
  PetscFunctionReturn(0);
}

/*
  JRHBMSetModes - use the modes (and basis) of another JRHBM that is set up, e.g. the node-to-node model's for its
  reduced model: nothing is solved again; the other JRHBM must outlive this one (its modes are not copied).
*/
PetscErrorCode JRHBMSetModes(JRHBM h, JRHBM from)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(from));
  PetscCheck(!from->physical, h->comm, PETSC_ERR_ARG_WRONG, "JRHBMSetModes: the other JRHBM works in physical coordinates");
  PetscCall(JRModesReference(from->modes));
  PetscCall(JRModesDestroy(&h->modes));
  h->modes        = from->modes; /* a reference: not solved here, released by JRHBMDestroy */
  h->modes_shared = PETSC_TRUE;
  h->basis        = from->basis;
  h->basis_set    = PETSC_TRUE;
  h->nmodes_opt   = from->modes->nm;
  h->setupcalled  = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The file the modes are saved to when neither -modes_load nor -modes_save is given ("": not saved) */
PetscErrorCode JRHBMSetModesFile(JRHBM h, const char file[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(h->modes_file, file ? file : "", sizeof(h->modes_file)));
  PetscFunctionReturn(0);
}

/* How the joints' members move (a reduced model; JRReduce passes its -rom_joint_motion): their mean motion (4.4) or
   a linear field over their positions, or over their positions and stuck-mode motions */
PetscErrorCode JRHBMSetJointMotion(JRHBM h, JRJointMotion jm)
{
  PetscFunctionBeginUser;
  h->jmotion     = jm;
  h->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* A reduced model in a stuck or mixed basis: keep each member's stuck springs on its motion outside its joint's field
   (its residual r_e - p_e, p_e the field's row at the member), linear, as part of the structure's stiffness (damped by
   gamma with it), and cancel only those on the field's motion, which the joint's elements replace
   (-rom_joint_residual). With a field that is an orthogonal projection of the members' motions for their springs,
   the reduced model stuck is node-to-node's stuck */
PetscErrorCode JRHBMSetJointResidual(JRHBM h, PetscBool on)
{
  PetscFunctionBeginUser;
  h->jresid      = on;
  h->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*
  JRHBMSetOptionsPrefix - a prefix put before "hbm_" on the options of the nested solvers (the SNES of a point and
  the continuation's bordered SNES): JRReduce gives its reduced models "rom_", so that -rom_hbm_snes_* tunes them and
  -hbm_snes_* the node-to-node model (the harmonic balance's own options, -hbm_harmonics and the like, stay shared)
*/
PetscErrorCode JRHBMSetOptionsPrefix(JRHBM h, const char prefix[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(h->prefix, prefix ? prefix : "", sizeof(h->prefix)));
  h->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The nested solvers' options prefix, "hbm_" after JRHBMSetOptionsPrefix's */
PetscErrorCode JRHBMGetOptionsPrefix(JRHBM h, const char **prefix)
{
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(h->snesprefix, sizeof(h->snesprefix), "%shbm_", h->prefix));
  *prefix = h->snesprefix;
  PetscFunctionReturn(0);
}

/* The modal basis (-hbm_basis): free (modes of K), stuck (modes of K with the stuck contact springs) or mixed */
PetscErrorCode JRHBMSetBasis(JRHBM h, JRHBMBasis basis)
{
  PetscFunctionBeginUser;
  PetscCheck(basis == JR_HBM_BASIS_FREE || basis == JR_HBM_BASIS_STUCK || basis == JR_HBM_BASIS_MIXED, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "Basis 0 (free), 1 (stuck) or 2 (mixed)");
  h->basis       = basis;
  h->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The basis check of the modes (JRModesGetBasisCheck; rho = -1: not computed, e.g. physical coordinates) */
PetscErrorCode JRHBMGetBasisCheck(JRHBM h, PetscReal *rho, PetscReal *rho0, PetscReal *tol, PetscInt *ns, PetscLogDouble *t)
{
  PetscFunctionBeginUser;
  if (!h->modes) {
    if (rho) *rho = -1.0;
    if (rho0) *rho0 = -1.0;
    if (tol) *tol = 0.0;
    if (ns) *ns = 0;
    if (t) *t = 0.0;
    PetscFunctionReturn(0);
  }
  PetscCall(JRModesGetBasisCheck(h->modes, rho, rho0, tol, ns, t));
  PetscFunctionReturn(0);
}

/* The modal basis, a JRHBMBasis value */
PetscErrorCode JRHBMGetBasis(JRHBM h, PetscInt *basis)
{
  PetscFunctionBeginUser;
  *basis = (PetscInt)h->basis;
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGetSizes(JRHBM h, PetscInt *nm, PetscInt *H, PetscInt *n)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  if (nm) *nm = h->nm;
  if (H) *H = h->H;
  if (n) *n = h->n;
  PetscFunctionReturn(0);
}

/* JRHBMGetSolveSize - the size of the unknowns that JRHBMSolve() and the continuation work on: the modal ones
   (JRHBMGetSizes n) or, condensed, the joints' motions (info: a description of the condensation, or "") */
PetscErrorCode JRHBMGetSolveSize(JRHBM h, PetscInt *ns, const char **info)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  if (ns) *ns = h->ns;
  if (info) *info = h->condinfo;
  PetscFunctionReturn(0);
}

/* Natural frequencies of the modes used [rad/s] (none in physical coordinates) */
PetscErrorCode JRHBMGetModalFrequencies(JRHBM h, PetscInt *nm, const PetscReal **omega)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  *nm    = h->physical ? 0 : h->nm;
  *omega = h->omega_r;
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGetDampingDescription(JRHBM h, const char **d)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  *d = h->damping;
  PetscFunctionReturn(0);
}

/* The excitation level F [N]: f(t) = F f_shape sin(w t). The SNES absolute tolerance follows the
   level unless -hbm_snes_atol is given: 1e-12 of the modal force; condensed, 1e-10 of the joints' static motion
   under it. The condensed residual is the modal one times Q Z^-1, whose gain grows from the static one by up to
   1/(2 zeta) (250-500 here) at resonance, and the round-off of x + G g - F xF with it: at 1e-12 of the static
   motion half of the solves ended on the step test after an iteration that gained nothing (round-off);
   1e-10 of the static motion is 2-4e-13 of the resonant one. */
PetscErrorCode JRHBMSetForceLevel(JRHBM h, PetscReal F)
{
  PetscBool set;
  PetscReal fn = 0.0;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  h->level = F;
  for (PetscInt i = 0; i < h->nm; i++) fn += h->fm[i] * h->fm[i];
  fn = PetscSqrtReal(fn);
  if (h->cond) { /* the residual is a motion of the joints: the modal force over the lowest elastic stiffness, on the rows */
    PetscReal lmin = 0, qn = 0;
    for (PetscInt k = 0; k < h->nm; k++)
      if (h->lamv[k] > 1e-8 * h->lamv[h->nm - 1] && (lmin == 0 || h->lamv[k] < lmin)) lmin = h->lamv[k];
    for (PetscInt r = 0; r < h->nq; r++) {
      PetscReal q = 0;
      for (PetscInt i = 0; i < h->nm; i++) q += h->Q[r * h->nm + i] * h->Q[r * h->nm + i];
      qn = PetscMax(qn, PetscSqrtReal(q));
    }
    if (lmin > 0) fn *= qn / lmin;
  }
  {
    const char *pre;
    PetscCall(JRHBMGetOptionsPrefix(h, &pre));
    PetscCall(PetscOptionsHasName(NULL, pre, "-snes_atol", &set));
  }
  h->rscale = PetscAbsReal(F) * fn + 1e-300;
  if (!set) PetscCall(SNESSetTolerances(h->snes, (h->cond ? 1e-10 : 1e-12) * PetscAbsReal(F) * fn + 1e-300, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGetSNES(JRHBM h, SNES *snes)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  *snes = h->snes;
  PetscFunctionReturn(0);
}

/* JRHBMForgetFactors - the harmonic-balance solver's kept LU (the next solves' preconditioner) dropped: the next solve
   factors its own Jacobian, so that it does not depend on the solves before it */
PetscErrorCode JRHBMForgetFactors(JRHBM h)
{
  JRDenseLU lu = NULL;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(SNESNewtonDenseGetDenseLU(h->snes, &lu));
  if (lu) PetscCall(JRDenseLUForget(lu));
  PetscFunctionReturn(0);
}

/* JRHBMGetReplicated - whether every rank holds all the elements (a reduced model on several ranks) */
PetscErrorCode JRHBMGetReplicated(JRHBM h, PetscBool *repl)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  *repl = h->repl;
  PetscFunctionReturn(0);
}

/*
  JRHBMSetLocal - with local, every call on a replicated h (JRHBMGetReplicated) is the calling rank's alone: its
  communicator PETSC_COMM_SELF, so that the ranks solve different things at once (the levels of a curve); without,
  the communicator it was created on again. The time in the elements while local is summed over the ranks when
  local ends (so that the ranks agree) and divided by their number.
*/
PetscErrorCode JRHBMSetLocal(JRHBM h, PetscBool local)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  if (local == h->local) PetscFunctionReturn(0);
  PetscCheck(!local || h->repl, h->comm, PETSC_ERR_ARG_WRONGSTATE, "JRHBMSetLocal: the elements are split over the ranks");
  if (local) {
    h->gcomm = h->comm;
    h->grank = h->rank;
    h->gsize = h->size;
    h->comm  = PETSC_COMM_SELF;
    h->rank  = 0;
    h->size  = 1;
    h->telem0    = h->telem;
    h->nelem0    = h->nelem;
    h->nelemjac0 = h->nelemjac;
  } else {
    PetscLogDouble dt = h->telem - h->telem0;
    PetscInt       dn[2] = {h->nelem - h->nelem0, h->nelemjac - h->nelemjac0};
    h->comm = h->gcomm;
    h->rank = h->grank;
    h->size = h->gsize;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &dt, 1, MPI_DOUBLE, MPI_SUM, h->comm)); /* PetscLogDouble: a double */
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, dn, 2, MPIU_INT, MPI_SUM, h->comm));
    h->telem    = h->telem0 + dt / h->size;
    h->nelem    = h->nelem0 + dn[0];
    h->nelemjac = h->nelemjac0 + dn[1];
  }
  h->local = local;
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGetJacobianType(JRHBM h, JRHBMJacobianType *jt)
{
  PetscFunctionBeginUser;
  *jt = h->jtype;
  PetscFunctionReturn(0);
}

/*
  JRHBMGetElementTime - the wall time [s] spent so far evaluating the contact elements (forces, their derivatives
  projected into the Jacobian, and the sums over the ranks: everything whose cost grows with the elements), and how
  many evaluations, of which with a Jacobian (any argument may be NULL). The rest of a solve is the linear
  algebra on the unknowns and the continuation, the same for any number of elements.
*/
PetscErrorCode JRHBMGetElementTime(JRHBM h, PetscLogDouble *seconds, PetscInt *calls, PetscInt *jacobians)
{
  PetscFunctionBeginUser;
  if (seconds) *seconds = h->telem;
  if (calls) *calls = h->nelem;
  if (jacobians) *jacobians = h->nelemjac;
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGetOutputs(JRHBM h, PetscInt *nout, const PetscInt **dofs)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  *nout = h->nout;
  if (dofs) *dofs = h->outdof;
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMView(JRHBM h, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(h->comm, &viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "JRHBM: %" PetscInt_FMT " harmonics + mean, %s, %" PetscInt_FMT " unknowns, %s Jacobian, %d rank(s)\n", h->H, h->physical ? "physical coordinates" : "modal coordinates", h->n, JRHBMJacobianTypes[h->jtype], h->size));
  if (!h->physical) PetscCall(PetscViewerASCIIPrintf(viewer, "  %" PetscInt_FMT " modes, %.6g .. %.6g Hz\n", h->nm, (double)(h->omega_r[0] / (2 * PETSC_PI)), (double)(h->omega_r[h->nm - 1] / (2 * PETSC_PI))));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  damping: %s\n", h->damping));
  for (PetscInt t = 0; t < h->ngroups; t++) {
    PetscInt nt;
    PetscCall(MPIU_Allreduce(&h->g[t].nloc, &nt, 1, MPIU_INT, MPI_SUM, h->ecomm));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  %" PetscInt_FMT " %s elements\n", nt, h->g[t].c->type_name));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMDestroy(JRHBM *hbm)
{
  JRHBM h = *hbm;

  PetscFunctionBeginUser;
  if (!h) PetscFunctionReturn(0);
  for (PetscInt t = 0; t < h->ngroups; t++) PetscCall(JRHBMGroupDestroy(&h->g[t]));
  PetscCall(PetscFree(h->g));
  PetscCall(JRModesDestroy(&h->modes));
  PetscCall(PetscFree3(h->Km, h->Mm, h->Cm));
  PetscCall(PetscFree(h->omega_r));
  PetscCall(PetscFree(h->pin));
  PetscCall(PetscFree(h->Kg));
  PetscCall(PetscFree(h->Kc));
  PetscCall(PetscFree(h->outdof));
  PetscCall(PetscFree(h->ptxyz));
  PetscCall(JRElementsDestroy(&h->el));
  PetscCall(PetscFree(h->fm));
  PetscCall(PetscFree(h->Phiout));
  PetscCall(PetscFree(h->buf));
  PetscCall(PetscFree(h->cache_a));
  PetscCall(SNESDestroy(&h->snes));
  PetscCall(MatDestroy(&h->J));
  PetscCall(VecDestroy(&h->r));
  PetscCall(PetscFree2(h->QQ, h->cb));
  PetscCall(PetscFree(h->pptab));
  PetscCall(PetscFree(h->jres));
  PetscCall(PetscFree2(h->llu, h->lpiv));
  PetscCall(PetscFree3(h->epsi, h->ep, h->ework));
  PetscCall(JRHBMHillDestroy(h));
  PetscCall(JRHBMMonodromyDestroy(h));
  PetscCall(PetscFree3(h->Q, h->QV, h->VF));
  PetscCall(PetscFree4(h->V, h->lamv, h->cv, h->G0));
  PetscCall(PetscFree2(h->Z0, h->piv0));
  PetscCall(PetscFree3(h->Gb, h->inv, h->ctmp));
  PetscCall(PetscFree(h));
  *hbm = NULL;
  PetscFunctionReturn(0);
}
