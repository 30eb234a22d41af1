//! A robot arm in glTF: every collision element of every link a node of its own, animated by
//! forward kinematics along a path of joint vectors.
//!
//! Between two corners the joints move linearly (an arm path's corners differ in one joint
//! at a time where the planner made them, CHS §1.5: the distal links then turn rigidly about
//! a fixed axis). Each move is sampled so that no joint turns more than
//! [`MAX_TURN_PER_KEY`] between keys; the links' poses at
//! the keys come from [`Arm::link_poses`], so slerp between them follows the arcs the links
//! sweep.

use super::animation::{continuous, DURATION, MAX_TURN_PER_KEY};
use super::gltf::{Gltf, Mode, Track, Trs};
use super::{colour, names, world_node, ExportError, Legend, Plan, Soup};
use crate::robot::arm::ShapeSource;
use crate::robot::Arm;
use crate::scene::moveit::{CollisionObject, ObjectShape};
use nalgebra::{Isometry3, Point3};

/// Keyframes of a joint path: `(time, joint vector, is a corner)`, time proportional to the
/// joint-space distance, [`DURATION`] seconds in all. Joint `i` with bit `i` of `continuous`
/// set turns the shorter way round, as the joint space moves it.
pub fn joint_keyframes(path: &[Vec<f64>], continuous: u64) -> Vec<(f64, Vec<f64>, bool)> {
    let Some(first) = path.first() else {
        return Vec::new();
    };
    let mut keys = vec![(0.0, first.clone(), true)];
    // the change of every joint from `a` to `b`
    let delta = |a: &[f64], b: &[f64]| -> Vec<f64> {
        a.iter()
            .zip(b)
            .enumerate()
            .map(|(i, (x, y))| {
                if i < 64 && continuous >> i & 1 == 1 {
                    crate::space::rotation::wrap_angle(y - x)
                } else {
                    y - x
                }
            })
            .collect()
    };
    let dist = |a: &[f64], b: &[f64]| delta(a, b).iter().map(|d| d * d).sum::<f64>().sqrt();
    let total: f64 = path.windows(2).map(|w| dist(&w[0], &w[1])).sum();
    if total <= 0.0 {
        return keys;
    }
    let mut t = 0.0;
    for w in path.windows(2) {
        let d = dist(&w[0], &w[1]);
        if d <= 0.0 {
            continue;
        }
        let d_joints = delta(&w[0], &w[1]);
        let turn = d_joints.iter().map(|d| d.abs()).fold(0.0, f64::max);
        let steps = ((turn / MAX_TURN_PER_KEY - 1e-9).ceil() as usize).max(1);
        let dt = DURATION * d / total;
        for s in 1..=steps {
            let f = s as f64 / steps as f64;
            // the corner itself at the end (a continuous joint may have gone round through ±π)
            let q: Vec<f64> = if s == steps {
                w[1].clone()
            } else {
                w[0].iter().zip(&d_joints).map(|(a, d)| a + f * d).collect()
            };
            keys.push((t + f * dt, q, s == steps));
        }
        t += dt;
    }
    keys
}

fn trs(p: &Isometry3<f64>) -> Trs {
    let r = p.rotation;
    Trs {
        translation: [p.translation.x, p.translation.y, p.translation.z],
        rotation: [r.i, r.j, r.k, r.w],
    }
}

/// Both paths of `plan` hold `dof` finite joint values per corner.
fn check_joint_paths(plan: &Plan, dof: usize) -> Result<(), ExportError> {
    for (which, path) in [("raw", &plan.raw), ("shortened", &plan.shortened)] {
        for (index, q) in path.iter().enumerate() {
            if q.len() != dof || q.iter().any(|v| !v.is_finite()) {
                return Err(ExportError::Path {
                    which,
                    index,
                    message: format!(
                        "{dof} finite joint values expected, got {}",
                        crate::short::config(q)
                    ),
                });
            }
        }
    }
    Ok(())
}

