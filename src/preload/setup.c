/*
   JRPreload's system: the supports (3-2-1 or the clamped end), the stiffness Kp = K - sum_b ka_b g_b g_b^T + supports in
   a pattern that also holds the pair blocks, the penalty stiffness of every pair, the bolt loads, and the Jacobian
   K + sum_i k_i b_i b_i^T of a closed set, assembled for the solvers.
*/
#include <jointrom/private/preloadimpl.h>

typedef struct {
  PetscReal x[3];
  PetscInt  dof;
} Cand;

/* the node of all ranks that maximises score (ties: by coordinates, then DOF, so the choice does not depend
   on the partition); X: nodal coordinates (DOF layout) */
static PetscErrorCode PickNode(Vec X, PetscReal (*score)(const PetscReal[3], void *), void *ctx, Cand *best)
{
  const PetscScalar *x;
  PetscInt           n, rs;
  PetscReal          bs = PETSC_MIN_REAL;
  Cand               c  = {{0, 0, 0}, -1}, *all;
  PetscMPIInt        size;
  MPI_Comm           comm;
  MPI_Datatype       t;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)X, &comm));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetOwnershipRange(X, &rs, NULL));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt i = 0; i < n; i += 3) {
    const PetscReal xi[3] = {PetscRealPart(x[i]), PetscRealPart(x[i + 1]), PetscRealPart(x[i + 2])}, s = score(xi, ctx);
    if (s > bs) {
      bs = s;
      for (int d = 0; d < 3; d++) c.x[d] = xi[d];
      c.dof = rs + i;
    }
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(PetscMalloc1(size, &all));
  PetscCallMPI(MPI_Type_contiguous((PetscMPIInt)sizeof(Cand), MPI_BYTE, &t));
  PetscCallMPI(MPI_Type_commit(&t));
  PetscCallMPI(MPI_Allgather(&c, 1, t, all, 1, t, comm));
  PetscCallMPI(MPI_Type_free(&t));
  *best = all[0];
  for (PetscMPIInt r = 1; r < size; r++) {
    PetscReal s0, s1;
    if (all[r].dof < 0) continue;
    if (best->dof < 0) {
      *best = all[r];
      continue;
    }
    s0 = score(best->x, ctx);
    s1 = score(all[r].x, ctx);
    if (s1 > s0 || (s1 == s0 && (all[r].x[0] < best->x[0] || (all[r].x[0] == best->x[0] && (all[r].x[1] < best->x[1] || (all[r].x[1] == best->x[1] && all[r].x[2] < best->x[2])))))) *best = all[r];
  }
  PetscCall(PetscFree(all));
  PetscFunctionReturn(0);
}

typedef struct {
  PetscReal a[3], e[3];
} LineCtx;
static PetscReal ScoreFirst(const PetscReal x[3], void *ctx) /* lexicographically smallest (x, y, z) */
{
  (void)ctx;
  return -(x[0] * 1e6 + x[1] * 1e3 + x[2]);
}
static PetscReal ScoreFar(const PetscReal x[3], void *ctx) /* farthest from the point a */
{
  const LineCtx *l = (const LineCtx *)ctx;
  return PetscSqr(x[0] - l->a[0]) + PetscSqr(x[1] - l->a[1]) + PetscSqr(x[2] - l->a[2]);
}
static PetscReal ScoreLine(const PetscReal x[3], void *ctx) /* farthest from the line a + s e */
{
  const LineCtx  *l = (const LineCtx *)ctx;
  const PetscReal r[3] = {x[0] - l->a[0], x[1] - l->a[1], x[2] - l->a[2]}, s = r[0] * l->e[0] + r[1] * l->e[1] + r[2] * l->e[2];
  return PetscSqr(r[0] - s * l->e[0]) + PetscSqr(r[1] - s * l->e[1]) + PetscSqr(r[2] - s * l->e[2]);
}

