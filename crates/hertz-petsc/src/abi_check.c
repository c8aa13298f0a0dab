/* Compiled with -fsyntax-only by build.rs: fails the build when an assumption of src/ffi.rs (the
 * hand-written declarations) does not hold for the PETSc and MPI that pkg-config found.
 * EXPECT_* come from build.rs. */
#include <petscksp.h>

#if defined(PETSC_USE_COMPLEX) || !defined(PETSC_USE_REAL_DOUBLE)
#error "real, double-precision PETSc required (Debian: libpetsc-real3.18-dev)"
#endif
_Static_assert(PETSC_VERSION_MAJOR == 3 && PETSC_VERSION_MINOR >= 18, "PETSc >= 3.18 required");
_Static_assert(sizeof(PetscInt) == EXPECT_PETSCINT_SIZE, "PetscInt width differs from build.rs detection");
_Static_assert(sizeof(PetscScalar) == 8 && sizeof(PetscReal) == 8, "PetscScalar/PetscReal must be double");
_Static_assert(sizeof(MPI_Comm) == EXPECT_MPI_COMM_SIZE, "MPI_Comm size differs from build.rs detection");
_Static_assert(sizeof(PetscBool) == 4 && sizeof(InsertMode) == 4 && sizeof(MatOption) == 4, "enum sizes");
_Static_assert(sizeof(ScatterMode) == 4 && sizeof(KSPConvergedReason) == 4, "enum sizes");
_Static_assert(PETSC_FALSE == 0 && PETSC_TRUE == 1, "PetscBool");
_Static_assert(INSERT_VALUES == 1 && ADD_VALUES == 2, "InsertMode");
_Static_assert(MAT_FINAL_ASSEMBLY == 0, "MatAssemblyType");
_Static_assert(SCATTER_FORWARD == 0, "ScatterMode");
_Static_assert(MAT_SYMMETRIC == 1 && MAT_SYMMETRY_ETERNAL == 10 && MAT_SPD == 15, "MatOption");
_Static_assert(PETSC_DECIDE == -1 && PETSC_DEFAULT == -2, "PETSC_DECIDE/DEFAULT");
