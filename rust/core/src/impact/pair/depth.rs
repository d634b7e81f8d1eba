//! The pair's largest overlap from the energy balance of its undamped normal law, and the
//! refusal of overlaps past half a body's radius.

use super::Start;
use crate::error::{Error, Result};
use crate::geometry::pair::{PairFrame, PairGeometry};
use crate::model::{Initial, NormalLaw, Pair};
use crate::numerics::roots;
use std::cell::Cell;

/// The pair's largest overlap from the energy balance of its undamped normal law along a
/// head-on approach from the first touch `start` (orientations held), refused where a body's
/// cap would pass half its radius (as r / 2 on the plate; for bodies with corners, the caps
/// of their circumscribed circles).
pub(super) fn estimate_max_overlap<G: PairGeometry>(
    pair: &Pair,
    init: &Initial,
    geometry: &G,
    start: &Start,
) -> Result<f64> {
    let law = &pair.law;
    let (r1, r2) = (pair.particle.r, pair.r2);
    let ke = 0.5 * pair.m_star * init.vy * init.vy;
    let hi = largest_overlap(r1, r2);
    let frame = |s: f64| {
        let q = start.q;
        geometry.frame(&[q[0], q[1] - s, q[2], q[3]])
    };
    let x0 = first_guess(pair, ke);
    let x0 = if x0 > 0.0 && x0 < hi { x0 } else { hi };
    let found = if G::CORNERS && matches!(law.scene.normal_law, NormalLaw::Area) {
        // Bodies with corners: the guess moved by one frame's power law, and the potential
        // continued from iterate to iterate (`ContinuedPotential`).
        let k = law.scene.e_modulus / law.length;
        let x0 = powered_guess(&frame, ke / k, x0, hi);
        let continued = ContinuedPotential::new(&frame, k);
        let potential = |delta: f64| continued.at(delta);
        roots::log_newton_below(potential, ke, (x0, potential(x0)), hi)
    } else {
        let potential = |delta: f64| overlap_potential(pair, geometry, &frame, delta);
        roots::log_newton_below(potential, ke, (x0, potential(x0)), hi)
    };
    found.ok_or_else(|| {
        let stiff = match law.scene.normal_law {
            NormalLaw::Linear { kn, .. } => format!("kn = {:e} Pa", 2.0 * kn),
            _ => format!("E = {:e} Pa", pair.particle.scene.e_modulus),
        };
        Error::invalid(
            "v",
            init.vx.hypot(init.vy),
            format!(
                "small enough that each body's estimated overlap stays below half its radius at \
                 {stiff} (normal kinetic energy {ke:e} J exceeds the elastic energy there: lower \
                 v or raise the modulus)"
            ),
        )
    })
}

/// Where the Newton iteration of the largest overlap starts: the overlap at which the
/// leading term of the round bodies' potential (the circumscribed circles' for bodies with
/// corners) reaches the normal kinetic energy `ke`: the lens's k (8/15) sqrt(2 R*)
/// delta^(5/2), R* = r1 r2 / (r1 + r2) (twice the segment's (4/3) sqrt(2 R*) delta^(3/2)
/// integrated), Hertz's (2/5) k delta^(5/2), a spring's k delta^2 / 2. Within a few per cent of
/// the root for round bodies; for bodies with corners a power of the depth all the same, which
/// the iteration's first step corrects (it was started at the largest overlap, where the law
/// is furthest from its power near touch, and evaluated the potential there at every impact).
fn first_guess(pair: &Pair, ke: f64) -> f64 {
    let law = &pair.law;
    match law.scene.normal_law {
        NormalLaw::Area => {
            let (r1, r2) = (pair.particle.r, pair.r2);
            let k = law.scene.e_modulus / law.length;
            let r_star = r1 * r2 / (r1 + r2);
            (15.0 * ke / (8.0 * k * (2.0 * r_star).sqrt())).powf(0.4)
        }
        NormalLaw::Linear { kn, .. } => (2.0 * ke / kn).sqrt(),
        NormalLaw::Hertz { .. } => {
            let k = law.hertz.map_or(0.0, |h| h.k);
            (2.5 * ke / k).powf(0.4)
        }
    }
}

