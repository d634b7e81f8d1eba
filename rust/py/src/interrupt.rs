//! Ctrl-C during an engine call: the engine runs with the GIL released, and Python runs its
//! signal handlers only on the main thread and only with the GIL, so a call lets them run at
//! the engine's polls (one thread) or watches a worker (parallel work), and stops the engine
//! through its cancel token when a handler raises.

use pyo3::prelude::*;
use restitution_core as core;
use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// How often a running call lets Python run its signal handlers (Ctrl-C): with the engine's
/// polls every `POLL_STEPS` steps on top, a call ends within a few tens of milliseconds.
const SIGNAL_PERIOD: Duration = Duration::from_millis(20);

/// What the last engine call made on this thread measured, for diagnostics
/// (`last_call_diagnostics`): the engine's own time and the waits after it returned.
#[derive(Clone, Copy, Default)]
pub(crate) struct CallDiagnostics {
    /// Seconds from the engine's entry to its return (the work alone, without the binding).
    pub(crate) engine_s: f64,
    /// Times the calling thread went back to wait for the watcher's next poll after the
    /// engine had already returned (each such wait could last a whole `SIGNAL_PERIOD`). None
    /// since issue 27: `run_here` has no watcher, and `run_watched` ends on the flag its worker
    /// sets before waking it (the loop it replaced read `is_finished()`, false until the worker
    /// thread had ended, and waited again in 10-50 % of calls).
    pub(crate) waits_after_engine: u64,
}

/// The Ctrl-C watch of a call running the engine on this thread: when Python's signal
/// handlers last ran, and the error one of them raised.
struct Watch {
    last: Instant,
    raised: Option<PyErr>,
}

thread_local! {
    static LAST_CALL: std::cell::Cell<CallDiagnostics> =
        const { std::cell::Cell::new(CallDiagnostics { engine_s: 0.0, waits_after_engine: 0 }) };
    static WATCH: RefCell<Option<Watch>> = const { RefCell::new(None) };
}

/// Runs `work`, the engine's part of a call, with the GIL released, so that Ctrl-C ends it
/// (Python runs signal handlers only on the main thread, and only with the GIL; the engine
/// runs without it). Work on one thread (`parallel` false) runs on this thread and its token's
/// polls let the handlers run ([`signals_raised`]); parallel work runs on a worker while this
/// thread watches ([`run_watched`]). On KeyboardInterrupt (or any error a handler raises) the
/// token stops the engine within `POLL_STEPS` steps, the work's result is dropped and the
/// error is raised.
pub(crate) fn interruptible<T: Send>(
    py: Python<'_>,
    parallel: bool,
    work: impl FnOnce(&core::Cancel) -> T + Send,
) -> PyResult<T> {
    let (result, diagnostics) = if parallel {
        run_watched(py, work)
    } else {
        run_here(py, work)
    };
    LAST_CALL.with(|last| last.set(diagnostics));
    result
}

/// `work` on this thread, GIL released, its token watched by [`signals_raised`]: no thread to
/// start, and the call ends when the engine returns.
fn run_here<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&core::Cancel) -> T + Send,
) -> (PyResult<T>, CallDiagnostics) {
    /// Puts back the watch of an enclosing call (a signal handler may run the engine too).
    struct Restore(Option<Watch>);
    impl Drop for Restore {
        fn drop(&mut self) {
            WATCH.set(self.0.take());
        }
    }
    let fresh = Watch {
        last: Instant::now(),
        raised: None,
    };
    let outer = Restore(WATCH.replace(Some(fresh)));
    let cancel = core::Cancel::watched(signals_raised);
    let (out, engine_s) = py.detach(|| {
        let start = Instant::now();
        let out = work(&cancel);
        (out, start.elapsed().as_secs_f64())
    });
    let raised = WATCH.take().and_then(|watch| watch.raised);
    drop(outer);
    let diagnostics = CallDiagnostics {
        engine_s,
        waits_after_engine: 0,
    };
    (raised.map_or(Ok(out), Err), diagnostics)
}

/// The watch of [`run_here`]'s token, called at the engine's polls on this thread: at most every
/// `SIGNAL_PERIOD` it takes the GIL and lets Python run its signal handlers; true once one has
/// raised (its error kept for the call to raise). False on a thread without a running call.
fn signals_raised() -> bool {
    let due = WATCH.with_borrow(|watch| match watch {
        None => false,
        Some(w) => w.raised.is_none() && w.last.elapsed() >= SIGNAL_PERIOD,
    });
    if !due {
        return WATCH.with_borrow(|watch| watch.as_ref().is_some_and(|w| w.raised.is_some()));
    }
    // No borrow held while the handlers run: one of them may run the engine itself.
    let raised = Python::attach(|py| py.check_signals()).err();
    WATCH.with_borrow_mut(|watch| {
        let watch = watch.as_mut().expect("set by run_here");
        watch.last = Instant::now();
        watch.raised = raised;
        watch.raised.is_some()
    })
}

/// `work` on a worker thread, GIL released, while this thread waits for it in steps of
/// `SIGNAL_PERIOD` and lets Python's signal handlers run between them; the worker sets
/// `returned` before waking this thread, so a wake-up is never mistaken for a timeout.
fn run_watched<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&core::Cancel) -> T + Send,
) -> (PyResult<T>, CallDiagnostics) {
    let cancel = core::Cancel::new();
    let watcher = std::thread::current();
    let returned = AtomicBool::new(false);
    let mut diagnostics = CallDiagnostics::default();
    let result = std::thread::scope(|scope| {
        let worker = scope.spawn(|| {
            let start = Instant::now();
            let out = work(&cancel);
            let engine_s = start.elapsed().as_secs_f64();
            returned.store(true, Ordering::Release);
            watcher.unpark();
            (out, engine_s)
        });
        loop {
            py.detach(|| {
                if !returned.load(Ordering::Acquire) {
                    std::thread::park_timeout(SIGNAL_PERIOD);
                }
            });
            if returned.load(Ordering::Acquire) {
                let (out, engine_s) = py
                    .detach(|| worker.join())
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
                diagnostics.engine_s = engine_s;
                return Ok(out);
            }
            if let Err(err) = py.check_signals() {
                cancel.cancel();
                let _ = py.detach(|| worker.join());
                return Err(err);
            }
        }
    });
    (result, diagnostics)
}

/// What the last engine call on this thread measured.
pub(crate) fn last_call() -> CallDiagnostics {
    LAST_CALL.with(std::cell::Cell::get)
}
