/*
   Bolts of the FE models.

   Each bolt is an Euler-Bernoulli beam (the shank: diameter d, steel of the beams' modulus) from the head
   footprint to the nut footprint. Each end is tied to its footprint (the washer's contact annulus on the
   outer face) by a least-squares rigid fit: the end's 3 displacements and 3 rotations are the rigid
   motion closest to the footprint nodes' displacements (an RBE3-like distributing coupling), so the bolt
   stiffness enters K as T^T K_beam T over the footprint DOFs. The washers, head and nut are not meshed:
   the footprints are not stiffened by them, which makes the joint slightly softer than a solid tied bolt
   (a few per cent on the modes that bend the lap; docs/validation.md). The assembly holds together through
   the bolts alone, with no contact, as in the thesis's modal analysis.
*/
#include <jointrom/private/feimpl.h>

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


/* K += sum of the blocks, through a matrix of their own pattern (K's pattern does not couple them);
   frees the blocks' arrays */
PetscErrorCode JRFEAddDenseBlocks(JRModel m, PetscInt nb, JRFEDenseBlock *bd)
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

/* one end of a bolt: its washer footprint */
typedef struct {
  PetscInt   n, *dof; /* footprint nodes (all ranks) and their first global DOFs */
  PetscReal *x, c[3]; /* the nodes' coordinates (3n) and their centroid, the beam's end */
  PetscReal *T;       /* 6 x 3n, row-major: the rigid fit (RigidFit) about c */
} Footprint;

/* the nodes of the faces labelled val (JR_LABEL_BOLT) and their centroid */
static PetscErrorCode FootprintGetNodes(DM dm, PetscInt val, Footprint *fp)
{
  PetscFunctionBeginUser;
  PetscCall(JRFEFaceNodes(dm, JR_LABEL_BOLT, val, &fp->n, &fp->x, &fp->dof));
  for (int d = 0; d < 3; d++) fp->c[d] = 0.0;
  for (PetscInt k = 0; k < fp->n; k++)
    for (int d = 0; d < 3; d++) fp->c[d] += fp->x[3 * k + d] / fp->n;
  fp->T = NULL;
  PetscFunctionReturn(0);
}

static PetscErrorCode FootprintFit(MPI_Comm comm, Footprint *fp)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(6 * 3 * fp->n, &fp->T));
  PetscCall(RigidFit(comm, fp->n, fp->x, fp->c, fp->T));
  PetscFunctionReturn(0);
}

static PetscErrorCode FootprintDestroy(Footprint *fp)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(fp->T));
  PetscCall(PetscFree2(fp->x, fp->dof));
  PetscFunctionReturn(0);
}

/* The pretension data of bolt i (B->off[i + 1], B->dof, B->g, B->ka[i], B->x): the elongation
   g = e3 . (u_nut - u_head) of the fitted ends, e3 from head to nut, over the footprints' DOFs */
static PetscErrorCode AppendPretension(const Model_FE *fe, PetscInt i, const Footprint *h, const Footprint *n, JRBolts *B)
{
  const PetscReal L = fe->bolt[i].axis, e3[3] = {(n->c[0] - h->c[0]) / L, (n->c[1] - h->c[1]) / L, (n->c[2] - h->c[2]) / L};
  const PetscInt  ntot = B->off[i], nh = h->n, nn = n->n;
  PetscInt       *dof;
  PetscReal      *g;

  PetscFunctionBeginUser;
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
    B->dof[ntot + c] = h->dof[c / 3] + c % 3;
    B->g[ntot + c]   = -(e3[0] * h->T[0 * 3 * nh + c] + e3[1] * h->T[1 * 3 * nh + c] + e3[2] * h->T[2 * 3 * nh + c]);
  }
  for (PetscInt c = 0; c < 3 * nn; c++) {
    B->dof[ntot + 3 * nh + c] = n->dof[c / 3] + c % 3;
    B->g[ntot + 3 * nh + c]   = e3[0] * n->T[0 * 3 * nn + c] + e3[1] * n->T[1 * 3 * nn + c] + e3[2] * n->T[2 * 3 * nn + c];
  }
  B->ka[i] = fe->E * PETSC_PI * fe->bolt[i].d * fe->bolt[i].d / 4 / L;
  for (int d = 0; d < 3; d++) B->x[3 * i + d] = h->c[d];
  PetscFunctionReturn(0);
}

/* The bolt's block over the head then the nut footprint DOFs: Kf = T^T Kbeam T, T = blockdiag(Th, Tn)
   (12 x 3(nh + nn)) */
