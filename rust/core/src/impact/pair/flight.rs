//! The free flight of a pair with corners between contacts (docs/model.md, section 17.8):
//! apart, the bodies move and turn uniformly, so the flight is skipped in one jump as far as
//! they certainly cannot touch (conservative advancement: no two points of the bodies close
//! faster than |g| + |omega1| R1 + |omega2| R2), and the impact ends once their circumscribed
//! circles are apart and receding, after which no point of them can meet again.

use crate::geometry::pair::PairGeometry;
use crate::integrate::Lanes;

/// Most advancement rounds of one skip; past them stepping resumes (a slow approach).
const MAX_ROUNDS: usize = 200;

/// What a pair apart at (q, v) does next.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Flight {
    /// They can never touch again: the impact is over.
    Over,
    /// Nothing can touch for this long (s): the flight may jump ahead by it.
    Skip(f64),
}

/// The lanes after a free flight of `tau` from (q, v).
pub(super) fn advance(q: &Lanes, v: &Lanes, tau: f64) -> Lanes {
    std::array::from_fn(|i| q[i] + v[i] * tau)
}

/// How far the free flight of a pair apart at lanes (`q`, `v`) may be skipped, `radii` the
/// bodies' circumradii; a skip shorter than `min_skip` is returned as found (the caller
/// steps on).
pub(super) fn skip<G: PairGeometry>(
    geometry: &G,
    q: &Lanes,
    v: &Lanes,
    radii: [f64; 2],
    min_skip: f64,
) -> Flight {
    let reach = radii[0] + radii[1];
    let speed = v[0].hypot(v[1]) + v[2].abs() * radii[0] + v[3].abs() * radii[1];
    let mut tau = 0.0;
    for _ in 0..MAX_ROUNDS {
        let at = advance(q, v, tau);
        let receding = at[0] * v[0] + at[1] * v[1] >= 0.0;
        if receding && at[0].hypot(at[1]) >= reach {
            return Flight::Over;
        }
        let gap = -geometry.signed_depth(&at);
        if !(gap > 0.0) || speed == 0.0 {
            return if speed == 0.0 && gap > 0.0 {
                Flight::Over
            } else {
                Flight::Skip(tau)
            };
        }
        let step = gap / speed;
        if step < min_skip {
            return Flight::Skip(tau);
        }
        tau += step;
    }
    Flight::Skip(tau)
}
