//! Two bodies (docs/model.md, section 17): a disc or sphere colliding with a free partner.
//!
//! Expected values come from symmetry and mechanics, never from the engine's own output:
//! two identical bodies at +-v are one body on the rigid plate at v (the mirror plane between
//! them is a rigid, frictionless wall); a rigid, heavy, huge partner is the plate; frictionless
//! central forces conserve the relative angular momentum, which ties the two normal
//! restitutions together exactly; swapping particle and partner, or mirroring the impact,
//! gives the same impact seen differently; momentum is conserved.

use restitution_core::{
    simulate, simulate_with_trace, Error, Initial, Integrator, NormalLaw, Partner, Record, Scene,
    Shape,
};

const V: f64 = 0.0357;
const R: f64 = 0.01;
const BOTH: [Integrator; 2] = [Integrator::Gear5, Integrator::Verlet];

fn disc_pair(scene: Scene) -> Scene {
    Scene {
        partner: Some(Partner::of(Shape::Disc { r: R })),
        ..scene
    }
}

fn run(scene: &Scene, init: &Initial) -> Record {
    simulate(scene, init).unwrap_or_else(|e| panic!("{e} for {scene:?} {init:?}"))
}

/// The Hertz spheres of Chung & Ooi's Test 1 and 2 (glass: E = 48 GPa, nu = 0.2,
/// rho = 2800, R = 0.01 m), elastic.
fn glass_sphere() -> Scene {
    Scene {
        shape: Shape::sphere(0.01).unwrap(),
        rho: 2800.0,
        e_modulus: 4.8e10,
        mu: 0.0,
        normal_law: NormalLaw::Hertz {
            nu: 0.2,
            plate: None,
            cor: 1.0,
        },
        ..Scene::default()
    }
}

/// Relative difference, for messages and bounds.
fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

/// The plate scene and its pair of identical bodies head-on at +-v: the same force history
/// step by step, contact time, e_N and depth (the pair's overlap is twice the plate's depth).
fn check_identical_pair_is_the_plate(plate: &Scene, v: f64, what: &str) {
    let pair = Scene {
        partner: Some(Partner::of(plate.shape.clone())),
        ..plate.clone()
    };
    let (a, ta) = simulate_with_trace(plate, &Initial::from_angle(v, 90.0, 0.0, 0.0)).unwrap();
    let (b, tb) =
        simulate_with_trace(&pair, &Initial::from_angle(2.0 * v, 90.0, 0.0, 0.0)).unwrap();
    assert_eq!(a.steps, b.steps, "{what}");
    assert!(
        rel(b.e_n, a.e_n) < 1e-12,
        "{what}: e_n {} vs {}",
        b.e_n,
        a.e_n
    );
    assert!(
        rel(b.contact_time, a.contact_time) < 1e-12,
        "{what}: contact time"
    );
    assert!(rel(0.5 * b.max_depth, a.max_depth) < 1e-12, "{what}: depth");
    let peak = ta.f_n.iter().cloned().fold(0.0, f64::max);
    for (k, (fa, fb)) in ta.f_n.iter().zip(&tb.f_n).enumerate() {
        assert!(
            (fa - fb).abs() < 1e-12 * peak,
            "{what}: step {k}: force {fb} vs {fa}"
        );
    }
}

#[test]
fn identical_discs_head_on_are_one_disc_on_the_plate() {
    for integrator in BOTH {
        for normal_law in [NormalLaw::Area, NormalLaw::Linear { kn: 1e7, cn: 300.0 }] {
            let plate = Scene {
                integrator,
                normal_law,
                ..Scene::default()
            };
            check_identical_pair_is_the_plate(&plate, V, &format!("{integrator:?} {normal_law:?}"));
        }
    }
}

#[test]
fn identical_spheres_head_on_are_one_sphere_on_the_plate() {
    // Chung & Ooi: Test 1 (two spheres, 10 m/s each) is Test 2 (one sphere on a rigid plate).
    for integrator in BOTH {
        for cor in [1.0, 0.5] {
            let plate = Scene {
                integrator,
                normal_law: NormalLaw::Hertz {
                    nu: 0.2,
                    plate: None,
                    cor,
                },
                ..glass_sphere()
            };
            check_identical_pair_is_the_plate(&plate, 10.0, &format!("{integrator:?} cor {cor}"));
        }
    }
}

