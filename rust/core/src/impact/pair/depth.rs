//! The pair's largest overlap from the energy balance of its undamped normal law, and the
//! refusal of overlaps past half a body's radius.

use super::Start;
use crate::error::{Error, Result};
use crate::geometry::pair::{PairFrame, PairGeometry};
use crate::model::{Initial, NormalLaw, Pair};
use crate::numerics::roots;

/// The pair's largest overlap from the energy balance of its undamped normal law along a
/// head-on approach from the first touch `start` (orientations held), refused where a body's
/// cap would pass half its radius (as r / 2 on the plate; for bodies with corners, the caps
/// of their circumscribed circles).
pub(super) fn estimate_max_overlap<G: PairGeometry>(
    pair: &Pair,
    init: &Initial,
    geometry: &G,
    start: &Start,
) -> Result<f64> {
    let law = &pair.law;
    let (r1, r2) = (pair.particle.r, pair.r2);
    let ke = 0.5 * pair.m_star * init.vy * init.vy;
    let hi = largest_overlap(r1, r2);
    let frame = |s: f64| {
        let q = start.q;
        geometry.frame(&[q[0], q[1] - s, q[2], q[3]])
    };
    let potential = |delta: f64| overlap_potential(pair, &frame, delta);
    let at_hi = potential(hi);
    if at_hi.0 < ke {
        let stiff = match law.scene.normal_law {
            NormalLaw::Linear { kn, .. } => format!("kn = {:e} Pa", 2.0 * kn),
            _ => format!("E = {:e} Pa", pair.particle.scene.e_modulus),
        };
        return Err(Error::invalid(
            "v",
            init.vx.hypot(init.vy),
            format!(
                "small enough that each body's estimated overlap stays below half its radius at \
                 {stiff} (normal kinetic energy {ke:e} J exceeds the elastic energy there: lower \
                 v or raise the modulus)"
            ),
        ));
    }
    Ok(roots::log_newton(potential, ke, hi, at_hi))
}

/// The overlap delta at which a body's cap reaches half its radius first (bisection on the
/// caps' closed form).
fn largest_overlap(r1: f64, r2: f64) -> f64 {
    let capped = |delta: f64| {
        let d = r1 + r2 - delta;
        let half = 0.5 * delta / d;
        (half * (r2 + d - r1) / r1).max(half * (r1 + d - r2) / r2) > 0.5
    };
    let (mut lo, mut hi) = (0.0, r1.min(r2));
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if capped(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    lo
}

/// The undamped normal law's potential at an approach `delta` from first touch and its rate
/// (the elastic force), from the contact's frames along the approach (`frame`).
fn overlap_potential(
    pair: &Pair,
    frame: &impl Fn(f64) -> Option<PairFrame>,
    delta: f64,
) -> (f64, f64) {
    let law = &pair.law;
    // The integral of a force over the approach: Gauss-Legendre on delta t^2, t in [0, 1]
    // (the lens's area grows like delta^(3/2), a corner's like delta^2).
    let integral = |force: &dyn Fn(f64) -> f64| -> f64 {
        GAUSS_8
            .iter()
            .map(|&(x, w)| {
                let t = 0.5 * (x + 1.0);
                0.5 * w * force(delta * t * t) * 2.0 * delta * t
            })
            .sum()
    };
    match law.scene.normal_law {
        NormalLaw::Area => {
            let k = law.scene.e_modulus / law.length;
            let area = |s: f64| frame(s).map_or(0.0, |f| f.area);
            (k * integral(&area), k * area(delta))
        }
        NormalLaw::Linear { kn, .. } => {
            // The springs' depths (their pushes turn with the edges they press on: their sum is
            // the force an approach meets, whatever the direction).
            let springs = |s: f64| frame(s).map_or(0.0, |f| f.springs.depth);
            (kn * integral(&springs), kn * springs(delta))
        }
        NormalLaw::Hertz { .. } => {
            let k = law.hertz.map_or(0.0, |h| h.k);
            let f = k * delta * delta.sqrt();
            (0.4 * f * delta, f)
        }
    }
}

/// Gauss-Legendre nodes and weights on [-1, 1], 8 points.
const GAUSS_8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329_0, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329_0, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
];
