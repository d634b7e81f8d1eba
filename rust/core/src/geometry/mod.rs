//! How the particle's shape meets the plate: the exact disc and its closed-form circular
//! segment, convex polygons clipped by the half-plane, and the general convex-convex
//! intersection through parry for any convex obstacle.

pub mod parry;
pub mod shape;

pub use self::parry::{ConvexObstacle, Patch};
pub use shape::*;
