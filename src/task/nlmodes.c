/*
   -task nlmodes: the backbone of a nonlinear mode by the extended periodic motion concept (EPMC): frequency and damping
   ratio against amplitude, from the stuck structure to gross slip.

   The structure and its elements come as for -task frf (src/task/frf.c): a matrices model with its element table, or an
   FE model's node-to-node contact model (model -> preload -> modes -> interface), or a reduced model (-rom_joints,
   -rom_elements, -rom_load: the EPMC keeps its modal unknowns, not condensed onto the joints). Then the harmonic
   balance becomes autonomous (src/hbm/epmc.c) and JRNLModes (src/nlmodes/) follows the -nlm_mode-th elastic stuck
   mode from -nlm_amp_min to -nlm_amp_max: one line per point
     backbone point <i> amplitude <q> freq_hz <f> damping_ratio <D> xi <xi> amp_1 <m> newton <its>
   and BASE.h5, BASE.csv, BASE.png (BASE: -nlm_output_file). -task compare -compare_nlmodes follows the same mode of
   the node-to-node and the reduced model over the same amplitudes (src/task/frf.c, JRPostCompareBackbones).
*/
#include <jointrom/private/taskimpl.h>

/* The backbone on hbm: solved, written, summarised (the frequency and damping ranges and the solve time) */
PetscErrorCode JRTaskNLModesSolve(MPI_Comm comm, JRNLModes nlm, JRHBM hbm)
{
  const char *cinfo;

  PetscFunctionBeginUser;
  PetscCall(JRHBMGetSolveSize(hbm, NULL, &cinfo));
  if (cinfo[0]) PetscCall(PetscPrintf(comm, "nlmodes: the reduced model's backbone in its modal unknowns (the EPMC normalises the mode there), not %s\n", cinfo));
  PetscCall(JRNLModesSetHBM(nlm, hbm));
  PetscCall(PetscLogStagePush(JR_StageSolve));
  PetscCall(JRNLModesSetUp(nlm));
  PetscCall(JRNLModesView(nlm, NULL));
  PetscCall(JRNLModesSolve(nlm));
  PetscCall(PetscLogStagePop());
  PetscCall(JRNLModesView(nlm, NULL));
  PetscCall(PetscLogStagePush(JR_StagePost));
  PetscCall(JRNLModesWrite(nlm));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}

/* An incomplete backbone is an error, raised once everything is written */
PetscErrorCode JRTaskNLModesCheckComplete(MPI_Comm comm, JRNLModes nlm)
{
  PetscBool complete;

  PetscFunctionBeginUser;
  PetscCall(JRNLModesGetStats(nlm, NULL, NULL, &complete));
  PetscCheck(complete, comm, PETSC_ERR_NOT_CONVERGED, "Nonlinear modes: the backbone did not reach -nlm_amp_max (what was computed is written); try a smaller -nlm_step_max or more -nlm_max_cuts");
  PetscFunctionReturn(0);
}

/* -task nlmodes */
PetscErrorCode JRTaskNLModes(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  PetscCall(JRTaskFRFPipeline(comm, PETSC_TRUE));
  PetscFunctionReturn(0);
}
