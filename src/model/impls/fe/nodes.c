/*
   Nodes of the FE models: their coordinates, the rigid-body motions, and the nodes of labelled face sets
   (contact surfaces, bolt footprints, the clamped end) with their area weights.

   A node is a mesh point carrying displacement DOFs; its position is the mean of the point's closure's
   vertices (vertex, edge midpoint, face or cell centre: the node positions of Lagrange elements on
   affine hexahedra).
*/
#include <jointrom/private/feimpl.h>

/* coordinates of a mesh point: the mean of its closure's vertices */
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

/* The natural position of every owned DOF of dm's global vector, in its order (nat: an IS of local size the owned
   DOFs): the DOFs sorted by their mesh point's number in the mesh as built (orig, JRFEDistribute) and then by
   component, which does not depend on the partition, so that a vector written in that order reads back on any number
   of ranks. Every rank holds every DOF's key while they are ranked (a few MB per million DOFs). */
PetscErrorCode JRFENaturalOrdering(DM dm, const PetscInt *orig, IS *nat)
{
  MPI_Comm     comm;
  PetscSection ls, gs;
  PetscInt     ps, pe, cs, nloc = 0, rs = 0, N = 0, *key, *all, *idx, md = 1, bad = 0;
  PetscMPIInt  size, *cnt, *dsp, nl;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(PetscSectionGetChart(ls, &ps, &pe));
  PetscCall(DMPlexGetChart(dm, &cs, NULL)); /* orig's first point */
  {
    Vec g;
    PetscCall(DMGetGlobalVector(dm, &g));
    PetscCall(VecGetLocalSize(g, &nloc));
    PetscCall(VecGetOwnershipRange(g, &rs, NULL));
    PetscCall(DMRestoreGlobalVector(dm, &g));
  }
  for (PetscInt p = ps; p < pe; p++) { /* the most DOFs of a point: the components' stride in the keys */
    PetscInt d;
    PetscCall(PetscSectionGetDof(ls, p, &d));
    md = PetscMax(md, d);
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &md, 1, MPIU_INT, MPI_MAX, comm));
  PetscCall(PetscMalloc1(nloc + 1, &key));
  for (PetscInt i = 0; i < nloc; i++) key[i] = -1;
  for (PetscInt p = ps; p < pe; p++) {
    PetscInt        d, cd, off, j = 0;
    const PetscInt *ci = NULL;
    PetscCall(PetscSectionGetOffset(gs, p, &off));
    if (off < 0) continue; /* not owned */
    PetscCall(PetscSectionGetDof(ls, p, &d));
    PetscCall(PetscSectionGetConstraintDof(ls, p, &cd));
    if (cd) PetscCall(PetscSectionGetConstraintIndices(ls, p, &ci));
    for (PetscInt c = 0; c < d; c++) {
      PetscBool con = PETSC_FALSE;
      for (PetscInt q = 0; q < cd; q++) con = (PetscBool)(con || ci[q] == c);
      if (con) continue;
      if (off - rs + j < 0 || off - rs + j >= nloc) bad = 1;
      else key[off - rs + j] = md * orig[p - cs] + c; /* a point's global DOFs: its unconstrained components in order */
      j++;
    }
  }
  for (PetscInt i = 0; i < nloc; i++)
    if (key[i] < 0) bad = 1;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(!bad, comm, PETSC_ERR_PLIB, "The owned DOFs and the mesh points' DOFs do not match");
  /* the position of each key among all of them */
  PetscCall(PetscMPIIntCast(nloc, &nl));
  PetscCall(PetscMalloc2(size, &cnt, size + 1, &dsp));
  PetscCallMPI(MPI_Allgather(&nl, 1, MPI_INT, cnt, 1, MPI_INT, comm));
  dsp[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) dsp[r + 1] = dsp[r] + cnt[r];
  N = dsp[size];
  PetscCall(PetscMalloc2(N + 1, &all, nloc + 1, &idx));
  PetscCallMPI(MPI_Allgatherv(key, nl, MPIU_INT, all, cnt, dsp, MPIU_INT, comm));
  PetscCall(PetscSortInt(N, all));
  for (PetscInt i = 0; i < nloc; i++) {
    PetscInt loc;
    PetscCall(PetscFindInt(key[i], N, all, &loc));
    if (loc < 0 || (loc > 0 && all[loc - 1] == key[i]) || (loc + 1 < N && all[loc + 1] == key[i])) bad = 1; /* not found, or shared */
    idx[i] = loc;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(!bad, comm, PETSC_ERR_PLIB, "Two DOFs share a natural key");
  PetscCall(ISCreateGeneral(comm, nloc, idx, PETSC_COPY_VALUES, nat));
  PetscCall(PetscFree2(all, idx));
  PetscCall(PetscFree2(cnt, dsp));
  PetscCall(PetscFree(key));
  PetscFunctionReturn(0);
}

