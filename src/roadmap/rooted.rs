//! Trees that grow out of a roadmap, for the ends a roadmap cannot join (a fixed workcell's
//! goal inside a box).
//!
//! A roadmap's query that cannot attach an end has two ways on: grow the roadmap (OS94's
//! expansion, [`super::QueryOptions::grow`]) or grow trees from start to goal ([`super::tree`]).
//! The trees from bare ends must find their way through the whole space, although the roadmap
//! already covers most of it with certified edges. Here each end that attaches to the roadmap
//! (the direct path to one of its nearest nodes is free) brings that node's whole component
//! along as its tree: a shortest-path tree of the component, rooted at the end, whose branches
//! are the roadmap's edges with their corners. RRT-Connect then grows from there
//! ([`super::tree::rrt_connect_rooted`]): the other tree need only reach *some* node of the
//! component, not the far end, and the first extend towards a trapped goal starts from the
//! roadmap node nearest to it. An end that attaches to nothing grows from itself, as before.
//!
//! Every branch is either a roadmap edge (certified when it was learnt) or a free direct path
//! checked here (for an arm, a straight motion proved free, as the trees' extends are), so the
//! path is again a chain of certified motions.

use super::graph::Roadmap;
use super::tree::{rrt_connect_rooted, Rooted, TreeError, TreeOutcome, TreeParams, TreeStop};
use crate::deadline::Deadline;
use crate::local::{check_direct, goes_straight, straight_connection};
use crate::oracle::{CallCounts, CollisionOracle, OracleError};
use crate::space::{Config, Group};
use petgraph::graph::NodeIndex;
use petgraph::visit::EdgeRef;
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::sync::{Arc, Mutex};

/// Nearest roadmap nodes an end tries to attach to with a free direct path (the default of
/// [`RoadmapTrees::with_candidates`]). Attaching is a yes/no call per group changed, so a few
/// candidates are cheap; an end in a pocket fails all of them and grows from itself.
pub const ATTACH_CANDIDATES: usize = 5;

/// RRT-Connect between two ends, each grown from the roadmap component it attaches to (module
/// docs).
pub struct RoadmapTrees<'a> {
    roadmap: &'a Roadmap,
    oracle: &'a dyn CollisionOracle,
    groups: &'a [Group],
    candidates: usize,
    kept: Option<&'a KeptTree>,
}

/// The last tree an end attached to a roadmap brought along, indexed, for the next query from
/// the same end through the same attachment ([`RoadmapTrees::keeping`]): a workcell's queries
/// start from one home pose, and its component's tree (hundreds of nodes with the edges'
/// corners, and their nearest-neighbour index) is the same each time.
#[derive(Debug, Default)]
pub struct KeptTree(Mutex<Option<(Vec<u64>, Arc<Rooted>)>>);

/// How an end joined the roadmap: the corners of a free direct path to `node`, `node` last.
struct Attachment {
    node: u32,
    corners: Vec<Config>,
}

