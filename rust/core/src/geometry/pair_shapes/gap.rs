//! The distance between the bodies of a pair with corners where they do not overlap (the gap
//! of docs/model.md 17.8, which the flights between contacts jump over), and whether two
//! polygons overlap at all.

use super::{cross, dot, sub};
use crate::geometry::convex_clip::{wrap, ClipVertex};
use crate::geometry::convex_window::{clip_windowed, PlacedPolygon, WindowScratch};
use across::{gap_across, separating_line};
use std::cell::{Cell, RefCell};

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
    // The corner after j without an integer division (a third of this scan's time).
    let next = |j: usize| if j + 1 == n { 0 } else { j + 1 };
    let side = |j: usize| cross(sub(b[next(j)], b[j]), sub(p, b[j])) <= 0.0;
    let (mut best, mut outside) = (f64::INFINITY, false);
    let (mut before, mut here) = (side(n - 1), side(0));
    for j in 0..n {
        let after = side(next(j));
        if here {
            outside |= cross(sub(b[next(j)], b[j]), sub(p, b[j])) < 0.0;
        }
        if before || here || after {
            best = best.min(segment_distance2(p, b[j], b[next(j)]));
        }
        (before, here) = (here, after);
    }
    if outside {
        best.sqrt()
    } else {
        0.0
    }
}

/// [`distance_from_corner`] where the polygon `b` has many corners: read from the edges near
/// the corner `p` where that gives the same value bit for bit ([`near_edges_distance`]), else
/// from every edge facing it. `body` is `b` as placed (its body frame), `hint` where the search
/// of its corner farthest along p started last.
fn corner_distance(p: [f64; 2], b: &[[f64; 2]], body: &PlacedPolygon, hint: &mut usize) -> f64 {
    if b.len() > FEW_EDGES {
        if let Some(d) = near_edges_distance(p, b, body, hint) {
            return d;
        }
    }
    distance_from_corner(p, b)
}

/// Polygons of at most this many corners are measured edge by edge ([`distance_from_corner`]):
/// the search of [`near_edges_distance`] costs more than it spares.
const FEW_EDGES: usize = 32;

/// The distance from the corner `p`, outside the placed polygon `b` (`body`), to it, measured
/// on the edges whose polar angles about b's centroid lie near p's only, where that is the
/// value of every edge's ([`distance_to_polygon`]) bit for bit; `None` where no edge of the
/// window has p outside its line (p inside b, or on its boundary to round-off).
///
/// The window grows from b's corner farthest along p, edge by edge both ways. Every point of
/// b whose polar angle differs from p's (w = p - centroid, in b's frame) by at least beta lies
/// within b's circumradius R of the centroid, so at least sqrt(|w|^2 + R^2 - 2 |w| R cos(beta))
/// from p where |w| cos(beta) >= R, else |w| sin(beta) (|w| past a right angle). Once the
/// corners where the window stops, one each side of w's direction, bound the edges beyond them
/// by more than the window's least squared distance (by a factor 1 + [`DISTANCE_MARGIN`] and
/// the round-off of the placed corners, of w and of the bound), none of those edges is nearer
/// and their computed distances are larger: the least over the window is the least over every
/// edge. A 1024-gon's corner far from the body measured every edge (a pentagon flying about a
/// 1024-gon fifty times smaller spent two thirds of its impact there).
fn near_edges_distance(
    p: [f64; 2],
    b: &[[f64; 2]],
    body: &PlacedPolygon,
    hint: &mut usize,
) -> Option<f64> {
    let n = b.len();
    let poly = body.polygon();
    let corners = poly.vertices();
    let w = body.in_body(sub(p, body.centre()));
    let w2 = dot(w, w);
    let k = poly.lowest_vertex_near(*hint, -w[0], -w[1]);
    *hint = k;
    let next = |j: usize| if j + 1 == n { 0 } else { j + 1 };
    let prev = |j: usize| if j == 0 { n - 1 } else { j - 1 };
    // Edge j's squared distance and whether p lies outside its line, as every edge's scan
    // computes them.
    let measure = |j: usize| {
        let (b0, b1) = (b[j], b[next(j)]);
        let outside = cross(sub(b1, b0), sub(p, b0)) < 0.0;
        (segment_distance2(p, b0, b1), outside)
    };
    // How far corner i lies from w's direction: the turn from w to it (> 0 counter-clockwise)
    // and the bound on the squared distance to every point of b at least that far round.
    let (radius, len_w) = (poly.circumradius(), w2.sqrt());
    let beyond = |i: usize| {
        let v = [corners[i].x, corners[i].y];
        (cross(w, v), angular_bound2(w, len_w, v, radius))
    };
    // The round-off of the squared distances and bounds (the placed corners, w, the bound's
    // cancellations), a few ulps of the coordinates squared with a wide margin.
    let c = body.centre();
    let scale = poly.circumradius() + c[0].abs() + c[1].abs() + p[0].abs() + p[1].abs();
    let slack = 1e-14 * scale * scale;
    let bounds = |bound2: f64, best: f64| bound2 - slack >= best * (1.0 + DISTANCE_MARGIN);
    let (mut best, mut outside) = (f64::INFINITY, false);
    let mut take = |j: usize, best: &mut f64| {
        let (d2, out) = measure(j);
        *best = best.min(d2);
        outside |= out;
    };
    // The edges at corner k, then on each side until a corner past w's direction bounds the
    // rest (or every edge is taken).
    take(prev(k), &mut best);
    take(k, &mut best);
    let mut taken = 2;
    let (mut ahead, mut behind) = (next(k), prev(k));
    while taken < n {
        let (turn, bound2) = beyond(ahead);
        if turn >= 0.0 && bounds(bound2, best) {
            break;
        }
        take(ahead, &mut best);
        ahead = next(ahead);
        taken += 1;
    }
    while taken < n {
        let (turn, bound2) = beyond(behind);
        if turn <= 0.0 && bounds(bound2, best) {
            break;
        }
        behind = prev(behind);
        take(behind, &mut best);
        taken += 1;
    }
    outside.then(|| best.sqrt())
}

