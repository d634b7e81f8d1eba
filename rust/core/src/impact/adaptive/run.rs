//! The loop of one impact: step, reject or accept, end the piece at the first switch, handle
//! chattering switches, and build the record.

use super::extremes::track_extremes;
use super::law::{Eval, Reference};
use super::mode::{apply, start_slip};
use super::piece::{Event, Mode, Tally, Tan, Touch};
use super::rules::{error_estimate, verdict, Chatter, ErrorSum, Limits, SwitchKind, Verdict};
use super::step::Step;
use super::{ReferenceOptions, State, NS, OM, PHI, VX, VY, W_D, W_EL, W_T, X, Y};
use crate::cancel::Cancel;
use crate::error::Result;
use crate::impact::flight;
use crate::impact::record::{Bodies, Ending, Record, StopReason, Trace};
use crate::model::{Initial, Model};
use std::f64::consts::PI;

/// Shortest stick phase, in units of the estimated contact time, that counts for
/// `slip_events` (see `Run::take`).
const MIN_STICK: f64 = 1e-6;

/// Integrates one impact from first touch (validated scene and initial state).
pub(crate) fn integrate(
    model: &Model,
    init: &Initial,
    depth_est: f64,
    opts: &ReferenceOptions,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let mut run = Run::new(model, init, depth_est, opts, trace);
    // Where each attempted step and each step redone up to a switch are written (~1.4 kB
    // each: returned by value, a step was copied twice per attempt).
    let (mut step, mut redo) = (Step::default(), Step::default());
    let stop = loop {
        if run.cleared() || (run.mode.touch == Touch::Off && run.fly()) {
            break StopReason::Separated;
        }
        cancel.poll(run.attempts)?;
        if let Some(stop) = run.budget_spent() {
            break stop;
        }
        if run.coast() {
            continue;
        }
        if let Some(stop) = run.attempt(&mut step, &mut redo) {
            break stop;
        }
    };
    Ok(run.finish(stop))
}

/// The state of one impact between steps.
struct Run<'a, 't> {
    ode: Reference<'a>,
    init: &'a Initial,
    lim: Limits,
    /// Kinetic energy before the impact.
    energy_in: f64,
    trace: Option<&'t mut Trace>,
    /// The ODE's state, its mode, and the first stage of the next step (FSAL).
    s: State,
    mode: Mode,
    k1: State,
    /// The evaluation at `s` whose derivative `k1` is.
    e1: Eval,
    tally: Tally,
    t: f64,
    /// The step to try next.
    h: f64,
    /// Accepted steps, and attempts (rejected ones and those redone to a switch included).
    steps: u64,
    attempts: u64,
    /// Consecutive negligible and zero-length pieces.
    chatter: Chatter,
    /// Stick/slip switches ignored for one step (a sliding mode, see `resolve_chatter`).
    hold_tangential: bool,
    /// The accepted steps' local errors, for `err_est`.
    err_acc: ErrorSum<NS>,
    /// No step taken since the last touch, at `t_touch`: the next starts at a point where the
    /// disc's force is not smooth, and the next few still see its root singularity.
    fresh_touch: bool,
    t_touch: f64,
}

impl<'a, 't> Run<'a, 't> {
    fn new(
        model: &'a Model,
        init: &'a Initial,
        depth_est: f64,
        opts: &ReferenceOptions,
        mut trace: Option<&'t mut Trace>,
    ) -> Self {
        let (ode, lim, energy_in) = Reference::for_impact(model, init, depth_est, opts);
        let shape = &model.scene.shape;
        let mut s: State = [0.0; NS];
        s[Y] = shape.touch_height(init.phi0);
        s[PHI] = init.phi0;
        s[VX] = init.vx;
        s[VY] = init.vy;
        s[OM] = init.omega;
        let mut mode = Mode {
            touch: ode.touch_mode(s[Y], s[PHI]),
            clip_on: true,
            clip_hold: false,
            tan: Tan::None,
            unloading: false,
        };
        mode.tan = ode.initial_tan(&mode, &s);
        let (k1, e0) = ode.eval(&mode, &s);
        if let Some(tr) = trace.as_deref_mut() {
            push(tr, 0.0, &s, &e0, ode.xi_of(&mode, &s, &e0));
        }
        Run {
            h: lim.h_max,
            ode,
            init,
            lim,
            energy_in,
            trace,
            s,
            mode,
            k1,
            e1: e0,
            tally: Tally {
                contacts: 1,
                ..Tally::default()
            },
            t: 0.0,
            steps: 0,
            attempts: 0,
            chatter: Chatter::default(),
            hold_tangential: false,
            err_acc: ErrorSum::default(),
            fresh_touch: true,
            t_touch: 0.0,
        }
    }

