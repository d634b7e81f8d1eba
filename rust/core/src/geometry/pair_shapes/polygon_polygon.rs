//! The overlap of two convex polygons (docs/model.md, 17.8): the O(n + m) clip
//! ([`crate::geometry::convex_clip`]), its chord through the two crossings of the boundaries,
//! and the area law's conservative push from the potential of `potential.rs`.

use super::potential::{polygon_cap, potential_push, Cap, CapSum, Crossing};
use super::springs::corner_springs;
use super::{assemble_into, sub, ShapePatch};
use crate::geometry::convex_clip::{
    clip_convex, cross, edge_crossing, wrap, ClipVertex, EdgeLine, Ring,
};
use crate::geometry::convex_window::{clip_windowed, PlacedPolygon, WindowScratch};
use crate::geometry::pair::HeldSprings;
use std::cell::RefCell;

/// What the overlap carries beside its area, chord and normal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Extras {
    /// Nothing more (the held springs are added by the caller).
    Nothing,
    /// The linear law's corner springs.
    Springs,
    /// The area law's potential and its push.
    Push,
}

/// Reused buffers: the clip's polygon, the windowed clip's scratch, and the overlap's points
/// with their crossing marks.
#[derive(Default)]
struct ClipScratch {
    out: Vec<ClipVertex>,
    window: WindowScratch,
    points: Vec<([f64; 2], bool)>,
    /// Where the last search of [`robustly_overlapping`] ended on each polygon.
    inside_hints: [usize; 2],
}

thread_local! {
    static CLIP: RefCell<ClipScratch> = RefCell::new(ClipScratch::default());
}

/// The overlap of the placed polygons `pa` (the particle, its centre at `at`) and `pb` (the
/// partner), with what `extras` asks for (the linear law's springs read every corner: all
/// placed), into `p`; `false` when apart, touching, or without two crossings (one inside the
/// other).
pub(super) fn polygon_patch(
    pa: &[[f64; 2]],
    pb: &[[f64; 2]],
    at: [f64; 2],
    reach: f64,
    extras: Extras,
    p: &mut ShapePatch,
) -> bool {
    clipped_patch(
        at,
        reach,
        |out, window| clip_convex(pa, pb, at, out, &mut window.next),
        |out, chord, points| {
            let all = Some((pa, pb));
            let normals = chord_normals(out, chord, pa, pb);
            patch_of(out, chord, normals, at, (extras, all), (points, p))
        },
    )
}

/// The area law's overlap of the polygons `pa` (the particle, its centre at `at`) and `pb`,
/// with its potential and push, into `p`, reading only the corners near the contact (the
/// windowed clip, `convex_window.rs`); `false` as for [`polygon_patch`].
pub(super) fn placed_patch(
    pa: &PlacedPolygon,
    pb: &PlacedPolygon,
    at: [f64; 2],
    reach: f64,
    p: &mut ShapePatch,
) -> bool {
    clipped_patch(
        at,
        reach,
        |out, window| clip_windowed(pa, pb, at, out, window),
        |out, chord, points| {
            let normals = chord_normals(out, chord, pa, pb);
            patch_of(out, chord, normals, at, (Extras::Push, None), (points, p))
        },
    )
}

/// The patch of two polygons whose centres are `at` apart, within `reach`: `clip` fills the
/// clip's vertices in the thread's scratch space (`false`: apart), `patch` makes the patch
/// from them and the chord between their farthest crossings. One body for the full and the
/// windowed clip.
fn clipped_patch(
    at: [f64; 2],
    reach: f64,
    clip: impl FnOnce(&mut Vec<ClipVertex>, &mut WindowScratch) -> bool,
    patch: impl FnOnce(&[ClipVertex], (usize, usize), &mut Vec<([f64; 2], bool)>) -> bool,
) -> bool {
    if at[0] * at[0] + at[1] * at[1] >= reach * reach {
        return false;
    }
    CLIP.with(|cell| {
        let mut buf = cell.borrow_mut();
        let ClipScratch {
            out,
            window,
            points,
            ..
        } = &mut *buf;
        if !clip(out, window) {
            return false;
        }
        match farthest_crossings(out) {
            Some(chord) => patch(out, chord, points),
            None => false,
        }
    })
}

/// Every corner of both polygons, placed (what the linear law's springs read).
type AllCorners<'a> = Option<(&'a [[f64; 2]], &'a [[f64; 2]])>;

