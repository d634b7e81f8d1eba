//! The intersection of two convex polygons in O(n + m) (docs/model.md, section 17.8): polygon
//! A clipped by the half-planes of polygon B's edges (Sutherland-Hodgman), starting from the
//! edge whose line A's centre lies farthest outside, so that the first clip leaves only the few
//! corners of A near the contact and every later clip costs a few operations. Each vertex of
//! the result remembers the two lines it lies on (an edge of A or of B), so that its position is
//! taken exactly (a corner of A, a corner of B, or where an edge of A crosses an edge of B) and
//! the crossings of the two boundaries, with the edges they lie on, are known: the contact's
//! chord and the potential's derivatives read them (`pair_shapes/potential.rs`).

/// A convex polygon's corners, counter-clockwise, read by index: placed vertices in a slice,
/// or a body's corners placed only when read (`convex_window::PlacedPolygon`), so that a clip
/// that visits a few corners places only those.
pub trait Ring {
    /// The number of corners.
    fn count(&self) -> usize;
    /// Whether [`Ring::clears`] can tell an edge clear (then the clip skips its own, placed,
    /// test of the bounding circle, which would almost never tell more).
    const KNOWS_LINES: bool = false;
    /// Corner `i` (0 <= i < count), placed.
    fn corner(&self, i: usize) -> [f64; 2];
    /// Whether the line of edge `j` certainly has the disc of radius `reach` about `centre`
    /// inside, beyond the round-off of its placed corners, told without placing them; `false`
    /// where that is not known (the clip then tests the edge as placed).
    #[inline(always)]
    fn clears(&self, _j: u32, _centre: [f64; 2], _reach: f64) -> bool {
        false
    }
}

impl Ring for [[f64; 2]] {
    #[inline(always)]
    fn count(&self) -> usize {
        self.len()
    }
    #[inline(always)]
    fn corner(&self, i: usize) -> [f64; 2] {
        self[i]
    }
}

/// The line of one polygon's edge: edge i runs from vertex i to vertex i + 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeLine {
    /// An edge of polygon A (the clipped one).
    A(u32),
    /// An edge of polygon B (the clipping one).
    B(u32),
}

/// A vertex of the intersection, between the lines of the edge before it and the edge after
/// it (counter-clockwise).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipVertex {
    /// Its position.
    pub p: [f64; 2],
    /// The line of the intersection's edge arriving at it.
    pub before: EdgeLine,
    /// The line of the intersection's edge leaving it.
    pub after: EdgeLine,
}

impl ClipVertex {
    /// Where the two boundaries cross: the edge of A and the edge of B it lies on.
    pub fn crossing(&self) -> Option<(u32, u32)> {
        match (self.before, self.after) {
            (EdgeLine::A(i), EdgeLine::B(j)) | (EdgeLine::B(j), EdgeLine::A(i)) => Some((i, j)),
            _ => None,
        }
    }
}

/// `i` modulo `m` for `i < 2 m`, without an integer division (tens of cycles each in the
/// window's and the clip's index arithmetic).
#[inline(always)]
pub(crate) fn wrap(i: usize, m: usize) -> usize {
    if i >= m {
        i - m
    } else {
        i
    }
}

/// 2D cross product.
#[inline(always)]
pub(crate) fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

#[inline(always)]
pub(crate) fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// Where the edge `a0`-`a1` crosses the line through `b0`, `b1`, interpolated from the
/// endpoint nearer that line (the other's error is then scaled down); `fallback` for parallel
/// lines.
#[inline]
pub fn edge_crossing(
    [a0, a1]: [[f64; 2]; 2],
    [b0, b1]: [[f64; 2]; 2],
    fallback: [f64; 2],
) -> [f64; 2] {
    let e = sub(b1, b0);
    let (o0, o1) = (cross(e, sub(a0, b0)), cross(e, sub(a1, b0)));
    if o0 == o1 {
        return fallback;
    }
    let (near, far, on, of) = if o0.abs() <= o1.abs() {
        (a0, a1, o0, o1)
    } else {
        (a1, a0, o1, o0)
    };
    let t = on / (on - of);
    [
        near[0] + t * (far[0] - near[0]),
        near[1] + t * (far[1] - near[1]),
    ]
}

