/*
   JRNLModes: a nonlinear mode of a structure with friction contact elements, by the extended periodic motion concept
   (EPMC, Krack 2015; src/hbm/epmc.c): the backbone of the stuck mode of interest, its frequency and damping ratio
   D = xi / (2 w) against its modal amplitude q, from the stuck limit to gross slip.

   Continuation in the scaled unknowns y = [a / q | w / w0 | xi / w0], which vary slowly with s = log q, from
   -nlm_amp_min to -nlm_amp_max: pseudo-arclength in z = [y | s] along the secant of the last two points (the default,
   every accepted point kept), or natural in s at -nlm_points amplitudes evenly spaced in s; steps at most
   -nlm_step_max decades, halved when Newton fails. The correctors are SNESs (prefix nlm_, newtondense) on the EPMC's
   n + 2 equations scaled by q w0^2 (the harmonic balance) and q (the normalisation), bordered for arclength by s and
   the constraint t^T (z - zp) = 0.
*/
#include <jointrom/private/nlmodesimpl.h>
#include <petscviewerhdf5.h>

PetscErrorCode JRNLModesCreate(MPI_Comm comm, JRNLModes *nlm)
{
  JRNLModes m;

  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(PetscNew(&m));
  m->comm      = comm;
  m->mode      = 1;
  m->npts      = 30;
  m->dmax      = 0.1;
  m->maxcuts   = 12;
  m->plot      = PETSC_TRUE;
  m->arclength = PETSC_TRUE;
  PetscCall(PetscStrncpy(m->out, "out/nlmodes", sizeof(m->out)));
  *nlm = m;
  PetscFunctionReturn(0);
}

