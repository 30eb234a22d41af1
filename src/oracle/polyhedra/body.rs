//! A mesh prepared for the edge–face predicate (CHS §2.1): the boundary representation the
//! seed asks for — faces with their planes, edges listed once, and a tree over the faces.
//!
//! Meshes from OMPL.app are triangle soups in which every triangle appears twice (once per
//! winding) and vertices are repeated. For *surface* contact the winding does not matter, so
//! vertices with identical coordinates are welded and every triangle is kept once; every edge
//! is listed once and *owned* by the first face that uses it, so that each edge–face pair is
//! evaluated once even though an edge borders several faces (a pair of faces is examined when
//! their boxes meet, and an edge's box lies inside its owner's).
//!
//! For *containment* (CHS §2.1, ray parity) what matters is how often a ray crosses the
//! surface, so there the multiplicity counts: a triangle that appears an even number of times
//! (a double-sided sheet) can never change the parity and is dropped, one that appears an odd
//! number of times is kept once. A double-sided soup therefore has no parity faces at all, and
//! containment is never reported for it — the surface-only behaviour of FCL on such meshes.

use super::pose::{Aabb, Bvh};
use crate::fast_hash::FastMap;
use crate::geometry::TriMesh;
use nalgebra::Vector3;
use std::sync::Arc;

type V3 = Vector3<f64>;

/// A face: its corners and its plane `n·x = offset` with `n = (v1 − v0) × (v2 − v0)` (not
/// normalised: the determinant identities of the predicate stay exact).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Face {
    /// Corners, counter-clockwise seen from the side `n` points to.
    pub v: [V3; 3],
    /// Normal, twice the area in length.
    pub n: V3,
    /// `n · v0`.
    pub offset: f64,
    /// `|n|`, which scales every tolerance of the predicate with this face.
    pub n_norm: f64,
    /// Edge vectors `v_{i+1} − v_i`.
    e: [V3; 3],
    /// Their lengths.
    pub e_len: [f64; 3],
}

impl Face {
    /// The face with corners `v`. The norms the predicate needs are computed here once, not
    /// per edge–face pair.
    pub fn new(v: [V3; 3]) -> Face {
        let n = (v[1] - v[0]).cross(&(v[2] - v[0]));
        let e = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
        Face {
            v,
            n,
            offset: n.dot(&v[0]),
            n_norm: n.norm(),
            e,
            e_len: e.map(|x| x.norm()),
        }
    }

    /// Edge vectors `v_{i+1} − v_i`.
    pub fn edges(&self) -> [V3; 3] {
        self.e
    }
}

/// One separate body (an obstacle, or the robot): what containment needs.
#[derive(Clone, Debug)]
pub(crate) struct Part {
    /// Whether containment applies: the mesh is closed ([`TriMesh::is_closed`]) and has faces
    /// that can change a ray's parity.
    pub solid: bool,
    /// Faces of odd multiplicity (indices into [`Body::vertices`]).
    pub parity: Arc<[[u32; 3]]>,
    /// Tree over `parity`.
    pub parity_bvh: Bvh,
    /// Box around the part.
    pub aabb: Aabb,
    /// A ball around the part: centre and radius (CHS §2.2: "approximations of smallest
    /// enclosing spheres are computed once for every object").
    pub sphere: (V3, f64),
    /// The connected pieces of `parity`: containment is tested with one point of each (a body
    /// of two separate boxes may have one inside an obstacle and the other outside).
    pub components: Vec<Component>,
}

/// A connected piece of a part's parity faces.
#[derive(Clone, Debug)]
pub(crate) struct Component {
    /// Indices into [`Part::parity`].
    pub faces: Arc<[u32]>,
    /// Box around the piece.
    pub aabb: Aabb,
}

/// Several meshes (the obstacles, or the one robot), welded, deduplicated and indexed.
#[derive(Clone, Debug)]
pub(crate) struct Body {
    /// Welded vertices.
    pub vertices: Vec<V3>,
    /// Faces, each geometric triangle once (shared with shifted copies, [`Body::shifted`]).
    pub faces: Arc<[[u32; 3]]>,
    /// Every face with its plane and norms, in this body's frame (the robot's faces never
    /// move in it, so they are prepared once).
    geo: Vec<Face>,
    /// Unique edges.
    pub edges: Arc<[[u32; 2]]>,
    /// `owned[owned_start[f]..owned_start[f + 1]]` are the edges owned by face `f`.
    owned_start: Arc<[u32]>,
    owned: Arc<[u32]>,
    /// Tree over `faces`.
    pub bvh: Bvh,
    /// The parts.
    pub parts: Vec<Part>,
    /// Box around everything.
    pub aabb: Aabb,
    /// Largest distance of a vertex from the origin.
    pub radius: f64,
}

