//! Where construction draws its new nodes: uniform sampling, and the samplers of PRM practice
//! that put nodes near obstacles, where narrow passages are (OMPL's valid state samplers).
//!
//! | spec | rule (OMPL's class) |
//! |---|---|
//! | `uniform` | uniform draws until one is free (`UniformValidStateSampler`) |
//! | `bodies` | several bodies placed one at a time, each drawn until it is free of the obstacles and the bodies placed before it (below; `uniform` for one robot) |
//! | `obstacle:margin=M` | a colliding draw, a free draw, walk from the free one towards the colliding one and keep the last free configuration (`ObstacleBasedValidStateSampler`) |
//! | `gaussian:sigma=S` | a uniform draw and a Gaussian neighbour; if exactly one is free, keep it (`GaussianValidStateSampler`) |
//! | `bridge:sigma=S` | a colliding draw and a colliding Gaussian neighbour; keep their midpoint if free (`BridgeTestValidStateSampler`) |
//! | `gap:sigma=S` | the bridge test with exact intervals: a colliding draw and a colliding Gaussian neighbour; the centre of the free gap between them nearest their midpoint (no OMPL counterpart) |
//! | `mix:uniform=1,bridge(sigma=0.05)=2` | each candidate picks one of these by weight |
//!
//! Each candidate runs at most [`LearnParams::sample_attempts`](super::LearnParams) attempts, as
//! OMPL's `nr_attempts` (100 by default, `MAX_VALID_SAMPLE_ATTEMPTS`). Distances are fractions of
//! the space's extent ([`Space::extent`], the diagonal of the position bounds); OMPL's default
//! standard deviation is 0.1 of the extent (`STD_DEV_AS_SPACE_EXTENT_FRACTION`).
//!
//! **The obstacle-based walk uses the exact oracle.** OMPL walks from the free draw towards the
//! colliding one with its discrete motion validator, state check by state check, and keeps the
//! last free state, somewhere within one check resolution (1 % of the extent) of the boundary.
//! Here one [`CountedOracle::intersect`] call on the straight motion gives every collision
//! interval along it (CHS §1.2), so the first boundary is known exactly; the sample is placed
//! `margin · extent` before it (at most half-way back to the start of the free stretch), so it
//! lies near the obstacle without touching it. For a rigid body the walk is the local method's
//! direct path (CHS §1.5): one straight motion per DOF group, in random order, so it costs one
//! intersect call per group moved.
//!
//! **The gap sampler is the bridge test done exactly.** OMPL's bridge test keeps a bridge only
//! when its midpoint happens to be free, so most bridges across a narrow passage are wasted.
//! With intervals (one intersect call per DOF group along the direct path between the two
//! colliding ends) every free gap between them is known; the sampler keeps the centre of the
//! gap nearest the bridge's midpoint — the point of that straight line farthest from both
//! obstacles.
//!
//! **Several bodies are placed one at a time.** Four squares in a corridor barely wider than
//! they are leave almost no free configuration to a uniform draw of all of them at once
//! (hundreds of thousands of draws find none), while each square alone lands in the corridor
//! often. So for an oracle of several bodies ([`CollisionOracle::body_collides`]) the `bodies`
//! sampler draws body 1's pose until it is free of the obstacles, then body 2's until it is
//! free of the obstacles and body 1, and so on, at most [`BODY_DRAWS`] draws per body; a body
//! that finds no place ends the attempt. Every draw is one counted state check. The samples are
//! free but not uniform over the free space: a first body that leaves little room for the
//! others is as likely as one that leaves much. Nor do they help a roadmap by themselves: the
//! bodies fall in any order along a corridor, and a straight motion keeps their order, so
//! most samples lie in parts of the free space that the start and the goal cannot reach
//! directly (see `benches/results/`).
//!
//! **Gaussian neighbours.** Position coordinates get independent normal offsets of standard
//! deviation `σ = sigma · extent` (OMPL's `sampleGaussian`). Departure: a neighbour outside the
//! bounds is not clamped onto them (OMPL's `enforceBounds`) but counts as colliding, as the
//! scene's oracle treats the bounds as walls ([`crate::oracle::Bounded`]); clamping would put
//! samples exactly on the walls. An orientation turns by a random rotation whose angle has standard
//! deviation `σ / rotation_scale`, so that robot points move about `σ` as in
//! [`Space::distance`] (departure: OMPL scales by the orientation space's own extent); beyond
//! π/2 the orientation is drawn uniformly, as OMPL's SO(3) sampler does.
//!
//! **Determinism.** A sampler draws only from the rng it is given; the learner gives every
//! candidate its own stream, so samples do not depend on the thread count.

