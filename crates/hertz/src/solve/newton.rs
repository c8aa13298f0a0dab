//! Newton–Raphson iterations of one (sub)step, with OOFEM's per-DOF-group convergence test
//! (spec §1.3, in [`super::convergence`]).
//!
//! Without contact: full or modified Newton as the input says (`manrmsteps`), the factorization of
//! a linear problem reused. With contact, hertz chooses: every iteration solves the full Newton
//! system, condensed on the contact equations when it can (see [`super::condensed`]): there the
//! branch of every contact point (closed or open) is decided on the linearized problem, which
//! keeps Newton from cycling around the kink of the contact force. Otherwise the full tangent of
//! the current state is factorized.
//!
//! Convergence of penalty contact is measured against the round-off floor of its forces: with
//! coordinates of size X a penalty force p·g is a staircase of steps ε·p·X, and once Newton
//! stops gaining on a residual within that floor, the step is as converged as double precision
//! allows (a warning then says the penalty is larger than double precision resolves).

use super::branches::{BranchSearch, ContactStep, OnCycle};
use super::condensed::{nearest_equations, CondensedContact};
use super::convergence::{check, penalty_warning, precision_warning, Residual};
use super::linear::{DenseLu, FaerSolver, LinearSolver, SolverSettings};
use super::multipliers::{Group, MultiplierElimination};
use super::report::{IterationReport, Observer, Phase};
use super::stepping::{PhaseTimes, SolveParams, SolverChoice, StepInfo};
use crate::assembly::{Assembler, Contribution, DofMap, Evaluation, NodalState, Pattern};
use crate::contact::point::Branch;
use crate::contact::{ContactPoint, ContactSystem, PointLaw, Search, SlotState};
use crate::error::{Error, Result};
use crate::model::{Analysis, Model};
use std::time::Instant;

/// How Newton systems with contact are solved.
pub(super) enum Condensed {
    /// Not applicable (no contact, too many candidates, an indefinite structural tangent).
    Off,
    /// To be set up at the first solve, with the candidate displacement equations.
    Pending(Vec<usize>),
    /// To be set up again with these equations (displacements and multipliers): the nearest
    /// points' grown by those that reached beyond them.
    Near(Vec<usize>),
    Ready(Box<CondensedContact>),
}

/// How often the condensed solve is set up again when contact reaches beyond its candidates
/// (each time a symbolic analysis and a factorization), before full tangents take over.
const MAX_REGROWTHS: usize = 4;

/// Largest number of branch updates of a step solved with full tangents (each a factorization).
const MAX_FULL_UPDATES: usize = 8;

/// The relative residual of an iterative solver's solves of branch guesses with full tangents
/// (only the branches are predicted from them; the last guess is solved again to the solver's
/// own tolerance).
const GUESS_TOL: f64 = 1e-4;

/// The state a cut-back restores (see [`NewtonContext::checkpoint`]).
pub(super) struct Checkpoint {
    contact: Option<Vec<SlotState>>,
    material: Option<Vec<f64>>,
}

pub(super) struct NewtonContext<'a> {
    asm: Assembler<'a>,
    contact: ContactSystem,
    dofs: &'a DofMap,
    solver: Box<dyn LinearSolver>,
    /// The node of every free equation (the condensed solve's ordering groups them).
    groups: Option<Vec<usize>>,
    /// Unknowns from which non-symmetric tangents go to GMRES.
    krylov_min: usize,
    /// The solver may be iterative (one from outside): branch guesses are solved loosely.
    loose_guesses: bool,
    /// The current factorization is the (constant) tangent of a linear problem.
    factor_valid: bool,
    /// Small strain and no contact: the tangent is constant.
    linear: bool,
    /// No element uses large deformation: the structural tangent is constant.
    small_strain: bool,
    /// Told of each phase, iteration and detail (see [`super::report`]).
    observer: &'a dyn Observer,
    /// The step being solved (for the reports).
    step: usize,
    condensed: Condensed,
    /// Contact states of the last converged step (the first hint of the next step's search,
    /// and the friction history: restoring them restores it).
    converged_states: Option<Vec<SlotState>>,
    /// Contact states at u = 0: the friction history of the first step.
    initial_states: Vec<SlotState>,
    /// The friction history of the current (sub)step: the converged states it started from and
    /// their primary state (still the history when the converged state is evaluated again for
    /// output).
    history: Option<(Vec<SlotState>, Vec<f64>)>,
    /// Per contact node: how often in the current attempt its partner and branch went back to
    /// what they were two iterations before (A → B → A: chattering, not sliding on).
    flips: Vec<usize>,
    /// How far the estimated round-off floor of penalty forces exceeded the tolerance in the last
    /// iteration of a failed attempt, if it did.
    floor_dominated: Option<f64>,
    /// The node of every contact point (for messages).
    slot_nodes: Vec<usize>,
    /// The round-off floor warning was given (once per analysis).
    floor_warned: bool,
    /// Time spent in assembly, factorizations and solves since the step began.
    times: PhaseTimes,
    /// How often the condensed solve was set up again with more candidates.
    regrowths: usize,
    /// The most equations the condensed step holds densely (`SolveParams::max_condensed`).
    max_condensed: usize,
    /// The full tangent's solve with the multipliers eliminated (see [`super::multipliers`]).
    eliminate: MultiplierElimination,
    /// The solver spans processes: (this process's rank, their number). Each process then
    /// assembles its share of the elements, and the first adds the contact's tangent.
    ranks: Option<(usize, usize)>,
}

/// Seconds since `t`.
fn since(t: Instant) -> f64 {
    t.elapsed().as_secs_f64()
}

