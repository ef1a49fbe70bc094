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

/* BASE_contact.csv (pair, x, y, z, the state at each level's peak) and BASE_contact.png */
static PetscErrorCode WriteContactMaps(MPI_Comm comm, JRModel model, JRCont cont, const JRElements *el, const PetscInt pair[], const char base[], PetscBool plot)
{
  const JRPairs  *P;
  PetscInt        nlev;
  PetscMPIInt     rank;
  char            csv[PETSC_MAX_PATH_LEN + 16], png[PETSC_MAX_PATH_LEN + 16], tmp[PETSC_MAX_PATH_LEN + 32];
  FILE           *fp;
  PetscInt       *of;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(JRModelGetPairs(model, &P));
  PetscCall(JRContGetNumLevels(cont, &nlev));
  PetscCall(PetscMalloc1(P->n, &of));
  for (PetscInt p = 0; p < P->n; p++) of[p] = -1;
  for (PetscInt e = 0; e < el->n; e++) of[pair[e]] = e;
  PetscCall(PetscSNPrintf(csv, sizeof(csv), "%s_contact.csv", base));
  PetscCall(PetscSNPrintf(png, sizeof(png), "%s_contact.png", base));
  PetscCall(JRFileOpenTemp(comm, csv, &fp, tmp, sizeof(tmp)));
  if (fp) {
    fprintf(fp, "pair,x_m,y_m,z_m,element");
    for (PetscInt l = 0; l < nlev; l++) fprintf(fp, ",state_level_%" PetscInt_FMT, l);
    fprintf(fp, "\n");
    for (PetscInt p = 0; p < P->n; p++) {
      fprintf(fp, "%" PetscInt_FMT ",%.9g,%.9g,%.9g,%" PetscInt_FMT, p, (double)P->x[3 * p], (double)P->x[3 * p + 1], (double)P->x[3 * p + 2], of[p]);
      for (PetscInt l = 0; l < nlev; l++) {
        const JRContactState *st;
        PetscCall(JRContGetPeakStates(cont, l, &st));
        fprintf(fp, ",%d", of[p] >= 0 ? (int)st[of[p]] : -1);
      }
      fprintf(fp, "\n");
    }
  }
  PetscCall(JRFileCommit(comm, &fp, tmp, csv));
  /* counts per level, for scripts */
  for (PetscInt l = 0; l < nlev; l++) {
    PetscInt cnt[4] = {0, 0, 0, 0};
    if (!rank) {
      const JRContactState *st;
      PetscCall(JRContGetPeakStates(cont, l, &st));
      for (PetscInt e = 0; e < el->n; e++) cnt[st[e]]++;
    }
    PetscCallMPI(MPI_Bcast(cnt, 4, MPIU_INT, 0, comm));
    PetscCall(PetscPrintf(comm, "contact level %" PetscInt_FMT " full_stick %" PetscInt_FMT " stick_slip %" PetscInt_FMT " separation_stick_slip %" PetscInt_FMT " full_separation %" PetscInt_FMT "\n", l, cnt[0], cnt[1], cnt[2], cnt[3]));
  }
  if (plot) {
    PetscBool made;
    char      vars[4 * PETSC_MAX_PATH_LEN], lv[3 * PETSC_MAX_PATH_LEN] = "";
    for (PetscInt l = 0; l < nlev && l < 24; l++) {
      PetscReal w, a, F;
      char      s[128];
      PetscCall(JRContGetPeak(cont, l, &w, &a));
      PetscCall(JRContGetLevel(cont, l, &F));
      PetscCall(PetscSNPrintf(s, sizeof(s), "; t%" PetscInt_FMT "='F = %g N, peak %.5g Hz'", l + 1, (double)F, (double)(w / (2 * PETSC_PI))));
      PetscCall(PetscStrlcat(lv, s, sizeof(lv)));
    }
    PetscCall(PetscSNPrintf(vars, sizeof(vars), "data='%s'; nlev=%" PetscInt_FMT "%s", csv, PetscMin(nlev, 24), lv));
    PetscCall(JRPlot(comm, "plot_contact.gp", png, vars, &made));
    PetscCall(PetscPrintf(comm, "frf: wrote %s%s%s\n", csv, made ? ", " : "", made ? png : ""));
  } else PetscCall(PetscPrintf(comm, "frf: wrote %s\n", csv));
  PetscCall(PetscFree(of));
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
  PetscCall(PetscTime(&t0));
  PetscCall(JRContSolve(*cont));
  PetscCall(PetscTime(&t1));
  PetscCall(JRHBMGetElementTime(hbm, &e1, NULL, NULL));
  *seconds = t1 - t0;
  if (elem) *elem = e1 - e0;
  PetscCall(JRContWrite(*cont));
  PetscFunctionReturn(0);
}

static PetscErrorCode TargetMode(MPI_Comm, JRHBM, PetscInt *, PetscReal *, PetscInt *, PetscReal **);

