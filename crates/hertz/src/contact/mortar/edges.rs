//! Mortar contact in 2D: straight or quadratic slave edges against master edges or rigid shapes.
//!
//! Glossary (one slave node j; see [`super`] for the weighted gap and force direction):
//! * ξ ∈ [0, 1] along a slave edge x(ξ) = Σ N_k(ξ) x_k, N_j(ξ) the node's shape function, ν(ξ)
//!   the unit normal pointing into the slave body (towards it from the master side);
//! * segmentation: a master edge y(η) overlaps the slave edge on [ξ_lo, ξ_hi], the slave
//!   parameters of its ends' closest points (clipped to [0, 1]); a Gauss point ξ meets the
//!   master where the line x(ξ) + t ν(ξ) crosses it, at η(ξ) (both by Newton, then one Newton
//!   step in duals for the exact derivative);
//! * gap g(ξ) = (x(ξ) − y(η(ξ)))·ν (< 0: penetration), against a rigid shape its signed distance;
//! * Φ_j: the dual basis biorthogonal over the overlapped part of the slave edge (the union of
//!   the segments), so that ḡ_j is exact for a linear gap field also on an edge that reaches
//!   past the master's end.
//!
//! In small deformation the segmentation, the normals and the weights are those of the reference
//! configuration and only the gap follows the displacements (linear contact), the gap and the
//! force along the blend of the slave's and the master's normals at the pair of points
//! ([`interface_weights`]) rather than along ν alone; in large
//! deformation all of it is evaluated at the current state and differentiated.
//!
//! Self-contact (the slave segment among the master segments, straight edges): each own edge
//! meets the parts of the surface that face it squarely ([`own`]); where two
//! walls are within an edge length the rays bisect their normals (`symmetric_ray`), so that
//! each wall as a slave is the mirror image of the other; pairs of nodes that meet each other's
//! walls at one place hold one constraint (`contact::repeated`).

use super::{
    nearest_sheet, own, rigid_node, search_limit, Facing, MortarLaw, SlipForm, Weighted, GRAZING,
};
use crate::contact::dual::{self, Dual, Jet};
use crate::contact::formulation::{
    interface_weights, Ctx, Formulation, Local, Partner, Search, SlotState,
};
use crate::contact::geometry::edges::{shape, EdgeSurface};
use crate::contact::geometry::rigid;
use crate::contact::geometry::scalar::Scalar;
use crate::contact::search::broad::BroadPhase;
use crate::contact::slot::SlotLinearization;
use crate::error::{Error, Result};
use crate::model::{Model, Pairing, SegmentKind};

/// Gauss points on [−1, 1] (3 points: the integrands of straight pairs are quadratic).
const GAUSS: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

pub struct Mortar {
    law: MortarLaw,
    slave: EdgeSurface,
    master: EdgeSurface,
    /// Rigid segments of the master side (model segment indices).
    rigid: Vec<usize>,
    /// Slave nodes (the slots), and for each the slave edges it belongs to.
    slots: Vec<(usize, Vec<usize>)>,
    /// Large deformation: the geometry follows the current state.
    nlgeo: bool,
    /// Nodes the rigid segments move with.
    rigid_nodes: Vec<usize>,
    /// How far the search for master edges goes.
    search_limit: f64,
    /// Per slave edge, the coefficients of its dual basis (reference configuration), for rigid
    /// shapes, which face the whole edge; against master edges the basis is adapted to the
    /// overlap ([`dual_basis_over`]).
    dual: Vec<[[f64; 4]; 4]>,
    /// Axisymmetric slave elements: every integral per radian, its arc length weighted by r.
    axisymmetric: bool,
    /// Per slave edge, its element's thickness (plane stress and strain; 1 in axisymmetry):
    /// every integral is over the edge's area, so that λ is a pressure and a penalty per unit
    /// area acts as it does in 3D, whatever the section's thickness.
    thick: Vec<f64>,
    /// Self-contact (the slave segment is among the master segments): per master edge, the
    /// slave edge it is, if it is one of the slave's own.
    own: Vec<Option<usize>>,
}

