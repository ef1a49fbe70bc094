/* JRModel: the linear structure (K, M, optional C), its interface pairs, bolts and contact elements */
#if !defined(JOINTROM_MODEL_H)
#define JOINTROM_MODEL_H

#include <jointrom/contact.h>

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

#define JR_NREL 6 /* released modes at most (-rom_release_fractions) */

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
  PetscReal *phir;             /* optional, JR_NREL per element: its tangential motion in the released modes (the
                                  stuck structure with the members that slip first freed; scaled), its further
                                  coordinates in the field with -rom_joint_motion shapes (0: none in its joint) */
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
PETSC_EXTERN PetscErrorCode JRModelGetNaturalOrdering(JRModel, IS *);
PETSC_EXTERN PetscErrorCode JRModelDOFsToNatural(JRModel, PetscInt, const PetscInt[], PetscInt[]);
PETSC_EXTERN PetscErrorCode JRModelDOFsFromNatural(JRModel, PetscInt, const PetscInt[], PetscInt[]);
PETSC_EXTERN PetscErrorCode JRElementsDestroy(JRElements *);
PETSC_EXTERN PetscErrorCode JRElementsDuplicate(const JRElements *, JRElements *);
PETSC_EXTERN PetscErrorCode JRElementsCreateStuckStiffness(Mat, const JRElements *, Mat *);
PETSC_EXTERN PetscErrorCode JRElementsStuckSignature(JRModel, const JRElements *, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRModelGetBoundingBox(JRModel, PetscReal[3], PetscReal[3]);
PETSC_EXTERN PetscErrorCode JRModelFindDof(JRModel, const PetscReal[3], PetscInt, PetscInt *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRModelGetRigidBasis(JRModel, PetscInt *, Vec[6]);
PETSC_EXTERN PetscErrorCode JRModelGetMass(JRModel, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode JRModelView(JRModel, PetscViewer);
PETSC_EXTERN PetscErrorCode JRModelDestroy(JRModel *);

#endif
