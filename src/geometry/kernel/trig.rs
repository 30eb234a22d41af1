//! The atomic inequality of a rotation, `α cos φ + β sin φ + γ ≥ 0` (CHS §2.3.2), for both
//! rigid-body oracles (and the arm oracle to come).
//!
//! Under a rotation by φ about a fixed axis, every atom of a static predicate — an orientation
//! test in the plane, an edge–face determinant in space — has this form (formula 2.1);
//! geometrically it is the part of the unit circle on one side of the line
//! `α x + β y + γ = 0`, hence one arc (or nothing, or the whole circle).
//!
//! The seed's substitution `τ = tan(φ/2)`: multiplying by `1 + τ²` turns the inequality into
//! `(γ − α) τ² + 2β τ + (α + γ) ≥ 0`, whose solution set on the real line is an interval, the
//! outside of one, or a half-line — at most two intervals. The angle `φ = π` is the point at
//! infinity `τ = ±∞`; it belongs to the solution iff `γ − α ≥ 0` (the leading coefficient), and
//! the degenerate case `γ = α` (the equation turns linear) is exactly the one where `φ = π` is
//! a root. One root formula, [`half_angle_roots`] (cancellation-free, so that a root near the
//! point at infinity stays accurate), serves two ways of reading the solution off:
//! - [`HalfAngle::solve`] (the polygon oracle): departure from the seed, which converts every
//!   root back to an angle with `arctan`. `τ` increases with the angle on each window of
//!   length `2π`, so a predicate is evaluated on interval lists *in τ* (∧, ∨ do not care about
//!   a monotone change of parameter) and only the ends of the final intervals are converted
//!   ([`HalfAngle::angles`]) — no trigonometric function per atom. To keep `φ = π` away from
//!   the interior of the window, the substitution is centred on the window's midpoint:
//!   `φ = mid + ψ`, `τ = tan(ψ/2)`, `ψ ∈ [−L/2, L/2]`;
//! - [`Trig::nonneg_in`] (the polyhedra oracle): the seed's way, the zeros as angles
//!   ([`Trig::zeros`], also what containment along a turn needs), the arc between them chosen
//!   by the direction `(α, β)` in which the left side is largest, cut to the window
//!   ([`arc_in_window`], which also cuts the turning sectors of the enveloping).
//!
//! Both give the same set up to rounding; each oracle keeps its own so that its answers stay
//! bit for bit what they were (`tests/graph_digest.rs` hashes the corners of the roadmap's
//! edges: running the polyhedra oracle through [`HalfAngle::solve`] leaves every answer, node
//! and edge of the SE(3) scenes as it was but moves some corners in the last bits).

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

/// A closed arc of the circle: `[start, start + length]` (mod 2π), `0 ≤ length < 2π` — such
/// as the angles for which a turning sector meets a fixed one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Arc {
    /// First angle.
    pub start: f64,
    /// Angular length.
    pub length: f64,
}

impl Arc {
    /// No angle at all (a negative length).
    pub const EMPTY: Arc = Arc {
        start: 0.0,
        length: -1.0,
    };

