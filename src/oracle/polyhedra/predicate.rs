//! The edge–face predicate `S(l_{p,q}, f)` of CHS §2.1, and the static overlap test built on it.
//!
//! For an edge from `p` to `q` and a convex face `f` with corners `v_0 … v_{k−1}`
//! (counter-clockwise about its normal `n`, plane `n·x = n_0`) the seed's predicate is
//!
//! ```text
//! S = ( n·(q−p) > 0 ∧ n·q − n_0 ≥ 0 ∧ n·p − n_0 ≤ 0 ∧ ⋀_i det[q−p, v_{i+1}−v_i, p−v_i] ≥ 0 )   "outward"
//!   ∨ ( n·(p−q) < 0 ∧ n·p − n_0 ≥ 0 ∧ n·q − n_0 ≤ 0 ∧ ⋀_i det[p−q, v_{i+1}−v_i, q−v_i] ≥ 0 )   "inward"
//! ```
//!
//! (the seed's second line reads `n·(p−q) < 0`, which repeats the first case; the text around
//! it — "inward: n·(q−p) < 0" — makes clear that `n·(q−p) < 0` is meant, and that is what we
//! use). Since `det[p−q, e, q−v] = −det[q−p, e, p−v]`, both cases test the same three
//! determinants `D_i = det[d, e_i, p − v_i]` with `d = q − p`, with opposite signs; and
//! `Σ_i D_i = n·d` for a triangle (the three determinants add up to the case split itself).
//!
//! The "parallel" case `n·d = 0` is left out (Lemma 2.1): an edge lying in the plane of a face
//! of the other body overlaps it only if some other, non-degenerate edge–face pair overlaps
//! too. The lemma is stated for solids; for two triangles of open soups it holds as long as the
//! triangles are not coplanar — the only contact we can miss is two coplanar triangles
//! overlapping with no third triangle touching them (a single flat sheet sliding exactly in
//! the plane of another).
//!
//! Every atom is tested with a tiny tolerance in favour of collision ([`Tolerance`]), so that
//! contacts exactly at a shared edge of two faces are not lost to rounding in both.

use super::body::Face;
use nalgebra::Vector3;

type V3 = Vector3<f64>;

/// Relative tolerance of the distance tests, as a fraction of the scene's size.
pub(crate) const DISTANCE_TOLERANCE: f64 = 1e-11;
/// Sine of the angle below which an edge counts as parallel to a face (Lemma 2.1).
pub(crate) const PARALLEL_TOLERANCE: f64 = 1e-10;

/// Numerical tolerances of one oracle.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tolerance {
    /// A point within this distance of a plane counts as on it (length units).
    pub dist: f64,
    /// An edge within this angle (radians, as a sine) of a face's plane counts as parallel.
    pub parallel: f64,
}

impl Tolerance {
    /// Tolerances for a scene of size `scale` (length units).
    pub fn for_scale(scale: f64) -> Tolerance {
        Tolerance {
            dist: DISTANCE_TOLERANCE * scale.max(f64::MIN_POSITIVE),
            parallel: PARALLEL_TOLERANCE,
        }
    }
}

/// `det[a, b, c] = a · (b × c)`.
pub(crate) fn det(a: &V3, b: &V3, c: &V3) -> f64 {
    a.dot(&b.cross(c))
}

/// `S(l_{p,q}, f)` for a fixed edge and face: whether the closed segment meets the face.
/// Parallel pairs answer `false` (Lemma 2.1).
pub(crate) fn edge_meets_face(p: &V3, q: &V3, f: &Face, tol: &Tolerance) -> bool {
    let d = q - p;
    let g = f.n.dot(&d);
    let nn = f.n_norm;
    if g.abs() <= tol.parallel * nn * d.norm() {
        return false;
    }
    // outward (g > 0) or inward (g < 0): multiply every atom by the sign of g
    let s = g.signum();
    let th = tol.dist * nn;
    if s * (f.n.dot(p) - f.offset) > th || s * (f.n.dot(q) - f.offset) < -th {
        return false;
    }
    let dl = d.norm();
    let e = f.edges();
    (0..3).all(|i| s * det(&d, &e[i], &(p - f.v[i])) >= -tol.dist * dl * f.e_len[i])
}

/// Whether two triangles meet (touching counts), by the predicate in both directions: the
/// edges of each against the other's face.
pub(crate) fn faces_meet(a: &Face, b: &Face, tol: &Tolerance) -> bool {
    let edges = |f: &Face| [(f.v[0], f.v[1]), (f.v[1], f.v[2]), (f.v[2], f.v[0])];
    let meet = |a: &Face, b: &Face| {
        !beyond_plane(a, b, tol) && edges(a).iter().any(|(p, q)| edge_meets_face(p, q, b, tol))
    };
    meet(a, b) || meet(b, a)
}

