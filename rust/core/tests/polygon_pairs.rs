//! Pairs with corners (docs/model.md, section 17.8): polygons with polygons and discs with
//! polygons, under the area law (parry's intersection, the chord's normal) and the linear law
//! (vertex springs).
//!
//! Expected values come from symmetry and mechanics: two mirror-image polygons head-on at +-v
//! are one polygon on the rigid plate at v (the mirror line is a rigid, frictionless wall);
//! turning the whole picture by pi and swapping the bodies is the same impact; an isolated
//! pair keeps its momentum and angular momentum; the integrators converge to one answer.

use restitution_core::{simulate, Initial, Integrator, NormalLaw, Partner, Record, Scene, Shape};

const V: f64 = 0.0357;
const R: f64 = 0.01;

fn run(scene: &Scene, init: &Initial) -> Record {
    simulate(scene, init).unwrap_or_else(|e| panic!("{e} for {scene:?} {init:?}"))
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

fn gon(n: usize) -> Shape {
    Shape::regular_polygon(R, n).unwrap()
}

fn with_partner(scene: Scene, partner: Shape) -> Scene {
    Scene {
        partner: Some(Partner::of(partner)),
        ..scene
    }
}

/// A polygon at phi head-on on the plate at v, and the pair of it with its mirror image
/// (phi2 = -phi) head-on at 2 v: the same e_n, spin, contact time and half the depth. The
/// linear law only face to face: corner against corner, its vertex springs measure each
/// corner's depth to the other body's edges, not to the mirror line (section 17.8).
#[test]
fn mirror_polygons_head_on_are_one_polygon_on_the_plate() {
    let laws = [
        (NormalLaw::Area, 0.0, "area, elastic"),
        (NormalLaw::Area, 0.3, "area, damped"),
    ];
    for (n, phi) in [(6, 7.0), (4, 20.0), (12, 3.0), (5, 90.0)] {
        for &(law, gamma, what) in &laws {
            // Gear-5 on the plate lands on the corners' crossings and the clip, on the pair it
            // steps through them (first order there): the two agree to the steps' error.
            for (integrator, tol) in [
                (Integrator::Gear5, 1e-4),
                (Integrator::Adaptive, 1e-7),
                (Integrator::Reference, 1e-9),
            ] {
                let plate = Scene {
                    shape: gon(n),
                    mu: 0.0,
                    gamma,
                    normal_law: law,
                    integrator,
                    tol: 1e-9,
                    dt_factor: 0.001,
                    ..Scene::default()
                };
                let pair = with_partner(plate.clone(), gon(n));
                let a = run(&plate, &Initial::from_angle(V, 90.0, 0.0, phi));
                let b = run(
                    &pair,
                    &Initial::from_angle(2.0 * V, 90.0, 0.0, phi).with_partner(0.0, -phi),
                );
                let what = format!("{n}-gon at {phi} deg, {what}, {integrator:?}");
                // Gear-5 on the plate lands on the corners' crossings, on the pair it steps
                // through them: the two agree to the steps' error.
                assert!(
                    rel(b.e_n, a.e_n) < tol,
                    "{what}: e_n {} vs {}",
                    b.e_n,
                    a.e_n
                );
                let spin = (b.omega_out - a.omega_out).abs() * R / V;
                assert!(
                    spin < tol,
                    "{what}: spin {} vs {}",
                    b.omega_out,
                    a.omega_out
                );
                assert!(
                    (b.partner_omega_out + b.omega_out).abs() * R / V < tol,
                    "{what}: the mirror spins back"
                );
                let tol = tol.max(1e-6);
                assert!(
                    rel(b.contact_time, a.contact_time) < tol,
                    "{what}: contact time"
                );
                // The deepest point is sampled where the centres' approach turns (the pair) or
                // the lowest corner's (the plate): a turning body puts them apart.
                assert!(
                    rel(0.5 * b.max_depth, a.max_depth) < 1e-4,
                    "{what}: depth {} vs {}",
                    0.5 * b.max_depth,
                    a.max_depth
                );
            }
        }
    }
}

/// The picture turned by pi with the bodies swapped: the same impact, the spins exchanged.
#[test]
fn swapping_the_bodies_gives_the_same_impact() {
    let shapes = [
        (gon(5), gon(7)),
        (Shape::Disc { r: R }, gon(4)),
        (gon(6), Shape::Disc { r: 1.3 * R }),
    ];
    for (a, b) in shapes {
        for integrator in [Integrator::Gear5, Integrator::Adaptive] {
            let scene = Scene {
                shape: a.clone(),
                mu: 0.4,
                gamma: 0.2,
                integrator,
                tol: 1e-9,
                partner: Some(Partner {
                    rho: Some(4000.0),
                    ..Partner::of(b.clone())
                }),
                ..Scene::default()
            };
            let swapped = Scene {
                shape: b.clone(),
                rho: 4000.0,
                partner: Some(Partner {
                    rho: Some(scene.rho),
                    ..Partner::of(a.clone())
                }),
                ..scene.clone()
            };
            for (theta, phi1, phi2, w1, w2) in
                [(35.0, 10.0, 40.0, 3.0, -2.0), (70.0, 80.0, 5.0, 0.0, 0.0)]
            {
                let x = run(
                    &scene,
                    &Initial::from_angle(V, theta, w1, phi1).with_partner(w2, phi2),
                );
                let y = run(
                    &swapped,
                    &Initial::from_angle(V, theta, w2, phi2 + 180.0).with_partner(w1, phi1 + 180.0),
                );
                let what = format!("{a:?} / {b:?} at {theta}, {integrator:?}");
                let tol = if integrator == Integrator::Gear5 {
                    1e-8
                } else {
                    1e-6
                };
                assert!(
                    (x.e_n - y.e_n).abs() < tol,
                    "{what}: e_n {} vs {}",
                    x.e_n,
                    y.e_n
                );
                assert!((x.e_kin - y.e_kin).abs() < tol, "{what}: e_kin");
                assert!(
                    (x.omega_out - y.partner_omega_out).abs() * R / V < tol
                        && (x.partner_omega_out - y.omega_out).abs() * R / V < tol,
                    "{what}: spins {} {} vs {} {}",
                    x.omega_out,
                    x.partner_omega_out,
                    y.partner_omega_out,
                    y.omega_out
                );
            }
        }
    }
}

/// An isolated pair keeps its momentum and its angular momentum, with friction and damping,
/// on every integrator; records are finite and end separated.
#[test]
fn polygon_pairs_conserve_momentum() {
    let shapes = [
        (gon(3), gon(4)),
        (gon(12), Shape::Disc { r: 0.7 * R }),
        (Shape::Disc { r: R }, gon(3)),
    ];
    for (a, b) in shapes {
        for integrator in [Integrator::Gear5, Integrator::Verlet, Integrator::Adaptive] {
            for law in [NormalLaw::Area, NormalLaw::Linear { kn: 2e8, cn: 20.0 }] {
                if integrator != Integrator::Gear5 && law != NormalLaw::Area {
                    continue; // refused (`linear_pairs_with_corners_take_gear5`)
                }
                let scene = Scene {
                    shape: a.clone(),
                    mu: 0.5,
                    gamma: 0.3,
                    normal_law: law,
                    integrator,
                    partner: Some(Partner::of(b.clone())),
                    ..Scene::default()
                };
                for (theta, phi1, phi2, w1) in [(20.0, 13.0, 71.0, 5.0), (60.0, 45.0, 0.0, -30.0)] {
                    let init = Initial::from_angle(V, theta, w1, phi1).with_partner(1.0, phi2);
                    let r = run(&scene, &init);
                    let what = format!("{a:?}/{b:?} {law:?} {integrator:?} at {theta}");
                    assert!(r.separated, "{what}: {r:?}");
                    assert!(r.momentum_residual.unwrap() < 1e-12, "{what}: {r:?}");
                    assert!(
                        r.angular_momentum_residual.unwrap().abs() < 1e-9,
                        "{what}: {r:?}"
                    );
                    assert!(r.e_n.is_finite() && r.energy_residual.is_finite(), "{what}");
                    assert!(
                        r.energy_out <= r.energy_in * (1.0 + 1e-6),
                        "{what}: damped and frictional: {r:?}"
                    );
                }
            }
        }
    }
}

/// Gear-5 converges with dt to the adaptive path's answer at a tight tolerance, and Verlet
/// to the same.
#[test]
fn polygon_pairs_converge_with_dt_and_the_integrators_agree() {
    let (a, b) = (gon(5), gon(6));
    let base = Scene {
        shape: a,
        mu: 0.3,
        gamma: 0.2,
        partner: Some(Partner::of(b)),
        ..Scene::default()
    };
    let init = Initial::from_angle(V, 40.0, 2.0, 17.0).with_partner(-1.0, 33.0);
    let reference = run(
        &Scene {
            integrator: Integrator::Adaptive,
            tol: 1e-10,
            ..base.clone()
        },
        &init,
    );
    let err = |integrator, dt_factor| {
        let r = run(
            &Scene {
                integrator,
                dt_factor,
                ..base.clone()
            },
            &init,
        );
        r.accuracy_distance(&reference, R, V)
    };
    for integrator in [Integrator::Gear5, Integrator::Verlet] {
        let (coarse, fine) = (err(integrator, 0.02), err(integrator, 0.0025));
        assert!(
            fine < 0.5 * coarse || fine < 1e-6,
            "{integrator:?}: {coarse:e} -> {fine:e}"
        );
        assert!(fine < 1e-3, "{integrator:?}: {fine:e}");
    }
}

/// The linear law on a pair with corners runs on Gear-5 only, and the others are refused
/// naming the integrator (vertex springs turn with the contact: docs/model.md, 17.8).
#[test]
fn linear_pairs_with_corners_take_gear5() {
    for integrator in [
        Integrator::Verlet,
        Integrator::Adaptive,
        Integrator::Reference,
    ] {
        let scene = Scene {
            shape: gon(5),
            normal_law: NormalLaw::Linear { kn: 2e7, cn: 0.0 },
            integrator,
            partner: Some(Partner::of(Shape::Disc { r: R })),
            ..Scene::default()
        };
        match simulate(&scene, &Initial::from_angle(V, 30.0, 0.0, 0.0)) {
            Err(restitution_core::Error::InvalidParameter { name, .. }) => {
                assert_eq!(name, "integrator")
            }
            other => panic!("{integrator:?}: {other:?}"),
        }
    }
}
