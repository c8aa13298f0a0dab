//! Contact kinematics: closest-point projection and the signed gap g (g < 0 = penetration) of a
//! node against a partner, computed in [`Jet`] arithmetic so that ∂g/∂q and ∂²g/∂q² are exact.
//!
//! Glossary: `xs` slave node position (current), `x1`, `x2` (and `xm`) segment node positions,
//! `xi` segment parameter, `n` unit normal pointing out of the master body, `side` ±1 chosen so that
//! the allowed side of a rigid surface is the one the node starts on.

use super::jet::{dot, Jet};

/// Closest point on a straight edge: ξ̄ ∈ [0, 1] from x1 to x2 (plain numbers, for the search).
pub fn project_on_line(xs: &[f64], x1: &[f64], x2: &[f64]) -> (f64, f64) {
    let d = xs.len();
    let (mut tt, mut dt) = (0.0, 0.0);
    for i in 0..d {
        let t = x2[i] - x1[i];
        tt += t * t;
        dt += (xs[i] - x1[i]) * t;
    }
    let xi = dt / tt;
    let mut dist2 = 0.0;
    for i in 0..d {
        let xc = x1[i] + xi * (x2[i] - x1[i]);
        dist2 += (xs[i] - xc).powi(2);
    }
    (xi, dist2.sqrt())
}

/// 3-node (quadratic) edge: position and derivatives at ξ ∈ [−1, 1]; nodes (end 1, end 2, middle).
fn quad_edge<T>(x: &[[T; 2]; 3], xi: T) -> ([T; 2], [T; 2], [T; 2])
where
    T: Copy
        + std::ops::Add<Output = T>
        + std::ops::Mul<Output = T>
        + std::ops::Mul<f64, Output = T>
        + std::ops::Sub<f64, Output = T>
        + std::ops::Add<f64, Output = T>
        + std::ops::Neg<Output = T>,
{
    let n = [
        xi * (xi - 1.0) * 0.5,
        xi * (xi + 1.0) * 0.5,
        -(xi * xi) + 1.0,
    ];
    let dn = [xi - 0.5, xi + 0.5, xi * -2.0];
    let mut p = [x[0][0] * n[0], x[0][1] * n[0]];
    let mut t = [x[0][0] * dn[0], x[0][1] * dn[0]];
    let mut c = [x[0][0], x[0][1]];
    for a in 1..3 {
        for i in 0..2 {
            p[i] = p[i] + x[a][i] * n[a];
            t[i] = t[i] + x[a][i] * dn[a];
        }
    }
    // Second derivative: N'' = (1, 1, −2).
    for i in 0..2 {
        c[i] = x[0][i] + x[1][i] + x[2][i] * -2.0;
    }
    (p, t, c)
}

/// Closest point on a quadratic edge by Newton (plain numbers); returns (ξ, distance, converged).
pub fn project_on_quad_edge(xs: [f64; 2], x: &[[f64; 2]; 3]) -> (f64, f64, bool) {
    let (xi0, _) = project_on_line(&xs, &x[0], &x[1]);
    let mut xi = 2.0 * xi0 - 1.0;
    let mut ok = false;
    for _ in 0..30 {
        let (p, t, c) = quad_edge(x, xi);
        let d = [xs[0] - p[0], xs[1] - p[1]];
        let r = d[0] * t[0] + d[1] * t[1];
        let dr = -(t[0] * t[0] + t[1] * t[1]) + d[0] * c[0] + d[1] * c[1];
        if dr.abs() < 1e-300 {
            break;
        }
        let step = r / dr;
        xi -= step;
        if step.abs() < 1e-14 {
            ok = true;
            break;
        }
    }
    let (p, _, _) = quad_edge(x, xi);
    (
        xi,
        ((xs[0] - p[0]).powi(2) + (xs[1] - p[1]).powi(2)).sqrt(),
        ok,
    )
}

/// Rotate a 2D tangent to the normal (t_y, −t_x): outward for a counter-clockwise element.
fn rot(t: [Jet; 2]) -> [Jet; 2] {
    [t[1], -t[0]]
}

/// Gap to a straight edge with the deformed normal (large deformation): the projection ξ(q) and
/// the normal are differentiated exactly.
pub fn gap_line(xs: &[Jet; 2], x1: &[Jet; 2], x2: &[Jet; 2], side: f64) -> Jet {
    let t = [x2[0] - x1[0], x2[1] - x1[1]];
    let d = [xs[0] - x1[0], xs[1] - x1[1]];
    let l2 = dot(&t, &t);
    let xi = dot(&d, &t) / l2;
    let e = [d[0] - xi * t[0], d[1] - xi * t[1]];
    let n = rot(t);
    dot(&e, &n) / l2.sqrt() * side
}

/// Small-deformation gap to a segment: g = n0·(x_s − Σ N_a(ξ) x_a) with the normal n0 and the
/// contact point ξ (shape values `shape`) held fixed — geometrically linear kinematics, so the
/// contact force acts along n0 and is shared by the segment nodes as N_a(ξ).
pub fn gap_linearized(xs: &[Jet], xa: &[Vec<Jet>], shape: &[f64], n0: &[f64]) -> Jet {
    let mut g = xs[0] * n0[0];
    for i in 1..xs.len() {
        g = g + xs[i] * n0[i];
    }
    for (x, &na) in xa.iter().zip(shape) {
        for i in 0..xs.len() {
            g = g - x[i] * (na * n0[i]);
        }
    }
    g
}

