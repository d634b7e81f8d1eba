//! The linear law on polygons with Gear-5 (Verlet is refused for it): worst energy residual
//! (damped), energy gain (elastic), mirror and 360 / n rotation differences, and the cost per
//! step, over a grid of impacts. With `dump` as first argument, prints the records of the
//! area law and the disc instead (to compare two builds bit for bit); with `conv ...`, one
//! impact at six halvings of its step (see `convergence`).
//!
//! `cargo run --release --example linear_events [dump | conv N INTEGRATOR MU DAMPED THETA W PHI]`

use restitution_core::{simulate, Initial, Integrator, NormalLaw, Record, Scene, Shape};
use std::time::Instant;

const V: f64 = 0.0357;
const R: f64 = 0.01;

fn mirrored(shape: &Shape) -> Shape {
    match shape {
        Shape::Polygon(p) => {
            let v: Vec<[f64; 2]> = p.vertices().iter().rev().map(|q| [-q.x, q.y]).collect();
            Shape::convex_polygon(&v).unwrap()
        }
        _ => shape.clone(),
    }
}

fn diff(a: &Record, b: &Record, sign: f64) -> f64 {
    [
        (a.vy_out - b.vy_out) / V,
        (a.vx_out - sign * b.vx_out) / V,
        (a.omega_out - sign * b.omega_out) * R / V,
    ]
    .iter()
    .fold(0.0f64, |m, x| m.max(x.abs()))
}

fn scene(shape: &Shape, law: NormalLaw, integrator: Integrator, mu: f64, damped: bool) -> Scene {
    let base = Scene {
        shape: shape.clone(),
        integrator,
        mu,
        gamma: if damped { 0.33 } else { 0.0 },
        gamma_t: if damped { 0.5 } else { 0.0 },
        ..Scene::default()
    };
    let mass = base.rho * shape.area();
    let zeta = if damped { 0.2 } else { 0.0 };
    let bound = restitution_core::max_dt_factor(&Scene {
        normal_law: law.with_scale(1e5, zeta, mass),
        ..base.clone()
    })
    .unwrap();
    Scene {
        normal_law: law.with_scale(1e5, zeta, mass),
        dt_factor: base.dt_factor.min(bound),
        ..base
    }
}

fn impacts() -> Vec<(f64, f64, f64)> {
    let mut out = Vec::new();
    for theta in [12.0, 35.0, 60.0, 85.0] {
        for w in [0.5, 0.0, -0.5] {
            for phi in [7.0, 19.0, 67.0, 92.0] {
                out.push((theta, w, phi + theta));
            }
        }
    }
    out
}

fn shapes() -> Vec<(String, Shape)> {
    Shape::representatives(R, 7)
        .into_iter()
        .filter(|(n, _)| n != "sphere")
        .collect()
}

