//! The benchmark database in OMPL's schema, so that Planner Arena (plannerarena.org) and
//! `ompl_benchmark_statistics.py` read it.
//!
//! The tables are those `ompl_benchmark_statistics.py` creates from a benchmark log:
//! `experiments` (one per scene), `plannerConfigs` (one per method and settings), `enums`,
//! `runs` (one row per run; the script adds one column per run property, typed `REAL`,
//! `INTEGER`, `BOOLEAN` or `ENUM`), `progress` (one row per run and stage, keyed by
//! `(runid, time)`), and the views `bestPlannerConfigsPerExperiment` and `bestPlannerConfigs`.
//!
//! Run properties keep OMPL's names where the meaning carries over: `time` is the learning
//! time to the target share of the scored queries (or to the end when the run missed it),
//! `solved` whether it got there, `status` OMPL's planner status (*Exact solution* or
//! *Timeout*; *Abort* when learning stalled), `memory` the peak resident set in MiB,
//! `graph_states`/`graph_motions` the roadmap's nodes and edges, `valid_segment_fraction` the
//! share of local-method attempts that connected, `solution_length` and
//! `simplified_solution_length` the mean path length before and after shortening, and
//! `correct_solution` whether the exact oracle found every returned path free. The rest are
//! viaroad's own (oracle calls, queries solved, latencies …). `progress.time` is learning time.

use super::report::{first_stage_solving, Report, SceneReport};
use super::run::{RunRecord, RunStop};
use super::BenchError;
use crate::roadmap::LearnParams;
use rusqlite::types::Value;
use rusqlite::{params, Connection};
use std::path::Path;

/// OMPL's planner status names, in the order of `ompl::base::PlannerStatus::StatusType`
/// (OMPL 1.5), as `Benchmark::saveResultsToStream` writes the `status` enum.
pub const OMPL_STATUS: [&str; 9] = [
    "Unknown status",
    "Invalid start",
    "Invalid goal",
    "Unrecognized goal type",
    "Timeout",
    "Approximate solution",
    "Exact solution",
    "Crash",
    "Abort",
];

/// Values of the `stop` enum (why a run ended), in [`RunStop`] order.
pub const STOP_NAMES: [&str; 4] = ["target reached", "node cap", "time limit", "stalled"];

fn stop_value(s: RunStop) -> i64 {
    match s {
        RunStop::Target => 0,
        RunStop::NodeCap => 1,
        RunStop::TimeLimit => 2,
        RunStop::Stalled => 3,
    }
}

fn status_value(s: RunStop) -> i64 {
    match s {
        RunStop::Target => 6,
        RunStop::NodeCap | RunStop::TimeLimit => 4,
        RunStop::Stalled => 8,
    }
}

const SCHEMA: &str = "CREATE TABLE IF NOT EXISTS experiments
    (id INTEGER PRIMARY KEY AUTOINCREMENT, name VARCHAR(512),
    totaltime REAL, timelimit REAL, memorylimit REAL, runcount INTEGER,
    version VARCHAR(128), hostname VARCHAR(1024), cpuinfo TEXT,
    date DATETIME, seed VARCHAR(24), setup TEXT);
    CREATE TABLE IF NOT EXISTS plannerConfigs
    (id INTEGER PRIMARY KEY AUTOINCREMENT,
    name VARCHAR(512) NOT NULL, settings TEXT);
    CREATE TABLE IF NOT EXISTS enums
    (name VARCHAR(512), value INTEGER, description TEXT,
    PRIMARY KEY (name, value));
    CREATE TABLE IF NOT EXISTS runs
    (id INTEGER PRIMARY KEY AUTOINCREMENT, experimentid INTEGER, plannerid INTEGER,
    FOREIGN KEY (experimentid) REFERENCES experiments(id) ON DELETE CASCADE,
    FOREIGN KEY (plannerid) REFERENCES plannerConfigs(id) ON DELETE CASCADE);
    CREATE TABLE IF NOT EXISTS progress
    (runid INTEGER, time REAL, PRIMARY KEY (runid, time),
    FOREIGN KEY (runid) REFERENCES runs(id) ON DELETE CASCADE)";

fn real(v: f64) -> Value {
    if v.is_finite() {
        Value::Real(v)
    } else {
        Value::Null
    }
}

fn opt_real(v: Option<f64>) -> Value {
    v.map_or(Value::Null, real)
}

fn int(v: impl TryInto<i64>) -> Value {
    v.try_into().map_or(Value::Null, Value::Integer)
}

fn boolean(b: bool) -> Value {
    Value::Integer(i64::from(b))
}

/// One run property: name, SQL type, value.
type Property = (&'static str, &'static str, Value);

