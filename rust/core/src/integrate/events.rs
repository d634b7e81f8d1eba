//! Events of a polygon's contact, for the fixed-step integrators.
//!
//! A polygon's contact law is smooth only while the same corners lie below the plate. When a
//! corner crosses the plate (and at touch and separation, which are such crossings) the force
//! or one of its time derivatives jumps: face first, the overlap grows linearly from touch, so
//! the force's rate jumps there and again at separation; a corner crossing while an edge slaps
//! down changes it sharply. A fixed step that straddles such an instant commits a low-order
//! error (Gear-5 and Verlet both gained up to 1e-5 of the energy on elastic, frictionless squares
//! and triangles at the default step), and Gear-5's higher Taylor terms keep extrapolating the
//! old branch for several steps after it.
//!
//! So, for contacts without friction, the loop locates a touch or a separation inside a step
//! along the integrator's own predicted path, shortens that step to end on it, and restarts the
//! integrator there with the acceleration and jerk of the new branch, measured by two short
//! one-sided peeks along the path; and Gear-5 halves the steps whose local error in height is
//! too large (a sliver of overlap left when an edge lifts off at a glancing angle). Between
//! events the integrators are untouched; the exact disc has no events and its loop is compiled
//! without any of this.

use crate::geometry::{Corners, Overlap};
use crate::integrate::Stepper;
use crate::law::{Contact, Dof, Forces, PlateGeometry};
use crate::numerics::roots;

/// Length of the one-sided peeks, as a fraction of the step: short enough that the peeks stay
/// on the new branch, long enough that their differences keep ~1e-13 relative precision.
const PEEK: f64 = 1.0 / 1024.0;

/// Crossings of different corners closer than this (fraction of a step) are one event: an
/// edge parallel to the plate touches with both corners at once, up to round-off.
const SIMULTANEOUS: f64 = 1e-9;

/// A shortened step covers at least this fraction of a step, so that every event advances time.
const MIN_CUT: f64 = 1e-9;

/// Which corners are below the plate (`None` when clear).
#[inline(always)]
pub fn corners(overlap: &Option<Overlap>) -> Option<Corners> {
    overlap.map(|o| o.corners)
}

/// Fraction of the coming step at which the contact starts or ends, along the stepper's
/// predicted path: for a touch the first crossing of the plate by one of the corners of
/// `chain` (those below the plate after it), for a separation the last (of those below
/// before it). `None` if no corner's height changes side along the path (a change seen only
/// through round-off at the step's end).
///
/// At a touch, crossings within `SIMULTANEOUS` of the first are one event (an edge parallel
/// to the plate); the fraction returned is the last of them, just past it on the new side.
pub fn locate<G: PlateGeometry, S: Stepper>(
    geometry: &G,
    stepper: &S,
    chain: Corners,
    touch: bool,
) -> Option<f64> {
    let n = geometry.corner_count();
    let height = |k: usize, s: f64| {
        let q = stepper.path(s);
        geometry.corner_height(k, q[1], q[2])
    };
    let mut crossings: Vec<f64> = (chain.first as usize..(chain.first + chain.count) as usize)
        .filter_map(|k| crossing(|s| height(k % n, s)))
        .collect();
    if touch {
        let first = crossings.iter().copied().fold(f64::INFINITY, f64::min);
        crossings.retain(|&s| s <= first + SIMULTANEOUS);
    }
    let last = crossings.into_iter().fold(f64::NEG_INFINITY, f64::max);
    last.is_finite().then(|| last.clamp(MIN_CUT, 1.0))
}

/// Where on [0, 1] the function `g` (a corner's height) changes side of the plate (a corner at
/// height <= 0 is below); the end of the final bracket on the far side, or `None` when both
/// ends lie on the same side.
fn crossing(g: impl Fn(f64) -> f64) -> Option<f64> {
    bracket(g).map(|(_, far)| far)
}

/// The final bracket (near, far) of a change of side of `g` on [0, 1]: `near` still on the
/// side of s = 0, `far` on the other, at most a few ulp apart; `None` when both ends lie on the
/// same side (a corner at height <= 0 is below).
fn bracket(g: impl Fn(f64) -> f64) -> Option<(f64, f64)> {
    let (g_lo, g_hi) = (g(0.0), g(1.0));
    if (g_lo > 0.0) == (g_hi > 0.0) {
        return None;
    }
    Some(roots::bracket(
        g,
        (0.0, g_lo),
        (1.0, g_hi),
        4.0 * f64::EPSILON,
    ))
}

