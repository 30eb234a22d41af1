//! `viaroad query`: answer queries against a saved roadmap.

use super::config_arg::parse_config;
use anyhow::Context;
use clap::Args;
use serde_json::json;
use std::io::Write;
use std::path::PathBuf;
use std::sync::Mutex;
use std::time::{Duration, Instant};
use viaroad::bench::validity::Checker;
use viaroad::deadline::Deadline;
use viaroad::roadmap::query::keep::{answer_keeping, KeptAnswers};
use viaroad::roadmap::tree::TreeParams;
use viaroad::roadmap::{BatchAnswer, QueryOptions, QueryPlanner, Roadmap};
use viaroad::scene::{ompl_cfg, Scene};
use viaroad::space::Config;

/// Arguments of `query`.
#[derive(Args)]
pub struct QueryArgs {
    /// The roadmap file.
    pub roadmap: PathBuf,
    /// The scene it was learnt for (checked against the roadmap's fingerprint).
    #[arg(long)]
    pub scene: PathBuf,
    /// Start configuration (numbers separated by commas or spaces).
    #[arg(
        long,
        allow_hyphen_values = true,
        requires = "to",
        conflicts_with = "queries"
    )]
    pub from: Option<String>,
    /// Goal configuration.
    #[arg(long, allow_hyphen_values = true, requires = "from")]
    pub to: Option<String>,
    /// A file with one query per line: start then goal coordinates, whitespace separated.
    /// Without it and without `--from`/`--to`, the scene's own queries are answered.
    #[arg(long)]
    pub queries: Option<PathBuf>,
    /// One JSON object per query on stdout.
    #[arg(long)]
    pub json: bool,
    /// Write each solved query's path as an OMPL state file (one state per line); several
    /// queries get `-1`, `-2`, … before the extension.
    #[arg(long, value_name = "FILE")]
    pub path_out: Option<PathBuf>,
    /// Path shortening (CHS A.1): `fast` drops corners greedily on paths of more than 32
    /// corners before the visibility graph, `exact` builds the visibility graph over every
    /// corner (shortest, up to m²/2 checks), `greedy` drops corners greedily pass after pass
    /// and builds no visibility graph, `off` returns the roadmap path as found.
    #[arg(long, value_enum, default_value_t = Shortening::Fast, help_heading = "Tuning")]
    pub shorten: Shortening,
    /// Call budget of the quick via-point try from start to goal before the roadmap
    /// (0: only the direct path is checked).
    #[arg(long, value_name = "N", help_heading = "Tuning")]
    pub direct_calls: Option<u64>,
    /// Via-point roadmaps: nearest nodes of each end first tried with the direct path alone,
    /// before the via-point planner searches from the nearest (0: the planner from the first
    /// on). Default: all the attach candidates (30).
    #[arg(long, value_name = "N", help_heading = "Tuning")]
    pub attach_direct: Option<usize>,
    /// Landmarks guiding A* (0: the space's distance alone as the heuristic). Default: 8 for a
    /// batch of queries, 0 for a single one (they cost one graph search each, once).
    #[arg(long, value_name = "N", help_heading = "Tuning")]
    pub landmarks: Option<usize>,
    /// Seconds each query may take (checked before every oracle call). Where the roadmap
    /// cannot join start and goal, the query grows a copy of it around them (or trees out of
    /// it, `--trees`) for the rest of this time.
    #[arg(long, value_name = "SECONDS", default_value_t = QueryOptions::DEFAULT_TIME.as_secs_f64())]
    pub time: f64,
    /// Do not grow the roadmap for a query it cannot answer: try a deeper local search
    /// instead (and give up sooner).
    #[arg(long, help_heading = "Tuning")]
    pub no_grow: bool,
    /// Where the roadmap cannot join start and goal, grow two trees out of it for the rest of
    /// the time instead of a copy of it: each end that a free direct path attaches to one of
    /// its nearest nodes brings that node's component along as its tree, and the other end's
    /// tree need only reach the roadmap (whole single-joint stairs, first-hit calls, as
    /// `bench mbm --planner tree`). `auto` (default): on for arms, whose goals in a box or a
    /// cage a grown copy does not reach; `on`; `off`.
    #[arg(long, value_name = "MODE", value_enum, default_value_t = Trees::Auto, help_heading = "Tuning")]
    pub trees: Trees,
    /// Where trees grow (`--trees`): ask the roadmap alone for MS milliseconds, then ask it
    /// again beside the trees on the thread pool, the first to answer stopping the other,
    /// instead of growing the trees only after attaching failed; `off`: in turn; `auto`
    /// (default): 2 ms for arms, in turn for every other space (`QueryOptions::race`).
    #[arg(
        long,
        value_name = "MS|off|auto",
        default_value = "auto",
        help_heading = "Tuning"
    )]
    pub race: HeadStart,
    /// Single-joint staircases only: no straight motions of several joints at once (by
    /// default an arm's query tries them where conservative advancement proves them free —
    /// start to goal, attaching, the trees' extends, shortening, as
    /// `QueryOptions::straight_shortcuts`; the Panda's workcells: half the path length).
    #[arg(long, help_heading = "Tuning")]
    pub no_straight: bool,
    /// Feed every path found back into the roadmap before the next query (its corners become
    /// nodes, its single-group pieces edges: `Roadmap::with_path`), answering the queries one
    /// after another in their order, and save the grown roadmap to FILE (it may be the roadmap
    /// file itself: written beside it, then renamed). A fixed workcell's next request from
    /// the same pose, or into the same pocket, attaches to what the earlier answers found.
    /// Ctrl-C stops the batch and saves what was kept so far.
    #[arg(long, value_name = "FILE")]
    pub keep_answers: Option<PathBuf>,
    /// With `--keep-answers`: keep the trees that found an answer too, not only its path
    /// (`Roadmap::with_kept`: every extend's end a node, joined to the node it grew from), so
    /// that the next goal in the same pocket (a cage, a box) attaches to them directly.
    #[arg(long, requires = "keep_answers", help_heading = "Tuning")]
    pub keep_trees: bool,
    /// Re-check every answer's path (the shortened one it returns) with the scene's
    /// independent checker, outside the query's
    /// time (the one `bench validity` uses: segment–disc distances, exact polygon sweeps,
    /// parry by conservative advancement, the arm checker at 1/10 of OMPL's resolution): each
    /// answer says `certified` (JSON: `"certified": true|false`, and `"check_error"`), and
    /// the command fails if any path is not.
    #[arg(long)]
    pub check: bool,
}

