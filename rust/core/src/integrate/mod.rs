//! How time advances: the fixed-step integrators (Gear-5, velocity Verlet), the events that
//! land a step on a switch of the contact law, and the adaptive Runge-Kutta path.

pub mod adaptive;
pub mod events;
pub mod fixed_step;
pub(crate) mod roots;

pub use fixed_step::{Gear5, Stepper, Verlet};
