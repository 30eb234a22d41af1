//! Several polyhedral bodies moving in space among polyhedra: exact collision intervals of the
//! seed's motions of concurrently moving objects (CHS Chapter 2), the spatial twin of
//! [`super::bodies`].
//!
//! A motion of SE(3)^k ([`crate::space::bodies3`]) is one of
//!
//! - **all bodies translate**, body `i` by its own vector `mᵢ` per unit parameter: body `i`
//!   against the obstacles is a translation of one polyhedral robot, answered by the
//!   [`Polyhedra`] oracle; bodies `i` and `j` against each other are one *relative*
//!   translation ("we exploit the relative nature of translational motions"): in body `j`'s
//!   frame body `i` translates by `Rⱼᵀ(mᵢ − mⱼ)` past the static body `j`, the same
//!   translation oracle with body `j` as its one obstacle;
//! - **body `r` turns** about a fixed axis `a` through its reference point
//!   ([`Change::BodyRotation`]): body `r` against the obstacles is a rotation of one
//!   polyhedral robot; against every other body `j` (static, in its own frame) it turns about
//!   `Rⱼᵀa` through its reference point seen from `j`; every other body stands still, so it
//!   collides throughout or never.
//!
//! Each pair of bodies is asked once per motion, and only if the balls that bound the two
//! bodies about their reference points can meet along it: for a translation the relative path
//! of their reference points must come within the sum of their radii, for a turn the two
//! reference points must lie that close. The answer is the union of the parts' answers, so it
//! is exact when they are (containment included: a body wholly inside another closed body is
//! a collision, as in [`Polyhedra`]). One motion is one call; the parts add the primitive pairs
//! they test to [`CallCounts::pairs_tested`].

use super::polyhedra::Polyhedra;
use super::several::{self, Parts};
use super::{CallCounts, CollisionOracle, OracleError};
use crate::geometry::TriMesh;
use crate::interval::{Interval, IntervalList};
use crate::space::bodies3::POSE;
use crate::space::rotation::{quat_from_slice, quat_to_slice};
use crate::space::{Change, Motion};
use nalgebra::Vector3;

/// Slack added to the sum of two bodies' radii before a pair is skipped: the exact tests
/// treat touching (within a tolerance) as collision, so the skip must never be closer.
const PRUNE_SLACK: f64 = 1e-9;

/// Exact collision intervals of `k` polyhedral bodies moving in space among polyhedra
/// (SE(3)^k: all bodies translate, or one turns about a fixed axis).
///
/// ```
/// use viaroad::geometry::TriMesh;
/// use viaroad::oracle::bodies3::SolidBodies;
/// use viaroad::oracle::{CallCounts, CollisionOracle};
/// use viaroad::space::{Change, Motion};
///
/// // two unit cubes 3 apart on the x-axis move towards each other, each by 2:
/// // they touch when the gap of 2 between them has closed, at t = 1/2
/// let cube = TriMesh::cuboid([0.5; 3]).unwrap();
/// let oracle = SolidBodies::new(vec![cube.clone(), cube], Vec::new());
/// let at = |x: f64| [x, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
/// let motion = Motion::segment(
///     [at(0.0), at(3.0)].concat(),
///     Change::Linear([[2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [-2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]].concat()),
/// );
/// let hits = oracle.intervals(&motion, &mut CallCounts::default()).unwrap();
/// assert!((hits.as_slice()[0].lo - 0.5).abs() < 1e-9);
/// ```
pub struct SolidBodies {
    /// Each body's radius about its reference point.
    radii: Vec<f64>,
    /// Body `i` (the robot) among the obstacles.
    world: Vec<Polyhedra>,
    /// Body `i` (the robot) against body `j` (the obstacle, in its own frame), at
    /// [`Self::pair_index`]`(i, j)`, for every `i ≠ j`.
    pairs: Vec<Polyhedra>,
}

