//! Load stepping (spec §1.3, §3.2): targets per step, substeps when a step fails, results.
//!
//! Per step the target is: prescribed values `value·f(t)` (total) and external loads
//! (LinearStatic/StaticStructural: `F·f(t)`; NonLinearStatic: the accumulated reference vectors
//! Σ_k R_k with R_k = F·f(t_k) for `refloadmode 0` or F·(f(t_k) − f(t_k − Δt)) for 1).
//! Newton ([`super::newton`]) solves F_int(u) = F_ext on the free DOFs.
//! A step that does not converge is restarted in 2, 4, … substeps (loads and prescribed values
//! interpolated linearly); after `max_cutbacks` halvings the run stops with an error.

use super::newton::NewtonContext;
use super::params::SolveParams;
use super::report::{Observer, Phase, Silent, StepInfo, StepReport};
use super::terms::{FollowerTerms, StepTerms};
use crate::assembly::DofMap;
use crate::contact::{ContactSystem, SlotState};
use crate::error::{Error, Result};
use crate::model::{AnalysisKind, Model};
use crate::solid::follower::FollowerLoads;
use crate::solid::loads::reference_contributions;
use crate::solid::GpState;
use std::time::Instant;

/// The converged state after a step.
pub struct StepResult<'a> {
    pub step: usize,
    pub time: f64,
    pub dofs: &'a DofMap,
    /// Primary displacement vector (free, then prescribed).
    pub u: &'a [f64],
    /// Reaction per prescribed DOF (same order as `dofs.prescribed`).
    pub reactions: &'a [f64],
    pub states: &'a [Vec<GpState>],
    /// Contact state of every contact node.
    pub contact: &'a [SlotState],
    pub info: &'a StepInfo,
    /// A dynamic analysis's velocities, accelerations and energies.
    pub motion: Option<Motion<'a>>,
}

/// The motion of a dynamic step: velocity and acceleration of every primary DOF (as `u`) and the
/// energies so far.
#[derive(Clone, Copy)]
pub struct Motion<'a> {
    pub velocity: &'a [f64],
    pub acceleration: &'a [f64],
    pub energy: Energy,
}

/// Energies of a dynamic analysis at a step: the kinetic energy and the work done since the
/// start (each integrated by the trapezoidal rule over every step's increment).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Energy {
    pub kinetic: f64,
    /// Work of the elements' internal forces (the strain energy of elastic bodies).
    pub internal: f64,
    /// Work of the contact forces on the bodies (the penalty's stored energy, friction's
    /// dissipation).
    pub contact: f64,
    /// Work of the damping forces (energy dissipated by Rayleigh damping).
    pub damping: f64,
    /// Work of the external loads.
    pub external: f64,
    /// Work of the support forces on prescribed motion.
    pub supports: f64,
    /// The kinetic energy at the start.
    pub initial: f64,
}

impl Energy {
    /// What the scheme created (> 0) or lost (< 0): kinetic + internal + contact + damping −
    /// external − supports − initial; zero for the trapezoidal rule on linear elastic bodies.
    pub fn balance(&self) -> f64 {
        self.kinetic + self.internal + self.contact + self.damping
            - self.external
            - self.supports
            - self.initial
    }
}

