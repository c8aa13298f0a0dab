//! Contact conditions (spec §2) as state-dependent internal forces with exact tangents.
//!
//! A condition is a [`Formulation`]: it says which nodes need DOFs, how many multipliers it adds
//! and which equations its contributions can touch, and evaluates itself at the current state into
//! local contributions (one per contact point) for the assembler. Every formulation has the same
//! inside: [`geometry`] (surfaces, projection, normals), [`search`] (which partner a node meets),
//! kinematics in [`dual`] arithmetic (gap, weight, force direction and their derivatives) and a
//! [`law`] (penalty or multiplier, and Coulomb friction: a return map on penalty points, friction
//! multipliers on node-to-segment multiplier points) that turns them into a residual and
//! tangent. Formulations: [`n2n`] (node-to-node), [`n2s`] (node-to-segment),
//! [`mortar`] (segment-to-segment, 2D edges and 3D faces). The friction history is the anchors
//! of the converged contact states ([`Anchor`]): the solver restores them with the states when
//! it cuts a step.
//!
//! OOFEM defects fixed here (spec §2.10): normals point out of the master body whatever the node
//! order; the gap is measured to the contact point; the tangent is the exact derivative, including
//! the variation of the contact point; the active set is a complementarity rule, not the sign of
//! the gap with frozen multipliers; contact forces are internal forces, never accumulated between
//! steps; prescribed normals are normalized; node numbers are labels; rigid segments have their
//! body on a side fixed by definition.

pub mod dual;
pub mod geometry;
pub mod law;
pub mod mortar;
pub mod n2n;
pub mod n2s;
pub mod point;
pub mod search;
pub mod tributary;

use crate::assembly::{DofMap, ExtraDofs};
use crate::error::{Error, Result};
use crate::model::{ContactLaw, Model, Pairing, SegmentKind};
use dual::{DVec, Dual};
use law::Laws;
pub use point::{ContactPoint, PointLaw};

/// What a contact node is paired with at the current state (the contact point itself is
/// recomputed at every evaluation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Partner {
    None,
    /// A fixed master node (node-to-node).
    Node(usize),
    /// An edge of the condition's master surface (index into its edges).
    Edge(usize),
    /// A face of the condition's master surface (index into its faces).
    Face(usize),
    /// A rigid segment (model segment index).
    Rigid(usize),
}

/// Contact state of one contact node after an evaluation.
#[derive(Debug, Clone)]
pub struct SlotState {
    /// BC record number of the condition.
    pub condition: usize,
    pub node: usize,
    pub partner: Partner,
    /// Contact point parameters on the partner (edge s ∈ [0, 1], face (ξ, η), polynomial
    /// abscissa; unused ones 0).
    pub xi: [f64; 2],
    /// Signed gap (NaN without a partner).
    pub gap: f64,
    /// Normal contact force on the node (≥ 0 in compression).
    pub force: f64,
    pub pressure: f64,
    pub active: bool,
    /// Current node position.
    pub x: [f64; 3],
    /// Boundary weight of the contact point (1 on its partner, less past an open end or edge).
    pub weight: f64,
    /// Its constraint repeats one of another condition (two-pass contact with multipliers) and
    /// is dropped.
    pub repeated: bool,
    /// Friction of a closed point: stick (else slip) and the friction force's magnitude.
    pub friction: Option<(bool, f64)>,
    /// Friction history this state leaves if it is the converged one: the anchor for the next
    /// step (None: no partner, or no friction).
    pub anchor: Option<Anchor>,
}

impl SlotState {
    /// The state of condition `condition`'s contact node `node` at `x` before its evaluation:
    /// no partner, no force.
    pub fn unpaired(condition: usize, node: usize, x: [f64; 3]) -> SlotState {
        SlotState {
            condition,
            node,
            partner: Partner::None,
            xi: [f64::NAN; 2],
            gap: f64::NAN,
            force: 0.0,
            pressure: 0.0,
            active: false,
            x,
            weight: 1.0,
            repeated: false,
            friction: None,
            anchor: None,
        }
    }
}

/// The master's material point a frictional contact node sticks to (the friction history).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anchor {
    /// The partner the point belongs to (an edge, or a rigid segment).
    pub partner: Partner,
    /// Its parameter on an edge.
    pub xi: [f64; 2],
    /// Its position relative to a rigid segment's origin (which moves with the segment's node).
    pub offset: [f64; 3],
}

