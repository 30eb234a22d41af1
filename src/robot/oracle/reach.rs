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
