//! Rigid analytical surfaces: circle (2D) or sphere (3D), line or plane, and the curve
//! y = f(x) of a polynomial. Each has its body on a side fixed by its definition, never by where
//! a node starts (OOFEM decides the side from the initial position: spec §2.4.4, QUIRK 9):
//! * circle/sphere: the body is the disk/ball, or with `cavity` everything outside it;
//! * line/plane: the body is on the side opposite to its normal;
//! * polynomial: the body is below the curve (OOFEM's normal (−f′, 1) points up), or above it
//!   with `bodyabove`.
//!
//! Each function returns the gap g (< 0: the node is inside the body) and the unit normal n that
//! points out of the body, generic over the number type so the search (f64) and the kinematics
//! (duals) share one formula.

use super::scalar::Scalar;

/// Gap and outward normal of a point `x` against a circle/sphere of radius `r` centred at `c`.
pub fn circle<T: Scalar>(x: &[T], c: &[T], r: f64, cavity: bool) -> (T, Vec<T>) {
    let d: Vec<T> = x.iter().zip(c).map(|(a, b)| *a - *b).collect();
    let mut rr = d[0] * d[0];
    for v in &d[1..] {
        rr = rr + *v * *v;
    }
    let dist = rr.sqrt();
    let sign = if cavity { -1.0 } else { 1.0 };
    let n = d.iter().map(|v| *v / dist * sign).collect();
    ((dist - r) * sign, n)
}

/// Gap and normal against the plane through `p` with unit normal `normal` (out of the body).
pub fn plane<T: Scalar>(x: &[T], p: &[T], normal: &[f64]) -> (T, Vec<T>) {
    let mut g = (x[0] - p[0]) * normal[0];
    for i in 1..x.len() {
        g = g + (x[i] - p[i]) * normal[i];
    }
    (g, normal.iter().map(|&v| x[0].cst(v)).collect())
}

/// f(x) = Σ a_i x^(k−1−i) (highest power first) and its first two derivatives.
pub fn poly<T: Scalar>(a: &[f64], x: T) -> (T, T, T) {
    let zero = x.cst(0.0);
    let (mut f, mut f1, mut f2) = (zero, zero, zero);
    for &c in a {
        // Horner: f = f·x + c, f' = f'·x + f, f'' = f''·x + 2 f'
        f2 = f2 * x + f1 * 2.0;
        f1 = f1 * x + f;
        f = f * x + c;
    }
    (f, f1, f2)
}

/// φ'(t) and φ''(t) of φ(t) = ½|(t, f(t)) − x|²: the closest point of the curve has φ' = 0.
fn poly_residual<T: Scalar>(a: &[f64], x: &[T], t: T) -> (T, T) {
    let (f, f1, f2) = poly(a, t);
    (
        (t - x[0]) + (f - x[1]) * f1,
        f1 * f1 + (f - x[1]) * f2 + 1.0,
    )
}

/// Abscissa of the point of y = f(x) closest to `x` (Newton from x's abscissa), if it converges
/// to a minimum.
pub fn project_on_poly(a: &[f64], x: [f64; 2]) -> Option<f64> {
    let mut t = x[0];
    let mut last = f64::INFINITY;
    for _ in 0..60 {
        let (g, h) = poly_residual(a, &x, t);
        if !(h.abs() > 1e-300) {
            return None;
        }
        let step = g / h;
        t -= step;
        last = step.abs();
        if last <= 1e-14 * (1.0 + t.abs()) {
            break;
        }
    }
    // Steps that stall at round-off have settled too.
    (last < 1e-10 * (1.0 + t.abs()) && poly_residual(a, &x, t).1 > 0.0).then_some(t)
}

/// Gap and normal against the polynomial curve, with the closest abscissa `t0` converged in plain
/// numbers; for duals one Newton step from it makes the derivatives of the contact point exact.
pub fn polynomial<T: Scalar>(a: &[f64], x: &[T], t0: f64, body_above: bool) -> (T, Vec<T>) {
    let t = x[0].cst(t0);
    let (g, h) = poly_residual(a, x, t);
    let t = t - g / h;
    let (f, f1, _) = poly(a, t);
    let len = (f1 * f1 + 1.0).sqrt();
    let sign = if body_above { -1.0 } else { 1.0 };
    let n = vec![-f1 / len * sign, x[0].cst(sign) / len];
    ((x[0] - t) * n[0] + (x[1] - f) * n[1], n)
}
