/*
   The reduced model's joint motion fields, for JRHBM (first reduction, thesis 4.4): every member of a joint moves with
   the joint's field, its mean motion or a field linear in the members' coordinates fitted to them by least squares
   (-rom_joint_motion mean, linear, mode, shapes); and the second reduction's joints, whose few elements move with the
   fields of their members. The fields' layout (JR_NF, JR_FIELD_WIDTH) is in include/jointrom/private/hbmimpl.h.
*/
#include <jointrom/private/hbmimpl.h>

/* Pseudo-inverse of a symmetric positive semi-definite n x n matrix G (n <= JR_NF), in place: directions with
   eigenvalues below 1e-10 of the largest are dropped (members on a line have no rotation about it; coordinates that
   do not vary within a joint carry nothing) */
static PetscErrorCode PseudoInverse(PetscInt n, PetscReal G[])
{
  PetscBLASInt bn, lwork = 64, info;
  PetscReal    lam[JR_NF], work[64], A[JR_NF * JR_NF];

  PetscFunctionBeginUser;
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCall(PetscArraycpy(A, G, n * n));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &bn, A, &bn, lam, work, &lwork, &info));
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed (%d)", (int)info);
  PetscCall(PetscArrayzero(G, n * n));
  for (PetscInt k = 0; k < n; k++) {
    if (!(lam[k] > 1e-10 * lam[n - 1])) continue;
    for (PetscInt a = 0; a < n; a++)
      for (PetscInt b = 0; b < n; b++) G[n * a + b] += A[n * k + a] * A[n * k + b] / lam[k];
  }
  PetscFunctionReturn(0);
}

/* The field of joint f at coordinates p: rows X[i] = mean_i + B_i . (p - cbar) (the mean when p is NULL) */
static inline void FieldAt(const PetscReal *f, PetscInt nm, PetscInt q, const PetscReal *p, PetscReal *X, PetscInt ldx)
{
  const PetscReal *cb = f + 1 + q * (JR_NF + (1 + JR_NF) * nm), *ms = cb + JR_NF, *B = ms + nm;
  PetscReal        dp[JR_NF];
  for (PetscInt c = 0; c < JR_NF; c++) dp[c] = p ? p[c] - cb[c] : 0.0;
  for (PetscInt i = 0; i < nm; i++) {
    PetscReal x = ms[i];
    for (PetscInt c = 0; c < JR_NF; c++) x += B[JR_NF * i + c] * dp[c];
    X[i * ldx] = x;
  }
}

/* -rom_joint_motion shapes: whether coordinate c (x, y, z, phi_t, phi_n, then the released modes' phi_t) enters the
   field of row set q (0 tangential: all but phi_n, the positions keeping the joint's turning in its plane; 1 normal:
   phi_n) */
static inline PetscBool ShapeCoordinate(PetscInt q, PetscInt c)
{
  return (PetscBool)(q ? c == 4 : c != 4);
}

/* First reduction (4.4): the motion field of each joint, from the rows R (and S) of this rank's elements eidx[] of el
   (nloc x nm, column-major), collective. The field is fitted to the members in contact at rest (n0 > 0: those whose
   stuck springs the joint replaces; all members if none is). With -rom_joint_motion mean (the thesis) it is their
   average motion; else a field linear in their coordinates P (JR_NF per element), fitted by least squares,
   r_e ~ mean + B (p_e - cbar): with positions, the mean plus the joint's rotation (the interface's bending within
   the joint, which a mean cannot carry); with the stuck-mode motions, the members' own motions in that mode. Either
   is an orthogonal projection of the members' motions (k sum u_e^2 >= the projection's, for equal k), so the reduced
   model is never stiffer than the node-to-node one */
