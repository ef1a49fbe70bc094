/*
   Floquet exponents of a periodic response with hysteretic elements, in the time domain (docs/theory.md, section 16).

   Hill's method (hill.c) puts exp(lambda t) p(t) into the periodic Jacobian dR/da. For a friction element that
   Jacobian is the derivative of the steady periodic force: while stuck, df(t) = kt (du(t) - du(t_r)), t_r the start
   of the stick phase, a memory that an exp(lambda t) perturbation scales by exp(lambda t_r), not exp(lambda t), so
   Hill's quadratic problem is not the linearisation for such elements. Here the linearisation itself is marched over
   one period: the variational equations of the modal equations (section 14's time-domain form, the kept modes),

     Mm dq'' + Cv dq' + (Km - Kc) dq + sum_e r_e df_e + sum_e s_e dn_e = 0,   Cv = Cm + (gamma / w) Kg,

   with each element's force linearised about the harmonic-balance motion, marched as the play operator: the slip
   w <- clamp(w, u - mu n / kt, u + mu n / kt) committed at the end of every step, and a return map from the committed
   slip, whose derivative is dw (the committed one, stuck), du -+ mu kn dv / kt (slipping at the upper or lower bound,
   kn for jenkins_nv in contact, else 0); df = kt (du - dw), dn = kn dv in contact (jenkins_nv), and df = 3 kt u^2 du
   for a cubic spring. The state (dq, dq', dw) has 2 nk + ne entries (ne friction elements); its fundamental matrix
   after one period T is the monodromy matrix, whose eigenvalues rho are the Floquet multipliers: exponents
   log(rho) / T. A stuck element's slip is a neutral state (rho = 1): a perturbed slip stays.

   With friction elements only (MarchPatterns), the elements' states over a step are those of the play operator on
   the steps' ends, and the equations over a step are linear with constant coefficients: the step's map is the
   exponential of their matrix (a Taylor polynomial, dt w_max <= 1, w_max the stiffest mode with every element
   stuck), kept by the states' pattern, which mostly repeats over a period; a step where a state changes gets the
   map of the two states weighted by their shares. The pattern's stiffness is updated by the elements whose state
   changes. Only the slips of elements that change state over the period are marched (Classify), and a slip is
   committed only where it will be read: where its element sticks or reverses within the next step, and at the
   period's end. With a cubic spring (MarchRK4) the march is RK4 (dt w_max <= 0.5) with the states at every stage.
   At least the harmonic balance's samples per period either way.

   Fast modes (JRHBMSetFloquetFast: the kept modes whose own frequency exceeds a multiple of H w and whose damping
   makes them decay within a period; an FE model's interface correction vectors, 10^4-10^5 Hz beside a 100 Hz
   resonance) are condensed quasi-statically for each step's pattern (QuasiStatic, Guyan's reduction with the
   pattern's stiffness): their inertia is dropped, the slow modes carry the rest, and the map is the exponential of
   the slow modes' equations, whose stiffest mode sets far fewer squarings. The exponents change by about
   (w / w_fast)^2 (test_stability); the fast modes' own exponents are not computed. Where the elements' rows are a
   few distinct ones, or combinations of a few (a reduced model's joints), each step's condensation follows from one
   factorisation per point by the Woodbury identity (LowRankPoint, LowRankStatic).
   Every rank holds every element (gathered once); JRHBMFloquetTime marches one point on rank 0 and broadcasts,
   JRHBMFloquetTimePoints shares a level's points out over the ranks.
*/
#include <jointrom/private/hbmimpl.h>

struct _JRMonodromy {
  PetscInt   ne, nk, m, ns;           /* elements (all ranks), kept modes, state size 2 nk + ne, steps per period */
  PetscInt  *type;                    /* 0 jenkins, 1 jenkins_nv, 2 cubic */
  PetscInt  *mem;                     /* each element's slip in the state (2 nk + mem[e]), -1 for a cubic spring */
  PetscReal *kt, *kn, *mu, *n0;       /* ne each */
  PetscReal *Ra, *Sa;                 /* ne x nm column-major: the rows over every mode (the point's motion) */
  PetscInt   l, *srow;                /* l = ne + the jenkins_nv elements; each element's normal row in RS (-1: none) */
  PetscReal *RS;                      /* l x nk column-major: [r_e; s_e of jenkins_nv] over the kept modes (the perturbation) */
  PetscReal *MRS;                     /* nk x l: -Mm^-1 [R^T S^T] */
  PetscReal *K, *C, *Kg, *Mi, *G;     /* nk x nk column-major: Km - Kc, Cm, Kg, Mm^-1; G = -Mm^-1 [K, Cv] (nk x 2 nk) */
  PetscReal  wmax;                    /* the stiffest mode with every element stuck [rad/s] */
  PetscReal *u, *v, *wn;              /* the point's motion at the half steps (ne x (2 ns + 1)), committed slip (ne x (ns + 1)) */
  PetscReal *rb, *nb;                 /* the slip bound mu n / kt and the normal load n at the half steps (ne x (2 ns + 1)) */
  unsigned char *sde, *cnt;           /* each element's side + 1 at the steps' ends against the committed slip (ne x ns: step
                                         j's end at sde[e ns + j]), and in contact (jenkins_nv, n > 0) at the half steps
                                         (ne x (2 ns + 1)), of the point's motion */
  PetscReal *Y, *Y0, *Ys, *DUV, *DFN, *Wc; /* the march's work: DUV = [du; dv], DFN = [df; dn] (max(l, 2 ne, nk) x m) */
  PetscReal *ev, *wr, *wi, *work;
  PetscBLASInt lwork;
  PetscBool  smooth;                  /* a cubic spring: its stiffness follows the motion within a step (RK4 march) */
  PetscInt   nslot, next;             /* step maps kept, and the slot the next new one takes */
  unsigned char *key, *slotkey;       /* the current step's pattern (ne), each kept map's (JR_MONO_SLOTS x ne) */
  unsigned char *ka, *kb;             /* a step's states of each element before and after a change within it */
  PetscReal     *th;                  /* the share of the step in state ka (ne) */
  PetscInt      *cls, *memp, mt;      /* per point: each element's class (JR_MONO_TRACK, _HOLD, _FORGET) and its slip's
                                         row among the tracked ones (-1: not tracked); the state's size 2 nk + tracked */
  PetscInt      *tel;                 /* per point: each tracked slip's element */
  PetscInt       np;                  /* per point: the tracked slips never read before their first commit (the last np) */
  PetscBool      unread;              /* leave those out of the march (JRHBMSetFloquetUnread) */
  unsigned char *lka, *lkb;           /* each element's states at the last StiffnessUpdate (valid where svalid) */
  PetscReal     *lth;
  PetscBool      svalid;
  PetscInt      *chg, nchg;           /* the step's elements whose states differ from those (all where not svalid) */
  PetscReal *SL, *SW;                 /* the kept step maps: n2 x n2 and n2 x ne each, n2 = 2 nk; SW's columns those of the
                                         held slips of stuck elements only (the others' are 0) */
  PetscInt  *ncol, *cols;             /* per kept map: those columns' number and their slips (JR_MONO_SLOTS + 1, x ne) */
  PetscReal *XL, *XW, *T2;            /* the step map's work (n2 x n2, n2 x ne), the march's (n2 x m) */
  PetscReal *trig;                    /* the harmonics at the half steps, 1, sin, cos of h w t (nc x (2 ns + 1)), and the
                                         elements' coefficients of u and v (ne x nc each) */
  PetscReal *PS;                      /* the exponential's work (5 n2 x n2: four for the polynomials, phi1's columns G) */
  PetscBLASInt *piv;                  /* a small LU's pivots (n2: Mr's, Aref_ff's) */
  PetscReal *RT;                      /* per point: the tracked elements' rows [r_e; s_e] over the kept modes (2 nt x nk) */
  /* the fast modes' quasi-static condensation (JRHBMSetFloquetFast; QuasiStatic) */
  PetscInt   nsl, nfa, n2r;           /* per point: slow and fast kept modes, the marched (q, q') size 2 nsl */
  PetscInt  *isl, *ifa;               /* their indices among the kept modes */
  PetscReal *Mm, *Cv;                 /* nk x nk column-major: the modal mass, the damping at the point's frequency */
  PetscReal *QW;                      /* the condensation's work (9 nk x nk + 4 nk x ne) */
  PetscReal *MCb;                     /* per point: Mm's and Cv's blocks over the slow and fast modes, ss, sf, fs, ff
                                         (PointBlocks; nk x nk each) */
  PetscBool  mcdiag[2];               /* per point: Mm, Cv diagonal (their blocks ss, ff then diagonals, sf, fs 0) */
  PetscReal *Ts, *KFs, *bws;          /* per kept map: the modes over the slow ones T (nk x nsl, stride nk nk), Kff^-1
                                         (nfa x nfa, stride nk nk), the held slips' stiffness (Bw = [r_e kt], nt, stride cap) */
  PetscBLASInt *pivs;                 /* per kept map: Kff's pivots (stride nk) */
  PetscReal *KFc, *XZc, *WB;          /* of the last condensation: Kff^-1 (nfa x nfa), X = -Kff^-1 Kfs and Z = Kff^-T Ksf^T
                                         (nfa x nsl each); their update's work (3 nk x nk) */
  PetscBool  kfvalid, wood;           /* KFc is that of Kp before the last StiffnessUpdate; update it (JRHBMSetFloquetWoodbury) */
  PetscInt   nupd, nwood, nwtot;      /* that update's columns (Kp += A V^T, in DUV), KFc's updates since its inverse, and
                                         at the point */
  PetscReal *Rfa, *bwt;               /* per point: the tracked elements' r over the fast modes (nfa x nt); the step's held
                                         slips' stiffness (nt) */
  PetscInt   cap;                     /* the tracked elements bws, Rfa, bwt have room for */
  PetscReal *RSt, *cf, *cfn, *Kp;     /* [R; S]^T (nk x l); each element's stiffness coefficients (3 ne: kt r r^T, r s^T,
                                         kn s s^T) in Kp = K + sum (...) (nk x nk), and the next step's; Kp is updated by the
                                         elements whose coefficients change (kvalid) */
  PetscBool  kvalid;
  PetscReal *CB, *Rg;                 /* the commits' work (2 cap x (2 nk + cap)), the committing rows (2 ne x nk) */
  PetscInt  *rows;                    /* the committing rows: u row (2 q) or v row (2 q + 1) of tracked slip q */
  PetscReal *sdr;                     /* each committing element's side x d(mu n / kt)/dv */
  /* the fast modes condensed through the elements' distinct rows (LowRankPoint, LowRankStatic): where the rows [R; S]
     are a few nd distinct ones Rd (elements sharing a joint's motion), Kp = Aref + Rd^T dD Rd with Aref the stiffness
     with every element stuck in contact, and Kff^-1 follows from Aref_ff^-1 once per point by the Woodbury identity */
  PetscInt   nd, *dr, *td;            /* distinct rows (0: too many), each of the l rows' distinct one (-1: the rows are
                                         combinations of Rd, coefficients in Cf), per point each tracked row (2 nt) */
  PetscReal *Cf;                      /* where the rows are combinations of Rd: each row's coefficients (l x nd, row-major) */
  PetscReal *Rd, *cref, *Aref;        /* nd x nk (row-major: row d at Rd + d nk); the reference coefficients (3 ne);
                                         K + Rd^T Dref Rd (nk x nk) */
  PetscBool  lowrank;                 /* this point uses them */
  PetscInt   lrnsl, *lrkey;           /* the slow modes of the split LowRankPoint's pieces are for (-1: none yet) */
  PetscReal *dDk, *cl;                /* per point: dD (nd x nd) of the coefficients cl (3 ne), updated by the elements whose
                                         coefficients change (dvalid) */
  PetscBool  dvalid;
  PetscReal *LR, *LW;                 /* per point: U, G, W, Rs, K0, KU, M0, Ma, Mb, Mc, C0, Ca, Cb, Cc; per step: work */
  PetscBLASInt *lpiv;                 /* the per-step LU's pivots (nd) */
};

#define JR_MONO_SLOTS  16 /* step maps kept per point: a period's stick-slip patterns mostly repeat */
#define JR_MONO_TAYLOR 8   /* terms of the step map's Taylor polynomial: error (w_max dt)^9 / 9! <= 3e-6 per step */
#define JR_MONO_WDT    1.0 /* the Taylor polynomial's dt w_max at most: larger steps are halved and the map squared */
#define JR_MONO_WOOD   16  /* Kff^-1 updated by the Woodbury identity at most this many times before a new inverse */
/* an element's slip over a point's period: it changes state (tracked), or it is stuck throughout (held: its slip a
   neutral state, multiplier 1), or it slips at every step (forgotten at every step: multiplier 0) */
enum {
  JR_MONO_TRACK,
  JR_MONO_HOLD,
  JR_MONO_FORGET
};

/* Free the time-domain Floquet work (JRHBMDestroy) */
PetscErrorCode JRHBMMonodromyDestroy(JRHBM h)
{
  struct _JRMonodromy *f = h->mono;

  PetscFunctionBeginUser;
  if (!f) PetscFunctionReturn(0);
  PetscCall(PetscFree5(f->type, f->kt, f->kn, f->mu, f->n0));
  PetscCall(PetscFree2(f->mem, f->srow));
  PetscCall(PetscFree4(f->Ra, f->Sa, f->RS, f->MRS));
  PetscCall(PetscFree5(f->K, f->C, f->Kg, f->Mi, f->G));
  PetscCall(PetscFree5(f->u, f->v, f->wn, f->rb, f->nb));
  PetscCall(PetscFree2(f->sde, f->cnt));
  PetscCall(PetscFree3(f->Y, f->Y0, f->Ys));
  PetscCall(PetscFree3(f->DUV, f->DFN, f->Wc));
  PetscCall(PetscFree4(f->ev, f->wr, f->wi, f->work));
  PetscCall(PetscFree4(f->key, f->slotkey, f->SL, f->SW));
  PetscCall(PetscFree3(f->XL, f->XW, f->T2));
  PetscCall(PetscFree(f->trig));
  PetscCall(PetscFree3(f->ka, f->kb, f->th));
  PetscCall(PetscFree3(f->cls, f->memp, f->tel));
  PetscCall(PetscFree4(f->lka, f->lkb, f->lth, f->chg));
  PetscCall(PetscFree2(f->ncol, f->cols));
  PetscCall(PetscFree3(f->PS, f->piv, f->RT));
  PetscCall(PetscFree5(f->isl, f->ifa, f->Mm, f->Cv, f->QW));
  PetscCall(PetscFree(f->MCb));
  PetscCall(PetscFree4(f->Ts, f->KFs, f->bws, f->pivs));
  PetscCall(PetscFree3(f->KFc, f->XZc, f->WB));
  PetscCall(PetscFree2(f->Rfa, f->bwt));
  PetscCall(PetscFree4(f->RSt, f->Kp, f->Rg, f->rows));
  PetscCall(PetscFree(f->CB));
  PetscCall(PetscFree2(f->cf, f->cfn));
  PetscCall(PetscFree(f->sdr));
  PetscCall(PetscFree4(f->dr, f->td, f->lpiv, f->lrkey));
  PetscCall(PetscFree5(f->Rd, f->cref, f->Aref, f->LR, f->LW));
  PetscCall(PetscFree2(f->dDk, f->cl));
  PetscCall(PetscFree(f->Cf));
  PetscCall(PetscFree(h->mono));
  PetscFunctionReturn(0);
}

/* Where the l rows of RSt are not a few distinct ones: a basis Rd of their span (a reduced model whose elements move
   with their joints' fields: a few rows per joint) by the SVD of the rows (singular values below 1e-10 of the largest
   dropped), nd of them, and each row's coefficients Cf on it; f->nd = 0 if more than nk / 2 or a row is not in the
   span to 1e-10 of the largest entry */
