/*
   -task preload: the FE model and its bolt preload (JRPreload). Prints the summary and the line
       preload total_normal_force <N> bolt_force_sum <N> pairs_in_contact <n> pairs <m>
   and writes BASE.csv, BASE.h5, BASE.xdmf and BASE.png (-preload_output_file, default out/preload).
*/
#include <jointrom.h>

PetscErrorCode JRTaskPreload(MPI_Comm comm)
{
  JRModel          model;
  JRPreload        pre;
  JRPreloadSummary s;
  char             base[PETSC_MAX_PATH_LEN] = "out/preload";
  PetscBool        plot = PETSC_TRUE, help;
  PetscInt         ndof;
  PetscLogDouble   t0, t1;

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Preload task (-task preload)", "JRTaskPreload");
  PetscCall(PetscOptionsString("-preload_output_file", "Output base name: BASE.csv, BASE.h5, BASE.xdmf, BASE.png ('' for none)", "JRTaskPreload", base, base, sizeof(base), NULL));
  PetscCall(PetscOptionsBool("-preload_plot", "Draw BASE.png (pressure and gap maps, mid-section profile)", "JRTaskPreload", plot, &plot, NULL));
  PetscOptionsEnd();
  PetscCall(JRModelCreate(comm, &model));
  PetscCall(JRModelSetFromOptions(model));
  PetscCall(JRPreloadCreate(comm, &pre));
  PetscCall(JRPreloadSetModel(pre, model));
  PetscCall(JRPreloadSetFromOptions(pre));
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (help) {
    PetscCall(JROptionsHelpSolvers(comm, PETSC_FALSE, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE));
    PetscCall(JRPreloadDestroy(&pre));
    PetscCall(JRModelDestroy(&model));
    PetscFunctionReturn(0);
  }
  PetscCall(JROptionsCheck(comm, "-task preload"));
  PetscCall(JRFileCheckOutput(comm, "-preload_output_file", base));
  PetscCall(PetscTime(&t0));
  PetscCall(JRModelSetUp(model));
  PetscCall(PetscTime(&t1));
  PetscCall(JRModelGetNumDofs(model, &ndof));
  PetscCall(PetscPrintf(comm, "preload: model %" PetscInt_FMT " DOFs in %.3g s\n", ndof, (double)(t1 - t0)));
  PetscCall(JRPreloadSolve(pre));
  PetscCall(JRPreloadView(pre, NULL));
  PetscCall(JRPreloadGetSummary(pre, &s));
  PetscCall(PetscPrintf(comm, "preload total_normal_force %.10g bolt_force_sum %.10g pairs_in_contact %" PetscInt_FMT " pairs %" PetscInt_FMT "\n", (double)s.total_force, (double)s.bolt_force_sum, s.in_contact, s.pairs));
  PetscCall(JRPreloadWrite(pre, base, plot));
  if (base[0]) PetscCall(PetscPrintf(comm, "preload: wrote %s.csv, %s.h5, %s.xdmf%s%s%s\n", base, base, base, plot ? ", " : "", plot ? base : "", plot ? ".png" : ""));
  PetscCall(JRPreloadDestroy(&pre));
  PetscCall(JRModelDestroy(&model));
  PetscFunctionReturn(0);
}
