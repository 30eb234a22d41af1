//! Throughput of `viaroad serve`: queries per second over TCP from 1, 2 and 8
//! concurrent clients, on the shipped discs demo roadmap and on OMPL.app's Home. Each client
//! keeps one query in flight (it waits for the reply before the next); a last row has 8
//! clients send everything at once (pipelined). Every reply is matched to its id (none lost,
//! none mixed up) and solved paths re-checked by the independent checkers of
//! `viaroad::bench::validity`: all of the discs', those of Home's first 20 queries
//! (`--home-check`). The server runs with `--no-grow` (see `start`); `query_ms mean` is the
//! server's own time per query, the rest of a round trip is JSON and TCP. Not a criterion
//! bench: one wall-clock figure per row, printed as a Markdown table.
//!
//! ```sh
//! cargo bench --bench serve                      # discs 10 000 queries, Home 200
//! cargo bench --bench serve -- --discs 2000 --home 0
//! cargo bench --bench serve -- --discs 0 --home 200 --home-check 200   # every Home path too (slow)
//! ```
//! Home's roadmap is learnt once (`viaroad build … --time 20 --seed 1`) into
//! `target/bench-serve/home.bin` and reused.

use rand::SeedableRng;
use serde_json::{json, Value};
use std::collections::BTreeMap;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::time::{Duration, Instant};
use viaroad::bench::validity::Checker;
use viaroad::scene::Scene;
use viaroad::space::Config;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A server, killed when dropped.
struct Server {
    child: Child,
    addr: SocketAddr,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn lines_of(r: impl Read + Send + 'static) -> Receiver<String> {
    let (tx, rx) = channel();
    std::thread::spawn(move || {
        for l in BufReader::new(r).lines() {
            let Ok(l) = l else { return };
            if tx.send(l).is_err() {
                return;
            }
        }
    });
    rx
}

fn start(roadmap: &Path, scene: &Path) -> Server {
    let mut child = Command::new(env!("CARGO_BIN_EXE_viaroad"))
        .arg("serve")
        .arg(roadmap)
        .arg("--scene")
        .arg(scene)
        // a query the roadmap cannot answer would otherwise grow a copy of it for up to 10 s,
        // and one such query would decide the figure of a whole run
        .args(["--listen", "127.0.0.1:0", "--no-grow"])
        .current_dir(root())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("viaroad runs");
    let err = lines_of(child.stderr.take().unwrap());
    let line = err
        .recv_timeout(Duration::from_secs(120))
        .expect("the server starts");
    let at = line.rfind("listening on ").expect(&line) + "listening on ".len();
    let addr = line[at..].trim().parse().unwrap();
    Server { child, addr }
}

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

/// One client's queries, one in flight or all at once; its replies by id.
fn client(
    addr: SocketAddr,
    ids: &[usize],
    pairs: &[(Config, Config)],
    pipelined: bool,
) -> BTreeMap<usize, Value> {
    let stream = TcpStream::connect(addr).unwrap();
    stream.set_nodelay(true).unwrap();
    let mut w = stream.try_clone().unwrap();
    let mut r = BufReader::new(stream);
    let line = |i: usize| {
        let (s, g) = &pairs[i];
        json!({"id": i, "start": s, "goal": g}).to_string() + "\n"
    };
    let mut out = BTreeMap::new();
    let mut read = |out: &mut BTreeMap<usize, Value>| {
        let mut l = String::new();
        assert!(r.read_line(&mut l).unwrap() > 0, "server closed");
        let v: Value = serde_json::from_str(&l).unwrap();
        let id = v["id"].as_u64().expect("an id") as usize;
        assert!(out.insert(id, v).is_none(), "id {id} twice");
    };
    if pipelined {
        let all: String = ids.iter().map(|&i| line(i)).collect();
        let writer = std::thread::spawn(move || w.write_all(all.as_bytes()).unwrap());
        for _ in ids {
            read(&mut out);
        }
        writer.join().unwrap();
    } else {
        for &i in ids {
            w.write_all(line(i).as_bytes()).unwrap();
            read(&mut out);
        }
    }
    out
}

/// Queries per second with `clients` clients; checks every reply.
fn run(
    server: &Server,
    checker: &Checker,
    checked: &mut BTreeMap<(usize, &'static str), Vec<Config>>,
    check_limit: usize,
    pairs: &[(Config, Config)],
    clients: usize,
    pipelined: bool,
) -> (f64, usize, f64) {
    let began = Instant::now();
    let replies: Vec<(Vec<usize>, BTreeMap<usize, Value>)> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..clients)
            .map(|c| {
                let ids: Vec<usize> = (c..pairs.len()).step_by(clients).collect();
                s.spawn(move || {
                    let got = client(server.addr, &ids, pairs, pipelined);
                    (ids, got)
                })
            })
            .collect();
        hs.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let secs = began.elapsed().as_secs_f64();
    let mut solved = 0;
    let mut server_ms = 0.0;
    for (ids, got) in &replies {
        // none lost, none mixed up
        assert_eq!(got.keys().copied().collect::<Vec<_>>(), *ids);
        for (&i, v) in got {
            assert!(v.get("error").is_none(), "{v}");
            server_ms += v["query_ms"].as_f64().unwrap();
            if v["solved"] == true {
                solved += 1;
                for key in ["path", "shortened"] {
                    let p: Vec<Config> = serde_json::from_value(v[key].clone()).unwrap();
                    // the server normalises start and goal again (a quaternion may move by
                    // an ulp)
                    let near = |a: Option<&Config>, b: &Config| {
                        a.is_some_and(|a| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9))
                    };
                    assert!(near(p.first(), &pairs[i].0), "query {i}: start");
                    assert!(near(p.last(), &pairs[i].1), "query {i}: goal");
                    // the same path as a run before was checked then (the independent
                    // checkers are slow on big meshes: Home's 200 paths take minutes)
                    if checked.get(&(i, key)) == Some(&p) || i >= check_limit {
                        continue;
                    }
                    checker
                        .check_path(&p)
                        .unwrap_or_else(|e| panic!("query {i} {key}: {e}"));
                    checked.insert((i, key), p);
                }
            }
        }
    }
    (
        pairs.len() as f64 / secs,
        solved,
        server_ms / pairs.len() as f64,
    )
}

