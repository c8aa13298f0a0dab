//! Node-to-segment contact (spec §2.5, §2.6): each node of the condition meets one partner among
//! its segments — an edge (2D) or a face (3D) of the master surface they form, or a rigid shape —
//! chosen by [`super::search`]. The kinematics against each kind of partner are in [`edges`],
//! [`faces`] and [`rigid`].
//!
//! Kinematics against a surface: the contact point solves "x_s − x(ξ) is parallel to ñ(ξ)" on the
//! current edge or face, ñ the smoothed normal (current in large deformation, reference in small
//! deformation); g = (x_s − x(ξ))·n̂(ξ); the force acts along n̂ (or the prescribed `normal`) on the
//! node and along −c_a(ξ) n̂ on the master nodes, x(ξ) = Σ c_a x_a. All of it is differentiated,
//! including ξ(q), so Newton converges quadratically while nodes slide. In small deformation the
//! force direction is the reference normal: the geometrically linear contact of OOFEM (its N2S_LM
//! test values come out exactly), now with the contact point following the node.
//!
//! Open boundaries of a master: past an open end (2D) or edge (3D) the surface continues and the
//! force is weighted by w ∈ [0, 1], the share of the node's tributary extent that still faces the
//! master (a smoothstep of (a − d)/(a + b), with d the distance past the boundary and a, b the
//! node's tributary extents behind and ahead). A node on the boundary with its surface behind it
//! keeps its full force, a node whose whole tributary extent is past it has none, and nothing jumps
//! in between. The multiplier law is the infinite-penalty limit: g = 0 wherever w > 0, and where
//! holding the node there would push it past the ramp's far end while, let go, it would come
//! back into the ramp below the master (a corner bulging past a die's edge), the node is held
//! at the ramp's end, e = d − a = 0, with g < 0: the state a penalty force ε·w·(−g) tends to as
//! ε grows (w → 0 there while the force stays finite). The constraint is max(g, e) = 0, see
//! [`crate::contact::law::multiplier`].
//!
//! Self-contact: a node on the condition's own master surface ([`slots::OwnSurface`]) meets only
//! the parts of it that face it, outside its own neighbourhood (`NodeToSegment::admits`); two
//! such nodes that meet each other's walls at one place hold one constraint ([`pairs`]).

mod edges;
mod faces;
mod pairs;
mod rigid;
mod slots;

use slots::{OwnSurface, Slot};

use super::dual::{DVec, Dual, Jet};
use super::formulation::Anchor;
use super::formulation::{apply_law, Ctx, Formulation, Local, Partner, Search, SlotState};
use super::geometry::bodies::{self, BodiesAt, Inside, MasterBodies};
use super::geometry::edges::{edge_normal, EdgeSurface};
use super::geometry::faces as faces_geom;
use super::geometry::faces::{FaceSurface, NodalNormal};
use super::geometry::scalar::Scalar;
use super::law::{SlipKinematics, SlotKinematics};
use super::law::{SlotFriction, SlotLaw};
use super::repeated;
use super::search::broad::BroadPhase;
use super::search::{self, Candidate};
use super::slot::SlotLinearization;
use super::tributary::PressureAreas;
use crate::error::Result;
use crate::model::queries::model_size;
use crate::model::{Enforcement, Friction, Model, Pairing, SegmentKind};
use std::collections::HashMap;

/// A projection within this distance (in parameter units) of an edge's ends or a face's edges
/// counts as inside it.
const INSIDE_TOL: f64 = 1e-9;
/// Beyond an interior boundary of its edge or face, a previous partner is kept within this band
/// (in parameter units): enough that round-off does not make a node on a vertex or a face edge
/// alternate between its neighbours, small enough that the extrapolated partner never changes an
/// answer (past an interior boundary, the neighbour is the surface).
const HYSTERESIS_BAND: f64 = 1e-6;
/// Ramp length at an open boundary for a node without neighbours, as a fraction of the
/// boundary's edge length.
const ISOLATED_RAMP: f64 = 0.01;
/// How far behind a facing part of its own surface a self-contact node still meets it without
/// lying in the element behind it (a Newton iterate's overshoot): this fraction of its spacing
/// to its neighbours or of that element's depth behind the part, the smaller (a wall thinner
/// than the spacing is not taken for a crossing).
const DEPTH: f64 = 0.25;
/// How far outside an element a point still lies in it, in the element's coordinates.
const ROUND_OFF: f64 = 1e-9;
/// An immediate neighbour faces a self-contact node when their normals make more than 120°
/// (n·n_s < −1/2): across a closing crease they are opposed, while the tip of a crease sees
/// the walls beside it at about 90°, from its side, and must not be held by them.
const NEIGHBOUR_FACING: f64 = -0.5;

