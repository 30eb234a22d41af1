//! The atomic inequality of the rotational case, `α cos φ + β sin φ + γ ≥ 0` (CHS §2.3.2).
//!
//! Every atom of the edge–face predicate under a rotation about a fixed axis has this form
//! (formula 2.1); geometrically it is the part of the unit circle on one side of the line
//! `α x + β y + γ = 0`, hence one arc (or nothing, or the whole circle).
//!
//! The zeros are found as in the seed: for `φ ≠ π` substitute `t = tan(φ/2)`, which gives
//! `(γ − α) t² + 2β t + (α + γ) = 0`; `φ = π` is a zero iff `γ = α` (the line passes through
//! `(−1, 0)`), and then the quadratic degenerates to `2β t + 2α = 0`. We use the cancellation-free
//! form of the quadratic formula (`t₁ = q / (γ − α)`, `t₂ = (α + γ) / q` with
//! `q = −(β + sign β · √(α² + β² − γ²))`), so that a root near `φ = π` (huge `t`) stays
//! accurate. Which of the two arcs between the zeros satisfies the inequality is read off the
//! direction `(α, β)` in which the left side is largest, not from a sample of its sign.

use super::spans::Spans;
use crate::interval::Interval;
use std::f64::consts::{PI, TAU};

/// `α cos φ + β sin φ + γ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Trig {
    /// Coefficient of `cos φ`.
    pub alpha: f64,
    /// Coefficient of `sin φ`.
    pub beta: f64,
    /// Constant.
    pub gamma: f64,
}

/// The zeros of a [`Trig`] in `(−π, π]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Zeros {
    /// No zero.
    None,
    /// One zero (the line touches the circle).
    One(f64),
    /// Two zeros, increasing.
    Two(f64, f64),
    /// Zero everywhere (`α = β = γ = 0`).
    All,
}

/// A closed arc of the circle: `[start, start + length]` (mod 2π).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Arc {
    /// No angle.
    Empty,
    /// Every angle.
    Full,
    /// `start ∈ (−π, π]`, `0 ≤ length < 2π`.
    Part {
        /// First angle.
        start: f64,
        /// Angular length.
        length: f64,
    },
}

impl Trig {
    /// The constant function `c`.
    #[cfg(test)]
    pub fn constant(c: f64) -> Trig {
        Trig {
            alpha: 0.0,
            beta: 0.0,
            gamma: c,
        }
    }

    /// Value at `φ`.
    pub fn eval(&self, phi: f64) -> f64 {
        let (s, c) = phi.sin_cos();
        self.alpha * c + self.beta * s + self.gamma
    }

    /// Derivative at `φ`.
    pub fn slope(&self, phi: f64) -> f64 {
        let (s, c) = phi.sin_cos();
        self.beta * c - self.alpha * s
    }

    /// `self + c`.
    pub fn plus(self, c: f64) -> Trig {
        Trig {
            gamma: self.gamma + c,
            ..self
        }
    }

    /// `self − other`.
    pub fn minus(self, o: Trig) -> Trig {
        Trig {
            alpha: self.alpha - o.alpha,
            beta: self.beta - o.beta,
            gamma: self.gamma - o.gamma,
        }
    }

    /// `−self`.
    pub fn neg(self) -> Trig {
        Trig {
            alpha: -self.alpha,
            beta: -self.beta,
            gamma: -self.gamma,
        }
    }

    /// Amplitude `√(α² + β²)`.
    #[cfg(test)]
    pub fn amplitude(&self) -> f64 {
        self.alpha.hypot(self.beta)
    }

    /// The zeros in `(−π, π]`, by the substitution `t = tan(φ/2)` (CHS §2.3.2).
    pub fn zeros(&self) -> Zeros {
        let (a, b, g) = (self.alpha, self.beta, self.gamma);
        if a == 0.0 && b == 0.0 {
            return if g == 0.0 { Zeros::All } else { Zeros::None };
        }
        // (γ − α) t² + 2β t + (α + γ) = 0
        let qa = g - a;
        let qc = a + g;
        if qa == 0.0 {
            // φ = π solves the equation; the rest is 2β t + 2α = 0
            if b == 0.0 {
                // the vertical line x = −1 touches the circle at (−1, 0) only
                return Zeros::One(PI);
            }
            let other = 2.0 * (-a / b).atan();
            return if other == PI || other == -PI {
                Zeros::One(PI)
            } else {
                Zeros::Two(other, PI)
            };
        }
        let disc = b * b - qa * qc; // α² + β² − γ²
        if disc < 0.0 {
            return Zeros::None;
        }
        if disc == 0.0 {
            return Zeros::One(2.0 * (-b / qa).atan());
        }
        let s = disc.sqrt();
        let q = -(b + s.copysign(b));
        let (t1, t2) = (q / qa, qc / q);
        let (p1, p2) = (to_angle(t1), to_angle(t2));
        if p1 == p2 {
            Zeros::One(p1)
        } else {
            Zeros::Two(p1.min(p2), p1.max(p2))
        }
    }

