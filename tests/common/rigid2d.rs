//! An independent validity check for SE(2) paths of polygonal robots, built on parry2d and
//! sharing no code with the library's polygon oracle: polygons are cut into triangles by the
//! ear clipping below and become parry compounds of convex pieces (so that containment shows as
//! distance zero), and every straight motion is certified by conservative advancement (see
//! `rigid.rs`): clearance `d` at `t₀` certifies `[t₀, t₁]` when no robot point moves farther than
//! `d` in between, i.e. `|Δp| + r·|Δθ| ≤ d`.
#![allow(dead_code)]

use parry2d_f64::math::{Isometry, Point};
use parry2d_f64::shape::{Compound, SharedShape, Triangle};
use viaroad::geometry::Polygon;
use viaroad::scene::{Obstacle, Robot, Scene};

/// Ear clipping of a simple counter-clockwise polygon.
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
        let i = ear.unwrap_or(0); // degenerate input: cut anyway (errs towards more triangles)
        out.push([v[(i + n - 1) % n], v[i], v[(i + 1) % n]]);
        v.remove(i);
    }
    out.push([v[0], v[1], v[2]]);
    out
}

fn compound(polys: &[Polygon]) -> Compound {
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
    Compound::new(parts)
}

pub struct PlanarChecker {
    robot: Compound,
    radius: f64,
    obstacles: Compound,
    lower: [f64; 2],
    upper: [f64; 2],
}

impl PlanarChecker {
    pub fn se2(scene: &Scene) -> PlanarChecker {
        let Robot::Polygons(parts) = &scene.robot else {
            panic!("an SE(2) scene")
        };
        let obstacles: Vec<Polygon> = scene
            .obstacles
            .iter()
            .map(|o| match o {
                Obstacle::Polygon(p) => p.clone(),
                _ => panic!("polygon obstacles"),
            })
            .collect();
        PlanarChecker {
            radius: parts
                .iter()
                .flat_map(|p| &p.vertices)
                .map(|v| v.coords.norm())
                .fold(0.0, f64::max),
            robot: compound(parts),
            obstacles: compound(&obstacles),
            lower: [scene.space.lower()[0], scene.space.lower()[1]],
            upper: [scene.space.upper()[0], scene.space.upper()[1]],
        }
    }

    pub fn clearance(&self, q: &[f64]) -> f64 {
        let pose = Isometry::new(parry2d_f64::na::Vector2::new(q[0], q[1]), q[2]);
        parry2d_f64::query::distance(&pose, &self.robot, &Isometry::identity(), &self.obstacles)
            .unwrap()
    }

    /// Certifies the straight motion from `a` to `b` (position or angle changes, not both; the
    /// angle the shorter way round, as the planner turns).
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
        super::certify_by_advancement(rate, |t| self.clearance(&at(t)))
            .map_err(|e| format!("{e} of {a:?} → {b:?}"))
    }

    /// Certifies a path: position bounds and every motion.
    pub fn certify_path(&self, path: &[Vec<f64>]) -> Result<(), String> {
        for q in path {
            for i in 0..2 {
                if q[i] < self.lower[i] - 1e-9 || q[i] > self.upper[i] + 1e-9 {
                    return Err(format!("{q:?} lies outside the bounds"));
                }
            }
        }
        for w in path.windows(2) {
            self.certify_motion(&w[0], &w[1])?;
        }
        Ok(())
    }
}
