//! Counters for benchmarks (feature `bench-counters`, off by default): what the engine did,
//! per thread, for a benchmark to relate its time to (`examples/switch_cost.rs`).

use std::cell::Cell;

thread_local! {
    static LOCATED_SWITCHES: Cell<u64> = const { Cell::new(0) };
    static DROPPED_STEPS: Cell<f64> = const { Cell::new(0.0) };
    static PAIR_LAW_EVALUATIONS: Cell<u64> = const { Cell::new(0) };
}

/// Switches the adaptive path on the plate has located inside a step on this thread (pieces
/// ended at a switch strictly inside their step), since the thread started.
pub fn located_switches() -> u64 {
    LOCATED_SWITCHES.with(Cell::get)
}

/// The parts of their steps that located switches dropped (the step past the switch,
/// integrated and not taken), summed in steps, on this thread.
pub fn dropped_steps() -> f64 {
    DROPPED_STEPS.with(Cell::get)
}

/// Counts one switch located at fraction `th` of its step.
pub(crate) fn count_located_switch(th: f64) {
    LOCATED_SWITCHES.with(|c| c.set(c.get() + 1));
    DROPPED_STEPS.with(|c| c.set(c.get() + (1.0 - th)));
}

/// Evaluations of a pair's contact law on the adaptive path on this thread (stages, event
/// functions, extremes, mode changes), since the thread started (`examples/pair_evaluations.rs`).
pub fn pair_law_evaluations() -> u64 {
    PAIR_LAW_EVALUATIONS.with(Cell::get)
}

/// Counts one evaluation of a pair's contact law.
pub(crate) fn count_pair_law_evaluation() {
    PAIR_LAW_EVALUATIONS.with(|c| c.set(c.get() + 1));
}
