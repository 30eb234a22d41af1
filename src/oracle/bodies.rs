//! Several polygonal bodies moving in the plane among polygons: exact collision intervals of
//! the seed's motions of concurrently moving objects (CHS Chapter 2).
//!
//! "At a given time either one object may rotate about a fixed axis with constant angular
//! velocity or all may translate simultaneously, each with its own fixed speed and direction."
//! A motion of SE(2)^k ([`crate::space::bodies`]) is therefore one of
//!
//! - **all bodies translate**, body `i` by its own vector `mᵢ` per unit parameter: body `i`
//!   against the obstacles is a translation of one polygonal robot, answered by the
//!   [`Polygons`] oracle; bodies `i` and `j` against each other are one *relative*
//!   translation ("we exploit the relative nature of translational motions"): in body `j`'s
//!   frame body `i` translates by `R(−θⱼ)(mᵢ − mⱼ)` past the static body `j`, the same
//!   translation oracle again;
//! - **body `r` turns** about its reference point: body `r` against the obstacles and against
//!   every other body (static, in its own frame) is a rotation of one polygonal robot; every
//!   other body stands still, so it collides throughout or never.
//!
//! Each pair of bodies is asked once per motion, and only if the discs that bound the two
//! bodies can meet along it: for a translation the relative path of their reference points
//! must come within the sum of their radii, for a turn the two reference points must lie
//! that close. The answer is the union of the parts' answers, so it is exact when they are.
//! One motion is one call; the parts add the primitive pairs they test to
//! [`CallCounts::pairs_tested`].

use super::polygons::Polygons;
use super::several::{self, Parts};
use super::{CallCounts, CollisionOracle, OracleError};
use crate::geometry::Polygon;
use crate::interval::{Interval, IntervalList};
use crate::space::{Change, Motion};

/// Slack added to the sum of two bodies' radii before a pair is skipped: the exact tests
/// treat touching (within a tolerance) as collision, so the skip must never be closer.
const PRUNE_SLACK: f64 = 1e-9;

/// Exact collision intervals of `k` polygonal bodies moving in the plane among polygons
/// (SE(2)^k: all bodies translate, or one turns).
///
/// ```
/// use viaroad::geometry::Polygon;
/// use viaroad::oracle::bodies::PlanarBodies;
/// use viaroad::oracle::{CallCounts, CollisionOracle};
/// use viaroad::space::{Change, Motion};
///
/// // two unit squares 3 apart on the x-axis move towards each other, each by 2:
/// // they touch when the gap of 2 between them has closed, at t = 1/2
/// let square = vec![Polygon::rectangle([0.0, 0.0], [0.5, 0.5]).unwrap()];
/// let oracle = PlanarBodies::new(vec![square.clone(), square], Vec::new());
/// let motion = Motion::segment(
///     vec![0.0, 0.0, 0.0, 3.0, 0.0, 0.0],
///     Change::Linear(vec![2.0, 0.0, 0.0, -2.0, 0.0, 0.0]),
/// );
/// let hits = oracle.intervals(&motion, &mut CallCounts::default()).unwrap();
/// assert!((hits.as_slice()[0].lo - 0.5).abs() < 1e-9);
/// ```
#[derive(Clone, Debug)]
pub struct PlanarBodies {
    /// Each body's radius about its reference point.
    radii: Vec<f64>,
    /// Body `i` (the robot) among the obstacles.
    world: Vec<Polygons>,
    /// Body `i` (the robot) against body `j` (the obstacle, in its own frame), at
    /// [`Self::pair_index`]`(i, j)`, for every `i ≠ j`.
    pairs: Vec<Polygons>,
}

/// What a motion of several bodies asks.
enum Kind<'a> {
    /// All bodies translate, body `i` by `delta[3i..3i + 2]` per unit parameter.
    Translation(&'a [f64]),
    /// Body `body` turns by `omega` per unit parameter; the others stand still.
    Rotation { body: usize, omega: f64 },
}

