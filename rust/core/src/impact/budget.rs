//! How much work one impact may take: the checks that refuse a scene up front, and the step
//! budget that ends an impact which runs on (`timed_out`,
//! [`StopReason::StepBudget`](super::StopReason::StepBudget)).
//!
//! The unit is the contact's own number of steps, N_c = t_c / h: the estimated contact time
//! t_c = pi d / |v_y| (d the largest depth of the undamped normal law, from its energy
//! balance: a corner's depth^2 force and a face's linear one are both in it) over the nominal
//! step h (`dt_factor t_ref` for the fixed-step integrators, the largest step for the reference
//! integrator, which adds the steps its tolerance needs; see [`contact_steps`]).

use crate::error::{Error, Result};
use crate::model::{Initial, Integrator, Model};
use std::f64::consts::PI;

/// Smallest estimated maximal depth, in units of the spacing of doubles at the centre's height
/// (ulp(r)), that an impact may have: below it the centre's height cannot resolve the overlap
/// (a grazing impact at theta ~ 1e-10 deg moves the centre by a few ulps) and the contact law
/// would act on round-off. 2^20 ulps keep the depth to ~1e-6 relative.
pub const MIN_DEPTH_ULPS: f64 = 1_048_576.0;

/// Most fixed steps an estimated contact may need: beyond it a scene is refused with the cure
/// named rather than run for seconds to hours (a tiny dt_factor, a stiff and slow contact).
/// 4e6 steps are about one second of one core.
pub const MAX_STEPS_PER_CONTACT: f64 = 4e6;

/// The default step budget, in contacts' own numbers of steps N_c ([`contact_steps`]):
/// an impact that has not separated after `BUDGET_CONTACTS N_c + BUDGET_SLACK_STEPS` steps
/// ends as timed out. Twice [`TIMEOUT_CONTACT_TIMES`](super::TIMEOUT_CONTACT_TIMES): plain
/// steps of dt meet the contact-time budget first (an over-damped creep lasts tens of
/// undamped contact times, `tests/physics.rs`), and the step budget bounds what that budget
/// does not count: steps refined below dt at a polygon's events, and free flights between
/// contacts (jumped over, each advance counted as a step).
pub const BUDGET_CONTACTS: u64 = 200;

/// The most attempts (rejected steps included) the adaptive path's default budget allows one
/// impact: about 0.8 s of one core at its slowest steps measured (3.3 us, a 4096-gon spinning
/// at 10^4 deg/s, one corner after another; `benchmarks/extremes_bench.py`). Its contacts'
/// own estimate can be far larger: a fine polygon dropped slowly with a fast spin rattles on
/// its corners through 10^5 ... 10^6 contacts, each resolved to the tolerance. Such an impact
/// ends as timed out rather than running for seconds; `Scene::max_steps` lifts the ceiling.
pub const MAX_ADAPTIVE_ATTEMPTS: u64 = 250_000;

/// Steps every budget has on top of its multiple of N_c (events, a few re-contacts of a
/// contact with very few steps).
pub const BUDGET_SLACK_STEPS: u64 = 10_000;

/// The contact's own number of steps N_c: the estimated contact time over the nominal step
/// (see the module's documentation), for an estimated largest depth `depth_est`.
pub fn contact_steps(model: &Model, init: &Initial, depth_est: f64) -> f64 {
    match model.scene.integrator {
        Integrator::Reference | Integrator::Adaptive => {
            let tol = model.scene.local_tol();
            reference_contact_steps(model, init, depth_est, model.dt, tol)
        }
        _ => PI * depth_est / init.vy.abs() / model.dt,
    }
}

