//! A pair on the adaptive path (docs/model.md, section 17.5): the partner as the one adaptive
//! loop sees it ([`AdaptiveSide`], the loop in `impact/adaptive/run.rs`). Dormand-Prince 5(4)
//! ([`crate::integrate::dopri`]) on the smooth pieces of the pair's contact law, in the same
//! centre-of-mass coordinates as the fixed-step loop, every switch between pieces located on
//! the step's dense output and the integration restarted there: the clip switching on (and
//! off), stick -> slip, slip -> stick, the held springs, separation and touch. The works are
//! integrated as components of the same ODE, so the energy audit is accurate to the
//! tolerance too. Round bodies cannot touch again once apart: the impact ends at separation.
//!
//! The continuous-time law is the dt -> 0 limit of the fixed steps' (docs/model.md,
//! sections 4, 5): while sticking d(xi)/dt = rate v_t and F_t = -k_xi xi - c_t v_t; while
//! slipping F_t = mu F_n s and the spring follows algebraically; slip ends where the sticking
//! spring's trial force would move inside the cone, s dF_trial/dt < mu dF_n/dt (both rates
//! taken along the motion by a forward difference).

use super::law::{error_scales, PairOde};
use super::piece::{
    Eval, Event, Kept, Mode, State, Tan, GX, GY, INTERPOLATED, NS, W1, W2, WD, WN, WT, X, XI, Y,
};
use super::switches::{first_switch, Ignored, KeptSamples, StepSamples};
use super::Start;
use crate::cancel::Cancel;
use crate::error::Result;
use crate::geometry::pair::PairGeometry;
use crate::impact::adaptive::{
    error_estimate, root_exponent, state_at_switch, turning_point, AdaptiveSide, ErrorSum, Limits,
    Run, SwitchKind, TangentialStages,
};
use crate::impact::flight::{self, Approach, Jump};
use crate::impact::record::{separation_normal, Bodies, Ending, Record, StopReason, Trace};
use crate::impact::side::poll_stride;
use crate::integrate::dopri::DenseStep;
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
    let mut run = begin(
        pair,
        init,
        (geometry, start),
        (depth_est, tol, max_steps),
        trace,
    );
    if let Some(tr) = run.trace.as_deref_mut() {
        push(&run.side, (&run.mode, &run.s, run.t), tr);
    }
    run.integrate(cancel)
}

/// What a pair keeps of its own through one impact on the adaptive path.
pub(super) struct OnPair<'a, G> {
    pub(super) ode: PairOde<'a, G>,
    pub(super) init: Initial,
    /// 1 / (tol x scale) of each component.
    weight: State,
    /// Local errors accumulated in quadrature (`err_est`).
    acc: ErrorSum<NS>,
    /// The switches the next step ignores where they chattered (the rules' remedies), and
    /// those the step being taken ignored.
    ignored: Ignored,
    step_ignored: Ignored,
    pub(super) separated: bool,
    /// How far past a touch its mode is probed (s).
    pub(super) probe_dt: f64,
    /// The pair's angular momentum, restored after every step (`Pair::restoring_turn`).
    l0: f64,
    /// The probe of a touch just applied, for the next piece's first derivative
    /// (`PairOde::touch_derivative`).
    pub(super) touch_probe: Option<State>,
    /// The sliding speed along a slip's force past which the slip ends (m/s).
    pub(super) slip_margin: f64,
    /// The centres' distance at first touch and the line of centres when the last contact
    /// ended.
    y0: f64,
    pub(super) n_sep: [f64; 2],
    pub(super) rec: Record,
    /// The law's evaluations a step shares between its events and extremes.
    kept: RefCell<KeptSamples>,
    /// The largest overlap and area inside the piece being taken, found with its switch.
    extremes: Option<[f64; 2]>,
    /// The derivative a slip going on was tested with at the step's end, the law's evaluation
    /// there, and the mode then (`end_a_reversed_slip`): the next step's first stage where the
    /// chatter rules keep it.
    k_end: Option<(State, Eval, Mode)>,
    /// The law's evaluation at the state the next step starts from, in its mode, where the
    /// first stage was taken from it (the stage filters' value at the start,
    /// [`OnPair::stays_in_tangential_mode`]).
    start: Option<(Mode, Eval)>,
    /// The law's last evaluation at a switch, with the state and mode it was taken in: the
    /// contact the switch's other tests and the next piece's first stage read
    /// ([`OnPair::eval_at_switch`]); dropped where the held springs change.
    pub(super) at_switch: Option<Kept>,
    /// The step just taken stayed in its slip by the stages' bound: its end cannot have turned
    /// the sliding (`end_a_reversed_slip` need not evaluate the law there).
    pub(super) firm_slip: bool,
}

