//! Configuration spaces: R^n with box bounds, SE(2) = R² × S¹, SE(3) = R³ × S³, and the
//! joint space of a robot arm's planning group ([`joints`]).
//!
//! A space knows distance, interpolation, sampling, its **DOF groups** (CHS §1.5) and how to
//! build the straight motions the oracle is asked about. Configurations are plain coordinate
//! vectors in OMPL's layout: `[x₀ … xₙ₋₁]`, `[x, y, θ]`, `[x, y, z, qx, qy, qz, qw]`.
//!
//! Only the position is bounded (as in OMPL); outside the bounds counts as obstacle, so every
//! borderline has bounded free sections (see [`crate::oracle::Bounded`]).

pub mod bodies;
pub mod bodies3;
pub mod joints;
pub mod motion;
pub mod rotation;
mod types;

pub use motion::{Change, Motion, Sweep};
pub use types::{extend_small, Config, Group, GroupKind, Space, SpaceError, SpaceKind};

use crate::interval::Interval;
use crate::short;
use rand::Rng;
use std::f64::consts::{PI, TAU};

impl Space {
    /// R^n with the box `[lower, upper]`.
    pub fn euclidean(lower: Vec<f64>, upper: Vec<f64>) -> Result<Space, SpaceError> {
        let n = lower.len();
        if n < 2 {
            // a borderline lies perpendicular to a motion: R^1 has no room for one
            return Err(SpaceError::Bounds(format!(
                "R^n needs n ≥ 2 coordinates, got {n}"
            )));
        }
        Space::build(SpaceKind::Euclidean(n), lower, upper, 1.0)
    }

    /// SE(2) with position bounds `[lower, upper]` (two coordinates each). `rotation_scale` is
    /// the length one radian of turning counts as (see [`Space::rotation_scale`]).
    pub fn se2(lower: [f64; 2], upper: [f64; 2], rotation_scale: f64) -> Result<Space, SpaceError> {
        Space::build(
            SpaceKind::Se2,
            lower.to_vec(),
            upper.to_vec(),
            rotation_scale,
        )
    }

    /// SE(3) with position bounds `[lower, upper]` (three coordinates each).
    pub fn se3(lower: [f64; 3], upper: [f64; 3], rotation_scale: f64) -> Result<Space, SpaceError> {
        Space::build(
            SpaceKind::Se3,
            lower.to_vec(),
            upper.to_vec(),
            rotation_scale,
        )
    }

    fn build(
        kind: SpaceKind,
        lower: Vec<f64>,
        upper: Vec<f64>,
        rotation_scale: f64,
    ) -> Result<Space, SpaceError> {
        if lower.len() != upper.len() {
            return Err(SpaceError::Bounds(format!(
                "lower has {} coordinates, upper {}",
                lower.len(),
                upper.len()
            )));
        }
        for (i, (l, u)) in lower.iter().zip(&upper).enumerate() {
            if !l.is_finite() || !u.is_finite() {
                return Err(SpaceError::Bounds(format!(
                    "coordinate {i} bound is not finite"
                )));
            }
            if l > u {
                return Err(SpaceError::Bounds(format!(
                    "coordinate {i}: lower {} > upper {}",
                    short::num(*l),
                    short::num(*u)
                )));
            }
            // a flat coordinate leaves no room beside a motion for the
            // via points, and every motion in the flat space runs into every obstacle on it
            if l == u {
                return Err(SpaceError::Bounds(format!(
                    "coordinate {i}: lower = upper = {}, the space has no width there; \
                     give bounds of positive width",
                    short::num(*l)
                )));
            }
            // beyond this, widths, distances and their squares overflow
            let max = crate::limits::MAX_COORDINATE;
            if l.abs() > max || u.abs() > max {
                return Err(SpaceError::Bounds(format!(
                    "coordinate {i}: bounds [{}, {}] exceed ±{max:e}, where distances overflow",
                    short::num(*l),
                    short::num(*u)
                )));
            }
        }
        if !(rotation_scale.is_finite() && rotation_scale > 0.0) {
            return Err(SpaceError::RotationScale(rotation_scale));
        }
        Ok(Space {
            kind,
            lower,
            upper,
            rotation_scale,
        })
    }

