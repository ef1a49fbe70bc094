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
#include <jointrom.h>
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
  PetscCall(JRElementsCreateStuckStiffness(K, el, &B, NULL));
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
   continuation's wall time (every level); elem (may be NULL): its part in the contact elements (JRHBMGetElementTime) */
static PetscErrorCode Curves(MPI_Comm comm, JRHBM hbm, const char base[], JRCont *cont, PetscReal *seconds, PetscReal *elem)
{
  PetscLogDouble t0, t1, e0, e1;

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
  *seconds = t1 - t0;
  if (elem) *elem = e1 - e0;
  PetscCall(PetscLogStagePush(JR_StagePost));
  PetscCall(JRContWrite(*cont));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}


static PetscErrorCode FRF(MPI_Comm comm, PetscBool compare)
{
  JRModel         model;
  JRPreload       pre = NULL;
  JRHBM           hbm = NULL, hbmr = NULL, hbmc;
  JRCont          cont = NULL, contr = NULL, contc;
  const JRPairs  *P;
  const char     *damping;
  JRReduce        red = NULL;
  JRPost          post = NULL;
  PetscInt        nm, H, n, *pair = NULL, romm = 0, fdof = 0, nout = 0, odof[21];
  PetscBool       n2n, fe, help, joints = PETSC_FALSE, set = PETSC_FALSE, oset = PETSC_FALSE, stickfe = PETSC_FALSE, plot = PETSC_TRUE, isrom = PETSC_FALSE, loaded = PETSC_FALSE;
  JRElements      el, elr, elj;
  char            base[PETSC_MAX_PATH_LEN] = "out/frf";
  const char     *romsave = "", *romload = "";
  PetscLogDouble  t0, t1, tpre = 0, tmodel;
  PetscReal       tn = 0, tr = 0, en = 0, er = 0, setn = 0, setr = 0, tred = 0;
  PetscInt        dir = 2, nd = 3, no = 63;
  PetscReal       at[3] = {0, 0, 0}, oat[63] = {0};
  const char     *dirs[] = {"x", "y", "z"};
  JRInterfaceOptions iopt;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&el, sizeof(el)));
  PetscCall(PetscMemzero(&elr, sizeof(elr)));
  PetscCall(PetscMemzero(&elj, sizeof(elj)));
  /* every object's options, read and checked before any work (with -help: listed, not checked) */
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  PetscCall(JRModelCreate(comm, &model));
  PetscCall(JRModelSetFromOptions(model));
  {
    JRModelType mt;
    PetscCall(JRModelGetType(model, &mt));
    fe = (PetscBool)strcmp(mt, JRMODELMATRICES);
  }
  PetscOptionsBegin(comm, NULL, "Frequency response (-task frf, -task compare)", "JRTaskFRF");
  PetscCall(PetscOptionsString("-frf_output_file", "Output base name", "JRTaskFRF", base, base, sizeof(base), NULL));
  PetscCall(PetscOptionsBool("-frf_plot", "Draw the PNG plots", "JRTaskFRF", plot, &plot, NULL));
  if (fe || help) {
    PetscCall(PetscOptionsBool("-frf_stick_fe", "Also the natural frequencies of the whole FE model with every element stuck (SLEPc): the modal truncation error", "JRTaskFRF", stickfe, &stickfe, NULL));
  }
  PetscOptionsEnd();
  PetscCheck(help || fe || !compare, comm, PETSC_ERR_ARG_WRONG, "-task compare needs an FE model with a contact interface (-model_type brb, lap1, lap3, lap, gmsh)");
  if (fe || help) {
    PetscBool d, o;
    PetscOptionsBegin(comm, NULL, "Excitation and responses of an FE model (-task frf)", "JRTaskFRF");
    PetscCall(PetscOptionsRealArray("-frf_at", "Excitation point x,y,z [m] (nearest node; default: the end x = xmin, mid-width, top)", "JRTaskFRF", at, &nd, &set));
    PetscCall(PetscOptionsEList("-frf_dir", "Direction of the excitation force and of the responses", "JRTaskFRF", dirs, 3, dirs[dir], &dir, NULL));
    PetscCall(PetscOptionsRealArray("-frf_output_at", "Response points x1,y1,z1,x2,... [m] (default: the other end, then the excitation point)", "JRTaskFRF", oat, &no, &oset));
    PetscOptionsEnd();
    PetscCheck(!set || nd == 3, comm, PETSC_ERR_ARG_WRONG, "-frf_at needs three coordinates x,y,z [m], got %" PetscInt_FMT, nd);
    PetscCheck(!oset || (no % 3 == 0 && no > 0), comm, PETSC_ERR_ARG_WRONG, "-frf_output_at needs triples x,y,z [m], got %" PetscInt_FMT " values", no);
    PetscCall(PetscOptionsHasName(NULL, NULL, "-frf_dof", &d));
    PetscCall(PetscOptionsHasName(NULL, NULL, "-frf_output", &o));
    PetscCheck(help || !fe || (!d && !o), comm, PETSC_ERR_ARG_INCOMP, "%s: on an FE model the DOF numbers depend on the partition; give points instead: -frf_at x,y,z and -frf_output_at x,y,z,... [m] with -frf_dir x|y|z", d ? "-frf_dof" : "-frf_output");
    PetscCall(JRPreloadCreate(comm, &pre));
    PetscCall(JRPreloadSetModel(pre, model));
    PetscCall(JRPreloadSetFromOptions(pre));
    PetscCall(JRInterfaceSetFromOptions(comm, &iopt));
    PetscCall(JRReduceCreate(comm, &red));
    PetscCall(JRReduceSetFromOptions(red));
    PetscCall(JRReduceGetRequest(red, &joints, &romm, NULL, &romsave, &romload));
    PetscCheck(help || !romm || joints || romload[0], comm, PETSC_ERR_ARG_INCOMP, "-rom_elements needs joints: -rom_joints strips|bolts|between|sides|zones");
    PetscCheck(help || !compare || joints || romload[0], comm, PETSC_ERR_ARG_WRONG, "-task compare needs a reduced model: joints (-rom_joints ..., optionally -rom_elements m) or -rom_load FILE");
    PetscCheck(!romsave[0] || (joints && romm > 0 && !(romload[0] && !compare)), comm, PETSC_ERR_ARG_INCOMP, "-rom_save saves a second-reduction model: it needs -rom_joints ... and -rom_elements m");
  }
  /* the harmonic balance's options; a loaded reduced model alone (-rom_load) has its own JRHBM, made later with these */
  PetscCall(JRHBMCreate(comm, &hbm));
  if (fe) PetscCall(JRHBMSetBasis(hbm, JR_HBM_BASIS_MIXED)); /* stuck + free-interface modes: -hbm_basis free for the thesis's */
  PetscCall(JRHBMSetFromOptions(hbm));
  { /* the continuation's options (-cont_*, -frf_force, the range): the case of a reduced model */
    JRCont    c;
    PetscInt  nl;
    PetscReal wmin, wmax, lv[64];
    PetscCall(JRContCreate(comm, &c));
    PetscCall(JRContSetFromOptions(c));
    PetscCall(JRContGetRange(c, &wmin, &wmax));
    PetscCall(JRContGetNumLevels(c, &nl));
    for (PetscInt l = 0; l < nl && l < 64; l++) PetscCall(JRContGetLevel(c, l, &lv[l]));
    if (red) PetscCall(JRReduceSetCase(red, wmin, wmax, PetscMin(nl, 64), lv));
    PetscCall(JRContDestroy(&c));
  }
  if (help) { /* -help: the options listed, nothing done */
    PetscCall(JROptionsHelpSolvers(comm, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE));
    PetscCall(JRReduceDestroy(&red));
    PetscCall(JRHBMDestroy(&hbm));
    PetscCall(JRPreloadDestroy(&pre));
    PetscCall(JRModelDestroy(&model));
    PetscFunctionReturn(0);
  }
  PetscCall(JRPostCreate(comm, &post));
  PetscCall(JRPostSetOutput(post, base, plot));
  PetscCall(JROptionsCheck(comm, fe ? (compare ? "-task compare" : "-task frf on an FE model") : "-task frf on a matrices model"));
  PetscCall(JRFileCheckOutput(comm, "-frf_output_file", base));
  if (fe && romload[0] && !compare) PetscCall(JRHBMDestroy(&hbm));

  /* 1. model */
  PetscCall(PetscLogStagePush(JR_StageModel));
  PetscCall(PetscTime(&t0));
  PetscCall(JRModelSetUp(model));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscLogStagePop());
  tmodel = t1 - t0;
  P   = NULL;
  n2n = PETSC_FALSE;
  {
    DM dm;
    PetscCall(JRModelGetDM(model, &dm));
    if (dm) {
      PetscCall(JRModelGetPairs(model, &P));
      n2n = (PetscBool)(P && P->n > 0);
    }
  }
  PetscCheck(n2n || !fe, comm, PETSC_ERR_ARG_WRONG, "-task frf: the FE model has no contact interface (node pairs)");

  if (n2n) {
    PetscInt         ndof;
    PetscReal        lo[3], hi[3], dist, fdist;
    JRPreloadSummary s;
    char             pbase[PETSC_MAX_PATH_LEN + 16], mfile[PETSC_MAX_PATH_LEN + 16];

    /* excitation and responses by position, checked before the preload */
    PetscCall(JRModelGetBoundingBox(model, lo, hi));
    if (!set) {
      at[0] = lo[0];
      at[1] = 0.5 * (lo[1] + hi[1]);
      at[2] = hi[2];
    }
    PetscCall(JRModelFindDof(model, at, dir, &fdof, &dist));
    fdist = dist;
    PetscCheck(dist <= 0.05 * (hi[0] - lo[0]), comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_at (%g, %g, %g) m: the nearest node is %g m away: the point is outside the model (box x %g..%g, y %g..%g, z %g..%g m)", (double)at[0], (double)at[1], (double)at[2], (double)dist, (double)lo[0], (double)hi[0], (double)lo[1], (double)hi[1], (double)lo[2], (double)hi[2]);
    if (!oset) {
      oat[0] = hi[0];
      oat[1] = 0.5 * (lo[1] + hi[1]);
      oat[2] = hi[2];
      oat[3] = at[0];
      oat[4] = at[1];
      oat[5] = at[2];
      no     = 6;
    }
    nout = no / 3;
    for (PetscInt o = 0; o < nout; o++) {
      PetscCall(JRModelFindDof(model, oat + 3 * o, dir, &odof[o], &dist));
      PetscCheck(dist <= 0.05 * (hi[0] - lo[0]), comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_output_at (%g, %g, %g) m: the nearest node is %g m away: the point is outside the model", (double)oat[3 * o], (double)oat[3 * o + 1], (double)oat[3 * o + 2], (double)dist);
    }
    PetscCall(JRModelGetNumDofs(model, &ndof));
    PetscCall(PetscPrintf(comm, "frf: node-to-node contact model, %" PetscInt_FMT " DOFs, %" PetscInt_FMT " interface pairs (model %.3g s)\n", ndof, P->n, (double)tmodel));
    if (romload[0] && !compare) { /* a saved reduced model: no preload, no interface, no fit */
      PetscCall(JRReduceLoad(red, model, &elr));
      isrom  = PETSC_TRUE;
      loaded = PETSC_TRUE;
    } else {
      /* 2. preload */
      PetscCall(PetscLogStagePush(JR_StagePreload));
      PetscCall(PetscTime(&t0));
      PetscCall(JRPreloadSolve(pre));
      PetscCall(PetscTime(&t1));
      PetscCall(PetscLogStagePop());
      tpre = t1 - t0;
      PetscCall(JRPreloadGetSummary(pre, &s));
      PetscCall(PetscPrintf(comm, "preload total_normal_force %.10g bolt_force_sum %.10g pairs_in_contact %" PetscInt_FMT " pairs %" PetscInt_FMT " (%.3g s)\n", (double)s.total_force, (double)s.bolt_force_sum, s.in_contact, s.pairs, (double)tpre));
      if (base[0]) {
        PetscCall(PetscSNPrintf(pbase, sizeof(pbase), "%s_preload", base));
        PetscCall(JRPreloadWrite(pre, pbase, plot));
      }
      /* 4. interface, and the reduced model from its joints */
      PetscCall(PetscLogStagePush(JR_StageInterface));
      PetscCall(JRInterfaceCreateElements(model, pre, &iopt, &el, &pair));
      PetscCall(JRReduceAssignJoints(red, model, &el, pair));
      PetscCall(PetscLogStagePop());
      {
        PetscReal nsum = 0, nmin = PETSC_MAX_REAL, nmax = -PETSC_MAX_REAL;
        for (PetscInt e = 0; e < el.n; e++) {
          nsum += el.n0[e];
          nmin = PetscMin(nmin, el.n0[e]);
          nmax = PetscMax(nmax, el.n0[e]);
        }
        PetscCall(PetscPrintf(comm, "interface: %" PetscInt_FMT " %s elements (kt %g N/m, kn %g N/m, mu %g), n0 %.4g .. %.4g N, sum %.6g N\n", el.n, el.typename[0], (double)el.kt[0], (double)el.kn[0], (double)el.mu[0], (double)nmin, (double)nmax, (double)nsum));
      }
      if (el.joint) {
        isrom = PETSC_TRUE;
        PetscCall(JRElementsDuplicate(&el, &elj)); /* the joints, reduced below */
        PetscCall(PetscFree(el.joint));           /* the node-to-node model itself */
        el.njoints = 0;
      } else if (romload[0]) {
        PetscCall(JRReduceLoad(red, model, &elr));
        isrom  = PETSC_TRUE;
        loaded = PETSC_TRUE;
      }
    }
    PetscCall(PetscPrintf(comm, "frf: excitation F sin(w t) along %s at (%g, %g, %g) m: DOF %" PetscInt_FMT " (node %.2g mm away)\n", dirs[dir], (double)at[0], (double)at[1], (double)at[2], fdof, (double)(fdist * 1e3)));
    for (PetscInt o = 0; o < nout; o++) PetscCall(PetscPrintf(comm, "frf: response %" PetscInt_FMT " along %s at (%g, %g, %g) m: DOF %" PetscInt_FMT "\n", o + 1, dirs[dir], (double)oat[3 * o], (double)oat[3 * o + 1], (double)oat[3 * o + 2], odof[o]));
    /* the modes are saved for reuse unless they are read (-modes_load) or saved elsewhere (-modes_save) */
    if (base[0] && hbm) {
      PetscCall(PetscSNPrintf(mfile, sizeof(mfile), "%s_modes.h5", base));
      PetscCall(JRHBMSetModesFile(hbm, mfile));
    }
  }
  /* the node-to-node (or matrices) model: its modes serve the reduced model too */
  if (!loaded) {
    if (n2n) {
      PetscCall(JRHBMSetExcitationDof(hbm, fdof, nout, odof));
      PetscCall(JRHBMSetOutputPoints(hbm, nout, oat, dir));
      PetscCall(JRModelSetElements(model, &el));
    }
    PetscCall(JRHBMSetModel(hbm, model));
    PetscCall(PetscLogStagePush(JR_StageModes));
    PetscCall(PetscTime(&t0));
    PetscCall(JRHBMSetUp(hbm));
    PetscCall(PetscTime(&t1));
    PetscCall(PetscLogStagePop());
    setn = t1 - t0;
  }
  PetscCall(PetscLogStagePush(JR_StageReduce));
  if (isrom && !loaded) { /* the reduction, from the joints of the node-to-node elements */
    PetscCall(JRReduceSetExcitation(red, fdof, nout, odof));
    PetscCall(JRReduceSetOutput(red, base, plot));
    PetscCall(JRReduceSetUp(red, model, hbm, &elj, &elr, &tred));
  }
  if (isrom) {
    if (loaded) PetscCall(JRReduceSetExcitation(red, fdof, nout, odof));
    PetscCall(JRReduceCreateHBM(red, model, hbm, loaded, &elr, &hbmr, &setr));
    PetscCall(JRHBMSetOutputPoints(hbmr, nout, oat, dir));
    PetscCall(JRReduceSave(red, model, &elr));
  }
  PetscCall(PetscLogStagePop());
  hbmc = isrom && !compare ? hbmr : hbm;
  PetscCall(JRHBMGetSizes(hbmc, &nm, &H, &n));
  PetscCall(JRHBMGetDampingDescription(hbmc, &damping));
  {
    PetscInt         nmod;
    const PetscReal *om;
    PetscCall(JRHBMGetModalFrequencies(hbmc, &nmod, &om));
    const char *cinfo;
    PetscCall(JRHBMGetSolveSize(isrom ? hbmr : hbmc, NULL, &cinfo));
    if (nmod) PetscCall(PetscPrintf(comm, "frf: %" PetscInt_FMT " modes (%.6g .. %.6g Hz), %" PetscInt_FMT " harmonics + mean, %" PetscInt_FMT " unknowns; damping: %s\n", nm, (double)(om[0] / (2 * PETSC_PI)), (double)(om[nmod - 1] / (2 * PETSC_PI)), H, n, damping));
    if (cinfo[0]) PetscCall(PetscPrintf(comm, "frf: reduced model %s\n", cinfo));
    else PetscCall(PetscPrintf(comm, "frf: %" PetscInt_FMT " physical coordinates, %" PetscInt_FMT " harmonics + mean, %" PetscInt_FMT " unknowns; damping: %s\n", nm, H, n, damping));
    if (n2n) {
      PetscInt b;
      PetscCall(JRHBMGetBasis(hbmc, &b));
      PetscCall(PetscPrintf(comm, "frf: modes and projections %.3g s; modes of the %s [Hz]:", (double)(setn + setr), b == 2 ? "mixed basis (Ritz, stuck + free)" : b ? "stuck structure" : "free interface"));
      for (PetscInt i = 0; i < nmod; i++) PetscCall(PetscPrintf(comm, " %.5g", (double)(om[i] / (2 * PETSC_PI))));
      PetscCall(PetscPrintf(comm, "\n"));
    }
  }
  if (compare) {
    char bn[PETSC_MAX_PATH_LEN + 8], br[PETSC_MAX_PATH_LEN + 8];
    PetscCall(PetscSNPrintf(bn, sizeof(bn), "%s%s", base, base[0] ? "_n2n" : ""));
    PetscCall(PetscSNPrintf(br, sizeof(br), "%s%s", base, base[0] ? "_rom" : ""));
    PetscCall(PetscPrintf(comm, "compare: node-to-node model\n"));
    PetscCall(Curves(comm, hbm, bn, &cont, &tn, &en));
    PetscCall(PetscPrintf(comm, "frf: solve (HBM + continuation, every level) node-to-node %.4g s\n", (double)tn));
    PetscCall(PetscPrintf(comm, "compare: reduced model\n"));
    PetscCall(Curves(comm, hbmr, br, &contr, &tr, &er));
    PetscCall(PetscPrintf(comm, "frf: solve (HBM + continuation, every level) reduced %.4g s\n", (double)tr));
    {
      const JRCompareTimes t = {tn, tr, en, er, setn, setr, tred};
      PetscCall(JRPostCompareReport(post, cont, contr, &el, &elr, &t));
    }
    contc = cont;
  } else {
    PetscCall(Curves(comm, hbmc, base[0] ? base : NULL, isrom ? &contr : &cont, &tn, NULL));
    PetscCall(PetscPrintf(comm, "frf: solve (HBM + continuation, every level) %.4g s\n", (double)tn));
    contc = isrom ? contr : cont;
  }
  if (n2n) {
    PetscReal *fs, w, a, best = 0, fe[64];
    PetscInt   nf;
    PetscCall(PetscMalloc1(nm, &fs));
    PetscCall(JRHBMStickFrequencies(hbmc, &nf, fs));
    PetscCall(JRContGetPeak(contc, 0, &w, &a));
    for (PetscInt i = 0; i < nf; i++)
      if (PetscAbsReal(fs[i] - w / (2 * PETSC_PI)) < PetscAbsReal(best - w / (2 * PETSC_PI))) best = fs[i];
    PetscCall(PetscPrintf(comm, "frf: stuck structure%s, modal basis of %" PetscInt_FMT " modes [Hz]:", hbmc == hbmr ? " (reduced model)" : "", nm));
    for (PetscInt i = 0; i < nf; i++) PetscCall(PetscPrintf(comm, " %.6g", (double)fs[i]));
    PetscCall(PetscPrintf(comm, "\n"));
    PetscCall(PetscPrintf(comm, "stick freq_hz %.8g modes %" PetscInt_FMT " lowest_level_peak_hz %.8g rel %.3e\n", (double)best, nm, (double)(w / (2 * PETSC_PI)), (double)(w / (2 * PETSC_PI) / best - 1)));
    if (stickfe) {
      PetscInt  nfe = PetscMin(nm, 64);
      PetscReal bfe = 0;
      PetscCall(PetscTime(&t0));
      PetscCall(StickFE(model, loaded ? &elr : &el, nfe, fe));
      PetscCall(PetscTime(&t1));
      PetscCall(PetscPrintf(comm, "frf: stuck structure, full FE model with the element springs (SLEPc, %.3g s) [Hz]:", (double)(t1 - t0)));
      for (PetscInt i = 0; i < nfe; i++) PetscCall(PetscPrintf(comm, " %.6g", (double)fe[i]));
      PetscCall(PetscPrintf(comm, "\n"));
      for (PetscInt i = 0; i < nfe; i++)
        if (PetscAbsReal(fe[i] - best) < PetscAbsReal(bfe - best)) bfe = fe[i];
      PetscCall(PetscPrintf(comm, "stick_fe freq_hz %.8g modal_freq_hz %.8g truncation_error %.3e\n", (double)bfe, (double)best, (double)(best / bfe - 1)));
    }
    PetscCall(PetscFree(fs));
    if (base[0] && contc == cont && cont) PetscCall(JRPostWriteContactMaps(post, model, cont, &el, pair));
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
  PetscCall(JRContDestroy(&contr));
  PetscCall(JRContDestroy(&cont));
  PetscCall(JRHBMDestroy(&hbmr));
  PetscCall(JRHBMDestroy(&hbm));
  PetscCall(JRPreloadDestroy(&pre));
  PetscCall(JRReduceDestroy(&red));
  PetscCall(JRPostDestroy(&post));
  PetscCall(JRElementsDestroy(&el));
  PetscCall(JRElementsDestroy(&elr));
  PetscCall(JRElementsDestroy(&elj));
  PetscCall(PetscFree(pair));
  PetscCall(JRModelDestroy(&model));
  PetscFunctionReturn(0);
}

PetscErrorCode JRTaskFRF(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  PetscCall(FRF(comm, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/*
  -task compare: node-to-node and reduced model of one case in one run, sharing the FE model, preload and modes:
  FRF overlays per level (BASE_compare.png), BASE_compare.csv, and per level
  "compare level <F> n2n_freq_hz <f> rom_freq_hz <f> n2n_amp <a> rom_amp <a> n2n_s <t> rom_s <t>".
*/
PetscErrorCode JRTaskCompare(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  PetscCall(FRF(comm, PETSC_TRUE));
  PetscFunctionReturn(0);
}
