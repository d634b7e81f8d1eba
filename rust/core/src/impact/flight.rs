//! Free flight between contacts, jumped over instead of stepped.
//!
//! Between contacts no force acts and the motion is uniform: q(t) = q + v t. A spinning
//! polygon that leaves the plate slowly (a rocking triangle at v ~ 1e-6 m/s) used to be
//! stepped, at the contact's step, until its circumscribed circle cleared the plate or a
//! corner came back: up to 1e9 steps of nothing (issue 14). Here the flight advances by
//! conservative advancement: the lowest point of the particle approaches the plate at most at
//! |v_y| + r |omega|, so from a gap g it is safe to advance by (g - near / 2) / that rate. The
//! jump ends where the gap falls below `near` (a few steps of motion before a touch: the
//! stepper takes over and lands on the touch as at the start), or where no part of the
//! particle can reach the plate again.

use crate::law::Dof;

/// Gap at which the stepper takes over again, in steps of the fastest approach.
const HANDOVER_STEPS: f64 = 4.0;

/// Where a flight ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Jump {
    /// Too close to the plate already: step on.
    Stay,
    /// Continue stepping after this time (s), close to a touch.
    To(f64),
    /// After this time (s) no part of the particle can reach the plate: the impact is over.
    Clear(f64),
}

/// Jumps a free flight from height `y` with velocity `v` (`gap(t)`: the height of the lowest
/// point after `t`), at most `max_advances` advances; returns where it ends and the advances
/// used. `r` is the circumradius; `arm` bounds how fast the spin lowers the lowest point
/// (|d touch_height / d phi| <= arm: r always, [`Shape::touch_arm`] at best).
///
/// [`Shape::touch_arm`]: crate::geometry::Shape::touch_arm
pub(crate) fn jump(
    gap: impl Fn(f64) -> f64,
    y: f64,
    v: &Dof,
    (r, arm): (f64, f64),
    dt: f64,
    max_advances: u64,
) -> (Jump, u64) {
    let rate = v[1].abs() + arm * v[2].abs();
    let near = HANDOVER_STEPS * rate * dt;
    // Not approaching, and the circumscribed circle already clear (or no motion at all):
    // nothing can ever reach the plate.
    if rate == 0.0 || (v[1] >= 0.0 && y >= r) {
        return (Jump::Clear(0.0), 0);
    }
    // Rising: once the circumscribed circle has cleared the plate it cannot come back.
    let t_clear = if v[1] > 0.0 {
        (r - y) / v[1]
    } else {
        f64::INFINITY
    };
    let (mut t, mut g) = (0.0, gap(0.0));
    if !(g > near) {
        return (Jump::Stay, 0);
    }
    for k in 1..=max_advances {
        t += (g - 0.5 * near) / rate;
        if t >= t_clear {
            return (Jump::Clear(t_clear), k);
        }
        g = gap(t);
        if !(g > near) {
            return (Jump::To(t), k);
        }
    }
    (Jump::To(t), max_advances)
}
