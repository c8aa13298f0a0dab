//! Linear solvers, the condensed contact solve and the Newton/load-stepping driver.

pub mod branches;
pub mod condensed;
pub mod convergence;
pub mod krylov;
pub mod linear;
pub mod multipliers;
pub mod newton;
pub mod ordering;
pub mod partition;
pub mod report;
pub mod softening;
pub mod stepping;

pub use report::{IterationReport, Observer, Phase, Silent, StepReport};
pub use stepping::{
    run_analysis, run_analysis_observed, SolveParams, SolverChoice, SolverFactory, StepInfo,
    StepResult,
};

use crate::assembly::DofMap;
use crate::contact::ContactSystem;
use crate::error::Result;
use crate::model::Model;

/// Number the DOFs of a model: its elements' DOFs plus what its contact conditions need.
pub fn number_dofs(model: &Model) -> Result<DofMap> {
    DofMap::new(model, &ContactSystem::new(model)?.extra_dofs())
}
