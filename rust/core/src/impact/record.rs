//! What one impact returns: the [`Record`] (the public names of the model), the optional
//! per-step [`Trace`], and the estimates every integrator starts from (the largest depth and
//! the contact's time budget). Shared by the fixed-step loop and the adaptive path, so that
//! neither depends on the other.

use crate::error::{Error, Result};
use crate::law::pair::{Lanes, PairForces};
use crate::law::{Dof, Forces};
use crate::model::{Initial, Model, NormalLaw, Pair};
use crate::numerics::roots;
use crate::numerics::trig::sin_cos;

/// A contact that has not ended after this many estimated contact times is stopped
/// ([`StopReason::ContactTimeBudget`]).
pub const TIMEOUT_CONTACT_TIMES: f64 = 100.0;

/// Why an impact ended. Every reason but [`StopReason::Separated`] sets `timed_out`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum StopReason {
    /// The particle left the plate and no part of it can reach the plate again.
    #[default]
    Separated,
    /// The impact used its step budget (`Scene::max_steps`, or the default budget
    /// [`crate::impact::default_step_budget`]) before it separated.
    StepBudget,
    /// The contact lasted [`TIMEOUT_CONTACT_TIMES`] estimated contact times (fixed-step
    /// integrators: counted in contact time; the reference integrator: in elapsed time).
    ContactTimeBudget,
    /// The reference integrator met a non-finite state even at its smallest step and stopped
    /// at the last finite one.
    NonFinite,
}

impl StopReason {
    /// Every reason, in code order (the code of a reason is its index here).
    pub const ALL: [StopReason; 4] = [
        StopReason::Separated,
        StopReason::StepBudget,
        StopReason::ContactTimeBudget,
        StopReason::NonFinite,
    ];

    /// Public name, as in the Python API.
    pub fn name(self) -> &'static str {
        match self {
            StopReason::Separated => "separated",
            StopReason::StepBudget => "step_budget",
            StopReason::ContactTimeBudget => "contact_time_budget",
            StopReason::NonFinite => "non_finite",
        }
    }

    /// Its index in [`StopReason::ALL`].
    pub fn code(&self) -> u8 {
        *self as u8
    }
}