static PetscErrorCode JointFields(JRHBM h, const JRElements *el, PetscInt nloc, const PetscInt eidx[], const PetscReal R[], const PetscReal S[], const PetscReal P[], PetscReal field[])
{
  const PetscBool shapes = (PetscBool)(h->jmotion == JR_JOINT_MOTION_SHAPES);
  const PetscInt  nm = h->nm, nj = el->njoints, nr = S ? 2 : 1, fw = JR_FIELD_WIDTH(nr, nm), NF = JR_NF;
  const PetscInt w = 1 + NF + NF * NF + (1 + NF) * nr * nm; /* count, sum p, sum p p^T, then per set sum r, sum r p^T */
  PetscReal     *loc, *sum;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc2(2 * nj * w, &loc, 2 * nj * w, &sum)); /* per joint: its members in contact at rest, then all */
  for (PetscInt e = 0; e < nloc; e++) {
    for (PetscInt a = 0; a < 2; a++) {
      PetscReal *r = loc + (2 * el->joint[eidx[e]] + a) * w;
      if (!a && !(el->n0[eidx[e]] > 0)) continue;
      r[0] += 1.0;
      if (P)
        for (PetscInt c = 0; c < NF; c++) {
          r[1 + c] += P[NF * e + c];
          for (PetscInt d = 0; d < NF; d++) r[1 + NF + NF * c + d] += P[NF * e + c] * P[NF * e + d];
        }
      for (PetscInt q = 0; q < nr; q++) {
        const PetscReal *X  = q ? S : R;
        PetscReal       *rs = r + 1 + NF + NF * NF + (1 + NF) * q * nm;
        for (PetscInt i = 0; i < nm; i++) {
          rs[i] += X[e + i * nloc];
          if (P)
            for (PetscInt c = 0; c < NF; c++) rs[nm + NF * i + c] += X[e + i * nloc] * P[NF * e + c];
        }
      }
    }
  }
  PetscCall(MPIU_Allreduce(loc, sum, 2 * nj * w, MPIU_REAL, MPIU_SUM, h->comm));
  PetscCall(PetscArrayzero(field, nj * fw));
  for (PetscInt j = 0; j < nj; j++) {
    const PetscReal *r = sum + 2 * j * w;
    PetscReal       *f = field + j * fw, G[JR_NF * JR_NF], cbar[JR_NF];
    if (!(r[0] > 0)) r += w; /* no member in contact at rest: the fit to all */
    if (!(r[0] > 0)) continue; /* no member here (of this element type): f[0] = 0 */
    f[0] = r[0];
    for (PetscInt c = 0; c < NF; c++) cbar[c] = r[1 + c] / r[0];
    for (PetscInt c = 0; c < NF; c++)
      for (PetscInt d = 0; d < NF; d++) G[NF * c + d] = r[1 + NF + NF * c + d] - r[0] * cbar[c] * cbar[d];
    for (PetscInt q = 0; q < nr; q++) {
      const PetscReal *rs = r + 1 + NF + NF * NF + (1 + NF) * q * nm;
      PetscReal        Gq[JR_NF * JR_NF];
      PetscCall(PetscArraycpy(Gq, G, NF * NF));
      if (shapes) /* the tangential rows on the tangential motions (stuck and released modes), the normal on the normal */
        for (PetscInt c = 0; c < NF; c++)
          for (PetscInt d = 0; d < NF; d++)
            if (!ShapeCoordinate(q, c) || !ShapeCoordinate(q, d)) Gq[NF * c + d] = 0.0;
      if (P) PetscCall(PseudoInverse(NF, Gq)); /* B = sum_e r_e (p_e - cbar)^T G^+, G = sum_e (p_e - cbar)(p_e - cbar)^T */
      PetscReal       *cb = f + 1 + q * (NF + (1 + NF) * nm), *ms = cb + NF, *B = ms + nm;
      for (PetscInt c = 0; c < NF; c++) cb[c] = cbar[c];
      for (PetscInt i = 0; i < nm; i++) {
        ms[i] = rs[i] / r[0];
        if (!P) continue;
        {
          PetscReal m[JR_NF];
          for (PetscInt c = 0; c < NF; c++) m[c] = rs[nm + NF * i + c] - rs[i] * cbar[c];
          for (PetscInt c = 0; c < NF; c++) {
            PetscReal x = 0;
            for (PetscInt d = 0; d < NF; d++) x += Gq[NF * c + d] * m[d];
            B[NF * i + c] = x;
          }
        }
      }
    }
  }
  PetscCall(PetscFree2(loc, sum));
  PetscFunctionReturn(0);
}

/* The field coordinates (JR_NF each) of elements eidx[0..nloc) of el: positions if el has them and lin, stuck-mode
   and released-mode motions if el has them (else 0); P = NULL (the mean) when there are none */
