//! What an impact is made of: the scene (particle, material, contact law, numerics), the
//! initial state, the derived model, and the time-step bound each integrator needs.

pub mod hertz;
pub mod scene;
pub mod stability;

pub use scene::{
    check_case, check_orientation, check_theta, scene_from_columns, shape_from_columns,
    sin_cos_deg, Hertz, InertiaModel, Initial, Integrator, Model, NormalLaw, Scene,
    TangentialModel, CASE_COLUMNS, CHOICES,
};
pub use stability::{max_dt_factor, max_dt_factor_reason, ContactRates};