/// How `query` shortens paths.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Shortening {
    /// Greedy corner dropping first on long paths, then the visibility graph.
    Fast,
    /// The visibility graph over every corner.
    Exact,
    /// Greedy corner dropping alone, pass after pass (at most two checks per corner and
    /// pass, a few per run of corners dropped): for a workcell's roadmap whose answers run
    /// along kept, already shortened ones.
    Greedy,
    /// No shortening.
    Off,
}

/// Percentile `p` (0–1) of sorted values.
pub fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

/// Prints answers as they come, one line (or JSON object with its `query` number) each, and
/// writes their paths; then a summary. Shared by the worker threads of a batch.
struct Printer {
    json: bool,
    total: usize,
    /// The independent checker every solved path is re-checked by (`--check`).
    checker: Option<Checker>,
    state: Mutex<Printed>,
}

#[derive(Default)]
struct Printed {
    ms: Vec<f64>,
    solved: usize,
    /// Where solved paths go, as they come.
    path_out: Option<super::path_out::PathOut>,
    /// The first failure to print or write, reported when the batch ends.
    failure: Option<anyhow::Error>,
    /// Solved paths the checker did not certify.
    uncertified: usize,
}

impl Printer {
    fn answer(&self, i: usize, a: &BatchAnswer) {
        // checked before the lock: checks of a batch's answers run in parallel
        let check = match (&self.checker, &a.result) {
            (Some(c), Ok(r)) if r.is_solved() => Some(c.check_path(&r.path)),
            _ => None,
        };
        let mut st = self.state.lock().unwrap_or_else(|p| p.into_inner());
        if st.failure.is_some() {
            return;
        }
        if let (1, Err(e)) = (self.total, &a.result) {
            // a single query's invalid input is the command's error, not an answer
            st.failure = Some(anyhow::anyhow!("{e}"));
            return;
        }
        let t = a.elapsed.as_secs_f64() * 1e3;
        st.ms.push(t);
        if let Ok(r) = &a.result {
            st.solved += usize::from(r.is_solved());
        }
        st.uncertified += usize::from(matches!(check, Some(Err(_))));
        let line = answer_line(i, a, t, self.json, check.as_ref());
        let mut out = std::io::stdout().lock();
        // a closed pipe ends the batch quietly, like any Unix tool
        if writeln!(out, "{line}").and_then(|_| out.flush()).is_err() {
            std::process::exit(0);
        }
        if let (Some(out), Ok(r)) = (&mut st.path_out, &a.result) {
            if let Err(e) = out.write(i, &r.path) {
                st.failure = Some(e);
            }
        }
    }
}