/* The harmonic balance whose mode is followed (a reference is kept: the caller keeps it alive) */
PetscErrorCode JRNLModesSetHBM(JRNLModes m, JRHBM hbm)
{
  PetscFunctionBeginUser;
  m->hbm         = hbm;
  m->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*
  Options: -nlm_mode k (the k-th elastic mode of the stuck structure), -nlm_amp_min, -nlm_amp_max (modal amplitudes of
  the mass-normalised mode; default: 0.1 times the amplitude at which the first friction element slips, 3 times the one
  by which the elements holding 95% of the slip force slip), -nlm_continuation arclength|natural, -nlm_points,
  -nlm_step_max, -nlm_max_cuts, -nlm_output_file, -nlm_plot, -nlm_view; -nlm_snes_* on the correctors
*/
PetscErrorCode JRNLModesSetFromOptions(JRNLModes m)
{
  static const char *const Conts[] = {"natural", "arclength"};
  PetscInt                 ct      = m->arclength ? 1 : 0;

  PetscFunctionBeginUser;
  PetscOptionsBegin(m->comm, NULL, "Nonlinear modes by EPMC (JRNLModes)", "JRNLModes");
  PetscCall(PetscOptionsInt("-nlm_mode", "Which elastic mode of the stuck structure (1: the first elastic mode)", "JRNLModesSetUp", m->mode, &m->mode, NULL));
  PetscCall(PetscOptionsReal("-nlm_amp_min", "Smallest modal amplitude q of the mass-normalised mode [m kg^1/2] (default: 0.1 x the amplitude at which the first element slips)", "JRNLModesSetUp", m->amin, &m->amin, NULL));
  PetscCall(PetscOptionsReal("-nlm_amp_max", "Largest modal amplitude q [m kg^1/2] (default: 3 x the amplitude by which the elements holding 95 percent of the slip force slip)", "JRNLModesSetUp", m->amax, &m->amax, NULL));
  PetscCall(PetscOptionsInt("-nlm_points", "Points of the backbone: at least this many (arclength), or exactly, evenly spaced in log q (natural)", "JRNLModesSolve", m->npts, &m->npts, NULL));
  PetscCall(PetscOptionsReal("-nlm_step_max", "Largest continuation step in log10 q [decades]: longer intervals are split", "JRNLModesSolve", m->dmax, &m->dmax, NULL));
  PetscCall(PetscOptionsEList("-nlm_continuation", "Continuation in the amplitude: arclength (pseudo-arclength in the scaled unknowns and log q: through folds) or natural (in log q, at the -nlm_points amplitudes exactly)", "JRNLModesSolve", Conts, 2, Conts[m->arclength ? 1 : 0], &ct, NULL));
  PetscCall(PetscOptionsInt("-nlm_max_cuts", "Step halvings in a row after failed Newton solves before the backbone stops (an error)", "JRNLModesSolve", m->maxcuts, &m->maxcuts, NULL));
  PetscCall(PetscOptionsString("-nlm_output_file", "Output base name: BASE.h5, BASE.csv, BASE.png ('' for none)", "JRNLModesWrite", m->out, m->out, sizeof(m->out), NULL));
  PetscCall(PetscOptionsBool("-nlm_plot", "Draw BASE.png (frequency and damping ratio against amplitude)", "JRNLModesWrite", m->plot, &m->plot, NULL));
  PetscCall(PetscOptionsBool("-nlm_view", "Print the nonlinear-mode set-up", "JRNLModesView", m->view, &m->view, NULL));
  PetscOptionsEnd();
  m->arclength = ct == 1 ? PETSC_TRUE : PETSC_FALSE;
  PetscCheck(m->mode >= 1, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-nlm_mode %" PetscInt_FMT ": the elastic modes are numbered from 1", m->mode);
  PetscCheck(m->amin >= 0 && m->amax >= 0, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-nlm_amp_min %g, -nlm_amp_max %g: modal amplitudes are positive", (double)m->amin, (double)m->amax);
  PetscCheck(!(m->amin > 0 && m->amax > 0) || m->amax > m->amin, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-nlm_amp_max %g must exceed -nlm_amp_min %g", (double)m->amax, (double)m->amin);
  PetscCheck(m->npts >= 2 && m->npts <= 100000, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-nlm_points %" PetscInt_FMT ": between 2 and 100000", m->npts);
  PetscCheck(m->dmax > 0 && m->dmax <= 2, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-nlm_step_max %g: a step in decades of amplitude, in (0, 2]", (double)m->dmax);
  PetscCheck(m->maxcuts >= 0 && m->maxcuts <= 40, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-nlm_max_cuts %" PetscInt_FMT ": between 0 and 40", m->maxcuts);
  m->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The output base name of -nlm_output_file ('' for none) */
PetscErrorCode JRNLModesGetOutputBase(JRNLModes m, const char **base)
{
  PetscFunctionBeginUser;
  *base = m->out;
  PetscFunctionReturn(0);
}

/* The output base name ("" for none) and whether to draw BASE.png, set in code after JRNLModesSetFromOptions (-task
   compare names both models' files from -frf_output_file) */
PetscErrorCode JRNLModesSetOutput(JRNLModes m, const char base[], PetscBool plot)
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(m->out, base ? base : "", sizeof(m->out)));
  m->plot = plot;
  PetscFunctionReturn(0);
}

/* A prefix put before "nlm_" on the correctors' options (-<prefix>nlm_snes_*), as JRHBMSetOptionsPrefix does for the
   harmonic balance: -task compare gives the reduced model's "rom_"; the -nlm_* options themselves are shared */
PetscErrorCode JRNLModesSetOptionsPrefix(JRNLModes m, const char prefix[])
{
  PetscFunctionBeginUser;
  PetscCheck(!m->setupcalled, m->comm, PETSC_ERR_ARG_WRONGSTATE, "JRNLModesSetOptionsPrefix() before JRNLModesSetUp()");
  PetscCall(PetscStrncpy(m->prefix, prefix ? prefix : "", sizeof(m->prefix)));
  PetscFunctionReturn(0);
}

/* The modal amplitude range [m kg^1/2] (as -nlm_amp_min, -nlm_amp_max; 0: the default from the elements), e.g. another
   backbone's, so that two models are followed over the same amplitudes */
PetscErrorCode JRNLModesSetRange(JRNLModes m, PetscReal amin, PetscReal amax)
{
  PetscFunctionBeginUser;
  PetscCheck(amin >= 0 && amax >= 0 && (!(amin > 0 && amax > 0) || amax > amin), m->comm, PETSC_ERR_ARG_OUTOFRANGE, "Nonlinear modes: amplitude range %g .. %g: positive and increasing", (double)amin, (double)amax);
  m->amin = amin;
  m->amax = amax;
  PetscFunctionReturn(0);
}

/* The modal amplitude range [m kg^1/2]: after JRNLModesSetUp, the one followed (the default filled in) */
PetscErrorCode JRNLModesGetRange(JRNLModes m, PetscReal *amin, PetscReal *amax)
{
  PetscFunctionBeginUser;
  if (amin) *amin = m->amin;
  if (amax) *amax = m->amax;
  PetscFunctionReturn(0);
}

/* y (scaled) -> x = [q y_a | w0 y_w | w0 y_xi] */
static PetscErrorCode Unscale(JRNLModes m, Vec y, Vec x)
{
  const PetscScalar *ya;
  PetscScalar       *xa;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(VecGetArray(x, &xa));
  for (PetscInt i = 0; i < m->n; i++) xa[i] = m->q * ya[i];
  xa[m->n]     = m->w0 * ya[m->n];
  xa[m->n + 1] = m->w0 * ya[m->n + 1];
  PetscCall(VecRestoreArray(x, &xa));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscFunctionReturn(0);
}

static PetscErrorCode FormFunction(SNES snes, Vec y, Vec F, void *ctx)
{
  JRNLModes    m = (JRNLModes)ctx;
  PetscScalar *f;

  PetscFunctionBeginUser;
  (void)snes;
  PetscCall(Unscale(m, y, m->xr));
  PetscCall(JRHBMComputeEPMC(m->hbm, m->q, m->xr, F, NULL));
  PetscCall(VecGetArray(F, &f));
  for (PetscInt i = 0; i < m->n; i++) f[i] /= m->q * m->w0 * m->w0;
  f[m->n] /= m->q;
  f[m->n + 1] /= m->q;
  PetscCall(VecRestoreArray(F, &f));
  PetscFunctionReturn(0);
}

static PetscErrorCode FormJacobian(SNES snes, Vec y, Mat J, Mat P, void *ctx)
{
  JRNLModes      m = (JRNLModes)ctx;
  PetscScalar   *j;
  const PetscInt n = m->n, N = m->N;

  PetscFunctionBeginUser;
  (void)snes;
  (void)P;
  PetscCall(Unscale(m, y, m->xr));
  PetscCall(JRHBMComputeEPMC(m->hbm, m->q, m->xr, m->rr, J));
  PetscCall(MatDenseGetArray(J, &j));
  for (PetscInt c = 0; c < N; c++) {
    const PetscReal sc = c < n ? m->q : m->w0;
    for (PetscInt r = 0; r < N; r++) j[r + c * N] *= sc / (r < n ? m->q * m->w0 * m->w0 : m->q);
  }
  PetscCall(MatDenseRestoreArray(J, &j));
  PetscFunctionReturn(0);
}

/* Arclength: z = [y | s = log q], the EPMC equations at q = e^s and the constraint t^T (z - zp) = 0 */
static PetscErrorCode FormFunctionArc(SNES snes, Vec z, Vec F, void *ctx)
{
  JRNLModes          m = (JRNLModes)ctx;
  const PetscScalar *za;
  PetscScalar       *fa;
  PetscReal          c = 0;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(z, &za));
  PetscCall(VecGetArray(F, &fa));
  m->q = PetscExpReal(PetscRealPart(za[m->N]));
  PetscCall(VecPlaceArray(m->yv, za));
  PetscCall(VecPlaceArray(m->fv, fa));
  PetscCall(FormFunction(snes, m->yv, m->fv, m));
  PetscCall(VecResetArray(m->yv));
  PetscCall(VecResetArray(m->fv));
  for (PetscInt i = 0; i <= m->N; i++) c += m->tz[i] * (PetscRealPart(za[i]) - m->zp[i]);
  fa[m->N] = c;
  PetscCall(VecRestoreArray(F, &fa));
  PetscCall(VecRestoreArrayRead(z, &za));
  PetscFunctionReturn(0);
}

/* d/ds of the scaled equations: the harmonic balance's rows scale with q except through the nonlinearity,
   dF_i/ds = sum_{j < n} Js_ij y_j - F_i; the normalisation's scaled rows do not depend on q */
static PetscErrorCode FormJacobianArc(SNES snes, Vec z, Mat J, Mat P, void *ctx)
{
  JRNLModes          m = (JRNLModes)ctx;
  const PetscScalar *za, *js, *rr;
  PetscScalar       *ja;
  const PetscInt     n = m->n, N = m->N, N1 = m->N + 1;

  PetscFunctionBeginUser;
  (void)P;
  PetscCall(VecGetArrayRead(z, &za));
  m->q = PetscExpReal(PetscRealPart(za[N]));
  PetscCall(VecPlaceArray(m->yv, za));
  PetscCall(FormJacobian(snes, m->yv, m->J, m->J, m));
  PetscCall(VecResetArray(m->yv));
  PetscCall(MatDenseGetArrayRead(m->J, &js));
  PetscCall(VecGetArrayRead(m->rr, &rr));
  PetscCall(MatDenseGetArrayWrite(J, &ja));
  for (PetscInt c = 0; c < N; c++) {
    for (PetscInt r = 0; r < N; r++) ja[r + c * N1] = js[r + c * N];
    ja[N + c * N1] = m->tz[c];
  }
  for (PetscInt r = 0; r < N; r++) {
    PetscReal d = 0;
    if (r < n) {
      for (PetscInt j = 0; j < n; j++) d += PetscRealPart(js[r + j * N] * za[j]);
      d -= PetscRealPart(rr[r]) / (m->q * m->w0 * m->w0);
    }
    ja[r + N * N1] = d;
  }
  ja[N + N * N1] = m->tz[N];
  PetscCall(MatDenseRestoreArrayWrite(J, &ja));
  PetscCall(VecRestoreArrayRead(m->rr, &rr));
  PetscCall(MatDenseRestoreArrayRead(m->J, &js));
  PetscCall(VecRestoreArrayRead(z, &za));
  PetscCall(JRMatDenseAssemble(J));
  PetscFunctionReturn(0);
}

/* The default amplitude range: from the modal amplitudes q_e = mu n0 / (kt |u_e|) at which each friction element in
   contact starts to slip in the stuck mode (u_e: its motion in the mode), 0.1 x the first to 3 x the one by which the
   elements holding 95% of the interface's slip force mu n0 slip (elements near a neutral line barely move) */
static PetscErrorCode DefaultRange(JRNLModes m)
{
  const JRElements *el;
  PetscReal        *u, *qe, tot = 0, sum = 0, lo = 0, hi = 0;
  PetscInt         *perm, nq = 0;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetElements(m->hbm, &el));
  PetscCall(PetscMalloc3(PetscMax(el->n, 1), &u, PetscMax(el->n, 1), &qe, PetscMax(el->n, 1), &perm));
  PetscCall(JRHBMStuckModeMotion(m->hbm, m->kmode, u, NULL));
  for (PetscInt e = 0; e < el->n; e++) {
    const char *t = el->typename[el->type[e]];
    if (strncmp(t, "jenkins", 7) || el->n0[e] <= 0 || el->mu[e] <= 0 || el->kt[e] <= 0 || PetscAbsReal(u[e]) < 1e-300) continue;
    qe[nq]   = el->mu[e] * el->n0[e] / (el->kt[e] * PetscAbsReal(u[e]));
    perm[nq] = e;
    tot += el->mu[e] * el->n0[e];
    nq++;
  }
  PetscCheck(nq || (m->amin > 0 && m->amax > 0), m->comm, PETSC_ERR_ARG_WRONG, "Nonlinear modes: no friction element slips in this mode; give the range with -nlm_amp_min and -nlm_amp_max");
  if (nq) {
    PetscCall(PetscSortRealWithArrayInt(nq, qe, perm));
    lo = qe[0];
    for (PetscInt i = 0; i < nq && sum < 0.95 * tot; i++) {
      sum += el->mu[perm[i]] * el->n0[perm[i]];
      hi = qe[i];
    }
  }
  PetscCall(PetscFree3(u, qe, perm));
  if (m->amin <= 0) m->amin = 0.1 * lo;
  if (m->amax <= 0) m->amax = 3 * hi;
  PetscCheck(m->amax > m->amin, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "Nonlinear modes: -nlm_amp_max %g must exceed -nlm_amp_min %g", (double)m->amax, (double)m->amin);
  PetscFunctionReturn(0);
}

/*
  JRNLModesSetUp - the harmonic balance (JRHBMSetUp), the stuck mode of interest (-nlm_mode among the elastic modes:
  stuck frequencies above 1e-4 of the highest), the EPMC system (JRHBMSetEPMC), the amplitude range and the corrector
*/
PetscErrorCode JRNLModesSetUp(JRNLModes m)
{
  PetscInt   nm, nf, ne = 0;
  PetscReal *f, fmax = 0;

  PetscFunctionBeginUser;
  if (m->setupcalled) PetscFunctionReturn(0);
  PetscCheck(m->hbm, m->comm, PETSC_ERR_ARG_WRONGSTATE, "JRNLModesSetHBM() first");
  PetscCall(JRHBMSetUp(m->hbm));
  PetscCall(JRHBMGetSizes(m->hbm, &nm, NULL, &m->n));
  PetscCall(PetscMalloc1(nm, &f));
  PetscCall(JRHBMStickFrequencies(m->hbm, &nf, f));
  for (PetscInt i = 0; i < nf; i++) fmax = PetscMax(fmax, f[i]);
  m->kmode = -1;
  for (PetscInt i = 0; i < nf && m->kmode < 0; i++)
    if (f[i] > 1e-4 * fmax && ++ne == m->mode) m->kmode = i;
  PetscCall(PetscFree(f));
  PetscCheck(m->kmode >= 0, m->comm, PETSC_ERR_ARG_OUTOFRANGE, "-nlm_mode %" PetscInt_FMT ": the stuck structure has %" PetscInt_FMT " elastic modes in the basis of %" PetscInt_FMT " modes (-hbm_modes)", m->mode, ne, nm);
  PetscCall(JRHBMSetEPMC(m->hbm, m->kmode, &m->w0));
  PetscCall(JRHBMGetEPMCMode(m->hbm, NULL, NULL, &m->xi0));
  if (m->amin <= 0 || m->amax <= 0) PetscCall(DefaultRange(m));
  PetscCall(JRHBMGetOutputs(m->hbm, &m->nout, NULL));
  m->N = m->n + 2;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, m->N, &m->y));
  PetscCall(VecDuplicate(m->y, &m->f));
  PetscCall(VecDuplicate(m->y, &m->xr));
  PetscCall(VecDuplicate(m->y, &m->rr));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, m->n, &m->a));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, m->N, m->N, NULL, &m->J));
  PetscCall(SNESCreate(PETSC_COMM_SELF, &m->snes));
  PetscCall(SNESSetOptionsPrefix(m->snes, m->prefix));
  PetscCall(SNESAppendOptionsPrefix(m->snes, "nlm_"));
  PetscCall(SNESSetFunction(m->snes, m->f, FormFunction, m));
  PetscCall(SNESSetJacobian(m->snes, m->J, m->J, FormJacobian, m));
  PetscCall(SNESSetType(m->snes, SNESNEWTONDENSE));
  PetscCall(SNESSetTolerances(m->snes, 1e-11, 1e-13, 1e-14, 40, 10000));
  PetscCall(SNESSetFromOptions(m->snes));
  if (m->arclength) {
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, m->N + 1, &m->z));
    PetscCall(VecDuplicate(m->z, &m->fz));
    PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, m->N, NULL, &m->yv));
    PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, m->N, NULL, &m->fv));
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, m->N + 1, m->N + 1, NULL, &m->Ja));
    PetscCall(PetscCalloc2(m->N + 1, &m->zp, m->N + 1, &m->tz));
    PetscCall(SNESCreate(PETSC_COMM_SELF, &m->snesa));
    PetscCall(SNESSetOptionsPrefix(m->snesa, m->prefix));
    PetscCall(SNESAppendOptionsPrefix(m->snesa, "nlm_"));
    PetscCall(SNESSetFunction(m->snesa, m->fz, FormFunctionArc, m));
    PetscCall(SNESSetJacobian(m->snesa, m->Ja, m->Ja, FormJacobianArc, m));
    PetscCall(SNESSetType(m->snesa, SNESNEWTONDENSE));
    PetscCall(SNESSetTolerances(m->snesa, 1e-11, 1e-13, 1e-14, 40, 10000));
    PetscCall(SNESSetFromOptions(m->snesa));
  }
  m->setupcalled = PETSC_TRUE;
  if (m->view) PetscCall(JRNLModesView(m, NULL));
  PetscFunctionReturn(0);
}

