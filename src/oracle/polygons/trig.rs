//! The atomic inequality of a rotation, `α cos φ + β sin φ + γ ≥ 0` (CHS §2.3.2), solved with
//! the seed's substitution `τ = tan(φ/2)`.
//!
//! Under a rotation by `φ`, every orientation test of the static predicate becomes such an
//! inequality. Multiplying by `1 + τ²` turns it into the quadratic inequality
//! `(γ − α) τ² + 2β τ + (α + γ) ≥ 0`, whose solution set on the real line is an interval,
//! the outside of one, or a half-line — at most two intervals. The angle `φ = π` is the point
//! at infinity `τ = ±∞`; it belongs to the solution iff `γ − α ≥ 0` (the leading coefficient),
//! and the degenerate case `γ = α` (the equation turns linear) is exactly the one where
//! `φ = π` is a root.
//!
//! Departure from the seed: the seed converts every root back to an angle with `arctan`. Here
//! `τ` increases with the angle on each window of length `2π`, so the pair predicates are
//! evaluated on interval lists *in τ* (∧, ∨ do not care about a monotone change of parameter)
//! and only the ends of the final intervals are converted — no trigonometric function per
//! atom. To keep `φ = π` away from the interior of the window, the substitution is centred on
//! the window's midpoint: `φ = mid + ψ`, `τ = tan(ψ/2)`, `ψ ∈ [−L/2, L/2]`.

use super::small_set::SmallSet;
use crate::interval::Interval;
use std::f64::consts::PI;

/// The half-angle parameter of one window of turned angles (length at most `2π`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct HalfAngle {
    window: Interval,
    mid: f64,
    cos_mid: f64,
    sin_mid: f64,
    /// `τ` at the ends of the window: `±tan(L/4)`, or `±∞` for a full turn.
    bound: f64,
}

impl HalfAngle {
    /// The substitution for angles `φ ∈ window`.
    pub fn new(window: Interval) -> HalfAngle {
        let mid = 0.5 * (window.lo + window.hi);
        let half = 0.5 * (window.hi - window.lo);
        // a window within rounding of a full turn is one (conservatively)
        let bound = if half >= PI * (1.0 - 1e-12) {
            f64::INFINITY
        } else {
            (0.5 * half).tan()
        };
        let (sin_mid, cos_mid) = mid.sin_cos();
        HalfAngle {
            window,
            mid,
            cos_mid,
            sin_mid,
            bound,
        }
    }

    /// All of the window, in `τ`.
    #[inline]
    pub fn all(&self) -> SmallSet {
        let mut s = SmallSet::new();
        s.push(Interval {
            lo: -self.bound,
            hi: self.bound,
        });
        s
    }

    /// `{τ in the window : α cos φ + β sin φ + γ ≥ 0}`, with `φ = mid + 2 atan τ`.
    #[inline]
    pub fn solve(&self, alpha: f64, beta: f64, gamma: f64) -> SmallSet {
        // α cos(mid + ψ) + β sin(mid + ψ) = a cos ψ + b sin ψ
        let a = alpha * self.cos_mid + beta * self.sin_mid;
        let b = beta * self.cos_mid - alpha * self.sin_mid;
        // (γ − a) τ² + 2b τ + (a + γ) ≥ 0; ψ = π (τ = ±∞) is in iff γ − a ≥ 0
        let qa = gamma - a;
        let qc = a + gamma;
        const INF: f64 = f64::INFINITY;
        let mut raw = SmallSet::new();
        let mut add = |lo: f64, hi: f64| raw.push(Interval { lo, hi });
        if qa == 0.0 {
            // linear: 2bτ + c ≥ 0, and ψ = π is a root (in the set, at both ends of the line)
            if b > 0.0 {
                add(-INF, -INF);
                add(-qc / (2.0 * b), INF);
            } else if b < 0.0 {
                add(-INF, -qc / (2.0 * b));
                add(INF, INF);
            } else if qc >= 0.0 {
                add(-INF, INF);
            } else {
                add(-INF, -INF);
                add(INF, INF);
            }
        } else {
            // discriminant / 4 = b² − (γ − a)(γ + a) = a² + b² − γ²
            let disc = (a * a + b * b) - gamma * gamma;
            if disc <= 0.0 {
                if qa > 0.0 {
                    add(-INF, INF); // never below zero
                } else if disc == 0.0 {
                    let t = -b / qa; // touches zero once
                    add(t, t);
                }
            } else {
                // numerically stable roots: q = −(b + sign(b)·√disc), τ = q/qa and qc/q
                let q = -(b + disc.sqrt().copysign(b));
                let (r1, r2) = (q / qa, qc / q);
                let (lo, hi) = (r1.min(r2), r1.max(r2));
                if qa > 0.0 {
                    add(-INF, lo);
                    add(hi, INF);
                } else {
                    add(lo, hi);
                }
            }
        }
        if self.bound == INF {
            raw
        } else {
            SmallSet::intersection(&raw, &self.all())
        }
    }

    /// The angle `φ` of the parameter `τ`, inside the window; the ends of the window exactly.
    pub fn angle(&self, tau: f64) -> f64 {
        if tau <= -self.bound {
            self.window.lo
        } else if tau >= self.bound {
            self.window.hi
        } else {
            (self.mid + 2.0 * tau.atan()).clamp(self.window.lo, self.window.hi)
        }
    }

