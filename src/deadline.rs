//! Budgets that hold: one [`Deadline`] travels from the command line through the learner and
//! the query down to the via-point search, which checks it before every oracle call.
//!
//! A planner's time budget is a promise. Checking the clock only between learning rounds let
//! one round on a big mesh (dozens of deep via-point searches, seconds each) overrun a 30-s
//! budget by minutes; checking it before every intersect call bounds the overrun by the cost
//! of one call. A deadline also carries an optional cancel flag, so that Ctrl-C or a caller
//! on another thread stops the same checks.
//!
//! ```
//! use std::time::Duration;
//! use viaroad::deadline::Deadline;
//!
//! let never = Deadline::none();
//! assert!(!never.expired());
//! let soon = Deadline::after(Duration::ZERO);
//! assert!(soon.expired());
//! // an absurdly long budget is no deadline at all, never an overflow
//! assert!(!Deadline::after(Duration::MAX).expired());
//! ```

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// A point in time after which long operations stop and return what they have, and/or a flag
/// that stops them at once. Cheap to clone and to check (one clock read).
#[derive(Clone, Debug, Default)]
pub struct Deadline {
    at: Option<Instant>,
    cancel: Option<Arc<AtomicBool>>,
    /// A second flag ([`Deadline::or_cancelled_by`]): another stream of a portfolio has won.
    also: Option<Arc<AtomicBool>>,
}

impl Deadline {
    /// No deadline: operations run until their other budgets end them.
    pub fn none() -> Self {
        Deadline::default()
    }

    /// `budget` from now. A budget too long to represent (`Duration::MAX`, 1e300 s) is no
    /// deadline.
    pub fn after(budget: Duration) -> Self {
        Deadline {
            at: Instant::now().checked_add(budget),
            cancel: None,
            also: None,
        }
    }

    /// A deadline `budget` from now if one is given, else none.
    pub fn after_opt(budget: Option<Duration>) -> Self {
        budget.map_or_else(Deadline::none, Deadline::after)
    }

    /// The same deadline, also stopped when `flag` becomes true (Ctrl-C, another thread).
    pub fn with_cancel(mut self, flag: Arc<AtomicBool>) -> Self {
        self.cancel = Some(flag);
        self
    }

    /// The same deadline (time and cancel flag), also stopped when `flag` becomes true: one of
    /// several streams racing for the same answer stops when another has it.
    pub fn or_cancelled_by(&self, flag: Arc<AtomicBool>) -> Self {
        Deadline {
            at: self.at,
            cancel: self.cancel.clone(),
            also: Some(flag),
        }
    }

    /// The earlier of this deadline and `budget` from now, with this deadline's cancel flags:
    /// a query's own budget inside a batch's, a learning stage inside a build.
    pub fn within(&self, budget: Option<Duration>) -> Self {
        let mine = budget.and_then(|b| Instant::now().checked_add(b));
        let at = match (self.at, mine) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        Deadline {
            at,
            cancel: self.cancel.clone(),
            also: self.also.clone(),
        }
    }

    /// Whether the time is up or the operation was cancelled.
    #[inline]
    pub fn expired(&self) -> bool {
        self.cancelled() || self.at.is_some_and(|at| Instant::now() >= at)
    }

    /// Whether a cancel flag was raised.
    pub fn cancelled(&self) -> bool {
        [&self.cancel, &self.also]
            .into_iter()
            .flatten()
            .any(|c| c.load(Ordering::Relaxed))
    }

    /// Time left (zero once expired); `None` without a time limit.
    pub fn remaining(&self) -> Option<Duration> {
        self.at
            .map(|at| at.saturating_duration_since(Instant::now()))
    }

    /// Whether anything can end it: a time limit or a cancel flag.
    pub fn is_limited(&self) -> bool {
        self.at.is_some() || self.cancel.is_some() || self.also.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn within_takes_the_earlier_and_keeps_the_flag() {
        let flag = Arc::new(AtomicBool::new(false));
        let outer = Deadline::after(Duration::from_secs(3600)).with_cancel(flag.clone());
        let inner = outer.within(Some(Duration::ZERO));
        assert!(inner.expired());
        assert!(!outer.expired());
        let same = outer.within(None);
        assert!(!same.expired());
        flag.store(true, Ordering::Relaxed);
        assert!(same.expired() && outer.expired() && same.cancelled());
        assert!(Deadline::none().remaining().is_none());
        assert!(
            Deadline::after(Duration::from_secs(60))
                .remaining()
                .unwrap()
                > Duration::ZERO
        );
        assert!(!Deadline::none().within(Some(Duration::MAX)).expired());
    }

    #[test]
    fn a_second_flag_stops_it_too_and_survives_within() {
        let ctrl_c = Arc::new(AtomicBool::new(false));
        let won = Arc::new(AtomicBool::new(false));
        let outer = Deadline::none().with_cancel(ctrl_c.clone());
        let racing = outer.or_cancelled_by(won.clone()).within(None);
        assert!(!racing.expired() && racing.is_limited());
        won.store(true, Ordering::Relaxed);
        assert!(racing.expired() && racing.cancelled() && !outer.expired());
        won.store(false, Ordering::Relaxed);
        ctrl_c.store(true, Ordering::Relaxed);
        assert!(racing.expired() && outer.expired());
    }
}
