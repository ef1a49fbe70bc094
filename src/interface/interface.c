/*
   JRInterface, the node-to-node interface (pipeline stage 4): one friction element per facing node pair of an FE
   model, its normal load from the bolt preload.

     JRInterfaceCreate -> JRInterfaceSetOptionsPrefix -> JRInterfaceSetFromOptions -> JRInterfaceSetUp(model, preload)
     -> JRInterfaceGetElements -> JRInterfaceView -> JRInterfaceDestroy

   Element e joins pair p = pair[e]: tangential relative motion u = (x_A - x_B) . t_p along the beam axis,
   normal v = (x_A - x_B) . n_p (positive presses the surfaces together), projection rows
   (phi_A - phi_B) . dir (4.3) formed by JRHBM. Options (prefix <prefix>interface_):
     -interface_element jenkins | jenkins_nv   constant normal load (ch. 4) or with its variation (5.1)
     -interface_kt [N/m]  tangential stiffness per element (thesis BRB: 1000 N/mm = 1e6 N/m)
     -interface_kn [N/m]  normal stiffness per element (jenkins_nv; default kt)
     -interface_mu [-]    friction coefficient
     -interface_max_gap [m] jenkins_nv: leave out pairs whose preload gap is larger (default: keep all)
     -interface_split k   every element as k identical elements in parallel (kt/k, kn/k, n0/k): the same
                          forces, k times the work; for benchmarks of large interfaces
   jenkins elements are made only for the pairs in contact after the preload (N_static > 0): an open pair
   carries no friction. jenkins_nv elements get n0 = N_static - kn v_gap (5.1): gaps as negative loads.
*/
#include <jointrom/private/interfaceimpl.h>

/* JRInterfaceCreate - an interface with the defaults: jenkins elements, kt 1e6 N/m, mu 0.12 */
PetscErrorCode JRInterfaceCreate(MPI_Comm comm, JRInterface *itf)
{
  JRInterface t;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&t));
  t->comm    = comm;
  t->element = 0;
  t->kt      = 1e6;
  t->kn      = -1;
  t->mu      = 0.12;
  t->max_gap = -1;
  t->split   = 1;
  *itf       = t;
  PetscFunctionReturn(0);
}

/* JRInterfaceSetOptionsPrefix - the prefix of the interface's options (before interface_), as the owner sets it */
PetscErrorCode JRInterfaceSetOptionsPrefix(JRInterface itf, const char prefix[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(itf->prefix));
  if (prefix && prefix[0]) PetscCall(PetscStrallocpy(prefix, &itf->prefix));
  PetscFunctionReturn(0);
}

