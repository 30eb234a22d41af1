//! One oracle call and one local-method connection on the seed's random disc problems
//! (CHS A.1.3). Inputs come from the seeded problem generator and are built outside the timed
//! loops; every connection is asserted to succeed, so a broken planner cannot look fast.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use viaroad::bench::discs::{problem, DiscProblem, GOAL, SEED_RADIUS, START};
use viaroad::interval::IntervalList;
use viaroad::local::viapoint::{Depth, ViaLimit, ViaPoint, ViaPointOptions};
use viaroad::local::{LocalMethod, StraightLine};
use viaroad::oracle::{CallCounts, CountedOracle, Workspace};
use viaroad::space::{Change, Motion};

fn oracle_calls(c: &mut Criterion) {
    let p = problem(1, 0, SEED_RADIUS);
    let oracle = p.oracle();
    let segment = Motion::segment(START.to_vec(), Change::Linear(vec![1.0, -1.0]));
    let line = Motion::line(
        vec![0.5, 0.5],
        Change::Linear(vec![std::f64::consts::FRAC_1_SQRT_2; 2]),
    );
    let mut g = c.benchmark_group("disc_oracle");
    g.bench_function("intersect_segment_50_discs", |b| {
        b.iter(|| {
            oracle
                .intersect(black_box(&segment), &mut CallCounts::default())
                .unwrap()
        })
    });
    g.bench_function("intersect_line_50_discs", |b| {
        b.iter(|| {
            oracle
                .intersect(black_box(&line), &mut CallCounts::default())
                .unwrap()
        })
    });
    // the allocation-free twin the via-point search uses (≤ 150 ns a segment call)
    let (mut out, mut ws) = (IntervalList::new(), Workspace::new());
    g.bench_function("intersect_into_segment_50_discs", |b| {
        b.iter(|| {
            oracle
                .intersect_into(
                    black_box(&segment),
                    &mut out,
                    &mut ws,
                    &mut CallCounts::default(),
                )
                .unwrap();
            out.len()
        })
    });
    g.bench_function("intersect_into_line_50_discs", |b| {
        b.iter(|| {
            oracle
                .intersect_into(
                    black_box(&line),
                    &mut out,
                    &mut ws,
                    &mut CallCounts::default(),
                )
                .unwrap();
            out.len()
        })
    });
    g.bench_function("check_segment_50_discs", |b| {
        b.iter(|| {
            oracle
                .check_motion(black_box(&segment), &mut CallCounts::default())
                .unwrap()
        })
    });
    g.finish();
}

fn connections(c: &mut Criterion) {
    let space = DiscProblem::space();
    let problems: Vec<DiscProblem> = (0..32).map(|i| problem(2, i, SEED_RADIUS)).collect();
    let oracles: Vec<_> = problems.iter().map(|p| p.oracle()).collect();
    let methods: Vec<(&str, Box<dyn LocalMethod>)> = vec![
        ("straight", Box::new(StraightLine::exact())),
        (
            "viapoint_reuse_via2",
            Box::new(ViaPoint::new(ViaPointOptions {
                discoveries: false,
                ..ViaPointOptions::seed_experiment()
            })),
        ),
        (
            "viapoint_reuse_all",
            Box::new(ViaPoint::new(ViaPointOptions {
                via: ViaLimit::All,
                discoveries: false,
                ..ViaPointOptions::seed_experiment()
            })),
        ),
        (
            "viapoint_deepen_via2",
            Box::new(ViaPoint::new(ViaPointOptions {
                depth: Depth::Deepen { max: 30 },
                discoveries: false,
                ..ViaPointOptions::seed_experiment()
            })),
        ),
        (
            "viapoint_default_with_discoveries",
            Box::new(ViaPoint::default()),
        ),
    ];
    let mut g = c.benchmark_group("connect_32_seed_problems");
    g.sample_size(20);
    for (name, m) in &methods {
        g.bench_function(*name, |b| {
            b.iter(|| {
                let mut solved = 0;
                for o in &oracles {
                    solved += m.connect(&space, o, &START, &GOAL).unwrap().is_connected() as u32;
                }
                if *name != "straight" {
                    assert!(solved >= 30, "{name} solved {solved}/32");
                }
                solved
            })
        });
    }
    g.finish();
}

criterion_group!(benches, oracle_calls, connections);
criterion_main!(benches);