pub struct NodeToSegment {
    number: usize,
    enforcement: Enforcement,
    /// The slots' forces are unknowns of the Newton system: multipliers, a penalty with
    /// friction, or a penalty far stiffer than its elements (with its compliance: see
    /// [`crate::contact::law::penalty::solved_as_multipliers`]).
    forces_unknown: bool,
    /// Coulomb friction (edges and rigid segments).
    friction: Option<Friction>,
    /// Prescribed force direction (`normal`), instead of the segment normal.
    normal: Option<[f64; 3]>,
    slots: Vec<Slot>,
    edges: EdgeSurface,
    faces: FaceSurface,
    /// Rigid segments of the condition (model segment indices).
    rigid: Vec<usize>,
    /// Reference nodes the rigid segments move with.
    rigid_nodes: Vec<usize>,
    dim: usize,
    /// Gap difference (a length) within which a previous partner counts as tied.
    tie: f64,
    /// Contact nodes of the model's other node-to-segment conditions. An open end (edge) of
    /// this condition's master made of them is held by the other condition (two-pass contact:
    /// the corner meets this condition's nodes' surface there), so the master does not continue
    /// past it (the extension would hold the other body's surface on this one's tangent beyond
    /// the corner, a constraint that is not there): the weight falls from 1 to 0 within
    /// `ISOLATED_RAMP` of an edge length past it, whatever the node's tributary extents, which
    /// keeps coincident corners (flush bodies) continuous.
    covered: std::collections::HashSet<usize>,
    /// The areas the nodes' pressures refer to.
    areas: PressureAreas,
    /// The elements behind the master's edges and faces.
    bodies: MasterBodies,
    /// The master's edges and faces of each of those elements.
    items_of: HashMap<usize, Vec<Partner>>,
}

/// A slot's contact point before its law: its multiplier equations, local unknowns and
/// kinematics, and its state so far.
struct Prepared {
    lambda_eqs: Option<std::ops::Range<usize>>,
    local: Local,
    kin: SlotKinematics,
    state: SlotState,
}

/// The master surface at the current state: positions of its nodes, the broad phases of its
/// edges and faces and, for faces in large deformation, their current nodal normals with
/// derivatives.
struct Current {
    x: HashMap<usize, [f64; 3]>,
    normals: HashMap<usize, NodalNormal>,
    edges: BroadPhase,
    faces: BroadPhase,
    bodies: BodiesAt,
}

impl NodeToSegment {
    /// Multipliers per contact node: the normal force's, and with friction the friction force's
    /// components.
    fn multipliers_per_node(&self) -> usize {
        1 + if self.friction.is_some() { self.dim } else { 0 }
    }

    /// The friction of a point with force direction `dir` anchored at `xa` (`anchor`), into
    /// `kin`: the slip the friction multipliers act on (see [`super::apply_law`]). Returns the
    /// anchor an open point leaves, `at_point`; the law keeps `anchor` where the point sticks
    /// and, with a penalty, takes `slid` where it slides: `slid` of the point behind the node by
    /// the elastic slip `held`/ε_T, `held` the friction force the iteration holds (its
    /// multipliers). `spread` distributes a force on the node over the local unknowns (the
    /// node, and its negative over the master), `jet` takes the kinematics' duals to the local
    /// unknowns.
    #[allow(clippy::too_many_arguments)]
    fn point_friction(
        &self,
        slot: &Slot,
        law: SlotFriction,
        [xs, xa, n]: [DVec; 3],
        (anchor, at_point): (&Anchor, Anchor),
        held: [f64; 3],
        slid: impl FnOnce([f64; 3]) -> Anchor,
        spread: impl Fn(&DVec) -> Vec<Jet>,
        jet: impl Fn(&Dual) -> Jet,
        kin: &mut SlotKinematics,
    ) -> Anchor {
        let dim = self.dim;
        let nv = xs[0].n;
        let penalty = !slot.law.is_multipliers();
        let compliance = if penalty { 1.0 / law.penalty } else { 0.0 };
        kin.slip = Some(SlipKinematics {
            slip: (0..dim).map(|i| jet(&(xs[i] - xa[i]))).collect(),
            normal: (0..dim).map(|i| jet(&n[i])).collect(),
            share: (0..dim)
                .map(|k| {
                    let unit = std::array::from_fn(|i| Dual::constant(f64::from(i == k), nv));
                    spread(&unit)
                })
                .collect(),
            mu: law.mu,
            stiffness: slot.stiffness,
            kept: *anchor,
            compliance,
            slid: penalty.then(|| slid(std::array::from_fn(|i| xs[i].v - held[i] * compliance))),
        });
        at_point
    }
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

/// Tributary extents (behind, ahead) of a node at `xs` along the unit direction `out`, from its
/// neighbours; a node without neighbours gets the ramp `isolated` behind.
fn extents(slot: &Slot, xs: [f64; 3], out: [f64; 3], isolated: f64) -> (f64, f64) {
    let (mut a, mut b) = (0.0f64, 0.0f64);
    for nb in &slot.neighbors {
        let d: f64 = (0..3).map(|i| (nb[i] - xs[i]) * out[i]).sum();
        a = a.max(-0.5 * d);
        b = b.max(0.5 * d);
    }
    if a + b > 0.0 {
        (a, b)
    } else {
        (isolated, 0.0)
    }
}

/// The weight factor of one open boundary: d past it, tributary extents (a, b).
fn ramp<T: Scalar>(d: T, (a, b): (f64, f64)) -> T {
    smoothstep((-d + a) * (1.0 / (a + b)))
}

/// Where a node stands against the open boundaries of its partner.
struct EndWeight<T> {
    /// w: the product of the boundaries' ramps.
    w: T,
    /// The distance d − a past the far end of the nearest ramp (w = 0 from 0 on), with that
    /// ramp's length a + b; None without an open boundary.
    past: Option<(T, f64)>,
}

impl<T: Scalar> EndWeight<T> {
    fn new(one: T) -> EndWeight<T> {
        EndWeight { w: one, past: None }
    }

