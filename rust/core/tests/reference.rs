//! The reference integrator (adaptive Dormand-Prince with located events) against analytic
//! limits, against itself at tighter tolerance, and as the limit that Gear-5 and Verlet
//! converge to as dt shrinks.

use restitution_core::{
    simulate, simulate_reference, simulate_reference_with_trace, Initial, Integrator, Model,
    NormalLaw, Record, ReferenceOptions, Scene, Shape,
};

const V: f64 = 0.0357;
const R: f64 = 0.01;

fn opts(tol: f64) -> ReferenceOptions {
    ReferenceOptions {
        tol,
        max_step_factor: Some(1.0),
    }
}

fn reference(scene: &Scene, init: &Initial) -> Record {
    simulate_reference(scene, init, &opts(1e-12)).expect("valid scene")
}

fn sci(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.2e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn gon(n: usize) -> Shape {
    Shape::regular_polygon(0.01, n).expect("valid polygon")
}

/// Largest difference of the outgoing velocities, in units of the impact speed (spin times r).
fn velocity_error(a: &Record, b: &Record) -> f64 {
    let (sv, r) = (V, 0.01);
    ((a.vx_out - b.vx_out).abs() / sv)
        .max((a.vy_out - b.vy_out).abs() / sv)
        .max((a.omega_out - b.omega_out).abs() * r / sv)
}

/// Scenes that exercise every kind of switch: touch and separation, the clip, stick and slip,
/// corners crossing the plate, re-contacts of a spinning polygon, the linear law.
fn hard_cases() -> Vec<(&'static str, Scene, Initial)> {
    let paper = Scene::default();
    vec![
        (
            "disc elastic frictionless",
            Scene {
                mu: 0.0,
                gamma: 0.0,
                ..paper.clone()
            },
            Initial::from_angle(V, 30.0, 0.0, 0.0),
        ),
        (
            "disc paper mu 0.5, 45 deg (slip then stick)",
            paper.clone(),
            Initial::from_angle(V, 45.0, 0.0, 0.0),
        ),
        (
            "disc mu 1, back-spin, 70 deg",
            Scene {
                mu: 1.0,
                ..paper.clone()
            },
            Initial::from_angle(V, 70.0, 3.0, 0.0),
        ),
        (
            "30-gon mu 0.1, 20 deg",
            Scene {
                shape: gon(30),
                mu: 0.1,
                ..paper.clone()
            },
            Initial::from_angle(V, 20.0, 0.0, 7.0),
        ),
        (
            "12-gon linear law, mu 1, 85 deg, spin",
            Scene {
                shape: gon(12),
                mu: 1.0,
                gamma: 1.0,
                gamma_t: 0.0,
                normal_law: NormalLaw::Linear { kn: 1e7, cn: 30.0 },
                ..paper.clone()
            },
            Initial::from_angle(V, 85.1, 8.15, 277.2),
        ),
        (
            "triangle mu 100, gamma 0, 77 deg (stick with corner switches)",
            Scene {
                shape: gon(3),
                mu: 100.0,
                gamma: 0.0,
                gamma_t: 0.0,
                ..paper.clone()
            },
            Initial::from_angle(V, 77.4, 0.88, 251.2),
        ),
        (
            "30-gon spinning, two contacts",
            Scene {
                shape: gon(30),
                mu: 0.1,
                gamma: 1.0,
                gamma_t: 0.0,
                ..paper
            },
            Initial::from_angle(V, 9.9, -3.77, 50.3),
        ),
    ]
}

#[test]
fn gear5_and_verlet_converge_to_the_reference() {
    for (name, scene, init) in hard_cases() {
        let r = reference(&scene, &init);
        for integrator in [Integrator::Gear5, Integrator::Verlet] {
            let linear_polygon = matches!(scene.normal_law, NormalLaw::Linear { .. })
                && matches!(scene.shape, Shape::Polygon(_));
            if integrator == Integrator::Verlet && linear_polygon {
                // Refused up front (it cannot locate the corner forces' jumps).
                let refused = Model::new(&Scene {
                    integrator,
                    ..scene.clone()
                });
                assert!(refused.is_err_and(|e| e.to_string().contains("`integrator`")));
                continue;
            }
            let errors: Vec<f64> = [0.006, 0.0015, 0.000375]
                .iter()
                .map(|&dt_factor| {
                    let s = Scene {
                        integrator,
                        dt_factor,
                        ..scene.clone()
                    };
                    velocity_error(&simulate(&s, &init).expect("valid"), &r)
                })
                .collect();
            let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log(4.0)).collect();
            println!(
                "{name}, {integrator:?}: errors {}, orders {orders:.2?}",
                sci(&errors)
            );
            // Each 4-fold refinement must gain at least a factor 3 (order >= 0.8, the first
            // order that friction switches allow), down to a small error.
            for w in errors.windows(2) {
                assert!(
                    w[1] < w[0] / 3.0 || w[1] < 1e-10,
                    "{name}, {integrator:?}: no convergence to the reference: {}",
                    sci(&errors)
                );
            }
            // Worst at dt_factor 3.75e-4: the spinning 12-gon on the linear law (4e-4).
            assert!(errors[2] < 1e-3, "{name}, {integrator:?}: {}", sci(&errors));
        }
    }
}

