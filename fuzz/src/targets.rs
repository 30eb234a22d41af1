//! The fuzz targets: one per loader, each with its seeds (the shipped files), its input
//! generator and the in-process call it makes.

use crate::mutate::{Kind, Mutator};
use rand::Rng;
use std::fs;
use std::path::{Path, PathBuf};
use viaroad::roadmap::persist::checksum;
use viaroad::roadmap::Roadmap;
use viaroad::robot::{srdf, urdf, Model};
use viaroad::scene::{collada, mesh_io, moveit, ompl_cfg, Scene};
use viaroad::space::Space;

/// The target names, in the order `all` runs them.
pub const NAMES: &[&str] = &[
    "toml", "cfg", "obj", "stl", "dae", "queries", "roadmap", "urdf", "srdf", "moveit",
];

/// Separates a `cfg` input's problem file from the mesh written as `mut.dae` beside it.
pub const MESH_SEPARATOR: &[u8] = b"\n#--viaroad-fuzz-mesh--\n";

/// One fuzz target.
pub struct Target {
    /// Its name on the command line.
    pub name: &'static str,
    /// The extension of saved inputs.
    pub ext: &'static str,
    kind: Kind,
    seeds: Vec<Vec<u8>>,
    /// For `cfg`: the Collada seeds its robot file is mutated from.
    meshes: Vec<Vec<u8>>,
    /// Inputs that loaded without error: mutated further, they reach deeper.
    pool: Vec<Vec<u8>>,
}

/// Files under `dir` (recursively) whose extension is one of `exts`, sorted, at most `max` bytes.
fn files(dir: &Path, exts: &[&str], max: u64) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(entries) = fs::read_dir(dir) else {
        return out;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(files(&p, exts, max));
        } else if p
            .extension()
            .and_then(|x| x.to_str())
            .is_some_and(|x| exts.iter().any(|e| x.eq_ignore_ascii_case(e)))
            && e.metadata().map(|m| m.len() <= max).unwrap_or(false)
        {
            out.push(p);
        }
    }
    out.sort();
    out
}

fn read_all(paths: &[PathBuf]) -> Vec<Vec<u8>> {
    paths.iter().filter_map(|p| fs::read(p).ok()).collect()
}

/// Small scenes covering what the shipped ones do not (discs in R^n, meshes, `center`).
const TOML_EXTRA: &[&str] = &[
    "[space]\nkind = \"r3\"\nlower = [0, 0, 0]\nupper = [1, 1, 1]\n[[obstacle]]\ndisc = { center = [0.5, 0.5, 0.5], radius = 0.1 }\n[[query]]\nstart = [0.1, 0.1, 0.1]\ngoal = [0.9, 0.9, 0.9]\n",
    "name = \"m\"\n[space]\nkind = \"se3\"\nlower = [-5, -5, -5]\nupper = [5, 5, 5]\nrotation_scale = 0.5\n[robot]\nmesh = \"octa_zup.dae\"\ncenter = \"mean\"\n[[obstacle]]\nmesh = \"cube_quads.obj\"\noffset = [2, 0, 0]\n[[obstacle]]\nmesh = \"octa_binary.stl\"\n[[obstacle]]\nconvex = { points = [[0, 0, 3], [1, 0, 3], [0, 1, 3], [0, 0, 4]] }\n[[query]]\nstart = [-3, 0, 0, 0, 0, 0, 1]\ngoal = [-3, 2, 0, 0, 0, 0.7071, 0.7071]\n",
    "[space]\nkind = \"se2\"\nlower = [-5, -5]\nupper = [5, 5]\n[robot]\nmesh = \"octa.obj\"\ncenter = [0.1, 0.2]\n[[obstacle]]\nmesh = \"cube_polylist.dae\"\noffset = [3, 0]\n[[obstacle]]\npolygons = [{ vertices = [[0, 0], [1, 0], [0, 1]] }]\n[[obstacle]]\nbox = { center = [-3, -3], half_extents = [0.5, 0.5] }\n[[query]]\nstart = [-4, 4, 0]\ngoal = [4, 4, 3.14159]\n",
    "[space]\nkind = \"rn\"\nlower = [0, 0, 0, 0, 0, 0]\nupper = [1, 1, 1, 1, 1, 1]\n[[obstacle]]\ndisc = { center = [0.5, 0.5, 0.5, 0.5, 0.5, 0.5], radius = 0 }\n",
];

