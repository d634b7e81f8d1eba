//! Where a piece of the pair's adaptive path ends (docs/model.md, 17.5 and 17.8): the first
//! switch inside an accepted step, located on the step's dense output by Brent's method; stick
//! and slip also sampled inside the step, by the plate's rule.

use super::law::PairOde;
use super::piece::{Eval, Event, Mode, State, Tan, INTERPOLATED, NS};
use crate::geometry::pair::PairGeometry;
use crate::impact::adaptive::{
    first_positive_sample, locate_switch, sampled_first_switch, TANGENTIAL_PARTS,
};
use crate::integrate::dopri::DenseStep;
use std::cell::RefCell;

/// The switches a step does not look for, where they chattered (the adaptive rules'
/// remedies, `Chatter`).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Ignored {
    /// Stick -> slip and slip -> stick.
    pub(super) tangential: bool,
    /// The clip switching off (the force back on).
    pub(super) clip: bool,
    /// Every switch (so many pieces of zero length in a row).
    pub(super) all: bool,
}

/// The law evaluated at fractions of one accepted step in the step's mode, each shared fraction
/// once: every candidate event samples the step's end, and the extremes sample it again (or
/// the switch located last); the law is a function of the state and mode alone, so an
/// evaluation is reused, never redone (two 12-gons evaluated it 16.7 times per step, 2.8 of
/// them again). The step's end is the last stage's state where the dense output rounds to it
/// bit for bit, and read from its evaluation. Round bodies keep nothing else: their law costs
/// less than keeping it (two discs kept theirs and ran 8-12 % slower with 16 % fewer
/// evaluations).
pub(super) struct StepSamples<'s, 'a, G> {
    pub(super) ode: &'s PairOde<'a, G>,
    pub(super) mode: Mode,
    pub(super) step: &'s DenseStep<NS, INTERPOLATED>,
    /// The last stage's evaluation, at the step's 5th-order end `y1`.
    at_end: &'s Eval,
    /// The dense output at the step's end: every candidate event samples it.
    end_state: State,
    /// Whether `end_state` is the last stage's state `y1` bit for bit in the components the
    /// law reads (y0 + (y1 - y0) need not round to it): then `at_end` is the law there.
    end_is_stage: bool,
    kept: &'s RefCell<KeptSamples>,
}

/// The evaluations a step keeps, without allocating: the step's end in the first slot, the
/// latest others in turn after it; held by the run and emptied for each step (a buffer built
/// per step, or a list allocated per step, cost the disc pair more than it saved).
#[derive(Default)]
pub(super) struct KeptSamples {
    /// The fractions evaluated (their bits) with the evaluation there, and how many were.
    seen: [(u64, Eval); SAMPLES_KEPT],
    count: usize,
}

/// How many evaluations of a step [`KeptSamples`] holds.
const SAMPLES_KEPT: usize = 4;

impl<'s, 'a, G: PairGeometry> StepSamples<'s, 'a, G> {
    pub(super) fn new(
        ode: &'s PairOde<'a, G>,
        mode: Mode,
        (step, at_end): (&'s DenseStep<NS, INTERPOLATED>, &'s Eval),
        kept: &'s RefCell<KeptSamples>,
    ) -> Self {
        kept.borrow_mut().count = 0;
        let end_state = step.at_end();
        let end_is_stage = end_state[..INTERPOLATED]
            .iter()
            .zip(&step.y1)
            .all(|(a, b)| a.to_bits() == b.to_bits());
        StepSamples {
            ode,
            mode,
            step,
            at_end,
            end_state,
            end_is_stage,
            kept,
        }
    }

    /// The dense output at fraction `th` of the step, the same bits as [`DenseStep::at`].
    pub(super) fn state_at(&self, th: f64) -> State {
        if th == 1.0 {
            self.end_state
        } else {
            self.step.at(th)
        }
    }

