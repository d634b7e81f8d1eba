//! Convex polygons: mass properties from the vertices (shoelace sums), and the overlap with the
//! plate by half-plane clipping that visits only the vertices below it (the lowest found by
//! binary search), area and centroid by the shoelace formula.

use super::chain::ChainSums;
use super::overlap::{Corners, Overlap};
use crate::error::{ensure_param, positive, Result};
use crate::numerics::trig::sin_cos;
use nalgebra::Vector2;
use std::f64::consts::PI;

/// A convex polygon in its body frame: counter-clockwise vertices about its centroid.
#[derive(Debug, Clone, PartialEq)]
pub struct Polygon {
    pub(crate) vertices: Vec<Vector2<f64>>,
    pub(crate) circumradius: f64,
    pub(crate) area: f64,
    /// Polar second moment of area about the centroid, m^4 (per unit depth).
    pub(crate) polar_moment: f64,
    /// Polar angles of the vertices about the centroid, unwrapped to increase from the first
    /// (convex and counter-clockwise about an interior point: monotone). Used to find the
    /// lowest vertex in O(log n) instead of scanning all of them every step.
    pub(crate) polar: Vec<f64>,
    /// The edges' cumulative shoelace sums, for the overlap of a long run of vertices below
    /// the plate in a few operations (`chain.rs`).
    pub(crate) chain: ChainSums,
    /// The largest world x of the lowest vertex over all orientations (m): see
    /// [`Polygon::lowest_arm`].
    pub(crate) lowest_arm: f64,
    /// The smallest distance from the centroid to an edge's line (m): the disc of this radius
    /// about the centroid lies inside, so an edge whose line is far from a point seen from the
    /// centroid need not be tested (`convex_window.rs`).
    pub(crate) inradius: f64,
    /// Each edge's line in the body frame: its outward unit normal and its distance from the
    /// centroid along it, so that the windowed clip tells an edge far from the contact without
    /// placing its corners (`convex_window.rs`).
    pub(crate) edge_lines: Vec<[f64; 3]>,
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
        let edge_lines: Vec<[f64; 3]> = (0..n)
            .map(|i| {
                let (p, q) = (vertices[i], vertices[(i + 1) % n]);
                let len = (q - p).norm();
                [(q.y - p.y) / len, (p.x - q.x) / len, cross(p, q) / len]
            })
            .collect();
        let inradius = edge_lines
            .iter()
            .map(|l| l[2])
            .fold(f64::INFINITY, f64::min);
        Polygon {
            inradius,
            edge_lines,
            chain: ChainSums::new(&vertices),
            lowest_arm: lowest_arm(&vertices),
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

    /// [`Self::lowest_vertex`] found by descending along the boundary from vertex `near` (the
    /// lowest one at a nearby orientation), without the binary search and its arctangent:
    /// where the body turned by few corners since, a few comparisons. After `MAX_DESCENT`
    /// steps the binary search takes over.
    #[inline]
    pub fn lowest_vertex_near(&self, near: usize, s: f64, c: f64) -> usize {
        const MAX_DESCENT: usize = 8;
        let n = self.vertices.len();
        let h = |i: usize| {
            let v = &self.vertices[i];
            s * v.x + c * v.y
        };
        // A hint is almost always a corner already: no integer division for it.
        let near = if near < n { near } else { near % n };
        let (mut k, mut hk) = (near, h(near));
        for _ in 0..MAX_DESCENT {
            let next = if k + 1 == n { 0 } else { k + 1 };
            let prev = if k == 0 { n - 1 } else { k - 1 };
            let (hn, hp) = (h(next), h(prev));
            if hn < hk {
                (k, hk) = (next, hn);
            } else if hp < hk {
                (k, hk) = (prev, hp);
            } else {
                return k;
            }
        }
        self.lowest_vertex(s, c)
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
        let (s, c) = sin_cos(phi);
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
        let (s, c) = sin_cos(phi);
        let v = &self.vertices[k];
        y + s * v.x + c * v.y
    }
}

/// The largest world x of the lowest vertex over all orientations: vertex k is lowest while
/// the downward direction lies between the outward normals of its two edges, and its offset
/// across that direction (< 90 deg from it, the centroid being inside) grows towards the
/// cone's edges, where it is |v_k . t| along the edge's tangent t.
fn lowest_arm(vertices: &[Vector2<f64>]) -> f64 {
    let n = vertices.len();
    (0..n)
        .map(|k| {
            let (a, b) = (vertices[k], vertices[(k + 1) % n]);
            let t = (b - a).normalize();
            a.dot(&t).abs().max(b.dot(&t).abs())
        })
        .fold(0.0, f64::max)
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
    use crate::geometry::Shape;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1e-300)
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
    fn the_lowest_arm_bounds_how_fast_the_spin_lowers_the_polygon() {
        // A regular n-gon: r sin(pi / n), reached where an edge lies flat.
        for n in [3, 4, 7, 120, 4096] {
            let p = Polygon::regular(0.01, n).unwrap();
            let exact = 0.01 * (PI / n as f64).sin();
            // To the rounding of 0.01-sized vertices 1.5e-5 apart.
            assert!(
                close(p.lowest_arm, exact, 1e-9),
                "n {n}: {} vs {exact}",
                p.lowest_arm
            );
        }
        // Any convex polygon: |d touch_height / d phi| <= arm at every orientation, and the
        // bound is reached (to the sampling's resolution).
        let shape =
            Shape::convex_polygon(&[[0.0, 0.0], [0.03, 0.002], [0.02, 0.011], [-0.004, 0.007]])
                .unwrap();
        let arm = shape.touch_arm();
        let (mut largest, h) = (0.0_f64, 1e-7);
        for k in 0..20_000 {
            let phi = k as f64 * (2.0 * PI / 20_000.0);
            let slope = (shape.touch_height(phi + h) - shape.touch_height(phi - h)) / (2.0 * h);
            assert!(
                slope.abs() <= arm * (1.0 + 1e-6),
                "phi {phi}: {slope} > {arm}"
            );
            largest = largest.max(slope.abs());
        }
        assert!(largest >= 0.99 * arm, "{largest} vs {arm}");
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
                matches!(e, crate::error::Error::InvalidParameter { ref name, .. } if name == "vertices"),
                "{e}"
            );
        }
    }
}