/// The edge `k` of the counter-clockwise polygon `v` as its two ends.
#[inline(always)]
pub(crate) fn edge<R: Ring + ?Sized>(v: &R, k: u32) -> [[f64; 2]; 2] {
    let k = k as usize;
    let next = if k + 1 == v.count() { 0 } else { k + 1 };
    [v.corner(k), v.corner(next)]
}

/// Clips `out` (a convex polygon) by the inner half-plane of B's edge `j` into `next`;
/// `false` when every vertex lies inside (nothing to do: `next` untouched). With `bound`,
/// first the polygon's bounding circle against the edge's line.
#[inline(always)]
pub(crate) fn clip_by_edge(
    out: &[ClipVertex],
    next: &mut Vec<ClipVertex>,
    bj: [[f64; 2]; 2],
    j: u32,
    bound: Option<Bound>,
) -> bool {
    let e = sub(bj[1], bj[0]);
    let side = |p: [f64; 2]| cross(e, sub(p, bj[0]));
    // The polygon's bounding circle inside the half-plane: nothing to clip (one test for
    // the many edges far from the contact).
    if let Some(bound) = bound {
        let c = side(bound.centre);
        if c >= 0.0 && c * c >= bound.radius2 * (e[0] * e[0] + e[1] * e[1]) {
            return false;
        }
    }
    if out.iter().all(|v| side(v.p) >= 0.0) {
        return false;
    }
    next.clear();
    let k = out.len();
    let mut prev = out[k - 1];
    let mut s_prev = side(prev.p);
    for &v in out {
        let s = side(v.p);
        if (s_prev >= 0.0) != (s >= 0.0) {
            // The edge prev -> v lies on prev.after; it crosses B's line j at t.
            let t = s_prev / (s_prev - s);
            let p = [
                prev.p[0] + t * (v.p[0] - prev.p[0]),
                prev.p[1] + t * (v.p[1] - prev.p[1]),
            ];
            let (before, after) = if s_prev >= 0.0 {
                (prev.after, EdgeLine::B(j))
            } else {
                (EdgeLine::B(j), prev.after)
            };
            next.push(ClipVertex { p, before, after });
        }
        if s >= 0.0 {
            next.push(v);
        }
        prev = v;
        s_prev = s;
    }
    true
}

/// A circle around a polygon: its vertices' mean and the largest squared distance from it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Bound {
    pub(crate) centre: [f64; 2],
    pub(crate) radius2: f64,
    /// The square root of `radius2`.
    pub(crate) radius: f64,
}

impl Bound {
    pub(crate) fn of(v: &[ClipVertex]) -> Self {
        let k = v.len() as f64;
        let (sx, sy) = v
            .iter()
            .fold((0.0, 0.0), |(x, y), w| (x + w.p[0], y + w.p[1]));
        let centre = [sx / k, sy / k];
        // A plain comparison: f64::max's NaN handling doubled this loop's instructions (the
        // same result on these finite values).
        let radius2 = v.iter().fold(0.0f64, |r, w| {
            let d = sub(w.p, centre);
            let d2 = d[0] * d[0] + d[1] * d[1];
            if d2 > r {
                d2
            } else {
                r
            }
        });
        // A hair more, so that round-off never skips a clip that cuts.
        let radius2 = radius2 * (1.0 + 1e-9);
        Bound {
            centre,
            radius2,
            radius: radius2.sqrt(),
        }
    }
}