static PetscErrorCode RowBasis(struct _JRMonodromy *f, PetscReal **Rd)
{
  const PetscInt nk = f->nk, l = f->l, mn = PetscMin(nk, l);
  PetscReal     *A, *U, *sv, wq, *work, big = 0.0, dev = 0.0;
  PetscBLASInt   bn, bl, lwork = -1, info, one = 1;
  PetscInt       nd = 0;

  PetscFunctionBeginUser;
  f->nd = 0;
  PetscCall(PetscMalloc3(nk * l + 1, &A, nk * mn + 1, &U, mn + 1, &sv));
  PetscCall(PetscArraycpy(A, f->RSt, nk * l)); /* column r: row r (nk x l, column-major) */
  PetscCall(PetscBLASIntCast(nk, &bn));
  PetscCall(PetscBLASIntCast(l, &bl));
  PetscCallBLAS("LAPACKgesvd", LAPACKgesvd_("S", "N", &bn, &bl, A, &bn, sv, U, &bn, NULL, &one, &wq, &lwork, &info));
  PetscCall(PetscBLASIntCast((PetscInt)wq + 1, &lwork));
  PetscCall(PetscMalloc1(lwork, &work));
  PetscCallBLAS("LAPACKgesvd", LAPACKgesvd_("S", "N", &bn, &bl, A, &bn, sv, U, &bn, NULL, &one, work, &lwork, &info));
  PetscCall(PetscFree(work));
  if (!info && mn > 0 && sv[0] > 0)
    while (nd < mn && sv[nd] > 1e-10 * sv[0]) nd++;
  if (!info && nd && nd <= nk / 2) {
    PetscCall(PetscMalloc1(l * nd, &f->Cf));
    for (PetscInt d = 0; d < nd; d++)
      for (PetscInt i = 0; i < nk; i++) (*Rd)[d * nk + i] = U[i + d * nk];
    for (PetscInt r = 0; r < l; r++) { /* Rd orthonormal: c = Rd x */
      const PetscReal *x = f->RSt + r * nk;
      PetscReal       *c = f->Cf + r * nd;
      f->dr[r]           = -1;
      for (PetscInt d = 0; d < nd; d++) {
        c[d] = 0.0;
        for (PetscInt i = 0; i < nk; i++) c[d] += (*Rd)[d * nk + i] * x[i];
      }
      for (PetscInt i = 0; i < nk; i++) {
        PetscReal y = x[i];
        for (PetscInt d = 0; d < nd; d++) y -= c[d] * (*Rd)[d * nk + i];
        big = PetscMax(big, PetscAbsReal(x[i]));
        dev = PetscMax(dev, PetscAbsReal(y));
      }
    }
    if (dev > 1e-10 * big) PetscCall(PetscFree(f->Cf));
    else f->nd = nd;
  }
  PetscCall(PetscFree3(A, U, sv));
  PetscFunctionReturn(0);
}

/* The elements' distinct rows among the l rows of RSt (equal to 1e-12 of the larger), f->nd of them, or else a basis
   of their span (RowBasis), or f->nd = 0 where more than nk / 2 (the fast modes then condensed by Kff^-1 per step);
   with them the reference stiffness Aref = K + sum over the elements stuck in contact (kt r r^T + kn s s^T), symmetric
   where K is, else f->nd = 0 */
static PetscErrorCode DistinctRows(struct _JRMonodromy *f)
{
  const PetscInt nk = f->nk, ne = f->ne, l = f->l;
  PetscInt       nd = 0;
  PetscReal     *Rd, kmax = 0.0, asym = 0.0;

  PetscFunctionBeginUser;
  f->nd = 0;
  PetscCall(PetscMalloc4(l + 1, &f->dr, 2 * ne + 1, &f->td, nk + 1, &f->lpiv, nk + 1, &f->lrkey));
  f->lrnsl = -1;
  PetscCall(PetscMalloc1(nk * (nk / 2 + 1), &Rd));
  for (PetscInt r = 0; r < l && nd <= nk / 2; r++) {
    const PetscReal *a = f->RSt + r * nk;
    PetscInt         d;
    for (d = 0; d < nd; d++) {
      const PetscReal *b = Rd + d * nk;
      PetscReal        big = 0.0, diff = 0.0;
      for (PetscInt i = 0; i < nk; i++) {
        big  = PetscMax(big, PetscMax(PetscAbsReal(a[i]), PetscAbsReal(b[i])));
        diff = PetscMax(diff, PetscAbsReal(a[i] - b[i]));
      }
      if (diff <= 1e-12 * big) break;
    }
    if (d == nd) {
      if (nd == nk / 2) {
        nd++;
        break;
      }
      PetscCall(PetscArraycpy(Rd + nd * nk, a, nk));
      nd++;
    }
    f->dr[r] = d;
  }
  if (nd > nk / 2) {
    PetscCall(RowBasis(f, &Rd));
    nd = f->nd;
  }
  for (PetscInt j = 0; j < nk; j++)
    for (PetscInt i = 0; i < nk; i++) {
      kmax = PetscMax(kmax, PetscAbsReal(f->K[i + j * nk]));
      asym = PetscMax(asym, PetscAbsReal(f->K[i + j * nk] - f->K[j + i * nk]));
    }
  f->nd = 0;
  if (nd > nk / 2 || nd == 0 || asym > 1e-12 * kmax) {
    PetscCall(PetscFree(Rd));
    PetscCall(PetscFree(f->Cf));
    PetscFunctionReturn(0);
  }
  f->nd = nd;
  PetscCall(PetscMalloc5(nd * nk, &f->Rd, 3 * ne + 1, &f->cref, nk * nk, &f->Aref, 10 * nk * nk + 16 * nk * nd + 8 * nd * nd + 1, &f->LR, 12 * nd * nd + 8 * nd * nk + 4 * nd * ne + 1, &f->LW));
  PetscCall(PetscMalloc2(nd * nd, &f->dDk, 3 * ne + 1, &f->cl));
  PetscCall(PetscArraycpy(f->Rd, Rd, nd * nk));
  PetscCall(PetscFree(Rd));
  PetscCall(PetscArraycpy(f->Aref, f->K, nk * nk));
  for (PetscInt e = 0; e < ne; e++) {
    PetscReal       *c  = f->cref + 3 * e;
    const PetscReal *r = f->RSt + e * nk, *sv = f->srow[e] >= 0 ? f->RSt + f->srow[e] * nk : NULL;
    c[0] = f->kt[e];
    c[1] = 0.0;
    c[2] = sv ? f->kn[e] : 0.0;
    for (PetscInt j = 0; j < nk; j++)
      for (PetscInt i = 0; i < nk; i++) f->Aref[i + j * nk] += c[0] * r[i] * r[j] + (sv ? c[2] * sv[i] * sv[j] : 0.0);
  }
  PetscFunctionReturn(0);
}

/* Row r of the l rows in the basis Rd, times scale, into c (nd): a unit vector where it is a distinct row, else its
   coefficients Cf[r, .] */
static inline void RowCoefficients(const struct _JRMonodromy *f, PetscInt r, PetscReal scale, PetscReal *c)
{
  if (f->dr[r] >= 0) {
    for (PetscInt d = 0; d < f->nd; d++) c[d] = 0.0;
    c[f->dr[r]] = scale;
  } else
    for (PetscInt d = 0; d < f->nd; d++) c[d] = scale * f->Cf[r * f->nd + d];
}

/* Every element's record on every rank (collective): type (0 jenkins, 1 jenkins_nv, 2 cubic), kt, kn, mu, n0 and its
   rows r, s over the nm modes, rec = 5 + 2 nm reals each, in all (*ne records) */
static PetscErrorCode GatherElements(JRHBM h, PetscInt rec, PetscReal **all, PetscInt *ne)
{
  const PetscInt nm   = h->nm;
  PetscInt       nloc = 0, tot = 0;
  PetscMPIInt    size = h->size, *cnt, *dsp, mine;
  PetscReal     *loc;

  PetscFunctionBeginUser;
  if (!h->repl || !h->rank)
    for (PetscInt t = 0; t < h->ngroups; t++) nloc += h->g[t].nloc;
  PetscCall(PetscMalloc1(rec * nloc + 1, &loc));
  nloc = 0;
  for (PetscInt t = 0; t < h->ngroups && (!h->repl || !h->rank); t++) {
    const JRHBMGroup *g = &h->g[t];
    const PetscReal   ty = !strcmp(g->c->type_name, JRCONTACTJENKINSNV) ? 1 : !strcmp(g->c->type_name, JRCONTACTCUBIC) ? 2 : 0;
    for (PetscInt e = 0; e < g->nloc; e++, nloc++) {
      PetscReal *r = loc + rec * nloc;
      r[0]         = ty;
      r[1]         = g->c->kt[e];
      r[2]         = g->c->kn ? g->c->kn[e] : 0.0;
      r[3]         = g->c->mu ? g->c->mu[e] : 0.0;
      r[4]         = g->c->n0 ? g->c->n0[e] : 0.0;
      for (PetscInt i = 0; i < nm; i++) {
        r[5 + i]      = g->R[e + i * g->nloc];
        r[5 + nm + i] = g->normal ? g->S[e + i * g->nloc] : 0.0;
      }
    }
  }
  PetscCall(PetscMalloc2(size, &cnt, size, &dsp));
  PetscCall(PetscMPIIntCast(rec * nloc, &mine));
  PetscCallMPI(MPI_Allgather(&mine, 1, MPI_INT, cnt, 1, MPI_INT, h->comm));
  for (PetscMPIInt r = 0; r < size; r++) {
    dsp[r] = (PetscMPIInt)tot;
    tot += cnt[r];
  }
  *ne = tot / rec;
  PetscCall(PetscMalloc1(tot + 1, all));
  PetscCallMPI(MPI_Allgatherv(loc, mine, MPIU_REAL, *all, cnt, dsp, MPIU_REAL, h->comm));
  PetscCall(PetscFree2(cnt, dsp));
  PetscCall(PetscFree(loc));
  PetscFunctionReturn(0);
}

/* f->Mi = Mm^-1 (from the modal mass in f->Mi), f->MRS = -Mm^-1 [R^T S^T], and w_max^2: the largest eigenvalue of
   (K + sum kt r r^T + kn s s^T, Mm), every element stuck */
static PetscErrorCode MassInverse(struct _JRMonodromy *f)
{
  const PetscInt nk = f->nk, ne = f->ne;
  PetscReal     *Ks, *Mc, *ev, *wk;
  PetscBLASInt   bn, info, itype = 1, lw;

  PetscFunctionBeginUser;
  PetscCall(PetscBLASIntCast(nk, &bn));
  PetscCall(PetscBLASIntCast(PetscMax(1, 3 * nk), &lw));
  PetscCall(PetscMalloc4(nk * nk, &Ks, nk * nk, &Mc, nk + 1, &ev, 3 * nk + 1, &wk));
  PetscCall(PetscArraycpy(Ks, f->K, nk * nk));
  PetscCall(PetscArraycpy(Mc, f->Mi, nk * nk));
  for (PetscInt e = 0; e < ne; e++)
    for (PetscInt j = 0; j < nk; j++)
      for (PetscInt i = 0; i < nk; i++) Ks[i + j * nk] += PetscAbsReal(f->kt[e]) * f->RS[e + i * f->l] * f->RS[e + j * f->l] + (f->srow[e] >= 0 ? f->kn[e] * f->RS[f->srow[e] + i * f->l] * f->RS[f->srow[e] + j * f->l] : 0.0);
  if (nk) {
    PetscCallBLAS("LAPACKsygv", LAPACKsygv_(&itype, "N", "U", &bn, Ks, &bn, Mc, &bn, ev, wk, &lw, &info));
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "Floquet exponents in time: LAPACK sygv failed (info %d): the modal mass is not positive definite", (int)info);
    f->wmax = PetscSqrtReal(PetscMax(ev[nk - 1], 0.0));
  }
  /* Mm^-1 by LU of a copy: the columns of the identity */
  PetscCall(PetscArraycpy(Mc, f->Mi, nk * nk));
  PetscCall(PetscArrayzero(f->Mi, nk * nk));
  for (PetscInt i = 0; i < nk; i++) f->Mi[i + i * nk] = 1.0;
  if (nk) {
    PetscBLASInt *piv;
    PetscCall(PetscMalloc1(nk, &piv));
    PetscCallBLAS("LAPACKgesv", LAPACKgesv_(&bn, &bn, Mc, &bn, piv, f->Mi, &bn, &info));
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "Floquet exponents in time: the modal mass is singular (LAPACK gesv info %d)", (int)info);
    PetscCall(PetscFree(piv));
  }
  PetscCall(PetscFree4(Ks, Mc, ev, wk));
  if (ne) PetscCall(JRGemm("N", "T", nk, f->l, nk, -1.0, f->Mi, nk, f->RS, f->l, 0.0, f->MRS, nk));
  PetscFunctionReturn(0);
}

/* Every element's parameters and rows on every rank (collective), the kept modes' linear matrices, and the stiffest
   mode */
