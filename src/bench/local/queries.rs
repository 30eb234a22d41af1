//! The fixed query set of a scene: the same queries for every method and every run.
//!
//! For an OMPL.app problem the query file next to it is used when there is one
//! (`scenes/ompl/queries/<problem>_*.txt`, written by the OMPL peer, so that both planners
//! answer the same 50 queries); otherwise the scene's own queries come first and seeded random
//! valid queries fill the set up to the requested size.

use super::BenchError;
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle};
use crate::scene::{ompl_cfg, Scene};
use crate::space::Config;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Which queries a benchmark asks.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum QueryChoice {
    /// The scene's OMPL query file if it has one, else random queries.
    Auto {
        /// Size of a random set.
        count: usize,
    },
    /// The scene's own queries, then random ones up to `count`.
    Random {
        /// Size of the set.
        count: usize,
    },
    /// Query pairs from a file (one pair per line: start then goal, OMPL's layout).
    File(PathBuf),
}

/// Query groups known to be infeasible, or at best extremely narrow, scored apart: the 25
/// queries of `cubicles_seed1_50.txt` that join the western basement (x ≲ 25, z < 0) with the
/// rest of the building, which OMPL's PRM never solved (8 runs, 20 s per query, RRTConnect for
/// 60 s), listed in `scenes/ompl/queries/README.md`. Returns the group's name and indices.
pub fn known_separate(file_name: &str) -> Option<(&'static str, &'static [usize])> {
    const CUBICLES_BASEMENT: [usize; 25] = [
        3, 6, 7, 9, 13, 15, 17, 18, 19, 20, 21, 22, 27, 28, 29, 31, 32, 33, 35, 37, 39, 40, 43, 46,
        48,
    ];
    match file_name {
        "cubicles_seed1_50.txt" => Some(("western basement", &CUBICLES_BASEMENT)),
        _ => None,
    }
}

/// The OMPL query file of a `.cfg` scene: `<cfg dir>/../queries/<stem>_*.txt`, the first in
/// name order.
pub fn ompl_query_file(scene: &Scene) -> Option<PathBuf> {
    let cfg = scene.source.as_ref()?;
    if cfg.extension().and_then(|e| e.to_str()) != Some("cfg") {
        return None;
    }
    let stem = cfg.file_stem()?.to_str()?;
    let dir = cfg.parent()?.parent()?.join("queries");
    let prefix = format!("{stem}_");
    let mut found: Vec<PathBuf> = std::fs::read_dir(&dir)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension().and_then(|e| e.to_str()) == Some("txt")
                && p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with(&prefix))
        })
        .collect();
    found.sort();
    found.into_iter().next()
}

/// How a query of the set is scored.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum QueryRole {
    /// Counts towards the target share.
    Scored,
    /// In a group known to be infeasible: answered once at the end, reported apart.
    Separate,
    /// Start or goal invalid under our oracle (the message says why): not asked.
    Invalid(String),
}

/// A fixed, ordered set of queries.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct QuerySet {
    /// Where the queries come from (a file, or `random: …`).
    pub source: String,
    /// Start and goal of each query, normalised.
    pub pairs: Vec<(Config, Config)>,
    /// How each query is scored.
    pub roles: Vec<QueryRole>,
    /// Name of the separate group, if any.
    pub separate_group: Option<String>,
}

/// Attempts to draw one free configuration before a random query set gives up.
const MAX_SAMPLE_ATTEMPTS: usize = 100_000;

impl QuerySet {
    /// The query set of `scene` chosen by `choice`; random queries come from a ChaCha8 stream
    /// seeded with `seed`.
    pub fn build(scene: &Scene, choice: &QueryChoice, seed: u64) -> Result<QuerySet, BenchError> {
        let oracle = scene.oracle();
        let set = match choice {
            QueryChoice::File(path) => Self::from_file(scene, oracle.as_ref(), path),
            QueryChoice::Auto { count } => match ompl_query_file(scene) {
                Some(path) => Self::from_file(scene, oracle.as_ref(), &path),
                None => Self::random(scene, oracle.as_ref(), *count, seed),
            },
            QueryChoice::Random { count } => Self::random(scene, oracle.as_ref(), *count, seed),
        }?;
        // a run stops at a share of the scored queries: with none, every run would "reach" it
        // at its first stage
        if set.scored().is_empty() {
            return Err(BenchError::Invalid(format!(
                "{}: no valid queries to score ({} in the set)",
                set.source,
                set.len()
            )));
        }
        Ok(set)
    }

