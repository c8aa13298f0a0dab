//! What each contact node stands for on its own surface: its tributary length·thickness (2D) or
//! area (3D), for the pressure output, and its neighbours on that surface, for the weights at the
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
    /// The thickness of its 2D element (unused in 3D).
    thick: f64,
    plane: bool,
    /// Its element is in large deformation: its current measure is the one that counts.
    pub nlgeo: bool,
}

impl Facet {
    /// Each node's share of the facet's length × thickness (2D) or area (3D) at positions `x`
    /// (in the facet's node order).
    pub fn shares(&self, x: &[[f64; 3]]) -> Vec<f64> {
        if self.plane {
            if x.len() == 2 {
                vec![0.5 * dist(x[0], x[1]) * self.thick; 2]
            } else {
                // Quadratic edge (ends, middle): Simpson weights 1/6, 1/6, 2/3.
                let l = (dist(x[0], x[2]) + dist(x[2], x[1])) * self.thick;
                vec![l / 6.0, l / 6.0, 2.0 * l / 3.0]
            }
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
            out.push(Facet {
                nodes: bn,
                thick: if plane {
                    crate::solid::loads::element_thickness(model, ei)
                } else {
                    0.0
                },
                plane,
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
}

impl PressureAreas {
    /// The areas of the contact nodes `nodes` of one condition.
    pub fn new(model: &Model, nodes: &[usize]) -> PressureAreas {
        let index: HashMap<usize, usize> = nodes.iter().enumerate().map(|(k, &n)| (n, k)).collect();
        let mut fixed = vec![0.0; nodes.len()];
        let mut moving = Vec::new();
        for f in facets(model, nodes) {
            let slots: Vec<usize> = f.nodes.iter().map(|n| index[n]).collect();
            if f.nlgeo {
                moving.push((f, slots));
                continue;
            }
            let x: Vec<[f64; 3]> = f.nodes.iter().map(|&n| model.nodes[n].coords).collect();
            for (&k, s) in slots.iter().zip(f.shares(&x)) {
                fixed[k] += s;
            }
        }
        PressureAreas { moving, fixed }
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