static PetscErrorCode BoltBlock(const PetscReal Kbeam[144], const Footprint *h, const Footprint *n, JRFEDenseBlock *bd)
{
  const PetscInt nh = h->n, nn = n->n, nf = 3 * (nh + nn);
  PetscReal     *T, *KT;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(12 * nf, &T, 12 * nf, &KT));
  PetscCall(PetscArrayzero(T, 12 * nf));
  for (int a = 0; a < 6; a++) {
    for (PetscInt c = 0; c < 3 * nh; c++) T[a * nf + c] = h->T[a * 3 * nh + c];
    for (PetscInt c = 0; c < 3 * nn; c++) T[(a + 6) * nf + 3 * nh + c] = n->T[a * 3 * nn + c];
  }
  bd->n = nf;
  PetscCall(PetscMalloc2(nf, &bd->dof, nf * nf, &bd->Kf));
  for (PetscInt k = 0; k < nh; k++)
    for (int d = 0; d < 3; d++) bd->dof[3 * k + d] = h->dof[k] + d;
  for (PetscInt k = 0; k < nn; k++)
    for (int d = 0; d < 3; d++) bd->dof[3 * nh + 3 * k + d] = n->dof[k] + d;
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
      bd->Kf[r * nf + c] = s;
    }
  PetscCall(PetscFree2(T, KT));
  PetscFunctionReturn(0);
}

/* -model_bolt_tie rigid: penalise the footprint's deviation from its rigid fit, kappa (I - B T), in the
   block's rows and columns o.. o + 3n; kappa = JR_TIE_PENALTY E times the footprint's rms radius */
static void TiePenalty(PetscReal E, const Footprint *fp, PetscInt o, JRFEDenseBlock *bd)
{
  const PetscInt   n = fp->n, nf = bd->n;
  const PetscReal *xe = fp->x, *ce = fp->c, *Te = fp->T;
  PetscReal        rho2 = 0.0, kappa;

  for (PetscInt k = 0; k < n; k++) rho2 += (PetscSqr(xe[3 * k] - ce[0]) + PetscSqr(xe[3 * k + 1] - ce[1]) + PetscSqr(xe[3 * k + 2] - ce[2])) / n;
  kappa = JR_TIE_PENALTY * E * PetscSqrtReal(rho2);
  for (PetscInt k = 0; k < n; k++) {
    PetscReal B[3][6];
    RigidRows(xe + 3 * k, ce, B);
    for (int d = 0; d < 3; d++)
      for (PetscInt c = 0; c < 3 * n; c++) {
        PetscReal bt = 0.0;
        for (int a = 0; a < 6; a++) bt += B[d][a] * Te[a * 3 * n + c];
        bd->Kf[(o + 3 * k + d) * nf + o + c] += kappa * ((3 * k + d == c ? 1.0 : 0.0) - bt);
      }
  }
}

/* add the bolts' stiffness to K: sum_b T_b^T K_beam T_b over the footprint DOFs; fill m->bolts (the
   pretension data) and fe->bolt[] (footprint sizes, shank axis and length) */
PetscErrorCode JRFEAddBolts(JRModel m, Model_FE *fe)
{
  JRFEDenseBlock *bd;
  JRBolts        *B = &m->bolts;

  PetscFunctionBeginUser;
  PetscCall(JRBoltsDestroy(B));
  if (!fe->nbolts) PetscFunctionReturn(0);
  PetscCall(PetscCalloc1(fe->nbolts, &bd));
  B->n = fe->nbolts;
  PetscCall(PetscMalloc3(fe->nbolts + 1, &B->off, fe->nbolts, &B->ka, 3 * fe->nbolts, &B->x));
  B->off[0] = 0;
  for (PetscInt i = 0; i < fe->nbolts; i++) {
    Footprint h, n;
    PetscReal Kbeam[144];
    PetscCall(FootprintGetNodes(fe->dm, 2 * i + 1, &h));
    PetscCall(FootprintGetNodes(fe->dm, 2 * i + 2, &n));
    PetscCheck(h.n >= 3 && n.n >= 3, m->comm, PETSC_ERR_ARG_WRONG, "Bolt %" PetscInt_FMT ": its washer footprints have %" PetscInt_FMT " (head) and %" PetscInt_FMT " (nut) nodes; refine the mesh (-model_mesh_h) or widen the washer", i + 1, h.n, n.n);
    fe->bolt[i].nhead = h.n;
    fe->bolt[i].nnut  = n.n;
    fe->bolt[i].axis  = PetscSqrtReal(PetscSqr(h.c[0] - n.c[0]) + PetscSqr(h.c[1] - n.c[1]) + PetscSqr(h.c[2] - n.c[2]));
    for (int d = 0; d < 3; d++) fe->bolt[i].x[d] = h.c[d];
    BeamStiffness(h.c, n.c, fe->bolt[i].d, fe->E, fe->nu, Kbeam);
    PetscCall(FootprintFit(m->comm, &h));
    PetscCall(FootprintFit(m->comm, &n));
    PetscCall(AppendPretension(fe, i, &h, &n, B));
    PetscCall(BoltBlock(Kbeam, &h, &n, &bd[i]));
    if (fe->rigidtie) {
      TiePenalty(fe->E, &h, 0, &bd[i]);
      TiePenalty(fe->E, &n, 3 * h.n, &bd[i]);
    }
    PetscCall(FootprintDestroy(&h));
    PetscCall(FootprintDestroy(&n));
  }
  PetscCall(JRFEAddDenseBlocks(m, fe->nbolts, bd));
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
