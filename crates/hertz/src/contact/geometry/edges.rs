//! A 2D master surface made of element edges (straight 2-node or quadratic 3-node), with a normal
//! field that is continuous across vertices.
//!
//! Glossary: `s` ∈ [0, 1] runs along an edge from its first to its second end node; `x(s)` is the
//! edge's point, `x'(s)` its tangent; `n_a` the nodal normal of node a: the normalized sum of the
//! unit outward normals of the edges meeting at a (for the middle node of a quadratic edge, that
//! edge's normal there); `ñ(s) = Σ N_a(s) n_a` the interpolated (smoothed) normal.
//!
//! Why smoothed normals: the outward normal of a polygon jumps at every vertex, so a node that
//! sits on a vertex (matched meshes) or slides over one sees its contact force turn abruptly, and
//! convex vertices leave "blind zones" where no edge projects. Projecting along the continuous
//! field ñ instead — the contact point of x_s is the s with (x_s − x(s)) ∥ ñ(s) — gives every node
//! near the surface exactly one contact point, continuous across vertices, where the force acts
//! along ñ. For a straight chain ñ is the edge normal and this is the usual closest-point
//! projection.
//!
//! Ends of an open surface: beyond an end node the surface continues along its end tangent with the
//! end node's normal, so a node just past the end still has a contact point; the condition weighs
//! its force down to zero over the node's tributary length (see `n2s`).

use super::scalar::Scalar;
use crate::contact::dual::Dual;
use crate::model::{Model, SegmentKind};
use std::collections::HashMap;

/// One edge of a master surface.
#[derive(Debug, Clone)]
pub struct Edge {
    /// Index of the contact segment (model) the edge belongs to.
    pub segment: usize,
    pub element: usize,
    /// Model node indices: (end 1, end 2) or (end 1, end 2, middle).
    pub nodes: Vec<usize>,
    /// +1 when (t_y, −t_x), t = x₂ − x₁, points out of the element, else −1.
    pub side: f64,
    /// The element uses large deformation: normals follow the deformed edge.
    pub nlgeo: bool,
}

/// The edges of one condition's edge segments, with their adjacency and reference normals.
#[derive(Debug, Clone, Default)]
pub struct EdgeSurface {
    pub edges: Vec<Edge>,
    /// Edges having a node as one of their end nodes.
    pub at_node: HashMap<usize, Vec<usize>>,
    /// Nodal normals of the reference configuration (end nodes and middle nodes).
    ref_normals: HashMap<usize, [f64; 2]>,
}

/// Shape values and derivatives of a 2- or 3-node edge at s ∈ [0, 1].
pub fn shape<T: Scalar>(n_nodes: usize, s: T) -> ([T; 3], [T; 3]) {
    if n_nodes == 2 {
        let one = s.cst(1.0);
        ([one - s, s, s.cst(0.0)], [s.cst(-1.0), one, s.cst(0.0)])
    } else {
        // η = 2s − 1 ∈ [−1, 1]; nodes (end 1, end 2, middle).
        let eta = s * 2.0 - 1.0;
        (
            [
                eta * (eta - 1.0) * 0.5,
                eta * (eta + 1.0) * 0.5,
                -(eta * eta) + 1.0,
            ],
            [(eta - 0.5) * 2.0, (eta + 0.5) * 2.0, eta * -4.0],
        )
    }
}

/// Σ N_a v_a for 2D vectors.
fn combine<T: Scalar>(w: &[T; 3], v: &[[T; 2]], k: usize) -> [T; 2] {
    let mut r = [v[0][0] * w[0], v[0][1] * w[0]];
    for a in 1..k {
        r[0] = r[0] + v[a][0] * w[a];
        r[1] = r[1] + v[a][1] * w[a];
    }
    r
}

fn cross<T: Scalar>(a: [T; 2], b: [T; 2]) -> T {
    a[0] * b[1] - a[1] * b[0]
}

/// Unit outward normal of an edge at s, from node positions `x` (ends first).
pub fn edge_normal<T: Scalar>(x: &[[T; 2]], side: f64, s: T) -> [T; 2] {
    let (_, dn) = shape(x.len(), s);
    let t = combine(&dn, x, x.len());
    let len = (t[0] * t[0] + t[1] * t[1]).sqrt();
    [t[1] * side / len, -t[0] * side / len]
}

