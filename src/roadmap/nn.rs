//! Nearest neighbours of roadmap nodes without scanning all of them.
//!
//! [`KdTree`] is a small incremental kd-tree over points whose dimension is known only at run
//! time: nodes are inserted one at a time while the roadmap grows, leaves hold buckets of up to
//! [`KdTree::BUCKET`] points and split at the median of their widest coordinate when they
//! overflow. [`NearestNeighbours`] puts configurations into it through
//! [`Space::embeddings`] and re-ranks the candidates by [`Space::distance`].
//!
//! Every embedding is a lower bound of the space's distance (`‖e(a) − e(b)‖ ≤ distance(a, b)`:
//! a chord is never longer than its arc, and `√(x² + y²) ≤ x + y`), so a radius filter in
//! embedded space never loses a node that lies within the radius. For R^n the embedding is the
//! identity and the k nearest are exact; for SE(2) and SE(3) the index fetches more candidates
//! than asked for and re-ranks them by the space's distance; if the k-th of those is farther
//! than the tree's search reached, a second search within that distance fetches every node
//! that could beat it, so the k nearest are exact there too.

use crate::space::{Space, SpaceKind};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// One node of the tree.
#[derive(Clone, Debug)]
enum Node {
    /// Indices of the points stored here.
    Leaf(Vec<u32>),
    /// Points with `p[axis] < value` go to `children[0]`, the others to `children[1]`.
    Split {
        axis: usize,
        value: f64,
        children: [u32; 2],
    },
}

/// An incremental kd-tree of points in R^d, each carrying a `u32` id (several points may share
/// one id: SE(3) puts `q` and `−q` of one node into the tree).
#[derive(Clone, Debug)]
pub struct KdTree {
    dim: usize,
    /// Coordinates, `dim` per point.
    coords: Vec<f64>,
    /// Id of each point.
    ids: Vec<u32>,
    nodes: Vec<Node>,
}

/// A candidate in the k-nearest search: ordered by squared distance, then id, then point
/// index, so that ties are broken the same way whatever the shape of the tree.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Candidate {
    dist2: f64,
    id: u32,
    point: u32,
}

impl Eq for Candidate {}

impl Ord for Candidate {
    fn cmp(&self, o: &Self) -> Ordering {
        self.dist2
            .total_cmp(&o.dist2)
            .then(self.id.cmp(&o.id))
            .then(self.point.cmp(&o.point))
    }
}

impl PartialOrd for Candidate {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl KdTree {
    /// Most points a leaf holds before it splits.
    pub const BUCKET: usize = 12;

    /// An empty tree of `dim`-dimensional points.
    pub fn new(dim: usize) -> Self {
        KdTree {
            dim,
            coords: Vec::new(),
            ids: Vec::new(),
            nodes: vec![Node::Leaf(Vec::new())],
        }
    }

    /// Dimension of the points.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Number of points stored.
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// Whether no point is stored.
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    fn point(&self, i: u32) -> &[f64] {
        let i = i as usize * self.dim;
        &self.coords[i..i + self.dim]
    }

    /// Squared Euclidean distance from `q` to point `i`.
    fn dist2(&self, q: &[f64], i: u32) -> f64 {
        self.point(i)
            .iter()
            .zip(q)
            .map(|(a, b)| (a - b) * (a - b))
            .sum()
    }

    /// Adds `point` (of length [`dim`](Self::dim), finite coordinates) with `id`.
    pub fn insert(&mut self, point: &[f64], id: u32) {
        debug_assert_eq!(point.len(), self.dim);
        let index = self.ids.len() as u32;
        self.coords.extend_from_slice(point);
        self.ids.push(id);
        let mut n = 0usize;
        loop {
            match &mut self.nodes[n] {
                Node::Split {
                    axis,
                    value,
                    children,
                } => n = children[usize::from(point[*axis] >= *value)] as usize,
                Node::Leaf(items) => {
                    items.push(index);
                    if items.len() > Self::BUCKET {
                        self.split(n);
                    }
                    return;
                }
            }
        }
    }

    /// Splits leaf `n` at the median of its widest coordinate; leaves whose points all
    /// coincide stay as they are.
    fn split(&mut self, n: usize) {
        let Node::Leaf(items) = &self.nodes[n] else {
            return;
        };
        let items = items.clone();
        let mut best = (0usize, 0.0f64);
        for axis in 0..self.dim {
            let (lo, hi) = items
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |acc, &i| {
                    let v = self.point(i)[axis];
                    (acc.0.min(v), acc.1.max(v))
                });
            if hi - lo > best.1 {
                best = (axis, hi - lo);
            }
        }
        let (axis, spread) = best;
        if spread <= 0.0 || spread.is_nan() {
            return;
        }
        let mut values: Vec<f64> = items.iter().map(|&i| self.point(i)[axis]).collect();
        values.sort_unstable_by(f64::total_cmp);
        let (min, max) = (values[0], values[values.len() - 1]);
        let mut value = values[values.len() / 2];
        if value <= min {
            // the median equals the minimum: split just above it instead
            value = values.iter().copied().find(|&v| v > min).unwrap_or(max);
        }
        let (left, right): (Vec<u32>, Vec<u32>) =
            items.iter().partition(|&&i| self.point(i)[axis] < value);
        let l = self.nodes.len() as u32;
        self.nodes.push(Node::Leaf(left));
        self.nodes.push(Node::Leaf(right));
        self.nodes[n] = Node::Split {
            axis,
            value,
            children: [l, l + 1],
        };
    }

