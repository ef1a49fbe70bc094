/*
   JRReduce's first reduction, the joints: the interface's elements grouped into regions (JRReduceAssignJoints), each
   joint's members, load share, centroid and region (the report, and the names in the stiffness correction's warning).
*/
#include <jointrom/private/reduceimpl.h>
#include <jointrom/private/modelimpl.h>

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
    auto     from the normal load at rest: every element belongs to its nearest bolt (in the interface's plane) and
             to a ring around it by load level, -rom_auto_rings k rings per bolt (default 2) whose radii split the
             bolt's load into k equal parts (the innermost ring carries the first 1/k of it; the outermost also holds
             every member beyond, gaps included); each ring is cut at the bolt's axis into its two sides: 2k joints
             per bolt. The inner half of the rings are the high-load joints.
    onset    from the normal load at rest and the stuck mode of interest: every member in contact starts to slip at
             the modal amplitude a_e = mu n0_e / (kt |u_e|) (u_e its tangential motion in that mode); -rom_onset_bands
             k bands (default 6) of equal ratio divide the onsets from the first to the one by which the fraction
             -rom_onset_upto (0.9) of the interface's slip force mu n0 slips (later onsets join the last band; the
             same bands over the whole interface), and each band is split by nearest bolt and side as in auto; the
             open members (n0 <= 0) of each bolt side are joints of their own (their field fitted to their own
             motion: tied to the closed members' field, the gaps could not breathe and close as they do),
             -rom_onset_open_bands k (default 1) of them by closing onset, the modal amplitude c_e = -n0_e / (kn
             |v_e|) at which the member closes (v_e its normal motion in the stuck mode), in bands of equal ratio
             from the first closing onset to the one by which the fraction -rom_onset_upto of the open members
             close (later ones join the last band): one field over a side's open members misplaces those that
             close first, near the contact's edge, where a few closing members stiffen the joint. Empty joints
             are dropped. The joints are set once the modes are known (JRReduceSetUp), each a region that
             slips at about one level, so that a slip front does not cross the inside of a joint.
  and -rom_split_width splits every strip-type region at mid-width. Each region must hold elements (else an error
  naming it); its members move with the average of their relative motions (4.4).
*/
const char *const JRReduceJointKinds[] = {"none", "each", "strips", "bolts", "between", "sides", "zones", "boxes", "auto", "onset"};
/* what a region of each kind is, in the joints' report: the regions between the cuts along the beam axis */
static const char *const RegionWords[] = {"", "element", "strip", "bolt region", "span", "bolt side", "bolt side", "box", "ring", "onset band"};

/* -rom_joints boxes: element e in the one box that holds its pair's point; *nreg boxes, cnt[] their members */
static PetscErrorCode AssignBoxes(JRReduce o, const JRPairs *P, JRElements *el, const PetscInt pair[], PetscInt *nreg, PetscInt **cnt)
{
  MPI_Comm         comm = o->comm;
  const PetscReal *box  = o->box;
  const PetscInt   nb   = o->nbox / 4;

  PetscFunctionBeginUser;
  PetscCheck(o->nbox >= 4 && o->nbox % 4 == 0, comm, PETSC_ERR_ARG_WRONG, "-rom_boxes needs x0,x1,y0,y1 per joint [m], got %" PetscInt_FMT " values", o->nbox);
  for (PetscInt b = 0; b < nb; b++) PetscCheck(box[4 * b + 1] > box[4 * b] && box[4 * b + 3] > box[4 * b + 2], comm, PETSC_ERR_ARG_WRONG, "-rom_boxes: box %" PetscInt_FMT " (%g..%g, %g..%g m) is empty: x0 < x1 and y0 < y1", b, (double)box[4 * b], (double)box[4 * b + 1], (double)box[4 * b + 2], (double)box[4 * b + 3]);
  PetscCall(PetscCalloc1(nb, cnt));
  for (PetscInt e = 0; e < el->n; e++) {
    const PetscReal *x  = P->x + 3 * pair[e];
    PetscInt         in = -1;
    for (PetscInt b = 0; b < nb; b++) {
      if (!(x[0] >= box[4 * b] && x[0] <= box[4 * b + 1] && x[1] >= box[4 * b + 2] && x[1] <= box[4 * b + 3])) continue;
      PetscCheck(in < 0, comm, PETSC_ERR_ARG_WRONG, "-rom_boxes: the element at (%g, %g) m lies in box %" PetscInt_FMT " and in box %" PetscInt_FMT ": the regions overlap", (double)x[0], (double)x[1], in, b);
      in = b;
    }
    PetscCheck(in >= 0, comm, PETSC_ERR_ARG_WRONG, "-rom_boxes: the element at (%g, %g) m lies in no box: every element must belong to a region", (double)x[0], (double)x[1]);
    el->joint[e] = in;
    (*cnt)[in]++;
  }
  for (PetscInt b = 0; b < nb; b++) PetscCheck((*cnt)[b] > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_boxes: box %" PetscInt_FMT " (%g..%g, %g..%g m) holds no element: an empty joint", b, (double)box[4 * b], (double)box[4 * b + 1], (double)box[4 * b + 2], (double)box[4 * b + 3]);
  *nreg = nb;
  PetscCall(PetscCalloc1(nb, &o->ji));
  for (PetscInt b = 0; b < nb; b++) {
    o->ji[b].zone = -1;
    PetscCall(PetscSNPrintf(o->ji[b].kind, sizeof(o->ji[b].kind), "box %g..%g, %g..%g m", (double)box[4 * b], (double)box[4 * b + 1], (double)box[4 * b + 2], (double)box[4 * b + 3]));
  }
  PetscFunctionReturn(0);
}

/* -rom_joints auto: rings of equal load around each bolt, each cut at the bolt's axis (the members sorted by their
   distance from their nearest bolt, ties by index, so every rank assigns the same) */
static PetscErrorCode AssignAuto(JRReduce o, JRModel model, const JRPairs *P, JRElements *el, const PetscInt pair[], PetscInt *nreg, PetscInt **cnt)
{
  MPI_Comm       comm = o->comm;
  const PetscInt k    = o->rings;
  const JRBolts *B;
  PetscInt      *bolt, *ord, *bx, nb;
  PetscReal     *rad, *ltot, lsum = 0;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetBolts(model, &B));
  PetscCheck(B && B->n > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_joints auto needs a model with bolts");
  nb = B->n;
  PetscCall(PetscMalloc5(el->n, &bolt, el->n, &ord, el->n, &rad, nb, &ltot, nb, &bx));
  for (PetscInt b = 0; b < nb; b++) bx[b] = b; /* the bolts in order of x */
  for (PetscInt b = 1; b < nb; b++)
    for (PetscInt c = b; c > 0 && B->x[3 * bx[c]] < B->x[3 * bx[c - 1]]; c--) {
      const PetscInt t = bx[c];
      bx[c]            = bx[c - 1];
      bx[c - 1]        = t;
    }
  for (PetscInt b = 0; b < nb; b++) ltot[b] = 0;
  for (PetscInt e = 0; e < el->n; e++) {
    const PetscReal *x = P->x + 3 * pair[e];
    bolt[e]            = -1;
    for (PetscInt b = 0; b < nb; b++) {
      const PetscReal *xb = B->x + 3 * bx[b], d = PetscSqrtReal(PetscSqr(x[0] - xb[0]) + PetscSqr(x[1] - xb[1]));
      if (bolt[e] < 0 || d < rad[e]) {
        bolt[e] = b;
        rad[e]  = d;
      }
    }
    ord[e] = e;
    if (el->n0[e] > 0) ltot[bolt[e]] += el->n0[e];
  }
  for (PetscInt a = 1; a < el->n; a++) /* by bolt, then distance, then index (insertion sort: stable) */
    for (PetscInt c = a; c > 0; c--) {
      const PetscInt i = ord[c], j = ord[c - 1];
      if (!(bolt[i] < bolt[j] || (bolt[i] == bolt[j] && rad[i] < rad[j]))) break;
      ord[c]     = j;
      ord[c - 1] = i;
    }
  for (PetscInt a = 0, b = -1, ring = 0; a < el->n; a++) {
    const PetscInt   e = ord[a];
    const PetscReal *x = P->x + 3 * pair[e];
    if (bolt[e] != b) {
      b    = bolt[e];
      ring = 0;
      lsum = 0;
    }
    /* the ring: the first whose share of the bolt's load is not yet filled when this member's load is counted */
    if (el->n0[e] > 0) lsum += el->n0[e];
    while (ring < k - 1 && lsum > (ring + 1) * ltot[b] / k * (1 + 1e-12)) ring++;
    el->joint[e] = (2 * b + (x[0] < B->x[3 * bx[b]] ? 0 : 1)) * k + ring;
  }
  *nreg = 2 * nb * k;
  PetscCall(PetscCalloc1(*nreg, cnt));
  for (PetscInt e = 0; e < el->n; e++) (*cnt)[el->joint[e]]++;
  PetscCall(PetscCalloc1(*nreg, &o->ji));
  for (PetscInt r = 0; r < *nreg; r++) {
    const PetscInt b = r / (2 * k), side = (r / k) % 2, ring = r % k;
    o->ji[r].zone    = k > 1 ? (2 * ring < k ? 1 : 0) : -1;
    PetscCall(PetscSNPrintf(o->ji[r].kind, sizeof(o->ji[r].kind), "ring %" PetscInt_FMT " of %" PetscInt_FMT " of bolt %" PetscInt_FMT ", %s side%s", ring + 1, k, b + 1, side ? "+x" : "-x", k > 1 ? (2 * ring < k ? ", high-load" : ", low-load") : ""));
    PetscCheck((*cnt)[r] > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_joints auto: %s holds no element: an empty joint (fewer -rom_auto_rings)", o->ji[r].kind);
  }
  PetscCall(PetscFree5(bolt, ord, rad, ltot, bx));
  PetscFunctionReturn(0);
}

/* Every element's nearest bolt (in the interface's plane; the bolts numbered in order of x) and side of its axis:
   side[e] = 2 b + (0 on the -x side, 1 on the +x side); *nb the bolts */
static PetscErrorCode BoltSides(JRReduce o, JRModel model, const JRPairs *P, const JRElements *el, const PetscInt pair[], PetscInt side[], PetscInt *nb)
{
  const JRBolts *B;
  PetscInt      *bx;

  PetscFunctionBeginUser;
  PetscCall(JRModelGetBolts(model, &B));
  PetscCheck(B && B->n > 0, o->comm, PETSC_ERR_ARG_WRONG, "-rom_joints %s needs a model with bolts", JRReduceJointKinds[o->joints]);
  PetscCall(PetscMalloc1(B->n, &bx));
  for (PetscInt b = 0; b < B->n; b++) bx[b] = b;
  for (PetscInt b = 1; b < B->n; b++)
    for (PetscInt c = b; c > 0 && B->x[3 * bx[c]] < B->x[3 * bx[c - 1]]; c--) {
      const PetscInt t = bx[c];
      bx[c]            = bx[c - 1];
      bx[c - 1]        = t;
    }
  for (PetscInt e = 0; e < el->n; e++) {
    const PetscReal *x  = P->x + 3 * pair[e];
    PetscInt         bb = 0;
    PetscReal        dd = PETSC_MAX_REAL;
    for (PetscInt b = 0; b < B->n; b++) {
      const PetscReal *xb = B->x + 3 * bx[b], d = PetscSqr(x[0] - xb[0]) + PetscSqr(x[1] - xb[1]);
      if (d < dd) {
        dd = d;
        bb = b;
      }
    }
    side[e] = 2 * bb + (x[0] < B->x[3 * bx[bb]] ? 0 : 1);
  }
  *nb = B->n;
  PetscCall(PetscFree(bx));
  PetscFunctionReturn(0);
}

/* The cuts along the beam axis of -rom_joints bolts (midway between bolts), between (at the bolts' axes), sides and
   zones (both); strips: -rom_strips's */
static PetscErrorCode JointCuts(JRReduce o, JRModel model, PetscInt *ncut, PetscReal cut[])
{
  const PetscInt kind = o->joints;
  const JRBolts *B;
  PetscReal      xb[64];
  PetscInt       nb;

  PetscFunctionBeginUser;
  *ncut = o->ncut;
  PetscCall(PetscArraycpy(cut, o->cut, 64));
  if (kind < 3) PetscFunctionReturn(0);
  PetscCall(JRModelGetBolts(model, &B));
  PetscCheck(B && B->n > 0 && B->n <= 32, o->comm, PETSC_ERR_ARG_WRONG, "-rom_joints %s needs a model with bolts (1 to 32)", JRReduceJointKinds[kind]);
  nb = B->n;
  for (PetscInt b = 0; b < nb; b++) xb[b] = B->x[3 * b];
  for (PetscInt b = 1; b < nb; b++) /* sort */
    for (PetscInt c = b; c > 0 && xb[c] < xb[c - 1]; c--) {
      const PetscReal t = xb[c];
      xb[c]             = xb[c - 1];
      xb[c - 1]         = t;
    }
  *ncut = 0;
  for (PetscInt b = 0; b < nb; b++) {
    if (kind != 3 && kind != 4 && b > 0) cut[(*ncut)++] = 0.5 * (xb[b - 1] + xb[b]); /* sides, zones */
    if (kind == 3 && b > 0) cut[(*ncut)++] = 0.5 * (xb[b - 1] + xb[b]);                  /* bolts */
    if (kind != 3) cut[(*ncut)++] = xb[b];                                               /* between, sides, zones */
  }
  PetscFunctionReturn(0);
}

/* -rom_joints strips, bolts, between, sides, zones: regions between cuts along the beam axis (halves of the width
   with -rom_split_width; zones: each split into a high-load and a low-load zone by -rom_zone_fraction) */
static PetscErrorCode AssignCuts(JRReduce o, JRModel model, const JRPairs *P, JRElements *el, const PetscInt pair[], PetscInt *nreg, PetscInt **cnt)
{
  MPI_Comm        comm = o->comm;
  const PetscInt  kind = o->joints, nz = kind == 6 ? 2 : 1;
  const PetscBool split = o->split_width;
  PetscInt        ncut;
  PetscReal       cut[64], ylo = PETSC_MAX_REAL, yhi = -PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  PetscCall(JointCuts(o, model, &ncut, cut));
  PetscCheck(kind != 2 || ncut > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_joints strips needs the cuts -rom_strips x1,x2,... [m]");
  for (PetscInt k = 1; k < ncut; k++) PetscCheck(cut[k] > cut[k - 1], comm, PETSC_ERR_ARG_WRONG, "-rom_strips: the cuts must increase, but %g m follows %g m", (double)cut[k], (double)cut[k - 1]);
  for (PetscInt e = 0; e < el->n; e++) {
    ylo = PetscMin(ylo, P->x[3 * pair[e] + 1]);
    yhi = PetscMax(yhi, P->x[3 * pair[e] + 1]);
  }
  *nreg = (ncut + 1) * (split ? 2 : 1) * nz;
  PetscCall(PetscCalloc1(*nreg, cnt));
  for (PetscInt e = 0; e < el->n; e++) {
    const PetscReal *x = P->x + 3 * pair[e];
    PetscInt         k = 0;
    while (k < ncut && x[0] >= cut[k]) k++;
    el->joint[e] = (split ? 2 * k + (x[1] > 0.5 * (ylo + yhi) ? 1 : 0) : k) * nz;
  }
  if (kind == 6) { /* zones: high load (>= zf of the side's largest n0) and low load */
    PetscReal *nmax;
    PetscCall(PetscCalloc1(*nreg, &nmax));
    for (PetscInt e = 0; e < el->n; e++) nmax[el->joint[e]] = PetscMax(nmax[el->joint[e]], el->n0[e]);
    for (PetscInt e = 0; e < el->n; e++) el->joint[e] += (nmax[el->joint[e]] > 0 && el->n0[e] >= o->zone_fraction * nmax[el->joint[e]]) ? 1 : 0;
    PetscCall(PetscFree(nmax));
  }
  for (PetscInt e = 0; e < el->n; e++) (*cnt)[el->joint[e]]++;
  PetscCall(PetscCalloc1(*nreg, &o->ji));
  for (PetscInt r = 0; r < *nreg; r++) {
    const PetscInt k = (split ? r / (2 * nz) : r / nz);
    o->ji[r].zone    = nz > 1 ? r % 2 : -1;
    PetscCall(PetscSNPrintf(o->ji[r].kind, sizeof(o->ji[r].kind), "%s %" PetscInt_FMT " of %" PetscInt_FMT "%s%s", RegionWords[kind], k + 1, ncut + 1, split ? ((r / nz) % 2 ? ", upper half" : ", lower half") : "", nz > 1 ? (r % 2 ? ", high-load zone" : ", low-load zone") : ""));
    PetscCheck((*cnt)[r] > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_joints %s: the region x %s%g .. %g%s m%s%s holds no element: an empty joint (%s)", JRReduceJointKinds[kind], k ? "" : "< ", (double)(k ? cut[k - 1] : cut[0]), (double)(k < ncut ? cut[k] : cut[ncut - 1]), k < ncut ? "" : " and beyond", split ? ((r / nz) % 2 ? ", upper half of the width" : ", lower half of the width") : "", nz > 1 ? (r % 2 ? ", high-load zone" : ", low-load zone") : "", kind == 2 ? "move the cuts" : kind == 6 ? "change -rom_zone_fraction" : "fewer regions");
  }
  PetscFunctionReturn(0);
}

/* The joints' report (JRJointInfo, o->ji) from the elements el with their joints and positions x (3 per element) */
static PetscErrorCode JointInfoSet(JRReduce o, const JRElements *el, const PetscReal x[])
{
  PetscFunctionBeginUser;
  if (!o->ji) {
    PetscCall(PetscCalloc1(el->njoints, &o->ji));
    for (PetscInt j = 0; j < el->njoints; j++) o->ji[j].zone = -1;
  }
  o->nji = el->njoints;
  for (PetscInt e = 0; e < el->n; e++) {
    JRJointInfo *J = &o->ji[el->joint[e]];
    J->members++;
    if (el->n0[e] > 0) {
      J->contact++;
      J->load += el->n0[e];
    }
    for (PetscInt c = 0; x && c < 3; c++) J->x[c] += x[3 * e + c];
  }
  for (PetscInt j = 0; j < o->nji; j++)
    for (PetscInt c = 0; c < 3; c++) o->ji[j].x[c] /= o->ji[j].members;
  PetscFunctionReturn(0);
}

/* A joint for a line: index, members, centroid and region */
PetscErrorCode JRReduceJointName(JRReduce o, PetscInt j, char buf[], size_t len)
{
  const JRJointInfo *J = &o->ji[j];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, len, "%" PetscInt_FMT " (%" PetscInt_FMT " members, centroid (%.4g, %.4g) m, %s)", j, J->members, (double)J->x[0], (double)J->x[1], J->kind));
  PetscFunctionReturn(0);
}

/*
  The joints' report: per joint its members (those in contact at rest), the normal load they carry at rest and its
  share of the interface's (the preload), their centroid and the region; then how the partition splits the members
  between high-load and low-load joints: -rom_joints zones by its zones, auto by its rings (the inner half), any other
  partition by load per member (a joint is high-load when its members carry more than the interface's mean per
  member). Rank 0 prints; every rank has
  every element, so the lines do not depend on the ranks.
*/
static PetscErrorCode JointReport(JRReduce o, const JRElements *el)
{
  MPI_Comm  comm = o->comm;
  PetscReal ltot = 0, lh = 0, mean;
  PetscInt  nh = 0, mh = 0, ch = 0, ctot = 0;
  char      list[256] = "";

  PetscFunctionBeginUser;
  for (PetscInt j = 0; j < o->nji; j++) {
    ltot += o->ji[j].load;
    ctot += o->ji[j].contact;
  }
  mean = ltot / el->n;
  if (o->joints == 1) PetscCall(PetscPrintf(comm, "rom: every element its own joint: %" PetscInt_FMT " joints (%" PetscInt_FMT " in contact at rest, normal load %.6g N)\n", o->nji, ctot, (double)ltot));
  for (PetscInt j = 0; j < o->nji && o->joints != 1; j++) {
    const JRJointInfo *J = &o->ji[j];
    PetscCall(PetscPrintf(comm, "rom: joint %" PetscInt_FMT ": %" PetscInt_FMT " members (%" PetscInt_FMT " in contact), normal load %.6g N (%.1f%% of the preload), centroid (%.4g, %.4g, %.4g) m, %s\n", j, J->members, J->contact, (double)J->load, (double)(ltot > 0 ? 100 * J->load / ltot : 0), (double)J->x[0], (double)J->x[1], (double)J->x[2], J->kind));
  }
  for (PetscInt j = 0; j < o->nji; j++) {
    const JRJointInfo *J  = &o->ji[j];
    const PetscBool    hi = J->zone >= 0 ? (PetscBool)(J->zone == 1) : (PetscBool)(J->load > mean * J->members);
    size_t             len;
    if (!hi) continue;
    nh++;
    mh += J->members;
    ch += J->contact;
    lh += J->load;
    PetscCall(PetscStrlen(list, &len));
    if (len < sizeof(list) - 24) PetscCall(PetscSNPrintf(list + len, sizeof(list) - len, "%s%" PetscInt_FMT, len ? "," : "", j));
  }
  if (o->joints == 1) PetscFunctionReturn(0);
  PetscCall(PetscPrintf(comm, "rom: partition %s: %" PetscInt_FMT " high-load joints (%s, %s) hold %" PetscInt_FMT " of %" PetscInt_FMT " members (%.1f%%), %" PetscInt_FMT " of %" PetscInt_FMT " in contact (%.1f%%) and %.1f%% of the preload; %" PetscInt_FMT " low-load joints the rest\n", JRReduceJointKinds[o->joints], nh, nh ? list : "none", o->joints == 6 ? "the zones' high-load joints" : o->joints == 8 ? "the inner rings" : "more load per member than the interface's mean", mh, el->n, (double)(100.0 * mh / el->n), ch, ctot, (double)(ctot ? 100.0 * ch / ctot : 0), (double)(ltot > 0 ? 100 * lh / ltot : 0), o->nji - nh));
  PetscCall(PetscPrintf(comm, "rom partition joints %" PetscInt_FMT " high_load_joints %" PetscInt_FMT " member_share %.4f contact_share %.4f load_share %.4f\n", o->nji, nh, (double)((PetscReal)mh / el->n), (double)(ctot ? (PetscReal)ch / ctot : 0), (double)(ltot > 0 ? lh / ltot : 0)));
  PetscFunctionReturn(0);
}

static PetscErrorCode AssignJoints(JRReduce o, JRModel model, const JRPairs *P, JRElements *el, const PetscInt pair[])
{
  PetscInt   nreg = 0, *cnt = NULL;
  PetscReal *x;

  PetscFunctionBeginUser;
  if (o->joints == 0) PetscFunctionReturn(0);
  PetscCall(PetscFree(o->ji));
  PetscCall(PetscMalloc1(el->n, &el->joint));
  if (o->joints == 1) { /* each */
    nreg = el->n;
    for (PetscInt e = 0; e < el->n; e++) el->joint[e] = e;
    PetscCall(PetscCalloc1(nreg, &o->ji));
    for (PetscInt e = 0; e < el->n; e++) {
      o->ji[e].zone = -1;
      PetscCall(PetscStrncpy(o->ji[e].kind, RegionWords[1], sizeof(o->ji[e].kind)));
    }
  } else if (o->joints == 9) { /* onset: one provisional joint; JRReduceSetUp sets them from the stuck mode */
    PetscInt *side, nb;
    PetscCall(PetscMalloc1(el->n, &side)); /* the bolts are needed: checked now, before the modes */
    PetscCall(BoltSides(o, model, P, el, pair, side, &nb));
    PetscCall(PetscFree(side));
    nreg = 1;
    for (PetscInt e = 0; e < el->n; e++) el->joint[e] = 0;
    el->njoints = 1;
    PetscFunctionReturn(0);
  } else if (o->joints == 7) PetscCall(AssignBoxes(o, P, el, pair, &nreg, &cnt));
  else if (o->joints == 8) PetscCall(AssignAuto(o, model, P, el, pair, &nreg, &cnt));
  else PetscCall(AssignCuts(o, model, P, el, pair, &nreg, &cnt));
  el->njoints = nreg;
  PetscCall(PetscMalloc1(3 * el->n + 1, &x));
  for (PetscInt e = 0; e < el->n; e++)
    for (PetscInt c = 0; c < 3; c++) x[3 * e + c] = P->x[3 * pair[e] + c];
  PetscCall(JointInfoSet(o, el, x));
  PetscCall(PetscFree(x));
  PetscCall(JointReport(o, el));
  PetscCall(PetscFree(cnt));
  PetscFunctionReturn(0);
}

/* JRReduceAssignJoints - the first reduction's regions: el->joint and el->njoints of the node-to-node elements el
   (element e on pair pair[e] of the model); nothing with -rom_joints none */
PetscErrorCode JRReduceAssignJoints(JRReduce r, JRModel model, JRElements *el, const PetscInt pair[])
{
  const JRPairs *P;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(JR_ReduceJoints, 0, 0, 0, 0));
  PetscCall(JRModelGetPairs(model, &P));
  r->pair = pair;
  PetscCall(AssignJoints(r, model, P, el, pair));
  PetscCall(PetscLogEventEnd(JR_ReduceJoints, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* ord[0..n) sorted by a[ord[i]], ties in the given order (insertion sort: stable, the same on every rank) */
static void SortByValue(const PetscReal a[], PetscInt n, PetscInt ord[])
{
  for (PetscInt i = 1; i < n; i++)
    for (PetscInt c = i; c > 0 && a[ord[c]] < a[ord[c - 1]]; c--) {
      const PetscInt t = ord[c];
      ord[c]           = ord[c - 1];
      ord[c - 1]       = t;
    }
}

/* The band of x among k bands of equal ratio from x0 to x1 (below x0 the first, above x1 the last) */
static inline PetscInt EqualRatioBand(PetscReal x, PetscReal x0, PetscReal x1, PetscInt k)
{
  const PetscInt band = x1 > x0 && x > x0 ? (PetscInt)PetscFloorReal(k * PetscLogReal(x / x0) / PetscLogReal(x1 / x0)) : 0;
  return PetscMin(PetscMax(band, 0), k - 1);
}

/*
  JRReduceAssignOnset - -rom_joints onset: the joints of el (the node-to-node elements) from their slip onsets (and the
  open ones' closing onsets) in the stuck mode of interest, u[e] and v[e] each element's tangential and normal motion
  in it (see the top of this file), then the report
*/
PetscErrorCode JRReduceAssignOnset(JRReduce o, JRModel model, JRElements *el, const PetscReal u[], const PetscReal v[])
{
  MPI_Comm       comm = o->comm;
  const JRPairs *P;
  const PetscInt k = o->bands, ko = o->obands, kk = k + ko, n = el->n;
  PetscInt      *side, *ord, nb = 0, nc = 0, nreg = 0;
  PetscReal     *a, cap = 0, sum = 0, *x, a0, a1, oc[2] = {0, 0};

  PetscFunctionBeginUser;
  PetscCheck(o->pair, comm, PETSC_ERR_ORDER, "JRReduceAssignJoints() first");
  PetscCall(JRModelGetPairs(model, &P));
  PetscCall(PetscMalloc3(n, &side, n, &ord, n, &a));
  PetscCall(BoltSides(o, model, P, el, o->pair, side, &nb));
  for (PetscInt e = 0; e < n; e++) {
    if (!(el->n0[e] > 0)) continue;
    a[e] = PetscAbsReal(u[e]) > 0 ? el->mu[e] * el->n0[e] / (el->kt[e] * PetscAbsReal(u[e])) : PETSC_MAX_REAL;
    cap += el->mu[e] * el->n0[e];
    ord[nc++] = e;
  }
  PetscCheck(nc > 0, comm, PETSC_ERR_ARG_WRONG, "-rom_joints onset: no member is in contact at rest");
  SortByValue(a, nc, ord); /* by onset, then index */
  for (PetscInt e = 0; e < n; e++) el->joint[e] = -1;
  a0 = a1 = a[ord[0]];
  { /* bands of equal ratio from the first onset a0 to a1, by which the fraction upto of the slip force slips */
    for (PetscInt i = 0; i < nc; i++) {
      sum += el->mu[ord[i]] * el->n0[ord[i]];
      a1 = a[ord[i]];
      if (sum >= o->upto * cap * (1 - 1e-12)) break;
    }
    for (PetscInt i = 0; i < nc; i++) el->joint[ord[i]] = side[ord[i]] * kk + EqualRatioBand(a[ord[i]], a0, a1, k);
  }
  { /* open members: their bolt side's gap joints, by closing onset c_e in bands of equal ratio from the first, c0, to
       c1, by which the fraction upto of them close */
    PetscInt no = 0;
    for (PetscInt e = 0; e < n; e++) {
      if (el->n0[e] > 0) continue;
      a[e]      = el->kn[e] > 0 && PetscAbsReal(v[e]) > 0 ? -el->n0[e] / (el->kn[e] * PetscAbsReal(v[e])) : PETSC_MAX_REAL;
      ord[no++] = e;
    }
    SortByValue(a, no, ord); /* by closing onset, then index */
    if (no) {
      PetscInt  i0 = 0;
      PetscReal c0, c1;
      while (i0 < no - 1 && !(a[ord[i0]] > 0)) i0++; /* members touching at rest (c = 0) join the first band */
      c0 = a[ord[i0]];
      c1 = a[ord[PetscMin(no - 1, PetscMax(i0, (PetscInt)PetscCeilReal(o->upto * no * (1 - 1e-12)) - 1))]];
      oc[0] = c0;
      oc[1] = c1;
      for (PetscInt i = 0; i < no; i++) el->joint[ord[i]] = side[ord[i]] * kk + k + EqualRatioBand(a[ord[i]], c0, c1, ko);
    }
  }
  { /* drop the empty joints, number the rest in order */
    PetscInt *map;
    PetscCall(PetscMalloc1(2 * nb * kk, &map));
    for (PetscInt r = 0; r < 2 * nb * kk; r++) map[r] = -1;
    for (PetscInt e = 0; e < n; e++) map[el->joint[e]] = 0;
    for (PetscInt r = 0; r < 2 * nb * kk; r++)
      if (!map[r]) map[r] = nreg++;
    PetscCall(PetscFree(o->ji));
    PetscCall(PetscCalloc1(nreg, &o->ji));
    for (PetscInt r = 0; r < 2 * nb * kk; r++) {
      if (map[r] < 0) continue;
      o->ji[map[r]].zone = -1;
      const PetscInt b = r / (2 * kk) + 1, band = r % kk;
      const char    *sd = (r / kk) % 2 ? "+x" : "-x";
      if (band < k) PetscCall(PetscSNPrintf(o->ji[map[r]].kind, sizeof(o->ji[map[r]].kind), "onset band %" PetscInt_FMT " of %" PetscInt_FMT ", bolt %" PetscInt_FMT ", %s side", band + 1, k, b, sd));
      else if (ko == 1) PetscCall(PetscSNPrintf(o->ji[map[r]].kind, sizeof(o->ji[map[r]].kind), "open pairs, bolt %" PetscInt_FMT ", %s side", b, sd));
      else PetscCall(PetscSNPrintf(o->ji[map[r]].kind, sizeof(o->ji[map[r]].kind), "open pairs, closing band %" PetscInt_FMT " of %" PetscInt_FMT ", bolt %" PetscInt_FMT ", %s side", band - k + 1, ko, b, sd));
    }
    for (PetscInt e = 0; e < n; e++) el->joint[e] = map[el->joint[e]];
    PetscCall(PetscFree(map));
  }
  el->njoints = nreg;
  if (ko == 1) PetscCall(PetscPrintf(comm, "rom: onset partition: the first member in contact starts to slip at the modal amplitude %.4g in the stuck mode, %g of the slip force by %.4g; %" PetscInt_FMT " bands of equal ratio between, and the open pairs, split by bolt side: %" PetscInt_FMT " joints\n", (double)a0, (double)o->upto, (double)a1, k, nreg));
  else PetscCall(PetscPrintf(comm, "rom: onset partition: the first member in contact starts to slip at the modal amplitude %.4g in the stuck mode, %g of the slip force by %.4g; %" PetscInt_FMT " bands of equal ratio between; the first open member closes at %.4g, %g of them by %.4g; %" PetscInt_FMT " bands of equal ratio between; split by bolt side: %" PetscInt_FMT " joints\n", (double)a0, (double)o->upto, (double)a1, k, (double)oc[0], (double)o->upto, (double)oc[1], ko, nreg));
  PetscCall(PetscMalloc1(3 * n + 1, &x));
  for (PetscInt e = 0; e < n; e++)
    for (PetscInt c = 0; c < 3; c++) x[3 * e + c] = P->x[3 * o->pair[e] + c];
  PetscCall(JointInfoSet(o, el, x));
  PetscCall(PetscFree(x));
  PetscCall(JointReport(o, el));
  PetscCall(PetscFree3(side, ord, a));
  PetscFunctionReturn(0);
}
