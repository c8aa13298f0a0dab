//! Mortar segmentation in 3D: where a slave face and a master face overlap, and the integration
//! points of the overlap (Puso–Laursen, Popp et al.).
//!
//! Glossary (one slave face S, one master face M; linear triangles or bilinear quadrilaterals):
//! * auxiliary plane: through the centre c₀ of S, normal n₀ = the unit outward normal of S there,
//!   with an orthonormal basis (e₁, e₂); a point x projects along n₀ to the plane coordinates
//!   p(x) = ((x − c₀)·e₁, (x − c₀)·e₂). The projection is linear, so the face maps of S and M
//!   project to plane maps Σ N_a(ξ) p(x_a) of the same shape functions;
//! * clip polygon: the projected S cut by the projected M (Sutherland–Hodgman; both convex,
//!   turned counter-clockwise), split into triangles (cells) from its area centroid, each
//!   integrated with its signed area by a 7-point rule of degree 5 (exact for the products of
//!   two bilinear shape functions on parallelogram faces);
//! * at a point p of a cell: ξ_S and ξ_M with p(x_S(ξ_S)) = p(x_M(ξ_M)) = p (the inverse plane
//!   maps), ν = −n₀ (towards the slave body), and dA the slave surface's area element:
//!   the cell's plane area times |x_ξ × x_η| / |det ∂p/∂ξ| of S.
//!
//! Written over any [`Scalar`]: in `f64` for the reference segmentation of small deformation, in
//! duals over the two faces' coordinates for the current one of large deformation, where every
//! choice (which vertices survive the clipping) is made on the values and every quantity is
//! differentiated through.

use crate::contact::geometry::faces::{centre, cross, dot, face_normal, shape, sub, FaceKind};
use crate::contact::geometry::scalar::Scalar;

type V3<T> = [T; 3];
type V2<T> = [T; 2];

/// A Newton iteration on face parameters has settled once its step is below this fraction of
/// the parameters' size: at round-off (~1e-14 near a corner, where a parameter is ±1) the steps
/// stop falling, and a tighter bar refused points and whole pairs by turns between iterations.
pub(super) const SETTLED: f64 = 1e-12;

/// One integration point of a slave face against a master face.
#[derive(Debug, Clone)]
pub struct Point<T> {
    /// Shape values of the slave and master faces there (a triangle's fourth is 0).
    pub slave: [T; 4],
    pub master: [T; 4],
    /// Unit vector towards the slave body (−n₀; in self-contact's [`super::mirror`] the bisector
    /// of the two walls' normals): the gap is (x_S − x_M)·ν.
    pub nu: V3<T>,
    /// Quadrature weight times the slave area element.
    pub weight: T,
}

/// The 7-point rule of degree 5 on a triangle (Radon): barycentric a, a, 1 − 2a and weights
/// (summing to 1, of the triangle's area).
fn triangle_rule() -> [([f64; 3], f64); 7] {
    let s = 15f64.sqrt();
    let (a1, w1) = ((6.0 - s) / 21.0, (155.0 - s) / 1200.0);
    let (a2, w2) = ((6.0 + s) / 21.0, (155.0 + s) / 1200.0);
    let t = 1.0 / 3.0;
    [
        ([t, t, t], 9.0 / 40.0),
        ([a1, a1, 1.0 - 2.0 * a1], w1),
        ([a1, 1.0 - 2.0 * a1, a1], w1),
        ([1.0 - 2.0 * a1, a1, a1], w1),
        ([a2, a2, 1.0 - 2.0 * a2], w2),
        ([a2, 1.0 - 2.0 * a2, a2], w2),
        ([1.0 - 2.0 * a2, a2, a2], w2),
    ]
}

