//! Landmark lower bounds for A* (Goldberg and Harrelson's ALT): graph distances from a few
//! landmark nodes bound the distance between any two nodes of a landmark's component by the
//! triangle inequality, `d(v, g) ≥ |d(L, v) − d(L, g)|`.
//!
//! The space's distance alone is a weak A* heuristic where obstacles make the roadmap detour
//! (a house, a cluttered plane): A* then settles most of the component. Landmarks placed far
//! apart, one farthest from the others in turn, see those detours. They cost one Dijkstra per
//! landmark, paid once per [`super::QueryPlanner`] and repaid after a few queries.

use super::graph::Roadmap;
use petgraph::visit::EdgeRef;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Graph distances from the landmarks (`f64::INFINITY` outside a landmark's component).
#[derive(Clone, Debug)]
pub struct Landmarks {
    /// `dist[l][v]`: the roadmap distance from landmark `l` to node `v`.
    dist: Vec<Vec<f64>>,
}

impl Landmarks {
    /// About `count` landmarks, chosen deterministically and shared out among the components
    /// in proportion to their size (a component with fewer than `1/count` of the nodes gets
    /// none, so at most `2 · count` in all): in each, the node farthest from its first node,
    /// then each time the node farthest from the landmarks chosen so far.
    pub fn new(roadmap: &Roadmap, count: usize) -> Landmarks {
        let mut dist: Vec<Vec<f64>> = Vec::new();
        let n = roadmap.node_count();
        if n == 0 || count == 0 {
            return Landmarks { dist };
        }
        let labels = roadmap.component_labels();
        for (c, &size) in roadmap.component_sizes().iter().enumerate() {
            let size = size as usize;
            if size < 2 || size * count < n {
                continue;
            }
            let share = ((count * size + n / 2) / n).max(1);
            let first = labels.iter().position(|&l| l as usize == c).unwrap_or(0);
            // how far each node is from the landmarks so far (from `first` to begin with)
            let mut nearest = dijkstra(roadmap, first as u32);
            for _ in 0..share {
                let far = nearest
                    .iter()
                    .enumerate()
                    .filter(|(_, d)| d.is_finite())
                    .max_by(|a, b| a.1.total_cmp(b.1).then(b.0.cmp(&a.0)))
                    .map(|(v, _)| v as u32);
                let Some(far) = far.filter(|&v| nearest[v as usize] > 0.0) else {
                    break;
                };
                let d = dijkstra(roadmap, far);
                for (m, x) in nearest.iter_mut().zip(&d) {
                    *m = m.min(*x);
                }
                dist.push(d);
            }
        }
        Landmarks { dist }
    }

    /// Number of landmarks.
    pub fn len(&self) -> usize {
        self.dist.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.dist.is_empty()
    }

    /// A lower bound of the roadmap distance from node `v` to node `g` (0 if no landmark
    /// shares their component).
    pub fn lower_bound(&self, v: u32, g: u32) -> f64 {
        let (v, g) = (v as usize, g as usize);
        self.dist
            .iter()
            .filter(|d| d[v].is_finite() && d[g].is_finite())
            .map(|d| (d[v] - d[g]).abs())
            .fold(0.0, f64::max)
    }
}

/// Roadmap distances from node `s` (Dijkstra over the edge lengths).
fn dijkstra(roadmap: &Roadmap, s: u32) -> Vec<f64> {
    #[derive(PartialEq)]
    struct Item(f64, u32);
    impl Eq for Item {}
    impl PartialOrd for Item {
        fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
            Some(self.cmp(other))
        }
    }
    impl Ord for Item {
        // a min-heap by distance, ties by node
        fn cmp(&self, other: &Self) -> Ordering {
            other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
        }
    }
    let graph = roadmap.graph();
    let mut dist = vec![f64::INFINITY; roadmap.node_count()];
    let mut heap = BinaryHeap::new();
    dist[s as usize] = 0.0;
    heap.push(Item(0.0, s));
    while let Some(Item(d, u)) = heap.pop() {
        if d > dist[u as usize] {
            continue;
        }
        for e in graph.edges(petgraph::graph::NodeIndex::new(u as usize)) {
            let v = e.target().index() as u32;
            let nd = d + *e.weight();
            if nd < dist[v as usize] {
                dist[v as usize] = nd;
                heap.push(Item(nd, v));
            }
        }
    }
    dist
}
