//! The consistency matrix's documented bounds (docs/consistency.md), shared by the matrix
//! (`consistency.rs`) and the measurements behind them (`measurements.rs`).

use restitution_core::{max_dt_factor, Integrator, NormalLaw, Scene, Shape};

/// The integrator's default step, or its stability bound where that is smaller.
pub fn default_step(scene: Scene) -> Scene {
    let bound = max_dt_factor(&scene).unwrap();
    Scene {
        dt_factor: scene.dt_factor.min(bound),
        tol: ADAPTIVE_TOL,
        ..scene
    }
}

/// The adaptive path's tolerance in the matrix (its documented bounds scale with it).
pub const ADAPTIVE_TOL: f64 = 1e-9;

/// The largest energy gain, energy_out / energy_in - 1, that an elastic impact (all damping
/// off, any mu) may show: the integrator's documented bound (docs/consistency.md), measured
/// over this matrix and the long random one.
pub fn documented_gain_bound(scene: &Scene) -> f64 {
    let polygon = !matches!(scene.shape, Shape::Disc { .. });
    if corners_in_pair(scene) && matches!(scene.normal_law, NormalLaw::Linear { .. }) {
        // Gear-5 (the one integrator of this pairing) steps through the vertex springs'
        // switches of edge (their force turns there) without locating them: measured up to
        // 3.4e-5 on twin triangles (`tests/consistency.rs`).
        return 5e-5;
    }
    let fixed = matches!(scene.integrator, Integrator::Gear5 | Integrator::Verlet);
    if corners_in_pair(scene) && scene.normal_law == NormalLaw::Area && fixed {
        // The potential's force (docs/model.md 17.8) jumps where a crossing of the two
        // boundaries passes a corner; the adaptive path and the reference hold the overlap
        // and locate those switches (their general bounds below hold: measured 2.6e-11 and
        // 1.5e-10 on twin 120-gons), the fixed steps step through them, first order there.
        // Measured over the quick matrix: up to 4.9e-5 at the default step (twin 12-gons,
        // theta 85; 2.9e-5, -3.6e-7 at half and a quarter of it). The old force, not a
        // potential's, gained up to 4.5 % on every integrator alike.
        return 1e-4;
    }
    match (scene.integrator, scene.normal_law, polygon) {
        (Integrator::Reference, _, _) => 1e-9,
        // The adaptive path: its e_kin error is at most a few tol.
        (Integrator::Adaptive, _, _) => 10.0 * scene.tol,
        // The linear force kinks at touch and separation (delta^1 against the area law's
        // delta^1.5) and at every corner crossing; a fixed step straddling a kink errs to
        // first order there (the disc's loop locates no events, frictional polygons neither).
        (_, NormalLaw::Linear { .. }, _) => 2e-5,
        // A frictional polygon keeps the plain steps (no located corner crossings): measured
        // 1.13e-5 on a face-first triangle at mu = 1e-9 (`measure_weak_friction`).
        (_, NormalLaw::Area, true) if scene.mu > 0.0 => 2e-5,
        // Verlet's own O(dt^2) error on a polygon: its modified energy jumps where a corner
        // crosses the plate, located or not; measured 5.8e-6 without friction (a square face
        // first, theta 90, omega_in r / v 0.2: `measure_frictionless_polygons`).
        (Integrator::Verlet, NormalLaw::Area, true) => 2e-5,
        _ => 1e-6,
    }
}

/// The largest |energy_residual| of a damped or frictional impact at the default step
/// (docs/model.md: 1e-6). The linear law's dashpot force jumps at touch (c_n v_n at zero depth),
/// which the fixed steps' work quadrature meets to first order: measured up to 1.23e-6 on the
/// disc. On a polygon Gear-5 locates every corner crossing, but with friction the stick/slip
/// switches between them are not located: measured up to 5.8e-6 (5-gon, mu 10, falling
/// 4.3e-6, 9.3e-7, 1.6e-7 per halving of the step; docs/consistency.md).
pub fn documented_residual_bound(scene: &Scene) -> f64 {
    let polygon = matches!(scene.shape, Shape::Polygon(_));
    if corners_in_pair(scene) && matches!(scene.normal_law, NormalLaw::Linear { .. }) {
        // As for the gain: the springs' switches and the dashpots' jumps at touch are stepped
        // through. Measured up to 1.09e-5 over the long matrix at 10^5 (twin triangles, damped,
        // mu 0 and 10), second order in the step (2.6e-6 and 6.5e-7 at half and a quarter of
        // it): the steps' error, not a defect of the balance. 7.0e-6 before that run.
        return 2e-5;
    }
    let fixed = matches!(scene.integrator, Integrator::Gear5 | Integrator::Verlet);
    let disc_on_plate = matches!(scene.shape, Shape::Disc { .. }) && scene.partner.is_none();
    let area = matches!(scene.normal_law, NormalLaw::Area);
    if fixed && disc_on_plate && area && scene.mu >= 100.0 && scene.gamma_t > 0.0 {
        // The disc on the plate (area law) at huge friction: the tangential dashpot's
        // -c_t v_t acts from the instant the cone mu F_n allows it, just after touch, inside
        // the first step. Measured 1.22e-6 at mu 1e3 over the long matrix at 10^5, third
        // order in the step (1.7e-7 and 2.1e-8 at half and a quarter of it).
        return 2e-6;
    }
    match (scene.integrator, scene.normal_law) {
        (Integrator::Reference | Integrator::Adaptive, _)
        | (_, NormalLaw::Area)
        | (_, NormalLaw::Hertz { .. }) => 1e-6,
        (_, NormalLaw::Linear { .. }) if polygon && scene.mu > 0.0 => 1e-5,
        (_, NormalLaw::Linear { .. }) => 2e-6,
    }
}

/// The largest |angular momentum residual| of a pair (relative to m* v (r1 + r2)): the issue's
/// 1e-12 for every integrator. The forces act at one point on both bodies, so the equations
/// conserve it, and the integrators restore it by a rigid turn of the pair (`Pair::restoring_turn`);
/// before that Gear-5 drifted by up to 7.4e-10 over the matrix at the default step and 3.7e-9
/// on an undamped linear spring at mu 1e3, the adaptive path by 2.6e-5 tol.
pub fn documented_angular_momentum_bound(_scene: &Scene) -> f64 {
    1e-12
}

/// Whether `scene` is a pair in which a body has corners (docs/model.md, section 17.8).
pub fn corners_in_pair(scene: &Scene) -> bool {
    let corners = |s: &Shape| matches!(s, Shape::Polygon(_));
    scene
        .partner
        .as_ref()
        .is_some_and(|p| corners(&p.shape) || corners(&scene.shape))
}
