//! Fixed-step integrators for the three rigid-body degrees of freedom (x, y, phi).
//!
//! Each step evaluates the contact law exactly once (the tangential spring is history
//! dependent, so every evaluation is a committed step).

use crate::contact::{Contact, Dof, Forces, PlateGeometry};

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
pub trait Stepper {
    /// Advances one step of `dt`, returning the forces used.
    fn step<G: PlateGeometry>(
        &mut self,
        contact: &mut Contact<G>,
        dt: f64,
        inv_mass: &Dof,
    ) -> Forces;
    /// Current position.
    fn position(&self) -> Dof;
    /// Current velocity.
    fn velocity(&self) -> Dof;
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
}

/// x, y, phi and a padding lane (kept at zero).
type Lanes = [f64; 4];

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

impl Gear5 {
    /// Starts at rest in acceleration (at first touch there is no force).
    pub fn new(q: Dof, v: Dof, dt: f64) -> Self {
        let mut gp = [[0.0; 4]; 6];
        for i in 0..3 {
            gp[0][i] = q[i];
            gp[1][i] = v[i] * dt;
        }
        let (q, v_dt) = (gp[0], gp[1]);
        pascal(&mut gp);
        Gear5 {
            gp,
            q,
            v_dt,
            v0: [v[0], v[1], v[2], 0.0],
            v0_dt: v_dt,
            dt,
            inv_dt: 1.0 / dt,
            half_dt2: 0.5 * dt * dt,
        }
    }
}

impl Stepper for Gear5 {
    #[inline(always)]
    fn step<G: PlateGeometry>(
        &mut self,
        contact: &mut Contact<G>,
        dt: f64,
        inv_mass: &Dof,
    ) -> Forces {
        debug_assert_eq!(dt, self.dt);
        let gp = self.gp;
        let inv_dt = self.inv_dt;
        let mut v = [0.0; 4];
        for i in 0..4 {
            v[i] = self.v0[i] + (gp[1][i] - self.v0_dt[i]) * inv_dt;
        }
        let f = contact.evaluate(&[gp[0][0], gp[0][1], gp[0][2]], &[v[0], v[1], v[2]], dt);
        // Independent of the forces: runs while they are evaluated.
        let mut next = gp;
        pascal(&mut next);
        // delta = a dt^2 / 2 - (g_p)_2, with the force scaled to a dt^2 / 2 in one product.
        let h = self.half_dt2;
        let force = [f.fx, f.fy, f.torque, 0.0];
        let scale = [inv_mass[0] * h, inv_mass[1] * h, inv_mass[2] * h, 0.0];
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
        self.gp = next;
        f
    }

    #[inline(always)]
    fn position(&self) -> Dof {
        [self.q[0], self.q[1], self.q[2]]
    }

    #[inline(always)]
    fn velocity(&self) -> Dof {
        let v = |i: usize| self.v0[i] + (self.v_dt[i] - self.v0_dt[i]) * self.inv_dt;
        [v(0), v(1), v(2)]
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
    #[inline(always)]
    fn step<G: PlateGeometry>(
        &mut self,
        contact: &mut Contact<G>,
        dt: f64,
        inv_mass: &Dof,
    ) -> Forces {
        debug_assert_eq!(dt, self.dt);
        let (q, v_pred) = (self.q_next, self.v_pred);
        let f = contact.evaluate(&[q[0], q[1], q[2]], &[v_pred[0], v_pred[1], v_pred[2]], dt);
        let (dt2, half_dt) = (dt * dt, 0.5 * dt);
        let force = [f.fx, f.fy, f.torque, 0.0];
        for i in 0..4 {
            // Independent of the forces: computed while they are evaluated.
            let q_part = q[i] + self.v[i] * dt + self.a[i] * (0.5 * dt2);
            let v_part = self.v[i] + self.a[i] * half_dt;
            let a_new = force[i] * inv_mass[i.min(2)];
            self.q_next[i] = q_part + a_new * dt2;
            self.v_pred[i] = v_part + a_new * (3.0 * half_dt);
            self.v[i] = v_part + a_new * half_dt;
            self.a[i] = a_new;
        }
        self.q = q;
        f
    }

    #[inline(always)]
    fn position(&self) -> Dof {
        [self.q[0], self.q[1], self.q[2]]
    }

    #[inline(always)]
    fn velocity(&self) -> Dof {
        [self.v[0], self.v[1], self.v[2]]
    }
}
