//! Node-to-segment contact (spec §2.5, §2.6): each node of the condition meets one partner among
//! its segments — an edge of the master surface they form (see [`super::geometry::edges`]) or a
//! rigid shape — chosen by [`super::search`].
//!
//! Kinematics against an edge: the contact point s solves (x_s − x(s)) × ñ(s) = 0 on the current
//! edge, ñ the smoothed normal (current in large deformation, reference in small deformation);
//! g = (x_s − x(s))·n̂(s); the force acts along n̂ (or the prescribed `normal`) on the node and
//! along −c_a(s) n̂ on the edge nodes, x(s) = Σ c_a x_a. All of it is differentiated, including
//! s(q), so Newton converges quadratically while nodes slide. In small deformation the force
//! direction is the reference normal: the geometrically linear contact of OOFEM (its N2S_LM test
//! values come out exactly), now with the contact point following the node.
//!
//! Ends of an open master: past an end the surface continues along its end tangent and the force
//! is weighted by w ∈ [0, 1], the share of the node's tributary length that still faces the
//! master (a smoothstep of (a − d)/(a + b), with d the distance past the end and a, b the node's
//! tributary extents behind and ahead). A node on the end with its surface behind it keeps its
//! full force, a node whose whole tributary length is past the end has none, and nothing jumps
//! in between. The multiplier law enforces g = 0 wherever w > 0 (the infinite-penalty limit).

use super::dual::{self, DVec, Dual};
use super::geometry::edges::{edge_normal, EdgeGeometry, EdgeSurface};
use super::geometry::rigid;
use super::geometry::scalar::Scalar;
use super::law::PointKinematics;
use super::search::{self, Candidate};
use super::{apply_law, ContactPoint, Ctx, Formulation, Local, Partner, Search, SlotState};
use crate::error::{Error, Result};
use crate::model::{ContactLaw, Model, Pairing, SegmentKind};
use std::collections::HashMap;

/// A projection within this distance (in s) of an edge's ends counts as inside it.
const INSIDE_TOL: f64 = 1e-9;
/// Beyond an interior end of its edge, a previous edge partner is kept within this band (in s):
/// enough that round-off does not make a node on a vertex alternate between the two edges, small
/// enough that the extrapolated edge never changes an answer (past a vertex, the neighbouring
/// edge is the surface).
const HYSTERESIS_BAND: f64 = 1e-6;
/// Ramp length at an open end for a node without neighbours, as a fraction of the end edge.
const ISOLATED_RAMP: f64 = 0.01;

struct Slot {
    node: usize,
    area: f64,
    /// Reference positions of the node's neighbours on its own surface.
    neighbors: Vec<[f64; 3]>,
    /// Half the distance to the farthest neighbour: how far past an open end the node can
    /// still meet the master.
    reach: f64,
}

pub struct NodeToSegment {
    number: usize,
    law: ContactLaw,
    /// Prescribed force direction (`normal`), instead of the segment normal.
    normal: Option<[f64; 3]>,
    slots: Vec<Slot>,
    surface: EdgeSurface,
    /// Rigid segments of the condition (model segment indices).
    rigid: Vec<usize>,
    /// Reference nodes the rigid segments move with.
    rigid_nodes: Vec<usize>,
    dim: usize,
    /// Gap difference (a length) within which a previous partner counts as tied.
    tie: f64,
}

/// C¹ step from 0 (τ ≤ 0) to 1 (τ ≥ 1).
fn smoothstep<T: Scalar>(tau: T) -> T {
    if tau.val() >= 1.0 {
        tau.cst(1.0)
    } else if tau.val() <= 0.0 {
        tau.cst(0.0)
    } else {
        tau * tau * (tau * -2.0 + 3.0)
    }
}

