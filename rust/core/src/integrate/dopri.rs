//! The Dormand-Prince 5(4) step with its embedded error estimate and its dense output, for any
//! autonomous ODE y' = f(y) of `N` components: the stepper the adaptive impact loop
//! (`crate::impact::adaptive`) drives. What a stage's evaluation yields besides the derivative
//! (forces, event samples) is the caller's: it sees every stage through its closure.

// Dormand-Prince 5(4) tableau (Dormand & Prince 1980; dense output of Hairer, Norsett & Wanner)

// The forces do not depend on time explicitly, so the nodes c_i are not needed.
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// 5th-order minus embedded 4th-order weights.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// Dense-output weights (4th-order continuous extension).
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// The nodes c_i of the stages (fractions of the step at which each stage is evaluated).
pub const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];

/// One Runge-Kutta step of an `N`-component state with its dense output over the first `M`
/// components (those whose values inside a step are read; the rest, e.g. accumulated works, are
/// only needed at the step's ends). `Default`: a blank one for [`DenseStep::take`] to write into.
pub struct DenseStep<const N: usize, const M: usize> {
    /// The state at the step's start.
    pub y0: [f64; N],
    /// The 5th-order state at the step's end.
    pub y1: [f64; N],
    k: [[f64; N]; 7],
    h: f64,
    /// The embedded error estimate of each component (5th minus 4th order).
    pub err: [f64; N],
    /// The dense output's coefficients r2 ... r5 of each of the first `M` components (see
    /// [`DenseStep::component_at`]), formed on its first call: the search for switches inside a
    /// step calls it many times (it took a sixth of the adaptive path's time when each call
    /// formed them again).
    dense: std::cell::OnceCell<[[f64; 4]; M]>,
}

impl<const N: usize, const M: usize> Default for DenseStep<N, M> {
    fn default() -> Self {
        DenseStep {
            y0: [0.0; N],
            y1: [0.0; N],
            k: [[0.0; N]; 7],
            h: 0.0,
            err: [0.0; N],
            dense: std::cell::OnceCell::new(),
        }
    }
}

impl<const N: usize, const M: usize> DenseStep<N, M> {
    /// Takes one step of length `h` from `y0`, whose derivative `k1` is known, in place (a step
    /// of ~1.4 kB returned by value was copied twice per attempt). `stage(i, y_i, k_out)`
    /// evaluates the derivative at stage `i` (1 ... 6) into `k_out`; the 6th stage is the
    /// 5th-order solution itself (first same as last), so the caller's last evaluation is the
    /// one at `y1`. Fills `err` with the embedded estimate; the norm is the caller's.
    #[inline]
    pub fn take(
        &mut self,
        y0: &[f64; N],
        k1: &[f64; N],
        h: f64,
        mut stage: impl FnMut(usize, &[f64; N], &mut [f64; N]),
    ) {
        let k = &mut self.k;
        k[0] = *k1;
        for st in 1..7 {
            // Component-wise over the stages before (the inner loop over the components
            // vectorises; summed per component over the stages it did not).
            let mut acc = [0.0; N];
            for (j, kj) in k.iter().enumerate().take(st) {
                let a = A[st][j];
                for i in 0..N {
                    acc[i] += a * kj[i];
                }
            }
            let yi: [f64; N] = std::array::from_fn(|i| y0[i] + h * acc[i]);
            stage(st, &yi, &mut k[st]);
            if st == 6 {
                self.y1 = yi;
            }
        }
        let mut err_vec = [0.0; N];
        for (kj, e_j) in k.iter().zip(E) {
            for i in 0..N {
                err_vec[i] += e_j * kj[i];
            }
        }
        self.err = err_vec.map(|x| h * x);
        self.y0 = *y0;
        self.h = h;
        self.dense = std::cell::OnceCell::new();
    }

    /// The step's length.
    pub fn h_len(&self) -> f64 {
        self.h
    }

    /// The derivative at `y1` (the next step's first stage when it starts there).
    pub fn k_end(&self) -> [f64; N] {
        self.k[6]
    }

    /// The whole state (all `N` components, the last `N - M` formed here rather than kept) at
    /// fraction `theta` of the step and, per component, how far it lies from the cubic Hermite
    /// interpolant of the step's ends and their derivatives (one order lower): an estimate of
    /// the interpolant's own error that overstates it.
    pub fn at_with_gap(&self, theta: f64) -> ([f64; N], [f64; N]) {
        self.at_with_scaled_gap(theta, |_, _| 1.0)
    }

