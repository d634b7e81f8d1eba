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

use super::law::{error_scales, PairOde};
use super::piece::{Eval, Event, Mode, State, Tan, GX, GY, NS, W1, W2, WD, WN, WT, X, XI, Y};
use super::switches::{first_switch, Ignored, KeptSamples, StepSamples};
use super::Start;
use crate::cancel::Cancel;
use crate::error::Result;
use crate::geometry::pair::PairGeometry;
use crate::impact::adaptive::{
    error_estimate, root_exponent, singular_cap, singular_factor, state_at_switch, turning_point,
    verdict, Chatter, ErrorSum, Limits, SwitchKind, Verdict,
};
use crate::impact::flight::{self, Approach, Jump};
use crate::impact::record::{separation_normal, Bodies, Ending, Record, StopReason, Trace};
use crate::impact::side::poll_stride;
use crate::integrate::dopri::DenseStep;
use crate::law::contact::NormalForce;
use crate::model::{Initial, Pair};
use std::cell::RefCell;
use std::f64::consts::PI;

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
    let mut run = Run::new(pair, init, (geometry, start), (depth_est, tol, max_steps));
    let mut trace = trace;
    if let Some(tr) = trace.as_deref_mut() {
        run.push(tr);
    }
    let mut step = DenseStep::<NS, NS>::default();
    // An attempt evaluates the law at 7 stages and more where it locates a switch.
    let stride = poll_stride(pair, 16);
    let stop = loop {
        cancel.poll_every(run.attempts, stride)?;
        if let Some(stop) = run.lim.budget_spent(run.attempts, run.contact_elapsed()) {
            break stop;
        }
        let accepted = match run.attempt(&mut step) {
            Ok(accepted) => accepted,
            Err(stop) => break stop,
        };
        if accepted {
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
pub(super) struct Run<'a, G> {
    pub(super) ode: PairOde<'a, G>,
    pub(super) init: Initial,
    pub(super) mode: Mode,
    pub(super) s: State,
    pub(super) k1: State,
    pub(super) t: f64,
    pub(super) h: f64,
    /// The largest and smallest steps, the budgets and the negligible piece.
    pub(super) lim: Limits,
    /// 1 / (tol x scale) of each component.
    pub(super) weight: State,
    /// Local errors accumulated in quadrature (`err_est`).
    pub(super) acc: ErrorSum<NS>,
    pub(super) attempts: u64,
    pub(super) steps: u64,
    /// Consecutive negligible and zero-length pieces.
    pub(super) chatter: Chatter,
    /// The switches ignored for one step where they chattered (the rules' remedies).
    pub(super) ignored: Ignored,
    /// No step taken since the last touch (`singular_cap`).
    pub(super) fresh_touch: bool,
    pub(super) separated: bool,
    /// When the current contact began (s), the centres' distance at first touch and the line
    /// of centres when the last contact ended.
    pub(super) t_touch: f64,
    /// How far past a touch its mode is probed (s).
    pub(super) probe_dt: f64,
    /// The pair's angular momentum, restored after every step (`Pair::restoring_turn`).
    pub(super) l0: f64,
    /// The probe of a touch just applied, for the next piece's first derivative
    /// (`PairOde::touch_derivative`).
    pub(super) touch_probe: Option<State>,
    /// The sliding speed along a slip's force past which the slip ends (m/s).
    pub(super) slip_margin: f64,
    pub(super) y0: f64,
    pub(super) n_sep: [f64; 2],
    pub(super) rec: Record,
    /// The law's evaluations a step shares between its events and extremes.
    pub(super) kept: RefCell<KeptSamples>,
}

impl<'a, G: PairGeometry> Run<'a, G> {
    fn new(
        pair: &'a Pair,
        init: &Initial,
        (geometry, start): (G, Start),
        (depth_est, tol, max_steps): (f64, f64, u64),
    ) -> Self {
        let law = &pair.law;
        let speed = init.vx.hypot(init.vy);
        // The speed the error scales are floored by, spins included (the plate's).
        let spun = speed + pair.particle.r * init.omega.abs() + pair.r2 * init.partner_omega.abs();
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
            error_scales(pair, init, (spun, energy_in), t_est, depth_est).map(|x| 1.0 / (tol * x));
        let k1 = ode.touch_derivative(&mode, &s, &probe);
        let lim = Limits::new(t_est, law.scene.dt_factor * law.t_ref, tol, max_steps);
        Run {
            ode,
            init: *init,
            mode,
            s,
            k1,
            t: 0.0,
            h: lim.h_max.min(lim.h_singular),
            lim,
            weight,
            acc: ErrorSum::default(),
            attempts: 0,
            steps: 0,
            chatter: Chatter::default(),
            ignored: Ignored::default(),
            fresh_touch: true,
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
                step_budget: max_steps,
                ..Record::default()
            },
            kept: RefCell::default(),
        }
    }

    /// One attempted step; true when it was accepted (up to a switch, which it then applies),
    /// `Err` with why the impact stops where it must.
    fn attempt(&mut self, step: &mut DenseStep<NS, NS>) -> std::result::Result<bool, StopReason> {
        self.attempts += 1;
        let h = self.capped_step();
        let (ode, mode) = (&self.ode, self.mode);
        let mut at_end = Eval::default();
        step.take(&self.s, &self.k1, h, |stage, y, k| {
            let e = ode.eval(&mode, y, k);
            if stage == 6 {
                at_end = e;
            }
        });
        let h_next = match verdict(self.scaled_norm(&step.err), h, self.lim.h_min()) {
            Verdict::Accept { h_next } => h_next,
            Verdict::Reject { h_retry } => {
                self.h = h_retry;
                return Ok(false);
            }
            Verdict::NonFinite => return Err(StopReason::NonFinite),
        };
        let ignored = std::mem::take(&mut self.ignored);
        let samples = StepSamples::new(&self.ode, self.mode, (step, at_end), &self.kept);
        let first = first_switch(&samples, ignored);
        let theta = first.map_or(1.0, |(th, _)| th);
        let extremes = (theta * h > 0.0).then(|| extremes_in(&samples, theta));
        let (s_new, err_taken) = if theta >= 1.0 {
            (step.y1, step.err)
        } else if theta * h <= 0.0 {
            (self.s, [0.0; NS])
        } else {
            // As on the plate, a switch inside the step counts against the budget as a step's
            // work, whether the step is redone to it or not.
            self.attempts += 1;
            self.state_at_switch(step, theta)
        };
        let event = first.map(|(_, ev)| ev);
        let factor = self.singular_factor(theta * h, event);
        self.acc.add(&err_taken, factor, [GX, GY, W1, W2]);
        let switch = event.map(|ev| (switch_kind(ev), self.ode.switch_precision(ev)));
        self.chatter.count(switch, (theta * h, h), self.lim.tiny);
        if let Some([depth, area]) = extremes {
            // Pieces of zero length are no steps (the plate's count).
            self.rec.max_depth = self.rec.max_depth.max(depth);
            self.rec.max_area = self.rec.max_area.max(area);
            self.fresh_touch = false;
            self.steps += 1;
        }
        // A whole step without a switch ends where its last stage was evaluated, in its mode.
        let whole_in = (theta >= 1.0 && event.is_none()).then_some(mode);
        self.s = s_new;
        self.keep_angular_momentum();
        self.t += theta * h;
        if ignored.clip {
            self.end_clip_hold();
        }
        let mut k_end = None;
        if let Some(ev) = event {
            self.apply(ev);
        } else if self.mode.apart {
            self.fly();
        } else {
            k_end = self.end_a_reversed_slip();
        }
        let kept = self.mode;
        self.resolve_chatter();
        // The derivative a slip going on was tested with, where the chatter rules kept its mode.
        let k_end = k_end.filter(|_| self.mode == kept);
        self.k1 = self.next_first_stage(step, k_end, whole_in);
        // After a switch the next step is at most this one (the plate's rule).
        self.h = if event.is_some() {
            h_next.min(h)
        } else {
            h_next
        };
        Ok(true)
    }

    /// The next step's first stage, at the state this one ended in: a touch's
    /// (`touch_derivative`); `k_end` where the slip's reversal test evaluated it there; after a
    /// whole step without a switch (`whole_in` its mode, still the mode), its last stage's
    /// (first same as last, as on the plate), the positions' rates the velocities restored to
    /// the angular momentum: the restoring turn is rigid, it changes no relative velocity at
    /// the contact, so the forces, the spring's rate and the forces' powers at the velocities
    /// before it are those after, to round-off; else the law evaluated afresh.
    fn next_first_stage(
        &mut self,
        step: &DenseStep<NS, NS>,
        k_end: Option<State>,
        whole_in: Option<Mode>,
    ) -> State {
        if let Some(probe) = self.touch_probe.take() {
            return self.ode.touch_derivative(&self.mode, &self.s, &probe);
        }
        if let Some(k) = k_end {
            return k;
        }
        if whole_in == Some(self.mode) && !self.mode.apart {
            let mut k = step.k_end();
            for (i, rate) in [(X, GX), (Y, GY), (4, W1), (6, W2)] {
                k[i] = self.s[rate];
            }
            return k;
        }
        self.ode.eval_new(&self.mode, &self.s).0
    }

    /// The factor on the local error of a piece of length `h_taken` ended by `event`, where
    /// the force has a root singularity at touch and separation ([`singular_factor`]).
    fn singular_factor(&self, h_taken: f64, event: Option<Event>) -> f64 {
        match root_exponent(&self.ode.pair.law.scene.normal_law) {
            Some(p) if self.singular_mode() => {
                let rho = (h_taken > 0.0).then(|| (self.t - self.t_touch) / h_taken);
                singular_factor(p, rho, event == Some(Event::Separate))
            }
            _ => 1.0,
        }
    }

    /// Leaves a chattering switch for one step in the mode of its sliding motion (the rules'
    /// remedies, `Chatter`): a clip that switches on and off at once stays clipped (no force),
    /// stick and slip that each end at once slide along the cone in slip.
    fn resolve_chatter(&mut self) {
        if self.mode.clipped && self.chatter.take_clip() {
            self.ignored.clip = true;
        }
        if self.chatter.take_tangential() {
            if self.mode.tan == Tan::Stick {
                let e = self.ode.eval_new(&self.mode, &self.s).1;
                self.mode.tan = Tan::Slip(e.trial.signum());
            }
            self.ignored.tangential = true;
        }
        self.ignored.all = self.chatter.stalled();
    }

    /// The state where a piece ends inside `step`, at fraction `th`, and its local error:
    /// from the dense output where its error estimate is within the local tolerance, else from
    /// the step redone up to there ([`state_at_switch`]).
    fn state_at_switch(&self, step: &DenseStep<NS, NS>, th: f64) -> (State, State) {
        if let Some(at) = state_at_switch(step, th, |gap| self.scaled_norm(gap))
            .filter(|_| !self.ode.ends_apart(&step.y1))
        {
            return at;
        }
        let (ode, mode) = (&self.ode, self.mode);
        let mut redo = DenseStep::<NS, NS>::default();
        redo.take(&self.s, &self.k1, th * step.h_len(), |_, y, k| {
            ode.eval(&mode, y, k);
        });
        (redo.y1, redo.err)
    }

    /// The step to take: the controller's, at most the largest; near touch and separation at
    /// most the rules' ([`singular_cap`]).
    fn capped_step(&self) -> f64 {
        let h = self.h.min(self.lim.h_max);
        if self.singular_mode() {
            h.min(singular_cap(
                self.fresh_touch,
                self.ode.opening(&self.s),
                self.lim.h_singular,
            ))
        } else {
            h
        }
    }

    /// Whether the normal force has a root singularity at touch and separation in the current
    /// mode: in contact and unclipped under the area and Hertz laws (the linear law's force
    /// is smooth there).
    fn singular_mode(&self) -> bool {
        let law = &self.ode.pair.law.scene.normal_law;
        !self.mode.clipped && !self.mode.apart && root_exponent(law).is_some()
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

    /// Apart: jumps the free flight (the plate's, [`flight`]), each advance counted as a
    /// step; ends the impact when the bodies can never touch again.
    pub(super) fn fly(&mut self) {
        let s = &mut self.s;
        let q = [s[X], s[Y], s[4], s[6]];
        let v = [s[GX], s[GY], s[W1], s[W2]];
        let radii = [self.ode.pair.particle.r, self.ode.pair.r2];
        let approach = Approach::of_pair(&q, &v, radii);
        let geometry = &self.ode.geometry;
        let at = |t: f64| -> [f64; 4] { std::array::from_fn(|i| q[i] + v[i] * t) };
        let gap = |t: f64| -geometry.signed_depth(&at(t));
        let left = self.lim.max_steps.saturating_sub(self.attempts);
        let (jump, advances) = flight::jump(gap, approach, self.lim.h_max, left);
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
        let (acc, pair) = (&self.acc, self.ode.pair);
        let spins = [(acc.of(W1), pair.particle.r), (acc.of(W2), pair.r2)];
        rec.err_est = Some(error_estimate(&self.init, (acc.of(GX), acc.of(GY)), spins));
        self.rec = rec;
        self.rec
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

/// The largest overlap and area inside the part of the step of `samples` up to `theta`: at
/// its end, and where the normal velocity turns (the deepest point), located on the dense
/// output.
fn extremes_in<G: PairGeometry>(samples: &StepSamples<'_, '_, G>, theta: f64) -> [f64; 2] {
    let step = samples.step;
    let g_n = |th: f64| {
        let s = step.at(th);
        s[X] * s[GX] + s[Y] * s[GY]
    };
    let (a, b) = (g_n(0.0), g_n(theta));
    let at = [Some(theta), turning_point(g_n, a, (theta, b))];
    let mut most = [f64::NEG_INFINITY; 2];
    for th in at.into_iter().flatten() {
        let e = samples.eval_at(th, &step.at(th));
        most = [most[0].max(e.depth), most[1].max(e.area)];
    }
    most
}
