//! One impact of a pair (docs/model.md, section 17) on the fixed-step integrators: the two
//! bodies touch with their centres on the y axis (the particle above), the relative velocity
//! g = v (cos theta, -sin theta) at first touch, and the pair is stepped in its centre-of-mass
//! frame on four lanes (x, y of the particle relative to the partner, phi1, phi2) until the
//! bodies separate. Round bodies cannot touch again once they move apart.

use super::budget::{self, MIN_DEPTH_ULPS};
use super::fixed::crossing_fraction;
use super::record::{Record, StopReason, Trace, TIMEOUT_CONTACT_TIMES};
use crate::cancel::Cancel;
use crate::error::{ensure_param, finite, Error, Result};
use crate::geometry::pair::{DiscPair, PairGeometry, SpherePair};
use crate::geometry::Shape;
use crate::integrate::{Gear5, LaneForces, Lanes, Stepper, Verlet};
use crate::law::pair::{PairContact, PairForces};
use crate::model::scene::MAX_RIM_SPEED;
use crate::model::{Initial, Integrator, Model, NormalLaw, Pair};
use std::f64::consts::PI;

/// Simulates one impact of the pair of a validated particle model whose scene has a partner.
pub(super) fn run(
    model: &Model,
    init: &Initial,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let pair = Pair::new(model.clone())?;
    let depth_est = checked_depth(&pair, init)?;
    let mut rec = run_fixed(&pair, init, depth_est, trace, cancel)?;
    if model.scene.error_estimate {
        rec.err_est = super::richardson_estimate(model, init, &rec, |half| {
            run_fixed(&Pair::new(half.clone())?, init, depth_est, None, cancel)
        })?;
    }
    Ok(rec)
}

/// The pair's estimated largest overlap, after the checks of its initial state: the
/// partner's spin, a depth that double precision resolves, a contact of at most
/// `MAX_STEPS_PER_CONTACT` steps.
fn checked_depth(pair: &Pair, init: &Initial) -> Result<f64> {
    finite("partner_omega_in", init.partner_omega)?;
    ensure_param!(
        init.partner_omega.abs() * pair.r2 <= MAX_RIM_SPEED,
        "partner_omega_in",
        init.partner_omega,
        format!(
            "with |partner_omega_in| r <= {MAX_RIM_SPEED:e} m/s (r = {} m)",
            pair.r2
        )
    );
    let depth_est = estimate_max_overlap(pair, init)?;
    let reach = pair.particle.r + pair.r2;
    let resolution = MIN_DEPTH_ULPS * f64::EPSILON * reach;
    if depth_est < resolution {
        return Err(Error::invalid(
            "v",
            init.vx.hypot(init.vy),
            format!(
                "large enough that the estimated overlap ({depth_est:e} m) resolves in double \
                 precision at the centres' distance (>= {resolution:e} m at r1 + r2 = {reach} m): \
                 raise theta_deg or v, or lower E"
            ),
        ));
    }
    budget::check_contact_steps(&pair.law, init, depth_est)?;
    Ok(depth_est)
}

/// Runs the pair's loop for its geometry and integrator.
fn run_fixed(
    pair: &Pair,
    init: &Initial,
    depth_est: f64,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let (r1, r2) = (pair.particle.r, pair.r2);
    let limits = Limits {
        max_steps: budget::step_budget(&pair.law, init, depth_est),
        contact_time: TIMEOUT_CONTACT_TIMES * PI * depth_est / init.vy.abs(),
    };
    let sphere = matches!(pair.particle.scene.shape, Shape::Sphere { .. });
    match (pair.law.scene.integrator, sphere) {
        (Integrator::Verlet, false) => {
            PairLoop::<Verlet, _>::new(pair, init, DiscPair { r1, r2 }, limits).run(trace, cancel)
        }
        (Integrator::Verlet, true) => {
            PairLoop::<Verlet, _>::new(pair, init, SpherePair { r1, r2 }, limits).run(trace, cancel)
        }
        (_, false) => {
            PairLoop::<Gear5, _>::new(pair, init, DiscPair { r1, r2 }, limits).run(trace, cancel)
        }
        (_, true) => {
            PairLoop::<Gear5, _>::new(pair, init, SpherePair { r1, r2 }, limits).run(trace, cancel)
        }
    }
}

