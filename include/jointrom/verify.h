/* JRVerify: FRF points checked by direct time integration */
#if !defined(JOINTROM_VERIFY_H)
#define JOINTROM_VERIFY_H

#include <jointrom/nlmodes.h>

/* ------------------------------------------------------------------------------------------ */
/* JRVerify: FRF points checked by direct time integration of the same modal equations (TS)    */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRVerify *JRVerify;
/* One point's check: the first-harmonic amplitude of output 1 by harmonic balance and by time integration [m], their
   relative difference and phase difference [deg], the higher harmonics' share of the motion (RMS of harmonics >= 2 over
   RMS of harmonics >= 1) in the time integration and in the harmonic balance, the periods integrated, the steps per
   period, the last period's relative change of the state, whether it was periodic, and the wall time [s] */
typedef struct {
  PetscReal amp_hbm, amp_time, rel_diff, phase_deg, higher_time, higher_hbm, change, seconds;
  PetscInt  periods, steps;
  PetscBool periodic;
} JRVerifyResult;
PETSC_EXTERN PetscErrorCode JRVerifyCreate(MPI_Comm, JRVerify *);
PETSC_EXTERN PetscErrorCode JRVerifySetFromOptions(JRVerify);
PETSC_EXTERN PetscErrorCode JRVerifySetHBM(JRVerify, JRHBM);
PETSC_EXTERN PetscErrorCode JRVerifySetUp(JRVerify);
PETSC_EXTERN PetscErrorCode JRVerifySolve(JRVerify, PetscReal, PetscReal, const PetscReal[], JRVerifyResult *);
PETSC_EXTERN PetscErrorCode JRVerifyCurves(JRVerify, JRHBM, JRCont);
PETSC_EXTERN PetscErrorCode JRVerifyGetNumPoints(JRVerify, PetscInt *);
PETSC_EXTERN PetscErrorCode JRVerifyView(JRVerify, PetscViewer);
PETSC_EXTERN PetscErrorCode JRVerifyDestroy(JRVerify *);

#endif
