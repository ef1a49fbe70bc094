/*
   JRHBM at a solution: the response at the output DOFs, the energy balance per cycle, the kinetic energy, and the
   contact state of every element over the cycle.
*/
#include <jointrom/private/hbmimpl.h>

/*
  JRHBMResponse - at the output DOFs: X[o*nc + k] the harmonics of x_o(t), amp[o] the amplitude of
  the first harmonic sqrt(Xs1^2 + Xc1^2) [m], pp[o] half the peak-to-peak of x_o(t) over a cycle
  (sampled at 16 (2H+1) points). Any of X, amp, pp may be NULL.
*/
PetscErrorCode JRHBMResponse(JRHBM h, Vec a, PetscReal X[], PetscReal amp[], PetscReal pp[])
{
  const PetscScalar *x;
  const PetscInt     nm = h->nm, nc = h->nc;
  PetscReal         *Xo;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(nc, &Xo));
  PetscCall(VecGetArrayRead(a, &x));
  for (PetscInt o = 0; o < h->nout; o++) {
    for (PetscInt k = 0; k < nc; k++) {
      PetscReal s = 0.0;
      for (PetscInt i = 0; i < nm; i++) s += h->Phiout[o * nm + i] * PetscRealPart(x[k * nm + i]);
      Xo[k] = s;
      if (X) X[o * nc + k] = s;
    }
    if (amp) amp[o] = PetscSqrtReal(Xo[1] * Xo[1] + Xo[2] * Xo[2]);
    if (pp) {
      const PetscInt ns = 16 * nc;
      PetscReal      lo = PETSC_MAX_REAL, hi = -PETSC_MAX_REAL;
      if (!h->pptab) { /* sin and cos of every harmonic at the ns samples, once */
        PetscCall(PetscMalloc1(ns * (nc - 1), &h->pptab));
        for (PetscInt j = 0; j < ns; j++)
          for (PetscInt hh = 1; 2 * hh < nc; hh++) {
            const PetscReal th = 2.0 * PETSC_PI * j / ns;
            h->pptab[j * (nc - 1) + 2 * hh - 2] = PetscSinReal(hh * th);
            h->pptab[j * (nc - 1) + 2 * hh - 1] = PetscCosReal(hh * th);
          }
      }
      for (PetscInt j = 0; j < ns; j++) {
        const PetscReal *sc = h->pptab + j * (nc - 1);
        PetscReal        v  = Xo[0];
        for (PetscInt hh = 1; 2 * hh < nc; hh++) v += Xo[2 * hh - 1] * sc[2 * hh - 2] + Xo[2 * hh] * sc[2 * hh - 1];
        lo = PetscMin(lo, v);
        hi = PetscMax(hi, v);
      }
      pp[o] = 0.5 * (hi - lo);
    }
  }
  PetscCall(VecRestoreArrayRead(a, &x));
  PetscCall(PetscFree(Xo));
  PetscFunctionReturn(0);
}

/* The work per cycle [J] at the modal unknowns x of this rank's elements (all of them if h->repl): of each one's
   tangential force through its tangential motion and of its normal load through its normal motion; in E[] by the
   model's element numbering if E is not NULL, and summed in *sum */
static PetscErrorCode LocalWork(JRHBM h, const PetscScalar *x, PetscReal E[], PetscReal *sum)
{
  const PetscInt nm = h->nm, nc = h->nc;

  PetscFunctionBeginUser;
  *sum        = 0;
  h->cache_ok = PETSC_FALSE;
  for (PetscInt t = 0; t < h->ngroups; t++) {
    JRHBMGroup    *g = &h->g[t];
    const PetscInt n = g->nloc;
    if (!n) continue;
    PetscCall(JRGemm("N", "N", n, nc, nm, 1.0, g->R, n, x, nm, 0.0, g->U, n));
    if (g->normal) PetscCall(JRGemm("N", "N", n, nc, nm, 1.0, g->S, n, x, nm, 0.0, g->V, n));
    PetscCall(JRContactEvaluate(g->c, g->U, g->V, g->F, g->normal ? g->N : NULL, NULL, NULL, NULL, NULL));
    for (PetscInt e = 0; e < n; e++) {
      PetscReal w = 0;
      for (PetscInt hh = 1; 2 * hh < nc; hh++) {
        w += PETSC_PI * hh * (g->U[(2 * hh - 1) * n + e] * g->F[2 * hh * n + e] - g->U[2 * hh * n + e] * g->F[(2 * hh - 1) * n + e]);
        if (g->normal) w += PETSC_PI * hh * (g->V[(2 * hh - 1) * n + e] * g->N[2 * hh * n + e] - g->V[2 * hh * n + e] * g->N[(2 * hh - 1) * n + e]);
      }
      if (E) E[g->eidx[e]] = w;
      *sum += w;
    }
  }
  PetscFunctionReturn(0);
}