impl StepResult<'_> {
    /// Total displacement of DOF `d` of node `n`, if the node has it.
    pub fn displacement(&self, n: usize, d: u8) -> Option<f64> {
        self.dofs.code(n, d).map(|c| self.dofs.value(self.u, c))
    }
}

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
    mut on_step: impl FnMut(&StepResult) -> Result<()>,
) -> Result<()> {
    if let Some(d) = model.analysis.dynamics {
        return match d.scheme {
            crate::model::TimeScheme::CentralDifference { .. } => {
                super::explicit::run(model, params, observer, on_step)
            }
            _ => super::dynamics::run(model, params, observer, on_step),
        };
    }
    let contact = ContactSystem::new(model)?;
    let dofs = DofMap::new(model, &contact.extra_dofs())?;
    observer.phase(&Phase::SetUp {
        unknowns: dofs.n_free,
        steps: model.step_times().len(),
    });
    let history = LoadHistory::new(model, &dofs)?;
    let follower = FollowerLoads::new(model, &dofs)?;
    let mut applied_factors = vec![0.0; model.loads.len()];
    let (mut ctx, mut initial_warnings) =
        NewtonContext::new(model, &dofs, contact, params, observer)?;
    let np = dofs.n_primary();
    let nf = dofs.n_free;
    let mut u = vec![0.0; np];
    let mut applied = vec![0.0; np];
    let times = model.step_times();
    for (k, &t) in times.iter().enumerate() {
        let clock = Instant::now();
        let step = k + 1;
        ctx.begin_step(step);
        let target = history.external_at(t, &applied);
        let factors = history.factors_at(t, &applied_factors);
        let mut info = StepInfo {
            warnings: std::mem::take(&mut initial_warnings),
            ..Default::default()
        };
        let goal = StepGoal {
            step,
            t,
            from: &applied,
            to: &target,
            prescribed: &history.prescribed_at(t),
            factors: (&applied_factors, &factors),
            follower: &follower,
        };
        step_with_cutbacks(&mut ctx, &mut u, &goal, params, &mut info)?;
        let committed = ctx.commit_step(&u)?;
        let (mut ev, contact_states) = (committed.ev, committed.states);
        // The reactions balance the follower loads too.
        goal.terms(1.0, model, &dofs).add_forces(&u, &mut ev.f_int);
        applied = target;
        applied_factors = factors;
        let reactions: Vec<f64> = (0..dofs.n_prescribed)
            .map(|i| ev.f_int[nf + i] - applied[nf + i])
            .collect();
        info.wall_seconds = clock.elapsed().as_secs_f64();
        ctx.finish_step_info(&mut info);
        observer.step(&StepReport {
            step,
            n_steps: times.len(),
            time: t,
            iterations: info.iterations,
            residual: info.residual_history.last().copied().unwrap_or(0.0),
            substeps: info.substeps,
            wall_seconds: info.wall_seconds,
            times: info.times,
            krylov_iterations: info.solver.krylov_iterations,
        });
        let states = ev.states.unwrap_or_default();
        on_step(&StepResult {
            step,
            time: t,
            dofs: &dofs,
            u: &u,
            reactions: &reactions,
            states: &states,
            contact: &contact_states,
            info: &info,
            motion: None,
        })?;
    }
    Ok(())
}

/// The loads and prescribed values of a model over time.
pub(super) struct LoadHistory<'a> {
    model: &'a Model,
    dofs: &'a DofMap,
    /// Per time function, the load vector it scales.
    reference: Vec<(usize, Vec<f64>)>,
}

