/*
   JRPreload: the bolt preload, a nonlinear static contact analysis of the FE assembly (thesis 4.2, 5.1),
   giving every interface node pair's normal load N_static and gap v_gap, and n0 = N_static - kv v_gap (5.1).

   Bolts: each shank carries the pretension P (-preload_force, N) whatever its elongation, as a bolt load
   applied "by force" in Abaqus: the shank's axial stiffness is taken out of K and the structure is loaded
   by -P g (g: the shank's elongation over the footprint DOFs, JRBolts). The bending, shear and torsion of
   the shank stay. Later analyses use the whole K: the bolt held at its preloaded length.

   Contact: frictionless and unilateral between the facing nodes of each pair, the penetration
   w = (uA - uB) . n - gap0 resisted by a penalty spring k_i = kp area_i (kp in N/m^3: pressure per
   penetration, area_i the node's share of the surface, so that a uniform pressure is carried exactly).
   -preload_method augmented (default) adds augmented-Lagrangian (Uzawa) updates of the pair forces,
   lambda_i <- max(0, lambda_i + k_i w_i), until no force changes by more than -preload_rtol of the largest:
   the penetration then vanishes and the result does not depend on kp; -preload_method penalty stops after
   the first solve (the result converges to the exact one as kp grows; tests/test_preload.c shows it).
   An open pair keeps -preload_open_stiffness x k_i (1e-8: a force below 1e-8 of a closed pair's) so that
   K stays regular when a part is held by contact alone (the axial bolt stiffness is out).

   Each solve is a semi-smooth Newton method (SNES, prefix preload_): the Jacobian K + sum_closed k_i b_i b_i^T
   depends only on which pairs are closed, so it is refactored (sparse LDL^T, MUMPS) only when that set
   changes. Supports (-preload_support): minimal (default: 3-2-1 springs at three far-apart nodes,
   statically determinate, so the self-equilibrated bolt loads leave them unloaded), clamp (the end face x = 0
   fixed, "fix-free" as in the thesis), none (JRPreloadAddSupport only). Units SI.
*/
#include <jointrom/private/feimpl.h>
#include <petscviewerhdf5.h>

const char *const JRPreloadMethods[]  = {"penalty", "augmented", "JRPreloadMethod", "JR_PRELOAD_", NULL};
const char *const JRPreloadSupports[] = {"minimal", "clamp", "none", "JRPreloadSupport", "JR_PRELOAD_SUPPORT_", NULL};

#define JR_PRELOAD_MAXBOLTS 256

struct _p_JRPreload {
  MPI_Comm          comm;
  JRModel           model;
  /* options */
  PetscInt          nforce;
  PetscReal         force[JR_PRELOAD_MAXBOLTS];
  JRPreloadMethod   method;
  JRPreloadSupport  support;
  PetscReal         kp, eps, rtol, kv, open_gap;
  PetscBool         kp_set, kv_set, open_start;
  PetscInt          maxit;
  char              load[PETSC_MAX_PATH_LEN];
  PetscReal         load_tol;
  Vec               fext;
  /* supports: nodes (first global DOF), directions, added to the automatic ones */
  PetscInt          nsup, supcap;
  PetscInt         *supdof;
  PetscReal        *supdir;
  /* the solve */
  SNES              snes;
  Mat               Kp, J;
  Vec               u, f, useq;
  VecScatter        sc;
  PetscInt          np;         /* pairs */
  PetscReal        *k, *lam, *w; /* per pair: penalty stiffness [N/m], multiplier [N], penetration [m] */
  PetscInt         *closed, *jclosed, nclamp, *clamp;
  PetscReal         diag;
  PetscBool         jvalid;
  /* condensed solver: K0 = Kp + sum_i k_i b_i b_i^T factored once, G = B^T K0^-1 B, yf = B^T K0^-1 f (every rank) */
  PetscBool         condensed;
  KSP               ksp0;
  PetscReal        *G, *yf;
  SNES              csnes;
  Mat               cJ;
  Vec               cw;
  /* results (every rank) */
  PetscReal        *N, *gap;
  PetscInt          newton, outer, factorisations;
  PetscReal         time, maxpen;
  PetscBool         solved, loaded;
};

PetscErrorCode JRPreloadCreate(MPI_Comm comm, JRPreload *pre)
{
  JRPreload p;

  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(PetscNew(&p));
  p->comm     = comm;
  p->nforce   = 1;
  p->force[0] = 11500.0;
  p->method   = JR_PRELOAD_AUGMENTED;
  p->support  = JR_PRELOAD_SUPPORT_MINIMAL;
  p->eps      = 1e-8;
  p->rtol     = 1e-6;
  p->maxit    = 100;
  p->open_gap = 1e-5;
  p->load_tol = 1e-6;
  p->condensed = PETSC_TRUE;
  *pre        = p;
  PetscFunctionReturn(0);
}

/* The FE model (borrowed: keep it until JRPreloadDestroy()); its interface must be free */
PetscErrorCode JRPreloadSetModel(JRPreload p, JRModel m)
{
  PetscFunctionBeginUser;
  p->model = m;
  PetscFunctionReturn(0);
}

/* Pretension [N]: one value for every bolt (n = 1) or one per bolt */
PetscErrorCode JRPreloadSetForces(JRPreload p, PetscInt n, const PetscReal F[])
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 1 && n <= JR_PRELOAD_MAXBOLTS, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_force: %" PetscInt_FMT " values; give 1 (every bolt) to %d", n, JR_PRELOAD_MAXBOLTS);
  for (PetscInt i = 0; i < n; i++) PetscCheck(F[i] >= 0 && PetscIsNormalReal(F[i] + 1.0), p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_force: value %" PetscInt_FMT " is %g N; a pretension is a tension, zero or positive", i + 1, (double)F[i]);
  p->nforce = n;
  PetscCall(PetscArraycpy(p->force, F, n));
  PetscFunctionReturn(0);
}

/* An external load besides the bolts (a vector of the model's DOFs; a reference is kept) */
PetscErrorCode JRPreloadSetExternalForce(JRPreload p, Vec f)
{
  PetscFunctionBeginUser;
  PetscCall(PetscObjectReference((PetscObject)f));
  PetscCall(VecDestroy(&p->fext));
  p->fext = f;
  PetscFunctionReturn(0);
}