static PetscErrorCode MonodromySetUp(JRHBM h)
{
  struct _JRMonodromy *f;
  const PetscInt       nm = h->nm;
  PetscInt             ne = 0, nk = 0, *keep;
  PetscReal           *all = NULL, *Kc;
  const PetscInt       rec = 5 + 2 * nm; /* type, kt, kn, mu, n0, r (nm), s (nm) */

  PetscFunctionBeginUser;
  if (h->mono) PetscFunctionReturn(0);
  PetscCall(PetscNew(&f));
  PetscCall(GatherElements(h, rec, &all, &ne));
  /* Km - Kc: Kc summed over the ranks unless every rank has every element */
  PetscCall(PetscCalloc1(nm * nm, &Kc));
  if (h->basis != JR_HBM_BASIS_FREE && h->Kc) {
    if (h->repl || h->size == 1) PetscCall(PetscArraycpy(Kc, h->Kc, nm * nm));
    else PetscCall(MPIU_Allreduce(h->Kc, Kc, nm * nm, MPIU_REAL, MPIU_SUM, h->comm));
  }
  PetscCall(PetscMalloc1(nm, &keep));
  for (PetscInt i = 0; i < nm; i++)
    if (!h->pin || h->pin[i] == 0.0) keep[nk++] = i;
  f->ne = ne;
  f->nk = nk;
  f->m  = 2 * nk;
  PetscCall(PetscMalloc5(ne, &f->type, ne, &f->kt, ne, &f->kn, ne, &f->mu, ne, &f->n0));
  PetscCall(PetscMalloc2(ne, &f->mem, ne, &f->srow));
  f->l = ne;
  for (PetscInt e = 0; e < ne; e++) f->srow[e] = (PetscInt)all[rec * e] == 1 ? f->l++ : -1;
  PetscCall(PetscMalloc4(ne * nm + 1, &f->Ra, ne * nm + 1, &f->Sa, f->l * nk + 1, &f->RS, f->l * nk + 1, &f->MRS));
  PetscCall(PetscMalloc5(nk * nk, &f->K, nk * nk, &f->C, nk * nk, &f->Kg, nk * nk, &f->Mi, 2 * nk * nk, &f->G));
  for (PetscInt e = 0; e < ne; e++) {
    const PetscReal *r = all + rec * e;
    f->type[e]         = (PetscInt)r[0];
    f->kt[e]           = r[1];
    f->kn[e]           = r[2];
    f->mu[e]           = r[3];
    f->n0[e]           = r[4];
    f->mem[e]          = f->type[e] == 2 ? -1 : f->m++ - 2 * nk;
    for (PetscInt i = 0; i < nm; i++) {
      f->Ra[e + i * ne] = r[5 + i];
      f->Sa[e + i * ne] = r[5 + nm + i];
    }
    for (PetscInt i = 0; i < nk; i++) {
      f->RS[e + i * f->l] = r[5 + keep[i]];
      if (f->srow[e] >= 0) f->RS[f->srow[e] + i * f->l] = r[5 + nm + keep[i]];
    }
  }
  for (PetscInt j = 0; j < nk; j++)
    for (PetscInt i = 0; i < nk; i++) {
      const PetscInt q = keep[i] * nm + keep[j]; /* row-major (i, j) */
      f->K[i + j * nk]  = h->Km[q] - Kc[keep[i] + keep[j] * nm];
      f->C[i + j * nk]  = h->Cm ? h->Cm[q] : 0.0;
      f->Kg[i + j * nk] = h->Kg[q];
      f->Mi[i + j * nk] = h->Mm[q];
    }
  PetscCall(MassInverse(f));
  {
    const PetscInt m = f->m;
    PetscCall(PetscMalloc3(m * m, &f->Y, m * m, &f->Y0, m * m, &f->Ys));
    PetscCall(PetscMalloc3(PetscMax(PetscMax(f->l, 2 * ne), nk) * m + 1, &f->DUV, f->l * m + 1, &f->DFN, ne * m + 1, &f->Wc));
    { /* geev's workspace: its optimal size for m (blocked Hessenberg reduction), at least the minimum 4 m + 4 */
      PetscBLASInt bm, one = 1, info;
      PetscReal    opt = 0.0, dummy = 0.0;
      f->lwork = -1;
      PetscCall(PetscBLASIntCast(m, &bm));
      PetscCallBLAS("LAPACKgeev", LAPACKgeev_("N", "N", &bm, &dummy, &bm, &dummy, &dummy, &dummy, &one, &dummy, &one, &opt, &f->lwork, &info));
      f->lwork = (PetscBLASInt)PetscMax(4 * m + 4, opt);
    }
    PetscCall(PetscMalloc4(m * m, &f->ev, m, &f->wr, m, &f->wi, f->lwork, &f->work));
  }
  for (PetscInt e = 0; e < ne; e++)
    if (f->type[e] == 2) f->smooth = PETSC_TRUE;
  if (!f->smooth) {
    const PetscInt n2 = 2 * nk;
    PetscCall(PetscMalloc4(ne + 1, &f->key, JR_MONO_SLOTS * ne + 1, &f->slotkey, (JR_MONO_SLOTS + 1) * n2 * n2 + 1, &f->SL, (JR_MONO_SLOTS + 1) * n2 * ne + 1, &f->SW));
    PetscCall(PetscMalloc3(n2 * n2 + 1, &f->XL, n2 * ne + 1, &f->XW, n2 * f->m + 1, &f->T2));
    PetscCall(PetscMalloc3(ne + 1, &f->ka, ne + 1, &f->kb, ne + 1, &f->th));
    PetscCall(PetscMalloc3(ne + 1, &f->cls, ne + 1, &f->memp, ne + 1, &f->tel));
    PetscCall(PetscMalloc4(ne + 1, &f->lka, ne + 1, &f->lkb, ne + 1, &f->lth, ne + 1, &f->chg));
    PetscCall(PetscMalloc2(JR_MONO_SLOTS + 1, &f->ncol, (JR_MONO_SLOTS + 1) * ne + 1, &f->cols));
    PetscCall(PetscMalloc3(5 * n2 * n2 + 1, &f->PS, n2 + 1, &f->piv, 2 * ne * nk + 1, &f->RT));
    PetscCall(PetscMalloc5(nk + 1, &f->isl, nk + 1, &f->ifa, nk * nk + 1, &f->Mm, nk * nk + 1, &f->Cv, 9 * nk * nk + 4 * nk * ne + 1, &f->QW));
    PetscCall(PetscMalloc1(2 * nk * nk + 1, &f->MCb));
    for (PetscInt j = 0; j < nk; j++)
      for (PetscInt i = 0; i < nk; i++) f->Mm[i + j * nk] = h->Mm[keep[i] * nm + keep[j]];
    PetscCall(PetscMalloc2(3 * ne + 1, &f->cf, 3 * ne + 1, &f->cfn));
    PetscCall(PetscMalloc4(f->l * nk + 1, &f->RSt, nk * nk + 1, &f->Kp, 2 * ne * nk + 1, &f->Rg, 2 * ne + 1, &f->rows));
    PetscCall(PetscMalloc1(ne + 1, &f->sdr));
    for (PetscInt r = 0; r < f->l; r++)
      for (PetscInt i = 0; i < nk; i++) f->RSt[i + r * nk] = f->RS[r + i * f->l];
    PetscCall(DistinctRows(f));
  }
  PetscCall(PetscFree(keep));
  PetscCall(PetscFree(Kc));
  PetscCall(PetscFree(all));
  h->mono = f;
  PetscFunctionReturn(0);
}

/* The slip bound r = mu n / kt and its normal load n (n0 + kn v, at least 0, for jenkins_nv; n0 otherwise) at element
   e's half step s of the point's motion (PointMotion keeps them) */
static inline PetscReal HalfBound(const struct _JRMonodromy *f, PetscInt e, PetscInt s, PetscReal *n)
{
  const PetscInt i = e * (2 * f->ns + 1) + s;

  *n = f->nb[i];
  return f->rb[i];
}

/* The linearised element forces at half step s from the committed slip of step j: DFN from DUV and Wc */
static void ElementForces(const struct _JRMonodromy *f, PetscInt s, PetscInt j)
{
  const PetscInt ne = f->ne, m = f->m, N2 = 2 * f->ns + 1, l = f->l;

  for (PetscInt e = 0; e < ne; e++) {
    const PetscReal u = f->u[e * N2 + s], w = f->wn[e * (f->ns + 1) + j], kt = f->kt[e], kn = f->kn[e];
    PetscReal       n, r;
    if (f->type[e] == 2) { /* cubic: f = kt u^3 */
      for (PetscInt c = 0; c < m; c++) f->DFN[e + c * l] = 3 * kt * u * u * f->DUV[e + c * l];
      continue;
    }
    r = HalfBound(f, e, s, &n);
    {
      const PetscBool contact = (PetscBool)(f->type[e] == 1 && n > 0);
      const PetscReal drdv    = contact && kt > 0 ? f->mu[e] * kn / kt : 0.0;
      const PetscInt  side    = w < u - r ? -1 : w > u + r ? 1 : 0; /* slipping at the lower / upper bound, or stuck */
      const PetscInt  sr      = f->srow[e];
      for (PetscInt c = 0; c < m; c++) {
        const PetscReal du = f->DUV[e + c * l], dv = sr >= 0 ? f->DUV[sr + c * l] : 0.0;
        const PetscReal dw = side == 0 ? f->Wc[e + c * ne] : side < 0 ? du - drdv * dv : du + drdv * dv;
        f->DFN[e + c * l] = kt * (du - dw);
        if (sr >= 0) f->DFN[sr + c * l] = contact ? kn * dv : 0.0;
      }
    }
  }
}

/* The right-hand side of the variational equations at half step s (committed slip of step j) for the state Z = [Q; P;
   W] (m x m, column-major) into D: Q' = P (rows 0..nk-1), P' = G [Q; P] - Mm^-1 (R^T df + S^T dn) (rows nk..2nk-1) */
static PetscErrorCode Rhs(JRHBM h, PetscInt s, PetscInt j, const PetscReal *Z, PetscReal *D)
{
  struct _JRMonodromy *f  = h->mono;
  const PetscInt       nk = f->nk, ne = f->ne, m = f->m;

  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < m; c++)
    for (PetscInt i = 0; i < nk; i++) D[i + c * m] = Z[nk + i + c * m];
  PetscCall(JRGemm("N", "N", nk, m, 2 * nk, 1.0, f->G, nk, Z, m, 0.0, D + nk, m));
  if (ne) {
    PetscCall(JRGemm("N", "N", f->l, m, nk, 1.0, f->RS, f->l, Z, m, 0.0, f->DUV, f->l));
    ElementForces(f, s, j);
    PetscCall(JRGemm("N", "N", nk, m, f->l, 1.0, f->MRS, nk, f->DFN, f->l, 1.0, D + nk, m));
  }
  PetscFunctionReturn(0);
}

/* The point's element motions at the half steps of one period and the committed slip at the steps (the play
   operator from rest over two periods first, as the alternating frequency-time march starts) */
static PetscErrorCode PointMotion(JRHBM h, PetscReal w, const PetscReal *a)
{
  struct _JRMonodromy *f = h->mono;
  const PetscInt       ne = f->ne, nm = h->nm, ns = f->ns, N2 = 2 * ns + 1, H = h->H, nc = h->nc;
  const PetscReal      dt = 2 * PETSC_PI / w / ns;
  PetscReal           *tb = f->trig, *uc = tb + nc * N2, *vc = uc + ne * nc;

  PetscFunctionBeginUser;
  for (PetscInt q = 0; q < N2; q++) { /* 1, sin, cos of h w t at the half steps, the same for every element */
    const PetscReal t = 0.5 * q * dt;
    tb[q * nc] = 1.0;
    for (PetscInt hh = 1; hh <= H; hh++) {
      tb[q * nc + 2 * hh - 1] = PetscSinReal(hh * w * t);
      tb[q * nc + 2 * hh]     = PetscCosReal(hh * w * t);
    }
  }
  /* the elements' harmonics of u and v (ne x nc), then their values at the half steps (N2 x ne: element e's at u + e N2) */
  if (!ne) PetscFunctionReturn(0);
  PetscCall(JRGemm("N", "N", ne, nc, nm, 1.0, f->Ra, ne, a, nm, 0.0, uc, ne));
  PetscCall(JRGemm("N", "N", ne, nc, nm, 1.0, f->Sa, ne, a, nm, 0.0, vc, ne));
  PetscCall(JRGemm("T", "T", N2, ne, nc, 1.0, tb, nc, uc, ne, 0.0, f->u, N2));
  PetscCall(JRGemm("T", "T", N2, ne, nc, 1.0, tb, nc, vc, ne, 0.0, f->v, N2));
  for (PetscInt e = 0; e < ne; e++) {
    const PetscReal *v = f->v + e * N2, n0 = f->n0[e], kn = f->kn[e], mu = f->mu[e], kt = f->kt[e];
    PetscReal       *rb = f->rb + e * N2, *nb = f->nb + e * N2;
    unsigned char   *cn = f->cnt + e * N2;
    if (f->type[e] == 1)
      for (PetscInt q = 0; q < N2; q++) {
        nb[q] = PetscMax(0.0, n0 + kn * v[q]);
        rb[q] = kt > 0 ? mu * nb[q] / kt : 0.0;
        cn[q] = (unsigned char)(nb[q] > 0);
      }
    else
      for (PetscInt q = 0; q < N2; q++) {
        nb[q] = PetscMax(n0, 0.0);
        rb[q] = kt > 0 ? mu * nb[q] / kt : 0.0;
        cn[q] = 0;
      }
  }
  /* the play operator from rest over two periods to the periodic slip, then the third's committed values: four
     elements at a time, their chains of min and max independent (a cubic spring's slip is not read) */
  for (PetscInt e0 = 0; e0 < ne; e0 += 4) {
    const PetscInt   nb = PetscMin(4, ne - e0);
    const PetscReal *u[4], *rb[4];
    PetscReal       *wn[4], s[4] = {0.0, 0.0, 0.0, 0.0};
    for (PetscInt b = 0; b < 4; b++) { /* a short block repeats its last element (the same values written twice) */
      const PetscInt e = e0 + PetscMin(b, nb - 1);
      u[b]             = f->u + e * N2;
      rb[b]            = f->rb + e * N2;
      wn[b]            = f->wn + e * (ns + 1);
    }
    for (PetscInt p = 0; p < 3; p++)
      for (PetscInt j = 0; j <= ns; j++)
        for (PetscInt b = 0; b < 4; b++) {
          s[b] = PetscMin(PetscMax(s[b], u[b][2 * j] - rb[b][2 * j]), u[b][2 * j] + rb[b][2 * j]);
          if (p == 2) wn[b][j] = s[b];
        }
  }
  for (PetscInt e = 0; e < ne; e++) { /* Side() at the steps' ends */
    const PetscReal *u = f->u + e * N2, *rb = f->rb + e * N2, *wn = f->wn + e * (ns + 1);
    unsigned char   *sd = f->sde + e * ns;
    if (f->type[e] != 2)
      for (PetscInt j = 0; j < ns; j++) sd[j] = (unsigned char)(wn[j] < u[2 * j + 2] - rb[2 * j + 2] ? 0 : wn[j] > u[2 * j + 2] + rb[2 * j + 2] ? 2 : 1);
  }
  PetscFunctionReturn(0);
}

/* Element e's state at the end of step j against its committed slip (PointMotion keeps them): -1 / 1 slipping at the
   lower / upper bound, 0 stuck */
static inline PetscInt Side(const struct _JRMonodromy *f, PetscInt e, PetscInt j)
{
  return (PetscInt)f->sde[e * f->ns + j] - 1;
}

/* The fundamental matrix Y (m x m, from the identity) over one period with a cubic spring, whose stiffness follows
   the motion within a step: RK4 with the elements' states at every stage, the slips committed at the steps' ends */
static PetscErrorCode MarchRK4(JRHBM h, PetscReal dt)
{
  struct _JRMonodromy *f  = h->mono;
  const PetscInt       nk = f->nk, ne = f->ne, m = f->m, ns = f->ns;
  PetscReal           *Y = f->Y, *Y0 = f->Y0, *Ys = f->Ys, *K1 = f->ev, *acc;

  PetscFunctionBeginUser;
PetscCall(PetscMalloc1(m * m, &acc));
  for (PetscInt j = 0; j < ns; j++) {
    /* the committed slips of step j: rows 2 nk .. */
    for (PetscInt c = 0; c < m; c++)
      for (PetscInt e = 0; e < ne; e++) f->Wc[e + c * ne] = f->mem[e] < 0 ? 0.0 : Y[2 * nk + f->mem[e] + c * m];
    PetscCall(PetscArraycpy(Y0, Y, m * m));
    PetscCall(PetscArrayzero(acc, m * m));
    for (PetscInt st = 0; st < 4; st++) { /* RK4 on (Q, P); the slip rows held */
      const PetscInt  s  = 2 * j + (st == 0 ? 0 : st == 3 ? 2 : 1);
      const PetscReal cw = st == 0 || st == 3 ? 1.0 : 2.0, cn = st == 2 ? 1.0 : 0.5;
      PetscCall(Rhs(h, s, j, st == 0 ? Y0 : Ys, K1));
      for (PetscInt c = 0; c < m; c++)
        for (PetscInt i = 0; i < 2 * nk; i++) {
          acc[i + c * m] += cw * K1[i + c * m];
          if (st < 3) Ys[i + c * m] = Y0[i + c * m] + cn * dt * K1[i + c * m];
        }
    }
    for (PetscInt c = 0; c < m; c++)
      for (PetscInt i = 0; i < 2 * nk; i++) Y[i + c * m] = Y0[i + c * m] + dt / 6 * acc[i + c * m];
    /* commit the slips at step j + 1: the return map's derivative from step j's committed slip */
    if (ne) {
      const PetscInt N2 = 2 * ns + 1;
      PetscCall(JRGemm("N", "N", f->l, m, nk, 1.0, f->RS, f->l, Y, m, 0.0, f->DUV, f->l));
      for (PetscInt e = 0; e < ne; e++) {
        const PetscReal u = f->u[e * N2 + 2 * j + 2], wj = f->wn[e * (ns + 1) + j];
        PetscReal       n, r;
        PetscInt        side;
        if (f->type[e] == 2) continue;
        r    = HalfBound(f, e, 2 * j + 2, &n);
        side = wj < u - r ? -1 : wj > u + r ? 1 : 0;
        if (!side) continue;
        {
          const PetscReal drdv = f->type[e] == 1 && n > 0 && f->kt[e] > 0 ? f->mu[e] * f->kn[e] / f->kt[e] : 0.0;
          for (PetscInt c = 0; c < m; c++) Y[2 * nk + f->mem[e] + c * m] = f->DUV[e + c * f->l] + (drdv != 0.0 ? (side < 0 ? -drdv : drdv) * f->DUV[f->srow[e] + c * f->l] : 0.0);
        }
      }
    }
  }
  PetscCall(PetscFree(acc));
  PetscFunctionReturn(0);
}

/* The zero of the line through (0, a) and (1, b), in [0, 1] */
static inline PetscReal Zero(PetscReal a, PetscReal b)
{
  return a != b ? PetscMin(PetscMax(a / (a - b), 0.0), 1.0) : 0.5;
}

/* Element e's states over step j as the play operator on the steps' ends (PointMotion) has them: it slips over the
   step only where its slip is committed at the step's end, from where |u - w| - mu n / kt crosses zero if it was stuck
   at the last step's end; a jenkins_nv contact opens or closes where n crosses zero (each zero by linear interpolation
   between the half steps). Output: the states before and after (side + 1, plus 3 in contact) and the share th of the
   step before. */
