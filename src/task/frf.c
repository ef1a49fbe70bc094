/*
   -task frf: frequency-response curves of a structure with contact elements.

   Matrices models (-model_type matrices): K, M, C and the element table from files -> modes -> harmonic
   balance (-hbm_*) -> continuation over the levels (-cont_*, -frf_*) -> BASE.h5, BASE.csv, BASE.png.

   FE models (brb, lap1, lap3, lap, gmsh): the node-to-node contact model, the whole pipeline
     model -> preload (-preload_*; or -preload_load FILE) -> modes (-hbm_modes, -modes_*; saved to
     BASE_modes.h5, reused by -modes_load) -> interface (one element per facing pair, -interface_*)
     -> harmonic balance + continuation -> post:
   the excitation and the responses are points of the mesh (-frf_at, -frf_dir, -frf_output_at; default: the
   force at the free end of part A, the responses at the free end of part B and at the force); the stuck
   structure's natural frequencies in the modal basis (and, with -frf_stick_fe, of the whole FE model with
   the stuck springs, by SLEPc); every element's contact state at each level's peak, BASE_contact.csv and
   the map BASE_contact.png in the four colours of thesis Figs 5.12-5.19.
*/
#include <jointrom/private/taskimpl.h>
#include <sys/resource.h>

/* The full FE model with every element in contact at rest (n0 > 0) stuck: K + sum_e kt t t^T (+ kn n n^T)
   between its nodes, and its
   lowest nf natural frequencies by SLEPc (the same shift-and-invert as the free modes) */
static PetscErrorCode StickFE(JRModel model, const JRElements *el, PetscInt nf, PetscReal f[])
{
  Mat              K, M, B, Ks;
  JRModes          md;
  PetscInt         nrb;
  Vec              rb[6];
  const PetscReal *lam;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetMatrices(model, &K, &M, NULL));
  PetscCall(JRElementsCreateStuckStiffness(K, el, &B));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &Ks));
  PetscCall(MatAXPY(Ks, 1.0, B, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatDestroy(&B));
  PetscCall(JRModesCreate(PetscObjectComm((PetscObject)K), &md));
  PetscCall(JRModesSetOperators(md, Ks, M));
  PetscCall(JRModelGetRigidBasis(model, &nrb, rb));
  PetscCall(JRModesSetRigidBasis(md, nrb, rb));
  for (PetscInt i = 0; i < nrb; i++) PetscCall(VecDestroy(&rb[i]));
  PetscCall(JRModesSetNumber(md, nf));
  PetscCall(JRModesSolve(md));
  PetscCall(JRModesGetEigenvalues(md, &lam));
  for (PetscInt i = 0; i < nf; i++) f[i] = PetscSqrtReal(PetscMax(lam[i], 0.0)) / (2 * PETSC_PI);
  PetscCall(JRModesDestroy(&md));
  PetscCall(MatDestroy(&Ks));
  PetscFunctionReturn(0);
}


/* Curves of one model: a JRCont on hbm (options -cont_*, -frf_*), written to base (if not empty); seconds: the
   continuation's wall time (every level, the peaks, not the stability), stab: the stability's; elem (may be NULL): the
   contact elements' part (JRHBMGetElementTime) */
static PetscErrorCode Curves(MPI_Comm comm, JRPost post, JRHBM hbm, const char base[], JRCont *cont, PetscReal *seconds, PetscReal *stab, PetscReal *elem)
{
  PetscLogDouble t0, t1, e0, e1;
  PetscReal      se;

  PetscFunctionBeginUser;
  PetscCall(JRContCreate(comm, cont));
  PetscCall(JRContSetHBM(*cont, hbm));
  PetscCall(JRContSetFromOptions(*cont));
  if (base) PetscCall(JRContSetOutputBase(*cont, base));
  PetscCall(JRHBMGetElementTime(hbm, &e0, NULL, NULL));
  PetscCall(PetscLogStagePush(JR_StageSolve));
  PetscCall(PetscTime(&t0));
  PetscCall(JRContSolve(*cont));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscLogStagePop());
  PetscCall(JRHBMGetElementTime(hbm, &e1, NULL, NULL));
  PetscCall(JRContGetStabilitySeconds(*cont, stab, &se));
  *seconds = t1 - t0 - *stab;
  if (elem) *elem = e1 - e0 - se;
  PetscCall(PetscLogStagePush(JR_StagePost));
  PetscCall(JRPostWriteCurves(post, *cont));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}


/* The run: its objects, what the options asked for, and the figures reported */
typedef struct {
  MPI_Comm           comm;
  PetscBool          nlmodes;         /* -task nlmodes: the backbone of a nonlinear mode instead of the curves */
  PetscBool          curves, backbones; /* -task compare: -compare_frf, -compare_nlmodes */
  JRNLModes          nlm, nlmr;       /* the backbone (-task nlmodes; -task compare: node-to-node's), the reduced model's */
  PetscBool          compare, help, fe, n2n, isrom, loaded, joints, stickfe, plot, set, oset;
  JRModel            model;
  JRPreload          pre;
  JRInterface        itf;
  JRReduce           red;
  JRPost             post;
  JRHBM              hbm, hbmr, hbmc; /* node-to-node (or matrices), reduced, the one whose curves a frf run reports */
  JRCont             cont, contr, contc;
  JRElements         el, elr, elj;   /* node-to-node elements, reduced elements, the joints' members */
  JRVerify           ver;             /* -frf_verify_points: the curves' points checked by time integration */
  const PetscInt    *pair;           /* each node-to-node element's pair (the interface's) */
  PetscInt           romm, fdof, nout, odof[21], dir, nd, no;
  PetscReal          at[3], oat[63], fdist;
  char               base[PETSC_MAX_PATH_LEN];
  const char        *romsave, *romload;
  PetscReal          tmodel, tn, tr, en, er, setn, setr, tred;
  PetscInt           adapt_rounds, adapt_added; /* -modes_adapt: rounds made, vectors added */
  PetscBool          adapt_conv;                /* its last round added nothing */
  PetscReal          adapt_lmax, adapt_dw, adapt_da, adapt_s; /* the last round's peak_load_deformation and peak moves; seconds */
} FRFRun;

static const char *const Dirs[] = {"x", "y", "z"};

