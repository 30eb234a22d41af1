//! Answers kept: a certified path fed back into the roadmap (the query-time twin of CHS §1.6's
//! feedback; OMPL's PRM likewise keeps the start and goal of each `solve` as milestones). In a
//! workcell the next query mostly starts from the same home pose and often ends in the same
//! pocket, so an answer that took a search (or two trees) becomes graph the next one attaches
//! to with a direct path.

use super::super::graph::Roadmap;
use super::work::Work;
use crate::local::direct_pieces;
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
        let dim = self.dim();
        if let Some(bad) = path
            .iter()
            .find(|q| q.len() != dim || q.iter().any(|c| !c.is_finite()))
        {
            return Err(format!(
                "a corner of the kept path is not {dim} finite numbers: {bad:?}"
            ));
        }
        let header = self.header();
        let groups = header.local_spec.build().groups(self.space());
        let mut work = Work::new(self.space(), groups, &header.params);
        work.copy_roadmap(self);
        for w in path.windows(2) {
            let mut from = work.add_node(&w[0]);
            for (_, corner) in direct_pieces(work.space, &work.groups, 0, &w[0], &w[1]) {
                let to = work.add_node(&corner);
                work.add_edge(from, to, &[]);
                from = to;
            }
        }
        Roadmap::assemble(header.clone(), work.coords, work.edges)
    }
}

#[cfg(test)]
mod tests {
    use crate::bench::discs::DiscProblem;
    use crate::local::{LocalSpec, ViaPointOptions};
    use crate::roadmap::{Budget, LearnParams, Learner};

    #[test]
    fn a_kept_path_joins_its_corners_with_single_group_edges() {
        let space = DiscProblem::space();
        let problem = crate::bench::discs::problem(3, 0, 0.05);
        let oracle = problem.oracle();
        // one group per axis, so that a diagonal step of the path is two edges
        let LocalSpec::ViaPoint(options) = LocalSpec::roadmap_default() else {
            unreachable!("the roadmap default is the via-point planner")
        };
        let local = LocalSpec::ViaPoint(ViaPointOptions {
            split_axes: true,
            ..options
        })
        .build();
        let learner = Learner::new(&space, &oracle, local.as_ref(), 0);
        let base = learner
            .learn(&LearnParams::default(), &Budget::nodes(30), 1, &mut |_| {})
            .unwrap()
            .roadmap;
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
}