/*
  JRHBMEnergy - energy per cycle [J]: Win put in by the excitation, Edamp dissipated by the linear
  damping, Enl dissipated by the elements (integral of f du over a cycle, summed; collective).
  At a solution Win = Edamp + Enl (energy balance).
*/
PetscErrorCode JRHBMEnergy(JRHBM h, PetscReal w, Vec a, PetscReal *Win, PetscReal *Edamp, PetscReal *Enl)
{
  const PetscScalar *x;
  const PetscInt     nm = h->nm, nc = h->nc;
  PetscReal          ein = 0.0, ed = 0.0, enl = 0.0, tot;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(a, &x));
  /* excitation F fm sin(w t) on the modal coordinates: W = pi (as . Fc - ac . Fs) = -pi F fm . ac_1 */
  for (PetscInt i = 0; i < nm; i++) ein += -PETSC_PI * h->level * h->fm[i] * PetscRealPart(x[2 * nm + i]);
  /* linear damping force B_h a with B_h = gamma Km + h w Cm: W = pi h (as.B as + ac.B ac) */
  for (PetscInt hh = 1; 2 * hh < nc; hh++) {
    const PetscScalar *as = x + (2 * hh - 1) * nm, *ac = x + 2 * hh * nm;
    for (PetscInt i = 0; i < nm; i++)
      for (PetscInt j = 0; j < nm; j++) {
        const PetscReal b = h->gamma * h->Kg[i * nm + j] + hh * w * h->Cm[i * nm + j];
        ed += PETSC_PI * hh * b * (PetscRealPart(as[i]) * PetscRealPart(as[j]) + PetscRealPart(ac[i]) * PetscRealPart(ac[j]));
      }
  }
  /* elements: sum of the work of f through u (and of the normal load through v) */
  PetscCall(LocalWork(h, x, NULL, &enl));
  PetscCall(VecRestoreArrayRead(a, &x));
  if (h->repl) tot = enl;
  else {
    PetscCallMPI(MPI_Reduce(&enl, &tot, 1, MPIU_REAL, MPIU_SUM, 0, h->comm));
    PetscCallMPI(MPI_Bcast(&tot, 1, MPIU_REAL, 0, h->comm));
  }
  *Win   = ein;
  *Edamp = ed;
  *Enl   = tot;
  PetscFunctionReturn(0);
}

/*
  JRHBMElementDissipation - the energy each element dissipates per cycle [J] at the solution a (the work of its
  tangential force through its tangential motion and of its normal load through its normal motion), for every element
  of the model (its numbering), on every rank (collective)
*/
PetscErrorCode JRHBMElementDissipation(JRHBM h, Vec a, PetscReal E[])
{
  const JRElements  *el;
  const PetscScalar *x;
  PetscReal          sum;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetElements(h, &el));
  PetscCall(PetscArrayzero(E, el->n));
  PetscCall(VecGetArrayRead(a, &x));
  PetscCall(LocalWork(h, x, E, &sum));
  PetscCall(VecRestoreArrayRead(a, &x));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, E, (PetscMPIInt)el->n, MPIU_REAL, MPIU_SUM, h->ecomm));
  PetscFunctionReturn(0);
}

/* Every local element's contact state over the cycle at the solution a, in g->state */
static PetscErrorCode EvaluateStates(JRHBM h, Vec a)
{
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(a, &x));
  h->cache_ok = PETSC_FALSE;
  for (PetscInt t = 0; t < h->ngroups; t++) {
    JRHBMGroup *g = &h->g[t];
    if (!g->nloc) continue;
    PetscCall(JRGemm("N", "N", g->nloc, h->nc, h->nm, 1.0, g->R, g->nloc, x, h->nm, 0.0, g->U, g->nloc));
    if (g->normal) PetscCall(JRGemm("N", "N", g->nloc, h->nc, h->nm, 1.0, g->S, g->nloc, x, h->nm, 0.0, g->V, g->nloc));
    PetscCall(JRContactEvaluate(g->c, g->U, g->V, NULL, NULL, NULL, NULL, NULL, g->state));
  }
  PetscCall(VecRestoreArrayRead(a, &x));
  PetscFunctionReturn(0);
}

