//! The independent arm checker: parry's `intersection_test` on every
//! non-exempt link pair and every link–obstacle pair at a configuration, and along a path by
//! sampling each segment finely.
//!
//! It shares no code with any exact oracle: its shapes are parry shapes built afresh from the
//! robot's meshes and from the *exact* primitives (parry's cuboid, cylinder, ball, cone — not
//! the circumscribed polytopes the exact oracle uses), so a configuration the oracle certifies
//! free against the larger polytopes is free here too. Touching counts as collision.
//!
//! A parry `TriMesh` is a surface: a small obstacle wholly inside a closed link mesh would not
//! intersect it. The checker therefore also asks, for every pair whose surfaces are apart,
//! whether one shape holds a point of the other (closed meshes are built with
//! `TriMeshFlags::ORIENTED`, which makes `contains_point` a solid test); open meshes cannot
//! hold anything and are tested as surfaces only.
//!
//! Two safe culls come first: bounding balls, and for mesh parts parry's convex hull of the
//! mesh (a pair whose hulls are apart is apart, surfaces and solids; primitives are their own
//! hulls). They change no verdict ([`ArmChecker::without_hulls`] is the reference) and spare
//! most of the triangle tests near obstacles (23× faster along MotionBenchMaker's paths).
//!
//! Along a path it samples, not certifies: each segment `a → b` is checked at `k/n`,
//! `n = ⌈‖b − a‖₂ / max_step⌉` — OMPL's `DiscreteMotionValidator` with `max_step` = its
//! longest valid segment. The acceptance check runs it at 1/10 of OMPL's default
//! (`0.001 · max_extent`).

use super::arm::{Arm, ShapeSource};
use super::objects::{CollisionObject, ObjectShape};
use super::shapes::Primitive;
use super::RobotError;
use crate::geometry::TriMesh;
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::shape::{SharedShape, TriMeshFlags};

/// One solid the checker tests: a parry shape at a pose relative to its owner's frame.
#[derive(Clone)]
struct Part {
    /// The owner: a link index, or an obstacle index.
    owner: usize,
    /// Pose in the owner's frame (link frame, or world for obstacles).
    origin: Isometry3<f64>,
    shape: SharedShape,
    /// A point of the shape (local), for the containment test.
    inner_point: Point3<f64>,
    /// Whether the shape bounds a solid (primitives, closed meshes).
    solid: bool,
    /// Radius of a ball about the local origin that holds the shape: a cheap, safe cull.
    radius: f64,
    /// A mesh's convex hull (parry's), which holds the mesh: where the hulls are apart the
    /// shapes are, surfaces and solids, so the pair is answered without walking the mesh's
    /// triangles (a second safe cull; primitives are their own hulls). `None` for primitives,
    /// degenerate meshes, and a checker built [`ArmChecker::without_hulls`].
    hull: Option<SharedShape>,
}

/// A colliding pair: link or obstacle names.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Collision {
    /// A link name.
    pub a: String,
    /// A link name or an obstacle id.
    pub b: String,
    /// How they meet.
    pub contact: Contact,
}

/// How two shapes meet.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Contact {
    /// Their surfaces (or solid primitives) intersect: what FCL's mesh tests see too.
    Surface,
    /// Their surfaces are apart but one solid holds the other (e.g. the Panda's finger
    /// folded wholly inside link 5): surface-only checkers such as FCL's BVH meshes miss it.
    Containment,
}

/// The result of checking a path.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PathReport {
    /// Whether every sampled configuration is within bounds and collision-free.
    pub valid: bool,
    /// Configurations checked.
    pub samples: usize,
    /// Segments of the path.
    pub segments: usize,
    /// The first invalid sample: segment index, parameter `t` along it, and its collisions
    /// (empty if it is out of bounds only).
    pub first_invalid: Option<(usize, f64, Vec<Collision>)>,
}

/// The independent checker of one arm in one scene.
#[derive(Clone)]
pub struct ArmChecker {
    arm: Arm,
    links: Vec<Part>,
    obstacles: Vec<Part>,
    obstacle_names: Vec<String>,
}

fn parry_mesh(mesh: &TriMesh) -> Result<(SharedShape, bool), String> {
    let closed = mesh.is_closed();
    let flags = if closed {
        TriMeshFlags::ORIENTED | TriMeshFlags::MERGE_DUPLICATE_VERTICES
    } else {
        TriMeshFlags::empty()
    };
    SharedShape::trimesh_with_flags(mesh.vertices.clone(), mesh.triangles.clone(), flags)
        .map(|s| (s, closed))
        .map_err(|e| format!("parry refuses the mesh: {e:?}"))
}

