//! The plate as the one adaptive loop sees it ([`AdaptiveSide`]): its ODE ([`Reference`]),
//! the switches a held mode can meet, the disc's clipped tail jumped in closed form, the
//! flight jumped by conservative advancement, and the record.

use super::extremes::track_extremes;
use super::law::{Eval, Reference};
use super::mode::{apply, start_slip};
use super::piece::{Event, Mode, Tally, Tan, Touch};
use super::rules::{error_estimate, root_exponent, ErrorSum, SwitchKind};
use super::run::Run;
use super::side::AdaptiveSide;
use super::step::Step;
use super::{ReferenceOptions, State, NS, OM, PHI, VX, VY, W_D, W_EL, W_T, X, Y};
use crate::cancel::{Cancel, POLL_STEPS};
use crate::error::Result;
use crate::impact::flight;
use crate::impact::record::{Bodies, Ending, Record, StopReason, Trace};
use crate::model::{Initial, Model};
use std::f64::consts::PI;

/// Shortest stick phase, in units of the estimated contact time, that counts for
/// `slip_events` (see [`OnPlate::after_piece`]).
const MIN_STICK: f64 = 1e-6;

/// Integrates one impact on the plate from first touch (validated scene and initial state).
pub(crate) fn integrate(
    model: &Model,
    init: &Initial,
    depth_est: f64,
    opts: &ReferenceOptions,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    start(model, init, depth_est, opts, trace).integrate(cancel)
}

/// What the plate keeps of its own through one impact.
struct OnPlate<'a> {
    ode: Reference<'a>,
    init: &'a Initial,
    /// Kinetic energy before the impact.
    energy_in: f64,
    /// The evaluation at the state whose derivative the run's `k1` is.
    e1: Eval,
    tally: Tally,
    /// Stick/slip switches ignored for one step (a sliding mode, see `resolve_chatter`).
    hold_tangential: bool,
    /// The accepted steps' local errors, for `err_est`.
    err_acc: ErrorSum<NS>,
}

/// The run of one impact on the plate at first touch.
fn start<'a, 't>(
    model: &'a Model,
    init: &'a Initial,
    depth_est: f64,
    opts: &ReferenceOptions,
    mut trace: Option<&'t mut Trace>,
) -> Run<'t, OnPlate<'a>> {
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
    let side = OnPlate {
        ode,
        init,
        energy_in,
        e1: e0,
        tally: Tally {
            contacts: 1,
            ..Tally::default()
        },
        hold_tangential: false,
        err_acc: ErrorSum::default(),
    };
    let h = lim.h_max;
    Run::new(side, (s, mode, k1), h, lim, trace)
}

impl<'a> AdaptiveSide for OnPlate<'a> {
    type State = State;
    type Mode = Mode;
    type Event = Event;
    type Step = Step;

    fn poll_stride(&self) -> u64 {
        POLL_STEPS
    }

    #[inline]
    fn dp_step(&self, m: &Mode, s: &State, k1: &State, h: f64, out: &mut Step) -> f64 {
        self.ode.dp_step(m, s, k1, h, out)
    }

    #[inline]
    fn step_end(step: &Step) -> (&State, &State) {
        (&step.y1, &step.err)
    }

    fn state_at_switch(&self, m: &Mode, step: &Step, th: f64) -> Option<(State, State)> {
        self.ode.state_at_switch(m, step, th)
    }

    #[inline]
    fn unseen_switch(step: &Step) -> Option<f64> {
        step.pull
    }

    fn root_exponent(&self) -> Option<f64> {
        root_exponent(&self.ode.model.scene.normal_law)
    }

    #[inline]
    fn singular_force(&self, m: &Mode) -> bool {
        self.ode.singular_force(m)
    }

    #[inline]
    fn opening(&self, s: &State) -> (f64, f64) {
        (self.ode.model.r - s[Y], s[VY])
    }

