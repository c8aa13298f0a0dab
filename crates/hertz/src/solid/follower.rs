//! Follower tractions (hertz's `follower` on a `csType 1` edge or surface load): the traction
//! acts on the current boundary, per current length or area, along its current axes, so a
//! pressure turns and stretches with the surface in large deformation. The force depends on the
//! displacements; its derivative is not symmetric.
//!
//! With x the current positions, s the outward sign (fixed on the reference boundary) and the
//! components (f₁, f₂) of a 2D edge, f₃ the normal one of a 3D face:
//! - 2D edge: F_a = s ∫ N_a [f₁(−t) + f₂(t_y, −t_x)] h dξ, t = ∂x/∂ξ, h the thickness, or the
//!   current radius Σ N_k x_k per radian in axisymmetry (OOFEM's edge axes of
//!   [`super::loads`], times the current length |t|);
//! - 3D face: F_a = s f₃ ∫ N_a (g₁ × g₂) dξ, g_i = ∂x/∂ξ_i.
//!
//! Both are polynomials in x: the forces and their exact derivative ∂F/∂x come from the same
//! quadrature (3 points on an edge, exact; the face rules of the dead surface loads).

use super::loads::{element_thickness, load_boundaries, outward_sign};
use crate::assembly::{Contribution, DofMap};
use crate::error::{Error, Result};
use crate::fem::{gauss_line, rule, Shape};
use crate::model::Model;

/// One boundary a follower load acts on.
struct Piece {
    /// Index of the load in the model.
    load: usize,
    element: usize,
    /// The boundary's local node numbers in the element.
    local: &'static [usize],
    /// +1 if the boundary's natural normal (t rotated by −90°, g₁ × g₂) points outward.
    sign: f64,
    /// The thickness of a plane element (1 otherwise).
    thick: f64,
    axisymmetric: bool,
    /// Location codes of the boundary's displacement DOFs, node by node.
    codes: Vec<usize>,
}

/// The follower loads of a model, boundary by boundary.
pub struct FollowerLoads {
    pieces: Vec<Piece>,
    dim: usize,
}

impl FollowerLoads {
    /// The follower loads of `model`, with the location codes of `dofs`.
    pub fn new(model: &Model, dofs: &DofMap) -> Result<FollowerLoads> {
        let dim = model.domain.nsd();
        let mut pieces = Vec::new();
        for (li, load) in model.loads.iter().enumerate().filter(|(_, l)| l.follower) {
            for (e, local) in load_boundaries(model, load)? {
                let el = &model.elements[e];
                let mut codes = Vec::with_capacity(local.len() * dim);
                for &a in local {
                    for d in 1..=dim as u8 {
                        codes.push(dofs.code(el.nodes[a], d).ok_or_else(|| Error::Input {
                            span: load.span.clone(),
                            msg: format!(
                                "follower load {}: node {} has no DOF {d}",
                                load.number, model.nodes[el.nodes[a]].label
                            ),
                        })?);
                    }
                }
                let x: Vec<[f64; 3]> = local
                    .iter()
                    .map(|&a| model.nodes[el.nodes[a]].coords)
                    .collect();
                let (point, normal) = natural_normal(el.etype.shape(), &x);
                let axisymmetric = el.etype.is_axisymmetric();
                pieces.push(Piece {
                    load: li,
                    element: e,
                    local,
                    sign: outward_sign(model, e, point, normal),
                    thick: if dim == 2 && !axisymmetric {
                        element_thickness(model, e)
                    } else {
                        1.0
                    },
                    axisymmetric,
                    codes,
                });
            }
        }
        Ok(FollowerLoads { pieces, dim })
    }

    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }

    /// The loads' forces at primary state `u`, each load scaled by `scale[load index]`, as
    /// contributions to the internal forces (the negative external force) with their tangent
    /// (row-major over the codes) when `want_k`.
    pub fn contributions(
        &self,
        model: &Model,
        dofs: &DofMap,
        u: &[f64],
        scale: &[f64],
        want_k: bool,
    ) -> Vec<Contribution> {
        let dim = self.dim;
        self.pieces
            .iter()
            .filter(|p| scale[p.load] != 0.0)
            .map(|p| {
                let el = &model.elements[p.element];
                let x: Vec<[f64; 3]> = p
                    .local
                    .iter()
                    .enumerate()
                    .map(|(k, &a)| {
                        let mut x = model.nodes[el.nodes[a]].coords;
                        for d in 0..dim {
                            x[d] += dofs.value(u, p.codes[k * dim + d]);
                        }
                        x
                    })
                    .collect();
                let f = &model.loads[p.load].components;
                let s = -scale[p.load] * p.sign;
                let (mut fe, mut ke) = if dim == 2 {
                    edge_force(&x, [f[0], f[1]], p.axisymmetric, want_k)
                } else {
                    let face = el.etype.shape().boundary_shape(x.len());
                    face_force(face, &x, f[2], want_k)
                };
                let factor = s * p.thick;
                fe.iter_mut().for_each(|v| *v *= factor);
                ke.iter_mut().for_each(|v| *v *= factor);
                Contribution {
                    codes: p.codes.clone(),
                    fe,
                    ke,
                }
            })
            .collect()
    }
}

