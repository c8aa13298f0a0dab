//! Node-to-segment self-contact's repeated pairs (see [`crate::contact::repeated`]): two nodes
//! that meet each other's partner within a quarter of their spacing. Dropping one, as two
//! conditions do (`ContactSystem::drop_repeated_constraints`), left its node free to sink into
//! the other wall by a second-order amount and broke the symmetry a fold has (a crushed ring's
//! force came out 0.5 % off its half model's), so they are merged, friction and all (its force
//! on the pair's mean relative slip). Past the ramp of an open end the pair is left to the
//! two-condition rule, and so is a convex corner on a face (their partners bend unlike, see
//! [`repeated::BEND_APART`]). Each node's distance is measured from the other's contact point,
//! so a pair closing from across an open gap is one before it closes.

use super::{Current, NodeToSegment, Prepared, Slot};
use crate::contact::formulation::{Formulation, Partner, Search};
use crate::contact::geometry::edges::{self, edge_normal};
use crate::contact::geometry::faces as faces_geom;
use crate::contact::law::SlotKinematics;
use crate::contact::repeated::{self, KEEP, PAIR};
use crate::contact::search::Candidate;

impl NodeToSegment {
    /// The self-contact slots (i, j), i < j, whose constraints repeat each other, closest first
    /// and each slot in one pair at most, among the slots `prepared` whose kinematics can merge.
    pub(super) fn repeated_pairs(
        &self,
        prepared: &[Prepared],
        search: &Search,
    ) -> Vec<(usize, usize)> {
        let slot_of: std::collections::HashMap<usize, usize> = (self.slots.iter().enumerate())
            .filter(|&(k, s)| mergeable(s, prepared[k].state.partner, &prepared[k].kin))
            .map(|(k, s)| (s.node, k))
            .collect();
        if slot_of.is_empty() {
            return Vec::new();
        }
        let state = |k: usize| &prepared[k].state;
        let dist = |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>();
        let position: std::collections::HashMap<usize, [f64; 3]> =
            prepared.iter().map(|p| (p.state.node, p.state.x)).collect();
        let mut pairs = Vec::new();
        for (&a, &i) in &slot_of {
            let partner = self.partner_nodes(state(i).partner);
            for b in partner {
                let Some(&j) = slot_of.get(b) else { continue };
                if j <= i || !self.partner_nodes(state(j).partner).contains(&a) {
                    continue;
                }
                // b's nearest neighbour on a's partner.
                let xb = state(j).x;
                let spacing = (partner.iter().filter(|&n| n != b))
                    .filter_map(|n| position.get(n).map(|x| dist(x, &xb)))
                    .fold(f64::INFINITY, f64::min)
                    .sqrt();
                let limit = if search.repeated(i) || search.repeated(j) {
                    KEEP
                } else {
                    PAIR
                };
                let d = repeated::apart(&state(i).x, state(i).point, &xb, state(j).point);
                // A corner on a face: left to the two-condition rule (see `BEND_APART`).
                let alike = (state(i).bend - state(j).bend).abs() <= repeated::BEND_APART;
                if spacing.is_finite() && d < limit * spacing && alike {
                    pairs.push((d, i, j));
                }
            }
        }
        repeated::closest_first(pairs, self.slots.len())
    }

    /// Where candidate `c`'s contact point lies on its edge or face.
    pub(super) fn contact_point(&self, c: Candidate, cur: &Current) -> Option<[f64; 3]> {
        let (nodes, w): (&[usize], Vec<f64>) = match c.partner {
            Partner::Edge(k) => {
                let e = &self.edges.edges[k];
                (&e.nodes, edges::shape(e.nodes.len(), c.xi[0]).0.to_vec())
            }
            Partner::Face(k) => {
                let f = &self.faces.faces[k];
                (
                    &f.nodes,
                    faces_geom::shape_values(f.kind, c.xi[0], c.xi[1])
                        .0
                        .to_vec(),
                )
            }
            _ => return None,
        };
        let mut p = [0.0; 3];
        for (n, w) in nodes.iter().zip(w) {
            for i in 0..3 {
                p[i] += w * cur.x[n][i];
            }
        }
        Some(p)
    }

    /// How much the partner surface of candidate `c` bends at the partner's corner nearest its
    /// contact point, for a node at `xs` (see [`crate::contact::formulation::SlotState::bend`]):
    /// 1 − n̂·n there, n̂ the smoothed normal and n the partner's own.
    pub(super) fn bend(&self, c: Candidate, xs: [f64; 3], cur: &Current) -> f64 {
        let at = |n: &usize| cur.x[n];
        let (smooth, own) = match c.partner {
            Partner::Edge(k) => {
                let geometry = self.edge_geometry_f64(k, cur);
                let s = if c.xi[0] < 0.5 { 0.0 } else { 1.0 };
                let (_, n) = geometry.gap([xs[0], xs[1]], s);
                let own = edge_normal(&geometry.x, self.edges.edges[k].side, s);
                ([n[0], n[1], 0.0], [own[0], own[1], 0.0])
            }
            Partner::Face(k) => {
                let f = &self.faces.faces[k];
                let x: Vec<[f64; 3]> = f.nodes.iter().map(at).collect();
                let (w, _, _) = faces_geom::shape_values(f.kind, c.xi[0], c.xi[1]);
                let corner = (0..f.kind.corners())
                    .max_by(|&a, &b| w[a].total_cmp(&w[b]))
                    .unwrap_or(0);
                let (xi, eta) = faces_geom::node_param(f.kind, corner);
                (
                    self.face_geometry_f64(k, cur).gap(&xs, xi, eta).1,
                    faces_geom::face_normal(f.kind, &x, f.side, xi, eta),
                )
            }
            _ => return 0.0,
        };
        1.0 - (0..3).map(|i| smooth[i] * own[i]).sum::<f64>()
    }
}

/// Whether a slot's kinematics can merge: on its partner (a weight above zero; a node on an
/// open boundary of its surface, the free face of a slab, sits in its ramp) and short of any
/// ramp's far end (the multipliers' max(g, e) is g). The merged weight is the
/// mean (a penalty's force is ε·w·⟨−g⟩; the multipliers' weight only switches).
fn mergeable(slot: &Slot, partner: Partner, kin: &SlotKinematics) -> bool {
    slot.own.is_some()
        && matches!(partner, Partner::Edge(_) | Partner::Face(_))
        && kin.weight.v > 0.0
        && kin.past_end.as_ref().is_none_or(|e| e.v < 0.0)
}
