//! The convex clip of `convex_clip.rs` visiting only the corners near the contact
//! (docs/model.md, section 17.8): in a shallow contact a few edges of each body are involved,
//! so the clip places and reads only those, and its result is the full clip's, vertex for
//! vertex and bit for bit.
//!
//! The full clip starts from B's edge facing A's centre (at B's corner farthest along q),
//! clips A by that edge's line, then by each of B's other edges in turn; an edge whose line has
//! every vertex of the clipped polygon inside changes nothing. Here: B's farthest corner and
//! the deepest corner of A below the facing edge's line are found by the body-frame search of
//! the plate's polygon (`Polygon::lowest_vertex_near`, warm-started from the last evaluation's
//! corners) and a climb along the boundary in the full clip's own arithmetic; A's corners
//! inside that line form one run around the deepest (A is convex), walked to its two ends; and
//! of B's other edges only those whose lines come near the first clip are tested. Every later
//! polygon lies in the first, whose corners lie within R0 of their mean C0; B's inscribed disc
//! about its centroid (radius r_in) lies inside every edge's line, so an edge whose unit
//! outward normal u_j has u_j . (C0 - centre) <= r_in - R0 (less a round-off margin) has every
//! later vertex inside, and the full clip passes it by. Such normals lie outside an arc around
//! the direction of C0, and B's normals turn monotonically, so the edges tested are one run
//! around B's corner farthest along C0 (for a regular polygon, exactly the edges whose lines
//! come within R0 of C0). Where the window cannot be trusted (A wholly inside the first line,
//! a corner next to the run within round-off of it), the full clip runs; where B's edges cannot
//! be ruled out (its inscribed disc too small against the first clip, or half of its edges
//! near), the clip goes on through every edge of B from the same first clip, as the full one.

