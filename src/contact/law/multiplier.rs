//! Lagrange multiplier law (λ > 0 in compression), with a complementarity active set:
//! active while w > 0 and λ − c·g > −c·gap_tol (so a node that touches, g = 0, with no force
//! yet, λ = 0, is active — a body that starts touching under a load is held);
//! * active: r_u = −λ·B, r_λ = −g; K_uu = −λ·∂B (geometric), K_uλ = −B, K_λu = −∇g;
//! * inactive: r_λ = λ, K_λλ = 1 (so λ = 0).
//!
//! The weight w only switches the constraint: in the limit of an infinite penalty, the penalty law
//! holds g = 0 wherever w > 0.

use super::{point, Laws, PointKinematics};
use crate::contact::point::{ContactPoint, PointLaw};

/// `codes`: the displacement codes, then the multiplier's equation.
pub fn evaluate(laws: &Laws, lambda: f64, codes: Vec<usize>, k: &PointKinematics) -> ContactPoint {
    let m = k.b.len();
    let mm = m + 1;
    let g = &k.gap;
    let law = PointLaw::Multiplier {
        lambda,
        c: laws.c,
        tol: laws.gap_tol,
    };
    if !(k.weight.v > 0.0) || g.v.is_nan() {
        return point(codes, law, k, None, false);
    }
    let geometric = laws.geometric_allowed(lambda, k.area);
    let mut fe = vec![0.0; mm];
    let mut ke = vec![0.0; mm * mm];
    for i in 0..m {
        fe[i] = -lambda * k.b[i].v;
        ke[i * mm + m] = -k.b[i].v;
        ke[m * mm + i] = -g.d[i];
        if geometric {
            for j in 0..m {
                ke[i * mm + j] = -lambda * k.b[i].d[j];
            }
        }
    }
    fe[m] = -g.v;
    let active = lambda - laws.c * g.v > -laws.c * laws.gap_tol;
    point(codes, law, k, Some((fe, ke)), active)
}