impl Mortar {
    pub fn new(model: &Model, ci: usize) -> Result<Mortar> {
        let c = &model.contacts[ci];
        let Pairing::Mortar { slave, segments } = &c.pairing else {
            unreachable!("a mortar condition")
        };
        let err = |msg: String| Error::Input {
            span: c.span.clone(),
            msg,
        };
        let self_contact = segments.contains(slave);
        let slave = EdgeSurface::new(model, &[*slave]);
        let master = EdgeSurface::new(model, segments);
        if slave.edges.is_empty() {
            return Err(err("the slave segment has no element edges".into()));
        }
        let rigid: Vec<usize> = segments
            .iter()
            .copied()
            .filter(|&g| !matches!(model.segments[g].kind, SegmentKind::Edges { .. }))
            .collect();
        if rigid
            .iter()
            .any(|&g| matches!(model.segments[g].kind, SegmentKind::Faces { .. }))
        {
            return Err(err("mortar contact is 2D: no faces".into()));
        }
        // Self-contact: the slave's own edges are master edges too.
        let own: Vec<Option<usize>> = (master.edges.iter())
            .map(|m| {
                (slave.edges.iter())
                    .position(|e| e.element == m.element && e.nodes == m.nodes)
                    .filter(|_| self_contact)
            })
            .collect();
        if self_contact && slave.edges.iter().any(|e| e.nodes.len() > 2) {
            return Err(err(
                "mortar self-contact takes straight (2-node) edges: a node-to-segment \
                 condition (`n2s...`) whose `slaveset` holds the segment's nodes is \
                 self-contact on quadratic ones"
                    .into(),
            ));
        }
        let shared = slave
            .edges
            .iter()
            .flat_map(|e| &e.nodes)
            .any(|n| master.edges.iter().any(|m| m.nodes.contains(n)));
        if shared && !self_contact {
            return Err(err(
                "the slave and master segments share nodes: a surface cannot contact itself".into(),
            ));
        }
        let mut slots: Vec<(usize, Vec<usize>)> = Vec::new();
        for (k, e) in slave.edges.iter().enumerate() {
            for &n in &e.nodes {
                match slots.iter_mut().find(|(m, _)| *m == n) {
                    Some(s) => s.1.push(k),
                    None => slots.push((n, vec![k])),
                }
            }
        }
        // Without a penalty, h is the mean length of the node's slave edges.
        let nodes: Vec<usize> = slots.iter().map(|s| s.0).collect();
        let length = |k: usize| {
            let (a, b) = (slave.edges[k].nodes[0], slave.edges[k].nodes[1]);
            let (x, y) = (model.nodes[a].coords, model.nodes[b].coords);
            (0..3).map(|i| (y[i] - x[i]).powi(2)).sum::<f64>().sqrt()
        };
        // ∫ N_j over a straight edge: L/2 at a 2-node edge's ends, L/6 and 2L/3 on a 3-node one
        // (∫ N_j r ds in axisymmetry).
        let axisymmetric = slave
            .edges
            .iter()
            .any(|e| model.elements[e.element].etype.is_axisymmetric());
        let thick: Vec<f64> = (slave.edges.iter())
            .map(|e| match axisymmetric {
                true => 1.0,
                false => crate::solid::loads::element_thickness(model, e.element),
            })
            .collect();
        let full_support = slots
            .iter()
            .map(|(n, edges)| {
                edges
                    .iter()
                    .map(|&k| {
                        let e = &slave.edges[k];
                        let share = match (e.nodes.len(), e.nodes.iter().position(|m| m == n)) {
                            (2, _) => 0.5,
                            (_, Some(2)) => 2.0 / 3.0,
                            _ => 1.0 / 6.0,
                        };
                        match axisymmetric {
                            true => {
                                let x: Vec<[f64; 3]> =
                                    e.nodes.iter().map(|&m| model.nodes[m].coords).collect();
                                let j = e.nodes.iter().position(|m| m == n).expect("its node");
                                crate::contact::tributary::axisymmetric_shares(&x)[j]
                            }
                            false => share * length(k) * thick[k],
                        }
                    })
                    .sum()
            })
            .collect();
        let law = MortarLaw::new(
            model,
            ci,
            &nodes,
            |j| {
                let edges = &slots[j].1;
                edges.iter().map(|&k| length(k)).sum::<f64>() / edges.len() as f64
            },
            full_support,
        );
        let nlgeo = slave.edges.iter().any(|e| e.nlgeo);
        let nodes = slave
            .edges
            .iter()
            .chain(&master.edges)
            .flat_map(|e| e.nodes.iter().copied());
        let search_limit = search_limit(model, nodes);
        let dual = slave
            .edges
            .iter()
            .map(|e| {
                let x: Vec<[f64; 3]> = e.nodes.iter().map(|&n| model.nodes[n].coords).collect();
                edge_dual_basis(&x, axisymmetric)
            })
            .collect();
        Ok(Mortar {
            own,
            dual,
            axisymmetric,
            thick,
            search_limit,
            law,
            rigid_nodes: rigid.iter().filter_map(|&g| rigid_node(model, g)).collect(),
            nlgeo,
            slave,
            master,
            rigid,
            slots,
        })
    }

    /// Self-contact: the outward normal of the own surface at node `node`, the mean of its edges'
    /// (positions `x`); where they cancel (the tip of a crease folded flat) the normal of edge
    /// `k` of the slave surface.
    fn nodal_normal(&self, node: usize, k: usize, x: &dyn Fn(usize) -> [Dual; 2]) -> [Dual; 2] {
        let normal = |e: usize| {
            let e = &self.slave.edges[e];
            edge_outward(x(e.nodes[0]), x(e.nodes[1]), e.side)
        };
        let edges = &self.slave.at_node[&node];
        let mut sum = normal(edges[0]);
        for &e in &edges[1..] {
            let n = normal(e);
            sum = [sum[0] + n[0], sum[1] + n[1]];
        }
        let len = (sum[0] * sum[0] + sum[1] * sum[1]).sqrt();
        if len.v < 1e-3 {
            return normal(k);
        }
        [sum[0] / len, sum[1] / len]
    }

    /// The nodal normals ([`Mortar::nodal_normal`]) of the two ends of own edge `k` (an index
    /// into the slave surface's edges).
    fn edge_normals(&self, k: usize, x: &dyn Fn(usize) -> [Dual; 2]) -> [[Dual; 2]; 2] {
        let e = &self.slave.edges[k];
        [
            self.nodal_normal(e.nodes[0], k, x),
            self.nodal_normal(e.nodes[1], k, x),
        ]
    }

    /// Position of node `n`: current (`q`, a dual over the local unknowns) or, for the geometry
    /// of small deformation, the reference one.
    fn point(
        &self,
        ctx: &Ctx,
        local: &Local,
        q: &[dual::DVec],
        n: usize,
        geometry: bool,
    ) -> [Dual; 2] {
        let m = local.m();
        if geometry && !self.nlgeo {
            let c = ctx.model.nodes[n].coords;
            [Dual::constant(c[0], m), Dual::constant(c[1], m)]
        } else {
            let v = q[local.index(n)];
            [v[0], v[1]]
        }
    }

    /// The broad phase of the master edges at the state the geometry is taken from.
    fn master_boxes(&self, ctx: &Ctx) -> Result<BroadPhase> {
        let mut boxes = Vec::with_capacity(self.master.edges.len());
        for e in &self.master.edges {
            let mut pts = Vec::with_capacity(e.nodes.len());
            for &n in &e.nodes {
                pts.push(if self.nlgeo {
                    ctx.position(n)?.0
                } else {
                    ctx.model.nodes[n].coords
                });
            }
            boxes.push(pts);
        }
        Ok(BroadPhase::new(boxes.iter().map(|v| (&v[..], v.len() > 2))))
    }