use crate::oracle::{CallCounts, CollisionOracle, CountedOracle, OracleError};
use crate::space::{rotation, Config, GroupKind, Space, SpaceKind};
use rand::Rng;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// OMPL's standard deviation of Gaussian samplers as a share of the space's extent
/// (`magic::STD_DEV_AS_SPACE_EXTENT_FRACTION`).
pub const DEFAULT_SIGMA: f64 = 0.1;

/// How far before the boundary the obstacle-based walk stops, as a share of the extent: OMPL's
/// check resolution (`longest_valid_segment_fraction` = 0.01), within which its discrete walk
/// stops.
pub const DEFAULT_MARGIN: f64 = 0.01;

/// Draws per body before one attempt of placing several bodies one at a time is given up
/// (OMPL's `nr_attempts`, per body).
pub const BODY_DRAWS: usize = 100;

/// How construction draws a free configuration. The spec string (see the [module](self)) is
/// what the command line takes and what the roadmap file records.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Sampler {
    /// Uniform draws until one is free.
    #[default]
    Uniform,
    /// Several bodies placed one at a time, each drawn until it is free of the obstacles and
    /// the bodies placed before it; uniform draws for one robot.
    Bodies,
    /// Obstacle-based (Amato et al.'s OBPRM rule as in OMPL): the last free configuration on
    /// the way from a free draw to a colliding one, found exactly by interval queries.
    Obstacle {
        /// Distance kept from the boundary, as a share of the extent.
        margin: f64,
    },
    /// Gaussian (Boor, Overmars, van der Stappen 1999): of a free/colliding pair at a Gaussian
    /// distance, the free one.
    Gaussian {
        /// Standard deviation of the pair's distance, as a share of the extent.
        sigma: f64,
    },
    /// Bridge test (Hsu et al. 2003): the free midpoint of two colliding configurations at a
    /// Gaussian distance, so samples fall into gaps between obstacles.
    Bridge {
        /// Standard deviation of the bridge's length, as a share of the extent.
        sigma: f64,
    },
    /// The bridge test with exact intervals: of two colliding configurations at a Gaussian
    /// distance, the centre of the free gap between them nearest their midpoint.
    Gap {
        /// Standard deviation of the bridge's length, as a share of the extent.
        sigma: f64,
    },
    /// Each candidate uses one of these, chosen by weight.
    Mix(Vec<(Sampler, f64)>),
}

/// A sampler spec that does not parse or names impossible numbers.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("sampler `{spec}`: {reason}")]
pub struct SamplerSpecError {
    /// The spec as given.
    pub spec: String,
    /// What is wrong.
    pub reason: String,
}