fn key(p: &V3) -> [u64; 3] {
    // + 0.0 turns −0.0 into 0.0 so that both weld
    [
        (p.x + 0.0).to_bits(),
        (p.y + 0.0).to_bits(),
        (p.z + 0.0).to_bits(),
    ]
}

fn sorted(t: [u32; 3]) -> [u32; 3] {
    let mut s = t;
    s.sort_unstable();
    s
}

/// Connected pieces of `faces` (sharing a vertex), by union–find.
fn components(faces: &[[u32; 3]], boxes: &[Aabb]) -> Vec<Component> {
    let mut parent: FastMap<u32, u32> = FastMap::default();
    fn find(parent: &mut FastMap<u32, u32>, x: u32) -> u32 {
        let mut r = x;
        while let Some(&p) = parent.get(&r) {
            if p == r {
                break;
            }
            r = p;
        }
        // path compression
        let mut y = x;
        while y != r {
            let next = parent[&y];
            parent.insert(y, r);
            y = next;
        }
        r
    }
    for t in faces {
        for &v in t {
            parent.entry(v).or_insert(v);
        }
        let a = find(&mut parent, t[0]);
        for &v in &t[1..] {
            let b = find(&mut parent, v);
            if a != b {
                parent.insert(b, a);
            }
        }
    }
    let mut index: FastMap<u32, usize> = FastMap::default();
    let mut out: Vec<(Vec<u32>, Aabb)> = Vec::new();
    for (i, t) in faces.iter().enumerate() {
        let root = find(&mut parent, t[0]);
        let k = *index.entry(root).or_insert_with(|| {
            out.push((Vec::new(), Aabb::EMPTY));
            out.len() - 1
        });
        out[k].0.push(i as u32);
        out[k].1 = out[k].1.merge(&boxes[i]);
    }
    out.into_iter()
        .map(|(faces, aabb)| Component {
            faces: faces.into(),
            aabb,
        })
        .collect()
}

/// Welds the finite vertices of `mesh` into `vertices` (equal coordinates, one vertex: shared
/// edges must be found by index); the index of each of the mesh's vertices, `None` when not
/// finite.
fn weld(mesh: &TriMesh, vertices: &mut Vec<V3>) -> Vec<Option<u32>> {
    let mut weld: FastMap<[u64; 3], u32> = FastMap::default();
    let mut index: Vec<Option<u32>> = Vec::with_capacity(mesh.vertices.len());
    for v in &mesh.vertices {
        let p = V3::new(v.x, v.y, v.z);
        if !p.iter().all(|c| c.is_finite()) {
            index.push(None);
            continue;
        }
        let id = *weld.entry(key(&p)).or_insert_with(|| {
            vertices.push(p);
            (vertices.len() - 1) as u32
        });
        index.push(Some(id));
    }
    index
}

/// The usable triangles of `mesh` (welded `index`): each geometric triangle once into `faces`
/// across all parts (`seen_face`), and, for the part, its distinct triangles in first-seen
/// order with those of odd multiplicity (what the containment test counts: a triangle given
/// twice cancels out).
fn count_triangles(
    mesh: &TriMesh,
    index: &[Option<u32>],
    vertices: &[V3],
    faces: &mut Vec<[u32; 3]>,
    seen_face: &mut FastMap<[u32; 3], ()>,
) -> (Vec<[u32; 3]>, Vec<[u32; 3]>) {
    let mut multiplicity: FastMap<[u32; 3], (u32, [u32; 3])> = FastMap::default();
    let mut order: Vec<[u32; 3]> = Vec::new();
    for t in &mesh.triangles {
        let ids: Option<Vec<u32>> = t
            .iter()
            .map(|&i| index.get(i as usize).copied().flatten())
            .collect();
        let Some(ids) = ids else { continue };
        let tri = [ids[0], ids[1], ids[2]];
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            continue;
        }
        let [a, b, c] = tri.map(|i| vertices[i as usize]);
        if (b - a).cross(&(c - a)).norm_squared() == 0.0 {
            continue;
        }
        let k = sorted(tri);
        let e = multiplicity.entry(k).or_insert_with(|| {
            order.push(k);
            (0, tri)
        });
        e.0 += 1;
        if seen_face.insert(k, ()).is_none() {
            faces.push(tri);
        }
    }
    let parity: Vec<[u32; 3]> = order
        .iter()
        .filter_map(|k| {
            let (count, tri) = multiplicity[k];
            (count % 2 == 1).then_some(tri)
        })
        .collect();
    (order, parity)
}

