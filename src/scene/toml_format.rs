//! viaroad's TOML scene format (documented in the README).
//!
//! ```toml
//! name = "discs-example"
//! [space]
//! kind = "r2"            # "rn", "se2", "se3"
//! lower = [0.0, 0.0]
//! upper = [1.0, 1.0]
//! [[obstacle]]
//! disc = { center = [0.30, 0.40], radius = 0.05 }
//! [[query]]
//! start = [0.02, 0.98]
//! goal  = [0.98, 0.02]
//! ```

use super::{Obstacle, Query, Robot, Scene, SceneError};
use crate::space::{Space, SpaceKind};
use serde::Deserialize;
use std::path::{Path, PathBuf};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    name: Option<String>,
    space: SpaceSpec,
    robot: Option<RobotSpec>,
    #[serde(default, rename = "obstacle")]
    obstacles: Vec<ObstacleSpec>,
    #[serde(default, rename = "query")]
    queries: Vec<QuerySpec>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SpaceSpec {
    kind: String,
    lower: Vec<f64>,
    upper: Vec<f64>,
    rotation_scale: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RobotSpec {}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ObstacleSpec {
    disc: Option<DiscSpec>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DiscSpec {
    center: Vec<f64>,
    radius: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct QuerySpec {
    start: Vec<f64>,
    goal: Vec<f64>,
}

/// Reads and validates a TOML scene file.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    from_str(&text, path)
}

/// Parses a TOML scene; `path` names the file in errors and anchors relative mesh paths.
pub fn from_str(text: &str, path: &Path) -> Result<Scene, SceneError> {
    let file: File = toml::from_str(text).map_err(|e| SceneError::Parse {
        path: path.to_path_buf(),
        message: e.to_string().trim_end().replace('\n', " "),
    })?;
    let invalid = |message: String| SceneError::Invalid {
        path: path.to_path_buf(),
        message,
    };
    let space = match file.space.kind.as_str() {
        "r2" | "rn" => {
            let n = file.space.lower.len();
            if file.space.kind == "r2" && n != 2 {
                return Err(invalid(format!(
                    "kind = \"r2\" needs 2 bounds per side, got {n}"
                )));
            }
            Space::euclidean(file.space.lower.clone(), file.space.upper.clone())
                .map_err(|e| invalid(format!("[space] {e}")))?
        }
        other => {
            return Err(invalid(format!(
                "[space] kind = \"{other}\" is not known; expected r2, rn, se2 or se3"
            )))
        }
    };
    if file.space.rotation_scale.is_some() {
        return Err(invalid(
            "rotation_scale applies to se2 and se3 spaces only".into(),
        ));
    }
    if file.robot.is_some() {
        return Err(invalid(format!(
            "a {} scene moves a point; remove [robot]",
            space.kind()
        )));
    }
    let SpaceKind::Euclidean(n) = space.kind() else {
        unreachable!()
    };
    let mut obstacles = Vec::new();
    for (i, o) in file.obstacles.iter().enumerate() {
        let Some(d) = &o.disc else {
            return Err(invalid(format!(
                "obstacle {}: give disc = {{ center, radius }}",
                i + 1
            )));
        };
        if d.center.len() != n {
            return Err(invalid(format!(
                "obstacle {}: disc center has {} coordinates, the space has {n}",
                i + 1,
                d.center.len()
            )));
        }
        if !d.center.iter().all(|c| c.is_finite()) {
            return Err(invalid(format!(
                "obstacle {}: disc center is not finite",
                i + 1
            )));
        }
        if !(d.radius.is_finite() && d.radius >= 0.0) {
            return Err(invalid(format!(
                "obstacle {}: disc radius must be a non-negative number, got {}",
                i + 1,
                d.radius
            )));
        }
        obstacles.push(Obstacle::Disc {
            centre: d.center.clone(),
            radius: d.radius,
        });
    }
    let queries = file
        .queries
        .iter()
        .map(|q| Query {
            start: q.start.clone(),
            goal: q.goal.clone(),
        })
        .collect();
    let scene = Scene {
        name: file.name.unwrap_or_else(|| default_name(path)),
        space,
        robot: Robot::Point,
        obstacles,
        queries,
        source: Some(path.to_path_buf()),
        warnings: Vec::new(),
    };
    validate_queries(&scene)?;
    Ok(scene)
}

/// Checks every query of the scene: shape, bounds, collision.
pub fn validate_queries(scene: &Scene) -> Result<(), SceneError> {
    let oracle = scene.oracle();
    for (i, q) in scene.queries.iter().enumerate() {
        scene.check_config(
            oracle.as_ref(),
            &format!("start of query {}", i + 1),
            &q.start,
        )?;
        scene.check_config(
            oracle.as_ref(),
            &format!("goal of query {}", i + 1),
            &q.goal,
        )?;
    }
    Ok(())
}

fn default_name(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| PathBuf::from("scene").display().to_string())
}
