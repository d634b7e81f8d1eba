//! The slow impacts of issue 14, one per process: `cargo run --release --example long_runs --
//! ROW PHI0_DEG [OMEGA_DEG_S]` prints the record's step count, contact time and wall time, or
//! with no arguments lists the rows.

use restitution_core::{estimate_max_depth, simulate, Initial, Model, Scene, Shape};
use std::time::Instant;

#[path = "../tests/common/slow_rows.rs"]
mod slow_rows;
use slow_rows::ROWS;

fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a number"))
        .collect();
    if args.is_empty() {
        for (i, r) in ROWS.iter().enumerate() {
            println!("{i}: {r:?}");
        }
        return;
    }
    let (n, theta, mu, gamma, e, v) = ROWS[args[0] as usize];
    let phi0 = args.get(1).copied().unwrap_or(0.0);
    let omega = args.get(2).copied().unwrap_or(0.0).to_radians();
    let scene = Scene {
        shape: Shape::regular_polygon(0.01, n).unwrap(),
        mu,
        gamma,
        e_modulus: e,
        ..Scene::default()
    };
    let init = Initial::from_angle(v, theta, omega, phi0);
    let model = Model::new(&scene).unwrap();
    if let Ok(d) = estimate_max_depth(&model, &init) {
        let t_est = std::f64::consts::PI * d / init.vy.abs();
        println!(
            "depth_est {d:e} ({:.3e} ulp(r)) t_est {t_est:e} s = {:.3e} steps of dt {:e}",
            d / (f64::EPSILON * 0.01),
            t_est / model.dt,
            model.dt
        );
    }
    let t0 = Instant::now();
    let rec = simulate(&scene, &init);
    let wall = t0.elapsed().as_secs_f64();
    match rec {
        Ok(r) => println!(
            "steps {} of {} ({}) contacts {} e_n {:.6} t_c {:e} gain {:.1e} wall {wall:.3} s",
            r.steps,
            r.step_budget,
            r.stop.name(),
            r.contacts,
            r.e_n,
            r.contact_time,
            r.energy_out / r.energy_in - 1.0
        ),
        Err(e) => println!("refused: {e} ({wall:.3} s)"),
    }
}