/// The first guess `x0` (in (0, `hi`]) moved to where the overlap's area as a power of the
/// approach, read from one frame there (its area A and rate dA/ds = l n_y: the power p = x0
/// A' / A), integrates to the potential `w` per unit stiffness: x0 (w (p + 1) / (A x0))^(1 /
/// (p + 1)). The round bodies' leading term is one power for every pairing, where a corner's
/// area grows like s^2 and an edge's like s: two 12-gons corner on corner started at half the
/// root, and the first iterate's eight frames went to correcting that. `x0` where the frame
/// has no overlap or the power is not positive.
fn powered_guess(frame: &impl Fn(f64) -> Option<PairFrame>, w: f64, x0: f64, hi: f64) -> f64 {
    let Some(f) = frame(x0) else {
        return x0;
    };
    let power = x0 * f.chord * f.n[1] / f.area;
    let moved = x0 * (w * (power + 1.0) / (f.area * x0)).powf(1.0 / (power + 1.0));
    if f.area > 0.0 && power > 0.0 && moved > 0.0 && moved < hi {
        moved
    } else {
        x0
    }
}

/// The area law's potential per unit stiffness along a head-on approach, evaluated at the
/// Newton iteration's iterates: at an overlap far from the anchor (the last such, or none
/// yet), the 8-point quadrature of [`overlap_potential`] (its own rate), which becomes the
/// anchor; within [`CONTINUE_WITHIN`] of it, the anchor's potential plus the area's integral
/// from there by Simpson's rule, and that sum's own rate (three frames, two once the anchor's
/// area is known, where the quadrature took eight). Between the events where a corner
/// crosses an edge's line, the overlap of two polygons with orientations held is a polygon
/// whose vertices move linearly with the approach, its area a quadratic, which Simpson's rule
/// integrates exactly; the iterates near the root are a small fraction of the overlap apart,
/// and an event between them moves the potential by a small fraction of that fraction's
/// square. One anchor for every iterate near it, so that the potential is one function there
/// and the iteration converges on its root quadratically (continued from each iterate in
/// turn, the iterates' potentials disagreed at 1e-13 and the bracket of the root closed on
/// none of them). An iterate within [`TANGENT_WITHIN`] of the last one evaluated reads that
/// one's tangent instead ([`Self::at`]).
struct ContinuedPotential<'a, F> {
    frame: &'a F,
    stiffness: f64,
    /// The anchor: its overlap, potential and (once read) area.
    anchor: Cell<Option<(f64, f64, Option<f64>)>>,
    /// The last iterate evaluated from frames: its overlap, potential and rate (per unit
    /// stiffness).
    last: Cell<Option<(f64, f64, f64)>>,
}

/// How near the anchor (relative to it) an iterate continues its potential.
const CONTINUE_WITHIN: f64 = 0.1;

/// How near the last iterate evaluated (relative to it) an iterate reads that one's tangent:
/// the tangent's error there, half the area's rate times the distance squared, is 1e-18 of
/// the potential, below its last bit, and the rate's 1e-9 of itself moves a Newton step that
/// small by less still.
const TANGENT_WITHIN: f64 = 1e-9;

impl<'a, F: Fn(f64) -> Option<PairFrame>> ContinuedPotential<'a, F> {
    fn new(frame: &'a F, stiffness: f64) -> Self {
        ContinuedPotential {
            frame,
            stiffness,
            anchor: Cell::new(None),
            last: Cell::new(None),
        }
    }

    /// The overlap's area at the approach `s` and its rate in s (the chord's length times
    /// n_y, 17.2).
    fn area(&self, s: f64) -> (f64, f64) {
        (self.frame)(s).map_or((0.0, 0.0), |f| (f.area, f.chord * f.n[1]))
    }