    /// A turning polygon brings corners to the plate: step finely enough (a quarter of the
    /// angle between corners) that no corner touches and leaves within one step, in flight (a
    /// missed re-contact) and in contact (a stale set of submerged corners).
    #[inline]
    fn step_cap(&self, _m: &Mode, s: &State) -> f64 {
        let n_corners = self.ode.verts.len();
        if n_corners > 0 && s[OM] != 0.0 {
            0.25 * (2.0 * PI / n_corners as f64) / s[OM].abs()
        } else {
            f64::INFINITY
        }
    }

    /// Events: the earliest switch inside the step ends the piece there.
    fn first_switch(run: &mut Run<'_, Self>, step: &Step) -> Option<(f64, Event)> {
        // The last resort against a loop of zero-length pieces (`Chatter::stalled`).
        if run.chatter.stalled() {
            return None;
        }
        let (ode, mode, side) = (&run.side.ode, &run.mode, &run.side);
        let mut first: Option<(f64, Event)> = None;
        let mut leaving: Option<f64> = None;
        for ev in ode.candidates(mode) {
            if side.hold_tangential && matches!(ev, Event::ToSlip | Event::ToStick) {
                continue;
            }
            if let Some(th) = ode.switch_in(mode, ev, step, (&run.k1, &side.e1)) {
                if ode.ends_contact(mode, ev) {
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
        let clip = leaving.and_then(|th| ode.clip_before_leaving(mode, step, th));
        match (first, clip) {
            (Some((t0, _)), Some((tc, ev))) if tc < t0 => Some((tc, ev)),
            (None, Some(c)) => Some(c),
            _ => first,
        }
    }

    fn switch_kind(ev: Event) -> SwitchKind {
        match ev {
            Event::ToSlip | Event::ToStick => SwitchKind::Tangential,
            Event::ClipOn | Event::ClipOff => SwitchKind::Clip,
            Event::Touch => SwitchKind::Touch,
            Event::Separate => SwitchKind::Separation,
            _ => SwitchKind::Other,
        }
    }

    fn switch_precision(&self, ev: Event) -> f64 {
        self.ode.switch_precision(ev)
    }

    /// After a step with the clip held off: the end state decides the clip again.
    fn settle(run: &mut Run<'_, Self>) {
        run.side.hold_tangential = false;
        let (ode, mode) = (&run.side.ode, &mut run.mode);
        if mode.clip_hold {
            mode.clip_hold = false;
            if ode.eval(mode, &run.s).1.fn_raw > 0.0 {
                mode.clip_on = true;
                mode.tan = ode.initial_tan(mode, &run.s);
            }
        }
    }

    fn apply(run: &mut Run<'_, Self>, ev: Event, known: Option<&Step>) {
        let side = &mut run.side;
        let at = (run.t, known.map(|step| &step.end));
        apply(
            &side.ode,
            &mut run.mode,
            ev,
            &mut run.s,
            at,
            &mut side.tally,
        );
    }

    /// Leaves a chattering switch for one step in the mode of its sliding motion.
    fn resolve_chatter(run: &mut Run<'_, Self>) {
        let (mode, s) = (&mut run.mode, &mut run.s);
        if !mode.clip_on && run.chatter.take_clip() {
            // The clip switches on and off at once: take one step without the force; an
            // explicit method could not follow the damper anyway.
            mode.clip_hold = true;
        }
        if run.chatter.take_tangential() {
            // Stick and slip each end at once: take one step in slip.
            if mode.tan == Tan::Stick {
                let e = run.side.ode.eval(mode, s).1;
                start_slip(&run.side.ode, mode, s, &e);
            }
            run.side.hold_tangential = true;
        }
    }

    /// A whole step's last stage is the next step's first unless the clip hold or a sliding
    /// mode changed the state or the mode.
    fn refresh(
        run: &mut Run<'_, Self>,
        whole: Option<&Step>,
        (mode_step, s_new): (&Mode, &State),
        h_taken: f64,
    ) {
        let known = whole.filter(|_| run.mode == *mode_step && run.s == *s_new);
        refresh(run, h_taken, known);
    }

    fn after_piece(run: &mut Run<'_, Self>, step: &Step, h_taken: f64, frac: f64) {
        let side = &mut run.side;
        // Only a stick phase of some length counts for slip events: a guess of stick at first
        // touch that the events correct at once, chattering, or the disc's stick of ~1e-9 t_c
        // just after touch (the damping's rate, like t^(-1/2), opens the Coulomb cone faster
        // than the spring loads; seen once steps are searched inside) is no micro-slip.
        side.tally.stuck |= run.mode.tan == Tan::Stick && h_taken >= MIN_STICK * run.lim.t_est;
        // The deepest point inside the step (where the depth stops growing).
        track_extremes(&side.ode, &run.mode, step, frac, &mut side.tally, &side.e1);
    }

    #[inline]
    fn add_error(&mut self, err: &State, factor: f64) {
        self.err_acc.add(err, factor, [VX, VY, OM]);
    }

    fn contact_time(run: &Run<'_, Self>) -> f64 {
        let tally = &run.side.tally;
        let ongoing = if run.mode.touch == Touch::Off {
            0.0
        } else {
            run.t - tally.contact_start
        };
        tally.contact_time + ongoing
    }

    /// Done once no part of the particle can reach the plate: its circumscribed circle is
    /// clear and moving away, or every point of it moves away (v_y > r |omega|); in flight the
    /// flight is jumped first ([`fly`]). Inlined: it is asked before every step (out of line
    /// it cost the disc 1 % of its time).
    #[inline]
    fn parted(run: &mut Run<'_, Self>) -> bool {
        let (s, r) = (&run.s, run.side.ode.model.r);
        let off = run.mode.touch == Touch::Off;
        let cleared = off && s[VY] > 0.0 && (s[Y] >= r || s[VY] > r * s[OM].abs());
        cleared || (off && fly(run))
    }

    #[inline]
    fn coast(run: &mut Run<'_, Self>) -> bool {
        coast(run)
    }

    fn finish(run: &mut Run<'_, Self>, stop: StopReason) -> Record {
        let s = &run.s;
        let side = &mut run.side;
        let (model, init) = (side.ode.model, side.init);
        if run.mode.touch != Touch::Off {
            side.tally.contact_time += run.t - side.tally.contact_start;
        }
        let tally = &side.tally;
        let acc = &side.err_acc;
        let spin = (acc.of(OM), model.r);
        let mut rec = Record {
            contact_time: tally.contact_time,
            steps: run.steps,
            contacts: tally.contacts,
            max_depth: tally.max_depth,
            max_area: tally.max_area,
            slip_events: tally.slip_events,
            energy_in: side.energy_in,
            work_normal: s[W_EL] + s[W_D],
            work_damping: s[W_D],
            work_friction: s[W_T],
            step_budget: run.lim.max_steps,
            stop,
            err_est: Some(error_estimate(init, (acc.of(VX), acc.of(VY)), [spin])),
            ..Record::default()
        };
        let end = Ending::on_plate(&[s[X], s[Y], s[PHI]], &[s[VX], s[VY], s[OM]]);
        rec.close(&Bodies::Plate(model), init, &end);
        rec
    }
}

/// A disc's or sphere's clipped tail: jumps to separation; true if it did. Once the unclipped
/// force F_el + F_d has turned negative (the damper pulling while the body rises, v_y > 0) no
/// force acts, so the body moves uniformly and the depth falls; the damper's share then grows
/// (the area law: F_el ~ delta^(3/2) against F_d ~ delta^(1/2) v_y; the linear law: kn delta
/// against cn v_y; Hertz: delta^(3/2) against delta^(1/4) v_y; the lever arms are zero on the
/// centre line), so the clip cannot switch on again and separation comes at y = r, in closed
/// form. Stepped instead, the tail took a few Runge-Kutta steps, a located switch and a step
/// redone up to it. Not where the jump would pass the contact-time budget.
#[inline]
fn coast(run: &mut Run<'_, OnPlate>) -> bool {
    let (m, s, r) = (&run.mode, &run.s, run.side.ode.model.r);
    // Written as the conditions to hold, so that a NaN fails them.
    let rising = s[VY] > 0.0;
    if m.touch != Touch::Disc || m.clip_on || m.clip_hold || !rising {
        return false;
    }
    let t_sep = ((r - s[Y]) / s[VY]).max(0.0);
    let within_budget = OnPlate::contact_time(run) + t_sep < run.lim.t_end;
    if !within_budget {
        return false;
    }
    drift(run, t_sep, 1);
    // Exactly at separation, where y + v_y t_sep may round either side of r.
    run.s[Y] = r;
    let side = &mut run.side;
    let at = (run.t, None);
    apply(
        &side.ode,
        &mut run.mode,
        Event::Separate,
        &mut run.s,
        at,
        &mut side.tally,
    );
    refresh(run, t_sep, None);
    true
}

/// In free flight: jumps over it by conservative advancement (see [`flight`]), each advance
/// counted as a step; true when no part of the particle can reach the plate again. Stepped
/// instead, a polygon flung round by a stiff spring could spend its whole budget flying before
/// its next corner came down. Out of line: once per flight.
#[inline(never)]
fn fly(run: &mut Run<'_, OnPlate>) -> bool {
    let (s, shape, r) = (run.s, &run.side.ode.model.scene.shape, run.side.ode.model.r);
    let v = [s[VX], s[VY], s[OM]];
    let gap = |t: f64| s[Y] + v[1] * t - shape.touch_height(s[PHI] + v[2] * t);
    let left = run.lim.max_steps.saturating_sub(run.attempts);
    let approach = flight::Approach::to_plate(s[Y], &v, (r, shape.touch_arm()));
    let (jump, advances) = flight::jump(gap, approach, run.lim.h_max, left);
    let (t_jump, done) = match jump {
        flight::Jump::Stay => return false,
        flight::Jump::To(t) => (t, false),
        flight::Jump::Clear(t) => (t, true),
    };
    drift(run, t_jump, advances);
    refresh(run, t_jump, None);
    done
}

/// Moves the body uniformly for `dt` (no force acts), counting `advances` steps.
fn drift(run: &mut Run<'_, OnPlate>, dt: f64, advances: u64) {
    for (q, dq) in [(X, VX), (Y, VY), (PHI, OM)] {
        run.s[q] += run.s[dq] * dt;
    }
    run.t += dt;
    run.steps += advances;
    run.attempts += advances;
}

/// The first stage of the next step, the extremes and the trace at the new state; `known`: the
/// step whose end is the current state, in the current mode (its last stage's derivative and
/// evaluation are then the next step's first, copied once: moved through a tuple they cost 7 %
/// of the disc's time in copies).
fn refresh(run: &mut Run<'_, OnPlate>, h_taken: f64, known: Option<&Step>) {
    let side = &mut run.side;
    match known {
        Some(step) => {
            run.k1 = step.k_end();
            side.e1 = step.end;
        }
        None => (run.k1, side.e1) = side.ode.eval(&run.mode, &run.s),
    }
    let e = &side.e1;
    side.tally.max_depth = side.tally.max_depth.max(e.depth);
    if let Some(o) = e.forces.overlap {
        side.tally.max_area = side.tally.max_area.max(o.area);
    }
    if let Some(tr) = run.trace.as_deref_mut() {
        if h_taken > 0.0 {
            let xi = side.ode.xi_of(&run.mode, &run.s, e);
            push(tr, run.t, &run.s, e, xi);
        }
    }
}

/// Appends the state `s` at time `t` to the trace.
fn push(tr: &mut Trace, t: f64, s: &State, e: &Eval, xi: f64) {
    let (q, v) = ([s[X], s[Y], s[PHI]], [s[VX], s[VY], s[OM]]);
    tr.push(t, &q, &v, &e.forces, e.depth, xi);
}
