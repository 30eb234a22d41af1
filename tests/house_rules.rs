//! The house rules that a reader meets: comments, help texts and the user's guide say what is
//! and why, not when or under which issue it was decided. The history is in git and in
//! `benches/results/`, whose dated folders are the one place dates belong.
//!
//! Checked: every comment line and every `help =` / `about =` string of `src/` and
//! `python/src/` (clap takes help texts from doc comments), and every line of `README.md`,
//! `ARCHITECTURE.md` and `docs/*.md`. Code outside comments may hold dates (a test of a date
//! formatter does).
//!
//! Also: no circles of imports and no function over 120 lines outside tests, by the scripts
//! in `tools/` that a maintainer runs by hand.

use std::path::{Path, PathBuf};

/// Where a line cites history: `issue 12`, `issues 10 and 11`, `issue #7`, or an ISO date
/// (`2026-12-05`). Returns what matched.
fn history(line: &str) -> Option<String> {
    let lower = line.to_ascii_lowercase();
    let b = lower.as_bytes();
    for (i, _) in lower.match_indices("issue") {
        let mut j = i + "issue".len();
        if b.get(j) == Some(&b's') {
            j += 1;
        }
        while b.get(j) == Some(&b' ') || b.get(j) == Some(&b'#') {
            j += 1;
        }
        if j > i + "issue".len() && b.get(j).is_some_and(u8::is_ascii_digit) {
            return Some(line[i..=j].to_string());
        }
    }
    let digit = |k: usize| b.get(k).is_some_and(u8::is_ascii_digit);
    (0..b.len()).find_map(|i| {
        let date = b[i] == b'2'
            && b.get(i + 1) == Some(&b'0')
            && [i + 2, i + 3, i + 5, i + 6, i + 8, i + 9]
                .into_iter()
                .all(digit)
            && b.get(i + 4) == Some(&b'-')
            && b.get(i + 7) == Some(&b'-');
        date.then(|| line[i..i + 10].to_string())
    })
}

/// Comment lines and help strings of a Rust source: what a reader or `--help` shows.
fn is_prose(line: &str) -> bool {
    let t = line.trim_start();
    t.starts_with("//") || t.contains("help =") || t.contains("about =")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn offences(path: &Path, prose_only: bool) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap();
    let rel = path
        .strip_prefix(root())
        .unwrap_or(path)
        .display()
        .to_string();
    text.lines()
        .enumerate()
        .filter(|(_, l)| !prose_only || is_prose(l))
        .filter_map(|(n, l)| history(l).map(|h| format!("{rel}:{}: `{h}` in: {}", n + 1, l.trim())))
        .collect()
}

#[test]
fn the_matcher_finds_issue_numbers_and_dates_only() {
    assert!(history("/// refused (issue 16: overflow)").is_some());
    assert!(history("see Issues #7").is_some());
    assert!(history("measured 2026-12-05 on the box").is_some());
    assert!(history("an issue of taste, 16 ways").is_none());
    assert!(history("the 2026 problems, 20-12-05").is_none());
    assert!(history("query p50 92 → 17 ms with 2 ms").is_none());
}

#[test]
fn comments_and_help_texts_cite_no_issues_or_dates() {
    let mut files = Vec::new();
    rust_files(&root().join("src"), &mut files);
    rust_files(&root().join("python/src"), &mut files);
    let found: Vec<String> = files.iter().flat_map(|f| offences(f, true)).collect();
    assert!(
        found.is_empty(),
        "say why without the history (it is in git):\n{}",
        found.join("\n")
    );
}

#[test]
fn the_users_guide_cites_no_issues_or_dates() {
    let mut files = vec![root().join("README.md"), root().join("ARCHITECTURE.md")];
    for entry in std::fs::read_dir(root().join("docs")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            files.push(path);
        }
    }
    let found: Vec<String> = files.iter().flat_map(|f| offences(f, false)).collect();
    assert!(
        found.is_empty(),
        "dated notes belong in benches/results/, issue numbers in commit messages:\n{}",
        found.join("\n")
    );
}

/// `--help` of every command says what options do, not their history, and puts the knobs
/// that only tuning needs under a "Tuning" heading after the options people need.
#[test]
fn help_texts_put_knobs_under_tuning_and_cite_no_history() {
    let commands: &[(&[&str], bool)] = &[
        (&[], false),
        (&["demo"], true),
        (&["build"], true),
        (&["query"], true),
        (&["serve"], true),
        (&["export"], true),
        (&["view"], true),
        (&["render"], true),
        (&["info"], false),
        (&["probe"], false),
        (&["certify"], false),
        (&["bench"], false),
        (&["bench", "discs"], true),
        (&["bench", "local"], true),
        (&["bench", "validity"], false),
        (&["bench", "mbm"], true),
        (&["bench", "certify"], false),
    ];
    for (command, tuning) in commands {
        let args: Vec<&str> = command.iter().copied().chain(["--help"]).collect();
        let o = crate::common::cli::viaroad(&args);
        assert!(o.status.success(), "{args:?}");
        let text = crate::common::cli::stdout(&o);
        for line in text.lines() {
            assert!(history(line).is_none(), "{args:?} cites history: {line}");
            assert!(!line.contains("benches/results"), "{args:?}: {line}");
        }
        let heading = text.lines().position(|l| l == "Tuning:");
        assert_eq!(
            heading.is_some(),
            *tuning,
            "{args:?}: a Tuning heading?\n{text}"
        );
        if let Some(h) = heading {
            let options = text.lines().position(|l| l == "Options:").unwrap();
            assert!(options < h, "{args:?}: the options people need come first");
        }
    }
}

/// Runs one of the house's Python checks in `tools/` (the same code a maintainer runs by hand);
/// returns its exit status and its standard output.
fn house_tool(script: &str, args: &[&str]) -> (bool, String) {
    let o = std::process::Command::new("python3")
        .arg(root().join("tools").join(script))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("python3 tools/{script}: {e} (the house checks need python3)"));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.trim().is_empty(), "tools/{script}: {stderr}");
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
    )
}

/// An import graph of `src/`, file by file (`tools/import_graph.py --strict`: a `mod.rs` and
/// the children it calls count too), has no circles: what a module and its children share
/// lives in a file below both.
#[test]
fn no_circles_of_imports_file_by_file() {
    let (ok, out) = house_tool("import_graph.py", &[]);
    assert!(ok, "circles of imports between modules:\n{out}");
    let (ok, out) = house_tool("import_graph.py", &["--strict"]);
    assert!(
        ok,
        "circles of imports (move what the files share into a file below them):\n{out}"
    );
}

/// No function outside tests is longer than 120 lines (`tools/long_functions.py`): a long
/// function reads better as named steps.
#[test]
fn no_function_outside_tests_is_over_120_lines() {
    let (ok, out) = house_tool("long_functions.py", &["--max", "120"]);
    assert!(ok, "split these into named steps:\n{out}");
}
