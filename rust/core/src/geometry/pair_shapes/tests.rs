use super::*;
use crate::geometry::disc_segment_at;
use std::f64::consts::PI;

fn square(r: f64) -> Shape {
    Shape::Polygon(std::sync::Arc::new(Polygon::regular(r, 4).unwrap()))
}

pub(super) fn ngon(r: f64, n: usize) -> Shape {
    Shape::Polygon(std::sync::Arc::new(Polygon::regular(r, n).unwrap()))
}

/// Area of the overlap by counting a fine grid's points inside both bodies, over a box of
/// half-width `half` around `centre`.
fn grid_area(pair: &ShapePair, q: &[f64; 4], centre: [f64; 2], half: f64) -> f64 {
    let body_pts = |b: PairBody, at: [f64; 2], phi: f64| -> Box<dyn Fn([f64; 2]) -> bool> {
        match b {
            PairBody::Disc(r) => {
                Box::new(move |p: [f64; 2]| (p[0] - at[0]).hypot(p[1] - at[1]) <= r)
            }
            PairBody::Polygon(poly) => {
                let v: Vec<[f64; 2]> = placed(poly, at, phi).collect();
                Box::new(move |p: [f64; 2]| inside(p, &v))
            }
        }
    };
    let in1 = body_pts(pair.particle, [q[0], q[1]], q[2]);
    let in2 = body_pts(pair.partner, [0.0, 0.0], q[3]);
    let n = 1500;
    let h = 2.0 * half / n as f64;
    let mut count = 0usize;
    for i in 0..n {
        for j in 0..n {
            let p = [
                centre[0] - half + (i as f64 + 0.5) * h,
                centre[1] - half + (j as f64 + 0.5) * h,
            ];
            if in1(p) && in2(p) {
                count += 1;
            }
        }
    }
    count as f64 * h * h
}

/// The particle's touch height above the partner at horizontal offset `x`, by bisection on
/// the gap.
pub(super) fn touch_at(pair: &ShapePair, x: f64, phi1: f64, phi2: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, pair.reach());
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if pair.gap(&[x, mid, phi1, phi2]) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// Configurations of each pairing at a moderate overlap: corners into faces, faces on
/// corners, a disc on a face and on a corner.
pub(super) fn cases() -> Vec<(Shape, Shape, [f64; 4])> {
    let (r, r2) = (0.01, 0.013);
    let mut out = Vec::new();
    for (a, b) in [
        (square(r), ngon(r2, 5)),
        (ngon(r, 6), ngon(r2, 3)),
        (Shape::Disc { r }, ngon(r2, 5)),
        (ngon(r, 7), Shape::Disc { r: r2 }),
    ] {
        for (phi1, phi2, x) in [(0.3, 1.1, 0.001), (1.0, 0.2, -0.002), (2.0, 2.5, 0.0)] {
            let pair = ShapePair::new(&a, &b).unwrap();
            let y = touch_at(&pair, x, phi1, phi2) - 0.04 * r;
            out.push((a.clone(), b.clone(), [x, y, phi1, phi2]));
        }
    }
    out
}

#[test]
fn area_matches_a_grid_count() {
    for (a, b, q) in cases() {
        let pair = ShapePair::new(&a, &b).unwrap();
        let Some(p) = pair.patch(&q) else {
            panic!(
                "no overlap at {q:?} ({:?} / {:?})",
                pair.particle, pair.partner
            )
        };
        let grid = grid_area(&pair, &q, p.centroid, 2.0 * p.chord.max(p.depth));
        assert!(
            (p.area - grid).abs() < 2e-3 * grid,
            "{q:?}: {} vs grid {grid}",
            p.area
        );
    }
}

/// The identities the damping and the torques rest on (module docs): dA/dq = -l n and
/// dA/dphi_i = b_i, against central differences; b_1 + b_2 = l (q x n).
#[test]
fn area_rates_are_the_chord_and_the_b_terms() {
    for (a, b, q) in cases() {
        let pair = ShapePair::new(&a, &b).unwrap();
        let p = pair.patch(&q).unwrap();
        let area = |k: usize, h: f64| {
            let mut qq = q;
            qq[k] += h;
            pair.patch(&qq).unwrap().area
        };
        let scale = p.chord * 1e-3 * 0.01;
        for (k, expect) in [
            (0, -p.chord * p.n[0]),
            (1, -p.chord * p.n[1]),
            (2, p.b[0]),
            (3, p.b[1]),
        ] {
            let h = if k < 2 { 1e-8 } else { 1e-6 };
            let fd = (area(k, h) - area(k, -h)) / (2.0 * h);
            assert!(
                (fd - expect).abs() < 1e-4 * p.chord.max(scale) * if k < 2 { 1.0 } else { 0.01 },
                "{q:?} lane {k}: fd {fd:e} vs {expect:e}"
            );
        }
        let sum = p.b[0] + p.b[1];
        let expect = p.chord * cross([q[0], q[1]], p.n);
        assert!(
            (sum - expect).abs() < 1e-9 * 0.01 * p.chord,
            "{sum:e} vs {expect:e}"
        );
    }
}

