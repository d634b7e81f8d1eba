//! The contact law in a held mode: the overlap and the forces of the piece's formulas,
//! continued smoothly a little beyond the piece's end, and the time derivative of the state.

use super::piece::{Mode, Tan, Touch};
use super::{State, NS, OM, PHI, VX, VY, W_D, W_EL, W_T, X, XI, Y};
use crate::geometry::crossing_x;
use crate::geometry::disc_segment_at;
use crate::geometry::{Overlap, Polygon, Shape};
use crate::law::{carrying, trial_force, vertex_springs, Forces, NormalForce, StickState};
use crate::model::{Model, NormalLaw};
use crate::numerics::trig::sin_cos;
use nalgebra::Vector2;

/// Everything the force evaluation yields besides the derivative.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Eval {
    pub(super) forces: Forces,
    /// F_el + F_d before the clip.
    pub(super) fn_raw: f64,
    /// Tangential velocity of the contact point.
    pub(super) v_t: f64,
    /// Trial force of a sticking spring, -k_t xi - c_t v_t.
    pub(super) trial: f64,
    /// Depth of the lowest point (signed).
    pub(super) depth: f64,
}

/// The ODE of one impact: the model, its corners and the error control's settings.
pub(super) struct Reference<'a> {
    pub(super) model: &'a Model,
    pub(super) verts: &'a [Vector2<f64>],
    pub(super) mu: f64,
    /// 1 / (tol x the error scale) of each state component: its local error's weight in the
    /// step's scaled norm (a product per component where a division cost ~3 % of the disc's
    /// time).
    pub(super) error_weight: State,
    pub(super) tol: f64,
    /// Time step of the directional finite differences of the slip -> stick test.
    pub(super) fd_step: f64,
    /// A pull of the unclipped normal force below -force_tol is a missed clip switch.
    pub(super) force_tol: f64,
    /// The normal law's force on an overlap (the fixed-step path's).
    pub(super) normal: NormalForce,
    /// 1 / mass and 1 / moment of inertia: the accelerations as products, since a division's
    /// latency sat on the chain from one stage to the next.
    pub(super) inv_mass: f64,
    /// See `inv_mass`.
    pub(super) inv_inertia: f64,
    /// The polygon whose long held runs take their overlap from its summed edges
    /// ([`LONG_RUN`]): on the adaptive path, not the reference's (whose tolerance is below
    /// the sums' rounding), nor under the linear law (one spring per corner).
    pub(super) summed: Option<&'a Polygon>,
}

/// Held runs of at least this many corners take their overlap from the polygon's summed edges
/// (`geometry/chain.rs`) rather than a walk over every corner (94 % of a 4096-gon's time deep in
/// a soft plate): the sums' rounding, ~1e-16 of the polygon's area, is below ~1e-12 of the
/// overlap of 64 corners of a 4096-gon, far below the adaptive path's tolerances (>= 1e-10).
pub(super) const LONG_RUN: usize = 64;

impl<'a> Reference<'a> {
    pub(super) fn linear(&self) -> Option<(f64, f64)> {
        match self.model.scene.normal_law {
            NormalLaw::Linear { kn, cn } => Some((kn, cn)),
            NormalLaw::Area | NormalLaw::Hertz { .. } => None,
        }
    }

    /// World position of corner `k` for centre height `y` and orientation (sin, cos):
    /// x relative to the centre of mass, y absolute.
    #[inline]
    pub(super) fn corner(&self, k: usize, y: f64, sc: (f64, f64)) -> (f64, f64) {
        let v = &self.verts[k % self.verts.len()];
        (sc.1 * v.x - sc.0 * v.y, y + sc.0 * v.x + sc.1 * v.y)
    }

