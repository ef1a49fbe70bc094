/*
   JRContact: a batch of friction contact elements of one registered type, evaluated for many
   motions at once (structure-of-arrays), with the force harmonics, their analytic derivatives,
   and each element's contact state over the cycle.
*/
#include <jointrom/private/contactimpl.h>

PetscFunctionList JRContactList              = NULL;
static PetscBool  JRContactRegisterAllCalled = PETSC_FALSE;

const char *const JRContactMethods[] = {"analytic", "aft", "JRContactMethod", "JR_CONTACT_", NULL};
const char *const JRContactStates[]  = {"full_stick", "stick_slip", "separation_stick_slip", "full_separation", "JRContactState", "JR_CONTACT_", NULL};
const char *const JRContactSequences[] = {"full_separation", "P1", "P2", "P3", "N1", "N2", "N3", "E1", "E2", "E3", "E4", "slip_no_separation", "full_stick", "other", "JRContactSequence", "JR_SEQ_", NULL};

/* Register a contact element type: name and the function that fills its ops */
PetscErrorCode JRContactRegister(const char name[], PetscErrorCode (*create)(JRContact))
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListAdd(&JRContactList, name, create));
  PetscFunctionReturn(0);
}

/* Register the built-in types once */
PetscErrorCode JRContactRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (JRContactRegisterAllCalled) PetscFunctionReturn(0);
  JRContactRegisterAllCalled = PETSC_TRUE;
  PetscCall(JRContactRegister(JRCONTACTJENKINS, JRContactCreate_Jenkins));
  PetscCall(JRContactRegister(JRCONTACTJENKINSNV, JRContactCreate_JenkinsNV));
  PetscCall(JRContactRegister(JRCONTACTCUBIC, JRContactCreate_Cubic));
  PetscFunctionReturn(0);
}

PetscErrorCode JRContactRegisterAllReset(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&JRContactList));
  JRContactRegisterAllCalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Create an empty contact batch: one harmonic (analytic path), 64 AFT samples, no elements */
PetscErrorCode JRContactCreate(MPI_Comm comm, JRContact *contact)
{
  JRContact c;

  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(PetscNew(&c));
  c->comm   = comm;
  c->H      = 1;
  c->N      = 64;
  c->nc     = 3;
  c->method = JR_CONTACT_ANALYTIC;
  *contact  = c;
  PetscFunctionReturn(0);
}

