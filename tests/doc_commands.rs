//! Every command the README and the user's guide (`docs/*.md`) show is run, so that what they
//! say stays true.
//!
//! Read from the fenced blocks marked `sh`, `bash`, `shell` or `console` (in a block with `$ `
//! prompts, only the prompted lines are commands; the rest is output). A `viaroad …` line (also
//! `cargo run --release -- …`) is one of:
//!
//! - **a command**: run by `sh` in a directory of its own (the repository's `scenes/`, `tests/`
//!   and friends linked in, `roadmaps/` copied, `/tmp/` redirected into it), one after another
//!   in the page's order; it must exit 0 without a panic. Variables set by a line such as
//!   `T=scenes/arms/mbm/table_pick` and files written by `printf … > file` carry over.
//! - **a synopsis**: a line with placeholders (`SCENE`, `DIR`, `N`) or `[optional]` parts. Its
//!   sub-command must exist and each of its `--flags` must be in that sub-command's `--help`.
//! - **a command that needs files the repository does not ship** (another planner's paths,
//!   VAMP's problem sets): the line says so in a `# needs …` comment that readers see. It is
//!   run too, without those files: it must fail with status 1 and one `error:` line, never a
//!   usage error (status 2), which shows that its arguments parse.
//!
//! A `viaroad …` span in the prose (`viaroad query --check`) is checked as a synopsis.
//!
//! Other tools' lines (`cargo test`, `pip`, `perf`, scripts under `benches/`) are not run here:
//! CI runs the suite and the Python tests itself, and profiling needs `perf`. The `python`
//! blocks are run by `python/tests/test_docs.py`. A block with a `viaroad` command but no shell
//! marking fails, so that no command escapes. Examples here must stay cheap (node budgets
//! rather than long time budgets): the whole file runs in well under a minute on two cores.

use crate::common;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// One line of a page's shell block, continuations joined.
#[derive(Debug)]
struct Line {
    /// Where it starts, for messages (`README.md:53`).
    at: String,
    text: String,
}

#[derive(Debug, PartialEq)]
enum Kind {
    Run,
    Needs,
    Synopsis,
    /// `NAME=value` alone, or `printf`/`echo` into a file: run, carried over.
    Setup,
    /// Another tool's line: not run.
    Other,
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn is_shell(info: &str) -> bool {
    let lang = info.split([' ', ',']).next().unwrap_or("");
    matches!(lang, "sh" | "bash" | "shell" | "console")
}

/// The lines of every shell block of `page` (relative to the repository), continuations
/// joined, prompts stripped. Panics on a `viaroad` command in a block not marked as shell.
fn shell_lines(page: &str) -> Vec<Line> {
    let text = std::fs::read_to_string(repo().join(page)).unwrap();
    let mut out = Vec::new();
    let mut block: Option<(String, Vec<(usize, &str)>)> = None;
    for (n, raw) in text.lines().enumerate() {
        let t = raw.trim_start();
        if let Some(info) = t.strip_prefix("```") {
            match block.take() {
                None => block = Some((info.trim().to_string(), Vec::new())),
                Some((info, lines)) => out.extend(block_lines(page, &info, &lines)),
            }
        } else if let Some((_, lines)) = &mut block {
            lines.push((n + 1, t));
        }
    }
    out
}

fn block_lines(page: &str, info: &str, lines: &[(usize, &str)]) -> Vec<Line> {
    if !is_shell(info) {
        for (n, l) in lines {
            assert!(
                !(l.starts_with("viaroad ") || l.starts_with("$ viaroad ")),
                "{page}:{n}: a viaroad command in a block marked `{info}`: mark it ```sh or ```console"
            );
        }
        return Vec::new();
    }
    let prompted = lines.iter().any(|(_, l)| l.starts_with("$ "));
    let mut out: Vec<Line> = Vec::new();
    let mut open = false;
    for (n, l) in lines {
        let body = if open {
            Some(*l)
        } else if prompted {
            l.strip_prefix("$ ")
        } else {
            Some(*l)
        };
        let Some(body) = body else { continue };
        let (part, more) = match body.trim_end().strip_suffix('\\') {
            Some(p) => (p, true),
            None => (body.trim_end(), false),
        };
        if open {
            let last = out.last_mut().unwrap();
            last.text.push(' ');
            last.text.push_str(part.trim());
        } else if !part.trim().is_empty() && !part.trim_start().starts_with('#') {
            out.push(Line {
                at: format!("{page}:{n}"),
                text: part.trim().to_string(),
            });
        }
        open = more;
    }
    out
}

/// The line without its `# comment`.
fn code(text: &str) -> &str {
    match text.find(" #") {
        Some(k) => text[..k].trim_end(),
        None => text,
    }
}

/// A placeholder (`SCENE`, `DIR`, `SCENE…`, `N]`) or an optional part (`[--json]`).
fn is_placeholder(word: &str) -> bool {
    let w = word.trim_end_matches([']', '…', '.', ',']);
    word.starts_with('[')
        || (w.chars().next().is_some_and(|c| c.is_ascii_uppercase())
            && w.chars()
                .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_'))
}

fn is_assignment(word: &str) -> bool {
    word.split_once('=').is_some_and(|(name, _)| {
        !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    })
}

/// The line as it is run (`cargo run --release --` is `viaroad`), and what it is.
fn classify(text: &str) -> (String, Kind) {
    let text = match text.strip_prefix("cargo run --release -- ") {
        Some(rest) => format!("viaroad {rest}"),
        None => text.to_string(),
    };
    let words: Vec<&str> = code(&text).split_whitespace().collect();
    let head = words.iter().find(|w| !is_assignment(w));
    let kind = match head {
        None => Kind::Setup,
        Some(&"printf" | &"echo") => Kind::Setup,
        Some(&"viaroad") if words.iter().any(|w| is_placeholder(w)) => Kind::Synopsis,
        Some(&"viaroad") if text.contains("# needs") => Kind::Needs,
        Some(&"viaroad") => Kind::Run,
        Some(_) => Kind::Other,
    };
    (text, kind)
}

/// A directory like the repository's root for the commands of one page.
fn workspace(name: &str) -> common::cli::TempDir {
    let dir = common::cli::temp_dir("doc_commands", name);
    for linked in ["scenes", "tests", "python", "benches", "assets", "docs"] {
        std::os::unix::fs::symlink(repo().join(linked), dir.join(linked)).unwrap();
    }
    std::fs::create_dir(dir.join("roadmaps")).unwrap();
    for entry in std::fs::read_dir(repo().join("roadmaps")).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), dir.join("roadmaps").join(entry.file_name())).unwrap();
    }
    std::fs::create_dir(dir.join("tmp")).unwrap();
    dir
}