/* the mean of a cell's vertex coordinates (independent of the closure order, which the Q2 kernel permutes
   to tensor order on the coordinate DM: DMPlexComputeCellGeometryFVM expects DMPlex's own order) */
PetscErrorCode JRFECellCentre(DM dm, PetscInt c, PetscReal x[3])
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
    PetscCall(JRFECellCentre(dm, e, xc));
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

/* ---- area weights of the nodes of one quadrilateral face ---- */

/* The closure indices of a quadrilateral face's four vertices in cyclic order: vertex 0, its edge
   neighbour, the opposite vertex, its other edge neighbour. cl: the face's closure (points, orientations). */
static PetscErrorCode FaceCorners(DM dm, PetscInt np, const PetscInt *cl, PetscInt corner[4])
{
  PetscInt vs, ve, es, ee, nv = 0, vidx[4], nb[2], nn = 0;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vs, &ve));
  PetscCall(DMPlexGetDepthStratum(dm, 1, &es, &ee));
  for (PetscInt k = 0; k < np; k++)
    if (cl[2 * k] >= vs && cl[2 * k] < ve) {
      PetscCheck(nv < 4, PETSC_COMM_SELF, PETSC_ERR_SUP, "Contact faces must be quadrilaterals (hexahedral meshes)");
      vidx[nv++] = k;
    }
  PetscCheck(nv == 4, PETSC_COMM_SELF, PETSC_ERR_SUP, "Contact faces must be quadrilaterals (hexahedral meshes)");
  /* the two vertices sharing an edge with vertex 0 */
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
  PetscFunctionReturn(0);
}

/* The reference position (s, t) in [-1, 1]^2 of every point of the face's closure: corners at (+-1, +-1),
   edges at their midpoints, the face itself at (0, 0). */
static PetscErrorCode ReferencePositions(DM dm, PetscInt np, const PetscInt *cl, const PetscInt corner[4], PetscReal ref[9][2])
{
  const PetscReal rc[4][2] = {
    {-1, -1},
    {1,  -1},
    {1,  1 },
    {-1, 1 }
  };
  PetscInt vs, ve, es, ee;

  PetscFunctionBeginUser;
  PetscCheck(np == 9, PETSC_COMM_SELF, PETSC_ERR_SUP, "Contact faces must be quadrilaterals");
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vs, &ve));
  PetscCall(DMPlexGetDepthStratum(dm, 1, &es, &ee));
  for (PetscInt k = 0; k < np; k++) ref[k][0] = ref[k][1] = 0.0;
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
  PetscFunctionReturn(0);
}

/* The area weights of the nodes of one quadrilateral face (bilinear geometry, 3 x 3 Gauss): the integral of
   each node's shape function over the face, so that a uniform pressure p gives the consistent nodal forces
   p w and sum w = the face's area. cl: the face's closure (points, orientations); order 1 (nodes at the
   vertices) or 2 (vertices, edge midpoints, the face centre: the tensor Q2 weights 1/36, 4/36, 16/36 on a
   parallelogram). w[k] is set for the closure's k-th point (0 for points without a node). */
