//! Load stepping and Newton–Raphson (spec §1.3, §3.2).
//!
//! Per step the target is: prescribed values `value·f(t)` (total) and external loads
//! (LinearStatic/StaticStructural: `F·f(t)`; NonLinearStatic: the accumulated reference vectors
//! Σ_k R_k with R_k = F·f(t_k) for `refloadmode 0` or F·(f(t_k) − f(t_k − Δt)) for 1).
//! Newton solves F_int(u) = F_ext on the free DOFs with OOFEM's per-DOF-id convergence test.
//! A step that does not converge is restarted in 2, 4, … substeps (loads and prescribed values
//! interpolated linearly); after `max_cutbacks` halvings the run stops with an error.

use super::condensed::CondensedContact;
use super::linear::{LinearSolver, SolverStats};
use crate::assembly::{Assembler, Contribution, DofMap, Evaluation};
use crate::contact::{ContactSystem, Partner, Search, SlotState};
use crate::error::{Error, Result};
use crate::model::{AnalysisKind, Model};
use crate::output::outfile::sci;
use crate::solid::loads::reference_contributions;
use crate::solid::GpState;
use std::io::IsTerminal;
use std::time::Instant;

/// Driver settings beyond what the input file says.
#[derive(Debug, Clone)]
pub struct SolveParams {
    /// How many times a failing step may be halved.
    pub max_cutbacks: usize,
    /// Print one line per step on stderr.
    pub log_steps: bool,
}

impl Default for SolveParams {
    fn default() -> Self {
        SolveParams {
            max_cutbacks: 5,
            log_steps: true,
        }
    }
}

/// Diagnostics of one step.
#[derive(Debug, Clone, Default)]
pub struct StepInfo {
    pub iterations: usize,
    /// Largest relative (or absolute) force error over the DOF groups, per iteration.
    pub residual_history: Vec<f64>,
    pub substeps: usize,
    pub wall_seconds: f64,
    pub solver: SolverStats,
}

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
}

impl StepResult<'_> {
    /// Total displacement of DOF `d` of node `n`, if the node has it.
    pub fn displacement(&self, n: usize, d: u8) -> Option<f64> {
        self.dofs.code(n, d).map(|c| self.dofs.value(self.u, c))
    }
}

