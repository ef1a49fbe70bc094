/*
   Errors a user can read. A user error (a bad option, value, file or line: the argument, file and input error
   codes) prints one message, once, as "jointrom: error: <message>", without PETSc's stack dump; the run then
   ends with exit status 1 (JRErrorExit). Every other error is an internal one and keeps PETSc's full traceback.
   -error_trace (or -on_error_attach_debugger, -start_in_debugger) keeps the traceback for user errors too.
*/
#include <jointrom.h>
#include <slepcsys.h>
#include <hdf5.h>

static PetscBool      jr_error_trace = PETSC_FALSE; /* traceback for user errors too */
static PetscErrorCode jr_user_error  = 0;           /* the code of the user error reported, 0 if none */
static PetscBool      jr_collective  = PETSC_FALSE; /* raised on every rank (a communicator as large as the world's) */
static char           jr_context[4][PETSC_MAX_PATH_LEN + 64];          /* what is being read, for messages from libraries */
static int            jr_ncontext    = 0;

static PetscBool IsUserError(PetscErrorCode n)
{
  switch (n) {
  case PETSC_ERR_ARG_SIZ:
  case PETSC_ERR_ARG_WRONG:
  case PETSC_ERR_ARG_OUTOFRANGE:
  case PETSC_ERR_ARG_INCOMP:
  case PETSC_ERR_ARG_UNKNOWN_TYPE:
  case PETSC_ERR_ARG_WRONGSTATE:
  case PETSC_ERR_FILE_OPEN:
  case PETSC_ERR_FILE_READ:
  case PETSC_ERR_FILE_WRITE:
  case PETSC_ERR_FILE_UNEXPECTED:
  case PETSC_ERR_USER_INPUT:
  case PETSC_ERR_SUP:
  case PETSC_ERR_NOT_CONVERGED: /* an outcome the message explains (an incomplete curve, no solution at the start) */
  case PETSC_ERR_MISSING_FACTOR: /* a factorisation package chosen by an option that cannot factor this matrix */
    return PETSC_TRUE;
  default:
    return PETSC_FALSE;
  }
}

static PetscErrorCode Handler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  const PetscBool choice = (PetscBool)(n == PETSC_ERR_USER && fun && !strncmp(fun, "PetscOptions", 12)); /* a value not among an option's choices */

  if (jr_user_error) return n; /* the error already reported, passing up the stack */
  if (p == PETSC_ERROR_INITIAL && (IsUserError(n) || choice || (jr_ncontext && n == PETSC_ERR_LIB)) && !jr_error_trace) { /* a library's error on a file being read: the file's fault */
    PetscMPIInt size = 1, rank = 0, wsize = 1, wrank = 0;
    MPI_Comm_size(comm, &size);
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &wsize);
    MPI_Comm_rank(MPI_COMM_WORLD, &wrank);
    jr_user_error = n;
    jr_collective = (PetscBool)(size == wsize || choice); /* options are the same on every rank, so is their check */
    if (choice ? !wrank : !rank) {
      const char *ctx = jr_ncontext ? jr_context[jr_ncontext - 1] : "", *sep = jr_ncontext ? ": " : "";
      const char *hint = n == PETSC_ERR_MISSING_FACTOR ? " (a -*pc_factor_mat_solver_type option chose a package that cannot factor this matrix: PETSc's own LU and Cholesky factor only sequential ones, so on more than one rank use mumps, the default)" : "";
      char        one[1024];
      snprintf(one, sizeof(one), "%s", mess ? mess : "(no message)");
      for (char *c = one; *c; c++) /* one line: PETSc's messages may carry line breaks */
        if (*c == '\n') *c = ' ';
      if (jr_collective) fprintf(stderr, "jointrom: error: %s%s%s%s\n", ctx, sep, one, hint);
      else fprintf(stderr, "jointrom: error (rank %d): %s%s%s%s\n", wrank, ctx, sep, one, hint);
      fflush(stderr);
    }
    return n;
  }
  return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, ctx);
}

/* What is being read (a file and the option that names it), put before the message of a user error raised until
   JRErrorContextPop: a library's message ("Unexpected data in file") then says which file */
PetscErrorCode JRErrorContextPush(const char what[])
{
  PetscFunctionBeginUser;
  if (jr_ncontext < 4) PetscCall(PetscStrncpy(jr_context[jr_ncontext], what, sizeof(jr_context[0])));
  jr_ncontext++;
  PetscFunctionReturn(0);
}

PetscErrorCode JRErrorContextPop(void)
{
  PetscFunctionBeginUser;
  if (jr_ncontext > 0) jr_ncontext--;
  PetscFunctionReturn(0);
}

/* A library call tried for its error alone (JRErrorCatchPush ... JRErrorCatchPop): the first message kept, nothing
   printed */
static char jr_caught[512];

static PetscErrorCode CatchHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm, (void)line, (void)fun, (void)file, (void)ctx;
  if (p == PETSC_ERROR_INITIAL && !jr_caught[0]) snprintf(jr_caught, sizeof(jr_caught), "%s", mess && mess[0] ? mess : "(no message)");
  return n;
}

PetscErrorCode JRErrorCatchPush(void)
{
  PetscFunctionBeginUser;
  jr_caught[0] = 0;
  PetscCall(PetscPushErrorHandler(CatchHandler, NULL));
  PetscFunctionReturn(0);
}

/* The message of the first error raised since JRErrorCatchPush ("" if none) */
PetscErrorCode JRErrorCatchPop(char msg[], size_t len)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscStrncpy(msg, jr_caught, len));
  PetscFunctionReturn(0);
}

/* Install the handler (after SlepcInitialize) */
PetscErrorCode JRErrorHandlerPush(void)
{
  PetscBool dbg = PETSC_FALSE, sid = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-error_trace", &jr_error_trace, NULL));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-on_error_attach_debugger", &dbg));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-start_in_debugger", &sid));
  if (dbg || sid) jr_error_trace = PETSC_TRUE;
  if (!jr_error_trace) H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* HDF5's stack dump; the error raised says which file */
  PetscCall(PetscPushErrorHandler(Handler, NULL));
  PetscFunctionReturn(0);
}

/*
  JRErrorExit - the end of a run that failed with ierr: a user error raised on every rank finalises and exits 1; one
  raised on some ranks only, or an internal error, aborts every rank (the others may wait in a collective call).
*/
int JRErrorExit(PetscErrorCode ierr)
{
  if (jr_user_error && jr_collective) {
    (void)SlepcFinalize();
    return 1;
  }
  fflush(stdout);
  fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, jr_user_error ? 1 : (int)ierr);
  return (int)ierr;
}
