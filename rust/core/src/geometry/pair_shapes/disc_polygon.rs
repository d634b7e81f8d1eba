//! The overlap of a disc with a convex polygon in closed form (docs/model.md, 17.8): the
//! polygon clipped by the circle, plus the circular segments its arcs cut beyond their chords.

use super::potential::{polygon_cap, potential_push, Cap, Crossing};
use super::{assemble, cross, dot, sub, ShapePatch};
use crate::geometry::convex_clip::wrap;
use crate::geometry::disc::disc_segment_at;
use std::cell::RefCell;

/// The disc-polygon overlap's buffers: the polygon relative to the circle's centre, the
/// overlap polygon's vertices (crossings marked), which of them are exits and the polygon's
/// edge each lies on.
#[derive(Default)]
struct DiscScratch {
    verts: Vec<[f64; 2]>,
    points: Vec<([f64; 2], bool)>,
    exits: Vec<bool>,
    edges: Vec<usize>,
}

/// What the disc-polygon overlap is asked for beside its patch: whether the area law's push
/// is wanted, and whether the disc is the particle.
#[derive(Debug, Clone, Copy)]
pub(super) struct DiscRole {
    /// Compute the area law's potential and push.
    pub push: bool,
    /// The disc is the particle (else the partner).
    pub disc_is_particle: bool,
    /// The polygon's edges on which the chord's crossings are held (`HeldSprings`), the
    /// overlap continued smoothly from them; `None`: the overlap as it is.
    pub held: Option<[u32; 2]>,
}

thread_local! {
    /// The disc-polygon overlap's vertices (reused: the overlap runs every step).
    static DISC_SCRATCH: RefCell<DiscScratch> = RefCell::new(DiscScratch::default());
}

/// The overlap of the disc of radius `r` centred at `c` with the convex polygon `poly`
/// (counter-clockwise), `q` the particle's centre: the polygon's part inside the circle
/// (its corners inside, and the points where its edges cross the circle), plus the circular
/// segment each arc of the circle inside the polygon cuts off beyond its chord.
pub(super) fn disc_polygon(
    c: [f64; 2],
    r: f64,
    poly: impl Iterator<Item = [f64; 2]>,
    q: [f64; 2],
    role: DiscRole,
) -> Option<ShapePatch> {
    DISC_SCRATCH.with(|cell| {
        let mut buf = cell.borrow_mut();
        let DiscScratch {
            verts,
            points,
            exits,
            edges,
        } = &mut *buf;
        verts.clear();
        verts.extend(poly.map(|p| sub(p, c)));
        points.clear();
        exits.clear();
        edges.clear();
        match role.held {
            None => clip_by_circle(verts, r, points, exits, edges),
            Some(held) => held_clip(verts, r, held, points, exits, edges),
        }
        if points.is_empty() {
            // No edge reaches the circle: the disc lies inside the polygon, or apart.
            return None;
        }
        let (mut area, mut moment) = shoelace(points);
        let mut apexes = [[0.0; 2]; 4];
        let mut n_apex = 0;
        let k = points.len();
        let mut chord: Option<[[f64; 2]; 2]> = None;
        let mut chord_at = 0;
        let mut best = -1.0;
        // The disc's cap: every segment (one in a shallow contact), area and first moment
        // about the circle's centre.
        let mut disc_cap = Cap::default();
        for i in 0..k {
            // An arc runs from an exit crossing to the next point, an entry crossing.
            if !exits[i] {
                continue;
            }
            let (exit, entry) = (points[i].0, points[(i + 1) % k].0);
            let (seg_area, seg_centroid, apex, len2) = circular_segment(r, exit, entry);
            moment[0] += seg_area * seg_centroid[0];
            moment[1] += seg_area * seg_centroid[1];
            area += seg_area;
            disc_cap.area += seg_area;
            disc_cap.moment[0] += seg_area * seg_centroid[0];
            disc_cap.moment[1] += seg_area * seg_centroid[1];
            if n_apex < apexes.len() {
                apexes[n_apex] = apex;
                n_apex += 1;
            }
            if len2 > best {
                best = len2;
                chord = Some([exit, entry]);
                chord_at = i;
            }
        }
        if !(area > 0.0) {
            return None;
        }
        let centroid = [c[0] + moment[0] / area, c[1] + moment[1] / area];
        let [a, b] = chord?;
        // The polygon's cap (its part inside the circle, closed by the chords) and the
        // disc's, with first moments about the chord's first end; the crossings' normals.
        let caps = role.push.then(|| {
            caps_and_crossings(points, verts, edges, disc_cap, ([a, b], chord_at), c, role)
        });
        for apex in &apexes[..n_apex] {
            points.push((*apex, false));
        }
        for p in points.iter_mut() {
            p.0 = [p.0[0] + c[0], p.0[1] + c[1]];
        }
        let chord = [[a[0] + c[0], a[1] + c[1]], [b[0] + c[0], b[1] + c[1]]];
        // Both ends lie on the circle, so the radius through the chord's midpoint is
        // perpendicular to it: known to the round-off of r, where the chord's own direction
        // (a short chord, just after touch) is known only to that of r over its length (1e-3
        // at a chord of 1e-14 m, which set a spring's elongation at stick 5e-4 apart between
        // tolerances).
        let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        let mut patch = assemble(q, area, centroid, chord, points, Some(mid))?;
        if let Some((caps, crossings)) = caps {
            (patch.potential, patch.push) = potential_push(q, patch.n, crossings, caps);
        }
        Some(patch)
    })
}

