//! A polygonal robot among polygons in SE(2): exact collision intervals of translations and of
//! rotations about the reference point (CHS Chapter 2, in the plane).
//!
//! The robot is a union of simple polygons given in its body frame (reference point at the
//! origin); a configuration `[x, y, θ]` places a body point `v` at `Rot(θ)·v + (x, y)`. The
//! obstacles are a union of simple polygons in the world frame. Robot and obstacles collide
//! iff some robot polygon and some obstacle polygon overlap as closed sets, which holds iff
//! (CHS §2.1, in the plane)
//!
//! - a robot edge meets an obstacle edge (closed segments: touching counts), or
//! - a reference vertex of one polygon lies in the other (containment).
//!
//! For a straight motion each of these primitive tests turns into inequalities in the motion
//! parameter — linear for a translation (`translation.rs`), `α cos φ + β sin φ + γ ≥ 0` for a
//! rotation (`rotation.rs`, solved through `τ = tan(φ/2)` by the kernel's trigonometric atom,
//! `geometry/kernel/trig.rs`) — whose solution sets
//! are combined as interval lists (∧ = intersection, ∨ = union), and the union over all pairs
//! is the answer.
//!
//! Enveloping (`envelope.rs`, the kernel's `Bvh`): an AABB tree over the obstacle edges, triangles and
//! reference vertices is queried once per kind of primitive with the region the whole robot
//! sweeps — a box in the frame of a translation, an annulus about the centre of a rotation —
//! and every robot primitive is then tested only against the candidates its own swept region
//! meets, so far-away obstacle parts cost nothing. `pairs_tested` counts the primitive pairs
//! that survive.
//!
//! Containment is decided with triangulations (ear clipping, `geometry/triangulate.rs`) instead of the
//! seed's random rays: "point in polygon" becomes "point in one of its triangles", three
//! orientation tests that move with the motion like all the others.
//!
//! Numerics: every orientation test is relaxed by a tolerance of [`TOLERANCE`] times the size
//! of the scene, in favour of collision, so intervals are closed and a grazing contact is never
//! lost to rounding. The answer is conservative by that much, never NaN, and nothing panics.
//!
//! OMPL.app's 2D problems ship 3D prisms; [`footprint_polygons`] turns them into triangles.

mod envelope;
mod prepared;
mod rotation;
mod translation;

/// Moved to [`crate::geometry`] (scene loading needs it without an oracle); kept here for
/// the callers that import it with the oracle.
pub use crate::geometry::footprint_polygons;
pub use prepared::{Polygons, TOLERANCE};

use prepared::{perp_dot, Aabb, Body, Bvh, World, P};

use super::{CallCounts, CollisionOracle, OracleError, Workspace};
use crate::geometry::kernel::hits::{merge_in_place, Hits};
use crate::geometry::Polygon;
use crate::interval::{Interval, IntervalList};
use crate::space::{Change, Motion};
use std::cell::RefCell;
use std::collections::HashSet;
use std::f64::consts::TAU;
use std::ops::ControlFlow;

/// Longest rotation answered, in full turns; a longer one is [`OracleError::Unsupported`].
pub const MAX_TURNS: f64 = 4096.0;

/// A call's reusable space: the pieces, and the copies of one turn's pieces for a longer turn.
/// One per thread, so that a call allocates nothing but its answer.
#[derive(Default)]
struct Scratch {
    hits: Hits,
    turns: Vec<Interval>,
    trans: translation::Buffers,
    rot: rotation::Buffers,
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

/// Runs `f` with this thread's scratch space (a fresh one should a call ever nest).
fn with_scratch<R>(f: impl FnOnce(&mut Scratch) -> R) -> R {
    SCRATCH.with(|cell| match cell.try_borrow_mut() {
        Ok(mut s) => f(&mut s),
        Err(_) => f(&mut Scratch::default()),
    })
}

/// Polygon parts prepared for the tests: edges (each segment once), triangles, one reference
/// vertex per part.
#[derive(Default)]
struct Parts {
    edges: Vec<[P; 2]>,
    tris: Vec<[P; 3]>,
    refs: Vec<P>,
    vertices: Vec<P>,
}

fn length(a: P, b: P) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1])
}

fn edge_lengths(edges: &[[P; 2]]) -> Vec<f64> {
    edges.iter().map(|&[a, b]| length(a, b)).collect()
}

fn triangle_lengths(tris: &[[P; 3]]) -> Vec<[f64; 3]> {
    tris.iter()
        .map(|t| [length(t[0], t[1]), length(t[1], t[2]), length(t[2], t[0])])
        .collect()
}