/// One part of a body: its bounds (box and ball over all its triangles `order`) and what its
/// containment test needs (the triangles of odd multiplicity `parity`, their tree and
/// connected components).
fn part(mesh: &TriMesh, order: &[[u32; 3]], parity: Vec<[u32; 3]>, vertices: &[V3]) -> Part {
    let boxes: Vec<Aabb> = parity
        .iter()
        .map(|t| Aabb::of_points(t.iter().map(|&i| &vertices[i as usize])))
        .collect();
    let aabb = order.iter().fold(Aabb::EMPTY, |b, t| {
        b.merge(&Aabb::of_points(t.iter().map(|&i| &vertices[i as usize])))
    });
    let centre = aabb.centre();
    let radius = order
        .iter()
        .flatten()
        .map(|&i| (vertices[i as usize] - centre).norm())
        .fold(0.0, f64::max);
    let solid = mesh.is_closed() && !parity.is_empty();
    let components = components(&parity, &boxes);
    Part {
        solid,
        parity_bvh: Bvh::build(boxes.clone()),
        parity: parity.into(),
        aabb,
        sphere: (centre, radius),
        components,
    }
}

/// Unique edges of `faces`, each owned by the first face using it (so that each is tested
/// once): the edges, and for each face the start of its run in the owned list, then that list.
#[allow(clippy::type_complexity)]
fn owned_edges(faces: &[[u32; 3]]) -> (Vec<[u32; 2]>, Vec<u32>, Vec<u32>) {
    let mut edge_id: FastMap<(u32, u32), u32> = FastMap::default();
    let mut edges: Vec<[u32; 2]> = Vec::new();
    let mut owned_start = Vec::with_capacity(faces.len() + 1);
    let mut owned = Vec::new();
    for t in faces {
        owned_start.push(owned.len() as u32);
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let key = (a.min(b), a.max(b));
            if let std::collections::hash_map::Entry::Vacant(e) = edge_id.entry(key) {
                e.insert(edges.len() as u32);
                owned.push(edges.len() as u32);
                edges.push([a, b]);
            }
        }
    }
    owned_start.push(owned.len() as u32);
    (edges, owned_start, owned)
}

impl Body {
    /// Prepares `meshes`, each a separate part. Triangles with an index out of range or a
    /// coordinate that is not finite are skipped (the fields of [`TriMesh`] are public, so its
    /// checks may have been bypassed); so are triangles whose corners weld together.
    pub fn new(meshes: &[TriMesh]) -> Body {
        let mut vertices: Vec<V3> = Vec::new();
        let mut faces: Vec<[u32; 3]> = Vec::new();
        let mut parts = Vec::with_capacity(meshes.len());
        let mut seen_face: FastMap<[u32; 3], ()> = FastMap::default();
        for mesh in meshes {
            let index = weld(mesh, &mut vertices);
            let (order, parity) =
                count_triangles(mesh, &index, &vertices, &mut faces, &mut seen_face);
            parts.push(part(mesh, &order, parity, &vertices));
        }
        let (edges, owned_start, owned) = owned_edges(&faces);
        let boxes: Vec<Aabb> = faces
            .iter()
            .map(|t| Aabb::of_points(t.iter().map(|&i| &vertices[i as usize])))
            .collect();
        let aabb = boxes.iter().fold(Aabb::EMPTY, |b, x| b.merge(x));
        let radius = faces
            .iter()
            .flatten()
            .map(|&i| vertices[i as usize].norm())
            .fold(0.0, f64::max);
        let geo = faces
            .iter()
            .map(|t| Face::new(t.map(|i| vertices[i as usize])))
            .collect();
        Body {
            bvh: Bvh::build(boxes),
            vertices,
            faces: faces.into(),
            geo,
            edges: edges.into(),
            owned_start: owned_start.into(),
            owned: owned.into(),
            parts,
            aabb,
            radius,
        }
    }

