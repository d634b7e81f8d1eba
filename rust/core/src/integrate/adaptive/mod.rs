//! The high-accuracy reference integrator: adaptive Dormand-Prince 5(4) on the smooth pieces of
//! the continuous-time contact law, every switch between pieces located and the integration
//! restarted there.
//!
//! Why: the fixed-step integrators step across the non-smooth points of the law (touch and
//! separation, a polygon corner crossing the plate, the normal-force clip switching on or off,
//! stick <-> slip), so their error falls only like dt^1 ... dt^3 (docs/model.md, section 7.6).
//! Between those points the law is smooth, and a 5th-order method with error control converges
//! at its full order there; locating each switch as a root of a continuous event function keeps
//! the whole impact accurate to about the tolerance.
//!
//! The continuous-time law is the dt -> 0 limit of the discrete rule of docs/model.md (sections 4, 5):
//! - Normal force: as in [`crate::law`], clipped to zero while F_el + F_d < 0.
//! - Cundall-Strack spring: while sticking dxi/dt = v_t and F_t = -k_t xi - c_t v_t with
//!   |F_t| <= mu F_n; while slipping F_t = mu F_n s (s the sign of the trial force) and the spring
//!   follows algebraically, xi = -(F_t + c_t v_t) / k_t. Slip ends when the trial force of a
//!   sticking spring would move back inside the cone: s (dF_trial/dt) < mu dF_n/dt with
//!   dF_trial/dt = -k_t v_t - c_t dv_t/dt (both rates taken along the motion).
//! - While the normal force is clipped there is no tangential force and xi = -c_t v_t / k_t.
//!
//! Inside a piece the mode is *held*: the force formulas of the piece are continued smoothly
//! a little beyond its end (a polygon's clipped region keeps its set of submerged corners, the
//! clip its state), so that the Runge-Kutta stages never see a kink. The work of each force is
//! integrated as three more components of the same ODE (the same stages), so the energy audit
//! is accurate to the tolerance too.
//!
//! `dt_factor` means the largest (and the first) step, in units of t_ref; the accuracy is set
//! by [`ReferenceOptions::tol`].

use crate::cancel::Cancel;
use crate::error::Result;
use crate::geometry::{Overlap, Shape};
use crate::impact::budget::{budget_for, reference_contact_steps};
use crate::impact::record::{estimate_max_depth, Record, StopReason, Trace, TIMEOUT_CONTACT_TIMES};
use crate::law::vertex_springs;
use crate::law::Forces;
use crate::law::StickState;
use crate::model::{Initial, Integrator, Model, NormalLaw, Scene};
use nalgebra::Vector2;
use std::f64::consts::PI;

/// Settings of the reference integrator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceOptions {
    /// Local error tolerance per step, relative to the natural scales of the impact (the
    /// estimated maximal depth for positions, the impact speed for velocities, the kinetic
    /// energy for works). Default 1e-12: global errors come out at about 20 tol.
    pub tol: f64,
    /// Largest step in units of t_ref; `None`: the scene's `dt_factor`.
    pub max_step_factor: Option<f64>,
}

/// The local tolerance per unit of the target error `Scene::tol` of the adaptive integrator:
/// global errors of the four outputs come out below the accumulated local errors, measured
/// over the accuracy grid (`tests/adaptive.rs`).
pub const LOCAL_TOL_PER_TARGET: f64 = 0.05;

/// Factor on the local error estimates accumulated in quadrature that makes `err_est`: the
/// 5 % quantile of err_est / error was 0.35 ... 1.5 over the accuracy grid's largest steps and
/// tolerances at factor 0.5, so 3 times that puts err_est >= error in >= 95 % of impacts at
/// every setting (`tests/adaptive.rs`).
pub const ERR_EST_FACTOR: f64 = 1.5;

impl ReferenceOptions {
    /// The settings a scene asks for: the reference's for `Integrator::Reference`, the scene's
    /// tolerance for `Integrator::Adaptive`; the largest step is the scene's `dt_factor`.
    pub fn for_scene(scene: &Scene) -> Self {
        match scene.integrator {
            Integrator::Adaptive => ReferenceOptions {
                tol: scene.tol * LOCAL_TOL_PER_TARGET,
                max_step_factor: None,
            },
            _ => ReferenceOptions::default(),
        }
    }
}

impl Default for ReferenceOptions {
    fn default() -> Self {
        ReferenceOptions {
            tol: 1e-12,
            max_step_factor: None,
        }
    }
}

/// Simulates one impact with the reference integrator, whatever `scene.integrator` says.
pub fn simulate_reference(
    scene: &Scene,
    init: &Initial,
    opts: &ReferenceOptions,
) -> Result<Record> {
    let model = reference_model(scene)?;
    model.check_initial(init)?;
    let depth_est = estimate_max_depth(&model, init)?;
    integrate(&model, init, depth_est, opts, None, Cancel::never())
}

/// As [`simulate_reference`], and records every accepted step.
pub fn simulate_reference_with_trace(
    scene: &Scene,
    init: &Initial,
    opts: &ReferenceOptions,
) -> Result<(Record, Trace)> {
    let model = reference_model(scene)?;
    model.check_initial(init)?;
    let depth_est = estimate_max_depth(&model, init)?;
    let mut trace = Trace::default();
    let rec = integrate(
        &model,
        init,
        depth_est,
        opts,
        Some(&mut trace),
        Cancel::never(),
    )?;
    Ok((rec, trace))
}

/// The scene validated as one for the reference integrator (its `dt_factor` is only its
/// largest step, so the fixed-step integrators' stability bounds do not apply).
fn reference_model(scene: &Scene) -> Result<Model> {
    Model::new(&Scene {
        integrator: Integrator::Reference,
        ..scene.clone()
    })
}

// ---------------------------------------------------------------------------------------------
// State and modes

/// x, y, phi, vx, vy, omega, xi, then the works of the elastic, damping and tangential forces.
const NS: usize = 10;
type State = [f64; NS];
const X: usize = 0;
const Y: usize = 1;
const PHI: usize = 2;
const VX: usize = 3;
const VY: usize = 4;
const OM: usize = 5;
const XI: usize = 6;
const W_EL: usize = 7;
const W_D: usize = 8;
const W_T: usize = 9;

/// Which overlap formula holds in a piece.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Touch {
    /// No overlap: free flight.
    Off,
    /// The disc's circular segment.
    Disc,
    /// A polygon with the corners `first .. first + len` (cyclic) below the plate; `low` is the
    /// lowest of them (for the overlap's x_low only).
    Poly {
        first: usize,
        len: usize,
        low: usize,
    },
}

