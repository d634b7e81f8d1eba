//! How many times a pair's adaptive path evaluates its contact law per step (issue 40: the
//! plate's loop about 7 per step), on the pairs of the impact benchmark's summary (the paper
//! preset, 45 degrees, relative speed twice the plate's): two discs, two 12-gons, two
//! 120-gons, a disc on a 12-gon. Counted by the engine (feature `bench-counters`).
//!
//! `cargo run --release -p restitution-core --features bench-counters --example pair_evaluations`

use restitution_core::counters::pair_law_evaluations;
use restitution_core::{simulate, Initial, Integrator, Partner, Scene, Shape};

fn main() {
    let disc = Scene {
        mu: 0.5,
        integrator: Integrator::Adaptive,
        dt_factor: Integrator::Adaptive.default_dt_factor(),
        ..Scene::default()
    };
    let twelve = Shape::regular_polygon(0.01, 12).expect("valid 12-gon");
    let gon120 = Shape::regular_polygon(0.01, 120).expect("valid 120-gon");
    let pair = |shape: &Shape, partner: &Shape| Scene {
        shape: shape.clone(),
        partner: Some(Partner::of(partner.clone())),
        ..disc.clone()
    };
    let round = Shape::Disc { r: 0.01 };
    let scenes = [
        ("two discs", pair(&round, &round)),
        ("two 12-gons", pair(&twelve, &twelve)),
        ("two 120-gons", pair(&gon120, &gon120)),
        ("disc on 12-gon", pair(&round, &twelve)),
    ];
    let init = Initial::from_angle(2.0 * 0.0357, 45.0, 0.0, 0.0);
    println!(
        "{:<16} {:>6} {:>12} {:>10}",
        "pair", "steps", "evaluations", "per step"
    );
    for (name, scene) in scenes {
        let before = pair_law_evaluations();
        let steps = simulate(&scene, &init).expect("a valid impact").steps;
        let evals = pair_law_evaluations() - before;
        println!(
            "{name:<16} {steps:>6} {evals:>12} {:>10.1}",
            evals as f64 / steps as f64
        );
    }
}
