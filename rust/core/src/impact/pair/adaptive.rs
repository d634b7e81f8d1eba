//! The adaptive path on a pair (docs/model.md, section 17.5): Dormand-Prince 5(4)
//! ([`crate::integrate::dopri`]) on the smooth pieces of the pair's contact law, in the same
//! centre-of-mass coordinates as the fixed-step loop, every switch between pieces located on
//! the step's dense output and the integration restarted there: the clip switching on (and
//! off), stick -> slip, slip -> stick, and separation. The works are integrated as components
//! of the same ODE, so the energy audit is accurate to the tolerance too. Round bodies cannot
//! touch again once apart: the impact ends at separation.
//!
//! The continuous-time law is the dt -> 0 limit of the fixed steps' (docs/model.md,
//! sections 4, 5): while sticking d(xi)/dt = rate v_t and F_t = -k_xi xi - c_t v_t; while
//! slipping F_t = mu F_n s and the spring follows algebraically; slip ends where the sticking
//! spring's trial force would move inside the cone, s dF_trial/dt < mu dF_n/dt (both rates
//! taken along the motion by a forward difference).

use super::ode::{
    error_estimate, error_scales, Event, Mode, PairOde, State, Tan, GX, GY, NS, W1, W2, WD, WN, WT,
    X, XI, Y,
};
use super::switches::first_switch;
use super::Start;
use crate::cancel::Cancel;
use crate::error::Result;
use crate::geometry::pair::PairGeometry;
use crate::impact::adaptive::step_factor;
use crate::impact::flight::{self, Approach, Jump};
use crate::impact::record::{
    separation_normal, Bodies, Ending, Record, StopReason, Trace, TIMEOUT_CONTACT_TIMES,
};
use crate::impact::side::poll_stride;
use crate::integrate::dopri::{root_error_ratio, DenseStep};
use crate::law::contact::NormalForce;
use crate::model::{Initial, NormalLaw, Pair};
use crate::numerics::roots;
use std::f64::consts::PI;

/// Consecutive pieces ended by a switch within [`CHATTER_SPAN`] of the contact time after which
/// a step ignores the switches that chatter: a slipping contact whose cone shrinks faster than
/// a stuck spring can follow (the tail of a contact at large mu) alternates stick and slip in
/// pieces of ~1e-17 s; it then slides along the cone for the step, as Coulomb's law says.
const MAX_CHATTER: u32 = 8;

/// See [`MAX_CHATTER`], in units of the estimated contact time.
const CHATTER_SPAN: f64 = 1e-9;
/// Integrates one pair impact on the adaptive path (validated pair and initial state, the
/// estimated largest overlap `depth_est`); `tol` the local tolerance per step.
pub(super) fn integrate<G: PairGeometry>(
    pair: &Pair,
    init: &Initial,
    (geometry, start): (G, Start),
    (depth_est, tol, max_steps): (f64, f64, u64),
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let mut run = Run::new(pair, init, (geometry, start), depth_est, tol);
    run.rec.step_budget = max_steps;
    let mut trace = trace;
    if let Some(tr) = trace.as_deref_mut() {
        run.push(tr);
    }
    let mut step = DenseStep::<NS, NS>::default();
    // An attempt evaluates the law at 7 stages and more where it locates a switch.
    let stride = poll_stride(pair, 16);
    let stop = loop {
        cancel.poll_every(run.attempts, stride)?;
        if run.attempts >= max_steps {
            break StopReason::StepBudget;
        }
        if run.contact_elapsed() > run.t_end {
            break StopReason::ContactTimeBudget;
        }
        if run.attempt(&mut step) {
            if let Some(tr) = trace.as_deref_mut() {
                run.push(tr);
            }
            if run.separated {
                break StopReason::Separated;
            }
        }
    };
    Ok(run.finish(stop))
}