    /// Done once no part of the particle can reach the plate: its circumscribed circle is
    /// clear and moving away, or every point of it moves away (v_y > r |omega|).
    fn cleared(&self) -> bool {
        let (s, r) = (&self.s, self.ode.model.r);
        self.mode.touch == Touch::Off && s[VY] > 0.0 && (s[Y] >= r || s[VY] > r * s[OM].abs())
    }

    /// The budget that is spent, if one is.
    fn budget_spent(&self) -> Option<StopReason> {
        self.lim.budget_spent(self.attempts, self.contact_time())
    }

    /// The time spent in contact so far, the ongoing contact included.
    fn contact_time(&self) -> f64 {
        let ongoing = if self.mode.touch == Touch::Off {
            0.0
        } else {
            self.t - self.tally.contact_start
        };
        self.tally.contact_time + ongoing
    }

    /// A disc's or sphere's clipped tail: jumps to separation; true if it did. Once the
    /// unclipped force F_el + F_d has turned negative (the damper pulling while the body
    /// rises, v_y > 0) no force acts, so the body moves uniformly and the depth falls; the
    /// damper's share then grows (the area law: F_el ~ delta^(3/2) against F_d ~
    /// delta^(1/2) v_y; the linear law: kn delta against cn v_y; Hertz: delta^(3/2) against
    /// delta^(1/4) v_y; the lever arms are zero on the centre line), so the clip cannot
    /// switch on again and separation comes at y = r, in closed form. Stepped instead, the
    /// tail took a few Runge-Kutta steps, a located switch and a step redone up to it.
    /// Not where the jump would pass the contact-time budget.
    fn coast(&mut self) -> bool {
        let (m, s, r) = (&self.mode, &self.s, self.ode.model.r);
        // Written as the conditions to hold, so that a NaN fails them.
        let rising = s[VY] > 0.0;
        if m.touch != Touch::Disc || m.clip_on || m.clip_hold || !rising {
            return false;
        }
        let t_sep = ((r - s[Y]) / s[VY]).max(0.0);
        let within_budget = self.contact_time() + t_sep < self.lim.t_end;
        if !within_budget {
            return false;
        }
        self.drift(t_sep, 1);
        // Exactly at separation, where y + v_y t_sep may round either side of r.
        self.s[Y] = r;
        apply(
            &self.ode,
            &mut self.mode,
            Event::Separate,
            &mut self.s,
            (self.t, None),
            &mut self.tally,
        );
        self.refresh(t_sep, None);
        true
    }

    /// In free flight: jumps over it by conservative advancement (see [`flight`]), each
    /// advance counted as a step; true when no part of the particle can reach the plate
    /// again. Stepped instead, a polygon flung round by a stiff spring could spend its whole
    /// budget flying before its next corner came down.
    fn fly(&mut self) -> bool {
        let (s, shape, r) = (self.s, &self.ode.model.scene.shape, self.ode.model.r);
        let v = [s[VX], s[VY], s[OM]];
        let gap = |t: f64| s[Y] + v[1] * t - shape.touch_height(s[PHI] + v[2] * t);
        let left = self.lim.max_steps.saturating_sub(self.attempts);
        let approach = flight::Approach::to_plate(s[Y], &v, (r, shape.touch_arm()));
        let (jump, advances) = flight::jump(gap, approach, self.lim.h_max, left);
        let (t_jump, done) = match jump {
            flight::Jump::Stay => return false,
            flight::Jump::To(t) => (t, false),
            flight::Jump::Clear(t) => (t, true),
        };
        self.drift(t_jump, advances);
        self.refresh(t_jump, None);
        done
    }

