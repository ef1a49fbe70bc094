/*
   Finite-element models of beams and bolted lap joints on DMPlex + PetscFE.

   Discretisation: isotropic linear elasticity on hexahedra with Lagrange elements of order
   -model_fe_order (default 2: 27-node quadratic hexahedra, which do not lock in bending); the mesh, its
   distribution, the DOF layout (PetscFE on DMPlex), assembly into the parallel matrices and the output are
   PETSc's. The order-2 element matrices (stiffness and consistent mass, 3x3x3 Gauss points on the trilinear
   geometry) come from a kernel in this file rather than from PETSc's generic PetscFE integration, which is
   two orders of magnitude slower on 81-DOF cells (15 ms a cell in PETSc 3.18: 10 minutes for the Brake-Reuss
   beam instead of a second); equal element shapes are computed once. -model_fe_assembly petscfe selects
   PETSc's integration (DMPlexSNESComputeJacobianFEM, DMCreateMassMatrix) instead; the two agree to
   round-off (tests/test_fe.c). Units SI.

   Bolts: each bolt is an Euler-Bernoulli beam (the shank: diameter d, steel of the beams' modulus) from
   the head footprint to the nut footprint. Each end is tied to its footprint (the washer's contact
   annulus on the outer face) by a least-squares rigid fit: the end's 3 displacements and 3 rotations are
   the rigid motion closest to the footprint nodes' displacements (an RBE3-like distributing coupling),
   so the bolt stiffness enters K as T^T K_beam T over the footprint DOFs. The washers, head and nut are
   not meshed: the footprints are not stiffened by them, which makes the joint slightly softer than a
   solid tied bolt (a few per cent on the modes that bend the lap; see the README). The assembly holds
   together through the bolts alone, with no contact, as in the thesis's modal analysis.
*/
#include <jointrom/private/feimpl.h>
#include <petscblaslapack.h>

/* -model_bolt_tie rigid: penalty on a footprint's non-rigid motion, times E and the footprint's radius (about
   100 times a node's stiffness: frequencies within 1e-4 of a perfectly rigid tie, K's conditioning spared) */
#define JR_TIE_PENALTY 1e2

/* ---- pointwise functions (PetscDS and DMProjectFunction signatures: most arguments unused) ---- */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
static void g3_elasticity(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, PetscReal u_tShift, const PetscReal x[], PetscInt numConstants, const PetscScalar constants[], PetscScalar g3[])
{
  const PetscReal lam = PetscRealPart(constants[0]), mu = PetscRealPart(constants[1]);
  for (PetscInt i = 0; i < dim; i++)
    for (PetscInt j = 0; j < dim; j++)
      for (PetscInt d = 0; d < dim; d++)
        for (PetscInt e = 0; e < dim; e++) g3[((i * dim + j) * dim + d) * dim + e] = (i == d && j == e ? lam : 0.0) + (i == j && d == e ? mu : 0.0) + (i == e && d == j ? mu : 0.0);
}

static PetscErrorCode zero_vector(PetscInt dim, PetscReal time, const PetscReal x[], PetscInt Nc, PetscScalar *u, void *ctx)
{
  for (PetscInt c = 0; c < Nc; c++) u[c] = 0.0;
  return 0;
}

#pragma GCC diagnostic pop

/* forward: the position of a mesh point's node */
static PetscErrorCode PointCoordinates(DM, PetscInt, PetscReal[3]);

/* the nodal coordinates as a global vector (3 per node): every owned, unconstrained node */
PetscErrorCode JRFENodalCoordinates(DM dm, Vec X)
{
  PetscSection ls, gs;
  PetscInt     ps, pe, rs;
  PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(PetscSectionGetChart(ls, &ps, &pe));
  PetscCall(VecGetOwnershipRange(X, &rs, NULL));
  PetscCall(VecGetArray(X, &x));
  for (PetscInt p = ps; p < pe; p++) {
    PetscInt  d, cd, off;
    PetscReal c[3];
    PetscCall(PetscSectionGetDof(ls, p, &d));
    PetscCall(PetscSectionGetConstraintDof(ls, p, &cd));
    if (d != 3 || cd) continue;
    PetscCall(PetscSectionGetOffset(gs, p, &off));
    if (off < 0) continue; /* not owned */
    PetscCall(PointCoordinates(dm, p, c));
    for (int k = 0; k < 3; k++) x[off - rs + k] = c[k];
  }
  PetscCall(VecRestoreArray(X, &x));
  PetscFunctionReturn(0);
}

/* the mean of a cell's vertex coordinates (independent of the closure order, which the Q2 kernel permutes
   to tensor order on the coordinate DM: DMPlexComputeCellGeometryFVM expects DMPlex's own order) */
static PetscErrorCode CellCentre(DM dm, PetscInt c, PetscReal x[3])
{
  DM           cdm;
  Vec          coords;
  PetscScalar *a = NULL;
  PetscInt     n;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(DMPlexVecGetClosure(cdm, NULL, coords, c, &n, &a));
  x[0] = x[1] = x[2] = 0.0;
  for (PetscInt i = 0; i < n; i++) x[i % 3] += 3.0 * PetscRealPart(a[i]) / n;
  PetscCall(DMPlexVecRestoreClosure(cdm, NULL, coords, c, &n, &a));
  PetscFunctionReturn(0);
}

/* the six rigid-body motions (translations x, y, z, rotations about x, y, z through the mean of the cell
   centres; JRModes M-orthonormalises them) */
PetscErrorCode JRFERigidBasis(DM dm, Vec rb[6])
{
  PetscReal          c[4] = {0, 0, 0, 0};
  PetscInt           cs, ce, n;
  MPI_Comm           comm;
  Vec                X;
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cs, &ce));
  for (PetscInt e = cs; e < ce; e++) {
    PetscReal xc[3];
    PetscCall(CellCentre(dm, e, xc));
    for (int d = 0; d < 3; d++) c[d] += xc[d];
    c[3] += 1.0;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, c, 4, MPIU_REAL, MPIU_SUM, comm));
  PetscCall(DMCreateGlobalVector(dm, &X));
  PetscCall(JRFENodalCoordinates(dm, X));
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt k = 0; k < 6; k++) {
    PetscScalar *r;
    PetscCall(VecDuplicate(X, &rb[k]));
    PetscCall(VecGetArray(rb[k], &r));
    for (PetscInt i = 0; i < n; i += 3) {
      const PetscReal d[3] = {PetscRealPart(x[i]) - c[0] / c[3], PetscRealPart(x[i + 1]) - c[1] / c[3], PetscRealPart(x[i + 2]) - c[2] / c[3]};
      r[i] = r[i + 1] = r[i + 2] = 0.0;
      if (k < 3) r[i + k] = 1.0;
      else { /* e_a x d */
        const PetscInt a = k - 3;
        r[i]             = a == 1 ? d[2] : a == 2 ? -d[1] : 0.0;
        r[i + 1]         = a == 2 ? d[0] : a == 0 ? -d[2] : 0.0;
        r[i + 2]         = a == 0 ? d[1] : a == 1 ? -d[0] : 0.0;
      }
    }
    PetscCall(VecRestoreArray(rb[k], &r));
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecDestroy(&X));
  PetscFunctionReturn(0);
}

/* ---- nodes on labelled faces ---- */
typedef struct {
  PetscInt  dof;
  PetscReal x[3];
  PetscReal w; /* the node's share of the faces' area (JRFEFaceNodeAreas) */
} Node;

static int CompareNodeDof(const void *a, const void *b)
{
  const Node *p = (const Node *)a, *q = (const Node *)b;
  return (p->dof > q->dof) - (p->dof < q->dof);
}

/* coordinates of a mesh point: the mean of its closure's vertices (the node position of Lagrange
   elements on affine hexahedra: vertex, edge midpoint, face or cell centre) */
