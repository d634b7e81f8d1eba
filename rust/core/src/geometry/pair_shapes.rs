//! Where a pair with corners meets (docs/model.md, section 17.8): a polygon with a polygon
//! (the O(n + m) convex clip, `polygon_polygon.rs`) and a disc with a polygon (closed form:
//! the polygon clipped by the circle, plus the circular segments its arcs cut). The area
//! law's elastic force is the gradient of a potential (`potential.rs`).
//!
//! Everything is in the partner's frame: the partner's centre at the origin, the particle's at
//! q = (x, y); each body turned by its own angle. As on the plate (section 3), the contact's
//! chord joins the two points where the boundaries cross, the normal n is perpendicular to it
//! (towards the particle), and friction acts at the overlap's centroid. Two facts make the
//! area law's damping exact and keep angular momentum (section 17.8): moving the particle by
//! dq changes the area by -l n.dq, and turning body i by dphi_i changes it by b_i dphi_i, with
//! b_1 = (|p_a - q|^2 - |p_b - q|^2) / 2 and b_2 = (|p_b|^2 - |p_a|^2) / 2 from the chord's ends
//! p_a, p_b (ordered along t = (n_y, -n_x)); b_1 + b_2 = l (q x n), so a rigid turn of the
//! pair leaves the area unchanged.

use super::convex_clip::{cross, sub};
use super::convex_window::{PlacedPolygon, FEW_CORNERS};
use super::pair::{HeldSprings, PairFrame, PairGeometry, Springs};
use super::{Polygon, Shape};
use crate::numerics::trig::sin_cos;
use disc_polygon::{crossing_edges, disc_polygon, held_crossings_value, DiscRole};
use gap::{
    distance_to_polygon, inside, polygons_overlap, separated, separated_gap, vertices_distance,
};
use polygon_polygon::{
    held_overlap, held_overlap_value, held_patch, placed_patch, polygon_patch, Extras,
};
use springs::{
    disc_spring, held_corner_springs, held_springs_value, parted_disc_patch, parted_patch,
    springs_of_held,
};
use std::cell::RefCell;

/// One body of a pair as its contact sees it.
#[derive(Debug, Clone, Copy)]
pub enum PairBody<'a> {
    /// A disc of radius r (m).
    Disc(f64),
    /// A convex polygon, vertices about its centroid.
    Polygon(&'a Polygon),
}

impl PairBody<'_> {
    fn circumradius(&self) -> f64 {
        match self {
            PairBody::Disc(r) => *r,
            PairBody::Polygon(p) => p.circumradius(),
        }
    }
}

/// The overlap of a pair in general position, in the partner's frame.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ShapePatch {
    /// Area (m^2).
    pub area: f64,
    /// Extent of the overlap along n (m): the pair's depth.
    pub depth: f64,
    /// Chord length l (m).
    pub chord: f64,
    /// Unit normal, perpendicular to the chord, from the partner towards the particle.
    pub n: [f64; 2],
    /// The overlap's centroid (m, relative to the partner's centre).
    pub centroid: [f64; 2],
    /// dA/dphi of the particle and of the partner (m^2 / rad).
    pub b: [f64; 2],
    /// The linear law's springs (empty unless the pair asks for them).
    pub springs: Springs,
    /// The area law's potential integral W = integral of dist(p, chord line) dA over the
    /// overlap (m^3; 0 unless the pair asks for it).
    pub potential: f64,
    /// -grad W on the lanes (x, y, phi1, phi2): the area law's elastic force per unit
    /// stiffness (m^2 on the position, m^3 on the angles).
    pub push: [f64; 4],
}

/// A pair of which at least one body has corners.
#[derive(Debug, Clone, Copy)]
pub struct ShapePair<'a> {
    /// The particle.
    pub particle: PairBody<'a>,
    /// The partner.
    pub partner: PairBody<'a>,
    /// Whether the overlap carries the linear law's springs ([`ShapePatch::springs`]).
    pub springs: bool,
}

/// The shortest chord taken for an overlap, in units of the round-off of the centres'
/// coordinates.
const MIN_CHORD_ULPS: f64 = 64.0;