    /// Takes in open boundary at distance `d` past it with tributary extents `ab`.
    fn boundary(&mut self, d: T, ab: (f64, f64)) {
        self.w = self.w * ramp(d, ab);
        let e = d - ab.0;
        if self.past.as_ref().is_none_or(|(p, _)| e.val() > p.val()) {
            self.past = Some((e, ab.0 + ab.1));
        }
    }

    /// Whether the boundary still counts the node as the partner's: inside its ramp, or with
    /// `multipliers` (whose end state holds e = 0, which an iterate overshoots) within a ramp's
    /// length past it.
    fn counts(&self, multipliers: bool) -> bool {
        self.w.val() > 0.0
            || (multipliers && self.past.as_ref().is_some_and(|(e, len)| e.val() < *len))
    }
}

impl NodeToSegment {
    /// Whether `slot` is held by Lagrange multipliers (not a penalty in any form).
    fn multipliers(&self, slot: &Slot) -> bool {
        slot.law.is_multipliers()
    }

    pub fn new(model: &Model, ci: usize) -> Result<NodeToSegment> {
        let c = &model.contacts[ci];
        let Pairing::NodeToSegment { nodes, segments } = &c.pairing else {
            unreachable!("a node-to-segment condition")
        };
        let edges = EdgeSurface::new(model, segments);
        let faces = FaceSurface::new(model, segments);
        slots::check_nodes(model, c, nodes)?;
        edges::check_support(model, &edges)?;
        let slots = slots::slots(model, c, nodes, segments, (&edges, &faces));
        let (rigid, rigid_nodes) = rigid_segments(model, segments);
        let mut items_of: HashMap<usize, Vec<Partner>> = HashMap::new();
        for (k, e) in edges.edges.iter().enumerate() {
            items_of
                .entry(e.element)
                .or_default()
                .push(Partner::Edge(k));
        }
        for (k, f) in faces.faces.iter().enumerate() {
            items_of
                .entry(f.element)
                .or_default()
                .push(Partner::Face(k));
        }
        let forces_unknown = c.enforcement.forces_are_unknowns(c.friction)
            || super::law::penalty::solved_as_multipliers(
                model,
                slots.iter().map(|s| (s.law.penalty(), s.stiffness)),
            );
        Ok(NodeToSegment {
            forces_unknown,
            items_of,
            bodies: MasterBodies::new(
                (edges.edges.iter().map(|e| e.element))
                    .chain(faces.faces.iter().map(|f| f.element)),
            ),
            areas: PressureAreas::new(model, nodes),
            number: c.number,
            enforcement: c.enforcement,
            friction: c.friction,
            normal: c.normal,
            slots,
            edges,
            faces,
            rigid,
            rigid_nodes,
            dim: model.domain.nsd(),
            tie: 1e-9 * model_size(model),
            covered: slots::covered(model, ci),
        })
    }

