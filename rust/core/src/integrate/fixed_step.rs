//! Fixed-step integrators for up to four rigid-body degrees of freedom: (x, y, phi) of a
//! particle on the plate, or (x, y, phi1, phi2) of a pair in its centre-of-mass frame (the
//! relative position and both orientations). Both run on the same four lanes per term.
//!
//! Each step evaluates the contact law exactly once (the tangential spring is history
//! dependent, so every evaluation is a committed step).

use crate::law::{Contact, Dof, Forces, PlateGeometry};

/// Gear corrector coefficients for second-order equations with velocity-dependent forces.
const GEAR5_CORRECTOR: [f64; 6] = [
    3.0 / 16.0,
    251.0 / 360.0,
    1.0,
    11.0 / 18.0,
    1.0 / 6.0,
    1.0 / 60.0,
];

/// A fixed-step integrator over (x, y, phi).
///
/// Besides the fixed step, a stepper can shorten one step and restart on a new branch of the
/// contact law: [`crate::integrate::events`] uses this to land a step exactly on a touch, a separation or a
/// corner crossing of a polygon (where the force is not smooth) and to go on from there with
/// the new branch's acceleration and jerk instead of extrapolating the old branch.
pub trait Stepper: Clone {
    /// Whether the works of the forces need a quadrature of higher order than the trapezoid
    /// when the integrator restarts at events (Gear-5: its energy is then accurate to far
    /// below the trapezoid's error). Verlet's velocity update is itself a trapezoid of the
    /// forces, so the trapezoid closes its energy balance.
    const HIGH_ORDER: bool;
    /// A fresh integrator at position `q` and velocity `v` with step `dt`, no force acting
    /// (at first touch, and after a free flight jumped over).
    fn start(q: Dof, v: Dof, dt: f64) -> Self;
    /// A fresh integrator over all four lanes (a pair: x, y, phi1, phi2 and their rates).
    fn start_lanes(q: Lanes, v: Lanes, dt: f64) -> Self;
    /// Advances one step of `dt`: `law` gives the generalised forces at the integrator's
    /// predicted position and velocity (and what else it reports, returned); `inv_mass` turns
    /// each lane's force into its acceleration.
    fn advance<L: LaneForces>(&mut self, dt: f64, inv_mass: &Lanes, law: L) -> L::Out;
    /// Advances one step of `dt` of a particle on the plate, returning the forces used.
    #[inline(always)]
    fn step<G: PlateGeometry>(
        &mut self,
        contact: &mut Contact<G>,
        dt: f64,
        inv_mass: &Dof,
    ) -> Forces {
        let inv_mass = [inv_mass[0], inv_mass[1], inv_mass[2], 0.0];
        self.advance(dt, &inv_mass, OnPlate { contact, dt })
    }
    /// Current position and velocity in all four lanes.
    fn lanes(&self) -> (Lanes, Lanes);
    /// Current position.
    fn position(&self) -> Dof;
    /// Current velocity.
    fn velocity(&self) -> Dof;
    /// Position at fraction `s` (0..1) of the coming step, along the integrator's own
    /// prediction (the polynomial it would evaluate the force on).
    fn path(&self, s: f64) -> Dof;
    /// Acceleration the integrator currently carries.
    fn acceleration(&self) -> Dof;
    /// Continues the same local solution with step `h` instead.
    fn resize(&mut self, h: f64);
    /// Restarts from the current position and velocity on a new branch of the force law, with
    /// its acceleration `a` and jerk `jerk` (higher derivatives zero), and step `h`.
    fn restart(&mut self, a: &Dof, jerk: &Dof, h: f64);
    /// Estimate of the last step's local error in position (x, y, phi), or `None` when the
    /// integrator has no estimate (its step is then never refined).
    fn local_error(&self) -> Option<Dof>;
}