/// The run properties of one run; `to_solvable` is its first stage that solved the target
/// share of the solvable queries.
fn run_properties(r: &RunRecord, to_solvable: Option<(f64, usize)>) -> Vec<Property> {
    let reached = r.stop == RunStop::Target;
    vec![
        (
            "time",
            "REAL",
            real(r.time_to_target.unwrap_or(r.learn_seconds)),
        ),
        ("memory", "REAL", opt_real(r.peak_rss_mib)),
        ("status", "ENUM", Value::Integer(status_value(r.stop))),
        ("solved", "BOOLEAN", boolean(reached)),
        (
            "valid_segment_fraction",
            "REAL",
            real(r.connected as f64 / r.attempts.max(1) as f64),
        ),
        ("graph_states", "INTEGER", int(r.nodes)),
        ("graph_motions", "INTEGER", int(r.edges)),
        ("solution_length", "REAL", opt_real(r.path_length_raw)),
        (
            "simplified_solution_length",
            "REAL",
            opt_real(r.path_length),
        ),
        ("correct_solution", "BOOLEAN", boolean(r.invalid_paths == 0)),
        ("run", "INTEGER", int(r.run)),
        ("seed", "INTEGER", int(r.seed)),
        ("feedback", "BOOLEAN", boolean(r.feedback)),
        ("stop", "ENUM", Value::Integer(stop_value(r.stop))),
        (
            "nodes_at_target",
            "INTEGER",
            r.nodes_at_target.map_or(Value::Null, int),
        ),
        (
            "time_to_solvable",
            "REAL",
            opt_real(to_solvable.map(|t| t.0)),
        ),
        (
            "nodes_to_solvable",
            "INTEGER",
            to_solvable.map_or(Value::Null, |t| int(t.1)),
        ),
        ("learning_time", "REAL", real(r.learn_seconds)),
        ("components", "INTEGER", int(r.components)),
        ("segment_calls", "INTEGER", int(r.counts.segment_calls)),
        ("line_calls", "INTEGER", int(r.counts.line_calls)),
        (
            "intersect_calls",
            "INTEGER",
            int(r.counts.intersect_calls()),
        ),
        ("state_checks", "INTEGER", int(r.counts.state_checks)),
        ("pairs_tested", "INTEGER", int(r.counts.pairs_tested)),
        ("local_attempts", "INTEGER", int(r.attempts)),
        ("local_connected", "INTEGER", int(r.connected)),
        ("queries", "INTEGER", int(r.queries)),
        ("scored_queries", "INTEGER", int(r.scored)),
        ("solved_queries", "INTEGER", int(r.solved)),
        (
            "solved_share",
            "REAL",
            real(r.solved as f64 / r.scored.max(1) as f64),
        ),
        ("separate_queries", "INTEGER", int(r.separate)),
        ("separate_solved", "INTEGER", int(r.separate_solved)),
        ("invalid_paths", "INTEGER", int(r.invalid_paths)),
        ("invalid_raw_paths", "INTEGER", int(r.invalid_raw_paths)),
        ("query_time_p50", "REAL", real(r.query_p50_ms / 1e3)),
        ("query_time_p95", "REAL", real(r.query_p95_ms / 1e3)),
        ("query_time_mean", "REAL", real(r.query_mean_ms / 1e3)),
        ("roadmap_bytes", "INTEGER", int(r.roadmap_bytes)),
        ("threads", "INTEGER", int(r.threads)),
        ("wall_time", "REAL", real(r.wall_seconds)),
    ]
}

/// Progress columns after `time`.
const PROGRESS_COLUMNS: [(&str, &str); 9] = [
    ("nodes", "INTEGER"),
    ("edges", "INTEGER"),
    ("components", "INTEGER"),
    ("largest_component", "INTEGER"),
    ("intersect_calls", "INTEGER"),
    ("state_checks", "INTEGER"),
    ("pairs_tested", "INTEGER"),
    ("solved_share", "REAL"),
    ("invalid_paths", "INTEGER"),
];

/// OMPL's planner settings text: `name = value` lines, each followed by `;`, sorted by name.
fn settings(local_spec: &str, feedback: bool, sampler: &str, seeding: &str) -> String {
    let params = LearnParams {
        feedback,
        sampler: sampler.parse().unwrap_or_default(),
        ..LearnParams::default()
    };
    let mut kv: Vec<(String, String)> = vec![
        ("local_method".into(), local_spec.to_string()),
        ("seeding".into(), seeding.to_string()),
    ];
    if let Ok(serde_json::Value::Object(map)) = serde_json::to_value(&params) {
        for (k, v) in map {
            let v = match v {
                serde_json::Value::Null => "none".to_string(),
                other => other.to_string(),
            };
            kv.push((format!("learn.{k}"), v));
        }
    }
    kv.sort();
    kv.into_iter()
        .map(|(k, v)| format!("{k} = {v}\n;"))
        .collect()
}