    /// Positions of the surface nodes, and the current nodal normals of faces in large
    /// deformation.
    fn current(&self, ctx: &Ctx) -> Result<Current> {
        let mut x = HashMap::new();
        let nodes = self
            .edges
            .edges
            .iter()
            .flat_map(|e| &e.nodes)
            .chain(self.faces.faces.iter().flat_map(|f| &f.nodes));
        for &n in nodes {
            if let std::collections::hash_map::Entry::Vacant(v) = x.entry(n) {
                v.insert(ctx.position(n)?.0);
            }
        }
        let mut normals = HashMap::new();
        if self.normal.is_none() {
            for f in self.faces.faces.iter().filter(|f| f.nlgeo) {
                for &a in &f.nodes {
                    normals
                        .entry(a)
                        .or_insert_with(|| self.faces.nodal_normal_jacobian(a, &|n| x[&n]));
                }
            }
        }
        let corners = |nodes: &Vec<usize>| nodes.iter().map(|n| x[n]).collect::<Vec<_>>();
        let edge_boxes: Vec<Vec<[f64; 3]>> =
            self.edges.edges.iter().map(|e| corners(&e.nodes)).collect();
        let face_boxes: Vec<Vec<[f64; 3]>> =
            self.faces.faces.iter().map(|f| corners(&f.nodes)).collect();
        Ok(Current {
            edges: BroadPhase::new(edge_boxes.iter().map(|v| (&v[..], v.len() > 2))),
            faces: BroadPhase::new(face_boxes.iter().map(|v| (&v[..], v.len() > 4))),
            bodies: self.bodies.at(ctx.model, |n| Ok(ctx.position(n)?.0))?,
            x,
            normals,
        })
    }

    /// Every possible partner of a node at `xs`, with the previous partner's band included.
    fn candidates(
        &self,
        ctx: &Ctx,
        slot: &Slot,
        xs: [f64; 3],
        cur: &Current,
        previous: Option<Partner>,
    ) -> Result<Vec<Candidate>> {
        let model = ctx.model;
        let mut out = Vec::new();
        // The previous partner is a candidate wherever the walk stops.
        let mut seen = false;
        let admits = self.admission(ctx, slot, xs, cur);
        let mut keep = |c: Option<Candidate>, out: &mut Vec<Candidate>| {
            let c = c.filter(|c| admits(c))?;
            seen |= Some(c.partner) == previous;
            out.push(c);
            c.inside.then_some(c.gap.abs())
        };
        cur.edges.walk(
            xs,
            slot.reach,
            |k| self.open_ends(k).iter().any(|&o| o),
            |k| keep(self.edge_candidate(model, slot, xs, cur, k), &mut out),
        );
        let faces = &self.faces.faces;
        cur.faces.walk(
            xs,
            slot.reach,
            |k| faces[k].open.iter().any(|&o| o),
            |k| keep(self.face_candidate(model, slot, xs, cur, k), &mut out),
        );
        let previous = match previous {
            Some(Partner::Edge(k)) if !seen => self.edge_candidate(model, slot, xs, cur, k),
            Some(Partner::Face(k)) if !seen => self.face_candidate(model, slot, xs, cur, k),
            _ => None,
        };
        out.extend(previous.filter(|c| admits(c)));
        self.rigid_candidates(ctx, xs, &mut out)?;
        Ok(out)
    }

    /// Where a node at `xs` lies inside the master's body (see [`bodies`]), if it does.
    fn inside_body(&self, ctx: &Ctx, slot: &Slot, xs: [f64; 3], cur: &Current) -> Option<Inside> {
        // How deep: the distance to the element's master edges (a quadratic one by its two
        // chords through the mid-side node) or to the planes of its master faces.
        let depth = |e: usize, p: [f64; 3]| {
            let at = |n: &usize| cur.x[n];
            self.items_of[&e]
                .iter()
                .map(|&item| match item {
                    Partner::Edge(k) => {
                        let x: Vec<[f64; 3]> = self.edges.edges[k].nodes.iter().map(at).collect();
                        match x.len() {
                            3 => bodies::segment_distance(p, x[0], x[2])
                                .min(bodies::segment_distance(p, x[2], x[1])),
                            _ => bodies::segment_distance(p, x[0], x[1]),
                        }
                    }
                    Partner::Face(k) => {
                        let f = &self.faces.faces[k];
                        let corners: Vec<[f64; 3]> =
                            f.nodes[..f.kind.corners()].iter().map(at).collect();
                        bodies::plane_distance(p, &corners)
                    }
                    _ => f64::INFINITY,
                })
                .fold(f64::INFINITY, f64::min)
        };
        cur.bodies
            .containing(ctx.model, &self.bodies, xs, slot.node, depth)
    }