    /// The same body with every vertex moved by `d`: what a new reference point (the pivot of
    /// a turn, CHS §2.3.2) needs, without welding, edge listing or tree building again.
    pub fn shifted(&self, d: &V3) -> Body {
        let vertices: Vec<V3> = self.vertices.iter().map(|v| v + d).collect();
        let geo = self
            .faces
            .iter()
            .map(|t| Face::new(t.map(|i| vertices[i as usize])))
            .collect();
        let radius = self
            .faces
            .iter()
            .flatten()
            .map(|&i| vertices[i as usize].norm())
            .fold(0.0, f64::max);
        let parts = self
            .parts
            .iter()
            .map(|p| Part {
                solid: p.solid,
                parity: p.parity.clone(),
                parity_bvh: p.parity_bvh.shifted(d),
                aabb: p.aabb.shifted(d),
                sphere: (p.sphere.0 + d, p.sphere.1),
                components: p
                    .components
                    .iter()
                    .map(|c| Component {
                        faces: c.faces.clone(),
                        aabb: c.aabb.shifted(d),
                    })
                    .collect(),
            })
            .collect();
        Body {
            vertices,
            faces: self.faces.clone(),
            geo,
            edges: self.edges.clone(),
            owned_start: self.owned_start.clone(),
            owned: self.owned.clone(),
            bvh: self.bvh.shifted(d),
            parts,
            aabb: self.aabb.shifted(d),
            radius,
        }
    }

    /// The corners of face `f` (kept with its plane: one load, not three indexed ones, in the
    /// pair loops that ask for them).
    pub fn corners(&self, f: u32) -> [V3; 3] {
        self.geo[f as usize].v
    }

    /// Face `f` with its plane and norms.
    pub fn face(&self, f: u32) -> &Face {
        &self.geo[f as usize]
    }

    /// The edges owned by face `f`.
    pub fn owned_edges(&self, f: u32) -> &[u32] {
        let f = f as usize;
        &self.owned[self.owned_start[f] as usize..self.owned_start[f + 1] as usize]
    }

    /// The end points of edge `e`.
    pub fn edge(&self, e: u32) -> (V3, V3) {
        let [a, b] = self.edges[e as usize];
        (self.vertices[a as usize], self.vertices[b as usize])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;

    #[test]
    fn double_sided_soup_has_no_parity_faces() {
        let cube = TriMesh::cuboid([1.0, 1.0, 1.0]).unwrap();
        let mut tris = cube.triangles.clone();
        tris.extend(cube.triangles.iter().map(|t| [t[0], t[2], t[1]]));
        // repeat the vertices so that welding is needed
        let n = cube.vertices.len() as u32;
        let mut verts = cube.vertices.clone();
        verts.extend(cube.vertices.iter().cloned());
        let tris: Vec<[u32; 3]> = tris
            .iter()
            .enumerate()
            .map(|(i, t)| if i >= 12 { t.map(|k| k + n) } else { *t })
            .collect();
        let soup = TriMesh::new(verts, tris).unwrap();
        let b = Body::new(&[soup]);
        assert_eq!(b.faces.len(), 12);
        assert_eq!(b.vertices.len(), 8);
        assert_eq!(b.edges.len(), 18);
        assert!(b.parts[0].parity.is_empty());
        assert!(!b.parts[0].solid);
        let solid = Body::new(&[cube]);
        assert!(solid.parts[0].solid);
        assert_eq!(solid.parts[0].parity.len(), 12);
        let owned: usize = (0..12).map(|f| solid.owned_edges(f).len()).sum();
        assert_eq!(owned, 18);
        assert_eq!(solid.parts[0].components.len(), 1);
        let two = TriMesh::new(
            [cube_vertices(0.0), cube_vertices(5.0)].concat(),
            [
                TriMesh::cuboid([1.0; 3]).unwrap().triangles,
                TriMesh::cuboid([1.0; 3])
                    .unwrap()
                    .triangles
                    .iter()
                    .map(|t| t.map(|k| k + 8))
                    .collect(),
            ]
            .concat(),
        )
        .unwrap();
        let b = Body::new(&[two]);
        assert_eq!(b.parts[0].components.len(), 2);
        assert!(b.parts[0].solid);
    }

    fn cube_vertices(x: f64) -> Vec<Point3<f64>> {
        TriMesh::cuboid([1.0; 3])
            .unwrap()
            .vertices
            .iter()
            .map(|v| v + nalgebra::Vector3::new(x, 0.0, 0.0))
            .collect()
    }

    #[test]
    fn bad_indices_are_skipped() {
        let m = TriMesh {
            vertices: vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(0.0, 1.0, 0.0),
            ],
            triangles: vec![[0, 1, 2], [0, 1, 9]],
        };
        let b = Body::new(&[m]);
        assert_eq!(b.faces.len(), 1);
    }
}
