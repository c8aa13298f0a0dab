//! Implicit dynamics (`NonLinearDynamic`, spec §1.2): in every time step Newton solves
//! M·a(u) + η·M·v(u) + δ·Ḟ_int(u) + F_int(u) + F_contact(u) = F_ext(t), with a and v of the
//! step's displacement increment by OOFEM's `ddtScheme` ([`TimeScheme::constants`]); the inertia
//! is a [`StepTerms`] of the same Newton iteration statics uses.
//!
//! Stiffness-proportional damping (`delta`) is δ times the rate of the elements' internal
//! forces, Ḟ, taken from their history by the scheme's own velocity rule (as v from u): on a
//! linear model δ·K·v exactly, in large deformation and plasticity the rate of the actual
//! forces, whose tangent δ·c₁·K_T (c₁ the velocity's coefficient of u) is exact. OOFEM takes
//! δ·K_T·v with K_T of the last iterate and of the step start (not the derivative of its
//! force), damps the contact's tangent by (1 + δ·c₁) though not its force, and in `DIIDynamic`
//! puts the Newmark a6 where the velocity's history belongs (its QUIRKs); hertz damps the
//! bodies alone, with the velocity's own history.
//!
//! Where hertz differs from OOFEM, on purpose: the mass couples prescribed and free DOFs (OOFEM
//! drops M_fp·a_p, QUIRK: base excitation is then wrong with consistent mass); the starting
//! acceleration is in equilibrium, M·a₀ = F_ext(0) − F_int(u₀) − C·v₀, where no initial
//! condition gives one (OOFEM takes 0, QUIRK); the reactions are the support forces, inertia
//! and damping included (OOFEM's omit them, QUIRK); a step that does not converge is cut in
//! time (the scheme's constants follow the substep); the mass of the contact surfaces' nodes,
//! slave and deformable master, is moved into their elements
//! ([`crate::assembly::mass::redistribute`]; OOFEM keeps it, and its contact chatters and
//! makes energy at an impact) unless the analysis says `keepcontactmass`.

use super::load_history::LoadHistory;
use super::newton::{Committed, NewtonContext};
use super::params::SolveParams;
use super::report::{Observer, StepInfo, StepReport};
use super::step_result::{Energy, Motion, StepResult};
use super::terms::{Both, FollowerTerms, StepTerms};
use crate::assembly::{DofMap, MassMatrix, Pattern};
use crate::contact::SlotState;
use crate::error::{Error, Result};
use crate::model::{Dynamics, Model};
use crate::solid::follower::FollowerLoads;
use crate::solid::GpState;
use std::time::Instant;

/// The inertia and damping of a step: c₀·M·u + M·base with c₀ = w·a0 + η·a1 and base the
/// history's part (w·a(u) + η·v(u) = c₀·u + base; M·base is `history`, formed once a step),
/// tangent c₀·M; with HHT (w = 1/(1 + α)) the step's start forces −α·w·(C·v + F_int + F_c −
/// F_ext)ₙ too (`start`, constant).
struct Inertia<'a> {
    mass: &'a MassMatrix,
    c0: f64,
    /// δ·c₁: the elements' forces and tangent are taken (1 + δ·c₁) times (`history` holds the
    /// rest of δ·Ḟ).
    element_scale: f64,
    history: Vec<f64>,
    start: Option<Vec<f64>>,
    n_free: usize,
}

