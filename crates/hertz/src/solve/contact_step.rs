//! How a Newton step of a contact problem is solved: the branch of every contact point (closed
//! or open) is decided on the linearized problem, condensed on the contact equations where the
//! solver offers a Schur block (see [`super::condensed`]), else with full tangents, one
//! factorization per guess of the branch search, the multipliers eliminated through their
//! slave nodes' rows where that is exact (see [`super::multipliers`]).
//!
//! The condensed step is set up at the first solve on the candidate equations; when contact
//! reaches beyond them it is set up again with more (a regrowth: one factorization, what one
//! guess of a full-tangent step costs), up to [`MAX_REGROWTHS`] times in one solve, after which
//! (or when the structural tangent is indefinite, or the closed points alone need more than
//! the dense block's largest size, [`super::condensed::MAX_DENSE`]: below it the block grows to
//! hold them) full tangents take over for the rest of the analysis. A contact zone
//! that grows over many steps regrows as often as it needs.

use super::branches::{BranchSearch, ContactStep, OnCycle};
use super::condensed::{nearest_equations, CondensedContact};
use super::equations::{describe_eq, since, Equations};
use super::linear::LinearSolver;
use super::multipliers::{Group, MultiplierElimination};
use super::report::Phase;
use super::terms::StepTerms;
use crate::assembly::{Contribution, DofMap, Evaluation, Pattern};
use crate::contact::slot::Branch;
use crate::contact::{BranchRule, SlotLinearization, SlotState};
use crate::error::{Error, Result};
use std::time::Instant;

/// How often one solve sets the condensed step up again when contact reaches beyond its
/// candidates (each time a symbolic analysis and a factorization), before full tangents take
/// over.
const MAX_REGROWTHS: usize = 4;

/// How many Newton iterations running may each need the condensed step set up again with more
/// candidates before full tangents take over for good: the candidates then chase a contact zone
/// that does not settle within the dense block. A 3D tube crushed 75 % with its bore in
/// self-contact (large deformation, the block grown to 4 149 equations) regrew at every
/// iteration and never converged, where full tangents take 3 iterations.
const MAX_REGROWN_ITERATIONS: usize = 3;

/// Largest number of branch updates of a step solved with full tangents (each a factorization).
const MAX_FULL_UPDATES: usize = 8;

/// The relative residual of an iterative solver's solves of branch guesses with full tangents
/// (only the branches are predicted from them; the last guess is solved again to the solver's
/// own tolerance).
const GUESS_TOL: f64 = 1e-4;

/// Makes a linear solver of the analysis' kind.
pub(super) type SolverMaker = Box<dyn Fn() -> Box<dyn LinearSolver>>;

/// Where the condensed step stands.
enum Condensed {
    /// Not used (no contact, a solver without a Schur block, too many candidates, an indefinite
    /// structural tangent).
    Off,
    /// To be set up at the next solve, with the candidate displacement equations.
    Pending(Vec<usize>),
    /// To be set up again with these equations (displacements and multipliers): the nearest
    /// points' grown by those that reached beyond them.
    Near(Vec<usize>),
    Ready(Box<CondensedContact>),
}

/// The strategy of a contact problem's Newton steps and its state over the analysis.
pub(super) struct ContactStepper {
    condensed: Condensed,
    /// How often the condensed solve was set up again with more candidates in this solve.
    regrowths: usize,
    /// How many solves (Newton iterations) running needed such a set-up.
    regrown_iterations: usize,
    /// A body is held by contact alone (known from the model's supports, or found singular by a
    /// set-up): every set-up shifts the candidates from the start.
    held: bool,
    /// The most equations the condensed step holds densely (`SolveParams::max_condensed`);
    /// where the closed points alone need more, it grows (up to
    /// [`super::condensed::MAX_DENSE`]) rather than leave the condensed step.
    max_condensed: usize,
    /// Makes the structural factor's solver of a condensed step (one with a Schur block).
    make_solver: SolverMaker,
    /// The full tangent's solve with the multipliers eliminated.
    eliminate: MultiplierElimination,
    /// Unknowns from which non-symmetric tangents go to GMRES.
    krylov_min: usize,
    /// The node of every contact point.
    slot_nodes: Vec<usize>,
}