/// (b − a) × (p − a) in the plane: > 0 when p lies left of a → b.
fn left<T: Scalar>(a: &V2<T>, b: &V2<T>, p: &V2<T>) -> T {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

/// Twice the signed area of a polygon.
fn area2<T: Scalar>(p: &[V2<T>]) -> T {
    let mut s = p[0][0].cst(0.0);
    for i in 0..p.len() {
        let (a, b) = (&p[i], &p[(i + 1) % p.len()]);
        s = s + a[0] * b[1] - a[1] * b[0];
    }
    s
}

/// The centroid of a polygon's area (of positive area), the centre of the clip polygon's fan of
/// cells: it moves continuously with the polygon, also when a vertex splits in two as a corner
/// crosses an edge. The mean of the vertices jumps there (by a vertex's share), and with it every
/// cell of the fan, so the quadrature of the rational integrands of distorted faces (inverse
/// bilinear maps, area ratios) jumped by its error as a master corner crossed a slave edge.
fn area_centroid<T: Scalar>(p: &[V2<T>]) -> V2<T> {
    let z = p[0][0].cst(0.0);
    let (mut cx, mut cy) = (z, z);
    for i in 0..p.len() {
        let (a, b) = (&p[i], &p[(i + 1) % p.len()]);
        let cross = a[0] * b[1] - a[1] * b[0];
        cx = cx + (a[0] + b[0]) * cross;
        cy = cy + (a[1] + b[1]) * cross;
    }
    let six_area = area2(p) * 3.0;
    [cx / six_area, cy / six_area]
}

/// The part of the convex polygon `subject` inside the convex polygon `clip`, both
/// counter-clockwise (Sutherland–Hodgman).
pub fn clip<T: Scalar>(subject: &[V2<T>], clip: &[V2<T>]) -> Vec<V2<T>> {
    let mut out: Vec<V2<T>> = subject.to_vec();
    for i in 0..clip.len() {
        if out.is_empty() {
            break;
        }
        let (a, b) = (&clip[i], &clip[(i + 1) % clip.len()]);
        // A vertex on the clipping edge's line (to round-off) counts as inside, whatever the
        // rounding: coincident edges (a patch test's boundaries) are then clipped the same way
        // at every iterate and the overlap's derivative does not jump between the two faces.
        let tol = 1e-12 * ((b[0] - a[0]).val().powi(2) + (b[1] - a[1]).val().powi(2));
        let input = std::mem::take(&mut out);
        for k in 0..input.len() {
            let (p, q) = (&input[k], &input[(k + 1) % input.len()]);
            let (sp, sq) = (left(a, b, p), left(a, b, q));
            let (p_in, q_in) = (sp.val() >= -tol, sq.val() >= -tol);
            if p_in {
                out.push(*p);
            }
            if p_in != q_in {
                let t = sp / (sp - sq);
                out.push([p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t]);
            }
        }
    }
    out
}

/// The slave polygon `ps` cut by the master polygon `pm` (of either orientation), counter-
/// clockwise; None where they overlap by less than 1e-12 of the slave's area.
pub(super) fn clipped<T: Scalar>(ps: &[V2<T>], pm: &[V2<T>]) -> Option<Vec<V2<T>>> {
    let ccw = |p: &[V2<T>]| {
        let mut p = p.to_vec();
        if area2(&p).val() < 0.0 {
            p.reverse();
        }
        p
    };
    let slave_poly = ccw(ps);
    let poly = clip(&slave_poly, &ccw(pm));
    (poly.len() >= 3 && area2(&poly).val() > 1e-12 * area2(&slave_poly).val()).then_some(poly)
}

/// The parameters of a face whose projected corners are `s` at the plane point `p`: Newton on
/// the values (a quadrilateral's map is bilinear), then one step in `T` from the root, which
/// makes the derivatives exact; None when the map is degenerate there.
pub(super) fn inverse<T: Scalar>(kind: FaceKind, s: &[V2<T>], p: &V2<T>) -> Option<(T, T)> {
    // One Newton step from (ξ, η): the new (ξ, η) and the step's size.
    fn step<T: Scalar>(
        kind: FaceKind,
        s: &[V2<T>],
        p: &V2<T>,
        xi: T,
        eta: T,
    ) -> Option<(T, T, f64)> {
        let z = xi.cst(0.0);
        let (n, dx, de) = shape(kind, xi, eta);
        let (mut r, mut j) = ([z - p[0], z - p[1]], [[z; 2]; 2]);
        for a in 0..s.len() {
            for i in 0..2 {
                r[i] = r[i] + s[a][i] * n[a];
                j[i][0] = j[i][0] + s[a][i] * dx[a];
                j[i][1] = j[i][1] + s[a][i] * de[a];
            }
        }
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if !(det.val().abs() > 0.0) {
            return None;
        }
        let dxi = (r[0] * j[1][1] - r[1] * j[0][1]) / det;
        let deta = (r[1] * j[0][0] - r[0] * j[1][0]) / det;
        Some((xi - dxi, eta - deta, dxi.val().abs().max(deta.val().abs())))
    }
    let (mut xi, mut eta) = crate::contact::geometry::faces::centre(kind);
    if kind == FaceKind::Quad {
        let sv: Vec<V2<f64>> = s.iter().map(|q| [q[0].val(), q[1].val()]).collect();
        let pv = [p[0].val(), p[1].val()];
        let mut settled = false;
        for _ in 0..40 {
            let (x, e, size) = step(kind, &sv, &pv, xi, eta)?;
            (xi, eta) = (x, e);
            if size < SETTLED * (1.0 + xi.abs() + eta.abs()) {
                settled = true;
                break;
            }
        }
        if !settled {
            return None;
        }
    }
    let z = p[0].cst(0.0);
    step(kind, s, p, z + xi, z + eta).map(|(x, e, _)| (x, e))
}

/// The integration points of slave face `xs` (outward orientation factor `side`) against
/// master face `xm`: empty when their projections do not overlap.
pub fn overlap<T: Scalar>(
    sk: FaceKind,
    xs: &[V3<T>],
    side: f64,
    mk: FaceKind,
    xm: &[V3<T>],
) -> Vec<Point<T>> {
    let z = xs[0][0].cst(0.0);
    let (cx, ce) = centre(sk);
    let (cn, _, _) = shape(sk, z + cx, z + ce);
    let mut c0 = [z; 3];
    for (a, x) in xs.iter().enumerate() {
        for i in 0..3 {
            c0[i] = c0[i] + x[i] * cn[a];
        }
    }
    let n0 = face_normal(sk, xs, side, z + cx, z + ce);
    let d = sub(&xs[1], &xs[0]);
    let t = sub(&d, &n0.map(|v| v * dot(&d, &n0)));
    let len = dot(&t, &t).sqrt();
    let e1 = t.map(|v| v / len);
    let e2 = cross(&n0, &e1);
    let plane = |x: &V3<T>| {
        let r = sub(x, &c0);
        [dot(&r, &e1), dot(&r, &e2)]
    };
    let ps: Vec<V2<T>> = xs.iter().map(plane).collect();
    let pm: Vec<V2<T>> = xm.iter().map(plane).collect();
    let Some(poly) = clipped(&ps, &pm) else {
        return Vec::new();
    };
    let nu = n0.map(|v| -v);
    let mut out = Vec::new();
    for (p, w) in fan_points(&poly) {
        let (Some((xi, eta)), Some((mxi, meta))) = (inverse(sk, &ps, &p), inverse(mk, &pm, &p))
        else {
            continue;
        };
        // dA = |x_ξ × x_η| / |det ∂p/∂ξ| times the plane area.
        let (slave, dx, de) = shape(sk, xi, eta);
        let (mut t1, mut t2) = ([z; 3], [z; 3]);
        let (mut j1, mut j2) = ([z; 2], [z; 2]);
        for a in 0..xs.len() {
            for i in 0..3 {
                t1[i] = t1[i] + xs[a][i] * dx[a];
                t2[i] = t2[i] + xs[a][i] * de[a];
            }
            for i in 0..2 {
                j1[i] = j1[i] + ps[a][i] * dx[a];
                j2[i] = j2[i] + ps[a][i] * de[a];
            }
        }
        let n = cross(&t1, &t2);
        let det = j1[0] * j2[1] - j1[1] * j2[0];
        let ratio = dot(&n, &n).sqrt() / if det.val() < 0.0 { -det } else { det };
        out.push(Point {
            slave,
            master: shape(mk, mxi, meta).0,
            nu,
            weight: ratio * w,
        });
    }
    out
}

/// The quadrature points of a clip polygon `poly` and their weights (plane area): the polygon
/// split into cells from its area centroid, each integrated by the 7-point rule.
///
/// Every cell counts with its signed area, also one of zero or negative area: the tolerant clip
/// repeats a vertex that lies on a clipping line (the vertex itself and the intersection of its
/// edge with the line), and the cell between the two has a round-off area of either sign but a
/// derivative as large as the polygon. Dropping it when not positive dropped that derivative:
/// the tangent of a slave face whose edge lay along a master's (a 3D extrusion's side, a
/// symmetry plane) was off by 10⁴ × its size, and Newton cycled there.
pub(super) fn fan_points<T: Scalar>(poly: &[V2<T>]) -> Vec<(V2<T>, T)> {
    let centroid = area_centroid(poly);
    let mut out = Vec::with_capacity(7 * poly.len());
    for i in 0..poly.len() {
        let (b, c) = (&poly[i], &poly[(i + 1) % poly.len()]);
        let cell = area2(&[centroid, *b, *c]) * 0.5;
        for (l, w) in triangle_rule() {
            let p = [
                centroid[0] * l[0] + b[0] * l[1] + c[0] * l[2],
                centroid[1] * l[0] + b[1] * l[1] + c[1] * l[2],
            ];
            out.push((p, cell * w));
        }
    }
    out
}

/// A quadrature rule over a whole face in its parameters: (ξ, η, weight), the weights summing to
/// the parametric area (a triangle's 7 points of degree 5, a quadrilateral's 3 × 3 Gauss points).
pub fn face_rule(kind: FaceKind) -> Vec<(f64, f64, f64)> {
    match kind.linear() {
        FaceKind::Tri => triangle_rule()
            .into_iter()
            .map(|(l, w)| (l[1], l[2], 0.5 * w))
            .collect(),
        _ => {
            let g = [
                (-(0.6f64).sqrt(), 5.0 / 9.0),
                (0.0, 8.0 / 9.0),
                ((0.6f64).sqrt(), 5.0 / 9.0),
            ];
            g.iter()
                .flat_map(|&(xi, wx)| g.iter().map(move |&(eta, we)| (xi, eta, wx * we)))
                .collect()
        }
    }
}

/// The dual (biorthogonal) basis of a slave face at positions `x`: Φ_a = Σ_b A_ab N_b with
/// ∫ Φ_a N_b dA = δ_ab ∫ N_b dA over the face, A = D M⁻¹ (D = diag ∫ N_a, M = [∫ N_a N_b]).
/// Σ_a Φ_a = 1, so a uniform pressure still gives the consistent forces; a slave node's force
/// is then D_j λ_j along ν, not spread over its neighbours. In `f64`, or in duals where the
/// positions move (large deformation: biorthogonal on the current face).
pub fn dual_basis<T: Scalar>(kind: FaceKind, x: &[[T; 3]]) -> [[T; 4]; 4] {
    let k = x.len();
    let z = x[0][0].cst(0.0);
    let (mut m, mut d) = ([[z; 4]; 4], [z; 4]);
    for (xi, eta, w) in face_rule(kind) {
        let (n, dx, de) = shape(kind, xi, eta);
        let (mut t1, mut t2) = ([z; 3], [z; 3]);
        for a in 0..k {
            for i in 0..3 {
                t1[i] = t1[i] + x[a][i] * dx[a];
                t2[i] = t2[i] + x[a][i] * de[a];
            }
        }
        let c = cross(&t1, &t2);
        let da = dot(&c, &c).sqrt() * w;
        for a in 0..k {
            d[a] = d[a] + da * n[a];
            for b in 0..k {
                m[a][b] = m[a][b] + da * (n[a] * n[b]);
            }
        }
    }
    biorthogonal(&m, &d, k)
}

/// A = D M⁻¹ of a slave facet with k ≤ 4 nodes from its M = [∫ N_a N_b] and D = [∫ N_a]: the
/// coefficients of its dual basis Φ_a = Σ_b A_ab N_b (in `f64`, or in duals where M and D
/// follow the unknowns).
pub fn biorthogonal<T: Scalar>(m: &[[T; 4]; 4], d: &[T; 4], k: usize) -> [[T; 4]; 4] {
    // Solve Mᵀ Aᵀ = D (M symmetric) by Gauss–Jordan on [M | D].
    let zero = d[0].cst(0.0);
    let mut aug = [[zero; 8]; 4];
    for a in 0..k {
        aug[a][..k].copy_from_slice(&m[a][..k]);
        aug[a][4 + a] = d[a];
    }
    for c in 0..k {
        let piv = (c..k)
            .max_by(|&i, &j| aug[i][c].val().abs().total_cmp(&aug[j][c].val().abs()))
            .expect("rows");
        aug.swap(c, piv);
        let p = aug[c][c];
        for v in aug[c].iter_mut() {
            *v = *v / p;
        }
        for r in 0..k {
            if r != c {
                let f = aug[r][c];
                let row = aug[c];
                for (v, w) in aug[r].iter_mut().zip(row) {
                    *v = *v - f * w;
                }
            }
        }
    }
    // aug's right half is M⁻¹ D = (D M⁻¹)ᵀ.
    let mut out = [[zero; 4]; 4];
    for a in 0..k {
        for b in 0..k {
            out[a][b] = aug[b][4 + a];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad(x0: f64, y0: f64, x1: f64, y1: f64, z: f64) -> Vec<[f64; 3]> {
        vec![[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]]
    }

    #[test]
    fn the_dual_basis_is_biorthogonal_and_a_partition_of_unity() {
        let tri = vec![[0.0, 0.0, 0.0], [2.0, 0.1, 0.0], [0.3, 1.5, 0.4]];
        // A skewed, tilted parallelogram (its shape functions are polynomials in the plane, so
        // the segmentation's rule integrates them exactly).
        let quad = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.1, 0.0],
            [2.3, 1.5, 0.4],
            [0.3, 1.4, 0.4],
        ];
        for (kind, x) in [(FaceKind::Tri, tri), (FaceKind::Quad, quad)] {
            let a = dual_basis(kind, &x);
            let k = x.len();
            // Σ_a Φ_a = Σ_b (Σ_a A_ab) N_b = 1.
            for b in 0..k {
                let s: f64 = (0..k).map(|r| a[r][b]).sum();
                assert!((s - 1.0).abs() < 1e-13, "{kind:?} column {b}: {s}");
            }
            // ∫ Φ_a N_b = δ_ab ∫ N_b, by a finer rule than the one that built A.
            let pts = overlap(kind, &x, 1.0, FaceKind::Quad, &{
                // A master face far larger than the slave, below it along its normal.
                let n = face_normal(kind, &x, 1.0, 0.2, 0.2);
                let c = [0.5, 0.5, 0.1];
                let (e1, e2) = ([1.0, 0.0, -n[0] / n[2]], [0.0, 1.0, -n[1] / n[2]]);
                [(-9.0, -9.0), (9.0, -9.0), (9.0, 9.0), (-9.0, 9.0)]
                    .map(|(u, v)| std::array::from_fn(|i| c[i] + u * e1[i] + v * e2[i] + n[i]))
                    .to_vec()
            });
            assert!(!pts.is_empty());
            for r in 0..k {
                for b in 0..k {
                    let phi_n: f64 = pts
                        .iter()
                        .map(|p| {
                            (0..k).map(|c| a[r][c] * p.slave[c]).sum::<f64>()
                                * p.slave[b]
                                * p.weight
                        })
                        .sum();
                    let n_b: f64 = pts.iter().map(|p| p.slave[b] * p.weight).sum();
                    let exact = if r == b { n_b } else { 0.0 };
                    assert!(
                        (phi_n - exact).abs() < 1e-12,
                        "{kind:?} {r} {b}: {phi_n} vs {exact}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_triangle_rule_integrates_quintics_exactly() {
        // ∫ over the unit triangle of x^a y^b = a! b! / (a + b + 2)!.
        let fact = |n: u32| (1..=n).map(f64::from).product::<f64>();
        for a in 0..=5u32 {
            for b in 0..=(5 - a) {
                let sum: f64 = triangle_rule()
                    .iter()
                    .map(|(l, w)| 0.5 * w * l[1].powi(a as i32) * l[2].powi(b as i32))
                    .sum();
                let exact = fact(a) * fact(b) / fact(a + b + 2);
                assert!((sum - exact).abs() < 1e-15, "x^{a} y^{b}: {sum} vs {exact}");
            }
        }
    }

    #[test]
    fn overlapping_squares_integrate_their_common_area_and_shape_moments() {
        // Slave [0, 1]² at z = 0 facing down (side −1 turns x_ξ × x_η = +z outward down),
        // master [0.3, 1.7] × [−0.4, 0.6] just below facing up: the overlap [0.3, 1] × [0, 0.6].
        let xs = quad(0.0, 0.0, 1.0, 1.0, 0.0);
        let xm = quad(0.3, -0.4, 1.7, 0.6, -0.1);
        let pts = overlap(FaceKind::Quad, &xs, -1.0, FaceKind::Quad, &xm);
        let area: f64 = pts.iter().map(|p| p.weight).sum();
        assert!((area - 0.7 * 0.6).abs() < 1e-15, "{area}");
        for p in &pts {
            assert!(
                (p.nu[2] - 1.0).abs() < 1e-15,
                "ν towards the slave body: {:?}",
                p.nu
            );
        }
        // ∫ N_0 (the slave's corner (0, 0)) = ∫ (1 − x)(1 − y) over the overlap.
        let n0: f64 = pts.iter().map(|p| p.slave[0] * p.weight).sum();
        let exact = (0.7 - (1.0 - 0.09) / 2.0) * (0.6 - 0.36 / 2.0);
        assert!((n0 - exact).abs() < 1e-15, "{n0} vs {exact}");
        // Σ_a N_a = 1 on both faces at every point.
        for p in &pts {
            assert!((p.slave.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            assert!((p.master.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        }
        // Disjoint faces give nothing.
        let far = quad(1.5, 1.5, 2.5, 2.5, -0.1);
        assert!(overlap(FaceKind::Quad, &xs, -1.0, FaceKind::Quad, &far).is_empty());
    }

    #[test]
    fn a_triangle_inside_a_tilted_square_keeps_the_triangle_area_on_the_slave() {
        // Slave triangle in the plane z = x, master a large square below it along the slave's
        // normal: the overlap is the whole triangle, and the weights sum to its true area √2/2.
        let xs = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [0.0, 1.0, 0.0]];
        let xm = quad(-2.0, -2.0, 8.0, 3.0, -5.0);
        let pts = overlap(FaceKind::Tri, &xs, -1.0, FaceKind::Quad, &xm);
        let area: f64 = pts.iter().map(|p| p.weight).sum();
        let exact = 0.5 * 2f64.sqrt();
        assert!((area - exact).abs() < 1e-14, "{area} vs {exact}");
    }

    #[test]
    fn the_overlap_quadrature_is_continuous_as_a_master_corner_crosses_a_slave_edge() {
        // A distorted slave quadrilateral and a master square whose corner (0.6, 0.78 + t)
        // crosses the slave's top edge at t = −0.02: the clip polygon gains a vertex there. A
        // rational integrand (shape functions at inverse-mapped points) must integrate to a
        // smooth function of t across it.
        let xs = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.1, 0.0],
            [1.3, 0.9, 0.0],
            [-0.2, 0.6, 0.0],
        ];
        let moment = |t: f64| {
            let y = 0.78 + t;
            let xm = vec![
                [0.6, y - 2.0, -0.1],
                [2.6, y - 2.0, -0.1],
                [2.6, y, -0.1],
                [0.6, y, -0.1],
            ];
            overlap(FaceKind::Quad, &xs, -1.0, FaceKind::Quad, &xm)
                .iter()
                .map(|p| p.weight * p.slave[2] * p.master[3])
                .sum::<f64>()
        };
        // Where does the corner (0.6, y) cross the slave's top edge from (1.3, 0.9) to
        // (−0.2, 0.6)? y = 0.9 − 0.3 (1.3 − 0.6) / 1.5 = 0.76, so t = −0.02.
        let h = 1e-9;
        let (below, at, above) = (moment(-0.02 - h), moment(-0.02), moment(-0.02 + h));
        assert!(at > 0.0);
        // Smooth: the two halves of the central difference agree (a jump of the vertex mean
        // showed as 9e-10 in one of them, 3e-10 each).
        assert!(
            ((above - at) - (at - below)).abs() < 1e-12,
            "jump across the crossing: {below} {at} {above}"
        );
        assert!(
            (above - below).abs() < 1e-7 * at,
            "jump across the crossing: {below} {at} {above}"
        );
    }

    #[test]
    fn a_slave_vertex_on_a_master_edge_keeps_the_overlaps_derivative() {
        // The slave trapezoid (0, 0), (2, 0), (2, 1), (1, 1) against the master [m, 3] × [−1, 3]
        // at m = 1: the slave's vertex (1, 1) lies on the master's edge x = m, and the clip
        // repeats it (as itself and as the intersection of the edge towards (0, 0)). The overlap
        // is the slave right of x = m, of height 1 there on both sides: ∂A/∂m = −1, shared by the
        // x of the master's nodes 0 and 3. The cell between the repeated vertices has zero area
        // but carries that derivative.
        type D = crate::contact::dual::DualN<24>;
        let xs = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        let xm = [
            [1.0, -1.0, -0.1],
            [3.0, -1.0, -0.1],
            [3.0, 3.0, -0.1],
            [1.0, 3.0, -0.1],
        ];
        let x: Vec<[D; 3]> = xs
            .iter()
            .chain(&xm)
            .enumerate()
            .map(|(a, p)| std::array::from_fn(|i| D::variable(p[i], 3 * a + i, 24)))
            .collect();
        let pts = overlap(FaceKind::Quad, &x[..4], -1.0, FaceKind::Quad, &x[4..]);
        let area = pts.iter().fold(D::constant(0.0, 24), |a, p| a + p.weight);
        assert!((area.v - 1.0).abs() < 1e-14, "area {}", area.v);
        // Master nodes 0 and 3 are unknowns 4 and 7 of the pair: their x is 12 and 21.
        let dm = area.d[12] + area.d[21];
        assert!((dm + 1.0).abs() < 1e-12, "∂A/∂m = {dm}");
        // The slave's right edge x = 2 moves the other side: ∂A/∂x = 1.
        let ds = area.d[3] + area.d[6];
        assert!((ds - 1.0).abs() < 1e-12, "∂A/∂x = {ds}");
    }

    /// The bilinear inverse settles on carried polygons of any shape: quadrilaterals in a face's
    /// parameters (corners near ±1) as thin as 1e-3 of their length, skewed and tapered, every
    /// interior point found and mapped back to itself. Newton's last steps there are the
    /// round-off of parameters of size one times the map's condition: a bar of 1e-14 in
    /// absolute terms refused such points (here from a quad 1.3e-3 thin on), [`SETTLED`] is
    /// relative.
    #[test]
    fn thin_skewed_quadrilaterals_invert_at_every_interior_point() {
        let mut rand = crate::testing::uniform(12345);
        let mut checked = 0;
        for _ in 0..400 {
            let thin = 10f64.powf(-3.0 * rand());
            let (c, s) = ((6.3 * rand()).cos(), (6.3 * rand()).sin());
            let taper = 0.9 * rand();
            let skew = 2.0 * rand() - 1.0;
            // The quad [−1, 1] × [−thin, thin], tapered, skewed, rotated and moved off the origin.
            let raw = [
                [-1.0, -thin * (1.0 - taper)],
                [1.0, -thin],
                [1.0 + skew * thin, thin],
                [-1.0 + skew * thin, thin * (1.0 - taper)],
            ];
            let (ox, oy) = (2.0 * rand() - 1.0, 2.0 * rand() - 1.0);
            let map = |p: [f64; 2]| [ox + c * p[0] - s * p[1], oy + s * p[0] + c * p[1]];
            let corners: Vec<V2<f64>> = raw.iter().map(|&p| map(p)).collect();
            for _ in 0..10 {
                let (xi, eta) = (1.8 * rand() - 0.9, 1.8 * rand() - 0.9);
                let (n, _, _) = shape(FaceKind::Quad, xi, eta);
                let p: V2<f64> =
                    std::array::from_fn(|i| (0..4).map(|a| corners[a][i] * n[a]).sum());
                let (u, v) = inverse(FaceKind::Quad, &corners, &p).unwrap_or_else(|| {
                    panic!("refused: thin {thin:e}, taper {taper}, skew {skew}")
                });
                assert!(
                    (u - xi).abs() < 1e-9 && (v - eta).abs() < 1e-9,
                    "({u}, {v}) for ({xi}, {eta}), thin {thin:e}"
                );
                checked += 1;
            }
        }
        assert_eq!(checked, 4000);
    }
}