    /// Master edges that can overlap slave edge `k`: those whose ends project within it along
    /// its normal and that face it, of the nearest sheet ([`nearest_sheet`]).
    fn overlapping(&self, ctx: &Ctx, boxes: &BroadPhase, k: usize) -> Result<Vec<usize>> {
        let pos = |n: usize| -> Result<[f64; 2]> {
            let x = if self.nlgeo {
                ctx.position(n)?.0
            } else {
                ctx.model.nodes[n].coords
            };
            Ok([x[0], x[1]])
        };
        let e = &self.slave.edges[k];
        let (a, b) = (pos(e.nodes[0])?, pos(e.nodes[1])?);
        let t = [b[0] - a[0], b[1] - a[1]];
        let l2 = t[0] * t[0] + t[1] * t[1];
        let l = l2.sqrt();
        // Outward normal of the slave body.
        let n = [t[1] * e.side / l, -t[0] * e.side / l];
        let (slo, shi) = (
            [a[0].min(b[0]), a[1].min(b[1])],
            [a[0].max(b[0]), a[1].max(b[1])],
        );
        nearest_sheet(l, self.search_limit, |grow| {
            let lo = [slo[0] - grow, slo[1] - grow, -1.0];
            let hi = [shi[0] + grow, shi[1] + grow, 1.0];
            let mut facing = Vec::new();
            for mi in boxes.intersecting(lo, hi) {
                let me = &self.master.edges[mi];
                let own = self.own[mi].is_some();
                // Self-contact: never the edge itself, any other part only facing it squarely
                // (see `OWN_FACING`).
                let shared = me.nodes.iter().filter(|m| e.nodes.contains(m)).count();
                if own && shared == me.nodes.len().min(2) {
                    continue;
                }
                let (ya, yb) = (pos(me.nodes[0])?, pos(me.nodes[1])?);
                // The master's outward normal must face the slave's.
                let tm = [yb[0] - ya[0], yb[1] - ya[1]];
                let lm = (tm[0] * tm[0] + tm[1] * tm[1]).sqrt();
                let nm = [tm[1] * me.side / lm, -tm[0] * me.side / lm];
                let squarely = if own { own::OWN_FACING } else { GRAZING };
                if nm[0] * n[0] + nm[1] * n[1] >= squarely {
                    continue;
                }
                // The master's ends on the slave edge along its normal (in self-contact the
                // parts are then cut along the mean of the two normals, [`symmetric_ray`]).
                let xi = |y: [f64; 2]| ((y[0] - a[0]) * t[0] + (y[1] - a[1]) * t[1]) / l2;
                let (lo, hi) = (xi(ya).min(xi(yb)).max(0.0), xi(ya).max(xi(yb)).min(1.0));
                if !(hi - lo > 1e-12) {
                    continue;
                }
                let mid = [0.5 * (ya[0] + yb[0]), 0.5 * (ya[1] + yb[1])];
                let dist = (mid[0] - a[0]) * n[0] + (mid[1] - a[1]) * n[1];
                // An edge beside it (sharing a node) by its other end: in front across a
                // closing crease, behind round a sharp convex tip.
                let behind = match shared {
                    0 => -dist,
                    _ => {
                        let far = if e.nodes.contains(&me.nodes[0]) {
                            yb
                        } else {
                            ya
                        };
                        -((far[0] - a[0]) * n[0] + (far[1] - a[1]) * n[1])
                    }
                };
                if own && behind > 0.0 {
                    // Behind a facing part of its own surface only within a quarter of the
                    // edges' size or of the depth of the element behind it (the far face of a
                    // thin wall lies behind the node without having been crossed).
                    let depth = (ctx.model.elements[me.element].nodes.iter())
                        .map(|&k| pos(k).map(|y| (ya[0] - y[0]) * nm[0] + (ya[1] - y[1]) * nm[1]))
                        .try_fold(0.0, |acc: f64, v| v.map(|v| acc.max(v)))?;
                    if !own::within_reach(behind, l.min(lm), depth) {
                        continue;
                    }
                }
                facing.push(Facing {
                    index: mi,
                    dist,
                    size: lm,
                });
            }
            Ok(facing)
        })
    }
}

/// The gap at a slave parameter ξ, with the master nodes and their shape values there, the force
/// direction ν and ds/dξ.
type GapAt<'a> = &'a dyn Fn(Dual) -> (Dual, Vec<(usize, Dual)>, [Dual; 2], Dual);