#[inline(always)]
fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The vertices of `p` turned by `phi` and placed with the centroid at `at`.
fn placed(p: &Polygon, at: [f64; 2], phi: f64) -> impl Iterator<Item = [f64; 2]> + '_ {
    let (s, c) = sin_cos(phi);
    p.vertices()
        .iter()
        .map(move |v| [at[0] + c * v.x - s * v.y, at[1] + s * v.x + c * v.y])
}

/// Fills `out` with the vertices of `p` turned by `phi` and placed at `at`.
fn place_into(out: &mut Vec<[f64; 2]>, p: &Polygon, at: [f64; 2], phi: f64) {
    out.clear();
    out.extend(placed(p, at, phi));
}

/// The placed vertices of a pair's two polygons.
type PlacedPair = (Vec<[f64; 2]>, Vec<[f64; 2]>);

thread_local! {
    /// Two polygons' placed vertices (reused: the overlap runs every step).
    static PLACED: RefCell<PlacedPair> = const { RefCell::new((Vec::new(), Vec::new())) };
}

/// Calls `f` with the placed vertices of the particle `a` (at lanes `q`) and of the partner
/// `b` (centred at the origin).
fn with_placed<R>(
    (a, b): (&Polygon, &Polygon),
    q: &[f64; 4],
    f: impl FnOnce(&[[f64; 2]], &[[f64; 2]]) -> R,
) -> R {
    PLACED.with(|cell| {
        let (pa, pb) = &mut *cell.borrow_mut();
        place_into(pa, a, [q[0], q[1]], q[2]);
        place_into(pb, b, [0.0, 0.0], q[3]);
        f(pa, pb)
    })
}

/// The particle `a` at lanes `q` and the partner `b` at the origin, each corner placed only
/// where the contact reads it (the area law's windowed clip).
fn placed_pair<'a>(
    (a, b): (&'a Polygon, &'a Polygon),
    q: &[f64; 4],
) -> (PlacedPolygon<'a>, PlacedPolygon<'a>) {
    (
        PlacedPolygon::new(a, [q[0], q[1]], q[2]),
        PlacedPolygon::new(b, [0.0, 0.0], q[3]),
    )
}

/// Whether two polygons have so few corners that they are clipped whole
/// ([`FEW_CORNERS`]).
fn few_corners((a, b): (&Polygon, &Polygon)) -> bool {
    a.vertices().len() + b.vertices().len() <= FEW_CORNERS
}