/* The driver's own options: outputs, and on FE models the excitation and response points */
static PetscErrorCode RunOptions(FRFRun *r)
{
  MPI_Comm comm = r->comm;

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Frequency response (-task frf, -task compare)", "JRTaskFRF");
  if (!r->nlmodes) { /* -task nlmodes: -nlm_output_file, -nlm_plot (JRNLModesSetFromOptions) */
    PetscCall(PetscOptionsString("-frf_output_file", "Output base name", "JRTaskFRF", r->base, r->base, sizeof(r->base), NULL));
    PetscCall(PetscOptionsBool("-frf_plot", "Draw the PNG plots", "JRTaskFRF", r->plot, &r->plot, NULL));
  }
  if (r->compare) {
    PetscCall(PetscOptionsBool("-compare_frf", "-task compare: the frequency-response curves of both models (-frf_force levels)", "JRTaskCompare", r->curves, &r->curves, NULL));
    PetscCall(PetscOptionsBool("-compare_nlmodes", "-task compare: the backbones of both models' nonlinear mode over the same amplitudes (-nlm_*), BASE_n2n_nlmodes.*, BASE_rom_nlmodes.*, BASE_nlmodes_compare.*", "JRTaskCompare", r->backbones, &r->backbones, NULL));
  }
  if (r->fe || r->help) PetscCall(PetscOptionsBool("-frf_stick_fe", "Also the natural frequencies of the whole FE model with every element stuck (SLEPc): the modal truncation error", "JRTaskFRF", r->stickfe, &r->stickfe, NULL));
  PetscOptionsEnd();
  PetscCheck(r->help || r->curves || r->backbones, comm, PETSC_ERR_ARG_WRONG, "-task compare -compare_frf 0: nothing to compare; add -compare_nlmodes (the backbones)");
  PetscCheck(r->help || r->fe || !r->compare, comm, PETSC_ERR_ARG_WRONG, "-task compare needs an FE model with a contact interface (-model_type brb, lap1, lap3, lap, gmsh)");
  if (r->fe || r->help) {
    PetscBool d, o;
    PetscOptionsBegin(comm, NULL, "Excitation and responses of an FE model (-task frf)", "JRTaskFRF");
    PetscCall(PetscOptionsRealArray("-frf_at", "Excitation point x,y,z [m] (nearest node; default: the end x = xmin, mid-width, top)", "JRTaskFRF", r->at, &r->nd, &r->set));
    PetscCall(PetscOptionsEList("-frf_dir", "Direction of the excitation force and of the responses", "JRTaskFRF", Dirs, 3, Dirs[r->dir], &r->dir, NULL));
    PetscCall(PetscOptionsRealArray("-frf_output_at", "Response points x1,y1,z1,x2,... [m] (default: the other end, then the excitation point)", "JRTaskFRF", r->oat, &r->no, &r->oset));
    PetscOptionsEnd();
    PetscCheck(!r->set || r->nd == 3, comm, PETSC_ERR_ARG_WRONG, "-frf_at needs three coordinates x,y,z [m], got %" PetscInt_FMT, r->nd);
    PetscCheck(!r->oset || (r->no % 3 == 0 && r->no > 0), comm, PETSC_ERR_ARG_WRONG, "-frf_output_at needs triples x,y,z [m], got %" PetscInt_FMT " values", r->no);
    PetscCall(PetscOptionsHasName(NULL, NULL, "-frf_dof", &d));
    PetscCall(PetscOptionsHasName(NULL, NULL, "-frf_output", &o));
    PetscCheck(r->help || !r->fe || (!d && !o), comm, PETSC_ERR_ARG_INCOMP, "%s: on an FE model the DOF numbers depend on the partition; give points instead: -frf_at x,y,z and -frf_output_at x,y,z,... [m] with -frf_dir x|y|z", d ? "-frf_dof" : "-frf_output");
  }
  PetscFunctionReturn(0);
}

/* -task compare -compare_nlmodes: the two backbones' options (-nlm_*, shared; the reduced model's correctors
   -rom_nlm_snes_*), their files named after -frf_output_file BASE: BASE_n2n_nlmodes.*, BASE_rom_nlmodes.* (their PNG
   is the comparison's) */
