//! Sampled checking of motions, like OMPL's `DiscreteMotionValidator`: the baseline.
//!
//! A motion is checked at discrete states spaced at most one *step* apart, where (as in OMPL)
//! the translation step is `resolution × extent` (the diagonal of the bounds) and the rotation
//! step is `resolution × π` radians of rotation (OMPL: `0.01 · π/2` in SO(3)'s quaternion-arc
//! metric, `0.01 · π` in SO(2)). Yes/no checks test the end state first and then the interior
//! states in bisection order, exactly like OMPL; the start is assumed valid.
//!
//! Interval answers are approximations: a run of colliding samples `i..=j` is reported as
//! `[t_{i-1}, t_{j+1}]`. Collisions thinner than a step can be missed entirely — which is why
//! this is the baseline and never the default.

use super::{CallCounts, CollisionOracle, OracleError, Workspace};
use crate::interval::{Interval, IntervalList};
use crate::space::{Change, Motion, Space, SpaceKind};
use std::collections::VecDeque;

/// OMPL's default state-validity-checking resolution (1 % of the space's extent).
pub const OMPL_DEFAULT_RESOLUTION: f64 = 0.01;

/// Checks motions by sampling states of `inner` at a fixed resolution.
pub struct Sampled<O> {
    inner: O,
    space: Space,
    translation_step: f64,
    rotation_step: f64,
}

impl<O: CollisionOracle> Sampled<O> {
    /// Samples at `resolution` (a fraction of the space's extent, OMPL's
    /// `setStateValidityCheckingResolution`); `inner` answers the state checks.
    pub fn new(space: Space, inner: O, resolution: f64) -> Self {
        let resolution = if resolution > 0.0 && resolution.is_finite() {
            resolution
        } else {
            OMPL_DEFAULT_RESOLUTION
        };
        Sampled {
            translation_step: resolution * space.extent(),
            rotation_step: resolution * std::f64::consts::PI,
            inner,
            space,
        }
    }

    /// Step along translations (length units).
    pub fn translation_step(&self) -> f64 {
        self.translation_step
    }

    /// Step along rotations (radians of rotation).
    pub fn rotation_step(&self) -> f64 {
        self.rotation_step
    }

    /// Number of steps `n` for the part `[lo, hi]` of a motion: the largest over translation
    /// and rotation of `ceil(distance / step)`, at least 1 (OMPL's `validSegmentCount`).
    pub fn step_count(&self, motion: &Motion, lo: f64, hi: f64) -> usize {
        let dt = (hi - lo).abs();
        let p = self.space.position_dim();
        let (trans, rot) = match &motion.change {
            // several bodies: the fastest body decides
            Change::Linear(d) if matches!(self.space.kind(), SpaceKind::Se2Bodies(_)) => {
                d.chunks_exact(3).fold((0.0f64, 0.0f64), |(t, r), b| {
                    (t.max(b[0].hypot(b[1]) * dt), r.max(b[2].abs() * dt))
                })
            }
            Change::Linear(d) => {
                let trans = d[..p].iter().map(|v| v * v).sum::<f64>().sqrt() * dt;
                let rot = if self.space.kind() == SpaceKind::Se2 {
                    d[2].abs() * dt
                } else {
                    0.0
                };
                (trans, rot)
            }
            Change::Rotation { angle, .. } | Change::BodyRotation { angle, .. } => {
                (0.0, angle.abs() * dt)
            }
        };
        let n_t = if self.translation_step > 0.0 {
            (trans / self.translation_step).ceil()
        } else {
            0.0
        };
        let n_r = (rot / self.rotation_step).ceil();
        (n_t.max(n_r) as usize).max(1)
    }

    fn bounded_range(motion: &Motion) -> Result<Interval, OracleError> {
        if motion.range.is_bounded() {
            Ok(motion.range)
        } else {
            Err(OracleError::Unsupported(
                "sampling an unbounded line; wrap the sampled oracle in Bounded".into(),
            ))
        }
    }

    fn sample_collides(
        &self,
        motion: &Motion,
        t: f64,
        q: &mut [f64],
        counts: &mut CallCounts,
    ) -> bool {
        motion.write_at(t, q);
        counts.state_checks += 1;
        self.inner.collides(q, counts)
    }
}

