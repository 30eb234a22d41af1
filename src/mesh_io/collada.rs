//! Collada (`.dae`) meshes, read the way OMPL.app reads them through assimp.
//!
//! OMPL.app's problems (`scenes/ompl/`) are SketchUp exports. Two things must match what
//! OMPL.app computes, or the shipped start, goal and path states are off:
//!
//! - **The frame.** Node transforms are applied (`<matrix>`, `<translate>`, `<rotate>`,
//!   `<scale>`, `<skew>`, `<lookat>`, nested nodes, `<instance_node>`), then the document's
//!   `<unit>` scale and its `<up_axis>` conversion to Y-up as assimp does it: `Z_UP` maps file
//!   `(x, y, z)` to `(x, z, −y)`, `X_UP` maps it to `(−y, x, z)`.
//! - **The robot centre** ([`ColladaMesh::assimp_centre`]). OMPL.app shifts the robot so that
//!   the mean of all vertices assimp imports is its reference point. Assimp makes one mesh per
//!   primitive element (`<triangles>`, `<lines>` …) and geometry instance, gives every index
//!   tuple of `<p>` a vertex of its own, generates flat face normals where the file has none
//!   (`aiProcess_GenNormals`) and then merges the vertices of each mesh whose position,
//!   normal, texture coordinates and colours agree (`aiProcess_JoinIdenticalVertices`,
//!   attributes within 1e-5). Line primitives (SketchUp's edges) are meshes too and count. The
//!   sum is taken in `f32` with the `f32` node transforms, as assimp does. Replicating this
//!   matters: for `alpha_robot.dae` a plain mean of the distinct vertices is 0.09 away.
//!
//! Only faces become geometry: triangles, triangle strips and fans, and polygons (`<polylist>`,
//! `<polygons>`, triangulated by ear clipping in their plane); lines are not faces.
//! `<polygons>` with holes (`<ph>`) are refused, as assimp does not read them either.
//! Controllers (skinned meshes) are ignored.

use super::input::{read_input, MeshError};
use super::weld::Welder;
use crate::fast_hash::FastMap;
use crate::geometry::TriMesh;
use dae_parser::{
    ArrayElement, Document, Geometry, Input, InputList, LocalMap, Node, Primitive, Semantic,
    Source, Transform, UpAxis, Vertices, VisualScene,
};
use nalgebra::{Matrix4, Point3, Vector3};
use std::path::Path;

/// A Collada mesh in OMPL.app's frame, with what OMPL.app derives from it.
#[derive(Clone, Debug, PartialEq)]
pub struct ColladaMesh {
    /// All faces in the world frame (node transforms, unit and up axis applied), vertices with
    /// equal positions welded, triangles of zero area dropped.
    pub mesh: TriMesh,
    /// Triangles as assimp imports them (every face instance, duplicates and degenerate ones
    /// included): the number OMPL.app hands to its collision checker.
    pub triangles_imported: usize,
    /// Vertices assimp keeps after `JoinIdenticalVertices`, over all mesh instances, line
    /// primitives included.
    pub vertices_imported: usize,
    /// Mean of those vertices in the world frame, accumulated in `f32` like assimp: OMPL.app's
    /// robot centre (`RigidBodyGeometry::getRobotCenter`; OMPL.app zeroes its z for 2D
    /// problems).
    pub assimp_centre: [f32; 3],
}

/// Reads a Collada file (see the module documentation for the conventions).
pub fn load_collada(path: &Path) -> Result<ColladaMesh, MeshError> {
    let text = read_input(path)?;
    let fail = |message: String| MeshError::Parse {
        path: path.to_path_buf(),
        message,
    };
    let xml = std::str::from_utf8(&text)
        .map_err(|e| fail(format!("not a Collada document: not UTF-8 text ({e})")))?;
    check_before_parsing(xml).map_err(fail)?;
    // dae-parser validates eagerly and reports errors, but it is third-party code reading
    // user input: a panic inside it must not escape as one.
    let parsed = std::panic::catch_unwind(|| Document::try_from(text.as_slice()))
        .map_err(|_| fail("not a readable Collada document (the parser gave up)".into()))?;
    let doc = parsed.map_err(|e| fail(format!("not a valid Collada 1.4.1 document: {e:?}")))?;
    let out = read_document(&doc, text.len()).map_err(fail)?;
    let n = out.centre_count as f32;
    Ok(ColladaMesh {
        mesh: out.faces.finish(path)?,
        triangles_imported: out.triangles_imported,
        vertices_imported: out.centre_count,
        assimp_centre: out.centre_sum.map(|c| c / n),
    })
}