impl NodeToSegment {
    pub fn new(model: &Model, ci: usize) -> Result<NodeToSegment> {
        let c = &model.contacts[ci];
        let Pairing::NodeToSegment { nodes, segments } = &c.pairing else {
            unreachable!("a node-to-segment condition")
        };
        let err = |msg: String| Error::Input {
            span: c.span.clone(),
            msg,
        };
        let surface = EdgeSurface::new(model, segments);
        let mut seen = std::collections::HashSet::new();
        for &n in nodes {
            let label = model.nodes[n].label;
            if !seen.insert(n) {
                return Err(err(format!("node {label} is listed twice in `nodeset`")));
            }
            if let Some(e) = surface.edges.iter().find(|e| e.nodes.contains(&n)) {
                return Err(err(format!(
                    "node {label} of `nodeset` belongs to an edge of contact segment {} (element {}): \
                     a node cannot be in contact with its own surface",
                    model.segments[e.segment].number, model.elements[e.element].label
                )));
            }
        }
        // The unknowns of a pair: the node and the edge's support (with the edges meeting it at
        // its ends in large deformation, whose normals are averaged).
        for (k, e) in surface.edges.iter().enumerate() {
            let m = 2 * (1 + surface.support(k).len());
            if m > super::dual::MAXV {
                return Err(Error::Input {
                    span: model.segments[e.segment].span.clone(),
                    msg: format!(
                        "the edge of element {} meets too many other edges of the contact surface \
                         at its ends ({m} unknowns for one contact pair, at most {})",
                        model.elements[e.element].label,
                        super::dual::MAXV
                    ),
                });
            }
        }
        let tribs = super::tributary::tributaries(model, nodes);
        let slots = nodes
            .iter()
            .zip(tribs)
            .map(|(&node, t)| {
                let x = model.nodes[node].coords;
                let neighbors: Vec<[f64; 3]> =
                    t.neighbors.iter().map(|&m| model.nodes[m].coords).collect();
                let reach = neighbors
                    .iter()
                    .map(|y| 0.5 * ((y[0] - x[0]).powi(2) + (y[1] - x[1]).powi(2)).sqrt())
                    .fold(0.0, f64::max);
                Slot {
                    node,
                    area: t.measure,
                    neighbors,
                    reach,
                }
            })
            .collect();
        let rigid: Vec<usize> = segments
            .iter()
            .copied()
            .filter(|&g| !matches!(model.segments[g].kind, SegmentKind::Edges { .. }))
            .collect();
        let rigid_nodes = rigid
            .iter()
            .filter_map(|&g| match &model.segments[g].kind {
                SegmentKind::Circle { node, .. } | SegmentKind::Plane { node, .. } => *node,
                _ => None,
            })
            .collect();
        Ok(NodeToSegment {
            number: c.number,
            law: c.law,
            normal: c.normal,
            slots,
            surface,
            rigid,
            rigid_nodes,
            dim: model.domain.nsd(),
            tie: 1e-9 * super::model_size(model),
        })
    }

    /// Nodal normals of edge `k` in the mode of its element, from positions `pos(e, i)` of node i
    /// of edge e (current ones matter only in large deformation).
    fn normals<T: Scalar>(
        &self,
        k: usize,
        x: &[[T; 2]],
        pos: &dyn Fn(usize, usize) -> [T; 2],
    ) -> Vec<[T; 2]> {
        let edge = &self.surface.edges[k];
        let z = x[0][0];
        if let Some(n) = self.normal {
            return vec![[z.cst(n[0]), z.cst(n[1])]; x.len()];
        }
        edge.nodes
            .iter()
            .enumerate()
            .map(|(i, &a)| {
                if !edge.nlgeo {
                    let n = self.surface.reference_normal(a);
                    [z.cst(n[0]), z.cst(n[1])]
                } else if i == 2 {
                    edge_normal(x, edge.side, z.cst(0.5))
                } else {
                    self.surface.nodal_normal(k, a, pos)
                }
            })
            .collect()
    }

