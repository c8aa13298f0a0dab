//! Mortar segmentation of quadratic (curved, 6- and 8-node) faces: of the reference
//! configuration in `f64` (small deformation), of the current one in duals over the two faces'
//! coordinates (large deformation).
//!
//! Each face is split into flat sub-faces through points of the curved face (a 6-node triangle
//! into the 4 triangles of its corners and mid-sides, an 8-node quadrilateral into the 4
//! quadrilaterals of its corners, mid-sides and centre; a linear face is its own sub-face); the
//! sub-faces are segmented pair by pair as linear faces ([`super::segment::overlap`]) and each
//! integration point is carried back to the parameters of the parent faces, where the quadratic
//! shape functions, the curved surfaces' normals and the curved slave's area element are taken
//! (the integration cells of Puso, Laursen & Solberg 2008 and Popp, Wohlmuth, Gee & Wall 2012).
//! The gap is then that of the curved surfaces, not of their facets, which overlap each other by
//! their sagittas.
//!
//! The multipliers' basis: a 6-node triangle's corner functions integrate to 0 and an 8-node
//! quadrilateral's to −A/12, so no dual basis biorthogonal to them carries a force at the
//! corners. Φ_j is made biorthogonal to the modified basis of Wohlmuth, Popp, Gee & Wall (2012,
//! Comput. Mech. 49) instead, N̂_c = N_c + α Σ N_m over the corner's two mid-sides and
//! N̂_m = (1 − 2α) N_m, α = 1/5 ([`modified`]): a partition of unity (a uniform pressure still
//! gives λ_j = p at every node) whose integrals are positive (flat faces: 2A/15 at a triangle's
//! corners and A/5 at its mid-sides, A/20 and A/5 on a quadrilateral), so every slave node has a
//! support D_j = ∫ N̂_j > 0.

use super::segment::{face_rule, overlap};
use crate::contact::geometry::faces::{cross, dot, node_param, shape, shape_values, FaceKind};
use crate::contact::geometry::scalar::Scalar;

type V3<T = f64> = [T; 3];

/// The modified basis' weight of the mid-side functions at the corners.
const ALPHA: f64 = 0.2;

/// One integration point of a slave face against a master face (any of them curved), in `f64`
/// (the reference segmentation) or in duals over the two faces' coordinates (the current one).
#[derive(Debug, Clone)]
pub struct CurvedPoint<T = f64> {
    /// Shape values of the slave and master faces (their node counts; zero past them).
    pub slave: [T; 8],
    pub master: [T; 8],
    /// The slave's modified shape values N̂ ([`modified`]): the multipliers' basis is
    /// biorthogonal to them.
    pub modified: [T; 8],
    /// Unit outward normals of the slave and the master surfaces there.
    pub slave_normal: V3<T>,
    pub master_normal: V3<T>,
    /// Quadrature weight times the curved slave surface's area element.
    pub weight: T,
}

/// A flat sub-face: its linear kind and its vertices' parameters in the parent face.
type SubFace = (FaceKind, Vec<(f64, f64)>);

/// The parameters of the vertices of a face's flat sub-faces, each with its linear kind, in
/// the face's own orientation.
pub fn sub_faces(kind: FaceKind) -> Vec<SubFace> {
    let q = |a: usize| node_param(kind, a);
    // Node indices: corners, then mid-sides (the centre of a quadrilateral: 8).
    let cells: &[&[usize]] = match kind {
        FaceKind::Tri => &[&[0, 1, 2]],
        FaceKind::Quad => &[&[0, 1, 2, 3]],
        FaceKind::Tri6 => &[&[0, 3, 5], &[3, 1, 4], &[5, 4, 2], &[3, 4, 5]],
        FaceKind::Quad8 => &[&[0, 4, 8, 7], &[4, 1, 5, 8], &[8, 5, 2, 6], &[7, 8, 6, 3]],
    };
    cells
        .iter()
        .map(|cell| {
            let v = cell
                .iter()
                .map(|&a| if a == 8 { (0.0, 0.0) } else { q(a) })
                .collect();
            (kind.linear(), v)
        })
        .collect()
}