/// What one impact returns (public names; definitions in docs/model.md, section 9).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Record {
    /// Normal restitution -vy' / vy.
    pub e_n: f64,
    /// Tangential restitution vx' / vx of the centre of mass; `None` when vx = 0.
    pub e_t: Option<f64>,
    /// Kinematic restitution |v'| / |v|.
    pub e_kin: f64,
    /// Spin after the impact (rad/s).
    pub omega_out: f64,
    /// Contact-point restitution -v_cp' / v_cp, v_cp = vx + r omega; `None` when v_cp = 0.
    pub beta: Option<f64>,
    /// atan2(vy', vx') in degrees.
    pub rebound_angle_deg: f64,
    /// Velocity after the impact (m/s).
    pub vx_out: f64,
    /// See `vx_out`.
    pub vy_out: f64,
    /// Time with overlap, summed over contacts, crossings interpolated linearly (s).
    pub contact_time: f64,
    /// Integration steps from first touch to the end (the reference integrator: accepted
    /// steps; its budget counts rejected ones too).
    pub steps: u64,
    /// The step budget this impact ran under (`Scene::max_steps` or the default budget,
    /// [`crate::impact::step_budget`]): `steps <= step_budget` always.
    pub step_budget: u64,
    /// Number of contacts (re-contacts of a spinning polygon belong to the same impact).
    pub contacts: u32,
    /// Largest depth of the lowest point below the plate (m).
    pub max_depth: f64,
    /// Largest overlap area (m^2).
    pub max_area: f64,
    /// Stick to slip transitions.
    pub slip_events: u64,
    /// Kinetic energy (translation + rotation) before the impact (J/m).
    pub energy_in: f64,
    /// Kinetic energy after the impact (J/m).
    pub energy_out: f64,
    /// Work of the normal force on the body, elastic and damping parts (J/m, <= 0 up to
    /// integration error where the law has a potential; see `work_damping`).
    pub work_normal: f64,
    /// Work of the tangential force on the body (J/m, <= 0 up to integration error).
    pub work_friction: f64,
    /// The part of `work_normal` done by the normal force's dashpot (J/m, <= 0 up to
    /// integration error); the rest, `work_normal - work_damping`, is the elastic force's: <= 0
    /// for a law with a potential (the clip drops the energy stored when it switches the force
    /// off), of either sign for the area law between bodies with corners (docs/model.md 17.8).
    pub work_damping: f64,
    /// (energy_out - energy_in - work_normal - work_friction) / energy_in.
    pub energy_residual: f64,
    /// The particle left the plate and cleared it.
    pub separated: bool,
    /// Stopped before separating, by a budget: `stop` says which.
    pub timed_out: bool,
    /// Why the impact ended (`timed_out` is `stop != Separated`).
    pub stop: StopReason,
    /// Estimated largest absolute error among e_N, e_T, e_kin and omega_out r / v (v the
    /// impact speed): the adaptive path's from its local error estimates, a fixed-step
    /// integrator's from a second run at half the step when `Scene::error_estimate` is set;
    /// `None` otherwise (and when the half-step run did not finish).
    pub err_est: Option<f64>,
    /// Normal restitution with the normal at separation: -(g' . n_s) / (g . n_0) (a pair;
    /// the plate's normal never turns, so there it is `e_n`).
    pub e_n_sep: f64,
    /// The angle from the normal at first touch to the normal at separation (degrees,
    /// counter-clockwise positive; 0 on the plate).
    pub normal_rotation_deg: f64,
    /// The partner's spin after the impact (rad/s; 0 for the plate).
    pub partner_omega_out: f64,
    /// The partner's velocity after the impact, in the frame where it was at rest before
    /// (m/s; 0 for the plate).
    pub partner_vx_out: f64,
    /// See `partner_vx_out`.
    pub partner_vy_out: f64,
    /// Linear momentum after minus before, over m* v (a pair; `None` for the plate, which
    /// takes momentum).
    pub momentum_residual: Option<f64>,
    /// Angular momentum about the pair's centre of mass after minus before, over
    /// m* v (r1 + r2) (a pair; `None` for the plate).
    pub angular_momentum_residual: Option<f64>,
}

/// The two bodies of an impact as its record reads them: the particle on the plate (a partner
/// of infinite mass that never moves), or a pair in its centre-of-mass frame.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Bodies<'a> {
    /// The particle on the plate.
    Plate(&'a Model),
    /// The particle and its partner.
    Pair(&'a Pair),
}

/// Where an impact ended: the relative lanes (x, y, phi1, phi2) and their rates (the plate:
/// the particle's x, y, phi, a fourth lane at rest), the centres' distance at first touch and
/// the normal at separation (the plate's never turns from +y).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ending {
    /// Final positions.
    pub q: Lanes,
    /// Final velocities.
    pub v: Lanes,
    /// The centres' distance at first touch (a pair's angular momentum before).
    pub y0: f64,
    /// The unit normal at separation.
    pub n_sep: [f64; 2],
}

impl Ending {
    /// The end of an impact on the plate at position `q` and velocity `v` = (vx, vy, omega).
    pub(crate) fn on_plate(q: &Dof, v: &Dof) -> Self {
        Ending {
            q: [q[0], q[1], q[2], 0.0],
            v: [v[0], v[1], v[2], 0.0],
            y0: 0.0,
            n_sep: [0.0, 1.0],
        }
    }
}

