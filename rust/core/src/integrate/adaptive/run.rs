//! The loop of one impact: step, reject or accept, end the piece at the first switch, handle
//! chattering switches, and build the record.

use super::dopri::{root_error_ratio, Step};
use super::law::{Eval, Reference};
use super::mode::{apply, start_slip};
use super::piece::{Event, Mode, Tally, Tan, Touch};
use super::{
    ReferenceOptions, State, ERR_EST_FACTOR, NS, OM, PHI, VX, VY, W_D, W_EL, W_T, X, XI, Y,
};
use crate::cancel::Cancel;
use crate::error::Result;
use crate::impact::budget::{budget_for, reference_contact_steps};
use crate::impact::flight;
use crate::impact::record::{Record, StopReason, Trace, TIMEOUT_CONTACT_TIMES};
use crate::integrate::roots;
use crate::law::NormalForce;
use crate::model::{Initial, Model, NormalLaw};
use std::f64::consts::PI;

/// Smallest error scale of a velocity component, relative to the impact's speed.
const SCALE_FLOOR: f64 = 1e-3;

/// The error scale of each state component, from the impact's own scales (so that a scene
/// rescaled with its dimensionless groups fixed takes the same steps): the velocities' are
/// the incident ones the outputs are relative to (|vx| for e_T, |vy| for e_N, v / r for the
/// spin; the speed where a component is zero), the positions' what those velocities cover
/// in t_c / pi, the spring's the elongation that holds as much energy as the contact point's
/// velocity scale (see below), the works' the energy.
fn error_scales(
    model: &Model,
    init: &Initial,
    (speed, energy): (f64, f64),
    t_est: f64,
    depth_est: f64,
) -> State {
    let r = model.r;
    let v_in = init.vx.hypot(init.vy);
    // Floored at 1e-3 of the speed (spin included): a component far below the others (a
    // grazing impact's v_y, a spinning body's v_x) cannot be followed to `tol` of itself in
    // double precision, and asking for it costs millions of steps (a triangle at 0.01 deg and
    // 1e4 deg/s took 3e7). Over the study's grid (theta >= 4 deg) no floor is reached.
    let or_speed = |x: f64| x.clamp(SCALE_FLOOR * speed, speed);
    let mut scale = [0.0; NS];
    scale[VX] = or_speed(init.vx.abs());
    scale[VY] = or_speed(init.vy.abs());
    scale[OM] = or_speed(v_in) / r;
    let t_c = t_est / PI;
    scale[X] = scale[VX] * t_c;
    scale[Y] = scale[VY] * t_c;
    scale[PHI] = scale[OM] * t_c;
    // In stick the spring and the contact point's motion are one oscillator: an error of xi
    // is worth one of the tangential velocity when their energies match, (1/2) k_t xi^2 =
    // (1/2) m_t v^2, with m_t = 1 / (1/m + r^2/I) the mass the spring moves at the contact
    // point and k_t its stiffness at the estimated largest depth. (The force that moves v_x in
    // t_c, the scale before, is 3 / (omega_t t_c) ~ 1/6 of that on the paper's disc: it set 90
    // % of the steps in stick, finer than any output needed.) Mindlin's xi is a force (section
    // 14.4), the elongation times k_t.
    let m_t = 1.0 / (1.0 / model.mass + r * r / model.inertia);
    let (k_xi, rate, _) = model.spring(depth_est);
    let k_t = k_xi * rate;
    // Without a spring (k_t = 0) its elongation does not act: no error of it counts.
    scale[XI] = if k_t > 0.0 {
        scale[VX] * (m_t / k_t).sqrt() * if model.mindlin { k_t } else { 1.0 }
    } else {
        f64::INFINITY
    };
    scale[W_EL] = energy;
    scale[W_D] = energy;
    scale[W_T] = energy;
    scale
}

