//! A static AABB tree over obstacle primitives (edges, triangles, reference vertices), so that
//! far-away obstacle parts cost nothing (the "enveloping" of CHS §2.2, taken to a hierarchy).
//!
//! Built once, top-down by median splits along the longer side; queried with any predicate on
//! boxes (a swept box for a translation, an annulus for a rotation), with early exit.

use std::ops::ControlFlow;

/// An axis-aligned box `[min, max]` in the plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Aabb {
    /// Lower corner.
    pub min: [f64; 2],
    /// Upper corner.
    pub max: [f64; 2],
}

impl Aabb {
    /// The box that contains nothing (the identity of [`Aabb::merge`]).
    pub const EMPTY: Aabb = Aabb {
        min: [f64::INFINITY; 2],
        max: [f64::NEG_INFINITY; 2],
    };

    /// The smallest box containing `points`.
    pub fn of_points(points: &[[f64; 2]]) -> Aabb {
        points.iter().fold(Aabb::EMPTY, |b, p| b.merge_point(*p))
    }

    /// This box grown to contain `p`.
    pub fn merge_point(self, p: [f64; 2]) -> Aabb {
        Aabb {
            min: [self.min[0].min(p[0]), self.min[1].min(p[1])],
            max: [self.max[0].max(p[0]), self.max[1].max(p[1])],
        }
    }

    /// The smallest box containing both.
    pub fn merge(self, o: Aabb) -> Aabb {
        Aabb {
            min: [self.min[0].min(o.min[0]), self.min[1].min(o.min[1])],
            max: [self.max[0].max(o.max[0]), self.max[1].max(o.max[1])],
        }
    }

    /// Whether the closed boxes share a point.
    pub fn intersects(&self, o: &Aabb) -> bool {
        self.min[0] <= o.max[0]
            && o.min[0] <= self.max[0]
            && self.min[1] <= o.max[1]
            && o.min[1] <= self.max[1]
    }

    /// Centre of the box.
    pub fn centre(&self) -> [f64; 2] {
        [
            0.5 * (self.min[0] + self.max[0]),
            0.5 * (self.min[1] + self.max[1]),
        ]
    }

    /// Half of the side lengths.
    pub fn half_extents(&self) -> [f64; 2] {
        [
            0.5 * (self.max[0] - self.min[0]),
            0.5 * (self.max[1] - self.min[1]),
        ]
    }

    /// Square of the smallest distance from `p` to the box (0 inside).
    pub fn distance_squared_to(&self, p: [f64; 2]) -> f64 {
        let dx = (self.min[0] - p[0]).max(p[0] - self.max[0]).max(0.0);
        let dy = (self.min[1] - p[1]).max(p[1] - self.max[1]).max(0.0);
        dx * dx + dy * dy
    }

    /// Square of the largest distance from `p` to a point of the box (its farthest corner).
    pub fn farthest_squared_from(&self, p: [f64; 2]) -> f64 {
        let dx = (p[0] - self.min[0]).abs().max((self.max[0] - p[0]).abs());
        let dy = (p[1] - self.min[1]).abs().max((self.max[1] - p[1]).abs());
        dx * dx + dy * dy
    }
}

#[derive(Clone, Debug)]
struct Node {
    aabb: Aabb,
    /// For a leaf, the range `start..start + count` of `Bvh::order`; for an inner node,
    /// `count == 0` and the children are `start` and `start + 1`.
    start: u32,
    count: u32,
}

/// A bounding-volume hierarchy over items numbered `0..n` with given boxes.
#[derive(Clone, Debug, Default)]
pub(crate) struct Bvh {
    nodes: Vec<Node>,
    /// Item numbers in leaf order.
    order: Vec<u32>,
    /// Box of every item, by item number.
    boxes: Vec<Aabb>,
}

/// Items per leaf.
const LEAF_SIZE: usize = 4;

impl Bvh {
    /// A tree over `boxes` (item `i` has box `boxes[i]`).
    pub fn new(boxes: Vec<Aabb>) -> Bvh {
        let mut bvh = Bvh {
            nodes: Vec::new(),
            order: (0..boxes.len() as u32).collect(),
            boxes,
        };
        if !bvh.boxes.is_empty() {
            bvh.nodes.push(Node {
                aabb: Aabb::EMPTY,
                start: 0,
                count: 0,
            });
            bvh.build(0, 0, bvh.order.len());
        }
        bvh
    }