static PetscErrorCode BackboneOptions(FRFRun *r)
{
  char      b[PETSC_MAX_PATH_LEN + 16];
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(JRNLModesCreate(r->comm, &r->nlm));
  PetscCall(JRNLModesSetFromOptions(r->nlm));
  PetscCall(JRNLModesCreate(r->comm, &r->nlmr));
  PetscCall(JRNLModesSetOptionsPrefix(r->nlmr, "rom_"));
  PetscCall(JRNLModesSetFromOptions(r->nlmr));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-nlm_output_file", &set));
  PetscCheck(r->help || !set, r->comm, PETSC_ERR_ARG_INCOMP, "-task compare -compare_nlmodes names the backbones' files after -frf_output_file BASE (BASE_n2n_nlmodes.*, BASE_rom_nlmodes.*): drop -nlm_output_file");
  PetscCall(PetscSNPrintf(b, sizeof(b), "%s%s", r->base, r->base[0] ? "_n2n_nlmodes" : ""));
  PetscCall(JRNLModesSetOutput(r->nlm, b, PETSC_FALSE));
  PetscCall(PetscSNPrintf(b, sizeof(b), "%s%s", r->base, r->base[0] ? "_rom_nlmodes" : ""));
  PetscCall(JRNLModesSetOutput(r->nlmr, b, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* Every object's options, read and checked before any work (with -help: listed, not checked) */
static PetscErrorCode SetFromOptions(FRFRun *r)
{
  MPI_Comm comm = r->comm;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &r->help));
  PetscCall(JRModelCreate(comm, &r->model));
  PetscCall(JRModelSetFromOptions(r->model));
  {
    JRModelType mt;
    PetscCall(JRModelGetType(r->model, &mt));
    r->fe = (PetscBool)strcmp(mt, JRMODELMATRICES);
  }
  if (r->nlmodes) {
    const char *base;
    PetscCall(JRNLModesCreate(comm, &r->nlm));
    PetscCall(JRNLModesSetFromOptions(r->nlm));
    PetscCall(JRNLModesGetOutputBase(r->nlm, &base));
    PetscCall(PetscStrncpy(r->base, base, sizeof(r->base)));
  }
  PetscCall(RunOptions(r));
  if (r->compare && (r->backbones || r->help)) PetscCall(BackboneOptions(r));
  if (r->fe || r->help) {
    PetscCall(JRPreloadCreate(comm, &r->pre));
    PetscCall(JRPreloadSetModel(r->pre, r->model));
    PetscCall(JRPreloadSetFromOptions(r->pre));
    PetscCall(JRInterfaceCreate(comm, &r->itf));
    PetscCall(JRInterfaceSetFromOptions(r->itf));
    PetscCall(JRReduceCreate(comm, &r->red));
    PetscCall(JRReduceSetFromOptions(r->red));
    PetscCall(JRReduceGetRequest(r->red, &r->joints, &r->romm, NULL, &r->romsave, &r->romload));
    PetscCheck(r->help || !r->romm || r->joints || r->romload[0], comm, PETSC_ERR_ARG_INCOMP, "-rom_elements needs joints: -rom_joints strips|bolts|between|sides|zones|boxes|auto|onset");
    PetscCheck(r->help || !r->compare || r->joints || r->romload[0], comm, PETSC_ERR_ARG_WRONG, "-task compare needs a reduced model: joints (-rom_joints ..., optionally -rom_elements m) or -rom_load FILE");
    PetscCheck(!r->romsave[0] || (r->joints && r->romm > 0 && !(r->romload[0] && !r->compare)), comm, PETSC_ERR_ARG_INCOMP, "-rom_save saves a second-reduction model: it needs -rom_joints ... and -rom_elements m");
  }
  /* the harmonic balance's options; a loaded reduced model alone (-rom_load) has its own JRHBM, made later with these */
  PetscCall(JRHBMCreate(comm, &r->hbm));
  if (r->fe) PetscCall(JRHBMSetBasis(r->hbm, JR_HBM_BASIS_MIXED)); /* stuck + free-interface modes: -hbm_basis free for the thesis's */
  PetscCall(JRHBMSetFromOptions(r->hbm));
  if ((r->nlmodes || r->backbones) && !r->help) PetscCall(JRHBMCheckEPMC(r->hbm)); /* the reduced model's reads the same */
  { /* the continuation's options (-cont_*, -frf_force, the range): the case of a reduced model */
    JRCont    c;
    PetscInt  nl;
    PetscReal wmin, wmax, lv[64];
    PetscCall(JRContCreate(comm, &c));
    PetscCall(JRContSetFromOptions(c));
    PetscCall(JRContGetRange(c, &wmin, &wmax));
    PetscCall(JRContGetNumLevels(c, &nl));
    for (PetscInt l = 0; l < nl && l < 64; l++) PetscCall(JRContGetLevel(c, l, &lv[l]));
    if (r->red) PetscCall(JRReduceSetCase(r->red, wmin, wmax, PetscMin(nl, 64), lv));
    PetscCall(JRContDestroy(&c));
  }
  if (!r->nlmodes) {
    PetscCall(JRVerifyCreate(comm, &r->ver));
    PetscCall(JRVerifySetFromOptions(r->ver));
  }
  if (r->help) PetscFunctionReturn(0);
  PetscCall(JRPostCreate(comm, &r->post));
  PetscCall(JRPostSetOutput(r->post, r->base, r->plot));
  PetscCall(JROptionsCheck(comm, r->nlmodes ? "-task nlmodes" : r->fe ? (r->compare ? "-task compare" : "-task frf on an FE model") : "-task frf on a matrices model"));
  PetscCall(JRFileCheckOutput(comm, r->nlmodes ? "-nlm_output_file" : "-frf_output_file", r->base));
  if (r->fe) { /* the reduced model's file is not one of the results' */
    const char *const results[] = {".h5", "_n2n.h5", "_rom.h5", "_preload.h5", "_modes.h5", "_n2n_nlmodes.h5", "_rom_nlmodes.h5", NULL};
    PetscCall(JRFileCheckNotOutput(comm, "-rom_save", r->romsave, r->nlmodes ? "-nlm_output_file" : "-frf_output_file", r->base, results));
  }
  if (r->fe && r->romload[0] && !r->compare) PetscCall(JRHBMDestroy(&r->hbm));
  PetscFunctionReturn(0);
}

/* 1. the model; on an FE model the excitation and response DOFs, found by position (checked before the preload) */
static PetscErrorCode SetUpModel(FRFRun *r)
{
  MPI_Comm       comm = r->comm;
  const JRPairs *P    = NULL;
  PetscLogDouble t0, t1;
  PetscReal      lo[3], hi[3], dist;
  PetscInt       ndof;

  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(JR_StageModel));
  PetscCall(PetscTime(&t0));
  PetscCall(JRModelSetUp(r->model));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscLogStagePop());
  r->tmodel = t1 - t0;
  {
    DM dm;
    PetscCall(JRModelGetDM(r->model, &dm));
    if (dm) {
      PetscCall(JRModelGetPairs(r->model, &P));
      r->n2n = (PetscBool)(P && P->n > 0);
    }
  }
  PetscCheck(r->n2n || !r->fe, comm, PETSC_ERR_ARG_WRONG, "-task frf: the FE model has no contact interface (node pairs)");
  if (!r->n2n) PetscFunctionReturn(0);
  PetscCall(JRModelGetBoundingBox(r->model, lo, hi));
  if (!r->set) {
    r->at[0] = lo[0];
    r->at[1] = 0.5 * (lo[1] + hi[1]);
    r->at[2] = hi[2];
  }
  PetscCall(JRModelFindDof(r->model, r->at, r->dir, &r->fdof, &dist));
  r->fdist = dist;
  PetscCheck(dist <= 0.05 * (hi[0] - lo[0]), comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_at (%g, %g, %g) m: the nearest node is %g m away: the point is outside the model (box x %g..%g, y %g..%g, z %g..%g m)", (double)r->at[0], (double)r->at[1], (double)r->at[2], (double)dist, (double)lo[0], (double)hi[0], (double)lo[1], (double)hi[1], (double)lo[2], (double)hi[2]);
  if (!r->oset) {
    r->oat[0] = hi[0];
    r->oat[1] = 0.5 * (lo[1] + hi[1]);
    r->oat[2] = hi[2];
    r->oat[3] = r->at[0];
    r->oat[4] = r->at[1];
    r->oat[5] = r->at[2];
    r->no     = 6;
  }
  r->nout = r->no / 3;
  for (PetscInt o = 0; o < r->nout; o++) {
    PetscCall(JRModelFindDof(r->model, r->oat + 3 * o, r->dir, &r->odof[o], &dist));
    PetscCheck(dist <= 0.05 * (hi[0] - lo[0]), comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_output_at (%g, %g, %g) m: the nearest node is %g m away: the point is outside the model", (double)r->oat[3 * o], (double)r->oat[3 * o + 1], (double)r->oat[3 * o + 2], (double)dist);
  }
  PetscCall(JRModelGetNumDofs(r->model, &ndof));
  PetscCall(PetscPrintf(comm, "frf: node-to-node contact model, %" PetscInt_FMT " DOFs, %" PetscInt_FMT " interface pairs (model %.3g s)\n", ndof, P->n, (double)r->tmodel));
  PetscFunctionReturn(0);
}

/* 2. the preload and 4. the interface: the node-to-node elements, their joints (a first reduction) or a saved model */
static PetscErrorCode SetUpInterface(FRFRun *r)
{
  MPI_Comm         comm = r->comm;
  PetscLogDouble   t0, t1;
  JRPreloadSummary s;
  char             pbase[PETSC_MAX_PATH_LEN + 16];

  PetscFunctionBeginUser;
  if (r->romload[0] && !r->compare) { /* a saved reduced model: no preload, no interface, no fit */
    PetscCall(JRReduceLoad(r->red, r->model, &r->elr));
    r->isrom  = PETSC_TRUE;
    r->loaded = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogStagePush(JR_StagePreload));
  PetscCall(PetscTime(&t0));
  PetscCall(JRPreloadSolve(r->pre));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscLogStagePop());
  PetscCall(JRPreloadGetSummary(r->pre, &s));
  PetscCall(PetscPrintf(comm, "preload total_normal_force %.10g bolt_force_sum %.10g pairs_in_contact %" PetscInt_FMT " pairs %" PetscInt_FMT " (%.3g s)\n", (double)s.total_force, (double)s.bolt_force_sum, s.in_contact, s.pairs, (double)(t1 - t0)));
  if (r->base[0]) {
    PetscCall(PetscSNPrintf(pbase, sizeof(pbase), "%s_preload", r->base));
    PetscCall(JRPreloadWrite(r->pre, pbase, r->plot));
  }
  PetscCall(PetscLogStagePush(JR_StageInterface));
  {
    const JRElements *el;
    PetscCall(JRInterfaceSetUp(r->itf, r->model, r->pre));
    PetscCall(JRInterfaceGetElements(r->itf, &el, &r->pair));
    PetscCall(JRElementsDuplicate(el, &r->el));
  }
  PetscCall(JRPreloadDestroy(&r->pre)); /* the elements have its results: its factorisation of the structure is freed before the modes make theirs */
  PetscCall(JRReduceAssignJoints(r->red, r->model, &r->el, r->pair));
  PetscCall(PetscLogStagePop());
  PetscCall(JRInterfaceView(r->itf, NULL));
  if (r->el.joint) {
    r->isrom = PETSC_TRUE;
    PetscCall(JRElementsDuplicate(&r->el, &r->elj)); /* the joints, reduced below */
    PetscCall(PetscFree(r->el.joint));              /* the node-to-node model itself */
    r->el.njoints = 0;
  } else if (r->romload[0]) {
    PetscCall(JRReduceLoad(r->red, r->model, &r->elr));
    r->isrom  = PETSC_TRUE;
    r->loaded = PETSC_TRUE;
  }
  PetscFunctionReturn(0);
}

