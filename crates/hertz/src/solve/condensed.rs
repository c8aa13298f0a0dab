//! Newton steps of contact problems, condensed on the contact equations, with every contact
//! point's branch (closed or open) decided on the linearized problem.
//!
//! The structural tangent K_s (elements only) is factorized with the contact candidate equations c
//! (the DOFs of every node a contact point can involve, and the multipliers) eliminated last; the
//! trailing block L₂₂ of its factor gives M = (K_s⁻¹)_cc = (L₂₂L₂₂ᵀ)⁻¹ without further solves.
//! Multiplier rows, empty in K_s, carry a unit diagonal there; a body held by contact alone makes
//! K_s singular, and then every candidate displacement carries a diagonal shift α as well. Both
//! shifts are taken back in the contact part, so the step solves the true tangent (but for a
//! guess that closes no point of such a body, which has no true step: see
//! [`CondensedContact::step`]).
//!
//! A Newton step for a choice of branches: the contact tangent C on the equations A it touches
//! (closed points, shifted equations) and the residual change δ of points whose branch differs from
//! the current one give, with w = K_s⁻¹(r + Pᵀδ) and S_A = (M_AA)⁻¹ (the Schur complement of K_s
//! on A),
//!   (S_A + C) Δu_A = S_A w_A,   f_A = C Δu_A = S_A (w_A − Δu_A),
//!   Δu = w − K_s⁻¹ Pᵀ f_A,
//! one dense system of the size of A and, for the whole step, two sparse solves. (Woodbury's
//! identity in this stiffness form: written with M C it would multiply a large penalty into the
//! round-off of Δu_A.) From Δu_c every
//! point's linearized gap (and multiplier) is predicted; the branches are updated from the
//! prediction and the dense system solved again, until prediction and choice agree (a
//! primal-dual active-set search on the linear model: see `contact::point`).
//!
//! Where the contact candidates are too many for M (a whole face meshed as the contact surface:
//! M is m × m, its inverse m³), the candidates are the nearest points' equations instead, the
//! closed ones first and then by gap, up to half the limit: the cost follows the contact zone,
//! not the surface. A point outside them stays open in the step (its multipliers keep their unit
//! diagonal in K_s', the open row's own tangent); a point outside that is closed or guessed
//! closed makes the caller set the solve up again with it (`solve::newton`).

use super::branches::{BranchSearch, ContactStep, OnCycle};
use super::linear::LinearSolver;
use crate::assembly::{DofMap, Pattern};
use crate::contact::slot::Branch;
use crate::contact::SlotLinearization;
use crate::error::{Error, Result};
use faer::linalg::solvers::{DenseSolveCore, Solve};
use faer::Mat;

/// Largest candidate set handled densely by default (M is m × m; `SolveParams::max_condensed`).
/// Larger models take more ([`default_limit`]).
pub const MAX_CANDIDATES: usize = 3000;

/// The most candidates a model of `unknowns` free equations condenses by default: 3000, or a
/// 64th of the unknowns up to 12 000 (a dense block of 1.2 GB). From 192 000 unknowns the
/// sparse factorization costs far more than the dense block: the 5·10⁵-unknown Hertz sphere's
/// 5 995 candidates were condensed in 147 s and 10 GB, where its full tangent's factorization
/// ran out of 24 GB.
pub fn default_limit(unknowns: usize) -> usize {
    (unknowns / 64).clamp(MAX_CANDIDATES, MAX_DENSE)
}

/// The largest dense block the default limit grows to (1.2 GB): with a model's unknowns, or
/// where the closed points alone need more than the limit (see `solve::contact_step`).
pub const MAX_DENSE: usize = 12_000;

/// Compliance added to the rows of active multipliers in the dense system, relative to the
/// structure's mean compliance on the contact equations (see [`CondensedContact::step`]).
pub const REDUNDANCY_COMPLIANCE: f64 = 1e-10;

/// The mean of the nonzero |K_ee| over the equations `eqs` (at least the smallest positive
/// float): the stiffness of the springs that hold a body held by contact alone.
pub(super) fn mean_diagonal(pattern: &Pattern, values: &[f64], eqs: &[usize]) -> f64 {
    let diag: Vec<f64> = eqs
        .iter()
        .map(|&e| values[pattern.position(e, e)].abs())
        .filter(|v| *v > 0.0)
        .collect();
    (diag.iter().sum::<f64>() / diag.len().max(1) as f64).max(f64::MIN_POSITIVE)
}

