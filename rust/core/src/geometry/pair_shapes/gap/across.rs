//! The gap of two polygons a line of one's edges separates, measured only at the corners that
//! can be nearest across that line (docs/model.md 17.8, the gap).

use super::{corner_distance, facing_edge_line, wrap, PlacedPolygon, HINTS, SEPARATION};
use crate::geometry::pair_shapes::{dot, sub};

/// A line of a body's edges in the world frame: a point p lies `beyond` it by n . (p - c) - h
/// (n the edge's unit outward normal, c the body's centre, h the edge's offset from it).
#[derive(Debug, Clone, Copy)]
pub(super) struct SeparatingLine {
    n: [f64; 2],
    c: [f64; 2],
    h: f64,
}

impl SeparatingLine {
    /// How far beyond the line `p` lies (negative inside).
    #[inline(always)]
    fn beyond(&self, p: [f64; 2]) -> f64 {
        let (n, c) = (self.n, self.c);
        n[0] * (p[0] - c[0]) + n[1] * (p[1] - c[1]) - self.h
    }
}

/// The line of `body`'s edges facing the corner of `a` nearest its centre, where every corner
/// of `a` lies outside it by [`SEPARATION`] of the coordinates; `None` where one does not.
pub(super) fn separating_line(a: &[[f64; 2]], body: &PlacedPolygon) -> Option<SeparatingLine> {
    let c = body.centre();
    let dist2 = |p: [f64; 2]| {
        let d = sub(p, c);
        dot(d, d)
    };
    let &first = a.first()?;
    let nearest = a.iter().fold(
        first,
        |best, &p| {
            if dist2(p) < dist2(best) {
                p
            } else {
                best
            }
        },
    );
    let [nx, ny, h] = facing_edge_line(body, nearest, 0);
    // The line in the world frame: n turned by the body's angle.
    let line = SeparatingLine {
        n: body.in_world([nx, ny]),
        c,
        h,
    };
    let scale = body.polygon().circumradius() + c[0].abs() + c[1].abs();
    a.iter()
        .all(|&p| line.beyond(p) > SEPARATION * (scale + p[0].abs() + p[1].abs()))
        .then_some(line)
}

