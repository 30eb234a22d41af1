//! The radius function of a convex polygon and its inverse (Brooks §3.1), on sets of angles.
//!
//! `R(ξ) = max_i d_i cos(ξ − η_i)`, where `(d_i, η_i)` are the polar coordinates of the
//! robot's vertices about its reference point, is how far the robot reaches in direction `ξ`
//! (its support function). The find-path algorithm needs it the other way round: the angles at
//! which the robot reaches no farther than `r`, `R⁻¹(r) = {ξ | R(ξ) ≤ r}`, "easily computed by
//! using the two values of arccos(r/d_i) for each i to form an interval containing η_i and
//! subtracting it from [0, 2π]". Sets of angles are [`AngleSet`]s.

use std::f64::consts::TAU;

/// Wraps an angle into `[0, 2π)`.
pub fn wrap(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w >= TAU {
        0.0
    } else {
        w
    }
}

/// A closed arc of the circle: from `lo` counter-clockwise over `len ∈ [0, 2π]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arc {
    /// Start angle in `[0, 2π)`.
    pub lo: f64,
    /// Length in radians (`2π` is the whole circle).
    pub len: f64,
}

impl Arc {
    /// Whether `a` lies on the arc.
    pub fn contains(&self, a: f64) -> bool {
        self.len >= TAU || wrap(a - self.lo) <= self.len
    }

    /// The middle angle (Brooks's choice of orientation within an interval, §4.1).
    pub fn mid(&self) -> f64 {
        wrap(self.lo + self.len / 2.0)
    }

    /// Whether the arc is the whole circle.
    pub fn is_full(&self) -> bool {
        self.len >= TAU
    }

    /// The signed turn from `a` to `b` that stays on this arc (both must lie on it): for the
    /// whole circle the shorter way.
    pub fn turn_within(&self, a: f64, b: f64) -> f64 {
        if self.is_full() {
            let d = wrap(b - a);
            return if d > std::f64::consts::PI { d - TAU } else { d };
        }
        wrap(b - self.lo) - wrap(a - self.lo)
    }
}

/// A closed set of angles: sorted, disjoint closed intervals of `[0, 2π]` (an arc across 0 is
/// stored as two pieces; [`AngleSet::arcs`] joins them again).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AngleSet {
    pieces: Vec<(f64, f64)>,
}

impl AngleSet {
    /// No angle.
    pub fn empty() -> AngleSet {
        AngleSet { pieces: Vec::new() }
    }

    /// Every angle.
    pub fn full() -> AngleSet {
        AngleSet {
            pieces: vec![(0.0, TAU)],
        }
    }

    /// Whether no angle is in the set.
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }

    /// The closed arc from `lo` counter-clockwise over `len` (clamped to `[0, 2π]`).
    pub fn arc(lo: f64, len: f64) -> AngleSet {
        if !(lo.is_finite() && len.is_finite()) || len < 0.0 {
            return AngleSet::empty();
        }
        if len >= TAU {
            return AngleSet::full();
        }
        let lo = wrap(lo);
        let hi = lo + len;
        if hi <= TAU {
            AngleSet {
                pieces: vec![(lo, hi)],
            }
        } else {
            AngleSet {
                pieces: vec![(0.0, hi - TAU), (lo, TAU)],
            }
        }
    }

    /// Union of sets.
    pub fn union(&self, o: &AngleSet) -> AngleSet {
        let mut all: Vec<(f64, f64)> = self.pieces.iter().chain(&o.pieces).copied().collect();
        all.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut out: Vec<(f64, f64)> = Vec::with_capacity(all.len());
        for (lo, hi) in all {
            match out.last_mut() {
                Some(last) if lo <= last.1 => last.1 = last.1.max(hi),
                _ => out.push((lo, hi)),
            }
        }
        AngleSet { pieces: out }
    }

    /// Intersection of sets.
    pub fn intersection(&self, o: &AngleSet) -> AngleSet {
        let (mut i, mut j) = (0, 0);
        let mut out = Vec::new();
        while i < self.pieces.len() && j < o.pieces.len() {
            let (a, b) = (self.pieces[i], o.pieces[j]);
            let lo = a.0.max(b.0);
            let hi = a.1.min(b.1);
            if lo <= hi {
                out.push((lo, hi));
            }
            if a.1 < b.1 {
                i += 1;
            } else {
                j += 1;
            }
        }
        AngleSet { pieces: out }
    }

    /// The closure of the complement.
    pub fn complement(&self) -> AngleSet {
        let mut out = Vec::new();
        let mut at = 0.0;
        for &(lo, hi) in &self.pieces {
            if lo > at {
                out.push((at, lo));
            }
            at = hi;
        }
        if at < TAU {
            out.push((at, TAU));
        }
        AngleSet { pieces: out }
    }

    /// `{ψ − ξ | ξ ∈ self}`: the set seen from the other side (a body angle `ξ` of the robot
    /// turned to world orientation `φ` points in world direction `φ + ξ`, so the orientations
    /// that put direction `ψ` at body angle `ξ` are `ψ − ξ`).
    pub fn reflected(&self, psi: f64) -> AngleSet {
        self.pieces
            .iter()
            .map(|&(lo, hi)| AngleSet::arc(psi - hi, hi - lo))
            .fold(AngleSet::empty(), |acc, s| acc.union(&s))
    }

    /// The connected components as arcs (a component across 0 is one arc).
    pub fn arcs(&self) -> Vec<Arc> {
        let p = &self.pieces;
        if p.is_empty() {
            return Vec::new();
        }
        if p.len() == 1 && p[0].0 <= 0.0 && p[0].1 >= TAU {
            return vec![Arc { lo: 0.0, len: TAU }];
        }
        let joined = p.len() > 1 && p[0].0 <= 0.0 && p[p.len() - 1].1 >= TAU;
        let mut out = Vec::with_capacity(p.len());
        let inner = if joined { &p[1..p.len() - 1] } else { &p[..] };
        for &(lo, hi) in inner {
            out.push(Arc { lo, len: hi - lo });
        }
        if joined {
            let (lo, _) = p[p.len() - 1];
            out.push(Arc {
                lo: wrap(lo),
                len: (TAU - lo) + p[0].1,
            });
        }
        out
    }

    /// Whether `a` is in the set.
    pub fn contains(&self, a: f64) -> bool {
        let a = wrap(a);
        self.pieces.iter().any(|&(lo, hi)| lo <= a && a <= hi)
            || (a == 0.0 && self.pieces.last().is_some_and(|p| p.1 >= TAU))
    }
}