impl Bodies<'_> {
    /// Kinetic energy at the (relative) lane velocities `v`.
    fn kinetic_energy(&self, v: &Lanes) -> f64 {
        match self {
            Bodies::Plate(model) => model.kinetic_energy(&[v[0], v[1], v[2]]),
            Bodies::Pair(pair) => pair.kinetic_energy(v),
        }
    }

    /// The radii of the two bodies' contact-point levers (the plate's is 0).
    fn radii(&self) -> (f64, f64) {
        match self {
            Bodies::Plate(model) => (model.r, 0.0),
            Bodies::Pair(pair) => (pair.particle.r, pair.r2),
        }
    }
}

impl Record {
    /// Completes the record of an impact from `init` that ended at `end`: the restitution
    /// coefficients and the rest of the outputs, the energy after it and the balance's
    /// residual (`energy_in`, the works and `stop` already set). Every integrator ends here,
    /// on the plate and on a pair, so the outputs have one definition: the plate's record is
    /// the pair's with an immovable partner (no partner motion, no momentum balance, the
    /// normal never turning).
    pub(crate) fn close(&mut self, bodies: &Bodies, init: &Initial, end: &Ending) {
        let (v, ns) = (&end.v, end.n_sep);
        let g0 = [init.vx, init.vy];
        self.energy_out = bodies.kinetic_energy(v);
        self.energy_residual =
            (self.energy_out - self.energy_in - self.work_normal - self.work_friction)
                / self.energy_in;
        self.e_n = -v[1] / g0[1];
        self.e_n_sep = -(v[0] * ns[0] + v[1] * ns[1]) / g0[1];
        // 0 - n_x: the plate's normal turns by +0 degrees, not -0.
        self.normal_rotation_deg = (0.0 - ns[0]).atan2(ns[1]).to_degrees();
        self.e_t = (g0[0] != 0.0).then(|| v[0] / g0[0]);
        self.e_kin = v[0].hypot(v[1]) / g0[0].hypot(g0[1]);
        self.omega_out = v[2];
        self.partner_omega_out = v[3];
        let (r1, r2) = bodies.radii();
        let partner_omega = match bodies {
            Bodies::Plate(_) => 0.0,
            Bodies::Pair(_) => init.partner_omega,
        };
        let v_cp = g0[0] + r1 * init.omega + r2 * partner_omega;
        self.beta = (v_cp != 0.0).then(|| -(v[0] + r1 * v[2] + r2 * v[3]) / v_cp);
        self.rebound_angle_deg = v[1].atan2(v[0]).to_degrees();
        (self.vx_out, self.vy_out) = (v[0], v[1]);
        if let Bodies::Pair(pair) = bodies {
            self.close_momenta(pair, init, end);
        }
        self.timed_out = self.stop != StopReason::Separated;
        self.separated = !self.timed_out;
    }

    /// A pair's lab velocities (in the frame where the partner was at rest: the centre of
    /// mass moves at m1 g0 / M throughout) and the residuals of its momenta, each relative to
    /// the largest momentum in its balance (`momentum_scales`).
    fn close_momenta(&mut self, pair: &Pair, init: &Initial, end: &Ending) {
        let (m1, m2) = (pair.particle.mass, pair.m2);
        let (q, v) = (&end.q, &end.v);
        let g0 = [init.vx, init.vy];
        let total = m1 + m2;
        let cm = [m1 * g0[0] / total, m1 * g0[1] / total];
        let v1 = [cm[0] + m2 / total * v[0], cm[1] + m2 / total * v[1]];
        let v2 = [cm[0] - m1 / total * v[0], cm[1] - m1 / total * v[1]];
        (self.vx_out, self.vy_out) = (v1[0], v1[1]);
        (self.partner_vx_out, self.partner_vy_out) = (v2[0], v2[1]);
        let p = [
            m1 * v1[0] + m2 * v2[0] - m1 * g0[0],
            m1 * v1[1] + m2 * v2[1] - m1 * g0[1],
        ];
        let q_in = [0.0, end.y0, 0.0, 0.0];
        let v_in = [g0[0], g0[1], init.omega, init.partner_omega];
        let (p_scale, l_scale) = momentum_scales(pair, [&q_in, q], [&v_in, v], [&v1, &v2]);
        self.momentum_residual = Some(p[0].hypot(p[1]) / p_scale);
        let l_in = pair.angular_momentum(&q_in, &v_in);
        let l_out = pair.angular_momentum(q, v);
        self.angular_momentum_residual = Some((l_out - l_in) / l_scale);
    }

