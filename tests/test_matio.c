/*
   Matrix and vector files: a matrix written as Matrix Market, PETSc binary and HDF5 (MATLAB v7.3
   sparse) reads back equal to the original, general and symmetric; force vectors from text files,
   with and without a header line.
*/
#include "jrtest.h"

int main(int argc, char **argv)
{
  Mat       A, B;
  PetscInt  n = 7, lo, hi;
  PetscBool eq;
  char      dir[] = "/tmp/jrmatioXXXXXX";

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  if (!JRTestRank()) PetscCheck(mkdtemp(dir), PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "mkdtemp");
  PetscCallMPI(MPI_Bcast(dir, sizeof(dir), MPI_CHAR, 0, PETSC_COMM_WORLD));
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, n, n, 3, NULL, 3, NULL, &A));
  PetscCall(MatGetOwnershipRange(A, &lo, &hi));
  for (PetscInt i = lo; i < hi; i++) { /* non-symmetric on purpose: checks the CSC/CSR orientation */
    PetscCall(MatSetValue(A, i, i, 10.0 + i, INSERT_VALUES));
    if (i + 1 < n) PetscCall(MatSetValue(A, i, i + 1, -1.5 - 0.1 * i, INSERT_VALUES));
    if (i > 1) PetscCall(MatSetValue(A, i, i - 2, 0.25 * i, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  {
    const char *ext[3] = {"mtx", "bin", "h5"};
    for (int k = 0; k < 3; k++) {
      char file[256];
      PetscCall(PetscSNPrintf(file, sizeof(file), "%s/A.%s", dir, ext[k]));
      PetscCall(JRMatSaveFile(A, file, "K"));
      PetscCall(JRMatLoadFile(PETSC_COMM_WORLD, file, "K", &B));
      PetscCall(MatEqual(A, B, &eq));
      CHECK(eq, "matrix written and read back as .%s equals the original (7 x 7, non-symmetric)", ext[k]);
      PetscCall(MatDestroy(&B));
    }
  }
  /* a symmetric Matrix Market file stores one triangle; the reader mirrors it */
  if (!JRTestRank()) {
    char  file[256];
    FILE *fp;
    PetscCall(PetscSNPrintf(file, sizeof(file), "%s/S.mtx", dir));
    fp = fopen(file, "w");
    fprintf(fp, "%%%%MatrixMarket matrix coordinate real symmetric\n%% comment\n3 3 4\n1 1 2.0\n2 1 -1.0\n2 2 2.0\n3 3 1.5\n");
    fclose(fp);
  }
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  {
    char      file[256];
    PetscReal v;
    Vec       x, y;
    PetscCall(PetscSNPrintf(file, sizeof(file), "%s/S.mtx", dir));
    PetscCall(JRMatLoadFile(PETSC_COMM_WORLD, file, "K", &B));
    PetscCall(MatIsSymmetric(B, 0.0, &eq));
    PetscCall(MatCreateVecs(B, &x, &y));
    PetscCall(VecSetValue(x, 1, 1.0, INSERT_VALUES)); /* column 1 of B: [A01, A11, A21] = [-1, 2, 0] if mirrored */
    PetscCall(VecAssemblyBegin(x));
    PetscCall(VecAssemblyEnd(x));
    PetscCall(MatMult(B, x, y));
    PetscCall(VecMin(y, NULL, &v));
    PetscCall(VecDestroy(&x));
    PetscCall(VecDestroy(&y));
    CHECK(eq && v == -1.0, "symmetric Matrix Market file: the lower triangle is mirrored (A01 = %g)", (double)v);
    PetscCall(MatDestroy(&B));
  }
  /* force vectors from text: plain numbers, or a header line */
  if (!JRTestRank()) {
    char  file[256];
    FILE *fp;
    PetscCall(PetscSNPrintf(file, sizeof(file), "%s/f1.csv", dir));
    fp = fopen(file, "w");
    fprintf(fp, "# force shape\n0\n1.5\n-2\n");
    fclose(fp);
    PetscCall(PetscSNPrintf(file, sizeof(file), "%s/f2.csv", dir));
    fp = fopen(file, "w");
    fprintf(fp, "f_N\n0\n1.5\n-2\n");
    fclose(fp);
  }
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  for (int k = 1; k <= 2; k++) {
    char      file[256];
    PetscReal f[3];
    PetscCall(PetscSNPrintf(file, sizeof(file), "%s/f%d.csv", dir, k));
    PetscCall(JRVecLoadFile(PETSC_COMM_WORLD, file, 3, f));
    CHECK(f[0] == 0.0 && f[1] == 1.5 && f[2] == -2.0, "force vector from text %s: %g %g %g", k == 1 ? "without a header" : "with a header", (double)f[0], (double)f[1], (double)f[2]);
  }
  PetscCall(MatDestroy(&A));
  if (!JRTestRank()) {
    char cmd[300];
    PetscCall(PetscSNPrintf(cmd, sizeof(cmd), "rm -rf %s", dir));
    if (system(cmd)) { /* nothing to do */
    }
  }
  PetscCall(PetscFinalize());
  return TestSummary("test_matio");
}