/// `err_est` from the local error estimates accumulated over the accepted steps (root sum of
/// squares, components VX, VY, OM): the largest over e_N, e_T, e_kin and omega_out r / v.
fn error_estimate(acc: &State, init: &Initial, r: f64) -> f64 {
    let v_in = init.vx.hypot(init.vy);
    let e_t = if init.vx != 0.0 {
        acc[VX] / init.vx.abs()
    } else {
        0.0
    };
    let e_n = acc[VY] / init.vy.abs();
    let e_kin = acc[VX].hypot(acc[VY]) / v_in;
    let spin = acc[OM] * r / v_in;
    ERR_EST_FACTOR * e_t.max(e_n).max(e_kin).max(spin)
}

impl Reference<'_> {
    /// Whether the force in mode `m` has the disc's root singularities at touch and
    /// separation: a disc or sphere in contact under the area or Hertz law (the linear law
    /// is smooth there), with the clip on (in the clipped tail no force acts, so nothing is
    /// singular at its end: halving towards separation there took 12 of a frictionless disc's
    /// 47 steps).
    fn singular_force(&self, m: &Mode) -> bool {
        self.linear().is_none() && m.touch == Touch::Disc && m.clip_on
    }

    /// The largest step near a point where a disc's force is not smooth (touch and
    /// separation: the area grows like depth^(3/2), the damping like depth^(1/2), so a step
    /// of h across such a point errs like (h / t_c)^(3/2) in the velocity, unseen by the
    /// embedded estimate). The step that contains the point is at most t_c tol^(2/3): the
    /// first after touch, and towards separation the steps halve the time left until then.
    /// `h_sing` is that step (`Limits::h_singular`).
    fn singular_cap(&self, m: &Mode, s: &State, fresh_touch: bool, h_sing: f64) -> f64 {
        if !self.singular_force(m) {
            return f64::INFINITY;
        }
        if fresh_touch {
            return h_sing;
        }
        let depth = self.model.r - s[Y];
        if s[VY] > 0.0 && depth > 0.0 {
            (0.5 * depth / s[VY]).max(h_sing)
        } else {
            f64::INFINITY
        }
    }

    /// The factor on the embedded error estimate of a step across or near a point where the
    /// disc's force is not smooth (a step that starts within [`ROOT_REACH`] of its lengths
    /// after touch, where the damping still grows like a root of the time; a step ending on
    /// separation), which the embedded estimate understates: [`root_error_ratio`] for the
    /// law's root (the area law's damping grows like t^(1/2), the Tsuji dashpot like
    /// t^(1/4)), `rho` the time since touch in units of the step. 1 for every other step.
    /// (Redoing the first four steps after touch as two halves and extrapolating their
    /// difference, as before, cost 12 evaluations of the law per step, ~6 % of the disc's time
    /// at tol 1e-6, and covered fewer of the grid's errors: >= 98.4 % against >= 99.9 %.)
    fn singular_factor(&self, m: &Mode, rho: Option<f64>, event: Option<Event>) -> f64 {
        if !self.singular_force(m) {
            return 1.0;
        }
        let p = match self.model.scene.normal_law {
            NormalLaw::Hertz { .. } => 0.25,
            _ => 0.5,
        };
        // Beyond a step's length from touch the embedded estimate no longer understates.
        let at_touch = rho
            .filter(|&rho| rho < ROOT_REACH)
            .map_or(1.0, |rho| root_error_ratio(p, rho, false));
        let at_separation = if event == Some(Event::Separate) {
            root_error_ratio(p, 0.0, true)
        } else {
            1.0
        };
        at_touch.max(at_separation)
    }
}

/// Steps from touch, in units of the step, beyond which [`root_error_ratio`] is 1 (1.1 at
/// one step, 0.5 at two).
const ROOT_REACH: f64 = 2.0;

