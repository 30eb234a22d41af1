//! `viaroad serve`: load a roadmap once and answer queries as JSON lines, on
//! stdin/stdout or on a local TCP port, several clients at once, queries answered in parallel.
//!
//! One request per line: `{"id": 7, "start": [...], "goal": [...], "shorten": "fast"}`
//! (`shorten` and `time` optional), `{"cmd": "info"}` or `{"cmd": "shutdown"}`. One reply per
//! line, in the order answers are ready (not the order asked: `id` ties them together): the
//! fields of `viaroad query --json` with `id` in place of `query`. A line that cannot be read
//! as a request gets `{"id": …, "error": "…"}` and the server goes on. `shutdown` stops
//! reading, answers every query already read, and then replies to the `shutdown` last, so a
//! client that sees that reply has seen every answer. End of input on stdin does the same.
//!
//! Over TCP, at most `--max-clients` clients are connected at once, and a client that sends
//! no line for `--idle-timeout` while none of its queries is in flight is told so and
//! disconnected. When every place is taken, a new client takes the place of the one idle
//! longest (idle for a second at least), so that a `shutdown` still gets through a server
//! held full by clients that connected and went quiet.
//!
//! Queries never change the roadmap (see [`viaroad::roadmap::query`]), so answers do not
//! depend on which client asked first or how many threads answer.

use super::query::Shortening;
use anyhow::Context;
use clap::Args;
use serde::Deserialize;
use serde_json::{json, Map, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::{Shutdown, SocketAddr, TcpListener, TcpStream};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{channel, sync_channel, Receiver, RecvTimeoutError, SyncSender};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};
use viaroad::bench::validity::Checker;
use viaroad::deadline::Deadline;
use viaroad::limits::{duration_from_secs, MAX_SERVE_CLIENTS};
use viaroad::roadmap::{QueryOptions, QueryPlanner, QueryResult, Roadmap};
use viaroad::scene::Scene;

/// Arguments of `serve`.
#[derive(Args)]
pub struct ServeArgs {
    /// The roadmap file.
    pub roadmap: PathBuf,
    /// The scene it was learnt for (checked against the roadmap's fingerprint).
    #[arg(long)]
    pub scene: PathBuf,
    /// Listen on this TCP address (e.g. `127.0.0.1:7878`; port 0 picks a free port, printed
    /// on stderr) instead of stdin/stdout. No authentication: keep it on the loopback. Serves
    /// up to `--max-clients` clients at once and disconnects idle ones (`--idle-timeout`).
    #[arg(long, value_name = "ADDR")]
    pub listen: Option<SocketAddr>,
    /// With `--listen`: a client that has sent no line for this many seconds and waits for no
    /// answer is sent one `error` line and disconnected, freeing its place (default: 60). An
    /// empty line keeps a client connected.
    #[arg(long, value_name = "SECONDS", help_heading = "Tuning")]
    pub idle_timeout: Option<f64>,
    /// With `--listen`: most clients connected at once (default and at most: 256). When every
    /// place is taken, a new client takes the place of the one idle longest, if that one has
    /// been idle for a second or more (it is sent one `error` line and disconnected);
    /// otherwise the new client is told the server is full and disconnected.
    #[arg(long, value_name = "N", help_heading = "Tuning")]
    pub max_clients: Option<usize>,
    /// Queries answered at once (default: the machine's cores).
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Seconds each query may take at most (a request's `time` can only shorten it); where the
    /// roadmap cannot join start and goal, the query grows a copy of it (or trees out of it,
    /// `--trees`) for the rest of it.
    #[arg(long, value_name = "SECONDS", default_value_t = QueryOptions::DEFAULT_TIME.as_secs_f64())]
    pub time: f64,
    /// Do not grow the roadmap for a query it cannot answer (a deeper local search instead).
    #[arg(long, help_heading = "Tuning")]
    pub no_grow: bool,
    /// Where the roadmap cannot join start and goal, grow two trees out of it instead of a
    /// copy of it (as `query --trees`): `auto` (default: on for arms), `on`, `off`.
    #[arg(long, value_name = "MODE", value_enum, default_value_t = super::query::Trees::Auto, help_heading = "Tuning")]
    pub trees: super::query::Trees,
    /// Where trees grow: the roadmap's head start before it races them (as `query --race`);
    /// `off`: in turn; `auto` (default): 2 ms for arms, in turn otherwise.
    #[arg(
        long,
        value_name = "MS|off|auto",
        default_value = "auto",
        help_heading = "Tuning"
    )]
    pub race: super::query::HeadStart,
    /// Single-joint staircases only: no straight motions of several joints at once (by
    /// default an arm's query tries them where conservative advancement proves them free, as
    /// `query --no-straight`).
    #[arg(long, help_heading = "Tuning")]
    pub no_straight: bool,
    /// Re-check every solved answer's path (the shortened one it returns) with the scene's
    /// independent checker, as `query --check` does, outside the query's time (`query_ms`):
    /// each reply says `"certified": true|false` (and `"check_error"`).
    #[arg(long)]
    pub check: bool,
}

