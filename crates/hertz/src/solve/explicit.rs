//! Explicit dynamics (`NlDEIDynamic`, spec §1.4): central differences on the lumped mass,
//! no equation solved. With h the time step and c the damping coefficient (C = c·M):
//! v_{k+½} (1 + c h/2) = v_{k−½} (1 − c h/2) + h (F_ext − F_int − F_contact)(u_k)/m,
//! u_{k+1} = u_k + h v_{k+½}; at step k v_k = (v_{k−½} + v_{k+½})/2 and a_k the change of
//! velocity over h. Contact is by penalty (a multiplier has no explicit update).
//!
//! The stable step: h ≤ reduct · 2/ω_max with ω²_max bounded by max_i Σ_j |K_ij + K_c,ij| / m_i
//! (the ∞-norm of M⁻¹K bounds its spectral radius): exact for a uniform bar, safe for every
//! element, with the contact's penalty stiffness included as it engages. OOFEM takes
//! max K_jj/M_jj, an underestimate of ω²_max by up to 2 (QUIRK: a uniform chain of bars is
//! unstable unless reduct ≤ 0.707), and ignores contact. A `deltat` above the stable step is
//! kept for the output and split into substeps, with a warning; OOFEM shortens the step and
//! adds steps instead. A penalty condition without `penalty` takes each contact node's own
//! stiffness as its penalty (see [`node_stiffness`]). hertz starts with v_½ = v₀ + (h/2) a₀, a₀ from equilibrium (second
//! order; OOFEM starts first order and puts u₀ at t = Δt, QUIRK).

use super::dynamics::{initial_values, Forces};
use super::load_history::LoadHistory;
use super::newton::NewtonContext;
use super::params::SolveParams;
use super::report::{Observer, StepInfo, StepReport};
use super::step_result::{Energy, Motion, StepResult};
use crate::assembly::{DofMap, MassMatrix};
use crate::error::{Error, Result};
use crate::model::{Enforcement, Model, TimeScheme};
use std::time::Instant;

/// The state at one time: positions, the velocity half a step ahead, the forces there.
struct Explicit<'a> {
    model: &'a Model,
    dofs: &'a DofMap,
    history: LoadHistory<'a>,
    /// The lumped mass of every primary DOF.
    mass: Vec<f64>,
    /// Σ_j |K_ij| of the bodies' tangent (free equations, at the start).
    stiffness: Vec<f64>,
    damping: f64,
    reduct: f64,
    u: Vec<f64>,
    /// v_{k+½}, computed for a next step as long as the last one (`h`); corrected by
    /// ½ (h_next − h) a_k when the next step differs (variable-step leapfrog).
    v_ahead: Vec<f64>,
    /// The last step's size, and the acceleration at its end (free DOFs).
    h: f64,
    a_last: Vec<f64>,
    forces: Forces,
    energy: Energy,
    /// The largest stable step at the last state.
    stable: f64,
}

