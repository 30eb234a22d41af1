//! A small glTF 2.0 binary (`.glb`) writer: one buffer, tightly packed accessors, TRS nodes,
//! linear animations. Only what the exporter needs, so no glTF crate is pulled in; the JSON
//! chunk is written with `serde_json`. The files it writes pass the Khronos validator
//! (`tests/export_gltf.rs`).

use serde_json::{json, Value};

/// `bufferView.target` for vertex attributes.
const ARRAY_BUFFER: u32 = 34962;
/// `bufferView.target` for indices.
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
/// `accessor.componentType` FLOAT.
const FLOAT: u32 = 5126;
/// `accessor.componentType` UNSIGNED_INT.
const UNSIGNED_INT: u32 = 5125;

/// How a primitive's vertices are joined (glTF `primitive.mode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Each vertex a point (roadmap nodes).
    Points = 0,
    /// Vertex pairs as segments (roadmap edges).
    Lines = 1,
    /// One polyline through all vertices (a path's trace).
    LineStrip = 3,
    /// Index triples as triangles (meshes).
    Triangles = 4,
}

/// A node's transform: translation, unit quaternion `[x, y, z, w]` (glTF's order, which is
/// also OMPL's), scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trs {
    /// Translation.
    pub translation: [f64; 3],
    /// Rotation as a unit quaternion, scalar last.
    pub rotation: [f64; 4],
}

impl Trs {
    /// No motion.
    pub const IDENTITY: Trs = Trs {
        translation: [0.0; 3],
        rotation: [0.0, 0.0, 0.0, 1.0],
    };
}

/// One animated property of one node: times (seconds, strictly increasing) and values.
#[derive(Clone, Debug, Default)]
pub struct Track {
    /// Key times in seconds.
    pub times: Vec<f32>,
    /// Translations at the key times.
    pub translations: Vec<[f32; 3]>,
    /// Rotations `[x, y, z, w]` at the key times.
    pub rotations: Vec<[f32; 4]>,
}

/// A glTF document under construction; [`Gltf::to_glb`] packs it.
#[derive(Default)]
pub struct Gltf {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
    materials: Vec<Value>,
    meshes: Vec<Value>,
    nodes: Vec<Value>,
    children: Vec<Vec<usize>>,
    roots: Vec<usize>,
    channels: Vec<Value>,
    samplers: Vec<Value>,
    unlit: bool,
    extras: Value,
}

/// Min and max per component: glTF requires them on `POSITION` and animation inputs.
fn bounds<const N: usize>(data: &[[f32; N]]) -> (Vec<f32>, Vec<f32>) {
    let mut lo = vec![f32::INFINITY; N];
    let mut hi = vec![f32::NEG_INFINITY; N];
    for v in data {
        for i in 0..N {
            lo[i] = lo[i].min(v[i]);
            hi[i] = hi[i].max(v[i]);
        }
    }
    (lo, hi)
}

impl Gltf {
    /// An empty document.
    pub fn new() -> Gltf {
        Gltf::default()
    }

    /// Application data stored in the asset's `extras` (the viewer's legend reads it there).
    pub fn set_extras(&mut self, extras: Value) {
        self.extras = extras;
    }