/// The deepest element nesting accepted: [`MAX_DEPTH`] nodes and room for what sits around and
/// inside them.
const MAX_XML_DEPTH: usize = MAX_DEPTH + 32;

/// What dae-parser cannot be trusted with, refused before it sees the document (both found by
/// fuzzing, see `tests/fuzz_regressions.rs`):
/// - an array (`<float_array count="…">` …) whose `count` exceeds the values it holds:
///   dae-parser reserves `count` elements up front, so a huge count in a small file would
///   allocate without bound;
/// - elements nested deeper than [`MAX_XML_DEPTH`]: the XML tree is built and dropped
///   recursively and dae-parser recurses once per `<node>` level, so a thousand nested nodes
///   overflowed the stack (an abort, not an error). The depth is measured on the text
///   ([`xml_depth_exceeds`]) before any tree is built.
///
/// Malformed XML is left to dae-parser to report.
fn check_before_parsing(xml: &str) -> Result<(), String> {
    if xml_depth_exceeds(xml.as_bytes(), MAX_XML_DEPTH) {
        return Err(format!("elements nest deeper than {MAX_XML_DEPTH} levels"));
    }
    let Ok(root) = xml.parse::<dae_parser::Element>() else {
        return Ok(());
    };
    let mut stack = vec![&root];
    while let Some(e) = stack.pop() {
        if e.name().ends_with("_array") {
            if let Some(count) = e.attr("count").and_then(|c| c.trim().parse::<u64>().ok()) {
                let held: usize = e.texts().map(|t| t.split_ascii_whitespace().count()).sum();
                if count > held as u64 {
                    return Err(format!(
                        "<{} count=\"{count}\"> holds only {held} values",
                        e.name()
                    ));
                }
            }
        }
        stack.extend(e.children());
    }
    Ok(())
}

/// Whether the elements of `xml` nest deeper than `limit`, from the text alone: comments,
/// CDATA, processing instructions and declarations are skipped, quotes inside tags respected
/// and self-closing tags do not nest. Text cannot hold a raw `<`, so well-formed XML is
/// measured exactly; for malformed XML the answer does not matter (the parser refuses it).
fn xml_depth_exceeds(xml: &[u8], limit: usize) -> bool {
    let find = |from: usize, pat: &[u8]| {
        xml.get(from..)
            .and_then(|rest| rest.windows(pat.len()).position(|w| w == pat))
            .map(|k| from + k + pat.len())
    };
    let (mut i, mut depth) = (0, 0usize);
    while let Some(k) = xml[i..].iter().position(|&b| b == b'<') {
        i += k + 1;
        let rest = &xml[i..];
        let skip_to = if rest.starts_with(b"!--") {
            find(i, b"-->")
        } else if rest.starts_with(b"![CDATA[") {
            find(i, b"]]>")
        } else if rest.starts_with(b"?") || rest.starts_with(b"!") {
            find(i, b">")
        } else if rest.starts_with(b"/") {
            depth = depth.saturating_sub(1);
            find(i, b">")
        } else {
            let mut quote = None;
            let mut j = i;
            while j < xml.len() {
                match (quote, xml[j]) {
                    (Some(q), c) if c == q => quote = None,
                    (None, c @ (b'"' | b'\'')) => quote = Some(c),
                    (None, b'>') => break,
                    _ => {}
                }
                j += 1;
            }
            if j > i && xml.get(j - 1) != Some(&b'/') {
                depth += 1;
                if depth > limit {
                    return true;
                }
            }
            Some(j + 1)
        };
        match skip_to {
            Some(next) if next <= xml.len() => i = next,
            _ => return false,
        }
    }
    false
}

