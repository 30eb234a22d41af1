//! Answers kept: a certified path fed back into the roadmap (the query-time twin of CHS §1.6's
//! feedback; OMPL's PRM likewise keeps the start and goal of each `solve` as milestones). In a
//! workcell the next query mostly starts from the same home pose and often ends in the same
//! pocket, so an answer that took a search (or two trees) becomes graph the next one attaches
//! to with a direct path.

use super::super::graph::Roadmap;
use super::super::tree::Rooted;
use super::work::Work;
use crate::local::path_pieces;
use crate::space::Config;

impl Roadmap {
    /// A copy of the roadmap with `path` kept: every corner becomes a node (the existing node
    /// where the coordinates agree bit for bit), and each pair of consecutive corners is joined
    /// by its direct path in the DOF groups of the roadmap's local method, one single-group edge
    /// per piece, as learnt edges with feedback are ([`super::super::Edge`]); nodes and edges
    /// are added as the learner adds them. Existing nodes keep their indices; a pair
    /// of nodes already joined is not joined twice.
    ///
    /// `path` must be certified free in the roadmap's scene corner to corner (the answer of a
    /// query or of [`crate::roadmap::tree::rrt_connect`] on this scene): nothing is checked
    /// against an oracle here. Fails on a malformed path (a corner of the wrong dimension or not
    /// finite).
    pub fn with_path(&self, path: &[Config]) -> Result<Roadmap, String> {
        self.with_kept(path, &[])
    }

    /// [`Self::with_path`], and with it what `trees` grew ([`Rooted`], e.g. the trees of
    /// the query that found `path`, [`crate::roadmap::tree::TreeOutcome::trees`]): every extend's end
    /// becomes a node, joined to the end or given node it grew from by one edge through the
    /// corners between them; a given node a grown one hangs from is joined to the tree's end
    /// along its branch (a given node is a roadmap node or a corner of a roadmap edge, so the
    /// branch's corners become nodes as `path`'s do). The trees' nodes must be certified
    /// free branch by branch in the roadmap's scene; corners that no kept end hangs from are
    /// dropped.
    ///
    /// A tree that found its way into a pocket (a goal inside MotionBenchMaker's cage) covers
    /// the pocket around the goal; kept, the next goal in that pocket attaches to one of its
    /// ends with a direct path instead of growing trees of its own.
    pub fn with_kept(&self, path: &[Config], trees: &[&Rooted]) -> Result<Roadmap, String> {
        let dim = self.dim();
        let malformed = |q: &&[f64]| q.len() != dim || q.iter().any(|c| !c.is_finite());
        if let Some(bad) = path.iter().map(|q| q.as_slice()).find(malformed) {
            return Err(format!(
                "a corner of the kept path is not {dim} finite numbers: {bad:?}"
            ));
        }
        for tree in trees {
            if let Some(bad) = (0..tree.node_count() as u32)
                .map(|i| tree.node(i))
                .find(malformed)
            {
                return Err(format!(
                    "a node of the kept tree is not {dim} finite numbers: {bad:?}"
                ));
            }
        }
        let header = self.header();
        let groups = header.local_spec.build().groups(self.space());
        let mut work = Work::new(self.space(), groups, &header.params);
        work.copy_roadmap(self);
        for w in path.windows(2) {
            keep_segment(&mut work, &w[0], &w[1]);
        }
        for tree in trees {
            keep_tree(&mut work, tree);
        }
        Roadmap::assemble(header.clone(), work.coords, work.edges)
    }
}

/// Joins `a` and `z` by their direct path's single-group pieces, every corner a node.
fn keep_segment(work: &mut Work, a: &[f64], z: &[f64]) -> u32 {
    let from = work.add_node(a);
    keep_segment_from(work, from, a, z)
}

