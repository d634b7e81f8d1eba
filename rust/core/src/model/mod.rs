//! What an impact is made of: the scene (particle, material, contact law, numerics), the
//! initial state, the derived model, and the time-step bound each integrator needs.

pub mod columns;
pub mod derived;
pub mod hertz;
pub mod pair;
pub mod scene;
pub mod stability;

pub use columns::{
    check_orientation, check_theta, scene_from_columns, shape_from_columns, Templates,
    CASE_COLUMNS, CHOICES,
};
pub use derived::{check_case, Hertz, Model};
pub use pair::Pair;
pub use scene::{
    sin_cos_deg, InertiaModel, Initial, Integrator, NormalLaw, Partner, Scene, TangentialHistory,
    TangentialModel,
};
pub use stability::{max_dt_factor, max_dt_factor_reason, ContactRates};
