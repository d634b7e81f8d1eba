//! Polygon impacts: convergence of the regular n-gon to the exact disc, invariance under a
//! rotation by 2 pi / n, the energy audit for corner-first and face-first squares and
//! triangles, energy conservation without friction and damping at any orientation, and
//! re-contacts of a spinning polygon.

use proptest::prelude::*;
use restitution_core::{
    run_cases, simulate, simulate_with_trace, Case, Initial, Integrator, OverlapMethod, Record,
    Scene, Shape,
};

const R: f64 = 0.01;
const V: f64 = 0.0357;

fn gon(n: usize) -> Scene {
    Scene {
        shape: Shape::regular_polygon(R, n).unwrap(),
        ..Scene::default()
    }
}

/// Step of the n-gon -> disc comparison without friction. Frictionless polygons are integrated
/// more accurately than the disc (touch and separation located, refined steps), so at the
/// default step the exact disc's own integration error (|de_N| ~ 1e-6) would hide the
/// geometric difference beyond n ~ 1920; at a fifth of it the disc's is ~1e-7. With friction
/// both take the same plain fixed steps at the default dt, whose errors (stick/slip, order 1)
/// then largely cancel in the difference.
const FRICTIONLESS_DT_FACTOR: f64 = 0.002;

/// The paper sweep, thinned: theta from 4 to 89 degrees, mu from 0 to 1, no spin, phi0 = 0.
/// Debug builds run a smaller subset (the 4096-gon is slow unoptimised); CI runs --release.
fn sweep_cases(shape: &Shape) -> Vec<Case> {
    let (thetas, mus): (&[f64], &[f64]) = if cfg!(debug_assertions) {
        (&[10.0, 45.0, 89.0], &[0.0, 0.5])
    } else {
        (
            &[4.0, 10.0, 20.0, 30.0, 45.0, 60.0, 75.0, 89.0],
            &[0.0, 0.1, 0.5, 1.0],
        )
    };
    let mut cases = vec![];
    for &mu in mus {
        for &theta in thetas {
            cases.push(Case {
                scene: Scene {
                    shape: shape.clone(),
                    mu,
                    dt_factor: if mu == 0.0 {
                        FRICTIONLESS_DT_FACTOR
                    } else {
                        Scene::default().dt_factor
                    },
                    ..Scene::default()
                },
                init: Initial::from_angle(V, theta, 0.0, 0.0),
            });
        }
    }
    cases
}

/// Largest |difference| over the sweep for e_n, e_t, e_kin and omega_out (in units of v / r).
fn max_differences(a: &[Record], b: &[Record]) -> [f64; 4] {
    let mut m = [0.0f64; 4];
    for (a, b) in a.iter().zip(b) {
        m[0] = m[0].max((a.e_n - b.e_n).abs());
        m[1] = m[1].max((a.e_t.unwrap() - b.e_t.unwrap()).abs());
        m[2] = m[2].max((a.e_kin - b.e_kin).abs());
        m[3] = m[3].max((a.omega_out - b.omega_out).abs() * R / V);
    }
    m
}

#[test]
fn regular_ngon_converges_to_the_exact_disc() {
    let disc = run_cases(&sweep_cases(&Shape::disc(R).unwrap()), 0).unwrap();
    let ns = [6usize, 12, 30, 120, 480, 1920, 4096];
    let mut table = vec![];
    println!(
        "\n{:>5} {:>10} {:>10} {:>10} {:>10}   (largest |difference| from the exact disc over the sweep; omega in v/r)",
        "n", "e_n", "e_t", "e_kin", "omega_out"
    );
    for &n in &ns {
        let recs = run_cases(&sweep_cases(&Shape::regular_polygon(R, n).unwrap()), 0).unwrap();
        let m = max_differences(&recs, &disc);
        println!(
            "{n:>5} {:>10.2e} {:>10.2e} {:>10.2e} {:>10.2e}",
            m[0], m[1], m[2], m[3]
        );
        table.push((n as f64, m));
    }
    println!("observed order log(err_k / err_k+1) / log(n_k+1 / n_k):");
    for w in table.windows(2) {
        let ((n0, a), (n1, b)) = (w[0], w[1]);
        let order: Vec<String> = (0..4)
            .map(|k| format!("{:>6.2}", (a[k] / b[k]).ln() / (n1 / n0).ln()))
            .collect();
        println!("{n0:>5} -> {n1:<5} {}", order.join(" "));
    }
    let err = |n: usize| table.iter().find(|(m, _)| *m == n as f64).unwrap().1;
    // From n = 30 on, every quantity's largest error falls as n grows.
    for w in table[2..].windows(2) {
        for k in 0..4 {
            assert!(
                w[1].1[k] < w[0].1[k],
                "quantity {k}: no convergence from n = {} to {}",
                w[0].0,
                w[1].0
            );
        }
    }
    // The reference |de_N| of docs/model.md, section 11 (6.2e-3, 5.3e-5, 1.1e-6 for n = 120, 480, 1920 on a
    // reference kernel; 2.6e-2 at n = 30, before the asymptotic regime) sets the scale.
    for (n, reference) in [(120, 6.2e-3), (480, 5.3e-5), (1920, 1.1e-6)] {
        assert!(
            err(n)[0] < 2.0 * reference,
            "n {n}: |de_n| {:.2e} vs the reference {reference:.1e}",
            err(n)[0]
        );
    }
    // Beyond the first few edges in contact the convergence is at least quadratic in 1 / n
    // (the sliver between edges and arc is O(1 / n^2)).
    for k in 0..4 {
        let order = (err(120)[k] / err(1920)[k]).ln() / 16f64.ln();
        assert!(
            order > 1.2,
            "quantity {k}: order {order:.2} from n = 120 to 1920"
        );
    }
    assert!(err(4096).iter().all(|&e| e < 1e-5), "{:?}", err(4096));
}

