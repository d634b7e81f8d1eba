//! Where inside an accepted step the first switch fires: each candidate event's function at
//! the step's ends, and, where a function may fire and clear again inside the step (stick and
//! slip grazing the Coulomb cone), samples between them; the root itself is located by
//! `Reference::locate` (`events.rs`).

use super::law::{Eval, Reference};
use super::piece::{Event, Mode, Tan, Touch};
use super::stages::LinearSlip;
use super::step::Step;
use super::{State, OM, VY};
use crate::numerics::roots;

impl Reference<'_> {
    /// The fraction of `step` at which event `ev` first fires, if it does inside the step;
    /// `start` is the derivative and evaluation at the step's start.
    pub(super) fn switch_in(
        &self,
        m: &Mode,
        ev: Event,
        step: &Step,
        start: (&State, &Eval),
    ) -> Option<f64> {
        let g1 = self.event_value_given(m, ev, &step.y1, Some((&step.k_end(), &step.end)));
        if ev == Event::ToSlip && g1 <= 0.0 && self.stays_stuck(m, step, start) {
            return None;
        }
        if ev == Event::ToStick && g1 <= 0.0 && self.stays_slipping(m, step, start.1) {
            return None;
        }
        let entering = matches!(ev, Event::EnterLeft | Event::EnterRight);
        if entering && g1 <= 0.0 && self.stays_up(m, ev, step, (-g1, start.0)) {
            return None;
        }
        if let Some(parts) = interior_samples(ev) {
            // A corner may dip below the plate and rise again within one step (a grazing
            // corner beside the chord), a short stick phase may begin and end within one (the
            // disc at theta 54, mu 0.7 at tol 1e-6 missed one: e_T off by 2e-4): look inside
            // the step too, also when the event fires at its end, so that the first switch is
            // the one found (located on all of the step, a 120-gon's stick -> slip at 0.8913
            // t_c gave way to the one at 0.9016 in the same step, and its short slip phase
            // between was lost: e_T off by 1.8e-6 at tol 1e-6).
            let g0 = || self.event_value_given(m, ev, &step.y0, Some(start));
            self.sampled_switch(m, ev, step, parts, (g0, g1))
        } else if g1 > 0.0 {
            Some(self.locate(m, ev, step, g1))
        } else if let (Event::ClipOff, Some(c)) = (ev, step.pull) {
            // A stage saw the plate pull although the end state does not: the clip
            // switched inside the step (and back, in the held continuation); find
            // where, on the dense output up to that stage.
            let at = (1..=16).map(|k| (c * k as f64 / 16.0, None));
            self.first_sampled(m, ev, step, at)
        } else {
            None
        }
    }

    /// Whether a stick step stays inside the Coulomb cone by more than its event function
    /// varies over the step's stages ([`super::stages::TangentialStages::stays_stuck`]): two
    /// evaluations per stick step skipped, where the stages' own evaluations already give the
    /// function at seven points.
    fn stays_stuck(&self, m: &Mode, step: &Step, start: (&State, &Eval)) -> bool {
        let g0 = self.event_value_given(m, Event::ToSlip, &step.y0, Some(start));
        step.tangential.stays_stuck(g0)
    }

    /// Whether a slip step keeps slipping by a wide margin, from the stages' normal forces and
    /// tangential velocities alone ([`super::stages::TangentialStages::stays_slipping`], linear
    /// spring): its two evaluations of the law (with the rates: two more off the disc) are
    /// skipped.
    fn stays_slipping(&self, m: &Mode, step: &Step, start: &Eval) -> bool {
        let Tan::Slip(sg) = m.tan else {
            return false;
        };
        if self.model.mindlin {
            return false;
        }
        let (k_t, _, c_t) = self.model.spring(0.0);
        let spring = LinearSlip {
            mu: self.mu,
            k_t,
            c_t,
        };
        let start = (start.forces.fy, start.v_t);
        step.tangential
            .stays_slipping(sg, start, step.h_len(), spring)
    }

    /// Whether the corner next to the run that event `ev` watches stays above the plate through
    /// `step`, from its height at the step's ends (`height_end` at the end) and the bound
    /// M h^2 / 8 on how far a function whose second derivative is bounded by M falls below the
    /// chord between its ends. The corner's height has the second derivative
    /// a_y + alpha x - omega^2 y (x, y its place from the centre), bounded by
    /// |a_y| + (|alpha| + omega^2) |v_k|: M is twice the larger of that at the step's two ends
    /// (`k1` the derivative at its start), for the accelerations' change inside the step.
    /// Then no sample inside can find the corner below the plate, and its eight samples (with
    /// a sine and cosine each, a third of the 120-gon's time) are skipped.
    fn stays_up(&self, m: &Mode, ev: Event, step: &Step, (height_end, k1): (f64, &State)) -> bool {
        let Touch::Poly { first, len, .. } = m.touch else {
            return false;
        };
        let n = self.verts.len();
        let k = if ev == Event::EnterLeft {
            first + n - 1
        } else {
            first + len
        };
        let arm = self.verts[k % n].norm();
        let curvature = |d: &State, s: &State| d[VY].abs() + (d[OM].abs() + s[OM] * s[OM]) * arm;
        let bound = 2.0 * curvature(k1, &step.y0).max(curvature(&step.k_end(), &step.y1));
        let height_start = -self.event_value(m, ev, &step.y0);
        let h = step.h_len();
        height_start.min(height_end) > 0.125 * bound * h * h
    }

    /// The first switch of `ev` inside `step` from its function sampled at `parts` equal
    /// parts ([`sampled_first_switch`]; `g0` its value at the start, computed only when needed: off
    /// the disc the slip -> stick test differences two more evaluations of the law; `g1` at the
    /// end), located on the dense output.
    fn sampled_switch(
        &self,
        m: &Mode,
        ev: Event,
        step: &Step,
        parts: usize,
        (g0, g1): (impl Fn() -> f64, f64),
    ) -> Option<f64> {
        sampled_first_switch(
            parts,
            |th| self.value_at(m, ev, step, th),
            (g0, g1),
            |before, after| self.locate_in(m, ev, step, before, after),
        )
    }

    /// Whether `ev` ends the contact: the disc separates or the last submerged corner leaves
    /// (a corner that leaves others submerged leaves the held formulas a contact past its leave
    /// point, whose clip the step's end shows; sampled for every leave, the clip's function
    /// cost the 120-gon a tenth of its evaluations).
    pub(super) fn ends_contact(&self, m: &Mode, ev: Event) -> bool {
        match (ev, m.touch) {
            (Event::Separate, _) => true,
            (Event::LeaveLeft, Touch::Poly { len, .. }) => len == 1,
            _ => false,
        }
    }

    /// A clip switch before the contact ends (the last corner leaves or the disc separates) at `th`
    /// of `step`. With damping the force pulls in the last stretch before a corner leaves (F =
    /// delta times (k delta + c delta') < 0 as delta -> 0 while it falls), so the clip switches off
    /// there; the check at the step's end cannot see it, since past the leave point the held
    /// formulas are no contact (a corner's area grows again like depth^2 above the plate): a step
    /// of 2 t_ref once crossed the pulling tail unclipped (the 12-gon at theta 74, mu 0.5: e_N off
    /// by 4e-5). Sampled on the dense output, densest towards the leave point.
    pub(super) fn clip_before_leaving(
        &self,
        m: &Mode,
        step: &Step,
        th: f64,
    ) -> Option<(f64, Event)> {
        if !m.clipped() || th <= 0.0 {
            return None;
        }
        const AT: [f64; 10] = [
            0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 0.9375, 0.96875, 0.984375,
        ];
        let at = AT.map(|f| (f * th, None));
        self.first_sampled(m, Event::ClipOff, step, at)
            .map(|at| (at, Event::ClipOff))
    }
}

