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
#[derive(Debug, Clone)]
pub struct Gear5 {
    g: [[f64; 6]; 3],
    dt: f64,
}

impl Gear5 {
    /// Starts at rest in acceleration (at first touch there is no force).
    pub fn new(q: Dof, v: Dof, dt: f64) -> Self {
        let mut g = [[0.0; 6]; 3];
        for i in 0..3 {
            g[i][0] = q[i];
            g[i][1] = v[i] * dt;
        }
        Gear5 { g, dt }
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
        for g in self.g.iter_mut() {
            // Pascal-triangle predictor.
            g[0] += g[1] + g[2] + g[3] + g[4] + g[5];
            g[1] += 2.0 * g[2] + 3.0 * g[3] + 4.0 * g[4] + 5.0 * g[5];
            g[2] += 3.0 * g[3] + 6.0 * g[4] + 10.0 * g[5];
            g[3] += 4.0 * g[4] + 10.0 * g[5];
            g[4] += 5.0 * g[5];
        }
        let q = [self.g[0][0], self.g[1][0], self.g[2][0]];
        let v = [self.g[0][1] / dt, self.g[1][1] / dt, self.g[2][1] / dt];
        let f = contact.evaluate(&q, &v, dt);
        let acc = [
            f.fx * inv_mass[0],
            f.fy * inv_mass[1],
            f.torque * inv_mass[2],
        ];
        let half_dt2 = 0.5 * dt * dt;
        for (g, a) in self.g.iter_mut().zip(acc) {
            let delta = a * half_dt2 - g[2];
            for (gk, ck) in g.iter_mut().zip(GEAR5_CORRECTOR) {
                *gk += ck * delta;
            }
        }
        f
    }

    fn position(&self) -> Dof {
        [self.g[0][0], self.g[1][0], self.g[2][0]]
    }

    fn velocity(&self) -> Dof {
        [
            self.g[0][1] / self.dt,
            self.g[1][1] / self.dt,
            self.g[2][1] / self.dt,
        ]
    }
}

/// Velocity Verlet. The forces depend on velocity, so they are evaluated at the new position
/// with the predicted velocity v + a dt; the velocity is then advanced with the average of the
/// old and new accelerations.
#[derive(Debug, Clone)]
pub struct Verlet {
    q: Dof,
    v: Dof,
    a: Dof,
}

impl Verlet {
    /// Starts with zero acceleration (no force at first touch).
    pub fn new(q: Dof, v: Dof) -> Self {
        Verlet { q, v, a: [0.0; 3] }
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
        let mut v_pred = [0.0; 3];
        for i in 0..3 {
            self.q[i] += self.v[i] * dt + 0.5 * self.a[i] * dt * dt;
            v_pred[i] = self.v[i] + self.a[i] * dt;
        }
        let f = contact.evaluate(&self.q, &v_pred, dt);
        let a_new = [
            f.fx * inv_mass[0],
            f.fy * inv_mass[1],
            f.torque * inv_mass[2],
        ];
        for i in 0..3 {
            self.v[i] += 0.5 * (self.a[i] + a_new[i]) * dt;
        }
        self.a = a_new;
        f
    }

    fn position(&self) -> Dof {
        self.q
    }

    fn velocity(&self) -> Dof {
        self.v
    }
}
