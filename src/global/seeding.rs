//! Where a roadmap starts: from nothing, as Overmars and Švestka's learner
//! does, or from a global method's output — the spine points of Brooks's freeways with their
//! legal orientations ([`super::cones::seeds`]). `viaroad build --seed-from cones` learns one
//! roadmap from the seeds; `viaroad bench local --seed-from plain cones` compares learning
//! with and without them inside the same learner, on the same queries.

use super::cones::seeds::{seed_roadmap, MAX_SEED_NODES};
use super::cones::{ConeError, Freeways};
use crate::local::LocalSpec;
use crate::oracle::CollisionOracle;
use crate::roadmap::{LearnParams, Roadmap};
use crate::scene::Scene;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;
use std::time::{Duration, Instant};

/// How a roadmap starts before learning grows it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Seeding {
    /// From nothing: every node is sampled or discovered by the learner.
    #[default]
    Plain,
    /// From the freeways of Brooks's generalized cones: spine intersections and spine ends at
    /// the middle of each legal orientation interval, joined along the spines and by turns on
    /// the spot, every node and edge checked by the exact oracle. Planar scenes only (SE(2)
    /// with a polygonal robot, R² with a point); see [`Freeways::supports`]. Written `cones`,
    /// or `cones:nodes=N` to keep at most `N` seed nodes (without it the caller's cap holds:
    /// half the node budget for `build`, half the node cap for `bench local`).
    Cones {
        /// Most seed nodes (`None`: the caller's cap); at most [`MAX_SEED_NODES`].
        nodes: Option<usize>,
    },
}

/// A seeding spec that is not `plain`, `cones` or `cones:nodes=N`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("seeding `{spec}`: {why}; expected `plain`, `cones` or `cones:nodes=N`")]
pub struct UnknownSeeding {
    /// The spec as given.
    pub spec: String,
    /// What is wrong with it.
    pub why: String,
}

impl FromStr for Seeding {
    type Err = UnknownSeeding;
    fn from_str(s: &str) -> Result<Self, UnknownSeeding> {
        let bad = |why: String| UnknownSeeding {
            spec: s.to_string(),
            why,
        };
        let (name, params) = s.trim().split_once(':').unwrap_or((s.trim(), ""));
        match name {
            "plain" | "none" if params.is_empty() => Ok(Seeding::Plain),
            "plain" | "none" => Err(bad("plain takes no parameters".into())),
            "cones" => {
                let mut nodes = None;
                for kv in params.split(',').map(str::trim).filter(|t| !t.is_empty()) {
                    match kv.split_once('=') {
                        Some(("nodes", v)) => {
                            let n = v
                                .trim()
                                .parse::<usize>()
                                .ok()
                                .filter(|n| (1..=MAX_SEED_NODES).contains(n))
                                .ok_or_else(|| {
                                    bad(format!(
                                        "nodes={v} must be a count from 1 to {MAX_SEED_NODES}"
                                    ))
                                })?;
                            nodes = Some(n);
                        }
                        _ => return Err(bad(format!("unknown parameter `{kv}`"))),
                    }
                }
                Ok(Seeding::Cones { nodes })
            }
            other => Err(bad(format!("unknown seeding `{other}`"))),
        }
    }
}

impl fmt::Display for Seeding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Seeding::Plain => f.write_str("plain"),
            Seeding::Cones { nodes: None } => f.write_str("cones"),
            Seeding::Cones { nodes: Some(n) } => write!(f, "cones:nodes={n}"),
        }
    }
}

impl Serialize for Seeding {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_string())
    }
}

impl<'de> Deserialize<'de> for Seeding {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

/// A seed roadmap and what it cost.
#[derive(Clone, Debug)]
pub struct Seeded {
    /// The roadmap learning starts from; its header's counts are the oracle work of building
    /// and checking it (the learner does not count them again).
    pub roadmap: Roadmap,
    /// Freeways (generalized cones) the seeds came from.
    pub freeways: usize,
    /// Wall time of building the freeways and checking the seeds.
    pub elapsed: Duration,
}

impl Seeding {
    /// Whether this seeding can start a roadmap of `scene`: always for
    /// [`Plain`](Seeding::Plain); for [`Cones`](Seeding::Cones) the check of
    /// [`Freeways::supports`] (no cones are built).
    pub fn check(&self, scene: &Scene) -> Result<(), ConeError> {
        match self {
            Seeding::Plain => Ok(()),
            Seeding::Cones { .. } => Freeways::supports(scene),
        }
    }

    /// The seed roadmap of `scene` (`None` for [`Plain`](Seeding::Plain)), of at most
    /// `max_nodes` nodes, or the seeding's own `nodes=` when it gives one (at most
    /// [`MAX_SEED_NODES`] either way). `params`, `local_spec` and `seed` go to its header as
    /// the learner will record them. Deterministic: it depends on the scene only.
    pub fn seed_roadmap(
        &self,
        scene: &Scene,
        oracle: &dyn CollisionOracle,
        params: &LearnParams,
        local_spec: &LocalSpec,
        seed: u64,
        max_nodes: usize,
    ) -> Result<Option<Seeded>, ConeError> {
        match self {
            Seeding::Plain => Ok(None),
            Seeding::Cones { nodes } => {
                let max_nodes = nodes.unwrap_or(max_nodes);
                let began = Instant::now();
                let fw = Freeways::build(scene)?;
                let roadmap = seed_roadmap(
                    &fw,
                    scene,
                    oracle,
                    params,
                    local_spec,
                    seed,
                    max_nodes.min(MAX_SEED_NODES),
                )?;
                Ok(Some(Seeded {
                    roadmap,
                    freeways: fw.cones().len(),
                    elapsed: began.elapsed(),
                }))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seedings_parse_and_print() {
        for s in [
            Seeding::Plain,
            Seeding::Cones { nodes: None },
            Seeding::Cones { nodes: Some(200) },
        ] {
            assert_eq!(s.to_string().parse::<Seeding>().unwrap(), s);
            let json = serde_json::to_string(&s).unwrap();
            assert_eq!(serde_json::from_str::<Seeding>(&json).unwrap(), s);
        }
        assert_eq!("none".parse::<Seeding>().unwrap(), Seeding::Plain);
        assert_eq!(
            "cones:nodes=50".parse::<Seeding>().unwrap().to_string(),
            "cones:nodes=50"
        );
        for bad in [
            "brooks",
            "cones:nodes=0",
            "cones:nodes=x",
            "cones:max=3",
            "plain:nodes=1",
        ] {
            assert!(bad.parse::<Seeding>().is_err(), "{bad}");
        }
    }
}
