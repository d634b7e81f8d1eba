//! The one loop of an impact on the adaptive path, on the plate and on a pair: step, reject or
//! accept, end the piece at the first switch, handle chattering switches, and build the
//! record. Generic over the body the particle meets ([`AdaptiveSide`]), monomorphised: the
//! disc on the plate compiles to its own loop.

use super::rules::{singular_cap, singular_factor, verdict, Chatter, Limits, SwitchKind, Verdict};
use super::side::AdaptiveSide;
use crate::cancel::Cancel;
use crate::error::Result;
use crate::impact::record::{Record, StopReason, Trace};

/// The state of one impact between steps; `side` what the body met keeps of its own.
pub(crate) struct Run<'t, S: AdaptiveSide> {
    pub(crate) side: S,
    /// The ODE's state, its mode, and the first stage of the next step (FSAL).
    pub(crate) s: S::State,
    pub(crate) mode: S::Mode,
    pub(crate) k1: S::State,
    pub(crate) t: f64,
    /// The step to try next.
    pub(crate) h: f64,
    /// The largest and smallest steps, the budgets and the negligible piece.
    pub(crate) lim: Limits,
    /// Accepted steps, and attempts (rejected ones and those redone to a switch included).
    pub(crate) steps: u64,
    pub(crate) attempts: u64,
    /// Consecutive negligible and zero-length pieces.
    pub(crate) chatter: Chatter,
    /// No step taken since the last touch, at `t_touch`: the next starts at a point where the
    /// force is not smooth, and the next few still see its root singularity.
    pub(crate) fresh_touch: bool,
    pub(crate) t_touch: f64,
    pub(crate) trace: Option<&'t mut Trace>,
}

impl<'t, S: AdaptiveSide> Run<'t, S> {
    /// A run at first touch (t = 0) in state `s` and mode `m`, first stage `k1`, first step `h`.
    pub(crate) fn new(
        side: S,
        (s, mode, k1): (S::State, S::Mode, S::State),
        h: f64,
        lim: Limits,
        trace: Option<&'t mut Trace>,
    ) -> Self {
        Run {
            side,
            s,
            mode,
            k1,
            t: 0.0,
            h,
            lim,
            steps: 0,
            attempts: 0,
            chatter: Chatter::default(),
            fresh_touch: true,
            t_touch: 0.0,
            trace,
        }
    }

    /// Integrates the impact to its end: the bodies parted for good, a budget spent, or a
    /// state no step keeps finite.
    pub(crate) fn integrate(&mut self, cancel: &Cancel) -> Result<Record> {
        // Where each attempted step and each step redone up to a switch are written (~1.4 kB
        // each on the plate: returned by value, a step was copied twice per attempt).
        let (mut step, mut redo) = (S::Step::default(), S::Step::default());
        let stride = self.side.poll_stride();
        let stop = loop {
            if S::parted(self) {
                break StopReason::Separated;
            }
            cancel.poll_every(self.attempts, stride)?;
            if let Some(stop) = self.lim.budget_spent(self.attempts, S::contact_time(self)) {
                break stop;
            }
            if S::coast(self) {
                continue;
            }
            if let Some(stop) = self.attempt(&mut step, &mut redo) {
                break stop;
            }
        };
        Ok(S::finish(self, stop))
    }

    /// The step to try: the next one, within the largest, near touch and separation within
    /// the rules' ([`singular_cap`]), and within the side's own cap.
    fn capped_step(&self) -> f64 {
        let (side, lim) = (&self.side, &self.lim);
        let mut h = self.h.min(lim.h_max);
        if side.singular_force(&self.mode) {
            // Just after a touch the cap does not read the opening (a pair's costs a clip).
            let opening = if self.fresh_touch {
                (0.0, 0.0)
            } else {
                side.opening(&self.s)
            };
            h = h.min(singular_cap(self.fresh_touch, opening, lim.h_singular));
        }
        h.min(side.step_cap(&self.mode, &self.s))
    }

