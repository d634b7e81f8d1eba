//! Particle shapes and their overlap with the flat plate y <= 0.
//!
//! "Model only what a scene requires": the exact disc uses the closed-form circular segment,
//! polygons are clipped against the half-plane y <= 0 (one Sutherland-Hodgman pass, no
//! allocation). Both return the same [`Overlap`] summary, which is all the contact law needs.
//! The general convex-convex intersection (finite plates, any convex obstacle) lives in
//! [`crate::geometry::parry`]; [`OverlapMethod::Parry`] routes the flat plate through it so that the
//! two paths can be compared on the same scene.

use crate::error::{ensure_param, positive, Result};
use nalgebra::Vector2;
use std::f64::consts::PI;

/// A rigid particle shape, in its body frame (centroid at the origin): a 2D body (per unit
/// depth) or a sphere moving in its plane of incidence (per particle).
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// Exact disc of radius `r` (m).
    Disc {
        /// Radius (m).
        r: f64,
    },
    /// Sphere of radius `r` (m), moving in the plane of incidence (x, y, spin about z): a 3D
    /// body, so its mass, forces and energies are per particle (kg, N, J), not per unit depth.
    /// Only the Hertz and linear laws act on it ([`sphere_contact`]).
    Sphere {
        /// Radius (m).
        r: f64,
    },
    /// Convex polygon (regular n-gons included).
    Polygon(Polygon),
}

/// The contact of a sphere of radius `r` whose centre is at height `y` with the plate: the
/// depth delta = r - y of its lowest point (directly below the centre), the Hertz contact
/// circle (radius a = sqrt(r delta), `chord` = 2 a, `area` = pi a^2 = pi r delta) and the point
/// where the forces act, taken at the undeformed radius below the centre (`cy` = y - r, the
/// arm of rigid-body impact theory and of LAMMPS's granular pair styles). `first_moment` is 0
/// (no area law acts on a sphere). `None` when clear.
#[inline(always)]
pub fn sphere_contact(r: f64, y: f64) -> Option<Overlap> {
    let depth = r - y;
    if depth <= 0.0 {
        return None;
    }
    let a2 = r * depth;
    Some(Overlap {
        area: PI * a2,
        cx: 0.0,
        cy: y - r,
        chord: 2.0 * a2.sqrt(),
        x_mid: 0.0,
        depth,
        x_low: 0.0,
        first_moment: 0.0,
        corners: Corners::default(),
    })
}

/// A convex polygon in its body frame: counter-clockwise vertices about its centroid.
#[derive(Debug, Clone, PartialEq)]
pub struct Polygon {
    vertices: Vec<Vector2<f64>>,
    circumradius: f64,
    area: f64,
    /// Polar second moment of area about the centroid, m^4 (per unit depth).
    polar_moment: f64,
    /// Polar angles of the vertices about the centroid, unwrapped to increase from the first
    /// (convex and counter-clockwise about an interior point: monotone). Used to find the
    /// lowest vertex in O(log n) instead of scanning all of them every step.
    polar: Vec<f64>,
}

/// What the contact law needs to know about the overlap of a particle with the plate.
///
/// Positions are relative to the particle's centre of mass in x (`cx`, `x_mid`, `x_low`) and
/// absolute in y (the plate is y = 0, so the overlap lies at y <= 0).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Overlap {
    /// Overlap area A (m^2).
    pub area: f64,
    /// Overlap centroid, x relative to the centre of mass (m).
    pub cx: f64,
    /// Overlap centroid, absolute y (m, <= 0).
    pub cy: f64,
    /// Chord length l: the part of y = 0 inside the particle (m).
    pub chord: f64,
    /// Chord midpoint, x relative to the centre of mass (m).
    pub x_mid: f64,
    /// Depth of the particle's lowest point below the plate (m, > 0 in contact).
    pub depth: f64,
    /// Lowest point, x relative to the centre of mass (m).
    pub x_low: f64,
    /// First moment of the overlap about y = 0: integral of (-y) dA (m^3). The elastic
    /// potential of the area law is (E / L) times this.
    pub first_moment: f64,
    /// Which of a polygon's vertices lie at or below the plate (all zero for a disc). The
    /// contact law is smooth while this stays the same; a change marks an event (a touch, a
    /// separation, a corner crossing the plate) that the fixed-step integrators locate.
    pub corners: Corners,
}

