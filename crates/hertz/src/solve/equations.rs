//! The equations Newton solves: the bodies' internal forces and tangent (the assembler, on one
//! process or summed across ranks, with the step's [`StepTerms`]), the contact system, and the
//! linear solver of full tangents, with where the time goes.

use super::linear::LinearSolver;
use super::partition::Ranks;
use super::report::{Observer, Phase, PhaseTimes};
use super::terms::StepTerms;
use crate::assembly::{Assembler, Contribution, DofMap, Evaluation};
use crate::contact::{ContactSystem, Search, SlotLinearization, SlotState};
use crate::error::Result;
use crate::model::Model;
use std::time::Instant;

/// Seconds since `t`.
pub(super) fn since(t: Instant) -> f64 {
    t.elapsed().as_secs_f64()
}

/// A free equation by its node and DOF (for messages): a node's own, before a `SlaveNode` that
/// shares it.
pub(super) fn describe_eq(model: &Model, dofs: &DofMap, eq: usize) -> String {
    let owner = |slaves: bool| {
        dofs.node_dofs.iter().enumerate().find_map(|(n, list)| {
            (model.nodes[n].slave.is_some() == slaves)
                .then(|| list.iter().find(|(_, c)| *c == eq))
                .flatten()
                .map(|(d, _)| format!("node {} DOF {d}", model.nodes[n].label))
        })
    };
    owner(false)
        .or_else(|| owner(true))
        .unwrap_or_else(|| format!("multiplier equation {eq}"))
}

pub(super) struct Equations<'a> {
    pub asm: Assembler<'a>,
    pub contact: ContactSystem,
    pub dofs: &'a DofMap,
    /// The solver of full tangents (and of a model without contact).
    pub solver: Box<dyn LinearSolver>,
    /// Told of each phase, iteration and detail (see [`super::report`]).
    pub observer: &'a dyn Observer,
    /// Time spent in assembly, factorizations and solves since the step began.
    pub times: PhaseTimes,
    /// The processes the solver spans, when more than one: each assembles its share of the
    /// elements, and the first adds the contact's tangent.
    pub ranks: Option<Ranks>,
    /// No element uses large deformation and no material has a state: the bodies' tangent is
    /// constant.
    pub constant_structure: bool,
    /// The solver holds the factorization of a constant tangent (a linear problem's), valid
    /// for the iterations to come.
    pub factor_kept: bool,
    /// The bodies' tangent changed though the structure is constant (a time integrator's new
    /// step size, a failed attempt): the condensed contact step factorizes it afresh.
    pub structure_stale: bool,
}

impl<'a> Equations<'a> {
    pub fn model(&self) -> &'a Model {
        self.asm.model
    }

    /// The bodies' internal forces (and tangent, and K_fp·Δu_p) at `u` for a Newton system,
    /// with the `extra` contributions and the step's `terms`: on one process the whole
    /// model's, across processes each its share (the forces summed, the tangent a share for the
    /// solver to sum, see [`Ranks::assemble`]).
    pub fn evaluate(
        &mut self,
        u: &[f64],
        want_k: bool,
        dup: Option<&[f64]>,
        extra: &[Contribution],
        terms: &dyn StepTerms,
    ) -> Result<Evaluation> {
        let t = Instant::now();
        let mut ev = self.scaled(terms, |eq| match (eq.ranks, eq.solver.distributed()) {
            (Some(ranks), Some(d)) => ranks.assemble(&eq.asm, d, u, want_k, dup, extra),
            _ => eq.asm.evaluate(u, want_k, false, dup, extra),
        })?;
        self.add_terms(u, &mut ev, terms, self.ranks.is_none_or(|r| r.rank == 0));
        self.times.assembly += since(t);
        Ok(ev)
    }

    /// The tangent of the bodies alone at `u` (elements and `terms`, the whole model's): the
    /// structural factor of the condensed contact step.
    pub fn structure(&mut self, u: &[f64], terms: &dyn StepTerms) -> Result<Evaluation> {
        let t = Instant::now();
        let mut ev = self.scaled(terms, |eq| eq.asm.evaluate(u, true, false, None, &[]))?;
        self.add_terms(u, &mut ev, terms, true);
        self.times.assembly += since(t);
        Ok(ev)
    }

    /// `assemble` with the elements' forces and tangent taken (1 + s) times, s the `terms`'
    /// stiffness-proportional damping ([`StepTerms::element_scale`]); other evaluations (the
    /// committed state's) see them as they are.
    fn scaled<T>(&mut self, terms: &dyn StepTerms, assemble: impl FnOnce(&Self) -> T) -> T {
        self.asm.set_element_scale(1.0 + terms.element_scale());
        let out = assemble(self);
        self.asm.set_element_scale(1.0);
        out
    }

    /// The step's terms into an evaluation whose forces are the whole model's (on every
    /// process: across processes they are summed before), and their tangent where `tangent`
    /// (across processes into the first one's share only, the solver summing the shares; into
    /// every process's whole structural tangent). Adding the forces on the first process
    /// alone left the others' residual without the inertia: they took other decisions in a
    /// dynamic step and the job ended in a crash.
    fn add_terms(&self, u: &[f64], ev: &mut Evaluation, terms: &dyn StepTerms, tangent: bool) {
        terms.add_forces(u, &mut ev.f_int);
        terms.add_force_norms(u, self.dofs, &mut ev.ebe);
        if let (true, Some(k)) = (tangent, ev.k_values.as_mut()) {
            terms.add_tangent(u, &self.asm.pattern, k);
        }
    }

    /// Whether this process adds the contact's tangent to the one it gives the solver (across
    /// processes only the first does, the solver summing their shares).
    pub fn adds_contact_tangent(&self) -> bool {
        self.ranks.is_none_or(|r| r.rank == 0)
    }

    /// Factorize a full tangent (values on the assembler's pattern); `constant`: it is the
    /// tangent of a linear problem, kept for the iterations to come.
    pub fn factorize(&mut self, kv: &[f64], constant: bool) -> Result<()> {
        let (model, dofs) = (self.asm.model, self.dofs);
        let describe = |eq: usize| describe_eq(model, dofs, eq);
        self.observer.phase(&Phase::Factorization {
            kind: if self.asm.pattern.symmetric {
                "symmetric tangent"
            } else {
                "non-symmetric tangent"
            },
            unknowns: self.asm.pattern.n,
        });
        let t = Instant::now();
        self.solver
            .factorize(&self.asm.pattern, kv, constant, &describe)?;
        self.times.factor += since(t);
        self.factor_kept = constant;
        Ok(())
    }

    /// Solve with the last factorization, `x` the right-hand side and then the solution.
    pub fn solve(&mut self, x: &mut [f64]) -> Result<()> {
        let t = Instant::now();
        self.solver.solve_in_place(x)?;
        self.times.solve += since(t);
        Ok(())
    }

    /// Contact points and states at `u`, with the friction `history` (converged states and
    /// their primary state; the initial states for the first step).
    pub fn contact_at(
        &self,
        u: &[f64],
        search: Search,
        history: (&[SlotState], Option<&[f64]>),
    ) -> Result<(Vec<SlotLinearization>, Vec<SlotState>)> {
        let nodes = self.asm.nodal_state(u).with_start(history.1);
        self.contact
            .evaluate_with_history(&nodes, search, Some(history.0))
    }
}