impl<'a> RoadmapTrees<'a> {
    /// Trees out of `roadmap`, extended in `groups` (the roadmap's local method's groups, so
    /// that its edges and the trees' stairs are the same kind of motion), asking `oracle`.
    pub fn new(
        roadmap: &'a Roadmap,
        oracle: &'a dyn CollisionOracle,
        groups: &'a [Group],
    ) -> RoadmapTrees<'a> {
        RoadmapTrees {
            roadmap,
            oracle,
            groups,
            candidates: ATTACH_CANDIDATES,
            kept: None,
        }
    }

    /// Keeps the tree an end brings along in `kept` for the next query that attaches the same
    /// end the same way (the same tree, found at once).
    pub fn keeping(mut self, kept: &'a KeptTree) -> Self {
        self.kept = Some(kept);
        self
    }

    /// Tries the `k` nearest nodes for each end (0: the trees grow from the bare ends).
    pub fn with_candidates(mut self, k: usize) -> Self {
        self.candidates = k;
        self
    }

    /// A path from `start` to `goal` (both free) as [`super::tree::rrt_connect`] finds it, the
    /// ends' components given to their trees. The outcome's calls include attaching; its
    /// nodes count only what the trees grew. Where both ends attach to one component the
    /// answer is the way through it (no tree grows).
    pub fn connect(
        &self,
        start: &[f64],
        goal: &[f64],
        params: &TreeParams,
        seed: u64,
        deadline: &Deadline,
    ) -> Result<TreeOutcome, TreeError> {
        let mut counts = CallCounts::default();
        let at_start = self.attach(start, params, &mut counts, deadline)?;
        let at_goal = self.attach(goal, params, &mut counts, deadline)?;
        let component = |a: &Option<Attachment>| a.as_ref().map(|a| self.roadmap.component(a.node));
        let (cs, cg) = (component(&at_start), component(&at_goal));
        let space = self.roadmap.space();
        if let (Some(s), Some(g)) = (&at_start, &at_goal) {
            if cs == cg {
                let (tree, index) = self.rooted(start, s);
                let mut path = tree.branch(index[g.node as usize]);
                path.extend(g.corners.iter().rev().skip(1).cloned());
                path.push(goal.to_vec());
                return Ok(TreeOutcome {
                    path: Some(path),
                    nodes: [1, 1],
                    extends: 0,
                    counts,
                    stop: TreeStop::Connected,
                    attempts: 1,
                    trees: None,
                });
            }
        }
        let root = |end: &[f64], a: &Option<Attachment>| match a {
            Some(a) => self.rooted_kept(end, a),
            None => Arc::new(Rooted::at(end)),
        };
        let roots = [root(start, &at_start), root(goal, &at_goal)];
        let mut out = rrt_connect_rooted(
            space,
            self.oracle,
            self.groups,
            [&*roots[0], &*roots[1]],
            params,
            seed,
            deadline,
        )?;
        out.counts += counts;
        Ok(out)
    }

    /// The first of the end's nearest nodes a free direct path reaches, nearest first: as the
    /// trees extend ([`TreeParams::straight`], [`TreeParams::staircase`]), an arm's straight
    /// motion first, the staircase only where the trees walk one. An arm's trees give an
    /// unproved straight motion up: an end in a pocket fails every candidate, and their
    /// staircases' exact sweeps cost more than the trees that then answer (bookshelf
    /// workcells: up to half a millisecond).
    fn attach(
        &self,
        end: &[f64],
        params: &TreeParams,
        counts: &mut CallCounts,
        deadline: &Deadline,
    ) -> Result<Option<Attachment>, OracleError> {
        let space = self.roadmap.space();
        for (node, _) in self.roadmap.nearest(end, self.candidates, None) {
            if deadline.expired() {
                break;
            }
            let to = self.roadmap.node(node);
            if params.straight && goes_straight(space, self.groups, end, to) {
                let straight =
                    straight_connection(space, self.oracle, self.groups, end, to, counts)?;
                if straight.is_some() {
                    let corners = vec![to.to_vec()];
                    return Ok(Some(Attachment { node, corners }));
                }
                if !params.staircase {
                    continue;
                }
            }
            if let Some(corners) = check_direct(space, self.oracle, self.groups, end, to, counts)? {
                return Ok(Some(Attachment { node, corners }));
            }
        }
        Ok(None)
    }

    /// [`Self::rooted`]'s tree, the kept one where the last query attached the same end the
    /// same way ([`Self::keeping`]; the key is the bits of the end, the node and the corners).
    fn rooted_kept(&self, end: &[f64], a: &Attachment) -> Arc<Rooted> {
        let Some(kept) = self.kept else {
            return Arc::new(self.rooted(end, a).0);
        };
        let key: Vec<u64> = std::iter::once(u64::from(a.node))
            .chain(
                end.iter()
                    .chain(a.corners.iter().flatten())
                    .map(|v| v.to_bits()),
            )
            .collect();
        let mut last = kept.0.lock().unwrap_or_else(|p| p.into_inner());
        if let Some((k, tree)) = last.as_ref() {
            if *k == key {
                return Arc::clone(tree);
            }
        }
        let tree = Arc::new(self.rooted(end, a).0.indexed(self.roadmap.space()));
        *last = Some((key, Arc::clone(&tree)));
        tree
    }

    /// The tree of `end`: its attachment's corners, then the attached node's component as a
    /// shortest-path tree (Dijkstra over edge lengths) with every edge's corners; with it, the
    /// tree index of every roadmap node of the component (`u32::MAX` elsewhere).
    fn rooted(&self, end: &[f64], a: &Attachment) -> (Rooted, Vec<u32>) {
        let mut tree = Rooted::at(end);
        let mut at = 0;
        for c in &a.corners {
            at = tree.add(c.clone(), at);
        }
        // roadmap node -> tree index, filled as Dijkstra settles nodes (parents first)
        let mut index = vec![u32::MAX; self.roadmap.node_count()];
        index[a.node as usize] = at;
        for (v, via) in self.shortest_path_tree(a.node) {
            let (edge, from) = via;
            let corners = self.roadmap.edge_path(edge, from);
            let mut at = index[from as usize];
            for c in corners.into_iter().skip(1) {
                at = tree.add(c, at);
            }
            index[v as usize] = at;
        }
        (tree, index)
    }

    /// The nodes of `root`'s component other than `root` in the order Dijkstra settles them,
    /// each with the edge (index, the node it is walked from) of its shortest way from `root`.
    fn shortest_path_tree(&self, root: u32) -> Vec<(u32, (usize, u32))> {
        let graph = self.roadmap.graph();
        let n = self.roadmap.node_count();
        let mut dist = vec![f64::INFINITY; n];
        let mut via: Vec<Option<(usize, u32)>> = vec![None; n];
        let mut done = vec![false; n];
        let mut order = Vec::new();
        let mut heap = BinaryHeap::new();
        dist[root as usize] = 0.0;
        heap.push(Open(0.0, root));
        while let Some(Open(d, u)) = heap.pop() {
            if done[u as usize] {
                continue;
            }
            done[u as usize] = true;
            if let Some(v) = via[u as usize] {
                order.push((u, v));
            }
            for e in graph.edges(NodeIndex::new(u as usize)) {
                let w = if e.source().index() == u as usize {
                    e.target().index()
                } else {
                    e.source().index()
                };
                let nd = d + e.weight();
                if !done[w] && nd < dist[w] {
                    dist[w] = nd;
                    via[w] = Some((e.id().index(), u));
                    heap.push(Open(nd, w as u32));
                }
            }
        }
        order
    }
}

/// A node open in Dijkstra's heap, nearest first.
struct Open(f64, u32);

impl PartialEq for Open {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Open {}

impl PartialOrd for Open {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Open {
    fn cmp(&self, other: &Self) -> Ordering {
        // reversed: BinaryHeap pops the greatest, Dijkstra wants the nearest
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}
