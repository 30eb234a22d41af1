//! Containment: one body wholly inside the other (CHS §2.1, §2.2, §2.3.2), decided only when
//! both meshes are closed.
//!
//! Static (CHS §2.1): a point `v` of P lies in Q iff a ray from `v` crosses Q's surface an odd
//! number of times; if the ray meets an edge or a vertex of Q, or runs inside a face's plane,
//! another direction (and another point) is tried. An odd count means `v ∈ P ∩ Q`; `P ⊂ Q`
//! implies it, so together with the surface test this decides overlap.
//!
//! Translation (CHS §2.2): the line `v + λ r` through the point along the motion crosses Q's
//! faces at sorted `λ_1 < λ_2 < …`; since `v^{±∞} ∉ Q`, the point is inside exactly on
//! `[λ_1, λ_2] ∪ [λ_3, λ_4] ∪ …`. The point is taken inside a face, not at a vertex, so that a
//! degeneracy can be escaped by moving it ("not every point of such a triangle can collide with
//! an edge or vertex of Q").
//!
//! Rotation (CHS §2.3.2): the circle the point describes crosses Q's faces where
//! `n·v_φ − c = 0`, an atom of the rotational kind; the state at the start of the turn comes
//! from a ray, and every crossing toggles it. Tangent crossings and crossings at edges are
//! degeneracies and make us try another point.
//!
//! Both directions are tested (P in Q and Q in P), with one point per connected piece. Parity
//! counts every face as often as the mesh lists it ([`super::body`]): double-sided sheets
//! cancel out. Should every attempt be degenerate — never seen in practice — the whole window
//! in which the boxes meet is reported as collision: more collision, never less.

use super::body::{Component, Face, Part};
use super::envelope::AngleRange;
use super::model::Polyhedra;
use super::pose::{Aabb, Pose};
use super::turning::{box_corner, lin, swept_box, turn};
use crate::geometry::kernel::hits::Hits;
use crate::geometry::kernel::trig::Zeros;
use crate::interval::Interval;
use crate::oracle::CallCounts;
use nalgebra::Vector3;
use std::f64::consts::TAU;
use std::ops::ControlFlow;

type V3 = Vector3<f64>;

/// Points (with fresh ray directions) tried before giving up on a degenerate configuration.
const ATTEMPTS: u64 = 24;
/// Degeneracy margin as a multiple of the oracle's distance tolerance.
const MARGIN: f64 = 100.0;

/// A part's parity faces with the coordinates they live in.
#[derive(Clone, Copy)]
struct View<'a> {
    vertices: &'a [V3],
    part: &'a Part,
}

impl View<'_> {
    fn face(&self, i: u32) -> Face {
        Face::new(self.part.parity[i as usize].map(|k| self.vertices[k as usize]))
    }
}

/// Where a line meets a face.
enum Cross {
    /// At parameter `s`, strictly inside the face.
    Hit(f64),
    Miss,
    /// Too close to an edge, a vertex, or the face's plane to tell.
    Degenerate,
}

/// Classifies the signed distances `d_i` of a point (or line) from the three edges of a face:
/// all clearly of one sign → inside, some clearly of both signs → outside, else degenerate.
fn classify(d: [f64; 3], margin: f64) -> Cross {
    if d.iter().all(|&x| x > margin) || d.iter().all(|&x| x < -margin) {
        Cross::Hit(0.0)
    } else if d.iter().any(|&x| x > margin) && d.iter().any(|&x| x < -margin) {
        Cross::Miss
    } else if d.iter().all(|&x| x >= -margin) || d.iter().all(|&x| x <= margin) {
        Cross::Degenerate
    } else {
        Cross::Miss
    }
}

/// The line `x0 + s·u` against a face.
fn line_face(x0: &V3, u: &V3, f: &Face, margin: f64, parallel: f64) -> Cross {
    let nn = f.n_norm;
    let denom = f.n.dot(u);
    if denom.abs() <= parallel * nn * u.norm() {
        return if (f.n.dot(x0) - f.offset).abs() <= margin * nn {
            Cross::Degenerate
        } else {
            Cross::Miss
        };
    }
    // the line passes through the face iff it passes on the same side of all three edges
    let e = f.edges();
    let mut d = [0.0; 3];
    for i in 0..3 {
        let w = u.cross(&e[i]);
        let wn = w.norm();
        if wn == 0.0 {
            return Cross::Degenerate;
        }
        d[i] = w.dot(&(x0 - f.v[i])) / wn;
    }
    match classify(d, margin) {
        Cross::Hit(_) => Cross::Hit((f.offset - f.n.dot(x0)) / denom),
        c => c,
    }
}

