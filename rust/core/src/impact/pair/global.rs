//! Global error control of a pair's adaptive path (docs/model.md, 17.5). Each step's local
//! error is held within the tolerance, and `err_est` accumulates those local errors; that
//! bounds the error of an impact with one contact, but not of an impact whose bodies touch
//! several times: the flight from one contact to the next amplifies the error the first left
//! in the spins and the placement (a damped 120-gon rattling five times on a pentagon: 0.07
//! tol after its first contact, 57 tol at the end; the reference itself moves 880 times a
//! perturbation of a spin), and the local estimate does not follow that growth. Such an
//! impact is run again at a local tolerance [`TIGHTEN`] times tighter: the two runs'
//! difference measures the coarser run's error, and so bounds the finer one's; the finer is
//! returned, its `err_est` the larger of its local estimate and that difference, tightened
//! again (at most [`MAX_RERUNS`] times) while the difference exceeds `tol`.

use super::{run_adaptive, Start};
use crate::cancel::Cancel;
use crate::error::Result;
use crate::geometry::pair::PairGeometry;
use crate::impact::record::{Record, StopReason, Trace};
use crate::model::scene::REFERENCE_LOCAL_TOL;
use crate::model::{Initial, Integrator, Pair};

/// How much tighter each rerun's tolerance is. A rerun costs about TIGHTEN^(1/5) = 2 times the
/// run before it (Dormand-Prince 5(4)), and its error is about 1/TIGHTEN of that run's where
/// the error follows the tolerance, so that the difference of the two runs overstates the
/// finer one's error about 30 times over.
pub const TIGHTEN: f64 = 30.0;

/// The most reruns of one impact (the finest at tol / TIGHTEN^2): the cost stays within 1 +
/// 2 + 4 = 7 times a single run.
pub const MAX_RERUNS: u32 = 2;

/// The smallest `err_est` of a pair (in units of the outputs, 64 ulps of 1): no output is
/// known better than the round-off of the velocities it is taken from. A pass-by whose bodies
/// never overlap (e_N = -1, its local errors 0) came out up to 22 ulps off the reference.
pub const ROUND_OFF: f64 = 64.0 * f64::EPSILON;

/// Runs the pair on the adaptive path at the scene's tolerance, and again at tighter ones where
/// its local error control does not bound the impact's error (several contacts); the finest
/// run completed is returned, `steps` and `step_budget` summed over the runs, `err_est` at
/// least [`ROUND_OFF`].
pub(super) fn run_controlled<G: PairGeometry>(
    pair: &Pair,
    init: &Initial,
    ctx: (G, Start),
    depth_est: f64,
    trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let mut rec = run_and_rerun(pair, init, ctx, depth_est, trace, cancel)?;
    rec.err_est = rec.err_est.map(|e| e.max(ROUND_OFF));
    Ok(rec)
}

/// [`run_controlled`] but for the round-off floor.
fn run_and_rerun<G: PairGeometry>(
    pair: &Pair,
    init: &Initial,
    ctx: (G, Start),
    depth_est: f64,
    mut trace: Option<&mut Trace>,
    cancel: &Cancel,
) -> Result<Record> {
    let first = run_adaptive(pair, init, ctx, depth_est, trace.as_deref_mut(), cancel)?;
    if !needs_global_control(pair, &first) {
        return Ok(first);
    }
    let target = pair.particle.scene.tol;
    let speed = init.vx.hypot(init.vy);
    let mut finer = pair.clone();
    let mut spent = Spent::of(&first);
    let mut best = first;
    for _ in 0..MAX_RERUNS {
        let Some(tol) = tighter(finer.particle.scene.tol, finer.particle.scene.local_tol()) else {
            break;
        };
        let Some(budget) = spent.left(pair) else {
            break;
        };
        finer.particle.scene.tol = tol;
        finer.law.scene.max_steps = budget;
        let mut fine_trace = Trace::default();
        let traced = trace.is_some().then_some(&mut fine_trace);
        let fine = run_adaptive(&finer, init, ctx, depth_est, traced, cancel)?;
        spent.add(&fine);
        if fine.stop != StopReason::Separated {
            // Stopped on its budget: the coarser run stands, its estimate unchecked.
            break;
        }
        if let Some(tr) = trace.as_deref_mut() {
            *tr = fine_trace;
        }
        let diff = difference(&best, &fine, pair, speed);
        best = fine;
        best.err_est = Some(best.err_est.unwrap_or(0.0).max(diff));
        if diff <= target {
            break;
        }
    }
    best.steps = spent.steps;
    best.step_budget = pair.law.scene.max_steps.unwrap_or(spent.budget);
    Ok(best)
}

/// The next rerun's target tol after a run at target `tol` and local tolerance `local`:
/// [`TIGHTEN`] times tighter, its local tolerance no tighter than the reference's (below it
/// round-off takes over); `None` where that is not even twice as tight (`tol` about 6e-11 and
/// below), since the difference of two runs bounds the finer's error only where that error is
/// the smaller (at a ratio k of the errors, by diff / (k - 1)).
fn tighter(tol: f64, local: f64) -> Option<f64> {
    let next = (local / TIGHTEN).max(REFERENCE_LOCAL_TOL);
    (next <= 0.5 * local).then(|| tol * next / local)
}

/// Whether an adaptive run's local error control may not bound its error: it ended separated
/// after several contacts, on the default path (the reference runs once, at its tightest).
fn needs_global_control(pair: &Pair, rec: &Record) -> bool {
    pair.particle.scene.integrator == Integrator::Adaptive
        && rec.stop == StopReason::Separated
        && rec.contacts > 1
}

/// The steps taken and the budgets granted over an impact's runs.
#[derive(Debug, Clone, Copy)]
struct Spent {
    steps: u64,
    budget: u64,
}

impl Spent {
    fn of(rec: &Record) -> Self {
        Spent {
            steps: rec.steps,
            budget: rec.step_budget,
        }
    }

    fn add(&mut self, rec: &Record) {
        self.steps += rec.steps;
        self.budget += rec.step_budget;
    }

    /// The next run's budget: a scene's own `max_steps` is shared by all its runs (what is
    /// left of it; `None` when nothing is), the default one is each run's own (`Some(None)`).
    fn left(&self, pair: &Pair) -> Option<Option<u64>> {
        match pair.law.scene.max_steps {
            None => Some(None),
            Some(n) if n > self.steps => Some(Some(n - self.steps)),
            Some(_) => None,
        }
    }
}

/// The largest difference of two runs of one impact over the outputs whose error `err_est`
/// bounds: e_N, e_T, e_kin and both spins times their radius over the impact speed `speed`.
fn difference(a: &Record, b: &Record, pair: &Pair, speed: f64) -> f64 {
    let (r1, r2) = (pair.particle.r, pair.r2);
    let partner_spin = (a.partner_omega_out - b.partner_omega_out).abs() * r2 / speed;
    a.accuracy_distance(b, r1, speed).max(partner_spin)
}