/// The tangential law in a piece.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Tan {
    /// mu = 0 or no overlap.
    None,
    /// Spring and damper within the Coulomb cone; xi integrated.
    Stick,
    /// F_t = mu F_n s, s = +-1.
    Slip(f64),
    /// The normal force is clipped: no tangential force, xi = -c_t v_t / k_t.
    Free,
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct Mode {
    touch: Touch,
    clip_on: bool,
    /// The clip held off for one step, its events ignored, where it chatters (see `integrate`).
    clip_hold: bool,
    tan: Tan,
}

/// The switches that end a piece. Each has a continuous event function that is <= 0 while
/// the piece's mode holds.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Event {
    Touch,
    Separate,
    EnterLeft,
    EnterRight,
    LeaveLeft,
    LeaveRight,
    ClipOff,
    ClipOn,
    ToSlip,
    ToStick,
}

/// Everything the force evaluation yields besides the derivative.
#[derive(Debug, Clone, Copy, Default)]
struct Eval {
    forces: Forces,
    /// F_el + F_d before the clip.
    fn_raw: f64,
    /// Tangential velocity of the contact point.
    v_t: f64,
    /// Trial force of a sticking spring, -k_t xi - c_t v_t.
    trial: f64,
    /// Depth of the lowest point (signed).
    depth: f64,
}

// ---------------------------------------------------------------------------------------------
// Dormand-Prince 5(4) tableau (Dormand & Prince 1980; dense output of Hairer, Norsett & Wanner)

// The forces do not depend on time explicitly, so the nodes c_i are not needed.
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// 5th-order minus embedded 4th-order weights.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// Dense-output weights (4th-order continuous extension).
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// The nodes c_i of the stages (fractions of the step at which each stage is evaluated).
const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];

/// One accepted Runge-Kutta step with what its dense output needs.
struct Step {
    y0: State,
    y1: State,
    k: [State; 7],
    h: f64,
    /// The embedded error estimate of each component (5th minus 4th order).
    err: State,
    /// The first node at which a stage saw the plate pull (F_el + F_d below minus the force
    /// tolerance) while the clip was on: the step integrated across a clip switch.
    pull: Option<f64>,
}

impl Step {
    /// The state at fraction `theta` of the step (4th-order interpolant).
    fn at(&self, theta: f64) -> State {
        let eta = 1.0 - theta;
        std::array::from_fn(|i| {
            let r2 = self.y1[i] - self.y0[i];
            let r3 = self.h * self.k[0][i] - r2;
            let r4 = r2 - self.h * self.k[6][i] - r3;
            let r5 = self.h * (0..7).map(|j| D[j] * self.k[j][i]).sum::<f64>();
            self.y0[i] + theta * (r2 + eta * (r3 + theta * (r4 + eta * r5)))
        })
    }
}

// ---------------------------------------------------------------------------------------------
// The integrator

struct Reference<'a> {
    model: &'a Model,
    verts: &'a [Vector2<f64>],
    mu: f64,
    /// Error scale of each state component (the tolerance multiplies it).
    scale: State,
    tol: f64,
    /// Time step of the directional finite differences of the slip -> stick test.
    fd_step: f64,
    /// A pull of the unclipped normal force below -force_tol is a missed clip switch.
    force_tol: f64,
}

impl<'a> Reference<'a> {
    fn linear(&self) -> Option<(f64, f64)> {
        match self.model.scene.normal_law {
            NormalLaw::Linear { kn, cn } => Some((kn, cn)),
            NormalLaw::Area | NormalLaw::Hertz { .. } => None,
        }
    }

    /// World position of corner `k` for centre height `y` and orientation (sin, cos):
    /// x relative to the centre of mass, y absolute.
    #[inline]
    fn corner(&self, k: usize, y: f64, sc: (f64, f64)) -> (f64, f64) {
        let v = &self.verts[k % self.verts.len()];
        (sc.1 * v.x - sc.0 * v.y, y + sc.0 * v.x + sc.1 * v.y)
    }

    /// The overlap of a polygon whose submerged corners are held fixed: the crossing points on
    /// the two boundary edges are placed on y = 0 by linear interpolation even when a held
    /// corner has just risen above the plate (a smooth continuation of the clip).
    fn held_polygon(&self, first: usize, len: usize, low: usize, y: f64, phi: f64) -> Overlap {
        let n = self.verts.len();
        let sc = phi.sin_cos();
        let a = (first + n - 1) % n;
        let last = (first + len - 1) % n;
        let b = (last + 1) % n;
        // Interpolated from the end nearer the plate (slivers keep their precision); an edge
        // parallel to the plate, possible only in the continuation, takes its midpoint.
        let crossing = |p: (f64, f64), q: (f64, f64)| {
            let (near, far) = if p.1.abs() <= q.1.abs() {
                (p, q)
            } else {
                (q, p)
            };
            let t = near.1 / (near.1 - far.1);
            if t.is_finite() {
                near.0 + t * (far.0 - near.0)
            } else {
                0.5 * (p.0 + q.0)
            }
        };
        let p_first = self.corner(first, y, sc);
        let p_last = self.corner(last, y, sc);
        let xp = crossing(self.corner(a, y, sc), p_first);
        let xq = crossing(p_last, self.corner(b, y, sc));
        // Shoelace over P, corners, Q (relative to P for precision); the chord Q -> P closes it.
        let (mut area2, mut mx, mut my) = (0.0, 0.0, 0.0);
        let mut prev = (0.0, 0.0);
        let mut depth = f64::NEG_INFINITY;
        for j in 0..=len {
            let cur = if j < len {
                let c = self.corner(first + j, y, sc);
                depth = depth.max(-c.1);
                (c.0 - xp, c.1)
            } else {
                (xq - xp, 0.0)
            };
            let w = prev.0 * cur.1 - cur.0 * prev.1;
            area2 += w;
            mx += (prev.0 + cur.0) * w;
            my += (prev.1 + cur.1) * w;
            prev = cur;
        }
        let (cx, cy) = if area2.abs() > 0.0 {
            (xp + mx / (3.0 * area2), my / (3.0 * area2))
        } else {
            (xp, 0.0)
        };
        let lowc = self.corner(low, y, sc);
        let area = 0.5 * area2;
        Overlap {
            area,
            cx,
            cy,
            chord: xq - xp,
            x_mid: 0.5 * (xp + xq),
            depth,
            x_low: lowc.0,
            first_moment: -area * cy,
            corners: crate::geometry::Corners {
                first: first as u32,
                count: len as u32,
            },
        }
    }