    /// The same space with another rotation scale.
    pub fn with_rotation_scale(mut self, scale: f64) -> Result<Space, SpaceError> {
        if !(scale.is_finite() && scale > 0.0) {
            return Err(SpaceError::RotationScale(scale));
        }
        self.rotation_scale = scale;
        Ok(self)
    }

    /// Which space.
    pub fn kind(&self) -> SpaceKind {
        self.kind
    }

    /// Number of coordinates of a configuration.
    pub fn dim(&self) -> usize {
        match self.kind {
            SpaceKind::Euclidean(n) => n,
            SpaceKind::Se2 => 3,
            SpaceKind::Se3 => 7,
            SpaceKind::Joints { dof, .. } => dof,
            SpaceKind::Se2Bodies(k) => 3 * k,
            SpaceKind::Se3Bodies(k) => bodies3::POSE * k,
        }
    }

    /// Number of bounded coordinates (all of them for R^n; for several bodies all their
    /// coordinates, the angles among them marked as [`wrapping`](Self::wrapping)).
    pub fn position_dim(&self) -> usize {
        self.lower.len()
    }

    /// Lower position bounds.
    pub fn lower(&self) -> &[f64] {
        &self.lower
    }

    /// Upper position bounds.
    pub fn upper(&self) -> &[f64] {
        &self.upper
    }

    /// Length that one radian of rotation counts as, in distances and valuations. For a rigid
    /// body the scene sets it to the robot's radius about its reference point, so that
    /// `distance` bounds how far any point of the robot moves. 1 for R^n.
    pub fn rotation_scale(&self) -> f64 {
        self.rotation_scale
    }

    /// Diagonal of the position bounds (OMPL's "extent" of a real vector space).
    pub fn extent(&self) -> f64 {
        self.lower
            .iter()
            .zip(&self.upper)
            .map(|(l, u)| (u - l) * (u - l))
            .sum::<f64>()
            .sqrt()
    }