    /// The law's evaluation at fraction `th` of the step, whose state there `s` is
    /// ([`Self::state_at`]).
    pub(super) fn eval_at(&self, th: f64, s: &State) -> Eval {
        if th == 1.0 && self.end_is_stage {
            return *self.at_end;
        }
        if !G::CORNERS {
            return self.ode.eval_value(&self.mode, s);
        }
        let key = th.to_bits();
        let mut kept = self.kept.borrow_mut();
        let count = kept.count;
        let seen = &mut kept.seen;
        if let Some((_, e)) = seen[..count.min(SAMPLES_KEPT)]
            .iter()
            .find(|(k, _)| *k == key)
        {
            return *e;
        }
        let e = self.ode.eval_value(&self.mode, s);
        // The first fraction sampled is the step's end (every candidate's first): kept; the
        // latest others in turn in the slots after it.
        let slot = if count < SAMPLES_KEPT {
            count
        } else {
            1 + (count - 1) % (SAMPLES_KEPT - 1)
        };
        seen[slot] = (key, e);
        kept.count = count + 1;
        e
    }

    /// The value of event `ev`'s function at fraction `th` of the step
    /// ([`PairOde::event_value`]).
    fn event_value(&self, ev: Event, th: f64) -> f64 {
        let (ode, m) = (self.ode, &self.mode);
        if th < 1.0 {
            let s = self.step.at(th);
            return ode.event_value_with(m, ev, &s, || self.eval_at(th, &s));
        }
        // The step's end and its evaluation read where they are kept, not copied: every
        // candidate samples them.
        let s = &self.end_state;
        if let Some(value) = ode.state_event_value(ev, s) {
            value
        } else if self.end_is_stage {
            ode.event_value_of(m, ev, s, self.at_end)
        } else {
            ode.event_value_of(m, ev, s, &self.eval_at(th, s))
        }
    }

    /// The overlap's depth and area at fraction `th` of the step ([`Self::eval_at`]).
    pub(super) fn depth_and_area_at(&self, th: f64) -> [f64; 2] {
        if th == 1.0 && self.end_is_stage {
            return [self.at_end.depth, self.at_end.area];
        }
        let e = self.eval_at(th, &self.state_at(th));
        [e.depth, e.area]
    }
}