/// A Dormand-Prince step of the pair's ODE, the law's evaluation at its end (its last stage,
/// first same as last), and what the stage filters read of its stages.
#[derive(Default)]
pub(super) struct PairStep {
    dp: DenseStep<NS, INTERPOLATED>,
    end: Eval,
    /// In stick the stick -> slip function's span over the stages, in slip the normal force
    /// and the tangential velocity at each.
    tangential: TangentialStages,
    /// The overlap at each stage (past the parting the tangential functions say nothing, and
    /// the stages bound nothing).
    depths: [f64; 6],
}

/// The run of a pair impact at first touch.
fn begin<'a, 't, G: PairGeometry>(
    pair: &'a Pair,
    init: &Initial,
    (geometry, start): (G, Start),
    (depth_est, tol, max_steps): (f64, f64, u64),
    trace: Option<&'t mut Trace>,
) -> Run<'t, OnPair<'a, G>> {
    let law = &pair.law;
    let speed = init.vx.hypot(init.vy);
    // The speed the error scales are floored by, spins included (the plate's).
    let spun = speed + pair.particle.r * init.omega.abs() + pair.r2 * init.partner_omega.abs();
    let t_est = PI * depth_est / init.vy.abs();
    let mut ode = PairOde::new(pair, geometry, 1e-7 * t_est);
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
    let side = OnPair {
        ode,
        init: *init,
        weight,
        acc: ErrorSum::default(),
        ignored: Ignored::default(),
        step_ignored: Ignored::default(),
        separated: false,
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
        extremes: None,
        k_end: None,
        start: None,
        at_switch: None,
        firm_slip: false,
    };
    let h = lim.h_max.min(lim.h_singular);
    Run::new(side, (s, mode, k1), h, lim, trace)
}

// The hooks the loop calls at every step are `#[inline]`, so that each is instantiated where
// the loop is: left to the codegen units' partitioning, `refresh`, `first_switch` and `settle`
// were called, and `refresh` copied its evaluations through `memcpy`.
impl<'a, G: PairGeometry> AdaptiveSide for OnPair<'a, G> {
    type State = State;
    type Mode = Mode;
    type Event = Event;
    type Step = PairStep;

    /// An attempt evaluates the law at 7 stages and more where it locates a switch.
    fn poll_stride(&self) -> u64 {
        poll_stride(self.ode.pair, 16)
    }

    fn dp_step(&self, m: &Mode, s: &State, k1: &State, h: f64, out: &mut PairStep) -> f64 {
        let (ode, mode) = (&self.ode, *m);
        let PairStep {
            dp,
            end,
            tangential,
            depths,
        } = out;
        tangential.begin();
        // The inner stages' depths are read for their signs alone (the stage filters'), and
        // in flight the law's derivative reads no contact: only the last stage's evaluation
        // (the step's end, where its switches are looked for) measures the gap.
        let flying = G::CORNERS && mode.apart && matches!(mode.tan, Tan::None | Tan::Free);
        dp.take(s, k1, h, |stage, y, k| {
            let e = if stage == 6 {
                ode.eval(&mode, y, k)
            } else if flying {
                ode.eval_in_flight(&mode, y, k)
            } else {
                ode.eval_stage(&mode, y, k)
            };
            depths[stage - 1] = e.depth;
            match mode.tan {
                Tan::Stick => tangential.stick(ode.to_slip_value(&e)),
                Tan::Slip(_) => tangential.slip(stage, e.f_raw, e.v_t),
                Tan::None | Tan::Free => {}
            }
            if stage == 6 {
                *end = e;
            }
        });
        self.scaled_norm(m, &dp.err)
    }