    /// Checks length and finiteness (and a normalisable quaternion); does not check bounds.
    pub fn check(&self, q: &[f64]) -> Result<(), SpaceError> {
        if q.len() != self.dim() {
            return Err(SpaceError::Dimension {
                kind: self.kind,
                want: self.dim(),
                got: q.len(),
            });
        }
        if let Some((index, &value)) = q.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(SpaceError::NotFinite { index, value });
        }
        if self.kind == SpaceKind::Se3 {
            let n = q[3..7].iter().map(|v| v * v).sum::<f64>().sqrt();
            if n < 1e-9 {
                return Err(SpaceError::Quaternion(n));
            }
        }
        if let Some(n) = matches!(self.kind, SpaceKind::Se3Bodies(_))
            .then(|| bodies3::degenerate_quaternion(q))
            .flatten()
        {
            return Err(SpaceError::Quaternion(n));
        }
        Ok(())
    }

    /// Canonical form: SE(2) angle wrapped into `[-π, π)`, SE(3) quaternion of unit length.
    pub fn normalize(&self, q: &mut [f64]) {
        match self.kind {
            SpaceKind::Euclidean(_) => {}
            SpaceKind::Joints { continuous, .. } => joints::wrap_continuous(continuous, q),
            SpaceKind::Se2Bodies(_) => joints::wrap_continuous(self.wrapping(), q),
            SpaceKind::Se3Bodies(_) => bodies3::normalize(q),
            SpaceKind::Se2 => q[2] = rotation::wrap_angle(q[2]),
            SpaceKind::Se3 => {
                let n = q[3..7].iter().map(|v| v * v).sum::<f64>().sqrt();
                if n > 0.0 {
                    q[3..7].iter_mut().for_each(|v| *v /= n);
                }
            }
        }
    }

    /// Whether the position lies in the closed bounds.
    pub fn in_bounds(&self, q: &[f64]) -> bool {
        let wraps = self.wrapping();
        q.iter()
            .zip(self.lower.iter().zip(&self.upper))
            .enumerate()
            .all(|(i, (v, (l, u)))| (*l <= *v && *v <= *u) || joints::bit(wraps, i))
    }

    /// The continuous joints of a joint space, or the bodies' angles of several bodies, as a
    /// bit set (none for other spaces): their coordinates wrap and have no bounds.
    pub fn wrapping(&self) -> u64 {
        match self.kind {
            SpaceKind::Joints { continuous, .. } => continuous,
            SpaceKind::Se2Bodies(k) => bodies::angle_bits(k),
            SpaceKind::Se3Bodies(k) => bodies3::quaternion_bits(k),
            _ => 0,
        }
    }

    /// The parameter range of `motion` in which the position stays inside the bounds (the slab
    /// method); `None` if it never is inside within `motion.range`.
    pub fn inside_range(&self, motion: &Motion) -> Option<Interval> {
        let rate = motion.translation_rate(self.position_dim());
        let mut range = motion.range;
        let wraps = self.wrapping();
        for i in (0..self.position_dim()).filter(|&i| !joints::bit(wraps, i)) {
            let p = motion.origin[i];
            let v = rate.get(i).copied().unwrap_or(0.0);
            let (l, u) = (self.lower[i], self.upper[i]);
            if v == 0.0 {
                if p < l || p > u {
                    return None;
                }
            } else {
                let (a, b) = ((l - p) / v, (u - p) / v);
                range = range.meet(&Interval {
                    lo: a.min(b),
                    hi: a.max(b),
                })?;
            }
        }
        Some(range)
    }

    /// Distance: Euclidean for R^n; `‖Δp‖ + rotation_scale · angle` for rigid bodies, with the
    /// angle of the rotation between the orientations (at most π).
    pub fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        match self.kind {
            SpaceKind::Joints { continuous, .. } => return joints::distance(continuous, a, b),
            SpaceKind::Se2Bodies(_) => return bodies::distance(self.rotation_scale, a, b),
            SpaceKind::Se3Bodies(_) => return bodies3::distance(self.rotation_scale, a, b),
            _ => {}
        }
        let p = self.position_dim();
        let dp = a[..p]
            .iter()
            .zip(&b[..p])
            .map(|(x, y)| (x - y) * (x - y))
            .sum::<f64>()
            .sqrt();
        match self.kind {
            SpaceKind::Euclidean(_) => dp,
            SpaceKind::Se2 => dp + self.rotation_scale * rotation::wrap_angle(b[2] - a[2]).abs(),
            SpaceKind::Se3 => {
                dp + self.rotation_scale * rotation::rotation_angle(&a[3..7], &b[3..7])
            }
            SpaceKind::Joints { .. } | SpaceKind::Se2Bodies(_) | SpaceKind::Se3Bodies(_) => {
                unreachable!("answered above")
            }
        }
    }

    /// Simultaneous interpolation of all coordinates (OMPL's `interpolate`): linear position,
    /// shortest-way angle, slerp for quaternions. Used by sampled checking, not by exact motions.
    pub fn interpolate(&self, a: &[f64], b: &[f64], t: f64) -> Config {
        match self.kind {
            SpaceKind::Joints { continuous, .. } => {
                return joints::interpolate(continuous, a, b, t)
            }
            SpaceKind::Se2Bodies(_) => return joints::interpolate(self.wrapping(), a, b, t),
            SpaceKind::Se3Bodies(_) => return bodies3::interpolate(a, b, t),
            _ => {}
        }
        let p = self.position_dim();
        let mut q: Config = a[..p]
            .iter()
            .zip(&b[..p])
            .map(|(x, y)| x + t * (y - x))
            .collect();
        match self.kind {
            SpaceKind::Euclidean(_) => {}
            SpaceKind::Se2 => q.push(rotation::wrap_angle(
                a[2] + t * rotation::wrap_angle(b[2] - a[2]),
            )),
            SpaceKind::Se3 => {
                let qa = rotation::quat_from_slice(&a[3..7]);
                let mut qb = rotation::quat_from_slice(&b[3..7]);
                if qa.coords.dot(&qb.coords) < 0.0 {
                    qb = nalgebra::UnitQuaternion::new_unchecked(-qb.into_inner());
                }
                let r = qa.try_slerp(&qb, t, 1e-12).unwrap_or(qa);
                q.extend_from_slice(&[0.0; 4]);
                rotation::quat_to_slice(&r, &mut q[3..7]);
            }
            SpaceKind::Joints { .. } | SpaceKind::Se2Bodies(_) | SpaceKind::Se3Bodies(_) => {
                unreachable!("answered above")
            }
        }
        q
    }

    /// A configuration drawn uniformly: position in the bounds, θ in `[-π, π)`, a uniformly
    /// random rotation (Shoemake's method).
    pub fn sample_uniform<R: Rng + ?Sized>(&self, rng: &mut R) -> Config {
        let mut q: Config = self
            .lower
            .iter()
            .zip(&self.upper)
            .map(|(l, u)| if u > l { rng.random_range(*l..=*u) } else { *l })
            .collect();
        match self.kind {
            SpaceKind::Euclidean(_) => {}
            // continuous joints have bounds [-π, π]: drawn like the others, then wrapped
            SpaceKind::Joints { continuous, .. } => joints::wrap_continuous(continuous, &mut q),
            SpaceKind::Se2Bodies(_) => joints::wrap_continuous(self.wrapping(), &mut q),
            SpaceKind::Se3Bodies(_) => bodies3::sample_orientations(&mut q, rng),
            SpaceKind::Se2 => q.push(rng.random_range(-PI..PI)),
            SpaceKind::Se3 => {
                let (u1, u2, u3): (f64, f64, f64) = (rng.random(), rng.random(), rng.random());
                let (s1, s2) = ((1.0 - u1).sqrt(), u1.sqrt());
                q.extend_from_slice(&[
                    s1 * (TAU * u2).sin(),
                    s1 * (TAU * u2).cos(),
                    s2 * (TAU * u3).sin(),
                    s2 * (TAU * u3).cos(),
                ]);
            }
        }
        q
    }

    /// The DOF groups (CHS §1.5). Natural groups: all of R^n; position and orientation of a
    /// rigid body. With `split_axes` every position coordinate is a group of its own, so paths
    /// run parallel to the axes (CHS A.1.1).
    pub fn groups(&self, split_axes: bool) -> Vec<Group> {
        let mut groups = Vec::new();
        self.groups_into(split_axes, &mut groups);
        groups
    }

    /// Whether this is an arm's joint space: what decides the arm's defaults (trees out of the
    /// roadmap, their racing head start, dynamic domains, first-hit prefixes).
    pub fn is_joints(&self) -> bool {
        matches!(self.kind, SpaceKind::Joints { .. })
    }

    /// One group of every joint of a joint space without continuous joints: its direct path
    /// is the straight motion of all joints at once, which an arm's oracle only certifies free
    /// or not ([`crate::robot::ArmOracle::straight_free`]) — what shortcuts across a staircase
    /// ask. `None` for other spaces, and where a joint wraps (a straight motion would not).
    pub fn straight_group(&self) -> Option<Group> {
        match self.kind {
            SpaceKind::Joints { dof, continuous } if continuous == 0 && dof > 1 => {
                Some(Group::run(GroupKind::Linear, 0..dof))
            }
            _ => None,
        }
    }

    /// [`groups`](Self::groups) written into `groups` (overwriting it, keeping its
    /// allocation): the planners ask for them on every connection.
    pub fn groups_into(&self, split_axes: bool, groups: &mut Vec<Group>) {
        let p = self.position_dim();
        groups.clear();
        if let SpaceKind::Joints { dof, continuous } = self.kind {
            // one group per joint whatever `split_axes` says (CHS §1.5, seed l. 438: "a robot
            // arm whose links may only move one at a time")
            groups.extend((0..dof).map(|i| {
                let kind = if joints::bit(continuous, i) {
                    GroupKind::Angle
                } else {
                    GroupKind::Linear
                };
                Group::run(kind, i..i + 1)
            }));
            return;
        }
        if let SpaceKind::Se2Bodies(k) = self.kind {
            bodies::groups_into(k, split_axes, groups);
            return;
        }
        if let SpaceKind::Se3Bodies(k) = self.kind {
            bodies3::groups_into(k, split_axes, groups);
            return;
        }
        if split_axes {
            groups.extend((0..p).map(|i| Group::run(GroupKind::Linear, i..i + 1)));
        } else {
            groups.push(Group::run(GroupKind::Linear, 0..p));
        }
        match self.kind {
            SpaceKind::Euclidean(_) => {}
            SpaceKind::Se2 => groups.push(Group::run(GroupKind::Angle, 2..3)),
            SpaceKind::Se3 => groups.push(Group::run(GroupKind::Quaternion, 3..7)),
            SpaceKind::Joints { .. } | SpaceKind::Se2Bodies(_) | SpaceKind::Se3Bodies(_) => {
                unreachable!("answered above")
            }
        }
    }

    /// Whether `a` and `b` have the same coordinates in `group` (orientations compared as
    /// rotations, `q ≡ -q`).
    pub fn same_in_group(&self, a: &[f64], b: &[f64], group: &Group) -> bool {
        match group.kind {
            GroupKind::Linear => group.indices().all(|i| a[i] == b[i]),
            GroupKind::Angle => {
                let i = group.coords.start;
                rotation::wrap_angle(b[i] - a[i]) == 0.0
            }
            GroupKind::Quaternion => {
                let (a, b) = (&a[group.coords.clone()], &b[group.coords.clone()]);
                a == b || a.iter().zip(b).all(|(x, y)| *x == -*y)
            }
        }
    }

    /// `a` with the coordinates of `group` taken from `b`.
    pub fn with_group_of(&self, a: &[f64], b: &[f64], group: &Group) -> Config {
        let mut q = a.to_vec();
        group.copy_coords(&mut q, b);
        q
    }

    /// The straight motion from `a` to `with_group_of(a, z, group)`: linear in a position
    /// group, the shorter way round for an angle, about one fixed axis for a quaternion.
    pub fn group_motion(&self, a: &[f64], z: &[f64], group: &Group) -> Motion {
        let change = match group.kind {
            GroupKind::Linear => {
                let mut delta = vec![0.0; a.len()];
                for i in group.indices() {
                    delta[i] = z[i] - a[i];
                }
                Change::Linear(delta)
            }
            GroupKind::Angle => {
                let mut delta = vec![0.0; a.len()];
                let i = group.coords.start;
                delta[i] = rotation::wrap_angle(z[i] - a[i]);
                Change::Linear(delta)
            }
            GroupKind::Quaternion if matches!(self.kind, SpaceKind::Se3Bodies(_)) => {
                let (axis, angle) = bodies3::relative_turn(a, z, group);
                bodies3::turn(group, axis, angle)
            }
            GroupKind::Quaternion => {
                let qa = rotation::quat_from_slice(&a[3..7]);
                let qz = rotation::quat_from_slice(&z[3..7]);
                let (axis, angle) = rotation::relative_axis_angle(&qa, &qz);
                Change::Rotation { axis, angle }
            }
        };
        Motion::segment(a.to_vec(), change)
    }

    /// Allocation-free twin of [`group_motion`](Self::group_motion): overwrites `out`,
    /// reusing its buffers (the via-point search keeps one motion per group).
    pub fn group_motion_into(&self, a: &[f64], z: &[f64], group: &Group, out: &mut Motion) {
        match group.kind {
            GroupKind::Linear => {
                let delta = out.reset_linear(a, Interval::UNIT, Sweep::Segment);
                for i in group.indices() {
                    delta[i] = z[i] - a[i];
                }
            }
            GroupKind::Angle => {
                let delta = out.reset_linear(a, Interval::UNIT, Sweep::Segment);
                let i = group.coords.start;
                delta[i] = rotation::wrap_angle(z[i] - a[i]);
            }
            GroupKind::Quaternion if matches!(self.kind, SpaceKind::Se3Bodies(_)) => {
                let (axis, angle) = bodies3::relative_turn(a, z, group);
                let change = bodies3::turn(group, axis, angle);
                out.reset_change(a, change, Interval::UNIT, Sweep::Segment);
            }
            GroupKind::Quaternion => {
                let qa = rotation::quat_from_slice(&a[3..7]);
                let qz = rotation::quat_from_slice(&z[3..7]);
                let (axis, angle) = rotation::relative_axis_angle(&qa, &qz);
                out.reset_rotation(a, axis, angle, Interval::UNIT, Sweep::Segment);
            }
        }
    }

    /// Allocation-free twin of [`with_group_of`](Self::with_group_of): overwrites `out`.
    pub fn with_group_of_into(&self, a: &[f64], b: &[f64], group: &Group, out: &mut Vec<f64>) {
        out.clear();
        extend_small(out, a);
        group.copy_coords(out, b);
    }

    /// The straight motion from `a` to `z` when all coordinates may change at once (R^n only,
    /// or motions that differ in a single group). `None` if `a` and `z` differ in more than one
    /// natural group of a rigid body.
    pub fn direct_motion(&self, a: &[f64], z: &[f64]) -> Option<Motion> {
        let groups = self.groups(false);
        let differing: Vec<&Group> = groups
            .iter()
            .filter(|g| !self.same_in_group(a, z, g))
            .collect();
        match differing.as_slice() {
            [] => Some(self.group_motion(a, z, &groups[0])),
            [g] => Some(self.group_motion(a, z, g)),
            _ => None,
        }
    }

    /// The unbounded line through `base` along the unit `direction` in a linear group;
    /// `direction` has one entry per coordinate of the group and `t` measures length.
    pub fn line_through(&self, base: &[f64], group: &Group, direction: &[f64]) -> Motion {
        debug_assert_eq!(group.kind, GroupKind::Linear);
        let mut delta = vec![0.0; base.len()];
        for (i, d) in group.indices().zip(direction) {
            delta[i] = *d;
        }
        Motion::line(base.to_vec(), Change::Linear(delta))
    }

    /// Allocation-free twin of [`line_through`](Self::line_through): overwrites `out`.
    pub fn line_through_into(
        &self,
        base: &[f64],
        group: &Group,
        direction: &[f64],
        out: &mut Motion,
    ) {
        debug_assert_eq!(group.kind, GroupKind::Linear);
        let delta = out.reset_linear(base, Interval::ALL, Sweep::Line);
        for (i, d) in group.indices().zip(direction) {
            delta[i] = *d;
        }
    }

    /// Allocation-free twin of [`turn_through`](Self::turn_through): overwrites `out`.
    /// `group` must be rotational.
    pub fn turn_through_into(&self, base: &[f64], group: &Group, axis: [f64; 3], out: &mut Motion) {
        let turn = Interval { lo: -0.5, hi: 0.5 };
        match group.kind {
            GroupKind::Angle => {
                let delta = out.reset_linear(base, turn, Sweep::Turn);
                delta[group.coords.start] = TAU;
            }
            GroupKind::Quaternion if matches!(self.kind, SpaceKind::Se3Bodies(_)) => {
                out.reset_change(base, bodies3::turn(group, axis, TAU), turn, Sweep::Turn)
            }
            GroupKind::Quaternion => out.reset_rotation(base, axis, TAU, turn, Sweep::Turn),
            GroupKind::Linear => panic!("turn_through on a linear group"),
        }
    }

    /// The full turn through `base` in a rotational group (about the unit `axis` for a
    /// quaternion; the axis is ignored for an angle). `t ∈ [-½, ½]` covers one turn.
    pub fn turn_through(&self, base: &[f64], group: &Group, axis: [f64; 3]) -> Motion {
        match group.kind {
            GroupKind::Angle => {
                let mut delta = vec![0.0; base.len()];
                delta[group.coords.start] = TAU;
                Motion::turn(base.to_vec(), Change::Linear(delta))
            }
            GroupKind::Quaternion if matches!(self.kind, SpaceKind::Se3Bodies(_)) => {
                Motion::turn(base.to_vec(), bodies3::turn(group, axis, TAU))
            }
            GroupKind::Quaternion => {
                Motion::turn(base.to_vec(), Change::Rotation { axis, angle: TAU })
            }
            GroupKind::Linear => panic!("turn_through on a linear group"),
        }
    }

    /// Length of the path a motion sweeps between parameters `t0` and `t1`, in the units of
    /// [`distance`](Self::distance).
    pub fn motion_length(&self, motion: &Motion, t0: f64, t1: f64) -> f64 {
        let dt = (t1 - t0).abs();
        match &motion.change {
            Change::Linear(delta) if matches!(self.kind, SpaceKind::Se2Bodies(_)) => {
                dt * bodies::change_length(self.rotation_scale, delta)
            }
            Change::Linear(delta) if matches!(self.kind, SpaceKind::Se3Bodies(_)) => {
                dt * bodies3::change_length(delta)
            }
            Change::Linear(delta) => {
                let p = self.position_dim();
                let lin = delta[..p].iter().map(|d| d * d).sum::<f64>().sqrt();
                let ang = if self.kind == SpaceKind::Se2 {
                    delta[2].abs()
                } else {
                    0.0
                };
                dt * (lin + self.rotation_scale * ang)
            }
            Change::Rotation { angle, .. } | Change::BodyRotation { angle, .. } => {
                dt * angle.abs() * self.rotation_scale
            }
        }
    }

    /// The length of [`group_motion`](Self::group_motion)`(a, z, group)` over its whole range,
    /// bit for bit, without building the motion: it depends only on `group`'s coordinates of
    /// `a` and `z` (shortening measures every pair of a path's corners, group by group).
    pub fn group_length(&self, a: &[f64], z: &[f64], group: &Group) -> f64 {
        if matches!(self.kind, SpaceKind::Se2Bodies(_)) {
            return bodies::group_length(self.rotation_scale, a, z, group);
        }
        if matches!(self.kind, SpaceKind::Se3Bodies(_)) {
            return bodies3::group_length(self.rotation_scale, a, z, group);
        }
        let p = self.position_dim();
        // the terms `motion_length` sums, in its order (the zeros of other groups add nothing)
        let linear = |delta: &dyn Fn(usize) -> f64| {
            let lin = group
                .coords
                .clone()
                .filter(|&i| i < p)
                .map(|i| delta(i) * delta(i))
                .fold(0.0, |s, d| s + d)
                .sqrt();
            let ang = if self.kind == SpaceKind::Se2 && group.coords.contains(&2) {
                delta(2).abs()
            } else {
                0.0
            };
            lin + self.rotation_scale * ang
        };
        match group.kind {
            GroupKind::Linear => linear(&|i| z[i] - a[i]),
            GroupKind::Angle => linear(&|i| rotation::wrap_angle(z[i] - a[i])),
            GroupKind::Quaternion => {
                let qa = rotation::quat_from_slice(&a[3..7]);
                let qz = rotation::quat_from_slice(&z[3..7]);
                let (_, angle) = rotation::relative_axis_angle(&qa, &qz);
                angle.abs() * self.rotation_scale
            }
        }
    }

    /// Points for a nearest-neighbour index whose Euclidean distance is a lower bound of
    /// [`distance`](Self::distance) (a chord is never longer than its arc, and
    /// `√(x² + y²) ≤ x + y`): the configuration itself for R^n;
    /// `[x, y, s·cos θ, s·sin θ]` for SE(2); `[x, y, z, 2s·q]` for SE(3), together with the
    /// antipodal `[x, y, z, -2s·q]` because `q ≡ -q` (so SE(3) yields two points).
    pub fn embeddings(&self, q: &[f64]) -> Vec<Vec<f64>> {
        let s = self.rotation_scale;
        match self.kind {
            SpaceKind::Euclidean(_) => vec![q.to_vec()],
            SpaceKind::Joints { continuous, .. } => vec![joints::embedding(continuous, q)],
            SpaceKind::Se2Bodies(_) => vec![bodies::embedding(s, q)],
            SpaceKind::Se3Bodies(_) => vec![bodies3::embedding(s, q)],
            SpaceKind::Se2 => vec![vec![q[0], q[1], s * q[2].cos(), s * q[2].sin()]],
            SpaceKind::Se3 => {
                let mut a = q[..3].to_vec();
                a.extend(q[3..7].iter().map(|v| 2.0 * s * v));
                let mut b = q[..3].to_vec();
                b.extend(q[3..7].iter().map(|v| -2.0 * s * v));
                vec![a, b]
            }
        }
    }

    /// Whether [`embeddings`](Self::embeddings) is the configuration itself and
    /// [`distance`](Self::distance) the Euclidean distance of configurations: R^n, and a joint
    /// space without continuous joints. A nearest-neighbour index over embeddings is then
    /// exact as it stands.
    pub fn embedding_is_identity(&self) -> bool {
        matches!(
            self.kind,
            SpaceKind::Euclidean(_) | SpaceKind::Joints { continuous: 0, .. }
        )
    }

    /// Length of the vectors [`embeddings`](Self::embeddings) returns.
    pub fn embedding_dim(&self) -> usize {
        match self.kind {
            SpaceKind::Euclidean(n) => n,
            SpaceKind::Se2 => 4,
            SpaceKind::Se3 => 7,
            SpaceKind::Joints { dof, continuous } => dof + continuous.count_ones() as usize,
            SpaceKind::Se2Bodies(k) => 4 * k,
            SpaceKind::Se3Bodies(k) => bodies3::EMBEDDING * k,
        }
    }
}

