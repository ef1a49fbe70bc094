/*
   JRHBM: the harmonic-balance equations of a linear structure carrying contact elements, in modal
   coordinates (thesis 2.3, eq 2.18) generalised to H harmonics plus the mean.

   Unknowns: modal harmonic coefficients a, harmonic-major blocks over the nm modes,
       a = [a_0 | as_1 ac_1 | ... | as_H ac_H]  (n = nm (2H+1)),  x(t) = Phi (a_0 + sum as_h sin + ac_h cos).
   Residual, per harmonic h >= 1 (and h = 0 without damping and excitation):
       R_s = (Km - (h w)^2 Mm) as - (gamma Km + h w Cm) ac + Phi^T fN_s - fm_s
       R_c = (Km - (h w)^2 Mm) ac + (gamma Km + h w Cm) as + Phi^T fN_c
   with Km = diag(omega_r^2), Mm = I for mass-normalised modes (the full projected matrices in
   physical coordinates), structural damping gamma (H = gamma K, 2.17), viscous Cm = Phi^T C Phi
   and/or modal 2 zeta omega_r, excitation F sin(w t): fm_s = F Phi^T f for h = 1.
   Nonlinear forces: element e with tangential projection row r_e = phi(dof_a) - phi(dof_b) (4.3) sees
   U_e = A^T r_e (A = a as nm x nc) and gives back r_e F_e; jenkins_nv also s_e (normal DOFs) and its
   dynamic normal load N_e - max(n0, 0) (the static part is balanced by the preload).
   Modal basis (-hbm_basis): free, the modes of K; or stuck, the modes of K + Ks with Ks the springs of every
   friction element in contact at rest (n0 > 0) stuck: then Km holds them, each element adds its deviation
   from stuck R^T (F - kt U) (and S^T (N - n0 - kn V)), and the structural damping is gamma Phi^T K Phi (Kg),
   the structure's own stiffness only. Node-to-node elements (JRElements vdof_a) get rows (phi_A - phi_B) . t.
   Rigid-body modes (omega = 0) get the mean equation pin * a0 = 0: no spring or element holds their mean.
   Jacobian: element derivatives projected, blocks (k, m): sum_e r_e dF_km/dU r_e^T = R^T diag(d) R
   (BLAS gemm). The thesis's finite differences (2.23) remain as -hbm_jacobian fd.
   Parallel: elements are split across the ranks (each type in contiguous chunks); each rank sums its
   own into the residual and Jacobian; rank 0 adds the contributions and broadcasts them, so every
   rank holds the same small dense system and runs the same SNES (PETSC_COMM_SELF, prefix hbm_).
*/
#include <jointrom/private/contactimpl.h>
#include <jointrom/private/modelimpl.h>
#include <petscblaslapack.h>

const char *const JRHBMJacobianTypes[] = {"analytic", "fd", "JRHBMJacobianType", "JR_HBM_JACOBIAN_", NULL};

typedef struct {
  JRContact  c;
  PetscBool  normal;
  PetscInt   nloc;
  PetscReal *R, *S;                         /* nloc x nm, column-major */
  PetscReal *U, *V, *F, *N, *DU, *DV, *DN; /* SoA work */
  PetscReal *W;                             /* nloc x nm scratch */
  PetscReal *nstatic;                       /* max(n0, 0) */
  JRContactState *state;
  /* Jacobian split: an element in its state at rest has dF/du = pt I (and dN/dv = pn I, dF/dv = 0) exactly, with
     (pt, pn) = (kt, kn) stuck if it is in contact at rest (n0 > 0) and 0 if open (a gap: no force while it stays
     open); that part, sum_e pt r_e r_e^T (x) I, is assembled once (Kst, Knn) and only the elements out of their state
     at rest are projected per iteration */
  PetscBool  split;
  PetscReal *Kst, *Knn;    /* nm x nm column-major, this rank's elements */
  PetscInt  *sel, nsel;    /* elements not in the stuck pattern */
  PetscReal *Rc, *Sc, *Dc; /* their projection rows (nsel x nm) and one derivative column */
  PetscReal *kt, *kn;
  PetscReal *pt, *pn;      /* the state at rest's dF/du and dN/dv: kt, kn if n0 > 0, else 0 */
  PetscInt  *eidx;         /* the model's element number of each local element */
  PetscReal *Kc;           /* stuck basis: the stuck springs of this rank's elements in contact at rest (nm x nm) */
  PetscReal *R0, *S0;      /* joints in a stuck basis: the members' own rows until Kc is formed */
  PetscInt  *qt, *qn;      /* condensed: each element's joint row among the nq condensed rows, and its normal row */
} HBMGroup;

struct _p_JRHBM {
  MPI_Comm          comm;
  PetscMPIInt       rank, size;
  JRModel           model;
  JRModes           modes;
  PetscBool         setupcalled, physical, view;
  PetscInt          H, Ns, nm, nc, n, nmodes_opt;
  PetscReal         gamma, zeta;
  PetscBool         has_C;
  PetscReal        *Km, *Mm, *Cm; /* nm x nm row-major */
  PetscReal        *omega_r;      /* natural frequencies of the modes kept [rad/s] */
  PetscReal        *pin;          /* rigid-body modes: the mean equation a0_r pin_r = 0 (else 0 = 0) */
  PetscInt          basis;        /* 0 free: modes of K; 1 stuck: modes of K + the stuck springs; 2 mixed: both */
  PetscInt          nfree;        /* mixed: free-interface modes added (-1: as many as stuck ones) */
  PetscBool         basis_set;
  PetscReal        *Kg;           /* the structure's own stiffness in the basis (structural damping gamma Kg) */
  PetscReal        *Kc;           /* stuck basis: the stuck springs in Km of this rank's elements (or members), nm x nm */
  PetscBool         modes_shared; /* JRHBMSetModes(): the modes are another JRHBM's, not solved or destroyed here */
  char              modes_file[PETSC_MAX_PATH_LEN]; /* JRHBMSetModesFile(): save the modes here unless -modes_load/-modes_save */
  PetscInt          fdof, nout, *outdof;
  PetscBool         fdof_set;      /* JRHBMSetExcitationDof() called: -frf_dof ignored */
  PetscInt          npts, ptdir;   /* JRHBMSetOutputPoints(): the response points, for naming the outputs */
  PetscReal        *ptxyz;        /* npts x 3 [m], NULL if none */
  char              ffile[PETSC_MAX_PATH_LEN];
  PetscReal        *fm, level;    /* modal force shape (unit level) and the level [N] */
  PetscReal        *Phiout;       /* nout x nm */
  JRHBMJacobianType jtype;
  PetscInt          ngroups;
  HBMGroup         *g;
  SNES              snes;
  Mat               J;
  Vec               r;
  PetscReal         omega;        /* frequency seen by the SNES callbacks */
  PetscReal        *buf;          /* n + n*n reduction buffer */
  PetscReal        *cache_a;      /* the unknowns at which the groups' forces and derivatives were evaluated */
  PetscBool         cache_ok;
  PetscLogDouble    telem;        /* wall time in Nonlinear(): the elements' forces and Jacobians, with their sums over ranks */
  PetscInt          nelem, nelemjac; /* its calls, and those with a Jacobian */
  char              damping[256];
  /* condensation onto the joints (-hbm_condense): the linear part is solved exactly for the joints' motions */
  PetscInt          condense;     /* option: 0 auto, 1 yes, 2 no */
  PetscBool         repl;         /* a reduced model on several ranks: every rank evaluates all its (few) elements, so
                                     the per-iteration sum over the ranks is not needed */
  MPI_Comm          ecomm;        /* the communicator of sums over the elements: h->comm, or PETSC_COMM_SELF if repl */
  PetscInt          jmotion;      /* first reduction: a joint's members move with 0 its mean motion, 1-2 its linear field
                                     over their coordinates (1: positions, JRElements pos; 2: and stuck-mode motions, phi) */
  PetscBool         cond;         /* in use: the solve space is the joints' motions */
  PetscInt          nq, ns;       /* condensed rows (nj tangential, then nj normal for jenkins_nv); solve-space size */
  PetscReal        *Q, *V, *lamv, *cv, *QV, *VF; /* rows (nq x nm row-major); (Kg, Mm) eigenvectors (col-major), values,
                                                     V^T Cm V (diagonal); Q V (nq x nm row-major); V^T fm */
  PetscReal        *Z0, *G0;      /* the mean block Kg + pin, LU-factored (nm x nm); Q Z0^-1 Q^T (nq x nq) */
  PetscBLASInt     *piv0;
  PetscReal        *Gb, *inv;     /* per harmonic at frequency wq: G, dG/dw (re, im), xF, dxF/dw; 1/z_k (re, im) */
  PetscReal        *QQ, *cb;      /* products of QV's rows per mode (nm x (pairs r <= c, then rows x VF)); CondBlocks work */
  PetscReal        *jres;         /* JRHBMComputeJacobian: the residual it also computes (ns) */
  PetscReal        *pptab;        /* JRHBMResponse: sin, cos of each harmonic at 16 nc samples of a cycle */
  PetscReal         wq;
  PetscBool         wq_ok;
  char              condinfo[256];
  PetscReal        *ctmp;         /* ns + ns^2 work */
  PetscReal        *llu;          /* JRHBMLinearSolution(): LU of the Jacobian (ns x ns) and its pivots */
  PetscBLASInt     *lpiv;
};

