//! Path shortening (CHS A.1): "a graph is built whose vertices are the corners of the path and
//! whose edges are all direct connections not intersecting an obstacle. The shortest way from
//! start to goal is then taken as a new path."
//!
//! Departure from the seed, same result: the visibility graph is evaluated *lazily* (as in
//! Bohlin and Kavraki's Lazy PRM). A* runs on all pairs of corners weighted by the length
//! of their direct path; only the pairs on the current shortest path are checked, a blocked
//! pair is removed and the search repeated. The path returned is the shortest path in the full
//! visibility graph up to a factor `1 + `[`UNCHECKED`] (every pair on it was checked, and every
//! unchecked pair was weighted by its length, that little more, and no free path can be
//! shorter than its length), typically after checking a handful of pairs instead of all
//! `m(m-1)/2`.

use super::{check_direct_known, direct_length, KnownPieces};
use crate::deadline::Deadline;
use crate::oracle::{CallCounts, CollisionOracle, OracleError};
use crate::space::{Config, Group, Space};

/// The relative weight added to a pair of corners not yet checked: among paths of equal
/// length the one already known free is taken, no check is spent on a pair that cannot shorten
/// the path, and the path returned is at most this much longer than the shortest in the
/// visibility graph.
///
/// Not in the seed, and what one group per joint calls for: the direct path between two
/// corners of a staircase that moves every joint one way is exactly as long as the staircase
/// (the length adds up over the groups), so an arm's path is full of pairs that gain nothing
/// and were all checked, most of them blocked (the box's workcell: query p50
/// 4.8 → 4.2 ms).
pub const UNCHECKED: f64 = 1e-6;

#[derive(Clone, Copy, PartialEq)]
enum Pair {
    Unknown,
    Free,
    Blocked,
}

/// The shortest path through the visibility graph over the corners of `path`, whose
/// consecutive corners must be joined by free direct paths. The result again consists of
/// corners joined by single-group straight motions (a direct path across several groups is
/// expanded into its pieces). Oracle calls are added to `counts`; a piece shared by several
/// pairs of corners, or one of the path's own, is not asked about ([`KnownPieces`]).
pub fn shorten(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    path: &[Config],
    counts: &mut CallCounts,
) -> Result<Vec<Config>, OracleError> {
    let mut known = KnownPieces::new();
    known.certify_path(space, groups, path);
    shorten_known(
        space,
        oracle,
        groups,
        path,
        &mut known,
        counts,
        &Deadline::none(),
    )
}

