//! The atomic inequality of a rotation: `α cos φ + β sin φ + γ ≥ 0` (CHS §2.3.2).
//!
//! Under a rotation by `φ`, every orientation test of the static predicate becomes such an
//! inequality. Its solution set is one closed arc of the circle (or all of it, or nothing),
//! hence at most two intervals in a parameter window of length `2π`.
//!
//! The roots are found as in the seed, with the substitution `τ = tan(φ/2)`, which turns the
//! equation into `(γ − α) τ² + 2β τ + (α + γ) = 0`; `φ = π` is a root iff `α = γ` (the
//! quadratic degenerates, the other root comes from `2βτ + α + γ = 0`). Departure from the
//! seed: instead of testing signs between the roots, the arc is chosen by symmetry — the left
//! side is `√(α² + β²) · cos(φ − atan2(β, α)) + γ`, so the solution arc is the one centred on
//! `atan2(β, α)`. This stays right when the two roots nearly coincide (tangency).

use crate::interval::Interval;
use std::f64::consts::{PI, TAU};

/// The solution set of one atomic inequality on the circle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Arc {
    /// No angle.
    Empty,
    /// Every angle.
    Full,
    /// The closed arc from `start` to `end` counter-clockwise: angles `start + 2πk ≤ φ ≤
    /// end + 2πk` for some integer `k`; `start ≤ end ≤ start + 2π`.
    Span {
        /// Start angle.
        start: f64,
        /// End angle (`≥ start`).
        end: f64,
    },
}

/// `{φ : α cos φ + β sin φ + γ ≥ 0}`.
pub(crate) fn solve(alpha: f64, beta: f64, gamma: f64) -> Arc {
    let r = alpha.hypot(beta);
    if !(r > 0.0) {
        return if gamma >= 0.0 { Arc::Full } else { Arc::Empty };
    }
    if gamma >= r {
        return Arc::Full;
    }
    if gamma < -r {
        return Arc::Empty;
    }
    // (γ − α) τ² + 2β τ + (α + γ) = 0 with τ = tan(φ/2); the discriminant / 4 is
    // β² − (γ − α)(γ + α) = α² + β² − γ² = (r − γ)(r + γ) ≥ 0 here.
    let a = gamma - alpha;
    let c = alpha + gamma;
    let sq = ((r - gamma) * (r + gamma)).max(0.0).sqrt();
    let (phi1, phi2) = if a == 0.0 {
        // φ = π is a root; the quadratic degenerates to 2βτ + (α + γ) = 0
        let other = if beta != 0.0 {
            2.0 * (-c / (2.0 * beta)).atan()
        } else {
            PI
        };
        (PI, other)
    } else {
        // numerically stable roots of a τ² + 2β τ + c: q = −(β + sign(β)·√disc), τ = q/a, c/q
        let q = -(beta + sq.copysign(beta));
        if q == 0.0 {
            // β = 0 and disc = 0, so c = 0: the double root τ = 0
            (0.0, 0.0)
        } else {
            (2.0 * (q / a).atan(), 2.0 * (c / q).atan())
        }
    };
    let (lo, hi) = (phi1.min(phi2), phi1.max(phi2));
    // The two roots cut the circle into [lo, hi] and [hi, lo + 2π]; the solution is the one
    // centred on the maximiser atan2(β, α).
    let centre = beta.atan2(alpha);
    let mid = 0.5 * (lo + hi);
    if angular_distance(mid, centre) <= 0.5 * PI {
        Arc::Span { start: lo, end: hi }
    } else {
        Arc::Span {
            start: hi,
            end: lo + TAU,
        }
    }
}

