//! Conservative advancement ahead of the exact sweep of a single-joint move (so that
//! a move is answered in microseconds, not milliseconds).
//!
//! Most of a move's link–obstacle pairs stay well apart for most of the move, yet the exact
//! sweep must look at every pair of faces whose cylindrical boxes meet, and near an object
//! (a hand above a table) that is many pairs over the whole turn. A separating plane proves
//! a stretch of the move free at once: if the moving link's vertices lie at least `gap` on one
//! side of a plane with normal `n` and the other body's on the other side, a turn by `θ` about
//! an axis `a` moves no vertex towards the plane by more than `2 |sin(θ/2)| |n⊥| ρ ≤ |θ| |n⊥| ρ`
//! (`n⊥`: `n` without its component along `a`; `ρ`: a bound on the vertices' distances from
//! the axis; the displacement `(R(θ) − I) u` lies in the plane across the axis and has length
//! `2 |sin(θ/2)| |u⊥|`), and a slide by `s` moves every vertex by `|n · s|`. So the pair is free
//! for `|θ| < (gap − margin) / (|n⊥| ρ)`; from there a new plane is sought (Mirtich's
//! conservative advancement, with the whole rigid motion's bound instead of a velocity).
//!
//! The plane's normal is GJK's separating direction between the convex hulls (parry's simplex,
//! the support found by climbing the hull's edges from a cube map's guess, [`Starts`]), but the
//! gap is then measured with the exact support over the bodies' own vertices (all but those
//! clearly inside the hull), as the dot products round: the proof does not depend on GJK's
//! accuracy. The exact support scans only the runs of vertices whose ball reaches beyond the
//! best vertex found ([`Leaf`]): the same maximum, a fraction of the dot products.
//!
//! What the advancement cannot prove from either end, a window `[lo, hi]` of the move, is left
//! to the exact sweep, which finds the same pieces there (outside the window the bodies stay
//! `margin` apart, far beyond the exact predicate's slack): the answers do not change, only
//! the work.

use crate::interval::Interval;
use nalgebra::{Isometry3, Point3, Translation3, Unit, UnitQuaternion, Vector3};
use parry3d_f64::query::gjk::{CSOPoint, VoronoiSimplex};
use parry3d_f64::shape::SupportMap;

/// Planes sought from each end of a move before the rest is left to the exact sweep: a pair
/// that stays close (a finger beside a shelf) would otherwise advance in ever smaller steps.
const MAX_STEPS: usize = 8;

/// A body's vertices (in its own frame) that its support function needs: the vertices of
/// its convex hull and any vertex the hull's faces do not clearly hold (all of them if the
/// hull is not a closed surface). The support in any direction is the whole body's, so the
/// gap that proves does not depend on the hull's accuracy.
#[derive(Clone, Debug)]
pub(crate) struct Cloud {
    vertices: Vec<Point3<f64>>,
    /// `vertices` in runs of at most [`LEAF`], each with a ball that holds it ([`Leaf`]).
    leaves: Vec<Leaf>,
    /// The hull's vertices and, per vertex, its neighbours along the hull's edges
    /// (`offsets[i]..offsets[i + 1]` in `neighbours`; empty without a closed hull): GJK's
    /// support by hill climbing.
    hull: Vec<Point3<f64>>,
    offsets: Vec<u32>,
    neighbours: Vec<u32>,
    /// Where a climb starts ([`Starts`]; empty for small hulls, where any start is near).
    starts: Starts,
}

/// Cells per side of each face of the cube map of [`Starts`].
const CELLS: usize = 8;
/// Hulls with fewer vertices than this climb from wherever the last climb ended.
const MAP_FROM: usize = 32;

/// A cube map of directions to hull vertices: per cell of each face of the cube `[-1, 1]³`,
/// the hull's support in the direction of the cell's centre. A climb toward `d` starts at the
/// vertex of `d`'s cell, a step or two from the top, when that is higher than where the last
/// climb ended (GJK's directions swing; bookshelf_thin's workcell requests: 0.97× the
/// instructions). Only where a climb starts changes, so the support found does not.
#[derive(Clone, Debug, Default)]
struct Starts(Vec<u32>);

impl Starts {
    /// The cell of direction `d` (not zero): the face of its largest coordinate and the other
    /// two coordinates scaled into `[-1, 1]`.
    fn cell(d: &Vector3<f64>) -> usize {
        let a = d.abs();
        let (axis, u, v) = if a.x >= a.y && a.x >= a.z {
            (0, d.y / a.x, d.z / a.x)
        } else if a.y >= a.z {
            (1, d.z / a.y, d.x / a.y)
        } else {
            (2, d.x / a.z, d.y / a.z)
        };
        let face = 2 * axis + usize::from(d[axis] < 0.0);
        let bin = |w: f64| (((w + 1.0) * 0.5 * CELLS as f64) as usize).min(CELLS - 1);
        (face * CELLS + bin(u)) * CELLS + bin(v)
    }

    /// The map of `hull` (empty below [`MAP_FROM`] vertices).
    fn of(hull: &[Point3<f64>]) -> Starts {
        if hull.len() < MAP_FROM {
            return Starts::default();
        }
        let centre = |i: usize| (i as f64 + 0.5) / CELLS as f64 * 2.0 - 1.0;
        let mut map = vec![0u32; 6 * CELLS * CELLS];
        for face in 0..6 {
            let (axis, sign) = (face / 2, if face % 2 == 0 { 1.0 } else { -1.0 });
            for i in 0..CELLS {
                for j in 0..CELLS {
                    let mut d = Vector3::zeros();
                    d[axis] = sign;
                    d[(axis + 1) % 3] = centre(i);
                    d[(axis + 2) % 3] = centre(j);
                    let best = (0..hull.len())
                        .max_by(|&a, &b| d.dot(&hull[a].coords).total_cmp(&d.dot(&hull[b].coords)))
                        .unwrap_or(0);
                    map[Starts::cell(&d)] = best as u32;
                }
            }
        }
        Starts(map)
    }
}