/* One corrector solve at the modal amplitude q from the guess in m->y; converged: SNES converged, residual finite */
static PetscErrorCode Correct(JRNLModes m, PetscReal q, PetscInt *its, PetscBool *converged)
{
  SNESConvergedReason reason;

  PetscFunctionBeginUser;
  m->q = q;
  PetscCall(SNESSolve(m->snes, NULL, m->y));
  PetscCall(SNESGetConvergedReason(m->snes, &reason));
  PetscCall(SNESGetIterationNumber(m->snes, its));
  *converged = reason > 0 ? PETSC_TRUE : PETSC_FALSE;
  if (*converged) { /* a positive frequency */
    const PetscScalar *ya;
    PetscCall(VecGetArrayRead(m->y, &ya));
    if (!(PetscRealPart(ya[m->n]) > 0.05)) *converged = PETSC_FALSE;
    PetscCall(VecRestoreArrayRead(m->y, &ya));
  }
  m->newton += *its;
  m->solves++;
  PetscFunctionReturn(0);
}

/* Room for cap points (the backbone's arrays grown, their contents kept) */
static PetscErrorCode Reserve(JRNLModes m, PetscInt cap)
{
  PetscReal *qs, *om, *xi, *amp, *as, *bal;
  PetscInt  *its;

  PetscFunctionBeginUser;
  if (cap <= m->cap) PetscFunctionReturn(0);
  PetscCall(PetscMalloc6(cap, &qs, cap, &om, cap, &xi, cap * m->nout, &amp, cap * m->n, &as, cap, &bal));
  PetscCall(PetscMalloc1(cap, &its));
  if (m->np) {
    PetscCall(PetscArraycpy(qs, m->qs, m->np));
    PetscCall(PetscArraycpy(om, m->omega, m->np));
    PetscCall(PetscArraycpy(xi, m->xi, m->np));
    PetscCall(PetscArraycpy(amp, m->amp, m->np * m->nout));
    PetscCall(PetscArraycpy(as, m->as, m->np * m->n));
    PetscCall(PetscArraycpy(bal, m->bal, m->np));
    PetscCall(PetscArraycpy(its, m->its, m->np));
  }
  PetscCall(PetscFree6(m->qs, m->omega, m->xi, m->amp, m->as, m->bal));
  PetscCall(PetscFree(m->its));
  m->qs    = qs;
  m->omega = om;
  m->xi    = xi;
  m->amp   = amp;
  m->as    = as;
  m->bal   = bal;
  m->its   = its;
  m->cap   = cap;
  PetscFunctionReturn(0);
}