/// The change of a point's unknowns (over its codes) in a step `du` of the free equations.
pub(super) fn local_change(dofs: &DofMap, p: &SlotLinearization, du: &[f64]) -> Vec<f64> {
    let nf = dofs.n_free;
    p.codes
        .iter()
        .map(|&code| {
            dofs.entries(code)
                .filter(|(e, _)| *e < nf)
                .map(|(e, w)| w * du[e])
                .sum()
        })
        .collect()
}

/// The step of a body held by springs (see [`ContactStepper::hold_contact_nodes`]) goes along
/// its load, its length the springs': stretched by doubling until a point closes, so that the
/// prediction sees the contact the motion makes (left as it is if none ever does).
fn reach_first_contact(dofs: &DofMap, points: &[SlotLinearization], step: &mut [f64]) {
    let closes = |s: &[f64]| {
        points
            .iter()
            .any(|p| p.can_close() && p.predicts(&local_change(dofs, p, s)).closed)
    };
    let mut scaled = step.to_vec();
    for _ in 0..200 {
        if closes(&scaled) {
            step.copy_from_slice(&scaled);
            return;
        }
        scaled.iter_mut().for_each(|v| *v *= 2.0);
    }
}

impl ContactStepper {
    /// The strategy of a model's contact: condensed from the first solve on the candidate
    /// equations `candidates` if `condense` (the caller knows the solver offers a Schur block
    /// and the caller allows it), `max_condensed` equations at most; the eliminations' reduced
    /// systems solved by `eliminate`. `held`: a body is held by contact alone
    /// ([`crate::assembly::rigid`]), so the condensed step shifts its candidates from the start.
    pub fn new(
        condense: Option<Vec<usize>>,
        held: bool,
        max_condensed: usize,
        make_solver: SolverMaker,
        eliminate: MultiplierElimination,
        krylov_min: usize,
        slot_nodes: Vec<usize>,
    ) -> ContactStepper {
        ContactStepper {
            condensed: condense.map_or(Condensed::Off, Condensed::Pending),
            regrowths: 0,
            regrown_iterations: 0,
            held,
            max_condensed,
            make_solver,
            eliminate,
            krylov_min,
            slot_nodes,
        }
    }

    /// Whether the condensed step needs the structural tangent of the current iterate: to set
    /// it up, or (large deformation) to factorize it again.
    pub fn needs_structure(&self, constant_structure: bool) -> bool {
        match self.condensed {
            Condensed::Pending(_) | Condensed::Near(_) => true,
            Condensed::Ready(_) => !constant_structure,
            Condensed::Off => false,
        }
    }

    /// Whether steps use full tangents (the condensed step is off for good).
    pub fn full_tangents(&self) -> bool {
        matches!(self.condensed, Condensed::Off)
    }

    /// The multipliers the last solve with full tangents eliminated and kept, and its
    /// statistics; None when the condensed step served.
    pub fn elimination(&self) -> Option<((usize, usize), super::linear::SolverStats)> {
        let e = &self.eliminate;
        (e.eliminated + e.kept > 0).then(|| ((e.eliminated, e.kept), e.stats()))
    }

    /// The first guess of the branch search: closed where a point is closed now or was active at
    /// the last converged state (`before`). A penalty point's penetration is only the force
    /// over the penalty, so the predictor's straight step along a curved master, or any iterate,
    /// can open it by a hair; starting from the contact the step began with finds the physical
    /// solution of the linearized problem where starting from the open iterate can settle on
    /// another one (a block balanced on one node).
    pub fn branch_guess(points: &[SlotLinearization], before: &[SlotState]) -> Vec<bool> {
        points
            .iter()
            .enumerate()
            .map(|(k, p)| p.closed || (p.can_close() && before.get(k).is_some_and(|s| s.active)))
            .collect()
    }

