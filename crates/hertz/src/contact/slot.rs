//! A contact point as the solver sees it: its unknowns, the residual and tangent of its law's
//! closed (active) branch, and what decides between the closed and the open branch.
//!
//! The contact force is a kink function of the state (zero when open, a smooth function when
//! closed). Newton's method that takes each point's branch from the current iterate can cycle
//! around the kink: a step from a closed state opens a node by a hair, the step from the open
//! state, where the node has no stiffness, pushes it deep inside, and so on. The solver therefore
//! decides the branches on the linearized problem itself: it solves the Newton system for a
//! guess of the branches, predicts every point's gap (and multiplier) from that solution, and
//! repeats until prediction and guess agree (a primal-dual active-set search on the linear model,
//! see `solve::condensed`). Each point provides both branches for that.
//!
//! Friction is not searched there: a condition with friction has its forces as unknowns (with a
//! penalty, its compliance in the multipliers' rows; see `contact::law::multiplier`), and the
//! semismooth Newton method takes stick or slip from the iterate's held forces.
//!
//! A stiff penalty has one more trap: its force −ε·g is the iterate's, and a Newton step along a
//! curved surface leaves a gap error (10⁻³–10⁻² on the shallow ironing die) far above the
//! penetration λ/ε of a penalty from the mesh (10⁻⁶). The parts of the tangent that scale with the
//! force (the geometric part) then carry a force wrong by orders of magnitude. The solver takes them with the force of the last step's linear model instead
//! ([`SlotLinearization::hold_force`]): the Newton step of the penalty with its force as an unknown
//! (a perturbed Lagrangian), which converges to the same solution.

use crate::assembly::Contribution;

/// How a point's branch is decided.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BranchRule {
    /// Closed while g ≤ 0.
    Penalty,
    /// Active while λ − c·(g + compliance·λ) > −c·tol; the normal multiplier is the last code,
    /// with value `lambda`, after the `tangential` friction multipliers with values `lambda_t`.
    /// `compliance` is 1/ε for a penalty solved in multiplier form, else 0.
    Multiplier {
        lambda: f64,
        lambda_t: [f64; 3],
        tangential: usize,
        c: f64,
        compliance: f64,
        tol: f64,
    },
}

#[derive(Debug, Clone)]
pub struct SlotLinearization {
    /// Location codes of the local displacement unknowns, then (multipliers) the equations of
    /// the friction multipliers, if any, and of the normal multiplier.
    pub codes: Vec<usize>,
    pub rule: BranchRule,
    /// Residual and row-major tangent of the closed/active branch, over `codes`. Empty when the
    /// point cannot close (no partner, zero weight).
    pub closed_fe: Vec<f64>,
    pub closed_ke: Vec<f64>,
    /// Gap and its gradient over the displacement codes: the constraint the normal row holds
    /// (a penalty in multiplier form: the weighted gap w·g; multipliers near an open end:
    /// max(g, e), see [`crate::contact::law::multiplier`]).
    pub gap: f64,
    pub gap_grad: Vec<f64>,
    /// Branch of the current state.
    pub closed: bool,
    /// A penalty point's geometric tangent part per unit force (see [`Geometric`]).
    pub geometric: Option<Geometric>,
}

/// The geometric part of a penalty point's closed tangent, −λ̂·∂v (v = w·B, r = −λ̂·v): ∂v over
/// `codes` (row-major), the λ̂ the closed tangent holds now (−ε·g, or 0 where the part is left
/// out: see [`crate::contact::law::Laws::geometric_allowed`]), the penalty ε and the weight w
/// (the normal force is w·λ̂).
#[derive(Debug, Clone)]
pub struct Geometric {
    pub dv: Vec<f64>,
    pub force: f64,
    pub penalty: f64,
    pub weight: f64,
}

/// A value `v` with gradient `d` after a change `dq`, by its linearization.
fn linearized(v: f64, d: &[f64], dq: &[f64]) -> f64 {
    v + d.iter().zip(dq).map(|(a, b)| a * b).sum::<f64>()
}

/// A branch of a contact point: closed or open.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Branch {
    pub closed: bool,
}

impl SlotLinearization {
    /// Take the closed branch away: the point exerts no force (a multiplier is held at zero).
    pub fn disable(&mut self) {
        self.closed_fe.clear();
        self.closed_ke.clear();
        self.closed = false;
    }

    /// Whether the point has a closed branch at all.
    pub fn can_close(&self) -> bool {
        !self.closed_fe.is_empty()
    }