/// How partners are found in an evaluation.
#[derive(Debug, Clone, Copy)]
pub enum Search<'a> {
    /// Search every node.
    Fresh,
    /// Search, but keep a node's previous partner while it remains valid (hysteresis: a node on a
    /// vertex does not alternate between the two edges).
    Hint(&'a [SlotState]),
    /// Keep the given partners (the finite-difference tests: the tangent is the derivative of the
    /// residual at fixed partners, with the contact point still moving).
    Frozen(&'a [SlotState]),
}

impl<'a> Search<'a> {
    /// The same search restricted to one formulation's states.
    fn slice(&self, range: std::ops::Range<usize>) -> Search<'a> {
        match *self {
            Search::Fresh => Search::Fresh,
            Search::Hint(s) => Search::Hint(&s[range]),
            Search::Frozen(s) => Search::Frozen(&s[range]),
        }
    }

    /// Previous partner and parameter of slot k, and whether it must be kept.
    pub fn previous(&self, k: usize) -> Option<(Partner, [f64; 2], bool)> {
        match self {
            Search::Fresh => None,
            Search::Hint(s) => s.get(k).map(|s| (s.partner, s.xi, false)),
            Search::Frozen(s) => s.get(k).map(|s| (s.partner, s.xi, true)),
        }
    }
}

/// The state a formulation is evaluated at.
pub struct Ctx<'a> {
    pub model: &'a Model,
    pub dofs: &'a DofMap,
    pub u: &'a [f64],
    pub dim: usize,
    pub laws: &'a Laws,
    /// The primary state of the last converged step (the friction history's), if given.
    pub start: Option<&'a [f64]>,
}

/// The friction history: the contact states of the last converged step and its primary state.
#[derive(Debug, Clone, Copy)]
pub struct History<'a> {
    pub states: &'a [SlotState],
    pub u: &'a [f64],
}

impl Ctx<'_> {
    /// A node's position at the last converged step (its reference position without one).
    pub fn start_position(&self, n: usize) -> [f64; 3] {
        let mut x = self.model.nodes[n].coords;
        if let Some(u) = self.start {
            for (d, xd) in x.iter_mut().enumerate().take(self.dim) {
                if let Some(code) = self.dofs.code(n, d as u8 + 1) {
                    *xd += self.dofs.value(u, code);
                }
            }
        }
        x
    }

    /// Current position of a node and the location codes of its displacement DOFs.
    pub fn position(&self, n: usize) -> Result<([f64; 3], [usize; 3])> {
        let mut x = self.model.nodes[n].coords;
        let mut codes = [0; 3];
        for d in 0..self.dim {
            let code = self.dofs.code(n, d as u8 + 1).ok_or_else(|| {
                Error::Solve(format!(
                    "contact node {} has no DOF {}",
                    self.model.nodes[n].label,
                    d + 1
                ))
            })?;
            x[d] += self.dofs.value(self.u, code);
            codes[d] = code;
        }
        Ok((x, codes))
    }
}

/// The local unknowns of one contact point: the positions of its nodes.
pub struct Local {
    pub nodes: Vec<usize>,
    pub codes: Vec<usize>,
    vals: Vec<f64>,
    dim: usize,
}

impl Local {
    pub fn new(dim: usize) -> Local {
        Local {
            nodes: Vec::new(),
            codes: Vec::new(),
            vals: Vec::new(),
            dim,
        }
    }

    /// Add a node (once); returns its local index.
    pub fn add(&mut self, ctx: &Ctx, n: usize) -> Result<usize> {
        if let Some(k) = self.nodes.iter().position(|&m| m == n) {
            return Ok(k);
        }
        let (x, codes) = ctx.position(n)?;
        self.nodes.push(n);
        self.codes.extend_from_slice(&codes[..self.dim]);
        self.vals.extend_from_slice(&x[..self.dim]);
        Ok(self.nodes.len() - 1)
    }

    pub fn index(&self, n: usize) -> usize {
        self.nodes
            .iter()
            .position(|&m| m == n)
            .expect("node added to the local unknowns")
    }

    /// Current positions of the local nodes, node after node.
    pub fn values(&self) -> &[f64] {
        &self.vals
    }

