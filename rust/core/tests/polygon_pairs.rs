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

/// Gear-5's distance from the reference (`scene`'s integrator) at dt_factor 1e-2, 1e-3, 1e-4.
fn gear5_from_the_reference(scene: &Scene, init: &Initial) -> [f64; 3] {
    let reference = run(scene, init);
    [1e-2, 1e-3, 1e-4].map(|dt_factor| {
        let gear5 = Scene {
            integrator: Integrator::Gear5,
            dt_factor,
            ..scene.clone()
        };
        run(&gear5, init).accuracy_distance(&reference, R, V)
    })
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
                if integrator == Integrator::Verlet && law != NormalLaw::Area {
                    continue; // refused (`linear_pairs_with_corners_refuse_verlet`)
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

/// The linear law on a pair with corners is refused on Verlet only, naming the integrator (a
/// corner's dashpot jumps as it enters the other body: docs/model.md, 17.8); Gear-5, the
/// adaptive path and the reference run it.
#[test]
fn linear_pairs_with_corners_refuse_verlet() {
    for integrator in Integrator::ALL {
        let scene = Scene {
            shape: gon(5),
            normal_law: NormalLaw::Linear { kn: 2e7, cn: 0.0 },
            integrator,
            partner: Some(Partner::of(Shape::Disc { r: R })),
            ..Scene::default()
        };
        match simulate(&scene, &Initial::from_angle(V, 30.0, 0.0, 0.0)) {
            Err(restitution_core::Error::InvalidParameter { name, .. })
                if integrator == Integrator::Verlet =>
            {
                assert_eq!(name, "integrator")
            }
            Ok(r) if integrator != Integrator::Verlet => assert!(r.separated, "{r:?}"),
            other => panic!("{integrator:?}: {other:?}"),
        }
    }
}

/// The linear law's vertex springs on the adaptive path (held between their switches,
/// docs/model.md 17.8): against the reference, the error of e_N, e_T, e_kin and omega r / v
/// is at most 3 tol at tol 1e-6 over corners meeting edges at turned orientations (polygon
/// pairs, a disc with a triangle; elastic and damped, frictionless to mu = 2, one contact
/// or several), and the reference's impact is the exchanged one's, the bodies swapped.
#[test]
fn linear_pairs_with_corners_meet_the_tolerance_and_exchange() {
    let shapes = [
        (gon(3), gon(5)),
        (gon(4), gon(4)),
        (Shape::Disc { r: 1.3 * R }, gon(3)),
        (gon(6), Shape::regular_polygon(0.7 * R, 12).unwrap()),
    ];
    let tol = 1e-6;
    for (a, b) in &shapes {
        for (mu, cn) in [(0.0, 0.0), (0.6, 20.0), (2.0, 200.0)] {
            for theta in [5.0, 30.0, 60.0, 89.0] {
                for (phi1, phi2) in [(13.0, 71.0), (45.0, 10.0)] {
                    let scene = Scene {
                        shape: a.clone(),
                        mu,
                        normal_law: NormalLaw::Linear { kn: 2e8, cn },
                        integrator: Integrator::Adaptive,
                        tol,
                        partner: Some(Partner::of(b.clone())),
                        ..Scene::default()
                    };
                    let reference = Scene {
                        integrator: Integrator::Reference,
                        ..scene.clone()
                    };
                    let init = Initial::from_angle(V, theta, 2.0, phi1).with_partner(-1.0, phi2);
                    let what = format!(
                        "{a:?} / {b:?}, mu {mu}, cn {cn}, theta {theta}, phi {phi1} {phi2}"
                    );
                    let (x, y) = (run(&scene, &init), run(&reference, &init));
                    let err = x.accuracy_distance(&y, R, V);
                    assert!(err <= 3.0 * tol, "{what}: error {err:e}");
                    let swapped = Scene {
                        shape: b.clone(),
                        partner: Some(Partner::of(a.clone())),
                        ..reference.clone()
                    };
                    let z = run(
                        &swapped,
                        &Initial::from_angle(V, theta, -1.0, phi2 + 180.0)
                            .with_partner(2.0, phi1 + 180.0),
                    );
                    assert!(
                        (z.e_n - y.e_n).abs() < 1e-8 && (z.e_kin - y.e_kin).abs() < 1e-8,
                        "{what}: exchanged e_n {} vs {}",
                        z.e_n,
                        y.e_n
                    );
                    assert!(
                        (z.omega_out - y.partner_omega_out).abs() * R / V < 1e-8,
                        "{what}: exchanged spins"
                    );
                }
            }
        }
    }
}

/// Gear-5, which steps through the corners' entries, converges to the adaptive path's answer
/// at first order (the error shrinks about tenfold per tenfold smaller step; at 89 deg e_T,
/// divided by the small tangential speed, is off by 0.15, 0.024, 0.0024).
#[test]
fn linear_pairs_with_corners_gear5_converges_to_the_adaptive_path() {
    let cases = [
        (gon(4), gon(4), 2.0, 20.0, 89.0, 45.0, 10.0),
        (
            Shape::Disc { r: 1.3 * R },
            gon(3),
            2.0,
            0.0,
            89.0,
            45.0,
            10.0,
        ),
        (gon(3), gon(5), 0.3, 0.0, 60.0, 13.0, 71.0),
    ];
    for (a, b, mu, cn, theta, phi1, phi2) in cases {
        let scene = Scene {
            shape: a.clone(),
            mu,
            normal_law: NormalLaw::Linear { kn: 2e8, cn },
            integrator: Integrator::Reference,
            partner: Some(Partner::of(b.clone())),
            ..Scene::default()
        };
        let init = Initial::from_angle(V, theta, 2.0, phi1).with_partner(-1.0, phi2);
        let errors = gear5_from_the_reference(&scene, &init);
        assert!(
            errors[1] < 0.3 * errors[0] && errors[2] < 0.3 * errors[1],
            "{a:?} / {b:?}: Gear-5 errors {errors:?}"
        );
    }
}

/// A corner entering with its dashpot makes the normal force, and the cone, jump: a slip
/// whose cone grows past the friction it exerts sticks there, the spring keeping that force.
/// Following the cone up instead, the spring was charged with no work done and gave it back:
/// twin pentagons at mu = 1000, damped, gained 24 % energy on the adaptive path and the
/// reference. Now friction does no positive work, the impact loses energy, and Gear-5
/// converges to the reference's e_n (1.41436, 1.41419 at dt_factor 1e-3, 1e-4).
#[test]
fn a_slip_sticks_where_an_entering_corner_widens_the_cone() {
    let shape = gon(5);
    let mass = 2500.0 * shape.area();
    let scene = Scene {
        shape: shape.clone(),
        mu: 1000.0,
        gamma_t: 0.5,
        normal_law: NormalLaw::Linear {
            kn: 1e5,
            cn: 0.4 * (1e5 * mass).sqrt(),
        },
        integrator: Integrator::Reference,
        partner: Some(Partner::of(shape)),
        ..Scene::default()
    };
    let w = 0.9940472390221615 * V / R;
    let init = Initial::from_angle(V, 27.436818147914295, w, 161.9411858764498)
        .with_partner(-0.5 * w, 0.0);
    let reference = run(&scene, &init);
    assert!(reference.work_friction <= 0.0, "{reference:?}");
    assert!(reference.energy_out < reference.energy_in, "{reference:?}");
    let adaptive = run(
        &Scene {
            integrator: Integrator::Adaptive,
            ..scene.clone()
        },
        &init,
    );
    assert!((adaptive.e_n - reference.e_n).abs() < 3e-6, "{adaptive:?}");
    let gear5 = run(
        &Scene {
            integrator: Integrator::Gear5,
            dt_factor: 1e-3,
            ..scene.clone()
        },
        &init,
    );
    assert!(
        (gear5.e_n - reference.e_n).abs() < 1e-3,
        "{gear5:?} vs {reference:?}"
    );
}

/// Gear-5 steps the tangential law of section 5 as it is written, and the adaptive path is
/// its continuous limit: with friction too they converge to one answer (first order for
/// Gear-5, at the springs' unlocated switches). Three ways they once parted, each converging
/// to its own answer (e_T 0.04 apart at dt_factor 1e-4): twin 120-gons whose normal force is
/// clipped and released while they overlap (the adaptive path reset the spring at the
/// release, its dashpot's whole force acting at once); twin 120-gons where a corner leaves
/// during a slip, its pulling dashpot gone and the cone wider (the adaptive path slipped on
/// where the stepped law sticks); twin triangles whose touch's probe met a chord of 2e-16 m,
/// its normal across the springs' push, which turned the contact's normal into the partner
/// (friction's sign reversed at the touch).
#[test]
fn frictional_linear_pairs_gear5_converges_to_the_reference() {
    // (n, mu, theta, omega_in r / v, phi1, phi2): damped (zeta 0.2, gamma_t 0.5), kn 1e5.
    let cases = [
        (120, 10.0, 85.0, 0.0014, 135.0, 0.0),
        (120, 0.3, 85.0, 0.5, 306.22, 144.24),
        (3, 0.3, 60.0, 0.5, 301.41, 261.70),
    ];
    for (n, mu, theta, w, phi1, phi2) in cases {
        let shape = gon(n);
        let mass = 2500.0 * shape.area();
        let scene = Scene {
            shape: shape.clone(),
            mu,
            gamma_t: 0.5,
            normal_law: NormalLaw::Linear { kn: 0.0, cn: 0.0 }.with_scale(1e5, 0.2, mass),
            integrator: Integrator::Reference,
            partner: Some(Partner::of(shape)),
            ..Scene::default()
        };
        let init = Initial::from_angle(V, theta, w * V / R, phi1).with_partner(0.0, phi2);
        let errors = gear5_from_the_reference(&scene, &init);
        assert!(
            errors[1] < 0.3 * errors[0] && errors[2] < 0.3 * errors[1] && errors[2] < 1e-3,
            "{n}-gons, mu {mu}, theta {theta}: Gear-5's distance from the reference {errors:?}"
        );
    }
}

/// The adaptive path at its largest step (dt_factor 1, the Python default) meets its tolerance
/// on linear-law pairs (at most 3 tol from the reference in e_N, e_T, e_kin and omega_out r / v).
/// Three ways it once missed by far more, whatever the tolerance: the first stage of the step
/// from touch lacked the dashpot's force c_n v_n (evaluated at the touch itself, where no
/// overlap acts), losing 9 % of that step's impulse (two damped discs: 7 tol at tol 1e-6, 20 tol
/// at 1e-10); twin 120-gons whose clipped force an entering corner turned to pushing for less
/// than a step stayed clipped (damped: e_N 0.035 off at every tol); and twin 120-gons whose
/// slip the entering corners ended for less than a step kept slipping (elastic: 2e-5 off at tol
/// 1e-8).
#[test]
fn linear_pairs_meet_the_tolerance_at_the_largest_step() {
    // (n, mu, damped, theta, omega_in r / v, phi1, phi2); n = 0: two discs.
    let cases = [
        (0, 0.0, true, 89.0, 0.0, 0.0, 0.0),
        (0, 0.3, true, 20.0, 0.5, 263.58, 164.99),
        (120, 0.3, true, 20.0, -2.0, 314.10, 199.54),
        (120, 0.3, false, 20.0, 0.0, 89.33, 228.40),
    ];
    for (n, mu, damped, theta, w, phi1, phi2) in cases {
        let shape = if n == 0 { Shape::Disc { r: R } } else { gon(n) };
        let mass = 2500.0 * shape.area();
        let zeta = if damped { 0.2 } else { 0.0 };
        let scene = Scene {
            shape: shape.clone(),
            mu,
            gamma_t: if damped { 0.5 } else { 0.0 },
            normal_law: NormalLaw::Linear { kn: 0.0, cn: 0.0 }.with_scale(1e5, zeta, mass),
            integrator: Integrator::Reference,
            partner: Some(Partner::of(shape)),
            ..Scene::default()
        };
        let init = Initial::from_angle(V, theta, w * V / R, phi1).with_partner(0.0, phi2);
        let reference = run(&scene, &init);
        for tol in [1e-6, 1e-8] {
            let adaptive = Scene {
                integrator: Integrator::Adaptive,
                dt_factor: 1.0,
                tol,
                ..scene.clone()
            };
            let err = run(&adaptive, &init).accuracy_distance(&reference, R, V);
            assert!(
                err <= 3.0 * tol,
                "n {n}, mu {mu}, damped {damped}, theta {theta}, tol {tol}: error {:.2} tol",
                err / tol
            );
        }
    }
}
