//! What each contact node stands for on its own surface: its tributary length·thickness (2D),
//! area per radian (axisymmetric: ∫ N_a r ds) or area (3D), for the pressure output, and its neighbours on that surface, for the weights at the
//! ends of an open master. Element boundaries whose nodes all belong to the same condition's
//! contact nodes make up the surface.

use crate::model::Model;
use std::collections::{HashMap, HashSet};

/// Tributary data of one contact node.
#[derive(Debug, Clone, Default)]
pub struct Tributary {
    /// Length × thickness (2D) or area (3D); 0 when the node lies on no such boundary.
    pub measure: f64,
    /// The other nodes of the boundaries it shares with its fellow contact nodes.
    pub neighbors: Vec<usize>,
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

fn triangle_area(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    0.5 * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt()
}

/// One boundary of the contact nodes' own surface: an element edge (2D) or face (3D) whose nodes
/// are all contact nodes of the condition.
#[derive(Debug, Clone)]
pub struct Facet {
    /// Its nodes (model indices), in the element's boundary order.
    pub nodes: Vec<usize>,
    /// The thickness of its 2D element (unused in 3D and in axisymmetry).
    thick: f64,
    plane: bool,
    /// Of an axisymmetric element: its measure per radian, ∫ N_a r ds.
    axisymmetric: bool,
    /// Its element is in large deformation: its current measure is the one that counts.
    pub nlgeo: bool,
}

impl Facet {
    /// Each node's share of the facet's length × thickness (2D) or area (3D) at positions `x`
    /// (in the facet's node order).
    pub fn shares(&self, x: &[[f64; 3]]) -> Vec<f64> {
        if self.axisymmetric {
            return axisymmetric_shares(x);
        }
        if self.plane {
            if x.len() == 2 {
                vec![0.5 * dist(x[0], x[1]) * self.thick; 2]
            } else {
                // Quadratic edge (ends, middle): Simpson weights 1/6, 1/6, 2/3.
                let l = (dist(x[0], x[2]) + dist(x[2], x[1])) * self.thick;
                vec![l / 6.0, l / 6.0, 2.0 * l / 3.0]
            }
        } else if x.len() > 4 {
            quadratic_face_shares(x)
        } else {
            let a = if x.len() == 3 {
                triangle_area(x[0], x[1], x[2])
            } else {
                triangle_area(x[0], x[1], x[2]) + triangle_area(x[0], x[2], x[3])
            };
            vec![a / x.len() as f64; x.len()]
        }
    }
}

/// Each node's ∫ N_a r ds over an axisymmetric element's edge at positions `x` (ends, then the
/// middle of a quadratic edge; r = x): its area per radian, integrated exactly (3 points).
pub(crate) fn axisymmetric_shares(x: &[[f64; 3]]) -> Vec<f64> {
    let shape = crate::fem::Shape::edge_shape(x.len());
    let (mut n, mut dn) = ([0.0; 3], [[0.0; 3]; 3]);
    let mut out = vec![0.0; x.len()];
    for (xi, w) in crate::fem::gauss_line(3).expect("3-point rule") {
        shape.eval([xi, 0.0, 0.0], &mut n, &mut dn);
        let t: [f64; 2] =
            std::array::from_fn(|i| (0..x.len()).map(|a| dn[a][0] * x[a][i]).sum::<f64>());
        let r: f64 = (0..x.len()).map(|a| n[a] * x[a][0]).sum();
        let ds = t[0].hypot(t[1]) * w;
        for (a, o) in out.iter_mut().enumerate() {
            *o += n[a] * r * ds;
        }
    }
    out
}

/// The shares of a 6- or 8-node face's area (positions `x`, corners then mid-sides): its area
/// lumped in proportion to ∫ N_a² (Hinton, Rock and Zienkiewicz 1976). ∫ N_a itself is zero at a
/// 6-node triangle's corners (negative at an 8-node quadrilateral's), which would leave a
/// corner node no area; these shares are all positive and sum to the area: 1/19 and 16/57 of a
/// flat triangle's.
fn quadratic_face_shares(x: &[[f64; 3]]) -> Vec<f64> {
    let m = face_mass(x);
    let area: f64 = m.iter().flatten().sum();
    let total: f64 = (0..x.len()).map(|a| m[a][a]).sum();
    (0..x.len()).map(|a| area * m[a][a] / total).collect()
}

/// ∫ N_a N_b dA over a 3D face at positions `x` (3, 4, 6 or 8 nodes): its consistent mass.
fn face_mass(x: &[[f64; 3]]) -> Vec<Vec<f64>> {
    use super::geometry::faces::{cross, dot, shape_values, FaceKind};
    let kind = FaceKind::of(x.len());
    let k = x.len();
    let mut m = vec![vec![0.0; k]; k];
    for (xi, eta, w) in super::mortar::segment::face_rule(kind) {
        let (n, dx, de) = shape_values(kind, xi, eta);
        let tangent = |d: &[f64; 8]| -> [f64; 3] {
            std::array::from_fn(|i| (0..k).map(|a| d[a] * x[a][i]).sum())
        };
        let normal = cross(&tangent(&dx), &tangent(&de));
        let da = w * dot(&normal, &normal).sqrt();
        for a in 0..k {
            for b in 0..k {
                m[a][b] += n[a] * n[b] * da;
            }
        }
    }
    m
}

/// The facets of the surface that the contact nodes `nodes` make up.
pub fn facets(model: &Model, nodes: &[usize]) -> Vec<Facet> {
    let members: HashSet<usize> = nodes.iter().copied().collect();
    let mut out = Vec::new();
    for (ei, el) in model.elements.iter().enumerate() {
        if el.etype.is_truss() || !el.nodes.iter().any(|n| members.contains(n)) {
            continue;
        }
        let shape = el.etype.shape();
        for local in shape.boundaries() {
            let bn: Vec<usize> = local.iter().map(|&a| el.nodes[a]).collect();
            if !bn.iter().all(|n| members.contains(n)) {
                continue;
            }
            let plane = shape.dim() == 2;
            let axisymmetric = el.etype.is_axisymmetric();
            out.push(Facet {
                nodes: bn,
                thick: if plane && !axisymmetric {
                    crate::solid::loads::element_thickness(model, ei)
                } else {
                    0.0
                },
                plane,
                axisymmetric,
                nlgeo: el.nlgeo,
            });
        }
    }
    out
}

/// Tributary data of every node of `nodes` (the contact nodes of one condition), in that order,
/// in the reference configuration.
pub fn tributaries(model: &Model, nodes: &[usize]) -> Vec<Tributary> {
    let mut out: HashMap<usize, Tributary> = HashMap::new();
    for f in facets(model, nodes) {
        let x: Vec<[f64; 3]> = f.nodes.iter().map(|&n| model.nodes[n].coords).collect();
        for (k, (&n, s)) in f.nodes.iter().zip(f.shares(&x)).enumerate() {
            let t = out.entry(n).or_default();
            t.measure += s;
            for (j, &m) in f.nodes.iter().enumerate() {
                if j != k && !t.neighbors.contains(&m) {
                    t.neighbors.push(m);
                }
            }
        }
    }
    nodes
        .iter()
        .map(|n| out.get(n).cloned().unwrap_or_default())
        .collect()
}

/// The area each contact node's pressure refers to: its tributary measure on its own surface,
/// with every facet in large deformation at its current position and the others at their
/// reference one, so that force / area is the true (Cauchy) contact pressure in large
/// deformation and the engineering one in small, for every formulation alike.
#[derive(Debug, Clone)]
pub struct PressureAreas {
    /// Their surface's facets in large deformation (the others keep their reference measure),
    /// each with the position of its nodes among the contact nodes.
    moving: Vec<(Facet, Vec<usize>)>,
    /// Each node's measure in the reference configuration, less the moving facets' shares.
    fixed: Vec<f64>,
    /// The curved (6- and 8-node) facets of a 3D surface, with their nodes' reference positions:
    /// the pressure there is the L2 projection of the nodal forces ([`PressureAreas::pressures`]).
    curved: Vec<(Facet, Vec<usize>, Vec<[f64; 3]>)>,
}

impl PressureAreas {
    /// The areas of the contact nodes `nodes` of one condition.
    pub fn new(model: &Model, nodes: &[usize]) -> PressureAreas {
        let index: HashMap<usize, usize> = nodes.iter().enumerate().map(|(k, &n)| (n, k)).collect();
        let mut fixed = vec![0.0; nodes.len()];
        let mut moving = Vec::new();
        let mut curved = Vec::new();
        for f in facets(model, nodes) {
            let slots: Vec<usize> = f.nodes.iter().map(|n| index[n]).collect();
            if !f.plane && f.nodes.len() > 4 {
                let x = f.nodes.iter().map(|&n| model.nodes[n].coords).collect();
                curved.push((f, slots, x));
                continue;
            }
            if f.nlgeo {
                moving.push((f, slots));
                continue;
            }
            let x: Vec<[f64; 3]> = f.nodes.iter().map(|&n| model.nodes[n].coords).collect();
            for (&k, s) in slots.iter().zip(f.shares(&x)) {
                fixed[k] += s;
            }
        }
        PressureAreas {
            moving,
            fixed,
            curved,
        }
    }

