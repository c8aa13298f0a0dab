//! The search for the contact points' branches (closed or open) on the linearized problem: guess
//! the branches, solve, predict every point's branch from the solution, and repeat until guess and
//! prediction agree (see `contact::point`).
//!
//! Updating every point at once (a primal-dual active-set step) settles in a few updates on most
//! problems, but it can cycle when closing one point opens its neighbours, as on a slender beam
//! pressed by a stiff penalty. Once a guess comes back, the search updates one point at a time,
//! the first whose prediction differs (Murty's least-index rule), which cannot cycle on a
//! positive-definite problem and settles where the block updates would not.

use std::collections::HashSet;

pub struct BranchSearch {
    seen: HashSet<Vec<bool>>,
    /// One point per update (after a cycle).
    single: bool,
    pub updates: usize,
    max_updates: usize,
}

impl BranchSearch {
    pub fn new(max_updates: usize) -> BranchSearch {
        BranchSearch {
            seen: HashSet::new(),
            single: false,
            updates: 0,
            max_updates,
        }
    }

    /// The next guess after guess `closed` predicted `predicted`; None when the search is over
    /// (settled, or out of updates, or back at a guess it tried).
    pub fn next(&mut self, closed: &[bool], predicted: &[bool]) -> Option<Vec<bool>> {
        if closed == predicted || self.updates >= self.max_updates {
            return None;
        }
        self.seen.insert(closed.to_vec());
        if !self.single && self.seen.contains(predicted) {
            self.single = true;
        }
        let next = if self.single {
            let first = (0..closed.len()).find(|&i| closed[i] != predicted[i])?;
            let mut v = closed.to_vec();
            v[first] = predicted[first];
            v
        } else {
            predicted.to_vec()
        };
        if self.seen.contains(&next) {
            return None;
        }
        self.updates += 1;
        Some(next)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_updates_then_single_updates_after_a_cycle() {
        let mut s = BranchSearch::new(10);
        let a = vec![false, false, false];
        let b = vec![true, true, false];
        assert_eq!(s.next(&a, &b), Some(b.clone()));
        // b predicts a again: a cycle; the first differing point alone changes.
        assert_eq!(s.next(&b, &a), Some(vec![false, true, false]));
        assert_eq!(s.next(&b, &b), None);
    }
}
