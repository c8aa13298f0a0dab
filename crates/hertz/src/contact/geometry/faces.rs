//! A 3D master surface made of element faces (linear triangles and bilinear quadrilaterals of
//! LSpace, LTRSpace and LWedge; the curved 6-node triangles and 8-node quadrilaterals of QTRSpace
//! and QSpace), with a normal field that is continuous across edges and corners: the 3D
//! counterpart of [`super::edges`].
//!
//! Glossary: (ξ, η) the face parameters — barycentric for a triangle, x = (1 − ξ − η)x₀ + ξx₁ +
//! ηx₂, bilinear on [−1, 1]² for a quadrilateral with its corners in cyclic order (a quadratic
//! face: the same parameters, its map through its mid-sides too); `x_ξ`, `x_η` the
//! tangents; `n_a` the nodal normal of node a (normalized sum of the unit outward normals of the
//! faces meeting there); `ñ = Σ N_a n_a` the smoothed normal. A node's contact point is where the
//! ray along ñ through it meets the face: the residual r_α = (x_s − x)·x_α − ((x_s − x)·ñ)(ñ·x_α)/
//! (ñ·ñ), α = ξ, η, vanishes.
//!
//! Open boundary of the surface: a face edge that no other face of the surface shares. Past it the
//! face map extends linearly (bilinearly) with the normal of its edge; the condition weighs the
//! force down over the node's tributary extent there, as at the end of a 2D master.

use super::scalar::Scalar;
use crate::model::{Model, SegmentKind};
use std::collections::HashMap;

/// Triangle or quadrilateral, linear (3, 4 nodes) or quadratic (6, 8 nodes: the corners, then
/// the mid-sides of sides 1–2, 2–3, 3–1 (3–4, 4–1), the faces of QTRSpace and QSpace).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaceKind {
    Tri,
    Quad,
    Tri6,
    Quad8,
}

impl FaceKind {
    /// The kind of a face with `nodes` nodes (3, 4, 6 or 8).
    pub fn of(nodes: usize) -> FaceKind {
        match nodes {
            3 => FaceKind::Tri,
            4 => FaceKind::Quad,
            6 => FaceKind::Tri6,
            _ => FaceKind::Quad8,
        }
    }

    /// The linear face on the same corners (its parameters are this face's).
    pub fn linear(self) -> FaceKind {
        match self {
            FaceKind::Tri | FaceKind::Tri6 => FaceKind::Tri,
            FaceKind::Quad | FaceKind::Quad8 => FaceKind::Quad,
        }
    }

    /// Number of corners (and of sides): 3 or 4.
    pub fn corners(self) -> usize {
        match self.linear() {
            FaceKind::Tri => 3,
            _ => 4,
        }
    }
}

/// One face of a master surface.
#[derive(Debug, Clone)]
pub struct Face {
    /// Index of the contact segment (model) the face belongs to.
    pub segment: usize,
    pub element: usize,
    /// Model node indices: the corners in cyclic order, then a quadratic face's mid-sides.
    pub nodes: Vec<usize>,
    pub kind: FaceKind,
    /// +1 when x_ξ × x_η points out of the element, else −1.
    pub side: f64,
    pub nlgeo: bool,
    /// Per face side (corners i, i+1): no other face of the surface shares it.
    pub open: Vec<bool>,
}

impl Face {
    /// The face parameters (ξ, η) of its node `a` (a model node index).
    fn param_of(&self, a: usize) -> (f64, f64) {
        let i = self
            .nodes
            .iter()
            .position(|&n| n == a)
            .expect("a node of the face");
        node_param(self.kind, i)
    }
}

/// The faces of one condition's surface segments, with their adjacency and reference normals.
#[derive(Debug, Clone, Default)]
pub struct FaceSurface {
    pub faces: Vec<Face>,
    /// Faces having a node as a corner or a mid-side.
    pub at_node: HashMap<usize, Vec<usize>>,
    ref_normals: HashMap<usize, [f64; 3]>,
}

type V3<T> = [T; 3];