    /// Number of local displacement unknowns.
    pub fn m(&self) -> usize {
        self.vals.len()
    }

    /// The node positions as dual vectors (each coordinate an unknown).
    pub fn seed(&self) -> Vec<DVec> {
        let m = self.m();
        assert!(m <= dual::MAXV, "contact pair with {m} unknowns");
        let q = dual::seed(&self.vals, m);
        (0..self.nodes.len())
            .map(|k| {
                let mut v = [Dual::constant(0.0, m); 3];
                v[..self.dim].copy_from_slice(&q[k * self.dim..(k + 1) * self.dim]);
                v
            })
            .collect()
    }

    /// B = Σ_k c_k n placed at node k's unknowns, for coefficients per local node.
    pub fn distribute(&self, coeffs: &[(usize, Dual)], n: &DVec) -> Vec<Dual> {
        let m = self.m();
        let mut b = vec![Dual::constant(0.0, m); m];
        for &(k, c) in coeffs {
            for i in 0..self.dim {
                b[k * self.dim + i] = b[k * self.dim + i] + c * n[i];
            }
        }
        b
    }

    /// [`Local::distribute`] as jets over the local unknowns.
    pub fn distribute_jets(&self, coeffs: &[(usize, Dual)], n: &DVec) -> Vec<dual::Jet> {
        self.distribute(coeffs, n)
            .into_iter()
            .map(dual::Jet::from)
            .collect()
    }
}

/// A contact formulation (one condition of the input).
pub trait Formulation {
    /// Number of contact points (slots): one per contact node.
    fn n_slots(&self) -> usize;
    /// Lagrange multipliers it adds (numbered after all displacement equations).
    fn n_multipliers(&self) -> usize;
    /// Nodes that must carry displacement DOFs even without elements.
    fn nodes_needing_dofs(&self) -> Vec<usize>;
    /// The nodes whose DOFs its contributions can touch from the state `ctx` on, as far as
    /// the geometry tells (the contact nodes, and the master nodes near them).
    fn candidate_nodes(&self, ctx: &Ctx) -> Result<Vec<usize>>;
    /// Whether its tangent is symmetric (B = ∇g at every contact point).
    fn symmetric(&self) -> bool;
    /// The master nodes of a partner (an edge's or a face's nodes; none for others).
    fn partner_nodes(&self, _partner: Partner) -> &[usize] {
        &[]
    }
    /// Evaluate every slot at `ctx`; `first_lambda` is the equation of its first multiplier,
    /// `history` the converged states of the last step (the friction history), if any.
    /// Returns the seconds spent searching partners.
    fn evaluate(
        &self,
        ctx: &Ctx,
        first_lambda: usize,
        search: Search,
        history: Option<&[SlotState]>,
        points: &mut Vec<ContactPoint>,
        states: &mut Vec<SlotState>,
    ) -> Result<f64>;
}

/// All contact conditions of a model.
pub struct ContactSystem {
    formulations: Vec<Box<dyn Formulation + Send + Sync>>,
    laws: Laws,
    dim: usize,
    /// Seconds spent in evaluations since the last [`ContactSystem::take_times`]: (searching,
    /// in all).
    clock: std::sync::Mutex<(f64, f64)>,
    /// Some condition has friction.
    frictional: bool,
}

impl ContactSystem {
    /// The model's contact conditions, checked (a node paired with itself is an input error).
    pub fn new(model: &Model) -> Result<ContactSystem> {
        let mut formulations: Vec<Box<dyn Formulation + Send + Sync>> = Vec::new();
        for (ci, c) in model.contacts.iter().enumerate() {
            match &c.pairing {
                Pairing::NodeToNode { .. } => {
                    formulations.push(Box::new(n2n::NodeToNode::new(model, ci)?))
                }
                Pairing::NodeToSegment { .. } => {
                    formulations.push(Box::new(n2s::NodeToSegment::new(model, ci)?))
                }
                Pairing::Mortar { .. } => formulations.push(mortar::new(model, ci)?),
            }
        }
        let young = model
            .materials
            .iter()
            .map(|m| m.young())
            .fold(0.0f64, f64::max)
            .max(1e-30);
        Ok(ContactSystem {
            formulations,
            laws: Laws {
                c: young,
                gap_tol: 1e-12 * model_size(model),
                pressure_limit: young,
            },
            dim: model.domain.nsd(),
            clock: Default::default(),
            frictional: model.contacts.iter().any(|c| c.friction.is_some()),
        })
    }