    /// Moves the body uniformly for `dt` (no force acts), counting `advances` steps.
    fn drift(&mut self, dt: f64, advances: u64) {
        for (q, dq) in [(X, VX), (Y, VY), (PHI, OM)] {
            self.s[q] += self.s[dq] * dt;
        }
        self.t += dt;
        self.steps += advances;
        self.attempts += advances;
    }

    /// The step to try: the next one, within the largest and the caps of the state.
    fn capped_step(&self) -> f64 {
        let (s, lim) = (&self.s, &self.lim);
        let mut h = self.h.min(lim.h_max).min(self.ode.singular_cap(
            &self.mode,
            s,
            self.fresh_touch,
            lim.h_singular,
        ));
        let n_corners = self.ode.verts.len();
        if n_corners > 0 && s[OM] != 0.0 {
            // A turning polygon brings corners to the plate: step finely enough (a quarter of
            // the angle between corners) that no corner touches and leaves within one step,
            // in flight (a missed re-contact) and in contact (a stale set of submerged corners).
            h = h.min(0.25 * (2.0 * PI / n_corners as f64) / s[OM].abs());
        }
        h
    }

    /// One attempted step: rejected (the next try is shorter) or taken up to the first
    /// switch inside it. Returns why the impact stops, if it does.
    fn attempt(&mut self, step: &mut Step, redo: &mut Step) -> Option<StopReason> {
        let h = self.capped_step();
        self.h = h;
        let err = self.ode.dp_step(&self.mode, &self.s, &self.k1, h, step);
        self.attempts += 1;
        let h_min = self.lim.h_min();
        let h_next = match verdict(err, h, h_min) {
            Verdict::Accept { h_next } => h_next,
            Verdict::Reject { h_retry } => {
                self.h = h_retry;
                return None;
            }
            Verdict::NonFinite => return Some(StopReason::NonFinite),
        };
        let first = self.first_switch(step);
        if let Some(c) = step.pull.filter(|_| !self.chatter.stalled()) {
            if first.is_none_or(|(th, _)| th > c) && h > h_min {
                // The step crossed a clip switch that its dense output does not show: never
                // integrate across it with the unclipped, pulling force; shorten the step.
                self.h = (0.5 * c * h).max(h_min);
                return None;
            }
        }
        self.take(step, redo, first, h_next);
        None
    }

    /// Events: the earliest switch inside the step ends the piece there (fraction of the
    /// step, switch).
    fn first_switch(&self, step: &Step) -> Option<(f64, Event)> {
        // The last resort against a loop of zero-length pieces (`Chatter::stalled`).
        if self.chatter.stalled() {
            return None;
        }
        let mut first: Option<(f64, Event)> = None;
        let mut leaving: Option<f64> = None;
        for ev in self.ode.candidates(&self.mode) {
            if self.hold_tangential && matches!(ev, Event::ToSlip | Event::ToStick) {
                continue;
            }
            if let Some(th) = self
                .ode
                .switch_in(&self.mode, ev, step, (&self.k1, &self.e1))
            {
                if self.ode.ends_contact(&self.mode, ev) {
                    leaving = Some(th);
                }
                if first.is_none_or(|(t0, _)| th < t0) {
                    first = Some((th, ev));
                }
            }
        }
        // Whatever ends the step first, the contact's last corner may leave (or the disc
        // separate) after the clip switched off, which the step's end state (past the leave
        // point) cannot show.
        let clip = leaving.and_then(|th| self.ode.clip_before_leaving(&self.mode, step, th));
        match (first, clip) {
            (Some((t0, _)), Some((tc, ev))) if tc < t0 => Some((tc, ev)),
            (None, Some(c)) => Some(c),
            _ => first,
        }
    }