    /// The overlap of a polygon whose submerged corners are held fixed: the crossing points on
    /// the two boundary edges are placed on y = 0 by linear interpolation even when a held
    /// corner has just risen above the plate (a smooth continuation of the clip).
    pub(super) fn held_polygon(
        &self,
        first: usize,
        len: usize,
        low: usize,
        y: f64,
        phi: f64,
    ) -> Overlap {
        let sc = sin_cos(phi);
        if let Some(poly) = self.summed.filter(|_| len >= LONG_RUN) {
            let low = poly.lowest_vertex_near(low, sc.0, sc.1);
            return poly.chain.overlap(self.verts, (first, len, low), y, sc);
        }
        let n = self.verts.len();
        let a = (first + n - 1) % n;
        let last = (first + len - 1) % n;
        let b = (last + 1) % n;
        // The geometry's crossing (interpolated from the end nearer the plate, so slivers
        // keep their precision); an edge parallel to the plate, possible only in the
        // continuation, takes its midpoint.
        let crossing = |p: (f64, f64), q: (f64, f64)| {
            let x = crossing_x(p, q);
            if x.is_finite() {
                x
            } else {
                0.5 * (p.0 + q.0)
            }
        };
        let p_first = self.corner(first, y, sc);
        let p_last = self.corner(last, y, sc);
        let xp = crossing(self.corner(a, y, sc), p_first);
        let xq = crossing(p_last, self.corner(b, y, sc));
        // Shoelace over P, corners, Q (relative to P for precision); the chord Q -> P closes it.
        let (mut area2, mut mx, mut my) = (0.0, 0.0, 0.0);
        let mut prev = (0.0, 0.0);
        let (mut depth, mut x_low) = (f64::NEG_INFINITY, p_first.0);
        for j in 0..=len {
            let cur = if j < len {
                let c = self.corner(first + j, y, sc);
                if -c.1 > depth {
                    (depth, x_low) = (-c.1, c.0);
                }
                (c.0 - xp, c.1)
            } else {
                (xq - xp, 0.0)
            };
            let w = prev.0 * cur.1 - cur.0 * prev.1;
            area2 += w;
            mx += (prev.0 + cur.0) * w;
            my += (prev.1 + cur.1) * w;
            prev = cur;
        }
        let (cx, cy) = if area2.abs() > 0.0 {
            (xp + mx / (3.0 * area2), my / (3.0 * area2))
        } else {
            (xp, 0.0)
        };
        let area = 0.5 * area2;
        Overlap {
            area,
            cx,
            cy,
            chord: xq - xp,
            x_mid: 0.5 * (xp + xq),
            depth,
            x_low,
            first_moment: -area * cy,
            corners: crate::geometry::Corners {
                first: first as u32,
                count: len as u32,
            },
        }
    }

    /// Overlap in the held mode; `None` in free flight. Inlined: out of line (it has two
    /// callers) the law's evaluation lost its inlining and the disc a tenth of its speed.
    #[inline(always)]
    pub(super) fn overlap(&self, touch: Touch, y: f64, phi: f64) -> Option<Overlap> {
        match touch {
            Touch::Off => None,
            Touch::Disc => {
                let r = self.model.r;
                let depth = r - y;
                Some(match self.model.scene.shape {
                    // The disc's segment built from its numbers, not through an Option (see
                    // `disc_segment_at`).
                    Shape::Disc { .. } if depth > 0.0 => disc_segment_at(r, y, depth),
                    // Beyond the separation point the contact continues as nothing.
                    ref shape => shape.overlap(y, phi).unwrap_or(Overlap {
                        cy: y - r,
                        depth,
                        ..Overlap::default()
                    }),
                })
            }
            Touch::Poly { first, len, low } => Some(self.held_polygon(first, len, low, y, phi)),
        }
    }

    /// Forces and the time derivative of the state in mode `m`: the law's own functions
    /// ([`NormalForce`], [`vertex_springs`], [`trial_force`], [`Forces::on_overlap`]) on the
    /// held overlap, with the clip and the tangential law that the mode holds.
    #[inline]
    pub(super) fn eval(&self, m: &Mode, s: &State) -> (State, Eval) {
        let mut d = [0.0; NS];
        let mut e = Eval::default();
        self.eval_to(m, s, &mut d, &mut e);
        (d, e)
    }

