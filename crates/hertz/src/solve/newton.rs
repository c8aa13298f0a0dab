//! Newton–Raphson iterations of one (sub)step, with OOFEM's per-DOF-group convergence test
//! (spec §1.3, in [`super::convergence`]): evaluate the residual, test it, solve for the step,
//! report.
//!
//! Without contact: full or modified Newton as the input says (`manrmsteps`; unsaid, full Newton
//! where the bodies' tangent varies), the factorization of a linear problem reused. With contact
//! every iteration solves the full Newton system, its contact branches decided on the
//! linearized problem ([`super::contact_step`]), which keeps
//! Newton from cycling around the kink of the contact force. A driver adds its own terms to the
//! bodies' equations through [`StepTerms`] (a time integrator's inertia).
//!
//! Convergence of penalty contact is measured against the round-off floor of its forces: with
//! coordinates of size X a penalty force p·g is a staircase of steps ε·p·X, and once Newton
//! stops gaining on a residual within that floor, the step is as converged as double precision
//! allows (a warning then says the penalty is larger than double precision resolves).

use super::backtrack::Backtrack;
use super::branches::OnCycle;
use super::contact_step::{local_change, ContactStepper};
use super::convergence::{check, penalty_warning, precision_warning, Residual};
use super::equations::Equations;
use super::multipliers::MultiplierElimination;
use super::params::SolveParams;
use super::partition::Ranks;
use super::report::{IterationReport, Observer, Phase, PhaseTimes, StepInfo};
use super::terms::StepTerms;
use super::watch::Watch;
use crate::assembly::{Assembler, Contribution, DofMap, Evaluation, NodalState};
use crate::contact::{ContactSystem, Search, SlotLinearization, SlotState};
use crate::error::{Error, Result};
use crate::model::{Analysis, Model};

/// The state a cut-back restores (see [`NewtonContext::checkpoint`]).
pub(super) struct Checkpoint {
    contact: Option<Vec<SlotState>>,
    material: Option<Vec<f64>>,
}

/// The contact states the iterations start from: the friction history and the search's hints.
struct ContactHistory {
    /// The states of the last converged step (the first hint of the next step's search, and the
    /// friction history: restoring them restores it).
    converged: Option<Vec<SlotState>>,
    /// The states at u = 0: the friction history of the first step.
    initial: Vec<SlotState>,
    /// The friction history of the current (sub)step: the converged states it started from and
    /// their primary state (still the history when the converged state is evaluated again for
    /// output).
    friction: Option<(Vec<SlotState>, Vec<f64>)>,
}

impl ContactHistory {
    /// The search hint of the last converged state, or a fresh search.
    fn search(&self) -> Search<'_> {
        match &self.converged {
            Some(s) => Search::Hint(s),
            None => Search::Fresh,
        }
    }

    /// The friction history to evaluate with: states and their primary state.
    fn friction(&self) -> (&[SlotState], Option<&[f64]>) {
        match &self.friction {
            Some((states, start)) => (states, Some(start)),
            None => (&self.initial, None),
        }
    }
}

/// A model's contact system and DOF map (its multipliers numbered after the displacements),
/// told to `observer` as the set-up phase: what every driver starts from.
pub(super) fn set_up(model: &Model, observer: &dyn Observer) -> Result<(ContactSystem, DofMap)> {
    let contact = ContactSystem::new(model)?;
    let dofs = DofMap::new(model, &contact.extra_dofs())?;
    observer.phase(&Phase::SetUp {
        unknowns: dofs.n_free,
        steps: model.step_times().len(),
    });
    Ok((contact, dofs))
}

/// A converged state's evaluation ([`NewtonContext::commit_step`]).
pub struct Committed {
    /// The internal forces (elements and contact) and the material points' states.
    pub ev: Evaluation,
    /// The contact points' states.
    pub states: Vec<SlotState>,
    /// The contact's forces alone (primary numbering).
    pub contact: Vec<f64>,
    /// Σ_j |K_c,ij| of the contact's tangent over the free equations (explicit dynamics' stable
    /// time step).
    pub contact_row_sums: Vec<f64>,
}

/// The solver state of one analysis: the equations, how contact steps are solved, the contact
/// history and what the iterations showed.
pub(super) struct NewtonContext<'a> {
    eq: Equations<'a>,
    /// How a Newton step with contact is solved (None without contact).
    stepper: Option<ContactStepper>,
    /// The step being solved (for the reports).
    step: usize,
    history: ContactHistory,
    watch: Watch,
}