/* The point just solved (m->y at m->q): stored, with its responses and its energy balance, and printed */
static PetscErrorCode Record(JRNLModes m, PetscInt its)
{
  const PetscScalar *ya;
  PetscScalar       *aa;
  const PetscInt     k = m->np, n = m->n;
  PetscReal          w, xi, ed, enl, win, exi;

  PetscFunctionBeginUser;
  if (m->np == m->cap) PetscCall(Reserve(m, PetscMax(2 * m->cap, m->npts)));
  PetscCall(VecGetArrayRead(m->y, &ya));
  PetscCall(VecGetArray(m->a, &aa));
  for (PetscInt i = 0; i < n; i++) aa[i] = m->q * ya[i];
  w  = m->w0 * PetscRealPart(ya[n]);
  xi = m->w0 * PetscRealPart(ya[n + 1]);
  PetscCall(VecRestoreArray(m->a, &aa));
  PetscCall(VecRestoreArrayRead(m->y, &ya));
  PetscCall(JRHBMEPMCWork(m->hbm, w, xi, m->a, &exi));
  m->qs[k]    = m->q;
  m->omega[k] = w;
  m->xi[k]    = xi;
  m->its[k]   = its;
  PetscCall(VecGetArrayRead(m->a, &ya));
  PetscCall(PetscArraycpy(m->as + k * n, ya, n));
  PetscCall(VecRestoreArrayRead(m->a, &ya));
  PetscCall(JRHBMResponse(m->hbm, m->a, NULL, m->amp + k * m->nout, NULL));
  PetscCall(JRHBMEnergy(m->hbm, w, m->a, &win, &ed, &enl));
  m->bal[k] = exi > 0 ? PetscAbsReal(exi - ed - enl) / exi : 0;
  m->np++;
  PetscCall(PetscPrintf(m->comm, "backbone point %" PetscInt_FMT " amplitude %.10e freq_hz %.10g damping_ratio %.8e xi %.6e amp_1 %.6e newton %" PetscInt_FMT "\n", k, (double)m->q, (double)(w / (2 * PETSC_PI)), (double)(xi / (2 * w)), (double)xi, (double)m->amp[k * m->nout], its));
  PetscFunctionReturn(0);
}

