//! What a step's own Runge-Kutta stages tell of its stick or slip phase, on the plate and on a
//! pair (docs/model.md, 7.3 and 17.5): the stages evaluate the law at six points of the step
//! (its end the last), and where their values keep the stick -> slip or slip -> stick function
//! below zero by a wide margin no sample between them can find a switch, so the step skips
//! its samples at thirds ([`super::sampled_first_switch`]) and the evaluations of the law they
//! take. Written once for both sides: each records its own function's values at its stages.

use crate::integrate::dopri::C;

/// The tangential values a step records at its stages (stages 2 ... 7, the 7th its end).
#[derive(Debug, Clone, Copy)]
pub(crate) struct TangentialStages {
    /// In stick: the least and the largest value of the stick -> slip event function.
    stick_span: (f64, f64),
    /// In slip: the normal force and the contact point's tangential velocity at each stage.
    slip: [(f64, f64); 6],
}

impl Default for TangentialStages {
    fn default() -> Self {
        TangentialStages {
            stick_span: EMPTY_SPAN,
            slip: [(0.0, 0.0); 6],
        }
    }
}

/// The span of no value.
const EMPTY_SPAN: (f64, f64) = (f64::INFINITY, f64::NEG_INFINITY);

/// The linear tangential spring of a slip: mu, k_t, c_t (not Mindlin's, whose stiffness and
/// damping change with the depth: no bound is written for it, its steps keep sampling).
#[derive(Debug, Clone, Copy)]
pub(crate) struct LinearSlip {
    pub(crate) mu: f64,
    pub(crate) k_t: f64,
    pub(crate) c_t: f64,
}

impl TangentialStages {
    /// Forgets the stick span before a step records its stages.
    pub(crate) fn begin(&mut self) {
        self.stick_span = EMPTY_SPAN;
    }

    /// Records the stick -> slip function's value `g` at a stage.
    pub(crate) fn stick(&mut self, g: f64) {
        self.stick_span = (self.stick_span.0.min(g), self.stick_span.1.max(g));
    }

    /// Records the normal force `f_n` and the tangential velocity `v_t` at stage `st`
    /// (1 ... 6, node `C[st]`).
    pub(crate) fn slip(&mut self, st: usize, f_n: f64, v_t: f64) {
        self.slip[st - 1] = (f_n, v_t);
    }

    /// Whether a stick step stays inside the Coulomb cone by more than its event function
    /// varies over the step's stages (`g0` its value at the step's start): then no sample
    /// between them can find a slip phase, and the law need not be evaluated for them. The
    /// function is evaluated at the stages' own states whatever it reads (on a pair the
    /// contact frame's turn and both spins are in each value), so the rule is the same for
    /// every side.
    pub(crate) fn stays_stuck(&self, g0: f64) -> bool {
        let (lo, hi) = (self.stick_span.0.min(g0), self.stick_span.1.max(g0));
        hi + STUCK_SPANS * (hi - lo) < 0.0
    }

    /// Whether a slip step (`sg` the sign of its force, `start` the normal force and the
    /// tangential velocity at its start, `h` its length) keeps slipping by a wide margin, from
    /// the stages' normal forces and tangential velocities alone. With a linear spring the
    /// slip -> stick function is mu dF_n/dt + s (k_t v_t + c_t dv_t/dt): a spring stuck at the
    /// slipping elongation carries the slip's own force, so the motion's rates are the slip's,
    /// and only the spring's rate v_t differs. While the contact point slides against the force
    /// (s v_t < 0) its term k_t s v_t outweighs the rates' bounds (twice the largest difference
    /// quotient between the stages' values, the sliding velocity's excursion between stages
    /// included): then no sample can find stick.
    pub(crate) fn stays_slipping(
        &self,
        sg: f64,
        start: (f64, f64),
        h: f64,
        spring: LinearSlip,
    ) -> bool {
        slides_on(&self.slip_rates(sg, start, h), h, spring)
    }

    /// [`Self::stays_slipping`], and the normal force stays positive through the step, its
    /// excursion between the stages included (the same bound on its rate). Where it falls to
    /// zero within the step (the parting) the law's rates are not bounded by the stages'
    /// difference quotients (the area law's damping grows like the root of the depth, its rate
    /// like the inverse root; a pair's contact frame turns faster as the overlap vanishes), and
    /// a slip -> stick function that reads the law ahead of the step (a pair's forward
    /// difference) may turn positive where the bound says it cannot: on a pair the last slip
    /// steps before the parting, at normal forces of 1e-15 to 1e-9 N, found slip -> stick
    /// switches that the bound alone ruled out (6 of the 1000 adaptive impacts of `--example
    /// pair_records`; none with this test).
    pub(crate) fn stays_slipping_in_contact(
        &self,
        sg: f64,
        start: (f64, f64),
        h: f64,
        spring: LinearSlip,
    ) -> bool {
        let rates = self.slip_rates(sg, start, h);
        rates.least_force > rates.force * WIDEST_GAP * h && slides_on(&rates, h, spring)
    }

