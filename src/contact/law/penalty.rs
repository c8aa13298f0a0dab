//! Penalty law: the force p·w·⟨−g⟩ along B. Closed at g ≤ 0: at g = 0 the force is zero but the
//! tangent is on (as OOFEM), so a body that starts touching under a load has stiffness.
//!
//! r = p·g·v, v = w·B;  K = p·(v ⊗ ∇g + g·∂v)  (the second term is the geometric part).

use super::{LawOutcome, Laws, PointKinematics};

pub fn evaluate(laws: &Laws, penalty: f64, k: &PointKinematics) -> LawOutcome {
    let m = k.b.len();
    let g = k.gap;
    if !(g.v <= 0.0) || k.weight.v <= 0.0 {
        return LawOutcome::default();
    }
    let v: Vec<_> = k.b.iter().map(|&b| k.weight * b).collect();
    let geometric = laws.geometric_allowed(penalty * g.v, &v);
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
    LawOutcome {
        fe: v.iter().map(|vi| penalty * g.v * vi.v).collect(),
        ke,
        force: -penalty * k.weight.v * g.v,
        active: g.v < 0.0,
    }
}
