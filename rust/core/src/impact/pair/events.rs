//! The switches that end a piece of a pair's impact (docs/model.md, 17.5 and 17.8): which can end
//! a mode, and their event functions (continuous, <= 0 while the piece's mode holds).

use super::law::PairOde;
use super::piece::{Eval, Event, Mode, State, Tan, NS, X, XI, Y};
use crate::geometry::pair::PairGeometry;
use crate::impact::adaptive::switch_precision;
use crate::model::NormalLaw;

impl<G: PairGeometry> PairOde<'_, G> {
    /// The events that can end a piece of mode `m`.
    pub(super) fn candidates(&self, m: &Mode) -> impl Iterator<Item = Event> {
        let apart = m.apart.then_some(Event::Touch);
        let clip = if m.apart {
            None
        } else if m.clipped {
            Some(Event::ClipOff)
        } else {
            Some(Event::ClipOn)
        };
        let tan = match m.tan {
            Tan::Stick => Some(Event::ToSlip),
            Tan::Slip(_) => Some(Event::ToStick),
            _ => None,
        };
        let separate = (!m.apart).then_some(Event::Separate);
        let springs = (!m.apart && self.geometry.holds_springs()).then_some(Event::Springs);
        [apart, separate, clip, tan, springs].into_iter().flatten()
    }

    /// To what fraction of its step switch `ev` is located: the plate's rule
    /// ([`switch_precision`]) at the run's local tolerance. The force jumps where the linear
    /// law's dashpot starts to push (the touch) and where the held springs switch (a corner's
    /// spring enters or leaves; under the area law a crossing passes a corner, where the
    /// potential's force jumps, docs/model.md 17.8).
    pub(super) fn switch_precision(&self, ev: Event) -> f64 {
        let linear = matches!(self.pair.law.scene.normal_law, NormalLaw::Linear { .. });
        let jumps = ev == Event::Springs || (linear && ev == Event::Touch);
        switch_precision(self.pair.particle.scene.local_tol(), jumps)
    }

    /// The value of event `ev`'s function at state `s` in mode `m` (> 0: it fired).
    pub(super) fn event_value(&self, m: &Mode, ev: Event, s: &State) -> f64 {
        self.event_value_with(m, ev, s, || self.eval_new(m, s).1)
    }

    /// [`Self::event_value`], the law's evaluation at `s` in mode `m` given by `eval` (called
    /// only where the event needs it: a step's candidates share one evaluation per sample).
    pub(super) fn event_value_with(
        &self,
        m: &Mode,
        ev: Event,
        s: &State,
        eval: impl FnOnce() -> Eval,
    ) -> f64 {
        if ev == Event::Springs {
            let q = [s[X], s[Y], s[4], s[6]];
            return self.geometry.held_springs_value(&q, &self.held);
        }
        let e = eval();
        match ev {
            Event::Separate => -e.depth,
            Event::Touch => e.depth,
            Event::ClipOn => -e.f_raw,
            Event::ClipOff => e.f_raw,
            Event::ToSlip => self.to_slip_value(&e),
            Event::ToStick => self.to_stick_value(m, s, &e),
            Event::Springs => unreachable!("answered above"),
        }
    }

    /// Stick -> slip: |F_trial| - mu F_n, at evaluation `e`.
    pub(super) fn to_slip_value(&self, e: &Eval) -> f64 {
        // Where no overlap is resolved (the touch itself) the cone is closed but no spring
        // acts either: the touch's probe has chosen the mode (`mode_after_touch`).
        if e.depth <= 0.0 {
            return f64::NEG_INFINITY;
        }
        // Past the cone by a margin of 1e-9 of it: a spring just set on the cone (at a
        // slip -> stick switch) is not taken back by round-off.
        let cap = self.mu * e.f_raw.max(0.0);
        e.trial.abs() - cap - 1e-9 * (e.trial.abs() + cap)
    }

    /// Slip -> stick: mu dF_n/dt - s dF_trial/dt, positive where sticking would move the
    /// trial force inside the cone: both rates taken by a forward difference along the motion
    /// the contact would have if it stuck now (the spring at its slipping elongation, moving
    /// as in stick), so that a slip the damper reverses ends, and the switch is consistent.
    fn to_stick_value(&self, m: &Mode, s: &State, e: &Eval) -> f64 {
        let Tan::Slip(sg) = m.tan else {
            return f64::NEG_INFINITY;
        };
        if e.depth <= 0.0 {
            return f64::NEG_INFINITY;
        }
        let h = self.fd_step;
        let mut held = *s;
        held[XI] = self.slipping_xi(e);
        let stick = Mode {
            tan: Tan::Stick,
            ..*m
        };
        // Held differs from `s` in the spring alone: the contact `e` found there is its own.
        let mut d_stick = [0.0; NS];
        let now = self.rates(&stick, &held, *e, &mut d_stick);
        let ahead: State = std::array::from_fn(|i| held[i] + h * d_stick[i]);
        let later = self.eval_new(&stick, &ahead).1;
        let dfn = (later.f_raw - now.f_raw) / h;
        let dtrial = (later.trial - now.trial) / h;
        let value = self.mu * dfn - sg * dtrial;
        // Past its root by a margin of 1e-9 of its terms, so that the spring starts inside.
        value - 1e-9 * (self.mu * dfn.abs() + dtrial.abs())
    }
}