    /// The potential and its rate (the elastic force) at the overlap `delta`. Newton's last
    /// iterate lies within round-off of the one before (two 120-gons: 5.6e-13 of it), where it
    /// only confirms the root: read on the tangent there, not from two more frames (each a
    /// clip of the bodies, an eighth of the estimate's).
    fn at(&self, delta: f64) -> (f64, f64) {
        if let Some((d, w, rate)) = self.last.get() {
            if (delta - d).abs() <= TANGENT_WITHIN * d {
                let k = self.stiffness;
                return (k * (w + rate * (delta - d)), k * rate);
            }
        }
        let (potential, rate) = match self.anchor.get() {
            Some((a, w, known)) if (delta - a).abs() <= CONTINUE_WITHIN * a => {
                let a0 = known.unwrap_or_else(|| self.area(a).0);
                self.anchor.set(Some((a, w, Some(a0))));
                let ((mid, mid_rate), (end, end_rate)) =
                    (self.area(0.5 * (a + delta)), self.area(delta));
                let h = delta - a;
                let added = h / 6.0 * (a0 + 4.0 * mid + end);
                // d/d delta of h/6 (A(a) + 4 A(a + h/2) + A(a + h)).
                let rate = (a0 + 4.0 * mid + end) / 6.0 + h / 6.0 * (2.0 * mid_rate + end_rate);
                (w + added, rate)
            }
            _ => {
                let (w, rate) = gauss_area_potential(self.frame, delta);
                self.anchor.set(Some((delta, w, None)));
                (w, rate)
            }
        };
        self.last.set(Some((delta, potential, rate)));
        (self.stiffness * potential, self.stiffness * rate)
    }
}

/// The overlap delta at which a body's cap reaches half its radius first. The particle's cap
/// depth is h1 = delta (2 r2 - delta) / (2 (r1 + r2 - delta)) (the chord on the radical line),
/// so h1 = r1 / 2 where delta^2 - (r1 + 2 r2) delta + r1 (r1 + r2) = 0: its smaller root,
/// written as the product of the roots over the larger (no cancellation), real where
/// 4 r2^2 >= 3 r1^2 (a partner much smaller than the particle never cuts half of it); the
/// partner's the same with the radii exchanged. At most the smaller radius (two equal discs
/// reach it there).
fn largest_overlap(r1: f64, r2: f64) -> f64 {
    let reaches_half = |r1: f64, r2: f64| {
        let disc = 4.0 * r2 * r2 - 3.0 * r1 * r1;
        if disc < 0.0 {
            return f64::INFINITY;
        }
        2.0 * r1 * (r1 + r2) / (r1 + 2.0 * r2 + disc.sqrt())
    };
    reaches_half(r1, r2)
        .min(reaches_half(r2, r1))
        .min(r1.min(r2))
}

/// The undamped normal law's potential at an approach `delta` from first touch and its rate
/// (the elastic force), from the contact's frames along the approach (`frame`).
fn overlap_potential<G: PairGeometry>(
    pair: &Pair,
    geometry: &G,
    frame: &impl Fn(f64) -> Option<PairFrame>,
    delta: f64,
) -> (f64, f64) {
    let law = &pair.law;
    // The integral of a force over the approach: Gauss-Legendre on delta t^2, t in [0, 1]
    // (the lens's area grows like delta^(3/2), a corner's like delta^2).
    let integral = |force: &dyn Fn(f64) -> f64| -> f64 {
        GAUSS_8
            .iter()
            .map(|&(x, w)| {
                let t = 0.5 * (x + 1.0);
                0.5 * w * force(delta * t * t) * 2.0 * delta * t
            })
            .sum()
    };
    match law.scene.normal_law {
        NormalLaw::Area => {
            let k = law.scene.e_modulus / law.length;
            if let Some((potential, area)) = geometry.area_potential(delta) {
                return (k * potential, k * area);
            }
            let (potential, rate) = gauss_area_potential(frame, delta);
            (k * potential, k * rate)
        }
        NormalLaw::Linear { kn, .. } => {
            // The springs' depths (their pushes turn with the edges they press on: their sum is
            // the force an approach meets, whatever the direction).
            let springs = |s: f64| frame(s).map_or(0.0, |f| f.springs.depth);
            (kn * integral(&springs), kn * springs(delta))
        }
        NormalLaw::Hertz { .. } => {
            let k = law.hertz.map_or(0.0, |h| h.k);
            let f = k * delta * delta.sqrt();
            (0.4 * f * delta, f)
        }
    }
}