    /// An interval of `τ` as an interval of angles.
    pub fn angles(&self, iv: Interval) -> Interval {
        Interval {
            lo: self.angle(iv.lo),
            hi: self.angle(iv.hi),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::TAU;

    fn value(alpha: f64, beta: f64, gamma: f64, phi: f64) -> f64 {
        alpha * phi.cos() + beta * phi.sin() + gamma
    }

    /// The solution converted to angles.
    fn solution(h: &HalfAngle, alpha: f64, beta: f64, gamma: f64) -> Vec<Interval> {
        h.solve(alpha, beta, gamma)
            .as_slice()
            .iter()
            .map(|&iv| h.angles(iv))
            .collect()
    }

    /// Checks against the sign of the left side on a fine grid of the window; where the left
    /// side is within `slack` of zero either answer is right.
    fn check(window: Interval, alpha: f64, beta: f64, gamma: f64) {
        let h = HalfAngle::new(window);
        let sol = solution(&h, alpha, beta, gamma);
        let scale = alpha.abs() + beta.abs() + gamma.abs();
        let slack = 1e-9 * scale.max(1e-300);
        for k in 0..=2000 {
            let phi = (window.lo + (window.hi - window.lo) * k as f64 / 2000.0).min(window.hi);
            let v = value(alpha, beta, gamma, phi);
            let inside = sol.iter().any(|iv| iv.contains(phi));
            assert!(
                v <= slack || inside,
                "{alpha} {beta} {gamma} on {window:?}: φ={phi} v={v} {sol:?}"
            );
            assert!(
                v >= -slack || !inside,
                "{alpha} {beta} {gamma} on {window:?}: φ={phi} v={v} {sol:?}"
            );
        }
    }

    const TURN: Interval = Interval { lo: -PI, hi: PI };

    #[test]
    fn degenerate_cases() {
        for w in [
            TURN,
            Interval {
                lo: 0.3,
                hi: 0.3 + TAU,
            },
            Interval { lo: -1.0, hi: 2.0 },
        ] {
            check(w, 0.0, 0.0, 1.0); // everything
            check(w, 0.0, 0.0, -1.0); // nothing
            check(w, 0.0, 0.0, 0.0); // everything (closed)
            check(w, 1.0, 0.0, 1.0); // cos φ + 1 ≥ 0: all, touching zero at π
            check(w, -1.0, 0.0, -1.0); // only φ = π
            check(w, 1.0, 1.0, 1.0); // roots π and −π/2
            check(w, -2.0, 1.0, -2.0);
            check(w, 1.0, 0.0, -1.0); // only φ = 0
            check(w, 1.0, 0.0, 0.0); // half a turn
            check(w, 0.0, 1.0, 0.0);
            check(w, 0.0, -3.0, 2.9);
        }
        // shrunk proptest case (the grid's last point rounded past the window's end)
        check(
            Interval {
                lo: 0.0,
                hi: 4.322948219244552,
            },
            0.0,
            -3.1456048638721854,
            0.0,
        );
    }

    #[test]
    fn the_point_at_infinity_is_phi_equals_pi() {
        // −cos φ − 1 ≥ 0 holds only at φ = π: in τ about mid = 0, only at ±∞
        let h = HalfAngle::new(TURN);
        let s = h.solve(-1.0, 0.0, -1.0);
        let angles: Vec<Interval> = s.as_slice().iter().map(|&iv| h.angles(iv)).collect();
        assert_eq!(
            angles,
            vec![Interval { lo: -PI, hi: -PI }, Interval { lo: PI, hi: PI }]
        );
        // about mid = π the same point is τ = 0
        let h = HalfAngle::new(Interval { lo: 0.0, hi: TAU });
        let s = h.solve(-1.0, 0.0, -1.0);
        assert_eq!(s.as_slice().len(), 1);
        assert!((h.angle(s.as_slice()[0].lo) - PI).abs() < 1e-15);
    }

    #[test]
    fn roots_are_where_the_left_side_vanishes() {
        let h = HalfAngle::new(TURN);
        for &(a, b, g) in &[(1.0, 2.0, 0.5), (-3.0, 0.1, 1.0), (0.2, -0.7, -0.1)] {
            for iv in solution(&h, a, b, g) {
                for end in [iv.lo, iv.hi] {
                    if end > -PI && end < PI {
                        assert!(value(a, b, g, end).abs() < 1e-12, "{a} {b} {g}: {end}");
                    }
                }
                assert!(value(a, b, g, 0.5 * (iv.lo + iv.hi)) >= 0.0);
            }
        }
    }

    #[test]
    fn tangency_gives_a_single_point() {
        let h = HalfAngle::new(TURN);
        // max of cos(φ − 2) − 1 is 0 at φ = 2
        let sol = solution(&h, 2f64.cos(), 2f64.sin(), -1.0);
        assert_eq!(sol.len(), 1, "{sol:?}");
        assert!((sol[0].lo - 2.0).abs() < 1e-7 && (sol[0].hi - 2.0).abs() < 1e-7);
    }

    proptest! {
        #[test]
        fn solutions_match_the_sign_of_the_left_side(
            a in -10.0f64..10.0, b in -10.0f64..10.0, g in -15.0f64..15.0,
            pick in 0u8..6, lo in -20.0f64..20.0, len in 0.0f64..TAU,
        ) {
            // bias towards the special cases: α = γ, β = 0, tangency
            let (a, b, g) = match pick {
                0 => (a, b, a),
                1 => (a, 0.0, g),
                2 => (a, b, -a.hypot(b)),
                3 => (a, b, a.hypot(b)),
                _ => (a, b, g),
            };
            check(Interval { lo, hi: lo + len }, a, b, g);
            check(Interval { lo, hi: lo + TAU }, a, b, g);
        }
    }
}
