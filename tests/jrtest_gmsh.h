/* Test helpers for the FE models (tests/test_fe.c, tests/test_preload.c): the options database, a model from
   options, and a hand-written Gmsh file of two stacked blocks. */
#if !defined(JRTEST_GMSH_H)
#define JRTEST_GMSH_H
#include "jrtest.h"

/* the options database replaced by s */
static PetscErrorCode Options(const char *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, s));
  PetscFunctionReturn(0);
}

/* a model created and set up from the options opts alone */
static PetscErrorCode ModelCreate(const char *opts, JRModel *m)
{
  PetscFunctionBeginUser;
  PetscCall(Options(opts));
  PetscCall(JRModelCreate(PETSC_COMM_WORLD, m));
  PetscCall(JRModelSetFromOptions(*m));
  PetscCall(JRModelSetUp(*m));
  PetscFunctionReturn(0);
}

/*
  A Gmsh 2.2 file: two blocks of nx x ny x nz hexahedra, A on z in [0, c], B on z in [c, 2c], each
  Lx x Ly, with their own nodes on the plane z = c (contact_a: A's top, contact_b: B's bottom). The
  vertices inside a block are moved by up to 0.2 of a cell in each direction (non-affine hexahedra);
  B's interface nodes are shifted by dx along x. Groups: body (volumes), contact_a, contact_b and, with
  bolt, bolt1_head (B's top) and bolt1_nut (A's bottom); skip: a group to leave out.
*/
#define GM_NX 6
#define GM_NY 4
#define GM_NZ 2
static const PetscReal GM_LX = 0.06, GM_LY = 0.04, GM_C = 0.01;

PETSC_UNUSED static PetscErrorCode WriteGmsh(const char *file, PetscBool bolt, PetscReal dx, const char *skip)
{
  FILE          *fp;
  const PetscInt nv = (GM_NX + 1) * (GM_NY + 1) * (GM_NZ + 1), nc = GM_NX * GM_NY * GM_NZ, nq = GM_NX * GM_NY;
  const char    *names[5] = {"body", "contact_a", "contact_b", "bolt1_head", "bolt1_nut"};
  const int      dims[5]  = {3, 2, 2, 2, 2};
  int            ngroups  = bolt ? 5 : 3, nphys = 0, eid = 1;
  unsigned       seed     = 12345;

  PetscFunctionBeginUser;
  if (JRTestRank()) PetscFunctionReturn(0);
  fp = fopen(file, "w");
  PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot write %s", file);
  for (int g = 0; g < ngroups; g++) nphys += !(skip && !strcmp(skip, names[g]));
  fprintf(fp, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n%d\n", nphys);
  for (int g = 0; g < ngroups; g++)
    if (!(skip && !strcmp(skip, names[g]))) fprintf(fp, "%d %d \"%s\"\n", dims[g], g + 1, names[g]);
  fprintf(fp, "$EndPhysicalNames\n$Nodes\n%d\n", (int)(2 * nv));
  for (int b = 0; b < 2; b++)
    for (int k = 0; k <= GM_NZ; k++)
      for (int j = 0; j <= GM_NY; j++)
        for (int i = 0; i <= GM_NX; i++) {
          const int inner = i > 0 && i < GM_NX && j > 0 && j < GM_NY && k > 0 && k < GM_NZ;
          double    x = GM_LX * i / GM_NX, y = GM_LY * j / GM_NY, z = GM_C * (b + (double)k / GM_NZ);
          if (inner) { /* a fixed pseudo-random distortion */
            double r[3];
            for (int d = 0; d < 3; d++) {
              seed = seed * 1103515245u + 12345u;
              r[d] = ((seed >> 8) & 0xffff) / 65535.0 - 0.5;
            }
            x += 0.4 * r[0] * GM_LX / GM_NX;
            y += 0.4 * r[1] * GM_LY / GM_NY;
            z += 0.4 * r[2] * GM_C / GM_NZ;
          }
          if (b == 1 && k == 0) x += dx;
          fprintf(fp, "%d %.17g %.17g %.17g\n", (int)(b * nv + (k * (GM_NY + 1) + j) * (GM_NX + 1) + i + 1), x, y, z);
        }
  fprintf(fp, "$EndNodes\n$Elements\n%d\n", (int)(2 * nc + 2 * nq + (bolt ? 2 * nq : 0)));
#define GID(b, i, j, k) ((int)((b) * nv + ((k) * (GM_NY + 1) + (j)) * (GM_NX + 1) + (i) + 1))
  for (int b = 0; b < 2; b++) /* hexahedra (Gmsh type 5): bottom face counter-clockwise, then top */
    for (int k = 0; k < GM_NZ; k++)
      for (int j = 0; j < GM_NY; j++)
        for (int i = 0; i < GM_NX; i++)
          fprintf(fp, "%d 5 2 1 %d %d %d %d %d %d %d %d %d\n", eid++, b + 1, GID(b, i, j, k), GID(b, i + 1, j, k), GID(b, i + 1, j + 1, k), GID(b, i, j + 1, k), GID(b, i, j, k + 1), GID(b, i + 1, j, k + 1), GID(b, i + 1, j + 1, k + 1), GID(b, i, j + 1, k + 1));
  for (int s = 0; s < (bolt ? 4 : 2); s++) { /* quadrangles (type 3): A's top, B's bottom, B's top, A's bottom */
    const int b = s == 0 || s == 3 ? 0 : 1, k = s == 0 || s == 2 ? GM_NZ : 0, phys = s + 2;
    for (int j = 0; j < GM_NY; j++)
      for (int i = 0; i < GM_NX; i++) fprintf(fp, "%d 3 2 %d %d %d %d %d %d\n", eid++, (skip && !strcmp(skip, names[phys - 1])) ? 0 : phys, 10 + s, GID(b, i, j, k), GID(b, i + 1, j, k), GID(b, i + 1, j + 1, k), GID(b, i, j + 1, k));
  }
#undef GID
  fprintf(fp, "$EndElements\n");
  fclose(fp);
  PetscFunctionReturn(0);
}

#endif
