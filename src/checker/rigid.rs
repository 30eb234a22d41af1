//! The SE(3) checker: parry3d trimeshes.

use super::advance::{certify_by_advancement, in_box};
use crate::scene::{Obstacle, Robot, Scene};
use crate::short;
use crate::space::Config;
use parry3d_f64::math::{Isometry, Translation, Vector};
use parry3d_f64::na::{Quaternion, Unit, UnitQuaternion};
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::{TriMesh, TriMeshFlags};

pub(super) fn parry_mesh(m: &crate::geometry::TriMesh) -> Result<TriMesh, String> {
    TriMesh::with_flags(
        m.vertices.clone(),
        m.triangles.clone(),
        TriMeshFlags::ORIENTED | TriMeshFlags::MERGE_DUPLICATE_VERTICES,
    )
    .or_else(|_| TriMesh::new(m.vertices.clone(), m.triangles.clone()))
    .map_err(|e| format!("parry refuses a mesh: {e}"))
}

fn pose(q: &[f64]) -> Isometry<f64> {
    let r = UnitQuaternion::from_quaternion(Quaternion::new(q[6], q[3], q[4], q[5]));
    Isometry::from_parts(Translation::new(q[0], q[1], q[2]), r)
}

/// Mesh robot among meshes.
pub struct RigidChecker {
    robot: TriMesh,
    robot_closed: bool,
    robot_radius: f64,
    obstacles: Vec<(TriMesh, bool)>,
    lower: Vec<f64>,
    upper: Vec<f64>,
}

impl RigidChecker {
    /// The checker of an SE(3) scene.
    pub fn se3(scene: &Scene) -> Result<RigidChecker, String> {
        let Robot::Mesh(robot) = &scene.robot else {
            return Err("not a mesh robot".into());
        };
        let mut obstacles = Vec::new();
        for o in &scene.obstacles {
            match o {
                Obstacle::Mesh(m) => obstacles.push((parry_mesh(m)?, m.is_closed())),
                _ => return Err("a non-mesh obstacle in SE(3)".into()),
            }
        }
        Ok(RigidChecker {
            robot_radius: robot
                .vertices
                .iter()
                .map(|v| v.coords.norm())
                .fold(0.0, f64::max),
            robot_closed: robot.is_closed(),
            robot: parry_mesh(robot)?,
            obstacles,
            lower: scene.space.lower()[..3].to_vec(),
            upper: scene.space.upper()[..3].to_vec(),
        })
    }

    /// Distance between the robot's surface at `q` and the nearest obstacle surface.
    pub fn clearance(&self, q: &[f64]) -> Result<f64, String> {
        let p = pose(q);
        let mut best = f64::INFINITY;
        for (o, _) in &self.obstacles {
            let d = parry3d_f64::query::distance(&p, &self.robot, &Isometry::identity(), o)
                .map_err(|e| format!("parry: {e}"))?;
            best = best.min(d);
        }
        Ok(best)
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

    /// Certifies the straight motion from `a` to `b` (a translation, or a turn about one
    /// axis; both at once is refused: the planner never moves so).
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
        certify_by_advancement(rate, |t| self.clearance(&at(t)))
            .map_err(|e| format!("{e} of {a:?} → {b:?}"))
    }

    /// Certifies a whole path: bounds, containment at the start, every motion.
    pub fn certify_path(&self, path: &[Config]) -> Result<(), String> {
        for q in path {
            if q.len() != 7 {
                return Err(format!("{q:?} is not an SE(3) configuration"));
            }
            in_box(q, &self.lower, &self.upper)?;
        }
        if let Some(q) = path.first() {
            if self.contained(q) {
                return Err(format!(
                    "the robot at {} lies inside an obstacle (or holds one)",
                    short::config(q)
                ));
            }
        }
        if let [q] = path {
            return self.certify_motion(q, q);
        }
        for w in path.windows(2) {
            self.certify_motion(&w[0], &w[1])?;
        }
        Ok(())
    }
}