/// The two caps of a disc-polygon overlap, the polygon's (`points`, its part inside the
/// circle, relative to the circle's centre `c`) and the disc's (`disc_cap`, first moment about
/// the circle's centre), each with its first moment about the chord's first end, in the order
/// particle, partner; and the chord's two crossings (`chord_at`: the index of its first end in
/// `points`, whose edges of `verts` are `edges`) with each body's outward normal there.
fn caps_and_crossings(
    points: &[([f64; 2], bool)],
    verts: &[[f64; 2]],
    edges: &[usize],
    disc_cap: Cap,
    ([a, b], chord_at): ([[f64; 2]; 2], usize),
    c: [f64; 2],
    role: DiscRole,
) -> ([Cap; 2], [Crossing; 2]) {
    let poly_cap = polygon_cap(points.iter().map(|p| p.0), a);
    let disc_cap = Cap {
        area: disc_cap.area,
        moment: [
            disc_cap.moment[0] - disc_cap.area * a[0],
            disc_cap.moment[1] - disc_cap.area * a[1],
        ],
    };
    let k = points.len();
    let edge_normal = |i: usize| {
        let j = edges[i];
        let e = sub(verts[(j + 1) % verts.len()], verts[j]);
        [e[1], -e[0]]
    };
    let crossing = |i: usize, p: [f64; 2]| {
        let (disc_n, poly_n) = (p, edge_normal(i));
        let (particle, partner) = if role.disc_is_particle {
            (disc_n, poly_n)
        } else {
            (poly_n, disc_n)
        };
        Crossing {
            at: [p[0] + c[0], p[1] + c[1]],
            particle,
            partner,
        }
    };
    let crossings = [crossing(chord_at, a), crossing((chord_at + 1) % k, b)];
    if role.disc_is_particle {
        ([disc_cap, poly_cap], crossings)
    } else {
        ([poly_cap, disc_cap], crossings)
    }
}