/// Rewrites `robot = …` / `world = …` of a `.cfg` to meshes present in the work directory
/// (the big OMPL.app environments would make every execution slow).
fn small_meshes(cfg: &str, present: &[String]) -> String {
    let mut out = String::new();
    for line in cfg.lines() {
        let key = line.split('=').next().unwrap_or("").trim();
        let value = line.split_once('=').map(|(_, v)| v.trim()).unwrap_or("");
        if (key == "robot" || key == "world") && !present.iter().any(|p| p == value) {
            let small = if key == "robot" {
                "octa_zup.dae"
            } else {
                "cube_polylist.dae"
            };
            out.push_str(&format!("{key} = {small}\n"));
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

impl Target {
    /// The target `name` with its seeds from the repository at `root`; `None` for unknown names.
    pub fn new(name: &str, root: &Path) -> Option<Target> {
        let data = root.join("tests/data");
        let scenes = root.join("scenes");
        let both = |exts: &[&str], max: u64| {
            let mut v = files(&scenes, exts, max);
            v.extend(files(&data, exts, max));
            read_all(&v)
        };
        let (name, ext, kind, seeds, meshes): (&'static str, _, _, Vec<Vec<u8>>, _) = match name {
            "toml" => {
                let mut s = both(&["toml"], 1 << 20);
                s.extend(TOML_EXTRA.iter().map(|t| t.as_bytes().to_vec()));
                ("toml", "toml", Kind::Text, s, vec![])
            }
            "cfg" => {
                let present = mesh_names(root);
                let mut s = Vec::new();
                for cfg in both(&["cfg"], 1 << 20) {
                    let text = small_meshes(&String::from_utf8_lossy(&cfg), &present);
                    s.push(text.clone().into_bytes());
                    for key in ["robot", "world"] {
                        let swapped: String = text
                            .lines()
                            .map(|l| {
                                if l.split('=').next().unwrap_or("").trim() == key {
                                    format!("{key} = mut.dae\n")
                                } else {
                                    format!("{l}\n")
                                }
                            })
                            .collect();
                        s.push(swapped.into_bytes());
                    }
                }
                let meshes = both(&["dae"], 30_000);
                ("cfg", "cfg", Kind::Text, s, meshes)
            }
            "obj" => ("obj", "obj", Kind::Text, both(&["obj"], 1 << 20), vec![]),
            "stl" => ("stl", "stl", Kind::Binary, both(&["stl"], 1 << 20), vec![]),
            "dae" => ("dae", "dae", Kind::Text, both(&["dae"], 30_000), vec![]),
            "queries" => (
                "queries",
                "txt",
                Kind::Text,
                both(&["txt", "path"], 1 << 20),
                vec![],
            ),
            "roadmap" => (
                "roadmap",
                "bin",
                Kind::Binary,
                read_all(&files(&root.join("roadmaps"), &["bin"], 1 << 20)),
                vec![],
            ),
            "urdf" => ("urdf", "urdf", Kind::Text, both(&["urdf"], 1 << 20), vec![]),
            "srdf" => ("srdf", "srdf", Kind::Text, both(&["srdf"], 1 << 20), vec![]),
            "moveit" => (
                "moveit",
                "yaml",
                Kind::Text,
                both(&["yaml"], 1 << 20),
                vec![],
            ),
            _ => return None,
        };
        Some(Target {
            name,
            ext,
            kind,
            seeds,
            meshes,
            pool: Vec::new(),
        })
    }

    /// The seeds, run unmutated first.
    pub fn seeds(&self) -> &[Vec<u8>] {
        &self.seeds
    }

    /// Remembers an input that loaded (a bounded pool of inputs no larger than twice the
    /// largest seed: repeated lines would otherwise grow them generation after generation and
    /// slow every execution down).
    pub fn keep(&mut self, input: Vec<u8>, m: &mut Mutator) {
        let largest = self.seeds.iter().map(Vec::len).max().unwrap_or(0);
        if input.len() > 2 * largest.max(2048) {
            return;
        }
        if self.pool.len() < 256 {
            self.pool.push(input);
        } else {
            let k = m.rng.random_range(0..self.pool.len());
            self.pool[k] = input;
        }
    }

    /// The next input.
    pub fn generate(&self, m: &mut Mutator) -> Vec<u8> {
        let base = if !self.pool.is_empty() && m.rng.random_bool(0.25) {
            &self.pool[m.rng.random_range(0..self.pool.len())]
        } else {
            &self.seeds[m.rng.random_range(0..self.seeds.len())]
        };
        match self.name {
            "cfg" => {
                let base = match base
                    .windows(MESH_SEPARATOR.len())
                    .position(|w| w == MESH_SEPARATOR)
                {
                    Some(k) => &base[..k],
                    None => &base[..],
                };
                let mut out = m.mutate(base, &self.seeds, self.kind);
                if m.rng.random_bool(0.3) {
                    let mesh = &self.meshes[m.rng.random_range(0..self.meshes.len())];
                    out.extend_from_slice(MESH_SEPARATOR);
                    out.extend(m.mutate(mesh, &self.meshes, Kind::Text));
                }
                out
            }
            "roadmap" if base.len() >= 36 && m.rng.random_bool(0.85) => {
                // mutate the payload, then make the header and checksums agree with it, so
                // the decoder and the structural checks behind the checksums are reached
                let payload = m.mutate(&base[36..], &self.seeds, self.kind);
                let mut out = base[..36].to_vec();
                out[12..20].copy_from_slice(&(payload.len() as u64).to_le_bytes());
                out[20..28].copy_from_slice(&checksum(&payload).to_le_bytes());
                let sum = checksum(&out[..28]);
                out[28..36].copy_from_slice(&sum.to_le_bytes());
                out.extend(payload);
                out
            }
            _ => m.mutate(base, &self.seeds, self.kind),
        }
    }
}

/// The mesh files copied into every work directory (small ones only).
fn mesh_sources(root: &Path) -> Vec<PathBuf> {
    let exts = ["dae", "obj", "stl"];
    let mut v = files(&root.join("tests/data"), &exts, 30_000);
    v.extend(files(&root.join("scenes"), &exts, 30_000));
    v
}

fn mesh_names(root: &Path) -> Vec<String> {
    mesh_sources(root)
        .iter()
        .filter_map(|p| p.file_name()?.to_str().map(String::from))
        .collect()
}

/// Prepares a work directory: the small meshes the scenes and problems name, flat and under
/// `meshes/`.
pub fn prepare_dir(dir: &Path, root: &Path) -> std::io::Result<()> {
    fs::create_dir_all(dir.join("meshes"))?;
    for p in mesh_sources(root) {
        let name = p.file_name().expect("a file");
        fs::copy(&p, dir.join(name))?;
        fs::copy(&p, dir.join("meshes").join(name))?;
    }
    fs::copy(
        root.join("tests/data/scenes/octa_zup.dae"),
        dir.join("default-mut.dae"),
    )?;
    Ok(())
}

fn spaces() -> Vec<Space> {
    vec![
        Space::euclidean(vec![0.0; 3], vec![1.0; 3]).expect("R^3"),
        Space::euclidean(vec![0.0; 6], vec![1.0; 6]).expect("R^6"),
        Space::se2([0.0; 2], [1.0; 2], 1.0).expect("SE(2)"),
        Space::se3([0.0; 3], [1.0; 3], 1.0).expect("SE(3)"),
    ]
}

/// `Ok(true)` when a loader accepted the input (after exercising what it returned with `then`),
/// `Ok(false)` when it refused it: the refusal's message is formatted too, since a `Display`
/// that panics is as much a defect as a loader that does.
fn classify<T, E: std::fmt::Display>(loaded: Result<T, E>, then: impl FnOnce(T)) -> bool {
    match loaded {
        Ok(value) => {
            then(value);
            true
        }
        Err(e) => {
            let _ = e.to_string();
            false
        }
    }
}

/// What a loaded scene offers its users, each of which must not panic either.
fn exercise_scene(scene: Scene) {
    let _ = scene.fingerprint();
    let _ = scene.checked_queries();
    let _ = scene.oracle();
}

/// The shipped Panda, loaded once: SRDF inputs resolve their groups against it (loading it per
/// input made the `srdf` target spend most of its time parsing the same URDF).
fn panda() -> Option<&'static Model> {
    static PANDA: std::sync::OnceLock<Option<Model>> = std::sync::OnceLock::new();
    PANDA
        .get_or_init(|| {
            let path =
                Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/arms/panda/panda.urdf");
            urdf::load_urdf(&path)
                .and_then(|u| Model::new(u, &path))
                .ok()
        })
        .as_ref()
}

/// Runs one input of target `name` in the work directory `dir`: `Ok(true)` when it loaded,
/// `Ok(false)` when it was refused with an error; I/O trouble of the harness is an `Err`.
pub fn run(name: &str, dir: &Path, input: &[u8]) -> std::io::Result<bool> {
    let write = |file: &str, bytes: &[u8]| -> std::io::Result<PathBuf> {
        let p = dir.join(file);
        fs::write(&p, bytes)?;
        Ok(p)
    };
    Ok(match name {
        "toml" => {
            let p = write("in.toml", input)?;
            classify(Scene::load(&p), exercise_scene)
        }
        "cfg" => {
            let (cfg, mesh) = match input
                .windows(MESH_SEPARATOR.len())
                .position(|w| w == MESH_SEPARATOR)
            {
                Some(k) => (&input[..k], Some(&input[k + MESH_SEPARATOR.len()..])),
                None => (input, None),
            };
            match mesh {
                Some(m) => {
                    write("mut.dae", m)?;
                }
                None => {
                    fs::copy(dir.join("default-mut.dae"), dir.join("mut.dae"))?;
                }
            }
            let p = write("in.cfg", cfg)?;
            classify(Scene::load(&p), exercise_scene)
        }
        // a Collada file is parsed once: `load_mesh` of a `.dae` is `load_collada`'s mesh
        "dae" => {
            let p = write("in.dae", input)?;
            classify(collada::load_collada(&p), |dae| {
                let _ = mesh_io::vertex_mean(&dae.mesh);
                let _ = dae.assimp_centre;
            })
        }
        "obj" | "stl" => {
            let p = write(&format!("in.{name}"), input)?;
            classify(mesh_io::load_mesh(&p), |mesh| {
                let _ = mesh_io::vertex_mean(&mesh);
            })
        }
        "queries" => {
            let p = write("in.txt", input)?;
            let mut any = false;
            for space in spaces() {
                any |= ompl_cfg::read_query_pairs(&p, &space).is_ok();
                any |= ompl_cfg::read_states(&p, &space).is_ok();
            }
            any
        }
        "roadmap" => {
            let p = write("in.bin", input)?;
            classify(Roadmap::load_any_scene(&p), |r| {
                let _ = r.info();
                let _ = Roadmap::from_bytes(input, r.header().fingerprint);
                if r.node_count() > 0 {
                    let q = r.node(0).to_vec();
                    let _ = r.nearest(&q, 3, None);
                }
                for e in 0..r.edge_count().min(4) {
                    let from = r.edges()[e].a;
                    let _ = r.edge_path(e, from);
                }
            })
        }
        "urdf" => {
            let text = String::from_utf8_lossy(input);
            let p = Path::new("in.urdf");
            classify(
                urdf::parse_urdf(&text, p).and_then(|u| Model::new(u, p)),
                |model| {
                    let values = vec![0.5; model.urdf.joints.len()];
                    let _ = model.link_poses(&nalgebra::Isometry3::identity(), &values);
                    for l in &model.urdf.links {
                        for c in &l.collisions {
                            if let urdf::Geometry::Primitive(prim) = &c.geometry {
                                let _ = prim.polytope();
                            }
                        }
                    }
                },
            )
        }
        "srdf" => {
            let text = String::from_utf8_lossy(input);
            let p = Path::new("in.srdf");
            classify(srdf::parse_srdf(&text, p), |s| {
                if let Some(model) = panda() {
                    for g in &s.groups {
                        let _ = model.resolve_group(&s, &g.name, p);
                    }
                }
            })
        }
        "moveit" => {
            let text = String::from_utf8_lossy(input);
            let p = Path::new("in.yaml");
            let scene = classify(moveit::parse_planning_scene(&text, p), |s| {
                for o in &s.objects {
                    for (_, shape) in &o.parts {
                        if let moveit::ObjectShape::Primitive(prim) = shape {
                            let _ = prim.polytope();
                        }
                    }
                }
            });
            let request = classify(moveit::parse_motion_plan_request(&text, p), |_| {});
            scene || request
        }
        _ => false,
    })
}