/// The chain of a polygon's vertices at or below the plate: the first of them in
/// counter-clockwise order and how many there are (below the plate they are contiguous).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Corners {
    /// Index of the first vertex of the chain.
    pub first: u32,
    /// Number of vertices in the chain.
    pub count: u32,
}

/// Which algorithm computes a particle's overlap with the flat plate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum OverlapMethod {
    /// What the scene requires: the closed-form segment for a disc, the half-plane clip for a
    /// polygon.
    #[default]
    Auto,
    /// Half-plane clip (for a disc this is its closed-form segment: the same cut, done exactly).
    HalfPlane,
    /// The general convex-convex intersection through parry, with the plate as a polygon
    /// (polygons only: a disc would need a polygonal approximation, use a fine regular n-gon).
    Parry,
}

impl OverlapMethod {
    /// Every method, in code order (the consistency matrix runs them all).
    pub const ALL: [OverlapMethod; 3] = [
        OverlapMethod::Auto,
        OverlapMethod::HalfPlane,
        OverlapMethod::Parry,
    ];

    /// Public name, as in the Python API.
    pub fn name(self) -> &'static str {
        match self {
            OverlapMethod::Auto => "auto",
            OverlapMethod::HalfPlane => "halfplane",
            OverlapMethod::Parry => "parry",
        }
    }

    /// Parses a public name ("auto", "halfplane", "parry").
    pub fn from_name(name: &str) -> Result<Self> {
        match name {
            "auto" => Ok(OverlapMethod::Auto),
            "halfplane" => Ok(OverlapMethod::HalfPlane),
            "parry" => Ok(OverlapMethod::Parry),
            other => Err(crate::error::Error::invalid(
                "overlap",
                format!("{other:?}"),
                "one of \"auto\", \"halfplane\", \"parry\"",
            )),
        }
    }

    /// Refuses a method the shape cannot use (parry on an exact disc).
    pub fn check_shape(self, shape: &Shape) -> Result<()> {
        ensure_param!(
            !(self == OverlapMethod::Parry
                && matches!(shape, Shape::Disc { .. } | Shape::Sphere { .. })),
            "overlap",
            "\"parry\"",
            "\"auto\" or \"halfplane\" for a Disc (the parry path intersects polygons; \
             use a RegularPolygon with large n to compare)"
        );
        Ok(())
    }
}

impl Shape {
    /// One shape of every kind the engine has, circumradius about `r`, for the consistency
    /// matrix: the exact disc, regular polygons from the triangle to a fine 120-gon, and a
    /// random convex 7-gon (points on an ellipse of axes r and 0.6 r at seeded angles). A new
    /// kind of shape adds its representatives here and joins the matrix.
    pub fn representatives(r: f64, seed: u64) -> Vec<(String, Shape)> {
        let mut out = vec![
            ("disc".to_string(), Shape::Disc { r }),
            ("sphere".to_string(), Shape::Sphere { r }),
        ];
        for n in [3, 4, 5, 12, 120] {
            if let Ok(p) = Shape::regular_polygon(r, n) {
                out.push((format!("{n}-gon"), p));
            }
        }
        let mut state = seed;
        let mut uniform = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut angles: Vec<f64> = (0..7).map(|_| uniform() * 2.0 * PI).collect();
        angles.sort_by(f64::total_cmp);
        let pts: Vec<[f64; 2]> = angles
            .iter()
            .map(|a| [r * a.cos(), 0.6 * r * a.sin()])
            .collect();
        if let Ok(p) = Shape::convex_polygon(&pts) {
            out.push(("convex 7-gon".to_string(), p));
        }
        out
    }

