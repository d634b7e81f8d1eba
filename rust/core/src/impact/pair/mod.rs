//! One impact of a pair (docs/model.md, section 17): the two bodies touch with their centres
//! on the y axis (the particle above, at the height where they touch with their initial
//! orientations), the relative velocity g = v (cos theta, -sin theta) at first touch, and the
//! pair is stepped in its centre-of-mass frame on four lanes (x, y of the particle relative to
//! the partner, phi1, phi2) until the bodies separate for good. Round bodies cannot touch
//! again once they move apart; bodies with corners can, until their circumscribed circles
//! part (the plate's `impact::flight`). The pair runs on the plate's loops: the fixed-step loop
//! (`impact/fixed.rs`, through `impact/side.rs`'s `PairSide`) and the one adaptive loop
//! (`impact/adaptive/run.rs`, through `adaptive::OnPair`, with its ODE in `law`, `events`,
//! `switches` and `mode`) integrate the same coordinates; both end in the one record builder,
//! the plate's (`Record::close` in `impact/record.rs`).

use super::budget::{self, MIN_DEPTH_ULPS};
use super::fixed::{FixedLoop, Limits};
use super::record::{Record, Trace};
use super::side::PairSide;
use crate::cancel::Cancel;
use crate::error::{ensure_param, finite, Error, Result};
use crate::geometry::pair::{DiscPair, PairGeometry, SpherePair};
use crate::geometry::pair_shapes::ShapePair;
use crate::geometry::Shape;
use crate::integrate::{Gear5, Lanes, Stepper, Verlet};
use crate::model::scene::MAX_RIM_SPEED;
use crate::model::{Initial, Integrator, Model, NormalLaw, Pair};

mod adaptive;
mod depth;
mod events;
mod global;
mod law;
mod mode;
mod piece;
mod switches;

/// Simulates one impact of the pair of a validated particle model whose scene has a partner.
pub(super) fn run(
    model: &Model,
    init: &Initial,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let pair = Pair::new(model.clone())?;
    let (r1, r2) = (pair.particle.r, pair.r2);
    let particle = &pair.particle.scene.shape;
    let partner = &pair.partner_shape;
    let linear = matches!(pair.law.scene.normal_law, NormalLaw::Linear { .. });
    match (particle, partner) {
        (Shape::Sphere { .. }, _) => {
            let geometry = SpherePair { r1, r2, linear };
            run_on(&pair, init, geometry, trace, cancel)
        }
        (Shape::Disc { .. }, Shape::Disc { .. }) => {
            run_on(&pair, init, DiscPair { r1, r2, linear }, trace, cancel)
        }
        _ => {
            let mut shapes = ShapePair::new(particle, partner)
                .ok_or_else(|| Error::invalid("partner", "Sphere", "a pairing with corners"))?;
            shapes.springs = linear;
            run_on(&pair, init, shapes, trace, cancel)
        }
    }
}

/// One impact of `pair` on `geometry`, on the scene's integrator.
fn run_on<G: PairGeometry>(
    pair: &Pair,
    init: &Initial,
    geometry: G,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let start = Start::of(&geometry, init);
    let depth_est = checked_depth(pair, init, &geometry, &start)?;
    if pair.law.scene.integrator.is_adaptive() {
        return global::run_controlled(pair, init, (geometry, start), depth_est, trace, cancel);
    }
    let mut rec = run_fixed(pair, init, (geometry, start), depth_est, trace, cancel)?;
    if pair.law.scene.error_estimate {
        rec.err_est = super::richardson_estimate(&pair.particle, init, &rec, |half| {
            let half = Pair::new(half.clone())?;
            run_fixed(&half, init, (geometry, start), depth_est, None, cancel)
        })?;
    }
    Ok(rec)
}

/// Where an impact of a pair starts: the particle straight above the partner at the height
/// where they touch with their initial orientations.
#[derive(Debug, Clone, Copy)]
pub(super) struct Start {
    pub(super) q: Lanes,
}

impl Start {
    fn of<G: PairGeometry>(geometry: &G, init: &Initial) -> Self {
        let (phi1, phi2) = (init.phi0, init.partner_phi0);
        Start {
            q: [0.0, geometry.touch_height(phi1, phi2), phi1, phi2],
        }
    }
}

/// The pair's estimated largest overlap, after the checks of its initial state: the
/// partner's spin, a depth that double precision resolves, a contact of at most
/// `MAX_STEPS_PER_CONTACT` steps.
fn checked_depth<G: PairGeometry>(
    pair: &Pair,
    init: &Initial,
    geometry: &G,
    start: &Start,
) -> Result<f64> {
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
    let depth_est = depth::estimate_max_overlap(pair, init, geometry, start)?;
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

/// Runs the pair's fixed-step loop for its integrator.
fn run_fixed<G: PairGeometry>(
    pair: &Pair,
    init: &Initial,
    (geometry, start): (G, Start),
    depth_est: f64,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let law = &pair.law;
    let limits = Limits::of(init, depth_est, budget::step_budget(law, init, depth_est));
    let (q0, v0) = (start.q, [init.vx, init.vy, init.omega, init.partner_omega]);
    let side = PairSide::new(pair, geometry, (&q0, &v0));
    match law.scene.integrator {
        Integrator::Verlet => {
            let stepper = Verlet::start_lanes(q0, v0, law.dt);
            FixedLoop::new(side, stepper, law.dt, &limits).run(init, trace, cancel)
        }
        _ => {
            let stepper = Gear5::start_lanes(q0, v0, law.dt);
            FixedLoop::new(side, stepper, law.dt, &limits).run(init, trace, cancel)
        }
    }
}

/// Runs the pair on the adaptive path (`adaptive`) at the scene's tolerance (the
/// reference's for `integrator="reference"`), its largest step `dt_factor` t_ref.
fn run_adaptive<G: PairGeometry>(
    pair: &Pair,
    init: &Initial,
    (geometry, start): (G, Start),
    depth_est: f64,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let law = &pair.law;
    // The particle's scene, which names the partner: the law's is a lone disc's.
    let tol = pair.particle.scene.local_tol();
    let n_c = budget::reference_contact_steps(law, init, depth_est, law.dt, tol);
    let limits = (depth_est, tol, budget::budget_for(law, n_c));
    adaptive::integrate(pair, init, (geometry, start), limits, trace, cancel)
}
