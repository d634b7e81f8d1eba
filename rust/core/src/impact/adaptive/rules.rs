//! The rules of the adaptive path that do not depend on what the particle meets, written once
//! for the plate and for a pair (docs/model.md, 7.3 and 17.5): the step size controller, the
//! step and the error factor near a root singularity of the force (touch and separation), the
//! local errors accumulated into `err_est`, the state where a piece ends inside a step, and the
//! count of chattering switches with its constants.

use super::ERR_EST_FACTOR;
use crate::impact::record::{StopReason, TIMEOUT_CONTACT_TIMES};
use crate::integrate::dopri::{root_error_ratio, DenseStep};
use crate::model::{Initial, Model, NormalLaw};

/// What bounds one impact's integration, fixed at its start, on the plate and on a pair.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Limits {
    /// The largest step.
    pub(crate) h_max: f64,
    /// The estimated contact time.
    pub(crate) t_est: f64,
    /// The largest step across a point where the force is not smooth, t_est tol^(2/3)
    /// ([`singular_cap`]), fixed per impact.
    pub(crate) h_singular: f64,
    /// Stop once the contacts have lasted this long ([`TIMEOUT_CONTACT_TIMES`] contact times;
    /// free flight is jumped over and does not count, as for the fixed steps).
    pub(crate) t_end: f64,
    /// The step budget (attempts, rejected steps included): steps may be much shorter than
    /// h_max while a turning polygon brings corner after corner to the plate (counted in
    /// N_c), but an explicit method crawls through a damper much stiffer than the contact (a
    /// spinning triangle at gamma = 10 takes steps of 1e-7 t_ref): such scenes end as timed
    /// out.
    pub(crate) max_steps: u64,
    /// Pieces shorter than this are negligible (for chattering, [`Chatter::count`]).
    pub(crate) tiny: f64,
}

impl Limits {
    /// The limits of an impact whose contact is estimated to last `t_est`, with largest step
    /// `h_max`, local tolerance `tol` and step budget `max_steps`.
    pub(crate) fn new(t_est: f64, h_max: f64, tol: f64, max_steps: u64) -> Self {
        Limits {
            h_max,
            t_est,
            h_singular: t_est * tol.powf(2.0 / 3.0),
            t_end: TIMEOUT_CONTACT_TIMES * t_est,
            max_steps,
            tiny: NEGLIGIBLE_PIECE * t_est,
        }
    }

    /// The smallest step the controller tries ([`verdict`]).
    pub(crate) fn h_min(&self) -> f64 {
        1e-13 * self.t_est
    }

    /// The budget that is spent after `attempts` attempted steps and `contact_time` in
    /// contact, if one is.
    pub(crate) fn budget_spent(&self, attempts: u64, contact_time: f64) -> Option<StopReason> {
        if attempts >= self.max_steps {
            Some(StopReason::StepBudget)
        } else if contact_time >= self.t_end {
            Some(StopReason::ContactTimeBudget)
        } else {
            None
        }
    }
}

/// Smallest error scale of a velocity component, relative to the impact's speed.
const SCALE_FLOOR: f64 = 1e-3;

/// The error scales of the incident velocity's components and of a spin times its radius, the
/// scales the outputs are relative to (|vx| for e_T, |vy| for e_N, v for omega r), floored at
/// 1e-3 of the impact's `speed` (spins included): a component far below the others (a grazing
/// impact's v_y, a spinning body's v_x) cannot be followed to `tol` of itself in double
/// precision, and asking for it costs millions of steps (a triangle at 0.01 deg and 1e4 deg/s
/// took 3e7). Over the study's grid (theta >= 4 deg) no floor is reached.
pub(crate) fn velocity_scales(init: &Initial, speed: f64) -> [f64; 3] {
    let or_speed = |x: f64| x.clamp(SCALE_FLOOR * speed, speed);
    [
        or_speed(init.vx.abs()),
        or_speed(init.vy.abs()),
        or_speed(init.vx.hypot(init.vy)),
    ]
}

