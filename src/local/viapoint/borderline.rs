//! Borderlines and via points (CHS §1.2–1.5).
//!
//! "Every path from a to z … must cross this borderline separating a from z. In order to avoid
//! the obstacle such a crossing can only take place on the free sections of b." The borderline
//! crosses the blocked motion at a *base point* (Table A.4), runs perpendicular to it (within the
//! blocked DOF group, or in another group, CHS §1.5), and its free sections give the via points:
//! their centres, ranked by `V_β(d, l) = d / l^β` with `d` the distance of the via point from the
//! blocked motion and `l` the length of its free section (CHS §1.3, "Via Points").

use super::directions::{perpendicular_into, DirScratch};
use super::options::{BasePoint, Directions, ViaPointOptions};
use crate::interval::{Interval, IntervalList};
use crate::space::{Change, Config, Group, GroupKind, Motion, Space, Sweep};
use rand::Rng;

/// The motion parameter in `[0, 1]` where the borderline crosses the blocked motion, given its
/// collision intervals (non-empty).
pub fn base_parameter(strategy: BasePoint, collisions: &IntervalList, rng: &mut impl Rng) -> f64 {
    let ivs = collisions.as_slice();
    let uniform = |iv: &Interval, rng: &mut dyn rand::RngCore| {
        if iv.hi > iv.lo {
            rng.random_range(iv.lo..=iv.hi)
        } else {
            iv.lo
        }
    };
    match strategy {
        BasePoint::StartOfFirst => ivs[0].lo,
        BasePoint::RandomInFirst => uniform(&ivs[0], rng),
        BasePoint::CentreOfFirst => ivs[0].centre(),
        BasePoint::CentreOfRandom => ivs[rng.random_range(0..ivs.len())].centre(),
        BasePoint::CentreOfMiddle => ivs[ivs.len() / 2].centre(),
        BasePoint::CentreNearestMiddle => ivs
            .iter()
            .map(Interval::centre)
            .min_by(|a, b| (a - 0.5).abs().total_cmp(&(b - 0.5).abs()))
            .unwrap_or(0.5),
        BasePoint::MiddleOfMotion => 0.5,
        BasePoint::RandomInMotion => rng.random_range(0.0..=1.0),
    }
    .clamp(0.0, 1.0)
}

/// Where a borderline is erected: the blocked motion, the index of the DOF group it moves in,
/// and the base point on it.
pub struct Crossing<'a> {
    /// The blocked straight motion.
    pub motion: &'a Motion,
    /// Index (into the planner's groups) of the group it changes.
    pub group: usize,
    /// The base point.
    pub base: &'a [f64],
}

/// Reusable buffers for [`borderlines_into`]: the motions are slots overwritten round after
/// round, so that erecting borderlines allocates nothing in steady state.
#[derive(Debug, Default)]
pub struct Lines {
    /// Motion slots and the group each one dodges in; the first [`Lines::len`] are current.
    slots: Vec<(Motion, usize)>,
    len: usize,
    dirs: Vec<f64>,
    unit: Vec<f64>,
    scratch: DirScratch,
}

impl Lines {
    /// The current borderlines.
    pub fn as_slice(&self) -> &[(Motion, usize)] {
        &self.slots[..self.len]
    }

    /// Number of current borderlines.
    pub fn len(&self) -> usize {
        self.len
    }

    fn next_slot(&mut self) -> &mut (Motion, usize) {
        if self.len == self.slots.len() {
            self.slots.push((Motion::default(), 0));
        }
        self.len += 1;
        &mut self.slots[self.len - 1]
    }
}