/// Vertices per leaf of a [`Cloud`]'s exact support.
const LEAF: usize = 16;

/// A run `start..end` of a cloud's vertices and a ball that holds them: no vertex of the run
/// lies farther along a unit direction `d` than `d · centre + radius`.
#[derive(Clone, Copy, Debug)]
struct Leaf {
    centre: Vector3<f64>,
    radius: f64,
    start: u32,
    end: u32,
}

/// `points` reordered into runs of at most [`LEAF`] that lie close together (halved at the
/// median of their box's longest side), and the runs' leaves.
fn leaves_of(mut points: Vec<Point3<f64>>) -> (Vec<Point3<f64>>, Vec<Leaf>) {
    fn split(points: &mut [Point3<f64>], offset: usize, out: &mut Vec<Leaf>) {
        let (lo, hi) = points.iter().fold(
            (
                Vector3::repeat(f64::INFINITY),
                Vector3::repeat(f64::NEG_INFINITY),
            ),
            |(lo, hi), p| (lo.inf(&p.coords), hi.sup(&p.coords)),
        );
        if points.len() <= LEAF {
            let centre = (lo + hi) / 2.0;
            let radius = points
                .iter()
                .map(|p| (p.coords - centre).norm())
                .fold(0.0, f64::max);
            out.push(Leaf {
                centre,
                // a relative margin for the rounding of the bound's dot product
                radius: radius * (1.0 + 1e-9) + 1e-12 * (1.0 + centre.norm()),
                start: offset as u32,
                end: (offset + points.len()) as u32,
            });
            return;
        }
        let axis = (hi - lo).imax();
        let mid = points.len() / 2;
        points.select_nth_unstable_by(mid, |a, b| a[axis].total_cmp(&b[axis]));
        let (left, right) = points.split_at_mut(mid);
        split(left, offset, out);
        split(right, offset + mid, out);
    }
    let mut leaves = Vec::new();
    split(&mut points, 0, &mut leaves);
    (points, leaves)
}

/// The exact support: a vertex of greatest `dir · v` as the dot products round, found by
/// scanning the leaf of the highest bound, then only the leaves whose bound reaches the best so
/// far (the bounds' margin covers the rounding, so a leaf left out holds no higher vertex).
impl SupportMap for Cloud {
    fn local_support_point(&self, dir: &Vector3<f64>) -> Point3<f64> {
        let scale = dir.norm();
        let bound = |l: &Leaf| dir.dot(&l.centre) + l.radius * scale;
        let mut best = self.vertices[0];
        let mut top = dir.dot(&best.coords);
        let scan = |l: &Leaf, best: &mut Point3<f64>, top: &mut f64| {
            for p in &self.vertices[l.start as usize..l.end as usize] {
                let d = dir.dot(&p.coords);
                if d > *top {
                    *top = d;
                    *best = *p;
                }
            }
        };
        let first = self
            .leaves
            .iter()
            .map(bound)
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i);
        if let Some(f) = first {
            scan(&self.leaves[f], &mut best, &mut top);
        }
        for (i, l) in self.leaves.iter().enumerate() {
            if Some(i) != first && bound(l) >= top {
                scan(l, &mut best, &mut top);
            }
        }
        best
    }
}

/// GJK's support while it searches: a climb along the hull's edges from where the last one
/// ended (a linear function's local maximum on a convex polytope is its maximum, so this is
/// the hull's support up to rounding; the gap that proves is measured with the exact one).
struct Climb<'a> {
    cloud: &'a Cloud,
    at: std::cell::Cell<u32>,
}

impl<'a> Climb<'a> {
    fn new(cloud: &'a Cloud) -> Self {
        Climb {
            cloud,
            at: std::cell::Cell::new(0),
        }
    }
}

impl SupportMap for Climb<'_> {
    fn local_support_point(&self, dir: &Vector3<f64>) -> Point3<f64> {
        let c = self.cloud;
        if c.offsets.is_empty() {
            return c.local_support_point(dir);
        }
        let mut i = self.at.get() as usize;
        let mut top = dir.dot(&c.hull[i].coords);
        if let Some(&m) = c.starts.0.get(Starts::cell(dir)) {
            let d = dir.dot(&c.hull[m as usize].coords);
            if d > top {
                (i, top) = (m as usize, d);
            }
        }
        loop {
            let mut moved = false;
            for &j in &c.neighbours[c.offsets[i] as usize..c.offsets[i + 1] as usize] {
                let d = dir.dot(&c.hull[j as usize].coords);
                if d > top {
                    top = d;
                    i = j as usize;
                    moved = true;
                }
            }
            if !moved {
                break;
            }
        }
        self.at.set(i as u32);
        c.hull[i]
    }
}

/// How far inside every face of the hull, relative to the body's size, a vertex must lie to be
/// left out of its cloud.
const INSIDE: f64 = 1e-9;

/// Points sorted and without repeats.
fn sorted(mut points: Vec<Point3<f64>>) -> Vec<Point3<f64>> {
    points.sort_by(|a, b| {
        a.coords
            .as_slice()
            .partial_cmp(b.coords.as_slice())
            .unwrap()
    });
    points.dedup();
    points
}