    /// [`Self::at_with_gap`], the gap scaled to an estimate of the next, omitted term: the
    /// dense output's terms r3 ... r5 (Hermite's, then the quartic one) carry h^2 ... h^4
    /// times the solution's derivatives, so where they shrink term by term the omitted one is
    /// about the gap times |r5 / r4| (~ h over the solution's time scale); near a root
    /// singularity of the force the ratio nears 1 and the estimate is the gap (the ratio
    /// capped at 1, also where r4 vanishes by chance).
    pub fn at_with_estimate(&self, theta: f64) -> ([f64; N], [f64; N]) {
        self.at_with_scaled_gap(theta, |r4, r5| {
            let ratio = (r5 / r4).abs();
            if ratio < 1.0 {
                ratio
            } else {
                1.0
            }
        })
    }

    /// The state at `theta` and each component's gap to the cubic Hermite interpolant, times
    /// `scale(r4, r5)` of its dense-output coefficients (formed once per component).
    fn at_with_scaled_gap(
        &self,
        theta: f64,
        scale: impl Fn(f64, f64) -> f64,
    ) -> ([f64; N], [f64; N]) {
        let eta = 1.0 - theta;
        let (h00, h10) = ((1.0 + 2.0 * theta) * eta * eta, theta * eta * eta);
        let (h01, h11) = (theta * theta * (3.0 - 2.0 * theta), -theta * theta * eta);
        let (mut s, mut gap) = ([0.0; N], [0.0; N]);
        for i in 0..N {
            let c = if i < M {
                self.dense_coefficients()[i]
            } else {
                self.coefficients(i)
            };
            s[i] = self.interpolate(theta, i, c);
            let hermite = h00 * self.y0[i]
                + h10 * self.h * self.k[0][i]
                + h01 * self.y1[i]
                + h11 * self.h * self.k[6][i];
            gap[i] = (s[i] - hermite).abs() * scale(c[2], c[3]);
        }
        (s, gap)
    }

    /// The state at fraction `theta` of the step (4th-order interpolant) in its first `M`
    /// components; the others are the step's start values, not interpolated.
    pub fn at(&self, theta: f64) -> [f64; N] {
        let mut s = self.y0;
        for (i, s_i) in s.iter_mut().enumerate().take(M) {
            *s_i = self.component_at(theta, i);
        }
        s
    }

    /// [`DenseStep::at`] at the step's end (`theta` = 1), the same bits, without forming the
    /// dense output's coefficients: there the interpolant is y0 + (y1 - y0), its other terms
    /// times eta = 0 (a zero added to y1 - y0 changes it only where it is -0, y0 = +0, and
    /// then not y0 plus it). Every switch's search samples the step's end first, and most
    /// steps contain no switch: forming the coefficients there was a twelfth of two discs'
    /// impact.
    pub fn at_end(&self) -> [f64; N] {
        let mut s = self.y0;
        for (i, s_i) in s.iter_mut().enumerate().take(M) {
            *s_i = self.component_at_end(i);
        }
        s
    }

    /// Component `i` (< `M`) of [`DenseStep::at_end`] alone.
    #[inline]
    pub fn component_at_end(&self, i: usize) -> f64 {
        self.y0[i] + (self.y1[i] - self.y0[i])
    }

    /// Component `i` (< `M`) of [`DenseStep::at`] alone: a search that follows one component
    /// (a disc's deepest point follows v_y only) need not form the whole state.
    #[inline]
    pub fn component_at(&self, theta: f64, i: usize) -> f64 {
        self.interpolate(theta, i, self.dense_coefficients()[i])
    }

    /// The dense output's coefficients of the first `M` components, formed on first use.
    #[inline]
    fn dense_coefficients(&self) -> &[[f64; 4]; M] {
        self.dense
            .get_or_init(|| std::array::from_fn(|i| self.coefficients(i)))
    }

    /// The dense output's coefficients r2 ... r5 of component `i`.
    #[inline]
    fn coefficients(&self, i: usize) -> [f64; 4] {
        let r2 = self.y1[i] - self.y0[i];
        let r3 = self.h * self.k[0][i] - r2;
        let r4 = r2 - self.h * self.k[6][i] - r3;
        let r5 = self.h * (0..7).map(|j| D[j] * self.k[j][i]).sum::<f64>();
        [r2, r3, r4, r5]
    }