/// The outward normals (unnormalised) of the particle's and the partner's edges through each
/// of the chord's two crossings.
type ChordNormals = [[[f64; 2]; 2]; 2];

/// [`ChordNormals`] of the crossings `k0`, `k1` of the overlap `out` of the polygons `pa`, `pb`.
fn chord_normals<R: Ring + ?Sized>(
    out: &[ClipVertex],
    (k0, k1): (usize, usize),
    pa: &R,
    pb: &R,
) -> ChordNormals {
    [k0, k1].map(|k| {
        let (i, j) = out[k].crossing().expect("a crossing");
        [edge_normal(pa, i), edge_normal(pb, j)]
    })
}

/// The patch of the overlap `out` (the clip's vertices) with the chord between its vertices
/// `chord`, the normals of the edges through them `normals`, the particle's centre at `at`,
/// into `p`; the springs need every corner placed (`all`).
fn patch_of(
    out: &[ClipVertex],
    (k0, k1): (usize, usize),
    normals: ChordNormals,
    at: [f64; 2],
    (extras, all): (Extras, AllCorners),
    (points, p): (&mut Vec<([f64; 2], bool)>, &mut ShapePatch),
) -> bool {
    let (c0, c1) = (out[k0], out[k1]);
    // The potential reads the two caps; the whole overlap is their sum (one pass over the
    // vertices rather than two: its shoelace terms are theirs, summed in another order).
    let caps = (extras == Extras::Push).then(|| caps_of(out, (k0, k1)));
    let whole = match caps {
        Some([c, d]) => Cap {
            area: c.area + d.area,
            moment: [c.moment[0] + d.moment[0], c.moment[1] + d.moment[1]],
        },
        None => polygon_cap(out.iter().map(|v| v.p), c0.p),
    };
    if !(whole.area > 0.0) {
        return false;
    }
    let centroid = [
        c0.p[0] + whole.moment[0] / whole.area,
        c0.p[1] + whole.moment[1] / whole.area,
    ];
    let across = shared_edge_normal(&c0, &c1, normals);
    let corners = out.iter().map(|v| v.p);
    if !assemble_into(p, at, (whole.area, centroid), [c0.p, c1.p], corners, across) {
        return false;
    }
    match extras {
        Extras::Springs => {
            if let Some((sa, sb)) = all {
                points.clear();
                points.extend(out.iter().map(|v| (v.p, v.crossing().is_some())));
                p.springs = corner_springs(sa, sb, points, at);
            }
        }
        Extras::Push => {
            let caps = caps.expect("the caps of the push");
            let crossing = |c: &ClipVertex, [particle, partner]: [[f64; 2]; 2]| Crossing {
                at: c.p,
                particle,
                partner,
            };
            let crossings = [crossing(&c0, normals[0]), crossing(&c1, normals[1])];
            (p.potential, p.push) = potential_push(at, p.n, crossings, caps);
        }
        Extras::Nothing => {}
    }
    true
}

/// The overlap of the placed polygons at `at` to hold through a piece of the adaptive path
/// (docs/model.md 17.8): its vertices' edge lines and its chord; empty when apart.
pub(super) fn held_overlap(pa: &PlacedPolygon, pb: &PlacedPolygon, at: [f64; 2]) -> HeldSprings {
    CLIP.with(|cell| {
        let mut buf = cell.borrow_mut();
        let ClipScratch { out, window, .. } = &mut *buf;
        match clip_windowed(pa, pb, at, out, window)
            .then(|| farthest_crossings(out))
            .flatten()
        {
            Some((k0, k1)) => HeldSprings {
                overlap: out.iter().map(|v| (v.before, v.after)).collect(),
                chord: [k0, k1],
                ..HeldSprings::default()
            },
            None => HeldSprings::default(),
        }
    })
}