fn shell(dir: &Path, setup: &str, text: &str) -> Output {
    let bin = Path::new(env!("CARGO_BIN_EXE_viaroad")).parent().unwrap();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let script = format!("{setup}{text}").replace("/tmp/", &format!("{}/tmp/", dir.display()));
    Command::new("sh")
        .arg("-c")
        .arg(script)
        .current_dir(dir)
        .env("PATH", path)
        .stdin(Stdio::null())
        .output()
        .expect("sh runs")
}

fn help(words: &[&str], cache: &mut HashMap<String, String>) -> String {
    let key = words.join(" ");
    cache
        .entry(key)
        .or_insert_with(|| {
            let args: Vec<&str> = words.iter().copied().chain(["--help"]).collect();
            let o = common::cli::viaroad(&args);
            assert!(o.status.success(), "viaroad {args:?}: no such command");
            common::cli::stdout(&o)
        })
        .clone()
}

/// Every `--flag` of a synopsis is in its sub-command's help.
fn check_synopsis(line: &Line, cache: &mut HashMap<String, String>) {
    let words: Vec<&str> = code(&line.text).split_whitespace().collect();
    let sub: Vec<&str> = words[1..]
        .iter()
        .take_while(|w| {
            w.chars().all(|c| c.is_ascii_lowercase() || c == '-') && !w.starts_with('-')
        })
        .copied()
        .collect();
    let text = help(&sub, cache);
    for w in &words {
        let flag = w.trim_start_matches('[');
        if !flag.starts_with("--") {
            continue;
        }
        let end = flag[2..]
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
            .map_or(flag.len(), |k| k + 2);
        let flag = &flag[..end];
        assert!(
            text.contains(&format!("{flag} ")) || text.contains(&format!("{flag}\n")),
            "{}: `{flag}` is not an option of `viaroad {}`",
            line.at,
            sub.join(" ")
        );
    }
}

fn report(line: &Line, o: &Output) -> String {
    format!(
        "{}: `{}` exited with {:?}\nstdout:\n{}\nstderr:\n{}",
        line.at,
        line.text,
        o.status.code(),
        common::cli::stdout(o),
        common::cli::stderr(o)
    )
}

