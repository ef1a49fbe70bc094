/*
   JRPreload's results in files: written (JRPreloadWrite: CSV, HDF5, XDMF, PNG) and read back instead of solving
   (-preload_load: this program's CSV or HDF5, matched to the model's pairs by position).
*/
#include <jointrom/private/preloadimpl.h>
#include <petscviewerhdf5.h>
#include <unistd.h>

/* a vector on rank 0 (the others hold none) with n values, block size bs, named name */
static PetscErrorCode RootVec(MPI_Comm comm, const char *name, PetscInt n, PetscInt bs, const PetscReal *a, Vec *v)
{
  PetscMPIInt  rank;
  PetscScalar *va;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecCreate(comm, v));
  PetscCall(VecSetSizes(*v, rank ? 0 : n * bs, PETSC_DETERMINE));
  PetscCall(VecSetBlockSize(*v, bs));
  PetscCall(VecSetType(*v, VECMPI));
  PetscCall(PetscObjectSetName((PetscObject)*v, name));
  PetscCall(VecGetArray(*v, &va));
  for (PetscInt i = 0; i < (rank ? 0 : n * bs); i++) va[i] = a[i];
  PetscCall(VecRestoreArray(*v, &va));
  PetscFunctionReturn(0);
}

/* The table written: per pair its position, area, N_static, pressure, gap, closed flag and, with -preload_kv, n0; and
   the mid-section, the row of pairs nearest the interface's centre line (y = ymid) */
typedef struct {
  PetscInt         n;
  const JRPairs   *P;
  const PetscReal *N, *g;
  PetscReal       *pr, *cl, *n0, ymid;
} PairTable;

static PetscErrorCode PairTableCreate(JRPreload p, PairTable *t)
{
  const JRPairs   *P;
  PetscInt         n;
  const PetscReal *N, *g;
  PetscReal       *pr, *cl, *n0 = NULL, ymin = PETSC_MAX_REAL, ymax = PETSC_MIN_REAL, ymid = 0.0, dbest = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  PetscCall(JRPreloadGetResults(p, &n, &N, &g));
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(PetscMalloc2(n, &pr, n, &cl));
  if (p->kv_set) {
    PetscCall(PetscMalloc1(n, &n0));
    PetscCall(JRPreloadGetN0(p, p->kv, n0));
  }
  for (PetscInt i = 0; i < n; i++) {
    pr[i] = N[i] / P->area[i];
    cl[i] = N[i] > 0 ? 1.0 : 0.0;
    ymin  = PetscMin(ymin, P->x[3 * i + 1]);
    ymax  = PetscMax(ymax, P->x[3 * i + 1]);
  }
  for (PetscInt i = 0; i < n; i++) /* the mid-section: the row of pairs nearest the interface's centre line */
    if (PetscAbsReal(P->x[3 * i + 1] - 0.5 * (ymin + ymax)) < dbest) {
      dbest = PetscAbsReal(P->x[3 * i + 1] - 0.5 * (ymin + ymax));
      ymid  = P->x[3 * i + 1];
    }
  t->n    = n;
  t->P    = P;
  t->N    = N;
  t->g    = g;
  t->pr   = pr;
  t->cl   = cl;
  t->n0   = n0;
  t->ymid = ymid;
  PetscFunctionReturn(0);
}

static PetscErrorCode PairTableDestroy(PairTable *t)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree2(t->pr, t->cl));
  PetscCall(PetscFree(t->n0));
  PetscFunctionReturn(0);
}

/* BASE.csv: one row per pair (pair,x_m,y_m,z_m,area_m2,N_static_N,pressure_Pa,v_gap_m,closed,mid[,n0_N]) */
static PetscErrorCode WriteCSV(JRPreload p, const PairTable *t, const char csv[])
{
  const PetscInt   n = t->n;
  const JRPairs   *P = t->P;
  const PetscReal *N = t->N, *g = t->g, *pr = t->pr, *cl = t->cl, *n0 = t->n0, ymid = t->ymid;
  char             tmp[PETSC_MAX_PATH_LEN + 32];
  FILE            *fp;

  PetscFunctionBeginUser;
  PetscCall(JRFileOpenTemp(p->comm, csv, &fp, tmp, sizeof(tmp)));
  if (fp) {
    fprintf(fp, "pair,x_m,y_m,z_m,area_m2,N_static_N,pressure_Pa,v_gap_m,closed,mid%s\n", n0 ? ",n0_N" : "");
    for (PetscInt i = 0; i < n; i++) {
      const int mid = PetscAbsReal(P->x[3 * i + 1] - ymid) < 1e-9;
      fprintf(fp, "%" PetscInt_FMT ",%.10g,%.10g,%.10g,%.8g,%.10g,%.10g,%.10g,%d,%d", i + 1, (double)P->x[3 * i], (double)P->x[3 * i + 1], (double)P->x[3 * i + 2], (double)P->area[i], (double)N[i], (double)pr[i], (double)g[i], (int)cl[i], mid);
      if (n0) fprintf(fp, ",%.10g", (double)n0[i]);
      fprintf(fp, "\n");
    }
  }
  PetscCall(JRFileCommit(p->comm, &fp, tmp, csv));
  PetscFunctionReturn(0);
}