/// Finite vertices without repeats, counter-clockwise.
fn clean(poly: &Polygon) -> Vec<P> {
    let mut v: Vec<P> = poly
        .vertices
        .iter()
        .filter(|p| p.x.is_finite() && p.y.is_finite())
        .map(|p| [p.x + 0.0, p.y + 0.0])
        .collect();
    v.dedup();
    while v.len() > 1 && v.first() == v.last() {
        v.pop();
    }
    let n = v.len();
    let area2: f64 = (0..n).map(|i| perp_dot(v[i], v[(i + 1) % n])).sum();
    if area2 < 0.0 {
        v.reverse();
    }
    v
}

/// Edges, triangles and reference vertices of a union of polygons.
///
/// Every part keeps all its edges (a segment listed twice is tested once): the containment
/// argument is per pair of parts, so an edge two parts share inside the union is still needed
/// — a frame-shaped obstacle whose hole lies inside a fan of robot triangles meets only their
/// shared edges.
fn prepare(polys: &[Polygon]) -> Parts {
    let mut parts = Parts::default();
    let mut seen: HashSet<[u64; 4]> = HashSet::new();
    for poly in polys {
        let v = clean(poly);
        let Some(&first) = v.first() else { continue };
        parts.refs.push(first);
        parts.vertices.extend_from_slice(&v);
        let n = v.len();
        let edge_count = match n {
            0 | 1 => 0,
            2 => 1,
            _ => n,
        };
        for i in 0..edge_count {
            let (a, b) = (v[i], v[(i + 1) % n]);
            let (p, q) = if (a[0], a[1]) <= (b[0], b[1]) {
                (a, b)
            } else {
                (b, a)
            };
            if seen.insert([
                p[0].to_bits(),
                p[1].to_bits(),
                q[0].to_bits(),
                q[1].to_bits(),
            ]) {
                parts.edges.push([a, b]);
            }
        }
        for t in crate::geometry::triangulate::triangulate(&v) {
            parts.tris.push([v[t[0]], v[t[1]], v[t[2]]]);
        }
    }
    parts
}

/// What a motion asks of this oracle.
enum Kind {
    /// The robot translates by `t·m` (a zero `m` is the static test over the range).
    Translation { centre: P, theta: f64, m: P },
    /// The robot turns about its reference point by `t·omega`.
    Rotation { centre: P, theta: f64, omega: f64 },
}

impl Polygons {
    /// `robot` parts in the body frame (reference point at the origin), obstacles in the world
    /// frame. Polygons should be simple; either orientation is accepted. Non-finite and repeated
    /// vertices are skipped; a polygon left with one vertex acts as a point, with none it is
    /// ignored. (On a polygon that is not simple, triangulation does its best and containment
    /// may err towards collision.) Enveloping is on.
    pub fn new(robot: Vec<Polygon>, obstacles: Vec<Polygon>) -> Polygons {
        let r = prepare(&robot);
        let o = prepare(&obstacles);
        let edge_radii: Vec<(f64, f64)> = r
            .edges
            .iter()
            .map(|&[a, b]| {
                let far = a[0].hypot(a[1]).max(b[0].hypot(b[1]));
                (rotation::segment_distance(a, b), far)
            })
            .collect();
        let tri_radii: Vec<(f64, f64)> = r.tris.iter().map(rotation::triangle_radii).collect();
        let radius = r
            .vertices
            .iter()
            .map(|p| p[0].hypot(p[1]))
            .fold(0.0, f64::max);
        let tri_inner_radius = tri_radii.iter().map(|r| r.0).fold(f64::INFINITY, f64::min);
        let edge_inner_radius = edge_radii.iter().map(|r| r.0).fold(f64::INFINITY, f64::min);
        let body = Body {
            vertices: r.vertices,
            edge_len: edge_lengths(&r.edges),
            edges: r.edges,
            edge_radii,
            edge_inner_radius: if edge_inner_radius.is_finite() {
                edge_inner_radius
            } else {
                0.0
            },
            tri_len: triangle_lengths(&r.tris),
            tris: r.tris,
            tri_radii,
            tri_inner_radius: if tri_inner_radius.is_finite() {
                tri_inner_radius
            } else {
                0.0
            },
            refs: r.refs,
            radius,
        };
        let scale = o
            .vertices
            .iter()
            .map(|p| p[0].abs().max(p[1].abs()))
            .fold(radius, f64::max);
        let world = World {
            edge_tree: Bvh::build(o.edges.iter().map(|e| Aabb::of_plane_points(e)).collect()),
            tri_tree: Bvh::build(o.tris.iter().map(|t| Aabb::of_plane_points(t)).collect()),
            ref_tree: Bvh::build(
                o.refs
                    .iter()
                    .map(|p| Aabb::of_plane_points(&[*p]))
                    .collect(),
            ),
            edge_len: edge_lengths(&o.edges),
            edges: o.edges,
            tri_len: triangle_lengths(&o.tris),
            tris: o.tris,
            refs: o.refs,
        };
        Polygons {
            robot,
            obstacles,
            enveloping: true,
            body,
            world,
            scale,
        }
    }

