//! The via-point planner on point-among-discs problems: every path is re-checked by an
//! independent segment–disc test, and the search strategies keep the promises the seed makes
//! about each other (CHS §1.3, Appendix A).

use crate::common;

use common::check_disc_path;
use proptest::prelude::*;
use viaroad::bench::discs::{problem, DiscProblem, GOAL, SEED_RADIUS, START};
use viaroad::local::viapoint::{
    BasePoint, Depth, Directions, Search, ViaLimit, ViaPoint, ViaPointOptions,
};
use viaroad::local::{
    check_direct, direct_length, drop_corners, path_length, shorten, LocalMethod, Outcome,
    StraightLine,
};
use viaroad::oracle::discs::Discs;
use viaroad::oracle::{Bounded, CallCounts};
use viaroad::space::Space;

const TOL: f64 = 1e-9;

fn check(p: &DiscProblem, path: &[Vec<f64>]) -> Result<(), String> {
    let centres: Vec<Vec<f64>> = p.centres.iter().map(|c| c.to_vec()).collect();
    let radii = vec![p.radius; centres.len()];
    check_disc_path(path, &centres, &radii, &[0.0, 0.0], &[1.0, 1.0], TOL)
}

fn solve(p: &DiscProblem, o: ViaPointOptions) -> viaroad::local::Connection {
    ViaPoint::new(o)
        .connect(&DiscProblem::space(), &p.oracle(), &START, &GOAL)
        .expect("discs answer every straight motion")
}

fn seed_options() -> ViaPointOptions {
    ViaPointOptions {
        max_calls: Some(200_000),
        ..ViaPointOptions::seed_experiment()
    }
}

#[test]
fn every_knob_gives_valid_paths_on_the_seed_problems() {
    let variants: Vec<ViaPointOptions> = vec![
        seed_options(),
        ViaPointOptions {
            via: ViaLimit::All,
            ..seed_options()
        },
        ViaPointOptions {
            beta: 0.0,
            ..seed_options()
        },
        ViaPointOptions {
            beta: 2.0,
            ..seed_options()
        },
        ViaPointOptions {
            depth: Depth::Deepen { max: 20 },
            ..seed_options()
        },
        ViaPointOptions {
            depth: Depth::Fixed(9),
            ..seed_options()
        },
        ViaPointOptions {
            search: Search::BreadthFirst,
            depth: Depth::DeepenReuse { max: 8 },
            ..seed_options()
        },
        ViaPointOptions {
            split_axes: true,
            ..seed_options()
        },
    ]
    .into_iter()
    .chain(BasePoint::ALL.iter().map(|&b| ViaPointOptions {
        base_point: b,
        depth: Depth::DeepenReuse { max: 10 },
        ..seed_options()
    }))
    .collect();
    for (k, o) in variants.iter().enumerate() {
        let mut solved = 0;
        for i in 0..40 {
            let p = problem(11, i, SEED_RADIUS);
            let c = solve(&p, o.clone());
            if c.is_connected() {
                solved += 1;
                assert_eq!(c.path.first().unwrap(), &START.to_vec());
                assert_eq!(c.path.last().unwrap(), &GOAL.to_vec());
                check(&p, &c.path).unwrap_or_else(|e| panic!("variant {k}, problem {i}: {e}"));
                if o.split_axes {
                    // CHS A.1.1: with separate degrees of freedom every piece is axis-parallel
                    assert!(
                        c.path
                            .windows(2)
                            .all(|w| w[0][0] == w[1][0] || w[0][1] == w[1][1]),
                        "variant {k}"
                    );
                }
            }
            // every certified free segment of the discoveries really is free
            let segs: Vec<Vec<Vec<f64>>> = c
                .discoveries
                .free_segments
                .iter()
                .map(|&(a, b)| {
                    vec![
                        c.discoveries.configs[a as usize].clone(),
                        c.discoveries.configs[b as usize].clone(),
                    ]
                })
                .collect();
            for s in segs {
                check(&p, &s).unwrap_or_else(|e| {
                    panic!("variant {k}, problem {i}, discovered segment: {e}")
                });
            }
        }
        // axis-parallel paths need deeper recursion (CHS A.1.1 needed six levels for its
        // example; "this restriction might turn the motion planning problem unsolvable")
        let expected = if o.split_axes { 32 } else { 36 };
        assert!(solved >= expected, "variant {k} solved only {solved}/40");
    }
}