    /// Overlap in the held mode; `None` in free flight.
    fn overlap(&self, touch: Touch, y: f64, phi: f64) -> Option<Overlap> {
        match touch {
            Touch::Off => None,
            Touch::Disc => {
                let r = self.model.r;
                // Beyond the separation point the segment continues as nothing.
                Some(self.model.scene.shape.overlap(y, phi).unwrap_or(Overlap {
                    cy: y - r,
                    depth: r - y,
                    ..Overlap::default()
                }))
            }
            Touch::Poly { first, len, low } => Some(self.held_polygon(first, len, low, y, phi)),
        }
    }

    /// Forces and the time derivative of the state in mode `m`.
    fn eval(&self, m: &Mode, s: &State) -> (State, Eval) {
        let model = self.model;
        let mut d = [0.0; NS];
        d[X] = s[VX];
        d[Y] = s[VY];
        d[PHI] = s[OM];
        let Some(o) = self.overlap(m.touch, s[Y], s[PHI]) else {
            let depth = model.scene.shape.touch_height(s[PHI]) - s[Y];
            return (
                d,
                Eval {
                    depth,
                    ..Eval::default()
                },
            );
        };
        let (vy, om) = (s[VY], s[OM]);
        let (f_el, f_d, x_el, x_damp, depth) = match (self.linear(), model.hertz) {
            (None, Some(h)) => {
                // The sphere's Hertz law (section 14); beyond separation it continues as
                // nothing, like the disc's segment. It acts along the centre line.
                let delta = (model.r - s[Y]).max(0.0);
                let q = delta.sqrt();
                (h.k * delta * q, h.c * q.sqrt() * -vy, 0.0, 0.0, o.depth)
            }
            (None, None) => (
                model.scene.e_modulus * o.area / model.length,
                model.area_damping * (-o.chord * (vy + om * o.x_mid)),
                o.cx,
                o.x_mid,
                o.depth,
            ),
            (Some((kn, cn)), _) => {
                let (f_el, f_d, x_el, x_damp) = match m.touch {
                    // One spring-dashpot per held corner, continued smoothly beyond a
                    // crossing (see `crate::law::vertex_springs`).
                    Touch::Poly { first, len, .. } => {
                        let sc = s[PHI].sin_cos();
                        let held = (first..first + len).map(|k| {
                            let (x, h) = self.corner(k, s[Y], sc);
                            (-h, x)
                        });
                        vertex_springs(kn, cn, held, &[s[VX], vy, om])
                    }
                    // The disc: at its lowest point, r - y below the centre.
                    _ => {
                        let delta = self.low_depth(m.touch, s[Y], s[PHI]);
                        let rate = -(vy + om * o.x_low);
                        (kn * delta, cn * rate, o.x_low, o.x_low)
                    }
                };
                (f_el, f_d, x_el, x_damp, o.depth)
            }
        };
        let fn_raw = f_el + f_d;
        let (f_el, f_d) = if m.clip_on { (f_el, f_d) } else { (0.0, 0.0) };
        let f_n = f_el + f_d;
        let arm_y = o.cy - s[Y];
        let v_t = s[VX] - om * arm_y;
        // (k_t, 1, c_t) for the linear spring; Mindlin's, incremental in the force, (1, k_t, c_t)
        // at this depth, xi then being minus the elastic force.
        let (k_xi, rate, ct) = model.spring(o.depth);
        let trial = -k_xi * s[XI] - ct * v_t;
        let (f_t, stick) = match m.tan {
            Tan::None => (0.0, StickState::None),
            Tan::Free => (0.0, StickState::Slip),
            Tan::Stick => (trial, StickState::Stick),
            Tan::Slip(sg) => (self.mu * f_n * sg, StickState::Slip),
        };
        let torque = x_el * f_el + x_damp * f_d - arm_y * f_t;
        d[VX] = f_t / model.mass;
        d[VY] = f_n / model.mass;
        d[OM] = torque / model.inertia;
        d[XI] = if m.tan == Tan::Stick { rate * v_t } else { 0.0 };
        d[W_EL] = f_el * (vy + om * x_el);
        d[W_D] = f_d * (vy + om * x_damp);
        d[W_T] = f_t * v_t;
        let forces = Forces {
            fx: f_t,
            fy: f_n,
            torque,
            f_el,
            f_d,
            f_t,
            overlap: Some(o),
            stick,
            x_el,
            x_damp,
        };
        (
            d,
            Eval {
                forces,
                fn_raw,
                v_t,
                trial,
                depth,
            },
        )
    }

    /// Depth of the held lowest corner of a polygon (linear law).
    fn low_depth(&self, touch: Touch, y: f64, phi: f64) -> f64 {
        match touch {
            Touch::Poly { low, .. } => -self.corner(low, y, phi.sin_cos()).1,
            Touch::Disc => self.model.r - y,
            Touch::Off => 0.0,
        }
    }

    /// The spring elongation the law implies: integrated while sticking, algebraic otherwise.
    fn xi_of(&self, m: &Mode, s: &State, e: &Eval) -> f64 {
        let (kt, _, ct) = self.model.spring(e.depth);
        match m.tan {
            Tan::Stick => s[XI],
            Tan::Slip(_) => -(e.forces.f_t + ct * e.v_t) / kt,
            Tan::Free => -ct * e.v_t / kt,
            Tan::None => 0.0,
        }
    }

    /// One Dormand-Prince step from `y0` with first stage `k1`; returns the step and the
    /// scaled error norm (<= 1: accepted).
    fn dp_step(&self, m: &Mode, y0: &State, k1: &State, h: f64) -> (Step, f64) {
        let mut k = [[0.0; NS]; 7];
        k[0] = *k1;
        let mut pull = None;
        for st in 1..7 {
            let mut yi = *y0;
            for i in 0..NS {
                let mut acc = 0.0;
                for j in 0..st {
                    acc += A[st][j] * k[j][i];
                }
                yi[i] += h * acc;
            }
            let (kk, e) = self.eval(m, &yi);
            k[st] = kk;
            if pull.is_none() && self.clipped(m) && e.fn_raw < -self.force_tol {
                pull = Some(C[st]);
            }
        }
        // The 7th stage is evaluated at the 5th-order solution itself (FSAL).
        let mut y1 = *y0;
        for i in 0..NS {
            let mut acc = 0.0;
            for j in 0..6 {
                acc += A[6][j] * k[j][i];
            }
            y1[i] += h * acc;
        }
        let err_vec: State =
            std::array::from_fn(|i| h * (0..7).map(|j| E[j] * k[j][i]).sum::<f64>());
        // The spring elongation is not integrated outside stick (there it is algebraic).
        let err = (0..NS)
            .filter(|&i| i != XI || m.tan == Tan::Stick)
            .map(|i| err_vec[i].abs() / (self.tol * self.scale[i]))
            .fold(0.0, f64::max);
        let step = Step {
            y0: *y0,
            y1,
            k,
            h,
            err: err_vec,
            pull,
        };
        (step, err)
    }

