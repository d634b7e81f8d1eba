//! The distance between the bodies of a pair with corners where they do not overlap (the gap
//! of docs/model.md 17.8, which the flights between contacts jump over), and whether two
//! polygons overlap at all.

use super::{cross, dot, sub};
use std::cell::RefCell;

/// Whether `p` lies inside (or on) the counter-clockwise convex polygon `b`.
pub(super) fn inside(p: [f64; 2], b: &[[f64; 2]]) -> bool {
    let n = b.len();
    (0..n).all(|j| cross(sub(b[(j + 1) % n], b[j]), sub(p, b[j])) >= 0.0)
}

/// Squared distance from point `p` to segment a-b.
fn segment_distance2(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (d, w) = (sub(b, a), sub(p, a));
    let t = (dot(w, d) / dot(d, d)).clamp(0.0, 1.0);
    let e = [w[0] - t * d[0], w[1] - t * d[1]];
    dot(e, e)
}

/// Distance from `p` to the boundary of polygon `b` (0 inside).
pub(super) fn distance_to_polygon(p: [f64; 2], b: &[[f64; 2]]) -> f64 {
    if inside(p, b) {
        return 0.0;
    }
    let n = b.len();
    (0..n)
        .map(|j| segment_distance2(p, b[j], b[(j + 1) % n]))
        .fold(f64::INFINITY, f64::min)
        .sqrt()
}

/// [`distance_to_polygon`] from a corner `p` of the other body: the nearest point lies on an
/// edge with `p` on (or outside) its line, or at a vertex of one, so only those edges and their
/// neighbours are measured (a nearest vertex's two edges give its distance rounded two ways,
/// and the neighbour's may be the smaller), and `p` is inside where no edge has it outside:
/// the same test and value, a division for about half the edges. A pentagon flying about a
/// 1024-gon fifty times smaller spent two thirds of its impact in this distance.
fn distance_from_corner(p: [f64; 2], b: &[[f64; 2]]) -> f64 {
    let n = b.len();
    let side = |j: usize| cross(sub(b[(j + 1) % n], b[j]), sub(p, b[j])) <= 0.0;
    let (mut best, mut outside) = (f64::INFINITY, false);
    let (mut before, mut here) = (side(n - 1), side(0));
    for j in 0..n {
        let after = side((j + 1) % n);
        if here {
            outside |= cross(sub(b[(j + 1) % n], b[j]), sub(p, b[j])) < 0.0;
        }
        if before || here || after {
            best = best.min(segment_distance2(p, b[j], b[(j + 1) % n]));
        }
        (before, here) = (here, after);
    }
    if outside {
        best.sqrt()
    } else {
        0.0
    }
}

/// Whether the convex polygons `a` (centred near `q`) and `b` overlap: the O(n + m) clip.
pub(super) fn polygons_overlap(a: &[[f64; 2]], b: &[[f64; 2]], q: [f64; 2]) -> bool {
    thread_local! {
        static BUF: RefCell<PlacedClip> = const { RefCell::new((Vec::new(), Vec::new())) };
    }
    BUF.with(|cell| {
        let (out, next) = &mut *cell.borrow_mut();
        crate::geometry::convex_clip::clip_convex(a, b, q, out, next)
    })
}

/// The clip's two buffers.
type PlacedClip = (
    Vec<crate::geometry::convex_clip::ClipVertex>,
    Vec<crate::geometry::convex_clip::ClipVertex>,
);

/// The smallest distance from a vertex of `a` to polygon `b` (centred at `centre`, circumradius
/// `r`), both convex and apart: vertices farther from the centre than r plus the best distance
/// so far cannot be nearer, so only the few facing `b` are measured against its edges.
pub(super) fn vertices_distance(a: &[[f64; 2]], b: &[[f64; 2]], centre: [f64; 2], r: f64) -> f64 {
    let reach = |p: [f64; 2]| {
        let d = sub(p, centre);
        dot(d, d).sqrt() - r
    };
    let Some(first) = a
        .iter()
        .copied()
        .min_by(|x, y| reach(*x).total_cmp(&reach(*y)))
    else {
        return f64::INFINITY;
    };
    let mut best = distance_from_corner(first, b);
    for &p in a {
        if reach(p) < best {
            best = best.min(distance_from_corner(p, b));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::{distance_from_corner, distance_to_polygon};

    /// The corner's distance measures only the edges facing it, and gives every edge's
    /// minimum bit for bit: points all around random convex polygons (3 to 1024 corners),
    /// near and far, inside, on vertices and on the extensions of edges.
    #[test]
    fn the_corner_distance_is_every_edges_bit_for_bit() {
        let mut seeded = crate::numerics::seeded::Seeded(7);
        let mut rng = move || seeded.uniform();
        for case in 0..400 {
            let n = [3usize, 4, 5, 12, 120, 1024][case % 6];
            let aspect = 0.3 + 0.7 * rng();
            let turn = rng() * std::f64::consts::TAU;
            let b: Vec<[f64; 2]> = (0..n)
                .map(|k| {
                    let t = turn + std::f64::consts::TAU * k as f64 / n as f64;
                    [t.cos(), aspect * t.sin()]
                })
                .collect();
            for k in 0..50 {
                let p = match k % 5 {
                    0 => b[k % n],
                    1 => {
                        let (u, v) = (b[k % n], b[(k + 1) % n]);
                        let s = 1.0 + 3.0 * rng();
                        [u[0] + s * (v[0] - u[0]), u[1] + s * (v[1] - u[1])]
                    }
                    _ => {
                        let (r, t) = (0.5 + 4.0 * rng(), rng() * std::f64::consts::TAU);
                        [r * t.cos(), r * t.sin()]
                    }
                };
                let (fast, every) = (distance_from_corner(p, &b), distance_to_polygon(p, &b));
                assert_eq!(fast.to_bits(), every.to_bits(), "{n}-gon, p {p:?}");
            }
        }
    }
}