    /// The four outputs whose error `err_est` bounds: e_N, e_T (0 when undefined), e_kin and
    /// omega_out r / v, v the impact speed `speed`.
    pub fn accuracy_outputs(&self, r: f64, speed: f64) -> [f64; 4] {
        [
            self.e_n,
            self.e_t.unwrap_or(0.0),
            self.e_kin,
            self.omega_out * r / speed,
        ]
    }

    /// The largest absolute difference between the four outputs of two records of the same
    /// impact ([`Record::accuracy_outputs`]).
    pub fn accuracy_distance(&self, other: &Record, r: f64, speed: f64) -> f64 {
        let (a, b) = (
            self.accuracy_outputs(r, speed),
            other.accuracy_outputs(r, speed),
        );
        (0..4).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
    }
}

/// The yardsticks of a pair's momentum residuals: the largest momentum in the balance (the
/// particle's before, m1 |g0|, which is the pair's whole momentum, and each body's after) and
/// the largest term of the angular momentum about the centre of mass (m* |r x g|, I1 |omega1|,
/// I2 |omega2|, before and after), each at least the pair's own scale m* v (times r1 + r2).
/// Relative to m* v alone, a body 4e5 times heavier than the other showed the round-off of its
/// own momentum, m_big / m* times larger, as a residual of 1.6e-10 (docs/model.md 17.4).
fn momentum_scales(
    pair: &Pair,
    q: [&[f64; 4]; 2],
    v: [&[f64; 4]; 2],
    lab: [&[f64; 2]; 2],
) -> (f64, f64) {
    let (m1, m2, ms) = (pair.particle.mass, pair.m2, pair.m_star);
    let speed = v[0][0].hypot(v[0][1]);
    let p_scale = (m1 * speed)
        .max(m1 * lab[0][0].hypot(lab[0][1]))
        .max(m2 * lab[1][0].hypot(lab[1][1]));
    let reach = pair.particle.r + pair.r2;
    let l_terms = |q: &[f64; 4], v: &[f64; 4]| {
        (ms * (q[0] * v[1] - q[1] * v[0]).abs())
            .max(pair.particle.inertia * v[2].abs())
            .max(pair.i2 * v[3].abs())
    };
    let l_scale = (ms * speed * reach)
        .max(l_terms(q[0], v[0]))
        .max(l_terms(q[1], v[1]));
    (p_scale, l_scale)
}

/// One value of a record column, as a binding stores it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Cell {
    /// A float.
    F64(f64),
    /// A float that may be undefined (e_t at theta = 90, beta when v_cp = 0).
    Opt(Option<f64>),
    /// A count.
    Int(u64),
    /// A flag.
    Bool(bool),
    /// A name (why the impact ended).
    Name(&'static str),
}

/// Names the record's columns and reads them, in one list: the schema every binding exports.
macro_rules! record_columns {
    ($($name:ident: $kind:ident $(as $cast:ty)? $(=> $map:path)?),* $(,)?) => {
        /// The record's column names, in output order (the public names of the model).
        pub const RECORD_COLUMNS: [&str; [$(stringify!($name)),*].len()] = [$(stringify!($name)),*];

        impl Record {
            /// The record's values in the order of [`RECORD_COLUMNS`].
            pub fn cells(&self) -> [Cell; RECORD_COLUMNS.len()] {
                [$(Cell::$kind($($map)?(self.$name $(as $cast)?))),*]
            }
        }
    };
}