/// The first switch of an event inside a step from its function `value` (of the fraction of
/// the step) sampled at `parts` equal parts (`g0` its value at the start, computed only when
/// needed; `g1` at the end): the first positive sample's, or, where every sample is negative,
/// one that fires and clears again between three samples around a local maximum (see
/// [`grazes`]): Brent's search for that maximum on the dense output. `locate` finds the root
/// between a point where the function has not fired (its value, if known) and one where it
/// has. The plate's and the pair's adaptive loops share it (a stick or slip phase shorter
/// than a step, inside it).
pub(crate) fn sampled_first_switch(
    parts: usize,
    value: impl Fn(f64) -> f64,
    (g0, g1): (impl Fn() -> f64, f64),
    locate: impl Fn((f64, Option<f64>), (f64, f64)) -> f64,
) -> Option<f64> {
    let w = 1.0 / parts as f64;
    let mut g = [0.0; MAX_PARTS + 1];
    for k in 1..=parts {
        g[k] = if k == parts { g1 } else { value(k as f64 * w) };
        if g[k] > 0.0 {
            let before = if k == 1 { g0() } else { g[k - 1] };
            let before = ((k - 1) as f64 * w, Some(before));
            return Some(locate(before, (k as f64 * w, g[k])));
        }
    }
    // A peak between the start and the first sample shows only with the start's value:
    // the function falls from the first sample to the second.
    let first = if g[1] >= g[2] {
        g[0] = g0();
        0
    } else {
        1
    };
    let k = first + grazes(&g[first..=parts])?;
    let positive = std::cell::Cell::new(None);
    let (lo, hi) = ((k - 1) as f64 * w, (k + 1) as f64 * w);
    roots::peak(
        |th| {
            let v = value(th);
            if v > 0.0 && positive.get().is_none() {
                positive.set(Some((th, v)));
            }
            v
        },
        (lo, hi),
        g[k],
        1e-6 * w,
    );
    let (th, v) = positive.get()?;
    // The root before the positive point (the samples left of it are negative).
    let from = if th < k as f64 * w {
        (lo, g[k - 1])
    } else {
        (k as f64 * w, g[k])
    };
    Some(locate((from.0, Some(from.1)), (th, v)))
}

