//! Geometric models shared by scene loading and the exact oracles: triangle meshes in 3D and
//! polygons in the plane, convex hulls, the footprint of a prism mesh and the triangulation of
//! a polygon, and (crate-internal) the geometric kernel of the rigid-body oracles. The
//! collision verbs live in [`crate::oracle`].

pub mod footprint;
pub mod hull;
pub(crate) mod kernel;
pub mod mesh;
pub mod polygon;
pub(crate) mod triangulate;

pub use footprint::footprint_polygons;
pub use mesh::TriMesh;
pub use polygon::Polygon;

/// Malformed geometry.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GeometryError {
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {0} has a coordinate that is not a finite number")]
    NotFinite(usize),
    /// A face refers to a vertex that does not exist.
    #[error("face {face} refers to vertex {index}, but there are only {count} vertices")]
    BadIndex {
        /// Face number.
        face: usize,
        /// The bad vertex index.
        index: usize,
        /// Number of vertices.
        count: usize,
    },
    /// Nothing left after dropping degenerate faces.
    #[error("no faces of positive area")]
    Empty,
    /// A polygon with fewer than three vertices or zero area.
    #[error("polygon needs at least 3 vertices and a positive area")]
    DegeneratePolygon,
    /// A size that must be positive is not.
    #[error("{0} must be a positive finite number")]
    NotPositive(&'static str),
}