/// A free equation by its node and DOF (for messages): a node's own, before a `SlaveNode`
/// that shares it.
fn describe_eq(model: &crate::model::Model, dofs: &DofMap, eq: usize) -> String {
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
        let np = dofs.n_primary();
        let small_strain = model.constant_element_stiffness();
        let linear = small_strain && contact.is_empty();
        let zero = vec![0.0; np];
        // Contact: Newton systems condensed on the contact equations (see `condensed`), unless
        // the solver comes from outside: it offers no trailing factor block, so full tangents.
        let condense =
            params.condensed_contact && !matches!(params.solver, SolverChoice::Custom(_));
        let condensed = if contact.is_empty() || !condense {
            Condensed::Off
        } else {
            Condensed::Pending(contact.candidate_equations(&NodalState::new(model, dofs, &zero))?)
        };
        let initial_states = contact
            .evaluate(&NodalState::new(model, dofs, &zero), Search::Fresh)?
            .1;
        let initial_warnings = crate::contact::initial_warnings(model, &initial_states);
        for w in &initial_warnings {
            observer.warning(w);
        }
        let slot_nodes: Vec<usize> = initial_states.iter().map(|s| s.node).collect();
        let groups = Some(dofs.free_eq_nodes());
        let mut eliminate = MultiplierElimination::new(params.krylov_min_unknowns);
        let solver: Box<dyn LinearSolver> = match &params.solver {
            SolverChoice::Sparse => Box::new(FaerSolver::new(SolverSettings {
                groups: groups.clone(),
                krylov_min: params.krylov_min_unknowns,
                ..Default::default()
            })),
            SolverChoice::Dense => Box::new(DenseLu::default()),
            SolverChoice::Custom(make) => {
                let modes = super::linear::rigid_body_modes(model, dofs);
                let mut solver = (make.0)();
                solver.set_near_null_space(&modes);
                solver.set_multipliers(dofs.n_lambda);
                // The reduced systems of eliminated multipliers go to a solver of the same
                // kind, positive definite where the bodies are held (CG with a multigrid);
                // across processes each reduces the whole tangent and gives it whole.
                if !contact.is_empty() {
                    let mut reduced = (make.0)();
                    reduced.take_whole_matrices();
                    eliminate = MultiplierElimination::with_solver(reduced, true, modes);
                }
                solver
            }
        };
        let ranks = solver
            .distributed()
            .map(|d| (d.rank(), d.size()))
            .filter(|&(_, size)| size > 1);
        if let Some((rank, size)) = ranks {
            let part = super::partition::elements(model, size)?;
            let share: Vec<bool> = part.iter().map(|&p| p == rank).collect();
            let mine = share.iter().filter(|&&s| s).count();
            observer.detail(&format!(
                "rank {rank} assembles {mine} of {} elements (METIS, {size} parts)",
                share.len()
            ));
            asm.set_share(share);
        }
        let mut ctx = NewtonContext {
            asm,
            contact,
            dofs,
            solver,
            groups,
            krylov_min: params.krylov_min_unknowns,
            loose_guesses: matches!(params.solver, SolverChoice::Custom(_)),
            factor_valid: false,
            linear,
            small_strain,
            observer,
            step: 0,
            condensed,
            converged_states: None,
            initial_states,
            history: None,
            flips: vec![0; slot_nodes.len()],
            floor_dominated: None,
            slot_nodes,
            floor_warned: false,
            times: PhaseTimes::default(),
            regrowths: 0,
            max_condensed: params
                .max_condensed
                .unwrap_or_else(|| super::condensed::default_limit(dofs.n_free)),
            eliminate,
            ranks,
        };
        if !ctx.contact.is_empty() && !condense {
            ctx.condense_off();
        }
        Ok((ctx, initial_warnings))
    }

    /// Fill a converged step's `info` with what the solvers did: the multipliers eliminated,
    /// the linear solver's statistics and the phase times.
    pub fn finish_step_info(&mut self, info: &mut StepInfo) {
        info.multipliers_eliminated = (self.eliminate.eliminated, self.eliminate.kept);
        info.solver = if self.eliminate.eliminated + self.eliminate.kept > 0 {
            self.eliminate.stats()
        } else {
            self.solver.stats().clone()
        };
        let (searching, contact) = self.contact.take_times();
        info.times = PhaseTimes {
            search: searching,
            contact: contact - searching,
            ..self.times
        };
    }

    /// Begin load step `step`: its phase times start from zero.
    pub fn begin_step(&mut self, step: usize) {
        self.times = PhaseTimes::default();
        self.contact.take_times();
        self.step = step;
    }

    pub fn model(&self) -> &'a Model {
        self.asm.model
    }

    pub fn dofs(&self) -> &'a DofMap {
        self.dofs
    }

    pub fn observer(&self) -> &'a dyn Observer {
        self.observer
    }

    /// What a cut-back restarts from: the converged contact states (the friction history) and
    /// the materials' committed state.
    pub fn checkpoint(&self) -> Checkpoint {
        Checkpoint {
            contact: self.converged_states.clone(),
            material: self
                .asm
                .has_material_state()
                .then(|| self.asm.material_state().to_vec()),
        }
    }

    /// Go back to `checkpoint` (the start of an attempt at a step).
    pub fn rollback(&mut self, checkpoint: &Checkpoint) {
        self.converged_states.clone_from(&checkpoint.contact);
        if let Some(m) = &checkpoint.material {
            self.asm.restore_material_state(m);
        }
    }

    /// An attempt at a step failed: factorize afresh in the next.
    pub fn attempt_failed(&mut self) {
        self.factor_valid = false;
    }

    /// A substep converged at `u`: commit the materials' state.
    pub fn commit_substep(&mut self, u: &[f64]) -> Result<()> {
        if self.asm.has_material_state() {
            self.asm.commit_material_state(u)?;
        }
        Ok(())
    }

    /// The load step converged at `u`: its contact states become the next step's history and
    /// search hint. Returns the evaluation for output and the contact states.
    pub fn commit_step(&mut self, u: &[f64]) -> Result<(Evaluation, Vec<SlotState>)> {
        let (ev, states) = self.evaluate_states(u)?;
        self.converged_states = Some(states.clone());
        Ok((ev, states))
    }

    /// Why a failed step may be the material's (see [`super::softening`]), at the state `u`.
    pub fn softening_hint(&self, u: &[f64]) -> Option<String> {
        super::softening::softening_hint(self.asm.model, &self.asm, u)
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
        let label = |s: &SlotState| self.asm.model.nodes[s.node].label;
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

    /// Contact points and states at `u`, with the friction history of the last converged step.
    fn evaluate_contact(
        &self,
        u: &[f64],
        search: Search,
    ) -> Result<(Vec<crate::contact::ContactPoint>, Vec<SlotState>)> {
        let nodes = self.asm.nodal_state(u);
        let (nodes, history) = match &self.history {
            Some((states, start)) => (nodes.with_start(Some(start)), states),
            None => (nodes, &self.initial_states),
        };
        self.contact
            .evaluate_with_history(&nodes, search, Some(history))
    }

    /// Elements and contact at state `u` for output: the evaluation and the contact states.
    fn evaluate_states(&mut self, u: &[f64]) -> Result<(Evaluation, Vec<SlotState>)> {
        let search = match &self.converged_states {
            Some(s) => Search::Hint(s),
            None => Search::Fresh,
        };
        let (points, states) = self.evaluate_contact(u, search)?;
        let contribs: Vec<Contribution> = points.iter().map(|p| p.contribution()).collect();
        let t = Instant::now();
        let ev = self.asm.evaluate(u, false, true, None, &contribs)?;
        self.times.assembly += since(t);
        Ok((ev, states))
    }

    /// The elements' internal forces (and tangent, and K_fp·Δu_p) at `u` for a Newton system,
    /// with `extra` contributions: on one process the whole model's; across processes each
    /// assembles its share of the elements (the first adds `extra`), the forces are summed on
    /// every process and the tangent stays this process's share, for the solver to sum.
    fn evaluate_newton(
        &self,
        u: &[f64],
        want_k: bool,
        dup: Option<&[f64]>,
        extra: &[Contribution],
    ) -> Result<Evaluation> {
        let Some((rank, size)) = self.ranks else {
            return self.asm.evaluate(u, want_k, false, dup, extra);
        };
        let share = self
            .asm
            .evaluate_share(u, want_k, dup, if rank == 0 { extra } else { &[] });
        // An element that fails (inverts) fails on its own rank: every rank must take the same
        // way on (a cut-back), or the others wait in the sum forever. The sum carries a flag per
        // rank.
        let d = self.solver.distributed().expect("a distributed solver");
        let nf = self.dofs.n_primary();
        let ndup = dup.map_or(0, |_| self.dofs.n_free);
        let mut all = vec![0.0; nf + ndup + 4 + size];
        match &share {
            Ok(ev) => {
                all[..nf].copy_from_slice(&ev.f_int);
                if let Some(v) = &ev.k_fp_dup {
                    all[nf..nf + ndup].copy_from_slice(v);
                }
                all[nf + ndup..nf + ndup + 4].copy_from_slice(&ev.ebe);
            }
            Err(_) => all[nf + ndup + 4 + rank] = 1.0,
        }
        d.sum(&mut all)?;
        let failed = all[nf + ndup + 4..].iter().position(|&f| f != 0.0);
        let mut ev = match (share, failed) {
            (Err(e), _) => return Err(e),
            (Ok(_), Some(r)) => {
                return Err(Error::Solve(format!(
                    "an element failed on rank {r} (its message is in that rank's output)"
                )))
            }
            (Ok(ev), None) => ev,
        };
        ev.f_int.copy_from_slice(&all[..nf]);
        if let Some(v) = ev.k_fp_dup.as_mut() {
            v.copy_from_slice(&all[nf..nf + ndup]);
        }
        ev.ebe.copy_from_slice(&all[nf + ndup..nf + ndup + 4]);
        Ok(ev)
    }

    /// Whether this process adds the contact's tangent to the one it gives the solver (across
    /// processes only the first does, the solver summing their shares).
    fn adds_contact_tangent(&self) -> bool {
        self.ranks.is_none_or(|(rank, _)| rank == 0)
    }

    /// Factorize a full tangent (values on the assembler's pattern).
    fn factorize(&mut self, kv: &[f64]) -> Result<()> {
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
            .factorize(&self.asm.pattern, kv, self.linear, &describe)?;
        self.times.factor += since(t);
        self.factor_valid = self.linear;
        Ok(())
    }

    /// Solve K Δu = rhs for the contact points `points` at state `u`: condensed when possible
    /// (branches decided on the linearized problem), else with the full tangent of the current
    /// branches.
    fn solve_step(
        &mut self,
        u: &[f64],
        rhs: Vec<f64>,
        points: &[ContactPoint],
        guess: &[bool],
        ks_fresh: Option<&Evaluation>,
        cycle: OnCycle,
    ) -> Result<ContactStep> {
        let (model, dofs) = (self.asm.model, self.dofs);
        let describe = |eq: usize| describe_eq(model, dofs, eq);
        let pending = match &self.condensed {
            Condensed::Pending(c) => Some(self.condensed_equations(c.clone(), points, guess)),
            Condensed::Near(eqs) => Some((eqs.clone(), true)),
            _ => None,
        };
        if let Some((cands, partial)) = pending {
            let ev;
            let ks = match ks_fresh {
                Some(e) => e,
                None => {
                    let t = Instant::now();
                    ev = self.asm.evaluate(u, true, false, None, &[])?;
                    self.times.assembly += since(t);
                    &ev
                }
            };
            let lambdas = self.dofs.n_free - self.dofs.n_lambda..self.dofs.n_free;
            self.observer.phase(&Phase::Factorization {
                kind: "structural tangent, contact condensed",
                unknowns: self.asm.pattern.n,
            });
            let t = Instant::now();
            let made = CondensedContact::new(
                &self.asm.pattern,
                ks.k_values.as_ref().expect("requested"),
                &cands,
                lambdas,
                self.max_condensed,
                self.groups.clone(),
                &describe,
            );
            self.times.factor += since(t);
            self.condensed = match made {
                Ok(Some(mut c)) => {
                    if partial {
                        c.set_partial();
                    }
                    Condensed::Ready(Box::new(c))
                }
                Ok(None) => Condensed::Off,
                // An indefinite structural tangent: the full tangent's LU takes over.
                Err(Error::Singular(_)) if !self.small_strain => Condensed::Off,
                Err(e) => return Err(e),
            };
            if matches!(self.condensed, Condensed::Off) {
                self.condense_off();
            }
        } else if let (Condensed::Ready(c), Some(ks)) = (&mut self.condensed, ks_fresh) {
            // Large deformation: the structural tangent changed.
            let kv = ks.k_values.as_ref().expect("requested");
            self.observer.phase(&Phase::Factorization {
                kind: "structural tangent, contact condensed",
                unknowns: self.asm.pattern.n,
            });
            let t = Instant::now();
            let ok = match c.factorize(&self.asm.pattern, kv, &describe) {
                Ok(ok) => ok,
                Err(Error::Singular(_)) => false,
                Err(e) => return Err(e),
            };
            self.times.factor += since(t);
            if !ok {
                self.condense_off();
            }
        }
        if let Condensed::Ready(c) = &mut self.condensed {
            self.observer.phase(&Phase::Solve);
            let t = Instant::now();
            let step = c.step(&rhs, points, guess, self.dofs, cycle, &describe)?;
            self.times.solve += since(t);
            if let Some(step) = step {
                return Ok(step);
            }
            // A point reaches beyond the candidates (a node slid on): set up again with the
            // candidates of the current state added.
            if self.regrowths < MAX_REGROWTHS {
                let n_disp = self.dofs.n_free - self.dofs.n_lambda;
                let mut cands: Vec<usize> = c
                    .candidates()
                    .iter()
                    .copied()
                    .filter(|&e| e < n_disp)
                    .collect();
                cands.extend(self.contact.candidate_equations(&self.asm.nodal_state(u))?);
                for p in points {
                    for &code in &p.codes {
                        cands.extend(self.dofs.entries(code).map(|(e, _)| e));
                    }
                }
                cands.retain(|&e| e < n_disp);
                cands.sort_unstable();
                cands.dedup();
                // Where those are too many, the nearest points' grow from the ones set up.
                let next = if cands.len() + self.dofs.n_lambda > self.max_condensed {
                    let kept = c.candidates().to_vec();
                    let budget = (kept.len() + self.max_condensed / 4).min(self.max_condensed);
                    let mut near = nearest_equations(points, guess, self.dofs, budget);
                    near.extend(kept);
                    near.sort_unstable();
                    near.dedup();
                    Condensed::Near(near)
                } else {
                    Condensed::Pending(cands)
                };
                self.regrowths += 1;
                let n = match &next {
                    Condensed::Near(e) | Condensed::Pending(e) => e.len(),
                    _ => 0,
                };
                self.observer.detail(&format!(
                    "contact reaches beyond the condensed equations: {n} candidates now"
                ));
                self.condensed = next;
                return self.solve_step(u, rhs, points, guess, None, cycle);
            }
            self.condense_off();
        }
        self.solve_full(u, rhs, points, guess)
    }

    /// The equations of the condensed solve from the candidate displacement equations `cands`:
    /// with every multiplier, or where those are more than M can take, the nearest points'
    /// ([`nearest_equations`]); and whether they are those.
    fn condensed_equations(
        &self,
        cands: Vec<usize>,
        points: &[ContactPoint],
        guess: &[bool],
    ) -> (Vec<usize>, bool) {
        let lambdas = self.dofs.n_free - self.dofs.n_lambda..self.dofs.n_free;
        let partial = cands.len() + lambdas.len() > self.max_condensed;
        let mut eqs = if partial {
            nearest_equations(points, guess, self.dofs, self.max_condensed / 2)
        } else {
            let mut all = cands;
            all.extend(lambdas);
            all
        };
        eqs.sort_unstable();
        eqs.dedup();
        (eqs, partial)
    }

    /// The first guess of the branch search: closed where a point is closed now or was active at
    /// the last converged state. A penalty point's penetration is only the force over the
    /// penalty, so the predictor's straight step along a curved master, or any iterate, can open
    /// it by a hair; starting from the contact the step began with finds the physical solution of
    /// the linearized problem where starting from the open iterate can settle on another one
    /// (a block balanced on one node).
    fn branch_guess(&self, points: &[ContactPoint]) -> Vec<bool> {
        let before = self.converged_states.as_deref().unwrap_or(&[]);
        points
            .iter()
            .enumerate()
            .map(|(k, p)| p.closed || (p.can_close() && before.get(k).is_some_and(|s| s.active)))
            .collect()
    }

    /// The change of a point's unknowns (over its codes) in a step `du` of the free equations.
    fn local_change(&self, p: &ContactPoint, du: &[f64]) -> Vec<f64> {
        let nf = self.dofs.n_free;
        p.codes
            .iter()
            .map(|&code| {
                self.dofs
                    .entries(code)
                    .filter(|(e, _)| *e < nf)
                    .map(|(e, w)| w * du[e])
                    .sum()
            })
            .collect()
    }

    /// Every multiplier point's multipliers and its slave node's free displacement equations.
    fn multiplier_groups(&self, points: &[ContactPoint]) -> Vec<Group> {
        let dofs = self.dofs;
        let n_disp = dofs.n_free - dofs.n_lambda;
        points
            .iter()
            .zip(&self.slot_nodes)
            .filter_map(|(p, &node)| {
                let PointLaw::Multiplier { tangential, .. } = p.law else {
                    return None;
                };
                let lambdas: Vec<usize> = p.codes[p.codes.len() - 1 - tangential..]
                    .iter()
                    .flat_map(|&c| dofs.entries(c).map(|(e, _)| e))
                    .collect();
                let slave: Vec<usize> = dofs.node_dofs[node]
                    .iter()
                    .map(|&(_, c)| c)
                    .filter(|&c| c < n_disp)
                    .collect();
                Some(Group { slave, lambdas })
            })
            .collect()
    }

    /// The contact's slave basis transformation ([`crate::contact::Formulation::slave_transform`])
    /// over the free displacement equations: each node pair's entry for every component both
    /// nodes have free.
    fn slave_transform(&self) -> Vec<(usize, usize, f64)> {
        let dofs = self.dofs;
        let n_disp = dofs.n_free - dofs.n_lambda;
        let mut out = Vec::new();
        for (k, l, w) in self.contact.slave_transform() {
            for &(id, ek) in &dofs.node_dofs[k] {
                let el = dofs.node_dofs[l]
                    .iter()
                    .find(|(i, _)| *i == id)
                    .map(|p| p.1);
                if let Some(el) = el.filter(|&el| ek < n_disp && el < n_disp) {
                    out.push((ek, el, w));
                }
            }
        }
        out
    }

    /// Give up condensing for the rest of the analysis: full tangents, on a pattern with both
    /// triangles if a contact tangent is not symmetric.
    pub(super) fn condense_off(&mut self) {
        self.condensed = Condensed::Off;
        self.asm.set_symmetric(self.contact.symmetric());
        self.solver.reset();
    }

    /// The Newton step with full tangents: the branches are searched on the linearized problem
    /// as in the condensed step, each guess costing a factorization (few are needed).
    fn solve_full(
        &mut self,
        u: &[f64],
        rhs: Vec<f64>,
        points: &[ContactPoint],
        guess: &[bool],
    ) -> Result<ContactStep> {
        let nf = self.dofs.n_free;
        let couplings: Vec<Vec<usize>> = points.iter().map(|p| p.codes.clone()).collect();
        if self.asm.set_couplings(&couplings) {
            self.solver.reset();
        }
        let t = Instant::now();
        let ks = self.evaluate_newton(u, true, None, &[])?;
        self.times.assembly += since(t);
        let mut closed: Vec<Branch> = points.iter().zip(guess).map(|(p, &g)| p.guess(g)).collect();
        let mut search = BranchSearch::new(MAX_FULL_UPDATES);
        // Multipliers eliminated through their slave rows (`solve::multipliers`): a symmetric
        // tangent into a symmetric system for Cholesky, a general one by GMRES on its symmetric
        // counterpart's elimination, at any size; else, below the Krylov threshold, the general
        // elimination's LU, and above it the whole tangent's GMRES, preconditioned with the LDLᵀ
        // of its symmetric part (the general reduced system's symmetric part, gap rows in place
        // of slave rows, is no preconditioner for it). With a solver from outside (PETSc) the
        // reduced systems go to one of its kind; the tangents it cannot reduce, whole to it.
        // Across processes each holds a share of the tangent: the shares are summed on every
        // process for the elimination, and a tangent it leaves goes whole to the solver from
        // the first.
        let general = nf < self.krylov_min && self.ranks.is_none();
        let groups = self.multiplier_groups(points);
        let transform = if groups.is_empty() {
            Vec::new()
        } else {
            self.slave_transform()
        };
        let summed = self.ranks.is_some() && !groups.is_empty();
        let mut k_structure = ks.k_values.expect("requested");
        // Guesses solved loosely, and the last of them being solved again.
        let (mut loose_ok, mut resolving) = (self.loose_guesses, false);
        if summed {
            let d = self.solver.distributed().expect("a distributed solver");
            d.sum(&mut k_structure)?;
        }
        loop {
            let mut kv = k_structure.clone();
            let mut step = rhs.clone();
            let contribs: Vec<Contribution> = points
                .iter()
                .zip(&closed)
                .map(|(p, &c)| {
                    if let Some(change) = p.branch_change(c) {
                        for (&code, d) in p.codes.iter().zip(change) {
                            for (e, w) in self.dofs.entries(code) {
                                if e < nf {
                                    step[e] -= w * d;
                                }
                            }
                        }
                    }
                    let (fe, ke) = p.branch(c);
                    Contribution {
                        codes: p.codes.clone(),
                        fe,
                        ke,
                    }
                })
                .collect();
            if summed || self.adds_contact_tangent() {
                self.asm.add_tangents(&mut kv, &contribs);
            }
            // Across processes a row is whole only in the sum of the shares.
            if self.ranks.is_none() || summed {
                pin_empty_multiplier_rows(&self.asm.pattern, &mut kv, nf - self.dofs.n_lambda..nf);
            }
            let eliminated = !resolving && !groups.is_empty() && {
                let (model, dofs) = (self.asm.model, self.dofs);
                let describe = |eq: usize| describe_eq(model, dofs, eq);
                self.observer.phase(&Phase::Factorization {
                    kind: "tangent, multipliers eliminated",
                    unknowns: self.asm.pattern.n,
                });
                let t = Instant::now();
                let solved = self.eliminate.solve(
                    &self.asm.pattern,
                    &kv,
                    &mut step,
                    &groups,
                    general,
                    &transform,
                    &describe,
                )?;
                self.times.factor += since(t);
                if solved && search.updates == 0 {
                    self.observer.detail(&format!(
                        "multipliers eliminated through the slave rows ({}): {} of {}",
                        self.eliminate.method.name(),
                        self.eliminate.eliminated,
                        self.eliminate.eliminated + self.eliminate.kept
                    ));
                }
                solved
            };
            // An iterative solver solves the guesses only to GUESS_TOL, enough to predict the
            // branches, and the last guess again to its own tolerance (from the loose solution);
            // where that predicts otherwise, the search goes on with accurate solves.
            let loose = !eliminated && loose_ok && !resolving;
            if !eliminated {
                if !resolving {
                    if summed && self.ranks.is_some_and(|(rank, _)| rank > 0) {
                        // The first process gives the summed tangent, the others nothing.
                        kv.fill(0.0);
                    }
                    self.factorize(&kv)?;
                }
                let t = Instant::now();
                if loose {
                    self.solver.set_relative_tolerance(Some(GUESS_TOL));
                }
                let solved = if resolving {
                    self.solver.resolve_in_place(&mut step)
                } else {
                    self.solver.solve_in_place(&mut step)
                };
                if loose {
                    self.solver.set_relative_tolerance(None);
                }
                solved?;
                self.times.solve += since(t);
            }
            let predicted: Vec<Branch> = points
                .iter()
                .map(|p| p.predicts(&self.local_change(p, &step)))
                .collect();
            if resolving && closed != predicted {
                // The accurate solve predicts otherwise: the search starts again from here, with
                // accurate solves.
                (resolving, loose_ok) = (false, false);
                search = BranchSearch::new(MAX_FULL_UPDATES);
            }
            // Unlike the condensed step, a cycle keeps the last guess's step here: the first
            // guess's made two coarse shallow-ironing runs (structural tangent indefinite, so
            // full tangents) fail where they converge with cut-backs.
            match search.next(&closed, &predicted) {
                Some(next) => closed = next,
                None if loose => resolving = true,
                None => {
                    return Ok(ContactStep {
                        du: step,
                        closed,
                        updates: search.updates,
                        cycled: search.cycled,
                    })
                }
            }
        }
    }

    /// Newton iterations towards external forces `f_ext` and prescribed values `up`.
    /// Ok(false) = no convergence within maxiter.
    pub fn newton(
        &mut self,
        u: &mut [f64],
        f_ext: &[f64],
        up: &[f64],
        a: &Analysis,
        info: &mut StepInfo,
    ) -> Result<bool> {
        let nf = self.dofs.n_free;
        if self.contact.has_friction() {
            self.history = self
                .converged_states
                .clone()
                .map(|states| (states, u.to_vec()));
        }
        if nf == 0 {
            u[nf..].copy_from_slice(up);
            return Ok(true);
        }
        let has_contact = !self.contact.is_empty();
        self.flips = vec![0; self.flips.len()];
        self.floor_dominated = None;
        let dup: Vec<f64> = (0..up.len()).map(|i| up[i] - u[nf + i]).collect();
        if a.initialguess && dup.iter().any(|&d| d != 0.0) {
            self.predict(u, &dup)?;
        }
        u[nf..].copy_from_slice(up);
        let mut du = vec![0.0; nf];
        let mut prev: Option<Vec<SlotState>> = self.converged_states.clone();
        let mut prev2: Option<Vec<SlotState>> = None;
        // Per penalty point closed in the last Newton step: the force of the step's linear model,
        // which the next step's geometric tangent part takes (see `ContactPoint::hold_force`).
        let mut held: Vec<Option<f64>> = Vec::new();
        let mut last_cycled = false;
        for it in 0..=a.maxiter {
            if self.observer.interrupted() {
                return Err(Error::Interrupted);
            }
            let search = match &prev {
                Some(p) => Search::Hint(p),
                None => Search::Fresh,
            };
            let (points, states) = self.evaluate_contact(u, search)?;
            if let (Some(p), Some(pp)) = (&prev, &prev2) {
                self.count_flips(&states, p, pp);
            }
            // Structural tangent (elements only) where the condensed solve needs it fresh; the
            // full-tangent path evaluates its own.
            let need_ks = has_contact
                && match self.condensed {
                    Condensed::Pending(_) | Condensed::Near(_) => true,
                    Condensed::Ready(_) => !self.small_strain,
                    Condensed::Off => false,
                };
            let want_k = need_ks
                || (!has_contact
                    && !self.factor_valid
                    && (it == 0 || a.manrmsteps.is_some_and(|k| it % k == 0)));
            let contribs: Vec<Contribution> = points.iter().map(|p| p.contribution()).collect();
            self.observer.phase(&Phase::Assembly);
            let t = Instant::now();
            let mut ev =
                self.evaluate_newton(u, want_k, None, if has_contact { &[] } else { &contribs })?;
            if has_contact {
                self.asm.add_residuals(&mut ev.f_int, &contribs);
            }
            self.times.assembly += since(t);
            let rhs: Vec<f64> = (0..nf).map(|i| f_ext[i] - ev.f_int[i]).collect();
            let last = info.residual_history.last().copied();
            let residual = Residual {
                rhs: &rhs,
                f_ext,
                ebe: &ev.ebe,
                du: &du,
                u,
            };
            let mut check = check(self.asm.model, self.dofs, &residual, a, it, &points);
            // On the round-off floor: accepted once Newton stops gaining on it.
            if !check.converged
                && check.on_floor
                && it > 0
                && last.is_some_and(|l| check.worst > 0.5 * l)
            {
                check.converged = true;
            }
            info.residual_history.push(check.worst);
            info.iterations += 1;
            self.observer.iteration(&self.iteration_report(
                it,
                check.worst,
                &states,
                prev.as_deref(),
            ));
            if check.converged && (it > 0 || check.worst == 0.0) {
                // Equilibrium with a node across its master is no solution (a smaller step is).
                if let Some(why) = crate::contact::crossing_message(self.asm.model, &states) {
                    return Err(Error::Solve(why));
                }
                let floor = check.floor_ratio.map(|r| (r, check.penalty_floor));
                self.accept(it, &ev, floor, states, a, info)?;
                return Ok(true);
            }
            if !check.worst.is_finite() {
                return Err(Error::Solve("residual is not finite".into()));
            }
            if it == a.maxiter {
                self.floor_dominated = (check.floor_excess > 1.0).then_some(check.floor_excess);
                break;
            }
            let (step, updates, cycled) = if has_contact {
                // A cycled search whose step did not lower the residual takes the earliest of
                // its equal guesses next time.
                let h = &info.residual_history;
                let stalled = last_cycled && h.len() >= 2 && check.worst >= 0.99 * h[h.len() - 2];
                let s = self.contact_newton_step(
                    u,
                    rhs,
                    points,
                    need_ks.then_some(&ev),
                    &mut held,
                    stalled,
                )?;
                last_cycled = s.cycled;
                (s.du, s.updates, s.cycled)
            } else {
                (self.structural_step(rhs, want_k.then_some(&ev))?, 0, false)
            };
            if updates > 0 {
                let back = if cycled {
                    " and came back to a guess"
                } else {
                    ""
                };
                self.observer.detail(&format!(
                    "contact branches updated {updates} times on the linearized problem{back}"
                ));
            }
            for i in 0..nf {
                u[i] += step[i];
            }
            du = step;
            prev2 = prev.replace(states);
        }
        Ok(false)
    }

    /// Count the contact points whose partner and branch went back to what they were two
    /// iterations before (`before`), from `last` to `states`.
    fn count_flips(&mut self, states: &[SlotState], last: &[SlotState], before: &[SlotState]) {
        let key = |s: &SlotState| (s.partner, s.active);
        for (k, s) in states.iter().enumerate() {
            if key(s) != key(&last[k]) && key(s) == key(&before[k]) {
                self.flips[k] += 1;
            }
        }
    }

    /// The Newton step of a model without contact for the residual `rhs`, factorizing the
    /// tangent of `ev` if given (else the last factorization is reused).
    fn structural_step(&mut self, rhs: Vec<f64>, ev: Option<&Evaluation>) -> Result<Vec<f64>> {
        if let Some(ev) = ev {
            self.factorize(ev.k_values.as_ref().expect("requested"))?;
        }
        let mut x = rhs;
        let t = Instant::now();
        self.solver.solve_in_place(&mut x)?;
        self.times.solve += since(t);
        Ok(x)
    }

    /// A converged iterate: a model whose first iterate is converged is factorized once all the
    /// same (an unloaded mechanism must not pass), a round-off floor (its residual over the
    /// tolerance, and whether the penalty's round-off makes it) is warned of once, the contact
    /// states are kept.
    fn accept(
        &mut self,
        it: usize,
        ev: &Evaluation,
        floor: Option<(f64, bool)>,
        states: Vec<SlotState>,
        a: &Analysis,
        info: &mut StepInfo,
    ) -> Result<()> {
        let has_contact = !self.contact.is_empty();
        if let (0, false, false, Some(kv)) =
            (it, has_contact, self.factor_valid, ev.k_values.as_ref())
        {
            self.factorize(kv)?;
        }
        if let Some((r, penalty)) = floor.filter(|_| !self.floor_warned) {
            let w = if penalty {
                penalty_warning(self.asm.model, r, a.rtolf)
            } else {
                precision_warning(r, a.rtolf)
            };
            self.observer.warning(&w);
            info.warnings.push(w);
            self.floor_warned = true;
        }
        if has_contact {
            self.converged_states = Some(states);
        }
        info.iterations -= 1;
        Ok(())
    }

    /// The Newton step of a model with contact: the branches searched on the linearized problem
    /// from the first guess, penalty points' geometric parts taken with the forces `held` from
    /// the last step's linear model (updated here for the next step), the earliest of equal
    /// guesses taken after a `stalled` cycle.
    fn contact_newton_step(
        &mut self,
        u: &[f64],
        rhs: Vec<f64>,
        mut points: Vec<ContactPoint>,
        ks: Option<&Evaluation>,
        held: &mut Vec<Option<f64>>,
        stalled: bool,
    ) -> Result<ContactStep> {
        let guess = self.branch_guess(&points);
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
        let s = self.solve_step(u, rhs, &points, &guess, ks, cycle)?;
        *held = points
            .iter()
            .zip(&s.closed)
            .map(|(p, b)| {
                b.closed
                    .then(|| p.held_force(&self.local_change(p, &s.du)))
                    .flatten()
            })
            .collect();
        Ok(s)
    }

    /// Tangent predictor for prescribed increments `dup`: K Δu_f = −K_fp Δu_p at the current state.
    ///
    /// The elements' part is linearized; the contact is evaluated at the prescribed values
    /// already moved (a rigid indenter's reference node, or driven nodes of either body), so
    /// the step's branch search sees the gaps the move makes. Linearizing the contact's part
    /// too (−K_fp Δu_p of its closed branches) left the search blind to it: the free nodes'
    /// linear gaps, without the indenter's move, predicted the pressed nodes open, and the
    /// step kept the closed branches' push without their stiffness (a neo-Hookean block
    /// pressed by a plane moving with a node: an element inverted in the first step even in
    /// 32 substeps).
    fn predict(&mut self, u: &mut [f64], dup: &[f64]) -> Result<()> {
        let nf = self.dofs.n_free;
        let has_contact = !self.contact.is_empty();
        let search = match &self.converged_states {
            Some(s) => Search::Hint(s),
            None => Search::Fresh,
        };
        let need_k = !self.factor_valid && !has_contact;
        let t = Instant::now();
        let ev = self.evaluate_newton(u, need_k, Some(dup), &[])?;
        self.times.assembly += since(t);
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
        let points = if has_contact {
            // The contact's change of residual from the move: −(f_c(moved) − f_c(u)).
            let (before, _) = self.evaluate_contact(u, search)?;
            let (after, _) = self.evaluate_contact(&moved, search)?;
            let mut change = vec![0.0; self.dofs.n_primary()];
            let contribs = |ps: &[ContactPoint]| -> Vec<Contribution> {
                ps.iter().map(|p| p.contribution()).collect()
            };
            self.asm.add_residuals(&mut change, &contribs(&after));
            let mut old = vec![0.0; self.dofs.n_primary()];
            self.asm.add_residuals(&mut old, &contribs(&before));
            for i in 0..nf {
                rhs[i] -= change[i] - old[i];
            }
            after
        } else {
            Vec::new()
        };
        let step = if has_contact {
            // The structural tangent of the condensed solve is the element part only.
            let need_ks = match self.condensed {
                Condensed::Pending(_) | Condensed::Near(_) => true,
                Condensed::Ready(_) => !self.small_strain,
                Condensed::Off => false,
            };
            let ks = if need_ks {
                let t = Instant::now();
                let ks = self.asm.evaluate(u, true, false, None, &[])?;
                self.times.assembly += since(t);
                Some(ks)
            } else {
                None
            };
            let guess = self.branch_guess(&points);
            self.solve_step(u, rhs, &points, &guess, ks.as_ref(), OnCycle::Last)?
                .du
        } else {
            if need_k {
                self.factorize(ev.k_values.as_ref().expect("requested"))?;
            }
            let mut x = rhs;
            self.solver.solve_in_place(&mut x)?;
            x
        };
        for i in 0..nf {
            u[i] += step[i];
        }
        Ok(())
    }

    /// Why the last attempt did not converge, in words, if something specific shows.
    pub fn diagnosis(&self) -> Option<String> {
        let mut why = Vec::new();
        if let Some(r) = self.floor_dominated {
            why.push(format!(
                "the round-off of the penalty forces is {r:.1e} times the tolerance: the penalty \
                 is beyond what double precision resolves"
            ));
        }
        {
            let mut chatter: Vec<(usize, usize)> = self
                .flips
                .iter()
                .enumerate()
                .filter(|(_, &f)| f >= 2)
                .map(|(k, &f)| (f, k))
                .collect();
            chatter.sort_unstable_by(|a, b| b.cmp(a));
            if !chatter.is_empty() {
                let labels: Vec<String> = chatter
                    .iter()
                    .take(8)
                    .map(|&(f, k)| {
                        format!("{} ({f}×)", self.asm.model.nodes[self.slot_nodes[k]].label)
                    })
                    .collect();
                why.push(format!(
                    "contact nodes went back and forth between states (chattering): {}{}",
                    labels.join(", "),
                    if chatter.len() > 8 { ", …" } else { "" }
                ));
            }
        }
        (!why.is_empty()).then(|| why.join("; "))
    }
}