/// The longest request line read (bytes): a start and a goal of any shipped robot fit many
/// times over; a longer line is answered with an error and skipped, not buffered.
pub const MAX_LINE: usize = 1 << 20;

/// How long a TCP client may stay idle unless `--idle-timeout` says otherwise: far longer
/// than any pause of a client at work, short enough that clients gone quiet free their places.
pub const DEFAULT_IDLE_TIMEOUT: Duration = Duration::from_secs(60);

/// A client idle this long (or `--idle-timeout`, if shorter) gives its place to a new client
/// when every place is taken: a client between two of its own requests keeps it.
const EVICTABLE_AFTER: Duration = Duration::from_secs(1);

/// How long the server tries to tell a disconnected client why: one that reads nothing must
/// not hold its thread.
const FAREWELL_WRITE: Duration = Duration::from_secs(1);

/// Queries read but not yet answered, per server: readers wait beyond this (back-pressure).
const QUEUE: usize = 1024;

/// Where the replies of one client go; a write failure (a client gone) is ignored, as its
/// answers have nobody to read them.
trait Sink: Send + Sync {
    fn send(&self, line: &str);
}

struct StdoutSink;

impl Sink for StdoutSink {
    fn send(&self, line: &str) {
        let mut out = std::io::stdout().lock();
        let _ = writeln!(out, "{line}").and_then(|_| out.flush());
    }
}

struct TcpSink(Mutex<TcpStream>);

impl Sink for TcpSink {
    fn send(&self, line: &str) {
        let mut s = self.0.lock().unwrap_or_else(|p| p.into_inner());
        let mut bytes = Vec::with_capacity(line.len() + 1);
        bytes.extend_from_slice(line.as_bytes());
        bytes.push(b'\n');
        let _ = s.write_all(&bytes).and_then(|_| s.flush());
    }
}

/// A query read, waiting for a worker.
struct Job {
    id: Value,
    start: Vec<f64>,
    goal: Vec<f64>,
    shorten: usize,
    time: Option<Duration>,
    sink: Arc<dyn Sink>,
    /// The TCP client that asked (none on stdin), told when its answer is sent.
    client: Option<Arc<Client>>,
}

/// Why the server disconnected a TCP client.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Eviction {
    /// Idle for `--idle-timeout`.
    Idle,
    /// Idle longest when every place was taken and a new client came.
    Full,
}

/// What the server knows of one TCP client's activity.
#[derive(Clone, Copy, Debug)]
struct Activity {
    /// Its last line read or answer sent.
    last: Instant,
    /// Its queries read and not answered yet.
    pending: usize,
    /// Set once, when the server disconnects it: no line of it is served afterwards.
    evicted: Option<Eviction>,
}

