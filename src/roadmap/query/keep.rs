//! Queries answered one after another, each answer fed back into the roadmap before the next
//! ([`answer_keeping`]): how a workcell's roadmap learns from requests like the ones it will be
//! asked, offline (example requests of the cell, before it goes into service) or while it
//! serves (`viaroad query --keep-answers`).
//!
//! A roadmap learnt by sampling the joint space rarely reaches into a pocket (a goal inside
//! MotionBenchMaker's box or cage): its queries attach the goal to nothing and grow trees for
//! tens of milliseconds. The trees that found such a goal cover the pocket around it; kept
//! ([`Roadmap::with_kept`]), the next goal in that pocket attaches to one of their ends by one
//! straight motion, and the way back to the cell's home pose is the kept answer, already
//! shortened.

use super::{BatchAnswer, QueryOptions, QueryPlanner};
use crate::deadline::Deadline;
use crate::roadmap::graph::Roadmap;
use crate::roadmap::persist::RoadmapError;
use crate::roadmap::tree::Rooted;
use crate::space::Config;
use std::time::Instant;

/// Why [`answer_keeping`] stopped.
#[derive(Debug, thiserror::Error)]
pub enum KeepError {
    /// The roadmap's local method cannot answer queries ([`QueryPlanner::new`]).
    #[error("{0}")]
    Roadmap(#[from] RoadmapError),
    /// An answer could not be kept ([`Roadmap::with_kept`]: a malformed path).
    #[error("keeping an answer: {0}")]
    Kept(String),
}

/// The roadmap after [`answer_keeping`], and how many answers it kept.
pub struct KeptAnswers {
    /// The roadmap with every kept answer.
    pub roadmap: Roadmap,
    /// Answers kept.
    pub kept: usize,
}

/// Answers `queries` in their order over `roadmap` with `options`, every answer found (with
/// `keep_trees`, and the trees that found it: [`QueryOptions::return_trees`] is set for it)
/// fed back into the roadmap before the next query ([`Roadmap::with_kept`]). Each answer goes
/// to `on_answer` with its index as it comes; an answer is kept only where `on_answer` says
/// so (a caller with an independent checker keeps only what it certifies). Answers are
/// certified by the oracle that found them, `oracle`, which must be the roadmap scene's.
/// `deadline` bounds the whole run (a query not begun then answers
/// [`super::QueryOutcome::TimedOut`]).
pub fn answer_keeping(
    roadmap: Roadmap,
    oracle: &dyn crate::oracle::CollisionOracle,
    options: &QueryOptions,
    queries: &[(Config, Config)],
    keep_trees: bool,
    deadline: &Deadline,
    on_answer: &mut dyn FnMut(usize, &BatchAnswer) -> bool,
) -> Result<KeptAnswers, KeepError> {
    let options = QueryOptions {
        return_trees: keep_trees,
        ..options.clone()
    };
    let mut roadmap = roadmap;
    let mut kept = 0;
    for (i, (s, g)) in queries.iter().enumerate() {
        let began = Instant::now();
        let result = QueryPlanner::new(&roadmap, oracle)?
            .with_options(options.clone())
            .query_within(s, g, deadline);
        let answer = BatchAnswer {
            result,
            elapsed: began.elapsed(),
        };
        let wanted = on_answer(i, &answer);
        let Ok(r) = &answer.result else { continue };
        if !(wanted && r.is_solved()) {
            continue;
        }
        let trees: Vec<&Rooted> = match &r.trees {
            Some(t) if keep_trees => t.iter().collect(),
            _ => Vec::new(),
        };
        roadmap = roadmap
            .with_kept(&r.path, &trees)
            .map_err(KeepError::Kept)?;
        kept += 1;
    }
    Ok(KeptAnswers { roadmap, kept })
}
