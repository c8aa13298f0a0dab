//! Element mass (spec §1.8): consistent, M_ab = ∫ ρ N_a N_b dV (with the thickness of a plane
//! element, per radian in axisymmetry), or lumped by HRZ (the consistent diagonal scaled to the
//! element's mass, positive on every node, quadratic elements included); a bar's is ρAL/2 at
//! each end either way, as OOFEM's. Both hold a rigid translation's momentum exactly.

use super::continuum::integrate_shape_products;
use super::loads::{element_thickness, truss_coords};
use crate::error::{Error, Result};
use crate::fem::{rule, Shape};
use crate::model::Model;

/// The integration points of a mass matrix: exact for N_a N_b (times r in axisymmetry) on an
/// undistorted element.
fn mass_points(shape: Shape) -> usize {
    match shape {
        Shape::Line2 | Shape::Line3 => 3,
        Shape::Quad4 => 4,
        Shape::Quad8 => 9,
        Shape::Tri3 | Shape::Tri6 => 7,
        Shape::Tet4 => 4,
        Shape::Tet10 => 14,
        Shape::Hexa8 => 8,
        Shape::Hexa20 => 27,
        Shape::Wedge6 => 9,
    }
}

/// The scalar mass block of element `e` (row-major, nodes × nodes; the same for each of its
/// displacement directions), consistent or `lumped` (diagonal).
pub fn element_mass(model: &Model, e: usize, lumped: bool) -> Result<Vec<f64>> {
    let el = &model.elements[e];
    let rho = model.materials[el.material].density;
    if el.etype.is_truss() {
        let x = truss_coords(model, e);
        let len = (x[1][0] - x[0][0]).hypot(x[1][1] - x[0][1]);
        let half = 0.5 * rho * model.cross_sections[el.cross_section].area * len;
        return Ok(vec![half, 0.0, 0.0, half]);
    }
    let shape = el.etype.shape();
    let points = rule(shape, mass_points(shape)).expect("mass rule exists for every shape");
    let thick = match (shape.dim(), el.etype.is_axisymmetric()) {
        (2, false) => Some(element_thickness(model, e)),
        (2, true) => None,
        _ => Some(1.0),
    };
    let x: Vec<[f64; 3]> = el.nodes.iter().map(|&n| model.nodes[n].coords).collect();
    let mut m = integrate_shape_products(shape, &points, thick, &x).map_err(|k| Error::Input {
        span: el.span.clone(),
        msg: format!("element {}: {}", el.label, k.msg),
    })?;
    m.iter_mut().for_each(|v| *v *= rho);
    if lumped {
        let nn = x.len();
        let total: f64 = m.iter().sum();
        let diagonal: f64 = (0..nn).map(|a| m[a * nn + a]).sum();
        let mut d = vec![0.0; nn * nn];
        for a in 0..nn {
            d[a * nn + a] = m[a * nn + a] * total / diagonal;
        }
        m = d;
    }
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(element: &str, nodes: &str, domain: &str, cs: &str) -> Model {
        let text = format!(
            "m.out\nmass\nNonLinearDynamic nsteps 1 deltat 1\ndomain {domain}\nOutputManager\n\
             ndofman {} nelem 1 ncrosssect 1 nmat 1 nbc 0 nic 0 nltf 1 nset 1\n{nodes}\n\
             {element} crossSect 1 mat 1\n{cs}\nIsoLE 1 d 7.5 E 1 n 0.3 tAlpha 0\n\
             ConstantFunction 1 f(t) 1\nSet 1 allelements\n",
            nodes.lines().count()
        );
        crate::input::read_model_str(&text, "m.in").unwrap().model
    }

    /// Consistent and lumped masses sum to ρ × the element's volume (a rigid translation's
    /// momentum): a distorted 8-node quadrilateral with thickness 0.2 (area 2.01), a quadratic
    /// tetrahedron (volume 1/6), an axisymmetric ring per radian (∫ r dA = 1.5 × 1 on r ∈ [1, 2]);
    /// the lumped 8-node masses are all positive (row sums of the consistent one are not).
    #[test]
    fn masses_sum_to_the_elements_mass() {
        let cases = [
            (
                model(
                    "QPlaneStress2d 1 nodes 8 1 2 3 4 5 6 7 8",
                    "node 1 coords 2 0 0\nnode 2 coords 2 2.1 0\nnode 3 coords 2 1.9 1.1\n\
                     node 4 coords 2 0 0.9\nnode 5 coords 2 1.05 0\nnode 6 coords 2 2.0 0.55\n\
                     node 7 coords 2 0.95 1.0\nnode 8 coords 2 0 0.45",
                    "2dPlaneStress",
                    "SimpleCS 1 thick 0.2 material 1 set 1",
                ),
                7.5 * 0.2 * 2.01,
            ),
            (
                model(
                    "QTRSpace 1 nodes 10 1 2 3 4 5 6 7 8 9 10",
                    "node 1 coords 3 0 0 0\nnode 2 coords 3 1 0 0\nnode 3 coords 3 0 1 0\n\
                     node 4 coords 3 0 0 1\nnode 5 coords 3 0.5 0 0\nnode 6 coords 3 0.5 0.5 0\n\
                     node 7 coords 3 0 0.5 0\nnode 8 coords 3 0 0 0.5\nnode 9 coords 3 0.5 0 0.5\n\
                     node 10 coords 3 0 0.5 0.5",
                    "3d",
                    "SimpleCS 1 material 1 set 1",
                ),
                7.5 / 6.0,
            ),
            (
                model(
                    "L4Axisymm 1 nodes 4 1 2 3 4",
                    "node 1 coords 2 1 0\nnode 2 coords 2 2 0\nnode 3 coords 2 2 1\nnode 4 coords 2 1 1",
                    "2dPlaneStress",
                    "SimpleCS 1 material 1 set 1",
                ),
                7.5 * 1.5,
            ),
        ];
        for (m, mass) in cases {
            let nn = m.elements[0].nodes.len();
            for lumped in [false, true] {
                let me = element_mass(&m, 0, lumped).unwrap();
                let total: f64 = me.iter().sum();
                assert!((total / mass - 1.0).abs() < 1e-12, "{total} vs {mass}");
                if lumped {
                    assert!((0..nn).all(|a| me[a * nn + a] > 0.0), "{me:?}");
                }
            }
        }
    }
}
