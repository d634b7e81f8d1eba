//! The pair's mode at a switch on the adaptive path (docs/model.md, 17.5 and 17.8): the mode a
//! piece continues in after an event, with the algebraic part of the state it implies (the
//! spring's elongation), the held springs switching, and the tangential and clip decisions
//! that follow from the state rather than from an event function.

use super::adaptive::{fly, OnPair};
use super::piece::{Eval, Event, Kept, Mode, State, Tan, NS, X, XI, Y};
use crate::geometry::pair::PairGeometry;
use crate::impact::adaptive::Run;

impl<G: PairGeometry> OnPair<'_, G> {
    /// After a step with the clip held: the end state decides the clip again.
    pub(super) fn end_clip_hold(run: &mut Run<'_, Self>) {
        if run.mode.clipped && Self::eval_in_mode(run).1.f_raw > 0.0 {
            Self::apply(run, Event::ClipOff);
        }
    }

    /// [`Self::eval_at_switch`] in the run's mode.
    #[inline]
    pub(super) fn eval_in_mode(run: &mut Run<'_, Self>) -> (State, Eval) {
        let m = run.mode;
        Self::eval_at_switch(run, &m)
    }

    /// Slip -> stick's function at the run's state in its (slipping) mode, from the contact
    /// kept there ([`Self::eval_at_switch`]) where it is.
    fn to_stick_value_at_switch(run: &Run<'_, Self>) -> f64 {
        let (side, m, s) = (&run.side, &run.mode, &run.s);
        match side.kept_contact(s, m) {
            Some(contact) => side.ode.event_value_with(m, Event::ToStick, s, || {
                side.ode.rates(m, s, contact, &mut [0.0; NS])
            }),
            None => side.ode.event_value(m, Event::ToStick, s),
        }
    }

    /// The law's derivative and evaluation at the run's state in mode `m`. A switch evaluates
    /// the law where it decides the mode, and the piece that follows starts from the same
    /// state (`OnPair::refresh`), often in another tangential mode or with another spring:
    /// where the last evaluation kept ([`OnPair::at_switch`]) was taken at these positions and
    /// velocities, with these held springs and in a mode of the same clip, its contact (the
    /// frame and the normal force, which read nothing else) is read and only the tangential
    /// law and the rates are formed ([`super::law::PairOde::rates`]: the same bits), the held
    /// overlap not clipped again. Found afresh, two 120-gons evaluated it up to four times at
    /// one switch.
    #[inline]
    pub(super) fn eval_at_switch(run: &mut Run<'_, Self>, m: &Mode) -> (State, Eval) {
        let (side, s) = (&mut run.side, &run.s);
        if !G::CORNERS {
            // Round bodies' frame is a lens in closed form, found again for less than keeping
            // it costs.
            return side.ode.eval_new(m, s);
        }
        let mut ds = [0.0; NS];
        let e = match side.kept_contact(s, m) {
            Some(contact) => side.ode.rates(m, s, contact, &mut ds),
            None => side.ode.eval(m, s, &mut ds),
        };
        side.at_switch = Some(Kept::new(s, m, e));
        (ds, e)
    }

    /// The contact kept at state `s` for a mode of `m`'s clip, where one is
    /// ([`Kept::contact_at`]).
    fn kept_contact(&self, s: &State, m: &Mode) -> Option<Eval> {
        self.at_switch
            .as_ref()
            .and_then(|kept| kept.contact_at(s, m))
    }

    /// Switches the mode at event `ev` and sets the algebraic part of the state.
    pub(super) fn apply(run: &mut Run<'_, Self>, ev: Event) {
        match ev {
            Event::Separate => Self::separate(run),
            Event::Touch => {
                run.mode = Mode {
                    clipped: false,
                    apart: false,
                    tan: Tan::None,
                };
                run.s[XI] = 0.0;
                let probe;
                let ode = &mut run.side.ode;
                (run.mode.tan, probe) = ode.mode_after_touch(&run.mode, &run.s, run.side.probe_dt);
                // The touch holds its own springs: no evaluation before it stands.
                run.side.at_switch = None;
                run.side.touch_probe = Some(probe);
                run.side.rec.contacts += 1;
            }
            Event::ClipOn => {
                run.mode = Mode {
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
                let clipped = Self::eval_in_mode(run).1;
                run.s[XI] = run.side.ode.slipping_xi(&clipped);
                run.mode.clipped = false;
                run.mode.tan = if run.side.ode.mu == 0.0 {
                    Tan::None
                } else {
                    let stuck = Mode {
                        tan: Tan::Stick,
                        ..run.mode
                    };
                    let e = Self::eval_at_switch(run, &stuck).1;
                    run.side.ode.tan_of_stuck(&e)
                };
            }
            Event::ToSlip => {
                let e = Self::eval_in_mode(run).1;
                run.mode.tan = Tan::Slip(e.trial.signum());
                run.side.rec.slip_events += 1;
            }
            Event::ToStick => {
                let e = Self::eval_in_mode(run).1;
                run.s[XI] = run.side.ode.slipping_xi(&e);
                run.mode.tan = Tan::Stick;
            }
            Event::Springs => Self::switch_springs(run),
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
    fn switch_springs(run: &mut Run<'_, Self>) {
        // The force before the switch is read by a clip's release and a slip's spring alone
        // (a stick's spring goes through as it is).
        let (m, apart) = (run.mode, run.mode.apart);
        let read_before = !apart && (m.clipped || matches!(m.tan, Tan::Slip(_)));
        let before = read_before.then(|| run.side.ode.eval_value(&m, &run.s));
        let q = [run.s[X], run.s[Y], run.s[4], run.s[6]];
        run.side.ode.held = run.side.ode.geometry.held_springs(&q);
        // Evaluated with the springs before, no evaluation kept stands.
        run.side.at_switch = None;
        let Some(before) = before else {
            if !apart && m.tan == Tan::Stick {
                Self::stick_or_slip_on_new_springs(run, false);
            }
            return;
        };
        if m.clipped {
            Self::release_a_clip(run, before.f_raw);
            return;
        }
        run.s[XI] = run.side.ode.slipping_xi(&before);
        Self::stick_or_slip_on_new_springs(run, true);
    }

    /// [`Self::switch_springs`]' decision on the new springs, `slipping` or sticking before
    /// them (the slip's spring already set to its slipping elongation).
    fn stick_or_slip_on_new_springs(run: &mut Run<'_, Self>, slipping: bool) {
        let stick = Mode {
            tan: Tan::Stick,
            ..run.mode
        };
        let after = Self::eval_at_switch(run, &stick).1;
        let (trial, cone) = (
            after.trial.abs(),
            run.side.ode.mu * (after.f_el + after.f_d),
        );
        if slipping && cone > trial * (1.0 + 1e-9) {
            run.mode.tan = Tan::Stick;
        } else if slipping && Self::to_stick_value_at_switch(run) > 0.0 {
            // On the cone, and sticking would move inside it (its rates changed with the
            // springs): the slip ends here. Its event, positive from the start of the next step,
            // fires on its value at the step's end, and a stick shorter than that step went
            // unseen (twin 120-gons, elastic, mu 0.3, 20 deg: 2e-5 off at tol 1e-8).
            Self::apply(run, Event::ToStick);
        } else if !slipping && trial > cone * (1.0 + 1e-9) {
            run.mode.tan = Tan::Slip(after.trial.signum());
            run.side.rec.slip_events += 1;
        }
    }

    /// A clipped force that a switch of the springs turned to pushing (an entering corner's
    /// dashpot, or a leaving corner's pull gone; `before` the force before the switch) is
    /// released there. Left to the clip's event, positive from the start of the next step, the
    /// release went unseen where the push ended within that step (the event fires on its
    /// value at the step's end): twin 120-gons (damped, mu 0.3, 20 deg) with a largest step of
    /// 1 t_ref ended 0.035 from the reference in e_N at every tol, err_est 2 tol.
    fn release_a_clip(run: &mut Run<'_, Self>, before: f64) {
        let after = Self::eval_in_mode(run).1.f_raw;
        // A jump beyond round-off: at a corner turning to another edge the force is unchanged.
        if after > 0.0 && after - before > 1e-9 * (after.abs() + before.abs()) {
            Self::apply(run, Event::ClipOff);
        }
    }

    /// Ends a slip whose force has turned with the sliding (s v_t > 0 past a margin of the
    /// speed) at the end of a step, where sticking is consistent there (`ToStick`'s function
    /// positive: a stuck spring would move inside the cone): the rate test of `ToStick`
    /// samples a sign change that a turning contact frame (bodies with corners) can carry
    /// through within one step. The contact sticks at its slipping elongation. Where sticking
    /// is not consistent the slip goes on: the cone closes faster than a stuck spring would
    /// follow, and the sliding turned by the spring relaxing along it is the motion the
    /// reference converges to. Stuck there, the slip's function rose above zero at once and
    /// fell back within the step, so its samples at thirds missed it (a damped pentagon on a
    /// 60-gon at mu 1.18, tol 1e-7: stuck 6e-6 s before the reference, 52.8 tol off with
    /// err_est 2.9 tol; the reference itself stuck and slipped again at each of its steps,
    /// 103 switches, now 3, to the same answer within 4e-13). The derivative it evaluated
    /// where the slip goes on (the next step's first stage, `OnPair::refresh`).
    pub(super) fn end_a_reversed_slip(run: &mut Run<'_, Self>) -> Option<(State, Eval)> {
        let Tan::Slip(sg) = run.mode.tan else {
            return None;
        };
        // A step whose stages kept it sliding against its force (`firm_slip`) ends sliding so.
        if !G::CORNERS || run.side.firm_slip {
            return None;
        }
        // Evaluated afresh: mostly the slip goes on, and the derivative is the next step's.
        let (ds, e) = run.side.ode.eval_new(&run.mode, &run.s);
        let consistent = || {
            run.side
                .ode
                .event_value_with(&run.mode, Event::ToStick, &run.s, || e)
        };
        if sg * e.v_t > run.side.slip_margin && consistent() > 0.0 {
            // The stick's first stage reads this contact (`OnPair::refresh`).
            run.side.at_switch = Some(Kept::new(&run.s, &run.mode, e));
            run.s[XI] = run.side.ode.slipping_xi(&e);
            run.mode.tan = Tan::Stick;
            return None;
        }
        Some((ds, e))
    }

    /// A contact ends: round bodies separate for good; bodies with corners fly apart, their
    /// flight skipped up to where they might touch again, or the impact ends.
    fn separate(run: &mut Run<'_, Self>) {
        run.side.rec.contact_time += run.t - run.t_touch;
        let s = &mut run.s;
        let d = s[X].hypot(s[Y]);
        run.side.n_sep = [s[X] / d, s[Y] / d];
        if !G::CORNERS {
            run.side.separated = true;
            return;
        }
        run.mode = Mode {
            clipped: false,
            apart: true,
            tan: Tan::None,
        };
        // Apart, no spring acts; the next touch holds its own (`mode_after_touch`).
        run.side.ode.held.springs.clear();
        run.side.at_switch = None;
        fly(run);
    }
}