impl Activity {
    /// How long it has been idle at `now` (nothing of it in flight), if it is.
    fn idle_for(&self, now: Instant) -> Option<Duration> {
        (self.pending == 0 && self.evicted.is_none())
            .then(|| now.saturating_duration_since(self.last))
    }
}

/// Which client gives its place to a new one when every place is taken: the one idle longest
/// (an index into `clients`), if it has been idle for `at_least`.
fn longest_idle(
    clients: impl IntoIterator<Item = Activity>,
    now: Instant,
    at_least: Duration,
) -> Option<usize> {
    clients
        .into_iter()
        .enumerate()
        .filter_map(|(i, a)| a.idle_for(now).map(|d| (d, i)))
        .filter(|(d, _)| *d >= at_least)
        .max_by_key(|(d, _)| *d)
        .map(|(_, i)| i)
}

/// A mutex's value, even if a thread panicked while holding it.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

/// One TCP client as the server tracks it.
struct Client {
    activity: Mutex<Activity>,
    /// Its stream, to end its reader from another thread.
    stream: TcpStream,
}

impl Client {
    fn new(stream: TcpStream) -> Client {
        Client {
            activity: Mutex::new(Activity {
                last: Instant::now(),
                pending: 0,
                evicted: None,
            }),
            stream,
        }
    }

    fn activity(&self) -> Activity {
        *lock(&self.activity)
    }

    /// Disconnects it (ends its reader, which then says why) if it has been idle for
    /// `at_least` at `now`; whether it did. Checked and marked at once, so a client is never
    /// disconnected with a query in flight.
    fn evict_if_idle(&self, now: Instant, at_least: Duration, why: Eviction) -> bool {
        let mut a = lock(&self.activity);
        if a.idle_for(now).is_none_or(|d| d < at_least) {
            return false;
        }
        a.evicted = Some(why);
        drop(a);
        let _ = self.stream.shutdown(Shutdown::Read);
        true
    }

    /// A line of it read (a query if `query`): false if it was disconnected meanwhile, and
    /// the line is not served.
    fn line_read(&self, query: bool) -> bool {
        let mut a = lock(&self.activity);
        if a.evicted.is_some() {
            return false;
        }
        a.last = Instant::now();
        a.pending += usize::from(query);
        true
    }

    /// One of its queries answered.
    fn answered(&self) {
        let mut a = lock(&self.activity);
        a.pending = a.pending.saturating_sub(1);
        a.last = Instant::now();
    }
}

/// A query request as sent (unknown fields are refused: a typo must not be silently ignored).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct QueryRequest {
    #[allow(dead_code)]
    id: Option<Value>,
    start: Vec<f64>,
    goal: Vec<f64>,
    shorten: Option<String>,
    time: Option<f64>,
}

/// A command request as sent.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CommandRequest {
    #[allow(dead_code)]
    id: Option<Value>,
    cmd: String,
}

/// What one line asks.
enum Request {
    Query(Job),
    Info(Value),
    Shutdown(Value),
}

/// The error reply to a line that is not a request.
fn error_reply(id: &Value, message: &str) -> String {
    json!({ "id": id, "error": message }).to_string()
}