static PetscErrorCode Gemm(const char *ta, const char *tb, PetscInt m, PetscInt n, PetscInt k, PetscReal alpha, const PetscReal *A, PetscInt lda, const PetscReal *B, PetscInt ldb, PetscReal beta, PetscReal *C, PetscInt ldc)
{
  PetscBLASInt bm, bn, bk, la, lb, lc;

  PetscFunctionBeginUser;
  if (!m || !n) PetscFunctionReturn(0);
  PetscCall(PetscBLASIntCast(m, &bm));
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCall(PetscBLASIntCast(k, &bk));
  PetscCall(PetscBLASIntCast(PetscMax(lda, 1), &la));
  PetscCall(PetscBLASIntCast(PetscMax(ldb, 1), &lb));
  PetscCall(PetscBLASIntCast(PetscMax(ldc, 1), &lc));
  if (!k) {
    if (beta != 1.0)
      for (PetscInt j = 0; j < n; j++)
        for (PetscInt i = 0; i < m; i++) C[i + j * ldc] *= beta;
    PetscFunctionReturn(0);
  }
  PetscCallBLAS("BLASgemm", BLASgemm_(ta, tb, &bm, &bn, &bk, &alpha, A, &la, B, &lb, &beta, C, &lc));
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMCreate(MPI_Comm comm, JRHBM *hbm)
{
  JRHBM h;

  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(PetscNew(&h));
  h->comm       = comm;
  h->ecomm      = comm;
  h->H          = 1;
  h->Ns         = 64;
  h->fdof       = 0;
  h->level      = 1.0;
  h->jtype      = JR_HBM_JACOBIAN_ANALYTIC;
  h->nmodes_opt = -1;
  h->nfree      = -1;
  PetscCallMPI(MPI_Comm_rank(comm, &h->rank));
  PetscCallMPI(MPI_Comm_size(comm, &h->size));
  *hbm = h;
  PetscFunctionReturn(0);
}

/* The structure and its elements (reference kept) */
PetscErrorCode JRHBMSetModel(JRHBM h, JRModel model)
{
  PetscFunctionBeginUser;
  h->model       = model;
  h->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*
  Options: -hbm_harmonics H, -hbm_samples N, -hbm_modes m (default: all for small models, else 10),
  -hbm_physical, -hbm_gamma, -hbm_zeta, -hbm_jacobian analytic|fd, -hbm_view; the excitation
  -frf_dof i or -frf_force_file FILE, the responses -frf_output i,j,...; and -hbm_snes_*, -hbm_ksp_*,
  -hbm_pc_* on the nonlinear solver.
*/
PetscErrorCode JRHBMSetFromOptions(JRHBM h)
{
  PetscInt  jt = h->jtype, nout = 64;
  PetscInt  out[64] = {0};
  PetscBool flg;

  PetscFunctionBeginUser;
  out[0] = h->fdof; /* the default shown by -help */
  PetscOptionsBegin(h->comm, NULL, "Harmonic balance (JRHBM)", "JRHBM");
  PetscCall(PetscOptionsInt("-hbm_harmonics", "Harmonics H (plus the mean) in the response", "JRHBMSetUp", h->H, &h->H, NULL));
  PetscCall(PetscOptionsInt("-hbm_samples", "Time samples per cycle N for alternating frequency-time (N >= 2H+1)", "JRHBMSetUp", h->Ns, &h->Ns, NULL));
  PetscCall(PetscOptionsInt("-hbm_modes", "Number of linear modes in the modal superposition (default: all up to 200 DOFs, else 10)", "JRHBMSetUp", h->nmodes_opt, &h->nmodes_opt, NULL));
  {
    const char *bases[] = {"free", "stuck", "mixed"};
    PetscCall(PetscOptionsEList("-hbm_basis", "Modal basis: free (modes of K: the interface held by the bolts only), stuck (modes of K plus every element in contact at rest stuck; the elements then add only their deviation from stuck) or mixed (Ritz vectors of the stuck structure in the span of both)", "JRHBMSetUp", bases, 3, bases[h->basis], &h->basis, &h->basis_set));
    PetscCall(PetscOptionsInt("-hbm_free_modes", "-hbm_basis mixed: free-interface modes added to the -hbm_modes stuck ones (default: as many)", "JRHBMSetUp", h->nfree, &h->nfree, NULL));
  }
  {
    const char *conds[] = {"auto", "yes", "no"};
    PetscCall(PetscOptionsEList("-hbm_condense", "Reduced models: eliminate the modes and solve for the joints' motions only (auto: when it is exact and smaller)", "JRHBMSetUp", conds, 3, conds[h->condense], &h->condense, NULL));
  }
  {
    const char *jm[] = {"mean", "linear", "mode"};
    PetscCall(PetscOptionsEList("-rom_joint_motion", "How a joint's members move: with its mean motion (4.4), or with a linear field over their coordinates, fitted by least squares: their positions (linear: the mean plus the joint's rotation) or their motions in the stuck mode of interest (mode); the coordinates are the elements' (JRElements pos, phi)", "JRHBMSetUp", jm, 3, jm[h->jmotion], &h->jmotion, NULL));
  }
  PetscCall(PetscOptionsBool("-hbm_physical", "Physical coordinates instead of modes (small systems: checks modal truncation)", "JRHBMSetUp", h->physical, &h->physical, NULL));
  PetscCall(PetscOptionsReal("-hbm_gamma", "Structural damping H = gamma K (2.17) [-]", "JRHBMSetUp", h->gamma, &h->gamma, NULL));
  PetscCall(PetscOptionsReal("-hbm_zeta", "Modal viscous damping ratio, every mode [-]", "JRHBMSetUp", h->zeta, &h->zeta, NULL));
  PetscCall(PetscOptionsEList("-hbm_jacobian", "Jacobian: analytic (element derivatives projected) or fd (finite differences, thesis 2.23)", "JRHBMSetUp", JRHBMJacobianTypes, 2, JRHBMJacobianTypes[h->jtype], &jt, NULL));
  h->jtype = (JRHBMJacobianType)jt;
  PetscCall(PetscOptionsBool("-hbm_view", "Print the harmonic-balance set-up", "JRHBMView", h->view, &h->view, NULL));
  if (!h->fdof_set) PetscCall(PetscOptionsInt("-frf_dof", "Excitation F sin(w t) at this DOF (0-based)", "JRHBMSetUp", h->fdof, &h->fdof, NULL));
  PetscCall(PetscOptionsString("-frf_force_file", "Excitation shape from a file instead (one value per DOF: .csv/.txt, .bin, .h5)", "JRHBMSetUp", h->ffile, h->ffile, sizeof(h->ffile), NULL));
  PetscCall(PetscOptionsIntArray("-frf_output", "Response DOFs (default: the excitation DOF)", "JRHBMResponse", out, &nout, &flg));
  PetscOptionsEnd();
  if (h->nout && h->fdof_set) flg = PETSC_FALSE; /* JRHBMSetOutputDofs() called */
  else PetscCall(PetscFree(h->outdof));
  if (flg) {
    PetscCheck(nout > 0, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_output needs at least one DOF");
    h->nout = nout;
    PetscCall(PetscMalloc1(nout, &h->outdof));
    PetscCall(PetscArraycpy(h->outdof, out, nout));
  } else if (!h->fdof_set) h->nout = 0;
  if (!h->modes_shared && !h->physical) { /* the modes' options (-modes_*), read and checked now: JRHBMSetUp makes the modes */
    JRModes md;
    PetscCall(JRModesCreate(h->comm, &md));
    PetscCall(JRModesSetFromOptions(md));
    PetscCall(JRModesDestroy(&md));
  }
  PetscCheck(h->H >= 1 && h->H <= JR_MAX_HARMONICS, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_harmonics %" PetscInt_FMT ": between 1 and %d", h->H, JR_MAX_HARMONICS);
  PetscCheck(h->Ns >= 2 * h->H + 1, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_samples %" PetscInt_FMT " must be at least 2H+1 = %" PetscInt_FMT " for -hbm_harmonics %" PetscInt_FMT, h->Ns, 2 * h->H + 1, h->H);
  PetscCheck(h->gamma >= 0.0 && !PetscIsInfOrNanReal(h->gamma), h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_gamma %g: the structural damping coefficient must be non-negative", (double)h->gamma);
  PetscCheck(h->zeta >= 0.0 && !PetscIsInfOrNanReal(h->zeta), h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_zeta %g: the modal damping ratio must be non-negative", (double)h->zeta);
  h->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

static PetscErrorCode GroupDestroy(HBMGroup *g)
{
  PetscFunctionBeginUser;
  PetscCall(JRContactDestroy(&g->c));
  PetscCall(JRFreeAligned(&g->R));
  PetscCall(JRFreeAligned(&g->S));
  PetscCall(JRFreeAligned(&g->U));
  PetscCall(JRFreeAligned(&g->V));
  PetscCall(JRFreeAligned(&g->F));
  PetscCall(JRFreeAligned(&g->N));
  PetscCall(JRFreeAligned(&g->DU));
  PetscCall(JRFreeAligned(&g->DV));
  PetscCall(JRFreeAligned(&g->DN));
  PetscCall(JRFreeAligned(&g->W));
  PetscCall(PetscFree(g->nstatic));
  PetscCall(PetscFree(g->state));
  PetscCall(PetscFree2(g->Kst, g->Knn));
  PetscCall(PetscFree(g->sel));
  PetscCall(JRFreeAligned(&g->Rc));
  PetscCall(JRFreeAligned(&g->Sc));
  PetscCall(JRFreeAligned(&g->Dc));
  PetscCall(PetscFree4(g->kt, g->kn, g->pt, g->pn));
  PetscCall(PetscFree(g->eidx));
  PetscCall(PetscFree(g->Kc));
  PetscCall(PetscFree(g->R0));
  PetscCall(PetscFree(g->S0));
  PetscCall(PetscFree2(g->qt, g->qn));
  PetscFunctionReturn(0);
}

/* Projection rows of a list of DOF pairs: rows[e*nm + i] = phi_i(a_e) - phi_i(b_e), col-major R */
static PetscErrorCode ProjectionRows(JRHBM h, PetscInt nloc, const PetscInt da[], const PetscInt db[], PetscReal R[])
{
  PetscInt  *dofs;
  PetscReal *rows;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(2 * nloc, &dofs, 2 * nloc * h->nm, &rows));
  for (PetscInt e = 0; e < nloc; e++) {
    dofs[2 * e]     = da[e];
    dofs[2 * e + 1] = db[e];
  }
  if (h->physical) {
    PetscCall(PetscArrayzero(rows, 2 * nloc * h->nm));
    for (PetscInt k = 0; k < 2 * nloc; k++)
      if (dofs[k] >= 0) rows[k * h->nm + dofs[k]] = 1.0;
  } else PetscCall(JRModesGetRows(h->modes, 2 * nloc, dofs, rows));
  for (PetscInt e = 0; e < nloc; e++)
    for (PetscInt i = 0; i < h->nm; i++) R[e + i * nloc] = rows[(2 * e) * h->nm + i] - rows[(2 * e + 1) * h->nm + i];
  PetscCall(PetscFree2(dofs, rows));
  PetscFunctionReturn(0);
}

/* Projection rows of node-to-node elements (4.3): R[e + i nloc] = sum_c dir_c (phi_i(A_c) - phi_i(B_c)) for the
   elements eidx[e] of the model's list, whose nodes' x, y, z DOFs are va[3 eidx..], vb[3 eidx..] */
static PetscErrorCode ProjectionRowsDir(JRHBM h, PetscInt nloc, const PetscInt eidx[], const PetscInt va[], const PetscInt vb[], const PetscReal dir[], PetscReal R[])
{
  const PetscInt nm = h->nm, chunk = 8192; /* elements per gather: bounds the work arrays (6 chunk nm values) */
  PetscInt      *dofs, nch, nchmax;
  PetscReal     *rows;

  PetscFunctionBeginUser;
  nch = (nloc + chunk - 1) / chunk;
  PetscCall(MPIU_Allreduce(&nch, &nchmax, 1, MPIU_INT, MPI_MAX, h->comm)); /* the gather is collective */
  PetscCall(PetscMalloc2(6 * chunk, &dofs, 6 * chunk * nm, &rows));
  for (PetscInt c0 = 0, ch = 0; ch < PetscMax(nchmax, 1); ch++, c0 += chunk) {
    const PetscInt n = PetscMax(0, PetscMin(chunk, nloc - c0));
    for (PetscInt e = 0; e < n; e++)
      for (PetscInt c = 0; c < 3; c++) {
        dofs[6 * e + c]     = va[3 * eidx[c0 + e] + c];
        dofs[6 * e + 3 + c] = vb[3 * eidx[c0 + e] + c];
      }
    if (h->physical) {
      PetscCall(PetscArrayzero(rows, 6 * n * nm));
      for (PetscInt k = 0; k < 6 * n; k++)
        if (dofs[k] >= 0) rows[k * nm + dofs[k]] = 1.0;
    } else PetscCall(JRModesGetRows(h->modes, 6 * n, dofs, rows));
    for (PetscInt e = 0; e < n; e++) {
      const PetscReal *d = dir + 3 * eidx[c0 + e];
      for (PetscInt i = 0; i < nm; i++) {
        PetscReal r = 0.0;
        for (PetscInt c = 0; c < 3; c++) r += d[c] * (rows[(6 * e + c) * nm + i] - rows[(6 * e + 3 + c) * nm + i]);
        R[c0 + e + i * nloc] = r;
      }
    }
  }
  PetscCall(PetscFree2(dofs, rows));
  PetscFunctionReturn(0);
}

/* Pseudo-inverse of a symmetric positive semi-definite n x n matrix G (n <= JR_NF), in place: directions with
   eigenvalues below 1e-10 of the largest are dropped (members on a line have no rotation about it; coordinates that
   do not vary within a joint carry nothing) */
static PetscErrorCode PseudoInverse(PetscInt n, PetscReal G[])
{
  PetscBLASInt bn, lwork = 64, info;
  PetscReal    lam[8], work[64], A[64];

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

/* A joint's field is linear in JR_NF coordinates of its members: their position x, y, z [m] (-rom_joint_motion
   linear, mode) and their tangential and normal motions in the stuck mode of interest (mode; JRElements phi). Its
   description, fw = 1 + nr (JR_NF + (1 + JR_NF) nm) numbers per joint: the members fitted, then per set of rows
   (tangential, then normal if nr = 2) the members' mean coordinates cbar, the mean rows (nm) and the gradient rows B
   (JR_NF nm, B[JR_NF i + c]) */
#define JR_NF 5
#define JR_FIELD_WIDTH(nr, nm) (1 + (nr) * (JR_NF + (1 + JR_NF) * (nm)))

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
  const PetscInt nm = h->nm, nj = el->njoints, nr = S ? 2 : 1, fw = JR_FIELD_WIDTH(nr, nm), NF = JR_NF;
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
    if (P) PetscCall(PseudoInverse(NF, G)); /* B = sum_e r_e (p_e - cbar)^T G^+, G = sum_e (p_e - cbar)(p_e - cbar)^T */
    for (PetscInt q = 0; q < nr; q++) {
      const PetscReal *rs = r + 1 + NF + NF * NF + (1 + NF) * q * nm;
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
            for (PetscInt d = 0; d < NF; d++) x += G[NF * c + d] * m[d];
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
   motions if el has them (else 0); P = NULL (the mean) when there are none */
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
  }
  PetscFunctionReturn(0);
}

/* The field coordinates of element e of el (buffer p), or NULL */
static inline const PetscReal *ElementCoordinates(const JRElements *el, PetscInt e, PetscReal p[JR_NF])
{
  if (!el->pos) return NULL;
  for (PetscInt c = 0; c < 3; c++) p[c] = el->pos[3 * e + c];
  for (PetscInt c = 0; c < 2; c++) p[3 + c] = el->phi ? el->phi[2 * e + c] : 0.0;
  return p;
}

/* First reduction (4.4): every member of a joint moves with the joint's field (JointFields) at its own position; so
   each member's rows R (and S) become the joint's (collective) */
static PetscErrorCode JointAverage(JRHBM h, const JRElements *el, PetscInt nloc, const PetscInt eidx[], PetscReal R[], PetscReal S[])
{
  const PetscInt nm = h->nm, nr = S ? 2 : 1, fw = JR_FIELD_WIDTH(nr, nm);
  PetscReal     *P, *field;

  PetscFunctionBeginUser;
  PetscCall(JointCoordinates(h, el, nloc, eidx, (PetscBool)(h->jmotion >= 1), &P));
  PetscCall(PetscMalloc1(el->njoints * fw, &field));
  PetscCall(JointFields(h, el, nloc, eidx, R, S, P, field));
  for (PetscInt e = 0; e < nloc; e++)
    for (PetscInt q = 0; q < nr; q++) FieldAt(field + el->joint[eidx[e]] * fw, nm, q, P ? P + JR_NF * e : NULL, (q ? S : R) + e, nloc);
  PetscCall(PetscFree(field));
  PetscCall(PetscFree(P));
  PetscFunctionReturn(0);
}

/* Second reduction: the joints' fields (JointFields, nj x JR_FIELD_WIDTH(2, nm), tangential then normal, on every
   rank) from their members' rows, the members split across the ranks (lin: the reduced elements have positions, so
   the linear field of -rom_joint_motion linear is wanted; else the mean); and, in a stuck basis, Kc += this rank's
   members' stuck springs on their own rows (the springs the basis holds, which the reduced elements replace) */
static PetscErrorCode JointRows(JRHBM h, const JRElements *mem, PetscBool lin, PetscReal field[], PetscReal Kc[])
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
  PetscCall(ProjectionRowsDir(h, nloc, eidx, mem->vdof_a, mem->vdof_b, mem->tdir, R));
  if (nv) PetscCall(ProjectionRowsDir(h, nloc, eidx, mem->vdof_a, mem->vdof_b, mem->ndir, S)); /* normal rows: jenkins_nv only */
  else PetscCall(PetscArrayzero(S, nloc * nm));
  PetscCall(JointCoordinates(h, mem, nloc, eidx, lin, &P));
  PetscCall(JointFields(h, mem, nloc, eidx, R, S, P, field));
  PetscCall(PetscFree(P));
  for (PetscInt j = 0; j < mem->njoints; j++) PetscCheck(field[j * JR_FIELD_WIDTH(2, nm)] > 0, h->comm, PETSC_ERR_ARG_WRONG, "Joint %" PetscInt_FMT " has no member element", j);
  if (Kc && nloc) {
    PetscReal *W;
    PetscCall(PetscMalloc1(nloc * nm, &W));
    for (PetscInt q = 0; q < 2; q++) {
      const PetscReal *X = q ? S : R;
      for (PetscInt i = 0; i < nm; i++)
        for (PetscInt e = 0; e < nloc; e++) {
          const PetscInt  k  = eidx[e];
          const PetscBool nv = (PetscBool)!strcmp(mem->typename[mem->type[k]], JRCONTACTJENKINSNV);
          W[e + i * nloc]    = mem->n0[k] > 0 ? (q ? (nv ? mem->kn[k] : 0.0) : mem->kt[k]) : 0.0;
          W[e + i * nloc] *= X[e + i * nloc];
        }
      PetscCall(Gemm("T", "N", nm, nm, nloc, 1.0, X, nloc, W, nloc, 1.0, Kc, nm));
    }
    PetscCall(PetscFree(W));
  }
  PetscCall(PetscFree3(eidx, R, S));
  PetscFunctionReturn(0);
}

/* Dense copy of a (small) distributed matrix on every rank, row-major */
static PetscErrorCode DenseAll(Mat A, PetscReal D[])
{
  Mat     *sub;
  IS       all;
  PetscInt n;

  PetscFunctionBeginUser;
  PetscCall(MatGetSize(A, &n, NULL));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, n, 0, 1, &all));
  PetscCall(MatCreateSubMatrices(A, 1, &all, &all, MAT_INITIAL_MATRIX, &sub));
  PetscCall(PetscArrayzero(D, n * n));
  for (PetscInt i = 0; i < n; i++) {
    PetscInt           nz;
    const PetscInt    *cols;
    const PetscScalar *v;
    PetscCall(MatGetRow(sub[0], i, &nz, &cols, &v));
    for (PetscInt k = 0; k < nz; k++) D[i * n + cols[k]] = PetscRealPart(v[k]);
    PetscCall(MatRestoreRow(sub[0], i, &nz, &cols, &v));
  }
  PetscCall(MatDestroySubMatrices(1, &sub));
  PetscCall(ISDestroy(&all));
  PetscFunctionReturn(0);
}

static PetscErrorCode FormFunction(SNES, Vec, Vec, void *);
static PetscErrorCode FormJacobian(SNES, Vec, Mat, Mat, void *);
static PetscErrorCode CondenseSetUp(JRHBM, const JRElements *);
static PetscErrorCode CondExpand(JRHBM, PetscReal, const PetscReal *, PetscReal *);

/*
  Mixed basis: the stuck modes of h->modes (operators K + Ks, M) and the elastic free-interface modes of (K, M),
  M-orthonormalised (dependent vectors dropped), then the Ritz vectors of (K + Ks, M) in their span, which
  replace h->modes' modes: exact for the stuck structure and for the structure with the interface free.
*/
static PetscErrorCode MixBasis(JRHBM h, Mat K, Mat M)
{
  JRModes       fm, md = h->modes;
  PetscInt      nrb, nf, nq = 0, ncand;
  Vec           rb[6], *Q, *MQ, *cand, Mv;
  PetscScalar  *d;
  PetscReal    *A, *lam, *work;
  PetscBLASInt  bn, lwork, info;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetRigidBasis(h->model, &nrb, rb));
  nf = h->nfree >= 0 ? h->nfree : h->nm;
  PetscCall(JRModesCreate(h->comm, &fm));
  PetscCall(JRModesSetOperators(fm, K, M));
  PetscCall(JRModesSetFromOptions(fm));
  fm->load[0] = fm->save[0] = 0;
  fm->view                  = PETSC_FALSE;
  PetscCall(JRModesSetNumber(fm, nf + nrb));
  PetscCall(JRModesSetRigidBasis(fm, nrb, rb));
  for (PetscInt i = 0; i < nrb; i++) PetscCall(VecDestroy(&rb[i]));
  PetscCall(JRModesSolve(fm));
  ncand = md->nm + nf;
  PetscCall(PetscMalloc2(ncand, &cand, ncand, &Q));
  for (PetscInt i = 0; i < md->nm; i++) cand[i] = md->phi[i];
  for (PetscInt i = 0; i < nf; i++) cand[md->nm + i] = fm->phi[nrb + i];
  PetscCall(VecDuplicate(md->phi[0], &Mv));
  PetscCall(PetscMalloc1(ncand, &d));
  PetscCall(PetscMalloc1(ncand, &MQ));
  for (PetscInt c = 0; c < ncand; c++) { /* Gram-Schmidt in the M inner product, twice, against M Q kept */
    PetscScalar nn;
    PetscReal   n0;
    PetscCall(VecDuplicate(cand[c], &Q[nq]));
    PetscCall(VecCopy(cand[c], Q[nq]));
    PetscCall(MatMult(M, Q[nq], Mv));
    PetscCall(VecDot(Q[nq], Mv, &nn));
    n0 = PetscSqrtReal(PetscRealPart(nn));
    for (PetscInt pass = 0; pass < 2 && nq; pass++) {
      PetscCall(VecMDot(Q[nq], nq, MQ, d));
      for (PetscInt j = 0; j < nq; j++) d[j] = -d[j];
      PetscCall(VecMAXPY(Q[nq], nq, d, Q));
    }
    PetscCall(MatMult(M, Q[nq], Mv));
    PetscCall(VecDot(Q[nq], Mv, &nn));
    if (PetscSqrtReal(PetscRealPart(nn)) < 1e-6 * n0) {
      PetscCall(VecDestroy(&Q[nq]));
      continue;
    }
    PetscCall(VecScale(Q[nq], 1.0 / PetscSqrtReal(PetscRealPart(nn))));
    PetscCall(VecDuplicate(Q[nq], &MQ[nq]));
    PetscCall(VecAXPBY(MQ[nq], 1.0 / PetscSqrtReal(PetscRealPart(nn)), 0.0, Mv));
    nq++;
  }
  /* Ritz: A = Q^T (K + Ks) Q, eigenvectors ascending */
  PetscCall(PetscMalloc3(nq * nq, &A, nq, &lam, 8 * nq, &work));
  for (PetscInt j = 0; j < nq; j++) {
    PetscCall(MatMult(md->K, Q[j], Mv));
    PetscCall(VecMDot(Mv, nq, Q, d));
    for (PetscInt i = 0; i < nq; i++) A[i + j * nq] = PetscRealPart(d[i]);
  }
  for (PetscInt j = 0; j < nq; j++)
    for (PetscInt i = 0; i < j; i++) A[i + j * nq] = A[j + i * nq] = 0.5 * (A[i + j * nq] + A[j + i * nq]);
  PetscCall(PetscBLASIntCast(nq, &bn));
  PetscCall(PetscBLASIntCast(8 * nq, &lwork));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &bn, A, &bn, lam, work, &lwork, &info));
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed: info %d", (int)info);
  PetscCall(VecDestroyVecs(md->nm, &md->phi));
  PetscCall(PetscFree(md->lambda));
  PetscCall(VecDuplicateVecs(Q[0], nq, &md->phi));
  PetscCall(PetscMalloc1(nq, &md->lambda));
  for (PetscInt i = 0; i < nq; i++) {
    PetscCall(VecZeroEntries(md->phi[i]));
    for (PetscInt j = 0; j < nq; j++) d[j] = A[j + i * nq];
    PetscCall(VecMAXPY(md->phi[i], nq, d, Q));
    md->lambda[i] = PetscAbsReal(lam[i]) <= 1e-10 * PetscAbsReal(lam[nq - 1]) ? 0.0 : lam[i];
  }
  md->nm = nq;
  PetscCall(PetscInfo(NULL, "Mixed basis: %" PetscInt_FMT " stuck + %" PetscInt_FMT " free modes -> %" PetscInt_FMT " Ritz vectors\n", md->nev, nf, nq));
  PetscCall(PetscFree3(A, lam, work));
  PetscCall(PetscFree(d));
  PetscCall(VecDestroy(&Mv));
  for (PetscInt i = 0; i < nq; i++) {
    PetscCall(VecDestroy(&Q[i]));
    PetscCall(VecDestroy(&MQ[i]));
  }
  PetscCall(PetscFree(MQ));
  PetscCall(PetscFree2(cand, Q));
  PetscCall(JRModesDestroy(&fm));
  PetscFunctionReturn(0);
}

/* Modes, projections, element partition, linear modal matrices, the SNES; a second call does nothing */
PetscErrorCode JRHBMSetUp(JRHBM h)
{
  Mat               K, M, C;
  PetscInt          ndof;
  const JRElements *el;
  PetscReal        *field = NULL; /* reduced models: the joints' motion fields (JointFields) */
  PetscReal         pc[JR_NF];     /* an element's field coordinates */

  PetscFunctionBeginUser;
  if (h->setupcalled) PetscFunctionReturn(0);
  PetscCheck(h->model, h->comm, PETSC_ERR_ARG_WRONGSTATE, "JRHBMSetModel() first");
  PetscCall(JRModelGetMatrices(h->model, &K, &M, &C));
  PetscCall(JRModelGetNumDofs(h->model, &ndof));
  PetscCall(JRModelGetElements(h->model, &el));
  h->nc    = 2 * h->H + 1;
  PetscCall(PetscFree(h->pptab)); /* sized by nc */
  h->has_C = C ? PETSC_TRUE : PETSC_FALSE;
  PetscCheck(h->fdof >= 0 && h->fdof < ndof, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_dof %" PetscInt_FMT " is out of range: DOFs are 0..%" PetscInt_FMT, h->fdof, ndof - 1);
  if (!h->nout) {
    h->nout = 1;
    PetscCall(PetscMalloc1(1, &h->outdof));
    h->outdof[0] = h->fdof;
  }
  for (PetscInt i = 0; i < h->nout; i++) PetscCheck(h->outdof[i] >= 0 && h->outdof[i] < ndof, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-frf_output %" PetscInt_FMT " is out of range: DOFs are 0..%" PetscInt_FMT, h->outdof[i], ndof - 1);

  /* the linear part: modes (or physical coordinates) */
  PetscCall(PetscFree3(h->Km, h->Mm, h->Cm));
  PetscCall(PetscFree(h->omega_r));
  PetscCall(PetscFree(h->pin));
  if (h->physical) {
    PetscCheck(ndof <= 2000, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_physical is for small systems (%" PetscInt_FMT " DOFs here, at most 2000): use modes", ndof);
    PetscCheck(h->zeta == 0.0, h->comm, PETSC_ERR_ARG_INCOMP, "-hbm_zeta (modal damping) needs modal coordinates, not -hbm_physical: give a damping matrix with -model_damping");
    PetscCheck(h->basis == 0, h->comm, PETSC_ERR_ARG_INCOMP, "-hbm_basis stuck needs modal coordinates, not -hbm_physical");
    h->nm = ndof;
    PetscCall(PetscCalloc3(h->nm * h->nm, &h->Km, h->nm * h->nm, &h->Mm, h->nm * h->nm, &h->Cm));
    PetscCall(DenseAll(K, h->Km));
    PetscCall(DenseAll(M, h->Mm));
    if (C) PetscCall(DenseAll(C, h->Cm));
    PetscCall(PetscMalloc1(0, &h->omega_r));
  } else {
    const PetscReal *lam;
    char             save[PETSC_MAX_PATH_LEN] = "";
    h->nm = h->nmodes_opt > 0 ? h->nmodes_opt : (ndof <= 200 ? ndof : 10);
    PetscCheck(h->nm <= ndof, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "-hbm_modes %" PetscInt_FMT ": the model has only %" PetscInt_FMT " DOFs", h->nm, ndof);
    if (!h->modes_shared) {
      PetscCall(JRModesDestroy(&h->modes));
      PetscCall(JRModesCreate(h->comm, &h->modes));
      if (h->basis >= 1) {
        Mat       Ks, KK;
        PetscReal sig;
        PetscCall(JRElementsCreateStuckStiffness(K, el, &Ks, &sig));
        PetscCall(MatDuplicate(K, MAT_COPY_VALUES, &KK));
        PetscCall(MatAXPY(KK, 1.0, Ks, DIFFERENT_NONZERO_PATTERN));
        PetscCall(JRModesSetOperators(h->modes, KK, M));
        PetscCall(JRModesSetSignature(h->modes, sig));
        PetscCall(MatDestroy(&KK));
        PetscCall(MatDestroy(&Ks));
      } else PetscCall(JRModesSetOperators(h->modes, K, M));
      PetscCall(JRModesSetNumber(h->modes, h->nm));
      PetscCall(JRModesSetFromOptions(h->modes));
      PetscCall(JRModesSetNumber(h->modes, h->nm)); /* -hbm_modes wins over -modes_nev */
      if (h->modes_file[0] && !h->modes->load[0] && !h->modes->save[0]) PetscCall(PetscStrncpy(h->modes->save, h->modes_file, sizeof(h->modes->save)));
      {
        PetscInt nrb;
        Vec      rb[6];
        PetscCall(JRModelGetRigidBasis(h->model, &nrb, rb));
        PetscCall(JRModesSetRigidBasis(h->modes, nrb, rb));
        for (PetscInt i = 0; i < nrb; i++) PetscCall(VecDestroy(&rb[i]));
        if (nrb) { /* an FE model: its coordinates go with saved modes */
          Vec X;
          PetscCall(JRModelGetCoordinates(h->model, &X));
          PetscCall(JRModesSetCoordinates(h->modes, X));
          PetscCall(VecDestroy(&X));
        }
      }
      if (h->basis == 2) { /* the saved or loaded basis is the mixed one, marked by the signature's sign */
        PetscCall(PetscStrncpy(save, h->modes->save, sizeof(save)));
        h->modes->save[0]  = 0;
        h->modes->load_all = PETSC_TRUE;
        h->modes->sig      = -h->modes->sig - 1.0;
      }
      PetscCall(JRModesSolve(h->modes));
      if (h->basis == 2 && !h->modes->load[0]) {
        PetscCall(MixBasis(h, K, M));
        if (save[0]) PetscCall(JRModesSave(h->modes, save));
      }
    }
    h->nm = h->modes->nm;
    PetscCall(JRModesGetEigenvalues(h->modes, &lam));
    PetscCall(PetscCalloc3(h->nm * h->nm, &h->Km, h->nm * h->nm, &h->Mm, h->nm * h->nm, &h->Cm));
    PetscCall(PetscMalloc1(h->nm, &h->omega_r));
    PetscCall(PetscCalloc1(h->nm, &h->pin));
    for (PetscInt i = 0; i < h->nm; i++) {
      h->Km[i * h->nm + i] = lam[i];
      h->Mm[i * h->nm + i] = 1.0;
      h->omega_r[i]        = PetscSqrtReal(PetscMax(lam[i], 0.0));
    }
    /* A free-free structure's rigid-body modes stretch no element (their projection rows vanish) and no
       spring: their mean has no equation. It is zero (the excitation is harmonic), so pin it. */
    for (PetscInt i = 0; i < h->nm; i++)
      if (lam[i] <= 1e-8 * lam[h->nm - 1]) h->pin[i] = lam[h->nm - 1];
    if (C) PetscCall(JRModesProject(h->modes, C, h->Cm));
    for (PetscInt i = 0; i < h->nm; i++) h->Cm[i * h->nm + i] += 2.0 * h->zeta * h->omega_r[i];
  }
  h->n = h->nm * h->nc;
  {
    char *d = h->damping;
    d[0]    = 0;
    if (h->gamma > 0) PetscCall(PetscSNPrintf(d + strlen(d), sizeof(h->damping) - strlen(d), "structural gamma = %g (H = gamma K); ", (double)h->gamma));
    if (h->zeta > 0) PetscCall(PetscSNPrintf(d + strlen(d), sizeof(h->damping) - strlen(d), "modal viscous zeta = %g; ", (double)h->zeta));
    if (C) PetscCall(PetscSNPrintf(d + strlen(d), sizeof(h->damping) - strlen(d), "viscous matrix C; "));
    if (!d[0]) PetscCall(PetscSNPrintf(d, sizeof(h->damping), "none (only the contact elements dissipate)"));
    else d[strlen(d) - 2] = 0;
  }

  /* excitation shape in modal coordinates, outputs */
  PetscCall(PetscFree(h->fm));
  PetscCall(PetscCalloc1(h->nm, &h->fm));
  PetscCall(PetscFree(h->Phiout));
  PetscCall(PetscMalloc1(h->nout * h->nm, &h->Phiout));
  if (h->ffile[0]) {
    PetscReal *f;
    PetscCall(PetscMalloc1(ndof, &f));
    PetscCall(JRVecLoadFile(h->comm, h->ffile, ndof, f));
    if (h->physical) PetscCall(PetscArraycpy(h->fm, f, ndof));
    else {
      Vec          fv;
      PetscInt     lo, hi;
      PetscScalar *d;
      PetscCall(VecDuplicate(h->modes->phi[0], &fv));
      PetscCall(VecGetOwnershipRange(fv, &lo, &hi));
      for (PetscInt i = lo; i < hi; i++) PetscCall(VecSetValue(fv, i, f[i], INSERT_VALUES));
      PetscCall(VecAssemblyBegin(fv));
      PetscCall(VecAssemblyEnd(fv));
      PetscCall(PetscMalloc1(h->nm, &d));
      PetscCall(VecMDot(fv, h->nm, h->modes->phi, d));
      for (PetscInt i = 0; i < h->nm; i++) h->fm[i] = PetscRealPart(d[i]);
      PetscCall(PetscFree(d));
      PetscCall(VecDestroy(&fv));
    }
    PetscCall(PetscFree(f));
  } else if (h->physical) h->fm[h->fdof] = 1.0;
  else PetscCall(JRModesGetRows(h->modes, 1, &h->fdof, h->fm));
  if (h->physical) {
    PetscCall(PetscArrayzero(h->Phiout, h->nout * h->nm));
    for (PetscInt i = 0; i < h->nout; i++) h->Phiout[i * h->nm + h->outdof[i]] = 1.0;
  } else PetscCall(JRModesGetRows(h->modes, h->nout, h->outdof, h->Phiout));

  /* reduced model: its joints' rows from their members (and, in a stuck basis, the members' springs to cancel) */
  PetscCall(PetscFree(h->Kc));
  PetscCall(PetscCalloc1(h->nm * h->nm, &h->Kc));
  if (el->members) {
    PetscCheck(el->joint && el->njoints == el->members->njoints, h->comm, PETSC_ERR_ARG_WRONG, "A reduced model needs a joint for every element, among its members' %" PetscInt_FMT " joints", el->members->njoints);
    PetscCall(PetscMalloc1(el->njoints * JR_FIELD_WIDTH(2, h->nm), &field));
    PetscCall(JointRows(h, el->members, (PetscBool)(el->pos != NULL), field, h->basis >= 1 ? h->Kc : NULL));
  }
  /* element groups, one per type, split across the ranks; a reduced model's few elements are on every rank instead
     (each rank's Newton iteration then needs no sum over the ranks: the same numbers, bit for bit, everywhere) */
  h->repl  = (PetscBool)(el->members && h->size > 1);
  h->ecomm = h->repl ? PETSC_COMM_SELF : h->comm;
  for (PetscInt t = 0; t < h->ngroups; t++) PetscCall(GroupDestroy(&h->g[t]));
  PetscCall(PetscFree(h->g));
  h->ngroups = el->ntypes;
  PetscCall(PetscCalloc1(h->ngroups, &h->g));
  for (PetscInt t = 0; t < h->ngroups; t++) {
    HBMGroup  *g = &h->g[t];
    PetscInt   ntot = 0, nloc = PETSC_DECIDE, start = 0, k = 0, *ia, *ib, *eidx;
    PetscReal *kt, *kn, *mu, *n0;
    const PetscInt nc = h->nc, nm = h->nm;
    for (PetscInt e = 0; e < el->n; e++) ntot += el->type[e] == t;
    if (h->repl) nloc = ntot;
    else {
      PetscCall(PetscSplitOwnership(h->comm, &nloc, &ntot));
      PetscCallMPI(MPI_Scan(&nloc, &start, 1, MPIU_INT, MPI_SUM, h->comm));
      start -= nloc;
    }
    g->nloc = nloc;
    PetscCall(PetscMalloc4(nloc, &kt, nloc, &kn, nloc, &mu, nloc, &n0));
    PetscCall(PetscMalloc2(nloc, &ia, nloc, &ib));
    PetscCall(PetscMalloc1(nloc, &g->nstatic));
    PetscCall(PetscMalloc1(nloc, &g->state));
    PetscCall(PetscMalloc1(nloc, &eidx));
    for (PetscInt e = 0, cnt = 0; e < el->n; e++) {
      if (el->type[e] != t) continue;
      if (cnt >= start && cnt < start + nloc) {
        eidx[k]        = e;
        ia[k]          = el->dof_a[e];
        ib[k]          = el->dof_b[e];
        kt[k]          = el->kt[e];
        kn[k]          = el->kn[e];
        mu[k]          = el->mu[e];
        n0[k]          = el->n0[e];
        g->nstatic[k] = PetscMax(el->n0[e], 0.0);
        k++;
      }
      cnt++;
    }
    PetscCall(JRContactCreate(PETSC_COMM_SELF, &g->c));
    PetscCall(JRContactSetType(g->c, el->typename[t]));
    PetscCall(JRContactSetHarmonics(g->c, h->H, h->Ns));
    PetscCall(JRContactSetElements(g->c, nloc, kt, kn, mu, n0));
    PetscCall(JRContactSetUp(g->c));
    PetscCall(JRContactUsesNormal(g->c, &g->normal));
    PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nm, &g->R));
    PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nm, &g->W));
    PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc, &g->U));
    PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc, &g->F));
    PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc * nc, &g->DU));
    if (el->members)
      for (PetscInt e = 0; e < nloc; e++)
        FieldAt(field + el->joint[eidx[e]] * JR_FIELD_WIDTH(2, nm), nm, 0, ElementCoordinates(el, eidx[e], pc), g->R + e, nloc);
    else if (el->vdof_a) PetscCall(ProjectionRowsDir(h, nloc, eidx, el->vdof_a, el->vdof_b, el->tdir, g->R));
    else PetscCall(ProjectionRows(h, nloc, ia, ib, g->R));
    if (g->normal) {
      for (k = 0; k < nloc; k++) {
        ia[k] = el->ndof_a[eidx[k]];
        ib[k] = el->ndof_b[eidx[k]];
      }
      PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nm, &g->S));
      PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc, &g->V));
      PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc, &g->N));
      PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc * nc, &g->DV));
      PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nc * nc, &g->DN));
      if (el->members)
        for (PetscInt e = 0; e < nloc; e++)
          FieldAt(field + el->joint[eidx[e]] * JR_FIELD_WIDTH(2, nm), nm, 1, ElementCoordinates(el, eidx[e], pc), g->S + e, nloc);
      else if (el->vdof_a) PetscCall(ProjectionRowsDir(h, nloc, eidx, el->vdof_a, el->vdof_b, el->ndir, g->S));
      else PetscCall(ProjectionRows(h, nloc, ia, ib, g->S));
    }
    if (el->joint && !el->members) {
      if (h->basis >= 1) { /* the basis holds the members' own stuck springs: Kc must cancel exactly those */
        PetscCall(PetscMalloc1(nloc * nm, &g->R0));
        PetscCall(PetscArraycpy(g->R0, g->R, nloc * nm));
        if (g->normal) {
          PetscCall(PetscMalloc1(nloc * nm, &g->S0));
          PetscCall(PetscArraycpy(g->S0, g->S, nloc * nm));
        }
      }
      PetscCall(JointAverage(h, el, nloc, eidx, g->R, g->normal ? g->S : NULL));
    }
    /* friction elements: the stuck part of the Jacobian, once */
    g->split = (PetscBool)(!strcmp(el->typename[t], JRCONTACTJENKINS) || !strcmp(el->typename[t], JRCONTACTJENKINSNV));
    PetscCall(PetscCalloc2(nm * nm, &g->Kst, nm * nm, &g->Knn));
    PetscCall(PetscMalloc4(nloc, &g->kt, nloc, &g->kn, nloc, &g->pt, nloc, &g->pn));
    PetscCall(PetscArraycpy(g->kt, kt, nloc));
    PetscCall(PetscArraycpy(g->kn, kn, nloc));
    for (PetscInt e = 0; e < nloc; e++) {
      g->pt[e] = g->nstatic[e] > 0 ? kt[e] : 0.0;
      g->pn[e] = g->nstatic[e] > 0 ? kn[e] : 0.0;
    }
    PetscCall(PetscMalloc1(nloc, &g->sel));
    PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nm, &g->Rc));
    PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc, &g->Dc));
    if (g->normal) PetscCall(JRMallocAligned(sizeof(PetscReal) * nloc * nm, &g->Sc));
    if (g->split && nloc) {
      for (PetscInt i = 0; i < nm; i++)
        for (PetscInt e = 0; e < nloc; e++) g->W[e + i * nloc] = g->pt[e] * g->R[e + i * nloc];
      PetscCall(Gemm("T", "N", nm, nm, nloc, 1.0, g->R, nloc, g->W, nloc, 0.0, g->Kst, nm));
      if (g->normal) {
        for (PetscInt i = 0; i < nm; i++)
          for (PetscInt e = 0; e < nloc; e++) g->W[e + i * nloc] = g->pn[e] * g->S[e + i * nloc];
        PetscCall(Gemm("T", "N", nm, nm, nloc, 1.0, g->S, nloc, g->W, nloc, 0.0, g->Knn, nm));
      }
    }
    PetscCall(PetscFree4(kt, kn, mu, n0));
    PetscCall(PetscFree2(ia, ib));
    g->eidx = eidx;
  }

  /* stuck basis: each element's stuck spring is in Km already, so the element adds F - kt u (its deviation from
     stuck); structural damping acts on the structure's own stiffness Kg = Km - Phi^T Ks Phi only */
  PetscCall(PetscFree(h->Kg));
  PetscCall(PetscMalloc1(h->nm * h->nm, &h->Kg));
  PetscCall(PetscArraycpy(h->Kg, h->Km, h->nm * h->nm));
  if (h->basis >= 1) {
    const PetscInt nm = h->nm;
    PetscReal     *loc, *all;
    PetscCall(PetscCalloc2(nm * nm, &loc, nm * nm, &all));
    for (PetscInt t = 0; t < h->ngroups && !el->members; t++) {
      HBMGroup *g = &h->g[t];
      PetscCall(PetscCalloc1(nm * nm, &g->Kc));
      if (!g->split || !g->nloc) continue;
      {
        const PetscReal *Rk = g->R0 ? g->R0 : g->R, *Sk = g->S0 ? g->S0 : g->S;
        for (PetscInt i = 0; i < nm; i++)
          for (PetscInt e = 0; e < g->nloc; e++) g->W[e + i * g->nloc] = (g->nstatic[e] > 0 ? g->kt[e] : 0.0) * Rk[e + i * g->nloc];
        PetscCall(Gemm("T", "N", nm, nm, g->nloc, 1.0, Rk, g->nloc, g->W, g->nloc, 0.0, g->Kc, nm));
        if (g->normal) {
          for (PetscInt i = 0; i < nm; i++)
            for (PetscInt e = 0; e < g->nloc; e++) g->W[e + i * g->nloc] = (g->nstatic[e] > 0 ? g->kn[e] : 0.0) * Sk[e + i * g->nloc];
          PetscCall(Gemm("T", "N", nm, nm, g->nloc, 1.0, Sk, g->nloc, g->W, g->nloc, 1.0, g->Kc, nm));
        }
      }
      PetscCall(PetscFree(g->R0));
      PetscCall(PetscFree(g->S0));
      for (PetscInt i = 0; i < nm * nm; i++) h->Kc[i] += g->Kc[i];
    }
    PetscCall(PetscArraycpy(loc, h->Kc, nm * nm));
    PetscCall(MPIU_Allreduce(loc, all, nm * nm, MPIU_REAL, MPIU_SUM, h->comm));
    if (h->repl) PetscCall(PetscArraycpy(h->Kc, all, nm * nm)); /* every rank has every element: the whole sum */
    for (PetscInt i = 0; i < nm; i++)
      for (PetscInt j = 0; j < nm; j++) h->Kg[i * nm + j] -= all[i + j * nm];
    PetscCall(PetscFree2(loc, all));
  }

  PetscCall(PetscFree(field));
  /* a reduced model: the modes eliminated, the joints' motions the unknowns */
  PetscCall(CondenseSetUp(h, el));
  /* the nonlinear solver at fixed frequency: SNES on every rank, prefix hbm_ */
  PetscCall(PetscFree(h->buf));
  PetscCall(PetscMalloc1(h->ns + h->ns * h->ns, &h->buf));
  PetscCall(PetscFree(h->cache_a));
  PetscCall(PetscMalloc1(h->ns, &h->cache_a));
  h->cache_ok = PETSC_FALSE;
  PetscCall(SNESDestroy(&h->snes));
  PetscCall(MatDestroy(&h->J));
  PetscCall(VecDestroy(&h->r));
  PetscCall(JRHBMCreateVecs(h, &h->r, &h->J));
  PetscCall(SNESCreate(PETSC_COMM_SELF, &h->snes));
  PetscCall(SNESSetOptionsPrefix(h->snes, "hbm_"));
  PetscCall(SNESSetFunction(h->snes, h->r, FormFunction, h));
  if (h->jtype == JR_HBM_JACOBIAN_FD) PetscCall(SNESSetJacobian(h->snes, h->J, h->J, SNESComputeJacobianDefault, h));
  else PetscCall(SNESSetJacobian(h->snes, h->J, h->J, FormJacobian, h));
  {
    KSP ksp;
    PC  pc;
    PetscCall(SNESGetKSP(h->snes, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, PCLU));
  }
  PetscCall(SNESSetTolerances(h->snes, PETSC_DEFAULT, 1e-10, 1e-12, 40, 10000));
  PetscCall(SNESSetType(h->snes, SNESNEWTONDENSE));
  PetscCall(SNESSetFromOptions(h->snes));
  h->setupcalled = PETSC_TRUE;
  if (h->view) PetscCall(JRHBMView(h, NULL));
  PetscFunctionReturn(0);
}