static PetscErrorCode JointCoordinates(JRHBM h, const JRElements *el, PetscInt nloc, const PetscInt eidx[], PetscBool lin, PetscReal **P)
{
  PetscFunctionBeginUser;
  *P = NULL;
  if (!lin) PetscFunctionReturn(0);
  PetscCheck(el->pos, h->comm, PETSC_ERR_ARG_WRONG, "-rom_joint_motion linear or mode needs the elements' positions (node-to-node elements of an FE model)");
  PetscCall(PetscCalloc1(JR_NF * nloc + 1, P));
  for (PetscInt e = 0; e < nloc; e++) {
    for (PetscInt c = 0; c < 3; c++) (*P)[JR_NF * e + c] = el->pos[3 * eidx[e] + c];
    for (PetscInt c = 0; el->phi && c < 2; c++) (*P)[JR_NF * e + 3 + c] = el->phi[2 * eidx[e] + c];
    for (PetscInt c = 0; el->phir && c < JR_NREL; c++) (*P)[JR_NF * e + 5 + c] = el->phir[JR_NREL * eidx[e] + c];
  }
  PetscFunctionReturn(0);
}

/* The field coordinates of element e of el (buffer p), or NULL */
static inline const PetscReal *ElementCoordinates(const JRElements *el, PetscInt e, PetscReal p[JR_NF])
{
  if (!el->pos) return NULL;
  for (PetscInt c = 0; c < 3; c++) p[c] = el->pos[3 * e + c];
  for (PetscInt c = 0; c < 2; c++) p[3 + c] = el->phi ? el->phi[2 * e + c] : 0.0;
  for (PetscInt c = 0; c < JR_NREL; c++) p[5 + c] = el->phir ? el->phir[JR_NREL * e + c] : 0.0;
  return p;
}

/* First reduction (4.4): every member of a joint moves with the joint's field (JointFields) at its own position; so
   each member's rows R (and S) become the joint's (collective) */
PetscErrorCode JRJointAverage(JRHBM h, const JRElements *el, PetscInt nloc, const PetscInt eidx[], PetscReal R[], PetscReal S[])
{
  const PetscInt nm = h->nm, nr = S ? 2 : 1, fw = JR_FIELD_WIDTH(nr, nm);
  PetscReal     *P, *field;

  PetscFunctionBeginUser;
  PetscCall(JointCoordinates(h, el, nloc, eidx, (PetscBool)(h->jmotion != JR_JOINT_MOTION_MEAN), &P));
  PetscCall(PetscMalloc1(el->njoints * fw, &field));
  PetscCall(JointFields(h, el, nloc, eidx, R, S, P, field));
  for (PetscInt e = 0; e < nloc; e++)
    for (PetscInt q = 0; q < nr; q++) FieldAt(field + el->joint[eidx[e]] * fw, nm, q, P ? P + JR_NF * e : NULL, (q ? S : R) + e, nloc);
  PetscCall(PetscFree(field));
  PetscCall(PetscFree(P));
  PetscFunctionReturn(0);
}

/* K += a sum over the members eidx[0..nloc) in contact at rest of kt x x^T + kn y y^T, x and y their rows in R and S
   (nloc x nm, column-major; kn for jenkins_nv only) */
static PetscErrorCode StuckSprings(const JRElements *mem, PetscInt nloc, const PetscInt eidx[], PetscInt nm, PetscReal a, const PetscReal R[], const PetscReal S[], PetscReal K[])
{
  PetscReal *W;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(nloc * nm, &W));
  for (PetscInt q = 0; q < 2; q++) {
    const PetscReal *X = q ? S : R;
    for (PetscInt i = 0; i < nm; i++)
      for (PetscInt e = 0; e < nloc; e++) {
        const PetscInt  k  = eidx[e];
        const PetscBool nv = (PetscBool)!strcmp(mem->typename[mem->type[k]], JRCONTACTJENKINSNV);
        W[e + i * nloc]    = (mem->n0[k] > 0 ? (q ? (nv ? mem->kn[k] : 0.0) : mem->kt[k]) : 0.0) * X[e + i * nloc];
      }
    PetscCall(JRGemm("T", "N", nm, nm, nloc, a, X, nloc, W, nloc, 1.0, K, nm));
  }
  PetscCall(PetscFree(W));
  PetscFunctionReturn(0);
}

