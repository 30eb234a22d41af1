//! Answers kept: a certified path fed back into the roadmap (the query-time twin of CHS §1.6's
//! feedback; OMPL's PRM likewise keeps the start and goal of each `solve` as milestones). In a
//! workcell the next query mostly starts from the same home pose and often ends in the same
//! pocket, so an answer that took a search (or two trees) becomes graph the next one attaches
//! to with a direct path.

use super::graph::{Edge, Roadmap};
use crate::local::{direct_length, direct_pieces};
use crate::space::Config;
use std::collections::{HashMap, HashSet};

impl Roadmap {
    /// A copy of the roadmap with `path` kept: every corner becomes a node (the existing node
    /// where the coordinates agree bit for bit), and each pair of consecutive corners is joined
    /// by its direct path in the DOF groups of the roadmap's local method, one single-group edge
    /// per piece, as learnt edges with feedback are ([`Edge`]). Existing nodes keep their
    /// indices; an edge between nodes already joined directly is not added twice.
    ///
    /// `path` must be certified free in the roadmap's scene corner to corner (the answer of a
    /// query or of [`super::tree::rrt_connect`] on this scene): nothing is checked against an
    /// oracle here. Fails on a malformed path (a corner of the wrong dimension or not finite).
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
        let space = self.space();
        let groups = self.header().local_spec.build().groups(space);
        let mut coords = self.coords().to_vec();
        let mut edges = self.edges().to_vec();
        let key = |q: &[f64]| q.iter().map(|v| v.to_bits()).collect::<Vec<u64>>();
        let mut by_bits: HashMap<Vec<u64>, u32> = self
            .nodes()
            .enumerate()
            .map(|(i, q)| (key(q), i as u32))
            .collect();
        let mut joined: HashSet<(u32, u32)> = edges
            .iter()
            .filter(|e| e.corners.is_empty())
            .map(|e| (e.a.min(e.b), e.a.max(e.b)))
            .collect();
        let mut node = |q: &[f64], coords: &mut Vec<f64>| -> u32 {
            *by_bits.entry(key(q)).or_insert_with(|| {
                coords.extend_from_slice(q);
                (coords.len() / dim - 1) as u32
            })
        };
        for w in path.windows(2) {
            let mut from = node(&w[0], &mut coords);
            let mut at = w[0].clone();
            for (_, corner) in direct_pieces(space, &groups, 0, &w[0], &w[1]) {
                let to = node(&corner, &mut coords);
                if from != to && joined.insert((from.min(to), from.max(to))) {
                    edges.push(Edge {
                        a: from,
                        b: to,
                        length: direct_length(space, &groups, &at, &corner),
                        corners: Vec::new(),
                    });
                }
                (from, at) = (to, corner);
            }
        }
        Roadmap::assemble(self.header().clone(), coords, edges)
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
