//! One impact, from first touch to separation: the record (docs/model.md, section 9) and an optional trace.

use crate::error::{Error, Result};
use crate::geometry::Shape;
use crate::integrate::events;
use crate::integrate::{Gear5, Stepper, Verlet};
use crate::law::{Contact, DiscPlate, Dof, Forces, PlateGeometry, ShapePlate, SpherePlate};
use crate::model::{Initial, Integrator, Model, Scene};
use std::f64::consts::PI;

pub mod record;

pub use record::{estimate_max_depth, Cell, Record, Trace, RECORD_COLUMNS, TIMEOUT_CONTACT_TIMES};

/// Smallest estimated maximal depth, in units of the spacing of doubles at the centre's height
/// (ulp(r)), that an impact may have: below it the centre's height cannot resolve the overlap
/// (a grazing impact at theta ~ 1e-10 deg moves the centre by a few ulps) and the contact law
/// would act on round-off. 2^20 ulps keep the depth to ~1e-6 relative.
pub const MIN_DEPTH_ULPS: f64 = 1_048_576.0;

/// Most fixed steps an estimated contact may need (~10 s of one core): beyond it a scene is
/// refused with the cure named rather than run for hours (a tiny dt_factor, a creeping contact).
pub const MAX_STEPS_PER_CONTACT: f64 = 1e8;

/// Largest local error per step that Gear-5 accepts in a polygon's contact, relative to the
/// estimated largest depth (x and y; phi in units of r): steps in which the force changes
/// faster than the step resolves are halved until they meet it.
pub const ERROR_TOLERANCE: f64 = 1e-12;

/// Where in the last step the depth crossed zero, by linear interpolation (0 when the two
/// depths are equal, e.g. both exactly zero: never 0 / 0).
#[inline]
fn crossing_fraction(prev_depth: f64, depth: f64) -> f64 {
    let span = prev_depth - depth;
    if span == 0.0 {
        0.0
    } else {
        prev_depth / span
    }
}

/// Simulates one impact.
pub fn simulate(scene: &Scene, init: &Initial) -> Result<Record> {
    let model = Model::new(scene)?;
    run(&model, init, None)
}

/// Simulates one impact of an already derived model, without [`Model::new`]'s checks of
/// `dt_factor` (used to measure the stability bound above it; see `tests/stability.rs`).
pub fn simulate_model(model: &Model, init: &Initial) -> Result<Record> {
    run(model, init, None)
}

/// Simulates one impact and records every step.
pub fn simulate_with_trace(scene: &Scene, init: &Initial) -> Result<(Record, Trace)> {
    let model = Model::new(scene)?;
    let mut trace = Trace::default();
    let rec = run(&model, init, Some(&mut trace))?;
    Ok((rec, trace))
}

fn run(model: &Model, init: &Initial, trace: Option<&mut Trace>) -> Result<Record> {
    model.check_initial(init)?;
    let scene = &model.scene;
    let depth_est = estimate_max_depth(model, init)?;
    let resolution = MIN_DEPTH_ULPS * f64::EPSILON * model.r;
    if depth_est < resolution {
        return Err(Error::invalid(
            "v",
            init.vx.hypot(init.vy),
            format!(
                "large enough that the estimated depth ({depth_est:e} m, at the normal speed \
                 v sin(theta) = {:e} m/s) resolves in double precision (>= {resolution:e} m at \
                 r = {} m): raise theta_deg or v, or lower E",
                init.vy.abs(),
                model.r
            ),
        ));
    }
    let t_est = PI * depth_est / init.vy.abs();
    let steps_per_contact = t_est / model.dt;
    if scene.integrator != Integrator::Reference && steps_per_contact > MAX_STEPS_PER_CONTACT {
        return Err(Error::invalid(
            "dt_factor",
            scene.dt_factor,
            format!(
                "large enough that a contact takes at most {MAX_STEPS_PER_CONTACT:e} steps (this \
                 scene needs ~{steps_per_contact:.1e}: raise dt_factor, theta_deg or v, or use \
                 integrator \"reference\")"
            ),
        ));
    }
    let max_steps = (TIMEOUT_CONTACT_TIMES * t_est / model.dt).ceil().min(1e12) as u64 + 10;
    let q0 = [0.0, scene.shape.touch_height(init.phi0), init.phi0];
    let v0 = [init.vx, init.vy, init.omega];
    match scene.integrator {
        Integrator::Gear5 => Ok(integrate(
            model,
            init,
            Gear5::new(q0, v0, model.dt),
            max_steps,
            depth_est,
            trace,
        )),
        Integrator::Verlet => Ok(integrate(
            model,
            init,
            Verlet::new(q0, v0, model.dt),
            max_steps,
            depth_est,
            trace,
        )),
        Integrator::Reference => Ok(crate::integrate::adaptive::integrate(
            model,
            init,
            depth_est,
            &crate::integrate::adaptive::ReferenceOptions::default(),
            trace,
        )),
    }
}

