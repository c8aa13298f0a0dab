//! Self-contact's segmentation in 3D: a slave face against a master face of the same surface
//! where the two walls are close (a tube's bore folding shut), along rays that bisect the two
//! walls' normals, so that two walls that mirror each other meet at mirror points along the
//! normal of their mirror plane, from either side: each wall's segmentation, gap and force as a
//! slave are then the mirror images of the other's, and the whole fold equals its half model on
//! the mirror plane. Along the slave's normal alone (the auxiliary plane of
//! [`super::segment`]) a wall inclined to the mirror plane meets the other askew.
//!
//! Glossary (slave face S with nodal normals n_a, master face M with nodal normals m_b, all
//! unit and outward; n(ξ) = normalize(Σ N_a(ξ) n_a) the interpolated normal):
//! * carried corner: master corner y_b taken into the slave's parameters, the ξ where the line
//!   through x(ξ) along m_b − n(ξ) passes through y_b. Neighbouring master faces share their
//!   corners and carry them to one point, so their parts of a slave face tile it (the nodal
//!   normals are the surface's, the same whatever face asks);
//! * clip polygon: the slave's parameter domain cut by the carried master polygon, split into
//!   cells from its area centroid ([`super::segment::fan_points`]);
//! * at a point ξ of a cell: the slave point x(ξ), the master parameters of ξ in the carried
//!   polygon (the master's shape functions over its carried corners), ν = normalize(m − n)
//!   from both faces' interpolated normals (towards the slave body) and dA = |x_ξ × x_η|.
//!
//! Written over any [`Scalar`] like [`super::segment::overlap`]: in `f64` for small deformation,
//! in duals over the faces' coordinates and nodal normals for large.

use super::segment::{clipped, fan_points, inverse, Point, SETTLED};
use crate::contact::dual::DualN;
use crate::contact::geometry::faces::{cross, dot, node_param, shape, sub, FaceKind};
use crate::contact::geometry::scalar::Scalar;

/// A master corner is carried only along a ray whose two normals are more than 60° apart
/// (m·n < 0.5, so |m − n| > 1): walls that face each other, or the sides of a crease's tip
/// against its neighbours (the tip's normal lies along the fold, at most 90° from either
/// wall's), never two tips of one crease (their normals agree).
const APART: f64 = 0.5;

type V3<T> = [T; 3];
type V2<T> = [T; 2];

/// A face's position and interpolated unit normal (from nodal normals `nn`), and its tangents,
/// at (ξ, η).
fn at<T: Scalar>(kind: FaceKind, x: &[V3<T>], nn: &[V3<T>], xi: T, eta: T) -> [V3<T>; 4] {
    let z = xi.cst(0.0);
    let (n, dx, de) = shape(kind, xi, eta);
    let (mut p, mut t1, mut t2, mut nv) = ([z; 3], [z; 3], [z; 3], [z; 3]);
    for a in 0..x.len() {
        for i in 0..3 {
            p[i] = p[i] + x[a][i] * n[a];
            t1[i] = t1[i] + x[a][i] * dx[a];
            t2[i] = t2[i] + x[a][i] * de[a];
            nv[i] = nv[i] + nn[a][i] * n[a];
        }
    }
    let len = dot(&nv, &nv).sqrt();
    [p, nv.map(|v| v / len), t1, t2]
}

/// How far the line through the slave point x(ξ, η) along m − n(ξ, η) misses `y`: (r × d)·x_ξ
/// and (r × d)·x_η, r = y − x, both zero on the line (d is no tangent of the slave).
fn miss<T: Scalar>(
    kind: FaceKind,
    (xs, ns): (&[V3<T>], &[V3<T>]),
    (y, m): (&V3<T>, &V3<T>),
    xi: T,
    eta: T,
) -> [T; 2] {
    let [x, n, t1, t2] = at(kind, xs, ns, xi, eta);
    let c = cross(&sub(y, &x), &sub(m, &n));
    [dot(&c, &t1), dot(&c, &t2)]
}