    /// Exact disc of radius `r`.
    pub fn disc(r: f64) -> Result<Self> {
        positive("r", r)?;
        Ok(Shape::Disc { r })
    }

    /// Sphere of radius `r`.
    pub fn sphere(r: f64) -> Result<Self> {
        positive("r", r)?;
        Ok(Shape::Sphere { r })
    }

    /// Whether the shape is a 3D body (the sphere: per particle) rather than a 2D one (per
    /// unit depth).
    pub fn is_sphere(&self) -> bool {
        matches!(self, Shape::Sphere { .. })
    }

    /// Regular n-gon with circumradius `r` (vertices at 2 pi k / n in the body frame).
    pub fn regular_polygon(r: f64, n: usize) -> Result<Self> {
        Ok(Shape::Polygon(Polygon::regular(r, n)?))
    }

    /// Convex polygon from counter-clockwise vertices (any origin: they are shifted to the centroid).
    pub fn convex_polygon(vertices: &[[f64; 2]]) -> Result<Self> {
        Ok(Shape::Polygon(Polygon::convex(vertices)?))
    }

    /// Circumradius r: the disc's radius or the largest vertex distance from the centroid (m).
    pub fn circumradius(&self) -> f64 {
        match self {
            Shape::Disc { r } | Shape::Sphere { r } => *r,
            Shape::Polygon(p) => p.circumradius,
        }
    }

    /// Area (m^2); for the sphere its volume (m^3), so that rho times it is the mass.
    pub fn area(&self) -> f64 {
        match self {
            Shape::Disc { r } => PI * r * r,
            Shape::Sphere { r } => 4.0 / 3.0 * PI * r * r * r,
            Shape::Polygon(p) => p.area,
        }
    }

    /// Polar second moment of area about the centroid (m^4): I = rho times this; for the
    /// sphere its second moment of volume about a diameter, 2/5 r^2 times its volume (m^5).
    pub fn polar_moment(&self) -> f64 {
        match self {
            Shape::Disc { r } => 0.5 * PI * r.powi(4),
            Shape::Sphere { r } => 0.4 * r * r * (4.0 / 3.0 * PI * r * r * r),
            Shape::Polygon(p) => p.polar_moment,
        }
    }

    /// Height of the centre of mass at first touch for orientation `phi` (rad): the lowest
    /// point then lies exactly on y = 0.
    pub fn touch_height(&self, phi: f64) -> f64 {
        match self {
            Shape::Disc { r } | Shape::Sphere { r } => *r,
            Shape::Polygon(p) => {
                let (s, c) = phi.sin_cos();
                let v = &p.vertices[p.lowest_vertex(s, c)];
                -(s * v.x + c * v.y)
            }
        }
    }

    /// Overlap with the plate y <= 0 for a centre of mass at height `y` and orientation `phi`;
    /// `None` when the particle does not reach below y = 0.
    #[inline]
    pub fn overlap(&self, y: f64, phi: f64) -> Option<Overlap> {
        match self {
            Shape::Disc { r } => disc_segment(*r, y),
            Shape::Sphere { r } => sphere_contact(*r, y),
            Shape::Polygon(p) => p.clip_below_plate(y, phi),
        }
    }

    /// Body-frame vertices (empty for a disc).
    pub fn vertices(&self) -> &[Vector2<f64>] {
        match self {
            Shape::Disc { .. } | Shape::Sphere { .. } => &[],
            Shape::Polygon(p) => &p.vertices,
        }
    }
}

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

impl Polygon {
    /// Regular n-gon, circumradius `r`, first vertex on the body +x axis.
    pub fn regular(r: f64, n: usize) -> Result<Self> {
        positive("r", r)?;
        ensure_param!(n >= 3, "n", n, ">= 3");
        ensure_param!(n <= 1 << 20, "n", n, "<= 1048576");
        let vertices: Vec<Vector2<f64>> = (0..n)
            .map(|k| {
                let a = 2.0 * PI * (k as f64) / (n as f64);
                Vector2::new(r * a.cos(), r * a.sin())
            })
            .collect();
        Ok(Self::from_valid_ccw(vertices))
    }