    /// Seconds spent (searching partners, evaluating in all) since the last call.
    pub fn take_times(&self) -> (f64, f64) {
        std::mem::take(&mut *self.clock.lock().expect("clock"))
    }

    pub fn is_empty(&self) -> bool {
        self.formulations.is_empty()
    }

    /// Number of contact points (one per contact node of every condition).
    pub fn n_slots(&self) -> usize {
        self.formulations.iter().map(|f| f.n_slots()).sum()
    }

    pub fn n_multipliers(&self) -> usize {
        self.formulations.iter().map(|f| f.n_multipliers()).sum()
    }

    /// Whether every contact tangent is symmetric: friction's is not where a point slides (its
    /// force follows the slip, its size the normal force), whatever the formulation's normal
    /// part. (Taken as symmetric before, a node sliding on a rigid shape had its slip tangent
    /// cut to one triangle.)
    pub fn symmetric(&self) -> bool {
        !self.frictional && self.formulations.iter().all(|f| f.symmetric())
    }

    /// What the DOF numbering must provide for the contact conditions.
    pub fn extra_dofs(&self) -> ExtraDofs {
        ExtraDofs {
            nodes: self
                .formulations
                .iter()
                .flat_map(|f| f.nodes_needing_dofs())
                .collect(),
            n_multipliers: self.n_multipliers(),
        }
    }

    /// Free equations that contact contributions can touch from the state `u` on (through
    /// slave-node weights), sorted; the multipliers are not among them.
    pub fn candidate_equations(
        &self,
        model: &Model,
        dofs: &DofMap,
        u: &[f64],
    ) -> Result<Vec<usize>> {
        let ctx = Ctx {
            model,
            dofs,
            u,
            dim: self.dim,
            laws: &self.laws,
            start: None,
        };
        let mut nodes = Vec::new();
        for f in &self.formulations {
            nodes.extend(f.candidate_nodes(&ctx)?);
        }
        let mut eqs: Vec<usize> = nodes
            .into_iter()
            .flat_map(|n| {
                dofs.node_dofs[n]
                    .iter()
                    .flat_map(|&(_, c)| dofs.entries(c).map(|(p, _)| p))
            })
            .filter(|&p| p < dofs.n_free - dofs.n_lambda)
            .collect();
        eqs.sort_unstable();
        eqs.dedup();
        Ok(eqs)
    }

    /// Set the contact pressure above which the geometric tangent part is dropped (see
    /// [`Laws::geometric_allowed`]); `f64::INFINITY` always assembles the exact tangent.
    pub fn set_pressure_limit(&mut self, limit: f64) {
        self.laws.pressure_limit = limit;
    }

    /// Whether any condition has friction (whose history the solver must keep).
    pub fn has_friction(&self) -> bool {
        self.frictional
    }

    /// Evaluate every contact point at the primary state `u` without friction history: the
    /// points (whose [`contribution`](ContactPoint::contribution) is the current residual and
    /// tangent) and their states.
    pub fn evaluate(
        &self,
        model: &Model,
        dofs: &DofMap,
        u: &[f64],
        search: Search,
    ) -> Result<(Vec<ContactPoint>, Vec<SlotState>)> {
        self.evaluate_with_history(model, dofs, u, search, None)
    }

    /// [`ContactSystem::evaluate`] with the friction history: the converged states of the last
    /// step (their anchors) and its primary state.
    pub fn evaluate_with_history(
        &self,
        model: &Model,
        dofs: &DofMap,
        u: &[f64],
        search: Search,
        history: Option<History>,
    ) -> Result<(Vec<ContactPoint>, Vec<SlotState>)> {
        let ctx = Ctx {
            model,
            dofs,
            u,
            dim: self.dim,
            laws: &self.laws,
            start: history.map(|h| h.u),
        };
        let history = history.map(|h| h.states);
        let start = std::time::Instant::now();
        let mut points = Vec::new();
        let mut states = Vec::new();
        let mut lambda = dofs.n_free - dofs.n_lambda;
        let mut slot = 0;
        let mut searching = 0.0;
        for f in &self.formulations {
            let n = f.n_slots();
            searching += f.evaluate(
                &ctx,
                lambda,
                search.slice(slot..slot + n),
                history.map(|h| &h[slot..slot + n]),
                &mut points,
                &mut states,
            )?;
            lambda += f.n_multipliers();
            slot += n;
        }
        let previous = match search {
            Search::Fresh => None,
            Search::Hint(s) | Search::Frozen(s) => Some(s),
        };
        self.drop_repeated_constraints(&mut points, &mut states, previous);
        let mut clock = self.clock.lock().expect("clock");
        clock.0 += searching;
        clock.1 += start.elapsed().as_secs_f64();
        Ok((points, states))
    }
}

