//! The windowed clip's tests: against the full clip bit for bit, and its body-frame tests
//! of edges and discs against the placed corners.

use super::*;
use crate::geometry::convex_clip::edge;
use crate::numerics::seeded::uniform as rng;

/// A random convex polygon: corners at sorted random angles on an ellipse.
fn random_convex(r: f64, n: usize, seed: &mut u64) -> Polygon {
    let aspect = 0.3 + 0.7 * rng(seed);
    let mut angles: Vec<f64> = (0..n).map(|_| rng(seed) * std::f64::consts::TAU).collect();
    angles.sort_by(f64::total_cmp);
    angles.dedup_by(|x, y| (*x - *y).abs() < 1e-6);
    let v: Vec<[f64; 2]> = angles
        .iter()
        .map(|a| [r * a.cos(), r * aspect * a.sin()])
        .collect();
    Polygon::convex(&v).unwrap_or_else(|_| Polygon::regular(r, n.max(3)).unwrap())
}

fn placed(p: &PlacedPolygon) -> Vec<[f64; 2]> {
    (0..p.count()).map(|i| p.corner(i)).collect()
}

/// An edge told clear of a disc from its body-frame line has every point of the disc inside
/// its placed line (the clip's own side test), on random polygons at random placements,
/// sizes 1e-3 to 1e3 and discs from far to touching: the test never skips an edge that
/// would cut, and it does tell most clear edges.
#[test]
fn an_edge_told_clear_has_the_disc_inside_its_placed_line() {
    let mut seed = 5u64;
    let (mut told, mut clear_in_fact) = (0, 0);
    for case in 0..4000 {
        let s = &mut seed;
        let size = 10f64.powf(-3.0 + 6.0 * rng(s));
        let n = 3 + (rng(s) * 200.0) as usize;
        let poly = if case % 2 == 0 {
            Polygon::regular(size, n).unwrap()
        } else {
            random_convex(size, n, s)
        };
        let at = [size * (rng(s) - 0.5) * 20.0, size * (rng(s) - 0.5) * 20.0];
        let b = PlacedPolygon::new(&poly, at, rng(s) * 6.3);
        let ang = rng(s) * 6.3;
        let dist = poly.inradius * (0.5 + 0.6 * rng(s));
        let centre = [at[0] + dist * ang.cos(), at[1] + dist * ang.sin()];
        let reach = size * 0.2 * rng(s).powi(3);
        for j in 0..b.count() {
            let [b0, b1] = edge(&b, j as u32);
            let e = [b1[0] - b0[0], b1[1] - b0[1]];
            let side = |p: [f64; 2]| e[0] * (p[1] - b0[1]) - e[1] * (p[0] - b0[0]);
            let len = e[0].hypot(e[1]);
            let inside_by = side(centre) / len - reach;
            clear_in_fact += usize::from(inside_by > 1e-9 * size);
            if b.clears(j as u32, centre, reach) {
                told += 1;
                for k in 0..16 {
                    let a = k as f64 * std::f64::consts::TAU / 16.0;
                    let p = [centre[0] + reach * a.cos(), centre[1] + reach * a.sin()];
                    assert!(side(p) >= 0.0, "case {case} edge {j}: {p:?} outside");
                }
                assert!(inside_by >= 0.0, "case {case} edge {j}: {inside_by:e}");
            }
        }
    }
    assert!(told * 10 >= clear_in_fact * 9, "{told} of {clear_in_fact}");
}

