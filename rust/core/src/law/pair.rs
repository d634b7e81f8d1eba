//! The contact law on a pair (docs/model.md, section 17): the plate's normal and tangential
//! laws, read with the pair's effective constants ([`crate::model::Pair`]), acting along the
//! line of centres and across it, on the relative motion and on both rotations.

use super::contact::{tangential_step, NormalForce};
use super::tangential::{StickState, TangentialSpring};
use crate::geometry::pair::PairGeometry;
use crate::geometry::Overlap;
use crate::model::Model;

/// A pair's four degrees of freedom (x, y, phi1, phi2), their rates, or the forces and
/// torques on them.
pub type Lanes = [f64; 4];

/// The forces of one evaluation on a pair and where they act.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairForces {
    /// The normal force's elastic and damping parts (clipped) and the tangential force, on
    /// the particle along n and t (the partner takes their opposite).
    pub f_el: f64,
    /// See `f_el`.
    pub f_d: f64,
    /// See `f_el`.
    pub f_t: f64,
    /// The unit normal (from the partner to the particle) and tangent t = (n_y, -n_x).
    pub n: [f64; 2],
    /// The arms from each centre to the point where the forces act, along the line of centres.
    pub arms: [f64; 2],
    /// The overlap's area and depth (0 when apart).
    pub area: f64,
    /// See `area`.
    pub depth: f64,
    /// Stick/slip state of this step.
    pub stick: StickState,
}

impl PairForces {
    /// The powers of the normal force (elastic, damping) and of the tangential force on the
    /// relative motion at lane velocities `v` = (g_x, g_y, omega1, omega2).
    #[inline(always)]
    pub fn powers(&self, v: &Lanes) -> (f64, f64, f64) {
        let [nx, ny] = self.n;
        let g_n = nx * v[0] + ny * v[1];
        let v_t = ny * v[0] - nx * v[1] + self.arms[0] * v[2] + self.arms[1] * v[3];
        (self.f_el * g_n, self.f_d * g_n, self.f_t * v_t)
    }
}

/// The contact of a pair, with its history (the tangential spring).
#[derive(Debug, Clone)]
pub struct PairContact<'a, G> {
    law: &'a Model,
    /// How the two bodies overlap.
    pub geometry: G,
    /// The tangential spring.
    pub spring: TangentialSpring,
    normal: NormalForce,
}

impl<'a, G: PairGeometry> PairContact<'a, G> {
    /// A fresh contact of the pair whose effective model is `law` (`Pair::law`).
    pub fn new(law: &'a Model, geometry: G) -> Self {
        PairContact {
            law,
            geometry,
            spring: TangentialSpring::default(),
            normal: NormalForce::new(law),
        }
    }

    /// The generalised forces on the lanes (F_x, F_y on the relative position, the torques on
    /// each body) at position `q` = (x, y, phi1, phi2) and velocity `v`; advances the spring
    /// by `dt`.
    #[inline(always)]
    pub fn evaluate(&mut self, q: &Lanes, v: &Lanes, dt: f64) -> (Lanes, PairForces) {
        // sqrt, not hypot: the centres' distance is never near the floats' limits, and
        // hypot's care cost a fifth of a pair's step.
        let d = (q[0] * q[0] + q[1] * q[1]).sqrt();
        let inv_d = 1.0 / d;
        let n = [q[0] * inv_d, q[1] * inv_d];
        let Some(o) = self.geometry.overlap(d) else {
            self.spring.reset();
            return (
                [0.0; 4],
                PairForces {
                    n,
                    ..PairForces::default()
                },
            );
        };
        let arms = [o.arm1, d - o.arm1];
        let g_n = n[0] * v[0] + n[1] * v[1];
        let g_t = n[1] * v[0] - n[0] * v[1];
        // The normal law as on the plate, in the contact's frame: the chord's midpoint and
        // the centroid lie on the line of centres (no lever).
        let frame = Overlap {
            area: o.area,
            chord: o.chord,
            depth: o.depth,
            ..Overlap::default()
        };
        let (f_el, f_d, _, _) = self.normal.on_overlap(&frame, &[g_t, g_n, 0.0]);
        let (f_n, f_el, f_d) = if f_el + f_d < 0.0 {
            (0.0, 0.0, 0.0)
        } else {
            (f_el + f_d, f_el, f_d)
        };
        let v_t = g_t + arms[0] * v[2] + arms[1] * v[3];
        let (f_t, stick) = tangential_step(&mut self.spring, self.law, o.depth, v_t, dt, f_n);
        let t = [n[1], -n[0]];
        let force = [
            f_n * n[0] + f_t * t[0],
            f_n * n[1] + f_t * t[1],
            arms[0] * f_t,
            arms[1] * f_t,
        ];
        let forces = PairForces {
            f_el,
            f_d,
            f_t,
            n,
            arms,
            area: o.area,
            depth: o.depth,
            stick,
        };
        (force, forces)
    }
}
