//! The gap's distances and separation against every edge's scan and the clip.

use super::{
    corner_distance, distance_from_corner, distance_to_polygon, near_edges_distance,
    vertices_distance,
};
use crate::geometry::convex_clip::{clip_convex, ClipVertex, Ring};
use crate::geometry::convex_window::PlacedPolygon;
use crate::geometry::Polygon;

/// The corner's distance measures only the edges facing it, and gives every edge's
/// minimum bit for bit: points all around random convex polygons (3 to 1024 corners),
/// near and far, inside, on vertices and on the extensions of edges.
#[test]
fn the_corner_distance_is_every_edges_bit_for_bit() {
    let mut seeded = crate::numerics::seeded::Seeded(7);
    let mut rng = move || seeded.uniform();
    for case in 0..400 {
        let n = [3usize, 4, 5, 12, 120, 1024][case % 6];
        let aspect = 0.3 + 0.7 * rng();
        let turn = rng() * std::f64::consts::TAU;
        let b: Vec<[f64; 2]> = (0..n)
            .map(|k| {
                let t = turn + std::f64::consts::TAU * k as f64 / n as f64;
                [t.cos(), aspect * t.sin()]
            })
            .collect();
        for k in 0..50 {
            let p = match k % 5 {
                0 => b[k % n],
                1 => {
                    let (u, v) = (b[k % n], b[(k + 1) % n]);
                    let s = 1.0 + 3.0 * rng();
                    [u[0] + s * (v[0] - u[0]), u[1] + s * (v[1] - u[1])]
                }
                _ => {
                    let (r, t) = (0.5 + 4.0 * rng(), rng() * std::f64::consts::TAU);
                    [r * t.cos(), r * t.sin()]
                }
            };
            let (fast, every) = (distance_from_corner(p, &b), distance_to_polygon(p, &b));
            assert_eq!(fast.to_bits(), every.to_bits(), "{n}-gon, p {p:?}");
        }
    }
}

/// The corner's distance read from the edges near it is every edge's, bit for bit: random
/// polygons of 33 to 1024 corners (regular, and convex ones of unequal edges, elongated up
/// to 20 to 1), turned and placed at random, corners from just off the boundary (1e-15.5 of
/// the size: the round-off of the placed corners) to a hundred sizes away, all round, with
/// hints left anywhere; and the window answers for nine in ten of the corners outside.
#[test]
fn the_near_edges_give_every_edges_distance_bit_for_bit() {
    let mut seeded = crate::numerics::seeded::Seeded(11);
    let mut rng = move || seeded.uniform();
    let (mut answered, mut apart, mut checked) = (0, 0, 0);
    for case in 0..300 {
        let n = [33usize, 64, 120, 200, 1024][case % 5];
        let poly = if case % 3 == 0 {
            Polygon::regular(0.3 + rng(), n).unwrap()
        } else {
            let aspect = 0.05 + 0.95 * rng();
            let mut angles: Vec<f64> = (0..n).map(|_| rng() * std::f64::consts::TAU).collect();
            angles.sort_by(f64::total_cmp);
            angles.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
            let v: Vec<[f64; 2]> = angles.iter().map(|t| [t.cos(), aspect * t.sin()]).collect();
            match Polygon::convex(&v) {
                Ok(p) => p,
                Err(_) => continue,
            }
        };
        let at = [rng() * 4.0 - 2.0, rng() * 4.0 - 2.0];
        let body = PlacedPolygon::new(&poly, at, rng() * 7.0);
        let b: Vec<[f64; 2]> = (0..body_count(&poly))
            .map(|i| crate::geometry::convex_clip::Ring::corner(&body, i))
            .collect();
        let mut hint = (rng() * n as f64) as usize;
        for k in 0..80 {
            let p = match k % 5 {
                // Off an edge along its normal, a thousandth to a third of the size away
                // (on an elongated polygon, far round from the corner farthest along p).
                4 => {
                    let i = (rng() * n as f64) as usize % n;
                    let (u, v) = (b[i], b[(i + 1) % n]);
                    let s = rng();
                    let e = [v[0] - u[0], v[1] - u[1]];
                    let len = e[0].hypot(e[1]);
                    let off = 10f64.powf(-3.0 + 2.5 * rng());
                    [
                        u[0] + s * e[0] + off * e[1] / len,
                        u[1] + s * e[1] - off * e[0] / len,
                    ]
                }
                // Just off a corner or an edge, along the outward direction from the centre.
                0 | 1 => {
                    let i = (rng() * n as f64) as usize % n;
                    let (u, v) = (b[i], b[(i + 1) % n]);
                    let s = if k % 5 == 0 { 0.0 } else { rng() };
                    let x = [u[0] + s * (v[0] - u[0]), u[1] + s * (v[1] - u[1])];
                    let d = [x[0] - at[0], x[1] - at[1]];
                    let off = 10f64.powf(-15.5 + 15.0 * rng());
                    [x[0] + off * d[0], x[1] + off * d[1]]
                }
                _ => {
                    let (r, t) = (10f64.powf(2.0 * rng()), rng() * std::f64::consts::TAU);
                    [at[0] + r * t.cos(), at[1] + r * t.sin()]
                }
            };
            let every = distance_to_polygon(p, &b);
            let window = corner_distance(p, &b, &body, &mut hint);
            assert_eq!(window.to_bits(), every.to_bits(), "{n}-gon, p {p:?}");
            checked += 1;
            if every > 0.0 {
                apart += 1;
                let mut fresh = hint;
                answered += usize::from(near_edges_distance(p, &b, &body, &mut fresh).is_some());
            }
            // Where every edge faces: the scan it replaces gives the same.
            assert_eq!(distance_from_corner(p, &b).to_bits(), every.to_bits());
        }
    }
    eprintln!("{checked} corners, {answered} of {apart} outside answered by the window");
    assert!(answered * 10 >= apart * 9, "{answered} of {apart}");
}

