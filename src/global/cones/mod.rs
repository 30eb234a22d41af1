//! Brooks's freeways: free space as overlapping generalized cones, searched with A*
//! (Brooks 1982, *Solving the find-path problem by good representation of free space*,
//! `seeds/001_…`).
//!
//! 1. **Cones** (§2.1, [`cone`]): every pair of obstacle edges whose free sides face each other
//!    (`n₁ · n₂ < 0`, each with a vertex on the free side of the other) spans a cone whose
//!    spine bisects them; the radius is the distance to the edges' lines, linear along the
//!    spine. Where another obstacle's edges enter the cone, their projection on the spine is
//!    cut out; the slices that still include part of both defining edges are the freeways.
//!    The bounds of the space are walls.
//! 2. **Legal orientations** (§3, [`radius`]): the robot's radius function
//!    `R(ξ) = max d_i cos(ξ − η_i)` bounds it by a rectangle aligned with the spine; its
//!    inverse `R⁻¹(r)` turns "the rectangle fits in the cone" into sets of orientations.
//! 3. **Graph and A*** (§4): nodes are spine intersections with one orientation interval each;
//!    arcs move along a spine at one orientation legal over the whole stretch, or change cone
//!    at an intersection where the two intervals meet. Paths are moves along spines at fixed
//!    orientation with rotations at the nodes, as in the paper's Figs 9–10 (the orientation
//!    of a stretch is the middle of its legal interval).
//!
//! Where this departs from the paper, on purpose:
//! - Legal orientations along a stretch `[s_a, s_b]` of a spine come from the robot's
//!   spine-aligned bounding rectangle swept over that stretch: ahead `R(ψ − φ) ≤ hi − s_max`,
//!   behind `R(ψ + π − φ) ≤ s_min − lo`, sideways `R(ψ ± π/2 − φ) ≤ min r` over
//!   `[s_min − d, s_max + d]`, `d` the robot's reach. This is the paper's rectangle (§3.2)
//!   checked per stretch instead of through `V(t)` and its lemma; it is at least as permissive
//!   and as safe. Radii are shrunk by a small margin, since touching is collision here.
//! - Start and goal are joined to the freeways by straight moves to the foot of the nearest
//!   spines (and a rotation there), each checked by the scene's exact oracle: the paper leaves
//!   this step open.
//! - A non-convex robot is represented by its convex hull (the paper restricts to convex
//!   robots). Disc obstacles (R² scenes) are replaced by circumscribed 16-gons.
//! - The finished path is re-checked by the exact oracle, motion by motion, before it is
//!   reported (the cone argument makes that check pass; it guards the numerics).
//!
//! Limits (the paper's own, §5): paths follow spines only, so in tight spaces — where the
//! robot must leave the middle of a passage, or where a turn needs more room than a spine
//! intersection offers — the method finds nothing although a path exists. It is incomplete by
//! design; README "Brooks's freeways" lists the shipped queries it fails.

pub mod cone;
mod freeways;
mod outcome;
pub mod radius;
mod search;
pub mod seeds;

use crate::oracle::CollisionOracle;
use crate::scene::{Obstacle, Robot, Scene};
use crate::space::SpaceKind;
pub use cone::{Cone, Edge, P};
pub use freeways::{Crossing, Freeways};
pub use outcome::{ConeError, ConeOutcome, ConePath};
pub use radius::{AngleSet, Arc, RadiusFunction};
use std::collections::HashSet;

/// Sides of the circumscribed polygon that stands in for a disc obstacle.
pub const DISC_SIDES: usize = 16;

/// Cleaned vertices of a polygon, counter-clockwise (so that the right of every edge is
/// outside).
fn ccw(vertices: impl Iterator<Item = P>) -> Vec<P> {
    let mut v: Vec<P> = vertices
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .map(|p| [p[0] + 0.0, p[1] + 0.0])
        .collect();
    v.dedup();
    while v.len() > 1 && v.first() == v.last() {
        v.pop();
    }
    let n = v.len();
    let area2: f64 = (0..n)
        .map(|i| v[i][0] * v[(i + 1) % n][1] - v[i][1] * v[(i + 1) % n][0])
        .sum();
    if area2 < 0.0 {
        v.reverse();
    }
    v
}

/// The robot's vertices in its own frame (none for a point robot): what the radius function
/// is made of.
fn robot_vertices(scene: &Scene) -> Result<Vec<P>, ConeError> {
    Ok(match &scene.robot {
        Robot::Point => Vec::new(),
        Robot::Polygons(parts) => parts
            .iter()
            .flat_map(|p| p.vertices.iter().map(|v| [v.x, v.y]))
            .collect(),
        Robot::Mesh(_) => return Err(ConeError::Unsupported("a mesh robot".into())),
        Robot::Arm(_) => return Err(ConeError::Unsupported("an arm".into())),
        Robot::Bodies(_) | Robot::MeshBodies(_) => {
            return Err(ConeError::Unsupported("several bodies".into()))
        }
    })
}

