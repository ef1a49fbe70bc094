/*
   jointrom: reduced-order models of bolted joints by harmonic balance with friction contact elements.
   Public API. Every object follows the PETSc life cycle
     JRXxxCreate -> JRXxxSetType -> JRXxxSetFromOptions -> JRXxxSetUp -> JRXxxEvaluate/Solve -> JRXxxView -> JRXxxDestroy.
   Equation numbers "(3.17)" refer to the thesis in ../shared/thesis-reduced-order-bolted-joints.txt.

   Conventions (fixed here, once):
   - Units are SI throughout: N, m, kg, s, rad.
   - A periodic signal with H harmonics and the mean is stored as nc = 2H+1 real coefficients
       x(theta) = x0 + sum_{h=1..H} [ xs_h sin(h theta) + xc_h cos(h theta) ],   theta = omega t   (2.7)
     in the order [x0, xs_1, xc_1, ..., xs_H, xc_H].
   - Element batches are structure-of-arrays: coefficient k of element e is X[k*n + e] (an n x nc
     column-major matrix); a derivative dY_k/dX_m of element e is D[(k*nc + m)*n + e].
   - Tangential relative motion u, normal relative motion v; positive v presses the surfaces
     together, n = max(0, n0 + kn v) (3.32).
*/
#if !defined(JOINTROM_H)
#define JOINTROM_H

#include <petscsys.h>
#include <petscviewer.h>
#include <petscmat.h>
#include <petscsnes.h>
#include <petscdm.h>

#define JR_VERSION_MAJOR 0
#define JR_VERSION_MINOR 1

PETSC_EXTERN PetscErrorCode JRInitializePackage(void);
PETSC_EXTERN PetscErrorCode JRFinalizePackage(void);

/* Log stages, one per pipeline stage, and events, one per costly phase (see -log_view; src/sys/log.c) */
PETSC_EXTERN PetscLogStage  JR_StageModel, JR_StagePreload, JR_StageInterface, JR_StageModes, JR_StageReduce, JR_StageSolve, JR_StagePost;
PETSC_EXTERN PetscLogEvent  JR_InterfaceSetUp, JR_ReduceJoints, JR_ReduceSelect, JR_ReduceFit, JR_ReduceHBM, JR_Verify, JR_NLModesSolve;
PETSC_EXTERN PetscErrorCode JRLogRegister(void);
PETSC_EXTERN PetscClassId  JR_CONTACT_CLASSID, JR_MODEL_CLASSID, JR_HBM_CLASSID;
PETSC_EXTERN PetscLogEvent JR_ContactEval, JR_ContactSetUp, JR_ContactLoop, JR_ModelLoad, JR_ModesSolve, JR_ModesStatic, JR_PreloadSetUp, JR_PreloadSolve, JR_HBMResidual, JR_HBMJacobian, JR_HBMSolve, JR_ContStep;
PETSC_EXTERN PetscLogEvent JR_HBMHill; /* Floquet exponents by Hill's method (src/hbm/hill.c) */

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

/* ------------------------------------------------------------------------------------------ */
/* JRModel: the linear structure (K, M, optional C) and its contact elements                   */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRModel *JRModel;
typedef const char        *JRModelType;
#define JRMODELMATRICES "matrices" /* K, M (C) from files and an element table: models from any FE code */
#define JRMODELBEAM     "beam"     /* a straight prismatic beam (checks the elements) */
#define JRMODELLAP      "lap"      /* a lap-joint assembly of two beams and N bolts, every dimension an option */
#define JRMODELBRB      "brb"      /* the Brake-Reuss beam preset of the lap model (thesis ch. 4) */
#define JRMODELLAP1     "lap1"     /* the single-bolt specimen preset (thesis 5.2) */
#define JRMODELLAP3     "lap3"     /* the three-bolt specimen preset (thesis 5.3) */
#define JRMODELGMSH     "gmsh"     /* a Gmsh .msh file with physical groups for contacts and bolts */

/* Facing node pairs of the two contact surfaces (node-to-node interface), on every rank:
   coordinates x[3i..], global DOFs of the x, y, z displacements of the node on surface A (dofA[3i..]) and
   on surface B (dofB[3i..]), the tangential direction t (the beam axis projected on the surface) and the
   normal nrm pointing from A into B, so that pressing the surfaces together is (uA - uB) . nrm > 0;
   area: the node's share of surface A [m^2] (its shape function integrated over the faces: a uniform
   pressure p is carried by the forces p area); gap0: the initial gap (xB - xA) . nrm [m] (0 when the nodes
   coincide). */
typedef struct {
  PetscInt   n;
  PetscReal *x, *t, *nrm, *area, *gap0;
  PetscInt  *dofA, *dofB;
} JRPairs;

/* The bolts of an FE model (on every rank), for the pretension: bolt b acts on the footprint DOFs
   dof[off[b]] .. dof[off[b+1]-1]; its shank elongation is sum_k g[k] u[dof[k]] (the rigid fits of its
   two ends, along the shank from head to nut), its axial stiffness ka[b] = E A / L [N/m], its head-side
   centre x[3b..] [m]. A tension P in the shank loads the structure with -P g. */
