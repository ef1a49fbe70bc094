/*
   Structured hexahedral meshes of a straight beam and of lap-joint assemblies, built on rank 0 as a cell
   list and distributed by DMPlex.

   Lap joint (Brake-Reuss beam and the single- and three-bolt specimens of thesis ch. 4-5): beam A on
   x in [0, L1], beam B on x in [L1 - Llap, L1 - Llap + L2]; width W along y, height H along z; over the
   lap x in [L1 - Llap, L1] A keeps the upper half z in [H/2, H] and B the lower half z in [0, H/2], so
   they meet on the plane z = H/2. The two beams are separate bodies: each has its own vertices, so the
   lap faces coincide without being joined, and every node of one contact surface faces a node of the
   other (one grid in x and y for both). Bolt holes are the cells whose centre lies inside the hole
   (a stair-step hole); the washer footprints are the outer faces (A's top, B's bottom) whose centre
   lies in the washer annulus. Grid: spacing h over the lap, h * grade outside it, hz (default h) through the
   height, at least two cells through each half height.
*/
#include <jointrom/private/feimpl.h>
#include <petscsf.h>
#include <unistd.h>

/* grid lines: n cells of equal size over each segment [b_i, b_{i+1}] of size at most hs[i] */
static PetscErrorCode GridLines(PetscInt nseg, const PetscReal b[], const PetscReal hs[], PetscInt minc, PetscInt *n, PetscReal **x)
{
  PetscInt tot = 0, k = 0;

  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < nseg; s++) tot += PetscMax(minc, (PetscInt)PetscCeilReal((b[s + 1] - b[s]) / hs[s] - 1e-9));
  PetscCall(PetscMalloc1(tot + 1, x));
  for (PetscInt s = 0; s < nseg; s++) {
    const PetscInt m = PetscMax(minc, (PetscInt)PetscCeilReal((b[s + 1] - b[s]) / hs[s] - 1e-9));
    for (PetscInt i = 0; i < m; i++) (*x)[k++] = b[s] + (b[s + 1] - b[s]) * i / m;
  }
  (*x)[k] = b[nseg];
  *n      = tot;
  PetscFunctionReturn(0);
}

/* the lap's element size through the height: -model_mesh_hz, or -model_mesh_h */
static PetscReal LapHz(const Model_FE *fe)
{
  return fe->hz > 0 ? fe->hz : fe->h;
}

/* the number of cells GridLines makes (a real: a mesh too fine to build is still counted) */
static PetscReal GridCount(PetscInt nseg, const PetscReal b[], const PetscReal hs[], PetscInt minc)
{
  PetscReal n = 0;
  for (PetscInt s = 0; s < nseg; s++) n += PetscMax((PetscReal)minc, PetscCeilReal((b[s + 1] - b[s]) / hs[s] - 1e-9));
  return n;
}

/* along one grid direction of n cells of order p: the nodes, and the sum over them of the nodes each one shares a
   cell with (vertex nodes 2p + 1, or p + 1 at the ends; nodes inside a cell p + 1) */
static void Grid1D(PetscReal n, PetscInt p, PetscReal *nodes, PetscReal *couple)
{
  *nodes  = p * n + 1;
  *couple = (n - 1) * (2 * p + 1) + 2 * (p + 1) + n * (p - 1) * (p + 1);
}

