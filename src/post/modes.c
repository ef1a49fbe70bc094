/*
   JRPost for -task modes: the table of the modes ('mode <index> <Hz>' lines and the share of each direction),
   BASE.h5 (the mesh and every mode as a field, omega), BASE.xdmf (ParaView) and BASE.png (side view of the first
   elastic mode shapes, BASE_shapes.csv).
*/
#include <jointrom/private/feimpl.h>
#include <jointrom/private/postimpl.h>
#include <petscviewerhdf5.h>

/* the vertices on the front face y = ymin: coordinates and first global DOF, on every rank */
static PetscErrorCode FrontFace(DM dm, PetscInt *n, PetscReal **x, PetscInt **dof)
{
  MPI_Comm      comm;
  PetscSection  ls, gs, cs;
  Vec           coords;
  PetscInt      vs, ve, cnt = 0, *ld;
  PetscReal     ymin = PETSC_MAX_REAL, *lx;
  const PetscScalar *ca;
  PetscMPIInt   size, *rc, *rd;
  PetscInt      tot = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vs, &ve));
  PetscCall(VecGetArrayRead(coords, &ca));
  for (PetscInt v = vs; v < ve; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    ymin = PetscMin(ymin, PetscRealPart(ca[off + 1]));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ymin, 1, MPIU_REAL, MPIU_MIN, comm));
  PetscCall(PetscMalloc2(3 * (ve - vs + 1), &lx, ve - vs + 1, &ld));
  for (PetscInt v = vs; v < ve; v++) {
    PetscInt off, goff, d, cd;
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    if (PetscAbsReal(PetscRealPart(ca[off + 1]) - ymin) > 1e-9) continue;
    PetscCall(PetscSectionGetDof(ls, v, &d));
    PetscCall(PetscSectionGetConstraintDof(ls, v, &cd));
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (d != 3 || cd || goff < 0) continue; /* owned, unconstrained vertices */
    for (int k = 0; k < 3; k++) lx[3 * cnt + k] = PetscRealPart(ca[off + k]);
    ld[cnt++] = goff;
  }
  PetscCall(VecRestoreArrayRead(coords, &ca));
  PetscCall(PetscMalloc2(size, &rc, size, &rd));
  {
    PetscMPIInt c = (PetscMPIInt)cnt;
    PetscCallMPI(MPI_Allgather(&c, 1, MPI_INT, rc, 1, MPI_INT, comm));
  }
  for (PetscMPIInt r = 0; r < size; r++) {
    rd[r] = (PetscMPIInt)tot;
    tot += rc[r];
  }
  PetscCall(PetscMalloc2(3 * PetscMax(tot, 1), x, PetscMax(tot, 1), dof));
  PetscCallMPI(MPI_Allgatherv(ld, (PetscMPIInt)cnt, MPIU_INT, *dof, rc, rd, MPIU_INT, comm));
  for (PetscMPIInt r = 0; r < size; r++) {
    rc[r] *= 3;
    rd[r] *= 3;
  }
  PetscCallMPI(MPI_Allgatherv(lx, (PetscMPIInt)(3 * cnt), MPIU_REAL, *x, rc, rd, MPIU_REAL, comm));
  *n = tot;
  PetscCall(PetscFree2(rc, rd));
  PetscCall(PetscFree2(lx, ld));
  PetscFunctionReturn(0);
}

/* One line per mode for scripts, 'mode <index> <frequency in Hz>' (rigid-body modes included), and the table */
PetscErrorCode JRPostModesTable(JRPost post, JRModes modes)
{
  MPI_Comm         comm = post->comm;
  PetscInt         nm, nrb;
  const PetscReal *lam;
  Vec             *phi;

  PetscFunctionBeginUser;
  PetscCall(JRModesGetNumber(modes, &nm));
  PetscCall(JRModesGetEigenvalues(modes, &lam));
  PetscCall(JRModesGetVecs(modes, &phi));
  PetscCall(JRModesGetNumRigid(modes, &nrb));
  for (PetscInt i = 0; i < nm; i++) PetscCall(PetscPrintf(comm, "mode %" PetscInt_FMT " %.10g\n", i + 1, (double)(PetscSqrtReal(PetscMax(lam[i], 0.0)) / (2.0 * PETSC_PI))));
  /* the table: which direction each mode moves in (share of sum phi_d^2 over the nodes) */
  PetscCall(PetscPrintf(comm, "modes table (share: the part of the mode shape's squared displacements along x, y, z)\n  mode      f [Hz]   omega [rad/s]  share x     y     z\n"));
  for (PetscInt i = 0; i < nm; i++) {
    const PetscScalar *a;
    PetscInt           n;
    PetscReal          sh[3] = {0, 0, 0}, tot;
    PetscCall(VecGetLocalSize(phi[i], &n));
    PetscCall(VecGetArrayRead(phi[i], &a));
    for (PetscInt k = 0; k < n; k++) sh[k % 3] += PetscSqr(PetscRealPart(a[k]));
    PetscCall(VecRestoreArrayRead(phi[i], &a));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sh, 3, MPIU_REAL, MPIU_SUM, comm));
    tot = sh[0] + sh[1] + sh[2];
    PetscCall(PetscPrintf(comm, "  %4" PetscInt_FMT " %11.4f %15.4f  %5.2f %5.2f %5.2f%s\n", i + 1, (double)(PetscSqrtReal(PetscMax(lam[i], 0.0)) / (2.0 * PETSC_PI)), (double)PetscSqrtReal(PetscMax(lam[i], 0.0)), (double)(sh[0] / tot), (double)(sh[1] / tot), (double)(sh[2] / tot), i < nrb ? "  rigid" : ""));
  }

  PetscFunctionReturn(0);
}