/// The linear law's events: fraction of the coming step just BEFORE the first corner of
/// `chains` (the chains below the plate before and after the step) changes side along the
/// stepper's predicted path, or `None` when none does. Each submerged corner carries its own
/// dashpot, whose force jumps by c_n times the corner's approach speed as it crosses, so the
/// step must end on the old branch (its force at the step's end the old branch's limit) and
/// the new branch start just past the crossing ([`branch_start`]'s peeks). Several corners
/// crossing within one step are met one event at a time.
pub fn locate_first<G: PlateGeometry, S: Stepper>(
    geometry: &G,
    stepper: &S,
    chains: &[Corners],
) -> Option<f64> {
    let n = geometry.corner_count();
    let height = |k: usize, s: f64| {
        let q = stepper.path(s);
        geometry.corner_height(k, q[1], q[2])
    };
    let first = chains
        .iter()
        .flat_map(|c| c.first as usize..(c.first + c.count) as usize)
        .filter_map(|k| bracket(|s| height(k % n, s)))
        .map(|(near, _)| near)
        .fold(f64::INFINITY, f64::min);
    first.is_finite().then(|| first.clamp(MIN_CUT, 1.0))
}

/// The start of a new branch of the contact law at the current state.
pub struct BranchStart {
    /// Acceleration just after the event (m/s^2, rad/s^2).
    pub a: Dof,
    /// Its rate of change (jerk).
    pub jerk: Dof,
    /// Corners below the plate on the new branch.
    pub corners: Option<Corners>,
    /// Powers (elastic, damping, tangential) just after the event, for the work quadrature.
    pub powers: (f64, f64, f64),
}

/// Acceleration, jerk and powers of the branch the contact is entering at position `q` and
/// velocity `v`, from two peeks at PEEK and 2 PEEK steps ahead along q + v t + a t^2 / 2
/// (`a`: the acceleration before the event), extrapolated back to the event. The peeks run
/// on a copy of the contact: the tangential spring's history is not touched.
pub fn branch_start<G: PlateGeometry>(
    contact: &Contact<G>,
    q: &Dof,
    v: &Dof,
    a: &Dof,
    inv_mass: &Dof,
    dt: f64,
) -> BranchStart {
    let eps = PEEK * dt;
    let mut peek = contact.clone();
    let mut acc = [[0.0; 3]; 2];
    let mut pow = [(0.0, 0.0, 0.0); 2];
    let mut corners_after = None;
    for (j, t) in [eps, 2.0 * eps].into_iter().enumerate() {
        let qt: Dof = std::array::from_fn(|i| q[i] + v[i] * t + a[i] * (0.5 * t * t));
        let vt: Dof = std::array::from_fn(|i| v[i] + a[i] * t);
        let f: Forces = peek.evaluate(&qt, &vt, eps);
        acc[j] = [
            f.fx * inv_mass[0],
            f.fy * inv_mass[1],
            f.torque * inv_mass[2],
        ];
        pow[j] = f.powers(qt[1], &vt);
        if j == 0 {
            corners_after = corners(&f.overlap);
        }
    }
    let extrapolate = |p1: f64, p2: f64| 2.0 * p1 - p2;
    BranchStart {
        a: std::array::from_fn(|i| extrapolate(acc[0][i], acc[1][i])),
        jerk: std::array::from_fn(|i| (acc[1][i] - acc[0][i]) / eps),
        corners: corners_after,
        powers: (
            extrapolate(pow[0].0, pow[1].0),
            extrapolate(pow[0].1, pow[1].1),
            extrapolate(pow[0].2, pow[1].2),
        ),
    }
}

/// Smallest step the error control may take, as a fraction of the nominal step.
const MIN_STEP: f64 = 1.0 / 1024.0;

/// One step taken by [`EventControl::step`].
pub struct Taken {
    /// Forces of the step (at its end).
    pub forces: Forces,
    /// Its length (s).
    pub h: f64,
    /// The branch restarted at its end, when it ended on an event.
    pub restart: Option<BranchStart>,
}