    /// Switches enveloping (the obstacle tree and the per-pair culling) on or off. Off, every
    /// robot primitive is tested against every obstacle primitive: the same answers, slower —
    /// for benchmarks and cross-checks.
    pub fn with_enveloping(mut self, on: bool) -> Polygons {
        self.enveloping = on;
        self
    }

    /// Whether enveloping is on.
    pub fn enveloping(&self) -> bool {
        self.enveloping
    }

    /// The robot's parts, in the body frame, as given.
    pub fn robot(&self) -> &[Polygon] {
        &self.robot
    }

    /// The obstacles, as given.
    pub fn obstacles(&self) -> &[Polygon] {
        &self.obstacles
    }

    /// Largest distance of a robot vertex from the reference point.
    pub fn robot_radius(&self) -> f64 {
        self.body.radius
    }

    /// Number of distinct obstacle edges (what one interval call is measured against).
    pub fn obstacle_edge_count(&self) -> usize {
        self.world.edges.len()
    }

    /// Number of distinct robot edges.
    pub fn robot_edge_count(&self) -> usize {
        self.body.edges.len()
    }

    fn classify(motion: &Motion) -> Result<Kind, OracleError> {
        let delta = match &motion.change {
            Change::Linear(d) => d,
            Change::Rotation { .. } | Change::BodyRotation { .. } => {
                return Err(OracleError::Unsupported(
                    "polygons: an SE(3) rotation (Change::Rotation) in the plane".into(),
                ))
            }
        };
        if motion.origin.len() != 3 || delta.len() != 3 {
            return Err(OracleError::Unsupported(format!(
                "polygons: SE(2) motions have 3 coordinates, got an origin of {} and a change of {}",
                motion.origin.len(),
                delta.len()
            )));
        }
        if !motion.origin.iter().chain(delta).all(|v| v.is_finite()) {
            return Err(OracleError::Unsupported(
                "polygons: a motion with a coordinate that is not a finite number".into(),
            ));
        }
        let r = motion.range;
        if r.lo.is_nan() || r.hi.is_nan() || r.lo > r.hi {
            return Err(OracleError::Unsupported(format!(
                "polygons: the parameter range [{}, {}] is empty",
                motion.range.lo, motion.range.hi
            )));
        }
        let centre = [motion.origin[0], motion.origin[1]];
        let theta = motion.origin[2];
        let moves = delta[0] != 0.0 || delta[1] != 0.0;
        if delta[2] == 0.0 {
            Ok(Kind::Translation {
                centre,
                theta,
                m: [delta[0], delta[1]],
            })
        } else if !moves {
            Ok(Kind::Rotation {
                centre,
                theta,
                omega: delta[2],
            })
        } else {
            Err(OracleError::Unsupported(
                "polygons: a simultaneous translation and rotation".into(),
            ))
        }
    }

    /// Maps intervals of turned angle `φ = omega · t` back to `t`. The ends of the angle range
    /// map exactly to the ends of `range` (a division would miss them by rounding).
    /// The sweep behind `intervals` and `intervals_into`: a translation's pieces into
    /// `scratch.hits` (`None`), or a rotation's pieces in turned angle, copied over every turn
    /// and merged, into `scratch.turns` (`Some(omega)`).
    fn collect(
        &self,
        motion: &Motion,
        scratch: &mut Scratch,
        counts: &mut CallCounts,
    ) -> Result<Option<f64>, OracleError> {
        let Scratch {
            hits,
            turns,
            trans,
            rot,
        } = scratch;
        hits.reset(false);
        let mut collect = |iv: Interval| hits.add(iv);
        match Self::classify(motion)? {
            Kind::Translation { centre, theta, m } => {
                let _ = translation::sweep(
                    self,
                    centre,
                    theta,
                    m,
                    motion.range,
                    &mut counts.pairs_tested,
                    trans,
                    &mut collect,
                );
                Ok(None)
            }
            Kind::Rotation {
                centre,
                theta,
                omega,
            } => {
                let (window, reach) = Self::rotation_window(motion.range, omega)?;
                let _ = rotation::sweep(
                    self,
                    centre,
                    theta,
                    window,
                    &mut counts.pairs_tested,
                    rot,
                    &mut collect,
                );
                // one turn computed; later turns repeat it
                let base = hits.as_slice();
                turns.clear();
                turns.extend_from_slice(base);
                let mut k = 1.0;
                while window.lo + k * TAU <= reach {
                    let shift = k * TAU;
                    turns.extend(
                        base.iter().filter_map(|iv| {
                            Interval::new(iv.lo + shift, (iv.hi + shift).min(reach))
                        }),
                    );
                    k += 1.0;
                }
                merge_in_place(turns);
                Ok(Some(omega))
            }
        }
    }

