//! Contact laws: from the kinematics of one contact point to a local residual and tangent.
//!
//! Glossary (m local displacement unknowns q):
//! * `gap` g(q) with ∇g: the constraint, g < 0 = penetration;
//! * `weight` w(q) ∈ [0, 1]: the share of the node's tributary surface that faces the master
//!   (1 except near the end of an open master), and `past_end` e(q) there: how far the node is
//!   past the end of w's ramp;
//! * `b` B(q), length m: how the normal force is shared by the unknowns (the slave node gets the
//!   unit normal n, the master nodes −N_a n); B = ∇g for a closest-point projection, not for a
//!   smoothed normal field or a prescribed normal, so the tangent need not be symmetric.
//!
//! Each law splits its tangent into a material part (B ⊗ ∇g) and a geometric part (force × ∂B);
//! the penalty laws drop the geometric part while the iterate is far from any solution (see
//! [`Laws::geometric_allowed`]), the multiplier law keeps it.

pub mod multiplier;
pub mod penalty;

use crate::model::{Enforcement, Friction, PenaltySource};

use super::dual::{Dual, Jet};
use super::slot::{BranchRule, SlotLinearization};

/// A condition's enforcement at one contact slot, its penalty resolved there: what the
/// formulations ask of a law, through these methods (a new law is a variant here and its file).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SlotLaw {
    /// The penalty ε in effect at the slot (force per penetration; per unit area for mortar).
    Penalty(f64),
    Multipliers,
}

impl SlotLaw {
    /// `enforcement` at a slot whose penalty from the mesh is `mesh` (see
    /// [`penalty::from_mesh`]), the penalties weighted by `weight` (upstream OOFEM's count of a
    /// node's slave elements, else 1).
    pub fn resolve(enforcement: Enforcement, mesh: f64, weight: f64) -> SlotLaw {
        match enforcement {
            Enforcement::Penalty(PenaltySource::Given(p)) => SlotLaw::Penalty(p * weight),
            Enforcement::Penalty(PenaltySource::FromMesh) => SlotLaw::Penalty(mesh * weight),
            Enforcement::Multipliers => SlotLaw::Multipliers,
        }
    }

    /// The penalty in effect, 0 for multipliers.
    pub fn penalty(self) -> f64 {
        match self {
            SlotLaw::Penalty(p) => p,
            SlotLaw::Multipliers => 0.0,
        }
    }

    /// The compliance 1/ε of the force in the multipliers' rows (a penalty with its forces as
    /// unknowns), 0 for a hard constraint.
    pub fn compliance(self) -> f64 {
        match self {
            SlotLaw::Penalty(p) => 1.0 / p,
            SlotLaw::Multipliers => 0.0,
        }
    }

    pub fn is_multipliers(self) -> bool {
        self == SlotLaw::Multipliers
    }

    /// The slot's friction: μ and its tangential penalty ε_T (`pt` weighted as the normal one,
    /// or the normal penalty in effect; 0 with multipliers).
    pub fn friction(self, friction: Friction, weight: f64) -> SlotFriction {
        SlotFriction {
            mu: friction.mu,
            penalty: match self {
                SlotLaw::Penalty(p) => friction.penalty.map_or(p, |pt| pt * weight),
                SlotLaw::Multipliers => 0.0,
            },
        }
    }
}

/// A slot's forces as unknowns: their equations (the friction force's components, if any, then
/// the normal force), their current values, the compliance in their rows (1/ε of a penalty in
/// this form, else 0) and whether a displacement code moves with a free equation.
pub struct Forces<'a> {
    pub eqs: std::ops::Range<usize>,
    pub values: &'a [f64],
    pub compliance: f64,
    pub free: &'a dyn Fn(usize) -> bool,
}

impl SlotLaw {
    /// The slot's linearization from its kinematics `kin` over the displacement `codes`: the
    /// penalty law where its forces follow the gap, the multiplier law where they are unknowns
    /// (`forces`; a penalty there with its compliance). With friction, also whether an active
    /// slot sticks and its friction force's magnitude. The one place the formulations reach a
    /// law.
    pub fn evaluate(
        self,
        laws: &Laws,
        codes: Vec<usize>,
        forces: Option<Forces>,
        kin: &SlotKinematics,
    ) -> (SlotLinearization, Option<(bool, f64)>) {
        match (self, forces) {
            (SlotLaw::Penalty(p), None) => (penalty::evaluate(laws, p, codes, kin), None),
            (_, Some(f)) => {
                multiplier::evaluate(laws, f.values, codes, f.eqs, kin, f.compliance, f.free)
            }
            (SlotLaw::Multipliers, None) => unreachable!("multiplier slots have equations"),
        }
    }
}

