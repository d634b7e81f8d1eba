//! The one fixed-step loop of an impact (Gear-5, Verlet), on the plate and on a pair alike:
//! steps of dt from first touch on four lanes, each with its works, extremes and contact
//! bookkeeping, events located on frictionless polygons ([`crate::integrate::events`]), free
//! flight jumped over (`super::flight`), until the bodies can no longer touch or a budget is
//! spent. What differs between the plate and a partner is the side the particle meets
//! ([`Side`]: `PlateSide`, `PairSide`), over which the loop is compiled.

use super::budget::step_budget;
use super::flight::{self, Jump};
use super::record::{Record, StopReason, Trace, TIMEOUT_CONTACT_TIMES};
use super::side::{OnSide, PlateSide, Side};
use super::work::Works;
use crate::cancel::Cancel;
use crate::error::Result;
use crate::geometry::Shape;
use crate::integrate::events;
use crate::integrate::{Gear5, Lanes, Stepper, Verlet};
use crate::law::{DiscPlate, ShapePlate, SpherePlate};
use crate::model::{Initial, Integrator, Model};
use std::f64::consts::PI;

/// Largest local error per step that Gear-5 accepts in a polygon's contact, relative to the
/// estimated largest depth (x and y; phi in units of r): steps in which the force changes
/// faster than the step resolves are halved until they meet it. Never below what double
/// precision resolves at the centre's height (see [`tolerance`]).
pub const ERROR_TOLERANCE: f64 = 1e-12;

/// Spacings of doubles at the centre's height below which no local error is asked of the
/// step control: an error estimate (a difference of positions ~r) finer than a few ulp(r) is
/// round-off, and halving the step cannot lower it. Without the floor a stiff, slow contact
/// (depth ~1e-8 m at r = 0.01 m) asks 1e-20 m, below ulp(0.01 m) = 1.7e-18 m, and every step
/// whose estimate carries round-off would be halved down to the smallest (dt / 1024). (In the
/// rows of issue 14 Gear-5's estimate stayed below even that: the floor changed no step there.)
pub const TOLERANCE_FLOOR_ULPS: f64 = 64.0;

/// The step control's tolerance in the centre's height (m): [`ERROR_TOLERANCE`] of the depth,
/// at least [`TOLERANCE_FLOOR_ULPS`] spacings of doubles at height r.
pub fn tolerance(depth_scale: f64, r: f64) -> f64 {
    (ERROR_TOLERANCE * depth_scale).max(TOLERANCE_FLOOR_ULPS * f64::EPSILON * r)
}

/// Where in the last step the depth crossed zero, by linear interpolation (0 when the two
/// depths are equal, e.g. both exactly zero: never 0 / 0).
#[inline]
pub(super) fn crossing_fraction(prev_depth: f64, depth: f64) -> f64 {
    let span = prev_depth - depth;
    if span == 0.0 {
        0.0
    } else {
        prev_depth / span
    }
}

/// One impact on the plate with a fixed-step integrator (validated model and initial state).
pub(super) fn run_fixed(
    model: &Model,
    init: &Initial,
    depth_est: f64,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let scene = &model.scene;
    let limits = Limits::of(init, depth_est, step_budget(model, init, depth_est));
    let q0 = [0.0, scene.shape.touch_height(init.phi0), init.phi0, 0.0];
    let v0 = [init.vx, init.vy, init.omega, 0.0];
    let start = (q0, v0, model.dt);
    match scene.integrator {
        Integrator::Verlet => on_plate::<Verlet>(model, init, start, &limits, trace, cancel),
        _ => on_plate::<Gear5>(model, init, start, &limits, trace, cancel),
    }
}

/// The budgets of one fixed-step impact.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Limits {
    /// Most steps ([`step_budget`]).
    pub(crate) max_steps: u64,
    /// Most contact time, summed over contacts (s): [`TIMEOUT_CONTACT_TIMES`] estimated
    /// contact times.
    pub(crate) contact_time: f64,
    /// The estimated largest depth (m), the scale of the step control's tolerance.
    pub(crate) depth_scale: f64,
}

impl Limits {
    /// The budgets of an impact from `init` whose largest depth is about `depth_est`, of at
    /// most `max_steps` steps.
    pub(crate) fn of(init: &Initial, depth_est: f64, max_steps: u64) -> Self {
        Limits {
            max_steps,
            contact_time: TIMEOUT_CONTACT_TIMES * PI * depth_est / init.vy.abs(),
            depth_scale: depth_est,
        }
    }
}