    fn geometry_f64(&self, k: usize, cur: &HashMap<usize, [f64; 2]>) -> EdgeGeometry<f64> {
        let edge = &self.surface.edges[k];
        let x: Vec<[f64; 2]> = edge.nodes.iter().map(|n| cur[n]).collect();
        let pos = |e: usize, i: usize| cur[&self.surface.edges[e].nodes[i]];
        EdgeGeometry {
            n: self.normals(k, &x, &pos),
            x,
            open: [
                self.surface.is_open_end(edge.nodes[0]),
                self.surface.is_open_end(edge.nodes[1]),
            ],
        }
    }

    /// Tributary extents (behind, ahead) of a slot's node along the outward direction of end `e`
    /// of edge `k`, from the reference configuration.
    fn ramp(&self, model: &Model, slot: &Slot, k: usize, e: usize) -> (f64, f64) {
        let edge = &self.surface.edges[k];
        let x: Vec<[f64; 2]> = edge
            .nodes
            .iter()
            .map(|&n| {
                let c = model.nodes[n].coords;
                [c[0], c[1]]
            })
            .collect();
        let geom = EdgeGeometry {
            n: x.clone(),
            x,
            open: [false; 2],
        };
        let (out, _) = geom.end_direction(e);
        let xs = model.nodes[slot.node].coords;
        let (mut a, mut b) = (0.0f64, 0.0f64);
        for nb in &slot.neighbors {
            let d = (nb[0] - xs[0]) * out[0] + (nb[1] - xs[1]) * out[1];
            a = a.max(-0.5 * d);
            b = b.max(0.5 * d);
        }
        if a + b > 0.0 {
            (a, b)
        } else {
            let (x0, x1) = (geom.x[0], geom.x[1]);
            (
                ISOLATED_RAMP * ((x1[0] - x0[0]).powi(2) + (x1[1] - x0[1]).powi(2)).sqrt(),
                0.0,
            )
        }
    }

    /// End weight of a node at `xs` against edge `k`: 1 unless the edge has an open end it nears.
    fn weight<T: Scalar>(
        &self,
        model: &Model,
        slot: &Slot,
        k: usize,
        geom: &EdgeGeometry<T>,
        xs: [T; 2],
    ) -> T {
        let mut w = xs[0].cst(1.0);
        for e in 0..2 {
            if !geom.open[e] {
                continue;
            }
            let (out, xe) = geom.end_direction(e);
            let d = (xs[0] - xe[0]) * out[0] + (xs[1] - xe[1]) * out[1];
            let (a, b) = self.ramp(model, slot, k, e);
            w = w * smoothstep((-d + a) * (1.0 / (a + b)));
        }
        w
    }

    /// Current positions of the surface nodes (2D).
    fn current(&self, ctx: &Ctx) -> Result<HashMap<usize, [f64; 2]>> {
        let mut cur = HashMap::new();
        for e in &self.surface.edges {
            for &n in &e.nodes {
                if let std::collections::hash_map::Entry::Vacant(v) = cur.entry(n) {
                    let (x, _) = ctx.position(n)?;
                    v.insert([x[0], x[1]]);
                }
            }
        }
        Ok(cur)
    }

    /// Origin of a rigid segment: its reference point moved with its node, if any.
    fn rigid_origin<T: Scalar>(
        &self,
        model: &Model,
        p: [f64; 3],
        node: Option<usize>,
        x_node: Option<&[T]>,
        like: T,
    ) -> Vec<T> {
        (0..self.dim)
            .map(|i| match (node, x_node) {
                (Some(n), Some(x)) => x[i] + (p[i] - model.nodes[n].coords[i]),
                _ => like.cst(p[i]),
            })
            .collect()
    }