/// The radius function of a robot: its vertices in polar form about the reference point.
#[derive(Clone, Debug, PartialEq)]
pub struct RadiusFunction {
    /// `(d_i, η_i)` per vertex of the robot's convex hull.
    polar: Vec<(f64, f64)>,
}

impl RadiusFunction {
    /// From the robot's vertices in the body frame (a non-convex robot is represented by its
    /// convex hull, whose radius function it shares: Brooks restricts to convex robots, and a
    /// robot inside its hull is safe wherever the hull is). No vertex: a point robot, `R ≡ 0`.
    pub fn new(vertices: &[[f64; 2]]) -> RadiusFunction {
        let hull = crate::oracle::minkowski::convex_hull(vertices);
        let polar = if hull.is_empty() {
            vec![(0.0, 0.0)]
        } else {
            hull.iter()
                .map(|v| (v[0].hypot(v[1]), v[1].atan2(v[0])))
                .collect()
        };
        RadiusFunction { polar }
    }

    /// `R(ξ) = max_i d_i cos(ξ − η_i)`: how far the robot reaches in body direction `ξ`.
    pub fn at(&self, xi: f64) -> f64 {
        self.polar
            .iter()
            .map(|&(d, eta)| d * (xi - eta).cos())
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// The largest `d_i`: how far the robot reaches in any direction (Brooks's rear extent).
    pub fn reach(&self) -> f64 {
        self.polar.iter().map(|p| p.0).fold(0.0, f64::max)
    }

    /// `R⁻¹(r) = {ξ | R(ξ) ≤ r}`, body angles: the circle minus, for every vertex with
    /// `d_i > r`, the open arc `η_i ± arccos(r/d_i)` about it (Brooks §3.1).
    pub fn inverse(&self, r: f64) -> AngleSet {
        if r.is_nan() {
            return AngleSet::empty();
        }
        let mut excluded = AngleSet::empty();
        for &(d, eta) in &self.polar {
            if d <= r {
                continue;
            }
            if d == 0.0 || r / d < -1.0 {
                return AngleSet::empty();
            }
            let h = (r / d).acos();
            excluded = excluded.union(&AngleSet::arc(eta - h, 2.0 * h));
        }
        if excluded.is_empty() {
            return AngleSet::full();
        }
        // the excluded arcs are open: their closed complement keeps the touching angles
        excluded.complement()
    }

    /// World orientations `φ` at which the robot reaches no farther than `r` in world
    /// direction `psi`: `{φ | R(ψ − φ) ≤ r} = ψ − R⁻¹(r)`.
    pub fn orientations_within(&self, psi: f64, r: f64) -> AngleSet {
        self.inverse(r).reflected(psi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn inverse_agrees_with_sampling() {
        // the se2-corridor's L-shaped robot (its hull)
        let r = RadiusFunction::new(&[
            [-1.2, -0.2],
            [1.2, -0.2],
            [1.2, 1.0],
            [0.8, 1.0],
            [0.8, 0.2],
            [-1.2, 0.2],
        ]);
        for limit in [0.1, 0.5, 0.9, 1.2, 1.3, 2.0] {
            let set = r.inverse(limit);
            for k in 0..720 {
                let xi = k as f64 * TAU / 720.0;
                let v = r.at(xi);
                if (v - limit).abs() > 1e-9 {
                    assert_eq!(
                        set.contains(xi),
                        v <= limit,
                        "limit {limit}, ξ {xi}: R = {v}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_rectangle_fits_a_strip_lengthwise_only() {
        // 2.4 × 0.4 about its centre: reaches 0.2 sideways only when lying along the strip
        let r = RadiusFunction::new(&[[-1.2, -0.2], [1.2, -0.2], [1.2, 0.2], [-1.2, 0.2]]);
        let legal = r
            .orientations_within(FRAC_PI_2, 0.3)
            .intersection(&r.orientations_within(-FRAC_PI_2, 0.3));
        assert!(legal.contains(0.0) && legal.contains(PI));
        assert!(!legal.contains(FRAC_PI_2));
        let arcs = legal.arcs();
        assert_eq!(arcs.len(), 2, "{arcs:?}");
        assert!(arcs
            .iter()
            .any(|a| a.contains(0.0) && a.contains(TAU - 0.01)));
    }
}
