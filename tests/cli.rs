//! The `viaroad` binary as users meet it: the JSON formats, one clear error line and a
//! non-zero exit for every kind of bad input, never a panic. Paths printed are re-checked by
//! the independent segment–disc test.

use crate::common;

use common::cli::{fails_with, stderr, stdout, viaroad, write};

use std::path::Path;

const EXAMPLE: &str = "scenes/discs-example.toml";
const CLUTTERED: &str = "scenes/discs-cluttered.toml";

/// The discs of a TOML disc scene, read with `toml` independently of the scene loader.
fn discs_of(path: &str) -> (Vec<Vec<f64>>, Vec<f64>) {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap();
    let v: toml::Value = toml::from_str(&text).unwrap();
    let mut centres = Vec::new();
    let mut radii = Vec::new();
    for o in v["obstacle"].as_array().unwrap() {
        let d = &o["disc"];
        centres.push(
            d["center"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_float().unwrap())
                .collect(),
        );
        radii.push(d["radius"].as_float().unwrap());
    }
    (centres, radii)
}

fn json_path(v: &serde_json::Value) -> Vec<Vec<f64>> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|q| {
            q.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect()
}

#[test]
fn solve_json_prints_checked_paths() {
    let (centres, radii) = discs_of(CLUTTERED);
    for local in ["viapoint", "viapoint:depth=deepen,via=all", "straight"] {
        let o = viaroad(&["solve", CLUTTERED, "--local", local, "--json"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let lines: Vec<serde_json::Value> = stdout(&o)
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        assert_eq!(lines.len(), 5, "one line per query");
        for v in &lines {
            for key in ["solved", "path", "shortened", "calls", "depth"] {
                assert!(v.get(key).is_some(), "{key} missing in {v}");
            }
            if v["solved"].as_bool().unwrap() {
                for key in ["path", "shortened"] {
                    let p = json_path(&v[key]);
                    common::check_disc_path(&p, &centres, &radii, &[0.0, 0.0], &[1.0, 1.0], 1e-9)
                        .unwrap_or_else(|e| panic!("{local} {key}: {e}"));
                }
            }
        }
        if local.starts_with("viapoint") {
            assert!(
                lines.iter().all(|v| v["solved"].as_bool().unwrap()),
                "{local}"
            );
        }
    }
}

#[test]
fn bad_scenes_and_configurations_are_one_line_errors() {
    let d = temp_dir("bad");
    let base =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(EXAMPLE)).unwrap();
    let nan = write(
        &d,
        "nan.toml",
        &base.replace("start = [0.02, 0.98]", "start = [nan, 0.98]"),
    );
    let inside = write(
        &d,
        "inside.toml",
        &base.replace("start = [0.02, 0.98]", "start = [0.30, 0.40]"),
    );
    let negative = write(
        &d,
        "negative.toml",
        &base.replace("radius = 0.05", "radius = -0.05"),
    );
    let kind = write(
        &d,
        "kind.toml",
        &base.replace("kind = \"r2\"", "kind = \"r7x\""),
    );
    let garbage = write(&d, "garbage.toml", "this is [not toml");
    fails_with(&["solve", "no/such/scene.toml"], "cannot read");
    fails_with(&["solve", &nan], "not a finite number");
    fails_with(&["solve", &inside], "in collision");
    fails_with(&["solve", &negative], "radius");
    fails_with(&["solve", &kind], "r7x");
    fails_with(&["solve", &garbage], "garbage.toml");
    fails_with(&["solve", EXAMPLE, "--beta", "x"], "beta");
    fails_with(&["solve", EXAMPLE, "--local", "curved"], "curved");
    fails_with(&["solve", EXAMPLE, "--via", "0"], "--via");
    fails_with(
        &["probe", EXAMPLE, "--from", "0,0.5", "--to", "1,0.5,2"],
        "coordinates",
    );
    fails_with(
        &["probe", EXAMPLE, "--from", "0,0.5", "--to", "1,x"],
        "not a number",
    );
}

#[test]
fn build_query_info_and_their_errors() {
    let d = temp_dir("roadmap");
    let rm = d.join("r.bin").to_string_lossy().into_owned();
    let o = viaroad(&[
        "build", CLUTTERED, "-o", &rm, "--nodes", "300", "--seed", "5",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("learnt"));
    // the same seed gives the same file
    let again = d.join("again.bin").to_string_lossy().into_owned();
    assert!(
        viaroad(&["build", CLUTTERED, "-o", &again, "--nodes", "300", "--seed", "5"])
            .status
            .success()
    );
    assert_eq!(std::fs::read(&rm).unwrap(), std::fs::read(&again).unwrap());

    let o = viaroad(&["info", &rm, "--json"]);
    assert!(o.status.success());
    let info: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert!(info["nodes"].as_u64().unwrap() >= 300);
    assert_eq!(info["seed"].as_u64(), Some(5));

    let (centres, radii) = discs_of(CLUTTERED);
    let q = write(
        &d,
        "queries.txt",
        "0.02 0.98 0.98 0.02\n0.05 0.05 0.95 0.95\n0.5 0.97 0.5 0.03\n",
    );
    // one JSON line per query, under each shortening mode
    let mode = |m: &str| -> Vec<serde_json::Value> {
        let o = viaroad(&[
            "query",
            &rm,
            "--scene",
            CLUTTERED,
            "--queries",
            &q,
            "--json",
            "--shorten",
            m,
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        // answers stream out as they complete, each with its query number
        let mut v: Vec<serde_json::Value> = stdout(&o)
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        v.sort_by_key(|a| a["query"].as_u64().unwrap());
        let numbers: Vec<u64> = v.iter().map(|a| a["query"].as_u64().unwrap()).collect();
        assert_eq!(numbers, (1..=v.len() as u64).collect::<Vec<_>>());
        v
    };
    let fast = mode("fast");
    assert_eq!(fast.len(), 3);
    for v in &fast {
        assert!(v["query_ms"].as_f64().unwrap() >= 0.0);
        if v["solved"].as_bool().unwrap() {
            let p = json_path(&v["shortened"]);
            common::check_disc_path(&p, &centres, &radii, &[0.0, 0.0], &[1.0, 1.0], 1e-9).unwrap();
        }
    }
    // off returns the roadmap path itself; exact is never longer than fast
    let (off, exact) = (mode("off"), mode("exact"));
    for ((o, f), e) in off.iter().zip(&fast).zip(&exact) {
        assert_eq!(o["solved"], f["solved"]);
        assert_eq!(o["path"], o["shortened"]);
        assert_eq!(o["length"], o["raw_length"]);
        if f["solved"].as_bool().unwrap() {
            let (lf, le) = (f["length"].as_f64().unwrap(), e["length"].as_f64().unwrap());
            assert!(le <= lf + 1e-9 && lf <= o["length"].as_f64().unwrap() + 1e-9);
            common::check_disc_path(
                &json_path(&e["shortened"]),
                &centres,
                &radii,
                &[0.0, 0.0],
                &[1.0, 1.0],
                1e-9,
            )
            .unwrap();
        }
    }

    let truncated = d.join("truncated.bin");
    std::fs::write(&truncated, &std::fs::read(&rm).unwrap()[..200]).unwrap();
    fails_with(&["info", &truncated.to_string_lossy()], "truncated");
    fails_with(&["info", EXAMPLE], "not a viaroad roadmap");
    fails_with(
        &[
            "query",
            &rm,
            "--scene",
            EXAMPLE,
            "--from",
            "0.02,0.98",
            "--to",
            "0.98,0.02",
        ],
        "another scene",
    );
    let empty = write(&d, "empty.txt", "");
    fails_with(
        &["query", &rm, "--scene", CLUTTERED, "--queries", &empty],
        "no queries",
    );
    // neither --from/--to nor --queries: the scene's own queries (five in discs-cluttered)
    let o = viaroad(&["query", &rm, "--scene", CLUTTERED, "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let own: Vec<serde_json::Value> = stdout(&o)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(own.len(), 5);
    for v in &own {
        assert!(v["solved"].as_bool().unwrap(), "{v}");
        common::check_disc_path(
            &json_path(&v["shortened"]),
            &centres,
            &radii,
            &[0.0, 0.0],
            &[1.0, 1.0],
            1e-9,
        )
        .unwrap();
    }
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(CLUTTERED)).unwrap();
    let cut = text.find("[[query]]").unwrap();
    let no_query = write(&d, "no-query.toml", &text[..cut]);
    fails_with(&["query", &rm, "--scene", &no_query], "names no query");
    // a missing flag is a usage error, reported by clap with its usage line and exit code 2
    let o = viaroad(&["query", &rm, "--scene", CLUTTERED, "--from", "0.02,0.98"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--to"));
    fails_with(
        &[
            "query",
            &rm,
            "--scene",
            CLUTTERED,
            "--from",
            "2,2",
            "--to",
            "0.98,0.02",
        ],
        "outside",
    );
    fails_with(&["build", CLUTTERED, "-o", &rm, "--nodes", "0"], "--nodes");
    // a failed save keeps the previous roadmap: the target is a directory
    fails_with(
        &[
            "build",
            CLUTTERED,
            "-o",
            &d.to_string_lossy(),
            "--nodes",
            "50",
        ],
        "",
    );
    assert_eq!(std::fs::read(&rm).unwrap(), std::fs::read(&again).unwrap());
}

#[test]
fn demo_writes_a_roadmap_and_a_picture() {
    let d = temp_dir("demo");
    let o = viaroad(&[
        "demo",
        "--out",
        &d.to_string_lossy(),
        "--queries",
        "200",
        "--nodes",
        "400",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("200 random queries"), "{out}");
    assert!(d.join("discs-cluttered.bin").is_file());
    let svg = std::fs::read_to_string(d.join("discs-cluttered.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("<polyline"));
}

#[test]
fn probe_reports_intervals_the_independent_check_confirms() {
    use common::rigid::RigidChecker;
    let scene = viaroad::scene::Scene::load(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/ompl/3D/Easy.cfg"),
    )
    .unwrap();
    let checker = RigidChecker::se3(&scene);
    for (from, to) in [
        ("270,160,-200,0,0,0,1", "270,160,-400,0,0,0,1"),
        ("270,160,-200,0,0,0,1", "270,160,-250,0,0,0,1"),
        (
            "270,160,-200,0,0,0,1",
            "270,160,-200,0,0,0.7071067811865476,0.7071067811865476",
        ),
    ] {
        let o = viaroad(&[
            "probe",
            "scenes/ompl/3D/Easy.cfg",
            "--from",
            from,
            "--to",
            to,
            "--json",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let v: serde_json::Value = serde_json::from_str(stdout(&o).trim()).unwrap();
        assert_eq!(v["calls"].as_u64(), Some(1));
        let ivs = json_path(&v["intervals"]);
        let parse = |s: &str| {
            s.split(',')
                .map(|x| x.parse::<f64>().unwrap())
                .collect::<Vec<f64>>()
        };
        let (a, b) = (parse(from), parse(to));
        // free exactly when the independent check certifies the whole motion
        assert_eq!(
            ivs.is_empty(),
            checker.certify_motion(&a, &b).is_ok(),
            "{from} → {to}: {ivs:?}"
        );
        for iv in &ivs {
            assert!(0.0 <= iv[0] && iv[0] <= iv[1] && iv[1] <= 1.0);
            // the robot collides at the middle of every interval (parry's distance is zero)
            let space = &scene.space;
            let m = space.direct_motion(&a, &b).unwrap();
            assert!(
                checker.clearance(&m.at(0.5 * (iv[0] + iv[1]))) <= 1e-9,
                "{from} → {to}: {iv:?}"
            );
        }
    }
    fails_with(
        &[
            "probe",
            "scenes/ompl/3D/Easy.cfg",
            "--from",
            "270,160,-200,0,0,0,1",
            "--to",
            "260,160,-200,0,0,1,0",
        ],
        "both position and orientation",
    );
}

#[test]
fn path_out_writes_ompl_state_files_the_independent_check_certifies() {
    use common::rigid::RigidChecker;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scene = viaroad::scene::Scene::load(&root.join("scenes/ompl/3D/Twistycool.cfg")).unwrap();
    let d = temp_dir("path-out");
    let out = d.join("twisty.path");
    let o = viaroad(&[
        "solve",
        "scenes/ompl/3D/Twistycool.cfg",
        "--path-out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("query 1: solved"), "{}", stdout(&o));
    // seven numbers per line (x y z qx qy qz qw), read back without the library's reader
    let text = std::fs::read_to_string(&out).unwrap();
    let path: Vec<Vec<f64>> = text
        .lines()
        .map(|l| l.split(' ').map(|x| x.parse::<f64>().unwrap()).collect())
        .collect();
    assert!(path.len() >= 2 && path.iter().all(|q| q.len() == 7));
    let q = &scene.queries[0];
    let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9);
    assert!(close(&path[0], &q.start) && close(path.last().unwrap(), &q.goal));
    RigidChecker::se3(&scene).certify_path(&path).unwrap();

    // several queries: numbered files, one per solved query
    let many = d.join("many.path");
    let o = viaroad(&["solve", CLUTTERED, "--path-out", many.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let solved = stdout(&o).matches(": solved").count();
    let files = (1..=20)
        .filter(|k| d.join(format!("many-{k}.path")).exists())
        .count();
    assert!(
        solved >= 2 && files == solved,
        "{solved} solved, {files} files"
    );

    // a path file that cannot be written is its own error, not a panic (a missing directory
    // is created, as for `build -o`; a regular file in the way of the directory is not)
    let blocker = d.join("a-file");
    std::fs::write(&blocker, b"x").unwrap();
    let nowhere = blocker.join("p.path");
    fails_with(
        &["solve", CLUTTERED, "--path-out", nowhere.to_str().unwrap()],
        "a-file",
    );
}

/// `query --trees on`: where a sparse roadmap cannot join a query's ends, trees grow out of it;
/// every answer (by the roadmap or the trees) is re-checked by the independent segment–disc
/// test, and `--check` says each is certified; a mode that is not one is a usage error.
#[test]
fn query_grows_trees_out_of_the_roadmap() {
    let d = temp_dir("trees");
    let rm = d.join("r.bin").to_string_lossy().into_owned();
    let o = viaroad(&["build", CLUTTERED, "-o", &rm, "--nodes", "5", "--seed", "2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (centres, radii) = discs_of(CLUTTERED);
    let o = viaroad(&[
        "query",
        &rm,
        "--scene",
        CLUTTERED,
        "--json",
        "--trees",
        "on",
        "--no-grow",
        "--time",
        "30",
        "--check",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let answers: Vec<serde_json::Value> = stdout(&o)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(answers.len(), 5);
    for v in &answers {
        assert!(v["solved"].as_bool().unwrap(), "{v}");
        // `--check`: the command's own independent check agrees with the test's
        assert_eq!(v["certified"], true, "{v}");
        for key in ["path", "shortened"] {
            common::check_disc_path(
                &json_path(&v[key]),
                &centres,
                &radii,
                &[0.0, 0.0],
                &[1.0, 1.0],
                1e-9,
            )
            .unwrap_or_else(|e| panic!("{key} of {v}: {e}"));
        }
    }
    assert!(
        answers.iter().any(|v| v["outcome"] == "trees"),
        "a 5-node roadmap leaves some query to the trees: {answers:?}"
    );
    let o = viaroad(&["query", &rm, "--scene", CLUTTERED, "--trees", "maybe"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--trees"), "{}", stderr(&o));
    for bad in ["soon", "-1", "NaN"] {
        let race = format!("--race={bad}");
        let o = viaroad(&["query", &rm, "--scene", CLUTTERED, &race]);
        assert_eq!(o.status.code(), Some(2), "--race {bad}");
        assert!(stderr(&o).contains("--race"), "{}", stderr(&o));
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// `query --keep-answers FILE`: the queries are answered in their order, every path found is
/// fed back into the roadmap before the next one, and the grown roadmap is saved: every corner
/// of every answer is one of its nodes, it loads for the scene, and it answers the same
/// queries again; every path printed is re-checked by the independent segment–disc test, and
/// the roadmap given is left as it was.
#[test]
fn query_keeps_its_answers_in_the_roadmap() {
    let d = temp_dir("keep");
    let rm = d.join("r.bin").to_string_lossy().into_owned();
    let kept = d.join("kept").join("r.bin").to_string_lossy().into_owned();
    let o = viaroad(&[
        "build", CLUTTERED, "-o", &rm, "--nodes", "40", "--seed", "2",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let before = std::fs::read(&rm).unwrap();
    let q = write(
        &d,
        "queries.txt",
        "0.02 0.98 0.98 0.02\n0.05 0.05 0.95 0.95\n0.5 0.97 0.5 0.03\n0.97 0.5 0.03 0.5\n",
    );
    let (centres, radii) = discs_of(CLUTTERED);
    let answers = |map: &str, keep: Option<&str>| -> Vec<serde_json::Value> {
        let mut args = vec![
            "query",
            map,
            "--scene",
            CLUTTERED,
            "--queries",
            &q,
            "--json",
        ];
        args.extend(keep.map(|k| ["--keep-answers", k]).into_iter().flatten());
        let o = viaroad(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let v: Vec<serde_json::Value> = stdout(&o)
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        for a in v.iter().filter(|a| a["solved"].as_bool().unwrap()) {
            let p = json_path(&a["shortened"]);
            common::check_disc_path(&p, &centres, &radii, &[0.0, 0.0], &[1.0, 1.0], 1e-9).unwrap();
        }
        v
    };
    let first = answers(&rm, Some(&kept));
    // one after another, in the file's order
    let numbers: Vec<u64> = first.iter().map(|a| a["query"].as_u64().unwrap()).collect();
    assert_eq!(numbers, vec![1, 2, 3, 4]);
    let solved: Vec<&serde_json::Value> = first
        .iter()
        .filter(|a| a["solved"].as_bool().unwrap())
        .collect();
    assert!(solved.len() >= 3, "{first:?}");
    assert_eq!(
        std::fs::read(&rm).unwrap(),
        before,
        "the roadmap given changed"
    );
    let nodes = |map: &str| -> u64 {
        let o = viaroad(&["info", map, "--json"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
        v["nodes"].as_u64().unwrap()
    };
    assert!(nodes(&kept) > nodes(&rm));
    // every corner of every answer is a node of the kept roadmap, bit for bit
    let roadmap = viaroad::roadmap::Roadmap::load(
        std::path::Path::new(&kept),
        viaroad::scene::Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join(CLUTTERED))
            .unwrap()
            .fingerprint(),
    )
    .unwrap();
    let bits = |q: &[f64]| q.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
    let node_bits: std::collections::HashSet<Vec<u64>> = (0..roadmap.node_count() as u32)
        .map(|i| bits(roadmap.node(i)))
        .collect();
    for a in &solved {
        for c in json_path(&a["shortened"]) {
            assert!(node_bits.contains(&bits(&c)), "{c:?} is not a node");
        }
    }
    // the kept roadmap answers every query the first run answered
    let again = answers(&kept, None);
    for (a, b) in first.iter().zip(&again) {
        assert!(!a["solved"].as_bool().unwrap() || b["solved"].as_bool().unwrap());
    }
    // a target that cannot be saved to is refused before any query is answered
    let args = [
        "query",
        &rm,
        "--scene",
        CLUTTERED,
        "--queries",
        &q,
        "--keep-answers",
        "/dev/null",
    ];
    fails_with(&args, "/dev/null");
    assert!(stdout(&viaroad(&args)).is_empty());
    // trees are kept only beside the answers they found
    let o = viaroad(&[
        "query",
        &rm,
        "--scene",
        CLUTTERED,
        "--queries",
        &q,
        "--keep-trees",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--keep-answers"), "{}", stderr(&o));
}

fn temp_dir(name: &str) -> common::cli::TempDir {
    common::cli::temp_dir("cli", name)
}