/// Gauss points for quadratic pairs (the integrands are rational there: 5 points).
const GAUSS5: [(f64, f64); 5] = [
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (-0.538_469_310_105_683, 0.478_628_670_499_366_5),
    (0.0, 0.568_888_888_888_888_9),
    (0.538_469_310_105_683, 0.478_628_670_499_366_5),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// Point, tangent and second derivative of an edge through `x` (ends first, then the middle of a
/// quadratic one) at s ∈ [0, 1].
fn curve(x: &[[Dual; 2]], s: Dual) -> ([Dual; 2], [Dual; 2], [Dual; 2]) {
    let (n, dn) = shape(x.len(), s);
    // d²N/ds² of the quadratic edge (η = 2s − 1): 4·(1, 1, −2).
    let d2 = [4.0, 4.0, -8.0];
    let zero = s * 0.0;
    let (mut p, mut t, mut t2) = ([zero; 2], [zero; 2], [zero; 2]);
    for a in 0..x.len() {
        for i in 0..2 {
            p[i] = p[i] + n[a] * x[a][i];
            t[i] = t[i] + dn[a] * x[a][i];
            if x.len() == 3 {
                t2[i] = t2[i] + x[a][i] * d2[a];
            }
        }
    }
    (p, t, t2)
}

/// The root of f(s) = 0 near `s0` (f returns f and df/ds), by Newton on the values, then one
/// Newton step in duals from the root: its derivative with respect to the unknowns is exact. A
/// `linear` f (straight edges) needs only that step.
fn solve(s0: f64, m: usize, linear: bool, f: impl Fn(Dual) -> (Dual, Dual)) -> Dual {
    let mut s = s0;
    for _ in 0..if linear { 0 } else { 30 } {
        let (v, d) = f(Dual::constant(s, m));
        if !(d.v.abs() > 1e-300) {
            break;
        }
        let step = v.v / d.v;
        s -= step;
        if step.abs() < 1e-15 * (1.0 + s.abs()) {
            break;
        }
    }
    let c = Dual::constant(s, m);
    let (v, d) = f(c);
    c - v / d
}

/// Whether two straight edges (ends `x`, `y`, at their values) are within the first's length of
/// each other:
/// self-contact's walls close enough to meet along the mean of their normals
/// ([`symmetric_ray`]). Farther apart the rays are along the slave's normal: on walls of one
/// circle (an open bore) the mean of the normals joins every point to every other, and its
/// parts and gaps are ill-posed; an open gap's value exerts no force, so the switch changes
/// nothing a step converges to.
fn close(x: &[[Dual; 2]], y: &[[Dual; 2]]) -> bool {
    let v = |p: &[Dual; 2]| [p[0].v, p[1].v];
    let (x, y) = ([v(&x[0]), v(&x[1])], [v(&y[0]), v(&y[1])]);
    let to_segment = |p: [f64; 2], [a, b]: [[f64; 2]; 2]| {
        let t = [b[0] - a[0], b[1] - a[1]];
        let l2 = t[0] * t[0] + t[1] * t[1];
        let s = (((p[0] - a[0]) * t[0] + (p[1] - a[1]) * t[1]) / l2).clamp(0.0, 1.0);
        ((p[0] - a[0] - s * t[0]).powi(2) + (p[1] - a[1] - s * t[1]).powi(2)).sqrt()
    };
    let length = ((x[1][0] - x[0][0]).powi(2) + (x[1][1] - x[0][1]).powi(2)).sqrt();
    let gap = [
        to_segment(x[0], y),
        to_segment(x[1], y),
        to_segment(y[0], x),
        to_segment(y[1], x),
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min);
    gap < length
}

/// a × b in 2D.
fn cross(a: [Dual; 2], b: [Dual; 2]) -> Dual {
    a[0] * b[1] - a[1] * b[0]
}

/// The unit outward normal of a straight edge from `a` to `b` (`side` as [`EdgeSurface`] gives
/// it).
fn edge_outward(a: [Dual; 2], b: [Dual; 2], side: f64) -> [Dual; 2] {
    let t = [b[0] - a[0], b[1] - a[1]];
    let len = (t[0] * t[0] + t[1] * t[1]).sqrt();
    [t[1] * side / len, -(t[0] * side) / len]
}

/// The unit normal interpolated at s ∈ [0, 1] between the nodal normals `n` of a straight edge,
/// normalize((1 − s) n₀ + s n₁), and its derivative along s.
fn interpolated(n: &[[Dual; 2]; 2], s: Dual) -> ([Dual; 2], [Dual; 2]) {
    let v: [Dual; 2] = std::array::from_fn(|i| n[0][i] * (-s + 1.0) + n[1][i] * s);
    let dv: [Dual; 2] = std::array::from_fn(|i| n[1][i] - n[0][i]);
    let len = (v[0] * v[0] + v[1] * v[1]).sqrt();
    let u = [v[0] / len, v[1] / len];
    let along = u[0] * dv[0] + u[1] * dv[1];
    (
        u,
        [(dv[0] - u[0] * along) / len, (dv[1] - u[1] * along) / len],
    )
}

/// Self-contact's ray from the slave point `x` whose normal into the slave body is `nu`: the
/// parameter η where the line through x along ν + n(η) crosses the straight master edge `yg`,
/// n(η) the master's outward normal interpolated between its nodal normals `mn`, and that
/// direction, unit. The line bisects the two walls' normals, so two walls that mirror each other
/// meet at mirror points along the normal of their mirror plane, from either side: each wall's
/// segmentation, gap and force as a slave are the mirror images of the other's (along ν alone
/// they are not, and a folded tube came out off its half model by the projections' skew). The
/// normals are the surface's nodal ones interpolated, continuous from edge to edge, so that the
/// master edges' parts of a slave edge meet without overlap (the edges' own normals turn at
/// each node, and two edges' rays there cross).
fn symmetric_ray(
    x: [Dual; 2],
    nu: [Dual; 2],
    yg: &[[Dual; 2]],
    mn: &[[Dual; 2]; 2],
    m: usize,
) -> (Dual, [Dual; 2]) {
    let eta = solve(0.5, m, false, |eta| {
        let (y, ty, _) = curve(yg, eta);
        let (n, dn) = interpolated(mn, eta);
        let d = [nu[0] + n[0], nu[1] + n[1]];
        let r = [y[0] - x[0], y[1] - x[1]];
        (cross(r, d), cross(ty, d) + cross(r, dn))
    });
    let (n, _) = interpolated(mn, eta);
    let d = [nu[0] + n[0], nu[1] + n[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    (eta, [d[0] / len, d[1] / len])
}

/// The dual basis of a slave edge (straight or quadratic) at reference positions `x`
/// (see [`super::segment::dual_basis`]).
fn edge_dual_basis(x: &[[f64; 3]], axisymmetric: bool) -> [[f64; 4]; 4] {
    dual_basis_over(x, &[(0.0, 1.0)], axisymmetric)
}

/// The dual basis of a slave edge (reference positions `x`) biorthogonal over the parts
/// `spans` = [ξ_lo, ξ_hi] of it (Popp et al. 2013): Φ_j = Σ_b A_jb N_b with ∫ Φ_j N_k =
/// δ_jk ∫ N_k over the spans, A = D M⁻¹ of M and D integrated over them; in duals where the
/// spans move with the unknowns (the overlap with the master in large deformation). Over the
/// whole edge it is [`edge_dual_basis`]; over the part that overlaps the master, ḡ_j is the gap
/// at node j of the gap field's linear (or quadratic) fit over the overlap, so its sign is the
/// gap's.
fn dual_basis_over<T: Scalar>(x: &[[f64; 3]], spans: &[(T, T)], axisymmetric: bool) -> [[T; 4]; 4] {
    let k = x.len();
    let zero = spans[0].0.cst(0.0);
    let (mut m, mut d) = ([[zero; 4]; 4], [zero; 4]);
    for &(lo, hi) in spans {
        let half = (hi - lo) * 0.5;
        for &(z, wz) in &GAUSS5 {
            let s = lo + half * (1.0 + z);
            let (n, dn) = shape(k, s);
            let t: [T; 2] =
                std::array::from_fn(|i| (0..k).fold(zero, |acc, a| acc + dn[a] * x[a][i]));
            let mut ds = half * wz * (t[0] * t[0] + t[1] * t[1]).sqrt();
            if axisymmetric {
                // Biorthogonal per radian: weighted by r.
                ds = ds * (0..k).fold(zero, |acc, a| acc + n[a] * x[a][0]);
            }
            for a in 0..k {
                d[a] = d[a] + n[a] * ds;
                for b in 0..k {
                    m[a][b] = m[a][b] + n[a] * n[b] * ds;
                }
            }
        }
    }
    super::segment::biorthogonal(&m, &d, k)
}

/// What one slave node's constraint integrates to, in duals.
struct Integrals {
    gap: Dual,
    area: Dual,
    b: Vec<Dual>,
    partner: Partner,
    /// Per local node its share w_jn, and ∫ Φ_j ν (see [`SlipForm`]).
    shares: Vec<Dual>,
    normal: [Dual; 2],
}

/// A slave edge of a slot: its nodes, its positions (of the geometry), the slot's node among
/// them and the edge's Gauss rule.
struct SlaveEdge<'e> {
    nodes: &'e [usize],
    xg: &'e [[Dual; 2]],
    jloc: usize,
    gauss: &'e [(f64, f64)],
}

impl SlaveEdge<'_> {
    /// Add to the slot's integrals `w` those over [lo, hi] of the edge with the dual function
    /// Φ_j = Σ_b coef[b] N_b, `gap_at(ξ)` the gap, the master nodes with their shape values,
    /// the force direction and ds/dξ at a point: ∫ Φ_j g, ∫ N_j, and for the slave nodes
    /// ∫ Φ_j N_k ν, for the master nodes −∫ Φ_j M_l ν.
    fn accumulate(
        &self,
        local: &Local,
        w: &mut Integrals,
        coef: &[Dual],
        (lo, hi): (Dual, Dual),
        gap_at: GapAt,
    ) {
        let zero = lo.cst(0.0);
        let half = (hi - lo) * 0.5;
        for &(z, wz) in self.gauss {
            let xi = lo + half * (1.0 + z);
            let (shape_s, _) = shape(self.xg.len(), xi);
            let (g, master, dir, jac) = gap_at(xi);
            let ds = half * jac * wz;
            let nj = shape_s[self.jloc];
            let phi = (0..self.xg.len()).fold(zero, |acc, b| acc + shape_s[b] * coef[b]);
            w.gap = w.gap + phi * g * ds;
            w.area = w.area + nj * ds;
            for (kk, &n) in self.nodes.iter().enumerate() {
                let i = local.index(n);
                let share = phi * shape_s[kk] * ds;
                w.shares[i] = w.shares[i] + share;
                for d in 0..2 {
                    w.b[2 * i + d] = w.b[2 * i + d] + share * dir[d];
                }
            }
            for (n, ml) in master {
                let i = local.index(n);
                let share = phi * ml * ds;
                w.shares[i] = w.shares[i] - share;
                for d in 0..2 {
                    w.b[2 * i + d] = w.b[2 * i + d] - share * dir[d];
                }
            }
            for d in 0..2 {
                w.normal[d] = w.normal[d] + phi * dir[d] * ds;
            }
        }
    }
}

impl Mortar {
    /// The weighted gap of slot `j`, its support and force direction, over the local unknowns;
    /// `overlaps[k]` are the master edges that can overlap slave edge k.
    fn integrate(
        &self,
        ctx: &Ctx,
        overlaps: &[Vec<usize>],
        j: usize,
    ) -> Result<(Local, Integrals)> {
        let node = &self.slots[j].0;
        let (local, pairs) = self.pair_unknowns(ctx, overlaps, j)?;
        let q = local.seed();
        let m = local.m();
        let zero = Dual::constant(0.0, m);
        let mut w = Integrals {
            gap: zero,
            area: zero,
            b: vec![zero; m],
            partner: Partner::None,
            shares: vec![zero; local.nodes.len()],
            normal: [zero; 2],
        };
        for (k, over) in pairs {
            let e = &self.slave.edges[k];
            let jloc = e
                .nodes
                .iter()
                .position(|n| n == node)
                .expect("the slot's node");
            let geo = |n: usize| self.point(ctx, &local, &q, n, true);
            let cur = |n: usize| self.point(ctx, &local, &q, n, false);
            let xg: Vec<[Dual; 2]> = e.nodes.iter().map(|&n| geo(n)).collect();
            let xc: Vec<[Dual; 2]> = e.nodes.iter().map(|&n| cur(n)).collect();
            let gauss: &[(f64, f64)] = if xg.len() == 3 { &GAUSS5 } else { &GAUSS };
            // One Gauss point at ξ: the slave point (geometry and current), ν into the slave
            // body, and ds/dξ.
            // In axisymmetry ds/dξ carries the radius r of the slave point (per radian), else the
            // thickness.
            let at = |xi: Dual| {
                let (x, t, _) = curve(&xg, xi);
                let len = (t[0] * t[0] + t[1] * t[1]).sqrt();
                let nu = [-(t[1] * e.side) / len, t[0] * e.side / len];
                let jac = match self.axisymmetric {
                    true => len * x[0],
                    false => len * self.thick[k],
                };
                (x, t, nu, jac, curve(&xc, xi).0)
            };
            let slave_edge = SlaveEdge {
                nodes: &e.nodes,
                xg: &xg,
                jloc,
                gauss,
            };
            let add = |w: &mut Integrals, coef: &[Dual], lo: Dual, hi: Dual, gap_at: GapAt| {
                slave_edge.accumulate(&local, w, coef, (lo, hi), gap_at)
            };
            // The overlaps [ξ_lo, ξ_hi] of the master edges (at `geo` positions) with the slave
            // edge.
            // Self-contact: not through the slot's own node (see `OWN_FACING`).
            let over: Vec<usize> = (over.iter().copied())
                .filter(|&mi| {
                    !(self.own[mi].is_some() && self.master.edges[mi].nodes.contains(node))
                })
                .collect();
            // Self-contact's nodal normals of the slave edge (see [`symmetric_ray`]).
            let sn =
                (over.iter().any(|&mi| self.own[mi].is_some())).then(|| self.edge_normals(k, &geo));
            let pieces = self.overlap_pieces(&over, (&xg, sn.as_ref()), &geo, m);
            // The dual basis biorthogonal over the overlap alone: on a slave edge that overlaps
            // the master only in part (at the master's ends), the whole edge's basis can be
            // negative over the overlap and turn the sign of the weighted gap (a node beyond the
            // master's end then "penetrates" it).
            let coef = if pieces.is_empty() {
                [zero; 4]
            } else {
                let xref: Vec<[f64; 3]> =
                    e.nodes.iter().map(|&n| ctx.model.nodes[n].coords).collect();
                let spans: Vec<(Dual, Dual)> = pieces.iter().map(|p| p.span).collect();
                dual_basis_over(&xref, &spans, self.axisymmetric)[jloc]
            };
            for piece in pieces {
                let (mi, yg, (lo, hi)) = (piece.master, piece.yg, piece.span);
                let me = &self.master.edges[mi];
                let yc: Vec<[Dual; 2]> = me.nodes.iter().map(|&n| cur(n)).collect();
                if w.partner == Partner::None {
                    w.partner = Partner::Edge(mi);
                }
                let (ws, wm) = interface_weights(ctx.model, e.element, me.element);
                // Self-contact, walls close: the nodal normals of both edges.
                let normals = sn.as_ref().zip(piece.normals);
                let own = normals.is_some();
                add(&mut w, &coef, lo, hi, &|xi: Dual| {
                    let (x, t, mut nu, jac, xcur) = at(xi);
                    // η where x(ξ) + s ν crosses the master: (y(η) − x(ξ))·x'(ξ) = 0; in
                    // self-contact along the mean of the two normals.
                    let eta = if let Some((sn, mn)) = &normals {
                        let n = interpolated(sn, xi).0;
                        let (eta, mean) = symmetric_ray(x, [-n[0], -n[1]], &yg, mn, m);
                        nu = mean;
                        eta
                    } else {
                        solve(0.5, m, yg.len() == 2, |eta| {
                            let (y, ty, _) = curve(&yg, eta);
                            (
                                (y[0] - x[0]) * t[0] + (y[1] - x[1]) * t[1],
                                ty[0] * t[0] + ty[1] * t[1],
                            )
                        })
                    };
                    let (ycur, _, _) = curve(&yc, eta);
                    if !self.nlgeo && !own {
                        // The blend of the two reference normals ([`interface_weights`]).
                        let (_, ty, _) = curve(&yg, eta);
                        let ly = (ty[0] * ty[0] + ty[1] * ty[1]).sqrt();
                        let nm = [ty[1] * me.side / ly, -(ty[0] * me.side) / ly];
                        let blend = [nu[0] * ws + nm[0] * wm, nu[1] * ws + nm[1] * wm];
                        let len = (blend[0] * blend[0] + blend[1] * blend[1]).sqrt();
                        nu = [blend[0] / len, blend[1] / len];
                    }
                    let g = (xcur[0] - ycur[0]) * nu[0] + (xcur[1] - ycur[1]) * nu[1];
                    let (shape_m, _) = shape(yg.len(), eta);
                    let master = me
                        .nodes
                        .iter()
                        .zip(shape_m)
                        .map(|(&n, ml)| (n, ml))
                        .collect();
                    (g, master, nu, jac)
                });
            }
            if !self.rigid.is_empty() {
                let one = Dual::constant(1.0, m);
                w.partner = Partner::Rigid(self.rigid[0]);
                let coef = self.dual[k][jloc].map(|a| Dual::constant(a, m));
                add(&mut w, &coef, zero, one, &|xi: Dual| {
                    let (_, _, _, jac, xcur) = at(xi);
                    let (g, n, node) = self.rigid_gap(ctx, &local, &q, &xcur);
                    // A rigid segment moving with a node: the node takes the reaction.
                    let master = node.map(|n| vec![(n, Dual::constant(1.0, m))]);
                    (g, master.unwrap_or_default(), [n[0], n[1]], jac)
                });
            }
        }
        Ok((local, w))
    }

    /// The local unknowns of slave node `j`'s integrals (the node, rigid segments' nodes, its
    /// edges and the master edges each overlaps) and its (slave edge, overlapping master edges)
    /// pairs.
    fn pair_unknowns<'o>(
        &self,
        ctx: &Ctx,
        overlaps: &'o [Vec<usize>],
        j: usize,
    ) -> Result<(Local, Vec<EdgeOverlaps<'o>>)> {
        let (node, edges) = &self.slots[j];
        let mut local = Local::new(2);
        local.add(ctx, *node)?;
        for n in self.rigid.iter().filter_map(|&g| rigid_node(ctx.model, g)) {
            local.add(ctx, n)?;
        }
        let mut pairs: Vec<(usize, &[usize])> = Vec::new();
        for &k in edges {
            for &n in &self.slave.edges[k].nodes {
                local.add(ctx, n)?;
            }
            let over = &overlaps[k];
            for &mi in over {
                for &n in &self.master.edges[mi].nodes {
                    local.add(ctx, n)?;
                }
            }
            // Self-contact's nodal normals move with the nodes beside both edges' ends (the
            // slave edge's once, if it meets any own edge).
            let own: Vec<usize> = (over.iter().copied())
                .filter(|&mi| self.own[mi].is_some())
                .collect();
            let slave_ends = own.first().map(|_| &self.slave.edges[k].nodes);
            let ends = (slave_ends.into_iter().flatten())
                .chain(own.iter().flat_map(|&mi| &self.master.edges[mi].nodes));
            for &a in ends {
                for &b in &self.slave.at_node[&a] {
                    for &n in &self.slave.edges[b].nodes {
                        local.add(ctx, n)?;
                    }
                }
            }
            pairs.push((k, over));
        }
        if local.m() > dual::MAXV {
            return Err(Error::Solve(format!(
                "mortar contact: slave node {} overlaps too many master edges ({} unknowns, at \
                 most {})",
                ctx.model.nodes[*node].label,
                local.m(),
                dual::MAXV
            )));
        }
        Ok((local, pairs))
    }

    /// The parts [ξ_lo, ξ_hi] of slave edge `xg` that the master edges `over` overlap (the
    /// master's ends projected on it, (y − x(ξ))·x'(ξ) = 0; in self-contact, `sn` the slave
    /// edge's nodal normals, along the mean of the two normals as the Gauss points' rays go,
    /// [`symmetric_ray`]).
    fn overlap_pieces(
        &self,
        over: &[usize],
        (xg, sn): (&[[Dual; 2]], Option<&[[Dual; 2]; 2]>),
        geo: &dyn Fn(usize) -> [Dual; 2],
        m: usize,
    ) -> Vec<Piece> {
        let zero = Dual::constant(0.0, m);
        let mut pieces = Vec::new();
        let ends = |mi: usize| -> Vec<[Dual; 2]> {
            (self.master.edges[mi].nodes.iter())
                .map(|&n| geo(n))
                .collect()
        };
        // Along the mirror rays for every own edge if one is close: the parts of a slave edge
        // tile it only if all are cut along the same rays (mixed, a crease's two sides covered
        // the slave edge twice).
        let mirrored =
            sn.is_some() && (over.iter()).any(|&mi| self.own[mi].is_some() && close(xg, &ends(mi)));
        for &mi in over {
            let yg = ends(mi);
            let normals = (self.own[mi])
                .filter(|_| mirrored)
                .map(|mk| self.edge_normals(mk, geo));
            let own = sn.zip(normals.as_ref());
            // The master's end `end` (0 or 1) projected on the slave edge.
            let project = |end: usize| {
                let y = yg[end];
                let chord = [xg[1][0] - xg[0][0], xg[1][1] - xg[0][1]];
                let s0 = ((y[0].v - xg[0][0].v) * chord[0].v + (y[1].v - xg[0][1].v) * chord[1].v)
                    / (chord[0].v * chord[0].v + chord[1].v * chord[1].v);
                if let Some((sn, mn)) = &own {
                    let ne = mn[end];
                    return solve(s0, m, false, |s| {
                        // The line from x(ξ) along ν(ξ) + n_e (ν = −n, n the slave's outward
                        // normal) through y: r × d = 0.
                        let (x, t, _) = curve(xg, s);
                        let (n, dn) = interpolated(sn, s);
                        let d = [ne[0] - n[0], ne[1] - n[1]];
                        let r = [y[0] - x[0], y[1] - x[1]];
                        (cross(r, d), cross(d, t) - cross(r, dn))
                    });
                }
                solve(s0, m, xg.len() == 2, |s| {
                    let (x, t, t2) = curve(xg, s);
                    let r = [y[0] - x[0], y[1] - x[1]];
                    (
                        r[0] * t[0] + r[1] * t[1],
                        r[0] * t2[0] + r[1] * t2[1] - (t[0] * t[0] + t[1] * t[1]),
                    )
                })
            };
            let (pa, pb) = (project(0), project(1));
            let (mut lo, mut hi) = if pa.v < pb.v { (pa, pb) } else { (pb, pa) };
            if lo.v < 0.0 {
                lo = zero;
            }
            if hi.v > 1.0 {
                hi = Dual::constant(1.0, m);
            }
            if hi.v - lo.v > 1e-12 {
                pieces.push(Piece {
                    master: mi,
                    yg,
                    span: (lo, hi),
                    normals,
                });
            }
        }
        pieces
    }

    /// The smallest gap of a point against the rigid segments, with their outward normal and the
    /// node the segment moves with, if any.
    fn rigid_gap(
        &self,
        ctx: &Ctx,
        local: &Local,
        q: &[dual::DVec],
        x: &[Dual; 2],
    ) -> (Dual, Vec<Dual>, Option<usize>) {
        let m = x[0].n;
        // A reference point moved with the segment's node.
        let origin = |p: [f64; 3], node: Option<usize>| -> [Dual; 2] {
            std::array::from_fn(|i| match node {
                Some(n) => q[local.index(n)][i] + (p[i] - ctx.model.nodes[n].coords[i]),
                None => Dual::constant(p[i], m),
            })
        };
        let mut best: Option<(Dual, Vec<Dual>, Option<usize>)> = None;
        for &g in &self.rigid {
            let node = rigid_node(ctx.model, g);
            let (gap, n) = match &ctx.model.segments[g].kind {
                SegmentKind::Circle {
                    center,
                    radius,
                    cavity,
                    ..
                } => rigid::circle(&x[..], &origin(*center, node), *radius, *cavity),
                SegmentKind::Plane { point, normal, .. } => {
                    rigid::plane(&x[..], &origin(*point, node), &normal[..2])
                }
                SegmentKind::Polynomial { coeffs, body_above } => {
                    match rigid::project_on_poly(coeffs, [x[0].v, x[1].v]) {
                        Some(t) => rigid::polynomial(coeffs, &x[..], t, *body_above),
                        None => continue,
                    }
                }
                _ => unreachable!("rigid segments only"),
            };
            if best.as_ref().is_none_or(|b| gap.v < b.0.v) {
                best = Some((gap, n, node));
            }
        }
        best.expect("a rigid segment")
    }
}