/// Give each multiplier among `range` whose row of the tangent `kv` is zero (to round-off of the
/// largest multiplier row) a diagonal of that row's size:
/// a friction traction component along a direction in which every unknown it acts on is held
/// (a slave node on a symmetry plane, whose slip and force along the plane's normal are both
/// fixed) has no equation of its own among the free unknowns, and left so the full tangent is
/// singular (the first step of a 3D mortar patch with friction multipliers, too large to
/// condense, went to a residual of 1e20). Its residual is zero there (the slip it holds cannot
/// change), so the pinned row keeps it where it is; a tangent without such rows is untouched.
fn pin_empty_multiplier_rows(pattern: &Pattern, kv: &mut [f64], range: std::ops::Range<usize>) {
    if range.is_empty() {
        return;
    }
    let mut largest = vec![0.0f64; range.len()];
    for c in 0..pattern.n {
        for k in pattern.col_ptr[c]..pattern.col_ptr[c + 1] {
            let r = pattern.row_idx[k];
            let v = kv[k].abs();
            if range.contains(&r) {
                largest[r - range.start] = largest[r - range.start].max(v);
            }
            if pattern.symmetric && r != c && range.contains(&c) {
                largest[c - range.start] = largest[c - range.start].max(v);
            }
        }
    }
    // Zero to round-off: entries of (I − n nᵀ)/c along a plane's normal.
    let scale = largest.iter().copied().fold(0.0, f64::max);
    for (i, &l) in largest.iter().enumerate() {
        if l <= 1e-10 * scale {
            let e = range.start + i;
            kv[pattern.position(e, e)] = scale;
        }
    }
}
