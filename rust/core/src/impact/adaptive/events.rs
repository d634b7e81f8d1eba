//! The switches that end a piece: their event functions (continuous, <= 0 while the piece's
//! mode holds), which of them can end a given mode, and where inside a step one fires.

use super::law::{Eval, Reference};
use super::piece::{Event, Mode, Tan, Touch};
use super::step::Step;
use super::switches::{first_positive_sample, locate_switch, switch_precision};
use super::{State, OM, PHI, VX, VY, Y};
use crate::geometry::{disc_arm_per_depth, Shape};
use crate::model::NormalLaw;
use crate::numerics::trig::sin_cos;

/// Margin of the slip -> stick event function, relative to the sum of its terms' magnitudes
/// (see `Reference::slip_to_stick`).
const STICK_MARGIN: f64 = 1e-9;

impl Reference<'_> {
    /// The events that can end a piece of mode `m` (at most six; a fixed array, as this runs
    /// once per step and an allocation per step showed in the profile).
    pub(super) fn candidates(&self, m: &Mode) -> impl Iterator<Item = Event> {
        let mut out = [None; 6];
        let mut push = |ev: Event| {
            if let Some(slot) = out.iter_mut().find(|e| e.is_none()) {
                *slot = Some(ev);
            }
        };
        match m.touch {
            Touch::Off => push(Event::Touch),
            Touch::Disc => push(Event::Separate),
            Touch::Poly { len, .. } => {
                let n = self.verts.len();
                if len + 1 < n {
                    push(Event::EnterLeft);
                    push(Event::EnterRight);
                }
                push(Event::LeaveLeft);
                if len > 1 {
                    push(Event::LeaveRight);
                }
            }
        }
        if m.touch != Touch::Off {
            if !m.clip_hold {
                push(if m.clip_on {
                    Event::ClipOff
                } else {
                    Event::ClipOn
                });
            }
            match m.tan {
                Tan::Stick => push(Event::ToSlip),
                Tan::Slip(_) => push(Event::ToStick),
                Tan::None | Tan::Free => {}
            }
            if !m.unloading && self.model.history.rescales() {
                push(Event::Unload);
            }
        }
        out.into_iter().flatten()
    }

    /// The event function: > 0 once the piece's mode no longer holds.
    pub(super) fn event_value(&self, m: &Mode, ev: Event, s: &State) -> f64 {
        self.event_value_given(m, ev, s, None)
    }

    /// [`Self::event_value`], with the evaluation at `s` (derivative and forces) when known.
    pub(super) fn event_value_given(
        &self,
        m: &Mode,
        ev: Event,
        s: &State,
        known: Option<(&State, &Eval)>,
    ) -> f64 {
        // Where the evaluation is known (a step's end, checked at every step) the clip's
        // function is the plain one, which has the same sign: its value is read only once the
        // switch fired, and `locate` then takes the smooth one (see `disc_push`).
        if let Some(push) = (known.is_none() && self.smooth_clip(m, ev))
            .then(|| self.disc_push(s))
            .flatten()
        {
            return if ev == Event::ClipOff { -push } else { push };
        }
        let eval = || known.map_or_else(|| self.eval(m, s), |(d, e)| (*d, *e));
        let (y, phi) = (s[Y], s[PHI]);
        let n = self.verts.len().max(1);
        let poly = |k: usize| self.corner(k, y, sin_cos(phi)).1;
        match (ev, m.touch) {
            (Event::Touch, _) => self.model.scene.shape.touch_height(phi) - y,
            (Event::Separate, _) => y - self.model.r,
            (Event::EnterLeft, Touch::Poly { first, .. }) => -poly(first + n - 1),
            (Event::EnterRight, Touch::Poly { first, len, .. }) => -poly(first + len),
            (Event::LeaveLeft, Touch::Poly { first, .. }) => poly(first),
            (Event::LeaveRight, Touch::Poly { first, len, .. }) => poly(first + len - 1),
            (Event::ClipOff, _) => -eval().1.fn_raw,
            (Event::ClipOn, _) => {
                // Only an overlap can push: once every held corner has risen above the plate
                // the held continuation is no contact, whatever sign its force has.
                let e = eval().1;
                if e.depth > 0.0 {
                    e.fn_raw
                } else {
                    f64::NEG_INFINITY
                }
            }
            (Event::ToSlip, _) => {
                // Stick starts with the spring on the cone (|trial| = mu F_n up to round-off):
                // a margin of 1e-9 mu F_n keeps round-off from ending it at once (a chatter of
                // zero-length pieces, then a sliding mode the tight run never enters). 1e-12
                // was too little once switches were located to the last bits: near
                // separation the disc's segment area carries ~2e-12 of round-off.
                self.to_slip_value(&eval().1)
            }
            (Event::ToStick, _) => self.slip_to_stick(m, s, eval),
            // The sphere's depth r - y grows while v_y < 0.
            (Event::Unload, _) => s[VY],
            _ => f64::NEG_INFINITY,
        }
    }

    /// The clip's event function on a disc or sphere in contact (depth > 0), from its height
    /// and v_y alone: F_el + F_d divided by the power of the depth its damping carries (the
    /// area law's chord, the Tsuji dashpot's delta^(1/4); 1 for the linear law), which both
    /// forces share. Near separation, where the clip switches off, F_el + F_d is that root
    /// times a smooth function: without it the root finder interpolates the smooth part
    /// (the area law: 6.3 -> 3.9 evaluations per switch on the disc grid), and each evaluation
    /// forms the segment and the normal law, not the whole law. `None` at or beyond
    /// separation (the held continuation decides there).
    fn disc_push(&self, s: &State) -> Option<f64> {
        // The shape's own overlap (the held mode's in contact): the mode's, called here too,
        // lost its inlining into the law's evaluation (16 % more instructions per step).
        let o = self.model.scene.shape.overlap(s[Y], s[PHI])?;
        let root = match self.model.scene.normal_law {
            NormalLaw::Area => o.chord,
            NormalLaw::Hertz { .. } => o.depth.sqrt().sqrt(),
            NormalLaw::Linear { .. } => 1.0,
        };
        if !(o.depth > 0.0 && root > 0.0) {
            return None;
        }
        let (f_el, f_d, _, _) = self.normal.on_overlap(&o, &[s[VX], s[VY], s[OM]]);
        Some((f_el + f_d) / root)
    }

    /// Whether event `ev` of mode `m` is a disc's (or sphere's) clip switch, whose function
    /// is [`Self::disc_push`] where no evaluation is known.
    fn smooth_clip(&self, m: &Mode, ev: Event) -> bool {
        m.touch == Touch::Disc && matches!(ev, Event::ClipOff | Event::ClipOn)
    }

    /// The stick -> slip event function at an evaluation: |F_trial| - mu F_n, with the
    /// margin of `STICK_MARGIN` (see `event_value_given`).
    pub(super) fn to_slip_value(&self, e: &Eval) -> f64 {
        e.trial.abs() - self.mu * e.forces.fy * (1.0 + STICK_MARGIN)
    }

    /// Positive when a sticking spring would stay inside the Coulomb cone: the value
    /// mu dF_n/dt + s (k_t v_t + c_t dv_t/dt) (plus Mindlin's drift,
    /// [`crate::model::Model::elastic_drift`]), both rates along the motion of the slipping
    /// body: in closed form on the exact disc (area or linear law, linear spring), by central
    /// differences elsewhere.
    fn slip_to_stick(&self, m: &Mode, s: &State, eval: impl FnOnce() -> (State, Eval)) -> f64 {
        let Tan::Slip(sg) = m.tan else {
            return f64::NEG_INFINITY;
        };
        let (d, e) = eval();
        if m.touch == Touch::Disc && e.depth <= 0.0 {
            // Beyond separation the disc's contact continues as nothing.
            return f64::NEG_INFINITY;
        }
        let rates = self
            .disc_rates(s, &d, &e)
            .or_else(|| self.polygon_rates(m, s, &d, &e));
        let (dfn, ddamp) = rates.unwrap_or_else(|| self.differenced_rates(m, s, &d, &e));
        let (k_xi, rate, ct) = self.model.spring(e.depth);
        // Located where the value exceeds 1e-9 of its terms, the switch is robustly past its
        // root (central differences carry ~1e-11 of the terms, the closed form round-off), and
        // late by only that fraction of the value's rise time: a switch located where the
        // value is noise leaves a spring on the cone that does not move inside, and stick and
        // slip chatter at once (the disc at theta 84, mu 0.8 lost a stick phase of 0.004 t_c
        // that way, e_T off by 1e-5 at tol 1e-6).
        // Mindlin's elastic force -k_xi xi also drifts with the depth where its history is
        // the displacement or rescaled: k_xi xi = -(F_t + c_t v_t) in slip (zero otherwise).
        let drift = if self.model.mindlin {
            let elastic = e.forces.f_t + ct * e.v_t;
            self.model.elastic_drift(e.depth, -s[VY], m.unloading) * elastic
        } else {
            0.0
        };
        let terms = [
            self.mu * dfn,
            sg * k_xi * rate * e.v_t,
            sg * ddamp,
            -sg * drift,
        ];
        let noise = STICK_MARGIN * terms.iter().map(|t| t.abs()).sum::<f64>();
        terms.iter().sum::<f64>() - noise
    }

    /// (dF_n/dt, d(c_t v_t)/dt) on the exact disc with the area or linear law and the linear
    /// spring, in closed form from the state `s`, its derivative `d` and the evaluation `e`
    /// there: F_n's rate from the law ([`NormalForce::rate_on_disc`]); v_t = v_x - omega
    /// (c_y - y) changes with the accelerations and with the centroid's height, which follows
    /// the depth ([`disc_arm_per_depth`]). One evaluation of the law where the differences
    /// take three. `None` where the closed form is not written (polygons, the sphere).
    fn disc_rates(&self, s: &State, d: &State, e: &Eval) -> Option<(f64, f64)> {
        // A disc takes only the area or linear law and the linear spring (`check_laws`), and
        // in slip it is in contact.
        let Shape::Disc { r } = self.model.scene.shape else {
            return None;
        };
        let o = e.forces.overlap?;
        let (v, a) = ([s[VX], s[VY], s[OM]], [d[VX], d[VY], d[OM]]);
        let dfn = self.normal.rate_on_disc(&o, r, &v, &a)?;
        let arm = o.cy - s[Y];
        let d_arm = disc_arm_per_depth(r, o.depth) * -s[VY];
        let dv_t = a[0] - a[2] * arm - s[OM] * d_arm;
        Some((dfn, self.model.spring(o.depth).2 * dv_t))
    }

    /// [`Self::disc_rates`] for a held polygon under the area law: the crossing points P, Q
    /// of its two end edges with the plate slide along those edges, so x_P moves at
    /// omega y - (v_y + omega x_P) e_x / e_y (the body's velocity at P, less its part along
    /// the edge e that keeps P on the plate), which gives the chord's and its midpoint's rates
    /// ([`NormalForce::rate_on_area`]); the centroid's height follows from
    /// d(A c_y)/dt = A (v_y + omega c_x) (the body's vertical velocity over the overlap: the
    /// chord, where material leaves, lies at y = 0). Two evaluations fewer than the
    /// differences for every slip step tested (a tenth of the 120-gon's evaluations).
    /// `None` under the linear law, or where an end edge lies along the plate.
    fn polygon_rates(&self, m: &Mode, s: &State, d: &State, e: &Eval) -> Option<(f64, f64)> {
        let Touch::Poly { first, len, .. } = m.touch else {
            return None;
        };
        let o = e.forces.overlap?;
        let (v, a) = ([s[VX], s[VY], s[OM]], [d[VX], d[VY], d[OM]]);
        let (y, om, n) = (s[Y], s[OM], self.verts.len());
        let sc = sin_cos(s[PHI]);
        let corner = |k: usize| self.corner(k, y, sc);
        let slide = |x: f64, p: (f64, f64), q: (f64, f64)| {
            om * y - (v[1] + om * x) * (q.0 - p.0) / (q.1 - p.1)
        };
        let x_p = o.x_mid - 0.5 * o.chord;
        let dx_p = slide(x_p, corner(first + n - 1), corner(first));
        let dx_q = slide(x_p + o.chord, corner(first + len - 1), corner(first + len));
        let rates = (dx_q - dx_p, 0.5 * (dx_p + dx_q));
        let dfn = self.normal.rate_on_area(&o, rates, &v, &a)?;
        let dcy_dt = (v[1] + om * o.cx) - o.cy * o.area_rate(&v) / o.area;
        let dv_t = a[0] - a[2] * (o.cy - y) - om * (dcy_dt - v[1]);
        let ddamp = self.model.spring(o.depth).2 * dv_t;
        (dfn.is_finite() && ddamp.is_finite()).then_some((dfn, ddamp))
    }

    /// (dF_n/dt, d(c_t v_t)/dt) by central differences along the motion (`d` the derivative
    /// at `s`): Mindlin's c_t(delta) changes too.
    fn differenced_rates(&self, m: &Mode, s: &State, d: &State, e: &Eval) -> (f64, f64) {
        let mut h = self.fd_step;
        if let (Touch::Disc, None) = (m.touch, self.linear()) {
            // Keep both sample points inside the segment (no continuation beyond separation).
            h = h.min(0.25 * e.depth / s[VY].abs().max(f64::MIN_POSITIVE));
        }
        let shifted = |sign: f64| {
            let mut p = *s;
            for i in 0..6 {
                p[i] += sign * h * d[i];
            }
            self.eval(m, &p).1
        };
        let (ep, em) = (shifted(1.0), shifted(-1.0));
        let dfn = (ep.fn_raw - em.fn_raw) / (2.0 * h);
        let damping = |ev: &Eval| self.model.spring(ev.depth).2 * ev.v_t;
        (dfn, (damping(&ep) - damping(&em)) / (2.0 * h))
    }

    /// Event `ev`'s function at fraction `th` of `step`, on its dense output. The touch's,
    /// separation's and a corner's read only the height and the orientation: those two
    /// components alone (a polygon samples its corners entering at eight points of every
    /// step), the others the whole state.
    pub(super) fn value_at(&self, m: &Mode, ev: Event, step: &Step, th: f64) -> f64 {
        let geometric = !matches!(
            ev,
            Event::ClipOff | Event::ClipOn | Event::ToSlip | Event::ToStick | Event::Unload
        );
        if geometric {
            let mut s = step.y0;
            s[Y] = step.component_at(th, Y);
            s[PHI] = step.component_at(th, PHI);
            self.event_value(m, ev, &s)
        } else {
            self.event_value(m, ev, &step.at(th))
        }
    }

    /// Fraction of `step` at which event `ev` first fires (its function turns positive),
    /// given that it fires at the end, located on the dense output.
    pub(super) fn locate(&self, m: &Mode, ev: Event, step: &Step, g1: f64) -> f64 {
        // The end's value in the same form as the samples' (`event_value_given`).
        let g1 = if self.smooth_clip(m, ev) {
            self.event_value(m, ev, &step.y1)
        } else {
            g1
        };
        self.locate_in(m, ev, step, (0.0, None), (1.0, g1))
    }

    /// As [`Self::locate`], within [lo, hi] of the step, the event function positive at hi
    /// (`g_hi`) and at lo `g_lo` when known (else evaluated here).
    pub(super) fn locate_in(
        &self,
        m: &Mode,
        ev: Event,
        step: &Step,
        (lo, g_lo): (f64, Option<f64>),
        (hi, g_hi): (f64, f64),
    ) -> f64 {
        let g = |th: f64| self.value_at(m, ev, step, th);
        let g0 = g_lo.unwrap_or_else(|| {
            if lo == 0.0 {
                self.event_value(m, ev, &step.y0)
            } else {
                g(lo)
            }
        });
        locate_switch(g, (lo, g0), (hi, g_hi), self.switch_precision(ev)).1
    }

    /// To what fraction of its step a switch `ev` is located ([`switch_precision`]): the
    /// linear law's dashpot jumps where a contact starts (touch, a corner entering).
    pub(super) fn switch_precision(&self, ev: Event) -> f64 {
        let jumps = matches!(ev, Event::Touch | Event::EnterLeft | Event::EnterRight);
        switch_precision(self.tol, jumps && self.linear().is_some())
    }

    /// The first switch of event `ev` among samples of its function at the increasing
    /// fractions `at` of `step` (with the value, where already known): located between the
    /// first sample where the function is positive and the sample before it (the step's start
    /// before the first), each value computed once.
    pub(super) fn first_sampled(
        &self,
        m: &Mode,
        ev: Event,
        step: &Step,
        at: impl IntoIterator<Item = (f64, Option<f64>)>,
    ) -> Option<f64> {
        first_positive_sample(|th| self.value_at(m, ev, step, th), at)
            .map(|(before, after)| self.locate_in(m, ev, step, before, after))
    }
}