/// The modified shape values N̂ of a face from its shape values `n` (see the module doc); a
/// linear face's are its own.
pub fn modified<T: Scalar>(kind: FaceKind, n: &[T; 8]) -> [T; 8] {
    let k = match kind {
        FaceKind::Tri6 => 3,
        FaceKind::Quad8 => 4,
        _ => return *n,
    };
    let mut out = *n;
    for c in 0..k {
        // Mid-side c lies between corners c and c + 1.
        out[c] = out[c] + (n[k + c] + n[k + (c + k - 1) % k]) * ALPHA;
        out[k + c] = n[k + c] * (1.0 - 2.0 * ALPHA);
    }
    out
}

/// The rows (node k, node l, T_kl) of the modified basis N̂ = T N over quadratic slave faces
/// (`faces`: kind and node list, corners then mid-sides): a corner's row has 1 at itself and α
/// at each mid-side of its sides, a mid-side's 1 − 2α at itself. A mid-side shared by two faces
/// sits between the same two corners in both, so T is one matrix over the surface.
pub fn transform_rows<'a>(
    faces: impl Iterator<Item = (FaceKind, &'a [usize])>,
) -> Vec<(usize, usize, f64)> {
    let mut rows = std::collections::BTreeSet::new();
    let mut out = Vec::new();
    for (kind, nodes) in faces {
        let k = match kind {
            FaceKind::Tri6 => 3,
            FaceKind::Quad8 => 4,
            _ => continue,
        };
        for c in 0..k {
            let (m, next) = (nodes[k + c], nodes[(c + 1) % k]);
            for (row, col, w) in [
                (nodes[c], nodes[c], 1.0),
                (nodes[c], m, ALPHA),
                (next, m, ALPHA),
                (m, m, 1.0 - 2.0 * ALPHA),
            ] {
                if rows.insert((row, col)) {
                    out.push((row, col, w));
                }
            }
        }
    }
    out
}

/// The point of the face with nodes `x` at parameters (ξ, η), and the surface's tangents there.
fn point_of<T: Scalar>(kind: FaceKind, x: &[V3<T>], xi: T, eta: T) -> (V3<T>, V3<T>, V3<T>) {
    let (n, dx, de) = shape_values(kind, xi, eta);
    let z = xi.cst(0.0);
    let (mut p, mut t1, mut t2) = ([z; 3], [z; 3], [z; 3]);
    for a in 0..x.len() {
        for i in 0..3 {
            p[i] = p[i] + n[a] * x[a][i];
            t1[i] = t1[i] + dx[a] * x[a][i];
            t2[i] = t2[i] + de[a] * x[a][i];
        }
    }
    (p, t1, t2)
}

/// The parameters in a sub-face's own coordinates of a point with sub-face shape values `s`
/// (a triangle's (N₁, N₂), a quadrilateral's from its bilinear values).
fn sub_params<T: Scalar>(kind: FaceKind, s: &[T; 4]) -> (T, T) {
    match kind {
        FaceKind::Tri => (s[1], s[2]),
        _ => (s[1] + s[2] - s[0] - s[3], s[2] + s[3] - s[0] - s[1]),
    }
}

/// The integration points of slave face (`sk`, nodes `xs`, orientation `side`) against master
/// face (`mk`, nodes `xm`, orientation `mside`), through their flat sub-faces: empty when they
/// do not overlap. In duals every quantity follows the nodes (the sub-faces' vertices are
/// points of the curved faces).
pub fn overlap_curved<T: Scalar>(
    slave: (FaceKind, &[V3<T>], f64),
    master: (FaceKind, &[V3<T>], f64),
) -> Vec<CurvedPoint<T>> {
    let mut out = Vec::new();
    each_curved_point(slave, master, |p| out.push(p));
    out
}