impl<'a> NewtonContext<'a> {
    /// The solver state of `model` with its DOF map `dofs` and contact `contact`: the assembler,
    /// the linear solver `params` choose, the contact's initial states. Returns the warnings
    /// about the starting contact (also told to `observer`).
    pub fn new(
        model: &'a Model,
        dofs: &'a DofMap,
        contact: ContactSystem,
        params: &SolveParams,
        observer: &'a dyn Observer,
    ) -> Result<(NewtonContext<'a>, Vec<String>)> {
        let mut asm = Assembler::new(model, dofs)?;
        // A follower load's tangent is not symmetric.
        asm.set_symmetric(!model.has_follower_loads());
        let zero = vec![0.0; dofs.n_primary()];
        let initial = contact
            .evaluate(&NodalState::new(model, dofs, &zero), Search::Fresh)?
            .1;
        let initial_warnings = crate::contact::initial_warnings(model, &initial);
        for w in &initial_warnings {
            observer.warning(w);
        }
        let slot_nodes: Vec<usize> = initial.iter().map(|s| s.node).collect();
        let (mut solver, make_solver) = params.solvers(&dofs.free_eq_nodes());
        let modes = super::linear::rigid_body_modes(model, dofs);
        solver.set_near_null_space(&modes);
        solver.set_multipliers(dofs.n_lambda);
        let ranks = solver
            .distributed()
            .map(|d| Ranks {
                rank: d.rank(),
                size: d.size(),
            })
            .filter(|r| r.size > 1);
        if let Some(r) = ranks {
            let part = super::partition::elements(model, r.size)?;
            let share: Vec<bool> = part.iter().map(|&p| p == r.rank).collect();
            let mine = share.iter().filter(|&&s| s).count();
            observer.detail(&format!(
                "rank {} assembles {mine} of {} elements (METIS, {} parts)",
                r.rank,
                share.len(),
                r.size
            ));
            asm.set_share(share);
        }
        // Contact steps condensed on the contact equations where the solver offers the Schur
        // block and the caller allows it; else full tangents from the start.
        let condense = params.condensed_contact && solver.capabilities().schur_block;
        let stepper = if contact.is_empty() {
            None
        } else {
            let candidates = if condense {
                Some(contact.candidate_equations(&NodalState::new(model, dofs, &zero))?)
            } else {
                None
            };
            // A body held by contact alone: its structural tangent is singular in statics (in
            // dynamics its inertia holds it).
            let held = model.analysis.dynamics.is_none()
                && crate::assembly::rigid::free_rigid_motions(model, dofs) > 0;
            Some(ContactStepper::new(
                candidates,
                held,
                params
                    .max_condensed
                    .unwrap_or_else(|| super::condensed::default_limit(dofs.n_free)),
                make_solver,
                MultiplierElimination::with_solver(params.reduced_solver(), modes),
                params.krylov_min_unknowns,
                slot_nodes.clone(),
            ))
        };
        let constant_structure = asm.constant_stiffness();
        let mut ctx = NewtonContext {
            eq: Equations {
                asm,
                contact,
                dofs,
                solver,
                observer,
                times: PhaseTimes::default(),
                ranks,
                constant_structure,
                factor_kept: false,
                structure_stale: false,
            },
            stepper,
            step: 0,
            history: ContactHistory {
                converged: None,
                initial,
                friction: None,
            },
            watch: Watch {
                flips: vec![0; slot_nodes.len()],
                slot_nodes,
                floor_dominated: None,
                floor_warned: false,
                arealess_warned: false,
            },
        };
        if let Some(s) = ctx.stepper.as_mut().filter(|s| s.full_tangents()) {
            s.condense_off(&mut ctx.eq);
        }
        Ok((ctx, initial_warnings))
    }

    /// Fill a converged step's `info` with what the solvers did: the multipliers eliminated,
    /// the linear solver's statistics and the phase times; and, the first time its `contact`
    /// states show them, warn of active contact nodes that stand for no area.
    pub fn finish_step_info(&mut self, info: &mut StepInfo, contact: &[SlotState]) {
        if !self.watch.arealess_warned {
            if let Some(w) = crate::contact::pressure_warning(self.eq.model(), contact) {
                self.eq.observer.warning(&w);
                info.warnings.push(w);
                self.watch.arealess_warned = true;
            }
        }
        match self.stepper.as_ref().and_then(|s| s.elimination()) {
            Some((counts, stats)) => {
                info.multipliers_eliminated = counts;
                info.solver = stats;
            }
            None => info.solver = self.eq.solver.stats().clone(),
        }
        let (searching, contact) = self.eq.contact.take_times();
        info.times = PhaseTimes {
            search: searching,
            contact: contact - searching,
            ..self.eq.times
        };
    }