    fn angles_to_parameters(angles: &[Interval], omega: f64, range: Interval) -> IntervalList {
        let mut ts = angles.to_vec();
        Self::angles_to_parameters_in_place(&mut ts, omega, range);
        IntervalList::from_unsorted(ts)
    }

    /// [`Self::angles_to_parameters`] in place, before the sort and merge.
    fn angles_to_parameters_in_place(angles: &mut [Interval], omega: f64, range: Interval) {
        let (a, b) = (omega * range.lo, omega * range.hi);
        let to_t = |phi: f64| {
            if phi == a {
                range.lo
            } else if phi == b {
                range.hi
            } else {
                (phi / omega).clamp(range.lo, range.hi)
            }
        };
        for iv in angles.iter_mut() {
            let (x, y) = (to_t(iv.lo), to_t(iv.hi));
            *iv = Interval {
                lo: x.min(y),
                hi: x.max(y),
            };
        }
    }

    /// The angle window of a rotation and how far the whole turn reaches beyond it.
    fn rotation_window(range: Interval, omega: f64) -> Result<(Interval, f64), OracleError> {
        if !range.is_bounded() {
            return Err(OracleError::Unsupported(
                "polygons: a rotation over an unbounded range".into(),
            ));
        }
        let (a, b) = (omega * range.lo, omega * range.hi);
        let (lo, hi) = (a.min(b), a.max(b));
        if hi - lo > MAX_TURNS * TAU {
            return Err(OracleError::Unsupported(format!(
                "polygons: a rotation of more than {MAX_TURNS} turns"
            )));
        }
        Ok((
            Interval {
                lo,
                hi: hi.min(lo + TAU),
            },
            hi,
        ))
    }
}

impl CollisionOracle for Polygons {
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        with_scratch(|s| match self.collect(motion, s, counts)? {
            None => Ok(s.hits.to_list(motion.range)),
            Some(omega) => Ok(Self::angles_to_parameters(&s.turns, omega, motion.range)),
        })
    }

    fn intervals_into(
        &self,
        motion: &Motion,
        out: &mut IntervalList,
        _ws: &mut Workspace,
        counts: &mut CallCounts,
    ) -> Result<(), OracleError> {
        with_scratch(|s| {
            match self.collect(motion, s, counts)? {
                None => s.hits.write_into(out, motion.range),
                Some(omega) => {
                    Self::angles_to_parameters_in_place(&mut s.turns, omega, motion.range);
                    out.set_from_unsorted(&mut s.turns);
                }
            }
            Ok(())
        })
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        if q.len() != 3 || !q.iter().all(|v| v.is_finite()) {
            // not a configuration of this scene: never call it free
            return true;
        }
        with_scratch(|s| {
            translation::sweep(
                self,
                [q[0], q[1]],
                q[2],
                [0.0, 0.0],
                Interval { lo: 0.0, hi: 0.0 },
                &mut counts.pairs_tested,
                &mut s.trans,
                &mut |_| ControlFlow::Break(()),
            )
            .is_break()
        })
    }

    fn motion_is_free(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<bool, OracleError> {
        let mut stop = |_| ControlFlow::Break(());
        let kind = Self::classify(motion)?;
        let flow = with_scratch(|s| match kind {
            Kind::Translation { centre, theta, m } => Ok(translation::sweep(
                self,
                centre,
                theta,
                m,
                motion.range,
                &mut counts.pairs_tested,
                &mut s.trans,
                &mut stop,
            )),
            Kind::Rotation {
                centre,
                theta,
                omega,
            } => {
                let (window, _) = Self::rotation_window(motion.range, omega)?;
                Ok(rotation::sweep(
                    self,
                    centre,
                    theta,
                    window,
                    &mut counts.pairs_tested,
                    &mut s.rot,
                    &mut stop,
                ))
            }
        })?;
        Ok(flow.is_continue())
    }
}