/// The work of a force along the steps, from its power at the end of each step: each step's
/// share is the integral of the parabola through the last three powers (third order, for
/// unequal steps too), the first step of a smooth stretch (from touch or from an event, where
/// the power may jump) the trapezoid's.
#[derive(Debug, Clone, Copy)]
struct Work {
    total: f64,
    /// Power at the end of the last step and of the one before.
    p: f64,
    p_prev: f64,
    /// Length of the last step; 0 at the start of a stretch.
    h: f64,
    /// One step into the stretch (its first share is still the trapezoid's).
    second: bool,
}

impl Work {
    fn starting_at(p: f64) -> Self {
        Work {
            total: 0.0,
            p,
            p_prev: 0.0,
            h: 0.0,
            second: false,
        }
    }

    /// A new smooth stretch from power `p`, keeping the work so far.
    fn restart(self, p: f64) -> Self {
        Work {
            total: self.total,
            ..Work::starting_at(p)
        }
    }

    /// The trapezoid's share, as for the exact disc (see `integrate_on`).
    #[inline(always)]
    fn push_trapezoid(&mut self, h: f64, p: f64) {
        self.total += 0.5 * h * (self.p + p);
        self.p = p;
    }

    #[inline(always)]
    fn push(&mut self, h: f64, p: f64) {
        let h1 = self.h;
        if self.second && h == h1 {
            // The stretch's first step was a trapezoid: now that a third power is known, its
            // share becomes the parabola's, h (5 p0 + 8 p1 - p2) / 12.
            self.total += h * (2.0 * self.p - self.p_prev - p) * (1.0 / 12.0);
        }
        self.second = h1 == 0.0;
        self.total += if h == h1 {
            h * (5.0 * p + 8.0 * self.p - self.p_prev) * (1.0 / 12.0)
        } else if h1 > 0.0 && h <= 4.0 * h1 {
            // Unequal steps (events, refined steps); far longer than the last one (after a
            // tiny cut) the parabola would amplify round-off, and the trapezoid is used.
            let s = h1 + h;
            h / 6.0
                * (p * (2.0 * h + 3.0 * h1) / s + self.p * (h + 3.0 * h1) / h1
                    - self.p_prev * h * h / (h1 * s))
        } else {
            0.5 * h * (self.p + p)
        };
        (self.p_prev, self.p, self.h) = (self.p, p, h);
    }
}

fn kinetic_energy(model: &Model, v: &Dof) -> f64 {
    0.5 * model.mass * (v[0] * v[0] + v[1] * v[1]) + 0.5 * model.inertia * v[2] * v[2]
}

/// Integrates one impact with `stepper`, the loop compiled separately for the exact disc and
/// for other shapes (see [`PlateGeometry`]).
fn integrate<S: Stepper>(
    model: &Model,
    init: &Initial,
    stepper: S,
    max_steps: u64,
    depth_scale: f64,
    trace: Option<&mut Trace>,
) -> Record {
    match &model.scene.shape {
        Shape::Disc { r } => integrate_on(
            model,
            init,
            stepper,
            DiscPlate { r: *r },
            max_steps,
            depth_scale,
            trace,
        ),
        Shape::Sphere { r } => integrate_on(
            model,
            init,
            stepper,
            SpherePlate { r: *r },
            max_steps,
            depth_scale,
            trace,
        ),
        shape => {
            let method = model.scene.overlap;
            integrate_on(
                model,
                init,
                stepper,
                ShapePlate { shape, method },
                max_steps,
                depth_scale,
                trace,
            )
        }
    }
}

