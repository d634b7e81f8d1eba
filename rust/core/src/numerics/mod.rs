//! Numerical tools that know nothing of the physics, used by every layer above: the one root
//! finder (Brent's method, bracketing and peak search), shared by the Hertz calibration in
//! `model`, the fixed-step events in `integrate` and the adaptive path's switches in `impact`;
//! the sine and cosine that turn a polygon's corners (`trig`); and the seeded uniform numbers of
//! the tests and the consistency matrix (`seeded`); a reference quadrature for the tests
//! (`quadrature`).

#[cfg(test)]
pub(crate) mod quadrature;
pub(crate) mod roots;
pub(crate) mod seeded;
pub(crate) mod trig;