/// The arm's obstacles, its links following the plan (joint vectors of the arm's group; the
/// shortened path, or the raw one where there is none) and the traces of the group's tip link
/// along both paths, as a glTF document. MoveIt scenes are Z-up. `wrapping` marks the
/// continuous joints, which turn the shorter way round (bit `i`: joint `i`).
pub fn arm_gltf(
    arm: &Arm,
    objects: &[CollisionObject],
    plan: &Plan,
    wrapping: u64,
    legend: &Legend,
) -> Result<Gltf, ExportError> {
    let dof = arm.group.dof();
    check_joint_paths(plan, dof)?;
    let path = plan.animated();
    let mut g = Gltf::new();
    let world = world_node(&mut g, true);
    let m_obstacle = g.material("obstacle", colour::linear(colour::OBSTACLE, 1.0), false);
    let m_robot = g.material("robot", colour::linear(colour::ROBOT, 1.0), false);

    let mut env = Soup::default();
    for o in objects {
        for (pose, shape) in &o.parts {
            let mesh = match shape {
                ObjectShape::Primitive(p) => match p.polytope() {
                    Ok(m) => m,
                    Err(_) => continue,
                },
                ObjectShape::Mesh(m) => m.clone(),
            };
            env.mesh(&mesh, |v| {
                let w = pose * Point3::from(v);
                [w.x, w.y, w.z]
            });
        }
    }
    env.add(&mut g, names::ENVIRONMENT, m_obstacle, world);

    let robot = g.node(names::ROBOT, None, Trs::IDENTITY, Some(world));
    let keys = joint_keyframes(path, wrapping);
    let start = path.first().cloned().unwrap_or_else(|| vec![0.0; dof]);
    let poses_at_start = arm.link_poses(&start);
    let poses: Vec<Vec<Isometry3<f64>>> = keys.iter().map(|k| arm.link_poses(&k.1)).collect();
    let times: Vec<f32> = keys.iter().map(|k| k.0 as f32).collect();
    for (i, shape) in arm.shapes.iter().enumerate() {
        let mut soup = Soup::default();
        match &shape.source {
            ShapeSource::Mesh { mesh, .. } => soup.mesh(mesh, |v| v),
            ShapeSource::Primitive(_) => soup.mesh(&shape.polytope, |v| v),
        }
        let name = format!("{} {}", arm.model.urdf.links[shape.link].name, i);
        let mesh = g.mesh(
            &name,
            &soup.positions,
            Some(&soup.indices),
            Mode::Triangles,
            m_robot,
        );
        let node = g.node(
            &name,
            mesh,
            trs(&(poses_at_start[shape.link] * shape.origin)),
            Some(robot),
        );
        let placed: Vec<Trs> = poses
            .iter()
            .map(|p| trs(&(p[shape.link] * shape.origin)))
            .collect();
        let mut rotations: Vec<[f64; 4]> = placed.iter().map(|t| t.rotation).collect();
        continuous(&mut rotations);
        g.animate(
            node,
            &Track {
                times: times.clone(),
                translations: placed
                    .iter()
                    .map(|t| t.translation.map(|v| v as f32))
                    .collect(),
                rotations: rotations.iter().map(|r| r.map(|v| v as f32)).collect(),
            },
        );
    }

    // the traces of the tip link's origin (the Panda's hand) along both paths
    let tip = arm
        .group
        .joints
        .last()
        .and_then(|&j| arm.model.link(&arm.model.urdf.joints[j].child))
        .unwrap_or(arm.model.urdf.links.len().saturating_sub(1));
    for (name, corners, hex) in [
        (names::RAW_PATH, &plan.raw, legend.raw_colour(plan)),
        (names::SHORT_PATH, &plan.shortened, colour::SHORT_PATH),
    ] {
        // through every key, not only the corners: the hand sweeps arcs between them
        let trace: Vec<[f32; 3]> = joint_keyframes(corners, wrapping)
            .iter()
            .map(|(_, q, _)| {
                let t = arm.link_poses(q)[tip].translation;
                [t.x as f32, t.y as f32, t.z as f32]
            })
            .collect();
        if trace.len() >= 2 {
            let m = g.material(name, colour::linear(hex, 1.0), true);
            let mesh = g.mesh(name, &trace, None, Mode::LineStrip, m);
            g.node(name, mesh, Trs::IDENTITY, Some(world));
        }
    }
    g.set_extras(serde_json::json!({
        "legend": legend, "duration": DURATION, "up": "z",
    }));
    Ok(g)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joint_keys_end_at_the_corners_and_take_small_steps() {
        let path = vec![vec![0.0, 0.0], vec![1.0, 0.0], vec![1.0, -0.5]];
        let keys = joint_keyframes(&path, 0);
        let corners: Vec<&Vec<f64>> = keys.iter().filter(|k| k.2).map(|k| &k.1).collect();
        assert_eq!(corners, vec![&path[0], &path[1], &path[2]]);
        assert!(keys.windows(2).all(|w| w[1].0 > w[0].0));
        for w in keys.windows(2) {
            let step = w[0]
                .1
                .iter()
                .zip(&w[1].1)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(step <= MAX_TURN_PER_KEY + 1e-12);
        }
        assert!((keys.last().unwrap().0 - DURATION).abs() < 1e-9);
    }

    #[test]
    fn continuous_joints_turn_the_short_way() {
        // joint 1 continuous: from 3 to -3 is 0.283 rad through ±π, not 6 rad back
        let path = vec![vec![0.0, 3.0], vec![0.0, -3.0]];
        let keys = joint_keyframes(&path, 0b10);
        // every step the short way round (the last lands on the corner, -3, one turn away)
        let turned: f64 = keys
            .windows(2)
            .map(|w| crate::space::rotation::wrap_angle(w[1].1[1] - w[0].1[1]).abs())
            .sum();
        assert!(
            (turned - (std::f64::consts::TAU - 6.0)).abs() < 1e-12,
            "{turned} {keys:?}"
        );
        assert!(keys[1..4].iter().all(|k| k.1[1] > 3.0), "{keys:?}");
        assert_eq!(keys.last().unwrap().1, path[1]);
        assert_eq!(keys.len(), 1 + 4);
        let limited = joint_keyframes(&path, 0);
        assert!(limited.len() > 60);
    }
}
