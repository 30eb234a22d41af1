//! The geometric kernel of the exact rigid-body oracles (CHS Chapter 2): what the polygon
//! oracle (SE(2)), the polyhedra oracle (SE(3)) and the arm oracle to come share.
//!
//! The seed separates the degrees of freedom — "either one object may rotate about a fixed
//! axis … or all may translate" — and so does every oracle built on this kernel:
//! - [`trig`]: the atom of a rotation, `α cos φ + β sin φ + γ ≥ 0` (CHS §2.3.2), one solver
//!   ([`trig::HalfAngle::solve`]) with the seed's substitution `τ = tan(φ/2)`;
//! - [`spans`]: the value of one predicate as a handful of intervals on the stack (∧, ∨);
//! - [`aabb`], [`bvh`]: one box type and one box tree, in the plane and in space, for the
//!   enveloping hierarchy (CHS §2.2);
//! - [`hits`]: how every pair's pieces are reported and merged, with the shortcuts that merging
//!   allows (skip a pair whose window already collides, stop at the first piece for a yes/no);
//! - [`memo`]: per-call caches by face or node, reset in O(1), kept per thread with the hits,
//!   so that an oracle call allocates nothing but its answer.

pub(crate) mod aabb;
pub(crate) mod bvh;
pub(crate) mod hits;
pub(crate) mod memo;
pub(crate) mod spans;
pub(crate) mod trig;
