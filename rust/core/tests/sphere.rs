//! The Hertz-Mindlin sphere (docs/model.md, section 14) against closed forms: Hertz's maximal
//! overlap, peak force and contact time (Chung & Ooi 2011, Test 2), the calibrated restitution
//! (Test 3), rigid-body theory on the gross-sliding branch of Test 4, and the time-step bound.

use restitution_core::{
    max_dt_factor, simulate, simulate_reference, simulate_with_trace, Initial, Integrator,
    NormalLaw, Record, ReferenceOptions, Scene, Shape, TangentialModel,
};
use std::f64::consts::PI;

mod common;

/// Contact time of an elastic Hertz impact in units of delta_max / v:
/// 2 int_0^1 (1 - x^(5/2))^(-1/2) dx = (4/5) B(2/5, 1/2) (Gamma functions, 16 digits).
const HERTZ_TIME: f64 = 2.943_275_184_324_704_7;

struct Material {
    e: f64,
    nu: f64,
    rho: f64,
}

const AL: Material = Material {
    e: 70e9,
    nu: 0.30,
    rho: 2699.0,
};
const MG: Material = Material {
    e: 40e9,
    nu: 0.35,
    rho: 1800.0,
};
const ALUMINA: Material = Material {
    e: 380e9,
    nu: 0.23,
    rho: 4000.0,
};
const CAST_IRON: Material = Material {
    e: 100e9,
    nu: 0.25,
    rho: 7000.0,
};

fn sphere(mat: &Material, r: f64, cor: f64, mu: f64) -> Scene {
    Scene {
        shape: Shape::sphere(r).unwrap(),
        rho: mat.rho,
        e_modulus: mat.e,
        mu,
        normal_law: NormalLaw::Hertz {
            nu: mat.nu,
            plate: None,
            cor,
        },
        ..Scene::default()
    }
}

fn head_on(v: f64) -> Initial {
    Initial::from_angle(v, 90.0, 0.0, 0.0)
}

fn with(scene: &Scene, integrator: Integrator) -> Scene {
    Scene {
        integrator,
        dt_factor: if integrator == Integrator::Reference {
            1.0
        } else {
            scene.dt_factor
        },
        ..scene.clone()
    }
}

fn run(scene: &Scene, init: &Initial) -> Record {
    if scene.integrator == Integrator::Reference {
        simulate_reference(scene, init, &ReferenceOptions::default()).unwrap()
    } else {
        simulate(scene, init).unwrap()
    }
}

const ALL: [Integrator; 3] = [Integrator::Gear5, Integrator::Verlet, Integrator::Reference];

#[test]
fn mass_and_inertia_are_a_spheres() {
    let scene = sphere(&AL, 0.1, 1.0, 0.0);
    let model = restitution_core::Model::new(&scene).unwrap();
    let m = 4.0 / 3.0 * PI * 0.1f64.powi(3) * 2699.0;
    assert!((model.mass / m - 1.0).abs() < 1e-15);
    assert!((model.inertia / (0.4 * m * 0.01) - 1.0).abs() < 1e-15);
}

/// Chung & Ooi Test 2: elastic normal impact on a rigid plane, closed forms of Hertz theory.
#[test]
fn test2_hertz_overlap_force_and_contact_time() {
    let v = 0.2;
    for mat in [&AL, &MG] {
        let r = 0.1;
        let scene = sphere(mat, r, 1.0, 0.0);
        let m = 4.0 / 3.0 * PI * r * r * r * mat.rho;
        let e_star = mat.e / (1.0 - mat.nu * mat.nu);
        let delta = (15.0 * m * v * v / (16.0 * e_star * r.sqrt())).powf(0.4);
        let force = 4.0 / 3.0 * e_star * r.sqrt() * delta.powf(1.5);
        let time = HERTZ_TIME * delta / v;
        for integ in ALL {
            let s = with(&scene, integ);
            let rec = run(&s, &head_on(v));
            let f_max = if integ == Integrator::Reference {
                f64::NAN
            } else {
                let (_, tr) = simulate_with_trace(&s, &head_on(v)).unwrap();
                tr.f_n.iter().cloned().fold(0.0, f64::max)
            };
            let dev = [
                rec.max_depth / delta - 1.0,
                rec.contact_time / time - 1.0,
                rec.e_n - 1.0,
            ];
            println!(
                "test 2 E={:e} {integ:?}: delta {:.3e}, t_c {:.3e}, e_n {:.3e}, F {:.3e}",
                mat.e,
                dev[0],
                dev[1],
                dev[2],
                f_max / force - 1.0
            );
            for d in dev {
                assert!(d.abs() < 1e-4, "{integ:?}: {dev:?}");
            }
            if f_max.is_finite() {
                assert!(
                    (f_max / force - 1.0).abs() < 1e-4,
                    "{integ:?} F {f_max} vs {force}"
                );
            }
        }
    }
}