/*
  JRFEMeshEstimate - the size of the beam's (lap false) or lap joint's model from its mesh parameters alone, before the
  mesh is built: the grid of JRFEGeometryBeam / JRFEGeometryLap taken as a full box (holes and the second set of nodes
  on the contact plane left out: a few per cent), the nonzeros of K as the tensor product of the couplings along each
  direction (exact for a box), 9 per pair of coupled nodes. Memory: K, M and the eigensolver's shifted K - sigma M in
  AIJ (a value and a column index per nonzero), and its sparse LDL^T factorisation, about 10 N^(4/3) entries for N
  DOFs in 13 bytes each (MUMPS on these beams), plus 50 MB for the program. Checked against real runs of brb and
  lap1 (-model_view prints both): within 15 per cent.
*/
PetscErrorCode JRFEMeshEstimate(const Model_FE *fe, PetscBool lap, JRFEMeshSize *est)
{
  PetscReal nx, ny, nz, n[3], c[3];

  PetscFunctionBeginUser;
  if (lap) {
    const PetscReal xl = fe->L1 - fe->Llap, xr = fe->L1, xe = fe->L1 - fe->Llap + fe->L2;
    const PetscReal bx[4] = {0, xl, xr, xe}, hx[3] = {fe->h * fe->grade, fe->h, fe->h * fe->grade};
    const PetscReal by[2] = {0, fe->W}, hy[1] = {fe->h}, bz[3] = {0, 0.5 * fe->H, fe->H}, hz[2] = {LapHz(fe), LapHz(fe)};
    nx = GridCount(3, bx, hx, 1);
    ny = GridCount(1, by, hy, 2);
    nz = GridCount(2, bz, hz, 2);
  } else {
    const PetscReal bx[2] = {0, fe->L1}, by[2] = {0, fe->W}, bz[2] = {0, fe->H}, h[1] = {fe->h};
    nx = GridCount(1, bx, h, 1);
    ny = GridCount(1, by, h, 1);
    nz = GridCount(1, bz, h, 1);
  }
  Grid1D(nx, fe->order, &n[0], &c[0]);
  Grid1D(ny, fe->order, &n[1], &c[1]);
  Grid1D(nz, fe->order, &n[2], &c[2]);
  est->cells = nx * ny * nz;
  est->nodes = n[0] * n[1] * n[2];
  est->dofs  = 3 * est->nodes;
  est->nnz   = 9 * c[0] * c[1] * c[2];
  est->km    = 2 * est->nnz * (sizeof(PetscScalar) + sizeof(PetscInt));
  est->total = 1.5 * est->km + 13 * 10 * PetscPowReal(est->dofs, 4.0 / 3.0) + 50e6;
  PetscFunctionReturn(0);
}

/* the memory this run may use [bytes]: -model_memory_limit, or what the machine has available (MemAvailable in
   /proc/meminfo, else the free physical pages); 0 if unknown */
static PetscErrorCode MemoryAvailable(MPI_Comm comm, PetscReal limit_gib, PetscReal *bytes)
{
  double      avail = 0;
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  *bytes = limit_gib * 1073741824.0;
  if (limit_gib > 0) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    FILE *fp = fopen("/proc/meminfo", "r");
    char  line[256];
    if (fp) {
      while (fgets(line, sizeof(line), fp)) {
        double kb;
        if (sscanf(line, "MemAvailable: %lf kB", &kb) == 1) avail = kb * 1024.0;
      }
      fclose(fp);
    }
#if defined(_SC_AVPHYS_PAGES) && defined(_SC_PAGESIZE)
    if (!avail) avail = (double)sysconf(_SC_AVPHYS_PAGES) * (double)sysconf(_SC_PAGESIZE);
#endif
  }
  PetscCallMPI(MPI_Bcast(&avail, 1, MPI_DOUBLE, 0, comm));
  *bytes = (PetscReal)avail;
  PetscFunctionReturn(0);
}