/// Library look-ups by id.
struct Maps<'a> {
    geometry: LocalMap<'a, Geometry>,
    node: LocalMap<'a, Node>,
    source: LocalMap<'a, Source>,
    vertices: LocalMap<'a, Vertices>,
}

/// What the traversal accumulates.
#[derive(Default)]
struct Collector {
    faces: Welder,
    triangles_imported: usize,
    centre_sum: [f32; 3],
    centre_count: usize,
    /// Node visits left: `<instance_node>` can instantiate a node twice, which instantiates
    /// the next twice … (2⁶⁴ visits within [`MAX_DEPTH`] levels).
    visits_left: usize,
    /// Primitive indices that may still be read, counting every instantiation.
    indices_left: usize,
    /// Attribute comparisons left for joining vertices: each index tuple is compared with the
    /// distinct ones at its position, quadratic when one position has many distinct normals.
    comparisons_left: usize,
}

/// Nesting deeper than this is taken for a cycle of `<instance_node>` references.
const MAX_DEPTH: usize = 64;

/// Work allowed per byte of the file: without instancing a node takes more than ten bytes and
/// an index at least two, so these bounds only stop exponential instancing (found by
/// fuzzing; see `tests/fuzz_regressions.rs`) while memory and time stay proportional to the
/// file's size.
const VISITS_PER_BYTE: usize = 1;
/// See [`VISITS_PER_BYTE`].
const INDICES_PER_BYTE: usize = 2;
/// See [`VISITS_PER_BYTE`].
const COMPARISONS_PER_BYTE: usize = 64;
/// Work always allowed, whatever the file's size.
const MIN_WORK: usize = 1_000_000;

fn read_document(doc: &Document, file_bytes: usize) -> Result<Collector, String> {
    let err = |e: dae_parser::Error| format!("{e:?}");
    let maps = Maps {
        geometry: doc.local_map().map_err(err)?,
        node: doc.local_map().map_err(err)?,
        source: doc.local_map().map_err(err)?,
        vertices: doc.local_map().map_err(err)?,
    };
    let scenes: LocalMap<VisualScene> = doc.local_map().map_err(err)?;
    let scene = match doc
        .scene
        .as_ref()
        .and_then(|s| s.instance_visual_scene.as_ref())
    {
        Some(instance) => scenes
            .get(&instance.url)
            .ok_or_else(|| format!("<scene> refers to a missing visual scene {}", instance.url))?,
        None => doc
            .iter::<VisualScene>()
            .next()
            .ok_or("the document has no visual scene")?,
    };
    // assimp: root transform ·= unit scale, then ·= the up-axis conversion to Y-up
    let s = doc.asset.unit.meter;
    if !(s.is_finite() && s > 0.0) {
        return Err(format!("<unit meter=\"{s}\"> is not a positive number"));
    }
    let up: Matrix4<f32> = match doc.asset.up_axis {
        UpAxis::YUp => Matrix4::identity(),
        UpAxis::ZUp => Matrix4::new(
            1.0, 0.0, 0.0, 0.0, //
            0.0, 0.0, 1.0, 0.0, //
            0.0, -1.0, 0.0, 0.0, //
            0.0, 0.0, 0.0, 1.0,
        ),
        UpAxis::XUp => Matrix4::new(
            0.0, -1.0, 0.0, 0.0, //
            1.0, 0.0, 0.0, 0.0, //
            0.0, 0.0, 1.0, 0.0, //
            0.0, 0.0, 0.0, 1.0,
        ),
    };
    let root = Matrix4::new_scaling(s) * up;
    let mut out = Collector {
        visits_left: MIN_WORK.saturating_add(file_bytes.saturating_mul(VISITS_PER_BYTE)),
        indices_left: MIN_WORK.saturating_add(file_bytes.saturating_mul(INDICES_PER_BYTE)),
        comparisons_left: MIN_WORK.saturating_add(file_bytes.saturating_mul(COMPARISONS_PER_BYTE)),
        ..Collector::default()
    };
    for node in &scene.nodes {
        visit(node, &root, &maps, &mut out, 0)?;
    }
    if out.centre_count == 0 {
        return Err("the visual scene instantiates no geometry".into());
    }
    Ok(out)
}