/// Gear 5th-order predictor-corrector: per degree of freedom the scaled Taylor terms
/// r_k = dt^k / k! d^k q / dt^k, k = 0..5. Forces from the predicted position and velocity.
///
/// One step of the textbook scheme is: predict g_p = P g (P the Pascal matrix,
/// (P g)_j = sum_{k >= j} C(k, j) g_k), evaluate the acceleration a at g_p, correct
/// g = g_p + c delta with delta = a dt^2 / 2 - (g_p)_2. Here the prediction for the *next* step
/// is formed directly, P g = P g_p + (P c) delta: P g_p is computed while the forces are being
/// evaluated, so from one force evaluation to the next position the dependency chain is a single
/// multiply-add instead of a corrector and a five-term sum (the same scheme; only the rounding
/// of the sums differs).
///
/// Stored term-major, `gp[k] = [x, y, phi, 0]`: every row is a short vector, so the arithmetic
/// runs on all three degrees of freedom at once (two SSE2 operations per row on any x86-64).
#[derive(Debug, Clone)]
pub struct Gear5 {
    /// Prediction for the coming step.
    gp: [Lanes; 6],
    /// Corrected position after the last step.
    q: Lanes,
    /// Corrected velocity times dt after the last step.
    v_dt: Lanes,
    /// Velocity at touch, and times dt: velocities are read as v0 + (g_1 - v0 dt) / dt, so
    /// that a degree of freedom without force (vx and omega of a frictionless disc) keeps its
    /// velocity bit for bit, whatever the rounding of v0 dt / dt.
    v0: Lanes,
    v0_dt: Lanes,
    dt: f64,
    /// 1 / dt: velocities are taken as products (a division per step would sit on the force
    /// evaluation's critical path).
    inv_dt: f64,
    half_dt2: f64,
    /// The last corrector increment: the predicted minus the evaluated acceleration, times
    /// dt^2 / 2. Gear's local error is proportional to it (a position).
    delta: Lanes,
}

/// The generalised forces of a contact law on the four lanes, evaluated once per step at the
/// integrator's predicted state. (A trait rather than a closure: the closure was compiled out
/// of line, and the plate's Verlet step took 34 % more instructions.)
pub trait LaneForces {
    /// What the evaluation reports besides the forces (the plate's [`Forces`]).
    type Out;
    /// The forces and torques on each lane at position `q` and velocity `v`.
    fn forces(self, q: &Lanes, v: &Lanes) -> (Lanes, Self::Out);
}

/// The contact law of a particle on the plate, seen on the lanes (the 4th lane carries nothing).
struct OnPlate<'c, 'm, G> {
    contact: &'c mut Contact<'m, G>,
    dt: f64,
}

impl<G: PlateGeometry> LaneForces for OnPlate<'_, '_, G> {
    type Out = Forces;

    #[inline(always)]
    fn forces(self, q: &Lanes, v: &Lanes) -> (Lanes, Forces) {
        let f = self
            .contact
            .evaluate(&[q[0], q[1], q[2]], &[v[0], v[1], v[2]], self.dt);
        ([f.fx, f.fy, f.torque, 0.0], f)
    }
}

/// x, y, phi and a padding lane kept at zero (a particle on the plate), or x, y, phi1, phi2
/// (a pair in its centre-of-mass frame).
pub type Lanes = [f64; 4];

/// P c: the corrector coefficients carried through the Pascal predictor,
/// (P c)_j = sum_{k >= j} C(k, j) c_k.
const GEAR5_PREDICTED_CORRECTOR: [f64; 6] = {
    let c = GEAR5_CORRECTOR;
    [
        c[0] + c[1] + c[2] + c[3] + c[4] + c[5],
        c[1] + 2.0 * c[2] + 3.0 * c[3] + 4.0 * c[4] + 5.0 * c[5],
        c[2] + 3.0 * c[3] + 6.0 * c[4] + 10.0 * c[5],
        c[3] + 4.0 * c[4] + 10.0 * c[5],
        c[4] + 5.0 * c[5],
        c[5],
    ]
};