    fn build(&mut self, node: usize, lo: usize, hi: usize) {
        let aabb = self.order[lo..hi]
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.merge(self.boxes[i as usize]));
        self.nodes[node].aabb = aabb;
        if hi - lo <= LEAF_SIZE {
            self.nodes[node].start = lo as u32;
            self.nodes[node].count = (hi - lo) as u32;
            return;
        }
        let h = aabb.half_extents();
        let axis = usize::from(h[1] > h[0]);
        let mid = lo + (hi - lo) / 2;
        let boxes = &self.boxes;
        self.order[lo..hi].select_nth_unstable_by(mid - lo, |&a, &b| {
            let ca = boxes[a as usize].centre()[axis];
            let cb = boxes[b as usize].centre()[axis];
            ca.total_cmp(&cb)
        });
        let left = self.nodes.len();
        let blank = Node {
            aabb: Aabb::EMPTY,
            start: 0,
            count: 0,
        };
        self.nodes.push(blank.clone());
        self.nodes.push(blank);
        self.nodes[node].start = left as u32;
        self.nodes[node].count = 0;
        self.build(left, lo, mid);
        self.build(left + 1, mid, hi);
    }

    /// Calls `visit` for every item whose box satisfies `overlaps` (tested on the boxes of the
    /// inner nodes first, so that whole subtrees are skipped). Stops when `visit` breaks.
    pub fn query<B>(
        &self,
        mut overlaps: impl FnMut(&Aabb) -> bool,
        mut visit: impl FnMut(usize) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        if self.nodes.is_empty() {
            return ControlFlow::Continue(());
        }
        self.descend(0, &mut overlaps, &mut visit)
    }

    /// Depth-first below `node`; the recursion is as deep as the tree (median splits keep it
    /// at `log2(n)`), and needs no heap.
    fn descend<B>(
        &self,
        node: usize,
        overlaps: &mut impl FnMut(&Aabb) -> bool,
        visit: &mut impl FnMut(usize) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        let n = &self.nodes[node];
        if !overlaps(&n.aabb) {
            return ControlFlow::Continue(());
        }
        if n.count == 0 {
            self.descend(n.start as usize, overlaps, visit)?;
            return self.descend(n.start as usize + 1, overlaps, visit);
        }
        let (s, c) = (n.start as usize, n.count as usize);
        for &item in &self.order[s..s + c] {
            if overlaps(&self.boxes[item as usize]) {
                visit(item as usize)?;
            }
        }
        ControlFlow::Continue(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn query_finds_exactly_the_overlapping_boxes() {
        // a 20 × 20 grid of unit boxes, queried with assorted windows
        let boxes: Vec<Aabb> = (0..400)
            .map(|i| {
                let (x, y) = ((i % 20) as f64, (i / 20) as f64);
                Aabb {
                    min: [x, y],
                    max: [x + 0.5, y + 0.5],
                }
            })
            .collect();
        let bvh = Bvh::new(boxes.clone());
        for (k, w) in [
            ([2.2, 3.1], [5.7, 3.2]),
            ([-1.0, -1.0], [0.1, 0.1]),
            ([19.4, 19.4], [30.0, 30.0]),
            ([0.6, 0.6], [0.9, 0.9]),
            ([-5.0, -5.0], [25.0, 25.0]),
        ]
        .into_iter()
        .enumerate()
        {
            let window = Aabb { min: w.0, max: w.1 };
            let mut found = Vec::new();
            let _ = bvh.query::<()>(
                |b| b.intersects(&window),
                |i| {
                    found.push(i);
                    ControlFlow::Continue(())
                },
            );
            found.sort_unstable();
            let expected: Vec<usize> = (0..boxes.len())
                .filter(|&i| boxes[i].intersects(&window))
                .collect();
            assert_eq!(found, expected, "window {k}");
        }
    }

    #[test]
    fn empty_tree_and_early_exit() {
        let empty = Bvh::new(Vec::new());
        assert!(empty
            .query::<()>(|_| true, |_| ControlFlow::Break(()))
            .is_continue());
        let one = Bvh::new(vec![Aabb::of_points(&[[0.0, 0.0], [1.0, 2.0]]); 10]);
        let mut seen = 0;
        let r = one.query(
            |_| true,
            |_| {
                seen += 1;
                ControlFlow::Break(())
            },
        );
        assert!(r.is_break());
        assert_eq!(seen, 1);
    }

    #[test]
    fn distances_to_a_box() {
        let b = Aabb {
            min: [0.0, 0.0],
            max: [2.0, 1.0],
        };
        assert_eq!(b.distance_squared_to([1.0, 0.5]), 0.0);
        assert_eq!(b.distance_squared_to([5.0, 5.0]), 25.0);
        assert_eq!(b.farthest_squared_from([0.0, 0.0]), 5.0);
    }
}
