/*
   The node-to-node interface (pipeline stage 4): one friction element per facing node pair of an FE
   model, its normal load from the bolt preload, and points of the mesh found by position.

   Element e joins pair p = pair[e]: tangential relative motion u = (x_A - x_B) . t_p along the beam axis,
   normal v = (x_A - x_B) . n_p (positive presses the surfaces together), projection rows
   (phi_A - phi_B) . dir (4.3) formed by JRHBM. Options (prefix interface_):
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
#include <jointrom/private/modelimpl.h>

/*
  JRInterfaceSetFromOptions - the interface's options, read and checked once, before any work: -interface_element,
  -interface_kt, -interface_kn, -interface_mu, -interface_split, -interface_max_gap
*/
PetscErrorCode JRInterfaceSetFromOptions(MPI_Comm comm, JRInterfaceOptions *o)
{
  const char *types[] = {JRCONTACTJENKINS, JRCONTACTJENKINSNV};

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(o, sizeof(*o)));
  o->element       = 0;
  o->kt            = 1e6;
  o->kn            = -1;
  o->mu            = 0.12;
  o->max_gap       = -1;
  o->split         = 1;
  PetscOptionsBegin(comm, "interface_", "Node-to-node interface: one friction element per facing node pair (prefix interface_)", "JRInterface");
  PetscCall(PetscOptionsEList("-element", "Element: jenkins (constant normal load) or jenkins_nv (normal load variation, separation)", "JRInterfaceCreateElements", types, 2, types[o->element], &o->element, NULL));
  PetscCall(PetscOptionsReal("-kt", "Tangential contact stiffness per element [N/m]", "JRInterfaceCreateElements", o->kt, &o->kt, NULL));
  PetscCall(PetscOptionsReal("-kn", "Normal contact stiffness per element [N/m] (jenkins_nv; default kt)", "JRInterfaceCreateElements", o->kn, &o->kn, NULL));
  PetscCall(PetscOptionsReal("-mu", "Friction coefficient [-]", "JRInterfaceCreateElements", o->mu, &o->mu, NULL));
  PetscCall(PetscOptionsInt("-split", "Every element as this many identical elements in parallel (kt/k, kn/k, n0/k): the same forces, k times the work (benchmarks)", "JRInterfaceCreateElements", o->split, &o->split, NULL));
  PetscCall(PetscOptionsReal("-max_gap", "jenkins_nv: leave out pairs whose preload gap exceeds this [m] (default: keep all)", "JRInterfaceCreateElements", o->max_gap, &o->max_gap, NULL));
  PetscOptionsEnd();
  if (o->kn < 0) o->kn = o->kt;
  PetscCheck(PetscIsNormalReal(o->kt) && o->kt > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-interface_kt %g: the tangential stiffness must be positive [N/m]", (double)o->kt);
  PetscCheck(PetscIsNormalReal(o->kn) && o->kn > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-interface_kn %g: the normal stiffness must be positive [N/m]", (double)o->kn);
  PetscCheck(o->split >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-interface_split %" PetscInt_FMT ": at least 1", o->split);
  PetscCheck(!PetscIsInfOrNanReal(o->mu) && o->mu > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-interface_mu %g: the friction coefficient must be positive", (double)o->mu);
  PetscFunctionReturn(0);
}


PetscErrorCode JRInterfaceCreateElements(JRModel model, JRPreload pre, const JRInterfaceOptions *o, JRElements *el, PetscInt **pair)
{
  MPI_Comm         comm;
  const JRPairs   *P;
  const PetscReal *N, *gap;
  const PetscReal  kt = o->kt, kn = o->kn, mu = o->mu, maxgap = o->max_gap;
  PetscInt         np, type = o->element, n = 0, split = o->split;
  const char      *types[] = {JRCONTACTJENKINS, JRCONTACTJENKINSNV};

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(JR_InterfaceSetUp, 0, 0, 0, 0));
  PetscCall(JRModelGetComm(model, &comm));
  PetscCall(JRModelGetPairs(model, &P));
  PetscCheck(P && P->n > 0, comm, PETSC_ERR_ARG_WRONG, "The model has no contact interface (node pairs): -task frf builds the node-to-node elements of FE models (-model_type brb, lap1, lap3, lap, gmsh)");
  PetscCall(JRPreloadGetResults(pre, &np, &N, &gap));
  PetscCheck(np == P->n, comm, PETSC_ERR_PLIB, "Preload has %" PetscInt_FMT " pairs, the model %" PetscInt_FMT, np, P->n);
  for (PetscInt p = 0; p < np; p++) n += type == 0 ? N[p] > 0 : (maxgap < 0 || gap[p] <= maxgap);
  PetscCheck(n > 0, comm, PETSC_ERR_ARG_WRONG, "No interface pair is in contact after the preload: no friction elements (check -preload_force)");
  n *= split;
  PetscCall(PetscMemzero(el, sizeof(*el)));
  el->n      = n;
  el->ntypes = 1;
  PetscCall(PetscStrncpy(el->typename[0], types[type], sizeof(el->typename[0])));
  PetscCall(PetscMalloc5(n, &el->type, n, &el->dof_a, n, &el->dof_b, n, &el->ndof_a, n, &el->ndof_b));
  PetscCall(PetscMalloc4(n, &el->kt, n, &el->kn, n, &el->mu, n, &el->n0));
  PetscCall(PetscMalloc4(3 * n, &el->vdof_a, 3 * n, &el->vdof_b, 3 * n, &el->tdir, 3 * n, &el->ndir));
  PetscCall(PetscMalloc1(3 * n, &el->pos));
  PetscCall(PetscMalloc1(n, pair));
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
      (*pair)[e] = p;
    }
  }
  PetscCall(PetscLogEventEnd(JR_InterfaceSetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Bounding box of the mesh [m] (collective) */
PetscErrorCode JRModelGetBoundingBox(JRModel model, PetscReal lo[3], PetscReal hi[3])
{
  Vec                X;
  const PetscScalar *x;
  PetscInt           rlo, rhi;
  PetscReal          l[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, h[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL};
  MPI_Comm           comm;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetComm(model, &comm));
  PetscCall(JRModelGetCoordinates(model, &X));
  PetscCheck(X, comm, PETSC_ERR_ARG_WRONG, "The model has no mesh coordinates (points are found by position only on FE models)");
  PetscCall(VecGetOwnershipRange(X, &rlo, &rhi));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt i = rlo; i < rhi; i++) {
    const PetscInt c = i % 3;
    l[c]             = PetscMin(l[c], PetscRealPart(x[i - rlo]));
    h[c]             = PetscMax(h[c], PetscRealPart(x[i - rlo]));
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecDestroy(&X));
  PetscCall(MPIU_Allreduce(l, lo, 3, MPIU_REAL, MPIU_MIN, comm));
  PetscCall(MPIU_Allreduce(h, hi, 3, MPIU_REAL, MPIU_MAX, comm));
  PetscFunctionReturn(0);
}

/*
  JRModelFindDof - the DOF of component comp (0 x, 1 y, 2 z) of the mesh node nearest to the point p [m],
  and that node's distance from it (collective; the same on every rank; ties go to the lowest rank).
  The DOFs of a node are consecutive x, y, z (PetscFE layout), so DOF i is component i % 3.
*/
PetscErrorCode JRModelFindDof(JRModel model, const PetscReal p[3], PetscInt comp, PetscInt *dof, PetscReal *dist)
{
  Vec                X;
  const PetscScalar *x;
  PetscInt           rlo, rhi, best = -1;
  PetscReal          bd = PETSC_MAX_REAL;
  MPI_Comm           comm;
  struct {
    double d;
    int    r;
  } in, out;
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetComm(model, &comm));
  PetscCheck(comp >= 0 && comp < 3, comm, PETSC_ERR_ARG_OUTOFRANGE, "Component %" PetscInt_FMT ": 0 (x), 1 (y) or 2 (z)", comp);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(JRModelGetCoordinates(model, &X));
  PetscCheck(X, comm, PETSC_ERR_ARG_WRONG, "The model has no mesh coordinates (points are found by position only on FE models)");
  PetscCall(VecGetOwnershipRange(X, &rlo, &rhi));
  PetscCheck(rlo % 3 == 0 && (rhi - rlo) % 3 == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "DOFs are not in x, y, z triples");
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt i = 0; i < rhi - rlo; i += 3) {
    PetscReal d = 0.0;
    for (PetscInt c = 0; c < 3; c++) d += PetscSqr(PetscRealPart(x[i + c]) - p[c]);
    if (d < bd) {
      bd   = d;
      best = rlo + i + comp;
    }
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecDestroy(&X));
  in.d = bd;
  in.r = rank;
  PetscCallMPI(MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm));
  PetscCallMPI(MPI_Bcast(&best, 1, MPIU_INT, out.r, comm));
  *dof = best;
  if (dist) *dist = PetscSqrtReal(out.d);
  PetscFunctionReturn(0);
}

