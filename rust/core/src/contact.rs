//! The contact law: normal force (area or linear law, with damping, never attractive) and the
//! tangential force, evaluated once per time step at the integrator's predicted state.

use crate::geometry::Overlap;
use crate::scene::{Model, NormalLaw};
use crate::tangential::{StickState, TangentialSpring};

/// Position (x, y, phi) or velocity (vx, vy, omega) of the particle.
pub type Dof = [f64; 3];

/// The forces of one evaluation and where they act.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Forces {
    /// Total force and torque on the body (N/m, N).
    pub fx: f64,
    /// See `fx`.
    pub fy: f64,
    /// See `fx`.
    pub torque: f64,
    /// Elastic part of the (clipped) normal force.
    pub f_el: f64,
    /// Damping part of the (clipped) normal force.
    pub f_d: f64,
    /// Tangential force (along +x).
    pub f_t: f64,
    /// Overlap, if any.
    pub overlap: Option<Overlap>,
    /// Stick/slip state of this step.
    pub stick: StickState,
    /// x of the damping force's point of application, relative to the centre of mass.
    pub x_damp: f64,
}

impl Forces {
    /// Power of the normal force (elastic, damping) and of the tangential force for the body
    /// velocity `v` at centre height `y`: F . (v + omega x arm).
    #[inline]
    pub fn powers(&self, y: f64, v: &Dof) -> (f64, f64, f64) {
        match self.overlap {
            None => (0.0, 0.0, 0.0),
            Some(o) => (
                self.f_el * (v[1] + v[2] * o.cx),
                self.f_d * (v[1] + v[2] * self.x_damp),
                self.f_t * (v[0] - v[2] * (o.cy - y)),
            ),
        }
    }
}

/// The contact law with its history (the tangential spring).
#[derive(Debug, Clone)]
pub struct Contact<'a> {
    model: &'a Model,
    /// The Cundall-Strack spring.
    pub spring: TangentialSpring,
}

impl<'a> Contact<'a> {
    /// A fresh contact (unstretched spring).
    pub fn new(model: &'a Model) -> Self {
        Contact {
            model,
            spring: TangentialSpring::default(),
        }
    }

    /// Forces at position `q` and velocity `v`; advances the tangential spring by `dt`.
    #[inline]
    pub fn evaluate(&mut self, q: &Dof, v: &Dof, dt: f64) -> Forces {
        let m = self.model;
        let Some(o) = m.scene.shape.overlap_with(m.scene.overlap, q[1], q[2]) else {
            self.spring.reset();
            return Forces::default();
        };
        let (mut f_el, mut f_d, x_damp) = match m.scene.normal_law {
            NormalLaw::Area => {
                // Exact rate of the overlap area: minus the chord times the normal velocity
                // of the body at the chord's midpoint (the body velocity is linear along it).
                let da_dt = -o.chord * (v[1] + v[2] * o.x_mid);
                (
                    m.scene.e_modulus * o.area / m.length,
                    m.area_damping * da_dt,
                    o.x_mid,
                )
            }
            NormalLaw::Linear { kn, cn } => {
                let ddepth_dt = -(v[1] + v[2] * o.x_low);
                (kn * o.depth, cn * ddepth_dt, o.cx)
            }
        };
        if f_el + f_d < 0.0 {
            // The plate never pulls.
            f_el = 0.0;
            f_d = 0.0;
        }
        let f_n = f_el + f_d;
        let arm_y = o.cy - q[1];
        let v_t = v[0] - v[2] * arm_y;
        let (f_t, stick) = self.spring.step(v_t, dt, m.scene.mu, f_n, m.kt, m.ct);
        Forces {
            fx: f_t,
            fy: f_n,
            torque: o.cx * f_el + x_damp * f_d - arm_y * f_t,
            f_el,
            f_d,
            f_t,
            overlap: Some(o),
            stick,
            x_damp,
        }
    }
}