/// The reply to a query: the fields of `viaroad query --json`, with `id` for `query`; with
/// `check` (`--check`), whether the independent checker certified the path.
pub fn answer_reply(
    id: &Value,
    result: &Result<QueryResult, String>,
    ms: f64,
    check: Option<&Result<(), String>>,
) -> String {
    match result {
        Ok(r) => {
            let mut v = json!({
            "id": id,
            "solved": r.is_solved(),
            "path": r.raw_path,
            "shortened": r.path,
            "calls": r.counts.intersect_calls(),
            "depth": r.depth,
            "query_ms": ms,
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
        Err(e) => json!({ "id": id, "solved": false, "error": e, "query_ms": ms }).to_string(),
    }
}

/// The roadmap, its planners (one per shortening) and the server's state, shared by every
/// reader and worker.
struct Server<'a> {
    /// Fast, exact, off (the order of [`SHORTENINGS`]).
    planners: Vec<QueryPlanner<'a>>,
    info: Value,
    /// Set by `shutdown`: readers stop reading.
    stop: AtomicBool,
    answered: AtomicU64,
    errors: AtomicU64,
    /// Where the `shutdown` reply goes once every query read is answered.
    shutdown_reply: Mutex<Option<(Value, Arc<dyn Sink>)>>,
    /// The independent checker of `--check`.
    checker: Option<Checker>,
}

/// The shortenings a request may name, in [`Server::planners`]'s order.
const SHORTENINGS: [(&str, Shortening); 4] = [
    ("fast", Shortening::Fast),
    ("exact", Shortening::Exact),
    ("greedy", Shortening::Greedy),
    ("off", Shortening::Off),
];

impl Server<'_> {
    /// Reads one line as a request, or the one-line reason it is none.
    fn parse(&self, line: &[u8], sink: &Arc<dyn Sink>) -> Result<Request, (Value, String)> {
        let text = std::str::from_utf8(line)
            .map_err(|_| (Value::Null, "the line is not UTF-8".to_string()))?;
        let v: Value = serde_json::from_str(text)
            .map_err(|e| (Value::Null, format!("not a JSON request: {e}")))?;
        let Value::Object(obj) = &v else {
            return Err((
                Value::Null,
                "a request is a JSON object ({\"id\", \"start\", \"goal\"} or {\"cmd\"})".into(),
            ));
        };
        let id = obj.get("id").cloned().unwrap_or(Value::Null);
        let bad = |e: String| (id.clone(), e);
        if obj.contains_key("cmd") {
            let c: CommandRequest =
                serde_json::from_value(v.clone()).map_err(|e| bad(format!("bad command: {e}")))?;
            return match c.cmd.as_str() {
                "info" => Ok(Request::Info(id)),
                "shutdown" => Ok(Request::Shutdown(id)),
                other => Err(bad(format!(
                    "unknown command {other:?} (known: \"info\", \"shutdown\")"
                ))),
            };
        }
        let q: QueryRequest =
            serde_json::from_value(v.clone()).map_err(|e| bad(format!("bad query: {e}")))?;
        let shorten = match q.shorten.as_deref() {
            None => 0,
            Some(s) => SHORTENINGS
                .iter()
                .position(|(name, _)| *name == s)
                .ok_or_else(|| {
                    bad(format!(
                        "unknown shorten {s:?} (known: \"fast\", \"exact\", \"greedy\", \"off\")"
                    ))
                })?,
        };
        let time = match q.time {
            None => None,
            Some(t) => Some(duration_from_secs(t).ok_or_else(|| {
                bad(format!(
                    "time must be a positive number of seconds of at most {:e}, got {t:?}",
                    viaroad::limits::MAX_SECONDS
                ))
            })?),
        };
        Ok(Request::Query(Job {
            id,
            start: q.start,
            goal: q.goal,
            shorten,
            time,
            sink: sink.clone(),
            client: None,
        }))
    }

    /// Reads requests from one client until its input ends, `shutdown`, a `shutdown` from
    /// another client, or the server disconnects it (`client`, over TCP); queries go to the
    /// workers, everything else is answered here.
    fn read_client(
        &self,
        input: impl Read,
        sink: Arc<dyn Sink>,
        client: Option<&Arc<Client>>,
        jobs: &SyncSender<Job>,
    ) {
        let mut input = BufReader::new(input);
        let mut line = Vec::new();
        while !self.stop.load(Ordering::SeqCst) {
            line.clear();
            match read_bounded_line(&mut input, &mut line, MAX_LINE) {
                Ok(Line::End) | Err(_) => return,
                Ok(Line::TooLong) => {
                    if client.is_some_and(|c| !c.line_read(false)) {
                        return;
                    }
                    self.errors.fetch_add(1, Ordering::Relaxed);
                    sink.send(&error_reply(
                        &Value::Null,
                        &format!("line longer than {MAX_LINE} bytes"),
                    ));
                    continue;
                }
                Ok(Line::Complete) => {}
            }
            let request = if line.iter().all(u8::is_ascii_whitespace) {
                None
            } else {
                Some(self.parse(&line, &sink))
            };
            if let Some(c) = client {
                if !c.line_read(matches!(request, Some(Ok(Request::Query(_))))) {
                    return;
                }
            }
            let Some(request) = request else { continue };
            match request {
                Ok(Request::Query(mut job)) => {
                    job.client = client.cloned();
                    if jobs.send(job).is_err() {
                        return;
                    }
                }
                Ok(Request::Info(id)) => {
                    let mut info = self.info.clone();
                    if let Value::Object(m) = &mut info {
                        m.insert("id".into(), id);
                        m.insert(
                            "answered".into(),
                            self.answered.load(Ordering::Relaxed).into(),
                        );
                        m.insert("errors".into(), self.errors.load(Ordering::Relaxed).into());
                    }
                    sink.send(&info.to_string());
                }
                Ok(Request::Shutdown(id)) => {
                    let mut slot = self
                        .shutdown_reply
                        .lock()
                        .unwrap_or_else(|p| p.into_inner());
                    slot.get_or_insert((id, sink.clone()));
                    self.stop.store(true, Ordering::SeqCst);
                    return;
                }
                Err((id, e)) => {
                    self.errors.fetch_add(1, Ordering::Relaxed);
                    sink.send(&error_reply(&id, &e));
                }
            }
        }
    }

    /// Answers queries until every reader is done.
    fn work(&self, jobs: &Mutex<Receiver<Job>>) {
        loop {
            let job = {
                let rx = jobs.lock().unwrap_or_else(|p| p.into_inner());
                rx.recv()
            };
            let Ok(job) = job else { return };
            let began = Instant::now();
            let outer = Deadline::after_opt(job.time);
            let result = self.planners[job.shorten]
                .query_within(&job.start, &job.goal, &outer)
                .map_err(|e| e.to_string());
            let ms = began.elapsed().as_secs_f64() * 1e3;
            let check = match (&self.checker, &result) {
                (Some(c), Ok(r)) if r.is_solved() => Some(c.check_path(&r.path)),
                _ => None,
            };
            self.answered.fetch_add(1, Ordering::Relaxed);
            job.sink
                .send(&answer_reply(&job.id, &result, ms, check.as_ref()));
            if let Some(c) = &job.client {
                c.answered();
            }
        }
    }

    /// The `shutdown` reply, once every query read has been answered.
    fn finish(&self) {
        let slot = self
            .shutdown_reply
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .take();
        if let Some((id, sink)) = slot {
            sink.send(
                &json!({
                    "id": id,
                    "shutdown": true,
                    "answered": self.answered.load(Ordering::Relaxed),
                    "errors": self.errors.load(Ordering::Relaxed),
                })
                .to_string(),
            );
        }
    }
}

/// How a bounded line read ended.
#[derive(Debug, PartialEq)]
enum Line {
    /// A line (without its newline) is in the buffer.
    Complete,
    /// The line was longer than the limit; it was skipped up to its newline.
    TooLong,
    /// The input ended (nothing read).
    End,
}

/// Reads one line of at most `max` bytes into `buf` without ever holding more than that.
fn read_bounded_line(
    input: &mut impl BufRead,
    buf: &mut Vec<u8>,
    max: usize,
) -> std::io::Result<Line> {
    let n = input.by_ref().take(max as u64 + 1).read_until(b'\n', buf)?;
    if n == 0 {
        return Ok(Line::End);
    }
    if buf.last() == Some(&b'\n') {
        buf.pop();
        if buf.last() == Some(&b'\r') {
            buf.pop();
        }
        return Ok(Line::Complete);
    }
    if buf.len() <= max {
        // the last line of the input, without a newline
        return Ok(Line::Complete);
    }
    // skip the rest of the long line, a bounded chunk at a time
    loop {
        let chunk = input.fill_buf()?;
        if chunk.is_empty() {
            return Ok(Line::TooLong);
        }
        match chunk.iter().position(|&b| b == b'\n') {
            Some(i) => {
                input.consume(i + 1);
                return Ok(Line::TooLong);
            }
            None => {
                let n = chunk.len();
                input.consume(n);
            }
        }
    }
}

/// One planner per shortening a request may ask for, each with the server's options.
fn planners<'a>(
    a: &ServeArgs,
    scene: &Scene,
    roadmap: &'a Roadmap,
    oracle: &'a dyn viaroad::oracle::CollisionOracle,
    time: std::time::Duration,
) -> anyhow::Result<Vec<QueryPlanner<'a>>> {
    let mut planners = Vec::new();
    for (_, s) in SHORTENINGS {
        let planner = QueryPlanner::new(roadmap, oracle).context("roadmap")?;
        let mut options = planner.options().clone();
        options.time = Some(time);
        options.grow = !a.no_grow;
        options.trees = a.trees.params(&scene.space);
        options.race = a.race.race(&scene.space);
        options.straight_shortcuts = !a.no_straight;
        match s {
            Shortening::Fast => {}
            Shortening::Exact => options.exact_shortening_limit = usize::MAX,
            Shortening::Greedy => options.exact_shortening_limit = 0,
            Shortening::Off => options.shorten = false,
        }
        planners.push(planner.with_options(options));
    }
    Ok(planners)
}