#[test]
fn all_via_points_make_the_minimal_depth_independent_of_beta() {
    // CHS Table A.1: "with all via points the mean minimal depth is 3.812 for every β" — with
    // every via point tried, the search at each limit is exhaustive, so only the order depends
    // on β, never the minimal depth.
    for i in 0..30 {
        let p = problem(5, i, SEED_RADIUS);
        let depths: Vec<u32> = [0.0, 0.5, 2.0 / 3.0, 1.0, 2.0]
            .iter()
            .map(|&beta| {
                solve(
                    &p,
                    ViaPointOptions {
                        beta,
                        via: ViaLimit::All,
                        ..seed_options()
                    },
                )
                .depth
            })
            .collect();
        assert!(
            depths.windows(2).all(|w| w[0] == w[1]),
            "problem {i}: {depths:?}"
        );
    }
}

#[test]
fn reuse_finds_the_same_depth_with_no_more_calls() {
    // CHS Table A.2 against A.1: the tree of solved subproblems changes the cost, not the answer
    for i in 0..40 {
        let p = problem(3, i, SEED_RADIUS);
        for via in [ViaLimit::Best(2), ViaLimit::All] {
            let plain = solve(
                &p,
                ViaPointOptions {
                    via,
                    depth: Depth::Deepen { max: 30 },
                    ..seed_options()
                },
            );
            let reuse = solve(
                &p,
                ViaPointOptions {
                    via,
                    depth: Depth::DeepenReuse { max: 30 },
                    ..seed_options()
                },
            );
            assert_eq!(plain.outcome, reuse.outcome, "problem {i}");
            assert_eq!(plain.depth, reuse.depth, "problem {i}");
            assert!(
                reuse.counts.intersect_calls() <= plain.counts.intersect_calls(),
                "problem {i}"
            );
        }
    }
}

#[test]
fn breadth_first_finds_a_minimal_depth_path_no_longer_than_depth_first() {
    let space = DiscProblem::space();
    let groups = space.groups(false);
    for i in 0..25 {
        let p = problem(8, i, SEED_RADIUS);
        let dfs = solve(&p, seed_options());
        let bfs = solve(
            &p,
            ViaPointOptions {
                search: Search::BreadthFirst,
                depth: Depth::DeepenReuse { max: 7 },
                ..seed_options()
            },
        );
        if !dfs.is_connected() || dfs.depth > 7 {
            continue;
        }
        assert!(bfs.is_connected(), "problem {i}");
        assert_eq!(
            bfs.depth, dfs.depth,
            "problem {i}: both find the minimal depth"
        );
        check(&p, &bfs.path).unwrap();
        let (lb, ld) = (
            path_length(&space, &groups, &bfs.path),
            path_length(&space, &groups, &dfs.path),
        );
        assert!(lb <= ld + 1e-12, "problem {i}: bfs {lb} > dfs {ld}");
    }
}

#[test]
fn shortening_keeps_paths_valid_and_never_longer() {
    let space = DiscProblem::space();
    let groups = space.groups(false);
    for i in 0..40 {
        let p = problem(9, i, SEED_RADIUS);
        let c = solve(&p, seed_options());
        if !c.is_connected() {
            continue;
        }
        let mut counts = CallCounts::default();
        let s = shorten(&space, &p.oracle(), &groups, &c.path, &mut counts).unwrap();
        check(&p, &s).unwrap_or_else(|e| panic!("problem {i}: {e}"));
        assert_eq!((s.first(), s.last()), (c.path.first(), c.path.last()));
        assert!(path_length(&space, &groups, &s) <= path_length(&space, &groups, &c.path) + 1e-12);
        assert!(s.len() <= c.path.len());
    }
}

/// A long path with many blocked pairs: there, back, and there again along a solved path.
fn there_and_back(path: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let mut long = path.to_vec();
    long.extend(path.iter().rev().skip(1).cloned());
    long.extend(path.iter().skip(1).cloned());
    long
}