/// The least distance from a corner of either polygon to the other, `x` (corners, body) lying
/// wholly beyond `line`, an edge line of `y`, which lies inside it; `y_side` names y's search
/// hint (0 the particle, 1 the partner). The least of every corner's [`corner_distance`], bit
/// for bit, from the corners that can be nearest alone:
///
/// - x's corners against y: a corner's distance beyond the line bounds its distance to y from
///   below, so those beyond it by the least distance so far are passed by;
/// - y's corners against x: only x's cap within that least distance (plus margins) of the line
///   can come that near a point inside the line; a corner of y whose distance to the cap is
///   bounded by its depth inside the line plus x's least distance beyond it, across, and by
///   how far along the line it lies outside the cap's extent, along, is passed by where the
///   bound is at least the least distance so far.
///
/// Two 12-gons apart measured two corners each way (edge to edge, both ends); a corner facing
/// an edge is now the only one measured. Every bound is made smaller, and the least larger, by
/// a margin far above the round-off of the placed corners, the bounds and the distances.
pub(super) fn gap_across(
    line: &SeparatingLine,
    (x, body_x): (&[[f64; 2]], &PlacedPolygon),
    (y, body_y): (&[[f64; 2]], &PlacedPolygon),
    y_side: usize,
) -> f64 {
    let (cx, cy) = (body_x.centre(), body_y.centre());
    let scale = body_x.polygon().circumradius()
        + body_y.polygon().circumradius()
        + cx[0].abs()
        + cx[1].abs()
        + cy[0].abs()
        + cy[1].abs();
    let margin = 1e-12 * scale;
    let mut hints = HINTS.get();
    // Around each boundary the corners' distance beyond the line falls to its least and rises
    // once (both convex): x's arc of corners nearest the line from the corner least along its
    // normal, y's from its corner farthest along it (body-frame searches, to within round-off).
    let (n, m) = (x.len(), y.len());
    let (next, prev) = (
        |i: usize, n: usize| wrap(i + 1, n),
        |i: usize, n: usize| wrap(i + n - 1, n),
    );
    let along_x = body_x.in_body(line.n);
    let k = body_x
        .polygon()
        .lowest_vertex_near(hints[2 + y_side], along_x[0], along_x[1]);
    hints[2 + y_side] = k;
    // x's corners against y, while one may lie nearer than the best so far.
    let measure_x = |i: usize, best: &mut f64, hint: &mut usize| {
        let near = line.beyond(x[i]) - margin < *best;
        if near {
            *best = best.min(corner_distance(x[i], y, body_y, hint));
        }
        near
    };
    let mut best = corner_distance(x[k], y, body_y, &mut hints[y_side]);
    let (mut ahead, mut behind, mut taken) = (next(k, n), prev(k, n), 1);
    while taken < n && measure_x(ahead, &mut best, &mut hints[y_side]) {
        (ahead, taken) = (next(ahead, n), taken + 1);
    }
    while taken < n && measure_x(behind, &mut best, &mut hints[y_side]) {
        (behind, taken) = (prev(behind, n), taken + 1);
    }
    // x's cap within best (and twice the margin) of the line, its extent along the line; its
    // least distance beyond the line, at most k's.
    let t = [-line.n[1], line.n[0]];
    let (lo, hi) = cap_extent(line, x, k, t, best + 2.0 * margin);
    let (lo, hi) = (lo - margin, hi + margin);
    let least_beyond = line
        .beyond(x[k])
        .min(line.beyond(x[prev(k, n)]))
        .min(line.beyond(x[next(k, n)]))
        - margin;
    // y's corners against x, from its corner farthest along the normal, while one lies inside
    // the line by less than the best so far less x's least distance beyond it.
    let from_y = body_y.in_body(line.n);
    let j = body_y
        .polygon()
        .lowest_vertex_near(hints[y_side], -from_y[0], -from_y[1]);
    let x_side = 1 - y_side;
    let measure_y = |i: usize, best: &mut f64, hint: &mut usize| {
        let p = y[i];
        let across = (least_beyond - line.beyond(p) - margin).max(0.0);
        let reach = *best + margin;
        if across >= reach {
            return false;
        }
        let s = dot(t, p);
        let along = (lo - s).max(s - hi).max(0.0);
        if across * across + along * along < reach * reach {
            *best = best.min(corner_distance(p, x, body_x, hint));
        }
        true
    };
    let (mut ahead, mut behind, mut taken) = (j, prev(j, m), 0);
    while taken < m && measure_y(ahead, &mut best, &mut hints[x_side]) {
        (ahead, taken) = (next(ahead, m), taken + 1);
    }
    while taken < m && measure_y(behind, &mut best, &mut hints[x_side]) {
        (behind, taken) = (prev(behind, m), taken + 1);
    }
    HINTS.set(hints);
    best
}

/// The least and largest of t . p over the part of the convex polygon `x` (corners) lying
/// beyond `line` by at most `level` (which corner `k` does): over its corners there, one arc
/// around k, and the crossings of the edges leaving the arc with the parallel line at `level`.
fn cap_extent(
    line: &SeparatingLine,
    x: &[[f64; 2]],
    k: usize,
    t: [f64; 2],
    level: f64,
) -> (f64, f64) {
    let n = x.len();
    let s = |i: usize| dot(t, x[i]);
    let (mut lo, mut hi) = (s(k), s(k));
    for step in [1, n - 1] {
        let (mut i, mut bi) = (k, line.beyond(x[k]));
        for _ in 1..n {
            let j = wrap(i + step, n);
            let bj = line.beyond(x[j]);
            let sj = if bj <= level {
                s(j)
            } else {
                // Where the edge leaves the cap.
                s(i) + (level - bi) / (bj - bi) * (s(j) - s(i))
            };
            (lo, hi) = (lo.min(sj), hi.max(sj));
            if bj > level {
                break;
            }
            (i, bi) = (j, bj);
        }
    }
    (lo, hi)
}