/// a × b.
pub fn cross<T: Scalar>(a: &V3<T>, b: &V3<T>) -> V3<T> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// a·b.
pub fn dot<T: Scalar>(a: &V3<T>, b: &V3<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// a − b.
pub fn sub<T: Scalar>(a: &V3<T>, b: &V3<T>) -> V3<T> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn normalize<T: Scalar>(a: &V3<T>) -> V3<T> {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

/// Shape values of any face and their ξ and η derivatives at (ξ, η), zero past its nodes.
/// Quadratic triangle: L₀ = 1 − ξ − η, L₁ = ξ, L₂ = η, N_a = L_a(2L_a − 1) at the corners and
/// 4 L_a L_{a+1} at the mid-sides; quadratic quadrilateral: the serendipity functions.
pub fn shape_values<T: Scalar>(kind: FaceKind, xi: T, eta: T) -> ([T; 8], [T; 8], [T; 8]) {
    let z = xi.cst(0.0);
    let one = xi.cst(1.0);
    let (mut n, mut dx, mut de) = ([z; 8], [z; 8], [z; 8]);
    match kind {
        FaceKind::Tri | FaceKind::Quad => {
            let (a, b, c) = shape(kind, xi, eta);
            n[..4].copy_from_slice(&a);
            dx[..4].copy_from_slice(&b);
            de[..4].copy_from_slice(&c);
        }
        FaceKind::Tri6 => {
            let l = [one - xi - eta, xi, eta];
            let dl = [(-1.0, -1.0), (1.0, 0.0), (0.0, 1.0)];
            for a in 0..3 {
                let b = (a + 1) % 3;
                n[a] = l[a] * (l[a] * 2.0 - 1.0);
                let f = l[a] * 4.0 - 1.0;
                dx[a] = f * dl[a].0;
                de[a] = f * dl[a].1;
                n[3 + a] = l[a] * l[b] * 4.0;
                dx[3 + a] = (l[b] * dl[a].0 + l[a] * dl[b].0) * 4.0;
                de[3 + a] = (l[b] * dl[a].1 + l[a] * dl[b].1) * 4.0;
            }
        }
        FaceKind::Quad8 => {
            for a in 0..8 {
                let (px, pe) = node_param(kind, a);
                if a < 4 {
                    let (fx, fe) = (one + xi * px, one + eta * pe);
                    let s = xi * px + eta * pe - 1.0;
                    n[a] = fx * fe * s * 0.25;
                    dx[a] = fe * (s + fx) * (px * 0.25);
                    de[a] = fx * (s + fe) * (pe * 0.25);
                } else if px == 0.0 {
                    let fe = one + eta * pe;
                    n[a] = (one - xi * xi) * fe * 0.5;
                    dx[a] = -(xi * fe);
                    de[a] = (one - xi * xi) * (pe * 0.5);
                } else {
                    let fx = one + xi * px;
                    n[a] = fx * (one - eta * eta) * 0.5;
                    dx[a] = (one - eta * eta) * (px * 0.5);
                    de[a] = -(eta * fx);
                }
            }
        }
    }
    (n, dx, de)
}

/// Shape values and their ξ and η derivatives at (ξ, η) of a linear face (of a quadratic one's
/// corners: the linear face on them).
pub fn shape<T: Scalar>(kind: FaceKind, xi: T, eta: T) -> ([T; 4], [T; 4], [T; 4]) {
    let z = xi.cst(0.0);
    let one = xi.cst(1.0);
    match kind.linear() {
        FaceKind::Tri => (
            [one - xi - eta, xi, eta, z],
            [xi.cst(-1.0), one, z, z],
            [xi.cst(-1.0), z, one, z],
        ),
        FaceKind::Quad => {
            let (xm, xp, em, ep) = (one - xi, one + xi, one - eta, one + eta);
            (
                [
                    xm * em * 0.25,
                    xp * em * 0.25,
                    xp * ep * 0.25,
                    xm * ep * 0.25,
                ],
                [em * -0.25, em * 0.25, ep * 0.25, ep * -0.25],
                [xm * -0.25, xp * -0.25, xp * 0.25, xm * 0.25],
            )
        }
        _ => unreachable!("a linear kind"),
    }
}

/// Parametric centre of a face.
pub fn centre(kind: FaceKind) -> (f64, f64) {
    match kind.linear() {
        FaceKind::Tri => (1.0 / 3.0, 1.0 / 3.0),
        _ => (0.0, 0.0),
    }
}

/// Parameters of node `a` (a corner, or a quadratic face's mid-side).
pub fn node_param(kind: FaceKind, a: usize) -> (f64, f64) {
    let tri = [
        (0.0, 0.0),
        (1.0, 0.0),
        (0.0, 1.0),
        (0.5, 0.0),
        (0.5, 0.5),
        (0.0, 0.5),
    ];
    let quad = [
        (-1.0, -1.0),
        (1.0, -1.0),
        (1.0, 1.0),
        (-1.0, 1.0),
        (0.0, -1.0),
        (1.0, 0.0),
        (0.0, 1.0),
        (-1.0, 0.0),
    ];
    match kind.linear() {
        FaceKind::Tri => tri[a],
        _ => quad[a],
    }
}

/// How far (ξ, η) lies outside the face, in parameter units (≤ 0 inside).
pub fn outside(kind: FaceKind, xi: f64, eta: f64) -> f64 {
    match kind.linear() {
        FaceKind::Tri => (-xi).max(-eta).max(xi + eta - 1.0),
        _ => (xi.abs() - 1.0).max(eta.abs() - 1.0),
    }
}

/// How far (ξ, η) lies beyond each face side (corners a, a + 1), in parameter units (≤ 0
/// inside).
pub fn edge_excess(kind: FaceKind, xi: f64, eta: f64) -> [f64; 4] {
    match kind.linear() {
        FaceKind::Tri => [-eta, xi + eta - 1.0, -xi, f64::NEG_INFINITY],
        _ => [-eta - 1.0, xi - 1.0, eta - 1.0, -xi - 1.0],
    }
}

/// The nearest point of the face in parameters (the normal field is frozen past the face),
/// differentiable along the boundary.
fn clamp<T: Scalar>(kind: FaceKind, xi: T, eta: T) -> (T, T) {
    let lim = |v: T, lo: f64, hi: f64| {
        if v.val() < lo {
            v.cst(lo)
        } else if v.val() > hi {
            v.cst(hi)
        } else {
            v
        }
    };
    match kind.linear() {
        FaceKind::Quad => (lim(xi, -1.0, 1.0), lim(eta, -1.0, 1.0)),
        _ => {
            let (a, b) = (lim(xi, 0.0, f64::INFINITY), lim(eta, 0.0, f64::INFINITY));
            let s = a + b;
            if s.val() > 1.0 {
                (a / s, b / s)
            } else {
                (a, b)
            }
        }
    }
}

/// Unit outward normal of a face at (ξ, η), from node positions `x` in cyclic order.
pub fn face_normal<T: Scalar>(kind: FaceKind, x: &[V3<T>], side: f64, xi: T, eta: T) -> V3<T> {
    let (_, dx, de) = shape_values(kind, xi, eta);
    let k = x.len();
    let mut t1 = [xi.cst(0.0); 3];
    let mut t2 = [xi.cst(0.0); 3];
    for a in 0..k {
        for i in 0..3 {
            t1[i] = t1[i] + x[a][i] * dx[a];
            t2[i] = t2[i] + x[a][i] * de[a];
        }
    }
    let n = normalize(&cross(&t1, &t2));
    [n[0] * side, n[1] * side, n[2] * side]
}

/// Geometry of one face for the projection: node positions and nodal normals in cyclic order.
pub struct FaceGeometry<T> {
    pub kind: FaceKind,
    pub x: Vec<V3<T>>,
    pub n: Vec<V3<T>>,
}

impl<T: Scalar> FaceGeometry<T> {
    /// Point, tangents x_ξ, x_η, and the smoothed normal ñ (not normalized) at (ξ, η); the normal
    /// is taken at the nearest point of the face when (ξ, η) lies outside it.
    pub fn eval(&self, xi: T, eta: T) -> (V3<T>, V3<T>, V3<T>, V3<T>) {
        let k = self.x.len();
        let (nn, dx, de) = shape_values(self.kind, xi, eta);
        let (cx, ce) = clamp(self.kind, xi, eta);
        let nc = if outside(self.kind, xi.val(), eta.val()) > 0.0 {
            shape_values(self.kind, cx, ce).0
        } else {
            nn
        };
        let z = xi.cst(0.0);
        let (mut x, mut t1, mut t2, mut n) = ([z; 3], [z; 3], [z; 3], [z; 3]);
        for a in 0..k {
            for i in 0..3 {
                x[i] = x[i] + self.x[a][i] * nn[a];
                t1[i] = t1[i] + self.x[a][i] * dx[a];
                t2[i] = t2[i] + self.x[a][i] * de[a];
                n[i] = n[i] + self.n[a][i] * nc[a];
            }
        }
        (x, t1, t2, n)
    }

    /// r_α = (x_s − x)·x_α − ((x_s − x)·ñ)(ñ·x_α)/(ñ·ñ): zero at the contact point.
    pub fn residual(&self, xs: &V3<T>, xi: T, eta: T) -> [T; 2] {
        let (x, t1, t2, n) = self.eval(xi, eta);
        let d = [xs[0] - x[0], xs[1] - x[1], xs[2] - x[2]];
        let dn = dot(&d, &n) / dot(&n, &n);
        [
            dot(&d, &t1) - dn * dot(&n, &t1),
            dot(&d, &t2) - dn * dot(&n, &t2),
        ]
    }

    /// Gap g = (x_s − x)·n̂ and the unit normal at (ξ, η).
    pub fn gap(&self, xs: &V3<T>, xi: T, eta: T) -> (T, V3<T>) {
        let (x, _, _, n) = self.eval(xi, eta);
        let nh = normalize(&n);
        let d = [xs[0] - x[0], xs[1] - x[1], xs[2] - x[2]];
        (dot(&d, &nh), nh)
    }

    /// Shape values at (ξ, η) (extended past the face): x = Σ c_a x_a.
    pub fn coefficients(&self, xi: T, eta: T) -> [T; 8] {
        shape_values(self.kind, xi, eta).0
    }

    /// Unit outward normal of face side (corners a, a + 1) in the face's tangent plane at the
    /// side's middle, and the side's first corner (a curved side: the normal to its chord).
    pub fn edge_outward(&self, a: usize) -> (V3<T>, V3<T>) {
        let k = self.kind.corners();
        let (p, q) = (self.x[a], self.x[(a + 1) % k]);
        let t = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        // m = t × (x_ξ × x_η) points away from the face: the corners run counter-clockwise
        // about x_ξ × x_η in both parametrizations.
        let ((ca, ea), (cb, eb)) = (node_param(self.kind, a), node_param(self.kind, (a + 1) % k));
        let z = p[0].cst(0.0);
        let (_, t1, t2, _) = self.eval(z + 0.5 * (ca + cb), z + 0.5 * (ea + eb));
        (normalize(&cross(&t, &cross(&t1, &t2))), p)
    }

    /// Signed distance of `xs` past face edge (a, a + 1), in the face's tangent plane at the edge
    /// (> 0 outside the face).
    pub fn past_edge(&self, xs: &V3<T>, a: usize) -> T {
        let (m, p) = self.edge_outward(a);
        let d = [xs[0] - p[0], xs[1] - p[1], xs[2] - p[2]];
        dot(&d, &m)
    }
}

/// A dual over a face's two parameters (ξ, η).
type InParams = super::super::dual::DualN<2>;

impl FaceGeometry<f64> {
    /// The face and the point `xs` as constants of duals in (ξ, η), positions measured from the
    /// face's first corner (see [`Self::project`]).
    fn constant_in_xi_eta(&self, xs: [f64; 3]) -> (FaceGeometry<InParams>, V3<InParams>) {
        let origin = self.x[0];
        let constant = |p: &[f64; 3]| p.map(|v| InParams::constant(v, 2));
        let from = |p: &[f64; 3]| constant(&std::array::from_fn(|i| p[i] - origin[i]));
        let geom = FaceGeometry {
            kind: self.kind,
            x: self.x.iter().map(from).collect(),
            n: self.n.iter().map(constant).collect(),
        };
        (geom, from(&xs))
    }

    /// Contact point of `xs` by Newton on r(ξ, η) = 0 from the face centre, with the Jacobian
    /// from dual numbers in (ξ, η). None when it does not converge.
    ///
    /// Worked from the face's first corner: in absolute coordinates each evaluation of x(ξ, η)
    /// carries a round-off of ε times the coordinates' size, a step in ξ of that over the face's
    /// size, and a face 10⁶ of its sizes from the origin met no point (Newton never settled).
    pub fn project(&self, xs: [f64; 3]) -> Option<(f64, f64)> {
        type Dual = InParams;
        let (mut xi, mut eta) = centre(self.kind);
        let (geom, xs_d) = self.constant_in_xi_eta(xs);
        let (mut last, mut slope) = (f64::INFINITY, 0.0);
        for _ in 0..40 {
            let r = geom.residual(&xs_d, Dual::variable(xi, 0, 2), Dual::variable(eta, 1, 2));
            let (j00, j01, j10, j11) = (r[0].d[0], r[0].d[1], r[1].d[0], r[1].d[1]);
            let det = j00 * j11 - j01 * j10;
            if !(det.abs() > 1e-300) {
                return None;
            }
            slope = det.abs().sqrt();
            // Limit the step: a far node must not jump across the whole surface.
            let dxi = ((j11 * r[0].v - j01 * r[1].v) / det).clamp(-0.5, 0.5);
            let deta = ((-j10 * r[0].v + j00 * r[1].v) / det).clamp(-0.5, 0.5);
            xi -= dxi;
            eta -= deta;
            last = dxi.abs().max(deta.abs());
            if last < 4e-14 * (1.0 + xi.abs() + eta.abs()) {
                return Some((xi, eta));
            }
        }
        // Steps that stall at round-off have settled too: on a face edge, where the normal field
        // has a kink (it is frozen past the face) and Newton can bounce across the edge, or for
        // a node far over a small face, where r_α = d·x_α − … carries ε·|d|·|x_α| (d = x_s −
        // x(ξ, η)) and its slope is |x_α|² (√|det| of the Jacobian).
        let (x, _, _, _) = self.eval(xi, eta);
        let d: f64 = (0..3).map(|i| (xs[i] - x[i]).powi(2)).sum::<f64>().sqrt();
        let noise = 64.0 * f64::EPSILON * d / slope.sqrt();
        (last < 1e-10_f64.max(noise)).then_some((xi, eta))
    }

    /// ∂r/∂(ξ, η) at (ξ, η), plain numbers.
    pub fn jacobian(&self, xs: [f64; 3], xi: f64, eta: f64) -> [[f64; 2]; 2] {
        type Dual = InParams;
        let (geom, xs_d) = self.constant_in_xi_eta(xs);
        let r = geom.residual(&xs_d, Dual::variable(xi, 0, 2), Dual::variable(eta, 1, 2));
        [[r[0].d[0], r[0].d[1]], [r[1].d[0], r[1].d[1]]]
    }
}

impl<const N: usize> FaceGeometry<super::super::dual::DualN<N>> {
    /// The contact parameters as duals: one Newton step from the converged (ξ₀, η₀), with `jac`
    /// = ∂r/∂(ξ, η) there, makes their derivatives with respect to the unknowns exact.
    pub fn project_dual(
        &self,
        xs: &V3<super::super::dual::DualN<N>>,
        xi0: [f64; 2],
        jac: [[f64; 2]; 2],
    ) -> [super::super::dual::DualN<N>; 2] {
        let z = xs[0].cst(0.0);
        let (xi, eta) = (z + xi0[0], z + xi0[1]);
        let r = self.residual(xs, xi, eta);
        let [[a, b], [c, d]] = jac;
        let det = a * d - b * c;
        [
            xi - (r[0] * d - r[1] * b) * (1.0 / det),
            eta - (r[1] * a - r[0] * c) * (1.0 / det),
        ]
    }
}

/// A nodal normal with its derivatives: ∂n_i/∂x_{b,j} for each node b it depends on.
#[derive(Debug, Clone)]
pub struct NodalNormal {
    pub n: [f64; 3],
    pub jac: Vec<(usize, [[f64; 3]; 3])>,
    /// |Σ n_f| over the number of faces: 1 where the faces around agree, near 0 at the tip of
    /// a crease folded flat (where n turns with the round-off).
    pub agreement: f64,
}

impl FaceSurface {
    /// The surface of the face segments `segments` (model segment indices; others skipped).
    pub fn new(model: &Model, segments: &[usize]) -> FaceSurface {
        let mut surf = FaceSurface::default();
        let mut edge_count: HashMap<(usize, usize), usize> = HashMap::new();
        for &g in segments {
            let SegmentKind::Faces { faces } = &model.segments[g].kind else {
                continue;
            };
            for &(e, b) in faces {
                let el = &model.elements[e];
                let nodes = el.boundary_nodes(b);
                let kind = FaceKind::of(nodes.len());
                let k = surf.faces.len();
                for &a in &nodes {
                    surf.at_node.entry(a).or_default().push(k);
                }
                let nc = kind.corners();
                for i in 0..nc {
                    let (a, b) = (nodes[i], nodes[(i + 1) % nc]);
                    *edge_count.entry((a.min(b), a.max(b))).or_default() += 1;
                }
                surf.faces.push(Face {
                    segment: g,
                    element: e,
                    side: outward_side(model, e, &nodes, kind),
                    kind,
                    nlgeo: el.nlgeo,
                    open: Vec::new(),
                    nodes,
                });
            }
        }
        for f in &mut surf.faces {
            let k = f.kind.corners();
            f.open = (0..k)
                .map(|i| {
                    let (a, b) = (f.nodes[i], f.nodes[(i + 1) % k]);
                    edge_count[&(a.min(b), a.max(b))] == 1
                })
                .collect();
        }
        let reference = |n: usize| model.nodes[n].coords;
        let mut normals = HashMap::new();
        for (k, face) in surf.faces.iter().enumerate() {
            for &a in &face.nodes {
                normals.entry(a).or_insert_with(|| {
                    surf.nodal_normal(k, a, &|f, i| reference(surf.faces[f].nodes[i]))
                });
            }
        }
        surf.ref_normals = normals;
        surf
    }

    /// Reference nodal normal of a node of the surface.
    pub fn reference_normal(&self, a: usize) -> [f64; 3] {
        self.ref_normals[&a]
    }

    /// Nodal normal of node `a` (of face `k`): the normalized sum of the unit outward normals, at
    /// a, of the faces having it as a corner. `pos(f, i)` gives node i of face f.
    pub fn nodal_normal<T: Scalar>(
        &self,
        k: usize,
        a: usize,
        pos: &dyn Fn(usize, usize) -> V3<T>,
    ) -> V3<T> {
        let empty = Vec::new();
        let faces = self.at_node.get(&a).unwrap_or(&empty);
        let mut sum: Option<V3<T>> = None;
        for &f in faces.iter().chain(faces.is_empty().then_some(&k)) {
            let face = &self.faces[f];
            let x: Vec<V3<T>> = (0..face.nodes.len()).map(|i| pos(f, i)).collect();
            let (c, e) = face.param_of(a);
            let z = x[0][0].cst(0.0);
            let n = face_normal(face.kind, &x, face.side, z + c, z + e);
            sum = Some(match sum {
                None => n,
                Some(m) => [m[0] + n[0], m[1] + n[1], m[2] + n[2]],
            });
        }
        normalize(&sum.expect("a face has its corners"))
    }

    /// Current nodal normal of node `a` with its derivatives, from positions `pos(node)`: each
    /// face normal is differentiated in duals over its own nodes, the sum is normalized in
    /// closed form (dn = (I − n nᵀ) ds / |s|), so the cost does not grow with the valence.
    pub fn nodal_normal_jacobian(&self, a: usize, pos: &dyn Fn(usize) -> [f64; 3]) -> NodalNormal {
        // A face normal depends on at most 8 nodes.
        type Dual = super::super::dual::DualN<24>;
        let mut s = [0.0; 3];
        let mut ds: Vec<(usize, [[f64; 3]; 3])> = Vec::new();
        for &f in &self.at_node[&a] {
            let face = &self.faces[f];
            let k = face.nodes.len();
            let x: Vec<V3<Dual>> = face
                .nodes
                .iter()
                .enumerate()
                .map(|(b, &n)| {
                    let p = pos(n);
                    [0, 1, 2].map(|j| Dual::variable(p[j], 3 * b + j, 3 * k))
                })
                .collect();
            let (c, e) = face.param_of(a);
            let z = Dual::constant(0.0, 3 * k);
            let nf = face_normal(face.kind, &x, face.side, z + c, z + e);
            for (b, &node) in face.nodes.iter().enumerate() {
                let slot = match ds.iter().position(|(m, _)| *m == node) {
                    Some(p) => p,
                    None => {
                        ds.push((node, [[0.0; 3]; 3]));
                        ds.len() - 1
                    }
                };
                for (ii, comp) in nf.iter().enumerate() {
                    for j in 0..3 {
                        ds[slot].1[ii][j] += comp.d[3 * b + j];
                    }
                }
            }
            for ii in 0..3 {
                s[ii] += nf[ii].v;
            }
        }
        let len = dot(&s, &s).sqrt();
        let n = s.map(|v| v / len);
        let jac = ds
            .into_iter()
            .map(|(node, d)| {
                let mut j = [[0.0; 3]; 3];
                for (ii, row) in j.iter_mut().enumerate() {
                    for (jj, v) in row.iter_mut().enumerate() {
                        *v = (0..3)
                            .map(|k| ((ii == k) as u8 as f64 - n[ii] * n[k]) * d[k][jj])
                            .sum::<f64>()
                            / len;
                    }
                }
                (node, j)
            })
            .collect();
        let agreement = len / self.at_node[&a].len() as f64;
        NodalNormal { n, jac, agreement }
    }
}

/// Orientation factor of a face: +1 if x_ξ × x_η at its centre points away from the element's
/// centroid.
fn outward_side(model: &Model, e: usize, nodes: &[usize], kind: FaceKind) -> f64 {
    let el = &model.elements[e];
    let x: Vec<[f64; 3]> = nodes.iter().map(|&n| model.nodes[n].coords).collect();
    let (c, eta) = centre(kind);
    let n = face_normal(kind, &x, 1.0, c, eta);
    let k = el.nodes.len() as f64;
    let cen = el.nodes.iter().fold([0.0; 3], |acc, &m| {
        let p = model.nodes[m].coords;
        [acc[0] + p[0] / k, acc[1] + p[1] / k, acc[2] + p[2] / k]
    });
    let fc = x.iter().fold([0.0; 3], |acc, p| {
        let k = x.len() as f64;
        [acc[0] + p[0] / k, acc[1] + p[1] / k, acc[2] + p[2] / k]
    });
    let d = [cen[0] - fc[0], cen[1] - fc[1], cen[2] - fc[2]];
    if dot(&d, &n) > 0.0 {
        -1.0
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Nodes over a flat face far from it (up to 10⁸ of its size away, as a coarse body's node
    /// over a fine mesh) are projected: Newton's last steps there are the round-off of the
    /// residual (ε times the distance) over its slope (the face's size), above the bar of 1e-10
    /// from about 10⁶ sizes away, and settle no further; each such point is still found, to
    /// 1e-6. Triangles and skewed quadrilaterals of every orientation and size, anywhere on the
    /// face.
    #[test]
    fn nodes_far_over_a_face_are_projected_onto_it() {
        let mut rand = crate::testing::uniform(246813579);
        for k in 0..2000 {
            let kind = if k % 2 == 0 {
                FaceKind::Quad
            } else {
                FaceKind::Tri
            };
            let size = 10f64.powf(4.0 * rand() - 2.0);
            // An orthonormal frame (e1, e2, n) of a random direction.
            let n = normalize(&[2.0 * rand() - 1.0, 2.0 * rand() - 1.0, 2.0 * rand() - 1.0]);
            let a = if n[0].abs() < 0.9 {
                [1.0, 0.0, 0.0]
            } else {
                [0.0, 1.0, 0.0]
            };
            let e1 = normalize(&cross(&n, &a));
            let e2 = cross(&n, &e1);
            let o: V3<f64> = std::array::from_fn(|_| 10.0 * rand() - 5.0);
            let at = |u: f64, v: f64| -> V3<f64> {
                std::array::from_fn(|i| o[i] + size * (u * e1[i] + v * e2[i]))
            };
            let skew = 0.3 * rand();
            let x: Vec<V3<f64>> = match kind {
                FaceKind::Tri => vec![at(0.0, 0.0), at(1.0, 0.0), at(skew, 1.0)],
                _ => vec![
                    at(0.0, 0.0),
                    at(1.0, 0.0),
                    at(1.0 + skew, 1.0),
                    at(skew, 0.8),
                ],
            };
            let side = if dot(&cross(&sub(&x[1], &x[0]), &sub(&x[2], &x[0])), &n) > 0.0 {
                1.0
            } else {
                -1.0
            };
            let geom = FaceGeometry {
                kind,
                n: vec![n.map(|v| v * side); x.len()],
                x,
            };
            let (xi, eta) = match kind {
                FaceKind::Tri => (0.1 + 0.3 * rand(), 0.1 + 0.3 * rand()),
                _ => (1.6 * rand() - 0.8, 1.6 * rand() - 0.8),
            };
            let (p, _, _, _) = geom.eval(xi, eta);
            let gap = size * 10f64.powf(9.0 * rand() - 1.0);
            let xs: V3<f64> = std::array::from_fn(|i| p[i] + gap * side * n[i]);
            let (u, v) = geom
                .project(xs)
                .unwrap_or_else(|| panic!("refused: {kind:?}, size {size:e}, gap {gap:e}"));
            assert!(
                (u - xi).abs() < 1e-6 && (v - eta).abs() < 1e-6,
                "({u}, {v}) for ({xi}, {eta}), gap {gap:e}"
            );
        }
    }
}