/// Keeps the ends `tree` grew ([`Roadmap::with_kept`]).
fn keep_tree(work: &mut Work, tree: &Rooted) {
    // roadmap node of each tree node kept so far (nodes come after their parents)
    let mut node_of: Vec<Option<u32>> = vec![None; tree.node_count()];
    let is_anchor = |i: u32| (i as usize) < tree.given() || !tree.is_corner(i);
    for v in tree.given() as u32..tree.node_count() as u32 {
        if tree.is_corner(v) {
            continue;
        }
        // up to the end or given node it hangs from, through the corners
        let mut chain = vec![v];
        let mut at = v;
        while let Some(p) = tree.parent(at) {
            chain.push(p);
            if is_anchor(p) {
                break;
            }
            at = p;
        }
        chain.reverse();
        let anchor = chain[0];
        let from = match node_of[anchor as usize] {
            Some(n) => n,
            None => keep_given(work, tree, anchor, &mut node_of),
        };
        // a tree edge is a single-group stair or a straight extend of several joints
        // ([`TreeParams::straight`](crate::roadmap::tree::TreeParams::straight)): the tree's
        // own motion, never the staircase between its ends ([`path_pieces`])
        let mut corners = Vec::new();
        for w in chain.windows(2) {
            let (a, z) = (tree.node(w[0]), tree.node(w[1]));
            corners.extend(
                path_pieces(work.space, &work.groups, a, z)
                    .into_iter()
                    .map(|(_, c)| c),
            );
        }
        corners.pop(); // `v` itself
        let to = work.add_node(tree.node(v));
        work.add_edge(from, to, &corners);
        node_of[v as usize] = Some(to);
    }
}

/// The roadmap node of the tree's given node `i` (or its end), joined to the end along its
/// branch, every corner a node; `node_of` learns every node of the branch.
fn keep_given(work: &mut Work, tree: &Rooted, i: u32, node_of: &mut [Option<u32>]) -> u32 {
    let mut branch = vec![i];
    let mut at = i;
    while let Some(p) = tree.parent(at) {
        if node_of[p as usize].is_some() {
            branch.push(p);
            break;
        }
        branch.push(p);
        at = p;
    }
    branch.reverse();
    let mut from = match node_of[branch[0] as usize] {
        Some(n) => n,
        None => work.add_node(tree.node(branch[0])),
    };
    node_of[branch[0] as usize] = Some(from);
    for w in branch.windows(2) {
        from = keep_segment_from(work, from, tree.node(w[0]), tree.node(w[1]));
        node_of[w[1] as usize] = Some(from);
    }
    from
}

/// [`keep_segment`] from the node `from` at `a`. The motion joining two corners of a kept
/// path is the path's own ([`path_pieces`]: in a joint space a straight shortcut of several
/// joints is one edge, not the staircase between its ends).
fn keep_segment_from(work: &mut Work, mut from: u32, a: &[f64], z: &[f64]) -> u32 {
    for (_, corner) in path_pieces(work.space, &work.groups, a, z) {
        let to = work.add_node(&corner);
        work.add_edge(from, to, &[]);
        from = to;
    }
    from
}

#[cfg(test)]
mod tests {
    use crate::bench::discs::DiscProblem;
    use crate::local::{LocalSpec, ViaPointOptions};
    use crate::roadmap::{Budget, LearnParams, Learner, Roadmap};

    /// A 30-node roadmap of a disc problem whose local method moves one axis at a time (so
    /// that a diagonal step is two edges, and a tree's stair two pieces), with that method.
    fn split_axes_roadmap() -> (DiscProblem, Box<dyn crate::local::LocalMethod>, Roadmap) {
        let space = DiscProblem::space();
        let problem = crate::bench::discs::problem(3, 0, 0.05);
        let LocalSpec::ViaPoint(options) = LocalSpec::roadmap_default() else {
            unreachable!("the roadmap default is the via-point planner")
        };
        let local = LocalSpec::ViaPoint(ViaPointOptions {
            split_axes: true,
            ..options
        })
        .build();
        let base = Learner::new(&space, &problem.oracle(), local.as_ref(), 0)
            .learn(&LearnParams::default(), &Budget::nodes(30), 1, &mut |_| {})
            .unwrap()
            .roadmap;
        (problem, local, base)
    }

