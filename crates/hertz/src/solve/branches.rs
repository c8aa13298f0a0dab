//! The search for the contact points' branches (closed or open) on the linearized problem:
//! guess the branches, solve, predict every
//! point's branch from the solution, and repeat until guess and prediction agree (see
//! `contact::point`).
//!
//! Updating every point at once (a primal-dual active-set step) settles in a few updates on most
//! problems, but it can cycle when closing one point opens its neighbours, as on a slender beam
//! pressed by a stiff penalty. Once a guess comes back, the search updates one point at a time,
//! the first whose prediction differs (Murty's least-index rule), which cannot cycle on a
//! positive-definite problem and settles where the block updates would not.
//!
//! With friction the linearized problem is not symmetric and need not have a consistent choice at
//! all: at a die's trailing corner sliding on a soft block (shallow ironing), opening a node
//! predicts it deep inside and closing it predicts it pulled. When a guess comes back even with
//! single updates, the search has no answer, and which guess's step to take is a choice
//! ([`OnCycle`]).

use crate::contact::slot::Branch;
use std::collections::HashSet;

/// Which guess's step a branch search that comes back to a guess returns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OnCycle {
    /// The last guess: for the predictor of a step, whose first guess is the contact before the
    /// step's motion, the guess furthest from the new contact.
    Last,
    /// The guess with the fewest points predicted otherwise (the latest of equals): for Newton
    /// iterations: the iterate's own branches where the search disagrees, so that the next
    /// iterate decides, rather than a guess that can pull one node hard at a corner.
    FewestMisses,
    /// The fewest-miss guess, the earliest of equals: for a Newton iteration after one whose
    /// cycled search did not lower the residual (the latest of equals there can be a step that
    /// leaves the iterate where it is, which would be chosen again and again).
    FewestMissesEarliest,
}

/// A Newton step of a contact problem, with how its branch search went.
pub struct ContactStep {
    pub du: Vec<f64>,
    /// Branch of every point the step was solved with.
    pub closed: Vec<Branch>,
    /// Number of times the branches were updated.
    pub updates: usize,
    /// The search came back to a guess (the step is then that of the guess [`OnCycle`] says).
    pub cycled: bool,
}

/// The search over guesses of type `T` per point (closed or open).
pub struct BranchSearch<T> {
    seen: HashSet<Vec<T>>,
    /// One point per update (after a cycle).
    single: bool,
    pub updates: usize,
    max_updates: usize,
    /// The search ended at a guess it had tried before.
    pub cycled: bool,
}

impl<T: Clone + Eq + std::hash::Hash> BranchSearch<T> {
    pub fn new(max_updates: usize) -> BranchSearch<T> {
        BranchSearch {
            seen: HashSet::new(),
            single: false,
            updates: 0,
            max_updates,
            cycled: false,
        }
    }

    /// The next guess after guess `closed` predicted `predicted`; None when the search is over
    /// (settled, or out of updates, or back at a guess it tried).
    pub fn next(&mut self, closed: &[T], predicted: &[T]) -> Option<Vec<T>> {
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
            v[first] = predicted[first].clone();
            v
        } else {
            predicted.to_vec()
        };
        if self.seen.contains(&next) {
            self.cycled = true;
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
        assert!(!s.cycled);
    }

    #[test]
    fn a_guess_that_comes_back_in_single_updates_ends_the_search_as_a_cycle() {
        let mut s = BranchSearch::new(10);
        let a = vec![false, true];
        let b = vec![true, true];
        // a predicts b, b predicts a: block updates see a come back, single updates start.
        assert_eq!(s.next(&a, &b), Some(b.clone()));
        assert_eq!(s.next(&b, &a), None);
        assert!(s.cycled);
    }
}
