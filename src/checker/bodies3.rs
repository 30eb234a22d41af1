//! The checker of several polyhedral bodies in space (SE(3)^k): parry3d trimeshes, every body
//! against every obstacle and every pair of bodies against each other, certified along each
//! motion by conservative advancement.
//!
//! A motion between two corners moves every body at once, linearly in position and about one
//! fixed axis through its reference point by the shorter way between its orientations (the
//! seed's motions — all bodies translating, or one turning — are special cases, and so are the
//! straight or sampled motions of other local methods). No point of body `i` moves faster than
//! `vᵢ = |Δpᵢ| + rᵢ·θᵢ`, so a clearance `d` (the least distance over all body–obstacle and
//! body–body pairs) cannot close before the parameter has advanced `d / (2 · maxᵢ vᵢ)`.
//! Containment (a body wholly inside a closed obstacle or another closed body, or holding one)
//! is checked at the first corner; surfaces that never touch cannot change it along the path.
//! It shares no code with the exact oracle ([`crate::oracle::bodies3`]).

use super::advance::{certify_by_advancement, in_box};
use super::rigid::parry_mesh;
use crate::scene::{Obstacle, Robot, Scene};
use crate::short;
use crate::space::Config;
use parry3d_f64::math::{Isometry, Translation, Vector};
use parry3d_f64::na::{Quaternion, Unit, UnitQuaternion};
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::TriMesh;

/// Coordinates per body.
const POSE: usize = 7;

/// One mesh and whether it is closed (has an inside).
struct Solid {
    mesh: TriMesh,
    closed: bool,
}

/// Several polyhedral bodies among polyhedra.
pub struct SolidBodiesChecker {
    bodies: Vec<Solid>,
    radii: Vec<f64>,
    names: Vec<String>,
    obstacles: Vec<Solid>,
    lower: [f64; 3],
    upper: [f64; 3],
}

fn orientation(p: &[f64]) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::new(p[6], p[3], p[4], p[5]))
}

fn pose(q: &[f64], i: usize) -> Isometry<f64> {
    let p = &q[POSE * i..POSE * i + POSE];
    Isometry::from_parts(Translation::new(p[0], p[1], p[2]), orientation(p))
}

impl SolidBodiesChecker {
    /// The checker of a scene of several bodies in space.
    pub fn new(scene: &Scene) -> Result<SolidBodiesChecker, String> {
        let Robot::MeshBodies(bodies) = &scene.robot else {
            return Err("not a scene of several bodies in space".into());
        };
        let solid = |m: &crate::geometry::TriMesh| {
            Ok::<_, String>(Solid {
                mesh: parry_mesh(m)?,
                closed: m.is_closed(),
            })
        };
        let mut obstacles = Vec::new();
        for o in &scene.obstacles {
            match o {
                Obstacle::Mesh(m) => obstacles.push(solid(m)?),
                _ => return Err("a non-mesh obstacle in space".into()),
            }
        }
        let (lo, hi) = (scene.space.lower(), scene.space.upper());
        Ok(SolidBodiesChecker {
            bodies: bodies
                .iter()
                .map(|b| solid(&b.mesh))
                .collect::<Result<_, _>>()?,
            radii: bodies
                .iter()
                .map(|b| {
                    b.mesh
                        .vertices
                        .iter()
                        .map(|v| v.coords.norm())
                        .fold(0.0, f64::max)
                })
                .collect(),
            names: bodies.iter().map(|b| b.name.clone()).collect(),
            obstacles,
            lower: [lo[0], lo[1], lo[2]],
            upper: [hi[0], hi[1], hi[2]],
        })
    }