    /// Every possible partner of a node at `xs`, with the previous partner's band included.
    fn candidates(
        &self,
        ctx: &Ctx,
        slot: &Slot,
        xs: [f64; 3],
        cur: &HashMap<usize, [f64; 2]>,
        previous: Option<Partner>,
    ) -> Result<Vec<Candidate>> {
        let model = ctx.model;
        let mut out = Vec::new();
        let xs2 = [xs[0], xs[1]];
        let mut best = f64::INFINITY;
        for k in 0..self.surface.edges.len() {
            let edge = &self.surface.edges[k];
            // Cheap rejection: the box of the edge's nodes, grown by the edge's length (curvature)
            // and the node's reach past an open end, farther than the best gap so far.
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for n in &edge.nodes {
                let p = cur[n];
                for i in 0..2 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
            let size = ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2)).sqrt();
            let outside = (0..2)
                .map(|i| (lo[i] - xs2[i]).max(xs2[i] - hi[i]).max(0.0).powi(2))
                .sum::<f64>()
                .sqrt();
            if outside > best + size + slot.reach && previous != Some(Partner::Edge(k)) {
                continue;
            }
            let geom = self.geometry_f64(k, cur);
            let Some(s) = geom.project(xs2) else { continue };
            let past_open = (s < 0.0 && geom.open[0]) || (s > 1.0 && geom.open[1]);
            let inside = if past_open {
                self.weight(model, slot, k, &geom, xs2) > 0.0
            } else {
                (-INSIDE_TOL..=1.0 + INSIDE_TOL).contains(&s)
            };
            if !inside && !(-HYSTERESIS_BAND..=1.0 + HYSTERESIS_BAND).contains(&s) {
                continue;
            }
            if past_open && !inside {
                continue;
            }
            let (g, _) = geom.gap(xs2, s);
            if inside {
                best = best.min(g.abs());
            }
            out.push(Candidate {
                partner: Partner::Edge(k),
                xi: s,
                gap: g,
                inside,
            });
        }
        for &seg in &self.rigid {
            let xv = &xs[..self.dim];
            let (gap, xi) = match &model.segments[seg].kind {
                SegmentKind::Circle {
                    center,
                    radius,
                    node,
                    cavity,
                } => {
                    let xn = node.map(|n| ctx.position(n)).transpose()?.map(|p| p.0);
                    let c =
                        self.rigid_origin(model, *center, *node, xn.as_ref().map(|x| &x[..]), 0.0);
                    let r: f64 = xv
                        .iter()
                        .zip(&c)
                        .map(|(a, b)| (a - b).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    if !(r > 0.0) {
                        continue;
                    }
                    (rigid::circle(xv, &c, *radius, *cavity).0, 0.0)
                }
                SegmentKind::Plane {
                    point,
                    normal,
                    node,
                } => {
                    let xn = node.map(|n| ctx.position(n)).transpose()?.map(|p| p.0);
                    let p =
                        self.rigid_origin(model, *point, *node, xn.as_ref().map(|x| &x[..]), 0.0);
                    (rigid::plane(xv, &p, &normal[..self.dim]).0, 0.0)
                }
                SegmentKind::Polynomial { coeffs, body_above } => {
                    let Some(t) = rigid::project_on_poly(coeffs, xs2) else {
                        continue;
                    };
                    (rigid::polynomial(coeffs, xv, t, *body_above).0, t)
                }
                SegmentKind::Edges { .. } => unreachable!("rigid segments only"),
            };
            out.push(Candidate {
                partner: Partner::Rigid(seg),
                xi,
                gap,
                inside: true,
            });
        }
        Ok(out)
    }