/* BASE.h5: the mesh and the preload displacement when solved; /preload/: x_m, area_m2, N_static_N, pressure_Pa,
   v_gap_m, closed, and n0_N with -preload_kv; the method and the units as attributes */
static PetscErrorCode WriteHDF5(JRPreload p, const PairTable *t, const char h5[])
{
  const PetscInt   n = t->n;
  const JRPairs   *P = t->P;
  const PetscReal *N = t->N, *g = t->g, *pr = t->pr, *cl = t->cl, *n0 = t->n0;
  char             tmp[PETSC_MAX_PATH_LEN + 32];
  PetscMPIInt      rank;
  DM               dm;
  PetscViewer      v;
  Vec              vv;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(p->comm, &rank));
  PetscCall(JRModelGetDM(p->model, &dm));
  PetscCall(JRFileTempName(p->comm, h5, tmp, sizeof(tmp)));
  PetscCall(PetscViewerHDF5Open(p->comm, tmp, FILE_MODE_WRITE, &v));
  if (p->solved) {
    Vec gv;
    PetscCall(PetscViewerPushFormat(v, PETSC_VIEWER_HDF5_VIZ));
    PetscCall(DMView(dm, v));
    PetscCall(DMGetGlobalVector(dm, &gv));
    PetscCall(VecCopy(p->u, gv));
    PetscCall(PetscObjectSetName((PetscObject)gv, "preload"));
    PetscCall(VecView(gv, v));
    PetscCall(DMRestoreGlobalVector(dm, &gv));
    PetscCall(PetscViewerPopFormat(v));
  }
  PetscCall(PetscViewerHDF5PushGroup(v, "/preload"));
  PetscCall(RootVec(p->comm, "x_m", n, 3, P->x, &vv));
  PetscCall(VecView(vv, v));
  PetscCall(VecDestroy(&vv));
  {
    const char      *names[6] = {"area_m2", "N_static_N", "pressure_Pa", "v_gap_m", "closed", "n0_N"};
    const PetscReal *data[6]  = {P->area, N, pr, g, cl, n0};
    for (int k = 0; k < (n0 ? 6 : 5); k++) {
      PetscCall(RootVec(p->comm, names[k], n, 1, data[k], &vv));
      PetscCall(VecView(vv, v));
      PetscCall(VecDestroy(&vv));
    }
  }
  PetscCall(PetscViewerHDF5PopGroup(v));
  {
    char info[512];
    PetscCall(PetscSNPrintf(info, sizeof(info), "%s; pretension %g N%s; kp %g N/m^3; kv %g N/m", p->loaded ? "read from a file" : p->method == JR_PRELOAD_PENALTY ? "penalty contact" : "augmented-Lagrangian contact", (double)p->force[0], p->nforce > 1 ? " (first bolt)" : " per bolt", (double)p->kp, (double)p->kv));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/preload", "method", PETSC_STRING, info));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "units", PETSC_STRING, "SI: /preload/x_m pair positions m, area_m2 m^2 (the node's share of surface A), N_static_N N (normal load pressing the pair together), pressure_Pa Pa (N / area), v_gap_m m, closed 1/0, n0_N N (N_static - kv v_gap); /fields/preload: the preload displacement m"));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(JRFileRename(p->comm, tmp, h5));
  PetscFunctionReturn(0);
}

/* BASE.xdmf (ParaView): the deformed mesh (when solved) and the interface pairs as points carrying N, pressure, gap */
static PetscErrorCode WriteXDMF(JRPreload p, const PairTable *t, const char h5[], const char xdmf[])
{
  const JRXdmfField mesh[1]  = {{"preload displacement", "/vertex_fields/preload_displacement", 3}};
  const JRXdmfField pairs[6] = {{"N_static_N", "/preload/N_static_N", 1}, {"pressure_Pa", "/preload/pressure_Pa", 1}, {"v_gap_m", "/preload/v_gap_m", 1}, {"closed", "/preload/closed", 1}, {"area_m2", "/preload/area_m2", 1}, {"n0_N", "/preload/n0_N", 1}};
  JRXdmfGrid        g[2];
  PetscInt          ng = 0;
  DM                dm;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetDM(p->model, &dm));
  if (p->solved) g[ng++] = (JRXdmfGrid){"assembly", dm, 0, NULL, 1, mesh};
  g[ng++] = (JRXdmfGrid){"interface pairs", NULL, t->n, "/preload/x_m", t->n0 ? 6 : 5, pairs};
  PetscCall(JRXdmfWrite(p->comm, xdmf, h5, ng, g));
  PetscFunctionReturn(0);
}

