//! The searchable graph of Brooks §4.1 and A* over it.
//!
//! Nodes are points on spines — the intersections, plus the feet where start and goal join —
//! each split by the connected intervals of orientations legal there ("a node for each
//! interval in V(t)"). Arcs: along a spine to the next point, at an orientation legal over the
//! whole stretch (the move keeps it); between the two cones of an intersection, when their
//! intervals meet (a rotation into the common part). A* minimises the distance travelled by
//! the reference point, with the straight distance to the goal as its estimate.

use super::cone::P;
use super::freeways::Freeways;
use super::outcome::{ConeError, ConeOutcome, ConePath};
use super::radius::{AngleSet, Arc};
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle};
use crate::scene::Scene;
use crate::space::Config;
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::f64::consts::FRAC_PI_2;

/// Where start or goal joins a spine: a straight move to the foot, then (SE(2)) a rotation
/// into one of the foot's intervals, both checked by the oracle.
#[derive(Clone, Copy, Debug)]
struct Attach {
    node: usize,
    arc: usize,
    dist: f64,
    /// The orientation turned to at the foot, when the endpoint's own is not in the interval.
    turn: Option<f64>,
}

struct Node {
    cone: usize,
    s: f64,
    point: P,
    arcs: Vec<Arc>,
    /// The same intersection on the other cone.
    partner: Option<usize>,
    /// Neighbours along the spine (previous, next).
    prev: Option<usize>,
    next: Option<usize>,
}

#[derive(Clone, Copy, Debug)]
enum Move {
    Along(f64),
    Switch(f64),
    ToGoal(usize),
}

#[derive(PartialEq)]
struct Entry(f64, usize);
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Entry {
    fn cmp(&self, o: &Self) -> Ordering {
        // a min-heap on the estimate, ties by state for determinism
        o.0.total_cmp(&self.0).then(o.1.cmp(&self.1))
    }
}

/// Nearest cones tried when joining an endpoint, and joins kept.
const ATTACH_TRIES: usize = 24;
const ATTACH_KEEP: usize = 8;

fn dist(a: P, b: P) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// A configuration at `p` with orientation `phi` (dropped in R²).
fn config(fw: &Freeways, p: P, phi: f64) -> Config {
    if fw.oriented {
        vec![p[0], p[1], phi]
    } else {
        vec![p[0], p[1]]
    }
}

fn attach(
    fw: &Freeways,
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    q: &[f64],
    nodes: &mut Vec<Node>,
    counts: &mut CallCounts,
) -> Result<Vec<Attach>, ConeError> {
    let x = [q[0], q[1]];
    let phi = if fw.oriented { q[2] } else { 0.0 };
    let mut feet: Vec<(f64, usize, f64)> = fw
        .cones
        .iter()
        .enumerate()
        .map(|(c, cone)| {
            let s = cone.param(x).clamp(cone.lo, cone.hi);
            (dist(x, cone.point(s)), c, s)
        })
        .collect();
    feet.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut out = Vec::new();
    for &(d, c, s) in feet.iter().take(ATTACH_TRIES) {
        if out.len() >= ATTACH_KEEP {
            break;
        }
        let cone = &fw.cones[c];
        let foot = cone.point(s);
        let at_foot = config(fw, foot, phi);
        let Some(m) = scene.space.direct_motion(q, &at_foot) else {
            continue;
        };
        if !oracle.check_motion(&m, counts)? {
            continue;
        }
        let arcs = fw.legal(cone, s, s).arcs();
        let node = nodes.len();
        let mut joined = false;
        for (k, a) in arcs.iter().enumerate() {
            let turn = if !fw.oriented || a.contains(phi) {
                None
            } else {
                let turned = config(fw, foot, a.mid());
                match scene.space.direct_motion(&at_foot, &turned) {
                    Some(m) if oracle.check_motion(&m, counts)? => Some(a.mid()),
                    _ => continue,
                }
            };
            out.push(Attach {
                node,
                arc: k,
                dist: d,
                turn,
            });
            joined = true;
        }
        if joined {
            nodes.push(Node {
                cone: c,
                s,
                point: foot,
                arcs,
                partner: None,
                prev: None,
                next: None,
            });
        }
    }
    Ok(out)
}