static PetscErrorCode PointCoordinates(DM dm, PetscInt p, PetscReal x[3])
{
  PetscInt           nc, *cl = NULL, vs, ve, nv = 0;
  Vec                coords;
  PetscSection       cs;
  const PetscScalar *ca;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vs, &ve));
  PetscCall(VecGetArrayRead(coords, &ca));
  x[0] = x[1] = x[2] = 0.0;
  PetscCall(DMPlexGetTransitiveClosure(dm, p, PETSC_TRUE, &nc, &cl));
  for (PetscInt k = 0; k < nc; k++) {
    const PetscInt q = cl[2 * k];
    PetscInt       off;
    if (q < vs || q >= ve) continue;
    PetscCall(PetscSectionGetOffset(cs, q, &off));
    for (int d = 0; d < 3; d++) x[d] += PetscRealPart(ca[off + d]);
    nv++;
  }
  PetscCall(DMPlexRestoreTransitiveClosure(dm, p, PETSC_TRUE, &nc, &cl));
  PetscCall(VecRestoreArrayRead(coords, &ca));
  for (int d = 0; d < 3; d++) x[d] /= nv;
  PetscFunctionReturn(0);
}

/* The area weights of the nodes of one quadrilateral face (bilinear geometry, 3 x 3 Gauss): the integral of
   each node's shape function over the face, so that a uniform pressure p gives the consistent nodal forces
   p w and sum w = the face's area. cl: the face's closure (points, orientations); order 1 (nodes at the
   vertices) or 2 (vertices, edge midpoints, the face centre: the tensor Q2 weights 1/36, 4/36, 16/36 on a
   parallelogram). w[k] is set for the closure's k-th point (0 for points without a node). */
static PetscErrorCode QuadNodeWeights(DM dm, PetscInt order, PetscInt np, const PetscInt *cl, PetscReal *w)
{
  PetscInt  vs, ve, es, ee, corner[4] = {-1, -1, -1, -1}, nv = 0, vidx[4];
  PetscReal X[4][3], ref[9][2], xi[3] = {-0.774596669241483377, 0.0, 0.774596669241483377}, gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vs, &ve));
  PetscCall(DMPlexGetDepthStratum(dm, 1, &es, &ee));
  for (PetscInt k = 0; k < np; k++)
    if (cl[2 * k] >= vs && cl[2 * k] < ve) {
      PetscCheck(nv < 4, PETSC_COMM_SELF, PETSC_ERR_SUP, "Contact faces must be quadrilaterals (hexahedral meshes)");
      vidx[nv++] = k;
    }
  PetscCheck(nv == 4, PETSC_COMM_SELF, PETSC_ERR_SUP, "Contact faces must be quadrilaterals (hexahedral meshes)");
  /* cyclic corner order: vertex 0, its two edge neighbours, the opposite vertex */
  {
    PetscInt nb[2], nn = 0;
    for (PetscInt k = 0; k < np; k++) {
      const PetscInt *cone, e = cl[2 * k];
      if (e < es || e >= ee) continue;
      PetscCall(DMPlexGetCone(dm, e, &cone));
      if (cone[0] == cl[2 * vidx[0]] && nn < 2) nb[nn++] = cone[1];
      else if (cone[1] == cl[2 * vidx[0]] && nn < 2) nb[nn++] = cone[0];
    }
    PetscCheck(nn == 2, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Face vertex without two edges");
    corner[0] = vidx[0];
    for (PetscInt j = 1; j < 4; j++) {
      const PetscInt p = cl[2 * vidx[j]];
      if (p == nb[0]) corner[1] = vidx[j];
      else if (p == nb[1]) corner[3] = vidx[j];
      else corner[2] = vidx[j];
    }
  }
  for (int c = 0; c < 4; c++) PetscCall(PointCoordinates(dm, cl[2 * corner[c]], X[c]));
  { /* reference position of every closure point with a node */
    const PetscReal rc[4][2] = {
      {-1, -1},
      {1,  -1},
      {1,  1 },
      {-1, 1 }
    };
    PetscCheck(np == 9, PETSC_COMM_SELF, PETSC_ERR_SUP, "Contact faces must be quadrilaterals");
    for (PetscInt k = 0; k < np; k++) w[k] = ref[k][0] = ref[k][1] = 0.0;
    for (PetscInt k = 0; k < np; k++) {
      const PetscInt p = cl[2 * k];
      if (p >= vs && p < ve) {
        for (int c = 0; c < 4; c++)
          if (corner[c] == k) {
            ref[k][0] = rc[c][0];
            ref[k][1] = rc[c][1];
          }
      } else if (p >= es && p < ee) {
        const PetscInt *cone;
        PetscCall(DMPlexGetCone(dm, p, &cone));
        for (int c = 0; c < 4; c++)
          if (cl[2 * corner[c]] == cone[0] || cl[2 * corner[c]] == cone[1]) {
            ref[k][0] += 0.5 * rc[c][0];
            ref[k][1] += 0.5 * rc[c][1];
          }
      } /* the face itself: (0, 0) */
    }
  }
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      const PetscReal s = xi[a], t = xi[b];
      PetscReal       dxs[3], dxt[3], cr[3], J;
      for (int d = 0; d < 3; d++) {
        dxs[d] = 0.25 * (-(1 - t) * X[0][d] + (1 - t) * X[1][d] + (1 + t) * X[2][d] - (1 + t) * X[3][d]);
        dxt[d] = 0.25 * (-(1 - s) * X[0][d] - (1 + s) * X[1][d] + (1 + s) * X[2][d] + (1 - s) * X[3][d]);
      }
      cr[0] = dxs[1] * dxt[2] - dxs[2] * dxt[1];
      cr[1] = dxs[2] * dxt[0] - dxs[0] * dxt[2];
      cr[2] = dxs[0] * dxt[1] - dxs[1] * dxt[0];
      J     = PetscSqrtReal(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]) * gw[a] * gw[b];
      for (PetscInt k = 0; k < np; k++) {
        PetscReal Ns, Nt;
        if (order == 2) { /* 1D quadratic Lagrange factors of the nodes at -1, 0, 1 */
          Ns = ref[k][0] < -0.5 ? 0.5 * s * (s - 1) : ref[k][0] > 0.5 ? 0.5 * s * (s + 1) : 1 - s * s;
          Nt = ref[k][1] < -0.5 ? 0.5 * t * (t - 1) : ref[k][1] > 0.5 ? 0.5 * t * (t + 1) : 1 - t * t;
        } else { /* bilinear, corners only */
          Ns = PetscAbsReal(ref[k][0]) == 1.0 && PetscAbsReal(ref[k][1]) == 1.0 ? 0.5 * (1 + ref[k][0] * s) : 0.0;
          Nt = 0.5 * (1 + ref[k][1] * t);
        }
        w[k] += Ns * Nt * J;
      }
    }
  PetscFunctionReturn(0);
}