    /// Appends bytes as a buffer view, 4-byte aligned (every accessor here has 4-byte
    /// components, which glTF requires to be aligned).
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        let mut v = json!({ "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len() });
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    fn float_accessor<const N: usize>(
        &mut self,
        data: &[[f32; N]],
        kind: &str,
        target: Option<u32>,
        with_bounds: bool,
    ) -> usize {
        let bytes: Vec<u8> = data
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let view = self.view(&bytes, target);
        let mut a = json!({
            "bufferView": view, "componentType": FLOAT, "count": data.len(), "type": kind,
        });
        if with_bounds {
            let (lo, hi) = bounds(data);
            a["min"] = json!(lo);
            a["max"] = json!(hi);
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    fn index_accessor(&mut self, indices: &[u32]) -> usize {
        let bytes: Vec<u8> = indices.iter().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes, Some(ELEMENT_ARRAY_BUFFER));
        self.accessors.push(json!({
            "bufferView": view, "componentType": UNSIGNED_INT, "count": indices.len(),
            "type": "SCALAR",
        }));
        self.accessors.len() - 1
    }

    /// A material of colour `rgba` (linear, 0–1). Unlit materials (lines, points) use
    /// `KHR_materials_unlit`, so that lines keep their colour whatever the lighting.
    pub fn material(&mut self, name: &str, rgba: [f32; 4], unlit: bool) -> usize {
        let mut m = json!({
            "name": name,
            "pbrMetallicRoughness": {
                "baseColorFactor": rgba, "metallicFactor": 0.0, "roughnessFactor": 0.8,
            },
            // meshes from SketchUp (OMPL.app) have both windings, others one: both faces drawn
            "doubleSided": true,
        });
        if rgba[3] < 1.0 {
            m["alphaMode"] = json!("BLEND");
        }
        if unlit {
            m["extensions"] = json!({ "KHR_materials_unlit": {} });
            self.unlit = true;
        }
        self.materials.push(m);
        self.materials.len() - 1
    }

    /// A mesh of one primitive: `positions`, joined per `mode` (by `indices` if given).
    /// Returns `None` for an empty primitive (glTF forbids accessors of count 0).
    pub fn mesh(
        &mut self,
        name: &str,
        positions: &[[f32; 3]],
        indices: Option<&[u32]>,
        mode: Mode,
        material: usize,
    ) -> Option<usize> {
        if positions.is_empty() || indices.is_some_and(<[u32]>::is_empty) {
            return None;
        }
        let pos = self.float_accessor(positions, "VEC3", Some(ARRAY_BUFFER), true);
        let mut prim = json!({
            "attributes": { "POSITION": pos }, "mode": mode as u32, "material": material,
        });
        if let Some(ix) = indices {
            prim["indices"] = json!(self.index_accessor(ix));
        }
        self.meshes
            .push(json!({ "name": name, "primitives": [prim] }));
        Some(self.meshes.len() - 1)
    }

    /// A node with an optional mesh and a transform, under `parent` (or at the root).
    pub fn node(
        &mut self,
        name: &str,
        mesh: Option<usize>,
        trs: Trs,
        parent: Option<usize>,
    ) -> usize {
        let mut n = json!({ "name": name });
        if let Some(m) = mesh {
            n["mesh"] = json!(m);
        }
        if trs.translation != [0.0; 3] {
            n["translation"] = json!(trs.translation);
        }
        if trs.rotation != [0.0, 0.0, 0.0, 1.0] {
            n["rotation"] = json!(trs.rotation);
        }
        self.nodes.push(n);
        self.children.push(Vec::new());
        let id = self.nodes.len() - 1;
        match parent {
            Some(p) => self.children[p].push(id),
            None => self.roots.push(id),
        }
        id
    }

    /// Animates `node`'s translation and rotation along `track` (linear interpolation, which
    /// three.js and other viewers do as slerp for rotations). Tracks of fewer than two keys
    /// are left out.
    pub fn animate(&mut self, node: usize, track: &Track) {
        if track.times.len() < 2 {
            return;
        }
        let times: Vec<[f32; 1]> = track.times.iter().map(|t| [*t]).collect();
        let input = self.float_accessor(&times, "SCALAR", None, true);
        for (path, output) in [
            (
                "translation",
                self.float_accessor(&track.translations, "VEC3", None, false),
            ),
            (
                "rotation",
                self.float_accessor(&track.rotations, "VEC4", None, false),
            ),
        ] {
            self.samplers
                .push(json!({ "input": input, "output": output, "interpolation": "LINEAR" }));
            self.channels.push(json!({
                "sampler": self.samplers.len() - 1,
                "target": { "node": node, "path": path },
            }));
        }
    }

    /// The document as JSON (buffer length filled in, nothing embedded).
    fn document(&self) -> Value {
        let mut nodes = self.nodes.clone();
        for (n, ch) in nodes.iter_mut().zip(&self.children) {
            if !ch.is_empty() {
                n["children"] = json!(ch);
            }
        }
        let mut doc = json!({
            "asset": { "version": "2.0", "generator": concat!("viaroad ", env!("CARGO_PKG_VERSION")) },
            "scene": 0,
            "scenes": [{ "name": "viaroad", "nodes": self.roots }],
            "nodes": nodes,
        });
        if !self.extras.is_null() {
            doc["asset"]["extras"] = self.extras.clone();
        }
        let mut put = |key: &str, v: &Vec<Value>| {
            if !v.is_empty() {
                doc[key] = json!(v);
            }
        };
        put("meshes", &self.meshes);
        put("materials", &self.materials);
        put("accessors", &self.accessors);
        put("bufferViews", &self.views);
        if !self.bin.is_empty() {
            doc["buffers"] = json!([{ "byteLength": self.padded_bin_len() }]);
        }
        if !self.channels.is_empty() {
            doc["animations"] = json!([{
                "name": "path", "channels": self.channels, "samplers": self.samplers,
            }]);
        }
        if self.unlit {
            doc["extensionsUsed"] = json!(["KHR_materials_unlit"]);
        }
        doc
    }

    fn padded_bin_len(&self) -> usize {
        self.bin.len().div_ceil(4) * 4
    }

    /// The binary glTF: a 12-byte header, the JSON chunk (padded with spaces), the BIN chunk
    /// (padded with zeros), every chunk 4-byte aligned (glTF 2.0 §4.4).
    pub fn to_glb(&self) -> Vec<u8> {
        let mut json_bytes = serde_json::to_vec(&self.document()).expect("JSON of plain values");
        while json_bytes.len() % 4 != 0 {
            json_bytes.push(b' ');
        }
        let mut bin = self.bin.clone();
        bin.resize(self.padded_bin_len(), 0);
        let bin_chunk = if bin.is_empty() { 0 } else { 8 + bin.len() };
        let total = 12 + 8 + json_bytes.len() + bin_chunk;
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(json_bytes.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&json_bytes);
        if !bin.is_empty() {
            out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
            out.extend_from_slice(b"BIN\0");
            out.extend_from_slice(&bin);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reads the JSON chunk back from a GLB, checking the header and chunk lengths.
    fn json_of(glb: &[u8]) -> Value {
        assert_eq!(&glb[0..4], b"glTF");
        let total = u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize;
        assert_eq!(total, glb.len());
        let jlen = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
        assert_eq!(&glb[16..20], b"JSON");
        assert_eq!(jlen % 4, 0);
        let rest = &glb[20 + jlen..];
        if !rest.is_empty() {
            let blen = u32::from_le_bytes(rest[0..4].try_into().unwrap()) as usize;
            assert_eq!(&rest[4..8], b"BIN\0");
            assert_eq!(blen + 8, rest.len());
            assert_eq!(blen % 4, 0);
        }
        serde_json::from_slice(&glb[20..20 + jlen]).unwrap()
    }

    #[test]
    fn triangle_round_trips_through_the_container() {
        let mut g = Gltf::new();
        let m = g.material("grey", [0.5, 0.5, 0.5, 1.0], false);
        let mesh = g.mesh(
            "tri",
            &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, -1.0]],
            Some(&[0, 1, 2]),
            Mode::Triangles,
            m,
        );
        let n = g.node("tri", mesh, Trs::IDENTITY, None);
        g.animate(
            n,
            &Track {
                times: vec![0.0, 1.0],
                translations: vec![[0.0; 3], [1.0, 0.0, 0.0]],
                rotations: vec![[0.0, 0.0, 0.0, 1.0]; 2],
            },
        );
        let glb = g.to_glb();
        let doc = json_of(&glb);
        assert_eq!(doc["accessors"][0]["min"], json!([0.0, 0.0, -1.0]));
        assert_eq!(doc["accessors"][0]["max"], json!([1.0, 2.0, 0.0]));
        assert_eq!(
            doc["animations"][0]["channels"].as_array().unwrap().len(),
            2
        );
        // every view lies inside the buffer and starts 4-byte aligned
        let blen = doc["buffers"][0]["byteLength"].as_u64().unwrap();
        for v in doc["bufferViews"].as_array().unwrap() {
            let (o, l) = (
                v["byteOffset"].as_u64().unwrap(),
                v["byteLength"].as_u64().unwrap(),
            );
            assert_eq!(o % 4, 0);
            assert!(o + l <= blen);
        }
    }

    #[test]
    fn empty_primitives_are_left_out() {
        let mut g = Gltf::new();
        let m = g.material("x", [1.0; 4], true);
        assert_eq!(g.mesh("none", &[], None, Mode::Points, m), None);
        assert_eq!(g.mesh("none", &[[0.0; 3]], Some(&[]), Mode::Lines, m), None);
        let doc = json_of(&g.to_glb());
        assert!(doc.get("meshes").is_none());
        assert_eq!(doc["extensionsUsed"], json!(["KHR_materials_unlit"]));
    }
}