typedef struct {
  PetscInt   n;
  PetscInt  *off, *dof;
  PetscReal *g, *ka, *x;
} JRBolts;

/* The contact elements of a model, one entry per element (the whole list, on every rank).
   Tangential relative motion u = x[dof_a] - x[dof_b], normal v = x[ndof_a] - x[ndof_b]; -1 = ground.
   Node-to-node interfaces instead give each element the x, y, z DOFs of its two nodes, vdof_a[3e..] and
   vdof_b[3e..], and unit directions tdir[3e..], ndir[3e..]: u = (x_A - x_B) . t, v = (x_A - x_B) . n
   (4.3); then dof_a .. ndof_b are unused (vdof_a = NULL for the single-DOF form). */
typedef struct _JRElements {
  PetscInt   n;
  PetscInt   ntypes;
  char       typename[8][32]; /* element types present; type[e] indexes this list */
  PetscInt  *type, *dof_a, *dof_b, *ndof_a, *ndof_b;
  PetscReal *kt, *kn, *mu, *n0;
  PetscInt  *vdof_a, *vdof_b;
  PetscReal *tdir, *ndir;
  PetscInt   njoints, *joint; /* first reduction (4.4), optional: element e belongs to joint joint[e] and moves
                                 with the joint, the average of its members' relative motions */
  PetscReal *pos;              /* optional, 3 per element: where the element sits [m] (node-to-node: the pair's node);
                                  with -rom_joint_motion linear or mode it takes its joint's motion field there */
  PetscReal *phi;              /* optional, 2 per element: its tangential and normal motion in the stuck mode of
                                  interest (scaled), its other coordinates in the field with -rom_joint_motion mode */
  struct _JRElements *members; /* second reduction, optional: the joints' motions are those of these (node-to-node)
                                  elements' joints (members->joint), whose stuck springs also define a stuck basis;
                                  then the elements here need no DOFs (their rows are their joint's) */
} JRElements;