/// Run every step of the analysis, calling `on_step` after each converged step.
pub fn run_analysis(
    model: &Model,
    params: &SolveParams,
    mut on_step: impl FnMut(&StepResult) -> Result<()>,
) -> Result<()> {
    let contact = ContactSystem::new(model)?;
    let dofs = DofMap::new(model, &contact.extra_dofs())?;
    let mut asm = Assembler::new(model, &dofs)?;
    asm.set_symmetric(contact.symmetric());
    let nf = dofs.n_free;
    let np = dofs.n_primary();
    let ref_loads = reference_load_vectors(model, &dofs)?;
    let external = |scale: &dyn Fn(usize) -> f64| -> Vec<f64> {
        let mut f = vec![0.0; np];
        for (func, v) in &ref_loads {
            let s = scale(*func);
            if s != 0.0 {
                for (a, b) in f.iter_mut().zip(v) {
                    *a += s * b;
                }
            }
        }
        f
    };
    let prescribed_at = |t: f64| -> Vec<f64> {
        dofs.prescribed
            .iter()
            .map(|&(_, d, bi)| {
                let bc = &model.dirichlet[bi];
                bc.value_for(d) * model.functions[bc.function - 1].eval(t)
            })
            .collect()
    };
    let a = &model.analysis;
    let small_strain = !model.elements.iter().any(|e| e.nlgeo);
    let linear = small_strain && contact.is_empty();
    // Linear elastic bodies in penalty contact: condense the Newton systems on the contact DOFs.
    let condensed = if small_strain && !contact.is_empty() && dofs.n_lambda == 0 {
        Condensed::Pending(contact.candidate_equations(&dofs))
    } else {
        Condensed::Off
    };
    let mut solver = LinearSolver::default();
    solver.groups = Some(dofs.free_eq_nodes());
    let mut ctx = NewtonContext {
        asm,
        contact,
        dofs: &dofs,
        solver,
        factor_valid: false,
        linear,
        progress: params.log_steps && std::io::stderr().is_terminal(),
        factored_contact: None,
        condensed,
    };
    let mut u = vec![0.0; np];
    let mut applied = vec![0.0; np];
    let times = model.step_times();
    let nsteps = times.len();
    for (k, &t) in times.iter().enumerate() {
        let clock = Instant::now();
        let step = k + 1;
        let target = match a.kind {
            AnalysisKind::NonLinearStatic => {
                let r = external(&|f| {
                    let func = &model.functions[f];
                    if a.refloadmode == 1 {
                        func.eval(t) - func.eval(t - a.deltat)
                    } else {
                        func.eval(t)
                    }
                });
                applied.iter().zip(&r).map(|(x, y)| x + y).collect()
            }
            _ => external(&|f| model.functions[f].eval(t)),
        };
        let up_target = prescribed_at(t);
        let mut info = StepInfo::default();
        let start_u = u.clone();
        let mut done = false;
        for level in 0..=params.max_cutbacks {
            let nsub = 1usize << level;
            u.copy_from_slice(&start_u);
            let mut ok = true;
            for s in 1..=nsub {
                let alpha = s as f64 / nsub as f64;
                let f_sub: Vec<f64> = applied
                    .iter()
                    .zip(&target)
                    .map(|(a0, a1)| a0 + alpha * (a1 - a0))
                    .collect();
                let up_sub: Vec<f64> = (0..dofs.n_prescribed)
                    .map(|i| start_u[nf + i] + alpha * (up_target[i] - start_u[nf + i]))
                    .collect();
                match ctx.newton(&mut u, &f_sub, &up_sub, a, &mut info) {
                    Ok(true) => {}
                    Ok(false) => {
                        ok = false;
                        break;
                    }
                    Err(Error::Solve(msg)) if level < params.max_cutbacks => {
                        if params.log_steps {
                            eprintln!("step {step}: {msg}; cutting the step");
                        }
                        ok = false;
                        break;
                    }
                    Err(e) => return Err(e),
                }
            }
            if ok {
                info.substeps = nsub;
                done = true;
                break;
            }
            ctx.factor_valid = false;
            if params.log_steps && level < params.max_cutbacks {
                eprintln!(
                    "step {step}: no convergence in {} iterations; retrying in {} substeps",
                    a.maxiter,
                    2 * nsub
                );
            }
        }
        if !done {
            return Err(Error::Solve(format!(
                "step {step} (t = {t}) did not converge within {} iterations even after {} step halvings; \
                 last residual {:.3e} (rtolf {:.1e})",
                a.maxiter,
                params.max_cutbacks,
                info.residual_history.last().copied().unwrap_or(f64::NAN),
                a.rtolf
            )));
        }
        applied = target;
        let (ev, contact_states, _) = ctx.evaluate(&u, false, true, None)?;
        let reactions: Vec<f64> = (0..dofs.n_prescribed)
            .map(|i| ev.f_int[nf + i] - applied[nf + i])
            .collect();
        info.wall_seconds = clock.elapsed().as_secs_f64();
        info.solver = ctx.solver.stats.clone();
        if params.log_steps {
            if ctx.progress {
                eprint!("\r\x1b[2K");
            }
            eprintln!(
                "step {step}/{nsteps}  t = {}  iterations {}  residual {}  substeps {}  {:.3} s",
                sci(t, 4),
                info.iterations,
                sci(info.residual_history.last().copied().unwrap_or(0.0), 2),
                info.substeps,
                info.wall_seconds
            );
        }
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
        })?;
    }
    Ok(())
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

struct NewtonContext<'a> {
    asm: Assembler<'a>,
    contact: ContactSystem,
    dofs: &'a DofMap,
    solver: LinearSolver,
    /// The current factorization is the (constant) tangent of a linear problem.
    factor_valid: bool,
    linear: bool,
    /// Show the iteration count on a terminal (overwritten by the step's log line).
    progress: bool,
    /// Contact state (partner, active) of every contact node at the last factorization.
    factored_contact: Option<Vec<(Partner, bool)>>,
    condensed: Condensed,
}

/// Whether Newton systems are solved condensed on the contact DOFs (see [`CondensedContact`]).
enum Condensed {
    /// Not applicable: large deformation, multipliers, no contact, or K_el singular alone.
    Off,
    /// Applicable; K_el is factorized at the first solve. Holds the candidate equations.
    Pending(Vec<usize>),
    Ready(Box<CondensedContact>),
}