/// The obstacles as counter-clockwise polygons, a disc as the regular polygon around it (the
/// cones are built from straight edges).
fn obstacle_polygons(scene: &Scene) -> Result<Vec<Vec<P>>, ConeError> {
    let mut polygons: Vec<Vec<P>> = Vec::new();
    for o in &scene.obstacles {
        match o {
            Obstacle::Polygon(p) => polygons.push(ccw(p.vertices.iter().map(|v| [v.x, v.y]))),
            Obstacle::Disc { centre, radius } if centre.len() == 2 => {
                let r = radius / (std::f64::consts::PI / DISC_SIDES as f64).cos();
                polygons.push(
                    (0..DISC_SIDES)
                        .map(|k| {
                            let a = std::f64::consts::TAU * k as f64 / DISC_SIDES as f64;
                            [centre[0] + r * a.cos(), centre[1] + r * a.sin()]
                        })
                        .collect(),
                );
            }
            _ => return Err(ConeError::Unsupported("a 3D obstacle".into())),
        }
    }
    Ok(polygons)
}

/// The edges that bound free space: the obstacles' and the walls of the scene's bounds. An edge
/// two polygons share in opposite directions lies inside their union (the triangles of
/// OMPL.app's footprints) and bounds no free space.
fn free_space_edges(scene: &Scene, polygons: &[Vec<P>]) -> Vec<Edge> {
    let mut directed: HashSet<[u64; 4]> = HashSet::new();
    let key = |a: P, b: P| {
        [
            a[0].to_bits(),
            a[1].to_bits(),
            b[0].to_bits(),
            b[1].to_bits(),
        ]
    };
    for v in polygons {
        for i in 0..v.len() {
            directed.insert(key(v[i], v[(i + 1) % v.len()]));
        }
    }
    let mut edges = Vec::new();
    for v in polygons {
        if v.len() < 3 {
            continue;
        }
        for i in 0..v.len() {
            let (a, b) = (v[i], v[(i + 1) % v.len()]);
            if directed.contains(&key(b, a)) {
                continue;
            }
            edges.extend(Edge::new(a, b));
        }
    }
    let (lo, hi) = (scene.space.lower(), scene.space.upper());
    let walls = [
        ([hi[0], lo[1]], [lo[0], lo[1]]),
        ([hi[0], hi[1]], [hi[0], lo[1]]),
        ([lo[0], hi[1]], [hi[0], hi[1]]),
        ([lo[0], lo[1]], [lo[0], hi[1]]),
    ];
    edges.extend(walls.iter().filter_map(|&(a, b)| Edge::new(a, b)));
    edges
}

/// The narrowest the robot can be sideways (a little less, against rounding): a cone never
/// wider than that is no freeway.
fn narrowest(radius: &RadiusFunction) -> f64 {
    (0..720)
        .map(|k| {
            let xi = std::f64::consts::TAU * k as f64 / 720.0;
            radius
                .at(xi + std::f64::consts::FRAC_PI_2)
                .max(radius.at(xi - std::f64::consts::FRAC_PI_2))
        })
        .fold(f64::INFINITY, f64::min)
        * 0.99
}

/// What the search for cones between pairs of edges shares.
struct ConeFinder<'a> {
    edges: &'a [Edge],
    /// The edges' boxes `[x_lo, y_lo, x_hi, y_hi]`, to reject far edges quickly.
    boxes: &'a [[f64; 4]],
    polygons: &'a [Vec<P>],
    narrowest: f64,
    margin: f64,
    /// How far a cone is extended beyond its ends: past any point of the scene.
    reach: f64,
}