static void StepStates(struct _JRMonodromy *f, PetscInt e, PetscInt j, unsigned char *ka, unsigned char *kb, PetscReal *th)
{
  const PetscInt       ns = f->ns, N2 = 2 * ns + 1, i = e * N2 + 2 * j;
  const unsigned char *cn = f->cnt + i;
  const PetscInt       sprev = Side(f, e, j ? j - 1 : ns - 1), send = Side(f, e, j);
  PetscReal            ts = -1.0, tc = -1.0;
  PetscInt             sa = 0, ca, cb;

  if (send) {
    sa = sprev == send || f->cls[e] == JR_MONO_FORGET ? send : 0;
    if (!sa) { /* stuck at the last step's end: it starts to slip where |u - w| - mu n / kt crosses zero */
      const PetscReal  w = f->wn[e * (ns + 1) + j], *u = f->u + i, *rb = f->rb + i;
      const PetscReal  g0 = PetscAbsReal(u[0] - w) - rb[0], g1 = PetscAbsReal(u[1] - w) - rb[1], g2 = PetscAbsReal(u[2] - w) - rb[2];
      ts = g1 > 0 ? 0.5 * Zero(g0, g1) : 0.5 + 0.5 * Zero(g1, g2);
    }
  }
  ca = cb = cn[0];
  if (cn[0] != cn[2]) { /* the contact opens or closes where n0 + kn v crosses zero */
    const PetscReal *v = f->v + i, n0 = f->n0[e], kn = f->kn[e];
    cb = cn[2];
    tc = cn[1] == cn[2] ? 0.5 * Zero(n0 + kn * v[0], n0 + kn * v[1]) : 0.5 + 0.5 * Zero(n0 + kn * v[1], n0 + kn * v[2]);
  }
  *ka = (unsigned char)(sa + 1 + (ca ? 3 : 0));
  *kb = (unsigned char)(send + 1 + (cb ? 3 : 0));
  *th = ts >= 0 && tc >= 0 ? 0.5 * (ts + tc) : ts >= 0 ? ts : tc >= 0 ? tc : 1.0;
}

/* Each element's class over the point's period (the play operator on the steps' ends, PointMotion): tracked where it
   changes state, held where it is stuck and its contact unchanged throughout, forgotten where its slip is committed
   at every step; f->memp, f->mt. Returns f->mt.
   A tracked slip whose element slips on the same side at the period's end and through the first step is not read
   (held) before its first commit overwrites it: its column of the monodromy matrix is 0, a multiplier 0. Such slips
   come last, f->np of them: the march propagates the other columns only and the multipliers are those of the
   leading block (its determinant expanded along the zero columns). */
static PetscInt Classify(struct _JRMonodromy *f)
{
  const PetscInt N2 = 2 * f->ns + 1;
  PetscInt       nt = 0;

  f->np = 0;
  for (PetscInt e = 0; e < f->ne; e++) {
    PetscInt commits = 0, contacts = 0;
    for (PetscInt j = 0; j < f->ns; j++) {
      if (Side(f, e, j)) commits++;
      if (f->cnt[e * N2 + 2 * j + 1]) contacts++;
    }
    f->cls[e]  = commits == f->ns ? JR_MONO_FORGET : commits == 0 && (contacts == 0 || contacts == f->ns) ? JR_MONO_HOLD : JR_MONO_TRACK;
    f->memp[e] = -1;
  }
  for (PetscInt pass = 0; pass < 2; pass++) /* the slips read at the period's start, then the others */
    for (PetscInt e = 0; e < f->ne; e++) {
      PetscBool unread;
      if (f->cls[e] != JR_MONO_TRACK) continue;
      unread = (PetscBool)(f->unread && Side(f, e, f->ns - 1) != 0 && Side(f, e, 0) == Side(f, e, f->ns - 1));
      if (unread != (PetscBool)pass) continue;
      f->tel[nt] = e;
      f->memp[e] = nt++;
      if (unread) f->np++;
    }
  for (PetscInt e = 0; e < f->ne; e++) /* the tracked elements' rows, for their motion at the steps' ends */
    if (f->memp[e] >= 0)
      for (PetscInt i = 0; i < f->nk; i++) {
        f->RT[2 * f->memp[e] + i * 2 * nt]     = f->RS[e + i * f->l];
        f->RT[2 * f->memp[e] + 1 + i * 2 * nt] = f->srow[e] >= 0 ? f->RS[f->srow[e] + i * f->l] : 0.0;
      }
  f->mt = 2 * f->nk + nt;
  return f->mt;
}

/* Y = XL X (n2 x n2) for XL = [0, a I; A, B] (a step's matrix: q' = p): Y's first half a X's second half, its
   second half [A, B] X, half a product */
static PetscErrorCode LeftXL(PetscInt n2, const PetscReal *XL, const PetscReal *X, PetscReal *Y)
{
  const PetscInt  h = n2 / 2;
  const PetscReal a = XL[h * n2];

  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < n2; c++)
    for (PetscInt i = 0; i < h; i++) Y[i + c * n2] = a * X[h + i + c * n2];
  PetscCall(JRGemm("N", "N", h, n2, n2, 1.0, XL + h, n2, X, n2, 0.0, Y + h, n2));
  PetscFunctionReturn(0);
}

/* SL = exp(XL) ^ (2^sq) (n2 x n2) and, where G is given, G = the last n2 / 2 columns of phi1(XL) = sum_k XL^k / (k + 1)!
   carried through the same squarings (n2 x n2 / 2): the held slips' response over the step is then G XW's last n2 / 2
   rows, exactly as the map of the augmented matrix [XL, XW; 0, 0] has it, with no inverse of XL. Both by their
   Taylor polynomials of degree JR_MONO_TAYLOR = 8 with Paterson and Stockmeyer's scheme, p(X) = B0 + X^4 B1, B0 and
   B1 of degree 3 and 4 in X (XL's powers by LeftXL, then one product for SL, one more for G), then squared sq times:
   [E, F; 0, I]^2 = [E E, (E + I) F; 0, I]; work (4 n2 x n2) */
static PetscErrorCode ExpmPhi(PetscInt n2, const PetscReal *XL, PetscInt sq, PetscReal *SL, PetscReal *G, PetscReal *work)
{
  PetscReal     *X2 = work, *X3 = work + n2 * n2, *X4 = work + 2 * n2 * n2, *B = work + 3 * n2 * n2;
  const PetscInt h  = n2 / 2;
  PetscReal      c[JR_MONO_TAYLOR + 2];

  PetscFunctionBeginUser;
  c[0] = 1.0;
  for (PetscInt i = 1; i <= JR_MONO_TAYLOR + 1; i++) c[i] = c[i - 1] / i;
  PetscCall(LeftXL(n2, XL, XL, X2));
  PetscCall(LeftXL(n2, XL, X2, X3));
  PetscCall(LeftXL(n2, XL, X3, X4));
  for (PetscInt i = 0; i < n2 * n2; i++) B[i] = c[5] * XL[i] + c[6] * X2[i] + c[7] * X3[i] + c[8] * X4[i];
  for (PetscInt i = 0; i < n2; i++) B[i + i * n2] += c[4];
  PetscCall(JRGemm("N", "N", n2, n2, n2, 1.0, X4, n2, B, n2, 0.0, SL, n2));
  for (PetscInt i = 0; i < n2 * n2; i++) SL[i] += c[1] * XL[i] + c[2] * X2[i] + c[3] * X3[i];
  for (PetscInt i = 0; i < n2; i++) SL[i + i * n2] += c[0];
  if (G) { /* phi1's last h columns: coefficients 1 / (k + 1)! */
    const PetscInt o = h * n2;
    for (PetscInt i = 0; i < n2 * h; i++) B[i] = c[6] * XL[o + i] + c[7] * X2[o + i] + c[8] * X3[o + i] + c[9] * X4[o + i];
    for (PetscInt i = 0; i < h; i++) B[h + i + i * n2] += c[5];
    PetscCall(JRGemm("N", "N", n2, h, n2, 1.0, X4, n2, B, n2, 0.0, G, n2));
    for (PetscInt i = 0; i < n2 * h; i++) G[i] += c[2] * XL[o + i] + c[3] * X2[o + i] + c[4] * X3[o + i];
    for (PetscInt i = 0; i < h; i++) G[h + i + i * n2] += c[1];
  }
  for (PetscInt q = 0; q < sq; q++) {
    if (G) {
      PetscCall(PetscArraycpy(X3, G, n2 * h));
      PetscCall(JRGemm("N", "N", n2, h, n2, 1.0, SL, n2, G, n2, 1.0, X3, n2));
      PetscCall(PetscArraycpy(G, X3, n2 * h));
    }
    PetscCall(JRGemm("N", "N", n2, n2, n2, 1.0, SL, n2, SL, n2, 0.0, X2, n2));
    PetscCall(PetscArraycpy(SL, X2, n2 * n2));
  }
  PetscFunctionReturn(0);
}

/* The stiffness of the step's element states (f->ka, f->kb, f->th: each element's two states weighted by their
   shares), Kp = K + sum_e (a r r^T + b r s^T + c s s^T): a = kt stuck, b = -side kt d(mu n / kt)/dv slipping in
   contact (jenkins_nv), c = kn in contact; updated by the elements whose coefficients change, in full at a point's
   first step. f->bwt: a held slip's stiffness, kt of the tracked elements stuck (its force on the modes kt w r_e).
   Only the elements whose states differ from those of the last call (f->chg) are visited. */
static PetscErrorCode StiffnessUpdate(struct _JRMonodromy *f)
{
  const PetscInt nk = f->nk, ne = f->ne;

  PetscFunctionBeginUser;
  for (PetscInt ic = 0; ic < f->nchg; ic++) {
    const PetscInt e = f->chg[ic];
    PetscReal     *c = f->cfn + 3 * e, bw = 0.0;
    f->lka[e] = f->ka[e];
    f->lkb[e] = f->kb[e];
    f->lth[e] = f->th[e];
    c[0] = c[1] = c[2] = 0.0;
    for (PetscInt q = 0; q < 2; q++) {
      const unsigned char st = q ? f->kb[e] : f->ka[e];
      const PetscReal     wq = q ? 1.0 - f->th[e] : f->th[e];
      const PetscInt      side = st % 3 - 1;
      const PetscBool     contact = (PetscBool)(st >= 3);
      const PetscReal     kt = f->kt[e], drdv = contact && kt > 0 ? f->mu[e] * f->kn[e] / kt : 0.0;
      if (wq == 0.0) continue;
      if (side == 0) c[0] += wq * kt;
      else if (drdv != 0.0) c[1] += -wq * side * kt * drdv;
      if (f->srow[e] >= 0 && contact) c[2] += wq * f->kn[e];
      if (side == 0) bw += wq * kt;
    }
    if (f->memp[e] >= 0) f->bwt[f->memp[e]] = bw;
  }
  f->svalid = PETSC_TRUE;
  f->nupd = 0;
  if (f->lowrank && f->nfa) { /* LowRankStatic takes the coefficients, not Kp */
    f->kvalid = PETSC_FALSE;
  } else if (!f->kvalid) { /* Kp = K + [R; S]^T V^T, V's columns a r + b s (row e) and c s (row srow[e]) */
    PetscReal *V = f->DUV;
    for (PetscInt e = 0; e < ne; e++) {
      const PetscReal *c = f->cfn + 3 * e, *r = f->RSt + e * nk, *sv = f->srow[e] >= 0 ? f->RSt + f->srow[e] * nk : NULL;
      for (PetscInt i = 0; i < nk; i++) V[i + e * nk] = c[0] * r[i] + (sv ? c[1] * sv[i] : 0.0);
      if (sv)
        for (PetscInt i = 0; i < nk; i++) V[i + f->srow[e] * nk] = c[2] * sv[i];
    }
    PetscCall(PetscArraycpy(f->Kp, f->K, nk * nk));
    PetscCall(JRGemm("N", "T", nk, nk, f->l, 1.0, f->RSt, nk, V, nk, 1.0, f->Kp, nk));
    PetscCall(PetscArraycpy(f->cf, f->cfn, 3 * ne));
    f->kvalid  = PETSC_TRUE;
    f->kfvalid = PETSC_FALSE;
  } else { /* Kp += A V^T over the elements whose coefficients change: A's columns r (and s), V's a r + b s (and c s) */
    PetscReal *A = f->DUV, *V = A + 2 * nk * ne;
    PetscInt   nu = 0;
    for (PetscInt ic = 0; ic < f->nchg; ic++) {
      const PetscInt   e = f->chg[ic];
      PetscReal       *o = f->cf + 3 * e;
      const PetscReal *c = f->cfn + 3 * e, *r = f->RSt + e * nk, *sv = f->srow[e] >= 0 ? f->RSt + f->srow[e] * nk : NULL;
      const PetscReal  da = c[0] - o[0], db = c[1] - o[1], dc = c[2] - o[2];
      o[0] = c[0];
      o[1] = c[1];
      o[2] = c[2];
      if (da == 0.0 && db == 0.0 && dc == 0.0) continue;
      for (PetscInt i = 0; i < nk; i++) {
        A[i + nu * nk] = r[i];
        V[i + nu * nk] = da * r[i] + (sv ? db * sv[i] : 0.0);
      }
      nu++;
      if (sv && dc != 0.0) {
        for (PetscInt i = 0; i < nk; i++) {
          A[i + nu * nk] = sv[i];
          V[i + nu * nk] = dc * sv[i];
        }
        nu++;
      }
    }
    if (nu) PetscCall(JRGemm("N", "T", nk, nk, nu, 1.0, A, nk, V, nk, 1.0, f->Kp, nk));
    f->nupd = nu;
  }
  PetscFunctionReturn(0);
}

/* A <- A^-1 (n x n, column-major, in place), or *singular where a pivot is 0. Up to JR_MONO_GJ_MAX by Gauss-Jordan
   elimination with partial pivoting (row interchanges, undone on the columns at the end): at the step maps' sizes
   (10-30) LAPACK's getrf and getri cost several times more, in their calls to level-2 BLAS; larger by them.
   piv: n, work: n x n. */
#define JR_MONO_GJ_MAX 48
static PetscErrorCode SmallInverse(PetscInt n, PetscReal *A, PetscBLASInt *piv, PetscReal *work, PetscBool *singular)
{
  PetscFunctionBeginUser;
  *singular = PETSC_FALSE;
  if (n > JR_MONO_GJ_MAX) {
    PetscBLASInt bn, lw, info;
    PetscCall(PetscBLASIntCast(n, &bn));
    PetscCall(PetscBLASIntCast(n * n, &lw));
    PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, A, &bn, piv, &info));
    PetscCheck(info >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK getrf: argument %d", (int)-info);
    if (info > 0) {
      *singular = PETSC_TRUE;
      PetscFunctionReturn(0);
    }
    PetscCallBLAS("LAPACKgetri", LAPACKgetri_(&bn, A, &bn, piv, work, &lw, &info));
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK getri failed (info %d)", (int)info);
    PetscFunctionReturn(0);
  }
  for (PetscInt k = 0; k < n; k++) {
    PetscInt  p = k;
    PetscReal d, *c = work;
    for (PetscInt i = k + 1; i < n; i++)
      if (PetscAbsReal(A[i + k * n]) > PetscAbsReal(A[p + k * n])) p = i;
    if (A[p + k * n] == 0.0) {
      *singular = PETSC_TRUE;
      PetscFunctionReturn(0);
    }
    piv[k] = (PetscBLASInt)p;
    if (p != k)
      for (PetscInt j = 0; j < n; j++) {
        const PetscReal t = A[k + j * n];
        A[k + j * n]      = A[p + j * n];
        A[p + j * n]      = t;
      }
    d = 1.0 / A[k + k * n];
    for (PetscInt i = 0; i < n; i++) c[i] = A[i + k * n];
    c[k] = 0.0;
    for (PetscInt j = 0; j < n; j++) {
      PetscReal *a = A + j * n, akj;
      if (j == k) continue;
      akj  = a[k] * d;
      a[k] = akj;
      for (PetscInt i = 0; i < n; i++) a[i] -= c[i] * akj;
    }
    for (PetscInt i = 0; i < n; i++) A[i + k * n] = -c[i] * d;
    A[k + k * n] = d;
  }
  for (PetscInt k = n - 1; k >= 0; k--)
    if (piv[k] != k)
      for (PetscInt i = 0; i < n; i++) {
        const PetscReal t  = A[i + k * n];
        A[i + k * n]       = A[i + piv[k] * n];
        A[i + piv[k] * n]  = t;
      }
  PetscFunctionReturn(0);
}

