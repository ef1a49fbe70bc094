/* JRContact: batches of friction contact elements of one type (thesis chapter 3) */
#if !defined(JOINTROM_CONTACT_H)
#define JOINTROM_CONTACT_H

#include <jointrom/sys.h>

/* ------------------------------------------------------------------------------------------ */
/* JRContact: a batch of friction contact elements of one type (thesis chapter 3)             */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRContact *JRContact;
typedef const char          *JRContactType;
#define JRCONTACTJENKINS   "jenkins"    /* 1D dry friction, constant normal load (3.1-3.30) */
#define JRCONTACTJENKINSNV "jenkins_nv" /* 1D dry friction, normal load variation (3.31-3.84) */
#define JRCONTACTCUBIC     "cubic"      /* nonlinear spring f = kt u^3, for Duffing-type checks */

/* Evaluation path: closed-form single harmonic (H = 1 only) or alternating frequency-time */
typedef enum {
  JR_CONTACT_ANALYTIC,
  JR_CONTACT_AFT
} JRContactMethod;
PETSC_EXTERN const char *const JRContactMethods[];

/* Contact state of an element over one cycle: the four colours of thesis Figs 5.12-5.19 */
typedef enum {
  JR_CONTACT_FULL_STICK,
  JR_CONTACT_STICK_SLIP,            /* stick-slip (or gross slip) without separation */
  JR_CONTACT_SEPARATION_STICK_SLIP, /* separation during part of the cycle, stick-slip otherwise */
  JR_CONTACT_FULL_SEPARATION
} JRContactState;
PETSC_EXTERN const char *const JRContactStates[];

/* The 13 single-harmonic motion sequences of the jenkins_nv element (section 3.3, Table 3.2) */
typedef enum {
  JR_SEQ_FULL_SEPARATION,
  JR_SEQ_P1, JR_SEQ_P2, JR_SEQ_P3,
  JR_SEQ_N1, JR_SEQ_N2, JR_SEQ_N3,
  JR_SEQ_E1, JR_SEQ_E2, JR_SEQ_E3, JR_SEQ_E4,
  JR_SEQ_SLIP_NO_SEPARATION,
  JR_SEQ_FULL_STICK,
  JR_SEQ_OTHER /* a sequence outside the thesis's list; never seen, reported if it is */
} JRContactSequence;
PETSC_EXTERN const char *const JRContactSequences[];

PETSC_EXTERN PetscFunctionList JRContactList;
PETSC_EXTERN PetscErrorCode JRContactRegister(const char[], PetscErrorCode (*)(JRContact));
PETSC_EXTERN PetscErrorCode JRContactRegisterAll(void);

PETSC_EXTERN PetscErrorCode JRContactCreate(MPI_Comm, JRContact *);
PETSC_EXTERN PetscErrorCode JRContactSetType(JRContact, JRContactType);
PETSC_EXTERN PetscErrorCode JRContactGetType(JRContact, JRContactType *);
PETSC_EXTERN PetscErrorCode JRContactSetOptionsPrefix(JRContact, const char[]);
PETSC_EXTERN PetscErrorCode JRContactSetHarmonics(JRContact, PetscInt, PetscInt);
PETSC_EXTERN PetscErrorCode JRContactGetHarmonics(JRContact, PetscInt *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRContactSetMethod(JRContact, JRContactMethod);
PETSC_EXTERN PetscErrorCode JRContactGetMethod(JRContact, JRContactMethod *);
PETSC_EXTERN PetscErrorCode JRContactUsesNormal(JRContact, PetscBool *);
PETSC_EXTERN PetscErrorCode JRContactSetElements(JRContact, PetscInt, const PetscReal[], const PetscReal[], const PetscReal[], const PetscReal[]);
PETSC_EXTERN PetscErrorCode JRContactGetElements(JRContact, PetscInt *, const PetscReal **, const PetscReal **, const PetscReal **, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRContactSetFromOptions(JRContact);
PETSC_EXTERN PetscErrorCode JRContactSetUp(JRContact);
PETSC_EXTERN PetscErrorCode JRContactEvaluate(JRContact, const PetscReal[], const PetscReal[], PetscReal[], PetscReal[], PetscReal[], PetscReal[], PetscReal[], JRContactState[]);
PETSC_EXTERN PetscErrorCode JRContactGetSequences(JRContact, const PetscReal[], const PetscReal[], JRContactSequence[]);
PETSC_EXTERN PetscErrorCode JRContactView(JRContact, PetscViewer);
PETSC_EXTERN PetscErrorCode JRContactDestroy(JRContact *);

/* A joint: several elements in parallel sharing one motion (Fig 4.10, (4.1)-(4.2), (5.2)-(5.5)) */
PETSC_EXTERN PetscErrorCode JRContactEvaluateJoint(JRContact, PetscInt, const PetscInt[], const PetscReal[], const PetscReal[], PetscReal[], PetscReal[], PetscReal[], PetscReal[], PetscReal[], JRContactState *);
PETSC_EXTERN PetscErrorCode JRContactJointLoop(JRContact, PetscInt, const PetscInt[], const PetscReal[], const PetscReal[], PetscInt, PetscReal[], PetscReal[], PetscReal[], PetscReal[]);

/* Energy dissipated per cycle by a force with harmonics F acting through a motion U (both nc long) */
PETSC_EXTERN PetscErrorCode JRHarmonicWork(PetscInt, const PetscReal[], const PetscReal[], PetscReal *);

#endif