impl ContactSystem {
    /// Two-pass contact: where a node a of one condition meets the other surface at (nearly) the
    /// place of a node b of it, and b meets a's surface near a, both constraints hold the same
    /// motion. Multipliers cannot share it (the constraints are dependent or nearly so, and
    /// Newton's active set chatters between them); a penalty would double its stiffness there,
    /// and in the limit of a large penalty over-constrain the surfaces as the multipliers would.
    /// So one of the two is dropped, for both laws alike (the penalty answer then tends to the
    /// multipliers' one): it exerts no force (its multiplier is held at zero), and its node
    /// penetrates the other surface by at most a second-order amount. "Nearly": a is closer to b than a quarter of the distance
    /// from b to its nearest neighbour on its surface (a third, if the pair was one at the
    /// previous state: a band, so that a pair at the limit does not alternate). The one dropped
    /// is the one past an open end of its partner (a node beside a corner, whose constraint is
    /// the extension of the surface) when the other lies on its partner (the corner on the
    /// surface); else the one of the condition listed later, or the one dropped before. Pairs
    /// are formed closest first, each node in one pair at most.
    fn drop_repeated_constraints(
        &self,
        points: &mut [ContactPoint],
        states: &mut [SlotState],
        previous: Option<&[SlotState]>,
    ) {
        // The formulation of every slot.
        let mut owner: Vec<usize> = Vec::with_capacity(states.len());
        for (f, form) in self.formulations.iter().enumerate() {
            owner.extend(std::iter::repeat_n(f, form.n_slots()));
        }
        let mut by_node: std::collections::HashMap<usize, Vec<usize>> = Default::default();
        for (k, s) in states.iter().enumerate() {
            if s.partner != Partner::None && points[k].can_close() {
                by_node.entry(s.node).or_default().push(k);
            }
        }
        if by_node.len() < 2 {
            return;
        }
        let position: std::collections::HashMap<usize, [f64; 3]> =
            states.iter().map(|s| (s.node, s.x)).collect();
        let dist = |a: &[f64; 3], b: &[f64; 3]| {
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
        };
        let was_repeated = |k: usize| previous.and_then(|p| p.get(k)).is_some_and(|p| p.repeated);
        // Candidate pairs (distance, i, j), i of the earlier condition.
        let mut pairs = Vec::new();
        for (i, &fi) in owner.iter().enumerate() {
            if states[i].partner == Partner::None || !points[i].can_close() {
                continue;
            }
            let partner = self.formulations[fi].partner_nodes(states[i].partner);
            for &b in partner {
                for &j in by_node.get(&b).into_iter().flatten() {
                    let fj = owner[j];
                    let back = self.formulations[fj].partner_nodes(states[j].partner);
                    if fj <= fi || !back.contains(&states[i].node) {
                        continue;
                    }
                    // b's nearest neighbour on its own surface (a's partner nodes other than b,
                    // wherever they are: with or without a partner of their own).
                    let xb = states[j].x;
                    let spacing = partner
                        .iter()
                        .filter(|&&n| n != b)
                        .filter_map(|&n| position.get(&n))
                        .map(|x| dist(x, &xb))
                        .fold(f64::INFINITY, f64::min);
                    if !spacing.is_finite() {
                        continue;
                    }
                    let before = was_repeated(i) || was_repeated(j);
                    let limit = if before { 1.0 / 3.0 } else { 0.25 };
                    let d = dist(&states[i].x, &xb);
                    if d < limit * spacing {
                        pairs.push((d, i, j));
                    }
                }
            }
        }
        pairs.sort_by(|p, q| p.0.total_cmp(&q.0));
        let mut used = vec![false; states.len()];
        for (_, i, j) in pairs {
            if used[i] || used[j] {
                continue;
            }
            used[i] = true;
            used[j] = true;
            let beside = |k: usize| states[k].weight < 1.0;
            let drop = if was_repeated(i) && !was_repeated(j) {
                i
            } else if was_repeated(j) && !was_repeated(i) {
                j
            } else if beside(i) && !beside(j) {
                i
            } else {
                j
            };
            points[drop].disable();
            let s = &mut states[drop];
            s.active = false;
            s.force = 0.0;
            s.pressure = 0.0;
            s.repeated = true;
            s.friction = None;
        }
    }
}