    /// The branch of the current state.
    pub fn current(&self) -> Branch {
        self.guess(self.closed)
    }

    /// Closed or open.
    pub fn guess(&self, closed: bool) -> Branch {
        Branch { closed }
    }

    /// Residual and tangent of a branch. The open branch is zero for the penalty and λ = 0 (the
    /// rows r_λ = λ, K_λλ = 1, friction multipliers too) for multipliers.
    pub fn branch(&self, b: Branch) -> (Vec<f64>, Vec<f64>) {
        if b.closed && self.can_close() {
            return (self.closed_fe.clone(), self.closed_ke.clone());
        }
        match self.rule {
            BranchRule::Penalty => (Vec::new(), Vec::new()),
            BranchRule::Multiplier {
                lambda,
                lambda_t,
                tangential,
                ..
            } => {
                let mm = self.codes.len();
                let mut fe = vec![0.0; mm];
                let mut ke = vec![0.0; mm * mm];
                let first = mm - 1 - tangential;
                fe[first..mm - 1].copy_from_slice(&lambda_t[..tangential]);
                fe[mm - 1] = lambda;
                for k in first..mm {
                    ke[k * mm + k] = 1.0;
                }
                (fe, ke)
            }
        }
    }

    /// How the local residual changes when the point takes branch `b` instead of its current
    /// one (over `codes`), if it does.
    pub fn branch_change(&self, b: Branch) -> Option<Vec<f64>> {
        let now = self.current();
        if b == now {
            return None;
        }
        let (to, _) = self.branch(b);
        let (from, _) = self.branch(now);
        if to == from {
            return None;
        }
        Some(
            (0..self.codes.len())
                .map(|a| to.get(a).copied().unwrap_or(0.0) - from.get(a).copied().unwrap_or(0.0))
                .collect(),
        )
    }

    /// The contribution of the current state, for the assembler.
    pub fn contribution(&self) -> Contribution {
        let (fe, ke) = self.branch(self.current());
        Contribution {
            codes: self.codes.clone(),
            fe,
            ke,
        }
    }

    /// The branch after a change `dq` of its unknowns (over `codes`): closed by the
    /// linearization of its gap (and its multiplier).
    pub fn predicts(&self, dq: &[f64]) -> Branch {
        Branch {
            closed: self.predicts_closed(dq),
        }
    }

    /// The gap after a change `dq` of its unknowns (over `codes`), by its linearization.
    fn linear_gap(&self, dq: &[f64]) -> f64 {
        linearized(self.gap, &self.gap_grad, dq)
    }

    /// The force λ̂ = −ε·g_lin of a penalty point's closed branch after a Newton step that
    /// changed its unknowns by `dq`, by the step's linear model, where that is a compression.
    pub fn held_force(&self, dq: &[f64]) -> Option<f64> {
        let geo = self.geometric.as_ref()?;
        let g = self.linear_gap(dq);
        (self.can_close() && g < 0.0).then(|| -geo.penalty * g)
    }

    /// Take the geometric part of the closed tangent with the held force λ̂ instead of the
    /// iterate's −ε·g: the Newton step of the penalty written with its force as an unknown
    /// (λ̂ + ε·g = 0, a perturbed Lagrangian), whose displacement step is the penalty's but for
    /// this part. Where a step along a curved surface leaves a gap error far above the
    /// penetration λ̂/ε of a stiff penalty, −ε·g is no measure of the force (BENCHMARKS.md,
    /// "Evidence behind design choices").
    pub fn hold_force(&mut self, force: f64) {
        let Some(geo) = &mut self.geometric else {
            return;
        };
        let d = geo.force - force;
        geo.force = force;
        if self.closed_ke.len() == geo.dv.len() {
            for (k, b) in self.closed_ke.iter_mut().zip(&geo.dv) {
                *k += d * b;
            }
        }
    }

    /// Whether the point is closed after a change `dq` of its unknowns (over `codes`), by the
    /// linearization of its gap (and its multiplier).
    fn predicts_closed(&self, dq: &[f64]) -> bool {
        if !self.can_close() {
            return false;
        }
        let g = self.linear_gap(dq);
        match self.rule {
            BranchRule::Penalty => g <= 0.0,
            BranchRule::Multiplier {
                lambda,
                c,
                compliance,
                tol,
                ..
            } => {
                let l = lambda + dq[self.codes.len() - 1];
                l - c * (g + compliance * l) > -c * tol
            }
        }
    }
}