#[test]
fn tightening_the_tolerance_changes_little() {
    for (name, scene, init) in hard_cases() {
        let loose = simulate_reference(&scene, &init, &opts(1e-10)).unwrap();
        let tight = simulate_reference(&scene, &init, &opts(1e-12)).unwrap();
        let tighter = simulate_reference(&scene, &init, &opts(1e-13)).unwrap();
        let (d_loose, d_tight) = (
            velocity_error(&loose, &tighter),
            velocity_error(&tight, &tighter),
        );
        println!("{name}: |1e-10 - 1e-13| = {d_loose:.1e}, |1e-12 - 1e-13| = {d_tight:.1e}");
        assert!(d_loose < 1e-8, "{name}: {d_loose:e}");
        assert!(d_tight < 1e-10, "{name}: {d_tight:e}");
        // The default step limit (the scene's dt_factor) gives the same answer.
        let default = simulate_reference(&scene, &init, &ReferenceOptions::default()).unwrap();
        assert!(velocity_error(&default, &tighter) < 1e-10, "{name}");
    }
}

#[test]
fn energy_is_conserved_without_friction_and_damping() {
    for shape in [Shape::disc(0.01).unwrap(), gon(12), gon(120), gon(3)] {
        for theta in [5.0, 30.0, 60.0, 90.0] {
            let scene = Scene {
                shape: shape.clone(),
                mu: 0.0,
                gamma: 0.0,
                ..Scene::default()
            };
            let r = reference(&scene, &Initial::from_angle(V, theta, 1.0, 10.0));
            let gain = r.energy_out / r.energy_in - 1.0;
            assert!(
                gain.abs() < 1e-10,
                "{shape:?} theta {theta}: energy ratio - 1 = {gain:e}"
            );
            assert!(r.energy_residual.abs() < 1e-11, "{}", r.energy_residual);
            assert_eq!(r.work_friction, 0.0);
            assert!(r.separated && !r.timed_out);
        }
    }
}

#[test]
fn sliding_impact_follows_the_coulomb_impulse() {
    // Sliding throughout, F_t = -mu F_n at every instant, so e_T = 1 - mu (1 + e_N) tan(theta)
    // exactly in continuous time (the study's Eq. 2, with the measured e_N).
    for (mu, theta) in [(0.1, 10.0), (0.05, 30.0), (0.3, 5.0)] {
        let scene = Scene {
            mu,
            ..Scene::default()
        };
        let r = reference(&scene, &Initial::from_angle(V, theta, 0.0, 0.0));
        let expected = 1.0 - mu * (1.0 + r.e_n) * theta.to_radians().tan();
        let e_t = r.e_t.unwrap();
        assert!(
            (e_t - expected).abs() < 1e-10,
            "mu {mu}, theta {theta}: e_t {e_t} vs {expected}"
        );
        assert_eq!(r.slip_events, 0);
    }
}