    /// Begin load step `step`: its phase times start from zero.
    pub fn begin_step(&mut self, step: usize) {
        self.eq.times = PhaseTimes::default();
        self.eq.contact.take_times();
        self.step = step;
    }

    pub fn model(&self) -> &'a Model {
        self.eq.model()
    }

    pub fn dofs(&self) -> &'a DofMap {
        self.eq.dofs
    }

    pub fn observer(&self) -> &'a dyn Observer {
        self.eq.observer
    }

    /// What a cut-back restarts from: the converged contact states (the friction history) and
    /// the materials' committed state.
    pub fn checkpoint(&self) -> Checkpoint {
        let asm = &self.eq.asm;
        Checkpoint {
            contact: self.history.converged.clone(),
            material: asm
                .has_material_state()
                .then(|| asm.material_state().to_vec()),
        }
    }

    /// Go back to `checkpoint` (the start of an attempt at a step).
    pub fn rollback(&mut self, checkpoint: &Checkpoint) {
        self.history.converged.clone_from(&checkpoint.contact);
        if let Some(m) = &checkpoint.material {
            self.eq.asm.restore_material_state(m);
        }
    }

    /// An attempt at a step failed: factorize afresh in the next.
    pub fn attempt_failed(&mut self) {
        self.eq.factor_kept = false;
        self.eq.structure_stale = true;
    }

    /// The elements' tangent at `u` times `x` over every primary equation (the rate of their
    /// forces along the motion x).
    pub fn tangent_product(&self, u: &[f64], x: &[f64]) -> Result<Vec<f64>> {
        self.eq.asm.tangent_product(u, x)
    }

    /// A substep converged at `u`: commit the materials' state.
    pub fn commit_substep(&mut self, u: &[f64]) -> Result<()> {
        if self.eq.asm.has_material_state() {
            self.eq.asm.commit_material_state(u)?;
        }
        Ok(())
    }

    /// The load step converged at `u`: its contact states become the next step's history and
    /// search hint. Returns the evaluation for output (its forces the elements' and the
    /// contact's), the contact states and the contact's own forces and stiffness.
    pub fn commit_step(&mut self, u: &[f64]) -> Result<Committed> {
        let (points, states) =
            self.eq
                .contact_at(u, self.history.search(), self.history.friction())?;
        let contribs: Vec<Contribution> = points.iter().map(|p| p.contribution()).collect();
        let t = std::time::Instant::now();
        let ev = self.eq.asm.evaluate(u, false, true, None, &contribs)?;
        let mut contact = vec![0.0; u.len()];
        self.eq.asm.add_residuals(&mut contact, &contribs);
        let dofs = self.eq.dofs;
        let mut contact_row_sums = vec![0.0; dofs.n_free];
        for c in contribs.iter().filter(|c| !c.ke.is_empty()) {
            let nd = c.codes.len();
            for (a, &ca) in c.codes.iter().enumerate() {
                for (p, wp) in dofs.entries(ca).filter(|&(p, _)| p < dofs.n_free) {
                    for (b, &cb) in c.codes.iter().enumerate() {
                        for (_, wq) in dofs.entries(cb) {
                            contact_row_sums[p] += (wp * wq * c.ke[a * nd + b]).abs();
                        }
                    }
                }
            }
        }
        self.eq.times.assembly += super::equations::since(t);
        self.history.converged = Some(states.clone());
        Ok(Committed {
            ev,
            states,
            contact,
            contact_row_sums,
        })
    }

    /// Why a failed step may be the material's (see [`super::softening`]), at the state `u`.
    pub fn softening_hint(&self, u: &[f64]) -> Option<String> {
        super::softening::softening_hint(self.eq.model(), &self.eq.asm, u)
    }

    /// The report of iteration `it`: its residual, and the contact nodes that closed, opened or
    /// changed between stick and slip since the previous iteration's `prev`.
    fn iteration_report(
        &self,
        it: usize,
        residual: f64,
        states: &[SlotState],
        prev: Option<&[SlotState]>,
    ) -> IterationReport {
        let label = |s: &SlotState| self.eq.model().nodes[s.node].label;
        let mut r = IterationReport {
            step: self.step,
            iteration: it,
            residual,
            contact_points: states.len(),
            closed: states.iter().filter(|s| s.active).count(),
            ..Default::default()
        };
        let slips = |s: &SlotState| s.friction.map(|(stick, _)| !stick);
        if states.iter().any(|s| s.friction.is_some()) {
            r.slipping = Some(states.iter().filter(|s| slips(s) == Some(true)).count());
        }
        if let Some(p) = prev.filter(|p| p.len() == states.len()) {
            for (s, q) in states.iter().zip(p) {
                if s.active != q.active {
                    if s.active {
                        r.closed_nodes.push(label(s));
                    } else {
                        r.opened_nodes.push(label(s));
                    }
                }
                if slips(s).is_some() && slips(q).is_some() && slips(s) != slips(q) {
                    r.switched_nodes.push(label(s));
                }
            }
        }
        r
    }

    /// Newton iterations towards external forces `f_ext` and prescribed values `up`, with the
    /// driver's `terms` added to the bodies' equations. Ok(false) = no convergence within
    /// maxiter.
    pub fn newton(
        &mut self,
        u: &mut [f64],
        (f_ext, up): (&[f64], &[f64]),
        a: &Analysis,
        info: &mut StepInfo,
        terms: &dyn StepTerms,
    ) -> Result<bool> {
        let nf = self.eq.dofs.n_free;
        if self.eq.contact.has_friction() {
            self.history.friction = self
                .history
                .converged
                .clone()
                .map(|states| (states, u.to_vec()));
        }
        if nf == 0 {
            u[nf..].copy_from_slice(up);
            return Ok(true);
        }
        self.watch.flips.fill(0);
        self.watch.floor_dominated = None;
        let dup: Vec<f64> = (0..up.len()).map(|i| up[i] - u[nf + i]).collect();
        let predict = a.predictor(self.eq.constant_structure && terms.constant_tangent());
        if predict && dup.iter().any(|&d| d != 0.0) {
            self.predict(u, &dup, terms)?;
        }
        u[nf..].copy_from_slice(up);
        let mut du = vec![0.0; nf];
        let mut prev: Option<Vec<SlotState>> = self.history.converged.clone();
        let mut prev2: Option<Vec<SlotState>> = None;
        // Per penalty point closed in the last Newton step: the force of the step's linear model,
        // which the next step's geometric tangent part takes (see `SlotLinearization::hold_force`).
        let mut held: Vec<Option<f64>> = Vec::new();
        let mut last_cycled = false;
        let mut backtrack = self.eq.asm.has_material_state().then(Backtrack::default);
        for it in 0..=a.maxiter {
            if self.eq.observer.interrupted() {
                return Err(Error::Interrupted);
            }
            let search = match &prev {
                Some(p) => Search::Hint(p),
                None => Search::Fresh,
            };
            let (points, states) = self.eq.contact_at(u, search, self.history.friction())?;
            if let (Some(p), Some(pp)) = (&prev, &prev2) {
                self.watch.count_flips(&states, p, pp);
            }
            let (ev, want_k) = self.residual_at(u, it, &points, a, terms)?;
            let rhs: Vec<f64> = (0..nf).map(|i| f_ext[i] - ev.f_int[i]).collect();
            let last = info.residual_history.last().copied();
            let residual = Residual {
                rhs: &rhs,
                f_ext,
                ebe: &ev.ebe,
                du: &du,
                u,
            };
            let mut check = check(self.eq.model(), self.eq.dofs, &residual, a, it, &points);
            check.accept_on_floor(it, last);
            info.residual_history.push(check.worst);
            info.iterations += 1;
            self.eq.observer.iteration(&self.iteration_report(
                it,
                check.worst,
                &states,
                prev.as_deref(),
            ));
            if check.converged && (it > 0 || check.worst == 0.0) {
                // Equilibrium with a node across its master is no solution (a smaller step is).
                if let Some(why) = crate::contact::crossing_message(self.eq.model(), &states) {
                    return Err(Error::Solve(why));
                }
                let floor = check.floor_ratio.map(|r| (r, check.penalty_floor));
                let linear = self.eq.constant_structure && terms.constant_tangent();
                self.accept(it, (&ev, linear), floor, states, a, info)?;
                return Ok(true);
            }
            if !check.worst.is_finite() {
                return Err(Error::Solve("residual is not finite".into()));
            }
            let halved = |b: &mut Backtrack| b.halves(&rhs, &mut u[..nf], &mut du);
            if it > 1 && it < a.maxiter && backtrack.as_mut().is_some_and(halved) {
                continue;
            }
            if it == a.maxiter {
                self.watch.floor_dominated =
                    (check.floor_excess > 1.0).then_some(check.floor_excess);
                break;
            }
            // Semismooth Newton on Coulomb friction can cycle: closed nodes' stick or slip back
            // to what it was two iterates before, the residual up and down. From such a cycle
            // on, the steps are backtracked as a yielding material's are: a die pressed onto a
            // block in one step cycled between two stick/slip states for 30 iterations and
            // needed 4 substeps (81 iterations); with this, 8. Not from the start, nor on
            // nodes opening and closing: the 2D ironing example's onset of sliding then failed.
            if backtrack.is_none() && self.eq.contact.has_friction() {
                if let (Some(p), Some(pp)) = (&prev, &prev2) {
                    if super::watch::stick_slip_cycles(&states, p, pp) {
                        backtrack = Some(Backtrack::default());
                    }
                }
            }
            let start = backtrack.is_some().then(|| rhs.clone());
            let step = match self.stepper.is_some() {
                true => {
                    // A cycled search whose step did not lower the residual takes the earliest
                    // of its equal guesses next time.
                    let h = &info.residual_history;
                    let stalled =
                        last_cycled && h.len() >= 2 && check.worst >= 0.99 * h[h.len() - 2];
                    let ks = want_k.then_some(&ev);
                    let s = self.contact_step(u, rhs, points, ks, &mut held, stalled, terms)?;
                    last_cycled = s.cycled;
                    s.du
                }
                false => self.structural_step(rhs, want_k.then_some(&ev), terms)?,
            };
            for i in 0..nf {
                u[i] += step[i];
            }
            if let (Some(b), Some(r)) = (backtrack.as_mut(), &start) {
                b.start(r, &step);
            }
            du = step;
            prev2 = prev.replace(states);
        }
        Ok(false)
    }

    /// The internal forces at `u` in iteration `it` (with the `points`' residuals where there
    /// is contact) and whether the evaluation holds a tangent the step needs: the structural
    /// tangent where the condensed contact step needs it fresh (the full-tangent path evaluates
    /// its own), without contact the tangent of full or modified Newton.
    fn residual_at(
        &mut self,
        u: &[f64],
        it: usize,
        points: &[SlotLinearization],
        a: &Analysis,
        terms: &dyn StepTerms,
    ) -> Result<(Evaluation, bool)> {
        let constant = self.eq.constant_structure && !self.eq.structure_stale;
        let want_k = match &self.stepper {
            Some(s) => s.needs_structure(constant),
            None => {
                let kept = self.eq.factor_kept && terms.constant_tangent();
                // OOFEM keeps the step's first tangent where `manrmsteps` is absent (modified
                // Newton). Where the tangent changes within the step (large deformation, a
                // material that yields) modified Newton converges linearly at best (a plastic
                // patch: 50 iterations without converging, against 4 with full Newton; a
                // corrugated strip compressed in large deformation: 70-80 iterations and 4
                // substeps a step, 20-35 and 2 with full Newton, 3 and none with full Newton
                // and the predictor, `Analysis::predictor`): hertz takes full Newton there
                // unless `manrmsteps` says otherwise. A constant tangent is factorized once
                // either way.
                let every = a.manrmsteps.or((!self.eq.constant_structure).then_some(1));
                !kept && (it == 0 || every.is_some_and(|k| it.is_multiple_of(k)))
            }
        };
        let contribs: Vec<Contribution> = points.iter().map(|p| p.contribution()).collect();
        self.eq.observer.phase(&super::report::Phase::Assembly);
        let has_contact = self.stepper.is_some();
        let mut ev = self.eq.evaluate(
            u,
            want_k,
            None,
            if has_contact { &[] } else { &contribs },
            terms,
        )?;
        if has_contact {
            let t = std::time::Instant::now();
            self.eq.asm.add_residuals(&mut ev.f_int, &contribs);
            self.eq.times.assembly += super::equations::since(t);
            if want_k {
                // The condensed step factorizes this tangent.
                self.eq.structure_stale = false;
            }
        }
        Ok((ev, want_k))
    }

    /// The Newton step of a model without contact for the residual `rhs`, factorizing the
    /// tangent of `ev` if given (else the last factorization is reused).
    fn structural_step(
        &mut self,
        rhs: Vec<f64>,
        ev: Option<&Evaluation>,
        terms: &dyn StepTerms,
    ) -> Result<Vec<f64>> {
        if let Some(ev) = ev {
            let linear = self.eq.constant_structure && terms.constant_tangent();
            self.eq
                .factorize(ev.k_values.as_ref().expect("requested"), linear)?;
        }
        let mut x = rhs;
        self.eq.solve(&mut x)?;
        Ok(x)
    }

    /// A converged iterate: a model whose first iterate is converged is factorized once all the
    /// same (an unloaded mechanism must not pass; `linear`: its tangent is kept), a round-off floor (its residual over the
    /// tolerance, and whether the penalty's round-off makes it) is warned of once, the contact
    /// states are kept.
    fn accept(
        &mut self,
        it: usize,
        (ev, linear): (&Evaluation, bool),
        floor: Option<(f64, bool)>,
        states: Vec<SlotState>,
        a: &Analysis,
        info: &mut StepInfo,
    ) -> Result<()> {
        let has_contact = self.stepper.is_some();
        if let (0, false, false, Some(kv)) =
            (it, has_contact, self.eq.factor_kept, ev.k_values.as_ref())
        {
            self.eq.factorize(kv, linear)?;
        }
        if let Some((r, penalty)) = floor.filter(|_| !self.watch.floor_warned) {
            let w = if penalty {
                penalty_warning(&self.eq.contact.penalties(), r, a.rtolf)
            } else {
                precision_warning(r, a.rtolf)
            };
            self.eq.observer.warning(&w);
            info.warnings.push(w);
            self.watch.floor_warned = true;
        }
        if has_contact {
            self.history.converged = Some(states);
        }
        info.iterations -= 1;
        Ok(())
    }

    /// The Newton step of a model with contact: the branches searched on the linearized problem
    /// from the first guess, penalty points' geometric parts taken with the forces `held` from
    /// the last step's linear model (updated here for the next step), the earliest of equal
    /// guesses taken after a `stalled` cycle.
    #[allow(clippy::too_many_arguments)]
    fn contact_step(
        &mut self,
        u: &[f64],
        rhs: Vec<f64>,
        mut points: Vec<SlotLinearization>,
        ks: Option<&Evaluation>,
        held: &mut Vec<Option<f64>>,
        stalled: bool,
        terms: &dyn StepTerms,
    ) -> Result<super::branches::ContactStep> {
        let before = self.history.converged.as_deref().unwrap_or(&[]);
        let guess = ContactStepper::branch_guess(&points, before);
        for (p, h) in points.iter_mut().zip(held.iter()) {
            if let Some(force) = *h {
                p.hold_force(force);
            }
        }
        let cycle = if stalled {
            OnCycle::FewestMissesEarliest
        } else {
            OnCycle::FewestMisses
        };
        let stepper = self.stepper.as_mut().expect("a contact problem");
        let s = stepper.solve(&mut self.eq, u, rhs, &points, &guess, ks, cycle, terms)?;
        let dofs = self.eq.dofs;
        *held = points
            .iter()
            .zip(&s.closed)
            .map(|(p, b)| {
                b.closed
                    .then(|| p.held_force(&local_change(dofs, p, &s.du)))
                    .flatten()
            })
            .collect();
        if s.updates > 0 {
            let back = if s.cycled {
                " and came back to a guess"
            } else {
                ""
            };
            self.eq.observer.detail(&format!(
                "contact branches updated {} times on the linearized problem{back}",
                s.updates
            ));
        }
        Ok(s)
    }

    /// Tangent predictor for prescribed increments `dup`: K Δu_f = −K_fp Δu_p at the current state.
    ///
    /// The elements' part is linearized; the contact is evaluated at the prescribed values
    /// already moved (a rigid indenter's reference node, or driven nodes of either body), so
    /// the step's branch search sees the gaps the move makes. Linearizing the contact's part
    /// too (−K_fp Δu_p of its closed branches) left the search blind to it: the free nodes'
    /// linear gaps, without the indenter's move, predicted the pressed nodes open, and the
    /// step kept the closed branches' push without their stiffness.
    fn predict(&mut self, u: &mut [f64], dup: &[f64], terms: &dyn StepTerms) -> Result<()> {
        let nf = self.eq.dofs.n_free;
        let kept = self.eq.factor_kept && terms.constant_tangent();
        let need_k = !kept && self.stepper.is_none();
        let ev = self.eq.evaluate(u, need_k, Some(dup), &[], terms)?;
        let mut rhs: Vec<f64> = ev
            .k_fp_dup
            .as_ref()
            .expect("requested")
            .iter()
            .map(|v| -v)
            .collect();
        let mut moved = u.to_vec();
        for (i, d) in dup.iter().enumerate() {
            moved[nf + i] += d;
        }
        let step = match self.stepper.is_some() {
            true => self.predict_contact(u, &moved, &mut rhs, terms)?,
            false => {
                if need_k {
                    let linear = self.eq.constant_structure && terms.constant_tangent();
                    self.eq
                        .factorize(ev.k_values.as_ref().expect("requested"), linear)?;
                }
                let mut x = rhs;
                self.eq.solver.solve_in_place(&mut x)?;
                x
            }
        };
        for i in 0..nf {
            u[i] += step[i];
        }
        Ok(())
    }

    /// The predictor's step with contact: the contact's change of residual from the move to
    /// `moved` (−(f_c(moved) − f_c(u))) into `rhs`, and the branches searched from the points
    /// at `moved` (the last guess's step where the search cycles).
    fn predict_contact(
        &mut self,
        u: &[f64],
        moved: &[f64],
        rhs: &mut [f64],
        terms: &dyn StepTerms,
    ) -> Result<Vec<f64>> {
        let nf = self.eq.dofs.n_free;
        let search = self.history.search();
        let friction = self.history.friction();
        let (before, _) = self.eq.contact_at(u, search, friction)?;
        let (after, _) = self.eq.contact_at(moved, search, friction)?;
        let residuals = |ps: &[SlotLinearization]| {
            let contribs: Vec<Contribution> = ps.iter().map(|p| p.contribution()).collect();
            let mut f = vec![0.0; self.eq.dofs.n_primary()];
            self.eq.asm.add_residuals(&mut f, &contribs);
            f
        };
        let (change, old) = (residuals(&after), residuals(&before));
        for i in 0..nf {
            rhs[i] -= change[i] - old[i];
        }
        // The structural tangent of the condensed solve is the element part only.
        let stepper = self.stepper.as_mut().expect("a contact problem");
        let constant = self.eq.constant_structure && !self.eq.structure_stale;
        let ks = match stepper.needs_structure(constant) {
            true => {
                self.eq.structure_stale = false;
                Some(self.eq.structure(u, terms)?)
            }
            false => None,
        };
        let before = self.history.converged.as_deref().unwrap_or(&[]);
        let guess = ContactStepper::branch_guess(&after, before);
        let step = stepper.solve(
            &mut self.eq,
            u,
            rhs.to_vec(),
            &after,
            &guess,
            ks.as_ref(),
            OnCycle::Last,
            terms,
        )?;
        Ok(step.du)
    }

    /// Σ_j |K_ij| over the free equations of the bodies' tangent at `u` (no contact): with a
    /// diagonal mass m, max_i of it over m_i bounds the squared highest frequency (the matrix
    /// ∞-norm bounds the spectral radius of M⁻¹K).
    pub fn tangent_row_sums(&mut self, u: &[f64]) -> Result<Vec<f64>> {
        let ev = self.eq.structure(u, &super::terms::Statics)?;
        let k = ev.k_values.expect("a tangent was asked for");
        Ok(self.eq.asm.pattern.abs_row_sums(&k))
    }

    /// Each contact node's penalty from the mesh as `stiffness[node]` where its condition gives
    /// none (see [`crate::contact::ContactSystem::set_mesh_penalties`]).
    pub fn set_mesh_penalties(&mut self, stiffness: &[f64]) {
        self.eq.contact.set_mesh_penalties(stiffness);
    }

    /// Why the last attempt did not converge, in words, if something specific shows.
    pub fn diagnosis(&self) -> Option<String> {
        let mut why = Vec::new();
        if let Some(r) = self.watch.floor_dominated {
            why.push(format!(
                "the round-off of the penalty forces is {r:.1e} times the tolerance: the penalty \
                 is beyond what double precision resolves"
            ));
        }
        why.extend(self.watch.chatter(self.eq.model()));
        (!why.is_empty()).then(|| why.join("; "))
    }
}
