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
//! particle can reach the plate again. A pair apart flies the same way (`Approach::of_pair`):
//! the plate is a partner of infinite mass, and the gap is the bodies' distance.

use crate::law::pair::Lanes;
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

/// How a flight approaches: the fastest rate at which the gap can close, and the time after
/// which it can never close again (0: it cannot now; infinite: no such time is known).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Approach {
    /// Bound on the closing rate of the gap (m/s).
    pub rate: f64,
    /// From this time (s) on no touch can come.
    pub t_clear: f64,
}

impl Approach {
    /// A particle on the plate at height `y` with velocity `v`: its lowest point approaches
    /// at most at |v_y| + arm |omega| (`r` the circumradius; `arm` bounds how fast the spin
    /// lowers the lowest point, |d touch_height / d phi| <= arm: r always,
    /// [`Shape::touch_arm`] at best); rising, once its circumscribed circle has cleared the
    /// plate it cannot come back.
    ///
    /// [`Shape::touch_arm`]: crate::geometry::Shape::touch_arm
    pub(crate) fn to_plate(y: f64, v: &Dof, (r, arm): (f64, f64)) -> Self {
        let t_clear = if v[1] >= 0.0 && y >= r {
            0.0
        } else if v[1] > 0.0 {
            (r - y) / v[1]
        } else {
            f64::INFINITY
        };
        Approach {
            rate: v[1].abs() + arm * v[2].abs(),
            t_clear,
        }
    }

    /// A pair apart at relative lanes (`q`, `v`) = ((x, y, phi1, phi2), (g_x, g_y, omega1,
    /// omega2)), `radii` the bodies' circumradii: no two points close faster than
    /// |g| + |omega1| R1 + |omega2| R2, and once the circumscribed circles are apart and
    /// receding (after the later root of |q + g t| = R1 + R2) no point of them can meet again.
    pub(crate) fn of_pair(q: &Lanes, v: &Lanes, radii: [f64; 2]) -> Self {
        let reach = radii[0] + radii[1];
        let rate = v[0].hypot(v[1]) + v[2].abs() * radii[0] + v[3].abs() * radii[1];
        let (rg, g2, d2) = (
            q[0] * v[0] + q[1] * v[1],
            v[0] * v[0] + v[1] * v[1],
            q[0] * q[0] + q[1] * q[1],
        );
        let disc = rg * rg - g2 * (d2 - reach * reach);
        let t_clear = if g2 == 0.0 {
            // The centres at rest: apart for good if the circles are.
            if d2 >= reach * reach {
                0.0
            } else {
                f64::INFINITY
            }
        } else if disc < 0.0 {
            // The centres' line never brings the circles together.
            0.0
        } else {
            ((disc.sqrt() - rg) / g2).max(0.0)
        };
        Approach { rate, t_clear }
    }
}

/// Jumps a free flight (`gap(t)`: the gap after `t`, how far the bodies are from touching,
/// closing at most at `approach.rate`), at most `max_advances` advances of conservative
/// advancement; returns where it ends and the advances used. `dt` is the step the stepper
/// takes over with.
pub(crate) fn jump(
    gap: impl Fn(f64) -> f64,
    approach: Approach,
    dt: f64,
    max_advances: u64,
) -> (Jump, u64) {
    let Approach { rate, t_clear } = approach;
    let near = HANDOVER_STEPS * rate * dt;
    // Not approaching, and clear already (or no motion at all): nothing can ever touch.
    if rate == 0.0 || t_clear <= 0.0 {
        return (Jump::Clear(0.0), 0);
    }
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