    /// Depth-first search for `q`, nearer side first, skipping every cell farther (squared)
    /// than the bound `leaf` returns after each leaf it is handed (`bound2` before the first).
    fn search(&self, q: &[f64], bound2: f64, mut leaf: impl FnMut(&[u32]) -> f64) {
        if self.is_empty() {
            return;
        }
        let mut bound2 = bound2;
        let mut stack: Vec<(u32, f64)> = vec![(0, 0.0)];
        while let Some((n, plane2)) = stack.pop() {
            if plane2 > bound2 {
                continue;
            }
            match &self.nodes[n as usize] {
                Node::Leaf(items) => bound2 = leaf(items),
                Node::Split {
                    axis,
                    value,
                    children,
                } => {
                    let diff = q[*axis] - value;
                    let (near, far) = if diff < 0.0 {
                        (children[0], children[1])
                    } else {
                        (children[1], children[0])
                    };
                    // the far side first onto the stack, so the near side is searched first
                    stack.push((far, plane2.max(diff * diff)));
                    stack.push((near, plane2));
                }
            }
        }
    }

    /// The `k` points nearest to `q` within Euclidean distance `max_dist` (inclusive), as
    /// `(distance, id)`, nearest first; ties are ordered by id.
    pub fn nearest(&self, q: &[f64], k: usize, max_dist: f64) -> Vec<(f64, u32)> {
        let k = k.min(self.len());
        if k == 0 {
            return Vec::new();
        }
        let bound2 = if max_dist.is_finite() {
            max_dist * max_dist
        } else {
            f64::INFINITY
        };
        let mut heap: BinaryHeap<Candidate> = BinaryHeap::with_capacity(k + 1);
        self.search(q, bound2, |items| {
            for &i in items {
                let c = Candidate {
                    dist2: self.dist2(q, i),
                    id: self.ids[i as usize],
                    point: i,
                };
                if c.dist2 > bound2 {
                    continue;
                }
                if heap.len() < k {
                    heap.push(c);
                } else if heap.peek().is_some_and(|w| c < *w) {
                    heap.pop();
                    heap.push(c);
                }
            }
            // worst distance still of interest: the bound, or the k-th best found so far
            if heap.len() < k {
                bound2
            } else {
                heap.peek().map_or(bound2, |c| c.dist2)
            }
        });
        let mut out = heap.into_sorted_vec();
        out.truncate(k);
        out.into_iter().map(|c| (c.dist2.sqrt(), c.id)).collect()
    }

    /// The point nearest to `q` as `(distance, id)`, ties by id (`None` for an empty tree):
    /// [`Self::nearest`]'s first for `k = 1` without its heap and vectors, for a tree's extend,
    /// which asks one nearest node per sample (and a dynamic domain's sample drawn again asks
    /// one more). Points are compared by the distance itself, not its square, as
    /// [`NearestNeighbours`] ranks nodes, so that two squares rounding to one distance fall to
    /// the id there too.
    pub fn nearest_one(&self, q: &[f64]) -> Option<(f64, u32)> {
        let mut best: Option<(f64, u32)> = None;
        self.search(q, f64::INFINITY, |items| {
            for &i in items {
                let c = (self.dist2(q, i).sqrt(), self.ids[i as usize]);
                if best.is_none_or(|b| c.0 < b.0 || (c.0 == b.0 && c.1 < b.1)) {
                    best = Some(c);
                }
            }
            // cells whose square reaches the best distance's (widened by a hair for the
            // rounding of the root) may still hold a tie
            best.map_or(f64::INFINITY, |(d, _)| d * d * (1.0 + 1e-12))
        });
        best
    }

    /// Every point within Euclidean distance `r` of `q` (inclusive), as `(distance, id)` in
    /// no particular order.
    pub fn within(&self, q: &[f64], r: f64) -> Vec<(f64, u32)> {
        let r2 = r * r;
        let mut out = Vec::new();
        self.search(q, r2, |items| {
            for &i in items {
                let d2 = self.dist2(q, i);
                if d2 <= r2 {
                    out.push((d2.sqrt(), self.ids[i as usize]));
                }
            }
            r2
        });
        out
    }
}