/// The borderlines of round `round` through the crossing's base point: unbounded motions paired
/// with the group each one dodges in, written into `lines` (overwriting what was there).
///
/// Round 0 holds the directions perpendicular to the motion within its own group and — if
/// `dodge_other_groups`, or if the group has no perpendicular direction (one axis, an angle) —
/// lines along the axes of every other linear group and full turns in every other rotational
/// group (about the world axes for a quaternion). Later rounds are the rotated bases of
/// [`Directions::Basis`](super::options::Directions) or nothing.
pub fn borderlines_into(
    space: &Space,
    groups: &[Group],
    options: &ViaPointOptions,
    crossing: &Crossing,
    round: u32,
    rng: &mut impl Rng,
    lines: &mut Lines,
) {
    let (blocked, blocked_group, base) = (crossing.motion, crossing.group, crossing.base);
    let g = &groups[blocked_group];
    lines.len = 0;
    match (g.kind, &blocked.change) {
        (GroupKind::Linear, Change::Linear(delta)) => {
            let mut u = std::mem::take(&mut lines.unit);
            u.clear();
            u.extend(g.indices().map(|i| delta[i]));
            let n = u.iter().map(|x| x * x).sum::<f64>().sqrt();
            if n > 0.0 {
                u.iter_mut().for_each(|x| *x /= n);
                let mut dirs = std::mem::take(&mut lines.dirs);
                let count = perpendicular_into(
                    &u,
                    options.directions,
                    round,
                    rng,
                    &mut lines.scratch,
                    &mut dirs,
                );
                let m = u.len();
                for d in dirs.chunks_exact(m).take(count) {
                    let slot = lines.next_slot();
                    space.line_through_into(base, g, d, &mut slot.0);
                    slot.1 = blocked_group;
                }
                lines.dirs = dirs;
                if let (0, Some(share)) = (round, options.sidestep) {
                    sidestep_lines(space, groups, crossing, &u, share * n, lines);
                }
            }
            lines.unit = u;
        }
        (
            GroupKind::Quaternion,
            Change::Rotation { axis, .. } | Change::BodyRotation { axis, .. },
        ) => {
            let mut dirs = std::mem::take(&mut lines.dirs);
            let count = perpendicular_into(
                axis,
                options.directions,
                round,
                rng,
                &mut lines.scratch,
                &mut dirs,
            );
            for d in dirs.chunks_exact(3).take(count) {
                let slot = lines.next_slot();
                space.turn_through_into(base, g, [d[0], d[1], d[2]], &mut slot.0);
                slot.1 = blocked_group;
            }
            lines.dirs = dirs;
        }
        _ => {}
    }
    if round == 0 && (options.dodge_other_groups || lines.len == 0) {
        let mut d = std::mem::take(&mut lines.unit);
        for (k, h) in groups.iter().enumerate() {
            if k == blocked_group {
                continue;
            }
            match h.kind {
                GroupKind::Linear => {
                    for i in 0..h.len() {
                        d.clear();
                        d.resize(h.len(), 0.0);
                        d[i] = 1.0;
                        let slot = lines.next_slot();
                        space.line_through_into(base, h, &d, &mut slot.0);
                        slot.1 = k;
                    }
                }
                GroupKind::Angle => {
                    let slot = lines.next_slot();
                    space.turn_through_into(base, h, [0.0, 0.0, 1.0], &mut slot.0);
                    slot.1 = k;
                }
                GroupKind::Quaternion => {
                    for axis in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
                        let slot = lines.next_slot();
                        space.turn_through_into(base, h, axis, &mut slot.0);
                        slot.1 = k;
                    }
                }
            }
        }
        lines.unit = d;
    }
}

/// The borderlines of CHS Fig 1.4, whose reference point lies off the blocked motion: the base
/// point steps by `step` (both ways) along each axis of every other linear group, and a line
/// through the stepped point runs along the blocked motion's unit direction `u`.
fn sidestep_lines(
    space: &Space,
    groups: &[Group],
    crossing: &Crossing,
    u: &[f64],
    step: f64,
    lines: &mut Lines,
) {
    if !(step.is_finite() && step > 0.0) {
        return;
    }
    let g = &groups[crossing.group];
    let mut q = crossing.base.to_vec();
    for (k, h) in groups.iter().enumerate() {
        if k == crossing.group || h.kind != GroupKind::Linear {
            continue;
        }
        for i in h.indices() {
            for sign in [1.0, -1.0] {
                q[i] = crossing.base[i] + sign * step;
                let slot = lines.next_slot();
                space.line_through_into(&q, g, u, &mut slot.0);
                slot.1 = crossing.group;
            }
            q[i] = crossing.base[i];
        }
    }
}

