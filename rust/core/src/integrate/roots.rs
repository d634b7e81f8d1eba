//! Roots and peaks of continuous functions of one variable: where a function changes sign
//! inside a bracket (the fixed-step path's corner crossings, the adaptive path's switches),
//! and where it peaks inside an interval (the deepest point of an adaptive step).

/// The final bracket `(near, far)` of a change of sign of `g` between `lo` (value `g_lo`) and
/// `hi` (value `g_hi`), given on opposite sides (`g <= 0` counts as one side, `g > 0` as the
/// other): `near` still on the side of `lo`, `far` on the side of `hi`, at most `width` apart
/// (or adjacent floats, if `width` is below their spacing).
///
/// The ITP method (interpolate, truncate, project; Oliveira & Takahashi, ACM TOMS 47 (2021)
/// 5): regula falsi, nudged towards the midpoint by 0.2 w^2 / w_0 so that the bracket closes
/// from both sides, and projected into a shrinking interval about the midpoint so that it never
/// takes more than one evaluation beyond bisection's. For smooth functions 10 to 25
/// evaluations take a bracket of one step to 1e-14 of it (the alternation of secant and
/// bisection it replaces needed about fifty). Non-finite values (an event function that is
/// -inf where its switch cannot happen) bisect.
pub(crate) fn bracket(
    g: impl Fn(f64) -> f64,
    (mut lo, mut g_lo): (f64, f64),
    (mut hi, mut g_hi): (f64, f64),
    width: f64,
) -> (f64, f64) {
    let lo_side = g_lo > 0.0;
    debug_assert!(
        lo_side != (g_hi > 0.0),
        "no change of sign between the ends"
    );
    let w0 = (hi - lo).abs();
    let eps = 0.5 * width.max(0.0);
    // Evaluations allowed beyond bisection's count: one (n_0 = 1).
    let n_max = if eps > 0.0 {
        (w0 / (2.0 * eps)).log2().ceil().max(0.0) + 1.0
    } else {
        f64::INFINITY
    };
    let kappa1 = 0.2 / w0;
    for j in 0..1100 {
        let w = (hi - lo).abs();
        let mid = 0.5 * (lo + hi);
        if w <= 2.0 * eps || mid == lo || mid == hi {
            break;
        }
        let radius = eps * (n_max - j as f64).exp2() - 0.5 * w;
        let falsi = (g_hi * lo - g_lo * hi) / (g_hi - g_lo);
        let falsi = if falsi.is_finite() { falsi } else { mid };
        let towards = (mid - falsi).signum();
        let delta = kappa1 * w * w;
        let truncated = if delta <= (mid - falsi).abs() {
            falsi + towards * delta
        } else {
            mid
        };
        let x = if (truncated - mid).abs() <= radius {
            truncated
        } else {
            mid - towards * radius
        };
        let x = if x > lo.min(hi) && x < lo.max(hi) {
            x
        } else {
            mid
        };
        let y = g(x);
        if (y > 0.0) == lo_side {
            (lo, g_lo) = (x, y);
        } else {
            (hi, g_hi) = (x, y);
        }
    }
    (lo, hi)
}