/// The state of one pair impact between steps.
struct Run<'a, G> {
    ode: PairOde<'a, G>,
    init: Initial,
    mode: Mode,
    s: State,
    k1: State,
    t: f64,
    h: f64,
    h_max: f64,
    /// The largest step near touch, where the damping grows like a root of the time.
    h_singular: f64,
    t_end: f64,
    /// 1 / (tol x scale) of each component.
    weight: State,
    /// Local errors accumulated in quadrature (`err_est`).
    acc: State,
    attempts: u64,
    steps: u64,
    /// Consecutive pieces shorter than the chatter span, and that span (s).
    chatter: u32,
    chatter_span: f64,
    separated: bool,
    /// When the current contact began (s), the centres' distance at first touch and the line
    /// of centres when the last contact ended.
    t_touch: f64,
    /// How far past a touch its mode is probed (s).
    probe_dt: f64,
    /// The pair's angular momentum, restored after every step (`Pair::restoring_turn`).
    l0: f64,
    /// The probe of a touch just applied, for the next piece's first derivative
    /// (`PairOde::touch_derivative`).
    touch_probe: Option<State>,
    /// The sliding speed along a slip's force past which the slip ends (m/s).
    slip_margin: f64,
    y0: f64,
    n_sep: [f64; 2],
    rec: Record,
}

impl<'a, G: PairGeometry> Run<'a, G> {
    fn new(
        pair: &'a Pair,
        init: &Initial,
        (geometry, start): (G, Start),
        depth_est: f64,
        tol: f64,
    ) -> Self {
        let law = &pair.law;
        let speed = init.vx.hypot(init.vy);
        let t_est = PI * depth_est / init.vy.abs();
        let mut ode = PairOde {
            pair,
            geometry,
            mu: law.scene.mu,
            normal: NormalForce::new(law),
            inv: [
                1.0 / pair.m_star,
                1.0 / pair.particle.inertia,
                1.0 / pair.i2,
            ],
            fd_step: 1e-7 * t_est,
            held: Default::default(),
        };
        let s: State = [
            start.q[0],
            start.q[1],
            init.vx,
            init.vy,
            init.phi0,
            init.omega,
            init.partner_phi0,
            init.partner_omega,
            0.0,
            0.0,
            0.0,
            0.0,
        ];
        let mut mode = Mode {
            clipped: false,
            apart: false,
            tan: Tan::None,
        };
        let probe;
        (mode.tan, probe) = ode.mode_after_touch(&mode, &s, 1e-12 * t_est);
        let energy_in = pair.kinetic_energy(&[init.vx, init.vy, init.omega, init.partner_omega]);
        let weight =
            error_scales(pair, init, (speed, energy_in), t_est, depth_est).map(|x| 1.0 / (tol * x));
        let k1 = ode.touch_derivative(&mode, &s, &probe);
        let h_max = law.scene.dt_factor * law.t_ref;
        Run {
            ode,
            init: *init,
            mode,
            s,
            k1,
            t: 0.0,
            h: h_max.min(t_est * tol.powf(2.0 / 3.0)),
            h_max,
            h_singular: t_est * tol.powf(2.0 / 3.0),
            t_end: TIMEOUT_CONTACT_TIMES * t_est,
            weight,
            acc: [0.0; NS],
            attempts: 0,
            steps: 0,
            chatter: 0,
            chatter_span: CHATTER_SPAN * t_est,
            separated: false,
            t_touch: 0.0,
            probe_dt: 1e-12 * t_est,
            touch_probe: None,
            l0: pair.angular_momentum(&[s[X], s[Y], s[4], s[6]], &[s[GX], s[GY], s[W1], s[W2]]),
            slip_margin: 1e-6 * speed,
            y0: start.q[1],
            n_sep: [0.0, 1.0],
            rec: Record {
                contacts: 1,
                energy_in,
                ..Record::default()
            },
        }
    }

