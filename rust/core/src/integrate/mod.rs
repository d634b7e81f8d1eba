//! How time advances: the fixed-step integrators (Gear-5, velocity Verlet) behind the
//! [`Stepper`] trait, the events that land a fixed step on a switch of the contact law, and the
//! Dormand-Prince 5(4) step with its dense output that the adaptive impact loop drives
//! (`crate::impact::adaptive`). The loops of one impact are in `crate::impact`.

pub mod dopri;
pub mod events;
pub mod fixed_step;

pub use fixed_step::{Gear5, LaneForces, Lanes, Stepper, Verlet};
