//! A query whose roadmap search races two trees out of the roadmap ([`QueryOptions::race`]).

#[cfg(doc)]
use super::QueryOptions;
use super::{query_seed, Endpoint, QueryError, QueryOutcome, QueryPlanner, QueryResult, Stages};
use crate::deadline::{race_after, Deadline, Raced};
use crate::oracle::CallCounts;
use crate::roadmap::rooted::RoadmapTrees;
use crate::roadmap::tree::{shortcut_passes, TreeParams, TreeStop, SHORTCUT_WINDOW};
use crate::space::Config;
use std::time::{Duration, Instant};

/// Whether a side of the race answered.
fn answered(a: &Result<QueryResult, QueryError>) -> bool {
    a.as_ref().is_ok_and(QueryResult::is_solved)
}

impl QueryPlanner<'_> {
    /// The roadmap's direct paths alone for at most `head_start` (an arm's; elsewhere its whole
    /// search), then its whole search beside the trees `tree` out of the roadmap
    /// ([`RoadmapTrees`]), until `outer` or the query's time ends; the answer carries the oracle
    /// work of both sides.
    pub(super) fn racing(
        &self,
        start: &[f64],
        goal: &[f64],
        outer: &Deadline,
        head_start: Duration,
        tree: &TreeParams,
    ) -> Result<QueryResult, QueryError> {
        // the ends are checked before either side runs: no tree grows from an end in collision
        // (the search checks them again, and counts that)
        let mut checks = CallCounts::default();
        let start = self.check_endpoint(Endpoint::Start, start, &mut checks)?;
        let goal = self.check_endpoint(Endpoint::Goal, goal, &mut checks)?;
        let deadline = outer.within(self.options.time);
        // an arm's head start asks the direct paths alone: where they fail, the local method's
        // searches (whole-range sweeps) run beside the trees (or after them, in turn), not
        // before; elsewhere they are quick, and the head start is the whole search cut short
        let head_stages = if self.space().is_joints() {
            Stages::Direct
        } else {
            Stages::All
        };
        let alone = if head_start.is_zero() {
            None
        } else {
            let finding = deadline.within(Some(head_start));
            let head = self.search(&start, &goal, (&finding, &deadline), None, head_stages);
            if answered(&head) || deadline.expired() {
                return head;
            }
            Some(head)
        };
        let Raced {
            first,
            head_start,
            second,
        } = race_after(
            &deadline,
            alone,
            |search, whole| self.search(&start, &goal, (search, whole), None, Stages::All),
            answered,
            |d| self.trees_beside(&start, &goal, tree, d),
            answered,
        );
        // the work of the sides that did not answer, added to the answer's
        let mut others = CallCounts::default();
        if let Some(Ok(h)) = &head_start {
            others += h.counts;
        }
        match (first, second) {
            (Ok(mut a), second) if a.is_solved() => {
                if let Some(Ok(t)) = &second {
                    others += t.counts;
                }
                a.counts += others;
                Ok(a)
            }
            (first, Some(Ok(mut t))) if t.is_solved() => {
                if let Ok(f) = &first {
                    others += f.counts;
                }
                t.counts += others;
                Ok(t)
            }
            // neither answered: the roadmap's outcome with the trees' work, or the error of
            // either side (as the trees in turn report theirs)
            (first, second) => {
                let mut a = first?;
                match second {
                    Some(Ok(t)) => others += t.counts,
                    Some(Err(e)) => return Err(e),
                    None => {}
                }
                a.counts += others;
                Ok(a)
            }
        }
    }

    /// Two trees out of the roadmap from `start` and `goal` until `deadline`, their path
    /// shortened by greedy shortcut passes within it.
    fn trees_beside(
        &self,
        start: &Config,
        goal: &Config,
        tree: &TreeParams,
        deadline: &Deadline,
    ) -> Result<QueryResult, QueryError> {
        let mut result =
            QueryResult::unanswered(start.clone(), goal.clone(), CallCounts::default());
        let seed = query_seed(self.roadmap.header().seed, &result);
        let found = RoadmapTrees::new(self.roadmap, self.oracle, &self.groups)
            .keeping(&self.kept_tree)
            .connect(start, goal, &self.tree_params(tree), seed, deadline)?;
        result.counts += found.counts;
        result.grown_nodes = found.nodes[0] + found.nodes[1];
        result.trees = found.trees.filter(|_| self.options.return_trees);
        let Some(raw) = found.path else {
            result.outcome = match found.stop {
                TreeStop::NodeBudget => QueryOutcome::Disconnected,
                _ => QueryOutcome::TimedOut,
            };
            return Ok(result);
        };
        result.outcome = QueryOutcome::Trees;
        let space = self.roadmap.space();
        let path = if self.options.shorten {
            let shortening = Instant::now();
            let (short, error) = shortcut_passes(
                space,
                self.oracle,
                &self.shortcut_groups,
                &raw,
                SHORTCUT_WINDOW,
                &mut result.counts,
                deadline,
            );
            result.shorten_s = shortening.elapsed().as_secs_f64();
            if let Some(e) = error {
                return Err(QueryError::Oracle(e));
            }
            short
        } else {
            raw.clone()
        };
        result.set_paths(space, &self.groups, raw, path);
        Ok(result)
    }
}