/// Largest number of branch updates in one step.
const MAX_BRANCH_UPDATES: usize = 60;

/// A guess of the branch search kept as the step if the search comes back to a guess: its
/// points predicted otherwise, δ − Pᵀ f_A, its branches, and the equation a driven mechanism
/// moves most under it (if it has one).
type Guess = (usize, Vec<f64>, Vec<Branch>, Option<usize>);

pub struct CondensedContact {
    /// The structural tangent's solver, with the candidates last (a Schur-block one).
    base: Box<dyn LinearSolver>,
    /// Position of every free equation among the candidates (usize::MAX if none).
    pos: Vec<usize>,
    /// Candidate equations, in the order of M.
    cand: Vec<usize>,
    /// M = (K_s'⁻¹)_cc, K_s' = K_s + diag(shift).
    m: Mat<f64>,
    /// Diagonal shift of every candidate (1 for multipliers, α or 0 for displacements).
    shift: Vec<f64>,
    /// The multipliers that are not candidates: a unit diagonal in K_s', their open row.
    unit: Vec<usize>,
    /// The candidates are the nearest points' only: open points outside them stay open in the
    /// step (else any point outside them makes the caller set the solve up again).
    partial: bool,
    /// The candidate displacements are shifted: a body is held by contact alone.
    held: bool,
    /// The last S_A = (M_AA)⁻¹ with its A: the guesses of a search often share A (a body held
    /// by contact alone has every candidate in it), and the inverse costs three times the
    /// guess's own solve.
    schur_cache: std::cell::RefCell<Option<(Vec<usize>, Mat<f64>)>>,
}

/// A point's local codes, each as the (candidate position, weight) pairs it stands for.
type PointLocs = Vec<Vec<(usize, f64)>>;

/// One guess of the branch search on the linearized problem: the points, their guessed
/// branches, their candidate positions and branch tangents (open, closed), and (K_s⁻¹ r) on
/// the candidates.
struct Linearized<'g> {
    points: &'g [SlotLinearization],
    closed: &'g [Branch],
    locs: &'g [PointLocs],
    tangents: &'g [[Vec<f64>; 2]],
    wc: &'g [f64],
}