/// The area law's patch with the overlap `held` continued smoothly: each held vertex where its
/// two edge lines meet, whether or not a crossing has passed the end of its edge since (the
/// switch is located by [`held_overlap_value`]), into `p`; `false` when the bodies do not
/// overlap, or the continued overlap has no area.
pub(super) fn held_patch(
    pa: &PlacedPolygon,
    pb: &PlacedPolygon,
    at: [f64; 2],
    held: &HeldSprings,
    p: &mut ShapePatch,
) -> bool {
    CLIP.with(|cell| {
        let mut buf = cell.borrow_mut();
        let ClipScratch {
            out,
            window,
            points,
            inside_hints,
        } = &mut *buf;
        let delta = OVERLAP_MARGIN * overlap_scale(pa, pb, at);
        let (crossing_certain, normals) = continue_held(held, (pa, pb), delta, out);
        // Whether the bodies overlap: certain where the chord's two crossings are proper (each
        // strictly inside both of its edges), or where a small disc lies inside both; else the
        // clip's own answer (its polygon is then dropped for the held one).
        if !crossing_certain && !robustly_overlapping(pa, pb, at, out, inside_hints) {
            if !clip_windowed(pa, pb, at, out, window) {
                return false;
            }
            continue_held(held, (pa, pb), delta, out);
        }
        let [k0, k1] = held.chord;
        patch_of(
            out,
            (k0, k1),
            normals,
            at,
            (Extras::Push, None),
            (points, p),
        )
    })
}

/// Fills `out` with the held overlap continued: each vertex where its two edge lines meet, as
/// [`meet`] places it (the same arithmetic, so the same bits), each line's ends placed once
/// (the edge a vertex leaves along is the next one's arriving edge, and at a corner the edge
/// after begins where the edge before ends). Returns whether the chord's two crossings are
/// proper beyond `delta` ([`crosses_properly`]): then the bodies certainly overlap; and the
/// normals of their edges, from the ends placed here.
fn continue_held(
    held: &HeldSprings,
    (pa, pb): (&PlacedPolygon, &PlacedPolygon),
    delta: f64,
    out: &mut Vec<ClipVertex>,
) -> (bool, ChordNormals) {
    out.clear();
    let ends_of = |l: EdgeLine| match l {
        EdgeLine::A(i) => ends(pa, i),
        EdgeLine::B(j) => ends(pb, j),
    };
    let mut normals = [[[0.0; 2]; 2]; 2];
    let Some(&(first_line, _)) = held.overlap.first() else {
        return (false, normals);
    };
    let first_ends = ends_of(first_line);
    let (mut line, mut line_ends) = (first_line, first_ends);
    let mut proper = 0;
    for (k, &(before, after)) in held.overlap.iter().enumerate() {
        let before_ends = if before == line {
            line_ends
        } else {
            ends_of(before)
        };
        let next_edge = |l: u32, count: usize| wrap(l as usize + 1, count) as u32;
        let (p, after_ends) = match (before, after) {
            // A corner: the edge after starts at it.
            (EdgeLine::A(i), EdgeLine::A(n)) if n == next_edge(i, pa.count()) => {
                let next = wrap(n as usize + 1, pa.count());
                (before_ends[1], [before_ends[1], pa.corner(next)])
            }
            (EdgeLine::B(j), EdgeLine::B(n)) if n == next_edge(j, pb.count()) => {
                let next = wrap(n as usize + 1, pb.count());
                (before_ends[1], [before_ends[1], pb.corner(next)])
            }
            _ => {
                let after_ends = if after == first_line && k + 1 == held.overlap.len() {
                    first_ends
                } else {
                    ends_of(after)
                };
                // Along the particle's edge, as the clip takes it (`meet`).
                let (ea, eb) = match (before, after) {
                    (EdgeLine::B(_), EdgeLine::A(_)) => (after_ends, before_ends),
                    _ => (before_ends, after_ends),
                };
                let crossing = matches!(
                    (before, after),
                    (EdgeLine::A(_), EdgeLine::B(_)) | (EdgeLine::B(_), EdgeLine::A(_))
                );
                if let Some(end) = held.chord.iter().position(|&c| c == k).filter(|_| crossing) {
                    normals[end] = [ends_normal(ea), ends_normal(eb)];
                    proper += usize::from(crosses_properly(ea, eb, delta));
                }
                (edge_crossing(ea, eb, ea[0]), after_ends)
            }
        };
        out.push(ClipVertex { p, before, after });
        (line, line_ends) = (after, after_ends);
    }
    (proper == 2, normals)
}

