//! What a run reports while it goes: the [`Observer`] the driver tells of each phase, Newton
//! iteration, finished step, cut-back and warning. The library prints nothing itself: the CLI
//! implements an observer (log lines, a progress bar, `-q`/`-v`), a test records the reports, a
//! script can forward them.

use super::linear::SolverStats;

/// A phase of the work, reported as it begins (a long one is what a user waits on).
#[derive(Debug, Clone, PartialEq)]
pub enum Phase {
    /// Reading the input file (with its includes and meshes).
    Reading,
    /// Contact conditions, DOF numbering and the sparse pattern, before the first of `steps`.
    SetUp { unknowns: usize, steps: usize },
    /// The element loop (internal forces and tangents) and the contact points.
    Assembly,
    /// A sparse factorization of `unknowns` equations (`kind`: Cholesky, LDLᵀ, LU, or the
    /// condensed contact step's structural factor).
    Factorization { kind: &'static str, unknowns: usize },
    /// Triangular solves and the contact branch search.
    Solve,
}

impl std::fmt::Display for Phase {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Phase::Reading => write!(f, "reading the input"),
            Phase::SetUp { unknowns, .. } => write!(f, "set-up ({unknowns} unknowns)"),
            Phase::Assembly => write!(f, "assembly"),
            Phase::Factorization { kind, unknowns } => {
                write!(f, "factorization ({kind}, {unknowns} unknowns)")
            }
            Phase::Solve => write!(f, "solve"),
        }
    }
}

/// One Newton iteration: its residual and what contact did.
#[derive(Debug, Clone, Default)]
pub struct IterationReport {
    pub step: usize,
    /// 0 before the first solve.
    pub iteration: usize,
    /// Largest relative (or absolute) force error over the DOF groups.
    pub residual: f64,
    /// Contact points in the model (0 without contact).
    pub contact_points: usize,
    /// Of them, closed.
    pub closed: usize,
    /// Node labels that closed and opened since the last iteration.
    pub closed_nodes: Vec<usize>,
    pub opened_nodes: Vec<usize>,
    /// With friction: the sliding nodes' count, and the nodes that changed between stick and
    /// slip since the last iteration.
    pub slipping: Option<usize>,
    pub switched_nodes: Vec<usize>,
}

/// A converged step.
#[derive(Debug, Clone, Default)]
pub struct StepReport {
    pub step: usize,
    pub n_steps: usize,
    pub time: f64,
    pub iterations: usize,
    pub residual: f64,
    pub substeps: usize,
    pub wall_seconds: f64,
    pub times: PhaseTimes,
    /// Krylov iterations of the last solve (hertz's GMRES, or PETSc's KSP; 0: a direct solve).
    pub krylov_iterations: usize,
}

impl StepReport {
    /// The report of step `step` of `n_steps`, converged at `time`, from its `info`.
    pub fn of(step: usize, n_steps: usize, time: f64, info: &StepInfo) -> StepReport {
        StepReport {
            step,
            n_steps,
            time,
            iterations: info.iterations,
            residual: info.residual_history.last().copied().unwrap_or(0.0),
            substeps: info.substeps,
            wall_seconds: info.wall_seconds,
            times: info.times,
            krylov_iterations: info.solver.krylov_iterations,
        }
    }
}

/// Receives a run's reports. Every method has an empty default: implement what you show.
/// Methods take `&self` (an observer keeps its own state in cells): the driver holds it shared.
pub trait Observer {
    /// A phase begins.
    fn phase(&self, _phase: &Phase) {}
    /// A Newton iteration's residual was evaluated.
    fn iteration(&self, _report: &IterationReport) {}
    /// A step converged.
    fn step(&self, _report: &StepReport) {}
    /// A step did not converge and is cut back (or retried in substeps): why.
    fn retry(&self, _message: &str) {}
    /// A detail of the solver's work, for a verbose log (e.g. the contact branch search).
    fn detail(&self, _message: &str) {}
    /// Something the user should know (also kept in the step's `StepInfo::warnings`).
    fn warning(&self, _message: &str) {}
    /// Whether the caller wants the analysis stopped (asked before every Newton iteration; the
    /// analysis then ends with [`crate::error::Error::Interrupted`]).
    fn interrupted(&self) -> bool {
        false
    }
}

/// An observer that shows nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Observer for Silent {}

/// Wall time of a step's phases, in seconds.
#[derive(Debug, Clone, Copy, Default)]
pub struct PhaseTimes {
    /// Contact search: broad phase, projections, choice of partners.
    pub search: f64,
    /// Contact kinematics and laws (the local residuals and tangents).
    pub contact: f64,
    /// Element loop: internal forces and tangents.
    pub assembly: f64,
    /// Sparse factorizations (with the condensed contact system's setup).
    pub factor: f64,
    /// Triangular solves and the condensed contact system.
    pub solve: f64,
}

/// Diagnostics of one step.
#[derive(Debug, Clone, Default)]
pub struct StepInfo {
    pub iterations: usize,
    /// Largest relative (or absolute) force error over the DOF groups, per iteration.
    pub residual_history: Vec<f64>,
    pub substeps: usize,
    pub wall_seconds: f64,
    /// Where the step's time went.
    pub times: PhaseTimes,
    pub solver: SolverStats,
    /// Things the user should know (e.g. a penalty beyond double precision).
    pub warnings: Vec<String>,
    /// Multipliers eliminated through their slave rows and kept, in the step's last solve with
    /// full tangents (see [`super::multipliers`]; none when the condensed solve served).
    pub multipliers_eliminated: (usize, usize),
}