/// The scene's independent checker for `--check` (`query`, `serve`), or `None` without it.
pub(super) fn independent_checker(
    scene: &viaroad::scene::Scene,
    check: bool,
) -> anyhow::Result<Option<Checker>> {
    if !check {
        return Ok(None);
    }
    Checker::for_scene(scene)
        .map(Some)
        .map_err(|e| anyhow::anyhow!("--check: no independent checker for this scene: {e}"))
}

/// One answer as printed: a JSON object or a line of text; `t` its time in ms.
fn answer_line(
    i: usize,
    a: &BatchAnswer,
    t: f64,
    json_lines: bool,
    check: Option<&Result<(), String>>,
) -> String {
    match &a.result {
        Ok(r) if json_lines => {
            let mut v = json!({
                "query": i + 1,
                "solved": r.is_solved(),
                "path": r.raw_path,
                "shortened": r.path,
                "calls": r.counts.intersect_calls(),
                "depth": r.depth,
                "query_ms": t,
                "shorten_ms": r.shorten_s * 1e3,
                "outcome": r.outcome,
                "length": r.length,
                "raw_length": r.raw_length,
                "grown_nodes": r.grown_nodes,
            });
            if let Some(c) = check {
                v["certified"] = json!(c.is_ok());
                if let Err(e) = c {
                    v["check_error"] = json!(e);
                }
            }
            v.to_string()
        }
        Ok(r) if r.is_solved() => format!(
            "query {}: solved ({:?}{}), length {:.4} (raw {:.4}), {} corners, {} intersect calls, {:.3} ms ({:.3} shortening){}",
            i + 1,
            r.outcome,
            if r.grown_nodes > 0 {
                format!(": {} nodes grown", r.grown_nodes)
            } else {
                String::new()
            },
            r.length,
            r.raw_length,
            r.path.len(),
            r.counts.intersect_calls(),
            t,
            r.shorten_s * 1e3,
            match check {
                None => String::new(),
                Some(Ok(())) => ", certified".into(),
                Some(Err(e)) => format!(", NOT CERTIFIED: {e}"),
            }
        ),
        Ok(r) => format!(
            "query {}: not solved ({:?}{}), {:.3} ms",
            i + 1,
            r.outcome,
            if r.grown_nodes > 0 {
                format!(", {} nodes grown", r.grown_nodes)
            } else {
                String::new()
            },
            t
        ),
        Err(e) if json_lines => {
            json!({ "query": i + 1, "solved": false, "error": e.to_string(), "query_ms": t })
                .to_string()
        }
        Err(e) => format!("query {}: error: {e}", i + 1),
    }
}

/// The roadmap's head start before it races the trees (`query --race MS|off|auto`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HeadStart {
    /// [`QueryOptions::DEFAULT_HEAD_START`] for arms, in turn otherwise.
    Auto,
    /// In turn.
    Off,
    /// This head start.
    After(Duration),
}

impl HeadStart {
    /// The head start in `space` (`QueryOptions::race`).
    pub fn race(self, space: &viaroad::space::Space) -> Option<Duration> {
        match self {
            HeadStart::Auto => QueryOptions::default().with_arm_trees(space).race,
            HeadStart::Off => None,
            HeadStart::After(d) => Some(d),
        }
    }
}