/// The largest value of `f` on [`a`, `b`] near `mid` (the interval's midpoint, where `f` is
/// `f_mid`), to a position of about `tol`: Brent's method (Brent, Algorithms for Minimization
/// without Derivatives, 1973, ch. 5), parabolic interpolation safeguarded by golden sections.
/// About ten evaluations where a golden-section search to the same position took 35. Returns
/// the largest value seen (a local maximum; the ends are the caller's).
pub(crate) fn peak(f: impl Fn(f64) -> f64, (a, b): (f64, f64), f_mid: f64, tol: f64) -> f64 {
    // Brent's local minimizer on -f.
    let golden = 0.5 * (3.0 - 5f64.sqrt());
    let (mut a, mut b) = (a, b);
    let mut x = 0.5 * (a + b);
    let (mut w, mut v) = (x, x);
    let mut fx = -f_mid;
    let (mut fw, mut fv) = (fx, fx);
    let (mut d, mut e) = (0.0f64, 0.0f64);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        let tol1 = 1.5e-8 * x.abs() + tol;
        let tol2 = 2.0 * tol1;
        if (x - m).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let (mut p, mut q, mut r) = (0.0, 0.0, 0.0);
        if e.abs() > tol1 {
            r = (x - w) * (fx - fv);
            q = (x - v) * (fx - fw);
            p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            r = e;
            e = d;
        }
        if p.abs() < (0.5 * q * r).abs() && p > q * (a - x) && p < q * (b - x) {
            // A parabolic step, kept at least tol1 from the ends.
            d = p / q;
            let u = x + d;
            if u - a < tol2 || b - u < tol2 {
                d = if x < m { tol1 } else { -tol1 };
            }
        } else {
            e = if x < m { b - x } else { a - x };
            d = golden * e;
        }
        let u = x + if d.abs() >= tol1 { d } else { tol1.copysign(d) };
        let fu = -f(u);
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    -fx
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    /// Counts the evaluations of `g` and returns the bracket.
    fn counted(g: impl Fn(f64) -> f64, lo: f64, hi: f64, width: f64) -> ((f64, f64), u32) {
        let n = Cell::new(0);
        let f = |x: f64| {
            n.set(n.get() + 1);
            g(x)
        };
        let b = bracket(f, (lo, g(lo)), (hi, g(hi)), width);
        (b, n.get())
    }

    #[test]
    fn brackets_the_root_of_smooth_functions_in_few_evaluations() {
        // Roots known in closed form: sqrt(2) - 1, pi / 4, 0.3^(2/3) and ln 2 on [0, 1].
        let cases: [(&dyn Fn(f64) -> f64, f64); 4] = [
            (&|x: f64| (x + 1.0) * (x + 1.0) - 2.0, 2f64.sqrt() - 1.0),
            (
                &|x: f64| (x - std::f64::consts::FRAC_PI_4).sin(),
                std::f64::consts::FRAC_PI_4,
            ),
            (&|x: f64| x.powf(1.5) - 0.3, 0.3f64.powf(2.0 / 3.0)),
            (&|x: f64| x.exp() - 2.0, 2f64.ln()),
        ];
        let mut total = 0;
        for (g, root) in cases {
            let ((near, far), evals) = counted(g, 0.0, 1.0, 1e-14);
            total += evals;
            assert!(
                near <= root + 1e-15 && root <= far + 1e-15,
                "{near} {root} {far}"
            );
            assert!(far - near <= 1e-14, "{near} {far}");
            assert!(g(near) <= 0.0 && g(far) > 0.0);
            // Never more than bisection's 47 and one.
            assert!(evals <= 48, "{evals} evaluations");
        }
        // Bisection would take 188; measured 55.
        assert!(total <= 70, "{total} evaluations");
    }

    #[test]
    fn brackets_from_either_side_and_keeps_the_sides() {
        // Decreasing: lo on the positive side, hi on the other.
        let g = |x: f64| 0.4 - x;
        let ((near, far), _) = counted(g, 0.0, 1.0, 1e-14);
        assert!(g(near) > 0.0 && g(far) <= 0.0 && far - near <= 1e-14);
        // A reversed interval (hi < lo) is bracketed too.
        let g = |x: f64| x - 0.7;
        let ((near, far), _) = counted(g, 1.0, 0.0, 1e-14);
        assert!(g(near) > 0.0 && g(far) <= 0.0 && near - far <= 1e-14);
    }

    #[test]
    fn a_step_function_and_non_finite_values_fall_back_to_bisection() {
        // A jump: no interpolation helps, bisection still closes the bracket on it.
        let g = |x: f64| if x > 0.123 { 1.0 } else { f64::NEG_INFINITY };
        let ((near, far), evals) = counted(g, 0.0, 1.0, 1e-12);
        assert!(near <= 0.123 && far > 0.123 && far - near <= 1e-12);
        assert!(evals <= 45, "{evals}");
        // A root on a flat stretch (the event function zero over an interval) ends in it.
        let g = |x: f64| (x - 0.5).max(0.0) - 1e-300;
        let ((near, far), _) = counted(g, 0.0, 1.0, 1e-14);
        assert!(g(near) <= 0.0 && g(far) > 0.0);
    }

    #[test]
    fn finds_peaks_in_few_evaluations() {
        // Peaks known in closed form: a parabola's vertex, sin at pi/2 (on [1, 2]), and
        // x^1.5 (1 - x) at 3/5.
        type Case<'a> = (&'a dyn Fn(f64) -> f64, (f64, f64), f64);
        let cases: [Case; 3] = [
            (&|x: f64| 1.0 - (x - 0.3) * (x - 0.3), (0.0, 1.0), 1.0),
            (&|x: f64| x.sin(), (1.0, 2.0), 1.0),
            (
                &|x: f64| x.powf(1.5) * (1.0 - x),
                (0.0, 1.0),
                0.6f64.powf(1.5) * 0.4,
            ),
        ];
        for (f, (a, b), top) in cases {
            let n = Cell::new(0);
            let counted = |x: f64| {
                n.set(n.get() + 1);
                f(x)
            };
            let got = peak(counted, (a, b), f(0.5 * (a + b)), 1e-8 * (b - a));
            assert!((got - top).abs() <= 1e-14, "{got} vs {top}");
            assert!(n.get() <= 15, "{} evaluations", n.get());
        }
    }
}