/// The window's bound holds: from random points (near and far) to random convex
/// polygons, every edge whose ends both turn at least as far from the point's direction as
/// a corner does lies at least the bound from the point.
#[test]
fn the_angular_bound_is_a_lower_bound() {
    let mut seeded = crate::numerics::seeded::Seeded(5);
    let mut rng = move || seeded.uniform();
    let angle = |w: [f64; 2], v: [f64; 2]| {
        let c = (w[0] * v[0] + w[1] * v[1]) / (w[0].hypot(w[1]) * v[0].hypot(v[1]));
        c.clamp(-1.0, 1.0).acos()
    };
    let mut tight = 0.0f64;
    for case in 0..200 {
        let n = [5usize, 12, 40, 120][case % 4];
        let aspect = 0.05 + 0.95 * rng();
        let turn0 = rng() * 7.0;
        let b: Vec<[f64; 2]> = (0..n)
            .map(|k| {
                let t = turn0 + std::f64::consts::TAU * k as f64 / n as f64;
                [t.cos(), aspect * t.sin()]
            })
            .collect();
        let radius = b.iter().map(|v| v[0].hypot(v[1])).fold(0.0, f64::max);
        for _ in 0..20 {
            let (r, t) = (10f64.powf(1.5 * rng() - 0.5), rng() * std::f64::consts::TAU);
            let w = [r * t.cos(), r * t.sin()];
            if super::inside(w, &b) {
                continue;
            }
            let len_w = w[0].hypot(w[1]);
            for &v in &b {
                let bound2 = super::angular_bound2(w, len_w, v, radius);
                let beta = angle(w, v);
                for j in 0..n {
                    let (e0, e1) = (b[j], b[(j + 1) % n]);
                    if angle(w, e0) < beta || angle(w, e1) < beta {
                        continue;
                    }
                    // Not across w's own direction (the window holds that one); across the
                    // opposite direction its points turn farther still.
                    let (t0, t1) = (super::cross(w, e0), super::cross(w, e1));
                    let behind = super::dot(w, e0) < 0.0 && super::dot(w, e1) < 0.0;
                    if (t0 > 0.0) != (t1 > 0.0) && !behind {
                        continue;
                    }
                    let d2 = super::segment_distance2(w, e0, e1);
                    assert!(d2 >= bound2 * (1.0 - 1e-12), "{d2} < {bound2}");
                    tight = tight.max(bound2 / d2);
                }
            }
        }
    }
    // The bound is close somewhere (not trivially small).
    assert!(tight > 0.9, "{tight}");
}

/// Where a line of one polygon has the other wholly outside by the margin, the clip finds
/// them apart (so the gap need not ask it), and the gap is then the corners' least
/// distance: random convex polygons of 3 to 1024 corners, elongated up to 20 to 1, turned
/// and placed from overlapping (crossed like a plus sign too) to apart.
#[test]
fn a_separating_line_is_one_the_clip_agrees_with() {
    let mut seeded = crate::numerics::seeded::Seeded(9);
    let mut rng = move || seeded.uniform();
    let mut clip = Default::default();
    let (mut certified, mut apart) = (0, 0);
    for case in 0..3000 {
        let (n, m) = (
            [3usize, 4, 5, 12, 120, 1024][case % 6],
            [4usize, 5, 7, 33, 200][case % 5],
        );
        let (pa, pb) = (elongated(&mut rng, n), elongated(&mut rng, m));
        let Placed {
            a,
            b,
            va,
            vb,
            overlap,
        } = placed(&mut rng, (&pa, &pb), &mut clip);
        apart += usize::from(!overlap);
        if super::separated((&va, &a), (&vb, &b)) {
            certified += 1;
            assert!(!overlap, "case {case}: separated, yet the clip overlaps");
        }
    }
    eprintln!("{certified} certified of {apart} apart");
    assert!(certified * 10 >= apart * 7, "{certified} of {apart}");
}