static PetscErrorCode JRContactReset(JRContact c)
{
  PetscFunctionBeginUser;
  PetscCall(JRAFTDestroy(&c->aft));
  c->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Set the element type (jenkins, jenkins_nv, or a registered one); -contact_type */
PetscErrorCode JRContactSetType(JRContact c, JRContactType type)
{
  PetscErrorCode (*create)(JRContact) = NULL;
  PetscBool match;

  PetscFunctionBeginUser;
  PetscCall(JRContactRegisterAll());
  PetscCall(PetscStrcmp(c->type_name, type, &match));
  if (match) PetscFunctionReturn(0);
  PetscCall(PetscFunctionListFind(JRContactList, type, &create));
  PetscCheck(create, c->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Unknown contact element type '%s' (-contact_type): the types are jenkins (constant normal load), jenkins_nv (normal load variation) and cubic (spring kt u^3)", type);
  if (c->ops->destroy) PetscCall((*c->ops->destroy)(c));
  PetscCall(PetscMemzero(c->ops, sizeof(struct _JRContactOps)));
  c->data      = NULL;
  c->signed_kt = PETSC_FALSE;
  PetscCall(JRContactReset(c));
  PetscCall(PetscStrncpy(c->type_name, type, sizeof(c->type_name)));
  PetscCall((*create)(c));
  PetscFunctionReturn(0);
}

PetscErrorCode JRContactGetType(JRContact c, JRContactType *type)
{
  PetscFunctionBeginUser;
  *type = c->type_name[0] ? c->type_name : NULL;
  PetscFunctionReturn(0);
}

PetscErrorCode JRContactSetOptionsPrefix(JRContact c, const char prefix[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(c->prefix));
  if (prefix) PetscCall(PetscStrallocpy(prefix, &c->prefix));
  PetscFunctionReturn(0);
}

/* Number of harmonics H (plus the mean) and time samples N per cycle for the AFT path (N >= 2H+1) */
PetscErrorCode JRContactSetHarmonics(JRContact c, PetscInt H, PetscInt N)
{
  PetscFunctionBeginUser;
  PetscCheck(H >= 1 && H <= JR_MAX_HARMONICS, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Number of harmonics H = %" PetscInt_FMT " must be between 1 and %d", H, JR_MAX_HARMONICS);
  PetscCheck(N >= 2 * H + 1, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Number of time samples per cycle N = %" PetscInt_FMT " must be at least 2H+1 = %" PetscInt_FMT " for H = %" PetscInt_FMT " harmonics", N, 2 * H + 1, H);
  if (H != c->H || N != c->N) PetscCall(JRContactReset(c));
  c->H  = H;
  c->N  = N;
  c->nc = 2 * H + 1;
  PetscFunctionReturn(0);
}

PetscErrorCode JRContactGetHarmonics(JRContact c, PetscInt *H, PetscInt *N, PetscInt *nc)
{
  PetscFunctionBeginUser;
  if (H) *H = c->H;
  if (N) *N = c->N;
  if (nc) *nc = c->nc;
  PetscFunctionReturn(0);
}

/* Evaluation path: JR_CONTACT_ANALYTIC (closed form, H = 1) or JR_CONTACT_AFT; -contact_method */
PetscErrorCode JRContactSetMethod(JRContact c, JRContactMethod method)
{
  PetscFunctionBeginUser;
  if (method != c->method) PetscCall(JRContactReset(c));
  c->method     = method;
  c->method_set = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode JRContactGetMethod(JRContact c, JRContactMethod *method)
{
  PetscFunctionBeginUser;
  *method = c->method;
  PetscFunctionReturn(0);
}

/* Does the element type use the normal motion v (and produce a varying normal load)? */
PetscErrorCode JRContactUsesNormal(JRContact c, PetscBool *normal)
{
  PetscFunctionBeginUser;
  PetscCheck(c->type_name[0], c->comm, PETSC_ERR_ARG_WRONGSTATE, "Set the contact type first (JRContactSetType or -contact_type)");
  *normal = c->normal;
  PetscFunctionReturn(0);
}

/* Copy the parameters of n elements (SoA): kt [N/m], kn [N/m] (NULL: 0), mu [-], n0 [N] */
PetscErrorCode JRContactSetElements(JRContact c, PetscInt n, const PetscReal kt[], const PetscReal kn[], const PetscReal mu[], const PetscReal n0[])
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 0, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Number of elements %" PetscInt_FMT " must be non-negative", n);
  PetscCall(PetscFree4(c->kt, c->kn, c->mu, c->n0));
  PetscCall(PetscMalloc4(n, &c->kt, n, &c->kn, n, &c->mu, n, &c->n0));
  c->n = n;
  if (n) {
    PetscCall(PetscArraycpy(c->kt, kt, n));
    if (kn) PetscCall(PetscArraycpy(c->kn, kn, n));
    else PetscCall(PetscArrayzero(c->kn, n));
    PetscCall(PetscArraycpy(c->mu, mu, n));
    PetscCall(PetscArraycpy(c->n0, n0, n));
  }
  c->setupcalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode JRContactGetElements(JRContact c, PetscInt *n, const PetscReal **kt, const PetscReal **kn, const PetscReal **mu, const PetscReal **n0)
{
  PetscFunctionBeginUser;
  if (n) *n = c->n;
  if (kt) *kt = c->kt;
  if (kn) *kn = c->kn;
  if (mu) *mu = c->mu;
  if (n0) *n0 = c->n0;
  PetscFunctionReturn(0);
}

/* Options: -contact_type jenkins|jenkins_nv, -contact_method analytic|aft, -contact_view */
PetscErrorCode JRContactSetFromOptions(JRContact c)
{
  char      type[64];
  PetscBool flg;
  PetscInt  method = c->method;

  PetscFunctionBeginUser;
  PetscCall(JRContactRegisterAll());
  PetscOptionsBegin(c->comm, c->prefix, "Friction contact elements (thesis chapter 3)", "JRContact");
  PetscCall(PetscOptionsFList("-contact_type", "Contact element type: jenkins (constant normal load), jenkins_nv (normal load variation), cubic (spring kt u^3)", "JRContactSetType", JRContactList, c->type_name[0] ? c->type_name : JRCONTACTJENKINS, type, sizeof(type), &flg));
  if (flg) PetscCall(JRContactSetType(c, type));
  else if (!c->type_name[0]) PetscCall(JRContactSetType(c, JRCONTACTJENKINS));
  PetscCall(PetscOptionsEList("-contact_method", "Evaluation path: analytic (closed form, 1 harmonic) or aft (alternating frequency-time)", "JRContactSetMethod", JRContactMethods, 2, JRContactMethods[c->method], &method, &flg));
  if (flg) PetscCall(JRContactSetMethod(c, (JRContactMethod)method));
  PetscCall(PetscOptionsBool("-contact_view", "Print the element batch (type, path, counts per rank, parameter ranges) at set-up", "JRContactView", c->view, &c->view, NULL));
  if (c->ops->setfromoptions) PetscCall((*c->ops->setfromoptions)(c, PetscOptionsObject));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

static PetscErrorCode JRContactValidate(JRContact c)
{
  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < c->n; e++) {
    PetscCheck(PetscIsNormalReal(c->kt[e]) && (c->kt[e] > 0.0 || c->signed_kt), c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Contact element %" PetscInt_FMT ": tangential stiffness kt = %g N/m must be positive and finite", e, (double)c->kt[e]);
    PetscCheck(!PetscIsInfOrNanReal(c->kn[e]) && c->kn[e] >= 0.0, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Contact element %" PetscInt_FMT ": normal stiffness kn = %g N/m must be non-negative and finite", e, (double)c->kn[e]);
    PetscCheck(!PetscIsInfOrNanReal(c->mu[e]) && c->mu[e] >= 0.0, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Contact element %" PetscInt_FMT ": friction coefficient mu = %g must be non-negative and finite", e, (double)c->mu[e]);
    PetscCheck(!PetscIsInfOrNanReal(c->n0[e]), c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Contact element %" PetscInt_FMT ": normal load n0 = %g N must be finite", e, (double)c->n0[e]);
    PetscCheck(c->normal || c->n0[e] >= 0.0, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Contact element %" PetscInt_FMT ": normal load n0 = %g N must be non-negative for the jenkins element (use jenkins_nv for gaps)", e, (double)c->n0[e]);
  }
  PetscFunctionReturn(0);
}

/* Check the parameters and build the AFT tables; a second call does nothing */
PetscErrorCode JRContactSetUp(JRContact c)
{
  PetscFunctionBeginUser;
  if (c->setupcalled) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(JR_ContactSetUp, 0, 0, 0, 0));
  if (!c->type_name[0]) PetscCall(JRContactSetType(c, JRCONTACTJENKINS));
  if (!c->method_set) c->method = c->H == 1 ? JR_CONTACT_ANALYTIC : JR_CONTACT_AFT;
  PetscCheck(c->method != JR_CONTACT_ANALYTIC || c->H == 1, c->comm, PETSC_ERR_ARG_INCOMP, "The analytic path (-contact_method analytic) is single-harmonic: H = %" PetscInt_FMT " needs -contact_method aft", c->H);
  PetscCall(JRContactValidate(c));
  if (c->method == JR_CONTACT_AFT && !c->aft) PetscCall(JRAFTCreate(c->H, c->N, &c->aft));
  if (c->ops->setup) PetscCall((*c->ops->setup)(c));
  c->setupcalled = PETSC_TRUE;
  PetscCall(PetscLogEventEnd(JR_ContactSetUp, 0, 0, 0, 0));
  if (c->view) PetscCall(JRContactView(c, NULL));
  PetscFunctionReturn(0);
}

/*
  JRContactEvaluate - evaluate every element of the batch for its own motion.

  Input (SoA, coefficient-major, nc = 2H+1): U[k*n+e] tangential motion harmonics [m];
  V[k*n+e] normal motion harmonics (jenkins_nv only; NULL for jenkins).
  Output (any may be NULL): F[k*n+e] tangential force harmonics [N]; N[k*n+e] normal load
  harmonics [N]; dFdU, dFdV, dNdV[(k*nc+m)*n+e] derivatives [N/m]; state[e] contact state.
*/
PetscErrorCode JRContactEvaluate(JRContact c, const PetscReal U[], const PetscReal V[], PetscReal F[], PetscReal N[], PetscReal dFdU[], PetscReal dFdV[], PetscReal dNdV[], JRContactState state[])
{
  PetscFunctionBeginUser;
  PetscCall(JRContactSetUp(c));
  PetscCheck(!c->normal || V || !c->n, c->comm, PETSC_ERR_ARG_NULL, "Contact type %s needs the normal motion V", c->type_name);
  PetscCall(PetscLogEventBegin(JR_ContactEval, 0, 0, 0, 0));
  PetscCall((*c->ops->evaluate)(c, 0, c->n, U, V, F, N, dFdU, dFdV, dNdV, state));
  PetscCall(PetscLogEventEnd(JR_ContactEval, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The single-harmonic motion sequence of every element (section 3.3); needs H = 1.
   jenkins elements are classified as jenkins_nv with kn = 0. */
PetscErrorCode JRContactGetSequences(JRContact c, const PetscReal U[], const PetscReal V[], JRContactSequence seq[])
{
  const PetscInt n = c->n;
  PetscReal      Ue[3], Ve[3] = {0, 0, 0};
  JRElementOut   out;

  PetscFunctionBeginUser;
  PetscCall(JRContactSetUp(c));
  PetscCheck(c->nc == 3, c->comm, PETSC_ERR_ARG_WRONGSTATE, "Motion sequences are defined for single-harmonic motion (H = 1), not H = %" PetscInt_FMT, c->H);
  PetscCall(PetscMemzero(&out, sizeof(out)));
  for (PetscInt e = 0; e < n; e++) {
    for (PetscInt k = 0; k < 3; k++) {
      Ue[k] = U[k * n + e];
      if (c->normal) Ve[k] = V[k * n + e];
    }
    PetscCheck(!JRJenkinsNVAnalytic(c->kt[e], c->normal ? c->kn[e] : 0.0, c->mu[e], c->n0[e], Ue, Ve, &out, &seq[e]), c->comm, PETSC_ERR_PLIB, "Element %" PetscInt_FMT ": too many transitions in one cycle", e);
  }
  PetscFunctionReturn(0);
}

#define JR_CHUNK 8

#if defined(__SSE2__)
  #include <emmintrin.h>
#endif

/* dst[0..m) = src[l*stride], l < m. A full chunk going to a whole cache line (64-byte aligned) is
   written with non-temporal stores: the SoA rows of a large batch are written once and not read back
   soon, so streaming them saves reading each line before overwriting it (half the memory traffic).
   Rows that straddle lines are written normally (partial-line streaming is slower, not faster);
   allocate large outputs with JRMallocAligned to get the benefit. */
static inline void WriteRow(PetscReal *restrict dst, const PetscReal *restrict src, PetscInt stride, PetscInt m)
{
#if defined(__SSE2__)
  if (m == JR_CHUNK && !((uintptr_t)dst & 63)) {
    for (PetscInt l = 0; l < JR_CHUNK; l += 2) _mm_stream_pd(dst + l, _mm_set_pd(src[(l + 1) * stride], src[l * stride]));
    return;
  }
#endif
  for (PetscInt l = 0; l < m; l++) dst[l] = src[l * stride];
}

/*
  JRContactEvaluateChunked - batch evaluation through the type's single-element kernel (ops->element):
  elements are taken JR_CHUNK at a time, their motions gathered, their dense outputs collected and
  then written to the SoA arrays row by row, JR_CHUNK consecutive values (a cache line) at a time.
*/
PetscErrorCode JRContactEvaluateChunked(JRContact c, PetscInt start, PetscInt end, const PetscReal U[], const PetscReal V[], PetscReal F[], PetscReal N[], PetscReal dFdU[], PetscReal dFdV[], PetscReal dNdV[], JRContactState state[])
{
  const PetscInt n = c->n, nc = c->nc, nc2 = nc * nc;
  PetscReal     *Ue, *Ve, *Fc, *Nc, *DUc, *DVc, *DNc;
  JRElementOut   out;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc7(nc, &Ue, nc, &Ve, JR_CHUNK * nc, &Fc, JR_CHUNK * nc, &Nc, JR_CHUNK * nc2, &DUc, JR_CHUNK * nc2, &DVc, JR_CHUNK * nc2, &DNc));
  for (PetscInt e0 = start; e0 < end; e0 += JR_CHUNK) {
    const PetscInt m = PetscMin(JR_CHUNK, end - e0);
    for (PetscInt l = 0; l < m; l++) {
      const PetscInt e = e0 + l;
      for (PetscInt k = 0; k < nc; k++) Ue[k] = U[k * n + e];
      if (c->normal)
        for (PetscInt k = 0; k < nc; k++) Ve[k] = V[k * n + e];
      out.F    = F ? Fc + l * nc : NULL;
      out.N    = N ? Nc + l * nc : NULL;
      out.dFdU = dFdU ? DUc + l * nc2 : NULL;
      out.dFdV = dFdV ? DVc + l * nc2 : NULL;
      out.dNdV = dNdV ? DNc + l * nc2 : NULL;
      PetscCall((*c->ops->element)(c, e, Ue, c->normal ? Ve : NULL, &out));
      if (state) state[e] = out.state;
    }
    if (F)
      for (PetscInt k = 0; k < nc; k++) WriteRow(F + k * n + e0, Fc + k, nc, m);
    if (N)
      for (PetscInt k = 0; k < nc; k++) WriteRow(N + k * n + e0, Nc + k, nc, m);
    if (dFdU)
      for (PetscInt k = 0; k < nc2; k++) WriteRow(dFdU + k * n + e0, DUc + k, nc2, m);
    if (dFdV)
      for (PetscInt k = 0; k < nc2; k++) WriteRow(dFdV + k * n + e0, DVc + k, nc2, m);
    if (dNdV)
      for (PetscInt k = 0; k < nc2; k++) WriteRow(dNdV + k * n + e0, DNc + k, nc2, m);
  }
#if defined(__SSE2__)
  _mm_sfence(); /* order the streamed stores before anyone reads the outputs */
#endif
  PetscCall(PetscFree7(Ue, Ve, Fc, Nc, DUc, DVc, DNc));
  PetscFunctionReturn(0);
}

/* Print the type, path, harmonics and the element parameter ranges (collective) */
PetscErrorCode JRContactView(JRContact c, PetscViewer viewer)
{
  PetscBool   iascii;
  PetscReal   lmin[4] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, lmax[4], gmin[4], gmax[4];
  PetscInt    ntot, nmin, nmax;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(c->comm, &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (!iascii) PetscFunctionReturn(0);
  for (int i = 0; i < 4; i++) lmax[i] = -PETSC_MAX_REAL;
  for (PetscInt e = 0; e < c->n; e++) {
    const PetscReal p[4] = {c->kt[e], c->kn[e], c->mu[e], c->n0[e]};
    for (int i = 0; i < 4; i++) {
      lmin[i] = PetscMin(lmin[i], p[i]);
      lmax[i] = PetscMax(lmax[i], p[i]);
    }
  }
  PetscCall(MPIU_Allreduce(lmin, gmin, 4, MPIU_REAL, MPIU_MIN, c->comm));
  PetscCall(MPIU_Allreduce(lmax, gmax, 4, MPIU_REAL, MPIU_MAX, c->comm));
  PetscCall(MPIU_Allreduce(&c->n, &ntot, 1, MPIU_INT, MPI_SUM, c->comm));
  PetscCall(MPIU_Allreduce(&c->n, &nmin, 1, MPIU_INT, MPI_MIN, c->comm));
  PetscCall(MPIU_Allreduce(&c->n, &nmax, 1, MPIU_INT, MPI_MAX, c->comm));
  PetscCallMPI(MPI_Comm_size(c->comm, &size));
  PetscCall(PetscViewerASCIIPrintf(viewer, "JRContact: type %s, %s path, H = %" PetscInt_FMT " harmonics", c->type_name[0] ? c->type_name : "(not set)", JRContactMethods[c->method], c->H));
  if (c->method == JR_CONTACT_AFT) PetscCall(PetscViewerASCIIPrintf(viewer, ", N = %" PetscInt_FMT " samples per cycle", c->N));
  PetscCall(PetscViewerASCIIPrintf(viewer, "\n  elements: %" PetscInt_FMT " on %d rank(s) (%" PetscInt_FMT " to %" PetscInt_FMT " per rank)\n", ntot, size, nmin, nmax));
  if (ntot) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "  kt %g .. %g N/m, mu %g .. %g, n0 %g .. %g N", (double)gmin[0], (double)gmax[0], (double)gmin[2], (double)gmax[2], (double)gmin[3], (double)gmax[3]));
    if (c->normal) PetscCall(PetscViewerASCIIPrintf(viewer, ", kn %g .. %g N/m", (double)gmin[1], (double)gmax[1]));
    PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
  }
  if (c->ops->view) PetscCall((*c->ops->view)(c, viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode JRContactDestroy(JRContact *contact)
{
  JRContact c = *contact;

  PetscFunctionBeginUser;
  if (!c) PetscFunctionReturn(0);
  if (c->ops->destroy) PetscCall((*c->ops->destroy)(c));
  PetscCall(JRAFTDestroy(&c->aft));
  PetscCall(PetscFree4(c->kt, c->kn, c->mu, c->n0));
  PetscCall(PetscFree(c->prefix));
  PetscCall(PetscFree(c));
  *contact = NULL;
  PetscFunctionReturn(0);
}

/*
  JRContactEvaluateJoint - a joint: the elements members[0..m-1] (NULL: all) in parallel, sharing
  one motion U, V (nc each); its force is the sum of theirs (4.1)-(4.2), (5.2)-(5.5).
  Outputs dense: F[nc], N[nc], dFdU[nc*nc] row-major (any may be NULL); state: full stick or full
  separation if every member is, separation with stick-slip if any member separates, else stick-slip.
*/
PetscErrorCode JRContactEvaluateJoint(JRContact c, PetscInt m, const PetscInt members[], const PetscReal U[], const PetscReal V[], PetscReal F[], PetscReal N[], PetscReal dFdU[], PetscReal dFdV[], PetscReal dNdV[], JRContactState *state)
{
  const PetscInt nc = c->nc, nc2 = nc * nc, cnt = members ? m : c->n;
  PetscReal     *Fe, *Ne, *DU, *DV, *DN;
  JRElementOut   out;
  PetscInt       nstick = 0, nsep = 0, npart = 0;

  PetscFunctionBeginUser;
  PetscCall(JRContactSetUp(c));
  PetscCheck(!c->normal || V, c->comm, PETSC_ERR_ARG_NULL, "Contact type %s needs the normal motion V", c->type_name);
  PetscCall(PetscMalloc5(nc, &Fe, nc, &Ne, nc2, &DU, nc2, &DV, nc2, &DN));
  out.F    = Fe;
  out.N    = Ne;
  out.dFdU = dFdU ? DU : NULL;
  out.dFdV = dFdV ? DV : NULL;
  out.dNdV = dNdV ? DN : NULL;
  if (F) PetscCall(PetscArrayzero(F, nc));
  if (N) PetscCall(PetscArrayzero(N, nc));
  if (dFdU) PetscCall(PetscArrayzero(dFdU, nc2));
  if (dFdV) PetscCall(PetscArrayzero(dFdV, nc2));
  if (dNdV) PetscCall(PetscArrayzero(dNdV, nc2));
  PetscCall(PetscLogEventBegin(JR_ContactEval, 0, 0, 0, 0));
  for (PetscInt i = 0; i < cnt; i++) {
    const PetscInt e = members ? members[i] : i;
    PetscCheck(e >= 0 && e < c->n, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Joint member %" PetscInt_FMT " is element %" PetscInt_FMT ", outside 0..%" PetscInt_FMT, i, e, c->n - 1);
    PetscCall((*c->ops->element)(c, e, U, V, &out));
    for (PetscInt k = 0; k < nc; k++) {
      if (F) F[k] += Fe[k];
      if (N) N[k] += Ne[k];
    }
    for (PetscInt k = 0; k < nc2; k++) {
      if (dFdU) dFdU[k] += DU[k];
      if (dFdV) dFdV[k] += DV[k];
      if (dNdV) dNdV[k] += DN[k];
    }
    nstick += out.state == JR_CONTACT_FULL_STICK;
    nsep += out.state == JR_CONTACT_FULL_SEPARATION;
    npart += out.state == JR_CONTACT_SEPARATION_STICK_SLIP;
  }
  PetscCall(PetscLogEventEnd(JR_ContactEval, 0, 0, 0, 0));
  if (state) {
    if (cnt && nstick == cnt) *state = JR_CONTACT_FULL_STICK;
    else if (cnt && nsep == cnt) *state = JR_CONTACT_FULL_SEPARATION;
    else if (npart || nsep) *state = JR_CONTACT_SEPARATION_STICK_SLIP;
    else *state = cnt ? JR_CONTACT_STICK_SLIP : JR_CONTACT_FULL_STICK;
  }
  PetscCall(PetscFree5(Fe, Ne, DU, DV, DN));
  PetscFunctionReturn(0);
}

/*
  JRContactJointLoop - the hysteresis loop of a joint (members, NULL: all elements) over one
  periodic cycle at ns equally spaced angles theta_j = 2 pi j/ns: the motion u[j] (and v[j]) and the
  summed tangential force f[j] and normal load n[j] (v, n may be NULL). Marched exactly at the
  samples (the periodic play operator of the AFT path) whatever the evaluation path.
*/
PetscErrorCode JRContactJointLoop(JRContact c, PetscInt m, const PetscInt members[], const PetscReal U[], const PetscReal V[], PetscInt ns, PetscReal u[], PetscReal v[], PetscReal f[], PetscReal n[])
{
  const PetscInt cnt = members ? m : c->n;
  JRAFT         *a;
  PetscReal     *ft, *nt;
  JRElementOut   out;

  PetscFunctionBeginUser;
  PetscCall(JRContactSetUp(c));
  PetscCheck(!c->normal || V, c->comm, PETSC_ERR_ARG_NULL, "Contact type %s needs the normal motion V", c->type_name);
  PetscCall(JRAFTCreate(c->H, ns, &a));
  PetscCall(PetscMalloc2(ns, &ft, ns, &nt));
  PetscCall(PetscMemzero(&out, sizeof(out)));
  PetscCall(PetscArrayzero(f, ns));
  if (n) PetscCall(PetscArrayzero(n, ns));
  PetscCall(PetscLogEventBegin(JR_ContactLoop, 0, 0, 0, 0));
  for (PetscInt i = 0; i < cnt; i++) {
    const PetscInt e = members ? members[i] : i;
    PetscCheck(e >= 0 && e < c->n, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "Joint member %" PetscInt_FMT " is element %" PetscInt_FMT ", outside 0..%" PetscInt_FMT, i, e, c->n - 1);
    JRAFTElement(a, c->kt[e], c->normal ? c->kn[e] : 0.0, c->mu[e], c->n0[e], U, c->normal ? V : NULL, &out, ft, nt);
    for (PetscInt j = 0; j < ns; j++) {
      f[j] += ft[j];
      if (n) n[j] += nt[j];
    }
  }
  PetscCall(PetscLogEventEnd(JR_ContactLoop, 0, 0, 0, 0));
  if (!cnt) JRAFTElement(a, 1.0, 0.0, 0.0, 0.0, U, c->normal ? V : NULL, &out, ft, nt); /* synthesise the motion only */
  PetscCall(PetscArraycpy(u, a->u, ns));
  if (v) {
    if (c->normal) PetscCall(PetscArraycpy(v, a->v, ns));
    else PetscCall(PetscArrayzero(v, ns));
  }
  PetscCall(PetscFree2(ft, nt));
  PetscCall(JRAFTDestroy(&a));
  PetscFunctionReturn(0);
}

/* Work done per cycle by the force F through the motion U (nc = 2H+1 harmonics each):
   W = integral of f du over one cycle = pi sum_h h (Us_h Fc_h - Uc_h Fs_h) [J];
   for a friction element this is the energy dissipated per cycle. */
PetscErrorCode JRHarmonicWork(PetscInt nc, const PetscReal U[], const PetscReal F[], PetscReal *W)
{
  PetscReal w = 0.0;

  PetscFunctionBeginUser;
  for (PetscInt h = 1; 2 * h < nc; h++) w += h * (U[2 * h - 1] * F[2 * h] - U[2 * h] * F[2 * h - 1]);
  *W = PETSC_PI * w;
  PetscFunctionReturn(0);
}