    /// Convex polygon from counter-clockwise vertices; rejects non-finite, duplicated,
    /// clockwise, degenerate (collinear) and non-convex input.
    pub fn convex(vertices: &[[f64; 2]]) -> Result<Self> {
        let pts = validate_convex("vertices", vertices)?;
        let n = pts.len();
        // Shoelace sums about the vertex mean: about a far-away origin their terms cancel
        // badly (a square 5 m from the origin lost 4e-10 of its circumradius).
        let mean = pts.iter().sum::<Vector2<f64>>() / n as f64;
        let rel: Vec<Vector2<f64>> = pts.iter().map(|p| p - mean).collect();
        let signed_area: f64 = (0..n).map(|i| cross(rel[i], rel[(i + 1) % n])).sum::<f64>() * 0.5;
        let mut c = Vector2::zeros();
        for i in 0..n {
            let (p, q) = (rel[i], rel[(i + 1) % n]);
            c += (p + q) * cross(p, q);
        }
        c /= 6.0 * signed_area;
        // Shift to the centroid.
        Ok(Self::from_valid_ccw(
            rel.into_iter().map(|p| p - c).collect(),
        ))
    }

    fn from_valid_ccw(vertices: Vec<Vector2<f64>>) -> Self {
        let n = vertices.len();
        let (mut area2, mut j, mut c) = (0.0, 0.0, Vector2::zeros());
        for i in 0..n {
            let (p, q) = (vertices[i], vertices[(i + 1) % n]);
            let w = cross(p, q);
            area2 += w;
            c += (p + q) * w;
            j += w * (p.dot(&p) + p.dot(&q) + q.dot(&q));
        }
        let area = 0.5 * area2;
        let c = c / (3.0 * area2);
        let polar_moment = j / 12.0 - area * c.norm_squared();
        let circumradius = vertices.iter().map(|v| v.norm()).fold(0.0, f64::max);
        let mut polar: Vec<f64> = Vec::with_capacity(n);
        for v in &vertices {
            let mut a = v.y.atan2(v.x);
            if let Some(&first) = polar.first() {
                while a < first {
                    a += 2.0 * PI;
                }
            }
            polar.push(a);
        }
        Polygon {
            vertices,
            circumradius,
            area,
            polar_moment,
            polar,
        }
    }

    /// Body-frame vertices, counter-clockwise about the centroid.
    pub fn vertices(&self) -> &[Vector2<f64>] {
        &self.vertices
    }

    /// Largest vertex distance from the centroid (m).
    pub fn circumradius(&self) -> f64 {
        self.circumradius
    }

    /// Area (m^2).
    pub fn area(&self) -> f64 {
        self.area
    }

    /// Index of the lowest vertex at orientation (sin, cos) = (`s`, `c`): the one that
    /// minimises s v.x + c v.y (its world height relative to the centre). A binary search on
    /// the polar angles gives a neighbour of it, a short descent along the boundary the vertex
    /// itself (for a convex polygon the heights along the boundary have one minimum).
    #[inline]
    pub fn lowest_vertex(&self, s: f64, c: f64) -> usize {
        let n = self.vertices.len();
        let h = |i: usize| {
            let v = &self.vertices[i];
            s * v.x + c * v.y
        };
        // The body-frame direction that points straight down in the world.
        let first = self.polar[0];
        let mut a = (-c).atan2(-s);
        a = first + (a - first).rem_euclid(2.0 * PI);
        let mut k = self.polar.partition_point(|&p| p <= a).saturating_sub(1);
        if k >= n {
            k = n - 1;
        }
        let mut hk = h(k);
        loop {
            let next = if k + 1 == n { 0 } else { k + 1 };
            let hn = h(next);
            if hn < hk {
                (k, hk) = (next, hn);
                continue;
            }
            let prev = if k == 0 { n - 1 } else { k - 1 };
            let hp = h(prev);
            if hp < hk {
                (k, hk) = (prev, hp);
                continue;
            }
            return k;
        }
    }