/// The step size controller's factor for a step with scaled error `err` (> 0; rejected above
/// 1): 0.9 err^(-1/5) within [0.2, 5]. Below 1.8e-4 that is 5 without the power (0.9
/// (1.8e-4)^(-1/5) = 5.04), which libm's pow, called at every step, made 4 % of a profile of
/// the adaptive path.
fn step_factor(err: f64) -> f64 {
    if err < 1.8e-4 {
        5.0
    } else {
        (0.9 * err.powf(-0.2)).clamp(0.2, 5.0)
    }
}

/// Shortest stick phase, in units of the estimated contact time, that counts for
/// `slip_events` (see `Run::take`).
const MIN_STICK: f64 = 1e-6;

/// How many times its location's precision a piece ended by a switch may last and still count
/// as negligible for the chatter remedies (see `Run::count_chatter`).
const CHATTER_RESOLUTIONS: f64 = 100.0;

/// Consecutive zero-length pieces after which a step ignores its events (see `first_switch`).
const MAX_ZERO_PIECES: u32 = 64;

/// Updates the largest depth and area with their maxima inside the taken part of a step. A
/// polygon's: where a parabola through three samples peaks inside the step, Brent's search on
/// the dense output finds the peak; a disc's: see [`deepest_disc`].
///
/// `start` is the evaluation at the step's start; at its end, a whole step reuses the last
/// stage's.
fn track_extremes(
    ode: &Reference,
    m: &Mode,
    step: &Step,
    frac: f64,
    tally: &mut Tally,
    start: &Eval,
) {
    match m.touch {
        Touch::Off => return,
        Touch::Disc => return deepest_disc(ode, step, frac, tally),
        Touch::Poly { .. } => {}
    }
    let of = |e: &Eval| [e.depth, e.forces.overlap.map_or(0.0, |o| o.area)];
    let sample = |th: f64| of(&ode.eval(m, &step.at(th)).1);
    let end = if frac == 1.0 {
        of(&step.end)
    } else {
        sample(frac)
    };
    let ends = [of(start), sample(0.5 * frac), end];
    for (k, best) in [&mut tally.max_depth, &mut tally.max_area]
        .into_iter()
        .enumerate()
    {
        let f3 = [ends[0][k], ends[1][k], ends[2][k]];
        *best = best.max(peak(|th| sample(th)[k], f3, frac));
    }
}

/// [`track_extremes`] for a disc or sphere, whose depth is r - y and whose overlap grows with
/// it: both peak where v_y turns from falling to rising, located on the dense output without
/// evaluating the law (sampling the law at mid-step for a peak cost an evaluation per step).
fn deepest_disc(ode: &Reference, step: &Step, frac: f64, tally: &mut Tally) {
    if step.y0[VY] > 0.0 || (frac == 1.0 && step.y1[VY] <= 0.0) {
        return;
    }
    deepest_disc_inside(ode, step, frac, tally);
}

/// The part of [`deepest_disc`] for a step where v_y may turn (once per impact): kept out of
/// line, it costs the other steps nothing.
#[inline(never)]
fn deepest_disc_inside(ode: &Reference, step: &Step, frac: f64, tally: &mut Tally) {
    let v_y = |th: f64| step.component_at(th, VY);
    let v_end = if frac == 1.0 { step.y1[VY] } else { v_y(frac) };
    if v_end <= 0.0 {
        return;
    }
    // Near its peak the depth moves like the square of the distance to it: a position to
    // 1e-10 of the step leaves nothing of the depth.
    let (_, th) = roots::bracket(v_y, (0.0, step.y0[VY]), (frac, v_end), 1e-10 * frac);
    let s = step.at(th);
    // The shape's own overlap (the same as the held mode's while in contact): calling the
    // mode's here, out of line, cost the law's evaluation its inlining of it (10 % per step).
    if let Some(o) = ode.model.scene.shape.overlap(s[Y], s[PHI]) {
        tally.max_depth = tally.max_depth.max(o.depth);
        tally.max_area = tally.max_area.max(o.area);
    }
}