    fn step_end(step: &PairStep) -> (&State, &State) {
        (&step.dp.y1, &step.dp.err)
    }

    fn state_at_switch(&self, m: &Mode, step: &PairStep, th: f64) -> Option<(State, State)> {
        state_at_switch(&step.dp, th, |gap| self.scaled_norm(m, gap))
            .filter(|_| !self.ode.ends_apart(&step.dp.y1))
    }

    fn root_exponent(&self) -> Option<f64> {
        root_exponent(&self.ode.pair.law.scene.normal_law)
    }

    /// In contact and unclipped under the area and Hertz laws (the linear law's force has no
    /// root singularity at touch and separation; its kink at the parting is `ends_apart`'s).
    fn singular_force(&self, m: &Mode) -> bool {
        !m.clipped && !m.apart && self.root_exponent().is_some()
    }

    /// Bodies with corners: read from the law's evaluation where the step starts, where it
    /// is kept (its frame is the held overlap's, which the force acts in; found again, the
    /// clip cost two 12-gons a tenth of their impact).
    fn opening(&self, s: &State) -> (f64, f64) {
        if !G::CORNERS {
            return self.ode.opening(s);
        }
        self.start
            .and_then(|(_, e)| self.ode.opening_of(&e, s))
            .unwrap_or_else(|| self.ode.opening(s))
    }

