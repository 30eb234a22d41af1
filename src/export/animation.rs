//! A path as keyframes that follow the motion the planner checked.
//!
//! Between two corners of a path the robot moves as the via-point planner moves it: one DOF
//! group at a time (CHS §1.5), a translation first, then a rotation about an axis fixed in the
//! world ([`crate::local::path_pieces`]). A viewer interpolates keyframes linearly
//! (positions) and by slerp (rotations), so a translation needs only its two ends, and a
//! rotation is sampled finely enough that every step turns by less than
//! [`MAX_TURN_PER_KEY`] about the same axis: slerp between two such keys turns about that
//! axis, so the drawn motion is the checked one. An arm's single-joint moves are sampled the
//! same way and carried to the links by forward kinematics.

use crate::local::path_pieces;
use crate::space::{Config, Group, Space, SpaceKind};
use nalgebra::UnitQuaternion;

/// Largest rotation between two keyframes (radians): 5°, so that slerp turns about the
/// motion's own axis and a joint's links move along arcs, not chords.
pub const MAX_TURN_PER_KEY: f64 = 5.0_f64 * std::f64::consts::PI / 180.0;

/// Seconds the whole animation lasts, whatever the path's length.
pub const DURATION: f64 = 8.0;

/// One keyframe: a time in `[0, DURATION]` and the configuration then.
#[derive(Clone, Debug, PartialEq)]
pub struct Key {
    /// Seconds from the start.
    pub time: f64,
    /// The configuration at that time.
    pub config: Config,
    /// Whether this key is a corner of the path (not a sample inside a rotation).
    pub corner: bool,
}

/// Keyframes of `path` in `space`, moving one group at a time as [`path_pieces`] does with
/// `groups`; time proportional to the space's distance, [`DURATION`] seconds in all. Returns
/// the corners alone at equal times if the path has length zero, and nothing for an empty path.
pub fn keyframes(space: &Space, groups: &[Group], path: &[Config]) -> Vec<Key> {
    let Some(first) = path.first() else {
        return Vec::new();
    };
    // (motion, length, number of steps) of every piece
    let mut pieces = Vec::new();
    for w in path.windows(2) {
        for (motion, _end) in path_pieces(space, groups, &w[0], &w[1]) {
            let len = space.motion_length(&motion, 0.0, 1.0);
            let turn = match (&motion.change, space.kind()) {
                (crate::space::Change::Rotation { angle, .. }, _)
                | (crate::space::Change::BodyRotation { angle, .. }, _) => angle.abs(),
                (crate::space::Change::Linear(d), SpaceKind::Se2) => d[2].abs(),
                // one body turns at a time; a straight motion may turn several
                (crate::space::Change::Linear(d), SpaceKind::Se2Bodies(_)) => d
                    .iter()
                    .skip(2)
                    .step_by(3)
                    .fold(0.0_f64, |m, a| m.max(a.abs())),
                _ => 0.0,
            };
            // (less a hair, so that 20° at 5° a key takes 4 steps, not 5 from rounding)
            let steps = ((turn / MAX_TURN_PER_KEY - 1e-9).ceil() as usize).max(1);
            pieces.push((motion, len, steps));
        }
    }
    let total: f64 = pieces.iter().map(|p| p.1).sum();
    let mut keys = vec![Key {
        time: 0.0,
        config: first.clone(),
        corner: true,
    }];
    if pieces.is_empty() {
        return keys;
    }
    // pieces of zero length (a turn by rounding noise) still take a little time, so that
    // times increase strictly, as glTF requires of animation inputs
    let floor = DURATION * 1e-3;
    let weights: Vec<f64> = pieces
        .iter()
        .map(|p| {
            if total > 0.0 {
                (p.1 / total).max(1e-3)
            } else {
                1.0
            }
        })
        .collect();
    let scale = DURATION / weights.iter().sum::<f64>();
    let mut t = 0.0;
    for ((motion, _, steps), w) in pieces.iter().zip(&weights) {
        let dt = (w * scale).max(floor);
        for s in 1..=*steps {
            let f = s as f64 / *steps as f64;
            let mut q = motion.at(f);
            space.normalize(&mut q);
            keys.push(Key {
                time: t + f * dt,
                config: q,
                corner: s == *steps,
            });
        }
        t += dt;
    }
    keys
}