    /// One attempted step; true when it was accepted (up to a switch, which it then applies).
    fn attempt(&mut self, step: &mut DenseStep<NS, NS>) -> bool {
        self.attempts += 1;
        let h = self.capped_step();
        let (ode, mode) = (&self.ode, self.mode);
        step.take(&self.s, &self.k1, h, |_, y, k| {
            ode.eval(&mode, y, k);
        });
        let err = self.error_norm(step, h);
        if !(err <= 1.0) {
            self.h = h * if err.is_finite() {
                step_factor(err)
            } else {
                0.2
            };
            return false;
        }
        let chattering = self.chatter >= MAX_CHATTER;
        let first = first_switch(&self.ode, &self.mode, step, chattering);
        let theta = first.map_or(1.0, |(th, _)| th);
        let (s_new, err_taken) = if theta < 1.0 {
            self.state_at_switch(step, theta)
        } else {
            (step.y1, step.err)
        };
        for (acc, e) in self.acc.iter_mut().zip(err_taken) {
            *acc = acc.hypot(e);
        }
        self.track_extremes(step, theta);
        self.s = s_new;
        self.keep_angular_momentum();
        self.t += theta * h;
        self.steps += 1;
        if let Some((_, ev)) = first {
            self.apply(ev);
            self.chatter = if theta * h <= self.chatter_span {
                self.chatter + 1
            } else {
                0
            };
        } else {
            self.chatter = 0;
            if self.mode.apart {
                self.fly();
            } else {
                self.end_a_reversed_slip();
            }
        }
        self.k1 = match self.touch_probe.take() {
            Some(probe) => self.ode.touch_derivative(&self.mode, &self.s, &probe),
            None => self.ode.eval_new(&self.mode, &self.s).0,
        };
        self.h = (h * step_factor(err.max(1e-12))).min(self.h_max);
        true
    }

    /// The state where a piece ends inside `step`, at fraction `th`, and its local error
    /// (section 7.3, with the unscaled gap): from the dense output where it agrees with the cubic
    /// Hermite interpolant of the step's ends to the local tolerance (their gap, which
    /// overstates the dense output's error, joins `err_est`), else from the step redone up
    /// to there. Taken from the dense output always, its error at the switches of the linear
    /// law's springs went unmeasured (`err_est` a tenth of the error).
    fn state_at_switch(&self, step: &DenseStep<NS, NS>, th: f64) -> (State, State) {
        let (s_th, gap) = step.at_with_gap(th);
        let err: State = std::array::from_fn(|i| th * step.err[i].abs() + gap[i]);
        if self.scaled_norm(&gap) <= 1.0 {
            return (s_th, err);
        }
        let (ode, mode) = (&self.ode, self.mode);
        let mut redo = DenseStep::<NS, NS>::default();
        redo.take(&self.s, &self.k1, th * step.h_len(), |_, y, k| {
            ode.eval(&mode, y, k);
        });
        (redo.y1, redo.err)
    }

    /// The step to take: the controller's, at most the largest; near touch at most the step
    /// whose error a root singularity of the force does not hide (the plate's rule).
    fn capped_step(&self) -> f64 {
        let mut h = self.h.min(self.h_max);
        if !self.mode.clipped && !self.mode.apart && self.singular() {
            if self.t - self.t_touch < 2.0 * self.h_singular {
                h = h.min(self.h_singular);
            }
            // Towards separation, half the time left until the overlap closes (the force's
            // root singularity lies there too).
            let (depth, rate) = self.ode.opening(&self.s);
            if depth > 0.0 && rate > 0.0 {
                h = h.min((0.5 * depth / rate).max(self.h_singular));
            }
        }
        h.max(1e-14 * self.h_max)
    }

    /// Whether the normal force has a root singularity at touch and separation (the area and
    /// Hertz laws; the linear law's force is smooth there).
    fn singular(&self) -> bool {
        !matches!(self.ode.pair.law.scene.normal_law, NormalLaw::Linear { .. })
    }

    /// The step's scaled error norm, the embedded estimate understating a step from touch by
    /// the tableau's factor (`root_error_ratio`).
    fn error_norm(&self, step: &DenseStep<NS, NS>, h: f64) -> f64 {
        let since = self.t - self.t_touch;
        let factor = if self.singular() && !self.mode.apart && since < 2.0 * h {
            let p = match self.ode.pair.law.scene.normal_law {
                NormalLaw::Hertz { .. } => 0.25,
                _ => 0.5,
            };
            root_error_ratio(p, since / h, false)
        } else {
            1.0
        };
        self.scaled_norm(&step.err) * factor
    }

