//! The Dormand-Prince 5(4) step with its embedded error estimate and its dense output.

use super::law::{Eval, Reference};
use super::piece::{Mode, Tan};
use super::{State, NS, XI};

/// The components the forces depend on: x, y, phi, the velocities and the spring (the works
/// follow them).
const MECHANICAL: usize = XI + 1;

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
pub(super) const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];

/// One accepted Runge-Kutta step with what its dense output needs (`Default`: a blank one for
/// [`Reference::dp_step`] to write into).
#[derive(Default)]
pub(super) struct Step {
    pub(super) y0: State,
    pub(super) y1: State,
    k: [State; 7],
    h: f64,
    /// The embedded error estimate of each component (5th minus 4th order).
    pub(super) err: State,
    /// The first node at which a stage saw the plate pull (F_el + F_d below minus the force
    /// tolerance) while the clip was on: the step integrated across a clip switch.
    pub(super) pull: Option<f64>,
    /// In stick: the least and the largest value of the stick -> slip event function over
    /// the stages' states, the end's included (see `Reference::stays_stuck`).
    pub(super) stick_span: (f64, f64),
    /// In slip: the normal force and the contact point's tangential velocity at the stages'
    /// states (the end's last), see `Reference::stays_slipping`.
    pub(super) slip_stages: [(f64, f64); 6],
    /// The dense output's coefficients r2 ... r5 of each mechanical component (see
    /// [`Step::at`]), formed on its first call: the search for switches inside a step calls it
    /// many times (it took a sixth of the adaptive path's time when each call formed them again).
    dense: std::cell::OnceCell<[[f64; 4]; MECHANICAL]>,
    /// The evaluation at `y1` (the last stage, first-same-as-last): its derivative is
    /// `k[6]`; reused for the event functions at the step's end and for the next step.
    pub(super) end: Eval,
}

impl Step {
    /// The step's length.
    pub(super) fn h_len(&self) -> f64 {
        self.h
    }

    /// The derivative at `y1` (the next step's first stage when it starts there).
    pub(super) fn k_end(&self) -> State {
        self.k[6]
    }

    /// The state at fraction `theta` of the step (4th-order interpolant) for the forces and the
    /// events, which depend on the position, velocity and spring: the works are the step's start
    /// values, not interpolated (nothing inside a step reads them; they are 3 of the 10
    /// components).
    pub(super) fn at(&self, theta: f64) -> State {
        let mut s = self.y0;
        for (i, s_i) in s.iter_mut().enumerate().take(MECHANICAL) {
            *s_i = self.component_at(theta, i);
        }
        s
    }

    /// Component `i` (a mechanical one) of [`Step::at`] alone: the search for a disc's
    /// deepest point follows v_y only (formed whole at each of its ~10 calls per impact, the
    /// state cost that search 40 % more instructions).
    #[inline]
    pub(super) fn component_at(&self, theta: f64, i: usize) -> f64 {
        let eta = 1.0 - theta;
        let dense = self.dense.get_or_init(|| {
            std::array::from_fn(|i| {
                let r2 = self.y1[i] - self.y0[i];
                let r3 = self.h * self.k[0][i] - r2;
                let r4 = r2 - self.h * self.k[6][i] - r3;
                let r5 = self.h * (0..7).map(|j| D[j] * self.k[j][i]).sum::<f64>();
                [r2, r3, r4, r5]
            })
        });
        let [r2, r3, r4, r5] = dense[i];
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
pub(super) fn root_error_ratio(p: f64, rho: f64, at_end: bool) -> f64 {
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

impl Reference<'_> {
    /// One Dormand-Prince step from `y0` with first stage `k1`, written into `out` (a step of
    /// ~1.4 kB: returned by value, it was copied twice per attempt); returns the scaled error
    /// norm (<= 1: accepted).
    pub(super) fn dp_step(&self, m: &Mode, y0: &State, k1: &State, h: f64, out: &mut Step) -> f64 {
        let k = &mut out.k;
        k[0] = *k1;
        let mut pull = None;
        let mut stick_span = (f64::INFINITY, f64::NEG_INFINITY);
        // The 7th stage is evaluated at the 5th-order solution itself (FSAL): its stage state,
        // formed with the weights A[6], is y1.
        for st in 1..7 {
            // Component-wise over the stages before (the inner loop over the 10 components
            // vectorises; summed per component over the stages it did not).
            let mut acc = [0.0; NS];
            for (j, kj) in k.iter().enumerate().take(st) {
                let a = A[st][j];
                for i in 0..NS {
                    acc[i] += a * kj[i];
                }
            }
            let yi: State = std::array::from_fn(|i| y0[i] + h * acc[i]);
            // Each stage's evaluation goes where the step keeps its end's: the last stays.
            let e = &mut out.end;
            self.eval_to(m, &yi, &mut k[st], e);
            if pull.is_none() && m.clipped() && e.fn_raw < -self.force_tol {
                pull = Some(C[st]);
            }
            match m.tan {
                Tan::Stick => {
                    let g = self.to_slip_value(e);
                    stick_span = (stick_span.0.min(g), stick_span.1.max(g));
                }
                Tan::Slip(_) => out.slip_stages[st - 1] = (e.forces.fy, e.v_t),
                Tan::None | Tan::Free => {}
            }
            if st == 6 {
                out.y1 = yi;
            }
        }
        let mut err_vec = [0.0; NS];
        for (kj, e_j) in k.iter().zip(E) {
            for i in 0..NS {
                err_vec[i] += e_j * kj[i];
            }
        }
        err_vec = err_vec.map(|x| h * x);
        // The spring elongation is not integrated outside stick (there it is algebraic).
        let err = (0..NS)
            .filter(|&i| i != XI || m.tan == Tan::Stick)
            .map(|i| err_vec[i].abs() * self.error_weight[i])
            .fold(0.0, f64::max);
        out.y0 = *y0;
        out.h = h;
        out.err = err_vec;
        out.pull = pull;
        out.stick_span = stick_span;
        out.dense = std::cell::OnceCell::new();
        err
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
