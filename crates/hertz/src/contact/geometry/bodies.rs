//! The bodies behind a master surface: the elements whose edges or faces form it, to tell
//! whether a contact node lies inside one of them at the current state. A node inside the
//! master's body has crossed the surface, whatever its gap to the partner the search chose says
//! (past a crease the nearest part of a folded surface can face the node from the open side).

use crate::contact::search::broad::BroadPhase;
use crate::fem::geometry::locate;
use crate::model::Model;

/// A point inside this much of the reference element (in its own coordinates) is inside: a node
/// held on the surface (a gap of zero, to round-off) is not.
const INSIDE_MARGIN: f64 = 1e-9;

/// The elements of a master surface (model element indices, each once).
#[derive(Debug, Clone, Default)]
pub struct MasterBodies {
    pub elements: Vec<usize>,
}

/// The master's elements at one state: their current node positions and boxes.
pub struct BodiesAt {
    x: Vec<Vec<[f64; 3]>>,
    boxes: BroadPhase,
}

/// An element of a master's body that holds a point, and how deep: the point's distance to the
/// element's master edges or faces (`element` a model element index).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inside {
    pub element: usize,
    pub depth: f64,
}

impl MasterBodies {
    /// The bodies of the master items owned by `elements` (in any order, repeated or not).
    pub fn new(elements: impl Iterator<Item = usize>) -> MasterBodies {
        let mut elements: Vec<usize> = elements.collect();
        elements.sort_unstable();
        elements.dedup();
        MasterBodies { elements }
    }

    /// The elements at the node positions `pos(n)`.
    pub fn at<E>(
        &self,
        model: &Model,
        pos: impl Fn(usize) -> Result<[f64; 3], E>,
    ) -> Result<BodiesAt, E> {
        let x: Vec<Vec<[f64; 3]>> = self
            .elements
            .iter()
            .map(|&e| model.elements[e].nodes.iter().map(|&n| pos(n)).collect())
            .collect::<Result<_, E>>()?;
        // A quadratic element's boundary can bulge out of its nodes' box: the box is widened.
        let boxes = BroadPhase::new(self.elements.iter().zip(&x).map(|(&e, pts)| {
            use crate::fem::Shape::*;
            let curved = matches!(
                model.elements[e].etype.shape(),
                Tri6 | Quad8 | Tet10 | Hexa20
            );
            (&pts[..], curved)
        }));
        Ok(BodiesAt { x, boxes })
    }
}

impl BodiesAt {
    /// The element of `bodies` that holds the point `p` strictly inside, skipping the elements
    /// of node `node` (a node lies on its own elements' boundaries); `depth(e, p)` measures how
    /// deep.
    pub fn containing(
        &self,
        model: &Model,
        bodies: &MasterBodies,
        p: [f64; 3],
        node: usize,
        depth: impl Fn(usize, [f64; 3]) -> f64,
    ) -> Option<Inside> {
        if self.boxes.is_empty() {
            return None;
        }
        self.boxes
            .intersecting(p, p)
            .into_iter()
            .filter(|&k| !model.elements[bodies.elements[k]].nodes.contains(&node))
            .find(|&k| {
                let shape = model.elements[bodies.elements[k]].etype.shape();
                locate(shape, &self.x[k], p)
                    .is_some_and(|xi| shape.inside_margin(xi) > INSIDE_MARGIN)
            })
            .map(|k| Inside {
                element: bodies.elements[k],
                depth: depth(bodies.elements[k], p),
            })
    }
}

/// Distance from `p` to the segment from `a` to `b`.
pub fn segment_distance(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let t: [f64; 3] = std::array::from_fn(|i| b[i] - a[i]);
    let tt: f64 = t.iter().map(|v| v * v).sum();
    let s = if tt > 0.0 {
        ((0..3).map(|i| (p[i] - a[i]) * t[i]).sum::<f64>() / tt).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (0..3)
        .map(|i| (p[i] - a[i] - s * t[i]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Distance from `p` to the plane through the polygon `corners` (its area-weighted normal).
pub fn plane_distance(p: [f64; 3], corners: &[[f64; 3]]) -> f64 {
    let n = corners.len();
    let c: [f64; 3] = std::array::from_fn(|i| corners.iter().map(|x| x[i]).sum::<f64>() / n as f64);
    let mut normal = [0.0; 3];
    for k in 0..n {
        let (a, b) = (corners[k], corners[(k + 1) % n]);
        normal[0] += (a[1] - c[1]) * (b[2] - c[2]) - (a[2] - c[2]) * (b[1] - c[1]);
        normal[1] += (a[2] - c[2]) * (b[0] - c[0]) - (a[0] - c[0]) * (b[2] - c[2]);
        normal[2] += (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]);
    }
    let len = normal.iter().map(|v| v * v).sum::<f64>().sqrt();
    if len == 0.0 {
        return f64::NAN;
    }
    ((0..3).map(|i| (p[i] - c[i]) * normal[i]).sum::<f64>() / len).abs()
}
