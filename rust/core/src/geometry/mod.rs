//! How the particle's shape meets the plate: the exact disc and its closed-form circular
//! segment, convex polygons clipped by the half-plane, and the general convex-convex
//! intersection through parry for any convex obstacle.

pub mod chain;
pub mod convex_clip;
pub mod convex_window;
pub mod disc;
pub mod overlap;
pub mod pair;
pub mod pair_shapes;
pub mod parry;
pub mod polygon;
pub mod shape;

pub use self::parry::{ConvexObstacle, Patch};
pub(crate) use disc::{disc_arm_per_depth, disc_segment, disc_segment_at};
pub use overlap::{Corners, Overlap};
pub(crate) use polygon::{crossing_x, validate_convex};
pub use shape::*;
