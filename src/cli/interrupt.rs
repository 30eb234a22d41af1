//! Ctrl-C as a budget: the first one stops the running operation, which then finishes as if
//! its time had run out (a build saves the roadmap learnt so far, a batch of queries prints
//! the answers it has); the second one ends the program at once.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};
use viaroad::deadline::Deadline;

static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// The process-wide interrupt flag, with the Ctrl-C handler installed on first use. Where no
/// handler can be installed (no terminal signals), the flag simply never rises.
fn flag() -> Arc<AtomicBool> {
    FLAG.get_or_init(|| {
        let flag = Arc::new(AtomicBool::new(false));
        let raised = flag.clone();
        let _ = ctrlc::set_handler(move || {
            if raised.swap(true, Ordering::SeqCst) {
                eprintln!("interrupted again: stopping now");
                std::process::exit(130);
            }
            eprintln!("interrupted: finishing with what is done (Ctrl-C again to stop at once)");
        });
        flag
    })
    .clone()
}

/// `deadline`, also stopped by Ctrl-C.
pub fn on_ctrl_c(deadline: Deadline) -> Deadline {
    deadline.with_cancel(flag())
}