/// Integrates one impact on the plate with stepper `S` from `start` = (lanes, rates, dt), the
/// loop compiled separately for the exact disc, the sphere and other shapes (see
/// [`crate::law::PlateGeometry`]).
fn on_plate<S: Stepper>(
    model: &Model,
    init: &Initial,
    (q0, v0, dt): (Lanes, Lanes, f64),
    limits: &Limits,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let stepper = S::start_lanes(q0, v0, dt);
    match &model.scene.shape {
        Shape::Disc { r } => {
            let side = PlateSide::new(model, DiscPlate { r: *r });
            FixedLoop::new(side, stepper, dt, limits).run(init, trace, cancel)
        }
        Shape::Sphere { r } => {
            let side = PlateSide::new(model, SpherePlate { r: *r });
            FixedLoop::new(side, stepper, dt, limits).run(init, trace, cancel)
        }
        shape => {
            let method = model.scene.overlap;
            let side = PlateSide::new(model, ShapePlate { shape, method });
            FixedLoop::new(side, stepper, dt, limits).run(init, trace, cancel)
        }
    }
}

/// The state of one fixed-step impact between steps.
pub(crate) struct FixedLoop<S, C: Side> {
    side: C,
    stepper: S,
    dt: f64,
    limits: Limits,
    /// Steps located on events and refined where the force changes within a step
    /// ([`Side::wants_events`]).
    events: bool,
    control: Option<events::EventControl>,
    /// Works of the normal and tangential forces: quadratures of their powers along the steps
    /// (of third order where events are located and the stepper is Gear-5; elsewhere the
    /// trapezoid: Gear-5 steps through a pair's switches (a corner entering, its dashpot's
    /// force jumping) unlocated, and a parabola through them left 10 times the trapezoid's
    /// residual, twin triangles under the linear law: -1.2e-4 against +1.1e-5).
    works: Works,
    /// Time taken beyond `steps * dt` (shortened and refined steps, flights jumped over).
    t_extra: f64,
    steps: u64,
    in_contact: bool,
    contact_start: f64,
    prev_depth: f64,
    /// The contact's normal when the last contact ended.
    n_sep: [f64; 2],
    rec: Record,
}

impl<S: Stepper, C: Side> FixedLoop<S, C> {
    /// The loop from first touch, `stepper` started there with step `dt`.
    pub(crate) fn new(side: C, stepper: S, dt: f64, limits: &Limits) -> Self {
        let events = side.wants_events();
        FixedLoop {
            side,
            stepper,
            dt,
            limits: *limits,
            events,
            control: None,
            works: Works::new(events && S::HIGH_ORDER),
            t_extra: 0.0,
            steps: 0,
            in_contact: true,
            contact_start: 0.0,
            prev_depth: 0.0,
            n_sep: [0.0, 1.0],
            rec: Record {
                contacts: 1,
                step_budget: limits.max_steps,
                ..Record::default()
            },
        }
    }

    pub(crate) fn run(
        mut self,
        init: &Initial,
        mut trace: Option<&mut Trace>,
        cancel: &Cancel,
    ) -> Result<Record> {
        let (q_in, v_in) = self.stepper.lanes();
        self.rec.energy_in = self.side.kinetic_energy(&v_in);
        if self.events {
            self.start_events();
        }
        if let Some(tr) = trace.as_deref_mut() {
            C::push(tr, 0.0, (&q_in, &v_in), &C::Out::default(), 0.0, 0.0);
        }
        loop {
            cancel.poll_every(self.steps, self.side.poll_stride())?;
            if let Some(stop) = self.budget_spent() {
                self.rec.stop = stop;
                break;
            }
            let (q, v) = self.step(trace.as_deref_mut());
            // Done once no part of the bodies can meet again (`Side::cleared`), or a flight
            // ends clear.
            if !self.in_contact && self.side.cleared(&q, &v) {
                break;
            }
            if !self.in_contact && self.fly(trace.as_deref_mut()) {
                break;
            }
        }
        Ok(self.finish(init))
    }

    /// First touch is an event: start on the branch being entered (face first, the force
    /// grows linearly from touch, and its rate is not zero).
    fn start_events(&mut self) {
        let dt = self.dt;
        let (q, v) = self.stepper.lanes();
        let b = self.side.branch_start(&q, &v, &[0.0; 3], dt);
        self.stepper.restart(&b.a, &b.jerk, dt);
        self.control = Some(events::EventControl {
            corners: b.corners,
            h: dt,
            dt,
            tolerance: tolerance(self.limits.depth_scale, self.side.radius()),
            every_crossing: self.side.every_crossing(),
        });
        self.works.restart(b.powers);
    }