/*
  Write BASE.csv (one row per pair), BASE.h5 (the mesh and the preload displacement when solved; /preload/: x_m,
  area_m2, N_static_N, pressure_Pa, v_gap_m, closed, and n0_N with -preload_kv), BASE.xdmf (ParaView: the
  deformed mesh and the interface pairs as points carrying N, pressure and gap) and, with plot, BASE.png
  (maps of the pressure and the gap over the interface and their mid-section profile, share/plot_preload.gp).
  Every file through a temporary name.
*/
PetscErrorCode JRPreloadWrite(JRPreload p, const char base[], PetscBool plot)
{
  PairTable t;
  char      csv[PETSC_MAX_PATH_LEN + 8], h5[PETSC_MAX_PATH_LEN + 8], xdmf[PETSC_MAX_PATH_LEN + 8], png[PETSC_MAX_PATH_LEN + 8];

  PetscFunctionBeginUser;
  if (!base || !base[0]) PetscFunctionReturn(0);
  PetscCall(PairTableCreate(p, &t));
  PetscCall(PetscSNPrintf(csv, sizeof(csv), "%s.csv", base));
  PetscCall(PetscSNPrintf(h5, sizeof(h5), "%s.h5", base));
  PetscCall(PetscSNPrintf(xdmf, sizeof(xdmf), "%s.xdmf", base));
  PetscCall(PetscSNPrintf(png, sizeof(png), "%s.png", base));
  PetscCall(WriteCSV(p, &t, csv));
  PetscCall(WriteHDF5(p, &t, h5));
  PetscCall(WriteXDMF(p, &t, h5, xdmf));
  if (plot) {
    char vars[3 * PETSC_MAX_PATH_LEN];
    PetscCall(PetscSNPrintf(vars, sizeof(vars), "data='%s'; ymid=%.6g", csv, (double)(t.ymid * 1e3)));
    PetscCall(JRPlot(p->comm, "plot_preload.gp", png, vars, NULL));
  }
  PetscCall(PairTableDestroy(&t));
  PetscFunctionReturn(0);
}

