//! Penalty law: the force p·w·⟨−g⟩ along B. Closed at g ≤ 0: at g = 0 the force is zero but the
//! tangent is on (as OOFEM), so a body that starts touching under a load has stiffness.
//!
//! Closed branch: r = p·g·v, v = w·B;  K = p·(v ⊗ ∇g + g·∂v) (the second term is the geometric
//! part), plus the friction of the point if it has any (see [`super::friction`]). At an open point (g > 0) the closed branch is the linear model of the closing force:
//! its value p·g·v (a pull) and the material part only; the solver uses it when it predicts that
//! the point closes within the step. The point also gives its geometric part per unit force
//! ([`Geometric`]) and, with friction, the slip force's part per unit normal force, so that the
//! solver can take both with the force of its last Newton step instead of −p·g (see
//! `ContactPoint::hold_force`).

use super::{point, Laws, PointKinematics};
use crate::contact::dual::Jet;
use crate::contact::point::{ContactPoint, FrictionBranch, Geometric, PointLaw};

pub fn evaluate(laws: &Laws, penalty: f64, codes: Vec<usize>, k: &PointKinematics) -> ContactPoint {
    let m = k.b.len();
    let g = &k.gap;
    if !(k.weight.v > 0.0) || g.v.is_nan() {
        return point(codes, PointLaw::Penalty, k, None, false);
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
    // Friction, with its exact (unsymmetric) tangent; at an open point its linear continuation.
    // The closed branch with the other friction state too, for the solver's branch search.
    let with = |fe: &[f64], ke: &[f64], r: &[Jet]| {
        let mut fe = fe.to_vec();
        let mut ke = ke.to_vec();
        for i in 0..m {
            fe[i] += r[i].v;
            for j in 0..m {
                ke[i * m + j] += r[i].d[j];
            }
        }
        (fe, ke)
    };
    let Some(fr) = &k.friction else {
        let mut p = point(codes, PointLaw::Penalty, k, Some((fe, ke)), g.v <= 0.0);
        p.geometric = Some(geo);
        return p;
    };
    let (other_fe, other_ke) = match &fr.other {
        Some(r) => with(&fe, &ke, r),
        None => (Vec::new(), Vec::new()),
    };
    let pair = |j: &Jet| (j.v, j.d.clone());
    let branch = FrictionBranch {
        stick: fr.stick,
        other_fe,
        other_ke,
        trial: fr.trial.iter().map(pair).collect(),
        limit: pair(&fr.limit),
        unit_slip_ke: fr.unit_slip.as_ref().map_or_else(Vec::new, |r| {
            r.iter().flat_map(|ri| ri.d.iter().copied()).collect()
        }),
    };
    let mut p = point(
        codes,
        PointLaw::Penalty,
        k,
        Some(with(&fe, &ke, &fr.residual)),
        g.v <= 0.0,
    );
    p.friction = Some(branch);
    p.geometric = Some(geo);
    p
}