/* The reduced model elx as a JRHBM (*hbmx) on the modes of hbm (the node-to-node model's, shared; NULL: its own),
   excited and observed at fdof and odof[]; with corr, every element's kt and kn are scaled so that the stuck mode of
   interest is at hbm's frequency (the factor in *corr, 1 if none in [1e-3, 1e3] reaches it: a warning). quiet: no
   lines printed. *setup: the set-up's wall time [s] */
static PetscErrorCode ReducedHBM(MPI_Comm comm, JRModel model, JRHBM hbm, PetscInt fdof, PetscInt nout, const PetscInt odof[], PetscBool corr, PetscBool quiet, JRElements *elx, JRHBM *hbmx, PetscReal *factor, PetscReal *setup)
{
  JRHBM          hr;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  *factor = 1.0;
  PetscCall(JRHBMCreate(comm, &hr));
  PetscCall(JRHBMSetExcitationDof(hr, fdof, nout, odof));
  PetscCall(JRHBMSetBasis(hr, 2));
  PetscCall(JRModelSetElements(model, elx));
  PetscCall(JRHBMSetModel(hr, model));
  PetscCall(JRHBMSetFromOptions(hr));
  if (hbm) PetscCall(JRHBMSetModes(hr, hbm));
  PetscCall(PetscTime(&t0));
  PetscCall(JRHBMSetUp(hr));
  PetscCall(PetscTime(&t1));
  *setup = t1 - t0;
  if (corr && hbm) { /* the stiffness correction: the reduced model's stuck resonance on the node-to-node one */
    PetscInt   k = 0, nm, nf;
    PetscReal  ft = 0, *fr, c;
    PetscCall(TargetMode(comm, hbm, &k, &ft, NULL, NULL));
    PetscCall(JRHBMGetSizes(hr, &nm, NULL, NULL));
    PetscCall(PetscMalloc1(nm, &fr));
    PetscCall(JRHBMStickFrequencies(hr, &nf, fr));
    PetscCall(JRHBMMatchStickFrequency(hr, k, ft, &c));
    if (c == 0) {
      PetscCall(PetscPrintf(comm, "rom: WARNING no stiffness correction: no factor in [1e-3, 1e3] on the joints' springs brings stuck mode %" PetscInt_FMT " from %.6g Hz to the node-to-node %.6g Hz (the joints' averaged motion cannot carry the interface's stiffness in this mode: use more joints)\n", k, (double)fr[k], (double)ft));
      c = 1.0;
    }
    if (!quiet) PetscCall(PetscPrintf(comm, "rom stiffness_correction %.8f stuck_mode %" PetscInt_FMT " n2n_hz %.8g rom_before_hz %.8g\n", (double)c, k, (double)ft, (double)fr[k]));
    PetscCall(PetscFree(fr));
    for (PetscInt e = 0; e < elx->n; e++) {
      elx->kt[e] *= c;
      elx->kn[e] *= c;
    }
    PetscCall(JRModelSetElements(model, elx));
    PetscCall(JRHBMSetModel(hr, model));
    PetscCall(PetscTime(&t0));
    PetscCall(JRHBMSetUp(hr));
    PetscCall(PetscTime(&t1));
    *setup += t1 - t0;
    *factor = c;
  }
  *hbmx = hr;
  PetscFunctionReturn(0);
}

/* The peaks (w [rad/s], amplitude [m]) of hbm's curves at every level of the options, solved without output */
static PetscErrorCode QuietPeaks(MPI_Comm comm, JRHBM hbm, PetscInt *nlev, PetscReal **w, PetscReal **a)
{
  JRCont c;

  PetscFunctionBeginUser;
  PetscCall(JRContCreate(comm, &c));
  PetscCall(JRContSetHBM(c, hbm));
  PetscCall(JRContSetFromOptions(c));
  PetscCall(JRContSetOutputBase(c, ""));
  PetscCall(JRContSetQuiet(c, PETSC_TRUE));
  PetscCall(JRContSolve(c));
  PetscCall(JRContGetNumLevels(c, nlev));
  PetscCall(PetscMalloc2(*nlev, w, *nlev, a));
  for (PetscInt l = 0; l < *nlev; l++) PetscCall(JRContGetPeak(c, l, &(*w)[l], &(*a)[l]));
  PetscCall(JRContDestroy(&c));
  PetscFunctionReturn(0);
}