/// What a motion of several bodies asks.
enum Kind<'a> {
    /// All bodies translate, body `i` by `delta[7i..7i + 3]` per unit parameter.
    Translation(&'a [f64]),
    /// Body `body` turns about the world `axis` by `angle` per unit parameter.
    Rotation {
        body: usize,
        axis: [f64; 3],
        angle: f64,
    },
}

impl SolidBodies {
    /// `bodies[i]` is body `i`'s mesh in its body frame (reference point at the origin),
    /// `obstacles` in the world frame.
    pub fn new(bodies: Vec<TriMesh>, obstacles: Vec<TriMesh>) -> SolidBodies {
        let radii = bodies.iter().map(TriMesh::radius).collect();
        let world = bodies
            .iter()
            .map(|b| Polyhedra::new(b.clone(), obstacles.clone()))
            .collect();
        let k = bodies.len();
        let mut pairs = Vec::with_capacity(k * k.saturating_sub(1));
        for (i, robot) in bodies.iter().enumerate() {
            for (j, other) in bodies.iter().enumerate() {
                if i != j {
                    pairs.push(Polyhedra::new(robot.clone(), vec![other.clone()]));
                }
            }
        }
        SolidBodies {
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
    pub fn body_oracle(&self, i: usize) -> &Polyhedra {
        &self.world[i]
    }

    fn pair_index(&self, i: usize, j: usize) -> usize {
        several::pair_index(self.world.len(), i, j)
    }

    fn classify<'m>(&self, motion: &'m Motion) -> Result<Kind<'m>, OracleError> {
        let k = self.world.len();
        if motion.origin.len() != POSE * k || !motion.origin.iter().all(|v| v.is_finite()) {
            return Err(OracleError::Unsupported(format!(
                "bodies in space: {k} bodies have {} finite coordinates, got an origin of {}",
                POSE * k,
                motion.origin.len()
            )));
        }
        match &motion.change {
            Change::Linear(delta) => {
                if delta.len() != POSE * k || !delta.iter().all(|v| v.is_finite()) {
                    return Err(OracleError::Unsupported(format!(
                        "bodies in space: a change of {} coordinates, {} finite numbers wanted",
                        delta.len(),
                        POSE * k
                    )));
                }
                if delta
                    .chunks_exact(POSE)
                    .any(|d| d[3..7].iter().any(|&v| v != 0.0))
                {
                    return Err(OracleError::Unsupported(
                        "bodies in space: a linear change of quaternion coordinates is not a \
                         turn about a fixed axis (translate, or turn one body with \
                         Change::BodyRotation)"
                            .into(),
                    ));
                }
                Ok(Kind::Translation(delta))
            }
            Change::BodyRotation { body, axis, angle } if *body < k => Ok(Kind::Rotation {
                body: *body,
                axis: *axis,
                angle: *angle,
            }),
            Change::BodyRotation { body, .. } => Err(OracleError::Unsupported(format!(
                "bodies in space: body {body} turns, there are {k}"
            ))),
            Change::Rotation { .. } => Err(OracleError::Unsupported(
                "bodies in space: a turn must name its body (Change::BodyRotation)".into(),
            )),
        }
    }

    /// Body `i`'s pose `[x, y, z, qx, qy, qz, qw]` relative to body `j`'s frame, and the world
    /// vector `v` seen from that frame.
    fn relative(q: &[f64], i: usize, j: usize, v: [f64; 3]) -> ([f64; 7], [f64; 3]) {
        let (pi, pj) = (&q[POSE * i..POSE * i + POSE], &q[POSE * j..POSE * j + POSE]);
        let (ri, rj) = (quat_from_slice(&pi[3..7]), quat_from_slice(&pj[3..7]));
        let inv = rj.inverse();
        let p = inv * Vector3::new(pi[0] - pj[0], pi[1] - pj[1], pi[2] - pj[2]);
        let mut pose = [p.x, p.y, p.z, 0.0, 0.0, 0.0, 1.0];
        quat_to_slice(&(inv * ri), &mut pose[3..7]);
        let w = inv * Vector3::from(v);
        (pose, [w.x, w.y, w.z])
    }