/// A point `h` in the plane of a face: inside, outside, or on its boundary.
fn point_in_face(h: &V3, f: &Face, margin: f64) -> Cross {
    let e = f.edges();
    let mut d = [0.0; 3];
    for i in 0..3 {
        let w = f.n.cross(&e[i]);
        d[i] = w.dot(&(h - f.v[i])) / w.norm();
    }
    classify(d, margin)
}

/// A well-spread pseudo-random 64-bit value (splitmix64).
fn mix(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}

fn unit(x: u64) -> f64 {
    (mix(x) >> 11) as f64 / (1u64 << 53) as f64
}

/// A pseudo-random direction for attempt `k`.
fn direction(k: u64) -> V3 {
    let z = 2.0 * unit(k * 7 + 1) - 1.0;
    let a = TAU * unit(k * 7 + 2);
    let r = (1.0 - z * z).max(0.0).sqrt();
    V3::new(r * a.cos(), r * a.sin(), z)
}

/// A point inside a face of `comp` for attempt `k`, away from the face's edges. For a line
/// test, faces nearly parallel to `along` are avoided in the first half of the attempts (their
/// lines are the ones that can run inside a face).
fn pick_point(view: View, comp: &Component, k: u64, along: Option<&V3>) -> Option<V3> {
    let n = comp.faces.len() as u64;
    if n == 0 {
        return None;
    }
    let f = view.face(comp.faces[(mix(k * 7 + 3) % n) as usize]);
    if let Some(dir) = along {
        if k < ATTEMPTS / 2 && f.n.dot(dir).abs() < 0.2 * f.n_norm * dir.norm() {
            return None;
        }
    }
    let (mut a, mut b) = (unit(k * 7 + 4), unit(k * 7 + 5));
    if a + b > 1.0 {
        a = 1.0 - a;
        b = 1.0 - b;
    }
    // shrink towards the centroid to stay clear of the edges
    let (a, b) = (0.1 + 0.7 * a, 0.1 + 0.7 * b);
    let c = 1.0 - a - b;
    let bary = if c < 0.0 { (a, b, 0.0) } else { (a, b, c) };
    let s = bary.0 + bary.1 + bary.2;
    Some((f.v[0] * bary.0 + f.v[1] * bary.1 + f.v[2] * bary.2) / s)
}

/// Ray parity: whether `x` is inside the part; `None` when degenerate.
fn inside(
    view: View,
    x: &V3,
    u: &V3,
    margin: f64,
    parallel: f64,
    counts: &mut CallCounts,
) -> Option<bool> {
    let mut odd = false;
    let mut degenerate = false;
    view.part.parity_bvh.visit_line(x, u, margin, |i| {
        counts.pairs_tested += 1;
        match line_face(x, u, &view.face(i), margin, parallel) {
            Cross::Hit(s) if s.abs() <= margin => degenerate = true,
            Cross::Hit(s) => odd ^= s > 0.0,
            Cross::Degenerate => degenerate = true,
            Cross::Miss => {}
        }
        !degenerate
    });
    (!degenerate).then_some(odd)
}

/// `{λ ∈ window : x0 + λ·dir inside the part}`; `None` when degenerate.
#[allow(clippy::too_many_arguments)]
fn inside_along_line(
    view: View,
    x0: &V3,
    dir: &V3,
    window: Interval,
    margin: f64,
    parallel: f64,
    counts: &mut CallCounts,
    buf: &mut Pieces,
) -> bool {
    let Pieces {
        crossings: hits,
        out,
    } = buf;
    hits.clear();
    out.clear();
    let mut degenerate = false;
    let speed = dir.norm();
    view.part.parity_bvh.visit_line(x0, dir, margin, |i| {
        counts.pairs_tested += 1;
        match line_face(x0, dir, &view.face(i), margin, parallel) {
            Cross::Hit(s) => hits.push(s),
            Cross::Degenerate => degenerate = true,
            Cross::Miss => {}
        }
        !degenerate
    });
    if degenerate || hits.len() % 2 == 1 {
        return false;
    }
    hits.sort_by(f64::total_cmp);
    if hits.windows(2).any(|w| (w[1] - w[0]) * speed <= margin) {
        // two crossings at one point: through an edge or vertex after all
        return false;
    }
    out.extend(
        hits.chunks(2)
            .filter_map(|c| Interval { lo: c[0], hi: c[1] }.meet(&window)),
    );
    true
}