/// A disc on a polygon's face is the disc on the plate: the same segment, its centroid on
/// the face's normal, the normal the face's.
#[test]
fn disc_on_a_face_is_the_plate_segment() {
    let (r, r2) = (0.01, 0.02);
    let b = square(r2);
    let a = Shape::Disc { r };
    let mut pair = ShapePair::new(&a, &b).unwrap();
    pair.springs = true;
    // Square turned by 45 degrees: its top face at y = r2 / sqrt 2.
    let top = r2 / 2f64.sqrt();
    for depth in [1e-9, 1e-6, 1e-4, 2e-3] {
        let q = [0.001, top + r - depth, 0.7, PI / 4.0];
        let p = pair.patch(&q).unwrap();
        let seg = disc_segment_at(r, r - depth, depth);
        // Round-off: the crossings' half chord carries eps r / depth of relative error.
        let tol = 8.0 * f64::EPSILON * (r / depth).max(1.0);
        assert!((p.area - seg.area).abs() < tol * seg.area, "{depth}: {p:?}");
        assert!((p.n[0]).abs() < 1e-12 && (p.n[1] - 1.0).abs() < 1e-12);
        assert!((p.depth - depth).abs() < tol * depth);
        assert!((p.centroid[0] - 0.001).abs() < 1e-12);
        assert!(
            p.b[0].abs() < 1e-12 * r * r,
            "a disc's turn leaves the area: {:e}",
            p.b[0]
        );
        assert!((p.springs.count - 1.0).abs() < 1e-12);
        assert!((p.springs.depth - depth).abs() < tol * depth);
    }
}

/// Swapping particle and partner (and mirroring through the partner's centre) leaves the
/// overlap: the same area and chord, the normal reversed.
#[test]
fn exchange_gives_the_same_overlap() {
    for (a, b, q) in cases() {
        let p = ShapePair::new(&a, &b).unwrap().patch(&q).unwrap();
        let swapped = ShapePair::new(&b, &a).unwrap();
        let q2 = [-q[0], -q[1], q[3], q[2]];
        let s = swapped.patch(&q2).unwrap();
        assert!((p.area - s.area).abs() < 1e-9 * p.area, "{q:?}");
        assert!((p.chord - s.chord).abs() < 1e-9 * p.chord);
        assert!((p.n[0] + s.n[0]).abs() < 1e-9 && (p.n[1] + s.n[1]).abs() < 1e-9);
        assert!((p.depth - s.depth).abs() < 1e-9 * p.depth);
    }
}

/// At the touch height the bodies touch: a hair lower they overlap, a hair higher they are
/// apart by about the hair.
#[test]
fn touch_height_is_where_they_touch() {
    for (a, b, q) in cases() {
        let pair = ShapePair::new(&a, &b).unwrap();
        let y0 = pair.touch_height(q[2], q[3]);
        let hair = 1e-9 * pair.reach();
        assert!(pair.patch(&[0.0, y0 - hair, q[2], q[3]]).is_some(), "{q:?}");
        let gap = pair.gap(&[0.0, y0 + hair, q[2], q[3]]);
        assert!(
            gap > 0.0 && gap <= hair * (1.0 + 1e-6),
            "{q:?}: gap {gap:e}"
        );
    }
}

/// The vertex springs are the gradient of their potential kn sum d_i^2 / 2 (Cundall's
/// vertex-edge contacts conserve energy while each keeps its edge): the push on every lane
/// against central differences of the potential.
#[test]
fn springs_push_down_their_potential() {
    for (a, b, q) in cases() {
        let mut pair = ShapePair::new(&a, &b).unwrap();
        pair.springs = true;
        let p = pair.patch(&q).unwrap();
        assert!(p.springs.count >= 1.0, "{q:?}");
        let potential = |k: usize, h: f64| {
            let mut qq = q;
            qq[k] += h;
            pair.patch(&qq).unwrap().springs.potential
        };
        for k in 0..4 {
            let h = if k < 2 { 1e-9 } else { 1e-7 };
            let fd = -(potential(k, h) - potential(k, -h)) / (2.0 * h);
            let push = p.springs.push[k];
            let scale = p.springs.depth * if k < 2 { 1.0 } else { 0.01 };
            assert!(
                (fd - push).abs() < 1e-5 * scale,
                "{q:?} lane {k}: {fd:e} vs {push:e}"
            );
        }
    }
}

