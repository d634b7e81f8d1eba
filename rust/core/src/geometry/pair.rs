//! Where the two bodies of a pair meet (docs/model.md, section 17): the frame every pairing
//! gives the laws ([`PairFrame`], [`PairGeometry`]), and the round pairings: two discs' lens
//! and two spheres' Hertz contact, both functions of the distance between the centres alone
//! (bodies with corners: [`super::pair_shapes`]).
//!
//! The lens of two discs is cut by its chord (on the radical line) into two circular segments,
//! one of each disc; each is computed as the plate's segment is (`disc_segment_at`: a series
//! in the depth at shallow overlap), from its own depth, written without cancellation:
//! h1 = delta (2 r2 - delta) / (2 d) with delta = r1 + r2 - d.

use super::convex_clip::EdgeLine;
use super::disc::{disc_segment_at, disc_segment_moment};

/// Where a pair's forces act at one configuration, as the laws read it (docs/model.md,
/// sections 17.2 and 17.8). A lever L = (L_1, L_2) of a force along a direction u acting at
/// point x is ((x - q) x u, -(x x u)): the torques on the particle and the partner per unit
/// of the force, and the rates of the point's relative velocity along u per unit of each spin.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PairFrame {
    /// Unit normal from the partner towards the particle; the tangent is t = (n_y, -n_x).
    pub n: [f64; 2],
    /// The overlap's depth along n (m).
    pub depth: f64,
    /// Overlap area (m^2; the Hertz contact circle's pi a^2 for spheres).
    pub area: f64,
    /// Chord length l (m): dA/dt = -l (g_n + lever_rate_area . omega).
    pub chord: f64,
    /// The area law's elastic force on the lanes per unit stiffness, -grad W of its
    /// potential (bodies with corners: `pair_shapes/potential.rs`; round bodies act along n
    /// without it).
    pub area_push: [f64; 4],
    /// Lever of the area law's damping: -b_i / l (dA/dt's terms in the spins).
    pub lever_rate_area: [f64; 2],
    /// Lever of the tangential force (along t, at the overlap's centroid).
    pub lever_t: [f64; 2],
    /// The linear law's springs.
    pub springs: Springs,
}

/// The linear law's springs on a pair (docs/model.md, section 17.8): spring i presses the
/// particle along its unit direction u_i at the point x_i with its depth d_i, and the partner
/// back; w_i = (u_i, (x_i - q) x u_i, -(x_i x u_i)) is its direction on the lanes, so that its
/// force on them is F_i w_i and the rate of its depth -w_i . v.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Springs {
    /// Their number.
    pub count: f64,
    /// Sum of the depths (m).
    pub depth: f64,
    /// Half the sum of the squared depths (m^2): the springs' potential per unit stiffness.
    pub potential: f64,
    /// Sum of d_i w_i.
    pub push: [f64; 4],
    /// Sum of w_i.
    pub sum: [f64; 4],
    /// Sum of w_i w_i^T (upper triangle, row by row).
    pub metric: [f64; 10],
}

impl Springs {
    /// Adds a spring of depth `depth` (m) and lane direction `w`.
    #[inline(always)]
    pub fn add(&mut self, depth: f64, w: [f64; 4]) {
        self.count += 1.0;
        self.depth += depth;
        self.potential += 0.5 * depth * depth;
        let mut k = 0;
        for i in 0..4 {
            self.push[i] += depth * w[i];
            self.sum[i] += w[i];
            for j in i..4 {
                self.metric[k] += w[i] * w[j];
                k += 1;
            }
        }
    }

    /// Sum of (w_i . v) w_i: the springs' depth rates' (negated) generalised dashpot force per
    /// unit damping.
    #[inline(always)]
    pub fn rates(&self, v: &[f64; 4]) -> [f64; 4] {
        let m = &self.metric;
        [
            m[0] * v[0] + m[1] * v[1] + m[2] * v[2] + m[3] * v[3],
            m[1] * v[0] + m[4] * v[1] + m[5] * v[2] + m[6] * v[3],
            m[2] * v[0] + m[5] * v[1] + m[7] * v[2] + m[8] * v[3],
            m[3] * v[0] + m[6] * v[1] + m[8] * v[2] + m[9] * v[3],
        ]
    }
}

