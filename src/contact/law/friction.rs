//! Coulomb friction regularized by a tangential penalty: an elastoplastic return map at each
//! contact point, evaluated in dual arithmetic so that its (unsymmetric) tangent is exact.
//!
//! Glossary (at one contact point, m local unknowns q):
//! * `xs` the contact node, `xa` the anchor: the master's material point the node stuck to at the
//!   end of the last converged step (its history), moving with the master;
//! * `n` the unit force direction of the normal contact, P = I − n ⊗ n;
//! * g_T = P (xs − xa) the elastic slip, f = ε_T g_T its trial force;
//! * `pn` the normal contact force (≥ 0 in compression).
//!
//! Stick, |f| ≤ μ·pn: the force on the node is −f. Slip: −μ·pn·g_T/|g_T|, and the anchor of the
//! next step is dragged behind the node so that |g_T| = μ·pn/ε_T (the elastic slip that remains).
//! The force is distributed like the normal force (the node, and −c_a on the master nodes at the
//! contact point), and its residual contribution (the internal force) is its negative.

use super::FrictionKinematics;
use crate::contact::dual::{DVec, Dual, Jet};
use crate::model::Friction;

/// The tangential part of a contact point.
pub struct Tangential {
    /// The internal force on the node (the friction force on it is its negative); distributed
    /// like the normal force, it is the point's residual contribution.
    pub vector: DVec,
    /// Stick (else slip).
    pub stick: bool,
    /// Magnitude of the friction force.
    pub force: f64,
    /// Where the anchor would be if the state were converged: unchanged in stick, dragged behind
    /// the node in slip (a spatial point, to be projected on the partner).
    pub next_anchor: [f64; 3],
    /// The force of the other branch at the same state, which the solver's branch search on
    /// the linearized problem takes where it predicts the point to change (see
    /// `contact::point`): in slip the stick force ε_T g_T; in stick, in 2D, the slip force along
    /// the elastic slip. In 2D a slip goes one of two ways, and the search takes this branch
    /// only where the predicted trial force points the elastic slip's way; in 3D the direction
    /// of a slip to come is not known at a stick state, so there is none (offered along the
    /// elastic slip, the predictor of a brick pushed obliquely slid its nodes along the inward
    /// slip of the press and took a Newton iteration more).
    pub other: Option<DVec>,
    /// The trial force ε_T g_T and the slip limit μ·pn: stick while |trial| < limit.
    pub trial: DVec,
    pub limit: Dual,
    /// The slip force per unit normal force, μ·g_T/|g_T| with pn held fixed, where the point
    /// has a slip branch (its own or the other): the part of the slip tangent that scales with
    /// pn (see `contact::point::ContactPoint::hold_force`).
    pub unit_slip: Option<DVec>,
}

impl Tangential {
    /// The friction part of a point's kinematics, with its residual contribution over the local
    /// unknowns.
    /// `jet` takes a dual to the local unknowns, `spread` a force on the node to the residual
    /// over them.
    pub fn kinematics(
        &self,
        dim: usize,
        jet: impl Fn(&Dual) -> Jet,
        spread: impl Fn(&DVec) -> Vec<Jet>,
    ) -> FrictionKinematics {
        FrictionKinematics {
            residual: spread(&self.vector),
            stick: self.stick,
            force: self.force,
            other: self.other.as_ref().map(&spread),
            trial: (0..dim).map(|i| jet(&self.trial[i])).collect(),
            limit: jet(&self.limit),
            unit_slip: self.unit_slip.as_ref().map(spread),
        }
    }
}

/// A closed contact point as friction sees it (see the glossary).
pub struct FrictionPoint {
    pub xs: DVec,
    pub xa: DVec,
    pub n: DVec,
    pub pn: Dual,
    pub dim: usize,
}

/// The friction of a closed contact point.
pub fn evaluate(law: Friction, point: &FrictionPoint) -> Tangential {
    let FrictionPoint { xs, xa, n, pn, dim } = *point;
    let zero = Dual::constant(0.0, xs[0].n);
    let d: Vec<Dual> = (0..dim).map(|i| xs[i] - xa[i]).collect();
    let dn = (0..dim).fold(zero, |acc, i| acc + d[i] * n[i]);
    let mut gt = [zero; 3];
    for i in 0..dim {
        gt[i] = d[i] - n[i] * dn;
    }
    let norm2 = (0..dim).fold(zero, |acc, i| acc + gt[i] * gt[i]);
    let slip_norm = norm2.v.sqrt();
    // At an open point (pn < 0, the closed branch's continuation) this slides with a negative
    // force: the closing point's friction continued linearly, as its normal force is.
    let limit = law.mu * pn.v;
    // A slip within the round-off of the positions it is the difference of has no direction:
    // it sticks. (Taken as a slip at a point that just touches, pn = 0, its tangent μ·∇pn ⊗ ĝ_T
    // would couple the normal motion to the tangential force along a direction that is noise —
    // a node anchored at a parameter that does not round-trip exactly, as 4/7 of an edge, sent
    // the first Newton step of a pressed pair of elastic blocks far off.)
    let resolution = 64.0
        * f64::EPSILON
        * (0..dim)
            .map(|i| xs[i].v.abs().max(xa[i].v.abs()))
            .fold(0.0, f64::max);
    // A point on the slip limit (within 1e-9 of it) slides: the force is the same either way, and
    // a node that slid in the last step starts the next one on it (its elastic slip is the
    // limit's), so taking the slip branch there lets a steady slide go on in one iteration per
    // step instead of starting each step from the stick tangent.
    let stick = law.penalty * slip_norm < limit * (1.0 - 1e-9) || slip_norm <= resolution;
    let mut trial = [zero; 3];
    for i in 0..dim {
        trial[i] = gt[i] * law.penalty;
    }
    let sliding_with = |pn: Dual| {
        let scale = pn * law.mu / norm2.sqrt();
        let mut f = [zero; 3];
        for i in 0..dim {
            f[i] = gt[i] * scale;
        }
        f
    };
    let (f, other, next_anchor);
    if stick {
        f = trial;
        other = (dim == 2 && slip_norm > resolution).then(|| sliding_with(pn));
        next_anchor = std::array::from_fn(|i| if i < dim { xa[i].v } else { 0.0 });
    } else {
        f = sliding_with(pn);
        other = Some(trial);
        // |xs − xa'| tangentially = μ·pn/ε_T, behind the node along the slip.
        let back = limit.max(0.0) / (law.penalty * slip_norm);
        next_anchor = std::array::from_fn(|i| {
            if i < dim {
                xs[i].v - back * gt[i].v
            } else {
                0.0
            }
        });
    }
    let unit_slip = (!stick || other.is_some()).then(|| sliding_with(Dual::constant(1.0, pn.n)));
    let force = (0..dim).map(|i| f[i].v * f[i].v).sum::<f64>().sqrt();
    Tangential {
        vector: f,
        stick,
        force,
        next_anchor,
        other,
        trial,
        limit: pn * law.mu,
        unit_slip,
    }
}
