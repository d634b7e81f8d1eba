//! Roots and peaks of continuous functions of one variable: where a function changes sign
//! inside a bracket (the fixed-step path's corner crossings, the adaptive path's switches),
//! and where it peaks inside an interval (the deepest point of an adaptive step).

/// Evaluations without the bracket halving after which [`bracket`] bisects: so never more than
/// four per halving, four times bisection's count at worst. (Brent's own safeguard, a step
/// shorter than half the one before last, bounds the count only by about its square: a triple
/// root takes 141 evaluations to 1e-14 of its bracket without this bound, 138 with it, which
/// tightened to two cost the smooth switches of the adaptive path 10 % more evaluations.)
const SLOW: u32 = 3;

/// The shortest step of [`bracket`], relative to half the width asked for (and never below the
/// floats' spacing): where the interpolation converges from one side, this step crosses the
/// root and closes the bracket. Brent's own shortest step, half the width, crossed it by up
/// to that much: a switch of the adaptive path then lay up to 5e-7 of its step past its root,
/// where the ITP method before had landed within ~1e-10, and the clip of a damper far
/// stiffer than the contact, a sliding mode, switched on and off in pieces too long for the
/// chatter remedy (8 of the extremes benchmark's 10^4 scenes ran out of steps instead of
/// separating in 200-42 000). A thousandth of it costs about one evaluation per impact on
/// the disc grid (11.6 at tol 1e-4, 15.4 at 1e-6 and 35.8 at 1e-9 against 10.7, 14.3 and
/// 32.3 with half the width; 1e-2 kept the 8 scenes too, 1e-1 lost one again).
const NUDGE: f64 = 1e-3;

/// The final bracket `(near, far)` of a change of sign of `g` between `lo` (value `g_lo`) and
/// `hi` (value `g_hi`), given on opposite sides (`g <= 0` counts as one side, `g > 0` as the
/// other): `near` still on the side of `lo`, `far` on the side of `hi`, at most `width` apart
/// (or adjacent floats, if `width` is below their spacing).
///
/// Brent's method (Brent, Algorithms for Minimization without Derivatives, 1973, ch. 4):
/// inverse quadratic interpolation through the last three points, or the secant through two,
/// kept well inside the bracket and shorter than half the step before last, else bisection
/// (and bisection after [`SLOW`] evaluations without the bracket halving); a step is never
/// shorter than [`NUDGE`] times half the width, so a convergence from one side closes the
/// bracket with one short step across the root. Smooth functions take 5 to 10 evaluations
/// from a bracket of one step to 1e-14 of it. The ITP method it replaces (interpolate,
/// truncate, project: regula falsi nudged towards the midpoint at every step) took 10 to 25,
/// and 7.6 per switch of the adaptive path on the disc grid at tol 1e-6 against 4.9 now: 5k
/// fewer instructions per impact, a sixth of that path's fixed cost. Non-finite values (an event function that is
/// -inf where its switch cannot happen) bisect.
pub(crate) fn bracket(
    g: impl Fn(f64) -> f64,
    (lo, g_lo): (f64, f64),
    (hi, g_hi): (f64, f64),
    width: f64,
) -> (f64, f64) {
    let lo_side = g_lo > 0.0;
    debug_assert!(
        lo_side != (g_hi > 0.0),
        "no change of sign between the ends"
    );
    let side = |v: f64| v > 0.0;
    let tol = 0.5 * width.max(0.0);
    // b: the latest point, c: the last one on the other side of the root (the bracket is
    // [b, c]), a: the point before b.
    let (mut a, mut fa, mut b, mut fb) = (lo, g_lo, hi, g_hi);
    let (mut c, mut fc) = (a, fa);
    let (mut d, mut e) = (b - a, b - a);
    // The bracket's width when it last halved, and the evaluations since.
    let (mut halved_at, mut since) = ((c - b).abs(), 0u32);
    for _ in 0..1100 {
        if side(fb) == side(fc) {
            (c, fc) = (a, fa);
            (d, e) = (b - a, b - a);
        }
        if fc.abs() < fb.abs() {
            // b the end with the smaller value, where the interpolation is centred.
            (a, fa) = (b, fb);
            (b, fb) = (c, fc);
            (c, fc) = (a, fa);
        }
        let m = 0.5 * (c - b);
        let mid = b + m;
        if m.abs() <= tol || mid == b || mid == c {
            break;
        }
        if 2.0 * m.abs() <= 0.5 * halved_at {
            (halved_at, since) = (2.0 * m.abs(), 0);
        } else {
            since += 1;
        }
        let interpolate = since < SLOW && e.abs() >= tol && fa.abs() > fb.abs() && fa.is_finite();
        let step = interpolate
            .then(|| interpolated_step((a, fa), (b, fb), (c, fc), e, tol))
            .flatten();
        (d, e) = match step {
            Some(step) => (step, d),
            None => (m, m),
        };
        (a, fa) = (b, fb);
        let nudge = (NUDGE * tol).max(4.0 * f64::EPSILON * b.abs());
        b += if d.abs() > nudge {
            d
        } else {
            nudge.copysign(m)
        };
        fb = g(b);
    }
    if side(fb) == lo_side {
        (b, c)
    } else {
        (c, b)
    }
}