impl Cloud {
    /// The cloud of a mesh's vertices (`None` without any, or with one not finite).
    pub(crate) fn of(vertices: &[Point3<f64>]) -> Option<Cloud> {
        if vertices.is_empty()
            || vertices
                .iter()
                .any(|v| !v.coords.iter().all(|c| c.is_finite()))
        {
            return None;
        }
        let all = sorted(vertices.to_vec());
        let plain = |all: Vec<Point3<f64>>| {
            let (vertices, leaves) = leaves_of(all);
            Cloud {
                vertices,
                leaves,
                hull: Vec::new(),
                offsets: Vec::new(),
                neighbours: Vec::new(),
                starts: Starts::default(),
            }
        };
        let Ok((hull, faces)) = parry3d_f64::transformation::try_convex_hull(&all) else {
            return Some(plain(all));
        };
        // a closed surface: every edge in exactly two faces, once each way
        let mut edges: Vec<(u32, u32)> = faces
            .iter()
            .flat_map(|f| [(f[0], f[1]), (f[1], f[2]), (f[2], f[0])])
            .collect();
        edges.sort_unstable();
        let closed = !faces.is_empty()
            && edges.windows(2).all(|w| w[0] != w[1])
            && edges
                .iter()
                .all(|&(a, b)| edges.binary_search(&(b, a)).is_ok())
            && edges.iter().all(|&(a, _)| (a as usize) < hull.len());
        if !closed {
            return Some(plain(all));
        }
        let centre = hull.iter().map(|p| p.coords).sum::<Vector3<f64>>() / hull.len() as f64;
        let size = all
            .iter()
            .map(|p| (p.coords - centre).norm())
            .fold(0.0, f64::max);
        let planes: Vec<(Vector3<f64>, f64)> = faces
            .iter()
            .filter_map(|f| {
                let [a, b, c] = f.map(|i| hull[i as usize].coords);
                let n = (b - a).cross(&(c - a));
                let len = n.norm();
                (len > 0.0).then(|| {
                    let n = n / len;
                    // outwards: the centre of the hull's vertices lies inside
                    if n.dot(&(centre - a)) > 0.0 {
                        (-n, -n.dot(&a))
                    } else {
                        (n, n.dot(&a))
                    }
                })
            })
            .collect();
        let held = |v: &Point3<f64>| {
            planes
                .iter()
                .all(|(n, d)| n.dot(&v.coords) - d <= -INSIDE * size)
        };
        let mut kept = hull.clone();
        kept.extend(all.iter().filter(|v| !held(v)));
        // the hull's edges, each way, grouped by their first vertex (`edges` is sorted)
        let mut offsets = vec![0u32; hull.len() + 1];
        for &(a, _) in &edges {
            offsets[a as usize + 1] += 1;
        }
        for i in 0..hull.len() {
            offsets[i + 1] += offsets[i];
        }
        let (vertices, leaves) = leaves_of(sorted(kept));
        Some(Cloud {
            vertices,
            leaves,
            starts: Starts::of(&hull),
            hull,
            offsets,
            neighbours: edges.iter().map(|&(_, b)| b).collect(),
        })
    }
}

/// A single-joint move of a rigid body in the world, `t ∈ [0, 1]`.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Move {
    /// A turn by `t · angle` about the unit `axis` through `pivot`.
    Turn {
        pivot: Vector3<f64>,
        axis: Vector3<f64>,
        angle: f64,
    },
    /// A slide by `t · offset`.
    Slide { offset: Vector3<f64> },
}

impl Move {
    /// How far from the axis of a turn a ball may reach (0 for a slide): a bound on every
    /// distance from the axis of a body inside the ball.
    pub(crate) fn reach(&self, centre: &Vector3<f64>, radius: f64) -> f64 {
        match self {
            Move::Turn { pivot, axis, .. } => {
                let u = centre - pivot;
                (u - axis * axis.dot(&u)).norm() + radius
            }
            Move::Slide { .. } => 0.0,
        }
    }

    /// The world motion at `t` (applied after the body's pose at `t = 0`).
    pub(crate) fn at(&self, t: f64) -> Isometry3<f64> {
        match self {
            Move::Turn { pivot, axis, angle } => {
                let r = UnitQuaternion::from_axis_angle(&Unit::new_unchecked(*axis), t * angle);
                let p = Point3::from(*pivot);
                Isometry3::rotation_wrt_point(r, p)
            }
            Move::Slide { offset } => {
                Isometry3::from_parts(Translation3::from(offset * t), UnitQuaternion::identity())
            }
        }
    }
}

/// One body moving against one body standing still, both placed in the world.
pub(crate) struct Pair<'a> {
    pub moving: &'a Cloud,
    /// The moving body's pose at `t = 0`.
    pub from: Isometry3<f64>,
    pub still: &'a Cloud,
    pub at: Isometry3<f64>,
}

/// Relative accuracy at which GJK's search for a separating direction stops: the direction
/// only has to prove, not to measure.
const ROUGH: f64 = 0.05;
/// GJK steps at most, per direction sought.
const GJK_STEPS: usize = 32;

