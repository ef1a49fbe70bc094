/*
   Stability by incremental dissipativity (docs/theory.md, section 16): a certificate that needs no eigenproblem.

   Take two motions q1, q2 of the modal equations (section 14's time-domain form)

     Mm q'' + Cv q' + Kg q + sum_e r_e f_e = F fm sin(w t),   Cv = Cm + (gamma / w) Kg,

   with jenkins elements f = kt (u - s), |f| <= mu n0, the slip s moving only while |f| = mu n0 and then in the
   direction of f (the play operator, section 2). With dq = q1 - q2, df = f1 - f2, ds = s1 - s2,

     E = 1/2 dq'^T Mm dq' + 1/2 dq^T Kg dq + sum_e df_e^2 / (2 kt_e)
     dE/dt = -dq'^T Cv dq' - sum_e df_e ds_e' <= 0,

   since df ds' = f1 s1' - f1 s2' - f2 s1' + f2 s2' >= mu n0 (|s1'| - |s2'| - |s1'| + |s2'|) = 0 (maximum dissipation:
   f1 s1' = mu n0 |s1'| >= |f1 s2'|). So when Mm is symmetric positive definite and Kg and the symmetric part of Cv
   positive semi-definite, no perturbation of any response grows: every periodic response is stable, no Floquet
   exponent has a positive real part, and (with Cv > 0) the periodic response to a given force is unique. This holds
   for the truncated modal system itself, whatever the harmonics and the stick-slip pattern, and decides exactly
   what Hill's method (hill.c) only approximates for these elements: its periodic Jacobian does not hold the slip's
   memory of the last reversal that an exp(lambda t) perturbation moves.

   A jenkins_nv element (normal load n0 + kn v, separation) is not monotone in this sense: its slip limit depends
   on the motion. At a point where every jenkins_nv element is stuck over the whole cycle (or separated over it),
   a small perturbation keeps it so, it acts as the linear springs kt, kn (or not at all), and the certificate
   holds at that point. Cubic springs (smooth; a hardening one has unstable branches) are left to Hill's method,
   which is exact for them up to truncation.
*/
#include <jointrom/private/hbmimpl.h>