    /// The largest component of the absolute errors `err` in units of the local tolerance
    /// (the spring's elongation only while it sticks: elsewhere it is algebraic; the dashpot's
    /// work is a part of the normal force's, which is controlled, and reported only).
    fn scaled_norm(&self, err: &State) -> f64 {
        (0..NS)
            .filter(|&i| (i != XI || self.mode.tan == Tan::Stick) && i != WD)
            .map(|i| err[i].abs() * self.weight[i])
            .fold(0.0, f64::max)
    }

    /// Switches the mode at event `ev` and sets the algebraic part of the state.
    fn apply(&mut self, ev: Event) {
        let (ode, s) = (&mut self.ode, &mut self.s);
        match ev {
            Event::Separate => self.separate(),
            Event::Touch => {
                self.mode = Mode {
                    clipped: false,
                    apart: false,
                    tan: Tan::None,
                };
                s[XI] = 0.0;
                let probe;
                (self.mode.tan, probe) = ode.mode_after_touch(&self.mode, s, self.probe_dt);
                self.touch_probe = Some(probe);
                self.t_touch = self.t;
                self.rec.contacts += 1;
            }
            Event::ClipOn => {
                self.mode = Mode {
                    clipped: true,
                    apart: false,
                    tan: Tan::Free,
                }
            }
            Event::ClipOff => {
                // Still in contact, the spring takes up where the clip left it: carrying the
                // dashpot's force alone, no tangential force (docs/model.md, section 5), as
                // on the plate and in the fixed loops. Reset to 0 instead, the dashpot's
                // full force acted at once: twin 120-gons (linear law, mu 10, 85 deg) ended
                // 0.038 apart in e_T from Gear-5, which converges to this.
                let clipped = ode.eval_new(&self.mode, s).1;
                s[XI] = ode.slipping_xi(&clipped);
                self.mode.clipped = false;
                self.mode.tan = ode.initial_tan(&self.mode, s);
            }
            Event::ToSlip => {
                let e = ode.eval_new(&self.mode, s).1;
                self.mode.tan = Tan::Slip(e.trial.signum());
                self.rec.slip_events += 1;
            }
            Event::ToStick => {
                let e = ode.eval_new(&self.mode, s).1;
                s[XI] = ode.slipping_xi(&e);
                self.mode.tan = Tan::Stick;
            }
            Event::Springs => self.switch_springs(),
        }
    }

    /// The held springs switch (a corner enters or leaves the other body, or turns to another
    /// edge): the normal force jumps by a corner's dashpot, and the springs' resultant, which
    /// is the normal, turns, and the tangential velocity with it. The tangential spring goes
    /// through the switch unchanged (a slip's at its slipping elongation), and the mode is
    /// decided again on the new side: a slip sticks where its trial force lies inside the new
    /// cone, a stick slips where it lies outside (the continuous limit of the stepped law,
    /// section 5, to which Gear-5 converges). Where no force changes (a corner turning to
    /// another edge) the mode is kept, round-off being no reason to switch. Sticking only
    /// where a corner entered and keeping the spring's force instead of its elongation, this
    /// path and Gear-5 converged to answers 0.002 to 0.04 apart in e_T (twin squares and
    /// 120-gons, damped, mu 0.5 and 0.3), and the order of a slip's end and a switch located
    /// together decided the answer (a square pair and its copy ten times as large 5e-5 apart).
    fn switch_springs(&mut self) {
        let before = self.ode.eval_new(&self.mode, &self.s).1;
        let q = [self.s[X], self.s[Y], self.s[4], self.s[6]];
        self.ode.held = self.ode.geometry.held_springs(&q);
        if self.mode.apart {
            return;
        }
        if self.mode.clipped {
            self.release_a_clip(before.f_raw);
            return;
        }
        let slipping = match self.mode.tan {
            Tan::Slip(_) => true,
            Tan::Stick => false,
            Tan::None | Tan::Free => return,
        };
        if slipping {
            self.s[XI] = self.ode.slipping_xi(&before);
        }
        let stick = Mode {
            tan: Tan::Stick,
            ..self.mode
        };
        let after = self.ode.eval_new(&stick, &self.s).1;
        let (trial, cone) = (after.trial.abs(), self.ode.mu * (after.f_el + after.f_d));
        if slipping && cone > trial * (1.0 + 1e-9) {
            self.mode.tan = Tan::Stick;
        } else if slipping && self.ode.event_value(&self.mode, Event::ToStick, &self.s) > 0.0 {
            // On the cone, and sticking would move inside it (its rates changed with the
            // springs): the slip ends here. Its event, positive from the start of the next step,
            // fires on its value at the step's end, and a stick shorter than that step went
            // unseen (twin 120-gons, elastic, mu 0.3, 20 deg: 2e-5 off at tol 1e-8).
            self.apply(Event::ToStick);
        } else if !slipping && trial > cone * (1.0 + 1e-9) {
            self.mode.tan = Tan::Slip(after.trial.signum());
            self.rec.slip_events += 1;
        }
    }