/// A direction `n` (unit, in body 1's frame, from body 1 towards body 2) and the gap along it
/// between body 1 and body 2 placed at `pos12` in body 1's frame: `min n · x₂ − max n · x₁`
/// over the clouds' vertices, as the dot products round (so a positive gap proves the bodies
/// apart whatever GJK's accuracy). Stops as soon as the gap exceeds `enough`; `None` when no
/// positive gap was found (the hulls meet).
fn gap(
    pos12: &Isometry3<f64>,
    a: &Climb<'_>,
    b: &Climb<'_>,
    init: Option<Vector3<f64>>,
    enough: f64,
    simplex: &mut VoronoiSimplex,
) -> Option<(Vector3<f64>, f64)> {
    let start = init
        .and_then(|d| Unit::try_new(d, 1e-12))
        .or_else(|| Unit::try_new(-pos12.translation.vector, 1e-12))
        .unwrap_or_else(Vector3::x_axis);
    simplex.reset(CSOPoint::from_shapes(pos12, a, b, &start));
    let mut best: Option<(Unit<Vector3<f64>>, f64)> = None;
    for _ in 0..GJK_STEPS {
        let proj = simplex.project_origin_and_reduce();
        if simplex.dimension() == 3 {
            // the origin lies in the tetrahedron: the hulls meet
            break;
        }
        let Some((dir, upper)) = Unit::try_new_and_get(-proj.coords, 1e-15) else {
            break;
        };
        let p = CSOPoint::from_shapes(pos12, a, b, &dir);
        let lower = -dir.dot(&p.point.coords);
        if lower > best.map_or(0.0, |(_, g)| g) {
            best = Some((dir, lower));
        }
        if lower > enough || upper - lower <= ROUGH * upper || !simplex.add_point(p) {
            break;
        }
    }
    // the gap along the best direction, by the exact supports
    let (dir, _) = best?;
    let p = CSOPoint::from_shapes(pos12, a.cloud, b.cloud, &dir);
    Some((dir.into_inner(), -dir.dot(&p.point.coords))).filter(|(_, g)| *g > 0.0)
}

/// Whether the clouds at these world poses are more than `margin` apart (a static pair's test
/// before its exact one).
pub(crate) fn apart(
    a: &Cloud,
    pose_a: &Isometry3<f64>,
    b: &Cloud,
    pose_b: &Isometry3<f64>,
    margin: f64,
) -> bool {
    let mut simplex = VoronoiSimplex::new();
    let (a, b) = (Climb::new(a), Climb::new(b));
    gap(&pose_a.inv_mul(pose_b), &a, &b, None, margin, &mut simplex)
        .is_some_and(|(_, g)| g > margin)
}

/// How far a multi-joint motion may carry two bodies towards each other, from a moment on:
/// at most `rate + growth · σ` per unit of `t` after `σ` more of it (the rate at that moment,
/// and how fast the rate itself may grow).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Speed {
    pub rate: f64,
    pub growth: f64,
    /// How the two bodies move at that moment, for a bound along the plane's normal
    /// ([`Along`]); `None` where it is not known (a prismatic joint moves one of them).
    pub along: Option<Along>,
}

/// How two bodies move at a moment: each one's ball's centre's velocity, its angular velocity
/// and the ball's radius (in one frame, the world's or one both move in), and a bound on the
/// acceleration of their points relative to each other over the whole motion. Along a
/// direction `n` their points then close in at most `Σ |n · velocity| + radius |n × spin|` per
/// unit of `t`, plus `accel` per unit of `t` elapsed since: the motion's own speed toward the
/// plane, not the sum of every joint's worst case.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Along {
    pub bodies: [Moving; 2],
    pub accel: f64,
}

/// One body of [`Along`]: its ball's centre's velocity, its angular velocity, the ball's
/// radius.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Moving {
    pub velocity: Vector3<f64>,
    pub spin: Vector3<f64>,
    pub radius: f64,
}

impl Speed {
    /// How much of `t` it takes to close a gap `g`: the least `s` with `rate · s + growth ·
    /// s² / 2 = g` (infinite where nothing moves).
    fn time_to_close(&self, g: f64) -> f64 {
        let (a, b) = (self.rate, self.growth);
        if b > 0.0 {
            2.0 * g / (a + (a * a + 2.0 * b * g).sqrt())
        } else if a > 0.0 {
            g / a
        } else {
            f64::INFINITY
        }
    }
}

/// Whether two bodies stay more than `margin` apart for all `t` in `range` while `at(t)` places
/// them (world poses of `a` and of `b`) and says how fast they may approach each other from
/// there ([`Speed`]; `fastest` bounds the rate over the whole motion): a separating plane at
/// the middle, then planes from both ends of what it leaves in turn, each proving the pair
/// apart until the bodies could have crossed its gap (a multi-joint motion,
/// [`super::oracle`]'s straight motions). A plane proves both
/// ways from its moment, so each front places its next plane ahead by the radius it last
/// proved (twice the reach per plane while the gap stays alike; where it falls short, what it
/// proved is joined once the front gets there). `false` when a plane cannot be found (the
/// hulls come within `margin`), when a look between stalling fronts finds them within `margin`
/// (no plane could pass there: the same answer, sooner), or when `max_steps` planes do not
/// meet in the middle (near contact the steps shrink): not proved, which is not a collision
/// found.
pub(crate) fn apart_along(
    a: &Cloud,
    b: &Cloud,
    at: &mut dyn FnMut(f64) -> (Isometry3<f64>, Isometry3<f64>, Speed),
    range: Interval,
    fastest: f64,
    margin: f64,
    max_steps: usize,
) -> bool {
    let mut planes_of = Separation {
        ca: Climb::new(a),
        cb: Climb::new(b),
        simplex: VoronoiSimplex::new(),
        fastest,
        margin,
    };
    // a plane at the middle proves twice as far as one at an end: the fronts prove what it
    // leaves on either side (if it finds no plane, they prove the whole range)
    let middle = (range.lo + range.hi) / 2.0;
    let mut first = None;
    let s = planes_of.step(at, middle, (range.hi - range.lo) / 2.0, &mut first);
    let mut planes = 1;
    if s <= 0.0 {
        return fronts(
            &mut planes_of,
            at,
            range,
            [None, None],
            &mut planes,
            max_steps,
        );
    }
    let below = Interval {
        lo: range.lo,
        hi: middle - s,
    };
    let above = Interval {
        lo: middle + s,
        hi: range.hi,
    };
    (below.lo >= below.hi
        || fronts(
            &mut planes_of,
            at,
            below,
            [None, first],
            &mut planes,
            max_steps,
        ))
        && (above.lo >= above.hi
            || fronts(
                &mut planes_of,
                at,
                above,
                [first, None],
                &mut planes,
                max_steps,
            ))
}