    /// The partner of a node at `xs` whose best candidate (`best`, from `cands`) leaves it open
    /// (a positive gap, or none): where the node lies inside the master's body it has crossed
    /// the surface, and the nearest candidate that measures it inside (a negative gap), among
    /// those and the edges or faces of the element it is in, holds it instead. Beside a crease
    /// or where two master bodies meet, the nearest part of the surface can face the node from
    /// the open side while the part it crossed is farther.
    fn held_inside(
        &self,
        ctx: &Ctx,
        slot: &Slot,
        xs: [f64; 3],
        cur: &Current,
        cands: &[Candidate],
        best: Option<Candidate>,
    ) -> Option<Candidate> {
        if best.is_some_and(|c| c.gap < 0.0) {
            return best;
        }
        let Some(inside) = self.inside_body(ctx, slot, xs, cur) else {
            return best;
        };
        let own = self.items_of[&inside.element]
            .iter()
            .filter_map(|&item| match item {
                Partner::Edge(k) => self.edge_candidate(ctx.model, slot, xs, cur, k),
                Partner::Face(k) => self.face_candidate(ctx.model, slot, xs, cur, k),
                _ => None,
            });
        let own = own.filter(self.admission(ctx, slot, xs, cur));
        cands
            .iter()
            .copied()
            .chain(own)
            .filter(|c| c.inside && c.gap < 0.0)
            .min_by(|a, b| a.gap.abs().total_cmp(&b.gap.abs()))
            .or(best)
    }