/// [`overlap_curved`]'s points handed to `f` one by one, not collected (in duals of 48 a point
/// is 12 kB).
pub fn each_curved_point<T: Scalar>(
    (sk, xs, side): (FaceKind, &[V3<T>], f64),
    (mk, xm, mside): (FaceKind, &[V3<T>], f64),
    mut f: impl FnMut(CurvedPoint<T>),
) {
    let z = xs[0][0].cst(0.0);
    let vertices = |kind: FaceKind, x: &[V3<T>], params: &[(f64, f64)]| -> Vec<V3<T>> {
        params
            .iter()
            .map(|&(a, b)| point_of(kind, x, z + a, z + b).0)
            .collect()
    };
    // The master's sub-faces with their vertices.
    let masters: Vec<(SubFace, Vec<V3<T>>)> = sub_faces(mk)
        .into_iter()
        .map(|sub| {
            let v = vertices(mk, xm, &sub.1);
            (sub, v)
        })
        .collect();
    // The sub-faces' maps are affine in the parent's parameters.
    let parent = |q: &[(f64, f64)], s: &[T; 4]| {
        (0..q.len()).fold((z, z), |(a, b), v| (a + s[v] * q[v].0, b + s[v] * q[v].1))
    };
    for (ssk, sq) in sub_faces(sk) {
        let sv = vertices(sk, xs, &sq);
        for ((msk, mq), mv) in &masters {
            for p in overlap(ssk, &sv, side, *msk, mv) {
                let (sxi, seta) = parent(&sq, &p.slave);
                let (mxi, meta) = parent(mq, &p.master);
                // p.weight carries the flat sub-face's area element; the curved face's is
                // |x_ξ × x_η| |det ∂ξ/∂ξ_sub| over the sub-face's |y_ξ × y_η|.
                let (a, b) = sub_params(ssk, &p.slave);
                let (_, dx, de) = shape(ssk, a, b);
                let (mut y1, mut y2) = ([z; 3], [z; 3]);
                let (mut q1, mut q2) = ([z; 2], [z; 2]);
                for v in 0..sq.len() {
                    for i in 0..3 {
                        y1[i] = y1[i] + dx[v] * sv[v][i];
                        y2[i] = y2[i] + de[v] * sv[v][i];
                    }
                    q1 = [q1[0] + dx[v] * sq[v].0, q1[1] + dx[v] * sq[v].1];
                    q2 = [q2[0] + de[v] * sq[v].0, q2[1] + de[v] * sq[v].1];
                }
                let flat = cross(&y1, &y2);
                // Each face's shape functions once (in duals they are most of the work).
                let (slave, dxs, des) = shape_values(sk, sxi, seta);
                let (master, dxm, dem) = shape_values(mk, mxi, meta);
                let curved = tangent_cross(xs, &dxs, &des);
                let curved_len = dot(&curved, &curved).sqrt();
                let nm = tangent_cross(xm, &dxm, &dem);
                let nm_len = dot(&nm, &nm).sqrt();
                // The sub-face's parametric map is affine with constant coefficients.
                let det = (q1[0] * q2[1] - q1[1] * q2[0]).val().abs();
                let ratio = curved_len * det / dot(&flat, &flat).sqrt();
                f(CurvedPoint {
                    slave,
                    master,
                    modified: modified(sk, &slave),
                    slave_normal: curved.map(|v| v * side / curved_len),
                    master_normal: nm.map(|v| v * mside / nm_len),
                    weight: p.weight * ratio,
                });
            }
        }
    }
}

/// x_ξ × x_η of the face with nodes `x` from its shape derivatives `dx`, `de`.
fn tangent_cross<T: Scalar>(x: &[V3<T>], dx: &[T; 8], de: &[T; 8]) -> V3<T> {
    let z = dx[0].cst(0.0);
    let (mut t1, mut t2) = ([z; 3], [z; 3]);
    for a in 0..x.len() {
        for i in 0..3 {
            t1[i] = t1[i] + dx[a] * x[a][i];
            t2[i] = t2[i] + de[a] * x[a][i];
        }
    }
    cross(&t1, &t2)
}

