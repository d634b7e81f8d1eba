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
//! where the clipped force reaches zero, located by bisection of the last step; accurate to
//! ~1e-11: halving the steps moves e by < 3e-12) and inverting e(beta) through a table of the
//! solver's e, computed lazily on a grid of ln beta and interpolated by degree-7 polynomials
//! (`beta_for_cor`): e of the beta found is the solver's within 2e-14 of cor, and the
//! inversion costs a few hundred nanoseconds once its nodes exist, so a calibration may vary
//! cor per case. (It replaced Brent's method on the solver itself, ~1.5 ms per value, which
//! its tests keep as the reference.)

use std::sync::atomic::{AtomicU64, Ordering};

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

/// The table of e(beta) that [`beta_for_cor`] inverts: nodes uniform in u = ln beta, from
/// [`U_FIRST`] in steps of [`U_STEP`]. In ln beta the law's expansion at small beta (powers of
/// beta, fractional ones included, from the clip's end near x = 0) becomes a sum of
/// exponentials of u, smooth at every scale, so one step serves from cor 1 - 1e-7 to 0.01.
const NODES: usize = 576;
/// ln beta at the first node: beta = e^-16 = 1.1e-7 (cor 1 - 1.6e-7); below it, e is linear in
/// beta to ~1e-14 (see [`beta_for_cor`]).
const U_FIRST: f64 = -16.0;
/// Spacing of the nodes in ln beta: the interpolant's largest gap to the solver at the
/// midpoints of the cells is 1.5e-14 (the test `table_matches_the_solver`; 3e-12 at twice
/// the spacing, 200 times more, as a degree-7 interpolant's error should grow).
const U_STEP: f64 = 1.0 / 32.0;
/// Nodes in one local interpolating polynomial (degree 7).
const STENCIL: usize = 8;
/// Marks a node not yet computed (a NaN's bits: no node has it).
const EMPTY: u64 = u64::MAX;

/// The nodes' e, computed on first use by whichever thread needs one first (a node is a pure
/// function of its index, so a race computes the same bits twice and the results never depend
/// on the order). Each costs one solution of the law, a tenth or less of what one inversion by
/// Brent's method cost; a sweep over cor in [0.5, 0.99] touches about 150 of the 576, once per
/// process.
static TABLE: [AtomicU64; NODES] = [const { AtomicU64::new(EMPTY) }; NODES];

/// The table's node `i`: e at beta = exp([`U_FIRST`] + i [`U_STEP`]).
fn node(i: usize) -> f64 {
    let bits = TABLE[i].load(Ordering::Relaxed);
    if bits != EMPTY {
        return f64::from_bits(bits);
    }
    let e = restitution_for_beta(node_beta(i));
    TABLE[i].store(e.to_bits(), Ordering::Relaxed);
    e
}

fn node_beta(i: usize) -> f64 {
    (U_FIRST + i as f64 * U_STEP).exp()
}