/* A node-to-node model's harmonic balance on the modes of another (r->hbm's, e.g. enriched), replacing it */
static PetscErrorCode ReplaceHBM(FRFRun *r)
{
  JRHBM h;

  PetscFunctionBeginUser;
  PetscCall(JRHBMCreate(r->comm, &h));
  PetscCall(JRHBMSetBasis(h, JR_HBM_BASIS_MIXED));
  PetscCall(JRHBMSetFromOptions(h));
  PetscCall(JRHBMSetExcitationDof(h, r->fdof, r->nout, r->odof));
  PetscCall(JRHBMSetOutputPoints(h, r->nout, r->oat, r->dir));
  PetscCall(JRHBMSetModel(h, r->model));
  PetscCall(JRHBMSetElements(h, &r->el));
  PetscCall(JRHBMSetModes(h, r->hbm));
  PetscCall(JRHBMSetUp(h));
  PetscCall(JRHBMDestroy(&r->hbm));
  r->hbm = h;
  PetscFunctionReturn(0);
}

/* The peak of level F's curve (quiet, no stability) over [wlo, whi] (0, 0: the whole range) on r->hbm: its frequency,
   amplitude and solution (a: the modal unknowns); *ok false if the curve did not complete */
static PetscErrorCode LevelPeak(FRFRun *r, PetscReal F, PetscReal wlo, PetscReal whi, PetscReal *w, PetscReal *amp, Vec a, PetscBool *ok)
{
  JRCont    c;
  PetscReal mis;

  PetscFunctionBeginUser;
  PetscCall(JRContCreate(r->comm, &c));
  PetscCall(JRContSetHBM(c, r->hbm));
  PetscCall(JRContSetFromOptions(c));
  PetscCall(JRContSetQuiet(c, PETSC_TRUE));
  PetscCall(JRContSetStability(c, PETSC_FALSE));
  PetscCall(JRContSetLevels(c, 1, &F));
  if (whi > wlo) PetscCall(JRContSetRange(c, wlo, whi));
  PetscCall(JRContSolve(c));
  PetscCall(JRContGetLevelComplete(c, 0, ok, &mis));
  PetscCall(JRContGetPeak(c, 0, w, amp));
  PetscCall(JRContGetPeakSolution(c, 0, a));
  PetscCall(JRContDestroy(&c));
  PetscFunctionReturn(0);
}

