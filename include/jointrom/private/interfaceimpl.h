/* JRInterface: the node-to-node interface, private struct */
#if !defined(JOINTROM_INTERFACEIMPL_H)
#define JOINTROM_INTERFACEIMPL_H
#include <jointrom/private/modelimpl.h>

struct _p_JRInterface {
  MPI_Comm   comm;
  char      *prefix;            /* options prefix before interface_ (NULL: none) */
  PetscInt   element;           /* -interface_element: 0 jenkins, 1 jenkins_nv */
  PetscReal  kt, kn, mu;        /* -interface_kt, -interface_kn [N/m], -interface_mu */
  PetscReal  max_gap;           /* -interface_max_gap [m] (negative: keep every pair) */
  PetscInt   split;             /* -interface_split */
  PetscBool  setup;
  JRElements el;                /* the elements (JRInterfaceSetUp) */
  PetscInt  *pair;              /* each element's node pair */
};
#endif
