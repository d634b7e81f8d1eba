//! The held overlap's evaluation (`polygon_polygon.rs`): its vertices continued as the clip
//! places them, and its two certificates that the bodies overlap without the clip.

use super::*;
use crate::geometry::Polygon;

/// A convex body of size about `r`: a regular polygon of 3 to 200 corners, or 3 to 40 corners at
/// sorted random angles on an ellipse of aspect 1 to 1e-3 (sharp corners, long thin edges, edges
/// almost parallel to their neighbours).
fn random_body(rng: &mut impl FnMut() -> f64, r: f64) -> Polygon {
    if rng() < 0.5 {
        return Polygon::regular(r, 3 + (rng() * 198.0) as usize).unwrap();
    }
    loop {
        let n = 3 + (rng() * 38.0) as usize;
        let aspect = 10f64.powf(-3.0 * rng());
        let mut angles: Vec<f64> = (0..n).map(|_| rng() * std::f64::consts::TAU).collect();
        angles.sort_by(f64::total_cmp);
        let v: Vec<[f64; 2]> = angles
            .iter()
            .map(|a| [r * a.cos(), r * aspect * a.sin()])
            .collect();
        // Corners too close or too nearly collinear are refused: draw again.
        if let Ok(p) = Polygon::convex(&v) {
            return p;
        }
    }
}

/// A regular polygon's turn that sets the middle of one of its `n` edges facing `direction`.
fn facing(direction: f64, n: usize) -> f64 {
    direction - std::f64::consts::PI / n as f64
}

/// The held overlap of the placed polygons (a piece's start: the clip's own vertices and
/// chord), with the clip's vertices; `None` when they do not overlap in two crossings.
fn held_at(
    a: &PlacedPolygon,
    b: &PlacedPolygon,
    at: [f64; 2],
    window: &mut WindowScratch,
    clipped: &mut Vec<ClipVertex>,
) -> Option<HeldSprings> {
    if !clip_windowed(a, b, at, clipped, window) {
        return None;
    }
    let (k0, k1) = farthest_crossings(clipped)?;
    Some(HeldSprings {
        overlap: clipped.iter().map(|v| (v.before, v.after)).collect(),
        chord: [k0, k1],
        ..HeldSprings::default()
    })
}

/// Where either certificate (the chord's two crossings proper, or a small disc inside both)
/// says the bodies overlap, the clip finds them overlapping, so the adaptive path's pieces need
/// not ask it; and the held overlap is continued bit for bit where `meet` places each vertex,
/// with its crossings' edge normals. Random bodies (regular polygons of 3 to 200 corners, thin
/// and sharp convex ones), sizes 0.1 to 10 apart, every orientation, faces almost parallel (a
/// turn of 1e-14 to 1e-2 rad off), from grazing to deep; each held overlap continued to the
/// particle moved and both bodies turned by up to three times the overlap's depth (some apart). Of the
/// overlaps of more than 1e-12 of the reach squared, the crossings' certificate holds in most
/// and one of the two in nearly all.
#[test]
fn a_certain_overlap_is_one_the_clip_finds() {
    let mut seeded = crate::numerics::seeded::Seeded(3);
    let mut rng = move || seeded.uniform();
    let (mut by_crossings, mut by_either, mut deep, mut parallel) = (0, 0, 0, 0);
    let mut window = WindowScratch::default();
    let (mut out, mut clipped) = (Vec::new(), Vec::new());
    let mut hints = [0, 0];
    for case in 0..20000 {
        let (r1, r2) = (10f64.powf(rng() * 2.0 - 1.0), 1.0);
        let (pa, pb) = (random_body(&mut rng, r1), random_body(&mut rng, r2));
        let ang = rng() * std::f64::consts::TAU;
        let (mut phi_a, mut phi_b) = (rng() * 6.3, rng() * 6.3);
        let faces = case % 3 == 0;
        let (ra, rb) = if faces {
            // Two regular polygons face to face, one turned a hair off.
            let (n, m) = (pa.vertices().len(), pb.vertices().len());
            phi_b = facing(ang, m);
            let off = 10f64.powf(-14.0 + 12.0 * rng()) * (rng() - 0.5).signum();
            phi_a = facing(ang + std::f64::consts::PI, n) + off;
            let inr =
                |p: &Polygon, k: usize| p.circumradius() * (std::f64::consts::PI / k as f64).cos();
            (inr(&pa, n), inr(&pb, m))
        } else {
            (r1, r2)
        };
        let depth = 10f64.powf(-8.0 * rng()) * (ra + rb);
        let d = ra + rb - depth;
        let at = [d * ang.cos(), d * ang.sin()];
        let a = PlacedPolygon::new(&pa, at, phi_a);
        let b = PlacedPolygon::new(&pb, [0.0, 0.0], phi_b);
        let Some(held) = held_at(&a, &b, at, &mut window, &mut clipped) else {
            continue;
        };
        // Later in the piece: the particle moved, both turned (the held overlap continued).
        // Up to three times the depth: some pieces end apart.
        let step = depth * 10f64.powf(0.5 - 3.0 * rng());
        let mut move_by = |x: f64| x + step * (2.0 * rng() - 1.0);
        let at2 = [move_by(at[0]), move_by(at[1])];
        let (turn_a, turn_b) = (step * (2.0 * rng() - 1.0), step * (2.0 * rng() - 1.0));
        let a2 = PlacedPolygon::new(&pa, at2, phi_a + turn_a / r1);
        let b2 = PlacedPolygon::new(&pb, [0.0, 0.0], phi_b + turn_b / r2);
        let delta = OVERLAP_MARGIN * overlap_scale(&a2, &b2, at2);
        let (certain, normals) = continue_held(&held, (&a2, &b2), delta, &mut out);
        for (v, &(before, after)) in out.iter().zip(&held.overlap) {
            let p = meet(before, after, &a2, &b2);
            assert_eq!(v.p.map(f64::to_bits), p.map(f64::to_bits), "case {case}");
        }
        let chord = (held.chord[0], held.chord[1]);
        assert_eq!(normals, chord_normals(&out, chord, &a2, &b2), "case {case}");
        let disc = robustly_overlapping(&a2, &b2, at2, &out, &mut hints);
        let area = polygon_cap(out.iter().map(|v| v.p), out[0].p).area;
        let is_deep = area > 1e-12 * (r1 + r2).powi(2);
        deep += usize::from(is_deep);
        if certain || disc {
            assert!(
                clip_windowed(&a2, &b2, at2, &mut clipped, &mut window),
                "case {case}: certain ({certain}, {disc}), the clip finds no overlap"
            );
        }
        by_crossings += usize::from(certain && is_deep);
        by_either += usize::from((certain || disc) && is_deep);
        parallel += usize::from(certain && faces);
    }
    eprintln!(
        "{by_crossings} (crossings), {by_either} (either) certain of {deep} deep; {parallel} faces"
    );
    assert!(parallel > 1000, "{parallel}");
    // The crossings' test is the cheap one; the disc's covers faces turned less than its
    // margin (crossings along almost parallel lines) and crossings moved past a corner.
    assert!(by_crossings * 10 >= deep * 6, "{by_crossings} of {deep}");
    assert!(by_either * 100 >= deep * 95, "{by_either} of {deep}");
}