/// One vertex spring of the linear law on two polygons (docs/model.md, 17.8): corner `corner`
/// of the particle (or of the partner) pressing on edge `edge` of the other body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringRef {
    /// Whether the corner is the partner's.
    pub partner_corner: bool,
    /// The corner's index in its body.
    pub corner: u32,
    /// The other body's edge (from its vertex `edge` to the next).
    pub edge: u32,
}

/// What a piece of the adaptive path holds between its switches, so that the law is smooth
/// there and the switches are located as events: the linear law's vertex springs (a switch
/// where a corner enters or leaves the other body, or turns to another nearest edge), or the
/// area law's overlap of two polygons (its vertices as the pairs of edge lines they lie on: a
/// switch where a crossing of the boundaries passes a corner, where the potential's force
/// jumps), or the edges a disc's crossings of a polygon lie on; empty for pairings whose law
/// is smooth without holding anything.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HeldSprings {
    /// The springs, in no particular order.
    pub springs: Vec<SpringRef>,
    /// The area law's overlap of two polygons: each vertex's (edge before, edge after).
    pub overlap: Vec<(EdgeLine, EdgeLine)>,
    /// The overlap's two vertices that are the chord's ends.
    pub chord: [usize; 2],
    /// The area law's overlap of a disc with a polygon: the polygon's edges on which the
    /// chord's two crossings lie, where the polygon's boundary enters the circle and where it
    /// leaves it (a switch where a crossing passes a corner).
    pub disc_crossings: Option<[u32; 2]>,
}

/// How a pair's two bodies overlap at the lanes q = (x, y, phi1, phi2) (the particle's centre
/// relative to the partner's, and the two orientations); one implementation per pairing, so
/// that the pair's loop is compiled for each.
pub trait PairGeometry: Copy {
    /// Whether a body has corners: then bodies apart and receding may still touch again (a
    /// spinning corner), and the impact ends only when they cannot ([`PairGeometry::gap`]).
    const CORNERS: bool;
    /// The contact's frame at `q`; `None` when apart.
    fn frame(&self, q: &[f64; 4]) -> Option<PairFrame>;
    /// The depth at `q` when in contact, minus the bodies' distance when apart (m).
    fn signed_depth(&self, q: &[f64; 4]) -> f64;
    /// The particle's centre's height above the partner's at first touch, straight above it,
    /// for orientations `phi1`, `phi2` (rad).
    fn touch_height(&self, phi1: f64, phi2: f64) -> f64;
    /// The largest centre distance at which the bodies can touch (m).
    fn reach(&self) -> f64;
    /// The area law's potential per unit stiffness at the overlap `delta` of a head-on
    /// approach from first touch (the overlap's area integrated over the approach) and the
    /// area there, where the pairing has them in closed form; `None` where the frames'
    /// areas are integrated instead.
    fn area_potential(&self, _delta: f64) -> Option<(f64, f64)> {
        None
    }
    /// Whether the law's springs switch where they must be held ([`HeldSprings`]).
    fn holds_springs(&self) -> bool {
        false
    }
    /// The springs at `q` to hold through a piece.
    fn held_springs(&self, _q: &[f64; 4]) -> HeldSprings {
        HeldSprings::default()
    }
    /// The contact's frame at `q` with the springs `held` (their law continued smoothly).
    fn frame_held(&self, q: &[f64; 4], _held: &HeldSprings) -> Option<PairFrame> {
        self.frame(q)
    }
    /// The event function of the springs `held` at `q`: > 0 once they are not the law's.
    fn held_springs_value(&self, _q: &[f64; 4], _held: &HeldSprings) -> f64 {
        f64::NEG_INFINITY
    }
    /// Where the frame follows the centres' distance `d` alone and its overlap is a lens:
    /// the rates per unit of `d` of the chord and of the tangential force's lever on the
    /// particle's spin, (dl/dd, dL_1/dd), at the frame's `chord`, `area` and lever `arm1`
    /// there (the partner's lever is d - L_1); `None` elsewhere.
    fn lens_rates(&self, _d: f64, _chord: f64, _area: f64, _arm1: f64) -> Option<(f64, f64)> {
        None
    }
}

