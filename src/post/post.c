/*
   JRPost: the outputs of a frequency-response run (the curves: curves.c, JRPostWriteCurves): the contact state
   of every element at each peak (BASE_contact.csv, .png) and the comparison of two models (BASE_compare.csv,
   .png, 'compare ...' lines). BASE is -frf_output_file ("" for no files); -frf_plot draws the PNGs.
*/
#include <jointrom/private/modelimpl.h>
#include <jointrom/private/postimpl.h>


PetscErrorCode JRPostCreate(MPI_Comm comm, JRPost *post)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(post));
  (*post)->comm = comm;
  (*post)->plot = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The output base name ("" for no files) and whether to draw the PNGs */
PetscErrorCode JRPostSetOutput(JRPost post, const char base[], PetscBool plot)
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(post->base, base ? base : "", sizeof(post->base)));
  post->plot = plot;
  PetscFunctionReturn(0);
}

PetscErrorCode JRPostDestroy(JRPost *post)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(*post));
  PetscFunctionReturn(0);
}

/* BASE_contact.csv (pair, x, y, z, the state at each level's peak of cont) and BASE_contact.png; a 'contact level' line
   per level with the counts of the four states */
PetscErrorCode JRPostWriteContactMaps(JRPost post, JRModel model, JRCont cont, const JRElements *el, const PetscInt pair[])
{
  MPI_Comm        comm = post->comm;
  const char     *base = post->base;
  const PetscBool plot = post->plot;
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

/* The energy dissipated per cycle by each joint of h's model at the peak of every level of c (c's model: h's, or
   another on the same modal unknowns): in *E (nj per level, on every rank), each element counted in its joint
   (joint[]) */
static PetscErrorCode JointDissipation(JRHBM h, JRCont c, PetscInt nlev, PetscInt nj, const PetscInt joint[], PetscReal E[])
{
  const JRElements *el;
  Vec               a;
  PetscReal        *e;
  PetscInt          n;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetElements(h, &el));
  PetscCall(JRHBMGetSizes(h, NULL, NULL, &n));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &a)); /* the modal unknowns (a condensed model's too) */
  PetscCall(PetscMalloc1(el->n, &e));
  PetscCall(PetscArrayzero(E, nlev * nj));
  for (PetscInt l = 0; l < nlev; l++) {
    PetscCall(JRContGetPeakSolution(c, l, a));
    PetscCall(JRHBMElementDissipation(h, a, e));
    for (PetscInt k = 0; k < el->n; k++) E[l * nj + joint[k]] += e[k];
  }
  PetscCall(PetscFree(e));
  PetscCall(VecDestroy(&a));
  PetscFunctionReturn(0);
}

