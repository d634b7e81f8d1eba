//! The mode of a piece: which overlap formula, clip state and tangential law hold, the
//! mode a contact starts in, and the switch of mode at an event (with the algebraic part of
//! the state it implies).

use super::law::{Eval, Reference};
use super::piece::{Event, Mode, Tally, Tan, Touch};
use super::{State, PHI, XI, Y};
use crate::geometry::Shape;
use crate::law::carrying;
use crate::numerics::trig::sin_cos;

impl Reference<'_> {
    /// The overlap formula a contact starts with at centre height `y`, orientation `phi`.
    pub(super) fn touch_mode(&self, y: f64, phi: f64) -> Touch {
        match self.model.scene.shape {
            Shape::Disc { .. } | Shape::Sphere { .. } => Touch::Disc,
            Shape::Polygon(_) => self.initial_run(y, phi),
        }
    }

    /// The corners below the plate when a polygon first touches: the lowest one and its
    /// neighbours that are not above the plate.
    pub(super) fn initial_run(&self, y: f64, phi: f64) -> Touch {
        let n = self.verts.len();
        let sc = sin_cos(phi);
        let yk = |k: usize| self.corner(k, y, sc).1;
        let low = (0..n).min_by(|&i, &j| yk(i).total_cmp(&yk(j))).unwrap_or(0);
        let (mut first, mut len) = (low, 1);
        while len + 2 < n && yk(first + n - 1) <= 0.0 {
            first = (first + n - 1) % n;
            len += 1;
        }
        while len + 2 < n && yk(first + len) <= 0.0 {
            len += 1;
        }
        Touch::Poly { first, len, low }
    }

    /// The tangential mode when the normal force (re)appears: stick if the spring's trial
    /// force is inside the cone, else slip in its direction. A wrong guess (both zero at first
    /// touch) is corrected by the events at once.
    pub(super) fn initial_tan(&self, m: &Mode, s: &State) -> Tan {
        if self.mu == 0.0 {
            return Tan::None;
        }
        let probe = Mode {
            tan: Tan::Stick,
            ..*m
        };
        let e = self.eval(&probe, s).1;
        let cap = self.mu * e.forces.fy.max(0.0);
        if e.trial.abs() <= cap {
            Tan::Stick
        } else {
            Tan::Slip(e.trial.signum())
        }
    }
}

/// Switches the mode at an event and sets the algebraic part of the state. `known`: the
/// evaluation at `s` in the mode before the switch, where the caller has it (the last stage of
/// the step that ends there); only the tangential switches and the clip's switching off read
/// it, and evaluate it themselves where it is not known (a corner entering or leaving, a
/// polygon's most frequent switches, evaluated it for nothing). Out of line: a few calls per
/// impact, where inlined into the loop of steps it cost every step instructions.
#[inline(never)]
pub(super) fn apply(
    ode: &Reference,
    m: &mut Mode,
    ev: Event,
    s: &mut State,
    (t, known): (f64, Option<&Eval>),
    tally: &mut Tally,
) {
    let n = ode.verts.len().max(1);
    let before = |m: &Mode, s: &State| known.copied().unwrap_or_else(|| ode.eval(m, s).1);
    match ev {
        Event::Touch => {
            m.touch = ode.touch_mode(s[Y], s[PHI]);
            m.clip_on = true;
            m.unloading = false;
            s[XI] = 0.0;
            m.tan = ode.initial_tan(m, s);
            tally.contacts += 1;
            tally.contact_start = t;
            tally.stuck = false;
        }
        Event::Separate => separate(m, s, t, tally),
        Event::EnterLeft | Event::EnterRight | Event::LeaveLeft | Event::LeaveRight => {
            if let Touch::Poly { first, len, low } = m.touch {
                let (first, len) = match ev {
                    Event::EnterLeft => ((first + n - 1) % n, len + 1),
                    Event::EnterRight => (first, len + 1),
                    Event::LeaveLeft => ((first + 1) % n, len - 1),
                    _ => (first, len - 1),
                };
                if len == 0 {
                    separate(m, s, t, tally);
                } else {
                    // Keep the lowest corner inside the run.
                    let inside = (low + n - first) % n < len;
                    let low = if inside { low } else { first };
                    m.touch = Touch::Poly { first, len, low };
                }
            }
        }
        Event::ClipOff => {
            if ode.mu > 0.0 {
                let e = before(m, s);
                let (kt, _, ct) = ode.model.spring(e.depth);
                m.tan = Tan::Free;
                s[XI] = carrying(0.0, kt, ct, e.v_t);
            }
            m.clip_on = false;
        }
        Event::ClipOn => {
            m.clip_on = true;
            m.tan = ode.initial_tan(m, s);
        }
        Event::ToSlip => {
            start_slip(ode, m, s, &before(m, s));
            if tally.stuck {
                tally.slip_events += 1;
            }
        }
        Event::ToStick => {
            // The spring takes over the force it carried while slipping.
            let e = before(m, s);
            let (kt, _, ct) = ode.model.spring(e.depth);
            s[XI] = carrying(e.forces.f_t, kt, ct, e.v_t);
            m.tan = Tan::Stick;
        }
        Event::Unload => m.unloading = true,
    }
}

/// Slip in the direction of the trial force (against the slip velocity where it is zero);
/// the spring follows algebraically. `e` is the evaluation at `s` in the stick mode.
pub(super) fn start_slip(ode: &Reference, m: &mut Mode, s: &mut State, e: &Eval) {
    let (kt, _, ct) = ode.model.spring(e.depth);
    let sg = if e.trial != 0.0 {
        e.trial.signum()
    } else {
        -e.v_t.signum()
    };
    m.tan = Tan::Slip(sg);
    s[XI] = carrying(ode.mu * e.forces.fy * sg, kt, ct, e.v_t);
}

fn separate(m: &mut Mode, s: &mut State, t: f64, tally: &mut Tally) {
    m.touch = Touch::Off;
    m.clip_on = false;
    m.tan = Tan::None;
    s[XI] = 0.0;
    tally.contact_time += t - tally.contact_start;
}
