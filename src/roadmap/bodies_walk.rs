//! Random-bounce walks for several bodies: steps that move one body, or slide every body in
//! turn, each step still one certified straight motion of one DOF group.
//!
//! The seed's motion model for concurrently moving objects has one translation group — all
//! bodies translate at once, "each with its own fixed speed and direction" — and one turn per
//! body ([`crate::space::bodies`]). A plain random-bounce step in the translation group moves
//! every body along its own random direction at once; in a cluttered place (bodies in a
//! corridor, one behind the other) the free section of such a line is tiny, because the first
//! body to touch anything ends it. But a speed of zero is a speed: the same group's line that
//! moves **one body alone** (every other body's part of the direction zero) is a motion of the
//! model too, asked in one *intersectLine* call, and its free section tells exactly how far
//! that body can go before it touches an obstacle or another body.
//!
//! So a walk of several bodies mixes four kinds of step:
//!
//! - **one body translating** along a random direction or a coordinate axis, to a random point
//!   of its free section or to just short of its end (the contact: where the body meets what
//!   stops it);
//! - a **slide**: every body in turn, front to back along one common direction, each to just
//!   short of its contact — the bodies compact against what lies ahead, in their order, as
//!   sliding puzzles are solved (a body that fits into a side pocket stays there while the
//!   others pass);
//! - all bodies translating together along one random direction in the group (the plain step);
//! - **one body turning**, as in a plain walk.
//!
//! Each step is one straight motion in one group (a slide is a chain of such motions, one per
//! body that moved), proved free by the exact oracle, so consecutive corners are joined by
//! direct paths and the walk becomes roadmap edges with no further local-method call.
//! Slides are what let several bodies change places: a configuration in which a body waits in a
//! pocket while the others stand in order beside it is a handful of slides from the start, and
//! almost never a uniform sample.

use super::step::{free_section, group_step, random_direction, Step, SECTION_MARGIN};
use crate::deadline::Deadline;
use crate::interval::Interval;
use crate::oracle::{CallCounts, CollisionOracle, OracleError};
use crate::space::{Config, Group, GroupKind, Space};
use rand::Rng;

/// Share of a several-body walk's steps that are slides.
pub const SLIDE_SHARE: f64 = 0.4;

/// Share of the steps that translate one body alone.
pub const ONE_BODY_SHARE: f64 = 0.3;

/// Share of the steps that translate all bodies together along one random direction (the plain
/// step of the translation group). The remaining steps turn one body.
pub const TOGETHER_SHARE: f64 = 0.1;

/// Share of slides and one-body steps that go along a coordinate axis (either way) rather than
/// a random direction: walls and pockets of built scenes mostly line up with the axes, and a
/// slide along a random direction stops at the first wall it meets at a slant.
pub const AXIS_SHARE: f64 = 0.5;

/// Share of one-body steps that go to the contact rather than to a random point of the free
/// section.
pub const CONTACT_SHARE: f64 = 0.5;

/// The DOF groups of a space of several bodies as a body-aware walk uses them.
#[derive(Debug)]
pub struct BodyGroups<'g> {
    bodies: usize,
    translations: Vec<&'g Group>,
    turns: Vec<&'g Group>,
}

impl<'g> BodyGroups<'g> {
    /// The groups of `space` split into translation groups that move every body (one run of
    /// coordinates per body) and the rest; `None` unless the space holds several bodies and
    /// `groups` has such a translation group.
    pub fn of(space: &Space, groups: &'g [Group]) -> Option<BodyGroups<'g>> {
        let bodies = space.body_count();
        if bodies < 2 {
            return None;
        }
        let (translations, turns): (Vec<&Group>, Vec<&Group>) = groups
            .iter()
            .partition(|g| g.kind == GroupKind::Linear && g.repeats == bodies && g.stride > 0);
        if translations.is_empty() {
            return None;
        }
        Some(BodyGroups {
            bodies,
            translations,
            turns,
        })
    }
}

/// What a walk step needs besides the random stream: the space, the oracle and the counts.
struct Stepper<'a> {
    space: &'a Space,
    oracle: &'a dyn CollisionOracle,
    counts: &'a mut CallCounts,
}

/// A direction in a group's per-body coordinates (`c` of them): a coordinate axis, either way,
/// with probability [`AXIS_SHARE`], else a random unit vector.
fn body_direction<R: Rng + ?Sized>(c: usize, rng: &mut R) -> Vec<f64> {
    if rng.random::<f64>() < AXIS_SHARE {
        let mut d = vec![0.0; c];
        let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
        d[rng.random_range(0..c)] = sign;
        d
    } else {
        random_direction(c, rng)
    }
}