/*
  -rom_fit_select first: the second reduction fitted with every pair of weights (-rom_fit_select_total x
  -rom_fit_select_case), each reduced model's curves solved (quietly), and the pair whose peaks come nearest the
  first reduction's kept (the smallest worst relative amplitude error over the levels): the first reduction is the
  reference a user has without node-to-node, and it is close to it (lap3 mode field within 1.6%, BRB 0.6%). Sets
  -rom_fit_total_weight and -rom_fit_case_weight to the pair chosen, for the fit that follows.
*/
static PetscErrorCode SelectWeights(MPI_Comm comm, JRModel model, JRHBM hbm, PetscInt fdof, PetscInt nout, const PetscInt odof[], PetscBool corr, const JRElements *elj, PetscInt romm, const PetscReal w[], const JRROMCase *cs, PetscInt nt, const PetscReal wtot[], PetscInt nk, const PetscReal wcas[])
{
  JRElements elf;
  JRHBM      hf;
  PetscReal  c, su, *wf, *af, best = PETSC_MAX_REAL, bt = 0, bk = 0;
  PetscInt   nlev;
  char       str[64];
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscMemzero(&elf, sizeof(elf)));
  PetscCall(JRROMReduce(comm, elj, 0, w, cs, NULL, PETSC_FALSE, PETSC_TRUE, &elf));
  PetscCall(ReducedHBM(comm, model, hbm, fdof, nout, odof, corr, PETSC_TRUE, &elf, &hf, &c, &su));
  PetscCall(QuietPeaks(comm, hf, &nlev, &wf, &af));
  PetscCall(JRHBMDestroy(&hf));
  PetscCall(JRElementsDestroy(&elf));
  for (PetscInt i = 0; i < nt; i++)
    for (PetscInt j = 0; j < nk; j++) {
      JRElements elc;
      JRHBM      hc;
      PetscReal *wc, *ac, ea = 0, ef = 0;
      PetscInt   nl;
      PetscCall(PetscSNPrintf(str, sizeof(str), "%.17g", (double)wtot[i]));
      PetscCall(PetscOptionsSetValue(NULL, "-rom_fit_total_weight", str));
      PetscCall(PetscSNPrintf(str, sizeof(str), "%.17g", (double)wcas[j]));
      PetscCall(PetscOptionsSetValue(NULL, "-rom_fit_case_weight", str));
      PetscCall(PetscMemzero(&elc, sizeof(elc)));
      PetscCall(JRROMReduce(comm, elj, romm, w, cs, NULL, PETSC_FALSE, PETSC_TRUE, &elc));
      PetscCall(ReducedHBM(comm, model, hbm, fdof, nout, odof, corr, PETSC_TRUE, &elc, &hc, &c, &su));
      PetscCall(QuietPeaks(comm, hc, &nl, &wc, &ac));
      PetscCheck(nl == nlev, comm, PETSC_ERR_PLIB, "Different level counts");
      for (PetscInt l = 0; l < nlev; l++) {
        ea = PetscMax(ea, PetscAbsReal(ac[l] / af[l] - 1));
        ef = PetscMax(ef, PetscAbsReal(wc[l] / wf[l] - 1));
      }
      PetscCall(PetscPrintf(comm, "rom select total_weight %g case_weight %g worst_amp_vs_first %.3e worst_freq_vs_first %.3e\n", (double)wtot[i], (double)wcas[j], (double)ea, (double)ef));
      if (ea < best) { /* the first pair of the smallest error */
        best = ea;
        bt   = wtot[i];
        bk   = wcas[j];
      }
      PetscCall(PetscFree2(wc, ac));
      PetscCall(JRHBMDestroy(&hc));
      PetscCall(JRElementsDestroy(&elc));
    }
  PetscCall(PetscFree2(wf, af));
  PetscCall(PetscSNPrintf(str, sizeof(str), "%.17g", (double)bt));
  PetscCall(PetscOptionsSetValue(NULL, "-rom_fit_total_weight", str));
  PetscCall(PetscSNPrintf(str, sizeof(str), "%.17g", (double)bk));
  PetscCall(PetscOptionsSetValue(NULL, "-rom_fit_case_weight", str));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscPrintf(comm, "rom: fit weights chosen against the first reduction: -rom_fit_total_weight %g -rom_fit_case_weight %g (worst amplitude %.2f%% off the first reduction's peaks; %" PetscInt_FMT " pairs, %.3g s)\n", (double)bt, (double)bk, (double)(100 * best), nt * nk, (double)(t1 - t0)));
  PetscFunctionReturn(0);
}

