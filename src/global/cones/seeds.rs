//! Cones as roadmap seeds: Brooks's freeways turned into a starting
//! roadmap. Nodes are the spine intersections and spine ends, once per orientation interval
//! legal there (at the interval's middle); edges follow the spines between consecutive nodes
//! at an orientation legal over the stretch, and turn between two nodes at one point. Every
//! node and edge is checked by the exact oracle, so the seed roadmap is as valid as a learnt
//! one; learning then grows it (`Learner::learn_from`).

use super::{Freeways, P};
use crate::local::LocalSpec;
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle, OracleError};
use crate::roadmap::{Edge, Header, LearnParams, Roadmap};
use crate::scene::Scene;
use crate::space::Config;
use std::collections::{HashMap, HashSet};
use std::f64::consts::{FRAC_PI_2, TAU};

/// Most seed nodes when the caller gives no cap.
pub const MAX_SEED_NODES: usize = 4000;

/// A roadmap of the freeways' spine points, for `learn_from`, of at most `max_nodes` nodes
/// (cones in the order built; the rest of a node budget is the learner's). `params`,
/// `local_spec` and `seed` go to its header as the learner will record them.
pub fn seed_roadmap(
    fw: &Freeways,
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    params: &LearnParams,
    local_spec: &LocalSpec,
    seed: u64,
    max_nodes: usize,
) -> Result<Roadmap, OracleError> {
    let mut counts = CallCounts::default();
    let mut nodes = SeedNodes {
        oracle,
        dim: scene.space.dim(),
        max_nodes,
        coords: Vec::new(),
        index: HashMap::new(),
        at_point: HashMap::new(),
    };
    let mut edges: Vec<Edge> = Vec::new();
    spine_edges(fw, scene, &mut nodes, &mut edges, &mut counts)?;
    turn_edges(scene, oracle, &nodes, &mut edges, &mut counts)?;
    let header = Header {
        space: scene.space.clone(),
        fingerprint: scene.fingerprint(),
        params: params.clone(),
        local_spec: local_spec.clone(),
        seed,
        node_budget: None,
        rounds: 0,
        counts,
    };
    Roadmap::assemble(header, nodes.coords, edges).map_err(OracleError::Unsupported)
}

/// The points of each cone's spine that become nodes: its intersections and its ends (just
/// inside the margin), sorted, each once.
fn spine_points(fw: &Freeways) -> Vec<Vec<f64>> {
    let mut per_cone: Vec<Vec<f64>> = vec![Vec::new(); fw.cones.len()];
    for c in &fw.crossings {
        per_cone[c.a].push(c.sa);
        per_cone[c.b].push(c.sb);
    }
    for (i, c) in fw.cones.iter().enumerate() {
        per_cone[i].push(c.lo + fw.margin);
        per_cone[i].push(c.hi - fw.margin);
        per_cone[i].sort_by(f64::total_cmp);
        per_cone[i].dedup();
    }
    per_cone
}

/// A configuration at `p` with orientation `phi` (normalised; dropped in R²).
fn seed_config(fw: &Freeways, scene: &Scene, p: P, phi: f64) -> Config {
    if fw.oriented {
        let mut q = vec![p[0], p[1], phi];
        scene.space.normalize(&mut q);
        q
    } else {
        vec![p[0], p[1]]
    }
}

/// The seed roadmap's nodes as they are found: each configuration once, checked free, within
/// the cap, and grouped by point for the turns between them.
struct SeedNodes<'a> {
    oracle: &'a dyn CollisionOracle,
    dim: usize,
    max_nodes: usize,
    coords: Vec<f64>,
    index: HashMap<[u64; 3], u32>,
    at_point: HashMap<[u64; 2], Vec<u32>>,
}

impl SeedNodes<'_> {
    /// The node at `q`, added if new and free and the cap allows.
    fn node(&mut self, q: &Config, counts: &mut CallCounts) -> Option<u32> {
        let key = [
            q[0].to_bits(),
            q[1].to_bits(),
            q.get(2).copied().unwrap_or(0.0).to_bits(),
        ];
        if let Some(&i) = self.index.get(&key) {
            return Some(i);
        }
        if self.coords.len() / self.dim >= self.max_nodes || !self.oracle.is_free(q, counts) {
            return None;
        }
        let i = (self.coords.len() / self.dim) as u32;
        self.coords.extend_from_slice(q);
        self.index.insert(key, i);
        self.at_point
            .entry([q[0].to_bits(), q[1].to_bits()])
            .or_default()
            .push(i);
        Some(i)
    }

    /// The configuration of node `i`.
    fn config(&self, i: u32) -> &[f64] {
        &self.coords[i as usize * self.dim..(i as usize + 1) * self.dim]
    }
}