impl std::str::FromStr for HeadStart {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "auto" => return Ok(HeadStart::Auto),
            "off" => return Ok(HeadStart::Off),
            _ => {}
        }
        match s.parse::<f64>() {
            Ok(ms) if ms.is_finite() && (0.0..=1e6).contains(&ms) => {
                Ok(HeadStart::After(Duration::from_secs_f64(ms / 1e3)))
            }
            _ => Err(format!(
                "{s:?}: expected milliseconds from 0 to 1e6, `off` or `auto`"
            )),
        }
    }
}

/// Whether a query grows trees out of the roadmap (`query --trees`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Trees {
    /// On for arms (joint spaces), off for every other space.
    Auto,
    /// Always.
    On,
    /// Never: the roadmap grows a copy of itself (unless `--no-grow`).
    Off,
}

impl Trees {
    /// The trees a query grows out of the roadmap in `space` (`QueryOptions::trees`), if
    /// any: the trees' defaults (whole stairs, the smaller tree extending; as `bench mbm
    /// --planner tree`), first-hit prefixes for arms.
    pub fn params(self, space: &viaroad::space::Space) -> Option<TreeParams> {
        let joints = space.is_joints();
        let on = match self {
            Trees::Auto => joints,
            Trees::On => true,
            Trees::Off => false,
        };
        on.then(|| TreeParams::for_space(space))
    }
}

/// Runs `query`.
pub fn run(a: QueryArgs) -> anyhow::Result<()> {
    let t = Instant::now();
    let scene = Scene::load(&a.scene)?;
    let scene_ms = t.elapsed().as_secs_f64() * 1e3;
    let t = Instant::now();
    let roadmap = Roadmap::load(&a.roadmap, scene.fingerprint())?;
    let load_ms = t.elapsed().as_secs_f64() * 1e3;
    let queries = query_pairs(&a, &scene)?;
    let time = Some(super::limits::parse_seconds("--time", a.time)?);
    let oracle = scene.oracle();
    let planner = QueryPlanner::new(&roadmap, oracle.as_ref()).context("roadmap")?;
    let options = query_options(&a, planner.options().clone(), time, &scene, queries.len());
    let planner = planner.with_options(options.clone());
    if let Some(out) = &a.keep_answers {
        // a target that cannot be saved to is refused before the queries (and before any
        // status line), not after them
        super::output::check_writable(out)?;
    }
    let path_out = match &a.path_out {
        Some(base) => Some(super::path_out::PathOut::new(base, queries.len())?),
        None => None,
    };
    // a status line must not precede an `error:` line: a single query's invalid
    // input is the command's error, so its status comes after the answer
    let loaded = || {
        eprintln!(
            "loaded {} ({} nodes, {} edges) in {load_ms:.2} ms (the scene in {scene_ms:.1} ms)",
            a.roadmap.display(),
            roadmap.node_count(),
            roadmap.edge_count()
        )
    };
    if !a.json && queries.len() > 1 {
        loaded();
    }
    let checker = independent_checker(&scene, a.check)?;
    let printer = Printer {
        json: a.json,
        total: queries.len(),
        checker,
        state: Mutex::new(Printed {
            path_out,
            ..Printed::default()
        }),
    };
    let deadline = super::interrupt::on_ctrl_c(Deadline::none());
    match &a.keep_answers {
        None => planner.query_each(&queries, &deadline, &|i, answer| printer.answer(i, &answer)),
        Some(out) => {
            drop(planner);
            let KeptAnswers {
                roadmap: grown,
                kept,
            } = answer_keeping(
                roadmap.clone(),
                oracle.as_ref(),
                &options,
                &queries,
                a.keep_trees,
                &deadline,
                &mut |i, answer| {
                    printer.answer(i, answer);
                    true
                },
            )?;
            super::output::create_parent(out)?;
            grown
                .save(out)
                .context("saving the roadmap with its answers kept")?;
            eprintln!(
                "kept {kept} answers: {} nodes, {} edges ({} and {} before), saved to {}",
                grown.node_count(),
                grown.edge_count(),
                roadmap.node_count(),
                roadmap.edge_count(),
                out.display()
            );
        }
    }
    let st = printer
        .state
        .into_inner()
        .unwrap_or_else(|p| p.into_inner());
    let one = queries.len() == 1;
    summarise(&a, st, queries.len(), || {
        if one {
            loaded()
        }
    })
}

