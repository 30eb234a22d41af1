//! What a roadmap grows from.

use super::super::graph::Roadmap;

/// What a roadmap grows from: a learnt roadmap and/or a pair of configurations to join.
#[derive(Clone, Copy, Default)]
pub(super) struct Seeds<'r> {
    pub(super) base: Option<&'r Roadmap>,
    pub(super) pair: Option<(&'r [f64], &'r [f64])>,
}