/// Brent's interpolated step from `b` (the bracket's end with the smaller value; `c` the other
/// end, `a` the point before `b`): inverse quadratic through the three, or the secant where
/// `a` is `c`. `None` where it would not fall well inside the bracket or not be shorter than
/// half `e`, the step before last (the interpolation is not converging: bisect).
fn interpolated_step(
    (a, fa): (f64, f64),
    (b, fb): (f64, f64),
    (c, fc): (f64, f64),
    e: f64,
    tol: f64,
) -> Option<f64> {
    let m = 0.5 * (c - b);
    let s = fb / fa;
    let (mut p, mut q) = if a == c {
        (2.0 * m * s, 1.0 - s)
    } else {
        let (q, r) = (fa / fc, fb / fc);
        (
            s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0)),
            (q - 1.0) * (r - 1.0) * (s - 1.0),
        )
    };
    if p > 0.0 {
        q = -q;
    } else {
        p = -p;
    }
    let inside = 2.0 * p < 3.0 * m * q - (tol * q).abs();
    let converging = p < (0.5 * e * q).abs();
    (p.is_finite() && q.is_finite() && inside && converging).then(|| p / q)
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

/// The x in (0, `hi`] at which an increasing power-like `f` (its value and derivative; f(0) =
/// 0) reaches `target`, from `at_hi` = f(`hi`) >= `target`: [`log_newton_below`] started at
/// `hi`, except where a step lands on the root exactly (f(x) = target): that x, at the
/// bracket's end, is taken for a step out of the bracket and bisected away from (up to ~40
/// evaluations more, to about the same root), as the plate's depth estimate has always done
/// (its records depend on it to the last bit).
pub fn log_newton(f: impl Fn(f64) -> (f64, f64), target: f64, hi: f64, at_hi: (f64, f64)) -> f64 {
    newton_in_logs(f, target, (hi, at_hi), hi, false).unwrap_or(hi)
}

/// The x in (0, `hi`] at which an increasing power-like `f` (its value and derivative; f(0) =
/// 0) reaches `target`, started at `x0` in (0, `hi`] (`at_x0` = f(`x0`)); `None` where f(`hi`)
/// falls short of `target` (evaluated only where the iterates would pass `hi`: a start near
/// the root never pays it). Newton's method on ln f against ln x: a power of x is solved in
/// one step, so the depths of tiny and huge speeds alike take a handful of evaluations
/// (bisection to the last bit took about 60); a step that leaves the bracket of the root
/// bisects instead. Converged to 1e-14 relative.
pub fn log_newton_below(
    f: impl Fn(f64) -> (f64, f64),
    target: f64,
    start: (f64, (f64, f64)),
    hi: f64,
) -> Option<f64> {
    newton_in_logs(f, target, start, hi, true)
}