#[test]
fn rotating_a_regular_ngon_by_one_period_changes_nothing() {
    // phi0 and phi0 + 360 / n place the same polygon; only round-off in the vertex
    // coordinates differs (the vertices are computed from different angles).
    for n in [3usize, 4, 5, 7, 120] {
        for &(theta, omega, phi0) in &[(20.0, 0.0, 0.0), (60.0, 5.0, 13.7), (35.0, -8.0, 200.0)] {
            let scene = gon(n);
            let a = simulate(&scene, &Initial::from_angle(V, theta, omega, phi0)).unwrap();
            let step = 360.0 / n as f64;
            for k in [1.0, -1.0, 2.0] {
                let b = simulate(
                    &scene,
                    &Initial::from_angle(V, theta, omega, phi0 + k * step),
                )
                .unwrap();
                let d = [
                    (a.e_n - b.e_n).abs(),
                    (a.e_t.unwrap() - b.e_t.unwrap()).abs(),
                    (a.e_kin - b.e_kin).abs(),
                    (a.omega_out - b.omega_out).abs() * R / V,
                ];
                assert!(
                    d.iter().all(|&x| x < 1e-10),
                    "n {n} theta {theta} omega {omega} phi0 {phi0} + {k} period: {d:?}"
                );
                assert_eq!(a.contacts, b.contacts);
                assert!((a.steps as i64 - b.steps as i64).abs() <= 1);
            }
        }
    }
}

/// Energy audit of one record: it separated, the balance closes, no energy gain, and the
/// contact forces do no positive work.
fn assert_audit(rec: &Record, what: &str) {
    assert!(rec.separated && !rec.timed_out, "{what}: {rec:?}");
    assert!(
        rec.energy_residual.abs() < 1e-6,
        "{what}: residual {:e}",
        rec.energy_residual
    );
    assert!(
        rec.energy_out <= rec.energy_in * (1.0 + 1e-6),
        "{what}: energy gain {:e}",
        rec.energy_out / rec.energy_in - 1.0
    );
    assert!(rec.work_normal <= 1e-6 * rec.energy_in, "{what}: {rec:?}");
    assert!(rec.work_friction <= 1e-6 * rec.energy_in, "{what}: {rec:?}");
}

#[test]
fn energy_audit_for_corner_first_and_face_first_squares_and_triangles() {
    // (n, phi0 with a vertex straight down, phi0 with an edge flat on the plate).
    let mut worst: f64 = 0.0;
    for (n, corner, face) in [(4usize, 0.0, 45.0), (3, 30.0, 90.0)] {
        for (first, phi0) in [("corner", corner), ("face", face)] {
            for mu in [0.0, 0.5, 1.0] {
                for theta in [10.0, 30.0, 60.0, 90.0] {
                    for omega in [-10.0, 0.0, 10.0] {
                        let scene = Scene { mu, ..gon(n) };
                        let rec =
                            simulate(&scene, &Initial::from_angle(V, theta, omega, phi0)).unwrap();
                        let what =
                            format!("{n}-gon {first}-first mu {mu} theta {theta} omega {omega}");
                        assert_audit(&rec, &what);
                        worst = worst.max(rec.energy_residual.abs());
                    }
                }
            }
        }
    }
    println!("largest |energy_residual| over squares and triangles: {worst:.2e}");
}

