//! The contact law on a pair (docs/model.md, section 17): the plate's normal and tangential
//! laws, read with the pair's effective constants ([`crate::model::Pair`]), acting along the
//! contact's normal and tangent at the points its frame gives ([`PairFrame`]: the line of
//! centres for round bodies), on the relative motion and on both rotations.

use super::contact::{tangential_step, NormalForce, PairNormal};
use super::tangential::{StickState, TangentialSpring};
use crate::geometry::pair::PairGeometry;
use crate::model::Model;

/// A pair's four degrees of freedom (x, y, phi1, phi2), their rates, or the forces and
/// torques on them.
pub type Lanes = [f64; 4];

/// The forces of one evaluation on a pair and where they act.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairForces {
    /// The normal force's elastic and damping parts (clipped) and the tangential force, on
    /// the particle (the partner takes their opposite).
    pub f_el: f64,
    /// See `f_el`.
    pub f_d: f64,
    /// See `f_el`.
    pub f_t: f64,
    /// The unit normal (from the partner to the particle) and tangent t = (n_y, -n_x).
    pub n: [f64; 2],
    /// The elastic and damping parts as generalised forces on the lanes.
    pub el: Lanes,
    /// See `el`.
    pub damp: Lanes,
    /// The tangential force's lever on the two spins.
    pub lever_t: [f64; 2],
    /// The overlap's area and depth (0 when apart).
    pub area: f64,
    /// See `area`.
    pub depth: f64,
    /// Stick/slip state of this step.
    pub stick: StickState,
}

/// The dot product of two lane vectors.
#[inline(always)]
pub fn dot(a: &Lanes, b: &Lanes) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
}

impl PairForces {
    /// The powers of the normal force (elastic, damping) and of the tangential force on the
    /// relative motion at lane velocities `v` = (g_x, g_y, omega1, omega2).
    #[inline(always)]
    pub fn powers(&self, v: &Lanes) -> (f64, f64, f64) {
        let [nx, ny] = self.n;
        let v_t = ny * v[0] - nx * v[1] + self.lever_t[0] * v[2] + self.lever_t[1] * v[3];
        (dot(&self.el, v), dot(&self.damp, v), self.f_t * v_t)
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
        let Some(fr) = self.geometry.frame(q) else {
            self.spring.reset();
            return ([0.0; 4], PairForces::default());
        };
        let n = fr.n;
        let t = [n[1], -n[0]];
        let mut normal = self.normal.on_pair(&fr, v, G::CORNERS);
        if normal.f_el + normal.f_d < 0.0 {
            normal = PairNormal::default();
        }
        let f_n = normal.f_el + normal.f_d;
        let v_t = t[0] * v[0] + t[1] * v[1] + fr.lever_t[0] * v[2] + fr.lever_t[1] * v[3];
        let (f_t, stick) = tangential_step(&mut self.spring, self.law, fr.depth, v_t, dt, f_n);
        let tan = [
            f_t * t[0],
            f_t * t[1],
            f_t * fr.lever_t[0],
            f_t * fr.lever_t[1],
        ];
        let mut force: Lanes = std::array::from_fn(|i| normal.el[i] + normal.damp[i] + tan[i]);
        if !G::CORNERS {
            // Round bodies: the normal force has no torque (see `NormalForce::on_pair`).
            (force[2], force[3]) = (tan[2], tan[3]);
        }
        let forces = PairForces {
            f_el: normal.f_el,
            f_d: normal.f_d,
            f_t,
            n,
            el: normal.el,
            damp: normal.damp,
            lever_t: fr.lever_t,
            area: fr.area,
            depth: fr.depth,
            stick,
        };
        (force, forces)
    }
}
