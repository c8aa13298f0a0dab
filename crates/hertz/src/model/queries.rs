//! Questions about a model that several parts ask: its size, the stiffness of its elements.

use super::{Model, SegmentKind};

/// Diagonal of the model's bounding box (a length scale for tolerances).
pub fn model_size(model: &Model) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for n in &model.nodes {
        for i in 0..3 {
            lo[i] = lo[i].min(n.coords[i]);
            hi[i] = hi[i].max(n.coords[i]);
        }
    }
    let d2: f64 = (0..3).map(|i| (hi[i] - lo[i]).max(0.0).powi(2)).sum();
    d2.sqrt().max(1e-300)
}

/// The size of the nodes' coordinates: the largest |X_i|, at least the model's size. A contact
/// gap is a difference of positions of this size, so its round-off is ε times it: a model far
/// from the origin (a mesh in a machine's coordinates, millimetres 10⁵ away) resolves gaps no
/// finer than that, however small the model.
pub fn coordinate_size(model: &Model) -> f64 {
    let far = (model.nodes.iter())
        .flat_map(|n| n.coords.iter())
        .fold(0.0f64, |a, x| a.max(x.abs()));
    far.max(model_size(model))
}

/// Young's modulus of the stiffest element on the master segments `segments` (infinite when one
/// is rigid): with the slave's, the modulus of the friction law's c_T.
pub fn master_young(model: &Model, segments: &[usize]) -> f64 {
    let mut young = 0.0f64;
    for &g in segments {
        match &model.segments[g].kind {
            SegmentKind::Edges { edges: sides } | SegmentKind::Faces { faces: sides } => {
                for &(e, _) in sides {
                    young = young.max(model.materials[model.elements[e].material].young());
                }
            }
            _ => return f64::INFINITY,
        }
    }
    young
}
/// Young's modulus of the stiffest element at each node (penalties chosen from the mesh).
pub fn stiffest_young(model: &Model) -> std::collections::HashMap<usize, f64> {
    let mut young = std::collections::HashMap::new();
    for el in &model.elements {
        let e = model.materials[el.material].young();
        for &n in &el.nodes {
            let v = young.entry(n).or_insert(0.0f64);
            *v = v.max(e);
        }
    }
    young
}

/// The nodes of every contact condition's surfaces, both sides: its slave nodes (a mortar
/// condition's slave edges or faces), the deformable master edges and faces it meets, and a
/// node-to-node condition's masters; sorted, once each.
pub fn contact_surface_nodes(model: &Model) -> Vec<usize> {
    let mut nodes = Vec::new();
    for c in &model.contacts {
        let segments: Vec<usize> = match &c.pairing {
            super::Pairing::NodeToNode { pairs } => {
                nodes.extend(pairs.iter().flat_map(|&(m, s)| [m, s]));
                continue;
            }
            super::Pairing::NodeToSegment {
                nodes: slaves,
                segments,
            } => {
                nodes.extend(slaves);
                segments.clone()
            }
            super::Pairing::Mortar { slave, segments } => {
                segments.iter().chain([slave]).copied().collect()
            }
        };
        for g in segments {
            if let SegmentKind::Edges { edges: sides } | SegmentKind::Faces { faces: sides } =
                &model.segments[g].kind
            {
                for &(e, b) in sides {
                    nodes.extend(model.elements[e].boundary_nodes(b));
                }
            }
        }
    }
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}