/// The polygon `verts` (relative to the circle's centre) clipped by the circle of radius `r`:
/// its corners inside and its edges' crossings of the circle, counter-clockwise, crossings
/// marked, and in `exits` which points are crossings where the boundary leaves the circle.
fn clip_by_circle(
    verts: &[[f64; 2]],
    r: f64,
    out: &mut Vec<([f64; 2], bool)>,
    exits: &mut Vec<bool>,
    edges: &mut Vec<usize>,
) {
    let n = verts.len();
    for j in 0..n {
        let (p, q) = (verts[j], verts[wrap(j + 1, n)]);
        let d = sub(q, p);
        let Some((t0, t1)) = line_roots(p, d, r) else {
            continue;
        };
        if t1 <= 0.0 || t0 >= 1.0 {
            continue;
        }
        let at = |t: f64| [p[0] + t * d[0], p[1] + t * d[1]];
        if t0 > 0.0 {
            out.push((at(t0), true));
            exits.push(false);
            edges.push(j);
        }
        if t1 < 1.0 {
            out.push((at(t1), true));
            exits.push(true);
        } else {
            out.push((q, false));
            exits.push(false);
        }
        edges.push(j);
    }
}

/// Where the line p + t d crosses the circle of radius `r` about the origin: the parameters
/// t0 <= t1 where it enters and leaves it; `None` when it misses it or touches it.
fn line_roots(p: [f64; 2], d: [f64; 2], r: f64) -> Option<(f64, f64)> {
    // |p + t d|^2 = r^2: t = (-b -+ sqrt(b^2 - a c)) / a with b = p.d.
    let (a, b, cc) = (dot(d, d), dot(p, d), dot(p, p) - r * r);
    let disc = b * b - a * cc;
    if !(disc > 0.0) {
        return None;
    }
    let s = disc.sqrt();
    // Stable roots: the larger in magnitude first.
    let big = -b - s.copysign(b);
    let (t0, t1) = (big / a, cc / big);
    Some((t0.min(t1), t0.max(t1)))
}

/// The polygon's edge `j` of `verts`, from its vertex j to the next.
fn edge(verts: &[[f64; 2]], j: u32) -> ([f64; 2], [f64; 2]) {
    let j = j as usize;
    let p = verts[j];
    (p, sub(verts[(j + 1) % verts.len()], p))
}

/// The overlap of the polygon `verts` (relative to the circle's centre) and the circle of
/// radius `r` with its crossings held on the edges `[entry, exit]` (`HeldSprings`), laid out as
/// [`clip_by_circle`] lays out one arc's: where the line of edge `entry` enters the circle,
/// the polygon's corners after it up to edge `exit`'s start, and where the line of edge `exit`
/// leaves the circle, each crossing on its line whether or not it has passed its edge's end
/// since (the switch is located by [`held_crossings_value`]). Empty when a line misses the
/// circle.
fn held_clip(
    verts: &[[f64; 2]],
    r: f64,
    [entry, exit]: [u32; 2],
    out: &mut Vec<([f64; 2], bool)>,
    exits: &mut Vec<bool>,
    edges: &mut Vec<usize>,
) {
    let n = verts.len();
    let (e_in, e_out) = (edge(verts, entry), edge(verts, exit));
    let (Some((t_in, _)), Some((_, t_out))) = (
        line_roots(e_in.0, e_in.1, r),
        line_roots(e_out.0, e_out.1, r),
    ) else {
        return;
    };
    let at = |(p, d): ([f64; 2], [f64; 2]), t: f64| [p[0] + t * d[0], p[1] + t * d[1]];
    out.push((at(e_in, t_in), true));
    exits.push(false);
    edges.push(entry as usize);
    let mut j = entry as usize;
    while j != exit as usize {
        // The corner at the end of edge j, inside the circle.
        j = wrap(j + 1, n);
        out.push((verts[j], false));
        exits.push(false);
        edges.push(wrap(j + n - 1, n));
    }
    out.push((at(e_out, t_out), true));
    exits.push(true);
    edges.push(exit as usize);
}

