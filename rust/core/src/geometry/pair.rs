//! Where two round bodies of a pair meet (docs/model.md, section 17): two discs' lens, and two
//! spheres' Hertz contact, both as functions of the distance between the centres alone.
//!
//! The lens of two discs is cut by its chord (on the radical line) into two circular segments,
//! one of each disc; each is computed as the plate's segment is (`disc_segment_at`: a series
//! in the depth at shallow overlap), from its own depth, written without cancellation:
//! h1 = delta (r2 + d - r1) / (2 d) with delta = r1 + r2 - d.

use super::disc::disc_segment_at;

/// What the contact law needs of a pair's overlap, measured along the line of centres.
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

/// How a pair's two bodies overlap, as a function of their centres' distance; one
/// implementation per pairing, so that the pair's loop is compiled for each.
pub trait PairGeometry: Copy {
    /// The overlap at centre distance `d`; `None` when apart.
    fn overlap(&self, d: f64) -> Option<PairOverlap>;
    /// The sum of the radii: the centre distance at touch.
    fn touch_distance(&self) -> f64;
}

/// Two discs of radii `r1` (the particle) and `r2` (the partner).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscPair {
    /// The particle's radius (m).
    pub r1: f64,
    /// The partner's radius (m).
    pub r2: f64,
}

/// The depths of the two caps a chord on the radical line cuts from discs (or spheres) of
/// radii `r1`, `r2` whose centres are `d` apart with overlap `delta`.
#[inline(always)]
fn cap_depths(r1: f64, r2: f64, d: f64, delta: f64) -> (f64, f64) {
    let half = 0.5 * delta / d;
    (half * (r2 + d - r1), half * (r1 + d - r2))
}

impl PairGeometry for DiscPair {
    #[inline(always)]
    fn overlap(&self, d: f64) -> Option<PairOverlap> {
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
        // Each cap as the plate's segment of its disc (centre at height r - h over the chord):
        // its centroid lies `y - cy` beyond its own centre.
        let (c1, c2) = (
            disc_segment_at(self.r1, self.r1 - h1, h1),
            disc_segment_at(self.r2, self.r2 - h2, h2),
        );
        let (dist1, dist2) = (self.r1 - h1 - c1.cy, self.r2 - h2 - c2.cy);
        let area = c1.area + c2.area;
        Some(PairOverlap {
            depth: delta,
            area,
            chord: c1.chord,
            arm1: (c1.area * dist1 + c2.area * (d - dist2)) / area,
        })
    }

    fn touch_distance(&self) -> f64 {
        self.r1 + self.r2
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
}

impl PairGeometry for SpherePair {
    #[inline(always)]
    fn overlap(&self, d: f64) -> Option<PairOverlap> {
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

    fn touch_distance(&self) -> f64 {
        self.r1 + self.r2
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
            let lens = DiscPair { r1: r, r2: r }.overlap(2.0 * r - delta).unwrap();
            let seg = disc_segment_at(r, r - 0.5 * delta, 0.5 * delta);
            let rel = (lens.area - 2.0 * seg.area).abs() / (2.0 * seg.area);
            assert!(rel < 1e-9 * (r / delta).max(1.0), "delta {delta}: {rel:e}");
            assert!(
                (lens.arm1 - (r - 0.5 * delta)).abs() < 1e-12 * r,
                "delta {delta}"
            );
        }
    }

    /// A disc on a huge disc: the lens tends to the disc's segment on the plate.
    #[test]
    fn huge_partner_lens_tends_to_the_plate_segment() {
        let (r, delta) = (0.01, 1e-4);
        let seg = disc_segment_at(r, r - delta, delta);
        let mut last = f64::INFINITY;
        for r2 in [1.0, 1e2, 1e4] {
            let lens = DiscPair { r1: r, r2 }.overlap(r + r2 - delta).unwrap();
            let err = (lens.area - seg.area).abs() / seg.area;
            assert!(err < last, "r2 {r2}: {err:e}");
            last = err;
        }
        assert!(last < 1e-5, "{last:e}");
    }

    /// The lens area against a direct quadrature of the overlap's width along the line of
    /// centres, for unequal discs at several overlaps.
    #[test]
    fn lens_area_matches_quadrature() {
        let (r1, r2) = (0.01, 0.023);
        for delta in [1e-3, 5e-3, 9e-3] {
            let d = r1 + r2 - delta;
            let lens = DiscPair { r1, r2 }.overlap(d).unwrap();
            // Centre 1 at 0, centre 2 at d on the x axis: the lens spans x in [d - r2, r1].
            let n = 200_000;
            let (a, b) = (d - r2, r1);
            let h = (b - a) / n as f64;
            let area: f64 = (0..n)
                .map(|i| {
                    let x = a + (i as f64 + 0.5) * h;
                    let w1 = (r1 * r1 - x * x).max(0.0).sqrt();
                    let w2 = (r2 * r2 - (x - d) * (x - d)).max(0.0).sqrt();
                    2.0 * w1.min(w2) * h
                })
                .sum();
            assert!((lens.area - area).abs() < 1e-7 * area, "delta {delta}");
        }
    }
}
