//! Shortening over one group per axis (the arm's mode, here a point among discs with x and y
//! moving one at a time): the lazy visibility graph against the visibility graph built by
//! brute force, the pairs it need not check, and the corner test that refuses a pair before
//! any sweep. Every path is re-checked by the independent segment test of `roadmap_support`.

use crate::roadmap_support;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use roadmap_support::*;
use viaroad::local::shorten::UNCHECKED;
use viaroad::local::{
    check_direct, check_direct_known, direct_length, path_length, shorten, KnownPieces,
};
use viaroad::oracle::CallCounts;
use viaroad::scene::Scene;
use viaroad::space::Group;

/// A free staircase of `steps` axis moves (alternating x and y, each a random amount either
/// way), from a free point; every step checked free by the independent segment test.
fn staircase(scene: &Scene, seed: u64, steps: usize) -> Vec<Vec<f64>> {
    let d = discs(scene);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let start = random_queries(scene, 1, seed).remove(0).0;
    let mut path = vec![start];
    while path.len() <= steps {
        let last = path[path.len() - 1].clone();
        let axis = path.len() % 2;
        let mut next = last.clone();
        next[axis] = (last[axis] + rng.random_range(-0.25..0.25)).clamp(0.0, 1.0);
        if next != last && segment_free(&last, &next, &d) {
            path.push(next);
        }
    }
    path
}

/// Shortest path from the first corner to the last over the pairs `free` says are joined by a
/// free direct path, weighted by their direct length (Dijkstra, dense).
fn shortest(path: &[Vec<f64>], length: impl Fn(usize, usize) -> f64, free: &[bool]) -> f64 {
    let m = path.len();
    let mut dist = vec![f64::INFINITY; m];
    let mut done = vec![false; m];
    dist[0] = 0.0;
    for _ in 0..m {
        let Some(u) = (0..m)
            .filter(|&i| !done[i])
            .min_by(|&a, &b| dist[a].total_cmp(&dist[b]))
        else {
            break;
        };
        done[u] = true;
        for v in 0..m {
            if free[u * m + v] {
                dist[v] = dist[v].min(dist[u] + length(u, v));
            }
        }
    }
    dist[m - 1]
}

/// Consecutive corners differ in one coordinate: single-axis moves, as the groups demand.
fn one_axis_at_a_time(path: &[Vec<f64>]) -> bool {
    path.windows(2)
        .all(|w| w[0].iter().zip(&w[1]).filter(|(a, b)| a != b).count() <= 1)
}

/// The lazy visibility graph returns what the full one does (every pair checked, Dijkstra),
/// up to its margin for unchecked pairs, and never a path shorter than the full one's
/// shortest (its pairs are all free).
#[test]
fn the_visibility_graph_is_shortest_within_its_margin() {
    let scene = disc_scene(5, 40, 0.06);
    let d = discs(&scene);
    let oracle = scene.oracle();
    let groups = scene.space.groups(true);
    let mut shortened = 0;
    for seed in 0..12 {
        let raw = staircase(&scene, seed, 24);
        let m = raw.len();
        let mut free = vec![false; m * m];
        for i in 0..m {
            for j in i + 1..m {
                let c = &mut CallCounts::default();
                let f = check_direct(&scene.space, oracle.as_ref(), &groups, &raw[i], &raw[j], c)
                    .unwrap()
                    .is_some();
                free[i * m + j] = f;
                free[j * m + i] = f;
            }
        }
        let length = |i: usize, j: usize| direct_length(&scene.space, &groups, &raw[i], &raw[j]);
        let best = shortest(&raw, length, &free);
        let c = &mut CallCounts::default();
        let path = shorten(&scene.space, oracle.as_ref(), &groups, &raw, c).unwrap();
        let got = path_length(&scene.space, &groups, &path);
        assert!(path_free(&path, &d), "seed {seed}: {path:?}");
        assert!(one_axis_at_a_time(&path), "seed {seed}: {path:?}");
        assert_eq!((&path[0], &path[path.len() - 1]), (&raw[0], &raw[m - 1]));
        assert!(got >= best - 1e-12, "seed {seed}: {got} < {best}");
        assert!(
            got <= best * (1.0 + UNCHECKED) + 1e-12,
            "seed {seed}: {got} > {best}"
        );
        shortened += usize::from(got < path_length(&scene.space, &groups, &raw) - 1e-9);
    }
    assert!(
        shortened >= 6,
        "only {shortened} of 12 staircases shortened"
    );
}

