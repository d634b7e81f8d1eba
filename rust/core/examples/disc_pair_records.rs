//! The records of random two-disc impacts on the adaptive path, every value as its bits, one
//! line per impact, so that two builds can be compared with `diff` (`pair_records` draws
//! polygons only). Partners 0.5-2x the particle (a fifth of them equal), random spins and
//! angles, mu 0-2, the area and the linear law, elastic or damped.
//!
//! `cargo run --release -p restitution-core --example disc_pair_records -- 2000 > after.txt`
#[path = "common/records.rs"]
#[allow(dead_code)]
mod records;
use records::record_bits;
use restitution_core::{simulate, Initial, Integrator, NormalLaw, Partner, Scene, Shape};
fn main() {
    let count: usize = std::env::args().nth(1).map_or(200, |s| s.parse().unwrap());
    let mut seeded = restitution_core::Seeded(54321);
    let mut rng = move || seeded.uniform();
    for case in 0..count {
        let r2 = if rng() < 0.2 {
            0.01
        } else {
            0.01 * (0.5 + 1.5 * rng())
        };
        let linear = rng() < 0.3;
        let scene = Scene {
            shape: Shape::Disc { r: 0.01 },
            partner: Some(Partner::of(Shape::Disc { r: r2 })),
            mu: 2.0 * rng() * rng(),
            gamma: if rng() < 0.3 { 0.0 } else { 0.33 },
            gamma_t: if rng() < 0.5 { 0.0 } else { 0.5 },
            normal_law: if linear {
                NormalLaw::Linear {
                    kn: 5e6,
                    cn: 10.0 * rng(),
                }
            } else {
                NormalLaw::Area
            },
            integrator: Integrator::Adaptive,
            dt_factor: 1.0,
            ..Scene::default()
        };
        let init = Initial::from_angle(0.0714, 2.0 + 87.0 * rng(), (rng() - 0.5) * 40.0, 0.0)
            .with_partner((rng() - 0.5) * 40.0, 0.0);
        match simulate(&scene, &init) {
            Ok(rec) => println!("{case} {}", record_bits(&rec)),
            Err(e) => println!("{case} err {e}"),
        }
    }
}
