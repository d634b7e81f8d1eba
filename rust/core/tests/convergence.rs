//! Convergence of one exact-disc impact with dt (docs/model.md, section 7.6): the orders of
//! Gear-5 and Verlet on elastic, damped and frictional impacts, the state in contact at a fixed
//! time, and the agreement of the two integrators at a fine step. Run with `--nocapture` to
//! see the measured orders.

mod common;

use common::*;
use restitution_core::{simulate_with_trace, Integrator, Record, Scene};

const DTS: [f64; 5] = [0.02, 0.01, 0.005, 0.0025, 0.00125];

/// Observed order from successive differences d_k = |q(dt_k) - q(dt_{k+1})| of a halving
/// sequence: log2(d_first / d_last) / (number of halvings between them).
fn order(diffs: &[f64]) -> f64 {
    (diffs[0] / diffs[diffs.len() - 1]).log2() / (diffs.len() - 1) as f64
}

fn diffs(values: &[f64]) -> Vec<f64> {
    values.windows(2).map(|w| (w[0] - w[1]).abs()).collect()
}

struct Case {
    name: &'static str,
    mu: f64,
    gamma: f64,
    theta: f64,
}

const CASES: [Case; 3] = [
    Case {
        name: "mu=0 gamma=0",
        mu: 0.0,
        gamma: 0.0,
        theta: 30.0,
    },
    Case {
        name: "damping only",
        mu: 0.0,
        gamma: 0.33,
        theta: 30.0,
    },
    Case {
        name: "friction",
        mu: 0.5,
        gamma: 0.33,
        theta: 45.0,
    },
];

fn sequence(case: &Case, integrator: Integrator) -> Vec<Record> {
    DTS.iter()
        .map(|&dt_factor| {
            let scene = Scene {
                mu: case.mu,
                gamma: case.gamma,
                integrator,
                dt_factor,
                ..Scene::default()
            };
            run(&scene, &at(case.theta, 0.0))
        })
        .collect()
}

#[test]
fn results_converge_with_dt_at_the_expected_orders() {
    // (case, integrator) -> floor on the order of the differences of e_n / e_kin (and e_t
    // with friction). docs/model.md, section 7.6: Gear-5 about 2.5 / 1.5 / 1, limited by the non-smooth force
    // (delta^{3/2}, then delta^{1/2} with damping, then stick/slip switches); a broken
    // integrator (first order, or one that does not converge) fails these floors.
    let floors = [
        (0, Integrator::Gear5, 2.0),
        (1, Integrator::Gear5, 1.2),
        (1, Integrator::Verlet, 1.2),
        (2, Integrator::Gear5, 0.8),
        (2, Integrator::Verlet, 0.8),
    ];
    for (i, integrator, floor) in floors {
        let case = &CASES[i];
        let recs = sequence(case, integrator);
        let mut quantities: Vec<(&str, Vec<f64>)> = vec![
            ("e_n", recs.iter().map(|r| r.e_n).collect()),
            ("e_kin", recs.iter().map(|r| r.e_kin).collect()),
        ];
        if case.mu > 0.0 {
            quantities.push(("e_t", recs.iter().map(|r| r.e_t.unwrap()).collect()));
        } else {
            // No friction: e_t is exactly 1 at every dt.
            assert!(recs.iter().all(|r| r.e_t == Some(1.0)));
        }
        for (q, values) in quantities {
            let d = diffs(&values);
            let p = order(&d);
            let sci_d = sci(&d);
            eprintln!(
                "order {integrator:?} {} {q}: {p:.2} (differences {sci_d})",
                case.name
            );
            assert!(
                d.windows(2).all(|w| w[1] < w[0]),
                "{integrator:?} {} {q}: differences not monotone: {sci_d}",
                case.name
            );
            assert!(
                p > floor,
                "{integrator:?} {} {q}: order {p:.2} <= {floor}",
                case.name
            );
        }
    }
}

#[test]
fn verlet_elastic_bounce_converged_below_tolerance() {
    // Verlet on the conservative bounce: the symplectic scheme's energy error lives only in
    // the touch and separation steps, so e_n's dt-dependence is at the 1e-9 level and not
    // monotone (it depends on where separation falls within a step). Check the size, and
    // measure the order on the smooth part below.
    let recs = sequence(&CASES[0], Integrator::Verlet);
    let d = diffs(&recs.iter().map(|r| r.e_n).collect::<Vec<_>>());
    let sci_d = sci(&d);
    eprintln!("Verlet mu=0 gamma=0 e_n differences: {sci_d}");
    assert!(d.iter().all(|&x| x < 1e-7), "{sci_d}");
}

#[test]
fn state_at_a_fixed_time_in_contact_converges_at_high_order() {
    // The order on the smooth part of the contact: the velocity at a fixed time inside the
    // contact (t = 8 t_ref of about 20, on every grid), mu = 0, gamma = 0. Verlet is second
    // order there; Gear-5 about 2.5. The only non-smoothness before t is the touch at t = 0
    // (force ~ t^{3/2}).
    let t_fixed = 8.0; // in t_ref
    for (integrator, floor) in [(Integrator::Gear5, 2.0), (Integrator::Verlet, 1.5)] {
        let vy: Vec<f64> = DTS
            .iter()
            .map(|&dt_factor| {
                let scene = Scene {
                    mu: 0.0,
                    gamma: 0.0,
                    integrator,
                    dt_factor,
                    ..Scene::default()
                };
                let (_, trace) = simulate_with_trace(&scene, &at(30.0, 0.0)).unwrap();
                let k = (t_fixed / dt_factor).round() as usize;
                trace.vy[k]
            })
            .collect();
        let d = diffs(&vy);
        let p = order(&d);
        let sci_d = sci(&d);
        eprintln!(
            "order {integrator:?} vy(t = 8 t_ref), mu=0 gamma=0: {p:.2} (differences {sci_d})"
        );
        assert!(d.windows(2).all(|w| w[1] < w[0]), "{integrator:?}: {sci_d}");
        assert!(p > floor, "{integrator:?}: order {p:.2}");
    }
}

/// A scalar read off a record.
type Quantity = fn(&Record) -> f64;

#[test]
fn gear5_and_verlet_agree_at_fine_dt() {
    // Two independent integrators agree within the sum of their own error estimates
    // (Richardson: error ~ last difference / (2^p - 1)).
    for case in &CASES {
        let g = sequence(case, Integrator::Gear5);
        let v = sequence(case, Integrator::Verlet);
        let mut qs: Vec<(&str, Quantity)> = vec![("e_n", |r| r.e_n), ("e_kin", |r| r.e_kin)];
        if case.mu > 0.0 {
            qs.push(("e_t", |r| r.e_t.unwrap()));
            qs.push(("omega_out", |r| r.omega_out * R / V));
        }
        for (q, f) in qs {
            let error = |recs: &[Record]| {
                let d = diffs(&recs.iter().map(f).collect::<Vec<_>>());
                let p = order(&d).clamp(0.5, 4.0);
                d[d.len() - 1] / (2f64.powf(p) - 1.0)
            };
            let (eg, ev) = (error(&g), error(&v));
            let (a, b) = (f(&g[DTS.len() - 1]), f(&v[DTS.len() - 1]));
            let gap = (a - b).abs();
            eprintln!(
                "agreement at dt_factor {}: {} {q}: |gear5 - verlet| = {gap:.2e} (error estimates {eg:.1e}, {ev:.1e})",
                DTS[DTS.len() - 1],
                case.name
            );
            assert!(gap <= 2.0 * (eg + ev) + 1e-12, "{} {q}: {gap:e}", case.name);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Mirror symmetry.