/*
  -modes_adapt N: the node-to-node basis adapted to the curves' peaks, round by round: every level's peak found (the
  first round over the whole range, then within 4% of the last peak, the whole range again if the peak lies at the
  window's edge), the peaks' contact forces' static responses outside the basis added where they deform the interface
  by more than -modes_adapt_tol times the springs' stretch (JRHBMEnrichBasis), the harmonic balance set up again on the
  enriched modes. It stops when a round adds nothing, when the peaks moved by less than -modes_adapt_move in amplitude
  (and a twentieth of it in frequency) with their deformation ratio below 100 times the tolerance, or after N rounds.
  Made for the mixed basis (the default) where the basis check warns: not when it passes (rho <= -modes_check_tol:
  every interface pattern's deformation outside the basis is below that many times the springs' stretch), is not made
  (-modes_check 0), or the basis is the free or stuck one asked for (-hbm_basis).
*/
static PetscErrorCode AdaptBasis(FRFRun *r)
{
  MPI_Comm       comm = r->comm;
  JRModes        md;
  PetscInt       rounds, nl = 0, nadd = 1, nm, basis;
  PetscReal      tol, mtol, rho, ctol, *wp, *ap, *lv, W0, W1, lmax = -1.0, dw = 0.0, da = 0.0;
  PetscLogDouble t0, t1;
  Vec            v, *a;
  PetscBool      small;

  PetscFunctionBeginUser;
  if (!r->n2n || r->loaded || !r->hbm) PetscFunctionReturn(0);
  PetscCall(JRHBMGetModes(r->hbm, &md));
  if (!md) PetscFunctionReturn(0);
  PetscCall(JRModesGetAdapt(md, &rounds, &tol, &mtol, NULL, NULL));
  PetscCall(JRHBMGetBasisCheck(r->hbm, &rho, NULL, &ctol, NULL, NULL));
  PetscCall(JRHBMGetBasis(r->hbm, &basis));
  if (!rounds || rho <= ctol || basis != JR_HBM_BASIS_MIXED || r->nlmodes) { /* rho < 0: no check; -hbm_basis free or stuck: as asked; no curves for -task nlmodes */
    PetscCall(JRModesEnrichEnd(md));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscTime(&t0));
  {
    JRCont c;
    PetscCall(JRContCreate(comm, &c));
    PetscCall(JRContSetHBM(c, r->hbm));
    PetscCall(JRContSetFromOptions(c));
    PetscCall(JRContGetNumLevels(c, &nl));
    PetscCall(JRContGetRange(c, &W0, &W1));
    PetscCall(PetscMalloc3(nl, &wp, nl, &ap, nl, &lv));
    for (PetscInt l = 0; l < nl; l++) PetscCall(JRContGetLevel(c, l, &lv[l]));
    PetscCall(JRContDestroy(&c));
  }
  for (PetscInt k = 0; k <= rounds; k++) {
    PetscLogDouble s0, s1, s2;
    PetscCall(PetscTime(&s0));
    PetscCall(JRHBMCreateVecs(r->hbm, &v, NULL));
    PetscCall(VecDuplicateVecs(v, nl, &a));
    dw = da = 0.0;
    for (PetscInt l = 0; l < nl; l++) {
      PetscReal w, amp, lo = 0.0, hi = 0.0;
      PetscBool ok;
      if (k) {
        lo = PetscMax(W0, 0.96 * wp[l]);
        hi = PetscMin(W1, 1.04 * wp[l]);
      }
      PetscCall(LevelPeak(r, lv[l], lo, hi, &w, &amp, a[l], &ok));
      if (k && (!ok || (lo > W0 && w < lo * (1 + 1e-3)) || (hi < W1 && w > hi * (1 - 1e-3)))) PetscCall(LevelPeak(r, lv[l], 0.0, 0.0, &w, &amp, a[l], &ok));
      if (k) {
        dw = PetscMax(dw, PetscAbsReal(w / wp[l] - 1));
        da = PetscMax(da, PetscAbsReal(amp / ap[l] - 1));
      }
      wp[l] = w;
      ap[l] = amp;
    }
    PetscCall(PetscTime(&s1));
    PetscCall(JRHBMGetSizes(r->hbm, &nm, NULL, NULL));
    nadd  = 0;
    small = (PetscBool)(k && da < mtol && dw < mtol / 20); /* then only what exceeds 100 tol */
    if (k < rounds) PetscCall(JRHBMEnrichBasis(r->hbm, nl, a, small ? 100 * tol : tol, &lmax, &nadd));
    PetscCall(PetscTime(&s2));
    PetscCall(VecDestroyVecs(nl, &a));
    PetscCall(VecDestroy(&v));
    if (k) PetscCall(PetscPrintf(comm, "basis adapt: round %" PetscInt_FMT " modes %" PetscInt_FMT " peaks moved %.2e in frequency %.2e in amplitude since the round before (the largest over the levels)\n", k, nm, (double)dw, (double)da));
    if (k < rounds) PetscCall(PetscPrintf(comm, "basis adapt: round %" PetscInt_FMT " modes %" PetscInt_FMT " peak_load_deformation %.3g tol %g added %" PetscInt_FMT " (peaks %.3g s, responses %.3g s)\n", k + 1, nm, (double)lmax, (double)(small ? 100 * tol : tol), nadd, (double)(s1 - s0), (double)(s2 - s1)));
    r->adapt_rounds = k + 1;
    r->adapt_lmax   = lmax;
    r->adapt_dw     = dw;
    r->adapt_da     = da;
    r->adapt_conv   = (PetscBool)(k < rounds && !nadd);
    if (!nadd) break;
    PetscCall(ReplaceHBM(r));
  }
  PetscCall(PetscFree3(wp, ap, lv));
  PetscCall(JRHBMGetModes(r->hbm, &md));
  PetscCall(JRModesEnrichEnd(md));
  PetscCall(JRModesGetAdapt(md, NULL, NULL, NULL, &r->adapt_added, NULL));
  PetscCall(JRModesSaveAdaptation(md, r->adapt_rounds, r->adapt_lmax, r->adapt_conv));
  PetscCall(PetscTime(&t1));
  r->adapt_s = t1 - t0;
  PetscFunctionReturn(0);
}

/* 3. the modes and the harmonic balance of the node-to-node (or matrices) model: its modes serve the reduced model too;
   5. the reduction and the reduced model's harmonic balance */
