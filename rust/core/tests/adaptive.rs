//! The adaptive integrator at a requested tolerance (`Integrator::Adaptive`, `Scene::tol`):
//! the tolerance honoured, the records' own error estimate (`err_est`) honest and useful, and
//! the error control dimensionless. Every error is measured against a tight reference run
//! (`simulate_reference` at tol 1e-13, largest step 0.2), never against values from the code.
//!
//! The full grid (theta 4 ... 89 every 5 degrees, mu 0 ... 1 in steps of 0.1, three shapes,
//! three spins, two tangential dampings, four tolerances) runs behind `--ignored`:
//! `cargo test --release --test adaptive -- --ignored --nocapture`.

use restitution_core::{
    simulate, simulate_reference, Initial, Integrator, Record, ReferenceOptions, Scene, Shape,
};

const V: f64 = 0.0357;
const R: f64 = 0.01;

fn shapes() -> Vec<(&'static str, Shape)> {
    vec![
        ("disc", Shape::disc(R).unwrap()),
        ("120-gon", Shape::regular_polygon(R, 120).unwrap()),
        ("12-gon", Shape::regular_polygon(R, 12).unwrap()),
    ]
}

/// One impact of the grid.
#[derive(Clone)]
struct Case {
    what: String,
    scene: Scene,
    init: Initial,
}

fn grid(thetas: &[f64], mus: &[f64]) -> Vec<Case> {
    let mut out = Vec::new();
    for (name, shape) in shapes() {
        for &theta in thetas {
            for &mu in mus {
                for omega_deg in [0.0, 50.0, -50.0] {
                    for gamma_t in [0.0, 0.5] {
                        let scene = Scene {
                            shape: shape.clone(),
                            gamma: 0.33299,
                            mu,
                            gamma_t,
                            ..Scene::default()
                        };
                        let omega = f64::to_radians(omega_deg);
                        out.push(Case {
                            what: format!(
                                "{name} theta {theta} mu {mu} omega {omega_deg} gamma_t {gamma_t}"
                            ),
                            scene,
                            init: Initial::from_angle(V, theta, omega, 0.0),
                        });
                    }
                }
            }
        }
    }
    out
}

fn tight(case: &Case) -> Record {
    let opts = ReferenceOptions {
        tol: 1e-13,
        max_step_factor: Some(0.2),
    };
    simulate_reference(&case.scene, &case.init, &opts).expect("valid scene")
}

fn adaptive(case: &Case, tol: f64, dt_factor: f64) -> Record {
    let scene = Scene {
        integrator: Integrator::Adaptive,
        tol,
        dt_factor,
        ..case.scene.clone()
    };
    simulate(&scene, &case.init).expect("valid scene")
}

/// The true error: the largest absolute difference of e_N, e_T, e_kin and omega_out r / v.
fn error(rec: &Record, reference: &Record, init: &Initial) -> f64 {
    rec.accuracy_distance(reference, R, init.vx.hypot(init.vy))
}