/* JRFEMeshCheckMemory - before the mesh is built: an error if the model would need more memory than this run may use */
PetscErrorCode JRFEMeshCheckMemory(MPI_Comm comm, const Model_FE *fe, PetscBool lap)
{
  JRFEMeshSize    est;
  const PetscReal gib = 1073741824.0;
  PetscReal       avail;

  PetscFunctionBeginUser;
  PetscCall(MemoryAvailable(comm, fe->memlimit, &avail));
  PetscCall(JRFEMeshEstimate(fe, lap, &est));
  PetscCall(PetscInfo(NULL, "mesh estimate: %g cells, %g nodes, %g nonzeros in K, %g GiB for K and M, %g GiB in all; %g GiB available\n", (double)est.cells, (double)est.nodes, (double)est.nnz, (double)(est.km / gib), (double)(est.total / gib), (double)(avail / gib)));
  PetscCheck(!avail || est.total <= avail, comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_mesh_h %g: the mesh would have %.3g nodes (%.3g DOFs), about %.3g GiB for K and M and %.3g GiB in all with the eigensolver's factorisation, more than the %.3g GiB %s (a coarser -model_mesh_h, or -model_memory_limit GiB)", (double)fe->h, (double)est.nodes, (double)est.dofs, (double)(est.km / gib), (double)(est.total / gib), (double)(avail / gib), fe->memlimit > 0 ? "of -model_memory_limit" : "available");
  PetscCheck(est.dofs < (PetscReal)PETSC_MAX_INT, comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_mesh_h %g: the mesh would have %.3g DOFs, more than this PETSc's integers count (%d)", (double)fe->h, (double)est.dofs, (int)PETSC_MAX_INT);
  PetscFunctionReturn(0);
}

typedef struct {
  const Model_FE *fe;
  PetscReal       xl, xr; /* lap */
} LapCtx;

/* which body holds cell (i, j, k) with centre c: 0 = A, 1 = B, -1 = none (outside, or in a hole) */
static PetscInt LapBody(const LapCtx *lc, const PetscReal c[3])
{
  const Model_FE *fe = lc->fe;
  PetscInt        b  = -1;
  if (!fe->lap) return 0;
  if (c[0] < lc->xl) b = 0;
  else if (c[0] > lc->xr) b = 1;
  else b = c[2] > 0.5 * fe->H ? 0 : 1;
  for (PetscInt i = 0; i < fe->nbolts; i++) {
    const PetscReal dx = c[0] - fe->bolt[i].x[0], dy = c[1] - fe->bolt[i].x[1];
    if (dx * dx + dy * dy < 0.25 * fe->dhole * fe->dhole) b = -1;
  }
  return b;
}

/* Build the DMPlex of the bodies on the grid; cells labelled by body, faces by contact, footprint, clamp */
static PetscErrorCode BuildMesh(MPI_Comm comm, Model_FE *fe, const LapCtx *lc, PetscInt nx, const PetscReal *X, PetscInt ny, const PetscReal *Y, PetscInt nz, const PetscReal *Z, DM *dm)
{
  PetscMPIInt rank;
  PetscInt    ncell = 0, nvert = 0, *cells = NULL, *body = NULL;
  PetscReal  *coords = NULL;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    const PetscInt nv = (nx + 1) * (ny + 1) * (nz + 1);
    PetscInt      *vid, cap = 0;
    PetscCall(PetscMalloc1(nv, &vid));
    for (PetscInt pass = 0; pass < 2; pass++) { /* pass 0 counts, pass 1 fills */
      ncell = nvert = 0;
      for (PetscInt b = 0; b < (fe->lap ? 2 : 1); b++) {
        for (PetscInt v = 0; v < nv; v++) vid[v] = -1;
        for (PetscInt k = 0; k < nz; k++)
          for (PetscInt j = 0; j < ny; j++)
            for (PetscInt i = 0; i < nx; i++) {
              const PetscReal c[3]   = {0.5 * (X[i] + X[i + 1]), 0.5 * (Y[j] + Y[j + 1]), 0.5 * (Z[k] + Z[k + 1])};
              /* DMPlex hexahedron: bottom face (i,j),(i,j+1),(i+1,j+1),(i+1,j), top face (i,j),(i+1,j),(i+1,j+1),(i,j+1) */
              const PetscInt  di[8] = {0, 0, 1, 1, 0, 1, 1, 0}, dj[8] = {0, 1, 1, 0, 0, 0, 1, 1}, dk[8] = {0, 0, 0, 0, 1, 1, 1, 1};
              if (LapBody(lc, c) != b) continue;
              for (PetscInt q = 0; q < 8; q++) {
                const PetscInt g = ((k + dk[q]) * (ny + 1) + (j + dj[q])) * (nx + 1) + (i + di[q]);
                if (vid[g] < 0) {
                  if (pass) {
                    coords[3 * nvert + 0] = X[i + di[q]];
                    coords[3 * nvert + 1] = Y[j + dj[q]];
                    coords[3 * nvert + 2] = Z[k + dk[q]];
                  }
                  vid[g] = nvert++;
                }
                if (pass) cells[8 * ncell + q] = vid[g];
              }
              if (pass) body[ncell] = b;
              ncell++;
            }
      }
      if (!pass) {
        cap = ncell;
        PetscCall(PetscMalloc3(8 * cap, &cells, 3 * nvert, &coords, cap, &body));
      }
    }
    PetscCall(PetscFree(vid));
  }
  PetscCall(DMPlexCreateFromCellListPetsc(comm, 3, ncell, nvert, 8, PETSC_TRUE, cells, 3, coords, dm));
  PetscCall(DMCreateLabel(*dm, JR_LABEL_BODY));
  PetscCall(DMCreateLabel(*dm, JR_LABEL_CONTACT));
  PetscCall(DMCreateLabel(*dm, JR_LABEL_BOLT));
  PetscCall(DMCreateLabel(*dm, JR_LABEL_CLAMP));
  if (rank == 0) {
    PetscInt fs, fe_;
    for (PetscInt c = 0; c < ncell; c++) PetscCall(DMSetLabelValue(*dm, JR_LABEL_BODY, c, body[c] + 1));
    PetscCall(DMPlexGetHeightStratum(*dm, 1, &fs, &fe_));
    for (PetscInt f = fs; f < fe_; f++) {
      PetscInt        ns, bd;
      const PetscInt *supp;
      PetscReal       area, cen[3], nrm[3];
      const PetscReal tol = 1e-9 * PetscMax(fe->H, fe->W);
      PetscCall(DMPlexGetSupportSize(*dm, f, &ns));
      if (ns != 1) continue; /* interior face */
      PetscCall(DMPlexGetSupport(*dm, f, &supp));
      bd = body[supp[0]];
      PetscCall(DMPlexComputeCellGeometryFVM(*dm, f, &area, cen, nrm));
      if (PetscAbsReal(cen[0]) < tol) PetscCall(DMSetLabelValue(*dm, JR_LABEL_CLAMP, f, 1));
      if (!fe->lap) continue;
      if (PetscAbsReal(cen[2] - 0.5 * fe->H) < tol && cen[0] > lc->xl && cen[0] < lc->xr) PetscCall(DMSetLabelValue(*dm, JR_LABEL_CONTACT, f, bd + 1));
      for (PetscInt i = 0; i < fe->nbolts; i++) {
        const PetscReal dx = cen[0] - fe->bolt[i].x[0], dy = cen[1] - fe->bolt[i].x[1], r = PetscSqrtReal(dx * dx + dy * dy);
        if (r < 0.5 * fe->dhole || r > 0.5 * fe->dwasher) continue;
        if (bd == 0 && PetscAbsReal(cen[2] - fe->H) < tol) PetscCall(DMSetLabelValue(*dm, JR_LABEL_BOLT, f, 2 * i + 1));
        if (bd == 1 && PetscAbsReal(cen[2]) < tol) PetscCall(DMSetLabelValue(*dm, JR_LABEL_BOLT, f, 2 * i + 2));
      }
    }
    PetscCall(PetscFree3(cells, coords, body));
  }
  { /* the cells are numbered along the beam axis: the simple partitioner cuts the beams into slabs (minimal
       cuts for a beam) and, unlike PT-Scotch, gives the same DOF numbering every run (saved modes and reduced
       models do not need it: they are written in the natural order, JRFEDistribute); -petscpartitioner_type
       chooses another */
    PetscPartitioner part;
    PetscCall(DMPlexGetPartitioner(*dm, &part));
    PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSIMPLE));
    PetscCall(PetscPartitionerSetFromOptions(part));
  }
  PetscCall(JRFEDistribute(fe, dm));
  PetscFunctionReturn(0);
}