/// `{ψ ∈ window : x0 turned by ψ about (centre, unit axis) inside the part}`, `window` within
/// one turn; `None` when degenerate.
#[allow(clippy::too_many_arguments)]
fn inside_along_circle(
    view: View,
    x0: &V3,
    centre: &V3,
    axis: &V3,
    window: Interval,
    k: u64,
    margin: f64,
    parallel: f64,
    counts: &mut CallCounts,
    buf: &mut Pieces,
) -> bool {
    let Pieces { crossings, out } = buf;
    crossings.clear();
    out.clear();
    let rel = x0 - centre;
    let start = centre + turn(&rel, axis, window.lo);
    let Some(mut state) = inside(view, &start, &direction(k), margin, parallel, counts) else {
        return false;
    };
    let radius = (rel - axis * axis.dot(&rel)).norm();
    if radius > margin {
        let arc = AngleRange::new(window.lo, window.hi)
            .arc_box(&rel, axis)
            .shifted(centre)
            .grown(margin);
        let mut degenerate = false;
        view.part.parity_bvh.visit_overlapping(&arc, |i| {
            counts.pairs_tested += 1;
            let f = view.face(i);
            let nn = f.n_norm;
            let h = lin(&f.n, &rel, axis).plus(f.n.dot(centre) - f.offset);
            let zeros = match h.zeros() {
                Zeros::None => return true,
                Zeros::All => {
                    degenerate = true;
                    return false;
                }
                Zeros::One(z) => [Some(z), None],
                Zeros::Two(a, b) => [Some(a), Some(b)],
            };
            for z in zeros.into_iter().flatten() {
                // every copy of the zero inside the window
                let mut phi = z + TAU * ((window.lo - z) / TAU).ceil();
                while phi <= window.hi {
                    let point = centre + turn(&rel, axis, phi);
                    match point_in_face(&point, &f, margin) {
                        Cross::Miss => {}
                        Cross::Degenerate => degenerate = true,
                        Cross::Hit(_) => {
                            let tangent = h.slope(phi).abs() <= parallel.sqrt() * nn * radius;
                            if tangent || (phi - window.lo) * radius <= margin {
                                degenerate = true;
                            } else {
                                crossings.push(phi);
                            }
                        }
                    }
                    phi += TAU;
                }
            }
            !degenerate
        });
        if degenerate {
            return false;
        }
    }
    crossings.sort_by(f64::total_cmp);
    if crossings
        .windows(2)
        .any(|w| (w[1] - w[0]) * radius <= margin)
    {
        return false;
    }
    let mut from = window.lo;
    for &c in crossings.iter() {
        if state {
            out.push(Interval { lo: from, hi: c });
        }
        state = !state;
        from = c;
    }
    if state {
        out.push(Interval {
            lo: from,
            hi: window.hi,
        });
    }
    true
}

/// Reusable buffers of one containment answer along a path: the parameters at which the path
/// crosses the surface, and the inside pieces (kept in the per-thread scratch space).
#[derive(Default)]
pub(crate) struct Pieces {
    crossings: Vec<f64>,
    out: Vec<Interval>,
}

/// Reports the inside pieces of one component (`pieces` if an attempt `found` them, else the
/// whole `window`, conservatively), negated if `negate` (a turn seen from the other body).
fn report(
    found: bool,
    pieces: &[Interval],
    window: Interval,
    negate: bool,
    sink: &mut Hits,
) -> ControlFlow<()> {
    let all = [window];
    let pieces = if found { pieces } else { &all[..] };
    for iv in pieces {
        let iv = if negate {
            Interval {
                lo: -iv.hi,
                hi: -iv.lo,
            }
        } else {
            *iv
        };
        sink.add(iv)?;
    }
    ControlFlow::Continue(())
}

/// The robot's part, if containment applies to it (a closed mesh with an inside).
fn both_solid(ph: &Polyhedra) -> Option<&Part> {
    ph.robot.parts.first().filter(|p| p.solid)
}

