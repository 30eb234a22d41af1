//! A robot arm in glTF: every collision element of every link a node of its own, animated by
//! forward kinematics along a path of joint vectors.
//!
//! Between two corners the joints move linearly (an arm path's corners differ in one joint
//! at a time where the planner made them, CHS §1.5: the distal links then turn rigidly about
//! a fixed axis). Each move is sampled so that no joint turns more than
//! [`MAX_TURN_PER_KEY`](super::animation::MAX_TURN_PER_KEY) between keys; the links' poses at
//! the keys come from [`Arm::link_poses`], so slerp between them follows the arcs the links
//! sweep.

use super::animation::{continuous, DURATION, MAX_TURN_PER_KEY};
use super::gltf::{Gltf, Mode, Track, Trs};
use super::{colour, names, world_node, ExportError, Legend, Soup};
use crate::robot::arm::ShapeSource;
use crate::robot::Arm;
use crate::scene::moveit::{CollisionObject, ObjectShape};
use nalgebra::{Isometry3, Point3};

/// Keyframes of a joint path: `(time, joint vector, is a corner)`, time proportional to the
/// joint-space distance, [`DURATION`] seconds in all.
pub fn joint_keyframes(path: &[Vec<f64>]) -> Vec<(f64, Vec<f64>, bool)> {
    let Some(first) = path.first() else {
        return Vec::new();
    };
    let mut keys = vec![(0.0, first.clone(), true)];
    let dist = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y) * (x - y))
            .sum::<f64>()
            .sqrt()
    };
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
        let turn = w[0]
            .iter()
            .zip(&w[1])
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        let steps = ((turn / MAX_TURN_PER_KEY - 1e-9).ceil() as usize).max(1);
        let dt = DURATION * d / total;
        for s in 1..=steps {
            let f = s as f64 / steps as f64;
            let q: Vec<f64> = w[0]
                .iter()
                .zip(&w[1])
                .map(|(a, b)| a + f * (b - a))
                .collect();
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

/// The arm's obstacles, its links following `path` (joint vectors of the arm's group) and the
/// trace of the end of its last link, as a glTF document. MoveIt scenes are Z-up.
pub fn arm_gltf(
    arm: &Arm,
    objects: &[CollisionObject],
    path: &[Vec<f64>],
    legend: &Legend,
) -> Result<Gltf, ExportError> {
    let dof = arm.group.dof();
    for (index, q) in path.iter().enumerate() {
        if q.len() != dof || q.iter().any(|v| !v.is_finite()) {
            return Err(ExportError::Path {
                which: "arm",
                index,
                message: format!("{} finite joint values expected, got {q:?}", dof),
            });
        }
    }
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
    let keys = joint_keyframes(path);
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

    // the trace of the last link's origin (the Panda's hand) at the corners
    if let Some(tip) = arm.model.urdf.links.len().checked_sub(1) {
        let trace: Vec<[f32; 3]> = keys
            .iter()
            .zip(&poses)
            .filter(|(k, _)| k.2)
            .map(|(_, p)| {
                let t = p[tip].translation;
                [t.x as f32, t.y as f32, t.z as f32]
            })
            .collect();
        if trace.len() >= 2 {
            let m = g.material(
                names::SHORT_PATH,
                colour::linear(colour::SHORT_PATH, 1.0),
                true,
            );
            let mesh = g.mesh(names::SHORT_PATH, &trace, None, Mode::LineStrip, m);
            g.node(names::SHORT_PATH, mesh, Trs::IDENTITY, Some(world));
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
        let keys = joint_keyframes(&path);
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
}
