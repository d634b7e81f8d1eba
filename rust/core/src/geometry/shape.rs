//! Particle shapes and their overlap with the flat plate y <= 0.
//!
//! "Model only what a scene requires": the exact disc uses the closed-form circular segment,
//! polygons are clipped against the half-plane y <= 0 (one Sutherland-Hodgman pass, no
//! allocation). Both return the same [`Overlap`] summary, which is all the contact law needs.
//! The general convex-convex intersection (finite plates, any convex obstacle) lives in
//! [`crate::geometry::parry`]; [`OverlapMethod::Parry`] routes the flat plate through it so that the
//! two paths can be compared on the same scene.

use super::disc::disc_segment;
use super::overlap::{Corners, Overlap};
pub use super::polygon::Polygon;
use crate::error::{ensure_param, positive, Result};
use crate::numerics::trig::sin_cos;
use nalgebra::Vector2;
use std::f64::consts::PI;
use std::sync::Arc;

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
    /// Convex polygon (regular n-gons included), shared: a sweep's cases of one shape hold one
    /// polygon (its vertices and edge sums), which each case's scene cloned before (four
    /// allocations per case: ~0.5 us of a 120-gon's, more than the engine's own setup).
    Polygon(Arc<Polygon>),
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
        let mut seeded = crate::numerics::seeded::Seeded(seed);
        let mut uniform = || seeded.uniform();
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
        Ok(Shape::Polygon(Arc::new(Polygon::regular(r, n)?)))
    }

    /// Convex polygon from counter-clockwise vertices (any origin: they are shifted to the centroid).
    pub fn convex_polygon(vertices: &[[f64; 2]]) -> Result<Self> {
        Ok(Shape::Polygon(Arc::new(Polygon::convex(vertices)?)))
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
                let (s, c) = sin_cos(phi);
                let v = &p.vertices[p.lowest_vertex(s, c)];
                -(s * v.x + c * v.y)
            }
        }
    }

    /// The most the lowest point's height changes per radian of turn, |d touch_height / d phi|
    /// (m): the world x of the lowest vertex, at most [`Polygon::lowest_arm`] (r sin(pi / n)
    /// for a regular n-gon); zero for a disc or sphere. A flight's spin brings the particle to
    /// the plate no faster than this times |omega|.
    pub fn touch_arm(&self) -> f64 {
        match self {
            Shape::Disc { .. } | Shape::Sphere { .. } => 0.0,
            Shape::Polygon(p) => p.lowest_arm,
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