#[cfg(test)]
mod tests {
    use super::super::{ReferenceOptions, NS, OM, VX, VY, XI, Y};
    use super::*;
    use crate::impact::record::estimate_max_depth;
    use crate::model::{Initial, Model, NormalLaw, Scene};

    /// The slip -> stick test's rates in closed form on the exact disc equal their central
    /// differences along the motion, over depths from grazing to deep, both laws, spins of
    /// both signs and both slip directions.
    #[test]
    fn closed_form_disc_rates_match_central_differences() {
        let laws = [NormalLaw::Area, NormalLaw::Linear { kn: 2e5, cn: 30.0 }];
        for law in laws {
            let scene = Scene {
                normal_law: law,
                gamma: 0.33,
                gamma_t: 0.5,
                ..Scene::default()
            };
            with_reference(&scene, |ode, depth_est| {
                let r = ode.model.r;
                for frac in [1e-3, 0.05, 0.3, 0.9] {
                    for (vy, om, sg) in [(-0.02, 3.0, 1.0), (0.01, -5.0, -1.0), (-0.005, 0.0, 1.0)]
                    {
                        let mut s: State = [0.0; NS];
                        s[Y] = r - frac * depth_est;
                        s[VX] = 0.02;
                        s[VY] = vy;
                        s[OM] = om;
                        s[XI] = 0.0;
                        let m = Mode {
                            touch: Touch::Disc,
                            clip_on: true,
                            clip_hold: false,
                            tan: Tan::Slip(sg),
                            unloading: false,
                        };
                        let (d, e) = ode.eval(&m, &s);
                        let closed = ode.disc_rates(&s, &d, &e).unwrap();
                        // Central differences err like h^2 (1e-4 of the value at 1e-3 of the
                        // depth, where the damping's rate grows like depth^-1/2) and, at finer
                        // steps, by round-off: the closed form must lie within the truncation
                        // error that halving the step reveals, or 1e-8 of the value.
                        let what = format!("{law:?} depth {frac} vy {vy} omega {om}");
                        assert_differences_agree(ode, (&m, &s, &d, &e), closed, &what);
                    }
                }
            });
        }
    }

