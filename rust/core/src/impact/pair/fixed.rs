//! The pair's fixed-step loop (Gear-5, Verlet on four lanes), its free flights between the
//! contacts of bodies with corners skipped (`flight`).

use super::flight::{self, Flight};
use super::record::{close_pair, separation_normal};
use super::Start;
use crate::cancel::Cancel;
use crate::error::Result;
use crate::geometry::pair::PairGeometry;
use crate::impact::fixed::crossing_fraction;
use crate::impact::record::{Record, StopReason, Trace};
use crate::impact::work::Works;
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
    /// The pair's angular momentum, restored on the final state (`Pair::restoring_turn`).
    l0: f64,
    pair: &'a Pair,
    init: Initial,
    stepper: S,
    contact: PairContact<'a, G>,
    limits: Limits,
    inv_mass: Lanes,
    /// Works of the normal and tangential forces: quadratures of their powers along the steps.
    works: Works,
    steps: u64,
    /// Time skipped in free flights between contacts (s).
    skipped: f64,
    /// The line of centres when the last contact ended.
    n_sep: [f64; 2],
    y0: f64,
    in_contact: bool,
    contact_start: f64,
    prev_depth: f64,
    rec: Record,
}

impl<'a, S: Stepper, G: PairGeometry> PairLoop<'a, S, G> {
    pub(super) fn new(
        pair: &'a Pair,
        init: &Initial,
        (geometry, start): (G, Start),
        limits: Limits,
    ) -> Self {
        let q0 = start.q;
        let v0 = [init.vx, init.vy, init.omega, init.partner_omega];
        let law = &pair.law;
        PairLoop {
            l0: pair.angular_momentum(&q0, &v0),
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
            // The trapezoid: Gear-5 steps through the pair's switches (a corner entering, its
            // dashpot's force jumping) unlocated, and a parabola through them left 10 times the
            // trapezoid's residual (twin triangles, linear law: -1.2e-4 against +1.1e-5).
            works: Works::new(false),
            steps: 0,
            skipped: 0.0,
            n_sep: [0.0, 1.0],
            y0: q0[1],
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
            if !self.in_contact && self.flight_over(&q, &v) {
                break;
            }
        }
        Ok(self.finish())
    }

    /// Apart: whether the bodies can never touch again (round bodies: once moving apart;
    /// bodies with corners: once their circumscribed circles part), skipping the flight up
    /// to where they might.
    fn flight_over(&mut self, q: &Lanes, v: &Lanes) -> bool {
        if !G::CORNERS {
            return q[0] * v[0] + q[1] * v[1] > 0.0;
        }
        let dt = self.pair.law.dt;
        let radii = [self.pair.particle.r, self.pair.r2];
        match flight::skip(&self.contact.geometry, q, v, radii, 4.0 * dt) {
            Flight::Over => true,
            Flight::Skip(tau) if tau > 0.0 => {
                let q = flight::advance(q, v, tau);
                self.stepper = S::start_lanes(q, *v, dt);
                self.skipped += tau;
                self.works.part();
                self.prev_depth = self.contact.geometry.signed_depth(&q);
                false
            }
            Flight::Skip(_) => false,
        }
    }

    fn time(&self) -> f64 {
        self.steps as f64 * self.pair.law.dt + self.skipped
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
        self.works.add(dt, f.powers(&v), f.f_el + f.f_d > 0.0);
        if f.area > self.rec.max_area {
            self.rec.max_area = f.area;
        }
        // The depth at the step's end (bodies with corners in contact: the evaluation's, to
        // spare a second intersection).
        let depth = if G::CORNERS && f.area > 0.0 {
            f.depth
        } else {
            self.contact.geometry.signed_depth(&q)
        };
        if depth > self.rec.max_depth {
            self.rec.max_depth = depth;
        }
        self.cross(self.time(), dt, depth, &q);
        if let Some(tr) = trace {
            tr.push_pair(self.time(), &q, &v, &f, self.contact.spring.xi);
        }
        self.prev_depth = depth;
        (q, v)
    }

    /// Contact starts and ends between steps: crossings interpolated linearly.
    fn cross(&mut self, t: f64, h: f64, depth: f64, q: &Lanes) {
        if self.in_contact && depth <= 0.0 {
            let end = t - h + crossing_fraction(self.prev_depth, depth) * h;
            self.rec.contact_time += end - self.contact_start;
            self.in_contact = false;
            let d = q[0].hypot(q[1]);
            self.n_sep = [q[0] / d, q[1] / d];
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
        let (q, mut v) = self.stepper.lanes();
        // The angular momentum restored once, on the final state: Gear-5's steps drift by up
        // to 7e-10 of m* v (r1 + r2) per impact (Verlet's by round-off), far below their error;
        // restored after every step, as the adaptive path does, it cost a quarter of a disc
        // pair's step (40 against 32.5 ns).
        let turn = self.pair.restoring_turn(&q, &v, self.l0);
        for (vi, d) in v.iter_mut().zip(turn) {
            *vi += d;
        }
        let mut rec = self.rec;
        rec.steps = self.steps;
        rec.slip_events = self.contact.spring.slip_events;
        rec.work_normal = self.works.normal.total;
        rec.work_friction = self.works.tangential.total;
        rec.work_damping = self.works.damping.total;
        let n_sep = if G::CORNERS {
            self.n_sep
        } else {
            separation_normal(&q, &v, self.contact.geometry.reach())
        };
        close_pair(&mut rec, self.pair, &self.init, (&q, &v), (self.y0, n_sep));
        rec
    }
}
