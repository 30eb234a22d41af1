//! The SE(2) checker: parry2d compounds of ear-clipped triangles.

use super::advance::{certify_by_advancement, in_box};
use crate::geometry::Polygon;
use crate::scene::{Obstacle, Robot, Scene};
use crate::space::Config;
use parry2d_f64::math::{Isometry, Point};
use parry2d_f64::shape::{Compound, SharedShape, Triangle};

/// Ear clipping of a simple counter-clockwise polygon (independent of the library's
/// polygon code).
fn triangles(p: &Polygon) -> Vec<[Point<f64>; 3]> {
    let mut v: Vec<Point<f64>> = p.vertices.iter().map(|q| Point::new(q.x, q.y)).collect();
    let cross = |a: Point<f64>, b: Point<f64>, c: Point<f64>| (b - a).perp(&(c - a));
    let mut out = Vec::new();
    while v.len() > 3 {
        let n = v.len();
        let ear = (0..n).find(|&i| {
            let (a, b, c) = (v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
            cross(a, b, c) > 0.0
                && v.iter().all(|&q| {
                    q == a
                        || q == b
                        || q == c
                        || !(cross(a, b, q) >= 0.0
                            && cross(b, c, q) >= 0.0
                            && cross(c, a, q) >= 0.0)
                })
        });
        let i = ear.unwrap_or(0); // degenerate input: cut anyway (more triangles, not fewer)
        out.push([v[(i + n - 1) % n], v[i], v[(i + 1) % n]]);
        v.remove(i);
    }
    if v.len() == 3 {
        out.push([v[0], v[1], v[2]]);
    }
    out
}

pub(super) fn compound(polys: &[Polygon]) -> Result<Compound, String> {
    let parts: Vec<(Isometry<f64>, SharedShape)> = polys
        .iter()
        .flat_map(triangles)
        .map(|[a, b, c]| {
            (
                Isometry::identity(),
                SharedShape::new(Triangle::new(a, b, c)),
            )
        })
        .collect();
    if parts.is_empty() {
        return Err("no triangles".into());
    }
    Ok(Compound::new(parts))
}

/// Polygonal robot among polygons.
pub struct PlanarChecker {
    robot: Compound,
    radius: f64,
    obstacles: Option<Compound>,
    lower: [f64; 2],
    upper: [f64; 2],
}

impl PlanarChecker {
    /// The checker of an SE(2) scene.
    pub fn se2(scene: &Scene) -> Result<PlanarChecker, String> {
        let Robot::Polygons(parts) = &scene.robot else {
            return Err("not a polygon robot".into());
        };
        let mut obstacles = Vec::new();
        for o in &scene.obstacles {
            match o {
                Obstacle::Polygon(p) => obstacles.push(p.clone()),
                _ => return Err("a non-polygon obstacle in SE(2)".into()),
            }
        }
        Ok(PlanarChecker {
            radius: parts
                .iter()
                .flat_map(|p| &p.vertices)
                .map(|v| v.coords.norm())
                .fold(0.0, f64::max),
            robot: compound(parts)?,
            obstacles: if obstacles.is_empty() {
                None
            } else {
                Some(compound(&obstacles)?)
            },
            lower: [scene.space.lower()[0], scene.space.lower()[1]],
            upper: [scene.space.upper()[0], scene.space.upper()[1]],
        })
    }

    /// Distance between the robot at `q` and the obstacles (0 when they overlap).
    pub fn clearance(&self, q: &[f64]) -> Result<f64, String> {
        let Some(obstacles) = &self.obstacles else {
            return Ok(f64::INFINITY);
        };
        let pose = Isometry::new(parry2d_f64::na::Vector2::new(q[0], q[1]), q[2]);
        parry2d_f64::query::distance(&pose, &self.robot, &Isometry::identity(), obstacles)
            .map_err(|e| format!("parry: {e}"))
    }

    /// Certifies the straight motion from `a` to `b` (position or angle, the angle the
    /// shorter way round, as the planner turns).
    pub fn certify_motion(&self, a: &[f64], b: &[f64]) -> Result<(), String> {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let mut dt = (b[2] - a[2]).rem_euclid(std::f64::consts::TAU);
        if dt > std::f64::consts::PI {
            dt -= std::f64::consts::TAU;
        }
        let dp = (dx * dx + dy * dy).sqrt();
        if dp > 0.0 && dt.abs() > 1e-12 {
            return Err(format!("{a:?} → {b:?} translates and turns at once"));
        }
        let rate = dp + self.radius * dt.abs();
        let at = |t: f64| [a[0] + t * dx, a[1] + t * dy, a[2] + t * dt];
        certify_by_advancement(rate, |t| self.clearance(&at(t)))
            .map_err(|e| format!("{e} of {a:?} → {b:?}"))
    }

    /// Certifies a path: position bounds and every motion.
    pub fn certify_path(&self, path: &[Config]) -> Result<(), String> {
        for q in path {
            if q.len() != 3 {
                return Err(format!("{q:?} is not an SE(2) configuration"));
            }
            in_box(q, &self.lower, &self.upper)?;
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