impl<'a> ShapePair<'a> {
    /// The pair of `particle` and `partner`; `None` when neither has corners (two discs or
    /// spheres: [`crate::geometry::pair`]).
    pub fn new(particle: &'a Shape, partner: &'a Shape) -> Option<Self> {
        let body = |s: &'a Shape| match s {
            Shape::Polygon(p) => Some(PairBody::Polygon(p)),
            Shape::Disc { r } => Some(PairBody::Disc(*r)),
            Shape::Sphere { .. } => None,
        };
        let pair = ShapePair {
            particle: body(particle)?,
            partner: body(partner)?,
            springs: false,
        };
        let corners = |b: &PairBody| matches!(b, PairBody::Polygon(_));
        (corners(&pair.particle) || corners(&pair.partner)).then_some(pair)
    }

    /// The sum of the circumradii: no contact beyond this centre distance.
    pub fn reach(&self) -> f64 {
        self.particle.circumradius() + self.partner.circumradius()
    }

    /// The overlap at lanes `q` = (x, y, phi1, phi2); `None` when apart (or touching in a
    /// point).
    pub fn patch(&self, q: &[f64; 4]) -> Option<ShapePatch> {
        let mut p = ShapePatch::default();
        self.patch_into(q, &mut p).then_some(p)
    }

    /// [`Self::patch`] written into `p` (`false`: apart, `p` unspecified): the overlap's ~0.3 kB
    /// handed up through the clip's closures by value cost two 120-gons a twentieth of their
    /// step and two 12-gons an eighth in copies.
    fn patch_into(&self, q: &[f64; 4], p: &mut ShapePatch) -> bool {
        let at = [q[0], q[1]];
        match self.polygons() {
            // The linear law's springs read every corner, and few corners are clipped whole
            // faster placed all at once (the same result as the window's, bit for bit).
            Some(ab) if self.springs || few_corners(ab) => with_placed(ab, q, |pa, pb| {
                let extras = if self.springs {
                    Extras::Springs
                } else {
                    Extras::Push
                };
                polygon_patch(pa, pb, at, self.reach(), extras, p)
            }),
            Some(ab) => {
                let (pa, pb) = placed_pair(ab, q);
                placed_patch(&pa, &pb, at, self.reach(), p)
            }
            None => {
                let Some((c, r, placed, sign)) = self.disc_and_polygon(q) else {
                    return false;
                };
                match self.disc_with_polygon(c, r, placed, at, (sign, None)) {
                    Some(disc) => {
                        *p = disc;
                        true
                    }
                    None => false,
                }
            }
        }
    }

    /// The two polygons, when both bodies are polygons.
    fn polygons(&self) -> Option<(&'a Polygon, &'a Polygon)> {
        match (self.particle, self.partner) {
            (PairBody::Polygon(a), PairBody::Polygon(b)) => Some((a, b)),
            _ => None,
        }
    }

    /// A disc with a polygon at lanes `q`: the disc's centre and radius, the polygon with where
    /// it is placed and how far turned, and the sign of the disc's push on the particle (as for
    /// [`disc_spring`]); `None` for two polygons or two discs.
    fn disc_and_polygon(&self, q: &[f64; 4]) -> Option<DiscAndPolygon<'a>> {
        let at = [q[0], q[1]];
        match (self.particle, self.partner) {
            (PairBody::Disc(r), PairBody::Polygon(b)) => Some((at, r, (b, [0.0, 0.0], q[3]), 1.0)),
            (PairBody::Polygon(a), PairBody::Disc(r)) => Some(([0.0, 0.0], r, (a, at, q[2]), -1.0)),
            _ => None,
        }
    }

    /// The linear law's disc spring of a disc-polygon pair at lanes `q`, signed where no
    /// overlap is resolved ([`parted_disc_patch`]).
    fn parted_disc_patch(&self, q: &[f64; 4]) -> Option<ShapePatch> {
        let (c, r, (poly, at, phi), sign) = self.disc_and_polygon(q)?;
        Some(PLACED.with(|cell| {
            let (verts, _) = &mut *cell.borrow_mut();
            place_into(verts, poly, at, phi);
            parted_disc_patch(c, r, verts, [q[0], q[1]], sign)
        }))
    }

    /// Calls `f` with a disc-polygon pair's polygon at lanes `q`, placed relative to the disc's
    /// centre, and the disc's radius; `None` for two polygons.
    fn with_disc_centred<R>(
        &self,
        q: &[f64; 4],
        f: impl FnOnce(&[[f64; 2]], f64) -> R,
    ) -> Option<R> {
        let (c, r, (poly, at, phi), _) = self.disc_and_polygon(q)?;
        Some(PLACED.with(|cell| {
            let (verts, _) = &mut *cell.borrow_mut();
            place_into(verts, poly, sub(at, c), phi);
            f(verts, r)
        }))
    }

    /// The particle's and the partner's circumradii.
    fn circumradii(&self) -> [f64; 2] {
        [self.particle.circumradius(), self.partner.circumradius()]
    }

    /// The contact's frame from the overlap `p` at lanes `q`.
    fn frame_of(&self, p: &ShapePatch, q: &[f64; 4]) -> PairFrame {
        // The contact's normal: the chord's, or under the linear law the direction of the
        // springs' push, so that friction acts across the normal force; turned to the side
        // of the springs' own directions (their sum, exact), so that a lone held spring's
        // normal keeps its direction where its depth (signed, see `frame_held`) passes zero
        // at the piece's end. Not to the chord's side: just past a touch, at a chord of
        // 2e-16 m across a corner, the chord's normal lay across the push and turned it into
        // the partner (twin triangles: friction's sign reversed at the touch, e_T 0.03 off).
        let n = if self.springs {
            let push = [p.springs.push[0], p.springs.push[1]];
            let sum = [p.springs.sum[0], p.springs.sum[1]];
            let side = if sum == [0.0; 2] { p.n } else { sum };
            let norm = push[0].hypot(push[1]).copysign(dot(push, side));
            if norm != 0.0 {
                [push[0] / norm, push[1] / norm]
            } else {
                p.n
            }
        } else {
            p.n
        };
        let (c, at) = (p.centroid, [q[0], q[1]]);
        let t = [n[1], -n[0]];
        // Each pair of levers sums to -(q x u), so that the torques cancel the orbit's
        // (angular momentum); the partner's is taken from that sum, to the last bit.
        let lever = |l1: f64, u: [f64; 2]| [l1, -l1 - cross(at, u)];
        let arm = sub(c, at);
        PairFrame {
            n,
            depth: p.depth,
            area: p.area,
            chord: p.chord,
            area_push: p.push,
            lever_rate_area: lever(
                if p.chord > 0.0 {
                    -p.b[0] / p.chord
                } else {
                    0.0
                },
                n,
            ),
            lever_t: lever(cross(arm, t), t),
            springs: p.springs,
        }
    }

    /// [`separated_gap`] of two polygons with few corners ([`few_corners`]) at lanes `q`;
    /// `None` for other bodies. Many corners are not tried: their windowed clip tells bodies
    /// apart in fewer instructions than the line's test over every corner (two 120-gons ran
    /// 1.9 % more with it, two 12-gons, whose clip places and clips every corner, 1.4 % fewer).
    fn separated_gap(&self, q: &[f64; 4]) -> Option<f64> {
        let ab = self.polygons().filter(|&ab| few_corners(ab))?;
        PLACED.with(|cell| {
            let (pa, pb) = &mut *cell.borrow_mut();
            let (body_a, body_b) = placed_pair(ab, q);
            place_into(pa, ab.0, [q[0], q[1]], q[2]);
            place_into(pb, ab.1, [0.0, 0.0], q[3]);
            separated_gap((pa, &body_a), (pb, &body_b))
        })
    }

    /// The distance between the bodies at lanes `q` (m; 0 when they touch or overlap).
    pub fn gap(&self, q: &[f64; 4]) -> f64 {
        let at = [q[0], q[1]];
        PLACED.with(|cell| {
            let (pa, pb) = &mut *cell.borrow_mut();
            match (self.particle, self.partner) {
                (PairBody::Polygon(a), PairBody::Polygon(b)) => {
                    let (body_a, body_b) = placed_pair((a, b), q);
                    place_into(pa, a, at, q[2]);
                    place_into(pb, b, [0.0, 0.0], q[3]);
                    let to_b = vertices_distance((pa, &body_a), (pb, &body_b), 1);
                    let to_a = vertices_distance((pb, &body_b), (pa, &body_a), 0);
                    let apart = to_b.min(to_a);
                    // Overlapping, 0; else the corners' least distance. A corner inside the
                    // other body (0) and a line of one body with the other wholly outside
                    // (apart) tell it without the clip.
                    if apart == 0.0 || separated((pa, &body_a), (pb, &body_b)) {
                        return apart;
                    }
                    if polygons_overlap(&body_a, &body_b, at) {
                        0.0
                    } else {
                        apart
                    }
                }
                (PairBody::Disc(r), PairBody::Polygon(b)) => {
                    place_into(pb, b, [0.0, 0.0], q[3]);
                    (distance_to_polygon(at, pb) - r).max(0.0)
                }
                (PairBody::Polygon(a), PairBody::Disc(r)) => {
                    place_into(pa, a, at, q[2]);
                    (distance_to_polygon([0.0, 0.0], pa) - r).max(0.0)
                }
                (PairBody::Disc(r1), PairBody::Disc(r2)) => (at[0].hypot(at[1]) - r1 - r2).max(0.0),
            }
        })
    }

    /// The overlap of the disc of radius `r` centred at `c` with the polygon placed at `at`
    /// and turned by `phi`, the particle's centre at `q`: the polygon's vertices placed once
    /// for the clip and the linear law's spring (`sign` as for [`disc_spring`]); the area
    /// law's crossings continued from the edges `held` ([`HeldSprings::disc_crossings`]).
    fn disc_with_polygon(
        &self,
        c: [f64; 2],
        r: f64,
        (poly, at, phi): (&Polygon, [f64; 2], f64),
        q: [f64; 2],
        (sign, held): (f64, Option<[u32; 2]>),
    ) -> Option<ShapePatch> {
        PLACED.with(|cell| {
            let (verts, _) = &mut *cell.borrow_mut();
            place_into(verts, poly, at, phi);
            let role = DiscRole {
                push: !self.springs,
                disc_is_particle: sign > 0.0,
                held,
            };
            let mut p = disc_polygon(c, r, verts.iter().copied(), q, role)?;
            if self.springs {
                p.springs = disc_spring(c, r, verts, q, sign);
            }
            Some(p)
        })
    }

    /// The height of the particle's centre, straight above the partner's, at which the two
    /// touch with orientations `phi1`, `phi2` (rad) (the first touch of section 17.8).
    pub fn touch_height(&self, phi1: f64, phi2: f64) -> f64 {
        touch::touch_height(self.particle, self.partner, [phi1, phi2])
    }
}

