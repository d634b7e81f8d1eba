//! Polygon overlap geometry: closed forms for triangles and squares (both paths), the
//! circular-segment limit of a regular n-gon, the degenerate configurations (an edge parallel
//! to the plate, a vertex exactly on it, slivers of tiny area), and the general convex-obstacle
//! path on a finite plate.

use restitution_core::{ConvexObstacle, Overlap, OverlapMethod, Polygon, Shape};
use std::f64::consts::PI;

const PATHS: [OverlapMethod; 2] = [OverlapMethod::HalfPlane, OverlapMethod::Parry];

fn overlap(shape: &Shape, method: OverlapMethod, y: f64, phi: f64) -> Overlap {
    restitution_core::plate_overlap(shape, method, y, phi)
        .unwrap_or_else(|| panic!("{method:?}: no overlap at y = {y}, phi = {phi}"))
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Finite everywhere (no NaN or infinity leaks out of a degenerate clip).
fn assert_finite(o: &Overlap) {
    for v in [
        o.area,
        o.cx,
        o.cy,
        o.chord,
        o.x_mid,
        o.depth,
        o.x_low,
        o.first_moment,
    ] {
        assert!(v.is_finite(), "non-finite overlap {o:?}");
    }
    assert!(o.area >= 0.0 && o.chord >= 0.0, "{o:?}");
}

#[test]
fn triangle_corner_down_and_face_down_match_closed_forms() {
    // Equilateral triangle of circumradius r = 0.01: side s = r sqrt 3.
    let r = 0.01;
    let tri = Shape::regular_polygon(r, 3).unwrap();
    for method in PATHS {
        for &d in &[1e-6, 1e-4, 2e-3] {
            // Corner down (vertex 2 at 240 + 30 = 270 deg): a 60-degree wedge of height d.
            let phi = PI / 6.0;
            let o = overlap(&tri, method, tri.touch_height(phi) - d, phi);
            let d = o.depth; // the depth the rounded coordinates actually give
            assert!(rel(o.area, d * d / 3f64.sqrt()) < 1e-9, "{method:?} {o:?}");
            assert!(rel(o.cy, -d / 3.0) < 1e-9, "{method:?} {o:?}");
            assert!(o.cx.abs() < 1e-12 * r, "{method:?} {o:?}");
            assert!(
                rel(o.chord, 2.0 * d / 3f64.sqrt()) < 1e-9,
                "{method:?} {o:?}"
            );
            assert!(o.x_mid.abs() < 1e-12 * r);

            // Face down (vertices at 90, 210, 330 deg): a trapezoid of height d with the side
            // s at the bottom and s - 2 d / tan 60 at the plate.
            let phi = PI / 2.0;
            let o = overlap(&tri, method, tri.touch_height(phi) - d, phi);
            let d = o.depth;
            let (b0, b1) = (r * 3f64.sqrt(), r * 3f64.sqrt() - 2.0 * d / 3f64.sqrt());
            let area = 0.5 * d * (b0 + b1);
            let from_bottom = d * (b0 + 2.0 * b1) / (3.0 * (b0 + b1));
            assert!(rel(o.area, area) < 1e-9, "{method:?} {o:?} vs {area}");
            assert!(rel(o.cy, -d + from_bottom) < 1e-9, "{method:?} {o:?}");
            assert!(rel(o.chord, b1) < 1e-12, "{method:?} {o:?}");
            assert!(o.cx.abs() < tilt_shift(b0, d), "{method:?} {o:?}");
        }
    }
}

#[test]
fn square_face_down_and_corner_down_match_closed_forms() {
    let r = 0.01;
    let side = r * 2f64.sqrt();
    let sq = Shape::regular_polygon(r, 4).unwrap();
    for method in PATHS {
        for &d in &[1e-7, 1e-4, 3e-3] {
            // Face down: a rectangle side x d.
            let phi = PI / 4.0;
            let o = overlap(&sq, method, sq.touch_height(phi) - d, phi);
            let d = o.depth;
            assert!(rel(o.area, side * d) < 1e-9, "{method:?} {o:?}");
            assert!(rel(o.cy, -d / 2.0) < 1e-9, "{method:?} {o:?}");
            assert!(rel(o.chord, side) < 1e-12, "{method:?} {o:?}");
            assert!(o.cx.abs() < tilt_shift(side, d), "{method:?} {o:?}");
            assert!(o.x_mid.abs() < 1e-12 * r, "{method:?} {o:?}");
            // Corner down: a right-angled wedge, area d^2, chord 2 d.
            let phi = -PI / 2.0;
            let o = overlap(&sq, method, sq.touch_height(phi) - d, phi);
            let d = o.depth;
            assert!(rel(o.area, d * d) < 1e-9, "{method:?} {o:?}");
            assert!(rel(o.cy, -d / 3.0) < 1e-9, "{method:?} {o:?}");
            assert!(rel(o.chord, 2.0 * d) < 1e-9, "{method:?} {o:?}");
        }
        // Tilted square: the overlap is a general triangle or quadrilateral; its area follows
        // from integrating the width: check against a fine midpoint rule in depth.
        let phi = 0.3;
        let y = sq.touch_height(phi) - 2e-3;
        let o = overlap(&sq, method, y, phi);
        let k = 20_000;
        let h = o.depth / k as f64;
        let (mut area, mut moment) = (0.0, 0.0);
        for i in 0..k {
            let yy = -o.depth + (i as f64 + 0.5) * h;
            // Width of the tilted square at height yy: clip the horizontal line.
            let w = width_at(&sq, y, phi, yy);
            area += w * h;
            moment += -yy * w * h;
        }
        assert!(rel(o.area, area) < 1e-7, "{method:?} {} vs {area}", o.area);
        assert!(rel(o.first_moment, moment) < 1e-7, "{method:?}");
    }
}

/// Bound on the centroid's x offset of a thin face-down overlap (width w, depth d) whose
/// bottom edge the rotation has tilted by round-off (a few 1e-16 rad): a tilt alpha moves the
/// centroid by w^2 alpha / (12 d).
fn tilt_shift(w: f64, d: f64) -> f64 {
    w * w * 1e-15 / (12.0 * d) + 1e-12 * w
}

/// Width of the placed polygon along the horizontal line at height `yy`.
fn width_at(shape: &Shape, y: f64, phi: f64, yy: f64) -> f64 {
    let (s, c) = phi.sin_cos();
    let v: Vec<(f64, f64)> = shape
        .vertices()
        .iter()
        .map(|p| (c * p.x - s * p.y, y + s * p.x + c * p.y))
        .collect();
    let mut xs = vec![];
    for i in 0..v.len() {
        let (p, q) = (v[i], v[(i + 1) % v.len()]);
        if (p.1 - yy) * (q.1 - yy) < 0.0 {
            xs.push(p.0 + (yy - p.1) / (q.1 - p.1) * (q.0 - p.0));
        }
    }
    xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        - xs.iter().cloned().fold(f64::INFINITY, f64::min)
}

/// The exact circular segment of radius r with centre at height y.
fn disc_segment(r: f64, y: f64) -> (f64, f64) {
    let a = (y / r).acos();
    let area = r * r * (a - a.sin() * a.cos());
    let d = 2.0 * (r * a.sin()).powi(3) / (3.0 * area);
    (area, y - d)
}

#[test]
fn regular_ngon_tends_to_the_circular_segment() {
    // At a fixed centre height, the n-gon's clipped area approaches the disc segment's like
    // 1 / n^2: the arc of half-angle t inside the plate spans t n / pi edges, each missing a
    // sliver r^2 (b - sin b) / 2 ~ r^2 b^3 / 12 (b = 2 pi / n), a relative deficit of
    // t b^2 / (6 (t - sin t cos t)) to leading order.
    let r = 0.01;
    let y = 0.8 * r;
    let (area, cy) = disc_segment(r, y);
    let t = (y / r).acos();
    let mut prev: Option<(f64, f64)> = None;
    println!(
        "{:>6} {:>12} {:>12} {:>6}",
        "n", "|dA|/A", "|dcy|/r", "order"
    );
    for &n in &[16usize, 64, 256, 1024, 4096] {
        let gon = Shape::regular_polygon(r, n).unwrap();
        // Average over orientations, so that the vertex-up/edge-up parity does not alias.
        let mut worst: f64 = 0.0;
        let mut worst_c: f64 = 0.0;
        for k in 0..7 {
            let phi = 2.0 * PI / n as f64 * k as f64 / 7.0;
            for method in PATHS {
                let o = overlap(&gon, method, y, phi);
                worst = worst.max(rel(o.area, area));
                worst_c = worst_c.max((o.cy - cy).abs() / r);
            }
        }
        let order = prev.map(|(pn, pe)| (pe / worst).ln() / (n as f64 / pn).ln());
        println!(
            "{n:>6} {worst:>12.3e} {worst_c:>12.3e} {:>6}",
            order.map_or("-".into(), |o| format!("{o:.2}"))
        );
        let b = 2.0 * PI / n as f64;
        let predicted = t * b * b / (6.0 * (t - t.sin() * t.cos()));
        assert!(worst < 1.2 * predicted, "n {n}: {worst} vs {predicted}");
        if let Some(o) = order {
            assert!((1.8..2.3).contains(&o), "n {n}: order {o}");
        }
        prev = Some((n as f64, worst));
    }
}

#[test]
fn edge_parallel_to_the_plate_is_continuous() {
    // A face-down square rotated through the parallel orientation at fixed centre height, and
    // lowered through first touch: area and centroid vary continuously, no NaN.
    let r = 0.01;
    let sq = Shape::regular_polygon(r, 4).unwrap();
    for method in PATHS {
        let y = sq.touch_height(PI / 4.0) - 1e-4;
        let mut prev: Option<Overlap> = None;
        for k in -200..=200 {
            let phi = PI / 4.0 + k as f64 * 1e-9;
            let o = overlap(&sq, method, y, phi);
            assert_finite(&o);
            if let Some(p) = prev {
                // dA/dphi ~ side^2 / 4, here 5e-5 m^2 per rad: steps of 1e-9 rad move A by ~5e-14.
                assert!((o.area - p.area).abs() < 1e-12, "{method:?} k {k}");
                // d(cx)/dphi ~ side^2 / (12 depth) = 0.17 m per rad here.
                assert!(
                    (o.cy - p.cy).abs() < 1e-12 && (o.cx - p.cx).abs() < 4e-10,
                    "{method:?} k {k}: {o:?} {p:?}"
                );
            }
            prev = Some(o);
        }
        // Lowering through touch, exactly face-down in the rounded coordinates or not.
        for phi in [PI / 4.0, PI / 4.0 + 1e-15, 3.0 * PI / 4.0] {
            let top = sq.touch_height(phi);
            let mut prev_area = 0.0;
            for k in 1..=60 {
                let d = r * 10f64.powf(-16.0 + k as f64 * 0.25);
                let Some(o) = restitution_core::plate_overlap(&sq, method, top - d, phi) else {
                    panic!("{method:?}: lost the overlap at depth {d}");
                };
                assert_finite(&o);
                assert!(
                    o.area >= prev_area,
                    "{method:?}: area not monotone in depth"
                );
                assert!(o.area <= 2.0 * r * 1.0001 * o.depth, "{method:?} {o:?}");
                prev_area = o.area;
            }
        }
    }
}

#[test]
fn vertex_exactly_on_the_plate() {
    // A triangle with one vertex exactly on y = 0 and one below: the on-plate vertex is a
    // chord end. Also: only a vertex on the plate (zero depth) is no contact.
    let tri = Shape::convex_polygon(&[[-1e-2, -1e-2], [1e-2, -5e-3], [0.0, 1e-2]]).unwrap();
    let v = tri.vertices().to_vec();
    for method in PATHS {
        // phi = 0: world y = y + v.y exactly; put vertex 1 on the plate.
        let y = -v[1].y;
        let o = overlap(&tri, method, y, 0.0);
        assert_finite(&o);
        assert_eq!(y + v[1].y, 0.0);
        // Closed form: the triangle below y = 0 spanned by vertex 0, vertex 1 (on the plate) and
        // the crossing of edge 2-0 with the plate.
        let p0 = (v[0].x, y + v[0].y);
        let p2 = (v[2].x, y + v[2].y);
        let xc = p0.0 + (0.0 - p0.1) / (p2.1 - p0.1) * (p2.0 - p0.0);
        let area = 0.5 * (v[1].x - xc) * (-p0.1);
        assert!(rel(o.area, area) < 1e-12, "{method:?} {} vs {area}", o.area);
        assert!(rel(o.cy, p0.1 / 3.0) < 1e-12, "{method:?}");
        assert!(rel(o.cx, (p0.0 + v[1].x + xc) / 3.0) < 1e-12, "{method:?}");
        assert!(rel(o.chord, v[1].x - xc) < 1e-12, "{method:?} {o:?}");
        // The lowest vertex exactly on the plate: no overlap.
        assert!(
            restitution_core::plate_overlap(&tri, method, -v[0].y, 0.0).is_none(),
            "{method:?}"
        );
        // Continuity around the exact placement.
        for k in [-1.0, 1.0] {
            let yk = y + k * 1e-15;
            let ok = overlap(&tri, method, yk, 0.0);
            assert!(rel(ok.area, o.area) < 1e-10, "{method:?}");
        }
    }
}

#[test]
fn slivers_keep_their_shape_down_to_tiny_depths() {
    // A corner-down square at depths from 1e-15 r up: area = depth^2 with the depth the
    // rounded coordinates give, for both paths, and both paths agree closely.
    let r = 0.01;
    let sq = Shape::regular_polygon(r, 4).unwrap();
    let gon = Shape::regular_polygon(r, 120).unwrap();
    let phi = -PI / 2.0;
    for k in 0..=26 {
        let d = r * 10f64.powf(-15.0 + 0.5 * k as f64);
        let a = overlap(&sq, OverlapMethod::HalfPlane, sq.touch_height(phi) - d, phi);
        let b = overlap(&sq, OverlapMethod::Parry, sq.touch_height(phi) - d, phi);
        for o in [a, b] {
            assert_finite(&o);
            assert!(rel(o.area, o.depth * o.depth) < 1e-6, "d {d}: {o:?}");
        }
        assert!(rel(a.area, b.area) < 1e-12, "d {d}: {a:?} vs {b:?}");
        // A 120-gon corner-first sliver: both paths agree.
        let phi_g = 0.37;
        let a = overlap(
            &gon,
            OverlapMethod::HalfPlane,
            gon.touch_height(phi_g) - d,
            phi_g,
        );
        let b = overlap(
            &gon,
            OverlapMethod::Parry,
            gon.touch_height(phi_g) - d,
            phi_g,
        );
        assert_finite(&a);
        assert_finite(&b);
        assert!(rel(a.area, b.area) < 1e-10, "d {d}: {a:?} vs {b:?}");
        assert!((a.cx - b.cx).abs() < 1e-12 * r && (a.cy - b.cy).abs() < 1e-12 * r);
    }
}

#[test]
fn parry_path_is_refused_for_a_disc() {
    use restitution_core::{simulate, Initial, Scene};
    let scene = Scene {
        overlap: OverlapMethod::Parry,
        ..Scene::default()
    };
    let e = simulate(&scene, &Initial::from_angle(0.0357, 45.0, 0.0, 0.0)).unwrap_err();
    assert!(e.to_string().contains("`overlap`"), "{e}");
    assert_eq!(
        OverlapMethod::from_name("parry").unwrap(),
        OverlapMethod::Parry
    );
    assert!(OverlapMethod::from_name("exact").is_err());
}

#[test]
fn finite_plate_edge_cuts_the_overlap() {
    // A corner-down square whose corner hangs just past the plate's right end: the overlap is
    // the right triangle between the square's left edge, the plate's top and its end face, and
    // the chord joins the two boundary crossings, so the normal tilts by 45 degrees.
    let r = 0.01;
    let poly = Polygon::regular(r, 4).unwrap();
    let plate = ConvexObstacle::finite_plate(-0.1, 0.0, 0.05).unwrap();
    let (d, e) = (2e-3, 5e-4);
    let phi = -PI / 2.0;
    // The corner (lowest vertex) at (e, -d): centre at (e, r - d).
    let p = plate.overlap(&poly, e, r - d, phi).unwrap();
    let leg = d - e;
    assert!(rel(p.area, 0.5 * leg * leg) < 1e-9, "{p:?}");
    assert!((p.centroid[0] - (-leg / 3.0)).abs() < 1e-12);
    assert!((p.centroid[1] - (-leg / 3.0)).abs() < 1e-12);
    assert!(rel(p.chord_length(), leg * 2f64.sqrt()) < 1e-9);
    let n = p.normal([e, r - d]).unwrap();
    let s = 0.5f64.sqrt();
    assert!((n[0] - s).abs() < 1e-9 && (n[1] - s).abs() < 1e-9, "{n:?}");
    // Far from the ends the finite plate is the half-plane.
    let gon = Polygon::regular(r, 120).unwrap();
    let shape = Shape::Polygon(std::sync::Arc::new(gon.clone()));
    let y = shape.touch_height(0.2) - 1e-3;
    let p = plate.overlap(&gon, -0.05, y, 0.2).unwrap();
    let h = restitution_core::plate_overlap(&shape, OverlapMethod::HalfPlane, y, 0.2).unwrap();
    assert!(rel(p.area, h.area) < 1e-12);
    assert!((p.centroid[0] - (-0.05 + h.cx)).abs() < 1e-12 * r);
    assert!(rel(p.chord_length(), h.chord) < 1e-12);
    let n = p.normal([-0.05, y]).unwrap();
    assert!(n[0].abs() < 1e-12 && (n[1] - 1.0).abs() < 1e-15);
    // Past the end: no overlap.
    assert!(plate.overlap(&gon, 0.05, y, 0.2).is_none());
    // A non-convex obstacle is refused, naming `obstacle`.
    let err = ConvexObstacle::new(&[[0.0, 0.0], [1.0, 0.0], [0.2, 0.2], [0.0, 1.0]]).unwrap_err();
    assert!(err.to_string().contains("`obstacle`"), "{err}");
}