/// Turns at `p` from `from` by `turn`, in steps of at most a quarter turn (so that the
/// shorter-way interpolation of consecutive configurations follows the turn).
fn rotate(fw: &Freeways, path: &mut Vec<Config>, p: P, from: f64, turn: f64) {
    if !fw.oriented || turn == 0.0 {
        return;
    }
    let n = (turn.abs() / FRAC_PI_2).ceil().max(1.0) as usize;
    for i in 1..=n {
        path.push(config(fw, p, from + turn * i as f64 / n as f64));
    }
}

/// A* along the freeways from `start` to `goal`, joined to them by straight moves; the path is
/// re-checked by the exact oracle before it is returned.
pub(super) fn solve(
    fw: &Freeways,
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    start: &[f64],
    goal: &[f64],
) -> Result<ConeOutcome, ConeError> {
    let mut counts = CallCounts::default();
    let mut nodes = crossing_nodes(fw);
    let starts = attach(fw, scene, oracle, start, &mut nodes, &mut counts)?;
    if starts.is_empty() {
        return Ok(ConeOutcome::NotFound(
            "the start reaches no freeway by a straight move".into(),
        ));
    }
    let goals = attach(fw, scene, oracle, goal, &mut nodes, &mut counts)?;
    if goals.is_empty() {
        return Ok(ConeOutcome::NotFound(
            "the goal reaches no freeway by a straight move".into(),
        ));
    }
    let graph = Graph::new(fw, nodes);
    let search = graph.a_star(fw, &starts, &goals, [goal[0], goal[1]]);
    if !search.done[graph.goal_state] {
        return Ok(ConeOutcome::NotFound(format!(
            "no path along the freeways ({} cones, {} intersections, {} states expanded)",
            fw.cones.len(),
            fw.crossings.len(),
            search.expanded
        )));
    }
    let (mut path, cones) = graph.path(fw, &search, &starts, &goals, start, goal);
    for q in &mut path {
        scene.space.normalize(q);
    }
    path.dedup();
    if let Some(failed) = recheck(scene, oracle, &path, &mut counts)? {
        return Ok(failed);
    }
    let length = path
        .windows(2)
        .map(|w| scene.space.distance(&w[0], &w[1]))
        .sum();
    Ok(ConeOutcome::Solved(ConePath {
        path,
        length,
        cones,
        expanded: search.expanded,
    }))
}

/// The two nodes of each intersection, one on each cone, partners of each other.
fn crossing_nodes(fw: &Freeways) -> Vec<Node> {
    let mut nodes: Vec<Node> = Vec::with_capacity(2 * fw.crossings.len() + 16);
    for cr in &fw.crossings {
        for (c, s) in [(cr.a, cr.sa), (cr.b, cr.sb)] {
            let cone = &fw.cones[c];
            nodes.push(Node {
                cone: c,
                s,
                point: cone.point(s),
                arcs: fw.legal(cone, s, s).arcs(),
                partner: None,
                prev: None,
                next: None,
            });
        }
        let n = nodes.len();
        nodes[n - 2].partner = Some(n - 1);
        nodes[n - 1].partner = Some(n - 2);
    }
    nodes
}

/// The nodes with their neighbours along each spine, and the states of A* — one per node and
/// interval, numbered node by node, then the goal's.
struct Graph {
    nodes: Vec<Node>,
    /// The first state of each node, then the number of states (the goal's state).
    offset: Vec<usize>,
    goal_state: usize,
}

/// What A* leaves for the path to be read back: the best move into each state, the start join
/// of the states reached straight from a start, the settled states and how many were expanded.
struct Search {
    prev: Vec<Option<(usize, Move)>>,
    first: Vec<Option<usize>>,
    done: Vec<bool>,
    expanded: usize,
}