/* The slow modes' equations after the condensation: Mr becomes Mr^-1 (in place; small, so an inverse and products
   cost less than triangular solves with the 2 nsl + held slips right-hand sides RH = [Kr, Cr, Br]); P = Mr^-1 Kr
   (nsl x nsl) and wmax >= the stiffest slow mode, the square root of P's 1-norm */
static PetscErrorCode SlowSolve(struct _JRMonodromy *f, PetscReal *Mr, const PetscReal *RH, PetscReal *P, PetscReal *wmax)
{
  const PetscInt nsl = f->nsl;
  PetscReal      norm = 0.0;
  PetscBool      singular;

  PetscFunctionBeginUser;
  PetscCall(SmallInverse(nsl, Mr, f->piv, P, &singular));
  PetscCheck(!singular, PETSC_COMM_SELF, PETSC_ERR_LIB, "Floquet exponents in time: the condensed modal mass is singular");
  PetscCall(JRGemm("N", "N", nsl, nsl, nsl, 1.0, Mr, nsl, RH, nsl, 0.0, P, nsl));
  for (PetscInt c = 0; c < nsl; c++) {
    PetscReal cs = 0.0;
    for (PetscInt i = 0; i < nsl; i++) cs += PetscAbsReal(P[i + c * nsl]);
    norm = PetscMax(norm, cs);
  }
  *wmax = PetscSqrtReal(norm);
  PetscFunctionReturn(0);
}

/* The rows x cols block (idx r, idx c) of the nk x nk column-major matrix A into B (column-major, nr rows) */
static void Block(const PetscReal *A, PetscInt nk, const PetscInt *ir, PetscInt nr, const PetscInt *ic, PetscInt nc, PetscReal *B)
{
  for (PetscInt j = 0; j < nc; j++)
    for (PetscInt i = 0; i < nr; i++) B[i + j * nr] = A[ir[i] + ic[j] * nk];
}

/* The point's blocks of Mm and Cv over its slow and fast modes (f->MCb: ss, sf, fs, ff of each, or the diagonals of
   ss and ff where the matrix is diagonal: f->mcdiag), for QuasiStatic */
static void PointBlocks(struct _JRMonodromy *f)
{
  const PetscInt nk = f->nk, nsl = f->nsl, nfa = f->nfa;

  for (PetscInt q = 0; q < 2; q++) {
    const PetscReal *B  = q ? f->Cv : f->Mm;
    PetscReal       *ss = f->MCb + q * nk * nk, *sf = ss + nsl * nsl, *fs = sf + nsl * nfa, *ff = fs + nfa * nsl;
    PetscBool        diag = PETSC_TRUE;
    for (PetscInt j = 0; j < nk && diag; j++)
      for (PetscInt i = 0; i < nk && diag; i++) diag = (PetscBool)(i == j || B[i + j * nk] == 0.0);
    f->mcdiag[q] = diag;
    if (diag) {
      for (PetscInt i = 0; i < nsl; i++) ss[i] = B[f->isl[i] * (nk + 1)];
      for (PetscInt a = 0; a < nfa; a++) ff[a] = B[f->ifa[a] * (nk + 1)];
      continue;
    }
    Block(B, nk, f->isl, nsl, f->isl, nsl, ss);
    Block(B, nk, f->isl, nsl, f->ifa, nfa, sf);
    Block(B, nk, f->ifa, nfa, f->isl, nsl, fs);
    Block(B, nk, f->ifa, nfa, f->ifa, nfa, ff);
  }
}

/* Kff^-1, X = -Kff^-1 Kfs and Z = Kff^-T Ksf^T (f->KFc, f->XZc) of the stiffness after the last StiffnessUpdate, from
   those before it, by the Woodbury identity: the update Kp + A V^T (nu columns) is Kff + Af Vf^T on the fast block
   (As, Vs: A's, V's slow rows), and with U = Kff^-1 Af, W = Vf^T Kff^-1, S = I + Vf^T U
     Kff^-1 <- Kff^-1 - U S^-1 W,   X <- X - U S^-1 (Vf^T X + Vs^T),   Z <- Z - W^T S^-T (Af^T Z - As^T)
   (6 nfa^2 nu multiply-adds against the 2 nfa^3 of an inverse and 4 nfa^2 nsl of X and Z). *done false where it does
   not apply (no inverse before, too many columns or updates since the last inverse, S singular). */
static PetscErrorCode WoodburyFast(struct _JRMonodromy *f, PetscBool *done)
{
  const PetscInt   nk = f->nk, nfa = f->nfa, nsl = f->nsl, nu = f->nupd;
  const PetscReal *A = f->DUV, *V = A + 2 * nk * f->ne;
  PetscReal       *Af = f->WB, *Vf = Af + nfa * nu, *U = Vf + nfa * nu, *W = U + nfa * nu, *P = W + nu * nfa, *S = P + nu * nfa;
  PetscReal       *Sw = S + nu * nu, *R = Sw + nu * nu, *R2 = R + nu * nsl, *X = f->XZc, *Z = X + nfa * nsl;
  PetscBool        singular;

  PetscFunctionBeginUser;
  *done = PETSC_FALSE;
  if (!f->wood || !f->kfvalid || 3 * nu > nfa || f->nwood >= JR_MONO_WOOD) PetscFunctionReturn(0);
  *done = PETSC_TRUE;
  if (!nu) PetscFunctionReturn(0);
  for (PetscInt c = 0; c < nu; c++)
    for (PetscInt a = 0; a < nfa; a++) {
      Af[a + c * nfa] = A[f->ifa[a] + c * nk];
      Vf[a + c * nfa] = V[f->ifa[a] + c * nk];
    }
  PetscCall(JRGemm("N", "N", nfa, nu, nfa, 1.0, f->KFc, nfa, Af, nfa, 0.0, U, nfa));
  PetscCall(JRGemm("T", "N", nu, nu, nfa, 1.0, Vf, nfa, U, nfa, 0.0, S, nu));
  for (PetscInt i = 0; i < nu; i++) S[i + i * nu] += 1.0;
  PetscCall(SmallInverse(nu, S, f->piv, Sw, &singular));
  if (singular) {
    *done = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  PetscCall(JRGemm("T", "N", nu, nfa, nfa, 1.0, Vf, nfa, f->KFc, nfa, 0.0, W, nu));
  /* X: R = Vf^T X + Vs^T, X -= U (S^-1 R) */
  PetscCall(JRGemm("T", "N", nu, nsl, nfa, 1.0, Vf, nfa, X, nfa, 0.0, R, nu));
  for (PetscInt b = 0; b < nsl; b++)
    for (PetscInt c = 0; c < nu; c++) R[c + b * nu] += V[f->isl[b] + c * nk];
  PetscCall(JRGemm("N", "N", nu, nsl, nu, 1.0, S, nu, R, nu, 0.0, R2, nu));
  PetscCall(JRGemm("N", "N", nfa, nsl, nu, -1.0, U, nfa, R2, nu, 1.0, X, nfa));
  /* Z: R = Af^T Z - As^T, Z -= W^T (S^-T R) */
  PetscCall(JRGemm("T", "N", nu, nsl, nfa, 1.0, Af, nfa, Z, nfa, 0.0, R, nu));
  for (PetscInt b = 0; b < nsl; b++)
    for (PetscInt c = 0; c < nu; c++) R[c + b * nu] -= A[f->isl[b] + c * nk];
  PetscCall(JRGemm("T", "N", nu, nsl, nu, 1.0, S, nu, R, nu, 0.0, R2, nu));
  PetscCall(JRGemm("T", "N", nfa, nsl, nu, -1.0, W, nu, R2, nu, 1.0, Z, nfa));
  /* Kff^-1 -= U (S^-1 W) */
  PetscCall(JRGemm("N", "N", nu, nfa, nu, 1.0, S, nu, W, nu, 0.0, P, nu));
  PetscCall(JRGemm("N", "N", nfa, nfa, nu, -1.0, U, nfa, P, nu, 1.0, f->KFc, nfa));
  f->nwood++;
  f->nwtot++;
  PetscFunctionReturn(0);
}

/* The fast kept modes (f->ifa) condensed quasi-statically for the step's element states (f->Kp, the stiffness with
   them, StiffnessUpdate; Bw, the held slips' forces): the fast modes follow the slow ones and the
   held slips statically, q = T q_s + T_w w, T = [I; X], X = -Kff^-1 Kfs, T_w = [0; Kff^-1 Bw_f] (rows slow; fast),
   and the slow modes obey Mr q_s'' + Cr q_s' + Kr q_s = Br w with Mr = T^T Mm T, Cr = T^T Cv T, Kr = T^T Kp T =
   Kss + Ksf X (the Schur complement: Kfs + Kff X = 0, Kp symmetric or not) and Br = Bw_s - Ksf Kff^-1 Bw_f; for
   B = Mm, Cv, T^T B T = Bss + Bsf X + X^T (Bfs + Bff X) from the point's blocks (PointBlocks; Bss + X^T Bff X where
   B is diagonal); Br by the nc held slips' columns col. Out: X = [Kr, Cr, Br] (nsl x (2 nsl + nc)), Mr^-1 and
   Mr^-1 Kr (at f->QW + 3 nk nk and + 4 nk nk, SlowSolve), wmax >= the stiffest slow mode, and slot k's T and Kff^-1
   for the commits. */
static PetscErrorCode QuasiStatic(struct _JRMonodromy *f, PetscInt k, PetscInt nc, const PetscInt *col, PetscReal **X, PetscReal *wmax)
{
  const PetscInt nk = f->nk, nsl = f->nsl, nfa = f->nfa, nt = f->mt - f->n2r;
  PetscReal     *Kp = f->Kp, *T = f->Ts + k * nk * nk, *MT = f->QW + 2 * nk * nk, *Mr = MT + nk * nk, *KF = f->KFs + k * nk * nk, *RH = Mr + 2 * nk * nk;
  PetscReal     *KS = f->QW, *BY = f->QW + nk * nk; /* Ksf (nsl x nfa); Bfs + Bff X (nfa x nsl) */
  PetscBLASInt  *piv = f->pivs + k * nk;
  PetscBool      singular, done;

  PetscFunctionBeginUser;
  /* Kff^-1 (kept for the commits: small, so an inverse and products cost less than triangular solves), X = -Kff^-1 Kfs
     (in MT) and Z = Kff^-T Ksf^T, updated from the last step's where few elements change state (WoodburyFast) */
  PetscCall(WoodburyFast(f, &done));
  if (!done) {
    PetscReal *X0 = f->XZc, *Z0 = X0 + nfa * nsl, *BF = f->CB;
    Block(Kp, nk, f->ifa, nfa, f->ifa, nfa, f->KFc);
    PetscCall(SmallInverse(nfa, f->KFc, piv, BY, &singular));
    PetscCheck(!singular, PETSC_COMM_SELF, PETSC_ERR_LIB, "Floquet exponents in time: the fast modes' stiffness is singular; -frf_stability_time_fast 0 marches every mode");
    for (PetscInt b = 0; b < nsl; b++)
      for (PetscInt a = 0; a < nfa; a++) {
        Z0[a + b * nfa] = Kp[f->ifa[a] + f->isl[b] * nk]; /* Kfs */
        BF[a + b * nfa] = Kp[f->isl[b] + f->ifa[a] * nk]; /* Ksf^T */
      }
    PetscCall(JRGemm("N", "N", nfa, nsl, nfa, -1.0, f->KFc, nfa, Z0, nfa, 0.0, X0, nfa));
    PetscCall(JRGemm("T", "N", nfa, nsl, nfa, 1.0, f->KFc, nfa, BF, nfa, 0.0, Z0, nfa));
    f->nwood = 0;
  }
  f->kfvalid = PETSC_TRUE;
  PetscCall(PetscArraycpy(KF, f->KFc, nfa * nfa));
  PetscCall(PetscArraycpy(MT, f->XZc, nfa * nsl));
  PetscCall(PetscArraycpy(f->bws + k * f->cap, f->bwt, nt));
  { /* RH's last block Br = Bw_s - Ksf Kff^-1 Bw_f = Bw_s - Z^T Bw_f, Z = Kff^-T Ksf^T (nfa x nsl), by the columns
       of the held slips of stuck elements (col; the others are 0) */
    PetscReal *Z = f->XZc + nfa * nsl, *BF = f->CB, *BR = RH + 2 * nsl * nsl;
    for (PetscInt q = 0; q < nc; q++) { /* Bw's column: bwt r_e */
      const PetscReal *r = f->RSt + f->tel[col[q]] * nk, bw = f->bwt[col[q]];
      for (PetscInt a = 0; a < nfa; a++) BF[a + q * nfa] = bw * r[f->ifa[a]];
      for (PetscInt i = 0; i < nsl; i++) BR[i + q * nsl] = bw * r[f->isl[i]];
    }
    PetscCall(JRGemm("T", "N", nsl, nc, nfa, -1.0, Z, nfa, BF, nfa, 1.0, BR, nsl));
  }
  PetscCall(PetscArrayzero(T, nk * nsl));
  for (PetscInt b = 0; b < nsl; b++) {
    T[f->isl[b] + b * nk] = 1.0;
    for (PetscInt a = 0; a < nfa; a++) T[f->ifa[a] + b * nk] = MT[a + b * nfa];
  }
  /* RH = [Kr, Cr, Br] (Br above): Kr = Kss + Ksf X; Mr and Cr = Bss + Bsf X + X^T (Bfs + Bff X) */
  Block(Kp, nk, f->isl, nsl, f->isl, nsl, RH);
  Block(Kp, nk, f->isl, nsl, f->ifa, nfa, KS);
  PetscCall(JRGemm("N", "N", nsl, nsl, nfa, 1.0, KS, nsl, MT, nfa, 1.0, RH, nsl));
  for (PetscInt q = 0; q < 2; q++) {
    const PetscReal *ss = f->MCb + q * nk * nk, *sf = ss + nsl * nsl, *fs = sf + nsl * nfa, *ff = fs + nfa * nsl;
    PetscReal       *out = q ? RH + nsl * nsl : Mr;
    if (f->mcdiag[q]) {
      PetscCall(PetscArrayzero(out, nsl * nsl));
      for (PetscInt i = 0; i < nsl; i++) out[i + i * nsl] = ss[i];
      for (PetscInt b = 0; b < nsl; b++)
        for (PetscInt a = 0; a < nfa; a++) BY[a + b * nfa] = ff[a] * MT[a + b * nfa];
    } else {
      PetscCall(PetscArraycpy(out, ss, nsl * nsl));
      PetscCall(JRGemm("N", "N", nsl, nsl, nfa, 1.0, sf, nsl, MT, nfa, 1.0, out, nsl));
      PetscCall(PetscArraycpy(BY, fs, nfa * nsl));
      PetscCall(JRGemm("N", "N", nfa, nsl, nfa, 1.0, ff, nfa, MT, nfa, 1.0, BY, nfa));
    }
    PetscCall(JRGemm("T", "N", nsl, nsl, nfa, 1.0, MT, nfa, BY, nfa, 1.0, out, nsl));
  }
  PetscCall(SlowSolve(f, Mr, RH, Mr + nk * nk, wmax));
  *X = RH;
  PetscFunctionReturn(0);
}

/* Per point, the fast modes' condensation through the distinct rows (f->lowrank): with A = Aref_ff (LU),
   U = A^-1 Rf^T, G = Rf U, X0 = A^-1 Aref_fs, W = Rf X0, K0 = Aref_ss - Aref_sf X0, KU = Aref_sf U, and for B = Mm,
   C and Kg the pieces of T^T B T for T's fast rows -X0 + U Y (LowRankStatic): B0 = Bss - Bsf X0 - X0^T Bfs +
   X0^T Bff X0, Ba = Bsf U - X0^T Bff U, Bb = U^T Bfs - U^T Bff X0, Bc = U^T Bff U. They depend on the point only
   through the split into slow and fast modes, and are kept while it stays; Cv's = C's + g Kg's (g = gamma / w).
   f->lowrank off where A is singular. */
static PetscErrorCode LowRankPoint(struct _JRMonodromy *f, PetscReal g)
{
  const PetscInt nk = f->nk, nd = f->nd, nsl = f->nsl, nfa = f->nfa, S = nsl * nsl + 2 * nsl * nd + nd * nd;
  PetscReal     *U = f->LR, *G = U + nfa * nd, *W = G + nd * nd, *Rs = W + nd * nsl, *K0 = Rs + nd * nsl, *KU = K0 + nsl * nsl;
  PetscReal     *B0 = KU + nsl * nd, *tmp = B0 + 4 * S;
  PetscReal     *AF = tmp, *X0 = AF + nfa * nfa, *Rf = X0 + nfa * nsl, *Bsf = Rf + nd * nfa, *Bfs = Bsf + nsl * nfa, *Bff = Bfs + nfa * nsl, *BX = Bff + nfa * nfa, *BU = BX + nfa * nsl;
  PetscBLASInt   bf, bn, info;
  PetscBool      same = (PetscBool)(f->lrnsl == nsl);

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < nsl && same; i++) same = (PetscBool)(f->lrkey[i] == f->isl[i]);
  if (!same) {
    f->lrnsl = -1;
    PetscCall(PetscBLASIntCast(nfa, &bf));
    for (PetscInt d = 0; d < nd; d++) {
      for (PetscInt i = 0; i < nsl; i++) Rs[d + i * nd] = f->Rd[d * nk + f->isl[i]];
      for (PetscInt a = 0; a < nfa; a++) Rf[d + a * nd] = f->Rd[d * nk + f->ifa[a]];
    }
    Block(f->Aref, nk, f->ifa, nfa, f->ifa, nfa, AF);
    PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bf, &bf, AF, &bf, f->piv, &info));
    if (info) {
      f->lowrank = PETSC_FALSE;
      PetscFunctionReturn(0);
    }
    for (PetscInt d = 0; d < nd; d++)
      for (PetscInt a = 0; a < nfa; a++) U[a + d * nfa] = Rf[d + a * nd];
    PetscCall(PetscBLASIntCast(nd, &bn));
    PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bf, &bn, AF, &bf, f->piv, U, &bf, &info));
    Block(f->Aref, nk, f->ifa, nfa, f->isl, nsl, X0);
    PetscCall(PetscBLASIntCast(nsl, &bn));
    PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bf, &bn, AF, &bf, f->piv, X0, &bf, &info));
    PetscCall(JRGemm("N", "N", nd, nd, nfa, 1.0, Rf, nd, U, nfa, 0.0, G, nd));
    PetscCall(JRGemm("N", "N", nd, nsl, nfa, 1.0, Rf, nd, X0, nfa, 0.0, W, nd));
    Block(f->Aref, nk, f->isl, nsl, f->isl, nsl, K0);
    Block(f->Aref, nk, f->isl, nsl, f->ifa, nfa, Bsf);
    PetscCall(JRGemm("N", "N", nsl, nsl, nfa, -1.0, Bsf, nsl, X0, nfa, 1.0, K0, nsl));
    PetscCall(JRGemm("N", "N", nsl, nd, nfa, 1.0, Bsf, nsl, U, nfa, 0.0, KU, nsl));
    for (PetscInt q = 0; q < 3; q++) { /* Mm, C, Kg */
      const PetscReal *B = q == 0 ? f->Mm : q == 1 ? f->C : f->Kg;
      PetscReal       *b0 = B0 + q * S, *ba = b0 + nsl * nsl, *bb = ba + nsl * nd, *bc = bb + nd * nsl;
      Block(B, nk, f->isl, nsl, f->isl, nsl, b0);
      Block(B, nk, f->isl, nsl, f->ifa, nfa, Bsf);
      Block(B, nk, f->ifa, nfa, f->isl, nsl, Bfs);
      Block(B, nk, f->ifa, nfa, f->ifa, nfa, Bff);
      PetscCall(JRGemm("N", "N", nfa, nsl, nfa, 1.0, Bff, nfa, X0, nfa, 0.0, BX, nfa));
      PetscCall(JRGemm("N", "N", nfa, nd, nfa, 1.0, Bff, nfa, U, nfa, 0.0, BU, nfa));
      PetscCall(JRGemm("N", "N", nsl, nsl, nfa, -1.0, Bsf, nsl, X0, nfa, 1.0, b0, nsl));
      PetscCall(JRGemm("T", "N", nsl, nsl, nfa, -1.0, X0, nfa, Bfs, nfa, 1.0, b0, nsl));
      PetscCall(JRGemm("T", "N", nsl, nsl, nfa, 1.0, X0, nfa, BX, nfa, 1.0, b0, nsl));
      PetscCall(JRGemm("N", "N", nsl, nd, nfa, 1.0, Bsf, nsl, U, nfa, 0.0, ba, nsl));
      PetscCall(JRGemm("T", "N", nsl, nd, nfa, -1.0, X0, nfa, BU, nfa, 1.0, ba, nsl));
      PetscCall(JRGemm("T", "N", nd, nsl, nfa, 1.0, U, nfa, Bfs, nfa, 0.0, bb, nd));
      PetscCall(JRGemm("T", "N", nd, nsl, nfa, -1.0, U, nfa, BX, nfa, 1.0, bb, nd));
      PetscCall(JRGemm("T", "N", nd, nd, nfa, 1.0, U, nfa, BU, nfa, 0.0, bc, nd));
    }
    f->lrnsl = nsl;
    PetscCall(PetscArraycpy(f->lrkey, f->isl, nsl));
  }
  for (PetscInt i = 0; i < S; i++) B0[3 * S + i] = B0[S + i] + g * B0[2 * S + i]; /* Cv = C + (gamma / w) Kg */
  for (PetscInt e = 0; e < f->ne; e++)
    if (f->memp[e] >= 0) {
      f->td[2 * f->memp[e]]     = e;
      f->td[2 * f->memp[e] + 1] = f->srow[e];
    }
  PetscFunctionReturn(0);
}