/// A partner ever larger, heavier and stiffer: the oblique, frictional impact tends to the
/// plate's (e_N, e_T, spin), the distance falling with each step of the partner. (In 2D a
/// large body is compliant: its share of the series length L goes as (E1/E2)^(2/3) r2^(1/3),
/// so E2 grows as r2^2 here.)
#[test]
fn rigid_heavy_huge_partner_tends_to_the_plate() {
    let base = Scene {
        mu: 0.3,
        ..Scene::default()
    };
    let init = Initial::from_angle(V, 35.0, 0.0, 0.0);
    let plate = run(&base, &init);
    let mut last = f64::INFINITY;
    for scale in [1e2, 1e4, 1e6] {
        let partner = Partner {
            shape: Shape::Disc { r: R * scale },
            rho: Some(2500.0 * scale),
            e_modulus: Some(1e7 * scale * scale),
            nu: None,
        };
        let pair = Scene {
            partner: Some(partner),
            ..base.clone()
        };
        let rec = run(&pair, &init);
        let dist = rec.accuracy_distance(&plate, R, V);
        assert!(dist < last, "scale {scale}: {dist:e} after {last:e}");
        last = dist;
    }
    assert!(last < 1e-4, "{last:e}");
}

/// Frictionless central forces conserve the relative angular momentum, and the centres are
/// r1 + r2 apart at touch and at separation, so g'.t_s = g.t_0: hence
/// e_n = e_n_sep cos(dpsi) + cot(theta) sin(dpsi) exactly, elastic or damped.
#[test]
fn frictionless_pairs_obey_the_identity_of_the_two_normal_restitutions() {
    for integrator in BOTH {
        for (gamma, law) in [
            (0.0, NormalLaw::Area),
            (0.33, NormalLaw::Area),
            (0.0, NormalLaw::Linear { kn: 1e7, cn: 500.0 }),
        ] {
            let scene = disc_pair(Scene {
                mu: 0.0,
                gamma,
                normal_law: law,
                integrator,
                ..Scene::default()
            });
            for theta in [0.3, 1.0, 5.0, 20.0, 60.0, 89.0] {
                let rec = run(&scene, &Initial::from_angle(1.0, theta, 0.0, 0.0));
                let (s, c) = rec.normal_rotation_deg.to_radians().sin_cos();
                let cot = 1.0 / (theta as f64).to_radians().tan();
                let want = rec.e_n_sep * c + cot * s;
                assert!(
                    (rec.e_n - want).abs() < 1e-10 * (1.0 + cot),
                    "{integrator:?} gamma {gamma} theta {theta}: e_n {} vs {want}",
                    rec.e_n
                );
            }
        }
    }
}

/// Elastic, frictionless discs: e_n_sep = 1 and e_kin = 1 to the integrator's error, while
/// e_n < 0 exactly where the line of centres turns by more than theta (from the identity with
/// e_n_sep = 1: e_n < 0 iff |dpsi| > theta), which happens at grazing incidence.
#[test]
fn elastic_discs_reach_negative_e_n_where_the_pair_turns_by_more_than_theta() {
    let scene = disc_pair(Scene {
        mu: 0.0,
        gamma: 0.0,
        ..Scene::default()
    });
    let mut negative = 0;
    for v in [0.0357, 1.0] {
        for theta in [0.2, 0.5, 1.0, 2.0, 5.0, 30.0] {
            let rec = run(&scene, &Initial::from_angle(v, theta, 0.0, 0.0));
            assert!((rec.e_n_sep - 1.0).abs() < 1e-6, "e_n_sep {}", rec.e_n_sep);
            assert!((rec.e_kin - 1.0).abs() < 1e-6, "e_kin {}", rec.e_kin);
            let turned = rec.normal_rotation_deg.abs();
            assert!(
                rec.normal_rotation_deg <= 0.0,
                "the pair turns clockwise for g_t > 0"
            );
            if (turned - theta).abs() > 1e-6 {
                assert_eq!(
                    rec.e_n < 0.0,
                    turned > theta,
                    "v {v} theta {theta}: {rec:?}"
                );
            }
            negative += usize::from(rec.e_n < 0.0);
        }
    }
    assert!(negative >= 4, "only {negative} negative e_n");
}