/// [`log_newton_below`], returning an iterate where f equals `target` if `exact_stops`.
fn newton_in_logs(
    f: impl Fn(f64) -> (f64, f64),
    target: f64,
    (x0, at_x0): (f64, (f64, f64)),
    hi: f64,
    exact_stops: bool,
) -> Option<f64> {
    let (mut lo, mut hi_bound) = (0.0, hi);
    // Whether f(hi) >= target is known: the root then lies in the bracket.
    let mut bracketed = x0 >= hi;
    if bracketed && at_x0.0 < target {
        return None;
    }
    let (mut x, (mut v, mut dv)) = (x0, at_x0);
    for _ in 0..200 {
        if exact_stops && v == target {
            return Some(x);
        }
        if v > target {
            (hi_bound, bracketed) = (x, true);
        } else {
            lo = x;
        }
        // d ln f / d ln x = x f' / f; one Newton step in ln x.
        let next = x * ((target / v).ln() / (x * dv / v)).exp();
        if !bracketed && (next >= hi_bound || next.is_nan()) {
            // Past the largest x allowed, whose value has not been needed so far.
            let at_hi = f(hi);
            if at_hi.0 < target {
                return None;
            }
            ((x, (v, dv)), bracketed) = ((hi, at_hi), true);
            continue;
        }
        let next = if next > lo && next < hi_bound && next.is_finite() {
            next
        } else {
            0.5 * (lo + hi_bound)
        };
        if (next - x).abs() <= 1e-14 * x || next == lo || next == hi_bound {
            return Some(next);
        }
        x = next;
        (v, dv) = f(x);
    }
    Some(x)
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
            // Each well under bisection's 47.
            assert!(evals <= 12, "{evals} evaluations");
        }
        // Bisection would take 188; measured 29 (the ITP method before took 55).
        assert!(total <= 40, "{total} evaluations");
    }

    #[test]
    fn hard_roots_fall_back_to_bisection_in_bounded_evaluations() {
        // Where interpolation converges slowly or not at all (a triple root, a root where the
        // function is singular, a steep front): at most four evaluations per halving of the
        // bracket (bisection's 47 and one, four times; the triple root takes 138).
        let cases: [(&dyn Fn(f64) -> f64, f64); 3] = [
            (&|x: f64| (x - 1.0 / 3.0).powi(3), 1.0 / 3.0),
            (&|x: f64| x.sqrt() - 1e-3, 1e-6),
            (&|x: f64| (1e3 * (x - 0.77)).tanh(), 0.77),
        ];
        for (g, root) in cases {
            let ((near, far), evals) = counted(g, 0.0, 1.0, 1e-14);
            assert!(g(near) <= 0.0 && g(far) > 0.0 && far - near <= 1e-14);
            assert!((near - root).abs() <= 1e-14, "{near} {root}");
            assert!(evals <= 4 * 48, "{evals} evaluations");
        }
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

    /// From a start on either side of the root, or at the top: the root of a power law in
    /// one step, of a power law bent by a factor in a handful; the top evaluated only where the root lies beyond it, and refused there.
    #[test]
    fn log_newton_below_finds_the_root_or_refuses_past_the_top() {
        let counted = |p: f64, bend: f64| {
            let n = Cell::new(0);
            let f = move |x: f64| {
                (
                    x.powf(p) * (1.0 + bend * x),
                    x.powf(p - 1.0) * (p + bend * (p + 1.0) * x),
                )
            };
            (n, f)
        };
        for (p, bend) in [(2.5, 0.0), (1.5, 0.0), (2.5, 0.3), (3.0, -0.4)] {
            let (n, f) = counted(p, bend);
            let g = |x: f64| {
                n.set(n.get() + 1);
                f(x)
            };
            let root = 0.3;
            let target = f(root).0;
            for x0 in [0.05, 0.29, 0.31, 0.9, 1.0] {
                n.set(0);
                let got = log_newton_below(&g, target, (x0, f(x0)), 1.0).unwrap();
                assert!((got - root).abs() <= 1e-14 * root, "p {p}, x0 {x0}: {got}");
                let most = if bend == 0.0 { 2 } else { 6 };
                assert!(n.get() <= most, "p {p} bend {bend} x0 {x0}: {}", n.get());
            }
            // The root beyond the top: refused, from below the top and at it.
            for x0 in [0.05, 0.5, 1.0] {
                let over = f(1.2).0;
                assert_eq!(
                    log_newton_below(&g, over, (x0, f(x0)), 1.0),
                    None,
                    "x0 {x0}"
                );
            }
        }
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
