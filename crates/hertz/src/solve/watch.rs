//! What the Newton iterations of an attempt show that can explain its failure (nodes that
//! chatter between contact states, a penalty beyond double precision), and what is warned of
//! once per analysis.

use crate::contact::SlotState;
use crate::model::Model;

/// What the iterations of an attempt showed that can explain its failure, and what is warned of
/// once per analysis.
pub(super) struct Watch {
    /// The node of every contact point (for messages).
    pub slot_nodes: Vec<usize>,
    /// Per contact point: how often in the current attempt its partner and branch went back to
    /// what they were two iterations before (A → B → A: chattering, not sliding on).
    pub flips: Vec<usize>,
    /// How far the estimated round-off floor of penalty forces exceeded the tolerance in the
    /// last iteration of a failed attempt, if it did.
    pub floor_dominated: Option<f64>,
    /// The round-off floor warning was given.
    pub floor_warned: bool,
    /// The warning of active contact nodes without area was given.
    pub arealess_warned: bool,
}

impl Watch {
    /// Count the contact points whose partner and branch went back to what they were two
    /// iterations before (`before`), from `last` to `states`.
    pub fn count_flips(&mut self, states: &[SlotState], last: &[SlotState], before: &[SlotState]) {
        let key = |s: &SlotState| (s.partner, s.active);
        for (k, s) in states.iter().enumerate() {
            if key(s) != key(&last[k]) && key(s) == key(&before[k]) {
                self.flips[k] += 1;
            }
        }
    }

    /// The nodes that chattered most, in words.
    pub fn chatter(&self, model: &Model) -> Option<String> {
        let mut chatter: Vec<(usize, usize)> = self
            .flips
            .iter()
            .enumerate()
            .filter(|(_, &f)| f >= 2)
            .map(|(k, &f)| (f, k))
            .collect();
        chatter.sort_unstable_by(|a, b| b.cmp(a));
        (!chatter.is_empty()).then(|| {
            let labels: Vec<String> = chatter
                .iter()
                .take(8)
                .map(|&(f, k)| format!("{} ({f}×)", model.nodes[self.slot_nodes[k]].label))
                .collect();
            format!(
                "contact nodes went back and forth between states (chattering): {}{}",
                labels.join(", "),
                if chatter.len() > 8 { ", …" } else { "" }
            )
        })
    }
}

/// Whether a closed frictional contact point went back to the stick or slip it had two
/// iterations before (`before`), from `last` to `states` (A → B → A), on the same partner.
pub(super) fn stick_slip_cycles(
    states: &[SlotState],
    last: &[SlotState],
    before: &[SlotState],
) -> bool {
    let stick = |s: &SlotState| s.friction.map(|f| f.0);
    states.iter().zip(last).zip(before).any(|((s, l), b)| {
        let held = [s, l, b].iter().all(|x| x.active && x.partner == s.partner);
        held && stick(s).is_some() && stick(s) != stick(l) && stick(s) == stick(b)
    })
}