/// A disc told inside a placed polygon by its body-frame lines lies inside every placed
/// edge's line (sampled on its rim), on random polygons, sizes and placements, discs from
/// deep inside to across the boundary; and most discs inside by a margin are told so.
#[test]
fn a_disc_told_inside_lies_inside_every_placed_edge() {
    let mut seed = 9u64;
    let (mut told, mut inside_in_fact, mut near) = (0, 0, 0);
    for case in 0..4000 {
        let s = &mut seed;
        let size = 10f64.powf(-3.0 + 6.0 * rng(s));
        let n = 3 + (rng(s) * 300.0) as usize;
        let poly = if case % 2 == 0 {
            Polygon::regular(size, n).unwrap()
        } else {
            random_convex(size, n, s)
        };
        let at = [size * (rng(s) - 0.5) * 20.0, size * (rng(s) - 0.5) * 20.0];
        let b = PlacedPolygon::new(&poly, at, rng(s) * 6.3);
        let ang = rng(s) * 6.3;
        let dist = poly.circumradius() * (1.05 * rng(s)).sqrt();
        let p = [at[0] + dist * ang.cos(), at[1] + dist * ang.sin()];
        let delta = size * 0.05 * rng(s).powi(4);
        let margin = (0..b.count())
            .map(|j| {
                let [b0, b1] = edge(&b, j as u32);
                let e = [b1[0] - b0[0], b1[1] - b0[1]];
                (e[0] * (p[1] - b0[1]) - e[1] * (p[0] - b0[0])) / e[0].hypot(e[1])
            })
            .fold(f64::INFINITY, f64::min);
        inside_in_fact += usize::from(margin > delta + 1e-9 * size);
        if b.holds_disc(p, delta, &mut near) {
            told += 1;
            // Less the placement's round-off (body-frame lines against placed corners).
            let round_off = 1e-14 * (size + at[0].abs() + at[1].abs());
            assert!(
                margin >= delta - round_off,
                "case {case}: {margin:e} < {delta:e}"
            );
        }
    }
    assert!(
        told * 10 >= inside_in_fact * 9,
        "{told} of {inside_in_fact}"
    );
    assert!(told > 1000, "{told}");
}

/// The windowed clip against the full clip, on random regular and convex polygons of 3 to
/// 300 corners, sizes 1e-2 to 1e2 apart, at every depth from grazing to one deep inside the
/// other, and corner on corner and face on face: the same vertices, bit for bit, with their
/// edge lines. Shallow contacts between many-cornered bodies take the window (not the full
/// clip's fallback) in most cases.
#[test]
fn the_window_gives_the_full_clip_bit_for_bit() {
    let mut seed = 11u64;
    let (mut full, mut next, mut win) = (Vec::new(), Vec::new(), Vec::new());
    let mut scratch = WindowScratch::default();
    let (mut overlapping, mut shallow_many, mut windowed) = (0, 0, 0);
    for case in 0..20000 {
        let s = &mut seed;
        let pick = |s: &mut u64| match (rng(s) * 4.0) as usize {
            0 => 3 + (rng(s) * 10.0) as usize,
            1 => 12,
            2 => 120,
            _ => 3 + (rng(s) * 300.0) as usize,
        };
        let (n, m) = (pick(s), pick(s));
        let r1 = if case % 2 == 0 {
            1.0
        } else {
            10f64.powf(-2.0 + 4.0 * rng(s))
        };
        let r2 = 1.0;
        let make = |r: f64, k: usize, s: &mut u64| {
            if rng(s) < 0.5 {
                Polygon::regular(r, k).unwrap()
            } else {
                random_convex(r, k, s)
            }
        };
        let (pa, pb) = (make(r1, n, s), make(r2, m, s));
        let reach = pa.circumradius() + pb.circumradius();
        // Corner on corner and face on face along y for one case in four.
        let (ang, phi1, phi2) = if case % 4 == 0 && n == 12 && m == 12 {
            let half = std::f64::consts::PI / 12.0;
            let k = (rng(s) * 2.0) as usize as f64;
            (
                std::f64::consts::FRAC_PI_2,
                -std::f64::consts::FRAC_PI_2 + k * half,
                std::f64::consts::FRAC_PI_2,
            )
        } else {
            (rng(s) * 6.3, rng(s) * 6.3, rng(s) * 6.3)
        };
        let depth = match case % 97 {
            // Centres at one point.
            0 => 1.0,
            _ if rng(s) < 0.7 => 1e-6 + 0.1 * rng(s),
            _ => rng(s),
        };
        let d = reach * (1.0 - depth);
        let q = [d * ang.cos(), d * ang.sin()];
        let (a, b) = (
            PlacedPolygon::new(&pa, q, phi1),
            PlacedPolygon::new(&pb, [0.0, 0.0], phi2),
        );
        let (va, vb) = (placed(&a), placed(&b));
        let theirs = clip_convex(&va[..], &vb[..], q, &mut full, &mut next);
        let before = FALLBACKS.with(|f| f.get());
        let ours = clip_in_window(&a, &b, q, &mut win, &mut scratch);
        assert_eq!(ours, theirs, "case {case}: n {n} m {m} q {q:?}");
        if theirs {
            overlapping += 1;
            assert_eq!(win, full, "case {case}: n {n} m {m} q {q:?}");
            if depth < 0.05 && n >= 60 && m >= 60 && r1 == 1.0 {
                shallow_many += 1;
                windowed += usize::from(FALLBACKS.with(|f| f.get()) == before);
            }
        }
    }
    let fell_back = FALLBACKS.with(|f| f.get());
    eprintln!("{overlapping} overlapping, {fell_back} fell back; {windowed} of {shallow_many} shallow ones windowed");
    assert!(overlapping > 10000, "{overlapping}");
    assert!(
        windowed * 10 >= shallow_many * 9,
        "{windowed} of {shallow_many}"
    );
}

