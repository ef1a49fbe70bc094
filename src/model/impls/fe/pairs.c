/*
   The interface of the lap-joint FE models: node-to-node pairs between the two contact surfaces (labels
   JR_LABEL_CONTACT 1 and 2) with their normal, tangent, area and initial gap, and -model_interface tied,
   which joins every pair by penalty springs.
*/
#include <jointrom/private/feimpl.h>

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
        PetscCall(JRFECellCentre(dm, supp[0], cc));
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

/* The pairs' tangent: the beam axis x (or y, -model_tangent) projected on the interface plane */
static PetscErrorCode PairTangent(JRModel m, const Model_FE *fe, const PetscReal nrm[3], PetscReal t[3])
{
  PetscReal tn = 0.0;

  PetscFunctionBeginUser;
  t[0] = t[1] = t[2] = 0.0;
  t[fe->tangent[0] == 'y' ? 1 : 0] = 1.0;
  for (int d = 0; d < 3; d++) tn += t[d] * nrm[d];
  for (int d = 0; d < 3; d++) t[d] -= tn * nrm[d];
  tn = PetscSqrtReal(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  PetscCheck(tn > 1e-6, m->comm, PETSC_ERR_ARG_WRONG, "-model_tangent %s is normal to the contact surface (normal %g %g %g)", fe->tangent, (double)nrm[0], (double)nrm[1], (double)nrm[2]);
  for (int d = 0; d < 3; d++) t[d] /= tn;
  PetscFunctionReturn(0);
}

/* Pair every node of contact surface A with the nearest node of B within -model_pair_tol; the normal is
   surface A's outward normal (from A into B), the tangent from PairTangent(). */
PetscErrorCode JRFEFindPairs(JRModel m, Model_FE *fe)
{
  PetscInt   na, nb, *da, *db, np = 0, *usedB;
  PetscReal *xa, *xb, *wa, tol = fe->pairtol, nrm[3], dev = 0.0, t[3], dmax = 0.0;
  JRNearest  kb;
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
  PetscCall(PairTangent(m, fe, nrm, t));
  PetscCall(JRNearestCreate(nb, xb, &kb));
  PetscCall(PetscCalloc1(PetscMax(nb, 1), &usedB));
  PetscCall(PetscMalloc5(3 * PetscMax(na, 1), &P->x, 3 * PetscMax(na, 1), &P->t, 3 * PetscMax(na, 1), &P->nrm, 3 * PetscMax(na, 1), &P->dofA, 3 * PetscMax(na, 1), &P->dofB));
  PetscCall(PetscMalloc2(PetscMax(na, 1), &P->area, PetscMax(na, 1), &P->gap0));
  for (PetscInt a = 0; a < na; a++) {
    PetscReal bd;
    PetscInt  best;
    PetscCall(JRNearestFind(kb, xa + 3 * a, tol, &best, &bd));
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
  PetscCall(JRNearestDestroy(&kb));
  PetscCall(PetscFree(usedB));
  PetscCall(PetscFree2(xa, da));
  PetscCall(PetscFree(wa));
  PetscCall(PetscFree2(xb, db));
  PetscFunctionReturn(0);
}

/* -model_interface tied: every pair joined in all three directions by a penalty spring (the stuck interface
   of a linear joint model), kappa = JR_TIE_PENALTY E sqrt(area per pair) */
PetscErrorCode JRFETieInterface(JRModel m, Model_FE *fe)
{
  const JRPairs  *P = &m->pairs;
  const PetscReal kappa = P->n ? JR_TIE_PENALTY * fe->E * PetscSqrtReal(fe->contact_area / P->n) : 0.0;
  JRFEDenseBlock *bd;

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
  PetscCall(JRFEAddDenseBlocks(m, 3 * P->n, bd));
  PetscCall(PetscFree(bd));
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
