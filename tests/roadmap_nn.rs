//! The nearest-neighbour index against brute force.

use proptest::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use viaroad::roadmap::{KdTree, NearestNeighbours};
use viaroad::space::Space;

/// All points within `max_dist`, sorted by (squared distance, id, index): the order the tree
/// promises.
fn brute_force(
    points: &[Vec<f64>],
    ids: &[u32],
    q: &[f64],
    k: usize,
    max_dist: f64,
) -> Vec<(f64, u32)> {
    let mut all: Vec<(f64, u32, usize)> = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let d2: f64 = p.iter().zip(q).map(|(a, b)| (a - b) * (a - b)).sum();
            (d2, ids[i], i)
        })
        .filter(|(d2, _, _)| d2.sqrt() <= max_dist)
        .collect();
    all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    all.truncate(k);
    all.into_iter().map(|(d2, id, _)| (d2.sqrt(), id)).collect()
}

fn arb_cloud() -> impl Strategy<Value = (usize, Vec<Vec<f64>>, Vec<f64>)> {
    (1usize..=7).prop_flat_map(|dim| {
        // coordinates on a coarse grid so that ties and duplicate points are common
        let coord = prop_oneof![(0i32..6).prop_map(|v| v as f64 * 0.5), -3.0f64..3.0];
        (
            Just(dim),
            prop::collection::vec(prop::collection::vec(coord.clone(), dim), 0..200),
            prop::collection::vec(coord, dim),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 200,
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn kd_tree_matches_brute_force(
        (dim, points, q) in arb_cloud(),
        k in 0usize..25,
        radius in prop_oneof![Just(f64::INFINITY), 0.0f64..4.0],
        shared_ids in any::<bool>(),
    ) {
        let ids: Vec<u32> = (0..points.len() as u32)
            .map(|i| if shared_ids { i / 2 } else { i })
            .collect();
        let mut tree = KdTree::new(dim);
        for (p, &id) in points.iter().zip(&ids) {
            tree.insert(p, id);
        }
        prop_assert_eq!(tree.len(), points.len());
        let got = tree.nearest(&q, k, radius);
        let want = brute_force(&points, &ids, &q, k, radius);
        prop_assert_eq!(got, want);
        // the single nearest, by distance then id
        let one = tree.nearest_one(&q);
        let want_one = points
            .iter()
            .zip(&ids)
            .map(|(p, &id)| {
                let d2: f64 = p.iter().zip(&q).map(|(a, b)| (a - b) * (a - b)).sum();
                (d2.sqrt(), id)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        prop_assert_eq!(one, want_one);
    }

    /// An arm's joint space without continuous joints is its own embedding: the index is
    /// exact there as in R^n, and the single nearest node is the brute force's, ties by id
    /// (coordinates on a grid make ties common).
    #[test]
    fn joint_space_index_is_exact(
        points in prop::collection::vec(prop::collection::vec((0i32..5).prop_map(|v| v as f64 * 0.25), 7), 1..150),
        q in prop::collection::vec(0.0f64..1.0, 7),
        k in 1usize..12,
    ) {
        let space = Space::joints(vec![0.0; 7], vec![1.0; 7], &[false; 7]).unwrap();
        prop_assert!(space.embedding_is_identity());
        let mut nn = NearestNeighbours::new(&space);
        for (i, p) in points.iter().enumerate() {
            nn.insert(i as u32, p);
        }
        let mut want: Vec<(u32, f64)> = points
            .iter()
            .enumerate()
            .map(|(i, p)| (i as u32, space.distance(&q, p)))
            .collect();
        want.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        prop_assert_eq!(nn.nearest_one(&q, |i| &points[i as usize]), Some(want[0]));
        want.truncate(k);
        prop_assert_eq!(nn.nearest(&q, k, None, |i| &points[i as usize]), want);
    }

    /// In R^n the index is exact: the k nearest nodes by the space's distance, ties by id.
    #[test]
    fn rn_index_is_exact(
        points in prop::collection::vec(prop::collection::vec(0.0f64..1.0, 3), 1..300),
        q in prop::collection::vec(0.0f64..1.0, 3),
        k in 1usize..20,
        radius in prop_oneof![Just(None), (0.05f64..0.8).prop_map(Some)],
    ) {
        let space = Space::euclidean(vec![0.0; 3], vec![1.0; 3]).unwrap();
        let mut nn = NearestNeighbours::new(&space);
        for (i, p) in points.iter().enumerate() {
            nn.insert(i as u32, p);
        }
        prop_assert_eq!(nn.len(), points.len());
        let got = nn.nearest(&q, k, radius, |i| &points[i as usize]);
        let mut want: Vec<(u32, f64)> = points
            .iter()
            .enumerate()
            .map(|(i, p)| (i as u32, space.distance(&q, p)))
            .filter(|&(_, d)| radius.is_none_or(|r| d <= r))
            .collect();
        want.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        want.truncate(k);
        prop_assert_eq!(got, want);
    }
}

fn rigid_clouds() -> Vec<(Space, Vec<Vec<f64>>)> {
    let se2 = Space::se2([0.0; 2], [4.0; 2], 0.7).unwrap();
    let se3 = Space::se3([0.0; 3], [4.0; 3], 0.7).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    [se2, se3]
        .into_iter()
        .map(|s| {
            let pts = (0..1500).map(|_| s.sample_uniform(&mut rng)).collect();
            (s, pts)
        })
        .collect()
}

/// With k at least the number of nodes, a radius query returns exactly the nodes within the
/// radius (the embeddings never overestimate the distance), sorted.
#[test]
fn rigid_radius_queries_are_complete() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for (space, pts) in rigid_clouds() {
        let mut nn = NearestNeighbours::new(&space);
        for (i, p) in pts.iter().enumerate() {
            nn.insert(i as u32, p);
        }
        let mut found = 0;
        for _ in 0..50 {
            let q = space.sample_uniform(&mut rng);
            let r = 2.0;
            let got: Vec<u32> = nn
                .nearest(&q, pts.len(), Some(r), |i| &pts[i as usize])
                .into_iter()
                .map(|(i, _)| i)
                .collect();
            let mut want: Vec<(u32, f64)> = pts
                .iter()
                .enumerate()
                .map(|(i, p)| (i as u32, space.distance(&q, p)))
                .filter(|&(_, d)| d <= r)
                .collect();
            want.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
            let want: Vec<u32> = want.into_iter().map(|(i, _)| i).collect();
            found += want.len();
            assert_eq!(got, want, "{:?}", space.kind());
        }
        assert!(
            found > 100,
            "{:?}: only {found} nodes within the radius",
            space.kind()
        );
    }
}

/// For SE(2) and SE(3) the k nearest are re-ranked from embedded candidates and completed by
/// a second search where the first stopped short: exactly the brute-force k nearest, with and
/// without a radius, for several k.
#[test]
fn rigid_k_nearest_are_exact() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for (space, pts) in rigid_clouds() {
        let mut nn = NearestNeighbours::new(&space);
        for (i, p) in pts.iter().enumerate() {
            nn.insert(i as u32, p);
        }
        for trial in 0..300 {
            let q = space.sample_uniform(&mut rng);
            let k = [1, 5, 10, 30][trial % 4];
            let radius = (trial % 3 == 0).then_some(0.8);
            let got = nn.nearest(&q, k, radius, |i| &pts[i as usize]);
            let mut want: Vec<(u32, f64)> = pts
                .iter()
                .enumerate()
                .map(|(i, p)| (i as u32, space.distance(&q, p)))
                .filter(|&(_, d)| radius.is_none_or(|r| d <= r))
                .collect();
            want.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
            want.truncate(k);
            assert_eq!(got, want, "{:?}, k = {k}, radius {radius:?}", space.kind());
        }
    }
}

/// A joint space with a continuous joint is not its own embedding (the joint enters as a
/// point on the circle): the single nearest node still comes out as the brute force's.
#[test]
fn continuous_joints_nearest_one_is_exact() {
    let space = Space::joints(vec![-1.0; 3], vec![1.0; 3], &[false, true, false]).unwrap();
    assert!(!space.embedding_is_identity());
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let pts: Vec<Vec<f64>> = (0..400).map(|_| space.sample_uniform(&mut rng)).collect();
    let mut nn = NearestNeighbours::new(&space);
    for (i, p) in pts.iter().enumerate() {
        nn.insert(i as u32, p);
    }
    for _ in 0..200 {
        let q = space.sample_uniform(&mut rng);
        let want = pts
            .iter()
            .enumerate()
            .map(|(i, p)| (i as u32, space.distance(&q, p)))
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        assert_eq!(nn.nearest_one(&q, |i| &pts[i as usize]), want);
    }
}

/// SE(3): `q` and `−q` are the same orientation; the index finds a node given either.
#[test]
fn se3_antipodal_quaternions_are_the_same_node() {
    let space = Space::se3([0.0; 3], [1.0; 3], 1.0).unwrap();
    let a = vec![0.5, 0.5, 0.5, 0.0, 0.0, 0.6, 0.8];
    let b = vec![0.5, 0.5, 0.5, 0.0, 0.0, -0.6, -0.8];
    let far = vec![0.5, 0.5, 0.5, 0.0, 0.6, 0.0, 0.8];
    let pts = [far.clone(), a.clone()];
    let mut nn = NearestNeighbours::new(&space);
    nn.insert(0, &far);
    nn.insert(1, &a);
    assert_eq!(nn.len(), 2);
    let got = nn.nearest(&b, 1, None, |i| &pts[i as usize]);
    assert_eq!(got[0].0, 1);
    assert!(got[0].1 < 1e-12);
}
