//! The linear law's vertex springs on a pair (docs/model.md, 17.8): Cundall's vertex-edge
//! contacts between two polygons, and the one spring between a disc and a polygon.

use super::{cross, dot, inside, sub};
use crate::geometry::pair::Springs;

/// The lane direction of a force on the particle along `u` at point `x`, the particle's
/// centre at `q`: (u, (x - q) x u, -(x x u)).
fn lane_direction(x: [f64; 2], u: [f64; 2], q: [f64; 2]) -> [f64; 4] {
    let l1 = cross(sub(x, q), u);
    [u[0], u[1], l1, -l1 - cross(q, u)]
}

/// How deep point `x` lies inside the counter-clockwise convex polygon `poly`, and the
/// outward normal of the edge it is nearest to (Cundall's vertex-edge contact).
fn least_penetration(x: [f64; 2], poly: &[[f64; 2]]) -> (f64, [f64; 2]) {
    let m = poly.len();
    let mut best = (f64::INFINITY, [0.0, 0.0]);
    for j in 0..m {
        let e = sub(poly[(j + 1) % m], poly[j]);
        let len = e[0].hypot(e[1]);
        let depth = cross(e, sub(x, poly[j])) / len;
        if depth < best.0 {
            best = (depth, [e[1] / len, -e[0] / len]);
        }
    }
    best
}

/// The vertex springs of two polygons (placed vertices `a` of the particle, `b` of the
/// partner): each corner of one inside the other, `corners` the overlap's vertices (the
/// unmarked ones are corners; parry hands back a vertex's own coordinates), pressing along
/// the outward normal of the edge it is nearest to, as deep as it lies below that edge.
pub(super) fn corner_springs(
    a: &[[f64; 2]],
    b: &[[f64; 2]],
    corners: &[([f64; 2], bool)],
    q: [f64; 2],
) -> Springs {
    let mut springs = Springs::default();
    for &(x, crossing) in corners {
        if crossing {
            continue;
        }
        let (depth, u) = if a.contains(&x) {
            least_penetration(x, b)
        } else {
            let (d, mu) = least_penetration(x, a);
            (d, [-mu[0], -mu[1]])
        };
        // A corner just inside may sit at a round-off depth of either sign: its spring is
        // there (its dashpot acts from the touch on), at zero depth.
        springs.add(depth.max(0.0), lane_direction(x, u, q));
    }
    springs
}

/// The linear law's one spring between a disc (centre `c`, radius `r`) and a polygon: the
/// disc's penetration r - dist(c, polygon) along the direction from the polygon's nearest
/// point to the centre; `sign` +1 when the disc is the particle, -1 when the polygon is.
pub(super) fn disc_spring(
    c: [f64; 2],
    r: f64,
    poly: &[[f64; 2]],
    q: [f64; 2],
    sign: f64,
) -> Springs {
    let mut springs = Springs::default();
    let (depth, u, x) = if inside(c, poly) {
        let (e, nu) = least_penetration(c, poly);
        (r + e, nu, [c[0] - e * nu[0], c[1] - e * nu[1]])
    } else {
        let m = poly.len();
        let mut best = (f64::INFINITY, [0.0, 0.0]);
        for j in 0..m {
            let (p, w) = (poly[j], poly[(j + 1) % m]);
            let d = sub(w, p);
            let t = (dot(sub(c, p), d) / dot(d, d)).clamp(0.0, 1.0);
            let foot = [p[0] + t * d[0], p[1] + t * d[1]];
            let dist = (c[0] - foot[0]).hypot(c[1] - foot[1]);
            if dist < best.0 {
                best = (dist, foot);
            }
        }
        let (dist, foot) = best;
        (
            r - dist,
            [(c[0] - foot[0]) / dist, (c[1] - foot[1]) / dist],
            foot,
        )
    };
    // The overlap exists (the caller's clip found it): a round-off depth is a zero one.
    springs.add(
        depth.max(0.0),
        lane_direction(x, [sign * u[0], sign * u[1]], q),
    );
    springs
}