    /// Body `i`'s reference point.
    fn point(q: &[f64], i: usize) -> Vector3<f64> {
        Vector3::new(q[POSE * i], q[POSE * i + 1], q[POSE * i + 2])
    }

    /// Whether bodies `i` and `j` (reference points `d0 + t·dm` apart, `t ∈ range`) can meet.
    fn may_meet(
        &self,
        i: usize,
        j: usize,
        d0: Vector3<f64>,
        dm: Vector3<f64>,
        range: Interval,
    ) -> bool {
        let reach = self.radii[i] + self.radii[j] + PRUNE_SLACK;
        let mm = dm.norm_squared();
        let t = if mm > 0.0 {
            (-d0.dot(&dm) / mm).clamp(range.lo, range.hi)
        } else {
            0.0
        };
        let t = if t.is_finite() { t } else { 0.0 };
        // a NaN distance may meet: only a sure miss skips the pair
        let d = (d0 + t * dm).norm();
        d <= reach || d.is_nan()
    }
}

impl Parts for SolidBodies {
    type Part = Polyhedra;

    fn parts(&self, motion: &Motion) -> Result<Vec<(&Polyhedra, Motion)>, OracleError> {
        let k = self.world.len();
        let o = &motion.origin;
        let one = |origin: [f64; 7], change: Change| Motion {
            origin: origin.to_vec(),
            change,
            range: motion.range,
            sweep: motion.sweep,
        };
        let pose = |i: usize| {
            let mut p = [0.0; 7];
            p.copy_from_slice(&o[POSE * i..POSE * i + POSE]);
            p
        };
        let slide = |v: [f64; 3]| Change::Linear(vec![v[0], v[1], v[2], 0.0, 0.0, 0.0, 0.0]);
        let mut parts = Vec::new();
        match self.classify(motion)? {
            Kind::Translation(delta) => {
                let m = |i: usize| {
                    Vector3::new(delta[POSE * i], delta[POSE * i + 1], delta[POSE * i + 2])
                };
                for i in 0..k {
                    let v = m(i);
                    parts.push((&self.world[i], one(pose(i), slide([v.x, v.y, v.z]))));
                }
                for i in 0..k {
                    for j in i + 1..k {
                        let dm = m(i) - m(j);
                        let d0 = Self::point(o, i) - Self::point(o, j);
                        if !self.may_meet(i, j, d0, dm, motion.range) {
                            continue;
                        }
                        let (rel, v) = Self::relative(o, i, j, [dm.x, dm.y, dm.z]);
                        parts.push((&self.pairs[self.pair_index(i, j)], one(rel, slide(v))));
                    }
                }
            }
            Kind::Rotation { body, axis, angle } => {
                let turn = |axis| Change::Rotation { axis, angle };
                parts.push((&self.world[body], one(pose(body), turn(axis))));
                for j in (0..k).filter(|&j| j != body) {
                    let d0 = Self::point(o, body) - Self::point(o, j);
                    if self.may_meet(body, j, d0, Vector3::zeros(), motion.range) {
                        let (rel, a) = Self::relative(o, body, j, axis);
                        parts.push((&self.pairs[self.pair_index(body, j)], one(rel, turn(a))));
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
            if self.world[i].collides(&q[POSE * i..POSE * i + POSE], counts) {
                return true;
            }
        }
        for i in (0..k).filter(fixed) {
            for j in (i + 1..k).filter(fixed) {
                let d0 = Self::point(q, i) - Self::point(q, j);
                if !self.may_meet(i, j, d0, Vector3::zeros(), Interval::UNIT) {
                    continue;
                }
                let (rel, _) = Self::relative(q, i, j, [0.0; 3]);
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

impl CollisionOracle for SolidBodies {
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        several::intervals(self, motion, counts)
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        if q.len() != POSE * self.world.len() || !q.iter().all(|v| v.is_finite()) {
            // not a configuration of this scene: never call it free
            return true;
        }
        self.static_collision(q, None, counts)
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
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

    fn at(x: f64, y: f64) -> [f64; 7] {
        [x, y, 0.0, 0.0, 0.0, 0.0, 1.0]
    }

    fn oracle() -> SolidBodies {
        let cube = TriMesh::cuboid([0.5; 3]).unwrap();
        let wall = TriMesh::cuboid([5.0, 0.25, 5.0])
            .unwrap()
            .translated(Vector3::new(0.0, 2.0, 0.0));
        SolidBodies::new(vec![cube.clone(), cube.clone(), cube], vec![wall])
    }

    fn hits(o: &SolidBodies, origin: Vec<f64>, change: Change) -> Vec<Interval> {
        let m = Motion::segment(origin, change);
        o.intervals(&m, &mut CallCounts::default())
            .unwrap()
            .as_slice()
            .to_vec()
    }

    fn slide(v: [[f64; 3]; 3]) -> Change {
        Change::Linear(
            v.iter()
                .flat_map(|d| [d[0], d[1], d[2], 0.0, 0.0, 0.0, 0.0])
                .collect(),
        )
    }

    #[test]
    fn bodies_translating_together_do_not_meet() {
        let o = oracle();
        let q = [at(-2.0, 0.0), at(0.0, 0.0), at(2.0, 0.0)].concat();
        assert!(hits(&o, q.clone(), slide([[1.0, 0.0, 0.0]; 3])).is_empty());
        // the last body runs into the wall (y from 1.75) when it has risen by 1.25 of 2.5
        let up = slide([[0.0; 3], [0.0; 3], [0.0, 2.5, 0.0]]);
        let h = hits(&o, q.clone(), up);
        assert!((h[0].lo - 0.5).abs() < 1e-9, "{h:?}");
        // the first body chases the second, which moves on more slowly: they meet at t = 1/2
        let chase = slide([[4.0, 0.0, 0.0], [2.0, 0.0, 0.0], [4.0, 0.0, 0.0]]);
        let h = hits(&o, q, chase);
        assert!((h[0].lo - 0.5).abs() < 1e-9, "{h:?}");
    }

    #[test]
    fn a_turning_body_meets_its_neighbour_and_static_collisions_block_all() {
        let o = oracle();
        // cubes 1.2 apart (gap 0.2): turning one by 45° about z reaches 0.707 > 0.7 from its
        // centre along x, so it meets its neighbour
        let q = [at(0.0, 0.0), at(1.2, 0.0), at(-5.0, -3.0)].concat();
        let turn = |body, angle| Change::BodyRotation {
            body,
            axis: [0.0, 0.0, 1.0],
            angle,
        };
        assert!(!hits(&o, q.clone(), turn(1, FRAC_PI_2)).is_empty());
        // a quarter turn about x keeps the cube's extent along x: free
        let roll = Change::BodyRotation {
            body: 1,
            axis: [1.0, 0.0, 0.0],
            angle: FRAC_PI_4,
        };
        assert!(hits(&o, q.clone(), roll).is_empty());
        // the third body turning far away is free
        assert!(hits(&o, q.clone(), turn(2, 1.0)).is_empty());
        // … unless two static bodies overlap: then the whole turn collides
        let overlapping = [at(0.0, 0.0), at(0.5, 0.0), at(-5.0, -3.0)].concat();
        assert_eq!(hits(&o, overlapping, turn(2, 1.0)), vec![Interval::UNIT]);
        // neither a linear change of a quaternion nor an anonymous turn is a seed's motion
        let mut bad = vec![0.0; 21];
        bad[6] = 1.0;
        let m = Motion::segment(q.clone(), Change::Linear(bad));
        assert!(o.intervals(&m, &mut CallCounts::default()).is_err());
        let m = Motion::segment(
            q,
            Change::Rotation {
                axis: [0.0, 0.0, 1.0],
                angle: 1.0,
            },
        );
        assert!(o.intervals(&m, &mut CallCounts::default()).is_err());
    }
}
