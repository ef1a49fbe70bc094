/*
   bin/jointrom: the jointrom driver.
     mpirun -n 2 bin/jointrom -options_file runs/<case>.opts
   -task selects what it does; -help lists every option.
*/
#include <jointrom.h>
#include <slepcsys.h>
#include <errno.h>

static const char help[] = "jointrom: reduced-order models of bolted joints by harmonic balance with friction contact elements.\n"
                           "Units are SI throughout (N, m, kg, s; angles in degrees where stated).\n"
                           "Tasks (-task):\n"
                           "  element   one friction element or joint (CSV) under a prescribed motion: force harmonics,\n"
                           "            dissipated energy, contact state, hysteresis loop (CSV + PNG)\n"
                           "  frf       frequency-response curves by harmonic balance and continuation of a structure given by its\n"
                           "            matrices (-model_type matrices) with contact elements, at several force levels (HDF5, CSV, PNG)\n"
                           "  modes     a finite-element model (-model_type beam, lap, brb, lap1, lap3, gmsh) and its modes (SLEPc):\n"
                           "            'mode <i> <Hz>' lines, HDF5 + XDMF for ParaView, PNG of the mode shapes\n"
                           "  compare   node-to-node and reduced-order joint model of one FE case in one run (-rom_joints,\n"
                           "            -rom_elements): FRF overlays, peak errors per level, wall times and their ratio\n"
                           "  nlmodes   the backbone of a nonlinear mode (extended periodic motion concept): frequency and damping\n"
                           "            ratio against amplitude from stick to gross slip, on the models of frf (HDF5, CSV, PNG)\n"
                           "  preload   a finite-element model and its bolt preload (static frictionless contact): normal load and\n"
                           "            gap of every interface pair, CSV + HDF5 + XDMF, PNG maps and mid-section profile\n\n";

typedef enum {
  TASK_ELEMENT,
  TASK_FRF,
  TASK_MODES,
  TASK_PRELOAD,
  TASK_COMPARE,
  TASK_NLMODES
} Task;
static const char *const Tasks[] = {"element", "frf", "modes", "preload", "compare", "nlmodes", "Task", "TASK_", NULL};

/* The task of -task, its objects' options read and checked before its work */
static PetscErrorCode Run(MPI_Comm comm)
{
  PetscInt task = TASK_ELEMENT;

  PetscFunctionBeginUser;
  PetscCall(JRInitializePackage());
  PetscCall(JROptionsCheckValues(comm));
  PetscOptionsBegin(comm, NULL, "jointrom driver", "jointrom");
  PetscCall(PetscOptionsEList("-task", "What to do", "jointrom", Tasks, 6, Tasks[task], &task, NULL));
  PetscOptionsEnd();
  switch ((Task)task) {
  case TASK_ELEMENT:
    PetscCall(JRTaskElement(comm));
    break;
  case TASK_FRF:
    PetscCall(JRTaskFRF(comm));
    break;
  case TASK_MODES:
    PetscCall(JRTaskModes(comm));
    break;
  case TASK_PRELOAD:
    PetscCall(JRTaskPreload(comm));
    break;
  case TASK_COMPARE:
    PetscCall(JRTaskCompare(comm));
    break;
  case TASK_NLMODES:
    PetscCall(JRTaskNLModes(comm));
    break;
  }
  PetscCall(JROptionsWarnUnused(comm));
  PetscFunctionReturn(0);
}

/* An -options_file on the command line that cannot be read: one line on rank 0 (PETSc's own message, from inside its
   initialisation, is a stack dump), true on every rank */
static int OptionsFileUnreadable(int argc, char **argv)
{
  int rank = 0, bad = 0;

  (void)MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (!rank)
    for (int i = 1; i < argc && !bad; i++) {
      FILE *fp;
      if (strcmp(argv[i], "-options_file")) continue;
      if (i + 1 >= argc || argv[i + 1][0] == '-') {
        fprintf(stderr, "jointrom: error: -options_file is given without a value: it takes a file name\n");
        bad = 1;
      } else if (!(fp = fopen(argv[i + 1], "r"))) {
        fprintf(stderr, "jointrom: error: -options_file %s: cannot be read (%s)\n", argv[i + 1], strerror(errno));
        bad = 1;
      } else fclose(fp);
    }
  (void)MPI_Bcast(&bad, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return bad;
}

int main(int argc, char **argv)
{
  PetscErrorCode ierr;

  (void)MPI_Init(&argc, &argv); /* before PETSc, to check the options files first; PETSc then leaves MPI_Finalize to us */
  if (OptionsFileUnreadable(argc, argv)) {
    (void)MPI_Finalize();
    return 1;
  }
  PetscCall(SlepcInitialize(&argc, &argv, NULL, help));
  PetscCall(JRErrorHandlerPush());
  ierr = Run(PETSC_COMM_WORLD);
  if (ierr) {
    ierr = (PetscErrorCode)JRErrorExit(ierr);
    (void)MPI_Finalize();
    return (int)ierr;
  }
  PetscCall(SlepcFinalize());
  (void)MPI_Finalize();
  return 0;
}