/// The error scale of the tangential spring's elongation on `model`'s contact at depth
/// `depth`, `v_scale` the tangential velocity's. In stick the spring and the contact point's
/// motion are one oscillator: an error of xi is worth one of the tangential velocity when
/// their energies match, (1/2) k_t xi^2 = (1/2) m_t v^2, with m_t = 1 / (1/m + r^2/I) the mass
/// the spring moves at the contact point and k_t its stiffness at the estimated largest depth.
/// (The force that moves v_x in t_c, the scale before, is 3 / (omega_t t_c) ~ 1/6 of that on
/// the paper's disc: it set 90 % of the steps in stick, finer than any output needed.)
/// Mindlin's xi kept as the force (section 14.4) is the elongation times k_t = rate. Without a
/// spring (k_t = 0) its elongation does not act: no error of it counts.
pub(crate) fn spring_scale(model: &Model, v_scale: f64, depth: f64) -> f64 {
    let m_t = 1.0 / (1.0 / model.mass + model.r * model.r / model.inertia);
    let (k_xi, rate, _) = model.spring(depth);
    let k_t = k_xi * rate;
    if k_t > 0.0 {
        v_scale * (m_t / k_t).sqrt() * rate
    } else {
        f64::INFINITY
    }
}

/// The step size controller's factor for a step with scaled error `err` (> 0; rejected above
/// 1): 0.9 err^(-1/5) within [0.2, 5]. Below 1.8e-4 that is 5 without the power (0.9
/// (1.8e-4)^(-1/5) = 5.04), which libm's pow, called at every step, made 4 % of a profile of
/// the adaptive path.
pub(crate) fn step_factor(err: f64) -> f64 {
    if err < 1.8e-4 {
        5.0
    } else {
        // In single precision: a step factor needs a few digits, and f64's powf was 6 % of the
        // disc's time (one per attempted step).
        (0.9 * f64::from((err as f32).powf(-0.2))).clamp(0.2, 5.0)
    }
}

/// What the controller makes of an attempted step of length `h` with scaled error `err`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Verdict {
    /// Taken; the next step proposed.
    Accept { h_next: f64 },
    /// Tried again with this step.
    Reject { h_retry: f64 },
    /// Not finite even at the smallest step: the impact stops with the last finite state.
    NonFinite,
}

/// The controller's verdict on a step of length `h` with scaled error `err`, `h_min` the
/// smallest step. Never accepts a non-finite state: it shrinks hard and retries, and gives up
/// only at the smallest step; a finite error above 1 is accepted only at the smallest step.
pub(crate) fn verdict(err: f64, h: f64, h_min: f64) -> Verdict {
    if !err.is_finite() {
        return if h > h_min {
            Verdict::Reject {
                h_retry: (0.1 * h).max(h_min),
            }
        } else {
            Verdict::NonFinite
        };
    }
    if err > 1.0 && h > h_min {
        return Verdict::Reject {
            h_retry: (h * step_factor(err)).max(h_min),
        };
    }
    Verdict::Accept {
        h_next: h * step_factor(err),
    }
}

/// The exponent p of the normal force's root singularity at touch and separation (the damping
/// grows like t^p from touch): 1/2 under the area law, 1/4 under Hertz's (the Tsuji dashpot);
/// `None` under the linear law, smooth there.
pub(crate) fn root_exponent(law: &NormalLaw) -> Option<f64> {
    match law {
        NormalLaw::Linear { .. } => None,
        NormalLaw::Hertz { .. } => Some(0.25),
        NormalLaw::Area => Some(0.5),
    }
}

/// The largest step near a point where the force is not smooth (touch and separation: the
/// area grows like depth^(3/2), the damping like depth^(1/2), so a step of h across such a
/// point errs like (h / t_c)^(3/2) in the velocity, unseen by the embedded estimate): the step
/// from touch (`from_touch`) is at most `h_singular` = t_c tol^(2/3), and towards separation
/// the steps halve the time left until it, `depth` closing at `rate` (> 0 while separating),
/// but are never shorter than `h_singular`. Infinite elsewhere.
pub(crate) fn singular_cap(from_touch: bool, (depth, rate): (f64, f64), h_singular: f64) -> f64 {
    if from_touch {
        return h_singular;
    }
    if rate > 0.0 && depth > 0.0 {
        (0.5 * depth / rate).max(h_singular)
    } else {
        f64::INFINITY
    }
}

/// Steps from touch, in units of the step, beyond which [`root_error_ratio`] is 1 (1.1 at
/// one step, 0.5 at two).
const ROOT_REACH: f64 = 2.0;