/*
  The backbone by pseudo-arclength from the first point y0 (at log q = lmin): steps h along the secant of the last two
  points in z = [y | log q] (the first along log q), at most the spacing of -nlm_points in log q and -nlm_step_max,
  each corrected on the plane t^T (z - zp) = 0 through the predictor zp; the last point is a natural solve at
  -nlm_amp_max. Every accepted point is recorded.
*/
static PetscErrorCode SolveArclength(JRNLModes m, const PetscReal y0[], PetscReal lmin, PetscReal lmax, PetscReal dln)
{
  const PetscInt  N1 = m->N + 1, maxpts = 50 * m->npts + 1000;
  const PetscReal hmax = PetscMin(dln, (lmax - lmin) / (m->npts - 1));
  PetscReal      *zk, *zq, h = hmax;
  PetscInt        cuts = 0, its, itp = 0;
  PetscBool       prev = PETSC_FALSE, ok;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(N1, &zk, N1, &zq));
  PetscCall(PetscArraycpy(zk, y0, m->N));
  zk[m->N] = lmin;
  while (zk[m->N] < lmax - 1e-12 * PetscMax(1, PetscAbsReal(lmax))) {
    PetscReal nt = 0;
    if (m->np >= maxpts) {
      m->complete = PETSC_FALSE;
      PetscCall(PetscPrintf(m->comm, "nlmodes: WARNING the backbone stops at amplitude %g after %" PetscInt_FMT " points without reaching -nlm_amp_max\n", (double)PetscExpReal(zk[m->N]), m->np));
      break;
    }
    for (PetscInt i = 0; i < N1; i++) { /* the unit tangent: the secant, or along log q at the start */
      m->tz[i] = prev ? zk[i] - zq[i] : (i == m->N ? 1.0 : 0.0);
      nt += m->tz[i] * m->tz[i];
    }
    nt = PetscSqrtReal(nt);
    for (PetscInt i = 0; i < N1; i++) {
      m->tz[i] /= nt;
      m->zp[i] = zk[i] + h * m->tz[i];
    }
    if (m->zp[m->N] >= lmax) { /* the end of the range: a natural solve at -nlm_amp_max from the predictor there */
      const PetscReal f = (lmax - zk[m->N]) / (m->zp[m->N] - zk[m->N]);
      PetscScalar    *ya;
      PetscCall(VecGetArray(m->y, &ya));
      for (PetscInt i = 0; i < m->N; i++) ya[i] = zk[i] + f * (m->zp[i] - zk[i]);
      PetscCall(VecRestoreArray(m->y, &ya));
      PetscCall(Correct(m, m->amax, &its, &ok));
      itp += its;
      if (ok) {
        PetscCall(Record(m, itp));
        break;
      }
    } else {
      PetscScalar        *za;
      SNESConvergedReason reason;
      PetscCall(VecGetArray(m->z, &za));
      for (PetscInt i = 0; i < N1; i++) za[i] = m->zp[i];
      PetscCall(VecRestoreArray(m->z, &za));
      PetscCall(SNESSolve(m->snesa, NULL, m->z));
      PetscCall(SNESGetConvergedReason(m->snesa, &reason));
      PetscCall(SNESGetIterationNumber(m->snesa, &its));
      m->newton += its;
      m->solves++;
      itp += its;
      PetscCall(VecGetArray(m->z, &za));
      ok = reason > 0 && PetscRealPart(za[m->n]) > 0.05 && PetscRealPart(za[m->N]) > lmin - 10 * dln ? PETSC_TRUE : PETSC_FALSE;
      if (ok) {
        PetscScalar *ya;
        PetscCall(PetscArraycpy(zq, zk, N1));
        for (PetscInt i = 0; i < N1; i++) zk[i] = PetscRealPart(za[i]);
        prev = PETSC_TRUE;
        m->q = PetscExpReal(zk[m->N]);
        PetscCall(VecGetArray(m->y, &ya));
        for (PetscInt i = 0; i < m->N; i++) ya[i] = zk[i];
        PetscCall(VecRestoreArray(m->y, &ya));
      }
      PetscCall(VecRestoreArray(m->z, &za));
      if (ok) {
        PetscCall(Record(m, itp));
        itp  = 0;
        cuts = 0;
        if (its <= 4) h = PetscMin(hmax, 1.5 * h);
        else if (its > 8) h *= 0.7;
        continue;
      }
    }
    h *= 0.5;
    if (++cuts > m->maxcuts) {
      m->complete = PETSC_FALSE;
      PetscCall(PetscPrintf(m->comm, "nlmodes: WARNING the backbone stops at amplitude %g: Newton failed %" PetscInt_FMT " times (-nlm_max_cuts)\n", (double)PetscExpReal(zk[m->N]), cuts));
      break;
    }
  }
  PetscCall(PetscFree2(zk, zq));
  PetscFunctionReturn(0);
}

