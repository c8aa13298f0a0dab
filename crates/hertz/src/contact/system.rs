//! [`ContactSystem`]: every contact condition of a model, evaluated together, with two-pass
//! pairing (a constraint two conditions repeat is dropped once).

use super::formulation::{Ctx, Formulation, Partner, Search, SlotState};
use super::law::Laws;
use super::slot::SlotLinearization;
use super::{mortar, n2n, n2s, repeated};
use crate::assembly::{ExtraDofs, NodalState};
use crate::error::Result;
use crate::model::queries::{coordinate_size, model_size};
use crate::model::{Model, Pairing};

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
        // The stiffest element's modulus: an unused material (a stiff one left in the file) once
        // set c, and with E = 1e300 the active-set rule λ − c·g lost λ to round-off, kept nodes
        // in tension closed and gave 8 % less force.
        let young = model
            .elements
            .iter()
            .map(|e| model.materials[e.material].young())
            .fold(0.0f64, f64::max)
            .max(1e-30);
        Ok(ContactSystem {
            formulations,
            laws: Laws {
                c: young,
                // Never below the round-off of the positions the gaps are differences of.
                gap_tol: (1e-12 * model_size(model))
                    .max(64.0 * f64::EPSILON * coordinate_size(model)),
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
    /// part.
    pub fn symmetric(&self) -> bool {
        !self.frictional && self.formulations.iter().all(|f| f.symmetric())
    }

    /// Every condition's [`Formulation::slave_transform`] rows, each entry once (a node slave
    /// of two conditions on quadratic faces has the same row in both).
    pub fn slave_transform(&self) -> Vec<(usize, usize, f64)> {
        let mut seen = std::collections::HashSet::new();
        self.formulations
            .iter()
            .flat_map(|f| f.slave_transform())
            .filter(|&(k, l, _)| seen.insert((k, l)))
            .collect()
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

    /// Free equations that contact contributions can touch from the state `nodes` on (through
    /// slave-node weights), sorted; the multipliers are not among them.
    pub fn candidate_equations(&self, nodes: &NodalState) -> Result<Vec<usize>> {
        let ctx = self.ctx(nodes);
        let mut candidates = Vec::new();
        for f in &self.formulations {
            candidates.extend(f.candidate_nodes(&ctx)?);
        }
        Ok(nodes.displacement_equations(candidates))
    }

    /// The state the formulations are evaluated at.
    fn ctx<'a>(&'a self, nodes: &NodalState<'a>) -> Ctx<'a> {
        Ctx {
            model: nodes.model(),
            nodes: *nodes,
            dim: self.dim,
            laws: &self.laws,
        }
    }

    /// Set the contact pressure above which the geometric tangent part is dropped (see
    /// [`Laws::geometric_allowed`]); `f64::INFINITY` always assembles the exact tangent.
    pub fn set_pressure_limit(&mut self, limit: f64) {
        self.laws.pressure_limit = limit;
    }

    /// Every penalty condition's number and the smallest and largest penalty in effect at its
    /// slots.
    pub fn penalties(&self) -> Vec<(usize, f64, f64)> {
        self.formulations
            .iter()
            .filter_map(|f| f.penalties())
            .collect()
    }

    /// Each node-to-segment node's penalty from the mesh as `stiffness[node]` where its
    /// condition gives none (see [`Formulation::set_mesh_penalties`]).
    pub fn set_mesh_penalties(&mut self, stiffness: &[f64]) {
        for f in &mut self.formulations {
            f.set_mesh_penalties(stiffness);
        }
    }

    /// Whether any condition has friction (whose history the solver must keep).
    pub fn has_friction(&self) -> bool {
        self.frictional
    }

    /// Evaluate every contact point at the state `nodes` without friction history: the points
    /// (whose [`contribution`](SlotLinearization::contribution) is the current residual and tangent)
    /// and their states.
    pub fn evaluate(
        &self,
        nodes: &NodalState,
        search: Search,
    ) -> Result<(Vec<SlotLinearization>, Vec<SlotState>)> {
        self.evaluate_with_history(nodes, search, None)
    }

    /// [`ContactSystem::evaluate`] with the friction history: the converged states of the last
    /// step (their anchors); its primary state is `nodes`' start state.
    pub fn evaluate_with_history(
        &self,
        nodes: &NodalState,
        search: Search,
        history: Option<&[SlotState]>,
    ) -> Result<(Vec<SlotLinearization>, Vec<SlotState>)> {
        let ctx = self.ctx(nodes);
        let start = std::time::Instant::now();
        let mut points = Vec::new();
        let mut states = Vec::new();
        let mut lambda = nodes.first_multiplier();
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

/// Why a state with contact nodes that crossed their master (see [`SlotState::crossed`]) or that
/// a repeated pair's one constraint leaves behind the other wall ([`SlotState::unheld`]) cannot
/// be a solution, in words: the worst few nodes, their conditions and the elements they are in.
pub fn crossing_message(model: &Model, states: &[SlotState]) -> Option<String> {
    if let Some((s, depth)) = (states.iter())
        .filter_map(|s| s.unheld.map(|d| (s, d)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
    {
        return Some(format!(
            "node {} of contact condition {} lies {depth:.3e} behind the other surface, which \
             it meets near a node of that surface held by the same constraint (two-pass or \
             self-contact keep one constraint per contact): the two are not one contact — a \
             corner pressed into a face beside one of its nodes, or two surfaces crossing \
             between their nodes — and node-to-segment cannot hold both; one condition whose \
             nodes are the corner's side and whose master is the face holds it",
            model.nodes[s.node].label, s.condition
        ));
    }
    let mut crossed: Vec<(&SlotState, super::geometry::bodies::Inside)> = states
        .iter()
        .filter_map(|s| s.crossed.map(|c| (s, c)))
        .collect();
    if crossed.is_empty() {
        return None;
    }
    crossed.sort_by(|a, b| b.1.depth.total_cmp(&a.1.depth));
    let list: Vec<String> = crossed
        .iter()
        .take(4)
        .map(|(s, c)| {
            format!(
                "node {} of contact condition {} lies {:.3e} inside element {}",
                model.nodes[s.node].label, s.condition, c.depth, model.elements[c.element].label
            )
        })
        .collect();
    Some(format!(
        "{}{} with no contact force: {} crossed the master surface where no partner holds \
         {} (past an end of the master or a crease of a folded surface); smaller steps keep \
         nodes from crossing, and a master that covers the whole surface they can meet holds them",
        list.join(", "),
        if crossed.len() > 4 {
            format!(" (and {} more)", crossed.len() - 4)
        } else {
            String::new()
        },
        if crossed.len() > 1 { "they" } else { "it" },
        if crossed.len() > 1 { "them" } else { "it" },
    ))
}

impl ContactSystem {
    /// Two-pass contact: where a node a of one condition meets the other surface at (nearly) the
    /// place of a node b of it, and b meets a's surface near a, both constraints hold the same
    /// motion. Multipliers cannot share it (the constraints are dependent or nearly so, and
    /// Newton's active set chatters between them); a penalty would double its stiffness there,
    /// and in the limit of a large penalty over-constrain the surfaces as the multipliers would.
    /// So one of the two is dropped, for both laws alike (the penalty answer then tends to the
    /// multipliers' one): it exerts no force of its own (its multiplier is held at zero; its node
    /// reports the kept one's pressure, which acts on it), and its node penetrates the other
    /// surface by at most a second-order amount. "Nearly": a is closer to b than a quarter of
    /// the distance from b to its nearest neighbour on its surface (a third, if the pair was one
    /// at the previous state: a band, so that a pair at the limit does not alternate). The one
    /// dropped is the one past an open end of its partner (a node beside a corner, whose
    /// constraint is the extension of the surface) when the other lies on its partner (the
    /// corner on the surface); else the one of the condition (or, in self-contact, the slot)
    /// listed later, or the one dropped before. Pairs are formed closest first, each node in one
    /// pair at most.
    fn drop_repeated_constraints(
        &self,
        points: &mut [SlotLinearization],
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
        // Candidate pairs (distance, i, j), i of the earlier condition or slot.
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
                    // Each pair once; in self-contact both slots are of one condition.
                    if (fj, j) <= (fi, i) || !back.contains(&states[i].node) {
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
                    let d = repeated::apart(&states[i].x, states[i].point, &xb, states[j].point);
                    if d < limit * spacing {
                        pairs.push((d, spacing, i, j));
                    }
                }
            }
        }
        pairs.sort_by(|p, q| p.0.total_cmp(&q.0));
        let mut used = vec![false; states.len()];
        for (_, spacing, i, j) in pairs {
            if used[i] || used[j] {
                continue;
            }
            used[i] = true;
            used[j] = true;
            let beside = |k: usize| states[k].weight < 1.0;
            let (bi, bj) = (states[i].bend, states[j].bend);
            let one_surface = owner[i] == owner[j];
            let drop = if one_surface && (bi - bj).abs() > repeated::BEND_APART {
                // Self-contact, a corner on a face: the corner's constraint on the face holds.
                // (Two conditions keep the earlier one's: which side is the corner is the
                // user's choice there, and under a deep indentation the face's dent bends
                // as much as the corner.)
                if bi > bj {
                    i
                } else {
                    j
                }
            } else if was_repeated(i) && !was_repeated(j) {
                i
            } else if was_repeated(j) && !was_repeated(i) {
                j
            } else if beside(i) && !beside(j) {
                i
            } else {
                j
            };
            points[drop].disable();
            // The node is held by the kept constraint, which presses on it through its master
            // share: the interface's pressure is the kept one's on both sides (reporting none
            // left the dropped side's field empty where it carries the contact).
            let kept = if drop == i { j } else { i };
            let (pressure, active) = (states[kept].pressure, states[kept].active);
            let unheld = repeated::unheld(states[drop].gap, states[kept].gap, spacing, 0.0);
            let s = &mut states[drop];
            s.unheld = unheld;
            s.active = active;
            s.pressure = if active { pressure } else { 0.0 };
            s.force = s.pressure * s.area;
            s.repeated = true;
            s.friction = None;
            // Held by the other's constraint (to a second-order overlap).
            s.crossed = None;
        }
    }
}