/// Swapping particle and partner is the same impact turned by 180 degrees: the same g, the
/// spins exchanged.
#[test]
fn swapping_particle_and_partner_gives_the_same_impact() {
    let small = (0.007, 2000.0);
    let large = (0.013, 3100.0);
    let scene = |own: (f64, f64), other: (f64, f64)| Scene {
        shape: Shape::Disc { r: own.0 },
        rho: own.1,
        mu: 0.4,
        partner: Some(Partner {
            shape: Shape::Disc { r: other.0 },
            rho: Some(other.1),
            e_modulus: Some(2e7),
            nu: None,
        }),
        e_modulus: 1e7,
        ..Scene::default()
    };
    let swapped = |s: Scene| Scene {
        e_modulus: 2e7,
        partner: s.partner.map(|p| Partner {
            e_modulus: Some(1e7),
            ..p
        }),
        ..s
    };
    for integrator in BOTH {
        let a_scene = Scene {
            integrator,
            ..scene(small, large)
        };
        let b_scene = Scene {
            integrator,
            ..swapped(scene(large, small))
        };
        for (theta, w1, w2) in [(30.0, 0.0, 0.0), (60.0, 2.0, -1.0), (10.0, -3.0, 4.0)] {
            let a = run(
                &a_scene,
                &Initial::from_angle(V, theta, w1, 0.0).with_partner(w2, 0.0),
            );
            let b = run(
                &b_scene,
                &Initial::from_angle(V, theta, w2, 0.0).with_partner(w1, 0.0),
            );
            for (x, y, what) in [
                (a.e_n, b.e_n, "e_n"),
                (a.e_n_sep, b.e_n_sep, "e_n_sep"),
                (a.e_kin, b.e_kin, "e_kin"),
                (a.omega_out, b.partner_omega_out, "spins"),
                (a.partner_omega_out, b.omega_out, "spins"),
            ] {
                assert!(
                    (x - y).abs() < 1e-9 * (1.0 + x.abs()),
                    "{integrator:?} {theta}: {what} {x} {y}"
                );
            }
        }
    }
}

/// The mirror image (g_x, omega1, omega2) -> (-g_x, -omega1, -omega2) gives the mirrored
/// record: e_n, e_n_sep, e_kin, e_t equal, spins and the normal's turn negated.
#[test]
fn mirror_image_gives_the_mirrored_record() {
    for integrator in BOTH {
        let scene = disc_pair(Scene {
            mu: 0.6,
            integrator,
            ..Scene::default()
        });
        for (theta, w1, w2) in [(25.0, 1.0, -2.0), (70.0, 0.0, 3.0)] {
            let init = Initial::from_angle(V, theta, w1, 0.0).with_partner(w2, 0.0);
            let mirror = Initial {
                vx: -init.vx,
                omega: -w1,
                partner_omega: -w2,
                ..init
            };
            let (a, b) = (run(&scene, &init), run(&scene, &mirror));
            assert_eq!(a.e_n, b.e_n);
            assert_eq!(a.e_kin, b.e_kin);
            assert_eq!(a.e_t, b.e_t);
            assert_eq!(a.omega_out, -b.omega_out);
            assert_eq!(a.partner_omega_out, -b.partner_omega_out);
            assert_eq!(a.normal_rotation_deg, -b.normal_rotation_deg);
        }
    }
}