/// The slave parameters master corner `y` (nodal normal `m`) is carried to: Newton on the values
/// from the face's centre, then one step in `T` from the root, which makes its derivatives
/// exact; None when the rays do not settle (a corner far round the surface) or their two normals
/// are not [`APART`] where they do.
fn carry<T: Scalar>(
    kind: FaceKind,
    slave: (&[V3<T>], &[V3<T>]),
    (y, m): (&V3<T>, &V3<T>),
) -> Option<V2<T>> {
    type D2 = DualN<2>;
    let value = |v: &[V3<T>]| -> Vec<V3<D2>> {
        v.iter()
            .map(|p| p.map(|c| D2::constant(c.val(), 2)))
            .collect()
    };
    let (xs, ns) = (value(slave.0), value(slave.1));
    let (yv, mv) = (value(&[*y])[0], value(&[*m])[0]);
    let (mut xi, mut eta) = crate::contact::geometry::faces::centre(kind);
    let mut jac = [[0.0; 2]; 2];
    let mut settled = false;
    for _ in 0..30 {
        let f = miss(
            kind,
            (&xs, &ns),
            (&yv, &mv),
            D2::variable(xi, 0, 2),
            D2::variable(eta, 1, 2),
        );
        jac = [[f[0].d[0], f[0].d[1]], [f[1].d[0], f[1].d[1]]];
        let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
        if !(det.abs() > 0.0) {
            return None;
        }
        let dxi = (f[0].v * jac[1][1] - f[1].v * jac[0][1]) / det;
        let deta = (f[1].v * jac[0][0] - f[0].v * jac[1][0]) / det;
        xi -= dxi;
        eta -= deta;
        // Beyond a few faces' reach the carried polygon means nothing.
        if !(xi.abs() < 20.0 && eta.abs() < 20.0) {
            return None;
        }
        if dxi.abs().max(deta.abs()) < SETTLED * (1.0 + xi.abs() + eta.abs()) {
            settled = true;
            break;
        }
    }
    if !settled {
        return None;
    }
    // The ray's direction m − n means something only where the walls' normals are apart:
    // at the tips of a crease, whose nodal normals all point along the fold, it is round-off
    // and the corner lands anywhere (slivers of a face far along the fold).
    let [_, n, _, _] = at(kind, &xs, &ns, D2::constant(xi, 2), D2::constant(eta, 2));
    if !(dot(&mv, &n).val() < APART) {
        return None;
    }
    // The step in T from the root: (ξ, η) − J⁻¹ f with J at the root's values (f vanishes
    // there, so J's own derivative does not enter).
    let z = y[0].cst(0.0);
    let f = miss(kind, slave, (y, m), z + xi, z + eta);
    let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
    Some([
        (z + xi) - (f[0] * jac[1][1] - f[1] * jac[0][1]) * (1.0 / det),
        (z + eta) - (f[1] * jac[0][0] - f[0] * jac[1][0]) * (1.0 / det),
    ])
}