/// What a round pair's overlap is, measured along the line of centres.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PairOverlap {
    /// Overlap of the centre distance, delta = r1 + r2 - d (m, > 0 in contact).
    pub depth: f64,
    /// Area of the lens (m^2; the Hertz contact circle's pi a^2 for spheres).
    pub area: f64,
    /// Chord of the lens (m; the contact circle's diameter 2 a for spheres).
    pub chord: f64,
    /// Distance from the particle's centre to the point where the forces act, towards the
    /// partner (the lens's centroid; the radical plane for spheres).
    pub arm1: f64,
}

/// The frame of a round pair at `q` from its overlap at the centres' distance: everything
/// acts on the line of centres, so only the tangential force has levers (its arms).
/// `d` is the centres' distance and `o` the overlap there.
#[inline(always)]
fn round_frame(q: &[f64; 4], linear: bool, d: f64, o: PairOverlap) -> PairFrame {
    let inv_d = 1.0 / d;
    let n = [q[0] * inv_d, q[1] * inv_d];
    let mut springs = Springs::default();
    if linear {
        springs.add(o.depth, [n[0], n[1], 0.0, 0.0]);
    }
    PairFrame {
        n,
        depth: o.depth,
        area: o.area,
        chord: o.chord,
        lever_t: [o.arm1, d - o.arm1],
        springs,
        ..PairFrame::default()
    }
}

/// The distance between a pair's centres at `q`.
#[inline(always)]
fn centre_distance(q: &[f64; 4]) -> f64 {
    // sqrt, not hypot: the centres' distance is never near the floats' limits, and hypot's
    // care cost a fifth of a pair's step.
    (q[0] * q[0] + q[1] * q[1]).sqrt()
}

/// Two discs of radii `r1` (the particle) and `r2` (the partner).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscPair {
    /// The particle's radius (m).
    pub r1: f64,
    /// The partner's radius (m).
    pub r2: f64,
    /// Whether the frame carries the linear law's spring (its other laws do without).
    pub linear: bool,
}

/// The depths of the two caps a chord on the radical line cuts from discs (or spheres) of
/// radii `r1`, `r2` whose centres are `d` apart with overlap `delta`.
#[inline(always)]
fn cap_depths(r1: f64, r2: f64, d: f64, delta: f64) -> (f64, f64) {
    // 1 / d as the frame's normal takes it (`round_frame`), so that the two are one division.
    // r2 + d - r1 = 2 r2 - delta, written so: the former cancels when r1 >> r2 (the latter
    // when r2 >> r1), losing digits as r1 / r2 grows.
    let half = 0.5 * delta * (1.0 / d);
    (half * (2.0 * r2 - delta), half * (2.0 * r1 - delta))
}

/// A round pairing's geometry: everything follows from the centres' distance and its
/// `overlap` there (`r1`, `r2`, `linear` fields and an `overlap(d)` method).
macro_rules! round_pair_geometry {
    ($pair:ty) => {
        impl PairGeometry for $pair {
            const CORNERS: bool = false;

            #[inline(always)]
            fn frame(&self, q: &[f64; 4]) -> Option<PairFrame> {
                let d = centre_distance(q);
                // The overlap inlined here, not passed as a closure: the closure stayed a
                // call, its caller's state spilled around it (a tenth of a pair's step).
                let o = self.overlap(d)?;
                Some(round_frame(q, self.linear, d, o))
            }

            fn signed_depth(&self, q: &[f64; 4]) -> f64 {
                // The fixed-step loop asks it every step.
                self.r1 + self.r2 - centre_distance(q)
            }

            fn touch_height(&self, _phi1: f64, _phi2: f64) -> f64 {
                self.r1 + self.r2
            }

            fn reach(&self) -> f64 {
                self.r1 + self.r2
            }

            fn area_potential(&self, delta: f64) -> Option<(f64, f64)> {
                <$pair>::area_potential(self, delta)
            }

            #[inline(always)]
            fn lens_rates(&self, d: f64, chord: f64, area: f64, arm1: f64) -> Option<(f64, f64)> {
                <$pair>::lens_rates(self, d, chord, area, arm1)
            }
        }
    };
}