/* QuasiStatic through the distinct rows (LowRankPoint's pieces): the step's Kp = Aref + Rd^T dD Rd, dD from the
   elements' coefficients less the reference ones; with P = I + dD G and Q1 = I - P^-1 dD G = P^-1 (Woodbury), T's fast rows
   are -X0 + U Y with Y = P^-1 dD W - Q1 dD Rs, and Kr = K0 + KU Y + Rs^T dD (Rd T), Rd T = Rs - W + G Y, Mr and Cr
   from their pieces, Br = (Rs^T (I - dD Hn) - KU Q1) E (E: the held slips' stiffness at their rows) with
   Hn = Rd_f Kff^-1 Rd_f^T = G Q1. Slot k keeps Rd T and Hn for the commits. Out as QuasiStatic's. */
static PetscErrorCode LowRankStatic(struct _JRMonodromy *f, PetscInt k, PetscInt nc, const PetscInt *col, PetscReal **X, PetscReal *wmax)
{
  const PetscInt nk = f->nk, nd = f->nd, nsl = f->nsl, nfa = f->nfa, nt = f->mt - f->n2r;
  const PetscReal *U = f->LR, *G = U + nfa * nd, *W = G + nd * nd, *Rs = W + nd * nsl, *K0 = Rs + nd * nsl, *KU = K0 + nsl * nsl, *B0 = KU + nsl * nd;
  PetscReal     *dD = f->LW, *DG = dD + nd * nd, *P = DG + nd * nd, *Q1 = P + nd * nd, *DH = Q1 + nd * nd, *Y = DH + nd * nd, *DW = Y + nd * nsl, *DR = DW + nd * nsl, *tmp = DR + nd * nsl, *Bm = tmp + nd * nsl;
  PetscReal     *RT = f->Ts + k * nk * nk, *Hn = f->KFs + k * nk * nk, *Mr = f->QW + 3 * nk * nk, *RH = f->QW + 5 * nk * nk;
  PetscBool      singular;
  const PetscBool all = (PetscBool)!f->dvalid;

  PetscFunctionBeginUser;
  PetscCall(PetscArraycpy(f->bws + k * f->cap, f->bwt, nt));
  if (all) { /* from the reference coefficients, at the point's first map; then by the elements that change (f->chg) */
    PetscCall(PetscArrayzero(f->dDk, nd * nd));
    PetscCall(PetscArraycpy(f->cl, f->cref, 3 * f->ne));
    f->dvalid = PETSC_TRUE;
  }
  for (PetscInt ic = 0; ic < (all ? f->ne : f->nchg); ic++) {
    const PetscInt   e = all ? ic : f->chg[ic];
    PetscReal       *o = f->cl + 3 * e;
    const PetscReal *c = f->cfn + 3 * e, d0 = c[0] - o[0], d1 = c[1] - o[1], d2 = c[2] - o[2];
    o[0] = c[0];
    o[1] = c[1];
    o[2] = c[2];
    if (d0 == 0.0 && d1 == 0.0 && d2 == 0.0) continue;
    if (!f->Cf) {
      const PetscInt ir = f->dr[e];
      f->dDk[ir + ir * nd] += d0;
      if (f->srow[e] >= 0) {
        const PetscInt is = f->dr[f->srow[e]];
        f->dDk[ir + is * nd] += d1;
        f->dDk[is + is * nd] += d2;
      }
    } else { /* d0 ct ct^T + d1 ct cs^T + d2 cs cs^T, ct and cs its rows' coefficients */
      const PetscReal *ct = f->Cf + e * nd, *cs = f->srow[e] >= 0 ? f->Cf + f->srow[e] * nd : NULL;
      for (PetscInt b = 0; b < nd; b++)
        for (PetscInt a = 0; a < nd; a++) f->dDk[a + b * nd] += d0 * ct[a] * ct[b] + (cs ? d1 * ct[a] * cs[b] + d2 * cs[a] * cs[b] : 0.0);
    }
  }
  PetscCall(PetscArraycpy(dD, f->dDk, nd * nd));
  PetscCall(JRGemm("N", "N", nd, nd, nd, 1.0, dD, nd, G, nd, 0.0, DG, nd));
  PetscCall(PetscArraycpy(P, DG, nd * nd));
  for (PetscInt i = 0; i < nd; i++) P[i + i * nd] += 1.0;
  PetscCall(SmallInverse(nd, P, f->lpiv, DH, &singular)); /* Q1 = I - P^-1 dD G = P^-1 */
  PetscCheck(!singular, PETSC_COMM_SELF, PETSC_ERR_LIB, "Floquet exponents in time: the fast modes' stiffness is singular; -frf_stability_time_fast 0 marches every mode");
  PetscCall(PetscArraycpy(Q1, P, nd * nd));
  PetscCall(JRGemm("N", "N", nd, nsl, nd, 1.0, dD, nd, W, nd, 0.0, DW, nd));
  PetscCall(JRGemm("N", "N", nd, nsl, nd, 1.0, Q1, nd, DW, nd, 0.0, Y, nd));
  PetscCall(JRGemm("N", "N", nd, nsl, nd, 1.0, dD, nd, Rs, nd, 0.0, DR, nd));
  PetscCall(JRGemm("N", "N", nd, nsl, nd, -1.0, Q1, nd, DR, nd, 1.0, Y, nd));
  for (PetscInt i = 0; i < nd * nsl; i++) RT[i] = Rs[i] - W[i];
  PetscCall(JRGemm("N", "N", nd, nsl, nd, 1.0, G, nd, Y, nd, 1.0, RT, nd));
  PetscCall(JRGemm("N", "N", nd, nd, nd, 1.0, G, nd, Q1, nd, 0.0, Hn, nd));
  /* RH = [Kr, Cr, Br] */
  PetscCall(PetscArraycpy(RH, K0, nsl * nsl));
  PetscCall(JRGemm("N", "N", nsl, nsl, nd, 1.0, KU, nsl, Y, nd, 1.0, RH, nsl));
  PetscCall(JRGemm("N", "N", nd, nsl, nd, 1.0, dD, nd, RT, nd, 0.0, tmp, nd));
  PetscCall(JRGemm("T", "N", nsl, nsl, nd, 1.0, Rs, nd, tmp, nd, 1.0, RH, nsl));
  for (PetscInt q = 0; q < 2; q++) { /* Mr, then Cr: B0 + Ba Y + Y^T Bb + Y^T Bc Y (Mm's pieces, Cv's) */
    const PetscReal *b0 = B0 + 3 * q * (nsl * nsl + 2 * nsl * nd + nd * nd), *ba = b0 + nsl * nsl, *bb = ba + nsl * nd, *bc = bb + nd * nsl;
    PetscReal       *out = q ? RH + nsl * nsl : Mr;
    PetscCall(PetscArraycpy(out, b0, nsl * nsl));
    PetscCall(JRGemm("N", "N", nsl, nsl, nd, 1.0, ba, nsl, Y, nd, 1.0, out, nsl));
    PetscCall(JRGemm("T", "N", nsl, nsl, nd, 1.0, Y, nd, bb, nd, 1.0, out, nsl));
    PetscCall(JRGemm("N", "N", nd, nsl, nd, 1.0, bc, nd, Y, nd, 0.0, tmp, nd));
    PetscCall(JRGemm("T", "N", nsl, nsl, nd, 1.0, Y, nd, tmp, nd, 1.0, out, nsl));
  }
  /* Bm = Rs^T (I - dD Hn) - KU Q1 (nsl x nd); Br's column c: the held slip's stiffness x Bm's column at its row */
  PetscCall(JRGemm("N", "N", nd, nd, nd, -1.0, dD, nd, Hn, nd, 0.0, DH, nd));
  for (PetscInt i = 0; i < nd; i++) DH[i + i * nd] += 1.0;
  PetscCall(JRGemm("T", "N", nsl, nd, nd, 1.0, Rs, nd, DH, nd, 0.0, Bm, nsl));
  PetscCall(JRGemm("N", "N", nsl, nd, nd, -1.0, KU, nsl, Q1, nd, 1.0, Bm, nsl));
  { /* Br = Bm Cq, Cq's columns the held slips' rows' coefficients in Rd scaled by their stiffness (nd x nc) */
    PetscReal *Cq = Bm + nsl * nd;
    for (PetscInt q = 0; q < nc; q++) RowCoefficients(f, f->td[2 * col[q]], f->bwt[col[q]], Cq + q * nd);
    if (nc) PetscCall(JRGemm("N", "N", nsl, nc, nd, 1.0, Bm, nsl, Cq, nd, 0.0, RH + 2 * nsl * nsl, nsl));
  }
  PetscCall(SlowSolve(f, Mr, RH, Mr + nk * nk, wmax));
  *X = RH;
  PetscFunctionReturn(0);
}

/* The map of the state over a step of length dtstep with the elements' states of StepStates (f->ka, f->kb, f->th:
   stuck or slipping at either bound, in contact or not, each element's two states weighted by their shares): the
   variational equations are then linear with constant coefficients, Z' = A Z, A = [L, Aw; 0, 0] in the blocks (Q, P)
   and the marched slips W, L = [0, I; G + Mm^-1 (-R^T D)], and the map is exp(A dtstep) = [SL, SW; 0, I]:
   SL = exp(L dtstep) and SW, the response to a held slip, = phi1(L dtstep) Aw dtstep (phi1(X) = sum_k X^k / (k + 1)!,
   no inverse of L: the pattern's stiffness may be singular) by ExpmPhi on a step halved sq times to
   dt w_max <= JR_MONO_WDT. Into slot k. */
