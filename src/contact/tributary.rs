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

/// Tributary data of every node of `nodes` (the contact nodes of one condition), in that order.
pub fn tributaries(model: &Model, nodes: &[usize]) -> Vec<Tributary> {
    let members: HashSet<usize> = nodes.iter().copied().collect();
    let mut out: HashMap<usize, Tributary> = HashMap::new();
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
            let x: Vec<[f64; 3]> = bn.iter().map(|&n| model.nodes[n].coords).collect();
            let shares: Vec<f64> = if shape.dim() == 2 {
                let thick = crate::solid::loads::element_thickness(model, ei);
                if bn.len() == 2 {
                    vec![0.5 * dist(x[0], x[1]) * thick; 2]
                } else {
                    // Quadratic edge (ends, middle): Simpson weights 1/6, 1/6, 2/3.
                    let l = (dist(x[0], x[2]) + dist(x[2], x[1])) * thick;
                    vec![l / 6.0, l / 6.0, 2.0 * l / 3.0]
                }
            } else {
                let a = if bn.len() == 3 {
                    triangle_area(x[0], x[1], x[2])
                } else {
                    triangle_area(x[0], x[1], x[2]) + triangle_area(x[0], x[2], x[3])
                };
                vec![a / bn.len() as f64; bn.len()]
            };
            for (k, (&n, s)) in bn.iter().zip(shares).enumerate() {
                let t = out.entry(n).or_default();
                t.measure += s;
                for (j, &m) in bn.iter().enumerate() {
                    if j != k && !t.neighbors.contains(&m) {
                        t.neighbors.push(m);
                    }
                }
            }
        }
    }
    nodes
        .iter()
        .map(|n| out.get(n).cloned().unwrap_or_default())
        .collect()
}
