//! Collision oracles: *all* collision intervals of a straight motion (CHS §1.2, Chapter 2).
//!
//! The via-point planner never samples along a motion: it asks an oracle for every parameter
//! interval in which the moving robot collides (*intersectSegment* for a bounded motion,
//! *intersectLine* for an unbounded one or a full turn) and dodges through the free sections.
//! The number of such calls is the seed's cost measure, so every call is counted
//! ([`CallCounts`]): callers go through [`CountedOracle`], which counts and then asks the
//! oracle.
//!
//! Implementations:
//! - [`discs::Discs`]: a point among discs (balls in R^n), analytic (CHS Appendix A.1);
//! - [`polygons`]: a polygonal robot among polygons in SE(2);
//! - [`bodies::PlanarBodies`]: several polygonal bodies in the plane, all translating or one
//!   turning (SE(2)^k);
//! - [`bodies3::SolidBodies`]: several polyhedral bodies in space, all translating or one
//!   turning about a fixed axis (SE(3)^k);
//! - [`polyhedra`]: a polyhedral robot among polyhedra in SE(3) (CHS Chapter 2);
//! - [`minkowski::Minkowski`]: a translating polygon through its C-obstacles (LaValle 3.3.2);
//! - [`sampled::Sampled`]: checks states at a resolution like OMPL's `DiscreteMotionValidator`
//!   — the baseline the benchmarks compare against, never the default;
//! - [`Bounded`]: adds "outside the bounds is obstacle" to any of them.

pub mod bodies;
pub mod bodies3;
pub mod discs;
pub mod minkowski;
pub mod polygons;
pub mod polyhedra;
pub mod sampled;
mod several;

use crate::interval::{Interval, IntervalList};
use crate::space::{Motion, Space, Sweep};
use serde::{Deserialize, Serialize};
use std::ops::{Add, AddAssign};

/// What an oracle cannot answer.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OracleError {
    /// The oracle cannot compute intervals for this kind of motion (for example a simultaneous
    /// translation and rotation asked of an exact polyhedral oracle).
    #[error("unsupported motion: {0}")]
    Unsupported(String),
    /// The deadline watched on this thread ([`crate::deadline::watching`]) passed during the
    /// call: there is no answer, and the caller stops as at its deadline.
    #[error("interrupted: the deadline passed during an oracle call")]
    Interrupted,
}

/// Counts of oracle work: the seed's cost measure (CHS A.1.3) and more.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct CallCounts {
    /// Bounded motions asked about (intersectSegment, and yes/no motion checks).
    pub segment_calls: u64,
    /// Unbounded motions and full turns asked about (intersectLine).
    pub line_calls: u64,
    /// Single configurations checked.
    pub state_checks: u64,
    /// Primitive pairs (disc, edge–face, triangle–triangle …) an exact oracle actually
    /// evaluated after culling; states a sampled oracle checked inside a motion.
    pub pairs_tested: u64,
}

impl CallCounts {
    /// Segment plus line calls: the seed's "intersect calls".
    pub fn intersect_calls(&self) -> u64 {
        self.segment_calls + self.line_calls
    }
}

impl AddAssign for CallCounts {
    fn add_assign(&mut self, o: CallCounts) {
        self.segment_calls += o.segment_calls;
        self.line_calls += o.line_calls;
        self.state_checks += o.state_checks;
        self.pairs_tested += o.pairs_tested;
    }
}

impl Add for CallCounts {
    type Output = CallCounts;
    fn add(mut self, o: CallCounts) -> CallCounts {
        self += o;
        self
    }
}

impl std::iter::Sum for CallCounts {
    fn sum<I: Iterator<Item = CallCounts>>(iter: I) -> CallCounts {
        iter.fold(CallCounts::default(), Add::add)
    }
}

/// Reusable scratch space for [`CollisionOracle::intervals_into`]: each thread (each via-point
/// search) keeps one, so that in steady state an intersect call allocates nothing (as
/// proved by `tests/alloc_free.rs`). Oracles may use any buffer; none carries meaning between
/// calls.
#[derive(Debug, Default)]
pub struct Workspace {
    /// Unsorted, unclipped hits before they are merged into the answer.
    pub hits: Vec<Interval>,
    /// One configuration's worth of numbers (sampled checking writes its states here).
    pub config: Vec<f64>,
    /// The inner answer of a wrapper such as [`Bounded`].
    pub inner: IntervalList,
    /// A motion a wrapper narrows before it asks its inner oracle.
    pub motion: Option<Motion>,
    /// Numbers an oracle lays out as it likes (the planar disc loop gathers the discs a line
    /// meets here); only ever grown, so that no call pays for zeroing it.
    pub numbers: Vec<f64>,
}

