//! Reference load vectors (load value 1·components) as (node, DOF id, value) contributions:
//! nodal forces, edge and surface tractions, dead weight.

use super::truss::{in_bar_plane, truss_axes};
use crate::error::{Error, Result};
use crate::fem::{gauss_line, rule};
use crate::model::{DofId, Load, LoadKind, Model};

/// Contributions of one load at unit time-function value. A follower load has none: it
/// depends on the state, and the step adds it ([`super::follower`]).
pub fn reference_contributions(model: &Model, load: &Load) -> Result<Vec<(usize, DofId, f64)>> {
    if load.follower {
        return Ok(Vec::new());
    }
    let set = &model.sets[load.set - 1];
    let mut out = Vec::new();
    let comps = || {
        load.dofs
            .iter()
            .copied()
            .zip(load.components.iter().copied())
    };
    match load.kind {
        LoadKind::Nodal => {
            for &n in &set.nodes {
                out.extend(comps().map(|(d, c)| (n, d, c)));
            }
        }
        LoadKind::DeadWeight => {
            for &e in &set.elements {
                let el = &model.elements[e];
                let rho = model.materials[el.material].density;
                let w = element_shape_integrals(model, e)?;
                for (a, &node) in el.nodes.iter().enumerate() {
                    out.extend(comps().map(|(d, c)| (node, d, rho * c * w[a])));
                }
            }
        }
        LoadKind::Edge => {
            for (e, local) in load_boundaries(model, load)? {
                let el = &model.elements[e];
                let shape = el.etype.shape();
                let axisymmetric = el.etype.is_axisymmetric();
                let thick = if shape.dim() == 2 && !axisymmetric {
                    element_thickness(model, e)
                } else {
                    1.0
                };
                let edge_shape = crate::fem::Shape::edge_shape(local.len());
                let mut n = [0.0; 3];
                let mut dn = [[0.0; 3]; 3];
                for (xi, w) in gauss_line(3).expect("3-point rule") {
                    edge_shape.eval([xi, 0.0, 0.0], &mut n, &mut dn);
                    let mut t = [0.0; 3];
                    for (k, &a) in local.iter().enumerate() {
                        let x = model.nodes[el.nodes[a]].coords;
                        for i in 0..3 {
                            t[i] += dn[k][0] * x[i];
                        }
                    }
                    let mut dl = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
                    if axisymmetric {
                        // Per radian: r ds, integrated exactly (3 points; OOFEM takes one point
                        // on a linear edge, its QUIRK: the total is right, the share of the two
                        // nodes is not where r varies along the edge).
                        let x = |a: usize| model.nodes[el.nodes[a]].coords[0];
                        dl *= local
                            .iter()
                            .enumerate()
                            .map(|(k, &a)| n[k] * x(a))
                            .sum::<f64>();
                    }
                    let point: [f64; 3] = std::array::from_fn(|i| {
                        let x = |a: usize| model.nodes[el.nodes[a]].coords[i];
                        local.iter().enumerate().map(|(k, &a)| n[k] * x(a)).sum()
                    });
                    let traction: Vec<(DofId, f64)> = match load.local {
                        true => edge_axes(model, e, (point, t), load),
                        false => comps().collect(),
                    };
                    for (k, &a) in local.iter().enumerate() {
                        out.extend(
                            traction
                                .iter()
                                .map(|&(d, c)| (el.nodes[a], d, c * n[k] * dl * w * thick)),
                        );
                    }
                }
            }
        }
        LoadKind::Surface => {
            for (e, local) in load_boundaries(model, load)? {
                let el = &model.elements[e];
                let shape = el.etype.shape();
                let face = shape.boundary_shape(local.len());
                let mut n = [0.0; 8];
                let mut dn = [[0.0; 3]; 8];
                let points = match local.len() {
                    3 => 3,
                    8 => 9,
                    _ => 4,
                };
                for qp in rule(face, points).expect("face rule") {
                    face.eval(qp.xi, &mut n, &mut dn);
                    let (mut g1, mut g2) = ([0.0; 3], [0.0; 3]);
                    for (k, &a) in local.iter().enumerate() {
                        let x = model.nodes[el.nodes[a]].coords;
                        for i in 0..3 {
                            g1[i] += dn[k][0] * x[i];
                            g2[i] += dn[k][1] * x[i];
                        }
                    }
                    let cr = [
                        g1[1] * g2[2] - g1[2] * g2[1],
                        g1[2] * g2[0] - g1[0] * g2[2],
                        g1[0] * g2[1] - g1[1] * g2[0],
                    ];
                    let da = (cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]).sqrt() * qp.weight;
                    let traction: Vec<(DofId, f64)> = match load.local {
                        true => {
                            let point: [f64; 3] = std::array::from_fn(|i| {
                                let x = |a: usize| model.nodes[el.nodes[a]].coords[i];
                                local.iter().enumerate().map(|(k, &a)| n[k] * x(a)).sum()
                            });
                            face_axes(model, e, point, cr, &load.components)
                        }
                        false => comps().collect(),
                    };
                    for (k, &a) in local.iter().enumerate() {
                        out.extend(
                            traction
                                .iter()
                                .map(|&(d, c)| (el.nodes[a], d, c * n[k] * da)),
                        );
                    }
                }
            }
        }
    }
    Ok(out)
}

