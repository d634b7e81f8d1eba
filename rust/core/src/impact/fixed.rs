//! The fixed-step loop of one impact (Gear-5, Verlet): steps of dt from first touch, each
//! with its works, extremes and contact bookkeeping, events located on frictionless polygons
//! ([`crate::integrate::events`]), free flight jumped over (`super::flight`), until the
//! particle clears the plate or a budget is spent.

use super::budget::step_budget;
use super::flight;
use super::record::{Record, StopReason, Trace, TIMEOUT_CONTACT_TIMES};
use super::work::Works;
use crate::cancel::Cancel;
use crate::error::Result;
use crate::geometry::Shape;
use crate::integrate::events;
use crate::integrate::{Gear5, Stepper, Verlet};
use crate::law::{Contact, DiscPlate, Dof, Forces, PlateGeometry, ShapePlate, SpherePlate};
use crate::model::{Initial, Integrator, Model, NormalLaw};
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

/// One impact with a fixed-step integrator (validated model and initial state).
pub(super) fn run_fixed(
    model: &Model,
    init: &Initial,
    depth_est: f64,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let scene = &model.scene;
    let limits = Limits {
        max_steps: step_budget(model, init, depth_est),
        contact_time: TIMEOUT_CONTACT_TIMES * PI * depth_est / init.vy.abs(),
        depth_scale: depth_est,
    };
    let q0 = [0.0, scene.shape.touch_height(init.phi0), init.phi0];
    let v0 = [init.vx, init.vy, init.omega];
    match scene.integrator {
        Integrator::Verlet => integrate(
            model,
            init,
            Verlet::new(q0, v0, model.dt),
            &limits,
            trace,
            cancel,
        ),
        _ => integrate(
            model,
            init,
            Gear5::new(q0, v0, model.dt),
            &limits,
            trace,
            cancel,
        ),
    }
}

/// The budgets of one fixed-step impact.
#[derive(Debug, Clone, Copy)]
struct Limits {
    /// Most steps ([`step_budget`]).
    max_steps: u64,
    /// Most contact time, summed over contacts (s): [`TIMEOUT_CONTACT_TIMES`] estimated
    /// contact times.
    contact_time: f64,
    /// The estimated largest depth (m), the scale of the step control's tolerance.
    depth_scale: f64,
}

/// Integrates one impact with `stepper`, the loop compiled separately for the exact disc and
/// for other shapes (see [`PlateGeometry`]).
fn integrate<S: Stepper>(
    model: &Model,
    init: &Initial,
    stepper: S,
    limits: &Limits,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    match &model.scene.shape {
        Shape::Disc { r } => {
            FixedLoop::new(model, stepper, DiscPlate { r: *r }, limits).run(init, trace, cancel)
        }
        Shape::Sphere { r } => {
            FixedLoop::new(model, stepper, SpherePlate { r: *r }, limits).run(init, trace, cancel)
        }
        shape => {
            let method = model.scene.overlap;
            let geometry = ShapePlate { shape, method };
            FixedLoop::new(model, stepper, geometry, limits).run(init, trace, cancel)
        }
    }
}

/// The state of one fixed-step impact between steps.
struct FixedLoop<'a, S, G> {
    model: &'a Model,
    stepper: S,
    contact: Contact<'a, G>,
    limits: Limits,
    inv_mass: Dof,
    /// Polygons without friction: steps located on events and refined where the force
    /// changes within a step (see `events`), only without friction: with it the stick/slip
    /// switches bound the fixed-step integrators to first order anyway (docs/model.md), and the
    /// restarts and refined steps measured no better e_n while they disturbed the energy
    /// balance of frictional spinning polygons (its residual rose from ~1e-7 to ~2e-6 at the
    /// default step), so those keep the plain steps.
    events: bool,
    control: Option<events::EventControl>,
    /// Works of the normal and tangential forces: quadratures of their powers along the steps
    /// (of third order where events are located and the stepper is Gear-5).
    works: Works,
    /// Time taken beyond `steps * dt` (shortened and refined steps, flights jumped over).
    t_extra: f64,
    steps: u64,
    in_contact: bool,
    contact_start: f64,
    prev_depth: f64,
    rec: Record,
}

