//! The linear law's vertex springs on a pair (docs/model.md, 17.8): Cundall's vertex-edge
//! contacts between two polygons, and the one spring between a disc and a polygon.

use super::{cross, dot, inside, sub, ShapePatch};
use crate::geometry::pair::{HeldSprings, SpringRef, Springs};

/// The lane direction of a force on the particle along `u` at point `x`, the particle's
/// centre at `q`: (u, (x - q) x u, -(x x u)).
fn lane_direction(x: [f64; 2], u: [f64; 2], q: [f64; 2]) -> [f64; 4] {
    let l1 = cross(sub(x, q), u);
    [u[0], u[1], l1, -l1 - cross(q, u)]
}

/// How deep point `x` lies below the line of edge `j` of the counter-clockwise convex
/// polygon `poly` (positive inside), and that edge's outward normal.
#[inline(always)]
fn edge_depth(x: [f64; 2], poly: &[[f64; 2]], j: usize) -> (f64, [f64; 2]) {
    let e = sub(poly[(j + 1) % poly.len()], poly[j]);
    let len = e[0].hypot(e[1]);
    (cross(e, sub(x, poly[j])) / len, [e[1] / len, -e[0] / len])
}

/// How deep point `x` lies inside the counter-clockwise convex polygon `poly`, the outward
/// normal of the edge it is nearest to (Cundall's vertex-edge contact), and that edge.
fn least_penetration(x: [f64; 2], poly: &[[f64; 2]]) -> (f64, [f64; 2], usize) {
    let mut best = (f64::INFINITY, [0.0, 0.0], 0);
    for j in 0..poly.len() {
        let (depth, u) = edge_depth(x, poly, j);
        if depth < best.0 {
            best = (depth, u, j);
        }
    }
    best
}

/// The vertex springs of two polygons (placed vertices `a` of the particle, `b` of the
/// partner): each corner of one inside the other, `corners` the overlap's vertices (the
/// unmarked ones are corners, at the vertex's own coordinates), pressing along
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
            let (d, u, _) = least_penetration(x, b);
            (d, u)
        } else {
            let (d, mu, _) = least_penetration(x, a);
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
    let (depth, n, x) = disc_contact(c, r, poly, sign);
    // The overlap exists (the caller's clip found it): a round-off depth is a zero one.
    one_spring(depth.max(0.0), x, n, q)
}

/// The disc's signed penetration, the direction of its push on the particle (`sign` as for
/// [`disc_spring`]) and the polygon's point nearest to the centre.
fn disc_contact(c: [f64; 2], r: f64, poly: &[[f64; 2]], sign: f64) -> (f64, [f64; 2], [f64; 2]) {
    let (depth, u, x) = disc_penetration(c, r, poly);
    (depth, [sign * u[0], sign * u[1]], x)
}

/// One spring of depth `depth` pushing the particle (centre `q`) along `n` at point `x`.
fn one_spring(depth: f64, x: [f64; 2], n: [f64; 2], q: [f64; 2]) -> Springs {
    let mut springs = Springs::default();
    springs.add(depth, lane_direction(x, n, q));
    springs
}

/// The disc's penetration r - dist(c, polygon) (signed: < 0 apart), the unit direction from
/// the polygon's nearest point to the centre, and that point.
fn disc_penetration(c: [f64; 2], r: f64, poly: &[[f64; 2]]) -> (f64, [f64; 2], [f64; 2]) {
    if inside(c, poly) {
        let (e, nu, _) = least_penetration(c, poly);
        return (r + e, nu, [c[0] - e * nu[0], c[1] - e * nu[1]]);
    }
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
}

/// The disc's one spring where the overlap is not resolved (just after the touch, just past
/// the parting): signed, so that the force is smooth through the piece's ends; the contact
/// point is the polygon's point nearest to the centre.
pub(super) fn parted_disc_patch(
    c: [f64; 2],
    r: f64,
    poly: &[[f64; 2]],
    q: [f64; 2],
    sign: f64,
) -> ShapePatch {
    let (depth, n, x) = disc_contact(c, r, poly, sign);
    ShapePatch {
        area: 0.0,
        depth,
        chord: 0.0,
        n,
        centroid: x,
        b: [0.0; 2],
        springs: one_spring(depth, x, n, q),
        ..ShapePatch::default()
    }
}

/// The corner springs of two polygons (placed vertices `a` of the particle, its centre at
/// `q`, and `b` of the partner, centred at the origin; circumradii `reach`) to hold through a
/// piece of the adaptive path: each corner inside the other body, and the edge it is nearest
/// to. The same springs as [`corner_springs`], found without the overlap's vertices.
pub(super) fn held_corner_springs(
    a: &[[f64; 2]],
    b: &[[f64; 2]],
    q: [f64; 2],
    reach: [f64; 2],
) -> HeldSprings {
    let springs = corners_in_reach(a, b, q, reach)
        .filter_map(|(partner_corner, i, x, poly)| {
            let (depth, _, edge) = least_penetration(x, poly);
            (depth > 0.0).then_some(SpringRef {
                partner_corner,
                corner: i as u32,
                edge: edge as u32,
            })
        })
        .collect();
    HeldSprings {
        springs,
        ..HeldSprings::default()
    }
}