/// Warnings about the initial configuration, from the contact states at u = 0: nodes that start
/// inside a rigid segment's body (they are pushed out: a rigid segment's side is fixed by its
/// definition, not by where a node starts, as it is in OOFEM).
pub fn initial_warnings(model: &Model, states: &[SlotState]) -> Vec<String> {
    use std::collections::BTreeMap;
    let tol = 1e-9 * model_size(model);
    let mut inside: BTreeMap<(usize, usize), (usize, f64)> = BTreeMap::new();
    for s in states {
        if let Partner::Rigid(g) = s.partner {
            // The node's own distance to the shape, not the state's gap: a mortar slot's is a
            // weighted mean over its faces, which the dual basis can make negative where a
            // convex tool first touches the surface without any node inside it.
            let gap = rigid_distance(model, g, s.x).unwrap_or(s.gap);
            if gap < -tol {
                let e = inside.entry((s.condition, g)).or_insert((0, 0.0));
                e.0 += 1;
                e.1 = e.1.max(-gap);
            }
        }
    }
    let mut out: Vec<String> = deep_starts(model, states);
    out.extend(inside
        .into_iter()
        .map(|((cond, g), (n, depth))| {
            let seg = &model.segments[g];
            let hint = match seg.kind {
                SegmentKind::Circle { cavity: false, .. } => " (if they belong inside the circle, add `cavity`)",
                SegmentKind::Polynomial { body_above: false, .. } => " (if the body is above the curve, add `bodyabove`)",
                SegmentKind::Plane { .. } => " (the plane's normal points out of the rigid body)",
                _ => "",
            };
            format!(
                "{n} node(s) of contact condition {cond} start inside rigid segment {} (by up to {depth:.3e}) and will be pushed out{hint}",
                seg.number
            )
        }));
    out
}

/// Warnings for contact nodes that start inside a deformable master by more than half the size
/// of their own elements: not a faceting overlap of curved surfaces but bodies placed into each
/// other, which the first step pushes apart with forces far above the load's.
fn deep_starts(model: &Model, states: &[SlotState]) -> Vec<String> {
    use std::collections::BTreeMap;
    let deep: Vec<&SlotState> = states
        .iter()
        .filter(|s| matches!(s.partner, Partner::Edge(_) | Partner::Face(_)) && s.gap < 0.0)
        .collect();
    if deep.is_empty() {
        return Vec::new();
    }
    // Each node's shortest distance to a node of its own elements.
    let mut size: std::collections::HashMap<usize, f64> =
        deep.iter().map(|s| (s.node, f64::INFINITY)).collect();
    for el in &model.elements {
        for &n in &el.nodes {
            let Some(h) = size.get(&n).copied() else {
                continue;
            };
            let x = model.nodes[n].coords;
            let near = el
                .nodes
                .iter()
                .filter(|&&m| m != n)
                .map(|&m| {
                    let y = model.nodes[m].coords;
                    (0..3).map(|i| (y[i] - x[i]).powi(2)).sum::<f64>().sqrt()
                })
                .fold(h, f64::min);
            size.insert(n, near);
        }
    }
    // condition -> (count, depth, node of the deepest)
    let mut found: BTreeMap<usize, (usize, f64, usize)> = BTreeMap::new();
    for s in deep {
        let h = size[&s.node];
        if h.is_finite() && -s.gap > 0.5 * h {
            let e = found.entry(s.condition).or_insert((0, 0.0, s.node));
            e.0 += 1;
            if -s.gap > e.1 {
                (e.1, e.2) = (-s.gap, s.node);
            }
        }
    }
    found
        .into_iter()
        .map(|(cond, (n, depth, node))| {
            format!(
                "{n} node(s) of contact condition {cond} start inside their master surface by more \
                 than half their elements' size, up to {depth:.3e} (node {}): the first step pushes \
                 the bodies apart with forces far above the load's; move them apart (or check the \
                 mesh and which side is the master)",
                model.nodes[node].label
            )
        })
        .collect()
}