/// The corners' least distance measured from the corners near the other body alone
/// (`vertices_distance`, a walk for many corners) is every corner's least distance to the
/// other body's every edge, bit for bit: random convex polygons of 3 to 1024 corners,
/// elongated up to 20 to 1, of sizes 1e-2 to 1e2 apart, turned at random and placed from
/// crossed to apart, and at gaps of 1e-12 to 1e-1 of the smaller size from touching, both
/// ways round, hints left by the cases before; and so is the gap across a separating line
/// (`separated_gap`), from the corners that can be nearest across it alone.
#[test]
fn the_corners_least_distance_is_every_corners_bit_for_bit() {
    let mut seeded = crate::numerics::seeded::Seeded(31);
    let mut rng = move || seeded.uniform();
    let mut clip: ClipBuffers = Default::default();
    let (mut walked, mut across) = (0, 0);
    for case in 0..2400 {
        let (n, m) = (
            [3usize, 12, 33, 120, 1024, 200][case % 6],
            [4usize, 5, 12, 48, 120][case % 5],
        );
        let size = 10f64.powf(4.0 * rng() - 2.0);
        let (pa, pb) = (
            elongated(&mut rng, n),
            scaled(&elongated(&mut rng, m), size),
        );
        let Placed { a, b, va, vb, .. } = if case % 2 == 0 {
            placed(&mut rng, (&pa, &pb), &mut clip)
        } else {
            let gap = 10f64.powf(11.0 * rng() - 12.0) * pa.inradius.min(pb.inradius);
            near_touch(&mut rng, (&pa, &pb), gap, &mut clip)
        };
        let mut both = f64::INFINITY;
        for (side, ((x, bx), (y, by))) in [((&va, &a), (&vb, &b)), ((&vb, &b), (&va, &a))]
            .into_iter()
            .enumerate()
        {
            let every = x
                .iter()
                .map(|&p| distance_to_polygon(p, y))
                .fold(f64::INFINITY, f64::min);
            let got = vertices_distance((x, bx), (y, by), 1 - side);
            assert_eq!(
                got.to_bits(),
                every.to_bits(),
                "case {case}: {got:e} vs {every:e}"
            );
            walked += usize::from(x.len() > super::FEW_EDGES);
            both = both.min(every);
        }
        // Across a separating line: the corners that can be nearest alone.
        if let Some(got) = super::separated_gap((&va, &a), (&vb, &b)) {
            assert_eq!(
                got.to_bits(),
                both.to_bits(),
                "case {case}: {got:e} vs {both:e}"
            );
            across += 1;
        }
    }
    assert!(walked > 1500 && across > 800, "{walked} {across}");
}

/// `poly` scaled by `size` about its centroid.
fn scaled(poly: &Polygon, size: f64) -> Polygon {
    let v: Vec<[f64; 2]> = poly
        .vertices()
        .iter()
        .map(|v| [size * v.x, size * v.y])
        .collect();
    Polygon::convex(&v).unwrap()
}

/// `pa` and `pb` placed as by [`placed`], then moved along the line of their centres to
/// `gap` (to a relative 1e-14) from where the full clip first finds them overlapping.
fn near_touch<'a>(
    rng: &mut dyn FnMut() -> f64,
    (pa, pb): (&'a Polygon, &'a Polygon),
    gap: f64,
    buffers: &mut ClipBuffers,
) -> Placed<'a> {
    let (ang, phi_a, phi_b) = (rng() * std::f64::consts::TAU, rng() * 7.0, rng() * 7.0);
    let u = [ang.cos(), ang.sin()];
    let at = |d: f64| [d * u[0], d * u[1]];
    let bodies = |d: f64| {
        let a = PlacedPolygon::new(pa, at(d), phi_a);
        let b = PlacedPolygon::new(pb, [0.0, 0.0], phi_b);
        let corners = |body: &PlacedPolygon| -> Vec<[f64; 2]> {
            (0..body.polygon().vertices().len())
                .map(|i| Ring::corner(body, i))
                .collect()
        };
        let (va, vb) = (corners(&a), corners(&b));
        (a, b, va, vb)
    };
    let (out, next) = buffers;
    let (mut lo, mut hi) = (0.0, pa.circumradius() + pb.circumradius());
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let (_, _, va, vb) = bodies(mid);
        if clip_convex(&va[..], &vb[..], at(mid), out, next) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (a, b, va, vb) = bodies(hi + gap);
    Placed {
        a,
        b,
        va,
        vb,
        overlap: false,
    }
}