/// Steps a polygon's contact: fixed steps of `dt`, shortened to land on events, and (for an
/// integrator with an error estimate) halved while the local error exceeds `tolerance`, which
/// happens only where the force changes within a step (a sliver of overlap left when an edge
/// lifts off at a glancing angle lives for a step or two).
pub struct EventControl {
    /// Corners below the plate on the current branch.
    pub corners: Option<Corners>,
    /// Current step (s).
    pub h: f64,
    /// Nominal step (s).
    pub dt: f64,
    /// Largest accepted local error in the centre's height (m): the height is driven by the
    /// normal force alone, whose fast changes are what needs finer steps.
    pub tolerance: f64,
    /// Every corner crossing is an event, in the middle of a contact too, each step ending
    /// just before it ([`locate_first`]): the linear law on a polygon, whose per-corner
    /// dashpots make the force jump there. Otherwise (the area law, continuous at a crossing)
    /// only touch and separation.
    pub every_crossing: bool,
}

impl EventControl {
    /// Fraction of the step just taken (from `snapshot`) at which it should end on an event,
    /// given the corners below the plate at its end.
    fn event_in_step<G: PlateGeometry, S: Stepper>(
        &self,
        geometry: &G,
        snapshot: &S,
        after: Option<Corners>,
    ) -> Option<f64> {
        match (self.corners, after) {
            (before, after) if self.every_crossing && before != after => {
                let chains: Vec<Corners> = before.into_iter().chain(after).collect();
                locate_first(geometry, snapshot, &chains)
            }
            (None, Some(c)) => locate(geometry, snapshot, c, true),
            (Some(c), None) => locate(geometry, snapshot, c, false),
            _ => None,
        }
    }

    /// Takes one step (retrying shorter ones as needed) and restarts on a new branch when it
    /// ends on an event.
    pub fn step<G: PlateGeometry, S: Stepper>(
        &mut self,
        stepper: &mut S,
        contact: &mut Contact<G>,
        inv_mass: &Dof,
    ) -> Taken {
        loop {
            let (snapshot, spring) = (stepper.clone(), contact.spring.clone());
            let mut forces = stepper.step(contact, self.h, inv_mass);
            let mut h = self.h;
            // A touch or a separation inside the step: redo it, shortened to end just past.
            // (Under the area law corners crossing while the contact goes on change the
            // force's curvature only; locating them too cost up to 40 % on fine polygons,
            // whose crossings come every few steps, and bought nothing measurable; sharp ones
            // are left to the error control. Under the linear law every crossing is a jump of
            // the force and is located: `every_crossing`.)
            let (before, after) = (self.corners, corners(&forces.overlap));
            let mut event = false;
            if let Some(s) = self.event_in_step(&contact.geometry, &snapshot, after) {
                (*stepper, contact.spring) = (snapshot.clone(), spring.clone());
                h = s * self.h;
                stepper.resize(h);
                forces = stepper.step(contact, h, inv_mass);
                event = true;
            }
            self.corners = after;
            let too_large = stepper
                .local_error()
                .is_some_and(|e| e[1].abs() > self.tolerance);
            if too_large && self.h > MIN_STEP * self.dt {
                // The retry starts where this attempt did, below the plate the same corners:
                // with the chain at the attempt's end a crossing inside the shorter retry
                // would go unseen.
                (*stepper, contact.spring, self.corners) = (snapshot, spring, before);
                self.h *= 0.5;
                stepper.resize(self.h);
                continue;
            }
            let restart = if event {
                let (q, v) = (stepper.position(), stepper.velocity());
                let a = stepper.acceleration();
                let b = branch_start(contact, &q, &v, &a, inv_mass, self.dt);
                // Each branch starts at the nominal step; the error control shortens it again
                // where the new branch needs it.
                self.h = self.dt;
                stepper.restart(&b.a, &b.jerk, self.h);
                self.corners = b.corners;
                Some(b)
            } else {
                // Gear-5's local error grows like h^6: doubling is safe well below the bound.
                let small = stepper
                    .local_error()
                    .is_some_and(|e| e[1].abs() * 128.0 < self.tolerance);
                if small && self.h < self.dt {
                    self.h = (2.0 * self.h).min(self.dt);
                    stepper.resize(self.h);
                }
                None
            };
            return Taken { forces, h, restart };
        }
    }
}
