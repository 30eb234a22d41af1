//! The roadmap itself: nodes (free configurations), edges (certified free local paths with
//! their length) and connected components (OS94's graph `G = (V, E)`).
//!
//! An edge is a path of *corners* from one node to the other, consecutive corners joined by the
//! direct path of the local method's DOF groups (CHS §1.5): with feedback every edge is a single
//! straight motion in one group and has no interior corners; without feedback an edge keeps the
//! interior corners of the path the local method found.

use super::header::Header;
use super::nn::NearestNeighbours;
use crate::space::{Config, Space};
use petgraph::graph::{NodeIndex, UnGraph};
use petgraph::unionfind::UnionFind;
use serde::{Deserialize, Serialize};

/// A certified free local path between two nodes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Edge {
    /// One end (a node index).
    pub a: u32,
    /// The other end.
    pub b: u32,
    /// Length of the path ([`crate::local::path_length`] over `a`, the corners, `b`).
    pub length: f64,
    /// Interior corners from `a` towards `b`, flattened (`dim` numbers each); empty for a single
    /// straight motion.
    pub corners: Vec<f64>,
}

/// A learnt roadmap, ready for queries: the graph, its components and a nearest-neighbour
/// index. Queries never change it ([`super::query`]), so one roadmap serves many threads.
#[derive(Clone, Debug)]
pub struct Roadmap {
    header: Header,
    dim: usize,
    coords: Vec<f64>,
    edges: Vec<Edge>,
    /// Adjacency for A*: graph edge `i` is `edges[i]`, weighted by its length.
    graph: UnGraph<(), f64, u32>,
    labels: Vec<u32>,
    sizes: Vec<u32>,
    nn: NearestNeighbours,
}

impl Roadmap {
    /// Builds a roadmap from its parts, checking that they fit together: node coordinates a
    /// multiple of the dimension and finite, edges between existing distinct nodes with finite
    /// non-negative lengths and whole corners. Computes the components and the index.
    pub(crate) fn assemble(
        header: Header,
        coords: Vec<f64>,
        edges: Vec<Edge>,
    ) -> Result<Roadmap, String> {
        let dim = header.space.dim();
        if coords.len() % dim != 0 {
            return Err(format!(
                "{} node coordinates are not a multiple of the dimension {dim}",
                coords.len()
            ));
        }
        if coords.iter().any(|c| !c.is_finite()) {
            return Err("a node coordinate is not finite".into());
        }
        let n = coords.len() / dim;
        if n > u32::MAX as usize {
            return Err(format!("{n} nodes are more than a roadmap can index"));
        }
        let mut graph = UnGraph::<(), f64, u32>::with_capacity(n, edges.len());
        for _ in 0..n {
            graph.add_node(());
        }
        let mut uf = UnionFind::<u32>::new(n);
        for (i, e) in edges.iter().enumerate() {
            if e.a as usize >= n || e.b as usize >= n {
                return Err(format!(
                    "edge {i} joins nodes {} and {}, but there are {n} nodes",
                    e.a, e.b
                ));
            }
            if e.a == e.b {
                return Err(format!("edge {i} is a loop at node {}", e.a));
            }
            if !(e.length.is_finite() && e.length >= 0.0) {
                return Err(format!("edge {i} has length {}", e.length));
            }
            if e.corners.len() % dim != 0 || e.corners.iter().any(|c| !c.is_finite()) {
                return Err(format!("edge {i} has malformed corners"));
            }
            graph.add_edge(
                NodeIndex::new(e.a as usize),
                NodeIndex::new(e.b as usize),
                e.length,
            );
            uf.union(e.a, e.b);
        }
        let (labels, sizes) = component_labels(&uf, n);
        let mut nn = NearestNeighbours::new(&header.space);
        for (i, q) in coords.chunks_exact(dim).enumerate() {
            nn.insert(i as u32, q);
        }
        Ok(Roadmap {
            header,
            dim,
            coords,
            edges,
            graph,
            labels,
            sizes,
            nn,
        })
    }

    /// How the roadmap was learnt, and for which scene.
    pub fn header(&self) -> &Header {
        &self.header
    }

    /// The configuration space.
    pub fn space(&self) -> &Space {
        &self.header.space
    }

    /// Number of coordinates of a configuration.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.coords.len() / self.dim
    }

    /// Number of edges.
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// Configuration of node `i`.
    ///
    /// # Panics
    /// If `i` is not a node index.
    pub fn node(&self, i: u32) -> &[f64] {
        let s = i as usize * self.dim;
        &self.coords[s..s + self.dim]
    }

    /// All node configurations, in index order.
    pub fn nodes(&self) -> impl Iterator<Item = &[f64]> {
        self.coords.chunks_exact(self.dim)
    }

    /// Node coordinates, flattened.
    pub fn coords(&self) -> &[f64] {
        &self.coords
    }

    /// All edges, in the order they were learnt.
    pub fn edges(&self) -> &[Edge] {
        &self.edges
    }

    /// The corners of edge `e` walked from node `from` (one of its ends) to the other end,
    /// both ends included.
    pub fn edge_path(&self, e: usize, from: u32) -> Vec<Config> {
        let edge = &self.edges[e];
        let mut path = vec![self.node(edge.a).to_vec()];
        path.extend(edge.corners.chunks_exact(self.dim).map(<[f64]>::to_vec));
        path.push(self.node(edge.b).to_vec());
        if from == edge.b {
            path.reverse();
        }
        path
    }

    /// Component label of node `i` (labels are `0..component_count()`, numbered in the order of
    /// their first node).
    pub fn component(&self, i: u32) -> u32 {
        self.labels[i as usize]
    }

    /// Component label of every node.
    pub fn component_labels(&self) -> &[u32] {
        &self.labels
    }

    /// Number of connected components.
    pub fn component_count(&self) -> usize {
        self.sizes.len()
    }

    /// Number of nodes in each component, by label.
    pub fn component_sizes(&self) -> &[u32] {
        &self.sizes
    }

    /// Nodes in the largest component (0 for an empty roadmap).
    pub fn largest_component(&self) -> usize {
        self.sizes.iter().copied().max().unwrap_or(0) as usize
    }

    /// The up to `k` nodes nearest to `q` within `radius`, as `(node, distance)`, nearest first.
    pub fn nearest(&self, q: &[f64], k: usize, radius: Option<f64>) -> Vec<(u32, f64)> {
        self.nn.nearest(q, k, radius, |i| self.node(i))
    }

    /// The adjacency A* runs on: node `i` is `NodeIndex(i)`, edge `j` is `edges()[j]` with its
    /// length as weight.
    pub fn graph(&self) -> &UnGraph<(), f64, u32> {
        &self.graph
    }
}

/// Component labels numbered by first appearance, and component sizes.
pub(crate) fn component_labels(uf: &UnionFind<u32>, n: usize) -> (Vec<u32>, Vec<u32>) {
    let mut by_root = vec![u32::MAX; n];
    let mut labels = Vec::with_capacity(n);
    let mut sizes: Vec<u32> = Vec::new();
    for i in 0..n {
        let r = uf.find(i as u32) as usize;
        if by_root[r] == u32::MAX {
            by_root[r] = sizes.len() as u32;
            sizes.push(0);
        }
        let l = by_root[r];
        sizes[l as usize] += 1;
        labels.push(l);
    }
    (labels, sizes)
}
