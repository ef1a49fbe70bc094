/*
   JRPost: the backbones of two models' nonlinear mode side by side (-task compare -compare_nlmodes): at every
   node-to-node point, the reduced model's backbone interpolated at the same modal amplitude (linear in log q,
   JRNLModesInterpolate), their frequencies and damping ratios and the differences; BASE_nlmodes_compare.csv and .png
   (share/plot_backbone_compare.gp, from the two models' CSVs). BASE is -frf_output_file ("" for no files).
*/
#include <jointrom/private/postimpl.h>

/* The frequency [Hz] and damping ratio ranges of a backbone */
static PetscErrorCode Ranges(JRNLModes m, PetscReal f[2], PetscReal d[2])
{
  PetscInt         np;
  const PetscReal *w, *xi;

  PetscFunctionBeginUser;
  PetscCall(JRNLModesGetBackbone(m, &np, NULL, &w, &xi, NULL, NULL));
  f[0] = d[0] = PETSC_MAX_REAL;
  f[1] = d[1] = 0;
  for (PetscInt k = 0; k < np; k++) {
    f[0] = PetscMin(f[0], w[k] / (2 * PETSC_PI));
    f[1] = PetscMax(f[1], w[k] / (2 * PETSC_PI));
    d[0] = PetscMin(d[0], xi[k] / (2 * w[k]));
    d[1] = PetscMax(d[1], xi[k] / (2 * w[k]));
  }
  PetscFunctionReturn(0);
}

/*
  JRPostCompareBackbones - the node-to-node backbone n and the reduced model's r (solved, over the same amplitudes):
  one line per node-to-node point
    compare backbone point <i> amplitude <q> n2n_freq_hz <f> rom_freq_hz <f> freq_rel_diff <e> n2n_damping_ratio <D>
      rom_damping_ratio <D> damping_diff <d>
  (rom at the same q, interpolated in log q; damping_diff = rom D - n2n D), then the worst differences, the two
  ranges and the two solve times ("compare backbone worst ..", ".. range ..", ".. time .."); BASE_nlmodes_compare.csv
  and, with -frf_plot, BASE_nlmodes_compare.png. Collective.
*/
PetscErrorCode JRPostCompareBackbones(JRPost post, JRNLModes n, JRNLModes r)
{
  MPI_Comm         comm = post->comm;
  const char      *base = post->base, *bn, *br;
  PetscInt         np, nc = 0;
  const PetscReal *q, *w, *xi;
  PetscReal        worstf = 0, worstd = 0, worstdr = 0, fn[2], dn[2], fr[2], dr[2], tn, tr;
  FILE            *fp = NULL;
  char             csv[PETSC_MAX_PATH_LEN + 32], tmp[PETSC_MAX_PATH_LEN + 48];

  PetscFunctionBeginUser;
  PetscCall(JRNLModesGetBackbone(n, &np, &q, &w, &xi, NULL, NULL));
  if (base[0]) {
    PetscCall(PetscSNPrintf(csv, sizeof(csv), "%s_nlmodes_compare.csv", base));
    PetscCall(JRFileOpenTemp(comm, csv, &fp, tmp, sizeof(tmp)));
    if (fp) fprintf(fp, "point,q,n2n_freq_hz,rom_freq_hz,freq_rel_diff,n2n_damping_ratio,rom_damping_ratio,damping_diff,damping_rel_diff,n2n_amp_1,rom_amp_1\n");
  }
  for (PetscInt k = 0; k < np; k++) {
    PetscReal wr, xr, ar, an, f0, f1, d0, d1, ef, ed;
    PetscBool in;
    PetscCall(JRNLModesInterpolate(n, q[k], NULL, NULL, &an, &in)); /* response 1 at the point itself */
    PetscCall(JRNLModesInterpolate(r, q[k], &wr, &xr, &ar, &in));
    if (!in) continue; /* beyond the reduced backbone (an incomplete one) */
    f0 = w[k] / (2 * PETSC_PI);
    f1 = wr / (2 * PETSC_PI);
    d0 = xi[k] / (2 * w[k]);
    d1 = xr / (2 * wr);
    ef = f1 / f0 - 1;
    ed = d1 - d0;
    worstf  = PetscMax(worstf, PetscAbsReal(ef));
    worstd  = PetscMax(worstd, PetscAbsReal(ed));
    worstdr = PetscMax(worstdr, PetscAbsReal(ed / d0));
    nc++;
    PetscCall(PetscPrintf(comm, "compare backbone point %" PetscInt_FMT " amplitude %.10e n2n_freq_hz %.10g rom_freq_hz %.10g freq_rel_diff %+.4e n2n_damping_ratio %.8e rom_damping_ratio %.8e damping_diff %+.4e\n", k, (double)q[k], (double)f0, (double)f1, (double)ef, (double)d0, (double)d1, (double)ed));
    if (fp) fprintf(fp, "%" PetscInt_FMT ",%.12e,%.12g,%.12g,%.6e,%.10e,%.10e,%.6e,%.6e,%.10e,%.10e\n", k, (double)q[k], (double)f0, (double)f1, (double)ef, (double)d0, (double)d1, (double)ed, (double)(ed / d0), (double)an, (double)ar);
  }
  PetscCall(Ranges(n, fn, dn));
  PetscCall(Ranges(r, fr, dr));
  PetscCall(JRNLModesGetStats(n, &tn, NULL, NULL));
  PetscCall(JRNLModesGetStats(r, &tr, NULL, NULL));
  PetscCall(PetscPrintf(comm, "compare backbone worst freq_rel_diff %.3e damping_diff %.3e damping_rel_diff %.3e points %" PetscInt_FMT " of %" PetscInt_FMT "\n", (double)worstf, (double)worstd, (double)worstdr, nc, np));
  PetscCall(PetscPrintf(comm, "compare backbone range n2n_freq_hz %.8g %.8g n2n_damping_ratio %.6e %.6e rom_freq_hz %.8g %.8g rom_damping_ratio %.6e %.6e\n", (double)fn[0], (double)fn[1], (double)dn[0], (double)dn[1], (double)fr[0], (double)fr[1], (double)dr[0], (double)dr[1]));
  PetscCall(PetscPrintf(comm, "compare backbone time n2n_s %.6g rom_s %.6g speedup %.4g\n", (double)tn, (double)tr, (double)(tn / PetscMax(tr, 1e-9))));
  if (!base[0]) PetscFunctionReturn(0);
  PetscCall(JRFileCommit(comm, &fp, tmp, csv));
  PetscCall(JRNLModesGetOutputBase(n, &bn));
  PetscCall(JRNLModesGetOutputBase(r, &br));
  if (post->plot && bn[0] && br[0]) {
    char      png[PETSC_MAX_PATH_LEN + 32], vars[3 * PETSC_MAX_PATH_LEN + 64];
    PetscBool made;
    PetscCall(PetscSNPrintf(png, sizeof(png), "%s_nlmodes_compare.png", base));
    PetscCall(PetscSNPrintf(vars, sizeof(vars), "n2n='%s.csv'; rom='%s.csv'; ttl='node-to-node (solid) vs reduced (dashed): worst difference frequency %.2e, damping ratio %.2e'", bn, br, (double)worstf, (double)worstd));
    PetscCall(JRPlot(comm, "plot_backbone_compare.gp", png, vars, &made));
    PetscCall(PetscPrintf(comm, "compare: wrote %s%s%s\n", csv, made ? ", " : "", made ? png : ""));
  } else PetscCall(PetscPrintf(comm, "compare: wrote %s\n", csv));
  PetscFunctionReturn(0);
}