/// Parry's exact shape for a primitive. parry's cylinder and cone run along y; URDF's and
/// MoveIt's along z: a quarter turn about x maps y onto z (the cone's apex stays at +z).
fn parry_primitive(p: &Primitive) -> (SharedShape, Isometry3<f64>) {
    let y_to_z = Isometry3::from_parts(
        Translation3::identity(),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2),
    );
    match *p {
        Primitive::Box { size } => (
            SharedShape::cuboid(size[0] / 2.0, size[1] / 2.0, size[2] / 2.0),
            Isometry3::identity(),
        ),
        Primitive::Sphere { radius } => (SharedShape::ball(radius), Isometry3::identity()),
        Primitive::Cylinder { radius, length } => {
            (SharedShape::cylinder(length / 2.0, radius), y_to_z)
        }
        Primitive::Cone { radius, length } => (SharedShape::cone(length / 2.0, radius), y_to_z),
    }
}

fn mesh_part(owner: usize, origin: Isometry3<f64>, mesh: &TriMesh) -> Result<Part, String> {
    let (shape, solid) = parry_mesh(mesh)?;
    let inner_point = mesh.vertices[mesh.triangles[0][0] as usize];
    let radius = mesh
        .vertices
        .iter()
        .map(|v| v.coords.norm())
        .fold(0.0, f64::max);
    let hull = SharedShape::convex_hull(&mesh.vertices);
    Ok(Part {
        owner,
        origin,
        shape,
        inner_point,
        solid,
        radius,
        hull,
    })
}

fn primitive_part(owner: usize, origin: Isometry3<f64>, p: &Primitive) -> Part {
    let (shape, turn) = parry_primitive(p);
    Part {
        owner,
        origin: origin * turn,
        shape,
        inner_point: Point3::origin(),
        solid: true,
        radius: p.bounding_radius(),
        hull: None,
    }
}

/// Whether two placed parts meet: surfaces (or solids) intersect, or one solid holds the other.
fn meet(a: &Part, pa: &Isometry3<f64>, b: &Part, pb: &Isometry3<f64>) -> Option<Contact> {
    let d = (pa.translation.vector - pb.translation.vector).norm();
    if d > a.radius + b.radius {
        return None;
    }
    if a.hull.is_some() || b.hull.is_some() {
        let ha = a.hull.as_ref().unwrap_or(&a.shape);
        let hb = b.hull.as_ref().unwrap_or(&b.shape);
        if !parry3d_f64::query::intersection_test(pa, &**ha, pb, &**hb).unwrap_or(true) {
            return None;
        }
    }
    let hit = parry3d_f64::query::intersection_test(pa, &*a.shape, pb, &*b.shape)
        // unsupported pairs cannot be judged: count them as collisions (conservative)
        .unwrap_or(true);
    if hit {
        return Some(Contact::Surface);
    }
    let held = (a.solid && a.shape.contains_point(pa, &(pb * b.inner_point)))
        || (b.solid && b.shape.contains_point(pb, &(pa * a.inner_point)));
    held.then_some(Contact::Containment)
}

impl ArmChecker {
    /// Builds parry shapes for the arm's links (from their meshes and exact primitives) and
    /// for the scene's collision objects.
    pub fn new(arm: &Arm, objects: &[CollisionObject]) -> Result<ArmChecker, RobotError> {
        let invalid = |what: &str, message: String| RobotError::Config {
            what: what.into(),
            message,
        };
        let mut links = Vec::new();
        for s in &arm.shapes {
            links.push(match &s.source {
                ShapeSource::Mesh { mesh, path } => mesh_part(s.link, s.origin, mesh)
                    .map_err(|m| invalid(&path.display().to_string(), m))?,
                ShapeSource::Primitive(p) => primitive_part(s.link, s.origin, p),
            });
        }
        let mut obstacles = Vec::new();
        for (i, o) in objects.iter().enumerate() {
            // the object's frame placed as the oracle places it: reading the scene is shared,
            // the geometry and its tests are not
            let at = arm
                .frame_pose(&o.frame)
                .map_err(|e| invalid(&o.id, e.to_string()))?;
            for (pose, shape) in &o.parts {
                let pose = at * pose;
                obstacles.push(match shape {
                    ObjectShape::Primitive(p) => primitive_part(i, pose, p),
                    ObjectShape::Mesh(m) => mesh_part(i, pose, m).map_err(|m| invalid(&o.id, m))?,
                });
            }
        }
        Ok(ArmChecker {
            arm: arm.clone(),
            links,
            obstacles,
            obstacle_names: objects.iter().map(|o| o.id.clone()).collect(),
        })
    }