/// A lower bound on the squared distance from the point w to every point within `radius` of
/// the origin whose direction differs from w's (|w| = `len_w`) by at least the angle beta that
/// v's direction makes with it: sqrt(|w|^2 + R^2 - 2 |w| R cos(beta)) where |w| cos(beta) >= R
/// (the nearest such point on the circle), else |w| sin(beta) (on the ray at beta), and |w|
/// past a right angle.
fn angular_bound2(w: [f64; 2], len_w: f64, v: [f64; 2], radius: f64) -> f64 {
    let along = dot(w, v);
    if along <= 0.0 {
        return dot(w, w);
    }
    let reach = along / dot(v, v).sqrt();
    if reach >= radius {
        let gap = len_w - radius;
        gap * gap + 2.0 * radius * (len_w - reach)
    } else {
        let turn = cross(w, v);
        turn * turn / dot(v, v)
    }
}

/// The relative margin on squared distances by which the edges beyond the window of
/// [`near_edges_distance`] must be farther (beside the absolute one of the round-off): far
/// above the few ulps of the formulas, far below a window's growth.
const DISTANCE_MARGIN: f64 = 1e-9;

/// Whether the placed convex polygons `a` (centred at `q`) and `b` overlap: the windowed clip,
/// whose answer is the O(n + m) clip's (`convex_window.rs`).
pub(super) fn polygons_overlap(a: &PlacedPolygon, b: &PlacedPolygon, q: [f64; 2]) -> bool {
    thread_local! {
        static BUF: RefCell<(Vec<ClipVertex>, WindowScratch)> = RefCell::default();
    }
    BUF.with(|cell| {
        let (out, scratch) = &mut *cell.borrow_mut();
        clip_windowed(a, b, q, out, scratch)
    })
}

