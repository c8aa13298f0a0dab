//! Lagrange multiplier law (λ > 0 in compression), with a complementarity active set:
//! active while w > 0 and λ − c·g > −c·gap_tol (so a node that touches, g = 0, with no force
//! yet, λ = 0, is active — a body that starts touching under a load is held);
//! * active: r_u = −λ·B, r_λ = −g; K_uu = −λ·∂B (geometric), K_uλ = −B, K_λu = −∇g;
//! * inactive: r_λ = λ, K_λλ = 1 (so λ = 0).
//!
//! The weight w only switches the constraint: in the limit of an infinite penalty, the penalty law
//! holds g = 0 wherever w > 0.

use super::{LawOutcome, Laws, PointKinematics};

pub fn evaluate(laws: &Laws, lambda: f64, k: &PointKinematics) -> LawOutcome {
    let m = k.b.len();
    let mm = m + 1;
    let g = k.gap;
    let mut out = LawOutcome {
        fe: vec![0.0; mm],
        ke: vec![0.0; mm * mm],
        force: 0.0,
        active: false,
    };
    let active = k.weight.v > 0.0 && lambda - laws.c * g.v > -laws.c * laws.gap_tol;
    if !active {
        out.fe[m] = lambda;
        out.ke[m * mm + m] = 1.0;
        return out;
    }
    let geometric = laws.geometric_allowed(lambda, &k.b);
    for i in 0..m {
        out.fe[i] = -lambda * k.b[i].v;
        out.ke[i * mm + m] = -k.b[i].v;
        out.ke[m * mm + i] = -g.d[i];
        if geometric {
            for j in 0..m {
                out.ke[i * mm + j] = -lambda * k.b[i].d[j];
            }
        }
    }
    out.fe[m] = -g.v;
    out.force = lambda;
    out.active = true;
    out
}