    /// Takes the accepted `step` up to its first switch (all of it if none), switches the
    /// mode there and prepares the next step (`h_next` the error control's proposal).
    fn take(&mut self, step: &Step, redo: &mut Step, first: Option<(f64, Event)>, h_next: f64) {
        let (h, mode_step) = (self.h, self.mode);
        // The state where the piece ends and the evaluation there in the piece's mode.
        let (s_new, h_taken, event, err_taken, e_new) = match first {
            None => (step.y1, h, None, step.err, Some(&step.end)),
            Some((th, ev)) if th >= 1.0 => (step.y1, h, Some(ev), step.err, Some(&step.end)),
            Some((th, ev)) if th * h <= 0.0 => (self.s, 0.0, Some(ev), [0.0; NS], None),
            Some((th, ev)) => {
                // A switch inside the step counts against the budget as a step's work, whether
                // the step is redone to it or not: a rattle of 10^5 short contacts is mostly
                // switches, and the budget bounds its time (uncounted, a 4096-gon's rattle ran
                // 0.85 s to the budget instead of 0.66).
                self.attempts += 1;
                #[cfg(feature = "bench-counters")]
                crate::counters::count_located_switch(th);
                match self.ode.state_at_switch(&self.mode, step, th) {
                    Some((s_th, err)) => (s_th, th * h, Some(ev), err, None),
                    None => {
                        // Redone to the switch, the state there has full Runge-Kutta accuracy.
                        self.ode
                            .dp_step(&self.mode, &self.s, &self.k1, th * h, redo);
                        (redo.y1, th * h, Some(ev), redo.err, Some(&redo.end))
                    }
                }
            }
        };
        let from_touch = (h_taken > 0.0).then(|| (self.t - self.t_touch) / h_taken);
        let factor = self.ode.singular_factor(&self.mode, from_touch, event);
        self.err_acc.add(&err_taken, factor, [VX, VY, OM]);
        self.hold_tangential = false;
        let switch = event.map(|ev| (switch_kind(ev), self.ode.switch_precision(ev)));
        self.chatter.count(switch, (h_taken, h), self.lim.tiny);
        if h_taken > 0.0 {
            self.fresh_touch = false;
            self.steps += 1;
            // Only a stick phase of some length counts for slip events: a guess of stick at
            // first touch that the events correct at once, chattering, or the disc's stick of
            // ~1e-9 t_c just after touch (the damping's rate, like t^(-1/2), opens the Coulomb
            // cone faster than the spring loads; seen once steps are searched inside) is no
            // micro-slip.
            self.tally.stuck |=
                self.mode.tan == Tan::Stick && h_taken >= MIN_STICK * self.lim.t_est;
            // The deepest point inside the step (where the depth stops growing).
            let frac = h_taken / h;
            track_extremes(&self.ode, &self.mode, step, frac, &mut self.tally, &self.e1);
        }
        self.t += h_taken;
        self.s = s_new;
        self.end_clip_hold();
        let e_new = e_new.filter(|_| self.mode == mode_step);
        if let Some(ev) = event {
            if ev == Event::Touch {
                (self.fresh_touch, self.t_touch) = (true, self.t);
            }
            apply(
                &self.ode,
                &mut self.mode,
                ev,
                &mut self.s,
                (self.t, e_new),
                &mut self.tally,
            );
        }
        // A whole step without a switch ends where its last stage was evaluated (FSAL):
        // reuse that evaluation unless the clip hold or a sliding mode changed the state.
        let known = (event.is_none() && h_taken == h).then_some(step);
        self.resolve_chatter();
        let known = known.filter(|_| self.mode == mode_step && self.s == s_new);
        self.refresh(h_taken, known);
        self.h = if event.is_some() {
            h_next.min(h)
        } else {
            h_next
        };
    }