/* The excitation DOF and the response DOFs (nout >= 1) set in code, e.g. found by position on an FE
   mesh: -frf_dof and -frf_output are then ignored. Call before JRHBMSetFromOptions(). */
PetscErrorCode JRHBMSetExcitationDof(JRHBM h, PetscInt dof, PetscInt nout, const PetscInt out[])
{
  PetscFunctionBeginUser;
  PetscCheck(nout >= 1, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "At least one response DOF");
  h->fdof     = dof;
  h->fdof_set = PETSC_TRUE;
  PetscCall(PetscFree(h->outdof));
  h->nout = nout;
  PetscCall(PetscMalloc1(nout, &h->outdof));
  PetscCall(PetscArraycpy(h->outdof, out, nout));
  h->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*
  JRHBMSetOutputPoints - the positions [m] of the n response points (xyz: x, y, z of each) and the direction
  of the responses (0 x, 1 y, 2 z), in the order of the response DOFs of JRHBMSetExcitationDof(). They name
  the outputs (HDF5 attributes, plot titles) where a DOF number would depend on the partition of an FE
  mesh; they do not change the solution. Without them an output is named by its DOF.
*/
PetscErrorCode JRHBMSetOutputPoints(JRHBM h, PetscInt n, const PetscReal xyz[], PetscInt dir)
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 1 && dir >= 0 && dir < 3, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "JRHBMSetOutputPoints: %" PetscInt_FMT " points along direction %" PetscInt_FMT ": at least one point, direction 0 (x), 1 (y) or 2 (z)", n, dir);
  PetscCall(PetscFree(h->ptxyz));
  PetscCall(PetscMalloc1(3 * n, &h->ptxyz));
  PetscCall(PetscArraycpy(h->ptxyz, xyz, 3 * n));
  h->npts  = n;
  h->ptdir = dir;
  PetscFunctionReturn(0);
}