    /// The largest step near a point where a disc's force is not smooth (touch and
    /// separation: the area grows like depth^(3/2), the damping like depth^(1/2), so a step
    /// of h across such a point errs like (h / t_c)^(3/2) in the velocity, unseen by the
    /// embedded estimate). The step that contains the point is at most t_c tol^(2/3): the
    /// first after touch, and towards separation the steps halve the time left until then.
    fn singular_cap(&self, m: &Mode, s: &State, fresh_touch: bool, t_est: f64) -> f64 {
        let smooth_law = self.linear().is_some();
        if smooth_law || m.touch != Touch::Disc {
            return f64::INFINITY;
        }
        let h_sing = t_est * self.tol.powf(2.0 / 3.0);
        if fresh_touch {
            return h_sing;
        }
        let depth = self.model.r - s[Y];
        if s[VY] > 0.0 && depth > 0.0 {
            (0.5 * depth / s[VY]).max(h_sing)
        } else {
            f64::INFINITY
        }
    }

    /// A clip switch before a corner leaves (or the disc separates) at `th` of `step`. With
    /// damping the force pulls in the last stretch before a corner leaves (F = delta (k delta
    /// + c delta') < 0 as delta -> 0 while it falls), so the clip switches off there; the
    /// check at the step's end cannot see it, since past the leave point the held formulas
    /// are no contact (a corner's area grows again like depth^2 above the plate): a step of
    /// 2 t_ref once crossed the pulling tail unclipped (the 12-gon at theta 74, mu 0.5: e_N off
    /// by 4e-5). Sampled on the dense output, densest towards the leave point.
    fn clip_before_leaving(&self, m: &Mode, step: &Step, th: f64) -> Option<(f64, Event)> {
        if !self.clipped(m) || th <= 0.0 {
            return None;
        }
        const AT: [f64; 10] = [0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 0.9375, 0.96875, 0.984375];
        let mut lo = 0.0;
        for f in AT {
            let g = self.event_value(m, Event::ClipOff, &step.at(f * th));
            if g > 0.0 {
                let at = self.locate_in(m, Event::ClipOff, step, lo, f * th, g);
                return Some((at, Event::ClipOff));
            }
            lo = f * th;
        }
        None
    }

    /// The error of a step across or near a point where the disc's force is not smooth (the
    /// first [`SINGULAR_STEPS`] steps after touch, where the damping still grows like
    /// t^(1/2); a step ending on separation), which the embedded estimate does not see: the
    /// step redone as two halves, and the difference extrapolated for an error that falls like
    /// h^(1/2) per unit time, as each half still holds the root singularity: 1 / (1 - 2^-1/2)
    /// = 3.41 (1.55, for the singularity in the first half only, left 13 % of the disc's
    /// impacts at tol 1e-4 with err_est below the error). Zero for every other step.
    #[allow(clippy::too_many_arguments)]
    fn singular_error(
        &self,
        m: &Mode,
        s: &State,
        k1: &State,
        h: f64,
        y1: &State,
        near_touch: bool,
        event: Option<Event>,
    ) -> State {
        let across = near_touch || event == Some(Event::Separate);
        if !across || h <= 0.0 || m.touch != Touch::Disc || self.linear().is_some() {
            return [0.0; NS];
        }
        let (half, _) = self.dp_step(m, s, k1, 0.5 * h);
        let (k_mid, _) = self.eval(m, &half.y1);
        let (second, _) = self.dp_step(m, &half.y1, &k_mid, 0.5 * h);
        std::array::from_fn(|i| 3.41 * (second.y1[i] - y1[i]).abs())
    }

    /// Whether the clip is watched in mode `m`: on, with an overlap, not held for chattering.
    fn clipped(&self, m: &Mode) -> bool {
        m.clip_on && !m.clip_hold && m.touch != Touch::Off
    }

    /// The events that can end a piece of mode `m`.
    fn candidates(&self, m: &Mode) -> Vec<Event> {
        let mut out = Vec::with_capacity(8);
        match m.touch {
            Touch::Off => {
                out.push(Event::Touch);
                return out;
            }
            Touch::Disc => out.push(Event::Separate),
            Touch::Poly { len, .. } => {
                let n = self.verts.len();
                if len + 1 < n {
                    out.push(Event::EnterLeft);
                    out.push(Event::EnterRight);
                }
                out.push(Event::LeaveLeft);
                if len > 1 {
                    out.push(Event::LeaveRight);
                }
            }
        }
        if !m.clip_hold {
            out.push(if m.clip_on {
                Event::ClipOff
            } else {
                Event::ClipOn
            });
        }
        match m.tan {
            Tan::Stick => out.push(Event::ToSlip),
            Tan::Slip(_) => out.push(Event::ToStick),
            Tan::None | Tan::Free => {}
        }
        out
    }

    /// The event function: > 0 once the piece's mode no longer holds.
    fn event_value(&self, m: &Mode, ev: Event, s: &State) -> f64 {
        let (y, phi) = (s[Y], s[PHI]);
        let n = self.verts.len().max(1);
        let poly = |k: usize| self.corner(k, y, phi.sin_cos()).1;
        match (ev, m.touch) {
            (Event::Touch, _) => self.model.scene.shape.touch_height(phi) - y,
            (Event::Separate, _) => y - self.model.r,
            (Event::EnterLeft, Touch::Poly { first, .. }) => -poly(first + n - 1),
            (Event::EnterRight, Touch::Poly { first, len, .. }) => -poly(first + len),
            (Event::LeaveLeft, Touch::Poly { first, .. }) => poly(first),
            (Event::LeaveRight, Touch::Poly { first, len, .. }) => poly(first + len - 1),
            (Event::ClipOff, _) => -self.eval(m, s).1.fn_raw,
            (Event::ClipOn, _) => {
                // Only an overlap can push: once every held corner has risen above the plate
                // the held continuation is no contact, whatever sign its force has.
                let e = self.eval(m, s).1;
                if e.depth > 0.0 {
                    e.fn_raw
                } else {
                    f64::NEG_INFINITY
                }
            }
            (Event::ToSlip, _) => {
                // Stick starts with the spring on the cone (|trial| = mu F_n up to round-off):
                // a margin of 1e-12 mu F_n keeps round-off from ending it at once (a chatter
                // of zero-length pieces, then a sliding mode the tight run never enters).
                let e = self.eval(m, s).1;
                e.trial.abs() - self.mu * e.forces.fy * (1.0 + 1e-12)
            }
            (Event::ToStick, _) => self.slip_to_stick(m, s),
            _ => f64::NEG_INFINITY,
        }
    }