/// The integration points of slave face `xs` (nodal normals `ns`) against master face `xm`
/// (nodal normals `nm`) of the same surface, along the rays that bisect the two walls' normals
/// (see the module's glossary); empty when they do not overlap, None when a master corner
/// cannot be carried (the pair then meets nowhere).
pub fn mirror_overlap<T: Scalar>(
    sk: FaceKind,
    (xs, ns): (&[V3<T>], &[V3<T>]),
    mk: FaceKind,
    (xm, nm): (&[V3<T>], &[V3<T>]),
) -> Option<Vec<Point<T>>> {
    let z = xs[0][0].cst(0.0);
    // Positions from the slave's first corner: the rays' round-off then scales with the faces,
    // not with their distance from the origin (at 1e6 faces' sizes away, every pair was
    // refused: Newton's steps stalled above its bar).
    let origin = xs[0].map(|c| c.val());
    let local = |x: &[V3<T>]| -> Vec<V3<T>> {
        x.iter()
            .map(|p| std::array::from_fn(|i| p[i] - origin[i]))
            .collect()
    };
    let (xs_at, xm_at) = (xs, xm);
    let (xs, xm) = (&local(xs)[..], &local(xm)[..]);
    let mut pm = Vec::with_capacity(xm.len());
    for (b, (y, m)) in xm.iter().zip(nm).enumerate() {
        // A corner the two faces share stays where it is (its ray has no direction there).
        let shared =
            (0..xs.len()).find(|&a| (0..3).all(|i| xs_at[a][i].val() == xm_at[b][i].val()));
        match shared {
            Some(a) => {
                let (u, v) = node_param(sk, a);
                pm.push([z + u, z + v]);
            }
            None => pm.push(carry(sk, (xs, ns), (y, m))?),
        }
    }
    let ps: Vec<V2<T>> = (0..xs.len())
        .map(|a| {
            let (u, v) = node_param(sk, a);
            [z + u, z + v]
        })
        .collect();
    let Some(poly) = clipped(&ps, &pm) else {
        return Some(Vec::new());
    };
    let mut out = Vec::new();
    for (p, w) in fan_points(&poly) {
        let Some((mxi, meta)) = inverse(mk, &pm, &p) else {
            continue;
        };
        let [_, n, t1, t2] = at(sk, xs, ns, p[0], p[1]);
        let [_, m, _, _] = at(mk, xm, nm, mxi, meta);
        let d = sub(&m, &n);
        let len = dot(&d, &d).sqrt();
        let da = cross(&t1, &t2);
        out.push(Point {
            slave: shape(sk, p[0], p[1]).0,
            master: shape(mk, mxi, meta).0,
            nu: d.map(|v| v / len),
            weight: dot(&da, &da).sqrt() * w,
        });
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square face at height `z` (outward normal ±z), its nodes counter-clockwise seen
    /// from +z when `up`.
    fn square(x0: f64, y0: f64, z: f64, up: bool) -> Vec<[f64; 3]> {
        let mut v = vec![
            [x0, y0, z],
            [x0 + 1.0, y0, z],
            [x0 + 1.0, y0 + 1.0, z],
            [x0, y0 + 1.0, z],
        ];
        if !up {
            v.reverse();
        }
        v
    }

    /// Two walls inclined to their mirror plane z = 0 (a fold's sides): the slave face
    /// x ∈ [0, 1] rises as z = 0.1 + 0.2 x, the master is its mirror image. The rays bisect
    /// the normals, so every point meets its mirror point: ν = −e_z, the gap twice the
    /// height, the whole face overlapped and every master parameter the slave's.
    #[test]
    fn mirror_walls_meet_at_mirror_points_along_the_mirror_planes_normal() {
        let lift = |p: [f64; 3], s: f64| [p[0], p[1], s * (0.1 + 0.2 * p[0])];
        let xs: Vec<[f64; 3]> = square(0.0, 0.0, 0.0, true)
            .into_iter()
            .map(|p| lift(p, 1.0))
            .collect();
        let xm: Vec<[f64; 3]> = square(0.0, 0.0, 0.0, false)
            .into_iter()
            .map(|p| lift(p, -1.0))
            .collect();
        // Outward normals: the slave's body lies above it, the master's below.
        let tilt = (1.0f64 + 0.04).sqrt();
        let ns = vec![[0.2 / tilt, 0.0, -1.0 / tilt]; 4];
        let nm = vec![[0.2 / tilt, 0.0, 1.0 / tilt]; 4];
        let points = mirror_overlap(FaceKind::Quad, (&xs, &ns), FaceKind::Quad, (&xm, &nm))
            .expect("carried");
        let area: f64 = points.iter().map(|p| p.weight).sum();
        assert!((area - tilt).abs() < 1e-13, "area {area}");
        for p in &points {
            assert!(
                (p.nu[2] - 1.0).abs() < 1e-14 && p.nu[0].abs() < 1e-14,
                "{:?}",
                p.nu
            );
            let pos = |x: &[[f64; 3]], s: &[f64; 4]| {
                [0, 1, 2].map(|i| (0..4).map(|a| x[a][i] * s[a]).sum::<f64>())
            };
            let (x, y) = (pos(&xs, &p.slave), pos(&xm, &p.master));
            assert!(
                (x[0] - y[0]).abs() < 1e-13
                    && (x[1] - y[1]).abs() < 1e-13
                    && (x[2] + y[2]).abs() < 1e-13,
                "{x:?} {y:?}"
            );
        }
    }
}

#[cfg(test)]
mod crease_tests {
    use super::*;

    /// The tip face of a crease's upper side between z0 and z0 + 1 (`up`), or of its lower
    /// side (the mirror image in y = 0): the tip edge on x = 0, the far edge at x = −1,
    /// y = ±0.2; its outward nodal normals (towards the slit), along the fold (−x) at the tip.
    fn tip_face(z0: f64, up: bool) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
        let s = if up { 1.0 } else { -1.0 };
        let mut x = vec![
            [0.0, 0.0, z0],
            [0.0, 0.0, z0 + 1.0],
            [-1.0, 0.2 * s, z0 + 1.0],
            [-1.0, 0.2 * s, z0],
        ];
        let l = 1.04f64.sqrt();
        let mut n = vec![
            [-1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [-0.2 / l, -s / l, 0.0],
            [-0.2 / l, -s / l, 0.0],
        ];
        if !up {
            x.reverse();
            n.reverse();
        }
        (x, n)
    }

    /// The two sides of a crease's tip share its edge: the shared corners stay where they are
    /// (along m − n, zero there, Newton crept to them and gave up: the pair was refused), and
    /// the far ones are carried to their mirror points: the faces meet whole, each point its
    /// mirror point, along e_y.
    #[test]
    fn a_creases_two_sides_meet_whole_at_its_tip() {
        let (xs, ns) = tip_face(0.0, true);
        let (xm, nm) = tip_face(0.0, false);
        let points = mirror_overlap(FaceKind::Quad, (&xs, &ns), FaceKind::Quad, (&xm, &nm))
            .expect("carried");
        let area: f64 = points.iter().map(|p| p.weight).sum();
        assert!((area - 1.04f64.sqrt()).abs() < 1e-13, "area {area}");
        let pos = |x: &[[f64; 3]], s: &[f64; 4]| {
            [0, 1, 2].map(|i| (0..4).map(|a| x[a][i] * s[a]).sum::<f64>())
        };
        for p in &points {
            assert!((p.nu[1] - 1.0).abs() < 1e-14, "{:?}", p.nu);
            let (x, y) = (pos(&xs, &p.slave), pos(&xm, &p.master));
            assert!(
                (x[0] - y[0]).abs() < 1e-13
                    && (x[1] + y[1]).abs() < 1e-13
                    && (x[2] - y[2]).abs() < 1e-13,
                "{x:?} {y:?}"
            );
        }
    }

    /// The crease's tip faces far from the origin (1e2 to 1e6 away, faces of size 1 to 0.01):
    /// they meet whole, to the round-off of their own coordinates. Before, from 1e6 faces'
    /// sizes away every corner's Newton stalled above its bar and the pair was refused.
    #[test]
    fn a_crease_far_from_the_origin_meets_as_near_it() {
        let exact = 1.04f64.sqrt();
        for off in [1e2, 1e3, 1e4, 1e5, 1e6] {
            for size in [1.0, 0.1, 0.01] {
                let at = |x: Vec<[f64; 3]>| -> Vec<[f64; 3]> {
                    x.into_iter().map(|p| p.map(|c| c * size + off)).collect()
                };
                let ((xs, ns), (xm, nm)) = (tip_face(0.0, true), tip_face(0.0, false));
                let (xs, xm) = (at(xs), at(xm));
                let points = mirror_overlap(FaceKind::Quad, (&xs, &ns), FaceKind::Quad, (&xm, &nm))
                    .unwrap_or_else(|| panic!("{off} away, size {size}: refused"));
                let area = points.iter().map(|p| p.weight).sum::<f64>() / (size * size);
                assert!(
                    (area - exact).abs() < 1e-14 * off / size,
                    "{off} away, size {size}: area {area}"
                );
            }
        }
    }

    /// Along a fold the tips of other layers lie on the tip's line, their normals all along
    /// it: the rays m − n between two tips are round-off. Tip faces of other layers (the next
    /// one and two away, either side), their corners and normals off by round-off to 1 %, meet
    /// nothing (before: overlaps in 405 of 2 000 such draws, up to 0.4 of the face).
    #[test]
    fn tips_of_one_crease_on_other_layers_meet_nothing() {
        let mut uniform = crate::testing::uniform(12345);
        let mut draw = || uniform() - 0.5;
        for trial in 0..2000 {
            let (mut xs, mut ns) = tip_face(0.0, trial % 2 == 0);
            let z0 = [2.0, -2.0, 1.0, -1.0][trial % 4];
            let (mut xm, mut nm) = tip_face(z0, trial % 2 == 1);
            let off = [1e-2, 1e-3, 1e-6][trial % 3];
            for v in xs.iter_mut().chain(xm.iter_mut()) {
                v.iter_mut().for_each(|c| *c += off * draw());
            }
            for v in ns.iter_mut().chain(nm.iter_mut()) {
                v.iter_mut().for_each(|c| *c += off * draw());
                let l = dot(v, v).sqrt();
                *v = v.map(|c| c / l);
            }
            let points = mirror_overlap(FaceKind::Quad, (&xs, &ns), FaceKind::Quad, (&xm, &nm));
            let area: f64 = points.iter().flatten().map(|p| p.weight).sum();
            assert!(
                area == 0.0,
                "draw {trial} (z0 {z0}, off {off}): area {area}"
            );
        }
    }
}

#[cfg(test)]
mod derivative_tests {
    use super::*;
    type D = DualN<48>;

    /// The overlap's area, ∫ g N_0 and ∫ M_2 ν_x of slave face `x[..4]` against master `x[4..]`
    /// with nodal normals `n`.
    fn integrals<T: Scalar>(x: &[[T; 3]], n: &[[T; 3]]) -> (T, T, T) {
        let pts = mirror_overlap(
            FaceKind::Quad,
            (&x[..4], &n[..4]),
            FaceKind::Quad,
            (&x[4..], &n[4..]),
        )
        .unwrap();
        let z = x[0][0].cst(0.0);
        let (mut a, mut g, mut s) = (z, z, z);
        for p in &pts {
            let mut d = [z; 3];
            for i in 0..3 {
                for b in 0..4 {
                    d[i] = d[i] + p.slave[b] * x[b][i] - p.master[b] * x[4 + b][i];
                }
            }
            a = a + p.weight;
            g = g + p.weight * dot(&d, &p.nu) * p.slave[0];
            s = s + p.weight * p.master[2] * p.nu[0];
        }
        (a, g, s)
    }

    /// Inclined faces at an angle, nodal normals apart from node to node: the area, a weighted
    /// gap and a master-weighted normal integrated over the mirror segmentation have the
    /// derivatives of central differences, over both faces' coordinates and nodal normals.
    #[test]
    fn mirror_integrals_have_exact_derivatives() {
        let mut v = vec![
            [0.0, 0.0, 0.1],
            [1.0, 0.05, 0.2],
            [1.1, 1.0, 0.25],
            [0.0, 0.9, 0.12],
            [0.3, 1.2, -0.1],
            [1.2, 1.1, -0.2],
            [1.3, 0.2, -0.15],
            [0.2, 0.1, -0.05],
            [0.1, 0.0, -1.0],
            [0.2, 0.1, -1.0],
            [0.0, 0.1, -1.0],
            [0.05, -0.1, -1.0],
            [0.1, 0.0, 1.0],
            [0.0, 0.2, 1.0],
            [-0.1, 0.1, 1.0],
            [0.1, 0.1, 1.0],
        ];
        for p in v[8..].iter_mut() {
            let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            *p = p.map(|c| c / l);
        }
        let flat: Vec<f64> = v.iter().flatten().copied().collect();
        let dual: Vec<[D; 3]> = (0..16)
            .map(|b| std::array::from_fn(|i| D::variable(flat[3 * b + i], 3 * b + i, 48)))
            .collect();
        let (a, g, s) = integrals(&dual[..8], &dual[8..]);
        assert!(a.v > 0.3, "the faces overlap: {}", a.v);
        let h = 1e-6;
        for k in 0..48 {
            let at = |d: f64| {
                let mut w = v.clone();
                w[k / 3][k % 3] += d;
                integrals(&w[..8], &w[8..])
            };
            let (p, m) = (at(h), at(-h));
            let fd = [
                (p.0 - m.0) / (2.0 * h),
                (p.1 - m.1) / (2.0 * h),
                (p.2 - m.2) / (2.0 * h),
            ];
            let ad = [a.d[k], g.d[k], s.d[k]];
            for c in 0..3 {
                assert!(
                    (fd[c] - ad[c]).abs() < 1e-6,
                    "k {k} c {c}: fd {} ad {}",
                    fd[c],
                    ad[c]
                );
            }
        }
    }
}