/// [`shorten()`] with the pieces known so far (those of `path` among them, see
/// [`KnownPieces::certify_path`]), kept up to date: a query shares them between the greedy
/// pass and the visibility graph. Once `deadline` passes (checked before every check of a
/// pair) it stops, a query's time being a promise, and returns the shortest path over the
/// pairs it had found free: valid, and never longer than `path` (whose own pairs are among
/// them), so the checks made before the deadline are not lost.
pub fn shorten_known(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    path: &[Config],
    known: &mut KnownPieces,
    counts: &mut CallCounts,
    deadline: &Deadline,
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
    // symmetric optimistic costs: the direct length (`UNCHECKED` more while a pair is not
    // known free), infinite once a pair is found blocked
    let mut length = vec![0.0; m * m];
    let mut cost = vec![f64::INFINITY; m * m];
    for i in 0..m {
        for j in i + 1..m {
            let d = direct_length(space, groups, &path[i], &path[j]);
            let c = if j == i + 1 { d } else { d * (1.0 + UNCHECKED) };
            length[i * m + j] = d;
            cost[i * m + j] = c;
            cost[j * m + i] = c;
        }
    }
    // the direct length to the last corner, a consistent A* heuristic (triangle inequality;
    // no cost is below the direct length)
    let h: Vec<f64> = (0..m).map(|i| length[i * m + m - 1]).collect();
    loop {
        // the shortest candidate path over the pairs not known to be blocked: a pair that
        // what is known blocks already (an inner corner in collision, a piece found blocked) is
        // set aside as the search reaches it, not after it returned a path through it
        let order = astar(m, &mut cost, &h, &mut |i, j| {
            let k = i.min(j) * m + i.max(j);
            let blocked = state[k] == Pair::Unknown
                && known.blocks(space, groups, &path[i.min(j)], &path[i.max(j)]);
            if blocked {
                state[k] = Pair::Blocked;
            }
            blocked
        });
        let mut all_free = true;
        for w in order.windows(2) {
            let k = w[0].min(w[1]) * m + w[0].max(w[1]);
            if state[k] == Pair::Unknown {
                if deadline.expired() {
                    // the best path certified so far: unchecked pairs count as blocked
                    let mut free = vec![f64::INFINITY; m * m];
                    for i in 0..m {
                        for j in i + 1..m {
                            if state[i * m + j] == Pair::Free {
                                free[i * m + j] = length[i * m + j];
                                free[j * m + i] = length[i * m + j];
                            }
                        }
                    }
                    let order = astar(m, &mut free, &h, &mut |_, _| false);
                    return Ok(assemble(path, &order, &corners));
                }
                let (i, j) = (w[0].min(w[1]), w[0].max(w[1]));
                match check_direct_known(
                    space,
                    oracle,
                    groups,
                    &path[i],
                    &path[j],
                    Some(known),
                    counts,
                )? {
                    Some(c) => {
                        state[k] = Pair::Free;
                        corners[k] = Some(c);
                        cost[i * m + j] = length[i * m + j];
                        cost[j * m + i] = length[i * m + j];
                    }
                    None => {
                        state[k] = Pair::Blocked;
                        cost[i * m + j] = f64::INFINITY;
                        cost[j * m + i] = f64::INFINITY;
                        all_free = false;
                        break;
                    }
                }
            }
        }
        if all_free {
            return Ok(assemble(path, &order, &corners));
        }
    }
}

/// The path through corners `order` of `path` (indices, from the first to the last), each
/// pair joined by its free direct path: the corners recorded when it was checked (`corners`,
/// indexed `i * m + j` with `i < j`), or the step itself where it is one of `path`'s own.
fn assemble(path: &[Config], order: &[usize], corners: &[Option<Vec<Config>>]) -> Vec<Config> {
    let m = path.len();
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
    out
}