impl Formulation for Mortar {
    fn n_slots(&self) -> usize {
        self.slots.len()
    }

    fn n_multipliers(&self) -> usize {
        self.law.n_multipliers(self.slots.len())
    }

    fn nodes_needing_dofs(&self) -> Vec<usize> {
        let mut out: Vec<usize> = self.slots.iter().map(|s| s.0).collect();
        out.extend(self.rigid_nodes.iter().copied());
        out
    }

    fn candidate_nodes(&self, _ctx: &Ctx) -> Result<Vec<usize>> {
        let mut out: Vec<usize> = self.nodes_needing_dofs();
        out.extend(
            self.master
                .edges
                .iter()
                .flat_map(|e| e.nodes.iter().copied()),
        );
        out.sort_unstable();
        out.dedup();
        Ok(out)
    }

    fn penalties(&self) -> Option<(usize, f64, f64)> {
        self.law.penalties()
    }

    fn symmetric(&self) -> bool {
        // B = ∇g̃ in small deformation; the tangent is then symmetric (material part only),
        // but for a self-contact pair's merged constraint.
        !self.nlgeo && self.law.symmetric() && self.own.iter().all(Option::is_none)
    }

    fn partner_nodes(&self, partner: Partner) -> &[usize] {
        match partner {
            Partner::Edge(k) => &self.master.edges[k].nodes,
            _ => &[],
        }
    }

