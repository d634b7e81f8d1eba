//! The general overlap of a polygon particle with any convex obstacle (a finite plate, a wedge,
//! a block), through parry's convex-polygon intersection (O'Rourke's edge chase).
//!
//! The default scene does not need this: its plate is a half-plane, clipped exactly and faster
//! in [`crate::geometry`]. [`OverlapMethod::Parry`](crate::geometry::OverlapMethod) routes the
//! flat plate through here, as a rectangle wider than the particle, so that users can compare
//! the two paths on the same impact; [`ConvexObstacle`] is the general entry point.
//!
//! Parry decides the topology (which vertices lie inside, which edges cross). The coordinates
//! are then placed here, not taken from parry, for two reasons of precision:
//! - parry's crossing point comes from Cramer's rule in absolute coordinates, which loses the
//!   relative precision of a sliver; here a crossing is interpolated along the particle's edge
//!   from the endpoint nearer the obstacle's edge line (for the flat plate this is exactly the
//!   half-plane path's formula);
//! - parry's collinearity tolerance is absolute (100 eps on twice a triangle's area); every
//!   sliver's triangles would be "degenerate" and skipped. Exact predicates are used instead
//!   (tolerance 0), on coordinates scaled by a power of two to O(1), so scaling is exact.
//!
//! Area and centroid come from the shoelace sums relative to the first overlap vertex, the
//! chord is the segment between the two points where the boundaries cross, and the contact
//! normal is perpendicular to it (docs/model.md, section 3).

use crate::error::Result;
use crate::geometry::{validate_convex, Overlap, Polygon};
use crate::numerics::trig::sin_cos;
use parry2d_f64::math::Vector2 as V;
use parry2d_f64::transformation::{
    convex_polygons_intersection_with_tolerances, PolygonIntersectionTolerances,
    PolylinePointLocation as Loc,
};
use std::cell::RefCell;

/// The overlap of a particle with a convex obstacle, in world coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Patch {
    /// Overlap area (m^2).
    pub area: f64,
    /// Overlap centroid (m).
    pub centroid: [f64; 2],
    /// The chord: the two points where the particle's and the obstacle's boundaries cross.
    /// `None` when they touch in a single point (zero area).
    pub chord: Option<[[f64; 2]; 2]>,
}

impl Patch {
    /// Chord length (m; 0 without a chord).
    pub fn chord_length(&self) -> f64 {
        self.chord
            .map_or(0.0, |[a, b]| (b[0] - a[0]).hypot(b[1] - a[1]))
    }

    /// Unit contact normal: perpendicular to the chord, on the side of the point `towards`
    /// (the particle's centre, so that it points out of the obstacle). `None` without a chord.
    pub fn normal(&self, towards: [f64; 2]) -> Option<[f64; 2]> {
        let [a, b] = self.chord?;
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        if len == 0.0 {
            return None;
        }
        let n = [-dy / len, dx / len];
        let side = n[0] * (towards[0] - a[0]) + n[1] * (towards[1] - a[1]);
        Some(if side >= 0.0 { n } else { [-n[0], -n[1]] })
    }
}

/// A fixed convex obstacle: counter-clockwise vertices in world coordinates (m).
#[derive(Debug, Clone, PartialEq)]
pub struct ConvexObstacle {
    vertices: Vec<[f64; 2]>,
}

impl ConvexObstacle {
    /// Validated like a particle polygon (finite, distinct, counter-clockwise, strictly convex);
    /// errors name `obstacle`.
    pub fn new(vertices: &[[f64; 2]]) -> Result<Self> {
        validate_convex("obstacle", vertices)?;
        Ok(ConvexObstacle {
            vertices: vertices.to_vec(),
        })
    }

    /// A finite plate: top face y = 0 for `x_min <= x <= x_max`, `thickness` deep.
    pub fn finite_plate(x_min: f64, x_max: f64, thickness: f64) -> Result<Self> {
        crate::error::finite("x_min", x_min)?;
        crate::error::ensure_param!(
            x_max.is_finite() && x_max > x_min,
            "x_max",
            x_max,
            format!("finite and > x_min = {x_min}")
        );
        crate::error::positive("thickness", thickness)?;
        Self::new(&[
            [x_min, -thickness],
            [x_max, -thickness],
            [x_max, 0.0],
            [x_min, 0.0],
        ])
    }

    /// Counter-clockwise vertices (m).
    pub fn vertices(&self) -> &[[f64; 2]] {
        &self.vertices
    }

