//! Inputs the loaders' fuzzer (`fuzz/`, see docs/reliability.md, "Fuzzing") found, minimized and kept
//! here inline: each must now be refused with a typed error, never a panic, a hang or an
//! allocation far beyond the input's size.

use std::path::PathBuf;
use viaroad::scene::collada::load_collada;
use viaroad::scene::mesh_io::load_mesh;
use viaroad::scene::toml_format::{from_str, MAX_SHAPE_POINTS};
use viaroad::scene::SceneError;

/// A file with `text` in a fresh temporary directory (kept until the returned guard is dropped).
struct TempFile {
    dir: PathBuf,
    path: PathBuf,
}

impl TempFile {
    fn new(name: &str, text: &[u8]) -> TempFile {
        let dir = std::env::temp_dir().join(format!(
            "viaroad-fuzz-regression-{}-{name}",
            std::process::id()
        ));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        TempFile { dir, path }
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// `tests/data/scenes/cube_polylist.dae` with the position array's `count` replaced.
fn cube_with_count(count: &str) -> String {
    format!(
        r##"<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><created>2026-01-01T00:00:00Z</created><modified>2026-01-01T00:00:00Z</modified><up_axis>Y_UP</up_axis></asset>
  <library_geometries>
    <geometry id="c"><mesh>
      <source id="c-p"><float_array id="c-p-a" count="{count}">0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 1 0 1 0 1 1 1 1 1</float_array>
        <technique_common><accessor source="#c-p-a" count="8" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
      <vertices id="c-v"><input semantic="POSITION" source="#c-p"/></vertices>
      <polylist count="6"><input offset="0" semantic="VERTEX" source="#c-v"/><vcount>4 4 4 4 4 4</vcount><p>0 2 3 1 4 5 7 6 0 1 5 4 2 6 7 3 0 4 6 2 1 3 7 5</p></polylist>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#c"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"##
    )
}

/// Fuzzer finding (dae target): dae-parser reserves an array's `count` elements before
/// reading them, so `count="400000000"` in a 1 kB file asked for 1.6 GB; a count of 10¹² made
/// the allocation fail and the process abort. The loader now compares the count with the
/// values present first.
#[test]
fn collada_array_count_larger_than_its_values_is_refused_before_allocating() {
    for count in ["400000000", "1000000000000", "25", "18446744073709551615"] {
        let f = TempFile::new("huge_count.dae", cube_with_count(count).as_bytes());
        for result in [load_mesh(&f.path).err(), load_collada(&f.path).err()] {
            match result {
                Some(SceneError::Parse { message, .. }) => assert!(
                    message.contains(&format!("count=\"{count}\"")) && message.contains("24"),
                    "count {count}: {message}"
                ),
                other => panic!("count {count}: expected a parse error, got {other:?}"),
            }
        }
    }
    // the unmodified count still loads: the check refuses only what cannot be right
    let f = TempFile::new("exact_count.dae", cube_with_count("24").as_bytes());
    let mesh = load_mesh(&f.path).expect("the cube loads");
    assert_eq!((mesh.vertices.len(), mesh.triangles.len()), (8, 12));
}

/// The cube, placed by a chain of `levels` library nodes each instantiating the next twice
/// (2^levels instances): with `geometry` false the last node is empty.
fn doubling_nodes(levels: usize, geometry: bool) -> String {
    let cube = cube_with_count("24");
    let head = &cube[..cube.find("<library_visual_scenes>").unwrap()];
    let mut nodes: String = (0..levels)
        .map(|i| {
            format!(
                r##"<node id="n{i}"><instance_node url="#n{j}"/><instance_node url="#n{j}"/></node>"##,
                j = i + 1
            )
        })
        .collect();
    nodes += &if geometry {
        format!(r##"<node id="n{levels}"><instance_geometry url="#c"/></node>"##)
    } else {
        format!(r##"<node id="n{levels}"/>"##)
    };
    format!(
        r##"{head}<library_nodes>{nodes}</library_nodes>
  <library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#c"/><instance_node url="#n0"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"##
    )
}

/// Fuzzer finding (dae target, a hang): `<instance_node>` chains that instantiate each node
/// twice make 2^40 instances within the 64 nesting levels allowed, so loading never ended.
/// Work is now bounded by the file's size; moderate instancing still loads.
#[test]
fn collada_exponential_instancing_is_refused_not_hung() {
    for geometry in [true, false] {
        let f = TempFile::new("doubling.dae", doubling_nodes(40, geometry).as_bytes());
        for result in [load_mesh(&f.path).err(), load_collada(&f.path).err()] {
            match result {
                Some(SceneError::Parse { message, .. }) => assert!(
                    message.contains("far more"),
                    "geometry {geometry}: {message}"
                ),
                other => panic!("geometry {geometry}: expected a parse error, got {other:?}"),
            }
        }
    }
    // 2^4 instances of the cube plus the direct one: 17 × 12 triangles imported, as placed
    let f = TempFile::new("doubling4.dae", doubling_nodes(4, true).as_bytes());
    let dae = load_collada(&f.path).expect("16 instances load");
    assert_eq!(dae.triangles_imported, 17 * 12);
}

/// `n` points on a circle of radius 3 (with `z`, a third coordinate cycling through 7 levels).
fn circle(n: usize, z: bool) -> String {
    let points: Vec<String> = (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            if z {
                format!(
                    "[{}, {}, {}]",
                    3.0 * t.cos(),
                    3.0 * t.sin(),
                    (k % 7) as f64 * 0.1
                )
            } else {
                format!("[{}, {}]", 3.0 * t.cos(), 3.0 * t.sin())
            }
        })
        .collect();
    points.join(", ")
}

fn se2_polygon_scene(n: usize) -> String {
    format!(
        "[space]\nkind = \"se2\"\nlower = [-5, -5]\nupper = [5, 5]\n[robot]\n\
         box = {{ half_extents = [0.1, 0.1] }}\n[[obstacle]]\npolygon = {{ vertices = [{}] }}\n",
        circle(n, false)
    )
}

/// Fuzzer findings (toml target): a polygon of 20 000 vertices hung loading (the simplicity
/// test and the triangulation are quadratic) and the 3D hull of 10 000 convex points made
/// parry ask for 377 MB. Shapes given point by point are now limited to
/// [`MAX_SHAPE_POINTS`] points, refused with a message saying so.
#[test]
fn toml_shapes_with_too_many_points_are_refused() {
    let path = std::path::Path::new("many_points.toml");
    let n = MAX_SHAPE_POINTS + 1;
    let polygon = se2_polygon_scene(n);
    let hull = format!(
        "[space]\nkind = \"se3\"\nlower = [-5, -5, -5]\nupper = [5, 5, 5]\n[robot]\n\
         box = {{ half_extents = [0.1, 0.1, 0.1] }}\n[[obstacle]]\nconvex = {{ points = [{}] }}\n",
        circle(n, true)
    );
    for text in [polygon, hull] {
        match from_str(&text, path) {
            Err(e) => {
                let message = e.to_string();
                assert!(
                    message.contains(&format!("{n} "))
                        && message.contains(&format!("at most {MAX_SHAPE_POINTS}")),
                    "{message}"
                );
            }
            Ok(_) => panic!("a shape of {n} points loaded"),
        }
    }
    // the limit itself is accepted: the obstacle is the polygon as given
    let scene = from_str(&se2_polygon_scene(MAX_SHAPE_POINTS), path).expect("the limit loads");
    match &scene.obstacles[..] {
        [viaroad::scene::Obstacle::Polygon(p)] => assert_eq!(p.vertices.len(), MAX_SHAPE_POINTS),
        other => panic!(
            "expected one polygon obstacle, got {} obstacles",
            other.len()
        ),
    }
}

/// One triangle list over three positions whose `n` index tuples all have distinct normals.
fn distinct_normals(n: usize) -> String {
    let normals: Vec<String> = (0..n)
        .map(|k| {
            format!(
                "{} {} 1",
                (k % 1000) as f64 / 1000.0,
                (k / 1000) as f64 / 100.0
            )
        })
        .collect();
    let p: Vec<String> = (0..n).map(|k| format!("{} {k}", k % 3)).collect();
    format!(
        r##"<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><created>2026-01-01T00:00:00Z</created><modified>2026-01-01T00:00:00Z</modified><up_axis>Y_UP</up_axis></asset>
  <library_geometries>
    <geometry id="c"><mesh>
      <source id="c-p"><float_array id="c-p-a" count="9">0 0 0 1 0 0 0 1 0</float_array>
        <technique_common><accessor source="#c-p-a" count="3" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
      <source id="c-n"><float_array id="c-n-a" count="{}">{}</float_array>
        <technique_common><accessor source="#c-n-a" count="{n}" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
      <vertices id="c-v"><input semantic="POSITION" source="#c-p"/></vertices>
      <triangles count="{}"><input offset="0" semantic="VERTEX" source="#c-v"/><input offset="1" semantic="NORMAL" source="#c-n"/><p>{}</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#c"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"##,
        3 * n,
        normals.join(" "),
        n / 3,
        p.join(" ")
    )
}

/// Found while fuzzing (dae, a hang): joining identical vertices compares each index tuple
/// with every distinct one at its position, so a 1.3 MB file whose 60 000 tuples share three
/// positions with distinct normals took 1.7 s per load and a 10 MB one minutes. The
/// comparisons are now bounded by the file's size; a modest number of distinct normals per
/// position still joins exactly (every tuple distinct: one imported vertex each).
#[test]
fn collada_quadratic_vertex_joining_is_refused() {
    let f = TempFile::new("normals.dae", distinct_normals(15_000).as_bytes());
    match load_collada(&f.path) {
        Err(SceneError::Parse { message, .. }) => {
            assert!(message.contains("distinct normals"), "{message}")
        }
        other => panic!(
            "expected a parse error, got {:?}",
            other.map(|m| m.vertices_imported)
        ),
    }
    let f = TempFile::new("normals600.dae", distinct_normals(600).as_bytes());
    let dae = load_collada(&f.path).expect("600 distinct normals load");
    assert_eq!((dae.vertices_imported, dae.triangles_imported), (600, 200));
}

/// The cube inside `levels` nested `<node>` elements.
fn nested_nodes(levels: usize) -> String {
    let cube = cube_with_count("24");
    let head = &cube[..cube.find("<library_visual_scenes>").unwrap()];
    format!(
        r##"{head}<library_visual_scenes><visual_scene id="s">{}<instance_geometry url="#c"/>{}</visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"##,
        "<node>".repeat(levels),
        "</node>".repeat(levels)
    )
}

/// Found while fuzzing (dae, a crash): a thousand nested `<node>` elements overflowed the
/// stack (the XML tree is built, parsed and dropped recursively), which aborts the process.
/// Nesting is now measured on the text first; moderate nesting still loads.
#[test]
fn collada_deep_nesting_is_refused_not_a_stack_overflow() {
    for levels in [1_000, 100_000] {
        let f = TempFile::new("deep.dae", nested_nodes(levels).as_bytes());
        match load_mesh(&f.path) {
            Err(SceneError::Parse { message, .. }) => {
                assert!(message.contains("nest deeper"), "{levels}: {message}")
            }
            other => panic!("{levels} levels: expected a parse error, got {other:?}"),
        }
    }
    let f = TempFile::new("nested20.dae", nested_nodes(20).as_bytes());
    let mesh = load_mesh(&f.path).expect("20 nested nodes load");
    assert_eq!((mesh.vertices.len(), mesh.triangles.len()), (8, 12));
}
