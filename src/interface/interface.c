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
  JRInterfaceSetFromOptions - the interface's options, read and checked once, before any work: the elements
  (-interface_element, -interface_kt, -interface_kn, -interface_mu, -interface_split, -interface_max_gap) and the
  first reduction's joints (-rom_joints, -rom_strips, -rom_boxes, -rom_zone_fraction, -rom_split_width)
*/
PetscErrorCode JRInterfaceSetFromOptions(MPI_Comm comm, JRInterfaceOptions *o)
{
  const char *types[] = {JRCONTACTJENKINS, JRCONTACTJENKINSNV};
  const char *kinds[] = {"none", "each", "strips", "bolts", "between", "sides", "zones", "boxes"};
  PetscBool   set, bset;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(o, sizeof(*o)));
  o->element       = 0;
  o->kt            = 1e6;
  o->kn            = -1;
  o->mu            = 0.12;
  o->max_gap       = -1;
  o->split         = 1;
  o->zone_fraction = 0.5;
  o->ncut          = 64;
  o->nbox          = 256;
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
  PetscOptionsBegin(comm, "rom_", "Reduced-order joints, first reduction (prefix rom_)", "JRInterface");
  PetscCall(PetscOptionsEList("-joints", "Joints: none (node-to-node), each, strips (-rom_strips cuts), bolts, between, sides, zones (per bolt side and load), boxes (-rom_boxes)", "JRInterfaceCreateElements", kinds, 8, kinds[o->joints], &o->joints, NULL));
  PetscCall(PetscOptionsRealArray("-strips", "Cut positions along the beam axis x1,x2,... [m], increasing", "JRInterfaceCreateElements", o->cut, &o->ncut, &set));
  PetscCall(PetscOptionsRealArray("-boxes", "Boxes x0,x1,y0,y1 per joint [m]", "JRInterfaceCreateElements", o->box, &o->nbox, &bset));
  PetscCall(PetscOptionsReal("-zone_fraction", "-rom_joints zones: the high-load zone of a bolt side holds the members with n0 at least this fraction of the side's largest", "JRInterfaceCreateElements", o->zone_fraction, &o->zone_fraction, NULL));
  PetscCall(PetscOptionsBool("-split_width", "Split every strip at mid-width into two joints", "JRInterfaceCreateElements", o->split_width, &o->split_width, NULL));
  PetscOptionsEnd();
  if (!set) o->ncut = 0;
  if (!bset) o->nbox = 0;
  PetscCheck(!set || o->joints == 2, comm, PETSC_ERR_ARG_INCOMP, "-rom_strips needs -rom_joints strips");
  PetscCheck(!bset || o->joints == 7, comm, PETSC_ERR_ARG_INCOMP, "-rom_boxes needs -rom_joints boxes");
  PetscCheck(!o->split_width || (o->joints >= 2 && o->joints <= 6), comm, PETSC_ERR_ARG_INCOMP, "-rom_split_width needs -rom_joints strips, bolts, between, sides or zones");
  PetscCheck(o->zone_fraction > 0 && o->zone_fraction < 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-rom_zone_fraction %g: between 0 and 1", (double)o->zone_fraction);
  PetscCheck(o->joints != 2 || o->ncut > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_joints strips needs the cuts -rom_strips x1,x2,... [m]");
  for (PetscInt k = 1; k < o->ncut; k++) PetscCheck(o->cut[k] > o->cut[k - 1], comm, PETSC_ERR_ARG_WRONG, "-rom_strips: the cuts must increase, but %g m follows %g m", (double)o->cut[k], (double)o->cut[k - 1]);
  PetscCheck(o->joints != 7 || (o->nbox >= 4 && o->nbox % 4 == 0), comm, PETSC_ERR_ARG_WRONG, "-rom_boxes needs x0,x1,y0,y1 per joint [m], got %" PetscInt_FMT " values", o->nbox);
  PetscFunctionReturn(0);
}

/*
  First reduction, joints from regions (options prefix rom_): -rom_joints
    none     node-to-node (default)
    each     every element its own joint: the node-to-node model again (a check)
    strips   cuts -rom_strips x1,x2,... [m] along the beam axis
    bolts    one joint per bolt: cuts midway between neighbouring bolts (thesis Fig 4.13: the 3-joint BRB)
    between  cuts at the bolts' axes: the outer side of each end bolt and the spans between bolts (Fig 4.15: the
             4-joint BRB; Fig 5.25: the 2-joint single bolt, cut at its axis of symmetry)
    sides    each side of each bolt (cuts at the axes and midway: Fig 4.17, the 6-joint BRB)
    zones    each side of each bolt split by normal load (thesis 5.2.2, Fig 5.29, 5.61: 4 joints per bolt): a
             high-load zone (members with n0 >= -rom_zone_fraction, default 0.5, of the largest n0 of that side)
             and a low-load zone (the rest, gaps included)
    boxes    boxes -rom_boxes x0,x1,y0,y1, x0,x1,y0,y1, ... [m], one joint each: every element must lie in exactly
             one box
  and -rom_split_width splits every strip-type region at mid-width. Each region must hold elements (else an error
  naming it); its members move with the average of their relative motions (4.4).
*/
static PetscErrorCode AssignJoints(MPI_Comm comm, JRModel model, const JRPairs *P, const JRInterfaceOptions *o, JRElements *el, const PetscInt pair[])
{
  const char *kinds[] = {"none", "each", "strips", "bolts", "between", "sides", "zones", "boxes"};
  PetscInt    kind = o->joints, ncut = o->ncut, nreg, nbox = o->nbox;
  PetscReal   cut[64], ylo = PETSC_MAX_REAL, yhi = -PETSC_MAX_REAL, box[256], zf = o->zone_fraction;
  PetscBool   split = o->split_width;
  PetscInt   *cnt;

  PetscFunctionBeginUser;
  PetscCall(PetscArraycpy(cut, o->cut, 64));
  PetscCall(PetscArraycpy(box, o->box, 256));
  if (kind == 0) PetscFunctionReturn(0);
  if (kind == 1) {
    el->njoints = el->n;
    PetscCall(PetscMalloc1(el->n, &el->joint));
    for (PetscInt e = 0; e < el->n; e++) el->joint[e] = e;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscMalloc1(el->n, &el->joint));
  if (kind == 7) { /* boxes */
    PetscCheck(nbox >= 4 && nbox % 4 == 0, comm, PETSC_ERR_ARG_WRONG, "-rom_boxes needs x0,x1,y0,y1 per joint [m], got %" PetscInt_FMT " values", nbox);
    nreg = nbox / 4;
    for (PetscInt b = 0; b < nreg; b++) PetscCheck(box[4 * b + 1] > box[4 * b] && box[4 * b + 3] > box[4 * b + 2], comm, PETSC_ERR_ARG_WRONG, "-rom_boxes: box %" PetscInt_FMT " (%g..%g, %g..%g m) is empty: x0 < x1 and y0 < y1", b, (double)box[4 * b], (double)box[4 * b + 1], (double)box[4 * b + 2], (double)box[4 * b + 3]);
    PetscCall(PetscCalloc1(nreg, &cnt));
    for (PetscInt e = 0; e < el->n; e++) {
      const PetscReal *x  = P->x + 3 * pair[e];
      PetscInt         in = -1;
      for (PetscInt b = 0; b < nreg; b++) {
        if (!(x[0] >= box[4 * b] && x[0] <= box[4 * b + 1] && x[1] >= box[4 * b + 2] && x[1] <= box[4 * b + 3])) continue;
        PetscCheck(in < 0, comm, PETSC_ERR_ARG_WRONG, "-rom_boxes: the element at (%g, %g) m lies in box %" PetscInt_FMT " and in box %" PetscInt_FMT ": the regions overlap", (double)x[0], (double)x[1], in, b);
        in = b;
      }
      PetscCheck(in >= 0, comm, PETSC_ERR_ARG_WRONG, "-rom_boxes: the element at (%g, %g) m lies in no box: every element must belong to a region", (double)x[0], (double)x[1]);
      el->joint[e] = in;
      cnt[in]++;
    }
    for (PetscInt b = 0; b < nreg; b++) PetscCheck(cnt[b] > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_boxes: box %" PetscInt_FMT " (%g..%g, %g..%g m) holds no element: an empty joint", b, (double)box[4 * b], (double)box[4 * b + 1], (double)box[4 * b + 2], (double)box[4 * b + 3]);
  } else {
    PetscInt nz = kind == 6 ? 2 : 1, nb = 0, *zone = NULL;
    if (kind >= 3) { /* cuts from the bolts' positions along the beam axis */
      const JRBolts *B;
      PetscReal      xb[64];
      PetscCall(JRModelGetBolts(model, &B));
      PetscCheck(B && B->n > 0 && B->n <= 32, comm, PETSC_ERR_ARG_WRONG, "-rom_joints %s needs a model with bolts (1 to 32)", kinds[kind]);
      nb = B->n;
      for (PetscInt b = 0; b < nb; b++) xb[b] = B->x[3 * b];
      for (PetscInt b = 1; b < nb; b++) /* sort */
        for (PetscInt c = b; c > 0 && xb[c] < xb[c - 1]; c--) {
          const PetscReal t = xb[c];
          xb[c]             = xb[c - 1];
          xb[c - 1]         = t;
        }
      ncut = 0;
      for (PetscInt b = 0; b < nb; b++) {
        if (kind != 3 && kind != 4 && b > 0) cut[ncut++] = 0.5 * (xb[b - 1] + xb[b]); /* sides, zones */
        if (kind == 3 && b > 0) cut[ncut++] = 0.5 * (xb[b - 1] + xb[b]);                  /* bolts */
        if (kind != 3) cut[ncut++] = xb[b];                                               /* between, sides, zones */
      }
    }
    PetscCheck(kind != 2 || ncut > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_joints strips needs the cuts -rom_strips x1,x2,... [m]");
    for (PetscInt k = 1; k < ncut; k++) PetscCheck(cut[k] > cut[k - 1], comm, PETSC_ERR_ARG_WRONG, "-rom_strips: the cuts must increase, but %g m follows %g m", (double)cut[k], (double)cut[k - 1]);
    for (PetscInt e = 0; e < el->n; e++) {
      ylo = PetscMin(ylo, P->x[3 * pair[e] + 1]);
      yhi = PetscMax(yhi, P->x[3 * pair[e] + 1]);
    }
    nreg = (ncut + 1) * (split ? 2 : 1) * nz;
    PetscCall(PetscCalloc1(nreg, &cnt));
    for (PetscInt e = 0; e < el->n; e++) {
      const PetscReal *x = P->x + 3 * pair[e];
      PetscInt         k = 0;
      while (k < ncut && x[0] >= cut[k]) k++;
      el->joint[e] = (split ? 2 * k + (x[1] > 0.5 * (ylo + yhi) ? 1 : 0) : k) * nz;
    }
    if (kind == 6) { /* zones: high load (>= zf of the side's largest n0) and low load */
      PetscReal *nmax;
      PetscCall(PetscCalloc1(nreg, &nmax));
      PetscCall(PetscMalloc1(el->n, &zone));
      for (PetscInt e = 0; e < el->n; e++) nmax[el->joint[e]] = PetscMax(nmax[el->joint[e]], el->n0[e]);
      for (PetscInt e = 0; e < el->n; e++) el->joint[e] += (nmax[el->joint[e]] > 0 && el->n0[e] >= zf * nmax[el->joint[e]]) ? 1 : 0;
      PetscCall(PetscFree(nmax));
      PetscCall(PetscFree(zone));
    }
    for (PetscInt e = 0; e < el->n; e++) cnt[el->joint[e]]++;
    for (PetscInt r = 0; r < nreg; r++) {
      const PetscInt k = (split ? r / (2 * nz) : r / nz);
      PetscCheck(cnt[r] > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_joints %s: the region x %s%g .. %g%s m%s%s holds no element: an empty joint (%s)", kinds[kind], k ? "" : "< ", (double)(k ? cut[k - 1] : cut[0]), (double)(k < ncut ? cut[k] : cut[ncut - 1]), k < ncut ? "" : " and beyond", split ? ((r / nz) % 2 ? ", upper half of the width" : ", lower half of the width") : "", nz > 1 ? (r % 2 ? ", high-load zone" : ", low-load zone") : "", kind == 2 ? "move the cuts" : kind == 6 ? "change -rom_zone_fraction" : "fewer regions");
    }
  }
  el->njoints = nreg;
  {
    PetscReal *n0s;
    PetscCall(PetscCalloc1(nreg, &n0s));
    for (PetscInt e = 0; e < el->n; e++) n0s[el->joint[e]] += el->n0[e];
    for (PetscInt r = 0; r < nreg; r++) PetscCall(PetscPrintf(comm, "rom: joint %" PetscInt_FMT ": %" PetscInt_FMT " elements, normal load %.6g N\n", r, cnt[r], (double)n0s[r]));
    PetscCall(PetscFree(n0s));
  }
  PetscCall(PetscFree(cnt));
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
  PetscCall(AssignJoints(comm, model, P, o, el, *pair));
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
