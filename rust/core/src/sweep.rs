//! Many impacts in parallel (rayon over cases). Every case runs the very same code as a single
//! [`simulate`](crate::simulate) call, so results do not depend on the thread count.

use crate::cancel::Cancel;
use crate::error::{Error, Result};
use crate::impact::{simulate_cancellable, Record};
use crate::model::{check_case, Initial, Scene};
use rayon::prelude::*;

/// One impact to run.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// The scene.
    pub scene: Scene,
    /// The initial state at first touch.
    pub init: Initial,
}

/// Runs `work` on `threads` threads (0: rayon's default pool).
fn on_threads<T: Send>(threads: usize, work: impl FnOnce() -> T + Send) -> T {
    if threads == 0 {
        return work();
    }
    match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
        Ok(pool) => pool.install(work),
        Err(_) => work(),
    }
}

/// Checks every rule of every case without running it ([`check_case`]), in parallel; the
/// error of the first failing case comes with its index.
pub fn check_cases(cases: &[Case], threads: usize) -> std::result::Result<(), (usize, Error)> {
    let results = on_threads(threads, || {
        cases
            .par_iter()
            .map(|c| check_case(&c.scene, &c.init))
            .collect::<Vec<Result<()>>>()
    });
    results
        .into_iter()
        .enumerate()
        .try_for_each(|(i, r)| r.map_err(|e| (i, e)))
}

/// Runs every case, in parallel over `threads` threads (0: rayon's default).
///
/// Returns one record per case in input order, or the error of the first failing case with
/// its index.
pub fn run_cases(
    cases: &[Case],
    threads: usize,
) -> std::result::Result<Vec<Record>, (usize, Error)> {
    run_cases_cancellable(cases, threads, Cancel::never())
}

/// As [`run_cases`], interruptible: once `cancel` is set every worker abandons its impact
/// within [`crate::POLL_STEPS`] steps and starts no new case, and the result is
/// `Err((i, Error::Interrupted))`, `i` the first case that did not finish.
pub fn run_cases_cancellable(
    cases: &[Case],
    threads: usize,
    cancel: &Cancel,
) -> std::result::Result<Vec<Record>, (usize, Error)> {
    let work = || {
        cases
            .par_iter()
            .map(|c| {
                if cancel.is_cancelled() {
                    return Err(Error::Interrupted);
                }
                simulate_cancellable(&c.scene, &c.init, cancel)
            })
            .collect::<Vec<Result<Record>>>()
    };
    let results = on_threads(threads, work);
    if let Some(i) = results
        .iter()
        .position(|r| matches!(r, Err(Error::Interrupted)))
    {
        return Err((i, Error::Interrupted));
    }
    results
        .into_iter()
        .enumerate()
        .map(|(i, r)| r.map_err(|e| (i, e)))
        .collect()
}