    /// Kinematics against edge `k` with the contact point converged at `s0`.
    fn edge_kinematics(
        &self,
        ctx: &Ctx,
        slot: &Slot,
        k: usize,
        s0: f64,
    ) -> Result<(Local, PointKinematics)> {
        let edge = &self.surface.edges[k];
        let mut local = Local::new(2);
        local.add(ctx, slot.node)?;
        for n in self.surface.support(k) {
            local.add(ctx, n)?;
        }
        let q = local.seed();
        let xy = |n: usize| {
            let v = q[local.index(n)];
            [v[0], v[1]]
        };
        let x: Vec<[Dual; 2]> = edge.nodes.iter().map(|&n| xy(n)).collect();
        let pos = |e: usize, i: usize| xy(self.surface.edges[e].nodes[i]);
        let geom = EdgeGeometry {
            n: self.normals(k, &x, &pos),
            x,
            open: [
                self.surface.is_open_end(edge.nodes[0]),
                self.surface.is_open_end(edge.nodes[1]),
            ],
        };
        let xs = [q[0][0], q[0][1]];
        let s = geom.project_dual(xs, s0);
        let (gap, nh) = geom.gap(xs, s);
        let m = local.m();
        let dir: DVec = match self.normal {
            Some(n) => dual::constant_vec(&n[..2], m),
            None => [nh[0], nh[1], Dual::constant(0.0, m)],
        };
        let (c, _, _) = geom.coefficients(s);
        let mut coeffs = vec![(0, Dual::constant(1.0, m))];
        for (a, &n) in edge.nodes.iter().enumerate() {
            coeffs.push((local.index(n), -c[a]));
        }
        let b = local.distribute(&coeffs, &dir);
        let weight = self.weight(ctx.model, slot, k, &geom, xs);
        Ok((
            local,
            PointKinematics {
                gap,
                weight,
                b,
                area: super::law_area(slot.area, ctx.model),
            },
        ))
    }

    /// Kinematics against rigid segment `seg`, with the polynomial's contact abscissa `t0`.
    fn rigid_kinematics(
        &self,
        ctx: &Ctx,
        slot: &Slot,
        seg: usize,
        t0: f64,
    ) -> Result<(Local, PointKinematics)> {
        let model = ctx.model;
        let dim = self.dim;
        let mut local = Local::new(dim);
        local.add(ctx, slot.node)?;
        let node = match &model.segments[seg].kind {
            SegmentKind::Circle { node, .. } | SegmentKind::Plane { node, .. } => *node,
            _ => None,
        };
        if let Some(n) = node {
            local.add(ctx, n)?;
        }
        let q = local.seed();
        let m = local.m();
        let xs = &q[0][..dim];
        let zero = Dual::constant(0.0, m);
        let xn = node.map(|_| &q[1][..dim]);
        let (gap, n) = match &model.segments[seg].kind {
            SegmentKind::Circle {
                center,
                radius,
                cavity,
                ..
            } => {
                let c = self.rigid_origin(model, *center, node, xn, zero);
                rigid::circle(xs, &c, *radius, *cavity)
            }
            SegmentKind::Plane { point, normal, .. } => {
                let p = self.rigid_origin(model, *point, node, xn, zero);
                rigid::plane(xs, &p, &normal[..dim])
            }
            SegmentKind::Polynomial { coeffs, body_above } => {
                rigid::polynomial(coeffs, xs, t0, *body_above)
            }
            SegmentKind::Edges { .. } => unreachable!("rigid segments only"),
        };
        let dir: DVec = match self.normal {
            Some(nf) => dual::constant_vec(&nf[..dim], m),
            None => {
                let mut v = [zero; 3];
                v[..dim].copy_from_slice(&n);
                v
            }
        };
        let mut coeffs = vec![(0, Dual::constant(1.0, m))];
        if node.is_some() {
            coeffs.push((1, Dual::constant(-1.0, m)));
        }
        let b = local.distribute(&coeffs, &dir);
        Ok((
            local,
            PointKinematics {
                gap,
                weight: Dual::constant(1.0, m),
                b,
                area: super::law_area(slot.area, model),
            },
        ))
    }
}

impl Formulation for NodeToSegment {
    fn n_slots(&self) -> usize {
        self.slots.len()
    }

    fn n_multipliers(&self) -> usize {
        if self.law == ContactLaw::Multiplier {
            self.slots.len()
        } else {
            0
        }
    }