    /// Overlap of `particle` placed with its centroid at (`x`, `y`) and rotated by `phi` (rad);
    /// `None` when they do not overlap.
    pub fn overlap(&self, particle: &Polygon, x: f64, y: f64, phi: f64) -> Option<Patch> {
        let scale = pow2_scale(particle.circumradius());
        let (s, c) = sin_cos(phi);
        SCRATCH.with(|cell| {
            let mut buf = cell.borrow_mut();
            let Scratch {
                particle: world,
                obstacle,
                out,
                ..
            } = &mut *buf;
            world.clear();
            // Work relative to the particle's centre, scaled to O(1) by a power of two.
            world.extend(
                particle
                    .vertices()
                    .iter()
                    .map(|v| V::new((c * v.x - s * v.y) * scale, (s * v.x + c * v.y) * scale)),
            );
            obstacle.clear();
            obstacle.extend(
                self.vertices
                    .iter()
                    .map(|o| V::new((o[0] - x) * scale, (o[1] - y) * scale)),
            );
            let p = intersect(world, obstacle, out)?;
            let inv = 1.0 / scale;
            let back = |q: [f64; 2]| [x + q[0] * inv, y + q[1] * inv];
            Some(Patch {
                area: p.area * inv * inv,
                centroid: back(p.centroid),
                chord: p.chord.map(|[a, b]| [back(a), back(b)]),
            })
        })
    }
}

/// The flat plate's overlap through the general path: the plate is a rectangle twice as wide
/// as the particle's circumscribed circle, in the frame of the half-plane path (x relative to
/// the centre of mass, plate at y = 0), so that both paths see the same vertex coordinates.
pub fn plate_overlap(particle: &Polygon, y: f64, phi: f64) -> Option<Overlap> {
    let scale = pow2_scale(particle.circumradius());
    let (s, c) = sin_cos(phi);
    SCRATCH.with(|cell| {
        let mut buf = cell.borrow_mut();
        let Scratch {
            particle: world,
            obstacle,
            out,
            ..
        } = &mut *buf;
        // The same expressions and lowest vertex as the half-plane path, then an exact
        // scaling.
        let place = |v: &nalgebra::Vector2<f64>| (c * v.x - s * v.y, y + s * v.x + c * v.y);
        let k_low = particle.lowest_vertex(s, c);
        let (x_low, low) = place(&particle.vertices()[k_low]);
        let depth = -low;
        if depth <= 0.0 {
            return None;
        }
        world.clear();
        world.extend(particle.vertices().iter().map(|v| {
            let (wx, wy) = place(v);
            V::new(wx * scale, wy * scale)
        }));
        // Half-width 2 (scaled circumradius <= sqrt 2): wider than the particle, and a power of
        // two so that the top edge's orientation test is exact. The bottom lies below the
        // particle at any depth.
        let bottom = (y * scale).min(0.0) - 2.0;
        obstacle.clear();
        obstacle.extend([
            V::new(-2.0, bottom),
            V::new(2.0, bottom),
            V::new(2.0, 0.0),
            V::new(-2.0, 0.0),
        ]);
        let inv = 1.0 / scale;
        let corners = particle.corners_below(y, s, c, k_low);
        let Some(p) = intersect(world, obstacle, out) else {
            // Parry found no area although a vertex is below the plate: a sliver below the
            // resolution of its predicates. Report it as a zero-area touch at the lowest point.
            return Some(Overlap {
                area: 0.0,
                cx: x_low,
                cy: -depth,
                chord: 0.0,
                x_mid: x_low,
                depth,
                x_low,
                first_moment: 0.0,
                corners,
            });
        };
        let (chord, x_mid) = match p.chord {
            Some([a, b]) => ((b[0] - a[0]).hypot(b[1] - a[1]), 0.5 * (a[0] + b[0])),
            None => (0.0, x_low * scale),
        };
        let area = p.area * inv * inv;
        let cy = p.centroid[1] * inv;
        Some(Overlap {
            area,
            cx: p.centroid[0] * inv,
            cy,
            chord: chord * inv,
            x_mid: x_mid * inv,
            depth,
            x_low,
            first_moment: -area * cy,
            corners,
        })
    })
}

