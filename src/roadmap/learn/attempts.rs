//! Connection attempts from one configuration towards its neighbours, made in the parallel
//! part of a round and applied later.

use super::Learner;
use crate::deadline::Deadline;
use crate::local::{direct_connection, Connection};
use crate::oracle::OracleError;

/// A neighbour of a construction candidate: an existing node, or an earlier candidate of the
/// same round.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Target {
    Node(u32),
    Candidate(usize),
}

/// A connection attempt made in the parallel part of a round, applied later.
pub(super) struct Attempt {
    pub(super) target: Target,
    pub(super) connection: Connection,
}

impl Learner<'_> {
    /// Tries the local method from `q` towards `targets` (nearest first), skipping targets in a
    /// component `q` has joined in this attempt sequence unless cycle edges are wanted.
    /// `component` names a target's component as the round began.
    pub(super) fn attempts(
        &self,
        q: &[f64],
        targets: &[(Target, &[f64])],
        mut joined: Vec<Target>,
        component: impl Fn(Target) -> Target,
        (cycle_edges, deep): (bool, Option<usize>),
        deadline: &Deadline,
    ) -> Result<Vec<Attempt>, OracleError> {
        let mut out = Vec::with_capacity(targets.len());
        let groups = deep.map(|_| self.local.groups(self.space));
        for &(target, tq) in targets {
            let comp = component(target);
            if !cycle_edges && joined.contains(&comp) {
                continue;
            }
            if deadline.expired() {
                break;
            }
            // cheap attempts beyond the nearest `deep` ones (LearnParams::deep_neighbours)
            let mut connection = match (&groups, deep) {
                (Some(groups), Some(d)) if out.len() >= d => {
                    direct_connection(self.space, self.oracle, groups, q, tq)?
                }
                _ => self.local.connect_within(
                    self.space,
                    self.oracle,
                    q,
                    tq,
                    &deadline.within(self.attempt_cap),
                )?,
            };
            connection.borderlines.clear();
            if connection.is_connected() {
                joined.push(comp);
            }
            out.push(Attempt { target, connection });
        }
        Ok(out)
    }
}