fn visit(
    node: &Node,
    parent: &Matrix4<f32>,
    maps: &Maps,
    out: &mut Collector,
    depth: usize,
) -> Result<(), String> {
    if depth > MAX_DEPTH {
        return Err(format!(
            "nodes nest deeper than {MAX_DEPTH} levels (a cycle of <instance_node>?)"
        ));
    }
    out.visits_left = out.visits_left.checked_sub(1).ok_or(
        "<instance_node> instantiates far more nodes than the file holds (nodes instantiated \
         over and over)",
    )?;
    let mut m = *parent;
    for t in &node.transforms {
        m *= transform_matrix(t)?;
    }
    for instance in &node.instance_geometry {
        let geometry = maps
            .geometry
            .get(&instance.url)
            .ok_or_else(|| format!("<instance_geometry> refers to a missing {}", instance.url))?;
        if let Some(mesh) = geometry.element.as_mesh() {
            for primitive in &mesh.elements {
                read_primitive(primitive, mesh.vertices.as_ref(), &m, maps, out)?;
            }
        }
    }
    for child in &node.children {
        visit(child, &m, maps, out, depth + 1)?;
    }
    for instance in &node.instance_node {
        let child = maps
            .node
            .get(&instance.url)
            .ok_or_else(|| format!("<instance_node> refers to a missing {}", instance.url))?;
        visit(child, &m, maps, out, depth + 1)?;
    }
    Ok(())
}

/// The matrix of one Collada transform element (angles in degrees; `<matrix>` row-major).
fn transform_matrix(t: &Transform) -> Result<Matrix4<f32>, String> {
    let m = match t {
        Transform::Matrix(m) => Matrix4::from_row_slice(&m.0[..]),
        Transform::Translate(v) => Matrix4::new_translation(&Vector3::from(*v.0)),
        Transform::Scale(v) => Matrix4::new_nonuniform_scaling(&Vector3::from(*v.0)),
        Transform::Rotate(r) => {
            let axis = Vector3::from(*r.axis());
            if axis.norm() == 0.0 {
                Matrix4::identity()
            } else {
                let axis = nalgebra::Unit::new_normalize(axis);
                Matrix4::from_axis_angle(&axis, r.angle().to_radians())
            }
        }
        Transform::LookAt(l) => {
            // the camera frame: x = right, y = up, z = −(view direction), origin at the eye
            let eye = Vector3::from(*l.eye());
            let dir = (Vector3::from(*l.target()) - eye).normalize();
            let right = dir.cross(&Vector3::from(*l.up())).normalize();
            let up = right.cross(&dir);
            Matrix4::new(
                right.x, up.x, -dir.x, eye.x, //
                right.y, up.y, -dir.y, eye.y, //
                right.z, up.z, -dir.z, eye.z, //
                0.0, 0.0, 0.0, 1.0,
            )
        }
        Transform::Skew(s) => {
            // Collada/RenderMan skew: p' = p + tan(angle)·(p·a)·r, a ⟂-projected onto r
            let r = Vector3::from(*s.axis()).normalize();
            let a = Vector3::from(*s.trans()).normalize();
            let k = s.angle().to_radians().tan();
            let mut m = Matrix4::identity();
            for i in 0..3 {
                for j in 0..3 {
                    m[(i, j)] += k * r[i] * a[j];
                }
            }
            m
        }
    };
    if m.iter().all(|v| v.is_finite()) {
        Ok(m)
    } else {
        Err("a node transform is not finite".into())
    }
}

/// One attribute stream of a primitive: where its index sits in an index tuple and the values.
struct Stream<'a> {
    offset: usize,
    source: &'a Source,
    values: &'a [f32],
}