impl PairGeometry for ShapePair<'_> {
    const CORNERS: bool = true;

    fn frame(&self, q: &[f64; 4]) -> Option<PairFrame> {
        let mut p = ShapePatch::default();
        self.patch_into(q, &mut p).then(|| self.frame_of(&p, q))
    }

    fn holds_springs(&self) -> bool {
        // A disc with a polygon: the area law's crossings (its one linear spring is smooth).
        self.polygons().is_some() || !self.springs
    }

    fn held_springs(&self, q: &[f64; 4]) -> HeldSprings {
        match self.polygons() {
            Some(ab) if self.springs => with_placed(ab, q, |pa, pb| {
                held_corner_springs(pa, pb, [q[0], q[1]], self.circumradii())
            }),
            Some(ab) => {
                let (pa, pb) = placed_pair(ab, q);
                held_overlap(&pa, &pb, [q[0], q[1]])
            }
            None => HeldSprings {
                disc_crossings: self.with_disc_centred(q, crossing_edges).flatten(),
                ..HeldSprings::default()
            },
        }
    }

    fn frame_held(&self, q: &[f64; 4], held: &HeldSprings) -> Option<PairFrame> {
        if !self.springs {
            // The area law on two polygons: the held overlap continued (its force smooth up
            // to the located switch where a crossing passes a corner).
            return match self.polygons() {
                Some(ab) if !held.overlap.is_empty() => {
                    let (pa, pb) = placed_pair(ab, q);
                    let mut p = ShapePatch::default();
                    held_patch(&pa, &pb, [q[0], q[1]], held, &mut p).then(|| self.frame_of(&p, q))
                }
                None if held.disc_crossings.is_some() => {
                    let (c, r, placed, sign) = self.disc_and_polygon(q)?;
                    let both = (sign, held.disc_crossings);
                    let p = self.disc_with_polygon(c, r, placed, [q[0], q[1]], both)?;
                    Some(self.frame_of(&p, q))
                }
                _ => self.frame(q),
            };
        }
        let Some(ab) = self.polygons() else {
            // A disc with a polygon: its one spring is smooth (C1 where the nearest feature
            // changes) and needs no holding, only to go on where no overlap is resolved.
            let p = self.patch(q).or_else(|| self.parted_disc_patch(q))?;
            return Some(self.frame_of(&p, q));
        };
        let at = [q[0], q[1]];
        // The polygons placed once for the overlap (without the unheld springs) and the held
        // springs. Where no overlap is resolved (just after the touch, just past the parting)
        // the held springs go on, so that the force is smooth through the piece's ends, where
        // the switches are located on the step's dense output.
        let p = with_placed(ab, q, |pa, pb| {
            let springs = springs_of_held(pa, pb, at, held);
            let mut p = ShapePatch::default();
            if polygon_patch(pa, pb, at, self.reach(), Extras::Nothing, &mut p) {
                Some(ShapePatch { springs, ..p })
            } else {
                parted_patch(pa, pb, held, springs)
            }
        })?;
        Some(self.frame_of(&p, q))
    }

    fn held_springs_value(&self, q: &[f64; 4], held: &HeldSprings) -> f64 {
        match self.polygons() {
            Some(ab) if self.springs => with_placed(ab, q, |pa, pb| {
                held_springs_value(pa, pb, [q[0], q[1]], self.circumradii(), held)
            }),
            Some(ab) if !held.overlap.is_empty() => {
                let (pa, pb) = placed_pair(ab, q);
                held_overlap_value(&pa, &pb, held)
            }
            None => held
                .disc_crossings
                .and_then(|e| self.with_disc_centred(q, |v, r| held_crossings_value(v, r, e)))
                .unwrap_or(f64::NEG_INFINITY),
            _ => f64::NEG_INFINITY,
        }
    }
    fn signed_depth(&self, q: &[f64; 4]) -> f64 {
        // Two polygons a line separates: no patch to look for (the flights' gaps, the
        // parting's samples past it, where the clip cost as much as the gap).
        if let Some(apart) = self.separated_gap(q) {
            return -apart;
        }
        match self.patch(q) {
            Some(p) => p.depth,
            None => -self.gap(q),
        }
    }

    fn touch_height(&self, phi1: f64, phi2: f64) -> f64 {
        ShapePair::touch_height(self, phi1, phi2)
    }

    fn reach(&self) -> f64 {
        ShapePair::reach(self)
    }
}

