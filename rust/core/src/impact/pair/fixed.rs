//! The pair's fixed-step loop (Gear-5, Verlet on four lanes).

use super::record::close_pair;
use crate::cancel::Cancel;
use crate::error::Result;
use crate::geometry::pair::PairGeometry;
use crate::impact::fixed::crossing_fraction;
use crate::impact::record::{Record, StopReason, Trace};
use crate::integrate::{LaneForces, Lanes, Stepper};
use crate::law::pair::{PairContact, PairForces};
use crate::model::{Initial, Pair};

/// The budgets of one pair impact.
#[derive(Debug, Clone, Copy)]
pub(super) struct Limits {
    pub(super) max_steps: u64,
    pub(super) contact_time: f64,
}

/// A pair's contact law as the steppers see it (one evaluation per step).
struct OnPair<'c, 'm, G> {
    contact: &'c mut PairContact<'m, G>,
    dt: f64,
}

impl<G: PairGeometry> LaneForces for OnPair<'_, '_, G> {
    type Out = PairForces;

    #[inline(always)]
    fn forces(self, q: &Lanes, v: &Lanes) -> (Lanes, PairForces) {
        self.contact.evaluate(q, v, self.dt)
    }
}

/// The state of one pair impact between steps.
pub(super) struct PairLoop<'a, S, G> {
    pair: &'a Pair,
    init: Initial,
    stepper: S,
    contact: PairContact<'a, G>,
    limits: Limits,
    inv_mass: Lanes,
    /// Works of the normal and tangential forces (trapezoids of their powers) and the powers
    /// at the end of the last step.
    work: [f64; 2],
    power: [f64; 2],
    steps: u64,
    in_contact: bool,
    contact_start: f64,
    prev_depth: f64,
    rec: Record,
}

impl<'a, S: Stepper, G: PairGeometry> PairLoop<'a, S, G> {
    pub(super) fn new(pair: &'a Pair, init: &Initial, geometry: G, limits: Limits) -> Self {
        let q0 = [0.0, geometry.touch_distance(), init.phi0, init.partner_phi0];
        let v0 = [init.vx, init.vy, init.omega, init.partner_omega];
        let law = &pair.law;
        PairLoop {
            pair,
            init: *init,
            stepper: S::start_lanes(q0, v0, law.dt),
            contact: PairContact::new(law, geometry),
            limits,
            inv_mass: [
                1.0 / pair.m_star,
                1.0 / pair.m_star,
                1.0 / pair.particle.inertia,
                1.0 / pair.i2,
            ],
            work: [0.0; 2],
            power: [0.0; 2],
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

    pub(super) fn run(mut self, mut trace: Option<&mut Trace>, cancel: &Cancel) -> Result<Record> {
        let (q0, v0) = self.stepper.lanes();
        self.rec.energy_in = self.pair.kinetic_energy(&v0);
        if let Some(tr) = trace.as_deref_mut() {
            tr.push_pair(0.0, &q0, &v0, &PairForces::default(), 0.0);
        }
        loop {
            cancel.poll(self.steps)?;
            if let Some(stop) = self.budget_spent() {
                self.rec.stop = stop;
                break;
            }
            let (q, v) = self.step(trace.as_deref_mut());
            // Apart and moving apart: round bodies cannot touch again.
            if !self.in_contact && q[0] * v[0] + q[1] * v[1] > 0.0 {
                break;
            }
        }
        Ok(self.finish())
    }

    fn time(&self) -> f64 {
        self.steps as f64 * self.pair.law.dt
    }

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

    /// One step with its works, extremes and contact bookkeeping; the new lanes.
    fn step(&mut self, trace: Option<&mut Trace>) -> (Lanes, Lanes) {
        let dt = self.pair.law.dt;
        let law = OnPair {
            contact: &mut self.contact,
            dt,
        };
        let f = self.stepper.advance(dt, &self.inv_mass, law);
        self.steps += 1;
        let (q, v) = self.stepper.lanes();
        let (p_el, p_d, p_t) = f.powers(&v);
        let p = [p_el + p_d, p_t];
        for i in 0..2 {
            self.work[i] += 0.5 * dt * (self.power[i] + p[i]);
        }
        self.power = p;
        if f.area > self.rec.max_area {
            self.rec.max_area = f.area;
        }
        let depth = self.contact.geometry.touch_distance() - (q[0] * q[0] + q[1] * q[1]).sqrt();
        if depth > self.rec.max_depth {
            self.rec.max_depth = depth;
        }
        self.cross(self.time(), dt, depth);
        if let Some(tr) = trace {
            tr.push_pair(self.time(), &q, &v, &f, self.contact.spring.xi);
        }
        self.prev_depth = depth;
        (q, v)
    }

    /// Contact starts and ends between steps: crossings interpolated linearly.
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

    fn finish(mut self) -> Record {
        if self.in_contact {
            self.rec.contact_time += self.time() - self.contact_start;
        }
        let (q, v) = self.stepper.lanes();
        let mut rec = self.rec;
        rec.steps = self.steps;
        rec.slip_events = self.contact.spring.slip_events;
        rec.work_normal = self.work[0];
        rec.work_friction = self.work[1];
        let reach = self.contact.geometry.touch_distance();
        close_pair(&mut rec, self.pair, &self.init, (&q, &v), reach);
        rec
    }
}
