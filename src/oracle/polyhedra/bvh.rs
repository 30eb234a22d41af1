//! An axis-aligned bounding-box tree over triangles, so that far-away parts of a mesh cost
//! nothing (the last level of the enveloping hierarchy, CHS §2.2 "Enveloping Techniques").
//!
//! Our own small tree rather than parry's `Qbvh`: the interval code must not depend on parry
//! (parry is the independent reference of the tests), and the queries we need are few — boxes
//! and lines. Built once per mesh by median splits along the longest axis of the centroids.

use super::envelope::Aabb;
use nalgebra::Vector3;

/// Most items in one leaf.
const LEAF_SIZE: usize = 4;

#[derive(Clone, Debug)]
struct Node {
    bounds: Aabb,
    /// Leaf: `items[first..first + count]`; inner node (`count == 0`): children `first` and
    /// `first + 1` in `nodes`.
    first: u32,
    count: u32,
}

/// A bounding-box tree over items (triangle indices) with known boxes.
#[derive(Clone, Debug, Default)]
pub(crate) struct Bvh {
    nodes: Vec<Node>,
    items: Vec<u32>,
}

impl Bvh {
    /// A tree over `boxes[i]` for every `i`; the item ids reported by queries are the indices.
    pub(crate) fn build(boxes: &[Aabb]) -> Bvh {
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * boxes.len() / LEAF_SIZE + 1),
            items: (0..boxes.len() as u32).collect(),
        };
        if boxes.is_empty() {
            return bvh;
        }
        let centres: Vec<Vector3<f64>> = boxes.iter().map(Aabb::centre).collect();
        bvh.nodes.push(Node {
            bounds: Aabb::EMPTY,
            first: 0,
            count: 0,
        });
        // explicit stack of (node index, item range) to build without recursion
        let mut stack = vec![(0usize, 0usize, boxes.len())];
        while let Some((node, lo, hi)) = stack.pop() {
            let mut bounds = Aabb::EMPTY;
            let mut cbounds = Aabb::EMPTY;
            for &it in &bvh.items[lo..hi] {
                bounds = bounds.merge(&boxes[it as usize]);
                cbounds.add_point(&centres[it as usize]);
            }
            bvh.nodes[node].bounds = bounds;
            if hi - lo <= LEAF_SIZE {
                bvh.nodes[node].first = lo as u32;
                bvh.nodes[node].count = (hi - lo) as u32;
                continue;
            }
            let ext = cbounds.hi - cbounds.lo;
            let axis = if ext.x >= ext.y && ext.x >= ext.z {
                0
            } else if ext.y >= ext.z {
                1
            } else {
                2
            };
            let mid = (lo + hi) / 2;
            bvh.items[lo..hi].select_nth_unstable_by(mid - lo, |&a, &b| {
                centres[a as usize][axis].total_cmp(&centres[b as usize][axis])
            });
            let left = bvh.nodes.len();
            for _ in 0..2 {
                bvh.nodes.push(Node {
                    bounds: Aabb::EMPTY,
                    first: 0,
                    count: 0,
                });
            }
            bvh.nodes[node].first = left as u32;
            stack.push((left, lo, mid));
            stack.push((left + 1, mid, hi));
        }
        bvh
    }

    /// Number of items.
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.items.len()
    }

    /// Calls `visit` for every item in a leaf whose box passes `test` along the whole path from
    /// the root; stops as soon as `visit` returns `false`. Returns `false` if stopped.
    pub(crate) fn visit(
        &self,
        mut test: impl FnMut(&Aabb) -> bool,
        mut visit: impl FnMut(u32) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return true;
        }
        let mut stack: Vec<u32> = Vec::with_capacity(64);
        stack.push(0);
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            if !test(&node.bounds) {
                continue;
            }
            if node.count > 0 {
                let start = node.first as usize;
                for &it in &self.items[start..start + node.count as usize] {
                    if !visit(it) {
                        return false;
                    }
                }
            } else {
                stack.push(node.first);
                stack.push(node.first + 1);
            }
        }
        true
    }

    /// Number of nodes (for per-call caches indexed by node).
    pub(crate) fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Simultaneous descent of two trees (this one "a", `other` "b") with a window `W` that
    /// narrows on the way down: `test(a_node, a_bounds, b_bounds, w)` returns the window in
    /// which the two nodes' (swept) volumes may meet, or `None` to prune the pair. For each
    /// pair of leaves that survives, `leaves(a_items, b_items, w)` is called; it returns
    /// `false` to stop the whole traversal. Returns `false` if stopped.
    ///
    /// The larger node (by box diagonal) is split first, so that a big robot part is not
    /// compared with tens of thousands of small obstacle leaves one by one.
    pub(crate) fn visit_pairs<W: Copy>(
        &self,
        other: &Bvh,
        init: W,
        mut test: impl FnMut(u32, &Aabb, &Aabb, W) -> Option<W>,
        mut leaves: impl FnMut(&[u32], &[u32], W) -> bool,
    ) -> bool {
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return true;
        }
        let mut stack: Vec<(u32, u32, W)> = Vec::with_capacity(128);
        stack.push((0, 0, init));
        while let Some((a, b, w)) = stack.pop() {
            let (na, nb) = (&self.nodes[a as usize], &other.nodes[b as usize]);
            let Some(w) = test(a, &na.bounds, &nb.bounds, w) else {
                continue;
            };
            let (a_leaf, b_leaf) = (na.count > 0, nb.count > 0);
            if a_leaf && b_leaf {
                let ia = &self.items[na.first as usize..(na.first + na.count) as usize];
                let ib = &other.items[nb.first as usize..(nb.first + nb.count) as usize];
                if !leaves(ia, ib, w) {
                    return false;
                }
            } else if b_leaf
                || (!a_leaf
                    && (na.bounds.hi - na.bounds.lo).norm_squared()
                        >= (nb.bounds.hi - nb.bounds.lo).norm_squared())
            {
                stack.push((na.first, b, w));
                stack.push((na.first + 1, b, w));
            } else {
                stack.push((a, nb.first, w));
                stack.push((a, nb.first + 1, w));
            }
        }
        true
    }

    /// Items whose leaf boxes overlap `query` (a superset of the items whose own boxes do).
    pub(crate) fn visit_overlapping(&self, query: &Aabb, visit: impl FnMut(u32) -> bool) -> bool {
        self.visit(|b| b.overlaps(query), visit)
    }

    /// Items whose leaf boxes meet the infinite line `origin + s·dir` (grown by `margin`).
    pub(crate) fn visit_line(
        &self,
        origin: &Vector3<f64>,
        dir: &Vector3<f64>,
        margin: f64,
        visit: impl FnMut(u32) -> bool,
    ) -> bool {
        self.visit(|b| b.grown(margin).line_range(origin, dir).is_some(), visit)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box(c: [f64; 3]) -> Aabb {
        let c = Vector3::from(c);
        Aabb {
            lo: c.add_scalar(-0.5),
            hi: c.add_scalar(0.5),
        }
    }

    #[test]
    fn box_query_matches_brute_force() {
        let boxes: Vec<Aabb> = (0..200)
            .map(|i| {
                let f = i as f64;
                unit_box([(f * 7.3) % 31.0, (f * 3.1) % 17.0, (f * 1.7) % 13.0])
            })
            .collect();
        let bvh = Bvh::build(&boxes);
        assert_eq!(bvh.len(), 200);
        let q = Aabb {
            lo: Vector3::new(3.0, 2.0, 1.0),
            hi: Vector3::new(12.0, 9.0, 6.0),
        };
        let mut got = Vec::new();
        bvh.visit_overlapping(&q, |i| {
            if boxes[i as usize].overlaps(&q) {
                got.push(i);
            }
            true
        });
        got.sort();
        let want: Vec<u32> = (0..200u32)
            .filter(|&i| boxes[i as usize].overlaps(&q))
            .collect();
        assert_eq!(got, want);
    }

    #[test]
    fn line_query_finds_every_box_on_the_line() {
        let boxes: Vec<Aabb> = (0..50)
            .map(|i| unit_box([i as f64 * 2.0, 0.0, 0.0]))
            .collect();
        let bvh = Bvh::build(&boxes);
        let mut n = 0;
        bvh.visit_line(
            &Vector3::new(-5.0, 0.2, 0.1),
            &Vector3::new(1.0, 0.0, 0.0),
            0.0,
            |_| {
                n += 1;
                true
            },
        );
        assert_eq!(n, 50);
        let mut m = 0;
        bvh.visit_line(
            &Vector3::new(0.0, 3.0, 0.0),
            &Vector3::new(1.0, 0.0, 0.0),
            0.0,
            |_| {
                m += 1;
                true
            },
        );
        assert_eq!(m, 0);
    }
}
