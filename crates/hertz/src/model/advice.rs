//! Warnings about a model that reads right but would not compute what its author expects.

use super::{Model, StressMode};
use crate::fem::Shape;

/// Bulk over shear modulus from which plain linear elements lock: on a thick ring in plane
/// strain (8 × 8 elements, its inner edge moved out), four-node quadrilaterals are 2.4 % too
/// stiff at K/G = 33 (ν = 0.485), 7.8 % at K/G = 100 and 40 % at K/G = 500, three-node
/// triangles 7.8, 21 and 94 %; eight-node quadrilaterals are exact to 10⁻⁵ at all of them.
pub const LOCKING_BULK_RATIO: f64 = 30.0;

/// One warning per material that is nearly incompressible (K/G ≥ [`LOCKING_BULK_RATIO`], of the
/// small-strain limit for a hyperelastic law), or plastic (isochoric flow), on linear continuum
/// elements in plane strain or 3D that are not barred: these lock (volumetric locking), too
/// stiff by percent to tens of percent, silently.
pub fn locking_warnings(model: &Model) -> Vec<String> {
    let mut out = Vec::new();
    for (m, material) in model.materials.iter().enumerate() {
        let nu = material.poisson();
        let ratio = 2.0 * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu));
        let plastic = matches!(material.law, super::MaterialLaw::Mises(_));
        if !(ratio >= LOCKING_BULK_RATIO) && !plastic {
            continue;
        }
        let locking: Vec<&super::Element> = model
            .elements
            .iter()
            .filter(|e| e.material == m && locks(e))
            .collect();
        let Some(first) = locking.first() else {
            continue;
        };
        let kinds: std::collections::BTreeSet<&str> =
            locking.iter().map(|e| e.etype.name()).collect();
        let three_d = first.etype.mode() == StressMode::ThreeD;
        let what = if ratio >= LOCKING_BULK_RATIO {
            format!("is nearly incompressible (K/G = {ratio:.0}, ν = {nu:.4})")
        } else {
            "is a MisesMat, whose plastic flow keeps the volume,".to_string()
        };
        out.push(format!(
            "material {} {what} on {} linear elements ({}, e.g. element {}): these lock, too \
             stiff by percent to tens of percent (a thick ring in plane strain: +8 % at K/G = \
             100, +40 % at K/G = 500 on four-node quadrilaterals); use the barred elements \
             ({}) or quadratic ones ({})",
            m + 1,
            locking.len(),
            kinds.into_iter().collect::<Vec<_>>().join(", "),
            first.label,
            if three_d {
                "LSpaceBB"
            } else {
                "Quad1PlaneStrainBB"
            },
            if three_d {
                "QSpace or QTRSpace"
            } else {
                "QPlaneStrain or QTrPlaneStrain"
            }
        ));
    }
    out
}

/// Whether an element locks near incompressibility: a linear continuum element in plane strain
/// or 3D, not barred.
fn locks(e: &super::Element) -> bool {
    matches!(e.etype.mode(), StressMode::PlaneStrain | StressMode::ThreeD)
        && matches!(
            e.etype.shape(),
            Shape::Tri3 | Shape::Quad4 | Shape::Tet4 | Shape::Hexa8 | Shape::Wedge6
        )
        && !e.bbar
}