impl CondensedContact {
    /// Factorize K_s (the upper triangle `values` on the symmetric `pattern`) with the candidate
    /// equations `candidates` (displacements and multipliers among `lambdas`) last, by `base`
    /// (a solver with [`crate::solve::linear::Capabilities::schur_block`]). Ok(None) when they
    /// are more than `max` or the factor does not have them as a trailing block (the caller
    /// then factorizes full tangents). `held`: a body is known to be held by contact alone (from
    /// the model's supports, or an earlier set-up found K_s singular), so the candidates are
    /// shifted from the start; else they are where K_s proves singular.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        mut base: Box<dyn LinearSolver>,
        pattern: &Pattern,
        values: &[f64],
        candidates: &[usize],
        lambdas: std::ops::Range<usize>,
        max: usize,
        held: bool,
        describe: &dyn Fn(usize) -> String,
    ) -> Result<Option<Self>> {
        let cand: Vec<usize> = candidates.to_vec();
        let chosen: std::collections::HashSet<usize> = cand.iter().copied().collect();
        let unit: Vec<usize> = lambdas.clone().filter(|e| !chosen.contains(e)).collect();
        if cand.is_empty() || cand.len() > max || !pattern.symmetric {
            return Ok(None);
        }
        base.set_last_block(cand.clone());
        let shift: Vec<f64> = cand
            .iter()
            .map(|e| if lambdas.contains(e) { 1.0 } else { 0.0 })
            .collect();
        let mut cc = CondensedContact {
            base,
            pos: vec![usize::MAX; pattern.n],
            cand,
            m: Mat::zeros(0, 0),
            shift,
            unit,
            partial: false,
            held: false,
            schur_cache: Default::default(),
        };
        let factorized = match held {
            true => Err(Error::Singular(String::new())),
            false => cc.factorize(pattern, values, describe),
        };
        let ok = match factorized {
            Err(Error::Singular(_)) => cc.hold(pattern, values, lambdas, describe)?,
            other => other?,
        };
        Ok(ok.then_some(cc))
    }

    /// Whether the candidate displacements carry the shift of a body held by contact alone.
    pub fn held(&self) -> bool {
        self.held
    }

    /// A body held by contact alone: shift every candidate displacement (the equations outside
    /// `lambdas`) by the mean diagonal of the candidates (a stiffness of the right size) and
    /// factorize K_s' again. Whether a round-off pivot passes the singularity test depends on
    /// the state and on the candidates' order, so once found, a body stays held: regrown
    /// candidates and refactorizations take the shift from the start (the step is exact either
    /// way). Ok(false) as [`Self::factorize`].
    pub fn hold(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        lambdas: std::ops::Range<usize>,
        describe: &dyn Fn(usize) -> String,
    ) -> Result<bool> {
        let alpha = mean_diagonal(pattern, values, &self.cand);
        for (s, e) in self.shift.iter_mut().zip(&self.cand) {
            if !lambdas.contains(e) {
                *s = alpha;
            }
        }
        self.held = true;
        self.base.reset();
        self.factorize(pattern, values, describe)
    }

    /// Factorize K_s' for new K_s values on the same pattern (large deformation) and update M.
    /// Ok(false) when the factor no longer has the trailing block (e.g. an indefinite K_s).
    pub fn factorize(
        &mut self,
        pattern: &Pattern,
        values: &[f64],
        describe: &dyn Fn(usize) -> String,
    ) -> Result<bool> {
        let mut shifted = values.to_vec();
        for (&e, &s) in self.cand.iter().zip(&self.shift) {
            shifted[pattern.position(e, e)] += s;
        }
        for &e in &self.unit {
            shifted[pattern.position(e, e)] += 1.0;
        }
        self.schur_cache.replace(None);
        self.base.factorize(pattern, &shifted, true, describe)?;
        let Some((eqs, l22)) = self.base.trailing_factor_block() else {
            return Ok(false);
        };
        // The factor orders the candidates its own way: M follows that order.
        let old: Vec<usize> = self.cand.clone();
        let shift_of: std::collections::HashMap<usize, f64> = old
            .iter()
            .copied()
            .zip(self.shift.iter().copied())
            .collect();
        self.shift = eqs.iter().map(|e| shift_of[e]).collect();
        self.cand = eqs;
        for (k, &e) in self.cand.iter().enumerate() {
            self.pos[e] = k;
        }
        // M = L₂₂⁻ᵀ L₂₂⁻¹ (the inverse from a Cholesky factor: its lower triangle, mirrored).
        let mdim = self.cand.len();
        let l22 = Mat::<f64>::from_fn(mdim, mdim, |i, j| l22.get(i, j));
        let par = faer::get_global_parallelism();
        let mut m = Mat::<f64>::zeros(mdim, mdim);
        let mut mem = faer::dyn_stack::MemBuffer::new(
            faer::linalg::cholesky::llt::inverse::inverse_scratch::<f64>(mdim, par),
        );
        faer::linalg::cholesky::llt::inverse::inverse(
            m.as_mut(),
            l22.as_ref(),
            par,
            faer::dyn_stack::MemStack::new(&mut mem),
        );
        for j in 0..mdim {
            for i in 0..j {
                m[(i, j)] = m[(j, i)];
            }
        }
        self.m = m;
        Ok(true)
    }

    /// One Newton step for the residual `r` (free equations) with the contact `points` at the
    /// current state: the branches are searched on the linearized problem (see the module docs),
    /// from the first guess `guess`; `cycle` says which guess's step a search that comes back to
    /// a guess returns. Ok(None) if a point touches an equation outside the candidates. A step
    /// that a mechanism makes impossible (a singular tangent whose null motion the load drives)
    /// is an [`Error::Singular`] naming an equation it moves (`describe`).
    pub fn step(
        &mut self,
        r: &[f64],
        points: &[SlotLinearization],
        guess: &[bool],
        dofs: &DofMap,
        cycle: OnCycle,
        describe: &dyn Fn(usize) -> String,
    ) -> Result<Option<ContactStep>> {
        let nf = dofs.n_free;
        // Candidate positions and weights of every point's local codes.
        let Some(locs) = self.candidate_locs(points, guess, dofs) else {
            return Ok(None);
        };
        let mut w = r.to_vec();
        self.base.solve_in_place(&mut w)?;
        let mdim = self.cand.len();
        let wc: Vec<f64> = self.cand.iter().map(|&e| w[e]).collect();
        // Closed or open, of every point.
        let mut closed: Vec<Branch> = points.iter().zip(guess).map(|(p, &g)| p.guess(g)).collect();
        let mut search = BranchSearch::new(MAX_BRANCH_UPDATES);
        // The guess with the fewest points predicted otherwise (the latest of equals), its
        // δ − Pᵀ f_A: the step if the search comes back to a guess.
        let mut best: Option<Guess> = None;
        // Whether a guess without closed points keeps the shift (see below).
        let mut hold = false;
        let shifted = (0..mdim).any(|k| self.shift[k] != 0.0 && !self.is_lambda(k, dofs));
        // The local tangents of every point's branches: open and closed.
        let tangents: Vec<[Vec<f64>; 2]> = points
            .iter()
            .map(|p| [p.branch(p.guess(false)).1, p.branch(p.guess(true)).1])
            .collect();
        loop {
            let none_closed = !(0..points.len()).any(|i| closed[i].closed && points[i].can_close());
            let guess = Linearized {
                points,
                closed: &closed,
                locs: &locs,
                tangents: &tangents,
                wc: &wc,
            };
            let (corr, du_c, mechanism) =
                self.solve_guess(&guess, dofs, hold && none_closed, shifted && !none_closed)?;
            // Predict every point's branch from the linearized step.
            let predicted = predict_branches(points, &locs, &du_c);
            let misses = closed
                .iter()
                .zip(&predicted)
                .filter(|(a, b)| a != b)
                .count();
            // A body held by contact alone whose guess closes no point has no Newton step (its
            // tangent is singular; the solve's round-off sends it anywhere, and its prediction
            // then confirms the guess): solved again with the shifted K_s', the body held by the
            // springs α, the step moves it a bounded amount along its load, and the prediction
            // sees the points that motion closes.
            if misses == 0 && none_closed && !hold && shifted {
                hold = true;
                continue;
            }
            let ended = search.next(&closed, &predicted);
            let better = |b: &(usize, _, _, _)| match cycle {
                OnCycle::FewestMisses => misses <= b.0,
                _ => misses < b.0,
            };
            if cycle != OnCycle::Last && best.as_ref().is_none_or(better) {
                best = Some((misses, corr.clone(), closed.clone(), mechanism));
            }
            if let Some(next) = ended {
                closed = next;
                continue;
            }
            let (corr, closed, mechanism) = match best {
                Some((_, c, g, m)) if search.cycled => (c, g, m),
                _ => (corr, closed, mechanism),
            };
            // The step's own branches leave a body free along a motion its load drives: there
            // is no Newton step, and no smaller load step makes one.
            if let Some(eq) = mechanism {
                return Err(mechanism_error(&describe(eq)));
            }
            return Ok(Some(ContactStep {
                du: self.whole_step(w, &corr, nf)?,
                closed,
                updates: search.updates,
                cycled: search.cycled,
            }));
        }
    }

    /// The dense system of one guess of the branches (`guess`): the contact force increment on
    /// its equations A and the correction δ − Pᵀ f_A of the step on the candidates, the
    /// predicted Δu there, and where `check`, an equation a mechanism the load drives moves;
    /// `hold`: the shifted equations keep their shift (a guess that closes no point of a body
    /// held by contact alone).
    fn solve_guess(
        &self,
        guess: &Linearized,
        dofs: &DofMap,
        hold: bool,
        check: bool,
    ) -> Result<(Vec<f64>, Vec<f64>, Option<usize>)> {
        let mdim = self.cand.len();
        // Equations of the dense system: those of closed points and the shifted ones.
        let (a, in_a) = self.dense_equations(guess.points, guess.closed, guess.locs, dofs);
        let na = a.len();
        let mut c = Mat::<f64>::zeros(na, na);
        for &k in &a {
            if !hold {
                c[(in_a[k], in_a[k])] -= self.shift[k];
            }
        }
        // δ: the residual change of points whose branch differs from their current one, and
        // their tangents on A into C.
        let delta = branch_changes(
            guess.points,
            guess.closed,
            guess.locs,
            guess.tangents,
            &in_a,
            &mut c,
            mdim,
        );
        // Active multipliers may constrain the same motion twice (a node in two conditions
        // on the same surface): their rows of the dense system are then dependent. A
        // compliance 1e-10 times the structure's on their diagonal keeps it regular (the
        // dependent multipliers share the force); only the step is regularized, not the
        // residual, so Newton still converges to the exact constraints.
        self.regularize_redundant(&a, &in_a, &mut c, dofs);
        // w_c = (K_s⁻¹(r + Pᵀδ))_c; on A the stiffness form of Woodbury's identity,
        //   (S_A + C) Δu_A = S_A w_A,  S_A = (M_AA)⁻¹ (the Schur complement of K_s on A),
        // keeps a large penalty from amplifying round-off; the contact force increment is
        // f_A = C Δu_A = S_A (w_A − Δu_A).
        let wc = guess.wc;
        let w_c: Vec<f64> = (0..mdim)
            .map(|k| wc[k] + (0..mdim).map(|j| self.m[(k, j)] * delta[j]).sum::<f64>())
            .collect();
        let (f_a, mechanism) = self.force_increment(&a, &c, &w_c, check);
        // corr = δ − Pᵀ f_A, and the predicted Δu on the candidates.
        let mut corr = delta;
        for i in 0..na {
            corr[a[i]] -= f_a[i];
        }
        let du_c: Vec<f64> = (0..mdim)
            .map(|k| wc[k] + (0..mdim).map(|j| self.m[(k, j)] * corr[j]).sum::<f64>())
            .collect();
        if du_c.iter().any(|v| !v.is_finite()) {
            return Err(Error::Solve(
                "the tangent is singular: a body is held by contact alone and no contact holds it"
                    .into(),
            ));
        }
        Ok((corr, du_c, mechanism))
    }

    /// The whole step from K_s⁻¹ r (`w`) and the correction on the candidates:
    /// Δu = w + K_s⁻¹ (δ − Pᵀ C Δu_A).
    fn whole_step(&mut self, mut w: Vec<f64>, corr: &[f64], nf: usize) -> Result<Vec<f64>> {
        let mut z = vec![0.0; nf];
        for (k, &e) in self.cand.iter().enumerate() {
            z[e] = corr[k];
        }
        self.base.solve_in_place(&mut z)?;
        for (wi, zi) in w.iter_mut().zip(&z) {
            *wi += zi;
        }
        if w.iter().any(|v| !v.is_finite()) {
            return Err(Error::Solve(
                "condensed contact step produced a non-finite update".into(),
            ));
        }
        Ok(w)
    }

    /// S_A = (M_AA)⁻¹, the Schur complement of K_s' on the candidates `a` (positions in M).
    fn schur(&self, a: &[usize]) -> Mat<f64> {
        if let Some((cached, s)) = self.schur_cache.borrow().as_ref() {
            if cached == a {
                return s.clone();
            }
        }
        let na = a.len();
        let m_aa = Mat::<f64>::from_fn(na, na, |i, j| self.m[(a[i], a[j])]);
        let s_a = m_aa.as_ref().partial_piv_lu().inverse();
        self.schur_cache.replace(Some((a.to_vec(), s_a.clone())));
        s_a
    }

    /// Mark the candidates as the nearest points' only (see the module docs).
    pub fn set_partial(&mut self) {
        self.partial = true;
    }

    /// The candidate equations (displacements and multipliers), in the order of M.
    pub fn candidates(&self) -> &[usize] {
        &self.cand
    }

    fn is_lambda(&self, k: usize, dofs: &DofMap) -> bool {
        self.cand[k] >= dofs.n_free - dofs.n_lambda
    }

    /// Each point's local codes as (candidate position, weight) lists; None when a point has
    /// an equation outside the candidates (the condensed system must grow) — where they are
    /// the nearest points' only, a point that is closed or guessed closed; an open point
    /// outside them then gets no entries: it stays open in the step, its linearized gap its
    /// current one.
    fn candidate_locs(
        &self,
        points: &[SlotLinearization],
        guess: &[bool],
        dofs: &DofMap,
    ) -> Option<Vec<PointLocs>> {
        let nf = dofs.n_free;
        let mut locs = Vec::with_capacity(points.len());
        for (i, p) in points.iter().enumerate() {
            let mut l = Vec::with_capacity(p.codes.len());
            let mut outside = false;
            for &code in &p.codes {
                let mut entries = Vec::new();
                for (e, w) in dofs.entries(code) {
                    if e >= nf {
                        continue;
                    }
                    let k = self.pos[e];
                    if k == usize::MAX {
                        outside = true;
                    }
                    entries.push((k, w));
                }
                l.push(entries);
            }
            if outside {
                if !self.partial || closed_or_guessed(points, guess, i) {
                    return None;
                }
                l.iter_mut().for_each(Vec::clear);
            }
            locs.push(l);
        }
        Some(locs)
    }

    /// The candidates of the dense system (the set A): the shifted equations and those of
    /// closed points; and each candidate's place in A (usize::MAX: not in it).
    fn dense_equations(
        &self,
        points: &[SlotLinearization],
        closed: &[Branch],
        locs: &[PointLocs],
        dofs: &DofMap,
    ) -> (Vec<usize>, Vec<usize>) {
        let mut in_a = vec![usize::MAX; self.cand.len()];
        let mut a: Vec<usize> = Vec::new();
        let mut add = |k: usize, a: &mut Vec<usize>| {
            if in_a[k] == usize::MAX {
                in_a[k] = a.len();
                a.push(k);
            }
        };
        for (k, &s) in self.shift.iter().enumerate() {
            if s != 0.0 && !self.is_lambda(k, dofs) {
                add(k, &mut a);
            }
        }
        for (i, l) in locs.iter().enumerate() {
            if closed[i].closed && points[i].can_close() {
                for entries in l {
                    for &(k, _) in entries {
                        add(k, &mut a);
                    }
                }
            }
        }
        (a, in_a)
    }

    /// Active multipliers may constrain the same motion twice (a node in two conditions on the
    /// same surface): their rows of the dense system are then dependent. A compliance 1e-10
    /// times the structure's on their diagonal keeps it regular (the dependent multipliers
    /// share the force); only the step is regularized, not the residual, so Newton still
    /// converges to the exact constraints.
    fn regularize_redundant(&self, a: &[usize], in_a: &[usize], c: &mut Mat<f64>, dofs: &DofMap) {
        let flex: Vec<f64> = a
            .iter()
            .filter(|&&k| !self.is_lambda(k, dofs))
            .map(|&k| self.m[(k, k)])
            .collect();
        if !flex.is_empty() {
            let eps = REDUNDANCY_COMPLIANCE * flex.iter().sum::<f64>() / flex.len() as f64;
            for &k in a {
                if self.is_lambda(k, dofs) {
                    c[(in_a[k], in_a[k])] -= eps;
                }
            }
        }
    }

    /// The contact force increment on A, f_A = S_A (w_A − Δu_A) with (S_A + C) Δu_A = S_A w_A,
    /// S_A = (M_AA)⁻¹; and, if `check`, the candidate along which the dense system leaves a
    /// body free that its load drives (see [`driven_mechanism`]).
    fn force_increment(
        &self,
        a: &[usize],
        c: &Mat<f64>,
        w_c: &[f64],
        check: bool,
    ) -> (Vec<f64>, Option<usize>) {
        let na = a.len();
        let mut f_a = vec![0.0; na];
        let mut mechanism = None;
        if na > 0 {
            let s_a = self.schur(a);
            let w_a = Mat::<f64>::from_fn(na, 1, |i, _| w_c[a[i]]);
            let mut x = &s_a * &w_a;
            let sys = &s_a + c;
            if check {
                // Tested equilibrated: displacement and multiplier rows differ in scale by the
                // stiffness over a node's area (a stiff body's mortar multipliers: 10¹⁹), which
                // must not read as a vanishing pivot, a mechanism.
                let (rows, cols) = equilibrate(sys.as_ref());
                let scaled = Mat::<f64>::from_fn(na, na, |i, j| rows[i] * sys[(i, j)] * cols[j]);
                let b = Mat::<f64>::from_fn(na, 1, |i, _| rows[i] * x[(i, 0)]);
                let lu = scaled.as_ref().partial_piv_lu();
                mechanism =
                    driven_mechanism(scaled.as_ref(), lu.U(), b.col(0)).map(|i| self.cand[a[i]]);
            }
            sys.as_ref().partial_piv_lu().solve_in_place(x.as_mut());
            let diff = Mat::<f64>::from_fn(na, 1, |i, _| w_a[(i, 0)] - x[(i, 0)]);
            let f = &s_a * &diff;
            for i in 0..na {
                f_a[i] = f[(i, 0)];
            }
        }
        (f_a, mechanism)
    }
}

