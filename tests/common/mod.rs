//! Independent validity checks. Disc scenes: plain segment–ball distances, written
//! here and sharing no code with the library's oracles.
#![allow(dead_code)]

/// Distance from point `c` to the segment `a`–`b` (any dimension).
pub fn segment_point_distance(a: &[f64], b: &[f64], c: &[f64]) -> f64 {
    let ab: Vec<f64> = a.iter().zip(b).map(|(x, y)| y - x).collect();
    let ac: Vec<f64> = a.iter().zip(c).map(|(x, y)| y - x).collect();
    let len2: f64 = ab.iter().map(|v| v * v).sum();
    let t = if len2 > 0.0 {
        (ab.iter().zip(&ac).map(|(u, v)| u * v).sum::<f64>() / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    a.iter()
        .zip(&ab)
        .zip(c)
        .map(|((x, d), y)| (x + t * d - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// A point robot's path among closed balls inside a box: every segment stays farther than the
/// radius from every centre (up to `tol` for rounding), every corner lies in the box (the box is
/// convex, so segments do too). Returns a description of the first violation.
pub fn check_disc_path(
    path: &[Vec<f64>],
    centres: &[Vec<f64>],
    radii: &[f64],
    lower: &[f64],
    upper: &[f64],
    tol: f64,
) -> Result<(), String> {
    for (k, q) in path.iter().enumerate() {
        for i in 0..q.len() {
            if q[i] < lower[i] - tol || q[i] > upper[i] + tol {
                return Err(format!("corner {k} {q:?} outside the bounds"));
            }
        }
    }
    for (k, w) in path.windows(2).enumerate() {
        for (c, r) in centres.iter().zip(radii) {
            let d = segment_point_distance(&w[0], &w[1], c);
            if d < r - tol {
                return Err(format!(
                    "segment {k} {:?}→{:?} passes {d} from disc {c:?} of radius {r}",
                    w[0], w[1]
                ));
            }
        }
    }
    Ok(())
}

/// Conservative advancement over `t ∈ [0, 1]`: a piece `[t₀, t₁]` is certified free when the
/// clearance at `t₀` exceeds `rate · (t₁ − t₀)`, the farthest any point of the robot can move
/// on it; uncertified pieces are halved. Fails where the clearance is zero, or where a piece
/// shorter than 1e-10 still cannot be certified (the robot comes within rounding of touching).
pub fn certify_by_advancement(rate: f64, clearance_at: impl Fn(f64) -> f64) -> Result<(), String> {
    let mut stack = vec![(0.0f64, 1.0f64)];
    while let Some((t0, t1)) = stack.pop() {
        let d = clearance_at(t0);
        if d > rate * (t1 - t0) {
            continue;
        }
        if d <= 0.0 || t1 - t0 < 1e-10 {
            return Err(format!("touches an obstacle near t = {t0} (clearance {d})"));
        }
        let m = 0.5 * (t0 + t1);
        stack.push((m, t1));
        stack.push((t0, m));
    }
    Ok(())
}

pub mod cli;
pub mod rigid;
pub mod rigid2d;
