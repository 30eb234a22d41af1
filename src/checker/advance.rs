//! The steps every checker shares: a bounds check with rounding slack, and conservative
//! advancement along a motion.

use crate::short;

/// Slack for rounding in the bounds and disc checks.
pub(super) const TOL: f64 = 1e-9;

/// Conservative advancement over `t ∈ [0, 1]` (the checker's module docs): fails where the
/// clearance is zero or a piece shorter than 1e-10 still cannot be certified.
pub(super) fn certify_by_advancement(
    rate: f64,
    clearance_at: impl Fn(f64) -> Result<f64, String>,
) -> Result<(), String> {
    let mut stack = vec![(0.0f64, 1.0f64)];
    while let Some((t0, t1)) = stack.pop() {
        let d = clearance_at(t0)?;
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
    // the end itself (the loop certifies [t0, t1) pieces up to their end by continuity, but a
    // clearance of exactly 0 at t = 1 is a touch)
    let d = clearance_at(1.0)?;
    if d <= 0.0 {
        return Err(format!("touches an obstacle at t = 1 (clearance {d})"));
    }
    Ok(())
}

/// Whether `q` lies within the bounds, up to [`TOL`].
pub(super) fn in_box(q: &[f64], lower: &[f64], upper: &[f64]) -> Result<(), String> {
    for i in 0..lower.len() {
        if !(q[i] >= lower[i] - TOL && q[i] <= upper[i] + TOL) {
            return Err(format!("{} lies outside the bounds", short::config(q)));
        }
    }
    Ok(())
}