/// Static containment at a pose, both ways, for every solid obstacle.
pub(crate) fn at_pose(ph: &Polyhedra, pose: &Pose, counts: &mut CallCounts) -> bool {
    let Some(rpart) = both_solid(ph) else {
        return false;
    };
    let (margin, parallel) = (MARGIN * ph.tol.dist, ph.tol.parallel);
    let rview = View {
        vertices: &ph.robot.vertices,
        part: rpart,
    };
    let robot_world = pose.world_box(&rpart.aabb);
    for opart in ph.obstacles.parts.iter().filter(|p| p.solid) {
        if !robot_world.overlaps(&opart.aabb) {
            continue;
        }
        let oview = View {
            vertices: &ph.obstacles.vertices,
            part: opart,
        };
        // a piece of the robot inside the obstacle
        for comp in &rpart.components {
            if !pose.world_box(&comp.aabb).overlaps(&opart.aabb) {
                continue;
            }
            let answer = (0..ATTEMPTS).find_map(|k| {
                let v = pick_point(rview, comp, k, None)?;
                inside(
                    oview,
                    &pose.world_point(&v),
                    &direction(k),
                    margin,
                    parallel,
                    counts,
                )
            });
            if answer != Some(false) {
                return true;
            }
        }
        // a piece of the obstacle inside the robot
        for comp in &opart.components {
            if !pose.body_box(&comp.aabb).overlaps(&rpart.aabb) {
                continue;
            }
            let answer = (0..ATTEMPTS).find_map(|k| {
                let w = pick_point(oview, comp, k, None)?;
                inside(
                    rview,
                    &pose.body_point(&w),
                    &direction(k),
                    margin,
                    parallel,
                    counts,
                )
            });
            if answer != Some(false) {
                return true;
            }
        }
    }
    false
}

/// Containment pieces (in λ) of the robot moving by `λ·dir_w` (world), `λ ∈ window`.
pub(crate) fn translation(
    ph: &Polyhedra,
    pose: &Pose,
    dir_w: &V3,
    window: Interval,
    sink: &mut Hits,
    buf: &mut Pieces,
    counts: &mut CallCounts,
) {
    let Some(rpart) = both_solid(ph) else {
        return;
    };
    let (margin, parallel) = (MARGIN * ph.tol.dist, ph.tol.parallel);
    let rview = View {
        vertices: &ph.robot.vertices,
        part: rpart,
    };
    let dir_b = pose.body_dir(dir_w);
    for opart in ph.obstacles.parts.iter().filter(|p| p.solid) {
        let oview = View {
            vertices: &ph.obstacles.vertices,
            part: opart,
        };
        // robot pieces, moving by +λ·dir in the world
        for comp in &rpart.components {
            let Some(w) = pose
                .world_box(&comp.aabb)
                .sweep_range(dir_w, &opart.aabb.grown(margin))
                .and_then(|w| w.meet(&window))
            else {
                continue;
            };
            let found = (0..ATTEMPTS).any(|k| {
                pick_point(rview, comp, k, Some(&dir_b)).is_some_and(|v| {
                    inside_along_line(
                        oview,
                        &pose.world_point(&v),
                        dir_w,
                        w,
                        margin,
                        parallel,
                        counts,
                        buf,
                    )
                })
            });
            if report(found, &buf.out, w, false, sink).is_break() {
                return;
            }
        }
        // obstacle pieces, moving by −λ·dir relative to the robot
        let back = -dir_b;
        for comp in &opart.components {
            let Some(w) = pose
                .body_box(&comp.aabb)
                .sweep_range(&back, &rpart.aabb.grown(margin))
                .and_then(|w| w.meet(&window))
            else {
                continue;
            };
            let found = (0..ATTEMPTS).any(|k| {
                pick_point(oview, comp, k, Some(dir_w)).is_some_and(|p| {
                    inside_along_line(
                        rview,
                        &pose.body_point(&p),
                        &back,
                        w,
                        margin,
                        parallel,
                        counts,
                        buf,
                    )
                })
            });
            if report(found, &buf.out, w, false, sink).is_break() {
                return;
            }
        }
    }
}