fn columns(conn: &Connection, table: &str) -> Result<Vec<String>, rusqlite::Error> {
    let mut st = conn.prepare(&format!("PRAGMA table_info({table})"))?;
    let names = st
        .query_map([], |row| row.get::<_, String>(1))?
        .collect::<Result<Vec<_>, _>>()?;
    Ok(names)
}

fn add_columns(
    conn: &Connection,
    table: &str,
    wanted: &[(&str, &str)],
) -> Result<(), rusqlite::Error> {
    let have = columns(conn, table)?;
    for (name, ty) in wanted {
        if !have.iter().any(|h| h == name) {
            conn.execute_batch(&format!("ALTER TABLE {table} ADD {name} {ty}"))?;
        }
    }
    Ok(())
}

fn fill(conn: &Connection, report: &Report) -> Result<(), rusqlite::Error> {
    conn.execute_batch(SCHEMA)?;
    for (enum_name, values) in [("status", &OMPL_STATUS[..]), ("stop", &STOP_NAMES[..])] {
        for (i, d) in values.iter().enumerate() {
            conn.execute(
                "INSERT OR IGNORE INTO enums VALUES (?1, ?2, ?3)",
                params![enum_name, i as i64, d],
            )?;
        }
    }
    for scene in &report.scenes {
        let experiment = insert_experiment(conn, report, scene)?;
        for r in &scene.runs {
            insert_run(conn, experiment, scene, r)?;
        }
    }
    create_views(conn)
}

/// One scene as an experiment, with the setup text OMPL's Planner Arena shows; its row id.
fn insert_experiment(
    conn: &Connection,
    report: &Report,
    scene: &SceneReport,
) -> Result<i64, rusqlite::Error> {
    let plan = &report.plan;
    let stages = plan.schedule.stages();
    let i = &scene.info;
    let setup = format!(
        "viaroad bench local: local methods inside the same learner (OS94 with CHS feedback)\n\
         scene: {} ({})\nqueries: {} ({} in all, {} scored, {} apart{}, {} invalid)\n\
         solvable (solved by some run): {}\nnode stages: {:?}\ntarget share: {}\n\
         learning time limit: {}\nqueries try the local method directly first: {}\ncommand: {}\n",
        i.name,
        i.source,
        i.query_source,
        i.queries,
        i.scored.len(),
        i.separate.len(),
        i.separate_group
            .as_deref()
            .map(|g| format!(": {g}"))
            .unwrap_or_default(),
        i.invalid.len(),
        scene.solvable.len(),
        stages,
        plan.target,
        plan.time_limit
            .map_or("none".to_string(), |t| format!("{t} s")),
        plan.direct,
        report.command
    );
    let total: f64 = scene.runs.iter().map(|r| r.wall_seconds).sum();
    conn.execute(
        "INSERT INTO experiments (name, totaltime, timelimit, memorylimit, runcount, version, \
         hostname, cpuinfo, date, seed, setup) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11)",
        params![
            i.name,
            total,
            plan.time_limit.unwrap_or(0.0),
            0.0,
            i64::from(plan.runs),
            format!("viaroad {}", report.version),
            report.host,
            report.cpu,
            report.date,
            plan.seed.to_string(),
            setup
        ],
    )?;
    Ok(conn.last_insert_rowid())
}