/* -task compare: per level the peaks of both models and their errors, the wall times, BASE_compare.csv and .png */
static PetscErrorCode CompareReport(MPI_Comm comm, JRCont cn, JRCont cr, const JRElements *eln, const JRElements *elr, PetscReal tn, PetscReal tr, PetscReal en, PetscReal er, PetscReal setn, PetscReal setr, PetscReal tred, const char base[], PetscBool plot)
{
  PetscInt nlev, nlr;
  FILE    *fp = NULL;
  char     csv[PETSC_MAX_PATH_LEN + 32], tmp[PETSC_MAX_PATH_LEN + 48];
  PetscReal worstf = 0, worsta = 0;

  PetscFunctionBeginUser;
  PetscCall(JRContGetNumLevels(cn, &nlev));
  PetscCall(JRContGetNumLevels(cr, &nlr));
  PetscCheck(nlev == nlr, comm, PETSC_ERR_PLIB, "Different level counts");
  if (base[0]) {
    PetscCall(PetscSNPrintf(csv, sizeof(csv), "%s_compare.csv", base));
    PetscCall(JRFileOpenTemp(comm, csv, &fp, tmp, sizeof(tmp)));
    if (fp) fprintf(fp, "level,F_N,n2n_freq_hz,rom_freq_hz,freq_rel_err,n2n_amp_m,rom_amp_m,amp_rel_err,n2n_zeta,rom_zeta,n2n_s,rom_s\n");
  }
  PetscCall(PetscPrintf(comm, "compare: node-to-node %" PetscInt_FMT " elements (%" PetscInt_FMT " nonlinear relative DOFs) vs reduced %" PetscInt_FMT " elements on %" PetscInt_FMT " joints (%" PetscInt_FMT " nonlinear DOFs)\n", eln->n, eln->n, elr->n, elr->njoints, elr->njoints));
  PetscCall(PetscPrintf(comm, "  %10s %12s %12s %10s %13s %13s %10s %9s %9s %9s %9s\n", "F [N]", "n2n [Hz]", "rom [Hz]", "err f", "n2n amp [m]", "rom amp [m]", "err amp", "n2n zeta", "rom zeta", "n2n [s]", "rom [s]"));
  for (PetscInt l = 0; l < nlev; l++) {
    PetscReal F, wn, an, wr, ar, zn, zr, sn, sr, ef, ea;
    PetscCall(JRContGetLevel(cn, l, &F));
    PetscCall(JRContGetPeak(cn, l, &wn, &an));
    PetscCall(JRContGetPeak(cr, l, &wr, &ar));
    PetscCall(JRContGetDamping(cn, l, &zn, NULL));
    PetscCall(JRContGetDamping(cr, l, &zr, NULL));
    PetscCall(JRContGetLevelStats(cn, l, &sn, NULL, NULL));
    PetscCall(JRContGetLevelStats(cr, l, &sr, NULL, NULL));
    ef     = wr / wn - 1;
    ea     = ar / an - 1;
    worstf = PetscMax(worstf, PetscAbsReal(ef));
    worsta = PetscMax(worsta, PetscAbsReal(ea));
    PetscCall(PetscPrintf(comm, "  %10g %12.6f %12.6f %+10.2e %13.6e %13.6e %+10.2e %9.5f %9.5f %9.4f %9.4f\n", (double)F, (double)(wn / (2 * PETSC_PI)), (double)(wr / (2 * PETSC_PI)), (double)ef, (double)an, (double)ar, (double)ea, (double)zn, (double)zr, (double)sn, (double)sr));
    if (fp) fprintf(fp, "%" PetscInt_FMT ",%.9g,%.10g,%.10g,%.6e,%.9e,%.9e,%.6e,%.6e,%.6e,%.6g,%.6g\n", l, (double)F, (double)(wn / (2 * PETSC_PI)), (double)(wr / (2 * PETSC_PI)), (double)ef, (double)an, (double)ar, (double)ea, (double)zn, (double)zr, (double)sn, (double)sr);
  }
  for (PetscInt l = 0; l < nlev; l++) {
    PetscReal F, wn, an, wr, ar, sn, sr;
    PetscCall(JRContGetLevel(cn, l, &F));
    PetscCall(JRContGetPeak(cn, l, &wn, &an));
    PetscCall(JRContGetPeak(cr, l, &wr, &ar));
    PetscCall(JRContGetLevelStats(cn, l, &sn, NULL, NULL));
    PetscCall(JRContGetLevelStats(cr, l, &sr, NULL, NULL));
    PetscCall(PetscPrintf(comm, "compare level %g n2n_freq_hz %.8g rom_freq_hz %.8g n2n_amp %.8e rom_amp %.8e n2n_s %.6g rom_s %.6g\n", (double)F, (double)(wn / (2 * PETSC_PI)), (double)(wr / (2 * PETSC_PI)), (double)an, (double)ar, (double)sn, (double)sr));
  }
  PetscCall(PetscPrintf(comm, "compare worst freq_rel_err %.3e amp_rel_err %.3e\n", (double)worstf, (double)worsta));
  PetscCall(PetscPrintf(comm, "compare time n2n_solve_s %.6g rom_solve_s %.6g speedup %.4g n2n_setup_s %.4g rom_setup_s %.4g rom_reduction_s %.4g\n", (double)tn, (double)tr, (double)(tn / tr), (double)setn, (double)setr, (double)tred));
  /* where the solve time goes: the elements (forces, Jacobians: what the reduction shrinks) and the rest (the linear
     algebra on the unknowns and the continuation: what it does not, unless condensed) */
  PetscCall(PetscPrintf(comm, "compare: solve time in the contact elements (forces and Jacobians) node-to-node %.4g s of %.4g s, reduced %.4g s of %.4g s; with free elements the reduced model would be at most %.3g x faster\n", (double)en, (double)tn, (double)er, (double)tr, (double)(tn / PetscMax(tr - er, 1e-9))));
  PetscCall(PetscPrintf(comm, "compare time_split n2n_elements_s %.6g n2n_rest_s %.6g rom_elements_s %.6g rom_rest_s %.6g speedup_cap %.4g\n", (double)en, (double)(tn - en), (double)er, (double)(tr - er), (double)(tn / PetscMax(tr - er, 1e-9))));
  if (base[0]) {
    PetscCall(JRFileCommit(comm, &fp, tmp, csv));
    if (plot) {
      char      png[PETSC_MAX_PATH_LEN + 32], vars[3 * PETSC_MAX_PATH_LEN + 64];
      PetscBool made;
      PetscCall(PetscSNPrintf(png, sizeof(png), "%s_compare.png", base));
      PetscCall(PetscSNPrintf(vars, sizeof(vars), "n2n='%s_n2n.csv'; rom='%s_rom.csv'; nlev=%" PetscInt_FMT "; ttl='node-to-node %" PetscInt_FMT " elements (solid) vs reduced %" PetscInt_FMT " elements in %" PetscInt_FMT " joints (dashed)'", base, base, nlev, eln->n, elr->n, elr->njoints));
      PetscCall(JRPlot(comm, "plot_compare.gp", png, vars, &made));
      PetscCall(PetscPrintf(comm, "compare: wrote %s%s%s\n", csv, made ? ", " : "", made ? png : ""));
    } else PetscCall(PetscPrintf(comm, "compare: wrote %s\n", csv));
  }
  PetscFunctionReturn(0);
}