    /// `check` with the reference path's ODE of one impact of `scene` (the preset's speed at
    /// 40 deg) and its estimated largest depth.
    fn with_reference(scene: &Scene, check: impl FnOnce(&Reference, f64)) {
        let model = Model::new(scene).unwrap();
        let init = Initial::from_angle(0.0357, 40.0, 0.0, 0.0);
        let depth_est = estimate_max_depth(&model, &init).unwrap();
        let (ode, _, _) =
            Reference::for_impact(&model, &init, depth_est, &ReferenceOptions::default());
        check(&ode, depth_est);
    }

    /// The closed form `closed` of (dF_n/dt, d(c_t v_t)/dt) at `s` in mode `m` against central
    /// differences at two steps. Central differences err like h^2 (1e-4 of the value at 1e-3
    /// of the disc's depth, where the damping's rate grows like depth^-1/2) and, at finer
    /// steps, by round-off: the closed form must lie within the truncation error that halving
    /// the step reveals, or 1e-8 of the value.
    fn assert_differences_agree(
        ode: &Reference,
        (m, s, d, e): (&Mode, &State, &State, &Eval),
        closed: (f64, f64),
        what: &str,
    ) {
        let at = |k: f64| {
            let fine = Reference {
                model: ode.model,
                verts: ode.verts,
                mu: ode.mu,
                error_weight: ode.error_weight,
                tol: ode.tol,
                fd_step: ode.fd_step / k,
                force_tol: ode.force_tol,
                normal: ode.normal,
                inv_mass: ode.inv_mass,
                inv_inertia: ode.inv_inertia,
                summed: ode.summed,
            };
            fine.differenced_rates(m, s, d, e)
        };
        let (coarse, fine) = (at(1.0), at(2.0));
        for (a, h, h2) in [(closed.0, coarse.0, fine.0), (closed.1, coarse.1, fine.1)] {
            let truncation = 4.0 / 3.0 * (h - h2).abs();
            let bound = 2.0 * truncation + 1e-8 * a.abs();
            assert!(
                (a - h2).abs() <= bound,
                "{what}: {a:e} vs {h2:e} ({h:e} at 2h)"
            );
        }
    }