static PetscErrorCode SetUpModels(FRFRun *r)
{
  MPI_Comm       comm = r->comm;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  if (r->n2n) {
    char mfile[PETSC_MAX_PATH_LEN + 16];
    PetscInt nd;
    PetscCall(JRModelDOFsToNatural(r->model, 1, &r->fdof, &nd)); /* the DOF's number in the natural order: the same on any ranks */
    PetscCall(PetscPrintf(comm, "frf: excitation F sin(w t) along %s at (%g, %g, %g) m: natural DOF %" PetscInt_FMT " (node %.2g mm away)\n", Dirs[r->dir], (double)r->at[0], (double)r->at[1], (double)r->at[2], nd, (double)(r->fdist * 1e3)));
    for (PetscInt o = 0; o < r->nout; o++) {
      PetscCall(JRModelDOFsToNatural(r->model, 1, &r->odof[o], &nd));
      PetscCall(PetscPrintf(comm, "frf: response %" PetscInt_FMT " along %s at (%g, %g, %g) m: natural DOF %" PetscInt_FMT "\n", o + 1, Dirs[r->dir], (double)r->oat[3 * o], (double)r->oat[3 * o + 1], (double)r->oat[3 * o + 2], nd));
    }
    if (r->base[0] && r->hbm) { /* the modes are saved for reuse unless they are read (-modes_load) or saved elsewhere */
      PetscCall(PetscSNPrintf(mfile, sizeof(mfile), "%s_modes.h5", r->base));
      PetscCall(JRHBMSetModesFile(r->hbm, mfile));
    }
  }
  if (!r->loaded) {
    if (r->n2n) {
      PetscCall(JRHBMSetExcitationDof(r->hbm, r->fdof, r->nout, r->odof));
      PetscCall(JRHBMSetOutputPoints(r->hbm, r->nout, r->oat, r->dir));
    }
    PetscCall(JRHBMSetModel(r->hbm, r->model));
    if (r->n2n) PetscCall(JRHBMSetElements(r->hbm, &r->el));
    PetscCall(PetscLogStagePush(JR_StageModes));
    PetscCall(PetscTime(&t0));
    PetscCall(JRHBMSetUp(r->hbm));
    PetscCall(PetscTime(&t1));
    PetscCall(PetscLogStagePop());
    r->setn = t1 - t0;
    PetscCall(AdaptBasis(r));
  }
  PetscCall(PetscLogStagePush(JR_StageReduce));
  if (r->isrom && !r->loaded) { /* the reduction, from the joints of the node-to-node elements */
    PetscCall(JRReduceSetExcitation(r->red, r->fdof, r->nout, r->odof));
    PetscCall(JRReduceSetOutput(r->red, r->base, r->plot));
    PetscCall(JRReduceSetUp(r->red, r->model, r->hbm, &r->elj, &r->elr, &r->tred));
  }
  if (r->isrom) {
    if (r->loaded) PetscCall(JRReduceSetExcitation(r->red, r->fdof, r->nout, r->odof));
    PetscCall(JRReduceCreateHBM(r->red, r->model, r->hbm, r->loaded, &r->elr, &r->hbmr, &r->setr));
    if (r->loaded) { /* its own modes: no adaptation, so no factorisation kept for it */
      JRModes md;
      PetscCall(JRHBMGetModes(r->hbmr, &md));
      if (md) PetscCall(JRModesEnrichEnd(md));
    }
    PetscCall(JRHBMSetOutputPoints(r->hbmr, r->nout, r->oat, r->dir));
    PetscCall(JRReduceSave(r->red, r->model, &r->elr));
  }
  PetscCall(PetscLogStagePop());
  r->hbmc = r->isrom && !r->compare ? r->hbmr : r->hbm;
  PetscFunctionReturn(0);
}

/* The basis check (JRModesCheckBasis): the largest residual flexibility times contact stiffness of an interface
   pattern outside the basis, and a warning above -modes_check_tol */
static PetscErrorCode ViewBasisCheck(FRFRun *r)
{
  MPI_Comm       comm = r->comm;
  PetscReal      rho, rho0, tol;
  PetscInt       ns;
  PetscLogDouble t;
  JRModes        md;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetBasisCheck(r->hbmc, &rho, &rho0, &tol, &ns, &t));
  PetscCall(JRHBMGetModes(r->hbmc, &md));
  if (rho < 0 && md) { /* a basis read whose file records its adaptation (JRModesMix does not check it) */
    PetscInt  rounds, added;
    PetscReal deform;
    PetscBool conv;
    PetscCall(JRModesGetReadAdaptation(md, &rounds, &added, &deform, &conv));
    if (rounds && conv) PetscCall(PetscPrintf(comm, "basis check: not made: the basis read (-modes_load) was adapted to the peaks of the run that wrote it (%" PetscInt_FMT " vectors added in %" PetscInt_FMT " rounds, the last adding none: the peaks' contact forces deform the interface outside the basis by %.3g times the springs' stretch); it holds for that run's levels and excitation (-modes_adapt 0: checked against every interface pattern)\n", added, rounds, (double)deform));
  }
  if (rho < 0) PetscFunctionReturn(0);
  PetscCall(PetscPrintf(comm, "basis check: rho %.3g rho_modes %.3g static_vectors %" PetscInt_FMT " seconds %.3g (rho: the largest interface residual flexibility x contact stiffness outside the basis; rho_modes: the same without the static correction vectors)\n", (double)rho, (double)rho0, ns, (double)t));
  if (r->adapt_rounds) {
    PetscCall(PetscPrintf(comm, "basis adapt: %" PetscInt_FMT " vectors added in %" PetscInt_FMT " rounds (%.3g s); the peaks' contact forces deform the interface outside the basis by %.3g times the springs' stretch, the last round moved the peaks by %.2e in frequency and %.2e in amplitude\n", r->adapt_added, r->adapt_rounds, (double)r->adapt_s, (double)r->adapt_lmax, (double)r->adapt_dw, (double)r->adapt_da));
    if (!r->adapt_conv) PetscCall(PetscPrintf(comm, "WARNING basis adapt: not converged after %" PetscInt_FMT " rounds (-modes_adapt): the peaks may still move with a larger basis\n", r->adapt_rounds));
  } else if (rho > tol) PetscCall(PetscPrintf(comm, "WARNING basis check %.3g > -modes_check_tol %g: the basis misses the interface's local compliance and the peaks may move with a larger basis; -modes_adapt adapts it to the peaks, or raise -modes_static_max\n", (double)rho, (double)tol));
  PetscFunctionReturn(0);
}