impl PlanarBodies {
    /// `bodies[i]` is body `i`'s parts in its body frame (reference point at the origin),
    /// `obstacles` in the world frame. Enveloping is on in every part.
    pub fn new(bodies: Vec<Vec<Polygon>>, obstacles: Vec<Polygon>) -> PlanarBodies {
        let k = bodies.len();
        let world: Vec<Polygons> = bodies
            .iter()
            .map(|b| Polygons::new(b.clone(), obstacles.clone()))
            .collect();
        let radii = world.iter().map(Polygons::robot_radius).collect();
        let mut pairs = Vec::with_capacity(k * k.saturating_sub(1));
        for (i, robot) in bodies.iter().enumerate() {
            for (j, other) in bodies.iter().enumerate() {
                if i != j {
                    pairs.push(Polygons::new(robot.clone(), other.clone()));
                }
            }
        }
        PlanarBodies {
            radii,
            world,
            pairs,
        }
    }

    /// Number of bodies.
    pub fn body_count(&self) -> usize {
        self.world.len()
    }

    /// Body `i` among the obstacles.
    pub fn body_oracle(&self, i: usize) -> &Polygons {
        &self.world[i]
    }

    fn pair_index(&self, i: usize, j: usize) -> usize {
        several::pair_index(self.world.len(), i, j)
    }

    fn classify<'m>(&self, motion: &'m Motion) -> Result<Kind<'m>, OracleError> {
        let k = self.world.len();
        let Change::Linear(delta) = &motion.change else {
            return Err(OracleError::Unsupported(
                "bodies: an SE(3) rotation (Change::Rotation) in the plane".into(),
            ));
        };
        if motion.origin.len() != 3 * k || delta.len() != 3 * k {
            return Err(OracleError::Unsupported(format!(
                "bodies: {k} bodies in the plane have {} coordinates, got an origin of {} and a \
                 change of {}",
                3 * k,
                motion.origin.len(),
                delta.len()
            )));
        }
        if !motion.origin.iter().chain(delta).all(|v| v.is_finite()) {
            return Err(OracleError::Unsupported(
                "bodies: a motion with a coordinate that is not a finite number".into(),
            ));
        }
        let mut turning = (0..k).filter(|&i| delta[3 * i + 2] != 0.0);
        let Some(body) = turning.next() else {
            return Ok(Kind::Translation(delta));
        };
        let translates = delta.chunks_exact(3).any(|d| d[0] != 0.0 || d[1] != 0.0);
        if turning.next().is_some() || translates {
            return Err(OracleError::Unsupported(
                "bodies: only one body turns at a time, and never while the bodies translate"
                    .into(),
            ));
        }
        Ok(Kind::Rotation {
            body,
            omega: delta[3 * body + 2],
        })
    }

    /// Body `i`'s pose relative to body `j`'s frame, and the vector `v` (world frame) seen
    /// from that frame.
    fn relative(origin: &[f64], i: usize, j: usize, v: [f64; 2]) -> ([f64; 3], [f64; 2]) {
        let (pi, pj) = (&origin[3 * i..3 * i + 3], &origin[3 * j..3 * j + 3]);
        let (s, c) = (-pj[2]).sin_cos();
        let rot = |x: f64, y: f64| [c * x - s * y, s * x + c * y];
        let p = rot(pi[0] - pj[0], pi[1] - pj[1]);
        ([p[0], p[1], pi[2] - pj[2]], rot(v[0], v[1]))
    }

    /// Whether bodies `i` and `j` (reference points `d0 + t·dm` apart, `t ∈ range`) can meet.
    fn may_meet(&self, i: usize, j: usize, d0: [f64; 2], dm: [f64; 2], range: Interval) -> bool {
        let reach = self.radii[i] + self.radii[j] + PRUNE_SLACK;
        let mm = dm[0] * dm[0] + dm[1] * dm[1];
        let t = if mm > 0.0 {
            (-(d0[0] * dm[0] + d0[1] * dm[1]) / mm).clamp(range.lo, range.hi)
        } else {
            0.0
        };
        let t = if t.is_finite() { t } else { 0.0 };
        let (x, y) = (d0[0] + t * dm[0], d0[1] + t * dm[1]);
        // a NaN distance may meet: only a sure miss skips the pair
        let d = x.hypot(y);
        d <= reach || d.is_nan()
    }
}