impl NewtonContext<'_> {
    /// Elements and contact at state `u`, with the contact contributions. When a tangent is
    /// wanted, a change of the contact couplings rebuilds the sparse pattern and forgets the
    /// symbolic factorization.
    fn evaluate(
        &mut self,
        u: &[f64],
        want_k: bool,
        want_states: bool,
        dup: Option<&[f64]>,
    ) -> Result<(Evaluation, Vec<SlotState>, Vec<Contribution>)> {
        let (contribs, states) =
            self.contact
                .evaluate(self.asm.model, self.dofs, u, Search::Fresh)?;
        let ev = self.evaluate_with_contact(u, want_k, want_states, dup, &contribs)?;
        Ok((ev, states, contribs))
    }

    /// The element loop plus already evaluated contact contributions.
    fn evaluate_with_contact(
        &mut self,
        u: &[f64],
        want_k: bool,
        want_states: bool,
        dup: Option<&[f64]>,
        contribs: &[Contribution],
    ) -> Result<Evaluation> {
        if want_k && !self.contact.is_empty() {
            let couplings: Vec<Vec<usize>> = contribs.iter().map(|c| c.codes.clone()).collect();
            if self.asm.set_couplings(&couplings) {
                self.solver.reset();
                self.factor_valid = false;
            }
        }
        self.asm.evaluate(u, want_k, want_states, dup, contribs)
    }

    fn factorize(&mut self, ev: &Evaluation) -> Result<()> {
        let kv = ev.k_values.as_ref().expect("tangent requested");
        let dofs = self.dofs;
        let model = self.asm.model;
        let describe = |eq: usize| {
            for (n, list) in dofs.node_dofs.iter().enumerate() {
                if let Some((d, _)) = list.iter().find(|(_, c)| *c == eq) {
                    return format!("node {} DOF {d}", model.nodes[n].label);
                }
            }
            format!("equation {eq}")
        };
        self.solver
            .factorize(&self.asm.pattern, kv, self.linear, &describe)?;
        self.factor_valid = self.linear;
        Ok(())
    }

    /// Solve the Newton system condensed on the contact DOFs, if that mode applies; Ok(false) when
    /// the caller must factorize the full tangent instead.
    fn solve_condensed(
        &mut self,
        u: &[f64],
        rhs: &mut [f64],
        contribs: &[Contribution],
    ) -> Result<bool> {
        if let Condensed::Pending(eqs) = &self.condensed {
            let eqs = eqs.clone();
            let ev = self.asm.evaluate(u, true, false, None, &[])?;
            let k = ev.k_values.as_ref().expect("requested");
            self.condensed = match CondensedContact::new(
                &self.asm.pattern,
                k,
                eqs,
                self.solver.groups.clone(),
            ) {
                Some(c) => Condensed::Ready(Box::new(c)),
                None => Condensed::Off,
            };
        }
        match &mut self.condensed {
            Condensed::Ready(c) => c.solve(rhs, contribs, self.dofs),
            _ => Ok(false),
        }
    }

    /// Newton iterations towards external forces `f_ext` and prescribed values `up`.
    /// Ok(false) = no convergence within maxiter.
    fn newton(
        &mut self,
        u: &mut [f64],
        f_ext: &[f64],
        up: &[f64],
        a: &crate::model::Analysis,
        info: &mut StepInfo,
    ) -> Result<bool> {
        let nf = self.dofs.n_free;
        if nf == 0 {
            u[nf..].copy_from_slice(up);
            return Ok(true);
        }
        let dup: Vec<f64> = (0..up.len()).map(|i| up[i] - u[nf + i]).collect();
        if a.initialguess && dup.iter().any(|&d| d != 0.0) {
            // Tangent predictor: K_ff Δu_f = −K_fp Δu_p at the current state.
            let condensed = !matches!(self.condensed, Condensed::Off);
            let need_k = !condensed && (!self.factor_valid || !self.contact.is_empty());
            let (ev, _, contribs) = self.evaluate(u, need_k, false, Some(&dup))?;
            let mut rhs: Vec<f64> = ev
                .k_fp_dup
                .as_ref()
                .expect("requested")
                .iter()
                .map(|v| -v)
                .collect();
            if !(condensed && self.solve_condensed(u, &mut rhs, &contribs)?) {
                if condensed {
                    // Condensing did not apply: factorize the full tangent.
                    let (ev, _, _) = self.evaluate(u, true, false, None)?;
                    self.factorize(&ev)?;
                } else if need_k {
                    self.factorize(&ev)?;
                }
                self.solver.solve_in_place(&mut rhs)?;
            }
            for i in 0..nf {
                u[i] += rhs[i];
            }
        }
        u[nf..].copy_from_slice(up);
        let mut du = vec![0.0; nf];
        let start = info.residual_history.len();
        let has_contact = !self.contact.is_empty();
        for it in 0..=a.maxiter {
            let (contribs, states) =
                self.contact
                    .evaluate(self.asm.model, self.dofs, u, Search::Fresh)?;
            let condensed = !matches!(self.condensed, Condensed::Off);
            let want_k = !condensed
                && !self.factor_valid
                && (it == 0 || has_contact || a.manrmsteps.is_some_and(|k| it % k == 0));
            let ev = self.evaluate_with_contact(u, want_k, false, None, &contribs)?;
            let mut rhs: Vec<f64> = (0..nf).map(|i| f_ext[i] - ev.f_int[i]).collect();
            let (force_err, converged) = self.check(&rhs, f_ext, &ev.ebe, &du, u, a, it);
            info.residual_history.push(force_err);
            info.iterations += 1;
            if self.progress {
                eprint!("\r  iteration {it:3}  residual {}   ", sci(force_err, 2));
            }
            if converged && (it > 0 || force_err == 0.0) {
                if it == 0 && !has_contact && !self.factor_valid && ev.k_values.is_some() {
                    // An unloaded step needs no solve, but a model must not pass as solved when
                    // its stiffness is singular (an unloaded mechanism): factorize once.
                    self.factorize(&ev)?;
                }
                info.iterations -= 1;
                return Ok(true);
            }
            if !force_err.is_finite() {
                return Err(Error::Solve("residual is not finite".into()));
            }
            if it == a.maxiter {
                break;
            }
            // With contact, hertz chooses the iteration (manrmsteps does not apply): full Newton
            // while the contact state (pairings, active set) changes or the residual falls less
            // than tenfold; once it is settled and contracting, the tangent has barely moved and
            // the factorization is reused (a chord step: one solve instead of a factorization).
            let refresh = if has_contact {
                let signature: Vec<(Partner, bool)> =
                    states.iter().map(|s| (s.partner, s.active)).collect();
                let hist = &info.residual_history[start..];
                let contracting =
                    hist.len() >= 2 && hist[hist.len() - 1] <= 0.1 * hist[hist.len() - 2];
                let refresh =
                    it == 0 || self.factored_contact.as_ref() != Some(&signature) || !contracting;
                if refresh {
                    self.factored_contact = Some(signature);
                }
                refresh
            } else {
                want_k
            };
            if !(condensed && self.solve_condensed(u, &mut rhs, &contribs)?) {
                if condensed {
                    // Condensing did not apply: factorize the full tangent.
                    let ev = self.evaluate_with_contact(u, true, false, None, &contribs)?;
                    self.factorize(&ev)?;
                } else if refresh {
                    self.factorize(&ev)?;
                }
                self.solver.solve_in_place(&mut rhs)?;
            }
            for i in 0..nf {
                u[i] += rhs[i];
            }
            du.copy_from_slice(&rhs);
        }
        Ok(false)
    }

    /// OOFEM's convergence test per DOF-id group (spec §1.3). Returns (largest force error, converged).
    #[allow(clippy::too_many_arguments)]
    fn check(
        &self,
        rhs: &[f64],
        f_ext: &[f64],
        ebe: &[f64; 4],
        du: &[f64],
        u: &[f64],
        a: &crate::model::Analysis,
        it: usize,
    ) -> (f64, bool) {
        let mut num = [0.0; 4];
        let mut den = [0.0; 4];
        let mut dd = [0.0; 4];
        let mut uu = [0.0; 4];
        let mut present = [false; 4];
        for i in 0..rhs.len() {
            let g = self.dofs.primary_dof_id[i] as usize;
            present[g] = true;
            num[g] += rhs[i] * rhs[i];
            den[g] += f_ext[i] * f_ext[i];
            dd[g] += du[i] * du[i];
            uu[g] += u[i] * u[i];
        }
        let mut worst: f64 = 0.0;
        let mut ok = true;
        // Multiplier rows (each its own group in OOFEM, with a negligible reference): absolute.
        for i in (self.dofs.n_free - self.dofs.n_lambda)..rhs.len() {
            worst = worst.max(rhs[i].abs());
            if !(rhs[i].abs() <= a.rtolf) {
                ok = false;
            }
        }
        for g in 1..4 {
            if !present[g] {
                continue;
            }
            let d = den[g] + ebe[g];
            let fe = if d < 1e-6 {
                num[g].sqrt()
            } else {
                (num[g] / d).sqrt()
            };
            worst = worst.max(fe);
            if !(fe <= a.rtolf) {
                ok = false;
            }
            if a.rtold > 0.0 && it > 0 {
                let de = if uu[g] < 1e-6 {
                    dd[g].sqrt()
                } else {
                    (dd[g] / uu[g]).sqrt()
                };
                if !(de <= a.rtold) {
                    ok = false;
                }
            }
        }
        (worst, ok)
    }
}