#[test]
fn the_parry_path_gives_the_same_impact() {
    // The two overlap paths agree to round-off at every step, so whole impacts agree closely
    // (friction's stick/slip decisions could amplify round-off; they do not here).
    for (n, phi0) in [(4usize, 0.0), (3, 90.0), (120, 0.0), (7, 11.0)] {
        for theta in [15.0, 50.0] {
            let init = Initial::from_angle(V, theta, 2.0, phi0);
            let a = simulate(&gon(n), &init).unwrap();
            let b = simulate(
                &Scene {
                    overlap: OverlapMethod::Parry,
                    ..gon(n)
                },
                &init,
            )
            .unwrap();
            assert!(
                (a.e_n - b.e_n).abs() < 1e-10 && (a.omega_out - b.omega_out).abs() * R / V < 1e-10,
                "{n}-gon theta {theta}: {a:?} vs {b:?}"
            );
            assert_eq!(a.contacts, b.contacts);
            assert_audit(&b, "parry path");
        }
    }
}

#[test]
fn a_spinning_square_hits_again_and_the_contacts_are_counted() {
    // Corner first at a shallow angle with backspin: the first corner's contact ends, the
    // square keeps turning and the next corner reaches the plate before the square clears it.
    let scene = gon(4);
    for (theta, omega) in [(10.0, -20.0), (20.0, 20.0), (5.0, 5.0)] {
        let (rec, tr) =
            simulate_with_trace(&scene, &Initial::from_angle(V, theta, omega, 0.0)).unwrap();
        assert_audit(&rec, &format!("square theta {theta} omega {omega}"));
        // Contacts = runs of positive depth in the trace, with free flight between them.
        let mut runs = 0;
        let mut inside = true; // the trace starts at first touch
        for &d in &tr.depth[1..] {
            if d > 0.0 && !inside {
                runs += 1;
            }
            inside = d > 0.0;
        }
        assert_eq!(rec.contacts, runs + 1, "theta {theta} omega {omega}");
        assert!(rec.contacts >= 2, "theta {theta} omega {omega}: {rec:?}");
        // It stopped only once no part of it could reach the plate again.
        let k = tr.t.len() - 1;
        let (y, vy, w) = (tr.y[k], tr.vy[k], tr.omega[k]);
        assert!(tr.depth[k] < 0.0 && vy > 0.0 && (y >= R || vy > R * w.abs()));
        // The contact time covers only the overlaps, not the flight in between.
        let overlap_steps = tr.depth.iter().filter(|&&d| d > 0.0).count() as f64;
        let dt = tr.t[1] - tr.t[0];
        assert!((rec.contact_time - overlap_steps * dt).abs() <= 2.0 * rec.contacts as f64 * dt);
    }
    // Without friction and damping the re-contacts conserve energy too.
    let elastic = Scene {
        mu: 0.0,
        gamma: 0.0,
        ..gon(4)
    };
    let rec = simulate(&elastic, &Initial::from_angle(V, 10.0, -20.0, 0.0)).unwrap();
    assert!(rec.contacts >= 2);
    assert!(
        (rec.energy_out / rec.energy_in - 1.0).abs() < 1e-6,
        "{rec:?}"
    );
}