/// Where an event function `g` of the fraction of a step (> 0 once its switch fired) first
/// turns positive between `lo`, where it has not fired (`g_lo` its value there), and `hi`,
/// where it has (`g_hi`), to `precision` of the step (Brent's method): the last point before
/// the switch and the first past it, which starts the next piece; both `lo` where the switch
/// had fired there already. Every located switch, on the plate and on a pair.
pub(crate) fn locate_switch(
    g: impl Fn(f64) -> f64,
    (lo, g_lo): (f64, f64),
    (hi, g_hi): (f64, f64),
    precision: f64,
) -> (f64, f64) {
    if g_lo > 0.0 {
        return (lo, lo);
    }
    roots::bracket(g, (lo, g_lo), (hi, g_hi), precision)
}

/// A fraction of a step where an event function is sampled, with its value there when known.
pub(crate) type Sample = (f64, Option<f64>);

/// The first of the increasing fractions `at` of a step (each with the event function's value
/// where already known) where `g` is positive, and the sample before it (the step's start,
/// value unknown, before the first): the bracket of the first switch among the samples, each
/// value computed once.
pub(crate) fn first_positive_sample(
    g: impl Fn(f64) -> f64,
    at: impl IntoIterator<Item = Sample>,
) -> Option<(Sample, (f64, f64))> {
    let mut before = (0.0, None);
    for (th, known) in at {
        let value = known.unwrap_or_else(|| g(th));
        if value > 0.0 {
            return Some((before, (th, value)));
        }
        before = (th, Some(value));
    }
    None
}

/// To what fraction of its step a switch is located, on the plate and on a pair, at local
/// tolerance `local_tol`; `jumps` where the force jumps at the switch. The other switches leave
/// the forces continuous, so one late by delta errs like delta^2: the local tolerance itself
/// (within [1e-10, 1e-6]) leaves ~tol^2. Only the linear law's dashpot jumps where a contact
/// starts (touch, a corner entering: by c_n v), an error like delta: those to 1e-10 of the
/// step, as every switch of the reference (1e-14 moved the plate's records by <= 2e-12 for ~5
/// more evaluations per switch; 1e-6 instead of 1e-10 saves ~3 % of the adaptive path's time
/// on the disc at tol 1e-6).
pub(crate) fn switch_precision(local_tol: f64, jumps: bool) -> f64 {
    if jumps {
        1e-10
    } else {
        local_tol.clamp(1e-10, 1e-6)
    }
}

/// Into how many parts a step is cut to look for a stick or slip phase inside it (see
/// [`interior_samples`]), on the plate and on a pair.
pub(crate) const TANGENTIAL_PARTS: usize = 3;