/* The response points of JRHBMSetOutputPoints() (xyz: 3 per response DOF, NULL if none were given) and their direction */
PetscErrorCode JRHBMGetOutputPoints(JRHBM h, const PetscReal **xyz, PetscInt *dir)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCheck(!h->ptxyz || h->npts == h->nout, h->comm, PETSC_ERR_ARG_SIZ, "JRHBMSetOutputPoints gave %" PetscInt_FMT " points for %" PetscInt_FMT " response DOFs", h->npts, h->nout);
  *xyz = h->ptxyz;
  if (dir) *dir = h->ptdir;
  PetscFunctionReturn(0);
}

/*
  JRHBMStickFrequencies - natural frequencies [Hz] of the linear structure with every element stuck
  (tangential springs kt and, for jenkins_nv, normal springs kn; only the elements in contact at rest,
  n0 > 0) in the modal basis of the HBM: eigenvalues of Phi^T (K + sum_e kt r_e r_e^T + kn s_e s_e^T) Phi
  (collective; freq has room for nm).
*/
static PetscErrorCode StickEig(JRHBM h, PetscReal scale, PetscInt *nf, PetscReal freq[], PetscInt kvec, PetscReal vec[]);

PetscErrorCode JRHBMStickFrequencies(JRHBM h, PetscInt *nf, PetscReal freq[])
{
  PetscFunctionBeginUser;
  PetscCall(StickEig(h, 1.0, nf, freq, -1, NULL));
  PetscFunctionReturn(0);
}

