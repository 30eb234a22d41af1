//! Triangulation of simple polygons by ear clipping, for containment tests.
//!
//! Containment (one polygon wholly inside the other, CHS §2.1) is decided by whether one
//! vertex of one polygon lies in the other. The seed shoots a ray and counts crossings; here a
//! polygon is cut once into triangles, so that "point in polygon" becomes "point in one of the
//! triangles" — three orientation tests each, which turn into linear inequalities under
//! translation and into the `α cos φ + β sin φ + γ` form under rotation, exactly like the
//! edge tests, with no special cases for rays through vertices.

/// `(b − a) × (c − a)`: twice the signed area of the triangle `abc`.
pub(crate) fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether `p` lies in the closed counter-clockwise triangle `abc`.
fn in_closed_triangle(p: [f64; 2], a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    orient(a, b, p) >= 0.0 && orient(b, c, p) >= 0.0 && orient(c, a, p) >= 0.0
}

/// Cuts the simple counter-clockwise polygon `v` into counter-clockwise triangles (vertex
/// indices) of positive area. Never fails: on input that is not quite simple (rounding,
/// collinear runs) it removes zero-area corners and, failing any ear, clips the most convex
/// corner, so the result covers the polygon as well as can be.
pub(crate) fn triangulate(v: &[[f64; 2]]) -> Vec<[usize; 3]> {
    let n = v.len();
    let mut out = Vec::with_capacity(n.saturating_sub(2));
    if n < 3 {
        return out;
    }
    let mut prev: Vec<usize> = (0..n).map(|i| (i + n - 1) % n).collect();
    let mut next: Vec<usize> = (0..n).map(|i| (i + 1) % n).collect();
    let mut alive = vec![true; n];
    let mut remaining = n;
    let convex = |p: usize, i: usize, q: usize| orient(v[p], v[i], v[q]);
    let is_ear = |p: usize, i: usize, q: usize, next: &[usize]| -> bool {
        if convex(p, i, q) <= 0.0 {
            return false;
        }
        // no other corner may lie in the ear (corners at the same spot as the ear's own
        // corners do not count: they touch it without entering)
        let mut r = next[q];
        while r != p {
            let pt = v[r];
            if pt != v[p] && pt != v[i] && pt != v[q] && in_closed_triangle(pt, v[p], v[i], v[q]) {
                return false;
            }
            r = next[r];
        }
        true
    };
    let emit = |a: usize, b: usize, c: usize, out: &mut Vec<[usize; 3]>| {
        let o = orient(v[a], v[b], v[c]);
        if o > 0.0 {
            out.push([a, b, c]);
        } else if o < 0.0 {
            out.push([a, c, b]);
        }
    };
    let mut i = 0;
    let mut stall = 0;
    while remaining > 3 {
        let (p, q) = (prev[i], next[i]);
        let clip = if is_ear(p, i, q, &next) {
            emit(p, i, q, &mut out);
            Some(i)
        } else {
            stall += 1;
            if stall > remaining {
                // no ear in a whole round: drop a flat corner, else clip the most convex one
                let mut best = i;
                let mut best_val = f64::NEG_INFINITY;
                let mut flat = None;
                let mut j = i;
                for _ in 0..remaining {
                    let o = convex(prev[j], j, next[j]);
                    if o == 0.0 {
                        flat = Some(j);
                        break;
                    }
                    if o > best_val {
                        best_val = o;
                        best = j;
                    }
                    j = next[j];
                }
                match flat {
                    Some(j) => Some(j),
                    None => {
                        emit(prev[best], best, next[best], &mut out);
                        Some(best)
                    }
                }
            } else {
                None
            }
        };
        match clip {
            Some(j) => {
                let (p, q) = (prev[j], next[j]);
                next[p] = q;
                prev[q] = p;
                alive[j] = false;
                remaining -= 1;
                stall = 0;
                i = p;
            }
            None => i = q,
        }
    }
    if let Some(a) = (0..n).find(|&k| alive[k]) {
        let b = next[a];
        let c = next[b];
        emit(a, b, c, &mut out);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(v: &[[f64; 2]]) -> f64 {
        let n = v.len();
        0.5 * (0..n)
            .map(|i| {
                let (a, b) = (v[i], v[(i + 1) % n]);
                a[0] * b[1] - b[0] * a[1]
            })
            .sum::<f64>()
    }

    fn tri_area(v: &[[f64; 2]], t: [usize; 3]) -> f64 {
        0.5 * orient(v[t[0]], v[t[1]], v[t[2]])
    }

    fn check(v: &[[f64; 2]]) {
        let tris = triangulate(v);
        assert_eq!(tris.len(), v.len() - 2, "{v:?}");
        let total: f64 = tris.iter().map(|&t| tri_area(v, t)).sum();
        assert!(tris.iter().all(|&t| tri_area(v, t) > 0.0));
        assert!(
            (total - area(v)).abs() < 1e-9 * area(v),
            "{total} vs {}",
            area(v)
        );
    }

    #[test]
    fn convex_and_non_convex() {
        check(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        // an L
        check(&[
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ]);
        // a comb with deep teeth
        let mut comb = vec![[0.0, 0.0], [9.0, 0.0]];
        for k in (0..5).rev() {
            let x = 2.0 * k as f64;
            comb.push([x + 1.0, 5.0]);
            comb.push([x + 0.5, 1.0]);
            comb.push([x, 5.0]);
        }
        comb.pop();
        comb.push([0.0, 5.0]);
        check(&comb);
        // a star
        let star: Vec<[f64; 2]> = (0..14)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 14.0;
                let r = if k % 2 == 0 { 3.0 } else { 1.0 };
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        check(&star);
    }

    #[test]
    fn collinear_corners_are_harmless() {
        let v = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        let tris = triangulate(&v);
        let total: f64 = tris.iter().map(|&t| tri_area(&v, t)).sum();
        assert!((total - 4.0).abs() < 1e-12);
        assert!(tris.iter().all(|&t| tri_area(&v, t) > 0.0));
    }
}