/// One run of a scene's experiment: its planner configuration (shared by equal settings), its
/// row with a column per property (added as needed) and its progress rows, one per stage.
fn insert_run(
    conn: &Connection,
    experiment: i64,
    scene: &SceneReport,
    r: &RunRecord,
) -> Result<(), rusqlite::Error> {
    let s = settings(&r.local_spec, r.feedback, &r.sampler, &r.seeding);
    let existing: Option<i64> = conn
        .query_row(
            "SELECT id FROM plannerConfigs WHERE (name = ?1 AND settings = ?2)",
            params![r.method, s],
            |row| row.get(0),
        )
        .ok();
    let planner = match existing {
        Some(id) => id,
        None => {
            conn.execute(
                "INSERT INTO plannerConfigs VALUES (NULL, ?1, ?2)",
                params![r.method, s],
            )?;
            conn.last_insert_rowid()
        }
    };
    let to_solvable = first_stage_solving(r, &scene.solvable, scene.solvable_needed)
        .map(|st| (st.learn_seconds, st.nodes));
    let props = run_properties(r, to_solvable);
    let wanted: Vec<(&str, &str)> = props.iter().map(|(n, t, _)| (*n, *t)).collect();
    add_columns(conn, "runs", &wanted)?;
    let names: Vec<&str> = props.iter().map(|p| p.0).collect();
    let sql = format!(
        "INSERT INTO runs (experimentid, plannerid, {}) VALUES (?1, ?2, {})",
        names.join(", "),
        (3..names.len() + 3)
            .map(|k| format!("?{k}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let mut values = vec![Value::Integer(experiment), Value::Integer(planner)];
    values.extend(props.into_iter().map(|p| p.2));
    conn.execute(&sql, rusqlite::params_from_iter(values))?;
    let run_id = conn.last_insert_rowid();
    add_columns(conn, "progress", &PROGRESS_COLUMNS)?;
    for st in &r.stages {
        conn.execute(
            "INSERT OR IGNORE INTO progress (runid, time, nodes, edges, components, \
             largest_component, intersect_calls, state_checks, pairs_tested, solved_share, \
             invalid_paths) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11)",
            rusqlite::params_from_iter([
                Value::Integer(run_id),
                real(st.learn_seconds),
                int(st.nodes),
                int(st.edges),
                int(st.components),
                int(st.largest_component),
                int(st.counts.intersect_calls()),
                int(st.counts.state_checks),
                int(st.counts.pairs_tested),
                real(st.solved as f64 / r.scored.max(1) as f64),
                int(st.invalid_paths),
            ]),
        )?;
    }
    Ok(())
}

/// The views `ompl_benchmark_statistics.py` computes (no simplification time here), which
/// Planner Arena reads.
fn create_views(conn: &Connection) -> Result<(), rusqlite::Error> {
    let s0 = "SELECT plannerid, plannerConfigs.name AS plannerName, experimentid, solved, \
              time AS total_time FROM plannerConfigs INNER JOIN experiments INNER JOIN runs \
              ON plannerConfigs.id=runs.plannerid AND experiments.id=runs.experimentid";
    let s1 = format!(
        "SELECT plannerid, plannerName, experimentid, AVG(solved) AS avg_solved, \
         AVG(total_time) AS avg_total_time FROM ({s0}) GROUP BY plannerid, experimentid"
    );
    let s2 = format!(
        "SELECT plannerid, experimentid, MIN(avg_solved) AS avg_solved, avg_total_time \
         FROM ({s1}) GROUP BY plannerName, experimentid ORDER BY avg_solved DESC, avg_total_time ASC"
    );
    conn.execute_batch("DROP VIEW IF EXISTS bestPlannerConfigsPerExperiment")?;
    conn.execute_batch(&format!(
        "CREATE VIEW IF NOT EXISTS bestPlannerConfigsPerExperiment AS {s2}"
    ))?;
    let s1 = format!(
        "SELECT plannerid, plannerName, AVG(solved) AS avg_solved, \
         AVG(total_time) AS avg_total_time FROM ({s0}) GROUP BY plannerid"
    );
    let s2 = format!(
        "SELECT plannerid, MIN(avg_solved) AS avg_solved, avg_total_time FROM ({s1}) \
         GROUP BY plannerName ORDER BY avg_solved DESC, avg_total_time ASC"
    );
    conn.execute_batch("DROP VIEW IF EXISTS bestPlannerConfigs")?;
    conn.execute_batch(&format!(
        "CREATE VIEW IF NOT EXISTS bestPlannerConfigs AS {s2}"
    ))?;
    Ok(())
}

/// Writes `report` as a new database at `path` (an existing file is replaced, as
/// `ompl_benchmark_statistics.py` does without `--append`). The database is written to a
/// temporary file beside it and renamed, so a failure leaves any previous one intact.
pub fn write_database(path: &Path, report: &Report) -> Result<(), BenchError> {
    // a special file (or a directory) at `path` is refused, not renamed over
    let path = &crate::safe_file::resolve_target(path)?;
    let tmp = path.with_extension("db.partial");
    let io = |source| BenchError::Io {
        path: tmp.clone(),
        source,
    };
    if tmp.exists() {
        std::fs::remove_file(&tmp).map_err(io)?;
    }
    {
        let mut conn = Connection::open(&tmp)?;
        conn.execute_batch("PRAGMA foreign_keys = ON")?;
        let tx = conn.transaction()?;
        fill(&tx, report)?;
        tx.commit()?;
    }
    std::fs::rename(&tmp, path).map_err(|source| BenchError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_look_like_ompl_logs() {
        let s = settings("straight", false, "uniform", "cones");
        assert!(s.starts_with("learn."));
        assert!(s.contains("learn.feedback = false\n;"));
        assert!(s.contains("local_method = straight\n;"));
        assert!(s.contains("seeding = cones\n;"));
        assert!(s.ends_with("\n;"));
    }
}