/*
  JRHBMMatchStickFrequency - the factor c on every element's stiffness (kt, kn) that puts the k-th stuck natural
  frequency (JRHBMStickFrequencies) at target [Hz]: the stiffness correction of a reduced model, by a bracketed
  secant (Illinois) solve on the eigenvalue in the modal basis, to 1e-12 relative (collective; the model is not
  changed: scale its elements by c and set it up again). c = 0 if no factor in [1e-3, 1e3] reaches the target (the
  elements cannot carry that much stiffness in that mode).
*/
PetscErrorCode JRHBMMatchStickFrequency(JRHBM h, PetscInt k, PetscReal target, PetscReal *c)
{
  PetscReal *f, lo = 1.0, hi = 1.0, glo, ghi, x = 1.0, gx;
  PetscInt   nf, side = 0;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCheck(k >= 0 && k < h->nm, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "Stuck mode %" PetscInt_FMT ": the basis has %" PetscInt_FMT, k, h->nm);
  PetscCall(PetscMalloc1(h->nm, &f));
  PetscCall(StickEig(h, 1.0, &nf, f, -1, NULL));
  glo = ghi = f[k] - target;
  for (PetscInt it = 0; glo > 0 && it < 10; it++) {
    hi  = lo;
    ghi = glo;
    lo *= 0.5;
    PetscCall(StickEig(h, lo, &nf, f, -1, NULL));
    glo = f[k] - target;
  }
  for (PetscInt it = 0; ghi < 0 && it < 10; it++) {
    lo  = hi;
    glo = ghi;
    hi *= 2.0;
    PetscCall(StickEig(h, hi, &nf, f, -1, NULL));
    ghi = f[k] - target;
  }
  if (!(glo <= 0 && ghi >= 0)) {
    *c = 0;
    PetscCall(PetscFree(f));
    PetscFunctionReturn(0);
  }
  x = lo;
  for (PetscInt it = 0; it < 200 && hi - lo > 1e-13 * hi; it++) {
    x = (lo * ghi - hi * glo) / (ghi - glo);
    PetscCall(StickEig(h, x, &nf, f, -1, NULL));
    gx = f[k] - target;
    if (PetscAbsReal(gx) <= 1e-12 * target) break;
    if (gx < 0) {
      lo  = x;
      glo = gx;
      if (side == -1) ghi *= 0.5;
      side = -1;
    } else {
      hi  = x;
      ghi = gx;
      if (side == 1) glo *= 0.5;
      side = 1;
    }
  }
  *c = x;
  PetscCall(PetscFree(f));
  PetscFunctionReturn(0);
}

/*
  JRHBMStuckModeMotion - the k-th stuck mode (JRHBMStickFrequencies, M-normalised in the basis) as every element's
  tangential relative motion u[e] (e in the model's element list, on every rank; collective) and, if v is not NULL,
  normal relative motion v[e] (0 for elements without a normal direction)
*/
PetscErrorCode JRHBMStuckModeMotion(JRHBM h, PetscInt k, PetscReal u[], PetscReal v[])
{
  const JRElements *el;
  PetscReal        *f, *q, *loc;
  PetscInt          nf;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(JRModelGetElements(h->model, &el));
  PetscCheck(k >= 0 && k < h->nm, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "Stuck mode %" PetscInt_FMT ": the basis has %" PetscInt_FMT, k, h->nm);
  PetscCall(PetscMalloc2(h->nm, &f, h->nm, &q));
  PetscCall(StickEig(h, 1.0, &nf, f, k, q));
  PetscCall(PetscCalloc1(2 * el->n, &loc));
  for (PetscInt t = 0; t < h->ngroups; t++) {
    HBMGroup *g = &h->g[t];
    for (PetscInt e = 0; e < g->nloc; e++) {
      PetscReal s = 0, sn = 0;
      for (PetscInt i = 0; i < h->nm; i++) s += g->R[e + i * g->nloc] * q[i];
      for (PetscInt i = 0; g->normal && i < h->nm; i++) sn += g->S[e + i * g->nloc] * q[i];
      loc[g->eidx[e]]         = s;
      loc[el->n + g->eidx[e]] = sn;
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, loc, (PetscMPIInt)(2 * el->n), MPIU_REAL, MPIU_SUM, h->ecomm));
  PetscCall(PetscArraycpy(u, loc, el->n));
  if (v) PetscCall(PetscArraycpy(v, loc + el->n, el->n));
  PetscCall(PetscFree(loc));
  PetscCall(PetscFree2(f, q));
  PetscFunctionReturn(0);
}

/*
  JRHBMStuckModeBalance - the energy balance of the k-th stuck mode q (M-normalised) at resonance, for the modal
  amplitude a: per cycle the excitation of level F puts in pi F |q.fm| a and the linear damping takes out
  damp a^2 = pi (gamma q^T Kg q + omega q^T Cm q) a^2. omega [rad/s], force = |q.fm| (per unit level). Collective.
*/
PetscErrorCode JRHBMStuckModeBalance(JRHBM h, PetscInt k, PetscReal *omega, PetscReal *force, PetscReal *damp)
{
  PetscReal *f, *q, fq = 0, kq = 0, cq = 0;
  PetscInt   nf;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCheck(k >= 0 && k < h->nm, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "Stuck mode %" PetscInt_FMT ": the basis has %" PetscInt_FMT, k, h->nm);
  PetscCall(PetscMalloc2(h->nm, &f, h->nm, &q));
  PetscCall(StickEig(h, 1.0, &nf, f, k, q));
  *omega = 2 * PETSC_PI * f[k];
  for (PetscInt i = 0; i < h->nm; i++) {
    fq += h->fm[i] * q[i];
    for (PetscInt j = 0; j < h->nm; j++) {
      kq += q[i] * h->Kg[i * h->nm + j] * q[j];
      cq += q[i] * h->Cm[i * h->nm + j] * q[j];
    }
  }
  *force = PetscAbsReal(fq);
  *damp  = PETSC_PI * (h->gamma * kq + *omega * cq);
  PetscCall(PetscFree2(f, q));
  PetscFunctionReturn(0);
}

static PetscErrorCode StickEig(JRHBM h, PetscReal scale, PetscInt *nf, PetscReal freq[], PetscInt kvec, PetscReal vec[])
{
  const PetscInt nm = h->nm;
  PetscReal     *A, *B, *loc, *w, *work;
  PetscBLASInt   n, lwork, info, itype = 1;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(PetscCalloc5(nm * nm, &A, nm * nm, &B, nm * nm, &loc, nm, &w, 8 * nm, &work));
  for (PetscInt t = 0; t < h->ngroups; t++) { /* the elements in contact at rest (n0 > 0), stuck, on the structure's own Kg */
    HBMGroup *g = &h->g[t];
    PetscCheck(g->split || !g->nloc, PETSC_COMM_SELF, PETSC_ERR_SUP, "Stuck frequencies need friction elements (jenkins, jenkins_nv)");
    if (!g->nloc) continue;
    for (PetscInt i = 0; i < nm; i++)
      for (PetscInt e = 0; e < g->nloc; e++) g->W[e + i * g->nloc] = (g->nstatic[e] > 0 ? g->kt[e] : 0.0) * g->R[e + i * g->nloc];
    PetscCall(Gemm("T", "N", nm, nm, g->nloc, scale, g->R, g->nloc, g->W, g->nloc, 1.0, loc, nm));
    if (g->normal) {
      for (PetscInt i = 0; i < nm; i++)
        for (PetscInt e = 0; e < g->nloc; e++) g->W[e + i * g->nloc] = (g->nstatic[e] > 0 ? g->kn[e] : 0.0) * g->S[e + i * g->nloc];
      PetscCall(Gemm("T", "N", nm, nm, g->nloc, scale, g->S, g->nloc, g->W, g->nloc, 1.0, loc, nm));
    }
  }
  PetscCall(MPIU_Allreduce(loc, A, nm * nm, MPIU_REAL, MPIU_SUM, h->ecomm));
  for (PetscInt i = 0; i < nm; i++)
    for (PetscInt j = 0; j < nm; j++) {
      A[i + j * nm] += h->Kg[i * nm + j];
      B[i + j * nm] = h->Mm[i * nm + j];
    }
  PetscCall(PetscBLASIntCast(nm, &n));
  PetscCall(PetscBLASIntCast(8 * nm, &lwork));
  PetscCallBLAS("LAPACKsygv", LAPACKsygv_(&itype, vec ? "V" : "N", "U", &n, A, &n, B, &n, w, work, &lwork, &info));
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK sygv failed: info %d", (int)info);
  for (PetscInt i = 0; i < nm; i++) freq[i] = PetscSqrtReal(PetscMax(w[i], 0.0)) / (2 * PETSC_PI);
  if (vec)
    for (PetscInt i = 0; i < nm; i++) vec[i] = A[i + kvec * nm];
  *nf = nm;
  PetscCall(PetscFree5(A, B, loc, w, work));
  PetscFunctionReturn(0);
}

/*
  JRHBMSetModes - use the modes (and basis) of another JRHBM that is set up, e.g. the node-to-node model's for its
  reduced model: nothing is solved again; the other JRHBM must outlive this one (its modes are not copied).
*/
PetscErrorCode JRHBMSetModes(JRHBM h, JRHBM from)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(from));
  PetscCheck(!from->physical, h->comm, PETSC_ERR_ARG_WRONG, "JRHBMSetModes: the other JRHBM works in physical coordinates");
  if (!h->modes_shared) PetscCall(JRModesDestroy(&h->modes));
  h->modes        = from->modes;
  h->modes_shared = PETSC_TRUE;
  h->basis        = from->basis;
  h->basis_set    = PETSC_TRUE;
  h->nmodes_opt   = from->modes->nm;
  h->setupcalled  = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The modal basis: 0 free (modes of K), 1 stuck (modes of K with the stuck contact springs); -hbm_basis */