impl Parts for PlanarBodies {
    type Part = Polygons;

    fn parts(&self, motion: &Motion) -> Result<Vec<(&Polygons, Motion)>, OracleError> {
        let k = self.world.len();
        let o = &motion.origin;
        let one = |origin: [f64; 3], change: [f64; 3]| Motion {
            origin: origin.to_vec(),
            change: Change::Linear(change.to_vec()),
            range: motion.range,
            sweep: motion.sweep,
        };
        let mut parts = Vec::new();
        match self.classify(motion)? {
            Kind::Translation(delta) => {
                for i in 0..k {
                    let pose = [o[3 * i], o[3 * i + 1], o[3 * i + 2]];
                    let m = [delta[3 * i], delta[3 * i + 1], 0.0];
                    parts.push((&self.world[i], one(pose, m)));
                }
                for i in 0..k {
                    for j in i + 1..k {
                        let dm = [
                            delta[3 * i] - delta[3 * j],
                            delta[3 * i + 1] - delta[3 * j + 1],
                        ];
                        let d0 = [o[3 * i] - o[3 * j], o[3 * i + 1] - o[3 * j + 1]];
                        if !self.may_meet(i, j, d0, dm, motion.range) {
                            continue;
                        }
                        let (pose, v) = Self::relative(o, i, j, dm);
                        parts.push((
                            &self.pairs[self.pair_index(i, j)],
                            one(pose, [v[0], v[1], 0.0]),
                        ));
                    }
                }
            }
            Kind::Rotation { body, omega } => {
                let pose = [o[3 * body], o[3 * body + 1], o[3 * body + 2]];
                parts.push((&self.world[body], one(pose, [0.0, 0.0, omega])));
                for j in (0..k).filter(|&j| j != body) {
                    let d0 = [o[3 * body] - o[3 * j], o[3 * body + 1] - o[3 * j + 1]];
                    if self.may_meet(body, j, d0, [0.0, 0.0], motion.range) {
                        let (rel, _) = Self::relative(o, body, j, [0.0, 0.0]);
                        parts.push((
                            &self.pairs[self.pair_index(body, j)],
                            one(rel, [0.0, 0.0, omega]),
                        ));
                    }
                }
            }
        }
        Ok(parts)
    }

    fn static_collision(&self, q: &[f64], moving: Option<usize>, counts: &mut CallCounts) -> bool {
        let k = self.world.len();
        let fixed = |i: &usize| Some(*i) != moving;
        for i in (0..k).filter(fixed) {
            if self.world[i].collides(&q[3 * i..3 * i + 3], counts) {
                return true;
            }
        }
        for i in (0..k).filter(fixed) {
            for j in (i + 1..k).filter(fixed) {
                let d0 = [q[3 * i] - q[3 * j], q[3 * i + 1] - q[3 * j + 1]];
                if !self.may_meet(i, j, d0, [0.0, 0.0], Interval::UNIT) {
                    continue;
                }
                let (rel, _) = Self::relative(q, i, j, [0.0, 0.0]);
                if self.pairs[self.pair_index(i, j)].collides(&rel, counts) {
                    return true;
                }
            }
        }
        false
    }

    fn turning_body(&self, motion: &Motion) -> Result<Option<usize>, OracleError> {
        Ok(match self.classify(motion)? {
            Kind::Rotation { body, .. } => Some(body),
            Kind::Translation(_) => None,
        })
    }
}