/* BASE.h5: the mesh and the modes in PETSc's visualisation layout, the frequencies */
static PetscErrorCode WriteModesH5(JRPost post, DM dm, JRModes modes, const char h5[])
{
  MPI_Comm         comm = post->comm;
  PetscInt         nm;
  const PetscReal *lam;
  Vec             *phi;
  PetscMPIInt      rank;
  char             tmp[PETSC_MAX_PATH_LEN + 32];
  PetscViewer      v;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(JRModesGetNumber(modes, &nm));
  PetscCall(JRModesGetEigenvalues(modes, &lam));
  PetscCall(JRModesGetVecs(modes, &phi));
  PetscCall(JRFileTempName(comm, h5, tmp, sizeof(tmp)));
  PetscCall(PetscViewerHDF5Open(comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(PetscViewerPushFormat(v, PETSC_VIEWER_HDF5_VIZ));
  PetscCall(DMView(dm, v));
  for (PetscInt i = 0; i < nm; i++) { /* a vector of the DM, so that the mesh viewer writes vertex fields */
    char name[32];
    Vec  g;
    PetscCall(DMGetGlobalVector(dm, &g));
    PetscCall(VecCopy(phi[i], g));
    PetscCall(PetscSNPrintf(name, sizeof(name), "mode_%" PetscInt_FMT, i + 1));
    PetscCall(PetscObjectSetName((PetscObject)g, name));
    PetscCall(VecView(g, v));
    PetscCall(DMRestoreGlobalVector(dm, &g));
  }
  PetscCall(PetscViewerPopFormat(v));
  for (int k = 0; k < 2; k++) { /* /modes/omega_rad_s and /modes/frequency_hz */
    Vec          f;
    PetscScalar *fa;
    PetscCall(VecCreateMPI(comm, rank ? 0 : nm, PETSC_DETERMINE, &f));
    PetscCall(PetscObjectSetName((PetscObject)f, k ? "frequency_hz" : "omega_rad_s"));
    PetscCall(VecGetArray(f, &fa));
    for (PetscInt i = 0; i < (rank ? 0 : nm); i++) fa[i] = PetscSqrtReal(PetscMax(lam[i], 0.0)) / (k ? 2.0 * PETSC_PI : 1.0);
    PetscCall(VecRestoreArray(f, &fa));
    PetscCall(PetscViewerHDF5PushGroup(v, "/modes"));
    PetscCall(VecView(f, v));
    PetscCall(PetscViewerHDF5PopGroup(v));
    PetscCall(VecDestroy(&f));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "units", PETSC_STRING, "SI: coordinates m; /fields/mode_i: every DOF of mode i (x, y, z per node), /vertex_fields: at the vertices, mass-normalised (kg^-1/2); omega_rad_s rad/s; frequency_hz Hz"));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(JRFileRename(comm, tmp, h5));
  PetscFunctionReturn(0);
}

/* BASE.xdmf for ParaView: the hexahedra and every mode as a nodal vector, from BASE.h5 */
static PetscErrorCode WriteModesXdmf(JRPost post, DM dm, JRModes modes, const char h5[], const char xdmf[])
{
  PetscInt         nm;
  const PetscReal *lam;
  JRXdmfField     *f;
  char           (*names)[64], (*sets)[64];
  JRXdmfGrid       g;

  PetscFunctionBeginUser;
  PetscCall(JRModesGetNumber(modes, &nm));
  PetscCall(JRModesGetEigenvalues(modes, &lam));
  PetscCall(PetscMalloc3(nm, &f, nm, &names, nm, &sets));
  for (PetscInt i = 0; i < nm; i++) {
    PetscCall(PetscSNPrintf(names[i], sizeof(names[i]), "mode %" PetscInt_FMT " (%.6g Hz)", i + 1, (double)(PetscSqrtReal(PetscMax(lam[i], 0.0)) / (2 * PETSC_PI))));
    PetscCall(PetscSNPrintf(sets[i], sizeof(sets[i]), "/vertex_fields/mode_%" PetscInt_FMT "_displacement", i + 1));
    f[i].name    = names[i];
    f[i].dataset = sets[i];
    f[i].ncomp   = 3;
  }
  g.name     = "modes";
  g.dm       = dm;
  g.npoints  = 0;
  g.geometry = NULL;
  g.nfields  = nm;
  g.fields   = f;
  PetscCall(JRXdmfWrite(post->comm, xdmf, h5, 1, &g));
  PetscCall(PetscFree3(f, names, sets));
  PetscFunctionReturn(0);
}

/* BASE.png (and BASE_shapes.csv): side view of the first nplot elastic modes, the front face deformed */
static PetscErrorCode PlotModes(JRPost post, DM dm, JRModes modes, PetscInt nplot)
{
  MPI_Comm         comm = post->comm;
  const char      *base = post->base;
  PetscInt         nm;
  const PetscReal *lam;

  PetscFunctionBeginUser;
  PetscCall(JRModesGetNumber(modes, &nm));
  PetscCall(JRModesGetEigenvalues(modes, &lam));
  {
    PetscInt   nf, *fd, first = 0, np;
    PetscReal *fx, *rows, L = 0.0;
    char       csv[PETSC_MAX_PATH_LEN + 8], png[PETSC_MAX_PATH_LEN + 8], tc[PETSC_MAX_PATH_LEN + 32];
    FILE      *fp;
    while (first < nm && lam[first] < 1e-8 * lam[nm - 1]) first++; /* skip the rigid-body modes (supplied or computed) */
    np = PetscMin(nplot, nm - first);
    PetscCall(FrontFace(dm, &nf, &fx, &fd));
    PetscCall(PetscMalloc1(PetscMax(nf, 1) * 3 * nm, &rows));
    {
      PetscInt *d3;
      PetscCall(PetscMalloc1(3 * PetscMax(nf, 1), &d3));
      for (PetscInt i = 0; i < nf; i++)
        for (int k = 0; k < 3; k++) d3[3 * i + k] = fd[i] + k;
      PetscCall(JRModesGetRows(modes, 3 * nf, d3, rows));
      PetscCall(PetscFree(d3));
    }
    for (PetscInt i = 0; i < nf; i++) L = PetscMax(L, fx[3 * i]);
    PetscCall(PetscSNPrintf(csv, sizeof(csv), "%s_shapes.csv", base));
    PetscCall(PetscSNPrintf(png, sizeof(png), "%s.png", base));
    PetscCall(JRFileOpenTemp(comm, csv, &fp, tc, sizeof(tc)));
    if (fp) fprintf(fp, "mode,freq_hz,x_m,z_m,xdef_m,zdef_m\n");
    for (PetscInt q = 0; q < np; q++) {
      const PetscInt r = first + q;
      PetscReal      umax = 0.0, s;
      for (PetscInt i = 0; i < nf; i++) umax = PetscMax(umax, PetscSqrtReal(PetscSqr(rows[(3 * i) * nm + r]) + PetscSqr(rows[(3 * i + 2) * nm + r])));
      s = umax > 0 ? 0.08 * L / umax : 0.0; /* the largest displacement drawn as 8% of the length */
      for (PetscInt i = 0; fp && i < nf; i++) fprintf(fp, "%" PetscInt_FMT ",%.6g,%.6g,%.6g,%.6g,%.6g\n", r + 1, (double)(PetscSqrtReal(PetscMax(lam[r], 0.0)) / (2 * PETSC_PI)), (double)fx[3 * i], (double)fx[3 * i + 2], (double)(fx[3 * i] + s * rows[(3 * i) * nm + r]), (double)(fx[3 * i + 2] + s * rows[(3 * i + 2) * nm + r]));
    }
    PetscCall(JRFileCommit(comm, &fp, tc, csv));
    if (np > 0) {
      char vars[3 * PETSC_MAX_PATH_LEN];
      PetscCall(PetscSNPrintf(vars, sizeof(vars), "data='%s'; first=%" PetscInt_FMT "; nplot=%" PetscInt_FMT, csv, first + 1, np));
      PetscCall(JRPlot(comm, "plot_modes.gp", png, vars, NULL));
    }
    PetscCall(PetscFree(rows));
    PetscCall(PetscFree2(fx, fd));
  }
  PetscFunctionReturn(0);
}

/* BASE.h5, BASE.xdmf and (with plot) BASE.png of the modes of an FE model; nplot elastic modes drawn */
PetscErrorCode JRPostWriteModes(JRPost post, JRModel model, JRModes modes, PetscInt nplot)
{
  const char *base = post->base;
  DM          dm;
  char        h5[PETSC_MAX_PATH_LEN + 8], xdmf[PETSC_MAX_PATH_LEN + 8];

  PetscFunctionBeginUser;
  PetscCall(JRModelGetDM(model, &dm));
  if (!base[0] || !dm) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(h5, sizeof(h5), "%s.h5", base));
  PetscCall(PetscSNPrintf(xdmf, sizeof(xdmf), "%s.xdmf", base));
  PetscCall(WriteModesH5(post, dm, modes, h5));
  PetscCall(WriteModesXdmf(post, dm, modes, h5, xdmf));
  if (post->plot) PetscCall(PlotModes(post, dm, modes, nplot));
  PetscCall(PetscPrintf(post->comm, "modes: wrote %s, %s%s%s.png\n", h5, xdmf, post->plot ? ", " : "", post->plot ? base : ""));
  PetscFunctionReturn(0);
}