/// An isolated pair conserves linear and angular momentum (about its centre of mass) to 1e-12
/// (the bound): with friction, damping, spins and unequal bodies. Linear momentum by
/// construction (the centre of mass is not integrated), angular momentum because both bodies
/// feel their force at one point, and the integrators restore it by a rigid turn of the pair
/// (`Pair::restoring_turn`: the adaptive path after every step, the fixed steps on the final
/// state; Gear-5 and the adaptive path drifted by up to 1.2e-10 and 2.6e-5 tol without it).
/// The turn changes no contact velocity, so it takes Gear-5 no further from the reference than
/// its own error: with an undamped tangential spring, where the drift was largest, its distance
/// from the reference still falls with the step.
#[test]
fn an_isolated_pair_conserves_momentum() {
    let scene = Scene {
        mu: 0.8,
        partner: Some(Partner {
            shape: Shape::Disc { r: 0.004 },
            rho: Some(7800.0),
            e_modulus: None,
            nu: None,
        }),
        ..Scene::default()
    };
    for integrator in Integrator::ALL {
        let scene = Scene {
            integrator,
            dt_factor: integrator.default_dt_factor(),
            // The adaptive path keeps it to its tolerance (2.6e-11 measured at tol 1e-6).
            tol: 1e-9,
            ..scene.clone()
        };
        for (theta, w1, w2) in [(15.0, 0.0, 0.0), (45.0, 5.0, -20.0), (80.0, -3.0, 9.0)] {
            let rec = run(
                &scene,
                &Initial::from_angle(V, theta, w1, 0.0).with_partner(w2, 0.0),
            );
            let lin = rec.momentum_residual.unwrap();
            let ang = rec.angular_momentum_residual.unwrap();
            assert!(lin < 1e-12, "{integrator:?} {theta}: linear {lin:e}");
            assert!(ang.abs() < 1e-12, "{integrator:?} {theta}: angular {ang:e}");
            assert!(
                rec.energy_out < rec.energy_in,
                "damped and frictional: energy lost"
            );
            assert!(rec.energy_residual.abs() < 1e-6, "{}", rec.energy_residual);
        }
    }
    // Without tangential damping (the undamped spring rings), where Gear-5's drift was largest
    // (1.2e-10 at the default step).
    let ringing = Scene {
        mu: 0.5,
        gamma: 0.0,
        gamma_t: 0.0,
        normal_law: NormalLaw::Linear { kn: 1e5, cn: 0.0 },
        ..disc_pair(Scene::default())
    };
    let init = Initial::from_angle(V, 85.0, -0.5 * V / R, 0.0).with_partner(0.25 * V / R, 0.0);
    let reference = run(
        &Scene {
            integrator: Integrator::Reference,
            ..ringing.clone()
        },
        &init,
    );
    let at = |dt_factor: f64| {
        let rec = run(
            &Scene {
                dt_factor,
                ..ringing.clone()
            },
            &init,
        );
        assert!(rec.angular_momentum_residual.unwrap().abs() < 1e-12);
        rec.accuracy_distance(&reference, R, V)
    };
    let (coarse, mid, fine) = (at(0.01), at(0.005), at(0.0025));
    assert!(
        fine < 0.6 * mid && mid < 0.6 * coarse,
        "Gear-5 from the reference: {coarse:e}, {mid:e}, {fine:e}"
    );
}

/// Without damping an elastic pair gains no energy beyond the fixed steps' bound (1e-6 at the
/// default step, as on the plate), frictionless or with an undamped tangential spring.
#[test]
fn elastic_pairs_gain_no_energy() {
    for integrator in BOTH {
        for mu in [0.0, 0.5, 1e3] {
            let scene = disc_pair(Scene {
                mu,
                gamma: 0.0,
                gamma_t: 0.0,
                integrator,
                ..Scene::default()
            });
            for theta in [3.0, 20.0, 50.0, 90.0] {
                let rec = run(
                    &scene,
                    &Initial::from_angle(V, theta, 1.0, 0.0).with_partner(-2.0, 0.0),
                );
                let gain = rec.energy_out / rec.energy_in - 1.0;
                assert!(
                    gain < 1e-6,
                    "{integrator:?} mu {mu} theta {theta}: gain {gain:e}"
                );
            }
        }
    }
}

/// Results converge as dt falls, and Gear-5 and Verlet agree at a fine step.
#[test]
fn pairs_converge_with_dt_and_the_integrators_agree() {
    let init = Initial::from_angle(V, 30.0, 2.0, 0.0).with_partner(-1.0, 0.0);
    for integrator in BOTH {
        let at = |dt_factor: f64| {
            run(
                &disc_pair(Scene {
                    mu: 0.3,
                    dt_factor,
                    integrator,
                    ..Scene::default()
                }),
                &init,
            )
        };
        let recs: Vec<Record> = [0.02, 0.01, 0.005, 0.0025].into_iter().map(at).collect();
        let diffs: Vec<f64> = recs
            .windows(2)
            .map(|w| w[0].accuracy_distance(&w[1], R, V))
            .collect();
        assert!(
            diffs.windows(2).all(|d| d[1] < d[0]),
            "{integrator:?}: {diffs:?}"
        );
    }
    let fine = |integrator| {
        run(
            &disc_pair(Scene {
                mu: 0.3,
                dt_factor: 0.00125,
                integrator,
                ..Scene::default()
            }),
            &init,
        )
    };
    let gap = fine(Integrator::Gear5).accuracy_distance(&fine(Integrator::Verlet), R, V);
    assert!(gap < 1e-5, "Gear-5 vs Verlet {gap:e}");
}

fn invalid_name(scene: &Scene) -> String {
    match simulate(scene, &Initial::from_angle(V, 30.0, 0.0, 0.0)) {
        Err(Error::InvalidParameter { name, .. }) => name,
        other => panic!("expected an error for {scene:?}, got {other:?}"),
    }
}