/// The most parts [`interior_samples`] cuts a step into.
const MAX_PARTS: usize = 8;

/// The sample around which a function sampled at equal steps, negative at every sample, may
/// still rise above zero: the middle of three consecutive samples whose parabola is concave
/// with its vertex between the outer two and peaks above minus the largest third difference of
/// the samples (the size of the cubic term the parabola leaves out). A stick phase grazing the
/// Coulomb cone for a tenth of a step lies between quarter samples (the disc at theta 54,
/// mu 0.7, gamma_t 0: a slip phase of 0.055 t_ref missed inside a step of 0.54 t_ref, e_T off
/// by 1.5e-4 at tol 1e-4), and so may one that starts with the step (the 120-gon at theta 89,
/// mu 0.7, gamma_t 0 slips for 0.04 t_ref from touch, where the function starts at zero).
fn grazes(g: &[f64]) -> Option<usize> {
    // The third differences only where a parabola peaks inside but below zero (this runs for
    // every sampled event of every step, and peaks near zero are rare).
    // Event functions are -inf where their switch cannot happen (a disc's slip -> stick test
    // beyond separation): no parabola through those.
    let cubic = || {
        g.windows(4)
            .map(|q| (q[3] - 3.0 * q[2] + 3.0 * q[1] - q[0]).abs())
            .filter(|d| d.is_finite())
            .fold(0.0, f64::max)
    };
    (1..g.len() - 1).find(|&k| {
        let (a, b, c) = (g[k - 1], g[k], g[k + 1]);
        if !(a.is_finite() && b.is_finite() && c.is_finite()) {
            return false;
        }
        let curv = 2.0 * b - a - c;
        // The vertex lies (c - a) / (2 curv) sample spacings from the middle sample.
        if !(curv > 0.0 && (c - a).abs() <= 2.0 * curv) {
            return false;
        }
        let top = b + (c - a) * (c - a) / (8.0 * curv);
        top > 0.0 || top + cubic() > 0.0
    })
}

/// Into how many parts a step is cut to look for an event that may fire and clear again
/// inside it (its function positive only in the middle), or `None` for events whose function
/// is monotone over a step.
///
/// Stick/slip: thirds, the fewest whose four values give [`grazes`] a third difference (with
/// halves the disc at theta 54, mu 0.7, gamma_t 0 lost its short slip phase again; quarters
/// found the same switches over the full adaptive grid at one evaluation more per step).
fn interior_samples(ev: Event) -> Option<usize> {
    match ev {
        Event::EnterLeft | Event::EnterRight | Event::Touch => Some(8),
        Event::ToStick | Event::ToSlip => Some(TANGENTIAL_PARTS),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `grazes` finds a peak above zero between negative samples (of a parabola, exactly), and
    /// none where the function stays below zero, is monotone, or is -inf at a sample.
    #[test]
    fn grazes_flags_a_peak_above_zero_between_negative_samples() {
        let at = |f: &dyn Fn(f64) -> f64, parts: usize| -> Vec<f64> {
            (0..=parts).map(|k| f(k as f64 / parts as f64)).collect()
        };
        // Positive only on (0.47, 0.53): every third is negative.
        let graze = |t: f64| 1e-3 - (t - 0.5) * (t - 0.5);
        let g = at(&graze, 3);
        assert!(g.iter().all(|&v| v < 0.0));
        assert!(grazes(&g).is_some());
        // The same peak 0.002 below zero, and a monotone function.
        assert_eq!(grazes(&at(&|t| graze(t) - 3e-3, 3)), None);
        assert_eq!(grazes(&at(&|t| -1.0 - t, 3)), None);
        // A slip -> stick test beyond separation is -inf: no parabola through it.
        assert_eq!(grazes(&[f64::NEG_INFINITY, -1.0, -0.5, -1.0]), None);
        // A peak just after a start at zero (a slip phase from touch): found from the parabola
        // through the start and the first two samples.
        let from_touch = |t: f64| t * (0.1 - t);
        let g = at(&from_touch, 3);
        assert!(g[1..].iter().all(|&v| v < 0.0) && g[0] == 0.0);
        assert_eq!(grazes(&g), Some(1));
    }
}