impl StepTerms for Inertia<'_> {
    fn add_forces(&self, u: &[f64], f_int: &mut [f64]) {
        self.mass.apply_add(self.c0, u, f_int);
        for (f, h) in f_int.iter_mut().zip(&self.history) {
            *f += h;
        }
        if let Some(start) = &self.start {
            for (f, s) in f_int.iter_mut().zip(start) {
                *f += s;
            }
        }
    }

    fn add_tangent(&self, _u: &[f64], pattern: &Pattern, k: &mut [f64]) {
        self.mass.add_to_tangent(self.c0, self.n_free, pattern, k);
    }

    /// The squares of the two inertia forces summed into the residual, M·c₀u and M·base, per
    /// DOF id: OOFEM measures the residual against the load with the inertia history in it
    /// (M·base); their difference, the inertia at the solution, can be far smaller than each
    /// (a slow oscillation at a short step), and the residual's round-off is theirs.
    fn add_force_norms(&self, u: &[f64], dofs: &DofMap, ebe: &mut [f64; 4]) {
        let mut scaled = vec![0.0; u.len()];
        self.mass.apply_add(self.c0, u, &mut scaled);
        let n = dofs.n_free - dofs.n_lambda;
        for f in [Some(&scaled), Some(&self.history), self.start.as_ref()]
            .into_iter()
            .flatten()
        {
            for (i, fi) in f.iter().enumerate().take(n) {
                ebe[dofs.primary_dof_id[i] as usize] += fi * fi;
            }
        }
    }

    /// Constant within a step; the driver asks for a new factorization when c₀ changes.
    fn constant_tangent(&self) -> bool {
        true
    }

    fn element_scale(&self) -> f64 {
        self.element_scale
    }
}

/// The state of the motion at the end of a (sub)step.
#[derive(Clone)]
struct State {
    u: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    /// The last increment (the three-point scheme's history); None at the start and after a
    /// change of step size.
    du: Option<Vec<f64>>,
    /// The elements' internal forces' rate and its rate (Ḟ, F̈, by the scheme's rules for v
    /// and a) and their last increment: the history of stiffness-proportional damping (empty
    /// without it).
    rate: Rates,
    /// The forces at this state, for the energies' trapezoidal rule: the elements', the
    /// contact's, the damping's, the external loads' (follower ones included) and the supports'.
    forces: Forces,
    /// The support forces on the prescribed DOFs (inertia and damping included).
    reactions: Vec<f64>,
    energy: Energy,
}

/// The rates of the elements' internal forces F: Ḟ and F̈ (as v and a of u), and F's last
/// increment (as `du`).
#[derive(Clone, Default)]
struct Rates {
    first: Vec<f64>,
    second: Vec<f64>,
    last: Option<Vec<f64>>,
}

impl Rates {
    /// The rates at the end of a step whose forces went from `old` to `new`, by the scheme's
    /// constants `k` (those of the step's a and v).
    fn advance(&self, new: &[f64], old: &[f64], k: &[f64; 7]) -> Rates {
        let df: Vec<f64> = new.iter().zip(old).map(|(a, b)| a - b).collect();
        let zero = vec![0.0; df.len()];
        let last = self.last.as_deref().unwrap_or(&zero);
        let (first, second) = advance(k, &df, (&self.first, &self.second), last);
        Rates {
            first,
            second,
            last: Some(df),
        }
    }
}

/// The scheme's rule (constants `k`, spec §1.2) for the first and second rates of a quantity
/// whose increment over the step is `d`, from their values at the step's start and the last
/// step's increment `last`: v and a of u, and Ḟ and F̈ of the elements' forces.
fn advance(
    k: &[f64; 7],
    d: &[f64],
    (first, second): (&[f64], &[f64]),
    last: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let rate = (0..d.len())
        .map(|i| k[1] * d[i] - k[4] * first[i] - k[5] * second[i] - k[6] * last[i])
        .collect();
    let rate2 = (0..d.len())
        .map(|i| k[0] * d[i] - k[2] * first[i] - k[3] * second[i])
        .collect();
    (rate, rate2)
}

/// A converged (sub)step's contact states and material point states.
type Converged = (Vec<SlotState>, Vec<Vec<GpState>>);

/// Forces at a state, primary numbering: the elements', the contact's, the damping's (empty
/// where the scheme keeps its own account of them) and the external loads' (follower ones
/// included).
#[derive(Clone, Default)]
pub(super) struct Forces {
    pub internal: Vec<f64>,
    pub contact: Vec<f64>,
    pub damping: Vec<f64>,
    pub external: Vec<f64>,
}

impl Forces {
    /// The forces of a `committed` state, whose internal forces hold the elements' and the
    /// contact's, with `damping` and `external`.
    pub(super) fn of(committed: &Committed, damping: Vec<f64>, external: Vec<f64>) -> Forces {
        let contact = &committed.contact;
        Forces {
            internal: committed
                .ev
                .f_int
                .iter()
                .zip(contact)
                .map(|(f, c)| f - c)
                .collect(),
            contact: contact.clone(),
            damping,
            external,
        }
    }