/*
  JRElementsCreateStuckStiffness - Ks: the springs of every friction element in contact at rest (n0 > 0) stuck,
  kt along its tangential direction and kn along its normal one (jenkins_nv), between its DOFs, as a
  matrix of K's layout (add it with MatAXPY(..., DIFFERENT_NONZERO_PATTERN)); sig: a signature of the set
  (sum of the springs' stiffness over the elements and their DOFs) that identifies it in saved modes.
*/
PetscErrorCode JRElementsCreateStuckStiffness(Mat K, const JRElements *el, Mat *Ks, PetscReal *sig)
{
  PetscInt  *bn, **bd, nb = 0;
  PetscReal **bv, sg = 0.0;

  PetscFunctionBeginUser;
  if (el->members) el = el->members; /* a reduced model: its basis is that of the node-to-node elements */
  PetscCall(PetscMalloc3(el->n, &bn, el->n, &bd, el->n, &bv));
  for (PetscInt e = 0; e < el->n; e++) {
    const char     *ty  = el->typename[el->type[e]];
    const PetscBool nv  = (PetscBool)!strcmp(ty, JRCONTACTJENKINSNV);
    const PetscReal kn  = nv ? el->kn[e] : 0.0;
    PetscInt        d[6], m = 0;
    PetscReal       v[6][2]; /* per DOF: its weight in u and in v */
    if (!(el->n0[e] > 0) || !(nv || !strcmp(ty, JRCONTACTJENKINS))) continue;
    if (el->vdof_a) {
      for (PetscInt c = 0; c < 3; c++) {
        d[m]      = el->vdof_a[3 * e + c];
        v[m][0]   = el->tdir[3 * e + c];
        v[m++][1] = el->ndir[3 * e + c];
      }
      for (PetscInt c = 0; c < 3; c++) {
        d[m]      = el->vdof_b[3 * e + c];
        v[m][0]   = -el->tdir[3 * e + c];
        v[m++][1] = -el->ndir[3 * e + c];
      }
    } else {
      const PetscInt dd[4] = {el->dof_a[e], el->dof_b[e], nv ? el->ndof_a[e] : -1, nv ? el->ndof_b[e] : -1};
      const PetscReal wt[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      for (PetscInt k = 0; k < 4; k++) {
        PetscInt j;
        if (dd[k] < 0) continue;
        for (j = 0; j < m; j++)
          if (d[j] == dd[k]) break;
        if (j == m) {
          d[m]    = dd[k];
          v[m][0] = v[m][1] = 0.0;
          m++;
        }
        v[j][0] += wt[k][0];
        v[j][1] += wt[k][1];
      }
    }
    bn[nb] = m;
    PetscCall(PetscMalloc2(m, &bd[nb], m * m, &bv[nb]));
    for (PetscInt i = 0; i < m; i++) {
      bd[nb][i] = d[i];
      for (PetscInt j = 0; j < m; j++) bv[nb][i * m + j] = el->kt[e] * v[i][0] * v[j][0] + kn * v[i][1] * v[j][1];
      sg += (el->kt[e] + kn) * (1.0 + 1e-7 * (PetscReal)d[i]);
    }
    nb++;
  }
  PetscCall(JRMatCreateFromBlocks(K, nb, bn, (const PetscInt *const *)bd, (const PetscReal *const *)bv, Ks));
  for (PetscInt b = 0; b < nb; b++) PetscCall(PetscFree2(bd[b], bv[b]));
  PetscCall(PetscFree3(bn, bd, bv));
  if (sig) *sig = sg;
  PetscFunctionReturn(0);
}
