//! # restitution-core
//!
//! The physics engine of *restitution*: one oblique impact of a rigid, frictional, damped 2D
//! particle (an exact disc or a convex polygon) on a flat plate, with the overlap-area contact
//! law of Krengel's 2D DEM study, integrated from first touch to separation.
//!
//! ```
//! use restitution_core::{simulate, Initial, Scene};
//!
//! // The study's preset on an exact disc (r = 0.01 m, E = 1e7 Pa, gamma = 0.33, mu = 0.5).
//! let scene = Scene { mu: 0.0, gamma: 0.0, ..Scene::default() };
//! let rec = simulate(&scene, &Initial::from_angle(0.0357, 30.0, 0.0, 0.0)).unwrap();
//! // Frictionless and undamped: elastic bounce, tangential velocity untouched.
//! assert!((rec.e_n - 1.0).abs() < 1e-6);
//! assert_eq!(rec.e_t, Some(1.0));
//! ```
//!
//! Conventions (docs/model.md, section 1): the plate is y = 0, the particle above it; theta is measured
//! from the plate; spin is counter-clockwise positive; units are per unit depth.
#![warn(missing_docs)]

// Layers, each using only those below it: `error`, `cancel` and `numerics` (the root finder),
// `geometry` (shapes and their overlap with the plate), `model` (scene and derived model), `law`
// (the contact forces), `integrate` (the steppers: how time advances), `impact` (the loops of
// one impact to a record), `sweep` (many impacts).
pub mod cancel;
#[cfg(feature = "bench-counters")]
pub mod counters;
pub mod error;
pub mod geometry;
pub mod impact;
pub mod integrate;
pub mod law;
pub mod model;
pub(crate) mod numerics;
pub mod sweep;

pub use cancel::{Cancel, POLL_STEPS};
pub use error::{Error, Result};
pub use geometry::{ConvexObstacle, Corners, Overlap, OverlapMethod, Patch, Polygon, Shape};
pub use impact::adaptive::{simulate_reference, simulate_reference_with_trace, ReferenceOptions};
pub use impact::{
    contact_steps, default_step_budget, estimate_max_depth, simulate, simulate_cancellable,
    simulate_model, simulate_with_trace, simulate_with_trace_cancellable, Cell, Record, StopReason,
    Trace, BUDGET_CONTACTS, BUDGET_SLACK_STEPS, MAX_ADAPTIVE_ATTEMPTS, MAX_STEPS_PER_CONTACT,
    RECORD_COLUMNS,
};
pub use law::{plate_overlap, StickState};
pub use model::{
    check_case, check_orientation, check_theta, max_dt_factor, max_dt_factor_reason,
    scene_from_columns, shape_from_columns, sin_cos_deg, ContactRates, Hertz, InertiaModel,
    Initial, Integrator, Model, NormalLaw, Pair, Partner, Scene, TangentialHistory,
    TangentialModel, Templates, CASE_COLUMNS, CHOICES,
};
pub use numerics::seeded::Seeded;
pub use sweep::{cases_from_rows, check_cases, run_cases, run_cases_cancellable, Case};
