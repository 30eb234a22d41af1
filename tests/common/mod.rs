//! Independent validity checks. Disc scenes: plain segment–ball distances, written
//! here and sharing no code with the library's oracles.
#![allow(dead_code)]

/// Distance from point `c` to the segment `a`–`b` (any dimension): the library's
/// validity sweep uses the same plain formula.
pub use viaroad::bench::validity::segment_point_distance;

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

pub mod arms;
pub mod bodies;
pub mod bodies3;
pub mod cli;
pub mod js;
pub mod rigid;
pub mod rigid2d;
pub mod tree;