/// The rigid-body pose of configuration `q`: translation (z = 0 in the plane) and unit
/// quaternion `[x, y, z, w]`.
pub fn pose(space: &Space, q: &[f64]) -> ([f64; 3], [f64; 4]) {
    match space.kind() {
        SpaceKind::Euclidean(n) => {
            let mut p = [0.0; 3];
            for (i, v) in q.iter().take(n.min(3)).enumerate() {
                p[i] = *v;
            }
            (p, [0.0, 0.0, 0.0, 1.0])
        }
        // the first body's pose; each body's own is `pose(se2, q[3i..3i + 3])`
        SpaceKind::Se2 | SpaceKind::Se2Bodies(_) => {
            let h = q[2] / 2.0;
            ([q[0], q[1], 0.0], [0.0, 0.0, h.sin(), h.cos()])
        }
        // an arm's joints place no single body: its links are placed by forward kinematics
        SpaceKind::Joints { .. } => ([0.0; 3], [0.0, 0.0, 0.0, 1.0]),
        // the first body's pose; each body's own is `pose(se3, q[7i..7i + 7])`
        SpaceKind::Se3 | SpaceKind::Se3Bodies(_) => {
            let r =
                UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[6], q[3], q[4], q[5]));
            ([q[0], q[1], q[2]], [r.i, r.j, r.k, r.w])
        }
    }
}

/// Flips each quaternion to the hemisphere of the one before, so that interpolation between
/// keys never takes the long way round (`q` and `-q` are the same rotation).
pub fn continuous(rotations: &mut [[f64; 4]]) {
    for i in 1..rotations.len() {
        let (a, b) = (rotations[i - 1], rotations[i]);
        if a.iter().zip(&b).map(|(x, y)| x * y).sum::<f64>() < 0.0 {
            rotations[i] = b.map(|v| -v);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn angle_between(a: [f64; 4], b: [f64; 4]) -> f64 {
        let d: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
        2.0 * d.abs().min(1.0).acos()
    }

    #[test]
    fn se3_corners_are_keys_and_turns_are_sampled_finely() {
        let space = Space::se3([-5.0; 3], [5.0; 3], 1.0).unwrap();
        let groups = space.groups(false);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        // translate then turn by 180° about z; then only translate back
        let path = vec![
            vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
            vec![1.0, 2.0, 0.0, 0.0, 0.0, 1.0, 0.0],
            vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0],
        ];
        let keys = keyframes(&space, &groups, &path);
        let corners: Vec<&Key> = keys.iter().filter(|k| k.corner).collect();
        // the corners of the path and the corner between translation and turn
        assert_eq!(corners.len(), 4);
        assert_eq!(corners[0].config, path[0]);
        assert_eq!(corners[1].config[..3], [1.0, 2.0, 0.0]);
        for (k, p) in [(2, 1), (3, 2)] {
            assert!(space.distance(&corners[k].config, &path[p]) < 1e-9);
        }
        assert!(keys.windows(2).all(|w| w[1].time > w[0].time));
        assert!((keys.last().unwrap().time - DURATION).abs() < 1e-9);
        // every step of the turn is small and about z (x, y of the quaternion stay 0)
        let rot: Vec<[f64; 4]> = keys.iter().map(|k| pose(&space, &k.config).1).collect();
        for w in rot.windows(2) {
            assert!(angle_between(w[0], w[1]) <= MAX_TURN_PER_KEY + 1e-9);
        }
        assert!(rot.iter().all(|r| r[0].abs() < 1e-12 && r[1].abs() < 1e-12));
        // half way through the turn the body faces 90° about z
        let mid = rot
            .iter()
            .map(|r| (angle_between(*r, [0.0, 0.0, h, h]), r))
            .fold(f64::INFINITY, |m, (a, _)| m.min(a));
        assert!(mid < 1e-9);
    }

    #[test]
    fn se2_keys_follow_the_wrapped_turn() {
        let space = Space::se2([-1.0; 2], [1.0; 2], 1.0).unwrap();
        let groups = space.groups(false);
        // from 170° to -170°: the short way (20° through 180°), not 340° back
        let a = 170f64.to_radians();
        let path = vec![vec![0.0, 0.0, a], vec![0.0, 0.0, -a]];
        let keys = keyframes(&space, &groups, &path);
        assert_eq!(keys.len(), 1 + 4);
        let mut rot: Vec<[f64; 4]> = keys.iter().map(|k| pose(&space, &k.config).1).collect();
        continuous(&mut rot);
        let turned: f64 = rot.windows(2).map(|w| angle_between(w[0], w[1])).sum();
        assert!((turned - 20f64.to_radians()).abs() < 1e-9);
        for w in rot.windows(2) {
            assert!(w[0].iter().zip(&w[1]).map(|(x, y)| x * y).sum::<f64>() > 0.0);
        }
    }

    #[test]
    fn empty_and_single_state_paths() {
        let space = Space::euclidean(vec![0.0; 2], vec![1.0; 2]).unwrap();
        let groups = space.groups(false);
        assert!(keyframes(&space, &groups, &[]).is_empty());
        assert_eq!(keyframes(&space, &groups, &[vec![0.5, 0.5]]).len(), 1);
        let twice = vec![vec![0.5, 0.5]; 2];
        assert_eq!(keyframes(&space, &groups, &twice).len(), 1);
    }
}
