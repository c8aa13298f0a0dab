//! Penalty law: the force p·w·⟨−g⟩ along B. Closed at g ≤ 0: at g = 0 the force is zero but the
//! tangent is on (as OOFEM), so a body that starts touching under a load has stiffness.
//!
//! Closed branch: r = p·g·v, v = w·B;  K = p·(v ⊗ ∇g + g·∂v) (the second term is the geometric
//! part). At an open point (g > 0) the closed branch is the linear model of the closing force:
//! its value p·g·v (a pull) and the material part only; the solver uses it when it predicts that
//! the point closes within the step. The point also gives its geometric part per unit force
//! ([`Geometric`]), so that the solver can take it with the force of its last Newton step
//! instead of −p·g (see `ContactPoint::hold_force`). A penalty with friction is solved in the
//! multipliers' form instead (see [`super::multiplier`]).

use super::{point, Laws, PointKinematics};
use crate::contact::point::{BranchRule, ContactPoint, Geometric};

pub fn evaluate(laws: &Laws, penalty: f64, codes: Vec<usize>, k: &PointKinematics) -> ContactPoint {
    let m = k.b.len();
    let g = &k.gap;
    if !(k.weight.v > 0.0) || g.v.is_nan() {
        return point(codes, BranchRule::Penalty, &k.gap, None, false);
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
    let mut p = point(codes, BranchRule::Penalty, g, Some((fe, ke)), g.v <= 0.0);
    p.geometric = Some(geo);
    p
}