/// The factor on the embedded error estimate of a step across or near a point where the force
/// has a root singularity t^`p` (a step that starts within [`ROOT_REACH`] of its lengths after
/// touch, `rho` the time since touch in units of the step; a step ending on separation,
/// `separating`), which the embedded estimate understates ([`root_error_ratio`]); 1 for every
/// other step. It multiplies the error the step adds to `err_est`; the step is accepted by its
/// plain estimate, its length near touch being capped ([`singular_cap`]). (Redoing the first
/// four steps after touch as two halves and extrapolating their difference, as before, cost
/// 12 evaluations of the law per step, ~6 % of the disc's time at tol 1e-6, and covered fewer
/// of the grid's errors: >= 98.4 % against >= 99.9 %.)
pub(crate) fn singular_factor(p: f64, rho: Option<f64>, separating: bool) -> f64 {
    // Beyond a step's length from touch the embedded estimate no longer understates.
    let at_touch = rho
        .filter(|&rho| rho < ROOT_REACH)
        .map_or(1.0, |rho| root_error_ratio(p, rho, false));
    let at_separation = if separating {
        root_error_ratio(p, 0.0, true)
    } else {
        1.0
    };
    at_touch.max(at_separation)
}

/// The local errors of the accepted steps, accumulated in quadrature (sums of squares) per
/// state component: their signs vary along an impact (summed, their absolute values
/// overstated the error 15-fold at tol 1e-4 and 124-fold at 1e-10).
pub(crate) struct ErrorSum<const N: usize>([f64; N]);

impl<const N: usize> Default for ErrorSum<N> {
    fn default() -> Self {
        ErrorSum([0.0; N])
    }
}

impl<const N: usize> ErrorSum<N> {
    /// Adds the local errors `err` of the components `at`, times `factor`.
    pub(crate) fn add(&mut self, err: &[f64; N], factor: f64, at: impl IntoIterator<Item = usize>) {
        for i in at {
            self.0[i] += (factor * err[i].abs()).powi(2);
        }
    }

    /// The accumulated error of component `i`.
    pub(crate) fn of(&self, i: usize) -> f64 {
        self.0[i].sqrt()
    }
}

/// `err_est` from the accumulated errors of the relative velocity `(gx, gy)` and of the spins
/// `(error, radius)`: the largest over e_T, e_N, e_kin and each spin in units of v / r, times
/// [`ERR_EST_FACTOR`] (measured on the plate).
pub(crate) fn error_estimate(
    init: &Initial,
    (gx, gy): (f64, f64),
    spins: impl IntoIterator<Item = (f64, f64)>,
) -> f64 {
    let v_in = init.vx.hypot(init.vy);
    let e_t = if init.vx != 0.0 {
        gx / init.vx.abs()
    } else {
        0.0
    };
    let e_n = gy / init.vy.abs();
    let e_kin = gx.hypot(gy) / v_in;
    let worst = spins
        .into_iter()
        .fold(e_t.max(e_n).max(e_kin), |w, (e, r)| w.max(e * r / v_in));
    ERR_EST_FACTOR * worst
}

/// The state where a piece ends inside `step`, at fraction `th`, from the step's dense output,
/// with its local error (`th` of the step's, plus the dense output's own error estimate,
/// `DenseStep::at_with_estimate`: its gap to the cubic Hermite interpolant of the step's ends,
/// scaled by the ratio of its last two terms), where that estimate is within the local
/// tolerance (`norm`, the norm steps are accepted by). `None` elsewhere (near a root
/// singularity of the force, at tight tolerances): the step is then redone up to the switch.
/// Redone always, a corner crossing cost the 120-gon a step (six evaluations of the law)
/// besides its location; taken from the dense output always, the disc erred 6.3 tol at tol
/// 1e-10; with the unscaled gap, which overstates the error by the ratio's inverse, half the
/// located switches were redone (a switch on the 120-gon 1.43-1.47 us against 1.35-1.39 us).
pub(crate) fn state_at_switch<const N: usize, const M: usize>(
    step: &DenseStep<N, M>,
    th: f64,
    norm: impl Fn(&[f64; N]) -> f64,
) -> Option<([f64; N], [f64; N])> {
    let (s_th, gap) = step.at_with_estimate(th);
    (norm(&gap) <= 1.0).then(|| {
        let err = std::array::from_fn(|i| th * step.err[i].abs() + gap[i]);
        (s_th, err)
    })
}

