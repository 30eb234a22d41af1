//! What every reader checks once it has a scene: coordinates within the limits, queries well
//! formed, free and within the bounds, quaternions of unit length; and the name a scene gets
//! when its file gives none.

use super::error::SceneError;
use super::types::{Obstacle, Query, Robot, Scene};
use crate::space::SpaceKind;
use std::path::Path;

/// Refuses robot and obstacle coordinates beyond [`crate::limits::MAX_COORDINATE`] (and disc
/// radii beyond it): the oracles square and multiply coordinates, which would overflow into
/// infinities and NaNs. The bounds are checked by [`Space`] itself.
pub(crate) fn check_magnitudes(scene: &Scene) -> Result<(), SceneError> {
    let max = crate::limits::MAX_COORDINATE;
    let too_big = |what: String| SceneError::Invalid {
        path: scene.source.clone().unwrap_or_default(),
        message: format!("{what} has a coordinate beyond ±{max:e}, where distances overflow"),
    };
    let big = |v: f64| v.is_nan() || v.abs() > max;
    match &scene.robot {
        // the robot's own files refuse such numbers as they are read
        Robot::Point | Robot::Arm(_) => {}
        Robot::Polygons(parts) => {
            if parts
                .iter()
                .flat_map(|p| &p.vertices)
                .any(|v| big(v.x) || big(v.y))
            {
                return Err(too_big("the robot".into()));
            }
        }
        Robot::Mesh(m) => {
            if m.vertices.iter().any(|v| big(v.x) || big(v.y) || big(v.z)) {
                return Err(too_big("the robot".into()));
            }
        }
        Robot::Bodies(bodies) => {
            for b in bodies {
                if b.parts
                    .iter()
                    .flat_map(|p| &p.vertices)
                    .any(|v| big(v.x) || big(v.y))
                {
                    return Err(too_big(format!("body \"{}\"", b.name)));
                }
            }
        }
        Robot::MeshBodies(bodies) => {
            for b in bodies {
                if b.mesh
                    .vertices
                    .iter()
                    .any(|v| big(v.x) || big(v.y) || big(v.z))
                {
                    return Err(too_big(format!("body \"{}\"", b.name)));
                }
            }
        }
    }
    for (i, o) in scene.obstacles.iter().enumerate() {
        let bad = match o {
            Obstacle::Disc { centre, radius } => centre.iter().any(|&c| big(c)) || big(*radius),
            Obstacle::Polygon(p) => p.vertices.iter().any(|v| big(v.x) || big(v.y)),
            Obstacle::Mesh(m) => m.vertices.iter().any(|v| big(v.x) || big(v.y) || big(v.z)),
        };
        if bad {
            return Err(too_big(format!("obstacle {}", i + 1)));
        }
    }
    Ok(())
}

/// Checks the scene's queries as it loads. A malformed query (wrong length, not a number, a
/// zero quaternion) is an error of the file; a well-formed one outside the bounds or in
/// collision only stops the commands that answer it ([`Scene::checked_queries`]): a roadmap
/// of the scene does not need its queries, so for `build` it is a warning.
pub(crate) fn check_queries_on_load(scene: &mut Scene) -> Result<(), SceneError> {
    match checked_queries(scene) {
        Ok(queries) => scene.queries = queries,
        Err(e @ SceneError::Config { .. }) => return Err(e),
        Err(e) => scene
            .warnings
            .push(format!("{e}: the scene's queries cannot be answered")),
    }
    Ok(())
}

/// The name a scene gets when its file gives none: the file name without extension.
pub(crate) fn default_name(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into())
}

/// Warnings for the scene's SE(3) queries whose quaternion is not of unit length (within
/// 10⁻⁶): they are normalised, as OMPL's `SO3StateSpace::enforceBounds` does, but a length far
/// from 1 may be a typo, so it is said rather than corrected silently.
pub(crate) fn quaternion_warnings(scene: &Scene) -> Vec<String> {
    let bodies = match scene.space.kind() {
        SpaceKind::Se3 => 1,
        SpaceKind::Se3Bodies(k) => k,
        _ => return Vec::new(),
    };
    let mut out = Vec::new();
    for (i, q) in scene.queries.iter().enumerate() {
        for (what, c) in [("start", &q.start), ("goal", &q.goal)] {
            for b in 0..bodies {
                let Some(quat) = c.get(7 * b + 3..7 * b + 7) else {
                    continue;
                };
                let n = quat.iter().map(|v| v * v).sum::<f64>().sqrt();
                if n.is_finite() && n >= 1e-9 && (n - 1.0).abs() > 1e-6 {
                    let whose = if bodies > 1 {
                        format!("body {}'s quaternion", b + 1)
                    } else {
                        "quaternion".into()
                    };
                    out.push(format!(
                        "{what} of query {}: {whose} of length {n} normalised to length 1",
                        i + 1
                    ));
                }
            }
        }
    }
    out
}

/// Checks every query of the scene: shape, bounds, collision.
pub fn validate_queries(scene: &Scene) -> Result<(), SceneError> {
    checked_queries(scene).map(|_| ())
}

/// The scene's queries after checking (shape, bounds, collision), normalised: quaternions of
/// unit length, angles in `[-π, π)`.
pub fn checked_queries(scene: &Scene) -> Result<Vec<Query>, SceneError> {
    // shapes first, for every query: a malformed one is an error of the file, whatever the
    // bounds and collisions of the queries before it
    for (i, q) in scene.queries.iter().enumerate() {
        for (what, c) in [("start", &q.start), ("goal", &q.goal)] {
            scene.space.check(c).map_err(|source| SceneError::Config {
                what: format!("{what} of query {}", i + 1),
                source,
            })?;
        }
    }
    let oracle = scene.oracle();
    scene
        .queries
        .iter()
        .enumerate()
        .map(|(i, q)| {
            Ok(Query {
                start: scene.check_config(
                    oracle.as_ref(),
                    &format!("start of query {}", i + 1),
                    &q.start,
                )?,
                goal: scene.check_config(
                    oracle.as_ref(),
                    &format!("goal of query {}", i + 1),
                    &q.goal,
                )?,
            })
        })
        .collect()
}