    /// The least distance over every body–obstacle and body–body pair at `q` (0 where two
    /// surfaces meet), and the pair it belongs to.
    pub fn clearance(&self, q: &[f64]) -> Result<(f64, String), String> {
        let k = self.bodies.len();
        let parry = |e: parry3d_f64::query::Unsupported| format!("parry: {e}");
        let mut best = (f64::INFINITY, String::new());
        for i in 0..k {
            let pi = pose(q, i);
            for o in &self.obstacles {
                let d = parry3d_f64::query::distance(
                    &pi,
                    &self.bodies[i].mesh,
                    &Isometry::identity(),
                    &o.mesh,
                )
                .map_err(parry)?;
                if d < best.0 {
                    best = (d, format!("body \"{}\" and an obstacle", self.names[i]));
                }
            }
            for j in i + 1..k {
                let d = parry3d_f64::query::distance(
                    &pi,
                    &self.bodies[i].mesh,
                    &pose(q, j),
                    &self.bodies[j].mesh,
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

    /// Whether closed `a` (at `pa`) holds a vertex of `b` (at `pb`).
    fn holds(a: &Solid, pa: &Isometry<f64>, b: &Solid, pb: &Isometry<f64>) -> bool {
        a.closed
            && b.mesh
                .vertices()
                .iter()
                .any(|v| a.mesh.contains_point(pa, &(pb * v)))
    }

    /// The first body inside an obstacle or another body (or holding one) at `q`.
    pub fn containment(&self, q: &[f64]) -> Option<String> {
        let k = self.bodies.len();
        let id = Isometry::identity();
        for i in 0..k {
            let (b, pi) = (&self.bodies[i], pose(q, i));
            if self
                .obstacles
                .iter()
                .any(|o| Self::holds(o, &id, b, &pi) || Self::holds(b, &pi, o, &id))
            {
                return Some(format!("body \"{}\" and an obstacle", self.names[i]));
            }
            for j in i + 1..k {
                let (c, pj) = (&self.bodies[j], pose(q, j));
                if Self::holds(b, &pi, c, &pj) || Self::holds(c, &pj, b, &pi) {
                    return Some(format!(
                        "bodies \"{}\" and \"{}\"",
                        self.names[i], self.names[j]
                    ));
                }
            }
        }
        None
    }

    /// Certifies the motion from `a` to `b`: every body linearly in position and about one
    /// axis the shorter way in orientation, all at once.
    pub fn certify_motion(&self, a: &[f64], b: &[f64]) -> Result<(), String> {
        let k = self.bodies.len();
        let mut moves = Vec::with_capacity(k);
        let mut fastest = 0.0f64;
        for i in 0..k {
            let (p, r) = (&a[POSE * i..POSE * i + POSE], &b[POSE * i..POSE * i + POSE]);
            let (ra, mut rb) = (orientation(p), orientation(r));
            if ra.coords.dot(&rb.coords) < 0.0 {
                rb = UnitQuaternion::new_unchecked(-rb.into_inner());
            }
            let dp = Vector::new(r[0] - p[0], r[1] - p[1], r[2] - p[2]);
            let rel = rb * ra.inverse();
            let angle = rel.angle();
            let axis = rel.axis().unwrap_or(Unit::new_normalize(Vector::x()));
            fastest = fastest.max(dp.norm() + self.radii[i] * angle);
            moves.push((dp, ra, axis, angle));
        }
        let at = |t: f64| -> Vec<f64> {
            let mut q = a.to_vec();
            for (i, (dp, ra, axis, angle)) in moves.iter().enumerate() {
                let r = UnitQuaternion::from_axis_angle(axis, t * angle) * ra;
                let p = &mut q[POSE * i..POSE * i + POSE];
                for c in 0..3 {
                    p[c] += t * dp[c];
                }
                p[3..7].copy_from_slice(&[r.i, r.j, r.k, r.w]);
            }
            q
        };
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

    /// Certifies a path: every reference point in the bounds, no containment at the start,
    /// every motion.
    pub fn certify_path(&self, path: &[Config]) -> Result<(), String> {
        let k = self.bodies.len();
        for q in path {
            if q.len() != POSE * k || !q.iter().all(|v| v.is_finite()) {
                return Err(format!(
                    "{} is not a configuration of {k} bodies in space",
                    short::config(q)
                ));
            }
            for i in 0..k {
                in_box(&q[POSE * i..POSE * i + 3], &self.lower, &self.upper)?;
            }
        }
        if let Some(q) = path.first() {
            if let Some(pair) = self.containment(q) {
                return Err(format!(
                    "at {}: {pair} lie one inside the other",
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
