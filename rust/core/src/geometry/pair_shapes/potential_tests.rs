//! The area law's potential on pairs with corners (docs/model.md 17.8): its push is -grad W
//! (central differences), it does no work over a closed path of relative placements, a rigid
//! turn of the pair does no work (the partner's torque from its own terms), and on a
//! half-plane-like partner it is the plate's law, force A n at the overlap's centroid.

use super::tests::{cases, ngon, touch_at};
use super::*;

/// W at lanes `q`.
fn potential(pair: &ShapePair, q: &[f64; 4]) -> f64 {
    pair.patch(q).expect("overlap").potential
}

#[test]
fn push_is_minus_the_gradient_of_the_potential() {
    for (a, b, q) in cases() {
        let pair = ShapePair::new(&a, &b).unwrap();
        let p = pair.patch(&q).unwrap();
        let r = pair.reach();
        for k in 0..4 {
            let h = 1e-7 * if k < 2 { r } else { 1.0 };
            let (mut up, mut down) = (q, q);
            up[k] += h;
            down[k] -= h;
            let fd = -(potential(&pair, &up) - potential(&pair, &down)) / (2.0 * h);
            // Scales: the force per stiffness is about the area, the torque the area times r.
            let scale = p.area * if k < 2 { 1.0 } else { r };
            assert!(
                (fd - p.push[k]).abs() < 1e-7 * scale,
                "{q:?} lane {k}: fd {fd:e} vs push {:e}",
                p.push[k]
            );
        }
    }
}

/// The partner's torque written from its own terms (the crossings sliding on its edges, its
/// cap turning) is the one taken from a rigid turn's invariance.
#[test]
fn a_rigid_turn_of_the_pair_does_no_work() {
    for (a, b, q) in cases() {
        let pair = ShapePair::new(&a, &b).unwrap();
        let p = pair.patch(&q).unwrap();
        let (mut up, mut down) = (q, q);
        let h = 1e-7;
        up[3] += h;
        down[3] -= h;
        let fd = -(potential(&pair, &up) - potential(&pair, &down)) / (2.0 * h);
        let turn = p.push[3];
        assert!(
            (fd - turn).abs() < 1e-7 * p.area * pair.reach(),
            "{q:?}: {fd:e} vs {turn:e}"
        );
    }
}

/// The work of the push along a closed loop of relative placements (position and both
/// angles at once) is zero: the law is conservative. The loop's work, by the midpoint rule on
/// a fine subdivision, is compared with the work along its first half.
#[test]
fn no_work_over_a_closed_path() {
    for (a, b, q) in cases() {
        let pair = ShapePair::new(&a, &b).unwrap();
        let r = pair.reach();
        let amp = [2e-4 * r, 3e-4 * r, 2e-3, 1.5e-3];
        let at = |s: f64| {
            let (sn, cs) = (s.sin(), s.cos());
            [
                q[0] + amp[0] * sn,
                q[1] + amp[1] * (cs - 1.0),
                q[2] + amp[2] * (2.0 * s).sin(),
                q[3] + amp[3] * (sn + cs - 1.0),
            ]
        };
        let steps = 20_000;
        let ds = std::f64::consts::TAU / steps as f64;
        let (mut work, mut half) = (0.0, 0.0);
        for i in 0..steps {
            let (q0, q1) = (at(i as f64 * ds), at((i + 1) as f64 * ds));
            let mid = at((i as f64 + 0.5) * ds);
            let push = pair.patch(&mid).unwrap().push;
            let dw: f64 = (0..4).map(|k| push[k] * (q1[k] - q0[k])).sum();
            work += dw;
            if i < steps / 2 {
                half += dw;
            }
        }
        assert!(
            work.abs() < 1e-6 * half.abs(),
            "{q:?}: loop work {work:e} against half {half:e}"
        );
    }
}