/// A `csType 1` edge load's global components at a point of element `e`'s edge whose tangent
/// (along the edge's node order) is `t`: OOFEM's f = T f_local with T = [[n_y, n_x], [−n_x,
/// n_y]], n the edge's outward unit normal (outward by the element's geometry, whatever its node
/// order; OOFEM takes the normal from the node order, inward on a clockwise element).
fn edge_axes(
    model: &Model,
    e: usize,
    (point, t): ([f64; 3], [f64; 3]),
    load: &Load,
) -> Vec<(DofId, f64)> {
    let len = t[0].hypot(t[1]);
    let normal = [t[1], -t[0], 0.0];
    let sign = outward_sign(model, e, point, normal);
    let n = [sign * normal[0] / len, sign * normal[1] / len];
    let (f1, f2) = (load.components[0], load.components[1]);
    vec![(1, n[1] * f1 + n[0] * f2), (2, -n[0] * f1 + n[1] * f2)]
}

/// A `csType 1` surface load's global components at `point` of a face of element `e` whose
/// normal (g₁ × g₂, any length) is `normal`: f = f₁ x̂ + f₂ ŷ + f₃ n̂ with n̂ the outward unit
/// normal (by the element's geometry), x̂ horizontal, (n̂_y, −n̂_x, 0) normalized, or x̂ = (1, 0, 0)
/// on a horizontal face, and ŷ = n̂ × x̂: OOFEM's `LSpace` axes. OOFEM takes one normal per face
/// (the mean of its corners') and leaves x̂ unnormalized (its length is √(1 − n̂_z²)), QUIRKs:
/// the same on a flat face with a vertical tangential load or none; here the normal is the
/// face's own at each point, exact on a curved face.
pub fn face_axes(
    model: &Model,
    e: usize,
    point: [f64; 3],
    normal: [f64; 3],
    f: &[f64],
) -> Vec<(DofId, f64)> {
    let len = (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
    let sign = outward_sign(model, e, point, normal);
    let n = normal.map(|c| sign * c / len);
    let h = n[0].hypot(n[1]);
    let x = if (n[2].abs() - 1.0).abs() < 1e-5 {
        [1.0, 0.0, 0.0]
    } else {
        [n[1] / h, -n[0] / h, 0.0]
    };
    let y = [
        n[1] * x[2] - n[2] * x[1],
        n[2] * x[0] - n[0] * x[2],
        n[0] * x[1] - n[1] * x[0],
    ];
    (0..3)
        .map(|i| (i as DofId + 1, f[0] * x[i] + f[1] * y[i] + f[2] * n[i]))
        .collect()
}

/// +1 if `normal` at `point` of a boundary of element `e` points out of the element (away from
/// the centroid of its nodes), else −1.
pub fn outward_sign(model: &Model, e: usize, point: [f64; 3], normal: [f64; 3]) -> f64 {
    let el = &model.elements[e];
    let count = el.nodes.len() as f64;
    let centre: [f64; 3] = std::array::from_fn(|i| {
        el.nodes
            .iter()
            .map(|&a| model.nodes[a].coords[i])
            .sum::<f64>()
            / count
    });
    let side: f64 = (0..3).map(|i| (point[i] - centre[i]) * normal[i]).sum();
    if side < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// The element boundaries an edge or surface load acts on (see [`Load::boundaries`]).
pub(super) fn load_boundaries(
    model: &Model,
    load: &Load,
) -> Result<Vec<(usize, &'static [usize])>> {
    let set = &model.sets[load.set - 1];
    load.boundaries(set, &model.elements)
        .map_err(|msg| Error::Input {
            span: load.span.clone(),
            msg,
        })
}

/// Thickness of a 2D element (1 when the cross section gives none).
pub fn element_thickness(model: &Model, e: usize) -> f64 {
    model.cross_sections[model.elements[e].cross_section]
        .thick
        .unwrap_or(1.0)
}

/// ∫ N_a dV over element e (with thickness in 2D, per radian in axisymmetry, and area for bars).
fn element_shape_integrals(model: &Model, e: usize) -> Result<Vec<f64>> {
    let el = &model.elements[e];
    if el.etype.is_truss() {
        let x = truss_coords(model, e);
        let len = ((x[1][0] - x[0][0]).powi(2) + (x[1][1] - x[0][1]).powi(2)).sqrt();
        let area = model.cross_sections[el.cross_section].area;
        return Ok(vec![0.5 * area * len; 2]);
    }
    let shape = el.etype.shape();
    let nip = el.nip.unwrap_or(el.etype.default_nip());
    let qr = rule(shape, nip).expect("nip validated by the reader");
    let thick = match (shape.dim(), el.etype.is_axisymmetric()) {
        (2, false) => Some(element_thickness(model, e)),
        (2, true) => None,
        _ => Some(1.0),
    };
    let x: Vec<[f64; 3]> = el.nodes.iter().map(|&n| model.nodes[n].coords).collect();
    let mut w = vec![0.0; el.nodes.len()];
    crate::solid::continuum::integrate_shape(shape, &qr, thick, &x, &mut w).map_err(|k| {
        Error::Input {
            span: el.span.clone(),
            msg: format!("element {}: {}", el.label, k.msg),
        }
    })?;
    Ok(w)
}

/// End coordinates of a bar in its own plane (Truss1d: x; Truss2d cs 0: x–z, 1: x–y, 2: y–z).
pub fn truss_coords(model: &Model, e: usize) -> [[f64; 2]; 2] {
    let el = &model.elements[e];
    let (axes, dim) = (truss_axes(el), el.dof_ids().len());
    [0, 1].map(|k| in_bar_plane(model.nodes[el.nodes[k]].coords, axes, dim))
}
