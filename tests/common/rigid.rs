//! An independent validity check for rigid-body paths (SE(3)), built on parry and sharing no
//! code with the library's exact oracles.
//!
//! Every straight motion of a path (a translation, or a turn about one axis through the
//! reference point) is *certified* by conservative advancement: if the robot's surface is
//! farther than `d` from every obstacle surface at parameter `t₀`, it cannot touch anything
//! while no point of it moves farther than `d`, and between `t₀` and `t₁` no point moves farther
//! than `|Δp|·(t₁−t₀) + r·|Δφ|·(t₁−t₀)` (r = the robot's radius about its reference point). The
//! motion is bisected until every piece is certified; a piece that cannot be certified down to a
//! tiny length is reported as a collision. Surfaces never touching, containment can only be
//! present from the start: it is checked once, at the path's first configuration, for closed
//! meshes (parry's pseudo-normal point containment).
#![allow(dead_code)]

use parry3d_f64::math::{Isometry, Point, Translation, Vector};
use parry3d_f64::na::{Quaternion, Unit, UnitQuaternion};
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::{TriMesh, TriMeshFlags};
use viaroad::scene::{Obstacle, Robot, Scene};

pub struct RigidChecker {
    robot: TriMesh,
    robot_closed: bool,
    robot_radius: f64,
    obstacles: Vec<(TriMesh, bool)>,
    lower: Vec<f64>,
    upper: Vec<f64>,
}

fn parry_mesh(m: &viaroad::geometry::TriMesh) -> TriMesh {
    TriMesh::with_flags(
        m.vertices.clone(),
        m.triangles.clone(),
        TriMeshFlags::ORIENTED | TriMeshFlags::MERGE_DUPLICATE_VERTICES,
    )
    .or_else(|_| TriMesh::new(m.vertices.clone(), m.triangles.clone()))
    .expect("a valid mesh")
}

fn pose(q: &[f64]) -> Isometry<f64> {
    let r = UnitQuaternion::from_quaternion(Quaternion::new(q[6], q[3], q[4], q[5]));
    Isometry::from_parts(Translation::new(q[0], q[1], q[2]), r)
}

impl RigidChecker {
    pub fn se3(scene: &Scene) -> RigidChecker {
        let Robot::Mesh(robot) = &scene.robot else {
            panic!("an SE(3) scene")
        };
        let obstacles = scene
            .obstacles
            .iter()
            .map(|o| match o {
                Obstacle::Mesh(m) => (parry_mesh(m), m.is_closed()),
                _ => panic!("mesh obstacles"),
            })
            .collect();
        RigidChecker {
            robot_radius: robot
                .vertices
                .iter()
                .map(|v| v.coords.norm())
                .fold(0.0, f64::max),
            robot_closed: robot.is_closed(),
            robot: parry_mesh(robot),
            obstacles,
            lower: scene.space.lower().to_vec(),
            upper: scene.space.upper().to_vec(),
        }
    }

    /// Distance between the robot at `q` and the nearest obstacle surface.
    pub fn clearance(&self, q: &[f64]) -> f64 {
        let p = pose(q);
        self.obstacles
            .iter()
            .map(|(o, _)| {
                parry3d_f64::query::distance(&p, &self.robot, &Isometry::identity(), o).unwrap()
            })
            .fold(f64::INFINITY, f64::min)
    }

    fn contained(&self, q: &[f64]) -> bool {
        let p = pose(q);
        self.obstacles.iter().any(|(o, closed)| {
            (*closed
                && self
                    .robot
                    .vertices()
                    .iter()
                    .any(|v| o.contains_point(&Isometry::identity(), &(p * v))))
                || (self.robot_closed
                    && o.vertices()
                        .iter()
                        .any(|v| self.robot.contains_point(&p, v)))
        })
    }

    /// Certifies the straight motion from `a` to `b` (which must differ in position only or in
    /// orientation only).
    pub fn certify_motion(&self, a: &[f64], b: &[f64]) -> Result<(), String> {
        let ra = UnitQuaternion::from_quaternion(Quaternion::new(a[6], a[3], a[4], a[5]));
        let mut rb = UnitQuaternion::from_quaternion(Quaternion::new(b[6], b[3], b[4], b[5]));
        if ra.coords.dot(&rb.coords) < 0.0 {
            rb = UnitQuaternion::new_unchecked(-rb.into_inner());
        }
        let dp = Vector::new(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
        let rel = rb * ra.inverse();
        let angle = rel.angle();
        if dp.norm() > 0.0 && angle > 1e-12 {
            return Err(format!("{a:?} → {b:?} translates and turns at once"));
        }
        let axis = rel.axis().unwrap_or(Unit::new_normalize(Vector::x()));
        let at = |t: f64| -> Vec<f64> {
            let r = UnitQuaternion::from_axis_angle(&axis, t * angle) * ra;
            vec![
                a[0] + t * dp.x,
                a[1] + t * dp.y,
                a[2] + t * dp.z,
                r.i,
                r.j,
                r.k,
                r.w,
            ]
        };
        let rate = dp.norm() + self.robot_radius * angle;
        super::certify_by_advancement(rate, |t| self.clearance(&at(t)))
            .map_err(|e| format!("{e} of {a:?} → {b:?}"))
    }

    /// Certifies a whole path: bounds, containment at the start, every motion.
    pub fn certify_path(&self, path: &[Vec<f64>]) -> Result<(), String> {
        for q in path {
            for i in 0..3 {
                if q[i] < self.lower[i] - 1e-9 || q[i] > self.upper[i] + 1e-9 {
                    return Err(format!("{q:?} lies outside the bounds"));
                }
            }
        }
        if let Some(q) = path.first() {
            if self.contained(q) {
                return Err(format!(
                    "the robot at {q:?} lies inside an obstacle (or holds one)"
                ));
            }
        }
        for w in path.windows(2) {
            self.certify_motion(&w[0], &w[1])?;
        }
        Ok(())
    }

    /// A point of the robot at `q`, for tests that need one.
    pub fn robot_point(&self, q: &[f64]) -> Point<f64> {
        pose(q) * self.robot.vertices()[0]
    }
}