    /// Whether the surface has curved facets (its pressures need [`PressureAreas::pressures`]).
    pub fn has_curved(&self) -> bool {
        !self.curved.is_empty()
    }

    /// The nodes' contact pressures, on a surface with curved (quadratic) facets
    /// ([`PressureAreas::has_curved`]), for their normal forces `forces`, the nodes at
    /// `position(n)` and `lumped` the linear facets' areas ([`PressureAreas::at`]): the pressure
    /// field p = Σ p_a N_a whose consistent nodal forces ∫ p N_a dA are the forces — the
    /// consistent mass M solved, M p = f (with the linear facets' areas on its diagonal). A
    /// uniform pressure puts no force on a 6-node triangle's corners and 1/3 of its area on each
    /// mid-side: force over any lumped area would report 0 and 1.19 p there, the projection p
    /// everywhere. Uncovered nodes (no facet): 0 force, NaN.
    pub fn pressures(
        &self,
        forces: &[f64],
        lumped: &[f64],
        mut position: impl FnMut(usize) -> crate::error::Result<[f64; 3]>,
    ) -> crate::error::Result<Vec<f64>> {
        let n = forces.len();
        let mut rows: Vec<Vec<(usize, f64)>> = (0..n).map(|k| vec![(k, lumped[k])]).collect();
        for (f, slots, reference) in &self.curved {
            let x = if f.nlgeo {
                f.nodes
                    .iter()
                    .map(|&m| position(m))
                    .collect::<crate::error::Result<Vec<_>>>()?
            } else {
                reference.clone()
            };
            let m = face_mass(&x);
            for (a, &i) in slots.iter().enumerate() {
                for (b, &j) in slots.iter().enumerate() {
                    rows[i].push((j, m[a][b]));
                }
            }
        }
        let covered: Vec<bool> = rows
            .iter()
            .map(|r| r.iter().any(|&(_, v)| v != 0.0))
            .collect();
        let mut p = conjugate_gradients(&rows, forces, &covered);
        for (v, c) in p.iter_mut().zip(&covered) {
            if !c {
                *v = f64::NAN;
            }
        }
        Ok(p)
    }