/// Run an `NlDEIDynamic` analysis (see the module's doc), calling `on_step` after each step.
pub fn run(
    model: &Model,
    params: &SolveParams,
    observer: &dyn Observer,
    mut on_step: impl FnMut(&StepResult) -> Result<()>,
) -> Result<()> {
    let dynamics = model.analysis.dynamics.expect("a dynamic analysis");
    let TimeScheme::CentralDifference { reduct } = dynamics.scheme else {
        unreachable!("an explicit analysis");
    };
    if let Some(c) = model
        .contacts
        .iter()
        .find(|c| c.enforcement.forces_are_unknowns(c.friction))
    {
        return Err(Error::Input {
            span: c.span.clone(),
            msg: format!(
                "explicit dynamics (NlDEIDynamic) takes frictionless penalty contact: contact \
                 condition {} has its forces as unknowns ({}), which only an implicit analysis \
                 (NonLinearDynamic) solves",
                c.number,
                if c.enforcement == Enforcement::Multipliers {
                    "Lagrange multipliers"
                } else {
                    "friction"
                }
            ),
        });
    }
    let (contact, dofs) = super::newton::set_up(model, observer)?;
    let (np, nf) = (dofs.n_primary(), dofs.n_free);
    let (mut ctx, mut warnings) = NewtonContext::new(model, &dofs, contact, params, observer)?;
    let stiffness = ctx.tangent_row_sums(&vec![0.0; np])?;
    ctx.set_mesh_penalties(&node_stiffness(&dofs, &stiffness));
    let mass = MassMatrix::new(model, &dofs, true, &vec![false; model.nodes.len()])?.diagonal(np);
    if let Some(i) = (0..nf).find(|&i| !(mass[i] > 0.0)) {
        return Err(Error::Solve(format!(
            "{} has no mass: explicit dynamics needs every free DOF to carry mass",
            super::equations::describe_eq(model, &dofs, i)
        )));
    }
    let mut state = Explicit {
        model,
        dofs: &dofs,
        history: LoadHistory::new(model, &dofs)?,
        stiffness,
        mass,
        damping: dynamics.eta,
        reduct,
        u: vec![0.0; np],
        v_ahead: vec![0.0; np],
        h: 0.0,
        a_last: vec![0.0; np],
        forces: Forces::default(),
        energy: Energy::default(),
        stable: f64::INFINITY,
    };
    let (mut v, mut a) = state.start(&mut ctx)?;
    let dt = model.analysis.deltat;
    let mut warned = false;
    let times = model.step_times();
    for (k, &t_end) in times.iter().enumerate() {
        let clock = Instant::now();
        let step = k + 1;
        ctx.begin_step(step);
        let mut info = StepInfo {
            warnings: std::mem::take(&mut warnings),
            ..Default::default()
        };
        // Substeps of equal size up to the step's end, each at most the stable step; one whose
        // end is less stable (a contact engaged) is taken again, shorter.
        let start = t_end - dt;
        let (mut t, mut substeps) = (start, 0);
        let mut states = (Vec::new(), Vec::new());
        while t < t_end - 1e-9 * dt {
            let remaining = t_end - t;
            let n = (remaining / state.stable - 1e-9).ceil().max(1.0);
            let h = remaining / n;
            if h < 1e-9 * dt {
                return Err(Error::Solve(format!(
                    "the stable time step fell to {:e} at t = {t:e} (a contact penalty far \
                     stiffer than the elements?)",
                    state.stable
                )));
            }
            if n > 1.0 && !warned {
                let msg = format!(
                    "deltat {dt:e} is above the stable time step {:e} at t = {t:e} (reduct \
                     {reduct} × 2/ω_max, contact included): steps are taken in substeps",
                    state.stable
                );
                observer.warning(&msg);
                info.warnings.push(msg);
                warned = true;
            }
            if k == 0 && substeps == 0 && t == start {
                // v_½ = v₀ + (h/2) a₀ on the free DOFs (the prescribed follow their conditions).
                state.start_velocity(&v, &a, h);
            }
            let r = state.advance(&mut ctx, t + h, h)?;
            if let Some((vs, acc, contact, gp)) = r {
                (v, a) = (vs, acc);
                states = (contact, gp);
                t += h;
                substeps += 1;
            }
        }
        info.substeps = substeps;
        info.wall_seconds = clock.elapsed().as_secs_f64();
        ctx.finish_step_info(&mut info, &states.0);
        observer.step(&StepReport::of(step, times.len(), t_end, &info));
        let reactions = state.reactions();
        on_step(&StepResult {
            step,
            time: t_end,
            dofs: &dofs,
            u: &state.u,
            reactions: &reactions,
            states: &states.1,
            contact: &states.0,
            info: &info,
            motion: Some(Motion {
                velocity: &v,
                acceleration: &a,
                energy: state.energy,
            }),
        })?;
    }
    Ok(())
}

/// Each node's stiffness in the reference state: the largest row sum Σ_j |K_ij| (`sums`, free
/// equations) of its free DOFs (0 where it has none). As a contact node's penalty it at most
/// doubles the node's squared frequency: the stable step shortens by √2 at most, and the node
/// does not bounce on the contact (a penalty 10 to 1000 times stiffer made a dropped rod's
/// bottom nodes chatter and the rod leave with 3 times its energy).
fn node_stiffness(dofs: &DofMap, sums: &[f64]) -> Vec<f64> {
    dofs.node_dofs
        .iter()
        .map(|list| {
            list.iter()
                .filter(|&&(_, c)| c < dofs.n_free)
                .map(|&(_, c)| sums[c])
                .fold(0.0, f64::max)
        })
        .collect()
}

/// A converged substep: velocities and accelerations at its end, contact and material states.
type Substep = (
    Vec<f64>,
    Vec<f64>,
    Vec<crate::contact::SlotState>,
    Vec<Vec<crate::solid::GpState>>,
);