/*
  JRInterfaceSetFromOptions - the interface's options, read and checked once, before any work: -interface_element,
  -interface_kt, -interface_kn, -interface_mu, -interface_split, -interface_max_gap
*/
PetscErrorCode JRInterfaceSetFromOptions(JRInterface itf)
{
  const char *types[] = {JRCONTACTJENKINS, JRCONTACTJENKINSNV};
  MPI_Comm    comm    = itf->comm;
  char        pre[256];
  PetscReal   kn      = itf->kn;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(pre, sizeof(pre), "%sinterface_", itf->prefix ? itf->prefix : ""));
  PetscOptionsBegin(comm, pre, "Node-to-node interface: one friction element per facing node pair", "JRInterface");
  PetscCall(PetscOptionsEList("-element", "Element: jenkins (constant normal load) or jenkins_nv (normal load variation, separation)", "JRInterfaceSetUp", types, 2, types[itf->element], &itf->element, NULL));
  PetscCall(PetscOptionsReal("-kt", "Tangential contact stiffness per element [N/m]", "JRInterfaceSetUp", itf->kt, &itf->kt, NULL));
  PetscCall(PetscOptionsReal("-kn", "Normal contact stiffness per element [N/m] (jenkins_nv; default kt)", "JRInterfaceSetUp", kn, &kn, NULL));
  PetscCall(PetscOptionsReal("-mu", "Friction coefficient [-]", "JRInterfaceSetUp", itf->mu, &itf->mu, NULL));
  PetscCall(PetscOptionsInt("-split", "Every element as this many identical elements in parallel (kt/k, kn/k, n0/k): the same forces, k times the work (benchmarks)", "JRInterfaceSetUp", itf->split, &itf->split, NULL));
  PetscCall(PetscOptionsReal("-max_gap", "jenkins_nv: leave out pairs whose preload gap exceeds this [m] (default: keep all)", "JRInterfaceSetUp", itf->max_gap, &itf->max_gap, NULL));
  PetscOptionsEnd();
  itf->kn = kn < 0 ? itf->kt : kn;
  PetscCheck(PetscIsNormalReal(itf->kt) && itf->kt > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sinterface_kt %g: the tangential stiffness must be positive [N/m]", itf->prefix ? itf->prefix : "", (double)itf->kt);
  PetscCheck(PetscIsNormalReal(itf->kn) && itf->kn > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sinterface_kn %g: the normal stiffness must be positive [N/m]", itf->prefix ? itf->prefix : "", (double)itf->kn);
  PetscCheck(itf->split >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sinterface_split %" PetscInt_FMT ": at least 1", itf->prefix ? itf->prefix : "", itf->split);
  PetscCheck(!PetscIsInfOrNanReal(itf->mu) && itf->mu > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sinterface_mu %g: the friction coefficient must be positive", itf->prefix ? itf->prefix : "", (double)itf->mu);
  PetscFunctionReturn(0);
}

/*
  JRInterfaceSetUp - the elements of the model's node pairs with the preload's normal loads and gaps (collective; the
  same list on every rank). jenkins: the pairs in contact; jenkins_nv: every pair within -interface_max_gap.
*/
PetscErrorCode JRInterfaceSetUp(JRInterface itf, JRModel model, JRPreload pre)
{
  MPI_Comm         comm = itf->comm;
  JRElements      *el   = &itf->el;
  const JRPairs   *P;
  const PetscReal *N, *gap;
  const PetscReal  kt = itf->kt, kn = itf->kn, mu = itf->mu, maxgap = itf->max_gap;
  PetscInt         np, type = itf->element, n = 0, split = itf->split;
  const char      *types[] = {JRCONTACTJENKINS, JRCONTACTJENKINSNV};

  PetscFunctionBeginUser;
  PetscCheck(!itf->setup, comm, PETSC_ERR_ORDER, "JRInterfaceSetUp: already set up");
  PetscCall(PetscLogEventBegin(JR_InterfaceSetUp, 0, 0, 0, 0));
  PetscCall(JRModelGetPairs(model, &P));
  PetscCheck(P && P->n > 0, comm, PETSC_ERR_ARG_WRONG, "The model has no contact interface (node pairs): -task frf builds the node-to-node elements of FE models (-model_type brb, lap1, lap3, lap, gmsh)");
  PetscCall(JRPreloadGetResults(pre, &np, &N, &gap));
  PetscCheck(np == P->n, comm, PETSC_ERR_PLIB, "Preload has %" PetscInt_FMT " pairs, the model %" PetscInt_FMT, np, P->n);
  for (PetscInt p = 0; p < np; p++) n += type == 0 ? N[p] > 0 : (maxgap < 0 || gap[p] <= maxgap);
  PetscCheck(n > 0, comm, PETSC_ERR_ARG_WRONG, "No interface pair is in contact after the preload: no friction elements (check -preload_force)");
  n *= split;
  el->n      = n;
  el->ntypes = 1;
  PetscCall(PetscStrncpy(el->typename[0], types[type], sizeof(el->typename[0])));
  PetscCall(PetscMalloc5(n, &el->type, n, &el->dof_a, n, &el->dof_b, n, &el->ndof_a, n, &el->ndof_b));
  PetscCall(PetscMalloc4(n, &el->kt, n, &el->kn, n, &el->mu, n, &el->n0));
  PetscCall(PetscMalloc4(3 * n, &el->vdof_a, 3 * n, &el->vdof_b, 3 * n, &el->tdir, 3 * n, &el->ndir));
  PetscCall(PetscMalloc1(3 * n, &el->pos));
  PetscCall(PetscMalloc1(n, &itf->pair));
  for (PetscInt p = 0, e = 0; p < np; p++) {
    if (!(type == 0 ? N[p] > 0 : (maxgap < 0 || gap[p] <= maxgap))) continue;
    for (PetscInt k = 0; k < split; k++, e++) {
      el->type[e]  = 0;
      el->dof_a[e] = el->dof_b[e] = el->ndof_a[e] = el->ndof_b[e] = -1;
      el->kt[e]    = kt / split;
      el->kn[e]    = type ? kn / split : 0.0;
      el->mu[e]    = mu;
      el->n0[e]    = (type ? N[p] - kn * gap[p] : N[p]) / split;
      for (PetscInt c = 0; c < 3; c++) {
        el->vdof_a[3 * e + c] = P->dofA[3 * p + c];
        el->vdof_b[3 * e + c] = P->dofB[3 * p + c];
        el->tdir[3 * e + c]   = P->t[3 * p + c];
        el->ndir[3 * e + c]   = P->nrm[3 * p + c];
        el->pos[3 * e + c]    = P->x[3 * p + c];
      }
      itf->pair[e] = p;
    }
  }
  itf->setup = PETSC_TRUE;
  PetscCall(PetscLogEventEnd(JR_InterfaceSetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*
  JRInterfaceGetElements - the interface's elements and, per element, its node pair (owned by the interface: copy the
  elements, JRElementsDuplicate, to change them)
*/
PetscErrorCode JRInterfaceGetElements(JRInterface itf, const JRElements **el, const PetscInt **pair)
{
  PetscFunctionBeginUser;
  PetscCheck(itf->setup, itf->comm, PETSC_ERR_ORDER, "JRInterfaceGetElements: call JRInterfaceSetUp first");
  if (el) *el = &itf->el;
  if (pair) *pair = itf->pair;
  PetscFunctionReturn(0);
}

/* JRInterfaceView - one line: the elements, their stiffnesses and the range and sum of their normal loads at rest */
PetscErrorCode JRInterfaceView(JRInterface itf, PetscViewer viewer)
{
  const JRElements *el = &itf->el;
  PetscReal         nsum = 0, nmin = PETSC_MAX_REAL, nmax = -PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(itf->comm, &viewer));
  if (!itf->setup) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "interface: %s elements (kt %g N/m, kn %g N/m, mu %g), not set up\n", itf->element ? JRCONTACTJENKINSNV : JRCONTACTJENKINS, (double)itf->kt, (double)itf->kn, (double)itf->mu));
    PetscFunctionReturn(0);
  }
  for (PetscInt e = 0; e < el->n; e++) {
    nsum += el->n0[e];
    nmin = PetscMin(nmin, el->n0[e]);
    nmax = PetscMax(nmax, el->n0[e]);
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "interface: %" PetscInt_FMT " %s elements (kt %g N/m, kn %g N/m, mu %g), n0 %.4g .. %.4g N, sum %.6g N\n", el->n, el->typename[0], (double)el->kt[0], (double)el->kn[0], (double)el->mu[0], (double)nmin, (double)nmax, (double)nsum));
  PetscFunctionReturn(0);
}

/* JRInterfaceDestroy - free the interface and its elements */
PetscErrorCode JRInterfaceDestroy(JRInterface *itf)
{
  PetscFunctionBeginUser;
  if (!*itf) PetscFunctionReturn(0);
  if ((*itf)->setup) PetscCall(JRElementsDestroy(&(*itf)->el));
  PetscCall(PetscFree((*itf)->pair));
  PetscCall(PetscFree((*itf)->prefix));
  PetscCall(PetscFree(*itf));
  PetscFunctionReturn(0);
}