/// The area law's potential per unit stiffness at the overlap `delta` of the approach whose
/// frames `frame` gives, the overlap's area integrated by 8-point Gauss-Legendre in delta t^2,
/// and its rate in delta.
fn gauss_area_potential(frame: &impl Fn(f64) -> Option<PairFrame>, delta: f64) -> (f64, f64) {
    // The quadrature's own rate in delta from the same frames: d/d delta of A(delta t^2) 2
    // delta t is 2 t (A + s dA/ds) at s = delta t^2, and an approach along -y grows the area
    // at its chord's length times n_y (17.2). Newton then converges on the quadrature's root
    // at its own pace (with the area at delta for the rate, which the quadrature's does not
    // match at a corner's kink, two 120-gons took six evaluations, each nine frames).
    let (mut potential, mut rate) = (0.0, 0.0);
    for &(x, w) in &GAUSS_8 {
        let t = 0.5 * (x + 1.0);
        let s = delta * t * t;
        if let Some(f) = frame(s) {
            potential += w * f.area * delta * t;
            rate += w * t * (f.area + s * f.chord * f.n[1]);
        }
    }
    (potential, rate)
}

/// Gauss-Legendre nodes and weights on [-1, 1], 8 points.
const GAUSS_8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329_0, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329_0, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
];

#[cfg(test)]
mod tests {
    use super::super::Start;
    use super::*;
    use crate::geometry::pair::DiscPair;
    use crate::geometry::pair_shapes::ShapePair;
    use crate::geometry::Shape;
    use crate::model::{Model, Partner, Scene};

    /// The area law's quadrature and its rate along the approach against the rate's central
    /// difference, for unequal discs, two 120-gons, two 12-gons and a disc on a 12-gon at
    /// several orientations and depths (the rate of the quadrature itself, so the Newton
    /// iteration converges on its root quadratically).
    #[test]
    fn the_potential_s_rate_is_its_derivative() {
        let twelve = Shape::regular_polygon(0.01, 12).unwrap();
        let gon = Shape::regular_polygon(0.01, 120).unwrap();
        let disc = Shape::Disc { r: 0.01 };
        let big = Shape::Disc { r: 0.023 };
        let cases = [
            (&disc, &big),
            (&gon, &gon),
            (&twelve, &twelve),
            (&disc, &twelve),
        ];
        for (case, (a, b)) in cases.into_iter().enumerate() {
            let scene = Scene {
                shape: a.clone(),
                partner: Some(Partner::of(b.clone())),
                ..Scene::default()
            };
            let pair = Pair::new(Model::new(&scene).unwrap()).unwrap();
            for (phi1, phi2) in [(0.0, 0.0), (0.3, 1.1), (2.0, 0.05)] {
                let init = Initial::from_angle(0.1, 45.0, 0.0, phi1).with_partner(0.0, phi2);
                let (init, check) = (init, |geometry: &dyn Fn(f64, f64) -> (f64, f64)| {
                    for delta in [3e-6, 4e-5, 2e-4, 1e-3] {
                        let h = 1e-6 * delta;
                        let (_, rate) = geometry(delta, 0.0);
                        let diff =
                            (geometry(delta + h, 0.0).0 - geometry(delta - h, 0.0).0) / (2.0 * h);
                        assert!(
                            (rate - diff).abs() <= 1e-6 * diff.abs(),
                            "case {case}, phi {phi1} {phi2}, delta {delta:e}: {rate} vs {diff}"
                        );
                    }
                });
                if let (Shape::Disc { r: r1 }, Shape::Disc { r: r2 }) = (a, b) {
                    let g = DiscPair {
                        r1: *r1,
                        r2: *r2,
                        linear: false,
                    };
                    let start = Start::of(&g, &init);
                    let frame = |s: f64| g.frame(&[0.0, start.q[1] - s, phi1, phi2]);
                    check(&|d, _| overlap_potential(&pair, &g, &frame, d));
                } else {
                    let g = ShapePair::new(a, b).unwrap();
                    let start = Start::of(&g, &init);
                    let frame = |s: f64| g.frame(&[0.0, start.q[1] - s, start.q[2], start.q[3]]);
                    check(&|d, _| overlap_potential(&pair, &g, &frame, d));
                }
            }
        }
    }