/*
  JRNLModesSolve - the backbone from -nlm_amp_min to -nlm_amp_max, one line
  "backbone point <i> amplitude <q> freq_hz <f> damping_ratio <D> xi <xi> amp_1 <m> newton <its>" per point: by
  pseudo-arclength (-nlm_continuation arclength: at least -nlm_points points, every accepted one) or natural
  continuation (exactly the -nlm_points amplitudes). A point that cannot be reached after -nlm_max_cuts halvings of
  the step ends the backbone (JRNLModesGetStats: complete false). Collective.
*/
PetscErrorCode JRNLModesSolve(JRNLModes m)
{
  const PetscReal lmin = PetscLogReal(m->amin), lmax = PetscLogReal(m->amax), dln = m->dmax * PetscLogReal(10.0);
  PetscReal      *yp, *yq, lp = 0, lq = 0; /* the last two solutions (scaled) and their log q */
  PetscInt        have = 0, its;
  PetscBool       ok;
  PetscLogDouble  t0, t1;

  PetscFunctionBeginUser;
  PetscCall(JRNLModesSetUp(m));
  PetscCall(PetscLogEventBegin(JR_NLModesSolve, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  m->np       = 0;
  m->complete = PETSC_TRUE;
  m->newton = m->solves = 0;
  PetscCall(Reserve(m, m->npts));
  PetscCall(PetscMalloc2(m->N, &yp, m->N, &yq));
  { /* the linear mode: x = q psi sin(w0 t), xi = xi0 */
    const PetscReal *psi;
    PetscScalar     *ya;
    PetscInt         nm;
    PetscCall(JRHBMGetSizes(m->hbm, &nm, NULL, NULL));
    PetscCall(JRHBMGetEPMCMode(m->hbm, NULL, &psi, NULL));
    PetscCall(VecZeroEntries(m->y));
    PetscCall(VecGetArray(m->y, &ya));
    for (PetscInt i = 0; i < nm; i++) ya[nm + i] = psi[i];
    ya[m->n]     = 1.0;
    ya[m->n + 1] = m->xi0 / m->w0;
    PetscCall(VecRestoreArray(m->y, &ya));
  }
  PetscCall(Correct(m, m->amin, &its, &ok));
  PetscCheck(ok, m->comm, PETSC_ERR_NOT_CONVERGED, "Nonlinear modes: no solution at the smallest amplitude -nlm_amp_min %g from the linear mode (%g Hz); try a smaller -nlm_amp_min or -nlm_snes_max_it", (double)m->amin, (double)(m->w0 / (2 * PETSC_PI)));
  PetscCall(Record(m, its));
  {
    const PetscScalar *ya;
    PetscCall(VecGetArrayRead(m->y, &ya));
    for (PetscInt i = 0; i < m->N; i++) yq[i] = PetscRealPart(ya[i]);
    PetscCall(VecRestoreArrayRead(m->y, &ya));
    lq   = lmin;
    have = 1;
  }
  if (m->arclength) PetscCall(SolveArclength(m, yq, lmin, lmax, dln));
  else {
    for (PetscInt p = 1; p < m->npts && m->complete; p++) {
      const PetscReal target = lmin + (lmax - lmin) * p / (m->npts - 1);
      PetscReal       step   = PetscMin(dln, target - lq);
      PetscInt        cuts = 0, itp = 0;
      while (lq < target - 1e-14 * PetscMax(1, PetscAbsReal(target))) {
        const PetscReal ln = PetscMin(lq + step, target);
        PetscScalar    *ya;
        PetscCall(VecGetArray(m->y, &ya)); /* the secant predictor in log q (the last solution if only one) */
        for (PetscInt i = 0; i < m->N; i++) ya[i] = yq[i] + (have > 1 ? (ln - lq) * (yq[i] - yp[i]) / (lq - lp) : 0.0);
        PetscCall(VecRestoreArray(m->y, &ya));
        PetscCall(Correct(m, PetscExpReal(ln), &its, &ok));
        itp += its;
        if (ok) {
          const PetscScalar *yc;
          PetscCall(PetscArraycpy(yp, yq, m->N));
          lp = lq;
          PetscCall(VecGetArrayRead(m->y, &yc));
          for (PetscInt i = 0; i < m->N; i++) yq[i] = PetscRealPart(yc[i]);
          PetscCall(VecRestoreArrayRead(m->y, &yc));
          lq   = ln;
          have = 2;
          if (its <= 4) step = PetscMin(dln, 1.5 * step);
        } else if (++cuts > m->maxcuts) {
          m->complete = PETSC_FALSE;
          PetscCall(PetscPrintf(m->comm, "nlmodes: WARNING the backbone stops at amplitude %g: Newton failed %" PetscInt_FMT " times towards %g (-nlm_max_cuts)\n", (double)PetscExpReal(lq), cuts, (double)PetscExpReal(target)));
          break;
        } else step *= 0.5;
      }
      if (m->complete) PetscCall(Record(m, itp));
    }
  }
  PetscCall(PetscFree2(yp, yq));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscLogEventEnd(JR_NLModesSolve, 0, 0, 0, 0));
  m->seconds = t1 - t0;
  PetscFunctionReturn(0);
}

/* The backbone: np points, the modal amplitude q, omega [rad/s], xi [1/s], the responses' first-harmonic amplitudes
   (np x nout) [m] and the harmonics (np x n); any pointer may be NULL */
PetscErrorCode JRNLModesGetBackbone(JRNLModes m, PetscInt *np, const PetscReal **q, const PetscReal **omega, const PetscReal **xi, const PetscReal **amp, const PetscReal **a)
{
  PetscFunctionBeginUser;
  if (np) *np = m->np;
  if (q) *q = m->qs;
  if (omega) *omega = m->omega;
  if (xi) *xi = m->xi;
  if (amp) *amp = m->amp;
  if (a) *a = m->as;
  PetscFunctionReturn(0);
}

/* The solve's wall time [s], its Newton iterations, and whether the backbone reached -nlm_amp_max */
PetscErrorCode JRNLModesGetStats(JRNLModes m, PetscReal *seconds, PetscInt *newton, PetscBool *complete)
{
  PetscFunctionBeginUser;
  if (seconds) *seconds = m->seconds;
  if (newton) *newton = m->newton;
  if (complete) *complete = m->complete;
  PetscFunctionReturn(0);
}

/*
  JRNLModesInterpolate - the backbone at the modal amplitude q: omega [rad/s], xi [1/s] and the first-harmonic
  amplitude of response 1 [m] (any may be NULL), linear in log q between the two points around q (the first such
  pair along the backbone); inside: false (and nothing set) when q lies outside the computed points' range
*/
PetscErrorCode JRNLModesInterpolate(JRNLModes m, PetscReal q, PetscReal *omega, PetscReal *xi, PetscReal *amp1, PetscBool *inside)
{
  const PetscReal tol = 1e-12;

  PetscFunctionBeginUser;
  *inside = PETSC_FALSE;
  if (!m->np || !(q > 0)) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < m->np; k++) {
    PetscReal t;
    PetscInt  j = k;
    if (k + 1 < m->np) {
      const PetscReal lo = PetscMin(m->qs[k], m->qs[k + 1]), hi = PetscMax(m->qs[k], m->qs[k + 1]);
      if (q < lo * (1 - tol) || q > hi * (1 + tol)) continue;
      t = hi > lo ? (PetscLogReal(q) - PetscLogReal(m->qs[k])) / (PetscLogReal(m->qs[k + 1]) - PetscLogReal(m->qs[k])) : 0;
      t = PetscMin(1, PetscMax(0, t));
      j = k + 1;
    } else {
      if (PetscAbsReal(q / m->qs[k] - 1) > tol) continue; /* a backbone of one point */
      t = 0;
    }
    if (omega) *omega = m->omega[k] + t * (m->omega[j] - m->omega[k]);
    if (xi) *xi = m->xi[k] + t * (m->xi[j] - m->xi[k]);
    if (amp1) *amp1 = m->amp[k * m->nout] + t * (m->amp[j * m->nout] - m->amp[k * m->nout]);
    *inside = PETSC_TRUE;
    break;
  }
  PetscFunctionReturn(0);
}