/* Distribute the mesh built on rank 0 (the partitioner the caller set) and keep, in fe->orig, each local point's number
   in the mesh as built: the same on any number of ranks, it orders the DOFs of saved modes and reduced models
   (JRFENaturalOrdering) */
PetscErrorCode JRFEDistribute(Model_FE *fe, DM *dm)
{
  DM       dist = NULL;
  PetscSF  sf   = NULL;
  PetscInt ps, pe;

  PetscFunctionBeginUser;
  PetscCall(DMPlexDistribute(*dm, 0, &sf, &dist));
  if (dist) {
    PetscCall(DMDestroy(dm));
    *dm = dist;
  }
  PetscCall(DMPlexGetChart(*dm, &ps, &pe));
  PetscCall(PetscFree(fe->orig));
  PetscCall(PetscMalloc1(pe - ps + 1, &fe->orig));
  for (PetscInt p = ps; p < pe; p++) fe->orig[p - ps] = p; /* one rank: the mesh as built */
  if (sf) {                                                 /* the migration: each new point (leaf) from a built one (root) */
    PetscInt           nl;
    const PetscInt    *il;
    const PetscSFNode *ir;
    PetscCall(PetscSFGetGraph(sf, NULL, &nl, &il, &ir));
    for (PetscInt i = 0; i < nl; i++) {
      const PetscInt p = il ? il[i] : i;
      PetscCheck(ir[i].rank == 0 && p >= ps && p < pe, PETSC_COMM_SELF, PETSC_ERR_PLIB, "The mesh's point %" PetscInt_FMT " does not come from the mesh built on rank 0", p);
      fe->orig[p - ps] = ir[i].index;
    }
    PetscCall(PetscSFDestroy(&sf));
  }
  PetscFunctionReturn(0);
}

