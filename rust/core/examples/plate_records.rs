//! The records of random impacts on the plate on the adaptive path, every value as its bits,
//! one line per impact, so that two builds can be compared with `diff` (issue 40: the plate's
//! and the pair's adaptive loops made one must leave every record the same, bit for bit).
//! Discs, spheres, regular 3- to 200-gons and random convex polygons; the area law, the linear
//! law and (spheres) Hertz with Mindlin's or the linear tangential spring and every history;
//! mu 0-2, elastic or damped, spins, grazing to head-on; one case in eight on the reference
//! integrator (its tolerance, its largest step).
//!
//! `cargo run --release -p restitution-core --example plate_records -- 2000 > after.txt`
#[path = "common/records.rs"]
mod records;
use records::{random_polygon, record_bits};
use restitution_core::{
    simulate, Initial, Integrator, NormalLaw, Scene, Shape, TangentialHistory, TangentialModel,
};

/// A regular or a random convex polygon of circumradius about `r`.
fn polygon(r: f64, rng: &mut dyn FnMut() -> f64) -> Shape {
    random_polygon(r, 0.3, rng)
}

/// A random scene on the adaptive path (or the reference's) with the laws its shape admits.
fn scene(case: usize, rng: &mut dyn FnMut() -> f64) -> Scene {
    let kind = rng();
    let shape = if kind < 0.3 {
        Shape::disc(0.01).unwrap()
    } else if kind < 0.45 {
        Shape::sphere(0.01).unwrap()
    } else {
        polygon(0.01, rng)
    };
    let sphere = matches!(shape, Shape::Sphere { .. });
    let law = rng();
    let normal_law = if sphere && law < 0.75 {
        NormalLaw::Hertz {
            nu: 0.3,
            plate: None,
            cor: 0.2 + 0.8 * rng(),
        }
    } else if law < 0.75 && !sphere {
        NormalLaw::Area
    } else {
        NormalLaw::Linear {
            kn: 5e6,
            cn: if rng() < 0.5 { 0.0 } else { 400.0 * rng() },
        }
    };
    let hertz = matches!(normal_law, NormalLaw::Hertz { .. });
    let tangential = if hertz && rng() < 0.5 {
        TangentialModel::Linear
    } else {
        TangentialModel::Auto
    };
    let histories = TangentialHistory::ALL;
    let tangential_history = if hertz && tangential == TangentialModel::Auto {
        histories[(rng() * histories.len() as f64) as usize]
    } else {
        TangentialHistory::Auto
    };
    let reference = case % 8 == 7;
    Scene {
        shape,
        mu: if rng() < 0.2 {
            0.0
        } else {
            2.0 * rng() * rng()
        },
        gamma: if rng() < 0.3 { 0.0 } else { 0.5 * rng() },
        normal_law,
        tangential,
        tangential_history,
        kt: (tangential == TangentialModel::Linear).then_some(1e8),
        integrator: if reference {
            Integrator::Reference
        } else {
            Integrator::Adaptive
        },
        dt_factor: Integrator::Adaptive.default_dt_factor() * (0.25 + rng()),
        tol: [1e-4, 1e-6, 1e-8][(rng() * 3.0) as usize],
        ..Scene::default()
    }
}

fn main() {
    let count: usize = std::env::args().nth(1).map_or(200, |s| s.parse().unwrap());
    let mut seeded = restitution_core::Seeded(2468);
    let mut rng = move || seeded.uniform();
    for case in 0..count {
        let scene = scene(case, &mut rng);
        // Grazing (0.5 deg) to head-on, spins up to +-50 rad/s, any orientation.
        let theta = if rng() < 0.1 {
            0.5 + 3.0 * rng()
        } else {
            2.0 + 88.0 * rng()
        };
        let init = Initial::from_angle(0.0714, theta, (rng() - 0.5) * 100.0, rng() * 360.0);
        let line = match simulate(&scene, &init) {
            Ok(rec) => record_bits(&rec),
            Err(e) => format!("err {e}"),
        };
        println!("{case} {line}");
    }
}