    /// One attempted step: rejected (the next try is shorter) or taken up to the first
    /// switch inside it. Returns why the impact stops, if it does.
    fn attempt(&mut self, step: &mut S::Step, redo: &mut S::Step) -> Option<StopReason> {
        let h = self.capped_step();
        self.h = h;
        let err = self.side.dp_step(&self.mode, &self.s, &self.k1, h, step);
        self.attempts += 1;
        let h_min = self.lim.h_min();
        let h_next = match verdict(err, h, h_min) {
            Verdict::Accept { h_next } => h_next,
            Verdict::Reject { h_retry } => {
                self.h = h_retry;
                return None;
            }
            Verdict::NonFinite => return Some(StopReason::NonFinite),
        };
        let first = S::first_switch(self, step);
        if let Some(c) = S::unseen_switch(step).filter(|_| !self.chatter.stalled()) {
            if first.is_none_or(|(th, _)| th > c) && h > h_min {
                // The step crossed a switch that its dense output does not show: never
                // integrate across it with the law of the other side; shorten the step.
                self.h = (0.5 * c * h).max(h_min);
                return None;
            }
        }
        self.take(step, redo, first, h_next);
        None
    }

    /// Takes the accepted `step` up to its first switch (all of it if none), switches the
    /// mode there and prepares the next step (`h_next` the error control's proposal).
    fn take(
        &mut self,
        step: &S::Step,
        redo: &mut S::Step,
        first: Option<(f64, S::Event)>,
        h_next: f64,
    ) {
        let (h, mode_step) = (self.h, self.mode);
        let (y1, err) = S::step_end(step);
        // The state where the piece ends, its local error, and the step whose end it is.
        let (s_new, h_taken, event, err_taken, ended) = match first {
            None => (*y1, h, None, *err, Some(step)),
            Some((th, ev)) if th >= 1.0 => (*y1, h, Some(ev), *err, Some(step)),
            Some((th, ev)) if th * h <= 0.0 => (self.s, 0.0, Some(ev), S::State::default(), None),
            Some((th, ev)) => {
                // A switch inside the step counts against the budget as a step's work, whether
                // the step is redone to it or not: a rattle of 10^5 short contacts is mostly
                // switches, and the budget bounds its time (uncounted, a 4096-gon's rattle ran
                // 0.85 s to the budget instead of 0.66).
                self.attempts += 1;
                #[cfg(feature = "bench-counters")]
                crate::counters::count_located_switch(th);
                match self.side.state_at_switch(&self.mode, step, th) {
                    Some((s_th, err)) => (s_th, th * h, Some(ev), err, None),
                    None => {
                        // Redone to the switch, the state there has full Runge-Kutta accuracy.
                        self.side
                            .dp_step(&self.mode, &self.s, &self.k1, th * h, redo);
                        let (y1, err) = S::step_end(redo);
                        (*y1, th * h, Some(ev), *err, Some(&*redo))
                    }
                }
            }
        };
        let factor = self.singular_factor(h_taken, event);
        self.side.add_error(&err_taken, factor);
        let switch = event.map(|ev| (S::switch_kind(ev), self.side.switch_precision(ev)));
        self.chatter.count(switch, (h_taken, h), self.lim.tiny);
        if h_taken > 0.0 {
            // Pieces of zero length are no steps.
            self.fresh_touch = false;
            self.steps += 1;
            S::after_piece(self, step, h_taken, h_taken / h);
        }
        self.t += h_taken;
        self.s = s_new;
        S::settle(self);
        match event {
            Some(ev) => {
                if S::switch_kind(ev) == SwitchKind::Touch {
                    (self.fresh_touch, self.t_touch) = (true, self.t);
                }
                let known = ended.filter(|_| self.mode == mode_step);
                S::apply(self, ev, known);
            }
            None => S::without_switch(self),
        }
        S::resolve_chatter(self);
        // A whole step without a switch ends where its last stage was evaluated (FSAL).
        let whole = (event.is_none() && h_taken == h).then_some(step);
        S::refresh(self, whole, (&mode_step, &s_new), h_taken);
        // After a switch the next step is at most this one.
        self.h = if event.is_some() {
            h_next.min(h)
        } else {
            h_next
        };
    }

    /// The factor on the local error of a piece of length `h_taken` ended by `event`, where
    /// the force has a root singularity at touch and separation ([`singular_factor`]).
    fn singular_factor(&self, h_taken: f64, event: Option<S::Event>) -> f64 {
        match self.side.root_exponent() {
            Some(p) if self.side.singular_force(&self.mode) => {
                let rho = (h_taken > 0.0).then(|| (self.t - self.t_touch) / h_taken);
                singular_factor(
                    p,
                    rho,
                    event.is_some_and(|ev| S::switch_kind(ev) == SwitchKind::Separation),
                )
            }
            _ => 1.0,
        }
    }
}