/// Containment pieces (in φ) of the robot turning by `φ ∈ phis` (at most one turn) about the
/// unit world `axis_w` through its reference point.
pub(crate) fn rotation(
    ph: &Polyhedra,
    pose: &Pose,
    axis_w: &V3,
    phis: Interval,
    sink: &mut Hits,
    buf: &mut Pieces,
    counts: &mut CallCounts,
) {
    let Some(rpart) = both_solid(ph) else {
        return;
    };
    let (margin, parallel) = (MARGIN * ph.tol.dist, ph.tol.parallel);
    let rview = View {
        vertices: &ph.robot.vertices,
        part: rpart,
    };
    let axis_b = pose.body_dir(axis_w).normalize();
    let turning = AngleRange::new(phis.lo, phis.hi);
    let back = Interval {
        lo: -phis.hi,
        hi: -phis.lo,
    };
    let back_turning = AngleRange::new(back.lo, back.hi);
    for opart in ph.obstacles.parts.iter().filter(|p| p.solid) {
        let oview = View {
            vertices: &ph.obstacles.vertices,
            part: opart,
        };
        // robot pieces, turning by +φ about the axis through the reference point
        for comp in &rpart.components {
            let swept = swept_box(pose, &comp.aabb, ph.robot.radius, axis_w, &turning);
            if !swept.overlaps(&opart.aabb.grown(margin)) {
                continue;
            }
            let found = (0..ATTEMPTS).any(|k| {
                pick_point(rview, comp, k, None).is_some_and(|v| {
                    let x0 = pose.world_point(&v);
                    inside_along_circle(
                        oview, &x0, &pose.pos, axis_w, phis, k, margin, parallel, counts, buf,
                    )
                })
            });
            if report(found, &buf.out, phis, false, sink).is_break() {
                return;
            }
        }
        // obstacle pieces, turning by −φ about the axis as seen from the robot
        for comp in &opart.components {
            let corners = pose.body_box(&comp.aabb);
            let swept = (0..8).fold(Aabb::EMPTY, |b, i| {
                b.merge(&back_turning.arc_box(&box_corner(&corners, i), &axis_b))
            });
            if !swept.overlaps(&rpart.aabb.grown(margin)) {
                continue;
            }
            let found = (0..ATTEMPTS).any(|k| {
                pick_point(oview, comp, k, None).is_some_and(|p| {
                    let y0 = pose.body_point(&p);
                    inside_along_circle(
                        rview,
                        &y0,
                        &V3::zeros(),
                        &axis_b,
                        back,
                        k,
                        margin,
                        parallel,
                        counts,
                        buf,
                    )
                })
            });
            // ψ = −φ
            if report(found, &buf.out, back, true, sink).is_break() {
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::body::Body;
    use super::*;
    use crate::geometry::TriMesh;
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

    #[test]
    fn ray_parity_in_a_cube() {
        let b = Body::new(&[TriMesh::cuboid([1.0, 1.0, 1.0]).unwrap()]);
        let view = View {
            vertices: &b.vertices,
            part: &b.parts[0],
        };
        let mut c = CallCounts::default();
        for k in 0..10 {
            let d = direction(k);
            assert_eq!(
                inside(view, &V3::new(0.3, -0.2, 0.1), &d, 1e-9, 1e-10, &mut c),
                Some(true)
            );
            assert_eq!(
                inside(view, &V3::new(1.3, -0.2, 0.1), &d, 1e-9, 1e-10, &mut c),
                Some(false)
            );
        }
        // along an axis through the middle of a face: the diagonal edge of the face is hit
        let deg = inside(
            view,
            &V3::zeros(),
            &V3::new(1.0, 0.0, 0.0),
            1e-9,
            1e-10,
            &mut c,
        );
        assert_eq!(deg, None);
    }

    #[test]
    fn line_and_circle_through_a_cube() {
        let b = Body::new(&[TriMesh::cuboid([1.0, 1.0, 1.0]).unwrap()]);
        let view = View {
            vertices: &b.vertices,
            part: &b.parts[0],
        };
        let mut c = CallCounts::default();
        let mut buf = Pieces::default();
        assert!(inside_along_line(
            view,
            &V3::new(-5.0, 0.3, 0.2),
            &V3::new(2.0, 0.0, 0.0),
            Interval::ALL,
            1e-9,
            1e-10,
            &mut c,
            &mut buf,
        ));
        let ivs = buf.out.clone();
        assert_eq!(ivs.len(), 1);
        assert!((ivs[0].lo - 2.0).abs() < 1e-12 && (ivs[0].hi - 3.0).abs() < 1e-12);
        // a point at radius 1.2 about the z-axis is inside the cube where |cos ψ| and |sin ψ|
        // are at most 1/1.2: four arcs around the diagonals
        let r = 1.2f64;
        // the buffers are reused: the first answer must not leak into the second
        assert!(inside_along_circle(
            view,
            &V3::new(r, 0.0, 0.3),
            &V3::zeros(),
            &V3::z(),
            Interval { lo: -PI, hi: PI },
            3,
            1e-9,
            1e-10,
            &mut c,
            &mut buf,
        ));
        let ivs = buf.out.clone();
        let half = FRAC_PI_4 - (1.0 / r).acos();
        assert_eq!(ivs.len(), 4, "{ivs:?}");
        for (k, iv) in ivs.iter().enumerate() {
            let centre = -3.0 * FRAC_PI_4 + k as f64 * FRAC_PI_2;
            assert!(
                (iv.lo - (centre - half)).abs() < 1e-9 && (iv.hi - (centre + half)).abs() < 1e-9,
                "{ivs:?}"
            );
        }
    }
}