    /// Clips the polygon, placed with its centroid at (0, y) and rotated by `phi`, to y <= 0.
    ///
    /// Only the vertices below the plate are visited: from the lowest vertex the boundary is
    /// walked backwards to the entry crossing, then forwards to the exit crossing (below the
    /// plate they form one contiguous chain of a convex polygon). The shoelace sums are
    /// accumulated on the fly, relative to the first emitted point so that slivers keep their
    /// precision. Vertices exactly on the plate count as inside; crossing points are placed
    /// exactly on y = 0.
    pub fn clip_below_plate(&self, y: f64, phi: f64) -> Option<Overlap> {
        let (s, c) = phi.sin_cos();
        let world = |v: &Vector2<f64>| (c * v.x - s * v.y, y + s * v.x + c * v.y);
        let n = self.vertices.len();
        let k = self.lowest_vertex(s, c);
        let low = world(&self.vertices[k]);
        let (depth, x_low) = (-low.1, low.0);
        if depth <= 0.0 {
            return None;
        }
        let first = self.chain_start(k, &world);
        let mut count = 0u32;
        let mut acc = ShoelaceAcc::default();
        let mut p = world(&self.vertices[if first == 0 { n - 1 } else { first - 1 }]);
        let mut i = first;
        for _ in 0..n {
            let q = world(&self.vertices[i]);
            let q_in = q.1 <= 0.0;
            if (p.1 <= 0.0) != q_in {
                acc.push((crossing_x(p, q), 0.0));
            }
            if !q_in {
                break;
            }
            acc.push(q);
            count += 1;
            p = q;
            i = if i + 1 == n { 0 } else { i + 1 };
        }
        let (area, cx, cy) = acc.finish();
        let (chord, x_mid) = if acc.chord_max >= acc.chord_min {
            (
                acc.chord_max - acc.chord_min,
                0.5 * (acc.chord_max + acc.chord_min),
            )
        } else {
            (0.0, x_low)
        };
        Some(Overlap {
            area,
            cx,
            cy,
            chord,
            x_mid,
            depth,
            x_low,
            first_moment: -area * cy,
            corners: Corners {
                first: first as u32,
                count,
            },
        })
    }

    /// From the lowest vertex `low` (at or below the plate), back to the first vertex of the
    /// chain at or below the plate; `world` places a body-frame vertex as (x, y).
    #[inline]
    fn chain_start(&self, low: usize, world: &impl Fn(&Vector2<f64>) -> (f64, f64)) -> usize {
        let n = self.vertices.len();
        let mut first = low;
        for _ in 1..n {
            let prev = if first == 0 { n - 1 } else { first - 1 };
            if world(&self.vertices[prev]).1 > 0.0 {
                break;
            }
            first = prev;
        }
        first
    }

    /// The chain of vertices at or below the plate for the centroid at (0, `y`) and
    /// orientation (sin, cos) = (`s`, `c`), given its lowest vertex `low` (at or below).
    pub(crate) fn corners_below(&self, y: f64, s: f64, c: f64, low: usize) -> Corners {
        let world = |v: &Vector2<f64>| (c * v.x - s * v.y, y + s * v.x + c * v.y);
        let n = self.vertices.len();
        let first = self.chain_start(low, &world);
        let mut count = 0u32;
        let mut i = first;
        while (count as usize) < n && world(&self.vertices[i]).1 <= 0.0 {
            count += 1;
            i = if i + 1 == n { 0 } else { i + 1 };
        }
        Corners {
            first: first as u32,
            count,
        }
    }

    /// World height of vertex `k` for the centroid at height `y` and orientation `phi`.
    #[inline]
    pub fn vertex_height(&self, k: usize, y: f64, phi: f64) -> f64 {
        let (s, c) = phi.sin_cos();
        let v = &self.vertices[k];
        y + s * v.x + c * v.y
    }
}