/// The edge of B (counter-clockwise vertices `b`, centred near the origin) that faces the
/// point `q`: of the two edges at B's farthest vertex along q, the one whose outward normal is
/// nearer q's direction. The clip starts there, so that its first cut leaves only A's corners
/// near the contact.
fn facing_edge<R: Ring + ?Sized>(b: &R, q: [f64; 2]) -> usize {
    let mut k = 0;
    let mut best = f64::NEG_INFINITY;
    for i in 0..b.count() {
        let s = along_q(b.corner(i), q);
        if s > best {
            best = s;
            k = i;
        }
    }
    facing_edge_at(b, k, q)
}

/// How far corner `v` lies along `q` (the measure [`facing_edge`] maximises).
#[inline(always)]
pub(crate) fn along_q(v: [f64; 2], q: [f64; 2]) -> f64 {
    v[0] * q[0] + v[1] * q[1]
}

/// Of the two edges at B's corner `k` (the farthest along q), the one whose outward normal is
/// nearer q's direction.
pub(crate) fn facing_edge_at<R: Ring + ?Sized>(b: &R, k: usize, q: [f64; 2]) -> usize {
    let m = b.count();
    let around = [
        b.corner(wrap(k + m - 1, m)),
        b.corner(k),
        b.corner(wrap(k + 1, m)),
    ];
    facing_edge_between(m, k, around, q)
}

/// [`facing_edge_at`] from the corners before B's corner `k`, at it and after it, placed (`m`
/// corners in all).
pub(crate) fn facing_edge_between(
    m: usize,
    k: usize,
    [c_prev, c_k, c_next]: [[f64; 2]; 3],
    q: [f64; 2],
) -> usize {
    let prev = wrap(k + m - 1, m);
    // The outward normal (e_y, -e_x) against q, and the edge's squared length.
    let parts = |[b0, b1]: [[f64; 2]; 2]| {
        let e = sub(b1, b0);
        (e[1] * q[0] - e[0] * q[1], e[0] * e[0] + e[1] * e[1])
    };
    let ((a_prev, l_prev), (a_k, l_k)) = (parts([c_prev, c_k]), parts([c_k, c_next]));
    // Both facing q (at the farthest corner, almost always): the quotients per unit length in
    // the order of a^2 times the other edge's l, without the square roots and divisions (a
    // twentieth of the window's time), unless within round-off of a tie (a relative 1e-12,
    // where the quotients below decide as before).
    if a_prev > 0.0 && a_k > 0.0 {
        let (x, y) = (a_prev * a_prev * l_k, a_k * a_k * l_prev);
        if x > y * (1.0 + TIE) {
            return prev;
        }
        if y > x * (1.0 + TIE) {
            return k;
        }
    }
    if a_prev / l_prev.sqrt() > a_k / l_k.sqrt() {
        prev
    } else {
        k
    }
}

/// The relative difference of the squared quotients within which [`facing_edge_at`] compares
/// the quotients themselves: far above the few ulps either carries.
const TIE: f64 = 1e-12;

/// The intersection of the counter-clockwise convex polygons `a` (centred near `q`) and `b`
/// into `out` (`next` is scratch space); `false` when they do not overlap. Each vertex's
/// position is taken from the lines it lies on: a corner of A or B exactly, a crossing by
/// [`edge_crossing`].
pub fn clip_convex<R: Ring + ?Sized>(
    a: &R,
    b: &R,
    q: [f64; 2],
    out: &mut Vec<ClipVertex>,
    next: &mut Vec<ClipVertex>,
) -> bool {
    let m = b.count();
    let j0 = facing_edge(b, q);
    first_clip(a, edge(b, j0 as u32), j0 as u32, out);
    if out.len() < 3 {
        return false;
    }
    let rest = (1..m).map(|k| wrap(j0 + k, m) as u32);
    clip_through(a, b, rest, (out, next), true)
}