    /// The largest overlap of bodies with corners (the guess moved by one frame's power law,
    /// the potential continued from the anchor by Simpson's rule) is the root of the potential
    /// integrated finely (400 panels of 8-point Gauss-Legendre in the approach, the area's
    /// kinks resolved) to within the 8-point quadrature's own error: random pairs of regular 3-
    /// to 120-gons and convex polygons (and a polygon on a disc), partners 0.5 to 2 times the size, at random
    /// orientations and speeds from 1e-3 to 3 m/s; and its rate is its derivative. Prints the largest errors, the 8-point
    /// root's and the continued one's (2.7e-4 and 1.9e-4).
    #[test]
    fn the_continued_root_is_the_fine_potential_s() {
        let mut seeded = crate::numerics::seeded::Seeded(5);
        let mut rng = move || seeded.uniform();
        let (mut worst_gauss, mut worst_continued) = (0.0f64, 0.0f64);
        for case in 0..120 {
            let shape = |r: f64, rng: &mut dyn FnMut() -> f64| {
                let n = [3usize, 4, 5, 7, 12, 24, 60, 120][(rng() * 8.0) as usize];
                if rng() < 0.25 {
                    let aspect = 0.4 + 0.6 * rng();
                    let m = n.max(5);
                    let v: Vec<[f64; 2]> = (0..m)
                        .map(|k| {
                            let t = std::f64::consts::TAU * (k as f64 + 0.8 * rng()) / m as f64;
                            [r * t.cos(), r * aspect * t.sin()]
                        })
                        .collect();
                    Shape::convex_polygon(&v).unwrap()
                } else {
                    Shape::regular_polygon(r, n).unwrap()
                }
            };
            let a = shape(0.01, &mut rng);
            let r2 = 0.01 * (0.5 + 1.5 * rng());
            // A disc for the partner in one case of six (its arcs' area is smooth, not
            // quadratic, between corner events: Simpson's rule is then exact to h^4).
            let b = if case % 6 == 5 {
                Shape::Disc { r: r2 }
            } else {
                shape(r2, &mut rng)
            };
            let scene = Scene {
                shape: a.clone(),
                partner: Some(Partner::of(b.clone())),
                ..Scene::default()
            };
            let pair = Pair::new(Model::new(&scene).unwrap()).unwrap();
            let v = 10f64.powf(-3.0 + 3.5 * rng());
            let init =
                Initial::from_angle(v, 90.0, 0.0, 360.0 * rng()).with_partner(0.0, 360.0 * rng());
            let g = ShapePair::new(&a, &b).unwrap();
            let start = Start::of(&g, &init);
            let Ok(continued) = estimate_max_overlap(&pair, &init, &g, &start) else {
                continue;
            };
            let frame = |s: f64| g.frame(&[0.0, start.q[1] - s, start.q[2], start.q[3]]);
            let k = pair.law.scene.e_modulus / pair.law.length;
            let ke = 0.5 * pair.m_star * init.vy * init.vy;
            let area = |s: f64| frame(s).map_or(0.0, |f| f.area);
            let fine = |delta: f64| {
                let panels = 400;
                let h = delta / panels as f64;
                let w: f64 = (0..panels)
                    .flat_map(|i| GAUSS_8.iter().map(move |&(x, w)| (i, x, w)))
                    .map(|(i, x, w)| 0.5 * h * w * area(h * (i as f64 + 0.5 * (x + 1.0))))
                    .sum();
                (k * w, k * area(delta))
            };
            // The continued potential's rate is its derivative (Newton converges on its root
            // quadratically): anchored at the root, the central difference 5 % past it.
            let c = ContinuedPotential::new(&frame, k);
            c.at(continued);
            let (y, h) = (1.05 * continued, 1e-6 * continued);
            let diff = (c.at(y + h).0 - c.at(y - h).0) / (2.0 * h);
            let rate = c.at(y).1;
            assert!(
                (rate - diff).abs() <= 1e-5 * diff,
                "case {case}: {rate:e} vs {diff:e}"
            );
            let hi = largest_overlap(pair.particle.r, pair.r2);
            let reference = roots::log_newton_below(fine, ke, (continued, fine(continued)), hi)
                .expect("a root below the largest overlap");
            let gauss = |d: f64| overlap_potential(&pair, &g, &frame, d);
            let eight = roots::log_newton_below(gauss, ke, (continued, gauss(continued)), hi)
                .expect("a root below the largest overlap");
            let (e8, ec) = (
                (eight - reference).abs() / reference,
                (continued - reference).abs() / reference,
            );
            (worst_gauss, worst_continued) = (worst_gauss.max(e8), worst_continued.max(ec));
            // The anchor's 8-point potential, continued: its error, plus Simpson's rule's across
            // the corner events between the anchor and the root (the two cases of 120 where
            // the continuation's own error showed, 4.9e-5 and 4.5e-5).
            assert!(
                ec <= e8 + 1e-4,
                "case {case}, v {v}: continued {ec:e}, 8-point {e8:e} from {reference:e}"
            );
        }
        eprintln!("largest error: 8-point {worst_gauss:e}, continued {worst_continued:e}");
        assert!(
            worst_continued <= 1.1 * worst_gauss,
            "{worst_continued:e} vs {worst_gauss:e}"
        );
    }