/// Whether one polygon's corners (placed, and the body) all lie outside the line of an edge
/// of the other by more than the round-off of the clip's arithmetic: then the two are apart,
/// and the clip finds them so (every vertex it keeps lies within its round-off of both bodies).
/// The corners tried are those of the polygon with fewer: few against the line of the other's
/// edges facing their corner nearest its centroid, each read ([`outside_a_line`]); many all
/// at once, by their least corner along the line facing its centre
/// ([`corners_outside_a_line`]), and no other line (each corner read against the first line
/// certified 7 more of 1516 random placements apart, and cost two 120-gons 1.2 % of their
/// impact: the clip tells those apart). `false` where that does not show it.
pub(super) fn separated(
    (a, body_a): (&[[f64; 2]], &PlacedPolygon),
    (b, body_b): (&[[f64; 2]], &PlacedPolygon),
) -> bool {
    // The polygon of fewer corners against a line of the other: a few operations (the other
    // way round, a 1024-gon's every corner, cost more than the clip it spares).
    if a.len() <= b.len() {
        corners_outside_a_line(a, body_a, body_b)
            || (a.len() <= FEW_EDGES && outside_a_line(a, body_b))
    } else {
        corners_outside_a_line(b, body_b, body_a)
            || (b.len() <= FEW_EDGES && outside_a_line(b, body_a))
    }
}

/// Whether the corners `a` of `body_a` (placed, in order) lie outside the line of `body`'s
/// edges facing its centre by more than twice [`outside_a_line`]'s margin, read at a's corner
/// least along the line's normal alone: then every corner of `body_a` lies outside that line
/// by more than that margin, and the clip finds the two apart (any line of one body's edges
/// with the other's corners outside it by the margin shows it, not only the one
/// `outside_a_line` tries). Two searches along the boundaries, where `outside_a_line` reads
/// every corner twice (two 120-gons apart spent 5-7 % of their impact there).
///
/// Why twice: the least corner is found in a's frame; placed and measured in the world's,
/// every corner's distance beyond the line is at least its distance less the round-off of
/// the placing and turning (~1e-15 of the coordinates), and the margin `outside_a_line` asks
/// of a corner p, SEPARATION (scale + |p_x| + |p_y|), is at most SEPARATION (scale +
/// |c_a,x| + |c_a,y| + 2 r) (r: a's circumradius): the second margin covers that round-off a
/// thousand times over.
fn corners_outside_a_line(a: &[[f64; 2]], body_a: &PlacedPolygon, body: &PlacedPolygon) -> bool {
    let poly_a = body_a.polygon();
    // Few corners are read faster than the facing edge is searched for the centre (two
    // 12-gons ran 0.5 % more instructions with it).
    if a.len() <= FEW_EDGES || a.len() != poly_a.vertices().len() {
        return false;
    }
    let (c, ca) = (body.centre(), body_a.centre());
    let [nx, ny, h] = facing_edge_line(body, ca, 0);
    let n = body.in_world([nx, ny]);
    let along = body_a.in_body(n);
    let least = a[poly_a.lowest_vertex_near(0, along[0], along[1])];
    let beyond = n[0] * (least[0] - c[0]) + n[1] * (least[1] - c[1]) - h;
    let scale = body.polygon().circumradius() + c[0].abs() + c[1].abs();
    let reach = ca[0].abs() + ca[1].abs() + 2.0 * poly_a.circumradius();
    beyond > 2.0 * SEPARATION * (scale + reach)
}

/// The gap of the placed polygons `a` and `b` (corners, body) where a line of one body's
/// edges has the other wholly outside it ([`separated`]), else `None`: `ShapePair::gap`'s
/// value bit for bit, without its clip. Then the clip finds no overlap either (the line's
/// margin exceeds the clip's round-off; tested on random convex pairs,
/// `a_separating_line_is_one_the_clip_agrees_with`), so there is no patch to look for, and
/// the corners' least distance is the gap, as `gap` takes it.
pub(super) fn separated_gap(
    (a, body_a): (&[[f64; 2]], &PlacedPolygon),
    (b, body_b): (&[[f64; 2]], &PlacedPolygon),
) -> Option<f64> {
    // The polygon of fewer corners against a line of the other, as `separated` tries them
    // (its search for many corners second: the two are pure, either answer is its answer;
    // the line for few corners only, as there).
    let ((few, body_few), (other, body_other), hint) = if a.len() <= b.len() {
        ((a, body_a), (b, body_b), 1)
    } else {
        ((b, body_b), (a, body_a), 0)
    };
    if let Some(line) = (few.len() <= FEW_EDGES)
        .then(|| separating_line(few, body_other))
        .flatten()
    {
        return Some(gap_across(
            &line,
            (few, body_few),
            (other, body_other),
            hint,
        ));
    }
    if !corners_outside_a_line(few, body_few, body_other) {
        return None;
    }
    // The two distances in `gap`'s order: each moves its body's search hint.
    let to_b = vertices_distance((a, body_a), (b, body_b), 1);
    let to_a = vertices_distance((b, body_b), (a, body_a), 0);
    Some(to_b.min(to_a))
}

