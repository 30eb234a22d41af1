//! The recursive via-point planner of Chadzelek, Hotz and Schömer (CHS §1.2–1.5).
//!
//! `connect(a, z)`: ask for the collision intervals of the direct path; if it is free, done.
//! Otherwise erect a *borderline* across the blocked motion, ask for its free sections, and try
//! their centres as *via points* `q`, best first, recursively connecting `a → q` and `q → z`
//! (divide and conquer, with backtracking and a recursion limit; Fig 1.3). In R^n borderlines
//! lie in the hyperplane perpendicular to the motion (§1.4); for rigid bodies a path changes one
//! DOF group at a time and may dodge into another group (§1.5, Fig 1.6).
//!
//! Everything learnt on the way — via points and certified free segments, also of failed
//! branches — is returned in [`Connection::discoveries`] for the roadmap (§1.6).
//!
//! Departures from the seed, each documented where it happens: the valuation's `d` is the
//! distance of the via point from the borderline's base point (equal to the distance from the
//! blocked motion for perpendicular borderlines); a turn that is free all the way round offers
//! quarter and half turns as via points; an optional call budget stops runaway searches, and a
//! deadline ([`Deadline`]) is checked before every oracle call and watched during one (a long
//! exact sweep gives up, [`crate::deadline::watching`]).

mod borderline;
mod directions;
mod options;
mod search;

pub use options::{BasePoint, Depth, Directions, Search, ViaLimit, ViaPointOptions};

use super::{Connection, LocalMethod, Outcome};
use crate::deadline::Deadline;
use crate::oracle::{CollisionOracle, OracleError};
use crate::space::{Group, Space};

/// The via-point local method.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ViaPoint {
    /// Its parameters.
    pub options: ViaPointOptions,
}

impl ViaPoint {
    /// A planner with these options.
    pub fn new(options: ViaPointOptions) -> Self {
        ViaPoint { options }
    }
}

impl LocalMethod for ViaPoint {
    fn spec(&self) -> super::LocalSpec {
        super::LocalSpec::ViaPoint(self.options.clone())
    }

    fn connect_within(
        &self,
        space: &Space,
        oracle: &dyn CollisionOracle,
        a: &[f64],
        z: &[f64],
        deadline: &Deadline,
    ) -> Result<Connection, OracleError> {
        // the groups and the search's buffers are kept per thread between connections, so
        // that a search in steady state allocates nothing but its answer
        let (mut groups, buffers) = SCRATCH.with(|c| c.take());
        space.groups_into(self.options.split_axes, &mut groups);
        let o = &self.options;
        let plain = o.search == Search::DepthFirst && matches!(o.depth, Depth::Deepen { .. });
        let mut s = search::Search::new(space, oracle, o, &groups, a, z, plain, deadline, buffers);
        // a long call gives up at the deadline too, and the search stops as at its deadline
        let result = crate::deadline::watching(deadline, || Self::run(&mut s, o, a, z));
        let buffers = s.into_buffers();
        SCRATCH.with(|c| c.replace((groups, buffers)));
        result
    }

    fn groups(&self, space: &Space) -> Vec<Group> {
        space.groups(self.options.split_axes)
    }
}

thread_local! {
    /// Per-thread groups and search buffers (see [`search::Buffers`]). Taken out for a
    /// search and put back after it, so a nested search on the same thread simply starts
    /// with empty ones.
    static SCRATCH: std::cell::RefCell<(Vec<Group>, search::Buffers)> = Default::default();
}

impl ViaPoint {
    /// The search proper: the depth strategy of the options run on `s` (CHS §1.3).
    fn run(
        s: &mut search::Search,
        o: &ViaPointOptions,
        a: &[f64],
        z: &[f64],
    ) -> Result<Connection, OracleError> {
        let mut root = s.new_root();
        let mut solved = false;
        let mut last_limit = 0;
        match o.search {
            Search::DepthFirst => {
                let (limits, reuse) = match o.depth {
                    Depth::Fixed(k) => (k..=k, true),
                    Depth::Deepen { max } => (0..=max, false),
                    Depth::DeepenReuse { max } => (0..=max, true),
                };
                for k in limits {
                    last_limit = k;
                    if !reuse && k > 0 {
                        root = s.new_root();
                    }
                    s.limit_hit = false;
                    match s.depth_first(root, k) {
                        Ok(true) => {
                            solved = true;
                            break;
                        }
                        Err(OracleError::Interrupted) => {
                            s.interrupted = true;
                            break;
                        }
                        r => r.map(|_| ())?,
                    }
                    if !s.limit_hit || s.budget_hit || s.dead(root) {
                        break;
                    }
                }
            }
            Search::BreadthFirst => {
                for level in 0..=o.depth.max() {
                    last_limit = level;
                    match s.expand(root, level) {
                        Err(OracleError::Interrupted) => {
                            s.interrupted = true;
                            break;
                        }
                        r => r?,
                    }
                    if s.shortest(root, level).is_some() {
                        solved = true;
                        break;
                    }
                    if s.budget_hit || s.mark_dead(root) {
                        break;
                    }
                }
            }
        }
        let (outcome, path, depth) = if solved {
            let mut path = vec![a.to_vec()];
            s.append_path(root, &mut path);
            if path.len() == 1 {
                path.push(z.to_vec());
            }
            (Outcome::Connected, path, s.solution_depth(root))
        } else if s.interrupted {
            (Outcome::Interrupted, Vec::new(), last_limit)
        } else if !s.budget_hit
            && (s.dead(root) || (o.search == Search::DepthFirst && !s.limit_hit))
        {
            (Outcome::Blocked, Vec::new(), last_limit)
        } else {
            (Outcome::DepthExhausted, Vec::new(), last_limit)
        };
        Ok(Connection {
            outcome,
            path,
            depth,
            counts: s.counts,
            discoveries: s.discoveries(),
            borderlines: std::mem::take(&mut s.borderlines),
        })
    }
}
