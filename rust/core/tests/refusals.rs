//! What the engine refuses, naming the parameter (bad input of every kind), and the integrators'
//! time-step bound on the stiffest scenes it accepts (the bound itself is measured in
//! `stability.rs`).

mod common;

use common::*;
use restitution_core::{
    estimate_max_depth, simulate, Error, InertiaModel, Initial, Integrator, Model, NormalLaw,
    Scene, Shape,
};

#[test]
fn bad_input_is_an_error_naming_the_parameter() {
    let bad_scenes: Vec<(&str, Scene)> = vec![
        (
            "rho",
            Scene {
                rho: f64::NAN,
                ..Scene::default()
            },
        ),
        (
            "rho",
            Scene {
                rho: -1.0,
                ..Scene::default()
            },
        ),
        (
            "rho",
            Scene {
                rho: f64::INFINITY,
                ..Scene::default()
            },
        ),
        (
            "E",
            Scene {
                e_modulus: 0.0,
                ..Scene::default()
            },
        ),
        (
            "E",
            Scene {
                e_modulus: f64::NAN,
                ..Scene::default()
            },
        ),
        (
            "gamma",
            Scene {
                gamma: -0.1,
                ..Scene::default()
            },
        ),
        (
            "gamma",
            Scene {
                gamma: f64::NAN,
                ..Scene::default()
            },
        ),
        (
            "gamma_t",
            Scene {
                gamma_t: -1.0,
                ..Scene::default()
            },
        ),
        (
            "gamma_t",
            Scene {
                gamma_t: f64::INFINITY,
                ..Scene::default()
            },
        ),
        (
            "mu",
            Scene {
                mu: -0.5,
                ..Scene::default()
            },
        ),
        (
            "mu",
            Scene {
                mu: f64::NAN,
                ..Scene::default()
            },
        ),
        (
            "kt",
            Scene {
                kt: Some(-1.0),
                ..Scene::default()
            },
        ),
        (
            "kt",
            Scene {
                kt: Some(f64::NAN),
                ..Scene::default()
            },
        ),
        (
            "dt_factor",
            Scene {
                dt_factor: 0.0,
                ..Scene::default()
            },
        ),
        (
            "dt_factor",
            Scene {
                dt_factor: -0.01,
                ..Scene::default()
            },
        ),
        (
            "dt_factor",
            Scene {
                dt_factor: f64::NAN,
                ..Scene::default()
            },
        ),
        (
            "dt_factor",
            Scene {
                dt_factor: 1.001 * restitution_core::max_dt_factor(&Scene::default()).unwrap(),
                ..Scene::default()
            },
        ),
        (
            "dt_factor",
            Scene {
                integrator: Integrator::Verlet,
                dt_factor: 1.001
                    * restitution_core::max_dt_factor(&Scene {
                        integrator: Integrator::Verlet,
                        ..Scene::default()
                    })
                    .unwrap(),
                ..Scene::default()
            },
        ),
        (
            "r",
            Scene {
                shape: Shape::Disc { r: -0.01 },
                ..Scene::default()
            },
        ),
        (
            "r",
            Scene {
                shape: Shape::Disc { r: f64::NAN },
                ..Scene::default()
            },
        ),
        (
            "kn",
            Scene {
                normal_law: NormalLaw::Linear { kn: -1.0, cn: 0.0 },
                ..Scene::default()
            },
        ),
        (
            "kn",
            Scene {
                normal_law: NormalLaw::Linear {
                    kn: f64::NAN,
                    cn: 0.0,
                },
                ..Scene::default()
            },
        ),
        (
            "cn",
            Scene {
                normal_law: NormalLaw::Linear { kn: 1e7, cn: -1.0 },
                ..Scene::default()
            },
        ),
        (
            "cn",
            Scene {
                normal_law: NormalLaw::Linear {
                    kn: 1e7,
                    cn: f64::INFINITY,
                },
                ..Scene::default()
            },
        ),
    ];
    for (name, scene) in bad_scenes {
        assert_eq!(
            invalid_name(simulate(&scene, &at(30.0, 0.0))),
            name,
            "{scene:?}"
        );
    }
    let ok = at(30.0, 0.0);
    let bad_inits = [
        ("vx", Initial { vx: f64::NAN, ..ok }),
        (
            "vx",
            Initial {
                vx: f64::INFINITY,
                ..ok
            },
        ),
        ("vy", Initial { vy: f64::NAN, ..ok }),
        ("vy", Initial { vy: 0.0, ..ok }),
        ("vy", Initial { vy: 0.01, ..ok }),
        (
            "vy",
            Initial {
                vy: f64::NEG_INFINITY,
                ..ok
            },
        ),
        (
            "omega_in",
            Initial {
                omega: f64::NAN,
                ..ok
            },
        ),
        (
            "omega_in",
            Initial {
                omega: f64::INFINITY,
                ..ok
            },
        ),
        (
            "phi0",
            Initial {
                phi0: f64::NAN,
                ..ok
            },
        ),
    ];
    for (name, init) in bad_inits {
        assert_eq!(
            invalid_name(simulate(&Scene::default(), &init)),
            name,
            "{init:?}"
        );
    }
    // Too fast for the modulus: the undamped depth estimate exceeds r / 2. The error names
    // v and says which modulus to raise.
    for scene in [
        Scene::default(),
        Scene {
            normal_law: linear_law(1e7, 0.0),
            ..Scene::default()
        },
    ] {
        match simulate(&scene, &Initial::from_angle(100.0, 60.0, 0.0, 0.0)) {
            Err(Error::InvalidParameter { name, expected, .. }) => {
                assert_eq!(name, "v");
                let modulus = if scene.normal_law == NormalLaw::Area {
                    "E"
                } else {
                    "kn"
                };
                assert!(expected.contains(modulus), "{expected}");
            }
            other => panic!("expected an error naming v, got {other:?}"),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Time-step stability bound (see `restitution_core::stability`; measured in tests/stability.rs).

/// The stiffest scenes the bound must hold for: head-on and oblique; full stick (mu = 1,
/// gamma_t = 0, also 0.5), disc and sphere inertia; gamma 0, 0.33 and 10; the preset speed and
/// a deep impact (depth about 0.4 r, the stiffest part of the area law); the linear law
/// (kn = E, stiffer than the area law at any depth) with zeta 0, 0.1 and 1.
fn stiff_scenes() -> Vec<(String, Scene, Initial)> {
    let base = Scene::default();
    // 90 % of the largest speed whose undamped depth estimate stays below r / 2.
    let deep = |scene: &Scene| {
        let model = Model::new(scene).unwrap();
        let (mut lo, mut hi) = (V, 1e3 * V);
        while hi / lo > 1.0 + 1e-6 {
            let mid = (lo * hi).sqrt();
            if estimate_max_depth(&model, &Initial::from_angle(mid, 90.0, 0.0, 0.0)).is_ok() {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.9 * lo
    };
    let mut out = Vec::new();
    for (speed, v) in [("preset v", V), ("deep", deep(&base))] {
        for gamma in [0.0, 0.33, 10.0] {
            let area = Scene {
                gamma,
                ..base.clone()
            };
            out.push((
                format!("area head-on {speed} gamma {gamma}"),
                Scene {
                    mu: 0.0,
                    ..area.clone()
                },
                Initial::from_angle(v, 90.0, 0.0, 0.0),
            ));
            for theta in [10.0, 45.0, 80.0] {
                out.push((
                    format!("area stick theta {theta} {speed} gamma {gamma}"),
                    Scene {
                        mu: 1.0,
                        gamma_t: 0.0,
                        ..area.clone()
                    },
                    Initial::from_angle(v, theta, 0.0, 0.0),
                ));
            }
            out.push((
                format!("area stick gamma_t 0.5 {speed} gamma {gamma}"),
                Scene {
                    mu: 1.0,
                    ..area.clone()
                },
                Initial::from_angle(v, 45.0, 0.0, 0.0),
            ));
            out.push((
                format!("area stick sphere {speed} gamma {gamma}"),
                Scene {
                    mu: 1.0,
                    gamma_t: 0.0,
                    inertia: InertiaModel::Sphere,
                    ..area.clone()
                },
                Initial::from_angle(v, 45.0, 0.0, 0.0),
            ));
        }
    }
    let linear = Scene {
        normal_law: linear_law(1e7, 0.0),
        ..base.clone()
    };
    for (speed, v) in [("preset v", V), ("deep", deep(&linear))] {
        for zeta in [0.0, 0.1, 1.0] {
            let lin = Scene {
                normal_law: linear_law(1e7, zeta),
                ..base.clone()
            };
            out.push((
                format!("linear head-on {speed} zeta {zeta}"),
                Scene {
                    mu: 0.0,
                    ..lin.clone()
                },
                Initial::from_angle(v, 90.0, 0.0, 0.0),
            ));
            out.push((
                format!("linear stick {speed} zeta {zeta}"),
                Scene {
                    mu: 1.0,
                    gamma_t: 0.0,
                    ..lin.clone()
                },
                Initial::from_angle(v, 45.0, 0.0, 0.0),
            ));
            out.push((
                format!("linear stick sphere {speed} zeta {zeta}"),
                Scene {
                    mu: 1.0,
                    gamma_t: 0.0,
                    inertia: InertiaModel::Sphere,
                    ..lin.clone()
                },
                Initial::from_angle(v, 45.0, 0.0, 0.0),
            ));
        }
    }
    out
}

/// The stability criterion of the measurement: finite numbers, a completed contact, no energy
/// gain where the scene dissipates (a conservative scene may err either way: |dE| <= 1 %),
/// |energy_residual| <= 1e-2, and results that are still qualitatively right: halving dt
/// changes vx', vy' and r omega' by at most 5 % of v. Returns the reason when unstable.
fn unstable(scene: &Scene, init: &Initial) -> Option<String> {
    let rec = simulate(scene, init).ok()?;
    let half = simulate(
        &Scene {
            dt_factor: 0.5 * scene.dt_factor,
            ..scene.clone()
        },
        init,
    )
    .ok()?;
    let finite = [
        rec.e_n,
        rec.e_kin,
        rec.omega_out,
        rec.energy_out,
        rec.energy_residual,
        rec.work_normal,
        rec.work_friction,
    ]
    .iter()
    .all(|x| x.is_finite());
    if !finite || !rec.separated || rec.timed_out {
        return Some(format!("not finite or not separated: {rec:?}"));
    }
    if let Some(reason) = common::energy_verdict(scene, &rec) {
        return Some(reason);
    }
    let v = init.vx.hypot(init.vy);
    let dv = [
        rec.vx_out - half.vx_out,
        rec.vy_out - half.vy_out,
        R * (rec.omega_out - half.omega_out),
    ];
    if dv.iter().any(|x| x.abs() > 0.05 * v) {
        let sci_dv = sci(&dv);
        return Some(format!(
            "halving dt changes the result by {sci_dv} (v = {v})"
        ));
    }
    None
}

#[test]
fn stiffest_scenes_are_stable_at_the_dt_bound() {
    let scenes = stiff_scenes();
    for integrator in BOTH {
        for (name, scene, init) in &scenes {
            let mut scene = Scene {
                integrator,
                ..scene.clone()
            };
            // The scene's own bound (it depends on its stiffness and damping).
            let bound = restitution_core::max_dt_factor(&scene).unwrap();
            scene.dt_factor = bound;
            if let Some(why) = unstable(&scene, init) {
                panic!("{integrator:?} at dt_factor {bound}: {name}: {why}");
            }
        }
    }
}