    fn evaluate(
        &self,
        ctx: &Ctx,
        first_lambda: usize,
        _search: Search,
        history: Option<&[SlotState]>,
        points: &mut Vec<SlotLinearization>,
        states: &mut Vec<SlotState>,
    ) -> Result<f64> {
        // The search, once per slave edge (each edge serves the slots of its nodes).
        let start = std::time::Instant::now();
        let boxes = self.master_boxes(ctx)?;
        let overlaps = (0..self.slave.edges.len())
            .map(|k| self.overlapping(ctx, &boxes, k))
            .collect::<Result<Vec<_>>>()?;
        let searching = start.elapsed().as_secs_f64();
        let weighted = (0..self.slots.len())
            .map(|j| {
                let (local, w) = self.integrate(ctx, &overlaps, j)?;
                // The shares of the reference (small deformation) or current segmentation.
                let slip = Some(SlipForm {
                    shares: w.shares.iter().map(|&s| s.into()).enumerate().collect(),
                    normal: [
                        w.normal[0].into(),
                        w.normal[1].into(),
                        Jet::constant(0.0, local.m()),
                    ],
                });
                let w = Weighted {
                    gap: w.gap.into(),
                    area: w.area.into(),
                    b: w.b.into_iter().map(Into::into).collect(),
                    partner: w.partner,
                    slip,
                };
                Ok((local, w))
            })
            .collect::<Result<Vec<_>>>()?;
        // Self-contact: pairs that repeat one contact hold it by one constraint.
        let pairs = self.repeated_pairs(ctx, &overlaps, &weighted, history)?;
        let nodes: Vec<usize> = self.slots.iter().map(|s| s.0).collect();
        self.law.evaluate_slots(
            ctx,
            first_lambda,
            &nodes,
            weighted,
            &pairs,
            history,
            points,
            states,
        )?;
        Ok(searching)
    }
}

