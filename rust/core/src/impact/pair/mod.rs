//! One impact of a pair (docs/model.md, section 17) on the fixed-step integrators: the two
//! bodies touch with their centres on the y axis (the particle above), the relative velocity
//! g = v (cos theta, -sin theta) at first touch, and the pair is stepped in its centre-of-mass
//! frame on four lanes (x, y of the particle relative to the partner, phi1, phi2) until the
//! bodies separate. Round bodies cannot touch again once they move apart. The adaptive path
//! (`adaptive`, `ode`) integrates the same coordinates; both end in the one record (`record`).

use super::budget::{self, MIN_DEPTH_ULPS};
use super::record::{Record, Trace, TIMEOUT_CONTACT_TIMES};
use crate::cancel::Cancel;
use crate::error::{ensure_param, finite, Error, Result};
use crate::geometry::pair::{DiscPair, SpherePair};
use crate::geometry::Shape;
use crate::integrate::{Gear5, Verlet};
use crate::model::scene::MAX_RIM_SPEED;
use crate::model::{Initial, Integrator, Model, Pair};
use fixed::{Limits, PairLoop};
use std::f64::consts::PI;

mod adaptive;
mod depth;
mod fixed;
mod ode;
mod record;

/// Simulates one impact of the pair of a validated particle model whose scene has a partner.
pub(super) fn run(
    model: &Model,
    init: &Initial,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let pair = Pair::new(model.clone())?;
    let depth_est = checked_depth(&pair, init)?;
    if model.scene.integrator.is_adaptive() {
        return run_adaptive(&pair, init, depth_est, trace, cancel);
    }
    let mut rec = run_fixed(&pair, init, depth_est, trace, cancel)?;
    if model.scene.error_estimate {
        rec.err_est = super::richardson_estimate(model, init, &rec, |half| {
            run_fixed(&Pair::new(half.clone())?, init, depth_est, None, cancel)
        })?;
    }
    Ok(rec)
}

/// The pair's estimated largest overlap, after the checks of its initial state: the
/// partner's spin, a depth that double precision resolves, a contact of at most
/// `MAX_STEPS_PER_CONTACT` steps.
fn checked_depth(pair: &Pair, init: &Initial) -> Result<f64> {
    finite("partner_omega_in", init.partner_omega)?;
    ensure_param!(
        init.partner_omega.abs() * pair.r2 <= MAX_RIM_SPEED,
        "partner_omega_in",
        init.partner_omega,
        format!(
            "with |partner_omega_in| r <= {MAX_RIM_SPEED:e} m/s (r = {} m)",
            pair.r2
        )
    );
    let depth_est = depth::estimate_max_overlap(pair, init)?;
    let reach = pair.particle.r + pair.r2;
    let resolution = MIN_DEPTH_ULPS * f64::EPSILON * reach;
    if depth_est < resolution {
        return Err(Error::invalid(
            "v",
            init.vx.hypot(init.vy),
            format!(
                "large enough that the estimated overlap ({depth_est:e} m) resolves in double \
                 precision at the centres' distance (>= {resolution:e} m at r1 + r2 = {reach} m): \
                 raise theta_deg or v, or lower E"
            ),
        ));
    }
    budget::check_contact_steps(&pair.law, init, depth_est)?;
    Ok(depth_est)
}

/// Runs the pair's loop for its geometry and integrator.
fn run_fixed(
    pair: &Pair,
    init: &Initial,
    depth_est: f64,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let (r1, r2) = (pair.particle.r, pair.r2);
    let limits = Limits {
        max_steps: budget::step_budget(&pair.law, init, depth_est),
        contact_time: TIMEOUT_CONTACT_TIMES * PI * depth_est / init.vy.abs(),
    };
    let sphere = matches!(pair.particle.scene.shape, Shape::Sphere { .. });
    match (pair.law.scene.integrator, sphere) {
        (Integrator::Verlet, false) => {
            PairLoop::<Verlet, _>::new(pair, init, DiscPair { r1, r2 }, limits).run(trace, cancel)
        }
        (Integrator::Verlet, true) => {
            PairLoop::<Verlet, _>::new(pair, init, SpherePair { r1, r2 }, limits).run(trace, cancel)
        }
        (_, false) => {
            PairLoop::<Gear5, _>::new(pair, init, DiscPair { r1, r2 }, limits).run(trace, cancel)
        }
        (_, true) => {
            PairLoop::<Gear5, _>::new(pair, init, SpherePair { r1, r2 }, limits).run(trace, cancel)
        }
    }
}

/// Runs the pair on the adaptive path (`adaptive`) at the scene's tolerance (the
/// reference's for `integrator="reference"`), its largest step `dt_factor` t_ref.
fn run_adaptive(
    pair: &Pair,
    init: &Initial,
    depth_est: f64,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let (r1, r2) = (pair.particle.r, pair.r2);
    let law = &pair.law;
    let tol = law.scene.local_tol();
    let n_c = budget::reference_contact_steps(law, init, depth_est, law.dt, tol);
    let limits = (depth_est, tol, budget::budget_for(law, n_c));
    match pair.particle.scene.shape {
        Shape::Sphere { .. } => {
            let geometry = SpherePair { r1, r2 };
            adaptive::integrate(pair, init, geometry, limits, trace, cancel)
        }
        _ => {
            let geometry = DiscPair { r1, r2 };
            adaptive::integrate(pair, init, geometry, limits, trace, cancel)
        }
    }
}