/// The inverse of the symmetric positive-definite k × k matrix `m` (k ≤ 8), by Gauss–Jordan.
pub fn inverse(m: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let k = m.len();
    let mut aug: Vec<Vec<f64>> = (0..k)
        .map(|a| {
            let mut row = m[a].clone();
            row.extend((0..k).map(|b| if a == b { 1.0 } else { 0.0 }));
            row
        })
        .collect();
    for c in 0..k {
        let piv = (c..k)
            .max_by(|&i, &j| aug[i][c].abs().total_cmp(&aug[j][c].abs()))
            .expect("rows");
        aug.swap(c, piv);
        let p = aug[c][c];
        if p == 0.0 {
            continue;
        }
        for v in aug[c].iter_mut() {
            *v /= p;
        }
        for r in 0..k {
            if r != c {
                let f = aug[r][c];
                let row = aug[c].clone();
                for (v, w) in aug[r].iter_mut().zip(row) {
                    *v -= f * w;
                }
            }
        }
    }
    aug.into_iter().map(|row| row[k..].to_vec()).collect()
}

/// The coefficients A = D M⁻¹ of the dual basis Φ_a = Σ_b A_ab N̂_b of a slave face with `k`
/// nodes biorthogonal to N̂ over `points` (M = Σ N̂_a N̂_b w, D = Σ N̂_a w).
pub fn dual_coefficients<'a>(
    k: usize,
    points: impl Iterator<Item = &'a CurvedPoint>,
) -> Vec<Vec<f64>> {
    let (mut m, mut d) = (vec![vec![0.0; k]; k], vec![0.0; k]);
    for p in points {
        for a in 0..k {
            d[a] += p.modified[a] * p.weight;
            for b in 0..k {
                m[a][b] += p.modified[a] * p.modified[b] * p.weight;
            }
        }
    }
    let inv = inverse(&m);
    (0..k)
        .map(|a| (0..k).map(|b| d[a] * inv[a][b]).collect())
        .collect()
}