/// A corner pressed a sliver deep (1e-14 m: a chord 25 times the round-off of the centres'
/// coordinates) into a disc, or into a polygon's edge, takes the exact normal: the radius
/// through the corner, or the edge's normal. Taken from the chord's own direction it was off
/// by ~1e-4 (the round-off of its ends over its length), which set a stuck spring's elongation
/// apart between tolerances (docs/model.md 17.8).
#[test]
fn a_sliver_takes_the_exact_normal() {
    let (r, r2, depth) = (0.01, 0.02, 1e-14);
    let (particle, disc, edge) = (square(r), Shape::Disc { r: r2 }, square(r2));
    let into_disc = ShapePair::new(&particle, &disc).unwrap();
    for alpha in [0.0f64, 0.3, -1.1, 2.0] {
        // The square's corner (at angle phi from its centre) points at the disc's centre.
        let u = [alpha.sin(), alpha.cos()];
        let reach = r2 - depth + r;
        let phi = (-u[1]).atan2(-u[0]);
        let p = into_disc
            .patch(&[reach * u[0], reach * u[1], phi, 0.0])
            .unwrap();
        let err = (p.n[0] - u[0]).hypot(p.n[1] - u[1]);
        assert!(
            err < 1e-12,
            "disc, alpha {alpha}: normal {:?} off by {err:e}",
            p.n
        );
    }
    // The partner turned by 45 degrees: its top edge at y = r2 / sqrt 2, normal +y.
    let into_edge = ShapePair::new(&particle, &edge).unwrap();
    for x in [0.0, 0.001, -0.0037] {
        let top = r2 / 2f64.sqrt();
        let p = into_edge
            .patch(&[x, top + r - depth, -PI / 2.0, PI / 4.0])
            .unwrap();
        let err = p.n[0].hypot(p.n[1] - 1.0);
        assert!(err < 1e-12, "edge, x {x}: normal {:?} off by {err:e}", p.n);
    }
}

/// Twin squares, a corner of the particle exactly on the partner's edge (a state the adaptive
/// path located at a switch): parry's edge chase returned the particle whole there (area
/// 2e-4 m^2, one crossing, no chord) and the contact's frame fell back to its held corners,
/// moving the centroid 4e-6 m for that one state (twin squares and their copy ten times as
/// large 5e-5 apart in e_T). The clip's overlap is the one a round-off away, where parry
/// finds it.
#[test]
fn a_corner_on_an_edge_keeps_its_overlap() {
    let sq = square(0.01);
    let pair = ShapePair::new(&sq, &sq).unwrap();
    let on_edge = [
        1.0933371791897257e-5,
        0.019599452157717794,
        1.61035704090474,
        -0.0014892791671718864,
    ];
    let beside = [
        1.0933371791899236e-5,
        0.01959945215771779,
        1.6103570409047405,
        -0.0014892791671719781,
    ];
    let (a, b) = (pair.patch(&on_edge).unwrap(), pair.patch(&beside).unwrap());
    assert!((a.area - b.area).abs() < 1e-9 * b.area, "{a:?} vs {b:?}");
    assert!((a.chord - b.chord).abs() < 1e-9 * b.chord, "{a:?} vs {b:?}");
    let moved = (a.centroid[0] - b.centroid[0]).hypot(a.centroid[1] - b.centroid[1]);
    assert!(moved < 1e-15, "centroid moved {moved:e}: {a:?} vs {b:?}");
}

/// Twin triangles just past their touch (a chord of 2.4e-16 m): the chord's own normal lay
/// nearly across the line of centres, and the springs' push, turned to its side, pointed into
/// the partner; the contact's friction then acted with the sliding, not against it. The
/// normal is the push turned to the side of the springs' own directions: towards the
/// particle.
#[test]
fn a_touching_corner_pushes_the_particle_away() {
    let tri = ngon(0.01, 3);
    let mut pair = ShapePair::new(&tri, &tri).unwrap();
    pair.springs = true;
    let q = [
        1.0159105823050462e-16,
        0.012827235745996663,
        5.260596898436119,
        4.5675266524691605,
    ];
    let fr = pair.frame(&q).unwrap();
    let push = fr.springs.push;
    assert!(
        fr.n[0] * push[0] + fr.n[1] * push[1] > 0.0 && fr.n[1] > 0.9,
        "normal {:?}, push {push:?}",
        fr.n
    );
}