static PetscErrorCode StepMap(struct _JRMonodromy *f, PetscReal dtstep, PetscInt k)
{
  const PetscInt nk = f->nk, ne = f->ne, n2 = f->n2r, m2 = 2 * nk, nt = f->mt - n2;
  PetscReal     *SL = f->SL + k * m2 * m2, *SW = f->SW + k * m2 * ne, *G = f->PS + 4 * m2 * m2;
  PetscReal      wmax = f->wmax, dt;
  PetscInt       sq, *col = f->cols + k * ne, nc = 0;

  PetscFunctionBeginUser;
  PetscCall(StiffnessUpdate(f));
  for (PetscInt c = 0; c < nt; c++) /* the held slips of stuck elements: SW's only nonzero columns */
    if (f->bwt[c] != 0.0) col[nc++] = c;
  f->ncol[k] = nc;
  PetscCall(PetscArrayzero(f->XL, n2 * n2));
  PetscCall(PetscArrayzero(f->XW, n2 * nc));
  if (!f->nfa) { /* XL = L dt = [0, I; -Mm^-1 Kp, -Mm^-1 Cv] dt, XW = Aw dt = [0; Mm^-1 Bw] dt */
    sq = dtstep * wmax > JR_MONO_WDT ? (PetscInt)PetscCeilReal(PetscLog2Real(dtstep * wmax / JR_MONO_WDT)) : 0;
    dt = dtstep / (PetscReal)(1 << sq);
    for (PetscInt i = 0; i < nk; i++) f->XL[i + (nk + i) * n2] = dt;
    PetscCall(JRGemm("N", "N", nk, nk, nk, -dt, f->Mi, nk, f->Kp, nk, 0.0, f->T2, nk));
    for (PetscInt c = 0; c < nk; c++)
      for (PetscInt i = 0; i < nk; i++) {
        f->XL[nk + i + c * n2]        = f->T2[i + c * nk];
        f->XL[nk + i + (nk + c) * n2] = dt * f->G[i + (nk + c) * nk];
      }
    for (PetscInt q = 0; q < nc; q++) { /* Bw's columns bwt r_e */
      const PetscReal *r = f->RSt + f->tel[col[q]] * nk, bw = f->bwt[col[q]];
      for (PetscInt i = 0; i < nk; i++) f->T2[i + q * nk] = bw * r[i];
    }
    if (nc) PetscCall(JRGemm("N", "N", nk, nc, nk, dt, f->Mi, nk, f->T2, nk, 0.0, f->XW + nk, n2));
  } else { /* the slow modes with the fast ones condensed: [0, I; -Mr^-1 [Kr, Cr]] dt and [0; Mr^-1 Br] dt */
    const PetscInt   nsl = f->nsl;
    const PetscReal *Mi = f->QW + 3 * nk * nk, *P = Mi + nk * nk; /* where either condensation leaves Mr^-1, Mr^-1 Kr */
    PetscReal       *X  = NULL;
    if (f->lowrank) PetscCall(LowRankStatic(f, k, nc, col, &X, &wmax));
    else PetscCall(QuasiStatic(f, k, nc, col, &X, &wmax));
    sq = dtstep * wmax > JR_MONO_WDT ? (PetscInt)PetscCeilReal(PetscLog2Real(dtstep * wmax / JR_MONO_WDT)) : 0;
    dt = dtstep / (PetscReal)(1 << sq);
    for (PetscInt i = 0; i < nsl; i++) f->XL[i + (nsl + i) * n2] = dt;
    for (PetscInt c = 0; c < nsl; c++)
      for (PetscInt i = 0; i < nsl; i++) f->XL[nsl + i + c * n2] = -dt * P[i + c * nsl];
    PetscCall(JRGemm("N", "N", nsl, nsl, nsl, -dt, Mi, nsl, X + nsl * nsl, nsl, 0.0, f->XL + nsl + nsl * n2, n2));
    if (nc) PetscCall(JRGemm("N", "N", nsl, nc, nsl, dt, Mi, nsl, X + n2 * nsl, nsl, 0.0, f->XW + nsl, n2));
  }
  /* SL, and SW = G XW (XW's first n2 / 2 rows are 0) */
  PetscCall(ExpmPhi(n2, f->XL, sq, SL, nc ? G : NULL, f->PS));
  if (nc) PetscCall(JRGemm("N", "N", n2, nc, n2 / 2, 1.0, G, n2, f->XW + n2 / 2, n2, 0.0, SW, n2));
  PetscFunctionReturn(0);
}

/* The tracked slips committed at the end of step j (whose map was slot k): a slipping element's slip becomes its
   u -+ mu n / kt, so its row of Y becomes the rows of du + side drdv dv. A slip is read only where its element is
   stuck (the step maps' held slips), so it is committed only where the element slips at the end of step j and not at
   the end of step j + 1 on the same side (it sticks or reverses within that step), and at the period's end. The
   modes' motion is Y's (Q) rows, or with fast modes condensed T q_s + T_w w (slot k's). */
static PetscErrorCode Commit(struct _JRMonodromy *f, PetscInt j, PetscInt k)
{
  const PetscInt nk = f->nk, ne = f->ne, n2 = f->n2r, m = f->mt, mc = m - f->np, nt = m - n2;
  PetscInt       nr = 0;
  PetscReal     *Y = f->Y, *side = f->sdr;

  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < ne; e++) {
    const PetscInt  sd = f->memp[e] < 0 ? 0 : Side(f, e, j), q = 2 * f->memp[e];
    const PetscBool contact = (PetscBool)(sd && f->cnt[e * (2 * f->ns + 1) + 2 * j + 2]);
    const PetscReal drdv    = contact && f->kt[e] > 0 ? f->mu[e] * f->kn[e] / f->kt[e] : 0.0;
    if (!sd || (j + 1 < f->ns && Side(f, e, j + 1) == sd)) continue;
    side[e]       = sd * drdv;
    f->rows[nr++] = q;
    if (drdv != 0.0) f->rows[nr++] = q + 1;
  }
  if (!nr) PetscFunctionReturn(0);
  for (PetscInt r = 0; r < nr; r++)
    for (PetscInt i = 0; i < nk; i++) f->Rg[r + i * nr] = f->RT[f->rows[r] + i * 2 * nt];
  if (f->nfa && f->lowrank) { /* the same from slot k's Rd T and Hn = Rd_f Kff^-1 Rd_f^T at the rows' distinct ones */
    const PetscInt   nsl = f->nsl, nd = f->nd;
    const PetscReal *RTk = f->Ts + k * nk * nk, *Hk = f->KFs + k * nk * nk, *bw = f->bws + k * f->cap;
    PetscReal       *A = f->CB, *B = A + nr * nsl, *HC = f->LW, *Ct = HC + nd * nt, *Cr = Ct + nd * nt;
    /* the rows' coefficients in Rd: Ct (nd x nt) of the held slips' (scaled by their stiffness), Cr (nd x nr) of the
       committing ones; HC = Hn Ct, A = Cr^T (Rd T), B = Cr^T HC */
    for (PetscInt c = 0; c < nt; c++) RowCoefficients(f, f->td[2 * c], bw[c], Ct + c * nd);
    for (PetscInt r = 0; r < nr; r++) RowCoefficients(f, f->td[f->rows[r]], 1.0, Cr + r * nd);
    PetscCall(JRGemm("N", "N", nd, nt, nd, 1.0, Hk, nd, Ct, nd, 0.0, HC, nd));
    PetscCall(JRGemm("T", "N", nr, nsl, nd, 1.0, Cr, nd, RTk, nd, 0.0, A, nr));
    PetscCall(JRGemm("T", "N", nr, nt, nd, 1.0, Cr, nd, HC, nd, 0.0, B, nr));
    PetscCall(JRGemm("N", "N", nr, mc, nsl, 1.0, A, nr, Y, m, 0.0, f->DUV, nr));
    PetscCall(JRGemm("N", "N", nr, mc, nt, 1.0, B, nr, Y + n2, m, 1.0, f->DUV, nr));
  } else if (f->nfa) { /* DUV = (Rg T) Y_q + (Rg_f Kff^-1 R_f diag(bw)) Y_w, Rg_f Kff^-1 = (Kff^-T Rg_f^T)^T */
    const PetscInt nsl = f->nsl, nfa = f->nfa;
    PetscReal     *A = f->CB, *B = A + nr * nsl, *Rf = B + nr * nt, *KR = Rf + nfa * nr, *bw = f->bws + k * f->cap;
    PetscCall(JRGemm("N", "N", nr, nsl, nk, 1.0, f->Rg, nr, f->Ts + k * nk * nk, nk, 0.0, A, nr));
    for (PetscInt r = 0; r < nr; r++)
      for (PetscInt a = 0; a < nfa; a++) Rf[a + r * nfa] = f->Rg[r + f->ifa[a] * nr];
    PetscCall(JRGemm("T", "N", nfa, nr, nfa, 1.0, f->KFs + k * nk * nk, nfa, Rf, nfa, 0.0, KR, nfa)); /* Kff^-T Rg_f^T */
    PetscCall(JRGemm("T", "N", nr, nt, nfa, 1.0, KR, nfa, f->Rfa, nfa, 0.0, B, nr));
    for (PetscInt c = 0; c < nt; c++)
      for (PetscInt r = 0; r < nr; r++) B[r + c * nr] *= bw[c];
    PetscCall(JRGemm("N", "N", nr, mc, f->nsl, 1.0, A, nr, Y, m, 0.0, f->DUV, nr));
    PetscCall(JRGemm("N", "N", nr, mc, nt, 1.0, B, nr, Y + n2, m, 1.0, f->DUV, nr));
  } else PetscCall(JRGemm("N", "N", nr, mc, nk, 1.0, f->Rg, nr, Y, m, 0.0, f->DUV, nr));
  for (PetscInt r = 0, e = 0; r < nr; e++) {
    const PetscInt q = 2 * f->memp[e];
    if (f->memp[e] < 0 || f->rows[r] != q) continue;
    if (r + 1 < nr && f->rows[r + 1] == q + 1) {
      for (PetscInt c = 0; c < mc; c++) Y[n2 + f->memp[e] + c * m] = f->DUV[r + c * nr] + side[e] * f->DUV[r + 1 + c * nr];
      r += 2;
    } else {
      for (PetscInt c = 0; c < mc; c++) Y[n2 + f->memp[e] + c * m] = f->DUV[r + c * nr];
      r += 1;
    }
  }
  PetscFunctionReturn(0);
}

/* The fundamental matrix Y (f->mt x f->mt, from the identity; its first f->mt - f->np columns, Classify) over one
   period of friction elements (no cubic spring):
   per step the map of its states (StepMap; kept by pattern where no state changes within the step: a period's
   patterns mostly repeat), then the tracked slips committed at the step's end by the return map's derivative */
static PetscErrorCode MarchPatterns(JRHBM h, PetscReal dt)
{
  struct _JRMonodromy *f  = h->mono;
  const PetscInt       nk = f->nk, ne = f->ne, n2 = f->n2r, m2 = 2 * nk, m = f->mt, mc = m - f->np, nt = m - n2, ns = f->ns;
  PetscReal           *Y  = f->Y;

  PetscFunctionBeginUser;
  f->nslot = f->next = 0;
  f->kvalid = f->dvalid = f->svalid = PETSC_FALSE;
  for (PetscInt j = 0; j < ns; j++) {
    PetscInt  k      = -1;
    PetscBool change = PETSC_FALSE;
    f->nchg          = 0;
    for (PetscInt e = 0; e < ne; e++) {
      StepStates(f, e, j, &f->ka[e], &f->kb[e], &f->th[e]);
      f->key[e] = f->kb[e] >= 3 || f->kb[e] == 1 ? f->kb[e] : 0; /* slipping off contact: either side the same map */
      if (f->ka[e] != f->kb[e]) change = PETSC_TRUE;
      if (!f->svalid || f->ka[e] != f->lka[e] || f->kb[e] != f->lkb[e] || (f->ka[e] != f->kb[e] && f->th[e] != f->lth[e])) f->chg[f->nchg++] = e;
    }
    if (change) { /* a state changes within the step: the map of the states weighted by their shares, not kept */
      k = JR_MONO_SLOTS;
      PetscCall(StepMap(f, dt, k));
    }
    for (PetscInt q = 0; q < f->nslot && k < 0; q++)
      if (!memcmp(f->key, f->slotkey + q * ne, (size_t)ne)) k = q;
    if (k < 0) {
      k       = f->next;
      f->next = (f->next + 1) % JR_MONO_SLOTS;
      if (f->nslot < JR_MONO_SLOTS) f->nslot++;
      PetscCall(PetscArraycpy(f->slotkey + k * ne, f->key, ne));
      PetscCall(StepMap(f, dt, k));
    }
    /* [Q; P] <- SL [Q; P] + SW W */
    PetscCall(JRGemm("N", "N", n2, mc, n2, 1.0, f->SL + k * m2 * m2, n2, Y, m, 0.0, f->T2, n2));
    if (nt && f->ncol[k]) { /* SW's columns by the held slips' rows of Y, gathered */
      const PetscInt nc = f->ncol[k], *col = f->cols + k * ne;
      for (PetscInt c = 0; c < mc; c++)
        for (PetscInt q = 0; q < nc; q++) f->Y0[q + c * nc] = Y[n2 + col[q] + c * m];
      PetscCall(JRGemm("N", "N", n2, mc, nc, 1.0, f->SW + k * m2 * ne, n2, f->Y0, nc, 1.0, f->T2, n2));
    }
    for (PetscInt c = 0; c < mc; c++) PetscCall(PetscArraycpy(Y + c * m, f->T2 + c * n2, n2));
    /* the slips committed at step j + 1 */
    if (nt) PetscCall(Commit(f, j, k));
  }
  PetscFunctionReturn(0);
}

/* The steps per period at frequency w: at least steps and the harmonic balance's samples; RK4 (a cubic spring) also
   dt w_max <= 0.5, while the step maps are exact for any dt (scaling and squaring) */
static PetscInt Steps(JRHBM h, PetscReal w, PetscInt steps)
{
  const struct _JRMonodromy *f = h->mono;
  const PetscInt             ns = PetscMax(steps, h->Ns);

  return f->smooth ? PetscMax(ns, (PetscInt)PetscCeilReal(2 * PETSC_PI * f->wmax / (0.5 * w))) : ns;
}

/* The kept modes split at frequency w (h->monofast): fast where K_ii / Mm_ii > (monofast H w)^2 and the mode's own
   damping makes it decay by e within a period (Cv_ii / (2 Mm_ii) >= w / (2 pi): its transients die out, it follows
   the slow ones), condensed quasi-statically (QuasiStatic); slow and marched otherwise (an undamped fast mode keeps
   its exponent, which switching might pump); none fast when monofast is 0 or no mode would be slow.
   f->isl, f->ifa, f->nsl, f->nfa, the room f->cap of the held slips' fast shapes, and *mt becomes 2 nsl + the tracked slips. */
static PetscErrorCode FastModes(JRHBM h, PetscReal w, PetscInt *mt)
{
  struct _JRMonodromy *f  = h->mono;
  const PetscInt       nk = f->nk, nt = *mt - 2 * nk;
  const PetscReal      wc = h->monofast * h->H * w;

  PetscFunctionBeginUser;
  f->nsl = f->nfa = 0;
  for (PetscInt i = 0; i < nk; i++) {
    if (h->monofast > 0 && f->K[i + i * nk] > wc * wc * f->Mm[i + i * nk] && f->Cv[i + i * nk] / (2 * f->Mm[i + i * nk]) >= w / (2 * PETSC_PI)) f->ifa[f->nfa++] = i;
    else f->isl[f->nsl++] = i;
  }
  if (!f->nsl || !f->nfa) {
    f->nsl = nk;
    f->nfa = 0;
    for (PetscInt i = 0; i < nk; i++) f->isl[i] = i;
  }
  if (!f->Ts || nt > f->cap) {
    PetscCall(PetscFree4(f->Ts, f->KFs, f->bws, f->pivs));
    PetscCall(PetscFree3(f->KFc, f->XZc, f->WB));
    PetscCall(PetscFree2(f->Rfa, f->bwt));
    PetscCall(PetscFree(f->CB));
    f->cap = nt;
    PetscCall(PetscMalloc4((JR_MONO_SLOTS + 1) * nk * nk + 1, &f->Ts, (JR_MONO_SLOTS + 1) * nk * nk + 1, &f->KFs, (JR_MONO_SLOTS + 1) * nt + 1, &f->bws, (JR_MONO_SLOTS + 1) * nk + 1, &f->pivs));
    PetscCall(PetscMalloc3(nk * nk + 1, &f->KFc, 2 * nk * nk + 1, &f->XZc, 3 * nk * nk + 1, &f->WB));
    PetscCall(PetscMalloc2(nk * nt + 1, &f->Rfa, nt + 1, &f->bwt));
    PetscCall(PetscMalloc1(2 * nt * (2 * nk + nt) + nk * nk + 1, &f->CB));
  }
  for (PetscInt e = 0; e < f->ne; e++) /* the tracked elements' r over the fast modes */
    if (f->memp[e] >= 0)
      for (PetscInt a = 0; a < f->nfa; a++) f->Rfa[a + f->memp[e] * f->nfa] = f->RSt[f->ifa[a] + e * nk];
  *mt        = 2 * f->nsl + nt;
  f->mt      = *mt;
  f->lowrank = (PetscBool)(f->nd && f->nfa && (h->monolr == 2 || (h->monolr == 1 && 2 * f->nd <= f->nfa)));
  if (f->lowrank) PetscCall(LowRankPoint(f, h->gamma / w));
  PetscFunctionReturn(0);
}

