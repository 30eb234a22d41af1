//! One bounding-box tree for both rigid-body oracles: obstacle edges, triangles and reference
//! points in the plane, robot and obstacle faces in space, so that far-away parts cost nothing
//! (the last level of the enveloping hierarchy, CHS §2.2 "Enveloping Techniques").
//!
//! Our own small tree rather than parry's: the interval code must not depend on parry (parry is
//! the independent reference of the tests), and the queries we need are few — a box test
//! (swept box, annulus, cylinder sector) down one tree, or two trees descended together with a
//! window of the motion parameter that narrows on the way down. Built once per mesh by median
//! splits along the longest axis of the item centres. Queries recurse (the depth is
//! `log2(n / LEAF_SIZE)`, median splits keep it so) and never touch the heap.

use super::aabb::Aabb;
use crate::interval::Interval;
use std::ops::ControlFlow;

/// Most items in one leaf.
const LEAF_SIZE: usize = 4;

#[derive(Clone, Debug)]
struct Node<const D: usize> {
    bounds: Aabb<D>,
    /// Leaf: `items[first..first + count]`; inner node (`count == 0`): children `first` and
    /// `first + 1` in `nodes`.
    first: u32,
    count: u32,
}

/// A bounding-box tree over items `0..n` with known boxes (kept, for the item-level test of
/// [`Bvh::query`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct Bvh<const D: usize> {
    nodes: Vec<Node<D>>,
    items: Vec<u32>,
    boxes: Vec<Aabb<D>>,
}

