//! What a caller sets beyond the input file: the linear solver and the limits of the driver.

use super::contact_step::SolverMaker;
use super::linear::{DenseLu, FaerSolver, LinearSolver, SolverSettings};

/// Driver settings beyond what the input file says.
#[derive(Debug, Clone)]
pub struct SolveParams {
    /// How many times a failing step may be halved.
    pub max_cutbacks: usize,
    /// Unknowns from which a non-symmetric tangent is solved by GMRES preconditioned with its
    /// symmetric part instead of a sparse LU (see [`super::krylov`]).
    pub krylov_min_unknowns: usize,
    /// Decide contact branches on the dense condensed system when the candidates allow it (see
    /// [`super::condensed`]); false: full tangents, the multipliers eliminated through their
    /// slave nodes' rows (see [`super::multipliers`]), as beyond the candidates' limit.
    pub condensed_contact: bool,
    /// The most candidate equations the condensed step holds in its dense block (M is m × m,
    /// its inverse m³); beyond, the nearest points' equations, half as many (see
    /// [`super::condensed`]); where the closed points alone need more, the block grows to hold
    /// them (up to [`super::condensed::MAX_DENSE`]). None (the default):
    /// [`super::condensed::default_limit`] of the model's unknowns,
    /// [`super::condensed::MAX_CANDIDATES`] up to 192 000 of them.
    pub max_condensed: Option<usize>,
    /// The linear solver of the full tangents.
    pub solver: SolverChoice,
}

/// Which [`LinearSolver`] factorizes the full tangents.
#[derive(Debug, Clone, Default)]
pub enum SolverChoice {
    /// [`FaerSolver`]: sparse direct factorizations, GMRES for large non-symmetric tangents.
    #[default]
    Sparse,
    /// [`DenseLu`]: a dense LU, the reference for small models (no Schur block: contact steps
    /// with full tangents).
    Dense,
    /// A solver from outside the library (PETSc's KSP in the `hertz` command's `petsc`
    /// feature), made by the factory as often as the analysis needs one; what it can do is
    /// asked of it ([`crate::solve::linear::Capabilities`]).
    Custom(SolverFactory),
}

/// Makes the [`LinearSolver`] of one analysis.
#[derive(Clone)]
pub struct SolverFactory(pub std::sync::Arc<dyn Fn() -> Box<dyn LinearSolver> + Send + Sync>);

impl std::fmt::Debug for SolverFactory {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("SolverFactory(..)")
    }
}

impl Default for SolveParams {
    fn default() -> Self {
        SolveParams {
            max_cutbacks: 5,
            krylov_min_unknowns: super::linear::KRYLOV_MIN_UNKNOWNS,
            condensed_contact: true,
            max_condensed: None,
            solver: SolverChoice::Sparse,
        }
    }
}

impl SolveParams {
    /// The chosen solver for full tangents (`groups`: the node of every free equation, for
    /// METIS), and the maker of more of its kind (the condensed step's structural factor).
    pub(super) fn solvers(&self, groups: &[usize]) -> (Box<dyn LinearSolver>, SolverMaker) {
        let krylov_min = self.krylov_min_unknowns;
        let groups = groups.to_vec();
        let make: SolverMaker = match &self.solver {
            SolverChoice::Sparse => Box::new(move || {
                Box::new(FaerSolver::new(SolverSettings {
                    groups: Some(groups.clone()),
                    krylov_min,
                    ..Default::default()
                })) as Box<dyn LinearSolver>
            }),
            SolverChoice::Dense => {
                Box::new(|| Box::new(DenseLu::default()) as Box<dyn LinearSolver>)
            }
            SolverChoice::Custom(make) => {
                let make = make.clone();
                Box::new(move || (make.0)())
            }
        };
        (make(), make)
    }

    /// The solver of the reduced systems of eliminated multipliers: hertz's own sparse one, or
    /// for a solver from outside one of its kind, given the whole matrix on every process.
    pub(super) fn reduced_solver(&self) -> Box<dyn LinearSolver> {
        match &self.solver {
            SolverChoice::Custom(make) => {
                let mut reduced = (make.0)();
                reduced.take_whole_matrices();
                reduced
            }
            _ => Box::new(FaerSolver::new(SolverSettings {
                krylov_min: self.krylov_min_unknowns,
                ..Default::default()
            })),
        }
    }
}
