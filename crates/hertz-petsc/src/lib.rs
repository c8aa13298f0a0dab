//! PETSc as a linear solver of hertz (the feature `petsc`): the tangent goes into a PETSc AIJ
//! matrix split by rows across the MPI ranks, and PETSc's KSP solves it to a relative residual
//! of 1e-12, by default with a method chosen from the matrix:
//! - CG with algebraic multigrid (GAMG, the model's rigid-body motions as its near-null space)
//!   for a positive definite tangent, and for the systems left when hertz eliminates contact
//!   multipliers;
//! - GMRES with hypre's BoomerAMG (tuned for 3D elasticity) for another tangent of 20 000
//!   unknowns or more without multipliers (penalty contact);
//! - MUMPS' LDLᵀ for another symmetric one, MUMPS' LU otherwise (multipliers kept as unknowns,
//!   small systems).
//!
//! Any PETSc option overrides that (`PETSC_OPTIONS`, or the options string given to
//! [`Session::start`], e.g. `-ksp_type cg -pc_type hypre`).
//!
//! Under `mpirun -n N` every rank reads the whole model and assembles its METIS share of the
//! elements (`hertz::solve::partition`); PETSc sums the ranks' shares of the tangent, and the
//! solver sums their residuals for hertz ([`hertz::solve::linear::Distributed`]). The
//! factorization or the multigrid hierarchy, and the solve, are distributed, and every rank gets
//! the whole solution back. Without the feature this crate is a
//! stub whose [`Session::start`] says how to build with PETSc.

use hertz::solve::SolverFactory;

#[cfg(feature = "petsc")]
mod ffi;
#[cfg(feature = "petsc")]
mod solver;
#[cfg(feature = "petsc")]
pub use solver::PetscSolver;

/// Whether this build has PETSc.
pub const AVAILABLE: bool = cfg!(feature = "petsc");

/// PETSc (and MPI) initialized for the life of the value; finalized when it is dropped, after
/// every solver made from it.
pub struct Session {
    rank: usize,
    size: usize,
    /// The options string given to [`Session::start`].
    #[cfg_attr(not(feature = "petsc"), allow(dead_code))]
    options: Option<String>,
}

impl Session {
    /// Initialize PETSc with the options in `options` (PETSc's syntax, added to those of the
    /// `PETSC_OPTIONS` environment variable). PETSc reports errors as return codes, printing
    /// nothing.
    #[cfg(feature = "petsc")]
    pub fn start(options: Option<&str>) -> Result<Session, String> {
        solver::start(options)
    }

    /// Without PETSc: an error that says how to build with it.
    #[cfg(not(feature = "petsc"))]
    pub fn start(_options: Option<&str>) -> Result<Session, String> {
        Err(
            "this hertz was built without PETSc: build it with `cargo build --release \
             --features petsc` (Debian: apt-get install libpetsc-real3.18-dev first)"
                .into(),
        )
    }

    /// This process's MPI rank (0 on one process).
    pub fn rank(&self) -> usize {
        self.rank
    }

    /// The number of MPI ranks.
    pub fn size(&self) -> usize {
        self.size
    }

    /// The options given (to [`Session::start`] or in `PETSC_OPTIONS`) that PETSc has not read:
    /// misspelled, or for a method the run did not take (e.g. `-pc_gamg_threshold` where MUMPS
    /// solved). Ask after the analysis.
    pub fn unused_options(&self) -> Vec<String> {
        #[cfg(feature = "petsc")]
        return solver::unused(self.options.as_deref());
        #[cfg(not(feature = "petsc"))]
        Vec::new()
    }

    /// The solver choice that makes a [`PetscSolver`] for each analysis.
    pub fn solver(&self) -> hertz::solve::SolverChoice {
        #[cfg(feature = "petsc")]
        let make = SolverFactory(std::sync::Arc::new(|| {
            Box::new(PetscSolver::new()) as Box<dyn hertz::solve::linear::LinearSolver>
        }));
        #[cfg(not(feature = "petsc"))]
        let make = SolverFactory(std::sync::Arc::new(|| unreachable!("no PETSc session")));
        hertz::solve::SolverChoice::Custom(make)
    }
}

#[cfg(feature = "petsc")]
impl Drop for Session {
    fn drop(&mut self) {
        solver::finish();
    }
}