/* The stuck mode of hbm nearest the middle of the frequency range of the options (or, without one, the lowest
   elastic one): the mode of interest of a reduced model */
static PetscErrorCode TargetMode(MPI_Comm comm, JRHBM hbm, PetscInt *k, PetscReal *f, PetscInt *nlev, PetscReal **lev)
{
  PetscReal *fs, wmin, wmax;
  PetscInt   nm, nf;
  JRCont     cont;

  PetscFunctionBeginUser;
  PetscCall(JRContCreate(comm, &cont));
  PetscCall(JRContSetHBM(cont, hbm));
  PetscCall(JRContSetFromOptions(cont));
  PetscCall(JRHBMGetSizes(hbm, &nm, NULL, NULL));
  PetscCall(PetscMalloc1(nm, &fs));
  PetscCall(JRHBMStickFrequencies(hbm, &nf, fs));
  PetscCall(JRContGetRange(cont, &wmin, &wmax));
  *k = -1;
  if (wmax > 0) {
    const PetscReal fc = 0.25 * (wmin + wmax) / PETSC_PI;
    for (PetscInt i = 0; i < nf; i++)
      if (*k < 0 || PetscAbsReal(fs[i] - fc) < PetscAbsReal(fs[*k] - fc)) *k = i;
  } else
    for (PetscInt i = 0; i < nf && *k < 0; i++)
      if (fs[i] > 1e-3 * fs[nf - 1]) *k = i;
  *f = fs[*k];
  if (lev) { /* the excitation levels of the case */
    PetscCall(JRContGetNumLevels(cont, nlev));
    PetscCall(PetscMalloc1(*nlev, lev));
    for (PetscInt l = 0; l < *nlev; l++) PetscCall(JRContGetLevel(cont, l, *lev + l));
  }
  PetscCall(PetscFree(fs));
  PetscCall(JRContDestroy(&cont));
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
  PetscInt        nm, H, n, *pair = NULL, romm = 0, jmotion = 0, fdof = 0, nout = 0, odof[21], select = 0, nst = 8, nsc = 8, dir = 2;
  PetscReal       oat[63]; /* FE models: the response points x, y, z [m] */
  PetscReal       swt[8] = {20, 100, 1000}, swc[8] = {10, 0};
  PetscBool       n2n, stickfe = PETSC_FALSE, plot = PETSC_TRUE, isrom = PETSC_FALSE, loaded = PETSC_FALSE, corr_on = PETSC_TRUE, weight = PETSC_TRUE;
  JRElements      el, elr, elj;
  char            base[PETSC_MAX_PATH_LEN] = "out/frf", romsave[PETSC_MAX_PATH_LEN] = "", romload[PETSC_MAX_PATH_LEN] = "";
  PetscLogDouble  t0, t1, tpre = 0, tmodel;
  PetscReal       corr = 1.0, tn = 0, tr = 0, en = 0, er = 0, setn = 0, setr = 0, tred = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&el, sizeof(el)));
  PetscCall(PetscMemzero(&elr, sizeof(elr)));
  PetscCall(PetscMemzero(&elj, sizeof(elj)));
  PetscCall(PetscTime(&t0));
  PetscCall(JRModelCreate(comm, &model));
  PetscCall(JRModelSetFromOptions(model));
  PetscCall(JRModelSetUp(model));
  PetscCall(PetscTime(&t1));
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
  PetscOptionsBegin(comm, NULL, "Frequency response (-task frf, -task compare)", "JRTaskFRF");
  PetscCall(PetscOptionsString("-frf_output_file", "Output base name", "JRTaskFRF", base, base, sizeof(base), NULL));
  PetscCall(PetscOptionsBool("-frf_plot", "Draw the PNG plots", "JRTaskFRF", plot, &plot, NULL));
  if (n2n) {
    PetscCall(PetscOptionsBool("-frf_stick_fe", "Also the natural frequencies of the whole FE model with every element stuck (SLEPc): the modal truncation error", "JRTaskFRF", stickfe, &stickfe, NULL));
    PetscCall(PetscOptionsInt("-rom_elements", "Second reduction: fit this many elements per joint to its hysteresis loops (0: the first reduction only)", "JRROMReduce", romm, &romm, NULL));
    PetscCall(PetscOptionsBool("-rom_mode_weights", "Weight every member of a joint by its motion relative to the joint's in the stuck mode of interest (w^2 kt, |w| f; jenkins)", "JRROMReduce", weight, &weight, NULL));
    {
      const char *jm[] = {"mean", "linear", "mode"};
      PetscCall(PetscOptionsEList("-rom_joint_motion", "How a joint's members move: mean (4.4), linear (a linear field over their positions) or mode (a linear field over their motions in the stuck mode of interest)", "JRROMReduce", jm, 3, jm[jmotion], &jmotion, NULL));
    }
    {
      const char *sel[] = {"none", "first"};
      PetscBool   st, sc;
      PetscCall(PetscOptionsEList("-rom_fit_select", "Second reduction: none (the fit weights as given) or first (fit with every pair of -rom_fit_select_total x -rom_fit_select_case and keep the pair whose peaks come nearest the first reduction's; nothing to choose with -rom_elements 0)", "JRROMReduce", sel, 2, sel[select], &select, NULL));
      PetscCall(PetscOptionsRealArray("-rom_fit_select_total", "-rom_fit_select first: the -rom_fit_total_weight values tried", "JRROMReduce", swt, &nst, &st));
      PetscCall(PetscOptionsRealArray("-rom_fit_select_case", "-rom_fit_select first: the -rom_fit_case_weight values tried", "JRROMReduce", swc, &nsc, &sc));
      if (!st) nst = 3;
      if (!sc) nsc = 2;
      PetscCheck(nst > 0 && nsc > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_select_total and -rom_fit_select_case: at least one value each (at most 8)");
      for (PetscInt i = 0; i < nst; i++) PetscCheck(swt[i] >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_select_total: %g: the weights must be non-negative", (double)swt[i]);
      for (PetscInt i = 0; i < nsc; i++) PetscCheck(swc[i] >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_select_case: %g: the weights must be non-negative", (double)swc[i]);
    }
    PetscCall(PetscOptionsBool("-rom_stiffness_correction", "Scale the reduced elements' stiffness so that the stuck resonance is the node-to-node one", "JRHBMMatchStickFrequency", corr_on, &corr_on, NULL));
    PetscCall(PetscOptionsString("-rom_save", "Save the reduced model (second reduction) to this HDF5 file", "JRROMSave", romsave, romsave, sizeof(romsave), NULL));
    PetscCall(PetscOptionsString("-rom_load", "Run the reduced model of this HDF5 file (no preload, no fit)", "JRROMLoad", romload, romload, sizeof(romload), NULL));
  }
  PetscOptionsEnd();
  PetscCheck(n2n || !compare, comm, PETSC_ERR_ARG_WRONG, "-task compare needs an FE model with a contact interface (-model_type brb, lap1, lap3, lap, gmsh)");
  PetscCheck(romm >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_elements %" PetscInt_FMT ": 0 (first reduction only) or more", romm);

  if (n2n) {
    PetscInt         ndof, nd = 3, no = 63;
    PetscReal        lo[3], hi[3], at[3], dist;
    PetscBool        set, oset;
    JRPreloadSummary s;
    const char      *dirs[] = {"x", "y", "z"};
    char             pbase[PETSC_MAX_PATH_LEN + 16], mfile[PETSC_MAX_PATH_LEN + 16];

    {
      PetscBool d, o;
      PetscCall(PetscOptionsHasName(NULL, NULL, "-frf_dof", &d));
      PetscCall(PetscOptionsHasName(NULL, NULL, "-frf_output", &o));
      PetscCheck(!d && !o, comm, PETSC_ERR_ARG_INCOMP, "%s: on an FE model the DOF numbers depend on the partition; give points instead: -frf_at x,y,z and -frf_output_at x,y,z,... [m] with -frf_dir x|y|z", d ? "-frf_dof" : "-frf_output");
    }
    PetscCall(JRModelGetNumDofs(model, &ndof));
    PetscCall(PetscPrintf(comm, "frf: node-to-node contact model, %" PetscInt_FMT " DOFs, %" PetscInt_FMT " interface pairs (model %.3g s)\n", ndof, P->n, (double)tmodel));
    if (romload[0] && !compare) { /* a saved reduced model: no preload, no interface, no fit */
      PetscCall(JRROMLoad(model, romload, &elr, &corr));
      isrom  = PETSC_TRUE;
      loaded = PETSC_TRUE;
    } else {
      /* 2. preload */
      PetscCall(PetscTime(&t0));
      PetscCall(JRPreloadCreate(comm, &pre));
      PetscCall(JRPreloadSetModel(pre, model));
      PetscCall(JRPreloadSetFromOptions(pre));
      PetscCall(JRPreloadSolve(pre));
      PetscCall(PetscTime(&t1));
      tpre = t1 - t0;
      PetscCall(JRPreloadGetSummary(pre, &s));
      PetscCall(PetscPrintf(comm, "preload total_normal_force %.10g bolt_force_sum %.10g pairs_in_contact %" PetscInt_FMT " pairs %" PetscInt_FMT " (%.3g s)\n", (double)s.total_force, (double)s.bolt_force_sum, s.in_contact, s.pairs, (double)tpre));
      if (base[0]) {
        PetscCall(PetscSNPrintf(pbase, sizeof(pbase), "%s_preload", base));
        PetscCall(JRPreloadWrite(pre, pbase, plot));
      }
      /* 4. interface, and the reduced model from its joints */
      PetscCall(JRInterfaceCreateElements(model, pre, &el, &pair));
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
        PetscCall(JRROMLoad(model, romload, &elr, &corr));
        isrom  = PETSC_TRUE;
        loaded = PETSC_TRUE;
      }
      PetscCheck(!romm || isrom, comm, PETSC_ERR_ARG_INCOMP, "-rom_elements needs joints: -rom_joints strips|bolts|between|sides|zones");
      PetscCheck(!compare || isrom, comm, PETSC_ERR_ARG_WRONG, "-task compare needs a reduced model: joints (-rom_joints ..., optionally -rom_elements m) or -rom_load FILE");
    }
    PetscCheck(!romsave[0] || (isrom && romm > 0 && !loaded), comm, PETSC_ERR_ARG_INCOMP, "-rom_save saves a second-reduction model: it needs -rom_joints ... and -rom_elements m");
    /* excitation and responses by position */
    PetscCall(JRModelGetBoundingBox(model, lo, hi));
    at[0] = lo[0];
    at[1] = 0.5 * (lo[1] + hi[1]);
    at[2] = hi[2];
    PetscOptionsBegin(comm, NULL, "Excitation and responses of an FE model (-task frf)", "JRTaskFRF");
    PetscCall(PetscOptionsRealArray("-frf_at", "Excitation point x,y,z [m] (nearest node; default: the end x = xmin, mid-width, top)", "JRTaskFRF", at, &nd, &set));
    PetscCall(PetscOptionsEList("-frf_dir", "Direction of the excitation force and of the responses", "JRTaskFRF", dirs, 3, dirs[dir], &dir, NULL));
    PetscCall(PetscOptionsRealArray("-frf_output_at", "Response points x1,y1,z1,x2,... [m] (default: the other end, then the excitation point)", "JRTaskFRF", oat, &no, &oset));
    PetscOptionsEnd();
    PetscCheck(!set || nd == 3, comm, PETSC_ERR_ARG_WRONG, "-frf_at needs three coordinates x,y,z [m], got %" PetscInt_FMT, nd);
    PetscCheck(!oset || (no % 3 == 0 && no > 0), comm, PETSC_ERR_ARG_WRONG, "-frf_output_at needs triples x,y,z [m], got %" PetscInt_FMT " values", no);
    PetscCall(JRModelFindDof(model, at, dir, &fdof, &dist));
    PetscCheck(dist <= 0.05 * (hi[0] - lo[0]), comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_at (%g, %g, %g) m: the nearest node is %g m away: the point is outside the model (box x %g..%g, y %g..%g, z %g..%g m)", (double)at[0], (double)at[1], (double)at[2], (double)dist, (double)lo[0], (double)hi[0], (double)lo[1], (double)hi[1], (double)lo[2], (double)hi[2]);
    PetscCall(PetscPrintf(comm, "frf: excitation F sin(w t) along %s at (%g, %g, %g) m: DOF %" PetscInt_FMT " (node %.2g mm away)\n", dirs[dir], (double)at[0], (double)at[1], (double)at[2], fdof, (double)(dist * 1e3)));
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
      PetscCall(PetscPrintf(comm, "frf: response %" PetscInt_FMT " along %s at (%g, %g, %g) m: DOF %" PetscInt_FMT "\n", o + 1, dirs[dir], (double)oat[3 * o], (double)oat[3 * o + 1], (double)oat[3 * o + 2], odof[o]));
    }
    /* the modes are saved for reuse unless they are read */
    {
      PetscBool ld, sv;
      PetscCall(PetscOptionsHasName(NULL, NULL, "-modes_load", &ld));
      PetscCall(PetscOptionsHasName(NULL, NULL, "-modes_save", &sv));
      if (!ld && !sv && base[0]) {
        PetscCall(PetscSNPrintf(mfile, sizeof(mfile), "%s_modes.h5", base));
        PetscCall(PetscOptionsSetValue(NULL, "-modes_save", mfile));
      }
    }
  }
  /* the node-to-node (or matrices) model: its modes serve the reduced model too */
  if (!loaded) {
    PetscCall(JRHBMCreate(comm, &hbm));
    if (n2n) {
      PetscCall(JRHBMSetExcitationDof(hbm, fdof, nout, odof));
      PetscCall(JRHBMSetOutputPoints(hbm, nout, oat, dir));
      PetscCall(JRHBMSetBasis(hbm, 2)); /* stuck + free-interface modes: -hbm_basis free for the thesis's */
      PetscCall(JRModelSetElements(model, &el));
    }
    PetscCall(JRHBMSetModel(hbm, model));
    PetscCall(JRHBMSetFromOptions(hbm));
    PetscCall(PetscTime(&t0));
    PetscCall(JRHBMSetUp(hbm));
    PetscCall(PetscTime(&t1));
    setn = t1 - t0;
  }
  if (isrom && !loaded) { /* the reduction, from the joints of the node-to-node elements */
    PetscReal *w = NULL, *ubar = NULL, *lev = NULL;
    JRROMCase  cs;
    PetscCall(PetscMemzero(&cs, sizeof(cs)));
    PetscCall(PetscTime(&t0));
    if (!strcmp(elj.typename[0], JRCONTACTJENKINS) || jmotion == 2) { /* the stuck mode of interest: each member's motion over its joint's (4.4: over its members in contact at rest, all if none), and the joints' amplitudes in the case */
      PetscInt   k  = 0, nlev = 0;
      PetscReal  ft = 0, *u, *v, *cnt, *ua, umax = 0, smax = 0, om;
      PetscCall(TargetMode(comm, hbm, &k, &ft, &nlev, &lev));
      PetscCall(PetscMalloc2(el.n, &u, el.n, &v));
      PetscCall(PetscCalloc1(elj.njoints, &ubar));
      PetscCall(PetscCalloc2(2 * elj.njoints, &cnt, elj.njoints, &ua));
      PetscCall(JRHBMStuckModeMotion(hbm, k, u, v));
      for (PetscInt e = 0; e < el.n; e++) { /* per joint: sum and count over its members in contact at rest, then over all */
        const PetscInt j = elj.joint[e];
        if (elj.n0[e] > 0) {
          ubar[j] += u[e];
          cnt[2 * j] += 1;
        }
        ua[j] += u[e];
        cnt[2 * j + 1] += 1;
        umax = PetscMax(umax, PetscAbsReal(u[e]));
      }
      for (PetscInt j = 0; j < elj.njoints; j++) ubar[j] = cnt[2 * j] > 0 ? ubar[j] / cnt[2 * j] : ua[j] / cnt[2 * j + 1];
      if (jmotion == 2) { /* -rom_joint_motion mode: each member's field coordinates are its position and its tangential
                             and normal motions in this mode (scaled to at most 1); the fit weighs the members */
        for (PetscInt e = 0; e < el.n; e++) smax = PetscMax(smax, PetscMax(PetscAbsReal(u[e]), PetscAbsReal(v[e])));
        PetscCheck(smax > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_joint_motion mode: the interface does not move in stuck mode %" PetscInt_FMT " (%g Hz)", k, (double)ft);
        PetscCall(PetscFree(elj.phi));
        PetscCall(PetscMalloc1(2 * el.n, &elj.phi));
        for (PetscInt e = 0; e < el.n; e++) {
          elj.phi[2 * e]     = u[e] / smax;
          elj.phi[2 * e + 1] = v[e] / smax;
        }
        PetscCall(PetscPrintf(comm, "rom: joints move with a field linear in their members' positions and motions in stuck mode %" PetscInt_FMT " (%.6g Hz)\n", k, (double)ft));
      }
      if (weight || jmotion == 2) {
        PetscCall(PetscMalloc1(el.n, &w));
        for (PetscInt e = 0; e < el.n; e++) w[e] = PetscAbsReal(ubar[elj.joint[e]]) > 1e-6 * umax ? u[e] / ubar[elj.joint[e]] : 1.0;
        PetscCall(PetscPrintf(comm, "rom: members weighted by their motion in stuck mode %" PetscInt_FMT " (%.6g Hz) over their joint's\n", k, (double)ft));
      }
      PetscCall(JRHBMStuckModeBalance(hbm, k, &om, &cs.force, &cs.damp));
      cs.nlev   = nlev;
      cs.level  = lev;
      cs.ujoint = ubar;
      PetscCall(PetscFree2(cnt, ua));
      PetscCall(PetscFree2(u, v));
    }
    if (select && romm > 0) PetscCall(SelectWeights(comm, model, hbm, fdof, nout, odof, corr_on, &elj, romm, w, ubar ? &cs : NULL, nst, swt, nsc, swc));
    PetscCall(JRROMReduce(comm, &elj, romm, w, ubar ? &cs : NULL, base, plot, PETSC_FALSE, &elr));
    PetscCall(PetscFree(ubar));
    PetscCall(PetscFree(lev));
    PetscCall(PetscTime(&t1));
    tred = t1 - t0;
    PetscCall(PetscPrintf(comm, "rom: %s reduction: %" PetscInt_FMT " elements in %" PetscInt_FMT " joints (%.3g s)\n", romm ? "second" : "first", elr.n, elr.njoints, (double)tred));
    PetscCall(PetscFree(w));
  }
  if (isrom) {
    PetscReal c = 1.0;
    PetscCall(ReducedHBM(comm, model, hbm, fdof, nout, odof, (PetscBool)(!loaded && corr_on), PETSC_FALSE, &elr, &hbmr, &c, &setr));
    PetscCall(JRHBMSetOutputPoints(hbmr, nout, oat, dir));
    if (!loaded) corr = c;
    if (romsave[0]) PetscCall(JRROMSave(model, &elr, corr, romsave));
  }
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
    PetscCall(CompareReport(comm, cont, contr, &el, &elr, tn, tr, en, er, setn, setr, tred, base, plot));
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
    if (base[0] && contc == cont && cont) PetscCall(WriteContactMaps(comm, model, cont, &el, pair, base, plot));
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