/// A staircase that moves every axis one way is exactly as long as the direct path between
/// any two of its corners: nothing to gain, and nothing is checked.
#[test]
fn a_staircase_moving_every_axis_one_way_costs_no_check() {
    let scene = disc_scene(5, 40, 0.06);
    let oracle = scene.oracle();
    let groups = scene.space.groups(true);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut p = vec![0.02, 0.02];
    let mut raw = vec![p.clone()];
    for k in 0..30 {
        p[k % 2] += rng.random_range(0.001..0.06);
        raw.push(p.clone());
    }
    let c = &mut CallCounts::default();
    let path = shorten(&scene.space, oracle.as_ref(), &groups, &raw, c).unwrap();
    assert_eq!(path, raw);
    assert_eq!((c.intersect_calls(), c.state_checks), (0, 0), "{c:?}");
    // one axis moving back on the way is worth checks, and they shorten it where free
    let mut back = raw.clone();
    back[10][0] += 0.5;
    back[11][0] += 0.5;
    let c = &mut CallCounts::default();
    shorten(&scene.space, oracle.as_ref(), &groups, &back, c).unwrap();
    assert!(c.intersect_calls() + c.state_checks > 0);
}

/// With the pieces known, a direct path's corners are checked before its sweeps: the same
/// answers as asking the sweeps alone, and a pair whose corner lies in a disc is refused
/// without any sweep.
#[test]
fn a_corner_in_collision_refuses_the_pair_before_any_sweep() {
    let scene = disc_scene(9, 60, 0.07);
    let d = discs(&scene);
    let oracle = scene.oracle();
    let groups: Vec<Group> = scene.space.groups(true);
    let ends = random_queries(&scene, 400, 2);
    let mut known = KnownPieces::new();
    let mut refused_by_corner = 0;
    for (a, z) in &ends {
        let plain = &mut CallCounts::default();
        let want = check_direct(&scene.space, oracle.as_ref(), &groups, a, z, plain).unwrap();
        let c = &mut CallCounts::default();
        let got = check_direct_known(
            &scene.space,
            oracle.as_ref(),
            &groups,
            a,
            z,
            Some(&mut known),
            c,
        )
        .unwrap();
        assert_eq!(got, want, "{a:?} → {z:?}");
        let corner = vec![z[0], a[1]];
        if a[0] != z[0] && a[1] != z[1] && !point_free(&corner, &d) {
            assert!(got.is_none());
            assert_eq!(c.intersect_calls(), 0, "{a:?} → {z:?}: {c:?}");
            refused_by_corner += 1;
        }
    }
    assert!(refused_by_corner > 20, "{refused_by_corner}");
}

/// The trees' greedy shortcut passes keep what each pass learnt ([`KnownPieces`]): the same
/// path as passes asking every pair afresh (the reference below, written out here), in fewer
/// calls, every piece free for the independent segment test.
#[test]
fn shortcut_passes_ask_each_pair_once() {
    use viaroad::deadline::Deadline;
    use viaroad::roadmap::tree::shortcut_passes;
    let scene = disc_scene(9, 60, 0.07);
    let d = discs(&scene);
    let oracle = scene.oracle();
    let groups: Vec<Group> = scene.space.groups(true);
    let window = 8;
    let (mut plain_calls, mut known_calls) = (0, 0);
    for seed in 0..12 {
        let path = staircase(&scene, seed, 60);
        // the reference: passes until one drops no corner, each pair asked by `check_direct`
        let plain = &mut CallCounts::default();
        let mut want = path.clone();
        loop {
            let mut out = vec![want[0].clone()];
            let mut i = 0;
            while i + 1 < want.len() {
                let far = (i + 1 + window).min(want.len());
                let jump = ((i + 2)..far).rev().find_map(|j| {
                    check_direct(
                        &scene.space,
                        oracle.as_ref(),
                        &groups,
                        &want[i],
                        &want[j],
                        plain,
                    )
                    .unwrap()
                    .map(|c| (j, c))
                });
                match jump {
                    Some((j, c)) => {
                        out.extend(c);
                        i = j;
                    }
                    None => {
                        out.push(want[i + 1].clone());
                        i += 1;
                    }
                }
            }
            let better = out.len() < want.len();
            want = out;
            if !better {
                break;
            }
        }
        let c = &mut CallCounts::default();
        let (got, error) = shortcut_passes(
            &scene.space,
            oracle.as_ref(),
            &groups,
            &path,
            window,
            c,
            &Deadline::none(),
        );
        assert!(error.is_none(), "{error:?}");
        assert_eq!(got, want, "seed {seed}");
        assert!(one_axis_at_a_time(&got), "seed {seed}");
        for w in got.windows(2) {
            assert!(segment_free(&w[0], &w[1], &d), "seed {seed}: {w:?}");
        }
        plain_calls += plain.intersect_calls();
        known_calls += c.intersect_calls();
    }
    assert!(
        known_calls < plain_calls,
        "{known_calls} calls with the pieces known, {plain_calls} without"
    );
}