    /// The same checker without the convex-hull cull: every pair whose bounding balls meet
    /// goes to parry's test of the shapes themselves. The reference the cull is tested against
    /// (the same collisions at every configuration, `tests/arm_checker.rs`).
    pub fn without_hulls(mut self) -> ArmChecker {
        for p in self.links.iter_mut().chain(self.obstacles.iter_mut()) {
            p.hull = None;
        }
        self
    }

    /// The arm this checker was built for.
    pub fn arm(&self) -> &Arm {
        &self.arm
    }

    /// Every colliding pair at group configuration `q` (link–link pairs not exempt, then
    /// link–obstacle pairs), each pair once.
    pub fn collisions(&self, q: &[f64]) -> Vec<Collision> {
        let poses = self.arm.link_poses(q);
        let placed: Vec<Isometry3<f64>> = self
            .links
            .iter()
            .map(|p| poses[p.owner] * p.origin)
            .collect();
        let name = |l: usize| self.arm.model.urdf.links[l].name.clone();
        let mut out: Vec<Collision> = Vec::new();
        // one entry per pair; a surface contact of any part outranks a containment
        let mut push = |c: Collision| match out.iter_mut().find(|o| o.a == c.a && o.b == c.b) {
            Some(o) if c.contact == Contact::Surface => o.contact = Contact::Surface,
            Some(_) => {}
            None => out.push(c),
        };
        for &(la, lb) in &self.arm.self_pairs {
            for (i, a) in self.links.iter().enumerate().filter(|(_, p)| p.owner == la) {
                for (j, b) in self.links.iter().enumerate().filter(|(_, p)| p.owner == lb) {
                    if let Some(contact) = meet(a, &placed[i], b, &placed[j]) {
                        push(Collision {
                            a: name(la),
                            b: name(lb),
                            contact,
                        });
                    }
                }
            }
        }
        for (i, a) in self.links.iter().enumerate() {
            for b in &self.obstacles {
                if let Some(contact) = meet(a, &placed[i], b, &b.origin) {
                    push(Collision {
                        a: name(a.owner),
                        b: self.obstacle_names[b.owner].clone(),
                        contact,
                    });
                }
            }
        }
        out
    }

    /// Whether `q` has the group's length, lies within the bounds, and collides nowhere.
    pub fn is_valid(&self, q: &[f64]) -> bool {
        self.arm.group.in_bounds(q) && self.collisions(q).is_empty()
    }

    /// Checks every vertex of a path and every segment sampled at most `max_step` apart
    /// (joint-space L2). Configurations of the wrong length are errors.
    pub fn check_path(&self, path: &[Vec<f64>], max_step: f64) -> Result<PathReport, RobotError> {
        if !(max_step.is_finite() && max_step > 0.0) {
            return Err(RobotError::Config {
                what: "check step".into(),
                message: format!("{max_step} is not a positive length"),
            });
        }
        for (i, q) in path.iter().enumerate() {
            self.arm
                .check_config(q, &format!("path configuration {i}"))?;
        }
        let mut report = PathReport {
            valid: true,
            samples: 0,
            segments: path.len().saturating_sub(1),
            first_invalid: None,
        };
        let bad = |seg: usize, t: f64, q: &[f64], report: &mut PathReport| -> bool {
            report.samples += 1;
            if self.arm.group.in_bounds(q) {
                let c = self.collisions(q);
                if c.is_empty() {
                    return false;
                }
                report.first_invalid = Some((seg, t, c));
            } else {
                report.first_invalid = Some((seg, t, Vec::new()));
            }
            report.valid = false;
            true
        };
        if let Some(first) = path.first() {
            if bad(0, 0.0, first, &mut report) {
                return Ok(report);
            }
        }
        for (s, w) in path.windows(2).enumerate() {
            let (a, b) = (&w[0], &w[1]);
            let len = a
                .iter()
                .zip(b)
                .map(|(x, y)| (y - x).powi(2))
                .sum::<f64>()
                .sqrt();
            let n = ((len / max_step).ceil() as usize).max(1);
            for k in 1..=n {
                let t = k as f64 / n as f64;
                // the end itself, not `a + 1 · (b − a)`, which rounds off a corner at a joint
                // limit (out of bounds by an ulp)
                let q: Vec<f64> = if k == n {
                    b.clone()
                } else {
                    a.iter().zip(b).map(|(x, y)| x + t * (y - x)).collect()
                };
                if bad(s, t, &q, &mut report) {
                    return Ok(report);
                }
            }
        }
        Ok(report)
    }
}
