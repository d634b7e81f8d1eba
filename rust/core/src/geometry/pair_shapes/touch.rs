//! Where the two bodies of a pair with corners first touch (docs/model.md 17.8): the particle's
//! centre straight above the partner's, at the largest height at which a corner or a disc rests
//! on the other body's top.

use super::{dot, placed, sub, PairBody};

/// The height of the particle's centre above the partner's at which they touch with
/// orientations `phi` = (phi1, phi2) (rad).
pub(super) fn touch_height(particle: PairBody<'_>, partner: PairBody<'_>, phi: [f64; 2]) -> f64 {
    let (phi1, phi2) = (phi[0], phi[1]);
    let origin = [0.0, 0.0];
    match (particle, partner) {
        (PairBody::Polygon(a), PairBody::Polygon(b)) => {
            let pa: Vec<[f64; 2]> = placed(a, origin, phi1).collect();
            let pb: Vec<[f64; 2]> = placed(b, origin, phi2).collect();
            // Corners of the particle over the partner's top, and the partner's corners
            // under the particle's bottom (the particle seen from below: mirrored).
            let flip = |p: &[[f64; 2]]| p.iter().map(|v| [-v[0], -v[1]]).collect::<Vec<_>>();
            corners_over_top(&pa, &pb).max(corners_over_top(&flip(&pb), &flip(&pa)))
        }
        (PairBody::Disc(r), PairBody::Polygon(b)) => {
            disc_over_top(r, &placed(b, origin, phi2).collect::<Vec<_>>())
        }
        (PairBody::Polygon(a), PairBody::Disc(r)) => {
            // The disc under the particle: the particle's bottom seen from below.
            let flipped: Vec<[f64; 2]> = placed(a, origin, phi1).map(|v| [-v[0], -v[1]]).collect();
            disc_over_top(r, &flipped)
        }
        (PairBody::Disc(r1), PairBody::Disc(r2)) => r1 + r2,
    }
}

/// The largest height h at which a corner of `a` (vertices relative to its centre, placed at
/// (0, h)) lies on the top of `b` (centred at the origin): over the corners above b's
/// upward-facing edges.
fn corners_over_top(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    let m = b.len();
    let mut best = f64::NEG_INFINITY;
    for j in 0..m {
        let (p, q) = (b[j], b[(j + 1) % m]);
        // Counter-clockwise: an edge going towards -x faces up.
        if q[0] >= p[0] {
            continue;
        }
        for v in a {
            if v[0] <= p[0] && v[0] >= q[0] {
                let y_edge = p[1] + (q[1] - p[1]) * (v[0] - p[0]) / (q[0] - p[0]);
                best = best.max(y_edge - v[1]);
            }
        }
    }
    best
}

/// The largest height at which a disc of radius `r` centred at (0, h) touches polygon `b`
/// (centred at the origin) from above: resting on a corner or tangent to an upward edge.
fn disc_over_top(r: f64, b: &[[f64; 2]]) -> f64 {
    let m = b.len();
    let mut best = f64::NEG_INFINITY;
    for j in 0..m {
        let (p, q) = (b[j], b[(j + 1) % m]);
        if p[0].abs() <= r {
            best = best.max(p[1] + (r * r - p[0] * p[0]).sqrt());
        }
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        let len = dx.hypot(dy);
        let nu = [dy / len, -dx / len];
        if nu[1] <= 0.0 {
            continue;
        }
        // The centre at distance r from the edge's line, its foot inside the edge.
        let h = (r + dot(nu, p)) / nu[1];
        let foot = [-r * nu[0], h - r * nu[1]];
        let t = dot(sub(foot, p), [dx, dy]) / (len * len);
        if (0.0..=1.0).contains(&t) {
            best = best.max(h);
        }
    }
    best
}
