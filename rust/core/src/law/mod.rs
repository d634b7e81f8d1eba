//! The contact law, written once: the normal force (overlap area or linear spring), its
//! damping and clip, the overlap dispatch per shape, and the tangential spring with Coulomb's
//! cap. Every integrator evaluates these functions.

pub mod contact;
pub mod pair;
pub mod tangential;

pub use contact::*;
pub use tangential::{carrying, trial_force, StickState, TangentialSpring};
