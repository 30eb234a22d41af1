//! How fast a straight joint motion can move each link's points: per joint, a bound on the
//! distance of the link's points from the joint's axis that holds in every configuration
//! (Schwarzer, Saha and Latombe's `R_kl`), built once per arm for the straight-motion proofs.

use crate::geometry::TriMesh;
use crate::robot::kinematics::Model;
use crate::robot::urdf::JointKind;

/// Per link, the movable joints between the root and it with the factor that turns the
/// joint's rate into a bound on the speed of the link's points (`R_kl`; 1 for a prismatic
/// joint). Empty for a link without geometry.
pub(super) type Reach = Vec<Vec<(usize, f64)>>;

/// [`Reach`] of every link of `model`'s arm (`link_meshes` in the link frames, `None` for a
/// link without geometry).
pub(super) fn reach_of<'m>(
    model: &Model,
    link_meshes: impl Iterator<Item = Option<&'m TriMesh>>,
) -> Reach {
    let travel = |k: usize| match model.urdf.joints[k].kind {
        JointKind::Prismatic { lower, upper } => lower.abs().max(upper.abs()),
        _ => 0.0,
    };
    link_meshes
        .enumerate()
        .map(|(l, m)| {
            let Some(mesh) = m else {
                return Vec::new();
            };
            let rho = mesh
                .vertices
                .iter()
                .map(|v| v.coords.norm())
                .fold(0.0, f64::max);
            let chain = model.chain_to(l);
            chain
                .iter()
                .enumerate()
                .filter(|(_, &k)| model.urdf.joints[k].kind.is_movable())
                .map(|(i, &k)| {
                    let factor = match model.urdf.joints[k].kind {
                        JointKind::Prismatic { .. } => 1.0,
                        _ => {
                            chain[i + 1..]
                                .iter()
                                .map(|&m| {
                                    model.urdf.joints[m].origin.translation.vector.norm()
                                        + travel(m)
                                })
                                .sum::<f64>()
                                + rho
                        }
                    };
                    // a relative margin for the rounding of the sums and of the poses
                    (k, factor * (1.0 + 1e-9))
                })
                .collect()
        })
        .collect()
}

/// Per link, the environment polytopes (by their balls, `obstacles`) it can meet in some
/// configuration: its points stay within `R_kl` of the axis point of the first movable joint
/// `k` above it, which no joint moves (a revolute joint's child frame turns about its origin),
/// and a link below no movable joint stays where `poses` put it. Every obstacle where the first
/// movable joint slides. A link near the base then skips the shelves across the room at every
/// moment of the sure test and every piece of a proof.
pub(super) fn reachable_obstacles(
    model: &Model,
    reach: &Reach,
    link_balls: &[Option<(nalgebra::Vector3<f64>, f64)>],
    poses: &[nalgebra::Isometry3<f64>],
    obstacles: &[(nalgebra::Vector3<f64>, f64)],
) -> Vec<Vec<u32>> {
    let within = |centre: nalgebra::Vector3<f64>, radius: f64| -> Vec<u32> {
        (0..obstacles.len())
            .filter(|&i| {
                let (c, r) = obstacles[i];
                (c - centre).norm() <= (radius + r) * (1.0 + 1e-9) + 1e-12
            })
            .map(|i| i as u32)
            .collect()
    };
    link_balls
        .iter()
        .enumerate()
        .map(|(l, ball)| {
            let Some((centre, radius)) = ball else {
                return Vec::new();
            };
            match reach[l].first() {
                // nothing above it moves: its ball where the poses put it
                None => within((poses[l] * nalgebra::Point3::from(*centre)).coords, *radius),
                Some(&(k, f)) => match model.urdf.joints[k].kind {
                    JointKind::Prismatic { .. } => (0..obstacles.len() as u32).collect(),
                    _ => within(poses[model.joint_links[k].1].translation.vector, f),
                },
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::arm::tests::panda;
    use crate::robot::oracle::ArmOracle;
    use nalgebra::{Point3, Vector3};
    use rand::{Rng, SeedableRng};

    /// Every obstacle ball a link's mesh reaches into, in random configurations, is one the
    /// link can reach; and balls far from the base are out of the near links' reach.
    #[test]
    fn a_link_meets_only_obstacles_it_can_reach() {
        let arm = panda();
        let oracle = ArmOracle::new(&arm, &[]).unwrap();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let obstacles: Vec<(Vector3<f64>, f64)> = (0..60)
            .map(|_| {
                let c = Vector3::new(
                    rng.random_range(-1.2..1.2),
                    rng.random_range(-1.2..1.2),
                    rng.random_range(-0.5..1.5),
                );
                (c, rng.random_range(0.02..0.2))
            })
            .collect();
        let balls: Vec<_> = oracle
            .link_meshes
            .iter()
            .map(|m| m.as_ref().map(|(_, b)| (b.centre, b.radius)))
            .collect();
        let g = &arm.group;
        let mid: Vec<f64> = (0..g.dof())
            .map(|i| (g.lower[i] + g.upper[i]) / 2.0)
            .collect();
        let reachable = reachable_obstacles(
            &arm.model,
            &oracle.reach,
            &balls,
            &arm.link_poses(&mid),
            &obstacles,
        );
        let mut met = 0;
        for _ in 0..100 {
            let q: Vec<f64> = (0..g.dof())
                .map(|i| rng.random_range(g.lower[i]..=g.upper[i]))
                .collect();
            let poses = arm.link_poses(&q);
            for (l, mesh) in oracle.link_meshes.iter().enumerate() {
                let Some((mesh, _)) = mesh else { continue };
                for (i, (c, r)) in obstacles.iter().enumerate() {
                    let inside = |v: &Point3<f64>| ((poses[l] * v).coords - c).norm() <= *r;
                    if mesh.vertices.iter().any(inside) {
                        met += 1;
                        assert!(reachable[l].contains(&(i as u32)), "link {l}, obstacle {i}");
                    }
                }
            }
        }
        let left_out: usize = reachable.iter().map(|r| obstacles.len() - r.len()).sum();
        assert!(met > 50, "{met} meetings");
        assert!(left_out > 60, "only {left_out} obstacles out of reach");
    }
}
