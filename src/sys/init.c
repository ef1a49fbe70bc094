/* Package registration: class id, log events, contact types. Called by every JRXxxCreate. */
#include <jointrom/private/contactimpl.h>

PetscClassId  JR_CONTACT_CLASSID;
PetscLogEvent JR_ContactEval, JR_ContactSetUp, JR_ContactLoop;

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
  PetscCall(JRContactRegisterAll());
  PetscCall(PetscRegisterFinalize(JRFinalizePackage));
  PetscFunctionReturn(0);
}

PetscErrorCode JRFinalizePackage(void)
{
  PetscFunctionBeginUser;
  PetscCall(JRContactRegisterAllReset());
  JRPackageInitialized = PETSC_FALSE;
  PetscFunctionReturn(0);
}
