//! Many impacts in parallel (rayon over cases). Every case runs the very same code as a single
//! [`simulate`](crate::simulate) call, so results do not depend on the thread count.

use crate::cancel::Cancel;
use crate::error::Error;
use crate::impact::{simulate_cancellable, Record};
use crate::model::columns::{scene_from_columns_with, shape_columns};
use crate::model::{check_case, Initial, Scene, Templates, CASE_COLUMNS};
use rayon::prelude::*;

/// One impact to run.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// The scene.
    pub scene: Scene,
    /// The initial state at first touch.
    pub init: Initial,
}

/// The cases of a table whose rows are in [`CASE_COLUMNS`] order, each read by
/// [`crate::scene_from_columns`], with the unit-circumradius vertices of its convex polygons
/// (`templates`); the error of the first bad row with its index. Consecutive rows with the same `n`, `r`
/// and `body` share one shape, built once: a regular 120-gon's corners, area and polar angles
/// took 3.5 us per case, more than its fixed cost of an impact.
pub fn cases_from_rows(
    rows: impl Iterator<Item = [f64; CASE_COLUMNS.len()]>,
    templates: Templates,
) -> std::result::Result<Vec<Case>, (usize, Error)> {
    let mut out: Vec<Case> = Vec::new();
    let mut last_key = None;
    let key_columns = shape_columns();
    for (i, row) in rows.enumerate() {
        let key = key_columns.map(|k| row[k].to_bits());
        let shape = out
            .last()
            .filter(|_| last_key == Some(key))
            .map(|c| c.scene.shape.clone());
        let (scene, init) = scene_from_columns_with(&row, templates, shape).map_err(|e| (i, e))?;
        last_key = Some(key);
        out.push(Case { scene, init });
    }
    Ok(out)
}

/// `f` of every case, in order, on `threads` threads (0: rayon's default pool). One thread maps
/// them on the calling thread: a pool of one built for each call cost ~50 us, most of a
/// one-impact `restitution.simulate` once its record was no longer built through a frame.
fn map_cases<R: Send>(
    cases: &[Case],
    threads: usize,
    f: impl Fn(&Case) -> R + Sync + Send,
) -> Vec<R> {
    let parallel = || cases.par_iter().map(&f).collect();
    match threads {
        0 => parallel(),
        1 => cases.iter().map(&f).collect(),
        _ => match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
            Ok(pool) => pool.install(parallel),
            Err(_) => parallel(),
        },
    }
}

/// Checks every rule of every case without running it ([`check_case`]), in parallel; the
/// error of the first failing case comes with its index.
pub fn check_cases(cases: &[Case], threads: usize) -> std::result::Result<(), (usize, Error)> {
    let results = map_cases(cases, threads, |c| check_case(&c.scene, &c.init));
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
/// within [`crate::cancel::POLL_STEPS`] steps and starts no new case, and the result is
/// `Err((i, Error::Interrupted))`, `i` the first case that did not finish.
pub fn run_cases_cancellable(
    cases: &[Case],
    threads: usize,
    cancel: &Cancel,
) -> std::result::Result<Vec<Record>, (usize, Error)> {
    let results = map_cases(cases, threads, |c| {
        if cancel.is_cancelled() {
            return Err(Error::Interrupted);
        }
        simulate_cancellable(&c.scene, &c.init, cancel)
    });
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::scene_from_columns;

    /// A row of the preset case with the given columns set.
    fn row(set: &[(&str, f64)]) -> [f64; CASE_COLUMNS.len()] {
        let mut row = [f64::NAN; CASE_COLUMNS.len()];
        let base = [
            ("theta_deg", 30.0),
            ("omega_in", 0.0),
            ("v", 0.0357),
            ("mu", 0.5),
            ("gamma", 0.33),
            ("gamma_t", 0.5),
            ("E", 1e7),
            ("rho", 2500.0),
            ("r", 0.01),
            ("phi0_deg", 0.0),
            ("n", 0.0),
            ("integrator", 0.0),
            ("normal_law", 0.0),
            ("inertia", 0.0),
            ("overlap", 0.0),
            ("tangential", 0.0),
            ("tangential_history", 0.0),
            ("body", 0.0),
            ("tol", 1e-6),
            ("error_estimate", 0.0),
            ("partner_body", 0.0),
            ("partner_omega_in", 0.0),
        ];
        for (name, v) in base.iter().chain(set) {
            let k = CASE_COLUMNS.iter().position(|c| c == name).unwrap();
            row[k] = *v;
        }
        row
    }

    #[test]
    fn shared_shapes_are_the_shapes_each_row_asks_for() {
        // Runs of equal shapes, then changes of n, r and body one at a time.
        let rows = [
            row(&[("n", 120.0)]),
            row(&[("n", 120.0), ("mu", 0.1)]),
            row(&[("n", 12.0)]),
            row(&[("n", 12.0), ("r", 0.02)]),
            row(&[("n", 0.0), ("r", 0.02)]),
            row(&[("n", 0.0), ("r", 0.02), ("body", 1.0)]),
            row(&[("n", 5.0)]),
        ];
        let cases = cases_from_rows(rows.iter().copied(), Templates::default()).unwrap();
        for (case, row) in cases.iter().zip(&rows) {
            let (scene, init) = scene_from_columns(row, Templates::default()).unwrap();
            assert_eq!(case.scene, scene);
            assert_eq!(case.init, init);
        }
        // A bad row is named by its index.
        let bad = [
            row(&[("n", 12.0)]),
            row(&[("n", 12.0), ("theta_deg", 100.0)]),
        ];
        assert!(matches!(
            cases_from_rows(bad.into_iter(), Templates::default()),
            Err((1, _))
        ));
    }
}