/// The lazy search checks a few pairs, yet returns what the seed's eager construction would:
/// a shortest path of the full visibility graph (every pair checked, Floyd–Warshall).
#[test]
fn shortening_finds_the_shortest_path_of_the_full_visibility_graph() {
    let space = DiscProblem::space();
    let groups = space.groups(false);
    let mut compared = 0;
    for i in 0..30 {
        let p = problem(9, i, SEED_RADIUS);
        let c = solve(&p, seed_options());
        if !c.is_connected() || c.path.len() < 3 {
            continue;
        }
        let oracle = p.oracle();
        let long = there_and_back(&c.path);
        let m = long.len();
        let mut eager = CallCounts::default();
        let mut d = vec![vec![f64::INFINITY; m]; m];
        for a in 0..m {
            d[a][a] = 0.0;
            for b in a + 1..m {
                if check_direct(&space, &oracle, &groups, &long[a], &long[b], &mut eager)
                    .unwrap()
                    .is_some()
                {
                    let l = direct_length(&space, &groups, &long[a], &long[b]);
                    (d[a][b], d[b][a]) = (l, l);
                }
            }
        }
        for k in 0..m {
            for a in 0..m {
                for b in 0..m {
                    d[a][b] = d[a][b].min(d[a][k] + d[k][b]);
                }
            }
        }
        let mut lazy = CallCounts::default();
        let s = shorten(&space, &oracle, &groups, &long, &mut lazy).unwrap();
        check(&p, &s).unwrap_or_else(|e| panic!("problem {i}: {e}"));
        let got = path_length(&space, &groups, &s);
        assert!(
            (got - d[0][m - 1]).abs() < 1e-9,
            "problem {i}: shortened {got}, shortest {}",
            d[0][m - 1]
        );
        assert!(lazy.intersect_calls() <= eager.intersect_calls());
        compared += 1;
    }
    assert!(compared >= 20, "only {compared} problems compared");
}

/// The first 40 seed problems the via-point planner solves with at least three corners, with
/// their paths walked there, back and there again: long paths with many corners to drop.
fn there_and_back_problems() -> impl Iterator<Item = (u64, DiscProblem, Vec<Vec<f64>>)> {
    (0..40).filter_map(|i| {
        let p = problem(9, i, SEED_RADIUS);
        let c = solve(&p, seed_options());
        (c.is_connected() && c.path.len() >= 3).then(|| (i, p, there_and_back(&c.path)))
    })
}

#[test]
fn dropping_corners_keeps_paths_valid_and_never_longer() {
    let space = DiscProblem::space();
    let groups = space.groups(false);
    let mut dropped = 0;
    for (i, p, long) in there_and_back_problems() {
        let mut counts = CallCounts::default();
        let s = drop_corners(&space, &p.oracle(), &groups, &long, &mut counts).unwrap();
        check(&p, &s).unwrap_or_else(|e| panic!("problem {i}: {e}"));
        assert_eq!((s.first(), s.last()), (long.first(), long.last()));
        assert!(path_length(&space, &groups, &s) <= path_length(&space, &groups, &long) + 1e-12);
        // at most two checks per inner corner (the pass gallops and halves), and the turning
        // point at the goal always goes
        assert!(counts.intersect_calls() as usize <= 2 * (long.len() - 2));
        assert!(s.len() < long.len(), "problem {i}: nothing dropped");
        dropped += long.len() - s.len();
    }
    assert!(dropped > 0);
}

