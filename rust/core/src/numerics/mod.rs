//! Numerical tools that know nothing of the physics, used by every layer above: the one root
//! finder (Brent's method, bracketing and peak search), shared by the Hertz calibration in
//! `model`, the fixed-step events in `integrate` and the adaptive path's switches in `impact`;
//! and the sine and cosine that turn a polygon's corners (`trig`).

pub(crate) mod roots;
pub(crate) mod trig;