    /// Component `i`'s value at `theta` from its coefficients.
    #[inline]
    fn interpolate(&self, theta: f64, i: usize, [r2, r3, r4, r5]: [f64; 4]) -> f64 {
        let eta = 1.0 - theta;
        self.y0[i] + theta * (r2 + eta * (r3 + theta * (r4 + eta * r5)))
    }
}

/// How many times the embedded estimate understates the error of a step across a root
/// singularity t^p of the force (p = 1/2: the area law's damping on a disc, ~ the chord; p =
/// 1/4: the Tsuji dashpot of a Hertz sphere), from the tableau: the error of the step's
/// quadrature of t^p over a step of unit length, against the embedded estimate of it, with
/// the singular point `rho` steps before the step's start (touch) or, `at_end`, after its end
/// (separation). At least 1. E.g. p = 1/2: 37 for a step from touch, 5.1 for one starting a
/// quarter of its length after it, 1.1 at one length; p = 1/4: 52, 5.8, 1.2.
pub fn root_error_ratio(p: f64, rho: f64, at_end: bool) -> f64 {
    // x^p by square roots for the laws' two roots: powf at every stage of the steps near
    // touch made this 7 % of the disc's instructions.
    let root = |x: f64| match p {
        0.5 => x.sqrt(),
        0.25 => x.sqrt().sqrt(),
        _ => x.powf(p),
    };
    let f = |c: f64| root((if at_end { 1.0 + rho - c } else { rho + c }).max(0.0));
    let exact = ((1.0 + rho) * root(1.0 + rho) - rho * root(rho)) / (p + 1.0);
    let quadrature: f64 = (0..6).map(|i| A[6][i] * f(C[i])).sum();
    let embedded: f64 = (0..7).map(|i| E[i] * f(C[i])).sum();
    let ratio = ((exact - quadrature) / embedded).abs();
    if ratio.is_finite() {
        ratio.max(1.0)
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Asserts that an error's ratio between steps h and h/2 lies in `range` (2^p for order p
    /// lies inside it), naming the order it shows where it does not.
    fn assert_halving_ratio(what: &str, ratio: f64, (lo, hi): (f64, f64)) {
        assert!(ratio > lo && ratio < hi, "{what}: order {}", ratio.log2());
    }

    /// One step of y' = -y from y = 1: the step's local error falls like h^6 (5th order), the
    /// embedded estimate like h^5, and the dense output at mid-step like h^5 (4th order), each
    /// against exp(-t); the estimate is of the size of the 4th-order error it measures.
    #[test]
    fn decay_step_converges_at_the_tableau_orders() {
        let errors = |h: f64| {
            let mut step = DenseStep::<1, 1>::default();
            step.take(&[1.0], &[-1.0], h, |_, y, k| k[0] = -y[0]);
            let local = (step.y1[0] - (-h).exp()).abs();
            let dense = (step.at(0.5)[0] - (-0.5 * h).exp()).abs();
            (local, step.err[0].abs(), dense)
        };
        let (l1, e1, d1) = errors(0.2);
        let (l2, e2, d2) = errors(0.1);
        assert_halving_ratio("local error", l1 / l2, (45.0, 90.0));
        assert_halving_ratio("estimate", e1 / e2, (24.0, 40.0));
        assert_halving_ratio("dense output", d1 / d2, (24.0, 40.0));
        assert!(
            e1 >= l1,
            "the estimate {e1} bounds the 5th-order error {l1}"
        );
        assert_eq!(step_ends(0.2), (1.0, 0.2));
    }

    /// [`DenseStep::at_end`] is [`DenseStep::at`] at theta = 1 bit for bit, in every
    /// component: on a damped oscillator with a drifting third component and a fourth left
    /// uninterpolated, from random states (signed zeros among them) and step lengths.
    #[test]
    fn the_end_without_coefficients_is_the_dense_outputs() {
        let mut seeded = crate::numerics::seeded::Seeded(3);
        let mut rng = move || seeded.uniform();
        let f = |y: &[f64; 4], k: &mut [f64; 4]| {
            *k = [y[1], -y[0] - 0.3 * y[1], 0.0 * y[0], y[0] * y[0]];
        };
        for case in 0..2000 {
            let zeros = [0.0, -0.0];
            let mut y0: [f64; 4] = std::array::from_fn(|_| 4.0 * rng() - 2.0);
            if case % 4 == 0 {
                (y0[0], y0[2]) = (zeros[case / 4 % 2], zeros[case / 8 % 2]);
            }
            let mut k1 = [0.0; 4];
            f(&y0, &mut k1);
            let mut step = DenseStep::<4, 3>::default();
            step.take(&y0, &k1, 10f64.powf(-4.0 * rng()), |_, y, k| f(y, k));
            let (dense, end) = (step.at(1.0), step.at_end());
            for i in 0..4 {
                assert_eq!(
                    dense[i].to_bits(),
                    end[i].to_bits(),
                    "{y0:?}, component {i}"
                );
                if i < 3 {
                    assert_eq!(step.component_at_end(i).to_bits(), end[i].to_bits());
                }
            }
        }
    }

    /// The step keeps its start and length, and the dense output meets both ends exactly.
    fn step_ends(h: f64) -> (f64, f64) {
        let mut step = DenseStep::<1, 1>::default();
        step.take(&[1.0], &[-1.0], h, |_, y, k| k[0] = -y[0]);
        assert!((step.at(1.0)[0] - step.y1[0]).abs() <= f64::EPSILON);
        (step.at(0.0)[0], step.h_len())
    }

    /// The dense output's error estimate inside a step: on a smooth solution (y' = -y), with
    /// the step's estimate's share th |err| that the adaptive path adds to it, it bounds the
    /// dense output's true error at every fraction; alone it falls at the dense output's
    /// order (like h^5), and lies far below the Hermite gap, which falls an order slower; on
    /// y' = sqrt(t) from the root (the area law's damping at touch) the ratio of the last
    /// terms nears 1 and the estimate stays the gap.
    #[test]
    fn dense_estimate_bounds_the_error_and_keeps_the_gap_at_a_root() {
        let smooth = |h: f64, th: f64| {
            let mut step = DenseStep::<1, 1>::default();
            step.take(&[1.0], &[-1.0], h, |_, y, k| k[0] = -y[0]);
            let (s, est) = step.at_with_estimate(th);
            let (_, gap) = step.at_with_gap(th);
            let share = th * step.err[0].abs();
            ((s[0] - (-th * h).exp()).abs(), est[0], gap[0], share)
        };
        for th in [0.05, 0.1, 0.3, 0.5, 0.8, 0.95] {
            let (err, est, gap, share) = smooth(0.2, th);
            assert!(
                share + est >= err,
                "th {th}: {share:e} + {est:e} below {err:e}"
            );
            assert!(est < 0.25 * gap, "th {th}: {est:e} vs gap {gap:e}");
        }
        let (_, e1, g1, _) = smooth(0.2, 0.5);
        let (_, e2, g2, _) = smooth(0.1, 0.5);
        assert_halving_ratio("estimate", e1 / e2, (24.0, 40.0));
        assert_halving_ratio("gap", g1 / g2, (12.0, 20.0));
        // y' = sqrt(t), y = (2/3) t^(3/2), t the first component's clock.
        let mut step = DenseStep::<2, 2>::default();
        step.take(&[0.0, 0.0], &[1.0, 0.0], 1.0, |_, y, k| {
            (k[0], k[1]) = (1.0, y[0].max(0.0).sqrt())
        });
        let (_, est) = step.at_with_estimate(0.5);
        let (_, gap) = step.at_with_gap(0.5);
        assert!(est[1] > 0.3 * gap[1], "{:e} vs {:e}", est[1], gap[1]);
    }

    /// The ratio by which the embedded estimate understates a step across a root: large for a
    /// step from the root (the quadrature error of sqrt(t) from 0, 2/3 - sum b_i sqrt(c_i),
    /// is ~1e-2 of the step against ~3e-4 estimated), falling as the step starts further from
    /// it, 1 once the estimate no longer understates; less so at the step's end (separation).
    #[test]
    fn root_error_ratio_falls_from_the_root_to_one() {
        for p in [0.25, 0.5] {
            let at = |rho: f64| root_error_ratio(p, rho, false);
            assert!(at(0.0) > 30.0, "p {p}: {}", at(0.0));
            let rhos = [0.0, 0.05, 0.25, 0.5];
            assert!(rhos.windows(2).all(|w| at(w[0]) > at(w[1])), "p {p}");
            assert!(at(0.25) > 4.0 && at(0.25) < 7.0, "p {p}: {}", at(0.25));
            assert_eq!(at(4.0), 1.0, "p {p}");
            // At the end the last stage sits on the root, and the estimate sees more of it.
            assert!(root_error_ratio(p, 0.0, true) > 4.0, "p {p} at the end");
        }
    }
}
