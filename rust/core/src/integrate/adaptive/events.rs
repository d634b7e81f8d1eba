//! The switches that end a piece: their event functions (continuous, <= 0 while the piece's
//! mode holds), which of them can end a given mode, and where inside a step one fires.

use super::dopri::{Step, C};
use super::law::{Eval, Reference};
use super::piece::{Event, Mode, Tan, Touch};
use super::{State, OM, PHI, VX, VY, Y};
use crate::geometry::{disc_arm_per_depth, Shape};
use crate::integrate::roots::{self, bracket};
use crate::model::NormalLaw;

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
        }
        out.into_iter().flatten()
    }

    /// The event function: > 0 once the piece's mode no longer holds.
    pub(super) fn event_value(&self, m: &Mode, ev: Event, s: &State) -> f64 {
        self.event_value_given(m, ev, s, None)
    }

    /// [`Self::event_value`], with the evaluation at `s` (derivative and forces) when known.
    fn event_value_given(
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
        let poly = |k: usize| self.corner(k, y, phi.sin_cos()).1;
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
    /// mu dF_n/dt + s (k_t v_t + c_t dv_t/dt), both rates along the motion of the slipping
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
        let (dfn, ddamp) = match self.disc_rates(s, &d, &e) {
            Some(rates) => rates,
            None => self.differenced_rates(m, s, &d, &e),
        };
        let (k_xi, rate, _) = self.model.spring(e.depth);
        // Located where the value exceeds 1e-9 of its terms, the switch is robustly past its
        // root (central differences carry ~1e-11 of the terms, the closed form round-off), and
        // late by only that fraction of the value's rise time: a switch located where the
        // value is noise leaves a spring on the cone that does not move inside, and stick and
        // slip chatter at once (the disc at theta 84, mu 0.8 lost a stick phase of 0.004 t_c
        // that way, e_T off by 1e-5 at tol 1e-6).
        let terms = [self.mu * dfn, sg * k_xi * rate * e.v_t, sg * ddamp];
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
    fn value_at(&self, m: &Mode, ev: Event, step: &Step, th: f64) -> f64 {
        let geometric = !matches!(
            ev,
            Event::ClipOff | Event::ClipOn | Event::ToSlip | Event::ToStick
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
    fn locate_in(
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
        if g0 > 0.0 {
            return lo;
        }
        // The state just past the switch (the event fired) starts the next piece.
        bracket(g, (lo, g0), (hi, g_hi), self.switch_precision(ev)).1
    }

    /// To what fraction of its step a switch `ev` is located. The switches leave the forces
    /// continuous, so one late by delta errs like delta^2: the local tolerance itself (within
    /// [1e-10, 1e-6]) leaves ~tol^2. Only the linear law's dashpot jumps where a contact
    /// starts (touch, a corner entering: by c_n v), an error like delta: those to 1e-10 of the
    /// step, as every switch of the reference (1e-14 moved its records by <= 2e-12 for ~5
    /// more evaluations per switch; 1e-6 instead of 1e-10 saves ~3 % of the adaptive path's
    /// time on the disc at tol 1e-6).
    pub(super) fn switch_precision(&self, ev: Event) -> f64 {
        let jumps = matches!(ev, Event::Touch | Event::EnterLeft | Event::EnterRight);
        if jumps && self.linear().is_some() {
            1e-10
        } else {
            self.tol.clamp(1e-10, 1e-6)
        }
    }

    /// The first switch of event `ev` among samples of its function at the increasing
    /// fractions `at` of `step` (with the value, where already known): located between the
    /// first sample where the function is positive and the sample before it (the step's start
    /// before the first), each value computed once.
    fn first_sampled(
        &self,
        m: &Mode,
        ev: Event,
        step: &Step,
        at: impl IntoIterator<Item = (f64, Option<f64>)>,
    ) -> Option<f64> {
        let mut before = (0.0, None);
        for (th, known) in at {
            let g = known.unwrap_or_else(|| self.value_at(m, ev, step, th));
            if g > 0.0 {
                return Some(self.locate_in(m, ev, step, before, (th, g)));
            }
            before = (th, Some(g));
        }
        None
    }
}

impl Reference<'_> {
    /// The fraction of `step` at which event `ev` first fires, if it does inside the step;
    /// `start` is the derivative and evaluation at the step's start.
    pub(super) fn switch_in(
        &self,
        m: &Mode,
        ev: Event,
        step: &Step,
        start: (&State, &Eval),
    ) -> Option<f64> {
        let g1 = self.event_value_given(m, ev, &step.y1, Some((&step.k_end(), &step.end)));
        if ev == Event::ToSlip && g1 <= 0.0 && self.stays_stuck(m, step, start) {
            return None;
        }
        if ev == Event::ToStick && g1 <= 0.0 && self.stays_slipping(m, step, start.1) {
            return None;
        }
        if let Some(parts) = interior_samples(ev) {
            // A corner may dip below the plate and rise again within one step (a grazing
            // corner beside the chord), a short stick phase may begin and end within one (the
            // disc at theta 54, mu 0.7 at tol 1e-6 missed one: e_T off by 2e-4): look inside
            // the step too, also when the event fires at its end, so that the first switch is
            // the one found (located on all of the step, a 120-gon's stick -> slip at 0.8913
            // t_c gave way to the one at 0.9016 in the same step, and its short slip phase
            // between was lost: e_T off by 1.8e-6 at tol 1e-6).
            let g0 = || self.event_value_given(m, ev, &step.y0, Some(start));
            self.sampled_switch(m, ev, step, parts, (g0, g1))
        } else if g1 > 0.0 {
            Some(self.locate(m, ev, step, g1))
        } else if let (Event::ClipOff, Some(c)) = (ev, step.pull) {
            // A stage saw the plate pull although the end state does not: the clip
            // switched inside the step (and back, in the held continuation); find
            // where, on the dense output up to that stage.
            let at = (1..=16).map(|k| (c * k as f64 / 16.0, None));
            self.first_sampled(m, ev, step, at)
        } else {
            None
        }
    }

    /// Whether a stick step stays inside the Coulomb cone by more than its event function
    /// varies over the step's stages: then no sample between them can find a slip phase, and
    /// the law need not be evaluated for them (two evaluations per stick step, where the
    /// stages' own evaluations already give the function at seven points).
    fn stays_stuck(&self, m: &Mode, step: &Step, start: (&State, &Eval)) -> bool {
        let g0 = self.event_value_given(m, Event::ToSlip, &step.y0, Some(start));
        let (lo, hi) = (step.stick_span.0.min(g0), step.stick_span.1.max(g0));
        hi + STUCK_SPANS * (hi - lo) < 0.0
    }

    /// Whether a slip step keeps slipping by a wide margin, from the stages' normal forces and
    /// tangential velocities alone: the slip -> stick function is mu dF_n/dt + s (k_t v_t +
    /// c_t dv_t/dt) (linear spring), and while the contact point slides against the force
    /// (s v_t < 0) its term k_t s v_t outweighs the rates' bounds (twice the largest
    /// difference quotient between the stages' values, the sliding velocity's excursion
    /// between stages included), then no sample can find stick, and its two evaluations of the
    /// law (with the rates: two more off the disc) are skipped.
    fn stays_slipping(&self, m: &Mode, step: &Step, start: &Eval) -> bool {
        let Tan::Slip(sg) = m.tan else {
            return false;
        };
        if self.model.mindlin {
            return false;
        }
        let (k_t, _, c_t) = self.model.spring(0.0);
        let h = step.h_len();
        // (node, F_n, v_t) in the order of the nodes: the start, stages 2 ... 6, the end.
        let mut at = [(0.0, start.forces.fy, start.v_t); 7];
        for (i, &(f, v)) in step.slip_stages.iter().enumerate() {
            at[i + 1] = (C[i + 1], f, v);
        }
        let (mut rate_f, mut rate_v, mut sliding) = (0.0f64, 0.0f64, f64::NEG_INFINITY);
        for w in at.windows(2) {
            let ((c0, f0, v0), (c1, f1, v1)) = (w[0], w[1]);
            sliding = sliding.max(sg * v0).max(sg * v1);
            // Nodes closer than 0.05 of the step (the last stage and the end, both at 1)
            // carry their states' errors more than their rates.
            if c1 - c0 >= 0.05 {
                rate_f = rate_f.max((f1 - f0).abs() / ((c1 - c0) * h));
                rate_v = rate_v.max((v1 - v0).abs() / ((c1 - c0) * h));
            }
        }
        let (rate_f, rate_v) = (2.0 * rate_f, 2.0 * rate_v);
        let widest_gap = 0.5 * h;
        let bound = k_t * (sliding + rate_v * widest_gap) + self.mu * rate_f + c_t * rate_v;
        bound < 0.0 && bound.is_finite()
    }

    /// The first switch of `ev` inside `step` from its function sampled at `parts` equal
    /// parts (`g0` its value at the start, computed only when needed: off the disc the slip ->
    /// stick test differences two more evaluations of the law; `g1` at the end): the first positive
    /// sample's, or, where every sample is negative, one that fires and clears again between
    /// three samples around a local maximum (see [`grazes`]): Brent's search for that maximum
    /// on the dense output.
    fn sampled_switch(
        &self,
        m: &Mode,
        ev: Event,
        step: &Step,
        parts: usize,
        (g0, g1): (impl Fn() -> f64, f64),
    ) -> Option<f64> {
        let w = 1.0 / parts as f64;
        let mut g = [0.0; MAX_PARTS + 1];
        for k in 1..=parts {
            g[k] = if k == parts {
                g1
            } else {
                self.value_at(m, ev, step, k as f64 * w)
            };
            if g[k] > 0.0 {
                let before = if k == 1 { g0() } else { g[k - 1] };
                let before = ((k - 1) as f64 * w, Some(before));
                return Some(self.locate_in(m, ev, step, before, (k as f64 * w, g[k])));
            }
        }
        // A peak between the start and the first sample shows only with the start's value:
        // the function falls from the first sample to the second.
        let first = if g[1] >= g[2] {
            g[0] = g0();
            0
        } else {
            1
        };
        let k = first + grazes(&g[first..=parts])?;
        let value = |th: f64| self.value_at(m, ev, step, th);
        let positive = std::cell::Cell::new(None);
        let (lo, hi) = ((k - 1) as f64 * w, (k + 1) as f64 * w);
        roots::peak(
            |th| {
                let v = value(th);
                if v > 0.0 && positive.get().is_none() {
                    positive.set(Some((th, v)));
                }
                v
            },
            (lo, hi),
            g[k],
            1e-6 * w,
        );
        let (th, v) = positive.get()?;
        // The root before the positive point (the samples left of it are negative).
        let from = if th < k as f64 * w {
            (lo, g[k - 1])
        } else {
            (k as f64 * w, g[k])
        };
        Some(self.locate_in(m, ev, step, (from.0, Some(from.1)), (th, v)))
    }

    /// A clip switch before a corner leaves (or the disc separates) at `th` of `step`. With
    /// damping the force pulls in the last stretch before a corner leaves (F = delta times
    /// (k delta + c delta') < 0 as delta -> 0 while it falls), so the clip switches off there; the
    /// check at the step's end cannot see it, since past the leave point the held formulas
    /// are no contact (a corner's area grows again like depth^2 above the plate): a step of
    /// 2 t_ref once crossed the pulling tail unclipped (the 12-gon at theta 74, mu 0.5: e_N off
    /// by 4e-5). Sampled on the dense output, densest towards the leave point.
    pub(super) fn clip_before_leaving(
        &self,
        m: &Mode,
        step: &Step,
        th: f64,
    ) -> Option<(f64, Event)> {
        if !m.clipped() || th <= 0.0 {
            return None;
        }
        const AT: [f64; 10] = [
            0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 0.9375, 0.96875, 0.984375,
        ];
        let at = AT.map(|f| (f * th, None));
        self.first_sampled(m, Event::ClipOff, step, at)
            .map(|at| (at, Event::ClipOff))
    }
}

/// How many times its variation over a step's stages the stick -> slip event function must
/// stay below zero for the step to skip its samples (see `Reference::stays_stuck`).
const STUCK_SPANS: f64 = 2.0;

/// The most parts [`interior_samples`] cuts a step into.
const MAX_PARTS: usize = 8;

/// The sample around which a function sampled at equal steps, negative at every sample, may
/// still rise above zero: the middle of three consecutive samples whose parabola is concave
/// with its vertex between the outer two and peaks above minus the largest third difference of
/// the samples (the size of the cubic term the parabola leaves out). A stick phase grazing the
/// Coulomb cone for a tenth of a step lies between quarter samples (the disc at theta 54,
/// mu 0.7, gamma_t 0: a slip phase of 0.055 t_ref missed inside a step of 0.54 t_ref, e_T off
/// by 1.5e-4 at tol 1e-4), and so may one that starts with the step (the 120-gon at theta 89,
/// mu 0.7, gamma_t 0 slips for 0.04 t_ref from touch, where the function starts at zero).
fn grazes(g: &[f64]) -> Option<usize> {
    // The third differences only where a parabola peaks inside but below zero (this runs for
    // every sampled event of every step, and peaks near zero are rare).
    // Event functions are -inf where their switch cannot happen (a disc's slip -> stick test
    // beyond separation): no parabola through those.
    let cubic = || {
        g.windows(4)
            .map(|q| (q[3] - 3.0 * q[2] + 3.0 * q[1] - q[0]).abs())
            .filter(|d| d.is_finite())
            .fold(0.0, f64::max)
    };
    (1..g.len() - 1).find(|&k| {
        let (a, b, c) = (g[k - 1], g[k], g[k + 1]);
        if !(a.is_finite() && b.is_finite() && c.is_finite()) {
            return false;
        }
        let curv = 2.0 * b - a - c;
        // The vertex lies (c - a) / (2 curv) sample spacings from the middle sample.
        if !(curv > 0.0 && (c - a).abs() <= 2.0 * curv) {
            return false;
        }
        let top = b + (c - a) * (c - a) / (8.0 * curv);
        top > 0.0 || top + cubic() > 0.0
    })
}

/// Into how many parts a step is cut to look for an event that may fire and clear again
/// inside it (its function positive only in the middle), or `None` for events whose function
/// is monotone over a step.
///
/// Stick/slip: thirds, the fewest whose four values give [`grazes`] a third difference (with
/// halves the disc at theta 54, mu 0.7, gamma_t 0 lost its short slip phase again; quarters
/// found the same switches over the full adaptive grid at one evaluation more per step).
fn interior_samples(ev: Event) -> Option<usize> {
    match ev {
        Event::EnterLeft | Event::EnterRight | Event::Touch => Some(8),
        Event::ToStick | Event::ToSlip => Some(3),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::super::{ReferenceOptions, NS, OM, VX, VY, XI, Y};
    use super::*;
    use crate::impact::record::estimate_max_depth;
    use crate::model::{Initial, Model, NormalLaw, Scene};

    /// `grazes` finds a peak above zero between negative samples (of a parabola, exactly), and
    /// none where the function stays below zero, is monotone, or is -inf at a sample.
    #[test]
    fn grazes_flags_a_peak_above_zero_between_negative_samples() {
        let at = |f: &dyn Fn(f64) -> f64, parts: usize| -> Vec<f64> {
            (0..=parts).map(|k| f(k as f64 / parts as f64)).collect()
        };
        // Positive only on (0.47, 0.53): every third is negative.
        let graze = |t: f64| 1e-3 - (t - 0.5) * (t - 0.5);
        let g = at(&graze, 3);
        assert!(g.iter().all(|&v| v < 0.0));
        assert!(grazes(&g).is_some());
        // The same peak 0.002 below zero, and a monotone function.
        assert_eq!(grazes(&at(&|t| graze(t) - 3e-3, 3)), None);
        assert_eq!(grazes(&at(&|t| -1.0 - t, 3)), None);
        // A slip -> stick test beyond separation is -inf: no parabola through it.
        assert_eq!(grazes(&[f64::NEG_INFINITY, -1.0, -0.5, -1.0]), None);
        // A peak just after a start at zero (a slip phase from touch): found from the parabola
        // through the start and the first two samples.
        let from_touch = |t: f64| t * (0.1 - t);
        let g = at(&from_touch, 3);
        assert!(g[1..].iter().all(|&v| v < 0.0) && g[0] == 0.0);
        assert_eq!(grazes(&g), Some(1));
    }

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
            let model = Model::new(&scene).unwrap();
            let init = Initial::from_angle(0.0357, 40.0, 0.0, 0.0);
            let depth_est = estimate_max_depth(&model, &init).unwrap();
            let (ode, _) =
                Reference::for_impact(&model, &init, depth_est, &ReferenceOptions::default());
            let r = model.r;
            for frac in [1e-3, 0.05, 0.3, 0.9] {
                for (vy, om, sg) in [(-0.02, 3.0, 1.0), (0.01, -5.0, -1.0), (-0.005, 0.0, 1.0)] {
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
                    };
                    let (d, e) = ode.eval(&m, &s);
                    let closed = ode.disc_rates(&s, &d, &e).unwrap();
                    // Central differences err like h^2 (1e-4 of the value at 1e-3 of the
                    // depth, where the damping's rate grows like depth^-1/2) and, at finer
                    // steps, by round-off: the closed form must lie within the truncation
                    // error that halving the step reveals, or 1e-8 of the value.
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
                        };
                        fine.differenced_rates(&m, &s, &d, &e)
                    };
                    let (coarse, fine) = (at(1.0), at(2.0));
                    let what = format!("{law:?} depth {frac} vy {vy} omega {om}");
                    for (a, h, h2) in [(closed.0, coarse.0, fine.0), (closed.1, coarse.1, fine.1)] {
                        let truncation = 4.0 / 3.0 * (h - h2).abs();
                        let bound = 2.0 * truncation + 1e-8 * a.abs();
                        assert!(
                            (a - h2).abs() <= bound,
                            "{what}: {a:e} vs {h2:e} ({h:e} at 2h)"
                        );
                    }
                }
            }
        }
    }
}
