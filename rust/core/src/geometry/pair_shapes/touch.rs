//! Where the two bodies of a pair with corners first touch (docs/model.md 17.8): the particle's
//! centre straight above the partner's, at the largest height at which a corner or a disc rests
//! on the other body's top.

use super::{dot, placed, sub, PairBody};
use crate::geometry::convex_clip::wrap;

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
/// upward-facing edges. Those edges (counter-clockwise, an edge going towards -x faces up)
/// are one chain along which x falls, so each corner finds the one or two edges over it by
/// bisection: O((n + m) log m) where every corner against every edge cost 14 400 edge tests
/// for two 120-gons, a twentieth of their adaptive impact. The same edges are tested with
/// the same arithmetic, so the height is the same to the last bit; where rounding breaks the
/// chain (an edge near vertical), every edge is tested.
fn corners_over_top(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    let m = b.len();
    let edge = |j: usize| (b[j], b[if j + 1 == m { 0 } else { j + 1 }]);
    let faces_up = |j: usize| {
        let (p, q) = edge(j);
        q[0] < p[0]
    };
    // The chain starts after an edge that does not face up.
    let Some(first) =
        (0..m).find(|&j| faces_up(j) && !faces_up(if j == 0 { m - 1 } else { j - 1 }))
    else {
        return corners_over_edges(a, b, 0..m);
    };
    let chain: Vec<([f64; 2], [f64; 2])> = (first..m)
        .chain(0..first)
        .take_while(|&j| faces_up(j))
        .map(edge)
        .collect();
    if chain.len() != (0..m).filter(|&j| faces_up(j)).count() {
        return corners_over_edges(a, b, 0..m);
    }
    let over = |v: [f64; 2], best: &mut f64| {
        // The edges whose far end is still right of the corner come first; the corner lies
        // over the next edge, and over the one after where it lies on their shared end.
        let k0 = chain.partition_point(|(_, q)| q[0] > v[0]);
        for &(p, q) in chain[k0..].iter().take(2) {
            if v[0] <= p[0] && v[0] >= q[0] {
                *best = best.max(height_over_edge(v, p, q));
            }
        }
    };
    // A corner rests on an edge at most as high as b's highest corner, so at most that less
    // its own height (plus the round-off of the edge's interpolation, a few ulps): from a's
    // lowest corner the heights rise along both sides of its boundary (a is convex), and once
    // a corner cannot reach the best height so far, none past it can. Two 120-gons tested
    // every corner (a fortieth of their adaptive impact).
    let top = b.iter().fold(f64::NEG_INFINITY, |t, v| t.max(v[1]));
    let n = a.len();
    let lowest = (0..n).fold(0, |k, i| if a[i][1] < a[k][1] { i } else { k });
    let reaches = |v: [f64; 2], best: f64| top - v[1] + 1e-12 * (top.abs() + v[1].abs()) >= best;
    let mut best = f64::NEG_INFINITY;
    over(a[lowest], &mut best);
    let (mut ahead, mut behind, mut taken) = (wrap(lowest + 1, n), wrap(lowest + n - 1, n), 1);
    while taken < n && reaches(a[ahead], best) {
        over(a[ahead], &mut best);
        (ahead, taken) = (wrap(ahead + 1, n), taken + 1);
    }
    while taken < n && reaches(a[behind], best) {
        over(a[behind], &mut best);
        (behind, taken) = (wrap(behind + n - 1, n), taken + 1);
    }
    best
}

/// The height at which corner `v` (relative to its centre) lies on the edge from `p` to `q`.
#[inline(always)]
fn height_over_edge(v: [f64; 2], p: [f64; 2], q: [f64; 2]) -> f64 {
    let y_edge = p[1] + (q[1] - p[1]) * (v[0] - p[0]) / (q[0] - p[0]);
    y_edge - v[1]
}

/// The largest height at which a corner of `a` lies on one of the `edges` of `b` that face up
/// (see [`corners_over_top`]).
fn corners_over_edges(a: &[[f64; 2]], b: &[[f64; 2]], edges: impl Iterator<Item = usize>) -> f64 {
    let m = b.len();
    let mut best = f64::NEG_INFINITY;
    for j in edges {
        let (p, q) = (b[j], b[(j + 1) % m]);
        if q[0] >= p[0] {
            continue;
        }
        for v in a {
            if v[0] <= p[0] && v[0] >= q[0] {
                best = best.max(height_over_edge(*v, p, q));
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Polygon;

    /// The chain's bisection, at the corners that can reach the highest, finds the same height
    /// as every corner against every edge, to the last bit: regular 3- to 200-gons and random
    /// convex polygons (corners of an ellipse), of sizes 1e-2 to 1e2 apart, at every
    /// orientation, each way round, and with corners on the partner's corners' abscissae
    /// (squares and their copies turned by multiples of a right angle).
    #[test]
    fn the_chain_gives_every_edge_tests_height() {
        let mut seeded = crate::numerics::seeded::Seeded(7);
        let mut rng = move || seeded.uniform();
        let polygon = |rng: &mut dyn FnMut() -> f64| {
            let n = 3 + (rng() * 198.0) as usize;
            if rng() < 0.5 {
                return Polygon::regular(0.5 + rng(), n).unwrap();
            }
            let mut t: Vec<f64> = (0..n.max(4))
                .map(|_| rng() * std::f64::consts::TAU)
                .collect();
            t.sort_by(f64::total_cmp);
            t.dedup_by(|x, y| (*x - *y).abs() < 1e-3);
            let aspect = 0.3 + 0.7 * rng();
            let v: Vec<[f64; 2]> = t.iter().map(|t| [t.cos(), aspect * t.sin()]).collect();
            Polygon::convex(&v).unwrap_or_else(|_| Polygon::regular(1.0, n).unwrap())
        };
        let check = |a: &[[f64; 2]], b: &[[f64; 2]]| {
            let all = corners_over_edges(a, b, 0..b.len());
            assert_eq!(corners_over_top(a, b).to_bits(), all.to_bits());
            all.is_finite()
        };
        let mut finite = 0;
        for case in 0..2000 {
            let (pa, pb) = (polygon(&mut rng), polygon(&mut rng));
            // Half the cases with a 1e-2 to 1e2 times the size of b.
            let size = if case % 2 == 0 {
                1.0
            } else {
                10f64.powf(4.0 * rng() - 2.0)
            };
            let a: Vec<[f64; 2]> = placed(&pa, [0.0, 0.0], rng() * 7.0)
                .map(|v| [size * v[0], size * v[1]])
                .collect();
            let b: Vec<[f64; 2]> = placed(&pb, [0.0, 0.0], rng() * 7.0).collect();
            finite += usize::from(check(&a, &b)) + usize::from(check(&b, &a));
        }
        // Where one body is a hundred times the other, no corner of the large one may lie
        // over the small one's top (its corners do over the large one's).
        assert!(finite > 3850, "{finite}");
        let square = Polygon::regular(1.0, 4).unwrap();
        for k in 0..8 {
            let phi = k as f64 * std::f64::consts::FRAC_PI_4;
            let a: Vec<[f64; 2]> = placed(&square, [0.0, 0.0], phi).collect();
            let b: Vec<[f64; 2]> = placed(&square, [0.0, 0.0], 0.0).collect();
            check(&a, &b);
            check(&b, &a);
        }
    }
}