/// Runs the commands of `pages` in order, each page in its own directory. Returns how many
/// lines of each kind were met.
fn run_pages(pages: &[String], name: &str) -> HashMap<&'static str, usize> {
    let mut cache = HashMap::new();
    let mut counts = HashMap::new();
    for page in pages {
        let dir = workspace(&format!("{name}-{}", page.replace(['/', '.'], "-")));
        let mut setup = String::new();
        for line in shell_lines(page) {
            let (text, kind) = classify(&line.text);
            let label = match kind {
                Kind::Run => {
                    let o = shell(&dir, &setup, &text);
                    let err = common::cli::stderr(&o);
                    assert!(
                        o.status.success() && !err.contains("panicked"),
                        "{}",
                        report(&line, &o)
                    );
                    "run"
                }
                Kind::Needs => {
                    let o = shell(&dir, &setup, &text);
                    let err = common::cli::stderr(&o);
                    assert!(
                        o.status.code() == Some(1)
                            && err.lines().any(|l| l.starts_with("error:"))
                            && !err.contains("panicked"),
                        "a command that needs files not shipped must parse and fail on them: {}",
                        report(&line, &o)
                    );
                    "needs"
                }
                Kind::Synopsis => {
                    check_synopsis(&line, &mut cache);
                    "synopsis"
                }
                Kind::Setup => {
                    if code(&text).split_whitespace().all(is_assignment) {
                        setup.push_str(code(&text));
                        setup.push('\n');
                    } else {
                        let o = shell(&dir, &setup, &text);
                        assert!(o.status.success(), "{}", report(&line, &o));
                    }
                    "setup"
                }
                Kind::Other => "other",
            };
            *counts.entry(label).or_insert(0) += 1;
        }
    }
    counts
}

#[test]
fn the_reader_tells_commands_synopses_and_other_tools_apart() {
    let kind = |t: &str| classify(t).1;
    assert_eq!(kind("viaroad info roadmaps/mine.bin"), Kind::Run);
    assert_eq!(kind("cargo run --release -- demo   # learn"), Kind::Run);
    assert_eq!(
        kind("viaroad solve SCENE --tree [--time S]"),
        Kind::Synopsis
    );
    assert_eq!(
        kind("viaroad bench local SCENE… --methods SPEC…"),
        Kind::Synopsis
    );
    assert_eq!(kind("viaroad certify $T/scene0001.yaml p.path"), Kind::Run);
    assert_eq!(
        kind("viaroad bench mbm /tmp/mbm --out o   # needs VAMP's problems"),
        Kind::Needs
    );
    assert_eq!(
        kind("T=scenes/arms/mbm/table_pick      # a problem"),
        Kind::Setup
    );
    assert_eq!(kind("printf \"0 1\\n\" > queries.txt"), Kind::Setup);
    assert_eq!(kind("cargo test --release"), Kind::Other);
    assert_eq!(
        kind("RAYON_NUM_THREADS=1 perf record -- target/release/viaroad"),
        Kind::Other
    );
    assert!(!is_placeholder("--from=0,-0.785"));
    assert!(is_placeholder("N]"));
}

#[test]
fn the_readme_commands_run() {
    let counts = run_pages(&["README.md".to_string()], "readme");
    assert!(counts["run"] >= 10, "{counts:?}");
}

#[test]
fn the_guide_commands_run() {
    let mut pages: Vec<String> = std::fs::read_dir(repo().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".md"))
        .map(|n| format!("docs/{n}"))
        .collect();
    pages.sort();
    let counts = run_pages(&pages, "guide");
    assert!(
        counts["run"] >= 10 && counts["synopsis"] >= 10,
        "{counts:?}"
    );
}

/// The `viaroad …` spans of a page's prose (outside fenced blocks), as synopses.
fn inline_commands(page: &str) -> Vec<Line> {
    let text = std::fs::read_to_string(repo().join(page)).unwrap();
    let mut fenced = false;
    let prose: Vec<&str> = text
        .lines()
        .map(|l| {
            if l.trim_start().starts_with("```") {
                fenced = !fenced;
                return "";
            }
            if fenced {
                ""
            } else {
                l
            }
        })
        .collect();
    let prose = prose.join("\n");
    let mut out = Vec::new();
    let mut offset = 0;
    for (i, span) in prose.split('`').enumerate() {
        if i % 2 == 1 && span.starts_with("viaroad ") {
            let line = prose[..offset].matches('\n').count() + 1;
            out.push(Line {
                at: format!("{page}:{line}"),
                text: span.replace('\n', " "),
            });
        }
        offset += span.len() + 1;
    }
    out
}

#[test]
fn commands_in_the_prose_name_real_commands_and_options() {
    let mut pages = vec!["README.md".to_string(), "ARCHITECTURE.md".to_string()];
    for entry in std::fs::read_dir(repo().join("docs")).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if name.ends_with(".md") {
            pages.push(format!("docs/{name}"));
        }
    }
    let mut cache = HashMap::new();
    let mut seen = 0;
    for page in &pages {
        for line in inline_commands(page) {
            check_synopsis(&line, &mut cache);
            seen += 1;
        }
    }
    assert!(seen >= 20, "{seen} commands in the prose");
}