/// [`apart_along`]'s separating planes from both ends of `range` in turn (`dir`: the fronts'
/// first directions; `planes`: the planes sought so far, at most `max_steps`).
fn fronts(
    planes_of: &mut Separation<'_>,
    at: &mut dyn FnMut(f64) -> (Isometry3<f64>, Isometry3<f64>, Speed),
    range: Interval,
    mut dir: [Option<Vector3<f64>>; 2],
    planes: &mut usize,
    max_steps: usize,
) -> bool {
    let (mut lo, mut hi) = (range.lo, range.hi);
    // per front (0: from `lo` up, 1: from `hi` down): the last plane's direction, the last
    // radius proved, and a stretch proved ahead of it by a look that fell short
    let mut radius = [0.0f64; 2];
    let mut island: [Option<Interval>; 2] = [None, None];
    let mut round = 0.0;
    let mut probes = 0u32;
    let mut from_probe = None;
    let mut side = 0;
    while *planes < max_steps {
        let rest = hi - lo;
        let before = rest;
        // a plane proves both ways from its moment: one placed ahead of the front by the last
        // radius proves from the front twice as far while the gaps stay alike
        let ahead = radius[side];
        let mut moved = false;
        if ahead > 0.0 && ahead < rest {
            let t = if side == 0 { lo + ahead } else { hi - ahead };
            *planes += 1;
            let s = planes_of.step(at, t, (rest - ahead).max(ahead), &mut dir[side]);
            if s <= 0.0 {
                return false;
            }
            if s >= ahead {
                if side == 0 {
                    lo = t + s;
                } else {
                    hi = t - s;
                }
                radius[side] = s;
                moved = true;
            } else {
                island[side] = Some(Interval {
                    lo: t - s,
                    hi: t + s,
                });
            }
        }
        if !moved && lo < hi {
            *planes += 1;
            let t = if side == 0 { lo } else { hi };
            // the far front starts from the near front's plane: nearby moments, alike planes
            if dir[side].is_none() {
                dir[side] = dir[side ^ 1];
            }
            let s = planes_of.step(at, t, rest, &mut dir[side]);
            if s <= 0.0 {
                return false;
            }
            if side == 0 {
                lo += s;
                if let Some(i) = island[0].take().filter(|i| lo >= i.lo) {
                    lo = lo.max(i.hi);
                }
            } else {
                hi -= s;
                if let Some(i) = island[1].take().filter(|i| hi <= i.hi) {
                    hi = hi.min(i.lo);
                }
            }
            radius[side] = s;
        }
        if lo >= hi {
            return true;
        }
        round += before - (hi - lo);
        if side == 1 {
            // fronts that hardly move are closing in on a contact, which no plane can pass:
            // a look between them (hulls within the margin there) ends the proof at once
            if round < STALL * (hi - lo) {
                probes += 1;
                let t = lo + (hi - lo) * van_der_corput(probes);
                if !planes_of.apart_at(at, t, &mut from_probe) {
                    return false;
                }
            }
            round = 0.0;
        }
        side ^= 1;
    }
    false
}

/// The two bodies of [`apart_along`] and what its planes share: the bodies' support maps, the
/// GJK simplex reused from plane to plane, the bound on the rate over the whole motion and the
/// margin.
struct Separation<'a> {
    ca: Climb<'a>,
    cb: Climb<'a>,
    simplex: VoronoiSimplex,
    fastest: f64,
    margin: f64,
}

impl Separation<'_> {
    /// How far in `t` the pair is proved apart from `t` on, either way (0: not at all), by a
    /// separating plane at `t` (starting from the front's last direction `dir`, updated);
    /// `rest` is what is left to prove, which bounds the gap worth finding.
    #[inline]
    fn step(
        &mut self,
        at: &mut dyn FnMut(f64) -> (Isometry3<f64>, Isometry3<f64>, Speed),
        t: f64,
        rest: f64,
        dir: &mut Option<Vector3<f64>>,
    ) -> f64 {
        let (fastest, margin) = (self.fastest, self.margin);
        let (pa, pb, speed) = at(t);
        let pos12 = pa.inv_mul(&pb);
        let enough = fastest * rest + 2.0 * margin;
        let Some((n, g)) = gap(&pos12, &self.ca, &self.cb, *dir, enough, &mut self.simplex) else {
            return 0.0;
        };
        *dir = Some(n);
        let g = g - margin;
        if g <= 0.0 {
            return 0.0;
        }
        let by_whole = if fastest > 0.0 {
            g / fastest
        } else {
            f64::INFINITY
        };
        let along = speed.along.map_or(0.0, |m| {
            let n = pa.rotation * n;
            Speed {
                rate: m
                    .bodies
                    .iter()
                    .map(|b| n.dot(&b.velocity).abs() + b.radius * n.cross(&b.spin).norm())
                    .sum(),
                growth: m.accel,
                along: None,
            }
            .time_to_close(g)
        });
        by_whole.max(speed.time_to_close(g)).max(along)
    }

    /// Whether the hulls are more than the margin apart at `t` (a look between stalling
    /// fronts), starting from the last look's direction `from`, updated.
    fn apart_at(
        &mut self,
        at: &mut dyn FnMut(f64) -> (Isometry3<f64>, Isometry3<f64>, Speed),
        t: f64,
        from: &mut Option<Vector3<f64>>,
    ) -> bool {
        let (pa, pb, _) = at(t);
        let near = gap(
            &pa.inv_mul(&pb),
            &self.ca,
            &self.cb,
            *from,
            self.margin,
            &mut self.simplex,
        );
        match near {
            Some((n, g)) if g > self.margin => {
                *from = Some(n);
                true
            }
            _ => false,
        }
    }
}