/// Whether the edges `a` (the particle's) and `b` (the partner's) cross at a point inside both:
/// each edge's ends lie on opposite sides of the other's line, each at least `delta` from it.
/// Two convex boundaries crossing there, transversally, enclose an overlap: the clip finds it
/// (`a_certain_overlap_is_one_the_clip_finds`).
#[inline(always)]
fn crosses_properly([a0, a1]: [[f64; 2]; 2], [b0, b1]: [[f64; 2]; 2], delta: f64) -> bool {
    let (ea, eb) = (sub(a1, a0), sub(b1, b0));
    // The ends' sides, times the other edge's length (compared squared: no root).
    let (sa0, sa1) = (cross(eb, sub(a0, b0)), cross(eb, sub(a1, b0)));
    let (sb0, sb1) = (cross(ea, sub(b0, a0)), cross(ea, sub(b1, a0)));
    let d2 = delta * delta;
    let beyond = |s0: f64, s1: f64, e: [f64; 2]| {
        let floor = d2 * (e[0] * e[0] + e[1] * e[1]);
        s0 * s1 < 0.0 && s0 * s0 >= floor && s1 * s1 >= floor
    };
    beyond(sa0, sa1, eb) && beyond(sb0, sb1, ea)
}

/// The size of the coordinates of two placed polygons whose centres are `at` apart (what the
/// certificates' margins are relative to).
fn overlap_scale(pa: &PlacedPolygon, pb: &PlacedPolygon, at: [f64; 2]) -> f64 {
    pa.polygon().circumradius() + pb.polygon().circumradius() + at[0].abs() + at[1].abs()
}

/// Whether the placed polygons certainly overlap: a disc about the mean of the vertices `v`
/// (the held overlap continued), far wider than the round-off of the clip's arithmetic
/// ([`OVERLAP_MARGIN`] of the coordinates), lies inside both. Then the clip, which keeps such
/// a disc, finds them overlapping: it need not run (in the adaptive path's pieces it ran
/// at every stage only for that answer: a third of a polygon pair's evaluation).
fn robustly_overlapping(
    pa: &PlacedPolygon,
    pb: &PlacedPolygon,
    at: [f64; 2],
    v: &[ClipVertex],
    hints: &mut [usize; 2],
) -> bool {
    if v.len() < 3 {
        return false;
    }
    let k = v.len() as f64;
    let (sx, sy) = v
        .iter()
        .fold((0.0, 0.0), |(x, y), w| (x + w.p[0], y + w.p[1]));
    let c = [sx / k, sy / k];
    let delta = OVERLAP_MARGIN * overlap_scale(pa, pb, at);
    let [ha, hb] = hints;
    pa.holds_disc(c, delta, ha) && pb.holds_disc(c, delta, hb)
}

/// The radius of the disc that certifies an overlap without the clip, relative to the
/// coordinates' size: a million times their round-off.
const OVERLAP_MARGIN: f64 = 1e-10;

#[cfg(test)]
/// Where two edge lines meet: a polygon's corner between its consecutive edges, else the
/// crossing of the two lines (interpolated along the first's edge, from its end nearer the
/// other line).
#[inline(always)]
fn meet<R: Ring + ?Sized>(l1: EdgeLine, l2: EdgeLine, pa: &R, pb: &R) -> [f64; 2] {
    let line = |l: EdgeLine| match l {
        EdgeLine::A(i) => ends(pa, i),
        EdgeLine::B(j) => ends(pb, j),
    };
    match (l1, l2) {
        (EdgeLine::A(i), EdgeLine::A(k)) if k as usize == wrap(i as usize + 1, pa.count()) => {
            pa.corner(k as usize)
        }
        (EdgeLine::B(j), EdgeLine::B(k)) if k as usize == wrap(j as usize + 1, pb.count()) => {
            pb.corner(k as usize)
        }
        // Along the particle's edge, as the clip takes it (`convex_clip::exact_position`).
        (EdgeLine::B(_), EdgeLine::A(_)) => edge_crossing(line(l2), line(l1), line(l2)[0]),
        _ => edge_crossing(line(l1), line(l2), line(l1)[0]),
    }
}

/// The two ends of edge `k` of the polygon `v`.
fn ends<R: Ring + ?Sized>(v: &R, k: u32) -> [[f64; 2]; 2] {
    crate::geometry::convex_clip::edge(v, k)
}