/// The residual change δ of the points whose branch `closed` differs from their current one
/// (over the candidates), their branch tangents (`tangents[i]`: open, closed) added to C on
/// the dense equations (`in_a`).
fn branch_changes(
    points: &[SlotLinearization],
    closed: &[Branch],
    locs: &[PointLocs],
    tangents: &[[Vec<f64>; 2]],
    in_a: &[usize],
    c: &mut Mat<f64>,
    mdim: usize,
) -> Vec<f64> {
    let mut delta = vec![0.0; mdim];
    for (i, l) in locs.iter().enumerate() {
        let ke = &tangents[i][usize::from(closed[i].closed)];
        let nd = l.len();
        if let Some(change) = points[i].branch_change(closed[i]) {
            for (entries, d) in l.iter().zip(change) {
                for &(k, wk) in entries {
                    delta[k] -= wk * d;
                }
            }
        }
        if ke.is_empty() {
            continue;
        }
        for (a_, ea) in l.iter().enumerate() {
            for &(ka, wa) in ea {
                let Some(ia) = (in_a[ka] != usize::MAX).then(|| in_a[ka]) else {
                    continue;
                };
                for (b_, eb) in l.iter().enumerate() {
                    let kab = ke[a_ * nd + b_];
                    if kab == 0.0 {
                        continue;
                    }
                    for &(kb, wb) in eb {
                        if in_a[kb] != usize::MAX {
                            c[(ia, in_a[kb])] += wa * wb * kab;
                        }
                    }
                }
            }
        }
    }
    delta
}