/// Largest value of `f` on [0, frac] when it peaks inside, given its values at 0, frac / 2 and
/// frac; -inf otherwise (the ends are recorded as step ends).
fn peak(f: impl Fn(f64) -> f64, [f0, fm, f1]: [f64; 3], frac: f64) -> f64 {
    // Parabola through the three samples: concave with its vertex within the step (a little
    // margin, so that a peak just past a sample is not missed).
    let curv = f0 - 2.0 * fm + f1;
    if curv >= 0.0 {
        return f64::NEG_INFINITY;
    }
    let vertex = 0.5 + 0.25 * (f0 - f1) / curv;
    if !(-0.1..=1.1).contains(&vertex) {
        return f64::NEG_INFINITY;
    }
    // Near its peak the value moves like the square of the distance to it: a position to
    // 1e-8 of the step leaves ~1e-16 of the value's change over the step, at round-off.
    roots::peak(f, (0.0, frac), fm, 1e-8 * frac.max(1e-300))
        .max(f0)
        .max(f1)
}

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

/// What bounds one impact's integration, fixed at its start.
pub(super) struct Limits {
    /// The largest step.
    h_max: f64,
    /// The estimated contact time.
    t_est: f64,
    /// The largest step across a point where the disc's force is not smooth, t_est tol^(2/3)
    /// (see `Reference::singular_cap`), fixed per impact.
    h_singular: f64,
    /// Stop once the contacts have lasted this long ([`TIMEOUT_CONTACT_TIMES`] contact times;
    /// free flight is jumped over and does not count, as for the fixed steps).
    t_end: f64,
    /// The step budget (attempts, rejected steps included): steps may be much shorter than
    /// h_max while a turning polygon brings corner after corner to the plate (counted in
    /// N_c), but an explicit method crawls through a damper much stiffer than the contact (a
    /// spinning triangle at gamma = 10 takes steps of 1e-7 t_ref): such scenes end as timed
    /// out.
    max_steps: u64,
    /// Pieces shorter than this are negligible (for chattering).
    tiny: f64,
    /// The polygon's corners (0 for a disc or sphere).
    n_corners: usize,
    /// Kinetic energy before the impact.
    energy_in: f64,
}