impl CollisionOracle for PlanarBodies {
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        several::intervals(self, motion, counts)
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        if q.len() != 3 * self.world.len() || !q.iter().all(|v| v.is_finite()) {
            // not a configuration of this scene: never call it free
            return true;
        }
        self.static_collision(q, None, counts)
    }

    fn body_collides(&self, q: &[f64], body: usize, counts: &mut CallCounts) -> Option<bool> {
        let k = self.world.len();
        if body >= k || q.len() != 3 * k || !q[..3 * body + 3].iter().all(|v| v.is_finite()) {
            return Some(true);
        }
        if self.world[body].collides(&q[3 * body..3 * body + 3], counts) {
            return Some(true);
        }
        Some((0..body).any(|j| {
            let d0 = [q[3 * body] - q[3 * j], q[3 * body + 1] - q[3 * j + 1]];
            self.may_meet(body, j, d0, [0.0, 0.0], Interval::UNIT) && {
                let (rel, _) = Self::relative(q, body, j, [0.0, 0.0]);
                self.pairs[self.pair_index(body, j)].collides(&rel, counts)
            }
        }))
    }

    fn motion_is_free(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<bool, OracleError> {
        several::motion_is_free(self, motion, counts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::space::Sweep;

    fn square() -> Vec<Polygon> {
        vec![Polygon::rectangle([0.0, 0.0], [0.5, 0.5]).unwrap()]
    }

    fn oracle() -> PlanarBodies {
        let wall = Polygon::rectangle([0.0, 2.0], [10.0, 0.5]).unwrap();
        PlanarBodies::new(vec![square(), square(), square()], vec![wall])
    }

    fn hits(o: &PlanarBodies, origin: Vec<f64>, delta: Vec<f64>) -> Vec<Interval> {
        let m = Motion::segment(origin, Change::Linear(delta));
        o.intervals(&m, &mut CallCounts::default())
            .unwrap()
            .as_slice()
            .to_vec()
    }

    #[test]
    fn bodies_translating_together_do_not_meet() {
        let o = oracle();
        let q = vec![0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 4.0, 0.0, 0.0];
        let same = vec![1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0];
        assert!(hits(&o, q.clone(), same).is_empty());
        // the last body runs into the wall above it when it rises by 1 of 2
        let up = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0];
        let h = hits(&o, q.clone(), up);
        assert!((h[0].lo - 0.5).abs() < 1e-9, "{h:?}");
        // the first body chases the second, which moves on more slowly: they meet at t = 1/2
        let chase = vec![4.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        let h = hits(&o, q, chase);
        assert!((h[0].lo - 0.5).abs() < 1e-9, "{h:?}");
    }

    #[test]
    fn a_turning_body_meets_its_neighbour_and_static_collisions_block_all() {
        let o = oracle();
        // a square's corner reaches 0.5·√2 ≈ 0.707 from its centre: two squares 1.2 apart
        // (gap 0.2) touch as one turns by 45°, whose half-diagonal then reaches 0.5 + 0.207
        let q = vec![0.0, 0.0, 0.0, 1.2, 0.0, 0.0, 5.0, 0.0, 0.0];
        let turn = vec![
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            std::f64::consts::FRAC_PI_2,
            0.0,
            0.0,
            0.0,
        ];
        assert!(!hits(&o, q.clone(), turn.clone()).is_empty());
        // the third body turning far away is free
        let far = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
        assert!(hits(&o, q.clone(), far.clone()).is_empty());
        // … unless two static bodies overlap: then the whole turn collides
        let overlapping = vec![0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 5.0, 0.0, 0.0];
        let h = hits(&o, overlapping, far);
        assert_eq!(h, vec![Interval::UNIT]);
        // a simultaneous translation and turn is not one of the seed's motions
        let m = Motion::segment(
            q,
            Change::Linear(vec![1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]),
        );
        assert!(o.intervals(&m, &mut CallCounts::default()).is_err());
        assert_eq!(m.sweep, Sweep::Segment);
    }
}