/// The signed distance of the point `x` to rigid segment `g` in its reference position (< 0:
/// inside its body), if `x` projects onto it.
fn rigid_distance(model: &Model, g: usize, x: [f64; 3]) -> Option<f64> {
    use geometry::rigid;
    let dim = model.domain.nsd();
    let x = &x[..dim];
    Some(match &model.segments[g].kind {
        SegmentKind::Circle {
            center,
            radius,
            cavity,
            ..
        } => rigid::circle(x, &center[..dim], *radius, *cavity).0,
        SegmentKind::Plane { point, normal, .. } => {
            rigid::plane(x, &point[..dim], &normal[..dim]).0
        }
        SegmentKind::Polynomial { coeffs, body_above } => {
            let t = rigid::project_on_poly(coeffs, [x[0], x[1]])?;
            rigid::polynomial(coeffs, x, t, *body_above).0
        }
        _ => return None,
    })
}

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

/// The modulus of friction's c_T at a slave node of modulus `slave` against a master of modulus
/// `master`: the two in series, E_s E_m / (E_s + E_m), as the tangential compliance of the
/// contact is the sum of the two bodies'. With the slave's alone, c_T of a stiff slave on a
/// soft master (the shallow ironing's die, ten times the block's E) is ten times the contact's
/// stiffness, and the stick/slip iteration cycled at nodes on the stick–slip boundary.
pub fn friction_modulus(slave: f64, master: f64) -> f64 {
    if master.is_infinite() || !(master > 0.0) {
        slave
    } else {
        slave * master / (slave + master)
    }
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

/// The area a contact node stands for in the laws: its tributary area, or for a node on no
/// contact surface (an isolated node) that of a tenth of the model's size.
pub fn law_area(tributary: f64, model: &Model) -> f64 {
    if tributary > 0.0 {
        tributary
    } else {
        (0.1 * model_size(model)).powi(model.domain.nsd() as i32 - 1)
    }
}

/// Apply a condition's law to the kinematics of one contact point and complete its state.
/// `lambda_eqs`: the equations of the point's multipliers (the friction force's components, if
/// any, then the normal force).
pub fn apply_law(
    ctx: &Ctx,
    law: ContactLaw,
    lambda_eqs: Option<std::ops::Range<usize>>,
    local: &Local,
    kin: &law::PointKinematics,
    area: f64,
    state: &mut SlotState,
) -> ContactPoint {
    let codes = local.codes.clone();
    let multipliers = law == ContactLaw::Multiplier;
    let (point, penalty) = match (law, lambda_eqs) {
        (ContactLaw::Penalty(p), None) => (law::penalty::evaluate(ctx.laws, p, codes, kin), p),
        (law, Some(eqs)) => {
            // A penalty with its forces as unknowns: its compliance 1/ε.
            let compliance = match law {
                ContactLaw::Penalty(p) => 1.0 / p,
                ContactLaw::Multiplier => 0.0,
            };
            let lambdas = &ctx.u[eqs.clone()];
            let (point, friction) =
                law::multiplier::evaluate(ctx.laws, lambdas, codes, eqs, kin, compliance);
            if let Some(s) = &kin.slip {
                state.friction = friction;
                // A sticking node keeps its anchor; a sliding one leaves it behind by its
                // elastic slip (none without a penalty: where it is now, as an open one, the
                // state's anchor from the kinematics).
                match friction {
                    Some((true, _)) => state.anchor = Some(s.kept),
                    Some((false, _)) if s.slid.is_some() => state.anchor = s.slid,
                    _ => {}
                }
            }
            (point, 0.0)
        }
        (ContactLaw::Multiplier, None) => unreachable!("multiplier points have equations"),
    };
    state.force = law::normal_force(&point, kin, penalty);
    state.active = point.closed && (multipliers || kin.gap.v < 0.0);
    state.pressure = if area > 0.0 {
        state.force / area
    } else {
        f64::NAN
    };
    point
}
