//! The tables of a TOML scene file, as serde reads them (checked and turned into a scene by
//! the reader).

use serde::Deserialize;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct File {
    pub(super) name: Option<String>,
    pub(super) space: SpaceSpec,
    pub(super) robot: Option<RobotSpec>,
    #[serde(default, rename = "body")]
    pub(super) bodies: Vec<BodySpec>,
    #[serde(default, rename = "obstacle")]
    pub(super) obstacles: Vec<ObstacleSpec>,
    #[serde(default, rename = "query")]
    pub(super) queries: Vec<QuerySpec>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SpaceSpec {
    pub(super) kind: String,
    pub(super) lower: Vec<f64>,
    pub(super) upper: Vec<f64>,
    pub(super) rotation_scale: Option<f64>,
}

#[derive(Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RobotSpec {
    #[serde(rename = "box")]
    pub(super) cuboid: Option<BoxSpec>,
    pub(super) mesh: Option<String>,
    pub(super) polygon: Option<PolygonSpec>,
    pub(super) polygons: Option<Vec<PolygonSpec>>,
    pub(super) convex: Option<ConvexSpec>,
    pub(super) center: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ObstacleSpec {
    #[serde(rename = "box")]
    pub(super) cuboid: Option<BoxSpec>,
    pub(super) mesh: Option<String>,
    pub(super) offset: Option<Vec<f64>>,
    pub(super) polygon: Option<PolygonSpec>,
    pub(super) convex: Option<ConvexSpec>,
    pub(super) disc: Option<DiscSpec>,
}

#[derive(Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BoxSpec {
    pub(super) center: Option<Vec<f64>>,
    pub(super) half_extents: Vec<f64>,
}

#[derive(Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PolygonSpec {
    pub(super) vertices: Vec<Vec<f64>>,
}

#[derive(Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ConvexSpec {
    pub(super) points: Vec<Vec<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct DiscSpec {
    pub(super) center: Vec<f64>,
    pub(super) radius: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct QuerySpec {
    pub(super) start: Vec<f64>,
    pub(super) goal: Vec<f64>,
}

/// A `[[body]]` table: a name and the shape of a se2 `[robot]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BodySpec {
    pub(super) name: Option<String>,
    #[serde(rename = "box")]
    pub(super) cuboid: Option<BoxSpec>,
    pub(super) mesh: Option<String>,
    pub(super) polygon: Option<PolygonSpec>,
    pub(super) polygons: Option<Vec<PolygonSpec>>,
    pub(super) convex: Option<ConvexSpec>,
    pub(super) center: Option<toml::Value>,
}

impl BodySpec {
    pub(super) fn shape(&self) -> RobotSpec {
        RobotSpec {
            cuboid: self.cuboid.clone(),
            mesh: self.mesh.clone(),
            polygon: self.polygon.clone(),
            polygons: self.polygons.clone(),
            convex: self.convex.clone(),
            center: self.center.clone(),
        }
    }
}
