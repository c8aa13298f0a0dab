//! DOF numbering, sparse assembly, linear solvers and the Newton/load-stepping driver.

pub mod analysis;
pub mod assembly;
pub mod condensed;
pub mod dofs;
pub mod linear;
pub mod ordering;

pub use analysis::{run_analysis, SolveParams, StepInfo, StepResult};
pub use dofs::DofMap;
