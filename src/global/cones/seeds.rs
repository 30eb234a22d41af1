//! Cones as roadmap seeds (issue 14, part 2): Brooks's freeways turned into a starting
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
    // points per cone: the intersections and the ends
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
    let dim = scene.space.dim();
    let mut coords: Vec<f64> = Vec::new();
    let mut index: HashMap<[u64; 3], u32> = HashMap::new();
    let mut edges: Vec<Edge> = Vec::new();
    let mut joined: HashSet<(u32, u32)> = HashSet::new();
    let mut at_point: HashMap<[u64; 2], Vec<u32>> = HashMap::new();
    let mut node = |q: &Config, coords: &mut Vec<f64>, counts: &mut CallCounts| -> Option<u32> {
        let key = [
            q[0].to_bits(),
            q[1].to_bits(),
            q.get(2).copied().unwrap_or(0.0).to_bits(),
        ];
        if let Some(&i) = index.get(&key) {
            return Some(i);
        }
        if coords.len() / dim >= max_nodes || !oracle.is_free(q, counts) {
            return None;
        }
        let i = (coords.len() / dim) as u32;
        coords.extend_from_slice(q);
        index.insert(key, i);
        at_point
            .entry([q[0].to_bits(), q[1].to_bits()])
            .or_default()
            .push(i);
        Some(i)
    };
    let config = |p: P, phi: f64| -> Config {
        if fw.oriented {
            let mut q = vec![p[0], p[1], phi];
            scene.space.normalize(&mut q);
            q
        } else {
            vec![p[0], p[1]]
        }
    };
    for (c, params_on) in per_cone.iter().enumerate() {
        let cone = &fw.cones[c];
        for w in params_on.windows(2) {
            let (a, b) = (w[0], w[1]);
            for arc in fw.legal(cone, a, b).arcs() {
                let phi = arc.mid();
                let (qa, qb) = (config(cone.point(a), phi), config(cone.point(b), phi));
                let (Some(ia), Some(ib)) = (
                    node(&qa, &mut coords, &mut counts),
                    node(&qb, &mut coords, &mut counts),
                ) else {
                    continue;
                };
                let Some(m) = scene.space.direct_motion(&qa, &qb) else {
                    continue;
                };
                // two cones along one stretch (a cone and its parallel extension) give the
                // same pair: one edge, one check
                if ia != ib
                    && !joined.contains(&(ia.min(ib), ia.max(ib)))
                    && oracle.check_motion(&m, &mut counts)?
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
    // turns between the orientations met at one point (shorter way, checked). A turn of
    // more than a quarter turn goes through its middle orientation as a corner: a turn of
    // (nearly) half a turn has two "shorter ways", and read from its other end an edge
    // without a corner could take the arc that was not checked (found by the bench's exact
    // re-check of returned paths on se2-translate, Maze and Barriers)
    let mut points: Vec<&Vec<u32>> = at_point.values().collect();
    points.sort();
    for ids in points {
        for (k, &i) in ids.iter().enumerate() {
            for &j in &ids[k + 1..] {
                let qi = &coords[i as usize * dim..(i as usize + 1) * dim];
                let qj = &coords[j as usize * dim..(j as usize + 1) * dim];
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
                let mut free = true;
                let mut length = 0.0;
                for w in pieces.windows(2) {
                    let Some(m) = scene.space.direct_motion(w[0], w[1]) else {
                        free = false;
                        break;
                    };
                    if !oracle.check_motion(&m, &mut counts)? {
                        free = false;
                        break;
                    }
                    length += scene.space.distance(w[0], w[1]);
                }
                if free {
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
    Roadmap::assemble(header, coords, edges).map_err(OracleError::Unsupported)
}