/* 3-2-1: P1 held in x, y, z; P2 (farthest from P1) across P1P2; P3 (farthest from that line) normal to
   the plane P1 P2 P3: six independent constraints on the rigid motion, none redundant */
static PetscErrorCode MinimalSupports(JRPreload p)
{
  Vec       X;
  Cand      c1, c2, c3;
  LineCtx   l;
  PetscReal e1[3], e2[3], e3[3], len;
  const PetscReal ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};

  PetscFunctionBeginUser;
  PetscCall(JRModelGetCoordinates(p->model, &X));
  PetscCall(PickNode(X, ScoreFirst, NULL, &c1));
  for (int d = 0; d < 3; d++) l.a[d] = c1.x[d];
  PetscCall(PickNode(X, ScoreFar, &l, &c2));
  len = PetscSqrtReal(ScoreFar(c2.x, &l));
  PetscCheck(len > 0, p->comm, PETSC_ERR_ARG_WRONG, "The model has a single node");
  for (int d = 0; d < 3; d++) l.e[d] = e1[d] = (c2.x[d] - c1.x[d]) / len;
  PetscCall(PickNode(X, ScoreLine, &l, &c3));
  PetscCall(VecDestroy(&X));
  {
    const PetscReal r[3] = {c3.x[0] - c1.x[0], c3.x[1] - c1.x[1], c3.x[2] - c1.x[2]};
    e3[0] = e1[1] * r[2] - e1[2] * r[1];
    e3[1] = e1[2] * r[0] - e1[0] * r[2];
    e3[2] = e1[0] * r[1] - e1[1] * r[0];
    len   = PetscSqrtReal(e3[0] * e3[0] + e3[1] * e3[1] + e3[2] * e3[2]);
    PetscCheck(len > 0, p->comm, PETSC_ERR_ARG_WRONG, "The model's nodes are collinear");
    for (int d = 0; d < 3; d++) e3[d] /= len;
    e2[0] = e3[1] * e1[2] - e3[2] * e1[1];
    e2[1] = e3[2] * e1[0] - e3[0] * e1[2];
    e2[2] = e3[0] * e1[1] - e3[1] * e1[0];
  }
  PetscCall(JRPreloadAddSupport(p, c1.dof, ex));
  PetscCall(JRPreloadAddSupport(p, c1.dof, ey));
  PetscCall(JRPreloadAddSupport(p, c1.dof, ez));
  PetscCall(JRPreloadAddSupport(p, c2.dof, e2));
  PetscCall(JRPreloadAddSupport(p, c2.dof, e3));
  PetscCall(JRPreloadAddSupport(p, c3.dof, e3));
  PetscFunctionReturn(0);
}

/* Jp = Kp + sum_i (closed ? k_i : eps k_i) b_i b_i^T */
PetscErrorCode JRPreloadAssembleJacobian(JRPreload p, const JRPairs *P, Mat Jp)
{
  PetscInt rs, re;

  PetscFunctionBeginUser;
  PetscCall(MatCopy(p->Kp, Jp, SAME_NONZERO_PATTERN));
  PetscCall(MatGetOwnershipRange(Jp, &rs, &re));
  for (PetscInt i = 0; i < p->np; i++) {
    const PetscReal kk = p->closed[i] ? p->k[i] : p->eps * p->k[i];
    PetscInt        dof[6];
    PetscReal       b[6], v[6];
    for (int d = 0; d < 3; d++) {
      dof[d]     = P->dofA[3 * i + d];
      dof[3 + d] = P->dofB[3 * i + d];
      b[d]       = P->nrm[3 * i + d];
      b[3 + d]   = -P->nrm[3 * i + d];
    }
    for (int r = 0; r < 6; r++) {
      if (dof[r] < rs || dof[r] >= re) continue;
      for (int c = 0; c < 6; c++) v[c] = kk * b[r] * b[c];
      PetscCall(MatSetValues(Jp, 1, &dof[r], 6, dof, v, ADD_VALUES));
    }
    p->jclosed[i] = p->closed[i];
  }
  PetscCall(MatAssemblyBegin(Jp, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Jp, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* The pair DOFs gathered on every rank: sc scatters u to useq (6 per pair: A's x, y, z, then B's) */
static PetscErrorCode PairScatter(JRPreload p, const JRPairs *P)
{
  PetscInt *idx;
  IS        is;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(6 * p->np, &idx));
  for (PetscInt i = 0; i < p->np; i++)
    for (int d = 0; d < 3; d++) {
      idx[6 * i + d]     = P->dofA[3 * i + d];
      idx[6 * i + 3 + d] = P->dofB[3 * i + d];
    }
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, 6 * p->np, idx, PETSC_OWN_POINTER, &is));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 6 * p->np, &p->useq));
  PetscCall(VecScatterCreate(p->u, is, p->useq, NULL, &p->sc));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

