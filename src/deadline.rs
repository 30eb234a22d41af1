//! Budgets that hold: one [`Deadline`] travels from the command line through the learner and
//! the query down to the via-point search, which checks it before every oracle call.
//!
//! A planner's time budget is a promise. Checking the clock only between learning rounds let
//! one round on a big mesh (dozens of deep via-point searches, seconds each) overrun a 30-s
//! budget by minutes; checking it before every intersect call bounds the overrun by the cost
//! of one call, and the search *watches* it during a call too ([`watching`]): a long exact
//! sweep gives up part-way. A deadline also carries an optional cancel flag, so that Ctrl-C or
//! a caller on another thread stops the same checks, and the flags of the races it is in:
//! [`race`] runs two planners for one answer, the first to answer stopping the other.
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

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// A point in time after which long operations stop and return what they have, and/or a flag
/// that stops them at once. Cheap to clone and to check (one clock read).
#[derive(Clone, Debug, Default)]
pub struct Deadline {
    at: Option<Instant>,
    cancel: Option<Arc<AtomicBool>>,
    /// Flags of the races this operation is part of ([`Deadline::or_cancelled_by`]): another
    /// stream of a portfolio has won. Races nest (trees racing the via-point planner race
    /// their own streams), so all of them are kept; shared, so that a clone stays cheap.
    also: Option<Arc<[Arc<AtomicBool>]>>,
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
    /// several streams racing for the same answer stops when another has it. The flags of the
    /// races this deadline is already in still stop it too.
    pub fn or_cancelled_by(&self, flag: Arc<AtomicBool>) -> Self {
        Deadline {
            at: self.at,
            cancel: self.cancel.clone(),
            also: Some(
                self.also
                    .iter()
                    .flat_map(|flags| flags.iter().cloned())
                    .chain([flag])
                    .collect(),
            ),
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
        self.cancel
            .iter()
            .chain(self.also.iter().flat_map(|flags| flags.iter()))
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

thread_local! {
    /// The deadline long oracle calls on this thread poll ([`watching`]).
    static WATCHED: RefCell<Option<Deadline>> = const { RefCell::new(None) };
}

/// Runs `f` with `deadline` watched on this thread: an oracle call inside it that takes long
/// (an exact sweep of a whole joint range among many faces: up to 20 ms on MotionBenchMaker's
/// cage) polls the deadline as it goes and gives up with
/// [`crate::oracle::OracleError::Interrupted`] once it has passed, instead of finishing an
/// answer nobody waits for. Checking before every call bounds an overrun by one call; this
/// bounds it by a few hundred primitive pairs. Only callers that treat that error as their
/// deadline stop watch (the via-point search), and `f` must not wait on other rayon work (a
/// job stolen meanwhile would run watched too). Nested, the innermost limited deadline is
/// watched; an unlimited one leaves the outer one watched.
pub fn watching<R>(deadline: &Deadline, f: impl FnOnce() -> R) -> R {
    if !deadline.is_limited() {
        return f();
    }
    struct Restore(Option<Deadline>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let previous = self.0.take();
            WATCHED.with(|w| *w.borrow_mut() = previous);
        }
    }
    let _restore = Restore(WATCHED.with(|w| w.replace(Some(deadline.clone()))));
    f()
}

/// Whether the deadline watched on this thread ([`watching`]) has passed; `false` when none is.
pub fn watched_expired() -> bool {
    WATCHED.with(|w| w.borrow().as_ref().is_some_and(Deadline::expired))
}

/// What [`race`] ran.
#[derive(Debug)]
pub struct Raced<A, B> {
    /// The first side's deciding run: the one in the race, or the head start when that
    /// answered (or the deadline ended with it, or the second side answered in turn after it).
    pub first: A,
    /// The head start that did not answer, when the first side ran again after it (its work
    /// counts too).
    pub head_start: Option<A>,
    /// The second side's run; `None` when there was no race.
    pub second: Option<B>,
}

/// How long the caller of a race without a head start waits for an idle pool thread to take
/// the second side before it runs the sides in turn itself (after a head start nothing waits:
/// [`race_after`]). Waking a sleeping rayon worker takes tens of microseconds;
/// a race only starts after a head start of milliseconds, so the wait costs little.
const STEAL_WAIT: Duration = Duration::from_micros(200);

/// Two planners for the same answer, a portfolio: `first` alone for `head_start` (none when
/// zero); unless that answered (`first_won`) or `deadline` ended, `first` again beside
/// `second` on the rayon pool, the first of them to answer (`first_won`, `second_won`)
/// stopping the other through their shared deadline. The caller picks the answer.
///
/// A race is a schedule, not a thread: when no pool thread is free to take the second side (a
/// pool of one thread, or a batch that keeps every thread busy), the caller runs the sides in
/// turn: the second until the deadline or its own budget, then the first again for what is
/// left. Waiting for a thread that never comes would leave the second side
/// nothing but an expired deadline, so every raced query of a busy batch would time out.
///
/// `first` gets two deadlines: the one its search stops at, and the one by which it finishes
/// (shortens) a path it found. In the head start they are `head_start` and `deadline`: the head
/// start bounds the search, and a path found as it ends is still shortened rather than handed
/// back raw. In the race both are the race's.
///
/// Without a time limit nothing is stopped: both sides run to their own budgets, so that a
/// caller who prefers the first side's answer gets the same answer on any thread count (as
/// racing tree streams do, [`crate::roadmap::tree::rrt_connect`]).
///
/// The head start keeps quick answers off the pool: handing a query to a worker thread and
/// waiting for both sides costs more than a sub-millisecond answer takes.
pub fn race<A: Send, B: Send>(
    deadline: &Deadline,
    head_start: Duration,
    first: impl Fn(&Deadline, &Deadline) -> A + Sync,
    first_won: impl Fn(&A) -> bool + Sync,
    second: impl FnOnce(&Deadline) -> B + Send,
    second_won: impl FnOnce(&B) -> bool + Send,
) -> Raced<A, B> {
    let mut alone = None;
    if !head_start.is_zero() {
        let a = first(&deadline.within(Some(head_start)), deadline);
        if first_won(&a) || deadline.expired() {
            return Raced {
                first: a,
                head_start: None,
                second: None,
            };
        }
        alone = Some(a);
    }
    race_after(deadline, alone, first, first_won, second, second_won)
}

/// [`race`] after a head start the caller ran itself (`alone`, one that did not answer; `None`:
/// no head start): a first side whose head start is a cheaper search of its own (a roadmap's
/// direct paths before its local method's searches) rather than the same search cut short.
/// After a head start the second side starts at once on the caller's thread and the first is
/// offered to an idle pool thread beside it (from outside the pool, after the second has run
/// alone for a while), or runs after the second where none takes it; in turn, as on one thread,
/// that is the same order.
pub fn race_after<A: Send, B: Send>(
    deadline: &Deadline,
    alone: Option<A>,
    first: impl Fn(&Deadline, &Deadline) -> A + Sync,
    first_won: impl Fn(&A) -> bool + Sync,
    second: impl FnOnce(&Deadline) -> B + Send,
    second_won: impl FnOnce(&B) -> bool + Send,
) -> Raced<A, B> {
    if deadline.remaining().is_none() {
        // nothing can starve: each side runs to its own budget wherever it runs
        let (a, b) = join_here(|| first(deadline, deadline), || second(deadline));
        return Raced {
            first: a,
            head_start: alone,
            second: Some(b),
        };
    }
    let won = Arc::new(AtomicBool::new(false));
    let racing = deadline.or_cancelled_by(won.clone());
    let sides = (&first, &first_won, second, second_won);
    match alone {
        Some(head) => behind_a_head_start(&racing, &won, head, sides),
        None => without_a_head_start(&racing, &won, sides),
    }
}

/// `value`, the race marked `won` where `answered` says it answers: the other side stops.
fn marking<T>(won: &AtomicBool, value: T, answered: impl FnOnce(&T) -> bool) -> T {
    if answered(&value) {
        won.store(true, Ordering::Relaxed);
    }
    value
}

/// The race with no head start: the caller runs the first side and offers the second to a pool
/// thread, waiting up to [`STEAL_WAIT`] for one to take it; where none does, the caller runs
/// the sides in turn ([`in_turn`]).
fn without_a_head_start<A: Send, B: Send, F, W, S, V>(
    racing: &Deadline,
    won: &AtomicBool,
    (first, first_won, second, second_won): (&F, &W, S, V),
) -> Raced<A, B>
where
    F: Fn(&Deadline, &Deadline) -> A + Sync,
    W: Fn(&A) -> bool + Sync,
    S: FnOnce(&Deadline) -> B + Send,
    V: FnOnce(&B) -> bool + Send,
{
    // the second side goes to whoever takes it first: a pool thread, or the caller in turn
    let second = Mutex::new(Some((second, second_won)));
    let taken = AtomicBool::new(false);
    let take = || {
        let side = second.lock().ok().and_then(|mut s| s.take());
        taken.store(true, Ordering::Release);
        side
    };
    let (caller, pool) = join_here(
        || {
            wait_for_a_thread(&taken);
            if let Some((second, second_won)) = take() {
                return Err(in_turn(racing, (first, first_won, second, second_won)));
            }
            Ok(marking(won, first(racing, racing), first_won))
        },
        || {
            let (second, second_won) = take()?;
            Some(marking(won, second(racing), second_won))
        },
    );
    match caller {
        Ok(a) => Raced {
            first: a,
            head_start: None,
            second: pool,
        },
        Err(raced) => raced,
    }
}

/// How long the second side of a race started outside the pool runs alone after the head start
/// before the first joins it on a worker: an arm's trees answer most requests a roadmap's direct
/// paths do not within a few milliseconds, and the roadmap's whole search beside them only
/// delays them (the caller then waits for it to stop, and its work shares the machine with them).
const SECOND_ALONE: Duration = Duration::from_millis(2);

/// The race after a head start that did not answer (`head`): the second side starts at once on
/// the caller's thread, as it would in turn, and the first is offered to an idle pool thread
/// beside it (from a caller outside the pool, once the second has run alone for
/// [`SECOND_ALONE`]); where none takes it, the caller runs it after the second, unless that
/// answered or the race's time ended (then the head start is the first side's run). The caller
/// never waits for a thread to start, and the side that mostly answers after a failed head start
/// (a roadmap's trees) starts on the thread that is running rather than on one that must first
/// wake up (on two threads a worker's wake-up would otherwise delay a bookshelf request's trees).
fn behind_a_head_start<A: Send, B: Send, F, W, S, V>(
    racing: &Deadline,
    won: &AtomicBool,
    head: A,
    (first, first_won, second, second_won): (&F, &W, S, V),
) -> Raced<A, B>
where
    F: Fn(&Deadline, &Deadline) -> A + Sync,
    W: Fn(&A) -> bool + Sync,
    S: FnOnce(&Deadline) -> B + Send,
    V: FnOnce(&B) -> bool + Send,
{
    // from outside the pool the first side waits, awake, while the second runs alone for a
    // while (see `SECOND_ALONE`); a pool thread never waits so, as it may have other work
    let alone_until = rayon::current_thread_index()
        .is_none()
        .then(|| Instant::now() + SECOND_ALONE);
    let second_over = AtomicBool::new(false);
    let (b, a) = join_here(
        || {
            let b = marking(won, second(racing), second_won);
            second_over.store(true, Ordering::Release);
            b
        },
        || {
            if let Some(until) = alone_until {
                while !second_over.load(Ordering::Acquire)
                    && !racing.expired()
                    && Instant::now() < until
                {
                    std::thread::yield_now();
                }
            }
            (!racing.expired()).then(|| marking(won, first(racing, racing), first_won))
        },
    );
    match a {
        Some(a) => Raced {
            first: a,
            head_start: Some(head),
            second: Some(b),
        },
        None => Raced {
            first: head,
            head_start: None,
            second: Some(b),
        },
    }
}

/// `rayon::join(a, b)` that starts `a` on the caller's thread wherever the caller runs. From
/// a thread outside the pool (a command's main thread, a server's or Python's) rayon queues
/// both closures and blocks the caller until a sleeping worker wakes and takes them, which on a
/// virtual machine costs about 0.14 ms before any work starts. There `a` runs at once on the
/// caller and `b` is offered to the pool, run by the caller after `a` where no worker took it
/// first; with a pool of one thread both run in turn on the caller, as rayon's own join would
/// on that one thread.
fn join_here<RA, RB>(a: impl FnOnce() -> RA + Send, b: impl FnOnce() -> RB + Send) -> (RA, RB)
where
    RA: Send,
    RB: Send,
{
    if rayon::current_thread_index().is_some() {
        return rayon::join(a, b);
    }
    join_outside_the_pool(rayon::current_num_threads(), a, b)
}

/// How long a caller outside the pool waits awake for a worker to finish the closure it took
/// ([`join_outside_the_pool`]) before it sleeps until the worker wakes it.
const AWAKE_WAIT: Duration = Duration::from_millis(2);

/// [`join_here`] from a thread outside a pool of `threads` threads.
fn join_outside_the_pool<RA, RB>(
    threads: usize,
    a: impl FnOnce() -> RA + Send,
    b: impl FnOnce() -> RB + Send,
) -> (RA, RB)
where
    RA: Send,
    RB: Send,
{
    if threads <= 1 {
        let ra = a();
        return (ra, b());
    }
    // `b` goes to whoever takes it first: a worker, or the caller once `a` is done
    let b = Mutex::new(Some(b));
    let rb = Mutex::new(None);
    let take_b = || {
        let side = b.lock().unwrap_or_else(|e| e.into_inner()).take();
        let Some(side) = side else { return false };
        let r = side();
        *rb.lock().unwrap_or_else(|e| e.into_inner()) = Some(r);
        true
    };
    let done = AtomicBool::new(false);
    let ra = rayon::in_place_scope(|s| {
        s.spawn(|_| {
            take_b();
            done.store(true, Ordering::Release);
        });
        let ra = a();
        if !take_b() {
            // a worker runs `b` (in a race, a side stopping now): the caller waits awake,
            // as the scope's sleep would cost another wake-up
            let began = Instant::now();
            while !done.load(Ordering::Acquire) && began.elapsed() < AWAKE_WAIT {
                std::hint::spin_loop();
            }
        }
        ra
    });
    let rb = rb.into_inner().unwrap_or_else(|e| e.into_inner());
    (
        ra,
        rb.expect("the second closure ran on the pool or the caller"),
    )
}

/// Waits up to [`STEAL_WAIT`] for a pool thread to take the second side (none can in a pool of
/// one thread).
fn wait_for_a_thread(taken: &AtomicBool) {
    let began = Instant::now();
    while rayon::current_num_threads() > 1
        && !taken.load(Ordering::Acquire)
        && began.elapsed() < STEAL_WAIT
    {
        std::thread::yield_now();
    }
}

/// The share of a race's time the first side gets before the second when they run in turn
/// (there is no head start then), and the most it gets: a head start of its own, short beside a
/// long budget.
const IN_TURN_FIRST_SHARE: u32 = 16;
const IN_TURN_FIRST_MOST: Duration = Duration::from_millis(50);

/// The sides of a race with no head start in turn on the caller's thread: the first for a
/// share of the time, the second until `racing` ends or its own budget does, then, unless it
/// answered, the first again for what is left. The second side, in a race a tree search that
/// grows from nothing, gets the time it would have had beside the first.
fn in_turn<A, B, F, W, S, V>(
    racing: &Deadline,
    (first, first_won, second, second_won): (&F, &W, S, V),
) -> Raced<A, B>
where
    F: Fn(&Deadline, &Deadline) -> A,
    W: Fn(&A) -> bool,
    S: FnOnce(&Deadline) -> B,
    V: FnOnce(&B) -> bool,
{
    let share = racing
        .remaining()
        .map(|t| (t / IN_TURN_FIRST_SHARE).min(IN_TURN_FIRST_MOST));
    let head = first(&racing.within(share), racing);
    if first_won(&head) || racing.expired() {
        return Raced {
            first: head,
            head_start: None,
            second: None,
        };
    }
    let b = second(racing);
    if second_won(&b) || racing.expired() {
        return Raced {
            first: head,
            head_start: None,
            second: Some(b),
        };
    }
    Raced {
        first: first(racing, racing),
        head_start: Some(head),
        second: Some(b),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn watching_nests_and_restores_the_outer_deadline() {
        assert!(!watched_expired(), "nothing watched");
        let past = Deadline::after(Duration::ZERO);
        let later = Deadline::after(Duration::from_secs(3600));
        watching(&past, || {
            assert!(watched_expired());
            watching(&later, || {
                assert!(!watched_expired(), "the innermost is watched")
            });
            watching(&Deadline::none(), || {
                assert!(
                    watched_expired(),
                    "an unlimited one leaves the outer watched"
                )
            });
            assert!(watched_expired(), "the outer is watched again");
        });
        assert!(!watched_expired(), "nothing watched after");
        let flag = Arc::new(AtomicBool::new(false));
        watching(&Deadline::none().with_cancel(flag.clone()), || {
            assert!(!watched_expired());
            flag.store(true, Ordering::Relaxed);
            assert!(watched_expired(), "a cancel flag stops a watched call too");
        });
    }

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

    #[test]
    fn races_nest_and_either_flag_stops_the_inner_one() {
        let outer_won = Arc::new(AtomicBool::new(false));
        let inner_won = Arc::new(AtomicBool::new(false));
        let outer = Deadline::none().or_cancelled_by(outer_won.clone());
        let inner = outer.or_cancelled_by(inner_won.clone());
        assert!(!inner.expired());
        inner_won.store(true, Ordering::Relaxed);
        assert!(inner.expired() && !outer.expired());
        inner_won.store(false, Ordering::Relaxed);
        outer_won.store(true, Ordering::Relaxed);
        assert!(inner.expired() && outer.expired());
    }

    /// Counts to `n` unless the deadline ends first; answers when it got there.
    fn count(n: u64, d: &Deadline) -> (u64, bool) {
        let mut i = 0;
        while i < n && !d.expired() {
            i += 1;
            std::thread::yield_now();
        }
        (i, i == n)
    }

    /// A race after a head start whose first side counts to `n` and whose second gives up
    /// after counting to 10.
    fn after_a_second_that_gives_up(n: u64) -> Raced<(u64, bool), (u64, bool)> {
        race(
            &Deadline::after(Duration::from_secs(3600)),
            Duration::from_millis(1),
            |d, _| count(n, d),
            |a| a.1,
            |d| count(10, d),
            |_| false,
        )
    }

    /// Races a first side that never answers against a second that answers, and asserts that
    /// the second ran where `thread` says the caller runs, and that the first was stopped or
    /// skipped.
    fn second_side_on_the_callers_thread<T: PartialEq + std::fmt::Debug + Send>(
        thread: impl Fn() -> T + Sync,
    ) {
        let caller = thread();
        let raced = race(
            &Deadline::after(Duration::from_secs(30)),
            Duration::from_millis(1),
            |d, _| count(u64::MAX, d),
            |a| a.1,
            |d| (thread(), count(1000, d)),
            |b| b.1 .1,
        );
        let (ran_on, answer) = raced.second.expect("the second side ran");
        assert_eq!((ran_on, answer), (caller, (1000, true)));
        assert!(!raced.first.1, "the first side was stopped or skipped");
    }

    #[test]
    fn a_quick_first_side_answers_in_its_head_start_alone() {
        let raced = race(
            &Deadline::none(),
            Duration::from_secs(3600),
            |d, _| count(10, d),
            |a| a.1,
            |d| count(10, d),
            |b| b.1,
        );
        assert_eq!(raced.first, (10, true));
        assert!(raced.head_start.is_none() && raced.second.is_none());
    }

    #[test]
    fn the_side_that_answers_stops_the_other() {
        // the first side would count for ever; the second answers and stops it
        let hour = Deadline::after(Duration::from_secs(3600));
        let raced = race(
            &hour,
            Duration::ZERO,
            |d, _| count(u64::MAX, d),
            |a| a.1,
            |d| count(1000, d),
            |b| b.1,
        );
        assert_eq!(raced.second, Some((1000, true)));
        assert!(raced.head_start.is_none());
        assert!(!raced.first.1, "the first side was stopped: {raced:?}");
        // a head start that runs out is followed by the race
        let raced = race(
            &hour,
            Duration::from_millis(1),
            |d, _| count(u64::MAX, d),
            |a| a.1,
            |d| count(1000, d),
            |b| b.1,
        );
        // (in turn when no pool thread came: then the head start is the first side's run)
        assert!(!raced.first.1 && raced.head_start.is_none_or(|(_, done)| !done));
        assert_eq!(raced.second, Some((1000, true)));
    }

    #[test]
    fn without_a_time_limit_both_sides_run_to_their_budgets() {
        let raced = race(
            &Deadline::none(),
            Duration::ZERO,
            |d, _| count(2000, d),
            |a| a.1,
            |d| count(10, d),
            |b| b.1,
        );
        assert_eq!(
            (raced.first, raced.second),
            ((2000, true), Some((10, true)))
        );
    }

    /// A race on a pool with no free thread runs its sides in turn rather than leaving the
    /// second side an expired deadline: on one thread, and in a batch larger than the pool.
    #[test]
    fn a_race_with_no_free_thread_runs_its_sides_in_turn() {
        let run = |head_start: Duration| {
            race(
                &Deadline::after(Duration::from_secs(30)),
                head_start,
                |d, _| count(u64::MAX, d),
                |a| a.1,
                |d| count(1000, d),
                |b| b.1,
            )
        };
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        for head_start in [Duration::ZERO, Duration::from_millis(1)] {
            let raced = one.install(|| run(head_start));
            assert_eq!(raced.second, Some((1000, true)), "{raced:?}");
            assert!(raced.head_start.is_none(), "the first ran once: {raced:?}");
        }
        let two = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let batch: Vec<_> = two.install(|| {
            use rayon::prelude::*;
            (0..8)
                .into_par_iter()
                .map(|_| run(Duration::from_millis(1)))
                .collect()
        });
        for raced in &batch {
            assert_eq!(raced.second, Some((1000, true)), "{raced:?}");
        }
        // in turn, a second side that gives up leaves the rest of the time to the first
        let raced = one.install(|| after_a_second_that_gives_up(50_000));
        assert_eq!(raced.first, (50_000, true), "{raced:?}");
        assert!(raced.head_start.is_some_and(|(_, done)| !done));
        assert_eq!(raced.second, Some((10, true)));
    }

    /// After a head start the second side starts at once on the caller's thread, whether a
    /// worker is free or not: it never waits for a sleeping worker to take it (the first side
    /// is the one offered to the pool), and it answers as before.
    #[test]
    fn after_a_head_start_the_second_side_runs_on_the_callers_thread() {
        let two = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        for _ in 0..20 {
            two.install(|| second_side_on_the_callers_thread(rayon::current_thread_index));
        }
    }

    /// From a thread outside the pool (a command's main thread), the second side after a head
    /// start runs on that thread at once, not on a worker the caller would wait for, and the
    /// race answers as on a pool thread.
    #[test]
    fn outside_the_pool_the_second_side_runs_on_the_callers_thread() {
        for _ in 0..20 {
            second_side_on_the_callers_thread(|| std::thread::current().id());
        }
    }

    /// From outside the pool the first side after a head start, waiting while the second runs
    /// alone, runs once the second gave up without an answer, and answers.
    #[test]
    fn outside_the_pool_the_first_side_runs_after_a_second_that_gave_up() {
        for _ in 0..20 {
            let raced = after_a_second_that_gives_up(5000);
            assert_eq!(raced.first, (5000, true), "the first side ran: {raced:?}");
            assert!(raced.head_start.is_some());
        }
    }

    /// Outside a pool of one thread both closures run on the caller, the first before the
    /// second; outside a larger pool the first runs on the caller and the second exactly once,
    /// on a worker or on the caller after the first.
    #[test]
    fn joining_outside_the_pool_starts_on_the_caller() {
        let caller = std::thread::current().id();
        let order = Mutex::new(Vec::new());
        let log = |k: u8| {
            order.lock().unwrap().push(k);
            std::thread::current().id()
        };
        let (a, b) = join_outside_the_pool(1, || log(1), || log(2));
        assert_eq!((a, b), (caller, caller));
        assert_eq!(*order.lock().unwrap(), [1, 2]);
        for _ in 0..20 {
            order.lock().unwrap().clear();
            let (a, b) = join_outside_the_pool(2, || log(1), || (log(2), 7));
            assert_eq!((a, b.1), (caller, 7));
            let mut ran = order.lock().unwrap().clone();
            ran.sort_unstable();
            assert_eq!(ran, [1, 2], "each closure ran once");
        }
    }

    /// The head start ends the first side's search, not its finishing: a path found as the
    /// head start ends is still finished (shortened) within the whole deadline.
    #[test]
    fn the_head_start_bounds_the_search_not_the_finishing() {
        let hour = Deadline::after(Duration::from_secs(3600));
        let raced = race(
            &hour,
            Duration::from_millis(1),
            |search, finish| {
                count(u64::MAX, search);
                (search.expired(), finish.expired())
            },
            |_| true,
            |d| count(10, d),
            |b| b.1,
        );
        assert_eq!(raced.first, (true, false));
        assert!(raced.second.is_none());
    }
}