    /// Newton's confirming iterate read on the last iterate's tangent (within
    /// [`TANGENT_WITHIN`]) is the potential continued by Simpson's rule there to within what
    /// moves the root by less than Newton's own stop, and its rate to the tangent's first-order
    /// error: two 120-gons, two 12-gons and a 7-gon
    /// on a 60-gon at several orientations, iterates 5 % past the anchor.
    #[test]
    fn the_tangent_read_is_the_continued_potential() {
        let shapes = [(120, 120), (12, 12), (7, 60)];
        for (n1, n2) in shapes {
            let a = Shape::regular_polygon(0.01, n1).unwrap();
            let b = Shape::regular_polygon(0.013, n2).unwrap();
            let g = ShapePair::new(&a, &b).unwrap();
            for (phi1, phi2) in [(0.0, 0.0), (0.3, 1.1), (2.0, 0.05)] {
                let init = Initial::from_angle(0.1, 90.0, 0.0, phi1).with_partner(0.0, phi2);
                let start = Start::of(&g, &init);
                let frame = |s: f64| g.frame(&[0.0, start.q[1] - s, start.q[2], start.q[3]]);
                for anchor in [2e-5, 2e-4] {
                    let iterate = 1.05 * anchor;
                    let confirming = iterate * (1.0 + 5e-10);
                    let read = ContinuedPotential::new(&frame, 1.0);
                    read.at(anchor);
                    read.at(iterate);
                    let (w, rate) = read.at(confirming);
                    let full = ContinuedPotential::new(&frame, 1.0);
                    full.at(anchor);
                    let (w_full, rate_full) = full.at(confirming);
                    // The root moves by the potential's difference over its rate: less than
                    // Newton's own stop (1e-14 of the iterate). The frames' areas carry the
                    // clip's round-off (their coordinates ~1e-2 m, the overlap ~1e-5 m), so
                    // the continued potential itself differs from its tangent at ~1e-14.
                    assert!(
                        (w - w_full).abs() <= 1e-14 * confirming * rate_full,
                        "{n1}-gon on {n2}-gon, phi {phi1} {phi2}, {anchor:e}: {w:e} vs {w_full:e}"
                    );
                    assert!(
                        (rate - rate_full).abs() <= 1e-8 * rate_full,
                        "{n1}-gon on {n2}-gon, rate {rate:e} vs {rate_full:e}"
                    );
                }
            }
        }
    }

    /// The closed form against a bisection to the last float on the caps' depths (either
    /// cap's depth over its radius past one half), over radius ratios from 1e-3 to 1e3.
    #[test]
    fn largest_overlap_is_where_a_cap_reaches_half_its_radius() {
        let capped = |r1: f64, r2: f64, delta: f64| {
            let d = r1 + r2 - delta;
            let half = 0.5 * delta / d;
            (half * (2.0 * r2 - delta) / r1).max(half * (2.0 * r1 - delta) / r2) > 0.5
        };
        for k in -30..=30 {
            let (r1, r2): (f64, f64) = (0.01, 0.01 * 10f64.powf(0.1 * k as f64));
            let (mut lo, mut hi) = (0.0, r1.min(r2));
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if capped(r1, r2, mid) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let got = largest_overlap(r1, r2);
            assert!(
                (got - lo).abs() <= 4.0 * f64::EPSILON * lo,
                "r2 / r1 {}: {got:e} vs {lo:e}",
                r2 / r1
            );
        }
    }
}
