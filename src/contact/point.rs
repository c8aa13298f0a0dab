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

use crate::assembly::Contribution;

/// How a point's branch is decided.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PointLaw {
    /// Closed while g ≤ 0.
    Penalty,
    /// Active while λ − c·g > −c·tol; the normal multiplier is the last code, with value
    /// `lambda`, after the `tangential` friction multipliers with values `lambda_t`.
    Multiplier {
        lambda: f64,
        lambda_t: [f64; 3],
        tangential: usize,
        c: f64,
        tol: f64,
    },
}

#[derive(Debug, Clone)]
pub struct ContactPoint {
    /// Location codes of the local displacement unknowns, then (multipliers) the equations of
    /// the friction multipliers, if any, and of the normal multiplier.
    pub codes: Vec<usize>,
    pub law: PointLaw,
    /// Residual and row-major tangent of the closed/active branch, over `codes`. Empty when the
    /// point cannot close (no partner, zero weight).
    pub closed_fe: Vec<f64>,
    pub closed_ke: Vec<f64>,
    /// Gap and its gradient over the displacement codes.
    pub gap: f64,
    pub gap_grad: Vec<f64>,
    /// Branch of the current state.
    pub closed: bool,
}

impl ContactPoint {
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

    /// Residual and tangent of a branch. The open branch is zero for the penalty and λ = 0 (the
    /// rows r_λ = λ, K_λλ = 1, friction multipliers too) for multipliers.
    pub fn branch(&self, closed: bool) -> (Vec<f64>, Vec<f64>) {
        if closed && self.can_close() {
            return (self.closed_fe.clone(), self.closed_ke.clone());
        }
        match self.law {
            PointLaw::Penalty => (Vec::new(), Vec::new()),
            PointLaw::Multiplier {
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

    /// How the local residual changes when the point takes branch `closed` instead of its
    /// current one (over `codes`), if it does.
    pub fn branch_change(&self, closed: bool) -> Option<Vec<f64>> {
        if closed == self.closed {
            return None;
        }
        let (to, _) = self.branch(closed);
        let (from, _) = self.branch(self.closed);
        Some(
            (0..self.codes.len())
                .map(|a| to.get(a).copied().unwrap_or(0.0) - from.get(a).copied().unwrap_or(0.0))
                .collect(),
        )
    }

    /// The contribution of the current state, for the assembler.
    pub fn contribution(&self) -> Contribution {
        let (fe, ke) = self.branch(self.closed);
        Contribution {
            codes: self.codes.clone(),
            fe,
            ke,
        }
    }

    /// Whether the point is closed after a change `dq` of its unknowns (over `codes`), by the
    /// linearization of its gap (and its multiplier).
    pub fn predicts_closed(&self, dq: &[f64]) -> bool {
        if !self.can_close() {
            return false;
        }
        let g = self.gap
            + self
                .gap_grad
                .iter()
                .zip(dq)
                .map(|(a, b)| a * b)
                .sum::<f64>();
        match self.law {
            PointLaw::Penalty => g <= 0.0,
            PointLaw::Multiplier { lambda, c, tol, .. } => {
                let l = lambda + dq[self.codes.len() - 1];
                l - c * g > -c * tol
            }
        }
    }
}