/// The first switch of the step's mode inside the accepted step of `samples`: (fraction of
/// the step, event), the `ignored` switches left out; `firm`: the step's stages showed it stays
/// stuck or stays slipping throughout, so its tangential switch is not looked for.
pub(super) fn first_switch<G: PairGeometry>(
    samples: &StepSamples<'_, '_, G>,
    ignored: Ignored,
    firm: bool,
) -> Option<(f64, Event)> {
    if ignored.all {
        return None;
    }
    let (ode, m) = (samples.ode, &samples.mode);
    let g = |ev: Event, th: f64| samples.event_value(ev, th);
    let mut first: Option<(f64, Event)> = None;
    let mut parting = None;
    // The held springs' switch, located once: the parting's search reads it before its turn.
    let springs = std::cell::OnceCell::new();
    let springs_in = || {
        *springs.get_or_init(|| {
            let precision = ode.switch_precision(Event::Springs);
            switch_in(|th| g(Event::Springs, th), precision)
        })
    };
    for ev in ode.candidates(m) {
        let tangential = matches!(ev, Event::ToSlip | Event::ToStick);
        if ((ignored.tangential || firm) && tangential) || (ignored.clip && ev == Event::ClipOff) {
            continue;
        }
        let precision = ode.switch_precision(ev);
        let found = if tangential {
            tangential_switch_in(|th| g(ev, th), precision).map(|th| (th, th))
        } else if ev == Event::Springs {
            springs_in()
        } else if ev == Event::Separate && ode.geometry.holds_springs() {
            parting_in(|th| g(ev, th), springs_in, precision)
        } else {
            switch_in(|th| g(ev, th), precision)
        };
        let Some((inside, th)) = found else {
            continue;
        };
        if ev == Event::Separate {
            parting = Some(inside);
        }
        if first.is_none_or(|(best, _)| th < best) {
            first = Some((th, ev));
        }
    }
    // In contact and unclipped, the clip switching on is a candidate (`PairOde::candidates`).
    let clip = parting
        .filter(|_| !m.clipped)
        .and_then(|inside| {
            let precision = ode.switch_precision(Event::ClipOn);
            before_parting(|th| g(Event::ClipOn, th), inside, precision)
        })
        .map(|th| (th, Event::ClipOn));
    // A stuck spring's cone closes with the normal force as the bodies part, so a stick
    // ends in a slip just before the parting; past it no overlap is left and the slip's
    // function says nothing, so the samples of the step cannot show that slip.
    let slip = parting
        .filter(|_| m.tan == Tan::Stick && !ignored.tangential)
        .and_then(|inside| {
            let precision = ode.switch_precision(Event::ToSlip);
            before_parting(|th| g(Event::ToSlip, th), inside, precision)
        })
        .map(|th| (th, Event::ToSlip));
    [first, clip, slip]
        .into_iter()
        .flatten()
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

/// Where the damped law's pull sets in before the bodies part at `inside` (the last point of
/// the step still in contact), `g` the clip's event function: the pull lasts up to the
/// parting, but past it no overlap, and no force, is left, so the step's end cannot show it.
/// Sampled towards the parting, densest there (the linear law pulls for c_n / k_n before it).
fn before_parting(g: impl Fn(f64) -> f64, inside: f64, precision: f64) -> Option<f64> {
    let at = (1..=24).map(|k| (inside * (1.0 - 0.5f64.powi(k)), None));
    let ((lo, g_lo), after) = first_positive_sample(&g, at)?;
    let g_lo = g_lo.unwrap_or_else(|| g(lo));
    Some(locate_switch(&g, (lo, g_lo), after, precision).1)
}

/// Where a stick -> slip or slip -> stick function `g` first fires inside the step: sampled
/// at thirds of it and between them where it may peak above zero (the plate's rule,
/// [`sampled_first_switch`]), for a stick or slip phase may begin and end inside one step.
/// Tested at the step's end only, a slip phase the shrinking cone forced at the start of a
/// stick step and that ended before its end went unseen (a triangle on a 24-gon at mu 1.6,
/// spinning: stuck one step early, 1.6e-5 to 6.1e-5 off at tol 1e-6 to 1e-8).
fn tangential_switch_in(g: impl Fn(f64) -> f64, precision: f64) -> Option<f64> {
    let locate = |(lo, g_lo): (f64, Option<f64>), hi: (f64, f64)| {
        let g_lo = g_lo.unwrap_or_else(|| g(lo));
        locate_switch(&g, (lo, g_lo), hi, precision).1
    };
    sampled_first_switch(TANGENTIAL_PARTS, &g, (|| g(0.0), g(1.0)), locate)
}

/// The parting of bodies whose overlap the held springs follow, `g` the separation's
/// function (-depth in contact, the gap past it): [`switch_in`] in a bracket from the held
/// springs' switch in the step (`springs`, located for its own sake), where there is one past
/// the parting. The overlap of two convex bodies closes to a corner on the other body's edge,
/// and there the held crossings reach that corner: the springs' switch fires a margin of
/// 1e-9 of an edge after the parting (twin 120-gons: 2.2e-9 of the step). Located on the
/// whole step, the depth inside and the gap past meet at a kink (slopes 1.84e-5 and 1.28e-5
/// per unit of the step there), so Brent's iterates closed in from past the parting, six of
/// its ten evaluations measuring the gap (~20k instructions each, places and scans every
/// corner); from the springs' switch one gap is measured, and the bracket widened towards
/// the start from the precision sixteenfold, three times at most, until it holds the parting
/// (in contact: the held overlap's depth, cheap), else from the start. Without such a switch,
/// or where the depth there is not past the parting, the whole step as [`switch_in`].
fn parting_in(
    g: impl Fn(f64) -> f64,
    springs: impl FnOnce() -> Option<(f64, f64)>,
    precision: f64,
) -> Option<(f64, f64)> {
    let g1 = g(1.0);
    if !(g1 > 0.0) {
        return None;
    }
    let whole = || Some(locate_switch(&g, (0.0, g(0.0)), (1.0, g1), precision));
    let Some((near, _)) = springs().filter(|&(near, _)| near > 0.0 && near < 1.0) else {
        return whole();
    };
    let g_near = g(near);
    if !(g_near > 0.0) {
        return whole();
    }
    let (mut past, mut g_past, mut width) = (near, g_near, precision);
    for _ in 0..3 {
        let th = past - width;
        if th <= 0.0 {
            break;
        }
        let value = g(th);
        if !(value > 0.0) {
            return Some(locate_switch(&g, (th, value), (past, g_past), precision));
        }
        (past, g_past, width) = (th, value, 16.0 * width);
    }
    Some(locate_switch(&g, (0.0, g(0.0)), (past, g_past), precision))
}

/// The bracket (inside, past) of the first change of sign of `g` on the step, `g` > 0
/// meaning the switch fired, located to `precision` of the step; `None` where `g(1)` has not
/// fired.
fn switch_in(g: impl Fn(f64) -> f64, precision: f64) -> Option<(f64, f64)> {
    let g1 = g(1.0);
    if !(g1 > 0.0) {
        return None;
    }
    Some(locate_switch(&g, (0.0, g(0.0)), (1.0, g1), precision))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    /// A separation function with a kink at the parting `r`: -depth inside (slope `inside`),
    /// the gap past it (slope `past`), as two 120-gons' at their parting; counts the
    /// evaluations past the parting (each measures the gap).
    fn kinked(r: f64, (inside, past): (f64, f64), gaps: &Cell<u32>) -> impl Fn(f64) -> f64 + '_ {
        move |th: f64| {
            if th < r {
                -inside * (r - th)
            } else {
                gaps.set(gaps.get() + 1);
                past * (th - r)
            }
        }
    }

    /// The parting from the held springs' switch just past it is the same parting, to the
    /// precision, as on the whole step, with no more gaps measured (fewer where the depth
    /// falls faster than the gap grows, as at two 120-gons' parting); from a switch far past
    /// it (three widenings, then from the start) the same at four gaps more at most; without
    /// a switch, or with one before the parting, the whole step's bracket bit for bit.
    #[test]
    fn the_parting_from_the_springs_switch_is_the_whole_steps() {
        let precision = 1e-9;
        for (r, slopes) in [
            (0.18847012144751962, (1.84e-5, 1.28e-5)),
            (0.5, (1.28e-5, 1.84e-5)),
            (0.93, (3.0, 0.01)),
        ] {
            let (hinted, whole) = (Cell::new(0), Cell::new(0));
            let after = Some((r + 2.2e-9, r + 2.3e-9));
            let (a, b) = parting_in(kinked(r, slopes, &hinted), || after, precision).unwrap();
            let (wa, wb) = switch_in(kinked(r, slopes, &whole), precision).unwrap();
            let parted = |(lo, hi): (f64, f64)| lo <= r && r < hi && hi - lo <= precision;
            assert!(
                parted((a, b)) && parted((wa, wb)),
                "{r}: {a} {b}, {wa} {wb}"
            );
            assert!(hinted.get() <= whole.get(), "{r}: {hinted:?} {whole:?}");
            if slopes.0 > slopes.1 {
                assert!(hinted.get() < whole.get(), "{r}: {hinted:?} {whole:?}");
            }
            // Far past the parting: three widenings, then from the start.
            let far = Some((r + 0.5 * (1.0 - r), 1.0));
            hinted.set(0);
            let (a, b) = parting_in(kinked(r, slopes, &hinted), || far, precision).unwrap();
            assert!(parted((a, b)), "{r}: {a} {b}");
            assert!(hinted.get() <= whole.get() + 4, "{r}: {hinted:?} {whole:?}");
            for no_use in [None, Some((0.5 * r, 0.6 * r))] {
                let g = kinked(r, slopes, &hinted);
                let bits = |(a, b): (f64, f64)| (a.to_bits(), b.to_bits());
                assert_eq!(
                    parting_in(&g, || no_use, precision).map(bits),
                    switch_in(&g, precision).map(bits)
                );
            }
        }
        // Still in contact at the step's end: no parting.
        let gaps = Cell::new(0);
        let g = kinked(1.5, (1.0, 1.0), &gaps);
        assert_eq!(parting_in(g, || Some((0.5, 0.6)), precision), None);
    }
}
