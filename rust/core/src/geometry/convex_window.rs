//! The convex clip of `convex_clip.rs` visiting only the corners near the contact
//! (docs/model.md, section 17.8): in a shallow contact a few edges of each body are involved,
//! so the clip places and reads only those, and its result is the full clip's, vertex for
//! vertex and bit for bit.
//!
//! The full clip starts from B's edge facing A's centre (at B's corner farthest along q),
//! clips A by that edge's line, then by each of B's other edges in turn; an edge whose line has
//! every vertex of the clipped polygon inside changes nothing. Here: B's farthest corner and
//! the deepest corner of A below the facing edge's line are found by a climb along the boundary
//! in the full clip's own arithmetic from the last evaluation's corners (the body-frame search
//! of the plate's polygon, `Polygon::lowest_vertex_near`, where that climb would be long), its
//! three placed corners handed on to the facing edge's choice; A's corners inside that line
//! form one run around the deepest (A is convex), walked back to its start, then on through it
//! emitting the first clip (each corner placed once); B's next edge clips that, as in the full
//! clip; and of B's remaining edges only those whose lines some vertex of the polygon it leaves
//! can lie outside of are tested. Every later polygon's vertices lie on segments between its
//! vertices (each clip cuts along a chord); B's inscribed disc about its centroid (radius r_in)
//! lies inside every edge's line, so an edge whose unit outward normal u_j has
//! u_j . (v - centre) <= r_in (less a round-off margin) for every vertex v has every later
//! vertex inside, and the full clip passes it by. For each v the others form one arc of edges
//! around B's corner farthest along v (B's normals turn monotonically); the edges tested are
//! the run spanning all of them around the facing edge. Where an edge of the run so far is
//! surely v's and the edges just past both its ends are not, v's arc lies within it (no
//! search); a walk that reaches the run goes on past its end. Told from the first clip, the
//! run also held the edges its crossing far along the facing edge's line reached, which B's
//! next edge cuts off: two study 120-gons in the benchmark's Gear-5 impact, 6.9 edges tested
//! per evaluation, 3.7 of which cut; now 4.2, 3.7 of which cut (16.5 where the test was the
//! first clip's bounding circle). B's edges are told from their body-frame lines
//! (`Polygon::edge_lines`) without placing their corners, and each tested edge's line is first
//! held against the current polygon's bounding circle the same way (`Ring::clears`). Where the
//! window cannot be trusted (A wholly inside the first line, a corner next to the run within
//! round-off of it), the full clip runs; where B's edges cannot be ruled out (a vertex may lie
//! outside half of B's edges' lines), the clip goes on through every edge of B from the same
//! polygon, as the full one.

use super::convex_clip::{
    along_q, clip_by_edge, clip_convex, clip_through, facing_edge_between, push_first_clip, wrap,
    ClipVertex, Ring,
};
use super::polygon::Polygon;
use crate::numerics::trig::sin_cos;

/// A convex polygon turned and placed, each corner computed when read, as the pairs place
/// their polygons (the same arithmetic, so the same bits).
#[derive(Debug, Clone, Copy)]
pub struct PlacedPolygon<'a> {
    poly: &'a Polygon,
    at: [f64; 2],
    sin: f64,
    cos: f64,
}

impl<'a> PlacedPolygon<'a> {
    /// `poly` turned by `phi` (rad), its centroid at `at`.
    pub fn new(poly: &'a Polygon, at: [f64; 2], phi: f64) -> Self {
        let (sin, cos) = sin_cos(phi);
        PlacedPolygon { poly, at, sin, cos }
    }

    /// A corner at or near the one farthest along the world direction `d`: the body-frame
    /// search from corner `near`.
    fn start_along(&self, d: [f64; 2], near: usize) -> usize {
        // The search finds the lowest corner, the one farthest along -(s, c).
        let w = self.in_body(d);
        self.poly.lowest_vertex_near(near, -w[0], -w[1])
    }