impl<const D: usize> Bvh<D> {
    /// A tree over `boxes[i]` for every `i`; the item ids reported by queries are the indices.
    pub(crate) fn build(boxes: Vec<Aabb<D>>) -> Bvh<D> {
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * boxes.len() / LEAF_SIZE + 1),
            items: (0..boxes.len() as u32).collect(),
            boxes,
        };
        if bvh.boxes.is_empty() {
            return bvh;
        }
        let boxes = &bvh.boxes;
        let centres: Vec<_> = boxes.iter().map(Aabb::centre).collect();
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
            // the first longest axis
            let mut axis = 0;
            for k in 1..D {
                if ext[k] > ext[axis] {
                    axis = k;
                }
            }
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

    /// The same tree over the items moved by `d` (every box shifted): a body placed with a
    /// different reference point keeps its tree instead of rebuilding it. Rounding is
    /// monotone, so a shifted box still holds its shifted item.
    pub(crate) fn shifted(&self, d: &nalgebra::SVector<f64, D>) -> Bvh<D> {
        Bvh {
            nodes: self
                .nodes
                .iter()
                .map(|n| Node {
                    bounds: n.bounds.shifted(d),
                    ..*n
                })
                .collect(),
            items: self.items.clone(),
            boxes: self.boxes.iter().map(|b| b.shifted(d)).collect(),
        }
    }

    /// Number of items.
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.items.len()
    }

    /// Number of nodes (for per-call caches indexed by node).
    pub(crate) fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Calls `visit` for every item in a leaf whose box passes `test` along the whole path from
    /// the root; stops as soon as `visit` returns `false`. Returns `false` if stopped.
    pub(crate) fn visit(
        &self,
        mut test: impl FnMut(&Aabb<D>) -> bool,
        mut visit: impl FnMut(u32) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return true;
        }
        self.descend(0, &mut test, &mut visit)
    }

    /// Depth first below `node`, the second child before the first.
    fn descend(
        &self,
        node: u32,
        test: &mut impl FnMut(&Aabb<D>) -> bool,
        visit: &mut impl FnMut(u32) -> bool,
    ) -> bool {
        let n = &self.nodes[node as usize];
        if !test(&n.bounds) {
            return true;
        }
        if n.count > 0 {
            let start = n.first as usize;
            return self.items[start..start + n.count as usize]
                .iter()
                .all(|&it| visit(it));
        }
        self.descend(n.first + 1, test, visit) && self.descend(n.first, test, visit)
    }

    /// Like [`Bvh::visit`], but each item's own box must pass `overlaps` too (the test of the
    /// polygon oracle's swept boxes and annuli); `visit` breaks to stop, and the break is
    /// returned.
    pub(crate) fn query<B>(
        &self,
        mut overlaps: impl FnMut(&Aabb<D>) -> bool,
        mut visit: impl FnMut(usize) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        if self.nodes.is_empty() {
            return ControlFlow::Continue(());
        }
        self.descend_items(0, &mut overlaps, &mut visit)
    }

    fn descend_items<B>(
        &self,
        node: u32,
        overlaps: &mut impl FnMut(&Aabb<D>) -> bool,
        visit: &mut impl FnMut(usize) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        let n = &self.nodes[node as usize];
        if !overlaps(&n.bounds) {
            return ControlFlow::Continue(());
        }
        if n.count == 0 {
            self.descend_items(n.first + 1, overlaps, visit)?;
            return self.descend_items(n.first, overlaps, visit);
        }
        let start = n.first as usize;
        for &it in &self.items[start..start + n.count as usize] {
            if overlaps(&self.boxes[it as usize]) {
                visit(it as usize)?;
            }
        }
        ControlFlow::Continue(())
    }

    /// Like [`Bvh::query`] for a moving box: `window` gives the interval of the motion
    /// parameter in which the box meets a node's or an item's box (`None` prunes), and `visit`
    /// gets each item with its own window. Lets a sweep narrow its window per item while it
    /// descends, instead of testing one box around the whole sweep. Both see `ctx` (the hits
    /// so far, say, so that a node whose window is known to collide is skipped whole). Of two
    /// children, the one met earlier is entered first: a yes/no question stops at the first
    /// collision, which more often lies where the moving box arrives first (and a
    /// first-collision question wants that one anyway).
    pub(crate) fn query_windows<C, B>(
        &self,
        ctx: &mut C,
        mut window: impl FnMut(&C, &Aabb<D>) -> Option<Interval>,
        mut visit: impl FnMut(&mut C, u32, Interval) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        let Some(root) = self.nodes.first() else {
            return ControlFlow::Continue(());
        };
        match window(ctx, &root.bounds) {
            Some(_) => self.descend_windows(0, ctx, &mut window, &mut visit),
            None => ControlFlow::Continue(()),
        }
    }

    /// Below `node`, whose own window is not empty.
    fn descend_windows<C, B>(
        &self,
        node: u32,
        ctx: &mut C,
        window: &mut impl FnMut(&C, &Aabb<D>) -> Option<Interval>,
        visit: &mut impl FnMut(&mut C, u32, Interval) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        let n = &self.nodes[node as usize];
        if n.count > 0 {
            let start = n.first as usize;
            for &it in &self.items[start..start + n.count as usize] {
                if let Some(w) = window(ctx, &self.boxes[it as usize]) {
                    visit(ctx, it, w)?;
                }
            }
            return ControlFlow::Continue(());
        }
        let (a, b) = (n.first + 1, n.first);
        let wa = window(ctx, &self.nodes[a as usize].bounds);
        let wb = window(ctx, &self.nodes[b as usize].bounds);
        let (first, second) = match (wa, wb) {
            (Some(x), Some(y)) if y.lo < x.lo => ((b, true), (a, true)),
            (x, y) => ((a, x.is_some()), (b, y.is_some())),
        };
        self.descend_windows_if(first, ctx, window, visit)?;
        self.descend_windows_if(second, ctx, window, visit)
    }

    /// The second child is tested again after the first: what the first found may cover it.
    fn descend_windows_if<C, B>(
        &self,
        (child, met): (u32, bool),
        ctx: &mut C,
        window: &mut impl FnMut(&C, &Aabb<D>) -> Option<Interval>,
        visit: &mut impl FnMut(&mut C, u32, Interval) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        if met && window(ctx, &self.nodes[child as usize].bounds).is_some() {
            self.descend_windows(child, ctx, window, visit)?;
        }
        ControlFlow::Continue(())
    }

    /// Simultaneous descent of two trees (this one "a", `other` "b") with a window `W` that
    /// narrows on the way down: `test(a_node, b_node, a_bounds, b_bounds, w)` returns the
    /// window in which the two nodes' (swept) volumes may meet, or `None` to prune the pair.
    /// For each pair of leaves that survives, `leaves(a_items, b_items, w)` is called with the
    /// window `test` gave that pair; it returns `false` to stop the whole traversal. Returns
    /// `false` if stopped. The node ids let callers keep per-call bounds of either tree's
    /// nodes (`Memo`): a node meets many nodes of the other tree.
    ///
    /// The larger node (by box diagonal) is split first, so that a big robot part is not
    /// compared with tens of thousands of small obstacle leaves one by one.
    pub(crate) fn visit_pairs<W: Copy>(
        &self,
        other: &Bvh<D>,
        init: W,
        mut test: impl FnMut(u32, u32, &Aabb<D>, &Aabb<D>, W) -> Option<W>,
        mut leaves: impl FnMut(&[u32], &[u32], W) -> bool,
    ) -> bool {
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return true;
        }
        self.pairs(other, 0, 0, init, &mut test, &mut leaves)
    }

    fn pairs<W: Copy>(
        &self,
        other: &Bvh<D>,
        a: u32,
        b: u32,
        w: W,
        test: &mut impl FnMut(u32, u32, &Aabb<D>, &Aabb<D>, W) -> Option<W>,
        leaves: &mut impl FnMut(&[u32], &[u32], W) -> bool,
    ) -> bool {
        let (na, nb) = (&self.nodes[a as usize], &other.nodes[b as usize]);
        let Some(w) = test(a, b, &na.bounds, &nb.bounds, w) else {
            return true;
        };
        match self.split(other, a, b) {
            None => leaves(self.leaf_items(na), other.leaf_items(nb), w),
            Some([(x1, y1), (x2, y2)]) => {
                self.pairs(other, x1, y1, w, test, leaves)
                    && self.pairs(other, x2, y2, w, test, leaves)
            }
        }
    }

    /// The two child pairs of the node pair `(a, b)` (`None`: two leaves): the larger node (by
    /// box diagonal) is split, a leaf never.
    fn split(&self, other: &Bvh<D>, a: u32, b: u32) -> Option<[(u32, u32); 2]> {
        let (na, nb) = (&self.nodes[a as usize], &other.nodes[b as usize]);
        let (a_leaf, b_leaf) = (na.count > 0, nb.count > 0);
        if a_leaf && b_leaf {
            None
        } else if b_leaf
            || (!a_leaf
                && (na.bounds.hi - na.bounds.lo).norm_squared()
                    >= (nb.bounds.hi - nb.bounds.lo).norm_squared())
        {
            Some([(na.first + 1, b), (na.first, b)])
        } else {
            Some([(a, nb.first + 1), (a, nb.first)])
        }
    }

    /// The items of leaf `n`.
    fn leaf_items(&self, n: &Node<D>) -> &[u32] {
        &self.items[n.first as usize..(n.first + n.count) as usize]
    }

    /// [`Bvh::visit_pairs`] for a question about the *earliest* collision: of the two child
    /// pairs of a split, the one whose window starts first (`start`) is descended first, and a
    /// pair whose window `skip` says cannot matter any more (it starts after the earliest
    /// collision found so far) is pruned, tested or not. The same node tests as the plain
    /// descent, fewer of them: deep pairs behind an early hit are never reached.
    pub(crate) fn visit_pairs_earliest<W: Copy>(
        &self,
        other: &Bvh<D>,
        init: W,
        mut test: impl FnMut(u32, u32, &Aabb<D>, &Aabb<D>, W) -> Option<W>,
        mut leaves: impl FnMut(&[u32], &[u32], W) -> bool,
        start: impl Fn(&W) -> f64,
        skip: impl Fn(&W) -> bool,
    ) -> bool {
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return true;
        }
        let Some(w) = test(0, 0, &self.nodes[0].bounds, &other.nodes[0].bounds, init) else {
            return true;
        };
        self.pairs_earliest(other, 0, 0, w, &mut test, &mut leaves, &start, &skip)
    }

    #[allow(clippy::too_many_arguments)]
    fn pairs_earliest<W: Copy>(
        &self,
        other: &Bvh<D>,
        a: u32,
        b: u32,
        w: W,
        test: &mut impl FnMut(u32, u32, &Aabb<D>, &Aabb<D>, W) -> Option<W>,
        leaves: &mut impl FnMut(&[u32], &[u32], W) -> bool,
        start: &impl Fn(&W) -> f64,
        skip: &impl Fn(&W) -> bool,
    ) -> bool {
        if skip(&w) {
            return true;
        }
        let Some(kids) = self.split(other, a, b) else {
            let (na, nb) = (&self.nodes[a as usize], &other.nodes[b as usize]);
            return leaves(self.leaf_items(na), other.leaf_items(nb), w);
        };
        let tested = kids.map(|(x, y)| {
            test(
                x,
                y,
                &self.nodes[x as usize].bounds,
                &other.nodes[y as usize].bounds,
                w,
            )
            .map(|wk| (x, y, wk))
        });
        let [first, second] = match tested {
            [Some(p), Some(q)] if start(&q.2) < start(&p.2) => [Some(q), Some(p)],
            t => t,
        };
        for (x, y, wk) in first.into_iter().chain(second) {
            if !self.pairs_earliest(other, x, y, wk, test, leaves, start, skip) {
                return false;
            }
        }
        true
    }

    /// Items whose leaf boxes overlap `query` (a superset of the items whose own boxes do).
    pub(crate) fn visit_overlapping(
        &self,
        query: &Aabb<D>,
        visit: impl FnMut(u32) -> bool,
    ) -> bool {
        self.visit(|b| b.overlaps(query), visit)
    }
}