/* The harmonic balance's size, damping and modal basis */
static PetscErrorCode ViewBasis(FRFRun *r)
{
  MPI_Comm         comm = r->comm;
  PetscInt         nm, H, n, nmod;
  const PetscReal *om;
  const char      *damping, *cinfo;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetSizes(r->hbmc, &nm, &H, &n));
  PetscCall(JRHBMGetDampingDescription(r->hbmc, &damping));
  PetscCall(JRHBMGetModalFrequencies(r->hbmc, &nmod, &om));
  PetscCall(JRHBMGetSolveSize(r->isrom ? r->hbmr : r->hbmc, NULL, &cinfo));
  if (nmod) PetscCall(PetscPrintf(comm, "frf: %" PetscInt_FMT " modes (%.6g .. %.6g Hz), %" PetscInt_FMT " harmonics + mean, %" PetscInt_FMT " unknowns; damping: %s\n", nm, (double)(om[0] / (2 * PETSC_PI)), (double)(om[nmod - 1] / (2 * PETSC_PI)), H, n, damping));
  if (cinfo[0]) PetscCall(PetscPrintf(comm, "frf: reduced model %s\n", cinfo));
  else if (!nmod) PetscCall(PetscPrintf(comm, "frf: %" PetscInt_FMT " physical coordinates, %" PetscInt_FMT " harmonics + mean, %" PetscInt_FMT " unknowns; damping: %s\n", nm, H, n, damping));
  if (r->n2n) {
    PetscInt b;
    PetscCall(JRHBMGetBasis(r->hbmc, &b));
    PetscCall(PetscPrintf(comm, "frf: modes and projections %.3g s; modes of the %s [Hz]:", (double)(r->setn + r->setr), b == JR_HBM_BASIS_MIXED ? "mixed basis (Ritz, stuck + free)" : b == JR_HBM_BASIS_STUCK ? "stuck structure" : "free interface"));
    for (PetscInt i = 0; i < nmod; i++) PetscCall(PetscPrintf(comm, " %.5g", (double)(om[i] / (2 * PETSC_PI))));
    PetscCall(PetscPrintf(comm, "\n"));
    PetscCall(ViewBasisCheck(r));
  }
  PetscFunctionReturn(0);
}

/* 6. the curves: of the one model, or of both (-task compare) with their comparison */
static PetscErrorCode Solve(FRFRun *r)
{
  MPI_Comm  comm = r->comm;
  PetscReal sn, sr;

  PetscFunctionBeginUser;
  if (r->nlmodes) {
    PetscCall(JRTaskNLModesSolve(comm, r->nlm, r->hbmc));
    PetscFunctionReturn(0);
  }
  if (r->compare && !r->curves) PetscFunctionReturn(0);
  if (r->compare) {
    char bn[PETSC_MAX_PATH_LEN + 8], br[PETSC_MAX_PATH_LEN + 8];
    PetscCall(PetscSNPrintf(bn, sizeof(bn), "%s%s", r->base, r->base[0] ? "_n2n" : ""));
    PetscCall(PetscSNPrintf(br, sizeof(br), "%s%s", r->base, r->base[0] ? "_rom" : ""));
    PetscCall(PetscPrintf(comm, "compare: node-to-node model\n"));
    PetscCall(Curves(comm, r->post, r->hbm, bn, &r->cont, &r->tn, &sn, &r->en));
    PetscCall(PetscPrintf(comm, "frf: solve (HBM + continuation, every level) node-to-node %.4g s, stability %.4g s\n", (double)r->tn, (double)sn));
    PetscCall(PetscPrintf(comm, "compare: reduced model\n"));
    PetscCall(Curves(comm, r->post, r->hbmr, br, &r->contr, &r->tr, &sr, &r->er));
    PetscCall(PetscPrintf(comm, "frf: solve (HBM + continuation, every level) reduced %.4g s, stability %.4g s\n", (double)r->tr, (double)sr));
    {
      const JRCompareTimes t = {r->tn, r->tr, r->en, r->er, r->setn, r->setr, r->tred};
      PetscCall(JRPostCompareReport(r->post, r->cont, r->contr, &r->el, &r->elr, &t));
      if (r->elj.joint && r->elr.joint) PetscCall(JRPostCompareJoints(r->post, r->cont, r->contr, &r->elj, &r->elr));
    }
    r->contc = r->cont;
  } else {
    PetscCall(Curves(comm, r->post, r->hbmc, r->base[0] ? r->base : NULL, r->isrom ? &r->contr : &r->cont, &r->tn, &sn, NULL));
    PetscCall(PetscPrintf(comm, "frf: solve (HBM + continuation, every level) %.4g s, stability %.4g s\n", (double)r->tn, (double)sn));
    r->contc = r->isrom ? r->contr : r->cont;
  }
  PetscFunctionReturn(0);
}

/* -task compare -compare_nlmodes: the node-to-node backbone, the reduced model's over the same amplitudes, their
   comparison (after the curves and their check by time integration: the harmonic balances become autonomous) */
static PetscErrorCode Backbones(FRFRun *r)
{
  MPI_Comm  comm = r->comm;
  PetscReal amin, amax;

  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(comm, "compare: node-to-node model, nonlinear mode\n"));
  PetscCall(JRTaskNLModesSolve(comm, r->nlm, r->hbm));
  PetscCall(JRNLModesGetRange(r->nlm, &amin, &amax));
  PetscCall(JRNLModesSetRange(r->nlmr, amin, amax));
  PetscCall(PetscPrintf(comm, "compare: reduced model, nonlinear mode\n"));
  PetscCall(JRTaskNLModesSolve(comm, r->nlmr, r->hbmr));
  PetscCall(JRPostCompareBackbones(r->post, r->nlm, r->nlmr));
  PetscFunctionReturn(0);
}

/* 7. the stuck structure's frequencies beside the lowest level's peak (and, with -frf_stick_fe, the whole FE model's),
   the contact maps at the peaks, the peak memory */