impl Workspace {
    /// An empty workspace; its buffers grow on first use and are kept.
    pub fn new() -> Self {
        Workspace::default()
    }
}

/// A scene's collision test, asked about whole motions.
///
/// # Contract
/// - [`intervals`](Self::intervals) returns exactly the closed set of `t ∈ motion.range` at
///   which `motion.at(t)` collides (touching counts as collision), as a sorted list clipped to
///   `motion.range`. For an unbounded range, intervals may reach `±∞`. Exact oracles must not
///   miss any collision; a [`sampled::Sampled`] oracle is an approximation and says so.
/// - Implementations add the primitive pairs they evaluate to `counts.pairs_tested` but do not
///   count the call itself: callers use [`CountedOracle`], which does.
/// - Must be thread safe: learning asks from many threads at once.
/// - Never panics on a motion of the right dimension; motions it cannot handle get
///   [`OracleError::Unsupported`].
pub trait CollisionOracle: Send + Sync {
    /// All collision intervals of `motion` within `motion.range`.
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError>;

    /// Allocation-free twin of [`intervals`](Self::intervals): writes the answer into `out`
    /// (overwriting it) using `ws` for scratch, so that the hot path allocates nothing per
    /// call in steady state. Same contract and same answer as `intervals`. The
    /// default calls `intervals` (and so allocates); the oracles on the hot path override it.
    fn intervals_into(
        &self,
        motion: &Motion,
        out: &mut IntervalList,
        ws: &mut Workspace,
        counts: &mut CallCounts,
    ) -> Result<(), OracleError> {
        let _ = ws;
        *out = self.intervals(motion, counts)?;
        Ok(())
    }

    /// Whether configuration `q` collides.
    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool;

    /// Whether `q` surely collides, by a test far cheaper than [`collides`](Self::collides)
    /// that may miss collisions but never reports one `collides` would not (an arm's balls
    /// inside its links against the obstacles' true shapes, [`crate::robot::inner`]):
    /// `Some(true)` where it finds one, `Some(false)` where it does not, `None` for an oracle
    /// without such a test (the default). A direct path with a surely colliding inner corner
    /// is blocked before any of its sweeps is asked. Not a counted call.
    fn surely_collides(&self, q: &[f64]) -> Option<bool> {
        let _ = q;
        None
    }

