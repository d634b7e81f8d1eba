//! The exact disc's overlap with the plate: the circular segment in closed form, and as a power
//! series in depth / 2r for shallow overlaps, which keeps full relative precision at touch.

use super::overlap::{Corners, Overlap};

/// u - sin(u), accurate also for small u where the difference cancels.
fn u_minus_sin(u: f64) -> f64 {
    if u < 0.1 {
        // Taylor series; the first omitted term is below 1e-19 relative at u = 0.1.
        let u2 = u * u;
        u * u2 / 6.0
            * (1.0 - u2 / 20.0 * (1.0 - u2 / 42.0 * (1.0 - u2 / 72.0 * (1.0 - u2 / 110.0))))
    } else {
        u - u.sin()
    }
}

/// Below this depth, as a fraction of the diameter (x = delta / (2 r) < 1/64), the disc
/// segment is evaluated from its power series in x; above it from the closed form.
const DISC_SERIES_MAX_X: f64 = 1.0 / 64.0;

/// A / (r^2 x^{3/2}) = sum_k AREA_SERIES[k] x^k, x = delta / (2 r). With x < 1/64 the first
/// omitted term is below 1e-19 relative.
const AREA_SERIES: [f64; 9] = [
    16.0 / 3.0,
    -8.0 / 5.0,
    -2.0 / 7.0,
    -1.0 / 9.0,
    -5.0 / 88.0,
    -7.0 / 208.0,
    -7.0 / 320.0,
    -0.015165441176470588, // -33/2176
    -0.011024876644736841, // -429/38912
];

/// d / r = sum_k CENTROID_SERIES[k] x^k: distance of the segment's centroid below the
/// disc's centre, d = 2 a^3 / (3 A) with a the half chord. First omitted term < 3e-21 at x = 1/64.
const CENTROID_SERIES: [f64; 10] = [
    1.0,
    -6.0 / 5.0,
    12.0 / 175.0,
    104.0 / 2625.0,
    0.02465009276437848,  // 8304/63165 (= 16/3 * 1557/336875)
    0.016190803482232053, // 16/3 * 66474/21896875
    0.011099082649776527, // 16/3 * 4784756/2299171875
    0.00788157956681174,  // 16/3 * 96268376/65143203125
    0.005766413852209299, // 16/3 * 515217398032/476522530859375
    0.004328884375497594, // 16/3 * 2486423898976/3063359126953125
];

/// Estrin evaluation (short dependency chains: this sits on the integrator's critical path).
#[inline(always)]
fn estrin9(c: &[f64; 9], x: f64, x2: f64, x4: f64, x8: f64) -> f64 {
    let p01 = c[0] + c[1] * x;
    let p23 = c[2] + c[3] * x;
    let p45 = c[4] + c[5] * x;
    let p67 = c[6] + c[7] * x;
    (p01 + x2 * p23) + x4 * (p45 + x2 * p67) + x8 * c[8]
}

/// See [`estrin9`].
#[inline(always)]
fn estrin10(c: &[f64; 10], x: f64, x2: f64, x4: f64, x8: f64) -> f64 {
    let p01 = c[0] + c[1] * x;
    let p23 = c[2] + c[3] * x;
    let p45 = c[4] + c[5] * x;
    let p67 = c[6] + c[7] * x;
    let p89 = c[8] + c[9] * x;
    (p01 + x2 * p23) + x4 * (p45 + x2 * p67) + x8 * p89
}

/// The circular segment of a disc of radius `r` with centre at height `y` below y = 0.
/// Written in terms of the depth delta = r - y so that tiny overlaps keep full relative precision:
/// a power series in delta / (2 r) for shallow overlaps (every contact of the paper preset), the
/// closed form beyond.
#[inline(always)]
pub(crate) fn disc_segment(r: f64, y: f64) -> Option<Overlap> {
    let depth = r - y;
    if depth <= 0.0 {
        return None;
    }
    Some(disc_segment_at(r, y, depth))
}