record_columns! {
    e_n: F64, e_t: Opt, e_kin: F64, omega_out: F64, beta: Opt, rebound_angle_deg: F64,
    vx_out: F64, vy_out: F64, contact_time: F64, steps: Int, contacts: Int as u64,
    max_depth: F64, max_area: F64, slip_events: Int, energy_in: F64, energy_out: F64,
    work_normal: F64, work_friction: F64, energy_residual: F64, separated: Bool,
    timed_out: Bool, step_budget: Int, stop: Name => StopReason::name,
    err_est: Opt, e_n_sep: F64, normal_rotation_deg: F64, partner_omega_out: F64,
    partner_vx_out: F64, partner_vy_out: F64, momentum_residual: Opt,
    angular_momentum_residual: Opt, work_damping: F64,
}

/// The normal at separation of two round bodies: the direction of the centres' line where
/// they last were `reach` apart, found from the final state `q`, `v` by going back along the
/// free flight since (no force acts once apart; a timed-out impact keeps its current
/// direction).
pub(crate) fn separation_normal(q: &Lanes, v: &Lanes, reach: f64) -> [f64; 2] {
    let (x, y, gx, gy) = (q[0], q[1], v[0], v[1]);
    let (rg, g2, r2) = (x * gx + y * gy, gx * gx + gy * gy, x * x + y * y);
    let disc = rg * rg - g2 * (r2 - reach * reach);
    let tau = if r2 > reach * reach && g2 > 0.0 && disc >= 0.0 {
        (rg - disc.sqrt()) / g2
    } else {
        0.0
    };
    let (xs, ys) = (x - gx * tau, y - gy * tau);
    let d = xs.hypot(ys);
    [xs / d, ys / d]
}

/// Per-step history of one impact, as columns (one entry per step, the first at touch).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Trace {
    /// Time since first touch (s).
    pub t: Vec<f64>,
    /// Centre of mass x (m).
    pub x: Vec<f64>,
    /// Centre of mass y (m).
    pub y: Vec<f64>,
    /// Orientation (rad).
    pub phi: Vec<f64>,
    /// Velocity x (m/s).
    pub vx: Vec<f64>,
    /// Velocity y (m/s).
    pub vy: Vec<f64>,
    /// Spin (rad/s).
    pub omega: Vec<f64>,
    /// Normal force (N/m), clipped.
    pub f_n: Vec<f64>,
    /// Tangential force (N/m).
    pub f_t: Vec<f64>,
    /// Overlap area (m^2).
    pub area: Vec<f64>,
    /// Depth of the lowest point, negative when clear (m).
    pub depth: Vec<f64>,
    /// 0 no tangential contact, 1 stick, 2 slip.
    pub stick: Vec<u8>,
    /// Tangential spring elongation (m); for Mindlin's spring with its history kept as the
    /// force (the default), minus the elastic force (N; docs/model.md, 14.8).
    pub xi: Vec<f64>,
    /// A pair's partner: its orientation (rad) and spin (rad/s); 0 for the plate. (For a pair
    /// x, y, vx, vy are the particle's position and velocity relative to the partner, phi and
    /// omega its own; f_n and f_t act along the line of centres and across it.)
    pub partner_phi: Vec<f64>,
    /// See `partner_phi`.
    pub partner_omega: Vec<f64>,
}

impl Trace {
    pub(crate) fn push(&mut self, t: f64, q: &Dof, v: &Dof, f: &Forces, depth: f64, xi: f64) {
        self.t.push(t);
        self.x.push(q[0]);
        self.y.push(q[1]);
        self.phi.push(q[2]);
        self.vx.push(v[0]);
        self.vy.push(v[1]);
        self.omega.push(v[2]);
        self.f_n.push(f.f_el + f.f_d);
        self.f_t.push(f.f_t);
        self.area.push(f.overlap.map_or(0.0, |o| o.area));
        self.depth.push(depth);
        self.stick.push(f.stick.code());
        self.xi.push(xi);
        self.partner_phi.push(0.0);
        self.partner_omega.push(0.0);
    }

