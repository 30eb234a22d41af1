//! `viaroad serve` as clients meet it: valid, malformed and concurrent requests over
//! stdin/stdout and TCP; every query answered exactly once under its own id, every path
//! re-checked by the independent checkers of `viaroad::bench::validity`, and the server still
//! serving after every kind of bad line. Every server started here is killed when its test
//! ends, whatever happens (no hanging CI).

use crate::common;

use rand::SeedableRng;
use serde_json::{json, Value};
use std::collections::{BTreeMap, BTreeSet};
use std::io::{BufRead, BufReader, ErrorKind, Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::time::{Duration, Instant};
use viaroad::bench::validity::Checker;
use viaroad::scene::Scene;
use viaroad::space::Config;

/// How long a test waits for any one reply before it fails (and kills the server).
const PATIENCE: Duration = Duration::from_secs(120);

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A running server, killed and reaped when dropped.
struct Server {
    child: Child,
    stdin: Option<ChildStdin>,
    lines: Receiver<String>,
    stderr: Receiver<String>,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Server {
    fn start(roadmap: &str, scene: &str, extra: &[&str]) -> Server {
        let mut child = Command::new(env!("CARGO_BIN_EXE_viaroad"))
            .args(["serve", roadmap, "--scene", scene])
            .args(extra)
            .current_dir(root())
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("the binary runs");
        let stdin = child.stdin.take();
        let lines = reader_thread(child.stdout.take().unwrap());
        let stderr = reader_thread(child.stderr.take().unwrap());
        Server {
            child,
            stdin,
            lines,
            stderr,
        }
    }

    fn send(&mut self, line: &[u8]) {
        let w = self.stdin.as_mut().unwrap();
        w.write_all(line).unwrap();
        w.write_all(b"\n").unwrap();
    }

    fn reply(&self) -> Value {
        let line = self.lines.recv_timeout(PATIENCE).expect("a reply in time");
        serde_json::from_str(&line).unwrap_or_else(|e| panic!("{e}: {line}"))
    }

    /// The address a `--listen …:0` server reports on stderr.
    fn address(&self) -> SocketAddr {
        self.status().1
    }

    /// The status line a `--listen …:0` server starts with, and the address it reports there.
    fn status(&self) -> (String, SocketAddr) {
        let line = self.stderr.recv_timeout(PATIENCE).expect("a status line");
        let at = line.rfind("listening on ").expect(&line) + "listening on ".len();
        let addr = line[at..].trim().parse().unwrap();
        (line, addr)
    }

    /// Waits for the server to end by itself; its exit status.
    fn exit(mut self) -> std::process::ExitStatus {
        drop(self.stdin.take());
        for _ in 0..1200 {
            if let Some(s) = self.child.try_wait().unwrap() {
                return s;
            }
            std::thread::sleep(Duration::from_millis(100));
        }
        panic!("the server did not stop");
    }
}

/// Lines of `r`, through a channel (so a silent server times a test out instead of hanging it).
fn reader_thread(r: impl Read + Send + 'static) -> Receiver<String> {
    let (tx, rx) = channel();
    std::thread::spawn(move || {
        for line in BufReader::new(r).lines() {
            let Ok(line) = line else { return };
            if tx.send(line).is_err() {
                return;
            }
        }
    });
    rx
}

/// `n` random pairs of free configurations of `scene`, from a seeded stream.
fn free_pairs(scene: &Scene, n: usize, seed: u64) -> Vec<(Config, Config)> {
    let oracle = scene.oracle();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut free = || loop {
        let mut q = scene.space.sample_uniform(&mut rng);
        scene.space.normalize(&mut q);
        if scene.check_config(oracle.as_ref(), "q", &q).is_ok() {
            return q;
        }
    };
    (0..n).map(|_| (free(), free())).collect()
}

fn path_of(v: &Value) -> Vec<Config> {
    v.as_array()
        .expect("a path is an array")
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

fn query_line(id: u64, (s, g): &(Config, Config)) -> String {
    json!({ "id": id, "start": s, "goal": g }).to_string()
}

/// Checks one answer to `pair`: solved paths run from start to goal and pass the independent
/// checker, raw and shortened alike. Returns whether it was solved.
fn check_answer(checker: &Checker, pair: &(Config, Config), v: &Value) -> bool {
    assert!(v.get("error").is_none(), "{v}");
    if !v["solved"].as_bool().unwrap() {
        return false;
    }
    for key in ["path", "shortened"] {
        let p = path_of(&v[key]);
        assert!(p.len() >= 2, "{key}: {v}");
        for (got, want) in [(&p[0], &pair.0), (p.last().unwrap(), &pair.1)] {
            assert!(
                got.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-9),
                "{key} ends at {got:?}, not {want:?}"
            );
        }
        checker
            .check_path(&p)
            .unwrap_or_else(|e| panic!("{key} of {v}: {e}"));
    }
    assert!(v["length"].as_f64().unwrap() <= v["raw_length"].as_f64().unwrap() + 1e-9);
    true
}

const DISCS_MAP: &str = "roadmaps/discs-cluttered.bin";
const DISCS: &str = "scenes/discs-cluttered.toml";

fn scene(rel: &str) -> Scene {
    Scene::load(&root().join(rel)).unwrap()
}

/// Malformed lines, each with the id its error reply must carry and a piece of its message.
fn malformed() -> Vec<(Vec<u8>, Value, &'static str)> {
    vec![
        (b"not json".to_vec(), Value::Null, "not a JSON request"),
        (
            b"[1, 2]".to_vec(),
            Value::Null,
            "a request is a JSON object",
        ),
        (
            b"{\"id\": 1e400}".to_vec(),
            Value::Null,
            "not a JSON request",
        ),
        (vec![b'{', 0xff, 0xfe, b'}'], Value::Null, "not UTF-8"),
        (
            br#"{"id": "a", "start": [0.5, 0.5]}"#.to_vec(),
            json!("a"),
            "missing field `goal`",
        ),
        (
            br#"{"id": "b", "start": [0.5, 0.5], "goal": "x"}"#.to_vec(),
            json!("b"),
            "bad query",
        ),
        (
            br#"{"id": "c", "start": [0.5, 0.5], "goal": [0.5, 0.5], "shorten": "best"}"#.to_vec(),
            json!("c"),
            "unknown shorten",
        ),
        (
            br#"{"id": "d", "start": [0.5, 0.5], "goal": [0.5, 0.5], "colour": 1}"#.to_vec(),
            json!("d"),
            "unknown field `colour`",
        ),
        (
            br#"{"id": "e", "start": [0.5, 0.5], "goal": [0.5, 0.5], "time": -1}"#.to_vec(),
            json!("e"),
            "time must be",
        ),
        (
            br#"{"id": "f", "cmd": "dance"}"#.to_vec(),
            json!("f"),
            "unknown command",
        ),
        (vec![b'x'; (1 << 20) + 10], Value::Null, "line longer than"),
        (
            br#"{"id": "g", "start": [0.5], "goal": [0.5, 0.5]}"#.to_vec(),
            json!("g"),
            "start: configuration has 1 coordinates",
        ),
        (
            br#"{"id": "h", "start": [0.02, 0.98], "goal": [2.0, 0.5]}"#.to_vec(),
            json!("h"),
            "goal [2.0, 0.5] lies outside the bounds",
        ),
    ]
}

#[test]
fn stdin_answers_every_query_once_and_survives_malformed_lines() {
    let sc = scene(DISCS);
    let checker = Checker::for_scene(&sc).unwrap();
    let pairs = free_pairs(&sc, 150, 1);
    let bad = malformed();
    let mut server = Server::start(DISCS_MAP, DISCS, &["--threads", "2"]);
    // queries and bad lines interleaved: the server keeps serving after each bad one
    for (i, pair) in pairs.iter().enumerate() {
        server.send(query_line(i as u64, pair).as_bytes());
        if let Some((line, _, _)) = bad.get(i) {
            server.send(line);
        }
    }
    server.send(br#"{"cmd": "info", "id": "info"}"#);
    server.send(br#"{"cmd": "shutdown", "id": "bye"}"#);
    // the server stops reading at `shutdown`: a query after it is not answered (the write
    // itself may fail if the server has already ended)
    let late = query_line(9999, &pairs[0]) + "\n";
    let _ = server.stdin.as_mut().unwrap().write_all(late.as_bytes());
    let mut answers = BTreeMap::new();
    let mut errors = Vec::new();
    let mut info = None;
    let bye = loop {
        let v = server.reply();
        if v["id"] == "bye" {
            break v;
        }
        if v["id"] == "info" {
            info = Some(v);
        } else if v.get("error").is_some() {
            errors.push(v);
        } else {
            let id = v["id"].as_u64().unwrap();
            assert!(answers.insert(id, v).is_none(), "id {id} answered twice");
        }
    };
    assert_eq!(bye["shutdown"], true);
    assert_eq!(bye["answered"], (pairs.len() + 2) as u64, "{bye}");
    assert!(server.lines.recv_timeout(Duration::from_secs(1)).is_err());
    assert!(server.exit().success());
    // every query once, under its own id, with a valid path
    assert_eq!(
        answers.keys().copied().collect::<Vec<_>>(),
        (0..pairs.len() as u64).collect::<Vec<_>>()
    );
    let solved = answers
        .iter()
        .filter(|(id, v)| check_answer(&checker, &pairs[**id as usize], v))
        .count();
    assert!(solved * 10 >= pairs.len() * 9, "{solved} solved");
    // every bad line answered with its own error, the ids that could be read kept
    assert_eq!(errors.len(), bad.len(), "{errors:?}");
    for (_, id, needle) in &bad {
        assert!(
            errors
                .iter()
                .any(|e| e["id"] == *id && e["error"].as_str().unwrap().contains(needle)),
            "no error with id {id} and `{needle}` in {errors:?}"
        );
    }
    let info = info.expect("info answered");
    assert_eq!(info["nodes"], 1000);
    assert_eq!(info["dof"], 2);
    assert!(info["edges"].as_u64().unwrap() > 0 && info["components"].as_u64().unwrap() >= 1);
}

#[test]
fn answers_are_those_of_query_json_with_id_for_query() {
    let sc = scene(DISCS);
    let pairs = free_pairs(&sc, 12, 2);
    let dir = std::env::temp_dir().join(format!("viaroad-serve-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("queries.txt");
    let text: String = pairs
        .iter()
        .map(|(s, g)| {
            let c: Vec<String> = s.iter().chain(g).map(|x| format!("{x:?}")).collect();
            c.join(" ") + "\n"
        })
        .collect();
    std::fs::write(&file, text).unwrap();
    // with `--check` on both sides, each answer also says whether the checker certified it
    for extra in [&[][..], &["--check"][..]] {
        let mut args = vec![
            "query",
            DISCS_MAP,
            "--scene",
            DISCS,
            "--json",
            "--queries",
            file.to_str().unwrap(),
        ];
        args.extend(extra);
        let o = common::cli::viaroad(&args);
        assert!(o.status.success(), "{}", common::cli::stderr(&o));
        let mut batch: BTreeMap<u64, Value> = BTreeMap::new();
        for line in common::cli::stdout(&o).lines() {
            let v: Value = serde_json::from_str(line).unwrap();
            batch.insert(v["query"].as_u64().unwrap() - 1, v);
        }
        let mut server = Server::start(DISCS_MAP, DISCS, extra);
        for (i, p) in pairs.iter().enumerate() {
            server.send(query_line(i as u64, p).as_bytes());
        }
        drop(server.stdin.take()); // end of input: answer what was read, then stop
        let mut served = BTreeMap::new();
        for _ in &pairs {
            let v = server.reply();
            served.insert(v["id"].as_u64().unwrap(), v);
        }
        assert!(server.exit().success());
        assert_eq!(batch.len(), pairs.len());
        for (i, b) in &batch {
            let s = &served[i];
            let keys = |v: &Value| -> BTreeSet<String> {
                v.as_object()
                    .unwrap()
                    .keys()
                    .filter(|k| !["id", "query"].contains(&k.as_str()))
                    .cloned()
                    .collect()
            };
            assert_eq!(keys(s), keys(b), "fields of {s} and {b} ({extra:?})");
            // queries never change the roadmap: the same question, the same answer
            for k in ["solved", "path", "shortened", "calls", "outcome", "length"] {
                assert_eq!(s[k], b[k], "{k} of query {i}");
            }
            if !extra.is_empty() && s["solved"] == true {
                assert_eq!(s["certified"], true, "query {i}: {s}");
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// One TCP client: sends its queries (a malformed line among them) all at once from one
/// thread, reads the replies on another; returns the replies by id and the errors.
fn tcp_client(
    addr: SocketAddr,
    base: u64,
    pairs: &[(Config, Config)],
) -> (BTreeMap<u64, Value>, Vec<Value>) {
    let stream = TcpStream::connect(addr).unwrap();
    stream.set_read_timeout(Some(PATIENCE)).unwrap();
    let mut writer = stream.try_clone().unwrap();
    let lines: Vec<String> = pairs
        .iter()
        .enumerate()
        .map(|(i, p)| query_line(base + i as u64, p))
        .collect();
    let sender = std::thread::spawn(move || {
        for (i, l) in lines.iter().enumerate() {
            writer.write_all(l.as_bytes()).unwrap();
            writer.write_all(b"\n").unwrap();
            if i == 3 {
                writer
                    .write_all(b"{\"id\": \"oops\", \"start\": \n")
                    .unwrap();
            }
        }
        writer.flush().unwrap();
    });
    let mut replies = BTreeMap::new();
    let mut errors = Vec::new();
    let mut reader = BufReader::new(stream);
    while replies.len() < pairs.len() || errors.is_empty() {
        let mut line = String::new();
        assert!(reader.read_line(&mut line).unwrap() > 0, "server closed");
        let v: Value = serde_json::from_str(&line).unwrap();
        if v.get("error").is_some() {
            errors.push(v);
        } else {
            let id = v["id"].as_u64().unwrap();
            assert!(replies.insert(id, v).is_none(), "id {id} twice");
        }
    }
    sender.join().unwrap();
    (replies, errors)
}

#[test]
fn tcp_answers_concurrent_clients_each_its_own() {
    let sc = scene(DISCS);
    let checker = Checker::for_scene(&sc).unwrap();
    let per_client = 60;
    let clients = 8;
    let pairs = free_pairs(&sc, per_client * clients, 3);
    let server = Server::start(DISCS_MAP, DISCS, &["--listen", "127.0.0.1:0"]);
    let addr = server.address();
    // a client that sends half a line and hangs up must not disturb anyone
    {
        let mut s = TcpStream::connect(addr).unwrap();
        s.write_all(b"{\"id\": 1, \"start\": [0.1").unwrap();
    }
    let answers: Vec<_> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..clients)
            .map(|c| {
                let mine = &pairs[c * per_client..(c + 1) * per_client];
                s.spawn(move || tcp_client(addr, (c * 1000) as u64, mine))
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let mut solved = 0;
    for (c, (replies, errors)) in answers.iter().enumerate() {
        let base = (c * 1000) as u64;
        // none lost, none mixed up: each client has exactly its own ids
        assert_eq!(
            replies.keys().copied().collect::<Vec<_>>(),
            (base..base + per_client as u64).collect::<Vec<_>>()
        );
        for (id, v) in replies {
            solved += usize::from(check_answer(
                &checker,
                &pairs[c * per_client + (id - base) as usize],
                v,
            ));
        }
        assert_eq!(errors.len(), 1);
        assert_eq!(errors[0]["id"], Value::Null);
        assert!(errors[0]["error"]
            .as_str()
            .unwrap()
            .contains("not a JSON request"));
    }
    assert!(solved * 10 >= pairs.len() * 9, "{solved} solved");
    // commands from a fresh client, then shutdown ends the server
    let mut c = TcpStream::connect(addr).unwrap();
    c.set_read_timeout(Some(PATIENCE)).unwrap();
    c.write_all(b"{\"cmd\": \"info\"}\n{\"cmd\": \"shutdown\", \"id\": 5}\n")
        .unwrap();
    let mut r = BufReader::new(c);
    let mut line = String::new();
    r.read_line(&mut line).unwrap();
    let info: Value = serde_json::from_str(&line).unwrap();
    assert_eq!(info["nodes"], 1000);
    assert_eq!(info["answered"], pairs.len() as u64);
    line.clear();
    r.read_line(&mut line).unwrap();
    let bye: Value = serde_json::from_str(&line).unwrap();
    assert_eq!(bye["id"], 5);
    assert_eq!(bye["shutdown"], true);
    assert_eq!(bye["answered"], pairs.len());
    // one bad line per client, and the half line if the server read it before the shutdown
    let errors = bye["errors"].as_u64().unwrap();
    assert!((8..=9).contains(&errors), "{bye}");
    assert!(server.exit().success());
}

#[test]
fn rigid_scenes_are_served_with_valid_paths() {
    for (map, sc_path, n) in [
        ("roadmaps/se2-corridor.bin", "scenes/se2-corridor.toml", 12),
        ("roadmaps/piano.bin", "scenes/piano.toml", 4),
    ] {
        let sc = scene(sc_path);
        let checker = Checker::for_scene(&sc).unwrap();
        let pairs = free_pairs(&sc, n, 4);
        let mut server = Server::start(map, sc_path, &["--time", "20"]);
        for (i, p) in pairs.iter().enumerate() {
            server.send(query_line(i as u64, p).as_bytes());
        }
        server.send(br#"{"cmd": "shutdown"}"#);
        let mut seen = BTreeSet::new();
        let mut solved = 0;
        loop {
            let v = server.reply();
            if v.get("shutdown").is_some() {
                break;
            }
            let id = v["id"].as_u64().unwrap();
            assert!(seen.insert(id));
            solved += usize::from(check_answer(&checker, &pairs[id as usize], &v));
        }
        assert_eq!(seen.len(), n, "{sc_path}");
        assert!(solved >= 1, "{sc_path}: nothing solved");
        assert!(server.exit().success());
    }
}

#[test]
fn a_roadmap_of_another_scene_is_refused_at_start() {
    let line = common::cli::fails_with(
        &["serve", DISCS_MAP, "--scene", "scenes/discs-example.toml"],
        "",
    );
    assert!(
        line.contains("fingerprint") || line.contains("scene"),
        "{line}"
    );
    common::cli::fails_with(
        &["serve", DISCS_MAP, "--scene", DISCS, "--threads", "0"],
        "--threads must be at least 1",
    );
    common::cli::fails_with(
        &["serve", DISCS_MAP, "--scene", DISCS, "--time=-1"],
        "--time must be",
    );
    assert!(Path::new(&root().join(DISCS_MAP)).exists());
}

/// A TCP client that sends nothing until told to, reading with the tests' patience.
fn quiet_client(addr: SocketAddr) -> BufReader<TcpStream> {
    let s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(PATIENCE)).unwrap();
    BufReader::new(s)
}

/// The next line from the server, parsed; `None` once it has closed the connection.
fn next_line(r: &mut BufReader<TcpStream>) -> Option<Value> {
    let mut line = String::new();
    match r.read_line(&mut line) {
        Ok(0) => None,
        Ok(_) => Some(serde_json::from_str(&line).unwrap_or_else(|e| panic!("{e}: {line}"))),
        Err(e) if e.kind() == ErrorKind::ConnectionReset => None,
        Err(e) => panic!("no line in time: {e}"),
    }
}

/// Sends `lines` at once; the first reply (a refused client's reason, if the server closed
/// the connection before it could send).
fn request(r: &mut BufReader<TcpStream>, lines: &str) -> Value {
    let _ = r.get_mut().write_all(format!("{lines}\n").as_bytes());
    next_line(r).expect("a reply")
}

#[test]
fn idle_clients_are_disconnected_after_the_idle_timeout_and_free_their_places() {
    let sc = scene(DISCS);
    let checker = Checker::for_scene(&sc).unwrap();
    let pair = &free_pairs(&sc, 1, 5)[0];
    let server = Server::start(
        DISCS_MAP,
        DISCS,
        &[
            "--listen",
            "127.0.0.1:0",
            "--threads",
            "1",
            "--idle-timeout",
            "1",
            "--max-clients",
            "2",
        ],
    );
    let (status, addr) = server.status();
    assert!(
        status.starts_with(&format!("serving {DISCS_MAP} (1000 nodes, ")),
        "{status}"
    );
    assert!(
        status.contains(
            " edges) with 1 thread for at most 2 clients (disconnected after 1 s idle), \
             listening on 127.0.0.1:"
        ),
        "{status}"
    );
    // two clients take every place and say nothing: each is told why, then disconnected
    let connected = Instant::now();
    let mut quiet: Vec<_> = (0..2).map(|_| quiet_client(addr)).collect();
    for c in &mut quiet {
        let v = next_line(c).expect("the reason before the end");
        assert!(connected.elapsed() >= Duration::from_secs(1), "{v}");
        assert_eq!(v["id"], Value::Null);
        assert!(
            v["error"]
                .as_str()
                .unwrap()
                .contains("disconnected: no line from this client in 1 s"),
            "{v}"
        );
        assert!(next_line(c).is_none(), "nothing after the reason");
    }
    // their places are free: a new client is served, and its `shutdown` ends the server
    let mut c = quiet_client(addr);
    let answer = request(
        &mut c,
        &(query_line(1, pair) + "\n{\"cmd\": \"shutdown\", \"id\": \"bye\"}"),
    );
    assert_eq!(answer["id"], 1, "{answer}");
    check_answer(&checker, pair, &answer);
    let bye = next_line(&mut c).expect("the shutdown reply");
    assert_eq!(bye["id"], "bye");
    assert_eq!(bye["answered"], 1);
    assert!(server.exit().success());
}

#[test]
fn a_server_full_of_idle_clients_makes_room_for_a_new_client_and_its_shutdown() {
    // the default idle timeout (60 s) never runs out here: room is made by the newcomer
    let server = Server::start(
        DISCS_MAP,
        DISCS,
        &[
            "--listen",
            "127.0.0.1:0",
            "--threads",
            "1",
            "--max-clients",
            "3",
        ],
    );
    let addr = server.address();
    // three clients take every place, each seen by the server in turn, then go quiet
    let mut quiet: Vec<_> = (0..3)
        .map(|i| {
            let mut c = quiet_client(addr);
            let v = request(&mut c, &format!(r#"{{"cmd": "info", "id": {i}}}"#));
            assert_eq!(v["id"], i, "{v}");
            c
        })
        .collect();
    // quiet for longer than the second that makes a client give its place away
    std::thread::sleep(Duration::from_millis(1500));
    let mut newcomer = quiet_client(addr);
    let bye = request(&mut newcomer, r#"{"cmd": "shutdown", "id": "bye"}"#);
    assert_eq!(bye["id"], "bye", "{bye}");
    assert_eq!(bye["shutdown"], true);
    // the client quiet longest gave its place and was told why
    let v = next_line(&mut quiet[0]).expect("the reason before the end");
    assert_eq!(v["id"], Value::Null);
    assert!(
        v["error"]
            .as_str()
            .unwrap()
            .contains("the server is full (at most 3 clients)"),
        "{v}"
    );
    assert!(next_line(&mut quiet[0]).is_none());
    // the others kept theirs until the shutdown closed them, without a word
    for c in &mut quiet[1..] {
        assert_eq!(next_line(c), None);
    }
    assert!(server.exit().success());
}

#[test]
fn idle_timeouts_and_client_limits_out_of_range_are_refused_at_start() {
    // without --listen: a bad value must be refused before the missing --listen is
    let serve = ["serve", DISCS_MAP, "--scene", DISCS];
    for (extra, needle) in [
        (
            ["--idle-timeout", "0"],
            "--idle-timeout must be a positive number of seconds",
        ),
        (
            ["--idle-timeout=-3", "--threads=1"],
            "--idle-timeout must be",
        ),
        (["--idle-timeout", "1e300"], "--idle-timeout must be"),
        (["--idle-timeout", "NaN"], "--idle-timeout must be"),
        (["--max-clients", "0"], "--max-clients must be at least 1"),
        (
            ["--max-clients", "257"],
            "--max-clients 257 is more than the 256 viaroad accepts",
        ),
        (
            ["--idle-timeout", "5"],
            "--idle-timeout applies to TCP clients only",
        ),
        (
            ["--max-clients", "5"],
            "--max-clients applies to TCP clients only",
        ),
    ] {
        let args: Vec<&str> = serve.iter().chain(&extra).copied().collect();
        common::cli::fails_with(&args, needle);
    }
}