/* The rows of this program's HDF5 (/preload/x_m, N_static_N, v_gap_m), on every rank: n rows, x (3 n), N, g */
static PetscErrorCode ReadHDF5(JRPreload p, PetscInt *nrows, PetscReal **xo, PetscReal **No, PetscReal **go)
{
  PetscInt    n = 0;
  PetscReal  *x, *N, *g;
  PetscViewer v;
  Vec         vx, vN, vg, s;
  VecScatter  sc;
  const char *names[3] = {"x_m", "N_static_N", "v_gap_m"};
  Vec        *vv[3]    = {&vx, &vN, &vg};
  PetscBool   has;

  PetscFunctionBeginUser;
  PetscCall(PetscTestFile(p->load, 'r', &has));
  PetscCheck(has, p->comm, PETSC_ERR_FILE_OPEN, "-preload_load %s: cannot read the file", p->load);
  {
    char what[PETSC_MAX_PATH_LEN + 32];
    PetscCall(PetscSNPrintf(what, sizeof(what), "-preload_load %s", p->load));
    PetscCall(JRErrorContextPush(what));
  }
  PetscCall(PetscViewerHDF5Open(p->comm, p->load, FILE_MODE_READ, &v));
  PetscCall(PetscViewerHDF5PushGroup(v, "/preload"));
  for (int k = 0; k < 3; k++) {
    char path[64];
    PetscCall(PetscSNPrintf(path, sizeof(path), "/preload/%s", names[k]));
    PetscCall(PetscViewerHDF5HasDataset(v, path, &has));
    PetscCheck(has, p->comm, PETSC_ERR_FILE_UNEXPECTED, "-preload_load %s: no dataset %s (a preload HDF5 of this program has /preload/x_m, N_static_N, v_gap_m)", p->load, path);
    PetscCall(VecCreate(p->comm, vv[k]));
    PetscCall(PetscObjectSetName((PetscObject)*vv[k], names[k]));
    PetscCall(VecLoad(*vv[k], v));
  }
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(JRErrorContextPop());
  PetscCall(VecGetSize(vN, &n));
  PetscCall(PetscMalloc3(3 * PetscMax(n, 1), &x, PetscMax(n, 1), &N, PetscMax(n, 1), &g));
  for (int k = 0; k < 3; k++) {
    const PetscScalar *a;
    PetscInt           m;
    PetscCall(VecScatterCreateToAll(*vv[k], &sc, &s));
    PetscCall(VecScatterBegin(sc, *vv[k], s, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sc, *vv[k], s, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetSize(s, &m));
    PetscCheck(m == (k ? n : 3 * n), p->comm, PETSC_ERR_FILE_UNEXPECTED, "-preload_load %s: /preload/%s has %" PetscInt_FMT " values, expected %" PetscInt_FMT, p->load, names[k], m, k ? n : 3 * n);
    PetscCall(VecGetArrayRead(s, &a));
    for (PetscInt i = 0; i < m; i++) (k == 0 ? x : k == 1 ? N : g)[i] = PetscRealPart(a[i]);
    PetscCall(VecRestoreArrayRead(s, &a));
    PetscCall(VecScatterDestroy(&sc));
    PetscCall(VecDestroy(&s));
    PetscCall(VecDestroy(vv[k]));
  }
  *nrows = n;
  *xo    = x;
  *No    = N;
  *go    = g;
  PetscFunctionReturn(0);
}

/* The rows of a CSV table (columns x_m, y_m, z_m, N_static_N, v_gap_m), on every rank: n rows, x (3 n), N, g */
static PetscErrorCode ReadTable(JRPreload p, PetscInt *nrows, PetscReal **xo, PetscReal **No, PetscReal **go)
{
  PetscInt   n = 0;
  PetscReal *x, *N, *g;
  JRTable    t;

  PetscFunctionBeginUser;
  PetscCall(JRTableRead(p->comm, p->load, &t));
  PetscCall(JRTableGetSize(t, &n, NULL));
  PetscCall(PetscMalloc3(3 * PetscMax(n, 1), &x, PetscMax(n, 1), &N, PetscMax(n, 1), &g));
  {
    const char *cols[5] = {"x_m", "y_m", "z_m", "N_static_N", "v_gap_m"};
    PetscReal  *col;
    PetscCall(PetscMalloc1(PetscMax(n, 1), &col));
    for (int c = 0; c < 5; c++) {
      PetscCall(JRTableGetColumn(t, cols[c], PETSC_TRUE, 0.0, col));
      for (PetscInt i = 0; i < n; i++) {
        if (c < 3) x[3 * i + c] = col[i];
        else (c == 3 ? N : g)[i] = col[i];
      }
    }
    PetscCall(PetscFree(col));
  }
  PetscCall(JRTableDestroy(&t));
  *nrows = n;
  *xo    = x;
  *No    = N;
  *go    = g;
  PetscFunctionReturn(0);
}

/* Every pair's N_static and v_gap (p->N, p->gap) from the file row at its position, within load_tol, each row once */
static PetscErrorCode MatchPairs(JRPreload p, const JRPairs *P, PetscInt n, const PetscReal x[], const PetscReal N[], const PetscReal g[])
{
  PetscInt *used;
  JRNearest key;

  PetscFunctionBeginUser;
  PetscCall(JRNearestCreate(n, x, &key));
  PetscCall(PetscCalloc1(n, &used));
  for (PetscInt i = 0; i < P->n; i++) { /* for each pair, the file row at its position */
    PetscInt best;
    PetscCall(JRNearestFind(key, P->x + 3 * i, p->load_tol, &best, NULL));
    PetscCheck(best >= 0, p->comm, PETSC_ERR_ARG_WRONG, "-preload_load %s: no row within %g m (-preload_load_tol) of the pair at (%g, %g, %g) m; the file does not match the model's interface", p->load, (double)p->load_tol, (double)P->x[3 * i], (double)P->x[3 * i + 1], (double)P->x[3 * i + 2]);
    PetscCheck(!used[best], p->comm, PETSC_ERR_ARG_WRONG, "-preload_load %s: row %" PetscInt_FMT " matches two pairs (-preload_load_tol %g m is too large)", p->load, best + 1, (double)p->load_tol);
    used[best] = 1;
    p->N[i]    = N[best];
    p->gap[i]  = g[best];
  }
  PetscCall(JRNearestDestroy(&key));
  PetscCall(PetscFree(used));
  PetscFunctionReturn(0);
}

/* Before any work: the -preload_load file reads (HDF5: a file with the group /preload; CSV: every row's five numbers,
   N_static and v_gap not negative), each error naming the file and, in a CSV file, the line */
PetscErrorCode JRPreloadCheckLoadFile(JRPreload p)
{
  const char *ext = strrchr(p->load, '.');
  PetscInt    n;
  PetscReal  *x, *N, *g;
  JRTable     t;

  PetscFunctionBeginUser;
  if (ext && !strcmp(ext, ".h5")) {
    PetscCall(JRFileCheckHDF5(p->comm, "-preload_load", p->load, "/preload", "write one with -preload_output_file, or give a CSV file"));
    PetscFunctionReturn(0);
  }
  PetscCall(ReadTable(p, &n, &x, &N, &g));
  PetscCall(JRTableRead(p->comm, p->load, &t));
  for (PetscInt r = 0; r < n; r++) {
    PetscInt line;
    PetscCall(JRTableGetLine(t, r, &line));
    PetscCheck(N[r] >= 0, p->comm, PETSC_ERR_FILE_UNEXPECTED, "-preload_load %s line %" PetscInt_FMT ": N_static_N = %g; it must be >= 0", p->load, line, (double)N[r]);
    PetscCheck(g[r] >= 0, p->comm, PETSC_ERR_FILE_UNEXPECTED, "-preload_load %s line %" PetscInt_FMT ": v_gap_m = %g; it must be >= 0", p->load, line, (double)g[r]);
  }
  if (n == 0) {
    PetscInt line;
    PetscCall(JRTableGetLine(t, -1, &line));
    SETERRQ(p->comm, PETSC_ERR_FILE_UNEXPECTED, "-preload_load %s line %" PetscInt_FMT ": a header but no rows after it (one row per interface pair)", p->load, line);
  }
  PetscCall(JRTableDestroy(&t));
  PetscCall(PetscFree3(x, N, g));
  PetscFunctionReturn(0);
}

/* N_static and v_gap per pair from a file (-preload_load): every row matched to the pair within load_tol, each pair once */
PetscErrorCode JRPreloadLoadResults(JRPreload p)
{
  const JRPairs *P;
  PetscInt       n = 0;
  PetscReal     *x, *N, *g;
  const char    *ext = strrchr(p->load, '.');

  PetscFunctionBeginUser;
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCheck(P->n > 0, p->comm, PETSC_ERR_ARG_WRONG, "-preload_load %s: the model has no contact interface", p->load);
  if (ext && !strcmp(ext, ".h5")) PetscCall(ReadHDF5(p, &n, &x, &N, &g));
  else PetscCall(ReadTable(p, &n, &x, &N, &g));
  PetscCheck(n == P->n, p->comm, PETSC_ERR_ARG_SIZ, "-preload_load %s: %" PetscInt_FMT " rows, but the model's interface has %" PetscInt_FMT " pairs", p->load, n, P->n);
  for (PetscInt r = 0; r < n; r++) {
    PetscCheck(N[r] >= 0 && PetscIsNormalReal(N[r] + 1.0), p->comm, PETSC_ERR_FILE_UNEXPECTED, "-preload_load %s: row %" PetscInt_FMT " has N_static = %g N; it must be >= 0", p->load, r + 1, (double)N[r]);
    PetscCheck(g[r] >= 0 && PetscIsNormalReal(g[r] + 1.0), p->comm, PETSC_ERR_FILE_UNEXPECTED, "-preload_load %s: row %" PetscInt_FMT " has v_gap = %g m; it must be >= 0", p->load, r + 1, (double)g[r]);
  }
  PetscCall(JRPreloadClearResults(p));
  p->np = P->n;
  PetscCall(PetscMalloc2(P->n, &p->N, P->n, &p->gap));
  PetscCall(MatchPairs(p, P, n, x, N, g));
  PetscCall(PetscFree3(x, N, g));
  p->loaded = PETSC_TRUE;
  PetscFunctionReturn(0);
}