/// How far the held overlap's crossings have gone past the ends of their edges (> 0: a
/// crossing has passed a corner, the held overlap is no longer the bodies' and the force
/// turns there), in units of the edges' lengths, less a margin of 1e-9 so that an overlap held
/// at a switch does not fire again on round-off.
pub(super) fn held_overlap_value<R: Ring + ?Sized>(pa: &R, pb: &R, held: &HeldSprings) -> f64 {
    let mut value = f64::NEG_INFINITY;
    for &(before, after) in &held.overlap {
        let (i, j) = match (before, after) {
            (EdgeLine::A(i), EdgeLine::B(j)) | (EdgeLine::B(j), EdgeLine::A(i)) => (i, j),
            _ => continue,
        };
        let (ea, eb) = (ends(pa, i), ends(pb, j));
        for (e, other) in [(ea, eb), (eb, ea)] {
            let d = sub(other[1], other[0]);
            let side = |p: [f64; 2]| d[0] * (p[1] - other[0][1]) - d[1] * (p[0] - other[0][0]);
            let (s0, s1) = (side(e[0]), side(e[1]));
            if s0 == s1 {
                continue;
            }
            let t = s0 / (s0 - s1);
            value = value.max((-t).max(t - 1.0));
        }
    }
    value - 1e-9
}

/// The two crossings farthest apart (the only two in a shallow contact; docs/model.md 17.8
/// states the rule for more).
fn farthest_crossings(out: &[ClipVertex]) -> Option<(usize, usize)> {
    // Almost always exactly two: told in one pass over the vertices.
    let mut found = [0usize; 2];
    let mut count = 0;
    for (k, v) in out.iter().enumerate() {
        if v.crossing().is_some() {
            if count < 2 {
                found[count] = k;
            }
            count += 1;
        }
    }
    match count {
        0 | 1 => return None,
        2 => return Some((found[0], found[1])),
        _ => {}
    }
    let mut best: Option<(f64, usize, usize)> = None;
    let crossings = || {
        out.iter()
            .enumerate()
            .filter(|(_, v)| v.crossing().is_some())
    };
    for (i, a) in crossings() {
        for (j, b) in crossings().filter(|&(j, _)| j > i) {
            let d = sub(b.p, a.p);
            let len2 = d[0] * d[0] + d[1] * d[1];
            if best.is_none_or(|(l, _, _)| len2 > l) {
                best = Some((len2, i, j));
            }
        }
    }
    best.map(|(_, i, j)| (i, j))
}

/// The outward normal (unnormalised) of edge `k` of the counter-clockwise polygon `v`.
fn edge_normal<R: Ring + ?Sized>(v: &R, k: u32) -> [f64; 2] {
    ends_normal(ends(v, k))
}

/// The outward normal (unnormalised) of a counter-clockwise polygon's edge from its ends.
#[inline(always)]
fn ends_normal([v0, v1]: [[f64; 2]; 2]) -> [f64; 2] {
    let e = sub(v1, v0);
    [e[1], -e[0]]
}

/// Where both crossings lie on one edge of either polygon (a corner pressed into an edge: the
/// chord lies on that edge), that edge's normal (of `normals`, the edges' through each
/// crossing): exact, where the chord's own direction carries the round-off of its ends over its
/// length (1e-3 at a chord of 1e-14 m).
fn shared_edge_normal(c0: &ClipVertex, c1: &ClipVertex, normals: ChordNormals) -> Option<[f64; 2]> {
    let ((i0, j0), (i1, j1)) = (c0.crossing()?, c1.crossing()?);
    if i0 == i1 {
        Some(normals[0][0])
    } else if j0 == j1 {
        Some(normals[0][1])
    } else {
        None
    }
}

/// The particle's and the partner's caps: the overlap cut by the chord between crossings
/// `k0` and `k1`, each part with the first moment about crossing `k0`. The part whose
/// boundary leaves `k0` along an edge of the particle is the particle's.
fn caps_of(out: &[ClipVertex], (k0, k1): (usize, usize)) -> [Cap; 2] {
    debug_assert!(k0 < k1, "the crossings in the clip's order");
    let o = out[k0].p;
    let forward = polygon_cap(out[k0..=k1].iter().map(|v| v.p), o);
    // From k1 round to k0: two runs of the slice, summed in turn.
    let mut back = CapSum::start(out[k1].p, o);
    out[k1 + 1..].iter().for_each(|v| back.push(v.p));
    out[..=k0].iter().for_each(|v| back.push(v.p));
    let back = back.finish();
    let particle_first = matches!(out[k0].after, crate::geometry::convex_clip::EdgeLine::A(_));
    if particle_first {
        [forward, back]
    } else {
        [back, forward]
    }
}

#[cfg(test)]
#[path = "polygon_polygon_tests.rs"]
mod tests;
