//! Load stepping (spec §1.3, §3.2): targets per step, substeps when a step fails, results.
//!
//! Per step the target is: prescribed values `value·f(t)` (total) and external loads
//! (LinearStatic/StaticStructural: `F·f(t)`; NonLinearStatic: the accumulated reference vectors
//! Σ_k R_k with R_k = F·f(t_k) for `refloadmode 0` or F·(f(t_k) − f(t_k − Δt)) for 1).
//! Newton ([`super::newton`]) solves F_int(u) = F_ext on the free DOFs.
//! A step that does not converge is restarted in 2, 4, … substeps (loads and prescribed values
//! interpolated linearly); after `max_cutbacks` halvings the run stops with an error.

use super::load_history::LoadHistory;
use super::newton::NewtonContext;
use super::params::SolveParams;
use super::report::{Observer, StepInfo, StepReport};
use super::step_result::StepResult;
use super::terms::{FollowerTerms, StepTerms};
use crate::assembly::DofMap;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::solid::follower::FollowerLoads;
use std::time::Instant;

/// Run a static analysis, telling `observer` of each phase, Newton iteration, step, cut-back
/// and warning as they come, and calling `on_step` after each converged step.
pub fn run(
    model: &Model,
    params: &SolveParams,
    observer: &dyn Observer,
    mut on_step: impl FnMut(&StepResult) -> Result<()>,
) -> Result<()> {
    let (contact, dofs) = super::newton::set_up(model, observer)?;
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
        ctx.finish_step_info(&mut info, &contact_states);
        observer.step(&StepReport::of(step, times.len(), t, &info));
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