/// Gap to a quadratic edge with nodes (end 1, end 2, middle) and the deformed normal, starting
/// the projection at `xi0` (the converged plain-number projection). Two Newton steps in jet
/// arithmetic make the first and second derivatives of the implicit ξ(q) exact.
pub fn gap_quad(xs: &[Jet; 2], x: &[[Jet; 2]; 3], xi0: f64, side: f64) -> Jet {
    let n = xs[0].n;
    let mut xi = Jet::constant(xi0, n);
    for _ in 0..2 {
        let (p, t, c) = quad_edge(x, xi);
        let d = [xs[0] - p[0], xs[1] - p[1]];
        let r = dot(&d, &t);
        let dr = dot(&d, &c) - dot(&t, &t);
        xi = xi - r / dr;
    }
    let (p, t, _) = quad_edge(x, xi);
    let e = [xs[0] - p[0], xs[1] - p[1]];
    let nn = rot(t);
    dot(&e, &nn) / dot(&t, &t).sqrt() * side
}

/// Shape values and tangent dx/dξ of a quadratic edge at ξ (plain numbers).
pub fn quad_edge_shape(x: &[[f64; 2]; 3], xi: f64) -> ([f64; 3], [f64; 2]) {
    let (_, t, _) = quad_edge(x, xi);
    (
        [xi * (xi - 1.0) * 0.5, xi * (xi + 1.0) * 0.5, 1.0 - xi * xi],
        t,
    )
}

/// Gap to a rigid circle/sphere of radius `r` centred at `c` (outside allowed when side = +1).
pub fn gap_circle(xs: &[Jet], c: &[Jet], r: f64, side: f64) -> Jet {
    let d: Vec<Jet> = xs.iter().zip(c).map(|(a, b)| *a - *b).collect();
    (dot(&d, &d).sqrt() - r) * side
}

/// Gap to a rigid plane through `p` with unit normal `n`.
pub fn gap_plane(xs: &[Jet], p: &[Jet], n: &[f64], side: f64) -> Jet {
    let mut g = (xs[0] - p[0]) * n[0];
    for i in 1..xs.len() {
        g = g + (xs[i] - p[i]) * n[i];
    }
    g * side
}

/// y = f(x) = Σ a_i x^(k−1−i) and its first two derivatives, generic over the number type.
fn poly<T>(a: &[f64], x: T, one: T) -> (T, T, T)
where
    T: Copy
        + std::ops::Add<Output = T>
        + std::ops::Mul<Output = T>
        + std::ops::Mul<f64, Output = T>,
{
    let k = a.len();
    let (mut f, mut f1, mut f2) = (one * 0.0, one * 0.0, one * 0.0);
    for (i, &c) in a.iter().enumerate() {
        // Horner: f = f·x + c, f' = f'·x + f, f'' = f''·x + 2 f'
        f2 = f2 * x + f1 * 2.0;
        f1 = f1 * x + f;
        f = f * x + one * c;
        let _ = (i, k);
    }
    (f, f1, f2)
}

/// Closest point on y = f(x) by Newton from x = xs (plain numbers).
pub fn project_on_poly(a: &[f64], xs: [f64; 2]) -> (f64, bool) {
    let mut x = xs[0];
    for _ in 0..60 {
        let (f, f1, f2) = poly(a, x, 1.0);
        let g = (x - xs[0]) + (f - xs[1]) * f1;
        let h = 1.0 + f1 * f1 + (f - xs[1]) * f2;
        if h.abs() < 1e-300 {
            return (x, false);
        }
        let step = g / h;
        x -= step;
        if step.abs() <= 1e-14 * (1.0 + x.abs()) {
            return (x, true);
        }
    }
    (x, false)
}

/// Signed distance to y = f(x) (positive above, normal (−f′, 1)/√(1 + f′²)), times `side`.
pub fn gap_poly(a: &[f64], xs: &[Jet; 2], x0: f64, side: f64) -> Jet {
    let n = xs[0].n;
    let one = Jet::constant(1.0, n);
    let mut x = Jet::constant(x0, n);
    for _ in 0..2 {
        let (f, f1, f2) = poly(a, x, one);
        let g = (x - xs[0]) + (f - xs[1]) * f1;
        let h = f1 * f1 + (f - xs[1]) * f2 + 1.0;
        x = x - g / h;
    }
    let (f, f1, _) = poly(a, x, one);
    let len = (f1 * f1 + 1.0).sqrt();
    ((xs[0] - x) * -f1 + (xs[1] - f)) / len * side
}

/// Plain-number value of the polynomial (for the search and the initial side).
pub fn poly_value(a: &[f64], x: f64) -> (f64, f64) {
    let (f, f1, _) = poly(a, x, 1.0);
    (f, f1)
}