/// What an `info` request answers: the roadmap's header, the scene and the server's threads.
fn server_info(scene: &Scene, roadmap: &Roadmap, threads: usize) -> anyhow::Result<Value> {
    let mut info = serde_json::to_value(roadmap.info()).context("roadmap info")?;
    if let Value::Object(m) = &mut info {
        let extra: Map<String, Value> = [
            ("scene".to_string(), Value::from(scene.name.clone())),
            ("dof".to_string(), Value::from(scene.space.dim())),
            ("threads".to_string(), Value::from(threads)),
        ]
        .into_iter()
        .collect();
        m.extend(extra);
    }
    Ok(info)
}

/// Runs `serve`.
pub fn run(a: ServeArgs) -> anyhow::Result<()> {
    let idle = super::limits::parse_seconds(
        "--idle-timeout",
        a.idle_timeout.unwrap_or(DEFAULT_IDLE_TIMEOUT.as_secs_f64()),
    )?;
    let max_clients = super::limits::count_in_range(
        "--max-clients",
        a.max_clients.unwrap_or(MAX_SERVE_CLIENTS),
        MAX_SERVE_CLIENTS,
        "each client holds a thread and three open files",
    )?;
    if a.listen.is_none() {
        for (flag, given) in [
            ("--idle-timeout", a.idle_timeout.is_some()),
            ("--max-clients", a.max_clients.is_some()),
        ] {
            anyhow::ensure!(
                !given,
                "{flag} applies to TCP clients only: give --listen ADDR with it"
            );
        }
    }
    let scene = Scene::load(&a.scene)?;
    let roadmap = Roadmap::load(&a.roadmap, scene.fingerprint())?;
    let time = super::limits::parse_seconds("--time", a.time)?;
    let threads = match a.threads {
        Some(n) => {
            super::limits::count_in_range("--threads", n, 1024, "each is a thread of the server")?
        }
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let oracle = scene.oracle();
    let planners = planners(&a, &scene, &roadmap, oracle.as_ref(), time)?;
    let info = server_info(&scene, &roadmap, threads)?;
    let checker = super::query::independent_checker(&scene, a.check)?;
    let server = Server {
        checker,
        planners,
        info,
        stop: AtomicBool::new(false),
        answered: AtomicU64::new(0),
        errors: AtomicU64::new(0),
        shutdown_reply: Mutex::new(None),
    };
    let (tx, rx) = sync_channel::<Job>(QUEUE);
    let rx = Mutex::new(rx);
    let listener = match a.listen {
        Some(addr) => {
            let l = TcpListener::bind(addr).with_context(|| format!("--listen {addr}"))?;
            if !addr.ip().is_loopback() {
                eprintln!(
                    "warning: serving on {addr}, not the loopback: anyone who can reach it can ask"
                );
            }
            Some(l)
        }
        None => None,
    };
    // the address ends the line, where a script that started the server on port 0 finds it
    eprintln!(
        "serving {} ({} nodes, {} edges) with {threads} thread{} {}",
        a.roadmap.display(),
        roadmap.node_count(),
        roadmap.edge_count(),
        if threads == 1 { "" } else { "s" },
        match &listener {
            Some(l) => format!(
                "for at most {max_clients} client{} (disconnected after {} s idle), \
                 listening on {}",
                if max_clients == 1 { "" } else { "s" },
                idle.as_secs_f64(),
                l.local_addr()?
            ),
            None => "on stdin/stdout".to_string(),
        }
    );
    std::thread::scope(|s| -> anyhow::Result<()> {
        for _ in 0..threads {
            s.spawn(|| server.work(&rx));
        }
        match &listener {
            None => {
                let sink: Arc<dyn Sink> = Arc::new(StdoutSink);
                server.read_client(std::io::stdin().lock(), sink, None, &tx);
                drop(tx);
            }
            Some(l) => {
                let result = accept_loop(s, &server, l, &tx, idle, max_clients);
                drop(tx);
                result?;
            }
        }
        Ok(())
    })?;
    server.finish();
    Ok(())
}

/// Accepts clients until `shutdown`, one reader thread each, at most `max` at once; then
/// stops every reader. A janitor thread disconnects clients idle for `idle`.
fn accept_loop<'scope, 'env>(
    s: &'scope std::thread::Scope<'scope, 'env>,
    server: &'env Server<'env>,
    listener: &TcpListener,
    jobs: &SyncSender<Job>,
    idle: Duration,
    max: usize,
) -> anyhow::Result<()> {
    let addr = listener.local_addr()?;
    // live clients, to disconnect idle ones and stop their readers at `shutdown`
    let live: Arc<Mutex<Vec<Arc<Client>>>> = Arc::default();
    // a reader's `shutdown` wakes the blocking accept by connecting once
    let wake = Arc::new(move || {
        let _ = TcpStream::connect_timeout(&addr, Duration::from_secs(5));
    });
    // the janitor runs until this loop ends (and drops `_janitor`)
    let (_janitor, stopped) = channel::<()>();
    {
        let live = live.clone();
        let tick = (idle / 10).clamp(Duration::from_millis(10), Duration::from_secs(1));
        s.spawn(move || {
            while let Err(RecvTimeoutError::Timeout) = stopped.recv_timeout(tick) {
                let now = Instant::now();
                lock(&live).retain(|c| !c.evict_if_idle(now, idle, Eviction::Idle));
            }
        });
    }
    let evictable = EVICTABLE_AFTER.min(idle);
    for stream in listener.incoming() {
        if server.stop.load(Ordering::SeqCst) {
            break;
        }
        let Ok(stream) = stream else {
            // out of descriptors or the like: let the clients finish before the next try
            std::thread::sleep(Duration::from_millis(50));
            continue;
        };
        let _ = stream.set_write_timeout(Some(Duration::from_secs(60)));
        let Ok(writer) = stream.try_clone() else {
            continue;
        };
        let Ok(closer) = stream.try_clone() else {
            continue;
        };
        let client = Arc::new(Client::new(closer));
        {
            let mut l = lock(&live);
            if l.len() >= max {
                // full: the client idle longest makes room, so that a newcomer (its
                // `shutdown` say) is not locked out by clients that went quiet
                let now = Instant::now();
                if let Some(i) = longest_idle(l.iter().map(|c| c.activity()), now, evictable) {
                    if l[i].evict_if_idle(now, evictable, Eviction::Full) {
                        l.swap_remove(i);
                    }
                }
            }
            if l.len() >= max {
                TcpSink(Mutex::new(writer)).send(&error_reply(
                    &Value::Null,
                    &format!(
                        "too many clients (at most {max}), none idle for {} s: try again later",
                        evictable.as_secs_f64()
                    ),
                ));
                let _ = stream.shutdown(Shutdown::Both);
                continue;
            }
            l.push(client.clone());
        }
        let jobs = jobs.clone();
        let live = live.clone();
        let wake = wake.clone();
        s.spawn(move || {
            let sink: Arc<dyn Sink> = Arc::new(TcpSink(Mutex::new(writer)));
            server.read_client(stream, sink.clone(), Some(&client), &jobs);
            lock(&live).retain(|c| !Arc::ptr_eq(c, &client));
            if let Some(why) = client.activity().evicted {
                // nothing of it is in flight, and nothing more will be
                let message = match why {
                    Eviction::Idle => format!(
                        "disconnected: no line from this client in {} s (--idle-timeout)",
                        idle.as_secs_f64()
                    ),
                    Eviction::Full => format!(
                        "disconnected: the server is full (at most {max} clients) and this \
                         client was the one idle longest"
                    ),
                };
                let _ = client.stream.set_write_timeout(Some(FAREWELL_WRITE));
                sink.send(&error_reply(&Value::Null, &message));
                let _ = client.stream.shutdown(Shutdown::Both);
            }
            if server.stop.load(Ordering::SeqCst) {
                wake();
            }
        });
    }
    // stop the other readers: their clients can still read the answers to what they sent
    for c in lock(&live).iter() {
        let _ = c.stream.shutdown(Shutdown::Read);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(input: &[u8], max: usize) -> Vec<Result<String, Line>> {
        let mut r = BufReader::with_capacity(4, input);
        let mut out = Vec::new();
        loop {
            let mut buf = Vec::new();
            match read_bounded_line(&mut r, &mut buf, max).unwrap() {
                Line::End => return out,
                Line::Complete => out.push(Ok(String::from_utf8(buf).unwrap())),
                Line::TooLong => out.push(Err(Line::TooLong)),
            }
        }
    }

    #[test]
    fn a_full_server_makes_room_by_the_client_idle_longest_never_a_busy_one() {
        let t0 = Instant::now();
        let now = t0 + Duration::from_secs(100);
        let second = Duration::from_secs(1);
        let seen = |at: u64, pending: usize| Activity {
            last: t0 + Duration::from_secs(at),
            pending,
            evicted: None,
        };
        // quiet for 100 s but waiting for an answer: busy; of the idle ones, the older
        assert_eq!(
            longest_idle([seen(0, 1), seen(50, 0), seen(10, 0)], now, second),
            Some(2)
        );
        // every client busy or idle for less than the threshold: nobody makes room
        assert_eq!(
            longest_idle([seen(0, 3), seen(99, 0)], now, Duration::from_secs(2)),
            None
        );
        // a client already disconnected does not count
        let mut gone = seen(0, 0);
        gone.evicted = Some(Eviction::Idle);
        assert_eq!(longest_idle([gone, seen(60, 0)], now, second), Some(1));
        assert_eq!(longest_idle([], now, second), None);
    }

    #[test]
    fn bounded_lines_skip_long_ones_and_keep_the_rest() {
        let got = lines(b"ab\r\n0123456789abc\nxyz\n\nlast", 5);
        assert_eq!(
            got,
            vec![
                Ok("ab".into()),
                Err(Line::TooLong),
                Ok("xyz".into()),
                Ok(String::new()),
                Ok("last".into())
            ]
        );
        // exactly the limit is still a line; one more is not
        assert_eq!(
            lines(b"12345\n123456\n", 5),
            vec![Ok("12345".into()), Err(Line::TooLong)]
        );
        assert_eq!(lines(b"123456", 5), vec![Err(Line::TooLong)]);
    }
}
