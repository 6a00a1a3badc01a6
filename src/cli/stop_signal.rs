//! SIGINT and SIGTERM for the subcommands that stop on them (`run`, `sweep run`).
//!
//! [`ctrlc`] takes one handler per process and refuses a second one. The program runs one
//! subcommand per process, but the Python package runs the command line in-process
//! (`hagfish._native.main`, behind the `hagfish` command pip installs), where one interpreter
//! may call it again. So the `ctrlc` handler is installed once, on first use, and calls the
//! handlers of the subcommands running now; each subcommand's [`StopSignal`] removes its
//! handler when dropped. A signal while none is running is ignored (once installed, the
//! `ctrlc` handler stays for the rest of the process).

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// A subcommand's handler: called on the `ctrlc` thread.
type Handler = Box<dyn FnMut() + Send>;

/// The handlers of the subcommands running now, with the number each was given.
static HANDLERS: Mutex<Vec<(u64, Handler)>> = Mutex::new(Vec::new());

/// The registration of one subcommand's handler; dropping it removes the handler.
#[must_use = "the handler is removed when this is dropped"]
pub(crate) struct StopSignal(u64);

/// Calls `handler` on SIGINT or SIGTERM until the returned [`StopSignal`] is dropped;
/// installs the process's `ctrlc` handler on first use (an error only then, from `ctrlc`).
pub(crate) fn on_stop_signal(
    handler: impl FnMut() + Send + 'static,
) -> Result<StopSignal, ctrlc::Error> {
    /// Whether this module's `ctrlc` handler is installed.
    static INSTALLED: Mutex<bool> = Mutex::new(false);
    let mut installed = lock(&INSTALLED);
    if !*installed {
        ctrlc::set_handler(dispatch)?;
        *installed = true;
    }
    Ok(register(Box::new(handler)))
}

/// Adds `handler` to the handlers called on a signal.
fn register(handler: Handler) -> StopSignal {
    /// The number of the next handler.
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let number = NEXT.fetch_add(1, Ordering::Relaxed);
    lock(&HANDLERS).push((number, handler));
    StopSignal(number)
}

/// The `ctrlc` handler: calls every registered handler.
fn dispatch() {
    for (_, handler) in lock(&HANDLERS).iter_mut() {
        handler();
    }
}

impl Drop for StopSignal {
    fn drop(&mut self) {
        lock(&HANDLERS).retain(|(number, _)| *number != self.0);
    }
}

/// `mutex` locked; a handler that panicked leaves the list usable.
fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(PoisonError::into_inner)
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;
    use std::sync::atomic::{AtomicUsize, Ordering};

    use super::*;

    /// Registered handlers without installing `ctrlc` (a test process keeps its SIGINT).
    #[test]
    fn a_signal_calls_the_handlers_registered_now_and_each_is_removed_when_dropped() {
        let calls = Arc::new(AtomicUsize::new(0));
        let counter = |step: usize| {
            let calls = Arc::clone(&calls);
            Box::new(move || {
                calls.fetch_add(step, Ordering::Relaxed);
            }) as Handler
        };
        let first = register(counter(1));
        dispatch();
        assert_eq!(calls.load(Ordering::Relaxed), 1);
        let second = register(counter(10));
        dispatch();
        assert_eq!(calls.load(Ordering::Relaxed), 12);
        drop(first);
        dispatch();
        assert_eq!(calls.load(Ordering::Relaxed), 22);
        drop(second);
        dispatch();
        assert_eq!(calls.load(Ordering::Relaxed), 22);
    }
}