/// A round of both fronts that proves less than this share of what is left between them is
/// taken for a stall ([`apart_along`] then looks between the fronts for a contact).
const STALL: f64 = 0.25;

/// The `k`-th point of the van der Corput sequence in base 2 (½, ¼, ¾, ⅛, …): probes that
/// spread over an interval whatever their number.
fn van_der_corput(mut k: u32) -> f64 {
    let (mut x, mut unit) = (0.0, 0.5);
    while k > 0 {
        if k & 1 == 1 {
            x += unit;
        }
        unit /= 2.0;
        k >>= 1;
    }
    x
}

/// The part of `[0, 1]` in which the pair may come within `margin` of each other during `mv`
/// (`None`: apart by more than `margin` throughout), proved from both ends by separating
/// planes. `reach`: a bound on the moving body's distances from the move's axis
/// ([`Move::reach`]; unused for a slide).
pub(crate) fn unproved(pair: &Pair<'_>, mv: &Move, reach: f64, margin: f64) -> Option<Interval> {
    let mut simplex = VoronoiSimplex::new();
    let (moving, still) = (Climb::new(pair.moving), Climb::new(pair.still));
    // how far a vertex may move towards any plane per unit of `t`
    let fastest = match mv {
        Move::Turn { angle, .. } => reach * angle.abs(),
        Move::Slide { offset } => offset.norm(),
    };
    // how far in `t` the pair is proved apart from `t` on, either way (0: not at all), with a
    // gap of `enough` proving the `rest` of the move at once
    let mut step = |t: f64, rest: f64, dir: &mut Option<Vector3<f64>>| -> f64 {
        let pose = mv.at(t) * pair.from;
        let pos12 = pose.inv_mul(&pair.at);
        let enough = fastest * rest + 2.0 * margin;
        let Some((n, g)) = gap(&pos12, &moving, &still, *dir, enough, &mut simplex) else {
            return 0.0;
        };
        *dir = Some(n);
        let g = g - margin;
        if g <= 0.0 {
            return 0.0;
        }
        let n_w = pose.rotation * n;
        let speed = match mv {
            Move::Turn { axis, angle, .. } => {
                (n_w - axis * axis.dot(&n_w)).norm() * reach * angle.abs()
            }
            Move::Slide { offset } => n_w.dot(offset).abs(),
        };
        if speed > 0.0 {
            g / speed
        } else {
            f64::INFINITY
        }
    };
    let mut dir = None;
    let mut lo = 0.0;
    for _ in 0..MAX_STEPS {
        let s = step(lo, 1.0 - lo, &mut dir);
        if s <= 0.0 {
            break;
        }
        lo += s;
        if lo >= 1.0 {
            return None;
        }
    }
    let mut hi = 1.0;
    dir = None;
    for _ in 0..MAX_STEPS {
        let s = step(hi, hi - lo, &mut dir);
        if s <= 0.0 {
            break;
        }
        hi -= s;
        if hi <= lo {
            return None;
        }
    }
    Some(Interval { lo, hi })
}