/* The file the modes are saved to when neither -modes_load nor -modes_save is given ("": not saved) */
PetscErrorCode JRHBMSetModesFile(JRHBM h, const char file[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(h->modes_file, file ? file : "", sizeof(h->modes_file)));
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMSetBasis(JRHBM h, PetscInt basis)
{
  PetscFunctionBeginUser;
  PetscCheck(basis >= 0 && basis <= 2, h->comm, PETSC_ERR_ARG_OUTOFRANGE, "Basis 0 (free), 1 (stuck) or 2 (mixed)");
  h->basis       = basis;
  h->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGetBasis(JRHBM h, PetscInt *basis)
{
  PetscFunctionBeginUser;
  *basis = h->basis;
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGetSizes(JRHBM h, PetscInt *nm, PetscInt *H, PetscInt *n)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  if (nm) *nm = h->nm;
  if (H) *H = h->H;
  if (n) *n = h->n;
  PetscFunctionReturn(0);
}

/* Natural frequencies of the modes used [rad/s] (none in physical coordinates) */
/* JRHBMGetSolveSize - the size of the unknowns that JRHBMSolve() and the continuation work on: the modal ones
   (JRHBMGetSizes n) or, condensed, the joints' motions (info: a description of the condensation, or "") */
PetscErrorCode JRHBMGetSolveSize(JRHBM h, PetscInt *ns, const char **info)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  if (ns) *ns = h->ns;
  if (info) *info = h->condinfo;
  PetscFunctionReturn(0);
}

/* JRHBMExpand - the modal unknowns a (JRHBMGetSizes n) of the solve-space unknowns x at frequency w: a copy, or
   condensed a = Z^-1 (F fm - Q^T g(x)) (collective: the elements are evaluated) */
PetscErrorCode JRHBMExpand(JRHBM h, PetscReal w, Vec x, Vec a)
{
  const PetscScalar *xx;
  PetscScalar       *aa;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  if (!h->cond) {
    PetscCall(VecCopy(x, a));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(x, &xx));
  PetscCall(VecGetArray(a, &aa));
  PetscCall(CondExpand(h, w, xx, aa));
  PetscCall(VecRestoreArray(a, &aa));
  PetscCall(VecRestoreArrayRead(x, &xx));
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGetModalFrequencies(JRHBM h, PetscInt *nm, const PetscReal **omega)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  *nm    = h->physical ? 0 : h->nm;
  *omega = h->omega_r;
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGetDampingDescription(JRHBM h, const char **d)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  *d = h->damping;
  PetscFunctionReturn(0);
}

/* The excitation level F [N]: f(t) = F f_shape sin(w t). The SNES absolute tolerance follows the
   level unless -hbm_snes_atol is given: 1e-12 of the modal force; condensed, 1e-10 of the joints' static motion
   under it. The condensed residual is the modal one times Q Z^-1, whose gain grows from the static one by up to
   1/(2 zeta) (250-500 here) at resonance, and the round-off of x + G g - F xF with it: at 1e-12 of the static
   motion half of the solves ended on the step test after an iteration that gained nothing (round-off);
   1e-10 of the static motion is 2-4e-13 of the resonant one. */
PetscErrorCode JRHBMSetForceLevel(JRHBM h, PetscReal F)
{
  PetscBool set;
  PetscReal fn = 0.0;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  h->level = F;
  for (PetscInt i = 0; i < h->nm; i++) fn += h->fm[i] * h->fm[i];
  fn = PetscSqrtReal(fn);
  if (h->cond) { /* the residual is a motion of the joints: the modal force over the lowest elastic stiffness, on the rows */
    PetscReal lmin = 0, qn = 0;
    for (PetscInt k = 0; k < h->nm; k++)
      if (h->lamv[k] > 1e-8 * h->lamv[h->nm - 1] && (lmin == 0 || h->lamv[k] < lmin)) lmin = h->lamv[k];
    for (PetscInt r = 0; r < h->nq; r++) {
      PetscReal q = 0;
      for (PetscInt i = 0; i < h->nm; i++) q += h->Q[r * h->nm + i] * h->Q[r * h->nm + i];
      qn = PetscMax(qn, PetscSqrtReal(q));
    }
    if (lmin > 0) fn *= qn / lmin;
  }
  PetscCall(PetscOptionsHasName(NULL, "hbm_", "-snes_atol", &set));
  if (!set) PetscCall(SNESSetTolerances(h->snes, (h->cond ? 1e-10 : 1e-12) * PetscAbsReal(F) * fn + 1e-300, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMCreateVecs(JRHBM h, Vec *x, Mat *J)
{
  PetscFunctionBeginUser;
  if (x) PetscCall(VecCreateSeq(PETSC_COMM_SELF, h->ns, x));
  if (J) {
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, h->ns, h->ns, NULL, J));
    PetscCall(MatSetOption(*J, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));
  }
  PetscFunctionReturn(0);
}

/*
  Nonlinear part: res (n) and, if jac, the Jacobian (n x n column-major) summed over all elements of
  all ranks (identical on every rank). a: the unknowns (n).
*/
/*
  Nonlinear part: res (n) and, if jac, the Jacobian (n x n column-major) summed over all elements of
  all ranks (identical on every rank). a: the unknowns (n). With the analytic Jacobian, every
  evaluation also computes the element derivatives and keeps them with a copy of a: the Jacobian that
  Newton asks for next, at the same a, then only assembles them.
*/
static PetscErrorCode Nonlinear(JRHBM h, const PetscReal *a, PetscReal *res, PetscReal *jac)
{
  const PetscInt  nm = h->cond ? h->nq : h->nm, nc = h->nc, n = h->ns, len = jac ? n + n * n : n; /* nm: the rows' length */
  PetscReal      *loc    = h->buf;
  const PetscBool derivs = (PetscBool)(jac || h->jtype == JR_HBM_JACOBIAN_ANALYTIC);
  PetscBool       reuse  = PETSC_FALSE;

  PetscLogDouble  t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  if (h->cache_ok) reuse = (PetscBool)!memcmp(a, h->cache_a, sizeof(PetscReal) * n); /* forces and derivatives kept from a call at this a (the Jacobian after the residual, the expansion after the accepted residual) */
  PetscCall(PetscArrayzero(loc, len));
  if (h->basis >= 1 && h->Kc && !h->cond) { /* stuck basis: less the stuck springs, which are in Km (this rank's share; all of them if repl) */
    PetscCall(Gemm("N", "N", nm, nc, nm, -1.0, h->Kc, nm, a, nm, 1.0, loc, nm));
    if (jac)
      for (PetscInt k = 0; k < nc; k++) {
        PetscReal *blk = loc + n + (k * nm) + (k * nm) * n;
        for (PetscInt j = 0; j < nm; j++)
          for (PetscInt i = 0; i < nm; i++) blk[i + j * n] -= h->Kc[i + j * nm];
      }
  }
  for (PetscInt t = 0; t < h->ngroups; t++) {
    HBMGroup        *g    = &h->g[t];
    const PetscInt   nloc = g->nloc;
    const PetscReal *GR = g->R, *GS = g->S, *Kst = g->Kst, *Knn = g->Knn;
    if (!nloc) continue;
    if (h->cond) { /* every element moves with one joint row (and one normal row): gathers and scatter-adds */
      const PetscInt *qt = g->qt, *qn = g->qn;
      if (!reuse) {
        for (PetscInt c = 0; c < nc; c++)
          for (PetscInt e = 0; e < nloc; e++) {
            g->U[e + c * nloc] = a[qt[e] + c * nm];
            if (g->normal) g->V[e + c * nloc] = a[qn[e] + c * nm];
          }
        PetscCall(JRContactEvaluate(g->c, g->U, g->V, g->F, g->normal ? g->N : NULL, derivs ? g->DU : NULL, derivs && g->normal ? g->DV : NULL, derivs && g->normal ? g->DN : NULL, NULL));
        if (g->normal)
          for (PetscInt e = 0; e < nloc; e++) g->N[e] -= g->nstatic[e];
      }
      for (PetscInt c = 0; c < nc; c++)
        for (PetscInt e = 0; e < nloc; e++) {
          loc[qt[e] + c * nm] += g->F[e + c * nloc];
          if (g->normal) loc[qn[e] + c * nm] += g->N[e + c * nloc];
        }
      if (jac) { /* dF/du on (joint row, joint row), dF/dv on (joint row, normal row), dN/dv on (normal row, normal row) */
        PetscCall(PetscLogEventBegin(JR_HBMJacobian, 0, 0, 0, 0));
        for (PetscInt k = 0; k < nc; k++)
          for (PetscInt m = 0; m < nc; m++) {
            PetscReal       *blk = loc + n + (k * nm) + (m * nm) * n;
            const PetscReal *du = g->DU + (k * nc + m) * nloc, *dv = g->normal ? g->DV + (k * nc + m) * nloc : NULL, *dn = g->normal ? g->DN + (k * nc + m) * nloc : NULL;
            for (PetscInt e = 0; e < nloc; e++) {
              blk[qt[e] + qt[e] * n] += du[e];
              if (g->normal) {
                blk[qt[e] + qn[e] * n] += dv[e];
                blk[qn[e] + qn[e] * n] += dn[e];
              }
            }
          }
        PetscCall(PetscLogFlops(1.0 * nloc * nc * nc * (g->normal ? 3 : 1)));
        PetscCall(PetscLogEventEnd(JR_HBMJacobian, 0, 0, 0, 0));
      }
      continue;
    }
    if (!reuse) {
      PetscCall(Gemm("N", "N", nloc, nc, nm, 1.0, GR, nloc, a, nm, 0.0, g->U, nloc));
      if (g->normal) PetscCall(Gemm("N", "N", nloc, nc, nm, 1.0, GS, nloc, a, nm, 0.0, g->V, nloc));
      PetscCall(JRContactEvaluate(g->c, g->U, g->V, g->F, g->normal ? g->N : NULL, derivs ? g->DU : NULL, derivs && g->normal ? g->DV : NULL, derivs && g->normal ? g->DN : NULL, NULL));
      if (g->normal)
        for (PetscInt e = 0; e < nloc; e++) g->N[e] -= g->nstatic[e]; /* the dynamic normal load */
    }
    PetscCall(Gemm("T", "N", nm, nc, nloc, 1.0, GR, nloc, g->F, nloc, 1.0, loc, nm));
    if (g->normal) PetscCall(Gemm("T", "N", nm, nc, nloc, 1.0, GS, nloc, g->N, nloc, 1.0, loc, nm));
    if (jac) {
      PetscInt         nsel = nloc;
      const PetscReal *Rj = GR, *Sj = GS;
      PetscCall(PetscLogEventBegin(JR_HBMJacobian, 0, 0, 0, 0));
      if (g->split) {
        /* which elements differ from their state at rest dF/du = pt I, dF/dv = 0, dN/dv = pn I */
        nsel = 0;
        for (PetscInt e = 0; e < nloc; e++) {
          const PetscReal tol = 1e-12 * g->kt[e], toln = 1e-12 * PetscMax(g->kn[e], g->kt[e]);
          PetscBool       stuck = PETSC_TRUE;
          for (PetscInt q = 0; q < nc * nc && stuck; q++) {
            const PetscBool diag = (PetscBool)(q / nc == q % nc);
            if (PetscAbsReal(g->DU[q * nloc + e] - (diag ? g->pt[e] : 0.0)) > tol) stuck = PETSC_FALSE;
            if (g->normal && (PetscAbsReal(g->DV[q * nloc + e]) > toln || PetscAbsReal(g->DN[q * nloc + e] - (diag ? g->pn[e] : 0.0)) > toln)) stuck = PETSC_FALSE;
          }
          if (!stuck) g->sel[nsel++] = e;
        }
        g->nsel = nsel;
        for (PetscInt i = 0; i < nm; i++) {
          for (PetscInt s = 0; s < nsel; s++) g->Rc[s + i * nsel] = GR[g->sel[s] + i * nloc];
          if (g->normal)
            for (PetscInt s = 0; s < nsel; s++) g->Sc[s + i * nsel] = GS[g->sel[s] + i * nloc];
        }
        Rj = g->Rc;
        Sj = g->Sc;
        /* the part at rest: Kst and Knn on the diagonal blocks */
        for (PetscInt k = 0; k < nc; k++) {
          PetscReal *blk = loc + n + (k * nm) + (k * nm) * n;
          for (PetscInt j = 0; j < nm; j++)
            for (PetscInt i = 0; i < nm; i++) blk[i + j * n] += Kst[i + j * nm] + (g->normal ? Knn[i + j * nm] : 0.0);
        }
      }
      if (nsel)
        for (PetscInt k = 0; k < nc; k++)
          for (PetscInt m = 0; m < nc; m++) {
            PetscReal     *blk   = loc + n + (k * nm) + (m * nm) * n;
            const PetscInt which = g->normal ? 3 : 1;
            for (PetscInt q = 0; q < which; q++) {
              const PetscReal *dall = (q == 0 ? g->DU : q == 1 ? g->DV : g->DN) + (k * nc + m) * nloc;
              const PetscReal *left = q == 2 ? Sj : Rj, *right = q == 0 ? Rj : Sj;
              PetscReal       *d    = g->Dc, dmax = 0.0;
              /* the selected elements' derivative, less the stuck part already counted */
              for (PetscInt s = 0; s < nsel; s++) {
                const PetscInt e = g->split ? g->sel[s] : s;
                d[s]             = dall[e] - (g->split && k == m ? (q == 0 ? g->pt[e] : q == 2 ? g->pn[e] : 0.0) : 0.0);
                dmax             = PetscMax(dmax, PetscAbsReal(d[s]));
              }
              if (dmax == 0.0) continue;
              for (PetscInt i = 0; i < nm; i++) {
                const PetscReal *col = right + i * nsel;
                PetscReal       *w   = g->W + i * nsel;
                for (PetscInt s = 0; s < nsel; s++) w[s] = d[s] * col[s];
              }
              PetscCall(Gemm("T", "N", nm, nm, nsel, 1.0, left, nsel, g->W, nsel, 1.0, blk, n));
            }
          }
      PetscCall(PetscLogFlops(2.0 * nsel * nm * nm * nc * nc * (g->normal ? 3 : 1)));
      PetscCall(PetscLogEventEnd(JR_HBMJacobian, 0, 0, 0, 0));
    }
    PetscCall(PetscLogFlops(4.0 * nloc * nm * nc * (g->normal ? 2 : 1)));
  }
  if (!reuse) {
    h->cache_ok = derivs;
    PetscCall(PetscArraycpy(h->cache_a, a, n));
  }
  /* sum over the ranks on rank 0, then everyone gets the same numbers */
  if (h->size > 1 && !h->repl) {
    PetscCallMPI(MPI_Reduce(h->rank ? loc : MPI_IN_PLACE, loc, (PetscMPIInt)len, MPIU_REAL, MPIU_SUM, 0, h->comm));
    PetscCallMPI(MPI_Bcast(loc, (PetscMPIInt)len, MPIU_REAL, 0, h->comm));
  }
  PetscCall(PetscArraycpy(res, loc, n));
  if (jac) PetscCall(PetscArraycpy(jac, loc + n, n * n));
  PetscCall(PetscTime(&t1));
  h->telem += t1 - t0;
  h->nelem++;
  if (jac) h->nelemjac++;
  PetscFunctionReturn(0);
}

/* Linear part of the residual (added to res), of the Jacobian (added to jac, may be NULL) and the
   frequency derivative dR/dw (set, may be NULL) */
static PetscErrorCode Linear(JRHBM h, PetscReal w, const PetscReal *a, PetscReal *res, PetscReal *jac, PetscReal *dw)
{
  const PetscInt nm = h->nm, n = h->n;

  PetscFunctionBeginUser;
  if (dw) PetscCall(PetscArrayzero(dw, n));
  for (PetscInt i = 0; i < nm; i++) { /* mean: K a0 */
    PetscReal s = 0.0;
    for (PetscInt j = 0; j < nm; j++) s += h->Km[i * nm + j] * a[j];
    if (h->pin) s += h->pin[i] * a[i];
    res[i] += s;
    if (jac) {
      for (PetscInt j = 0; j < nm; j++) jac[i + j * n] += h->Km[i * nm + j];
      if (h->pin) jac[i + i * n] += h->pin[i];
    }
  }
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    const PetscInt   os = (2 * hh - 1) * nm, oc = 2 * hh * nm;
    const PetscReal  hw = hh * w;
    const PetscReal *as = a + os, *ac = a + oc;
    for (PetscInt i = 0; i < nm; i++) {
      PetscReal ds = 0.0, dc = 0.0, bs = 0.0, bc = 0.0, ms = 0.0, mc = 0.0, cs = 0.0, cc = 0.0;
      for (PetscInt j = 0; j < nm; j++) {
        const PetscReal kij = h->Km[i * nm + j], mij = h->Mm[i * nm + j], cij = h->Cm[i * nm + j];
        const PetscReal dij = kij - hw * hw * mij, bij = h->gamma * h->Kg[i * nm + j] + hw * cij;
        ds += dij * as[j];
        dc += dij * ac[j];
        bs += bij * as[j];
        bc += bij * ac[j];
        ms += mij * as[j];
        mc += mij * ac[j];
        cs += cij * as[j];
        cc += cij * ac[j];
        if (jac) {
          jac[(os + i) + (os + j) * n] += dij;
          jac[(os + i) + (oc + j) * n] -= bij;
          jac[(oc + i) + (os + j) * n] += bij;
          jac[(oc + i) + (oc + j) * n] += dij;
        }
      }
      res[os + i] += ds - bc - (hh == 1 ? h->level * h->fm[i] : 0.0);
      res[oc + i] += dc + bs;
      if (dw) {
        dw[os + i] = -2.0 * hh * hw * ms - hh * cc;
        dw[oc + i] = -2.0 * hh * hw * mc + hh * cs;
      }
    }
  }
  PetscFunctionReturn(0);
}

/*
  Condensation onto the joints (-hbm_condense). Per harmonic h, in complex form z = as + i ac, the linear part is
      Z_h(w) = Kg (1 + i gamma) - (h w)^2 Mm + i h w Cm   (the mean: Kg + pin),
  with Kg the structure's own stiffness (Km less the stuck springs that the stuck basis holds). When V^T Cm V is
  diagonal for the eigenvectors V of (Kg, Mm) (no viscous damping, or proportional), Z_h^-1 = V diag(1/z_k) V^T with
  z_k = lam_k (1 + i gamma) - (h w)^2 + i h w c_k. Every element of a reduced model moves with one of the nq
  condensed rows Q (its joint's), so with x = Q a the joints' motions and g(x) the elements' forces summed on those
  rows, a = Z^-1 (F fm - Q^T g) and
      r_h(x) = x_h + G_h g_h(x) - F xF_h,   G_h = Q Z_h^-1 Q^T (nq x nq),  xF_1 = Q Z_1^-1 fm,
  the modal equations with the modes eliminated exactly: nq (2H+1) unknowns instead of nm (2H+1).
  CondBlocks: G_h, dG_h/dw, xF_h, dxF_h/dw (re, im; column-major, symmetric) and 1/z_k at frequency w, kept.
*/
static PetscErrorCode CondBlocks(JRHBM h, PetscReal w)
{
  const PetscInt nq = h->nq, nm = h->nm, bs = 4 * nq * nq + 4 * nq, np = nq * (nq + 1) / 2 + nq;
  PetscReal     *dr, *di, *o;

  PetscFunctionBeginUser;
  if (h->wq_ok && h->wq == w) PetscFunctionReturn(0);
  if (!h->QQ) { /* once: the products of the joints' modal rows, pairs r <= c then each row with V^T fm */
    PetscCall(PetscMalloc2(nm * np, &h->QQ, 2 * nm + 4 * np, &h->cb));
    for (PetscInt k = 0; k < nm; k++) {
      PetscReal *q = h->QQ + k * np;
      for (PetscInt c = 0; c < nq; c++)
        for (PetscInt r = 0; r <= c; r++) *q++ = h->QV[r * nm + k] * h->QV[c * nm + k];
      for (PetscInt r = 0; r < nq; r++) *q++ = h->QV[r * nm + k] * h->VF[k];
    }
  }
  dr = h->cb;
  di = dr + nm;
  o  = di + nm; /* 4 x np: sums over the modes of the products times 1/z, d(1/z)/dw (re, im) */
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    PetscReal      *Gr = h->Gb + (hh - 1) * bs, *Gi = Gr + nq * nq, *dGr = Gi + nq * nq, *dGi = dGr + nq * nq;
    PetscReal      *xFr = dGi + nq * nq, *xFi = xFr + nq, *dxFr = xFi + nq, *dxFi = dxFr + nq;
    PetscReal      *ir = h->inv + 2 * (hh - 1) * nm, *ii = ir + nm;
    PetscReal      *o0 = o, *o1 = o + np, *o2 = o + 2 * np, *o3 = o + 3 * np;
    const PetscReal s  = hh * w;
    for (PetscInt k = 0; k < nm; k++) {
      const PetscReal zr = h->lamv[k] - s * s, zi = h->gamma * h->lamv[k] + s * h->cv[k], den = zr * zr + zi * zi;
      const PetscReal dzr = -2.0 * s * hh, dzi = hh * h->cv[k]; /* dz/dw */
      PetscReal       sr, si;
      ir[k] = zr / den;
      ii[k] = -zi / den;
      sr    = ir[k] * ir[k] - ii[k] * ii[k]; /* (1/z)^2 */
      si    = 2.0 * ir[k] * ii[k];
      dr[k] = -(sr * dzr - si * dzi); /* d(1/z)/dw = -(1/z)^2 dz/dw */
      di[k] = -(sr * dzi + si * dzr);
    }
    PetscCall(PetscArrayzero(o, 4 * np));
    for (PetscInt k = 0; k < nm; k++) { /* mode by mode: the inner loop runs over independent sums (vectorised) */
      const PetscReal *q = h->QQ + k * np, a = ir[k], b = ii[k], c = dr[k], d = di[k];
      for (PetscInt p = 0; p < np; p++) {
        o0[p] += q[p] * a;
        o1[p] += q[p] * b;
        o2[p] += q[p] * c;
        o3[p] += q[p] * d;
      }
    }
    for (PetscInt c = 0, p = 0; c < nq; c++)
      for (PetscInt r = 0; r <= c; r++, p++) {
        Gr[r + c * nq] = Gr[c + r * nq] = o0[p];
        Gi[r + c * nq] = Gi[c + r * nq] = o1[p];
        dGr[r + c * nq] = dGr[c + r * nq] = o2[p];
        dGi[r + c * nq] = dGi[c + r * nq] = o3[p];
      }
    for (PetscInt r = 0, p = nq * (nq + 1) / 2; r < nq; r++, p++) { /* the force enters the first harmonic only */
      xFr[r]  = hh == 1 ? o0[p] : 0.0;
      xFi[r]  = hh == 1 ? o1[p] : 0.0;
      dxFr[r] = hh == 1 ? o2[p] : 0.0;
      dxFi[r] = hh == 1 ? o3[p] : 0.0;
    }
  }
  PetscCall(PetscLogFlops(8.0 * h->H * nm * np));
  h->wq    = w;
  h->wq_ok = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Condensed: res holds g(x) on entry and r(x) on exit; jac (if not NULL) dg/dx on entry and I + G dg/dx on exit;
   dw (if not NULL) gets dr/dw */
static PetscErrorCode CondApply(JRHBM h, PetscReal w, const PetscReal *x, PetscReal *res, PetscReal *jac, PetscReal *dw)
{
  const PetscInt nq = h->nq, ns = h->ns, bs = 4 * nq * nq + 4 * nq;
  PetscReal     *t = h->ctmp, *T = h->ctmp + ns;

  PetscFunctionBeginUser;
  PetscCall(CondBlocks(h, w));
  for (PetscInt r = 0; r < nq; r++) { /* the mean */
    PetscReal v = x[r];
    for (PetscInt c = 0; c < nq; c++) v += h->G0[r + c * nq] * res[c];
    t[r] = v;
    if (dw) dw[r] = 0.0;
  }
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    const PetscReal *Gr = h->Gb + (hh - 1) * bs, *Gi = Gr + nq * nq, *dGr = Gi + nq * nq, *dGi = dGr + nq * nq;
    const PetscReal *xFr = dGi + nq * nq, *xFi = xFr + nq, *dxFr = xFi + nq, *dxFi = dxFr + nq;
    const PetscInt   os = (2 * hh - 1) * nq, oc = 2 * hh * nq;
    const PetscReal *gs = res + os, *gc = res + oc;
    for (PetscInt r = 0; r < nq; r++) {
      PetscReal vs = x[os + r] - h->level * xFr[r], vc = x[oc + r] - h->level * xFi[r], ds = -h->level * dxFr[r], dc = -h->level * dxFi[r];
      for (PetscInt c = 0; c < nq; c++) {
        vs += Gr[r + c * nq] * gs[c] - Gi[r + c * nq] * gc[c];
        vc += Gi[r + c * nq] * gs[c] + Gr[r + c * nq] * gc[c];
        ds += dGr[r + c * nq] * gs[c] - dGi[r + c * nq] * gc[c];
        dc += dGi[r + c * nq] * gs[c] + dGr[r + c * nq] * gc[c];
      }
      t[os + r] = vs;
      t[oc + r] = vc;
      if (dw) {
        dw[os + r] = ds;
        dw[oc + r] = dc;
      }
    }
  }
  if (jac) { /* T = I + blockdiag(G) dg/dx, row blocks of dg/dx (leading dimension ns); blocks of a few joints:
                plain loops, the inner one over the rows (a BLAS call costs more than its 6 x 6 product) */
    for (PetscInt j = 0; j < ns; j++) {
      const PetscReal *jc = jac + j * ns;
      PetscReal       *tc = T + j * ns;
      for (PetscInt r = 0; r < nq; r++) tc[r] = 0.0;
      for (PetscInt c = 0; c < nq; c++) {
        const PetscReal v = jc[c];
        if (v != 0.0)
          for (PetscInt r = 0; r < nq; r++) tc[r] += h->G0[r + c * nq] * v;
      }
      for (PetscInt hh = 1; hh <= h->H; hh++) {
        const PetscReal *Gr = h->Gb + (hh - 1) * bs, *Gi = Gr + nq * nq;
        const PetscInt   os = (2 * hh - 1) * nq, oc = 2 * hh * nq;
        for (PetscInt r = 0; r < nq; r++) tc[os + r] = tc[oc + r] = 0.0;
        for (PetscInt c = 0; c < nq; c++) {
          const PetscReal vs = jc[os + c], vc = jc[oc + c];
          if (vs == 0.0 && vc == 0.0) continue;
          for (PetscInt r = 0; r < nq; r++) {
            tc[os + r] += Gr[r + c * nq] * vs - Gi[r + c * nq] * vc;
            tc[oc + r] += Gi[r + c * nq] * vs + Gr[r + c * nq] * vc;
          }
        }
      }
    }
    PetscCall(PetscLogFlops(4.0 * ns * nq * ns));
    for (PetscInt i = 0; i < ns; i++) T[i + i * ns] += 1.0;
    PetscCall(PetscArraycpy(jac, T, ns * ns));
  }
  PetscCall(PetscArraycpy(res, t, ns));
  PetscFunctionReturn(0);
}

