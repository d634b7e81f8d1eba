//! The fixed cost per impact, outside the steps (issue 13): a sweep of the 946-impact grid
//! (theta 4..89 deg x mu 0, 0.1 ... 1) on one thread, cases built the way the bindings build
//! them (`cases_from_rows`, one scene per case), for several steps of one integrator; prints
//! us/impact, mean steps and the intercept and slope of time against steps.
//!
//! `cargo run --release -p restitution-core --example overhead -- INTEGRATOR SHAPE_N [vary]`
//! (INTEGRATOR gear5, verlet, adaptive or reference; SHAPE_N 0 for the exact disc, 120 for the
//! 120-gon; `vary`: every case its own gamma, so that no two cases share a scene). Also
//! useful under `perf record`.

use restitution_core::{cases_from_rows, run_cases, Case, Templates, CASE_COLUMNS, CHOICES};
use std::time::Instant;

/// The cases of the grid with `integrator` at step `dt` (adaptive: largest step 1 at `tol`).
fn grid(integrator: usize, n: f64, dt: f64, tol: f64, vary: bool) -> Vec<Case> {
    let mut rows = Vec::new();
    for t in 4..=89 {
        for m in 0..=10 {
            let k = rows.len() as f64;
            let gamma = if vary { 0.33299 + 1e-6 * k } else { 0.33299 };
            let mut row = [f64::NAN; CASE_COLUMNS.len()];
            let set = |row: &mut [f64; CASE_COLUMNS.len()], name: &str, v: f64| {
                row[CASE_COLUMNS
                    .iter()
                    .position(|c| *c == name)
                    .expect("a column")] = v;
            };
            for (name, v) in [
                ("theta_deg", t as f64),
                ("omega_in", 0.0),
                ("v", 0.0357),
                ("mu", 0.1 * m as f64),
                ("gamma", gamma),
                ("gamma_t", 0.5),
                ("E", 1e7),
                ("rho", 2500.0),
                ("r", 0.01),
                ("phi0_deg", 0.0),
                ("dt_factor", dt),
                ("n", n),
                ("integrator", integrator as f64),
                ("normal_law", 0.0),
                ("inertia", 0.0),
                ("overlap", 0.0),
                ("tangential", 0.0),
                ("tangential_history", 0.0),
                ("body", 0.0),
                ("tol", tol),
                ("error_estimate", 0.0),
                ("partner_body", 0.0),
                ("partner_omega_in", 0.0),
            ] {
                set(&mut row, name, v);
            }
            rows.push(row);
        }
    }
    cases_from_rows(rows.into_iter(), Templates::default()).expect("valid cases")
}

/// Least-squares intercept and slope of y against x.
fn fit(x: &[f64], y: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    let slope = sxy / sxx;
    (my - slope * mx, slope)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().map_or("gear5", String::as_str);
    let n: f64 = args.get(1).map_or(0.0, |s| s.parse().expect("a shape n"));
    let vary = args.iter().any(|a| a == "vary");
    let integrator = CHOICES[0]
        .1
        .iter()
        .position(|c| *c == name)
        .expect("gear5, verlet, reference or adaptive");
    // (dt_factor, tol) pairs that vary the steps per impact.
    let settings: Vec<(f64, f64)> = match name {
        "gear5" | "verlet" => [0.06, 0.03, 0.01].iter().map(|&d| (d, 1e-6)).collect(),
        "reference" => [1.0, 0.2, 0.05].iter().map(|&d| (d, 1e-6)).collect(),
        _ => [1e-4, 1e-6, 1e-8].iter().map(|&t| (1.0, t)).collect(),
    };
    if args.iter().any(|a| a == "pieces") {
        pieces(&grid(integrator, n, settings[0].0, settings[0].1, vary));
        return;
    }
    let (mut xs, mut ys) = (Vec::new(), Vec::new());
    for (dt, tol) in settings {
        let start = Instant::now();
        let cases = grid(integrator, n, dt, tol, vary);
        let build = start.elapsed().as_secs_f64();
        let mut best = f64::INFINITY;
        let mut steps = 0.0;
        for _ in 0..3 {
            let start = Instant::now();
            let recs = run_cases(&cases, 1).expect("every case runs");
            best = best.min(start.elapsed().as_secs_f64());
            steps = recs.iter().map(|r| r.steps as f64).sum::<f64>() / recs.len() as f64;
        }
        let per = 1e6 * best / cases.len() as f64;
        let build_us = 1e6 * build / cases.len() as f64;
        println!("{name} n={n} dt={dt} tol={tol:e}: {per:.2} us/impact, {steps:.1} steps, build {build_us:.2} us/case");
        xs.push(steps);
        ys.push(per);
    }
    let (a, b) = fit(&xs, &ys);
    println!(
        "{name}: intercept {a:.2} us/impact, slope {:.1} ns/step",
        1e3 * b
    );
}

/// Times the per-impact pieces outside the steps on the grid's cases (`pieces` mode).
pub fn pieces(cases: &[Case]) {
    use restitution_core::impact::step_budget;
    use restitution_core::{estimate_max_depth, Model};
    use std::hint::black_box;
    let time = |what: &str, f: &dyn Fn(&Case)| {
        let mut best = f64::INFINITY;
        for _ in 0..5 {
            let start = Instant::now();
            for c in cases {
                f(c);
            }
            best = best.min(start.elapsed().as_secs_f64());
        }
        println!("{what:<24} {:8.3} us/case", 1e6 * best / cases.len() as f64);
    };
    time("Model::derive+check", &|c| {
        black_box(Model::new(black_box(&c.scene)).expect("valid"));
    });
    time("scene clone", &|c| {
        black_box(black_box(&c.scene).clone());
    });
    let models: Vec<Model> = cases
        .iter()
        .map(|c| Model::new(&c.scene).expect("valid"))
        .collect();
    let models = &models;
    let index = |c: &Case| {
        (c as *const Case as usize - cases.as_ptr() as usize) / std::mem::size_of::<Case>()
    };
    time("check_initial", &|c| {
        black_box(
            models[index(c)]
                .check_initial(black_box(&c.init))
                .expect("valid"),
        );
    });
    time("estimate_max_depth", &|c| {
        black_box(estimate_max_depth(&models[index(c)], black_box(&c.init)).expect("valid"));
    });
    time("step_budget", &|c| {
        let m = &models[index(c)];
        black_box(step_budget(m, &c.init, black_box(1e-4)));
    });
}
