//! Hand-written declarations of the PETSc (3.18+) and MPI calls hertz-petsc makes: no bindgen,
//! no libclang. build.rs checks every size and enum value hard-coded here against the installed
//! headers (src/abi_check.c) and selects PetscInt and MPI_Comm by `cfg(petsc_int64)` and
//! `cfg(mpi_comm_is_int)`.
#![allow(
    non_camel_case_types,
    non_upper_case_globals,
    dead_code,
    clippy::upper_case_acronyms
)]

use std::os::raw::{c_char, c_int, c_uint, c_void};

pub type PetscErrorCode = c_int;
#[cfg(not(petsc_int64))]
pub type PetscInt = i32;
#[cfg(petsc_int64)]
pub type PetscInt = i64;
pub type PetscScalar = f64;
pub type PetscReal = f64;
pub type PetscBool = c_uint;
pub const PETSC_FALSE: PetscBool = 0;
pub const PETSC_TRUE: PetscBool = 1;
pub const PETSC_DEFAULT: PetscInt = -2;
/// PETSC_DEFAULT as a real argument (a tolerance left as it is, or at its default, which is the
/// same for those hertz leaves).
pub const PETSC_DEFAULT_REAL: PetscReal = -2.0;

#[cfg(not(mpi_comm_is_int))]
pub type MPI_Comm = *mut ompi_communicator_t;
#[cfg(mpi_comm_is_int)]
pub type MPI_Comm = c_int;

macro_rules! opaque {
    ($($name:ident => $alias:ident),* $(,)?) => {$(
        #[repr(C)]
        pub struct $name { _private: [u8; 0] }
        pub type $alias = *mut $name;
    )*};
}
opaque!(_p_Mat => Mat, _p_Vec => PetscVec, _p_KSP => KSP, _p_PC => PC, _p_PetscOptions => PetscOptions,
        _p_PetscSF => VecScatter, _p_MatNullSpace => MatNullSpace,
        ompi_communicator_t => OmpiCommPtr);

pub type InsertMode = c_uint;
pub const INSERT_VALUES: InsertMode = 1;
pub const ADD_VALUES: InsertMode = 2;
pub const PETSC_DECIDE: PetscInt = -1;
pub type ScatterMode = c_uint;
pub const SCATTER_FORWARD: ScatterMode = 0;
pub type MatAssemblyType = c_uint;
pub const MAT_FINAL_ASSEMBLY: MatAssemblyType = 0;
pub type MatOption = c_int;
pub const MAT_SYMMETRIC: MatOption = 1;
pub const MAT_SYMMETRY_ETERNAL: MatOption = 10;
pub const MAT_SPD: MatOption = 15;
pub type KSPConvergedReason = c_int;
pub type PetscErrorType = c_int;
pub type ErrorHandler = unsafe extern "C" fn(
    MPI_Comm,
    c_int,
    *const c_char,
    *const c_char,
    PetscErrorCode,
    PetscErrorType,
    *const c_char,
    *mut c_void,
) -> PetscErrorCode;