/// Consecutive negligible pieces ended by the same kind of switch after which its remedy acts
/// (`Chatter`): the loop then leaves that switch for one step in the mode of its sliding motion.
const CHATTERING: u32 = 16;

/// How many times its location's precision a piece ended by a switch may last and still count
/// as negligible for the chatter remedies (see [`Chatter::count`]).
const CHATTER_RESOLUTIONS: f64 = 100.0;

/// Consecutive zero-length pieces after which a step ignores its events: the last resort
/// against a loop of zero-length pieces, well above [`CHATTERING`], whose remedies must act
/// first (at 16 a tangential chatter once switched every event off and the step crossed the
/// clip with the plate pulling: the disc at theta 34, mu 0.6, e_N off by 1.2e-4).
const MAX_ZERO_PIECES: u32 = 64;

/// Pieces shorter than this, in units of the estimated contact time, are negligible for the
/// chatter remedies whatever the precision of their switch.
const NEGLIGIBLE_PIECE: f64 = 1e-9;

/// The kinds of switch the loop treats apart: those whose chattering has a remedy, and the
/// touch and the separation, where the force has its root singularity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum SwitchKind {
    /// Stick -> slip or slip -> stick.
    Tangential,
    /// The normal force's clip switching on or off.
    Clip,
    /// A contact begins.
    Touch,
    /// The contact ends.
    Separation,
    /// Any other (a corner or a spring switching, the deepest point).
    Other,
}

/// Consecutive negligible pieces ended by a stick/slip switch and by a clip switch, and
/// consecutive zero-length pieces.
#[derive(Debug, Default)]
pub(crate) struct Chatter {
    tangential: u32,
    clip: u32,
    zero_pieces: u32,
}

impl Chatter {
    /// Counts a piece of length `h_taken` in a step of `h` ended by `switch` (its kind and the
    /// fraction of its step to which it was located), `tiny` the negligible length
    /// ([`NEGLIGIBLE_PIECE`] contact times). A piece is negligible if shorter than `tiny` or
    /// than [`CHATTER_RESOLUTIONS`] times its switch's precision: the root finder may return any
    /// point within that precision past the root, and a sliding mode amplifies it (a bracket
    /// that crossed the root by half the precision left the clip of a damper far stiffer than
    /// the contact switching on and off in pieces of 2.5e-7 and 3e-6 of a step, precision
    /// 1e-6, above `tiny`, until the step budget ran out: 8 of the extremes benchmark's scenes),
    /// so the remedy does not depend on where within its precision a switch lands.
    pub(crate) fn count(
        &mut self,
        switch: Option<(SwitchKind, f64)>,
        (h_taken, h): (f64, f64),
        tiny: f64,
    ) {
        let resolution = switch.map_or(0.0, |(_, precision)| CHATTER_RESOLUTIONS * precision * h);
        let tiny = tiny.max(resolution);
        match switch.map(|(kind, _)| kind) {
            Some(SwitchKind::Tangential) if h_taken < tiny => self.tangential += 1,
            Some(SwitchKind::Clip) if h_taken < tiny => self.clip += 1,
            _ if h_taken >= tiny => (self.tangential, self.clip) = (0, 0),
            _ => {}
        }
        if h_taken > 0.0 {
            self.zero_pieces = 0;
        } else {
            self.zero_pieces += 1;
        }
    }

    /// Whether so many pieces in a row had zero length that the next step ignores its events.
    pub(crate) fn stalled(&self) -> bool {
        self.zero_pieces >= MAX_ZERO_PIECES
    }

    /// Whether stick and slip chatter (and the count starts again): the motion slides along the
    /// Coulomb cone (a Filippov sliding mode), whose force law is slip's.
    pub(crate) fn take_tangential(&mut self) -> bool {
        let chattering = self.tangential >= CHATTERING;
        if chattering {
            self.tangential = 0;
        }
        chattering
    }

    /// Whether the clip chatters (and the count starts again): a damper much stiffer than the
    /// contact holds F_el + F_d at zero (a sliding mode), so the force is about zero too.
    pub(crate) fn take_clip(&mut self) -> bool {
        let chattering = self.clip >= CHATTERING;
        if chattering {
            self.clip = 0;
        }
        chattering
    }
}