/// Distance between two angles on the circle, in `[0, π]`.
fn angular_distance(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

impl Arc {
    /// Calls `push` with the pieces of the arc inside `window` (whose length must not exceed
    /// `2π` by much), in increasing order: at most two, or three when the window is a full
    /// turn and the arc touches both of its ends.
    pub fn pieces_in(&self, window: Interval, mut push: impl FnMut(Interval)) {
        match *self {
            Arc::Empty => {}
            Arc::Full => push(window),
            Arc::Span { start, end } => {
                // first k with end + 2πk ≥ window.lo
                let mut k = ((window.lo - end) / TAU).ceil();
                for _ in 0..4 {
                    let (s, e) = (start + TAU * k, end + TAU * k);
                    if s > window.hi {
                        break;
                    }
                    let (lo, hi) = (s.max(window.lo), e.min(window.hi));
                    if lo <= hi {
                        push(Interval { lo, hi });
                    }
                    k += 1.0;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn holds(alpha: f64, beta: f64, gamma: f64, phi: f64) -> f64 {
        alpha * phi.cos() + beta * phi.sin() + gamma
    }

    fn in_arc(arc: &Arc, phi: f64) -> bool {
        let mut hit = false;
        arc.pieces_in(Interval { lo: -PI, hi: PI }, |iv| hit |= iv.contains(phi));
        hit
    }

    /// Checks the arc against the sign of the left side on a fine grid, allowing a slack of
    /// `slack` in the value (where the left side is nearly zero either answer is right).
    fn check(alpha: f64, beta: f64, gamma: f64) {
        let arc = solve(alpha, beta, gamma);
        let scale = alpha.abs() + beta.abs() + gamma.abs();
        let slack = 1e-9 * scale.max(1e-300);
        for k in 0..=4000 {
            let phi = -PI + TAU * k as f64 / 4000.0;
            let v = holds(alpha, beta, gamma, phi);
            if v > slack {
                assert!(
                    in_arc(&arc, phi),
                    "{alpha} {beta} {gamma}: φ={phi} v={v} {arc:?}"
                );
            }
            if v < -slack {
                assert!(
                    !in_arc(&arc, phi),
                    "{alpha} {beta} {gamma}: φ={phi} v={v} {arc:?}"
                );
            }
        }
    }

    #[test]
    fn degenerate_cases() {
        check(0.0, 0.0, 1.0); // everything
        check(0.0, 0.0, -1.0); // nothing
        check(0.0, 0.0, 0.0); // everything (closed)
        check(1.0, 0.0, 1.0); // α = γ: φ = π is a root, double (tangent): all
        check(-1.0, 0.0, -1.0); // α = γ < 0: only φ = π
        check(1.0, 1.0, 1.0); // α = γ with β ≠ 0: roots π and −π/2
        check(-2.0, 1.0, -2.0);
        check(1.0, 0.0, -1.0); // tangent at φ = 0
        check(1.0, 0.0, 0.0); // half circle
        check(0.0, 1.0, 0.0); // half circle about π/2
        check(0.0, -3.0, 2.9);
    }

    #[test]
    fn roots_are_where_the_left_side_vanishes() {
        for &(a, b, g) in &[(1.0, 2.0, 0.5), (-3.0, 0.1, 1.0), (0.2, -0.7, -0.1)] {
            match solve(a, b, g) {
                Arc::Span { start, end } => {
                    assert!(holds(a, b, g, start).abs() < 1e-12);
                    assert!(holds(a, b, g, end).abs() < 1e-12);
                    assert!(holds(a, b, g, 0.5 * (start + end)) > 0.0);
                }
                other => panic!("expected an arc, got {other:?}"),
            }
        }
    }

    #[test]
    fn tangency_gives_a_single_point() {
        // max of cos φ − 1 is 0 at φ = 0
        let arc = solve(1.0, 0.0, -1.0);
        match arc {
            Arc::Span { start, end } => assert!(start.abs() < 1e-7 && end.abs() < 1e-7),
            other => panic!("{other:?}"),
        }
        // rotated: max at φ = 2
        let (a, b) = (2f64.cos(), 2f64.sin());
        match solve(a, b, -1.0) {
            Arc::Span { start, end } => {
                assert!((start - 2.0).abs() < 1e-7 && (end - 2.0).abs() < 1e-7)
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn pieces_in_a_window_wrap_around() {
        let arc = Arc::Span {
            start: -1.0,
            end: 1.0,
        };
        let mut pieces = Vec::new();
        arc.pieces_in(Interval { lo: 0.0, hi: TAU }, |iv| pieces.push(iv));
        assert_eq!(pieces.len(), 2);
        assert_eq!(pieces[0], Interval { lo: 0.0, hi: 1.0 });
        assert!((pieces[1].lo - (TAU - 1.0)).abs() < 1e-15 && pieces[1].hi == TAU);
        // a window far from the origin: the copy of the arc about 16·2π = 100.53 covers it
        let mut pieces = Vec::new();
        arc.pieces_in(
            Interval {
                lo: 100.0,
                hi: 101.0,
            },
            |iv| pieces.push(iv),
        );
        assert_eq!(
            pieces,
            vec![Interval {
                lo: 100.0,
                hi: 101.0
            }]
        );
    }

    proptest! {
        #[test]
        fn arcs_match_the_sign_of_the_left_side(
            a in -10.0f64..10.0, b in -10.0f64..10.0, g in -15.0f64..15.0,
            pick in 0u8..6,
        ) {
            // bias towards the special cases: α = γ, β = 0, tangency
            let (a, b, g) = match pick {
                0 => (a, b, a),
                1 => (a, 0.0, g),
                2 => (a, b, -a.hypot(b)),
                3 => (a, b, a.hypot(b)),
                _ => (a, b, g),
            };
            check(a, b, g);
        }
    }
}
