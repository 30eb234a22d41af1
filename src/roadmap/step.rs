//! The steps walks are made of: a random direction, the free section of a line or turn through
//! a configuration (one *intersectLine* call, CHS §1.2), and one plain step of a random-bounce
//! walk to a random point of it. Shared by the plain walks ([`super::bounce`]) and the walks of
//! several bodies ([`super::bodies_walk`]).

use crate::interval::Interval;
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle, OracleError};
use crate::space::{Config, Group, GroupKind, Motion, Space};
use rand::Rng;

/// Share of a free section kept clear at each end when choosing where a step ends: its ends
/// touch obstacles.
pub const SECTION_MARGIN: f64 = 0.01;

/// Largest turn of one step, in turns (0.45 · 2π): below half a turn, the shorter way between
/// the step's ends is the turn that was checked.
pub const MAX_TURN: f64 = 0.45;

/// A random unit vector in `n` dimensions (Box–Muller normals, normalised).
pub fn random_direction<R: Rng + ?Sized>(n: usize, rng: &mut R) -> Vec<f64> {
    loop {
        let mut v: Vec<f64> = (0..n)
            .map(|_| {
                let u1: f64 = 1.0 - rng.random::<f64>(); // (0, 1]
                let u2: f64 = rng.random::<f64>();
                (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
            })
            .collect();
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm > 1e-9 {
            v.iter_mut().for_each(|x| *x /= norm);
            return v;
        }
    }
}

/// What one step of a walk did.
#[derive(Debug)]
pub(super) enum Step {
    /// It moved to this configuration.
    Moved(Config),
    /// It drew a point where it stood.
    Stayed,
    /// The configuration has no free section around it in the step's group (it touches an
    /// obstacle that way).
    Stuck,
}

/// The free section of `motion` that contains its parameter 0, clipped to `clip`: `None` when
/// the motion collides at 0.
pub(super) fn free_section(
    oracle: &dyn CollisionOracle,
    motion: &Motion,
    clip: Interval,
    counts: &mut CallCounts,
) -> Result<Option<Interval>, OracleError> {
    let hits = oracle.intersect(motion, counts)?;
    Ok(hits
        .complement_within(motion.range)
        .iter()
        .find(|s| s.contains(0.0))
        .and_then(|s| s.meet(&clip)))
}

/// One plain step of a random-bounce walk in group `g` from `current`: along a random direction
/// of a position group (every coordinate of the group at once) or a turn about a random axis,
/// to a random point of the free section (one *intersectLine* call).
pub(super) fn group_step<R: Rng + ?Sized>(
    space: &Space,
    oracle: &dyn CollisionOracle,
    g: &Group,
    current: &[f64],
    rng: &mut R,
    counts: &mut CallCounts,
) -> Result<Step, OracleError> {
    let (motion, clip) = match g.kind {
        GroupKind::Linear => {
            let reach = space.extent();
            let dir = random_direction(g.len(), rng);
            let line = space.line_through(current, g, &dir);
            (
                line,
                Interval {
                    lo: -reach,
                    hi: reach,
                },
            )
        }
        GroupKind::Angle | GroupKind::Quaternion => {
            let a = random_direction(3, rng);
            let turn = space.turn_through(current, g, [a[0], a[1], a[2]]);
            (
                turn,
                Interval {
                    lo: -MAX_TURN,
                    hi: MAX_TURN,
                },
            )
        }
    };
    let Some(section) = free_section(oracle, &motion, clip, counts)? else {
        return Ok(Step::Stuck);
    };
    let margin = SECTION_MARGIN * section.length();
    let (lo, hi) = (section.lo + margin, section.hi - margin);
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        return Ok(Step::Stuck);
    }
    let t = rng.random_range(lo..hi);
    if t == 0.0 {
        return Ok(Step::Stayed);
    }
    let mut next = motion.at(t);
    if g.kind != GroupKind::Linear {
        // wrap the angle / renormalise the quaternion; a translation leaves the orientation
        // bit for bit as it was, so that the step stays within one group
        space.normalize(&mut next);
    }
    if next.as_slice() == current {
        return Ok(Step::Stayed);
    }
    Ok(Step::Moved(next))
}
