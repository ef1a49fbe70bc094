/*
   -task element: one friction element, or a joint of elements in parallel read from a CSV file,
   under the prescribed motion u = U sin(theta), v = V sin(theta + phase). Prints the first force
   harmonic, the energy dissipated per cycle and the contact state, one line per amplitude
       fs <N> fc <N> energy <J> state <name>
   and writes the hysteresis loops (force vs displacement over a cycle) as CSV and PNG.
*/
#include <jointrom/private/contactimpl.h>

#define MAX_AMPS 32

typedef struct {
  PetscReal kt, kn, mu, n0;     /* single element [N/m, N/m, -, N] */
  PetscReal U[MAX_AMPS], V, phase;
  PetscInt  nu, H, N, nloop;
  char      joint[PETSC_MAX_PATH_LEN], loop[PETSC_MAX_PATH_LEN];
  PetscBool hasjoint, hasloop;
} ElementCtx;

static PetscErrorCode ElementOptions(MPI_Comm comm, PetscBool normal, ElementCtx *ctx)
{
  PetscBool flg;

  PetscFunctionBeginUser;
  ctx->kt       = 1.0e6;
  ctx->kn       = 1.0e6;
  ctx->mu       = 0.12;
  ctx->n0       = 100.0;
  ctx->nu       = MAX_AMPS;
  ctx->U[0]     = 30.0e-6;
  ctx->V        = 0.0;
  ctx->phase    = 0.0;
  ctx->H        = 1;
  ctx->N        = 64;
  ctx->nloop    = 720;
  ctx->joint[0] = ctx->loop[0] = 0;
  PetscOptionsBegin(comm, NULL, "Element task (-task element): one element or joint under a prescribed motion", "JRTaskElement");
  PetscCall(PetscOptionsReal("-element_kt", "Tangential contact stiffness kt (k_u) [N/m]", "JRContactSetElements", ctx->kt, &ctx->kt, NULL));
  PetscCall(PetscOptionsReal("-element_kn", "Normal contact stiffness kn (k_v) [N/m] (jenkins_nv)", "JRContactSetElements", ctx->kn, &ctx->kn, NULL));
  PetscCall(PetscOptionsReal("-element_mu", "Friction coefficient mu [-]", "JRContactSetElements", ctx->mu, &ctx->mu, NULL));
  PetscCall(PetscOptionsReal("-element_n0", "Normal load n0 [N] (jenkins_nv: negative for an initial gap)", "JRContactSetElements", ctx->n0, &ctx->n0, NULL));
  PetscCall(PetscOptionsRealArray("-element_u", "Tangential motion amplitude(s) U [m], u = U sin(theta); a list gives one loop each", "JRTaskElement", ctx->U, &ctx->nu, &flg));
  if (!flg) ctx->nu = 1;
  PetscCall(PetscOptionsReal("-element_v", "Normal motion amplitude V [m], v = V sin(theta + phase) (jenkins_nv)", "JRTaskElement", ctx->V, &ctx->V, NULL));
  PetscCall(PetscOptionsReal("-element_phase", "Phase of v ahead of u [degrees]", "JRTaskElement", ctx->phase, &ctx->phase, NULL));
  PetscCall(PetscOptionsInt("-element_harmonics", "Harmonics H: 1 = analytic path, > 1 = alternating frequency-time", "JRContactSetHarmonics", ctx->H, &ctx->H, NULL));
  PetscCall(PetscOptionsInt("-element_samples", "Time samples per cycle N for the AFT path (N >= 2H+1)", "JRContactSetHarmonics", ctx->N, &ctx->N, NULL));
  PetscCall(PetscOptionsString("-element_joint", "CSV file of a joint's elements in parallel, header kt,kn,mu,n0 (kn optional for jenkins)", "JRContactEvaluateJoint", ctx->joint, ctx->joint, sizeof(ctx->joint), &ctx->hasjoint));
  PetscCall(PetscOptionsString("-element_loop", "Write the hysteresis loop to FILE.csv and FILE.png ('' for none)", "JRContactJointLoop", ctx->loop, ctx->loop, sizeof(ctx->loop), &ctx->hasloop));
  PetscCall(PetscOptionsInt("-element_loop_samples", "Points per cycle in the hysteresis loop", "JRContactJointLoop", ctx->nloop, &ctx->nloop, NULL));
  PetscOptionsEnd();
  if (!ctx->loop[0]) ctx->hasloop = PETSC_FALSE; /* -element_loop '' turns the loop files off */

  /* bad input: say which option, which value, what is allowed */
  PetscCheck(ctx->H >= 1 && ctx->H <= JR_MAX_HARMONICS, comm, PETSC_ERR_ARG_OUTOFRANGE, "-element_harmonics %" PetscInt_FMT ": the number of harmonics must be between 1 and %d", ctx->H, JR_MAX_HARMONICS);
  PetscCheck(ctx->N >= 2 * ctx->H + 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-element_samples %" PetscInt_FMT ": the number of time samples must be at least 2H+1 = %" PetscInt_FMT " for -element_harmonics %" PetscInt_FMT, ctx->N, 2 * ctx->H + 1, ctx->H);
  PetscCheck(ctx->nloop >= 2 * ctx->H + 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-element_loop_samples %" PetscInt_FMT " must be at least 2H+1 = %" PetscInt_FMT, ctx->nloop, 2 * ctx->H + 1);
  PetscCheck(ctx->nu >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-element_u needs at least one amplitude [m]");
  for (PetscInt i = 0; i < ctx->nu; i++) PetscCheck(!PetscIsInfOrNanReal(ctx->U[i]) && ctx->U[i] >= 0.0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-element_u %g: the tangential amplitude must be finite and non-negative [m]", (double)ctx->U[i]);
  PetscCheck(!PetscIsInfOrNanReal(ctx->V), comm, PETSC_ERR_ARG_OUTOFRANGE, "-element_v %g: the normal amplitude must be finite [m]", (double)ctx->V);
  PetscCheck(!PetscIsInfOrNanReal(ctx->phase), comm, PETSC_ERR_ARG_OUTOFRANGE, "-element_phase %g: the phase must be finite [degrees]", (double)ctx->phase);
  if (!ctx->hasjoint) {
    PetscCheck(PetscIsNormalReal(ctx->kt) && ctx->kt > 0.0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-element_kt %g: the tangential stiffness must be positive and finite [N/m]", (double)ctx->kt);
    PetscCheck(!PetscIsInfOrNanReal(ctx->kn) && ctx->kn >= 0.0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-element_kn %g: the normal stiffness must be non-negative and finite [N/m]", (double)ctx->kn);
    PetscCheck(!PetscIsInfOrNanReal(ctx->mu) && ctx->mu >= 0.0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-element_mu %g: the friction coefficient must be non-negative and finite", (double)ctx->mu);
    PetscCheck(!PetscIsInfOrNanReal(ctx->n0), comm, PETSC_ERR_ARG_OUTOFRANGE, "-element_n0 %g: the normal load must be finite [N]", (double)ctx->n0);
    PetscCheck(normal || ctx->n0 >= 0.0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-element_n0 %g: the normal load of a jenkins element must be non-negative [N] (initial gaps need -contact_type jenkins_nv)", (double)ctx->n0);
  }
  PetscFunctionReturn(0);
}

/* Elements of the joint file (validated with file and line in the message) */
static PetscErrorCode ReadJoint(MPI_Comm comm, const char file[], PetscBool normal, JRContact c)
{
  JRTable    t;
  PetscInt   n;
  PetscReal *kt, *kn, *mu, *n0;

  PetscFunctionBeginUser;
  PetscCall(JRTableRead(comm, file, &t));
  PetscCall(JRTableGetSize(t, &n, NULL));
  if (n == 0) {
    PetscInt line;
    PetscCall(JRTableGetLine(t, -1, &line));
    SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "Joint file %s (-element_joint) line %" PetscInt_FMT ": a header but no element rows after it", file, line);
  }
  PetscCall(PetscMalloc4(n, &kt, n, &kn, n, &mu, n, &n0));
  PetscCall(JRTableGetColumn(t, "kt", PETSC_TRUE, 0.0, kt));
  PetscCall(JRTableGetColumn(t, "kn", normal, 0.0, kn));
  PetscCall(JRTableGetColumn(t, "mu", PETSC_TRUE, 0.0, mu));
  PetscCall(JRTableGetColumn(t, "n0", PETSC_TRUE, 0.0, n0));
  for (PetscInt e = 0; e < n; e++) {
    PetscInt line;
    PetscCall(JRTableGetLine(t, e, &line));
    PetscCheck(PetscIsNormalReal(kt[e]) && kt[e] > 0.0, comm, PETSC_ERR_FILE_UNEXPECTED, "Joint file %s line %" PetscInt_FMT ": kt = %g must be positive [N/m]", file, line, (double)kt[e]);
    PetscCheck(kn[e] >= 0.0 && !PetscIsInfOrNanReal(kn[e]), comm, PETSC_ERR_FILE_UNEXPECTED, "Joint file %s line %" PetscInt_FMT ": kn = %g must be non-negative [N/m]", file, line, (double)kn[e]);
    PetscCheck(mu[e] >= 0.0 && !PetscIsInfOrNanReal(mu[e]), comm, PETSC_ERR_FILE_UNEXPECTED, "Joint file %s line %" PetscInt_FMT ": mu = %g must be non-negative", file, line, (double)mu[e]);
    PetscCheck(!PetscIsInfOrNanReal(n0[e]) && (normal || n0[e] >= 0.0), comm, PETSC_ERR_FILE_UNEXPECTED, "Joint file %s line %" PetscInt_FMT ": n0 = %g must be finite%s [N]", file, line, (double)n0[e], normal ? "" : " and non-negative for jenkins");
  }
  PetscCall(JRContactSetElements(c, n, kt, kn, mu, n0));
  PetscCall(PetscFree4(kt, kn, mu, n0));
  PetscCall(JRTableDestroy(&t));
  PetscFunctionReturn(0);
}

/* Strip a .csv or .png extension so FILE, FILE.csv and FILE.png name the same pair */
static void LoopBase(const char *in, char *base, size_t len)
{
  size_t l;
  snprintf(base, len, "%s", in);
  l = strlen(base);
  if (l > 4 && (!strcmp(base + l - 4, ".csv") || !strcmp(base + l - 4, ".png"))) base[l - 4] = 0;
}

/* Contact state of each member of the joint under the common motion: counts per state */
static PetscErrorCode MemberStates(JRContact c, PetscInt nel, PetscInt nc, const PetscReal U[], const PetscReal V[], MPI_Comm comm)
{
  PetscReal      *Ub, *Vb;
  JRContactState *st;
  PetscInt        count[4] = {0, 0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc3(nel * nc, &Ub, nel * nc, &Vb, nel, &st));
  for (PetscInt k = 0; k < nc; k++)
    for (PetscInt e = 0; e < nel; e++) {
      Ub[k * nel + e] = U[k];
      Vb[k * nel + e] = V ? V[k] : 0.0;
    }
  PetscCall(JRContactEvaluate(c, Ub, V ? Vb : NULL, NULL, NULL, NULL, NULL, NULL, st));
  for (PetscInt e = 0; e < nel; e++) count[st[e]]++;
  PetscCall(PetscPrintf(comm, "element: members %s %" PetscInt_FMT ", %s %" PetscInt_FMT ", %s %" PetscInt_FMT ", %s %" PetscInt_FMT "\n", JRContactStates[0], count[0], JRContactStates[1], count[1], JRContactStates[2], count[2], JRContactStates[3], count[3]));
  PetscCall(PetscFree3(Ub, Vb, st));
  PetscFunctionReturn(0);
}

PetscErrorCode JRTaskElement(MPI_Comm comm)
{
  ElementCtx     ctx;
  JRContact      c;
  JRContactType  type;
  PetscBool      normal;
  PetscInt       nc, nel;
  PetscReal     *U, *V, *F, *N, *lu, *lv, *lf, *ln;
  FILE          *fp = NULL;
  char           base[PETSC_MAX_PATH_LEN], csv[PETSC_MAX_PATH_LEN + 8], png[PETSC_MAX_PATH_LEN + 8], tmp[PETSC_MAX_PATH_LEN + 32];

  PetscFunctionBeginUser;
  PetscCall(JRContactCreate(comm, &c));
  PetscCall(JRContactSetFromOptions(c));
  PetscCall(JRContactGetType(c, &type));
  PetscCall(JRContactUsesNormal(c, &normal));
  PetscCall(ElementOptions(comm, normal, &ctx));
  {
    PetscBool help;
    PetscCall(PetscOptionsHasHelp(NULL, &help));
    if (help) {
      PetscCall(JRContactDestroy(&c));
      PetscFunctionReturn(0);
    }
  }
  PetscCall(JROptionsCheck(comm, "-task element"));
  if (ctx.hasloop) PetscCall(JRFileCheckOutput(comm, "-element_loop", ctx.loop));
  PetscCall(JRContactSetHarmonics(c, ctx.H, ctx.N));
  if (ctx.hasjoint) PetscCall(ReadJoint(comm, ctx.joint, normal, c));
  else PetscCall(JRContactSetElements(c, 1, &ctx.kt, &ctx.kn, &ctx.mu, &ctx.n0));
  PetscCall(JRContactSetUp(c));
  PetscCall(JRContactGetHarmonics(c, NULL, NULL, &nc));
  PetscCall(JRContactGetElements(c, &nel, NULL, NULL, NULL, NULL));

  {
    JRContactMethod method;
    PetscCall(JRContactGetMethod(c, &method));
    PetscCall(PetscPrintf(comm, "element: %s, %" PetscInt_FMT " element%s in parallel, %s path, H = %" PetscInt_FMT, type, nel, nel > 1 ? "s" : "", JRContactMethods[method], ctx.H));
    if (method == JR_CONTACT_AFT) PetscCall(PetscPrintf(comm, ", N = %" PetscInt_FMT " samples", ctx.N));
    PetscCall(PetscPrintf(comm, "\n"));
  }
  if (!ctx.hasjoint) {
    PetscCall(PetscPrintf(comm, "element: kt %g N/m, mu %g, n0 %g N", (double)ctx.kt, (double)ctx.mu, (double)ctx.n0));
    if (normal) PetscCall(PetscPrintf(comm, ", kn %g N/m", (double)ctx.kn));
    if (ctx.kt > 0 && ctx.n0 > 0) PetscCall(PetscPrintf(comm, "; slip starts at U = mu n0/kt = %g m", (double)(ctx.mu * ctx.n0 / ctx.kt)));
    PetscCall(PetscPrintf(comm, "\n"));
  }
  if (normal) PetscCall(PetscPrintf(comm, "element: motion u = U sin(theta), v = %g sin(theta + %g deg) m\n", (double)ctx.V, (double)ctx.phase));
  else PetscCall(PetscPrintf(comm, "element: motion u = U sin(theta) m\n"));

  PetscCall(PetscCalloc4(nc, &U, nc, &V, nc, &F, nc, &N));
  PetscCall(PetscMalloc4(ctx.nloop, &lu, ctx.nloop, &lv, ctx.nloop, &lf, ctx.nloop, &ln));
  if (ctx.hasloop) {
    LoopBase(ctx.loop, base, sizeof(base));
    PetscCall(PetscSNPrintf(csv, sizeof(csv), "%s.csv", base));
    PetscCall(PetscSNPrintf(png, sizeof(png), "%s.png", base));
    PetscCall(JRFileOpenTemp(comm, csv, &fp, tmp, sizeof(tmp)));
    if (fp) fprintf(fp, "level,U_m,theta_rad,u_m,v_m,f_N,n_N\n");
  }
  for (PetscInt i = 0; i < ctx.nu; i++) {
    JRContactState st;
    PetscReal      energy;
    U[1] = ctx.U[i];
    V[1] = ctx.V * PetscCosReal(ctx.phase * PETSC_PI / 180.0);
    V[2] = ctx.V * PetscSinReal(ctx.phase * PETSC_PI / 180.0);
    PetscCall(JRContactEvaluateJoint(c, 0, NULL, U, normal ? V : NULL, F, N, NULL, NULL, NULL, &st));
    PetscCall(JRHarmonicWork(nc, U, F, &energy));
    if (ctx.nu > 1) PetscCall(PetscPrintf(comm, "element: U = %g m\n", (double)ctx.U[i]));
    if (normal) PetscCall(PetscPrintf(comm, "element: normal load harmonics n0 %g ns %g nc %g N\n", (double)N[0], (double)N[1], (double)N[2]));
    if (nc == 3 && nel == 1) {
      JRContactSequence seq;
      PetscCall(JRContactGetSequences(c, U, V, &seq));
      PetscCall(PetscPrintf(comm, "element: motion sequence %s (thesis 3.3, Table 3.2)\n", JRContactSequences[seq]));
    }
    if (ctx.U[i] > 0.0) PetscCall(PetscPrintf(comm, "element: equivalent stiffness fs/U %.6g N/m, loss factor fc/fs %.4g\n", (double)(F[1] / ctx.U[i]), (double)(F[1] != 0.0 ? F[2] / F[1] : 0.0)));
    if (nel > 1) PetscCall(MemberStates(c, nel, nc, U, normal ? V : NULL, comm));
    PetscCall(PetscPrintf(comm, "fs %.10g fc %.10g energy %.10g state %s\n", (double)F[1], (double)F[2], (double)energy, JRContactStates[st]));
    if (ctx.hasloop) {
      PetscCall(JRContactJointLoop(c, 0, NULL, U, normal ? V : NULL, ctx.nloop, lu, lv, lf, ln));
      if (fp) {
        for (PetscInt j = 0; j <= ctx.nloop; j++) { /* close the loop: repeat the first point */
          const PetscInt jj = j % ctx.nloop;
          fprintf(fp, "%" PetscInt_FMT ",%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", i, (double)ctx.U[i], (double)(2.0 * PETSC_PI * j / ctx.nloop), (double)lu[jj], (double)lv[jj], (double)lf[jj], (double)ln[jj]);
        }
      }
    }
  }
  if (ctx.hasloop) {
    PetscBool made;
    char      vars[3 * PETSC_MAX_PATH_LEN];
    PetscCall(JRFileCommit(comm, &fp, tmp, csv));
    PetscCall(PetscSNPrintf(vars, sizeof(vars), "data='%s'; nlev=%" PetscInt_FMT "; normal=%d; ttl='%s element%s, hysteresis loop%s'", csv, ctx.nu, (int)normal, type, nel > 1 ? "s (joint)" : "", ctx.nu > 1 ? "s" : ""));
    PetscCall(JRPlot(comm, "plot_loop.gp", png, vars, &made));
    PetscCall(PetscPrintf(comm, "element: loop written to %s%s%s\n", csv, made ? " and " : "", made ? png : ""));
  }
  PetscCall(PetscFree4(U, V, F, N));
  PetscCall(PetscFree4(lu, lv, lf, ln));
  PetscCall(JRContactDestroy(&c));
  PetscFunctionReturn(0);
}