/// Whether [`borderlines_into`] certainly writes no borderline for `round`, whatever the blocked
/// motion and base point: rounds after the first hold only the blocked group's rotated bases
/// (or nothing for random directions, an angle, or a plane whose one perpendicular has no
/// rotation), so the search can mark a node's rounds exhausted without building the blocked
/// motion and erecting nothing (in the disc experiment two in five calls of
/// `extend_vias` were such an empty round). `false` means "ask [`borderlines_into`]".
pub fn round_is_empty(
    groups: &[Group],
    options: &ViaPointOptions,
    blocked_group: usize,
    round: u32,
) -> bool {
    if round == 0 {
        return false;
    }
    let g = &groups[blocked_group];
    // the dimension of the vector whose perpendiculars `perpendicular_into` completes
    let m = match g.kind {
        GroupKind::Linear => g.len(),
        GroupKind::Quaternion => 3,
        GroupKind::Angle => return true,
    };
    m < 2
        || match options.directions {
            Directions::Basis { rotations, .. } => round > rotations || m < 3,
            Directions::Random { .. } => true,
        }
}

/// A via point on a borderline and what it is worth.
#[derive(Clone, Copy, Debug)]
pub struct Candidate {
    /// Parameter of the via point on its borderline.
    pub t: f64,
    /// `V_β(d, l)`; smaller is better.
    pub value: f64,
}

/// The via point at parameter `t` of a borderline, normalised.
pub fn via_point(space: &Space, motion: &Motion, t: f64) -> Config {
    let mut q = motion.at(t);
    space.normalize(&mut q);
    q
}

/// The free sections of a borderline with collision intervals `collisions`: for a full turn the
/// section across `t = ±½` is joined into one (it is one arc of the circle), with `hi > ½`.
#[cfg(test)]
pub fn free_sections(motion: &Motion, collisions: &IntervalList) -> Vec<Interval> {
    let mut out = Vec::new();
    free_sections_into(motion, collisions, &mut IntervalList::new(), &mut out);
    out
}

/// Allocation-free form of the free sections: `complement` is scratch, `out` the answer.
pub fn free_sections_into(
    motion: &Motion,
    collisions: &IntervalList,
    complement: &mut IntervalList,
    out: &mut Vec<Interval>,
) {
    collisions.complement_within_into(motion.range, complement);
    out.clear();
    out.extend(complement.iter().copied().filter(|iv| iv.hi > iv.lo));
    let v = out;
    if motion.sweep == Sweep::Turn && v.len() > 1 {
        let (first, last) = (v[0], v[v.len() - 1]);
        if first.lo <= motion.range.lo && last.hi >= motion.range.hi {
            v.pop();
            v[0] = Interval {
                lo: last.lo,
                hi: first.hi + (motion.range.hi - motion.range.lo),
            };
        }
    }
}

/// Via points on one borderline: the centres of its bounded free sections, valued by
/// `V_β(d, l) = d / l^β` (CHS §1.3). A turn that is free all the way round has no centre; it
/// offers the quarter and half turns instead. `scratch` (one configuration long) saves
/// allocating a configuration per candidate: only the via points kept become configurations.
#[cfg(test)]
pub fn candidates(
    space: &Space,
    motion: &Motion,
    sections: &[Interval],
    base: &[f64],
    beta: f64,
    scratch: &mut [f64],
) -> Vec<Candidate> {
    let mut out = Vec::new();
    candidates_into(space, motion, sections, base, beta, scratch, &mut out);
    out
}

