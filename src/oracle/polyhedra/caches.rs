//! What one call remembers while it sweeps: per robot face or tree node, the boxes and bounds
//! that several obstacle nodes ask for again.

use super::body::Face;
use super::containment::Pieces;
use super::envelope::{CylBounds, CylBox, FrameBox};
use super::pose::Aabb;
use crate::geometry::kernel::memo::Memo;

/// A robot node's bounds for a turn: cylindrical bounds, their angular sector, and the world box
/// its ball sweeps.
pub(crate) type NodeBounds = (CylBounds, Option<(f64, f64)>, Aabb);

/// An obstacle node's bounds for a turn: cylindrical bounds and their angular sector.
pub(crate) type ObstNodeBounds = (CylBounds, Option<(f64, f64)>);

/// Per-call caches of the sweeps, by robot face or robot tree node (see [`Memo`]).
#[derive(Default)]
pub(crate) struct Caches {
    /// A robot face's box in the frame of a translation.
    pub(super) frame_boxes: Memo<FrameBox>,
    /// A robot face's cylindrical box about the axis of a turn.
    pub(super) cyl_boxes: Memo<CylBox>,
    /// A robot node's box placed at the pose.
    pub(super) placed: Memo<Aabb>,
    /// A robot node's bounds for a turn.
    pub(super) nodes: Memo<NodeBounds>,
    /// A robot face's world box swept over a turn.
    pub(super) swept: Memo<Aabb>,
    /// A robot vertex's arc box over a turn.
    pub(super) vertex_arcs: Memo<Aabb>,
    /// A robot edge's cylindrical box about the axis of a turn.
    pub(super) robot_edges: Memo<CylBox>,
    /// An obstacle edge's cylindrical box about the axis of a turn, in the robot's frame.
    pub(super) obst_edges: Memo<CylBox>,
    /// An obstacle node's cylindrical bounds (and sector) about the axis of a turn: a node
    /// meets many robot nodes in one descent.
    pub(super) obst_nodes: Memo<ObstNodeBounds>,
    /// An obstacle face's world box (a turn).
    pub(super) obst_world: Memo<Aabb>,
    /// An obstacle face in the robot's frame with its cylindrical box about the axis of a
    /// turn: a large face (a shelf board) is returned with many robot leaves.
    pub(super) obst_faces: Memo<(Face, CylBox)>,
    /// An obstacle face in the robot's frame at a static test's pose, with its box grown by
    /// the distance tolerance: a large face (a wall) is returned with many robot leaves.
    pub(super) posed_faces: Memo<(Face, Aabb)>,
    /// Containment along a path.
    pub(super) pieces: Pieces,
}