/// Each corner of either body within the other's circumradius (`reach`: the particle's and
/// the partner's; the particle's centre at `q`, the partner's at the origin): whether it is
/// the partner's, its index, where it is, and the body it may press into. Corners beyond
/// cannot be inside the other body.
fn corners_in_reach<'p>(
    a: &'p [[f64; 2]],
    b: &'p [[f64; 2]],
    q: [f64; 2],
    reach: [f64; 2],
) -> impl Iterator<Item = (bool, usize, [f64; 2], &'p [[f64; 2]])> + 'p {
    [
        (false, a, b, [0.0, 0.0], reach[1]),
        (true, b, a, q, reach[0]),
    ]
    .into_iter()
    .flat_map(move |(partner_corner, corners, poly, centre, r)| {
        corners
            .iter()
            .enumerate()
            .filter(move |&(_, &x)| within(x, centre, r))
            .map(move |(i, &x)| (partner_corner, i, x, poly))
    })
}

/// Whether `x` lies within distance `r` of `centre`.
#[inline(always)]
fn within(x: [f64; 2], centre: [f64; 2], r: f64) -> bool {
    let d = sub(x, centre);
    dot(d, d) <= r * r
}

/// The corner and the body it presses into of held spring `s`, and the sign of its push on
/// the particle.
#[inline(always)]
fn held_corner<'p>(
    s: &SpringRef,
    a: &'p [[f64; 2]],
    b: &'p [[f64; 2]],
) -> ([f64; 2], &'p [[f64; 2]], f64) {
    if s.partner_corner {
        (b[s.corner as usize], a, -1.0)
    } else {
        (a[s.corner as usize], b, 1.0)
    }
}

/// The held springs' forces: each corner's depth below its held edge's line (signed: the
/// law continued smoothly across the piece's end, where the switch is located).
pub(super) fn springs_of_held(
    a: &[[f64; 2]],
    b: &[[f64; 2]],
    q: [f64; 2],
    held: &HeldSprings,
) -> Springs {
    let mut springs = Springs::default();
    for s in &held.springs {
        let (x, poly, sign) = held_corner(s, a, b);
        let (depth, u) = edge_depth(x, poly, s.edge as usize);
        springs.add(depth, lane_direction(x, [sign * u[0], sign * u[1]], q));
    }
    springs
}

/// The event function of the held springs (> 0 once they are no longer the law's): a held
/// corner out of its edge's line (-depth), nearer to another edge than to its own (depth
/// minus the other's), or a corner not held inside the other body (its least penetration).
/// The largest of continuous functions: continuous, so a root finder locates the switch.
pub(super) fn held_springs_value(
    a: &[[f64; 2]],
    b: &[[f64; 2]],
    q: [f64; 2],
    reach: [f64; 2],
    held: &HeldSprings,
) -> f64 {
    let mut value = f64::NEG_INFINITY;
    for s in &held.springs {
        let (x, poly, _) = held_corner(s, a, b);
        let depth = edge_depth(x, poly, s.edge as usize).0;
        value = value.max(-depth);
        for k in 0..poly.len() {
            if k != s.edge as usize {
                value = value.max(depth - edge_depth(x, poly, k).0);
            }
        }
    }
    for (partner_corner, i, x, poly) in corners_in_reach(a, b, q, reach) {
        let is_held = |s: &SpringRef| s.partner_corner == partner_corner && s.corner as usize == i;
        if !held.springs.iter().any(is_held) {
            value = value.max(least_penetration(x, poly).0);
        }
    }
    value
}

/// The contact of held springs where the bodies' overlap is not resolved (none yet, or no
/// longer): no area, the springs' signed depths (the deepest is the pair's depth, < 0 once
/// they have parted), the normal their edges' mean, and the held corners' mean as the point
/// where friction acts (where the overlap shrinks to as they part). `None` with none held.
pub(super) fn parted_patch(
    a: &[[f64; 2]],
    b: &[[f64; 2]],
    held: &HeldSprings,
    springs: Springs,
) -> Option<ShapePatch> {
    let count = held.springs.len() as f64;
    let (mut n, mut centroid, mut depth) = ([0.0; 2], [0.0; 2], f64::NEG_INFINITY);
    for s in &held.springs {
        let (x, poly, sign) = held_corner(s, a, b);
        let (d, u) = edge_depth(x, poly, s.edge as usize);
        depth = depth.max(d);
        for i in 0..2 {
            n[i] += sign * u[i];
            centroid[i] += x[i] / count;
        }
    }
    let norm = n[0].hypot(n[1]);
    (norm > 0.0).then(|| ShapePatch {
        area: 0.0,
        depth,
        chord: 0.0,
        n: [n[0] / norm, n[1] / norm],
        centroid,
        b: [0.0; 2],
        springs,
        ..ShapePatch::default()
    })
}