/// [`disc_segment`] for a positive `depth` = r - y. Its branches yield the segment's area,
/// centroid distance and half chord as numbers and the overlap is formed once after them:
/// formed in each branch, it went through memory, and reading it back there stalled the
/// adaptive path's every stage (removing it made the disc 1.12x faster).
#[inline(always)]
pub(crate) fn disc_segment_at(r: f64, y: f64, depth: f64) -> Overlap {
    let x = depth * (0.5 / r);
    let (area, d, half_chord) = if x >= DISC_SERIES_MAX_X {
        disc_segment_closed(r, depth)
    } else {
        let (x2, sx) = (x * x, x.sqrt());
        let (x4, rrx) = (x2 * x2, r * r * x);
        let x8 = x4 * x4;
        let area = rrx * (sx * estrin9(&AREA_SERIES, x, x2, x4, x8));
        let d = r * estrin10(&CENTROID_SERIES, x, x2, x4, x8);
        (area, d, (depth * (2.0 * r - depth)).sqrt())
    };
    segment(y, depth, area, d, half_chord)
}

/// A disc's circular segment below the plate, from its area, the distance `d` of its centroid
/// below the centre and its half chord (the series and the closed form share it).
fn segment(y: f64, depth: f64, area: f64, d: f64, half_chord: f64) -> Overlap {
    let cy = y - d;
    Overlap {
        area,
        cx: 0.0,
        cy,
        chord: 2.0 * half_chord,
        x_mid: 0.0,
        depth,
        x_low: 0.0,
        first_moment: -area * cy,
        corners: Corners::default(),
    }
}

/// The first moment about its chord of a disc's segment of depth `depth` (its area integrated
/// over the depths from 0 to `depth`: the area law's potential per unit stiffness of a disc
/// pressed into a half-plane, or of two equal discs, docs/model.md 17.8), and its area.
/// Below [`DISC_SERIES_MAX_X`] the area's series integrated term by term, M = r^3 x^{5/2}
/// sum_k 4 c_k / (2 k + 5) x^k (no cancellation at touch); beyond, M = 2 a^3 / 3 - (r - depth) A
/// (the moment about the centre, 2 a^3 / 3 for half chord a, moved to the chord), which
/// cancels by at most r / depth <= 32 there.
pub(crate) fn disc_segment_moment(r: f64, depth: f64) -> (f64, f64) {
    let x = depth * (0.5 / r);
    if x >= DISC_SERIES_MAX_X {
        let (area, _, half_chord) = disc_segment_closed(r, depth);
        let moment = 2.0 / 3.0 * half_chord * half_chord * half_chord - (r - depth) * area;
        return (moment, area);
    }
    let (x2, sx) = (x * x, x.sqrt());
    let (x4, rrx) = (x2 * x2, r * r * x);
    let x8 = x4 * x4;
    let area = rrx * (sx * estrin9(&AREA_SERIES, x, x2, x4, x8));
    let moment_series: [f64; 9] =
        std::array::from_fn(|k| 4.0 * AREA_SERIES[k] / (2 * k + 5) as f64);
    let moment = r * rrx * x * (sx * estrin9(&moment_series, x, x2, x4, x8));
    (moment, area)
}

/// How the height of a disc's segment centroid relative to the centre (`cy - y`, negative)
/// changes with the depth: d(cy - y)/d(depth) = -dz/d(depth), z = 4 r sin^3(t) / (3 (u - sin u))
/// the centroid's distance from the centre, t the half angle (cos t = 1 - depth / r), u = 2 t:
/// dz/d(depth) = (4/3) sin t (3 cos t (u - sin u) - 4 sin^3 t) / (u - sin u)^2. Its numerator
/// cancels to t^5 from terms of order t^3, so below t = 0.5 the Taylor series (through t^18, the
/// first omitted term below 1e-17 there) is used; 3/5 at the surface (a parabola's centroid
/// lies 2/5 of its height below the chord).
pub(crate) fn disc_arm_per_depth(r: f64, depth: f64) -> f64 {
    let t = 2.0 * (0.5 * depth / r).sqrt().asin();
    if t < 0.5 {
        // dz/d(depth) = sum c_k t^(2k), coefficients of the expansion above.
        const C: [f64; 10] = [
            -3.0 / 5.0,
            3.0 / 175.0,
            2.0 / 875.0,
            67.0 / 336875.0,
            146.0 / 13138125.0,
            4166.0 / 20692546875.0,
            -21092.0 / 586288828125.0,
            -193240721.0 / 38598324999609375.0,
            -211521614.0 / 578974874994140625.0,
            -3180273638.0 / 213846072946365234375.0,
        ];
        let t2 = t * t;
        -C.iter().rev().fold(0.0, |acc, c| acc * t2 + c)
    } else {
        let u = 2.0 * t;
        let (s, c) = t.sin_cos();
        let um = u - u.sin();
        -4.0 / 3.0 * s * (3.0 * c * um - 4.0 * s * s * s) / (um * um)
    }
}

