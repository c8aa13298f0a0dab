//! Linear solvers, the condensed contact solve and the Newton/load-stepping driver.

mod backtrack;
pub mod branches;
pub mod condensed;
mod contact_step;
pub mod convergence;
pub mod dynamics;
mod equations;
pub mod explicit;
pub mod krylov;
pub mod linear;
pub mod load_history;
pub mod multipliers;
pub mod newton;
pub mod ordering;
pub mod params;
pub mod partition;
pub mod report;
pub mod run;
pub mod softening;
pub mod step_result;
pub mod stepping;
pub mod terms;
mod watch;

pub use params::{SolveParams, SolverChoice, SolverFactory};
pub use report::{IterationReport, Observer, Phase, PhaseTimes, Silent, StepInfo, StepReport};
pub use run::{run_analysis, run_analysis_observed};
pub use step_result::{Energy, Motion, StepResult};
pub use terms::{Statics, StepTerms};

use crate::assembly::DofMap;
use crate::contact::ContactSystem;
use crate::error::Result;
use crate::model::Model;

/// Number the DOFs of a model: its elements' DOFs plus what its contact conditions need.
pub fn number_dofs(model: &Model) -> Result<DofMap> {
    DofMap::new(model, &ContactSystem::new(model)?.extra_dofs())
}