/// The start–goal pairs to answer: `--from`/`--to`, a `--queries` file, or else the scene's
/// own queries (an OMPL.app `.cfg` names one), as `solve` answers them.
fn query_pairs(a: &QueryArgs, scene: &Scene) -> anyhow::Result<Vec<(Config, Config)>> {
    let queries: Vec<(Config, Config)> = match (&a.from, &a.to, &a.queries) {
        (Some(f), Some(t), None) => vec![(parse_config("--from", f)?, parse_config("--to", t)?)],
        (None, None, Some(file)) => ompl_cfg::read_query_pairs(file, &scene.space)?
            .into_iter()
            .map(|q| (q.start, q.goal))
            .collect(),
        // neither: the scene's own queries (an OMPL.app `.cfg` names one), as `solve` answers them
        (None, None, None) => {
            let own = scene.checked_queries()?;
            if own.is_empty() {
                anyhow::bail!(
                    "{} names no query: give --from and --to, or --queries FILE",
                    a.scene.display()
                );
            }
            own.into_iter().map(|q| (q.start, q.goal)).collect()
        }
        _ => anyhow::bail!("give either --from and --to, or --queries FILE"),
    };
    if let (true, Some(file)) = (queries.is_empty(), &a.queries) {
        anyhow::bail!("{}: no queries in the file", file.display());
    }
    Ok(queries)
}

/// The planner's options as the arguments set them, from the roadmap's `defaults`, for a
/// batch of `count` queries of at most `time` each.
fn query_options(
    a: &QueryArgs,
    mut defaults: QueryOptions,
    time: Option<Duration>,
    scene: &Scene,
    count: usize,
) -> QueryOptions {
    defaults.time = time;
    defaults.grow = !a.no_grow;
    defaults.trees = a.trees.params(&scene.space);
    defaults.race = a.race.race(&scene.space);
    defaults.straight_shortcuts = !a.no_straight;
    defaults.return_trees = a.keep_trees;
    if let Some(n) = a.direct_calls {
        defaults.direct_calls = n;
    }
    if let Some(n) = a.attach_direct {
        defaults.attach_direct_candidates = n;
    }
    match a.landmarks {
        Some(n) => defaults.landmarks = n,
        // landmarks cost a Dijkstra each, repaid over a batch, not by one query (nor by a
        // roadmap that changes after every answer kept)
        None if count == 1 || a.keep_answers.is_some() => defaults.landmarks = 0,
        None => {}
    }
    match a.shorten {
        Shortening::Fast => defaults,
        Shortening::Exact => QueryOptions {
            exact_shortening_limit: usize::MAX,
            ..defaults
        },
        Shortening::Greedy => QueryOptions {
            exact_shortening_limit: 0,
            ..defaults
        },
        Shortening::Off => QueryOptions {
            shorten: false,
            ..defaults
        },
    }
}

/// After the batch: the first failure to print or write, else the status line (after
/// `loaded` for a single query), the path files closed, and an error if a solved path was
/// not certified.
fn summarise(
    a: &QueryArgs,
    mut st: Printed,
    count: usize,
    loaded: impl Fn(),
) -> anyhow::Result<()> {
    if let Some(e) = st.failure.take() {
        return Err(e);
    }
    st.ms.sort_by(f64::total_cmp);
    if !a.json {
        loaded();
        println!(
            "{}/{} solved; latency p50 {:.3} ms, p95 {:.3} ms",
            st.solved,
            count,
            percentile(&st.ms, 0.5),
            percentile(&st.ms, 0.95)
        );
    }
    if let Some(out) = st.path_out {
        out.finish();
    }
    if st.uncertified > 0 {
        anyhow::bail!(
            "{} of {} solved paths not certified by the independent checker",
            st.uncertified,
            st.solved
        );
    }
    Ok(())
}