static PetscErrorCode Report(FRFRun *r)
{
  MPI_Comm comm = r->comm;

  PetscFunctionBeginUser;
  if (r->n2n && r->contc) {
    PetscReal *fs, w, a, best = 0, fe[64];
    PetscInt   nf, nm;
    PetscCall(JRHBMGetSizes(r->hbmc, &nm, NULL, NULL));
    PetscCall(PetscMalloc1(nm, &fs));
    PetscCall(JRHBMStickFrequencies(r->hbmc, &nf, fs));
    PetscCall(JRContGetPeak(r->contc, 0, &w, &a));
    for (PetscInt i = 0; i < nf; i++)
      if (PetscAbsReal(fs[i] - w / (2 * PETSC_PI)) < PetscAbsReal(best - w / (2 * PETSC_PI))) best = fs[i];
    PetscCall(PetscPrintf(comm, "frf: stuck structure%s, modal basis of %" PetscInt_FMT " modes [Hz]:", r->hbmc == r->hbmr ? " (reduced model)" : "", nm));
    for (PetscInt i = 0; i < nf; i++) PetscCall(PetscPrintf(comm, " %.6g", (double)fs[i]));
    PetscCall(PetscPrintf(comm, "\n"));
    PetscCall(PetscPrintf(comm, "stick freq_hz %.8g modes %" PetscInt_FMT " lowest_level_peak_hz %.8g rel %.3e\n", (double)best, nm, (double)(w / (2 * PETSC_PI)), (double)(w / (2 * PETSC_PI) / best - 1)));
    if (r->stickfe) {
      PetscInt       nfe = PetscMin(nm, 64);
      PetscReal      bfe = 0;
      PetscLogDouble t0, t1;
      PetscCall(PetscTime(&t0));
      PetscCall(StickFE(r->model, r->loaded ? &r->elr : &r->el, nfe, fe));
      PetscCall(PetscTime(&t1));
      PetscCall(PetscPrintf(comm, "frf: stuck structure, full FE model with the element springs (SLEPc, %.3g s) [Hz]:", (double)(t1 - t0)));
      for (PetscInt i = 0; i < nfe; i++) PetscCall(PetscPrintf(comm, " %.6g", (double)fe[i]));
      PetscCall(PetscPrintf(comm, "\n"));
      for (PetscInt i = 0; i < nfe; i++)
        if (PetscAbsReal(fe[i] - best) < PetscAbsReal(bfe - best)) bfe = fe[i];
      PetscCall(PetscPrintf(comm, "stick_fe freq_hz %.8g modal_freq_hz %.8g truncation_error %.3e\n", (double)bfe, (double)best, (double)(best / bfe - 1)));
    }
    PetscCall(PetscFree(fs));
    if (r->base[0] && r->contc == r->cont && r->cont) PetscCall(JRPostWriteContactMaps(r->post, r->model, r->cont, &r->el, r->pair));
  }
  { /* peak resident memory of the processes */
    struct rusage ru;
    PetscReal     mb[2], mx[2];
    getrusage(RUSAGE_SELF, &ru);
    mb[0] = mb[1] = ru.ru_maxrss / 1024.0;
    PetscCall(MPIU_Allreduce(&mb[0], &mx[0], 1, MPIU_REAL, MPIU_MAX, comm));
    PetscCall(MPIU_Allreduce(&mb[1], &mx[1], 1, MPIU_REAL, MPIU_SUM, comm));
    PetscCall(PetscPrintf(comm, "frf: peak memory %.1f MB per process (largest), %.1f MB in all\n", (double)mx[0], (double)mx[1]));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy(FRFRun *r)
{
  PetscFunctionBeginUser;
  PetscCall(JRVerifyDestroy(&r->ver));
  PetscCall(JRNLModesDestroy(&r->nlm));
  PetscCall(JRNLModesDestroy(&r->nlmr));
  PetscCall(JRContDestroy(&r->contr));
  PetscCall(JRContDestroy(&r->cont));
  PetscCall(JRHBMDestroy(&r->hbmr));
  PetscCall(JRHBMDestroy(&r->hbm));
  PetscCall(JRPreloadDestroy(&r->pre));
  PetscCall(JRReduceDestroy(&r->red));
  PetscCall(JRPostDestroy(&r->post));
  PetscCall(JRElementsDestroy(&r->el));
  PetscCall(JRElementsDestroy(&r->elr));
  PetscCall(JRElementsDestroy(&r->elj));
  PetscCall(JRInterfaceDestroy(&r->itf));
  PetscCall(JRModelDestroy(&r->model));
  PetscFunctionReturn(0);
}

/* The pipeline: options (all, checked), model, preload and interface, modes and harmonic balance, reduction, curves,
   outputs */
static PetscErrorCode FRF(MPI_Comm comm, PetscBool compare, PetscBool nlmodes)
{
  FRFRun r;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&r, sizeof(r)));
  r.comm    = comm;
  r.compare = compare;
  r.nlmodes = nlmodes;
  r.plot    = PETSC_TRUE;
  r.curves  = PETSC_TRUE;
  r.dir     = 2;
  r.nd      = 3;
  r.no      = 63;
  r.romsave = r.romload = "";
  PetscCall(PetscStrncpy(r.base, "out/frf", sizeof(r.base)));
  PetscCall(SetFromOptions(&r));
  if (r.help) {
    PetscCall(JROptionsHelpSolvers(comm, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE));
    PetscCall(Destroy(&r));
    PetscFunctionReturn(0);
  }
  PetscCall(SetUpModel(&r));
  if (r.n2n) PetscCall(SetUpInterface(&r));
  PetscCall(SetUpModels(&r));
  PetscCall(ViewBasis(&r));
  PetscCall(Solve(&r));
  if (r.ver && r.contc) PetscCall(JRVerifyCurves(r.ver, r.hbmc, r.contc));
  if (r.backbones) PetscCall(Backbones(&r));
  PetscCall(Report(&r));
  if (r.cont) PetscCall(JRContCheckComplete(r.cont)); /* an incomplete curve or backbone: an error once everything is written */
  if (r.contr) PetscCall(JRContCheckComplete(r.contr));
  if (r.nlm) PetscCall(JRTaskNLModesCheckComplete(comm, r.nlm));
  if (r.nlmr) PetscCall(JRTaskNLModesCheckComplete(comm, r.nlmr));
  PetscCall(Destroy(&r));
  PetscFunctionReturn(0);
}

PetscErrorCode JRTaskFRF(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  PetscCall(FRF(comm, PETSC_FALSE, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/*
  -task compare: node-to-node and reduced model of one case in one run, sharing the FE model, preload and modes:
  FRF overlays per level (BASE_compare.png), BASE_compare.csv, and per level
  "compare level <F> n2n_freq_hz <f> rom_freq_hz <f> n2n_amp <a> rom_amp <a> n2n_s <t> rom_s <t>"; with
  -compare_nlmodes also both backbones over the same amplitudes (BASE_nlmodes_compare.csv, .png, "compare backbone"
  lines; JRPostCompareBackbones), and with -compare_frf 0 the backbones alone.
*/
PetscErrorCode JRTaskCompare(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  PetscCall(FRF(comm, PETSC_TRUE, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* -task nlmodes: the model, preload, interface, modes and harmonic balance of -task frf, then the backbone of a
   nonlinear mode (src/task/nlmodes.c) */
PetscErrorCode JRTaskFRFPipeline(MPI_Comm comm, PetscBool nlmodes)
{
  PetscFunctionBeginUser;
  PetscCall(FRF(comm, PETSC_FALSE, nlmodes));
  PetscFunctionReturn(0);
}
