//! The Hertz law's damping, calibrated: the map from the requested head-on restitution `cor`
//! to the damping ratio beta of the Tsuji dashpot (docs/model.md, section 14.3).
//!
//! The law is m delta'' = -(k delta^(3/2) + c delta^(1/4) delta')^+ with k = 4/3 E* sqrt(R),
//! c delta^(1/4) = 2 sqrt(5/6) beta sqrt(S_n m), S_n = 2 E* sqrt(R delta) (the Tsuji form of
//! LIGGGHTS and Yade, beta >= 0 here), clipped so that the plate never pulls. With
//! delta = delta_0 x, t = T tau, delta_0 = v T and k delta_0^(3/2) = m delta_0 / T^2 it reads
//!
//!   x'' = -(x^(3/2) + sqrt(5) beta x^(1/4) x')^+,   x(0) = 0, x'(0) = 1,
//!
//! free of v, m, R and E*: the restitution e = -x' at the end of the contact depends on beta
//! alone (speed-independent, the reason for the form). The formula LIGGGHTS uses,
//! beta = -ln e / sqrt(ln^2 e + pi^2), is the linear spring's and misses e by up to ~0.05 here
//! (with the clip): so beta is found from this equation instead, by solving it (Runge-Kutta 4,
//! steps of at most 1/20 of the time to touch or to leave, from 1e-9 at touch, where the force is
//! not smooth, to 1e-3; the end,
//! where the clipped force reaches zero, located by bisection of the last step) and inverting
//! e(beta) by Brent's method (`integrate::roots`). Accuracy of e(beta): ~1e-11 (halving the
//! steps moves it by < 3e-12); beta is found to 1e-13 of itself (|e(beta) - cor| <= 1e-15 over
//! cor 0.01 ... 0.999). A sweep varies cor rarely, so the last value is cached per thread.

use crate::numerics::roots;
use std::cell::Cell;

/// Smallest `cor` the calibration accepts: below it the contact is so overdamped that e(beta)
/// flattens and beta is ill-determined.
pub const MIN_COR: f64 = 0.01;

/// Right-hand side of the dimensionless law: (x', x''). Unclipped: the contact ends where the
/// force first reaches zero (located in [`restitution_for_beta_with`]), and a stage past that
/// point continues the smooth law rather than the clip's kink (which would cost the last step
/// its order).
#[inline]
fn rhs(c: f64, x: f64, p: f64) -> (f64, f64) {
    (p, -push(c, x, p))
}

/// The repulsive force x^(3/2) + c x^(1/4) x' before the clip (the contact ends when it, or
/// x, reaches zero on the way out).
#[inline]
fn push(c: f64, x: f64, p: f64) -> f64 {
    let xp = x.max(0.0);
    let s = xp.sqrt();
    xp * s + c * s.sqrt() * p
}

/// One classical Runge-Kutta step of length h.
fn rk4(c: f64, x: f64, p: f64, h: f64) -> (f64, f64) {
    let (k1x, k1p) = rhs(c, x, p);
    let (k2x, k2p) = rhs(c, x + 0.5 * h * k1x, p + 0.5 * h * k1p);
    let (k3x, k3p) = rhs(c, x + 0.5 * h * k2x, p + 0.5 * h * k2p);
    let (k4x, k4p) = rhs(c, x + h * k3x, p + h * k3p);
    (
        x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x),
        p + h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p),
    )
}

/// Whether the contact has ended at (x, p): moving out and either no overlap or no push.
#[inline]
fn ended(c: f64, x: f64, p: f64) -> bool {
    p < 0.0 && (x <= 0.0 || push(c, x, p) <= 0.0)
}