/*
  JRPostCompareJoints - -task compare: where the two models dissipate at each level's peak, joint by joint (cn the
  node-to-node curves, its elements counted in the joints of elj, the reduction's members; cr the reduced model's, in
  its own joints): "compare joints level <F> n2n_J <E> rom_J <E> worst_joint <j> n2n_share <s> rom_share <s>" (the
  joint whose share of its model's friction dissipation differs most) and BASE_compare_joints.csv, every joint's
  energy per cycle [J] and share at every level
*/
PetscErrorCode JRPostCompareJoints(JRPost post, JRCont cn, JRCont cr, const JRElements *elj, const JRElements *elr)
{
  MPI_Comm  comm = post->comm;
  PetscInt  nlev, nj = elj->njoints;
  PetscReal *En, *Er, *Ex = NULL;
  JRHBM      hn, hr;
  PetscInt   un, ur; /* the two models' unknowns */
  FILE     *fp = NULL;
  char      csv[PETSC_MAX_PATH_LEN + 32], tmp[PETSC_MAX_PATH_LEN + 48];

  PetscFunctionBeginUser;
  PetscCheck(elj->joint && elr->joint && elr->njoints == nj, comm, PETSC_ERR_ARG_WRONG, "Both models' elements need the same joints");
  PetscCall(JRContGetNumLevels(cn, &nlev));
  PetscCall(PetscMalloc2(nlev * nj, &En, nlev * nj, &Er));
  PetscCall(JRContGetHBM(cn, &hn));
  PetscCall(JRContGetHBM(cr, &hr));
  PetscCall(JointDissipation(hn, cn, nlev, nj, elj->joint, En));
  PetscCall(JointDissipation(hr, cr, nlev, nj, elr->joint, Er));
  PetscCall(JRHBMGetSizes(hn, NULL, NULL, &un));
  PetscCall(JRHBMGetSizes(hr, NULL, NULL, &ur));
  if (un == ur) { /* the same modal unknowns (a reduced model on the node-to-node basis, not condensed): the reduced
                     joints under the node-to-node peak's motion, where they should dissipate what its members do */
    PetscCall(PetscMalloc1(nlev * nj, &Ex));
    PetscCall(JointDissipation(hr, cn, nlev, nj, elr->joint, Ex));
  }
  if (post->base[0]) {
    PetscCall(PetscSNPrintf(csv, sizeof(csv), "%s_compare_joints.csv", post->base));
    PetscCall(JRFileOpenTemp(comm, csv, &fp, tmp, sizeof(tmp)));
    if (fp) fprintf(fp, "level,F_N,joint,n2n_dissipation_J,rom_dissipation_J,n2n_share,rom_share,rom_at_n2n_peak_J\n");
  }
  for (PetscInt l = 0; l < nlev; l++) {
    PetscReal F, tn = 0, tr = 0, tx = 0, worst = -1;
    PetscInt  jw = 0;
    PetscCall(JRContGetLevel(cn, l, &F));
    for (PetscInt j = 0; j < nj; j++) {
      tn += En[l * nj + j];
      tr += Er[l * nj + j];
      tx += Ex ? Ex[l * nj + j] : 0;
    }
    for (PetscInt j = 0; j < nj; j++) {
      const PetscReal sn = tn > 0 ? En[l * nj + j] / tn : 0, sr = tr > 0 ? Er[l * nj + j] / tr : 0;
      if (PetscAbsReal(sr - sn) > worst) {
        worst = PetscAbsReal(sr - sn);
        jw    = j;
      }
      if (fp) fprintf(fp, "%" PetscInt_FMT ",%.9g,%" PetscInt_FMT ",%.9e,%.9e,%.6e,%.6e,%.9e\n", l, (double)F, j, (double)En[l * nj + j], (double)Er[l * nj + j], (double)sn, (double)sr, (double)(Ex ? Ex[l * nj + j] : NAN));
    }
    PetscCall(PetscPrintf(comm, "compare joints level %g n2n_J %.6e rom_J %.6e worst_joint %" PetscInt_FMT " n2n_share %.4f rom_share %.4f", (double)F, (double)tn, (double)tr, jw, (double)(tn > 0 ? En[l * nj + jw] / tn : 0), (double)(tr > 0 ? Er[l * nj + jw] / tr : 0)));
    if (Ex) PetscCall(PetscPrintf(comm, " rom_at_n2n_peak_J %.6e", (double)tx));
    PetscCall(PetscPrintf(comm, "\n"));
  }
  if (post->base[0]) {
    PetscCall(JRFileCommit(comm, &fp, tmp, csv));
    PetscCall(PetscPrintf(comm, "compare: wrote %s\n", csv));
  }
  PetscCall(PetscFree2(En, Er));
  PetscCall(PetscFree(Ex));
  PetscFunctionReturn(0);
}

/* -task compare: per level the peaks of both models (cn node-to-node, cr reduced) and their errors, the wall times,
   BASE_compare.csv and .png */
PetscErrorCode JRPostCompareReport(JRPost post, JRCont cn, JRCont cr, const JRElements *eln, const JRElements *elr, const JRCompareTimes *t)
{
  MPI_Comm        comm = post->comm;
  const char     *base = post->base;
  const PetscBool plot = post->plot;
  const PetscReal tn = t->n2n_solve, tr = t->rom_solve, en = t->n2n_elements, er = t->rom_elements, setn = t->n2n_setup, setr = t->rom_setup, tred = t->reduction;
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