/// The budgets of one pair impact.
#[derive(Debug, Clone, Copy)]
struct Limits {
    max_steps: u64,
    contact_time: f64,
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
struct PairLoop<'a, S, G> {
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
    fn new(pair: &'a Pair, init: &Initial, geometry: G, limits: Limits) -> Self {
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

    fn run(mut self, mut trace: Option<&mut Trace>, cancel: &Cancel) -> Result<Record> {
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
        let depth = self.contact.geometry.touch_distance() - q[0].hypot(q[1]);
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

/// The normal at separation: the direction of the centres' line where they last were `reach`
/// apart, found from the final state `q`, `v` by going back along the free flight since
/// (no force acts once apart; a timed-out impact keeps its current direction).
fn separation_normal(q: &Lanes, v: &Lanes, reach: f64) -> [f64; 2] {
    let (x, y, gx, gy) = (q[0], q[1], v[0], v[1]);
    let (rg, g2, r2) = (x * gx + y * gy, gx * gx + gy * gy, x * x + y * y);
    let disc = rg * rg - g2 * (r2 - reach * reach);
    let tau = if r2 > reach * reach && g2 > 0.0 && disc >= 0.0 {
        (rg - disc.sqrt()) / g2
    } else {
        0.0
    };
    let (xs, ys) = (x - gx * tau, y - gy * tau);
    let d = xs.hypot(ys);
    [xs / d, ys / d]
}

/// Completes a pair's record (section 17 of docs/model.md): the first-touch normal is +y and
/// its tangent +x, g0 = (init.vx, init.vy); `qv` the final lanes.
fn close_pair(rec: &mut Record, pair: &Pair, init: &Initial, (q, v): (&Lanes, &Lanes), reach: f64) {
    let (m1, m2, ms) = (pair.particle.mass, pair.m2, pair.m_star);
    let (r1, r2) = (pair.particle.r, pair.r2);
    let g0 = [init.vx, init.vy];
    let speed = g0[0].hypot(g0[1]);
    rec.energy_out = pair.kinetic_energy(v);
    rec.energy_residual =
        (rec.energy_out - rec.energy_in - rec.work_normal - rec.work_friction) / rec.energy_in;
    let ns = separation_normal(q, v, reach);
    rec.e_n = -v[1] / g0[1];
    rec.e_n_sep = -(v[0] * ns[0] + v[1] * ns[1]) / g0[1];
    rec.normal_rotation_deg = (-ns[0]).atan2(ns[1]).to_degrees();
    rec.e_t = (g0[0] != 0.0).then(|| v[0] / g0[0]);
    rec.e_kin = v[0].hypot(v[1]) / speed;
    rec.omega_out = v[2];
    rec.partner_omega_out = v[3];
    let v_cp = g0[0] + r1 * init.omega + r2 * init.partner_omega;
    rec.beta = (v_cp != 0.0).then(|| -(v[0] + r1 * v[2] + r2 * v[3]) / v_cp);
    rec.rebound_angle_deg = v[1].atan2(v[0]).to_degrees();
    // Lab velocities in the frame where the partner was at rest: the centre of mass moves
    // at m1 g0 / M throughout.
    let total = m1 + m2;
    let cm = [m1 * g0[0] / total, m1 * g0[1] / total];
    let v1 = [cm[0] + m2 / total * v[0], cm[1] + m2 / total * v[1]];
    let v2 = [cm[0] - m1 / total * v[0], cm[1] - m1 / total * v[1]];
    (rec.vx_out, rec.vy_out) = (v1[0], v1[1]);
    (rec.partner_vx_out, rec.partner_vy_out) = (v2[0], v2[1]);
    let p = [
        m1 * v1[0] + m2 * v2[0] - m1 * g0[0],
        m1 * v1[1] + m2 * v2[1] - m1 * g0[1],
    ];
    rec.momentum_residual = Some(p[0].hypot(p[1]) / (ms * speed));
    let (i1, i2) = (pair.particle.inertia, pair.i2);
    let l_in = ms * (0.0 * g0[1] - reach * g0[0]) + i1 * init.omega + i2 * init.partner_omega;
    let l_out = ms * (q[0] * v[1] - q[1] * v[0]) + i1 * v[2] + i2 * v[3];
    rec.angular_momentum_residual = Some((l_out - l_in) / (ms * speed * reach));
    rec.timed_out = rec.stop != StopReason::Separated;
    rec.separated = !rec.timed_out;
}

/// The pair's largest overlap from the energy balance of its undamped normal law,
/// refused where a body's cap would pass half its radius (as r / 2 on the plate).
fn estimate_max_overlap(pair: &Pair, init: &Initial) -> Result<f64> {
    let law = &pair.law;
    let (r1, r2) = (pair.particle.r, pair.r2);
    let ke = 0.5 * pair.m_star * init.vy * init.vy;
    let hi = largest_overlap(r1, r2);
    let potential = |delta: f64| overlap_potential(pair, delta);
    let (u_hi, _) = potential(hi);
    if u_hi < ke {
        let stiff = match law.scene.normal_law {
            NormalLaw::Linear { kn, .. } => format!("kn = {:e} Pa", 2.0 * kn),
            _ => format!("E = {:e} Pa", pair.particle.scene.e_modulus),
        };
        return Err(Error::invalid(
            "v",
            init.vx.hypot(init.vy),
            format!(
                "small enough that each body's estimated overlap stays below half its radius at \
                 {stiff} (normal kinetic energy {ke:e} J exceeds the elastic energy there: lower \
                 v or raise the modulus)"
            ),
        ));
    }
    Ok(solve_depth(potential, ke, hi))
}

/// The overlap delta at which a body's cap reaches half its radius first (bisection on the
/// caps' closed form).
fn largest_overlap(r1: f64, r2: f64) -> f64 {
    let capped = |delta: f64| {
        let d = r1 + r2 - delta;
        let half = 0.5 * delta / d;
        (half * (r2 + d - r1) / r1).max(half * (r1 + d - r2) / r2) > 0.5
    };
    let (mut lo, mut hi) = (0.0, r1.min(r2));
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if capped(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    lo
}

/// The undamped normal law's potential at overlap `delta` and its rate (the elastic force).
fn overlap_potential(pair: &Pair, delta: f64) -> (f64, f64) {
    let law = &pair.law;
    match law.scene.normal_law {
        NormalLaw::Area => {
            // (E* / L) times the integral of the lens area over the overlap (Gauss-Legendre
            // on delta t^2, t in [0, 1]: the area grows like delta^(3/2)).
            let (r1, r2) = (pair.particle.r, pair.r2);
            let lens = DiscPair { r1, r2 };
            let area = |s: f64| lens.overlap(r1 + r2 - s).map_or(0.0, |o| o.area);
            let k = law.scene.e_modulus / law.length;
            let integral: f64 = GAUSS_8
                .iter()
                .map(|&(x, w)| {
                    let t = 0.5 * (x + 1.0);
                    0.5 * w * area(delta * t * t) * 2.0 * delta * t
                })
                .sum();
            (k * integral, k * area(delta))
        }
        NormalLaw::Linear { kn, .. } => (0.5 * kn * delta * delta, kn * delta),
        NormalLaw::Hertz { .. } => {
            let k = law.hertz.map_or(0.0, |h| h.k);
            let f = k * delta * delta.sqrt();
            (0.4 * f * delta, f)
        }
    }
}

/// Gauss-Legendre nodes and weights on [-1, 1], 8 points.
const GAUSS_8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329_0, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329_0, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
];

/// The overlap at which `potential` reaches `energy`, below `hi` (where it is above): Newton
/// on log potential against log depth, bisecting where a step leaves the bracket.
fn solve_depth(potential: impl Fn(f64) -> (f64, f64), energy: f64, hi: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, hi);
    let mut depth = hi;
    for _ in 0..200 {
        let (p, dp) = potential(depth);
        if p > energy {
            hi = depth;
        } else {
            lo = depth;
        }
        let next = depth * ((energy / p).ln() / (depth * dp / p)).exp();
        let next = if next > lo && next < hi && next.is_finite() {
            next
        } else {
            0.5 * (lo + hi)
        };
        if (next - depth).abs() <= 1e-14 * depth || next == lo || next == hi {
            return next;
        }
        depth = next;
    }
    depth
}