fn random_convex(angles: &[f64], stretch: f64) -> Shape {
    let mut a = angles.to_vec();
    a.sort_by(f64::total_cmp);
    let v: Vec<[f64; 2]> = a
        .iter()
        .map(|t| [R * t.cos(), R * stretch * t.sin()])
        .collect();
    Shape::convex_polygon(&v).unwrap_or_else(|_| Shape::regular_polygon(R, 5).unwrap())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(if cfg!(debug_assertions) { 4 } else { 32 }))]

    /// The area law is conservative for any convex polygon at any orientation (its potential
    /// is (E / L) times the overlap's first moment, torque included): the reference
    /// integrator, which locates touch and separation, closes the balance to round-off. The
    /// default integrator ends every such impact (re-contacts included) and never lets the
    /// plate push sideways.
    #[test]
    fn frictionless_undamped_impacts_conserve_energy(
        n in 3usize..9,
        angles in prop::collection::vec(0.0..std::f64::consts::TAU, 3..9),
        stretch in 0.5f64..1.0,
        regular in any::<bool>(),
        phi0 in 0.0f64..360.0,
        theta in 5.0f64..90.0,
        omega in -10.0f64..10.0,
    ) {
        let shape = if regular {
            Shape::regular_polygon(R, n).unwrap()
        } else {
            random_convex(&angles, stretch)
        };
        let init = Initial::from_angle(V, theta, omega, phi0);
        let scene = Scene { shape, mu: 0.0, gamma: 0.0, ..Scene::default() };
        let rec = simulate(&Scene { integrator: Integrator::Reference, ..scene.clone() }, &init)
            .unwrap();
        prop_assert!((rec.energy_out / rec.energy_in - 1.0).abs() < 1e-9,
            "energy change {:e}", rec.energy_out / rec.energy_in - 1.0);
        let rec = simulate(&scene, &init).unwrap();
        prop_assert!(rec.separated && !rec.timed_out, "{:?}", rec);
        prop_assert_eq!(rec.work_friction, 0.0);
        // Without friction the plate exerts no tangential force: v_x is untouched (up to the
        // integrator's rescaling of its Taylor terms).
        prop_assert!((rec.e_t.unwrap() - 1.0).abs() < 1e-14, "e_t {:?}", rec.e_t);
    }
}

/// Elastic, frictionless impacts of squares and triangles with Gear-5 and Verlet: largest
/// |energy_out / energy_in - 1| over orientations phi0 (degrees), angles and spins.
fn elastic_energy_error(integrator: Integrator, dt_factor: f64, n: usize, phis: &[f64]) -> f64 {
    let mut worst: f64 = 0.0;
    for &phi0 in phis {
        for theta in [30.0, 60.0, 80.0, 90.0] {
            for omega in [-3.0, 0.0, 3.0] {
                let scene = Scene {
                    mu: 0.0,
                    gamma: 0.0,
                    integrator,
                    dt_factor,
                    ..gon(n)
                };
                let rec = simulate(&scene, &Initial::from_angle(V, theta, omega, phi0)).unwrap();
                assert!(rec.separated && !rec.timed_out);
                worst = worst.max((rec.energy_out / rec.energy_in - 1.0).abs());
            }
        }
    }
    worst
}

#[test]
fn fixed_step_energy_error_without_friction_and_damping() {
    // Gear-5 (the default) conserves energy to ~1e-8 at the default dt, corner or face first:
    // touch and separation are located inside the step and the integrator restarts there on
    // the new branch (face first the force grows linearly from touch), and steps in which the
    // force changes faster than they resolve (a sliver left when an edge lifts off) are
    // refined. Verlet's energy error is its own O(dt^2) one (a symplectic method conserves a
    // modified energy, which jumps where the polygon's stiffness does, when a corner crosses
    // the plate): it must shrink like dt^2.
    for (n, corner, face) in [(4usize, 0.0, 45.0), (3, 30.0, 90.0)] {
        let phis = [corner, corner + 7.0, face, face + 1.0];
        let g = elastic_energy_error(Integrator::Gear5, 0.01, n, &phis);
        println!("Gear5 {n}-gon: |dE|/E <= {g:.1e} at the default dt_factor 0.01");
        assert!(g < 1e-7, "Gear5 {n}-gon: {g:e}");
        let coarse = elastic_energy_error(Integrator::Verlet, 0.01, n, &[face]);
        let fine = elastic_energy_error(Integrator::Verlet, 0.0025, n, &[face]);
        let order = (coarse / fine).ln() / 4f64.ln();
        let c = elastic_energy_error(Integrator::Verlet, 0.01, n, &[corner, corner + 7.0]);
        println!(
            "Verlet {n}-gon: corner first {c:.1e}; face first {coarse:.1e} at dt_factor 0.01, {fine:.1e} at 0.0025 (order {order:.2})"
        );
        assert!(order > 1.8, "Verlet {n}-gon face first: order {order:.2}");
    }
}

#[test]
fn face_first_elastic_impacts_conserve_energy_at_the_default_dt() {
    // docs/model.md, section 11: mu = 0 and gamma = 0 conserve energy for any polygon and orientation, and no
    // impact gains more than 1e-6 at the default dt (Gear-5 gained up to 1.1e-5 here before
    // touch and separation were located inside the step).
    for (n, face) in [(4usize, 45.0), (3, 90.0)] {
        let e = elastic_energy_error(Integrator::Gear5, 0.01, n, &[face, face + 1.0]);
        assert!(e < 1e-7, "{n}-gon face first: |dE|/E {e:.2e}");
    }
}