/// Every point's branch after the linearized step `du_c` (over the candidates).
fn predict_branches(points: &[SlotLinearization], locs: &[PointLocs], du_c: &[f64]) -> Vec<Branch> {
    points
        .iter()
        .zip(locs)
        .map(|(p, l)| {
            let dq: Vec<f64> = l
                .iter()
                .map(|entries| entries.iter().map(|&(k, wk)| wk * du_c[k]).sum())
                .collect();
            p.predicts(&dq)
        })
        .collect()
}

/// The step's own branches leave a body free along a motion its load drives (at equation
/// `at`): there is no Newton step, and no smaller load step makes one.
fn mechanism_error(at: &str) -> Error {
    Error::Singular(format!(
        "the tangent with the contact's stiffness is singular at {at}: a mechanism, a \
         motion of a body that contact alone holds which nothing resists (sideways \
         on frictionless contact, or sliding where the tangential load exceeds what \
         friction holds, mu times the normal force), and the load drives it: no \
         equilibrium exists; restrain that motion (a support, a symmetry condition, \
         friction) or lower the tangential load"
    ))
}

/// Row and column scales (r, c) that make every row and column of diag(r) `m` diag(c) have
/// its largest entry near 1 (Ruiz's equilibration, a few sweeps; powers of two, so the scaling
/// itself is exact). An empty row or column keeps the scale 1.
fn equilibrate(m: faer::MatRef<'_, f64>) -> (Vec<f64>, Vec<f64>) {
    let n = m.nrows();
    let (mut r, mut c) = (vec![1.0; n], vec![1.0; n]);
    let pow2 = |x: f64| {
        if x > 0.0 && x.is_finite() {
            x.log2().round().exp2()
        } else {
            1.0
        }
    };
    for _ in 0..8 {
        let mut row_max = vec![0.0f64; n];
        let mut col_max = vec![0.0f64; n];
        for j in 0..n {
            for i in 0..n {
                let v = (r[i] * m[(i, j)] * c[j]).abs();
                row_max[i] = row_max[i].max(v);
                col_max[j] = col_max[j].max(v);
            }
        }
        for i in 0..n {
            r[i] *= pow2(1.0 / row_max[i].sqrt());
            c[i] *= pow2(1.0 / col_max[i].sqrt());
        }
    }
    (r, c)
}

