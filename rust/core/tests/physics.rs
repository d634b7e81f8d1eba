//! Physics of one exact-disc impact against the limits of docs/model.md, section 11 (issue 3): elastic limit,
//! energy audit, sliding and rolling regimes (disc and sphere inertia), the linear law against
//! its analytic restitution, mirror symmetry, the time-out and the depth estimate. Convergence
//! with dt is `convergence.rs`; refusals and the time-step bound, `refusals.rs`.
//!
//! Expected values come from rigid-body theory and the contact law's equations, never from the
//! code's own output. Run with `cargo test -p restitution-core --release --test physics --
//! --nocapture` to see the measured agreements.

mod common;

use common::*;
use restitution_core::{
    estimate_max_depth, simulate_with_trace, InertiaModel, Initial, Integrator, Model, NormalLaw,
    Scene, Shape,
};
use std::f64::consts::PI;

// ---------------------------------------------------------------------------------------------
// mu = 0, gamma = 0: a perfectly elastic, frictionless bounce.

#[test]
fn frictionless_undamped_bounce_is_elastic() {
    // The energy error is the integrator's (order ~3 for Gear-5 here): at the default
    // dt_factor 0.01 the worst, head-on, is 1.6e-8 for Gear-5; 1e-8 needs dt_factor 0.005.
    // e_n, e_t and omega hold at the default dt.
    for integrator in BOTH {
        for (dt_factor, energy_tol) in [(0.01, 1e-7), (0.005, 1e-8)] {
            let scene = Scene {
                mu: 0.0,
                gamma: 0.0,
                integrator,
                dt_factor,
                ..Scene::default()
            };
            let mut worst: f64 = 0.0;
            for theta in [5.0, 30.0, 60.0, 89.0, 90.0] {
                for omega in [0.0, 3.0, -2.0] {
                    let rec = run(&scene, &at(theta, omega));
                    let what =
                        format!("{integrator:?} dt_factor {dt_factor} theta {theta} omega {omega}");
                    assert!((rec.e_n - 1.0).abs() < 1e-6, "{what}: e_n = {}", rec.e_n);
                    // No tangential force and no torque (the disc's normal force acts right
                    // below its centre): vx and omega are untouched, bit for bit.
                    if theta == 90.0 {
                        assert_eq!(rec.e_t, None, "{what}: vx = 0 exactly at 90 deg");
                    } else {
                        assert_eq!(rec.e_t, Some(1.0), "{what}");
                    }
                    assert_eq!(rec.omega_out, omega, "{what}");
                    assert_eq!(rec.work_friction, 0.0, "{what}");
                    let rel = (rec.energy_out - rec.energy_in) / rec.energy_in;
                    worst = worst.max(rel.abs());
                    assert!(rel.abs() < energy_tol, "{what}: energy change {rel:e}");
                    assert!(rec.separated && !rec.timed_out, "{what}");
                }
            }
            eprintln!("elastic bounce, {integrator:?}, dt_factor {dt_factor}: largest |energy change| {worst:.2e}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// gamma > 0: the energy audit closes and the contact never creates energy.

#[test]
fn damped_impacts_lose_energy_and_the_audit_closes() {
    for integrator in BOTH {
        for gamma in [0.1, 0.33, 1.0] {
            for mu in [0.0, 0.1, 0.5, 1.0] {
                for theta in [5.0, 20.0, 45.0, 70.0, 90.0] {
                    let scene = Scene {
                        gamma,
                        mu,
                        integrator,
                        ..Scene::default()
                    };
                    let rec = run(&scene, &at(theta, 0.0));
                    let what = format!("{integrator:?} gamma {gamma} mu {mu} theta {theta}");
                    let e0 = rec.energy_in;
                    assert!(
                        rec.energy_residual.abs() < 1e-6,
                        "{what}: residual {:e}",
                        rec.energy_residual
                    );
                    assert!(rec.energy_out <= e0 * (1.0 + 1e-6), "{what}: energy gained");
                    // Damping and friction only take energy out; "<= 0" up to the audit's
                    // own integration error.
                    assert!(
                        rec.work_normal <= 1e-6 * e0,
                        "{what}: W_n = {:e}",
                        rec.work_normal
                    );
                    assert!(
                        rec.work_friction <= 1e-6 * e0,
                        "{what}: W_t = {:e}",
                        rec.work_friction
                    );
                    if mu == 0.0 {
                        assert_eq!(rec.work_friction, 0.0, "{what}");
                    }
                }
            }
        }
    }
}

#[test]
fn energy_residual_shrinks_with_dt() {
    // Gear-5: the residual is the audit's quadrature error against the integrator's, and
    // must shrink as dt does.
    for (gamma, mu, theta) in [(0.33, 0.5, 45.0), (10.0, 0.0, 90.0), (10.0, 1.0, 30.0)] {
        // gamma = 10 bounds dt_factor at 0.013 (the damping rate, tests/stability.rs): halve.
        let scale = if gamma > 1.0 { 0.5 } else { 1.0 };
        let res: Vec<f64> = [0.02, 0.01, 0.005]
            .iter()
            .map(|&dt_factor| {
                let scene = Scene {
                    gamma,
                    mu,
                    dt_factor: dt_factor * scale,
                    ..Scene::default()
                };
                run(&scene, &at(theta, 0.0)).energy_residual.abs()
            })
            .collect();
        let sci_res = sci(&res);
        eprintln!("gear5 |energy_residual| at dt_factor (0.02, 0.01, 0.005) x {scale} (gamma {gamma}, mu {mu}, theta {theta}): {sci_res}");
        assert!(
            res[0] > res[1] && res[1] > res[2],
            "gamma {gamma} mu {mu}: {sci_res}"
        );
    }
    // Velocity Verlet: with v' = v + (a + a') dt / 2 the trapezoidal work of the forces equals
    // the kinetic energy change up to sum (F'^2 - F^2) dt^2 / (8 m), which telescopes to zero
    // because the force is zero at touch and after separation. The audit therefore closes to
    // round-off at every dt and cannot measure Verlet's error; Verlet's energy accuracy is
    // checked directly by the elastic test above.
    for dt_factor in [0.1, 0.01] {
        let scene = Scene {
            gamma: 0.33,
            mu: 0.5,
            integrator: Integrator::Verlet,
            dt_factor,
            ..Scene::default()
        };
        let rec = run(&scene, &at(45.0, 0.0));
        assert!(
            rec.energy_residual.abs() < 1e-12,
            "{:e}",
            rec.energy_residual
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Rigid-body limits: sliding throughout, or ending in rolling.

/// docs/model.md, section 10: the impact slides throughout iff mu (1 + e_N) v_N < kappa / (1 + kappa) |v_cp|.
fn slides_throughout(mu: f64, e_n: f64, init: &Initial, kappa: f64) -> bool {
    let v_cp = init.vx + R * init.omega;
    mu * (1.0 + e_n) * init.vy.abs() < kappa / (1.0 + kappa) * v_cp.abs()
}

#[test]
fn sliding_regime_follows_the_study_eq2() {
    for inertia in [InertiaModel::Shape, InertiaModel::Sphere] {
        for integrator in BOTH {
            let scene = Scene {
                mu: 0.1,
                inertia,
                integrator,
                ..Scene::default()
            };
            for theta in [5.0_f64, 10.0, 20.0, 30.0] {
                let init = at(theta, 0.0);
                let (rec, trace) = simulate_with_trace(&scene, &init).unwrap();
                let what = format!("{inertia:?} {integrator:?} theta {theta}");
                assert!(
                    slides_throughout(0.1, rec.e_n, &init, kappa(inertia)),
                    "{what}: not in the sliding regime"
                );
                // It does slide at every step with a tangential force (code 2), never sticks.
                assert!(trace.stick.iter().all(|&s| s != 1), "{what}: a step stuck");
                let expected = 1.0 - 0.1 * (1.0 + rec.e_n) * theta.to_radians().tan();
                let e_t = rec.e_t.unwrap();
                assert!(
                    (e_t / expected - 1.0).abs() < 0.01,
                    "{what}: e_t {e_t} vs {expected}"
                );
                // Stronger, and why: while sliding F_t = -mu F_n at every step and both
                // integrators update velocities linearly in the force, so
                // dvx = -mu dvy holds to round-off, with any inertia.
                assert!(
                    (e_t / expected - 1.0).abs() < 1e-9,
                    "{what}: e_t {e_t} vs {expected}"
                );
            }
        }
    }
}

#[test]
fn rolling_regime_follows_rigid_body_theory() {
    // omega_in: none, +-50 deg/s (the study's range) and +-5 rad/s (|r omega| up to 1.4 v).
    let omegas = [0.0, 50f64.to_radians(), -50f64.to_radians(), 5.0, -5.0];
    for inertia in [InertiaModel::Shape, InertiaModel::Sphere] {
        let k = kappa(inertia);
        let scene = Scene {
            mu: 1.0,
            inertia,
            ..Scene::default()
        };
        for theta in [60.0_f64, 70.0, 80.0, 85.0] {
            for omega in omegas {
                let init = at(theta, omega);
                let rec = run(&scene, &init);
                let what = format!("{inertia:?} theta {theta} omega {omega}");
                assert!(
                    !slides_throughout(1.0, rec.e_n, &init, k),
                    "{what}: not in the rolling regime"
                );
                let v_t = init.vx;
                let v_cp_in = init.vx + R * omega;
                let e_t = rec.e_t.unwrap();
                let expected = 1.0 / (1.0 + k) - k * R * omega / ((1.0 + k) * v_t);
                // The contact point ends nearly at rest: the micro-slip oscillation left at
                // separation (docs/model.md, section 5: +-1.3 % of e_T with gamma_t = 0.5) is a few percent
                // of the incoming slip.
                let v_cp_out = rec.vx_out + R * rec.omega_out;
                assert!(
                    v_cp_out.abs() < 0.03 * v_cp_in.abs(),
                    "{what}: contact point {v_cp_out:e} vs {v_cp_in:e}"
                );
                // Impulse balance: e_T - rolling value = kappa/(1+kappa) v_cp_out / v_T (plus
                // the arm being r minus the overlap depth), so its tolerance scales with the
                // incoming slip relative to v_T.
                let tol = (k / (1.0 + k) * 0.03 + 0.01) * v_cp_in.abs() / v_t;
                assert!(
                    (e_t - expected).abs() < tol,
                    "{what}: e_t {e_t} vs {expected} (tol {tol:e})"
                );
                if omega == 0.0 {
                    let roll = 1.0 / (1.0 + k);
                    assert!(
                        (e_t / roll - 1.0).abs() < 0.03,
                        "{what}: e_t {e_t} vs {roll}"
                    );
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Linear spring-dashpot, head-on, mu = 0.

/// Unclipped restitution of the linear spring-dashpot (docs/model.md, section 4.3).
fn e_unclipped(zeta: f64) -> f64 {
    (-PI * zeta / (1.0 - zeta * zeta).sqrt()).exp()
}

/// With the clip the contact ends when kn delta + cn delta' = 0 (afterwards the force would
/// pull, stays clipped, and the body flies off). For delta = (v/w_d) e^{-zeta w t} sin(w_d t)
/// that happens at w_d t = pi - 2 asin(zeta), where |delta'| = v e^{-zeta w t} exactly, so
/// e_N = exp(-zeta (pi - 2 asin zeta) / sqrt(1 - zeta^2)) (derived from the equations of
/// motion; it is Schwager & Poeschel's 2007 result for zeta < 1).
fn e_clipped(zeta: f64) -> f64 {
    (-zeta * (PI - 2.0 * zeta.asin()) / (1.0 - zeta * zeta).sqrt()).exp()
}

#[test]
fn linear_law_unclipped_formula_is_a_lower_bound_and_the_limit() {
    let zetas = [0.003, 0.01, 0.03, 0.1, 0.3, 0.5, 0.7, 0.9];
    let mut last = 1.0;
    for zeta in zetas {
        let e = |dt_factor: f64| {
            let scene = Scene {
                mu: 0.0,
                normal_law: linear_law(1e7, zeta),
                dt_factor,
                ..Scene::default()
            };
            run(&scene, &at(90.0, 0.0)).e_n
        };
        let (coarse, fine) = (e(0.002), e(0.001));
        let (lower, clipped) = (e_unclipped(zeta), e_clipped(zeta));
        eprintln!(
            "linear law zeta {zeta}: e_n {fine:.6} (dt 0.001), clipped theory {clipped:.6}, unclipped {lower:.6}"
        );
        // The clip only removes pulling forces, so it can only raise e_N.
        assert!(fine > lower && fine < 1.0, "zeta {zeta}: {fine} vs {lower}");
        assert!(fine < last, "e_N must fall as zeta grows");
        last = fine;
        // The measured e_N converges (first order: the clip switches the force off between
        // steps) to the clipped theory.
        let (err_c, err_f) = ((coarse - clipped).abs(), (fine - clipped).abs());
        assert!(err_f < 5e-4, "zeta {zeta}: e_n {fine} vs clipped {clipped}");
        assert!(
            err_f < err_c || err_f < 1e-6,
            "zeta {zeta}: {err_c:e} -> {err_f:e}"
        );
        // For zeta -> 0 the clip matters only at order zeta^2 (e_clip/e_unclip = 1 + 2 zeta^2
        // + ...), while 1 - e_N is of order zeta: the unclipped formula is the limit.
        if zeta <= 0.03 {
            assert!(
                fine - lower < 3.0 * zeta * zeta,
                "zeta {zeta}: {}",
                fine - lower
            );
            assert!(fine - lower < 0.1 * (1.0 - lower), "zeta {zeta}");
        }
    }
}

/// The linear law's loss split between its dashpot and its spring: the clip (see `e_clipped`)
/// switches the force off at depth delta_c = (c_n / k_n) |delta'| = (2 zeta / w) v e_N, so the
/// spring keeps 1/2 k_n delta_c^2 = 4 zeta^2 e_N^2 E_in, which the elastic force's work,
/// `work_normal - work_damping`, loses; the dashpot's work is the rest of the loss,
/// (e_N^2 - 1 + 4 zeta^2 e_N^2) E_in. The reference and the adaptive path locate the clip (to
/// their tolerance); the fixed steps step over it (first order, like e_N).
#[test]
fn linear_law_loss_splits_between_the_dashpot_and_the_clipped_spring() {
    for zeta in [0.1, 0.3, 0.5, 0.7] {
        let e = e_clipped(zeta);
        let elastic = -4.0 * zeta * zeta * e * e;
        let damping = e * e - 1.0 + 4.0 * zeta * zeta * e * e;
        for (integrator, tol, allowed) in [
            (Integrator::Reference, 1e-12, 1e-9),
            (Integrator::Adaptive, 1e-6, 1e-5),
        ] {
            let scene = Scene {
                mu: 0.0,
                normal_law: linear_law(1e7, zeta),
                integrator,
                tol,
                ..Scene::default()
            };
            let rec = run(&scene, &at(90.0, 0.0));
            let w_d = rec.work_damping / rec.energy_in;
            let w_el = rec.work_normal / rec.energy_in - w_d;
            assert!(
                (w_el - elastic).abs() < allowed && (w_d - damping).abs() < allowed,
                "zeta {zeta}, {integrator:?}: elastic {w_el} vs {elastic}, dashpot {w_d} vs {damping}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Convergence with dt, and Gear-5/Verlet agreement.

#[test]
fn mirror_image_gives_the_mirrored_record_bit_for_bit() {
    // For the exact disc the overlap centroid and chord midpoint lie exactly below the centre
    // (cx = x_mid = 0.0), so every operation on x-quantities is a product or sum of negated
    // numbers; IEEE negation is exact and rounding is symmetric in sign, hence the mirrored
    // run is the exact negative in x and omega, and everything else is identical, bit for
    // bit. Only the rebound angle goes through atan2 and 180 - angle, so it is equal to
    // rounding (1e-12 deg).
    let scenes = [
        Scene::default(),
        Scene {
            mu: 0.1,
            ..Scene::default()
        },
        Scene {
            mu: 1.0,
            gamma_t: 0.0,
            ..Scene::default()
        },
        Scene {
            mu: 1.0,
            inertia: InertiaModel::Sphere,
            ..Scene::default()
        },
        Scene {
            mu: 0.5,
            normal_law: linear_law(1e7, 0.1),
            ..Scene::default()
        },
    ];
    for integrator in BOTH {
        for scene in &scenes {
            let scene = Scene {
                integrator,
                ..scene.clone()
            };
            for (theta, omega) in [
                (30.0, 0.0),
                (70.0, 3.0),
                (20.0, -2.0),
                (85.0, 50f64.to_radians()),
            ] {
                let a = at(theta, omega);
                let b = Initial {
                    vx: -a.vx,
                    omega: -a.omega,
                    ..a
                };
                let (ra, rb) = (run(&scene, &a), run(&scene, &b));
                let what = format!("{scene:?} theta {theta} omega {omega}");
                assert_eq!(ra.e_n.to_bits(), rb.e_n.to_bits(), "{what}");
                assert_eq!(ra.e_t, rb.e_t, "{what}");
                assert_eq!(ra.e_kin, rb.e_kin, "{what}");
                assert_eq!(ra.beta, rb.beta, "{what}");
                assert_eq!(ra.omega_out, -rb.omega_out, "{what}");
                assert_eq!(ra.vx_out, -rb.vx_out, "{what}");
                assert_eq!(ra.vy_out, rb.vy_out, "{what}");
                for (x, y) in [
                    (ra.energy_in, rb.energy_in),
                    (ra.energy_out, rb.energy_out),
                    (ra.work_normal, rb.work_normal),
                    (ra.work_friction, rb.work_friction),
                    (ra.energy_residual, rb.energy_residual),
                    (ra.contact_time, rb.contact_time),
                    (ra.max_depth, rb.max_depth),
                ] {
                    assert_eq!(x.to_bits(), y.to_bits(), "{what}");
                }
                assert_eq!(
                    (ra.steps, ra.slip_events),
                    (rb.steps, rb.slip_events),
                    "{what}"
                );
                let mirrored = 180.0 - rb.rebound_angle_deg;
                assert!(
                    (ra.rebound_angle_deg - mirrored).abs() < 1e-12,
                    "{what}: {} vs {mirrored}",
                    ra.rebound_angle_deg
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Time-out and bad input.

#[test]
fn overdamped_creep_times_out_instead_of_hanging() {
    // Strong damping makes the exit a creep: the elastic force is balanced by damping, the
    // depth relaxes on the time gamma t_ref, so the contact time grows in proportion to
    // gamma (checked below) while the budget, 100 contact times estimated without damping,
    // does not. At gamma = 2000 the contact cannot end within the budget.
    // Each at its own dt bound (0.0013 at gamma = 100; it falls as 1 / gamma).
    let at_bound = |gamma: f64| {
        let scene = Scene {
            gamma,
            ..Scene::default()
        };
        Scene {
            dt_factor: restitution_core::max_dt_factor(&scene).unwrap(),
            ..scene
        }
    };
    let contact = |gamma: f64| run(&at_bound(gamma), &at(60.0, 0.0));
    let (r100, r1000) = (contact(100.0), contact(1000.0));
    assert!(r100.separated && r1000.separated && !r1000.timed_out);
    let ratio = r1000.contact_time / r100.contact_time;
    assert!((8.0..12.0).contains(&ratio), "contact time ratio {ratio}");

    let scene = at_bound(2000.0);
    let init = at(60.0, 0.0);
    let rec = run(&scene, &init);
    assert!(rec.timed_out && !rec.separated);
    for x in [
        rec.e_n,
        rec.e_kin,
        rec.omega_out,
        rec.vx_out,
        rec.vy_out,
        rec.contact_time,
        rec.max_depth,
        rec.energy_out,
        rec.work_normal,
        rec.work_friction,
        rec.energy_residual,
    ] {
        assert!(x.is_finite());
    }
    assert!(rec.energy_out <= rec.energy_in);
    // The budget is 100 estimated contact times pi depth / |v_y| of contact: the contact
    // stops at the first step past it, well within the step budget.
    let model = Model::new(&scene).unwrap();
    let t_est = PI * estimate_max_depth(&model, &init).unwrap() / init.vy.abs();
    assert_eq!(rec.stop, restitution_core::StopReason::ContactTimeBudget);
    assert!(
        rec.contact_time > 100.0 * t_est,
        "{}",
        rec.contact_time / t_est
    );
    assert!(rec.contact_time <= 100.0 * t_est + model.dt);
    assert_eq!(rec.steps, (100.0 * t_est / model.dt).floor() as u64 + 1);
    assert!(rec.steps < rec.step_budget);
}

/// The estimated largest depth (the energy balance without damping, solved by Newton's method
/// in log depth) against its closed forms, from tiny to fast impacts: a linear spring,
/// delta = v sqrt(m / k_n); Hertz, delta = (5 m v^2 / (4 k))^(2/5); and on the area law the
/// first moment of the exact disc's segment about the plate, the integral of its area over the
/// depth
/// (so E / L times it equals the normal kinetic energy).
#[test]
fn estimated_depth_solves_the_energy_balance_in_closed_form() {
    let r = 0.01;
    for v in [1e-6, 1e-3, 0.0357, 1.0] {
        let init = Initial::from_angle(v, 90.0, 0.0, 0.0);
        let linear = Scene {
            normal_law: NormalLaw::Linear { kn: 1e5, cn: 0.0 },
            ..Scene::default()
        };
        let model = Model::new(&linear).unwrap();
        let got = estimate_max_depth(&model, &init).unwrap();
        let want = v * (model.mass / 1e5).sqrt();
        assert!(
            (got / want - 1.0).abs() < 1e-12,
            "linear v {v}: {got:e} vs {want:e}"
        );

        let hertz = Scene {
            shape: Shape::sphere(r).unwrap(),
            normal_law: NormalLaw::Hertz {
                nu: 0.3,
                plate: None,
                cor: 1.0,
            },
            ..Scene::default()
        };
        let model = Model::new(&hertz).unwrap();
        let got = estimate_max_depth(&model, &init).unwrap();
        let k = model.hertz.unwrap().k;
        let want = (1.25 * model.mass * v * v / k).powf(0.4);
        assert!(
            (got / want - 1.0).abs() < 1e-12,
            "hertz v {v}: {got:e} vs {want:e}"
        );

        let model = Model::new(&Scene::default()).unwrap();
        let d = estimate_max_depth(&model, &init).unwrap();
        let potential = Scene::default().e_modulus * segment_moment(r, d) / model.length;
        let ke = 0.5 * model.mass * v * v;
        assert!(
            (potential / ke - 1.0).abs() < 1e-6,
            "area v {v}: {potential:e} vs {ke:e}"
        );
    }
}

/// First moment about the plate of a circular segment of depth `d` (radius `r`): the integral
/// of the segment's area A(s) = r^2 (x - sin x) / 2, x = 4 asin(sqrt(s / 2r)), over s in [0, d],
/// with x - sin x by its series where it cancels, and s = d w^2 so that the integrand is
/// smooth (composite Simpson, 2000 intervals: ~1e-14 relative).
fn segment_moment(r: f64, d: f64) -> f64 {
    let x_minus_sin = |x: f64| {
        if x < 0.1 {
            let x2 = x * x;
            x * x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0)))
        } else {
            x - x.sin()
        }
    };
    let area = |s: f64| 0.5 * r * r * x_minus_sin(4.0 * (s / (2.0 * r)).sqrt().asin());
    let f = |w: f64| 2.0 * d * w * area(d * w * w);
    let n = 2000;
    let h = 1.0 / n as f64;
    let inner: f64 = (1..n)
        .map(|k| if k % 2 == 1 { 4.0 } else { 2.0 } * f(k as f64 * h))
        .sum();
    h / 3.0 * (f(0.0) + inner + f(1.0))
}
