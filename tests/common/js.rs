//! The JavaScript tools some suites drive (node and the npm packages pinned in `tools/js`,
//! and for the viewer a Chromium): where they are missing a test cannot run, and cargo
//! would still print `ok`. [`skip`] says so on stderr (`SKIPPED test: why`, shown with
//! `--nocapture`), and fails the test instead where `VIAROAD_REQUIRE_JS` is set: `.ci/run`
//! installs the tools, so a skip there would hide a broken install.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The environment variable that turns a skip into a failure.
pub const REQUIRE: &str = "VIAROAD_REQUIRE_JS";

/// Says why `test` is skipped, or fails it where [`REQUIRE`] is set.
pub fn skip(test: &str, why: &str) {
    skip_unless(test, why, std::env::var_os(REQUIRE).is_some());
}

/// [`skip`] with the requirement given: panics where `required`, else prints the line.
pub fn skip_unless(test: &str, why: &str, required: bool) {
    assert!(!required, "{test}: {why}, and {REQUIRE} is set");
    eprintln!("SKIPPED {test}: {why}");
}

/// `tools/js`, where the npm packages and the scripts driving them live.
pub fn tools_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/js")
}

/// The script `tools/js/SCRIPT` where node and the npm package `package` are present, or why
/// the test cannot run.
pub fn node_script(package: &str, script: &str) -> Result<PathBuf, String> {
    let js = tools_dir();
    if !js.join("node_modules").join(package).is_dir() {
        return Err(format!(
            "tools/js/node_modules/{package} is absent (cd tools/js && npm ci --omit=dev)"
        ));
    }
    match Command::new("node").arg("--version").output() {
        Ok(o) if o.status.success() => Ok(js.join(script)),
        _ => Err("node is absent".into()),
    }
}