/// The greedy pass gallops from each kept corner: it keeps no corner that asking the corners
/// one after another would drop (its first kept corner lies at or beyond the first one that
/// the one-by-one pass keeps), and a path every corner of which the start sees collapses to
/// its two ends in a number of checks logarithmic in its corners.
#[test]
fn dropping_corners_gallops_at_least_as_far_as_one_by_one() {
    let space = DiscProblem::space();
    let groups = space.groups(false);
    let mut compared = 0;
    for (i, p, long) in there_and_back_problems() {
        let oracle = p.oracle();
        let counts = &mut CallCounts::default();
        let s = drop_corners(&space, &oracle, &groups, &long, counts).unwrap();
        check(&p, &s).unwrap_or_else(|e| panic!("problem {i}: {e}"));
        // one by one from the start: the last corner before the first it cannot see
        let sees = |j: usize, c: &mut CallCounts| {
            check_direct(&space, &oracle, &groups, &long[0], &long[j], c)
                .unwrap()
                .is_some()
        };
        let one_by_one = (2..long.len())
            .find(|&j| !sees(j, &mut CallCounts::default()))
            .map_or(long.len() - 1, |j| j - 1);
        // (a there-and-back path passes its corners more than once: the last time counts)
        let kept = long
            .iter()
            .rposition(|q| *q == s[1])
            .unwrap_or_else(|| panic!("problem {i}: {:?} is no corner of the input", s[1]));
        assert!(
            kept >= one_by_one,
            "problem {i}: kept {kept}, one by one {one_by_one}"
        );
        compared += 1;
    }
    assert!(compared >= 10, "only {compared} compared");
    // no discs: every corner is seen from the start
    let open = DiscProblem {
        centres: vec![],
        radius: 0.05,
    };
    let m = 200;
    let zigzag: Vec<Vec<f64>> = (0..m)
        .map(|k| {
            let t = k as f64 / (m - 1) as f64;
            vec![0.1 + 0.8 * t, 0.5 + if k % 2 == 0 { 0.05 } else { -0.05 }]
        })
        .collect();
    let counts = &mut CallCounts::default();
    let s = drop_corners(&space, &open.oracle(), &groups, &zigzag, counts).unwrap();
    assert_eq!(s, vec![zigzag[0].clone(), zigzag[m - 1].clone()]);
    assert!(
        counts.intersect_calls() <= 10,
        "{} checks for {m} corners",
        counts.intersect_calls()
    );
}

#[test]
fn a_free_straight_line_costs_one_call_and_depth_zero() {
    let p = DiscProblem {
        centres: vec![[0.9, 0.9]],
        radius: 0.05,
    };
    let c = solve(&p, seed_options());
    assert_eq!(
        (c.outcome, c.depth, c.counts.intersect_calls()),
        (Outcome::Connected, 0, 1)
    );
    assert_eq!(c.path, vec![START.to_vec(), GOAL.to_vec()]);
}

#[test]
fn an_enclosed_goal_is_blocked_not_exhausted() {
    // the goal corner is cut off by one disc touching both walls next to it
    let p = DiscProblem {
        centres: vec![[0.95, 0.05]],
        radius: 0.08,
    };
    let space = DiscProblem::space();
    let oracle = p.oracle();
    let goal = [0.999, 0.001];
    let c = ViaPoint::new(ViaPointOptions {
        via: ViaLimit::All,
        ..seed_options()
    })
    .connect(&space, &oracle, &START, &goal);
    // the goal is inside the disc: contract violated, but the planner must not panic; with a
    // free goal behind a wall of discs the search exhausts its alternatives
    assert!(c.is_ok());
    let wall: Vec<Vec<f64>> = (0..=10)
        .map(|k| vec![0.6 + k as f64 * 0.04, 0.4 - k as f64 * 0.04])
        .collect();
    let mut centres = wall.clone();
    centres.push(vec![0.6, 0.4]);
    let radii = vec![0.03; centres.len()];
    let oracle = Bounded::new(space.clone(), Discs::new(2, &centres, &radii));
    let c = ViaPoint::new(ViaPointOptions {
        via: ViaLimit::All,
        depth: Depth::DeepenReuse { max: 6 },
        ..seed_options()
    })
    .connect(&space, &oracle, &[0.5, 0.5], &[0.99, 0.01])
    .unwrap();
    assert!(
        !c.is_connected()
            || check_disc_path(&c.path, &centres, &radii, &[0.0, 0.0], &[1.0, 1.0], TOL).is_ok()
    );
}

#[test]
fn straight_line_agrees_with_the_independent_check() {
    let space = DiscProblem::space();
    for i in 0..60 {
        let p = problem(4, i, SEED_RADIUS);
        let c = StraightLine::exact()
            .connect(&space, &p.oracle(), &START, &GOAL)
            .unwrap();
        assert_eq!(
            c.is_connected(),
            check(&p, &[START.to_vec(), GOAL.to_vec()]).is_ok(),
            "problem {i}"
        );
    }
}

fn ball_scene(dim: usize, seed: u64) -> (Space, Vec<Vec<f64>>, Vec<f64>) {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let space = Space::euclidean(vec![0.0; dim], vec![1.0; dim]).unwrap();
    let mut centres = Vec::new();
    while centres.len() < 25 {
        let c: Vec<f64> = (0..dim).map(|_| rng.random_range(0.1..0.9)).collect();
        // keep the two corners used as start and goal free
        if c.iter().map(|v| v * v).sum::<f64>().sqrt() > 0.3
            && c.iter().map(|v| (1.0 - v) * (1.0 - v)).sum::<f64>().sqrt() > 0.3
        {
            centres.push(c);
        }
    }
    let radii = vec![0.12; centres.len()];
    (space, centres, radii)
}