    /// The world vector `d` in the body frame (R^T d).
    #[inline(always)]
    pub(crate) fn in_body(&self, d: [f64; 2]) -> [f64; 2] {
        [
            self.cos * d[0] + self.sin * d[1],
            -self.sin * d[0] + self.cos * d[1],
        ]
    }

    /// The body-frame vector `d` in the world frame (R d).
    #[inline(always)]
    pub(crate) fn in_world(&self, d: [f64; 2]) -> [f64; 2] {
        [
            self.cos * d[0] - self.sin * d[1],
            self.sin * d[0] + self.cos * d[1],
        ]
    }

    /// A bound on the round-off of its placed corners and of a side test against a point
    /// `d` from its centre: a few ulps of the coordinates, with a wide margin.
    #[inline(always)]
    fn round_off(&self, d: [f64; 2]) -> f64 {
        ROUND_OFF
            * (self.poly.circumradius()
                + self.at[0].abs()
                + self.at[1].abs()
                + d[0].abs()
                + d[1].abs())
    }

    /// Whether the disc of radius `delta` about the world point `p` lies inside the polygon:
    /// each edge's body-frame line (`Polygon::edge_lines`) at least `delta` from p. Only the
    /// edges whose lines can come that near are tested: one run around the corner farthest
    /// along p (found from `near`, which is updated), the others' lines lying beyond the
    /// inscribed disc.
    pub(crate) fn holds_disc(&self, p: [f64; 2], delta: f64, near: &mut usize) -> bool {
        let poly = self.poly;
        let lines = &poly.edge_lines;
        let m = lines.len();
        let w = self.in_body([p[0] - self.at[0], p[1] - self.at[1]]);
        let along = |k: usize| lines[k][0] * w[0] + lines[k][1] * w[1];
        // Beyond the inscribed disc's margin an edge's line is certainly far; along the
        // boundary from the farthest corner, n . w falls to its least and rises once.
        let limit = poly.inradius - delta;
        let k0 = poly.lowest_vertex_near(*near, -w[0], -w[1]);
        *near = k0;
        let mut tested = 0;
        for forward in [true, false] {
            let mut k = if forward { k0 } else { wrap(k0 + m - 1, m) };
            loop {
                let a = along(k);
                if a <= limit {
                    break;
                }
                if a > lines[k][2] - delta {
                    return false;
                }
                tested += 1;
                if tested >= m {
                    return true;
                }
                k = if forward {
                    wrap(k + 1, m)
                } else {
                    wrap(k + m - 1, m)
                };
            }
        }
        true
    }

    /// Where its centroid is placed.
    pub fn centre(&self) -> [f64; 2] {
        self.at
    }

    /// The polygon itself.
    pub fn polygon(&self) -> &'a Polygon {
        self.poly
    }
}

impl Ring for PlacedPolygon<'_> {
    const KNOWS_LINES: bool = true;

    #[inline(always)]
    fn count(&self) -> usize {
        self.poly.vertices.len()
    }

    #[inline(always)]
    fn corner(&self, i: usize) -> [f64; 2] {
        let v = &self.poly.vertices[i];
        [
            self.at[0] + self.cos * v.x - self.sin * v.y,
            self.at[1] + self.sin * v.x + self.cos * v.y,
        ]
    }

    /// The disc's centre in the body frame, against the edge's body-frame line (its unit
    /// normal and offset, `Polygon::edge_lines`): clear where the disc lies inside by more
    /// than the round-off of the placed edge and of the clip's side test (so the clip, testing
    /// the placed edge, would find every vertex in the disc inside).
    #[inline(always)]
    fn clears(&self, j: u32, centre: [f64; 2], reach: f64) -> bool {
        let [nx, ny, h] = self.poly.edge_lines[j as usize];
        let d = [centre[0] - self.at[0], centre[1] - self.at[1]];
        let w = self.in_body(d);
        nx * w[0] + ny * w[1] + reach + self.round_off(d) <= h
    }
}

/// The round-off margin of the window's tests, relative to the coordinates' size (as the
/// first clip's `tiny` and the edges' `reach`): far above the few ulps the placements and
/// side tests lose, far below any overlap the contact resolves.
const ROUND_OFF: f64 = 1e-12;