/// Clips the first clip `out` by B's edges `edges` in turn (`next` is scratch space), then
/// sets each vertex at its exact position; `false` where the overlap vanishes. The full clip
/// and the windowed one (`convex_window.rs`) go on from their first clip by this one loop.
/// With `bounded`, each edge's line is first held against the polygon's bounding circle (many
/// edges far from the contact); without, every edge is tested vertex by vertex (edges chosen
/// because they may cut: the circle would pass few of them by, at the cost of its update).
pub(crate) fn clip_through<R: Ring + ?Sized>(
    a: &R,
    b: &R,
    edges: impl Iterator<Item = u32>,
    (out, next): (&mut Vec<ClipVertex>, &mut Vec<ClipVertex>),
    bounded: bool,
) -> bool {
    let mut bound = bounded.then(|| Bound::of(out));
    // The end of the last edge placed, the start of the next where the edges run on.
    let mut end: Option<(u32, [f64; 2])> = None;
    for j in edges {
        // An edge whose line is far from the clip changes nothing: told from its body-frame
        // line where the ring knows it, without placing its corners.
        if let Some(c) = bound.filter(|_| R::KNOWS_LINES) {
            if b.clears(j, c.centre, c.radius) {
                continue;
            }
        }
        let placed_bound = bound.filter(|_| !R::KNOWS_LINES);
        let bj = if R::KNOWS_LINES {
            // Placed as read (a slice's corners are read in place).
            let after = wrap(j as usize + 1, b.count()) as u32;
            let start = match end {
                Some((k, p)) if k == j => p,
                _ => b.corner(j as usize),
            };
            let bj = [start, b.corner(after as usize)];
            end = Some((after, bj[1]));
            bj
        } else {
            edge(b, j)
        };
        if clip_by_edge(out, next, bj, j, placed_bound) {
            std::mem::swap(out, next);
            if out.len() < 3 {
                out.clear();
                return false;
            }
            if bounded {
                bound = Some(Bound::of(out));
            }
        }
    }
    set_exact_positions(out, a, b);
    true
}

/// Each vertex of the intersection `out` of `a` and `b` at its exact position
/// ([`exact_position`]). A corner of A is already there: the clips copy A's corners as read
/// (`first_clip_run`) and never move a vertex they keep, so it is not placed again.
pub(crate) fn set_exact_positions<R: Ring + ?Sized>(out: &mut [ClipVertex], a: &R, b: &R) {
    for v in out.iter_mut() {
        if let (EdgeLine::A(_), EdgeLine::A(_)) = (v.before, v.after) {
            continue;
        }
        v.p = exact_position(v, a, b);
    }
}

/// A clipped by the inner half-plane of B's edge `j` into `out`, A's corners read in place
/// (the first clip, where A is whole: no copy of it is made).
fn first_clip<R: Ring + ?Sized>(a: &R, bj: [[f64; 2]; 2], j: u32, out: &mut Vec<ClipVertex>) {
    out.clear();
    let n = a.count();
    first_clip_run(a, bj, j, n - 1, 0..n, out);
}

/// The first clip's vertices for A's corners `run` (consecutive, `prev` the corner before the
/// first), pushed onto `out` in that order: each corner inside B's edge line `j`, and where the
/// edge arriving at a corner crosses that line, the crossing before it. Over every corner from
/// 0 it is the whole first clip; over a run that starts and ends outside, the whole clip too,
/// in another cyclic order (`convex_window.rs`).
pub(crate) fn first_clip_run<R: Ring + ?Sized>(
    a: &R,
    bj: [[f64; 2]; 2],
    j: u32,
    prev: usize,
    run: impl Iterator<Item = usize>,
    out: &mut Vec<ClipVertex>,
) {
    let e = sub(bj[1], bj[0]);
    let side = |p: [f64; 2]| cross(e, sub(p, bj[0]));
    let a_prev = a.corner(prev);
    let mut last = (prev, a_prev, side(a_prev));
    for i in run {
        let ai = a.corner(i);
        let this = (i, ai, side(ai));
        push_first_clip(last, this, j, out);
        last = this;
    }
}

