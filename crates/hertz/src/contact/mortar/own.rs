//! Mortar self-contact, shared by 2D ([`super::edges`]) and 3D ([`super::faces`]): which parts
//! of its own surface a slave facet may meet, which pairs of its nodes repeat one contact, and
//! the evaluation of slots of which such pairs hold one merged constraint
//! ([`crate::contact::repeated`]).

use super::{MortarLaw, Weighted, SLIVER};
use crate::contact::formulation::{Anchor, Ctx, Local, Partner, SlotState};
use crate::contact::law::SlotKinematics;
use crate::contact::repeated;
use crate::contact::slot::SlotLinearization;
use crate::error::Result;

/// A slave facet meets a facing part of its own surface behind it only within this fraction of
/// the facets' size or of the depth of the element behind that part (the far side of a thin
/// wall lies behind the facet without having been crossed).
pub(super) const OWN_DEPTH: f64 = 0.25;

/// A slave facet meets a part of its own surface only where their normals are more than 120°
/// apart (cos = −0.5): walls closing on each other, the two facets at the tip of a closing
/// crease, not the next facet round a bend, nor a wall seen askew, whose rays along the mean of
/// the two normals would skim both. A slave node's own constraint never takes a master facet
/// through the node itself (its gap there is zero whatever the motion).
pub(super) const OWN_FACING: f64 = -0.5;

/// Two slave nodes closer than this fraction of the second's facet size, each meeting the
/// other's wall, hold one contact; a pair that was one at the last converged state stays one up
/// to `PAIR_KEPT` (a band: no alternation). Twice node-to-segment's radius
/// ([`repeated::PAIR`]): a node's weighted gap spans its facets, and two nodes within half a
/// spacing of each other share most of their supports, so their two constraints are nearly
/// dependent — kept apart, a ring whose walls' nodes are offset by 0.3 of a spacing took 43
/// iterations and two cuts at one step of its crush (merged: at most 10, no cut).
const PAIR: f64 = 2.0 * repeated::PAIR;
const PAIR_KEPT: f64 = 2.0 * repeated::KEEP;

/// How far a master facet lies behind a slave facet of its own surface, `behind` (> 0: behind
/// it), admits it: up to [`OWN_DEPTH`] of the smaller facet size `size` or of the depth `depth`
/// of the master's element behind it.
pub(super) fn within_reach(behind: f64, size: f64, depth: f64) -> bool {
    behind <= 0.0 || behind <= OWN_DEPTH * size.min(depth)
}

/// Whether one of `points` lies in the element of shape `shape` at `x`, its boundary included:
/// a slave facet with a corner there has crossed that element's face, however deep (a Newton
/// iterate's overshoot past [`within_reach`]), and meets it.
pub(super) fn crossed(shape: crate::fem::Shape, x: &[[f64; 3]], points: &[[f64; 3]]) -> bool {
    (points.iter()).any(|&p| {
        crate::fem::geometry::locate(shape, x, p).is_some_and(|xi| shape.inside_margin(xi) > -1e-9)
    })
}

/// Self-contact's repeated pairs: slots (i, j), i < j, of nodes `nodes[i]` and `nodes[j]`
/// whose slave facets each overlap an own facet of the other's node (`met[j]`: the nodes of the
/// own facets slot j meets, sorted), closer than [`PAIR`] of the second's facet size
/// `spacing(j)` ([`PAIR_KEPT`] if either was in a pair at the last converged state), closest
/// first and each slot in one pair at most. A slot whose support is below [`SLIVER`] of its
/// full support (`supported`) meets nothing here.
pub(super) fn repeated_pairs(
    ctx: &Ctx,
    nodes: &[usize],
    met: &[Vec<usize>],
    supported: &dyn Fn(usize) -> bool,
    spacing: &dyn Fn(usize) -> Result<f64>,
    history: Option<&[SlotState]>,
) -> Result<Vec<(usize, usize)>> {
    let n = nodes.len();
    let slot_of: std::collections::HashMap<usize, usize> =
        nodes.iter().enumerate().map(|(j, &s)| (s, j)).collect();
    let pos = |node: usize| ctx.position(node).map(|p| p.0);
    let dist = |a: [f64; 3], b: [f64; 3]| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>();
    let was = |j: usize| history.and_then(|h| h.get(j)).is_some_and(|s| s.repeated);
    let mut pairs = Vec::new();
    for i in (0..n).filter(|&i| supported(i)) {
        let a = nodes[i];
        for b in &met[i] {
            let Some(&j) = slot_of.get(b) else { continue };
            if j <= i || !supported(j) || met[j].binary_search(&a).is_err() {
                continue;
            }
            let limit = if was(i) || was(j) { PAIR_KEPT } else { PAIR };
            let d = dist(pos(a)?, pos(*b)?).sqrt();
            if d < limit * spacing(j)? {
                pairs.push((d, i, j));
            }
        }
    }
    Ok(repeated::closest_first(pairs, n))
}