    /// The budget this impact has used up, if any: its steps, or its contact time.
    fn budget_spent(&self) -> Option<StopReason> {
        if self.steps >= self.limits.max_steps {
            return Some(StopReason::StepBudget);
        }
        let ongoing = if self.in_contact {
            self.time() - self.contact_start
        } else {
            0.0
        };
        (self.rec.contact_time + ongoing > self.limits.contact_time)
            .then_some(StopReason::ContactTimeBudget)
    }

    fn time(&self) -> f64 {
        self.steps as f64 * self.dt + self.t_extra
    }

    /// One step, with its works, extremes and contact bookkeeping; the new position and
    /// velocity.
    fn step(&mut self, trace: Option<&mut Trace>) -> (Lanes, Lanes) {
        let dt = self.dt;
        let (f, h, restarted) = match self.control.as_mut() {
            None => {
                let inv_mass = self.side.inv_mass();
                let law = OnSide {
                    side: &mut self.side,
                    dt,
                };
                (self.stepper.advance(dt, &inv_mass, law), dt, None)
            }
            Some(c) => self.side.event_step(c, &mut self.stepper),
        };
        self.steps += 1;
        let (q, v) = self.stepper.lanes();
        self.works.add(h, C::powers(&f, &q, &v), C::pushing(&f));
        if self.events {
            self.t_extra += h - dt;
            if let Some(b) = restarted {
                // A new smooth stretch of the powers starts (they may jump at the event).
                self.works.restart(b.powers);
            }
        }
        let t = self.time();
        // Plain comparisons rather than f64::max: the same result for these non-NaN values,
        // without max's NaN handling in the loop.
        if let Some(area) = C::area(&f) {
            if area > self.rec.max_area {
                self.rec.max_area = area;
            }
        }
        let depth = self.side.depth(&q, &f);
        if depth > self.rec.max_depth {
            self.rec.max_depth = depth;
        }
        self.cross(t, h, depth, &q);
        if let Some(tr) = trace {
            C::push(tr, t, (&q, &v), &f, depth, self.side.spring().xi);
        }
        self.prev_depth = depth;
        (q, v)
    }

    /// Contact starts and ends between steps: crossings interpolated linearly.
    #[inline(always)]
    fn cross(&mut self, t: f64, h: f64, depth: f64, q: &Lanes) {
        if self.in_contact && depth <= 0.0 {
            let end = t - h + crossing_fraction(self.prev_depth, depth) * h;
            self.rec.contact_time += end - self.contact_start;
            self.in_contact = false;
            self.n_sep = self.side.normal(q);
        } else if !self.in_contact && depth > 0.0 {
            self.contact_start = t - h + crossing_fraction(self.prev_depth, depth) * h;
            self.rec.contacts += 1;
            self.in_contact = true;
        }
    }

    /// In free flight: jumps over it (see [`flight`]), each advance counted as a step; true
    /// when no part of the bodies can meet again.
    fn fly(&mut self, trace: Option<&mut Trace>) -> bool {
        let (q, v) = self.stepper.lanes();
        let dt = self.dt;
        let side = &self.side;
        let gap = |t: f64| side.gap_after(&q, &v, t);
        let left = self.limits.max_steps.saturating_sub(self.steps);
        let (jump, advances) = flight::jump(gap, side.approach(&q, &v), dt, left);
        let (t_jump, done) = match jump {
            Jump::Stay => return false,
            Jump::To(t) => (t, false),
            Jump::Clear(t) => (t, true),
        };
        let depth = -gap(t_jump);
        self.steps += advances;
        let q_new: Lanes = std::array::from_fn(|i| q[i] + v[i] * t_jump);
        self.stepper = S::start_lanes(q_new, v, dt);
        self.t_extra += t_jump;
        if let Some(c) = self.control.as_mut() {
            (c.h, c.corners) = (dt, None);
        }
        self.works.part();
        self.prev_depth = depth;
        if let Some(tr) = trace {
            let (t, xi) = (self.time(), self.side.spring().xi);
            C::push(tr, t, (&q_new, &v), &C::Out::default(), depth, xi);
        }
        done
    }

    fn finish(self, init: &Initial) -> Record {
        let mut rec = self.rec;
        rec.steps = self.steps;
        if self.in_contact {
            rec.contact_time += self.time() - self.contact_start;
        }
        rec.slip_events = self.side.spring().slip_events;
        // The elastic force is integrated like the others, not taken as minus the change of
        // its potential: in the clipped tail the force is switched off while the potential is
        // not yet zero, and that stored energy is lost to the clip (a real part of the normal
        // work).
        rec.work_normal = self.works.normal.total;
        rec.work_friction = self.works.tangential.total;
        rec.work_damping = self.works.damping.total;
        self.side
            .close(&mut rec, init, self.stepper.lanes(), self.n_sep);
        rec
    }
}
