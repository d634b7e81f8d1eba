//! One Dormand-Prince step of an impact's ODE ([`crate::integrate::dopri`]) with what the
//! switches need from its stages: a pull of the clipped normal force, the stick or slip
//! values at the stages ([`TangentialStages`]), and the evaluation at its end.

use super::law::{Eval, Reference};
use super::piece::{Mode, Tan};
use super::rules::state_at_switch;
use super::stages::TangentialStages;
use super::{State, NS, XI};
use crate::integrate::dopri::{DenseStep, C};

/// The components the forces depend on: x, y, phi, the velocities and the spring (the works
/// follow them; a piece that ends on the dense output forms them there,
/// `DenseStep::at_with_gap`).
const INTERPOLATED: usize = XI + 1;

/// One accepted Runge-Kutta step with what its dense output and the switches need
/// (`Default`: a blank one for [`Reference::dp_step`] to write into).
#[derive(Default)]
pub(super) struct Step {
    /// The step itself: its ends, stages, error estimate and dense output.
    dp: DenseStep<NS, INTERPOLATED>,
    /// The first node at which a stage saw the plate pull (F_el + F_d below minus the force
    /// tolerance) while the clip was on: the step integrated across a clip switch.
    pub(super) pull: Option<f64>,
    /// In stick the stick -> slip function's span over the stages, in slip the normal force
    /// and the contact point's tangential velocity at each (see `Reference::stays_stuck`,
    /// `Reference::stays_slipping`).
    pub(super) tangential: TangentialStages,
    /// The evaluation at `y1` (the last stage, first-same-as-last): its derivative is
    /// `k_end()`; reused for the event functions at the step's end and for the next step.
    pub(super) end: Eval,
}

impl std::ops::Deref for Step {
    type Target = DenseStep<NS, INTERPOLATED>;

    fn deref(&self) -> &Self::Target {
        &self.dp
    }
}

impl Reference<'_> {
    /// One Dormand-Prince step from `y0` with first stage `k1`, written into `out`; returns the
    /// scaled error norm (<= 1: accepted).
    pub(super) fn dp_step(&self, m: &Mode, y0: &State, k1: &State, h: f64, out: &mut Step) -> f64 {
        let mut pull = None;
        let (end, tangential) = (&mut out.end, &mut out.tangential);
        tangential.begin();
        // What the stages test of the mode, read once: left to each stage, the mode's fields
        // were loaded and tested again at every one of them.
        let (watch_pull, tan) = (m.clipped(), m.tan);
        out.dp.take(y0, k1, h, |st, yi, k_out| {
            // Each stage's evaluation goes where the step keeps its end's: the last stays.
            self.eval_to(m, yi, k_out, end);
            if pull.is_none() && watch_pull && end.fn_raw < -self.force_tol {
                pull = Some(C[st]);
            }
            match tan {
                Tan::Stick => tangential.stick(self.to_slip_value(end)),
                Tan::Slip(_) => tangential.slip(st, end.forces.fy, end.v_t),
                Tan::None | Tan::Free => {}
            }
        });
        out.pull = pull;
        self.scaled_norm(m, &out.dp.err)
    }

    /// The state where a piece of mode `m` ends inside `step`, at fraction `th`, with its
    /// local error, from the dense output where that is within the local tolerance
    /// ([`state_at_switch`]); `None` where the step must be redone up to the switch.
    pub(super) fn state_at_switch(&self, m: &Mode, step: &Step, th: f64) -> Option<(State, State)> {
        state_at_switch(step, th, |gap| self.scaled_norm(m, gap))
    }

    /// The largest of the components of `err` (absolute errors of the state) in units of the
    /// local tolerance, in mode `m`: the norm the steps are accepted by.
    pub(super) fn scaled_norm(&self, m: &Mode, err: &State) -> f64 {
        // The spring elongation is not integrated outside stick (there it is algebraic).
        (0..NS)
            .filter(|&i| i != XI || m.tan == Tan::Stick)
            .map(|i| err[i].abs() * self.error_weight[i])
            .fold(0.0, f64::max)
    }
}
