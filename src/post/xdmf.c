/*
   The XDMF writer (ParaView's description of the datasets of an HDF5 file): grids that are either the hexahedral
   mesh of a DM as PETSc's HDF5 viewer writes it (/viz/topology/cells, /geometry/vertices) or a set of points, each
   with nodal fields (scalars or 3-vectors). Used by the mode files (src/post/modes.c) and the preload's
   (src/preload/io.c).
*/
#include <jointrom.h>
#include <petscdmplex.h>

/* The global numbers of cells and of vertices of dm (collective) */
static PetscErrorCode MeshSizes(MPI_Comm comm, DM dm, PetscInt *nc, PetscInt *nv)
{
  PetscInt        cs, ce, nl, own = 0;
  IS              vn;
  const PetscInt *idx;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cs, &ce));
  *nc = ce - cs;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, nc, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(DMPlexGetVertexNumbering(dm, &vn));
  PetscCall(ISGetLocalSize(vn, &nl));
  PetscCall(ISGetIndices(vn, &idx));
  for (PetscInt i = 0; i < nl; i++) own += idx[i] >= 0;
  PetscCall(ISRestoreIndices(vn, &idx));
  PetscCallMPI(MPI_Allreduce(&own, nv, 1, MPIU_INT, MPI_SUM, comm));
  PetscFunctionReturn(0);
}

/*
  JRXdmfWrite - xdmf describing the ngrids grids whose datasets are in h5 (named relative to xdmf's directory by its
  last path component), written through a temporary name (collective: rank 0 writes).
*/
PetscErrorCode JRXdmfWrite(MPI_Comm comm, const char xdmf[], const char h5[], PetscInt ngrids, const JRXdmfGrid grids[])
{
  const char *leaf = strrchr(h5, '/') ? strrchr(h5, '/') + 1 : h5;
  char        tmp[PETSC_MAX_PATH_LEN + 32];
  FILE       *fp;
  PetscInt   *nc, *nv;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(ngrids, &nc, ngrids, &nv));
  for (PetscInt g = 0; g < ngrids; g++) {
    if (grids[g].dm) PetscCall(MeshSizes(comm, grids[g].dm, &nc[g], &nv[g]));
    else nc[g] = nv[g] = grids[g].npoints;
  }
  PetscCall(JRFileOpenTemp(comm, xdmf, &fp, tmp, sizeof(tmp)));
  if (fp) {
    fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n");
    for (PetscInt g = 0; g < ngrids; g++) {
      const JRXdmfGrid *G = &grids[g];
      fprintf(fp, "  <Grid Name=\"%s\" GridType=\"Uniform\">\n", G->name);
      if (G->dm) {
        fprintf(fp, "   <Topology TopologyType=\"Hexahedron\" NumberOfElements=\"%" PetscInt_FMT "\">\n    <DataItem Dimensions=\"%" PetscInt_FMT " 8\" NumberType=\"Int\" Format=\"HDF\">%s:/viz/topology/cells</DataItem>\n   </Topology>\n", nc[g], nc[g], leaf);
        fprintf(fp, "   <Geometry GeometryType=\"XYZ\">\n    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/geometry/vertices</DataItem>\n   </Geometry>\n", nv[g], leaf);
      } else {
        fprintf(fp, "   <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%" PetscInt_FMT "\"/>\n", nv[g]);
        fprintf(fp, "   <Geometry GeometryType=\"XYZ\">\n    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:%s</DataItem>\n   </Geometry>\n", nv[g], leaf, G->geometry);
      }
      for (PetscInt f = 0; f < G->nfields; f++) {
        const JRXdmfField *F = &G->fields[f];
        if (F->ncomp == 3) fprintf(fp, "   <Attribute Name=\"%s\" AttributeType=\"Vector\" Center=\"Node\">\n    <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:%s</DataItem>\n   </Attribute>\n", F->name, nv[g], leaf, F->dataset);
        else fprintf(fp, "   <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">\n    <DataItem Dimensions=\"%" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:%s</DataItem>\n   </Attribute>\n", F->name, nv[g], leaf, F->dataset);
      }
      fprintf(fp, "  </Grid>\n");
    }
    fprintf(fp, " </Domain>\n</Xdmf>\n");
  }
  PetscCall(JRFileCommit(comm, &fp, tmp, xdmf));
  PetscCall(PetscFree2(nc, nv));
  PetscFunctionReturn(0);
}
