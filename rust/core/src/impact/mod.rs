//! One impact, from first touch to separation: the record (docs/model.md, section 9) and an optional trace.
//!
//! The dependencies run one way: this dispatch calls the adaptive path
//! ([`crate::impact::adaptive`]), which uses only the leaves [`record`] and [`budget`]
//! (themselves free of both), never this file.

use crate::cancel::Cancel;
use crate::error::Result;
use crate::model::{Initial, Model, Scene};

pub mod adaptive;
pub mod budget;
pub mod fixed;
pub(crate) mod flight;
pub(crate) mod pair;
pub mod record;
pub(crate) mod side;
pub(crate) mod work;

pub use fixed::{tolerance, ERROR_TOLERANCE, TOLERANCE_FLOOR_ULPS};

pub use budget::{
    budget_for, contact_steps, default_step_budget, reference_contact_steps, step_budget,
    BUDGET_CONTACTS, BUDGET_SLACK_STEPS, MAX_ADAPTIVE_ATTEMPTS, MAX_STEPS_PER_CONTACT,
    MIN_DEPTH_ULPS,
};
pub use record::{
    estimate_max_depth, Cell, Record, StopReason, Trace, RECORD_COLUMNS, TIMEOUT_CONTACT_TIMES,
};

/// Simulates one impact.
pub fn simulate(scene: &Scene, init: &Initial) -> Result<Record> {
    simulate_cancellable(scene, init, Cancel::never())
}

/// Simulates one impact; returns `Err(Error::Interrupted)` soon after `cancel` is set
/// (polled every [`crate::cancel::POLL_STEPS`] steps).
pub fn simulate_cancellable(scene: &Scene, init: &Initial, cancel: &Cancel) -> Result<Record> {
    let model = Model::new(scene)?;
    run(&model, init, None, cancel)
}

/// Simulates one impact of an already derived model, without [`Model::new`]'s checks of
/// `dt_factor` (used to measure the stability bound above it; see `tests/stability.rs`).
pub fn simulate_model(model: &Model, init: &Initial) -> Result<Record> {
    run(model, init, None, Cancel::never())
}

/// Simulates one impact and records every step.
pub fn simulate_with_trace(scene: &Scene, init: &Initial) -> Result<(Record, Trace)> {
    simulate_with_trace_cancellable(scene, init, Cancel::never())
}

/// As [`simulate_with_trace`], interruptible like [`simulate_cancellable`].
pub fn simulate_with_trace_cancellable(
    scene: &Scene,
    init: &Initial,
    cancel: &Cancel,
) -> Result<(Record, Trace)> {
    let model = Model::new(scene)?;
    let mut trace = Trace::default();
    let rec = run(&model, init, Some(&mut trace), cancel)?;
    Ok((rec, trace))
}

fn run(
    model: &Model,
    init: &Initial,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    model.check_initial(init)?;
    let scene = &model.scene;
    if scene.partner.is_some() {
        return pair::run(model, init, trace, cancel);
    }
    let depth_est = estimate_max_depth(model, init)?;
    budget::check_resolution(model, init, depth_est)?;
    budget::check_contact_steps(model, init, depth_est)?;
    if scene.integrator.is_adaptive() {
        return adaptive::integrate(
            model,
            init,
            depth_est,
            &adaptive::ReferenceOptions::for_scene(scene),
            trace,
            cancel,
        );
    }
    let mut rec = fixed::run_fixed(model, init, depth_est, trace, cancel)?;
    if scene.error_estimate {
        rec.err_est = richardson_estimate(model, init, &rec, |half| {
            let depth_est = estimate_max_depth(half, init)?;
            fixed::run_fixed(half, init, depth_est, None, cancel)
        })?;
    }
    Ok(rec)
}

/// The error of a fixed-step record estimated from a second run at half the step: for an
/// order p >= 1 the error at dt is |diff| 2^p / (2^p - 1) <= 2 |diff| (first order, the
/// frictional impacts, sets the factor 2), times a safety factor 2: the switches make the
/// convergence uneven (measured on the disc: the true error is 0.33 ... 1.2 times 2 |diff|,
/// `tests/adaptive.rs`). The second run gets twice the step budget.
fn richardson_estimate(
    model: &Model,
    init: &Initial,
    rec: &Record,
    run_half: impl FnOnce(&Model) -> Result<Record>,
) -> Result<Option<f64>> {
    let scene = &model.scene;
    let half = Model::derive(&Scene {
        dt_factor: 0.5 * scene.dt_factor,
        max_steps: scene.max_steps.map(|n| n.saturating_mul(2)),
        error_estimate: false,
        ..scene.clone()
    })?;
    // A half step the budget refuses (over 4e6 steps) leaves the estimate undefined.
    let fine = match run_half(&half) {
        Err(crate::error::Error::Interrupted) => return Err(crate::error::Error::Interrupted),
        Err(_) => return Ok(None),
        Ok(fine) => fine,
    };
    if rec.timed_out || fine.timed_out {
        return Ok(None);
    }
    let speed = init.vx.hypot(init.vy);
    Ok(Some(4.0 * rec.accuracy_distance(&fine, model.r, speed)))
}