/// A disc sliding along a face of a square under the area law: the crossings held on the face
/// give the overlap as it is until one passes the face's corner (the held event function
/// changes sign there), then the face continued (more area than the square's), and held anew
/// past the corner the overlap as it is again.
#[test]
fn a_disc_holds_its_crossings_until_one_passes_a_corner() {
    let (r, r2) = (0.01, 0.02);
    let (a, b) = (Shape::Disc { r }, square(r2));
    let pair = ShapePair::new(&a, &b).unwrap();
    assert!(pair.holds_springs());
    // Square turned by 45 degrees: its top face at y = r2 / sqrt 2, ending at x = r2 / sqrt 2;
    // the disc 1e-3 deep, its crossings 4.36e-3 either side of its centre.
    let top = r2 / 2f64.sqrt();
    let at = |x: f64| [x, top + r - 1e-3, 0.7, PI / 4.0];
    let held = pair.held_springs(&at(0.005));
    assert!(held.disc_crossings.is_some(), "{held:?}");
    let close = |p: PairFrame, q: PairFrame| {
        (p.area - q.area).abs() < 1e-12 * q.area
            && (0..4).all(|i| (p.area_push[i] - q.area_push[i]).abs() < 1e-12 * q.area)
    };
    for x in [0.0, 0.005, 0.0095] {
        let (h, f) = (pair.frame_held(&at(x), &held), pair.frame(&at(x)));
        assert!(close(h.unwrap(), f.unwrap()), "{x}: {h:?} vs {f:?}");
        assert!(pair.held_springs_value(&at(x), &held) < 0.0);
    }
    let past = 0.0099;
    assert!(pair.held_springs_value(&at(past), &held) > 0.0);
    let (h, f) = (
        pair.frame_held(&at(past), &held).unwrap(),
        pair.frame(&at(past)).unwrap(),
    );
    assert!(
        h.area > f.area,
        "the face continued: {} vs {}",
        h.area,
        f.area
    );
    let anew = pair.held_springs(&at(past));
    assert_ne!(anew.disc_crossings, held.disc_crossings);
    assert!(close(pair.frame_held(&at(past), &anew).unwrap(), f));
    // The linear law's one disc spring is smooth: nothing held.
    let springs = ShapePair {
        springs: true,
        ..pair
    };
    assert!(!springs.holds_springs());
}

/// `signed_depth` spares the clip only where a separating line proves the bodies apart
/// (`separated_gap`): its value is the patch's depth, else minus the gap, bit for bit, from
/// deep overlaps (crossed corners) through grazing to far apart, for both laws. Without the
/// proof's condition the overlapping placements would be read as apart (minus a corner's
/// distance, not the depth).
#[test]
fn a_separated_depth_is_the_patch_or_the_gap() {
    let mut seeded = crate::numerics::seeded::Seeded(17);
    let mut rng = move || seeded.uniform();
    let (mut overlapping, mut separated_seen) = (0, 0);
    for case in 0..4000 {
        let (n, m) = (
            [3usize, 4, 5, 7, 12][case % 5],
            [3usize, 5, 6, 12][case % 4],
        );
        let (a, b) = (ngon(0.01 * (0.3 + rng()), n), ngon(0.01, m));
        let mut pair = ShapePair::new(&a, &b).unwrap();
        pair.springs = case % 3 == 0;
        let ang = rng() * std::f64::consts::TAU;
        let d = pair.reach() * (0.3 + 0.9 * rng());
        let q = [d * ang.cos(), d * ang.sin(), rng() * 7.0, rng() * 7.0];
        let expected = match pair.patch(&q) {
            Some(p) => {
                overlapping += 1;
                p.depth
            }
            None => -pair.gap(&q),
        };
        separated_seen += usize::from(pair.separated_gap(&q).is_some());
        let got = pair.signed_depth(&q);
        assert_eq!(
            got.to_bits(),
            expected.to_bits(),
            "case {case}: {got} vs {expected}"
        );
    }
    // Both branches taken often (the test would not see a wrong skip otherwise).
    assert!(
        overlapping > 400 && separated_seen > 400,
        "{overlapping} {separated_seen}"
    );
}
