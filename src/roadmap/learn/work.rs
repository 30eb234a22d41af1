//! The roadmap while it grows: nodes (one per distinct configuration), edges, components,
//! failure counts and the nearest-neighbour index.

use super::super::graph::{Edge, Roadmap};
use super::super::nn::NearestNeighbours;
use super::super::params::LearnParams;
use crate::fast_hash::{FastMap, FastSet};
use crate::local::{path_length, segment_length};
use crate::oracle::CallCounts;
use crate::space::{Config, Group, Space};
use petgraph::unionfind::UnionFind;

/// The roadmap while it grows.
pub(super) struct Work<'s> {
    pub(super) space: &'s Space,
    pub(super) groups: Vec<Group>,
    pub(super) dim: usize,
    pub(super) feedback: bool,
    pub(super) cycle_edges: bool,
    pub(super) coords: Vec<f64>,
    pub(super) edges: Vec<Edge>,
    pub(super) edge_set: FastSet<(u32, u32)>,
    pub(super) by_bits: FastMap<Vec<u64>, u32>,
    pub(super) uf: UnionFind<u32>,
    pub(super) components: usize,
    /// Connection attempts and failures per node (OS94's failure ratio).
    pub(super) tries: Vec<u32>,
    pub(super) failures: Vec<u32>,
    pub(super) nn: NearestNeighbours,
    pub(super) counts: CallCounts,
    pub(super) attempts: u64,
    pub(super) connected: u64,
    /// The learning deadline passed during the round being applied.
    pub(super) stopped: bool,
}

impl<'s> Work<'s> {
    /// An empty roadmap of `space` whose edges change the DOF groups `groups` one at a time.
    pub(super) fn new(space: &'s Space, groups: Vec<Group>, params: &LearnParams) -> Self {
        Work {
            space,
            groups,
            dim: space.dim(),
            feedback: params.feedback,
            cycle_edges: params.cycle_edges,
            coords: Vec::new(),
            edges: Vec::new(),
            edge_set: FastSet::default(),
            by_bits: FastMap::default(),
            uf: UnionFind::new(0),
            components: 0,
            tries: Vec::new(),
            failures: Vec::new(),
            nn: NearestNeighbours::new(space),
            counts: CallCounts::default(),
            attempts: 0,
            connected: 0,
            stopped: false,
        }
    }

    pub(super) fn node_count(&self) -> usize {
        self.coords.len() / self.dim
    }

    pub(super) fn node(&self, i: u32) -> &[f64] {
        let s = i as usize * self.dim;
        &self.coords[s..s + self.dim]
    }

    pub(super) fn nearest(&self, q: &[f64], k: usize, radius: Option<f64>) -> Vec<(u32, f64)> {
        self.nn.nearest(q, k, radius, |i| self.node(i))
    }

    /// The node at `q`, added if no node has exactly these coordinates (bit for bit: an SE(3)
    /// orientation and its antipode make two nodes, joined by whatever joins them).
    pub(super) fn add_node(&mut self, q: &[f64]) -> u32 {
        let bits: Vec<u64> = q.iter().map(|v| v.to_bits()).collect();
        if let Some(&i) = self.by_bits.get(&bits) {
            return i;
        }
        let i = self.node_count() as u32;
        self.by_bits.insert(bits, i);
        self.coords.extend_from_slice(q);
        self.uf.new_set();
        self.components += 1;
        self.tries.push(0);
        self.failures.push(0);
        self.nn.insert(i, q);
        i
    }

    /// Copies a learnt roadmap's nodes (same indices) and edges, to grow it further. Failure
    /// counts start at zero: the file does not keep them.
    pub(super) fn copy_roadmap(&mut self, base: &Roadmap) {
        for q in base.nodes() {
            self.add_node(q);
        }
        for e in base.edges() {
            if e.a != e.b && self.edge_set.insert((e.a.min(e.b), e.a.max(e.b))) {
                self.edges.push(e.clone());
                if self.uf.union(e.a, e.b) {
                    self.components -= 1;
                }
            }
        }
    }

    /// Adds a roadmap's nodes (each one an identical node already there, or the next index)
    /// and its edges (those not joining an already joined pair), for a merge. Returns the index
    /// each of its nodes got.
    pub(super) fn add_roadmap(&mut self, part: &Roadmap) -> Vec<u32> {
        let ids: Vec<u32> = part.nodes().map(|q| self.add_node(q)).collect();
        for e in part.edges() {
            let (a, b) = (ids[e.a as usize], ids[e.b as usize]);
            if a != b && self.edge_set.insert((a.min(b), a.max(b))) {
                self.edges.push(Edge {
                    a,
                    b,
                    length: e.length,
                    corners: e.corners.clone(),
                });
                if self.uf.union(a, b) {
                    self.components -= 1;
                }
            }
        }
        ids
    }

    /// Adds the edge `a → corners → b` unless it is a loop or the pair is joined already.
    pub(super) fn add_edge(&mut self, a: u32, b: u32, corners: &[Config]) {
        if a == b || !self.edge_set.insert((a.min(b), a.max(b))) {
            return;
        }
        debug_assert!(
            !corners.is_empty()
                || self
                    .groups
                    .iter()
                    .filter(|g| !self.space.same_in_group(self.node(a), self.node(b), g))
                    .count()
                    <= 1
                || self.space.straight_group().is_some(),
            "a single-segment edge must change one DOF group (LocalMethod contract), or be a \
             kept straight shortcut of several joints (crate::local::path_pieces)"
        );
        let length = if corners.is_empty() {
            segment_length(self.space, &self.groups, self.node(a), self.node(b))
        } else {
            let mut path = Vec::with_capacity(corners.len() + 2);
            path.push(self.node(a).to_vec());
            path.extend(corners.iter().cloned());
            path.push(self.node(b).to_vec());
            path_length(self.space, &self.groups, &path)
        };
        self.edges.push(Edge {
            a,
            b,
            length,
            corners: corners.iter().flatten().copied().collect(),
        });
        if self.uf.union(a, b) {
            self.components -= 1;
        }
    }
}
