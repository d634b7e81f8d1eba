//! The step control of the adaptive path on the plate: each state component's error scale, the
//! limits of one impact's integration, and where the disc's force has its root singularities
//! (touch and separation; the steps and error factors there are the rules', `rules.rs`).

use super::law::Reference;
use super::piece::{Mode, Touch};
use super::rules::{spring_scale, velocity_scales, Limits};
use super::{ReferenceOptions, State, NS, OM, PHI, VX, VY, W_D, W_EL, W_T, X, XI, Y};
use crate::geometry::Shape;
use crate::impact::budget::{budget_for, reference_contact_steps};
use crate::law::NormalForce;
use crate::model::{Initial, Integrator, Model, NormalLaw};
use std::f64::consts::PI;

/// The error scale of each state component, from the impact's own scales (so that a scene
/// rescaled with its dimensionless groups fixed takes the same steps): the velocities' are
/// the incident ones the outputs are relative to ([`velocity_scales`]), the positions' what
/// those velocities cover in t_c / pi, the spring's the elongation that holds as much energy
/// as the contact point's velocity scale ([`spring_scale`]), the works' the energy.
pub(super) fn error_scales(
    model: &Model,
    init: &Initial,
    (speed, energy): (f64, f64),
    t_est: f64,
    depth_est: f64,
) -> State {
    let [vx, vy, v_in] = velocity_scales(init, speed);
    let mut scale = [0.0; NS];
    scale[VX] = vx;
    scale[VY] = vy;
    scale[OM] = v_in / model.r;
    let t_c = t_est / PI;
    scale[X] = scale[VX] * t_c;
    scale[Y] = scale[VY] * t_c;
    scale[PHI] = scale[OM] * t_c;
    scale[XI] = spring_scale(model, scale[VX], depth_est);
    scale[W_EL] = energy;
    scale[W_D] = energy;
    scale[W_T] = energy;
    scale
}

impl Reference<'_> {
    /// Whether the force in mode `m` has the disc's root singularities at touch and
    /// separation: a disc or sphere in contact under the area or Hertz law (the linear law
    /// is smooth there), with the clip on (in the clipped tail no force acts, so nothing is
    /// singular at its end: halving towards separation there took 12 of a frictionless disc's
    /// 47 steps).
    pub(super) fn singular_force(&self, m: &Mode) -> bool {
        self.linear().is_none() && m.touch == Touch::Disc && m.clip_on
    }
}

/// The polygon whose long held runs are summed (`law.rs`, [`super::law::LONG_RUN`]): on the
/// adaptive path under the area law.
fn summed_polygon(model: &Model) -> Option<&crate::geometry::Polygon> {
    let adaptive = model.scene.integrator == Integrator::Adaptive;
    match &model.scene.shape {
        Shape::Polygon(p) if adaptive && model.scene.normal_law == NormalLaw::Area => Some(p),
        _ => None,
    }
}

impl<'a> Reference<'a> {
    /// The ODE of one impact, the limits of its integration and the kinetic energy before it.
    pub(super) fn for_impact(
        model: &'a Model,
        init: &Initial,
        depth_est: f64,
        opts: &ReferenceOptions,
    ) -> (Self, Limits, f64) {
        let r = model.r;
        let speed = init.vx.hypot(init.vy) + r * init.omega.abs();
        let t_est = PI * depth_est / init.vy.abs();
        let h_max = opts.max_step_factor.unwrap_or(model.scene.dt_factor) * model.t_ref;
        let energy_in = model.kinetic_energy(&[init.vx, init.vy, init.omega]);
        let scale = error_scales(model, init, (speed, energy_in), t_est, depth_est);
        let verts = model.scene.shape.vertices();
        let ode = Reference {
            model,
            verts,
            mu: model.scene.mu,
            error_weight: scale.map(|sc| 1.0 / (opts.tol * sc)),
            tol: opts.tol,
            fd_step: 1e-5 * t_est,
            force_tol: opts.tol * model.mass * speed / t_est,
            normal: NormalForce::new(model),
            inv_mass: 1.0 / model.mass,
            inv_inertia: 1.0 / model.inertia,
            summed: summed_polygon(model),
        };
        let max_steps = budget_for(
            model,
            reference_contact_steps(model, init, depth_est, h_max, opts.tol),
        );
        let lim = Limits::new(t_est, h_max, opts.tol, max_steps);
        (ode, lim, energy_in)
    }
}
