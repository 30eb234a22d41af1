//! Long calls that Ctrl-C stops. Python runs its signal handlers only on the main thread,
//! between bytecodes, so a Rust call holding that thread would keep `KeyboardInterrupt` back
//! until it ends (a 100 000-query batch: minutes). Instead the work runs on another thread with
//! the interpreter released while the calling thread looks for signals every
//! [`SIGNAL_POLL`]; on one it raises the work's cancel flag, which the library's deadlines
//! carry, and raises the handler's exception once the work has stopped.

use pyo3::prelude::*;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::Duration;
use viaroad::deadline::Deadline;

/// How often the calling thread looks for signals: well below what a person notices.
pub const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// What the calling thread and the work exchange.
struct State<M> {
    /// A message of the work for the calling thread, not yet handled.
    message: Option<M>,
    /// The answer to the last message: whether the work may go on.
    reply: Option<bool>,
    /// The work has ended (its result is in [`Exchange::result`]).
    finished: bool,
}

struct Exchange<M> {
    state: Mutex<State<M>>,
    changed: Condvar,
    /// Held by a sender from its message to its reply, so that messages of several threads
    /// of the work take turns.
    turn: Mutex<()>,
}

impl<M> Exchange<M> {
    fn lock(&self) -> MutexGuard<'_, State<M>> {
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }
}

/// The work's side: the cancel flag to stop at, and messages to the calling thread.
pub struct Watch<'a, M> {
    cancel: Arc<AtomicBool>,
    exchange: &'a Exchange<M>,
}

impl<M> Watch<'_, M> {
    /// Whether the work should stop (a signal, or an exception of a message's handler).
    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    /// A deadline that ends when the work is cancelled, for the library's long operations.
    pub fn deadline(&self) -> Deadline {
        Deadline::none().with_cancel(self.cancel.clone())
    }

    /// Hands `message` to the calling thread's handler (which runs Python, on the thread that
    /// called) and waits for it; `false` if the work is cancelled and should stop.
    pub fn send(&self, message: M) -> bool {
        if self.cancelled() {
            return false;
        }
        let _turn = self.exchange.turn.lock().unwrap_or_else(|p| p.into_inner());
        let mut s = self.exchange.lock();
        s.message = Some(message);
        self.exchange.changed.notify_all();
        let mut s = self
            .exchange
            .changed
            .wait_while(s, |s| s.reply.is_none())
            .unwrap_or_else(|p| p.into_inner());
        s.reply.take().unwrap_or(false)
    }
}

/// Runs `work` with the interpreter released while this thread looks for signals; see
/// [`interruptible_with`].
pub fn interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&Watch<'_, ()>) -> T + Send,
) -> PyResult<T> {
    interruptible_with(py, |_, ()| Ok(()), work)
}

/// Runs `work` on a thread of its own with the interpreter released, while this thread looks
/// for signals every [`SIGNAL_POLL`] and hands the work's messages ([`Watch::send`]) to
/// `on_message`, so that Python callbacks still run on the thread that called. A signal
/// handler's exception (`KeyboardInterrupt`) or one of `on_message` raises the work's cancel
/// flag; once the work has stopped, that exception is returned. `work` must look at the flag
/// ([`Watch::cancelled`], [`Watch::deadline`]) often.
pub fn interruptible_with<T: Send, M: Send>(
    py: Python<'_>,
    mut on_message: impl FnMut(Python<'_>, M) -> PyResult<()>,
    work: impl FnOnce(&Watch<'_, M>) -> T + Send,
) -> PyResult<T> {
    let exchange = Exchange {
        state: Mutex::new(State {
            message: None,
            reply: None,
            finished: false,
        }),
        changed: Condvar::new(),
        turn: Mutex::new(()),
    };
    let watch = Watch {
        cancel: Arc::new(AtomicBool::new(false)),
        exchange: &exchange,
    };
    let mut raised: Option<PyErr> = None;
    let outcome = std::thread::scope(|scope| {
        let worker = scope.spawn(|| {
            // a panic still ends the wait below; it is raised again on this thread
            let r = catch_unwind(AssertUnwindSafe(|| work(&watch)));
            exchange.lock().finished = true;
            exchange.changed.notify_all();
            r
        });
        loop {
            let (message, finished) = py.detach(|| {
                let s = exchange.lock();
                let (mut s, _) = exchange
                    .changed
                    .wait_timeout_while(s, SIGNAL_POLL, |s| !s.finished && s.message.is_none())
                    .unwrap_or_else(|p| p.into_inner());
                (s.message.take(), s.finished)
            });
            if let Some(m) = message {
                let go_on = raised.is_none()
                    && match on_message(py, m) {
                        Ok(()) => true,
                        Err(e) => {
                            raised = Some(e);
                            watch.cancel.store(true, Ordering::SeqCst);
                            false
                        }
                    };
                exchange.lock().reply = Some(go_on);
                exchange.changed.notify_all();
                continue;
            }
            if finished {
                break;
            }
            if raised.is_none() {
                if let Err(e) = py.check_signals() {
                    raised = Some(e);
                    watch.cancel.store(true, Ordering::SeqCst);
                }
            }
        }
        py.detach(|| worker.join())
    });
    let value = match outcome {
        Ok(Ok(v)) => v,
        Ok(Err(panic)) | Err(panic) => resume_unwind(panic),
    };
    match raised {
        Some(e) => Err(e),
        None => Ok(value),
    }
}
