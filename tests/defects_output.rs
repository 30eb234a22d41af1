//! What viaroad prints and draws about paths and numbers: a path file that collides is said to
//! collide (legend and stderr) instead of being drawn as a shortened path, an empty path file
//! is an error, lengths are never `-0`, huge numbers in messages are short, an output that
//! cannot be written is refused before a batch, and a JavaScript test that cannot run says so.

use crate::common;

use common::cli::{fails_alone_with, fails_with, stderr, temp_dir, viaroad, write};
use serde_json::Value;
use std::path::Path;

const EASY: &str = "scenes/ompl/3D/Easy.cfg";
const CLUTTERED: &str = "scenes/discs-cluttered.toml";
const CLUTTERED_MAP: &str = "roadmaps/discs-cluttered.bin";
/// The valid path's blue key: never the key of a path that collides.
const BLUE: &str = "#0967d2";

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The JSON chunk of a `.glb` file.
fn glb_json(file: &Path) -> Value {
    let b = std::fs::read(file).unwrap();
    assert_eq!(&b[0..4], b"glTF");
    let n = u32::from_le_bytes(b[12..16].try_into().unwrap()) as usize;
    serde_json::from_slice(&b[20..20 + n]).unwrap()
}

/// The legend's HTML in a page written by `view`.
fn legend_html(page: &Path) -> String {
    let html = std::fs::read_to_string(page).unwrap();
    let start = html.find(r#"<div id="legend">"#).expect("a legend");
    let end = start + html[start..].find(r#"<div id="controls">"#).unwrap();
    html[start..end].to_string()
}

/// The `warning:` lines of a run.
fn warnings(o: &std::process::Output) -> Vec<String> {
    stderr(o)
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .map(str::to_string)
        .collect()
}

/// Easy's shipped solution path (free) as lines of its file.
fn easy_lines() -> Vec<String> {
    std::fs::read_to_string(root().join("scenes/ompl/3D/Easy.path"))
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(str::to_string)
        .collect()
}

/// Easy's start and goal: the goal lies behind a wall, so the straight translation between
/// them runs through it.
const EASY_START: [f64; 7] = [270.0, 160.0, -200.0, 0.0, 0.0, 0.0, 1.0];
const EASY_GOAL: [f64; 7] = [270.0, 160.0, -400.0, 0.0, 0.0, 0.0, 1.0];

fn state_line(q: &[f64]) -> String {
    q.iter()
        .map(|x| format!("{x:?}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A path of three segments: the first two of Easy's free solution, then straight from the
/// third corner to the goal, through the wall.
fn colliding_in_segment_3(dir: &Path) -> String {
    let lines = easy_lines();
    let text = format!(
        "{}\n{}\n{}\n{}\n",
        lines[0],
        lines[1],
        lines[2],
        state_line(&EASY_GOAL)
    );
    write(dir, "colliding.path", &text)
}

#[test]
fn a_colliding_path_file_is_said_to_collide_in_the_legend_and_on_stderr() {
    let d = temp_dir("defects_output", "colliding");
    let path = colliding_in_segment_3(&d);
    let glb = d.join("out.glb");
    let page = d.join("out.html");
    for (command, out) in [("export", &glb), ("view", &page)] {
        let o = viaroad(&[command, EASY, "--path", &path, "-o", out.to_str().unwrap()]);
        assert!(o.status.success(), "{command}: {}", stderr(&o));
        let w = warnings(&o);
        assert_eq!(w.len(), 1, "{command}: one warning line: {}", stderr(&o));
        assert!(
            w[0].contains("collides in segment 3 at t = "),
            "{command}: {}",
            w[0]
        );
    }

    let doc = glb_json(&glb);
    let rows = doc["asset"]["extras"]["legend"]["paths"]
        .as_array()
        .unwrap();
    // drawn as given: not shortened (shortening assumes a free path), one row, a warning
    assert_eq!(rows.len(), 1, "{rows:?}");
    let label = rows[0]["label"].as_str().unwrap();
    assert!(
        label.starts_with("given path — collides in segment 3 at t = "),
        "{label}"
    );
    assert_eq!(rows[0]["collides"], true);
    assert_ne!(rows[0]["colour"], BLUE);
    let nodes: Vec<&str> = doc["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n["name"].as_str().unwrap())
        .collect();
    assert!(!nodes.contains(&"shortened path"), "{nodes:?}");
    // the trace has the key's colour, not the valid path's blue
    let trace = doc["materials"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["name"] == "raw path")
        .unwrap();
    let blue = viaroad_linear(0x0967d2);
    let rgba: Vec<f64> = trace["pbrMetallicRoughness"]["baseColorFactor"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(
        (rgba[2] - blue[2]).abs() > 0.1,
        "the colliding trace is drawn blue: {rgba:?}"
    );

    let legend = legend_html(&page);
    assert!(
        legend.contains(r#"class="warning""#)
            && legend.contains("given path — collides in segment 3 at t = "),
        "{legend}"
    );
    assert!(!legend.contains(BLUE), "{legend}");
    assert!(!legend.contains("shortened path"), "{legend}");
}

/// sRGB hex as glTF's linear factors (as the exporter converts them).
fn viaroad_linear(hex: u32) -> [f64; 3] {
    let c = |shift: u32| {
        let s = ((hex >> shift) & 0xff) as f64 / 255.0;
        if s <= 0.04045 {
            s / 12.92
        } else {
            ((s + 0.055) / 1.055).powf(2.4)
        }
    };
    [c(16), c(8), c(0)]
}

/// The `t` the legend gives is where the independent checker (parry, conservative
/// advancement) finds the first contact: the translation to a little before it is free, to a
/// little after it is not.
#[test]
fn the_collision_reported_is_where_the_independent_checker_finds_it() {
    use viaroad::local::{first_collision_on_path, LocalSpec};
    use viaroad::scene::Scene;

    let scene = Scene::load(&root().join(EASY)).unwrap();
    let groups = LocalSpec::roadmap_default().build().groups(&scene.space);
    let oracle = scene.oracle();
    let path = vec![EASY_START.to_vec(), EASY_GOAL.to_vec()];
    let mut counts = viaroad::oracle::CallCounts::default();
    let hit = first_collision_on_path(&scene.space, oracle.as_ref(), &groups, &path, &mut counts)
        .unwrap()
        .expect("the straight translation runs into the wall");
    assert_eq!(hit.segment, 0);
    assert!(hit.proved && hit.t > 0.0 && hit.t < 1.0, "{hit:?}");
    let at = |t: f64| -> Vec<f64> {
        EASY_START
            .iter()
            .zip(&EASY_GOAL)
            .map(|(a, b)| a + t * (b - a))
            .collect()
    };
    let checker = common::rigid::RigidChecker::se3(&scene);
    // 1 % of the 200-unit segment either side
    checker
        .certify_motion(&EASY_START, &at(hit.t - 0.01))
        .unwrap_or_else(|e| panic!("free before t = {}: {e}", hit.t));
    assert!(
        checker
            .certify_motion(&EASY_START, &at(hit.t + 0.01))
            .is_err(),
        "blocked after t = {}",
        hit.t
    );
    // the shipped solution is free
    let lines = easy_lines();
    let free: Vec<Vec<f64>> = lines
        .iter()
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect();
    assert_eq!(
        first_collision_on_path(&scene.space, oracle.as_ref(), &groups, &free, &mut counts)
            .unwrap(),
        None
    );
}

#[test]
fn a_free_path_file_is_labelled_as_the_given_path() {
    let d = temp_dir("defects_output", "free");
    let path = root().join("scenes/ompl/3D/Easy.path");
    let path = path.to_str().unwrap();
    let glb = d.join("out.glb");
    let glb = glb.to_str().unwrap();
    for (shorten, labels) in [
        ("fast", vec!["shortened path", "given path"]),
        ("off", vec!["given path"]),
    ] {
        let o = viaroad(&[
            "export",
            EASY,
            "--path",
            path,
            "--shorten",
            shorten,
            "-o",
            glb,
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert_eq!(warnings(&o), Vec::<String>::new(), "--shorten {shorten}");
        let doc = glb_json(Path::new(glb));
        let rows = doc["asset"]["extras"]["legend"]["paths"]
            .as_array()
            .unwrap();
        let got: Vec<&str> = rows.iter().map(|r| r["label"].as_str().unwrap()).collect();
        assert_eq!(got, labels, "--shorten {shorten}");
        assert!(rows.iter().all(|r| r["collides"] == false));
        // the path the robot follows has the valid path's blue key
        assert_eq!(rows[0]["colour"], BLUE, "--shorten {shorten}");
    }
}

#[test]
fn a_colliding_request_path_is_keyed_in_the_warning_colour() {
    let d = temp_dir("defects_output", "request");
    let page = d.join("box.html");
    let a = "scenes/arms";
    // MotionBenchMaker's box problem 1: the straight joint motion from start to goal hits the box
    let o = viaroad(&[
        "view",
        &format!("{a}/mbm/box/scene0001.yaml"),
        "--request",
        &format!("{a}/mbm/box/request0001.yaml"),
        "--urdf",
        &format!("{a}/panda/panda.urdf"),
        "--srdf",
        &format!("{a}/panda/panda.srdf"),
        "-o",
        page.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let w = warnings(&o);
    assert_eq!(w.len(), 1, "{}", stderr(&o));
    assert!(w[0].contains("collides in segment 1 at t = "), "{}", w[0]);
    let legend = legend_html(&page);
    assert!(
        !legend.contains(BLUE),
        "a colliding path with a blue key: {legend}"
    );
    assert!(
        legend.contains(r#"class="warning""#) && legend.contains("collides in segment 1"),
        "{legend}"
    );
}

/// The `t` after "at t = " in a message.
fn t_of(line: &str) -> f64 {
    let rest = &line[line.find("at t = ").expect(line) + 7..];
    let end = rest
        .find(|c: char| c != '.' && !c.is_ascii_digit())
        .unwrap_or(rest.len());
    rest[..end].parse().unwrap()
}

/// An arm scene's oracle answers a straight motion of several joints only yes or no: the
/// collision is still located, where the independent arm checker (the `--request` form,
/// sampling every 0.01 rad) finds it.
#[test]
fn a_colliding_arm_path_file_is_located_where_the_arm_checker_finds_it() {
    let d = temp_dir("defects_output", "arm");
    let a = "scenes/arms";
    // MotionBenchMaker's box problem 1: its start and goal (panda_arm's joints)
    let path = write(
        &d,
        "box.path",
        "0 -0.785 0 -2.356 0 1.571 0.785\n\
         0.4534448383669427 1.7628 0.1941262264518609 -0.8667848896139277 \
         -0.3798524112731043 2.606927984171601 -0.1898611792470702\n",
    );
    let out = d.join("out.glb");
    let out = out.to_str().unwrap();
    let o = viaroad(&[
        "export",
        &format!("{a}/panda-box-1.toml"),
        "--path",
        &path,
        "-o",
        out,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let w = warnings(&o);
    assert_eq!(w.len(), 1, "{}", stderr(&o));
    assert!(w[0].contains("collides in segment 1 at t = "), "{}", w[0]);
    let ours = t_of(&w[0]);
    let o = viaroad(&[
        "export",
        &format!("{a}/mbm/box/scene0001.yaml"),
        "--request",
        &format!("{a}/mbm/box/request0001.yaml"),
        "--urdf",
        &format!("{a}/panda/panda.urdf"),
        "--srdf",
        &format!("{a}/panda/panda.srdf"),
        "--path",
        &path,
        "-o",
        out,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let w = warnings(&o);
    assert_eq!(w.len(), 1, "{}", stderr(&o));
    let checker = t_of(&w[0]);
    assert!(
        (ours - checker).abs() <= 0.01,
        "{ours} vs the checker's {checker}"
    );
}

#[test]
fn an_empty_path_file_is_an_error() {
    let d = temp_dir("defects_output", "empty");
    let empty = write(&d, "empty.path", "# nothing here\n\n");
    let out = d.join("out.glb");
    for command in ["export", "view"] {
        fails_alone_with(
            &[command, EASY, "--path", &empty, "-o", out.to_str().unwrap()],
            &format!("the path file {empty} holds no configuration"),
        );
    }
    assert!(!out.exists());
}

#[test]
fn a_one_configuration_path_has_length_zero_not_minus_zero() {
    let d = temp_dir("defects_output", "one");
    let one = write(&d, "one.path", &format!("{}\n", state_line(&EASY_START)));
    let glb = d.join("out.glb");
    let page = d.join("out.html");
    for (command, out) in [("export", &glb), ("view", &page)] {
        let o = viaroad(&[command, EASY, "--path", &one, "-o", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", stderr(&o));
        let err = stderr(&o);
        assert!(!err.contains("-0.0"), "{err}");
        assert!(err.contains("length 0.0000 (raw 0.0000)"), "{err}");
    }
    let doc = glb_json(&glb);
    let legend = &doc["asset"]["extras"]["legend"];
    for v in [
        &legend["length"],
        &legend["raw_length"],
        &legend["paths"][0]["length"],
    ] {
        let x = v.as_f64().unwrap();
        assert!(x == 0.0 && x.is_sign_positive(), "{legend}");
    }
    let html = legend_html(&page);
    assert!(
        html.contains("length 0.000<") && !html.contains("-0.0"),
        "{html}"
    );
    // the library's sum, which every printed length comes from
    let scene = viaroad::scene::Scene::load(&root().join(EASY)).unwrap();
    let l = viaroad::local::path_length(&scene.space, &[], &[EASY_START.to_vec()]);
    assert!(l == 0.0 && l.is_sign_positive());
    assert_eq!(format!("{l:.4}"), "0.0000");
}

#[test]
fn huge_numbers_in_messages_are_printed_in_short_form() {
    let d = temp_dir("defects_output", "huge");
    // bounds the wrong way round, one of them 10^300: the message used to hold its 301 digits
    let scene = write(
        &d,
        "huge.toml",
        "name = \"huge\"\n[space]\nkind = \"r2\"\nlower = [1e300, 0.0]\nupper = [0.0, 1.0]\n",
    );
    let line = fails_alone_with(&["solve", &scene], "lower 1e300 > upper 0");
    assert!(line.len() < 200, "{line}");
    // a start far out of the bounds: exponent notation from 10^6 on, not 12345678.9
    let scene = write(
        &d,
        "far.toml",
        "name = \"far\"\n[space]\nkind = \"r2\"\nlower = [0.0, 0.0]\nupper = [1.0, 1.0]\n\
         [[query]]\nstart = [12345678.9, 0.5]\ngoal = [0.5, 0.5]\n",
    );
    let line = fails_with(&["solve", &scene], "[1.23456789e7, 0.5]");
    assert!(!line.contains("12345678.9"), "{line}");
    // data meant to be read back keeps every digit: path files are written with `{:?}`
    let q = vec![0.1 + 0.2, 1e300];
    let file = d.join("data.path");
    viaroad::scene::ompl_cfg::write_states(&file, std::slice::from_ref(&q)).unwrap();
    let back: Vec<f64> = std::fs::read_to_string(&file)
        .unwrap()
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    assert_eq!(back, q);
}

/// Several queries, so that a batch would run before a late error.
fn query_file(dir: &Path) -> String {
    write(
        dir,
        "queries.txt",
        "0.02 0.98 0.98 0.02\n0.05 0.05 0.95 0.95\n0.5 0.97 0.5 0.03\n0.97 0.5 0.03 0.5\n",
    )
}

#[test]
fn keep_answers_into_an_unwritable_place_is_refused_before_the_batch() {
    let d = temp_dir("defects_output", "keep");
    let queries = query_file(&d);
    // a "directory" that is a regular file: no file can be created under it, even by root
    let blocker = write(&d, "blocker", "a file, not a directory\n");
    let under_file = format!("{blocker}/kept.bin");
    // `fails_alone_with`: the error is the only line, nothing printed before it, so no
    // query of the batch was answered first
    for out in [
        vec!["--keep-answers", &under_file],
        vec!["--path-out", &under_file],
    ] {
        let mut args = vec![
            "query",
            CLUTTERED_MAP,
            "--scene",
            CLUTTERED,
            "--queries",
            &queries,
        ];
        args.extend(out);
        fails_alone_with(&args, "blocker");
    }

    // a directory no one may create files in, not even root: /proc
    if Path::new("/proc/self").is_dir() {
        fails_alone_with(
            &[
                "query",
                CLUTTERED_MAP,
                "--scene",
                CLUTTERED,
                "--queries",
                &queries,
                "--keep-answers",
                "/proc/viaroad-kept.bin",
            ],
            "no file can be created in /proc",
        );
    }

    // a read-only directory (which binds only where the tests do not run as root)
    let ro = d.join("read-only");
    std::fs::create_dir(&ro).unwrap();
    set_mode(&ro, 0o555);
    let probe = ro.join("probe");
    if std::fs::write(&probe, b"").is_ok() {
        let _ = std::fs::remove_file(&probe);
        eprintln!("SKIPPED the read-only directory: this user may write into it anyway (root)");
    } else {
        let target = ro.join("kept.bin");
        let target = target.to_str().unwrap();
        let line = fails_alone_with(
            &[
                "query",
                CLUTTERED_MAP,
                "--scene",
                CLUTTERED,
                "--queries",
                &queries,
                "--keep-answers",
                target,
            ],
            "no file can be created in",
        );
        assert!(line.contains("Permission denied"), "{line}");
    }
    set_mode(&ro, 0o755);
}

fn set_mode(p: &Path, mode: u32) {
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(p, std::fs::Permissions::from_mode(mode)).unwrap();
}

#[test]
fn a_js_test_without_its_tools_says_it_skipped_and_fails_where_they_are_required() {
    // not required: a line, no failure
    common::js::skip_unless("some_js_test", "node is absent", false);
    // required (VIAROAD_REQUIRE_JS set): the skip is a failure naming the test and the cause
    let failed = std::panic::catch_unwind(|| {
        common::js::skip_unless("some_js_test", "node is absent", true)
    })
    .expect_err("a required skip fails");
    let message = failed.downcast_ref::<String>().cloned().unwrap_or_default();
    assert!(
        message.contains("some_js_test")
            && message.contains("node is absent")
            && message.contains(common::js::REQUIRE),
        "{message}"
    );
}