    /// Whether the arc has no angle.
    pub fn is_empty(&self) -> bool {
        self.length < 0.0
    }
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
        let (t1, t2) = half_angle_roots(qa, b, qc, disc);
        let (p1, p2) = (to_angle(t1), to_angle(t2));
        if p1 == p2 {
            Zeros::One(p1)
        } else {
            Zeros::Two(p1.min(p2), p1.max(p2))
        }
    }

    /// The closed set `{φ : self(φ) ≥ 0}` as an arc of the whole circle (`None`: every angle),
    /// from the zeros.
    fn nonneg(&self) -> Option<Arc> {
        match self.zeros() {
            Zeros::All => None,
            // constant sign: that of γ, since |γ| > √(α² + β²) or α = β = 0
            Zeros::None => {
                if self.gamma >= 0.0 {
                    None
                } else {
                    Some(Arc::EMPTY)
                }
            }
            // touching: non-negative everywhere if the minimum touches zero (γ > 0), else only
            // at the touching point
            Zeros::One(p) => {
                if self.gamma > 0.0 {
                    None
                } else {
                    Some(Arc {
                        start: p,
                        length: 0.0,
                    })
                }
            }
            Zeros::Two(p1, p2) => {
                // the arc from p1 to p2 is the non-negative one iff its middle leans towards
                // the maximum direction (α, β)
                let m = 0.5 * (p1 + p2);
                let inner = self.alpha * m.cos() + self.beta * m.sin() > 0.0;
                Some(if inner {
                    Arc {
                        start: p1,
                        length: p2 - p1,
                    }
                } else {
                    Arc {
                        start: p2,
                        length: TAU - (p2 - p1),
                    }
                })
            }
        }
    }

    /// `{φ ∈ window : self(φ) ≥ 0}` in angles, from the arc of the whole circle between the
    /// zeros (the polyhedra oracle's way; the window spans at most one turn).
    pub fn nonneg_in<const N: usize>(&self, window: Interval) -> Spans<N> {
        match self.nonneg() {
            None => Spans::single(window),
            Some(arc) if arc.is_empty() => Spans::EMPTY,
            Some(arc) => arc_in_window(arc, window),
        }
    }
}