/// Checks, for `draws` pairs of uniform samples of `space`, that the Euclidean distance of
/// their embeddings is at most their distance (the nearest-neighbour index relies on it) and
/// returns the pairs for further checks.
#[cfg(test)]
pub(crate) fn assert_embedding_below_distance(space: &Space, seed: u64) -> Vec<(Config, Config)> {
    use rand::SeedableRng;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    (0..200)
        .map(|_| {
            let a = space.sample_uniform(&mut rng);
            let b = space.sample_uniform(&mut rng);
            assert!(space.in_bounds(&a));
            let (ea, eb) = (&space.embeddings(&a)[0], &space.embeddings(&b)[0]);
            assert_eq!(ea.len(), space.embedding_dim());
            let e = ea
                .iter()
                .zip(eb)
                .map(|(x, y)| (x - y) * (x - y))
                .sum::<f64>()
                .sqrt();
            assert!(e <= space.distance(&a, &b) + 1e-12);
            (a, b)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn inside_range_clips_a_line_to_the_box() {
        let s = Space::euclidean(vec![0.0, 0.0], vec![1.0, 1.0]).unwrap();
        let m = Motion::line(vec![0.5, 0.5], Change::Linear(vec![1.0, 0.0]));
        assert_eq!(s.inside_range(&m), Some(Interval { lo: -0.5, hi: 0.5 }));
        let m = Motion::line(vec![2.0, 0.5], Change::Linear(vec![0.0, 1.0]));
        assert_eq!(s.inside_range(&m), None);
    }

    #[test]
    fn se3_group_motion_ends_at_the_goal() {
        let s = Space::se3([-1.0; 3], [1.0; 3], 1.0).unwrap();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        for _ in 0..50 {
            let a = s.sample_uniform(&mut rng);
            let z = s.sample_uniform(&mut rng);
            let g = &s.groups(false)[1];
            let m = s.group_motion(&a, &z, g);
            let end = m.at(1.0);
            assert!(rotation::rotation_angle(&end[3..7], &z[3..7]) < 1e-9);
            assert_eq!(&end[..3], &a[..3]);
            // the distance of the motion equals the space's distance
            let len = s.motion_length(&m, 0.0, 1.0);
            assert!((len - s.distance(&a, &s.with_group_of(&a, &z, g))).abs() < 1e-9);
        }
    }

    #[test]
    fn checks_reject_bad_configurations() {
        let s = Space::se3([-1.0; 3], [1.0; 3], 1.0).unwrap();
        assert!(matches!(
            s.check(&[0.0; 6]),
            Err(SpaceError::Dimension { .. })
        ));
        assert!(matches!(
            s.check(&[0.0, f64::NAN, 0.0, 0.0, 0.0, 0.0, 1.0]),
            Err(SpaceError::NotFinite { index: 1, .. })
        ));
        assert!(matches!(s.check(&[0.0; 7]), Err(SpaceError::Quaternion(_))));
        assert!(Space::euclidean(vec![1.0], vec![0.0]).is_err());
        assert!(Space::euclidean(vec![f64::NAN], vec![0.0]).is_err());
    }
}