/// The state of one impact between steps.
struct Run<'a, 't> {
    ode: Reference<'a>,
    init: &'a Initial,
    lim: Limits,
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
    /// Accepted steps, and attempts (rejected ones included).
    steps: u64,
    attempts: u64,
    /// Consecutive pieces of zero length (switches that fire at once).
    zero_pieces: u32,
    /// Consecutive negligible pieces ended by a stick/slip switch, and by a clip switch.
    chatter_t: u32,
    chatter_c: u32,
    /// Stick/slip switches ignored for one step (a sliding mode, see `resolve_chatter`).
    hold_tangential: bool,
    /// The accepted steps' local error estimates (sums of squares), for `err_est`.
    err_acc: State,
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
        let (ode, lim) = Reference::for_impact(model, init, depth_est, opts);
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
            zero_pieces: 0,
            chatter_t: 0,
            chatter_c: 0,
            hold_tangential: false,
            err_acc: [0.0; NS],
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
        if self.attempts >= self.lim.max_steps {
            Some(StopReason::StepBudget)
        } else if self.contact_time() >= self.lim.t_end {
            Some(StopReason::ContactTimeBudget)
        } else {
            None
        }
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
        let (jump, advances) = flight::jump(gap, s[Y], &v, r, self.lim.h_max, left);
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
        if lim.n_corners > 0 && s[OM] != 0.0 {
            // A turning polygon brings corners to the plate: step finely enough (a quarter of
            // the angle between corners) that no corner touches and leaves within one step,
            // in flight (a missed re-contact) and in contact (a stale set of submerged corners).
            h = h.min(0.25 * (2.0 * PI / lim.n_corners as f64) / s[OM].abs());
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
        let h_min = 1e-13 * self.lim.t_est;
        if !err.is_finite() {
            // Never accept a non-finite state: shrink hard and retry; if even the smallest
            // step fails, stop with the last finite state and say so.
            if h > h_min {
                self.h = (0.1 * h).max(h_min);
                return None;
            }
            return Some(StopReason::NonFinite);
        }
        if err > 1.0 && h > h_min {
            self.h = (h * step_factor(err)).max(h_min);
            return None;
        }
        let h_next = h * step_factor(err);
        let first = self.first_switch(step);
        if let Some(c) = step.pull.filter(|_| self.zero_pieces < MAX_ZERO_PIECES) {
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
        // The last resort against a loop of zero-length pieces: well above the chatter counts
        // (16), whose remedies (`resolve_chatter`) must act first; at 16 a tangential chatter
        // once switched every event off and the step crossed the clip with the plate pulling
        // (the disc at theta 34, mu 0.6: e_N off by 1.2e-4).
        if self.zero_pieces >= MAX_ZERO_PIECES {
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
                if matches!(ev, Event::LeaveLeft | Event::LeaveRight | Event::Separate) {
                    leaving = Some(th);
                }
                if first.is_none_or(|(t0, _)| th < t0) {
                    first = Some((th, ev));
                }
            }
        }
        // Whatever ends the step first, a corner that leaves inside it may leave after the
        // clip switched off, which the step's end state (past the leave point) cannot show.
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
                // Redo the step to the switch so the state there has full Runge-Kutta accuracy.
                self.ode
                    .dp_step(&self.mode, &self.s, &self.k1, th * h, redo);
                (redo.y1, th * h, Some(ev), redo.err, Some(&redo.end))
            }
        };
        let from_touch = (h_taken > 0.0).then(|| (self.t - self.t_touch) / h_taken);
        let factor = self.ode.singular_factor(&self.mode, from_touch, event);
        for i in [VX, VY, OM] {
            // In quadrature: the local errors' signs vary along an impact (summed, their
            // absolute values overstated the error 15-fold at tol 1e-4 and 124-fold at 1e-10).
            self.err_acc[i] += (factor * err_taken[i].abs()).powi(2);
        }
        self.hold_tangential = false;
        self.count_chatter(event, h_taken, h);
        if h_taken > 0.0 {
            self.fresh_touch = false;
            self.steps += 1;
            self.zero_pieces = 0;
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
        } else {
            self.zero_pieces += 1;
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
        let known = (event.is_none() && h_taken == h).then(|| (step.k_end(), step.end));
        self.resolve_chatter();
        let known = known.filter(|_| self.mode == mode_step && self.s == s_new);
        self.refresh(h_taken, known);
        self.h = if event.is_some() {
            h_next.min(h)
        } else {
            h_next
        };
    }

    /// Counts consecutive negligible pieces ended by the same kind of switch: shorter than
    /// [`Limits::tiny`] or than [`CHATTER_RESOLUTIONS`] times the precision to which the switch
    /// was located in its step `h`. The root finder may return any point within that
    /// precision past the root, and a sliding mode amplifies it: a bracket that crossed the
    /// root by half the precision left the clip of a damper far stiffer than the contact
    /// switching on and off in pieces of 2.5e-7 and 3e-6 of a step (precision 1e-6), above
    /// `tiny`, until the step budget ran out (8 of the extremes benchmark's scenes); so the
    /// remedy no longer depends on where within its precision a switch lands.
    fn count_chatter(&mut self, event: Option<Event>, h_taken: f64, h: f64) {
        let resolution = event.map_or(0.0, |ev| {
            CHATTER_RESOLUTIONS * self.ode.switch_precision(ev) * h
        });
        let tiny = self.lim.tiny.max(resolution);
        match event {
            Some(Event::ToSlip | Event::ToStick) if h_taken < tiny => self.chatter_t += 1,
            Some(Event::ClipOn | Event::ClipOff) if h_taken < tiny => self.chatter_c += 1,
            _ if h_taken >= tiny => (self.chatter_t, self.chatter_c) = (0, 0),
            _ => {}
        }
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
        if self.chatter_c >= 16 && !mode.clip_on {
            // The clip switches on and off at once: a damper much stiffer than the contact
            // holds F_el + F_d at zero (a sliding mode), so the force is about zero too. Take
            // one step without it; an explicit method could not follow the damper anyway.
            mode.clip_hold = true;
            self.chatter_c = 0;
        }
        if self.chatter_t >= 16 {
            // Stick and slip each end at once: the motion slides along |F_trial| = mu F_n
            // (a Filippov sliding mode), whose force law is slip's. Take one step in slip.
            if mode.tan == Tan::Stick {
                let e = self.ode.eval(mode, s).1;
                start_slip(&self.ode, mode, s, &e);
            }
            self.hold_tangential = true;
            self.chatter_t = 0;
        }
    }

    /// The first stage of the next step, the extremes and the trace at the new state.
    fn refresh(&mut self, h_taken: f64, known: Option<(State, Eval)>) {
        let (k, e) = known.unwrap_or_else(|| self.ode.eval(&self.mode, &self.s));
        self.k1 = k;
        self.e1 = e;
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
                    &e,
                    self.ode.xi_of(&self.mode, &self.s, &e),
                );
            }
        }
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
            energy_in: self.lim.energy_in,
            work_normal: s[W_EL] + s[W_D],
            work_friction: s[W_T],
            step_budget: self.lim.max_steps,
            stop,
            err_est: Some(error_estimate(&self.err_acc.map(f64::sqrt), init, model.r)),
            ..Record::default()
        };
        rec.close(model, init, &[s[VX], s[VY], s[OM]]);
        rec
    }
}