/*
  JRFEFaceNodes - the nodes (mesh points carrying displacement DOFs) in the closure of the faces with
  label value val: n nodes, coordinates x[3n], first global DOF dof[n] (x, y, z at dof, dof+1, dof+2),
  gathered on every rank, one entry per node, sorted by DOF. Constrained nodes are left out.
  JRFEFaceNodeAreas also gives each node's area weight w[n] (its shape function integrated over the faces,
  quadrilateral faces of order-2 or order-1 elements): a uniform pressure p has the nodal forces p w.
*/
static PetscErrorCode FaceNodes(DM dm, const char *label, PetscInt val, PetscInt *n, PetscReal **x, PetscInt **dof, PetscReal **wout)
{
  MPI_Comm     comm;
  PetscSection ls, gs;
  IS           is;
  PetscInt     nf = 0, cap = 0, cnt = 0, tot, *counts, *displs;
  Node        *loc = NULL, *all;
  PetscMPIInt  size, *rc, *rd;
  MPI_Datatype nodetype;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetStratumIS(dm, label, val, &is));
  if (is) PetscCall(ISGetLocalSize(is, &nf));
  if (nf) {
    const PetscInt *faces;
    PetscCall(ISGetIndices(is, &faces));
    for (PetscInt i = 0; i < nf; i++) {
      PetscInt  np, *cl = NULL;
      PetscReal wf[9];
      PetscCall(DMPlexGetTransitiveClosure(dm, faces[i], PETSC_TRUE, &np, &cl));
      if (wout) { /* the order from the DOFs of the face's own point: 3 (one node) for order 2, none for order 1 */
        PetscInt d0;
        PetscCheck(np == 9, comm, PETSC_ERR_SUP, "Node areas need quadrilateral faces (hexahedral meshes)");
        PetscCall(PetscSectionGetDof(ls, cl[0], &d0));
        PetscCheck(d0 == 0 || d0 == 3, comm, PETSC_ERR_SUP, "Node areas need elements of order 1 or 2 (-model_fe_order)");
        PetscCall(QuadNodeWeights(dm, d0 ? 2 : 1, np, cl, wf));
      }
      for (PetscInt k = 0; k < np; k++) {
        const PetscInt p = cl[2 * k];
        PetscInt       d, cd, off;
        PetscCall(PetscSectionGetDof(ls, p, &d));
        PetscCall(PetscSectionGetConstraintDof(ls, p, &cd));
        if (d != 3 || cd) continue;
        PetscCall(PetscSectionGetOffset(gs, p, &off));
        if (off < 0) off = -(off + 1);
        if (cnt == cap) {
          Node *nn;
          cap = cap ? 2 * cap : 256;
          PetscCall(PetscMalloc1(cap, &nn));
          if (cnt) PetscCall(PetscArraycpy(nn, loc, cnt));
          PetscCall(PetscFree(loc));
          loc = nn;
        }
        loc[cnt].dof = off;
        loc[cnt].w   = wout ? wf[k] : 0.0;
        PetscCall(PointCoordinates(dm, p, loc[cnt].x));
        cnt++;
      }
      PetscCall(DMPlexRestoreTransitiveClosure(dm, faces[i], PETSC_TRUE, &np, &cl));
    }
    PetscCall(ISRestoreIndices(is, &faces));
  }
  PetscCall(ISDestroy(&is));
  /* gather on every rank */
  PetscCall(PetscMalloc4(size, &counts, size, &displs, size, &rc, size, &rd));
  PetscCallMPI(MPI_Allgather(&cnt, 1, MPIU_INT, counts, 1, MPIU_INT, comm));
  tot = 0;
  for (PetscMPIInt r = 0; r < size; r++) {
    displs[r] = tot;
    rc[r]     = (PetscMPIInt)counts[r];
    rd[r]     = (PetscMPIInt)tot;
    tot += counts[r];
  }
  PetscCall(PetscMalloc1(PetscMax(tot, 1), &all));
  PetscCallMPI(MPI_Type_contiguous((PetscMPIInt)sizeof(Node), MPI_BYTE, &nodetype));
  PetscCallMPI(MPI_Type_commit(&nodetype));
  PetscCallMPI(MPI_Allgatherv(loc, (PetscMPIInt)cnt, nodetype, all, rc, rd, nodetype, comm));
  PetscCallMPI(MPI_Type_free(&nodetype));
  qsort(all, (size_t)tot, sizeof(Node), CompareNodeDof);
  cnt = 0;
  for (PetscInt i = 0; i < tot; i++) {
    if (!cnt || all[i].dof != all[cnt - 1].dof) all[cnt++] = all[i];
    else all[cnt - 1].w += all[i].w; /* a node of several faces: its weights add */
  }
  *n = cnt;
  PetscCall(PetscMalloc2(3 * PetscMax(cnt, 1), x, PetscMax(cnt, 1), dof));
  if (wout) PetscCall(PetscMalloc1(PetscMax(cnt, 1), wout));
  for (PetscInt i = 0; i < cnt; i++) {
    (*dof)[i] = all[i].dof;
    for (int d = 0; d < 3; d++) (*x)[3 * i + d] = all[i].x[d];
    if (wout) (*wout)[i] = all[i].w;
  }
  PetscCall(PetscFree(all));
  PetscCall(PetscFree(loc));
  PetscCall(PetscFree4(counts, displs, rc, rd));
  PetscFunctionReturn(0);
}

PetscErrorCode JRFEFaceNodes(DM dm, const char *label, PetscInt val, PetscInt *n, PetscReal **x, PetscInt **dof)
{
  PetscFunctionBeginUser;
  PetscCall(FaceNodes(dm, label, val, n, x, dof, NULL));
  PetscFunctionReturn(0);
}

PetscErrorCode JRFEFaceNodeAreas(DM dm, const char *label, PetscInt val, PetscInt *n, PetscReal **x, PetscInt **dof, PetscReal **w)
{
  PetscFunctionBeginUser;
  PetscCall(FaceNodes(dm, label, val, n, x, dof, w));
  PetscFunctionReturn(0);
}

/* ---- element matrices: 27-node (Q2) hexahedra, trilinear geometry, 3 x 3 x 3 Gauss ----
   PETSc's generic pointwise integration takes ~15 ms per Q2 hexahedron (measured: 4.7 s for 320 cells),
   ten minutes for 10^6 DOFs; this kernel builds the same element matrices in ~0.1 ms, and a structured
   mesh reuses them (identical bricks are computed once). The closure is in tensor (lexicographic) order
   (DMPlexSetClosurePermutationTensor): node a + 3b + 9c at reference (a - 1, b - 1, c - 1), 3 components
   each. -model_fe_assembly petscfe uses DMPlexSNESComputeJacobianFEM instead (a test checks they agree). */
typedef struct {
  PetscReal rel[24]; /* vertex coordinates relative to vertex 0: the cell's shape */
  PetscReal K[81 * 81], M[81 * 81];
} ElemCache;

static void Lagrange1D(PetscReal x, PetscReal N[3], PetscReal dN[3])
{
  N[0]  = 0.5 * x * (x - 1.0);
  N[1]  = 1.0 - x * x;
  N[2]  = 0.5 * x * (x + 1.0);
  dN[0] = x - 0.5;
  dN[1] = -2.0 * x;
  dN[2] = x + 0.5;
}

/* Ke (81 x 81, stiffness) and Me (81 x 81, mass with density rho) of one hexahedron with vertices X
   (8 x 3, lexicographic: vertex i + 2j + 4k at reference (2i - 1, 2j - 1, 2k - 1)) */