#[test]
fn borderlines_work_in_higher_dimensions() {
    // CHS §1.4: borderlines in the hyperplane perpendicular to the motion
    for dim in [3, 4] {
        for strategy in [
            Directions::Basis {
                axis_preference: true,
                rotations: 2,
            },
            Directions::Basis {
                axis_preference: false,
                rotations: 0,
            },
            Directions::Random { count: 4 },
        ] {
            let mut solved = 0;
            for seed in 0..8 {
                let (space, centres, radii) = ball_scene(dim, seed);
                let oracle = Bounded::new(space.clone(), Discs::new(dim, &centres, &radii));
                let (a, z) = (vec![0.05; dim], vec![0.95; dim]);
                let o = ViaPointOptions {
                    directions: strategy,
                    depth: Depth::DeepenReuse { max: 6 },
                    ..seed_options()
                };
                let c = ViaPoint::new(o).connect(&space, &oracle, &a, &z).unwrap();
                if c.is_connected() {
                    solved += 1;
                    check_disc_path(
                        &c.path,
                        &centres,
                        &radii,
                        &vec![0.0; dim],
                        &vec![1.0; dim],
                        TOL,
                    )
                    .unwrap_or_else(|e| panic!("dim {dim} {strategy:?} seed {seed}: {e}"));
                }
            }
            assert!(solved >= 6, "dim {dim} {strategy:?}: solved {solved}/8");
        }
    }
}

#[test]
fn results_do_not_depend_on_anything_but_the_inputs() {
    let p = problem(2, 17, SEED_RADIUS);
    for b in [BasePoint::RandomInMotion, BasePoint::CentreOfRandom] {
        let o = ViaPointOptions {
            base_point: b,
            seed: 42,
            ..seed_options()
        };
        let c1 = solve(&p, o.clone());
        let c2 = std::thread::spawn({
            let p = p.clone();
            move || solve(&p, o)
        })
        .join()
        .unwrap();
        assert_eq!(c1, c2);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, .. ProptestConfig::default() })]

    /// Random scenes, random start and goal: whatever comes back is collision-free.
    #[test]
    fn random_scenes_give_valid_paths(
        centres in prop::collection::vec((0.0f64..1.0, 0.0f64..1.0, 0.01f64..0.12), 1..40),
        a in (0.0f64..1.0, 0.0f64..1.0),
        z in (0.0f64..1.0, 0.0f64..1.0),
        beta in 0.0f64..2.0,
        all in any::<bool>(),
        split in any::<bool>(),
    ) {
        let cs: Vec<Vec<f64>> = centres.iter().map(|c| vec![c.0, c.1]).collect();
        let rs: Vec<f64> = centres.iter().map(|c| c.2).collect();
        let (a, z) = (vec![a.0, a.1], vec![z.0, z.1]);
        let free = |q: &[f64]| cs.iter().zip(&rs).all(|(c, r)| ((q[0]-c[0]).powi(2) + (q[1]-c[1]).powi(2)).sqrt() > *r);
        prop_assume!(free(&a) && free(&z));
        let space = Space::euclidean(vec![0.0, 0.0], vec![1.0, 1.0]).unwrap();
        let oracle = Bounded::new(space.clone(), Discs::new(2, &cs, &rs));
        let o = ViaPointOptions {
            beta,
            via: if all { ViaLimit::All } else { ViaLimit::Best(2) },
            split_axes: split,
            depth: Depth::DeepenReuse { max: 6 },
            max_calls: Some(20_000),
            ..ViaPointOptions::default()
        };
        let c = ViaPoint::new(o).connect(&space, &oracle, &a, &z).unwrap();
        if c.is_connected() {
            prop_assert_eq!(c.path.first().unwrap(), &a);
            prop_assert_eq!(c.path.last().unwrap(), &z);
            if let Err(e) = check_disc_path(&c.path, &cs, &rs, &[0.0, 0.0], &[1.0, 1.0], TOL) {
                return Err(TestCaseError::fail(e));
            }
        }
    }
}