impl Stream<'_> {
    /// Up to 4 components of element `i`, zero-padded.
    fn get(&self, i: u32) -> Result<[f32; 4], String> {
        let a = &self.source.accessor;
        let width = a.param.len().min(a.stride).min(4);
        let i = i as usize;
        if i >= a.count {
            return Err(format!(
                "index {i} is out of range of source {} ({} elements)",
                self.source.id.as_deref().unwrap_or("?"),
                a.count
            ));
        }
        let start = i
            .checked_mul(a.stride)
            .and_then(|k| k.checked_add(a.offset))
            .unwrap_or(usize::MAX);
        let slice = self
            .values
            .get(start..start.saturating_add(width))
            .ok_or_else(|| {
                format!(
                    "source {} is shorter than its accessor says",
                    self.source.id.as_deref().unwrap_or("?")
                )
            })?;
        let mut v = [0.0; 4];
        v[..width].copy_from_slice(slice);
        Ok(v)
    }
}

fn stream<'a>(input: &'a Input, offset: usize, maps: &Maps<'a>) -> Result<Stream<'a>, String> {
    let source = maps
        .source
        .get_raw(&input.source)
        .ok_or_else(|| format!("input refers to a missing source {}", input.source))?;
    let values = match &source.array {
        Some(ArrayElement::Float(a)) => &a.val[..],
        _ => {
            return Err(format!(
                "source {} holds no float array",
                source.id.as_deref().unwrap_or("?")
            ))
        }
    };
    Ok(Stream {
        offset,
        source,
        values,
    })
}

/// How the index tuples of a primitive form faces or lines, as assimp builds them.
enum Shape {
    /// Polygons (triangles have 3 vertices), given by their vertex counts.
    Faces(Vec<usize>),
    /// Line segments, two vertices each.
    Lines,
}

/// The index data of a primitive as (inputs, tuples of indices, shape). Strips and fans are
/// turned into the faces assimp makes of them (strips: one triangle each, with copied
/// vertices; fans: one polygon).
fn indices(primitive: &Primitive) -> Result<(&InputList, Vec<u32>, Shape), String> {
    let flat = |p: &Option<Box<[u32]>>| p.as_deref().unwrap_or(&[]).to_vec();
    Ok(match primitive {
        Primitive::Triangles(t) => {
            let s = t.inputs.stride.max(1);
            let data = flat(&t.data.prim);
            let n = data.len() / s;
            if n % 3 != 0 {
                return Err(format!(
                    "<triangles> has {n} index tuples, not a multiple of 3"
                ));
            }
            (&t.inputs, data, Shape::Faces(vec![3; n / 3]))
        }
        Primitive::Lines(l) => {
            let s = l.inputs.stride.max(1);
            let data = flat(&l.data.prim);
            if (data.len() / s) % 2 != 0 {
                return Err("<lines> has an odd number of index tuples".into());
            }
            (&l.inputs, data, Shape::Lines)
        }
        Primitive::LineStrips(l) => {
            let s = l.inputs.stride.max(1);
            let mut data = Vec::new();
            for strip in &l.data.prim {
                let tuples: Vec<&[u32]> = strip.chunks(s).collect();
                for w in tuples.windows(2) {
                    data.extend_from_slice(w[0]);
                    data.extend_from_slice(w[1]);
                }
            }
            (&l.inputs, data, Shape::Lines)
        }
        Primitive::PolyList(p) => {
            let counts: Vec<usize> = p.data.vcount.iter().map(|&c| c as usize).collect();
            (&p.inputs, p.data.prim.to_vec(), Shape::Faces(counts))
        }
        Primitive::Polygons(p) => {
            let s = p.inputs.stride.max(1);
            let mut data = Vec::new();
            let mut counts = Vec::new();
            for polygon in &p.data.0 {
                if !polygon.hole.is_empty() {
                    return Err("<polygons> with holes (<ph>) are not supported".into());
                }
                data.extend_from_slice(&polygon.verts);
                counts.push(polygon.verts.len() / s);
            }
            (&p.inputs, data, Shape::Faces(counts))
        }
        Primitive::TriFans(f) => {
            let s = f.inputs.stride.max(1);
            let mut data = Vec::new();
            let mut counts = Vec::new();
            for fan in &f.data.prim {
                data.extend_from_slice(fan);
                counts.push(fan.len() / s);
            }
            (&f.inputs, data, Shape::Faces(counts))
        }
        Primitive::TriStrips(t) => {
            let s = t.inputs.stride.max(1);
            let mut data = Vec::new();
            let mut counts = Vec::new();
            for strip in &t.data.prim {
                let tuples: Vec<&[u32]> = strip.chunks(s).collect();
                for (k, w) in tuples.windows(3).enumerate() {
                    // every other triangle of a strip is flipped to keep the winding
                    let order = if k % 2 == 0 { [0, 1, 2] } else { [1, 0, 2] };
                    for o in order {
                        data.extend_from_slice(w[o]);
                    }
                    counts.push(3);
                }
            }
            (&t.inputs, data, Shape::Faces(counts))
        }
    })
}