/// The corners found at the last evaluation, where the next search starts (hints only: the
/// clip's result does not depend on them).
#[derive(Debug, Clone, Copy, Default)]
struct Hints {
    facing: usize,
    deepest: usize,
    towards: usize,
}

#[cfg(test)]
thread_local! {
    /// How often the windowed clip fell back to the full clip or to every edge of B (for the
    /// tests).
    static FALLBACKS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// The full clip, where the window cannot be trusted.
fn fallback(
    a: &PlacedPolygon,
    b: &PlacedPolygon,
    q: [f64; 2],
    out: &mut Vec<ClipVertex>,
    next: &mut Vec<ClipVertex>,
) -> bool {
    #[cfg(test)]
    FALLBACKS.with(|f| f.set(f.get() + 1));
    clip_convex(a, b, q, out, next)
}

/// The windowed clip's reusable buffers: the clip's second polygon and its warm starts.
#[derive(Debug, Default)]
pub struct WindowScratch {
    /// The clip's scratch polygon (as `next` of [`clip_convex`]).
    pub next: Vec<ClipVertex>,
    hints: Hints,
}

/// The intersection of the placed convex polygons `a` (the particle, centred at `q`) and `b`
/// into `out`, exactly as [`clip_convex`] gives it, reading only the corners near the contact
/// where that can be trusted (module doc); `false` when they do not overlap.
pub fn clip_windowed(
    a: &PlacedPolygon,
    b: &PlacedPolygon,
    q: [f64; 2],
    out: &mut Vec<ClipVertex>,
    scratch: &mut WindowScratch,
) -> bool {
    if a.count() + b.count() <= FEW_CORNERS {
        return clip_convex(a, b, q, out, &mut scratch.next);
    }
    clip_in_window(a, b, q, out, scratch)
}

/// Two polygons with this many corners in all are clipped whole: the window's searches cost
/// more than they spare (two 12-gons: 494 against 456 ns per step, `benches/impact.rs`; and
/// placed all at once, 484 ns placed as read).
pub(crate) const FEW_CORNERS: usize = 32;

/// [`clip_windowed`] through the window whatever the corners' number.
fn clip_in_window(
    a: &PlacedPolygon,
    b: &PlacedPolygon,
    q: [f64; 2],
    out: &mut Vec<ClipVertex>,
    scratch: &mut WindowScratch,
) -> bool {
    // Centres at one point: every corner of B is as far along q (the full scan keeps corner 0).
    if q == [0.0, 0.0] {
        return fallback(a, b, q, out, &mut scratch.next);
    }
    // B's corner farthest along q (the lowest index of equals, as the full scan keeps the
    // first), and the facing edge there.
    let hint = (scratch.hints.facing, q);
    let (kb, _, [c_prev, c_kb, c_next]) = climb_from(b, hint, |v| along_q(v, q), true);
    scratch.hints.facing = kb;
    let j0 = facing_edge_between(b.count(), kb, [c_prev, c_kb, c_next], q);
    let bj0 = if j0 == kb {
        [c_kb, c_next]
    } else {
        [c_prev, c_kb]
    };
    if !first_clip_window(a, bj0, j0 as u32, out, &mut scratch.hints) {
        return fallback(a, b, q, out, &mut scratch.next);
    }
    if out.len() < 3 {
        return false;
    }
    // B's edge after j0 first, as the full clip: it cuts off what the first clip holds
    // beyond B's next corner (its crossing far along j0's line, and A's corners there), so the
    // edges that may cut are told from what it leaves: every later polygon's vertices lie on
    // segments between its vertices, as between the first clip's.
    let m = b.count();
    let next = &mut scratch.next;
    let j1 = wrap(j0 + 1, m);
    // Its ends: the climb's corners after the facing edge's start.
    let bj1 = if j0 == kb {
        [c_next, b.corner(wrap(j1 + 1, m))]
    } else {
        [c_kb, c_next]
    };
    if clip_by_edge(out, next, bj1, j1 as u32, None) {
        std::mem::swap(out, next);
        if out.len() < 3 {
            out.clear();
            return false;
        }
    }
    // Where B's edges cannot be ruled out, every edge after those two, as the full clip goes
    // on from the same polygon.
    match edges_cutting(b, out, j0, &mut scratch.hints.towards) {
        // The edges that may cut: each tested vertex by vertex (a bounding circle would pass
        // few of them by).
        Some(run) => {
            let rest = in_clip_order(run, j0, m).filter(|&j| j as usize != j1);
            clip_through(a, b, rest, (out, next), false)
        }
        None => {
            #[cfg(test)]
            FALLBACKS.with(|f| f.set(f.get() + 1));
            let every = (2..m).map(move |k| wrap(j0 + k, m) as u32);
            clip_through(a, b, every, (out, next), true)
        }
    }
}

/// [`climb`] from the corner `hint` (the last evaluation's: the bodies turn little between
/// evaluations, and the climb places only the corners it passes) where that takes at most
/// [`FEW_MOVES`] moves, else from the body-frame search's corner along the world direction
/// `d` (`PlacedPolygon::start_along`, warm-started from the same hint).
fn climb_from(
    ring: &PlacedPolygon,
    (hint, d): (usize, [f64; 2]),
    f: impl Fn([f64; 2]) -> f64,
    lowest: bool,
) -> (usize, f64, [[f64; 2]; 3]) {
    let near = if hint < ring.count() { hint } else { 0 };
    climb(ring, near, &f, lowest, FEW_MOVES)
        .unwrap_or_else(|| climb(ring, ring.start_along(d, near), &f, lowest, usize::MAX).unwrap())
}

/// The moves a climb from the last evaluation's corner may take before the body-frame search
/// is asked for a start (it costs about three moves).
const FEW_MOVES: usize = 3;

/// From corner `k`, along the boundary of `ring` while `f` of the corner grows: for a convex
/// polygon and a linear `f`, a corner where `f` is largest, with that value and the corners
/// before it, at it and after it, placed; `None` after `max_moves` moves. With `lowest`, of
/// two neighbours where `f` is equal the lower index (as a scan from corner 0 keeps the first).
fn climb<R: Ring + ?Sized>(
    ring: &R,
    mut k: usize,
    f: impl Fn([f64; 2]) -> f64,
    lowest: bool,
    max_moves: usize,
) -> Option<(usize, f64, [[f64; 2]; 3])> {
    let n = ring.count();
    let around = |k: usize| {
        let (prev, next) = (
            if k == 0 { n - 1 } else { k - 1 },
            if k + 1 == n { 0 } else { k + 1 },
        );
        [ring.corner(prev), ring.corner(k), ring.corner(next)]
    };
    let mut ck = ring.corner(k);
    let mut fk = f(ck);
    let mut moves = 0;
    loop {
        if moves > max_moves {
            return None;
        }
        moves += 1;
        let next = if k + 1 == n { 0 } else { k + 1 };
        let c_next = ring.corner(next);
        let f_next = f(c_next);
        if f_next > fk {
            (k, fk, ck) = (next, f_next, c_next);
            continue;
        }
        let prev = if k == 0 { n - 1 } else { k - 1 };
        let c_prev = ring.corner(prev);
        let f_prev = f(c_prev);
        if f_prev > fk {
            (k, fk, ck) = (prev, f_prev, c_prev);
            continue;
        }
        if lowest && ((f_next == fk && next < k) || (f_prev == fk && prev < k)) {
            let mut low = k;
            if f_next == fk && next < low {
                low = next;
            }
            if f_prev == fk && prev < low {
                low = prev;
            }
            return Some((low, fk, around(low)));
        }
        return Some((k, fk, [c_prev, ck, c_next]));
    }
}

/// The first clip (A by the inner half-plane of B's edge `j`, ends `bj`) into `out` from the
/// run of A's corners inside that line, in the full clip's order; `false` where the run cannot
/// be trusted to be every corner inside (A wholly inside, or a corner next to the run within
/// round-off of the line).
fn first_clip_window(
    a: &PlacedPolygon,
    bj: [[f64; 2]; 2],
    j: u32,
    out: &mut Vec<ClipVertex>,
    hints: &mut Hints,
) -> bool {
    let n = a.count();
    let e = [bj[1][0] - bj[0][0], bj[1][1] - bj[0][1]];
    // The full clip's side test, bit for bit.
    let side = |p: [f64; 2]| e[0] * (p[1] - bj[0][1]) - e[1] * (p[0] - bj[0][0]);
    let (deepest, s_deepest, _) = climb_from(a, (hints.deepest, [-e[1], e[0]]), side, false);
    hints.deepest = deepest;
    // Beyond the round-off of a side test, a corner next to the run cannot hide another
    // corner inside behind it (the side along a convex boundary has one maximum, one minimum).
    let scale = (e[0].abs() + e[1].abs())
        * (a.centre()[0].abs()
            + a.centre()[1].abs()
            + 2.0 * a.polygon().circumradius()
            + bj[0][0].abs()
            + bj[0][1].abs());
    let tiny = ROUND_OFF * scale;
    out.clear();
    if s_deepest < 0.0 {
        // Beyond the round-off every corner lies outside (the climb's is the deepest): apart.
        // Within it (a touch being located: two 120-gons' impact meets 12 such evaluations)
        // round-off may have stopped the climb short, so every corner is tested as the full
        // clip's first clip tests it: all outside, its first clip is empty and it finds the
        // bodies apart, as here, at a quarter of its instructions; one inside, it runs.
        return s_deepest < -tiny || (0..n).all(|i| side(a.corner(i)) < 0.0);
    }
    let prev = |i: usize| if i == 0 { n - 1 } else { i - 1 };
    let next = |i: usize| if i + 1 == n { 0 } else { i + 1 };
    // Back from the deepest corner to the corner before the run.
    let mut first = deepest;
    let before = loop {
        let i = prev(first);
        let c = a.corner(i);
        let s = side(c);
        if s < 0.0 {
            break (i, c, s);
        }
        first = i;
        if first == deepest {
            return false;
        }
    };
    if before.2 > -tiny {
        return false;
    }
    // On from it through the run and the corner after it, each placed once: the first clip's
    // vertices in the walk's order, then turned to the full clip's, which reads the corners
    // from 0 (the run split where it passes corner 0).
    let (mut last, mut i, mut inside, mut at_zero) = (before, first, 0, 0);
    loop {
        if i == 0 {
            at_zero = out.len();
        }
        let c = a.corner(i);
        let this = (i, c, side(c));
        push_first_clip(last, this, j, out);
        last = this;
        if this.2 < 0.0 {
            break;
        }
        inside += 1;
        if inside == n {
            return false;
        }
        i = next(i);
    }
    if last.2 > -tiny {
        return false;
    }
    out.rotate_left(at_zero);
    true
}

/// The edges of B whose lines may cut the polygon `out` (the first clip, by B's edge `j0`,
/// cut by the edge after it): one run of them around `j0`, from its first edge and of its
/// length; `None` where a vertex may lie outside half of B's edges' lines (every edge is then
/// tested). Every later polygon's vertices lie on segments between those of `out` (the clips
/// cut along chords), so an edge whose line has every vertex of `out` inside, by more than the
/// round-off, never cuts. Vertex v lies that far inside every line whose unit outward normal
/// u_j has u_j . (v - centre) <= r_in - margin (B's inscribed disc about its centroid lies
/// inside every line); the others form one arc around B's corner farthest along v (B's normals
/// turn monotonically, and u . (v - centre) has one maximum and one minimum around B, so the
/// edges where it exceeds any bound are contiguous). The run spans those of every vertex:
/// where the polygon reaches past a few of B's edges, the edges between its ends and twice as
/// far, a fraction of those whose lines come within its bounding circle.
fn edges_cutting(
    b: &PlacedPolygon,
    out: &[ClipVertex],
    j0: usize,
    hint: &mut usize,
) -> Option<(usize, usize)> {
    let m = b.count();
    let poly = b.polygon();
    let lines = &poly.edge_lines;
    let half = m as isize / 2;
    // Each edge by its offset from j0, in (-m/2, m/2].
    let offset = |j: usize| wrap(j + m - j0, m) as isize;
    let signed = |k: isize| if k > half { k - m as isize } else { k };
    let (mut lo, mut hi) = (0isize, 0isize);
    // The edge `off` edges after j0 (|off| <= m).
    let at_offset = |off: isize| {
        let i = j0 as isize + off;
        (if i < 0 {
            i + m as isize
        } else if i >= m as isize {
            i - m as isize
        } else {
            i
        }) as usize
    };
    for v in out {
        let d = [v.p[0] - b.centre()[0], v.p[1] - b.centre()[1]];
        let w = b.in_body(d);
        let limit = poly.inradius - b.round_off(d);
        let w2 = w[0] * w[0] + w[1] * w[1];
        if limit > 0.0 && w2 <= limit * limit {
            continue;
        }
        // Twice the inscribed radius away, a vertex can lie outside a third of the edges'
        // lines (a large body pressed on a small one): every edge, without walking them.
        if w2 >= 4.0 * poly.inradius * poly.inradius {
            return None;
        }
        let along = |j: usize| lines[j][0] * w[0] + lines[j][1] * w[1];
        // An edge of the run so far surely v's (past the limit by half the margin, far more
        // than the round-off of `along`, so in v's arc in exact arithmetic too) and the edges
        // just past both its ends not: v's arc, holding one edge of the run and neither edge
        // beyond it, lies within the run (no search).
        let sure = limit + 0.5 * b.round_off(d);
        let in_run = |j: usize| {
            let at = signed(offset(j));
            lo <= at && at <= hi
        };
        // The hint may come from another polygon (the scratch is the thread's).
        let h = if *hint < m { *hint } else { 0 };
        let h_prev = wrap(h + m - 1, m);
        if ((in_run(h) && along(h) > sure) || (in_run(h_prev) && along(h_prev) > sure))
            && along(at_offset(lo - 1)) <= limit
            && along(at_offset(hi + 1)) <= limit
        {
            continue;
        }
        let k = poly.lowest_vertex_near(*hint, -w[0], -w[1]);
        *hint = k;
        // Forward from the edge leaving corner k, back from the edge arriving at it.
        let mut len = 0;
        for forward in [true, false] {
            let mut j = if forward { k } else { wrap(k + m - 1, m) };
            while along(j) > limit {
                let at = signed(offset(j));
                if lo <= at && at <= hi {
                    // Already in the run: v's edges go on past it only through the edge just
                    // beyond it (they are contiguous), so the walk goes on from there.
                    j = if forward {
                        wrap(j0 + hi as usize + 1, m)
                    } else {
                        wrap((j0 + m) - (1 - lo) as usize, m)
                    };
                    continue;
                }
                (lo, hi) = (lo.min(at), hi.max(at));
                len += 1;
                if 2 * len >= m || hi - lo >= half {
                    return None;
                }
                j = if forward {
                    wrap(j + 1, m)
                } else {
                    wrap(j + m - 1, m)
                };
            }
        }
    }
    Some((
        (j0 as isize + lo).rem_euclid(m as isize) as usize,
        (hi - lo + 1) as usize,
    ))
}

/// The edges of the run from `first`, `len` long, other than `j0`, in the order the full clip
/// meets them (from `j0` on, around B).
fn in_clip_order((first, len): (usize, usize), j0: usize, m: usize) -> impl Iterator<Item = u32> {
    let at = wrap(j0 + m - first, m);
    let (head, tail) = if at < len {
        (at + 1..len, 0..at)
    } else {
        (0..len, 0..0)
    };
    head.chain(tail).map(move |k| wrap(first + k, m) as u32)
}

#[cfg(test)]
mod tests;