    /// The closed set `{φ : self(φ) ≥ 0}` as an arc.
    pub fn nonneg(&self) -> Arc {
        match self.zeros() {
            Zeros::All => Arc::Full,
            // constant sign: that of γ, since |γ| > √(α² + β²) or α = β = 0
            Zeros::None => {
                if self.gamma >= 0.0 {
                    Arc::Full
                } else {
                    Arc::Empty
                }
            }
            // touching: non-negative everywhere if the minimum touches zero (γ > 0), else only
            // at the touching point
            Zeros::One(p) => {
                if self.gamma > 0.0 {
                    Arc::Full
                } else {
                    Arc::Part {
                        start: p,
                        length: 0.0,
                    }
                }
            }
            Zeros::Two(p1, p2) => {
                // the arc from p1 to p2 is the non-negative one iff its middle leans towards
                // the maximum direction (α, β)
                let m = 0.5 * (p1 + p2);
                let inner = self.alpha * m.cos() + self.beta * m.sin() > 0.0;
                if inner {
                    Arc::Part {
                        start: p1,
                        length: p2 - p1,
                    }
                } else {
                    Arc::Part {
                        start: p2,
                        length: TAU - (p2 - p1),
                    }
                }
            }
        }
    }

    /// `{φ ∈ window : self(φ) ≥ 0}`; the window spans at most one turn.
    pub fn nonneg_in(&self, window: Interval) -> Spans {
        arc_in_window(self.nonneg(), window)
    }
}

/// `φ = 2 atan t`, in `(−π, π]` (an infinite `t` gives `π`).
fn to_angle(t: f64) -> f64 {
    let p = 2.0 * t.atan();
    if p <= -PI {
        PI
    } else {
        p
    }
}