impl<'a, S: Stepper, G: PlateGeometry> FixedLoop<'a, S, G> {
    fn new(model: &'a Model, stepper: S, geometry: G, limits: &Limits) -> Self {
        let events = G::EVENTS && (model.scene.mu == 0.0 || Self::linear(model));
        FixedLoop {
            model,
            stepper,
            contact: Contact::new(model, geometry),
            limits: *limits,
            inv_mass: [1.0 / model.mass, 1.0 / model.mass, 1.0 / model.inertia],
            events,
            control: None,
            works: Works::new(events && S::HIGH_ORDER),
            t_extra: 0.0,
            steps: 0,
            in_contact: true,
            contact_start: 0.0,
            prev_depth: 0.0,
            rec: Record {
                contacts: 1,
                step_budget: limits.max_steps,
                ..Record::default()
            },
        }
    }

    /// The linear law on a polygon (Gear-5 only): one dashpot per submerged corner, whose force
    /// jumps as the corner crosses the plate, so every crossing is an event, with friction too
    /// (a step straddling a jump errs to first order: energy residuals up to 2.7e-5 with plain
    /// steps, 1.5e-6 located, quick matrix and `examples/linear_events.rs`). Verlet is
    /// refused for this law on a polygon (`check_laws`): its audit, the trapezoid of the
    /// powers, closes only where the force is continuous and the step fixed (the boundary term
    /// h^2 |F|^2 / 8m telescopes away), so every located jump would leave an O(h^2) residual
    /// (up to 7e-5 at the default step on a triangle), and plain steps miss the jumps.
    fn linear(model: &Model) -> bool {
        G::EVENTS && matches!(model.scene.normal_law, NormalLaw::Linear { .. })
    }