    /// The areas with the nodes at `position(n)`.
    pub fn at(
        &self,
        mut position: impl FnMut(usize) -> crate::error::Result<[f64; 3]>,
    ) -> crate::error::Result<Vec<f64>> {
        let mut out = self.fixed.clone();
        for (f, slots) in &self.moving {
            let x = f
                .nodes
                .iter()
                .map(|&n| position(n))
                .collect::<crate::error::Result<Vec<_>>>()?;
            for (&k, s) in slots.iter().zip(f.shares(&x)) {
                out[k] += s;
            }
        }
        Ok(out)
    }
}

/// M p = f by Jacobi-preconditioned conjugate gradients, M symmetric positive definite given by
/// rows of (column, value) entries (repeated columns add up); rows not `covered` hold p = 0. A
/// surface mass matrix is well conditioned (its condition number does not grow with the mesh):
/// a few dozen iterations reach round-off.
fn conjugate_gradients(rows: &[Vec<(usize, f64)>], f: &[f64], covered: &[bool]) -> Vec<f64> {
    let n = f.len();
    let apply = |x: &[f64]| -> Vec<f64> {
        rows.iter()
            .map(|r| r.iter().map(|&(j, v)| v * x[j]).sum())
            .collect()
    };
    let diag: Vec<f64> = rows
        .iter()
        .enumerate()
        .map(|(i, r)| r.iter().filter(|e| e.0 == i).map(|e| e.1).sum())
        .collect();
    let precond = |r: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|i| {
                if covered[i] && diag[i] > 0.0 {
                    r[i] / diag[i]
                } else {
                    0.0
                }
            })
            .collect()
    };
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let mut x = vec![0.0; n];
    let mut r: Vec<f64> = (0..n)
        .map(|i| if covered[i] { f[i] } else { 0.0 })
        .collect();
    let norm0 = dot(&r, &r).sqrt();
    let mut z = precond(&r);
    let mut d = z.clone();
    let mut rz = dot(&r, &z);
    for _ in 0..10 * n.max(10) {
        if !(dot(&r, &r).sqrt() > 1e-14 * norm0) {
            break;
        }
        let q = apply(&d);
        let alpha = rz / dot(&d, &q);
        for i in 0..n {
            x[i] += alpha * d[i];
            r[i] -= alpha * q[i];
        }
        z = precond(&r);
        let rz_new = dot(&r, &z);
        let beta = rz_new / rz;
        rz = rz_new;
        for i in 0..n {
            d[i] = z[i] + beta * d[i];
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat 6-node triangle's area lumped by ∫ N_a²: 1/19 to each corner, 16/57 to each
    /// mid-side. A flat 8-node square's consistent mass gives ∫ N_a = −1/12 of its area at the
    /// corners and 1/3 at the mid-sides; its lumped shares are positive and sum to the area.
    #[test]
    fn quadratic_faces_lump_their_area_by_the_squares_of_their_shape_functions() {
        let tri: Vec<[f64; 3]> = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let s = quadratic_face_shares(&tri);
        for a in 0..3 {
            assert!((s[a] - 2.0 / 19.0).abs() < 1e-14, "{s:?}");
            assert!((s[3 + a] - 2.0 * 16.0 / 57.0).abs() < 1e-14, "{s:?}");
        }
        let quad: Vec<[f64; 3]> = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, 0.0],
            [1.0, 0.5, 0.0],
            [0.5, 1.0, 0.0],
            [0.0, 0.5, 0.0],
        ];
        let m = face_mass(&quad);
        let consistent: Vec<f64> = m.iter().map(|r| r.iter().sum()).collect();
        for a in 0..4 {
            assert!((consistent[a] + 1.0 / 12.0).abs() < 1e-14, "{consistent:?}");
            assert!(
                (consistent[4 + a] - 1.0 / 3.0).abs() < 1e-14,
                "{consistent:?}"
            );
        }
        let s = quadratic_face_shares(&quad);
        assert!((s.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        assert!(s.iter().all(|&v| v > 0.0), "{s:?}");
    }
}
