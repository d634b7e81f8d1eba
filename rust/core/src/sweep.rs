//! Many impacts in parallel (rayon over cases). Every case runs the very same code as a single
//! [`simulate`](crate::simulate) call, so results do not depend on the thread count.

use crate::cancel::Cancel;
use crate::error::{Error, Result};
use crate::impact::{simulate_cancellable, Record};
use crate::model::{Initial, Scene};
use rayon::prelude::*;

/// One impact to run.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// The scene.
    pub scene: Scene,
    /// The initial state at first touch.
    pub init: Initial,
}

/// Runs every case, in parallel over `threads` threads (0: rayon's default).
///
/// Returns one record per case in input order, or the error of the first failing case with
/// its index.
pub fn run_cases(
    cases: &[Case],
    threads: usize,
) -> std::result::Result<Vec<Record>, (usize, crate::Error)> {
    run_cases_cancellable(cases, threads, Cancel::never())
}

/// As [`run_cases`], interruptible: once `cancel` is set every worker abandons its impact
/// within [`crate::POLL_STEPS`] steps and starts no new case, and the result is
/// `Err((i, Error::Interrupted))`, `i` the first case that did not finish.
pub fn run_cases_cancellable(
    cases: &[Case],
    threads: usize,
    cancel: &Cancel,
) -> std::result::Result<Vec<Record>, (usize, crate::Error)> {
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
    let results = if threads == 0 {
        work()
    } else {
        match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
            Ok(pool) => pool.install(work),
            Err(_) => work(),
        }
    };
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