impl Explicit<'_> {
    /// The start: u₀, v₀ and a₀ from the initial conditions, a₀ from equilibrium where none
    /// gives one (as the implicit schemes). Returns v₀ and a₀ (the run sets v_½ = v₀ + (h/2) a₀
    /// once it knows the first step h).
    fn start(&mut self, ctx: &mut NewtonContext) -> Result<(Vec<f64>, Vec<f64>)> {
        let nf = self.dofs.n_free;
        let ([u, v, a], given_a) = initial_values(self.model, self.dofs);
        self.u = u;
        self.u[nf..].copy_from_slice(&self.history.prescribed_at(0.0));
        self.evaluate(ctx, 0.0)?;
        let a = if given_a { a } else { self.acceleration(&v) };
        self.energy.kinetic = self.kinetic(&v);
        self.energy.initial = self.energy.kinetic;
        Ok((v, a))
    }

    /// v_½ = v₀ + (h/2) a₀ for a first step `h`.
    fn start_velocity(&mut self, v: &[f64], a: &[f64], h: f64) {
        let nf = self.dofs.n_free;
        self.v_ahead = (0..v.len())
            .map(|i| if i < nf { v[i] + 0.5 * h * a[i] } else { 0.0 })
            .collect();
        self.h = h;
        self.a_last = a.to_vec();
    }

    /// The forces at the current state and time `t`, and the stable step there.
    fn evaluate(&mut self, ctx: &mut NewtonContext, t: f64) -> Result<super::newton::Committed> {
        let committed = ctx.commit_step(&self.u)?;
        let nf = self.dofs.n_free;
        let mut omega2: f64 = 0.0;
        for i in 0..nf {
            let k = self.stiffness[i] + committed.contact_row_sums[i];
            omega2 = omega2.max(k / self.mass[i]);
        }
        // Never longer again: a step that grows back when a contact opens, next to a node
        // bouncing on a stiff penalty, breaks the scheme's energy (leapfrog is symplectic only
        // at a fixed step).
        let stable = if omega2 > 0.0 {
            self.reduct * 2.0 / omega2.sqrt()
        } else {
            f64::INFINITY
        };
        self.stable = self.stable.min(stable);
        let external = self.history.total_at(t);
        self.forces = Forces::of(&committed, Vec::new(), external);
        Ok(committed)
    }

    /// (F_ext − F_int − F_c − c·M·v)/m on the free DOFs (0 on the prescribed).
    fn acceleration(&self, v: &[f64]) -> Vec<f64> {
        let f = &self.forces;
        (0..self.u.len())
            .map(|i| {
                if i < self.dofs.n_free {
                    (f.external[i] - f.internal[i] - f.contact[i]) / self.mass[i]
                        - self.damping * v[i]
                } else {
                    0.0
                }
            })
            .collect()
    }

    fn kinetic(&self, v: &[f64]) -> f64 {
        0.5 * v
            .iter()
            .zip(&self.mass)
            .map(|(v, m)| m * v * v)
            .sum::<f64>()
    }

    /// Advance by `h` to time `t`: move with v_{k+½}, evaluate the forces, the velocity half a
    /// step ahead, the energies. Returns the velocities and accelerations at `t`, and the
    /// contact and material states; None, with nothing changed but the stable step, if the
    /// step is above the stable step at its end (a contact engaged: the step must be shorter).
    fn advance(&mut self, ctx: &mut NewtonContext, t: f64, h: f64) -> Result<Option<Substep>> {
        let (np, nf) = (self.u.len(), self.dofs.n_free);
        let before = self.u.clone();
        let kept_ahead = self.v_ahead.clone();
        for i in 0..nf {
            self.v_ahead[i] += 0.5 * (h - self.h) * self.a_last[i];
        }
        for i in 0..nf {
            self.u[i] += h * self.v_ahead[i];
        }
        self.u[nf..].copy_from_slice(&self.history.prescribed_at(t));
        let old = std::mem::take(&mut self.forces);
        let committed = self.evaluate(ctx, t)?;
        if self.stable < h * (1.0 - 1e-9) {
            self.u = before;
            self.v_ahead = kept_ahead;
            self.forces = old;
            return Ok(None);
        }
        if self.u.iter().any(|x| !x.is_finite()) {
            return Err(Error::Solve(format!(
                "the explicit solution blew up by t = {t:e} (step {h:e}, stable {:e})",
                self.stable
            )));
        }
        // The velocity half a step ahead, damping central: v(1 + ch/2) = v(1 − ch/2) + h F/m.
        let c = self.damping * 0.5 * h;
        let f = &self.forces;
        let behind = std::mem::take(&mut self.v_ahead);
        self.v_ahead = (0..np)
            .map(|i| {
                if i < nf {
                    let force = f.external[i] - f.internal[i] - f.contact[i];
                    (behind[i] * (1.0 - c) + h * force / self.mass[i]) / (1.0 + c)
                } else {
                    0.0
                }
            })
            .collect();
        let du: Vec<f64> = self.u.iter().zip(&before).map(|(a, b)| a - b).collect();
        let mut v: Vec<f64> = (0..np)
            .map(|i| 0.5 * (behind[i] + self.v_ahead[i]))
            .collect();
        let mut a: Vec<f64> = (0..np).map(|i| (self.v_ahead[i] - behind[i]) / h).collect();
        for i in nf..np {
            // A prescribed DOF's velocity over the step; its acceleration is not tracked.
            v[i] = du[i] / h;
            a[i] = 0.0;
        }
        // The damping's work on the velocity it acted with, v_{k−½}, over the step.
        self.forces.add_work(&old, &du, &mut self.energy);
        let damping: f64 = (0..nf)
            .map(|i| self.damping * self.mass[i] * behind[i] * behind[i] * h)
            .sum();
        self.energy.damping += damping;
        self.energy.kinetic = self.kinetic(&v);
        self.h = h;
        self.a_last.clone_from(&a);
        Ok(Some((
            v,
            a,
            committed.states,
            committed.ev.states.unwrap_or_default(),
        )))
    }

    /// The support forces at the prescribed DOFs: F_int + F_c − F_ext (the prescribed DOFs'
    /// inertia is not tracked in the explicit scheme).
    fn reactions(&self) -> Vec<f64> {
        let f = &self.forces;
        (self.dofs.n_free..self.u.len())
            .map(|p| f.internal[p] + f.contact[p] - f.external[p])
            .collect()
    }
}