    /// Appends a pair's state (see `partner_phi`).
    pub(crate) fn push_pair(&mut self, t: f64, q: &Lanes, v: &Lanes, f: &PairForces, xi: f64) {
        self.t.push(t);
        self.x.push(q[0]);
        self.y.push(q[1]);
        self.phi.push(q[2]);
        self.vx.push(v[0]);
        self.vy.push(v[1]);
        self.omega.push(v[2]);
        self.f_n.push(f.f_el + f.f_d);
        self.f_t.push(f.f_t);
        self.area.push(f.area);
        self.depth.push(f.depth);
        self.stick.push(f.stick.code());
        self.xi.push(xi);
        self.partner_phi.push(q[3]);
        self.partner_omega.push(v[3]);
    }
}

/// Elastic potential of the normal law at depth `depth` below touch, orientation `phi`,
/// translation only (J/m; J for a sphere), and its rate with the depth (the elastic force).
fn normal_potential(model: &Model, depth: f64, phi: f64) -> (f64, f64) {
    match model.scene.normal_law {
        NormalLaw::Area => {
            // The first moment of the overlap about the plate rises with the depth at the
            // rate of its area.
            let shape = &model.scene.shape;
            let y = shape.touch_height(phi) - depth;
            let k = model.scene.e_modulus / model.length;
            shape
                .overlap(y, phi)
                .map_or((0.0, 0.0), |o| (k * o.first_moment, k * o.area))
        }
        NormalLaw::Linear { kn, .. } => {
            // One spring per corner below the plate (the disc: its lowest point).
            let shape = &model.scene.shape;
            let corners = shape.vertices();
            if corners.is_empty() {
                return (0.5 * kn * depth * depth, kn * depth);
            }
            let y = shape.touch_height(phi) - depth;
            let (s, c) = sin_cos(phi);
            corners
                .iter()
                .map(|p| (-(y + s * p.x + c * p.y)).max(0.0))
                .fold((0.0, 0.0), |(e, f), d| (e + 0.5 * kn * d * d, f + kn * d))
        }
        // The integral of 4/3 E* sqrt(R) delta^(3/2): 2/5 of it times delta.
        NormalLaw::Hertz { .. } => {
            let k = model.hertz.map_or(0.0, |h| h.k);
            let f = k * depth * depth.sqrt();
            (0.4 * f * depth, f)
        }
    }
}

/// Largest depth from the energy balance of the normal law without damping, and a check that
/// it stays below r / 2 (beyond that the overlap law describes no real contact).
pub fn estimate_max_depth(model: &Model, init: &Initial) -> Result<f64> {
    let ke_n = 0.5 * model.mass * init.vy * init.vy;
    let half_r = 0.5 * model.r;
    let (at_half, force_at_half) = normal_potential(model, half_r, init.phi0);
    if at_half < ke_n {
        let (stiff_name, stiff) = match model.scene.normal_law {
            NormalLaw::Area => ("E", model.scene.e_modulus),
            NormalLaw::Linear { kn, .. } => ("kn", kn),
            NormalLaw::Hertz { .. } => ("E", model.scene.e_modulus),
        };
        let v = (init.vx * init.vx + init.vy * init.vy).sqrt();
        let per = if model.scene.shape.is_sphere() {
            ""
        } else {
            "/m"
        };
        return Err(Error::invalid(
            "v",
            v,
            format!(
                "small enough that the estimated depth stays below r / 2 at {stiff_name} = {stiff:e} Pa \
                 (normal kinetic energy {ke_n:e} J{per} exceeds the elastic energy at depth r / 2: lower v or raise {stiff_name})"
            ),
        ));
    }
    // Every law is a power of the depth near touch (the disc's area law 3/2, Hertz 5/2, a
    // spring 2): Newton on the logarithms solves it in a few evaluations.
    Ok(roots::log_newton(
        |d| normal_potential(model, d, init.phi0),
        ke_n,
        half_r,
        (at_half, force_at_half),
    ))
}