/// Relative size of a pivot below which a dense contact system counts as singular.
const SINGULAR_PIVOT: f64 = 1e-13;

/// Whether the square system `sys` x = `b` has no solution because of a mechanism: `sys` singular
/// (a vanishing pivot) and `b` not orthogonal to its left null vector. Then the index of the
/// unknown the mechanism moves most. `u` is the upper factor of the partial-pivoting LU the caller
/// solves with: a cheap first sign, confirmed by two rank-revealing (full-pivoting) factorizations
/// only when a pivot vanishes there.
fn driven_mechanism(
    sys: faer::MatRef<'_, f64>,
    u: faer::MatRef<'_, f64>,
    b: faer::ColRef<'_, f64>,
) -> Option<usize> {
    let pivots = |u: faer::MatRef<'_, f64>| {
        let d: Vec<f64> = (0..u.nrows()).map(|i| u[(i, i)].abs()).collect();
        let max = d.iter().copied().fold(0.0, f64::max);
        let min = d.iter().copied().fold(f64::INFINITY, f64::min);
        (min, max)
    };
    let (min, max) = pivots(u);
    if !(min <= SINGULAR_PIVOT * max) || max == 0.0 {
        return None;
    }
    let right = null_vector(sys)?;
    let left = null_vector(sys.transpose())?;
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let b: Vec<f64> = (0..b.nrows()).map(|i| b[i]).collect();
    let drive = left.iter().zip(&b).map(|(y, b)| y * b).sum::<f64>().abs();
    if drive <= 1e-8 * norm(&left) * norm(&b) {
        return None;
    }
    (0..right.len()).max_by(|&i, &j| right[i].abs().total_cmp(&right[j].abs()))
}