    /// A clipped force that a switch of the springs turned to pushing (an entering corner's
    /// dashpot, or a leaving corner's pull gone; `before` the force before the switch) is
    /// released there. Left to the clip's event, positive from the start of the next step, the
    /// release went unseen where the push ended within that step (the event fires on its
    /// value at the step's end): twin 120-gons (damped, mu 0.3, 20 deg) with a largest step of
    /// 1 t_ref ended 0.035 from the reference in e_N at every tol, err_est 2 tol.
    fn release_a_clip(&mut self, before: f64) {
        let after = self.ode.eval_new(&self.mode, &self.s).1.f_raw;
        // A jump beyond round-off: at a corner turning to another edge the force is unchanged.
        if after > 0.0 && after - before > 1e-9 * (after.abs() + before.abs()) {
            self.apply(Event::ClipOff);
        }
    }

    /// Restores the pair's angular momentum after a step: the step's polynomial does not keep
    /// a product of position and velocity (the drift was up to 2.6e-5 tol), the forces do.
    fn keep_angular_momentum(&mut self) {
        let s = &mut self.s;
        let q = [s[X], s[Y], s[4], s[6]];
        let v = [s[GX], s[GY], s[W1], s[W2]];
        let dv = self.ode.pair.restoring_turn(&q, &v, self.l0);
        for (i, d) in [GX, GY, W1, W2].into_iter().zip(dv) {
            s[i] += d;
        }
    }

    /// Ends a slip whose force has turned with the sliding (s v_t > 0 past a margin of the
    /// speed) at the end of a step: the rate test of `ToStick` samples a sign change that a
    /// turning contact frame (bodies with corners) can carry through within one step, and a
    /// slip left on would feed the motion. The contact sticks at its slipping elongation,
    /// from where sticking moves the spring's force inside the cone.
    fn end_a_reversed_slip(&mut self) {
        let Tan::Slip(sg) = self.mode.tan else {
            return;
        };
        if !G::CORNERS {
            return;
        }
        let e = self.ode.eval_new(&self.mode, &self.s).1;
        if sg * e.v_t > self.slip_margin {
            self.s[XI] = self.ode.slipping_xi(&e);
            self.mode.tan = Tan::Stick;
        }
    }

    /// The time spent in contact so far (s): the budget's measure (flights between contacts
    /// do not count).
    fn contact_elapsed(&self) -> f64 {
        let ongoing = if self.mode.apart {
            0.0
        } else {
            self.t - self.t_touch
        };
        self.rec.contact_time + ongoing
    }