    /// Which candidates a node at `xs` can meet: any, unless it is in self-contact (then those
    /// [`NodeToSegment::admits`] admits, against its current normal).
    fn admission<'a>(
        &'a self,
        ctx: &'a Ctx,
        slot: &'a Slot,
        xs: [f64; 3],
        cur: &'a Current,
    ) -> impl Fn(&Candidate) -> bool + 'a {
        let own = (slot.own.as_ref()).map(|own| (own, self.own_normal(slot.node, own, cur)));
        move |c: &Candidate| own.is_none_or(|(own, n)| self.admits(ctx, slot, own, n, xs, cur, c))
    }

    /// The current outward normal of self-contact node `node`: the mean of its own edges' or faces'
    /// unit normals there (a direction to tell facing parts of the surface, not differentiated).
    fn own_normal(&self, node: usize, own: &OwnSurface, cur: &Current) -> [f64; 3] {
        let at = |n: &usize| cur.x[n];
        let node_of = |nodes: &[usize]| nodes.iter().position(|&n| n == node);
        let mut sum = [0.0; 3];
        for &item in &own.items {
            let n = match item {
                Partner::Edge(k) => {
                    let e = &self.edges.edges[k];
                    let x: Vec<[f64; 2]> = e.nodes.iter().map(|n| [at(n)[0], at(n)[1]]).collect();
                    let s = [0.0, 1.0, 0.5][node_of(&e.nodes).unwrap_or(2)];
                    let n = edge_normal(&x, e.side, s);
                    [n[0], n[1], 0.0]
                }
                Partner::Face(k) => {
                    let f = &self.faces.faces[k];
                    let x: Vec<[f64; 3]> = f.nodes.iter().map(at).collect();
                    let (xi, eta) = node_of(&f.nodes).map_or(faces_geom::centre(f.kind), |i| {
                        faces_geom::node_param(f.kind, i)
                    });
                    faces_geom::face_normal(f.kind, &x, f.side, xi, eta)
                }
                _ => continue,
            };
            for i in 0..3 {
                sum[i] += n[i];
            }
        }
        let len = sum.iter().map(|v| v * v).sum::<f64>().sqrt();
        sum.map(|v| v / len)
    }

    /// Whether a self-contact node at `xs` (normal `normal` on its own surface `own`) can meet
    /// candidate `c`: never an edge or face it belongs to, never a part of the surface facing
    /// the same way as its own (n·n_s ≥ 0; an immediate neighbour only facing it squarely,
    /// [`NEIGHBOUR_FACING`]: across a closing crease, where a node meets the edge across it,
    /// while the tip of a crease sees the walls beside it at about 90°), and behind a part
    /// facing it (a negative gap) only within [`DEPTH`] or where it lies in the element behind
    /// that part, its boundary included: it has crossed the surface there. A node on a convex
    /// bulge lies far behind the tangent planes of the opposite side, a node of a thin wall
    /// behind its other face, and neither has crossed anything; a node on a body's flat free
    /// face (a slab's end) that crossed lies on the boundary of the element it entered, not
    /// strictly inside. Never a face of the node's own elements.
    #[allow(clippy::too_many_arguments)]
    fn admits(
        &self,
        ctx: &Ctx,
        slot: &Slot,
        own: &OwnSurface,
        normal: [f64; 3],
        xs: [f64; 3],
        cur: &Current,
        c: &Candidate,
    ) -> bool {
        if own.items.contains(&c.partner) {
            return false;
        }
        let (n, element) = match c.partner {
            Partner::Edge(k) => {
                let (_, n) = self.edge_geometry_f64(k, cur).gap([xs[0], xs[1]], c.xi[0]);
                ([n[0], n[1], 0.0], self.edges.edges[k].element)
            }
            Partner::Face(k) => (
                self.face_geometry_f64(k, cur).gap(&xs, c.xi[0], c.xi[1]).1,
                self.faces.faces[k].element,
            ),
            _ => return true,
        };
        let facing = match own.neighbours.contains(&c.partner) {
            true => NEIGHBOUR_FACING,
            false => 0.0,
        };
        let el = &ctx.model.elements[element];
        if (0..3).map(|i| n[i] * normal[i]).sum::<f64>() >= facing || el.nodes.contains(&slot.node)
        {
            return false;
        }
        if c.gap >= 0.0 {
            return true;
        }
        let Ok(x) = (el.nodes.iter())
            .map(|&m| ctx.position(m).map(|p| p.0))
            .collect::<Result<Vec<_>>>()
        else {
            return false;
        };
        // The element's depth behind the partner: how far its nodes lie behind the contact
        // point along the normal.
        let point: [f64; 3] = std::array::from_fn(|i| xs[i] - c.gap * n[i]);
        let depth = (x.iter())
            .map(|y| -(0..3).map(|i| (y[i] - point[i]) * n[i]).sum::<f64>())
            .fold(0.0, f64::max);
        let shape = el.etype.shape();
        -c.gap <= DEPTH * own.spacing.min(depth)
            || crate::fem::geometry::locate(shape, &x, xs)
                .is_some_and(|xi| shape.inside_margin(xi) > -ROUND_OFF)
    }

    /// The local unknowns and kinematics of a slot without a partner: no force; a multiplier is
    /// held at zero.
    fn no_partner(&self, ctx: &Ctx, slot: &Slot) -> Result<(Local, SlotKinematics)> {
        let mut local = Local::new(self.dim);
        local.add(ctx, slot.node)?;
        let m = local.m();
        let kin = SlotKinematics::from_duals(
            Dual::constant(f64::NAN, m),
            Dual::constant(0.0, m),
            &vec![Dual::constant(0.0, m); m],
            0.0,
        );
        Ok((local, kin))
    }

    /// The contact point of a kept partner, recomputed at the current state.
    fn reproject(&self, ctx: &Ctx, c: Candidate, xs: [f64; 3], cur: &Current) -> Option<Candidate> {
        match c.partner {
            Partner::Edge(e) => self
                .edge_geometry_f64(e, cur)
                .project([xs[0], xs[1]])
                .map(|s| Candidate { xi: [s, 0.0], ..c }),
            Partner::Face(f) => self
                .face_geometry_f64(f, cur)
                .project(xs)
                .map(|(a, b)| Candidate { xi: [a, b], ..c }),
            Partner::Rigid(seg) => self
                .rigid_reproject(ctx, seg, xs)
                .map(|t| Candidate { xi: [t, 0.0], ..c }),
            _ => Some(c),
        }
    }
}

impl Formulation for NodeToSegment {
    fn n_slots(&self) -> usize {
        self.slots.len()
    }

    fn n_multipliers(&self) -> usize {
        if self.forces_unknown {
            self.slots.len() * self.multipliers_per_node()
        } else {
            0
        }
    }

    fn nodes_needing_dofs(&self) -> Vec<usize> {
        let mut out: Vec<usize> = self.slots.iter().map(|s| s.node).collect();
        out.extend(&self.rigid_nodes);
        out
    }

    fn candidate_nodes(&self, ctx: &Ctx) -> Result<Vec<usize>> {
        // The edges and faces every node could meet now, and the ring around them (sliding,
        // and the nodal normals of large deformation, which average the faces around a node).
        let cur = self.current(ctx)?;
        let mut near = std::collections::BTreeSet::new();
        for slot in &self.slots {
            let (xs, _) = ctx.position(slot.node)?;
            for c in self.candidates(ctx, slot, xs, &cur, None)? {
                let nodes = match c.partner {
                    Partner::Edge(k) => &self.edges.edges[k].nodes,
                    Partner::Face(k) => &self.faces.faces[k].nodes,
                    _ => continue,
                };
                near.extend(nodes.iter().copied());
            }
        }
        let mut out = self.nodes_needing_dofs();
        for &a in &near {
            for &e in self.edges.at_node.get(&a).into_iter().flatten() {
                out.extend(&self.edges.edges[e].nodes);
            }
            for &f in self.faces.at_node.get(&a).into_iter().flatten() {
                out.extend(&self.faces.faces[f].nodes);
            }
        }
        out.extend(near);
        Ok(out)
    }