/// The Pascal predictor, g_k <- sum_{j >= k} C(j, k) g_j, as the Taylor shift by repeated
/// addition: 15 vector additions and no multiplications.
#[inline(always)]
fn pascal(g: &mut [Lanes; 6]) {
    for lo in 0..5 {
        for k in (lo..5).rev() {
            for i in 0..4 {
                g[k][i] += g[k + 1][i];
            }
        }
    }
}

/// Sets the rows of the higher derivatives (2 to 5) to zero where they have decayed below the
/// smallest normal float. Without a force they decay geometrically, step after step (a damped
/// Hertz contact ends where its force is clipped to zero while the overlap still closes, over
/// hundreds of steps at cor 0.5), into subnormal numbers, on which every addition of the
/// predictor costs an x86 core a microcode assist of ~100 cycles: the sphere's Gear-5 impact
/// cost 4x at cor 0.5 what it cost at 0.98 for 10 % more steps. A value below 2.2e-308 is far
/// below half an ulp of any position or velocity it is added to, so nothing else changes.
#[inline(always)]
fn flush_subnormal(g: &mut [Lanes; 6]) {
    for row in g[2..].iter_mut() {
        for x in row.iter_mut() {
            if x.abs() < f64::MIN_POSITIVE {
                *x = 0.0;
            }
        }
    }
}

/// The inverse of [`pascal`]: the Taylor shift back by one step.
fn unpascal(g: &mut [Lanes; 6]) {
    for lo in 0..5 {
        for k in (lo..5).rev() {
            for i in 0..4 {
                g[k][i] -= g[k + 1][i];
            }
        }
    }
}

impl Gear5 {
    /// Starts at rest in acceleration (at first touch there is no force).
    pub fn new(q: Dof, v: Dof, dt: f64) -> Self {
        let mut g = [[0.0; 4]; 6];
        for i in 0..3 {
            g[0][i] = q[i];
        }
        Self::from_terms(g, [v[0], v[1], v[2], 0.0], dt)
    }

    /// From the scaled Taylor terms `g` for step `dt` (row 1 is replaced by `v dt`, so that the
    /// velocity is read back as exactly `v` while no force acts).
    fn from_terms(mut g: [Lanes; 6], v: Lanes, dt: f64) -> Self {
        for i in 0..4 {
            g[1][i] = v[i] * dt;
        }
        let (q, v_dt) = (g[0], g[1]);
        let mut gp = g;
        pascal(&mut gp);
        Gear5 {
            gp,
            q,
            v_dt,
            v0: v,
            v0_dt: v_dt,
            dt,
            inv_dt: 1.0 / dt,
            half_dt2: 0.5 * dt * dt,
            delta: [0.0; 4],
        }
    }

    /// The corrected scaled Taylor terms at the current time (the stored prediction shifted
    /// back; rows 0 and 1 as stored).
    fn terms(&self) -> [Lanes; 6] {
        let mut g = self.gp;
        unpascal(&mut g);
        g[0] = self.q;
        g[1] = self.v_dt;
        g
    }

    #[inline(always)]
    fn velocity_lanes(&self) -> Lanes {
        let mut v = [0.0; 4];
        for i in 0..4 {
            v[i] = self.v0[i] + (self.v_dt[i] - self.v0_dt[i]) * self.inv_dt;
        }
        v
    }
}

impl Stepper for Gear5 {
    const HIGH_ORDER: bool = true;

    fn start(q: Dof, v: Dof, dt: f64) -> Self {
        Self::new(q, v, dt)
    }

    fn start_lanes(q: Lanes, v: Lanes, dt: f64) -> Self {
        let mut g = [[0.0; 4]; 6];
        g[0] = q;
        Self::from_terms(g, v, dt)
    }

