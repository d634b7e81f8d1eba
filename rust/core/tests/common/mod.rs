//! Helpers shared by the kernel's integration tests.

use restitution_core::{NormalLaw, Record, Scene};

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