/*
  CondenseSetUp - decide on condensation (-hbm_condense auto: a reduced model whose elements all move with their
  joint's rows, fewer rows than modes, and damping diagonal with Kg) and build its operators (collective)
*/
static PetscErrorCode CondenseSetUp(JRHBM h, const JRElements *el)
{
  const PetscInt nm = h->nm, nc = h->nc;
  PetscInt       nj, nq, wdt;
  PetscBool      anyn = PETSC_FALSE, want = (PetscBool)(h->condense == 1);
  PetscReal     *loc, *sum, dev = 0, scale = 0, dd[2], da[2], *A, *B, *work, *Y, cmax = 0, coff = 0;
  PetscBLASInt   bn, bq, lwork, info, itype = 1;
  const char    *why = NULL;

  PetscFunctionBeginUser;
  h->cond        = PETSC_FALSE;
  h->ns          = h->n;
  h->wq_ok       = PETSC_FALSE;
  h->condinfo[0] = 0;
  PetscCall(PetscFree3(h->Q, h->QV, h->VF));
  PetscCall(PetscFree4(h->V, h->lamv, h->cv, h->G0));
  PetscCall(PetscFree2(h->Z0, h->piv0));
  PetscCall(PetscFree3(h->Gb, h->inv, h->ctmp));
  PetscCall(PetscFree2(h->QQ, h->cb)); /* products of the rows: rebuilt from the new ones */
  PetscCall(PetscFree(h->jres));       /* sized by the solve space */
  PetscCall(PetscFree2(h->llu, h->lpiv));
  if (h->condense == 2) PetscFunctionReturn(0);
  if (!el->joint || el->njoints < 1) PetscFunctionReturn(0); /* not a reduced model: nothing to condense onto */
  nj = el->njoints;
  for (PetscInt t = 0; t < h->ngroups; t++) anyn = (PetscBool)(anyn || h->g[t].normal);
  nq  = anyn ? 2 * nj : nj;
  wdt = 2 * nm + 1;
  /* the joints' rows: every element's rows are its joint's (the average of its members' rows, 4.4) */
  PetscCall(PetscCalloc2(nj * wdt, &loc, nj * wdt, &sum));
  for (PetscInt t = 0; t < h->ngroups; t++) {
    HBMGroup *g = &h->g[t];
    for (PetscInt e = 0; e < g->nloc; e++) {
      PetscReal *r = loc + el->joint[g->eidx[e]] * wdt;
      for (PetscInt i = 0; i < nm; i++) r[i] += g->R[e + i * g->nloc];
      if (g->normal)
        for (PetscInt i = 0; i < nm; i++) r[nm + i] += g->S[e + i * g->nloc];
      r[wdt - 1] += 1.0;
    }
  }
  PetscCall(MPIU_Allreduce(loc, sum, nj * wdt, MPIU_REAL, MPIU_SUM, h->ecomm));
  PetscCall(PetscCalloc3(nq * nm, &h->Q, nq * nm, &h->QV, nm, &h->VF));
  for (PetscInt j = 0; j < nj; j++) {
    const PetscReal *r = sum + j * wdt;
    PetscCheck(r[wdt - 1] > 0, h->comm, PETSC_ERR_ARG_WRONG, "Joint %" PetscInt_FMT " has no element", j);
    for (PetscInt i = 0; i < nm; i++) {
      h->Q[j * nm + i] = r[i] / r[wdt - 1];
      if (anyn) h->Q[(nj + j) * nm + i] = r[nm + i] / r[wdt - 1];
    }
  }
  for (PetscInt i = 0; i < nq * nm; i++) scale = PetscMax(scale, PetscAbsReal(h->Q[i]));
  for (PetscInt t = 0; t < h->ngroups; t++) {
    HBMGroup *g = &h->g[t];
    for (PetscInt e = 0; e < g->nloc; e++) {
      const PetscInt j = el->joint[g->eidx[e]];
      for (PetscInt i = 0; i < nm; i++) {
        dev = PetscMax(dev, PetscAbsReal(g->R[e + i * g->nloc] - h->Q[j * nm + i]));
        if (g->normal) dev = PetscMax(dev, PetscAbsReal(g->S[e + i * g->nloc] - h->Q[(nj + j) * nm + i]));
      }
    }
  }
  PetscCall(PetscFree2(loc, sum));
  dd[0] = dev;
  dd[1] = scale;
  PetscCall(MPIU_Allreduce(dd, da, 2, MPIU_REAL, MPIU_MAX, h->comm));
  if (da[0] > 1e-10 * da[1]) why = "the elements of a joint do not all move with the joint's rows";
  else if (nq >= nm && !want) why = "at least as many joint rows as modes (nothing to gain; -hbm_condense yes forces it)";
  if (!why) { /* (Kg, Mm) eigenvectors; the viscous damping must be diagonal in them */
    PetscCall(PetscMalloc4(nm * nm, &h->V, nm, &h->lamv, nm, &h->cv, nq * nq, &h->G0));
    PetscCall(PetscMalloc4(nm * nm, &A, nm * nm, &B, 8 * nm, &work, nm * PetscMax(nm, nq), &Y));
    for (PetscInt i = 0; i < nm; i++)
      for (PetscInt j = 0; j < nm; j++) {
        h->V[i + j * nm] = 0.5 * (h->Kg[i * nm + j] + h->Kg[j * nm + i]);
        B[i + j * nm]    = 0.5 * (h->Mm[i * nm + j] + h->Mm[j * nm + i]);
      }
    PetscCall(PetscBLASIntCast(nm, &bn));
    PetscCall(PetscBLASIntCast(8 * nm, &lwork));
    PetscCallBLAS("LAPACKsygv", LAPACKsygv_(&itype, "V", "U", &bn, h->V, &bn, B, &bn, h->lamv, work, &lwork, &info));
    PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK sygv (condensation) failed: info %d", (int)info);
    /* C' = V^T Cm V */
    for (PetscInt i = 0; i < nm; i++)
      for (PetscInt j = 0; j < nm; j++) A[i + j * nm] = h->Cm[i * nm + j];
    PetscCall(Gemm("N", "N", nm, nm, nm, 1.0, A, nm, h->V, nm, 0.0, Y, nm));
    PetscCall(Gemm("T", "N", nm, nm, nm, 1.0, h->V, nm, Y, nm, 0.0, A, nm));
    for (PetscInt i = 0; i < nm; i++) {
      h->cv[i] = A[i + i * nm];
      for (PetscInt j = 0; j < nm; j++) {
        cmax = PetscMax(cmax, PetscAbsReal(A[i + j * nm]));
        if (i != j) coff = PetscMax(coff, PetscAbsReal(A[i + j * nm]));
      }
    }
    if (coff > 1e-9 * cmax) why = "the viscous damping is not diagonal in the eigenvectors of the structure's stiffness and mass (use -hbm_gamma, or proportional damping)";
    else {
      /* Q V, V^T fm */
      PetscCall(Gemm("T", "N", nm, nq, nm, 1.0, h->V, nm, h->Q, nm, 0.0, h->QV, nm)); /* (QV)^T col-major nm x nq = QV row-major */
      PetscCall(Gemm("T", "N", nm, 1, nm, 1.0, h->V, nm, h->fm, nm, 0.0, h->VF, nm));
      /* the mean block Kg + pin, LU, and G0 = Q Z0^-1 Q^T */
      PetscCall(PetscMalloc2(nm * nm, &h->Z0, nm, &h->piv0));
      for (PetscInt i = 0; i < nm; i++)
        for (PetscInt j = 0; j < nm; j++) h->Z0[i + j * nm] = h->Kg[i * nm + j] + (i == j && h->pin ? h->pin[i] : 0.0);
      PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, h->Z0, &bn, h->piv0, &info));
      PetscCheck(!info, h->comm, PETSC_ERR_MAT_LU_ZRPVT, "Condensation: the static stiffness (mean block) is singular, info %d", (int)info);
      PetscCall(PetscArraycpy(Y, h->Q, nq * nm)); /* Q^T, col-major nm x nq */
      PetscCall(PetscBLASIntCast(nq, &bq));
      PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bn, &bq, h->Z0, &bn, h->piv0, Y, &bn, &info));
      PetscCall(Gemm("T", "N", nq, nq, nm, 1.0, h->Q, nm, Y, nm, 0.0, h->G0, nq));
    }
    PetscCall(PetscFree4(A, B, work, Y));
  }
  if (why) {
    PetscCheck(!want, h->comm, PETSC_ERR_ARG_INCOMP, "-hbm_condense yes: cannot condense onto the joints: %s", why);
    PetscCall(PetscInfo(NULL, "No condensation: %s\n", why));
    PetscCall(PetscFree3(h->Q, h->QV, h->VF));
    PetscCall(PetscFree4(h->V, h->lamv, h->cv, h->G0));
    PetscCall(PetscFree2(h->Z0, h->piv0));
    PetscFunctionReturn(0);
  }
  /* every element's joint row (and normal row) */
  for (PetscInt t = 0; t < h->ngroups; t++) {
    HBMGroup      *g    = &h->g[t];
    const PetscInt nloc = g->nloc;
    PetscCall(PetscFree2(g->qt, g->qn));
    PetscCall(PetscMalloc2(nloc, &g->qt, nloc, &g->qn));
    for (PetscInt e = 0; e < nloc; e++) {
      const PetscInt j = el->joint[g->eidx[e]];
      g->qt[e]         = j;
      g->qn[e]         = g->normal ? nj + j : -1;
    }
  }
  h->nq = nq;
  h->ns = nq * nc;
  PetscCall(PetscMalloc3(h->H * (4 * nq * nq + 4 * nq), &h->Gb, 2 * h->H * nm, &h->inv, h->ns + h->ns * h->ns, &h->ctmp));
  h->cond = PETSC_TRUE;
  PetscCall(PetscSNPrintf(h->condinfo, sizeof(h->condinfo), "condensed onto %" PetscInt_FMT " joint motions: %" PetscInt_FMT " unknowns instead of %" PetscInt_FMT, nq, h->ns, h->n));
  PetscFunctionReturn(0);
}

