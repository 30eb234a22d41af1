//! Shared helpers of the roadmap tests: disc scenes built in code and an independent validity
//! checker that shares no code with the disc oracle (closest point of a segment to a centre).
#![allow(dead_code)]

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use viaroad::local::LocalSpec;
use viaroad::roadmap::{Budget, LearnParams, Learner, Learnt, Roadmap};
use viaroad::scene::{Obstacle, Robot, Scene};
use viaroad::space::Space;

/// `n` discs of radius `r` with centres drawn uniformly in the unit square (seeded).
pub fn disc_scene(seed: u64, n: usize, r: f64) -> Scene {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let obstacles = (0..n)
        .map(|_| Obstacle::Disc {
            centre: vec![rng.random::<f64>(), rng.random::<f64>()],
            radius: r,
        })
        .collect();
    Scene {
        name: format!("discs-{seed}-{n}-{r}"),
        space: Space::euclidean(vec![0.0, 0.0], vec![1.0, 1.0]).unwrap(),
        robot: Robot::Point,
        obstacles,
        queries: Vec::new(),
        source: None,
        warnings: Vec::new(),
    }
}

/// The discs of a scene as (centre, radius).
pub fn discs(scene: &Scene) -> Vec<([f64; 2], f64)> {
    scene
        .obstacles
        .iter()
        .map(|o| match o {
            Obstacle::Disc { centre, radius } => ([centre[0], centre[1]], *radius),
            _ => panic!("disc scenes only"),
        })
        .collect()
}

/// Distance from `c` to the segment `p`–`q`.
pub fn segment_point_distance(p: &[f64], q: &[f64], c: [f64; 2]) -> f64 {
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let len2 = dx * dx + dy * dy;
    let s = if len2 == 0.0 {
        0.0
    } else {
        (((c[0] - p[0]) * dx + (c[1] - p[1]) * dy) / len2).clamp(0.0, 1.0)
    };
    let (x, y) = (p[0] + s * dx - c[0], p[1] + s * dy - c[1]);
    (x * x + y * y).sqrt()
}

/// A point strictly outside every disc and inside the closed unit square.
pub fn point_free(p: &[f64], discs: &[([f64; 2], f64)]) -> bool {
    p.len() == 2
        && p.iter().all(|v| (0.0..=1.0).contains(v))
        && discs.iter().all(|(c, r)| {
            let (x, y) = (p[0] - c[0], p[1] - c[1]);
            (x * x + y * y).sqrt() > *r
        })
}

/// The straight segment stays in the unit square (convex: its ends do) and keeps clear of every
/// disc. A relative tolerance of 1e-9 absorbs rounding on segments that graze a disc.
pub fn segment_free(p: &[f64], q: &[f64], discs: &[([f64; 2], f64)]) -> bool {
    point_free(p, discs)
        && point_free(q, discs)
        && discs
            .iter()
            .all(|(c, r)| segment_point_distance(p, q, *c) > r * (1.0 - 1e-9))
}

/// Every consecutive pair of a path is a free straight segment.
pub fn path_free(path: &[Vec<f64>], discs: &[([f64; 2], f64)]) -> bool {
    !path.is_empty() && path.windows(2).all(|w| segment_free(&w[0], &w[1], discs))
}

/// Sum of Euclidean segment lengths.
pub fn polyline_length(path: &[Vec<f64>]) -> f64 {
    path.windows(2)
        .map(|w| ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt())
        .sum()
}

/// `n` pairs of free points drawn uniformly (seeded), checked by [`point_free`].
pub fn random_queries(scene: &Scene, n: usize, seed: u64) -> Vec<(Vec<f64>, Vec<f64>)> {
    let d = discs(scene);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut free = || loop {
        let p = vec![rng.random::<f64>(), rng.random::<f64>()];
        if point_free(&p, &d) {
            return p;
        }
    };
    (0..n).map(|_| (free(), free())).collect()
}

/// Learns a roadmap of `scene` with `spec`, `params`, a node budget and a seed.
pub fn learn(
    scene: &Scene,
    spec: &LocalSpec,
    params: &LearnParams,
    nodes: usize,
    seed: u64,
) -> Learnt {
    let oracle = scene.oracle();
    let local = spec.build();
    Learner::for_scene(scene, oracle.as_ref(), local.as_ref())
        .learn(params, &Budget::nodes(nodes), seed, &mut |_| {})
        .expect("learning succeeds")
}