    /// Add each force's work over the increment `du` from the state of `old` to this one, by
    /// the trapezoidal rule, to `energy` (the damping's where both states track it).
    pub(super) fn add_work(&self, old: &Forces, du: &[f64], energy: &mut Energy) {
        let work = |o: &[f64], n: &[f64]| -> f64 {
            du.iter()
                .enumerate()
                .map(|(i, d)| 0.5 * (o[i] + n[i]) * d)
                .sum()
        };
        energy.internal += work(&old.internal, &self.internal);
        energy.contact += work(&old.contact, &self.contact);
        energy.external += work(&old.external, &self.external);
        if !self.damping.is_empty() && !old.damping.is_empty() {
            energy.damping += work(&old.damping, &self.damping);
        }
    }
}

/// The initial displacements, velocities and accelerations of the free DOFs from the model's
/// `InitialCondition`s (0 where none is given; the prescribed DOFs follow their conditions),
/// and whether any gives an acceleration.
pub(super) fn initial_values(model: &Model, dofs: &DofMap) -> ([Vec<f64>; 3], bool) {
    let (np, nf) = (dofs.n_primary(), dofs.n_free);
    let mut values = [vec![0.0; np], vec![0.0; np], vec![0.0; np]];
    let mut given_a = false;
    for ic in &model.initial_conditions {
        for &n in &model.sets[ic.set - 1].nodes {
            for &d in &ic.dofs {
                let Some(code) = dofs.code(n, d).filter(|&c| c < nf) else {
                    continue;
                };
                for (value, target) in [ic.displacement, ic.velocity, ic.acceleration]
                    .into_iter()
                    .zip(values.iter_mut())
                {
                    if let Some(x) = value {
                        target[code] = x;
                    }
                }
                given_a |= ic.acceleration.is_some();
            }
        }
    }
    (values, given_a)
}

/// What stays fixed over the run.
struct Run<'a> {
    model: &'a Model,
    dofs: &'a DofMap,
    dynamics: Dynamics,
    mass: MassMatrix,
    history: LoadHistory<'a>,
    follower: FollowerLoads,
    /// c₀ and the elements' damping scale δ·c₁ of the factorization the solver holds.
    last_c0: Option<(f64, f64)>,
}

/// Run a `NonLinearDynamic` analysis (see the module's doc), calling `on_step` after each step.
pub fn run(
    model: &Model,
    params: &SolveParams,
    observer: &dyn Observer,
    mut on_step: impl FnMut(&StepResult) -> Result<()>,
) -> Result<()> {
    let dynamics = model.analysis.dynamics.expect("a dynamic analysis");
    let (contact, dofs) = super::newton::set_up(model, observer)?;
    let (mut ctx, mut initial_warnings) =
        NewtonContext::new(model, &dofs, contact, params, observer)?;
    let mut massless = vec![false; model.nodes.len()];
    if !dynamics.keep_contact_mass {
        for n in crate::model::queries::contact_surface_nodes(model) {
            massless[n] = true;
        }
    }
    let mut run = Run {
        model,
        dofs: &dofs,
        dynamics,
        mass: MassMatrix::new(model, &dofs, dynamics.lumped, &massless)?,
        history: LoadHistory::new(model, &dofs)?,
        follower: FollowerLoads::new(model, &dofs)?,
        last_c0: None,
    };
    let mut state = run.initial_state(&mut ctx)?;
    let times = model.step_times();
    let dt = model.analysis.deltat;
    for (k, &t) in times.iter().enumerate() {
        let clock = Instant::now();
        let step = k + 1;
        ctx.begin_step(step);
        let mut info = StepInfo {
            warnings: std::mem::take(&mut initial_warnings),
            ..Default::default()
        };
        let (contact_states, states) =
            run.step_with_cutbacks(&mut ctx, &mut state, (t - dt, t), params, &mut info)?;
        info.wall_seconds = clock.elapsed().as_secs_f64();
        ctx.finish_step_info(&mut info, &contact_states);
        observer.step(&StepReport::of(step, times.len(), t, &info));
        on_step(&StepResult {
            step,
            time: t,
            dofs: &dofs,
            u: &state.u,
            reactions: &state.reactions,
            states: &states,
            contact: &contact_states,
            info: &info,
            motion: Some(Motion {
                velocity: &state.v,
                acceleration: &state.a,
                energy: state.energy,
            }),
        })?;
    }
    Ok(())
}