impl Mortar {
    /// Self-contact's repeated pairs ([`own::repeated_pairs`]): slots whose slave edges each
    /// overlap an own edge of the other's node, their spacing the second's shortest edge.
    fn repeated_pairs(
        &self,
        ctx: &Ctx,
        overlaps: &[Vec<usize>],
        weighted: &[(Local, Weighted)],
        history: Option<&[SlotState]>,
    ) -> Result<Vec<(usize, usize)>> {
        if self.own.iter().all(Option::is_none) {
            return Ok(Vec::new());
        }
        // The nodes of the own edges each slot's slave edges overlap.
        let met: Vec<Vec<usize>> = (self.slots.iter())
            .map(|(_, edges)| {
                let mut nodes: Vec<usize> = (edges.iter())
                    .flat_map(|&k| &overlaps[k])
                    .filter(|&&mi| self.own[mi].is_some())
                    .flat_map(|&mi| self.master.edges[mi].nodes.iter().copied())
                    .collect();
                nodes.sort_unstable();
                nodes.dedup();
                nodes
            })
            .collect();
        let pos = |node: usize| ctx.position(node).map(|p| p.0);
        // The shortest of a slot's slave edges.
        let spacing = |j: usize| -> Result<f64> {
            let mut spacing = f64::INFINITY;
            for &k in &self.slots[j].1 {
                let e = &self.slave.edges[k].nodes;
                let (a, b) = (pos(e[0])?, pos(e[1])?);
                spacing = spacing.min((0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt());
            }
            Ok(spacing)
        };
        let nodes: Vec<usize> = self.slots.iter().map(|s| s.0).collect();
        own::repeated_pairs(
            ctx,
            &nodes,
            &met,
            &|j| self.law.supported(j, weighted[j].1.area.v),
            &spacing,
            history,
        )
    }
}

/// A slave edge and the master edges that overlap it.
type EdgeOverlaps<'o> = (usize, &'o [usize]);

/// The part [ξ_lo, ξ_hi] (`span`) of a slave edge that master edge `master` (positions `yg`)
/// overlaps, and in self-contact where the walls are close the master edge's nodal normals
/// (the rays then run along the mean of both walls' normals, [`symmetric_ray`]).
struct Piece {
    master: usize,
    yg: Vec<[Dual; 2]>,
    span: (Dual, Dual),
    normals: Option<[[Dual; 2]; 2]>,
}