/// Reads one primitive element of one geometry instance: its faces into the mesh, its
/// joined vertices into the centre.
fn read_primitive(
    primitive: &Primitive,
    mesh_vertices: Option<&Vertices>,
    m: &Matrix4<f32>,
    maps: &Maps,
    out: &mut Collector,
) -> Result<(), String> {
    let (inputs, data, shape) = indices(primitive)?;
    out.indices_left = out.indices_left.checked_sub(data.len()).ok_or(
        "the nodes instantiate far more geometry than the file holds (geometry instantiated \
         over and over)",
    )?;
    let stride = inputs.stride;
    if stride == 0 || data.is_empty() {
        return Ok(()); // no inputs or no primitives: assimp makes no mesh of it
    }
    if data.len() % stride != 0 {
        return Err(format!(
            "a primitive has {} indices, not a multiple of its {stride} inputs",
            data.len()
        ));
    }
    let streams = Streams::of(inputs, mesh_vertices, maps)?;
    let (local, mut attrs) = streams.vertices(&data, stride)?;
    let generated = add_faces(&shape, &local, m, !streams.has_normals, out)?;
    for (a, g) in attrs.iter_mut().zip(generated) {
        a.extend(g);
    }
    join_identical(&local, &attrs, m, out)
}

/// One vertex per index tuple: positions in the geometry's frame, and each vertex's other
/// attributes (up to 4 components each).
type TupleVertices = (Vec<[f32; 3]>, Vec<Vec<[f32; 4]>>);

/// A primitive's position stream and its other attribute streams, in input order.
struct Streams<'a> {
    position: Stream<'a>,
    attributes: Vec<Stream<'a>>,
    /// Whether the file gives normals (else flat ones are made, as assimp makes them).
    has_normals: bool,
}