/// A corner of A as the first clip reads it: its index, its placed position, and its side of
/// B's line (>= 0 inside).
pub(crate) type Sided = (usize, [f64; 2], f64);

/// The first clip's vertices for A's corner `this` after corner `prev` onto `out`: where A's
/// edge between them crosses B's line `j`, the crossing; then the corner if inside.
#[inline(always)]
pub(crate) fn push_first_clip(
    (prev, a_prev, s_prev): Sided,
    (i, ai, s): Sided,
    j: u32,
    out: &mut Vec<ClipVertex>,
) {
    if (s_prev >= 0.0) != (s >= 0.0) {
        // The edge prev -> i (A's edge `prev`) crosses B's line j.
        let t = s_prev / (s_prev - s);
        let p = [
            a_prev[0] + t * (ai[0] - a_prev[0]),
            a_prev[1] + t * (ai[1] - a_prev[1]),
        ];
        let (before, after) = if s_prev >= 0.0 {
            (EdgeLine::A(prev as u32), EdgeLine::B(j))
        } else {
            (EdgeLine::B(j), EdgeLine::A(prev as u32))
        };
        out.push(ClipVertex { p, before, after });
    }
    if s >= 0.0 {
        out.push(ClipVertex {
            p: ai,
            before: EdgeLine::A(prev as u32),
            after: EdgeLine::A(i as u32),
        });
    }
}