    fn partner_nodes(&self, partner: Partner) -> &[usize] {
        match partner {
            Partner::Edge(k) => &self.edges.edges[k].nodes,
            Partner::Face(k) => &self.faces.faces[k].nodes,
            _ => &[],
        }
    }

    fn penalties(&self) -> Option<(usize, f64, f64)> {
        crate::contact::formulation::penalty_range(self.number, self.slots.iter().map(|s| s.law))
    }

    fn set_mesh_penalties(&mut self, stiffness: &[f64]) {
        if self.enforcement == Enforcement::Penalty(crate::model::PenaltySource::FromMesh) {
            for s in &mut self.slots {
                s.law = SlotLaw::Penalty(stiffness[s.node]);
            }
        }
    }

    fn symmetric(&self) -> bool {
        // B = ∇g only for the exact closest point on a rigid shape along its own normal.
        self.edges.edges.is_empty() && self.faces.faces.is_empty() && self.normal.is_none()
    }

    fn evaluate(
        &self,
        ctx: &Ctx,
        first_lambda: usize,
        search: Search,
        history: Option<&[SlotState]>,
        points: &mut Vec<SlotLinearization>,
        states: &mut Vec<SlotState>,
    ) -> Result<f64> {
        let start = std::time::Instant::now();
        let cur = self.current(ctx)?;
        let mut chosen = Vec::with_capacity(self.slots.len());
        for (k, slot) in self.slots.iter().enumerate() {
            let (xs, _) = ctx.position(slot.node)?;
            let previous = search.previous(k);
            chosen.push(match previous {
                // With the partner frozen, the contact point is still recomputed (it moves with q).
                Some((p, xi, true)) => (p != Partner::None)
                    .then_some(Candidate {
                        partner: p,
                        xi,
                        gap: 0.0,
                        inside: true,
                    })
                    .and_then(|c| self.reproject(ctx, c, xs, &cur)),
                _ => {
                    let prev = previous.map(|p| p.0);
                    let cands = self.candidates(ctx, slot, xs, &cur, prev)?;
                    let best = search::choose(&cands, prev, self.tie);
                    self.held_inside(ctx, slot, xs, &cur, &cands, best)
                }
            });
        }
        let searching = start.elapsed().as_secs_f64();
        let areas = self.areas.at(|n| Ok(ctx.position(n)?.0))?;
        let first_state = states.len();
        let mut prepared = Vec::with_capacity(self.slots.len());
        for (k, (slot, chosen)) in self.slots.iter().zip(chosen).enumerate() {
            let per = self.multipliers_per_node();
            let lambda_eqs = self
                .forces_unknown
                .then_some(first_lambda + per * k..first_lambda + per * (k + 1));
            // The friction force the iteration holds (its multipliers; see `point_friction`).
            let mut held = [0.0; 3];
            if let (Some(eqs), Some(_)) = (&lambda_eqs, self.friction) {
                held[..self.dim]
                    .copy_from_slice(ctx.nodes.multipliers(eqs.start..eqs.start + self.dim));
            }
            let mut state = SlotState::unpaired(self.number, slot.node, ctx.position(slot.node)?.0);
            let anchor = history
                .and_then(|h| h.get(k))
                .and_then(|s| s.anchor.as_ref());
            let (local, kin) = match chosen {
                Some(c) => {
                    state.partner = c.partner;
                    state.xi = c.xi;
                    let (local, kin, next) = match c.partner {
                        Partner::Edge(e) => {
                            self.edge_kinematics(ctx, slot, e, c.xi[0], (anchor, held))?
                        }
                        Partner::Face(f) => {
                            self.face_kinematics(ctx, slot, f, c.xi, &cur, (anchor, held))?
                        }
                        Partner::Rigid(seg) => {
                            self.rigid_kinematics(ctx, slot, seg, c.xi[0], (anchor, held))?
                        }
                        _ => unreachable!("node-to-segment partners are edges, faces or rigid"),
                    };
                    state.anchor = next;
                    state.gap = kin.gap.v;
                    // What pairing judges (self-contact, or two conditions: two-pass).
                    if slot.own.is_some() || !self.covered.is_empty() {
                        state.bend = self.bend(c, state.x, &cur);
                        state.point = self.contact_point(c, &cur);
                    }
                    state.weight = kin.weight.v;
                    (local, kin)
                }
                None => self.no_partner(ctx, slot)?,
            };
            prepared.push(Prepared {
                lambda_eqs,
                local,
                kin,
                state,
            });
        }
        // Self-contact: pairs that repeat one contact hold it by one constraint (see `pairs`).
        let pairs = self.repeated_pairs(&prepared, &search);
        // Per pair, the share of the merged force on each of its two nodes, and the second
        // node's anchors (it sticks or slides with the first).
        let mut shares = Vec::with_capacity(pairs.len());
        let mut anchors = Vec::with_capacity(pairs.len());
        let mut unheld = HashMap::new();
        for &(i, j) in &pairs {
            let (a, b) = (&prepared[i], &prepared[j]);
            let (ga, gb) = (a.kin.gap.v, b.kin.gap.v);
            for (k, g, other) in [(i, ga, gb), (j, gb, ga)] {
                let spacing = self.slots[k].own.as_ref().map_or(0.0, |o| o.spacing);
                if let Some(depth) = repeated::unheld(g, other, spacing, ctx.laws.gap_tol) {
                    unheld.insert(k, depth);
                }
            }
            let (local, kin) = repeated::merge((&a.local, &a.kin), (&b.local, &b.kin));
            shares.push([
                repeated::share_at(&local, &kin, self.slots[i].node),
                repeated::share_at(&local, &kin, self.slots[j].node),
            ]);
            anchors.push(b.kin.slip.as_ref().map(|s| (s.kept, s.slid)));
            (prepared[i].local, prepared[i].kin) = (local, kin);
            (prepared[j].local, prepared[j].kin) = self.no_partner(ctx, &self.slots[j])?;
            prepared[j].state.repeated = true;
        }
        for (k, (slot, p)) in self.slots.iter().zip(prepared).enumerate() {
            let Prepared {
                lambda_eqs,
                local,
                kin,
                mut state,
            } = p;
            let point = apply_law(
                ctx, slot.law, lambda_eqs, &local, &kin, areas[k], &mut state,
            );
            if !state.active && !state.repeated {
                // Within the gap tolerance of the master the node touches it (the tip of a fold
                // lying on the wall beside it, to round-off).
                state.crossed = (self.inside_body(ctx, slot, state.x, &cur))
                    .filter(|i| i.depth > ctx.laws.gap_tol);
            }
            state.unheld = unheld.get(&k).copied();
            points.push(point);
            states.push(state);
        }
        let mine = &mut states[first_state..];
        for (((i, j), share), anchor) in pairs.into_iter().zip(shares).zip(anchors) {
            let (force, active) = (mine[i].force, mine[i].active);
            for (k, share) in [i, j].into_iter().zip(share) {
                mine[k].force = force * share;
                mine[k].active = active;
                mine[k].area = areas[k];
                mine[k].pressure = mine[k].force / areas[k];
            }
            // The merged friction force acts on both nodes whole.
            mine[j].friction = mine[i].friction;
            match (mine[i].friction, anchor) {
                (Some((true, _)), Some((kept, _))) => mine[j].anchor = Some(kept),
                (Some((false, _)), Some((_, Some(slid)))) => mine[j].anchor = Some(slid),
                _ => {}
            }
        }
        if self.areas.has_curved() {
            let mine = &mut states[first_state..];
            let forces: Vec<f64> = mine.iter().map(|s| s.force).collect();
            let p = self
                .areas
                .pressures(&forces, &areas, |n| Ok(ctx.position(n)?.0))?;
            for (s, p) in mine.iter_mut().zip(p) {
                s.pressure = p;
            }
        }
        Ok(searching)
    }
}

/// The rigid segments among `segments` (model segment indices) and the reference nodes they
/// move with.
fn rigid_segments(model: &Model, segments: &[usize]) -> (Vec<usize>, Vec<usize>) {
    let rigid: Vec<usize> = segments
        .iter()
        .copied()
        .filter(|&g| {
            !matches!(
                model.segments[g].kind,
                SegmentKind::Edges { .. } | SegmentKind::Faces { .. }
            )
        })
        .collect();
    let nodes = rigid
        .iter()
        .filter_map(|&g| match &model.segments[g].kind {
            SegmentKind::Circle { node, .. } | SegmentKind::Plane { node, .. } => *node,
            _ => None,
        })
        .collect();
    (rigid, nodes)
}
