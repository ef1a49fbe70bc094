/* Package registration: class id, log events, contact types. Called by every JRXxxCreate. */
#include <jointrom/private/contactimpl.h>
#include <jointrom/private/modelimpl.h>

PetscClassId  JR_CONTACT_CLASSID, JR_MODEL_CLASSID, JR_HBM_CLASSID;
PetscLogEvent JR_ContactEval, JR_ContactSetUp, JR_ContactLoop, JR_ModelLoad, JR_ModesSolve, JR_ModesStatic, JR_PreloadSetUp, JR_PreloadSolve, JR_HBMResidual, JR_HBMJacobian, JR_HBMSolve, JR_ContStep, JR_DenseLU, JR_DenseGMRES;
PetscLogEvent JR_ContTangent, JR_ContChord, JR_ContPeak;
PetscLogEvent JR_HBMHill;
PetscLogEvent JR_HBMFloquetTime;

static PetscBool JRPackageInitialized = PETSC_FALSE;

/* Register jointrom's classes, log events and types once; JRFinalizePackage runs at PetscFinalize */
PetscErrorCode JRInitializePackage(void)
{
  PetscFunctionBeginUser;
  if (JRPackageInitialized) PetscFunctionReturn(0);
  JRPackageInitialized = PETSC_TRUE;
  PetscCall(PetscClassIdRegister("JRContact", &JR_CONTACT_CLASSID));
  PetscCall(PetscLogEventRegister("JR_ContactEval", JR_CONTACT_CLASSID, &JR_ContactEval));
  PetscCall(PetscLogEventRegister("JR_ContactSetUp", JR_CONTACT_CLASSID, &JR_ContactSetUp));
  PetscCall(PetscLogEventRegister("JR_ContactLoop", JR_CONTACT_CLASSID, &JR_ContactLoop));
  PetscCall(PetscClassIdRegister("JRModel", &JR_MODEL_CLASSID));
  PetscCall(PetscClassIdRegister("JRHBM", &JR_HBM_CLASSID));
  PetscCall(PetscLogEventRegister("JR_ModelLoad", JR_MODEL_CLASSID, &JR_ModelLoad));
  PetscCall(PetscLogEventRegister("JR_ModesSolve", JR_MODEL_CLASSID, &JR_ModesSolve));
  PetscCall(PetscLogEventRegister("JR_ModesStatic", JR_MODEL_CLASSID, &JR_ModesStatic));
  PetscCall(PetscLogEventRegister("JR_PreloadSetUp", JR_MODEL_CLASSID, &JR_PreloadSetUp));
  PetscCall(PetscLogEventRegister("JR_PreloadSolve", JR_MODEL_CLASSID, &JR_PreloadSolve));
  PetscCall(PetscLogEventRegister("JR_HBMResidual", JR_HBM_CLASSID, &JR_HBMResidual));
  PetscCall(PetscLogEventRegister("JR_Jacobian", JR_HBM_CLASSID, &JR_HBMJacobian));
  PetscCall(PetscLogEventRegister("JR_Hill", JR_HBM_CLASSID, &JR_HBMHill));
  PetscCall(PetscLogEventRegister("JR_FloquetTime", JR_HBM_CLASSID, &JR_HBMFloquetTime));
  PetscCall(PetscLogEventRegister("JR_HBMSolve", JR_HBM_CLASSID, &JR_HBMSolve));
  PetscCall(PetscLogEventRegister("JR_ContStep", JR_HBM_CLASSID, &JR_ContStep));
  PetscCall(PetscLogEventRegister("JR_ContTangent", JR_HBM_CLASSID, &JR_ContTangent));
  PetscCall(PetscLogEventRegister("JR_ContChord", JR_HBM_CLASSID, &JR_ContChord));
  PetscCall(PetscLogEventRegister("JR_ContPeak", JR_HBM_CLASSID, &JR_ContPeak));
  PetscCall(PetscLogEventRegister("JR_DenseLU", JR_HBM_CLASSID, &JR_DenseLU));
  PetscCall(PetscLogEventRegister("JR_DenseGMRES", JR_HBM_CLASSID, &JR_DenseGMRES));
  PetscCall(JRLogRegister());
  PetscCall(SNESRegister(SNESNEWTONDENSE, SNESCreate_NewtonDense));
  PetscCall(JRModelRegisterAll());
  PetscCall(JRContactRegisterAll());
  PetscCall(JRPreloadSolverRegisterAll());
  PetscCall(JRContRegisterAll());
  PetscCall(PetscRegisterFinalize(JRFinalizePackage));
  PetscFunctionReturn(0);
}

PetscErrorCode JRFinalizePackage(void)
{
  PetscFunctionBeginUser;
  PetscCall(JRContactRegisterAllReset());
  PetscCall(PetscFunctionListDestroy(&JRModelList));
  PetscCall(PetscFunctionListDestroy(&JRPreloadSolverList));
  PetscCall(PetscFunctionListDestroy(&JRContList));
  JRPackageInitialized = PETSC_FALSE;
  PetscFunctionReturn(0);
}
