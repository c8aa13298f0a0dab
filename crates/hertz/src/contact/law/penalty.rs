//! Penalty law: the force p·w·⟨−g⟩ along B. Closed at g ≤ 0: at g = 0 the force is zero but the
//! tangent is on (as OOFEM), so a body that starts touching under a load has stiffness.
//!
//! Closed branch: r = p·g·v, v = w·B;  K = p·(v ⊗ ∇g + g·∂v) (the second term is the geometric
//! part). At an open point (g > 0) the closed branch is the linear model of the closing force:
//! its value p·g·v (a pull) and the material part only; the solver uses it when it predicts that
//! the point closes within the step. The point also gives its geometric part per unit force
//! ([`Geometric`]), so that the solver can take it with the force of its last Newton step
//! instead of −p·g (see `SlotLinearization::hold_force`). A penalty with friction is solved in the
//! multipliers' form instead (see [`super::multiplier`]).

use super::{linearization, Laws, SlotKinematics};
use crate::contact::slot::{BranchRule, Geometric, SlotLinearization};

/// The factor of [`from_mesh`] in statics and implicit dynamics: the penalty is this many times
/// the stiffness of the softer body under a contact slot, overlaps of 10⁻³ of its strain.
pub const FROM_MESH_FACTOR: f64 = 1e3;

/// How many times the stiffness E·A/h of the elements under its node (10³ times the penalty
/// from the mesh) a node-to-segment penalty must be to be solved with its forces as unknowns
/// (see [`solved_as_multipliers`]).
pub const STIFF_RATIO: f64 = 1e6;

/// Whether a penalty condition of `model` whose slots have the (penalty, stiffness E·A/h of
/// the elements under the node) pairs `penalty_and_stiffness` has its forces as unknowns with
/// the penalty's compliance in their rows (`contact::law::multiplier`; the penalty's
/// solution, λ = −ε·w·g): where one is more than [`STIFF_RATIO`] times stiffer than its
/// elements, outside explicit dynamics (where the penalty sets the stable time step). With the
/// iterate's force −ε·g such a penalty decides each node's branch on gaps at the round-off of
/// the solve: a brick block pressed on a rigid plane by 25 nodes with ε = 1e12 against E·A/h =
/// 250 chattered and failed after 5 halvings (1e10: 7 iterations); in this form 2.
pub fn solved_as_multipliers(
    model: &crate::model::Model,
    mut penalty_and_stiffness: impl Iterator<Item = (f64, f64)>,
) -> bool {
    model.analysis.kind != crate::model::AnalysisKind::NlDEIDynamic
        && penalty_and_stiffness.any(|(p, k)| p > STIFF_RATIO * k)
}

/// The penalty a slot takes from the mesh where its condition gives none, one rule for every
/// formulation: `factor` ([`mesh_factor`]) times E·A/h, E the softer of the slave's modulus at the
/// slot (`slave`, the stiffest element there) and the master's (`master`, infinite for a rigid
/// one), h the distance to the slot's neighbours on its surface (the size of its facets) and A
/// its tributary area for a force per penetration (node-to-segment), 1 for a pressure
/// (mortar): `area_per_h` = A/h.
pub fn from_mesh(slave: f64, master: f64, area_per_h: f64, factor: f64) -> f64 {
    factor * softer(slave, master) * area_per_h
}

/// The factor of [`from_mesh`] in `model`: [`FROM_MESH_FACTOR`], or 1 in explicit dynamics
/// (`NlDEIDynamic`): there a penalty stiffer than the elements shortens the stable time step by
/// its square root and makes the contact nodes bounce on it, each bounce making energy (a rod
/// dropped on a floor left with 3 times its energy at 1e3, kept it within 0.5 % at 1; explicit
/// codes take soft penalties for the same reason).
pub fn mesh_factor(model: &crate::model::Model) -> f64 {
    match model.analysis.kind {
        crate::model::AnalysisKind::NlDEIDynamic => 1.0,
        _ => FROM_MESH_FACTOR,
    }
}

/// The softer of the slave's and the master's modulus (`master` infinite for a rigid one, 0 when
/// unknown): what an overlap strains. A stiff slave (a steel plate) on a soft master (rubber)
/// with its own modulus would get a penalty 10⁴–10⁵ times the rubber's stiffness.
fn softer(slave: f64, master: f64) -> f64 {
    if master > 0.0 {
        slave.min(master)
    } else {
        slave
    }
}

pub fn evaluate(
    laws: &Laws,
    penalty: f64,
    codes: Vec<usize>,
    k: &SlotKinematics,
) -> SlotLinearization {
    let m = k.b.len();
    let g = &k.gap;
    if !(k.weight.v > 0.0) || g.v.is_nan() {
        return linearization(codes, BranchRule::Penalty, &k.gap, None, false);
    }
    let v: Vec<_> = k.b.iter().map(|b| k.weight.product(b)).collect();
    let geometric = g.v < 0.0 && laws.geometric_allowed(penalty * k.weight.v * g.v, k.area);
    let mut ke = vec![0.0; m * m];
    for i in 0..m {
        for j in 0..m {
            let mut kij = v[i].v * g.d[j];
            if geometric {
                kij += g.v * v[i].d[j];
            }
            ke[i * m + j] = penalty * kij;
        }
    }
    let fe: Vec<f64> = v.iter().map(|vi| penalty * g.v * vi.v).collect();
    let geo = Geometric {
        dv: v.iter().flat_map(|vi| vi.d.iter().copied()).collect(),
        force: if geometric { -penalty * g.v } else { 0.0 },
        penalty,
        weight: k.weight.v,
    };
    let mut p = linearization(codes, BranchRule::Penalty, g, Some((fe, ke)), g.v <= 0.0);
    p.geometric = Some(geo);
    p
}
