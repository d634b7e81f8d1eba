//! The high-accuracy reference integrator: adaptive Dormand-Prince 5(4) on the smooth pieces of
//! the continuous-time contact law, every switch between pieces located and the integration
//! restarted there.
//!
//! Why: the fixed-step integrators step across the non-smooth points of the law (touch and
//! separation, a polygon corner crossing the plate, the normal-force clip switching on or off,
//! stick <-> slip), so their error falls only like dt^1 ... dt^3 (docs/model.md, section 7.6).
//! Between those points the law is smooth, and a 5th-order method with error control converges
//! at its full order there; locating each switch as a root of a continuous event function keeps
//! the whole impact accurate to about the tolerance.
//!
//! The continuous-time law is the dt -> 0 limit of the discrete rule of docs/model.md (sections 4, 5):
//! - Normal force: as in [`crate::law`], clipped to zero while F_el + F_d < 0.
//! - Cundall-Strack spring: while sticking dxi/dt = v_t and F_t = -k_t xi - c_t v_t with
//!   |F_t| <= mu F_n; while slipping F_t = mu F_n s (s the sign of the trial force) and the spring
//!   follows algebraically, xi = -(F_t + c_t v_t) / k_t. Slip ends when the trial force of a
//!   sticking spring would move back inside the cone: s (dF_trial/dt) < mu dF_n/dt with
//!   dF_trial/dt = -k_t v_t - c_t dv_t/dt (both rates taken along the motion).
//! - While the normal force is clipped there is no tangential force and xi = -c_t v_t / k_t.
//!
//! Inside a piece the mode is *held*: the force formulas of the piece are continued smoothly
//! a little beyond its end (a polygon's clipped region keeps its set of submerged corners, the
//! clip its state), so that the Runge-Kutta stages never see a kink. The work of each force is
//! integrated as three more components of the same ODE (the same stages), so the energy audit
//! is accurate to the tolerance too.
//!
//! `dt_factor` means the largest (and the first) step, in units of t_ref; the accuracy is set
//! by [`ReferenceOptions::tol`].
//!
//! The parts: `run` the one loop of an impact, on the plate and on a pair, generic over
//! `side`'s `AdaptiveSide` (what the loop asks of the body the particle meets); `rules`,
//! `switches` and `extremes` the rules every side follows (step control, err_est, chatter,
//! the location of a switch and of the deepest point); the plate's side: `plate` (its
//! `AdaptiveSide`), `step` one Runge-Kutta step ([`crate::integrate::dopri`]) with what the
//! switches read from its stages, `law` the forces of a held mode, `mode` the modes and the
//! switch at an event, `events` the event functions and their location. A pair's side lives
//! in `impact/pair`, which implements `AdaptiveSide` from below.

mod control;
mod events;
mod extremes;
mod law;
mod mode;
mod piece;
mod plate;
mod rules;
mod run;
mod side;
mod stages;
mod step;
mod switches;

use crate::cancel::Cancel;
use crate::error::Result;
use crate::impact::record::{estimate_max_depth, Record, Trace};
use crate::model::scene::REFERENCE_LOCAL_TOL;
use crate::model::{Initial, Integrator, Model, Scene};

pub(crate) use extremes::turning_point;
pub(crate) use piece::Tan;
pub(crate) use plate::integrate;
pub(crate) use rules::{
    error_estimate, root_exponent, spring_scale, state_at_switch, velocity_scales, ErrorSum,
    Limits, SwitchKind,
};
pub(crate) use run::Run;
pub(crate) use side::AdaptiveSide;
pub(crate) use stages::{LinearSlip, TangentialStages};
pub(crate) use switches::{
    first_positive_sample, locate_switch, sampled_first_switch, switch_precision, TANGENTIAL_PARTS,
};

/// Settings of the reference integrator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceOptions {
    /// Local error tolerance per step, relative to the natural scales of the impact (the
    /// estimated maximal depth for positions, the impact speed for velocities, the kinetic
    /// energy for works). Default 1e-12: global errors come out at about 20 tol.
    pub tol: f64,
    /// Largest step in units of t_ref; `None`: the scene's `dt_factor`.
    pub max_step_factor: Option<f64>,
}

pub use crate::model::scene::LOCAL_TOL_PER_TARGET;

/// Factor on the local error estimates accumulated in quadrature that makes `err_est`: at the
/// local tolerance [`LOCAL_TOL_PER_TARGET`] the 5 % quantile of err_est / error over the
/// accuracy grid's largest steps and tolerances is 0.26 ... 4.3 at factor 0.5, so 4.5 times
/// that puts err_est >= error in >= 99.9 % of impacts at every setting, within 9 ... 36 times it
/// in the median (`tests/adaptive.rs`).
pub const ERR_EST_FACTOR: f64 = 2.25;

impl ReferenceOptions {
    /// The settings a scene asks for: the reference's for `Integrator::Reference`, the scene's
    /// tolerance for `Integrator::Adaptive`; the largest step is the scene's `dt_factor`.
    pub fn for_scene(scene: &Scene) -> Self {
        ReferenceOptions {
            tol: scene.local_tol(),
            max_step_factor: None,
        }
    }
}

impl Default for ReferenceOptions {
    fn default() -> Self {
        ReferenceOptions {
            tol: REFERENCE_LOCAL_TOL,
            max_step_factor: None,
        }
    }
}

/// Simulates one impact with the reference integrator, whatever `scene.integrator` says.
pub fn simulate_reference(
    scene: &Scene,
    init: &Initial,
    opts: &ReferenceOptions,
) -> Result<Record> {
    let model = reference_model(scene)?;
    model.check_initial(init)?;
    let depth_est = estimate_max_depth(&model, init)?;
    integrate(&model, init, depth_est, opts, None, Cancel::never())
}

/// As [`simulate_reference`], and records every accepted step.
pub fn simulate_reference_with_trace(
    scene: &Scene,
    init: &Initial,
    opts: &ReferenceOptions,
) -> Result<(Record, Trace)> {
    let model = reference_model(scene)?;
    model.check_initial(init)?;
    let depth_est = estimate_max_depth(&model, init)?;
    let mut trace = Trace::default();
    let rec = integrate(
        &model,
        init,
        depth_est,
        opts,
        Some(&mut trace),
        Cancel::never(),
    )?;
    Ok((rec, trace))
}

/// The scene validated as one for the reference integrator (its `dt_factor` is only its
/// largest step, so the fixed-step integrators' stability bounds do not apply).
fn reference_model(scene: &Scene) -> Result<Model> {
    Model::new(&Scene {
        integrator: Integrator::Reference,
        ..scene.clone()
    })
}

// ---------------------------------------------------------------------------------------------
// The state of the ODE

/// x, y, vx, vy, phi, omega, xi, then the works of the elastic, damping and tangential forces.
/// (vx, vy) at the offset of a pair of components: the stages write the state in pairs, and
/// the law reads the velocity as one; across a pair's boundary that read missed the store
/// forwarding at every stage.
const NS: usize = 10;
type State = [f64; NS];
const X: usize = 0;
const Y: usize = 1;
const VX: usize = 2;
const VY: usize = 3;
const PHI: usize = 4;
const OM: usize = 5;
const XI: usize = 6;
const W_EL: usize = 7;
const W_D: usize = 8;
const W_T: usize = 9;