static PetscErrorCode QuadNodeWeights(DM dm, PetscInt order, PetscInt np, const PetscInt *cl, PetscReal *w)
{
  PetscInt  corner[4] = {-1, -1, -1, -1};
  PetscReal X[4][3], ref[9][2], xi[3] = {-0.774596669241483377, 0.0, 0.774596669241483377}, gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

  PetscFunctionBeginUser;
  PetscCall(FaceCorners(dm, np, cl, corner));
  for (int c = 0; c < 4; c++) PetscCall(PointCoordinates(dm, cl[2 * corner[c]], X[c]));
  PetscCall(ReferencePositions(dm, np, cl, corner, ref));
  for (PetscInt k = 0; k < np; k++) w[k] = 0.0;
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

/* ---- nodes on labelled faces ---- */
typedef struct {
  PetscInt  dof;
  PetscReal x[3];
  PetscReal w; /* the node's share of the faces' area (JRFEFaceNodeAreas) */
} Node;

typedef struct {
  PetscInt n, cap;
  Node    *a;
} NodeList;

static int CompareNodeDof(const void *a, const void *b)
{
  const Node *p = (const Node *)a, *q = (const Node *)b;
  return (p->dof > q->dof) - (p->dof < q->dof);
}

static PetscErrorCode NodeListPush(NodeList *l, PetscInt dof, PetscReal w, Node **node)
{
  PetscFunctionBeginUser;
  if (l->n == l->cap) {
    Node *nn;
    l->cap = l->cap ? 2 * l->cap : 256;
    PetscCall(PetscMalloc1(l->cap, &nn));
    if (l->n) PetscCall(PetscArraycpy(nn, l->a, l->n));
    PetscCall(PetscFree(l->a));
    l->a = nn;
  }
  *node        = &l->a[l->n++];
  (*node)->dof = dof;
  (*node)->w   = w;
  PetscFunctionReturn(0);
}

/* Append the unconstrained nodes of one face (owned or not) to l, with their area weights if wantw */
static PetscErrorCode FaceAppendNodes(DM dm, PetscInt face, PetscBool wantw, NodeList *l)
{
  MPI_Comm     comm;
  PetscSection ls, gs;
  PetscInt     np, *cl = NULL;
  PetscReal    wf[9];

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMPlexGetTransitiveClosure(dm, face, PETSC_TRUE, &np, &cl));
  if (wantw) { /* the order from the DOFs of the face's own point: 3 (one node) for order 2, none for order 1 */
    PetscInt d0;
    PetscCheck(np == 9, comm, PETSC_ERR_SUP, "Node areas need quadrilateral faces (hexahedral meshes)");
    PetscCall(PetscSectionGetDof(ls, cl[0], &d0));
    PetscCheck(d0 == 0 || d0 == 3, comm, PETSC_ERR_SUP, "Node areas need elements of order 1 or 2 (-model_fe_order)");
    PetscCall(QuadNodeWeights(dm, d0 ? 2 : 1, np, cl, wf));
  }
  for (PetscInt k = 0; k < np; k++) {
    const PetscInt p = cl[2 * k];
    PetscInt       d, cd, off;
    Node          *node = NULL;
    PetscCall(PetscSectionGetDof(ls, p, &d));
    PetscCall(PetscSectionGetConstraintDof(ls, p, &cd));
    if (d != 3 || cd) continue;
    PetscCall(PetscSectionGetOffset(gs, p, &off));
    if (off < 0) off = -(off + 1);
    PetscCall(NodeListPush(l, off, wantw ? wf[k] : 0.0, &node));
    PetscCall(PointCoordinates(dm, p, node->x));
  }
  PetscCall(DMPlexRestoreTransitiveClosure(dm, face, PETSC_TRUE, &np, &cl));
  PetscFunctionReturn(0);
}

/* every rank's nodes, in rank order, on every rank: all (tot entries, free with PetscFree) */
static PetscErrorCode NodesAllGather(MPI_Comm comm, const NodeList *l, PetscInt *tot, Node **all)
{
  PetscMPIInt  size, *rc, *rd;
  PetscInt    *counts, *displs;
  MPI_Datatype nodetype;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc4(size, &counts, size, &displs, size, &rc, size, &rd));
  PetscCallMPI(MPI_Allgather(&l->n, 1, MPIU_INT, counts, 1, MPIU_INT, comm));
  *tot = 0;
  for (PetscMPIInt r = 0; r < size; r++) {
    displs[r] = *tot;
    rc[r]     = (PetscMPIInt)counts[r];
    rd[r]     = (PetscMPIInt)*tot;
    *tot += counts[r];
  }
  PetscCall(PetscMalloc1(PetscMax(*tot, 1), all));
  PetscCallMPI(MPI_Type_contiguous((PetscMPIInt)sizeof(Node), MPI_BYTE, &nodetype));
  PetscCallMPI(MPI_Type_commit(&nodetype));
  PetscCallMPI(MPI_Allgatherv(l->a, (PetscMPIInt)l->n, nodetype, *all, rc, rd, nodetype, comm));
  PetscCallMPI(MPI_Type_free(&nodetype));
  PetscCall(PetscFree4(counts, displs, rc, rd));
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
  MPI_Comm        comm;
  IS              is;
  PetscInt        nf = 0, cnt = 0, tot;
  const PetscInt *faces;
  NodeList        loc = {0, 0, NULL};
  Node           *all;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCall(DMGetStratumIS(dm, label, val, &is));
  if (is) PetscCall(ISGetLocalSize(is, &nf));
  if (nf) {
    PetscCall(ISGetIndices(is, &faces));
    for (PetscInt i = 0; i < nf; i++) PetscCall(FaceAppendNodes(dm, faces[i], wout ? PETSC_TRUE : PETSC_FALSE, &loc));
    PetscCall(ISRestoreIndices(is, &faces));
  }
  PetscCall(ISDestroy(&is));
  PetscCall(NodesAllGather(comm, &loc, &tot, &all));
  qsort(all, (size_t)tot, sizeof(Node), CompareNodeDof);
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
  PetscCall(PetscFree(loc.a));
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