fn dump() {
    for (name, shape) in shapes() {
        for law in [NormalLaw::Area, NormalLaw::Linear { kn: 0.0, cn: 0.0 }] {
            let disc = name == "disc";
            if !disc && law != NormalLaw::Area {
                continue;
            }
            for integrator in [Integrator::Gear5, Integrator::Verlet] {
                for mu in [0.0, 0.5, 10.0] {
                    for damped in [false, true] {
                        let s = scene(&shape, law, integrator, mu, damped);
                        for &(theta, w, phi) in impacts().iter().step_by(5) {
                            let init = Initial::from_angle(V, theta, w * V / R, phi);
                            let r = simulate(&s, &init).unwrap();
                            println!(
                                "{name} {} {} {mu} {damped} {theta} {w} {phi}: {:e} {:e} {:e} {:e} {:e} {}",
                                law.name(),
                                integrator.name(),
                                r.vx_out,
                                r.vy_out,
                                r.omega_out,
                                r.work_normal,
                                r.work_friction,
                                r.steps
                            );
                        }
                    }
                }
            }
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    match args.get(1).map(String::as_str) {
        Some("dump") => dump(),
        Some("conv") => convergence(&args[2..]),
        _ => survey(),
    }
}

/// `conv N INTEGRATOR MU DAMPED THETA W PHI`: one N-gon impact under the linear law at six
/// halvings of the scene's step (its energy residual and outgoing velocities).
fn convergence(args: &[String]) {
    let n: usize = args[0].parse().unwrap();
    let integ = match args[1].as_str() {
        "verlet" => Integrator::Verlet,
        "reference" => Integrator::Reference,
        _ => Integrator::Gear5,
    };
    let p = |i: usize| args[i].parse::<f64>().unwrap();
    let shape = Shape::regular_polygon(R, n).unwrap();
    let law = NormalLaw::Linear { kn: 0.0, cn: 0.0 };
    let s = scene(&shape, law, integ, p(2), args[3] == "true");
    let init = Initial::from_angle(V, p(4), p(5) * V / R, p(6));
    for k in 0..6 {
        let sk = Scene {
            dt_factor: s.dt_factor / (1 << k) as f64,
            ..s.clone()
        };
        let r = simulate(&sk, &init).unwrap();
        println!(
            "dtf {:.3e}: residual {:+.3e} vy {:.12e} vx {:.12e} om {:.12e} steps {} contacts {}",
            sk.dt_factor, r.energy_residual, r.vy_out, r.vx_out, r.omega_out, r.steps, r.contacts
        );
    }
}

/// The worst energy residual (damped), energy gain (elastic), mirror and rotation differences
/// and the cost per step of Gear-5 under the linear law, per polygon of the representatives.
fn survey() {
    let (law, integrator) = (NormalLaw::Linear { kn: 0.0, cn: 0.0 }, Integrator::Gear5);
    for (name, shape) in shapes().into_iter().filter(|(n, _)| n != "disc") {
        let n_reg: Option<usize> = name.strip_suffix("-gon").and_then(|n| n.parse().ok());
        let (mut res, mut gain, mut mir, mut rot) = (0.0f64, f64::MIN, 0.0f64, 0.0f64);
        let (mut steps, mut secs) = (0u64, 0.0);
        let (mut at_res, mut at_rot) = (String::new(), String::new());
        for mu in [0.0, 0.5, 10.0] {
            for damped in [false, true] {
                let s = scene(&shape, law, integrator, mu, damped);
                let m = Scene {
                    shape: mirrored(&shape),
                    ..s.clone()
                };
                for &(theta, w, phi) in &impacts() {
                    let init = Initial::from_angle(V, theta, w * V / R, phi);
                    let t0 = Instant::now();
                    let r = simulate(&s, &init).unwrap();
                    secs += t0.elapsed().as_secs_f64();
                    steps += r.steps;
                    let case = format!("mu {mu} damped {damped} theta {theta} w {w} phi {phi}");
                    if damped && r.energy_residual.abs() > res {
                        at_res = case.clone();
                    }
                    if damped {
                        res = res.max(r.energy_residual.abs());
                    } else {
                        gain = gain.max(r.energy_out / r.energy_in - 1.0);
                    }
                    let mi = Initial {
                        vx: -init.vx,
                        omega: -init.omega,
                        phi0: -init.phi0,
                        ..init
                    };
                    mir = mir.max(diff(&r, &simulate(&m, &mi).unwrap(), -1.0));
                    if let Some(n) = n_reg {
                        let t = Initial::from_angle(V, theta, w * V / R, phi + 360.0 / n as f64);
                        let d = diff(&r, &simulate(&s, &t).unwrap(), 1.0);
                        if d > rot {
                            at_rot = case.clone();
                        }
                        rot = rot.max(d);
                    }
                }
            }
        }
        println!(
            "{:>7} {name:>13}: residual {res:.2e} gain {gain:+.2e} mirror {mir:.2e} rotation {rot:.2e} | {:.1} ns/step ({steps} steps)",
            integrator.name(),
            1e9 * secs / steps as f64
        );
        if std::env::var("WHERE").is_ok() {
            println!("      worst residual at {at_res}; rotation at {at_rot}");
        }
    }
}