impl<'a> Streams<'a> {
    fn of(
        inputs: &'a InputList,
        mesh_vertices: Option<&'a Vertices>,
        maps: &Maps<'a>,
    ) -> Result<Streams<'a>, String> {
        let mut position = None;
        let mut attributes: Vec<Stream> = Vec::new();
        for input in inputs.iter() {
            let offset = input.offset as usize;
            match input.semantic {
                Semantic::Vertex => {
                    let vertices = maps
                        .vertices
                        .get_raw(&input.source)
                        .or(mesh_vertices)
                        .ok_or_else(|| {
                            format!("VERTEX input refers to a missing {}", input.source)
                        })?;
                    for v in &vertices.inputs {
                        let s = stream(v, offset, maps)?;
                        if v.semantic == Semantic::Position {
                            position = Some(s);
                        } else {
                            attributes.push(s);
                        }
                    }
                }
                _ => attributes.push(stream(input, offset, maps)?),
            }
        }
        let position = position.ok_or("a primitive has no POSITION input")?;
        let accessor = &position.source.accessor;
        if accessor.stride < 3 || accessor.param.len() < 3 {
            return Err(format!(
                "POSITION source {} has fewer than 3 components",
                position.source.id.as_deref().unwrap_or("?")
            ));
        }
        let has_normals = inputs.iter().any(|i| i.semantic == Semantic::Normal)
            || inputs.iter().any(|i| {
                i.semantic == Semantic::Vertex
                    && maps
                        .vertices
                        .get_raw(&i.source)
                        .or(mesh_vertices)
                        .is_some_and(|v| v.inputs.iter().any(|x| x.semantic == Semantic::Normal))
            });
        Ok(Streams {
            position,
            attributes,
            has_normals,
        })
    }

    /// One vertex per index tuple, as assimp's Collada importer makes them: its position in
    /// the geometry's frame and its other attributes.
    fn vertices(&self, data: &[u32], stride: usize) -> Result<TupleVertices, String> {
        let n = data.len() / stride;
        let mut local: Vec<[f32; 3]> = Vec::with_capacity(n);
        let mut attrs: Vec<Vec<[f32; 4]>> = Vec::with_capacity(n);
        for k in 0..n {
            let tuple = &data[k * stride..(k + 1) * stride];
            let p = self.position.get(tuple[self.position.offset])?;
            if !p[..3].iter().all(|c| c.is_finite()) {
                return Err("a vertex position is not a finite number".into());
            }
            local.push([p[0], p[1], p[2]]);
            attrs.push(
                self.attributes
                    .iter()
                    .map(|s| s.get(tuple[s.offset]))
                    .collect::<Result<_, _>>()?,
            );
        }
        Ok((local, attrs))
    }
}

/// Triangulates the faces into the mesh (f64, world frame). Returns the flat normal of each
/// vertex where `flat_normals` (the file has none): written per triangle to its vertices, a
/// later triangle of a polygon overwrites.
fn add_faces(
    shape: &Shape,
    local: &[[f32; 3]],
    m: &Matrix4<f32>,
    flat_normals: bool,
    out: &mut Collector,
) -> Result<Vec<Option<[f32; 4]>>, String> {
    let n = local.len();
    let world = m.cast::<f64>();
    let place = |p: [f32; 3]| world.transform_point(&Point3::from(p).cast::<f64>());
    let mut generated: Vec<Option<[f32; 4]>> = vec![None; n];
    if let Shape::Faces(counts) = shape {
        let mut first = 0;
        for &count in counts {
            if count < 3 || first + count > n {
                return Err(format!(
                    "a face has {count} vertices or runs past the index list"
                ));
            }
            let corners: Vec<Point3<f64>> =
                (first..first + count).map(|k| place(local[k])).collect();
            for [a, b, c] in triangulate(&corners) {
                let t = [a, b, c].map(|i| out.faces.vertex(corners[i].into()));
                out.faces.triangles.push(t);
                out.triangles_imported += 1;
                if flat_normals {
                    let normal = flat_normal(local[first + a], local[first + b], local[first + c]);
                    for i in [a, b, c] {
                        generated[first + i] = Some(normal);
                    }
                }
            }
            first += count;
        }
        if first != n {
            return Err("face vertex counts do not add up to the index list".into());
        }
    }
    Ok(generated)
}

/// assimp's JoinIdenticalVertices: equal position, then every attribute within 1e-5 (assimp's
/// squared epsilon 1e-10); the first match wins. Each vertex left counts towards the centre.
fn join_identical(
    local: &[[f32; 3]],
    attrs: &[Vec<[f32; 4]>],
    m: &Matrix4<f32>,
    out: &mut Collector,
) -> Result<(), String> {
    let same = |a: &[[f32; 4]], b: &[[f32; 4]]| {
        a.len() == b.len()
            && a.iter()
                .zip(b)
                .all(|(x, y)| x.iter().zip(y).map(|(u, v)| (u - v) * (u - v)).sum::<f32>() <= 1e-10)
    };
    let mut unique: FastMap<[u32; 3], Vec<usize>> = FastMap::default();
    for k in 0..local.len() {
        let key = local[k].map(|c| (c + 0.0).to_bits());
        let candidates = unique.entry(key).or_default();
        let mut joined = false;
        for &u in candidates.iter() {
            out.comparisons_left = out.comparisons_left.checked_sub(1).ok_or(
                "too many vertices with distinct normals or colours at one position (joining \
                 them would take time quadratic in the file's size)",
            )?;
            if same(&attrs[u], &attrs[k]) {
                joined = true;
                break;
            }
        }
        if !joined {
            candidates.push(k);
            let p = m.transform_point(&Point3::from(local[k]));
            for (s, c) in out.centre_sum.iter_mut().zip(p.coords.iter()) {
                *s += c;
            }
            out.centre_count += 1;
        }
    }
    Ok(())
}