/// The damping ratio beta (>= 0) whose head-on restitution is `cor`, for `cor` in
/// [[`MIN_COR`], 1] (0 for cor = 1); NaN outside.
///
/// Found from the table of e(ln beta) ([`node`]): the cell holding `cor` by bisection over
/// the nodes (e falls monotonically), then the root of the degree-7 polynomial through the
/// eight nodes around that cell by Newton's method from the cell's linear interpolation,
/// polished to the floats' resolution. Its e agrees with the solver's to ~2e-14 (the test
/// `table_matches_the_solver`; the solver itself is accurate to ~1e-11), so a sweep may vary
/// cor per case at about the cost of a fixed one. Above the first node (cor > 1 - 1.6e-7) the map is
/// the line through beta = 0 and that node: e = 1 - a beta (1 + O(beta)) errs there by ~a
/// beta_0 beta < 1e-13.
pub fn beta_for_cor(cor: f64) -> f64 {
    if !(MIN_COR..=1.0).contains(&cor) {
        return f64::NAN;
    }
    if cor == 1.0 {
        return 0.0;
    }
    let first = node(0);
    if cor >= first {
        return node_beta(0) * (1.0 - cor) / (1.0 - first);
    }
    // The cell [lo, lo + 1] with node(lo) > cor >= node(lo + 1).
    let (mut lo, mut hi) = (0, NODES - 1);
    debug_assert!(node(hi) < MIN_COR, "the table must reach below MIN_COR");
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if node(mid) > cor {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let start = lo.saturating_sub(STENCIL / 2 - 1).min(NODES - STENCIL);
    let poly = Stencil::new(start);
    let (e_lo, e_hi) = (node(lo), node(hi));
    // t: the position in node spacings from the stencil's first node.
    let (t_lo, t_hi) = ((lo - start) as f64, (hi - start) as f64);
    let mut t = t_lo + (e_lo - cor) / (e_lo - e_hi);
    for _ in 0..20 {
        let (p, dp) = poly.value_and_slope(t);
        let step = (p - cor) / dp;
        t = (t - step).clamp(t_lo, t_hi);
        if step.abs() <= 1e-15 * t.abs().max(1.0) {
            break;
        }
    }
    (U_FIRST + (start as f64 + t) * U_STEP).exp()
}

/// The polynomial through [`STENCIL`] consecutive nodes in Newton's form: the forward
/// differences of the nodes divided by k!, in the position t counted in node spacings from
/// the first.
struct Stencil {
    coefficients: [f64; STENCIL],
}

impl Stencil {
    fn new(start: usize) -> Self {
        let mut c: [f64; STENCIL] = std::array::from_fn(|j| node(start + j));
        for k in 1..STENCIL {
            for j in (k..STENCIL).rev() {
                c[j] = (c[j] - c[j - 1]) / k as f64;
            }
        }
        Stencil { coefficients: c }
    }

    /// The polynomial and its derivative in t, by Horner's scheme on the Newton form.
    fn value_and_slope(&self, t: f64) -> (f64, f64) {
        let c = &self.coefficients;
        let (mut p, mut dp) = (c[STENCIL - 1], 0.0);
        for k in (0..STENCIL - 1).rev() {
            dp = dp * (t - k as f64) + p;
            p = p * (t - k as f64) + c[k];
        }
        (p, dp)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::roots;

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

    /// The root of e(beta) - cor by the project's root finder ([`roots::bracket`], Brent's
    /// method) on the solver itself, to 1e-14 of beta: what the table replaced, kept as its
    /// reference.
    fn beta_by_root(cor: f64) -> f64 {
        let g = |b: f64| restitution_for_beta(b) - cor;
        let (mut lo, mut hi) = (0.0, 1e-3);
        let (mut glo, mut ghi) = (1.0 - cor, g(hi));
        while ghi > 0.0 {
            (lo, glo) = (hi, ghi);
            hi *= 2.0;
            ghi = g(hi);
        }
        let (near, far) = roots::bracket(g, (lo, glo), (hi, ghi), 1e-14 * hi);
        0.5 * (near + far)
    }

    #[test]
    fn table_agrees_with_the_root_finder() {
        // cor from 0.01 to 1 - 1e-9, denser towards 1 (1 - cor log-spaced), and the edges.
        let mut worst: (f64, f64) = (0.0, 0.0);
        let cors = (0..=90)
            .map(|k| 1.0 - 0.99 * 10f64.powf(-(k as f64) / 10.0))
            .chain([MIN_COR, 0.5, 0.98, 1.0 - 1.6e-7, 1.0 - 1e-12]);
        for cor in cors {
            let (table, root) = (beta_for_cor(cor), beta_by_root(cor));
            let miss = (restitution_for_beta(table) - cor).abs();
            // beta itself to 1e-9 of itself, or to 1e-14 where beta is tiny (there e falls
            // by about pi per unit of beta, and the root finder stops at 1e-14 of its bracket).
            let gap = (table - root).abs();
            worst = (worst.0.max(miss), worst.1.max(gap / root));
            assert!(miss < 1e-13, "cor {cor}: e(beta) - cor = {miss:e}");
            assert!(
                gap < 1e-9 * root + 1e-14,
                "cor {cor}: beta {table} against {root}"
            );
        }
        println!(
            "largest |e(beta) - cor| {:e}, largest relative beta gap {:e}",
            worst.0, worst.1
        );
    }

    #[test]
    fn table_matches_the_solver() {
        // The interpolant at the middle of every cell against the solver there.
        let mut worst: f64 = 0.0;
        for lo in 0..NODES - 1 {
            let start = lo.saturating_sub(STENCIL / 2 - 1).min(NODES - STENCIL);
            let t = (lo - start) as f64 + 0.5;
            let beta = (U_FIRST + (lo as f64 + 0.5) * U_STEP).exp();
            let gap = (Stencil::new(start).value_and_slope(t).0 - restitution_for_beta(beta)).abs();
            worst = worst.max(gap);
        }
        println!("largest gap of the interpolant to the solver: {worst:e}");
        assert!(worst < 1e-13, "{worst:e}");
        assert!(node(NODES - 1) < MIN_COR, "the table ends above MIN_COR");
    }
}