    /// Solve K Δu = rhs for the contact points `points` at state `u`: condensed when possible
    /// (branches decided on the linearized problem), else with the full tangent of the current
    /// branches. `ks_fresh`: the structural tangent at `u`, if evaluated already.
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        eq: &mut Equations,
        u: &[f64],
        rhs: Vec<f64>,
        points: &[SlotLinearization],
        guess: &[bool],
        ks_fresh: Option<&Evaluation>,
        cycle: OnCycle,
        terms: &dyn StepTerms,
    ) -> Result<ContactStep> {
        self.set_up_condensed(eq, u, points, guess, ks_fresh, terms)?;
        if let Condensed::Ready(c) = &mut self.condensed {
            let (model, dofs) = (eq.asm.model, eq.dofs);
            let describe = |e: usize| describe_eq(model, dofs, e);
            eq.observer.phase(&Phase::Solve);
            let t = Instant::now();
            let step = c.step(&rhs, points, guess, eq.dofs, cycle, &describe)?;
            eq.times.solve += since(t);
            if let Some(step) = step {
                self.regrown_iterations = match self.regrowths {
                    0 => 0,
                    _ => self.regrown_iterations + 1,
                };
                self.regrowths = 0;
                if self.regrown_iterations >= MAX_REGROWN_ITERATIONS {
                    eq.observer.detail(&format!(
                        "the contact zone reached beyond the condensed equations in \
                         {MAX_REGROWN_ITERATIONS} iterations running: full tangents from here"
                    ));
                    self.condense_off(eq);
                }
                return Ok(step);
            }
            // A point reaches beyond the candidates (a node slid on): set up again with the
            // candidates of the current state added.
            if self.regrowths < MAX_REGROWTHS {
                self.regrow(eq, u, points, guess)?;
                return self.solve(eq, u, rhs, points, guess, None, cycle, terms);
            }
            self.condense_off(eq);
        }
        self.solve_full(eq, u, rhs, points, guess, terms)
    }

    /// Set the condensed step up where it is pending (factorizing the structural tangent with
    /// the candidates last), or factorize its structural tangent again (`ks_fresh`: large
    /// deformation); where that fails, full tangents take over.
    fn set_up_condensed(
        &mut self,
        eq: &mut Equations,
        u: &[f64],
        points: &[SlotLinearization],
        guess: &[bool],
        ks_fresh: Option<&Evaluation>,
        terms: &dyn StepTerms,
    ) -> Result<()> {
        let (model, dofs) = (eq.asm.model, eq.dofs);
        let describe = |e: usize| describe_eq(model, dofs, e);
        let pending = match &self.condensed {
            Condensed::Pending(c) => {
                Some(self.condensed_equations(eq.dofs, c.clone(), points, guess))
            }
            Condensed::Near(eqs) => Some((eqs.clone(), true)),
            _ => None,
        };
        if let Some((cands, partial)) = pending {
            let ev;
            let ks = match ks_fresh {
                Some(e) => e,
                None => {
                    ev = eq.structure(u, terms)?;
                    &ev
                }
            };
            let lambdas = dofs.n_free - dofs.n_lambda..dofs.n_free;
            eq.observer.phase(&Phase::Factorization {
                kind: "structural tangent, contact condensed",
                unknowns: eq.asm.pattern.n,
            });
            let t = Instant::now();
            let made = CondensedContact::new(
                (self.make_solver)(),
                &eq.asm.pattern,
                ks.k_values.as_ref().expect("requested"),
                &cands,
                lambdas,
                self.max_condensed,
                self.held,
                &describe,
            );
            eq.times.factor += since(t);
            self.condensed = match made {
                Ok(Some(mut c)) => {
                    self.held |= c.held();
                    if partial {
                        c.set_partial();
                    }
                    Condensed::Ready(Box::new(c))
                }
                Ok(None) => Condensed::Off,
                // An indefinite structural tangent: the full tangent's LU takes over.
                Err(Error::Singular(_)) if !eq.constant_structure => Condensed::Off,
                Err(e) => return Err(e),
            };
            if matches!(self.condensed, Condensed::Off) {
                self.condense_off(eq);
            }
        } else if let (Condensed::Ready(c), Some(ks)) = (&mut self.condensed, ks_fresh) {
            // Large deformation: the structural tangent changed.
            let kv = ks.k_values.as_ref().expect("requested");
            eq.observer.phase(&Phase::Factorization {
                kind: "structural tangent, contact condensed",
                unknowns: eq.asm.pattern.n,
            });
            let t = Instant::now();
            let ok = match c.factorize(&eq.asm.pattern, kv, &describe) {
                Ok(ok) => ok,
                // Found held by contact alone only now (see `CondensedContact::hold`).
                Err(Error::Singular(_)) if !c.held() => {
                    let lambdas = dofs.n_free - dofs.n_lambda..dofs.n_free;
                    match c.hold(&eq.asm.pattern, kv, lambdas, &describe) {
                        Ok(ok) => ok,
                        Err(Error::Singular(_)) => false,
                        Err(e) => return Err(e),
                    }
                }
                Err(Error::Singular(_)) => false,
                Err(e) => return Err(e),
            };
            self.held |= c.held();
            eq.times.factor += since(t);
            if !ok {
                self.condense_off(eq);
            }
        }
        Ok(())
    }

    /// Contact reached beyond the condensed step's candidates at `u`: its next set-up takes
    /// the candidates of the current state too, or where those are too many, the nearest
    /// points' grown from the ones set up.
    fn regrow(
        &mut self,
        eq: &Equations,
        u: &[f64],
        points: &[SlotLinearization],
        guess: &[bool],
    ) -> Result<()> {
        let Condensed::Ready(c) = &self.condensed else {
            return Ok(());
        };
        let dofs = eq.dofs;
        let n_disp = dofs.n_free - dofs.n_lambda;
        let mut cands: Vec<usize> = c
            .candidates()
            .iter()
            .copied()
            .filter(|&e| e < n_disp)
            .collect();
        cands.extend(eq.contact.candidate_equations(&eq.asm.nodal_state(u))?);
        for p in points {
            for &code in &p.codes {
                cands.extend(dofs.entries(code).map(|(e, _)| e));
            }
        }
        cands.retain(|&e| e < n_disp);
        cands.sort_unstable();
        cands.dedup();
        let next = if cands.len() + dofs.n_lambda > self.max_condensed {
            // The nearest points' up to three quarters of the limit, then as many of the
            // equations set up before as fit: never more than the limit (more would leave
            // the condensed step for good), unless the closed points alone need more.
            let mut near: std::collections::BTreeSet<usize> =
                nearest_equations(points, guess, dofs, 3 * self.max_condensed / 4)
                    .into_iter()
                    .collect();
            if near.len() > self.max_condensed && near.len() <= super::condensed::MAX_DENSE {
                // The closed points alone need more: a larger dense block costs less than a
                // whole-tangent factorization for every guess of every step to come.
                let grown = (near.len() + near.len() / 3)
                    .clamp(self.max_condensed, super::condensed::MAX_DENSE);
                eq.observer.detail(&format!(
                    "the condensed block grows from {} to {grown} equations",
                    self.max_condensed
                ));
                self.max_condensed = grown;
            }
            for &e in c.candidates() {
                if near.len() >= self.max_condensed {
                    break;
                }
                near.insert(e);
            }
            Condensed::Near(near.into_iter().collect())
        } else {
            Condensed::Pending(cands)
        };
        self.regrowths += 1;
        let n = match &next {
            Condensed::Near(e) | Condensed::Pending(e) => e.len(),
            _ => 0,
        };
        eq.observer.detail(&format!(
            "contact reaches beyond the condensed equations: {n} candidates now"
        ));
        self.condensed = next;
        Ok(())
    }

    /// The equations of the condensed solve from the candidate displacement equations `cands`:
    /// with every multiplier, or where those are more than M can take, the nearest points'
    /// ([`nearest_equations`]); and whether they are those.
    fn condensed_equations(
        &self,
        dofs: &DofMap,
        cands: Vec<usize>,
        points: &[SlotLinearization],
        guess: &[bool],
    ) -> (Vec<usize>, bool) {
        let lambdas = dofs.n_free - dofs.n_lambda..dofs.n_free;
        let partial = cands.len() + lambdas.len() > self.max_condensed;
        let mut eqs = if partial {
            nearest_equations(points, guess, dofs, self.max_condensed / 2)
        } else {
            let mut all = cands;
            all.extend(lambdas);
            all
        };
        eqs.sort_unstable();
        eqs.dedup();
        (eqs, partial)
    }

    /// Give up condensing for the rest of the analysis: full tangents, on a pattern with both
    /// triangles if a contact tangent or a follower load's is not symmetric.
    pub fn condense_off(&mut self, eq: &mut Equations) {
        self.condensed = Condensed::Off;
        let follower = eq.model().has_follower_loads();
        eq.asm.set_symmetric(eq.contact.symmetric() && !follower);
        eq.solver.reset();
    }

    /// Every multiplier point's multipliers and its slave node's free displacement equations.
    fn multiplier_groups(&self, dofs: &DofMap, points: &[SlotLinearization]) -> Vec<Group> {
        let n_disp = dofs.n_free - dofs.n_lambda;
        points
            .iter()
            .zip(&self.slot_nodes)
            .filter_map(|(p, &node)| {
                let BranchRule::Multiplier { tangential, .. } = p.rule else {
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
    fn slave_transform(eq: &Equations) -> Vec<(usize, usize, f64)> {
        let dofs = eq.dofs;
        let n_disp = dofs.n_free - dofs.n_lambda;
        let mut out = Vec::new();
        for (k, l, w) in eq.contact.slave_transform() {
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

    /// The Newton step with full tangents: the branches are searched on the linearized problem
    /// as in the condensed step, each guess costing a factorization (few are needed).
    ///
    /// Multipliers are eliminated through their slave rows (`solve::multipliers`): a symmetric
    /// tangent into a symmetric system for Cholesky, a general one by GMRES on its symmetric
    /// counterpart's elimination, at any size; else, below the Krylov threshold, the general
    /// elimination's LU, and above it the whole tangent's GMRES, preconditioned with the LDLᵀ
    /// of its symmetric part. Across processes each holds a share of the tangent: the shares
    /// are summed on every process for the elimination, and a tangent it leaves goes whole to
    /// the solver from the first.
    fn solve_full(
        &mut self,
        eq: &mut Equations,
        u: &[f64],
        rhs: Vec<f64>,
        points: &[SlotLinearization],
        guess: &[bool],
        terms: &dyn StepTerms,
    ) -> Result<ContactStep> {
        let couplings: Vec<Vec<usize>> = points.iter().map(|p| p.codes.clone()).collect();
        if eq.asm.set_couplings(&couplings) {
            eq.solver.reset();
        }
        let ks = eq.evaluate(u, true, None, &[], terms)?;
        let mut closed: Vec<Branch> = points.iter().zip(guess).map(|(p, &g)| p.guess(g)).collect();
        let mut search = BranchSearch::new(MAX_FULL_UPDATES);
        let general = eq.dofs.n_free < self.krylov_min && eq.ranks.is_none();
        let groups = self.multiplier_groups(eq.dofs, points);
        let transform = if groups.is_empty() {
            Vec::new()
        } else {
            Self::slave_transform(eq)
        };
        let summed = eq.ranks.is_some() && !groups.is_empty();
        let mut k_structure = ks.k_values.expect("requested");
        if summed {
            let d = eq.solver.distributed().expect("a distributed solver");
            d.sum(&mut k_structure)?;
        }
        // An iterative solver solves the guesses only to GUESS_TOL, enough to predict the
        // branches, and the last guess again to its own tolerance (from the loose solution);
        // where that predicts otherwise, the search goes on with accurate solves.
        let (mut loose_ok, mut resolving) = (eq.solver.capabilities().iterative, false);
        loop {
            let mut step = rhs.clone();
            let mut kv = self.guess_tangent(eq, &k_structure, points, &closed, &mut step, summed);
            let none_closed = !points
                .iter()
                .zip(&closed)
                .any(|(p, b)| b.closed && p.can_close());
            let held = self.held && none_closed && (eq.ranks.is_none() || summed);
            if held {
                self.hold_contact_nodes(eq, &mut kv);
            }
            let eliminated = !resolving
                && !groups.is_empty()
                && self
                    .eliminated_solve(eq, &kv, &mut step, &groups, general, &transform, &search)?;
            let loose = !eliminated && loose_ok && !resolving;
            if !eliminated {
                Self::full_solve(eq, kv, &mut step, summed, loose, resolving)?;
            }
            if held {
                reach_first_contact(eq.dofs, points, &mut step);
            }
            let predicted: Vec<Branch> = points
                .iter()
                .map(|p| p.predicts(&local_change(eq.dofs, p, &step)))
                .collect();
            if resolving && closed != predicted {
                // The accurate solve predicts otherwise: the search starts again from here, with
                // accurate solves.
                (resolving, loose_ok) = (false, false);
                search = BranchSearch::new(MAX_FULL_UPDATES);
            }
            // Unlike the condensed step, a cycle keeps the last guess's step here (the first
            // guess's fails on indefinite structural tangents where the last one's converges).
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

    /// A body held by contact alone, in a guess that closes no point, has no Newton step (its
    /// tangent is singular): its contact nodes are held by springs of the size of their
    /// diagonal, so the step moves it a bounded amount along its load and the prediction sees
    /// the points that motion closes (as the condensed step's shift; the next guess, with
    /// them closed, is the true tangent's).
    fn hold_contact_nodes(&self, eq: &Equations, kv: &mut [f64]) {
        let n_disp = eq.dofs.n_free - eq.dofs.n_lambda;
        let pattern = &eq.asm.pattern;
        let mut eqs: Vec<usize> = self
            .slot_nodes
            .iter()
            .flat_map(|&n| eq.dofs.node_dofs[n].iter().map(|&(_, c)| c))
            .flat_map(|c| eq.dofs.entries(c).map(|(e, _)| e).collect::<Vec<_>>())
            .filter(|&e| e < n_disp)
            .collect();
        eqs.sort_unstable();
        eqs.dedup();
        let alpha = super::condensed::mean_diagonal(pattern, kv, &eqs);
        for &e in &eqs {
            kv[pattern.position(e, e)] += alpha;
        }
    }

    /// The full tangent of a guess `closed` of the branches: the bodies' `k_structure` with
    /// every point's branch tangent; the residual change of the points whose branch differs
    /// from their current one into `step`.
    fn guess_tangent(
        &self,
        eq: &Equations,
        k_structure: &[f64],
        points: &[SlotLinearization],
        closed: &[Branch],
        step: &mut [f64],
        summed: bool,
    ) -> Vec<f64> {
        let nf = eq.dofs.n_free;
        let mut kv = k_structure.to_vec();
        let contribs: Vec<Contribution> = points
            .iter()
            .zip(closed)
            .map(|(p, &c)| {
                if let Some(change) = p.branch_change(c) {
                    for (&code, d) in p.codes.iter().zip(change) {
                        for (e, w) in eq.dofs.entries(code) {
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
        if summed || eq.adds_contact_tangent() {
            eq.asm.add_tangents(&mut kv, &contribs);
        }
        // Across processes a row is whole only in the sum of the shares.
        if eq.ranks.is_none() || summed {
            pin_empty_multiplier_rows(&eq.asm.pattern, &mut kv, nf - eq.dofs.n_lambda..nf);
        }
        kv
    }

    /// Solve a guess's tangent `kv` with its multipliers eliminated; false where the
    /// elimination does not apply (the caller solves the whole tangent).
    #[allow(clippy::too_many_arguments)]
    fn eliminated_solve(
        &mut self,
        eq: &mut Equations,
        kv: &[f64],
        step: &mut [f64],
        groups: &[Group],
        general: bool,
        transform: &[(usize, usize, f64)],
        search: &BranchSearch<Branch>,
    ) -> Result<bool> {
        let (model, dofs) = (eq.asm.model, eq.dofs);
        let describe = |e: usize| describe_eq(model, dofs, e);
        eq.observer.phase(&Phase::Factorization {
            kind: "tangent, multipliers eliminated",
            unknowns: eq.asm.pattern.n,
        });
        let t = Instant::now();
        let solved = self.eliminate.solve(
            &eq.asm.pattern,
            kv,
            step,
            groups,
            general,
            transform,
            &describe,
        )?;
        eq.times.factor += since(t);
        if solved && search.updates == 0 {
            eq.observer.detail(&format!(
                "multipliers eliminated through the slave rows ({}): {} of {}",
                self.eliminate.method.name(),
                self.eliminate.eliminated,
                self.eliminate.eliminated + self.eliminate.kept
            ));
        }
        Ok(solved)
    }

    /// Solve a guess's whole tangent `kv` for `step` (factorized unless `resolving` the last
    /// guess again); `loose`: to [`GUESS_TOL`] only.
    fn full_solve(
        eq: &mut Equations,
        mut kv: Vec<f64>,
        step: &mut [f64],
        summed: bool,
        loose: bool,
        resolving: bool,
    ) -> Result<()> {
        if !resolving {
            if summed && eq.ranks.is_some_and(|r| r.rank > 0) {
                // The first process gives the summed tangent, the others nothing.
                kv.fill(0.0);
            }
            eq.factorize(&kv, false)?;
        }
        let t = Instant::now();
        if loose {
            eq.solver.set_relative_tolerance(Some(GUESS_TOL));
        }
        let solved = if resolving {
            eq.solver.resolve_in_place(step)
        } else {
            eq.solver.solve_in_place(step)
        };
        if loose {
            eq.solver.set_relative_tolerance(None);
        }
        solved?;
        eq.times.solve += since(t);
        Ok(())
    }
}

/// Give each multiplier among `range` whose row of the tangent `kv` is zero (to round-off of the
/// largest multiplier row) a diagonal of that row's size: a friction traction component along a
/// direction in which every unknown it acts on is held (a slave node on a symmetry plane, whose
/// slip and force along the plane's normal are both fixed) has no equation of its own among the
/// free unknowns, and left so the full tangent is singular. Its residual is zero there (the
/// slip it holds cannot change), so the pinned row keeps it where it is; a tangent without such
/// rows is untouched.
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
