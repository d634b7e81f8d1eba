//! sin and cos of one angle together, for placing a polygon's corners: every evaluation of a
//! polygon's law turns its corners by its orientation, and the C library's `sincos` (its
//! general argument reduction and table) was a seventh of the 120-gon's adaptive impact. Here
//! the angle is reduced to |r| <= pi/4 by Cody and Waite's method (pi/2 split into three parts,
//! the first two with 33 significant bits, so that k times each is exact for |k| < 2^20) and
//! sin r, cos r are their Taylor series, whose first omitted terms r^19/19! and r^18/18! are
//! below 3e-18 relative at pi/4. The result is within about an ulp of the exact values;
//! beyond |phi| ~ 1.6e6 rad (and for NaN, infinities) the library's function answers.

/// pi/2 in three parts: P1 and P2 have 33 significant bits, P1 + P2 + P3 = pi/2 to 5e-17
/// of P3.
const P1: f64 = 1.5707963267341256;
const P2: f64 = 6.077100506303966e-11;
const P3: f64 = 2.0222662487959506e-21;

/// Below this |phi| the quadrant's index k < 2^20 and k P1, k P2 are exact.
const REDUCED_MAX: f64 = 1.6e6;

/// (sin r, cos r) for |r| <= pi/4 (a little beyond is harmless: the quadrant's rounding).
#[inline(always)]
fn kernel(r: f64) -> (f64, f64) {
    let z = r * r;
    // sin r = r + r^3 (-1/3! + z/5! - ...), cos r = 1 - z/2 + z^2 (1/4! - z/6! + ...): the
    // leading terms added last, so that their rounding is the result's.
    let s = -1.0 / 6.0
        + z * (1.0 / 120.0
            + z * (-1.0 / 5040.0
                + z * (1.0 / 362880.0
                    + z * (-1.0 / 39916800.0
                        + z * (1.0 / 6227020800.0
                            + z * (-1.0 / 1307674368000.0 + z * (1.0 / 355687428096000.0)))))));
    let c = 1.0 / 24.0
        + z * (-1.0 / 720.0
            + z * (1.0 / 40320.0
                + z * (-1.0 / 3628800.0
                    + z * (1.0 / 479001600.0
                        + z * (-1.0 / 87178291200.0 + z * (1.0 / 20922789888000.0))))));
    (r + r * z * s, 1.0 - (0.5 * z - z * z * c))
}

/// (sin phi, cos phi), as `f64::sin_cos` to about an ulp, faster for |phi| < 1.6e6.
#[inline(always)]
pub(crate) fn sin_cos(phi: f64) -> (f64, f64) {
    if phi.abs() <= std::f64::consts::FRAC_PI_4 {
        return kernel(phi);
    }
    if !(phi.abs() < REDUCED_MAX) {
        return phi.sin_cos();
    }
    let k = (phi * std::f64::consts::FRAC_2_PI).round();
    let r = ((phi - k * P1) - k * P2) - k * P3;
    let (s, c) = kernel(r);
    match (k as i64) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the C library over the reduced range and beyond: random angles, the quadrants'
    /// edges, multiples of pi/2 (where sin or cos is tiny and only an accurate reduction keeps
    /// its relative precision) and the fallbacks.
    #[test]
    fn agrees_with_the_library_to_an_ulp_or_two() {
        let mut angles: Vec<f64> = vec![0.0, -0.0, 1e-300, 1e-8, 0.5, 1.0, 3.0, 100.0, 1e5, 1.5e6];
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        for _ in 0..200_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let u = (seed >> 11) as f64 / (1u64 << 53) as f64;
            angles.push((u - 0.5) * 20.0);
            angles.push((u - 0.5) * 2e4);
        }
        for k in -2000..2000 {
            let q = k as f64 * std::f64::consts::FRAC_PI_2;
            angles.extend([
                q,
                q.next_up(),
                q.next_down(),
                q + std::f64::consts::FRAC_PI_4,
            ]);
        }
        for &phi in &angles {
            let (s, c) = sin_cos(phi);
            let (s0, c0) = phi.sin_cos();
            for (got, want) in [(s, s0), (c, c0)] {
                let ulp = (want.abs() * f64::EPSILON).max(f64::MIN_POSITIVE);
                assert!(
                    (got - want).abs() <= 2.0 * ulp,
                    "phi {phi:e}: {got:e} vs {want:e}"
                );
            }
            // Odd and even, exactly.
            assert_eq!(sin_cos(-phi), (-s, c), "phi {phi:e}");
        }
        for phi in [1e7, 1e300, f64::INFINITY, f64::NAN] {
            let (s, c) = sin_cos(phi);
            let (s0, c0) = phi.sin_cos();
            assert!(s.to_bits() == s0.to_bits() && c.to_bits() == c0.to_bits());
        }
    }
}