    fn nodes_needing_dofs(&self) -> Vec<usize> {
        let mut out: Vec<usize> = self.slots.iter().map(|s| s.node).collect();
        out.extend(&self.rigid_nodes);
        out
    }

    fn candidate_nodes(&self) -> Vec<usize> {
        let mut out = self.nodes_needing_dofs();
        for e in &self.surface.edges {
            out.extend(&e.nodes);
        }
        // Nodal normals in large deformation reach the neighbouring edges' nodes: all are edges
        // of the surface, already listed.
        out
    }

    fn symmetric(&self) -> bool {
        // B = ∇g only for the exact closest point on a rigid shape along its own normal.
        self.surface.edges.is_empty() && self.normal.is_none()
    }

    fn evaluate(
        &self,
        ctx: &Ctx,
        first_lambda: usize,
        search: Search,
        points: &mut Vec<ContactPoint>,
        states: &mut Vec<SlotState>,
    ) -> Result<()> {
        let cur = self.current(ctx)?;
        for (k, slot) in self.slots.iter().enumerate() {
            let (xs, _) = ctx.position(slot.node)?;
            let previous = search.previous(k);
            let chosen = match previous {
                Some((p, xi, true)) => (p != Partner::None).then_some(Candidate {
                    partner: p,
                    xi,
                    gap: 0.0,
                    inside: true,
                }),
                _ => {
                    let prev = previous.map(|p| p.0);
                    let cands = self.candidates(ctx, slot, xs, &cur, prev)?;
                    search::choose(&cands, prev, self.tie)
                }
            };
            // With the partner frozen, the contact point is still recomputed (it moves with q).
            let chosen = match (chosen, previous) {
                (Some(c), Some((_, _, true))) => match c.partner {
                    Partner::Edge(e) => self
                        .geometry_f64(e, &cur)
                        .project([xs[0], xs[1]])
                        .map(|s| Candidate { xi: s, ..c }),
                    Partner::Rigid(seg) => match &ctx.model.segments[seg].kind {
                        SegmentKind::Polynomial { coeffs, .. } => {
                            rigid::project_on_poly(coeffs, [xs[0], xs[1]])
                                .map(|t| Candidate { xi: t, ..c })
                        }
                        _ => Some(c),
                    },
                    _ => Some(c),
                },
                (c, _) => c,
            };
            let lambda_eq = (self.law == ContactLaw::Multiplier).then_some(first_lambda + k);
            let mut state = SlotState {
                condition: self.number,
                node: slot.node,
                partner: Partner::None,
                xi: f64::NAN,
                gap: f64::NAN,
                force: 0.0,
                pressure: 0.0,
                active: false,
                x: xs,
            };
            let (local, kin) = match chosen {
                Some(c) => {
                    state.partner = c.partner;
                    state.xi = c.xi;
                    match c.partner {
                        Partner::Edge(e) => self.edge_kinematics(ctx, slot, e, c.xi)?,
                        Partner::Rigid(seg) => self.rigid_kinematics(ctx, slot, seg, c.xi)?,
                        _ => unreachable!("node-to-segment partners are edges or rigid segments"),
                    }
                }
                None => {
                    // No partner: no force; a multiplier is held at zero.
                    let mut local = Local::new(self.dim);
                    local.add(ctx, slot.node)?;
                    let m = local.m();
                    let kin = PointKinematics {
                        gap: Dual::constant(f64::NAN, m),
                        weight: Dual::constant(0.0, m),
                        b: vec![Dual::constant(0.0, m); m],
                        area: 0.0,
                    };
                    (local, kin)
                }
            };
            if chosen.is_some() {
                state.gap = kin.gap.v;
            }
            points.push(apply_law(
                ctx, self.law, lambda_eq, &local, &kin, slot.area, &mut state,
            ));
            states.push(state);
        }
        Ok(())
    }
}