/* The relative asymmetry of A (n x n) and the extreme eigenvalues of its symmetric part */
static PetscErrorCode SymmetricPart(PetscInt n, const PetscReal *A, PetscReal *asym, PetscReal *emin, PetscReal *emax)
{
  PetscReal   *S, *ev, *work, amax = 0.0, dmax = 0.0;
  PetscBLASInt bn, lwork, info;

  PetscFunctionBeginUser;
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCall(PetscBLASIntCast(4 * n, &lwork));
  PetscCall(PetscMalloc3(n * n, &S, n, &ev, 4 * n, &work));
  for (PetscInt i = 0; i < n; i++)
    for (PetscInt j = 0; j < n; j++) {
      S[i + j * n] = 0.5 * (A[i * n + j] + A[j * n + i]);
      amax         = PetscMax(amax, PetscAbsReal(A[i * n + j]));
      dmax         = PetscMax(dmax, PetscAbsReal(A[i * n + j] - A[j * n + i]));
    }
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("N", "U", &bn, S, &bn, ev, work, &lwork, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed (info %d)", (int)info);
  *asym = amax > 0 ? dmax / amax : 0.0;
  *emin = n ? ev[0] : 0.0;
  *emax = n ? ev[n - 1] : 0.0;
  PetscCall(PetscFree3(S, ev, work));
  PetscFunctionReturn(0);
}

/* The model's part of the certificate, once: h->dissip (see hbmimpl.h) and h->fric. Collective. */
static PetscErrorCode ModelDissipative(JRHBM h)
{
  const PetscReal tol = 1e-8;
  PetscInt        kinds[3] = {0, 0, 0}, all[3]; /* elements other than jenkins (or with negative kt, mu); jenkins_nv ones; friction ones */
  PetscInt        lin = 0;

  PetscFunctionBeginUser;
  if (h->dissip) PetscFunctionReturn(0);
  for (PetscInt t = 0; t < h->ngroups; t++) {
    const JRHBMGroup *g  = &h->g[t];
    const PetscBool   nv = (PetscBool)!strcmp(g->c->type_name, JRCONTACTJENKINSNV);
    if (!g->nloc) continue;
    if (nv) kinds[1] = 1;
    else if (strcmp(g->c->type_name, JRCONTACTJENKINS)) kinds[0] = 1;
    if (strcmp(g->c->type_name, JRCONTACTCUBIC)) kinds[2] = 1;
    for (PetscInt e = 0; e < g->nloc; e++)
      if (g->c->kt[e] < 0 || g->c->mu[e] < 0 || (nv && g->c->kn[e] < 0)) kinds[0] = 1;
  }
  PetscCall(MPIU_Allreduce(kinds, all, 3, MPIU_INT, MPI_MAX, h->comm));
  if (!h->rank) { /* the linear part: Mm > 0, Kg >= 0 symmetric, Cm + (gamma / w) Kg >= 0 (symmetric part) */
    PetscReal as, lo, hi;
    lin = 1;
    PetscCall(SymmetricPart(h->nm, h->Mm, &as, &lo, &hi));
    if (as > tol || !(lo > tol * hi)) lin = 0;
    PetscCall(SymmetricPart(h->nm, h->Kg, &as, &lo, &hi));
    if (as > tol || lo < -tol * PetscAbsReal(hi)) lin = 0;
    if (h->gamma < 0) lin = 0;
    if (h->Cm) {
      PetscCall(SymmetricPart(h->nm, h->Cm, &as, &lo, &hi));
      if (lo < -tol * PetscAbsReal(hi)) lin = 0;
    }
  }
  PetscCallMPI(MPI_Bcast(&lin, 1, MPIU_INT, 0, h->comm));
  h->dissip = (!lin || all[0]) ? 1 : all[1] ? 3 : 2;
  h->fric   = (PetscBool)(all[2] != 0);
  PetscFunctionReturn(0);
}

/*
  JRHBMStabilityVerdict - what decides the stability of the response a (solve space) of the JRHBM: with certify, the
  incremental dissipativity above where it holds (JR_STABILITY_DISSIPATIVE: the point is stable, nothing to solve);
  otherwise JR_STABILITY_HILL_HYSTERETIC when the model has friction elements (at a point where the certificate was
  asked for, some element changes state over the cycle: Hill's method there indicates, it does not decide; the
  monodromy matrix in time decides) and JR_STABILITY_HILL for smooth elements only (cubic; Hill's method is exact up
  to truncation). Collective; the same answer on every rank.
*/
PetscErrorCode JRHBMStabilityVerdict(JRHBM h, Vec a, PetscBool certify, JRStabilityVerdict *v)
{
  PetscInt changing = 0, any;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(ModelDissipative(h));
  *v = h->fric ? JR_STABILITY_HILL_HYSTERETIC : JR_STABILITY_HILL;
  if (!certify || h->dissip == 1) PetscFunctionReturn(0);
  if (h->dissip == 2) {
    *v = JR_STABILITY_DISSIPATIVE;
    PetscFunctionReturn(0);
  }
  {
    const PetscScalar *x;
    PetscCall(VecGetArrayRead(a, &x));
    h->cache_ok = PETSC_FALSE;
    for (PetscInt t = 0; t < h->ngroups && !changing; t++) {
      JRHBMGroup *g = &h->g[t];
      if (!g->nloc || strcmp(g->c->type_name, JRCONTACTJENKINSNV)) continue;
      PetscCall(JRHBMGroupMotion(h, g, x)); /* a: the solve space's unknowns, modal or condensed */
      PetscCall(JRContactEvaluate(g->c, g->U, g->V, NULL, NULL, NULL, NULL, NULL, g->state));
      for (PetscInt e = 0; e < g->nloc; e++)
        if (g->state[e] != JR_CONTACT_FULL_STICK && g->state[e] != JR_CONTACT_FULL_SEPARATION) changing = 1;
    }
    PetscCall(VecRestoreArrayRead(a, &x));
  }
  PetscCall(MPIU_Allreduce(&changing, &any, 1, MPIU_INT, MPI_MAX, h->comm));
  if (!any) *v = JR_STABILITY_DISSIPATIVE;
  PetscFunctionReturn(0);
}

/*
  JRHBMStabilityCheap - whether deciding the stability of every point (JRContStability) costs little next to the
  curve: the model is incrementally dissipative at every point (every element jenkins: one LU per point), or it has
  friction elements and no cubic spring (the monodromy matrix in time, its fast modes condensed: 1.3-1.9 times the
  curve's solve on the FE models of docs/performance.md; on a model condensed onto its joints, whose curve is far
  cheaper, through the joints' few distinct rows, at about that curve's cost again), or with a cubic spring the
  monodromy matrix (RK4) has at most 64 states (2 kept modes + friction elements), or, with smooth elements only,
  Hill's problem has at most 128 unknowns. size: the monodromy's state or Hill's problem's size (0 where it is cheap
  for any size). Collective.
*/
PetscErrorCode JRHBMStabilityCheap(JRHBM h, PetscBool *cheap, PetscInt *size)
{
  PetscInt ne = 0, all, nk = 0, ncub = 0, anycub;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(ModelDissipative(h));
  *size  = 0;
  *cheap = PETSC_TRUE;
  if (h->dissip == 2) PetscFunctionReturn(0);
  if (!h->fric && !h->cond) {
    *size  = 2 * h->nm * h->nc;
    *cheap = (PetscBool)(*size <= 128);
    PetscFunctionReturn(0);
  }
  for (PetscInt t = 0; t < h->ngroups && (!h->repl || !h->rank); t++) {
    if (strcmp(h->g[t].c->type_name, JRCONTACTCUBIC)) ne += h->g[t].nloc;
    else ncub += h->g[t].nloc;
  }
  PetscCall(MPIU_Allreduce(&ncub, &anycub, 1, MPIU_INT, MPI_SUM, h->comm));
  if (!anycub) PetscFunctionReturn(0);
  PetscCall(MPIU_Allreduce(&ne, &all, 1, MPIU_INT, MPI_SUM, h->comm));
  for (PetscInt i = 0; i < h->nm; i++)
    if (!h->pin || h->pin[i] == 0.0) nk++;
  *size  = 2 * nk + all;
  *cheap = (PetscBool)(!h->cond && *size <= 64);
  PetscFunctionReturn(0);
}