    /// Positive when a sticking spring would stay inside the Coulomb cone: the value
    /// mu dF_n/dt + s (k_t v_t + c_t dv_t/dt), both rates by central differences along the
    /// motion of the slipping body.
    fn slip_to_stick(&self, m: &Mode, s: &State) -> f64 {
        let Tan::Slip(sg) = m.tan else {
            return f64::NEG_INFINITY;
        };
        let (d, e) = self.eval(m, s);
        let mut h = self.fd_step;
        if let (Touch::Disc, None) = (m.touch, self.linear()) {
            // Keep both sample points inside the segment (no continuation beyond separation).
            if e.depth <= 0.0 {
                return f64::NEG_INFINITY;
            }
            h = h.min(0.25 * e.depth / s[VY].abs().max(f64::MIN_POSITIVE));
        }
        let shifted = |sign: f64| {
            let mut p = *s;
            for i in 0..6 {
                p[i] += sign * h * d[i];
            }
            self.eval(m, &p).1
        };
        let (ep, em) = (shifted(1.0), shifted(-1.0));
        let dfn = (ep.fn_raw - em.fn_raw) / (2.0 * h);
        let (k_xi, rate, ct) = self.model.spring(e.depth);
        // The damping force's rate: c_t dv_t/dt, and for Mindlin's c_t(delta) its own change.
        let dct = if self.model.mindlin {
            let c = |ev: &Eval| self.model.spring(ev.depth).2 * ev.v_t;
            (c(&ep) - c(&em)) / (2.0 * h)
        } else {
            ct * (ep.v_t - em.v_t) / (2.0 * h)
        };
        self.mu * dfn + sg * (k_xi * rate * e.v_t + dct)
    }

    /// Fraction of `step` at which event `ev` first fires (its function turns positive),
    /// given that it fires at the end. Secant and bisection alternate on the dense output.
    fn locate(&self, m: &Mode, ev: Event, step: &Step, g1: f64) -> f64 {
        self.locate_in(m, ev, step, 0.0, 1.0, g1)
    }

    /// As [`Self::locate`], within [lo, hi] of the step, the event function positive at hi.
    fn locate_in(&self, m: &Mode, ev: Event, step: &Step, lo: f64, hi: f64, g1: f64) -> f64 {
        let g = |th: f64| self.event_value(m, ev, &step.at(th));
        let g0 = if lo == 0.0 {
            self.event_value(m, ev, &step.y0)
        } else {
            g(lo)
        };
        if g0 > 0.0 {
            return lo;
        }
        let (mut lo, mut hi, mut glo, mut ghi) = (lo, hi, g0, g1);
        for it in 0..200 {
            if hi - lo <= 1e-14 {
                break;
            }
            let mut th = if it % 2 == 0 && ghi > glo && glo.is_finite() && ghi.is_finite() {
                lo + (hi - lo) * (-glo) / (ghi - glo)
            } else {
                0.5 * (lo + hi)
            };
            let w = hi - lo;
            th = th.clamp(lo + 0.01 * w, hi - 0.01 * w);
            let gm = g(th);
            if gm > 0.0 {
                hi = th;
                ghi = gm;
            } else {
                lo = th;
                glo = gm;
            }
        }
        hi
    }