/// Whether every corner of `a` lies beyond the same side of `f`'s plane, past the tolerance
/// [`edge_meets_face`] allows: then the predicate's plane test refuses every edge of `a`
/// against `f` (the same expressions, evaluated the same way), and three dot products replace
/// three edge tests. Not the same as "the triangles are apart": within the tolerances an edge
/// of `f` may still meet `a` (nearly coplanar triangles), so `f`'s edges are still tested.
fn beyond_plane(a: &Face, f: &Face, tol: &Tolerance) -> bool {
    let th = tol.dist * f.n_norm;
    let side = |p: &V3| f.n.dot(p) - f.offset;
    let s = [side(&a.v[0]), side(&a.v[1]), side(&a.v[2])];
    s.iter().all(|&x| x > th) || s.iter().all(|&x| x < -th)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tol() -> Tolerance {
        Tolerance::for_scale(10.0)
    }

    fn unit_face() -> Face {
        Face::new([
            V3::new(0.0, 0.0, 0.0),
            V3::new(1.0, 0.0, 0.0),
            V3::new(0.0, 1.0, 0.0),
        ])
    }

    #[test]
    fn piercing_touching_and_missing_edges() {
        let f = unit_face();
        let t = tol();
        // straight through the middle, both directions
        assert!(edge_meets_face(
            &V3::new(0.2, 0.2, -1.0),
            &V3::new(0.2, 0.2, 1.0),
            &f,
            &t
        ));
        assert!(edge_meets_face(
            &V3::new(0.2, 0.2, 1.0),
            &V3::new(0.2, 0.2, -1.0),
            &f,
            &t
        ));
        // ending exactly on the face
        assert!(edge_meets_face(
            &V3::new(0.2, 0.2, 0.0),
            &V3::new(0.2, 0.2, 1.0),
            &f,
            &t
        ));
        // through a corner and along the boundary
        assert!(edge_meets_face(
            &V3::new(1.0, 0.0, -1.0),
            &V3::new(1.0, 0.0, 1.0),
            &f,
            &t
        ));
        assert!(edge_meets_face(
            &V3::new(0.5, 0.5, -1.0),
            &V3::new(0.5, 0.5, 1.0),
            &f,
            &t
        ));
        // outside the triangle, or short of the plane
        assert!(!edge_meets_face(
            &V3::new(0.6, 0.6, -1.0),
            &V3::new(0.6, 0.6, 1.0),
            &f,
            &t
        ));
        assert!(!edge_meets_face(
            &V3::new(0.2, 0.2, 0.1),
            &V3::new(0.2, 0.2, 1.0),
            &f,
            &t
        ));
        // in the plane: degenerate, ignored (Lemma 2.1)
        assert!(!edge_meets_face(
            &V3::new(-1.0, 0.2, 0.0),
            &V3::new(2.0, 0.2, 0.0),
            &f,
            &t
        ));
    }

    #[test]
    fn determinants_add_up_to_the_case_split() {
        let f = Face::new([
            V3::new(0.3, -0.2, 0.7),
            V3::new(1.9, 0.4, -0.1),
            V3::new(-0.5, 1.3, 0.2),
        ]);
        let (p, q) = (V3::new(0.1, 0.2, 0.3), V3::new(-1.0, 2.0, 0.5));
        let d = q - p;
        let e = f.edges();
        let sum: f64 = (0..3).map(|i| det(&d, &e[i], &(p - f.v[i]))).sum();
        assert!((sum - f.n.dot(&d)).abs() < 1e-12);
    }

    #[test]
    fn crossing_triangles_meet_and_separated_ones_do_not() {
        let a = unit_face();
        let b = Face::new([
            V3::new(0.2, 0.2, -1.0),
            V3::new(0.2, 0.2, 1.0),
            V3::new(-1.0, -1.0, 0.5),
        ]);
        assert!(faces_meet(&a, &b, &tol()));
        let c = Face::new([
            V3::new(2.0, 2.0, -1.0),
            V3::new(2.0, 2.0, 1.0),
            V3::new(3.0, 1.0, 0.5),
        ]);
        assert!(!faces_meet(&a, &c, &tol()));
    }

    /// The plane pre-test answers exactly as the six edge tests would: on random triangles, on
    /// triangles whose corners lie within a few tolerances of the other's plane (where the
    /// tolerances decide), and on triangles sharing a corner or lying in one plane.
    #[test]
    fn the_plane_test_changes_no_verdict() {
        use rand::{Rng, SeedableRng};
        let by_edges = |a: &Face, b: &Face, t: &Tolerance| {
            let edges = |f: &Face| [(f.v[0], f.v[1]), (f.v[1], f.v[2]), (f.v[2], f.v[0])];
            edges(a).iter().any(|(p, q)| edge_meets_face(p, q, b, t))
                || edges(b).iter().any(|(p, q)| edge_meets_face(p, q, a, t))
        };
        let t = tol();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let point = |rng: &mut rand_chacha::ChaCha8Rng| {
            V3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
        };
        let (mut met, mut near, mut refused) = (0, 0, 0);
        for k in 0..200_000 {
            let a = Face::new([point(&mut rng), point(&mut rng), point(&mut rng)]);
            let v = match k % 4 {
                // anywhere
                0 => [point(&mut rng), point(&mut rng), point(&mut rng)],
                // corners within a few tolerances of a's plane, on either side or on it
                1 | 2 => {
                    let unit = a.n / a.n_norm;
                    [0, 1, 2].map(|_| {
                        let p = point(&mut rng);
                        let off = unit.dot(&p) - a.offset / a.n_norm;
                        let k: i32 = rng.random_range(-3..=3);
                        p - unit * off + unit * (f64::from(k) * t.dist)
                    })
                }
                // sharing a corner with a
                _ => [
                    a.v[rng.random_range(0..3)],
                    point(&mut rng),
                    point(&mut rng),
                ],
            };
            let b = Face::new(v);
            if b.n_norm < 1e-9 || a.n_norm < 1e-9 {
                continue;
            }
            let want = by_edges(&a, &b, &t);
            assert_eq!(faces_meet(&a, &b, &t), want, "{a:?} {b:?}");
            met += usize::from(want);
            near += usize::from(k % 4 != 0 && k % 4 != 3);
            refused += usize::from(beyond_plane(&a, &b, &t) || beyond_plane(&b, &a, &t));
        }
        // the cases occur: triangles that meet, and some the pre-test refuses
        assert!(
            met > 10_000 && refused > 10_000 && near > 10_000,
            "{met} {near} {refused}"
        );
    }
}