/// The closed form of [`disc_segment`], valid at any positive depth: the segment's area, the
/// distance of its centroid below the centre and its half chord.
fn disc_segment_closed(r: f64, depth: f64) -> (f64, f64, f64) {
    let depth_c = depth.min(2.0 * r);
    // Half-angle of the segment, acos(y / r) written without cancellation.
    let half = 2.0 * (depth_c / (2.0 * r)).sqrt().min(1.0).asin();
    let area = 0.5 * r * r * u_minus_sin(2.0 * half);
    let half_chord = (depth_c * (2.0 * r - depth_c)).max(0.0).sqrt();
    // Distance of the segment's centroid below the centre: 2 a^3 / (3 A).
    let d = if area > 0.0 {
        2.0 * half_chord.powi(3) / (3.0 * area)
    } else {
        r
    };
    (area, d, half_chord)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The centroid's height per unit depth against central differences of the segment's own
    /// centroid (closed form, at depths where its round-off is small against the step), on
    /// both sides of the switch from series to closed form at half angle 0.5, and 3/5 at the
    /// surface.
    #[test]
    fn disc_arm_per_depth_is_the_rate_of_the_segment_centroid() {
        let r = 0.01;
        let arm = |depth: f64| {
            let y = r - depth;
            let (_, d, _) = disc_segment_closed(r, r - y);
            (y - d) - y
        };
        for depth in [1e-3 * r, 0.05 * r, 0.11 * r, 0.13 * r, 0.3 * r, 0.5 * r] {
            let h = 1e-5 * depth;
            let diff = (arm(depth + h) - arm(depth - h)) / (2.0 * h);
            let got = disc_arm_per_depth(r, depth);
            assert!((got - diff).abs() < 1e-6, "depth {depth}: {got} vs {diff}");
        }
        let t_switch = r * (1.0 - 0.5f64.cos());
        let (below, above) = (
            disc_arm_per_depth(r, t_switch * (1.0 - 1e-12)),
            disc_arm_per_depth(r, t_switch * (1.0 + 1e-12)),
        );
        assert!((below - above).abs() < 1e-13, "{below} vs {above}");
        assert!((disc_arm_per_depth(r, 1e-12 * r) - 0.6).abs() < 1e-12);
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1e-300)
    }

    #[test]
    fn disc_segment_matches_closed_form_at_half_depth() {
        // Centre on the plate: a half disc, centroid 4 r / (3 pi) below the centre.
        let r = 0.5;
        let o = disc_segment(r, 0.0).unwrap();
        assert!(close(o.area, 0.5 * PI * r * r, 1e-14), "area {}", o.area);
        assert!(close(o.cy, -4.0 * r / (3.0 * PI), 1e-14), "cy {}", o.cy);
        assert!(close(o.chord, 2.0 * r, 1e-14));
    }

    #[test]
    fn disc_segment_small_depth_keeps_relative_precision() {
        // A = (4/3) sqrt(2 r) delta^{3/2} (1 - delta / (10 r) + ...) for small delta.
        let r = 0.01;
        for &delta in &[1e-14, 1e-12, 1e-9, 1e-7] {
            let o = disc_segment(r, r - delta).unwrap();
            let approx =
                4.0 / 3.0 * (2.0 * r).sqrt() * delta.powf(1.5) * (1.0 - delta / (10.0 * r));
            // Computing y = r - delta loses bits of delta itself; compare against the delta
            // actually represented.
            let d_eff = r - (r - delta);
            let approx_eff = approx * (d_eff / delta).powf(1.5);
            assert!(
                close(o.area, approx_eff, 1e-6),
                "delta {delta}: {} vs {approx_eff}",
                o.area
            );
        }
    }

    /// (y, area, centroid distance below the centre) for r = 0.01, from 40-digit mpmath:
    /// A = r^2 (a - sin a cos a), d = 2 (r sin a)^3 / (3 A), a = acos(y / r), y the f64 value.
    const DISC_REFERENCE: [(f64, f64, f64); 15] = [
        (
            0.00999999999999,
            1.8858106567928402413e-22,
            0.0099999999999939997997,
        ),
        (
            0.00999999999,
            5.9628486791574033345e-18,
            0.0099999999939999997119,
        ),
        (
            0.00999999,
            1.88561780030459155e-13,
            0.0099999940000001716724,
        ),
        (
            0.009999,
            1.8855897986431648506e-10,
            0.0099994000017143348478,
        ),
        (0.00999, 5.9619534329329721454e-9, 0.0099940001714781111021),
        (0.00995, 6.6616644323508318328e-8, 0.0099700042919144070754),
        (0.0099, 1.8827871257349458845e-7, 0.0099400171925355237348),
        (0.0097, 9.7537493611135749244e-7, 0.0098201556354604793602),
        (0.009688, 1.0342907316232970133e-6, 0.0098129683942824314167),
        (0.009687, 1.0392515147854658229e-6, 0.0098123694804104530106),
        (0.0095, 2.0923024367597473671e-6, 0.0097004348598029072511),
        (0.009, 5.8725906877601890903e-6, 0.0094017654025490147941),
        (0.005, 0.000061418484930437844834, 0.0070502016189856615544),
        (0.0, 0.00015707963267948966846, 0.0042441318157838757089),
        (-0.005, 0.00025274078042854149209, 0.0017132680415009121503),
    ];

    #[test]
    fn disc_segment_matches_high_precision_reference() {
        let r = 0.01;
        for &(y, area, d) in &DISC_REFERENCE {
            let o = disc_segment(r, y).unwrap();
            let series = (r - y) * (0.5 / r) < DISC_SERIES_MAX_X;
            // The series keeps a few ulps; the closed form loses up to ~1e-13 to u - sin(u).
            let tol = if series { 4e-16 } else { 2e-13 };
            assert!(close(o.area, area, tol), "y {y}: area {} vs {area}", o.area);
            assert!(close(y - o.cy, d, tol), "y {y}: d {} vs {d}", y - o.cy);
        }
    }

    /// The segment's first moment about its chord against the closed form's cy (its
    /// centroid's height, at depths where the closed form keeps its digits: 2e-13 above), and
    /// against a quadrature of the area over the depth at touch, both sides of the series'
    /// switch; its rate is the area.
    #[test]
    fn disc_segment_moment_integrates_the_area() {
        let r = 0.01;
        for &(y, area, d) in &DISC_REFERENCE {
            let depth = r - y;
            let (moment, a) = disc_segment_moment(r, depth);
            let tol = if depth * (0.5 / r) < DISC_SERIES_MAX_X {
                4e-16
            } else {
                2e-13
            };
            assert!(close(a, area, tol), "y {y}: area {a} vs {area}");
            // The centroid lies d - y below the chord: the reference's d, rounded to a double,
            // keeps it to about an ulp of d.
            let want = area * (d - y);
            let tol = 2e-13 + 2.0 * f64::EPSILON * d / (d - y);
            assert!(close(moment, want, tol), "y {y}: {moment} vs {want}");
        }
        for depth in [
            1e-12 * r,
            1e-6 * r,
            0.02 * r,
            2.0 * r * DISC_SERIES_MAX_X,
            0.04 * r,
            0.5 * r,
        ] {
            // The segment's area integrated over the depth (`numerics::quadrature`).
            let quad =
                crate::numerics::quadrature::over_depth(|s| disc_segment_moment(r, s).1, depth);
            let (moment, _) = disc_segment_moment(r, depth);
            // The closed form keeps about 2e-13 (its area's u - sin u, above).
            let tol = if depth * (0.5 / r) < DISC_SERIES_MAX_X {
                1e-14
            } else {
                2e-13
            };
            assert!(
                close(moment, quad, tol),
                "depth {depth:e}: {moment} vs {quad}"
            );
        }
    }

    #[test]
    fn disc_segment_branches_agree_at_the_switch() {
        let r = 0.01;
        for k in -3i32..=3 {
            let depth = 2.0 * r * DISC_SERIES_MAX_X * (1.0 + 1e-9 * k as f64);
            let y = r - depth;
            let a = disc_segment(r, y).unwrap();
            let (area, d, half_chord) = disc_segment_closed(r, r - y);
            // Both within the closed form's own accuracy (see the reference test above).
            assert!(close(a.area, area, 2e-13), "{} vs {area}", a.area);
            assert!(close(a.cy, y - d, 2e-13), "{} vs {}", a.cy, y - d);
            assert_eq!(a.chord, 2.0 * half_chord);
        }
    }
}
