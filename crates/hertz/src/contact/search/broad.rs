//! Broad phase: an R*-tree over the bounding boxes of a master surface's edges or faces at the
//! current state, rebuilt at every evaluation (bulk loading costs O(n log n)), walked from each
//! contact node outwards in order of box distance.
//!
//! Which boxes a node visits: the narrow phase needs every edge or face on which the node could
//! have its contact point. That point lies within the node's gap of it, and the node's gap to
//! the partner it ends up with is at most the distance to the nearest inside candidate found so
//! far (`best`); a box farther than best plus the item's size (the surface may curve inside its
//! box) plus the node's reach past an open boundary cannot hold a better one. And a partner is
//! sought near the surface point closest to the node: the walk stops once the boxes are farther
//! than the nearest box by twice the largest item size plus the reach, so a node hanging beyond
//! the master, with no inside candidate at all, costs a few projections, not a scan of the
//! surface.

use rstar::primitives::{GeomWithData, Rectangle};
use rstar::RTree;

type Entry = GeomWithData<Rectangle<[f64; 3]>, usize>;

/// The boxes of a surface's items (edges or faces, by index) at one state.
pub struct BroadPhase {
    tree: RTree<Entry>,
    /// Box diagonal of every item.
    sizes: Vec<f64>,
    largest: f64,
}

impl BroadPhase {
    /// The boxes of items with corner positions `items[k]`.
    pub fn new<'a>(items: impl Iterator<Item = &'a [[f64; 3]]>) -> BroadPhase {
        let mut entries = Vec::new();
        let mut sizes = Vec::new();
        for (k, pts) in items.enumerate() {
            let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            for p in pts {
                for i in 0..3 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
            sizes.push((0..3).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt());
            entries.push(GeomWithData::new(Rectangle::from_corners(lo, hi), k));
        }
        let largest = sizes.iter().copied().fold(0.0, f64::max);
        BroadPhase {
            tree: RTree::bulk_load(entries),
            sizes,
            largest,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.sizes.is_empty()
    }

    /// The items whose boxes meet the box [lo, hi].
    pub fn intersecting(&self, lo: [f64; 3], hi: [f64; 3]) -> Vec<usize> {
        let mut out: Vec<usize> = self
            .tree
            .locate_in_envelope_intersecting(rstar::AABB::from_corners(lo, hi))
            .map(|e| e.data)
            .collect();
        out.sort_unstable();
        out
    }

    /// Visit the items that can hold the contact point of a node at `xs` with reach `reach`, in
    /// order of box distance: `visit(k)` projects on item k and returns the |gap| of an inside
    /// candidate, if it found one.
    pub fn walk(&self, xs: [f64; 3], reach: f64, mut visit: impl FnMut(usize) -> Option<f64>) {
        let mut best = f64::INFINITY;
        let mut limit = f64::INFINITY;
        for (entry, d2) in self.tree.nearest_neighbor_iter_with_distance_2(xs) {
            let d = d2.sqrt();
            if limit.is_infinite() {
                limit = d + 2.0 * self.largest + reach;
            }
            if d > limit.min(best + self.largest + reach) {
                break;
            }
            let k = entry.data;
            if d > best + self.sizes[k] + reach {
                continue;
            }
            if let Some(g) = visit(k) {
                best = best.min(g);
            }
        }
    }
}