/// A vector v with `m` v ≈ 0 from a full-pivoting LU whose last pivot vanishes (relative to the
/// first, the largest), or None if no pivot does.
fn null_vector(m: faer::MatRef<'_, f64>) -> Option<Vec<f64>> {
    let n = m.nrows();
    let lu = m.full_piv_lu();
    let u = lu.U();
    if n == 0 || u[(n - 1, n - 1)].abs() > SINGULAR_PIVOT * u[(0, 0)].abs() {
        return None;
    }
    // U w = 0 with w_n = 1: back substitution on the leading block.
    let mut w = vec![0.0; n];
    w[n - 1] = 1.0;
    for i in (0..n - 1).rev() {
        let s: f64 = (i + 1..n).map(|j| u[(i, j)] * w[j]).sum();
        w[i] = -s / u[(i, i)];
    }
    // v = Q w or Q⁻¹ w, whichever the factorization's convention makes the null vector.
    let (fwd, bwd) = lu.Q().arrays();
    let residual = |v: &[f64]| {
        (0..n)
            .map(|i| (0..n).map(|j| m[(i, j)] * v[j]).sum::<f64>().powi(2))
            .sum::<f64>()
    };
    let a: Vec<f64> = (0..n).map(|i| w[fwd[i]]).collect();
    let b: Vec<f64> = (0..n).map(|i| w[bwd[i]]).collect();
    Some(if residual(&a) <= residual(&b) { a } else { b })
}