/* Second reduction: the joints' fields (JointFields, nj x JR_FIELD_WIDTH(2, nm), tangential then normal, on every
   rank) from their members' rows, the members split across the ranks (lin: the reduced elements have positions, so
   the linear field of -rom_joint_motion linear is wanted; else the mean); and, in a stuck basis, Kc += this rank's
   members' stuck springs on their own rows (the springs the basis holds, which the reduced elements replace), less,
   with h->jresid, those on their residual motion r_e - p_e outside their joint's field (which the basis keeps) */
PetscErrorCode JRJointRows(JRHBM h, const JRElements *mem, PetscBool lin, PetscReal field[], PetscReal Kc[])
{
  const PetscInt nm = h->nm;
  PetscInt       nloc = PETSC_DECIDE, n = mem->n, start = 0, *eidx;
  PetscReal     *R, *S, *P;
  PetscBool      nv = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCheck(mem->vdof_a && mem->joint, h->comm, PETSC_ERR_ARG_WRONG, "A reduced model's members must be node-to-node elements with joints");
  for (PetscInt t = 0; t < mem->ntypes; t++) nv = (PetscBool)(nv || !strcmp(mem->typename[t], JRCONTACTJENKINSNV));
  PetscCall(PetscSplitOwnership(h->comm, &nloc, &n));
  PetscCallMPI(MPI_Scan(&nloc, &start, 1, MPIU_INT, MPI_SUM, h->comm));
  start -= nloc;
  PetscCall(PetscMalloc3(nloc, &eidx, nloc * nm, &R, nloc * nm, &S));
  for (PetscInt e = 0; e < nloc; e++) eidx[e] = start + e;
  PetscCall(JRHBMProjectionRowsDir(h, nloc, eidx, mem->vdof_a, mem->vdof_b, mem->tdir, R));
  if (nv) PetscCall(JRHBMProjectionRowsDir(h, nloc, eidx, mem->vdof_a, mem->vdof_b, mem->ndir, S)); /* normal rows: jenkins_nv only */
  else PetscCall(PetscArrayzero(S, nloc * nm));
  PetscCall(JointCoordinates(h, mem, nloc, eidx, lin, &P));
  PetscCall(JointFields(h, mem, nloc, eidx, R, S, P, field));
  if (Kc && nloc) PetscCall(StuckSprings(mem, nloc, eidx, nm, 1.0, R, S, Kc));
  if (Kc && nloc && h->jresid) { /* less the springs on the residual rows r_e - p_e, which the basis keeps */
    PetscReal *Rr, *Sr;
    PetscCall(PetscMalloc2(nloc * nm, &Rr, nloc * nm, &Sr));
    for (PetscInt e = 0; e < nloc; e++)
      for (PetscInt q = 0; q < 2; q++) FieldAt(field + mem->joint[eidx[e]] * JR_FIELD_WIDTH(2, nm), nm, q, P ? P + JR_NF * e : NULL, (q ? Sr : Rr) + e, nloc);
    for (PetscInt i = 0; i < nloc * nm; i++) {
      Rr[i] = R[i] - Rr[i];
      Sr[i] = S[i] - Sr[i];
    }
    PetscCall(StuckSprings(mem, nloc, eidx, nm, -1.0, Rr, Sr, Kc));
    PetscCall(PetscFree2(Rr, Sr));
  }
  PetscCall(PetscFree(P));
  for (PetscInt j = 0; j < mem->njoints; j++) PetscCheck(field[j * JR_FIELD_WIDTH(2, nm)] > 0, h->comm, PETSC_ERR_ARG_WRONG, "Joint %" PetscInt_FMT " has no member element", j);
  PetscCall(PetscFree3(eidx, R, S));
  PetscFunctionReturn(0);
}

/* Reduced model: the rows X (nloc x nm, column-major) of its elements eidx[] of el from their joints' fields (JRJointRows;
   set q: 0 tangential, 1 normal), each at its own coordinates (JRElements pos, phi) */
PetscErrorCode JRJointFieldRows(JRHBM h, const JRElements *el, PetscInt nloc, const PetscInt eidx[], const PetscReal field[], PetscInt q, PetscReal X[])
{
  const PetscInt nm = h->nm;
  PetscReal      pc[JR_NF]; /* an element's field coordinates */

  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < nloc; e++) FieldAt(field + el->joint[eidx[e]] * JR_FIELD_WIDTH(2, nm), nm, q, ElementCoordinates(el, eidx[e], pc), X + e, nloc);
  PetscFunctionReturn(0);
}