#[test]
fn undamped_linear_spring_is_a_half_period() {
    // F = kn delta on a disc: contact time pi sqrt(m / kn), depth v_n sqrt(m / kn), e_n = 1.
    let kn = 2e6;
    let scene = Scene {
        mu: 0.0,
        normal_law: NormalLaw::Linear { kn, cn: 0.0 },
        ..Scene::default()
    };
    let m = 2500.0 * std::f64::consts::PI * 1e-4;
    let w = (m / kn).sqrt();
    let init = Initial::from_angle(V, 50.0, 0.0, 0.0);
    let r = reference(&scene, &init);
    let t_c = std::f64::consts::PI * w;
    assert!(
        (r.contact_time / t_c - 1.0).abs() < 1e-10,
        "{} vs {t_c}",
        r.contact_time
    );
    let depth = init.vy.abs() * w;
    assert!(
        (r.max_depth / depth - 1.0).abs() < 1e-9,
        "{} vs {depth}",
        r.max_depth
    );
    assert!((r.e_n - 1.0).abs() < 1e-10, "{}", r.e_n);
}

#[test]
fn mirror_image_gives_the_mirror_result() {
    // x -> -x: vx and spin change sign; a regular polygon at phi0 becomes one at pi - phi0.
    let cases = [
        (Shape::disc(0.01).unwrap(), 0.0),
        (gon(7), 0.3),
        (gon(30), 1.1),
    ];
    for (shape, phi0) in cases {
        let scene = Scene {
            shape: shape.clone(),
            mu: 0.7,
            ..Scene::default()
        };
        let init = Initial {
            vx: 0.02,
            vy: -0.03,
            omega: 2.0,
            phi0,
            ..Initial::default()
        };
        let mirror = Initial {
            vx: -init.vx,
            omega: -init.omega,
            phi0: std::f64::consts::PI - phi0,
            ..init
        };
        let (a, b) = (reference(&scene, &init), reference(&scene, &mirror));
        let tol = 1e-10 * V;
        assert!((a.vy_out - b.vy_out).abs() < tol, "{shape:?}");
        assert!((a.vx_out + b.vx_out).abs() < tol, "{shape:?}");
        assert!((a.omega_out + b.omega_out).abs() * 0.01 < tol, "{shape:?}");
    }
}

#[test]
fn record_and_trace_agree_with_the_fixed_step_integrators() {
    let scene = Scene {
        shape: gon(30),
        ..Scene::default()
    };
    let init = Initial::from_angle(V, 40.0, -1.0, 3.0);
    let (r, tr) = simulate_reference_with_trace(&scene, &init, &opts(1e-12)).unwrap();
    let g = simulate(
        &Scene {
            dt_factor: 0.0005,
            ..scene.clone()
        },
        &init,
    )
    .unwrap();
    assert_eq!(tr.t.len() as u64, r.steps + 1);
    assert!(tr.t.windows(2).all(|w| w[1] > w[0]));
    assert_eq!(*tr.vx.last().unwrap(), r.vx_out);
    assert_eq!(r.contacts, g.contacts);
    for (what, a, b, tol) in [
        ("contact_time", r.contact_time, g.contact_time, 1e-4),
        ("max_depth", r.max_depth, g.max_depth, 1e-6),
        ("max_area", r.max_area, g.max_area, 1e-6),
        ("work_normal", r.work_normal, g.work_normal, 1e-4),
        ("work_friction", r.work_friction, g.work_friction, 1e-3),
    ] {
        assert!((a / b - 1.0).abs() < tol, "{what}: {a} vs {b}");
    }
    assert!(r.work_normal < 0.0 && r.work_friction < 0.0);
    // The trace's forces: never a pulling plate, friction within the cone. (At first touch
    // the corner sits on the plate up to rounding, and the held overlap may be -1e-17 N/m.)
    let f_max = tr.f_n.iter().fold(0.0f64, |a, &b| a.max(b));
    for (f_n, f_t) in tr.f_n.iter().zip(&tr.f_t) {
        assert!(*f_n >= -1e-15 * f_max, "{f_n}");
        assert!(f_t.abs() <= scene.mu * f_n.abs() * (1.0 + 1e-12) + 1e-15 * f_max);
    }
}

