/* Private: the finite-element models (beam, lap-joint presets, Gmsh import) built on DMPlex + PetscFE. */
#if !defined(JOINTROM_FEIMPL_H)
#define JOINTROM_FEIMPL_H

#include <jointrom/private/modelimpl.h>
#include <petscdmplex.h>
#include <petscds.h>

/* label names and values used on the DMPlex */
#define JR_LABEL_BODY    "jr_body"    /* cells: 1 = beam A (or the only beam), 2 = beam B */
#define JR_LABEL_CONTACT "jr_contact" /* faces: 1 = contact surface of A, 2 = of B */
#define JR_LABEL_BOLT    "jr_bolt"    /* faces: 2i+1 = head footprint of bolt i, 2i+2 = nut footprint */
#define JR_LABEL_CLAMP   "jr_clamp"   /* faces: 1 = the end x = 0 (clamped with -model_clamp) */

typedef struct {
  PetscReal x[3];  /* centre of the shank at the head-side face */
  PetscReal axis;  /* shank length along -z from the head face to the nut face [m] */
  PetscReal d;     /* shank diameter [m] */
  PetscInt  nhead, nnut; /* footprint nodes (all ranks) */
} JRBolt;

typedef struct {
  /* geometry and mesh parameters (SI) */
  PetscReal  L1, L2, W, H, Llap, pitch, dbolt, dhole, dwasher, h, grade, hz; /* hz: lap's size through the height, 0: h */
  PetscInt   nbolts, order;
  PetscReal  E, nu, rho, pairtol;
  PetscBool  clamp, lap;        /* clamp x = 0; the geometry has a lap joint */
  PetscBool  rigidtie;          /* bolt ends tie their footprints rigidly (else: distributing, RBE3-like) */
  PetscBool  tied;              /* the interface pairs tied (a stuck interface) instead of free */
  PetscBool  petscfe;           /* assemble with PETSc's generic PetscFE integration instead of the Q2 kernel */
  PetscReal  memlimit;          /* memory a generated mesh's model may need [GiB] (-model_memory_limit; 0: available) */
  char       file[PETSC_MAX_PATH_LEN];
  char       tangent[8];
  /* the discretisation */
  DM         dm;
  PetscReal  volume, mass;
  PetscInt   nnodes;            /* DOF points (nodes) over all ranks */
  PetscInt   nbolt_alloc;
  JRBolt    *bolt;
  PetscInt   ncontact[2];       /* nodes on each contact surface */
  PetscReal  pairgap;           /* largest distance between the two nodes of a pair [m] */
  PetscReal  contact_area;      /* area of contact surface A [m^2] */
  PetscInt  *orig;              /* each local mesh point's number in the mesh as built, before it was distributed */
} Model_FE;

/* -model_bolt_tie rigid and -model_interface tied: penalty stiffness, times E and a length of the footprint
   or of the area per pair (about 100 times a node's stiffness: frequencies within 1e-4 of a perfectly rigid
   tie, K's conditioning spared) */
#define JR_TIE_PENALTY 1e2

/* a dense stiffness block over arbitrary global DOFs (every rank holds all blocks; each adds its own rows) */
typedef struct {
  PetscInt   n, *dof;
  PetscReal *Kf; /* n x n, row-major */
} JRFEDenseBlock;

/* the size of a generated mesh's model, estimated from the mesh parameters before the mesh is built */
typedef struct {
  PetscReal cells, nodes, dofs, nnz; /* nnz: of K (and of M) */
  PetscReal km, total;               /* bytes: K and M; all, with the eigensolver's shifted matrix and factorisation */
} JRFEMeshSize;

/* the mesh: geometry.c, gmsh.c */
PETSC_INTERN PetscErrorCode JRFEMeshEstimate(const Model_FE *, PetscBool, JRFEMeshSize *);
PETSC_INTERN PetscErrorCode JRFEMeshCheckMemory(MPI_Comm, const Model_FE *, PetscBool);
PETSC_INTERN PetscErrorCode JRFEGeometryBeam(MPI_Comm, Model_FE *, DM *);
PETSC_INTERN PetscErrorCode JRFEGeometryLap(MPI_Comm, Model_FE *, DM *);
PETSC_INTERN PetscErrorCode JRFEGeometryGmsh(MPI_Comm, Model_FE *, DM *);
PETSC_INTERN PetscErrorCode JRFEDistribute(Model_FE *, DM *);
/* the set-up: fe.c, and its steps in assemble.c, bolts.c, pairs.c */
PETSC_INTERN PetscErrorCode JRFESetUp(JRModel, Model_FE *);
PETSC_INTERN PetscErrorCode JRFEDiscretise(MPI_Comm, Model_FE *);
PETSC_INTERN PetscErrorCode JRFEAssemble(JRModel, Model_FE *);
PETSC_INTERN PetscErrorCode JRFEAddBolts(JRModel, Model_FE *);
PETSC_INTERN PetscErrorCode JRFEAddDenseBlocks(JRModel, PetscInt, JRFEDenseBlock *);
PETSC_INTERN PetscErrorCode JRFEFindPairs(JRModel, Model_FE *);
PETSC_INTERN PetscErrorCode JRFETieInterface(JRModel, Model_FE *);
/* nodes: nodes.c */
PETSC_INTERN PetscErrorCode JRFERigidBasis(DM, Vec[6]);
PETSC_INTERN PetscErrorCode JRFECellCentre(DM, PetscInt, PetscReal[3]);

/* nodes (DOF points) on a labelled face set: coordinates (3 each) and global DOF indices (3 each),
   gathered on every rank, duplicates removed, sorted by global DOF */
PETSC_INTERN PetscErrorCode JRFEFaceNodes(DM, const char *, PetscInt, PetscInt *, PetscReal **, PetscInt **);
/* the same with each node's area weight (free x, dof with PetscFree2, w with PetscFree) */
PETSC_INTERN PetscErrorCode JRFEFaceNodeAreas(DM, const char *, PetscInt, PetscInt *, PetscReal **, PetscInt **, PetscReal **);
PETSC_INTERN PetscErrorCode JRFENodalCoordinates(DM, Vec);
PETSC_INTERN PetscErrorCode JRFENaturalOrdering(DM, const PetscInt *, IS *);

#endif