    /// The first switch of the step's mode ([`first_switch`]), the switches that chattered
    /// left out; the largest overlap and area up to it are found on the same samples of the
    /// law ([`extremes_in`]).
    #[inline]
    fn first_switch(run: &mut Run<'_, Self>, step: &PairStep) -> Option<(f64, Event)> {
        let side = &mut run.side;
        let ignored = std::mem::take(&mut side.ignored);
        side.step_ignored = ignored;
        let firm = side.stays_in_tangential_mode(&run.mode, step);
        side.firm_slip = firm && matches!(run.mode.tan, Tan::Slip(_));
        let samples = StepSamples::new(&side.ode, run.mode, (&step.dp, &step.end), &side.kept);
        let first = first_switch(&samples, ignored, firm);
        let theta = first.map_or(1.0, |(th, _)| th);
        side.extremes = (theta * step.dp.h_len() > 0.0).then(|| extremes_in(&samples, theta));
        first
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

    /// Restores the angular momentum; after a step with the clip held, the end state decides
    /// the clip again.
    #[inline]
    fn settle(run: &mut Run<'_, Self>) {
        keep_angular_momentum(run);
        if run.side.step_ignored.clip {
            Self::end_clip_hold(run);
        }
    }

    fn apply(run: &mut Run<'_, Self>, ev: Event, _known: Option<&PairStep>) {
        Self::apply(run, ev);
    }

    /// Apart, the flight is jumped; in a slip, a slip whose force turned with the sliding ends.
    #[inline]
    fn without_switch(run: &mut Run<'_, Self>) {
        if run.mode.apart {
            fly(run);
        } else {
            let k = Self::end_a_reversed_slip(run);
            run.side.k_end = k.map(|(k, e)| (k, e, run.mode));
        }
    }

    /// Leaves a chattering switch for one step in the mode of its sliding motion (the rules'
    /// remedies, `Chatter`): a clip that switches on and off at once stays clipped (no force),
    /// stick and slip that each end at once slide along the cone in slip.
    fn resolve_chatter(run: &mut Run<'_, Self>) {
        let side = &mut run.side;
        if run.mode.clipped && run.chatter.take_clip() {
            side.ignored.clip = true;
        }
        if run.chatter.take_tangential() {
            if run.mode.tan == Tan::Stick {
                let e = Self::eval_in_mode(run).1;
                run.mode.tan = Tan::Slip(e.trial.signum());
            }
            run.side.ignored.tangential = true;
        }
        run.side.ignored.all = run.chatter.stalled();
    }

    /// The next step's first stage, at the state this one ended in: a touch's
    /// (`touch_derivative`); the one the slip's reversal test evaluated there, where the
    /// chatter rules kept its mode; after a whole step without a switch still in its mode, its
    /// last stage's (first same as last, as on the plate), the positions' rates the
    /// velocities restored to the angular momentum: the restoring turn is rigid, it changes no
    /// relative velocity at the contact, so the forces, the spring's rate and the forces'
    /// powers at the velocities before it are those after, to round-off; else the law
    /// evaluated afresh, or from its contact where the switch evaluated it at this state
    /// (`eval_at_switch`). Then the trace.
    #[inline]
    fn refresh(
        run: &mut Run<'_, Self>,
        whole: Option<&PairStep>,
        (mode_step, _): (&Mode, &State),
        _h_taken: f64,
    ) {
        let side = &mut run.side;
        let k_end = side.k_end.take().filter(|(_, _, kept)| run.mode == *kept);
        let start;
        (run.k1, start) = if let Some(probe) = side.touch_probe.take() {
            let k = side.ode.touch_derivative(&run.mode, &run.s, &probe);
            (k, None)
        } else if let Some((k, e, _)) = k_end {
            (k, Some(e))
        } else if let Some(step) = whole.filter(|_| *mode_step == run.mode && !run.mode.apart) {
            let mut k = step.dp.k_end();
            for (i, rate) in [(X, GX), (Y, GY), (4, W1), (6, W2)] {
                k[i] = run.s[rate];
            }
            // The restoring turn changes no relative velocity at the contact: the end's
            // normal force, tangential velocity and trial force are the state's.
            (k, Some(step.end))
        } else if run.mode.apart && matches!(run.mode.tan, Tan::None | Tan::Free) {
            // Apart, no force acts: the derivative without the contact, the same bits, and no
            // start kept (a flight's steps read none). Measuring the gap here, where the
            // flight has just measured it, cost two 120-gons a tenth of their impact.
            let mut k = [0.0; NS];
            side.ode.eval_in_flight(&run.mode, &run.s, &mut k);
            (k, None)
        } else {
            let (k, e) = if G::CORNERS {
                Self::eval_in_mode(run)
            } else {
                // Round bodies keep nothing at a switch: their law inlined here (called, it
                // cost two discs 5 % of their time at the same instructions).
                run.side.ode.eval_new(&run.mode, &run.s)
            };
            (k, Some(e))
        };
        run.side.start = start.map(|e| (run.mode, e));
        if let Some(tr) = run.trace.as_deref_mut() {
            push(&run.side, (&run.mode, &run.s, run.t), tr);
        }
    }

    fn after_piece(run: &mut Run<'_, Self>, _step: &PairStep, _h_taken: f64, _frac: f64) {
        let rec = &mut run.side.rec;
        if let Some([depth, area]) = run.side.extremes.take() {
            rec.max_depth = rec.max_depth.max(depth);
            rec.max_area = rec.max_area.max(area);
        }
    }

    fn add_error(&mut self, err: &State, factor: f64) {
        self.acc.add(err, factor, [GX, GY, W1, W2]);
    }

    /// Flights between contacts do not count.
    fn contact_time(run: &Run<'_, Self>) -> f64 {
        let ongoing = if run.mode.apart {
            0.0
        } else {
            run.t - run.t_touch
        };
        run.side.rec.contact_time + ongoing
    }

    fn parted(run: &mut Run<'_, Self>) -> bool {
        run.side.separated
    }

    fn finish(run: &mut Run<'_, Self>, stop: StopReason) -> Record {
        let s = run.s;
        let side = &run.side;
        let mut rec = side.rec;
        rec.stop = stop;
        rec.steps = run.steps;
        if !run.mode.apart && !side.separated {
            rec.contact_time += run.t - run.t_touch;
        }
        rec.work_normal = s[WN];
        rec.work_friction = s[WT];
        rec.work_damping = s[WD];
        let (q, v) = ([s[X], s[Y], s[4], s[6]], [s[GX], s[GY], s[W1], s[W2]]);
        let n_sep = if G::CORNERS {
            side.n_sep
        } else {
            separation_normal(&q, &v, side.ode.geometry.reach())
        };
        let end = Ending {
            q,
            v,
            y0: side.y0,
            n_sep,
        };
        let pair = side.ode.pair;
        rec.close(&Bodies::Pair(pair), &side.init, &end);
        let acc = &side.acc;
        let spins = [(acc.of(W1), pair.particle.r), (acc.of(W2), pair.r2)];
        rec.err_est = Some(error_estimate(&side.init, (acc.of(GX), acc.of(GY)), spins));
        rec
    }
}

impl<G: PairGeometry> OnPair<'_, G> {
    /// Whether the accepted `step` of mode `m` stays stuck or stays slipping throughout, by
    /// the bound the plate's stages give ([`TangentialStages`]): the stick -> slip function
    /// |F_trial| - mu F_n at the stages' states (the contact frame's turn and both spins are
    /// in each value), or in slip, with a linear spring, the stages' normal forces and
    /// tangential velocities v_t = g.t + a_1 omega_1 + a_2 omega_2 (at a spring stuck at its
    /// slipping elongation the trial force is the slip's, so the motion's rates are the
    /// slip's), where the normal force stays positive through the step (near the parting the
    /// law's rates are not bounded by the stages',
    /// [`TangentialStages::stays_slipping_in_contact`]) or the contact loads throughout (the
    /// plate's bound, [`TangentialStages::stays_slipping`]). Then its samples inside are
    /// skipped.
    /// Not where the start's evaluation is not kept (a touch), nor where a stage found the
    /// bodies apart.
    #[inline]
    fn stays_in_tangential_mode(&self, m: &Mode, step: &PairStep) -> bool {
        let Some((_, start)) = self.start.filter(|(mode, _)| mode == m) else {
            return false;
        };
        if start.depth <= 0.0 || step.depths.iter().any(|&d| d <= 0.0) {
            return false;
        }
        match m.tan {
            Tan::Stick => step.tangential.stays_stuck(self.ode.to_slip_value(&start)),
            Tan::Slip(sg) => self.ode.linear_slip().is_some_and(|spring| {
                let at_start = (start.f_raw, start.v_t);
                let h = step.dp.h_len();
                // A loading contact (each stage deeper than the one before it in time, the
                // first deeper than the start) is not parting: the plate's bound holds there.
                // The parting's guard (the least force above half a step of its largest rate)
                // never held while the force rose from the touch, and the first slip steps
                // after it sampled their switch: 7 of two 120-gons' 22 searches per impact.
                // (The last two stages both lie at the step's end: each is compared with the
                // one at 8/9 of it.)
                let d = &step.depths;
                let loading =
                    d[0] > start.depth && d[..5].windows(2).all(|w| w[1] > w[0]) && d[5] > d[3];
                if loading {
                    step.tangential.stays_slipping(sg, at_start, h, spring)
                } else {
                    step.tangential
                        .stays_slipping_in_contact(sg, at_start, h, spring)
                }
            }),
            Tan::None | Tan::Free => false,
        }
    }