extern "C" {
    pub static mut PETSC_COMM_WORLD: MPI_Comm;

    pub fn MPI_Comm_rank(comm: MPI_Comm, rank: *mut c_int) -> c_int;
    pub fn MPI_Comm_size(comm: MPI_Comm, size: *mut c_int) -> c_int;
    pub fn MPI_Abort(comm: MPI_Comm, code: c_int) -> c_int;

    pub fn PetscInitialize(
        argc: *mut c_int,
        args: *mut *mut *mut c_char,
        file: *const c_char,
        help: *const c_char,
    ) -> PetscErrorCode;
    pub fn PetscFinalize() -> PetscErrorCode;
    pub fn PetscOptionsInsertString(o: PetscOptions, s: *const c_char) -> PetscErrorCode;
    pub fn PetscOptionsHasName(
        o: PetscOptions,
        pre: *const c_char,
        name: *const c_char,
        set: *mut PetscBool,
    ) -> PetscErrorCode;
    pub fn PetscOptionsLeftGet(
        o: PetscOptions,
        n: *mut PetscInt,
        names: *mut *mut *mut c_char,
        values: *mut *mut *mut c_char,
    ) -> PetscErrorCode;
    pub fn PetscOptionsLeftRestore(
        o: PetscOptions,
        n: *mut PetscInt,
        names: *mut *mut *mut c_char,
        values: *mut *mut *mut c_char,
    ) -> PetscErrorCode;
    pub fn PetscOptionsSetValue(
        o: PetscOptions,
        name: *const c_char,
        value: *const c_char,
    ) -> PetscErrorCode;
    pub fn PetscPushErrorHandler(handler: ErrorHandler, ctx: *mut c_void) -> PetscErrorCode;
    pub fn PetscReturnErrorHandler(
        comm: MPI_Comm,
        line: c_int,
        fun: *const c_char,
        file: *const c_char,
        n: PetscErrorCode,
        p: PetscErrorType,
        mess: *const c_char,
        ctx: *mut c_void,
    ) -> PetscErrorCode;

    pub fn MatCreate(comm: MPI_Comm, a: *mut Mat) -> PetscErrorCode;
    pub fn MatSetSizes(
        a: Mat,
        m: PetscInt,
        n: PetscInt,
        gm: PetscInt,
        gn: PetscInt,
    ) -> PetscErrorCode;
    pub fn MatSetType(a: Mat, t: *const c_char) -> PetscErrorCode;
    pub fn MatSeqAIJSetPreallocation(a: Mat, nz: PetscInt, nnz: *const PetscInt) -> PetscErrorCode;
    pub fn MatMPIAIJSetPreallocation(
        a: Mat,
        dnz: PetscInt,
        dnnz: *const PetscInt,
        onz: PetscInt,
        onnz: *const PetscInt,
    ) -> PetscErrorCode;
    pub fn MatSetValues(
        a: Mat,
        m: PetscInt,
        im: *const PetscInt,
        n: PetscInt,
        jn: *const PetscInt,
        v: *const PetscScalar,
        mode: InsertMode,
    ) -> PetscErrorCode;
    pub fn MatZeroEntries(a: Mat) -> PetscErrorCode;
    pub fn MatAssemblyBegin(a: Mat, t: MatAssemblyType) -> PetscErrorCode;
    pub fn MatAssemblyEnd(a: Mat, t: MatAssemblyType) -> PetscErrorCode;
    pub fn MatSetOption(a: Mat, op: MatOption, flg: PetscBool) -> PetscErrorCode;
    pub fn MatCreateVecs(a: Mat, right: *mut PetscVec, left: *mut PetscVec) -> PetscErrorCode;
    pub fn MatDestroy(a: *mut Mat) -> PetscErrorCode;
    pub fn MatNullSpaceCreate(
        comm: MPI_Comm,
        has_constant: PetscBool,
        n: PetscInt,
        vecs: *const PetscVec,
        sp: *mut MatNullSpace,
    ) -> PetscErrorCode;
    pub fn MatSetNearNullSpace(a: Mat, sp: MatNullSpace) -> PetscErrorCode;
    pub fn MatNullSpaceDestroy(sp: *mut MatNullSpace) -> PetscErrorCode;
    pub fn VecDuplicate(x: PetscVec, y: *mut PetscVec) -> PetscErrorCode;
    pub fn VecCreateMPI(
        comm: MPI_Comm,
        n: PetscInt,
        big_n: PetscInt,
        v: *mut PetscVec,
    ) -> PetscErrorCode;
    pub fn VecSet(x: PetscVec, alpha: PetscScalar) -> PetscErrorCode;

    pub fn VecSetValues(
        x: PetscVec,
        n: PetscInt,
        ix: *const PetscInt,
        y: *const PetscScalar,
        mode: InsertMode,
    ) -> PetscErrorCode;
    pub fn VecAssemblyBegin(x: PetscVec) -> PetscErrorCode;
    pub fn VecAssemblyEnd(x: PetscVec) -> PetscErrorCode;
    pub fn VecGetArrayRead(x: PetscVec, a: *mut *const PetscScalar) -> PetscErrorCode;
    pub fn VecRestoreArrayRead(x: PetscVec, a: *mut *const PetscScalar) -> PetscErrorCode;
    pub fn VecScatterCreateToAll(
        x: PetscVec,
        ctx: *mut VecScatter,
        all: *mut PetscVec,
    ) -> PetscErrorCode;
    pub fn VecScatterBegin(
        ctx: VecScatter,
        x: PetscVec,
        y: PetscVec,
        mode: InsertMode,
        sm: ScatterMode,
    ) -> PetscErrorCode;
    pub fn VecScatterEnd(
        ctx: VecScatter,
        x: PetscVec,
        y: PetscVec,
        mode: InsertMode,
        sm: ScatterMode,
    ) -> PetscErrorCode;
    pub fn VecScatterDestroy(ctx: *mut VecScatter) -> PetscErrorCode;
    pub fn VecDestroy(x: *mut PetscVec) -> PetscErrorCode;

    pub fn KSPCreate(comm: MPI_Comm, ksp: *mut KSP) -> PetscErrorCode;
    pub fn KSPSetOperators(ksp: KSP, a: Mat, p: Mat) -> PetscErrorCode;
    pub fn KSPSetType(ksp: KSP, t: *const c_char) -> PetscErrorCode;
    pub fn KSPSetTolerances(
        ksp: KSP,
        rtol: PetscReal,
        abstol: PetscReal,
        dtol: PetscReal,
        maxits: PetscInt,
    ) -> PetscErrorCode;
    pub fn KSPGetTolerances(
        ksp: KSP,
        rtol: *mut PetscReal,
        abstol: *mut PetscReal,
        dtol: *mut PetscReal,
        maxits: *mut PetscInt,
    ) -> PetscErrorCode;
    pub fn KSPSetFromOptions(ksp: KSP) -> PetscErrorCode;
    pub fn KSPSetInitialGuessNonzero(ksp: KSP, flg: PetscBool) -> PetscErrorCode;
    pub fn KSPGetType(ksp: KSP, t: *mut *const c_char) -> PetscErrorCode;
    pub fn KSPSetUp(ksp: KSP) -> PetscErrorCode;
    pub fn KSPSolve(ksp: KSP, b: PetscVec, x: PetscVec) -> PetscErrorCode;
    pub fn KSPGetIterationNumber(ksp: KSP, its: *mut PetscInt) -> PetscErrorCode;
    pub fn KSPGetConvergedReason(ksp: KSP, r: *mut KSPConvergedReason) -> PetscErrorCode;
    pub fn KSPGetPC(ksp: KSP, pc: *mut PC) -> PetscErrorCode;
    pub fn KSPDestroy(ksp: *mut KSP) -> PetscErrorCode;
    pub fn PCSetType(pc: PC, t: *const c_char) -> PetscErrorCode;
    pub fn PCFactorSetMatSolverType(pc: PC, t: *const c_char) -> PetscErrorCode;
}
