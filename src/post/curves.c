/*
   JRPost's writer of the frequency-response curves of a JRCont (JRPostWriteCurves): BASE.csv, BASE.h5, BASE.png.
*/
#include <jointrom/private/contimpl.h>
#include <jointrom/private/postimpl.h>
#include <petscviewerhdf5.h>

/* The responses' description, from the JRHBM: their DOFs or points and direction, H and the modes */
typedef struct {
  PetscInt         nout, nm, H, dir;
  const PetscInt  *dofs;
  const PetscReal *xyz; /* NULL on a matrices model */
  const char      *damping;
} Outputs;

/* Response o (0-based) in words: "response 1 along z at (x, y, z) m" at a point (JRHBMSetOutputPoints), else "response 1 at DOF d" */
static PetscErrorCode ResponseName(PetscInt o, const PetscReal xyz[], PetscInt dir, const PetscInt dofs[], char s[], size_t len)
{
  PetscFunctionBeginUser;
  if (xyz) PetscCall(PetscSNPrintf(s, len, "response %" PetscInt_FMT " along %c at (%g, %g, %g) m", o + 1, "xyz"[dir], (double)xyz[3 * o], (double)xyz[3 * o + 1], (double)xyz[3 * o + 2]));
  else PetscCall(PetscSNPrintf(s, len, "response %" PetscInt_FMT " at DOF %" PetscInt_FMT, o + 1, dofs[o]));
  PetscFunctionReturn(0);
}

/* BASE.csv: level,F_N,omega_rad_s,freq_hz,amp_1..amp_n[,pp_1..pp_n],stable (pp with H > 1; stable 1/0 by Hill's
   method, -1 not computed), one row per point */
static PetscErrorCode WriteCSV(JRCont c, const Outputs *o, const char csv[])
{
  char  tmp[PETSC_MAX_PATH_LEN + 32];
  FILE *fp;

  PetscFunctionBeginUser;
  PetscCall(JRFileOpenTemp(c->comm, csv, &fp, tmp, sizeof(tmp)));
  if (fp) {
    fprintf(fp, "level,F_N,omega_rad_s,freq_hz");
    for (PetscInt i = 0; i < o->nout; i++) fprintf(fp, ",amp_%" PetscInt_FMT, i + 1);
    if (o->H > 1)
      for (PetscInt i = 0; i < o->nout; i++) fprintf(fp, ",pp_%" PetscInt_FMT, i + 1);
    fprintf(fp, ",stable\n");
    for (PetscInt l = 0; l < c->nlev; l++) {
      JRContBranch *b = &c->br[l];
      for (PetscInt k = 0; k < b->np; k++) {
        fprintf(fp, "%" PetscInt_FMT ",%.10g,%.12g,%.12g", l, (double)b->F, (double)b->omega[k], (double)(b->omega[k] / (2 * PETSC_PI)));
        for (PetscInt i = 0; i < o->nout; i++) fprintf(fp, ",%.10e", (double)b->amp[k * o->nout + i]);
        if (o->H > 1)
          for (PetscInt i = 0; i < o->nout; i++) fprintf(fp, ",%.10e", (double)b->pp[k * o->nout + i]);
        fprintf(fp, ",%d\n", b->stable ? (int)b->stable[k] : -1);
      }
    }
  }
  PetscCall(JRFileCommit(c->comm, &fp, tmp, csv));
  PetscFunctionReturn(0);
}

/* The HDF5 root's attributes: the run's options, units, damping, sizes, the continuation and each response's group */
static PetscErrorCode WriteHDF5Header(JRCont c, const Outputs *o, PetscViewer v)
{
  char *opts;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(NULL, &opts));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "options", PETSC_STRING, opts));
  PetscCall(PetscFree(opts));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "units", PETSC_STRING, "SI: omega rad/s, freq_hz Hz, amp m, force N; a: modal coordinates of mass-normalised modes (physical DOFs with -hbm_physical)"));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "damping", PETSC_STRING, o->damping));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "harmonics", PETSC_INT, &o->H));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "modes", PETSC_INT, &o->nm));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "layout_a", PETSC_STRING, "per point: [a0 | as_1 ac_1 | ... | as_H ac_H], each block over the modes"));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "continuation", PETSC_STRING, c->type_name));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "responses", PETSC_STRING, "amp and pp: one column per response, in order; /response_i: response i's point (x_m, y_m, z_m, direction) or, on a matrices model, its dof (0-based)"));
  for (PetscInt i = 0; i < o->nout; i++) {
    char grp[64], name[192];
    PetscCall(PetscSNPrintf(grp, sizeof(grp), "/response_%" PetscInt_FMT, i + 1));
    PetscCall(ResponseName(i, o->xyz, o->dir, o->dofs, name, sizeof(name)));
    PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "name", PETSC_STRING, name));
    if (o->xyz) {
      const char *xn[] = {"x_m", "y_m", "z_m"}, *dn[] = {"x", "y", "z"};
      for (PetscInt k = 0; k < 3; k++) PetscCall(PetscViewerHDF5WriteAttribute(v, grp, xn[k], PETSC_REAL, &o->xyz[3 * i + k]));
      PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "direction", PETSC_STRING, dn[o->dir]));
    } else PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "dof", PETSC_INT, &o->dofs[i]));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "residual", PETSC_STRING, "per point: ||R|| / ||F f||, the harmonic-balance residual against the excitation in the solve space (-hbm_residual_tol bounds it)"));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "peaks", PETSC_STRING, "per level: peak_freq_hz, peak_amp_m of response 1 (attributes) and peaks_freq_hz, peaks_amp_m of every response (datasets): the maxima of the solution curve, each also a point of the curve"));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "stability", PETSC_STRING, "per level (with -frf_stability): stable (1/0 per point, Hill's method), floquet_max_re (the largest real part of the kept Floquet exponents, 1/s), folds_freq_hz and branch_points_freq_hz (when there are any)"));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "peak_states", PETSC_STRING, "per level: every element's contact state at the peak, 0 full stick, 1 stick-slip without separation, 2 separation with stick-slip, 3 full separation"));
  PetscFunctionReturn(0);
}