/// Geometry of one edge for the projection: node positions and nodal normals (ends first), and
/// whether the surface is open beyond each end.
pub struct EdgeGeometry<T> {
    pub x: Vec<[T; 2]>,
    pub n: Vec<[T; 2]>,
    pub open: [bool; 2],
}

impl<T: Scalar> EdgeGeometry<T> {
    /// Coefficients c_a(s) with x(s) = Σ c_a x_a, their derivatives, and the end beyond which s
    /// lies (an open end, where the surface continues along the end tangent).
    pub fn coefficients(&self, s: T) -> ([T; 3], [T; 3], Option<usize>) {
        let k = self.x.len();
        let beyond = if self.open[0] && s.val() < 0.0 {
            Some(0)
        } else if self.open[1] && s.val() > 1.0 {
            Some(1)
        } else {
            None
        };
        match beyond {
            None => {
                let (w, dw) = shape(k, s);
                (w, dw, None)
            }
            Some(e) => {
                let (w, dw) = shape(k, s.cst(e as f64));
                let ds = s - e as f64;
                let mut c = w;
                for a in 0..k {
                    c[a] = w[a] + dw[a] * ds;
                }
                (c, dw, Some(e))
            }
        }
    }

    /// Point, tangent, smoothed normal (not normalized) and its derivative at s.
    pub fn eval(&self, s: T) -> ([T; 2], [T; 2], [T; 2], [T; 2]) {
        let k = self.x.len();
        let (c, dc, beyond) = self.coefficients(s);
        let (x, t) = (combine(&c, &self.x, k), combine(&dc, &self.x, k));
        match beyond {
            None => {
                let (w, dw) = shape(k, s);
                (x, t, combine(&w, &self.n, k), combine(&dw, &self.n, k))
            }
            Some(e) => {
                let zero = s.cst(0.0);
                (x, t, self.n[e], [zero, zero])
            }
        }
    }

    /// Unit tangent at end `e` (0 or 1) pointing out of the edge, and the end point.
    pub fn end_direction(&self, e: usize) -> ([T; 2], [T; 2]) {
        let k = self.x.len();
        let (w, dw) = shape(k, self.x[0][0].cst(e as f64));
        let (x, t) = (combine(&w, &self.x, k), combine(&dw, &self.x, k));
        let len = (t[0] * t[0] + t[1] * t[1]).sqrt();
        let sign = if e == 0 { -1.0 } else { 1.0 };
        ([t[0] * sign / len, t[1] * sign / len], x)
    }

    /// F(s) = (x_s − x(s)) × ñ(s): zero at the contact point; and F'(s).
    fn residual(&self, xs: [T; 2], s: T) -> (T, T) {
        let (x, t, n, dn) = self.eval(s);
        let d = [xs[0] - x[0], xs[1] - x[1]];
        (cross(d, n), cross([-t[0], -t[1]], n) + cross(d, dn))
    }

    /// Gap g = (x_s − x(s))·n̂(s) and the unit normal at s.
    pub fn gap(&self, xs: [T; 2], s: T) -> (T, [T; 2]) {
        let (x, _, n, _) = self.eval(s);
        let len = (n[0] * n[0] + n[1] * n[1]).sqrt();
        let nh = [n[0] / len, n[1] / len];
        ((xs[0] - x[0]) * nh[0] + (xs[1] - x[1]) * nh[1], nh)
    }
}

impl EdgeGeometry<f64> {
    /// Contact point parameter of `xs` by Newton on F(s) = 0, started at the chord projection.
    /// None when it does not converge or the normal field degenerates. Worked from the edge's
    /// first node, as the face projection is ([`super::faces::FaceGeometry::project`]).
    pub fn project(&self, xs: [f64; 2]) -> Option<f64> {
        let o = self.x[0];
        let local = EdgeGeometry {
            x: self.x.iter().map(|p| [p[0] - o[0], p[1] - o[1]]).collect(),
            n: self.n.clone(),
            open: self.open,
        };
        local.project_from_origin([xs[0] - o[0], xs[1] - o[1]])
    }

