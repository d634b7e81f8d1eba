//! The measurements behind the consistency matrix's documented energy bounds
//! (docs/consistency.md): the worst gains of the undamped linear law on polygons, of elastic
//! frictionless regular polygons per fixed-step integrator, and of weak friction on face-first
//! polygons. Ignored by default; `cargo test --release --test measurements -- --ignored
//! --nocapture` prints them.

mod common;

use common::bounds::{default_step, documented_gain_bound};
use restitution_core::{
    max_dt_factor, simulate, Initial, Integrator, NormalLaw, Record, Scene, Shape,
};

const R: f64 = 0.01;
const V: f64 = 0.0357;

/// The random convex 7-gon of the engine's representative shapes (seed 7), circumradius ~R.
fn random_convex_7gon() -> Shape {
    Shape::representatives(R, 7)
        .into_iter()
        .find_map(|(name, shape)| (name == "convex 7-gon").then_some(shape))
        .expect("the representatives include a convex 7-gon")
}

fn linear_elastic(shape: Shape, mu: f64, integrator: Integrator) -> Scene {
    default_step(Scene {
        shape,
        gamma: 0.0,
        gamma_t: 0.0,
        mu,
        normal_law: NormalLaw::Linear { kn: 1e5, cn: 0.0 },
        integrator,
        ..Scene::default()
    })
}

fn gain(rec: &Record) -> f64 {
    rec.energy_out / rec.energy_in - 1.0
}

/// The measurement: worst energy gain of the undamped linear law on polygons.
#[test]
#[ignore]
fn measure_linear_polygons() {
    let shapes: Vec<(&str, Shape, f64)> = vec![
        ("square face", Shape::regular_polygon(R, 4).unwrap(), 45.0),
        ("triangle face", Shape::regular_polygon(R, 3).unwrap(), 90.0),
        ("convex 7-gon", random_convex_7gon(), 0.0),
        ("12-gon", Shape::regular_polygon(R, 12).unwrap(), 0.0),
    ];
    for integrator in [Integrator::Gear5, Integrator::Verlet, Integrator::Reference] {
        for (name, shape, phi0) in &shapes {
            let mut worst = (f64::NEG_INFINITY, 0.0, 0.0, 0.0);
            for mu in [0.5, 1e3] {
                let scene = linear_elastic(shape.clone(), mu, integrator);
                for theta in (5..=89).step_by(3) {
                    for w in [0.0, 0.5, -0.5] {
                        let init = Initial::from_angle(V, theta as f64, w * V / R, *phi0);
                        let rec = simulate(&scene, &init).unwrap();
                        if gain(&rec) > worst.0 {
                            worst = (gain(&rec), theta as f64, mu, w);
                        }
                    }
                }
            }
            println!(
                "{:>9} {name:>14}: worst gain {:+.3e} (theta {}, mu {}, omega r/v {})",
                integrator.name(),
                worst.0,
                worst.1,
                worst.2,
                worst.3
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The reference path: the plate never pulls, no force once the overlap has ended

/// The 120-gon of the reproducers at the reference's largest step `dtf`.
/// The worst elastic, frictionless gain of regular polygons per fixed-step integrator at its
/// default step, over theta 3..90, omega_in r / v -1..1 and 8 orientations per corner spacing,
/// against the documented bound (docs/consistency.md).
#[test]
#[ignore]
fn measure_frictionless_polygons() {
    for integrator in [Integrator::Gear5, Integrator::Verlet] {
        for n in [3usize, 4, 5, 6, 12, 30, 120] {
            let scene = default_step(Scene {
                shape: Shape::regular_polygon(R, n).unwrap(),
                gamma: 0.0,
                gamma_t: 0.0,
                mu: 0.0,
                integrator,
                ..Scene::default()
            });
            let mut worst = (f64::NEG_INFINITY, 0.0, 0.0, 0.0);
            for theta in (3..=90).step_by(3) {
                for w in (0..=10).map(|k| -1.0 + 0.2 * k as f64) {
                    for k in 0..8 {
                        let phi0 = 360.0 / n as f64 * k as f64 / 8.0;
                        let init = Initial::from_angle(V, theta as f64, w * V / R, phi0);
                        let g = gain(&simulate(&scene, &init).unwrap());
                        if g > worst.0 {
                            worst = (g, theta as f64, w, phi0);
                        }
                    }
                }
            }
            println!(
                "{:>6} {n:>3}-gon: worst gain {:+.2e} (theta {}, omega r/v {:.1}, phi0 {:.2})",
                integrator.name(),
                worst.0,
                worst.1,
                worst.2,
                worst.3
            );
            assert!(worst.0 <= documented_gain_bound(&scene));
        }
    }
}

/// Issue 18, item 3: the weak-friction gain of face-first polygons (area law, gamma = 0,
/// gamma_t = 0, mu = 1e-9) per integrator at its default step.
#[test]
#[ignore]
fn measure_weak_friction() {
    for integrator in Integrator::ALL {
        for (n, phi0) in [(4, 45.0), (3, 90.0), (5, 90.0)] {
            let scene = default_step(Scene {
                shape: Shape::regular_polygon(R, n).unwrap(),
                gamma: 0.0,
                gamma_t: 0.0,
                mu: 1e-9,
                integrator,
                ..Scene::default()
            });
            let mut worst = (f64::NEG_INFINITY, 0.0, 0.0);
            for theta in (5..=89).step_by(4) {
                for w in [0.0, 0.5, -0.5] {
                    let init = Initial::from_angle(V, theta as f64, w * V / R, phi0);
                    let g = gain(&simulate(&scene, &init).unwrap());
                    if g > worst.0 {
                        worst = (g, theta as f64, w);
                    }
                }
            }
            println!(
                "{:>9} {n}-gon phi0 {phi0}: worst gain {:+.2e} (theta {}, omega r/v {})",
                integrator.name(),
                worst.0,
                worst.1,
                worst.2
            );
        }
    }
    for n in [120usize, 30] {
        let s = Scene {
            shape: Shape::regular_polygon(R, n).unwrap(),
            normal_law: NormalLaw::Linear { kn: 1e7, cn: 0.0 },
            ..Scene::default()
        };
        println!(
            "{n}-gon linear law, gear5 bound: dt_factor <= {}",
            max_dt_factor(&s).unwrap()
        );
    }
}