/* The pairs' penalty stiffness k_i = kp area_i, kp default 10 x the structure's normal stiffness per area at surface A
   (from diagK, K's diagonal); the multipliers zero */
static PetscErrorCode Penalty(JRPreload p, const JRPairs *P, Vec diagK)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc5(p->np, &p->k, p->np, &p->lam, p->np, &p->w, p->np, &p->closed, p->np, &p->jclosed));
  if (!p->kp_set) {
    const PetscScalar *dg;
    PetscReal          s = 0.0, a = 0.0;
    PetscCall(VecScatterBegin(p->sc, diagK, p->useq, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(p->sc, diagK, p->useq, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(p->useq, &dg));
    for (PetscInt i = 0; i < p->np; i++) {
      for (int d = 0; d < 3; d++) s += PetscRealPart(dg[6 * i + d]) * PetscSqr(P->nrm[3 * i + d]);
      a += P->area[i];
    }
    PetscCall(VecRestoreArrayRead(p->useq, &dg));
    p->kp = 10.0 * s / a;
  }
  for (PetscInt i = 0; i < p->np; i++) {
    p->k[i]   = p->kp * P->area[i];
    p->lam[i] = 0.0;
  }
  PetscFunctionReturn(0);
}

/* -preload_support clamp: the DOFs of the end face x = 0 owned here (p->clamp), which must not touch the interface */
static PetscErrorCode ClampSupport(JRPreload p, const JRPairs *P, DM dm)
{
  PetscInt   n, *dof, rs0, re0, cnt = 0;
  PetscReal *x;

  PetscFunctionBeginUser;
  PetscCall(JRFEFaceNodes(dm, JR_LABEL_CLAMP, 1, &n, &x, &dof));
  PetscCheck(n > 0, p->comm, PETSC_ERR_ARG_WRONG, "-preload_support clamp: the model has no clamp face (the end x = 0; a Gmsh model needs the physical group 'clamp')");
  PetscCall(VecGetOwnershipRange(p->u, &rs0, &re0));
  for (PetscInt i = 0; i < n; i++) cnt += dof[i] >= rs0 && dof[i] < re0;
  PetscCall(PetscMalloc1(3 * cnt + 1, &p->clamp));
  for (PetscInt i = 0; i < n; i++)
    if (dof[i] >= rs0 && dof[i] < re0)
      for (int d = 0; d < 3; d++) p->clamp[p->nclamp++] = dof[i] + d;
  for (PetscInt i = 0; i < 3 * p->np; i++)
    for (PetscInt j = 0; j < n; j++) PetscCheck(P->dofA[i] / 3 != dof[j] / 3 && P->dofB[i] / 3 != dof[j] / 3, p->comm, PETSC_ERR_ARG_WRONG, "-preload_support clamp: the clamped face touches the contact interface");
  PetscCall(PetscFree2(x, dof));
  PetscFunctionReturn(0);
}

/* The blocks added to K: each bolt's axial stiffness taken out (-ka g g^T), each support's spring (k d d^T) */
static PetscErrorCode BoltSupportBlocks(JRPreload p, Mat K, const JRBolts *B, Mat *Bb)
{
  PetscInt   nb, *bn, **bdof;
  PetscReal **bval;

  PetscFunctionBeginUser;
  nb = B->n + p->nsup;
  PetscCall(PetscMalloc3(nb + 1, &bn, nb + 1, &bdof, nb + 1, &bval));
  for (PetscInt b = 0; b < B->n; b++) {
    const PetscInt n = B->off[b + 1] - B->off[b];
    bn[b]            = n;
    bdof[b]          = B->dof + B->off[b];
    PetscCall(PetscMalloc1(n * n, &bval[b]));
    for (PetscInt r = 0; r < n; r++)
      for (PetscInt c = 0; c < n; c++) bval[b][r * n + c] = -B->ka[b] * B->g[B->off[b] + r] * B->g[B->off[b] + c];
  }
  for (PetscInt s = 0; s < p->nsup; s++) {
    const PetscInt b = B->n + s;
    PetscInt      *d;
    bn[b] = 3;
    PetscCall(PetscMalloc1(3, &d));
    for (int c = 0; c < 3; c++) d[c] = p->supdof[s] + c;
    bdof[b] = d;
    PetscCall(PetscMalloc1(9, &bval[b]));
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) bval[b][3 * r + c] = p->diag * p->supdir[3 * s + r] * p->supdir[3 * s + c];
  }
  PetscCall(JRMatCreateFromBlocks(K, nb, bn, (const PetscInt *const *)bdof, (const PetscReal *const *)bval, Bb));
  for (PetscInt b = 0; b < nb; b++) {
    PetscCall(PetscFree(bval[b]));
    if (b >= B->n) PetscCall(PetscFree(bdof[b]));
  }
  PetscCall(PetscFree3(bn, bdof, bval));
  PetscFunctionReturn(0);
}

