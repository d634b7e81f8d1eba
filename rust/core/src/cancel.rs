//! Interrupting a running impact or sweep from another thread (a Ctrl-C watcher).
//!
//! The integration loops poll the token every [`POLL_STEPS`] steps (one relaxed atomic load,
//! measured to cost nothing: see `benches/impact.rs`) and return
//! [`Error::Interrupted`](crate::error::Error::Interrupted) once it is set; a sweep stops all its
//! workers the same way.

use std::sync::atomic::{AtomicBool, Ordering};

/// Steps between two polls of the token (a power of two: the test is a mask). At the
/// engine's few million steps per second of one core that is about a millisecond.
pub const POLL_STEPS: u64 = 4096;

/// A cancellation token: set once from any thread, seen by every loop polling it.
#[derive(Debug, Default)]
pub struct Cancel(AtomicBool);

/// A token that is never set, for the entry points without one.
static NEVER: Cancel = Cancel::new();

impl Cancel {
    /// A token not yet set.
    pub const fn new() -> Self {
        Cancel(AtomicBool::new(false))
    }

    /// A shared token that nothing sets.
    pub fn never() -> &'static Cancel {
        &NEVER
    }

    /// Asks every loop polling this token to stop.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Clears the token, so that it can serve a new run.
    pub fn reset(&self) {
        self.0.store(false, Ordering::Relaxed);
    }

    /// Whether the token has been set.
    #[inline(always)]
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// `Err(Error::Interrupted)` once the token is set, polled only every [`POLL_STEPS`]
    /// steps (`step` counts the loop's iterations).
    #[inline(always)]
    pub(crate) fn poll(&self, step: u64) -> crate::error::Result<()> {
        if step & (POLL_STEPS - 1) == 0 && self.is_cancelled() {
            return Err(crate::error::Error::Interrupted);
        }
        Ok(())
    }
}
