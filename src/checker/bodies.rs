//! The checker of several polygonal bodies in the plane (SE(2)^k): parry2d compounds of
//! ear-clipped triangles, every body against the obstacles and every pair of bodies against
//! each other, certified along each motion by conservative advancement.
//!
//! A motion between two corners moves every body at once, linearly in position and the
//! shorter way round in angle (what [`crate::space::Space::interpolate`] does; the seed's
//! motions — all bodies translating, or one turning — are special cases, and so are the
//! straight or sampled motions of other local methods). No point of body `i` moves faster than
//! `vᵢ = |Δpᵢ| + rᵢ·|Δθᵢ|`, so a clearance `d` (the least distance over all body–obstacle and
//! body–body pairs) cannot close before the parameter has advanced `d / (2 · maxᵢ vᵢ)`. It
//! shares no code with the exact oracle ([`crate::oracle::bodies`]).

use super::advance::{certify_by_advancement, in_box};
use super::planar;
use crate::scene::{Obstacle, Robot, Scene};
use crate::short;
use crate::space::Config;
use parry2d_f64::math::Isometry;
use parry2d_f64::shape::Compound;
use std::f64::consts::{PI, TAU};

/// Several polygonal bodies among polygons.
pub struct BodiesChecker {
    bodies: Vec<Compound>,
    radii: Vec<f64>,
    names: Vec<String>,
    obstacles: Option<Compound>,
    lower: [f64; 2],
    upper: [f64; 2],
}

/// The change of an angle the shorter way round, in `[-π, π)`.
fn turn(a: f64, b: f64) -> f64 {
    let d = (b - a).rem_euclid(TAU);
    if d >= PI {
        d - TAU
    } else {
        d
    }
}

impl BodiesChecker {
    /// The checker of a scene of several bodies.
    pub fn new(scene: &Scene) -> Result<BodiesChecker, String> {
        let Robot::Bodies(bodies) = &scene.robot else {
            return Err("not a scene of several bodies".into());
        };
        let mut obstacles = Vec::new();
        for o in &scene.obstacles {
            match o {
                Obstacle::Polygon(p) => obstacles.push(p.clone()),
                _ => return Err("a non-polygon obstacle in the plane".into()),
            }
        }
        Ok(BodiesChecker {
            bodies: bodies
                .iter()
                .map(|b| planar::compound(&b.parts))
                .collect::<Result<_, _>>()?,
            radii: bodies
                .iter()
                .map(|b| {
                    b.parts
                        .iter()
                        .flat_map(|p| &p.vertices)
                        .map(|v| v.coords.norm())
                        .fold(0.0, f64::max)
                })
                .collect(),
            names: bodies.iter().map(|b| b.name.clone()).collect(),
            obstacles: if obstacles.is_empty() {
                None
            } else {
                Some(planar::compound(&obstacles)?)
            },
            lower: [scene.space.lower()[0], scene.space.lower()[1]],
            upper: [scene.space.upper()[0], scene.space.upper()[1]],
        })
    }

    fn pose(q: &[f64], i: usize) -> Isometry<f64> {
        Isometry::new(
            parry2d_f64::na::Vector2::new(q[3 * i], q[3 * i + 1]),
            q[3 * i + 2],
        )
    }

    /// The least distance over every body–obstacle and body–body pair at `q` (0 where two
    /// overlap), and the pair it belongs to.
    pub fn clearance(&self, q: &[f64]) -> Result<(f64, String), String> {
        let k = self.bodies.len();
        let parry = |e: parry2d_f64::query::Unsupported| format!("parry: {e}");
        let mut best = (f64::INFINITY, String::new());
        for i in 0..k {
            if let Some(o) = &self.obstacles {
                let d = parry2d_f64::query::distance(
                    &Self::pose(q, i),
                    &self.bodies[i],
                    &Isometry::identity(),
                    o,
                )
                .map_err(parry)?;
                if d < best.0 {
                    best = (d, format!("body \"{}\" and an obstacle", self.names[i]));
                }
            }
            for j in i + 1..k {
                let d = parry2d_f64::query::distance(
                    &Self::pose(q, i),
                    &self.bodies[i],
                    &Self::pose(q, j),
                    &self.bodies[j],
                )
                .map_err(parry)?;
                if d < best.0 {
                    best = (
                        d,
                        format!("bodies \"{}\" and \"{}\"", self.names[i], self.names[j]),
                    );
                }
            }
        }
        Ok(best)
    }

    /// Certifies the motion from `a` to `b`: every body linearly in position, the shorter way
    /// round in angle, all at once.
    pub fn certify_motion(&self, a: &[f64], b: &[f64]) -> Result<(), String> {
        let k = self.bodies.len();
        let mut delta = vec![0.0; 3 * k];
        let mut fastest = 0.0f64;
        for i in 0..k {
            let (dx, dy) = (b[3 * i] - a[3 * i], b[3 * i + 1] - a[3 * i + 1]);
            let dt = turn(a[3 * i + 2], b[3 * i + 2]);
            delta[3 * i..3 * i + 3].copy_from_slice(&[dx, dy, dt]);
            fastest = fastest.max(dx.hypot(dy) + self.radii[i] * dt.abs());
        }
        let at = |t: f64| -> Vec<f64> { a.iter().zip(&delta).map(|(x, d)| x + t * d).collect() };
        // the pair nearest where advancement stopped, for the message
        let last = std::cell::RefCell::new(String::new());
        let result = certify_by_advancement(2.0 * fastest, |t| {
            let (d, pair) = self.clearance(&at(t))?;
            *last.borrow_mut() = pair;
            Ok(d)
        });
        result.map_err(|e| {
            format!(
                "{e} ({}) of {} → {}",
                last.borrow(),
                short::config(a),
                short::config(b)
            )
        })
    }

    /// Certifies a path: every reference point in the bounds and every motion.
    pub fn certify_path(&self, path: &[Config]) -> Result<(), String> {
        let k = self.bodies.len();
        for q in path {
            if q.len() != 3 * k {
                return Err(format!(
                    "{} is not a configuration of {k} bodies",
                    short::config(q)
                ));
            }
            for i in 0..k {
                in_box(&q[3 * i..3 * i + 2], &self.lower, &self.upper)?;
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