fn quantile(v: &mut [f64], q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

/// Per tolerance and largest step: max error / tol, the share of impacts with err_est >= the
/// error, and the median of err_est / error. Fails on the first tolerance not honoured.
fn survey(cases: &[Case], tols: &[f64], steps: &[f64], print: bool) -> Vec<String> {
    let refs: Vec<Record> = cases.iter().map(tight).collect();
    let mut failures = Vec::new();
    for &dt_factor in steps {
        for &tol in tols {
            let (mut worst, mut worst_what) = (0.0f64, String::new());
            let (mut covered, mut ratios, mut steps_sum) = (0usize, Vec::new(), 0u64);
            for (case, reference) in cases.iter().zip(&refs) {
                let rec = adaptive(case, tol, dt_factor);
                let err = error(&rec, reference, &case.init);
                steps_sum += rec.steps;
                if err > worst {
                    (worst, worst_what) = (err, case.what.clone());
                }
                // An error below the reference's own accuracy cannot be judged.
                let judged = err.max(1e-12);
                covered += usize::from(rec.err_est.unwrap() >= judged);
                if std::env::var("SURVEY_DETAIL").is_ok() && rec.err_est.unwrap() < judged {
                    println!(
                        "    under: {} err {err:.2e} est {:.2e} steps {}",
                        case.what,
                        rec.err_est.unwrap(),
                        rec.steps
                    );
                }
                ratios.push(rec.err_est.unwrap() / judged);
            }
            let share = covered as f64 / cases.len() as f64;
            if std::env::var("SURVEY_DETAIL").is_ok() {
                let mut r = ratios.clone();
                r.sort_by(f64::total_cmp);
                let q: Vec<String> = [0.0, 0.05, 0.1, 0.25, 0.5, 0.75, 0.95, 1.0]
                    .iter()
                    .map(|&p| format!("{:.2e}", r[((r.len() - 1) as f64 * p) as usize]))
                    .collect();
                println!(
                    "  est/err quantiles 0,5,10,25,50,75,95,100%: {}",
                    q.join(" ")
                );
            }
            let median = quantile(&mut ratios, 0.5);
            if print {
                println!(
                    "dt_factor {dt_factor} tol {tol:.0e}: max err {:.2e} = {:.2} tol ({worst_what}), \
                     err_est >= err in {:.1} %, median err_est / err {median:.2}, mean steps {:.1}",
                    worst,
                    worst / tol,
                    100.0 * share,
                    steps_sum as f64 / cases.len() as f64
                );
            }
            if worst > 3.0 * tol {
                failures.push(format!(
                    "dt_factor {dt_factor} tol {tol:e}: max error {worst:e} > 3 tol at {worst_what}"
                ));
            }
            if share < 0.95 || median > 100.0 {
                failures.push(format!(
                    "dt_factor {dt_factor} tol {tol:e}: err_est >= error in {share} of impacts, \
                     median ratio {median}"
                ));
            }
        }
    }
    failures
}

#[test]
fn tolerance_and_error_estimate_hold_on_a_reduced_grid() {
    let cases = grid(&[4.0, 20.0, 45.0, 70.0, 89.0], &[0.0, 0.3, 1.0]);
    let failures = survey(&cases, &[1e-4, 1e-8], &[1.0], true);
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
#[ignore = "the full grid: minutes"]
fn tolerance_and_error_estimate_hold_on_the_full_grid() {
    let thetas: Vec<f64> = (0..18).map(|k| 4.0 + 5.0 * k as f64).collect();
    let mus: Vec<f64> = (0..=10).map(|k| 0.1 * k as f64).collect();
    let cases = grid(&thetas, &mus);
    let failures = survey(&cases, &[1e-4, 1e-6, 1e-8, 1e-10], &[0.2, 1.0, 5.0], true);
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Scaling r, rho, E and v with the dimensionless groups (v sqrt(rho / E), omega r / v,
/// gamma, gamma_t, mu) fixed gives the same dimensionless record: the error control works in
/// the impact's own scales.
#[test]
fn adaptive_records_are_invariant_under_rescaling() {
    for (name, shape) in shapes() {
        for theta in [7.0, 45.0, 80.0] {
            let base = Scene {
                shape: shape.clone(),
                integrator: Integrator::Adaptive,
                tol: 1e-6,
                dt_factor: 1.0,
                ..Scene::default()
            };
            let init = Initial::from_angle(V, theta, 1.0, 0.0);
            let a = simulate(&base, &init).unwrap();
            let (ls, rs, es): (f64, f64, f64) = (1e3, 0.3, 50.0);
            let vs = (es / rs).sqrt();
            let scaled = Scene {
                shape: match &shape {
                    Shape::Disc { .. } => Shape::disc(R * ls).unwrap(),
                    _ => Shape::regular_polygon(R * ls, shape.vertices().len()).unwrap(),
                },
                rho: base.rho * rs,
                e_modulus: base.e_modulus * es,
                ..base.clone()
            };
            let init_s = Initial::from_angle(V * vs, theta, vs / ls, 0.0);
            let b = simulate(&scaled, &init_s).unwrap();
            assert_eq!(a.steps, b.steps, "{name} theta {theta}: steps differ");
            let d = a
                .accuracy_outputs(R, V)
                .iter()
                .zip(b.accuracy_outputs(R * ls, V * vs))
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max);
            assert!(d < 1e-9, "{name} theta {theta}: records differ by {d:e}");
            let rel = (a.err_est.unwrap() / b.err_est.unwrap() - 1.0).abs();
            assert!(
                rel < 1e-6,
                "{name} theta {theta}: err_est differs by {rel:e}"
            );
        }
    }
}

/// Gear-5 and Verlet with `error_estimate`: a second run at half the step bounds the error.
#[test]
fn fixed_step_error_estimate_bounds_the_error() {
    let cases = grid(&[4.0, 30.0, 60.0, 89.0], &[0.0, 0.5]);
    for integrator in [Integrator::Gear5, Integrator::Verlet] {
        let (mut covered, mut ratios) = (0usize, Vec::new());
        for case in cases.iter().filter(|c| c.what.starts_with("disc")) {
            let scene = Scene {
                integrator,
                error_estimate: true,
                ..case.scene.clone()
            };
            let rec = simulate(&scene, &case.init).unwrap();
            let err = error(&rec, &tight(case), &case.init).max(1e-12);
            covered += usize::from(rec.err_est.unwrap() >= err);
            ratios.push(rec.err_est.unwrap() / err);
            let plain = Scene {
                error_estimate: false,
                ..scene
            };
            assert!(simulate(&plain, &case.init).unwrap().err_est.is_none());
        }
        let n = ratios.len();
        let median = quantile(&mut ratios, 0.5);
        println!("{integrator:?}: err_est >= err in {covered} of {n}, median ratio {median:.2}");
        assert!(
            covered as f64 >= 0.95 * n as f64,
            "{integrator:?}: {covered} of {n}"
        );
        assert!(median <= 100.0, "{integrator:?}: median ratio {median}");
    }
}

/// The deepest point of an undamped, frictionless impact without spin is where the normal
/// kinetic energy has all gone into the law's potential (the energy balance `estimate_max_depth`
/// solves), and the largest overlap is the disc's segment at that depth, r^2 acos(1 - d / r)
/// minus (r - d) sqrt(2 r d - d^2): both found inside a step on the adaptive path, at any theta.
/// A 12-gon falling head-on onto a corner does not turn either: its depth follows the same
/// balance.
#[test]
fn largest_depth_and_area_of_an_undamped_disc_follow_the_energy_balance() {
    use restitution_core::{estimate_max_depth, Model};
    for theta in [10.0, 45.0, 90.0] {
        for dt_factor in [0.3, 1.0, 5.0] {
            let scene = Scene {
                gamma: 0.0,
                gamma_t: 0.0,
                mu: 0.0,
                integrator: Integrator::Adaptive,
                tol: 1e-10,
                dt_factor,
                ..Scene::default()
            };
            let init = Initial::from_angle(V, theta, 0.0, 0.0);
            let rec = simulate(&scene, &init).unwrap();
            let d = estimate_max_depth(&Model::new(&scene).unwrap(), &init).unwrap();
            let what = format!("theta {theta} dt_factor {dt_factor}");
            assert!(
                (rec.max_depth / d - 1.0).abs() < 1e-9,
                "{what}: {} vs {d}",
                rec.max_depth
            );
            let area = R * R * (1.0 - d / R).acos() - (R - d) * (2.0 * R * d - d * d).sqrt();
            assert!(
                (rec.max_area / area - 1.0).abs() < 1e-8,
                "{what}: {} vs {area}",
                rec.max_area
            );

            let polygon = Scene {
                shape: Shape::regular_polygon(R, 12).unwrap(),
                ..scene.clone()
            };
            let head_on = Initial::from_angle(V, 90.0, 0.0, 0.0);
            let rec = simulate(&polygon, &head_on).unwrap();
            let d = estimate_max_depth(&Model::new(&polygon).unwrap(), &head_on).unwrap();
            assert!(
                (rec.max_depth / d - 1.0).abs() < 1e-9,
                "12-gon {what}: {} vs {d}",
                rec.max_depth
            );
        }
    }
}

/// Impacts whose short stick or slip phases the adaptive path once lost (each then off by
/// 1e-6 ... 2e-6 at tol 1e-6, against <= 1e-7 elsewhere, or by 1.1e-4 ... 1.5e-4 at tol 1e-4,
/// at a local tolerance of 0.15 tol): the same switches as the tight run, and the error within
/// two local tolerances (1 tol at the local tolerance 0.5 tol: without the grazing search the
/// 120-gon at theta 89 is off by 1.5 tol, and without samples inside the steps the disc at
/// theta 54 by 1.5 tol and the 12-gon by 0.99 tol with a slip phase lost; found, the largest
/// is 0.58 tol). A 120-gon (the study's,
/// gamma 0.33) at theta 65, mu 0.4 whose slip phase of 0.002 t_c lay inside a step that also
/// ended on the next stick -> slip; the disc at theta 84, mu 0.8, gamma_t 0, whose stick phase
/// near separation was lost to round-off in the cone test; a spinning 12-gon at theta 39,
/// mu 0.6, largest step 0.2; two phases that graze the cone between the samples of a step
/// (`grazes` in the adaptive path's events): the disc at theta 54, mu 0.7, gamma_t 0 slips for
/// 0.055 t_ref inside a stick step of 0.54 t_ref, the 120-gon at theta 89, mu 0.7, gamma_t 0
/// for 0.04 t_ref from touch.
#[test]
fn short_stick_and_slip_phases_are_not_lost() {
    let (disc, c120) = (
        Shape::disc(R).unwrap(),
        Shape::regular_polygon(R, 120).unwrap(),
    );
    let c12 = Shape::regular_polygon(R, 12).unwrap();
    // (shape, gamma, theta, mu, omega_in deg, gamma_t, largest step, tol)
    let cases = [
        (c120.clone(), 0.33, 65.0, 0.4, 0.0, 0.5, 1.0, 1e-6),
        (disc.clone(), 0.33299, 84.0, 0.8, 0.0, 0.0, 1.0, 1e-6),
        (c12, 0.33299, 39.0, 0.6, -50.0, 0.0, 0.2, 1e-6),
        (disc, 0.33299, 54.0, 0.7, 0.0, 0.0, 5.0, 1e-4),
        (c120, 0.33299, 89.0, 0.7, 0.0, 0.0, 1.0, 1e-4),
    ];
    for (shape, gamma, theta, mu, omega_deg, gamma_t, dt_factor, tol) in cases {
        let scene = Scene {
            shape,
            gamma,
            mu,
            gamma_t,
            ..Scene::default()
        };
        let case = Case {
            what: format!("theta {theta} mu {mu} tol {tol:e}"),
            init: Initial::from_angle(V, theta, f64::to_radians(omega_deg), 0.0),
            scene,
        };
        let reference = tight(&case);
        let rec = adaptive(&case, tol, dt_factor);
        let err = error(&rec, &reference, &case.init);
        assert_eq!(rec.slip_events, reference.slip_events, "{}", case.what);
        let bound = 2.0 * case.scene.local_tol_per_target() * tol;
        assert!(err <= bound, "{}: error {err:e}", case.what);
    }
}
