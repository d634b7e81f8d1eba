//! Helpers shared by the kernel's integration tests (each test crate uses a part of them).
#![allow(dead_code)]

pub mod bounds;

use restitution_core::{
    simulate, Error, InertiaModel, Initial, Integrator, Model, NormalLaw, Record, Scene,
};

/// The energy half of the stability criterion shared by `physics.rs` and `stability.rs`:
/// damped or frictional scenes gain at most 1e-6, conservative ones change by at most 1 %, and
/// the audit closes within 1e-2. Returns the reason when the record fails it.
pub fn energy_verdict(scene: &Scene, rec: &Record) -> Option<String> {
    let damped = match scene.normal_law {
        NormalLaw::Area => scene.gamma > 0.0,
        NormalLaw::Linear { cn, .. } => cn > 0.0,
        NormalLaw::Hertz { cor, .. } => cor < 1.0,
    };
    let gain = rec.energy_out / rec.energy_in - 1.0;
    if (damped || scene.mu > 0.0) && gain > 1e-6 {
        return Some(format!("energy gained: {gain:e}"));
    }
    if !(damped || scene.mu > 0.0) && gain.abs() > 1e-2 {
        return Some(format!("energy changed by {gain:e}"));
    }
    if rec.energy_residual.abs() > 1e-2 {
        return Some(format!("energy residual {:e}", rec.energy_residual));
    }
    None
}

/// The paper preset's impact speed (m/s) and radius (m); `Scene::default()` is the preset on
/// an exact disc.
pub const V: f64 = 0.0357;
pub const R: f64 = 0.01;
pub const BOTH: [Integrator; 2] = [Integrator::Gear5, Integrator::Verlet];

pub fn run(scene: &Scene, init: &Initial) -> Record {
    simulate(scene, init).unwrap_or_else(|e| panic!("{e} for {scene:?} {init:?}"))
}

pub fn at(theta_deg: f64, omega_in: f64) -> Initial {
    Initial::from_angle(V, theta_deg, omega_in, 0.0)
}

pub fn kappa(inertia: InertiaModel) -> f64 {
    match inertia {
        InertiaModel::Shape => 0.5,
        InertiaModel::Sphere => 0.4,
    }
}

/// Critical damping of the linear law for the preset disc: cn = 2 zeta sqrt(kn m).
pub fn linear_law(kn: f64, zeta: f64) -> NormalLaw {
    let mass = Model::new(&Scene::default()).unwrap().mass;
    NormalLaw::Linear {
        kn,
        cn: zeta * 2.0 * (kn * mass).sqrt(),
    }
}

/// A list of numbers in scientific notation, for messages.
pub fn sci(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|x| format!("{x:.2e}")).collect();
    format!("[{}]", items.join(", "))
}

pub fn invalid_name(r: Result<Record, Error>) -> String {
    match r {
        Err(Error::InvalidParameter { name, .. }) => name,
        other => panic!("expected an InvalidParameter error, got {other:?}"),
    }
}