/// x where the segment p-q crosses y = 0 (p and q on opposite sides), interpolated from the
/// endpoint nearer the plate so that the short side of a sliver keeps its relative precision.
#[inline]
pub(crate) fn crossing_x(p: (f64, f64), q: (f64, f64)) -> f64 {
    if p.1.abs() <= q.1.abs() {
        p.0 + p.1 / (p.1 - q.1) * (q.0 - p.0)
    } else {
        q.0 + q.1 / (q.1 - p.1) * (p.0 - q.0)
    }
}

/// Checks that `vertices` form a strictly convex polygon in counter-clockwise order: at least
/// 3 finite, distinct vertices, positive signed area, every turn to the left (no collinear
/// vertices) and total turning 2 pi (no star). Errors name the parameter `name`.
pub(crate) fn validate_convex(name: &str, vertices: &[[f64; 2]]) -> Result<Vec<Vector2<f64>>> {
    let n = vertices.len();
    ensure_param!(n >= 3, name, format!("{n} vertices"), "at least 3 vertices");
    for (k, v) in vertices.iter().enumerate() {
        ensure_param!(
            v[0].is_finite() && v[1].is_finite(),
            name,
            format!("vertex {k} = {v:?}"),
            "finite coordinates"
        );
    }
    let pts: Vec<Vector2<f64>> = vertices.iter().map(|v| Vector2::new(v[0], v[1])).collect();
    let scale = pts
        .iter()
        .map(|p| p.norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    for i in 0..n {
        for j in (i + 1)..n {
            ensure_param!(
                (pts[i] - pts[j]).norm() > 1e-12 * scale,
                name,
                format!("vertices {i} and {j} coincide"),
                "distinct vertices"
            );
        }
    }
    let signed_area: f64 = (0..n).map(|i| cross(pts[i], pts[(i + 1) % n])).sum::<f64>() * 0.5;
    ensure_param!(
        signed_area > 0.0,
        name,
        format!("signed area {signed_area:e}"),
        "counter-clockwise order (positive signed area)"
    );
    let mut turning = 0.0;
    for i in 0..n {
        let e0 = pts[(i + 1) % n] - pts[i];
        let e1 = pts[(i + 2) % n] - pts[(i + 1) % n];
        let c = cross(e0, e1);
        ensure_param!(
            c > 1e-12 * e0.norm() * e1.norm(),
            name,
            format!("turn at vertex {}", (i + 1) % n),
            "a strictly convex polygon (every turn to the left, no collinear vertices)"
        );
        turning += c.atan2(e0.dot(&e1));
    }
    ensure_param!(
        (turning - 2.0 * PI).abs() < 1e-6,
        name,
        format!("total turning {turning:.6} rad"),
        "a simple convex polygon (total turning 2 pi)"
    );
    Ok(pts)
}

/// Shoelace sums over a stream of polygon vertices, relative to the first one.
#[derive(Default)]
struct ShoelaceAcc {
    origin: Option<(f64, f64)>,
    prev: (f64, f64),
    area2: f64,
    mx: f64,
    my: f64,
    chord_min: f64,
    chord_max: f64,
    started_chord: bool,
}

impl ShoelaceAcc {
    #[inline]
    fn push(&mut self, q: (f64, f64)) {
        if q.1 == 0.0 {
            if !self.started_chord {
                self.chord_min = q.0;
                self.chord_max = q.0;
                self.started_chord = true;
            } else {
                self.chord_min = self.chord_min.min(q.0);
                self.chord_max = self.chord_max.max(q.0);
            }
        }
        match self.origin {
            None => {
                self.origin = Some(q);
                self.prev = (0.0, 0.0);
            }
            Some(o) => {
                let r = (q.0 - o.0, q.1 - o.1);
                self.add_edge(self.prev, r);
                self.prev = r;
            }
        }
    }

    #[inline]
    fn add_edge(&mut self, a: (f64, f64), b: (f64, f64)) {
        let w = a.0 * b.1 - b.0 * a.1;
        self.area2 += w;
        self.mx += (a.0 + b.0) * w;
        self.my += (a.1 + b.1) * w;
    }

    /// (area, centroid x, centroid y); the centroid falls back to the origin point for a
    /// degenerate (zero-area) overlap.
    fn finish(&mut self) -> (f64, f64, f64) {
        let Some(o) = self.origin else {
            return (0.0, 0.0, 0.0);
        };
        if !self.started_chord {
            self.chord_min = f64::INFINITY;
            self.chord_max = f64::NEG_INFINITY;
        }
        // Closing edge back to the origin point contributes nothing (it ends at (0, 0)).
        if self.area2 > 0.0 {
            let area = 0.5 * self.area2;
            (
                area,
                o.0 + self.mx / (3.0 * self.area2),
                o.1 + self.my / (3.0 * self.area2),
            )
        } else {
            (0.0, o.0, o.1)
        }
    }
}

#[inline]
fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn regular_polygon_mass_properties() {
        let (r, n) = (2.0, 6usize);
        let p = Polygon::regular(r, n).unwrap();
        let area = 0.5 * n as f64 * r * r * (2.0 * PI / n as f64).sin();
        assert!(close(p.area, area, 1e-14));
        // Regular n-gon: J = A r^2 (1 + 2 cos^2(pi/n)) / 6.
        let j = area * r * r * (1.0 + 2.0 * (PI / n as f64).cos().powi(2)) / 6.0;
        assert!(close(p.polar_moment, j, 1e-13), "{} vs {j}", p.polar_moment);
    }

    #[test]
    fn square_face_down_clip_is_a_rectangle() {
        // Square of side 2 rotated by 45 deg about a vertex-based regular 4-gon: face down.
        let s = Shape::regular_polygon(2f64.sqrt(), 4).unwrap();
        let phi = PI / 4.0;
        let y = s.touch_height(phi) - 0.1; // 0.1 deep
        let o = s.overlap(y, phi).unwrap();
        assert!(close(o.area, 0.2, 1e-12), "area {}", o.area);
        assert!(close(o.cy, -0.05, 1e-12));
        assert!(o.cx.abs() < 1e-12);
        assert!(close(o.chord, 2.0, 1e-12));
        assert!(close(o.depth, 0.1, 1e-12));
    }

    #[test]
    fn triangle_corner_down_clip() {
        // Square standing on a corner: the overlap is a triangle of height d, base 2 d.
        let s = Shape::regular_polygon(1.0, 4).unwrap();
        let phi = -PI / 2.0; // a vertex points straight down
        let d = 1e-3;
        let y = s.touch_height(phi) - d;
        let o = s.overlap(y, phi).unwrap();
        assert!(close(o.area, d * d, 1e-9), "area {}", o.area);
        assert!(close(o.cy, -d / 3.0, 1e-9));
        assert!(close(o.chord, 2.0 * d, 1e-9));
    }

    #[test]
    fn convex_polygon_rejects_bad_vertices() {
        let ok = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        assert!(Polygon::convex(&ok).is_ok());
        let cw = [[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]];
        let dup = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let nan = [[0.0, 0.0], [f64::NAN, 0.0], [0.0, 1.0]];
        let collinear = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 1.0]];
        let nonconvex = [[0.0, 0.0], [2.0, 0.0], [0.5, 0.5], [0.0, 2.0]];
        let star: Vec<[f64; 2]> = (0..5)
            .map(|k| {
                let a = 4.0 * PI * k as f64 / 5.0;
                [a.cos(), a.sin()]
            })
            .collect();
        for bad in [
            &cw[..],
            &dup[..],
            &nan[..],
            &collinear[..],
            &nonconvex[..],
            &star[..],
            &ok[..2],
        ] {
            let e = Polygon::convex(bad).unwrap_err();
            assert!(
                matches!(e, crate::Error::InvalidParameter { ref name, .. } if name == "vertices"),
                "{e}"
            );
        }
    }
}