/*
  JRHBMKineticEnergy - the kinetic energy averaged over a cycle [J], (1/4) sum_h (h w)^2 (as_h^T M as_h +
  ac_h^T M ac_h): with the energy dissipated per cycle E it gives the equivalent damping ratio
  zeta = E / (8 pi T) (= gamma / 2 for structural damping at resonance).
*/
PetscErrorCode JRHBMKineticEnergy(JRHBM h, PetscReal w, Vec a, PetscReal *T)
{
  const PetscScalar *x;
  const PetscInt     nm = h->nm;
  PetscReal          t  = 0.0;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(a, &x));
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    const PetscScalar *as = x + (2 * hh - 1) * nm, *ac = x + 2 * hh * nm;
    PetscReal          q  = 0.0;
    for (PetscInt i = 0; i < nm; i++)
      for (PetscInt j = 0; j < nm; j++) q += h->Mm[i * nm + j] * (PetscRealPart(as[i]) * PetscRealPart(as[j]) + PetscRealPart(ac[i]) * PetscRealPart(ac[j]));
    t += 0.25 * (hh * w) * (hh * w) * q;
  }
  PetscCall(VecRestoreArrayRead(a, &x));
  *T = t;
  PetscFunctionReturn(0);
}

/*
  JRHBMElementStates - the contact state of every element of the model (its numbering) at the solution
  a, gathered on rank 0 (state: the model's element count; other ranks may pass NULL; collective)
*/
PetscErrorCode JRHBMElementStates(JRHBM h, Vec a, JRContactState state[])
{
  PetscInt     nloc = 0, k = 0, *buf, ntot = 0;
  PetscMPIInt *counts = NULL, *displs = NULL, sendc;
  PetscInt    *all = NULL;

  PetscFunctionBeginUser;
  PetscCall(EvaluateStates(h, a));
  for (PetscInt t = 0; t < h->ngroups; t++) nloc += h->g[t].nloc;
  PetscCall(PetscMalloc1(2 * nloc, &buf));
  for (PetscInt t = 0; t < h->ngroups; t++)
    for (PetscInt e = 0; e < h->g[t].nloc; e++, k++) {
      buf[2 * k]     = h->g[t].eidx[e];
      buf[2 * k + 1] = (PetscInt)h->g[t].state[e];
    }
  PetscCall(PetscMPIIntCast(2 * nloc, &sendc));
  if (!h->rank) PetscCall(PetscMalloc2(h->size, &counts, h->size, &displs));
  PetscCallMPI(MPI_Gather(&sendc, 1, MPI_INT, counts, 1, MPI_INT, 0, h->comm));
  if (!h->rank) {
    for (PetscMPIInt r = 0; r < h->size; r++) {
      displs[r] = (PetscMPIInt)ntot;
      ntot += counts[r];
    }
    PetscCall(PetscMalloc1(ntot, &all));
  }
  PetscCallMPI(MPI_Gatherv(buf, sendc, MPIU_INT, all, counts, displs, MPIU_INT, 0, h->comm));
  if (!h->rank)
    for (PetscInt i = 0; i < ntot / 2; i++) state[all[2 * i]] = (JRContactState)all[2 * i + 1];
  PetscCall(PetscFree(all));
  if (!h->rank) PetscCall(PetscFree2(counts, displs));
  PetscCall(PetscFree(buf));
  PetscFunctionReturn(0);
}

/* How many elements are in each contact state at the solution a (collective, every rank) */
PetscErrorCode JRHBMContactStates(JRHBM h, Vec a, PetscInt count[4])
{
  PetscInt loc[4] = {0, 0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(EvaluateStates(h, a));
  for (PetscInt t = 0; t < h->ngroups; t++)
    for (PetscInt e = 0; e < h->g[t].nloc; e++) loc[h->g[t].state[e]]++;
  PetscCall(MPIU_Allreduce(loc, count, 4, MPIU_INT, MPI_SUM, h->ecomm));
  PetscFunctionReturn(0);
}