/* Condensed: the modal unknowns a (n) of the joints' motions x (ns) at frequency w, a = Z^-1 (F fm - Q^T g(x)) */
static PetscErrorCode CondExpand(JRHBM h, PetscReal w, const PetscReal *x, PetscReal *a)
{
  const PetscInt nq = h->nq, nm = h->nm;
  PetscReal     *g, *br, *bi;
  PetscBLASInt   bn, one = 1, info;

  PetscFunctionBeginUser;
  PetscCall(CondBlocks(h, w));
  PetscCall(PetscMalloc3(h->ns, &g, nm, &br, nm, &bi));
  PetscCall(Nonlinear(h, x, g, NULL));
  for (PetscInt i = 0; i < nm; i++) { /* the mean: Z0 a0 = -Q^T g0 */
    PetscReal v = 0;
    for (PetscInt r = 0; r < nq; r++) v -= h->Q[r * nm + i] * g[r];
    a[i] = v;
  }
  PetscCall(PetscBLASIntCast(nm, &bn));
  PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bn, &one, h->Z0, &bn, h->piv0, a, &bn, &info));
  for (PetscInt hh = 1; hh <= h->H; hh++) {
    const PetscInt   os = (2 * hh - 1) * nq, oc = 2 * hh * nq;
    const PetscReal *ir = h->inv + 2 * (hh - 1) * nm, *ii = ir + nm;
    for (PetscInt k = 0; k < nm; k++) { /* b = V^T (F fm - Q^T g), then z = b / z_k */
      PetscReal vr = hh == 1 ? h->level * h->VF[k] : 0.0, vi = 0.0;
      for (PetscInt r = 0; r < nq; r++) {
        vr -= h->QV[r * nm + k] * g[os + r];
        vi -= h->QV[r * nm + k] * g[oc + r];
      }
      br[k] = ir[k] * vr - ii[k] * vi;
      bi[k] = ir[k] * vi + ii[k] * vr;
    }
    PetscCall(Gemm("N", "N", nm, 1, nm, 1.0, h->V, nm, br, nm, 0.0, a + (2 * hh - 1) * nm, nm));
    PetscCall(Gemm("N", "N", nm, 1, nm, 1.0, h->V, nm, bi, nm, 0.0, a + 2 * hh * nm, nm));
  }
  PetscCall(PetscFree3(g, br, bi));
  PetscFunctionReturn(0);
}

/* R(a, w): the harmonic-balance residual (collective) */
PetscErrorCode JRHBMComputeResidual(JRHBM h, PetscReal w, Vec a, Vec R)
{
  const PetscScalar *x;
  PetscScalar       *r;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(PetscLogEventBegin(JR_HBMResidual, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(a, &x));
  PetscCall(VecGetArray(R, &r));
  PetscCall(Nonlinear(h, x, r, NULL));
  if (h->cond) PetscCall(CondApply(h, w, x, r, NULL, NULL));
  else PetscCall(Linear(h, w, x, r, NULL, NULL));
  PetscCall(VecRestoreArray(R, &r));
  PetscCall(VecRestoreArrayRead(a, &x));
  PetscCall(PetscLogEventEnd(JR_HBMResidual, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* J = dR/da (analytic) and, if Rw is not NULL, dR/dw (collective) */
PetscErrorCode JRHBMComputeJacobian(JRHBM h, PetscReal w, Vec a, Mat J, Vec Rw)
{
  const PetscScalar *x;
  PetscScalar       *j, *rw = NULL;
  PetscReal         *res;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  if (!h->jres) PetscCall(PetscMalloc1(h->ns, &h->jres));
  res = h->jres;
  PetscCall(VecGetArrayRead(a, &x));
  PetscCall(MatDenseGetArrayWrite(J, &j));
  if (Rw) PetscCall(VecGetArray(Rw, &rw));
  PetscCall(Nonlinear(h, x, res, j));
  if (h->cond) PetscCall(CondApply(h, w, x, res, j, rw));
  else PetscCall(Linear(h, w, x, res, j, rw));
  if (Rw) PetscCall(VecRestoreArray(Rw, &rw));
  PetscCall(MatDenseRestoreArrayWrite(J, &j));
  PetscCall(VecRestoreArrayRead(a, &x));
  PetscCall(JRMatDenseAssemble(J));
  PetscFunctionReturn(0);
}

static PetscErrorCode FormFunction(SNES snes, Vec a, Vec R, void *ctx)
{
  JRHBM h = (JRHBM)ctx;

  PetscFunctionBeginUser;
  (void)snes;
  PetscCall(JRHBMComputeResidual(h, h->omega, a, R));
  PetscFunctionReturn(0);
}

static PetscErrorCode FormJacobian(SNES snes, Vec a, Mat J, Mat P, void *ctx)
{
  JRHBM h = (JRHBM)ctx;

  PetscFunctionBeginUser;
  (void)snes;
  (void)P;
  PetscCall(JRHBMComputeJacobian(h, h->omega, a, J, NULL));
  PetscFunctionReturn(0);
}

/* Solve R(a, w) = 0 at fixed frequency w from the guess in a; its: Newton iterations */
PetscErrorCode JRHBMSolve(JRHBM h, PetscReal w, Vec a, PetscInt *its, PetscBool *converged)
{
  SNESConvergedReason reason;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(PetscLogEventBegin(JR_HBMSolve, 0, 0, 0, 0));
  h->omega = w;
  PetscCall(SNESSolve(h->snes, NULL, a));
  PetscCall(SNESGetConvergedReason(h->snes, &reason));
  PetscCall(SNESGetIterationNumber(h->snes, its));
  *converged = reason > 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscLogEventEnd(JR_HBMSolve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The response of the structure with every element linearised about rest (stuck contacts):
   one Newton step from a = 0, exact when the elements stay in full stick */
PetscErrorCode JRHBMLinearSolution(JRHBM h, PetscReal w, Vec a)
{
  const PetscInt     n = h->ns;
  const PetscScalar *j;
  PetscScalar       *x;
  PetscBool          singular;

  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  PetscCall(VecZeroEntries(a));
  PetscCall(JRHBMComputeJacobian(h, w, a, h->J, NULL)); /* and the residual at a = 0, in jres */
  if (!h->llu) PetscCall(PetscMalloc2(n * n, &h->llu, n, &h->lpiv));
  PetscCall(VecGetArray(a, &x));
  for (PetscInt i = 0; i < n; i++) x[i] = -h->jres[i];
  PetscCall(MatDenseGetArrayRead(h->J, &j));
  PetscCall(JRDenseSolve(n, j, n, h->llu, h->lpiv, x, &singular));
  PetscCall(MatDenseRestoreArrayRead(h->J, &j));
  PetscCall(VecRestoreArray(a, &x));
  PetscCheck(!singular, h->comm, PETSC_ERR_MAT_LU_ZRPVT, "The linearised harmonic-balance system is singular at %g Hz (a zero pivot): an undamped resonance or a rigid-body mode without -hbm_gamma or a stuck basis", (double)(w / (2 * PETSC_PI)));
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGetSNES(JRHBM h, SNES *snes)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  *snes = h->snes;
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGetJacobianType(JRHBM h, JRHBMJacobianType *jt)
{
  PetscFunctionBeginUser;
  *jt = h->jtype;
  PetscFunctionReturn(0);
}

/*
  JRHBMGetElementTime - the wall time [s] spent so far evaluating the contact elements (forces, their derivatives
  projected into the Jacobian, and the sums over the ranks: everything whose cost grows with the elements), and how
  many evaluations, of which with a Jacobian (any argument may be NULL). The rest of a solve is the linear
  algebra on the unknowns and the continuation, the same for any number of elements.
*/
PetscErrorCode JRHBMGetElementTime(JRHBM h, PetscLogDouble *seconds, PetscInt *calls, PetscInt *jacobians)
{
  PetscFunctionBeginUser;
  if (seconds) *seconds = h->telem;
  if (calls) *calls = h->nelem;
  if (jacobians) *jacobians = h->nelemjac;
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMGetOutputs(JRHBM h, PetscInt *nout, const PetscInt **dofs)
{
  PetscFunctionBeginUser;
  PetscCall(JRHBMSetUp(h));
  *nout = h->nout;
  if (dofs) *dofs = h->outdof;
  PetscFunctionReturn(0);
}

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
  h->cache_ok = PETSC_FALSE;
  for (PetscInt t = 0; t < h->ngroups; t++) {
    HBMGroup *g = &h->g[t];
    if (!g->nloc) continue;
    PetscCall(Gemm("N", "N", g->nloc, nc, nm, 1.0, g->R, g->nloc, x, nm, 0.0, g->U, g->nloc));
    if (g->normal) PetscCall(Gemm("N", "N", g->nloc, nc, nm, 1.0, g->S, g->nloc, x, nm, 0.0, g->V, g->nloc));
    PetscCall(JRContactEvaluate(g->c, g->U, g->V, g->F, g->normal ? g->N : NULL, NULL, NULL, NULL, NULL));
    for (PetscInt e = 0; e < g->nloc; e++)
      for (PetscInt hh = 1; 2 * hh < nc; hh++) {
        enl += PETSC_PI * hh * (g->U[(2 * hh - 1) * g->nloc + e] * g->F[2 * hh * g->nloc + e] - g->U[2 * hh * g->nloc + e] * g->F[(2 * hh - 1) * g->nloc + e]);
        if (g->normal) enl += PETSC_PI * hh * (g->V[(2 * hh - 1) * g->nloc + e] * g->N[2 * hh * g->nloc + e] - g->V[2 * hh * g->nloc + e] * g->N[(2 * hh - 1) * g->nloc + e]);
      }
  }
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

/* Every local element's contact state over the cycle at the solution a, in g->state */
static PetscErrorCode EvaluateStates(JRHBM h, Vec a)
{
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(a, &x));
  h->cache_ok = PETSC_FALSE;
  for (PetscInt t = 0; t < h->ngroups; t++) {
    HBMGroup *g = &h->g[t];
    if (!g->nloc) continue;
    PetscCall(Gemm("N", "N", g->nloc, h->nc, h->nm, 1.0, g->R, g->nloc, x, h->nm, 0.0, g->U, g->nloc));
    if (g->normal) PetscCall(Gemm("N", "N", g->nloc, h->nc, h->nm, 1.0, g->S, g->nloc, x, h->nm, 0.0, g->V, g->nloc));
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

PetscErrorCode JRHBMView(JRHBM h, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(h->comm, &viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "JRHBM: %" PetscInt_FMT " harmonics + mean, %s, %" PetscInt_FMT " unknowns, %s Jacobian, %d rank(s)\n", h->H, h->physical ? "physical coordinates" : "modal coordinates", h->n, JRHBMJacobianTypes[h->jtype], h->size));
  if (!h->physical) PetscCall(PetscViewerASCIIPrintf(viewer, "  %" PetscInt_FMT " modes, %.6g .. %.6g Hz\n", h->nm, (double)(h->omega_r[0] / (2 * PETSC_PI)), (double)(h->omega_r[h->nm - 1] / (2 * PETSC_PI))));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  damping: %s\n", h->damping));
  for (PetscInt t = 0; t < h->ngroups; t++) {
    PetscInt nt;
    PetscCall(MPIU_Allreduce(&h->g[t].nloc, &nt, 1, MPIU_INT, MPI_SUM, h->ecomm));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  %" PetscInt_FMT " %s elements\n", nt, h->g[t].c->type_name));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode JRHBMDestroy(JRHBM *hbm)
{
  JRHBM h = *hbm;

  PetscFunctionBeginUser;
  if (!h) PetscFunctionReturn(0);
  for (PetscInt t = 0; t < h->ngroups; t++) PetscCall(GroupDestroy(&h->g[t]));
  PetscCall(PetscFree(h->g));
  if (!h->modes_shared) PetscCall(JRModesDestroy(&h->modes));
  PetscCall(PetscFree3(h->Km, h->Mm, h->Cm));
  PetscCall(PetscFree(h->omega_r));
  PetscCall(PetscFree(h->pin));
  PetscCall(PetscFree(h->Kg));
  PetscCall(PetscFree(h->Kc));
  PetscCall(PetscFree(h->outdof));
  PetscCall(PetscFree(h->ptxyz));
  PetscCall(PetscFree(h->fm));
  PetscCall(PetscFree(h->Phiout));
  PetscCall(PetscFree(h->buf));
  PetscCall(PetscFree(h->cache_a));
  PetscCall(SNESDestroy(&h->snes));
  PetscCall(MatDestroy(&h->J));
  PetscCall(VecDestroy(&h->r));
  PetscCall(PetscFree2(h->QQ, h->cb));
  PetscCall(PetscFree(h->pptab));
  PetscCall(PetscFree(h->jres));
  PetscCall(PetscFree2(h->llu, h->lpiv));
  PetscCall(PetscFree3(h->Q, h->QV, h->VF));
  PetscCall(PetscFree4(h->V, h->lamv, h->cv, h->G0));
  PetscCall(PetscFree2(h->Z0, h->piv0));
  PetscCall(PetscFree3(h->Gb, h->inv, h->ctmp));
  PetscCall(PetscFree(h));
  *hbm = NULL;
  PetscFunctionReturn(0);
}
