//! Property tests: the half-plane clip and the general parry path compute the same overlap, to
//! round-off, for random convex polygons at random orientations and depths (slivers included).

use proptest::prelude::*;
use restitution_core::{OverlapMethod, Shape};
use std::f64::consts::PI;

/// A random convex polygon: sorted angles on the unit circle, then a random affine map
/// (scale, stretch, shear), which keeps it convex. `None` when the validation refuses it
/// (nearly coincident or collinear vertices).
fn polygon(angles: &[f64], scale: f64, stretch: f64, shear: f64) -> Option<Shape> {
    let mut a = angles.to_vec();
    a.sort_by(f64::total_cmp);
    let v: Vec<[f64; 2]> = a
        .iter()
        .map(|t| {
            let (x, y) = (t.cos(), stretch * t.sin());
            [scale * (x + shear * y), scale * y]
        })
        .collect();
    Shape::convex_polygon(&v).ok()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn half_plane_and_parry_paths_agree(
        angles in prop::collection::vec(0.0..2.0 * PI, 3..24),
        log_scale in -3.0f64..1.0,
        stretch in 0.2f64..1.0,
        shear in -1.0f64..1.0,
        phi in 0.0..2.0 * PI,
        log_frac in -12.0f64..0.0,
    ) {
        let shape = polygon(&angles, 10f64.powf(log_scale), stretch, shear);
        prop_assume!(shape.is_some());
        let shape = shape.unwrap();
        let r = shape.circumradius();
        // Depth: a fraction (down to 1e-12, slivers) of the polygon's height at this angle,
        // never beyond 90 % of it.
        let height = shape.touch_height(phi) + shape.touch_height(phi + PI);
        let y = shape.touch_height(phi) - 0.9 * 10f64.powf(log_frac) * height;
        let a = restitution_core::plate_overlap(&shape, OverlapMethod::HalfPlane, y, phi);
        let b = restitution_core::plate_overlap(&shape, OverlapMethod::Parry, y, phi);
        prop_assert_eq!(a.is_some(), b.is_some());
        let (Some(a), Some(b)) = (a, b) else { return Ok(()) };
        prop_assert_eq!(a.depth, b.depth);
        prop_assert_eq!(a.x_low, b.x_low);
        // Relative to the overlap's own size (area, sqrt(area) for lengths), with a floor at
        // the round-off of the coordinates themselves (ulp(r) ~ 1e-16 r).
        let size = a.area.sqrt().max(a.chord);
        let tol_len = 1e-12 * size + 1e-15 * r;
        prop_assert!((a.area - b.area).abs() <= 1e-12 * a.area + 1e-15 * r * size,
            "area {} vs {}", a.area, b.area);
        prop_assert!((a.cx - b.cx).abs() <= tol_len, "cx {} vs {} ({a:?})", a.cx, b.cx);
        prop_assert!((a.cy - b.cy).abs() <= tol_len, "cy {} vs {}", a.cy, b.cy);
        prop_assert!((a.chord - b.chord).abs() <= tol_len, "chord {} vs {}", a.chord, b.chord);
        prop_assert!((a.x_mid - b.x_mid).abs() <= tol_len, "x_mid {} vs {}", a.x_mid, b.x_mid);
        for v in [b.area, b.cx, b.cy, b.chord, b.x_mid, b.first_moment] {
            prop_assert!(v.is_finite());
        }
    }

    #[test]
    fn lowest_vertex_search_matches_a_full_scan(
        angles in prop::collection::vec(0.0..2.0 * PI, 3..40),
        stretch in 0.05f64..1.0,
        shear in -2.0f64..2.0,
        phi in -10.0..10.0f64,
    ) {
        // The O(log n) search (binary search on polar angles, then descent) finds the same
        // lowest point as scanning every vertex, also for thin, sheared polygons.
        let shape = polygon(&angles, 0.01, stretch, shear);
        prop_assume!(shape.is_some());
        let shape = shape.unwrap();
        let (s, c) = phi.sin_cos();
        let scan = shape
            .vertices()
            .iter()
            .map(|v| s * v.x + c * v.y)
            .fold(f64::INFINITY, f64::min);
        // To rounding: the engine turns corners by its own sine and cosine, within about an
        // ulp of the library's; a wrong vertex would sit a whole edge's slope away.
        let tol = 8.0 * f64::EPSILON * 0.01;
        prop_assert!((shape.touch_height(phi) + scan).abs() <= tol, "{} vs {}", shape.touch_height(phi), -scan);
    }

    #[test]
    fn overlap_is_continuous_in_depth_and_angle(
        n in 3usize..12,
        phi in 0.0..2.0 * PI,
        log_depth in -14.0f64..-1.0,
    ) {
        // Small changes of the placement change area and centroid a little: no jumps at the
        // moments a vertex crosses the plate or an edge turns parallel to it.
        let r = 0.01;
        let shape = Shape::regular_polygon(r, n).unwrap();
        let y = shape.touch_height(phi) - r * 10f64.powf(log_depth);
        for method in [OverlapMethod::HalfPlane, OverlapMethod::Parry] {
            let o = restitution_core::plate_overlap(&shape, method, y, phi).unwrap();
            for (dy, dphi) in [(1e-12 * r, 0.0), (-1e-12 * r, 0.0), (0.0, 1e-12), (0.0, -1e-12)] {
                let Some(p) = restitution_core::plate_overlap(&shape, method, y + dy, phi + dphi) else {
                    // Only possible when the step lifts the particle clear of the plate.
                    prop_assert!(o.depth < 2e-12 * r);
                    continue;
                };
                // dA = chord * d(depth); the depth moves by at most |dy| + r |dphi|.
                let dd = 1e-12 * r * 1.0001 + 1e-18;
                prop_assert!((p.area - o.area).abs() <= 2.0 * r * dd + 1e-15 * o.area,
                    "{method:?}: {o:?} -> {p:?}");
            }
        }
    }
}