#[cfg(test)]
mod tests {
    use super::*;
    use parry3d_f64::shape::ConvexPolyhedron;
    use proptest::prelude::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A convex-ish blob: random points on a squashed sphere, and some inside.
    fn blob(rng: &mut ChaCha8Rng, size: f64) -> Vec<Point3<f64>> {
        let axes = Vector3::new(
            rng.random_range(0.3..1.0),
            rng.random_range(0.3..1.0),
            rng.random_range(0.3..1.0),
        ) * size;
        (0..40)
            .map(|i| {
                let v = Vector3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                )
                .normalize();
                let r = if i % 4 == 0 { 0.5 } else { 1.0 };
                Point3::from(v.component_mul(&axes) * r)
            })
            .collect()
    }

    /// A moving blob (size 0.3) and a still one (0.5), and their clouds.
    fn two_blobs(rng: &mut ChaCha8Rng) -> (Vec<Point3<f64>>, Vec<Point3<f64>>, Cloud, Cloud) {
        let (a, b) = (blob(rng, 0.3), blob(rng, 0.5));
        let (ca, cb) = (Cloud::of(&a).unwrap(), Cloud::of(&b).unwrap());
        (a, b, ca, cb)
    }

    /// A random vector in the cube `[-1, 1]³`.
    fn cube(rng: &mut ChaCha8Rng) -> Vector3<f64> {
        Vector3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        )
    }

    /// The independent distance: parry's convex polyhedra built from all the points.
    fn distance(
        a: &[Point3<f64>],
        pa: &Isometry3<f64>,
        b: &[Point3<f64>],
        pb: &Isometry3<f64>,
    ) -> f64 {
        let ha = ConvexPolyhedron::from_convex_hull(a).unwrap();
        let hb = ConvexPolyhedron::from_convex_hull(b).unwrap();
        parry3d_f64::query::distance(pa, &ha, pb, &hb).unwrap()
    }

    #[test]
    fn the_cloud_keeps_the_support_of_every_vertex() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for _ in 0..20 {
            let pts = blob(&mut rng, 1.0);
            let cloud = Cloud::of(&pts).unwrap();
            assert!(
                cloud.vertices.len() < pts.len(),
                "the points inside are left out"
            );
            for _ in 0..50 {
                let d = Vector3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                let want = pts
                    .iter()
                    .map(|p| d.dot(&p.coords))
                    .fold(f64::MIN, f64::max);
                assert_eq!(d.dot(&cloud.local_support_point(&d).coords), want);
            }
        }
        // the climb along the hull's edges finds the same support value
        for _ in 0..20 {
            let pts = blob(&mut rng, 1.0);
            let cloud = Cloud::of(&pts).unwrap();
            assert!(!cloud.offsets.is_empty(), "a closed hull");
            let climb = Climb::new(&cloud);
            for _ in 0..50 {
                let d = Vector3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                let want = d.dot(&cloud.local_support_point(&d).coords);
                let got = d.dot(&climb.local_support_point(&d).coords);
                assert!((want - got).abs() <= 1e-12, "{want} {got}");
            }
        }
        // hulls of hundreds of vertices: the exact support's leaves and the climbs' cube map
        for _ in 0..5 {
            // on an ellipsoid: every point a vertex of the hull
            let axes = Vector3::new(1.0, rng.random_range(0.2..1.0), rng.random_range(0.2..1.0));
            let pts: Vec<Point3<f64>> = (0..400)
                .map(|_| Point3::from(cube(&mut rng).normalize().component_mul(&axes)))
                .collect();
            let cloud = Cloud::of(&pts).unwrap();
            assert!(cloud.leaves.len() > 4 && !cloud.starts.0.is_empty());
            let climb = Climb::new(&cloud);
            for _ in 0..200 {
                let d = cube(&mut rng);
                let want = pts
                    .iter()
                    .map(|p| d.dot(&p.coords))
                    .fold(f64::MIN, f64::max);
                assert_eq!(d.dot(&cloud.local_support_point(&d).coords), want);
                let got = d.dot(&climb.local_support_point(&d).coords);
                assert!((want - got).abs() <= 1e-12, "{want} {got}");
            }
        }
        assert!(Cloud::of(&[]).is_none());
        assert!(Cloud::of(&[Point3::new(f64::NAN, 0.0, 0.0)]).is_none());
        // flat: no closed hull, every point kept
        let flat: Vec<_> = (0..5)
            .map(|i| Point3::new(i as f64, (i * i) as f64, 0.0))
            .collect();
        assert_eq!(Cloud::of(&flat).unwrap().vertices.len(), 5);
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

        /// Outside the window left unproved, the bodies stay more than `margin` apart at every
        /// sampled `t` (parry's distance between the hulls of all the points).
        #[test]
        fn outside_the_window_the_bodies_are_apart(
            seed in 0u64..1_000_000,
            slide in any::<bool>(),
            angle in -6.0f64..6.0,
        ) {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let (a, b, ca, cb) = two_blobs(&mut rng);
            let mut v = || cube(&mut rng);
            let from = Isometry3::new(v() * 1.5, v());
            let at = Isometry3::new(v() * 0.5, v());
            let mv = if slide {
                Move::Slide { offset: v() * 3.0 }
            } else {
                Move::Turn { pivot: v() * 0.3, axis: v().normalize(), angle }
            };
            let reach = match mv {
                Move::Turn { pivot, axis, .. } => a
                    .iter()
                    .map(|p| {
                        let u = (from * p).coords - pivot;
                        (u - axis * axis.dot(&u)).norm()
                    })
                    .fold(0.0, f64::max),
                Move::Slide { .. } => 0.0,
            };
            let margin = 1e-3;
            let pair = Pair { moving: &ca, from, still: &cb, at };
            let w = unproved(&pair, &mv, reach, margin);
            for i in 0..=400 {
                let t = i as f64 / 400.0;
                if w.is_some_and(|w| w.lo <= t && t <= w.hi) {
                    continue;
                }
                let d = distance(&a, &(mv.at(t) * from), &b, &at);
                prop_assert!(d > margin * 0.999, "t = {t}: distance {d}, window {w:?}");
            }
        }
    }

    /// A screw motion of body `a` from `from` (turning by `angle` about `axis` through the
    /// origin while sliding by `offset`), as [`apart_along`] asks for it: the poses at `t`
    /// and the bounds on how fast `a`'s points approach the still body `b`, with the motion's
    /// own velocities ([`Along`]) if `along`. `reach`: the largest norm of `a`'s points in its
    /// frame; `centre`, `radius`: a ball holding them.
    #[allow(clippy::too_many_arguments)]
    fn screw(
        from: Isometry3<f64>,
        axis: Unit<Vector3<f64>>,
        angle: f64,
        offset: Vector3<f64>,
        reach: f64,
        centre: Point3<f64>,
        radius: f64,
        along: bool,
    ) -> impl FnMut(f64) -> (Isometry3<f64>, Isometry3<f64>, Speed) {
        move |t| {
            let pose = Translation3::from(offset * t)
                * UnitQuaternion::from_axis_angle(&axis, angle * t)
                * from;
            let c = pose * centre;
            // a point of `a` lies at most `reach + |from|` from the axis' origin
            let far = reach + from.translation.vector.norm();
            let speed = Speed {
                rate: offset.norm() + angle.abs() * far,
                growth: 0.0,
                along: along.then(|| Along {
                    bodies: [
                        Moving {
                            // the turn is about the axis through the origin before the
                            // slide: the centre's lever arm leaves the slide out
                            velocity: offset + axis.cross(&(c.coords - offset * t)) * angle,
                            spin: axis.into_inner() * angle,
                            radius,
                        },
                        Moving::default(),
                    ],
                    accel: angle * angle * far,
                }),
            };
            (pose, Isometry3::identity(), speed)
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

        /// A pair [`apart_along`] proves apart over a screw motion is more than `margin` apart
        /// at every sampled `t` (parry's distance between the hulls of all the points), with
        /// the bound along the planes' normals or without.
        #[test]
        fn a_motion_proved_apart_stays_apart(
            seed in 0u64..1_000_000,
            along in any::<bool>(),
            angle in -4.0f64..4.0,
        ) {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let (a, b, ca, cb) = two_blobs(&mut rng);
            let mut v = || cube(&mut rng);
            let from = Isometry3::new(v() * 1.5, v());
            let (axis, offset) = (Unit::new_normalize(v()), v() * 2.0);
            let reach = a.iter().map(|p| p.coords.norm()).fold(0.0, f64::max);
            let centre = Point3::origin();
            let mut at = screw(from, axis, angle, offset, reach, centre, reach, along);
            let fastest = offset.norm() + angle.abs() * (reach + from.translation.vector.norm());
            let margin = 1e-3;
            let proved = apart_along(&ca, &cb, &mut at, Interval { lo: 0.0, hi: 1.0 }, fastest, margin, 128);
            if proved {
                for i in 0..=400 {
                    let t = i as f64 / 400.0;
                    let (pa, pb, _) = at(t);
                    let d = distance(&a, &pa, &b, &pb);
                    prop_assert!(d > margin * 0.999, "t = {t}: distance {d}");
                }
            }
        }
    }

    /// The property above is not vacuous, and the bound along the normals proves with fewer
    /// planes: over seeded screw motions that pass near the still body or through it, those
    /// through it are never proved, and with 8 planes [`Along`] proves many more of the others
    /// (the motion's own speed toward each plane, not its worst case).
    #[test]
    fn screw_motions_are_proved_and_refused() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let (mut plain, mut with_along, mut through, mut refused) = (0, 0, 0, 0);
        // few planes: the bound along the normals proves with fewer
        const PLANES: usize = 8;
        for _ in 0..300 {
            let (a, b, ca, cb) = two_blobs(&mut rng);
            let mut v = || cube(&mut rng);
            let from = Isometry3::new(Vector3::new(-2.0, 0.0, 0.0) + v() * 0.2, v());
            // across the still body, passing it at some height
            let offset = Vector3::new(4.0, 0.0, 0.0) + v() * 0.2 + Vector3::z() * 1.2 * v().z;
            let (axis, angle) = (Unit::new_normalize(v()), v().x);
            let reach = a.iter().map(|p| p.coords.norm()).fold(0.0, f64::max);
            let fastest = offset.norm() + angle.abs() * (reach + from.translation.vector.norm());
            let run = |along: bool| {
                let mut at = screw(
                    from,
                    axis,
                    angle,
                    offset,
                    reach,
                    Point3::origin(),
                    reach,
                    along,
                );
                apart_along(
                    &ca,
                    &cb,
                    &mut at,
                    Interval { lo: 0.0, hi: 1.0 },
                    fastest,
                    1e-3,
                    PLANES,
                )
            };
            let (p, w) = (run(false), run(true));
            let mut at = screw(
                from,
                axis,
                angle,
                offset,
                reach,
                Point3::origin(),
                reach,
                false,
            );
            let touches = (0..=400).any(|i| {
                let (pa, pb, _) = at(i as f64 / 400.0);
                distance(&a, &pa, &b, &pb) <= 1e-3
            });
            assert!(
                !(touches && (p || w)),
                "a motion through the body proved apart"
            );
            through += usize::from(touches);
            plain += usize::from(p);
            with_along += usize::from(w);
            refused += usize::from(!w && !touches);
        }
        assert!(
            through > 30 && plain > 30,
            "through {through}, proved {plain}"
        );
        assert!(
            with_along > plain + 30,
            "with the normals' bound {with_along}, without {plain}"
        );
        assert!(refused < 20, "{refused} motions that pass refused");
    }

    /// The property above is not vacuous: over seeded moves, some are proved free throughout,
    /// some in part, and some not at all near their start.
    #[test]
    fn moves_are_proved_free_in_whole_in_part_and_not_at_all() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let (mut whole, mut part, mut none) = (0, 0, 0);
        for _ in 0..300 {
            let (_, _, ca, cb) = two_blobs(&mut rng);
            let mut v = || cube(&mut rng);
            let from = Isometry3::new(v(), v());
            let at = Isometry3::new(v() * 0.5, v());
            let axis = v().normalize();
            let mv = Move::Turn {
                pivot: Vector3::zeros(),
                axis,
                angle: 3.0,
            };
            let c = from.translation.vector;
            let reach = (c - axis * axis.dot(&c)).norm() + 0.6;
            match unproved(
                &Pair {
                    moving: &ca,
                    from,
                    still: &cb,
                    at,
                },
                &mv,
                reach,
                1e-6,
            ) {
                None => whole += 1,
                Some(w) if w.lo > 0.0 || w.hi < 1.0 => part += 1,
                Some(_) => none += 1,
            }
        }
        assert!(
            whole >= 20 && part >= 20 && none >= 5,
            "{whole} {part} {none}"
        );
    }
}
