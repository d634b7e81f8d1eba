//! The largest depth and overlap area of an impact, found inside the steps: on the dense output
//! where they peak between a step's ends (where the normal velocity turns: `turning_point`, on
//! the plate and on a pair).

use super::law::{Eval, Reference};
use super::piece::{Mode, Tally, Touch};
use super::step::Step;
use super::{State, OM, PHI, VX, VY, Y};
use crate::geometry::Overlap;
use crate::numerics::roots;

/// Updates the largest depth and area with their maxima inside the taken part of a step. A
/// polygon's: where its depth or its area stops growing inside the step (their rates at the
/// ends, below), a parabola through three samples and Brent's search on the dense output
/// find the peak; a disc's: see [`deepest_disc`].
///
/// `start` is the evaluation at the step's start; at its end, a whole step reuses the last
/// stage's.
pub(super) fn track_extremes(
    ode: &Reference,
    m: &Mode,
    step: &Step,
    frac: f64,
    tally: &mut Tally,
    start: &Eval,
) {
    match m.touch {
        Touch::Off => return,
        Touch::Disc => return deepest_disc(ode, step, frac, tally),
        Touch::Poly { .. } => {}
    }
    let of = |o: Option<Overlap>| o.map_or([0.0; 2], |o| [o.depth, o.area]);
    let (end_state, end) = if frac == 1.0 {
        (step.y1, step.end.forces.overlap)
    } else {
        let s = step.at(frac);
        (s, ode.overlap(m.touch, s[Y], s[PHI]))
    };
    let (g0, g1) = (
        rates(&step.y0, start.forces.overlap).map(|r| r > 0.0),
        rates(&end_state, end).map(|r| r > 0.0),
    );
    // Only the overlap where the peak is sought: the law's forces are not needed.
    let sample = |th: f64| {
        let s = step.at(th);
        of(ode.overlap(m.touch, s[Y], s[PHI]))
    };
    // Near its peak the value moves like the square of the distance to it: a position to
    // sqrt(tol) of the step leaves ~tol of the value's change over the step.
    let precision = ode.tol.sqrt().clamp(1e-8, 1e-4) * frac.max(1e-300);
    let mut ends = None;
    for (k, best) in [&mut tally.max_depth, &mut tally.max_area]
        .into_iter()
        .enumerate()
    {
        // A peak inside only where the value grows at the start and no longer at the end
        // (a step is short against the motion: no second turn inside it). Sampled at
        // mid-step on every step, the law cost the polygon an evaluation per step.
        let peaks_inside = g0[k] && !g1[k];
        if !peaks_inside {
            continue;
        }
        let ends =
            *ends.get_or_insert_with(|| [of(start.forces.overlap), sample(0.5 * frac), of(end)]);
        let f3 = [ends[0][k], ends[1][k], ends[2][k]];
        *best = best.max(peak(|th| sample(th)[k], f3, frac, precision));
    }
}

/// The rates of a held polygon's depth and overlap area at state `s` with overlap `o`
/// ([`Overlap::depth_rate`], [`Overlap::area_rate`]).
fn rates(s: &State, o: Option<Overlap>) -> [f64; 2] {
    let Some(o) = o else {
        return [0.0; 2];
    };
    let v = [s[VX], s[VY], s[OM]];
    [o.depth_rate(&v), o.area_rate(&v)]
}

/// [`track_extremes`] for a disc or sphere, whose depth is r - y and whose overlap grows with
/// it: both peak where v_y turns from falling to rising, located on the dense output without
/// evaluating the law (sampling the law at mid-step for a peak cost an evaluation per step).
fn deepest_disc(ode: &Reference, step: &Step, frac: f64, tally: &mut Tally) {
    if step.y0[VY] > 0.0 || (frac == 1.0 && step.y1[VY] <= 0.0) {
        return;
    }
    deepest_disc_inside(ode, step, frac, tally);
}

/// The part of [`deepest_disc`] for a step where v_y may turn (once per impact): kept out of
/// line, it costs the other steps nothing.
#[inline(never)]
fn deepest_disc_inside(ode: &Reference, step: &Step, frac: f64, tally: &mut Tally) {
    let v_y = |th: f64| step.component_at(th, VY);
    let v_end = if frac == 1.0 { step.y1[VY] } else { v_y(frac) };
    let Some(th) = turning_point(v_y, step.y0[VY], (frac, v_end)) else {
        return;
    };
    let s = step.at(th);
    // The shape's own overlap (the same as the held mode's while in contact): calling the
    // mode's here, out of line, cost the law's evaluation its inlining of it (10 % per step).
    if let Some(o) = ode.model.scene.shape.overlap(s[Y], s[PHI]) {
        tally.max_depth = tally.max_depth.max(o.depth);
        tally.max_area = tally.max_area.max(o.area);
    }
}

/// Where a rate that is not positive at a step's start (`start`) and positive at `frac` of it
/// (`end`) turns from falling to rising, located on the step's dense output (`rate` of the
/// fraction of the step): the deepest point of a contact, where the normal velocity turns, on
/// the plate and on a pair. Near its turn a depth moves like the square of the distance to it:
/// a position to 1e-10 of the step leaves nothing of the depth. `None` where it does not turn.
pub(crate) fn turning_point(
    rate: impl Fn(f64) -> f64,
    start: f64,
    (frac, end): (f64, f64),
) -> Option<f64> {
    (start <= 0.0 && end > 0.0)
        .then(|| roots::bracket(rate, (0.0, start), (frac, end), 1e-10 * frac).1)
}

/// Largest value of `f` on [0, frac] when it peaks inside, given its values at 0, frac / 2 and
/// frac; -inf otherwise (the ends are recorded as step ends).
fn peak(f: impl Fn(f64) -> f64, [f0, fm, f1]: [f64; 3], frac: f64, precision: f64) -> f64 {
    // Parabola through the three samples: concave with its vertex within the step (a little
    // margin, so that a peak just past a sample is not missed).
    let curv = f0 - 2.0 * fm + f1;
    if curv >= 0.0 {
        return f64::NEG_INFINITY;
    }
    let vertex = 0.5 + 0.25 * (f0 - f1) / curv;
    if !(-0.1..=1.1).contains(&vertex) {
        return f64::NEG_INFINITY;
    }
    roots::peak(f, (0.0, frac), fm, precision).max(f0).max(f1)
}