impl Run<'_> {
    /// The support forces on the prescribed DOFs at a state with accelerations `acc` and
    /// forces `f`: F_int + F_c + C·v + M·a − F_ext.
    fn support_forces(&self, f: &Forces, acc: &[f64]) -> Vec<f64> {
        let (np, nf) = (self.dofs.n_primary(), self.dofs.n_free);
        let mut m = vec![0.0; np];
        self.mass.apply_add(1.0, acc, &mut m);
        (nf..np)
            .map(|p| f.internal[p] + f.contact[p] + f.damping[p] + m[p] - f.external[p])
            .collect()
    }

    /// The start: displacements and velocities from the initial conditions (prescribed DOFs
    /// from their conditions at t = 0), accelerations from them or, where none is given, from
    /// equilibrium.
    fn initial_state(&self, ctx: &mut NewtonContext) -> Result<State> {
        let (model, dofs) = (self.model, self.dofs);
        let (np, nf) = (dofs.n_primary(), dofs.n_free);
        let ([mut u, v, mut a], given_a) = initial_values(model, dofs);
        u[nf..].copy_from_slice(&self.history.prescribed_at(0.0));
        let committed = ctx.commit_step(&u)?;
        let delta = self.dynamics.delta;
        let mut rate = Rates::default();
        let mut damping = vec![0.0; np];
        self.mass.apply_add(self.dynamics.eta, &v, &mut damping);
        if delta > 0.0 {
            // Ḟ₀ = K(u₀)·v₀.
            rate.first = ctx.tangent_product(&u, &v)?;
            for (d, f) in damping.iter_mut().zip(&rate.first) {
                *d += delta * f;
            }
        }
        let forces = Forces::of(&committed, damping, self.external_forces(0.0, &u));
        if !given_a {
            // M_ff a_f = F_ext − F_int − F_c − C v over the displacement equations.
            let n_disp = nf - dofs.n_lambda;
            let f = &forces;
            let rhs: Vec<f64> = (0..n_disp)
                .map(|i| f.external[i] - f.internal[i] - f.contact[i] - f.damping[i])
                .collect();
            let af = self.solve_mass(&rhs);
            a[..n_disp].copy_from_slice(&af);
        }
        if delta > 0.0 {
            // F̈₀ = K(u₀)·a₀ (the term of v₀ along the tangent's change left out).
            rate.second = ctx.tangent_product(&u, &a)?;
        }
        let kinetic = self.mass.half_norm(&v);
        Ok(State {
            reactions: self.support_forces(&forces, &a),
            u,
            v,
            a,
            du: None,
            rate,
            forces,
            energy: Energy {
                kinetic,
                initial: kinetic,
                ..Default::default()
            },
        })
    }

    /// x with M_ff·x = b over the first b.len() equations (the displacement ones), 0 on the
    /// DOFs without mass (contact nodes whose mass moved into the body: they follow by
    /// equilibrium): conjugate gradients preconditioned by the diagonal (M is positive definite
    /// and well conditioned on the DOFs with mass).
    fn solve_mass(&self, b: &[f64]) -> Vec<f64> {
        let n = b.len();
        let np = self.dofs.n_primary();
        let diag = self.mass.diagonal(n);
        let has = |i: usize| diag[i] > 0.0;
        let apply = |x: &[f64]| {
            let mut full = vec![0.0; np];
            full[..n].copy_from_slice(x);
            let mut y = vec![0.0; np];
            self.mass.apply_add(1.0, &full, &mut y);
            y.truncate(n);
            (0..n)
                .map(|i| if has(i) { y[i] } else { 0.0 })
                .collect::<Vec<f64>>()
        };
        let precondition = |r: &[f64]| -> Vec<f64> {
            (0..n)
                .map(|i| if has(i) { r[i] / diag[i] } else { 0.0 })
                .collect()
        };
        let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
        let mut x = vec![0.0; n];
        let mut r: Vec<f64> = (0..n).map(|i| if has(i) { b[i] } else { 0.0 }).collect();
        let norm_b = dot(&r, &r).sqrt();
        let mut z = precondition(&r);
        let mut p = z.clone();
        let mut rz = dot(&r, &z);
        for _ in 0..n.max(1) {
            if dot(&r, &r).sqrt() <= 1e-14 * norm_b || norm_b == 0.0 {
                break;
            }
            let mp = apply(&p);
            let alpha = rz / dot(&p, &mp);
            for i in 0..n {
                x[i] += alpha * p[i];
                r[i] -= alpha * mp[i];
            }
            z = precondition(&r);
            let rz_new = dot(&r, &z);
            let beta = rz_new / rz;
            rz = rz_new;
            for i in 0..n {
                p[i] = z[i] + beta * p[i];
            }
        }
        x
    }

    /// The external forces at time `t` and state `u`: the loads and the follower loads.
    fn external_forces(&self, t: f64, u: &[f64]) -> Vec<f64> {
        let np = self.dofs.n_primary();
        let mut f = self.history.total_at(t);
        let terms = self.follower_terms(t);
        // The follower terms add −F to the internal side.
        let mut neg = vec![0.0; np];
        terms.add_forces(u, &mut neg);
        for (f, n) in f.iter_mut().zip(&neg) {
            *f -= n;
        }
        f
    }

    fn follower_terms(&self, t: f64) -> FollowerTerms<'_> {
        FollowerTerms {
            loads: &self.follower,
            model: self.model,
            dofs: self.dofs,
            scale: self.history.total_factors_at(t),
        }
    }

    /// Advance `state` from time `span.0` to `span.1`, in 2, 4, … substeps when Newton does not
    /// converge; returns the contact and material states at the end.
    fn step_with_cutbacks(
        &mut self,
        ctx: &mut NewtonContext,
        state: &mut State,
        span: (f64, f64),
        params: &SolveParams,
        info: &mut StepInfo,
    ) -> Result<Converged> {
        let start = state.clone();
        let checkpoint = ctx.checkpoint();
        let mut why = String::new();
        for level in 0..=params.max_cutbacks {
            let nsub = 1usize << level;
            *state = start.clone();
            ctx.rollback(&checkpoint);
            if level > 0 {
                // A new step size: the three-point scheme restarts from backward Euler.
                state.du = None;
                state.rate.last = None;
            }
            let h = (span.1 - span.0) / nsub as f64;
            let mut contact = None;
            for s in 1..=nsub {
                let t = span.0 + s as f64 * h;
                match self.substep(ctx, state, (t, h), info) {
                    Ok(Some(states)) => contact = Some(states),
                    Ok(None) => {
                        why = format!(
                            "no convergence in {} iterations{}",
                            self.model.analysis.maxiter,
                            ctx.diagnosis()
                                .map(|d| format!(" ({d})"))
                                .unwrap_or_default()
                        );
                        contact = None;
                        break;
                    }
                    Err(Error::Solve(msg)) => {
                        why = msg;
                        contact = None;
                        break;
                    }
                    Err(e) => return Err(e),
                }
            }
            if let Some(states) = contact {
                info.substeps = nsub;
                return Ok(states);
            }
            ctx.attempt_failed();
            self.last_c0 = None;
            if level < params.max_cutbacks {
                ctx.observer().retry(&format!(
                    "t = {}: {why}; retrying in {} time substeps",
                    span.1,
                    2 * nsub
                ));
            }
        }
        Err(Error::Solve(format!(
            "the time step to t = {} did not converge even after {} halvings: {why}",
            span.1, params.max_cutbacks
        )))
    }

    /// One Newton solve from `state` to time `t` over the step `h`; None if it did not converge.
    fn substep(
        &mut self,
        ctx: &mut NewtonContext,
        state: &mut State,
        (t, h): (f64, f64),
        info: &mut StepInfo,
    ) -> Result<Option<Converged>> {
        let (np, nf) = (self.dofs.n_primary(), self.dofs.n_free);
        let eta = self.dynamics.eta;
        let k = self.dynamics.scheme.constants(h, state.du.is_none());
        // HHT divides its step's equation by 1 + α: the inertia by it, the start's forces by −α.
        let alpha = self.dynamics.scheme.alpha();
        let w = 1.0 / (1.0 + alpha);
        let c0 = w * k[0] + eta * k[1];
        let zero = vec![0.0; np];
        let du_prev = state.du.as_deref().unwrap_or(&zero);
        // w a(u) + η v(u) = c0 (u − u_n) + h_n.
        let base: Vec<f64> = (0..np)
            .map(|i| {
                -c0 * state.u[i]
                    - (w * k[2] + eta * k[4]) * state.v[i]
                    - (w * k[3] + eta * k[5]) * state.a[i]
                    - eta * k[6] * du_prev[i]
            })
            .collect();
        // δ·Ḟ(u) = δ·(c₁·(F(u) − Fₙ) − a4·Ḟₙ − a5·F̈ₙ − a6·ΔFₙ): its δ·c₁·F(u) by the elements'
        // scale, the rest constant.
        let delta = self.dynamics.delta;
        let element_scale = delta * k[1];
        let f = &state.forces;
        let damping_history: Option<Vec<f64>> = (delta > 0.0).then(|| {
            let r = &state.rate;
            let last = r.last.as_deref().unwrap_or(&zero);
            (0..np)
                .map(|i| {
                    -delta
                        * (k[1] * f.internal[i]
                            + k[4] * r.first[i]
                            + k[5] * r.second[i]
                            + k[6] * last[i])
                })
                .collect()
        });
        let start = (alpha != 0.0).then(|| {
            (0..np)
                .map(|i| -alpha * w * (f.damping[i] + f.internal[i] + f.contact[i] - f.external[i]))
                .collect()
        });
        if self.last_c0 != Some((c0, element_scale)) {
            // The tangent's mass part or the elements' damping changed: factorize afresh.
            ctx.attempt_failed();
            self.last_c0 = Some((c0, element_scale));
        }
        let mut history = damping_history.unwrap_or_else(|| vec![0.0; np]);
        self.mass.apply_add(1.0, &base, &mut history);
        let inertia = Inertia {
            mass: &self.mass,
            c0,
            element_scale,
            history,
            start,
            n_free: nf,
        };
        let follower = self.follower_terms(t);
        let terms = Both(&inertia, &follower);
        let f_ext = self.history.total_at(t);
        let up = self.history.prescribed_at(t);
        let mut u = state.u.clone();
        if !ctx.newton(&mut u, (&f_ext, &up), &self.model.analysis, info, &terms)? {
            return Ok(None);
        }
        ctx.commit_substep(&u)?;
        let du: Vec<f64> = u.iter().zip(&state.u).map(|(a, b)| a - b).collect();
        let (v, a) = advance(&k, &du, (&state.v, &state.a), du_prev);
        let committed = ctx.commit_step(&u)?;
        let mut damping = vec![0.0; np];
        self.mass.apply_add(eta, &v, &mut damping);
        let mut forces = Forces::of(&committed, damping, self.external_forces(t, &u));
        let rate = if delta > 0.0 {
            let rate = state
                .rate
                .advance(&forces.internal, &state.forces.internal, &k);
            for (d, f) in forces.damping.iter_mut().zip(&rate.first) {
                *d += delta * f;
            }
            rate
        } else {
            Rates::default()
        };
        let mut energy = state.energy;
        forces.add_work(&state.forces, &du, &mut energy);
        // The supports' forces at both ends, on the prescribed DOFs' increments.
        let reactions = self.support_forces(&forces, &a);
        energy.supports += (0..np - nf)
            .map(|i| 0.5 * (state.reactions[i] + reactions[i]) * du[nf + i])
            .sum::<f64>();
        energy.kinetic = self.mass.half_norm(&v);
        *state = State {
            u,
            v,
            a,
            du: Some(du),
            rate,
            forces,
            reactions,
            energy,
        };
        Ok(Some((
            committed.states,
            committed.ev.states.unwrap_or_default(),
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::Assembler;

    /// The inertia term's tangent c₀·M is the derivative of its forces (central differences,
    /// every free column), on two plane stress quadrilaterals with the consistent mass (full
    /// blocks) and one node's mass moved into its element, with a step history and HHT's start
    /// forces in the residual.
    #[test]
    fn inertia_tangent_is_the_derivative_of_its_forces() {
        let text = "m.out\nmass\nNonLinearDynamic nsteps 1 deltat 0.1 ddtScheme 2\n\
                    domain 2dPlaneStress\nOutputManager\n\
                    ndofman 6 nelem 2 ncrosssect 1 nmat 1 nbc 1 nic 0 nltf 1 nset 2\n\
                    node 1 coords 2 0 0\nnode 2 coords 2 1 0\nnode 3 coords 2 2.1 0.1\n\
                    node 4 coords 2 0 1\nnode 5 coords 2 1.1 1.2\nnode 6 coords 2 2 1\n\
                    PlaneStress2d 1 nodes 4 1 2 5 4 crossSect 1 mat 1\n\
                    PlaneStress2d 2 nodes 4 2 3 6 5 crossSect 1 mat 1\n\
                    SimpleCS 1 thick 0.3 material 1 set 1\nIsoLE 1 d 2.5 E 1 n 0.3 tAlpha 0\n\
                    BoundaryCondition 1 loadTimeFunction 1 dofs 2 1 2 values 2 0 0 set 2\n\
                    ConstantFunction 1 f(t) 1\nSet 1 allelements\nSet 2 nodes 1 1\n";
        let model = crate::input::read_model_str(text, "m.in").unwrap().model;
        let dofs = DofMap::new(&model, &Default::default()).unwrap();
        let mut massless = vec![false; model.nodes.len()];
        massless[2] = true;
        let mass = MassMatrix::new(&model, &dofs, false, &massless).unwrap();
        let (np, nf) = (dofs.n_primary(), dofs.n_free);
        let history: Vec<f64> = (0..np).map(|i| 0.3 * i as f64 - 1.0).collect();
        let inertia = Inertia {
            mass: &mass,
            c0: 37.0,
            element_scale: 0.0,
            history,
            start: Some((0..np).map(|i| 0.1 * (i as f64).sin()).collect()),
            n_free: nf,
        };
        let pattern = Assembler::new(&model, &dofs).unwrap().pattern;
        let mut k = vec![0.0; pattern.nnz()];
        let u: Vec<f64> = (0..np).map(|i| 0.01 * (i as f64).cos()).collect();
        inertia.add_tangent(&u, &pattern, &mut k);
        let entry = |r: usize, c: usize| {
            let (r, c) = if pattern.symmetric {
                (r.min(c), r.max(c))
            } else {
                (r, c)
            };
            let (s, e) = (pattern.col_ptr[c], pattern.col_ptr[c + 1]);
            pattern.row_idx[s..e]
                .binary_search(&r)
                .map_or(0.0, |p| k[s + p])
        };
        let h = 1e-6;
        for j in 0..nf {
            let force = |d: f64| {
                let mut x = u.clone();
                x[j] += d;
                let mut f = vec![0.0; np];
                inertia.add_forces(&x, &mut f);
                f
            };
            let (plus, minus) = (force(h), force(-h));
            for i in 0..nf {
                let fd = (plus[i] - minus[i]) / (2.0 * h);
                assert!(
                    (fd - entry(i, j)).abs() < 1e-7 * 37.0,
                    "({i}, {j}): {} vs {fd}",
                    entry(i, j)
                );
            }
        }
        // The mass moved off node 3 leaves its rows empty and keeps the body's: ½·1ᵀM1 over
        // both directions is ρ·t·(1.15 + 1.05).
        let diagonal = mass.diagonal(np);
        for d in 1..=2 {
            assert_eq!(diagonal[dofs.code(2, d).unwrap()], 0.0);
        }
        let total = mass.half_norm(&vec![1.0; np]);
        assert!((total / (2.5 * 0.3 * 2.2) - 1.0).abs() < 1e-12, "{total}");
    }
}
