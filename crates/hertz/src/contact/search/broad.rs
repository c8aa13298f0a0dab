//! Broad phase: an R*-tree over the bounding boxes of a master surface's edges or faces at the
//! current state, rebuilt at every evaluation (bulk loading costs O(n log n)), walked from each
//! contact node outwards in order of box distance.
//!
//! Which boxes a node visits: the narrow phase needs every edge or face on which the node could
//! have its contact point. That point lies within the node's gap of it, and the node's gap to
//! the partner it ends up with is at most the distance to the nearest inside candidate found so
//! far (`best`); a box farther than best cannot hold a better one, nor, for an item with an open
//! side, one farther than best plus the node's reach past the open boundary (a node far from a
//! curved master projected on every face in that band: 300 faces of the other dome for the
//! equator nodes of two Gmsh hemispheres, 2.9 of a 9.3 s run). A straight edge or flat face
//! lies in the box of its nodes; a curved (quadratic) one may bulge out of it, so its box is
//! widened by its size. And a partner is sought near the surface point closest to the node:
//! the walk stops once the boxes are farther than the nearest box by twice the nearest item's
//! size plus the reach, so a node hanging beyond the master, with no inside candidate at all,
//! costs a few projections, not a scan of the surface.
//!
//! The bounds are the items' own sizes, not the surface's largest: on a graded mesh (Gmsh's,
//! fine at the contact and coarse far from it) the largest face is ten times the contact zone's,
//! and every node visited every face within that distance (two tetrahedral hemispheres of 25 000
//! nodes: 13–16 s of search in a 25–35 s run).

use rstar::primitives::{GeomWithData, Rectangle};
use rstar::RTree;

type Entry = GeomWithData<Rectangle<[f64; 3]>, usize>;

/// The boxes of a surface's items (edges or faces, by index) at one state.
pub struct BroadPhase {
    tree: RTree<Entry>,
    /// Box diagonal of every item.
    sizes: Vec<f64>,
}

impl BroadPhase {
    /// The boxes of items with node positions `items[k]` and whether each is curved.
    pub fn new<'a>(items: impl Iterator<Item = (&'a [[f64; 3]], bool)>) -> BroadPhase {
        let mut entries = Vec::new();
        let mut sizes = Vec::new();
        for (k, (pts, curved)) in items.enumerate() {
            let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            for p in pts {
                for i in 0..3 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
            let size = (0..3).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt();
            if curved {
                for i in 0..3 {
                    lo[i] -= size;
                    hi[i] += size;
                }
            }
            sizes.push(size);
            entries.push(GeomWithData::new(Rectangle::from_corners(lo, hi), k));
        }
        BroadPhase {
            tree: RTree::bulk_load(entries),
            sizes,
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
    /// candidate, if it found one. Only an item with an open side (`open(k)`: a contact point
    /// past it counts within the reach) is visited past the best |gap| so far; any other holds
    /// its contact point on itself, no nearer than its box.
    pub fn walk(
        &self,
        xs: [f64; 3],
        reach: f64,
        open: impl Fn(usize) -> bool,
        mut visit: impl FnMut(usize) -> Option<f64>,
    ) {
        let mut best = f64::INFINITY;
        let mut limit = f64::INFINITY;
        for (entry, d2) in self.tree.nearest_neighbor_iter_with_distance_2(xs) {
            let d = d2.sqrt();
            let k = entry.data;
            if limit.is_infinite() {
                limit = d + 2.0 * self.sizes[k] + reach;
            }
            if d > limit.min(best + reach) {
                break;
            }
            if d > best && !open(k) {
                continue;
            }
            if let Some(g) = visit(k) {
                best = best.min(g);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A row of flat squares in z = 0 graded from 0.01 wide at the origin to 0.64 wide far
    /// from it, and a node 0.001 above the middle of the first: the walk visits the square
    /// under it and its neighbours, not every square within the largest's size (a 0.64 square
    /// 1.3 away would have kept it walking over all of them), and finds the square under it.
    #[test]
    fn a_graded_surface_is_walked_by_the_local_sizes() {
        let mut squares: Vec<Vec<[f64; 3]>> = Vec::new();
        let (mut x, mut w) = (0.0, 0.01);
        while x < 2.0 {
            squares.push(vec![
                [x, 0.0, 0.0],
                [x + w, 0.0, 0.0],
                [x + w, w, 0.0],
                [x, w, 0.0],
            ]);
            x += w;
            w = (w * 1.5).min(0.64);
        }
        let broad = BroadPhase::new(squares.iter().map(|v| (&v[..], false)));
        let node = [0.005, 0.005, 0.001];
        let mut visited = Vec::new();
        broad.walk(
            node,
            0.0,
            |_| false,
            |k| {
                visited.push(k);
                // The gap to square k, an inside candidate where the node is above it.
                let s = &squares[k];
                (node[0] >= s[0][0] && node[0] <= s[1][0]).then_some(node[2])
            },
        );
        assert!(visited.contains(&0), "{visited:?}");
        assert!(
            visited.len() <= 3,
            "{} of {}: {visited:?}",
            visited.len(),
            squares.len()
        );
    }

    /// A row of 0.1 squares along x and a node 1 above the middle of the tenth: the square under
    /// it is an inside candidate at |gap| 1, and every other square's box is farther, so it is
    /// the only one projected (a far node of two Gmsh hemispheres projected on 300 faces of the
    /// other dome before). Squares with an open side are walked on to the best |gap| plus the
    /// reach (0.3): the eight within 0.8 of the foot on either side.
    #[test]
    fn a_far_node_projects_on_the_items_nearer_than_its_best_gap() {
        let squares: Vec<Vec<[f64; 3]>> = (0..20)
            .map(|i| {
                let x = i as f64 * 0.1;
                vec![
                    [x, 0.0, 0.0],
                    [x + 0.1, 0.0, 0.0],
                    [x + 0.1, 0.1, 0.0],
                    [x, 0.1, 0.0],
                ]
            })
            .collect();
        let broad = BroadPhase::new(squares.iter().map(|v| (&v[..], false)));
        let node = [0.95, 0.05, 1.0];
        let walk = |open: bool| {
            let mut visited = Vec::new();
            broad.walk(
                node,
                0.3,
                |_| open,
                |k| {
                    visited.push(k);
                    let s = &squares[k];
                    (node[0] >= s[0][0] && node[0] <= s[1][0]).then_some(node[2])
                },
            );
            visited.sort_unstable();
            visited
        };
        assert_eq!(walk(false), vec![9]);
        assert_eq!(walk(true), (1..18).collect::<Vec<_>>());
    }
}