/// Head-on restitution of the Hertz law with the Tsuji dashpot of damping ratio `beta`
/// (dimensionless, >= 0), clipped; with `h_max` the largest step of the solver (1e-3 by
/// default in [`restitution_for_beta`]).
pub fn restitution_for_beta_with(beta: f64, h_max: f64) -> f64 {
    let c = 5f64.sqrt() * beta;
    let (mut x, mut p): (f64, f64) = (0.0, 1.0);
    for _ in 0..10_000_000 {
        // Steps of at most 1/20 of the time to touch or to leave at the current speed: the
        // force's derivatives grow without bound at x = 0 (x^(1/4), x^(1/2)), so the steps
        // shrink geometrically there (from 1e-9 at touch; the error of that stretch falls
        // like the fraction^2.75).
        let h = (0.05 * x / p.abs()).clamp(1e-9, h_max);
        let (x1, p1) = rk4(c, x, p, h);
        if ended(c, x1, p1) {
            // The end lies inside this step: bisect its length (the state at the end is
            // what the step of that length gives; after it no force acts).
            let (mut lo, mut hi) = (0.0, h);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let (xm, pm) = rk4(c, x, p, mid);
                if ended(c, xm, pm) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return -rk4(c, x, p, hi).1;
        }
        (x, p) = (x1, p1);
    }
    f64::NAN
}

/// Head-on restitution of the Hertz law with the Tsuji dashpot of damping ratio `beta`.
pub fn restitution_for_beta(beta: f64) -> f64 {
    restitution_for_beta_with(beta, 1e-3)
}

thread_local! {
    static LAST: Cell<(u64, f64)> = const { Cell::new((u64::MAX, f64::NAN)) };
}

/// The damping ratio beta (>= 0) whose head-on restitution is `cor`, for `cor` in
/// [[`MIN_COR`], 1] (0 for cor = 1); NaN outside.
pub fn beta_for_cor(cor: f64) -> f64 {
    if !(MIN_COR..=1.0).contains(&cor) {
        return f64::NAN;
    }
    if cor == 1.0 {
        return 0.0;
    }
    let cached = LAST.with(|c| c.get());
    if cached.0 == cor.to_bits() {
        return cached.1;
    }
    let beta = invert(cor);
    LAST.with(|c| c.set((cor.to_bits(), beta)));
    beta
}

/// The root of e(beta) - cor, bracketed from the linear-spring guess and closed by the
/// project's one root finder ([`roots::bracket`], Brent's method) to 1e-13 of beta (e falls by
/// at most ~1 per unit of beta).
fn invert(cor: f64) -> f64 {
    let g = |b: f64| restitution_for_beta(b) - cor;
    let ln = cor.ln();
    let guess = -ln / (ln * ln + PI2).sqrt();
    let (mut lo, mut hi) = (0.0, guess.max(1e-3));
    let (mut glo, mut ghi) = (1.0 - cor, g(hi));
    while ghi > 0.0 {
        (lo, glo) = (hi, ghi);
        hi *= 2.0;
        ghi = g(hi);
    }
    let (near, far) = roots::bracket(g, (lo, glo), (hi, ghi), 1e-13 * hi);
    0.5 * (near + far)
}

const PI2: f64 = std::f64::consts::PI * std::f64::consts::PI;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elastic_hertz_returns_the_speed() {
        // Without damping the law is conservative: e = 1.
        let e = restitution_for_beta(0.0);
        assert!((e - 1.0).abs() < 1e-10, "{e}");
    }

    #[test]
    fn solver_converges() {
        for b in [0.05, 0.3, 1.0, 3.0] {
            let e1 = restitution_for_beta_with(b, 1e-3);
            let e2 = restitution_for_beta_with(b, 5e-4);
            println!("beta {b}: e {e1}, change on halving {:e}", e1 - e2);
            assert!((e1 - e2).abs() < 1e-9, "beta {b}: {e1} vs {e2}");
        }
    }

    #[test]
    fn map_is_monotone() {
        // Less restitution takes more damping; prints the map documented in docs/model.md 14.3.
        let cors = [0.01, 0.1, 0.2, 0.5, 0.8, 0.9, 0.98, 1.0];
        let betas: Vec<f64> = cors.iter().map(|&c| beta_for_cor(c)).collect();
        println!("cor {cors:?}\nbeta {betas:?}");
        assert!(betas.windows(2).all(|w| w[0] > w[1]) && betas[7] == 0.0);
    }

    #[test]
    fn calibration_inverts() {
        for cor in [MIN_COR, 0.1, 0.2, 0.5, 0.8, 0.98, 0.999] {
            let b = beta_for_cor(cor);
            assert!((restitution_for_beta(b) - cor).abs() < 1e-11, "cor {cor}");
        }
        assert!(beta_for_cor(0.0).is_nan() && beta_for_cor(1.5).is_nan());
    }
}