/// Whether every corner of `a` lies outside one line of `body`'s edges, by a margin
/// ([`separated`], [`separating_line`]).
fn outside_a_line(a: &[[f64; 2]], body: &PlacedPolygon) -> bool {
    separating_line(a, body).is_some()
}

/// The line of `body`'s edges (body frame: unit outward normal and offset) that the point `p`
/// lies farthest outside of, or near it: from the edges at the corner farthest along p (its
/// search started at corner `near`), along the boundary while the lines lie farther inside
/// of p.
fn facing_edge_line(body: &PlacedPolygon, p: [f64; 2], near: usize) -> [f64; 3] {
    let poly = body.polygon();
    let lines = &poly.edge_lines;
    let m = lines.len();
    let w = body.in_body(sub(p, body.centre()));
    let beyond = |j: usize| lines[j][0] * w[0] + lines[j][1] * w[1] - lines[j][2];
    let k = poly.lowest_vertex_near(near, -w[0], -w[1]);
    let mut j = if beyond(k) >= beyond(wrap(k + m - 1, m)) {
        k
    } else {
        wrap(k + m - 1, m)
    };
    for _ in 0..m {
        let (next, prev) = (wrap(j + 1, m), wrap(j + m - 1, m));
        if beyond(next) > beyond(j) {
            j = next;
        } else if beyond(prev) > beyond(j) {
            j = prev;
        } else {
            break;
        }
    }
    lines[j]
}

/// The margin, relative to the coordinates, by which [`separated`] wants every corner outside
/// the line: far above the few ulps of the placed corners and of the clip's side tests.
const SEPARATION: f64 = 1e-12;

thread_local! {
    /// Where the last searches of the gap's corners ended: of each body's corner farthest
    /// along a corner of the other (the particle's, the partner's), then of each body's corner
    /// least along the other's facing edge (the same order). The flights measure the gap at
    /// nearby places.
    static HINTS: Cell<[usize; 4]> = const { Cell::new([0; 4]) };
}

/// The smallest distance from a corner of the polygon `a` to the polygon `b` (each as its
/// placed corners, in the body's order, and the body; `side` names b: 0 the particle, 1 the
/// partner), both convex: the least of their [`corner_distance`]s, measuring only the corners
/// that can be nearest. Few corners are read all at once ([`few_corners_distance`]), many
/// from the one nearest b along its boundary ([`walked_corners_distance`]).
pub(super) fn vertices_distance(
    (a, body_a): (&[[f64; 2]], &PlacedPolygon),
    (b, body_b): (&[[f64; 2]], &PlacedPolygon),
    side: usize,
) -> f64 {
    debug_assert_eq!(
        a.len(),
        body_a.polygon().vertices().len(),
        "a's corners, placed"
    );
    let mut hints = HINTS.get();
    let best = if a.len() > FEW_EDGES {
        walked_corners_distance((a, body_a), (b, body_b), &mut hints, side)
    } else {
        few_corners_distance(a, (b, body_b), &mut hints[side])
    };
    HINTS.set(hints);
    best
}