    /// The corners below the plate when a polygon first touches: the lowest one and its
    /// neighbours that are not above the plate.
    fn initial_run(&self, y: f64, phi: f64) -> Touch {
        let n = self.verts.len();
        let sc = phi.sin_cos();
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
    fn initial_tan(&self, m: &Mode, s: &State) -> Tan {
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

fn kinetic_energy(model: &Model, s: &State) -> f64 {
    0.5 * model.mass * (s[VX] * s[VX] + s[VY] * s[VY]) + 0.5 * model.inertia * s[OM] * s[OM]
}

/// Bookkeeping of one impact that is not part of the ODE state.
#[derive(Default)]
struct Tally {
    contact_start: f64,
    contact_time: f64,
    contacts: u32,
    slip_events: u64,
    stuck: bool,
    max_depth: f64,
    max_area: f64,
}

/// Smallest error scale of a velocity component, relative to the impact's speed.
const SCALE_FLOOR: f64 = 1e-3;

/// Steps after a disc's touch whose error is estimated by step halving (see
/// `Reference::singular_error`): the steps grow at most 5-fold, so these cover the first
/// ~150 lengths of the first step.
const SINGULAR_STEPS: u32 = 4;

/// Consecutive zero-length pieces after which a step ignores its events (see `integrate`).
const MAX_ZERO_PIECES: u32 = 64;

/// Into how many parts a step is cut to look for an event that may fire and clear again
/// inside it (its function positive only in the middle), or `None` for events whose function
/// is monotone over a step.
fn interior_samples(ev: Event) -> Option<usize> {
    match ev {
        Event::EnterLeft | Event::EnterRight | Event::Touch => Some(8),
        Event::ToStick | Event::ToSlip => Some(4),
        _ => None,
    }
}

/// The error scale of each state component, from the impact's own scales (so that a scene
/// rescaled with its dimensionless groups fixed takes the same steps): the velocities' are
/// the incident ones the outputs are relative to (|vx| for e_T, |vy| for e_N, v / r for the
/// spin; the speed where a component is zero), the positions' what those velocities cover
/// in t_c / pi, the spring's the force that moves vx in t_c, the works' the energy.
fn error_scales(model: &Model, init: &Initial, speed: f64, t_est: f64, energy: f64) -> State {
    let r = model.r;
    let v_in = init.vx.hypot(init.vy);
    // Floored at 1e-3 of the speed (spin included): a component far below the others (a
    // grazing impact's v_y, a spinning body's v_x) cannot be followed to `tol` of itself in
    // double precision, and asking for it costs millions of steps (a triangle at 0.01 deg and
    // 1e4 deg/s took 3e7). Over the study's grid (theta >= 4 deg) no floor is reached.
    let or_speed = |x: f64| x.clamp(SCALE_FLOOR * speed, speed);
    let mut scale = [0.0; NS];
    scale[VX] = or_speed(init.vx.abs());
    scale[VY] = or_speed(init.vy.abs());
    scale[OM] = or_speed(v_in) / r;
    let t_c = t_est / PI;
    scale[X] = scale[VX] * t_c;
    scale[Y] = scale[VY] * t_c;
    scale[PHI] = scale[OM] * t_c;
    // Mindlin's xi is a force (section 14.4).
    let force_scale = model.mass * scale[VX] / t_est;
    scale[XI] = force_scale / if model.mindlin { 1.0 } else { model.kt };
    scale[W_EL] = energy;
    scale[W_D] = energy;
    scale[W_T] = energy;
    scale
}

/// `err_est` from the local error estimates accumulated over the accepted steps (root sum of
/// squares, components VX, VY, OM): the largest over e_N, e_T, e_kin and omega_out r / v.
fn error_estimate(acc: &State, init: &Initial, r: f64) -> f64 {
    let v_in = init.vx.hypot(init.vy);
    let e_t = if init.vx != 0.0 {
        acc[VX] / init.vx.abs()
    } else {
        0.0
    };
    let e_n = acc[VY] / init.vy.abs();
    let e_kin = acc[VX].hypot(acc[VY]) / v_in;
    let spin = acc[OM] * r / v_in;
    ERR_EST_FACTOR * e_t.max(e_n).max(e_kin).max(spin)
}

/// Integrates one impact from first touch (validated scene and initial state).
pub(crate) fn integrate(
    model: &Model,
    init: &Initial,
    depth_est: f64,
    opts: &ReferenceOptions,
    mut trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let shape = &model.scene.shape;
    let r = model.r;
    let speed = init.vx.hypot(init.vy) + r * init.omega.abs();
    let t_est = PI * depth_est / init.vy.abs();
    let h_max = opts.max_step_factor.unwrap_or(model.scene.dt_factor) * model.t_ref;
    let energy_in = 0.5 * model.mass * (init.vx * init.vx + init.vy * init.vy)
        + 0.5 * model.inertia * init.omega * init.omega;
    let scale = error_scales(model, init, speed, t_est, energy_in);
    let verts = shape.vertices();
    let ode = Reference {
        model,
        verts,
        mu: model.scene.mu,
        scale,
        tol: opts.tol,
        fd_step: 1e-5 * t_est,
        force_tol: opts.tol * model.mass * speed / t_est,
    };
    let t_end = TIMEOUT_CONTACT_TIMES * t_est;
    // The step budget (attempts, rejected steps included): steps may be much shorter than
    // h_max while a turning polygon brings corner after corner to the plate (counted in N_c),
    // but an explicit method crawls through a damper much stiffer than the contact (a
    // spinning triangle at gamma = 10 takes steps of 1e-7 t_ref): such scenes end as timed
    // out.
    let max_steps = budget_for(
        model,
        reference_contact_steps(model, init, depth_est, h_max, opts.tol),
    );
    // Pieces shorter than this are negligible (for chattering and for slip counting).
    let tiny = 1e-9 * t_est;
    let n_corners = verts.len();

    let mut s: State = [0.0; NS];
    s[Y] = shape.touch_height(init.phi0);
    s[PHI] = init.phi0;
    s[VX] = init.vx;
    s[VY] = init.vy;
    s[OM] = init.omega;
    let touch = match shape {
        Shape::Disc { .. } | Shape::Sphere { .. } => Touch::Disc,
        Shape::Polygon(_) => ode.initial_run(s[Y], s[PHI]),
    };
    let mut mode = Mode {
        touch,
        clip_on: true,
        clip_hold: false,
        tan: Tan::None,
    };
    mode.tan = ode.initial_tan(&mode, &s);
    let mut tally = Tally {
        contacts: 1,
        ..Tally::default()
    };
    let mut t = 0.0;
    let mut steps: u64 = 0;
    let mut attempts: u64 = 0;
    let mut h = h_max;
    let mut zero_pieces = 0u32;
    // Consecutive negligible pieces ended by a stick/slip switch, and by a clip switch.
    let (mut chatter_t, mut chatter_c) = (0u32, 0u32);
    let mut hold_tangential = false;
    let mut stop = StopReason::Separated;
    let mut err_acc: State = [0.0; NS];
    // The first step of a contact starts at a point where the disc's force is not smooth.
    let mut fresh_touch = true;
    // Steps taken since the last touch: the first few still see the force's root singularity.
    let mut since_touch = 0u32;

    let (mut k1, e0) = ode.eval(&mode, &s);
    if let Some(tr) = trace.as_deref_mut() {
        push(tr, 0.0, &s, &e0, ode.xi_of(&mode, &s, &e0));
    }
    loop {
        // Done once no part of the particle can reach the plate: its circumscribed circle is
        // clear and moving away, or every point of it moves away (v_y > r |omega|).
        if mode.touch == Touch::Off && s[VY] > 0.0 && (s[Y] >= r || s[VY] > r * s[OM].abs()) {
            break;
        }
        cancel.poll(attempts)?;
        if attempts >= max_steps {
            stop = StopReason::StepBudget;
            break;
        }
        if t >= t_end {
            stop = StopReason::ContactTimeBudget;
            break;
        }
        h = h
            .min(h_max)
            .min(ode.singular_cap(&mode, &s, fresh_touch, t_est));
        if n_corners > 0 && s[OM] != 0.0 {
            // A turning polygon brings corners to the plate: step finely enough (a quarter of
            // the angle between corners) that no corner touches and leaves within one step,
            // in flight (a missed re-contact) and in contact (a stale set of submerged corners).
            h = h.min(0.25 * (2.0 * PI / n_corners as f64) / s[OM].abs());
        }
        let (step, err) = ode.dp_step(&mode, &s, &k1, h);
        attempts += 1;
        let h_min = 1e-13 * t_est;
        if !err.is_finite() {
            // Never accept a non-finite state: shrink hard and retry; if even the smallest
            // step fails, stop with the last finite state and say so.
            if h > h_min {
                h = (0.1 * h).max(h_min);
                continue;
            }
            stop = StopReason::NonFinite;
            break;
        }
        if err > 1.0 && h > h_min {
            h = (h * (0.9 * err.powf(-0.2)).max(0.2)).max(h_min);
            continue;
        }
        let h_next = h * (0.9 * err.max(1e-10).powf(-0.2)).clamp(0.2, 5.0);
        // Events: the earliest switch inside the step ends the piece there.
        let mut first: Option<(f64, Event)> = None;
        let mut leaving: Option<f64> = None;
        // The last resort against a loop of zero-length pieces: well above the chatter
        // counts (16), whose remedies (the sliding modes below) must act first; at 16 a
        // tangential chatter once switched every event off and the step crossed the clip
        // with the plate pulling (the disc at theta 34, mu 0.6: e_N off by 1.2e-4).
        if zero_pieces < MAX_ZERO_PIECES {
            for ev in ode.candidates(&mode) {
                if hold_tangential && matches!(ev, Event::ToSlip | Event::ToStick) {
                    continue;
                }
                let g1 = ode.event_value(&mode, ev, &step.y1);
                let found = if g1 > 0.0 {
                    Some(ode.locate(&mode, ev, &step, g1))
                } else if let (Event::ClipOff, Some(c)) = (ev, step.pull) {
                    // A stage saw the plate pull although the end state does not: the clip
                    // switched inside the step (and back, in the held continuation); find
                    // where, on the dense output up to that stage.
                    (1..=16).map(|k| c * k as f64 / 16.0).find_map(|th| {
                        let g = ode.event_value(&mode, ev, &step.at(th));
                        let lo = th - c / 16.0;
                        (g > 0.0).then(|| ode.locate_in(&mode, ev, &step, lo, th, g))
                    })
                } else if let Some(parts) = interior_samples(ev) {
                    // A corner may dip below the plate and rise again within one step (a
                    // grazing corner beside the chord), a short stick phase may begin and
                    // end within one (the disc at theta 54, mu 0.7 at tol 1e-6 missed one:
                    // e_T off by 2e-4): look inside the step too.
                    let w = 1.0 / parts as f64;
                    (1..parts).map(|k| k as f64 * w).find_map(|th| {
                        let g = ode.event_value(&mode, ev, &step.at(th));
                        (g > 0.0).then(|| ode.locate_in(&mode, ev, &step, th - w, th, g))
                    })
                } else {
                    None
                };
                if let Some(th) = found {
                    if matches!(ev, Event::LeaveLeft | Event::LeaveRight | Event::Separate) {
                        leaving = Some(th);
                    }
                    if first.is_none_or(|(t0, _)| th < t0) {
                        first = Some((th, ev));
                    }
                }
            }
        }
        // Whatever ends the step first, a corner that leaves inside it may leave after the
        // clip switched off, which the step's end state (past the leave point) cannot show.
        if let Some(clip) = leaving.and_then(|th| ode.clip_before_leaving(&mode, &step, th)) {
            if first.is_none_or(|(t0, _)| clip.0 < t0) {
                first = Some(clip);
            }
        }
        if let Some(c) = step.pull.filter(|_| zero_pieces < MAX_ZERO_PIECES) {
            if first.is_none_or(|(th, _)| th > c) && h > h_min {
                // The step crossed a clip switch that its dense output does not show: never
                // integrate across it with the unclipped, pulling force; shorten the step.
                h = (0.5 * c * h).max(h_min);
                continue;
            }
        }
        let (s_new, h_taken, event, err_taken) = match first {
            None => (step.y1, h, None, step.err),
            Some((th, ev)) if th >= 1.0 => (step.y1, h, Some(ev), step.err),
            Some((th, ev)) if th * h <= 0.0 => (s, 0.0, Some(ev), [0.0; NS]),
            Some((th, ev)) => {
                // Redo the step to the switch so the state there has full Runge-Kutta accuracy.
                let (st, _) = ode.dp_step(&mode, &s, &k1, th * h);
                (st.y1, th * h, Some(ev), st.err)
            }
        };
        let near_touch = since_touch < SINGULAR_STEPS;
        let singular = ode.singular_error(&mode, &s, &k1, h_taken, &s_new, near_touch, event);
        for i in [VX, VY, OM] {
            // In quadrature: the local errors' signs vary along an impact (summed, their
            // absolute values overstated the error 15-fold at tol 1e-4 and 124-fold at 1e-10).
            err_acc[i] += (err_taken[i].abs() + singular[i]).powi(2);
        }
        if event.is_none() {
            zero_pieces = 0;
        }
        hold_tangential = false;
        match event {
            Some(Event::ToSlip | Event::ToStick) if h_taken < tiny => chatter_t += 1,
            Some(Event::ClipOn | Event::ClipOff) if h_taken < tiny => chatter_c += 1,
            _ if h_taken >= tiny => (chatter_t, chatter_c) = (0, 0),
            _ => {}
        }
        if h_taken > 0.0 {
            fresh_touch = false;
            since_touch += 1;
            steps += 1;
            zero_pieces = 0;
            // Only a stick phase of some length counts for slip events: a guess of stick at
            // first touch that the events correct at once, chattering, or the disc's stick of
            // ~1e-9 t_c just after touch (the damping's rate, like t^(-1/2), opens the Coulomb
            // cone faster than the spring loads; seen once the steps are searched inside) is
            // no micro-slip.
            tally.stuck |= mode.tan == Tan::Stick && h_taken >= 1e-6 * t_est;
            // The deepest point inside the step (where the depth stops growing).
            track_extremes(&ode, &mode, &step, h_taken / h, &mut tally);
        } else {
            zero_pieces += 1;
        }
        t += h_taken;
        s = s_new;
        if mode.clip_hold {
            // The held step is done: the end state decides the clip again.
            mode.clip_hold = false;
            if ode.eval(&mode, &s).1.fn_raw > 0.0 {
                mode.clip_on = true;
                mode.tan = ode.initial_tan(&mode, &s);
            }
        }
        if let Some(ev) = event {
            fresh_touch |= ev == Event::Touch;
            if ev == Event::Touch {
                since_touch = 0;
            }
            apply(&ode, &mut mode, ev, &mut s, t, &mut tally);
        }
        if chatter_c >= 16 && !mode.clip_on {
            // The clip switches on and off at once: a damper much stiffer than the contact
            // holds F_el + F_d at zero (a sliding mode), so the force is about zero too. Take
            // one step without it; an explicit method could not follow the damper anyway.
            mode.clip_hold = true;
            chatter_c = 0;
        }
        if chatter_t >= 16 {
            // Stick and slip each end at once: the motion slides along |F_trial| = mu F_n
            // (a Filippov sliding mode), whose force law is slip's. Take one step in slip.
            if mode.tan == Tan::Stick {
                let e = ode.eval(&mode, &s).1;
                let sg = if e.trial != 0.0 {
                    e.trial.signum()
                } else {
                    -e.v_t.signum()
                };
                mode.tan = Tan::Slip(sg);
                let (kt, _, ct) = model.spring(e.depth);
                s[XI] = -(ode.mu * e.forces.fy * sg + ct * e.v_t) / kt;
            }
            hold_tangential = true;
            chatter_t = 0;
        }
        let (k, e) = ode.eval(&mode, &s);
        k1 = k;
        tally.max_depth = tally.max_depth.max(e.depth);
        if let Some(o) = e.forces.overlap {
            tally.max_area = tally.max_area.max(o.area);
        }
        if let Some(tr) = trace.as_deref_mut() {
            if h_taken > 0.0 {
                push(tr, t, &s, &e, ode.xi_of(&mode, &s, &e));
            }
        }
        h = if event.is_some() {
            h_next.min(h)
        } else {
            h_next
        };
    }
    if mode.touch != Touch::Off {
        tally.contact_time += t - tally.contact_start;
    }
    let energy_out = kinetic_energy(model, &s);
    let work_normal = s[W_EL] + s[W_D];
    let work_friction = s[W_T];
    let (vx, vy, om) = (s[VX], s[VY], s[OM]);
    let v_cp = init.vx + r * init.omega;
    Ok(Record {
        e_n: -vy / init.vy,
        e_t: (init.vx != 0.0).then(|| vx / init.vx),
        e_kin: vx.hypot(vy) / init.vx.hypot(init.vy),
        omega_out: om,
        beta: (v_cp != 0.0).then(|| -(vx + r * om) / v_cp),
        rebound_angle_deg: vy.atan2(vx).to_degrees(),
        vx_out: vx,
        vy_out: vy,
        contact_time: tally.contact_time,
        steps,
        contacts: tally.contacts,
        max_depth: tally.max_depth,
        max_area: tally.max_area,
        slip_events: tally.slip_events,
        energy_in,
        energy_out,
        work_normal,
        work_friction,
        energy_residual: (energy_out - energy_in - work_normal - work_friction) / energy_in,
        separated: stop == StopReason::Separated,
        timed_out: stop != StopReason::Separated,
        step_budget: max_steps,
        stop,
        err_est: Some(error_estimate(&err_acc.map(f64::sqrt), init, r)),
    })
}

/// Updates the largest depth and area with their maxima inside the taken part of a step:
/// where a parabola through three samples peaks inside the step, a golden-section search on
/// the dense output finds the peak (the depth peaks where its rate changes sign).
fn track_extremes(ode: &Reference, m: &Mode, step: &Step, frac: f64, tally: &mut Tally) {
    if m.touch == Touch::Off {
        return;
    }
    let sample = |th: f64| {
        let e = ode.eval(m, &step.at(th)).1;
        [e.depth, e.forces.overlap.map_or(0.0, |o| o.area)]
    };
    let ends = [sample(0.0), sample(0.5 * frac), sample(frac)];
    for (k, best) in [&mut tally.max_depth, &mut tally.max_area]
        .into_iter()
        .enumerate()
    {
        let f3 = [ends[0][k], ends[1][k], ends[2][k]];
        *best = best.max(peak(|th| sample(th)[k], f3, frac));
    }
}

/// Largest value of `f` on [0, frac] when it peaks inside, given its values at 0, frac / 2 and
/// frac; -inf otherwise (the ends are recorded as step ends).
fn peak(f: impl Fn(f64) -> f64, [f0, fm, f1]: [f64; 3], frac: f64) -> f64 {
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
    let (mut a, mut b) = (0.0, frac);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..80 {
        if b - a <= 1e-15 * frac.max(1e-300) {
            break;
        }
        if fc > fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    fc.max(fd).max(f0).max(f1)
}

/// Switches the mode at an event and sets the algebraic part of the state.
fn apply(ode: &Reference, m: &mut Mode, ev: Event, s: &mut State, t: f64, tally: &mut Tally) {
    let model = ode.model;
    let n = ode.verts.len().max(1);
    let e = ode.eval(m, s).1;
    let (kt, _, ct) = model.spring(e.depth);
    match ev {
        Event::Touch => {
            m.touch = match model.scene.shape {
                Shape::Disc { .. } | Shape::Sphere { .. } => Touch::Disc,
                Shape::Polygon(_) => ode.initial_run(s[Y], s[PHI]),
            };
            m.clip_on = true;
            s[XI] = 0.0;
            m.tan = Tan::None;
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
            m.clip_on = false;
            if ode.mu > 0.0 {
                m.tan = Tan::Free;
                s[XI] = -ct * e.v_t / kt;
            }
        }
        Event::ClipOn => {
            m.clip_on = true;
            m.tan = ode.initial_tan(m, s);
        }
        Event::ToSlip => {
            let sg = if e.trial != 0.0 {
                e.trial.signum()
            } else {
                -e.v_t.signum()
            };
            m.tan = Tan::Slip(sg);
            s[XI] = -(ode.mu * e.forces.fy * sg + ct * e.v_t) / kt;
            if tally.stuck {
                tally.slip_events += 1;
            }
        }
        Event::ToStick => {
            // The spring takes over the force it carried while slipping.
            s[XI] = -(e.forces.f_t + ct * e.v_t) / kt;
            m.tan = Tan::Stick;
        }
    }
}

fn separate(m: &mut Mode, s: &mut State, t: f64, tally: &mut Tally) {
    m.touch = Touch::Off;
    m.clip_on = false;
    m.tan = Tan::None;
    s[XI] = 0.0;
    tally.contact_time += t - tally.contact_start;
}

fn push(tr: &mut Trace, t: f64, s: &State, e: &Eval, xi: f64) {
    tr.t.push(t);
    tr.x.push(s[X]);
    tr.y.push(s[Y]);
    tr.phi.push(s[PHI]);
    tr.vx.push(s[VX]);
    tr.vy.push(s[VY]);
    tr.omega.push(s[OM]);
    tr.f_n.push(e.forces.f_el + e.forces.f_d);
    tr.f_t.push(e.forces.f_t);
    tr.area.push(e.forces.overlap.map_or(0.0, |o| o.area));
    tr.depth.push(e.depth);
    tr.stick.push(e.forces.stick.code());
    tr.xi.push(xi);
}