/// A polygon on a partner a million times larger with an edge flat on top (a half-plane for
/// the overlap) is pushed as on the plate: force A n at the overlap's centroid, W the depth
/// integrated over the overlap.
#[test]
fn a_huge_flat_partner_pushes_as_the_plate() {
    let big = 1e4;
    let plate = ngon(big, 4);
    for n in [3, 5, 7, 12] {
        let particle = ngon(0.01, n);
        let pair = ShapePair::new(&particle, &plate).unwrap();
        // The square turned by 45 degrees: its top edge at y = big / sqrt 2, normal +y.
        let top = big / 2f64.sqrt();
        for (phi, x) in [(0.3, 0.0), (1.3, 0.004), (-0.7, -0.02)] {
            let phi2 = std::f64::consts::FRAC_PI_4;
            let y = touch_at(&pair, x, phi, phi2) - 1e-4;
            let q = [x, y, phi, phi2];
            let p = pair.patch(&q).unwrap();
            assert!((p.n[1] - 1.0).abs() < 1e-12, "{n}: {:?}", p.n);
            let expect = [
                0.0,
                p.area,
                p.area * cross(sub(p.centroid, [x, y]), [0.0, 1.0]),
            ];
            for k in 0..3 {
                let scale = p.area * if k < 2 { 1.0 } else { 0.01 };
                assert!(
                    (p.push[k] - expect[k]).abs() < 1e-9 * scale,
                    "{n}-gon lane {k}: {:e} vs {:e}",
                    p.push[k],
                    expect[k]
                );
            }
            // W: the overlap's depth below the top edge, integrated (its centroid's depth).
            // (The expectation's own round-off: the top's, 1e4, against a depth of 1e-4.)
            let w = p.area * (top - p.centroid[1]);
            let tol = 64.0 * f64::EPSILON * top / (top - p.centroid[1]);
            assert!((p.potential - w).abs() < tol * w, "{} vs {w}", p.potential);
        }
    }
}

/// How much the push jumps where a crossing passes a corner (docs/model.md 17.8): the largest
/// change between neighbouring samples of a path of 20 000 (pressing, sliding and turning), in
/// units of the path's largest push. `cargo test --release --lib measure_push_jumps --
/// --ignored --nocapture`.
#[test]
#[ignore]
fn measure_push_jumps() {
    for (n1, n2) in [(12, 12), (120, 120), (3, 0)] {
        let a = ngon(0.01, n1);
        let b = if n2 == 0 {
            Shape::Disc { r: 0.01 }
        } else {
            ngon(0.01, n2)
        };
        let pair = ShapePair::new(&a, &b).unwrap();
        let (phi1, phi2) = (0.4, 1.3);
        let y0 = touch_at(&pair, 0.0, phi1, phi2);
        let steps = 20_000;
        let (mut worst, mut scale) = (0.0f64, 0.0f64);
        let mut prev: Option<[f64; 4]> = None;
        for i in 1..steps {
            let s = i as f64 / steps as f64;
            let dip = 2e-4 * (std::f64::consts::PI * s).sin();
            let q = [0.002 * s, y0 - dip, phi1 + 0.3 * s, phi2];
            let Some(p) = pair.patch(&q) else {
                prev = None;
                continue;
            };
            scale = scale.max(p.push[0].hypot(p.push[1]));
            if let Some(pp) = prev {
                worst = worst.max((p.push[0] - pp[0]).hypot(p.push[1] - pp[1]));
            }
            prev = Some(p.push);
        }
        println!(
            "{n1}/{n2}: largest jump of the push {:e} of its largest",
            worst / scale
        );
    }
}

/// The overlap held through a piece of the adaptive path is the bodies' own where it was held
/// (the same push), its switch has not fired there, and it fires once a crossing has passed
/// a corner (the held value, continuous, changes sign between the two).
#[test]
fn the_held_overlap_is_the_overlap_until_its_switch() {
    use crate::geometry::pair::PairGeometry;
    for (a, b, q) in cases() {
        let pair = ShapePair::new(&a, &b).unwrap();
        if pair.polygons().is_none() {
            continue;
        }
        let held = pair.held_springs(&q);
        assert!(!held.overlap.is_empty(), "{q:?}");
        let (own, kept) = (pair.frame(&q).unwrap(), pair.frame_held(&q, &held).unwrap());
        assert_eq!(own.area_push, kept.area_push, "{q:?}");
        assert!(pair.held_springs_value(&q, &held) < 0.0);
        // Slide sideways until the overlap's vertices are no longer the held ones.
        let mut moved = q;
        while pair.held_springs(&moved).overlap == held.overlap {
            moved[0] += 1e-5 * pair.reach();
        }
        assert!(
            pair.held_springs_value(&moved, &held) > 0.0,
            "{q:?} -> {moved:?}"
        );
    }
}