/// ∫ N̂_a dA over a whole face with nodes `x` (curved area element): a slave node's full
/// support from this face.
pub fn supports(kind: FaceKind, x: &[V3]) -> Vec<f64> {
    let mut out = vec![0.0; x.len()];
    for (xi, eta, w) in face_rule(kind) {
        let (_, t1, t2) = point_of(kind, x, xi, eta);
        let c = cross(&t1, &t2);
        let da = w * dot(&c, &c).sqrt();
        let n = modified(kind, &shape_values(kind, xi, eta).0);
        for (s, v) in out.iter_mut().zip(n) {
            *s += v * da;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 6-node triangle and an 8-node quadrilateral on the sphere of radius 2 about the origin
    /// (nodes on the sphere, the faces' normals outward).
    fn on_sphere(kind: FaceKind) -> Vec<V3> {
        let params: Vec<(f64, f64)> = (0..if kind == FaceKind::Tri6 { 6 } else { 8 })
            .map(|a| node_param(kind, a))
            .collect();
        params
            .iter()
            .map(|&(a, b)| {
                let p = [0.3 * a + 0.05 * b, 0.25 * b - 0.04 * a, 2.0];
                let l = dot(&p, &p).sqrt();
                p.map(|v| 2.0 * v / l)
            })
            .collect()
    }

    /// The modified basis is a partition of unity with positive supports on flat faces: 2/15 and
    /// 1/5 of a triangle's area at its corners and mid-sides, 1/20 and 1/5 of a quadrilateral's.
    #[test]
    fn the_modified_basis_has_positive_supports() {
        let tri: Vec<V3> = [
            [0.0, 0.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [0.5, 0.0],
            [0.5, 0.5],
            [0.0, 0.5],
        ]
        .iter()
        .map(|p| [p[0], p[1], 0.0])
        .collect();
        let quad: Vec<V3> = [
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [0.0, 1.0],
            [1.0, 0.0],
            [2.0, 0.5],
            [1.0, 1.0],
            [0.0, 0.5],
        ]
        .iter()
        .map(|p| [p[0], p[1], 0.0])
        .collect();
        for (kind, x, area, corner) in [
            (FaceKind::Tri6, &tri, 0.5, 2.0 / 15.0),
            (FaceKind::Quad8, &quad, 2.0, 1.0 / 20.0),
        ] {
            let s = supports(kind, x);
            let k = kind.corners();
            for (a, v) in s.iter().enumerate() {
                let want = if a < k { corner } else { 0.2 } * area;
                assert!((v - want).abs() < 1e-14, "{kind:?} node {a}: {v} vs {want}");
            }
            for (xi, eta) in [(0.1, 0.2), (0.3, 0.6), (-0.7, 0.4)] {
                let n = modified(kind, &shape_values(kind, xi, eta).0);
                assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            }
        }
    }

    /// A curved face segmented against itself covers its whole curved area (the sub-faces'
    /// cells carried to the curved area element: the sum of the weights equals the face rule's
    /// area to the two rules' quadrature errors, 4e-8, where the flat sub-faces fall short by
    /// 5e-3), every point's slave and master shape values agree (the
    /// same parameters), and the dual basis integrates N̂_b to δ_ab ∫ N̂_b.
    #[test]
    fn a_curved_face_against_itself_covers_its_curved_area() {
        for kind in [FaceKind::Tri6, FaceKind::Quad8] {
            let x = on_sphere(kind);
            let area: f64 = supports(kind, &x).iter().sum();
            // The flat sub-faces' area, below the curved one by their sagittas.
            let flat: f64 = sub_faces(kind)
                .iter()
                .map(|(k, q)| {
                    let v: Vec<V3> = q.iter().map(|&(a, b)| point_of(kind, &x, a, b).0).collect();
                    let (d1, d2) = if *k == FaceKind::Tri {
                        (
                            [0, 1, 2].map(|i| v[1][i] - v[0][i]),
                            [0, 1, 2].map(|i| v[2][i] - v[0][i]),
                        )
                    } else {
                        (
                            [0, 1, 2].map(|i| v[2][i] - v[0][i]),
                            [0, 1, 2].map(|i| v[3][i] - v[1][i]),
                        )
                    };
                    let c = cross(&d1, &d2);
                    0.5 * dot(&c, &c).sqrt()
                })
                .sum();
            let points = overlap_curved((kind, &x, 1.0), (kind, &x, -1.0));
            let covered: f64 = points.iter().map(|p| p.weight).sum();
            assert!(
                (covered / area - 1.0).abs() < 1e-6 && area / flat - 1.0 > 1e-3,
                "{kind:?}: covered {covered}, curved {area}, flat {flat}"
            );
            for p in &points {
                let d = (0..8)
                    .map(|a| (p.slave[a] - p.master[a]).abs())
                    .fold(0.0, f64::max);
                assert!(d < 1e-12, "{kind:?}: shape values differ by {d}");
            }
            let k = x.len();
            let dual = dual_coefficients(k, points.iter());
            for a in 0..k {
                for b in 0..k {
                    let int: f64 = points
                        .iter()
                        .map(|p| {
                            let phi: f64 = (0..k).map(|c| dual[a][c] * p.modified[c]).sum();
                            phi * p.modified[b] * p.weight
                        })
                        .sum();
                    let d: f64 = points.iter().map(|p| p.modified[b] * p.weight).sum();
                    let want = if a == b { d } else { 0.0 };
                    assert!(
                        (int - want).abs() < 1e-12,
                        "{kind:?} Φ_{a} N̂_{b}: {int} vs {want}"
                    );
                }
            }
        }
    }
}