impl Stepper<'_> {
    /// The line through `current` in group `g` that moves body `body` alone along `d` (its
    /// part of the group's coordinates), and its free section around `current`.
    fn one_body_section(
        &mut self,
        g: &Group,
        current: &[f64],
        body: usize,
        d: &[f64],
    ) -> Result<Option<(crate::space::Motion, Interval)>, OracleError> {
        let c = g.coords.len();
        let mut dir = vec![0.0; g.len()];
        dir[body * c..(body + 1) * c].copy_from_slice(d);
        let motion = self.space.line_through(current, g, &dir);
        let reach = self.space.extent();
        let clip = Interval {
            lo: -reach,
            hi: reach,
        };
        let section = free_section(self.oracle, &motion, clip, self.counts)?;
        Ok(section.map(|s| (motion, s)))
    }

    /// Body `body` moved along `d` to just short of its contact ahead; `None` when it cannot
    /// move forward.
    fn contact_step(
        &mut self,
        g: &Group,
        current: &[f64],
        body: usize,
        d: &[f64],
    ) -> Result<Option<Config>, OracleError> {
        let Some((motion, section)) = self.one_body_section(g, current, body, d)? else {
            return Ok(None);
        };
        let t = section.hi - SECTION_MARGIN * section.length();
        if t.is_nan() || t <= 0.0 {
            return Ok(None);
        }
        Ok(Some(motion.at(t)).filter(|q| q.as_slice() != current))
    }

    /// Body `body` moved along `d` to a random point of its free section (either way).
    fn random_point_step<R: Rng + ?Sized>(
        &mut self,
        g: &Group,
        current: &[f64],
        body: usize,
        d: &[f64],
        rng: &mut R,
    ) -> Result<Option<Config>, OracleError> {
        let Some((motion, section)) = self.one_body_section(g, current, body, d)? else {
            return Ok(None);
        };
        let margin = SECTION_MARGIN * section.length();
        let (lo, hi) = (section.lo + margin, section.hi - margin);
        if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
            return Ok(None);
        }
        let t = rng.random_range(lo..hi);
        Ok(Some(motion.at(t)).filter(|q| t != 0.0 && q.as_slice() != current))
    }

    /// One body, drawn at random, translated along [`body_direction`] in group `g`.
    fn one_body<R: Rng + ?Sized>(
        &mut self,
        g: &Group,
        current: &[f64],
        bodies: usize,
        rng: &mut R,
    ) -> Result<Option<Config>, OracleError> {
        let body = rng.random_range(0..bodies);
        let d = body_direction(g.coords.len(), rng);
        if rng.random::<f64>() < CONTACT_SHARE {
            self.contact_step(g, current, body, &d)
        } else {
            self.random_point_step(g, current, body, &d, rng)
        }
    }

    /// A slide along [`body_direction`] in group `g`: every body in turn, the one farthest
    /// ahead first, to just short of its contact. Pushes a corner for every body that moved and
    /// returns the configuration reached.
    #[allow(clippy::too_many_arguments)]
    fn slide<R: Rng + ?Sized>(
        &mut self,
        g: &Group,
        current: &[f64],
        bodies: usize,
        rng: &mut R,
        deadline: &Deadline,
        corners: &mut Vec<Config>,
    ) -> Result<Config, OracleError> {
        let d = body_direction(g.coords.len(), rng);
        let ahead = |q: &[f64], body: usize| -> f64 {
            let base = body * g.stride + g.coords.start;
            d.iter().enumerate().map(|(j, dj)| dj * q[base + j]).sum()
        };
        let mut order: Vec<(usize, f64)> = (0..bodies).map(|b| (b, ahead(current, b))).collect();
        order.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        let mut q = current.to_vec();
        for (body, _) in order {
            if deadline.expired() {
                break;
            }
            if let Some(next) = self.contact_step(g, &q, body, &d)? {
                corners.push(next.clone());
                q = next;
            }
        }
        Ok(q)
    }
}

/// [`super::bounce::random_bounce`] for a space of several bodies: `steps` steps, each a slide,
/// one body translating, all translating together, or one body turning (see the module docs),
/// from the free configuration `start`. Returns the corners reached (`start` excluded), each
/// joined to the one before by a certified free motion in one group. Stops early when
/// `deadline` has passed; a step that cannot move is skipped.
#[allow(clippy::too_many_arguments)]
pub fn bodies_bounce<R: Rng + ?Sized>(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &BodyGroups<'_>,
    start: &[f64],
    steps: usize,
    rng: &mut R,
    counts: &mut CallCounts,
    deadline: &Deadline,
) -> Result<Vec<Config>, OracleError> {
    let mut corners: Vec<Config> = Vec::with_capacity(steps.min(64));
    let mut current = start.to_vec();
    let mut stepper = Stepper {
        space,
        oracle,
        counts,
    };
    for _ in 0..steps {
        if deadline.expired() {
            break;
        }
        let g = groups.translations[rng.random_range(0..groups.translations.len())];
        let u = rng.random::<f64>();
        let turn = u >= SLIDE_SHARE + ONE_BODY_SHARE + TOGETHER_SHARE && !groups.turns.is_empty();
        if turn {
            let t = groups.turns[rng.random_range(0..groups.turns.len())];
            if let Step::Moved(next) = group_step(space, oracle, t, &current, rng, stepper.counts)?
            {
                corners.push(next.clone());
                current = next;
            }
        } else if u < SLIDE_SHARE {
            current = stepper.slide(g, &current, groups.bodies, rng, deadline, &mut corners)?;
        } else if u < SLIDE_SHARE + ONE_BODY_SHARE {
            if let Some(next) = stepper.one_body(g, &current, groups.bodies, rng)? {
                corners.push(next.clone());
                current = next;
            }
        } else if let Step::Moved(next) =
            group_step(space, oracle, g, &current, rng, stepper.counts)?
        {
            corners.push(next.clone());
            current = next;
        }
    }
    Ok(corners)
}