impl ConeFinder<'_> {
    /// Whether a pruned slice is a freeway: wider than the robot somewhere, and not inside an
    /// obstacle.
    fn keep(&self, c: &Cone) -> bool {
        c.radius(c.lo).max(c.radius(c.hi)) > self.narrowest + self.margin && {
            // no edge crosses a slice, so an obstacle that holds one of its points holds
            // all of it (a cone between two faces of one block)
            let m = c.point((c.lo + c.hi) / 2.0);
            !self.polygons.iter().any(|v| contains(v, m))
        }
    }

    /// The cones of every pair of edges, pruned, with their extensions; the joints between a
    /// cone and its extensions (collinear cones that continue each other); how many candidate
    /// cones there were.
    fn all(&self) -> (Vec<Cone>, Vec<Crossing>, usize) {
        let (edges, boxes, margin) = (self.edges, self.boxes, self.margin);
        let mut cones = Vec::new();
        let mut joints: Vec<Crossing> = Vec::new();
        let mut candidates = 0;
        for i in 0..edges.len() {
            for j in i + 1..edges.len() {
                let Some((cone, own)) = cone::candidate(edges, i, j) else {
                    continue;
                };
                candidates += 1;
                if cone.radius(cone.lo).max(cone.radius(cone.hi)) <= self.narrowest + margin {
                    continue;
                }
                for slice in cone::prune(&cone, own, edges, boxes, margin) {
                    if !self.keep(&slice) {
                        continue;
                    }
                    let k = cones.len();
                    cones.push(slice);
                    self.extend(&cone, k, &mut cones, &mut joints);
                }
            }
        }
        (cones, joints, candidates)
    }

    /// "At each vertex of the two edges the cone is extended parallel to the spine" (§2.1): a
    /// cone of constant radius beyond each end the slice `cones[k]` of `cone` reaches, pruned
    /// like the others, and kept (joined to the slice) if it starts at the joint.
    fn extend(&self, cone: &Cone, k: usize, cones: &mut Vec<Cone>, joints: &mut Vec<Crossing>) {
        let (margin, reach) = (self.margin, self.reach);
        let slice = cones[k];
        for (end, from, to) in [
            (cone.lo, cone.lo - reach, cone.lo),
            (cone.hi, cone.hi, cone.hi + reach),
        ] {
            let at_end = if end == cone.lo { slice.lo } else { slice.hi };
            if (at_end - end).abs() > margin {
                continue;
            }
            let r = cone.radius(end);
            let ext = Cone {
                lo: from,
                hi: to,
                r0: r,
                slope: 0.0,
                ..*cone
            };
            let near = (end - 101.0 * margin, end + 101.0 * margin);
            if let Some(e) = cone::prune(&ext, [near, near], self.edges, self.boxes, margin)
                .into_iter()
                .find(|e| self.keep(e))
            {
                joints.push(Crossing {
                    a: k,
                    sa: end.clamp(slice.lo, slice.hi),
                    b: cones.len(),
                    sb: end.clamp(e.lo, e.hi),
                });
                cones.push(e);
            }
        }
    }
}

/// Coinciding edges (a wall of the bounds on an obstacle's face) give the same cone twice: each
/// kept once, the joints renumbered, sorted, and those that became a cone's joint with itself
/// or a repeat dropped.
fn without_duplicates(
    cones: Vec<Cone>,
    mut joints: Vec<Crossing>,
    margin: f64,
) -> (Vec<Cone>, Vec<Crossing>) {
    let mut seen: std::collections::HashMap<[u64; 5], usize> = Default::default();
    let mut kept: Vec<Cone> = Vec::with_capacity(cones.len());
    let renumber: Vec<usize> = cones
        .iter()
        .map(|c| {
            let [a, b] = c.spine();
            let r = |v: f64| (v / margin).round().to_bits();
            let key = [r(a[0]), r(a[1]), r(b[0]), r(b[1]), r(c.radius(c.lo))];
            *seen.entry(key).or_insert_with(|| {
                kept.push(*c);
                kept.len() - 1
            })
        })
        .collect();
    joints.iter_mut().for_each(|j| {
        j.a = renumber[j.a];
        j.b = renumber[j.b];
    });
    joints.retain(|j| j.a != j.b);
    joints.sort_by(|x, y| (x.a, x.b).cmp(&(y.a, y.b)).then(x.sa.total_cmp(&y.sa)));
    joints.dedup_by(|x, y| x.a == y.a && x.b == y.b);
    (kept, joints)
}

impl Freeways {
    /// Whether [`build`](Self::build) can represent `scene`, without building anything: SE(2)
    /// with a polygonal robot or R² with a point, among polygons and discs. Otherwise
    /// [`ConeError::Unsupported`] names what is in the way (an SE(3) or R³ scene, a mesh robot,
    /// an arm, a 3D obstacle).
    pub fn supports(scene: &Scene) -> Result<(), ConeError> {
        match scene.space.kind() {
            SpaceKind::Se2 | SpaceKind::Euclidean(2) => {}
            k => return Err(ConeError::Unsupported(format!("a {k} scene"))),
        }
        match &scene.robot {
            Robot::Point | Robot::Polygons(_) => {}
            Robot::Mesh(_) => return Err(ConeError::Unsupported("a mesh robot".into())),
            Robot::Arm(_) => return Err(ConeError::Unsupported("an arm".into())),
            Robot::Bodies(_) | Robot::MeshBodies(_) => {
                return Err(ConeError::Unsupported("several bodies".into()))
            }
        }
        for o in &scene.obstacles {
            match o {
                Obstacle::Polygon(_) => {}
                Obstacle::Disc { centre, .. } if centre.len() == 2 => {}
                _ => return Err(ConeError::Unsupported("a 3D obstacle".into())),
            }
        }
        Ok(())
    }