    /// The bounds a slip's stages give (`sg` the sign of its force, `start` the normal force
    /// and the tangential velocity at its start, `h` its length).
    fn slip_rates(&self, sg: f64, start: (f64, f64), h: f64) -> SlipRates {
        // (node, F_n, v_t) in the order of the nodes: the start, stages 2 ... 6, the end.
        let mut at = [(0.0, start.0, start.1); 7];
        for (i, &(f, v)) in self.slip.iter().enumerate() {
            at[i + 1] = (C[i + 1], f, v);
        }
        let (mut rate_f, mut rate_v, mut sliding) = (0.0f64, 0.0f64, f64::NEG_INFINITY);
        for w in at.windows(2) {
            let ((c0, f0, v0), (c1, f1, v1)) = (w[0], w[1]);
            sliding = sliding.max(sg * v0).max(sg * v1);
            // Nodes closer than 0.05 of the step (the last stage and the end, both at 1)
            // carry their states' errors more than their rates.
            if c1 - c0 >= 0.05 {
                rate_f = rate_f.max((f1 - f0).abs() / ((c1 - c0) * h));
                rate_v = rate_v.max((v1 - v0).abs() / ((c1 - c0) * h));
            }
        }
        SlipRates {
            force: 2.0 * rate_f,
            velocity: 2.0 * rate_v,
            sliding,
            least_force: at.iter().map(|a| a.1).fold(f64::INFINITY, f64::min),
        }
    }
}

/// The bound of [`TangentialStages::stays_slipping`] on a slip's stage `rates` in a step of
/// length `h`: the spring's term k_t s v_t outweighs the rates' bounds.
fn slides_on(rates: &SlipRates, h: f64, spring: LinearSlip) -> bool {
    let LinearSlip { mu, k_t, c_t } = spring;
    let (rate_f, rate_v) = (rates.force, rates.velocity);
    let bound = k_t * (rates.sliding + rate_v * WIDEST_GAP * h) + mu * rate_f + c_t * rate_v;
    bound < 0.0 && bound.is_finite()
}

/// What a slip's stages bound: the rates of the normal force and of the tangential velocity
/// (twice the largest difference quotient between the stages), the largest of s v_t, and the
/// least normal force at them.
struct SlipRates {
    force: f64,
    velocity: f64,
    sliding: f64,
    least_force: f64,
}

/// The widest gap between a step's nodes (0.3 to 0.8 of it), as a fraction of the step: no
/// point of the step lies farther than half of it from a node (the excursions between them
/// are bounded over all of it, generously).
const WIDEST_GAP: f64 = 0.5;

/// How many times its variation over a step's stages the stick -> slip event function must
/// stay below zero for the step to skip its samples (see [`TangentialStages::stays_stuck`]).
const STUCK_SPANS: f64 = 2.0;

#[cfg(test)]
mod tests {
    use super::*;

    /// A stick function far below zero and flat skips; one whose span reaches within twice
    /// itself of zero, or that is -inf at a stage (no overlap), does not.
    #[test]
    fn a_stick_skips_only_far_inside_the_cone() {
        let mut st = TangentialStages::default();
        for g in [-1.0, -1.1, -0.9, -1.0, -1.05, -1.0] {
            st.stick(g);
        }
        assert!(st.stays_stuck(-1.0));
        // Spans 0.2 + 0.6 = 0.8 below -0.75: within twice the span of zero.
        assert!(!st.stays_stuck(-0.6));
        st.begin();
        for g in [-1.0, f64::NEG_INFINITY, -1.0, -1.0, -1.0, -1.0] {
            st.stick(g);
        }
        assert!(!st.stays_stuck(-1.0));
    }

    /// A slip sliding against its force skips where the spring's term outweighs the rates,
    /// not where the sliding slows so fast that it may turn inside the step.
    #[test]
    fn a_slip_skips_only_while_it_slides_firmly() {
        let spring = LinearSlip {
            mu: 0.5,
            k_t: 1e3,
            c_t: 1.0,
        };
        let (h, sg) = (1e-3, 1.0);
        let steady = |slope: f64| {
            let mut st = TangentialStages::default();
            for (i, c) in C[1..].iter().enumerate() {
                st.slip(i + 1, 10.0, -1.0 + slope * c);
            }
            st
        };
        assert!(steady(0.0).stays_slipping(sg, (10.0, -1.0), h, spring));
        // v_t from -1 to -0.1 over the step: the rate bound's excursion reaches zero.
        assert!(!steady(0.9).stays_slipping(sg, (10.0, -1.0), h, spring));
        // Sliding with the force: no bound.
        assert!(!steady(0.0).stays_slipping(-sg, (10.0, -1.0), h, spring));
    }

    /// A slip in contact skips where its normal force stays above its bounded excursion, not
    /// where the force collapses within the step (the parting).
    #[test]
    fn a_slip_in_contact_skips_only_away_from_the_parting() {
        let spring = LinearSlip {
            mu: 0.5,
            k_t: 1e4,
            c_t: 0.0,
        };
        let at = |forces: [f64; 6]| {
            let mut st = TangentialStages::default();
            for (i, f) in forces.into_iter().enumerate() {
                st.slip(i + 1, f, -1.0);
            }
            st
        };
        let (h, start) = (1e-3, (10.0, -1.0));
        let falling = at([9.8, 9.7, 9.2, 9.1, 9.0, 9.0]);
        assert!(falling.stays_slipping_in_contact(1.0, start, h, spring));
        let parting = at([5e-9, 4e-9, 1e-9, 1e-11, 5e-13, 5e-13]);
        let start = (5.6e-9, -1.0);
        assert!(parting.stays_slipping(1.0, start, h, spring));
        assert!(!parting.stays_slipping_in_contact(1.0, start, h, spring));
    }
}