/// N_c of the reference integrator with largest step `h_max` and tolerance `tol`: t_c / h_max,
/// plus the steps its tolerance needs where it, not h_max, sets the step: about tol^(-1/5)
/// per smooth piece of a fifth-order method, times 16 pieces (touch, clip, stick/slip,
/// corners), plus 4 steps per corner that the initial spin turns past the plate during t_c
/// (it steps at most a quarter of the angle between corners).
pub fn reference_contact_steps(
    model: &Model,
    init: &Initial,
    depth_est: f64,
    h_max: f64,
    tol: f64,
) -> f64 {
    let t_est = PI * depth_est / init.vy.abs();
    let corners = model.scene.shape.vertices().len() as f64;
    let turned = 4.0 * corners * init.omega.abs() * t_est / (2.0 * PI);
    t_est / h_max + 16.0 * tol.powf(-0.2) + turned
}

/// A step budget for N_c = `n`: `BUDGET_CONTACTS n + BUDGET_SLACK_STEPS`, at most
/// [`MAX_ADAPTIVE_ATTEMPTS`] on the adaptive path, unless `Scene::max_steps` is set.
pub fn budget_for(model: &Model, n: f64) -> u64 {
    model.scene.max_steps.unwrap_or_else(|| {
        let budget = (BUDGET_CONTACTS as f64 * n.ceil()).min(1e15) as u64 + BUDGET_SLACK_STEPS;
        if model.scene.integrator == Integrator::Adaptive {
            budget.min(MAX_ADAPTIVE_ATTEMPTS)
        } else {
            budget
        }
    })
}

/// The step budget of an impact: `Scene::max_steps` when set, else `BUDGET_CONTACTS N_c +
/// BUDGET_SLACK_STEPS`.
pub fn step_budget(model: &Model, init: &Initial, depth_est: f64) -> u64 {
    budget_for(model, contact_steps(model, init, depth_est))
}

/// The default step budget of an impact (whatever `Scene::max_steps` says), for a validated
/// model and initial state.
pub fn default_step_budget(model: &Model, init: &Initial) -> Result<u64> {
    model.check_initial(init)?;
    let depth_est = super::estimate_max_depth(model, init)?;
    let unset = Model {
        scene: crate::model::Scene {
            max_steps: None,
            ..model.scene.clone()
        },
        ..model.clone()
    };
    Ok(step_budget(&unset, init, depth_est))
}

/// Refuses an impact whose estimated depth double precision cannot resolve at the centre's
/// height.
pub(crate) fn check_resolution(model: &Model, init: &Initial, depth_est: f64) -> Result<()> {
    let resolution = MIN_DEPTH_ULPS * f64::EPSILON * model.r;
    if depth_est < resolution {
        return Err(Error::invalid(
            "v",
            init.vx.hypot(init.vy),
            format!(
                "large enough that the estimated depth ({depth_est:e} m, at the normal speed \
                 v sin(theta) = {:e} m/s) resolves in double precision (>= {resolution:e} m at \
                 r = {} m): raise theta_deg or v, or lower E",
                init.vy.abs(),
                model.r
            ),
        ));
    }
    Ok(())
}

/// Refuses an impact whose contact needs more than [`MAX_STEPS_PER_CONTACT`] steps (for the
/// adaptive path and the reference: at a largest step too small for the contact).
pub(crate) fn check_contact_steps(model: &Model, init: &Initial, depth_est: f64) -> Result<()> {
    let n = contact_steps(model, init, depth_est);
    if n > MAX_STEPS_PER_CONTACT {
        let t_ref = model.t_ref;
        let cure = if model.scene.integrator.is_adaptive() {
            "raise dt_factor (here only the largest step: the tolerance sets the accuracy)"
        } else {
            "raise dt_factor, theta_deg or v, lower E, or use integrator \"adaptive\""
        };
        return Err(Error::invalid(
            "dt_factor",
            model.scene.dt_factor,
            format!(
                "large enough that a contact takes at most {MAX_STEPS_PER_CONTACT:e} steps: this \
                 one lasts ~{:.1e} t_ref (t_ref = {t_ref:e} s), ~{n:.1e} steps of dt_factor \
                 t_ref (a slow contact on a stiff material: its force grows slowly with depth); \
                 {cure}",
                n * model.scene.dt_factor,
            ),
        ));
    }
    Ok(())
}
