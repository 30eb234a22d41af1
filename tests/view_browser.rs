//! The viewer page in a real browser: `viaroad view` writes the page, headless
//! Debian Chromium opens it from `file://` (driven by playwright-core, pinned in tools/js,
//! through tools/js/view-check.js), and the test asserts that the model loaded, that the robot
//! is drawn at t = 0 and at t = 1 (a render with the robot alone gives its mask, and on much
//! of it the full render differs from the render without the robot), that it moved (the masks differ and the
//! full renders change where the robot was), and that the console stayed free of errors.
//!
//! Skipped with a `SKIPPED` line on stderr where Chromium (`/usr/bin/chromium`, or
//! `CHROMIUM`), node or the npm packages are absent, and failed instead where
//! `VIAROAD_REQUIRE_JS` is set (`common::js`); `.ci/run` installs them. One rigid body (OMPL.app's Easy, a
//! handful of nodes) and one arm (the Panda in
//! MotionBenchMaker's table_pick problem 1, `scenes/arms/panda-table_pick-1.toml`), so
//! that the suite stays quick; and two squares of a several-body scene along a path given by
//! hand (`--path`, checked by the oracle before it is drawn).

use crate::common;

use common::cli::{stderr, temp_dir, viaroad};
use common::js::{node_script, skip};
use serde_json::Value;
use std::path::PathBuf;
use std::process::Command;

/// The browser and the driver, or why the test cannot run.
fn browser() -> Result<(PathBuf, PathBuf), String> {
    let chromium = std::env::var_os("CHROMIUM")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/usr/bin/chromium"));
    if !chromium.is_file() {
        return Err(format!(
            "{} is absent (apt-get install -y chromium)",
            chromium.display()
        ));
    }
    Ok((chromium, node_script("playwright-core", "view-check.js")?))
}

/// Writes the page with `viaroad view ARGS -o page.html`, loads it and returns the report.
fn check_page(name: &str, args: &[&str]) -> Option<Value> {
    let (chromium, script) = match browser() {
        Ok(b) => b,
        Err(why) => {
            skip(&format!("view_browser {name}"), &why);
            return None;
        }
    };
    let dir = temp_dir("view_browser", name);
    let page = dir.join("view.html");
    let mut all = vec!["view"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", page.to_str().unwrap()]);
    let o = viaroad(&all);
    assert!(o.status.success(), "{all:?}: {}", stderr(&o));
    let html = std::fs::read_to_string(&page).unwrap();
    // self-contained: no script, style or image fetched from anywhere
    assert!(
        !html.contains("src=\"") && !html.contains("<link"),
        "the page fetches nothing"
    );
    let out = Command::new("node")
        .arg(&script)
        .arg(&page)
        .arg(&*dir)
        .env("CHROMIUM", &chromium)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "view-check: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: Value = serde_json::from_slice(&out.stdout).unwrap();
    for shot in ["t0.png", "t1.png"] {
        let png = std::fs::read(dir.join(shot)).unwrap();
        assert_eq!(&png[1..4], b"PNG", "{shot} is a PNG");
    }
    let _ = std::fs::remove_dir_all(&dir);
    Some(report)
}

/// The assertions every page must pass.
fn assert_robot_drawn_and_moved(name: &str, r: &Value) {
    let n = |k: &str| {
        r[k].as_f64()
            .unwrap_or_else(|| panic!("{name}: no {k} in {r}"))
    };
    assert_eq!(r["console_errors"], serde_json::json!([]), "{name}: {r}");
    let pixels = n("width") * n("height");
    for t in ["t0", "t1"] {
        // the robot alone covers a visible patch of the canvas …
        let drawn = n(&format!("robot_pixels_{t}"));
        assert!(drawn >= 200.0 && drawn < 0.5 * pixels, "{name} {t}: {r}");
        // … and in the full picture the robot changes much of that patch (drawn in front, or
        // seen through a translucent wall)
        assert!(
            n(&format!("robot_drawn_{t}")) > 0.5 * drawn,
            "{name} {t}: {r}"
        );
    }
    // the robot moved: its masks differ, and the full pictures change where it was at t = 0
    let smaller = n("robot_pixels_t0").min(n("robot_pixels_t1"));
    assert!(n("moved_pixels") > 0.2 * smaller, "{name}: {r}");
    assert!(
        n("changed_where_robot_was") > 0.2 * n("robot_pixels_t0"),
        "{name}: {r}"
    );
    let legend = r["legend"].as_str().unwrap();
    assert!(legend.contains("length"), "{name}: legend {legend}");
}

#[test]
fn rigid_body_moves_in_the_browser() {
    let Some(r) = check_page("easy", &["scenes/ompl/3D/Easy.cfg"]) else {
        return;
    };
    assert_robot_drawn_and_moved("Easy", &r);
    let legend = r["legend"].as_str().unwrap();
    assert!(
        legend.contains("Easy") && legend.contains("oracle calls"),
        "{legend}"
    );
}

#[test]
fn arm_moves_in_the_browser() {
    // planned here (the joint space's roadmap, a few nodes), every link placed by forward
    // kinematics
    let Some(r) = check_page("panda", &["scenes/arms/panda-table_pick-1.toml"]) else {
        return;
    };
    assert_robot_drawn_and_moved("Panda", &r);
    assert!(r["legend"].as_str().unwrap().contains("panda-table_pick-1"));
}

#[test]
fn several_bodies_move_in_the_browser() {
    // the second square rises into the niche, the first passes beneath it
    let dir = temp_dir("view_browser", "bodies-path");
    let path = dir.join("swap.path");
    std::fs::write(
        &path,
        "0.5 0.5 0 1.5 0.5 0\n0.5 0.5 0 1.5 1.5 0\n2.5 0.5 0 1.5 1.5 0\n",
    )
    .unwrap();
    let args = [
        "scenes/bodies/swap-corridor-2.toml",
        "--path",
        path.to_str().unwrap(),
    ];
    let Some(r) = check_page("bodies", &args) else {
        return;
    };
    assert_robot_drawn_and_moved("swap-corridor-2", &r);
    let legend = r["legend"].as_str().unwrap();
    assert!(legend.contains("s1") && legend.contains("s2"), "{legend}");
}
