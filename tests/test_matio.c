/*
   Matrix and vector files: a matrix written as Matrix Market, PETSc binary and HDF5 (MATLAB v7.3
   sparse) reads back equal to the original, general and symmetric; force vectors from text files,
   with and without a header line; bad Matrix Market files refused with the line and what is wrong (a value that is
   not a finite number, a field too many, an entry given twice, more entries than announced, a bad size line, an
   index outside the size), a byte-order mark skipped.
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
  { /* bad Matrix Market files (symmetric): each refused with its line and what is wrong */
    const char *bad[][2] = {
      {"2 2 3\n1 1 1\n2 1 abc\n2 2 1\n", "line 4: bad entry '2 1 abc': field 3 (the value) 'abc' is not a finite number"},
      {"1 1 1\n1 1 inf\n", "line 3: bad entry '1 1 inf': field 3 (the value) 'inf' is not a finite number"},
      {"1 1 1\n1 1 2 3\n", "line 3: bad entry '1 1 2 3': 4 fields"},
      {"2 2 3\n1 1 1\n2 1 1\n1 2 1\n", "line 5: entry (2, 1) is given again (first at line 4)"},
      {"1 1 1\n1 1 1\n1 1 1\n", "line 4: more entries than the 1 the size line announces"},
      {"1 1\n1 1 1\n", "bad size line '1 1'"},
      {"2 2 1\n3 1 1\n", "line 3: bad entry '3 1 1': indices are 1-based within the size 2 x 2"},
    };
    for (size_t k = 0; k < sizeof(bad) / sizeof(bad[0]); k++) {
      char           file[256], msg[512];
      PetscErrorCode ierr;
      PetscCall(PetscSNPrintf(file, sizeof(file), "%s/bad%d.mtx", dir, (int)k));
      if (!JRTestRank()) {
        FILE *fp = fopen(file, "w");
        fprintf(fp, "%%%%MatrixMarket matrix coordinate real symmetric\n%s", bad[k][0]);
        fclose(fp);
      }
      PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
      B = NULL;
      PetscCall(JRErrorCatchPush());
      ierr = JRMatLoadFile(PETSC_COMM_WORLD, file, "K", &B);
      PetscCall(JRErrorCatchPop(msg, sizeof(msg)));
      CHECK(ierr && strstr(msg, bad[k][1]), "bad Matrix Market file %d refused: %s", (int)k, msg);
      if (!ierr) PetscCall(MatDestroy(&B));
    }
  }
  { /* a byte-order mark before the banner is skipped; a general file keeps (1,2) and (2,1) apart */
    char      file[256];
    PetscReal a01 = 0, a10 = 0;
    PetscCall(PetscSNPrintf(file, sizeof(file), "%s/bom.mtx", dir));
    if (!JRTestRank()) {
      FILE *fp = fopen(file, "w");
      fprintf(fp, "\xEF\xBB\xBF%%%%MatrixMarket matrix coordinate real general\n2 2 3\n1 1 2\n1 2 -1\n2 2 2\n");
      fclose(fp);
    }
    PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
    PetscCall(JRMatLoadFile(PETSC_COMM_WORLD, file, "K", &B));
    {
      Mat               *sub;
      IS                 is;
      const PetscInt     rows[2] = {0, 1};
      const PetscScalar *v;
      PetscCall(ISCreateGeneral(PETSC_COMM_SELF, 2, rows, PETSC_COPY_VALUES, &is));
      PetscCall(MatCreateSubMatrices(B, 1, &is, &is, MAT_INITIAL_MATRIX, &sub));
      PetscCall(MatConvert(sub[0], MATSEQDENSE, MAT_INPLACE_MATRIX, &sub[0]));
      PetscCall(MatDenseGetArrayRead(sub[0], &v));
      a01 = PetscRealPart(v[2]); /* column-major */
      a10 = PetscRealPart(v[1]);
      PetscCall(MatDenseRestoreArrayRead(sub[0], &v));
      PetscCall(MatDestroySubMatrices(1, &sub));
      PetscCall(ISDestroy(&is));
    }
    CHECK(a01 == -1.0 && a10 == 0.0, "Matrix Market file after a byte-order mark, general: A01 = %g, A10 = %g", (double)a01, (double)a10);
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
