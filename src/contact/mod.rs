//! Contact conditions (spec §2) as state-dependent internal forces with exact tangents.
//!
//! Every contact node ("slot") is evaluated at the current iterate: the search finds its partner
//! (the fixed master node, or the closest segment it projects onto across all segments of its
//! condition), [`kinematics`] gives the gap g(q) with exact derivatives, and the law turns it into
//! a local residual and tangent:
//! * penalty: r = p·g·∇g and K = p·(∇g∇gᵀ + g·∇²g) for g < 0 (potential ½·p·⟨−g⟩²);
//! * multipliers (λ > 0 in compression): active when λ − c·g > 0, then r_u = −λ∇g, r_λ = −g,
//!   K_uu = −λ∇²g, K_uλ = K_λuᵀ = −∇g; inactive: r_λ = λ, K_λλ = 1 (so λ = 0).
//!
//! OOFEM defects fixed here (spec §2.10): normals point out of the master body whatever the node
//! order; the gap is measured to the projected point; the tangent is the exact derivative; the
//! active set is a complementarity rule, not the sign of the gap with frozen multipliers;
//! contact forces are internal forces, never accumulated between steps; prescribed normals are
//! normalized; node numbers are labels.

pub mod jet;
pub mod kinematics;

use crate::assembly::{Contribution, DofMap, ExtraDofs};
use crate::error::{Error, Result};
use crate::model::{ContactLaw, Model, Pairing, SegmentKind};
use jet::{Jet, MAXV};
use kinematics as kin;

/// Tolerance on the segment parameter for "projects onto the segment".
const INSIDE_TOL: f64 = 1e-9;

/// What a slot is paired with at the current state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Partner {
    None,
    Node(usize),
    /// (segment, edge index within the segment, parameter of the projection)
    Edge(usize, usize, f64),
    Rigid(usize, f64),
}

/// One contact node of one condition.
#[derive(Debug, Clone)]
struct Slot {
    cond: usize,
    node: usize,
    /// N2N: the master node and the fixed normal.
    master: Option<(usize, [f64; 3])>,
    /// Multiplier equation (free-equation index), for Lagrange multipliers.
    lambda_eq: Option<usize>,
    /// Per segment of the condition: side factor ±1 (rigid) from the initial configuration.
    sides: Vec<f64>,
    /// Tributary length (2D, times thickness) or area (3D) for the pressure.
    area: f64,
}

/// Contact state of a slot after an evaluation.
#[derive(Debug, Clone)]
pub struct SlotState {
    pub condition: usize,
    pub node: usize,
    pub partner: Partner,
    pub gap: f64,
    /// Normal contact force on the node (≥ 0 in compression).
    pub force: f64,
    pub pressure: f64,
    pub active: bool,
    /// Current node position.
    pub x: [f64; 3],
}

/// All contact conditions of a model.
pub struct ContactSystem {
    slots: Vec<Slot>,
    nsd: usize,
    /// Outward orientation factor of every edge of every edge segment.
    edge_sides: Vec<Vec<f64>>,
    /// Constant of the active-set rule λ − c·g > 0 (stiffness scale).
    c: f64,
    /// Bound of the curvature safeguard (force · ‖∇²g‖).
    curvature_limit: f64,
    pub n_lambda: usize,
}

impl ContactSystem {
    /// What the DOF numbering must provide for the model's contact conditions.
    pub fn extra_dofs(model: &Model) -> ExtraDofs {
        ExtraDofs {
            nodes: Self::nodes_needing_dofs(model),
            n_multipliers: Self::count_multipliers(model),
        }
    }

    /// Number of multiplier unknowns the model's conditions need (before DOF numbering).
    pub fn count_multipliers(model: &Model) -> usize {
        model
            .contacts
            .iter()
            .filter(|c| c.law == ContactLaw::Multiplier)
            .map(|c| match &c.pairing {
                Pairing::NodeToNode { pairs } => pairs.len(),
                Pairing::NodeToSegment { nodes, .. } => nodes.len(),
            })
            .sum()
    }