/// A disc with a polygon ([`ShapePair::disc_and_polygon`]): the disc's centre and radius, the
/// polygon with where it is placed and how far turned, the sign of the disc's push.
type DiscAndPolygon<'a> = ([f64; 2], f64, (&'a Polygon, [f64; 2], f64), f64);

/// The patch from the overlap's area, centroid, chord and vertices, the particle's centre at
/// `q` (no springs); `across`, where known, a vector perpendicular to the chord that is known
/// more precisely than the chord's own direction where the chord is short (see
/// `disc_polygon`).
fn assemble(
    q: [f64; 2],
    area: f64,
    centroid: [f64; 2],
    chord: [[f64; 2]; 2],
    points: &[([f64; 2], bool)],
    across: Option<[f64; 2]>,
) -> Option<ShapePatch> {
    let mut p = ShapePatch::default();
    let corners = points.iter().map(|&(x, _)| x);
    assemble_into(&mut p, q, (area, centroid), chord, corners, across).then_some(p)
}

/// [`assemble`] written into `p` (no springs, potential or push: those of `p` are left as
/// they are); `false` where there is no overlap.
fn assemble_into(
    p: &mut ShapePatch,
    q: [f64; 2],
    (area, centroid): (f64, [f64; 2]),
    [p0, p1]: [[f64; 2]; 2],
    points: impl Iterator<Item = [f64; 2]>,
    across: Option<[f64; 2]>,
) -> bool {
    let d = sub(p1, p0);
    // The plain root, not `hypot` (a call, 3 % of two 120-gons' impact): the chord's square
    // stays in range for bodies of 1e-100 m to 1e100 m (shorter chords are refused below).
    let chord = dot(d, d).sqrt();
    // A chord at the round-off of the coordinates is a touch, not an overlap: its direction
    // (the normal) would be noise.
    let resolution = MIN_CHORD_ULPS * f64::EPSILON * (q[0].abs() + q[1].abs());
    if !(chord > resolution && area > 0.0) {
        return false;
    }
    // The chord's direction carries the round-off of its ends over its length; `across`
    // carries theirs over its own, and is taken where that is the longer.
    let across = across.map(|m| (m, dot(m, m).sqrt()));
    let mut n = match across {
        Some((m, len)) if len > chord => [m[0] / len, m[1] / len],
        _ => [-d[1] / chord, d[0] / chord],
    };
    if dot(n, sub(q, p0)) < 0.0 {
        n = [-n[0], -n[1]];
    }
    // Order the chord's ends along t = (n_y, -n_x).
    let t = [n[1], -n[0]];
    let (pa, pb) = if dot(d, t) >= 0.0 { (p0, p1) } else { (p1, p0) };
    let sq = |p: [f64; 2]| dot(p, p);
    let b = [
        0.5 * (sq(sub(pa, q)) - sq(sub(pb, q))),
        0.5 * (sq(pb) - sq(pa)),
    ];
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    // Plain comparisons: f64::min and max's NaN handling costs instructions these finite
    // values do not need (the same result).
    for x in points {
        let s = dot(n, x);
        if s < lo {
            lo = s;
        }
        if s > hi {
            hi = s;
        }
    }
    p.area = area;
    p.depth = (hi - lo).max(0.0);
    p.chord = chord;
    p.n = n;
    p.centroid = centroid;
    p.b = b;
    true
}

mod disc_polygon;
mod gap;
mod polygon_polygon;
pub(crate) mod potential;
#[cfg(test)]
mod potential_tests;
mod springs;
#[cfg(test)]
mod tests;
mod touch;
