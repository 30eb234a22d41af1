//! Expansion rounds (OS94, OMPL's `expandRoadmap`): random-bounce walks from nodes drawn by
//! failure ratio, their ends connected to nearest nodes in other components. Joining a pair,
//! a share of the walks are directed instead (RRT-Connect's extend, LaValle–Kuffner 2000): from
//! the node of one end's component nearest to a uniform sample, towards that sample, and their
//! ends are also tried against the other end's component.

use super::super::bounce::{directed_walk, random_bounce};
use super::super::params::{Budget, LearnParams};
use super::attempts::{Attempt, Target};
use super::streams::{stream, WALK_STREAM};
use super::work::Work;
use super::{LearnError, Learner};
use crate::deadline::Deadline;
use crate::oracle::{CallCounts, OracleError};
use crate::space::Config;
use rand::Rng;
use rayon::prelude::*;

/// The weight every node of a focused component has beyond its failure ratio, so that walks
/// also leave components whose nodes have not failed yet.
const FOCUS_FLOOR: f64 = 0.05;

/// Passes over the DOF groups of one directed walk.
const DIRECTED_ROUNDS: usize = 2;

/// Nodes of the other end's component a directed walk's end is also tried against.
const OTHER_SIDE_TARGETS: usize = 2;

/// The two components a pair-joining expansion grows: the nodes of the start's and of the
/// goal's component as the round began.
struct Sides {
    nodes: [Vec<u32>; 2],
}

impl Sides {
    /// `None` unless `focus` is a pair whose ends are in different components.
    fn of(work: &Work<'_>, focus: Option<(u32, u32)>) -> Option<Sides> {
        let (s, g) = focus?;
        let (cs, cg) = (work.uf.find(s), work.uf.find(g));
        if cs == cg {
            return None;
        }
        let mut nodes = [Vec::new(), Vec::new()];
        for i in 0..work.node_count() as u32 {
            let c = work.uf.find(i);
            if c == cs {
                nodes[0].push(i);
            } else if c == cg {
                nodes[1].push(i);
            }
        }
        Some(Sides { nodes })
    }

    /// The `k` nodes of side `side` nearest to `q`, nearest first (a scan: a side holds at most
    /// the roadmap's nodes, and one oracle call costs more than the scan).
    fn nearest(&self, work: &Work<'_>, side: usize, q: &[f64], k: usize) -> Vec<(u32, f64)> {
        let mut near: Vec<(u32, f64)> = self.nodes[side]
            .iter()
            .map(|&i| (i, work.space.distance(work.node(i), q)))
            .collect();
        near.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        near.truncate(k);
        near
    }
}

/// A walk made in the parallel part of an expansion round.
struct Walk {
    from: u32,
    corners: Vec<Config>,
    attempts: Vec<Attempt>,
}

/// OS94's weights `f / (n + 1)` of the nodes walks may leave, as cumulative sums for drawing
/// by weight, and their total. Joining a pair (`focus`: its two nodes), walks leave only the
/// two components that must meet, half from each, weighted by failure ratio within each (a
/// small component boxed in by a narrow passage gets as many walks as the rest of the
/// roadmap).
fn walk_weights(work: &Work<'_>, focus: Option<(u32, u32)>) -> (Vec<f64>, f64) {
    let ratio = |i: usize| f64::from(work.failures[i]) / (f64::from(work.tries[i]) + 1.0);
    let mut cumulative = Vec::with_capacity(work.node_count());
    let mut total = 0.0;
    match focus.map(|(s, g)| (work.uf.find(s), work.uf.find(g))) {
        Some((cs, cg)) if cs != cg => {
            let side = |i: usize| {
                let c = work.uf.find(i as u32);
                (c == cs, c == cg)
            };
            let (mut sum_s, mut sum_g) = (0.0, 0.0);
            for i in 0..work.node_count() {
                let w = ratio(i) + FOCUS_FLOOR;
                match side(i) {
                    (true, _) => sum_s += w,
                    (_, true) => sum_g += w,
                    _ => {}
                }
            }
            for i in 0..work.node_count() {
                let w = ratio(i) + FOCUS_FLOOR;
                total += match side(i) {
                    (true, _) => w / sum_s,
                    (_, true) => w / sum_g,
                    _ => 0.0,
                };
                cumulative.push(total);
            }
        }
        _ => {
            for i in 0..work.node_count() {
                total += ratio(i);
                cumulative.push(total);
            }
        }
    }
    (cumulative, total)
}