round_pair_geometry!(DiscPair);
round_pair_geometry!(SpherePair);

impl DiscPair {
    /// The lens's potential per unit stiffness and its area at overlap `delta` (see
    /// [`PairGeometry::area_potential`]), for two equal discs: each point of the lens entered
    /// it when the other disc's boundary passed it, so the potential is the lens's width
    /// squared over two, integrated across it; the chord halves the lens into two segments
    /// of depth delta / 2, and so the potential is four times a segment's first moment about
    /// its chord. Unequal discs' is an elliptic integral: their frames are integrated.
    pub fn area_potential(&self, delta: f64) -> Option<(f64, f64)> {
        (self.r1 == self.r2).then(|| {
            let (moment, area) = disc_segment_moment(self.r1, 0.5 * delta);
            (4.0 * moment, 2.0 * area)
        })
    }

    /// The lens's rates at centre distance `d` (see [`PairGeometry::lens_rates`]), from its
    /// `chord` l, `area` A and centroid's distance `arm1` from centre 1. The chord lies at
    /// x_1 = r1 - h1 from centre 1 and x_2 = r2 - h2 from centre 2 (`cap_depths`), with
    /// dx_1/dd = x_2 / d and dx_2/dd = x_1 / d; its half l / 2 = sqrt(r1^2 - x_1^2), so
    /// dl/dd = -4 x_1 x_2 / (l d) (on the plate, r2 -> inf, the disc's -4 (r - depth) / l).
    /// Cap i loses area at l dx_i/dd as its chord recedes, so dA_2/dd = -l x_1 / d, and the
    /// centroid arm1 = d A_2 / A moves at A_2 / A - l (x_1 - arm1) / A; equal discs' centroid
    /// lies on the chord, halfway (1 / 2).
    #[inline(always)]
    pub fn lens_rates(&self, d: f64, chord: f64, area: f64, arm1: f64) -> Option<(f64, f64)> {
        let delta = self.r1 + self.r2 - d;
        let (h1, h2) = cap_depths(self.r1, self.r2, d, delta);
        let (x1, x2) = (self.r1 - h1, self.r2 - h2);
        let chord_rate = -4.0 * x1 * x2 / (chord * d);
        if self.r1 == self.r2 {
            return Some((chord_rate, 0.5));
        }
        Some((chord_rate, (arm1 / d) - chord * (x1 - arm1) / area))
    }

    /// The lens at centre distance `d`; `None` when apart.
    #[inline(always)]
    pub fn overlap(&self, d: f64) -> Option<PairOverlap> {
        let delta = self.r1 + self.r2 - d;
        if delta <= 0.0 {
            return None;
        }
        if self.r1 == self.r2 {
            // Two equal discs: the chord halves the overlap, the lens is two equal segments
            // and its centroid lies on the chord (one segment computed, not two).
            let h = 0.5 * delta;
            let c = disc_segment_at(self.r1, self.r1 - h, h);
            return Some(PairOverlap {
                depth: delta,
                area: 2.0 * c.area,
                chord: c.chord,
                arm1: 0.5 * d,
            });
        }
        let (h1, h2) = cap_depths(self.r1, self.r2, d, delta);
        // Each cap as the plate's segment of its disc (centre at height r - h over the chord).
        let (c1, c2) = (
            disc_segment_at(self.r1, self.r1 - h1, h1),
            disc_segment_at(self.r2, self.r2 - h2, h2),
        );
        let area = c1.area + c2.area;
        // A segment of half-chord a has its first moment about its disc's centre 2 a^3 / 3,
        // the same for both caps (one chord): about centre 1 the lens's moment is then
        // 2 a^3 / 3 + A2 d - 2 a^3 / 3, and its centroid lies at d A2 / A (the caps' own
        // centroids, a division each, are not needed).
        Some(PairOverlap {
            depth: delta,
            area,
            chord: c1.chord,
            arm1: d * c2.area / area,
        })
    }
}

