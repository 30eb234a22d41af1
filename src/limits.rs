//! The largest (or smallest) numbers viaroad accepts from users, in one place.
//!
//! A number past these limits is refused with one clear message *before* anything is allocated
//! or looped over: a time of 10³⁰⁰ s cannot become a [`std::time::Duration`], 10¹¹
//! generated discs do not fit in memory, a sampling resolution of 10⁻³⁰⁰ never finishes a
//! motion, and bounds of ±10³⁰⁸ overflow every distance. The limits are far beyond any useful
//! run, so they only ever catch typos and hostile input.

use std::time::Duration;

/// Longest time budget, in seconds (about 31 years): anything longer is a typo, and far longer
/// values (10³⁰⁰) do not fit a [`Duration`].
pub const MAX_SECONDS: f64 = 1e9;

/// Most roadmap nodes one learning run may be asked for. A node costs at least its
/// coordinates, its neighbour lists and its edges (hundreds of bytes), so ten million nodes
/// already take gigabytes; with no `--time` a larger count would run until memory runs out.
pub const MAX_NODES: usize = 10_000_000;

/// Most random queries generated at once (`demo --queries`, `bench local --queries`): each
/// pair of configurations is stored before the first is answered.
pub const MAX_QUERIES: usize = 1_000_000;

/// Most discs of a generated scene (`gen:discs:n=…`): 10⁵ discs of any useful radius already
/// cover the unit square.
pub const MAX_GENERATED_DISCS: usize = 100_000;

/// Most runs per scene and method of `bench local`.
pub const MAX_RUNS: u32 = 100_000;

/// Smallest resolution of the sampled local method (a fraction of the space's extent, OMPL's
/// convention): a motion is checked at up to `1 / resolution` states, so 10⁻⁹ is already a
/// billion checks per motion, and 10⁻³⁰⁰ never ends.
pub const MIN_SAMPLED_RESOLUTION: f64 = 1e-9;

/// Largest magnitude of a position bound. Distances, squared distances and valuations of
/// configurations inside bounds of ±10¹⁰⁰ stay finite; ±10³⁰⁰ gives infinite edge lengths and
/// ±10³⁰⁸ overflows even the width of the box.
pub const MAX_COORDINATE: f64 = 1e100;

/// Most clients `viaroad serve --listen` keeps connected at once (`--max-clients` can only
/// lower it). Each holds a reader thread and three descriptors, so 256 stay well inside the
/// usual limit of 1024 open files.
pub const MAX_SERVE_CLIENTS: usize = 256;

/// Most bytes read from a scene, mesh or query file: a file this large is not a scene (and
/// `/dev/zero` would otherwise be read until memory runs out).
pub const MAX_TEXT_FILE_BYTES: u64 = 1 << 30;

/// Most `<link>` and `<joint>` elements of a URDF, together, counted before any of them is
/// read: arms have tens (the Panda 25, VAMP's Fetch 33), and the kinematic tree, the joint
/// values and the link poses all grow with them.
pub const MAX_URDF_ELEMENTS: usize = 10_000;

/// Most `<collision>` elements of a URDF, all links together, counted before any is read:
/// each becomes a polytope with its inner balls when the robot is loaded (some 10 ms for a
/// sphere), and a spherized Fetch has about a hundred.
pub const MAX_COLLISION_ELEMENTS: usize = 1_000;

/// Most XML nodes (elements, text runs, comments) of a URDF or SRDF: the XML parser stops
/// there instead of building a tree of a whole file first. About thirty nodes per link with
/// its visual, inertial and whitespace, so [`MAX_URDF_ELEMENTS`] links fit several times over.
pub const MAX_XML_NODES: u32 = 1_000_000;

/// Most link pairs an arm checks for self-collision (pairs of links with geometry that the
/// SRDF does not exempt). The exact oracle builds one oracle per pair when the scene is
/// loaded (about 0.1 MB each for two spheres): 5 000 is every pair of 100 links, several times
/// what a two-armed robot with hands needs.
pub const MAX_SELF_PAIRS: usize = 5_000;

/// Largest MoveIt YAML file (PlanningScene, MotionPlanRequest), checked before it is read: the
/// YAML reader holds every token of the file at once, some 120 bytes per token, so the densest
/// 8 MiB (`[0,0,0],` repeated) already takes 0.6 GB. MotionBenchMaker's scenes have a few
/// kilobytes; 8 MiB still holds an inline mesh of 100 000 triangles written in block style.
pub const MAX_MOVEIT_YAML_BYTES: u64 = 8 << 20;

/// Most collision objects of a PlanningScene, counted as they are read: each becomes placed
/// polytopes, bounding volumes and a part of the environment every link is checked against.
pub const MAX_SCENE_OBJECTS: usize = 10_000;

/// Most shapes (primitives and meshes) of a PlanningScene, all objects together.
pub const MAX_SCENE_SHAPES: usize = 10_000;

/// Deepest nesting of YAML sequences and mappings (flow `[`/`{` or block), checked before the
/// YAML is deserialized. MoveIt messages nest about eight deep; the YAML scanner's work per
/// token grows with the nesting of flow collections (80 000 `[` took 80 s), and yaml_serde's
/// own limit of 128 applies only after the whole file has been scanned.
pub const MAX_YAML_DEPTH: usize = 128;

/// `seconds` as a [`Duration`] if it is a positive, finite number of at most [`MAX_SECONDS`].
pub fn duration_from_secs(seconds: f64) -> Option<Duration> {
    if seconds.is_finite() && seconds > 0.0 && seconds <= MAX_SECONDS {
        Duration::try_from_secs_f64(seconds).ok()
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_in_range_only() {
        assert_eq!(duration_from_secs(1.5), Some(Duration::from_millis(1500)));
        assert_eq!(
            duration_from_secs(MAX_SECONDS),
            Some(Duration::from_secs(1_000_000_000))
        );
        for bad in [
            0.0,
            -1.0,
            1e300,
            f64::INFINITY,
            f64::NAN,
            MAX_SECONDS * 1.01,
        ] {
            assert_eq!(duration_from_secs(bad), None, "{bad}");
        }
    }
}
