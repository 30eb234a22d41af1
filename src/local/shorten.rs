//! Path shortening (CHS A.1): "a graph is built whose vertices are the corners of the path and
//! whose edges are all direct connections not intersecting an obstacle. The shortest way from
//! start to goal is then taken as a new path."
//!
//! Departure from the seed, same result: the visibility graph is evaluated *lazily* (as in
//! Bohlin and Kavraki's Lazy PRM). Dijkstra runs on all pairs of corners weighted by the length
//! of their direct path; only the pairs on the current shortest path are checked, a blocked
//! pair is removed and the search repeated. The path returned is the shortest path in the full
//! visibility graph (every pair on it was checked, and every unchecked pair was weighted by a
//! length no blocked-free path can beat), typically after checking a handful of pairs instead
//! of all `m(m-1)/2`.

use super::{check_direct, direct_length};
use crate::oracle::{CallCounts, CollisionOracle, OracleError};
use crate::space::{Config, Group, Space};

#[derive(Clone, Copy, PartialEq)]
enum Pair {
    Unknown,
    Free,
    Blocked,
}

/// The shortest path through the visibility graph over the corners of `path`, whose
/// consecutive corners must be joined by free direct paths. The result again consists of
/// corners joined by single-group straight motions (a direct path across several groups is
/// expanded into its pieces). Oracle calls are added to `counts`.
pub fn shorten(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    path: &[Config],
    counts: &mut CallCounts,
) -> Result<Vec<Config>, OracleError> {
    let m = path.len();
    if m <= 2 {
        return Ok(path.to_vec());
    }
    let mut state = vec![Pair::Unknown; m * m];
    let mut corners: Vec<Option<Vec<Config>>> = vec![None; m * m];
    for i in 0..m - 1 {
        state[i * m + i + 1] = Pair::Free;
    }
    let weight: Vec<f64> = (0..m * m)
        .map(|k| {
            let (i, j) = (k / m, k % m);
            if i < j {
                direct_length(space, groups, &path[i], &path[j])
            } else {
                f64::INFINITY
            }
        })
        .collect();
    loop {
        let order = dijkstra(m, |i, j| match state[i * m + j] {
            Pair::Blocked => None,
            _ => Some(weight[i * m + j]),
        });
        let mut all_free = true;
        for w in order.windows(2) {
            let k = w[0].min(w[1]) * m + w[0].max(w[1]);
            if state[k] == Pair::Unknown {
                let (i, j) = (w[0].min(w[1]), w[0].max(w[1]));
                match check_direct(space, oracle, groups, &path[i], &path[j], counts)? {
                    Some(c) => {
                        state[k] = Pair::Free;
                        corners[k] = Some(c);
                    }
                    None => {
                        state[k] = Pair::Blocked;
                        all_free = false;
                        break;
                    }
                }
            }
        }
        if all_free {
            let mut out = vec![path[0].clone()];
            for w in order.windows(2) {
                let (i, j) = (w[0].min(w[1]), w[0].max(w[1]));
                match &corners[i * m + j] {
                    // a direct path checked from i to j, walked here from j to i: the same
                    // pieces backwards, so its corners reversed (dropping j itself), then i
                    Some(c) if w[0] > w[1] => {
                        out.extend(c[..c.len() - 1].iter().rev().cloned());
                        out.push(path[i].clone());
                    }
                    Some(c) => out.extend(c.iter().cloned()),
                    None => out.push(path[w[1]].clone()),
                }
            }
            return Ok(out);
        }
    }
}

/// Dijkstra on the complete graph over `m` corners (dense, `O(m²)`), from corner 0 to corner
/// `m - 1`; `weight(i, j)` with `i < j` is `None` for a blocked pair. Consecutive pairs are
/// always free, so a path always exists.
fn dijkstra(m: usize, weight: impl Fn(usize, usize) -> Option<f64>) -> Vec<usize> {
    let mut dist = vec![f64::INFINITY; m];
    let mut prev = vec![usize::MAX; m];
    let mut done = vec![false; m];
    dist[0] = 0.0;
    for _ in 0..m {
        let Some(u) = (0..m)
            .filter(|&i| !done[i] && dist[i].is_finite())
            .min_by(|&a, &b| dist[a].total_cmp(&dist[b]))
        else {
            break;
        };
        done[u] = true;
        if u == m - 1 {
            break;
        }
        for v in 0..m {
            if done[v] || v == u {
                continue;
            }
            if let Some(w) = weight(u.min(v), u.max(v)) {
                if dist[u] + w < dist[v] {
                    dist[v] = dist[u] + w;
                    prev[v] = u;
                }
            }
        }
    }
    let mut order = vec![m - 1];
    while let Some(&last) = order.last() {
        if last == 0 {
            break;
        }
        order.push(prev[last]);
    }
    order.reverse();
    order
}