/* BASE.csv: point,q,omega_rad_s,freq_hz,damping_ratio,xi,amp_1..amp_n,newton,balance */
static PetscErrorCode WriteCSV(JRNLModes m, const char csv[])
{
  char  tmp[PETSC_MAX_PATH_LEN + 32];
  FILE *fp;

  PetscFunctionBeginUser;
  PetscCall(JRFileOpenTemp(m->comm, csv, &fp, tmp, sizeof(tmp)));
  if (fp) {
    fprintf(fp, "point,q,omega_rad_s,freq_hz,damping_ratio,xi");
    for (PetscInt o = 0; o < m->nout; o++) fprintf(fp, ",amp_%" PetscInt_FMT, o + 1);
    fprintf(fp, ",newton,balance\n");
    for (PetscInt k = 0; k < m->np; k++) {
      fprintf(fp, "%" PetscInt_FMT ",%.12e,%.12g,%.12g,%.10e,%.10e", k, (double)m->qs[k], (double)m->omega[k], (double)(m->omega[k] / (2 * PETSC_PI)), (double)(m->xi[k] / (2 * m->omega[k])), (double)m->xi[k]);
      for (PetscInt o = 0; o < m->nout; o++) fprintf(fp, ",%.10e", (double)m->amp[k * m->nout + o]);
      fprintf(fp, ",%" PetscInt_FMT ",%.3e\n", m->its[k], (double)m->bal[k]);
    }
  }
  PetscCall(JRFileCommit(m->comm, &fp, tmp, csv));
  PetscFunctionReturn(0);
}

/* BASE.h5: the root's attributes (options, units, the mode) and the backbone's datasets */
static PetscErrorCode WriteHDF5(JRNLModes m, const char h5[])
{
  char        tmp[PETSC_MAX_PATH_LEN + 32], *opts;
  PetscViewer v;
  PetscReal  *f, *d, f0 = m->w0 / (2 * PETSC_PI), d0 = m->xi0 / (2 * m->w0);
  PetscInt    nm, H;
  const char *damping;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetSizes(m->hbm, &nm, &H, NULL));
  PetscCall(JRHBMGetDampingDescription(m->hbm, &damping));
  PetscCall(JRFileTempName(m->comm, h5, tmp, sizeof(tmp)));
  PetscCall(PetscViewerHDF5Open(m->comm, tmp, FILE_MODE_WRITE, &v));
  PetscCall(PetscOptionsGetAll(NULL, &opts));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "options", PETSC_STRING, opts));
  PetscCall(PetscFree(opts));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "method", PETSC_STRING, "extended periodic motion concept (Krack 2015): harmonic balance of the free motion with the negative damping -xi M; damping_ratio = xi / (2 omega)"));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "units", PETSC_STRING, "SI: q modal amplitude of the mass-normalised stuck mode [m kg^1/2], omega rad/s, freq_hz Hz, xi 1/s, amp m (first harmonic at each response)"));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "damping", PETSC_STRING, damping));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "harmonics", PETSC_INT, &H));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "modes", PETSC_INT, &nm));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "mode_elastic", PETSC_INT, &m->mode));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "mode_index", PETSC_INT, &m->kmode));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "stuck_freq_hz", PETSC_REAL, &f0));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "stuck_damping_ratio", PETSC_REAL, &d0));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "complete", PETSC_BOOL, &m->complete));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "layout_a", PETSC_STRING, "per point: [a0 | as_1 ac_1 | ... | as_H ac_H], each block over the modes"));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "balance", PETSC_STRING, "per point: |W_xi - W_damping - W_contact| / W_xi, the work of the negative damping per cycle against the dissipated energy"));
  PetscCall(PetscMalloc2(m->np, &f, m->np, &d));
  for (PetscInt k = 0; k < m->np; k++) {
    f[k] = m->omega[k] / (2 * PETSC_PI);
    d[k] = m->xi[k] / (2 * m->omega[k]);
  }
  PetscCall(JRViewerHDF5WriteRank0(m->comm, v, "q", m->np, 1, m->qs, NULL));
  PetscCall(JRViewerHDF5WriteRank0(m->comm, v, "omega", m->np, 1, m->omega, NULL));
  PetscCall(JRViewerHDF5WriteRank0(m->comm, v, "freq_hz", m->np, 1, f, NULL));
  PetscCall(JRViewerHDF5WriteRank0(m->comm, v, "damping_ratio", m->np, 1, d, NULL));
  PetscCall(JRViewerHDF5WriteRank0(m->comm, v, "xi", m->np, 1, m->xi, NULL));
  PetscCall(JRViewerHDF5WriteRank0(m->comm, v, "amp", m->np * m->nout, m->nout, m->amp, NULL));
  PetscCall(JRViewerHDF5WriteRank0(m->comm, v, "a", m->np * m->n, m->n, m->as, NULL));
  PetscCall(JRViewerHDF5WriteRank0(m->comm, v, "balance", m->np, 1, m->bal, NULL));
  PetscCall(JRViewerHDF5WriteRank0(m->comm, v, "newton_its", m->np, 1, NULL, m->its));
  PetscCall(PetscFree2(f, d));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(JRFileRename(m->comm, tmp, h5));
  PetscFunctionReturn(0);
}

