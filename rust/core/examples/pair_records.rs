//! The records of random pair impacts, every value as its bits, one line per impact, so that
//! two builds can be compared with `diff` (issue 40: a faster pair geometry must leave every
//! record the same, bit for bit). Regular 3- to 200-gons and random convex polygons, partners
//! 0.5-2x the particle, random orientations, spins and angles, mu 0-2, the area and the linear
//! law, elastic or damped; even cases on the adaptive path, odd ones with Gear-5.
//!
//! `cargo run --release -p restitution-core --example pair_records -- 2000 > after.txt`
#[path = "common/records.rs"]
mod records;
use records::{random_polygon, record_bits};
use restitution_core::{simulate, Initial, Integrator, NormalLaw, Partner, Scene};
fn main() {
    let count: usize = std::env::args().nth(1).map_or(200, |s| s.parse().unwrap());
    let mut seeded = restitution_core::Seeded(12345);
    let mut rng = move || seeded.uniform();
    for case in 0..count {
        let shape = |r: f64, rng: &mut dyn FnMut() -> f64| random_polygon(r, 0.25, rng);
        let s1 = shape(0.01, &mut rng);
        let s2 = shape(0.01 * (0.5 + 1.5 * rng()), &mut rng);
        let linear = rng() < 0.2;
        let adaptive = case % 2 == 0;
        let scene = Scene {
            shape: s1,
            partner: Some(Partner::of(s2)),
            mu: 2.0 * rng() * rng(),
            gamma: if rng() < 0.3 { 0.0 } else { 0.33 },
            normal_law: if linear {
                NormalLaw::Linear { kn: 5e6, cn: 0.0 }
            } else {
                NormalLaw::Area
            },
            integrator: if adaptive {
                Integrator::Adaptive
            } else {
                Integrator::Gear5
            },
            dt_factor: if adaptive { 1.0 } else { 0.01 },
            ..Scene::default()
        };
        let init = Initial::from_angle(
            0.0714,
            2.0 + 87.0 * rng(),
            (rng() - 0.5) * 20.0,
            rng() * 360.0,
        )
        .with_partner((rng() - 0.5) * 20.0, rng() * 360.0);
        match simulate(&scene, &init) {
            Ok(rec) => {
                println!(
                    "{case} {} {}",
                    if adaptive { "A" } else { "G" },
                    record_bits(&rec)
                );
            }
            Err(e) => println!("{case} err {e}"),
        }
    }
}