/* The pair blocks' pattern (values 1, added to Kp and taken away again so that only the pattern stays) */
static PetscErrorCode PairPattern(JRPreload p, Mat K, const JRPairs *P, Mat *Bp)
{
  PetscInt   *bn, **bdof;
  PetscReal **bval;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc3(p->np, &bn, p->np, &bdof, p->np, &bval));
  for (PetscInt i = 0; i < p->np; i++) {
    bn[i] = 6;
    PetscCall(PetscMalloc1(6, &bdof[i]));
    PetscCall(PetscMalloc1(36, &bval[i]));
    for (int d = 0; d < 3; d++) {
      bdof[i][d]     = P->dofA[3 * i + d];
      bdof[i][3 + d] = P->dofB[3 * i + d];
    }
    for (int c = 0; c < 36; c++) bval[i][c] = 1.0;
  }
  PetscCall(JRMatCreateFromBlocks(K, p->np, bn, (const PetscInt *const *)bdof, (const PetscReal *const *)bval, Bp));
  for (PetscInt i = 0; i < p->np; i++) PetscCall(PetscFree(bdof[i]));
  for (PetscInt i = 0; i < p->np; i++) PetscCall(PetscFree(bval[i]));
  PetscCall(PetscFree3(bn, bdof, bval));
  PetscFunctionReturn(0);
}

/* Kp = K - sum_b ka_b g_b g_b^T + supports, in a pattern that also holds the pair blocks, clamped rows and columns
   zeroed; J, the Jacobian's matrix, a copy (symmetric positive definite) */
