//! Where a piece of the pair's adaptive path ends (docs/model.md, 17.5 and 17.8): the first
//! switch inside an accepted step, located on the step's dense output by Brent's method; stick
//! and slip also sampled inside the step, by the plate's rule.

use super::law::PairOde;
use super::piece::{Event, Mode, Tan, NS};
use crate::geometry::pair::PairGeometry;
use crate::impact::adaptive::{
    first_positive_sample, locate_switch, sampled_first_switch, TANGENTIAL_PARTS,
};
use crate::integrate::dopri::DenseStep;

/// To what fraction of its step a switch is located.
pub(super) const SWITCH_PRECISION: f64 = 1e-12;

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

/// The first switch of mode `m` inside the accepted `step`: (fraction of the step, event),
/// the `ignored` switches left out.
pub(super) fn first_switch<G: PairGeometry>(
    ode: &PairOde<'_, G>,
    m: &Mode,
    step: &DenseStep<NS, NS>,
    ignored: Ignored,
) -> Option<(f64, Event)> {
    if ignored.all {
        return None;
    }
    let g = |ev: Event, th: f64| ode.event_value(m, ev, &step.at(th));
    let mut first: Option<(f64, Event)> = None;
    let mut parting = None;
    for ev in ode.candidates(m) {
        let tangential = matches!(ev, Event::ToSlip | Event::ToStick);
        if (ignored.tangential && tangential) || (ignored.clip && ev == Event::ClipOff) {
            continue;
        }
        let found = if matches!(ev, Event::ToSlip | Event::ToStick) {
            tangential_switch_in(|th| g(ev, th)).map(|th| (th, th))
        } else {
            switch_in(|th| g(ev, th), 1.0)
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
        .and_then(|inside| before_parting(|th| g(Event::ClipOn, th), inside))
        .map(|th| (th, Event::ClipOn));
    // A stuck spring's cone closes with the normal force as the bodies part, so a stick
    // ends in a slip just before the parting; past it no overlap is left and the slip's
    // function says nothing, so the samples of the step cannot show that slip.
    let slip = parting
        .filter(|_| m.tan == Tan::Stick && !ignored.tangential)
        .and_then(|inside| before_parting(|th| g(Event::ToSlip, th), inside))
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
fn before_parting(g: impl Fn(f64) -> f64, inside: f64) -> Option<f64> {
    let at = (1..=24).map(|k| (inside * (1.0 - 0.5f64.powi(k)), None));
    let ((lo, g_lo), after) = first_positive_sample(&g, at)?;
    let g_lo = g_lo.unwrap_or_else(|| g(lo));
    Some(locate_switch(&g, (lo, g_lo), after, SWITCH_PRECISION).1)
}

/// Where a stick -> slip or slip -> stick function `g` first fires inside the step: sampled
/// at thirds of it and between them where it may peak above zero (the plate's rule,
/// [`sampled_first_switch`]), for a stick or slip phase may begin and end inside one step.
/// Tested at the step's end only, a slip phase the shrinking cone forced at the start of a
/// stick step and that ended before its end went unseen (a triangle on a 24-gon at mu 1.6,
/// spinning: stuck one step early, 1.6e-5 to 6.1e-5 off at tol 1e-6 to 1e-8).
fn tangential_switch_in(g: impl Fn(f64) -> f64) -> Option<f64> {
    let locate = |(lo, g_lo): (f64, Option<f64>), hi: (f64, f64)| {
        let g_lo = g_lo.unwrap_or_else(|| g(lo));
        locate_switch(&g, (lo, g_lo), hi, SWITCH_PRECISION).1
    };
    sampled_first_switch(TANGENTIAL_PARTS, &g, (|| g(0.0), g(1.0)), locate)
}

/// The bracket (inside, past) of the first change of sign of `g` on [0, `end`], `g` > 0
/// meaning the switch fired; `None` where `g(end)` has not fired.
fn switch_in(g: impl Fn(f64) -> f64, end: f64) -> Option<(f64, f64)> {
    let g1 = g(end);
    if !(g1 > 0.0) {
        return None;
    }
    Some(locate_switch(
        &g,
        (0.0, g(0.0)),
        (end, g1),
        SWITCH_PRECISION,
    ))
}