impl Learner<'_> {
    /// One expansion round of `size` walks: made in parallel against the roadmap as the round
    /// began, then applied in order.
    pub(super) fn expansion_round(
        &self,
        work: &mut Work<'_>,
        params: &LearnParams,
        budget: &Budget,
        deadline: &Deadline,
        focus: Option<(u32, u32)>,
        (seed, round, size): (u64, u64, usize),
    ) -> Result<(), LearnError> {
        let weights = walk_weights(work, focus);
        let sides = Sides::of(work, focus).filter(|_| params.directed_share > 0.0);
        let shared: &Work<'_> = work;
        let walks: Vec<(Result<Walk, OracleError>, CallCounts)> = (0..size as u64)
            .into_par_iter()
            .map(|i| {
                let mut rng = stream(seed, round, i, WALK_STREAM);
                let mut counts = CallCounts::default();
                let walk = match &sides {
                    Some(sides) if rng.random::<f64>() < params.directed_share => {
                        self.directed(shared, params, deadline, sides, &mut rng, &mut counts)
                    }
                    _ => self.walk(shared, params, deadline, &weights, &mut rng, &mut counts),
                };
                (walk, counts)
            })
            .collect();
        work.stopped = deadline.expired();
        apply_walks(work, params, budget, walks)
    }

    /// One directed walk of a pair-joining round: a uniform sample, the node of a random side
    /// nearest to it, a [`directed_walk`] from that node towards the sample, and attempts from
    /// the walk's end to its nearest nodes and to the other side's nearest nodes (RRT-Connect's
    /// connect, made by the local method).
    fn directed(
        &self,
        shared: &Work<'_>,
        params: &LearnParams,
        deadline: &Deadline,
        sides: &Sides,
        rng: &mut impl Rng,
        counts: &mut CallCounts,
    ) -> Result<Walk, OracleError> {
        let side = rng.random_range(0..2usize);
        let sample = self.space.sample_uniform(rng);
        let Some(&(from, _)) = sides.nearest(shared, side, &sample, 1).first() else {
            return self.no_walk(0);
        };
        if deadline.expired() {
            return self.no_walk(from);
        }
        let corners = directed_walk(
            self.space,
            self.oracle,
            &shared.groups,
            shared.node(from),
            &sample,
            DIRECTED_ROUNDS,
            counts,
            deadline,
        )?;
        let Some(end) = corners.last() else {
            return Ok(Walk {
                from,
                corners,
                attempts: Vec::new(),
            });
        };
        let mut near = shared.nearest(end, params.neighbours, params.radius);
        for (n, d) in sides.nearest(shared, 1 - side, end, OTHER_SIDE_TARGETS) {
            if !near.iter().any(|&(m, _)| m == n) {
                near.push((n, d));
            }
        }
        near.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        let attempts = self.attempts_from(shared, params, deadline, from, end, &near)?;
        Ok(Walk {
            from,
            corners,
            attempts,
        })
    }

    /// A walk that did not move (the deadline passed, or nothing to walk from).
    fn no_walk(&self, from: u32) -> Result<Walk, OracleError> {
        Ok(Walk {
            from,
            corners: Vec::new(),
            attempts: Vec::new(),
        })
    }

    /// Attempts from a walk's `end` to the nodes `near` (nearest first) outside the component
    /// of the node `from` the walk left.
    fn attempts_from(
        &self,
        shared: &Work<'_>,
        params: &LearnParams,
        deadline: &Deadline,
        from: u32,
        end: &[f64],
        near: &[(u32, f64)],
    ) -> Result<Vec<Attempt>, OracleError> {
        let targets: Vec<(Target, &[f64])> = near
            .iter()
            .map(|&(n, _)| (Target::Node(n), shared.node(n)))
            .collect();
        let component = |t: Target| match t {
            Target::Node(n) => Target::Node(shared.uf.find(n)),
            c => c,
        };
        let joined = vec![Target::Node(shared.uf.find(from))];
        self.attempts(
            end,
            &targets,
            joined,
            component,
            (params.cycle_edges, params.deep_neighbours),
            deadline,
        )
    }

    /// One walk: a node drawn by `(cumulative, total)` weight, a random-bounce walk from it, and
    /// attempts from the walk's end to its nearest nodes outside the node's component.
    fn walk(
        &self,
        shared: &Work<'_>,
        params: &LearnParams,
        deadline: &Deadline,
        (cumulative, total): &(Vec<f64>, f64),
        rng: &mut impl Rng,
        counts: &mut CallCounts,
    ) -> Result<Walk, OracleError> {
        let n_nodes = shared.node_count() as u32;
        let from = if *total > 0.0 {
            let u = rng.random::<f64>() * total;
            (cumulative.partition_point(|&c| c <= u) as u32).min(n_nodes - 1)
        } else {
            rng.random_range(0..n_nodes)
        };
        if deadline.expired() {
            return self.no_walk(from);
        }
        let corners = random_bounce(
            self.space,
            self.oracle,
            &shared.groups,
            shared.node(from),
            params.bounce_steps,
            rng,
            counts,
            deadline,
        )?;
        let attempts = match corners.last() {
            None => Vec::new(),
            Some(end) => {
                let near = shared.nearest(end, params.neighbours, params.radius);
                self.attempts_from(shared, params, deadline, from, end, &near)?
            }
        };
        Ok(Walk {
            from,
            corners,
            attempts,
        })
    }
}

/// Applies a round's walks in order, as far as the node budget lets them in: each walk's end
/// becomes a node (with its corners, see [`LearnParams::bounce_nodes`]) and its attempts are
/// applied.
fn apply_walks(
    work: &mut Work<'_>,
    params: &LearnParams,
    budget: &Budget,
    walks: Vec<(Result<Walk, OracleError>, CallCounts)>,
) -> Result<(), LearnError> {
    let mut stopped = false;
    for (walk, counts) in walks {
        work.counts += counts;
        if budget.nodes.is_some_and(|n| work.node_count() >= n) {
            stopped = true;
        }
        if stopped {
            if let Ok(walk) = walk {
                walk.attempts
                    .iter()
                    .for_each(|a| work.counts += a.connection.counts);
            }
            continue;
        }
        let walk = walk?;
        work.tries[walk.from as usize] += 1;
        let Some(last) = walk.corners.last() else {
            continue;
        };
        let end = if params.bounce_nodes {
            let mut prev = walk.from;
            for q in &walk.corners {
                let id = work.add_node(q);
                work.add_edge(prev, id, &[]);
                prev = id;
            }
            prev
        } else {
            let end = work.add_node(last);
            work.add_edge(walk.from, end, &walk.corners[..walk.corners.len() - 1]);
            end
        };
        for a in &walk.attempts {
            // walks only target nodes that existed when the round began
            if let Target::Node(target) = a.target {
                work.apply(end, target, &a.connection);
            }
        }
    }
    Ok(())
}
