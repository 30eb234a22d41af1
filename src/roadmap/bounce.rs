//! Random-bounce walks of the expansion step (OS94), driven by exact free sections.
//!
//! OS94 walks from a difficult node in a random direction "until an obstacle is hit", then
//! bounces off in a new random direction. A sampling planner has to discover the obstacle
//! step by step; with an interval oracle the walk knows at once how far it may go: one
//! *intersectLine* call on the unbounded line (or full turn) through the current configuration
//! gives every collision interval along it, and the free section containing the current
//! configuration is exactly the part it can reach (CHS §1.2). The walk moves to a random point
//! of that section, so every step is a certified free straight motion in one DOF group.
//!
//! Departure from OS94: each step moves in one DOF group (CHS §1.5) — a line in a position
//! group, a turn about a random axis in a rotation group, alternating between groups — rather
//! than along a random direction in the whole configuration space, so that every step is a
//! direct path of the local method and can become a roadmap edge.

use super::bodies_walk::{bodies_bounce, BodyGroups};
use super::step::{group_step, Step};
pub use super::step::{random_direction, MAX_TURN, SECTION_MARGIN};
use crate::deadline::Deadline;
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle, OracleError};
use crate::space::{Config, Group, GroupKind, Space};
use rand::Rng;

/// Walks `steps` single-group straight motions from the free configuration `start` and returns
/// the configurations reached after each step that moved (`start` excluded). Consecutive
/// configurations of `[start, result…]` are joined by certified free motions in one of
/// `groups`. Stops early when the current configuration has no free section around it (it
/// touches an obstacle), or when `deadline` has passed.
///
/// In a space of several bodies the steps are body-aware ([`super::bodies_walk`]): one body
/// translating or turning, or a slide of every body in turn.
#[allow(clippy::too_many_arguments)]
pub fn random_bounce<R: Rng + ?Sized>(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    start: &[f64],
    steps: usize,
    rng: &mut R,
    counts: &mut CallCounts,
    deadline: &Deadline,
) -> Result<Vec<Config>, OracleError> {
    if let Some(bodies) = BodyGroups::of(space, groups) {
        return bodies_bounce(space, oracle, &bodies, start, steps, rng, counts, deadline);
    }
    let mut corners: Vec<Config> = Vec::with_capacity(steps.min(64));
    let mut current = start.to_vec();
    let mut group = rng.random_range(0..groups.len().max(1));
    for step in 0..steps {
        if deadline.expired() {
            // the walk so far is free: it ends here
            break;
        }
        if step > 0 && groups.len() > 1 {
            // bounce into another group
            group = (group + rng.random_range(1..groups.len())) % groups.len();
        }
        match group_step(space, oracle, &groups[group], &current, rng, counts)? {
            Step::Moved(next) => {
                corners.push(next.clone());
                current = next;
            }
            Step::Stayed => {}
            Step::Stuck => break,
        }
    }
    Ok(corners)
}

/// Walks from the free configuration `start` towards `target` one DOF group at a time, each step
/// as far as it is free: RRT's *extend* (LaValle–Kuffner) with the exact oracle, which tells in
/// one call how far the straight single-group motion towards the target's coordinates of that
/// group is free (CHS §1.2). A step that reaches the target's coordinates ends there; one that
/// hits an obstacle stops just short of it ([`SECTION_MARGIN`] of the free part). Up to `rounds`
/// passes over `groups`; stops early when a pass moves nothing, when the target is reached or
/// when `deadline` has passed. Returns the configurations reached (`start` excluded), joined to
/// `start` and to each other by certified free single-group motions.
#[allow(clippy::too_many_arguments)]
pub fn directed_walk(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    start: &[f64],
    target: &[f64],
    rounds: usize,
    counts: &mut CallCounts,
    deadline: &Deadline,
) -> Result<Vec<Config>, OracleError> {
    let mut corners: Vec<Config> = Vec::new();
    let mut current = start.to_vec();
    for _ in 0..rounds {
        let mut moved = false;
        for g in groups {
            if deadline.expired() {
                return Ok(corners);
            }
            if space.same_in_group(&current, target, g) {
                continue;
            }
            let goal = space.with_group_of(&current, target, g);
            let motion = space.group_motion(&current, &goal, g);
            // the free section from the start is [lo, first collision]: the first-hit question
            // answers it and can stop early
            let lo = motion.range.lo;
            let hi = match oracle.first_hit(&motion, counts)? {
                None => motion.range.hi,
                // the current configuration touches an obstacle in this group's direction
                Some(hit) if hit <= lo => continue,
                Some(hit) => hit,
            };
            let next = if hi >= motion.range.hi {
                goal
            } else {
                let t = hi - SECTION_MARGIN * (hi - lo);
                if t <= 0.0 {
                    continue;
                }
                let mut q = motion.at(t);
                if g.kind != GroupKind::Linear {
                    space.normalize(&mut q);
                }
                q
            };
            if next == current {
                continue;
            }
            corners.push(next.clone());
            current = next;
            moved = true;
        }
        if !moved || current.as_slice() == target {
            break;
        }
    }
    Ok(corners)
}