/// The edges along the spines: between consecutive points of a cone, at the middle of each
/// interval of orientations legal over the stretch, checked.
fn spine_edges(
    fw: &Freeways,
    scene: &Scene,
    nodes: &mut SeedNodes,
    edges: &mut Vec<Edge>,
    counts: &mut CallCounts,
) -> Result<(), OracleError> {
    let oracle = nodes.oracle;
    let mut joined: HashSet<(u32, u32)> = HashSet::new();
    for (c, params_on) in spine_points(fw).iter().enumerate() {
        let cone = &fw.cones[c];
        for w in params_on.windows(2) {
            let (a, b) = (w[0], w[1]);
            for arc in fw.legal(cone, a, b).arcs() {
                let phi = arc.mid();
                let qa = seed_config(fw, scene, cone.point(a), phi);
                let qb = seed_config(fw, scene, cone.point(b), phi);
                let (Some(ia), Some(ib)) = (nodes.node(&qa, counts), nodes.node(&qb, counts))
                else {
                    continue;
                };
                let Some(m) = scene.space.direct_motion(&qa, &qb) else {
                    continue;
                };
                // two cones along one stretch (a cone and its parallel extension) give the
                // same pair: one edge, one check
                if ia != ib
                    && !joined.contains(&(ia.min(ib), ia.max(ib)))
                    && oracle.check_motion(&m, counts)?
                {
                    joined.insert((ia.min(ib), ia.max(ib)));
                    edges.push(Edge {
                        a: ia,
                        b: ib,
                        length: scene.space.distance(&qa, &qb),
                        corners: Vec::new(),
                    });
                }
            }
        }
    }
    Ok(())
}

/// Turns between the orientations met at one point (shorter way, checked). A turn of more than
/// a quarter turn goes through its middle orientation as a corner: a turn of (nearly) half a
/// turn has two "shorter ways", and read from its other end an edge without a corner could take
/// the arc that was not checked.
fn turn_edges(
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    nodes: &SeedNodes,
    edges: &mut Vec<Edge>,
    counts: &mut CallCounts,
) -> Result<(), OracleError> {
    let mut points: Vec<&Vec<u32>> = nodes.at_point.values().collect();
    points.sort();
    for ids in points {
        for (k, &i) in ids.iter().enumerate() {
            for &j in &ids[k + 1..] {
                let (qi, qj) = (nodes.config(i), nodes.config(j));
                let turn = (qj[2] - qi[2]).rem_euclid(TAU);
                let corners: Vec<Config> = if turn.min(TAU - turn) > FRAC_PI_2 {
                    vec![scene.space.interpolate(qi, qj, 0.5)]
                } else {
                    Vec::new()
                };
                let pieces: Vec<&[f64]> = std::iter::once(qi)
                    .chain(corners.iter().map(Vec::as_slice))
                    .chain(std::iter::once(qj))
                    .collect();
                if let Some(length) = free_length(scene, oracle, &pieces, counts)? {
                    edges.push(Edge {
                        a: i,
                        b: j,
                        length,
                        corners: corners.concat(),
                    });
                }
            }
        }
    }
    Ok(())
}

/// The length of the chain of direct motions through `pieces`, or `None` at the first motion
/// that is not free (the rest unchecked).
fn free_length(
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    pieces: &[&[f64]],
    counts: &mut CallCounts,
) -> Result<Option<f64>, OracleError> {
    let mut length = 0.0;
    for w in pieces.windows(2) {
        let Some(m) = scene.space.direct_motion(w[0], w[1]) else {
            return Ok(None);
        };
        if !oracle.check_motion(&m, counts)? {
            return Ok(None);
        }
        length += scene.space.distance(w[0], w[1]);
    }
    Ok(Some(length))
}
