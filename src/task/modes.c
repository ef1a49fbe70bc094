/*
   -task modes: model + free-free (or clamped) modes. Prints the frequency table and one line per mode
       mode <index> <frequency in Hz>
   (rigid-body modes included), and writes BASE.h5 (the mesh, every mode as a field, omega), BASE.xdmf
   (ParaView: the mode shapes on the mesh) and BASE.png (side view of the first elastic mode shapes): JRPost
   (src/post/modes.c).
*/
#include <jointrom.h>
#include <sys/resource.h>
PetscErrorCode JRTaskModes(MPI_Comm comm)
{
  JRModel          model;
  JRModes          modes;
  JRPost           post;
  Mat              K, M;
  PetscInt         nm, nrb, nplot = 4, ndof;
  char             base[PETSC_MAX_PATH_LEN] = "out/modes";
  PetscBool        plot = PETSC_TRUE, help;
  PetscLogDouble   t0, t1, t2;

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Modes task (-task modes)", "JRTaskModes");
  PetscCall(PetscOptionsString("-modes_output_file", "Output base name: BASE.h5, BASE.xdmf, BASE.png ('' for none)", "JRTaskModes", base, base, sizeof(base), NULL));
  PetscCall(PetscOptionsInt("-modes_plot", "Elastic modes drawn in BASE.png", "JRTaskModes", nplot, &nplot, NULL));
  PetscCall(PetscOptionsBool("-modes_plot_png", "Draw BASE.png", "JRTaskModes", plot, &plot, NULL));
  PetscOptionsEnd();
  PetscCall(JRModelCreate(comm, &model));
  PetscCall(JRModelSetFromOptions(model));
  PetscCall(JRModesCreate(comm, &modes));
  PetscCall(JRModesSetNumber(modes, 12));
  PetscCall(JRModesSetFromOptions(modes));
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (help) {
    PetscCall(JROptionsHelpSolvers(comm, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE, PETSC_FALSE));
    PetscCall(JRModesDestroy(&modes));
    PetscCall(JRModelDestroy(&model));
    PetscFunctionReturn(0);
  }
  PetscCall(JROptionsCheck(comm, "-task modes"));
  PetscCall(JRFileCheckOutput(comm, "-modes_output_file", base));
  PetscCall(PetscLogStagePush(JR_StageModel));
  PetscCall(PetscTime(&t0));
  PetscCall(JRModelSetUp(model));
  PetscCall(PetscTime(&t1));
  PetscCall(PetscLogStagePop());
  PetscCall(PetscLogStagePush(JR_StageModes));
  PetscCall(JRModelGetMatrices(model, &K, &M, NULL));
  PetscCall(JRModelGetNumDofs(model, &ndof));
  PetscCall(JRModesSetOperators(modes, K, M));
  PetscCall(JRModesSetModel(modes, model));
  PetscCall(JRModesSolve(modes));
  PetscCall(PetscTime(&t2));
  PetscCall(PetscLogStagePop());
  PetscCall(JRModesGetNumber(modes, &nm));
  PetscCall(JRModesGetNumRigid(modes, &nrb));
  PetscCall(PetscPrintf(comm, "modes: %" PetscInt_FMT " DOFs; model %.3g s, eigensolve %.3g s; %" PetscInt_FMT " modes%s\n", ndof, (double)(t1 - t0), (double)(t2 - t1), nm, nrb ? " (the 6 rigid-body modes supplied exactly, -modes_rigid_basis)" : ""));
  { /* peak resident memory of the processes (the factorisation dominates) */
    struct rusage ru;
    double        mb[2];
    getrusage(RUSAGE_SELF, &ru);
    mb[0] = mb[1] = ru.ru_maxrss / 1024.0;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mb[0], 1, MPI_DOUBLE, MPI_MAX, comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mb[1], 1, MPI_DOUBLE, MPI_SUM, comm));
    PetscCall(PetscPrintf(comm, "modes: peak memory %.0f MB per process (largest), %.0f MB in all\n", mb[0], mb[1]));
  }
  PetscCall(JRPostCreate(comm, &post));
  PetscCall(JRPostSetOutput(post, base, plot));
  PetscCall(PetscLogStagePush(JR_StagePost));
  PetscCall(JRPostModesTable(post, modes));
  PetscCall(JRPostWriteModes(post, model, modes, nplot));
  PetscCall(PetscLogStagePop());
  PetscCall(JRPostDestroy(&post));
  PetscCall(JRModesDestroy(&modes));
  PetscCall(JRModelDestroy(&model));
  PetscFunctionReturn(0);
}