fn arg(args: &[String], name: &str, default: usize) -> usize {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .map_or(default, |v| v.parse().expect("a count"))
}

fn home_roadmap() -> PathBuf {
    let dir = root().join("target").join("bench-serve");
    let file = dir.join("home.bin");
    // learnt anew where missing or of an older format
    if viaroad::roadmap::Roadmap::load_any_scene(&file).is_err() {
        std::fs::create_dir_all(&dir).unwrap();
        eprintln!("learning Home's roadmap (20 s) into {}", file.display());
        let ok = Command::new(env!("CARGO_BIN_EXE_viaroad"))
            .args([
                "build",
                "scenes/ompl/3D/Home.cfg",
                "--time",
                "20",
                "--seed",
                "1",
                "-o",
            ])
            .arg(&file)
            .current_dir(root())
            .status()
            .unwrap()
            .success();
        assert!(ok, "viaroad build Home");
    }
    file
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let discs = arg(&args, "--discs", 10_000);
    let home = arg(&args, "--home", 200);
    // the independent SE(3) checker certifies a Home path in seconds (parry distances on a
    // big mesh): all of the discs' paths, Home's first 20 queries' unless told otherwise
    let home_check = arg(&args, "--home-check", 20);
    let mut targets: Vec<(&str, PathBuf, PathBuf, usize, usize)> = Vec::new();
    if discs > 0 {
        targets.push((
            "discs-cluttered (1000 nodes)",
            root().join("roadmaps/discs-cluttered.bin"),
            root().join("scenes/discs-cluttered.toml"),
            discs,
            discs,
        ));
    }
    if home > 0 {
        targets.push((
            "OMPL.app Home",
            home_roadmap(),
            root().join("scenes/ompl/3D/Home.cfg"),
            home,
            home_check,
        ));
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!("serve throughput, {cores} cores, server threads = cores; paths re-checked: discs all, Home the first {home_check} queries\n");
    println!("| roadmap | queries | clients | mode | queries/s | query_ms mean | solved |");
    println!("|---|---:|---:|---|---:|---:|---:|");
    for (name, map, scene_path, n, check) in targets {
        let scene = Scene::load(&scene_path).unwrap();
        let checker = Checker::for_scene(&scene).unwrap();
        let pairs = free_pairs(&scene, n, 12);
        let server = start(&map, &scene_path);
        let mut checked = BTreeMap::new();
        for (clients, pipelined) in [(1, false), (2, false), (8, false), (8, true)] {
            let (qps, solved, ms) = run(
                &server,
                &checker,
                &mut checked,
                check,
                &pairs,
                clients,
                pipelined,
            );
            println!(
                "| {name} | {n} | {clients} | {} | {qps:.0} | {ms:.3} | {solved}/{n} |",
                if pipelined {
                    "pipelined"
                } else {
                    "one in flight"
                }
            );
        }
    }
}