    /// [`Self::eval`] into `d_out` and `e_out`: the Runge-Kutta stages write each derivative
    /// where the next stage reads it (returned and copied into place, the ~0.3 kB result cost
    /// 8 % of the adaptive path's time on the disc and 13 % on the 120-gon).
    #[inline(never)]
    pub(super) fn eval_to(&self, m: &Mode, s: &State, d_out: &mut State, e_out: &mut Eval) {
        let model = self.model;
        let mut d = [0.0; NS];
        d[X] = s[VX];
        d[Y] = s[VY];
        d[PHI] = s[OM];
        let Some(o) = self.overlap(m.touch, s[Y], s[PHI]) else {
            let depth = model.scene.shape.touch_height(s[PHI]) - s[Y];
            *d_out = d;
            *e_out = Eval {
                depth,
                ..Eval::default()
            };
            return;
        };
        let v = [s[VX], s[VY], s[OM]];
        let (f_el, f_d, x_el, x_damp) = match (self.linear(), m.touch) {
            // One spring-dashpot per held corner, continued smoothly beyond a crossing.
            (Some((kn, cn)), Touch::Poly { first, len, .. }) => {
                let sc = sin_cos(s[PHI]);
                let held = (first..first + len).map(|k| {
                    let (x, h) = self.corner(k, s[Y], sc);
                    (-h, x)
                });
                vertex_springs(kn, cn, held, &v)
            }
            // The area law, the disc's lowest point, the sphere's Hertz law: beyond
            // separation the disc's or sphere's contact continues as nothing.
            _ => self.normal.on_overlap(&o, &v),
        };
        let fn_raw = f_el + f_d;
        let (f_el, f_d) = if m.clip_on { (f_el, f_d) } else { (0.0, 0.0) };
        let f_n = f_el + f_d;
        let v_t = s[VX] - s[OM] * (o.cy - s[Y]);
        // (k_t, 1, c_t) for the linear spring; Mindlin's, incremental in the force, (1, k_t, c_t)
        // at this depth, xi then being minus the elastic force (as the displacement: (k_t, 1,
        // c_t)). Only the sphere has Mindlin's spring: its depth r - y falls at -v_y.
        let (k_xi, rate, ct) = model.spring(o.depth);
        let trial = trial_force(k_xi, s[XI], ct, v_t);
        let (f_t, stick) = match m.tan {
            Tan::None => (0.0, StickState::None),
            Tan::Free => (0.0, StickState::Slip),
            Tan::Stick => (trial, StickState::Stick),
            Tan::Slip(sg) => (self.mu * f_n * sg, StickState::Slip),
        };
        let forces = Forces::on_overlap(o, s[Y], f_n, (f_el, f_d, x_el, x_damp), f_t, stick);
        d[VX] = f_t * self.inv_mass;
        d[VY] = f_n * self.inv_mass;
        d[OM] = forces.torque * self.inv_inertia;
        // A rescaled history also shrinks once the contact unloads (its mode says when).
        let shrink = || model.history_shrink(o.depth, -s[VY]) * s[XI];
        d[XI] = match m.tan {
            Tan::Stick if m.unloading => rate * v_t + shrink(),
            Tan::Stick => rate * v_t,
            _ => 0.0,
        };
        (d[W_EL], d[W_D], d[W_T]) = forces.powers(s[Y], &v);
        let e = Eval {
            forces,
            fn_raw,
            v_t,
            trial,
            depth: o.depth,
        };
        (*d_out, *e_out) = (d, e);
    }

    /// The spring elongation the law implies: integrated while sticking, algebraic otherwise.
    pub(super) fn xi_of(&self, m: &Mode, s: &State, e: &Eval) -> f64 {
        let (kt, _, ct) = self.model.spring(e.depth);
        match m.tan {
            Tan::Stick => s[XI],
            Tan::Slip(_) => carrying(e.forces.f_t, kt, ct, e.v_t),
            Tan::Free => carrying(0.0, kt, ct, e.v_t),
            Tan::None => 0.0,
        }
    }
}