/// Component labels by breadth-first search over the edges (numbered by first node), computed
/// without the roadmap's union–find.
pub fn bfs_labels(roadmap: &Roadmap) -> Vec<u32> {
    let n = roadmap.node_count();
    let mut adj = vec![Vec::new(); n];
    for e in roadmap.edges() {
        adj[e.a as usize].push(e.b as usize);
        adj[e.b as usize].push(e.a as usize);
    }
    let mut label = vec![u32::MAX; n];
    let mut next = 0;
    for s in 0..n {
        if label[s] != u32::MAX {
            continue;
        }
        let mut queue = std::collections::VecDeque::from([s]);
        label[s] = next;
        while let Some(u) = queue.pop_front() {
            for &v in &adj[u] {
                if label[v] == u32::MAX {
                    label[v] = next;
                    queue.push_back(v);
                }
            }
        }
        next += 1;
    }
    label
}

/// Every node free and every edge (with its corners) a chain of free segments.
pub fn roadmap_valid(roadmap: &Roadmap, discs: &[([f64; 2], f64)]) -> Result<(), String> {
    for (i, q) in roadmap.nodes().enumerate() {
        if !point_free(q, discs) {
            return Err(format!("node {i} {q:?} is not free"));
        }
    }
    for (i, e) in roadmap.edges().iter().enumerate() {
        let path = roadmap.edge_path(i, e.a);
        if !path_free(&path, discs) {
            return Err(format!("edge {i} ({} – {}) {path:?} is not free", e.a, e.b));
        }
        let len = polyline_length(&path);
        if (len - e.length).abs() > 1e-9 * (1.0 + len) {
            return Err(format!(
                "edge {i} has length {} but its path is {len}",
                e.length
            ));
        }
    }
    Ok(())
}

/// Free-space components on a grid of `n × n` cell centres: adjacent centres (8-neighbours)
/// are joined when the segment between them is free. Returns a labeller: the component of a
/// free point is that of a grid centre it sees by a free segment among its nearest ones (None
/// if it sees none, which a fine enough grid makes rare).
pub struct GridComponents {
    n: usize,
    label: Vec<u32>,
    discs: Vec<([f64; 2], f64)>,
}

impl GridComponents {
    pub fn new(scene: &Scene, n: usize) -> Self {
        let discs = discs(scene);
        let centre =
            |i: usize, j: usize| vec![(i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64];
        let mut label = vec![u32::MAX; n * n];
        let mut next = 0;
        for start in 0..n * n {
            if label[start] != u32::MAX || !point_free(&centre(start / n, start % n), &discs) {
                continue;
            }
            label[start] = next;
            let mut stack = vec![start];
            while let Some(c) = stack.pop() {
                let (i, j) = ((c / n) as i64, (c % n) as i64);
                for di in -1..=1i64 {
                    for dj in -1..=1i64 {
                        let (a, b) = (i + di, j + dj);
                        if (di, dj) == (0, 0) || a < 0 || b < 0 || a >= n as i64 || b >= n as i64 {
                            continue;
                        }
                        let d = (a * n as i64 + b) as usize;
                        if label[d] == u32::MAX
                            && segment_free(
                                &centre(i as usize, j as usize),
                                &centre(a as usize, b as usize),
                                &discs,
                            )
                        {
                            label[d] = next;
                            stack.push(d);
                        }
                    }
                }
            }
            next += 1;
        }
        GridComponents { n, label, discs }
    }

    pub fn component(&self, p: &[f64]) -> Option<u32> {
        let n = self.n as i64;
        let (ci, cj) = ((p[0] * n as f64) as i64, (p[1] * n as f64) as i64);
        for r in 0..3i64 {
            for i in ci - r..=ci + r {
                for j in cj - r..=cj + r {
                    if i < 0 || j < 0 || i >= n || j >= n {
                        continue;
                    }
                    let l = self.label[(i * n + j) as usize];
                    let c = [(i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64];
                    if l != u32::MAX && segment_free(p, &c, &self.discs) {
                        return Some(l);
                    }
                }
            }
        }
        None
    }

    /// Whether the grid says start and goal lie in one free component.
    pub fn solvable(&self, s: &[f64], g: &[f64]) -> Option<bool> {
        Some(self.component(s)? == self.component(g)?)
    }
}