    /// The cones of a planar scene (SE(2) with a polygonal robot, or R² with a point among
    /// discs or polygons), pruned, and their spine intersections. `O(n³)` in the number of
    /// obstacle edges `n` (Brooks §2.1), less in practice: edges far from a cone are rejected
    /// by their boxes.
    pub fn build(scene: &Scene) -> Result<Freeways, ConeError> {
        Self::supports(scene)?;
        let oriented = matches!(scene.space.kind(), SpaceKind::Se2);
        let robot_vertices = robot_vertices(scene)?;
        let polygons = obstacle_polygons(scene)?;
        let edges = free_space_edges(scene, &polygons);
        let margin = 1e-6 * scene.space.extent().max(1e-9);
        let radius = RadiusFunction::new(&robot_vertices);
        let boxes: Vec<[f64; 4]> = edges
            .iter()
            .map(|e| {
                [
                    e.a[0].min(e.b[0]),
                    e.a[1].min(e.b[1]),
                    e.a[0].max(e.b[0]),
                    e.a[1].max(e.b[1]),
                ]
            })
            .collect();
        let finder = ConeFinder {
            edges: &edges,
            boxes: &boxes,
            polygons: &polygons,
            narrowest: narrowest(&radius),
            margin,
            reach: 2.0 * scene.space.extent(),
        };
        let (cones, joints, candidates) = finder.all();
        let (cones, joints) = without_duplicates(cones, joints, margin);
        let mut crossings = spine_crossings(&cones);
        crossings.extend(joints);
        Ok(Freeways {
            edges,
            cones,
            crossings,
            radius,
            margin,
            oriented,
            candidates,
        })
    }

    /// A path from `start` to `goal` along the freeways (Brooks §4), or why there is none.
    /// `oracle` (the scene's exact one) checks the moves that join start and goal to the
    /// spines and re-checks the finished path.
    pub fn solve(
        &self,
        scene: &Scene,
        oracle: &dyn CollisionOracle,
        start: &[f64],
        goal: &[f64],
    ) -> Result<ConeOutcome, ConeError> {
        let dim = scene.space.dim();
        for q in [start, goal] {
            if q.len() != dim {
                return Err(ConeError::Dimension {
                    got: q.len(),
                    expected: dim,
                });
            }
        }
        search::solve(self, scene, oracle, start, goal)
    }
}

/// Whether `p` lies in the closed polygon `v` (crossing number; a point on an edge counts).
fn contains(v: &[P], p: P) -> bool {
    let n = v.len();
    if n < 3 {
        return false;
    }
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (v[i], v[(i + 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            if p[0] <= x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Where the spines of two cones cross (`O(c²)` over the cones, boxes first).
fn spine_crossings(cones: &[Cone]) -> Vec<Crossing> {
    let boxes: Vec<[f64; 4]> = cones
        .iter()
        .map(|c| {
            let [a, b] = c.spine();
            [
                a[0].min(b[0]),
                a[1].min(b[1]),
                a[0].max(b[0]),
                a[1].max(b[1]),
            ]
        })
        .collect();
    let mut out = Vec::new();
    for i in 0..cones.len() {
        for j in i + 1..cones.len() {
            let (bi, bj) = (boxes[i], boxes[j]);
            if bi[0] > bj[2] || bj[0] > bi[2] || bi[1] > bj[3] || bj[1] > bi[3] {
                continue;
            }
            let (ci, cj) = (&cones[i], &cones[j]);
            let den = ci.dir[0] * cj.dir[1] - ci.dir[1] * cj.dir[0];
            if den.abs() < 1e-9 {
                continue;
            }
            let w = [cj.origin[0] - ci.origin[0], cj.origin[1] - ci.origin[1]];
            let sa = (w[0] * cj.dir[1] - w[1] * cj.dir[0]) / den;
            let sb = (w[0] * ci.dir[1] - w[1] * ci.dir[0]) / den;
            if sa >= ci.lo && sa <= ci.hi && sb >= cj.lo && sb <= cj.hi {
                out.push(Crossing { a: i, sa, b: j, sb });
            }
        }
    }
    out
}