/* The largest-first Floquet exponents out (2 m: real parts, then imaginary parts) of the solution x (solve space) at
   frequency w, by the monodromy matrix marched on this rank alone (MonodromySetUp() first) */
static PetscErrorCode FloquetLocal(JRHBM h, PetscReal w, const PetscScalar *x, PetscInt steps, PetscReal *out)
{
  struct _JRMonodromy *f  = h->mono;
  const PetscInt       m  = f->m, nk = f->nk;
  const PetscInt       ns = Steps(h, w, steps);
  const PetscReal      dt = 2 * PETSC_PI / w / ns, T = ns * dt;
  PetscReal           *Y  = f->Y, *Cv;
  PetscBLASInt         bm, ld, info, one = 1;
  PetscInt             mt, np;

  PetscFunctionBeginUser;
  if (ns != f->ns) {
    PetscCall(PetscFree5(f->u, f->v, f->wn, f->rb, f->nb));
    PetscCall(PetscFree2(f->sde, f->cnt));
    PetscCall(PetscFree(f->trig));
    f->ns = ns;
    PetscCall(PetscMalloc5(f->ne * (2 * ns + 1) + 1, &f->u, f->ne * (2 * ns + 1) + 1, &f->v, f->ne * (ns + 1) + 1, &f->wn, f->ne * (2 * ns + 1) + 1, &f->rb, f->ne * (2 * ns + 1) + 1, &f->nb));
    PetscCall(PetscMalloc2(f->ne * ns + 1, &f->sde, f->ne * (2 * ns + 1) + 1, &f->cnt));
    PetscCall(PetscMalloc1(h->nc * (2 * ns + 1 + 2 * f->ne) + 1, &f->trig));
  }
  Cv = f->smooth ? f->Y0 : f->Cv; /* Cm + (gamma / w) Kg at this frequency */
  for (PetscInt i = 0; i < nk * nk; i++) Cv[i] = f->C[i] + h->gamma / w * f->Kg[i];
  PetscCall(PointMotion(h, w, x));
  f->unread = (PetscBool)!h->monomarch;
  f->wood   = h->monowood;
  f->nwtot  = 0;
  mt        = f->smooth ? m : Classify(f);
  f->nsl = nk;
  f->nfa = 0;
  if (!f->smooth) PetscCall(FastModes(h, w, &mt));
  if (f->nfa && !f->lowrank) PointBlocks(f);
  f->n2r = 2 * f->nsl;
  /* G = -Mm^-1 [K, Cv] where every mode is marched (its stiffness block for RK4 only: the step maps take Mm^-1 Kp) */
  if (f->smooth) PetscCall(JRGemm("N", "N", nk, nk, nk, -1.0, f->Mi, nk, f->K, nk, 0.0, f->G, nk));
  if (!f->nfa) PetscCall(JRGemm("N", "N", nk, nk, nk, -1.0, f->Mi, nk, Cv, nk, 0.0, f->G + nk * nk, nk));
  PetscCall(PetscArrayzero(Y, mt * mt));
  for (PetscInt i = 0; i < mt; i++) Y[i + i * mt] = 1.0;
  if (f->smooth) PetscCall(MarchRK4(h, dt));
  else PetscCall(MarchPatterns(h, dt));
  /* the multipliers: the marched state's (0 for the slips not read before their first commit, Classify), then 1 per
     held slip and 0 per forgotten one */
  np = f->smooth ? 0 : f->np;
  PetscCall(PetscBLASIntCast(mt - np, &bm));
  PetscCall(PetscBLASIntCast(mt, &ld));
  if (mt - np) {
    PetscReal dummy;
    PetscCallBLAS("LAPACKgeev", LAPACKgeev_("N", "N", &bm, Y, &ld, f->wr, f->wi, &dummy, &one, &dummy, &one, f->work, &f->lwork, &info));
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "Floquet exponents in time: LAPACK geev failed (info %d) at %g Hz", (int)info, (double)(w / (2 * PETSC_PI)));
  }
  for (PetscInt i = mt - np; i < mt; i++) f->wr[i] = f->wi[i] = 0.0;
  for (PetscInt i = 0; i < mt; i++) {
    const PetscReal mod = PetscSqrtReal(f->wr[i] * f->wr[i] + f->wi[i] * f->wi[i]);
    out[i]              = mod > 0 ? PetscLogReal(mod) / T : PETSC_NINFINITY;
    out[m + i]          = PetscAtan2Real(f->wi[i], f->wr[i]) / T;
  }
  for (PetscInt i = mt; i < mt + 2 * f->nfa; i++) { /* the fast modes: condensed, not marched */
    out[i]     = PETSC_NINFINITY;
    out[m + i] = 0.0;
  }
  for (PetscInt e = 0, i = mt + 2 * f->nfa; e < f->ne && !f->smooth; e++)
    if (f->cls[e] != JR_MONO_TRACK) {
      out[i]     = f->cls[e] == JR_MONO_HOLD ? 0.0 : PETSC_NINFINITY;
      out[m + i] = 0.0;
      i++;
    }
  for (PetscInt i = 1; i < m; i++) { /* largest real part first */
    const PetscReal r = out[i], q = out[m + i];
    PetscInt        k = i - 1;
    while (k >= 0 && out[k] < r) {
      out[1 + k]     = out[k];
      out[1 + m + k] = out[m + k];
      k--;
    }
    out[1 + k]     = r;
    out[1 + m + k] = q;
  }
  PetscFunctionReturn(0);
}

/* JRHBMFloquetTimeSupported - whether JRHBMFloquetTime() can run: the solve space is the modal one, or the model is
   condensed onto its joints and has friction elements only (the points' modal unknowns then come from JRHBMExpand()).
   Collective. */
PetscErrorCode JRHBMFloquetTimeSupported(JRHBM h, PetscBool *ok)
{
  PetscInt cub = 0, any;

  PetscFunctionBeginUser;
  PetscCall(JRHBMHillSupported(h, ok));
  if (*ok) PetscFunctionReturn(0);
  for (PetscInt t = 0; t < h->ngroups; t++)
    if (h->g[t].nloc && !strcmp(h->g[t].c->type_name, JRCONTACTCUBIC)) cub = 1;
  PetscCall(MPIU_Allreduce(&cub, &any, 1, MPIU_INT, MPI_MAX, h->comm));
  *ok = (PetscBool)!any;
  PetscFunctionReturn(0);
}

/* The monodromy work of h, set up (collective); an error where JRHBMFloquetTimeSupported() says no */
static PetscErrorCode FloquetBegin(JRHBM h, struct _JRMonodromy **f)
{
  PetscBool ok;

  PetscFunctionBeginUser;
  PetscCall(JRHBMFloquetTimeSupported(h, &ok));
  PetscCheck(ok, h->comm, PETSC_ERR_SUP, "Floquet exponents in time need the modal unknowns, or friction elements only: this model is condensed onto its joints and has a cubic spring (-hbm_condense no keeps the modes)");
  PetscCall(MonodromySetUp(h));
  *f = h->mono;
  PetscFunctionReturn(0);
}

/*
  JRHBMFloquetTime - the Floquet exponents of the solution a (the modal unknowns, JRHBMExpand() of a condensed model's) at frequency w from the monodromy
  matrix of the variational equations marched over one period (collective; rank 0 marches and broadcasts).

  Input: steps, the least steps per period (more if the stiffest mode or the harmonic balance's samples ask).
  Output: nexp = 2 nk + ne (nk the modes other than rigid-body ones, ne the friction elements: their slips); re, im (room for
  nexp each, may be NULL): the exponents, largest real part first [1/s] (a zero multiplier, a slip that a slipping
  element forgets, gives -inf, and so does a fast mode condensed by JRHBMSetFloquetFast); maxre: the largest real part; nsteps: the steps per period taken (may be NULL).
  An error for a condensed model (JRHBMHillSupported()).
*/
PetscErrorCode JRHBMFloquetTime(JRHBM h, PetscReal w, Vec a, PetscInt steps, PetscInt *nexp, PetscReal re[], PetscReal im[], PetscReal *maxre, PetscInt *nsteps)
{
  struct _JRMonodromy *f;
  PetscInt             m;
  PetscReal           *out;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(JR_HBMFloquetTime, 0, 0, 0, 0));
  PetscCall(FloquetBegin(h, &f));
  m = f->m;
  PetscCall(PetscCalloc1(1 + 2 * m, &out));
  if (!h->rank) {
    const PetscScalar *x;
    PetscCall(VecGetArrayRead(a, &x));
    PetscCall(FloquetLocal(h, w, x, steps, out + 1));
    PetscCall(VecRestoreArrayRead(a, &x));
    out[0]    = m ? out[1] : 0.0;
    h->monond = f->lowrank ? f->nd : 0;
    h->mononp = f->smooth ? 0 : f->np;
    h->monowu = f->nwtot;
  }
  if (h->size > 1) PetscCallMPI(MPI_Bcast(out, (PetscMPIInt)(1 + 2 * m), MPIU_REAL, 0, h->comm));
  if (h->size > 1) PetscCallMPI(MPI_Bcast(&h->monond, 1, MPIU_INT, 0, h->comm));
  if (h->size > 1) PetscCallMPI(MPI_Bcast(&h->mononp, 1, MPIU_INT, 0, h->comm));
  if (h->size > 1) PetscCallMPI(MPI_Bcast(&h->monowu, 1, MPIU_INT, 0, h->comm));
  if (nexp) *nexp = m;
  if (nsteps) *nsteps = Steps(h, w, steps);
  *maxre = out[0];
  if (re) PetscCall(PetscArraycpy(re, out + 1, m));
  if (im) PetscCall(PetscArraycpy(im, out + 1 + m, m));
  PetscCall(PetscFree(out));
  PetscCall(PetscLogEventEnd(JR_HBMFloquetTime, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*
  JRHBMFloquetTimePoints - the largest real part of the Floquet exponents in time (JRHBMFloquetTime) of the points k
  with pick[k] among np solutions X (np x n, the solve space, the same on every rank) at frequencies omega; the points
  shared out over the ranks, each marched by one (collective). maxre[k] of the others is left as it is. nfast (may be
  NULL): the most kept modes condensed at a point (JRHBMSetFloquetFast).
*/
PetscErrorCode JRHBMFloquetTimePoints(JRHBM h, PetscInt np, const PetscReal omega[], const PetscScalar X[], PetscInt n, const PetscBool pick[], PetscInt steps, PetscReal maxre[], PetscInt *nfast)
{
  struct _JRMonodromy *f;
  PetscReal           *out, *mine;
  PetscInt             q = 0, nf = 0, nr = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(JR_HBMFloquetTime, 0, 0, 0, 0));
  PetscCall(FloquetBegin(h, &f));
  PetscCall(PetscMalloc1(2 * f->m + 1, &out));
  PetscCall(PetscCalloc1(np + 1, &mine));
  for (PetscInt k = 0; k < np; k++) {
    if (!pick[k]) continue;
    if (q++ % h->size != h->rank) continue;
    PetscCall(FloquetLocal(h, omega[k], X + k * n, steps, out));
    mine[k] = f->m ? out[0] : 0.0;
    nf      = PetscMax(nf, f->nfa);
    nr      = PetscMax(nr, f->lowrank ? f->nd : 0);
  }
  PetscCall(MPIU_Allreduce(&nr, &h->monond, 1, MPIU_INT, MPI_MAX, h->comm));
  if (h->size > 1) PetscCall(MPIU_Allreduce(MPI_IN_PLACE, mine, (PetscMPIInt)np, MPIU_REAL, MPIU_SUM, h->comm));
  if (nfast) PetscCall(MPIU_Allreduce(&nf, nfast, 1, MPIU_INT, MPI_MAX, h->comm));
  for (PetscInt k = 0; k < np; k++)
    if (pick[k]) maxre[k] = mine[k];
  PetscCall(PetscFree(out));
  PetscCall(PetscFree(mine));
  PetscCall(PetscLogEventEnd(JR_HBMFloquetTime, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*
  JRHBMGetFloquetLowRankRows - the distinct rows through which the last JRHBMFloquetTime() or JRHBMFloquetTimePoints()
  condensed the fast modes (the most over the points; 0: by the fast block's inverse, or none fast). Not collective.
*/
PetscErrorCode JRHBMGetFloquetLowRankRows(JRHBM h, PetscInt *nd)
{
  PetscFunctionBeginUser;
  *nd = h->monond;
  PetscFunctionReturn(0);
}

/*
  JRHBMSetFloquetLowRank - how JRHBMFloquetTime condenses the fast modes at each step's element states: 0 by the fast
  block's LU (every step), 1 (the default) through the elements' distinct rows where at most half as many as the
  fast modes (a reduced model's joints: the Woodbury identity from one LU per point), 2 through them wherever they
  are at most half the kept modes. The same exponents to round-off. Logically collective.
*/
PetscErrorCode JRHBMSetFloquetLowRank(JRHBM h, PetscInt mode)
{
  PetscFunctionBeginUser;
  PetscCheck(mode >= 0 && mode <= 2, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "the fast modes' low-rank condensation %" PetscInt_FMT ": give 0, 1 or 2", mode);
  h->monolr = mode;
  PetscFunctionReturn(0);
}

/*
  JRHBMSetFloquetUnread - leave = PETSC_TRUE (the default): JRHBMFloquetTime leaves the slips that are not read before
  their first commit (their elements slip on the same side at the period's end and through the first step) out of
  the march, their columns of the monodromy matrix being zero (multipliers 0); PETSC_FALSE marches them too. The
  same exponents to round-off. Logically collective.
*/
PetscErrorCode JRHBMSetFloquetUnread(JRHBM h, PetscBool leave)
{
  PetscFunctionBeginUser;
  h->monomarch = (PetscBool)!leave;
  PetscFunctionReturn(0);
}

/*
  JRHBMGetFloquetUnreadSlips - the slips the last JRHBMFloquetTime point left out of the march (JRHBMSetFloquetUnread).
  Not collective.
*/
PetscErrorCode JRHBMGetFloquetUnreadSlips(JRHBM h, PetscInt *np)
{
  PetscFunctionBeginUser;
  *np = h->mononp;
  PetscFunctionReturn(0);
}

/*
  JRHBMSetFloquetWoodbury - update = PETSC_TRUE (the default): where the fast modes are condensed by their block's
  inverse, JRHBMFloquetTime updates that inverse from the last step map's by the Woodbury identity where few elements
  changed state since (at most a third as many columns as fast modes; a new inverse after 16 updates); PETSC_FALSE
  inverts the block at every step map. The same exponents to round-off. Logically collective.
*/
PetscErrorCode JRHBMSetFloquetWoodbury(JRHBM h, PetscBool update)
{
  PetscFunctionBeginUser;
  h->monowood = update;
  PetscFunctionReturn(0);
}

/*
  JRHBMGetFloquetWoodburyUpdates - the updates of the fast block's inverse at the last JRHBMFloquetTime point
  (JRHBMSetFloquetWoodbury). Not collective.
*/
PetscErrorCode JRHBMGetFloquetWoodburyUpdates(JRHBM h, PetscInt *nu)
{
  PetscFunctionBeginUser;
  *nu = h->monowu;
  PetscFunctionReturn(0);
}

/*
  JRHBMSetFloquetFast - the kept modes whose own frequency (sqrt(K_ii / Mm_ii)) exceeds ratio x H w are condensed
  quasi-statically in the monodromy matrix of JRHBMFloquetTime (their inertia and damping forces dropped, the slow
  modes' mass and damping projected on the static shapes): their exponents are reported as -inf, the others'
  change by about (H w / (ratio w_fast))^2. ratio 0 (the default) marches every mode. Logically collective.
*/
PetscErrorCode JRHBMSetFloquetFast(JRHBM h, PetscReal ratio)
{
  PetscFunctionBeginUser;
  PetscCheck(ratio == 0 || ratio >= 2, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "the fast modes' ratio %g: give 0 (none) or at least 2", (double)ratio);
  h->monofast = ratio;
  PetscFunctionReturn(0);
}