    /// The largest component of the absolute errors `err` in units of the local tolerance, in
    /// mode `m` (the spring's elongation only while it sticks: elsewhere it is algebraic; the
    /// dashpot's work is a part of the normal force's, which is controlled, and reported only).
    fn scaled_norm(&self, m: &Mode, err: &State) -> f64 {
        (0..NS)
            .filter(|&i| (i != XI || m.tan == Tan::Stick) && i != WD)
            .map(|i| err[i].abs() * self.weight[i])
            .fold(0.0, f64::max)
    }
}

/// Restores the pair's angular momentum after a step: the step's polynomial does not keep a
/// product of position and velocity (the drift was up to 2.6e-5 tol), the forces do.
fn keep_angular_momentum<G: PairGeometry>(run: &mut Run<'_, OnPair<'_, G>>) {
    let s = &mut run.s;
    let q = [s[X], s[Y], s[4], s[6]];
    let v = [s[GX], s[GY], s[W1], s[W2]];
    let dv = run.side.ode.pair.restoring_turn(&q, &v, run.side.l0);
    for (i, d) in [GX, GY, W1, W2].into_iter().zip(dv) {
        s[i] += d;
    }
}

/// Apart: jumps the free flight (the plate's, [`flight`]), each advance counted as a step;
/// ends the impact when the bodies can never touch again.
pub(super) fn fly<G: PairGeometry>(run: &mut Run<'_, OnPair<'_, G>>) {
    let s = &mut run.s;
    let q = [s[X], s[Y], s[4], s[6]];
    let v = [s[GX], s[GY], s[W1], s[W2]];
    let radii = [run.side.ode.pair.particle.r, run.side.ode.pair.r2];
    let approach = Approach::of_pair(&q, &v, radii);
    let geometry = &run.side.ode.geometry;
    let at = |t: f64| -> [f64; 4] { std::array::from_fn(|i| q[i] + v[i] * t) };
    let gap = |t: f64| -geometry.signed_depth(&at(t));
    let left = run.lim.max_steps.saturating_sub(run.attempts);
    let (jump, advances) = flight::jump(gap, approach, run.lim.h_max, left);
    let t_jump = match jump {
        Jump::Stay => return,
        Jump::To(t) => t,
        Jump::Clear(t) => {
            run.side.separated = true;
            t
        }
    };
    let q = at(t_jump);
    (s[X], s[Y], s[4], s[6]) = (q[0], q[1], q[2], q[3]);
    run.t += t_jump;
    run.steps += advances;
    run.attempts += advances;
}

