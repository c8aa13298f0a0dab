//! Finding each contact node's partner: the broad phase ([`broad`]) lists the edges and faces
//! near a node, the formulation projects the node on them (the narrow phase, in
//! [`super::geometry`]) into candidates, and [`choose`] picks one deterministically and with
//! hysteresis.

pub mod broad;

use super::formulation::Partner;

/// A possible partner of a node at the current state.
#[derive(Debug, Clone, Copy)]
pub struct Candidate {
    pub partner: Partner,
    /// Contact point parameters (edge s, face (ξ, η), polynomial abscissa).
    pub xi: [f64; 2],
    pub gap: f64,
    /// Inside the partner proper (not in the tolerance band that only keeps a previous partner).
    pub inside: bool,
}

/// The candidate with the smallest |gap| among those inside their partner (ties: the first);
/// but the previous partner is kept while it is still a candidate (in its tolerance band too) and
/// not farther than `tie` beyond the closest. A node on a vertex then stays with one edge instead
/// of alternating between the two from one iteration to the next.
pub fn choose(cands: &[Candidate], previous: Option<Partner>, tie: f64) -> Option<Candidate> {
    let best = cands
        .iter()
        .filter(|c| c.inside)
        .min_by(|a, b| a.gap.abs().total_cmp(&b.gap.abs()))
        .copied();
    let kept = previous.and_then(|p| cands.iter().find(|c| c.partner == p).copied());
    match (kept, best) {
        (Some(k), Some(b)) if k.gap.abs() <= b.gap.abs() + tie => Some(k),
        (Some(k), None) => Some(k),
        (_, b) => b,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cand(k: usize, gap: f64, inside: bool) -> Candidate {
        Candidate {
            partner: Partner::Edge(k),
            xi: [0.0; 2],
            gap,
            inside,
        }
    }

    #[test]
    fn previous_partner_is_kept_on_a_tie_and_left_for_a_closer_one() {
        let c = [cand(0, -1e-3, true), cand(1, -1e-3 - 1e-15, true)];
        assert_eq!(choose(&c, None, 1e-12).unwrap().partner, Partner::Edge(0));
        assert_eq!(
            choose(&c, Some(Partner::Edge(1)), 1e-12).unwrap().partner,
            Partner::Edge(1)
        );
        let c = [cand(0, -1e-3, true), cand(1, -0.5, true)];
        assert_eq!(
            choose(&c, Some(Partner::Edge(1)), 1e-12).unwrap().partner,
            Partner::Edge(0)
        );
        // In the tolerance band only: kept when it was the partner, never taken anew.
        let c = [cand(0, -1e-3, false)];
        assert!(choose(&c, None, 1e-12).is_none());
        assert_eq!(
            choose(&c, Some(Partner::Edge(0)), 1e-12).unwrap().partner,
            Partner::Edge(0)
        );
    }
}