    /// Nodes that must carry displacement DOFs for contact (slaves, masters, segment nodes).
    pub fn nodes_needing_dofs(model: &Model) -> Vec<usize> {
        let mut out = Vec::new();
        for c in &model.contacts {
            match &c.pairing {
                Pairing::NodeToNode { pairs } => {
                    out.extend(pairs.iter().flat_map(|&(a, b)| [a, b]))
                }
                Pairing::NodeToSegment { nodes, .. } => out.extend(nodes),
            }
        }
        for s in &model.segments {
            match &s.kind {
                SegmentKind::Circle { node: Some(n), .. }
                | SegmentKind::Plane { node: Some(n), .. } => out.push(*n),
                _ => {}
            }
        }
        out
    }

    /// Every node whose DOFs a contact contribution can touch: contact nodes, masters, the nodes of
    /// all edge segments and the reference nodes of rigid segments.
    pub fn candidate_nodes(model: &Model) -> Vec<usize> {
        let mut out = Self::nodes_needing_dofs(model);
        for s in &model.segments {
            if let SegmentKind::Edges { edges } = &s.kind {
                for &(e, b) in edges {
                    let el = &model.elements[e];
                    out.extend(
                        el.etype.shape().boundaries()[b - 1]
                            .iter()
                            .map(|&a| el.nodes[a]),
                    );
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Free equations of the candidate nodes (through slave-node weights), sorted.
    pub fn candidate_equations(model: &Model, dofs: &DofMap) -> Vec<usize> {
        let mut eqs: Vec<usize> = Self::candidate_nodes(model)
            .into_iter()
            .flat_map(|n| {
                dofs.node_dofs[n]
                    .iter()
                    .flat_map(|&(_, c)| dofs.entries(c).map(|(p, _)| p))
            })
            .filter(|&p| p < dofs.n_free)
            .collect();
        eqs.sort_unstable();
        eqs.dedup();
        eqs
    }

    /// Build the slots; `first_lambda` is the free-equation index of the first multiplier.
    pub fn new(model: &Model, first_lambda: usize) -> Result<ContactSystem> {
        let nsd = model.domain.nsd();
        let mut slots = Vec::new();
        let mut next_lambda = first_lambda;
        let edge_sides: Vec<Vec<f64>> = model
            .segments
            .iter()
            .map(|s| match &s.kind {
                SegmentKind::Edges { edges } => edges
                    .iter()
                    .map(|&(e, b)| edge_outward_side(model, e, b))
                    .collect(),
                _ => Vec::new(),
            })
            .collect();
        for (ci, c) in model.contacts.iter().enumerate() {
            let mut lambda = || {
                (c.law == ContactLaw::Multiplier).then(|| {
                    next_lambda += 1;
                    next_lambda - 1
                })
            };
            match &c.pairing {
                Pairing::NodeToNode { pairs } => {
                    for &(m, s) in pairs {
                        let xm = model.nodes[m].coords;
                        let xs = model.nodes[s].coords;
                        let n = match c.normal {
                            Some(n) => n,
                            None => {
                                let d = [xs[0] - xm[0], xs[1] - xm[1], xs[2] - xm[2]];
                                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                                if len < 1e-8 {
                                    return Err(Error::Input {
                                        span: c.span.clone(),
                                        msg: format!(
                                            "nodes {} and {} are too close to define a contact normal; give `normal`",
                                            model.nodes[m].label, model.nodes[s].label
                                        ),
                                    });
                                }
                                [d[0] / len, d[1] / len, d[2] / len]
                            }
                        };
                        slots.push(Slot {
                            cond: ci,
                            node: s,
                            master: Some((m, n)),
                            lambda_eq: lambda(),
                            sides: vec![],
                            area: 0.0,
                        });
                    }
                }
                Pairing::NodeToSegment { nodes, segments } => {
                    for &s in nodes {
                        let x = model.nodes[s].coords;
                        let sides = segments
                            .iter()
                            .map(|&g| rigid_initial_side(model, g, &x[..nsd]))
                            .collect();
                        slots.push(Slot {
                            cond: ci,
                            node: s,
                            master: None,
                            lambda_eq: lambda(),
                            sides,
                            area: 0.0,
                        });
                    }
                }
            }
        }
        let areas = tributary_areas(model, &slots);
        for (s, a) in slots.iter_mut().zip(areas) {
            s.area = a;
        }
        let c = model
            .materials
            .iter()
            .map(|m| m.young)
            .fold(0.0f64, f64::max)
            .max(1e-30);
        Ok(ContactSystem {
            slots,
            nsd,
            edge_sides,
            c,
            curvature_limit: 0.1 * c,
            n_lambda: next_lambda - first_lambda,
        })
    }

    pub fn is_empty(&self) -> bool {
        self.slots.is_empty()
    }

    /// Set the bound of the curvature safeguard (see [`curvature_allowed`](Self::curvature_allowed));
    /// `f64::INFINITY` always uses the exact tangent.
    pub fn set_curvature_limit(&mut self, limit: f64) {
        self.curvature_limit = limit;
    }

    /// Whether the curvature part of a node's tangent (force · ∇²g) is assembled. It is part of
    /// the exact tangent, but far from the solution — a node deep inside a curved master — it is a
    /// large negative stiffness that makes the tangent indefinite and the Newton step useless. It
    /// is kept while force·‖∇²g‖ stays below a tenth of the stiffest material's modulus, which
    /// always holds near convergence (force = p|g| with |g| small), so the tangent is exact where
    /// quadratic convergence matters.
    fn curvature_allowed(&self, force: f64, g: &Jet) -> bool {
        let mut h2 = 0.0;
        for i in 0..g.n {
            for j in 0..g.n {
                h2 += g.h[i][j] * g.h[i][j];
            }
        }
        force * h2.sqrt() <= self.curvature_limit
    }

    /// Evaluate every slot at the primary state `u`: local contributions and states.
    pub fn evaluate(
        &self,
        model: &Model,
        dofs: &DofMap,
        u: &[f64],
    ) -> Result<(Vec<Contribution>, Vec<SlotState>)> {
        self.evaluate_with(model, dofs, u, None)
    }

    /// As [`evaluate`](Self::evaluate), with the partners (search results, including the contact
    /// point) taken from `frozen` instead of searched: the tangent is the exact derivative of the
    /// residual at fixed search results, which is what the finite-difference tests check.
    pub fn evaluate_with(
        &self,
        model: &Model,
        dofs: &DofMap,
        u: &[f64],
        frozen: Option<&[SlotState]>,
    ) -> Result<(Vec<Contribution>, Vec<SlotState>)> {
        let mut contribs = Vec::with_capacity(self.slots.len());
        let mut states = Vec::with_capacity(self.slots.len());
        for (k, slot) in self.slots.iter().enumerate() {
            let (c, st) = self.evaluate_slot(model, dofs, u, slot, frozen.map(|f| f[k].partner))?;
            contribs.push(c);
            states.push(st);
        }
        Ok((contribs, states))
    }

    fn position(
        &self,
        model: &Model,
        dofs: &DofMap,
        u: &[f64],
        n: usize,
    ) -> Result<([f64; 3], Vec<usize>)> {
        let mut x = model.nodes[n].coords;
        let mut codes = Vec::with_capacity(self.nsd);
        for d in 1..=self.nsd as u8 {
            let code = dofs.code(n, d).ok_or_else(|| {
                Error::Solve(format!(
                    "contact node {} has no DOF {d}",
                    model.nodes[n].label
                ))
            })?;
            x[d as usize - 1] += dofs.value(u, code);
            codes.push(code);
        }
        Ok((x, codes))
    }

    /// Find the partner of an N2S slot: the closest segment the node projects onto.
    fn search(
        &self,
        model: &Model,
        dofs: &DofMap,
        u: &[f64],
        slot: &Slot,
        xs: &[f64; 3],
    ) -> Result<Partner> {
        let Pairing::NodeToSegment { segments, .. } = &model.contacts[slot.cond].pairing else {
            unreachable!("search is for node-to-segment slots")
        };
        let d = self.nsd;
        let mut best: (f64, Partner) = (f64::INFINITY, Partner::None);
        for &g in segments {
            match &model.segments[g].kind {
                SegmentKind::Edges { edges } => {
                    for (k, &(e, b)) in edges.iter().enumerate() {
                        let el = &model.elements[e];
                        let local = el.etype.shape().boundaries()[b - 1];
                        if local.contains(
                            &el.nodes
                                .iter()
                                .position(|&n| n == slot.node)
                                .unwrap_or(usize::MAX),
                        ) {
                            continue; // a node never contacts its own edges
                        }
                        let mut xe = Vec::with_capacity(local.len());
                        for &a in local {
                            xe.push(self.position(model, dofs, u, el.nodes[a])?.0);
                        }
                        let (xi, dist) = if local.len() == 2 {
                            let (t, dist) =
                                kin::project_on_line(&xs[..d], &xe[0][..d], &xe[1][..d]);
                            (t, dist)
                        } else {
                            let x3 = [
                                [xe[0][0], xe[0][1]],
                                [xe[1][0], xe[1][1]],
                                [xe[2][0], xe[2][1]],
                            ];
                            let (t, dist, ok) = kin::project_on_quad_edge([xs[0], xs[1]], &x3);
                            if !ok {
                                continue;
                            }
                            (0.5 * (t + 1.0), dist)
                        };
                        if (-INSIDE_TOL..=1.0 + INSIDE_TOL).contains(&xi) && dist < best.0 {
                            let param = if local.len() == 2 { xi } else { 2.0 * xi - 1.0 };
                            best = (dist, Partner::Edge(g, k, param));
                        }
                    }
                }
                SegmentKind::Polynomial { coeffs } => {
                    let (x, ok) = kin::project_on_poly(coeffs, [xs[0], xs[1]]);
                    if ok {
                        let (f, _) = kin::poly_value(coeffs, x);
                        let dist = ((xs[0] - x).powi(2) + (xs[1] - f).powi(2)).sqrt();
                        if dist < best.0 {
                            best = (dist, Partner::Rigid(g, x));
                        }
                    }
                }
                SegmentKind::Circle {
                    center,
                    radius,
                    node,
                } => {
                    let c = self.rigid_origin(model, dofs, u, *center, *node)?;
                    let r: f64 = (0..d).map(|i| (xs[i] - c[i]).powi(2)).sum::<f64>().sqrt();
                    if r > 0.0 && (r - radius).abs() < best.0 {
                        best = ((r - radius).abs(), Partner::Rigid(g, 0.0));
                    }
                }
                SegmentKind::Plane {
                    point,
                    normal,
                    node,
                } => {
                    let p = self.rigid_origin(model, dofs, u, *point, *node)?;
                    let dist = (0..d)
                        .map(|i| (xs[i] - p[i]) * normal[i])
                        .sum::<f64>()
                        .abs();
                    if dist < best.0 {
                        best = (dist, Partner::Rigid(g, 0.0));
                    }
                }
            }
        }
        Ok(best.1)
    }

    fn rigid_origin(
        &self,
        model: &Model,
        dofs: &DofMap,
        u: &[f64],
        p: [f64; 3],
        node: Option<usize>,
    ) -> Result<[f64; 3]> {
        let mut c = p;
        if let Some(n) = node {
            let (x, _) = self.position(model, dofs, u, n)?;
            for i in 0..3 {
                c[i] += x[i] - model.nodes[n].coords[i];
            }
        }
        Ok(c)
    }

    fn evaluate_slot(
        &self,
        model: &Model,
        dofs: &DofMap,
        u: &[f64],
        slot: &Slot,
        frozen: Option<Partner>,
    ) -> Result<(Contribution, SlotState)> {
        let d = self.nsd;
        let cond = &model.contacts[slot.cond];
        let (xs, s_codes) = self.position(model, dofs, u, slot.node)?;
        let mut state = SlotState {
            condition: cond.number,
            node: slot.node,
            partner: Partner::None,
            gap: f64::NAN,
            force: 0.0,
            pressure: 0.0,
            active: false,
            x: xs,
        };
        let partner = match (slot.master, frozen) {
            (Some((m, _)), _) => Partner::Node(m),
            (None, Some(p)) => p,
            (None, None) => self.search(model, dofs, u, slot, &xs)?,
        };
        state.partner = partner;
        // Local unknowns: slave position, then the partner's nodes.
        let mut codes = s_codes;
        let mut vals: Vec<f64> = xs[..d].to_vec();
        let push_node = |n: usize, codes: &mut Vec<usize>, vals: &mut Vec<f64>| -> Result<()> {
            let (x, c) = self.position(model, dofs, u, n)?;
            codes.extend(c);
            vals.extend_from_slice(&x[..d]);
            Ok(())
        };
        let fixed_normal = cond.normal;
        let gap: Option<Jet> = match partner {
            Partner::None => None,
            Partner::Node(m) => {
                push_node(m, &mut codes, &mut vals)?;
                let q = jet::seed(&vals);
                let n = slot.master.expect("node partner").1;
                let dvec: Vec<Jet> = (0..d).map(|i| q[i] - q[d + i]).collect();
                Some(jet::dot_const(&dvec, &n[..d]))
            }
            Partner::Edge(g, k, xi) => {
                let SegmentKind::Edges { edges } = &model.segments[g].kind else {
                    unreachable!()
                };
                let (e, b) = edges[k];
                let el = &model.elements[e];
                let local = el.etype.shape().boundaries()[b - 1];
                for &a in local {
                    push_node(el.nodes[a], &mut codes, &mut vals)?;
                }
                let q = jet::seed(&vals);
                let side = self.edge_sides[g][k];
                let xsj = [q[0], q[1]];
                let xn = |a: usize| [q[2 + 2 * a], q[3 + 2 * a]];
                let refx = |a: usize| {
                    let c = model.nodes[el.nodes[local[a]]].coords;
                    [c[0], c[1]]
                };
                if el.nlgeo && fixed_normal.is_none() {
                    Some(if local.len() == 2 {
                        kin::gap_line(&xsj, &xn(0), &xn(1), side)
                    } else {
                        kin::gap_quad(&xsj, &[xn(0), xn(1), xn(2)], xi, side)
                    })
                } else {
                    // Small deformation (or a prescribed normal): reference normal at the contact
                    // point, contact point held fixed in the linearization.
                    let (shape, t_ref): (Vec<f64>, [f64; 2]) = if local.len() == 2 {
                        let (a, b2) = (refx(0), refx(1));
                        (vec![1.0 - xi, xi], [b2[0] - a[0], b2[1] - a[1]])
                    } else {
                        let (nsh, t) = kin::quad_edge_shape(&[refx(0), refx(1), refx(2)], xi);
                        (nsh.to_vec(), t)
                    };
                    let n0 = match fixed_normal {
                        Some(n) => [n[0], n[1]],
                        None => {
                            let l = (t_ref[0] * t_ref[0] + t_ref[1] * t_ref[1]).sqrt();
                            [side * t_ref[1] / l, -side * t_ref[0] / l]
                        }
                    };
                    let xa: Vec<Vec<Jet>> = (0..local.len()).map(|a| xn(a).to_vec()).collect();
                    Some(kin::gap_linearized(&xsj, &xa, &shape, &n0))
                }
            }
            Partner::Rigid(g, x0) => {
                let k = match &model.contacts[slot.cond].pairing {
                    Pairing::NodeToSegment { segments, .. } => {
                        segments.iter().position(|&s| s == g).unwrap_or(0)
                    }
                    _ => 0,
                };
                let side = slot.sides[k];
                let (origin, node) = match &model.segments[g].kind {
                    SegmentKind::Circle { center, node, .. } => (*center, *node),
                    SegmentKind::Plane { point, node, .. } => (*point, *node),
                    _ => ([0.0; 3], None),
                };
                if let Some(n) = node {
                    push_node(n, &mut codes, &mut vals)?;
                }
                let q = jet::seed(&vals);
                let nv = vals.len();
                let xsj = &q[..d];
                // Origin of the rigid body: fixed, or the reference point plus the node's motion.
                let o: Vec<Jet> = (0..d)
                    .map(|i| match node {
                        Some(n) => q[d + i] + (origin[i] - model.nodes[n].coords[i]),
                        None => Jet::constant(origin[i], nv),
                    })
                    .collect();
                Some(match &model.segments[g].kind {
                    SegmentKind::Circle { radius, .. } => match fixed_normal {
                        Some(n) => {
                            // Gap along the prescribed normal to the closest point of the circle.
                            let dv: Vec<Jet> = (0..d).map(|i| xsj[i] - o[i]).collect();
                            let r = jet::dot(&dv, &dv).sqrt();
                            let proj: Vec<Jet> =
                                (0..d).map(|i| dv[i] - dv[i] / r * *radius).collect();
                            jet::dot_const(&proj, &n[..d]) * side
                        }
                        None => kin::gap_circle(xsj, &o, *radius, side),
                    },
                    SegmentKind::Plane { normal, .. } => {
                        kin::gap_plane(xsj, &o, &fixed_normal.unwrap_or(*normal)[..d], side)
                    }
                    SegmentKind::Polynomial { coeffs } => {
                        kin::gap_poly(coeffs, &[q[0], q[1]], x0, side)
                    }
                    SegmentKind::Edges { .. } => unreachable!(),
                })
            }
        };
        let m = codes.len();
        debug_assert!(m <= MAXV);
        let mut out = Contribution::default();
        if let Some(g) = gap {
            state.gap = g.v;
        }
        match (cond.law, slot.lambda_eq) {
            (ContactLaw::Penalty(p), _) => {
                // Closed at g ≤ 0: at g = 0 the force is zero but the tangent is on (as OOFEM), so
                // a load-controlled indenter that starts touching has stiffness.
                if let Some(g) = gap.filter(|g| g.v <= 0.0) {
                    out.codes = codes;
                    out.fe = (0..m).map(|i| p * g.v * g.g[i]).collect();
                    let curv = if self.curvature_allowed(p * g.v.abs(), &g) {
                        1.0
                    } else {
                        0.0
                    };
                    out.ke = (0..m * m)
                        .map(|k| p * (g.g[k / m] * g.g[k % m] + curv * g.v * g.h[k / m][k % m]))
                        .collect();
                    state.force = -p * g.v;
                    state.active = g.v < 0.0;
                } else {
                    out.codes = codes;
                }
            }
            (ContactLaw::Multiplier, Some(leq)) => {
                let lambda = u[leq];
                let active = gap.is_some_and(|g| lambda - self.c * g.v > 0.0);
                let mm = m + 1;
                out.codes = codes;
                out.codes.push(leq);
                out.fe = vec![0.0; mm];
                out.ke = vec![0.0; mm * mm];
                if let (true, Some(g)) = (active, gap) {
                    for i in 0..m {
                        out.fe[i] = -lambda * g.g[i];
                        out.ke[i * mm + m] = -g.g[i];
                        out.ke[m * mm + i] = -g.g[i];
                        if self.curvature_allowed(lambda.abs(), &g) {
                            for j in 0..m {
                                out.ke[i * mm + j] = -lambda * g.h[i][j];
                            }
                        }
                    }
                    out.fe[m] = -g.v;
                    state.force = lambda;
                    state.active = true;
                } else {
                    out.fe[m] = lambda;
                    out.ke[m * mm + m] = 1.0;
                }
            }
            (ContactLaw::Multiplier, None) => unreachable!("multiplier slots have an equation"),
        }
        state.pressure = if slot.area > 0.0 {
            state.force / slot.area
        } else {
            f64::NAN
        };
        Ok((out, state))
    }
}

/// +1 if (t_y, −t_x) of the edge (first → second node) points out of the element, else −1.
fn edge_outward_side(model: &Model, e: usize, b: usize) -> f64 {
    let el = &model.elements[e];
    let local = el.etype.shape().boundaries()[b - 1];
    let x1 = model.nodes[el.nodes[local[0]]].coords;
    let x2 = model.nodes[el.nodes[local[1]]].coords;
    let n = [x2[1] - x1[1], -(x2[0] - x1[0])];
    let nn = el.nodes.len() as f64;
    let c = el.nodes.iter().fold([0.0, 0.0], |acc, &k| {
        let x = model.nodes[k].coords;
        [acc[0] + x[0] / nn, acc[1] + x[1] / nn]
    });
    let m = [0.5 * (x1[0] + x2[0]), 0.5 * (x1[1] + x2[1])];
    if (c[0] - m[0]) * n[0] + (c[1] - m[1]) * n[1] > 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// Side factor of a rigid segment: +1 if the node starts on the side the normal points to (or on
/// the surface), else −1 (the allowed side is where the node starts; spec §2.4.4).
fn rigid_initial_side(model: &Model, g: usize, x: &[f64]) -> f64 {
    let d = x.len();
    let signed = match &model.segments[g].kind {
        SegmentKind::Circle { center, radius, .. } => {
            (0..d)
                .map(|i| (x[i] - center[i]).powi(2))
                .sum::<f64>()
                .sqrt()
                - radius
        }
        SegmentKind::Plane { point, normal, .. } => {
            (0..d).map(|i| (x[i] - point[i]) * normal[i]).sum()
        }
        SegmentKind::Polynomial { coeffs } => {
            let (f, _) = kin::poly_value(coeffs, x[0]);
            x[1] - f
        }
        SegmentKind::Edges { .. } => 1.0,
    };
    if signed < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// Tributary length·thickness (2D) or area (3D) of each slot's node: element boundaries whose
/// nodes all belong to the same condition's contact nodes share their measure among their nodes.
fn tributary_areas(model: &Model, slots: &[Slot]) -> Vec<f64> {
    use std::collections::{HashMap, HashSet};
    let mut by_cond: HashMap<usize, HashSet<usize>> = HashMap::new();
    for s in slots {
        by_cond.entry(s.cond).or_default().insert(s.node);
    }
    let mut area: HashMap<(usize, usize), f64> = HashMap::new();
    for (&cond, nodes) in &by_cond {
        for (ei, el) in model.elements.iter().enumerate() {
            if el.etype.is_truss() || !el.nodes.iter().any(|n| nodes.contains(n)) {
                continue;
            }
            let shape = el.etype.shape();
            for local in shape.boundaries() {
                let bn: Vec<usize> = local.iter().map(|&a| el.nodes[a]).collect();
                if !bn.iter().all(|n| nodes.contains(n)) {
                    continue;
                }
                let x: Vec<[f64; 3]> = bn.iter().map(|&n| model.nodes[n].coords).collect();
                let dist = |a: [f64; 3], b: [f64; 3]| {
                    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
                };
                let shares: Vec<f64> = if shape.dim() == 2 {
                    let thick = crate::solid::loads::element_thickness(model, ei);
                    if bn.len() == 2 {
                        let l = dist(x[0], x[1]) * thick;
                        vec![0.5 * l, 0.5 * l]
                    } else {
                        // Quadratic edge (ends, middle): Simpson weights 1/6, 1/6, 2/3.
                        let l = (dist(x[0], x[2]) + dist(x[2], x[1])) * thick;
                        vec![l / 6.0, l / 6.0, 2.0 * l / 3.0]
                    }
                } else {
                    let cross = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
                        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
                        let w = [
                            u[1] * v[2] - u[2] * v[1],
                            u[2] * v[0] - u[0] * v[2],
                            u[0] * v[1] - u[1] * v[0],
                        ];
                        0.5 * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt()
                    };
                    let a = if bn.len() == 3 {
                        cross(x[0], x[1], x[2])
                    } else {
                        cross(x[0], x[1], x[2]) + cross(x[0], x[2], x[3])
                    };
                    vec![a / bn.len() as f64; bn.len()]
                };
                for (n, s) in bn.iter().zip(shares) {
                    *area.entry((cond, *n)).or_default() += s;
                }
            }
        }
    }
    slots
        .iter()
        .map(|s| area.get(&(s.cond, s.node)).copied().unwrap_or(0.0))
        .collect()
}