impl<O: CollisionOracle> CollisionOracle for Sampled<O> {
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        let mut out = IntervalList::new();
        self.intervals_into(motion, &mut out, &mut Workspace::new(), counts)?;
        Ok(out)
    }

    fn intervals_into(
        &self,
        motion: &Motion,
        out: &mut IntervalList,
        ws: &mut Workspace,
        counts: &mut CallCounts,
    ) -> Result<(), OracleError> {
        let range = Self::bounded_range(motion)?;
        let n = self.step_count(motion, range.lo, range.hi);
        let t_at = |i: usize| range.lo + (range.hi - range.lo) * (i as f64 / n as f64);
        // the states go to the workspace's configuration buffer (taken out, so that the inner
        // oracle may use the rest of the workspace for its state checks)
        let mut q = std::mem::take(&mut ws.config);
        q.clear();
        q.extend_from_slice(&motion.origin);
        out.clear();
        let mut run_start: Option<usize> = None;
        for i in 0..=n {
            let hit = self.sample_collides(motion, t_at(i), &mut q, counts);
            match (hit, run_start) {
                (true, None) => run_start = Some(i),
                (false, Some(s)) => {
                    out.push(Interval {
                        lo: t_at(s.saturating_sub(1)),
                        hi: t_at(i),
                    });
                    run_start = None;
                }
                _ => {}
            }
        }
        if let Some(s) = run_start {
            out.push(Interval {
                lo: t_at(s.saturating_sub(1)),
                hi: range.hi,
            });
        }
        ws.config = q;
        Ok(())
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        self.inner.collides(q, counts)
    }

    fn body_collides(&self, q: &[f64], body: usize, counts: &mut CallCounts) -> Option<bool> {
        self.inner.body_collides(q, body, counts)
    }

    fn motion_is_free(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<bool, OracleError> {
        let range = Self::bounded_range(motion)?;
        let n = self.step_count(motion, range.lo, range.hi);
        let t_at = |i: usize| range.lo + (range.hi - range.lo) * (i as f64 / n as f64);
        let mut q = motion.origin.clone();
        if self.sample_collides(motion, t_at(n), &mut q, counts) {
            return Ok(false);
        }
        // interior states in OMPL's bisection order
        let mut queue = VecDeque::new();
        if n >= 2 {
            queue.push_back((1usize, n - 1));
        }
        while let Some((lo, hi)) = queue.pop_front() {
            let mid = (lo + hi) / 2;
            if self.sample_collides(motion, t_at(mid), &mut q, counts) {
                return Ok(false);
            }
            if lo < mid {
                queue.push_back((lo, mid - 1));
            }
            if hi > mid {
                queue.push_back((mid + 1, hi));
            }
        }
        Ok(true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::oracle::discs::Discs;

    #[test]
    fn bisection_checks_every_interior_state_once() {
        let space = Space::euclidean(vec![0.0, 0.0], vec![1.0, 1.0]).unwrap();
        let s = Sampled::new(space, Discs::new(2, &[], &[]), 0.01);
        let m = Motion::segment(vec![0.0, 0.0], Change::Linear(vec![1.0, 1.0]));
        let mut c = CallCounts::default();
        assert!(s.motion_is_free(&m, &mut c).unwrap());
        assert_eq!(c.state_checks, 100); // n = 100 steps: the end plus 99 interior states
    }

    #[test]
    fn thin_obstacles_between_samples_are_missed() {
        let space = Space::euclidean(vec![0.0, 0.0], vec![1.0, 1.0]).unwrap();
        // length 1, step 0.01·√2: n = 71 steps, samples at i/71; a disc of radius 0.001
        // centred halfway between samples 35 and 36
        let discs = Discs::new(2, &[vec![35.5 / 71.0, 0.5]], &[0.001]);
        let s = Sampled::new(space, discs.clone(), 0.01);
        let m = Motion::segment(vec![0.0, 0.5], Change::Linear(vec![1.0, 0.0]));
        assert!(s.motion_is_free(&m, &mut CallCounts::default()).unwrap());
        assert!(!discs
            .motion_is_free(&m, &mut CallCounts::default())
            .unwrap());
    }
}