/// [`vertices_distance`] from the corners of `a` near `b` alone, the least of every corner's
/// bit for bit. b lies inside the line of each of its edges, so a corner's distance beyond one
/// is a lower bound on its distance to b: the line of b's edge facing a's corner least along
/// the centres' line ([`facing_edge_line`]). Along a's boundary the corners' distance beyond
/// that line falls to its least and rises once (a is convex), so from a's corner least along
/// it the corners are measured both ways until one lies beyond the line by more than the least
/// distance so far (less the round-off of the bound and of the distances): every corner past
/// it lies farther beyond, its distance exceeds that least, which it would leave as it was.
/// Every corner was read before: two 120-gons apart spent 6 % of their impact here.
fn walked_corners_distance(
    (a, body_a): (&[[f64; 2]], &PlacedPolygon),
    (b, body_b): (&[[f64; 2]], &PlacedPolygon),
    hints: &mut [usize; 4],
    side: usize,
) -> f64 {
    let (n, poly_a) = (a.len(), body_a.polygon());
    let (centre, r) = (body_b.centre(), body_b.polygon().circumradius());
    // a's corner least along the centres' line (from b's centre towards a's), and the line of
    // b's edge facing it: its world normal and its offset from b's centre.
    let towards = body_a.in_body(sub(body_a.centre(), centre));
    let first = poly_a.lowest_vertex_near(hints[2 + side], towards[0], towards[1]);
    let [nx, ny, h] = facing_edge_line(body_b, a[first], hints[side]);
    let normal = body_b.in_world([nx, ny]);
    let along = body_a.in_body(normal);
    let k = poly_a.lowest_vertex_near(first, along[0], along[1]);
    hints[2 + side] = k;
    // How far beyond the line a corner certainly lies, less the round-off of the bound and of
    // the distances: a few ulps of the coordinates.
    let beyond = |p: [f64; 2]| {
        let slack = 1e-13 * (r + centre[0].abs() + centre[1].abs() + p[0].abs() + p[1].abs());
        normal[0] * (p[0] - centre[0]) + normal[1] * (p[1] - centre[1]) - h - slack
    };
    let hint = &mut hints[side];
    let mut best = corner_distance(a[k], b, body_b, hint);
    let (next, prev) = (|j: usize| wrap(j + 1, n), |j: usize| wrap(j + n - 1, n));
    let (mut ahead, mut behind, mut taken) = (next(k), prev(k), 1);
    while taken < n && beyond(a[ahead]) < best {
        best = best.min(corner_distance(a[ahead], b, body_b, hint));
        (ahead, taken) = (next(ahead), taken + 1);
    }
    while taken < n && beyond(a[behind]) < best {
        best = best.min(corner_distance(a[behind], b, body_b, hint));
        (behind, taken) = (prev(behind), taken + 1);
    }
    best
}

/// [`vertices_distance`] for few corners of `a`, each read: corners farther from b's centre
/// than its circumradius plus the best distance so far cannot be nearer, so only the few
/// facing b are measured against its edges (a search for the nearest, as
/// [`walked_corners_distance`] does, cost two 12-gons more than it spared: two corners are
/// measured either way, edge to edge).
fn few_corners_distance(
    a: &[[f64; 2]],
    (b, body): (&[[f64; 2]], &PlacedPolygon),
    hint: &mut usize,
) -> f64 {
    let (centre, r) = (body.centre(), body.polygon().circumradius());
    let dist2 = |p: [f64; 2]| {
        let d = sub(p, centre);
        dot(d, d)
    };
    let reach = |p: [f64; 2]| dist2(p).sqrt() - r;
    // The vertex of least reach, the first of equals: among those of least squared distance
    // (a relative 1e-9 apart in it, their reaches differ), without a square root for each.
    let least2 = a.iter().fold(f64::INFINITY, |m, &p| {
        let d2 = dist2(p);
        if d2 < m {
            d2
        } else {
            m
        }
    });
    let by_reach = |x: &[f64; 2], y: &[f64; 2]| reach(*x).total_cmp(&reach(*y));
    let near = a
        .iter()
        .copied()
        .filter(|&p| dist2(p) <= least2 * (1.0 + 1e-9));
    let Some(first) = near
        .min_by(by_reach)
        .or_else(|| a.iter().copied().min_by(by_reach))
    else {
        return f64::INFINITY;
    };
    let mut best = corner_distance(first, b, body, hint);
    for &p in a {
        // Farther than (best + r) by a relative 1e-12 in the squared distance, the reach is
        // certainly at least best (the test below would fail): no square root.
        let far = best + r;
        if dist2(p) > far * far * (1.0 + 1e-12) {
            continue;
        }
        if reach(p) < best {
            best = best.min(corner_distance(p, b, body, hint));
        }
    }
    best
}

mod across;
#[cfg(test)]
mod tests;
