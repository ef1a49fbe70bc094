/* JRPost: contact maps at the peaks, mode files and the comparison of two models */
#if !defined(JOINTROM_POST_H)
#define JOINTROM_POST_H

#include <jointrom/verify.h>

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
PETSC_EXTERN PetscErrorCode JRPostCompareJoints(JRPost, JRCont, JRCont, const JRElements *, const JRElements *);
PETSC_EXTERN PetscErrorCode JRPostCompareBackbones(JRPost, JRNLModes, JRNLModes);
PETSC_EXTERN PetscErrorCode JRPostModesTable(JRPost, JRModes);
PETSC_EXTERN PetscErrorCode JRPostWriteModes(JRPost, JRModel, JRModes, PetscInt);
PETSC_EXTERN PetscErrorCode JRPostWriteCurves(JRPost, JRCont);
/* XDMF files for ParaView (src/post/xdmf.c): grids of an HDF5 file, a DM's hexahedra or points, with nodal fields */
typedef struct {
  const char *name;    /* as ParaView shows it */
  const char *dataset; /* its HDF5 path */
  PetscInt    ncomp;   /* 1 (scalar) or 3 (vector) per node */
} JRXdmfField;
typedef struct {
  const char        *name;
  DM                 dm;       /* the mesh's hexahedra (/viz/topology/cells, /geometry/vertices), or NULL: points */
  PetscInt           npoints;  /* points: how many, */
  const char        *geometry; /* and the dataset of their x, y, z */
  PetscInt           nfields;
  const JRXdmfField *fields;
} JRXdmfGrid;
PETSC_EXTERN PetscErrorCode JRXdmfWrite(MPI_Comm, const char[], const char[], PetscInt, const JRXdmfGrid[]);
PETSC_EXTERN PetscErrorCode JRPostDestroy(JRPost *);

#endif