/// The polygon's edges `[entry, exit]` on which the crossings of the overlap's chord lie (the
/// arc with the longest chord, as [`disc_polygon`] takes it), for the polygon `verts` relative
/// to the circle's centre; `None` when apart.
pub(super) fn crossing_edges(verts: &[[f64; 2]], r: f64) -> Option<[u32; 2]> {
    let (mut points, mut exits, mut edges) = (Vec::new(), Vec::new(), Vec::new());
    clip_by_circle(verts, r, &mut points, &mut exits, &mut edges);
    let k = points.len();
    let mut best: Option<(f64, [u32; 2])> = None;
    for i in (0..k).filter(|&i| exits[i]) {
        let d = sub(points[(i + 1) % k].0, points[i].0);
        let len2 = dot(d, d);
        if best.is_none_or(|(l, _)| len2 > l) {
            best = Some((len2, [edges[(i + 1) % k] as u32, edges[i] as u32]));
        }
    }
    best.map(|(_, held)| held)
}

/// The event function of the crossings held on the edges `[entry, exit]` of the polygon
/// `verts` (relative to the circle's centre): > 0 once one of them has passed an end of its
/// edge, in units of the edge, less 1e-9 (as for two polygons' held overlap). Where the line of
/// an edge misses the circle its crossing is its point nearest the circle, passed the edge's
/// end or not as that point is.
pub(super) fn held_crossings_value(verts: &[[f64; 2]], r: f64, [entry, exit]: [u32; 2]) -> f64 {
    let param = |j: u32, leaving: bool| {
        let (p, d) = edge(verts, j);
        match line_roots(p, d, r) {
            Some((t0, t1)) => {
                if leaving {
                    t1
                } else {
                    t0
                }
            }
            None => -dot(p, d) / dot(d, d),
        }
    };
    let past = |t: f64| (-t).max(t - 1.0);
    past(param(entry, false)).max(past(param(exit, true))) - 1e-9
}

/// Area and first moment (relative to the frame's origin) of the polygon through `points`,
/// summed relative to its first vertex so that slivers keep their precision.
fn shoelace(points: &[([f64; 2], bool)]) -> (f64, [f64; 2]) {
    let o = points[0].0;
    let (mut a2, mut mx, mut my) = (0.0, 0.0, 0.0);
    let mut prev = [0.0, 0.0];
    for &(p, _) in &points[1..] {
        let r = sub(p, o);
        let w = cross(prev, r);
        a2 += w;
        mx += (prev[0] + r[0]) * w;
        my += (prev[1] + r[1]) * w;
        prev = r;
    }
    let area = 0.5 * a2;
    if a2 == 0.0 {
        return (0.0, [0.0, 0.0]);
    }
    (area, [area * o[0] + mx / 6.0, area * o[1] + my / 6.0])
}

/// The circular segment between the chord exit -> entry of a circle of radius `r` (centre at
/// the origin) and the arc from exit counter-clockwise to entry (on the chord's right): its
/// area, centroid, the arc's apex and the squared chord.
fn circular_segment(r: f64, exit: [f64; 2], entry: [f64; 2]) -> (f64, [f64; 2], [f64; 2], f64) {
    let d = sub(entry, exit);
    let len2 = dot(d, d);
    let len = len2.sqrt();
    // Unit normal on the chord's right, towards the arc.
    let u = [d[1] / len, -d[0] / len];
    let half2 = 0.25 * len2;
    let minor = half2 / (r + (r * r - half2).max(0.0).sqrt());
    // The centre on the chord's left: the minor segment; else the major one.
    let h = if cross(exit, entry) >= 0.0 {
        minor
    } else {
        2.0 * r - minor
    };
    let seg = disc_segment_at(r, r - h, h);
    let below = (r - h) - seg.cy;
    // The apex as the chord's midpoint plus the segment's height: its distance from the
    // chord stays h when a nearly closed chord leaves u to round-off.
    let mid = [0.5 * (exit[0] + entry[0]), 0.5 * (exit[1] + entry[1])];
    (
        seg.area,
        [below * u[0], below * u[1]],
        [mid[0] + h * u[0], mid[1] + h * u[1]],
        len2,
    )
}