impl<'a> LoadHistory<'a> {
    pub(super) fn new(model: &'a Model, dofs: &'a DofMap) -> Result<LoadHistory<'a>> {
        Ok(LoadHistory {
            model,
            dofs,
            reference: reference_load_vectors(model, dofs)?,
        })
    }

    /// Σ scale(f)·(load vector of f).
    fn external(&self, scale: &dyn Fn(usize) -> f64) -> Vec<f64> {
        let mut f = vec![0.0; self.dofs.n_primary()];
        for (func, v) in &self.reference {
            let s = scale(*func);
            if s != 0.0 {
                for (a, b) in f.iter_mut().zip(v) {
                    *a += s * b;
                }
            }
        }
        f
    }

    /// The external forces at time `t`, `applied` those of the last step (NonLinearStatic
    /// `refloadmode 1` adds the increment to them).
    pub(super) fn external_at(&self, t: f64, applied: &[f64]) -> Vec<f64> {
        let (model, a) = (self.model, &self.model.analysis);
        match a.kind {
            AnalysisKind::NonLinearStatic => {
                let r = self.external(&|f| {
                    let func = &model.functions[f];
                    if a.refloadmode == 1 {
                        func.eval(t) - func.eval(t - a.deltat)
                    } else {
                        func.eval(t)
                    }
                });
                applied.iter().zip(&r).map(|(x, y)| x + y).collect()
            }
            _ => self.external(&|f| model.functions[f].eval(t)),
        }
    }

    /// The factor of every load at time `t` (`applied` those of the last step): what its time
    /// function scales it by, as [`Self::external_at`] sums them.
    pub(super) fn factors_at(&self, t: f64, applied: &[f64]) -> Vec<f64> {
        let (model, a) = (self.model, &self.model.analysis);
        model
            .loads
            .iter()
            .zip(applied)
            .map(|(load, &before)| {
                let func = &model.functions[load.function - 1];
                match a.kind {
                    AnalysisKind::NonLinearStatic if a.refloadmode == 1 => {
                        before + func.eval(t) - func.eval(t - a.deltat)
                    }
                    AnalysisKind::NonLinearStatic => before + func.eval(t),
                    _ => func.eval(t),
                }
            })
            .collect()
    }

    /// The prescribed values at time `t`.
    pub(super) fn prescribed_at(&self, t: f64) -> Vec<f64> {
        self.dofs
            .prescribed
            .iter()
            .map(|&(_, d, bi)| {
                let bc = &self.model.dirichlet[bi];
                bc.value_for(d) * self.model.functions[bc.function - 1].eval(t)
            })
            .collect()
    }
}

/// What a load step goes to: step number and time, external forces from and to, the prescribed
/// values at its end, and the follower loads with their factors from and to.
struct StepGoal<'g> {
    step: usize,
    t: f64,
    from: &'g [f64],
    to: &'g [f64],
    prescribed: &'g [f64],
    factors: (&'g [f64], &'g [f64]),
    follower: &'g FollowerLoads,
}

impl<'g> StepGoal<'g> {
    /// The follower loads at the fraction `alpha` of the step.
    fn terms(&self, alpha: f64, model: &'g Model, dofs: &'g DofMap) -> FollowerTerms<'g> {
        let (from, to) = self.factors;
        FollowerTerms {
            loads: self.follower,
            model,
            dofs,
            scale: from
                .iter()
                .zip(to)
                .map(|(a, b)| a + alpha * (b - a))
                .collect(),
        }
    }
}

/// Why an attempt at a step failed.
#[derive(PartialEq)]
enum Failure {
    /// Newton ran out of iterations, with what it showed if something specific did.
    NoConvergence(Option<String>),
    /// The solver gave up on the way (an element inverted, a node crossed its master).
    Stopped(String),
}

