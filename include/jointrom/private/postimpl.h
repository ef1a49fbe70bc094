/* JRPost: the outputs beside the curves, private struct */
#if !defined(JOINTROM_POSTIMPL_H)
#define JOINTROM_POSTIMPL_H
#include <jointrom.h>

struct _p_JRPost {
  MPI_Comm  comm;
  char      base[PETSC_MAX_PATH_LEN]; /* output base name ("" for no files) */
  PetscBool plot;                     /* draw the PNGs */
};
#endif