fn reference_scene(gamma: f64, mu: f64, gamma_t: f64, dtf: f64) -> Scene {
    Scene {
        shape: Shape::regular_polygon(R, 120).unwrap(),
        gamma,
        mu,
        gamma_t,
        dt_factor: dtf,
        integrator: Integrator::Reference,
        ..Scene::default()
    }
}

/// Without friction the only force is F_n >= 0 along +y: v_y can never decrease, at any
/// step, in the clipped tail included (the case: 120-gon, theta 10, gamma 0.1,
/// omega_in -50 deg/s, largest step 0.2 t_ref, where v_y fell by 1.4e-8 m/s after the clip).
#[test]
fn reference_plate_never_pulls_in_the_clipped_tail() {
    use restitution_core::{simulate_reference_with_trace, ReferenceOptions};
    let mut worst: f64 = 0.0;
    for dtf in [0.2, 1.0] {
        for k in 0..40 {
            let phi0 = 0.075 * k as f64;
            for (theta, om_deg) in [(10.0, -50.0f64), (30.0, 50.0), (70.0, -20.0)] {
                let scene = reference_scene(0.10, 0.0, 0.0, dtf);
                let init = Initial::from_angle(V, theta, om_deg.to_radians(), phi0);
                let opts = ReferenceOptions::default();
                let (_, tr) = simulate_reference_with_trace(&scene, &init, &opts).unwrap();
                for w in tr.vy.windows(2) {
                    worst = worst.max(w[0] - w[1]);
                }
            }
        }
    }
    // Round-off of v_y (~0.03 m/s) only.
    assert!(
        worst <= 1e-15,
        "v_y fell by {worst:e} m/s: the plate pulled"
    );
}

/// Once no corner is below the plate and every point of the body moves away (v_y > r |omega|)
/// nothing can touch it again: the velocities stay as they are (the case: 120-gon,
/// gamma 0.33, mu 0.1, gamma_t 0.5, omega_in +50 deg/s, where one more step found a sliver
/// and applied f_n = mu^-1 f_t ~ 1e-2 N/m).
#[test]
fn reference_applies_no_force_after_separation() {
    use restitution_core::{simulate_reference_with_trace, ReferenceOptions};
    let mut bad = Vec::new();
    for dtf in [0.2, 1.0] {
        for k in 0..100 {
            let phi0 = 0.03 * k as f64;
            for theta in [50.0, 70.0] {
                let scene = reference_scene(0.33, 0.1, 0.5, dtf);
                let init = Initial::from_angle(V, theta, 50f64.to_radians(), phi0);
                let opts = ReferenceOptions::default();
                let (_, tr) = simulate_reference_with_trace(&scene, &init, &opts).unwrap();
                let n = tr.t.len();
                let gone = (1..n).find(|&i| tr.depth[i] <= 0.0 && tr.vy[i] > R * tr.omega[i].abs());
                if let Some(g) = gone {
                    let moved = (g + 1..n).any(|j| {
                        tr.vx[j] != tr.vx[g] || tr.vy[j] != tr.vy[g] || tr.omega[j] != tr.omega[g]
                    });
                    if moved {
                        bad.push((dtf, phi0, theta));
                    }
                }
            }
        }
    }
    assert!(
        bad.is_empty(),
        "a force after separation in {} cases, e.g. {:?}",
        bad.len(),
        bad.first()
    );
}

// ---------------------------------------------------------------------------------------------
// The matrix