/// [`candidates`] appended to `out` instead of a new vector (the search keeps one list).
pub fn candidates_into(
    space: &Space,
    motion: &Motion,
    sections: &[Interval],
    base: &[f64],
    beta: f64,
    scratch: &mut [f64],
    out: &mut Vec<Candidate>,
) {
    let period = motion.range.hi - motion.range.lo;
    // a linear motion's length per unit parameter, once per borderline rather than once per
    // candidate: `motion_length(m, 0, len)` is `|len - 0| · speed` with this very `speed`
    // (`|1 - 0| · speed` is exact), so `l` keeps its bits; a rotation's length multiplies in
    // another order and is asked as it is
    let speed = match motion.change {
        Change::Linear(_) => Some(space.motion_length(motion, 0.0, 1.0)),
        Change::Rotation { .. } | Change::BodyRotation { .. } => None,
    };
    let mut add = |t: f64, len: f64, scratch: &mut [f64]| {
        motion.write_at(t, scratch);
        space.normalize(scratch);
        let d = space.distance(scratch, base);
        let l = match speed {
            Some(speed) => (len - 0.0).abs() * speed,
            None => space.motion_length(motion, 0.0, len),
        };
        let value = if beta == 0.0 { d } else { d / l.powf(beta) };
        if value.is_finite() {
            out.push(Candidate { t, value });
        }
    };
    for s in sections {
        if !s.is_bounded() || s.hi <= s.lo {
            continue;
        }
        if motion.sweep == Sweep::Turn && s.length() >= period {
            for t in [0.25, -0.25, 0.5] {
                add(t, period, scratch);
            }
            continue;
        }
        let mut c = s.centre();
        if motion.sweep == Sweep::Turn && c > motion.range.hi {
            c -= period;
        }
        add(c, s.length(), scratch);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::space::Change;

    #[test]
    fn turn_sections_join_across_the_seam() {
        let m = Motion::turn(
            vec![0.0, 0.0, 0.0],
            Change::Linear(vec![0.0, 0.0, std::f64::consts::TAU]),
        );
        let hits = IntervalList::from_bounds(-0.1, 0.2);
        let s = free_sections(&m, &hits);
        assert_eq!(s, vec![Interval { lo: 0.2, hi: 0.9 }]);
        let space = Space::se2([-1.0; 2], [1.0; 2], 1.0).unwrap();
        let c = candidates(&space, &m, &s, &[0.0, 0.0, 0.0], 0.0, &mut [0.0; 3]);
        assert_eq!(c.len(), 1);
        // the centre of the joined arc [0.2, 0.9] is 0.55, i.e. t = -0.45 of a turn
        assert!((via_point(&space, &m, c[0].t)[2] - (-0.45 * std::f64::consts::TAU)).abs() < 1e-12);
        // the via point is 0.45 of a turn from the base, the short way round: 0.55·2π → 0.45·2π
        assert!((c[0].value - 0.45 * std::f64::consts::TAU).abs() < 1e-9);
    }

    /// [`round_is_empty`] against [`borderlines_into`]: whenever it says "empty", erecting the
    /// borderlines of that round really gives none, for planar, spatial and rigid-body spaces,
    /// both direction strategies and random blocked motions.
    #[test]
    fn sidesteps_leave_the_blocked_motion_and_run_along_it() {
        // CHS Fig 1.4: axis-parallel motions in the plane; x is blocked at the base point
        let space = Space::euclidean(vec![0.0; 2], vec![10.0; 2]).unwrap();
        let groups = space.groups(true);
        let motion = space.group_motion(&[1.0, 5.0], &[9.0, 5.0], &groups[0]);
        let base = [4.0, 5.0];
        let crossing = Crossing {
            motion: &motion,
            group: 0,
            base: &base,
        };
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let plain = ViaPointOptions {
            split_axes: true,
            ..ViaPointOptions::default()
        };
        let mut lines = Lines::default();
        borderlines_into(&space, &groups, &plain, &crossing, 0, &mut rng, &mut lines);
        assert_eq!(lines.len(), 1, "one line along y through the base point");
        let stepping = ViaPointOptions {
            sidestep: Some(0.25),
            ..plain
        };
        borderlines_into(
            &space, &groups, &stepping, &crossing, 0, &mut rng, &mut lines,
        );
        assert_eq!(lines.len(), 3);
        // the sidesteps come first, then the line along y through the base point
        assert_eq!(lines.as_slice()[2].0.origin, vec![4.0, 5.0]);
        for (sign, (m, g)) in [1.0, -1.0].iter().zip(&lines.as_slice()[..2]) {
            // stepped by a quarter of the blocked motion's length (8) in y, running along x
            assert_eq!(*g, 0);
            assert_eq!(m.origin, vec![4.0, 5.0 + sign * 2.0]);
            assert_eq!(m.change, Change::Linear(vec![1.0, 0.0]));
        }
    }

    #[test]
    fn empty_rounds_are_really_empty() {
        use rand::SeedableRng;
        let spaces = [
            Space::euclidean(vec![0.0; 2], vec![1.0; 2]).unwrap(),
            Space::euclidean(vec![0.0; 3], vec![1.0; 3]).unwrap(),
            Space::euclidean(vec![0.0; 4], vec![1.0; 4]).unwrap(),
            Space::se2([-1.0; 2], [1.0; 2], 1.0).unwrap(),
            Space::se3([-1.0; 3], [1.0; 3], 1.0).unwrap(),
        ];
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let (mut said_empty, mut checked) = (0, 0);
        for space in &spaces {
            for split in [false, true] {
                let groups = space.groups(split);
                for directions in [
                    Directions::Basis {
                        axis_preference: true,
                        rotations: 0,
                    },
                    Directions::Basis {
                        axis_preference: false,
                        rotations: 2,
                    },
                    Directions::Random { count: 3 },
                ] {
                    for dodge in [false, true] {
                        let options = ViaPointOptions {
                            directions,
                            dodge_other_groups: dodge,
                            ..ViaPointOptions::default()
                        };
                        for _ in 0..20 {
                            let a = space.sample_uniform(&mut rng);
                            let z = space.sample_uniform(&mut rng);
                            for (gi, g) in groups.iter().enumerate() {
                                if space.same_in_group(&a, &z, g) {
                                    continue;
                                }
                                let motion = space.group_motion(&a, &z, g);
                                let crossing = Crossing {
                                    motion: &motion,
                                    group: gi,
                                    base: &a,
                                };
                                for round in 0..5 {
                                    let mut lines = Lines::default();
                                    borderlines_into(
                                        space, &groups, &options, &crossing, round, &mut rng,
                                        &mut lines,
                                    );
                                    checked += 1;
                                    if round_is_empty(&groups, &options, gi, round) {
                                        said_empty += 1;
                                        assert_eq!(lines.len(), 0, "{options:?} {g:?} {round}");
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        assert!(said_empty > checked / 3, "{said_empty} of {checked}");
    }

    #[test]
    fn valuation_prefers_close_and_wide() {
        let space = Space::euclidean(vec![-10.0, -10.0], vec![10.0, 10.0]).unwrap();
        let m = Motion::line(vec![0.0, 0.0], Change::Linear(vec![0.0, 1.0]));
        let sections = [
            Interval { lo: 1.0, hi: 3.0 },
            Interval { lo: -9.0, hi: -1.0 },
        ];
        let close = candidates(&space, &m, &sections, &[0.0, 0.0], 0.0, &mut [0.0; 2]);
        assert!(close[0].value < close[1].value); // β = 0: distance only (2 < 5)
        let wide = candidates(&space, &m, &sections, &[0.0, 0.0], 2.0, &mut [0.0; 2]);
        assert!(wide[0].value > wide[1].value); // β = 2: 2/4 > 5/64
    }
}