/// Solve one load step from `u`, halving it up to `params.max_cutbacks` times when Newton does
/// not converge; the contact and material states restart from the step's start at each retry.
fn step_with_cutbacks(
    ctx: &mut NewtonContext,
    u: &mut [f64],
    goal: &StepGoal,
    params: &SolveParams,
    info: &mut StepInfo,
) -> Result<()> {
    let a = &ctx.model().analysis;
    let (nf, np) = (ctx.dofs().n_free, ctx.dofs().n_prescribed);
    let (step, t) = (goal.step, goal.t);
    let start_u = u.to_vec();
    let start = ctx.checkpoint();
    // Why the attempts failed, each reason once, the last attempt's last.
    let mut failures: Vec<Failure> = Vec::new();
    // The furthest state any substep converged to (for a failure's diagnosis).
    let mut furthest = (0.0, start_u.clone());
    for level in 0..=params.max_cutbacks {
        let nsub = 1usize << level;
        u.copy_from_slice(&start_u);
        ctx.rollback(&start);
        let mut failed = None;
        for s in 1..=nsub {
            let alpha = s as f64 / nsub as f64;
            let f_sub: Vec<f64> = goal
                .from
                .iter()
                .zip(goal.to)
                .map(|(a0, a1)| a0 + alpha * (a1 - a0))
                .collect();
            let up_sub: Vec<f64> = (0..np)
                .map(|i| start_u[nf + i] + alpha * (goal.prescribed[i] - start_u[nf + i]))
                .collect();
            let terms = goal.terms(alpha, ctx.model(), ctx.dofs());
            match ctx.newton(u, (&f_sub, &up_sub), a, info, &terms) {
                Ok(true) => {
                    ctx.commit_substep(u)?;
                    if alpha > furthest.0 && alpha < 1.0 {
                        furthest = (alpha, u.to_vec());
                    }
                }
                Ok(false) => {
                    failed = Some(Failure::NoConvergence(ctx.diagnosis()));
                    break;
                }
                Err(Error::Solve(msg)) => {
                    failed = Some(Failure::Stopped(msg));
                    break;
                }
                // No smaller step helps a mechanism: say at which step it showed.
                Err(Error::Singular(msg)) => {
                    return Err(Error::Singular(format!("step {step} (t = {t}): {msg}")))
                }
                Err(e) => return Err(e),
            }
        }
        let Some(failure) = failed else {
            info.substeps = nsub;
            return Ok(());
        };
        ctx.attempt_failed();
        if level < params.max_cutbacks {
            let why = match &failure {
                Failure::NoConvergence(d) => format!(
                    "no convergence in {} iterations{}",
                    a.maxiter,
                    d.as_ref().map(|d| format!(" ({d})")).unwrap_or_default()
                ),
                Failure::Stopped(msg) => msg.clone(),
            };
            ctx.observer().retry(&format!(
                "step {step}: {why}; retrying in {} substeps",
                2 * nsub
            ));
        }
        failures.retain(|f| *f != failure);
        failures.push(failure);
    }
    let last = failures.pop().expect("an attempt failed");
    // The last two other reasons (a crossing at each of several step sizes says the same).
    let earlier: Vec<&str> = failures
        .iter()
        .rev()
        .filter_map(|f| match f {
            Failure::Stopped(msg) => Some(msg.as_str()),
            Failure::NoConvergence(_) => None,
        })
        .take(2)
        .collect();
    let earlier = if earlier.is_empty() {
        String::new()
    } else {
        format!("; in earlier attempts: {}", earlier.join("; "))
    };
    let softening = ctx
        .softening_hint(&furthest.1)
        .map(|d| format!("; {d}"))
        .unwrap_or_default();
    let halvings = params.max_cutbacks;
    Err(Error::Solve(match last {
        Failure::NoConvergence(diagnosis) => format!(
            "step {step} (t = {t}) did not converge within {} iterations even after {halvings} \
             step halvings; last residual {:.3e} (rtolf {:.1e}){}{earlier}{softening}",
            a.maxiter,
            info.residual_history.last().copied().unwrap_or(f64::NAN),
            a.rtolf,
            diagnosis.map(|d| format!("; {d}")).unwrap_or_default(),
        ),
        Failure::Stopped(msg) => format!(
            "step {step} (t = {t}): {msg}, even after {halvings} step halvings{earlier}{softening}"
        ),
    }))
}

/// Reference load vector of every load (components at f = 1) in primary numbering, with the
/// index of its time function.
pub fn reference_load_vectors(model: &Model, dofs: &DofMap) -> Result<Vec<(usize, Vec<f64>)>> {
    let np = dofs.n_primary();
    let mut out = Vec::with_capacity(model.loads.len());
    for load in &model.loads {
        let mut v = vec![0.0; np];
        for (node, d, val) in reference_contributions(model, load)? {
            if let Some(code) = dofs.code(node, d) {
                for (p, w) in dofs.entries(code) {
                    v[p] += w * val;
                }
            }
        }
        out.push((load.function - 1, v));
    }
    Ok(out)
}