/// Chung & Ooi Test 3: the head-on restitution equals the requested cor, at any speed.
#[test]
fn test3_restitution_equals_cor() {
    for mat in [&ALUMINA, &CAST_IRON] {
        for cor in [0.2, 0.4, 0.6, 0.8, 1.0] {
            let scene = sphere(mat, 2.5e-3, cor, 0.0);
            for integ in ALL {
                for v in [0.39, 3.9, 39.0] {
                    let e = run(&with(&scene, integ), &head_on(v)).e_n;
                    assert!(
                        (e - cor).abs() < 1e-3,
                        "E {:e} cor {cor} {integ:?} v {v}: e_n {e}",
                        mat.e
                    );
                }
            }
            // The reference integrator resolves the calibration itself.
            let e = run(&with(&scene, Integrator::Reference), &head_on(3.9)).e_n;
            assert!((e - cor).abs() < 1e-6, "reference cor {cor}: {e}");
        }
    }
}

/// Chung & Ooi Test 4 (alumina, R = 2.5 mm, 3.9 m/s, cor 0.98, mu 0.092): where the contact
/// slides throughout (theta >= 35 deg from the normal) rigid-body theory is exact:
/// e_t = 1 - mu (1 + e) / tan(theta_n), |omega'| = 2.5 mu (1 + e) v cos(theta_n) / R.
#[test]
fn test4_gross_sliding_is_rigid_body_theory() {
    let (r, v, mu) = (2.5e-3, 3.9, 0.092);
    let scene = sphere(&ALUMINA, r, 0.98, mu);
    for tangential in [TangentialModel::Mindlin, TangentialModel::Linear] {
        let scene = Scene {
            tangential,
            kt: Some(1e8),
            ..scene.clone()
        };
        for integ in ALL {
            for theta_n in [35.0f64, 45.0, 60.0, 75.0, 85.0] {
                let init = Initial::from_angle(v, 90.0 - theta_n, 0.0, 0.0);
                let rec = run(&with(&scene, integ), &init);
                let a = mu * (1.0 + rec.e_n);
                let e_t = 1.0 - a / theta_n.to_radians().tan();
                let omega = 2.5 * a * v * theta_n.to_radians().cos() / r;
                let de = rec.e_t.unwrap() / e_t - 1.0;
                let dw = -rec.omega_out / omega - 1.0;
                assert!(
                    de.abs() < 1e-3 && dw.abs() < 1e-3,
                    "{tangential:?} {integ:?} theta_n {theta_n}: e_t {de:e}, omega {dw:e}"
                );
            }
        }
    }
}

/// Energy: never a gain with damping or friction, the audit closes, and an elastic
/// frictionless impact keeps its energy.
#[test]
fn energy_audit_closes() {
    for (cor, mu) in [(1.0, 0.0), (0.5, 0.0), (0.98, 0.092), (0.5, 0.4)] {
        let scene = sphere(&ALUMINA, 2.5e-3, cor, mu);
        for integ in ALL {
            for theta in [10.0, 45.0, 80.0] {
                let rec = run(
                    &with(&scene, integ),
                    &Initial::from_angle(3.9, theta, 0.0, 0.0),
                );
                let s = with(&scene, integ);
                assert_eq!(common::energy_verdict(&s, &rec), None, "{integ:?}");
                assert!(rec.energy_residual.abs() < 1e-6, "{integ:?} {rec:?}");
            }
        }
    }
}

/// The time-step bound holds: at the largest accepted dt_factor every scene, stiff damping
/// and deep impacts included, stays finite, gains no energy, and lands within 2 % of v of
/// the reference.
#[test]
fn stability_bound_holds() {
    for cor in [0.01, 0.3, 1.0] {
        for mu in [0.0, 0.4, 1.0] {
            let base = sphere(&ALUMINA, 2.5e-3, cor, mu);
            for integ in [Integrator::Gear5, Integrator::Verlet] {
                let scene = with(&base, integ);
                let bound = max_dt_factor(&scene).unwrap();
                let scene = Scene {
                    dt_factor: bound,
                    ..scene
                };
                // 3.9 m/s and a deep impact (depth ~ 0.4 r).
                for v in [3.9, 1.5e3] {
                    for theta in [20.0, 60.0, 90.0] {
                        let init = Initial::from_angle(v, theta, 0.0, 0.0);
                        let rec = run(&scene, &init);
                        let reference = run(&with(&base, Integrator::Reference), &init);
                        // Head-on without spin the friction never acts (v_t = 0): judged as
                        // the frictionless scene it is.
                        let judged = Scene {
                            mu: if theta == 90.0 { 0.0 } else { mu },
                            ..scene.clone()
                        };
                        assert_eq!(
                            common::energy_verdict(&judged, &rec),
                            None,
                            "{integ:?} dt {bound} cor {cor} mu {mu} v {v} theta {theta}"
                        );
                        let err = (rec.vx_out - reference.vx_out)
                            .abs()
                            .max((rec.vy_out - reference.vy_out).abs())
                            .max((rec.omega_out - reference.omega_out).abs() * 2.5e-3)
                            / v;
                        assert!(
                            err < 0.02,
                            "{integ:?} dt {bound} cor {cor} mu {mu} v {v} theta {theta}: {err}"
                        );
                    }
                }
            }
        }
    }
}