/// The two roots of `qa τ² + 2b τ + qc = 0` for a positive quarter-discriminant `disc`
/// (`b² − qa·qc`, however the caller rounds it), without cancellation: `q = −(b + sign b · √disc)`,
/// roots `q / qa` and `qc / q` — a root near the point at infinity (`φ = π`) stays accurate.
/// The one root formula of the kernel: [`Trig::zeros`] and [`HalfAngle::solve`] both use it.
#[inline]
fn half_angle_roots(qa: f64, b: f64, qc: f64, disc: f64) -> (f64, f64) {
    let q = -(b + disc.sqrt().copysign(b));
    (q / qa, qc / q)
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
pub(crate) fn arc_in_window<const N: usize>(arc: Arc, window: Interval) -> Spans<N> {
    let Arc { start, length } = arc;
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
    pub fn all<const N: usize>(&self) -> Spans<N> {
        let mut s = Spans::EMPTY;
        s.push(Interval {
            lo: -self.bound,
            hi: self.bound,
        });
        s
    }

    /// `{τ in the window : α cos φ + β sin φ + γ ≥ 0}`, with `φ = mid + 2 atan τ`.
    #[inline]
    pub fn solve<const N: usize>(&self, alpha: f64, beta: f64, gamma: f64) -> Spans<N> {
        // α cos(mid + ψ) + β sin(mid + ψ) = a cos ψ + b sin ψ
        let a = alpha * self.cos_mid + beta * self.sin_mid;
        let b = beta * self.cos_mid - alpha * self.sin_mid;
        // (γ − a) τ² + 2b τ + (a + γ) ≥ 0; ψ = π (τ = ±∞) is in iff γ − a ≥ 0
        let qa = gamma - a;
        let qc = a + gamma;
        const INF: f64 = f64::INFINITY;
        let mut raw = Spans::EMPTY;
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
                let (r1, r2) = half_angle_roots(qa, b, qc, disc);
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
            raw.intersect(&self.all())
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

    /// Brute-force membership on a fine grid, with slack around the zeros. (Regression: the
    /// slack once widened the forbidden zone instead of narrowing it, so a correct answer whose
    /// zero lay within 1e-6 of a grid point failed, e.g. α = −2.2167, β = −0.4133,
    /// γ = −0.5114.)
    fn check(f: Trig) {
        let w = Interval { lo: -PI, hi: PI };
        let set: Spans<8> = f.nonneg_in(w);
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
        let turn = Interval { lo: -PI, hi: PI };
        let all: Spans<8> = f.nonneg_in(turn);
        assert_eq!(all.as_slice(), &[turn]);
        let at_pi: Spans<8> = f.neg().nonneg_in(turn);
        assert!(at_pi
            .as_slice()
            .iter()
            .all(|iv| iv.lo == iv.hi && iv.lo.abs() == PI));
        // α = β = 0
        let s: Spans<8> = Trig::constant(0.0).nonneg_in(turn);
        assert_eq!(s.as_slice(), &[turn]);
        let s: Spans<8> = Trig::constant(-1.0).nonneg_in(turn);
        assert!(s.is_empty());
        assert_eq!(Trig::constant(1.0).zeros(), Zeros::None);
        // cos φ ≥ 0 is [−π/2, π/2]
        let f = Trig {
            alpha: 1.0,
            beta: 0.0,
            gamma: 0.0,
        };
        let s: Spans<8> = f.nonneg_in(turn);
        assert_eq!(s.as_slice().len(), 1);
        let iv = s.as_slice()[0];
        assert!((iv.lo + PI / 2.0).abs() < 1e-15 && (iv.hi - PI / 2.0).abs() < 1e-15);
        // −cos φ ≥ 0 wraps through π
        let s: Spans<8> = f.neg().nonneg_in(Interval { lo: -PI, hi: PI });
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
        let arc = Arc {
            start: 3.0,
            length: 0.5,
        };
        let s: Spans<8> = arc_in_window(arc, Interval { lo: -PI, hi: PI });
        assert_eq!(s.as_slice().len(), 2);
        let s: Spans<8> = arc_in_window(arc, Interval { lo: 10.0, hi: 10.2 });
        assert!(s.is_empty());
        let s: Spans<8> = arc_in_window(arc, Interval { lo: 9.0, hi: 9.3 });
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

#[cfg(test)]
mod half_angle_tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::TAU;

    fn value(alpha: f64, beta: f64, gamma: f64, phi: f64) -> f64 {
        alpha * phi.cos() + beta * phi.sin() + gamma
    }

    /// The solution converted to angles.
    fn solution(h: &HalfAngle, alpha: f64, beta: f64, gamma: f64) -> Vec<Interval> {
        h.solve::<6>(alpha, beta, gamma)
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
        let s = h.solve::<6>(-1.0, 0.0, -1.0);
        let angles: Vec<Interval> = s.as_slice().iter().map(|&iv| h.angles(iv)).collect();
        assert_eq!(
            angles,
            vec![Interval { lo: -PI, hi: -PI }, Interval { lo: PI, hi: PI }]
        );
        // about mid = π the same point is τ = 0
        let h = HalfAngle::new(Interval { lo: 0.0, hi: TAU });
        let s = h.solve::<6>(-1.0, 0.0, -1.0);
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
        /// The two readings of the kernel's solution agree: in τ then converted
        /// ([`HalfAngle::solve`]) and as an arc between the zeros ([`Trig::nonneg_in`]), at
        /// every angle of the window where the left side is not within rounding of zero.
        #[test]
        fn both_readings_agree(
            a in -10.0f64..10.0, b in -10.0f64..10.0, g in -15.0f64..15.0,
            lo in -20.0f64..20.0, len in 0.0f64..TAU,
        ) {
            let window = Interval { lo, hi: lo + len };
            let h = HalfAngle::new(window);
            let tau: Vec<Interval> =
                solution(&h, a, b, g);
            let arcs: Spans<8> = Trig { alpha: a, beta: b, gamma: g }.nonneg_in(window);
            let slack = 1e-9 * (a.abs() + b.abs() + g.abs());
            for k in 0..=500 {
                let phi = (lo + len * k as f64 / 500.0).min(window.hi);
                if value(a, b, g, phi).abs() <= slack {
                    continue;
                }
                let x = tau.iter().any(|iv| iv.contains(phi));
                let y = arcs.as_slice().iter().any(|iv| iv.contains(phi));
                prop_assert_eq!(x, y, "φ = {} in {:?}: τ {:?}, arcs {:?}", phi, window, tau, arcs);
            }
        }
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