/// The overlap of two convex polygons whose counter-clockwise vertices `particle` and `partner`
/// are given in one frame (m), of size about `reach`: its patch and the overlap polygon's
/// vertices, each marked when it is a crossing of the two boundaries (the others are corners
/// of one polygon inside the other), handed to `f`. `None` when they do not overlap.
#[cfg(test)]
pub(crate) fn polygon_pair_overlap<R>(
    particle: impl Iterator<Item = [f64; 2]>,
    partner: impl Iterator<Item = [f64; 2]>,
    reach: f64,
    f: impl FnOnce(&Patch, &[([f64; 2], bool)]) -> R,
) -> Option<R> {
    let scale = pow2_scale(reach);
    SCRATCH.with(|cell| {
        let mut buf = cell.borrow_mut();
        let Scratch {
            particle: a,
            obstacle: b,
            out,
            points,
        } = &mut *buf;
        a.clear();
        a.extend(particle.map(|p| V::new(p[0] * scale, p[1] * scale)));
        b.clear();
        b.extend(partner.map(|p| V::new(p[0] * scale, p[1] * scale)));
        let p = intersect(a, b, out)?;
        let inv = 1.0 / scale;
        let back = |q: [f64; 2]| [q[0] * inv, q[1] * inv];
        let patch = Patch {
            area: p.area * inv * inv,
            centroid: back(p.centroid),
            chord: p.chord.map(|[u, w]| [back(u), back(w)]),
        };
        points.clear();
        points.extend(
            out.iter()
                .map(|&(v, crossing)| ([v.x * inv, v.y * inv], crossing)),
        );
        Some(f(&patch, points))
    })
}

/// A power of two near 1 / r: multiplying by it is exact.
fn pow2_scale(r: f64) -> f64 {
    let e = (-r.log2().round()).clamp(-1000.0, 1000.0);
    2f64.powi(e as i32)
}