/// Coulomb friction at one slot: μ and the tangential penalty ε_T in effect (0 with
/// multipliers).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlotFriction {
    pub mu: f64,
    pub penalty: f64,
}

/// Kinematics of one contact point.
pub struct SlotKinematics {
    pub gap: Jet,
    pub weight: Jet,
    pub b: Vec<Jet>,
    /// The node's tributary area (2D: length × thickness), or a floor for isolated nodes.
    pub area: f64,
    /// Near an open boundary of a node-to-segment partner: e, the distance past the far end of
    /// the weight's ramp (w = 0 for e ≥ 0); the multipliers hold max(g, e) = 0.
    pub past_end: Option<Jet>,
    /// Slip of the point (conditions with `friction`: the law's friction multipliers act on it).
    pub slip: Option<SlipKinematics>,
}

/// What the friction of a point with Lagrange multipliers needs from its kinematics.
pub struct SlipKinematics {
    /// x_s − x_a, the node's motion relative to its anchor (dim entries, over the local unknowns).
    pub slip: Vec<Jet>,
    /// The normal n of the contact force (dim entries).
    pub normal: Vec<Jet>,
    /// `share[k]`: the residual over the local unknowns of a unit internal force on the node
    /// along axis k (the node's own entries, and its negative spread over the master).
    pub share: Vec<Vec<Jet>>,
    /// Friction coefficient.
    pub mu: f64,
    /// c_T of the friction law's complementarity function, a stiffness (E·A/h of the elements
    /// under the node): it sets the Newton path, not the solution.
    pub stiffness: f64,
    /// The anchor the node keeps if it sticks (else it is anchored where it is).
    pub kept: crate::contact::Anchor,
    /// 1/ε_T of a penalty solved in multiplier form (else 0), and the anchor a sliding node
    /// leaves: behind it by the elastic slip λ_T/ε_T (node-to-segment; None: where it is).
    pub compliance: f64,
    pub slid: Option<crate::contact::Anchor>,
}

impl SlotKinematics {
    /// Kinematics evaluated in duals over the local unknowns.
    pub fn from_duals(gap: Dual, weight: Dual, b: &[Dual], area: f64) -> SlotKinematics {
        SlotKinematics {
            gap: gap.into(),
            weight: weight.into(),
            b: b.iter().map(|&v| v.into()).collect(),
            area,
            past_end: None,
            slip: None,
        }
    }
}

/// Settings shared by the laws of a model.
#[derive(Debug, Clone, Copy)]
pub struct Laws {
    /// c of the multipliers' active-set rule λ − c·g > −c·gap_tol (a stiffness).
    pub c: f64,
    /// Gaps smaller than this (a length, from the model size) count as touching.
    pub gap_tol: f64,
    /// Contact pressure above which the penalty laws drop the geometric tangent part (the
    /// stiffest modulus).
    pub pressure_limit: f64,
}

impl Laws {
    /// Whether a penalty law assembles the geometric tangent part (force × ∂B). It is part of the
    /// exact tangent, but when an iterate has pushed a node deep into a curved master, the force
    /// there is far beyond anything the bodies can carry, and its geometric stiffness — a large
    /// negative one inside a convex master — makes the Newton step useless. A contact pressure
    /// above the stiffest Young's modulus (a strain of 100 %) marks such an iterate: there the
    /// geometric part is dropped; at any state the bodies can actually reach, the tangent is exact.
    pub fn geometric_allowed(&self, force: f64, area: f64) -> bool {
        force.abs() <= self.pressure_limit * area
    }
}

/// The constraint `gap` the point's rows hold (with its gradient) and the closed branch's
/// (fe, ke) into a [`SlotLinearization`].
fn linearization(
    codes: Vec<usize>,
    rule: BranchRule,
    gap: &Jet,
    closed: Option<(Vec<f64>, Vec<f64>)>,
    closed_now: bool,
) -> SlotLinearization {
    let (closed_fe, closed_ke) = closed.unwrap_or_default();
    SlotLinearization {
        codes,
        rule,
        closed_fe,
        closed_ke,
        gap: gap.v,
        gap_grad: gap.d.clone(),
        closed: closed_now,
        geometric: None,
    }
}

/// Normal force (≥ 0 in compression) of a point in its current branch.
pub fn normal_force(p: &SlotLinearization, k: &SlotKinematics, penalty: f64) -> f64 {
    if !p.closed {
        return 0.0;
    }
    match p.rule {
        BranchRule::Penalty => -penalty * k.weight.v * k.gap.v,
        BranchRule::Multiplier { lambda, .. } => lambda,
    }
}