/// assimp's flat face normal: `((v2 − v1) × (v3 − v1))` normalised, zero if degenerate.
fn flat_normal(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> [f32; 4] {
    let (a, b, c) = (Vector3::from(a), Vector3::from(b), Vector3::from(c));
    let n = (b - a).cross(&(c - a));
    let len = n.norm();
    let n = if len > 0.0 { n / len } else { n };
    [n.x, n.y, n.z, 0.0]
}

/// Triangulates a planar polygon (indices into `corners`): a triangle as it is, otherwise ear
/// clipping in the plane of the Newell normal; a fan if the polygon is degenerate or not
/// simple.
fn triangulate(corners: &[Point3<f64>]) -> Vec<[usize; 3]> {
    let n = corners.len();
    if n == 3 {
        return vec![[0, 1, 2]];
    }
    let fan = || (1..n - 1).map(|i| [0, i, i + 1]).collect::<Vec<_>>();
    let mut normal = Vector3::zeros();
    for i in 0..n {
        let (p, q) = (corners[i], corners[(i + 1) % n]);
        normal += Vector3::new(
            (p.y - q.y) * (p.z + q.z),
            (p.z - q.z) * (p.x + q.x),
            (p.x - q.x) * (p.y + q.y),
        );
    }
    if normal.norm() == 0.0 {
        return fan();
    }
    // drop the dominant axis of the normal; orient so that the polygon is counter-clockwise
    let axis = normal.iamax();
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let flip = normal[axis] < 0.0;
    let pt = |i: usize| {
        let (x, y) = (corners[i][u], corners[i][v]);
        if flip {
            (y, x)
        } else {
            (x, y)
        }
    };
    let cross = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
        (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
    };
    let mut ring: Vec<usize> = (0..n).collect();
    let mut out = Vec::with_capacity(n - 2);
    while ring.len() > 3 {
        let m = ring.len();
        let ear = (0..m).find(|&i| {
            let (a, b, c) = (ring[(i + m - 1) % m], ring[i], ring[(i + 1) % m]);
            if cross(pt(a), pt(b), pt(c)) <= 0.0 {
                return false;
            }
            ring.iter().all(|&k| {
                k == a
                    || k == b
                    || k == c
                    || cross(pt(a), pt(b), pt(k)) < 0.0
                    || cross(pt(b), pt(c), pt(k)) < 0.0
                    || cross(pt(c), pt(a), pt(k)) < 0.0
            })
        });
        let Some(i) = ear else {
            return fan();
        };
        let m = ring.len();
        out.push([ring[(i + m - 1) % m], ring[i], ring[(i + 1) % m]]);
        ring.remove(i);
    }
    out.push([ring[0], ring[1], ring[2]]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ear_clipping_handles_a_concave_polygon() {
        // an L: the fan from vertex 0 would cover the notch
        let l = [
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (0.0, 2.0),
        ]
        .map(|(x, y)| Point3::new(x, y, 0.0));
        let tris = triangulate(&l);
        assert_eq!(tris.len(), 4);
        let area: f64 = tris
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| l[i]);
                0.5 * (b - a).cross(&(c - a)).z
            })
            .sum();
        assert!((area - 3.0).abs() < 1e-12, "area {area}");
        assert!(tris.iter().all(|t| {
            let [a, b, c] = t.map(|i| l[i]);
            (b - a).cross(&(c - a)).z > 0.0
        }));
    }
}
