/* Log stages, one per pipeline stage, and the interface's, the reduction's, the check's and the nonlinear modes' events: -log_view reads as the pipeline */
#include <jointrom.h>

PetscLogStage JR_StageModel, JR_StagePreload, JR_StageInterface, JR_StageModes, JR_StageReduce, JR_StageSolve, JR_StagePost;
PetscLogEvent JR_InterfaceSetUp, JR_ReduceJoints, JR_ReduceSelect, JR_ReduceFit, JR_ReduceHBM, JR_Verify, JR_NLModesSolve;

PetscErrorCode JRLogRegister(void)
{
  PetscClassId id;

  PetscFunctionBeginUser;
  PetscCall(PetscLogStageRegister("JR 1 model", &JR_StageModel));
  PetscCall(PetscLogStageRegister("JR 2 preload", &JR_StagePreload));
  PetscCall(PetscLogStageRegister("JR 3 interface", &JR_StageInterface));
  PetscCall(PetscLogStageRegister("JR 4 modes+HBM", &JR_StageModes));
  PetscCall(PetscLogStageRegister("JR 5 reduce", &JR_StageReduce));
  PetscCall(PetscLogStageRegister("JR 6 solve", &JR_StageSolve));
  PetscCall(PetscLogStageRegister("JR 7 post", &JR_StagePost));
  PetscCall(PetscClassIdRegister("JRReduce", &id));
  PetscCall(PetscLogEventRegister("JR_InterfaceSetUp", id, &JR_InterfaceSetUp));
  PetscCall(PetscLogEventRegister("JR_ReduceJoints", id, &JR_ReduceJoints));
  PetscCall(PetscLogEventRegister("JR_ReduceSelect", id, &JR_ReduceSelect));
  PetscCall(PetscLogEventRegister("JR_ReduceFit", id, &JR_ReduceFit));
  PetscCall(PetscLogEventRegister("JR_ReduceHBM", id, &JR_ReduceHBM));
  PetscCall(PetscClassIdRegister("JRVerify", &id));
  PetscCall(PetscLogEventRegister("JR_Verify", id, &JR_Verify));
  PetscCall(PetscClassIdRegister("JRNLModes", &id));
  PetscCall(PetscLogEventRegister("JR_NLModesSolve", id, &JR_NLModesSolve));
  PetscFunctionReturn(0);
}