/// Two spheres of radii `r1` (the particle) and `r2` (the partner): the Hertz contact, its
/// forces acting on the radical plane (a point both bodies share, so that the torques of the
/// pair's forces cancel the orbit's: angular momentum is conserved).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpherePair {
    /// The particle's radius (m).
    pub r1: f64,
    /// The partner's radius (m).
    pub r2: f64,
    /// Whether the frame carries the linear law's spring (its other laws do without).
    pub linear: bool,
}

impl SpherePair {
    /// `None`: spheres' laws are Hertz's (its potential in closed form where the depth is
    /// estimated) and the linear one.
    pub fn area_potential(&self, _delta: f64) -> Option<(f64, f64)> {
        None
    }

    /// `None`: the Hertz law's rates are differenced.
    pub fn lens_rates(&self, _d: f64, _c: f64, _a: f64, _arm1: f64) -> Option<(f64, f64)> {
        None
    }

    /// The Hertz contact at centre distance `d`; `None` when apart.
    #[inline(always)]
    pub fn overlap(&self, d: f64) -> Option<PairOverlap> {
        let delta = self.r1 + self.r2 - d;
        if delta <= 0.0 {
            return None;
        }
        let (h1, _) = cap_depths(self.r1, self.r2, d, delta);
        let r_star = self.r1 * self.r2 / (self.r1 + self.r2);
        let a2 = r_star * delta;
        Some(PairOverlap {
            depth: delta,
            area: std::f64::consts::PI * a2,
            chord: 2.0 * a2.sqrt(),
            arm1: self.r1 - h1,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two identical discs: the lens is twice the plate's segment at half the overlap, its
    /// centroid on the chord, halfway.
    #[test]
    fn identical_discs_lens_is_two_plate_segments() {
        let r = 0.01;
        for delta in [1e-9, 1e-6, 1e-4, 3e-3, 9e-3] {
            let lens = DiscPair {
                r1: r,
                r2: r,
                linear: false,
            }
            .overlap(2.0 * r - delta)
            .unwrap();
            let seg = disc_segment_at(r, r - 0.5 * delta, 0.5 * delta);
            let rel = (lens.area - 2.0 * seg.area).abs() / (2.0 * seg.area);
            assert!(rel < 1e-9 * (r / delta).max(1.0), "delta {delta}: {rel:e}");
            assert!(
                (lens.arm1 - (r - 0.5 * delta)).abs() < 1e-12 * r,
                "delta {delta}"
            );
        }
    }

    /// Two equal discs' closed-form potential against a quadrature of the lens's own area
    /// over the approach (Gauss-Legendre on delta t^2, 40 panels of 4 points), from touch to
    /// overlaps of 0.9 r; its rate is the lens's area; unequal discs have none.
    #[test]
    fn equal_discs_potential_integrates_the_lens_area() {
        let r = 0.01;
        let pair = DiscPair {
            r1: r,
            r2: r,
            linear: false,
        };
        // The lens's area at overlap s, placed as the frames place it (d = 2 r - s).
        let area = |s: f64| pair.overlap(2.0 * r - s).map_or(0.0, |o| o.area);
        for delta in [1e-9 * r, 1e-5 * r, 1e-3 * r, 0.05 * r, 0.3 * r, 0.9 * r] {
            let quad = crate::numerics::quadrature::over_depth(area, delta);
            let (potential, a) = pair.area_potential(delta).unwrap();
            // The frames' overlap is 2 r - (2 r - s): exact to an ulp of r, a part in
            // r / delta of it (the potential, a power 5/2 of it, 2.5 times that).
            let tol = 2e-13 + 8.0 * f64::EPSILON * r / delta;
            assert!(
                (potential - quad).abs() <= tol * quad,
                "delta {delta:e}: {potential} vs {quad}"
            );
            assert!((a - area(delta)).abs() <= tol * a, "delta {delta:e}");
        }
        let unequal = DiscPair {
            r2: 2.0 * r,
            ..pair
        };
        assert_eq!(unequal.area_potential(1e-4), None);
    }

    /// A disc on a huge disc: the lens tends to the disc's segment on the plate.
    #[test]
    fn huge_partner_lens_tends_to_the_plate_segment() {
        let (r, delta) = (0.01, 1e-4);
        let seg = disc_segment_at(r, r - delta, delta);
        let mut last = f64::INFINITY;
        for r2 in [1.0, 1e2, 1e4] {
            let lens = DiscPair {
                r1: r,
                r2,
                linear: false,
            }
            .overlap(r + r2 - delta)
            .unwrap();
            let err = (lens.area - seg.area).abs() / seg.area;
            assert!(err < last, "r2 {r2}: {err:e}");
            last = err;
        }
        assert!(last < 1e-5, "{last:e}");
    }

    /// Both caps of a lens share its chord: their depths give the same half chord to rounding,
    /// however unequal the discs (written as r1 + d - r2, the smaller disc's partner's cap lost
    /// digits as r2 / r1 grew: 5e-14 at 1000).
    #[test]
    fn caps_share_the_chord_at_any_radius_ratio() {
        for (r1, r2) in [(1e-3, 1.0), (1.0, 1e-3), (0.01, 0.02), (1e-4, 10.0)] {
            for x in [1e-9, 1e-6, 1e-3, 0.1] {
                let d = r1 + r2 - 2.0 * f64::min(r1, r2) * x;
                let delta = r1 + r2 - d;
                let (h1, h2) = cap_depths(r1, r2, d, delta);
                assert!((h1 + h2 - delta).abs() <= 4.0 * f64::EPSILON * delta);
                let (a1, a2) = (h1 * (2.0 * r1 - h1), h2 * (2.0 * r2 - h2));
                let rel = (a1 - a2).abs() / a1;
                assert!(rel < 1e-15, "r1 {r1}, r2 {r2}, x {x:e}: {rel:e}");
            }
        }
    }

    /// The lens area and its centroid's distance from centre 1 against a direct quadrature of
    /// the overlap's width along the line of centres, for unequal discs at several overlaps.
    #[test]
    fn lens_area_matches_quadrature() {
        let (r1, r2) = (0.01, 0.023);
        for delta in [1e-3, 5e-3, 9e-3] {
            let d = r1 + r2 - delta;
            let lens = DiscPair {
                r1,
                r2,
                linear: false,
            }
            .overlap(d)
            .unwrap();
            // Centre 1 at 0, centre 2 at d on the x axis: the lens spans x in [d - r2, r1].
            let n = 200_000;
            let (a, b) = (d - r2, r1);
            let h = (b - a) / n as f64;
            let (area, moment) = (0..n)
                .map(|i| {
                    let x = a + (i as f64 + 0.5) * h;
                    let w1 = (r1 * r1 - x * x).max(0.0).sqrt();
                    let w2 = (r2 * r2 - (x - d) * (x - d)).max(0.0).sqrt();
                    let strip = 2.0 * w1.min(w2) * h;
                    (strip, x * strip)
                })
                .fold((0.0, 0.0), |(s, m), (a, xa)| (s + a, m + xa));
            assert!((lens.area - area).abs() < 1e-7 * area, "delta {delta}");
            let arm = moment / area;
            assert!(
                (lens.arm1 - arm).abs() < 1e-7 * d,
                "delta {delta}: {} vs {arm}",
                lens.arm1
            );
        }
    }
}
