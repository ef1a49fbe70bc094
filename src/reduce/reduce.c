/*
   JRReduce: the reduced-order joints, the whole of both reductions (thesis 4.1-4.5, 5.2-5.5; options prefix rom_).

     JRReduceCreate -> JRReduceSetFromOptions -> JRReduceSetCase / JRReduceSetExcitation / JRReduceSetOutput
       -> JRReduceAssignJoints (the first reduction's regions, on the node-to-node elements: src/reduce/joints.c)
       -> JRReduceSetUp (the mode of interest, the members' weights and the case, the fit weights' selection, the
          second reduction's fit: src/reduce/fit.c) -> JRReduceCreateHBM (the reduced model's harmonic balance, with
          the stiffness correction) -> JRReduceSave -> JRReduceDestroy
   A saved model is read back by JRReduceLoad (-rom_load).
*/
#include <jointrom/private/reduceimpl.h>
#include <jointrom/private/modelimpl.h>

/* The stuck mode of hbm nearest the middle of the case's frequency range (or, without one, the lowest elastic one):
   the mode of interest of a reduced model; k its index, f its frequency [Hz] */
static PetscErrorCode TargetMode(JRReduce red, JRHBM hbm, PetscInt *k, PetscReal *f)
{
  PetscReal      *fs;
  const PetscReal wmin = red->wmin, wmax = red->wmax;
  PetscInt        nm, nf;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetSizes(hbm, &nm, NULL, NULL));
  PetscCall(PetscMalloc1(nm, &fs));
  PetscCall(JRHBMStickFrequencies(hbm, &nf, fs));
  *k = -1;
  if (wmax > 0) {
    const PetscReal fc = 0.25 * (wmin + wmax) / PETSC_PI;
    for (PetscInt i = 0; i < nf; i++)
      if (*k < 0 || PetscAbsReal(fs[i] - fc) < PetscAbsReal(fs[*k] - fc)) *k = i;
  } else
    for (PetscInt i = 0; i < nf && *k < 0; i++)
      if (fs[i] > 1e-3 * fs[nf - 1]) *k = i;
  *f = fs[*k];
  PetscCall(PetscFree(fs));
  PetscFunctionReturn(0);
}

/*
  Which joints a stiffness correction far from 1 comes from. In the node-to-node model's stuck mode of interest q
  (M-normalised, omega^2 = q^T K q), joint j's members' stuck springs hold the share s_j = E_j / omega^2 of the mode's
  strain energy (JRHBMStuckSpringEnergy), and the reduced joint's springs, moving with the joint's field in the same
  q, the share r_j. By Rayleigh's quotient the reduced model's stuck frequency falls short of (or exceeds) the
  node-to-node one by the sum of the differences d_j = s_j - r_j, to first order; for an exact reduction (every
  element its own joint, or the mode-shape weights of a jenkins joint) every d_j is 0. The joints named are the
  fewest, in order of d_j (of the sign of the correction: too soft for c > 1, too stiff for c < 1), whose d_j make up
  80% of the differences of that sign. Prints one line per joint with its shares when the correction is outside
  [0.9, 1.1] (or none is found: c = 0), then one WARNING line and the machine-readable `rom stiffness_joints` line.
  Collective; rank 0 prints.
*/
static PetscErrorCode StiffnessJoints(JRReduce red, JRHBM hbm, JRHBM hr, const JRElements *elx, PetscInt k, PetscReal c, PetscReal fr, PetscReal ft)
{
  MPI_Comm          comm = red->comm;
  const JRElements *mem  = elx->members ? elx->members : elx, *eln;
  const PetscInt    nj   = elx->njoints;
  const PetscBool   bad  = (PetscBool)(c == 0 || c < 0.9 || c > 1.1);
  const PetscReal   sgn  = (c == 0 || c > 1) ? 1.0 : -1.0;
  PetscInt          nm, nmr, *ord, nn = 0;
  PetscReal        *q, *u, *v, *En, *Er, om, lam, sn = 0, sr = 0, dtot = 0, dsum = 0, tiny;
  char              names[1024] = "", ids[256] = "", buf[256];
  size_t            len;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetSizes(hbm, &nm, NULL, NULL));
  PetscCall(JRHBMGetSizes(hr, &nmr, NULL, NULL));
  PetscCall(JRHBMGetElements(hbm, &eln));
  if (nm != nmr || !elx->joint || nj < 1 || !mem->joint || mem->njoints != nj || !eln || eln->n != mem->n) { /* not the node-to-node model's members: the factor alone */
    if (bad) PetscCall(PetscPrintf(comm, "rom: WARNING stiffness correction %.4g outside [0.9, 1.1] (stuck mode %" PetscInt_FMT ": %.6g Hz reduced, %.6g Hz node-to-node)\n", (double)c, k, (double)fr, (double)ft));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscMalloc3(nm, &q, mem->n, &u, mem->n, &v));
  PetscCall(PetscCalloc3(nj, &En, nj, &Er, nj, &ord));
  PetscCall(JRHBMStuckMode(hbm, k, &om, q));
  lam = om * om;
  PetscCall(JRHBMStuckModeMotion(hbm, k, u, v)); /* the members are the node-to-node model's elements, in its order */
  for (PetscInt e = 0; e < mem->n; e++)
    if (mem->n0[e] > 0) En[mem->joint[e]] += mem->kt[e] * u[e] * u[e] + mem->kn[e] * v[e] * v[e];
  PetscCall(JRHBMStuckSpringEnergy(hr, q, Er));
  for (PetscInt j = 0; j < nj; j++) {
    En[j] /= lam;
    Er[j] /= lam;
    sn += En[j];
    sr += Er[j];
  }
  tiny = 1e-2 * PetscMax(sn, sr); /* a joint whose share differs by less than 1% of the joints' is not responsible */
  for (PetscInt j = 0; j < nj; j++)
    if (sgn * (En[j] - Er[j]) > tiny) dtot += sgn * (En[j] - Er[j]);
  PetscCall(PetscPrintf(comm, "rom stiffness_energy stuck_mode %" PetscInt_FMT " members_share %.6e joints_share %.6e\n", k, (double)sn, (double)sr));
  if (!bad) {
    PetscCall(PetscFree3(q, u, v));
    PetscCall(PetscFree3(En, Er, ord));
    PetscFunctionReturn(0);
  }
  for (PetscInt j = 0; j < nj; j++) ord[j] = j;
  for (PetscInt a = 1; a < nj; a++) /* by sgn d_j, largest first (ties: the lower index) */
    for (PetscInt b = a; b > 0 && sgn * (En[ord[b]] - Er[ord[b]]) > sgn * (En[ord[b - 1]] - Er[ord[b - 1]]); b--) {
      const PetscInt t = ord[b];
      ord[b]           = ord[b - 1];
      ord[b - 1]       = t;
    }
  for (PetscInt a = 0; a < nj && dtot > 0 && dsum < 0.8 * dtot && nn < 8; a++) {
    const PetscInt  j = ord[a];
    const PetscReal d = sgn * (En[j] - Er[j]);
    if (!(d > tiny)) break;
    dsum += d;
    nn++;
    if (red->ji && red->nji == nj) PetscCall(JRReduceJointName(red, j, buf, sizeof(buf)));
    else PetscCall(PetscSNPrintf(buf, sizeof(buf), "%" PetscInt_FMT, j));
    PetscCall(PetscStrlen(names, &len));
    PetscCall(PetscSNPrintf(names + len, sizeof(names) - len, "%s%s: %.2f%% -> %.2f%%", len ? "; " : "", buf, (double)(100 * En[j]), (double)(100 * Er[j])));
    PetscCall(PetscStrlen(ids, &len));
    PetscCall(PetscSNPrintf(ids + len, sizeof(ids) - len, "%s%" PetscInt_FMT, len ? "," : "", j));
  }
  for (PetscInt j = 0; j < nj && nj <= 64; j++) PetscCall(PetscPrintf(comm, "rom joint_energy %" PetscInt_FMT " members_share %.6e joint_share %.6e\n", j, (double)En[j], (double)Er[j]));
  if (c == 0) PetscCall(PetscPrintf(comm, "rom: WARNING no stiffness correction: no factor in [1e-3, 1e3] on the joints' springs brings stuck mode %" PetscInt_FMT " from %.6g Hz to the node-to-node %.6g Hz (the joints' motion cannot carry the interface's stiffness in this mode); ", k, (double)fr, (double)ft));
  else PetscCall(PetscPrintf(comm, "rom: WARNING stiffness correction %.4g outside [0.9, 1.1] (stuck mode %" PetscInt_FMT ": %.6g Hz reduced, %.6g Hz node-to-node); ", (double)c, k, (double)fr, (double)ft));
  PetscCall(PetscPrintf(comm, "the joints' springs hold %.2f%% of the mode's strain energy where their members' hold %.2f%%; %s: %s\n", (double)(100 * sr), (double)(100 * sn), nn ? (sgn > 0 ? "joints too soft, members' share -> joint's" : "joints too stiff, members' share -> joint's") : "no joint's share explains it", nn ? names : "the joints' motion changes the mode's shape (more joints, or -rom_joint_motion linear or mode)"));
  PetscCall(PetscPrintf(comm, "rom stiffness_joints factor %.6g joints %s deficit_named %.4e deficit_total %.4e\n", (double)c, nn ? ids : "none", (double)(sgn * dsum), (double)(sgn * dtot)));
  PetscCall(PetscFree3(q, u, v));
  PetscCall(PetscFree3(En, Er, ord));
  PetscFunctionReturn(0);
}