impl Graph {
    /// Links each node to its neighbours along its spine and numbers the states.
    fn new(fw: &Freeways, mut nodes: Vec<Node>) -> Graph {
        let mut per_cone: Vec<Vec<usize>> = vec![Vec::new(); fw.cones.len()];
        for (i, n) in nodes.iter().enumerate() {
            per_cone[n.cone].push(i);
        }
        for list in &mut per_cone {
            list.sort_by(|&a, &b| nodes[a].s.total_cmp(&nodes[b].s).then(a.cmp(&b)));
            for w in list.windows(2) {
                nodes[w[0]].next = Some(w[1]);
                nodes[w[1]].prev = Some(w[0]);
            }
        }
        let mut offset = Vec::with_capacity(nodes.len() + 1);
        let mut total = 0;
        for n in &nodes {
            offset.push(total);
            total += n.arcs.len();
        }
        offset.push(total);
        Graph {
            nodes,
            offset,
            goal_state: total,
        }
    }

    /// The node a state belongs to.
    fn node_of(&self, state: usize) -> usize {
        self.offset.partition_point(|&o| o <= state) - 1
    }

    /// A* from the start joins to the goal state, reached from the goal joins.
    fn a_star(&self, fw: &Freeways, starts: &[Attach], goals: &[Attach], gx: P) -> Search {
        let (nodes, offset, goal_state) = (&self.nodes, &self.offset, self.goal_state);
        let total = goal_state;
        let mut goal_join: Vec<Option<usize>> = vec![None; total];
        for (k, g) in goals.iter().enumerate() {
            let st = offset[g.node] + g.arc;
            if goal_join[st].is_none_or(|j| goals[j].dist > g.dist) {
                goal_join[st] = Some(k);
            }
        }
        let h = |state: usize| {
            if state == goal_state {
                0.0
            } else {
                dist(nodes[self.node_of(state)].point, gx)
            }
        };
        let mut g = vec![f64::INFINITY; total + 1];
        let mut prev: Vec<Option<(usize, Move)>> = vec![None; total + 1];
        let mut first: Vec<Option<usize>> = vec![None; total + 1];
        let mut heap = BinaryHeap::new();
        for (k, a) in starts.iter().enumerate() {
            let st = offset[a.node] + a.arc;
            if a.dist < g[st] {
                g[st] = a.dist;
                first[st] = Some(k);
                heap.push(Entry(a.dist + h(st), st));
            }
        }
        let mut expanded = 0;
        let mut done = vec![false; total + 1];
        while let Some(Entry(_, st)) = heap.pop() {
            if done[st] {
                continue;
            }
            done[st] = true;
            if st == goal_state {
                break;
            }
            expanded += 1;
            let ni = self.node_of(st);
            let node = &nodes[ni];
            let arc = node.arcs[st - offset[ni]];
            let mut relax = |to: usize, cost: f64, mv: Move, heap: &mut BinaryHeap<Entry>| {
                let c = g[st] + cost;
                if c < g[to] {
                    g[to] = c;
                    prev[to] = Some((st, mv));
                    heap.push(Entry(c + h(to), to));
                }
            };
            let cone = &fw.cones[node.cone];
            for nb in [node.prev, node.next].into_iter().flatten() {
                let other = &nodes[nb];
                for j in fw.legal(cone, node.s, other.s).arcs() {
                    let phi = j.mid();
                    if !arc.contains(phi) {
                        continue;
                    }
                    if let Some(k) = other.arcs.iter().position(|a| a.contains(phi)) {
                        relax(
                            offset[nb] + k,
                            (other.s - node.s).abs(),
                            Move::Along(phi),
                            &mut heap,
                        );
                    }
                }
            }
            if let Some(p) = node.partner {
                let here = AngleSet::arc(arc.lo, arc.len);
                for (k, a) in nodes[p].arcs.iter().enumerate() {
                    if let Some(common) = here
                        .intersection(&AngleSet::arc(a.lo, a.len))
                        .arcs()
                        .first()
                    {
                        relax(offset[p] + k, 0.0, Move::Switch(common.mid()), &mut heap);
                    }
                }
            }
            if let Some(k) = goal_join[st] {
                relax(goal_state, goals[k].dist, Move::ToGoal(k), &mut heap);
            }
        }
        Search {
            prev,
            first,
            done,
            expanded,
        }
    }