/* A support: the node whose x DOF is dof0 held along the unit direction dir (a stiff spring to ground) */
PetscErrorCode JRPreloadAddSupport(JRPreload p, PetscInt dof0, const PetscReal dir[3])
{
  const PetscReal len = PetscSqrtReal(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);

  PetscFunctionBeginUser;
  PetscCheck(len > 0, p->comm, PETSC_ERR_ARG_WRONG, "Support direction is zero");
  if (p->nsup == p->supcap) {
    PetscInt  *d;
    PetscReal *r;
    p->supcap = p->supcap ? 2 * p->supcap : 16;
    PetscCall(PetscMalloc2(p->supcap, &d, 3 * p->supcap, &r));
    if (p->nsup) {
      PetscCall(PetscArraycpy(d, p->supdof, p->nsup));
      PetscCall(PetscArraycpy(r, p->supdir, 3 * p->nsup));
    }
    PetscCall(PetscFree2(p->supdof, p->supdir));
    p->supdof = d;
    p->supdir = r;
  }
  p->supdof[p->nsup] = dof0;
  for (int d = 0; d < 3; d++) p->supdir[3 * p->nsup + d] = dir[d] / len;
  p->nsup++;
  PetscFunctionReturn(0);
}

PetscErrorCode JRPreloadSetFromOptions(JRPreload p)
{
  PetscInt  m = JR_PRELOAD_MAXBOLTS, meth = p->method, sup = p->support;
  PetscReal F[JR_PRELOAD_MAXBOLTS];
  PetscBool set;

  PetscFunctionBeginUser;
  PetscOptionsBegin(p->comm, "preload_", "Bolt preload: static contact analysis (prefix preload_)", "JRPreload");
  PetscCall(PetscOptionsRealArray("-force", "Bolt pretension [N]: one value for all bolts, or one per bolt (comma-separated)", "JRPreloadSetForces", F, &m, &set));
  if (set) PetscCall(JRPreloadSetForces(p, m, F));
  PetscCall(PetscOptionsEList("-method", "Contact enforcement: penalty (penetration ~ pressure / kp) or augmented (Lagrangian updates until the penetration vanishes)", "JRPreloadSolve", JRPreloadMethods, 2, JRPreloadMethods[meth], &meth, NULL));
  p->method = (JRPreloadMethod)meth;
  PetscCall(PetscOptionsReal("-penalty", "Contact penalty kp [N/m^3] (pressure per penetration; default 10 x the structure's normal stiffness per area at the interface)", "JRPreloadSolve", p->kp, &p->kp, &p->kp_set));
  PetscCall(PetscOptionsReal("-rtol", "Augmented Lagrangian: stop when no pair force changes by more than rtol x the largest", "JRPreloadSolve", p->rtol, &p->rtol, NULL));
  PetscCall(PetscOptionsInt("-max_it", "Augmented Lagrangian: most updates", "JRPreloadSolve", p->maxit, &p->maxit, NULL));
  PetscCall(PetscOptionsReal("-open_stiffness", "Stiffness of an open pair, relative to a closed one", "JRPreloadSolve", p->eps, &p->eps, NULL));
  {
    const char *solvers[] = {"condensed", "full"};
    PetscInt    sv        = p->condensed ? 0 : 1;
    PetscCall(PetscOptionsEList("-solver", "condensed (one factorisation of K, Newton on the interface's dense flexibility) or full (Newton on all DOFs, a factorisation per change of the closed set)", "JRPreloadSolve", solvers, 2, solvers[sv], &sv, NULL));
    p->condensed = sv == 0 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(PetscOptionsEList("-support", "Supports: minimal (3-2-1, statically determinate), clamp (end x = 0 fixed, as in the thesis), none", "JRPreloadSolve", JRPreloadSupports, 3, JRPreloadSupports[sup], &sup, NULL));
  p->support = (JRPreloadSupport)sup;
  PetscCall(PetscOptionsBool("-open_start", "Start Newton from every pair open (by -preload_open_gap) instead of closed", "JRPreloadSolve", p->open_start, &p->open_start, NULL));
  PetscCall(PetscOptionsReal("-open_gap", "Opening of the pairs at an open start [m]", "JRPreloadSolve", p->open_gap, &p->open_gap, NULL));
  PetscCall(PetscOptionsReal("-kv", "Normal contact stiffness kv [N/m] for n0 = N_static - kv v_gap (5.1)", "JRPreloadGetN0", p->kv, &p->kv, &p->kv_set));
  PetscCall(PetscOptionsString("-load", "Read N_static and v_gap per pair from a file (CSV: x_m,y_m,z_m,N_static_N,v_gap_m; or this program's HDF5) instead of solving", "JRPreloadSolve", p->load, p->load, sizeof(p->load), NULL));
  PetscCall(PetscOptionsReal("-load_tol", "Distance within which a row of the -preload_load file matches a pair [m]", "JRPreloadSolve", p->load_tol, &p->load_tol, NULL));
  PetscOptionsEnd();
  PetscCheck(p->rtol > 0 && p->rtol < 1, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_rtol %g: in (0, 1)", (double)p->rtol);
  PetscCheck(p->maxit >= 1, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_max_it %" PetscInt_FMT ": at least 1", p->maxit);
  PetscCheck(p->eps > 0 && p->eps < 1, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_open_stiffness %g: in (0, 1)", (double)p->eps);
  PetscCheck(!p->kp_set || (p->kp > 0 && PetscIsNormalReal(p->kp)), p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_penalty %g: a positive stiffness per area [N/m^3]", (double)p->kp);
  PetscCheck(!p->kv_set || (p->kv >= 0 && PetscIsNormalReal(p->kv + 1.0)), p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_kv %g: zero or a positive stiffness [N/m]", (double)p->kv);
  PetscCheck(p->open_gap > 0 && PetscIsNormalReal(p->open_gap), p->comm, PETSC_ERR_ARG_OUTOFRANGE, "-preload_open_gap %g: a positive distance [m]", (double)p->open_gap);
  PetscFunctionReturn(0);
}

/* ---- set-up ---- */
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

/* ---- SNES callbacks ---- */
/* w_i (penetration) and the contact force c_i of every pair from the gathered pair DOFs */
static PetscErrorCode PairState(JRPreload p, const JRPairs *P, Vec u)
{
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(p->sc, u, p->useq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(p->sc, u, p->useq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(p->useq, &a));
  for (PetscInt i = 0; i < p->np; i++) {
    PetscReal v = 0.0;
    for (int d = 0; d < 3; d++) v += (PetscRealPart(a[6 * i + d]) - PetscRealPart(a[6 * i + 3 + d])) * P->nrm[3 * i + d];
    p->w[i]      = v - P->gap0[i];
    p->closed[i] = p->lam[i] + p->k[i] * p->w[i] >= 0.0; /* touching counts as closed: Newton starts from the closed state */
  }
  PetscCall(VecRestoreArrayRead(p->useq, &a));
  PetscFunctionReturn(0);
}

static inline PetscReal PairForce(JRPreload p, PetscInt i) /* the force pressing pair i together [N] */
{
  const PetscReal t = p->lam[i] + p->k[i] * p->w[i];
  return t > 0 ? t : p->eps * t;
}

static PetscErrorCode FormFunction(SNES snes, Vec u, Vec r, void *ctx)
{
  JRPreload       p = (JRPreload)ctx;
  const JRPairs  *P;
  PetscScalar    *ra;
  const PetscScalar *ua;
  PetscInt        rs, re;

  PetscFunctionBeginUser;
  (void)snes;
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(MatMult(p->Kp, u, r));
  PetscCall(VecAXPY(r, -1.0, p->f));
  PetscCall(PairState(p, P, u));
  PetscCall(VecGetOwnershipRange(r, &rs, &re));
  PetscCall(VecGetArray(r, &ra));
  for (PetscInt i = 0; i < p->np; i++) {
    const PetscReal c = PairForce(p, i);
    for (int d = 0; d < 3; d++) {
      const PetscInt a = P->dofA[3 * i + d], b = P->dofB[3 * i + d];
      if (a >= rs && a < re) ra[a - rs] += c * P->nrm[3 * i + d];
      if (b >= rs && b < re) ra[b - rs] -= c * P->nrm[3 * i + d];
    }
  }
  PetscCall(VecGetArrayRead(u, &ua));
  for (PetscInt i = 0; i < p->nclamp; i++) ra[p->clamp[i] - rs] = p->diag * ua[p->clamp[i] - rs];
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(VecRestoreArray(r, &ra));
  PetscFunctionReturn(0);
}

/* J = Kp + sum_i k_i (closed) or eps k_i (open) b_i b_i^T; left untouched (no new factorisation) when the
   set of closed pairs is the one of the last assembly */
static PetscErrorCode AssembleJacobian(JRPreload, const JRPairs *, Mat);

static PetscErrorCode FormJacobian(SNES snes, Vec u, Mat J, Mat Jp, void *ctx)
{
  JRPreload      p = (JRPreload)ctx;
  const JRPairs *P;
  PetscInt       same = 1;

  PetscFunctionBeginUser;
  (void)snes;
  (void)J;
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(PairState(p, P, u));
  if (p->jvalid)
    for (PetscInt i = 0; i < p->np && same; i++) same = p->closed[i] == p->jclosed[i];
  if (p->jvalid && same) PetscFunctionReturn(0);
  PetscCall(AssembleJacobian(p, P, Jp));
  p->jvalid = PETSC_TRUE;
  p->factorisations++;
  PetscFunctionReturn(0);
}

/* Jp = Kp + sum_i (closed ? k_i : eps k_i) b_i b_i^T */
static PetscErrorCode AssembleJacobian(JRPreload p, const JRPairs *P, Mat Jp)
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

static PetscErrorCode ClearResults(JRPreload p)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree2(p->N, p->gap));
  p->solved = p->loaded = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Kp = K - sum_b ka_b g_b g_b^T + supports, in a pattern that also holds the pair blocks; the loads */
static PetscErrorCode SetUpSystem(JRPreload p)
{
  const JRPairs *P;
  const JRBolts *B;
  Mat            K, Bb, Bp;
  PetscInt       nb, *bn, **bdof, nbolt;
  PetscReal    **bval;
  DM             dm;
  PetscScalar   *fa;
  PetscInt       rs, re;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetMatrices(p->model, &K, NULL, NULL));
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(JRModelGetBolts(p->model, &B));
  PetscCall(JRModelGetDM(p->model, &dm));
  PetscCheck(dm && P->n > 0, p->comm, PETSC_ERR_ARG_WRONG, "The preload needs an FE model with a contact interface (-model_type lap, brb, lap1, lap3 or gmsh)");
  PetscCheck(!p->model->tied, p->comm, PETSC_ERR_ARG_WRONG, "-model_interface tied: the preload needs the free interface (the contact decides what closes)");
  nbolt = B->n;
  PetscCheck(p->nforce == 1 || p->nforce == nbolt, p->comm, PETSC_ERR_ARG_SIZ, "-preload_force has %" PetscInt_FMT " values but the model has %" PetscInt_FMT " bolts: give one value for all or one per bolt", p->nforce, nbolt);
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
  /* the pair DOFs gathered on every rank */
  {
    PetscInt *idx;
    IS        is;
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
  }
  PetscCall(PetscMalloc5(p->np, &p->k, p->np, &p->lam, p->np, &p->w, p->np, &p->closed, p->np, &p->jclosed));
  /* the penalty: kp per area, default 10 x the structure's normal stiffness per area at surface A */
  if (!p->kp_set) {
    const PetscScalar *dg;
    PetscReal          s = 0.0, a = 0.0;
    PetscCall(VecScatterBegin(p->sc, p->f, p->useq, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(p->sc, p->f, p->useq, INSERT_VALUES, SCATTER_FORWARD));
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
  /* supports */
  if (p->support == JR_PRELOAD_SUPPORT_MINIMAL) PetscCall(MinimalSupports(p));
  if (p->support == JR_PRELOAD_SUPPORT_CLAMP) {
    PetscInt   n, *dof, rs0, re0, cnt = 0;
    PetscReal *x;
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
  }
  /* blocks: bolts (-ka g g^T), supports (k d d^T) */
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
  PetscCall(JRMatCreateFromBlocks(K, nb, bn, (const PetscInt *const *)bdof, (const PetscReal *const *)bval, &Bb));
  for (PetscInt b = 0; b < nb; b++) {
    PetscCall(PetscFree(bval[b]));
    if (b >= B->n) PetscCall(PetscFree(bdof[b]));
  }
  PetscCall(PetscFree3(bn, bdof, bval));
  /* the pair blocks' pattern (values 1, added and taken away again so that only the pattern stays) */
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
  PetscCall(JRMatCreateFromBlocks(K, p->np, bn, (const PetscInt *const *)bdof, (const PetscReal *const *)bval, &Bp));
  for (PetscInt i = 0; i < p->np; i++) PetscCall(PetscFree(bdof[i]));
  for (PetscInt i = 0; i < p->np; i++) PetscCall(PetscFree(bval[i]));
  PetscCall(PetscFree3(bn, bdof, bval));
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
  /* loads: -P_b g_b, plus the external force; zero on clamped rows */
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
  /* SNES: Newton with sparse LDL^T (MUMPS when present) */
  {
    KSP ksp;
    PC  pc;
    PetscCall(SNESCreate(p->comm, &p->snes));
    PetscCall(SNESSetOptionsPrefix(p->snes, "preload_"));
    PetscCall(SNESSetFunction(p->snes, NULL, FormFunction, p));
    PetscCall(SNESSetJacobian(p->snes, p->J, p->J, FormJacobian, p));
    PetscCall(SNESSetTolerances(p->snes, PETSC_DEFAULT, 1e-10, PETSC_DEFAULT, 50, PETSC_DEFAULT));
    PetscCall(SNESSetDivergenceTolerance(p->snes, -1.0)); /* from an open start the first step overshoots by far */
    { /* full Newton steps: on this piecewise-linear system they are active-set steps (11 iterations instead of 24
         with backtracking on the 67k-DOF lap of tests/test_preload.c at h = 2.5 mm) */
      SNESLineSearch ls;
      PetscCall(SNESGetLineSearch(p->snes, &ls));
      PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
    }
    PetscCall(SNESGetKSP(p->snes, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, PCCHOLESKY));
#if defined(PETSC_HAVE_MUMPS)
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
#endif
    PetscCall(SNESSetFromOptions(p->snes));
  }
  PetscFunctionReturn(0);
}

/* ---- the condensed solver ----
   With K0 = Kp + sum_i k_i b_i b_i^T (every pair closed; regular) and s_i(w) = c_i(w) - k_i (w_i + gap0_i), the
   equilibrium Kp u + B c(w) = f is K0 u = f - B s(w), so the penetrations solve the interface equations
     F(w) = w + gap0 - yf + G s(w) = 0,   G = B^T K0^-1 B (n x n, the interface flexibility),  yf = B^T K0^-1 f,
   with the Jacobian I + G diag(c_i' - k_i) (columns of closed pairs are unit vectors). One sparse factorisation
   of K0 and n solves (blocks of right-hand sides) give G; the Newton iterations are dense and cheap. */
static PetscErrorCode PairValues(JRPreload p, const JRPairs *P, Vec x, PetscReal *y)
{
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(p->sc, x, p->useq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(p->sc, x, p->useq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(p->useq, &a));
  for (PetscInt i = 0; i < p->np; i++) {
    y[i] = 0.0;
    for (int d = 0; d < 3; d++) y[i] += (PetscRealPart(a[6 * i + d]) - PetscRealPart(a[6 * i + 3 + d])) * P->nrm[3 * i + d];
  }
  PetscCall(VecRestoreArrayRead(p->useq, &a));
  PetscFunctionReturn(0);
}

/* r = sum_i s_i b_i (rows owned here) */
static PetscErrorCode PairLoads(JRPreload p, const JRPairs *P, const PetscReal *sv, Vec r)
{
  PetscScalar *ra;
  PetscInt     rs, re;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(r));
  PetscCall(VecGetOwnershipRange(r, &rs, &re));
  PetscCall(VecGetArray(r, &ra));
  for (PetscInt i = 0; i < p->np; i++)
    for (int d = 0; d < 3; d++) {
      const PetscInt a = P->dofA[3 * i + d], b = P->dofB[3 * i + d];
      if (a >= rs && a < re) ra[a - rs] += sv[i] * P->nrm[3 * i + d];
      if (b >= rs && b < re) ra[b - rs] -= sv[i] * P->nrm[3 * i + d];
    }
  PetscCall(VecRestoreArray(r, &ra));
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedState(JRPreload p, const JRPairs *P, Vec w)
{
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(w, &a));
  for (PetscInt i = 0; i < p->np; i++) {
    p->w[i]      = PetscRealPart(a[i]);
    p->closed[i] = p->lam[i] + p->k[i] * p->w[i] >= 0.0;
  }
  PetscCall(VecRestoreArrayRead(w, &a));
  (void)P;
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedFunction(SNES snes, Vec w, Vec F, void *ctx)
{
  JRPreload      p = (JRPreload)ctx;
  const JRPairs *P;
  PetscScalar   *fa;
  PetscReal     *sv;
  const PetscInt n = p->np;

  PetscFunctionBeginUser;
  (void)snes;
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(CondensedState(p, P, w));
  PetscCall(PetscMalloc1(n, &sv));
  for (PetscInt j = 0; j < n; j++) sv[j] = PairForce(p, j) - p->k[j] * (p->w[j] + P->gap0[j]);
  PetscCall(VecGetArray(F, &fa));
  for (PetscInt i = 0; i < n; i++) fa[i] = p->w[i] + P->gap0[i] - p->yf[i];
  for (PetscInt j = 0; j < n; j++) /* G is symmetric: column j = row j, contiguous */
    for (PetscInt i = 0; i < n; i++) fa[i] += p->G[(size_t)j * n + i] * sv[j];
  PetscCall(VecRestoreArray(F, &fa));
  PetscCall(PetscFree(sv));
  PetscFunctionReturn(0);
}

static PetscErrorCode CondensedJacobian(SNES snes, Vec w, Mat J, Mat Jp, void *ctx)
{
  JRPreload      p = (JRPreload)ctx;
  const JRPairs *P;
  PetscScalar   *ja;
  PetscInt       same = 1;
  const PetscInt n = p->np;

  PetscFunctionBeginUser;
  (void)snes;
  (void)J;
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(CondensedState(p, P, w));
  if (p->jvalid)
    for (PetscInt i = 0; i < n && same; i++) same = p->closed[i] == p->jclosed[i];
  if (p->jvalid && same) PetscFunctionReturn(0); /* the same closed set: the same matrix, no new LU */
  PetscCall(MatDenseGetArray(Jp, &ja));
  for (PetscInt j = 0; j < n; j++) {
    const PetscReal f = (p->closed[j] ? 1.0 : p->eps) * p->k[j] - p->k[j];
    for (PetscInt i = 0; i < n; i++) ja[(size_t)j * n + i] = (i == j ? 1.0 : 0.0) + p->G[(size_t)j * n + i] * f;
    p->jclosed[j] = p->closed[j];
  }
  PetscCall(MatDenseRestoreArray(Jp, &ja));
  PetscCall(MatAssemblyBegin(Jp, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Jp, MAT_FINAL_ASSEMBLY));
  p->jvalid = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* factor K0, compute G and yf (on every rank), create the dense SNES (PETSC_COMM_SELF: every rank solves the same
   small system with the same data, so the ranks agree exactly) */
static PetscErrorCode CondensedSetUp(JRPreload p, const JRPairs *P)
{
  const PetscInt n = p->np, chunk = 64;
  PC             pc;
  Vec            x;
  PetscInt       nloc, N;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) p->closed[i] = 1;
  PetscCall(AssembleJacobian(p, P, p->J));
  PetscCall(KSPCreate(p->comm, &p->ksp0));
  PetscCall(KSPSetOptionsPrefix(p->ksp0, "preload_"));
  PetscCall(KSPSetOperators(p->ksp0, p->J, p->J));
  PetscCall(KSPSetType(p->ksp0, KSPPREONLY));
  PetscCall(KSPGetPC(p->ksp0, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
#if defined(PETSC_HAVE_MUMPS)
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
#endif
  PetscCall(KSPSetFromOptions(p->ksp0));
  PetscCall(KSPSetUp(p->ksp0));
  p->factorisations++;
  PetscCall(PetscMalloc2((size_t)n * n, &p->G, n, &p->yf));
  PetscCall(VecDuplicate(p->u, &x));
  PetscCall(KSPSolve(p->ksp0, p->f, x));
  PetscCall(PairValues(p, P, x, p->yf));
  PetscCall(VecDestroy(&x));
  PetscCall(VecGetLocalSize(p->u, &nloc));
  PetscCall(VecGetSize(p->u, &N));
  for (PetscInt j0 = 0; j0 < n; j0 += chunk) {
    const PetscInt m = PetscMin(chunk, n - j0);
    Mat            R, X;
    PetscScalar   *ra;
    PetscInt       rs, re;
    PetscCall(MatCreateDense(p->comm, nloc, PETSC_DECIDE, N, m, NULL, &R));
    PetscCall(MatCreateDense(p->comm, nloc, PETSC_DECIDE, N, m, NULL, &X));
    PetscCall(MatGetOwnershipRange(R, &rs, &re));
    PetscCall(MatDenseGetArray(R, &ra)); /* local rows, column-major with leading dimension nloc */
    for (PetscInt c = 0; c < m; c++) {
      const PetscInt j = j0 + c;
      for (int d = 0; d < 3; d++) {
        const PetscInt a = P->dofA[3 * j + d], b = P->dofB[3 * j + d];
        if (a >= rs && a < re) ra[(size_t)c * nloc + a - rs] += P->nrm[3 * j + d];
        if (b >= rs && b < re) ra[(size_t)c * nloc + b - rs] -= P->nrm[3 * j + d];
      }
    }
    PetscCall(MatDenseRestoreArray(R, &ra));
    PetscCall(KSPMatSolve(p->ksp0, R, X));
    for (PetscInt c = 0; c < m; c++) {
      Vec col;
      PetscCall(MatDenseGetColumnVecRead(X, c, &col));
      PetscCall(PairValues(p, P, col, p->G + (size_t)(j0 + c) * n));
      PetscCall(MatDenseRestoreColumnVecRead(X, c, &col));
    }
    PetscCall(MatDestroy(&R));
    PetscCall(MatDestroy(&X));
  }
  for (PetscInt j = 0; j < n; j++) /* symmetrise (round-off) */
    for (PetscInt i = 0; i < j; i++) p->G[(size_t)j * n + i] = p->G[(size_t)i * n + j] = 0.5 * (p->G[(size_t)j * n + i] + p->G[(size_t)i * n + j]);
  {
    KSP ksp;
    PC  cpc;
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, &p->cJ));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &p->cw));
    PetscCall(SNESCreate(PETSC_COMM_SELF, &p->csnes));
    PetscCall(SNESSetOptionsPrefix(p->csnes, "preload_"));
    PetscCall(SNESSetFunction(p->csnes, NULL, CondensedFunction, p));
    PetscCall(SNESSetJacobian(p->csnes, p->cJ, p->cJ, CondensedJacobian, p));
    PetscCall(SNESSetTolerances(p->csnes, PETSC_DEFAULT, 1e-12, PETSC_DEFAULT, 100, PETSC_DEFAULT));
    PetscCall(SNESSetDivergenceTolerance(p->csnes, -1.0));
    {
      SNESLineSearch ls;
      PetscCall(SNESGetLineSearch(p->csnes, &ls));
      PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
    }
    PetscCall(SNESGetKSP(p->csnes, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &cpc));
    PetscCall(PCSetType(cpc, PCLU));
    PetscCall(PCFactorSetMatSolverType(cpc, MATSOLVERPETSC));
    PetscCall(SNESSetFromOptions(p->csnes));
  }
  PetscFunctionReturn(0);
}

/* the displacement of the condensed solution: K0 u = f - B s(w) */
static PetscErrorCode CondensedDisplacement(JRPreload p, const JRPairs *P)
{
  PetscReal *sv;
  Vec        r;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(p->np, &sv));
  for (PetscInt j = 0; j < p->np; j++) sv[j] = PairForce(p, j) - p->k[j] * (p->w[j] + P->gap0[j]);
  PetscCall(VecDuplicate(p->f, &r));
  PetscCall(PairLoads(p, P, sv, r));
  PetscCall(VecAYPX(r, -1.0, p->f));
  PetscCall(KSPSolve(p->ksp0, r, p->u));
  PetscCall(VecDestroy(&r));
  PetscCall(PetscFree(sv));
  PetscFunctionReturn(0);
}

/* ---- import ---- */
typedef struct {
  PetscReal x;
  PetscInt  i;
} XKey;
static int CompareXKey(const void *a, const void *b)
{
  const XKey *p = (const XKey *)a, *q = (const XKey *)b;
  return (p->x > q->x) - (p->x < q->x);
}

/* N_static and v_gap per pair from a file: every row matched to the pair within load_tol, each pair once */
static PetscErrorCode LoadResults(JRPreload p)
{
  const JRPairs *P;
  PetscInt       n = 0, *used;
  PetscReal     *x, *N, *g;
  const char    *ext = strrchr(p->load, '.');
  XKey          *key;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCheck(P->n > 0, p->comm, PETSC_ERR_ARG_WRONG, "-preload_load %s: the model has no contact interface", p->load);
  if (ext && !strcmp(ext, ".h5")) {
    PetscViewer v;
    Vec         vx, vN, vg, s;
    VecScatter  sc;
    const char *names[3] = {"x_m", "N_static_N", "v_gap_m"};
    Vec        *vv[3]    = {&vx, &vN, &vg};
    PetscBool   has;
    PetscCall(PetscTestFile(p->load, 'r', &has));
    PetscCheck(has, p->comm, PETSC_ERR_FILE_OPEN, "-preload_load %s: cannot read the file", p->load);
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
  } else {
    JRTable t;
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
  }
  PetscCheck(n == P->n, p->comm, PETSC_ERR_ARG_SIZ, "-preload_load %s: %" PetscInt_FMT " rows, but the model's interface has %" PetscInt_FMT " pairs", p->load, n, P->n);
  for (PetscInt r = 0; r < n; r++) {
    PetscCheck(N[r] >= 0 && PetscIsNormalReal(N[r] + 1.0), p->comm, PETSC_ERR_FILE_UNEXPECTED, "-preload_load %s: row %" PetscInt_FMT " has N_static = %g N; it must be >= 0", p->load, r + 1, (double)N[r]);
    PetscCheck(g[r] >= 0 && PetscIsNormalReal(g[r] + 1.0), p->comm, PETSC_ERR_FILE_UNEXPECTED, "-preload_load %s: row %" PetscInt_FMT " has v_gap = %g m; it must be >= 0", p->load, r + 1, (double)g[r]);
  }
  PetscCall(ClearResults(p));
  p->np = P->n;
  PetscCall(PetscMalloc2(P->n, &p->N, P->n, &p->gap));
  PetscCall(PetscMalloc1(n, &key));
  PetscCall(PetscCalloc1(n, &used));
  for (PetscInt r = 0; r < n; r++) {
    key[r].x = x[3 * r];
    key[r].i = r;
  }
  qsort(key, (size_t)n, sizeof(XKey), CompareXKey);
  for (PetscInt i = 0; i < P->n; i++) { /* for each pair, the file row at its position */
    PetscInt  lo = 0, hi = n, best = -1;
    PetscReal bd = p->load_tol;
    while (lo < hi) {
      const PetscInt mid = (lo + hi) / 2;
      if (key[mid].x < P->x[3 * i] - p->load_tol) lo = mid + 1;
      else hi = mid;
    }
    for (PetscInt j = lo; j < n && key[j].x <= P->x[3 * i] + p->load_tol; j++) {
      const PetscInt  r = key[j].i;
      const PetscReal d = PetscSqrtReal(PetscSqr(x[3 * r] - P->x[3 * i]) + PetscSqr(x[3 * r + 1] - P->x[3 * i + 1]) + PetscSqr(x[3 * r + 2] - P->x[3 * i + 2]));
      if (d <= bd) {
        bd   = d;
        best = r;
      }
    }
    PetscCheck(best >= 0, p->comm, PETSC_ERR_ARG_WRONG, "-preload_load %s: no row within %g m (-preload_load_tol) of the pair at (%g, %g, %g) m; the file does not match the model's interface", p->load, (double)p->load_tol, (double)P->x[3 * i], (double)P->x[3 * i + 1], (double)P->x[3 * i + 2]);
    PetscCheck(!used[best], p->comm, PETSC_ERR_ARG_WRONG, "-preload_load %s: row %" PetscInt_FMT " matches two pairs (-preload_load_tol %g m is too large)", p->load, best + 1, (double)p->load_tol);
    used[best] = 1;
    p->N[i]    = N[best];
    p->gap[i]  = g[best];
  }
  PetscCall(PetscFree(key));
  PetscCall(PetscFree(used));
  PetscCall(PetscFree3(x, N, g));
  p->loaded = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Solve the preload (or read it with -preload_load) */
PetscErrorCode JRPreloadSolve(JRPreload p)
{
  const JRPairs     *P;
  PetscLogDouble     t0, t1;
  SNESConvergedReason reason;

  PetscFunctionBeginUser;
  PetscCheck(p->model, p->comm, PETSC_ERR_ARG_WRONGSTATE, "JRPreloadSetModel() first");
  PetscCall(PetscTime(&t0));
  if (p->load[0]) {
    PetscCall(LoadResults(p));
    PetscCall(PetscTime(&t1));
    p->time = t1 - t0;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(JR_PreloadSetUp, 0, 0, 0, 0));
  if (!p->Kp) PetscCall(SetUpSystem(p));
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(ClearResults(p));
  p->newton = p->outer = p->factorisations = 0;
  if (p->condensed && !p->G) PetscCall(CondensedSetUp(p, P));
  PetscCall(PetscLogEventEnd(JR_PreloadSetUp, 0, 0, 0, 0));
  PetscCall(PetscLogEventBegin(JR_PreloadSolve, 0, 0, 0, 0));
  PetscCall(VecZeroEntries(p->u));
  if (p->condensed) PetscCall(VecSet(p->cw, p->open_start ? -p->open_gap : 0.0));
  else if (p->open_start) { /* every pair open: B's pair nodes moved along the normal, away from A */
    PetscInt rs, re;
    PetscCall(VecGetOwnershipRange(p->u, &rs, &re));
    for (PetscInt i = 0; i < 3 * p->np; i++)
      if (P->dofB[i] >= rs && P->dofB[i] < re) PetscCall(VecSetValue(p->u, P->dofB[i], p->open_gap * P->nrm[i], INSERT_VALUES));
    PetscCall(VecAssemblyBegin(p->u));
    PetscCall(VecAssemblyEnd(p->u));
  }
  for (PetscInt i = 0; i < p->np; i++) p->lam[i] = 0.0;
  p->jvalid = PETSC_FALSE;
  for (PetscInt it = 0; it < p->maxit; it++) {
    PetscInt  its;
    PetscReal dmax = 0.0, fmax = 0.0;
    SNES      snes = p->condensed ? p->csnes : p->snes;
    if (p->condensed) PetscCall(SNESSolve(snes, NULL, p->cw));
    else PetscCall(SNESSolve(snes, NULL, p->u));
    PetscCall(SNESGetConvergedReason(snes, &reason));
    PetscCall(SNESGetIterationNumber(snes, &its));
    p->newton += its;
    p->outer++;
    PetscCheck(reason > 0, p->comm, PETSC_ERR_NOT_CONVERGED, "preload: Newton did not converge (%s after %" PetscInt_FMT " iterations, update %" PetscInt_FMT "); see -preload_snes_monitor, raise -preload_snes_max_it, or try -preload_solver full", SNESConvergedReasons[reason], its, it + 1);
    if (p->condensed) PetscCall(CondensedState(p, P, p->cw));
    else PetscCall(PairState(p, P, p->u));
    if (p->method == JR_PRELOAD_PENALTY) break;
    for (PetscInt i = 0; i < p->np; i++) {
      const PetscReal l = PetscMax(0.0, p->lam[i] + p->k[i] * p->w[i]);
      dmax              = PetscMax(dmax, PetscAbsReal(l - p->lam[i]));
      fmax              = PetscMax(fmax, l);
      p->lam[i]         = l;
    }
    if (dmax <= p->rtol * fmax) break;
    PetscCheck(it + 1 < p->maxit, p->comm, PETSC_ERR_NOT_CONVERGED, "preload: the augmented Lagrangian did not converge in %" PetscInt_FMT " updates (-preload_max_it): largest force change %g N of %g N; raise -preload_penalty or -preload_rtol", p->maxit, (double)dmax, (double)fmax);
  }
  if (p->condensed) PetscCall(CondensedDisplacement(p, P));
  PetscCall(PetscLogEventEnd(JR_PreloadSolve, 0, 0, 0, 0));
  /* results */
  PetscCall(PetscMalloc2(p->np, &p->N, p->np, &p->gap));
  p->maxpen = 0.0;
  for (PetscInt i = 0; i < p->np; i++) {
    const PetscReal t = p->lam[i] + (p->method == JR_PRELOAD_PENALTY ? p->k[i] * p->w[i] : 0.0);
    p->N[i]           = PetscMax(0.0, p->method == JR_PRELOAD_PENALTY ? t : p->lam[i]);
    p->gap[i]         = p->N[i] > 0 ? 0.0 : PetscMax(0.0, -p->w[i]);
    p->maxpen         = PetscMax(p->maxpen, p->w[i]);
  }
  p->solved = PETSC_TRUE;
  PetscCall(PetscTime(&t1));
  p->time = t1 - t0;
  PetscFunctionReturn(0);
}

/* Per pair (every rank, borrowed): normal load N_static [N] and gap v_gap [m] */
PetscErrorCode JRPreloadGetResults(JRPreload p, PetscInt *n, const PetscReal **N, const PetscReal **gap)
{
  PetscFunctionBeginUser;
  PetscCheck(p->solved || p->loaded, p->comm, PETSC_ERR_ARG_WRONGSTATE, "JRPreloadSolve() first");
  if (n) *n = p->np;
  if (N) *N = p->N;
  if (gap) *gap = p->gap;
  PetscFunctionReturn(0);
}

/* n0 = N_static - kv v_gap per pair (5.1), kv [N/m] */
PetscErrorCode JRPreloadGetN0(JRPreload p, PetscReal kv, PetscReal n0[])
{
  PetscInt         n;
  const PetscReal *N, *g;

  PetscFunctionBeginUser;
  PetscCall(JRPreloadGetResults(p, &n, &N, &g));
  for (PetscInt i = 0; i < n; i++) n0[i] = N[i] - kv * g[i];
  PetscFunctionReturn(0);
}

/* The displacement of the preload solve (borrowed; NULL after -preload_load) */
PetscErrorCode JRPreloadGetSolution(JRPreload p, Vec *u)
{
  PetscFunctionBeginUser;
  *u = p->solved ? p->u : NULL;
  PetscFunctionReturn(0);
}

PetscErrorCode JRPreloadGetSummary(JRPreload p, JRPreloadSummary *s)
{
  const JRPairs *P;
  const JRBolts *B;
  PetscInt       n;
  const PetscReal *N, *g;
  PetscReal      atot = 0.0;

  PetscFunctionBeginUser;
  PetscCall(JRPreloadGetResults(p, &n, &N, &g));
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(JRModelGetBolts(p->model, &B));
  PetscCall(PetscMemzero(s, sizeof(*s)));
  s->pairs = n;
  for (PetscInt i = 0; i < n; i++) {
    atot += P->area[i];
    s->total_force += N[i];
    s->gap_max = PetscMax(s->gap_max, g[i]);
    if (N[i] > 0) {
      s->in_contact++;
      s->contact_area += P->area[i];
      s->peak_force    = PetscMax(s->peak_force, N[i]);
      s->peak_pressure = PetscMax(s->peak_pressure, N[i] / P->area[i]);
    }
  }
  s->interface_area = atot;
  for (PetscInt b = 0; b < B->n; b++) s->bolt_force_sum += p->nforce == 1 ? p->force[0] : p->force[b];
  s->bolts            = B->n;
  s->newton           = p->newton;
  s->updates          = p->outer;
  s->factorisations   = p->factorisations;
  s->penalty          = p->kp;
  s->max_penetration  = p->maxpen;
  s->time             = p->time;
  s->loaded           = p->loaded;
  PetscFunctionReturn(0);
}

PetscErrorCode JRPreloadView(JRPreload p, PetscViewer viewer)
{
  JRPreloadSummary s;

  PetscFunctionBeginUser;
  if (!viewer) viewer = PETSC_VIEWER_STDOUT_(p->comm);
  PetscCall(JRPreloadGetSummary(p, &s));
  if (s.loaded) PetscCall(PetscViewerASCIIPrintf(viewer, "preload: read from %s (%" PetscInt_FMT " pairs)\n", p->load, s.pairs));
  else {
    PetscCall(PetscViewerASCIIPrintf(viewer, "preload: %" PetscInt_FMT " bolts, pretension %s%.6g N; %s contact, kp = %.3g N/m^3; supports %s\n", s.bolts, p->nforce > 1 ? "first " : "", (double)p->force[0], p->method == JR_PRELOAD_PENALTY ? "penalty" : "augmented-Lagrangian", (double)s.penalty, JRPreloadSupports[p->support]));
    PetscCall(PetscViewerASCIIPrintf(viewer, "preload: %" PetscInt_FMT " Newton iterations in %" PetscInt_FMT " solve%s (%s), %" PetscInt_FMT " sparse factorisations, %.3g s; largest penetration %.3g m\n", s.newton, s.updates, s.updates > 1 ? "s" : "", p->condensed ? "condensed on the interface" : "all DOFs", s.factorisations, (double)s.time, (double)s.max_penetration));
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "preload: contact area %.4g mm^2 of %.4g mm^2 (%.1f%%), %" PetscInt_FMT " of %" PetscInt_FMT " pairs closed (%.1f%%)\n", (double)(s.contact_area * 1e6), (double)(s.interface_area * 1e6), (double)(100 * s.contact_area / s.interface_area), s.in_contact, s.pairs, (double)(100.0 * s.in_contact / PetscMax(s.pairs, 1))));
  PetscCall(PetscViewerASCIIPrintf(viewer, "preload: peak pressure %.4g MPa, mean over the contact area %.4g MPa, largest pair force %.4g N, largest gap %.3g um\n", (double)(s.peak_pressure * 1e-6), (double)(s.contact_area > 0 ? s.total_force / s.contact_area * 1e-6 : 0.0), (double)s.peak_force, (double)(s.gap_max * 1e6)));
  PetscFunctionReturn(0);
}

PetscErrorCode JRPreloadDestroy(JRPreload *pre)
{
  JRPreload p = *pre;

  PetscFunctionBeginUser;
  if (!p) PetscFunctionReturn(0);
  PetscCall(ClearResults(p));
  PetscCall(SNESDestroy(&p->snes));
  PetscCall(MatDestroy(&p->Kp));
  PetscCall(MatDestroy(&p->J));
  PetscCall(VecDestroy(&p->u));
  PetscCall(VecDestroy(&p->f));
  PetscCall(VecDestroy(&p->useq));
  PetscCall(VecDestroy(&p->fext));
  PetscCall(VecScatterDestroy(&p->sc));
  PetscCall(KSPDestroy(&p->ksp0));
  PetscCall(SNESDestroy(&p->csnes));
  PetscCall(MatDestroy(&p->cJ));
  PetscCall(VecDestroy(&p->cw));
  PetscCall(PetscFree2(p->G, p->yf));
  if (p->k) PetscCall(PetscFree5(p->k, p->lam, p->w, p->closed, p->jclosed));
  PetscCall(PetscFree(p->clamp));
  PetscCall(PetscFree2(p->supdof, p->supdir));
  PetscCall(PetscFree(p));
  *pre = NULL;
  PetscFunctionReturn(0);
}

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

/*
  Write BASE.csv (one row per pair), BASE.h5 (the mesh and the preload displacement when solved; /preload/: x_m,
  area_m2, N_static_N, pressure_Pa, v_gap_m, closed, and n0_N with -preload_kv), BASE.xdmf (ParaView: the
  deformed mesh and the interface pairs as points carrying N, pressure and gap) and, with plot, BASE.png
  (maps of the pressure and the gap over the interface and their mid-section profile, share/plot_preload.gp).
  Every file through a temporary name.
*/
PetscErrorCode JRPreloadWrite(JRPreload p, const char base[], PetscBool plot)
{
  const JRPairs   *P;
  PetscInt         n, nmid = 0;
  const PetscReal *N, *g;
  PetscReal       *pr, *cl, *n0 = NULL, ymin = PETSC_MAX_REAL, ymax = PETSC_MIN_REAL, ymid = 0.0, dbest = PETSC_MAX_REAL;
  char             csv[PETSC_MAX_PATH_LEN + 8], h5[PETSC_MAX_PATH_LEN + 8], xdmf[PETSC_MAX_PATH_LEN + 8], png[PETSC_MAX_PATH_LEN + 8], tmp[PETSC_MAX_PATH_LEN + 32];
  FILE            *fp;
  PetscMPIInt      rank;
  DM               dm;

  PetscFunctionBeginUser;
  if (!base || !base[0]) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(p->comm, &rank));
  PetscCall(JRPreloadGetResults(p, &n, &N, &g));
  PetscCall(JRModelGetPairs(p->model, &P));
  PetscCall(JRModelGetDM(p->model, &dm));
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
  PetscCall(PetscSNPrintf(csv, sizeof(csv), "%s.csv", base));
  PetscCall(PetscSNPrintf(h5, sizeof(h5), "%s.h5", base));
  PetscCall(PetscSNPrintf(xdmf, sizeof(xdmf), "%s.xdmf", base));
  PetscCall(PetscSNPrintf(png, sizeof(png), "%s.png", base));
  PetscCall(JRFileOpenTemp(p->comm, csv, &fp, tmp, sizeof(tmp)));
  if (fp) {
    fprintf(fp, "pair,x_m,y_m,z_m,area_m2,N_static_N,pressure_Pa,v_gap_m,closed,mid%s\n", n0 ? ",n0_N" : "");
    for (PetscInt i = 0; i < n; i++) {
      const int mid = PetscAbsReal(P->x[3 * i + 1] - ymid) < 1e-9;
      fprintf(fp, "%" PetscInt_FMT ",%.10g,%.10g,%.10g,%.8g,%.10g,%.10g,%.10g,%d,%d", i + 1, (double)P->x[3 * i], (double)P->x[3 * i + 1], (double)P->x[3 * i + 2], (double)P->area[i], (double)N[i], (double)pr[i], (double)g[i], (int)cl[i], mid);
      if (n0) fprintf(fp, ",%.10g", (double)n0[i]);
      fprintf(fp, "\n");
      nmid += mid;
    }
  }
  PetscCall(JRFileCommit(p->comm, &fp, tmp, csv));
  { /* HDF5 */
    PetscViewer v;
    Vec         vv;
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
  }
  { /* XDMF */
    const char *leaf = strrchr(h5, '/') ? strrchr(h5, '/') + 1 : h5;
    PetscInt    nc = 0, nv = 0;
    if (p->solved) {
      PetscInt cs, ce, nl, own = 0;
      IS       vn;
      const PetscInt *idx;
      PetscCall(DMPlexGetHeightStratum(dm, 0, &cs, &ce));
      nc = ce - cs;
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nc, 1, MPIU_INT, MPI_SUM, p->comm));
      PetscCall(DMPlexGetVertexNumbering(dm, &vn));
      PetscCall(ISGetLocalSize(vn, &nl));
      PetscCall(ISGetIndices(vn, &idx));
      for (PetscInt i = 0; i < nl; i++) own += idx[i] >= 0;
      PetscCall(ISRestoreIndices(vn, &idx));
      PetscCallMPI(MPI_Allreduce(&own, &nv, 1, MPIU_INT, MPI_SUM, p->comm));
    }
    PetscCall(JRFileOpenTemp(p->comm, xdmf, &fp, tmp, sizeof(tmp)));
    if (fp) {
      fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n");
      if (p->solved) {
        fprintf(fp, "  <Grid Name=\"assembly\" GridType=\"Uniform\">\n   <Topology TopologyType=\"Hexahedron\" NumberOfElements=\"%" PetscInt_FMT "\">\n    <DataItem Dimensions=\"%" PetscInt_FMT " 8\" NumberType=\"Int\" Format=\"HDF\">%s:/viz/topology/cells</DataItem>\n   </Topology>\n", nc, nc, leaf);
        fprintf(fp, "   <Geometry GeometryType=\"XYZ\">\n    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/geometry/vertices</DataItem>\n   </Geometry>\n", nv, leaf);
        fprintf(fp, "   <Attribute Name=\"preload displacement\" AttributeType=\"Vector\" Center=\"Node\">\n    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/vertex_fields/preload_displacement</DataItem>\n   </Attribute>\n  </Grid>\n", nv, leaf);
      }
      fprintf(fp, "  <Grid Name=\"interface pairs\" GridType=\"Uniform\">\n   <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%" PetscInt_FMT "\"/>\n", n);
      fprintf(fp, "   <Geometry GeometryType=\"XYZ\">\n    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/preload/x_m</DataItem>\n   </Geometry>\n", n, leaf);
      {
        const char *names[6] = {"N_static_N", "pressure_Pa", "v_gap_m", "closed", "area_m2", "n0_N"};
        for (int k = 0; k < (n0 ? 6 : 5); k++) fprintf(fp, "   <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">\n    <DataItem Dimensions=\"%" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/preload/%s</DataItem>\n   </Attribute>\n", names[k], n, leaf, names[k]);
      }
      fprintf(fp, "  </Grid>\n </Domain>\n</Xdmf>\n");
    }
    PetscCall(JRFileCommit(p->comm, &fp, tmp, xdmf));
  }
  if (plot) {
    char vars[3 * PETSC_MAX_PATH_LEN];
    PetscCall(PetscSNPrintf(vars, sizeof(vars), "data='%s'; ymid=%.6g", csv, (double)(ymid * 1e3)));
    PetscCall(JRPlot(p->comm, "plot_preload.gp", png, vars, NULL));
  }
  PetscCall(PetscFree2(pr, cl));
  PetscCall(PetscFree(n0));
  (void)nmid;
  PetscFunctionReturn(0);
}