/// A vertex's position from the two lines it lies on: a corner where both are one polygon's
/// consecutive edges, a crossing where they are one of each.
fn exact_position<R: Ring + ?Sized>(v: &ClipVertex, a: &R, b: &R) -> [f64; 2] {
    let next = |k: u32, len: usize| wrap(k as usize + 1, len);
    match (v.before, v.after) {
        (EdgeLine::A(i), EdgeLine::A(k)) if k as usize == next(i, a.count()) => {
            a.corner(k as usize)
        }
        (EdgeLine::B(j), EdgeLine::B(k)) if k as usize == next(j, b.count()) => {
            b.corner(k as usize)
        }
        (EdgeLine::A(i), EdgeLine::B(j)) | (EdgeLine::B(j), EdgeLine::A(i)) => {
            edge_crossing(edge(a, i), edge(b, j), v.p)
        }
        _ => v.p,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn regular(r: f64, n: usize, phi: f64, at: [f64; 2]) -> Vec<[f64; 2]> {
        (0..n)
            .map(|k| {
                let a = phi + 2.0 * std::f64::consts::PI * k as f64 / n as f64;
                [at[0] + r * a.cos(), at[1] + r * a.sin()]
            })
            .collect()
    }

    fn shoelace(v: &[ClipVertex]) -> f64 {
        let k = v.len();
        (0..k).map(|i| 0.5 * cross(v[i].p, v[(i + 1) % k].p)).sum()
    }

    /// The facing edge without square roots is the one the quotients per unit length pick:
    /// random polygons of 3 to 1024 corners, directions at random and within 1e-16 to 1e-6 of
    /// the bisector of the corner's two edges (the ties).
    #[test]
    fn the_facing_edge_is_the_quotients_pick() {
        let mut seeded = crate::numerics::seeded::Seeded(13);
        let mut rnd = || seeded.uniform();
        let quotients = |b: &[[f64; 2]], k: usize, q: [f64; 2]| {
            let m = b.len();
            let prev = (k + m - 1) % m;
            let along = |j: usize| {
                let [b0, b1] = edge(b, j as u32);
                let e = sub(b1, b0);
                (e[1] * q[0] - e[0] * q[1]) / (e[0] * e[0] + e[1] * e[1]).sqrt()
            };
            if along(prev) > along(k) {
                prev
            } else {
                k
            }
        };
        let mut near_ties = 0;
        for case in 0..4000 {
            let n = [3usize, 5, 12, 120, 1024][case % 5];
            let b = regular(0.5 + rnd(), n, rnd() * 6.3, [rnd() - 0.5, rnd() - 0.5]);
            let k = (rnd() * n as f64) as usize % n;
            let [p, c, x] = [b[(k + n - 1) % n], b[k], b[(k + 1) % n]];
            let unit = |v: [f64; 2]| {
                let l = v[0].hypot(v[1]);
                [v[0] / l, v[1] / l]
            };
            // The outward normals of the two edges at corner k, and their bisector.
            let (u1, u2) = (
                unit([c[1] - p[1], p[0] - c[0]]),
                unit([x[1] - c[1], c[0] - x[0]]),
            );
            let q = if case % 2 == 0 {
                let t = 10f64.powf(-16.0 + 10.0 * rnd()) * (rnd() - 0.5);
                near_ties += 1;
                [u1[0] + u2[0] - t * u1[1], u1[1] + u2[1] + t * u1[0]]
            } else {
                let a = rnd() * 6.3;
                [a.cos(), a.sin()]
            };
            assert_eq!(
                facing_edge_at(&b[..], k, q),
                quotients(&b, k, q),
                "case {case}"
            );
        }
        assert!(near_ties > 1000);
    }

    /// Against parry's general intersection (the plate's obstacle path), over random regular
    /// polygons at random placements: the same area, two crossings in a shallow contact, each on
    /// both boundaries.
    #[test]
    fn agrees_with_parry_and_marks_the_crossings() {
        let mut seeded = crate::numerics::seeded::Seeded(7);
        let mut rnd = || seeded.uniform();
        let (mut out, mut next) = (Vec::new(), Vec::new());
        let mut overlapping = 0;
        for _ in 0..2000 {
            let (n, m) = (3 + (rnd() * 40.0) as usize, 3 + (rnd() * 40.0) as usize);
            let (r1, r2) = (0.5 + rnd(), 0.5 + rnd());
            let ang = rnd() * 6.3;
            let d = (r1 + r2) * (0.6 + 0.45 * rnd());
            let q = [d * ang.cos(), d * ang.sin()];
            let a = regular(r1, n, rnd() * 6.3, q);
            let b = regular(r2, m, rnd() * 6.3, [0.0, 0.0]);
            let ours = clip_convex(&a[..], &b[..], q, &mut out, &mut next);
            let theirs = crate::geometry::parry::polygon_pair_overlap(
                a.iter().copied(),
                b.iter().copied(),
                r1 + r2,
                |p, _| p.area,
            );
            match (ours, theirs) {
                (true, Some(area)) => {
                    overlapping += 1;
                    let mine = shoelace(&out);
                    // Round-off: the crossings' coordinates (sizes ~1) to ~1e-16 each.
                    assert!((mine - area).abs() <= 1e-12 * area + 1e-14, "{mine} {area}");
                    let crossings: Vec<_> = out.iter().filter_map(|v| v.crossing()).collect();
                    assert!(crossings.len() >= 2 && crossings.len() % 2 == 0);
                    for v in out.iter().filter(|v| v.crossing().is_some()) {
                        let (i, j) = v.crossing().unwrap();
                        for (poly, k) in [(&a[..], i), (&b[..], j)] {
                            let [p0, p1] = edge(poly, k);
                            let e = sub(p1, p0);
                            let off = cross(e, sub(v.p, p0)) / e[0].hypot(e[1]);
                            assert!(off.abs() < 1e-13, "off its edge by {off:e}");
                        }
                    }
                }
                (false, None) => {}
                (false, Some(area)) => assert!(area < 1e-14, "missed an overlap of {area:e}"),
                (true, None) => assert!(shoelace(&out) < 1e-14),
            }
        }
        assert!(overlapping > 500, "{overlapping}");
    }
}