/// Reused buffers: the overlap runs once per time step and should not allocate.
#[derive(Default)]
struct Scratch {
    particle: Vec<V>,
    obstacle: Vec<V>,
    out: Vec<(V, bool)>,
    /// The overlap's vertices in the caller's units (`polygon_pair_overlap`, the reference
    /// the pairs' own clip is tested against).
    #[cfg_attr(not(test), allow(dead_code))]
    points: Vec<([f64; 2], bool)>,
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

/// Twice the signed area of (a, b, p): > 0 when p is left of a -> b.
#[inline]
fn orient(a: V, b: V, p: V) -> f64 {
    (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)
}

/// Where the particle's edge p-q crosses the line of the obstacle's edge a-b, interpolated
/// from the endpoint nearer that line. Falls back to `fallback` for (numerically) parallel
/// edges, where the line test cannot place the point.
#[inline]
fn edge_crossing(p: V, q: V, a: V, b: V, fallback: V) -> V {
    let (op, oq) = (orient(a, b, p), orient(a, b, q));
    if op == oq || op * oq > 0.0 {
        return fallback;
    }
    if op.abs() <= oq.abs() {
        p + (q - p) * (op / (op - oq))
    } else {
        q + (p - q) * (oq / (oq - op))
    }
}

/// Area, centroid and chord of the intersection of two counter-clockwise convex polygons
/// (scaled coordinates); `None` when they do not overlap. `out` is scratch space.
fn intersect(particle: &[V], obstacle: &[V], out: &mut Vec<(V, bool)>) -> Option<Patch> {
    out.clear();
    let tol = PolygonIntersectionTolerances {
        collinearity_epsilon: 0.0,
    };
    convex_polygons_intersection_with_tolerances(particle, obstacle, tol, |l1, l2| {
        let point = match (l1, l2) {
            (Some(Loc::OnVertex(i)), _) => particle[i],
            (_, Some(Loc::OnVertex(j))) => obstacle[j],
            (Some(Loc::OnEdge(i, k, w)), Some(Loc::OnEdge(j, l, _))) => edge_crossing(
                particle[i],
                particle[k],
                obstacle[j],
                obstacle[l],
                Loc::OnEdge(i, k, w).to_point(particle),
            ),
            (Some(l), None) => l.to_point(particle),
            (None, Some(l)) => l.to_point(obstacle),
            (None, None) => return,
        };
        // A point on both boundaries is a crossing; so is a vertex of one polygon lying exactly
        // on the other's boundary (parry reports those as plain vertices).
        let crossing = (l1.is_some() && l2.is_some())
            || (l2.is_none() && on_boundary(obstacle, point))
            || (l1.is_none() && on_boundary(particle, point));
        out.push((point, crossing));
    });
    match patch_of(out) {
        // Two convex boundaries that cross do so at least twice. Where a corner lies exactly
        // on the other's edge parry's edge chase can lose its way and return one polygon
        // whole, with one crossing (two squares, a corner on an edge: the particle's whole
        // area, no chord, so the contact's centroid jumped for that one state). Then the
        // overlap is clipped here (checked on the chord, which is searched for anyway: the
        // common path gains nothing; 12-gon pairs 527 against 525 ns per step).
        Some(p) if p.chord.is_none() => {
            clip_convex(particle, obstacle, out);
            patch_of(out)
        }
        p => p,
    }
}

/// Area, centroid and chord of the overlap polygon `out` (its vertices with their crossing
/// marks); `None` for fewer than three vertices or no area.
fn patch_of(out: &[(V, bool)]) -> Option<Patch> {
    if out.len() < 3 {
        return None;
    }
    // Shoelace relative to the first vertex (slivers keep their relative precision).
    let o = out[0].0;
    let (mut a2, mut mx, mut my) = (0.0, 0.0, 0.0);
    let mut prev = V::new(0.0, 0.0);
    for &(pt, _) in &out[1..] {
        let r = pt - o;
        let w = prev.x * r.y - r.x * prev.y;
        a2 += w;
        mx += (prev.x + r.x) * w;
        my += (prev.y + r.y) * w;
        prev = r;
    }
    // The closing edge ends at the origin point and contributes nothing.
    if a2 == 0.0 {
        return None;
    }
    let centroid = [o.x + mx / (3.0 * a2), o.y + my / (3.0 * a2)];
    // The chord: the two crossing points farthest apart (duplicates from degenerate
    // configurations are harmless).
    let mut chord = None;
    let mut best = -1.0;
    for (i, &(a, ca)) in out.iter().enumerate() {
        if !ca {
            continue;
        }
        for &(b, cb) in &out[i + 1..] {
            if cb && (b - a).length_squared() > best {
                best = (b - a).length_squared();
                chord = Some([[a.x, a.y], [b.x, b.y]]);
            }
        }
    }
    Some(Patch {
        area: 0.5 * a2.abs(),
        centroid,
        chord,
    })
}

/// Which boundary the edge leaving a vertex of the clipped polygon runs along.
#[derive(Clone, Copy)]
enum Along {
    Particle,
    Obstacle,
}

/// The overlap of two counter-clockwise convex polygons by clipping `particle` with each of
/// `obstacle`'s edges in turn (Sutherland-Hodgman, exact orientation predicates), into `out`
/// with the same marks as parry's path: a crossing of the two boundaries, or a corner of one
/// inside the other (a corner of either on the other's boundary counts as a crossing). A point
/// cut from a particle's edge is a crossing; one cut from an edge the clip made (along the
/// obstacle's boundary) is the obstacle's corner (a crossing only on the particle's boundary).
/// O(n m), against parry's O(n + m): used only where parry's result is inconsistent.
#[cold]
#[inline(never)]
fn clip_convex(particle: &[V], obstacle: &[V], out: &mut Vec<(V, bool)>) {
    let mut poly: Vec<(V, bool, Along)> = particle
        .iter()
        .map(|&p| (p, on_boundary(obstacle, p), Along::Particle))
        .collect();
    let m = obstacle.len();
    for j in 0..m {
        let (a, b) = (obstacle[j], obstacle[(j + 1) % m]);
        let mut next = Vec::with_capacity(poly.len() + 1);
        for i in 0..poly.len() {
            let (p, p_cross, along) = poly[i];
            let q = poly[(i + 1) % poly.len()].0;
            let (op, oq) = (orient(a, b, p), orient(a, b, q));
            if op >= 0.0 {
                next.push((p, p_cross, along));
            }
            if (op > 0.0 && oq < 0.0) || (op < 0.0 && oq > 0.0) {
                let cut = edge_crossing(p, q, a, b, p + (q - p) * (op / (op - oq)));
                let crossing = match along {
                    Along::Particle => true,
                    Along::Obstacle => on_boundary(particle, cut),
                };
                // Leaving, the boundary runs on along the obstacle's edge; entering, along
                // the edge it came in on.
                let after = if op > 0.0 { Along::Obstacle } else { along };
                next.push((cut, crossing, after));
            }
        }
        poly = next;
        if poly.len() < 3 {
            break;
        }
    }
    out.clear();
    out.extend(poly.iter().map(|&(p, crossing, _)| (p, crossing)));
}

/// Whether `p` lies exactly on the boundary of the counter-clockwise convex polygon `poly`
/// (p is known to lie in it).
fn on_boundary(poly: &[V], p: V) -> bool {
    let n = poly.len();
    (0..n).any(|i| orient(poly[i], poly[(i + 1) % n], p) == 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Shape;

    #[test]
    fn square_face_down_matches_half_plane() {
        let s = Polygon::regular(2f64.sqrt(), 4).unwrap();
        let phi = std::f64::consts::FRAC_PI_4;
        let y = Shape::Polygon(std::sync::Arc::new(s.clone())).touch_height(phi) - 0.1;
        let a = s.clip_below_plate(y, phi).unwrap();
        let b = plate_overlap(&s, y, phi).unwrap();
        assert!((a.area - b.area).abs() < 1e-14, "{a:?} vs {b:?}");
        assert!((a.cy - b.cy).abs() < 1e-14);
        assert!((a.chord - b.chord).abs() < 1e-14);
    }
}