    /// After a step with the clip held off: the end state decides the clip again.
    fn end_clip_hold(&mut self) {
        if self.mode.clip_hold {
            self.mode.clip_hold = false;
            if self.ode.eval(&self.mode, &self.s).1.fn_raw > 0.0 {
                self.mode.clip_on = true;
                self.mode.tan = self.ode.initial_tan(&self.mode, &self.s);
            }
        }
    }

    /// Leaves a chattering switch for one step in the mode of its sliding motion.
    fn resolve_chatter(&mut self) {
        let (mode, s) = (&mut self.mode, &mut self.s);
        if !mode.clip_on && self.chatter.take_clip() {
            // The clip switches on and off at once: take one step without the force; an
            // explicit method could not follow the damper anyway.
            mode.clip_hold = true;
        }
        if self.chatter.take_tangential() {
            // Stick and slip each end at once: take one step in slip.
            if mode.tan == Tan::Stick {
                let e = self.ode.eval(mode, s).1;
                start_slip(&self.ode, mode, s, &e);
            }
            self.hold_tangential = true;
        }
    }

    /// The first stage of the next step, the extremes and the trace at the new state;
    /// `known`: the step whose end is the current state, in the current mode (its last stage's
    /// derivative and evaluation are then the next step's first, copied once: moved through a
    /// tuple they cost 7 % of the disc's time in copies).
    fn refresh(&mut self, h_taken: f64, known: Option<&Step>) {
        match known {
            Some(step) => {
                self.k1 = step.k_end();
                self.e1 = step.end;
            }
            None => (self.k1, self.e1) = self.ode.eval(&self.mode, &self.s),
        }
        let e = &self.e1;
        self.tally.max_depth = self.tally.max_depth.max(e.depth);
        if let Some(o) = e.forces.overlap {
            self.tally.max_area = self.tally.max_area.max(o.area);
        }
        if let Some(tr) = self.trace.as_deref_mut() {
            if h_taken > 0.0 {
                push(
                    tr,
                    self.t,
                    &self.s,
                    e,
                    self.ode.xi_of(&self.mode, &self.s, e),
                );
            }
        }
    }

    /// `err_est` from the accumulated local errors of the velocities and the spin.
    fn err_est(&self) -> f64 {
        let acc = &self.err_acc;
        let spin = (acc.of(OM), self.ode.model.r);
        error_estimate(self.init, (acc.of(VX), acc.of(VY)), [spin])
    }

    /// The record of the impact, ended for `stop`.
    fn finish(mut self, stop: StopReason) -> Record {
        let (model, init, s) = (self.ode.model, self.init, &self.s);
        if self.mode.touch != Touch::Off {
            self.tally.contact_time += self.t - self.tally.contact_start;
        }
        let tally = &self.tally;
        let mut rec = Record {
            contact_time: tally.contact_time,
            steps: self.steps,
            contacts: tally.contacts,
            max_depth: tally.max_depth,
            max_area: tally.max_area,
            slip_events: tally.slip_events,
            energy_in: self.energy_in,
            work_normal: s[W_EL] + s[W_D],
            work_damping: s[W_D],
            work_friction: s[W_T],
            step_budget: self.lim.max_steps,
            stop,
            err_est: Some(self.err_est()),
            ..Record::default()
        };
        let end = Ending::on_plate(&[s[X], s[Y], s[PHI]], &[s[VX], s[VY], s[OM]]);
        rec.close(&Bodies::Plate(model), init, &end);
        rec
    }
}

/// The kind of a switch, for the chatter count.
fn switch_kind(ev: Event) -> SwitchKind {
    match ev {
        Event::ToSlip | Event::ToStick => SwitchKind::Tangential,
        Event::ClipOn | Event::ClipOff => SwitchKind::Clip,
        _ => SwitchKind::Other,
    }
}

/// Appends the state `s` at time `t` to the trace.
fn push(tr: &mut Trace, t: f64, s: &State, e: &Eval, xi: f64) {
    let (q, v) = ([s[X], s[Y], s[PHI]], [s[VX], s[VY], s[OM]]);
    tr.push(t, &q, &v, &e.forces, e.depth, xi);
}