    #[test]
    fn a_kept_path_joins_its_corners_with_single_group_edges() {
        let (_, _, base) = split_axes_roadmap();
        let (n, e) = (base.node_count(), base.edge_count());
        let first = base.node(0).to_vec();
        // three new corners, then an existing node
        let path = vec![
            vec![0.01, 0.02],
            vec![0.01, 0.03],
            vec![0.4, 0.5],
            first.clone(),
        ];
        let kept = base.with_path(&path).unwrap();
        // the three new corners, one stair corner on the way to [0.4, 0.5] and one on the way
        // to the node (which shares no coordinate with it): five nodes, five one-axis edges
        assert!(first.iter().zip([0.4, 0.5]).all(|(a, b)| *a != b));
        assert_eq!(kept.node_count(), n + 5);
        assert_eq!(kept.edge_count(), e + 5);
        for edge in &kept.edges()[e..] {
            let (a, b) = (kept.node(edge.a), kept.node(edge.b));
            let changed = (0..2).filter(|&i| a[i] != b[i]).count();
            assert_eq!(changed, 1, "each kept edge changes one coordinate");
        }
        assert_eq!(
            kept.component(n as u32),
            kept.component(0),
            "the path's start is joined to the node it ends at"
        );
        assert_eq!(&kept.coords()[..base.coords().len()], base.coords());
        assert!(base.with_path(&[vec![0.1, f64::NAN]]).is_err());
        assert!(base.with_path(&[vec![0.1]]).is_err());
    }

    #[test]
    fn kept_trees_bring_their_ends_joined_by_single_group_corners() {
        use crate::deadline::Deadline;
        use crate::roadmap::tree::{rrt_connect, TreeParams};
        let (problem, local, base) = split_axes_roadmap();
        let (space, oracle) = (DiscProblem::space(), problem.oracle());
        // one group per axis: each stair is two pieces, so that edges have corners
        let groups = local.groups(&space);
        assert_eq!(groups.len(), 2);
        let params = TreeParams {
            max_nodes: Some(400),
            ..TreeParams::default()
        };
        let (start, goal) = (vec![0.02, 0.03], vec![0.97, 0.95]);
        let found = rrt_connect(
            &space,
            &oracle,
            &groups,
            &start,
            &goal,
            &params,
            7,
            &Deadline::none(),
        )
        .unwrap();
        let trees = found.trees.expect("trees grew");
        let kept = base.with_kept(&[], &[&trees[0], &trees[1]]).unwrap();
        assert_eq!(&kept.coords()[..base.coords().len()], base.coords());
        // every end and every extend's end is a node, each in its tree's end's component
        let node_at = |q: &[f64]| {
            (0..kept.node_count() as u32)
                .find(|&i| kept.node(i) == q)
                .unwrap_or_else(|| panic!("{q:?} kept"))
        };
        let mut ends = std::collections::HashSet::new();
        for tree in trees.iter() {
            let root = node_at(tree.end());
            for i in 0..tree.node_count() as u32 {
                if !tree.is_corner(i) {
                    ends.insert(tree.node(i).iter().map(|c| c.to_bits()).collect::<Vec<_>>());
                    assert_eq!(kept.component(node_at(tree.node(i))), kept.component(root));
                }
            }
        }
        assert!(ends.len() > 2, "the trees grew ends");
        assert_eq!(
            kept.node_count(),
            base.node_count() + ends.len(),
            "corners stay on edges"
        );
        // each edge's corners change one group at a time, and lie on the trees' branches
        let mut through_corners = 0;
        for (e, edge) in kept.edges().iter().enumerate().skip(base.edge_count()) {
            let path = kept.edge_path(e, edge.a);
            through_corners += usize::from(path.len() > 2);
            for w in path.windows(2) {
                let changed = (0..2).filter(|&i| w[0][i] != w[1][i]).count();
                assert_eq!(changed, 1, "edge {e}: {path:?}");
            }
        }
        assert!(
            through_corners > 0,
            "whole stairs keep their corners on edges"
        );
        let mut bad = trees[0].clone();
        bad.add(vec![f64::NAN, 0.5], 0);
        assert!(base.with_kept(&[], &[&bad]).is_err());
    }
}
