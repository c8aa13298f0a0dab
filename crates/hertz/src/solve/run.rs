//! An analysis from start to end: statics ([`super::stepping`]), implicit dynamics
//! ([`super::dynamics`]) or explicit dynamics ([`super::explicit`]), by the analysis record.

use super::params::SolveParams;
use super::report::{Observer, Silent};
use super::step_result::StepResult;
use crate::error::Result;
use crate::model::{Model, TimeScheme};

/// Run every step of the analysis, calling `on_step` after each converged step; nothing is
/// reported on the way (see [`run_analysis_observed`]).
pub fn run_analysis(
    model: &Model,
    params: &SolveParams,
    on_step: impl FnMut(&StepResult) -> Result<()>,
) -> Result<()> {
    run_analysis_observed(model, params, &Silent, on_step)
}

/// [`run_analysis`], telling `observer` of each phase, Newton iteration, step, cut-back and
/// warning as they come.
pub fn run_analysis_observed(
    model: &Model,
    params: &SolveParams,
    observer: &dyn Observer,
    on_step: impl FnMut(&StepResult) -> Result<()>,
) -> Result<()> {
    match model.analysis.dynamics.map(|d| d.scheme) {
        Some(TimeScheme::CentralDifference { .. }) => {
            super::explicit::run(model, params, observer, on_step)
        }
        Some(_) => super::dynamics::run(model, params, observer, on_step),
        None => super::stepping::run(model, params, observer, on_step),
    }
}