/*
  JRNLModesWrite - BASE.h5 (every point: q, omega, freq_hz, damping_ratio, xi, amp, a, balance, newton_its), BASE.csv
  and BASE.png (share/plot_backbone.gp: frequency and damping ratio against the amplitude of response 1); BASE is
  -nlm_output_file ('' writes nothing), -nlm_plot 0 leaves out the PNG
*/
PetscErrorCode JRNLModesWrite(JRNLModes m)
{
  char      h5[PETSC_MAX_PATH_LEN + 8], csv[PETSC_MAX_PATH_LEN + 8], png[PETSC_MAX_PATH_LEN + 8];
  PetscBool made = PETSC_FALSE;

  PetscFunctionBeginUser;
  if (!m->out[0] || !m->np) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(h5, sizeof(h5), "%s.h5", m->out));
  PetscCall(PetscSNPrintf(csv, sizeof(csv), "%s.csv", m->out));
  PetscCall(PetscSNPrintf(png, sizeof(png), "%s.png", m->out));
  PetscCall(WriteCSV(m, csv));
  PetscCall(WriteHDF5(m, h5));
  if (m->plot) {
    char     vars[3 * PETSC_MAX_PATH_LEN];
    PetscInt H;
    PetscCall(JRHBMGetSizes(m->hbm, NULL, &H, NULL));
    PetscCall(PetscSNPrintf(vars, sizeof(vars), "data='%s'; ttl='nonlinear mode: elastic stuck mode %" PetscInt_FMT " (%.5g Hz stuck), EPMC, H = %" PetscInt_FMT "'", csv, m->mode, (double)(m->w0 / (2 * PETSC_PI)), H));
    PetscCall(JRPlot(m->comm, "plot_backbone.gp", png, vars, &made));
  }
  PetscCall(PetscPrintf(m->comm, "nlmodes: wrote %s, %s%s%s\n", h5, csv, made ? ", " : "", made ? png : ""));
  PetscFunctionReturn(0);
}

/* The mode followed, its linear limit, the range and the corrector; after a solve, the backbone's ranges */
PetscErrorCode JRNLModesView(JRNLModes m, PetscViewer viewer)
{
  PetscFunctionBeginUser;
  if (!viewer) viewer = PETSC_VIEWER_STDOUT_(m->comm);
  if (!m->np) PetscCall(PetscViewerASCIIPrintf(viewer, "nlmodes: elastic stuck mode %" PetscInt_FMT " (mode %" PetscInt_FMT " of the basis): %.8g Hz, linear damping ratio %.6e; modal amplitude %g .. %g, %" PetscInt_FMT " points, steps <= %g decades\n", m->mode, m->kmode, (double)(m->w0 / (2 * PETSC_PI)), (double)(m->xi0 / (2 * m->w0)), (double)m->amin, (double)m->amax, m->npts, (double)m->dmax));
  if (m->np) {
    PetscReal fl = PETSC_MAX_REAL, fh = 0, dl = PETSC_MAX_REAL, dh = 0;
    for (PetscInt k = 0; k < m->np; k++) {
      const PetscReal f = m->omega[k] / (2 * PETSC_PI), d = m->xi[k] / (2 * m->omega[k]);
      fl = PetscMin(fl, f);
      fh = PetscMax(fh, f);
      dl = PetscMin(dl, d);
      dh = PetscMax(dh, d);
    }
    PetscCall(PetscViewerASCIIPrintf(viewer, "nlmodes: %" PetscInt_FMT " points%s, frequency %.6g .. %.6g Hz, damping ratio %.4e .. %.4e, %" PetscInt_FMT " solves, %" PetscInt_FMT " Newton iterations, %.3g s\n", m->np, m->complete ? "" : " (incomplete)", (double)fl, (double)fh, (double)dl, (double)dh, m->solves, m->newton, (double)m->seconds));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode JRNLModesDestroy(JRNLModes *nlm)
{
  JRNLModes m = *nlm;

  PetscFunctionBeginUser;
  if (!m) PetscFunctionReturn(0);
  PetscCall(SNESDestroy(&m->snes));
  PetscCall(VecDestroy(&m->y));
  PetscCall(VecDestroy(&m->f));
  PetscCall(VecDestroy(&m->xr));
  PetscCall(VecDestroy(&m->rr));
  PetscCall(VecDestroy(&m->a));
  PetscCall(MatDestroy(&m->J));
  PetscCall(SNESDestroy(&m->snesa));
  PetscCall(VecDestroy(&m->z));
  PetscCall(VecDestroy(&m->fz));
  PetscCall(VecDestroy(&m->yv));
  PetscCall(VecDestroy(&m->fv));
  PetscCall(MatDestroy(&m->Ja));
  PetscCall(PetscFree2(m->zp, m->tz));
  PetscCall(PetscFree6(m->qs, m->omega, m->xi, m->amp, m->as, m->bal));
  PetscCall(PetscFree(m->its));
  PetscCall(PetscFree(m));
  *nlm = NULL;
  PetscFunctionReturn(0);
}
