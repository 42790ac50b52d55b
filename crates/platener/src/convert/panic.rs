//! Panics inside a conversion become [`Internal::Panic`] errors instead of taking the caller
//! down. With [`PanicHook::install`], they also say where they happened and print nothing
//! (the report says it); without it, Rust's own hook prints them as usual.

use std::cell::{Cell, RefCell};
use std::panic::{self, AssertUnwindSafe};

use crate::error::Internal;

thread_local! {
    /// Whether this thread is running a conversion under [`catch`].
    static CAPTURING: Cell<bool> = const { Cell::new(false) };
    /// Where the last captured panic of this thread happened.
    static LOCATION: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// A process-wide panic hook that, inside conversions, records where a panic happened
/// instead of printing it; elsewhere the previous hook runs. Programs (the CLI, the service)
/// install it once at start; dropping the guard restores Rust's default hook.
#[derive(Debug)]
pub struct PanicHook(());

impl PanicHook {
    /// Installs the hook.
    pub fn install() -> Self {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if CAPTURING.with(Cell::get) {
                let at = info
                    .location()
                    .map(|l| format!("{}:{}:{}", l.file(), l.line(), l.column()));
                tracing::debug!(at = ?at, "a conversion panicked");
                LOCATION.with(|l| *l.borrow_mut() = at);
            } else {
                previous(info);
            }
        }));
        Self(())
    }
}

impl Drop for PanicHook {
    fn drop(&mut self) {
        // Back to the default hook; conversions left running after a timeout report nothing.
        let _ = panic::take_hook();
    }
}

/// Runs `f`; a panic becomes [`Internal::Panic`] with its message and, under the hook, where.
pub(crate) fn catch<T>(f: impl FnOnce() -> T) -> Result<T, Internal> {
    let was = CAPTURING.with(|c| c.replace(true));
    let result = panic::catch_unwind(AssertUnwindSafe(f));
    CAPTURING.with(|c| c.set(was));
    result.map_err(|payload| {
        let message = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic without a message".into());
        Internal::Panic {
            message,
            location: LOCATION.with(|l| l.borrow_mut().take()),
        }
    })
}
