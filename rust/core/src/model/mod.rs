//! What an impact is made of: the scene (particle, material, contact law, numerics), the
//! initial state, the derived model, and the time-step bound each integrator needs.

pub mod scene;
pub mod stability;

pub use scene::{sin_cos_deg, InertiaModel, Initial, Integrator, Model, NormalLaw, Scene};
pub use stability::{max_dt_factor, max_dt_factor_reason, ContactRates};