    fn from_file(
        scene: &Scene,
        oracle: &dyn CollisionOracle,
        path: &Path,
    ) -> Result<QuerySet, BenchError> {
        let queries = ompl_cfg::read_query_pairs(path, &scene.space)?;
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default();
        let separate = known_separate(name);
        let mut set = QuerySet {
            source: path.display().to_string(),
            pairs: Vec::with_capacity(queries.len()),
            roles: Vec::with_capacity(queries.len()),
            separate_group: separate.map(|(g, _)| g.to_string()),
        };
        for (i, q) in queries.into_iter().enumerate() {
            let start = scene.check_config(oracle, &format!("start of query {i}"), &q.start);
            let goal = scene.check_config(oracle, &format!("goal of query {i}"), &q.goal);
            match (start, goal) {
                (Ok(s), Ok(g)) => {
                    set.pairs.push((s, g));
                    let apart = separate.is_some_and(|(_, idx)| idx.contains(&i));
                    set.roles.push(if apart {
                        QueryRole::Separate
                    } else {
                        QueryRole::Scored
                    });
                }
                (s, g) => {
                    let why = [s.err(), g.err()]
                        .into_iter()
                        .flatten()
                        .map(|e| e.to_string())
                        .collect::<Vec<_>>()
                        .join("; ");
                    set.pairs.push((q.start, q.goal));
                    set.roles.push(QueryRole::Invalid(why));
                }
            }
        }
        Ok(set)
    }

    fn random(
        scene: &Scene,
        oracle: &dyn CollisionOracle,
        count: usize,
        seed: u64,
    ) -> Result<QuerySet, BenchError> {
        let mut set = QuerySet {
            source: format!("random: {count} queries, seed {seed} (the scene's own first)"),
            pairs: Vec::with_capacity(count),
            roles: Vec::with_capacity(count),
            separate_group: None,
        };
        for (i, q) in scene.queries.iter().take(count).enumerate() {
            // a loaded scene has checked its queries; a generated one has none
            let s = scene.check_config(oracle, &format!("start of query {i}"), &q.start)?;
            let g = scene.check_config(oracle, &format!("goal of query {i}"), &q.goal)?;
            set.pairs.push((s, g));
            set.roles.push(QueryRole::Scored);
        }
        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x7175_6572_6965_7321); // "queries!"
        let mut counts = CallCounts::default();
        let mut free = || -> Result<Config, BenchError> {
            for _ in 0..MAX_SAMPLE_ATTEMPTS {
                let mut q = scene.space.sample_uniform(&mut rng);
                scene.space.normalize(&mut q);
                if oracle.is_free(&q, &mut counts) {
                    return Ok(q);
                }
            }
            Err(BenchError::Invalid(format!(
                "scene {}: no free configuration in {MAX_SAMPLE_ATTEMPTS} uniform samples",
                scene.name
            )))
        };
        while set.pairs.len() < count {
            let s = free()?;
            let g = free()?;
            set.pairs.push((s, g));
            set.roles.push(QueryRole::Scored);
        }
        Ok(set)
    }

    /// Number of queries.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    /// Whether the set is empty.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// Indices of the queries with `role`'s kind.
    fn indices(&self, keep: impl Fn(&QueryRole) -> bool) -> Vec<usize> {
        (0..self.len()).filter(|&i| keep(&self.roles[i])).collect()
    }

    /// Indices of the scored queries.
    pub fn scored(&self) -> Vec<usize> {
        self.indices(|r| *r == QueryRole::Scored)
    }

    /// Indices of the separate group.
    pub fn separate(&self) -> Vec<usize> {
        self.indices(|r| *r == QueryRole::Separate)
    }

    /// Indices of the invalid queries.
    pub fn invalid(&self) -> Vec<usize> {
        self.indices(|r| matches!(r, QueryRole::Invalid(_)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    fn scene(path: &str) -> Scene {
        Scene::load(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap()
    }

    #[test]
    fn random_sets_are_free_fixed_and_start_with_the_scene_queries() {
        let s = scene("scenes/discs-cluttered.toml");
        let a = QuerySet::build(&s, &QueryChoice::Auto { count: 40 }, 3).unwrap();
        let b = QuerySet::build(&s, &QueryChoice::Random { count: 40 }, 3).unwrap();
        assert_eq!(a, b);
        assert_eq!(a.len(), 40);
        assert_eq!(a.scored().len(), 40);
        assert_eq!(
            a.pairs[0],
            (s.queries[0].start.clone(), s.queries[0].goal.clone())
        );
        let oracle = s.oracle();
        for (p, q) in &a.pairs {
            assert!(oracle.is_free(p, &mut CallCounts::default()));
            assert!(oracle.is_free(q, &mut CallCounts::default()));
        }
        let c = QuerySet::build(&s, &QueryChoice::Random { count: 40 }, 4).unwrap();
        assert_ne!(a.pairs[10], c.pairs[10]);
    }

    #[test]
    fn cubicles_uses_its_ompl_file_and_sets_the_basement_apart() {
        let s = scene("scenes/ompl/3D/cubicles.cfg");
        let set = QuerySet::build(&s, &QueryChoice::Auto { count: 7 }, 1).unwrap();
        assert!(
            set.source.ends_with("cubicles_seed1_50.txt"),
            "{}",
            set.source
        );
        assert_eq!(set.len(), 50);
        assert_eq!(set.separate_group.as_deref(), Some("western basement"));
        assert_eq!(
            set.separate().len() + set.invalid().len() + set.scored().len(),
            50
        );
        assert!(set.separate().contains(&3) || set.invalid().contains(&3));
        assert!(set.scored().len() >= 20, "{:?}", set.invalid());
    }
}