/* The group /level_<l>'s attributes: force, points, time, the peak, damping, Newton total and the contact states */
static PetscErrorCode WriteHDF5LevelAttributes(PetscViewer v, const char grp[], JRContBranch *b)
{
  PetscReal fhz = b->wpeak / (2 * PETSC_PI), aof = b->apeak / b->F;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "force_N", PETSC_REAL, &b->F));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "points", PETSC_INT, &b->np));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "seconds", PETSC_REAL, &b->seconds));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "complete", PETSC_BOOL, &b->complete));
  if (!b->complete) PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "incomplete", PETSC_STRING, b->why[0] ? b->why : "stopped before the end of the range"));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "residual_max", PETSC_REAL, &b->resmax));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "peak_refine_solves", PETSC_INT, &b->refine_its));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "peak_freq_hz", PETSC_REAL, &fhz));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "peak_amp_m", PETSC_REAL, &b->apeak));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "peak_amp_over_force_m_per_N", PETSC_REAL, &aof));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "zeta_eq", PETSC_REAL, &b->zeta));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "energy_balance", PETSC_REAL, &b->ebal));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "newton_total", PETSC_INT, &b->newton));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "elements_full_stick", PETSC_INT, &b->states[0]));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "elements_stick_slip", PETSC_INT, &b->states[1]));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "elements_separation_stick_slip", PETSC_INT, &b->states[2]));
  PetscCall(PetscViewerHDF5WriteAttribute(v, grp, "elements_full_separation", PETSC_INT, &b->states[3]));
  PetscFunctionReturn(0);
}

/* The group /level_<l>: every point's omega, amp, pp, a, step, Newton iterations, and the elements' states at the peak */
static PetscErrorCode WriteHDF5Level(JRCont c, PetscViewer v, PetscInt l)
{
  JRContBranch  *b = &c->br[l];
  char           grp[64];
  const PetscInt np = b->np, nel = b->states[0] + b->states[1] + b->states[2] + b->states[3];
  PetscInt      *st;
  PetscMPIInt    rank;
  const struct {
    const char *name;
    PetscInt    bs;
    PetscReal  *data;
  } sets[] = {
    {"omega", 1,       b->omega},
    {"amp",   c->nout, b->amp  },
    {"pp",    c->nout, b->pp   },
    {"a",     c->nmod, b->a    },
    {"step",  1,       b->step },
    {"residual", 1,    b->res  }
  };

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(c->comm, &rank));
  PetscCall(PetscSNPrintf(grp, sizeof(grp), "/level_%" PetscInt_FMT, l));
  PetscCall(PetscViewerHDF5PushGroup(v, grp));
  for (size_t s = 0; s < sizeof(sets) / sizeof(sets[0]); s++) PetscCall(JRViewerHDF5WriteRank0(c->comm, v, sets[s].name, np * sets[s].bs, sets[s].bs, sets[s].data, NULL));
  PetscCall(JRViewerHDF5WriteRank0(c->comm, v, "newton_its", np, 1, NULL, b->its));
  {
    PetscReal *f;
    PetscCall(PetscMalloc1(c->nout, &f));
    for (PetscInt o = 0; o < c->nout; o++) f[o] = b->wpk[o] / (2 * PETSC_PI);
    PetscCall(JRViewerHDF5WriteRank0(c->comm, v, "peaks_freq_hz", c->nout, 1, f, NULL));
    PetscCall(JRViewerHDF5WriteRank0(c->comm, v, "peaks_amp_m", c->nout, 1, b->apk, NULL));
    PetscCall(PetscFree(f));
  }
  if (b->stable) {
    PetscReal *f;
    PetscCall(JRViewerHDF5WriteRank0(c->comm, v, "stable", np, 1, NULL, b->stable));
    PetscCall(JRViewerHDF5WriteRank0(c->comm, v, "floquet_max_re", np, 1, b->maxre, NULL));
    PetscCall(PetscMalloc1(b->nfold + b->nbranch, &f));
    for (PetscInt i = 0; i < b->nfold; i++) f[i] = b->wfold[i] / (2 * PETSC_PI);
    for (PetscInt i = 0; i < b->nbranch; i++) f[b->nfold + i] = b->wbranch[i] / (2 * PETSC_PI);
    if (b->nfold) PetscCall(JRViewerHDF5WriteRank0(c->comm, v, "folds_freq_hz", b->nfold, 1, f, NULL));
    if (b->nbranch) PetscCall(JRViewerHDF5WriteRank0(c->comm, v, "branch_points_freq_hz", b->nbranch, 1, f + b->nfold, NULL));
    PetscCall(PetscFree(f));
  }
  PetscCall(WriteHDF5LevelAttributes(v, grp, b));
  PetscCall(PetscMalloc1(rank ? 0 : nel, &st));
  for (PetscInt i = 0; !rank && i < nel; i++) st[i] = (PetscInt)b->estate[i];
  PetscCall(JRViewerHDF5WriteRank0(c->comm, v, "peak_states", nel, 1, NULL, st));
  PetscCall(PetscFree(st));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscFunctionReturn(0);
}