/// Case `case`'s pair: an `n`-gon of circumradius 0.1 to 10 (random convex in every third
/// case) and an `m`-gon of circumradius 1 (random convex in every fifth), drawn from `s`.
fn drawn_pair(case: usize, (n, m): (usize, usize), s: &mut u64) -> (Polygon, Polygon) {
    let r1 = 10f64.powf(-1.0 + 2.0 * rng(s));
    let pa = if case % 3 == 0 {
        random_convex(r1, n, s)
    } else {
        Polygon::regular(r1, n).unwrap()
    };
    let pb = if case % 5 == 0 {
        random_convex(1.0, m, s)
    } else {
        Polygon::regular(1.0, m).unwrap()
    };
    (pa, pb)
}

/// The windowed clip along slow motions, as an impact's evaluations meet it: each pair turned
/// and moved a small part of a corner's angle per evaluation, from grazing through deep and
/// out again, so that the searches start from the last evaluation's corners (and the run of
/// B's edges grows from its last vertices' arcs), against the full clip bit for bit; and most
/// of these shallow contacts between many-cornered bodies stay in the window.
#[test]
fn the_window_follows_slow_motion_bit_for_bit() {
    let mut seed = 23u64;
    let (mut full, mut next, mut win) = (Vec::new(), Vec::new(), Vec::new());
    let mut scratch = WindowScratch::default();
    let (mut overlapping, mut fell_back) = (0, 0);
    for case in 0..120 {
        let s = &mut seed;
        let (n, m) = (
            [12, 40, 120, 300][case % 4],
            [120, 300, 17, 120][(case / 4) % 4],
        );
        let (pa, pb) = drawn_pair(case, (n, m), s);
        let reach = pa.circumradius() + pb.circumradius();
        let (ang0, phi1, phi2) = (rng(s) * 6.3, rng(s) * 6.3, rng(s) * 6.3);
        let (spin1, spin2, swing) = (rng(s) - 0.5, rng(s) - 0.5, 0.3 * (rng(s) - 0.5));
        let steps = 400;
        for k in 0..steps {
            // Along the line of centres from apart to 3 % of the reach deep and back.
            let t = k as f64 / steps as f64;
            let depth = 0.03 * (std::f64::consts::PI * t).sin() - 0.002;
            let ang = ang0 + swing * t;
            let d = reach * (1.0 - depth);
            let q = [d * ang.cos(), d * ang.sin()];
            let a = PlacedPolygon::new(&pa, q, phi1 + 0.05 * spin1 * t);
            let b = PlacedPolygon::new(&pb, [0.0, 0.0], phi2 + 0.05 * spin2 * t);
            let (va, vb) = (placed(&a), placed(&b));
            let theirs = clip_convex(&va[..], &vb[..], q, &mut full, &mut next);
            let before = FALLBACKS.with(|f| f.get());
            let ours = clip_in_window(&a, &b, q, &mut win, &mut scratch);
            assert_eq!(ours, theirs, "case {case} step {k}: n {n} m {m} q {q:?}");
            if theirs {
                overlapping += 1;
                assert_eq!(win, full, "case {case} step {k}: n {n} m {m} q {q:?}");
                fell_back += usize::from(FALLBACKS.with(|f| f.get()) != before);
            }
        }
    }
    eprintln!("{overlapping} overlapping, {fell_back} fell back");
    assert!(overlapping > 20000, "{overlapping}");
    assert!(
        fell_back * 10 <= overlapping,
        "{fell_back} of {overlapping}"
    );
}