    /// A contact ends: round bodies separate for good; bodies with corners fly apart, their
    /// flight skipped up to where they might touch again, or the impact ends.
    fn separate(&mut self) {
        self.rec.contact_time += self.t - self.t_touch;
        let s = &mut self.s;
        let d = s[X].hypot(s[Y]);
        self.n_sep = [s[X] / d, s[Y] / d];
        if !G::CORNERS {
            self.separated = true;
            return;
        }
        self.mode = Mode {
            clipped: false,
            apart: true,
            tan: Tan::None,
        };
        // Apart, no spring acts; the next touch holds its own (`mode_after_touch`).
        self.ode.held.springs.clear();
        self.fly();
    }

    /// Apart: jumps the free flight (the plate's, [`flight`]), each advance counted as a
    /// step; ends the impact when the bodies can never touch again.
    fn fly(&mut self) {
        let s = &mut self.s;
        let q = [s[X], s[Y], s[4], s[6]];
        let v = [s[GX], s[GY], s[W1], s[W2]];
        let radii = [self.ode.pair.particle.r, self.ode.pair.r2];
        let approach = Approach::of_pair(&q, &v, radii);
        let geometry = &self.ode.geometry;
        let at = |t: f64| -> [f64; 4] { std::array::from_fn(|i| q[i] + v[i] * t) };
        let gap = |t: f64| -geometry.signed_depth(&at(t));
        let left = self.rec.step_budget.saturating_sub(self.attempts);
        let (jump, advances) = flight::jump(gap, approach, self.h_max, left);
        let t_jump = match jump {
            Jump::Stay => return,
            Jump::To(t) => t,
            Jump::Clear(t) => {
                self.separated = true;
                t
            }
        };
        let q = at(t_jump);
        (s[X], s[Y], s[4], s[6]) = (q[0], q[1], q[2], q[3]);
        self.t += t_jump;
        self.steps += advances;
        self.attempts += advances;
    }

    /// The largest overlap and area inside the taken part of the step: at its end, and where
    /// the normal velocity turns (the deepest point), located on the dense output.
    fn track_extremes(&mut self, step: &DenseStep<NS, NS>, theta: f64) {
        let g_n = |th: f64| {
            let s = step.at(th);
            s[X] * s[GX] + s[Y] * s[GY]
        };
        let (a, b) = (g_n(0.0), g_n(theta));
        let mut at = vec![theta];
        if a < 0.0 && b > 0.0 {
            at.push(roots::bracket(g_n, (0.0, a), (theta, b), 1e-10 * theta).0);
        }
        for th in at {
            let e = self.ode.eval_new(&self.mode, &step.at(th)).1;
            self.rec.max_depth = self.rec.max_depth.max(e.depth);
            self.rec.max_area = self.rec.max_area.max(e.area);
        }
    }

    fn push(&self, tr: &mut Trace) {
        let s = &self.s;
        let f = self.ode.eval_new(&self.mode, s).1.forces(&self.mode);
        let q = [s[X], s[Y], s[4], s[6]];
        let v = [s[GX], s[GY], s[W1], s[W2]];
        tr.push_pair(self.t, &q, &v, &f, s[XI]);
    }

    fn finish(mut self, stop: StopReason) -> Record {
        let s = self.s;
        let mut rec = self.rec;
        rec.stop = stop;
        rec.steps = self.steps;
        if !self.mode.apart && !self.separated {
            rec.contact_time += self.t - self.t_touch;
        }
        rec.work_normal = s[WN];
        rec.work_friction = s[WT];
        rec.work_damping = s[WD];
        let (q, v) = ([s[X], s[Y], s[4], s[6]], [s[GX], s[GY], s[W1], s[W2]]);
        let n_sep = if G::CORNERS {
            self.n_sep
        } else {
            separation_normal(&q, &v, self.ode.geometry.reach())
        };
        let end = Ending {
            q,
            v,
            y0: self.y0,
            n_sep,
        };
        rec.close(&Bodies::Pair(self.ode.pair), &self.init, &end);
        rec.err_est = Some(error_estimate(&self.acc, &self.init, self.ode.pair));
        self.rec = rec;
        self.rec
    }
}