fn integrate_on<S: Stepper, G: PlateGeometry>(
    model: &Model,
    init: &Initial,
    mut stepper: S,
    geometry: G,
    mut max_steps: u64,
    depth_scale: f64,
    mut trace: Option<&mut Trace>,
) -> Record {
    let contact_budget = max_steps;
    let dt = model.dt;
    let inv_mass = [1.0 / model.mass, 1.0 / model.mass, 1.0 / model.inertia];
    let mut contact = Contact::new(model, geometry);
    let mut rec = Record {
        contacts: 1,
        ..Record::default()
    };
    let v_in = stepper.velocity();
    rec.energy_in = kinetic_energy(model, &v_in);

    // Works of the normal and tangential forces: quadratures of their powers along the steps.
    let (mut w_n, mut w_t) = (Work::starting_at(0.0), Work::starting_at(0.0));
    let mut was_pushing = false;
    let mut t_extra = 0.0;
    let (mut max_area, mut max_depth) = (0.0f64, 0.0f64);
    let mut steps = 0u64;
    let (mut in_contact, mut contact_start, mut prev_depth) = (true, 0.0, 0.0);
    // Polygons: steps located on events and refined where the force changes within a step
    // (see `events`), only without friction: with it the stick/slip switches bound the fixed-step integrators
    // to first order anyway (docs/model.md, section 7.6), and the restarts and refined steps measured no better
    // e_n while they disturbed the energy balance of frictional spinning polygons (its
    // residual rose from ~1e-7 to ~2e-6 at the default step), so those keep the plain steps.
    let events = G::EVENTS && model.scene.mu == 0.0;
    let mut control = None;
    if events {
        // First touch is an event: start on the branch being entered (face first, the force
        // grows linearly from touch, and its rate is not zero).
        let (q, v) = (stepper.position(), stepper.velocity());
        let b = events::branch_start(&contact, &q, &v, &[0.0; 3], &inv_mass, dt);
        stepper.restart(&b.a, &b.jerk, dt);
        let tol = ERROR_TOLERANCE * depth_scale;
        control = Some(events::EventControl {
            corners: b.corners,
            h: dt,
            dt,
            tolerance: tol,
        });
        let (p_el, p_d, p_t) = b.powers;
        (w_n, w_t) = (Work::starting_at(p_el + p_d), Work::starting_at(p_t));
    }
    if let Some(tr) = trace.as_deref_mut() {
        tr.push(
            0.0,
            &stepper.position(),
            &v_in,
            &Forces::default(),
            0.0,
            0.0,
        );
    }
    loop {
        if steps >= max_steps {
            rec.timed_out = true;
            break;
        }
        let (f, h, restarted) = match control.as_mut() {
            None => (stepper.step(&mut contact, dt, &inv_mass), dt, None),
            Some(c) => {
                let taken = c.step(&mut stepper, &mut contact, &inv_mass);
                (taken.forces, taken.h, taken.restart)
            }
        };
        steps += 1;
        let (q, v) = (stepper.position(), stepper.velocity());
        let (p_el, p_d, p_t) = f.powers(q[1], &v);
        if events && S::HIGH_ORDER {
            // The normal power kinks where the force is clipped to zero or released: a parabola
            // through both sides would be worse than the trapezoid, so a new stretch starts
            // there.
            let pushing = f.f_el + f.f_d > 0.0;
            if pushing == was_pushing {
                w_n.push(h, p_el + p_d);
                w_t.push(h, p_t);
            } else {
                w_n.push_trapezoid(h, p_el + p_d);
                w_t.push_trapezoid(h, p_t);
                (w_n, w_t) = (w_n.restart(p_el + p_d), w_t.restart(p_t));
            }
            was_pushing = pushing;
        } else {
            w_n.push_trapezoid(h, p_el + p_d);
            w_t.push_trapezoid(h, p_t);
        }
        if events {
            t_extra += h - dt;
            if let Some(b) = restarted {
                // A new smooth stretch of the powers starts (they may jump at the event).
                let (p_el, p_d, p_t) = b.powers;
                (w_n, w_t) = (w_n.restart(p_el + p_d), w_t.restart(p_t));
            }
        }
        let t = steps as f64 * dt + t_extra;
        // Plain comparisons rather than f64::max: the same result for these non-NaN values,
        // without max's NaN handling in the loop.
        if let Some(o) = f.overlap {
            if o.area > max_area {
                max_area = o.area;
            }
        }
        let depth = contact.geometry.depth(q[1], q[2]);
        if depth > max_depth {
            max_depth = depth;
        }
        // Contact starts and ends between steps: crossings interpolated linearly.
        if in_contact && depth <= 0.0 {
            rec.contact_time += t - h + crossing_fraction(prev_depth, depth) * h - contact_start;
            in_contact = false;
            // The timeout budgets contact, not the free flight of a spinning polygon between
            // contacts: in uniform motion its circumscribed circle clears within
            // (r - y) / v_y when rising, and when sinking its centre (which stays above the
            // plate) meets it within y / |v_y|. Capped, so that a near-zero v_y still ends,
            // as a timeout.
            let gap = if v[1] > 0.0 { model.r - q[1] } else { q[1] };
            let flight = (gap.max(0.0) / (v[1].abs() * dt)).ceil();
            let cap = 20.0 * contact_budget as f64;
            max_steps = max_steps.saturating_add(flight.min(cap) as u64 + 1);
        } else if !in_contact && depth > 0.0 {
            contact_start = t - h + crossing_fraction(prev_depth, depth) * h;
            rec.contacts += 1;
            in_contact = true;
        }
        if let Some(tr) = trace.as_deref_mut() {
            tr.push(t, &q, &v, &f, depth, contact.spring.xi);
        }
        prev_depth = depth;
        // Done once no part of the particle can reach the plate: its circumscribed circle is
        // clear and moving away, or every point of it moves away (v_y > r |omega|: in free
        // flight the gap then only grows; without this a face-first polygon at a glancing
        // angle would time out while drifting up to clear r).
        if !in_contact && v[1] > 0.0 && (q[1] >= model.r || v[1] > model.r * v[2].abs()) {
            break;
        }
    }
    rec.steps = steps;
    rec.max_area = max_area;
    rec.max_depth = max_depth;
    let v = stepper.velocity();
    if in_contact {
        rec.contact_time += rec.steps as f64 * dt + t_extra - contact_start;
    }
    rec.slip_events = contact.spring.slip_events;
    // The elastic force is integrated like the others, not taken as minus the change of its
    // potential: in the clipped tail the force is switched off while the potential is not
    // yet zero, and that stored energy is lost to the clip (a real part of the normal work).
    rec.work_normal = w_n.total;
    rec.work_friction = w_t.total;
    rec.energy_out = kinetic_energy(model, &v);
    rec.energy_residual =
        (rec.energy_out - rec.energy_in - rec.work_normal - rec.work_friction) / rec.energy_in;
    rec.vx_out = v[0];
    rec.vy_out = v[1];
    rec.omega_out = v[2];
    rec.e_n = -v[1] / init.vy;
    rec.e_t = (init.vx != 0.0).then(|| v[0] / init.vx);
    rec.e_kin = (v[0].hypot(v[1])) / init.vx.hypot(init.vy);
    let v_cp = init.vx + model.r * init.omega;
    rec.beta = (v_cp != 0.0).then(|| -(v[0] + model.r * v[2]) / v_cp);
    rec.rebound_angle_deg = v[1].atan2(v[0]).to_degrees();
    rec.separated = !rec.timed_out;
    rec
}