static PetscErrorCode SystemMatrices(JRPreload p, Mat K, const JRPairs *P, const JRBolts *B)
{
  Mat Bb, Bp;

  PetscFunctionBeginUser;
  PetscCall(BoltSupportBlocks(p, K, B, &Bb));
  PetscCall(PairPattern(p, K, P, &Bp));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &p->Kp));
  PetscCall(MatAXPY(p->Kp, 1.0, Bb, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatAXPY(p->Kp, 1.0, Bp, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatAXPY(p->Kp, -1.0, Bp, SUBSET_NONZERO_PATTERN));
  PetscCall(MatDestroy(&Bb));
  PetscCall(MatDestroy(&Bp));
  if (p->support == JR_PRELOAD_SUPPORT_CLAMP) PetscCall(MatZeroRowsColumns(p->Kp, p->nclamp, p->clamp, p->diag, NULL, NULL)); /* collective */
  PetscCall(MatSetOption(p->Kp, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatDuplicate(p->Kp, MAT_COPY_VALUES, &p->J));
  PetscCall(MatSetOption(p->J, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(p->J, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  PetscCall(MatSetOption(p->J, MAT_SPD, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* The loads f: -P_b g_b per bolt b, plus the external force; zero on clamped rows */
static PetscErrorCode Loads(JRPreload p, const JRBolts *B)
{
  PetscScalar *fa;
  PetscInt     rs, re;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(p->f));
  PetscCall(VecGetOwnershipRange(p->f, &rs, &re));
  PetscCall(VecGetArray(p->f, &fa));
  for (PetscInt b = 0; b < B->n; b++) {
    const PetscReal F = p->nforce == 1 ? p->force[0] : p->force[b];
    for (PetscInt k = B->off[b]; k < B->off[b + 1]; k++)
      if (B->dof[k] >= rs && B->dof[k] < re) fa[B->dof[k] - rs] -= F * B->g[k];
  }
  for (PetscInt i = 0; i < p->nclamp; i++) fa[p->clamp[i] - rs] = 0.0;
  PetscCall(VecRestoreArray(p->f, &fa));
  if (p->fext) PetscCall(VecAXPY(p->f, 1.0, p->fext));
  PetscFunctionReturn(0);
}

/* The system: Kp, J, the loads f, the pair DOFs' scatter, the pairs' penalty stiffness, the supports (collective) */
PetscErrorCode JRPreloadSetUpSystem(JRPreload p)
{
  const JRPairs *P;
  const JRBolts *B;
  Mat            K;
  DM             dm;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetMatrices(p->model, &K, NULL, NULL));
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(JRModelGetBolts(p->model, &B));
  PetscCall(JRModelGetDM(p->model, &dm));
  PetscCheck(dm && P->n > 0, p->comm, PETSC_ERR_ARG_WRONG, "The preload needs an FE model with a contact interface (-model_type lap, brb, lap1, lap3 or gmsh)");
  PetscCheck(!p->model->tied, p->comm, PETSC_ERR_ARG_WRONG, "-model_interface tied: the preload needs the free interface (the contact decides what closes)");
  PetscCheck(p->nforce == 1 || p->nforce == B->n, p->comm, PETSC_ERR_ARG_SIZ, "-preload_force has %" PetscInt_FMT " values but the model has %" PetscInt_FMT " bolts: give one value for all or one per bolt", p->nforce, B->n);
  p->np = P->n;
  PetscCall(MatCreateVecs(K, &p->u, &p->f));
  { /* the mean diagonal of K: the scale of the support springs and of the clamp rows */
    PetscReal s;
    PetscInt  N;
    PetscCall(MatGetDiagonal(K, p->f));
    PetscCall(VecSum(p->f, &s));
    PetscCall(VecGetSize(p->f, &N));
    p->diag = PetscRealPart(s) / N;
  }
  PetscCall(PairScatter(p, P));
  PetscCall(Penalty(p, P, p->f)); /* f holds K's diagonal until the loads */
  if (p->support == JR_PRELOAD_SUPPORT_MINIMAL) PetscCall(MinimalSupports(p));
  if (p->support == JR_PRELOAD_SUPPORT_CLAMP) PetscCall(ClampSupport(p, P, dm));
  PetscCall(SystemMatrices(p, K, P, B));
  PetscCall(Loads(p, B));
  PetscFunctionReturn(0);
}