use super::convex_clip::{
    along_q, clip_convex, clip_through, edge, facing_edge_at, first_clip_run, Bound, ClipVertex,
    Ring,
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
    fn in_body(&self, d: [f64; 2]) -> [f64; 2] {
        [
            self.cos * d[0] + self.sin * d[1],
            -self.sin * d[0] + self.cos * d[1],
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
            let mut k = if forward { k0 } else { (k0 + m - 1) % m };
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
                    (k + 1) % m
                } else {
                    (k + m - 1) % m
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
    let kb = climb(
        b,
        b.start_along(q, scratch.hints.facing),
        |v| along_q(v, q),
        true,
    );
    scratch.hints.facing = kb;
    let j0 = facing_edge_at(b, kb, q);
    if !first_clip_window(a, edge(b, j0 as u32), j0 as u32, out, &mut scratch.hints) {
        return fallback(a, b, q, out, &mut scratch.next);
    }
    if out.len() < 3 {
        return false;
    }
    let bound = Bound::of(out);
    // Where B's edges cannot be ruled out, every edge after the first, as the full clip
    // goes on from the same first clip.
    let m = b.count();
    let (run, all) = match edges_near(b, bound, &mut scratch.hints.towards) {
        Some(run) => (run, 0..0),
        None => {
            #[cfg(test)]
            FALLBACKS.with(|f| f.set(f.get() + 1));
            ((0, 0), 1..m)
        }
    };
    let every = all.map(move |k| ((j0 + k) % m) as u32);
    clip_through(
        a,
        b,
        in_clip_order(run, j0, m).chain(every),
        out,
        &mut scratch.next,
    )
}

/// From corner `k`, along the boundary of `ring` while `f` of the corner grows: for a convex
/// polygon and a linear `f`, a corner where `f` is largest. With `lowest`, of two neighbours
/// where `f` is equal the lower index (as a scan from corner 0 keeps the first).
fn climb<R: Ring + ?Sized>(
    ring: &R,
    mut k: usize,
    f: impl Fn([f64; 2]) -> f64,
    lowest: bool,
) -> usize {
    let n = ring.count();
    let mut fk = f(ring.corner(k));
    loop {
        let next = if k + 1 == n { 0 } else { k + 1 };
        let f_next = f(ring.corner(next));
        if f_next > fk {
            (k, fk) = (next, f_next);
            continue;
        }
        let prev = if k == 0 { n - 1 } else { k - 1 };
        let f_prev = f(ring.corner(prev));
        if f_prev > fk {
            (k, fk) = (prev, f_prev);
            continue;
        }
        if lowest {
            if f_next == fk && next < k {
                k = next;
            }
            if f_prev == fk && prev < k {
                k = prev;
            }
        }
        return k;
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
    let deepest = climb(a, a.start_along([-e[1], e[0]], hints.deepest), side, false);
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
    let s_deepest = side(a.corner(deepest));
    if s_deepest < 0.0 {
        return s_deepest < -tiny;
    }
    let prev = |i: usize| if i == 0 { n - 1 } else { i - 1 };
    let next = |i: usize| if i + 1 == n { 0 } else { i + 1 };
    let (mut first, mut last, mut len) = (deepest, deepest, 1);
    while side(a.corner(prev(first))) >= 0.0 {
        first = prev(first);
        len += 1;
        if len == n {
            return false;
        }
    }
    while side(a.corner(next(last))) >= 0.0 {
        last = next(last);
        len += 1;
        if len == n {
            return false;
        }
    }
    if side(a.corner(prev(first))) > -tiny || side(a.corner(next(last))) > -tiny {
        return false;
    }
    // The full clip emits in the order of the corner it reads (from 0): the run from its
    // first corner through the corner after its last, split where it passes corner 0.
    let end = next(last);
    if first <= end {
        first_clip_run(a, bj, j, prev(first), first..=end, out);
    } else {
        first_clip_run(a, bj, j, n - 1, 0..=end, out);
        first_clip_run(a, bj, j, first - 1, first..n, out);
    }
    true
}

/// The edges of B whose lines may cut the first clip (bounding circle `bound`): one run of
/// them, from its first edge and of its length; `None` where B's inscribed disc cannot rule
/// edges out, or the run is half of B's edges (the full clip then runs).
fn edges_near(b: &PlacedPolygon, bound: Bound, hint: &mut usize) -> Option<(usize, usize)> {
    let m = b.count();
    let centre = b.centre();
    let u = [bound.centre[0] - centre[0], bound.centre[1] - centre[1]];
    let poly = b.polygon();
    // Every later polygon lies in the first (module doc); the margin covers the round-off of
    // the placed edges, of the clips' crossings and of the full clip's own side tests.
    let scale = poly.circumradius() + u[0].abs() + u[1].abs() + centre[0].abs() + centre[1].abs();
    let reach = bound.radius2.sqrt() + ROUND_OFF * scale;
    let limit = poly.inradius - reach;
    let u_len2 = u[0] * u[0] + u[1] * u[1];
    if limit > 0.0 && u_len2 <= limit * limit {
        return Some((0, 0));
    }
    if limit <= 0.0 && u_len2 <= limit * limit {
        return None;
    }
    // The outward unit normal of edge j against u beyond `limit`, from the body-frame lines
    // (no corner placed; the margin in `reach` covers their round-off).
    let w = b.in_body(u);
    let needed = |j: usize| {
        let [nx, ny, _] = poly.edge_lines[j];
        nx * w[0] + ny * w[1] > limit
    };
    let toward = climb(
        b,
        b.start_along(u, *hint),
        |v| (v[0] - centre[0]) * u[0] + (v[1] - centre[1]) * u[1],
        false,
    );
    *hint = toward;
    let (mut last, mut len) = (toward, 0);
    while needed(last) {
        last = if last + 1 == m { 0 } else { last + 1 };
        len += 1;
        if 2 * len >= m {
            return None;
        }
    }
    let mut first = toward;
    loop {
        let before = if first == 0 { m - 1 } else { first - 1 };
        if before == last || !needed(before) {
            break;
        }
        first = before;
        len += 1;
        if 2 * len >= m {
            return None;
        }
    }
    Some((first, len))
}

/// The edges of the run from `first`, `len` long, other than `j0`, in the order the full clip
/// meets them (from `j0` on, around B).
fn in_clip_order((first, len): (usize, usize), j0: usize, m: usize) -> impl Iterator<Item = u32> {
    let at = (j0 + m - first) % m;
    let (head, tail) = if at < len {
        (at + 1..len, 0..at)
    } else {
        (0..len, 0..0)
    };
    head.chain(tail).map(move |k| ((first + k) % m) as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rng(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A random convex polygon: corners at sorted random angles on an ellipse.
    fn random_convex(r: f64, n: usize, seed: &mut u64) -> Polygon {
        let aspect = 0.3 + 0.7 * rng(seed);
        let mut angles: Vec<f64> = (0..n).map(|_| rng(seed) * std::f64::consts::TAU).collect();
        angles.sort_by(f64::total_cmp);
        angles.dedup_by(|x, y| (*x - *y).abs() < 1e-6);
        let v: Vec<[f64; 2]> = angles
            .iter()
            .map(|a| [r * a.cos(), r * aspect * a.sin()])
            .collect();
        Polygon::convex(&v).unwrap_or_else(|_| Polygon::regular(r, n.max(3)).unwrap())
    }

    fn placed(p: &PlacedPolygon) -> Vec<[f64; 2]> {
        (0..p.count()).map(|i| p.corner(i)).collect()
    }

    /// An edge told clear of a disc from its body-frame line has every point of the disc inside
    /// its placed line (the clip's own side test), on random polygons at random placements,
    /// sizes 1e-3 to 1e3 and discs from far to touching: the test never skips an edge that
    /// would cut, and it does tell most clear edges.
    #[test]
    fn an_edge_told_clear_has_the_disc_inside_its_placed_line() {
        let mut seed = 5u64;
        let (mut told, mut clear_in_fact) = (0, 0);
        for case in 0..4000 {
            let s = &mut seed;
            let size = 10f64.powf(-3.0 + 6.0 * rng(s));
            let n = 3 + (rng(s) * 200.0) as usize;
            let poly = if case % 2 == 0 {
                Polygon::regular(size, n).unwrap()
            } else {
                random_convex(size, n, s)
            };
            let at = [size * (rng(s) - 0.5) * 20.0, size * (rng(s) - 0.5) * 20.0];
            let b = PlacedPolygon::new(&poly, at, rng(s) * 6.3);
            let ang = rng(s) * 6.3;
            let dist = poly.inradius * (0.5 + 0.6 * rng(s));
            let centre = [at[0] + dist * ang.cos(), at[1] + dist * ang.sin()];
            let reach = size * 0.2 * rng(s).powi(3);
            for j in 0..b.count() {
                let [b0, b1] = edge(&b, j as u32);
                let e = [b1[0] - b0[0], b1[1] - b0[1]];
                let side = |p: [f64; 2]| e[0] * (p[1] - b0[1]) - e[1] * (p[0] - b0[0]);
                let len = e[0].hypot(e[1]);
                let inside_by = side(centre) / len - reach;
                clear_in_fact += usize::from(inside_by > 1e-9 * size);
                if b.clears(j as u32, centre, reach) {
                    told += 1;
                    for k in 0..16 {
                        let a = k as f64 * std::f64::consts::TAU / 16.0;
                        let p = [centre[0] + reach * a.cos(), centre[1] + reach * a.sin()];
                        assert!(side(p) >= 0.0, "case {case} edge {j}: {p:?} outside");
                    }
                    assert!(inside_by >= 0.0, "case {case} edge {j}: {inside_by:e}");
                }
            }
        }
        assert!(told * 10 >= clear_in_fact * 9, "{told} of {clear_in_fact}");
    }

    /// A disc told inside a placed polygon by its body-frame lines lies inside every placed
    /// edge's line (sampled on its rim), on random polygons, sizes and placements, discs from
    /// deep inside to across the boundary; and most discs inside by a margin are told so.
    #[test]
    fn a_disc_told_inside_lies_inside_every_placed_edge() {
        let mut seed = 9u64;
        let (mut told, mut inside_in_fact, mut near) = (0, 0, 0);
        for case in 0..4000 {
            let s = &mut seed;
            let size = 10f64.powf(-3.0 + 6.0 * rng(s));
            let n = 3 + (rng(s) * 300.0) as usize;
            let poly = if case % 2 == 0 {
                Polygon::regular(size, n).unwrap()
            } else {
                random_convex(size, n, s)
            };
            let at = [size * (rng(s) - 0.5) * 20.0, size * (rng(s) - 0.5) * 20.0];
            let b = PlacedPolygon::new(&poly, at, rng(s) * 6.3);
            let ang = rng(s) * 6.3;
            let dist = poly.circumradius() * (1.05 * rng(s)).sqrt();
            let p = [at[0] + dist * ang.cos(), at[1] + dist * ang.sin()];
            let delta = size * 0.05 * rng(s).powi(4);
            let margin = (0..b.count())
                .map(|j| {
                    let [b0, b1] = edge(&b, j as u32);
                    let e = [b1[0] - b0[0], b1[1] - b0[1]];
                    (e[0] * (p[1] - b0[1]) - e[1] * (p[0] - b0[0])) / e[0].hypot(e[1])
                })
                .fold(f64::INFINITY, f64::min);
            inside_in_fact += usize::from(margin > delta + 1e-9 * size);
            if b.holds_disc(p, delta, &mut near) {
                told += 1;
                // Less the placement's round-off (body-frame lines against placed corners).
                let round_off = 1e-14 * (size + at[0].abs() + at[1].abs());
                assert!(
                    margin >= delta - round_off,
                    "case {case}: {margin:e} < {delta:e}"
                );
            }
        }
        assert!(
            told * 10 >= inside_in_fact * 9,
            "{told} of {inside_in_fact}"
        );
        assert!(told > 1000, "{told}");
    }

    /// The windowed clip against the full clip, on random regular and convex polygons of 3 to
    /// 300 corners, sizes 1e-2 to 1e2 apart, at every depth from grazing to one deep inside the
    /// other, and corner on corner and face on face: the same vertices, bit for bit, with their
    /// edge lines. Shallow contacts between many-cornered bodies take the window (not the full
    /// clip's fallback) in most cases.
    #[test]
    fn the_window_gives_the_full_clip_bit_for_bit() {
        let mut seed = 11u64;
        let (mut full, mut next, mut win) = (Vec::new(), Vec::new(), Vec::new());
        let mut scratch = WindowScratch::default();
        let (mut overlapping, mut shallow_many, mut windowed) = (0, 0, 0);
        for case in 0..20000 {
            let s = &mut seed;
            let pick = |s: &mut u64| match (rng(s) * 4.0) as usize {
                0 => 3 + (rng(s) * 10.0) as usize,
                1 => 12,
                2 => 120,
                _ => 3 + (rng(s) * 300.0) as usize,
            };
            let (n, m) = (pick(s), pick(s));
            let r1 = if case % 2 == 0 {
                1.0
            } else {
                10f64.powf(-2.0 + 4.0 * rng(s))
            };
            let r2 = 1.0;
            let make = |r: f64, k: usize, s: &mut u64| {
                if rng(s) < 0.5 {
                    Polygon::regular(r, k).unwrap()
                } else {
                    random_convex(r, k, s)
                }
            };
            let (pa, pb) = (make(r1, n, s), make(r2, m, s));
            let reach = pa.circumradius() + pb.circumradius();
            // Corner on corner and face on face along y for one case in four.
            let (ang, phi1, phi2) = if case % 4 == 0 && n == 12 && m == 12 {
                let half = std::f64::consts::PI / 12.0;
                let k = (rng(s) * 2.0) as usize as f64;
                (
                    std::f64::consts::FRAC_PI_2,
                    -std::f64::consts::FRAC_PI_2 + k * half,
                    std::f64::consts::FRAC_PI_2,
                )
            } else {
                (rng(s) * 6.3, rng(s) * 6.3, rng(s) * 6.3)
            };
            let depth = match case % 97 {
                // Centres at one point.
                0 => 1.0,
                _ if rng(s) < 0.7 => 1e-6 + 0.1 * rng(s),
                _ => rng(s),
            };
            let d = reach * (1.0 - depth);
            let q = [d * ang.cos(), d * ang.sin()];
            let (a, b) = (
                PlacedPolygon::new(&pa, q, phi1),
                PlacedPolygon::new(&pb, [0.0, 0.0], phi2),
            );
            let (va, vb) = (placed(&a), placed(&b));
            let theirs = clip_convex(&va[..], &vb[..], q, &mut full, &mut next);
            let before = FALLBACKS.with(|f| f.get());
            let ours = clip_in_window(&a, &b, q, &mut win, &mut scratch);
            assert_eq!(ours, theirs, "case {case}: n {n} m {m} q {q:?}");
            if theirs {
                overlapping += 1;
                assert_eq!(win, full, "case {case}: n {n} m {m} q {q:?}");
                if depth < 0.05 && n >= 60 && m >= 60 && r1 == 1.0 {
                    shallow_many += 1;
                    windowed += usize::from(FALLBACKS.with(|f| f.get()) == before);
                }
            }
        }
        let fell_back = FALLBACKS.with(|f| f.get());
        eprintln!("{overlapping} overlapping, {fell_back} fell back; {windowed} of {shallow_many} shallow ones windowed");
        assert!(overlapping > 10000, "{overlapping}");
        assert!(
            windowed * 10 >= shallow_many * 9,
            "{windowed} of {shallow_many}"
        );
    }
}
