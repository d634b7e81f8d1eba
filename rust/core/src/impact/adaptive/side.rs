//! What the one adaptive loop (`run.rs`) asks of the body the particle meets: the plate
//! (`plate.rs`) and a partner body (`impact/pair`, which implements this from below) are two
//! answers, and the loop, monomorphised over them, is written once.
//!
//! The loop owns what every impact has: the state, its mode, the next step's first stage, the
//! clock, the step sizes, the limits, the step counts, the chatter count and the trace. A side
//! owns its ODE and what only it keeps (the plate's tally and its evaluation at the state; a
//! pair's angular momentum, its touch probe, the switches it ignores). Where a rule needs both
//! (applying a switch, the chatter remedies, the flight, the record), the side's function
//! takes the whole run.

use super::run::Run;
use super::SwitchKind;
use crate::impact::record::{Record, StopReason};

/// The body the particle meets, as the adaptive loop sees it (docs/model.md, 7.3 and 17.5).
pub(crate) trait AdaptiveSide: Sized {
    /// The ODE's state (positions, velocities, the spring, the works).
    type State: Copy + PartialEq + Default;
    /// The law that holds in a piece (clip, tangential law, contact formula).
    type Mode: Copy + PartialEq;
    /// The switches that end a piece.
    type Event: Copy + PartialEq;
    /// One Dormand-Prince step with what the switches read from its stages.
    type Step: Default;

    /// How many attempts apart the cancel token is polled (a power of two).
    fn poll_stride(&self) -> u64;

    // ---------------------------------------------------------------------------------------
    // Steps

    /// One Dormand-Prince step from `s` in mode `m` with first stage `k1`, written into `out`;
    /// returns its scaled error norm (<= 1: accepted).
    fn dp_step(
        &self,
        m: &Self::Mode,
        s: &Self::State,
        k1: &Self::State,
        h: f64,
        out: &mut Self::Step,
    ) -> f64;

    /// A step's 5th-order end and its embedded error estimate.
    fn step_end(step: &Self::Step) -> (&Self::State, &Self::State);

    /// The state at fraction `th` of `step` (mode `m`) and its local error, from the dense
    /// output where that is within the tolerance (`rules::state_at_switch`); `None`: the loop
    /// redoes the step up to there.
    fn state_at_switch(
        &self,
        m: &Self::Mode,
        step: &Self::Step,
        th: f64,
    ) -> Option<(Self::State, Self::State)>;

    /// The first node of `step` at which the law crossed a switch that the dense output does
    /// not show (the plate's clip pulling): the step is then shortened. None by default.
    fn unseen_switch(_step: &Self::Step) -> Option<f64> {
        None
    }

    // ---------------------------------------------------------------------------------------
    // Step caps and the error factors at the force's root singularity

    /// The exponent of the normal law's root singularity at touch and separation, if it has one
    /// (`rules::root_exponent`).
    fn root_exponent(&self) -> Option<f64>;

    /// Whether mode `m` has that singularity (in contact, the force unclipped, a law that has
    /// one).
    fn singular_force(&self, m: &Self::Mode) -> bool;

    /// The depth at `s` and the rate at which it closes (> 0 while separating), for the cap of
    /// the steps towards separation (`rules::singular_cap`).
    fn opening(&self, s: &Self::State) -> (f64, f64);

    /// A cap of the side's own on the next step (a turning polygon's corners); none by default.
    fn step_cap(&self, _m: &Self::Mode, _s: &Self::State) -> f64 {
        f64::INFINITY
    }

    // ---------------------------------------------------------------------------------------
    // Switches

    /// The earliest switch inside the accepted `step`: (fraction of the step, event), the
    /// switches the chatter remedies ignore left out.
    fn first_switch(run: &mut Run<'_, Self>, step: &Self::Step) -> Option<(f64, Self::Event)>;

    /// The kind of switch `ev` is, for the chatter count and the root singularity.
    fn switch_kind(ev: Self::Event) -> SwitchKind;

    /// To what fraction of its step switch `ev` is located.
    fn switch_precision(&self, ev: Self::Event) -> f64;

    /// After a piece has been taken, before its switch: what the state decides again (a clip
    /// held off for a step, a pair's angular momentum).
    fn settle(_run: &mut Run<'_, Self>) {}

    /// Switches the mode at `ev` and sets the algebraic part of the state; `known`: the step
    /// whose end is the state, where it ended there in the current mode (its last stage's
    /// evaluation is the state's).
    fn apply(run: &mut Run<'_, Self>, ev: Self::Event, known: Option<&Self::Step>);

    /// After a piece that ended without a switch (a pair's flight, a slip's reversal).
    fn without_switch(_run: &mut Run<'_, Self>) {}

    /// Leaves a chattering switch for one step in the mode of its sliding motion
    /// (`rules::Chatter`'s remedies).
    fn resolve_chatter(run: &mut Run<'_, Self>);

    /// The first stage of the next step at the state reached, and the trace; `whole`: the step,
    /// where it was taken whole without a switch (first same as last where the state and mode
    /// are still its end's: `before`, the mode it ran in and its end), `h_taken` how far the
    /// piece went.
    fn refresh(
        run: &mut Run<'_, Self>,
        whole: Option<&Self::Step>,
        before: (&Self::Mode, &Self::State),
        h_taken: f64,
    );

    // ---------------------------------------------------------------------------------------
    // Extremes, errors, flight and the record

    /// After a piece of length `h_taken` (> 0), `frac` of its `step`: the extremes inside it
    /// and the side's tallies.
    fn after_piece(run: &mut Run<'_, Self>, step: &Self::Step, h_taken: f64, frac: f64);

    /// Adds a piece's local errors `err` (times `factor`) to those `err_est` accumulates.
    fn add_error(&mut self, err: &Self::State, factor: f64);

    /// The time spent in contact so far, the ongoing contact included (the budget's measure).
    fn contact_time(run: &Run<'_, Self>) -> f64;

    /// Whether the bodies have parted for good (a flight jumped over on the way, where the side
    /// flies at the loop's head).
    fn parted(run: &mut Run<'_, Self>) -> bool;

    /// A jump the side takes instead of a step (the disc's clipped tail); true if it took one.
    fn coast(_run: &mut Run<'_, Self>) -> bool {
        false
    }

    /// The record of the impact, ended for `stop`.
    fn finish(run: &mut Run<'_, Self>, stop: StopReason) -> Record;
}
