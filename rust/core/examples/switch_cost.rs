//! What a located switch of the adaptive path costs (issue 27: <= 1.5 us), measured on the
//! study's grid (theta 4 ... 89 deg x mu 0, 0.1 ... 1, 946 impacts, Scene() on the plate:
//! adaptive, tol 1e-6) from each impact's time (best of batches of 20 calls, in shuffled passes) against its
//! steps and its located switches (counted by the engine, feature `bench-counters`): the
//! least-squares fit t = a + b steps + c switches. c is what a switch adds beyond the piece it
//! ends (its location on the dense output, the state there or the step redone up to it, the
//! mode's change); the part of its step it drops (integrated, not taken) is counted too and
//! priced at b. The halves of the grid (odd and even impacts) are fitted apart as a check.
//!
//! `cargo run --release -p restitution-core --features bench-counters --example switch_cost
//! [-- SHAPE_N ...]` (SHAPE_N 0 for the exact disc, n for a regular n-gon; default 0 120).

use restitution_core::counters::{dropped_steps, located_switches};
use restitution_core::{simulate, Initial, Integrator, Scene, Shape};
use std::hint::black_box;
use std::time::Instant;

/// One impact's (steps, located switches, steps dropped).
fn count(scene: &Scene, init: &Initial) -> [f64; 3] {
    let (n0, d0) = (located_switches(), dropped_steps());
    let steps = simulate(scene, init).expect("a valid impact").steps as f64;
    let (n, d) = ((located_switches() - n0) as f64, dropped_steps() - d0);
    [steps, n, d]
}

/// Best us per call of each impact: passes over the impacts in shuffled orders (a drift of
/// the machine's speed during the run would otherwise follow the grid's order, and with it
/// the angle and the switches), three batches of 20 calls per impact and pass.
fn times(impacts: &[(Scene, Initial)]) -> Vec<f64> {
    let mut best = vec![f64::INFINITY; impacts.len()];
    let mut order: Vec<usize> = (0..impacts.len()).collect();
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    for _ in 0..5 {
        for i in (1..order.len()).rev() {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            order.swap(i, (seed % (i as u64 + 1)) as usize);
        }
        for &i in &order {
            let (scene, init) = &impacts[i];
            for _ in 0..3 {
                let start = Instant::now();
                for _ in 0..20 {
                    black_box(simulate(black_box(scene), black_box(init)).expect("valid"));
                }
                best[i] = best[i].min(1e6 * start.elapsed().as_secs_f64() / 20.0);
            }
        }
    }
    best
}

/// Least-squares (a, b, c) of t = a + b x + c y over `rows` (x, y, t): the normal equations
/// of the centred data, solved by Cramer's rule.
fn fit(rows: &[[f64; 3]]) -> [f64; 3] {
    let n = rows.len() as f64;
    let mean = |k: usize| rows.iter().map(|r| r[k]).sum::<f64>() / n;
    let (mx, my, mt) = (mean(0), mean(1), mean(2));
    let s = |f: &dyn Fn(&[f64; 3]) -> f64| rows.iter().map(f).sum::<f64>();
    let sxx = s(&|r| (r[0] - mx) * (r[0] - mx));
    let syy = s(&|r| (r[1] - my) * (r[1] - my));
    let sxy = s(&|r| (r[0] - mx) * (r[1] - my));
    let sxt = s(&|r| (r[0] - mx) * (r[2] - mt));
    let syt = s(&|r| (r[1] - my) * (r[2] - mt));
    let det = sxx * syy - sxy * sxy;
    let b = (sxt * syy - syt * sxy) / det;
    let c = (sxx * syt - sxy * sxt) / det;
    [mt - b * mx - c * my, b, c]
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a shape's corner count (0: the disc)"))
        .collect();
    let shapes = if args.is_empty() { vec![0, 120] } else { args };
    for n in shapes {
        let shape = match n {
            0 => Shape::disc(0.01),
            _ => Shape::regular_polygon(0.01, n),
        }
        .expect("a valid shape");
        let mut impacts = Vec::new();
        for theta in 4..=89 {
            for m in 0..=10 {
                let scene = Scene {
                    shape: shape.clone(),
                    gamma: 0.33299,
                    mu: 0.1 * m as f64,
                    integrator: Integrator::Adaptive,
                    tol: 1e-6,
                    dt_factor: 1.0,
                    ..Scene::default()
                };
                impacts.push((scene, Initial::from_angle(0.0357, theta as f64, 0.0, 0.0)));
            }
        }
        let counts: Vec<[f64; 3]> = impacts.iter().map(|(s, i)| count(s, i)).collect();
        let impacts: Vec<[f64; 4]> = counts
            .iter()
            .zip(times(&impacts))
            .map(|(c, t)| [c[0], c[1], c[2], t])
            .collect();
        report(n, &impacts);
    }
}

/// Prints the fit over all impacts and over each half.
fn report(n: usize, impacts: &[[f64; 4]]) {
    let count = impacts.len() as f64;
    let mean = |k: usize| impacts.iter().map(|r| r[k]).sum::<f64>() / count;
    let dropped = mean(2) / mean(1);
    let rows = |keep: &dyn Fn(usize) -> bool| -> Vec<[f64; 3]> {
        (0..impacts.len())
            .filter(|&i| keep(i))
            .map(|i| [impacts[i][0], impacts[i][1], impacts[i][3]])
            .collect()
    };
    let name = if n == 0 {
        "disc".to_string()
    } else {
        format!("{n}-gon")
    };
    println!(
        "{name}: {:.2} us/impact, {:.1} steps, {:.2} located switches per impact, each dropping {dropped:.2} of its step",
        mean(3),
        mean(0),
        mean(1)
    );
    for (what, part) in [
        ("all", rows(&|_| true)),
        ("odd", rows(&|i| i % 2 == 1)),
        ("even", rows(&|i| i % 2 == 0)),
    ] {
        let [a, b, c] = fit(&part);
        println!(
            "  {what:>4}: intercept {a:5.2} us, per step {b:.3} us, per located switch {c:.3} us \
             + its dropped part {:.3} us = {:.2} us",
            dropped * b,
            c + dropped * b
        );
    }
}