impl MortarLaw {
    /// Whether slot `j` with support `area` has at least [`SLIVER`] of its full support: enough
    /// to meet the other wall as one of a repeated pair.
    pub(super) fn supported(&self, j: usize, area: f64) -> bool {
        area > 0.0 && area >= SLIVER * self.full_support[j]
    }

    /// Every slot's contact point and state from its integrals (`weighted`, slot j of node
    /// `nodes[j]`), the repeated `pairs` each held by one constraint on their mean gap
    /// ([`repeated::merge`]) with its pressure on the first slot's multiplier, the second's at
    /// zero; each node of a pair reports the force the merged constraint puts on it.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn evaluate_slots(
        &self,
        ctx: &Ctx,
        first_lambda: usize,
        nodes: &[usize],
        weighted: Vec<(Local, Weighted)>,
        pairs: &[(usize, usize)],
        history: Option<&[SlotState]>,
        points: &mut Vec<SlotLinearization>,
        states: &mut Vec<SlotState>,
    ) -> Result<()> {
        let mut merged: Vec<Option<(Local, SlotKinematics)>> = Vec::new();
        merged.resize_with(nodes.len(), || None);
        let mut reports = Vec::with_capacity(pairs.len());
        for &(i, j) in pairs {
            let kin = |k: usize| {
                let (local, w) = &weighted[k];
                let mut kin = self.slot_kinematics(k, local, w, w.b.clone());
                kin.slip = self.slip_kinematics(ctx, k, local, w, history);
                kin
            };
            let (ki, kj) = (kin(i), kin(j));
            let (local, kin) = repeated::merge((&weighted[i].0, &ki), (&weighted[j].0, &kj));
            reports.push(PairReport {
                slots: [i, j],
                shares: [nodes[i], nodes[j]].map(|n| repeated::share_at(&local, &kin, n)),
                gaps: [ki.gap.v, kj.gap.v],
                areas: [weighted[i].1.area.v, weighted[j].1.area.v],
                partner: weighted[j].1.partner,
            });
            merged[i] = Some((local, kin));
        }
        let mut second = vec![false; nodes.len()];
        for &(_, j) in pairs {
            second[j] = true;
        }
        let first_state = states.len();
        for (j, (local, w)) in weighted.into_iter().enumerate() {
            // The second of a pair holds nothing of its own (its multiplier at zero).
            let w = match second[j] {
                true => Weighted::none(local.m()),
                false => w,
            };
            let (point, state) = self.evaluate(
                ctx,
                first_lambda,
                j,
                nodes[j],
                &local,
                w,
                history,
                merged[j].take(),
            )?;
            points.push(point);
            states.push(state);
        }
        let mine = &mut states[first_state..];
        for r in reports {
            // The merged constraint's pressure λ: each node carries λ times its share.
            let (lambda, active) = (mine[r.slots[0]].pressure, mine[r.slots[0]].active);
            for k in 0..2 {
                let s = &mut mine[r.slots[k]];
                s.force = lambda * r.shares[k];
                s.area = r.areas[k];
                s.pressure = s.force / s.area;
                s.gap = r.gaps[k];
                s.active = active;
                s.repeated = true;
            }
            mine[r.slots[1]].partner = r.partner;
            // The merged friction force acts on both nodes whole, each anchored at the pair's
            // elastic slip (the second's relative slip is the first's reversed).
            let [first, second] = r.slots;
            mine[second].friction = mine[first]
                .friction
                .map(|(stick, t)| (stick, t / r.areas[0] * r.areas[1]));
            mine[second].anchor = mine[first].anchor.map(|a| Anchor {
                partner: r.partner,
                offset: a.offset.map(|v| -v),
                ..a
            });
        }
        Ok(())
    }
}

/// What each node of a self-contact pair reports: its share of the merged force direction, its
/// own weighted gap and support, and the second's partner.
struct PairReport {
    slots: [usize; 2],
    shares: [f64; 2],
    gaps: [f64; 2],
    areas: [f64; 2],
    partner: Partner,
}