static PetscErrorCode HexQ2(const PetscReal X[24], PetscReal lam, PetscReal mu, PetscReal rho, PetscReal *Ke, PetscReal *Me)
{
  const PetscReal g[3] = {-PetscSqrtReal(0.6), 0.0, PetscSqrtReal(0.6)}, gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 81 * 81; i++) Ke[i] = Me[i] = 0.0;
  for (int qz = 0; qz < 3; qz++)
    for (int qy = 0; qy < 3; qy++)
      for (int qx = 0; qx < 3; qx++) {
        const PetscReal xi[3] = {g[qx], g[qy], g[qz]}, w = gw[qx] * gw[qy] * gw[qz];
        PetscReal       N1[3][3], dN1[3][3], J[3][3] = {{0}}, Ji[3][3], det, N[27], dN[27][3];
        for (int d = 0; d < 3; d++) Lagrange1D(xi[d], N1[d], dN1[d]);
        /* geometry: x = sum_v M_v(xi) X_v, M_v = prod (1 +- xi_d)/2 */
        for (int v = 0; v < 8; v++) {
          const int       s[3] = {v & 1, (v >> 1) & 1, (v >> 2) & 1};
          PetscReal       m[3], dm[3];
          for (int d = 0; d < 3; d++) {
            m[d]  = 0.5 * (1.0 + (2 * s[d] - 1) * xi[d]);
            dm[d] = 0.5 * (2 * s[d] - 1);
          }
          const PetscReal dM[3] = {dm[0] * m[1] * m[2], m[0] * dm[1] * m[2], m[0] * m[1] * dm[2]};
          for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) J[a][b] += X[3 * v + a] * dM[b]; /* dx_a / dxi_b */
        }
        det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
        PetscCheck(det != 0.0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Degenerate hexahedron");
        Ji[0][0] = (J[1][1] * J[2][2] - J[1][2] * J[2][1]) / det;
        Ji[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / det;
        Ji[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / det;
        Ji[1][0] = (J[1][2] * J[2][0] - J[1][0] * J[2][2]) / det;
        Ji[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / det;
        Ji[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / det;
        Ji[2][0] = (J[1][0] * J[2][1] - J[1][1] * J[2][0]) / det;
        Ji[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / det;
        Ji[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / det;
        for (int c = 0; c < 3; c++)
          for (int b = 0; b < 3; b++)
            for (int a = 0; a < 3; a++) {
              const int       n      = a + 3 * b + 9 * c;
              const PetscReal dr[3]  = {dN1[0][a] * N1[1][b] * N1[2][c], N1[0][a] * dN1[1][b] * N1[2][c], N1[0][a] * N1[1][b] * dN1[2][c]};
              N[n]                   = N1[0][a] * N1[1][b] * N1[2][c];
              for (int d = 0; d < 3; d++) dN[n][d] = dr[0] * Ji[0][d] + dr[1] * Ji[1][d] + dr[2] * Ji[2][d];
            }
        {
          const PetscReal wd = w * PetscAbsReal(det);
          for (int p = 0; p < 27; p++)
            for (int q = 0; q < 27; q++) {
              const PetscReal gpq = dN[p][0] * dN[q][0] + dN[p][1] * dN[q][1] + dN[p][2] * dN[q][2];
              const PetscReal mpq = wd * rho * N[p] * N[q];
              for (int i = 0; i < 3; i++) {
                PetscReal *row = Ke + (3 * p + i) * 81 + 3 * q;
                for (int j = 0; j < 3; j++) row[j] += wd * (lam * dN[p][i] * dN[q][j] + mu * dN[p][j] * dN[q][i] + (i == j ? mu * gpq : 0.0));
                Me[(3 * p + i) * 81 + 3 * q + i] += mpq;
              }
            }
        }
      }
  PetscFunctionReturn(0);
}

/* K and M by the kernel above, element by element into the DMPlex matrices */
static PetscErrorCode AssembleHexQ2(DM dm, PetscReal E, PetscReal nu, PetscReal rho, Mat K, Mat M)
{
  const PetscReal lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  DM              cdm;
  Vec             coords;
  PetscInt        cs, ce, ncache = 0;
  ElemCache      *cache;
  PetscReal      *Ke, *Me;
  const PetscInt  maxcache = 32;

  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cs, &ce));
  PetscCall(PetscMalloc1(maxcache, &cache));
  PetscCall(PetscMalloc2(81 * 81, &Ke, 81 * 81, &Me));
  for (PetscInt c = cs; c < ce; c++) {
    PetscScalar *xc = NULL;
    PetscInt     nx, hit = -1;
    PetscReal    X[24], rel[24], scale = 0.0;
    PetscCall(DMPlexVecGetClosure(cdm, NULL, coords, c, &nx, &xc));
    PetscCheck(nx == 24, PETSC_COMM_SELF, PETSC_ERR_SUP, "The 27-node kernel needs hexahedra with 8 vertices (cell %" PetscInt_FMT " has %" PetscInt_FMT " coordinates); use -model_fe_assembly petscfe", c, nx);
    for (int k = 0; k < 24; k++) X[k] = PetscRealPart(xc[k]);
    PetscCall(DMPlexVecRestoreClosure(cdm, NULL, coords, c, &nx, &xc));
    for (int k = 0; k < 24; k++) {
      rel[k] = X[k] - X[k % 3];
      scale  = PetscMax(scale, PetscAbsReal(rel[k]));
    }
    for (PetscInt h = 0; h < ncache && hit < 0; h++) {
      PetscBool same = PETSC_TRUE;
      for (int k = 0; k < 24 && same; k++)
        if (PetscAbsReal(cache[h].rel[k] - rel[k]) > 1e-12 * scale) same = PETSC_FALSE;
      if (same) hit = h;
    }
    if (hit < 0) {
      PetscCall(HexQ2(X, lam, mu, rho, Ke, Me));
      if (ncache < maxcache) {
        for (int k = 0; k < 24; k++) cache[ncache].rel[k] = rel[k];
        PetscCall(PetscArraycpy(cache[ncache].K, Ke, 81 * 81));
        PetscCall(PetscArraycpy(cache[ncache].M, Me, 81 * 81));
        hit = ncache++;
      }
    }
    PetscCall(DMPlexMatSetClosure(dm, NULL, NULL, K, c, hit >= 0 ? cache[hit].K : Ke, ADD_VALUES));
    PetscCall(DMPlexMatSetClosure(dm, NULL, NULL, M, c, hit >= 0 ? cache[hit].M : Me, ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree2(Ke, Me));
  PetscCall(PetscFree(cache));
  PetscFunctionReturn(0);
}

/* ---- bolts ---- */
/* invert a 6 x 6 matrix (Gauss-Jordan with partial pivoting) */
static PetscErrorCode Invert6(PetscReal A[36], MPI_Comm comm)
{
  PetscReal M[6][12];

  PetscFunctionBeginUser;
  for (int i = 0; i < 6; i++)
    for (int j = 0; j < 12; j++) M[i][j] = j < 6 ? A[i * 6 + j] : (j - 6 == i);
  for (int c = 0; c < 6; c++) {
    int piv = c;
    for (int r = c + 1; r < 6; r++)
      if (PetscAbsReal(M[r][c]) > PetscAbsReal(M[piv][c])) piv = r;
    PetscCheck(PetscAbsReal(M[piv][c]) > 0.0, comm, PETSC_ERR_ARG_WRONG, "A bolt footprint cannot carry rotations (its nodes are collinear)");
    for (int j = 0; j < 12; j++) {
      PetscReal t = M[c][j];
      M[c][j]     = M[piv][j];
      M[piv][j]   = t;
    }
    for (int r = 0; r < 6; r++)
      if (r != c) {
        const PetscReal f = M[r][c] / M[c][c];
        for (int j = c; j < 12; j++) M[r][j] -= f * M[c][j];
      }
  }
  for (int i = 0; i < 6; i++)
    for (int j = 0; j < 6; j++) A[i * 6 + j] = M[i][j + 6] / M[i][i];
  PetscFunctionReturn(0);
}

/* B (3 x 6): the displacement at x of the rigid motion (u_ref, theta) about xref, u = u_ref + theta x (x - xref) */
static void RigidRows(const PetscReal x[3], const PetscReal xref[3], PetscReal B[3][6])
{
  const PetscReal r[3] = {x[0] - xref[0], x[1] - xref[1], x[2] - xref[2]};
  const PetscReal b[3][6] = {
    {1, 0, 0, 0,     r[2],  -r[1]},
    {0, 1, 0, -r[2], 0,     r[0] },
    {0, 0, 1, r[1],  -r[0], 0    }
  };
  for (int k = 0; k < 3; k++)
    for (int a = 0; a < 6; a++) B[k][a] = b[k][a];
}

/* T (6 x 3n, row-major): the rigid motion (u_ref, theta) fitting the footprint nodes' displacements in
   the least-squares sense, u_i ~ u_ref + theta x (x_i - xref); B_i = [I, -[r_i]x] */
static PetscErrorCode RigidFit(MPI_Comm comm, PetscInt n, const PetscReal *x, const PetscReal xref[3], PetscReal *T)
{
  PetscReal G[36] = {0};

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) {
    PetscReal B[3][6];
    RigidRows(x + 3 * i, xref, B);
    for (int a = 0; a < 6; a++)
      for (int b = 0; b < 6; b++)
        for (int k = 0; k < 3; k++) G[a * 6 + b] += B[k][a] * B[k][b];
  }
  PetscCall(Invert6(G, comm));
  for (PetscInt i = 0; i < n; i++) {
    PetscReal B[3][6];
    RigidRows(x + 3 * i, xref, B);
    for (int a = 0; a < 6; a++)
      for (int k = 0; k < 3; k++) {
        PetscReal s = 0.0;
        for (int b = 0; b < 6; b++) s += G[a * 6 + b] * B[k][b];
        T[a * 3 * n + 3 * i + k] = s;
      }
  }
  PetscFunctionReturn(0);
}

/* 12 x 12 stiffness of an Euler-Bernoulli beam from p1 to p2 in global axes, DOFs (u, theta) at p1 then p2 */
static void BeamStiffness(const PetscReal p1[3], const PetscReal p2[3], PetscReal d, PetscReal E, PetscReal nu, PetscReal K[144])
{
  const PetscReal ax[3] = {p2[0] - p1[0], p2[1] - p1[1], p2[2] - p1[2]}, L = PetscSqrtReal(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
  const PetscReal A = PETSC_PI * d * d / 4, Ib = PETSC_PI * d * d * d * d / 64, Jt = 2 * Ib, G = E / (2 * (1 + nu));
  PetscReal       e3[3] = {ax[0] / L, ax[1] / L, ax[2] / L}, e1[3], e2[3], R[3][3], Kl[144] = {0};
  const PetscReal a = E * A / L, t = G * Jt / L, b = E * Ib / (L * L * L);
  /* local frame: e3 along the shank, e1 perpendicular, e2 = e3 x e1 */
  {
    const PetscReal h[3] = {PetscAbsReal(e3[0]) < 0.9 ? 1.0 : 0.0, PetscAbsReal(e3[0]) < 0.9 ? 0.0 : 1.0, 0.0};
    PetscReal       s;
    e1[0] = h[1] * e3[2] - h[2] * e3[1];
    e1[1] = h[2] * e3[0] - h[0] * e3[2];
    e1[2] = h[0] * e3[1] - h[1] * e3[0];
    s     = PetscSqrtReal(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int k = 0; k < 3; k++) e1[k] /= s;
    e2[0] = e3[1] * e1[2] - e3[2] * e1[1];
    e2[1] = e3[2] * e1[0] - e3[0] * e1[2];
    e2[2] = e3[0] * e1[1] - e3[1] * e1[0];
  }
  for (int k = 0; k < 3; k++) {
    R[0][k] = e1[k];
    R[1][k] = e2[k];
    R[2][k] = e3[k];
  }
#define KL(i, j) Kl[(i) * 12 + (j)]
  /* local DOFs: node n at 6n: u1 u2 u3 th1 th2 th3 */
  {
    const int u3[2] = {2, 8}, th3[2] = {5, 11};
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) {
        KL(u3[i], u3[j]) += (i == j ? a : -a);
        KL(th3[i], th3[j]) += (i == j ? t : -t);
      }
  }
  {
    /* bending: (w1, phi1, w2, phi2) with phi = dw/ds: u1 with th2 (du1/ds = th2), u2 with -th1 */
    const PetscReal kb[4][4] = {
      {12,     6 * L,     -12,    6 * L    },
      {6 * L,  4 * L * L, -6 * L, 2 * L * L},
      {-12,    -6 * L,    12,     -6 * L   },
      {6 * L,  2 * L * L, -6 * L, 4 * L * L}
    };
    const int    w1[4] = {0, 4, 6, 10}, w2[4] = {1, 3, 7, 9};
    const double s2[4] = {1, -1, 1, -1};
    for (int i = 0; i < 4; i++)
      for (int j = 0; j < 4; j++) {
        KL(w1[i], w1[j]) += b * kb[i][j];
        KL(w2[i], w2[j]) += b * s2[i] * s2[j] * kb[i][j];
      }
  }
#undef KL
  /* K = T^T Kl T, T = blockdiag(R, R, R, R) */
  for (int i = 0; i < 12; i++)
    for (int j = 0; j < 12; j++) {
      PetscReal s = 0.0;
      for (int p = 0; p < 12; p++) {
        if (p / 3 != i / 3) continue;
        for (int q = 0; q < 12; q++) {
          if (q / 3 != j / 3) continue;
          s += R[p % 3][i % 3] * Kl[p * 12 + q] * R[q % 3][j % 3];
        }
      }
      K[i * 12 + j] = s;
    }
}

/* dense stiffness blocks over arbitrary global DOFs (every rank holds all blocks; each adds its own rows) */
typedef struct {
  PetscInt   n, *dof;
  PetscReal *Kf; /* n x n, row-major */
} DenseBlock;

/* K += sum of the blocks, through a matrix of their own pattern (K's pattern does not couple them);
   frees the blocks' arrays */
static PetscErrorCode AddDenseBlocks(JRModel m, PetscInt nb, DenseBlock *bd)
{
  Mat         Kb;
  PetscInt   *bn;
  PetscInt  **bdof;
  PetscReal **bval;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc3(nb + 1, &bn, nb + 1, &bdof, nb + 1, &bval));
  for (PetscInt i = 0; i < nb; i++) {
    bn[i]   = bd[i].n;
    bdof[i] = bd[i].dof;
    bval[i] = bd[i].Kf;
  }
  PetscCall(JRMatCreateFromBlocks(m->K, nb, bn, (const PetscInt *const *)bdof, (const PetscReal *const *)bval, &Kb));
  for (PetscInt i = 0; i < nb; i++) PetscCall(PetscFree2(bd[i].dof, bd[i].Kf));
  PetscCall(PetscFree3(bn, bdof, bval));
  PetscCall(MatAXPY(m->K, 1.0, Kb, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatDestroy(&Kb));
  PetscFunctionReturn(0);
}

/* add the bolts' stiffness to K: sum_b T_b^T K_beam T_b over the footprint DOFs */
static PetscErrorCode AddBolts(JRModel m, Model_FE *fe)
{
  DenseBlock *bd;

  JRBolts    *B = &m->bolts;
  PetscInt    ntot = 0;

  PetscFunctionBeginUser;
  PetscCall(JRBoltsDestroy(B));
  if (!fe->nbolts) PetscFunctionReturn(0);
  PetscCall(PetscCalloc1(fe->nbolts, &bd));
  B->n = fe->nbolts;
  PetscCall(PetscMalloc3(fe->nbolts + 1, &B->off, fe->nbolts, &B->ka, 3 * fe->nbolts, &B->x));
  B->off[0] = 0;
  for (PetscInt i = 0; i < fe->nbolts; i++) {
    PetscInt   nh, nn, *dh, *dn;
    PetscReal *xh, *xn, ch[3] = {0, 0, 0}, cn[3] = {0, 0, 0}, Kbeam[144], *Th, *Tn, *T;
    PetscCall(JRFEFaceNodes(fe->dm, JR_LABEL_BOLT, 2 * i + 1, &nh, &xh, &dh));
    PetscCall(JRFEFaceNodes(fe->dm, JR_LABEL_BOLT, 2 * i + 2, &nn, &xn, &dn));
    PetscCheck(nh >= 3 && nn >= 3, m->comm, PETSC_ERR_ARG_WRONG, "Bolt %" PetscInt_FMT ": its washer footprints have %" PetscInt_FMT " (head) and %" PetscInt_FMT " (nut) nodes; refine the mesh (-model_mesh_h) or widen the washer", i + 1, nh, nn);
    fe->bolt[i].nhead = nh;
    fe->bolt[i].nnut  = nn;
    for (PetscInt k = 0; k < nh; k++)
      for (int d = 0; d < 3; d++) ch[d] += xh[3 * k + d] / nh;
    for (PetscInt k = 0; k < nn; k++)
      for (int d = 0; d < 3; d++) cn[d] += xn[3 * k + d] / nn;
    fe->bolt[i].axis = PetscSqrtReal(PetscSqr(ch[0] - cn[0]) + PetscSqr(ch[1] - cn[1]) + PetscSqr(ch[2] - cn[2]));
    for (int d = 0; d < 3; d++) fe->bolt[i].x[d] = ch[d];
    BeamStiffness(ch, cn, fe->bolt[i].d, fe->E, fe->nu, Kbeam);
    PetscCall(PetscMalloc3(6 * 3 * nh, &Th, 6 * 3 * nn, &Tn, 12 * 3 * (nh + nn), &T));
    PetscCall(RigidFit(m->comm, nh, xh, ch, Th));
    PetscCall(RigidFit(m->comm, nn, xn, cn, Tn));
    { /* the pretension data: elongation g = e3 . (u_nut - u_head) of the fitted ends, e3 from head to nut */
      const PetscReal L = fe->bolt[i].axis, e3[3] = {(cn[0] - ch[0]) / L, (cn[1] - ch[1]) / L, (cn[2] - ch[2]) / L};
      PetscInt       *dof;
      PetscReal      *g;
      B->off[i + 1] = ntot + 3 * (nh + nn);
      PetscCall(PetscMalloc2(B->off[i + 1], &dof, B->off[i + 1], &g));
      if (ntot) {
        PetscCall(PetscArraycpy(dof, B->dof, ntot));
        PetscCall(PetscArraycpy(g, B->g, ntot));
        PetscCall(PetscFree2(B->dof, B->g));
      }
      B->dof = dof;
      B->g   = g;
      for (PetscInt c = 0; c < 3 * nh; c++) {
        B->dof[ntot + c] = dh[c / 3] + c % 3;
        B->g[ntot + c]   = -(e3[0] * Th[0 * 3 * nh + c] + e3[1] * Th[1 * 3 * nh + c] + e3[2] * Th[2 * 3 * nh + c]);
      }
      for (PetscInt c = 0; c < 3 * nn; c++) {
        B->dof[ntot + 3 * nh + c] = dn[c / 3] + c % 3;
        B->g[ntot + 3 * nh + c]   = e3[0] * Tn[0 * 3 * nn + c] + e3[1] * Tn[1 * 3 * nn + c] + e3[2] * Tn[2 * 3 * nn + c];
      }
      ntot     = B->off[i + 1];
      B->ka[i] = fe->E * PETSC_PI * fe->bolt[i].d * fe->bolt[i].d / 4 / L;
      for (int d = 0; d < 3; d++) B->x[3 * i + d] = ch[d];
    }
    /* T = blockdiag(Th, Tn): 12 x 3(nh + nn) */
    PetscCall(PetscArrayzero(T, 12 * 3 * (nh + nn)));
    for (int a = 0; a < 6; a++) {
      for (PetscInt c = 0; c < 3 * nh; c++) T[a * 3 * (nh + nn) + c] = Th[a * 3 * nh + c];
      for (PetscInt c = 0; c < 3 * nn; c++) T[(a + 6) * 3 * (nh + nn) + 3 * nh + c] = Tn[a * 3 * nn + c];
    }
    bd[i].n = 3 * (nh + nn);
    PetscCall(PetscMalloc2(bd[i].n, &bd[i].dof, bd[i].n * bd[i].n, &bd[i].Kf));
    for (PetscInt k = 0; k < nh; k++)
      for (int d = 0; d < 3; d++) bd[i].dof[3 * k + d] = dh[k] + d;
    for (PetscInt k = 0; k < nn; k++)
      for (int d = 0; d < 3; d++) bd[i].dof[3 * nh + 3 * k + d] = dn[k] + d;
    { /* Kf = T^T Kbeam T */
      const PetscInt nf = bd[i].n;
      PetscReal     *KT;
      PetscCall(PetscMalloc1(12 * nf, &KT));
      for (int a = 0; a < 12; a++)
        for (PetscInt c = 0; c < nf; c++) {
          PetscReal s = 0.0;
          for (int b = 0; b < 12; b++) s += Kbeam[a * 12 + b] * T[b * nf + c];
          KT[a * nf + c] = s;
        }
      for (PetscInt r = 0; r < nf; r++)
        for (PetscInt c = 0; c < nf; c++) {
          PetscReal s = 0.0;
          for (int a = 0; a < 12; a++) s += T[a * nf + r] * KT[a * nf + c];
          bd[i].Kf[r * nf + c] = s;
        }
      PetscCall(PetscFree(KT));
      if (fe->rigidtie) { /* penalise the footprints' deviation from their rigid fit: kappa (I - B T) per end */
        for (int end = 0; end < 2; end++) {
          const PetscInt   o = end ? 3 * nh : 0, n = end ? nn : nh;
          const PetscReal *xe = end ? xn : xh, *ce = end ? cn : ch, *Te = end ? Tn : Th;
          PetscReal        rho2 = 0.0, kappa;
          for (PetscInt k = 0; k < n; k++) rho2 += (PetscSqr(xe[3 * k] - ce[0]) + PetscSqr(xe[3 * k + 1] - ce[1]) + PetscSqr(xe[3 * k + 2] - ce[2])) / n;
          kappa = JR_TIE_PENALTY * fe->E * PetscSqrtReal(rho2);
          for (PetscInt k = 0; k < n; k++) {
            PetscReal B[3][6];
            RigidRows(xe + 3 * k, ce, B);
            for (int d = 0; d < 3; d++)
              for (PetscInt c = 0; c < 3 * n; c++) {
                PetscReal bt = 0.0;
                for (int a = 0; a < 6; a++) bt += B[d][a] * Te[a * 3 * n + c];
                bd[i].Kf[(o + 3 * k + d) * nf + o + c] += kappa * ((3 * k + d == c ? 1.0 : 0.0) - bt);
              }
          }
        }
      }
    }
    PetscCall(PetscFree3(Th, Tn, T));
    PetscCall(PetscFree2(xh, dh));
    PetscCall(PetscFree2(xn, dn));
  }
  PetscCall(AddDenseBlocks(m, fe->nbolts, bd));
  PetscCall(PetscFree(bd));
  PetscFunctionReturn(0);
}

/* ---- interface pairs ---- */
/* The outward unit normal of the faces labelled val (area-weighted mean over all ranks) and the largest
   angle [rad] between a face's normal and the mean: the node-to-node model needs a plane interface. */
static PetscErrorCode SurfaceNormal(DM dm, const char *label, PetscInt val, PetscReal nrm[3], PetscReal *dev, PetscReal *area_tot)
{
  IS              is;
  PetscInt        nf = 0;
  const PetscInt *faces = NULL;
  PetscReal       s[4] = {0, 0, 0, 0}, len, cmin = 1.0;
  MPI_Comm        comm;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCall(DMGetStratumIS(dm, label, val, &is));
  if (is) {
    PetscCall(ISGetLocalSize(is, &nf));
    PetscCall(ISGetIndices(is, &faces));
  }
  for (PetscInt pass = 0; pass < 2; pass++) {
    for (PetscInt i = 0; i < nf; i++) {
      const PetscInt *supp;
      PetscInt        ns;
      PetscReal       area, cf[3], n[3], cc[3], dot = 0.0;
      PetscCall(DMPlexComputeCellGeometryFVM(dm, faces[i], &area, cf, n));
      PetscCall(DMPlexGetSupportSize(dm, faces[i], &ns));
      PetscCall(DMPlexGetSupport(dm, faces[i], &supp));
      if (ns == 1) { /* point away from the cell */
        PetscCall(CellCentre(dm, supp[0], cc));
        if ((cf[0] - cc[0]) * n[0] + (cf[1] - cc[1]) * n[1] + (cf[2] - cc[2]) * n[2] < 0) area = -area;
      }
      len = PetscSqrtReal(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (pass == 0) {
        for (int d = 0; d < 3; d++) s[d] += area * n[d] / len;
        s[3] += PetscAbsReal(area);
      }
      else {
        for (int d = 0; d < 3; d++) dot += (area > 0 ? 1 : -1) * n[d] / len * nrm[d];
        cmin = PetscMin(cmin, dot);
      }
    }
    if (pass == 0) {
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s, 4, MPIU_REAL, MPIU_SUM, comm));
      *area_tot = s[3];
      len = PetscSqrtReal(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
      for (int d = 0; d < 3; d++) nrm[d] = len > 0 ? s[d] / len : 0.0;
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &cmin, 1, MPIU_REAL, MPIU_MIN, comm));
  *dev = PetscAcosReal(PetscMax(-1.0, PetscMin(1.0, cmin)));
  if (is) PetscCall(ISRestoreIndices(is, &faces));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

typedef struct {
  PetscReal x;
  PetscInt  i;
} XKey;

static int CompareXKey(const void *a, const void *b)
{
  const XKey *p = (const XKey *)a, *q = (const XKey *)b;
  return (p->x > q->x) - (p->x < q->x);
}

/* Pair every node of contact surface A with the nearest node of B within -model_pair_tol (B sorted by x,
   a window search); the normal is surface A's outward normal (from A into B), the tangent the beam axis x
   (or y) projected on the interface plane. */
static PetscErrorCode FindPairs(JRModel m, Model_FE *fe)
{
  PetscInt   na, nb, *da, *db, np = 0, *usedB;
  PetscReal *xa, *xb, *wa, tol = fe->pairtol, nrm[3], dev = 0.0, t[3] = {0, 0, 0}, tn = 0.0, dmax = 0.0;
  XKey      *kb;
  JRPairs   *P = &m->pairs;

  PetscFunctionBeginUser;
  PetscCheck(tol > 0 && PetscIsNormalReal(tol), m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_pair_tol %g: must be a positive distance [m]", (double)tol);
  PetscCall(JRPairsDestroy(P));
  PetscCall(JRFEFaceNodeAreas(fe->dm, JR_LABEL_CONTACT, 1, &na, &xa, &da, &wa));
  PetscCall(JRFEFaceNodes(fe->dm, JR_LABEL_CONTACT, 2, &nb, &xb, &db));
  fe->ncontact[0] = na;
  fe->ncontact[1] = nb;
  PetscCall(SurfaceNormal(fe->dm, JR_LABEL_CONTACT, 1, nrm, &dev, &fe->contact_area));
  PetscCheck(dev < 1e-6, m->comm, PETSC_ERR_SUP, "The contact surface is not plane (its face normals differ by up to %g degrees): node-to-node pairs need a plane interface", (double)(dev * 180 / PETSC_PI));
  t[fe->tangent[0] == 'y' ? 1 : 0] = 1.0;
  for (int d = 0; d < 3; d++) tn += t[d] * nrm[d];
  for (int d = 0; d < 3; d++) t[d] -= tn * nrm[d];
  tn = PetscSqrtReal(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  PetscCheck(tn > 1e-6, m->comm, PETSC_ERR_ARG_WRONG, "-model_tangent %s is normal to the contact surface (normal %g %g %g)", fe->tangent, (double)nrm[0], (double)nrm[1], (double)nrm[2]);
  for (int d = 0; d < 3; d++) t[d] /= tn;
  PetscCall(PetscMalloc1(PetscMax(nb, 1), &kb));
  PetscCall(PetscCalloc1(PetscMax(nb, 1), &usedB));
  for (PetscInt i = 0; i < nb; i++) {
    kb[i].x = xb[3 * i];
    kb[i].i = i;
  }
  qsort(kb, (size_t)nb, sizeof(XKey), CompareXKey);
  PetscCall(PetscMalloc5(3 * PetscMax(na, 1), &P->x, 3 * PetscMax(na, 1), &P->t, 3 * PetscMax(na, 1), &P->nrm, 3 * PetscMax(na, 1), &P->dofA, 3 * PetscMax(na, 1), &P->dofB));
  PetscCall(PetscMalloc2(PetscMax(na, 1), &P->area, PetscMax(na, 1), &P->gap0));
  for (PetscInt a = 0; a < na; a++) {
    PetscInt  lo = 0, hi = nb, best = -1;
    PetscReal bd = tol;
    while (lo < hi) { /* first B node with x >= xa - tol */
      const PetscInt mid = (lo + hi) / 2;
      if (kb[mid].x < xa[3 * a] - tol) lo = mid + 1;
      else hi = mid;
    }
    for (PetscInt j = lo; j < nb && kb[j].x <= xa[3 * a] + tol; j++) {
      const PetscInt  b = kb[j].i;
      const PetscReal r = PetscSqrtReal(PetscSqr(xa[3 * a] - xb[3 * b]) + PetscSqr(xa[3 * a + 1] - xb[3 * b + 1]) + PetscSqr(xa[3 * a + 2] - xb[3 * b + 2]));
      if (r <= bd) {
        bd   = r;
        best = b;
      }
    }
    if (best < 0 || usedB[best]) continue;
    usedB[best] = 1;
    dmax        = PetscMax(dmax, bd);
    P->area[np] = wa[a];
    P->gap0[np] = (xb[3 * best] - xa[3 * a]) * nrm[0] + (xb[3 * best + 1] - xa[3 * a + 1]) * nrm[1] + (xb[3 * best + 2] - xa[3 * a + 2]) * nrm[2];
    for (int d = 0; d < 3; d++) {
      P->x[3 * np + d]    = xa[3 * a + d];
      P->dofA[3 * np + d] = da[a] + d;
      P->dofB[3 * np + d] = db[best] + d;
      P->nrm[3 * np + d]  = nrm[d];
      P->t[3 * np + d]    = t[d];
    }
    np++;
  }
  P->n        = np;
  fe->pairgap = dmax;
  PetscCheck(np == na && np == nb, m->comm, PETSC_ERR_ARG_WRONG, "Contact surfaces do not face each other node to node: %" PetscInt_FMT " nodes on surface A, %" PetscInt_FMT " on B, %" PetscInt_FMT " pairs within %g m (-model_pair_tol)", na, nb, np, (double)tol);
  PetscCall(PetscFree(kb));
  PetscCall(PetscFree(usedB));
  PetscCall(PetscFree2(xa, da));
  PetscCall(PetscFree(wa));
  PetscCall(PetscFree2(xb, db));
  PetscFunctionReturn(0);
}

/* -model_interface tied: every pair joined in all three directions by a penalty spring (the stuck interface
   of a linear joint model), kappa = JR_TIE_PENALTY E sqrt(area per pair) */
static PetscErrorCode TieInterface(JRModel m, Model_FE *fe)
{
  const JRPairs  *P = &m->pairs;
  const PetscReal kappa = P->n ? JR_TIE_PENALTY * fe->E * PetscSqrtReal(fe->contact_area / P->n) : 0.0;
  DenseBlock     *bd;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(P->n * 3 + 1, &bd));
  for (PetscInt i = 0; i < 3 * P->n; i++) {
    bd[i].n = 2;
    PetscCall(PetscMalloc2(2, &bd[i].dof, 4, &bd[i].Kf));
    bd[i].dof[0] = P->dofA[i];
    bd[i].dof[1] = P->dofB[i];
    bd[i].Kf[0] = bd[i].Kf[3] = kappa;
    bd[i].Kf[1] = bd[i].Kf[2] = -kappa;
  }
  PetscCall(AddDenseBlocks(m, 3 * P->n, bd));
  PetscCall(PetscFree(bd));
  PetscFunctionReturn(0);
}

PetscErrorCode JRBoltsDestroy(JRBolts *B)
{
  PetscFunctionBeginUser;
  if (B->off) PetscCall(PetscFree3(B->off, B->ka, B->x));
  if (B->dof) PetscCall(PetscFree2(B->dof, B->g));
  PetscCall(PetscMemzero(B, sizeof(*B)));
  PetscFunctionReturn(0);
}

PetscErrorCode JRPairsDestroy(JRPairs *P)
{
  PetscFunctionBeginUser;
  if (P->x) PetscCall(PetscFree5(P->x, P->t, P->nrm, P->dofA, P->dofB));
  if (P->area) PetscCall(PetscFree2(P->area, P->gap0));
  PetscCall(PetscMemzero(P, sizeof(*P)));
  PetscFunctionReturn(0);
}

/* ---- set-up ---- */
PetscErrorCode JRFESetUp(JRModel m, Model_FE *fe)
{
  PetscFE   pfe;
  PetscDS   ds;
  Vec       u, Mu;
  PetscReal vol = 0.0;

  PetscFunctionBeginUser;
  PetscCheck(fe->E > 0 && PetscIsNormalReal(fe->E), m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_E %g: Young's modulus must be positive [Pa]", (double)fe->E);
  PetscCheck(fe->nu > -1.0 && fe->nu < 0.5, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_nu %g: Poisson's ratio must be in (-1, 0.5)", (double)fe->nu);
  PetscCheck(fe->rho > 0 && PetscIsNormalReal(fe->rho), m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_rho %g: the density must be positive [kg/m^3]", (double)fe->rho);
  PetscCheck(fe->order >= 1 && fe->order <= 4, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-model_fe_order %" PetscInt_FMT ": 1 to 4", fe->order);
  PetscCall(PetscFECreateLagrange(m->comm, 3, 3, PETSC_FALSE, fe->order, PETSC_DETERMINE, &pfe));
  PetscCall(PetscObjectSetName((PetscObject)pfe, "displacement"));
  PetscCall(DMAddField(fe->dm, NULL, (PetscObject)pfe));
  PetscCall(PetscFEDestroy(&pfe));
  PetscCall(DMCreateDS(fe->dm));
  if (fe->clamp) { /* the end x = 0 fixed: a cantilever */
    DMLabel        label;
    const PetscInt val = 1;
    PetscCall(DMGetLabel(fe->dm, JR_LABEL_CLAMP, &label));
    PetscCall(DMAddBoundary(fe->dm, DM_BC_ESSENTIAL, "clamp", label, 1, &val, 0, 0, NULL, (void (*)(void))zero_vector, NULL, NULL, NULL));
  }
  PetscCall(DMGetDS(fe->dm, &ds));
  {
    const PetscReal   lam = fe->E * fe->nu / ((1 + fe->nu) * (1 - 2 * fe->nu)), mu = fe->E / (2 * (1 + fe->nu));
    const PetscScalar cst[2] = {lam, mu};
    PetscCall(PetscDSSetConstants(ds, 2, (PetscScalar *)cst));
  }
  PetscCall(PetscDSSetJacobian(ds, 0, 0, NULL, NULL, NULL, g3_elasticity));
  { /* the volume from PETSc's cell geometry (independent of the element kernel; before the closure permutation) */
    PetscInt cs, ce;
    PetscCall(DMPlexGetHeightStratum(fe->dm, 0, &cs, &ce));
    for (PetscInt c = cs; c < ce; c++) {
      PetscReal v, cen[3]; /* no overlap: every cell is owned */
      PetscCall(DMPlexComputeCellGeometryFVM(fe->dm, c, &v, cen, NULL));
      vol += v;
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &vol, 1, MPIU_REAL, MPIU_SUM, m->comm));
    fe->volume = vol;
  }
  PetscCall(DMSetUp(fe->dm));
  PetscCall(DMCreateMatrix(fe->dm, &m->K));
  PetscCall(DMCreateGlobalVector(fe->dm, &u));
  PetscCall(VecZeroEntries(u));
  if (fe->order == 2 && !fe->petscfe) {
    DM cdm;
    PetscCall(DMPlexSetClosurePermutationTensor(fe->dm, PETSC_DETERMINE, NULL));
    PetscCall(DMGetCoordinateDM(fe->dm, &cdm));
    PetscCall(DMPlexSetClosurePermutationTensor(cdm, PETSC_DETERMINE, NULL));
    PetscCall(MatDuplicate(m->K, MAT_DO_NOT_COPY_VALUES, &m->M)); /* K's pattern: half the preallocation time */
    PetscCall(AssembleHexQ2(fe->dm, fe->E, fe->nu, fe->rho, m->K, m->M));
  } else {
    PetscCall(DMPlexSNESComputeJacobianFEM(fe->dm, u, m->K, m->K, NULL));
    PetscCall(DMCreateMassMatrix(fe->dm, fe->dm, &m->M));
    PetscCall(MatScale(m->M, fe->rho));
  }
  PetscCall(MatGetSize(m->K, &m->ndof, NULL));
  PetscCall(PetscObjectSetName((PetscObject)m->K, "K"));
  PetscCall(PetscObjectSetName((PetscObject)m->M, "M"));
  PetscCall(AddBolts(m, fe));
  /* mass: a unit translation u_x = 1 gives u^T M u = total mass */
  if (!fe->clamp) { /* the x translation through M */
    PetscScalar *a;
    PetscInt     n;
    PetscCall(VecDuplicate(u, &Mu));
    PetscCall(VecGetLocalSize(u, &n));
    PetscCall(VecGetArray(u, &a));
    for (PetscInt i = 0; i < n; i++) a[i] = i % 3 == 0 ? 1.0 : 0.0;
    PetscCall(VecRestoreArray(u, &a));
    PetscCall(MatMult(m->M, u, Mu));
    PetscCall(VecDot(u, Mu, &fe->mass));
    PetscCall(VecDestroy(&Mu));
  } else fe->mass = fe->rho * vol; /* a clamped end removes DOFs: the mass check is made free-free */
  m->mass        = fe->mass;
  m->volume_mass = fe->rho * fe->volume;
  fe->nnodes     = m->ndof / 3;
  PetscCall(VecDestroy(&u));
  if (fe->lap) PetscCall(FindPairs(m, fe));
  if (fe->lap && fe->tied) PetscCall(TieInterface(m, fe));
  m->tied = fe->lap && fe->tied ? PETSC_TRUE : PETSC_FALSE;
  { /* the rigid-body modes as K's near null space: algebraic multigrid (-modes_st_pc_type gamg) needs them */
    Vec          X, Xb;
    MatNullSpace nsp;
    PetscInt     n;
    PetscCall(DMCreateGlobalVector(fe->dm, &X));
    PetscCall(JRFENodalCoordinates(fe->dm, X));
    PetscCall(VecGetLocalSize(X, &n));
    PetscCall(VecCreateMPI(m->comm, n, PETSC_DETERMINE, &Xb));
    PetscCall(VecSetBlockSize(Xb, 3));
    PetscCall(VecCopy(X, Xb));
    PetscCall(MatNullSpaceCreateRigidBody(Xb, &nsp));
    PetscCall(MatSetNearNullSpace(m->K, nsp));
    PetscCall(MatNullSpaceDestroy(&nsp));
    PetscCall(VecDestroy(&Xb));
    PetscCall(VecDestroy(&X));
  }
  m->dm = fe->dm;
  PetscCall(PetscObjectReference((PetscObject)fe->dm));
  PetscFunctionReturn(0);
}