/// Appends the state `s` at time `t` in mode `m` to the trace.
fn push<G: PairGeometry>(side: &OnPair<'_, G>, (m, s, t): (&Mode, &State, f64), tr: &mut Trace) {
    let f = side.ode.eval_new(m, s).1.forces(m);
    let q = [s[X], s[Y], s[4], s[6]];
    let v = [s[GX], s[GY], s[W1], s[W2]];
    tr.push_pair(t, &q, &v, &f, s[XI]);
}

/// The largest overlap and area inside the part of the step of `samples` up to `theta`: at
/// its end, and where the normal velocity turns (the deepest point), located on the dense
/// output.
fn extremes_in<G: PairGeometry>(samples: &StepSamples<'_, '_, G>, theta: f64) -> [f64; 2] {
    let step = samples.step;
    // The normal velocity reads four components: the others are not formed, nor, at the
    // step's ends, the dense output's coefficients (the start's value is y0's, a zero's sign
    // aside, which a product and sum of the two directions' terms does not show).
    let g_n = |th: f64| {
        let c = |i| match th {
            0.0 => step.y0[i],
            1.0 => step.component_at_end(i),
            _ => step.component_at(th, i),
        };
        c(X) * c(GX) + c(Y) * c(GY)
    };
    let (a, b) = (g_n(0.0), g_n(theta));
    let at = [Some(theta), turning_point(g_n, a, (theta, b))];
    let mut most = [f64::NEG_INFINITY; 2];
    for th in at.into_iter().flatten() {
        let [depth, area] = samples.depth_and_area_at(th);
        most = [most[0].max(depth), most[1].max(area)];
    }
    most
}