/* The reduced model elx as a JRHBM (*hbmx) on the modes of hbm (the node-to-node model's, shared; NULL: its own),
   excited and observed where red says; with corr, every element's kt and kn are scaled so that the stuck mode of
   interest is at hbm's frequency (the factor in *factor; 1 if none in [1e-3, 1e3] reaches it). Unless quiet, the
   factor is printed (`rom stiffness_correction`), with -rom_stiffness_correction 0 the factor that would be needed,
   and a factor outside [0.9, 1.1] is a warning naming the joints responsible (StiffnessJoints). *setup: the
   set-up's wall time [s] */
static PetscErrorCode ReducedHBM(JRReduce red, JRModel model, JRHBM hbm, PetscBool corr, PetscBool quiet, JRElements *elx, JRHBM *hbmx, PetscReal *factor, PetscReal *setup)
{
  MPI_Comm       comm = red->comm;
  JRHBM          hr;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  *factor = 1.0;
  PetscCall(JRHBMCreate(comm, &hr));
  PetscCall(JRHBMSetExcitationDof(hr, red->fdof, red->nout, red->odof));
  PetscCall(JRHBMSetBasis(hr, JR_HBM_BASIS_MIXED));
  PetscCall(JRHBMSetJointMotion(hr, (JRJointMotion)red->fit.jmotion));
  PetscCall(JRHBMSetJointResidual(hr, red->fit.resid));
  PetscCall(JRHBMSetOptionsPrefix(hr, "rom_"));
  PetscCall(JRHBMSetModel(hr, model));
  PetscCall(JRHBMSetElements(hr, elx));
  PetscCall(JRHBMSetFromOptions(hr));
  if (hbm) PetscCall(JRHBMSetModes(hr, hbm));
  PetscCall(PetscTime(&t0));
  PetscCall(JRHBMSetUp(hr));
  PetscCall(PetscTime(&t1));
  *setup = t1 - t0;
  if (hbm && (corr || !quiet)) { /* the stiffness correction: the reduced model's stuck resonance on the node-to-node one */
    PetscInt  k = 0, nm, nf;
    PetscReal ft = 0, *fr, c, f0;
    PetscCall(TargetMode(red, hbm, &k, &ft));
    PetscCall(JRHBMGetSizes(hr, &nm, NULL, NULL));
    PetscCall(PetscMalloc1(nm, &fr));
    PetscCall(JRHBMStickFrequencies(hr, &nf, fr));
    f0 = fr[k];
    PetscCall(PetscFree(fr));
    PetscCall(JRHBMMatchStickFrequency(hr, k, ft, &c));
    if (!quiet) {
      if (corr) PetscCall(PetscPrintf(comm, "rom stiffness_correction %.8f stuck_mode %" PetscInt_FMT " n2n_hz %.8g rom_before_hz %.8g\n", (double)(c == 0 ? 1.0 : c), k, (double)ft, (double)f0));
      else PetscCall(PetscPrintf(comm, "rom stiffness_correction 1 stuck_mode %" PetscInt_FMT " n2n_hz %.8g rom_before_hz %.8g off needed %.8f\n", k, (double)ft, (double)f0, (double)c));
      PetscCall(StiffnessJoints(red, hbm, hr, elx, k, c, f0, ft));
    }
    if (c == 0) c = 1.0;
    if (corr) {
      for (PetscInt e = 0; e < elx->n; e++) {
        elx->kt[e] *= c;
        elx->kn[e] *= c;
      }
      PetscCall(JRHBMSetElements(hr, elx));
      PetscCall(PetscTime(&t0));
      PetscCall(JRHBMSetUp(hr));
      PetscCall(PetscTime(&t1));
      *setup += t1 - t0;
      *factor = c;
    }
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
  reference a user has without node-to-node. fit gets the pair chosen (its wtotal and wcase), for the fit that
  follows.
*/
static PetscErrorCode SelectWeights(JRReduce red, JRModel model, JRHBM hbm, const JRElements *elj, const PetscReal w[], const JRROMCase *cs)
{
  MPI_Comm         comm = red->comm;
  const PetscBool  corr = red->corr_on;
  const PetscInt   romm = red->m, nt = red->nst, nk = red->nsc;
  const PetscReal *wtot = red->swt, *wcas = red->swc;
  JRROMFit        *fit  = &red->fit;
  JRElements elf;
  JRHBM      hf;
  PetscReal  c, su, *wf, *af, best = PETSC_MAX_REAL, bt = 0, bk = 0;
  PetscInt   nlev;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(PetscMemzero(&elf, sizeof(elf)));
  PetscCall(JRROMReduce(comm, elj, 0, w, cs, fit, NULL, PETSC_FALSE, PETSC_TRUE, &elf));
  PetscCall(ReducedHBM(red, model, hbm, corr, PETSC_TRUE, &elf, &hf, &c, &su));
  PetscCall(QuietPeaks(comm, hf, &nlev, &wf, &af));
  PetscCall(JRHBMDestroy(&hf));
  PetscCall(JRElementsDestroy(&elf));
  for (PetscInt i = 0; i < nt; i++)
    for (PetscInt j = 0; j < nk; j++) {
      JRElements elc;
      JRHBM      hc;
      PetscReal *wc, *ac, ea = 0, ef = 0;
      PetscInt   nl;
      JRROMFit   fc = *fit;
      fc.wtotal     = wtot[i];
      fc.wcase      = wcas[j];
      PetscCall(PetscMemzero(&elc, sizeof(elc)));
      PetscCall(JRROMReduce(comm, elj, romm, w, cs, &fc, NULL, PETSC_FALSE, PETSC_TRUE, &elc));
      PetscCall(ReducedHBM(red, model, hbm, corr, PETSC_TRUE, &elc, &hc, &c, &su));
      PetscCall(QuietPeaks(comm, hc, &nl, &wc, &ac));
      PetscCheck(nl == nlev, comm, PETSC_ERR_PLIB, "Different level counts");
      for (PetscInt l = 0; l < nlev; l++) {
        ea = PetscMax(ea, PetscAbsReal(ac[l] / af[l] - 1));
        ef = PetscMax(ef, PetscAbsReal(wc[l] / wf[l] - 1));
      }
      PetscCall(PetscPrintf(comm, "rom select total_weight %g case_weight %g worst_amp_vs_first %.3e worst_freq_vs_first %.3e stiffness_correction %.6f\n", (double)wtot[i], (double)wcas[j], (double)ea, (double)ef, (double)c));
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
  fit->wtotal = bt;
  fit->wcase  = bk;
  PetscCall(PetscTime(&t1));
  PetscCall(PetscPrintf(comm, "rom: fit weights chosen against the first reduction: -rom_fit_total_weight %g -rom_fit_case_weight %g (worst amplitude %.2f%% off the first reduction's peaks; %" PetscInt_FMT " pairs, %.3g s)\n", (double)bt, (double)bk, (double)(100 * best), nt * nk, (double)(t1 - t0)));
  PetscFunctionReturn(0);
}

PetscErrorCode JRReduceCreate(MPI_Comm comm, JRReduce *red)
{
  JRReduce r;

  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(PetscNew(&r));
  r->comm          = comm;
  r->zone_fraction = 0.5;
  r->rings         = 2;
  r->bands         = 6;
  r->obands        = 1;
  r->upto          = 0.9;
  r->nrel          = JR_NREL; /* released modes: from the first members to slip to a third of the slip force (ReleasedModes) */
  r->relauto       = PETSC_TRUE;
  r->mode_weights  = PETSC_TRUE;
  r->corr_on       = PETSC_TRUE;
  r->nst           = 3;
  r->nsc           = 2;
  r->swt[0]        = 20;
  r->swt[1]        = 100;
  r->swt[2]        = 1000;
  r->swc[0]        = 10;
  r->swc[1]        = 0;
  r->corr          = 1.0;
  r->plot          = PETSC_TRUE;
  *red             = r;
  PetscFunctionReturn(0);
}

PetscErrorCode JRReduceDestroy(JRReduce *red)
{
  PetscFunctionBeginUser;
  if (!*red) PetscFunctionReturn(0);
  PetscCall(PetscFree((*red)->lev));
  PetscCall(PetscFree((*red)->ji));
  PetscCall(PetscFree(*red));
  PetscFunctionReturn(0);
}

/*
  JRReduceSetFromOptions - every option of the reduction, read and checked once: the joints (-rom_joints, -rom_strips,
  -rom_boxes, -rom_zone_fraction, -rom_auto_rings, -rom_onset_bands, -rom_onset_upto, -rom_split_width), -rom_elements, -rom_mode_weights, -rom_fit_select (with
  -rom_fit_select_total, -rom_fit_select_case), -rom_stiffness_correction, -rom_save, -rom_load, and the fit's
  (JRROMFitSetFromOptions: -rom_fit_*, -rom_joint_motion)
*/
PetscErrorCode JRReduceSetFromOptions(JRReduce r)
{
  const char *sel[] = {"none", "first"};
  MPI_Comm    comm    = r->comm;
  PetscBool   set, bset, st, sc, rset, bdset, uset, obset, relset;
  PetscInt    nst = 8, nsc = 8, nrel = JR_NREL;

  PetscFunctionBeginUser;
  r->ncut = 64;
  r->nbox = 256;
  PetscOptionsBegin(comm, "rom_", "Reduced-order joints (prefix rom_)", "JRReduce");
  PetscCall(PetscOptionsEList("-joints", "First reduction, the joints: none (node-to-node), each, strips (-rom_strips cuts), bolts, between, sides, zones (per bolt side and load), boxes (-rom_boxes), auto (rings of equal load around each bolt, -rom_auto_rings), onset (bands of slip onset in the stuck mode of interest, per bolt side, -rom_onset_bands)", "JRReduceAssignJoints", JRReduceJointKinds, 10, JRReduceJointKinds[r->joints], &r->joints, NULL));
  PetscCall(PetscOptionsRealArray("-strips", "Cut positions along the beam axis x1,x2,... [m], increasing", "JRReduceAssignJoints", r->cut, &r->ncut, &set));
  PetscCall(PetscOptionsRealArray("-boxes", "Boxes x0,x1,y0,y1 per joint [m]", "JRReduceAssignJoints", r->box, &r->nbox, &bset));
  PetscCall(PetscOptionsReal("-zone_fraction", "-rom_joints zones: the high-load zone of a bolt side holds the members with n0 at least this fraction of the side's largest", "JRReduceAssignJoints", r->zone_fraction, &r->zone_fraction, NULL));
  PetscCall(PetscOptionsInt("-auto_rings", "-rom_joints auto: rings of equal load per bolt (each cut into the bolt's two sides)", "JRReduceAssignJoints", r->rings, &r->rings, &rset));
  PetscCall(PetscOptionsInt("-onset_bands", "-rom_joints onset: bands of slip onset in the stuck mode of interest (each split by bolt side)", "JRReduceAssignJoints", r->bands, &r->bands, &bdset));
  PetscCall(PetscOptionsInt("-onset_open_bands", "-rom_joints onset: bands of closing onset in the stuck mode of interest that divide the open members (each split by bolt side)", "JRReduceAssignJoints", r->obands, &r->obands, &obset));
  PetscCall(PetscOptionsReal("-onset_upto", "-rom_joints onset: the bands divide, in equal ratios, the slip onsets from the first to the one by which this fraction of the interface's slip force mu n0 slips (later onsets join the last band)", "JRReduceAssignJoints", r->upto, &r->upto, &uset));
  PetscCall(PetscOptionsRealArray("-release_fractions", "-rom_joint_motion shapes (or mode): the released modes, each the stuck mode of interest with the members that slip first (in the order of their slip onsets in it) freed until they hold this fraction of the interface's slip force mu n0; increasing, in (0, 1), up to 6 (default for shapes: 6, from the first members to slip, in equal ratios up to 0.3)", "JRReduceSetUp", r->rel, &nrel, &relset));
  PetscCall(PetscOptionsBool("-split_width", "Split every strip at mid-width into two joints", "JRReduceAssignJoints", r->split_width, &r->split_width, NULL));
  PetscCall(PetscOptionsInt("-elements", "Second reduction: fit this many elements per joint to its hysteresis loops (0: the first reduction only)", "JRReduceSetUp", r->m, &r->m, NULL));
  PetscCall(PetscOptionsBool("-mode_weights", "Weight every member of a joint by its motion relative to the joint's in the stuck mode of interest (w^2 kt, |w| f; jenkins)", "JRReduceSetUp", r->mode_weights, &r->mode_weights, NULL));
  PetscCall(PetscOptionsEList("-fit_select", "Second reduction: none (the fit weights as given) or first (fit with every pair of -rom_fit_select_total x -rom_fit_select_case and keep the pair whose peaks come nearest the first reduction's; nothing to choose with -rom_elements 0)", "JRReduceSetUp", sel, 2, sel[r->select], &r->select, NULL));
  PetscCall(PetscOptionsRealArray("-fit_select_total", "-rom_fit_select first: the -rom_fit_total_weight values tried", "JRReduceSetUp", r->swt, &nst, &st));
  PetscCall(PetscOptionsRealArray("-fit_select_case", "-rom_fit_select first: the -rom_fit_case_weight values tried", "JRReduceSetUp", r->swc, &nsc, &sc));
  PetscCall(PetscOptionsBool("-stiffness_correction", "Scale the reduced elements' stiffness so that the stuck resonance is the node-to-node one", "JRReduceCreateHBM", r->corr_on, &r->corr_on, NULL));
  PetscCall(PetscOptionsString("-save", "Save the reduced model (second reduction) to this HDF5 file", "JRReduceSave", r->save, r->save, sizeof(r->save), NULL));
  PetscCall(PetscOptionsString("-load", "Run the reduced model of this HDF5 file (no preload, no fit)", "JRReduceLoad", r->load, r->load, sizeof(r->load), NULL));
  PetscOptionsEnd();
  if (!set) r->ncut = 0;
  if (!bset) r->nbox = 0;
  if (st) r->nst = nst;
  if (sc) r->nsc = nsc;
  PetscCheck(!set || r->joints == 2, comm, PETSC_ERR_ARG_INCOMP, "-rom_strips needs -rom_joints strips");
  PetscCheck(!bset || r->joints == 7, comm, PETSC_ERR_ARG_INCOMP, "-rom_boxes needs -rom_joints boxes");
  PetscCheck(!rset || r->joints == 8, comm, PETSC_ERR_ARG_INCOMP, "-rom_auto_rings needs -rom_joints auto");
  PetscCheck(!bdset || r->joints == 9, comm, PETSC_ERR_ARG_INCOMP, "-rom_onset_bands needs -rom_joints onset");
  PetscCheck(!uset || r->joints == 9, comm, PETSC_ERR_ARG_INCOMP, "-rom_onset_upto needs -rom_joints onset");
  PetscCheck(!obset || r->joints == 9, comm, PETSC_ERR_ARG_INCOMP, "-rom_onset_open_bands needs -rom_joints onset");
  PetscCheck(r->obands >= 1 && r->obands <= 16, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_onset_open_bands %" PetscInt_FMT ": 1 to 16 bands", r->obands);
  PetscCheck(r->upto > 0 && r->upto <= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_onset_upto %g: a fraction in (0, 1]", (double)r->upto);
  PetscCheck(r->bands >= 1 && r->bands <= 16, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_onset_bands %" PetscInt_FMT ": 1 to 16 bands", r->bands);
  PetscCheck(r->rings >= 1 && r->rings <= 8, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_auto_rings %" PetscInt_FMT ": 1 to 8 rings per bolt", r->rings);
  PetscCheck(!r->split_width || (r->joints >= 2 && r->joints <= 6), comm, PETSC_ERR_ARG_INCOMP, "-rom_split_width needs -rom_joints strips, bolts, between, sides or zones");
  PetscCheck(r->zone_fraction > 0 && r->zone_fraction < 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_zone_fraction %g: between 0 and 1", (double)r->zone_fraction);
  PetscCheck(r->joints != 2 || r->ncut > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_joints strips needs the cuts -rom_strips x1,x2,... [m]");
  for (PetscInt k = 1; k < r->ncut; k++) PetscCheck(r->cut[k] > r->cut[k - 1], comm, PETSC_ERR_ARG_WRONG, "-rom_strips: the cuts must increase, but %g m follows %g m", (double)r->cut[k], (double)r->cut[k - 1]);
  PetscCheck(r->joints != 7 || (r->nbox >= 4 && r->nbox % 4 == 0), comm, PETSC_ERR_ARG_WRONG, "-rom_boxes needs x0,x1,y0,y1 per joint [m], got %" PetscInt_FMT " values", r->nbox);
  PetscCheck(r->m >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_elements %" PetscInt_FMT ": 0 (first reduction only) or more", r->m);
  PetscCheck(r->nst > 0 && r->nsc > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_select_total and -rom_fit_select_case: at least one value each (at most 8)");
  for (PetscInt i = 0; i < r->nst; i++) PetscCheck(r->swt[i] >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_select_total: %g: the weights must be non-negative", (double)r->swt[i]);
  for (PetscInt i = 0; i < r->nsc; i++) PetscCheck(r->swc[i] >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_fit_select_case: %g: the weights must be non-negative", (double)r->swc[i]);
  if (r->load[0]) {
    PetscBool ok;
    PetscCall(PetscTestFile(r->load, 'r', &ok));
    PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "-rom_load %s: no such file (write one with -rom_save)", r->load);
    PetscCall(JRFileCheckHDF5(comm, "-rom_load", r->load, "/rom", "write one with -rom_save"));
  }
  PetscCall(JRROMFitSetFromOptions(comm, &r->fit));
  PetscCheck(!r->fit.mmax || (r->m > 0 && r->fit.mmax >= r->m), comm, PETSC_ERR_ARG_INCOMP, "-rom_fit_elements_max %" PetscInt_FMT ": at least -rom_elements (%" PetscInt_FMT "), the elements every joint starts with", r->fit.mmax, r->m);
  if (relset) {
    r->nrel    = nrel;
    r->relauto = PETSC_FALSE;
  } else if (r->fit.jmotion != JR_JOINT_MOTION_SHAPES) r->nrel = 0; /* mode: released modes only when asked for */
  PetscCheck(!relset || r->fit.jmotion >= JR_JOINT_MOTION_MODE, comm, PETSC_ERR_ARG_INCOMP, "-rom_release_fractions needs -rom_joint_motion mode or shapes");
  PetscCheck(!relset || r->nrel > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_release_fractions: 1 to %d fractions", JR_NREL);
  for (PetscInt i = 0; relset && i < r->nrel; i++) PetscCheck(r->rel[i] > 0 && r->rel[i] < 1 && (!i || r->rel[i] > r->rel[i - 1]), comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_release_fractions: %g: the fractions must increase, each in (0, 1)", (double)r->rel[i]);
  r->setfromoptions = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* What the options ask for: joints (a first reduction), m (-rom_elements), the joint motion (0 mean, 1 linear, 2
   mode), the files of -rom_save and -rom_load ("" none); any argument may be NULL */
PetscErrorCode JRReduceGetRequest(JRReduce r, PetscBool *joints, PetscInt *m, PetscInt *jmotion, const char **save, const char **load)
{
  PetscFunctionBeginUser;
  if (joints) *joints = (PetscBool)(r->joints > 0);
  if (m) *m = r->m;
  if (jmotion) *jmotion = r->fit.jmotion;
  if (save) *save = r->save;
  if (load) *load = r->load;
  PetscFunctionReturn(0);
}

/* The case the reduced model is for: the frequency range [rad/s] (the mode of interest is the stuck mode nearest its
   middle; wmax 0: the lowest elastic mode) and the excitation levels [N] */
PetscErrorCode JRReduceSetCase(JRReduce r, PetscReal wmin, PetscReal wmax, PetscInt nlev, const PetscReal lev[])
{
  PetscFunctionBeginUser;
  r->wmin = wmin;
  r->wmax = wmax;
  PetscCall(PetscFree(r->lev));
  r->nlev = nlev;
  PetscCall(PetscMalloc1(nlev + 1, &r->lev));
  PetscCall(PetscArraycpy(r->lev, lev, nlev));
  PetscFunctionReturn(0);
}

/* The excitation DOF and the response DOFs of the reduced model's harmonic balance (as JRHBMSetExcitationDof) */
PetscErrorCode JRReduceSetExcitation(JRReduce r, PetscInt fdof, PetscInt nout, const PetscInt odof[])
{
  PetscFunctionBeginUser;
  PetscCheck(nout >= 1 && nout <= 64, r->comm, PETSC_ERR_ARG_OUTOFRANGE, "1 to 64 response DOFs, not %" PetscInt_FMT, nout);
  r->fdof = fdof;
  r->nout = nout;
  PetscCall(PetscArraycpy(r->odof, odof, nout));
  PetscFunctionReturn(0);
}

/* BASE_rom_loops.csv (and .png with plot): the loops of the fit ("" for none) */
PetscErrorCode JRReduceSetOutput(JRReduce r, const char base[], PetscBool plot)
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(r->base, base ? base : "", sizeof(r->base)));
  r->plot = plot;
  PetscFunctionReturn(0);
}



/* -rom_joint_motion shapes (or mode with -rom_release_fractions): the members' tangential motions elj->phir in the
   released modes. A member in contact at
   rest starts to slip at the modal amplitude a_e = mu n0_e / (kt |u_e|) in the stuck mode of interest k (u: its
   motion in it); in that order, released mode i frees (kt = 0) the members that slip first until they hold the fraction
   r->rel[i] of the interface's slip force mu n0 (with every member whose onset ties with the last one's, to 1e-6) and
   is the mode of that structure most like mode k (largest |q^T M q_k|),
   so a joint's field spans the motion of a slip front inside it. A joint without a freed member takes no coordinate from
   that mode (0: the joint's field keeps only what it spans). Each mode is scaled to a largest member motion of 1. */
static PetscErrorCode ReleasedModes(JRReduce r, JRHBM hbm, JRElements *elj, PetscInt k, const PetscReal u[])
{
  const PetscInt n = elj->n;
  PetscReal     *a, *ktf, *ur, tot = 0;
  PetscInt      *perm, *has;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc4(n, &a, n, &ktf, n, &ur, n, &perm));
  PetscCall(PetscCalloc1(elj->njoints, &has));
  PetscCall(PetscFree(elj->phir));
  PetscCall(PetscCalloc1(JR_NREL * n, &elj->phir));
  for (PetscInt e = 0; e < n; e++) {
    perm[e] = e;
    a[e]    = elj->n0[e] > 0 && PetscAbsReal(u[e]) > 0 ? elj->mu[e] * elj->n0[e] / (elj->kt[e] * PetscAbsReal(u[e])) : PETSC_MAX_REAL;
    if (elj->n0[e] > 0) tot += elj->mu[e] * elj->n0[e];
  }
  PetscCall(PetscSortRealWithPermutation(n, a, perm));
  if (r->relauto) { /* the first members to slip (their onsets tied), s1 of the slip force, then in equal ratios to 0.3 */
    PetscReal s1 = 0;
    for (PetscInt q = 0; q < n && a[perm[q]] < PETSC_MAX_REAL && (q == 0 || a[perm[q]] <= a[perm[q - 1]] * (1 + 1e-6)); q++) s1 += elj->mu[perm[q]] * elj->n0[perm[q]];
    s1 = tot > 0 ? s1 / tot : 0;
    PetscCheck(s1 > 0, r->comm, PETSC_ERR_ARG_WRONG, "-rom_joint_motion %s: no member in contact moves in the stuck mode of interest, so none slips first; -rom_release_fractions sets the released modes", r->fit.jmotion == JR_JOINT_MOTION_SHAPES ? "shapes" : "mode");
    r->nrel = s1 < JR_REL_TOP ? JR_NREL : 1;
    r->rel[0] = 0.5 * s1; /* frees the first tied members alone */
    for (PetscInt i = 1; i < r->nrel; i++) r->rel[i] = s1 * PetscPowReal(JR_REL_TOP / s1, i / (PetscReal)(r->nrel - 1));
    PetscCall(PetscPrintf(r->comm, "rom: release fractions from the first members to slip (%.3g of the interface's slip force) in equal ratios up to %g (-rom_release_fractions sets them)\n", (double)s1, (double)JR_REL_TOP));
  }
  for (PetscInt i = 0, c = 0, last = 0; i < r->nrel; i++) {
    PetscReal cum = 0, um = 0, fr;
    PetscInt  nfree = 0, nj = 0;
    for (PetscInt e = 0; e < n; e++) ktf[e] = 1.0;
    for (PetscInt j = 0; j < elj->njoints; j++) has[j] = 0;
    for (PetscInt q = 0; q < n && a[perm[q]] < PETSC_MAX_REAL && (cum < r->rel[i] * tot || (q > 0 && a[perm[q]] <= a[perm[q - 1]] * (1 + 1e-6))); q++) {
      const PetscInt e = perm[q]; /* (members whose onsets tie with the last one freed are freed too: a set that round-off cannot change) */
      ktf[e]           = 0.0;
      cum += elj->mu[e] * elj->n0[e];
      has[elj->joint[e]] = 1;
      nfree++;
    }
    if (nfree == last) { /* the same members as the fraction before (a group of tied onsets): the same mode again */
      PetscCall(PetscPrintf(r->comm, "rom: release fraction %g frees the same %" PetscInt_FMT " members as the one before: no mode from it\n", (double)r->rel[i], nfree));
      continue;
    }
    last = nfree;
    PetscCall(JRHBMReleasedModeMotion(hbm, k, ktf, ur, &fr));
    for (PetscInt e = 0; e < n; e++) um = PetscMax(um, PetscAbsReal(ur[e]));
    PetscCheck(um > 0, r->comm, PETSC_ERR_ARG_WRONG, "-rom_release_fractions: the interface does not move in released mode %" PetscInt_FMT " (%g of the slip force freed)", c, (double)r->rel[i]);
    for (PetscInt e = 0; e < n; e++) elj->phir[JR_NREL * e + c] = has[elj->joint[e]] ? ur[e] / um : 0.0;
    for (PetscInt j = 0; j < elj->njoints; j++) nj += has[j];
    PetscCall(PetscPrintf(r->comm, "rom: released mode %" PetscInt_FMT ": %.6g Hz, %" PetscInt_FMT " members freed (%.3g of the slip force, the first to slip) in %" PetscInt_FMT " joints\n", c, (double)fr, nfree, (double)(tot > 0 ? cum / tot : 0), nj));
    c++;
  }
  PetscCall(PetscFree(has));
  PetscCall(PetscFree4(a, ktf, ur, perm));
  PetscFunctionReturn(0);
}

/*
  JRReduceSetUp - the reduced model elr from the node-to-node elements elj whose joints JRReduceAssignJoints set:
  the stuck mode of interest of hbm (the node-to-node model, set up), each member's motion over its joint's in it (the
  mode-shape weights, 4.4 over its members in contact at rest, all if none) and the joints' amplitudes in the case
  (jenkins, or -rom_joint_motion mode: then the members' field coordinates too, in elj->phi), the fit weights'
  selection (-rom_fit_select first) and the fit (-rom_elements m; 0: the first reduction itself). *seconds: its wall
  time.
*/
PetscErrorCode JRReduceSetUp(JRReduce r, JRModel model, JRHBM hbm, JRElements *elj, JRElements *elr, PetscReal *seconds)
{
  MPI_Comm       comm = r->comm;
  PetscReal     *w = NULL, *ubar = NULL;
  JRROMCase      cs;
  PetscLogDouble t0, t1;
  const PetscInt jmotion = r->fit.jmotion, n = elj->n;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&cs, sizeof(cs)));
  PetscCall(PetscTime(&t0));
  if (r->joints == 9) { /* onset: the joints from the members' slip onsets in the stuck mode of interest */
    PetscInt  k = 0;
    PetscReal ft = 0, *u, *v;
    PetscCall(TargetMode(r, hbm, &k, &ft));
    PetscCall(PetscMalloc1(n, &u));
    PetscCall(PetscMalloc1(n, &v));
    PetscCall(JRHBMStuckModeMotion(hbm, k, u, v));
    PetscCall(JRReduceAssignOnset(r, model, elj, u, v));
    PetscCall(PetscFree(u));
    PetscCall(PetscFree(v));
  }
  if (!strcmp(elj->typename[0], JRCONTACTJENKINS) || jmotion >= JR_JOINT_MOTION_MODE) {
    PetscInt  k = 0;
    PetscReal ft = 0, *u, *v, *cnt, *ua, umax = 0, smax = 0, om;
    PetscCall(TargetMode(r, hbm, &k, &ft));
    PetscCall(PetscMalloc2(n, &u, n, &v));
    PetscCall(PetscCalloc1(elj->njoints, &ubar));
    PetscCall(PetscCalloc2(2 * elj->njoints, &cnt, elj->njoints, &ua));
    PetscCall(JRHBMStuckModeMotion(hbm, k, u, v));
    for (PetscInt e = 0; e < n; e++) { /* per joint: sum and count over its members in contact at rest, then over all */
      const PetscInt j = elj->joint[e];
      if (elj->n0[e] > 0) {
        ubar[j] += u[e];
        cnt[2 * j] += 1;
      }
      ua[j] += u[e];
      cnt[2 * j + 1] += 1;
      umax = PetscMax(umax, PetscAbsReal(u[e]));
    }
    for (PetscInt j = 0; j < elj->njoints; j++) ubar[j] = cnt[2 * j] > 0 ? ubar[j] / cnt[2 * j] : ua[j] / cnt[2 * j + 1];
    if (jmotion >= JR_JOINT_MOTION_MODE) { /* -rom_joint_motion mode: each member's field coordinates are its position
                                              and its tangential and normal motions in this mode (scaled to at most 1);
                                              shapes (and mode with -rom_release_fractions): also its tangential
                                              motions in the released modes; the fit weighs the members */
      for (PetscInt e = 0; e < n; e++) smax = PetscMax(smax, PetscMax(PetscAbsReal(u[e]), PetscAbsReal(v[e])));
      PetscCheck(smax > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_joint_motion %s: the interface does not move in stuck mode %" PetscInt_FMT " (%g Hz)", JRJointMotions[jmotion], k, (double)ft);
      PetscCall(PetscFree(elj->phi));
      PetscCall(PetscMalloc1(2 * n, &elj->phi));
      for (PetscInt e = 0; e < n; e++) {
        elj->phi[2 * e]     = u[e] / smax;
        elj->phi[2 * e + 1] = v[e] / smax;
      }
      if (jmotion == JR_JOINT_MOTION_MODE) PetscCall(PetscPrintf(comm, "rom: joints move with a field linear in their members' positions and motions in stuck mode %" PetscInt_FMT " (%.6g Hz)%s\n", k, (double)ft, r->nrel ? " and their tangential motions in the released modes" : ""));
      else PetscCall(PetscPrintf(comm, "rom: joints move with a field linear in their members' positions and tangential motions in stuck mode %" PetscInt_FMT " (%.6g Hz) and in released modes (tangential rows), their normal motion in it (normal rows)\n", k, (double)ft));
      if (r->nrel) PetscCall(ReleasedModes(r, hbm, elj, k, u));
    }
    if (r->mode_weights || jmotion >= JR_JOINT_MOTION_MODE) {
      PetscCall(PetscMalloc1(n, &w));
      for (PetscInt e = 0; e < n; e++) w[e] = PetscAbsReal(ubar[elj->joint[e]]) > 1e-6 * umax ? u[e] / ubar[elj->joint[e]] : 1.0;
      PetscCall(PetscPrintf(comm, "rom: members weighted by their motion in stuck mode %" PetscInt_FMT " (%.6g Hz) over their joint's\n", k, (double)ft));
    }
    PetscCall(JRHBMStuckModeBalance(hbm, k, &om, &cs.force, &cs.damp));
    cs.nlev   = r->nlev;
    cs.level  = r->lev;
    cs.ujoint = ubar;
    PetscCall(PetscFree2(cnt, ua));
    PetscCall(PetscFree2(u, v));
  }
  if (r->select && r->m > 0) {
    PetscCall(PetscLogEventBegin(JR_ReduceSelect, 0, 0, 0, 0));
    PetscCall(SelectWeights(r, model, hbm, elj, w, ubar ? &cs : NULL));
    PetscCall(PetscLogEventEnd(JR_ReduceSelect, 0, 0, 0, 0));
  }
  PetscCall(PetscLogEventBegin(JR_ReduceFit, 0, 0, 0, 0));
  PetscCall(JRROMReduce(comm, elj, r->m, w, ubar ? &cs : NULL, &r->fit, r->base, r->plot, PETSC_FALSE, elr));
  PetscCall(PetscLogEventEnd(JR_ReduceFit, 0, 0, 0, 0));
  PetscCall(PetscFree(ubar));
  PetscCall(PetscFree(w));
  PetscCall(PetscTime(&t1));
  *seconds = t1 - t0;
  PetscCall(PetscPrintf(comm, "rom: %s reduction: %" PetscInt_FMT " elements in %" PetscInt_FMT " joints (%.3g s)\n", r->m ? "second" : "first", elr->n, elr->njoints, (double)*seconds));
  PetscFunctionReturn(0);
}

/*
  JRReduceCreateHBM - the reduced model elr's harmonic balance on the modes of hbm (NULL: its own), with the stiffness
  correction (-rom_stiffness_correction, not for a loaded model: its factor is in its file) that puts its stuck mode
  of interest on hbm's. Prints the factor (`rom stiffness_correction`, also for a loaded model and with the correction
  off) and, outside [0.9, 1.1], a warning naming the joints responsible. *setup: the set-up's wall time [s]
*/
PetscErrorCode JRReduceCreateHBM(JRReduce r, JRModel model, JRHBM hbm, PetscBool loaded, JRElements *elr, JRHBM *hbmr, PetscReal *setup)
{
  PetscReal c = 1.0;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(JR_ReduceHBM, 0, 0, 0, 0));
  PetscCall(ReducedHBM(r, model, hbm, (PetscBool)(!loaded && r->corr_on), loaded, elr, hbmr, &c, setup));
  PetscCall(PetscLogEventEnd(JR_ReduceHBM, 0, 0, 0, 0));
  if (!loaded) r->corr = c;
  else { /* the factor applied when the file was written, in its elements' springs */
    PetscCall(PetscPrintf(r->comm, "rom stiffness_correction %.8f file %s\n", (double)r->corr, r->load));
    if (r->corr < 0.9 || r->corr > 1.1) PetscCall(PetscPrintf(r->comm, "rom: WARNING stiffness correction %.4g outside [0.9, 1.1] in %s (applied when it was written; the run that wrote it named the joints responsible)\n", (double)r->corr, r->load));
  }
  PetscFunctionReturn(0);
}

/* -rom_save: the reduced model elr, with its stiffness correction (nothing without -rom_save) */
PetscErrorCode JRReduceSave(JRReduce r, JRModel model, const JRElements *elr)
{
  PetscFunctionBeginUser;
  if (r->save[0]) PetscCall(JRROMSave(model, elr, r->corr, r->fit.jmotion, r->save));
  PetscFunctionReturn(0);
}

/* -rom_load: the reduced model of the file, for this FE model */
PetscErrorCode JRReduceLoad(JRReduce r, JRModel model, JRElements *elr)
{
  PetscInt jm;

  PetscFunctionBeginUser;
  PetscCall(JRROMLoad(model, r->load, elr, &r->corr, &jm));
  if (jm >= 0) { /* the joint motion that saved it (a file without one: as -rom_joint_motion says) */
    PetscBool set;
    PetscCall(PetscOptionsHasName(NULL, NULL, "-rom_joint_motion", &set));
    PetscCheck(!set || jm == r->fit.jmotion, r->comm, PETSC_ERR_ARG_INCOMP, "-rom_load %s: the model was reduced with -rom_joint_motion %s, not %s (the file's joint motion is used: leave the option out)", r->load, JRJointMotions[jm], JRJointMotions[r->fit.jmotion]);
    r->fit.jmotion = jm;
  }
  PetscFunctionReturn(0);
}

/* The stiffness correction applied to the reduced model's springs (1: none) */
PetscErrorCode JRReduceGetStiffnessCorrection(JRReduce r, PetscReal *c)
{
  PetscFunctionBeginUser;
  *c = r->corr;
  PetscFunctionReturn(0);
}

PetscErrorCode JRReduceView(JRReduce r, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  if (!viewer) viewer = PETSC_VIEWER_STDOUT_(r->comm);
  PetscCall(PetscViewerASCIIPrintf(viewer, "JRReduce: joints %s, %" PetscInt_FMT " elements per joint%s, joint motion %s, stiffness correction %s (%g)\n", JRReduceJointKinds[r->joints], r->m, r->m ? "" : " (first reduction)", JRJointMotions[r->fit.jmotion], r->corr_on ? "on" : "off", (double)r->corr));
  PetscFunctionReturn(0);
}