#[test]
fn what_a_pair_cannot_be_is_refused_naming_the_parameter() {
    let cases: Vec<(&str, Scene)> = vec![
        (
            "partner",
            Scene {
                partner: Some(Partner::of(Shape::sphere(R).unwrap())),
                ..Scene::default()
            },
        ),
        (
            "partner_rho",
            Scene {
                partner: Some(Partner {
                    rho: Some(-1.0),
                    ..Partner::of(Shape::Disc { r: R })
                }),
                ..Scene::default()
            },
        ),
        (
            "dt_factor",
            disc_pair(Scene {
                dt_factor: 0.5,
                ..Scene::default()
            }),
        ),
    ];
    for (name, scene) in cases {
        assert_eq!(invalid_name(&scene), name, "{scene:?}");
    }
    let fast = simulate(
        &disc_pair(Scene::default()),
        &Initial::from_angle(1e3, 90.0, 0.0, 0.0),
    );
    assert!(
        matches!(fast, Err(Error::InvalidParameter { ref name, .. }) if name == "v"),
        "{fast:?}"
    );
    let spin = Initial::from_angle(V, 30.0, 0.0, 0.0).with_partner(f64::NAN, 0.0);
    let res = simulate(&disc_pair(Scene::default()), &spin);
    assert!(
        matches!(res, Err(Error::InvalidParameter { ref name, .. }) if name == "partner_omega_in")
    );
}

/// The adaptive path on pairs meets its tolerance against the reference (largest error of e_N,
/// e_T, e_kin and omega_out r / v at most 3 tol, as promised on the plate) and its `err_est`
/// covers the error in at least 95 % of the impacts, over angles, friction, damping and spins.
#[test]
fn adaptive_pairs_meet_their_tolerance() {
    let mut covered = (0, 0);
    for tol in [1e-4, 1e-6, 1e-8] {
        let mut worst: f64 = 0.0;
        for (mu, gamma) in [(0.0, 0.0), (0.1, 0.33), (0.5, 0.33), (1.0, 0.33)] {
            for theta in [2.0, 10.0, 30.0, 60.0, 89.0] {
                let init = Initial::from_angle(V, theta, 1.0, 0.0).with_partner(-2.0, 0.0);
                let at = |integrator, dt_factor| {
                    let scene = disc_pair(Scene {
                        mu,
                        gamma,
                        integrator,
                        dt_factor,
                        tol,
                        ..Scene::default()
                    });
                    run(&scene, &init)
                };
                let (fast, reference) = (
                    at(Integrator::Adaptive, 1.0),
                    at(Integrator::Reference, 0.2),
                );
                let err = fast.accuracy_distance(&reference, R, V);
                worst = worst.max(err / tol);
                covered.0 += usize::from(fast.err_est.unwrap() >= err);
                covered.1 += 1;
            }
        }
        assert!(worst <= 3.0, "tol {tol}: largest error {worst:.2} tol");
    }
    assert!(
        20 * covered.0 >= 19 * covered.1,
        "err_est covers {covered:?}"
    );
}

/// On the adaptive path too, two identical discs head-on are one disc on the plate (to the
/// tolerance: the two paths take different steps), and the identity of the two normal
/// restitutions holds to the tolerance.
#[test]
fn adaptive_pairs_keep_the_plate_equivalence_and_the_identity() {
    let tol = 1e-8;
    let adaptive = |scene: Scene| Scene {
        integrator: Integrator::Adaptive,
        tol,
        ..scene
    };
    let plate = run(
        &adaptive(Scene::default()),
        &Initial::from_angle(V, 90.0, 0.0, 0.0),
    );
    let pair = run(
        &adaptive(disc_pair(Scene::default())),
        &Initial::from_angle(2.0 * V, 90.0, 0.0, 0.0),
    );
    assert!(
        (pair.e_n - plate.e_n).abs() < 3.0 * tol,
        "{} vs {}",
        pair.e_n,
        plate.e_n
    );
    let scene = adaptive(disc_pair(Scene {
        mu: 0.0,
        ..Scene::default()
    }));
    for theta in [0.5, 5.0, 40.0] {
        let rec = run(&scene, &Initial::from_angle(1.0, theta, 0.0, 0.0));
        let (s, c) = rec.normal_rotation_deg.to_radians().sin_cos();
        let cot = 1.0 / (theta as f64).to_radians().tan();
        assert!(
            (rec.e_n - (rec.e_n_sep * c + cot * s)).abs() < 3.0 * tol * (1.0 + cot),
            "theta {theta}"
        );
    }
}