/// A point of a boundary with nodes at `x` and its natural normal there (t rotated by −90° on
/// an edge, g₁ × g₂ on a face of `shape`'s boundary), at the boundary's centre.
fn natural_normal(shape: Shape, x: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let m = x.len();
    let (boundary, xi) = if shape.dim() == 2 {
        (Shape::edge_shape(m), [0.0; 3])
    } else {
        let face = shape.boundary_shape(m);
        let centre = if m == 3 || m == 6 { 1.0 / 3.0 } else { 0.0 };
        (face, [centre, centre, 0.0])
    };
    let mut n = [0.0; 8];
    let mut dn = [[0.0; 3]; 8];
    boundary.eval(xi, &mut n, &mut dn);
    let mut point = [0.0; 3];
    let (mut g1, mut g2) = ([0.0; 3], [0.0; 3]);
    for k in 0..m {
        for i in 0..3 {
            point[i] += n[k] * x[k][i];
            g1[i] += dn[k][0] * x[k][i];
            g2[i] += dn[k][1] * x[k][i];
        }
    }
    let normal = if shape.dim() == 2 {
        [g1[1], -g1[0], 0.0]
    } else {
        cross(g1, g2)
    };
    (point, normal)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// ∫ N_a [f₁(−t) + f₂(t_y, −t_x)] h dξ over an edge with nodes at `x` (h = 1, or the radius
/// Σ N_k x_k when `axisymmetric`) and its derivative by the nodes' coordinates (row-major,
/// two per node).
fn edge_force(
    x: &[[f64; 3]],
    f: [f64; 2],
    axisymmetric: bool,
    want_k: bool,
) -> (Vec<f64>, Vec<f64>) {
    let m = x.len();
    let nd = 2 * m;
    let mut fe = vec![0.0; nd];
    let mut ke = if want_k {
        vec![0.0; nd * nd]
    } else {
        Vec::new()
    };
    let shape = Shape::edge_shape(m);
    let mut n = [0.0; 3];
    let mut dn = [[0.0; 3]; 3];
    // ∂g/∂t, g = f₁(−t) + f₂(t_y, −t_x).
    let dg = [[-f[0], f[1]], [-f[1], -f[0]]];
    for (xi, w) in gauss_line(3).expect("3-point rule") {
        shape.eval([xi, 0.0, 0.0], &mut n, &mut dn);
        let mut t = [0.0; 2];
        let mut r = 0.0;
        for k in 0..m {
            t[0] += dn[k][0] * x[k][0];
            t[1] += dn[k][0] * x[k][1];
            r += n[k] * x[k][0];
        }
        let h = if axisymmetric { r } else { 1.0 };
        let g = [-f[0] * t[0] + f[1] * t[1], -f[0] * t[1] - f[1] * t[0]];
        for a in 0..m {
            for i in 0..2 {
                fe[2 * a + i] += w * n[a] * h * g[i];
            }
            if !want_k {
                continue;
            }
            for b in 0..m {
                for i in 0..2 {
                    for j in 0..2 {
                        let mut d = h * dg[i][j] * dn[b][0];
                        if axisymmetric && j == 0 {
                            d += n[b] * g[i];
                        }
                        ke[(2 * a + i) * nd + 2 * b + j] += w * n[a] * d;
                    }
                }
            }
        }
    }
    (fe, ke)
}

/// f₃ ∫ N_a (g₁ × g₂) dξ over a face of shape `face` with nodes at `x` and its derivative by
/// the nodes' coordinates (row-major, three per node).
fn face_force(face: Shape, x: &[[f64; 3]], f3: f64, want_k: bool) -> (Vec<f64>, Vec<f64>) {
    let m = x.len();
    let nd = 3 * m;
    let mut fe = vec![0.0; nd];
    let mut ke = if want_k {
        vec![0.0; nd * nd]
    } else {
        Vec::new()
    };
    let points = match m {
        3 => 3,
        8 | 9 => 9,
        _ => 4,
    };
    let mut n = [0.0; 9];
    let mut dn = [[0.0; 3]; 9];
    let unit = |j: usize| std::array::from_fn::<f64, 3, _>(|i| f64::from(u8::from(i == j)));
    for qp in rule(face, points).expect("face rule") {
        face.eval(qp.xi, &mut n, &mut dn);
        let (mut g1, mut g2) = ([0.0; 3], [0.0; 3]);
        for k in 0..m {
            for i in 0..3 {
                g1[i] += dn[k][0] * x[k][i];
                g2[i] += dn[k][1] * x[k][i];
            }
        }
        let c = cross(g1, g2);
        let w = qp.weight * f3;
        for a in 0..m {
            for i in 0..3 {
                fe[3 * a + i] += w * n[a] * c[i];
            }
            if !want_k {
                continue;
            }
            for b in 0..m {
                for j in 0..3 {
                    // ∂(g₁ × g₂)/∂x_bj = dN_b,1 (e_j × g₂) + dN_b,2 (g₁ × e_j).
                    let d1 = cross(unit(j), g2);
                    let d2 = cross(g1, unit(j));
                    for i in 0..3 {
                        ke[(3 * a + i) * nd + 3 * b + j] +=
                            w * n[a] * (dn[b][0] * d1[i] + dn[b][1] * d2[i]);
                    }
                }
            }
        }
    }
    (fe, ke)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central differences of `force` by every coordinate against its tangent `ke`.
    fn check_tangent(
        x: &[[f64; 3]],
        dim: usize,
        force: impl Fn(&[[f64; 3]], bool) -> (Vec<f64>, Vec<f64>),
    ) {
        let (_, ke) = force(x, true);
        let nd = dim * x.len();
        let scale = ke.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let h = 1e-6;
        for b in 0..x.len() {
            for j in 0..dim {
                let moved = |d: f64| {
                    let mut y = x.to_vec();
                    y[b][j] += d;
                    force(&y, false).0
                };
                let (plus, minus) = (moved(h), moved(-h));
                for r in 0..nd {
                    let fd = (plus[r] - minus[r]) / (2.0 * h);
                    let exact = ke[r * nd + dim * b + j];
                    assert!(
                        (fd - exact).abs() < 1e-7 * scale,
                        "row {r}, node {b} coordinate {j}: {exact} vs finite difference {fd}"
                    );
                }
            }
        }
    }

    /// The parametric coordinates of `shape`'s nodes (where its shape function is 1).
    fn reference_nodes(shape: Shape) -> Vec<[f64; 3]> {
        let mut out = vec![[f64::NAN; 3]; shape.n_nodes()];
        let mut n = [0.0; 20];
        let mut dn = [[0.0; 3]; 20];
        let steps = [-1.0, -0.5, 0.0, 0.5, 1.0];
        for &a in &steps {
            for &b in &steps {
                for &c in &steps {
                    shape.eval([a, b, c], &mut n, &mut dn);
                    for (k, p) in out.iter_mut().enumerate() {
                        if p[0].is_nan() && (n[k] - 1.0).abs() < 1e-12 {
                            *p = [a, b, c];
                        }
                    }
                }
            }
        }
        out
    }

    /// A curved, stretched boundary: the nodes of the reference element mapped by a smooth
    /// distortion so that no derivative vanishes by symmetry.
    fn distorted(x: &[[f64; 3]]) -> Vec<[f64; 3]> {
        x.iter()
            .map(|p| {
                [
                    1.3 + p[0] + 0.11 * p[1] * p[1] + 0.07 * p[2],
                    0.4 + 0.9 * p[1] + 0.13 * p[0] * p[0] - 0.05 * p[2],
                    0.2 + 1.1 * p[2] + 0.09 * p[0] * p[1],
                ]
            })
            .collect()
    }

    /// The edge force's tangent is its derivative: plane and axisymmetric, linear and quadratic
    /// edges, tangential and normal components.
    #[test]
    fn edge_follower_tangent_is_the_derivative_of_its_force() {
        for x in [
            vec![[0.0, 0.0, 0.0], [1.0, 0.3, 0.0]],
            vec![[0.0, 0.0, 0.0], [1.0, 0.3, 0.0], [0.45, 0.35, 0.0]],
        ] {
            let x = distorted(&x);
            for axisymmetric in [false, true] {
                check_tangent(&x, 2, |y, k| edge_force(y, [0.7, -2.3], axisymmetric, k));
            }
        }
    }

    /// The face force's tangent is its derivative on every face shape (linear and quadratic
    /// triangles and quadrilaterals).
    #[test]
    fn face_follower_tangent_is_the_derivative_of_its_force() {
        for (shape, nodes) in [
            (Shape::Tet4, 3),
            (Shape::Tet10, 6),
            (Shape::Hexa8, 4),
            (Shape::Hexa20, 8),
        ] {
            let face = shape.boundary_shape(nodes);
            let corners: Vec<[f64; 3]> = reference_nodes(face)
                .iter()
                .map(|p| [p[0], p[1], 0.3 * p[0] * p[1]])
                .collect();
            let x = distorted(&corners);
            check_tangent(&x, 3, |y, k| face_force(face, y, -1.7, k));
        }
    }

    /// A closed surface under a follower pressure is in equilibrium: the forces on a distorted
    /// (curved) brick's six faces, outward by their natural normals, sum to zero.
    #[test]
    fn follower_pressure_on_a_closed_surface_sums_to_zero() {
        let shape = Shape::Hexa20;
        let x = distorted(&reference_nodes(shape));
        let mut total = [0.0; 3];
        for local in shape.boundaries() {
            let y: Vec<[f64; 3]> = local.iter().map(|&a| x[a]).collect();
            let (fe, _) = face_force(shape.boundary_shape(y.len()), &y, 1.0, false);
            let (point, normal) = natural_normal(shape, &y);
            let centre = [1.3, 0.4, 0.2];
            let side: f64 = (0..3).map(|i| (point[i] - centre[i]) * normal[i]).sum();
            let sign = side.signum();
            for (k, f) in fe.iter().enumerate() {
                total[k % 3] += sign * f;
            }
        }
        for t in total {
            assert!(t.abs() < 1e-12, "{total:?}");
        }
    }
}