    #[inline(always)]
    fn advance<L: LaneForces>(&mut self, dt: f64, inv_mass: &Lanes, law: L) -> L::Out {
        debug_assert_eq!(dt, self.dt);
        let gp = self.gp;
        let inv_dt = self.inv_dt;
        let mut v = [0.0; 4];
        for i in 0..4 {
            v[i] = self.v0[i] + (gp[1][i] - self.v0_dt[i]) * inv_dt;
        }
        let (force, out) = law.forces(&gp[0], &v);
        // Independent of the forces: runs while they are evaluated.
        let mut next = gp;
        pascal(&mut next);
        // delta = a dt^2 / 2 - (g_p)_2, with the force scaled to a dt^2 / 2 in one product.
        let h = self.half_dt2;
        let scale = [
            inv_mass[0] * h,
            inv_mass[1] * h,
            inv_mass[2] * h,
            inv_mass[3] * h,
        ];
        let mut delta = [0.0; 4];
        for i in 0..4 {
            delta[i] = force[i] * scale[i] - gp[2][i];
            self.q[i] = gp[0][i] + GEAR5_CORRECTOR[0] * delta[i];
            self.v_dt[i] = gp[1][i] + GEAR5_CORRECTOR[1] * delta[i];
        }
        for (row, pc) in next.iter_mut().zip(GEAR5_PREDICTED_CORRECTOR) {
            for i in 0..4 {
                row[i] += pc * delta[i];
            }
        }
        flush_subnormal(&mut next);
        self.gp = next;
        self.delta = delta;
        out
    }

    #[inline(always)]
    fn lanes(&self) -> (Lanes, Lanes) {
        (self.q, self.velocity_lanes())
    }

    #[inline(always)]
    fn position(&self) -> Dof {
        [self.q[0], self.q[1], self.q[2]]
    }

    #[inline(always)]
    fn velocity(&self) -> Dof {
        let v = self.velocity_lanes();
        [v[0], v[1], v[2]]
    }

    fn path(&self, s: f64) -> Dof {
        let g = self.terms();
        std::array::from_fn(|i| {
            let mut p = g[5][i];
            for k in (0..5).rev() {
                p = p * s + g[k][i];
            }
            p
        })
    }

    fn acceleration(&self) -> Dof {
        let g = self.terms();
        let scale = 2.0 / (self.dt * self.dt);
        [g[2][0] * scale, g[2][1] * scale, g[2][2] * scale]
    }

    fn resize(&mut self, h: f64) {
        let mut g = self.terms();
        let ratio = h / self.dt;
        let mut scale = ratio;
        for row in g.iter_mut().skip(2) {
            scale *= ratio;
            for x in row.iter_mut() {
                *x *= scale;
            }
        }
        if ratio > 1.0 {
            // Longer steps magnify what the short ones left in the highest terms (by 2^4 and
            // 2^5 when doubling). Along x and phi those terms are rebuilt by the corrector
            // instead: magnified, the tangential force's stick/slip noise in them disturbed the
            // energy balance (measured while frictional contacts were still refined; without
            // friction x carries no force). The height's are kept: the error control watches it.
            for row in &mut g[4..] {
                row[0] = 0.0;
                row[2] = 0.0;
            }
        }
        *self = Self::from_terms(g, self.velocity_lanes(), h);
    }

    fn restart(&mut self, a: &Dof, jerk: &Dof, h: f64) {
        let mut g = [[0.0; 4]; 6];
        let (a_scale, j_scale) = (0.5 * h * h, h * h * h / 6.0);
        for i in 0..3 {
            g[0][i] = self.q[i];
            g[2][i] = a[i] * a_scale;
            g[3][i] = jerk[i] * j_scale;
        }
        *self = Self::from_terms(g, self.velocity_lanes(), h);
    }

    fn local_error(&self) -> Option<Dof> {
        Some([self.delta[0], self.delta[1], self.delta[2]])
    }
}

