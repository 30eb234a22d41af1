//! Growing the two trees of [`viaroad::roadmap::tree`] for a scene's first query, as the tree
//! tests do it: no deadline, so a node budget in `params` makes the outcome the same everywhere.

use viaroad::deadline::Deadline;
use viaroad::roadmap::tree::{rrt_connect, TreeOutcome, TreeParams};
use viaroad::scene::Scene;

/// The two trees from the first query's start and goal of `scene`, grown with `params` and
/// `seed`.
pub fn grow(scene: &Scene, params: &TreeParams, seed: u64) -> TreeOutcome {
    let oracle = scene.oracle();
    let groups = scene.space.groups(false);
    let q = &scene.checked_queries().unwrap()[0];
    rrt_connect(
        &scene.space,
        oracle.as_ref(),
        &groups,
        &q.start,
        &q.goal,
        params,
        seed,
        &Deadline::none(),
    )
    .unwrap()
}