fn body_count(poly: &Polygon) -> usize {
    poly.vertices().len()
}

/// A body's least corner outside the line of the other body's edges facing its centre
/// (`corners_outside_a_line`) has every corner outside that line by the separation's margin,
/// and the clip finds the two apart: random convex polygons of 33 to 1024 corners, elongated
/// up to 20 to 1, placed from crossed to apart. Read at another corner than the least (the
/// centre's nearest, say), the test fails on the placements whose corners cross the line.
#[test]
fn a_least_corner_outside_a_line_has_every_corner_outside_it() {
    let mut seeded = crate::numerics::seeded::Seeded(23);
    let mut rng = move || seeded.uniform();
    let mut clip = Default::default();
    let (mut certified, mut apart) = (0, 0);
    for case in 0..3000 {
        let (n, m) = (
            [33usize, 48, 120, 1024][case % 4],
            [3usize, 5, 12, 120, 200][case % 5],
        );
        let (pa, pb) = (elongated(&mut rng, n), elongated(&mut rng, m));
        let Placed {
            a, b, va, overlap, ..
        } = placed(&mut rng, (&pa, &pb), &mut clip);
        apart += usize::from(!overlap);
        if !super::corners_outside_a_line(&va, &a, &b) {
            continue;
        }
        certified += 1;
        assert!(
            !overlap,
            "case {case}: the circle is outside, yet the clip overlaps"
        );
        let [nx, ny, h] = super::facing_edge_line(&b, a.centre(), 0);
        let nw = b.in_world([nx, ny]);
        let c = b.centre();
        let scale = pb.circumradius() + c[0].abs() + c[1].abs();
        for p in &va {
            let beyond = nw[0] * (p[0] - c[0]) + nw[1] * (p[1] - c[1]) - h;
            let margin = super::SEPARATION * (scale + p[0].abs() + p[1].abs());
            assert!(
                beyond > margin,
                "case {case}: a corner {beyond} within {margin}"
            );
        }
    }
    eprintln!("{certified} certified of {apart} apart");
    assert!(certified * 2 >= apart, "{certified} of {apart}");
}

/// A convex polygon of `n` corners on an ellipse of aspect 1 to 20 to 1 (up to 1).
fn elongated(rng: &mut dyn FnMut() -> f64, n: usize) -> Polygon {
    let aspect = 0.05 + 0.95 * rng();
    let v: Vec<[f64; 2]> = (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            [t.cos(), aspect * t.sin()]
        })
        .collect();
    Polygon::convex(&v).unwrap()
}

/// Two polygons placed, their corners, and whether the full clip finds them overlapping.
struct Placed<'a> {
    a: PlacedPolygon<'a>,
    b: PlacedPolygon<'a>,
    va: Vec<[f64; 2]>,
    vb: Vec<[f64; 2]>,
    overlap: bool,
}

/// The clip's buffers, reused from case to case.
type ClipBuffers = (Vec<ClipVertex>, Vec<ClipVertex>);

/// `pa` turned at random and placed in a random direction at 0.2 to 1.2 times the sum of the
/// circumradii from `pb`, turned at random at the origin: from crossed to apart.
fn placed<'a>(
    rng: &mut dyn FnMut() -> f64,
    (pa, pb): (&'a Polygon, &'a Polygon),
    (out, next): &mut ClipBuffers,
) -> Placed<'a> {
    let ang = rng() * std::f64::consts::TAU;
    let d = (pa.circumradius() + pb.circumradius()) * (0.2 + 1.0 * rng());
    let at = [d * ang.cos(), d * ang.sin()];
    let a = PlacedPolygon::new(pa, at, rng() * 7.0);
    let b = PlacedPolygon::new(pb, [0.0, 0.0], rng() * 7.0);
    let corners = |body: &PlacedPolygon| -> Vec<[f64; 2]> {
        (0..body.polygon().vertices().len())
            .map(|i| Ring::corner(body, i))
            .collect()
    };
    let (va, vb) = (corners(&a), corners(&b));
    let overlap = clip_convex(&va[..], &vb[..], at, out, next);
    Placed {
        a,
        b,
        va,
        vb,
        overlap,
    }
}
