//! The roadmaps shipped in `roadmaps/` load against their scenes (format version and scene
//! fingerprint) and answer every query of their scene with a path the independent checkers
//! certify.

use crate::common;

use common::rigid::RigidChecker;
use common::rigid2d::PlanarChecker;
use std::path::Path;
use viaroad::roadmap::{QueryPlanner, Roadmap};
use viaroad::scene::{Obstacle, Scene};
use viaroad::space::SpaceKind;

fn root(p: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(p)
}

fn check(name: &str) {
    let scene = Scene::load(&root(&format!("scenes/{name}.toml"))).unwrap();
    let roadmap = Roadmap::load(&root(&format!("roadmaps/{name}.bin")), scene.fingerprint())
        .unwrap_or_else(|e| {
            panic!("roadmaps/{name}.bin: {e} — regenerate it (roadmaps/README.md)")
        });
    let oracle = scene.oracle();
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).unwrap();
    for (i, q) in scene.queries.iter().enumerate() {
        let r = planner.query(&q.start, &q.goal).unwrap();
        assert!(r.is_solved(), "{name} query {}: {:?}", i + 1, r.outcome);
        let verdict = match scene.space.kind() {
            SpaceKind::Euclidean(_) => {
                let (centres, radii): (Vec<Vec<f64>>, Vec<f64>) = scene
                    .obstacles
                    .iter()
                    .map(|o| match o {
                        Obstacle::Disc { centre, radius } => (centre.clone(), *radius),
                        _ => unreachable!(),
                    })
                    .unzip();
                common::check_disc_path(
                    &r.path,
                    &centres,
                    &radii,
                    scene.space.lower(),
                    scene.space.upper(),
                    1e-9,
                )
            }
            SpaceKind::Se2 => PlanarChecker::se2(&scene).certify_path(&r.path),
            SpaceKind::Se3 => RigidChecker::se3(&scene).certify_path(&r.path),
            SpaceKind::Joints { .. } => panic!("{name}: no arm roadmap is shipped"),
            SpaceKind::Se2Bodies(_) => {
                common::bodies::BodiesChecker::new(&scene).certify_path(&r.path)
            }
            SpaceKind::Se3Bodies(_) => {
                common::bodies3::SolidBodiesChecker::new(&scene).certify_path(&r.path)
            }
        };
        verdict.unwrap_or_else(|e| panic!("{name} query {}: {e}", i + 1));
    }
}

#[test]
fn discs_cluttered() {
    check("discs-cluttered");
}

#[test]
fn se2_corridor() {
    check("se2-corridor");
}

#[test]
fn cube_into_box() {
    check("cube-into-box");
}

#[test]
fn piano() {
    check("piano");
}