/// A standard normal number (Box–Muller), from `rng` alone.
fn normal<R: Rng + ?Sized>(rng: &mut R) -> f64 {
    let u1: f64 = 1.0 - rng.random::<f64>(); // (0, 1]
    let u2: f64 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// A uniform draw in canonical form.
fn uniform<R: Rng + ?Sized>(space: &Space, rng: &mut R) -> Config {
    let mut q = space.sample_uniform(rng);
    space.normalize(&mut q);
    q
}

/// A configuration near `mean`: normal offsets of standard deviation `sigma` (a distance) in
/// the position (possibly outside the bounds), and a random turn of about `sigma / rotation_scale`
/// (see the [module](self)).
pub fn gaussian_near<R: Rng + ?Sized>(
    space: &Space,
    mean: &[f64],
    sigma: f64,
    rng: &mut R,
) -> Config {
    let mut q = mean.to_vec();
    let p = space.position_dim();
    for i in 0..p {
        q[i] = mean[i] + sigma * normal(rng);
    }
    let angle_sigma = sigma / space.rotation_scale();
    match space.kind() {
        SpaceKind::Euclidean(_) => {}
        SpaceKind::Joints { continuous, .. } => {
            crate::space::joints::wrap_continuous(continuous, &mut q)
        }
        SpaceKind::Se2 => q[2] = rotation::wrap_angle(mean[2] + angle_sigma * normal(rng)),
        SpaceKind::Se2Bodies(k) => {
            for i in (0..k).map(|b| 3 * b + 2) {
                q[i] = rotation::wrap_angle(mean[i] + angle_sigma * normal(rng));
            }
        }
        SpaceKind::Se3Bodies(_) => {
            crate::space::bodies3::perturb_orientations(&mut q, mean, angle_sigma, rng, normal)
        }
        SpaceKind::Se3 => {
            if angle_sigma > std::f64::consts::FRAC_PI_2 {
                let u = space.sample_uniform(rng);
                q[3..7].copy_from_slice(&u[3..7]);
            } else {
                // a rotation vector with isotropic normal components: its length (the angle)
                // has RMS `angle_sigma`
                let s = angle_sigma / 3f64.sqrt();
                let v = nalgebra::Vector3::new(s * normal(rng), s * normal(rng), s * normal(rng));
                let turn = nalgebra::UnitQuaternion::from_scaled_axis(v);
                let r = turn * rotation::quat_from_slice(&mean[3..7]);
                rotation::quat_to_slice(&r, &mut q[3..7]);
            }
        }
    }
    space.normalize(&mut q);
    q
}

/// What placing several bodies one at a time gave.
enum Placed {
    /// Every body found a free place.
    Free(Config),
    /// A body found none in [`BODY_DRAWS`] draws.
    Stuck,
    /// The space holds one robot, or the oracle cannot test one body at a time.
    OneRobot,
}

/// One attempt of placing several bodies one at a time (see the [module](self)): body `i`'s
/// pose is drawn until it is free of the obstacles and of bodies `0..i`.
fn place_bodies<R: Rng + ?Sized>(
    space: &Space,
    oracle: &dyn CollisionOracle,
    rng: &mut R,
    counts: &mut CallCounts,
) -> Placed {
    let k = space.body_count();
    if k < 2 {
        return Placed::OneRobot;
    }
    let mut q = uniform(space, rng);
    for body in 0..k {
        let coords = space.body_coords(body);
        let mut placed = false;
        for draw in 0..BODY_DRAWS {
            if draw > 0 {
                let d = uniform(space, rng);
                q[coords.clone()].copy_from_slice(&d[coords.clone()]);
            }
            match oracle.body_collides(&q, body, counts) {
                None => return Placed::OneRobot,
                Some(true) => counts.state_checks += 1,
                Some(false) => {
                    counts.state_checks += 1;
                    placed = true;
                    break;
                }
            }
        }
        if !placed {
            return Placed::Stuck;
        }
    }
    Placed::Free(q)
}

/// Free: inside the bounds (walls, whatever the oracle does about them) and free under the
/// oracle (one counted state check).
fn free(space: &Space, oracle: &dyn CollisionOracle, q: &[f64], counts: &mut CallCounts) -> bool {
    space.in_bounds(q) && oracle.is_free(q, counts)
}

impl Sampler {
    /// Draws one free configuration with at most `attempts` attempts; `None` when none was
    /// found. Every oracle question is counted in `counts`. Draws only from `rng`.
    pub fn sample<R: Rng + ?Sized>(
        &self,
        space: &Space,
        oracle: &dyn CollisionOracle,
        attempts: usize,
        rng: &mut R,
        counts: &mut CallCounts,
    ) -> Result<Option<Config>, OracleError> {
        let extent = space.extent();
        match self {
            Sampler::Uniform => {
                for _ in 0..attempts {
                    let q = uniform(space, rng);
                    if oracle.is_free(&q, counts) {
                        return Ok(Some(q));
                    }
                }
                Ok(None)
            }
            Sampler::Bodies => {
                for _ in 0..attempts {
                    match place_bodies(space, oracle, rng, counts) {
                        Placed::Free(q) => return Ok(Some(q)),
                        Placed::Stuck => {}
                        Placed::OneRobot => {
                            let q = uniform(space, rng);
                            if oracle.is_free(&q, counts) {
                                return Ok(Some(q));
                            }
                        }
                    }
                }
                Ok(None)
            }
            Sampler::Obstacle { margin } => {
                obstacle_based(space, oracle, margin * extent, attempts, rng, counts)
            }
            Sampler::Gaussian { sigma } => {
                for _ in 0..attempts {
                    let a = uniform(space, rng);
                    let b = gaussian_near(space, &a, sigma * extent, rng);
                    let fa = oracle.is_free(&a, counts);
                    let fb = free(space, oracle, &b, counts);
                    if fa != fb {
                        return Ok(Some(if fa { a } else { b }));
                    }
                }
                Ok(None)
            }
            Sampler::Bridge { sigma } => {
                for _ in 0..attempts {
                    let a = uniform(space, rng);
                    if oracle.is_free(&a, counts) {
                        continue;
                    }
                    let b = gaussian_near(space, &a, sigma * extent, rng);
                    if free(space, oracle, &b, counts) {
                        continue;
                    }
                    let mut m = space.interpolate(&b, &a, 0.5);
                    space.normalize(&mut m);
                    if free(space, oracle, &m, counts) {
                        return Ok(Some(m));
                    }
                }
                Ok(None)
            }
            Sampler::Gap { sigma } => {
                for _ in 0..attempts {
                    let a = uniform(space, rng);
                    if oracle.is_free(&a, counts) {
                        continue;
                    }
                    let b = gaussian_near(space, &a, sigma * extent, rng);
                    if free(space, oracle, &b, counts) {
                        continue;
                    }
                    if let Some(q) = gap_centre(space, oracle, &a, &b, rng, counts)? {
                        return Ok(Some(q));
                    }
                }
                Ok(None)
            }
            Sampler::Mix(parts) => {
                let total: f64 = parts.iter().map(|(_, w)| w).sum();
                if parts.is_empty() || total.is_nan() || total <= 0.0 {
                    return Ok(None);
                }
                let u = rng.random::<f64>() * total;
                let mut acc = 0.0;
                let mut chosen = &parts[parts.len() - 1].0;
                for (s, w) in parts {
                    acc += w;
                    if u < acc {
                        chosen = s;
                        break;
                    }
                }
                chosen.sample(space, oracle, attempts, rng, counts)
            }
        }
    }

    /// Checks the numbers (also of a spec read from a file); returns what is wrong.
    pub fn validate(&self) -> Result<(), String> {
        match self {
            Sampler::Uniform | Sampler::Bodies => Ok(()),
            Sampler::Obstacle { margin } => {
                if margin.is_finite() && *margin > 0.0 && *margin <= 1.0 {
                    Ok(())
                } else {
                    Err(format!("margin must lie in (0, 1], got {margin}"))
                }
            }
            Sampler::Gaussian { sigma } | Sampler::Bridge { sigma } | Sampler::Gap { sigma } => {
                if sigma.is_finite() && *sigma > 0.0 {
                    Ok(())
                } else {
                    Err(format!("sigma must be a positive number, got {sigma}"))
                }
            }
            Sampler::Mix(parts) => {
                if parts.is_empty() {
                    return Err("a mix needs at least one sampler".into());
                }
                for (s, w) in parts {
                    if matches!(s, Sampler::Mix(_)) {
                        return Err("a mix cannot contain a mix".into());
                    }
                    if !(w.is_finite() && *w > 0.0) {
                        return Err(format!("weights must be positive numbers, got {w}"));
                    }
                    s.validate()?;
                }
                Ok(())
            }
        }
    }

    /// The spec's name and its parameters as `key=value` items.
    fn parts(&self) -> (&'static str, Vec<String>) {
        match self {
            Sampler::Uniform => ("uniform", vec![]),
            Sampler::Bodies => ("bodies", vec![]),
            Sampler::Obstacle { margin } => ("obstacle", vec![format!("margin={margin}")]),
            Sampler::Gaussian { sigma } => ("gaussian", vec![format!("sigma={sigma}")]),
            Sampler::Bridge { sigma } => ("bridge", vec![format!("sigma={sigma}")]),
            Sampler::Gap { sigma } => ("gap", vec![format!("sigma={sigma}")]),
            Sampler::Mix(parts) => (
                "mix",
                parts
                    .iter()
                    .map(|(s, w)| {
                        let (name, kv) = s.parts();
                        if kv.is_empty() {
                            format!("{name}={w}")
                        } else {
                            format!("{name}({})={w}", kv.join(","))
                        }
                    })
                    .collect(),
            ),
        }
    }

    /// A single sampler from its name and `key=value` items (not a mix).
    fn simple(name: &str, items: &[&str]) -> Result<Sampler, String> {
        let value = |key: &str, default: f64| -> Result<f64, String> {
            let mut v = default;
            for kv in items {
                let (k, x) = kv
                    .split_once('=')
                    .ok_or_else(|| format!("`{kv}` is not key=value"))?;
                if k.trim() != key {
                    return Err(format!(
                        "unknown key `{}` for {name}; expected {key}",
                        k.trim()
                    ));
                }
                v = x
                    .trim()
                    .parse()
                    .map_err(|_| format!("{key}={x} is not a number"))?;
            }
            Ok(v)
        };
        match name {
            "uniform" => {
                if let Some(kv) = items.first() {
                    return Err(format!("uniform takes no parameters, got `{kv}`"));
                }
                Ok(Sampler::Uniform)
            }
            "bodies" => {
                if let Some(kv) = items.first() {
                    return Err(format!("bodies takes no parameters, got `{kv}`"));
                }
                Ok(Sampler::Bodies)
            }
            "obstacle" => Ok(Sampler::Obstacle {
                margin: value("margin", DEFAULT_MARGIN)?,
            }),
            "gaussian" => Ok(Sampler::Gaussian {
                sigma: value("sigma", DEFAULT_SIGMA)?,
            }),
            "bridge" => Ok(Sampler::Bridge {
                sigma: value("sigma", DEFAULT_SIGMA)?,
            }),
            "gap" => Ok(Sampler::Gap {
                sigma: value("sigma", DEFAULT_SIGMA)?,
            }),
            "mix" => Err("a mix cannot contain a mix".into()),
            other => Err(format!(
                "unknown sampler `{other}`; expected uniform, bodies, obstacle, gaussian, bridge, gap or mix"
            )),
        }
    }
}

/// Splits at commas outside parentheses.
fn split_top(s: &str) -> Result<Vec<&str>, String> {
    let mut out = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    for (i, c) in s.char_indices() {
        match c {
            '(' => depth += 1,
            ')' => {
                depth -= 1;
                if depth < 0 {
                    return Err("unbalanced `)`".into());
                }
            }
            ',' if depth == 0 => {
                out.push(&s[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    if depth != 0 {
        return Err("unbalanced `(`".into());
    }
    out.push(&s[start..]);
    Ok(out
        .into_iter()
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .collect())
}

/// One part of a mix: `name`, `name=w`, `name(k=v,…)` or `name(k=v,…)=w`.
fn mix_part(item: &str) -> Result<(Sampler, f64), String> {
    let (body, weight) = match item.rfind(')') {
        Some(close) => {
            let rest = item[close + 1..].trim();
            let w = match rest.strip_prefix('=') {
                Some(w) => Some(w),
                None if rest.is_empty() => None,
                None => return Err(format!("`{item}`: expected `=weight` after `)`")),
            };
            (&item[..=close], w)
        }
        None => match item.split_once('=') {
            Some((b, w)) => (b, Some(w)),
            None => (item, None),
        },
    };
    let weight = match weight {
        Some(w) => w
            .trim()
            .parse::<f64>()
            .map_err(|_| format!("weight `{}` of `{item}` is not a number", w.trim()))?,
        None => 1.0,
    };
    let body = body.trim();
    let sampler = match body.split_once('(') {
        Some((name, args)) => {
            let args = args
                .strip_suffix(')')
                .ok_or_else(|| format!("`{item}`: expected `)`"))?;
            let items: Vec<&str> = args
                .split(',')
                .map(str::trim)
                .filter(|t| !t.is_empty())
                .collect();
            Sampler::simple(name.trim(), &items)?
        }
        None => Sampler::simple(body, &[])?,
    };
    Ok((sampler, weight))
}

impl FromStr for Sampler {
    type Err = SamplerSpecError;
    fn from_str(s: &str) -> Result<Sampler, SamplerSpecError> {
        let bad = |reason: String| SamplerSpecError {
            spec: s.to_string(),
            reason,
        };
        let (name, rest) = s.trim().split_once(':').unwrap_or((s.trim(), ""));
        let sampler = if name.trim() == "mix" {
            let parts = split_top(rest)
                .map_err(bad)?
                .into_iter()
                .map(mix_part)
                .collect::<Result<Vec<_>, String>>()
                .map_err(bad)?;
            Sampler::Mix(parts)
        } else {
            let items: Vec<&str> = rest
                .split(',')
                .map(str::trim)
                .filter(|t| !t.is_empty())
                .collect();
            Sampler::simple(name.trim(), &items).map_err(bad)?
        };
        sampler.validate().map_err(bad)?;
        Ok(sampler)
    }
}

impl fmt::Display for Sampler {
    /// The canonical spec: every parameter written out, so that it parses back to the same
    /// sampler.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (name, items) = self.parts();
        if items.is_empty() {
            write!(f, "{name}")
        } else {
            write!(f, "{name}:{}", items.join(","))
        }
    }
}

/// Serialised as its spec string, so that roadmap files and JSON reports say it readably.
impl Serialize for Sampler {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_string())
    }
}

impl<'de> Deserialize<'de> for Sampler {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

/// OMPL's obstacle-based rule with the walk done by interval queries (see the
/// [module](self)): `margin` is a distance.
fn obstacle_based<R: Rng + ?Sized>(
    space: &Space,
    oracle: &dyn CollisionOracle,
    margin: f64,
    attempts: usize,
    rng: &mut R,
    counts: &mut CallCounts,
) -> Result<Option<Config>, OracleError> {
    // a colliding configuration …
    let Some(x) = (0..attempts).find_map(|_| {
        let q = uniform(space, rng);
        (!oracle.is_free(&q, counts)).then_some(q)
    }) else {
        return Ok(None);
    };
    // … and a free one
    let Some(v) = (0..attempts).find_map(|_| {
        let q = uniform(space, rng);
        oracle.is_free(&q, counts).then_some(q)
    }) else {
        return Ok(None);
    };
    let mut groups = space.groups(false);
    if groups.len() > 1 && rng.random::<bool>() {
        groups.reverse();
    }
    let mut current = v;
    for g in &groups {
        if space.same_in_group(&current, &x, g) {
            continue;
        }
        let motion = space.group_motion(&current, &x, g);
        // only the first collision matters: the first-hit question, which can stop early
        let Some(first_lo) = oracle.first_hit(&motion, counts)? else {
            current = space.with_group_of(&current, &x, g);
            continue;
        };
        let start = motion.range.lo;
        if first_lo <= start {
            return Ok(None); // the free stretch is empty (touching at the start)
        }
        let length = space.motion_length(&motion, start, motion.range.hi);
        let back = if length > 0.0 {
            margin / length * (motion.range.hi - start)
        } else {
            0.0
        };
        let t = first_lo - back.min(0.5 * (first_lo - start));
        let mut q = motion.at(t);
        if g.kind != GroupKind::Linear {
            space.normalize(&mut q);
        }
        // the exact boundary is known; one state check guards against rounding
        return Ok(free(space, oracle, &q, counts).then_some(q));
    }
    Ok(None)
}

/// The gap sampler's step (see the [module](self)): the direct path from `a` to `b` (both
/// colliding), one straight motion per DOF group in random order, asked for all its collision
/// intervals; returns the centre of the free section whose centre lies nearest the path's
/// middle (by length), if it is free.
fn gap_centre<R: Rng + ?Sized>(
    space: &Space,
    oracle: &dyn CollisionOracle,
    a: &[f64],
    b: &[f64],
    rng: &mut R,
    counts: &mut CallCounts,
) -> Result<Option<Config>, OracleError> {
    let mut groups = space.groups(false);
    if groups.len() > 1 && rng.random::<bool>() {
        groups.reverse();
    }
    // (motion, its free sections, length before it, its length)
    let mut legs = Vec::with_capacity(groups.len());
    let mut current = a.to_vec();
    let mut offset = 0.0;
    for g in &groups {
        if space.same_in_group(&current, b, g) {
            continue;
        }
        let motion = space.group_motion(&current, b, g);
        let hits = oracle.intersect(&motion, counts)?;
        let gaps = hits.complement_within(motion.range);
        let length = space.motion_length(&motion, motion.range.lo, motion.range.hi);
        legs.push((motion, gaps, offset, length, g.kind));
        offset += length;
        current = space.with_group_of(&current, b, g);
    }
    let middle = 0.5 * offset;
    let mut best: Option<(f64, Config, GroupKind)> = None;
    for (motion, gaps, before, length, kind) in &legs {
        let span = motion.range.hi - motion.range.lo;
        for gap in gaps.iter().filter(|s| s.length() > 0.0) {
            let t = gap.centre();
            let at = before + length * (t - motion.range.lo) / span;
            if best
                .as_ref()
                .is_none_or(|(d, _, _)| (at - middle).abs() < *d)
            {
                best = Some(((at - middle).abs(), motion.at(t), *kind));
            }
        }
    }
    let Some((_, mut q, kind)) = best else {
        return Ok(None);
    };
    if kind != GroupKind::Linear {
        space.normalize(&mut q);
    }
    Ok(free(space, oracle, &q, counts).then_some(q))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_parse_with_defaults_and_print_canonically() {
        let s: Sampler = "obstacle".parse().unwrap();
        assert_eq!(s, Sampler::Obstacle { margin: 0.01 });
        assert_eq!(s.to_string(), "obstacle:margin=0.01");
        assert_eq!("bodies".parse::<Sampler>().unwrap().to_string(), "bodies");
        let m: Sampler = "mix:uniform=1,bridge=2,gaussian(sigma=0.05)"
            .parse()
            .unwrap();
        assert_eq!(
            m,
            Sampler::Mix(vec![
                (Sampler::Uniform, 1.0),
                (Sampler::Bridge { sigma: 0.1 }, 2.0),
                (Sampler::Gaussian { sigma: 0.05 }, 1.0),
            ])
        );
        assert_eq!(
            m.to_string(),
            "mix:uniform=1,bridge(sigma=0.1)=2,gaussian(sigma=0.05)=1"
        );
        for bad in [
            "",
            "ring",
            "gaussian:sigma=0",
            "gaussian:sigma=-1",
            "bridge:width=2",
            "uniform:x=1",
            "obstacle:margin=2",
            "mix:",
            "mix:uniform=0",
            "mix:mix",
            "mix:gaussian(sigma=0.1",
            "mix:uniform=x",
            "mix:bridge(sigma=0.1)x",
        ] {
            assert!(bad.parse::<Sampler>().is_err(), "{bad}");
        }
    }
}