    /// The same for a held polygon under the area law: a triangle, a 12-gon and a 120-gon at
    /// many orientations, depths from grazing to deep, spins of both signs, both slip
    /// directions; the depths those of the polygon's own (not continued) run.
    #[test]
    fn closed_form_polygon_rates_match_central_differences() {
        for n in [3, 12, 120] {
            let scene = Scene {
                shape: crate::geometry::Shape::regular_polygon(0.01, n).unwrap(),
                gamma: 0.33,
                gamma_t: 0.5,
                mu: 0.5,
                ..Scene::default()
            };
            with_reference(&scene, |ode, depth_est| {
                for k in 0..12 {
                    let phi = 0.37 * k as f64;
                    let touch_y = ode.model.scene.shape.touch_height(phi);
                    for frac in [0.02, 0.3, 1.0] {
                        for (vy, om, sg) in
                            [(-0.02, 3.0, 1.0), (0.01, -5.0, -1.0), (-0.005, 0.0, 1.0)]
                        {
                            let mut s: State = [0.0; NS];
                            (s[Y], s[PHI], s[VX], s[VY], s[OM]) =
                                (touch_y - frac * depth_est, phi, 0.02, vy, om);
                            let m = Mode {
                                touch: ode.initial_run(s[Y], phi),
                                clip_on: true,
                                clip_hold: false,
                                tan: Tan::Slip(sg),
                                unloading: false,
                            };
                            let (d, e) = ode.eval(&m, &s);
                            let closed = ode.polygon_rates(&m, &s, &d, &e).unwrap();
                            let what = format!("{n}-gon phi {phi} depth {frac} vy {vy} omega {om}");
                            assert_differences_agree(ode, (&m, &s, &d, &e), closed, &what);
                        }
                    }
                }
            });
        }
    }
}