/// Within round-off of a touch, as the searches for the first touch and the parting meet the
/// bodies, the window answers as the full clip, bit for bit, and tells most of the bodies
/// apart there without it (each of A's corners against the facing edge's line, as the full
/// clip's first clip tests them): random and regular 12- to 300-gons, sizes 0.1 to 10, each
/// moved along a random line of centres to where the full clip first finds them apart, then
/// within 2e-12 of that distance and by single ulps.
#[test]
fn the_window_gives_the_full_clip_at_a_touch() {
    let mut seed = 5u64;
    let (mut full, mut next, mut win) = (Vec::new(), Vec::new(), Vec::new());
    let mut scratch = WindowScratch::default();
    let (mut apart, mut told, mut overlapping) = (0, 0, 0);
    for case in 0..200 {
        let s = &mut seed;
        let (n, m) = (
            [12, 40, 120, 300][case % 4],
            [120, 17, 300, 120][(case / 4) % 4],
        );
        let (pa, pb) = drawn_pair(case, (n, m), s);
        let (ang, phi1, phi2) = (rng(s) * 6.3, rng(s) * 6.3, rng(s) * 6.3);
        let b = PlacedPolygon::new(&pb, [0.0, 0.0], phi2);
        let vb = placed(&b);
        let at = |d: f64| [d * ang.cos(), d * ang.sin()];
        let mut clip_full = |d: f64, full: &mut Vec<ClipVertex>| {
            let a = PlacedPolygon::new(&pa, at(d), phi1);
            clip_convex(&placed(&a)[..], &vb[..], at(d), full, &mut next)
        };
        // The nearest distance found apart, by bisection on the full clip's answer.
        let (mut lo, mut hi) = (1e-3, pa.circumradius() + pb.circumradius());
        assert!(clip_full(lo, &mut full) && !clip_full(hi, &mut full));
        loop {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if clip_full(mid, &mut full) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let near = (-20..=20)
            .map(|k| hi * (1.0 + k as f64 * 1e-13))
            .chain((-4i64..=4).map(|k| f64::from_bits((hi.to_bits() as i64 + k) as u64)));
        for d in near {
            let theirs = clip_full(d, &mut full);
            let a = PlacedPolygon::new(&pa, at(d), phi1);
            let before = FALLBACKS.with(|f| f.get());
            let ours = clip_in_window(&a, &b, at(d), &mut win, &mut scratch);
            assert_eq!(ours, theirs, "case {case} d {d}: n {n} m {m}");
            if theirs {
                overlapping += 1;
                assert_eq!(win, full, "case {case} d {d}: n {n} m {m}");
            } else {
                apart += 1;
                told += usize::from(FALLBACKS.with(|f| f.get()) == before);
            }
        }
    }
    eprintln!("{overlapping} overlapping, {apart} apart, {told} of them told in the window");
    assert!(overlapping > 1000 && apart > 1000, "{overlapping}, {apart}");
    // 92 %; 60 % where every apart one within round-off fell back to the full clip.
    assert!(told * 10 >= apart * 8, "{told} of {apart}");
}