/// The parts of `arc` (taken modulo 2π) inside `window`, which spans at most one turn.
pub(crate) fn arc_in_window(arc: Arc, window: Interval) -> Spans {
    match arc {
        Arc::Empty => Spans::EMPTY,
        Arc::Full => Spans::single(window),
        Arc::Part { start, length } => {
            let mut out = Spans::EMPTY;
            // first copy of the arc that ends at or after the window's start
            let k0 = ((window.lo - start - length) / TAU).ceil();
            let mut s = start + k0 * TAU;
            for _ in 0..3 {
                if s > window.hi {
                    break;
                }
                let iv = Interval {
                    lo: s.max(window.lo),
                    hi: (s + length).min(window.hi),
                };
                if iv.lo <= iv.hi {
                    out.push(iv);
                }
                s += TAU;
            }
            out
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Brute-force membership on a fine grid, with slack around the zeros. (Regression: the
    /// slack once widened the forbidden zone instead of narrowing it, so a correct answer whose
    /// zero lay within 1e-6 of a grid point failed, e.g. α = −2.2167, β = −0.4133,
    /// γ = −0.5114.)
    fn check(f: Trig) {
        let w = Interval { lo: -PI, hi: PI };
        let set = f.nonneg_in(w);
        let amp = f.amplitude().max(f.gamma.abs()).max(1e-300);
        for i in 0..=4000 {
            let phi = -PI + TAU * i as f64 / 4000.0;
            let v = f.eval(phi) / amp;
            let inside = set.as_slice().iter().any(|iv| iv.contains(phi));
            if v > 1e-9 {
                assert!(
                    inside,
                    "{f:?}: φ = {phi} has f = {v} > 0 but is outside {set:?}"
                );
            }
            if v < -1e-9 {
                // the set may be slightly larger than the true one (conservative, in favour of
                // collision), so only a point well inside an interval is wrong
                let well_inside = set
                    .as_slice()
                    .iter()
                    .any(|iv| iv.lo + 1e-6 < phi && phi < iv.hi - 1e-6);
                assert!(
                    !well_inside,
                    "{f:?}: φ = {phi} has f = {v} < 0 but is inside {set:?}"
                );
            }
        }
    }

    #[test]
    fn zero_near_a_grid_point() {
        check(Trig {
            alpha: -2.2166605983332395,
            beta: -0.4133090059105891,
            gamma: -0.5113824325021508,
        });
    }

    #[test]
    fn seed_special_cases() {
        // γ = α: φ = π is a zero
        let f = Trig {
            alpha: 1.0,
            beta: 1.0,
            gamma: 1.0,
        };
        assert!(matches!(f.zeros(), Zeros::Two(a, b) if (a + PI / 2.0).abs() < 1e-15 && b == PI));
        check(f);
        // γ = α, β = 0: touching at (−1, 0)
        let f = Trig {
            alpha: 2.0,
            beta: 0.0,
            gamma: 2.0,
        };
        assert_eq!(f.zeros(), Zeros::One(PI));
        assert_eq!(f.nonneg(), Arc::Full);
        assert_eq!(
            f.neg().nonneg(),
            Arc::Part {
                start: PI,
                length: 0.0
            }
        );
        // α = β = 0
        assert_eq!(Trig::constant(0.0).nonneg(), Arc::Full);
        assert_eq!(Trig::constant(-1.0).nonneg(), Arc::Empty);
        assert_eq!(Trig::constant(1.0).zeros(), Zeros::None);
        // cos φ ≥ 0 is [−π/2, π/2]
        let f = Trig {
            alpha: 1.0,
            beta: 0.0,
            gamma: 0.0,
        };
        match f.nonneg() {
            Arc::Part { start, length } => {
                assert!((start + PI / 2.0).abs() < 1e-15 && (length - PI).abs() < 1e-15)
            }
            a => panic!("{a:?}"),
        }
        // −cos φ ≥ 0 wraps through π
        let s = f.neg().nonneg_in(Interval { lo: -PI, hi: PI });
        assert_eq!(s.as_slice().len(), 2);
        check(f.neg());
    }

    #[test]
    fn zeros_near_pi_are_accurate() {
        // zero at π − 1e-9: f = sin(φ − (π − 1e-9)) = −cos(ε)... build from the zeros
        let z = PI - 1e-9;
        let f = Trig {
            alpha: -z.sin(),
            beta: z.cos(),
            gamma: 0.0,
        };
        match f.zeros() {
            Zeros::Two(_, b) => assert!((b - z).abs() < 1e-15, "{b}"),
            o => panic!("{o:?}"),
        }
    }

    #[test]
    fn window_copies() {
        let arc = Arc::Part {
            start: 3.0,
            length: 0.5,
        };
        let s = arc_in_window(arc, Interval { lo: -PI, hi: PI });
        assert_eq!(s.as_slice().len(), 2);
        let s = arc_in_window(arc, Interval { lo: 10.0, hi: 10.2 });
        assert!(s.is_empty());
        let s = arc_in_window(arc, Interval { lo: 9.0, hi: 9.3 });
        assert_eq!(
            s.as_slice(),
            &[Interval {
                lo: 3.0 + TAU,
                hi: 9.3
            }]
        );
    }

    proptest! {
        #[test]
        fn nonneg_matches_brute_force(a in -3.0f64..3.0, b in -3.0f64..3.0, g in -4.0f64..4.0) {
            check(Trig { alpha: a, beta: b, gamma: g });
        }

        #[test]
        fn zeros_solve_the_seed_quadratic(a in -3.0f64..3.0, b in -3.0f64..3.0, g in -4.0f64..4.0) {
            let f = Trig { alpha: a, beta: b, gamma: g };
            let zs: Vec<f64> = match f.zeros() {
                Zeros::One(p) => vec![p],
                Zeros::Two(p, q) => vec![p, q],
                _ => vec![],
            };
            for p in zs {
                prop_assert!(f.eval(p).abs() <= 1e-9 * (1.0 + a.abs() + b.abs() + g.abs()));
                let t = (p / 2.0).tan();
                if t.abs() < 1e6 {
                    let quad = (g - a) * t * t + 2.0 * b * t + (a + g);
                    prop_assert!(quad.abs() <= 1e-8 * (1.0 + t * t) * (1.0 + a.abs() + b.abs() + g.abs()));
                }
            }
        }
    }
}
