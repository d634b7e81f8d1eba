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
    let mut best = distance_to_polygon(first, b);
    for &p in a {
        if reach(p) < best {
            best = best.min(distance_to_polygon(p, b));
        }
    }
    best
}