    fn run(
        mut self,
        init: &Initial,
        mut trace: Option<&mut Trace>,
        cancel: &Cancel,
    ) -> Result<Record> {
        let v_in = self.stepper.velocity();
        self.rec.energy_in = self.model.kinetic_energy(&v_in);
        if self.events {
            self.start_events();
        }
        if let Some(tr) = trace.as_deref_mut() {
            let q = self.stepper.position();
            tr.push(0.0, &q, &v_in, &Forces::default(), 0.0, 0.0);
        }
        loop {
            cancel.poll(self.steps)?;
            if let Some(stop) = self.budget_spent() {
                self.rec.stop = stop;
                break;
            }
            let (q, v) = self.step(trace.as_deref_mut());
            // Done once no part of the particle can reach the plate: its circumscribed circle
            // is clear and moving away, or every point of it moves away (v_y > r |omega|: in
            // free flight the gap then only grows; without this a face-first polygon at a
            // glancing angle would time out while drifting up to clear r).
            let r = self.model.r;
            if !self.in_contact && v[1] > 0.0 && (q[1] >= r || v[1] > r * v[2].abs()) {
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
        let dt = self.model.dt;
        let (q, v) = (self.stepper.position(), self.stepper.velocity());
        let b = events::branch_start(&self.contact, &q, &v, &[0.0; 3], &self.inv_mass, dt);
        self.stepper.restart(&b.a, &b.jerk, dt);
        self.control = Some(events::EventControl {
            corners: b.corners,
            h: dt,
            dt,
            tolerance: tolerance(self.limits.depth_scale, self.model.r),
            every_crossing: Self::linear(self.model),
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
        self.steps as f64 * self.model.dt + self.t_extra
    }

    /// One step, with its works, extremes and contact bookkeeping; the new position and
    /// velocity.
    fn step(&mut self, trace: Option<&mut Trace>) -> (Dof, Dof) {
        let dt = self.model.dt;
        let (f, h, restarted) = match self.control.as_mut() {
            None => (
                self.stepper.step(&mut self.contact, dt, &self.inv_mass),
                dt,
                None,
            ),
            Some(c) => {
                let taken = c.step(&mut self.stepper, &mut self.contact, &self.inv_mass);
                (taken.forces, taken.h, taken.restart)
            }
        };
        self.steps += 1;
        let (q, v) = (self.stepper.position(), self.stepper.velocity());
        self.add_work(&f, h, &q, &v);
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
        if let Some(o) = f.overlap {
            if o.area > self.rec.max_area {
                self.rec.max_area = o.area;
            }
        }
        let depth = self.contact.geometry.depth(q[1], q[2]);
        if depth > self.rec.max_depth {
            self.rec.max_depth = depth;
        }
        self.cross(t, h, depth);
        if let Some(tr) = trace {
            tr.push(t, &q, &v, &f, depth, self.contact.spring.xi);
        }
        self.prev_depth = depth;
        (q, v)
    }

    /// Adds the step's share of the works.
    #[inline(always)]
    fn add_work(&mut self, f: &Forces, h: f64, q: &Dof, v: &Dof) {
        self.works.add(h, f.powers(q[1], v), f.f_el + f.f_d > 0.0);
    }

    /// Contact starts and ends between steps: crossings interpolated linearly.
    #[inline(always)]
    fn cross(&mut self, t: f64, h: f64, depth: f64) {
        if self.in_contact && depth <= 0.0 {
            let end = t - h + crossing_fraction(self.prev_depth, depth) * h;
            self.rec.contact_time += end - self.contact_start;
            self.in_contact = false;
        } else if !self.in_contact && depth > 0.0 {
            self.contact_start = t - h + crossing_fraction(self.prev_depth, depth) * h;
            self.rec.contacts += 1;
            self.in_contact = true;
        }
    }

    /// In free flight: jumps over it (see [`flight`]), each advance counted as a step; true
    /// when no part of the particle can reach the plate again.
    fn fly(&mut self, trace: Option<&mut Trace>) -> bool {
        let (q, v) = (self.stepper.position(), self.stepper.velocity());
        let dt = self.model.dt;
        let geometry = &self.contact.geometry;
        let gap = |t: f64| -geometry.depth(q[1] + v[1] * t, q[2] + v[2] * t);
        let left = self.limits.max_steps.saturating_sub(self.steps);
        let (jump, advances) = flight::jump(gap, q[1], &v, (self.model.r, self.model.r), dt, left);
        let (t_jump, done) = match jump {
            flight::Jump::Stay => return false,
            flight::Jump::To(t) => (t, false),
            flight::Jump::Clear(t) => (t, true),
        };
        let depth = -gap(t_jump);
        self.steps += advances;
        let q_new: Dof = std::array::from_fn(|i| q[i] + v[i] * t_jump);
        self.stepper = S::start(q_new, v, dt);
        self.t_extra += t_jump;
        if let Some(c) = self.control.as_mut() {
            (c.h, c.corners) = (dt, None);
        }
        self.works.part();
        self.prev_depth = depth;
        if let Some(tr) = trace {
            let (t, xi) = (self.time(), self.contact.spring.xi);
            tr.push(t, &q_new, &v, &Forces::default(), depth, xi);
        }
        done
    }

    fn finish(self, init: &Initial) -> Record {
        let model = self.model;
        let mut rec = self.rec;
        rec.steps = self.steps;
        if self.in_contact {
            rec.contact_time += self.time() - self.contact_start;
        }
        let v = self.stepper.velocity();
        rec.slip_events = self.contact.spring.slip_events;
        // The elastic force is integrated like the others, not taken as minus the change of
        // its potential: in the clipped tail the force is switched off while the potential is
        // not yet zero, and that stored energy is lost to the clip (a real part of the normal
        // work).
        rec.work_normal = self.works.normal.total;
        rec.work_friction = self.works.tangential.total;
        rec.work_damping = self.works.damping.total;
        rec.close(model, init, &v);
        rec
    }
}