/// The free equations (displacements and multipliers) of the contact points nearest to closing:
/// every point closed or guessed closed, then the open ones by increasing gap (none without a
/// partner), until `budget` equations are reached.
pub fn nearest_equations(
    points: &[SlotLinearization],
    guess: &[bool],
    dofs: &DofMap,
    budget: usize,
) -> Vec<usize> {
    let must = |i: usize| closed_or_guessed(points, guess, i);
    let mut order: Vec<usize> = (0..points.len())
        .filter(|&i| must(i) || !points[i].gap.is_nan())
        .collect();
    order.sort_by(|&a, &b| {
        must(b)
            .cmp(&must(a))
            .then(points[a].gap.total_cmp(&points[b].gap))
    });
    let mut eqs = std::collections::BTreeSet::new();
    for i in order {
        if !must(i) && eqs.len() >= budget {
            break;
        }
        for &code in &points[i].codes {
            eqs.extend(
                dofs.entries(code)
                    .map(|(e, _)| e)
                    .filter(|&e| e < dofs.n_free),
            );
        }
    }
    eqs.into_iter().collect()
}

/// Whether point `i` is closed now or in the branch search's first guess.
fn closed_or_guessed(points: &[SlotLinearization], guess: &[bool], i: usize) -> bool {
    points[i].closed || guess.get(i).copied().unwrap_or(false)
}