/// Appends the state `s` at time `t` to the trace.
fn push(tr: &mut Trace, t: f64, s: &State, e: &Eval, xi: f64) {
    let (q, v) = ([s[X], s[Y], s[PHI]], [s[VX], s[VY], s[OM]]);
    tr.push(t, &q, &v, &e.forces, e.depth, xi);
}

impl<'a> Reference<'a> {
    /// The ODE of one impact and the limits of its integration.
    pub(super) fn for_impact(
        model: &'a Model,
        init: &Initial,
        depth_est: f64,
        opts: &ReferenceOptions,
    ) -> (Self, Limits) {
        let r = model.r;
        let speed = init.vx.hypot(init.vy) + r * init.omega.abs();
        let t_est = PI * depth_est / init.vy.abs();
        let h_max = opts.max_step_factor.unwrap_or(model.scene.dt_factor) * model.t_ref;
        let energy_in = model.kinetic_energy(&[init.vx, init.vy, init.omega]);
        let scale = error_scales(model, init, (speed, energy_in), t_est, depth_est);
        let verts = model.scene.shape.vertices();
        let ode = Reference {
            model,
            verts,
            mu: model.scene.mu,
            error_weight: scale.map(|sc| 1.0 / (opts.tol * sc)),
            tol: opts.tol,
            fd_step: 1e-5 * t_est,
            force_tol: opts.tol * model.mass * speed / t_est,
            normal: NormalForce::new(model),
            inv_mass: 1.0 / model.mass,
            inv_inertia: 1.0 / model.inertia,
        };
        let lim = Limits {
            h_max,
            t_est,
            h_singular: t_est * opts.tol.powf(2.0 / 3.0),
            t_end: TIMEOUT_CONTACT_TIMES * t_est,
            max_steps: budget_for(
                model,
                reference_contact_steps(model, init, depth_est, h_max, opts.tol),
            ),
            tiny: 1e-9 * t_est,
            n_corners: verts.len(),
            energy_in,
        };
        (ode, lim)
    }
}