/// A* on the complete graph over `m` corners (dense, `O(m)` per expansion), from corner 0 to
/// corner `m - 1`; `cost` is the symmetric `m × m` matrix of pair costs (infinite for blocked
/// pairs and the diagonal), `h[i]` the direct length from `i` to the last corner. Direct
/// lengths obey the triangle inequality, so `h` is consistent, blocked pairs included, and
/// the path found is a shortest one; the search expands only corners that can lie on it,
/// which is what makes re-running it after each blocked pair affordable on long paths (a
/// 111-corner path checks thousands of pairs in a cluttered scene). Consecutive pairs are
/// always finite, so a path always exists.
///
/// `set_aside(i, j)` is asked about the pair joining a corner to its parent as the corner is
/// expanded (Lazy Weighted A*'s edge evaluation on expansion): where it says the pair is
/// blocked, its cost becomes infinite and the corner takes its best parent among the corners
/// done, staying open. A corner's parent at expansion is final, so every pair of the path
/// returned was asked, and the path is a shortest one over the pairs not set aside. Re-running
/// the search once per pair set aside would cost as much as the checks: the
/// box workcell's answers, 36 corners, 208 searches for 40 checks.
fn astar(
    m: usize,
    cost: &mut [f64],
    h: &[f64],
    set_aside: &mut dyn FnMut(usize, usize) -> bool,
) -> Vec<usize> {
    let mut dist = vec![f64::INFINITY; m];
    let mut prev = vec![usize::MAX; m];
    // `dist + h` of the open corners, infinite once a corner is done (or before it is
    // reached): the selection is one scan for the minimum instead of a sum and a flag per
    // corner, and picks the same corner (the first of the smallest)
    let mut open = vec![f64::INFINITY; m];
    let mut done = vec![false; m];
    dist[0] = 0.0;
    open[0] = h[0];
    loop {
        let mut best = usize::MAX;
        let mut best_f = f64::INFINITY;
        for (i, &f) in open.iter().enumerate() {
            if f < best_f {
                best_f = f;
                best = i;
            }
        }
        if best == usize::MAX {
            break;
        }
        let u = best;
        let p = prev[u];
        if p != usize::MAX && set_aside(p, u) {
            cost[p * m + u] = f64::INFINITY;
            cost[u * m + p] = f64::INFINITY;
            // the best parent among the corners done (the corners done keep their distance)
            let (mut d, mut from) = (f64::INFINITY, usize::MAX);
            for v in (0..m).filter(|&v| done[v]) {
                let via = dist[v] + cost[v * m + u];
                if via < d {
                    (d, from) = (via, v);
                }
            }
            dist[u] = d;
            prev[u] = from;
            open[u] = d + h[u];
            continue;
        }
        if u == m - 1 {
            break;
        }
        let du = dist[u];
        done[u] = true;
        open[u] = f64::INFINITY;
        let row = &cost[u * m..(u + 1) * m];
        for v in 0..m {
            if done[v] {
                continue;
            }
            let d = du + row[v];
            if d < dist[v] {
                dist[v] = d;
                prev[v] = u;
                open[v] = d + h[v];
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

/// One greedy pass over `path` that drops every corner the last kept corner can see past: a
/// corner is kept only if the direct path from the last kept one to the corner after it is
/// blocked. From each kept corner the pass gallops: it asks the corner after next, then
/// corners twice as far each time until one is blocked, and then halves the gap between the
/// farthest free and the nearest blocked one. A run of `r` corners it can drop costs about
/// `2 log₂ r` checks instead of `r`; where one check's cost grows with the distance (an arm's
/// straight motion is proved piece by piece) that is what the pass costs. It keeps no corner
/// that asking the corners one after another would drop: every corner before the first
/// blocked one is free, so the halving ends at or beyond it. The result is never longer
/// (triangle inequality) and again consists of corners joined by single-group straight
/// motions.
///
/// Not in the seed: a cheap first pass for long roadmap paths, whose full visibility graph
/// costs up to `m(m-1)/2` checks (a 111-corner path across OMPL.app's Home checked 4573 pairs);
/// [`shorten`] then runs on the corners that are left.
pub fn drop_corners(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    path: &[Config],
    counts: &mut CallCounts,
) -> Result<Vec<Config>, OracleError> {
    let mut known = KnownPieces::new();
    known.certify_path(space, groups, path);
    drop_corners_known(
        space,
        oracle,
        groups,
        path,
        &mut known,
        counts,
        &Deadline::none(),
    )
}

/// [`drop_corners`] with the pieces known so far (see [`shorten_known`]). A check from a
/// corner to the one after next that is the path's own two pieces costs no call. Once
/// `deadline` passes (checked before every check) the rest of `path` is kept as it is.
pub fn drop_corners_known(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    path: &[Config],
    known: &mut KnownPieces,
    counts: &mut CallCounts,
    deadline: &Deadline,
) -> Result<Vec<Config>, OracleError> {
    let m = path.len();
    if m <= 2 {
        return Ok(path.to_vec());
    }
    let mut out = vec![path[0].clone()];
    // the last kept corner, an index into `path`
    let mut from = 0;
    while from + 1 < m {
        // `None`: out of time, the rest of `path` as it is
        let mut check = |j: usize, known: &mut KnownPieces| -> Result<Option<_>, OracleError> {
            if deadline.expired() {
                return Ok(None);
            }
            check_direct_known(
                space,
                oracle,
                groups,
                &path[from],
                &path[j],
                Some(known),
                counts,
            )
            .map(Some)
        };
        // the farthest corner known free from `from` (with the direct path's corners; the
        // next one is joined by the input's own motion), and the nearest known blocked
        let (mut free, mut corners): (usize, Option<Vec<Config>>) = (from + 1, None);
        let mut blocked = m;
        let mut out_of_time = false;
        // gallop: the corner after next, then twice as far from `from` each time
        let mut probe = from + 2;
        while probe < blocked && probe < m {
            match check(probe, known)? {
                None => {
                    out_of_time = true;
                    break;
                }
                Some(Some(c)) => {
                    (free, corners) = (probe, Some(c));
                    probe = (from + 2 * (probe - from)).min(m - 1).max(probe + 1);
                }
                Some(None) => blocked = probe,
            }
        }
        // halve the gap between the farthest free and the nearest blocked corner
        while !out_of_time && blocked < m && blocked - free > 1 {
            let mid = free + (blocked - free) / 2;
            match check(mid, known)? {
                None => out_of_time = true,
                Some(Some(c)) => (free, corners) = (mid, Some(c)),
                Some(None) => blocked = mid,
            }
        }
        match corners {
            Some(c) => out.extend(c),
            None => out.push(path[free].clone()),
        }
        from = free;
        if out_of_time {
            out.extend(path[from + 1..].iter().cloned());
            return Ok(out);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::astar;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Dijkstra's distance from corner 0 to corner `m - 1` over the finite costs.
    fn shortest(m: usize, cost: &[f64]) -> f64 {
        let mut dist = vec![f64::INFINITY; m];
        let mut done = vec![false; m];
        dist[0] = 0.0;
        while let Some(u) = (0..m)
            .filter(|&u| !done[u] && dist[u].is_finite())
            .min_by(|&a, &b| dist[a].total_cmp(&dist[b]))
        {
            done[u] = true;
            for v in 0..m {
                dist[v] = dist[v].min(dist[u] + cost[u * m + v]);
            }
        }
        dist[m - 1]
    }

    /// Corners set aside as the search reaches them: the path found is a shortest one over
    /// the pairs that are not, every pair on it was asked about and none set aside, and no
    /// pair is asked about twice.
    #[test]
    fn pairs_set_aside_on_expansion_leave_a_shortest_path_over_the_rest() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for _ in 0..300 {
            let m = rng.random_range(2..24);
            let points: Vec<[f64; 2]> = (0..m)
                .map(|_| [rng.random_range(0.0..1.0), rng.random_range(0.0..1.0)])
                .collect();
            let d = |i: usize, j: usize| {
                (points[i][0] - points[j][0]).hypot(points[i][1] - points[j][1])
            };
            let mut cost = vec![f64::INFINITY; m * m];
            let mut blocked = vec![false; m * m];
            for i in 0..m {
                for j in i + 1..m {
                    cost[i * m + j] = d(i, j);
                    cost[j * m + i] = d(i, j);
                    // consecutive corners are always joined (the path's own pieces)
                    let b = j > i + 1 && rng.random_bool(0.6);
                    blocked[i * m + j] = b;
                    blocked[j * m + i] = b;
                }
            }
            let h: Vec<f64> = (0..m).map(|i| d(i, m - 1)).collect();
            let mut asked = vec![0u32; m * m];
            let mut work = cost.clone();
            let order = astar(m, &mut work, &h, &mut |i, j| {
                asked[i * m + j] += 1;
                blocked[i * m + j]
            });
            assert_eq!((order[0], *order.last().unwrap()), (0, m - 1));
            let mut length = 0.0;
            for w in order.windows(2) {
                let k = w[0] * m + w[1];
                assert!(!blocked[k], "a blocked pair on the path: {w:?}");
                assert_eq!(asked[k], 1, "each pair of the path asked once: {w:?}");
                length += cost[k];
            }
            let open: Vec<f64> = cost
                .iter()
                .zip(&blocked)
                .map(|(&c, &b)| if b { f64::INFINITY } else { c })
                .collect();
            let best = shortest(m, &open);
            assert!(
                (length - best).abs() <= 1e-12 * (1.0 + best),
                "{length} against {best}"
            );
            assert!(asked.iter().all(|&a| a <= 1), "a pair asked twice");
        }
    }
}