impl Bvh<3> {
    /// Items whose leaf boxes meet the infinite line `origin + s·dir` (grown by `margin`).
    pub(crate) fn visit_line(
        &self,
        origin: &nalgebra::Vector3<f64>,
        dir: &nalgebra::Vector3<f64>,
        margin: f64,
        visit: impl FnMut(u32) -> bool,
    ) -> bool {
        self.visit(|b| b.grown(margin).line_range(origin, dir).is_some(), visit)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    fn unit_box(c: [f64; 3]) -> Aabb<3> {
        let c = Vector3::from(c);
        Aabb {
            lo: c.add_scalar(-0.5),
            hi: c.add_scalar(0.5),
        }
    }

    #[test]
    fn box_query_matches_brute_force() {
        let boxes: Vec<Aabb<3>> = (0..200)
            .map(|i| {
                let f = i as f64;
                unit_box([(f * 7.3) % 31.0, (f * 3.1) % 17.0, (f * 1.7) % 13.0])
            })
            .collect();
        let bvh = Bvh::build(boxes.clone());
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
        // the item-level query reports exactly the overlapping boxes
        let mut exact = Vec::new();
        let _ = bvh.query::<()>(
            |b| b.overlaps(&q),
            |i| {
                exact.push(i as u32);
                ControlFlow::Continue(())
            },
        );
        exact.sort();
        assert_eq!(exact, want);
    }

    #[test]
    fn plane_query_finds_exactly_the_overlapping_boxes() {
        // a 20 × 20 grid of boxes, queried with assorted windows
        let boxes: Vec<Aabb<2>> = (0..400)
            .map(|i| {
                let (x, y) = ((i % 20) as f64, (i / 20) as f64);
                Aabb::of_plane_points(&[[x, y], [x + 0.5, y + 0.5]])
            })
            .collect();
        let bvh = Bvh::build(boxes.clone());
        for w in [
            ([2.2, 3.1], [5.7, 3.2]),
            ([-1.0, -1.0], [0.1, 0.1]),
            ([19.4, 19.4], [30.0, 30.0]),
            ([0.6, 0.6], [0.9, 0.9]),
            ([-5.0, -5.0], [25.0, 25.0]),
        ] {
            let window = Aabb::of_plane_points(&[w.0, w.1]);
            let mut found = Vec::new();
            let _ = bvh.query::<()>(
                |b| b.overlaps(&window),
                |i| {
                    found.push(i);
                    ControlFlow::Continue(())
                },
            );
            found.sort_unstable();
            let expected: Vec<usize> = (0..boxes.len())
                .filter(|&i| boxes[i].overlaps(&window))
                .collect();
            assert_eq!(found, expected, "window {w:?}");
        }
    }

    #[test]
    fn empty_tree_and_early_exit() {
        let empty = Bvh::<2>::build(Vec::new());
        assert!(empty
            .query::<()>(|_| true, |_| ControlFlow::Break(()))
            .is_continue());
        assert!(empty.visit_pairs(&empty, (), |_, _, _, _, _| Some(()), |_, _, _| false));
        let one = Bvh::build(vec![Aabb::of_plane_points(&[[0.0, 0.0], [1.0, 2.0]]); 10]);
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
    fn pairs_of_leaves_cover_every_overlapping_pair() {
        let a: Vec<Aabb<3>> = (0..60)
            .map(|i| unit_box([i as f64 * 0.7, (i % 7) as f64, 0.0]))
            .collect();
        let b: Vec<Aabb<3>> = (0..80)
            .map(|i| unit_box([(i % 13) as f64 * 3.0, (i / 13) as f64, 0.3]))
            .collect();
        let (ta, tb) = (Bvh::build(a.clone()), Bvh::build(b.clone()));
        let mut got = Vec::new();
        ta.visit_pairs(
            &tb,
            (),
            |_, _, x, y, ()| x.overlaps(y).then_some(()),
            |ia, ib, ()| {
                for &i in ia {
                    for &j in ib {
                        if a[i as usize].overlaps(&b[j as usize]) {
                            got.push((i, j));
                        }
                    }
                }
                true
            },
        );
        got.sort();
        let mut want = Vec::new();
        for i in 0..a.len() as u32 {
            for j in 0..b.len() as u32 {
                if a[i as usize].overlaps(&b[j as usize]) {
                    want.push((i, j));
                }
            }
        }
        assert!(!want.is_empty());
        assert_eq!(got, want);
    }

    #[test]
    fn line_query_finds_every_box_on_the_line() {
        let boxes: Vec<Aabb<3>> = (0..50)
            .map(|i| unit_box([i as f64 * 2.0, 0.0, 0.0]))
            .collect();
        let bvh = Bvh::build(boxes);
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