    fn project_from_origin(&self, xs: [f64; 2]) -> Option<f64> {
        let (a, b) = (self.x[0], self.x[1]);
        let t = [b[0] - a[0], b[1] - a[1]];
        let tt = t[0] * t[0] + t[1] * t[1];
        let mut s = ((xs[0] - a[0]) * t[0] + (xs[1] - a[1]) * t[1]) / tt;
        let (mut last, mut slope) = (f64::INFINITY, 0.0);
        for _ in 0..40 {
            let (f, df) = self.residual(xs, s);
            if !(df.abs() > 1e-300) {
                return None;
            }
            // Limit the step: a far node must not jump across the whole surface.
            let step = (f / df).clamp(-0.5, 0.5);
            s -= step;
            (last, slope) = (step.abs(), df.abs());
            if last < 1e-14 * (1.0 + s.abs()) {
                break;
            }
        }
        // Steps that stall at round-off have settled too: at a kink of the normal field (an
        // edge's end), or for a node far over a short edge, where F = d × ñ carries ε·|d|·|ñ|
        // (d = x_s − x(s)) and its slope F' is the edge's length.
        let (x, _, n, _) = self.eval(s);
        let d = [xs[0] - x[0], xs[1] - x[1]];
        let noise = 64.0 * f64::EPSILON * d[0].hypot(d[1]) * n[0].hypot(n[1]) / slope;
        if !(last < 1e-10_f64.max(noise)) {
            return None;
        }
        (n[0] * n[0] + n[1] * n[1] > 1e-24).then_some(s)
    }
}

impl EdgeGeometry<Dual> {
    /// The contact parameter as a dual: one Newton step from the converged `s0` makes its
    /// derivative with respect to the unknowns exact.
    pub fn project_dual(&self, xs: [Dual; 2], s0: f64) -> Dual {
        let s = Dual::constant(s0, xs[0].n);
        let (f, df) = self.residual(xs, s);
        s - f / df
    }
}

impl EdgeSurface {
    /// The surface of the edge segments `segments` (model segment indices; rigid ones skipped).
    pub fn new(model: &Model, segments: &[usize]) -> EdgeSurface {
        let mut surf = EdgeSurface::default();
        for &g in segments {
            let SegmentKind::Edges { edges } = &model.segments[g].kind else {
                continue;
            };
            for &(e, b) in edges {
                let el = &model.elements[e];
                let nodes = el.boundary_nodes(b);
                let k = surf.edges.len();
                for &end in &nodes[..2] {
                    surf.at_node.entry(end).or_default().push(k);
                }
                surf.edges.push(Edge {
                    segment: g,
                    element: e,
                    side: outward_side(model, e, &nodes),
                    nodes,
                    nlgeo: el.nlgeo,
                });
            }
        }
        let reference = |n: usize| {
            let c = model.nodes[n].coords;
            [c[0], c[1]]
        };
        let mut normals = HashMap::new();
        for (k, edge) in surf.edges.iter().enumerate() {
            for (i, &a) in edge.nodes.iter().enumerate() {
                if i == 2 {
                    let x: Vec<[f64; 2]> = edge.nodes.iter().map(|&n| reference(n)).collect();
                    normals.insert(a, edge_normal(&x, edge.side, 0.5));
                } else {
                    normals.entry(a).or_insert_with(|| {
                        surf.nodal_normal(k, a, &|e, n| reference(surf.edges[e].nodes[n]))
                    });
                }
            }
        }
        surf.ref_normals = normals;
        surf
    }

    /// Whether the surface ends at node `a` (only one edge has it as an end node).
    pub fn is_open_end(&self, a: usize) -> bool {
        self.at_node.get(&a).is_none_or(|v| v.len() < 2)
    }

    /// Reference nodal normal of a node of the surface.
    pub fn reference_normal(&self, a: usize) -> [f64; 2] {
        self.ref_normals[&a]
    }

    /// Nodal normal of end node `a` of edge `k`: the normalized sum of the unit outward normals,
    /// at a, of the edges meeting there. `pos(e, i)` gives the position of node i of edge e.
    pub fn nodal_normal<T: Scalar>(
        &self,
        k: usize,
        a: usize,
        pos: &dyn Fn(usize, usize) -> [T; 2],
    ) -> [T; 2] {
        let mut sum: Option<[T; 2]> = None;
        let empty = Vec::new();
        let edges = self.at_node.get(&a).unwrap_or(&empty);
        for &e in edges.iter().chain(edges.is_empty().then_some(&k)) {
            let edge = &self.edges[e];
            let x: Vec<[T; 2]> = (0..edge.nodes.len()).map(|i| pos(e, i)).collect();
            let s = x[0][0].cst(if edge.nodes[0] == a { 0.0 } else { 1.0 });
            let n = edge_normal(&x, edge.side, s);
            sum = Some(match sum {
                None => n,
                Some(m) => [m[0] + n[0], m[1] + n[1]],
            });
        }
        let m = sum.expect("an edge has its end nodes");
        let len = (m[0] * m[0] + m[1] * m[1]).sqrt();
        [m[0] / len, m[1] / len]
    }