/* BASE.h5: the root's attributes and one group per level, written to a temporary file and renamed */
static PetscErrorCode WriteHDF5(JRCont c, const Outputs *o, const char h5[])
{
  char        tmp[PETSC_MAX_PATH_LEN + 32];
  PetscViewer v;

  PetscFunctionBeginUser;
  PetscCall(JRFileTempName(c->comm, h5, tmp, sizeof(tmp)));
  PetscCall(PetscViewerHDF5Open(c->comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(WriteHDF5Header(c, o, v));
  for (PetscInt l = 0; l < c->nlev; l++) PetscCall(WriteHDF5Level(c, v, l));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(JRFileRename(c->comm, tmp, h5));
  PetscFunctionReturn(0);
}

/* BASE.png from BASE.csv (share/plot_frf.gp: response 1, every level; -frf_normalize divides by the force) */
static PetscErrorCode Plot(JRCont c, const Outputs *o, const char csv[], const char png[], PetscBool *made)
{
  char vars[3 * PETSC_MAX_PATH_LEN], name[192];

  PetscFunctionBeginUser;
  PetscCall(ResponseName(0, o->xyz, o->dir, o->dofs, name, sizeof(name)));
  PetscCall(PetscSNPrintf(vars, sizeof(vars), "data='%s'; nlev=%" PetscInt_FMT "; normalize=%d; scol=%" PetscInt_FMT "; ttl='%s (%s continuation, H = %" PetscInt_FMT ")'", csv, c->nlev, (int)c->normalize, 5 + c->nout * (o->H > 1 ? 2 : 1), name, c->type_name, o->H));
  PetscCall(JRPlot(c->comm, "plot_frf.gp", png, vars, made));
  PetscFunctionReturn(0);
}

/*
  JRPostWriteCurves - the curves of c: BASE.h5 (every point), BASE.csv (level,F_N,omega_rad_s,freq_hz,amp_1..amp_n[,pp_1..pp_n],stable: the
  responses by their index, 1-based) and BASE.png (response 1). The HDF5 group /response_<i> names response i:
  its point x_m, y_m, z_m and direction (JRHBMSetOutputPoints: an FE model) or its dof (a matrices model).
  BASE is the curves' own (-frf_output_file or JRContSetOutputBase, '' for none: in -task compare each model's), not
  post's; -frf_plot 0 leaves out the PNG.
*/
PetscErrorCode JRPostWriteCurves(JRPost post, JRCont c)
{
  char      h5[PETSC_MAX_PATH_LEN + 8], csv[PETSC_MAX_PATH_LEN + 8], png[PETSC_MAX_PATH_LEN + 8];
  Outputs   o;
  PetscBool made;

  PetscFunctionBeginUser;
  (void)post;
  if (!c->write) PetscFunctionReturn(0);
  PetscCall(JRHBMGetOutputs(c->hbm, &c->nout, &o.dofs));
  PetscCall(JRHBMGetOutputPoints(c->hbm, &o.xyz, &o.dir));
  PetscCall(JRHBMGetSizes(c->hbm, &o.nm, &o.H, NULL));
  PetscCall(JRHBMGetDampingDescription(c->hbm, &o.damping));
  o.nout = c->nout;
  PetscCall(PetscSNPrintf(h5, sizeof(h5), "%s.h5", c->out));
  PetscCall(PetscSNPrintf(csv, sizeof(csv), "%s.csv", c->out));
  PetscCall(PetscSNPrintf(png, sizeof(png), "%s.png", c->out));
  PetscCall(WriteCSV(c, &o, csv));
  PetscCall(WriteHDF5(c, &o, h5));
  if (c->plot) {
    PetscCall(Plot(c, &o, csv, png, &made));
    PetscCall(PetscPrintf(c->comm, "frf: wrote %s, %s%s%s\n", h5, csv, made ? ", " : "", made ? png : ""));
  } else PetscCall(PetscPrintf(c->comm, "frf: wrote %s, %s\n", h5, csv));
  PetscFunctionReturn(0);
}
