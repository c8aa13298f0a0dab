//! Self-contact's repeated pairs. Where node a of a self-contact surface meets it at (nearly) the
//! place of node b, and b meets it near a, the two constraints hold the same motion: the two
//! walls of a tube folded flat, matched node for node. Two multipliers cannot share it (the
//! constraints are dependent or nearly so); dropping one, as two conditions do
//! (`ContactSystem::drop_repeated_constraints`), leaves its node free to sink into the other wall
//! by a second-order amount and breaks the symmetry a fold has (a crushed ring's force came out
//! 0.5 % off its half model's). So the two are merged into one constraint on the mean gap
//! ḡ = (g_a + g_b)/2 = 0, whose force λ acts along its gradient (B_a + B_b)/2: for a matched
//! pair (g_a = g_b) it is either constraint, exactly; otherwise both nodes meet the other wall to
//! second order, alike. The force is reported half at each node. With friction (whose slips do
//! not merge) or past the ramp of an open end the pair is left to the two-condition rule.

use super::{NodeToSegment, Prepared, Slot};
use crate::contact::dual::Jet;
use crate::contact::formulation::{Formulation, Local, Partner, Search};
use crate::contact::law::SlotKinematics;

/// A pair closer than this fraction of the spacing of the nodes around it repeats one contact;
/// a pair that was one at the previous state stays one up to `KEEP` (a band: no alternation).
const PAIR: f64 = 0.25;
const KEEP: f64 = 1.0 / 3.0;

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
                let d = dist(&state(i).x, &xb).sqrt();
                if spacing.is_finite() && d < limit * spacing {
                    pairs.push((d, i, j));
                }
            }
        }
        pairs.sort_by(|p, q| p.0.total_cmp(&q.0).then((p.1, p.2).cmp(&(q.1, q.2))));
        let mut used = vec![false; self.slots.len()];
        let mut out = Vec::new();
        for (_, i, j) in pairs {
            if !used[i] && !used[j] {
                used[i] = true;
                used[j] = true;
                out.push((i, j));
            }
        }
        out
    }
}

/// Whether a slot's kinematics can merge: on its partner (a weight above zero; a node on an
/// open boundary of its surface, the free face of a slab, sits in its ramp) and short of any
/// ramp's far end (the multipliers' max(g, e) is g), frictionless. The merged weight is the
/// mean (a penalty's force is ε·w·⟨−g⟩; the multipliers' weight only switches).
fn mergeable(slot: &Slot, partner: Partner, kin: &SlotKinematics) -> bool {
    slot.own.is_some()
        && matches!(partner, Partner::Edge(_) | Partner::Face(_))
        && kin.weight.v > 0.0
        && kin.past_end.as_ref().is_none_or(|e| e.v < 0.0)
        && kin.slip.is_none()
}

/// A jet over another local set's unknowns, placed by `map` among `m` unknowns.
fn placed(x: &Jet, map: &[usize], m: usize) -> Jet {
    let mut d = vec![0.0; m];
    for (k, v) in x.d.iter().enumerate() {
        d[map[k]] += v;
    }
    Jet { v: x.v, d }
}

/// (x + y)/2.
fn mean(x: &Jet, y: &Jet) -> Jet {
    Jet {
        v: 0.5 * (x.v + y.v),
        d: x.d.iter().zip(&y.d).map(|(p, q)| 0.5 * (p + q)).collect(),
    }
}

/// The constraint on the mean gap of two kinematics over their local sets, over the union of
/// the sets (the first's law and area).
pub(super) fn merge(
    (la, ka): (&Local, &SlotKinematics),
    (lb, kb): (&Local, &SlotKinematics),
) -> (Local, SlotKinematics) {
    let (local, map_b) = la.union(lb);
    let m = local.m();
    let map_a: Vec<usize> = (0..la.m()).collect();
    let both = |x: &Jet, y: &Jet| mean(&placed(x, &map_a, m), &placed(y, &map_b, m));
    let mut b = vec![Jet::constant(0.0, m); m];
    for (side, map) in [(&ka.b, &map_a), (&kb.b, &map_b)] {
        for (k, v) in side.iter().enumerate() {
            let v = placed(v, map, m);
            let t = &mut b[map[k]];
            t.v += 0.5 * v.v;
            for (p, q) in t.d.iter_mut().zip(&v.d) {
                *p += 0.5 * q;
            }
        }
    }
    let kin = SlotKinematics {
        gap: both(&ka.gap, &kb.gap),
        weight: both(&ka.weight, &kb.weight),
        b,
        area: ka.area,
        past_end: None,
        slip: None,
    };
    (local, kin)
}