PETSC_EXTERN PetscFunctionList JRModelList;
PETSC_EXTERN PetscErrorCode JRModelRegister(const char[], PetscErrorCode (*)(JRModel));
PETSC_EXTERN PetscErrorCode JRModelCreate(MPI_Comm, JRModel *);
PETSC_EXTERN PetscErrorCode JRModelSetType(JRModel, JRModelType);
PETSC_EXTERN PetscErrorCode JRModelGetType(JRModel, JRModelType *);
PETSC_EXTERN PetscErrorCode JRModelSetFromOptions(JRModel);
PETSC_EXTERN PetscErrorCode JRModelSetUp(JRModel);
PETSC_EXTERN PetscErrorCode JRModelSetMatrices(JRModel, Mat, Mat, Mat);
PETSC_EXTERN PetscErrorCode JRModelSetElements(JRModel, const JRElements *);
PETSC_EXTERN PetscErrorCode JRModelGetMatrices(JRModel, Mat *, Mat *, Mat *);
PETSC_EXTERN PetscErrorCode JRModelGetNumDofs(JRModel, PetscInt *);
PETSC_EXTERN PetscErrorCode JRModelGetElements(JRModel, const JRElements **);
PETSC_EXTERN PetscErrorCode JRModelGetPairs(JRModel, const JRPairs **);
PETSC_EXTERN PetscErrorCode JRModelGetBolts(JRModel, const JRBolts **);
PETSC_EXTERN PetscErrorCode JRModelGetCoordinates(JRModel, Vec *);
PETSC_EXTERN PetscErrorCode JRModelGetDM(JRModel, DM *);
PETSC_EXTERN PetscErrorCode JRModelGetComm(JRModel, MPI_Comm *);
PETSC_EXTERN PetscErrorCode JRModelGetBoundingBox(JRModel, PetscReal[3], PetscReal[3]);
PETSC_EXTERN PetscErrorCode JRModelFindDof(JRModel, const PetscReal[3], PetscInt, PetscInt *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRModelGetRigidBasis(JRModel, PetscInt *, Vec[6]);
PETSC_EXTERN PetscErrorCode JRModelGetMass(JRModel, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRModelView(JRModel, PetscViewer);
PETSC_EXTERN PetscErrorCode JRModelDestroy(JRModel *);

/* ------------------------------------------------------------------------------------------ */
/* JRPreload: bolt preload, static frictionless contact analysis (prefix preload_)              */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRPreload *JRPreload;
typedef enum {
  JR_PRELOAD_PENALTY,
  JR_PRELOAD_AUGMENTED
} JRPreloadMethod;
PETSC_EXTERN const char *const JRPreloadMethods[];
typedef enum {
  JR_PRELOAD_SUPPORT_MINIMAL, /* 3-2-1: statically determinate */
  JR_PRELOAD_SUPPORT_CLAMP,   /* the end face x = 0 fixed ("fix-free") */
  JR_PRELOAD_SUPPORT_NONE     /* only JRPreloadAddSupport() */
} JRPreloadSupport;
PETSC_EXTERN const char *const JRPreloadSupports[];
/* Solvers of the contact problem (-preload_solver), registered types */
typedef const char *JRPreloadSolverType;
#define JRPRELOADCONDENSED "condensed" /* one factorisation of K, Newton on the interface's dense flexibility */
#define JRPRELOADFULL      "full"      /* Newton on all DOFs, a factorisation per change of the closed set */
PETSC_EXTERN PetscFunctionList JRPreloadSolverList;
PETSC_EXTERN PetscErrorCode JRPreloadSolverRegister(const char[], PetscErrorCode (*)(JRPreload));
PETSC_EXTERN PetscErrorCode JRPreloadSolverRegisterAll(void);
typedef struct {
  PetscInt  pairs, in_contact, bolts, newton, updates, factorisations;
  PetscReal total_force, bolt_force_sum;        /* sum of the pairs' normal loads, of the pretensions [N] */
  PetscReal contact_area, interface_area;       /* [m^2] */
  PetscReal peak_pressure, peak_force, gap_max; /* [Pa], [N], [m] */
  PetscReal penalty, max_penetration, time;     /* [N/m^3], [m], [s] */
  PetscBool loaded;                             /* read with -preload_load instead of solved */
} JRPreloadSummary;
PETSC_EXTERN PetscErrorCode JRPreloadCreate(MPI_Comm, JRPreload *);
PETSC_EXTERN PetscErrorCode JRPreloadSetModel(JRPreload, JRModel);
PETSC_EXTERN PetscErrorCode JRPreloadSetForces(JRPreload, PetscInt, const PetscReal[]);
PETSC_EXTERN PetscErrorCode JRPreloadSetExternalForce(JRPreload, Vec);
PETSC_EXTERN PetscErrorCode JRPreloadAddSupport(JRPreload, PetscInt, const PetscReal[3]);
PETSC_EXTERN PetscErrorCode JRPreloadSetFromOptions(JRPreload);
PETSC_EXTERN PetscErrorCode JRPreloadSetSolverType(JRPreload, JRPreloadSolverType);
PETSC_EXTERN PetscErrorCode JRPreloadGetSolverType(JRPreload, JRPreloadSolverType *);
PETSC_EXTERN PetscErrorCode JRPreloadSolve(JRPreload);
PETSC_EXTERN PetscErrorCode JRPreloadGetResults(JRPreload, PetscInt *, const PetscReal **, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRPreloadGetN0(JRPreload, PetscReal, PetscReal[]);
PETSC_EXTERN PetscErrorCode JRPreloadGetSolution(JRPreload, Vec *);
PETSC_EXTERN PetscErrorCode JRPreloadGetSummary(JRPreload, JRPreloadSummary *);
PETSC_EXTERN PetscErrorCode JRPreloadWrite(JRPreload, const char[], PetscBool);
PETSC_EXTERN PetscErrorCode JRPreloadView(JRPreload, PetscViewer);
PETSC_EXTERN PetscErrorCode JRPreloadDestroy(JRPreload *);

/* The node-to-node interface: one friction element per facing node pair (options -interface_*) */
typedef struct {
  PetscInt  element;                 /* -interface_element: 0 jenkins, 1 jenkins_nv */
  PetscReal kt, kn, mu, max_gap;     /* -interface_kt, -interface_kn [N/m], -interface_mu, -interface_max_gap [m] */
  PetscInt  split;                   /* -interface_split */
} JRInterfaceOptions;
PETSC_EXTERN PetscErrorCode JRInterfaceSetFromOptions(MPI_Comm, JRInterfaceOptions *);
PETSC_EXTERN PetscErrorCode JRInterfaceCreateElements(JRModel, JRPreload, const JRInterfaceOptions *, JRElements *, PetscInt **);
PETSC_EXTERN PetscErrorCode JRElementsDestroy(JRElements *);
PETSC_EXTERN PetscErrorCode JRElementsDuplicate(const JRElements *, JRElements *);
PETSC_EXTERN PetscErrorCode JRElementsCreateStuckStiffness(Mat, const JRElements *, Mat *, PetscReal *);

/* Reduced-order joints: second reduction (TAO fit of m elements per joint, options -rom_*), saved models */
/* The case a reduced model is for: the response of the mode of interest at each level, by energy balance at resonance */
typedef struct {
  PetscInt         nlev;
  const PetscReal *level;  /* excitation levels [N] */
  PetscReal        force;  /* |mode . force shape| per unit level */
  PetscReal        damp;   /* linear damping energy per cycle / (modal amplitude)^2 */
  const PetscReal *ujoint; /* each joint's (average) motion per unit modal amplitude [m] */
} JRROMCase;
/* The second reduction's fit options (prefix rom_), read once by JRROMFitSetFromOptions */
typedef struct {
  PetscReal fr[3];   /* -rom_fit_fractions */
  PetscReal efrom;   /* -rom_fit_energy_from */
  PetscBool refine;  /* -rom_fit_refine */
  PetscReal perturb; /* -rom_fit_perturb */
  PetscInt  ns;      /* -rom_fit_samples */
  PetscReal wcase;   /* -rom_fit_case_weight */
  PetscReal wtotal;  /* -rom_fit_total_weight */
  PetscReal wgross;  /* -rom_fit_gross_weight */
  PetscReal wstiff;  /* -rom_fit_stiffness_weight */
  PetscInt  npass;   /* -rom_fit_normal_passes */
  PetscInt  jmotion; /* -rom_joint_motion: 0 mean, 1 linear, 2 mode */
  PetscBool search;  /* -rom_fit_search */
} JRROMFit;
PETSC_EXTERN PetscErrorCode JRROMFitSetFromOptions(MPI_Comm, JRROMFit *);
PETSC_EXTERN PetscErrorCode JRROMReduce(MPI_Comm, const JRElements *, PetscInt, const PetscReal[], const JRROMCase *, const JRROMFit *, const char[], PetscBool, PetscBool, JRElements *);
PETSC_EXTERN PetscErrorCode JRROMSave(JRModel, const JRElements *, PetscReal, const char[]);
PETSC_EXTERN PetscErrorCode JRROMLoad(JRModel, const char[], JRElements *, PetscReal *);

/* ------------------------------------------------------------------------------------------ */
/* JRModes: mass-normalised modes of K phi = omega^2 M phi (SLEPc, prefix modes_)              */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRModes *JRModes;
PETSC_EXTERN PetscErrorCode JRModesCreate(MPI_Comm, JRModes *);
PETSC_EXTERN PetscErrorCode JRModesSetOperators(JRModes, Mat, Mat);
PETSC_EXTERN PetscErrorCode JRModesSetNumber(JRModes, PetscInt);
PETSC_EXTERN PetscErrorCode JRModesSetRigidBasis(JRModes, PetscInt, Vec[]);
PETSC_EXTERN PetscErrorCode JRModesSetCoordinates(JRModes, Vec);
PETSC_EXTERN PetscErrorCode JRModesSetSignature(JRModes, PetscReal);
PETSC_EXTERN PetscErrorCode JRModesGetVecs(JRModes, Vec **);
PETSC_EXTERN PetscErrorCode JRModesGetNumRigid(JRModes, PetscInt *);
PETSC_EXTERN PetscErrorCode JRModesSetFromOptions(JRModes);
PETSC_EXTERN PetscErrorCode JRModesSolve(JRModes);
PETSC_EXTERN PetscErrorCode JRModesGetNumber(JRModes, PetscInt *);
PETSC_EXTERN PetscErrorCode JRModesGetEigenvalues(JRModes, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRModesGetRows(JRModes, PetscInt, const PetscInt[], PetscReal[]);
PETSC_EXTERN PetscErrorCode JRModesProject(JRModes, Mat, PetscReal[]);
PETSC_EXTERN PetscErrorCode JRModesView(JRModes, PetscViewer);
PETSC_EXTERN PetscErrorCode JRModesSetSaveDefault(JRModes, const char[]);
PETSC_EXTERN PetscErrorCode JRModesSetMixed(JRModes);
PETSC_EXTERN PetscErrorCode JRModesMix(JRModes, Mat, PetscInt, PetscInt, Vec[]);
PETSC_EXTERN PetscErrorCode JRModesSetInterface(JRModes, PetscInt, PetscInt, const PetscInt[], const PetscReal[], const PetscReal[]);
PETSC_EXTERN PetscErrorCode JRModesCheckBasis(JRModes);
PETSC_EXTERN PetscErrorCode JRModesGetBasisCheck(JRModes, PetscReal *, PetscReal *, PetscReal *, PetscInt *, PetscLogDouble *);
PETSC_EXTERN PetscErrorCode JRModesReference(JRModes);
PETSC_EXTERN PetscErrorCode JRModesDestroy(JRModes *);

/* ------------------------------------------------------------------------------------------ */
/* JRHBM: harmonic balance in modal coordinates (thesis 2.18, H harmonics + mean), SNES hbm_     */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRHBM *JRHBM;
typedef enum {
  JR_HBM_JACOBIAN_ANALYTIC,
  JR_HBM_JACOBIAN_FD
} JRHBMJacobianType;
PETSC_EXTERN const char *const JRHBMJacobianTypes[];
typedef enum {
  JR_HBM_BASIS_FREE,  /* the modes of K: the interface held by the bolts only */
  JR_HBM_BASIS_STUCK, /* the modes of K plus every element in contact at rest stuck */
  JR_HBM_BASIS_MIXED  /* Ritz vectors of the stuck structure in the span of the stuck and free-interface modes */
} JRHBMBasis;
PETSC_EXTERN const char *const JRHBMBases[];
/* -rom_joint_motion: how a joint's members move in the first reduction (4.4) */
typedef enum {
  JR_JOINT_MOTION_MEAN,   /* the joint's mean motion (the thesis) */
  JR_JOINT_MOTION_LINEAR, /* a linear field over the members' positions (JRElements pos) */
  JR_JOINT_MOTION_MODE    /* ... and over their motions in the stuck mode of interest (JRElements phi) */
} JRJointMotion;
PETSC_EXTERN const char *const JRJointMotions[];

PETSC_EXTERN PetscErrorCode JRHBMCreate(MPI_Comm, JRHBM *);
PETSC_EXTERN PetscErrorCode JRHBMSetModel(JRHBM, JRModel);
PETSC_EXTERN PetscErrorCode JRHBMSetElements(JRHBM, const JRElements *);
PETSC_EXTERN PetscErrorCode JRHBMGetElements(JRHBM, const JRElements **);
PETSC_EXTERN PetscErrorCode JRHBMSetFromOptions(JRHBM);
PETSC_EXTERN PetscErrorCode JRHBMSetUp(JRHBM);
PETSC_EXTERN PetscErrorCode JRHBMGetSizes(JRHBM, PetscInt *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMGetSolveSize(JRHBM, PetscInt *, const char **);
PETSC_EXTERN PetscErrorCode JRHBMExpand(JRHBM, PetscReal, Vec, Vec);
PETSC_EXTERN PetscErrorCode JRHBMSetForceLevel(JRHBM, PetscReal);
PETSC_EXTERN PetscErrorCode JRHBMGetModalFrequencies(JRHBM, PetscInt *, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRHBMComputeResidual(JRHBM, PetscReal, Vec, Vec);
PETSC_EXTERN PetscErrorCode JRHBMComputeJacobian(JRHBM, PetscReal, Vec, Mat, Vec);
PETSC_EXTERN PetscErrorCode JRHBMCreateVecs(JRHBM, Vec *, Mat *);
PETSC_EXTERN PetscErrorCode JRHBMSolve(JRHBM, PetscReal, Vec, PetscInt *, PetscBool *);
PETSC_EXTERN PetscErrorCode JRHBMSolveResidual(JRHBM, PetscReal, Vec, PetscInt *, PetscBool *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMResidualNorm(JRHBM, Vec, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMGetResidualTolerance(JRHBM, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMLinearSolution(JRHBM, PetscReal, Vec);
PETSC_EXTERN PetscErrorCode JRHBMGetSNES(JRHBM, SNES *);
PETSC_EXTERN PetscErrorCode JRHBMGetJacobianType(JRHBM, JRHBMJacobianType *);
PETSC_EXTERN PetscErrorCode JRHBMGetElementTime(JRHBM, PetscLogDouble *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMGetOutputs(JRHBM, PetscInt *, const PetscInt **);
PETSC_EXTERN PetscErrorCode JRHBMResponse(JRHBM, Vec, PetscReal[], PetscReal[], PetscReal[]);
PETSC_EXTERN PetscErrorCode JRHBMEnergy(JRHBM, PetscReal, Vec, PetscReal *, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMContactStates(JRHBM, Vec, PetscInt[4]);
PETSC_EXTERN PetscErrorCode JRHBMElementStates(JRHBM, Vec, JRContactState[]);
PETSC_EXTERN PetscErrorCode JRHBMKineticEnergy(JRHBM, PetscReal, Vec, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMSetExcitationDof(JRHBM, PetscInt, PetscInt, const PetscInt[]);
PETSC_EXTERN PetscErrorCode JRHBMSetOutputPoints(JRHBM, PetscInt, const PetscReal[], PetscInt);
PETSC_EXTERN PetscErrorCode JRHBMGetOutputPoints(JRHBM, const PetscReal **, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMMatchStickFrequency(JRHBM, PetscInt, PetscReal, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMStuckModeMotion(JRHBM, PetscInt, PetscReal[], PetscReal[]);
PETSC_EXTERN PetscErrorCode JRHBMStuckModeBalance(JRHBM, PetscInt, PetscReal *, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMSetModes(JRHBM, JRHBM);
PETSC_EXTERN PetscErrorCode JRHBMSetBasis(JRHBM, JRHBMBasis);
PETSC_EXTERN PetscErrorCode JRHBMSetJointMotion(JRHBM, JRJointMotion);
PETSC_EXTERN PetscErrorCode JRHBMSetOptionsPrefix(JRHBM, const char[]);
PETSC_EXTERN PetscErrorCode JRHBMGetOptionsPrefix(JRHBM, const char **);
PETSC_EXTERN PetscErrorCode JRHBMSetModesFile(JRHBM, const char[]);
PETSC_EXTERN PetscErrorCode JRHBMGetBasis(JRHBM, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMGetBasisCheck(JRHBM, PetscReal *, PetscReal *, PetscReal *, PetscInt *, PetscLogDouble *);
PETSC_EXTERN PetscErrorCode JRHBMStickFrequencies(JRHBM, PetscInt *, PetscReal[]);
PETSC_EXTERN PetscErrorCode JRHBMGetDampingDescription(JRHBM, const char **);
PETSC_EXTERN PetscErrorCode JRHBMView(JRHBM, PetscViewer);
PETSC_EXTERN PetscErrorCode JRHBMDestroy(JRHBM *);
/* the extended periodic motion concept's autonomous system (src/hbm/epmc.c): unknowns [a | w | xi] */
PETSC_EXTERN PetscErrorCode JRHBMSetEPMC(JRHBM, PetscInt, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMGetEPMCMode(JRHBM, PetscReal *, const PetscReal **, PetscReal *);
PETSC_EXTERN PetscErrorCode JRHBMComputeEPMC(JRHBM, PetscReal, Vec, Vec, Mat);
PETSC_EXTERN PetscErrorCode JRHBMEPMCWork(JRHBM, PetscReal, PetscReal, Vec, PetscReal *);
/* Stability by Hill's method (src/hbm/hill.c): which 2 nm of the 2 nm (2H + 1) exponents are the physical ones */
typedef enum {
  JR_HILL_SELECT_VECTOR, /* eigenvectors centred on the mean harmonic (symmetry criterion) */
  JR_HILL_SELECT_IMAG    /* |Im lambda| <= w / 2 (the fundamental strip) */
} JRHillSelect;
PETSC_EXTERN const char *const JRHillSelects[];
PETSC_EXTERN PetscErrorCode JRHBMFloquet(JRHBM, PetscReal, Vec, JRHillSelect, PetscInt, PetscInt *, PetscReal[], PetscReal[], PetscReal *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRHBMHillSupported(JRHBM, PetscBool *);

/* ------------------------------------------------------------------------------------------ */
/* JRReduce: reduced-order joints, the first and the second reduction (prefix rom_)            */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRReduce *JRReduce;
PETSC_EXTERN PetscErrorCode JRReduceCreate(MPI_Comm, JRReduce *);
PETSC_EXTERN PetscErrorCode JRReduceSetFromOptions(JRReduce);
PETSC_EXTERN PetscErrorCode JRReduceGetRequest(JRReduce, PetscBool *, PetscInt *, PetscInt *, const char **, const char **);
PETSC_EXTERN PetscErrorCode JRReduceSetCase(JRReduce, PetscReal, PetscReal, PetscInt, const PetscReal[]);
PETSC_EXTERN PetscErrorCode JRReduceSetExcitation(JRReduce, PetscInt, PetscInt, const PetscInt[]);
PETSC_EXTERN PetscErrorCode JRReduceSetOutput(JRReduce, const char[], PetscBool);
PETSC_EXTERN PetscErrorCode JRReduceAssignJoints(JRReduce, JRModel, JRElements *, const PetscInt[]);
PETSC_EXTERN PetscErrorCode JRReduceSetUp(JRReduce, JRModel, JRHBM, JRElements *, JRElements *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRReduceCreateHBM(JRReduce, JRModel, JRHBM, PetscBool, JRElements *, JRHBM *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRReduceSave(JRReduce, JRModel, const JRElements *);
PETSC_EXTERN PetscErrorCode JRReduceLoad(JRReduce, JRModel, JRElements *);
PETSC_EXTERN PetscErrorCode JRReduceGetStiffnessCorrection(JRReduce, PetscReal *);
PETSC_EXTERN PetscErrorCode JRReduceView(JRReduce, PetscViewer);
PETSC_EXTERN PetscErrorCode JRReduceDestroy(JRReduce *);

/* ------------------------------------------------------------------------------------------ */
/* JRCont: frequency-response curves by continuation (thesis 2.4.2-2.4.3), several force levels */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRCont *JRCont;
typedef const char       *JRContType;
#define JRCONTNATURAL   "natural"   /* natural-parameter: step in frequency (2.4.2) */
#define JRCONTARCLENGTH "arclength" /* pseudo-arclength: passes turning points (2.4.3) */
/* The arclength type's constraint (-cont_constraint): orthogonal to the tangent, or the sphere (2.28) */
typedef enum {
  JR_CONT_PSEUDO,
  JR_CONT_SPHERE
} JRContConstraint;
PETSC_EXTERN const char *const JRContConstraints[];

PETSC_EXTERN PetscFunctionList JRContList;
PETSC_EXTERN PetscErrorCode JRContRegister(const char[], PetscErrorCode (*)(JRCont));
PETSC_EXTERN PetscErrorCode JRContRegisterAll(void);

PETSC_EXTERN PetscErrorCode JRContCreate(MPI_Comm, JRCont *);
PETSC_EXTERN PetscErrorCode JRContSetType(JRCont, JRContType);
PETSC_EXTERN PetscErrorCode JRContGetType(JRCont, JRContType *);
PETSC_EXTERN PetscErrorCode JRContSetHBM(JRCont, JRHBM);
PETSC_EXTERN PetscErrorCode JRContSetFromOptions(JRCont);
PETSC_EXTERN PetscErrorCode JRContSetStepBounds(JRCont, PetscReal, PetscReal);
PETSC_EXTERN PetscErrorCode JRContSetRange(JRCont, PetscReal, PetscReal);
PETSC_EXTERN PetscErrorCode JRContGetRange(JRCont, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRContSetOutputBase(JRCont, const char[]);
PETSC_EXTERN PetscErrorCode JRContSetLevels(JRCont, PetscInt, const PetscReal[]);
PETSC_EXTERN PetscErrorCode JRContCheckComplete(JRCont);
PETSC_EXTERN PetscErrorCode JRContGetLevelComplete(JRCont, PetscInt, PetscBool *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRContSolve(JRCont);
PETSC_EXTERN PetscErrorCode JRContSetQuiet(JRCont, PetscBool);
PETSC_EXTERN PetscErrorCode JRContGetNumLevels(JRCont, PetscInt *);
PETSC_EXTERN PetscErrorCode JRContGetBranch(JRCont, PetscInt, PetscInt *, const PetscReal **, const PetscReal **, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRContGetPeak(JRCont, PetscInt, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRContGetLevel(JRCont, PetscInt, PetscReal *);
PETSC_EXTERN PetscErrorCode JRContGetPeakStates(JRCont, PetscInt, const JRContactState **);
PETSC_EXTERN PetscErrorCode JRContGetDamping(JRCont, PetscInt, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRContGetLevelStats(JRCont, PetscInt, PetscReal *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRContGetStability(JRCont, PetscInt, const PetscInt **, const PetscReal **, PetscInt *, const PetscReal **, PetscInt *, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRContWrite(JRCont);
PETSC_EXTERN PetscErrorCode JRContDestroy(JRCont *);

/* ------------------------------------------------------------------------------------------ */
/* JRNLModes: nonlinear modes by the extended periodic motion concept (EPMC), backbones of      */
/* frequency and damping ratio against amplitude, options -nlm_*                               */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRNLModes *JRNLModes;
PETSC_EXTERN PetscErrorCode JRNLModesCreate(MPI_Comm, JRNLModes *);
PETSC_EXTERN PetscErrorCode JRNLModesSetHBM(JRNLModes, JRHBM);
PETSC_EXTERN PetscErrorCode JRNLModesSetFromOptions(JRNLModes);
PETSC_EXTERN PetscErrorCode JRNLModesGetOutputBase(JRNLModes, const char **);
PETSC_EXTERN PetscErrorCode JRNLModesSetUp(JRNLModes);
PETSC_EXTERN PetscErrorCode JRNLModesSolve(JRNLModes);
PETSC_EXTERN PetscErrorCode JRNLModesGetBackbone(JRNLModes, PetscInt *, const PetscReal **, const PetscReal **, const PetscReal **, const PetscReal **, const PetscReal **);
PETSC_EXTERN PetscErrorCode JRNLModesGetStats(JRNLModes, PetscReal *, PetscInt *, PetscBool *);
PETSC_EXTERN PetscErrorCode JRNLModesWrite(JRNLModes);
PETSC_EXTERN PetscErrorCode JRNLModesView(JRNLModes, PetscViewer);
PETSC_EXTERN PetscErrorCode JRNLModesDestroy(JRNLModes *);

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

/* ------------------------------------------------------------------------------------------ */
/* JRPost: contact maps at the peaks and the comparison of two models (BASE = -frf_output_file) */
/* ------------------------------------------------------------------------------------------ */
typedef struct _p_JRPost *JRPost;
/* The wall times [s] of -task compare: the two solves, their parts in the contact elements, the two set-ups, the
   reduction */
typedef struct {
  PetscReal n2n_solve, rom_solve, n2n_elements, rom_elements, n2n_setup, rom_setup, reduction;
} JRCompareTimes;
PETSC_EXTERN PetscErrorCode JRPostCreate(MPI_Comm, JRPost *);
PETSC_EXTERN PetscErrorCode JRPostSetOutput(JRPost, const char[], PetscBool);
PETSC_EXTERN PetscErrorCode JRPostWriteContactMaps(JRPost, JRModel, JRCont, const JRElements *, const PetscInt[]);
PETSC_EXTERN PetscErrorCode JRPostCompareReport(JRPost, JRCont, JRCont, const JRElements *, const JRElements *, const JRCompareTimes *);
PETSC_EXTERN PetscErrorCode JRPostModesTable(JRPost, JRModes);
PETSC_EXTERN PetscErrorCode JRPostWriteModes(JRPost, JRModel, JRModes, PetscInt);
PETSC_EXTERN PetscErrorCode JRPostDestroy(JRPost *);

/* ------------------------------------------------------------------------------------------ */
/* Small utilities                                                                            */
/* ------------------------------------------------------------------------------------------ */
/* CSV tables with a header line; columns looked up by name */
typedef struct _p_JRTable *JRTable;
PETSC_EXTERN PetscErrorCode JRTableRead(MPI_Comm, const char[], JRTable *);
PETSC_EXTERN PetscErrorCode JRTableGetSize(JRTable, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode JRTableGetColumn(JRTable, const char[], PetscBool, PetscReal, PetscReal[]);
PETSC_EXTERN PetscErrorCode JRTableHasColumn(JRTable, const char[], PetscBool *);
PETSC_EXTERN PetscErrorCode JRTableGetString(JRTable, const char[], PetscInt, const char **);
PETSC_EXTERN PetscErrorCode JRTableGetLine(JRTable, PetscInt, PetscInt *);
PETSC_EXTERN PetscErrorCode JRTableGetHeader(JRTable, PetscInt, const char **);
PETSC_EXTERN PetscErrorCode JRTableGetFileName(JRTable, const char **);
PETSC_EXTERN PetscErrorCode JRTableDestroy(JRTable *);

/* Matrices and vectors from files: .mtx (Matrix Market), .bin (PETSc binary), .h5 (MATLAB v7.3 sparse) */
PETSC_EXTERN PetscErrorCode JRMatLoadFile(MPI_Comm, const char[], const char[], Mat *);
PETSC_EXTERN PetscErrorCode JRMatSaveFile(Mat, const char[], const char[]);
PETSC_EXTERN PetscErrorCode JRVecLoadFile(MPI_Comm, const char[], PetscInt, PetscReal[]);
PETSC_EXTERN PetscErrorCode JRFileCheckHDF5(MPI_Comm, const char[], const char[], const char[], const char[]);

/* Write a file atomically: open a temporary beside it, rename on close. Temporary names come from
   JRFileTempName (registered: removed if the run is stopped by SIGTERM, SIGINT or SIGHUP) and are
   released by JRFileTempDone once renamed or removed (JRFileRename, JRFileCommit do it) */
PETSC_EXTERN PetscErrorCode JRFileTempName(MPI_Comm, const char[], char[], size_t);
PETSC_EXTERN PetscErrorCode JRFileTempDone(const char[]);
PETSC_EXTERN PetscErrorCode JRFileRename(MPI_Comm, const char[], const char[]);
PETSC_EXTERN PetscErrorCode JRFileOpenTemp(MPI_Comm, const char[], FILE **, char[], size_t);
PETSC_EXTERN PetscErrorCode JRFileCommit(MPI_Comm, FILE **, const char[], const char[]);
PETSC_EXTERN PetscErrorCode JRViewerHDF5WriteRank0(MPI_Comm, PetscViewer, const char[], PetscInt, PetscInt, const PetscReal[], const PetscInt[]);

/* Newton's method for small dense systems on one rank: LAPACK LU, backtracking (src/hbm/newtondense.c); the
   default of the harmonic-balance and continuation solvers (-hbm_snes_type) */
#define SNESNEWTONDENSE "newtondense"
PETSC_EXTERN PetscErrorCode SNESCreate_NewtonDense(SNES);
PETSC_EXTERN PetscErrorCode JRDenseSolve(PetscInt, const PetscScalar *, PetscInt, PetscScalar *, PetscBLASInt *, PetscScalar *, PetscBool *);

/* A dense matrix written through its array: assembled once; later writes only raise its state (MatDenseRestoreArray),
   which is what a factorisation checks (MatAssemblyEnd's per-call options lookups cost more than a 19 x 19 LU) */
PETSC_EXTERN PetscErrorCode JRMatDenseAssemble(Mat);

/* 64-byte aligned allocations (whole cache lines) for large SoA batches */
PETSC_EXTERN PetscErrorCode JRMallocAligned(size_t, void *);
PETSC_EXTERN PetscErrorCode JRFreeAligned(void *);

/* Run a gnuplot script from share/ to make a PNG (temporary name, then rename) */
PETSC_EXTERN PetscErrorCode JRPlot(MPI_Comm, const char[], const char[], const char[], PetscBool *);

/* User errors: one message, once, without PETSc's traceback (src/sys/error.c); exit status of a failed run */
PETSC_EXTERN PetscErrorCode JRErrorHandlerPush(void);
PETSC_EXTERN int            JRErrorExit(PetscErrorCode);
PETSC_EXTERN PetscErrorCode JRErrorContextPush(const char[]);
PETSC_EXTERN PetscErrorCode JRErrorContextPop(void);
PETSC_EXTERN PetscErrorCode JRErrorCatchPush(void);
PETSC_EXTERN PetscErrorCode JRErrorCatchPop(char[], size_t);
/* Options nothing read: an error before the work (jointrom's own), a warning at the end (src/sys/options.c) */
PETSC_EXTERN PetscErrorCode JROptionsCheck(MPI_Comm, const char[]);
PETSC_EXTERN PetscErrorCode JROptionsCheckValues(MPI_Comm);
PETSC_EXTERN PetscErrorCode JROptionsWarnUnused(MPI_Comm);
PETSC_EXTERN PetscErrorCode JROptionsHelpSolvers(MPI_Comm, PetscBool, PetscBool, PetscBool, PetscBool);
/* The directory of an output base name exists (created if missing) and is writable, else an error naming option */
PETSC_EXTERN PetscErrorCode JRFileCheckOutput(MPI_Comm, const char[], const char[]);

/* Driver tasks */
PETSC_EXTERN PetscErrorCode JRTaskElement(MPI_Comm);
PETSC_EXTERN PetscErrorCode JRTaskFRF(MPI_Comm);
PETSC_EXTERN PetscErrorCode JRTaskCompare(MPI_Comm);
PETSC_EXTERN PetscErrorCode JRTaskNLModes(MPI_Comm);
PETSC_EXTERN PetscErrorCode JRTaskModes(MPI_Comm);
PETSC_EXTERN PetscErrorCode JRTaskPreload(MPI_Comm);

#endif