/// Nearest roadmap nodes by the space's distance, through a [`KdTree`] of embeddings.
#[derive(Clone, Debug)]
pub struct NearestNeighbours {
    space: Space,
    tree: KdTree,
    /// Points per node (2 for SE(3)).
    per_node: usize,
    /// Whether a configuration is its own embedding and the space's distance the Euclidean
    /// one ([`Space::embedding_is_identity`]): the tree's nearest are then the space's, and
    /// need neither more candidates nor a second search.
    identity: bool,
}

impl NearestNeighbours {
    /// An empty index for configurations of `space`.
    pub fn new(space: &Space) -> Self {
        let per_node = match space.kind() {
            SpaceKind::Se3 => 2,
            _ => 1,
        };
        NearestNeighbours {
            space: space.clone(),
            tree: KdTree::new(space.embedding_dim()),
            per_node,
            identity: space.embedding_is_identity(),
        }
    }

    /// Number of nodes indexed.
    pub fn len(&self) -> usize {
        self.tree.len() / self.per_node
    }

    /// Whether no node is indexed.
    pub fn is_empty(&self) -> bool {
        self.tree.is_empty()
    }

    /// Adds node `id` at configuration `q`.
    pub fn insert(&mut self, id: u32, q: &[f64]) {
        if self.identity {
            // a tree out of a roadmap indexes its whole component as a query begins
            self.tree.insert(q, id);
            return;
        }
        for e in self.space.embeddings(q) {
            self.tree.insert(&e, id);
        }
    }

    /// The up to `k` nodes nearest to `q` by [`Space::distance`], within `radius` if given,
    /// as `(id, distance)` nearest first (ties by id). `config(id)` returns a node's
    /// configuration for the re-ranking.
    pub fn nearest<'c>(
        &self,
        q: &[f64],
        k: usize,
        radius: Option<f64>,
        config: impl Fn(u32) -> &'c [f64],
    ) -> Vec<(u32, f64)> {
        let k = k.min(self.len());
        if k == 0 {
            return Vec::new();
        }
        let exact = self.identity;
        // distinct nodes wanted from the tree before re-ranking
        let wanted = if exact { k } else { (2 * k).max(k + 8) };
        let max_dist = radius.unwrap_or(f64::INFINITY);
        // The tree holds both antipodes of an SE(3) node, so one embedding of `q` suffices;
        // the radius is widened by a hair so that rounding cannot drop a node at distance
        // exactly `radius` before the exact filter below.
        let embeddings;
        let embedded = if self.identity {
            q
        } else {
            embeddings = self.space.embeddings(q);
            &embeddings[0][..]
        };
        let widen = |r: f64| r * (1.0 + 1e-9) + 1e-12;
        let tree_radius = widen(max_dist);
        let points = self
            .tree
            .nearest(embedded, wanted * self.per_node, tree_radius);
        let mut found = self.ranked(q, &points, max_dist, &config);
        if !exact && points.len() == wanted * self.per_node {
            // Exact after all: a node nearer than the k-th found (or within the radius, if
            // fewer were found) lies within that distance in embedded space too (embeddings are
            // lower bounds), so if the tree stopped short of it, one more search within that
            // distance fetches every candidate.
            let bound = if found.len() >= k {
                found[k - 1].1.min(max_dist)
            } else {
                max_dist
            };
            let reached = points.last().map_or(0.0, |p| p.0);
            if bound.is_finite() && reached < bound {
                let points = self.tree.within(embedded, widen(bound));
                found = self.ranked(q, &points, max_dist, &config);
            }
        }
        found.truncate(k);
        found
    }

    /// The node nearest to `q` by [`Space::distance`] and that distance (ties by id; `None`
    /// while the index is empty): [`Self::nearest`] with `k = 1` and no radius, and in spaces
    /// whose configurations are their own embeddings (R^n, an arm without continuous joints)
    /// one search of the tree without allocating.
    pub fn nearest_one<'c>(
        &self,
        q: &[f64],
        config: impl Fn(u32) -> &'c [f64],
    ) -> Option<(u32, f64)> {
        if self.identity {
            let (_, id) = self.tree.nearest_one(q)?;
            // the space's own distance, as the ranked search reports it
            return Some((id, self.space.distance(q, config(id))));
        }
        self.nearest(q, 1, None, config).first().copied()
    }

    /// Distinct nodes among tree `points`, by the space's distance from `q` within `max_dist`,
    /// nearest first (ties by id).
    fn ranked<'c>(
        &self,
        q: &[f64],
        points: &[(f64, u32)],
        max_dist: f64,
        config: &impl Fn(u32) -> &'c [f64],
    ) -> Vec<(u32, f64)> {
        let mut ids: Vec<u32> = points.iter().map(|&(_, id)| id).collect();
        ids.sort_unstable();
        ids.dedup();
        let mut found: Vec<(u32, f64)> = ids
            .into_iter()
            .map(|id| (id, self.space.distance(q, config(id))))
            .filter(|&(_, d)| d <= max_dist)
            .collect();
        found.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        found
    }
}