/// Velocity Verlet. The forces depend on velocity, so they are evaluated at the new position
/// with the predicted velocity v + a dt; the velocity is then advanced with the average of the
/// old and new accelerations.
///
/// As for [`Gear5`], the next position and predicted velocity are formed as soon as the new
/// acceleration is known, from parts computed while the forces were being evaluated:
/// q_{n+2} = (q_{n+1} + v_n dt + a_n dt^2 / 2) + a_{n+1} dt^2 and
/// v_pred = (v_n + a_n dt / 2) + 3/2 a_{n+1} dt (the same scheme; only the rounding differs).
#[derive(Debug, Clone)]
pub struct Verlet {
    /// Position of the last force evaluation.
    q: Lanes,
    /// Velocity after the last step.
    v: Lanes,
    /// Acceleration of the last step.
    a: Lanes,
    /// Position of the coming step.
    q_next: Lanes,
    /// Predicted velocity of the coming step.
    v_pred: Lanes,
    dt: f64,
}

impl Verlet {
    /// Starts with zero acceleration (no force at first touch).
    pub fn new(q: Dof, v: Dof, dt: f64) -> Self {
        let q = [q[0], q[1], q[2], 0.0];
        let v = [v[0], v[1], v[2], 0.0];
        let mut q_next = [0.0; 4];
        for i in 0..4 {
            q_next[i] = q[i] + v[i] * dt;
        }
        Verlet {
            q,
            v,
            a: [0.0; 4],
            q_next,
            v_pred: v,
            dt,
        }
    }
}

impl Stepper for Verlet {
    const HIGH_ORDER: bool = false;

    fn start(q: Dof, v: Dof, dt: f64) -> Self {
        Self::new(q, v, dt)
    }

    fn start_lanes(q: Lanes, v: Lanes, dt: f64) -> Self {
        let mut s = Self::new([q[0], q[1], q[2]], [v[0], v[1], v[2]], dt);
        (s.q[3], s.v[3], s.v_pred[3], s.q_next[3]) = (q[3], v[3], v[3], q[3] + v[3] * dt);
        s
    }

    #[inline(always)]
    fn advance<L: LaneForces>(&mut self, dt: f64, inv_mass: &Lanes, law: L) -> L::Out {
        debug_assert_eq!(dt, self.dt);
        let (q, v_pred) = (self.q_next, self.v_pred);
        let (force, out) = law.forces(&q, &v_pred);
        let (dt2, half_dt) = (dt * dt, 0.5 * dt);
        for i in 0..4 {
            // Independent of the forces: computed while they are evaluated.
            let q_part = q[i] + self.v[i] * dt + self.a[i] * (0.5 * dt2);
            let v_part = self.v[i] + self.a[i] * half_dt;
            let a_new = force[i] * inv_mass[i];
            self.q_next[i] = q_part + a_new * dt2;
            self.v_pred[i] = v_part + a_new * (3.0 * half_dt);
            self.v[i] = v_part + a_new * half_dt;
            self.a[i] = a_new;
        }
        self.q = q;
        out
    }

    #[inline(always)]
    fn lanes(&self) -> (Lanes, Lanes) {
        (self.q, self.v)
    }

    #[inline(always)]
    fn position(&self) -> Dof {
        [self.q[0], self.q[1], self.q[2]]
    }

    #[inline(always)]
    fn velocity(&self) -> Dof {
        [self.v[0], self.v[1], self.v[2]]
    }

    fn path(&self, s: f64) -> Dof {
        let t = s * self.dt;
        std::array::from_fn(|i| self.q[i] + self.v[i] * t + self.a[i] * (0.5 * t * t))
    }

    fn acceleration(&self) -> Dof {
        [self.a[0], self.a[1], self.a[2]]
    }

    fn resize(&mut self, h: f64) {
        for i in 0..4 {
            self.q_next[i] = self.q[i] + self.v[i] * h + self.a[i] * (0.5 * h * h);
            self.v_pred[i] = self.v[i] + self.a[i] * h;
        }
        self.dt = h;
    }

    fn restart(&mut self, a: &Dof, _jerk: &Dof, h: f64) {
        self.a = [a[0], a[1], a[2], 0.0];
        self.resize(h);
    }

    fn local_error(&self) -> Option<Dof> {
        None
    }
}