    /// Nodes whose positions the current normals of edge `k` depend on: its own nodes, then (for
    /// large deformation) the nodes of the edges meeting it at its ends.
    pub fn support(&self, k: usize) -> Vec<usize> {
        let edge = &self.edges[k];
        let mut out = edge.nodes.clone();
        if edge.nlgeo {
            for &end in &edge.nodes[..2] {
                for &e in self.at_node.get(&end).into_iter().flatten() {
                    for &n in &self.edges[e].nodes {
                        if !out.contains(&n) {
                            out.push(n);
                        }
                    }
                }
            }
        }
        out
    }
}

/// Orientation factor of an edge: +1 if (t_y, −t_x) of (first → second node) points away from
/// the element's centroid.
fn outward_side(model: &Model, e: usize, nodes: &[usize]) -> f64 {
    let el = &model.elements[e];
    let (x1, x2) = (model.nodes[nodes[0]].coords, model.nodes[nodes[1]].coords);
    let n = [x2[1] - x1[1], -(x2[0] - x1[0])];
    let k = el.nodes.len() as f64;
    let c = el.nodes.iter().fold([0.0, 0.0], |acc, &m| {
        let x = model.nodes[m].coords;
        [acc[0] + x[0] / k, acc[1] + x[1] / k]
    });
    let m = [0.5 * (x1[0] + x2[0]), 0.5 * (x1[1] + x2[1])];
    if (c[0] - m[0]) * n[0] + (c[1] - m[1]) * n[1] > 0.0 {
        -1.0
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Nodes over an edge far from it (up to 10⁸ of its length away, as a coarse body's node
    /// over a fine mesh) are projected: Newton's last steps there are the round-off of the
    /// residual (ε times the distance) over its slope (the edge's length), above 1e-14 of the
    /// parameter, and settle no further; each such point is still found, to 1e-6. Edges of every
    /// direction and length, straight normal fields (and, near the edge, end normals up to 40°
    /// apart), points anywhere along the edge and past its open end.
    #[test]
    fn nodes_far_over_an_edge_are_projected_onto_it() {
        let mut rand = crate::testing::uniform(987654321);
        let mut checked = 0;
        for _ in 0..2000 {
            let len = 10f64.powf(4.0 * rand() - 2.0);
            let phi = 6.3 * rand();
            let t = [phi.cos(), phi.sin()];
            let a = [10.0 * rand() - 5.0, 10.0 * rand() - 5.0];
            let b = [a[0] + len * t[0], a[1] + len * t[1]];
            let normal = |turn: f64| {
                let (c, s) = (turn.cos(), turn.sin());
                [c * -t[1] - s * t[0], s * -t[1] + c * t[0]]
            };
            let turn = if rand() < 0.5 { 0.7 } else { 0.0 };
            let geom = EdgeGeometry {
                x: vec![a, b],
                n: vec![normal(turn * (rand() - 0.5)), normal(turn * (rand() - 0.5))],
                open: [false, true],
            };
            let target = 1.2 * rand();
            let (p, _, np, _) = geom.eval(target);
            let nl = (np[0] * np[0] + np[1] * np[1]).sqrt();
            // Far only over a straight normal field: over turning normals a far node's rays
            // fan out and it may have no contact point (it meets another edge first).
            let gap = match turn > 0.0 {
                true => len * 0.25 * rand(),
                false => len * 10f64.powf(9.0 * rand() - 1.0),
            };
            let xs = [p[0] + gap * np[0] / nl, p[1] + gap * np[1] / nl];
            let s = geom
                .project(xs)
                .unwrap_or_else(|| panic!("refused: len {len:e}, gap {gap:e}, at {target}"));
            assert!(
                (s - target).abs() < 1e-6,
                "s = {s} for {target}, gap {gap:e}"
            );
            checked += 1;
        }
        assert_eq!(checked, 2000);
    }
}