    /// The configurations of the path A* found (start, the moves along and between spines with
    /// the turns they need, goal), and the cones it follows in turn.
    fn path(
        &self,
        fw: &Freeways,
        search: &Search,
        starts: &[Attach],
        goals: &[Attach],
        start: &[f64],
        goal: &[f64],
    ) -> (Vec<Config>, Vec<usize>) {
        let (nodes, offset, goal_state) = (&self.nodes, &self.offset, self.goal_state);
        // the chain of states back to a start join
        let mut chain = Vec::new();
        let mut at = goal_state;
        while let Some((p, mv)) = search.prev[at] {
            chain.push((p, mv));
            at = p;
        }
        chain.reverse();
        let join = starts[search.first[at].expect("a chain starts at a start join")];
        let mut path: Vec<Config> = vec![start.to_vec()];
        let mut phi = if fw.oriented { start[2] } else { 0.0 };
        let foot = nodes[join.node].point;
        path.push(config(fw, foot, phi));
        if let Some(t) = join.turn {
            path.push(config(fw, foot, t));
            phi = t;
        }
        let mut cones = vec![nodes[join.node].cone];
        for (i, &(st, mv)) in chain.iter().enumerate() {
            let ni = self.node_of(st);
            let arc = nodes[ni].arcs[st - offset[ni]];
            let p = nodes[ni].point;
            match mv {
                Move::Along(to) => {
                    rotate(fw, &mut path, p, phi, arc.turn_within(phi, to));
                    phi = to;
                    let next = chain.get(i + 1).map_or(goal_state, |c| c.0);
                    let nn = self.node_of(next);
                    path.push(config(fw, nodes[nn].point, phi));
                }
                Move::Switch(to) => {
                    rotate(fw, &mut path, p, phi, arc.turn_within(phi, to));
                    phi = to;
                    let next = chain.get(i + 1).map_or(goal_state, |c| c.0);
                    let c = nodes[self.node_of(next)].cone;
                    if cones.last() != Some(&c) {
                        cones.push(c);
                    }
                }
                Move::ToGoal(k) => {
                    let gj = goals[k];
                    let gphi = if fw.oriented { goal[2] } else { 0.0 };
                    match gj.turn {
                        Some(t) => {
                            rotate(fw, &mut path, p, phi, arc.turn_within(phi, t));
                            path.push(config(fw, p, gphi));
                        }
                        None => rotate(fw, &mut path, p, phi, arc.turn_within(phi, gphi)),
                    }
                    path.push(goal.to_vec());
                }
            }
        }
        (path, cones)
    }
}

/// The exact oracle's re-check of the path, motion by motion: the freeways are built from an
/// approximation of the free space. The outcome to report when a motion fails.
fn recheck(
    scene: &Scene,
    oracle: &dyn CollisionOracle,
    path: &[Config],
    counts: &mut CallCounts,
) -> Result<Option<ConeOutcome>, ConeError> {
    for (k, w) in path.windows(2).enumerate() {
        let free = match scene.space.direct_motion(&w[0], &w[1]) {
            Some(m) => oracle.check_motion(&m, counts)?,
            None => false,
        };
        if !free {
            return Ok(Some(ConeOutcome::NotFound(format!(
                "the freeway path failed the oracle's re-check at motion {} of {}",
                k + 1,
                path.len() - 1
            ))));
        }
    }
    Ok(None)
}
