//! Interrupting a running impact or sweep: from another thread (a Ctrl-C watcher), or from the
//! engine's own thread through a watch the token asks at each poll.
//!
//! The integration loops poll the token every [`POLL_STEPS`] steps (one relaxed atomic load,
//! measured to cost nothing: see `benches/impact.rs`) and return
//! [`Error::Interrupted`](crate::error::Error::Interrupted) once it is set; a sweep stops all its
//! workers the same way. A token made by [`Cancel::watched`] also calls its watch at each poll:
//! how a caller whose signal handlers can run only on the thread that runs the engine (Python's
//! main thread) stops it without a second thread.

use std::sync::atomic::{AtomicBool, Ordering};

/// Steps between two polls of the token (a power of two: the test is a mask). At the
/// engine's few million steps per second of one core that is about a millisecond.
pub const POLL_STEPS: u64 = 4096;

/// A cancellation token: set once from any thread, seen by every loop polling it.
#[derive(Debug, Default)]
pub struct Cancel {
    set: AtomicBool,
    /// Asked at each poll whether to stop (see [`Cancel::watched`]).
    watch: Option<fn() -> bool>,
}

/// A token that is never set, for the entry points without one.
static NEVER: Cancel = Cancel::new();

impl Cancel {
    /// A token not yet set.
    pub const fn new() -> Self {
        Cancel {
            set: AtomicBool::new(false),
            watch: None,
        }
    }

    /// A token not yet set that every poll (each [`POLL_STEPS`] steps, on the thread running
    /// the loop) also asks `watch` whether to stop; `true` sets the token. The watch runs on
    /// every thread that polls, so a token for a sweep over several threads should not have
    /// one; it should be cheap, as it runs about every millisecond of engine time (a watch
    /// that takes a lock or a clock should throttle itself).
    pub const fn watched(watch: fn() -> bool) -> Self {
        Cancel {
            set: AtomicBool::new(false),
            watch: Some(watch),
        }
    }

    /// A shared token that nothing sets.
    pub fn never() -> &'static Cancel {
        &NEVER
    }

    /// Asks every loop polling this token to stop.
    pub fn cancel(&self) {
        self.set.store(true, Ordering::Relaxed);
    }

    /// Clears the token, so that it can serve a new run.
    pub fn reset(&self) {
        self.set.store(false, Ordering::Relaxed);
    }

    /// Whether the token has been set.
    #[inline(always)]
    pub fn is_cancelled(&self) -> bool {
        self.set.load(Ordering::Relaxed)
    }

    /// `Err(Error::Interrupted)` once the token is set, polled only every `stride` steps
    /// (`step` counts the loop's iterations; `stride` a power of two, at most [`POLL_STEPS`]);
    /// a watched token asks its watch first. The plate's loops poll every [`POLL_STEPS`]; a
    /// loop whose steps cost far more than the plate's (a pair of fine polygons: two
    /// 1024-gons take ~0.2 ms a fixed step, so 4096 steps would be most of a second) polls as
    /// often in time.
    #[inline(always)]
    pub(crate) fn poll_every(&self, step: u64, stride: u64) -> crate::error::Result<()> {
        if step & (stride - 1) == 0 && self.stop_requested() {
            return Err(crate::error::Error::Interrupted);
        }
        Ok(())
    }

    /// Whether the token is set, after asking the watch if there is one (out of line: it runs
    /// once per [`POLL_STEPS`] steps, and keeps the loops' hot path as small as before).
    #[inline(never)]
    fn stop_requested(&self) -> bool {
        if self.watch.is_some_and(|watch| watch()) {
            self.cancel();
        }
        self.is_cancelled()
    }
}