    /// Whether the whole of `motion.range` is free. The default asks for all intervals;
    /// oracles override it to stop at the first collision found.
    fn motion_is_free(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<bool, OracleError> {
        Ok(self.intervals(motion, counts)?.is_empty())
    }

    /// The earliest collision of `motion`: the least `t` of its collision set within
    /// `motion.range`, `None` if the whole range is free. What an RRT extend needs (the free
    /// prefix, CHS §1.2) and no more: an oracle may skip every pair that cannot collide before
    /// the earliest collision found so far. The default takes the first of all intervals.
    fn first_collision(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<Option<f64>, OracleError> {
        Ok(self
            .intervals(motion, counts)?
            .iter()
            .next()
            .map(|iv| iv.lo))
    }

    /// For an oracle of several bodies: whether body `body` of configuration `q` collides with
    /// the obstacles or with one of the bodies before it in `q` (the bodies after it are not
    /// looked at, so `q` may hold anything there). A sampler places bodies one at a time with
    /// it: uniform draws of all bodies at once are almost never free when the bodies crowd a
    /// narrow space, while each body alone often is. `None` for an oracle of one robot (the
    /// default). Not a counted call: the caller counts a state check.
    fn body_collides(&self, q: &[f64], body: usize, counts: &mut CallCounts) -> Option<bool> {
        let _ = (q, body, counts);
        None
    }

    /// Whether asking about an unbounded range costs no more than asking about a bounded one
    /// (analytic oracles). [`Bounded`] then asks about the motion as it is instead of a copy
    /// clipped to the bounds. Default `false`: enveloping needs bounded sweeps.
    fn prefers_unclipped(&self) -> bool {
        false
    }
}

/// Counting access to an oracle: every question goes through here, so that every call is
/// counted exactly once (the seed's cost measure).
pub trait CountedOracle {
    /// intersectSegment / intersectLine: all collision intervals of `motion`, counted as one
    /// segment call or one line call.
    fn intersect(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError>;
    /// [`intersect`](Self::intersect) without allocating: the answer goes into `out`, scratch
    /// into `ws` (see [`CollisionOracle::intervals_into`]). Counted the same way.
    fn intersect_into(
        &self,
        motion: &Motion,
        out: &mut IntervalList,
        ws: &mut Workspace,
        counts: &mut CallCounts,
    ) -> Result<(), OracleError>;
    /// The earliest collision of `motion` ([`CollisionOracle::first_collision`]), counted as
    /// one segment or line call, like [`intersect`](Self::intersect).
    fn first_hit(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<Option<f64>, OracleError>;
    /// A yes/no check of a bounded motion, counted as one segment call.
    fn check_motion(&self, motion: &Motion, counts: &mut CallCounts) -> Result<bool, OracleError>;
    /// Whether `q` is collision-free, counted as one state check.
    fn is_free(&self, q: &[f64], counts: &mut CallCounts) -> bool;
}

impl<T: CollisionOracle + ?Sized> CountedOracle for T {
    fn intersect(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        match motion.sweep {
            Sweep::Segment => counts.segment_calls += 1,
            Sweep::Line | Sweep::Turn => counts.line_calls += 1,
        }
        self.intervals(motion, counts)
    }

    fn intersect_into(
        &self,
        motion: &Motion,
        out: &mut IntervalList,
        ws: &mut Workspace,
        counts: &mut CallCounts,
    ) -> Result<(), OracleError> {
        match motion.sweep {
            Sweep::Segment => counts.segment_calls += 1,
            Sweep::Line | Sweep::Turn => counts.line_calls += 1,
        }
        self.intervals_into(motion, out, ws, counts)
    }

    fn first_hit(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<Option<f64>, OracleError> {
        match motion.sweep {
            Sweep::Segment => counts.segment_calls += 1,
            Sweep::Line | Sweep::Turn => counts.line_calls += 1,
        }
        self.first_collision(motion, counts)
    }

    fn check_motion(&self, motion: &Motion, counts: &mut CallCounts) -> Result<bool, OracleError> {
        counts.segment_calls += 1;
        self.motion_is_free(motion, counts)
    }

    fn is_free(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        counts.state_checks += 1;
        !self.collides(q, counts)
    }
}

/// References and smart pointers to an oracle are oracles (so that `Box<dyn CollisionOracle>`
/// and `&dyn CollisionOracle` can be wrapped by [`Bounded`] or [`sampled::Sampled`]).
macro_rules! forward_oracle {
    ($($ptr:ty),*) => {$(
        impl<T: CollisionOracle + ?Sized> CollisionOracle for $ptr {
            fn intervals(&self, motion: &Motion, counts: &mut CallCounts) -> Result<IntervalList, OracleError> {
                (**self).intervals(motion, counts)
            }
            fn intervals_into(&self, motion: &Motion, out: &mut IntervalList, ws: &mut Workspace, counts: &mut CallCounts) -> Result<(), OracleError> {
                (**self).intervals_into(motion, out, ws, counts)
            }
            fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
                (**self).collides(q, counts)
            }
            fn surely_collides(&self, q: &[f64]) -> Option<bool> {
                (**self).surely_collides(q)
            }
            fn body_collides(&self, q: &[f64], body: usize, counts: &mut CallCounts) -> Option<bool> {
                (**self).body_collides(q, body, counts)
            }
            fn motion_is_free(&self, motion: &Motion, counts: &mut CallCounts) -> Result<bool, OracleError> {
                (**self).motion_is_free(motion, counts)
            }
            fn first_collision(&self, motion: &Motion, counts: &mut CallCounts) -> Result<Option<f64>, OracleError> {
                (**self).first_collision(motion, counts)
            }
            fn prefers_unclipped(&self) -> bool {
                (**self).prefers_unclipped()
            }
        }
    )*};
}

forward_oracle!(&T, Box<T>, std::sync::Arc<T>);

/// Wraps an oracle so that a position outside the space's bounds counts as obstacle.
///
/// Unbounded motions are clipped to the part inside the bounds before the inner oracle is
/// asked, so the inner oracle only ever sees bounded sweeps of translation, and every borderline
/// has bounded free sections (CHS §1.3 assumes "the whole scene is bounded in some way").
pub struct Bounded<O> {
    space: Space,
    inner: O,
}

impl<O: CollisionOracle> Bounded<O> {
    /// `inner` restricted to the bounds of `space`.
    pub fn new(space: Space, inner: O) -> Self {
        Bounded { space, inner }
    }

    /// The wrapped oracle.
    pub fn inner(&self) -> &O {
        &self.inner
    }

    /// The space whose bounds apply.
    pub fn space(&self) -> &Space {
        &self.space
    }
}

impl<O: CollisionOracle> CollisionOracle for Bounded<O> {
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        let Some(inside) = self.space.inside_range(motion) else {
            return Ok(IntervalList::single(motion.range));
        };
        if inside == motion.range {
            // the common case of a segment within the bounds: nothing to add, nothing to clip
            return self.inner.intervals(motion, counts);
        }
        // partly out of bounds: the workspace path adds the out-of-bounds ends around the
        // inner answer (one copy of that logic)
        let mut out = IntervalList::new();
        self.intervals_into(motion, &mut out, &mut Workspace::new(), counts)?;
        Ok(out)
    }

    fn intervals_into(
        &self,
        motion: &Motion,
        out: &mut IntervalList,
        ws: &mut Workspace,
        counts: &mut CallCounts,
    ) -> Result<(), OracleError> {
        let Some(inside) = self.space.inside_range(motion) else {
            out.clear();
            out.push(motion.range);
            return Ok(());
        };
        if inside == motion.range {
            return self.inner.intervals_into(motion, out, ws, counts);
        }
        // the inner answer goes to a buffer of the workspace (taken out, so that the inner
        // oracle may use the rest of it), then the out-of-bounds ends are added around it
        let mut hits = std::mem::take(&mut ws.inner);
        let asked = if self.inner.prefers_unclipped() {
            self.inner.intervals_into(motion, &mut hits, ws, counts)
        } else {
            let mut clipped = ws.motion.take().unwrap_or_default();
            clipped.copy_from(motion);
            clipped.range = inside;
            let r = self.inner.intervals_into(&clipped, &mut hits, ws, counts);
            ws.motion = Some(clipped);
            r
        };
        if let Err(e) = asked {
            ws.inner = hits;
            return Err(e);
        }
        if self.inner.prefers_unclipped() {
            hits.clip_in_place(inside);
        }
        out.clear();
        if inside.lo > motion.range.lo {
            out.push(Interval {
                lo: motion.range.lo,
                hi: inside.lo,
            });
        }
        hits.iter().for_each(|iv| out.push(*iv));
        if inside.hi < motion.range.hi {
            out.push(Interval {
                lo: inside.hi,
                hi: motion.range.hi,
            });
        }
        ws.inner = hits;
        Ok(())
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        !self.space.in_bounds(q) || self.inner.collides(q, counts)
    }

    fn surely_collides(&self, q: &[f64]) -> Option<bool> {
        let inner = self.inner.surely_collides(q)?;
        Some(inner || !self.space.in_bounds(q))
    }

    fn body_collides(&self, q: &[f64], body: usize, counts: &mut CallCounts) -> Option<bool> {
        let inner = self.inner.body_collides(q, body, counts)?;
        Some(inner || !self.space.body_in_bounds(q, body))
    }

    fn first_collision(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<Option<f64>, OracleError> {
        let Some(inside) = self.space.inside_range(motion) else {
            return Ok(Some(motion.range.lo));
        };
        if inside.lo > motion.range.lo {
            return Ok(Some(motion.range.lo));
        }
        let inner = if inside == motion.range || self.inner.prefers_unclipped() {
            self.inner.first_collision(motion, counts)?
        } else {
            let mut clipped = motion.clone();
            clipped.range = inside;
            self.inner.first_collision(&clipped, counts)?
        };
        // leaving the bounds is the latest the first collision can be
        let exit = (inside.hi < motion.range.hi).then_some(inside.hi);
        Ok(match (inner, exit) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        })
    }

    fn motion_is_free(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<bool, OracleError> {
        match self.space.inside_range(motion) {
            Some(inside) if inside == motion.range => self.inner.motion_is_free(motion, counts),
            _ => Ok(false),
        }
    }
}