/* A straight prismatic beam along x: -model_length, -model_width (y), -model_height (z) */
PetscErrorCode JRFEGeometryBeam(MPI_Comm comm, Model_FE *fe, DM *dm)
{
  PetscInt   nx = 0, ny = 0, nz = 0;
  PetscReal *X, *Y, *Z;
  LapCtx     lc = {fe, 0.0, 0.0};
  PetscReal  bx[2] = {0, fe->L1}, by[2] = {0, fe->W}, bz[2] = {0, fe->H}, h[1] = {fe->h};

  PetscFunctionBeginUser;
  fe->lap    = PETSC_FALSE;
  fe->nbolts = 0;
  PetscCall(GridLines(1, bx, h, 1, &nx, &X));
  PetscCall(GridLines(1, by, h, 1, &ny, &Y));
  PetscCall(GridLines(1, bz, h, 1, &nz, &Z));
  PetscCall(BuildMesh(comm, fe, &lc, nx, X, ny, Y, nz, Z, dm));
  PetscCall(PetscFree(X));
  PetscCall(PetscFree(Y));
  PetscCall(PetscFree(Z));
  PetscFunctionReturn(0);
}

/* The lap-joint assembly (see the top of this file) */
PetscErrorCode JRFEGeometryLap(MPI_Comm comm, Model_FE *fe, DM *dm)
{
  const PetscReal xl = fe->L1 - fe->Llap, xr = fe->L1, xe = fe->L1 - fe->Llap + fe->L2;
  PetscInt        nx = 0, ny = 0, nz = 0;
  PetscReal      *X, *Y, *Z;
  LapCtx          lc    = {fe, xl, xr};
  const PetscReal bx[4] = {0, xl, xr, xe}, hx[3] = {fe->h * fe->grade, fe->h, fe->h * fe->grade};
  const PetscReal by[2] = {0, fe->W}, hy[1] = {fe->h}, bz[3] = {0, 0.5 * fe->H, fe->H}, hz[2] = {LapHz(fe), LapHz(fe)};

  PetscFunctionBeginUser;
  fe->lap = PETSC_TRUE;
  PetscCheck(fe->L1 > fe->Llap && fe->L2 > fe->Llap, comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_lap_length %g m must be shorter than both beams (-model_length_a %g, -model_length_b %g m)", (double)fe->Llap, (double)fe->L1, (double)fe->L2);
  PetscCheck(fe->dwasher > fe->dhole && fe->dhole >= fe->dbolt, comm, PETSC_ERR_ARG_OUTOFRANGE, "Bolt %g m, hole %g m, washer %g m: need bolt <= hole < washer diameter (-model_bolt_diameter, -model_hole_diameter, -model_washer_diameter)", (double)fe->dbolt, (double)fe->dhole, (double)fe->dwasher);
  PetscCall(PetscFree(fe->bolt));
  PetscCall(PetscCalloc1(PetscMax(fe->nbolts, 1), &fe->bolt));
  for (PetscInt i = 0; i < fe->nbolts; i++) { /* centred in the lap at the pitch, on the width's midline */
    JRBolt *b = &fe->bolt[i];
    b->x[0]   = 0.5 * (xl + xr) + (i - 0.5 * (fe->nbolts - 1)) * fe->pitch;
    b->x[1]   = 0.5 * fe->W;
    b->x[2]   = fe->H;
    b->axis   = fe->H;
    b->d      = fe->dbolt;
    PetscCheck(b->x[0] - 0.5 * fe->dwasher > xl - 1e-12 && b->x[0] + 0.5 * fe->dwasher < xr + 1e-12, comm, PETSC_ERR_ARG_OUTOFRANGE, "Bolt %" PetscInt_FMT " at x = %g m: its washer (diameter %g m) reaches outside the lap [%g, %g] m (check -model_nbolts, -model_bolt_pitch, -model_lap_length)", i + 1, (double)b->x[0], (double)fe->dwasher, (double)xl, (double)xr);
    PetscCheck(0.5 * fe->dwasher < 0.5 * fe->W + 1e-12, comm, PETSC_ERR_ARG_OUTOFRANGE, "Washer diameter %g m is wider than the beam (-model_width %g m)", (double)fe->dwasher, (double)fe->W);
  }
  PetscCall(GridLines(3, bx, hx, 1, &nx, &X));
  PetscCall(GridLines(1, by, hy, 2, &ny, &Y));
  PetscCall(GridLines(2, bz, hz, 2, &nz, &Z));
  PetscCall(BuildMesh(comm, fe, &lc, nx, X, ny, Y, nz, Z, dm));
  PetscCall(PetscFree(X));
  PetscCall(PetscFree(Y));
  PetscCall(PetscFree(Z));
  PetscFunctionReturn(0);
}
