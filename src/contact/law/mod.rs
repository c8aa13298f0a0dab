//! Contact laws: from the kinematics of one contact point to a local residual and tangent.
//!
//! Glossary (m local displacement unknowns q):
//! * `gap` g(q) with ∇g: the constraint, g < 0 = penetration;
//! * `weight` w(q) ∈ [0, 1]: the share of the node's tributary surface that faces the master
//!   (1 except near the end of an open master);
//! * `b` B(q), length m: how the normal force is shared by the unknowns (the slave node gets the
//!   unit normal n, the master nodes −N_a n); B = ∇g for a closest-point projection, not for a
//!   smoothed normal field or a prescribed normal, so the tangent need not be symmetric.
//!
//! Each law splits its tangent into a material part (B ⊗ ∇g) and a geometric part (force × ∂B),
//! and drops the geometric part while it is large against the bodies' stiffness (see
//! [`Laws::geometric_allowed`]).

pub mod multiplier;
pub mod penalty;

use super::dual::Dual;

/// Kinematics of one contact point.
pub struct PointKinematics {
    pub gap: Dual,
    pub weight: Dual,
    pub b: Vec<Dual>,
}

/// A law's output for one contact point: local residual and row-major tangent (over the m
/// displacement unknowns, plus the multiplier last for multipliers), the normal force (≥ 0 in
/// compression) and whether the point is in contact.
#[derive(Debug, Clone, Default)]
pub struct LawOutcome {
    pub fe: Vec<f64>,
    pub ke: Vec<f64>,
    pub force: f64,
    pub active: bool,
}

/// Settings shared by the laws of a model.
#[derive(Debug, Clone, Copy)]
pub struct Laws {
    /// c of the multipliers' active-set rule λ − c·g > −c·gap_tol (a stiffness).
    pub c: f64,
    /// Gaps smaller than this (a length, from the model size) count as touching.
    pub gap_tol: f64,
    /// Bound on the Frobenius norm of the geometric tangent part (a stiffness).
    pub geometric_limit: f64,
}

impl Laws {
    /// Whether the geometric tangent part `force · ∂v` (v = w·B, or B) is assembled. It is part of
    /// the exact tangent, but far from the solution — a node deep inside a curved master — it is
    /// a large negative stiffness that makes the tangent indefinite and the Newton step useless.
    /// It is kept while |force|·‖∂v‖ stays below the limit (a tenth of the stiffest modulus),
    /// which holds near convergence, where quadratic convergence matters.
    pub fn geometric_allowed(&self, force: f64, v: &[Dual]) -> bool {
        let norm2: f64 = v
            .iter()
            .map(|x| x.grad().iter().map(|d| d * d).sum::<f64>())
            .sum();
        force.abs() * norm2.sqrt() <= self.geometric_limit
    }
}
