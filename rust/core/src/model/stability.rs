//! The time-step bound of a scene: how fast the contact's linearised equations of motion can
//! change the state, and the largest `dt_factor` each integrator stays stable with.
//!
//! A fixed-step integrator is stable while dt times the largest eigenvalue modulus of the
//! linearised equations stays inside its stability region. For a damped oscillator that
//! modulus is at most max(omega, c / m) (omega when underdamped, below c / m when overdamped),
//! so the *stiffness index* of a scene is h = dt * max(omega_n, lambda_n, omega_t, lambda_t)
//! with the four rates below, each an upper bound over every state the contact can reach
//! (depth up to r, any orientation), so that the bound holds whatever v and theta are. Each
//! integrator accepts h up to [`Integrator::max_stiffness_index`], measured by scanning
//! `dt_factor` over stiff and strongly damped scenes (`tests/stability.rs`).
//!
//! The rates, for mass m, moment of inertia I = kappa m r^2 and circumradius r:
//! - Area law, elastic: the potential is (E / L) times the overlap's first moment, so moving
//!   the body changes the force by (E / L) per unit of chord it sweeps: the chord acts as a
//!   bed of vertical springs of density E / L. On a chord of length l centred x_mid off the
//!   centre the stiffness matrix in (y, phi) is (E / L) integral [1, x; x, x^2] dx, and the
//!   largest eigenvalue of M^-1 K is at most its trace,
//!   (E / L) l (1 / m + (x_mid^2 + l^2 / 12 + mu r x_mid) / I)
//!   (the mu term: a slipping contact's friction mu F_n acts at an arm <= r). The chord lies
//!   inside the circumscribed circle: l = 2 r u, |x_mid| <= r (1 - u), u in [0, 1]. The
//!   rotation of the overlap itself adds a negative (destabilising, not oscillating) term,
//!   left out. A disc's force passes through its centre: only (E / L) l / m <= E / (2 m).
//! - Area law, damping: F_d = -c l (v_y + omega x_mid) at the chord midpoint, c = gamma
//!   sqrt(m E) / L: a rank-one damping matrix with rate c l (1 / m + x_mid (x_mid + mu r) / I),
//!   maximised over u as above (disc: c 2 r / m = gamma / (2 t_ref)).
//! - Linear law, disc: k_n times the depth of the lowest point, below the centre: rate
//!   k_n (1 / m + a (1 + mu) r / I) with a = 0; the same lever with c_n for the damping.
//! - Linear law, polygon: one spring k_n per submerged corner at x_i: the trace bound
//!   k_n sum_i (1 / m + x_i (|x_i| + mu r) / I) over the corners that can be below the plate
//!   together (within r / 2 of the lowest, deeper impacts being refused), maximised over
//!   orientations; the same lever with c_n for the damping.
//! - Hertz law (a sphere): the stiffness dF/d(delta) = 2 E* sqrt(R delta) and the dashpot's
//!   coefficient c delta^(1/4) at the deepest accepted contact, delta = r / 2 (deeper impacts
//!   are refused), with no lever (the force acts below the centre). The dashpot's own depth
//!   derivative, c delta^(-3/4) delta' / 4, is singular at touch but acts over a vanishing
//!   depth; `tests/sphere.rs` checks that the bound holds. Mindlin's spring likewise at r / 2.
//! - Tangential (mu > 0): the Cundall-Strack spring at an arm <= r below the centre gives
//!   omega_t = sqrt(k_t / m_t) and lambda_t = c_t / m_t = gamma_t omega_t, with
//!   m_t = 1 / (1 / m + r^2 / I).

use super::derived::Model;
use super::scene::{Integrator, NormalLaw, Scene};
use crate::error::{ensure_param, Error, Result};
use crate::geometry::Shape;

/// Upper bounds on the rates of the contact's linearised equations of motion (1/s), over
/// every state the contact can reach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactRates {
    /// Angular frequency of the normal spring, rotation coupling included (rad/s).
    pub normal: f64,
    /// Decay rate of the normal damper (1/s).
    pub normal_damping: f64,
    /// Angular frequency of the tangential spring (rad/s; 0 without friction).
    pub tangential: f64,
    /// Decay rate of the tangential damper (1/s; 0 without friction).
    pub tangential_damping: f64,
}

impl ContactRates {
    /// The fastest of the four rates and what it belongs to, in words.
    pub fn fastest(&self) -> (f64, &'static str) {
        [
            (self.normal, "the normal spring"),
            (self.normal_damping, "the normal damping"),
            (self.tangential, "the tangential spring"),
            (self.tangential_damping, "the tangential damping"),
        ]
        .into_iter()
        .fold(
            (0.0, "the normal spring"),
            |a, b| if b.0 > a.0 { b } else { a },
        )
    }
}

/// Samples on [0, 1] of the maxima of the area law's levers: k / SAMPLES, k = 0 ... SAMPLES.
const SAMPLES: usize = 4096;

/// Largest value of `f` on [0, 1], sampled: for the cubics here (slope below 1 + 4 / kappa,
/// maximum >= 1) 4097 samples miss the maximum by less than 0.1 % unless kappa < 0.1. The
/// definition of the bound; [`max_of_cubic_on_unit`] finds the same value from a few samples.
#[cfg(test)]
fn max_on_unit(f: impl Fn(f64) -> f64) -> f64 {
    (0..=SAMPLES)
        .map(|k| f(k as f64 / SAMPLES as f64))
        .fold(0.0, f64::max)
}

/// The largest of the 4097 samples of [`max_on_unit`] for a cubic `f` with a positive leading
/// coefficient, whose derivative vanishes at `critical` (its real roots, if any), from the
/// samples that can hold it: the cubic rises up to its local maximum (the smaller root), falls
/// to its local minimum and rises again, so the largest sample is the last one, or one of the
/// two around the local maximum. A window of 8 samples on each side covers the rounding of the
/// roots; the samples are the same numbers (k / 4096, `f` evaluated alike), so the result is
/// the sampled maximum bit for bit, at a cost of ~20 evaluations instead of 4097 (the bound is
/// checked by every `Model::new`, i.e. once per impact).
fn max_of_cubic_on_unit(f: impl Fn(f64) -> f64, critical: &[f64]) -> f64 {
    const WINDOW: f64 = 8.0;
    let n = SAMPLES as f64;
    let sample = |k: f64| f(k / n);
    let mut best = 0.0f64.max(sample(0.0)).max(sample(n));
    for &c in critical.iter().filter(|c| c.is_finite()) {
        let lo = (c * n - WINDOW).floor().max(0.0);
        let hi = (c * n + WINDOW).ceil().min(n);
        let mut k = lo;
        while k <= hi {
            best = best.max(sample(k));
            k += 1.0;
        }
    }
    best
}

/// Real roots of a u^2 - 2 b u + c (a > 0): (b -+ sqrt(b^2 - a c)) / a; none when complex.
fn quadratic_roots(a: f64, b: f64, c: f64) -> [f64; 2] {
    let d = b * b - a * c;
    if d < 0.0 {
        return [f64::NAN; 2];
    }
    [(b - d.sqrt()) / a, (b + d.sqrt()) / a]
}

/// The area law's levers, the maxima over u in [0, 1] of the elastic trace
/// u (1 + (x^2 + u^2 / 3 + mu x) / kappa) and of the damping's u (1 + x (x + mu) / kappa),
/// x = 1 - u for a polygon (0 for a disc: both are u, largest at u = 1, exactly 1). Their
/// derivatives times kappa are 4 u^2 - 2 (2 + mu) u + (1 + mu + kappa) and
/// 3 u^2 - 2 (2 + mu) u + (1 + mu + kappa): quadratics whose roots place the maxima.
fn area_levers(polygon: bool, mu: f64, kappa: f64) -> (f64, f64) {
    if !polygon {
        return (1.0, 1.0);
    }
    let elastic = |u: f64| {
        let x = 1.0 - u;
        u * (1.0 + (x * x + u * u / 3.0 + mu * x) / kappa)
    };
    let damping = |u: f64| {
        let x = 1.0 - u;
        u * (1.0 + x * (x + mu) / kappa)
    };
    let (b, c) = (2.0 + mu, 1.0 + mu + kappa);
    (
        max_of_cubic_on_unit(elastic, &quadratic_roots(4.0, b, c)),
        max_of_cubic_on_unit(damping, &quadratic_roots(3.0, b, c)),
    )
}

/// Largest horizontal offset from the centroid that a polygon's lowest point can have: vertex
/// p is lowest while the downward direction d lies between the outward normals of its two
/// edges, and its offset |p x d| is largest at an end of that range or where d is
/// perpendicular to p. 0 for a disc (its lowest point is always below the centre).
fn lowest_point_arm(shape: &Shape) -> f64 {
    let v = shape.vertices();
    let n = v.len();
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    let unit = |a: [f64; 2]| {
        let l = a[0].hypot(a[1]);
        [a[0] / l, a[1] / l]
    };
    let mut arm: f64 = 0.0;
    for i in 0..n {
        let (prev, p, next) = (v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
        let p = [p.x, p.y];
        // Outward normals of the edges (prev, p) and (p, next) of a counter-clockwise polygon.
        let n1 = unit([p[1] - prev.y, -(p[0] - prev.x)]);
        let n2 = unit([next.y - p[1], -(next.x - p[0])]);
        let inside = |d: [f64; 2]| cross(n1, d) >= 0.0 && cross(d, n2) >= 0.0;
        let len = p[0].hypot(p[1]);
        arm = arm.max(cross(p, n1).abs()).max(cross(p, n2).abs());
        if len > 0.0 {
            let perp = [-p[1] / len, p[0] / len];
            if inside(perp) || inside([-perp[0], -perp[1]]) {
                arm = arm.max(len);
            }
        }
    }
    arm
}

/// The linear law on a polygon (one spring per submerged corner, at x_i from the centre):
/// the trace bound sum_i (1 + x_i (|x_i| + mu r) / (kappa r^2)) over the corners that can be
/// below the plate together, maximised over orientations (sampled, 16 per corner spacing and
/// at least 1024) with every corner within r / 2 of the lowest submerged (deeper impacts are
/// refused). A face carries two springs, a fine n-gon many: the rate grows with them.
fn vertex_springs_lever(shape: &Shape, mu: f64, kappa: f64) -> f64 {
    let v = shape.vertices();
    if v.is_empty() {
        // A sphere on the linear law: its one spring below the centre, no orientation to scan.
        return 1.0;
    }
    let r = shape.circumradius();
    let samples = (16 * v.len()).max(1024);
    let mut worst: f64 = 1.0;
    for j in 0..samples {
        let (s, c) = (2.0 * std::f64::consts::PI * j as f64 / samples as f64).sin_cos();
        let h = |p: &nalgebra::Vector2<f64>| s * p.x + c * p.y;
        let low = v.iter().map(h).fold(f64::INFINITY, f64::min);
        let sum: f64 = v
            .iter()
            // Relative margin: a corner exactly r / 2 above the lowest (the 12-gon's second
            // neighbour, cos 60 deg = 1/2) was in or out by round-off, so the bound changed
            // with the scale of the same polygon (0.00347 against 0.00244 for Gear-5).
            .filter(|p| h(p) <= low + 0.5 * r * (1.0 + 1e-9))
            .map(|p| {
                let x = (c * p.x - s * p.y).abs();
                1.0 + x * (x + mu * r) / (kappa * r * r)
            })
            .sum();
        worst = worst.max(sum);
    }
    worst
}

/// Rounds down to three significant digits, so that the printed bound is itself accepted.
fn round_down_3(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return x;
    }
    let exp = x.log10().floor() as i32 - 2;
    // The 1e-9 keeps an exact decimal (0.065 / 5e4 = 1.3e-6) from flooring to 1.29e-6 on
    // a rounding error; the margin of 2 dwarfs it.
    let mantissa = (x * (1.0 + 1e-9) / 10f64.powi(exp)).floor();
    // Through the decimal text, so that e.g. 0.0123 is the f64 nearest 0.0123.
    format!("{mantissa}e{exp}").parse().unwrap_or(x)
}

/// A number for messages: plain when moderate, scientific when tiny.
fn show(x: f64) -> String {
    if x >= 1e-3 {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Largest `dt_factor` of the adaptive path (`Reference`, `Adaptive`): its largest step, in
/// units of t_ref (a contact lasts about pi t_ref).
pub const ADAPTIVE_MAX_STEP: f64 = 10.0;

impl Model {
    /// Upper bounds on the contact's rates (see the module documentation for the derivation).
    pub fn contact_rates(&self) -> ContactRates {
        let s = &self.scene;
        let (m, r, mu) = (self.mass, self.r, s.mu);
        let kappa = self.inertia / (m * r * r);
        let polygon = !matches!(s.shape, Shape::Disc { .. });
        let (normal, normal_damping) = match s.normal_law {
            NormalLaw::Area => {
                // Chord 2 r u, midpoint offset r (1 - u) (0 for a disc).
                let (elastic, damping) = area_levers(polygon, mu, kappa);
                (
                    (s.e_modulus * 2.0 * r * elastic / (self.length * m)).sqrt(),
                    self.area_damping * 2.0 * r * damping / m,
                )
            }
            NormalLaw::Linear { kn, cn } if polygon => {
                let lever = vertex_springs_lever(&s.shape, mu, kappa);
                ((kn * lever / m).sqrt(), cn * lever / m)
            }
            NormalLaw::Linear { kn, cn } => {
                let lever = 1.0 + lowest_point_arm(&s.shape) * (1.0 + mu) / (kappa * r);
                ((kn * lever / m).sqrt(), cn * lever / m)
            }
            NormalLaw::Hertz { .. } => {
                // At the deepest accepted contact, r / 2: the stiffness dF/d(delta) =
                // 3/2 k sqrt(delta) = 2 E* sqrt(R delta) and the dashpot c delta^(1/4) grow
                // with the depth. The force acts below the centre (no lever).
                let h = self
                    .hertz
                    .unwrap_or_else(|| unreachable!("Hertz law without constants"));
                let s = (0.5 * r).sqrt();
                ((1.5 * h.k * s / m).sqrt(), h.c * s.sqrt() / m)
            }
        };
        let (tangential, tangential_damping) = if mu > 0.0 {
            let mt = 1.0 / (1.0 / m + r * r / self.inertia);
            ((self.kt / mt).sqrt(), self.ct / mt)
        } else {
            (0.0, 0.0)
        };
        ContactRates {
            normal,
            normal_damping,
            tangential,
            tangential_damping,
        }
    }

    /// The stiffness index h = dt * (fastest contact rate) of this model.
    pub fn stiffness_index(&self) -> f64 {
        self.dt * self.contact_rates().fastest().0
    }

    /// Largest `dt_factor` this scene accepts with its integrator: the integrator's
    /// [`Integrator::max_stiffness_index`] over the fastest contact rate, in units of t_ref,
    /// rounded down to three significant digits (at most 1; the adaptive path's largest step
    /// at most [`ADAPTIVE_MAX_STEP`]).
    pub fn max_dt_factor(&self) -> f64 {
        let h = self.scene.integrator.max_stiffness_index();
        if h.is_infinite() {
            // The adaptive path: its largest step, whatever the rates (its error control
            // and event location hold for any; beyond a few contact times it changes nothing).
            return ADAPTIVE_MAX_STEP;
        }
        let rate = self.fastest_rate_cached();
        round_down_3((h / (rate * self.t_ref)).min(1.0))
    }

    /// The fastest contact rate. The linear law on a polygon samples its orientations
    /// (~16 n^2 operations, 0.5 ms for a 120-gon): that one is computed once per distinct
    /// scene and thread, so that a sweep over angles and spins (the [`crate::model::Initial`],
    /// not the scene) pays for it once. The rates do not depend on the numerics (integrator,
    /// `dt_factor`, budget, tolerance), which the cache's key leaves out. The other laws' rates
    /// are closed forms (~0.1 us), cheaper than the key's copy of the scene: no cache.
    fn fastest_rate_cached(&self) -> f64 {
        use std::cell::RefCell;
        thread_local! {
            static LAST: RefCell<Option<(Scene, f64)>> = const { RefCell::new(None) };
        }
        let polygon = !matches!(self.scene.shape, Shape::Disc { .. } | Shape::Sphere { .. });
        if !(polygon && matches!(self.scene.normal_law, NormalLaw::Linear { .. })) {
            return self.contact_rates().fastest().0;
        }
        let key = Scene {
            integrator: Integrator::Gear5,
            dt_factor: 0.0,
            max_steps: None,
            tol: 0.0,
            error_estimate: false,
            ..self.scene.clone()
        };
        LAST.with(|last| {
            if let Some((scene, rate)) = last.borrow().as_ref() {
                if *scene == key {
                    return *rate;
                }
            }
            let rate = self.contact_rates().fastest().0;
            *last.borrow_mut() = Some((key, rate));
            rate
        })
    }

    /// What sets [`Model::max_dt_factor`], in words (for messages): the fastest rate, its
    /// value in units of 1 / t_ref and the integrator's largest stiffness index.
    pub fn dt_bound_reason(&self) -> String {
        let s = &self.scene;
        let (rate, what) = self.contact_rates().fastest();
        let cause = match (what, s.normal_law) {
            ("the normal damping", NormalLaw::Area) => format!(" (gamma = {})", s.gamma),
            ("the normal damping", NormalLaw::Linear { cn, .. }) => format!(" (cn = {cn} Pa s)"),
            ("the normal damping", NormalLaw::Hertz { cor, .. }) => format!(" (cor = {cor})"),
            ("the tangential damping", NormalLaw::Hertz { cor, .. }) if self.mindlin => {
                format!(" (cor = {cor})")
            }
            ("the tangential damping", _) => format!(" (gamma_t = {})", s.gamma_t),
            _ => String::new(),
        };
        if s.integrator.is_adaptive() {
            "its largest step".to_string()
        } else {
            format!(
                "its stability bound in this scene: the fastest rate, {what}{cause}, is {} / t_ref, \
                 and dt times it must stay <= {}",
                show(round_down_3(rate * self.t_ref)),
                s.integrator.max_stiffness_index()
            )
        }
    }

    /// Refuses a `dt_factor` above the scene's bound, naming the bound and what sets it.
    pub(crate) fn check_dt(&self) -> Result<()> {
        let s = &self.scene;
        let bound = self.max_dt_factor();
        if !(s.dt_factor.is_finite() && s.dt_factor > 0.0 && s.dt_factor <= bound) {
            // The reason costs a second pass over the rates: only when refusing.
            return Err(Error::invalid(
                "dt_factor",
                s.dt_factor,
                format!(
                    "in (0, {}] for the {} integrator ({})",
                    show(bound),
                    s.integrator.name(),
                    self.dt_bound_reason()
                ),
            ));
        }
        ensure_param!(
            self.dt.is_finite() && self.dt > 0.0,
            "dt",
            self.dt,
            "finite and > 0 (check the magnitudes of r, rho and E)"
        );
        Ok(())
    }
}

/// Largest `dt_factor` a scene accepts (its own `dt_factor` is not checked): see
/// [`Model::max_dt_factor`]. Errors name any other invalid parameter.
pub fn max_dt_factor(scene: &Scene) -> Result<f64> {
    Ok(bounding_model(scene)?.max_dt_factor())
}

/// [`max_dt_factor`] and [`Model::dt_bound_reason`] of a scene.
pub fn max_dt_factor_reason(scene: &Scene) -> Result<(f64, String)> {
    let model = bounding_model(scene)?;
    Ok((model.max_dt_factor(), model.dt_bound_reason()))
}

/// The model whose rates bound the scene's step: the particle's on the plate, or a pair's
/// contact ([`super::pair::Pair::law`]).
fn bounding_model(scene: &Scene) -> Result<Model> {
    let model = Model::derive(scene)?;
    match scene.partner {
        None => Ok(model),
        Some(_) => Ok(super::pair::Pair::new(model)?.law),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lowest_point_arm_of_regular_polygons_is_r_sin_pi_over_n() {
        for n in [3usize, 4, 5, 12, 120] {
            let shape = Shape::regular_polygon(1.0, n).unwrap();
            let want = (std::f64::consts::PI / n as f64).sin();
            let got = lowest_point_arm(&shape);
            assert!((got - want).abs() < 1e-12, "n {n}: {got} vs {want}");
        }
        assert_eq!(lowest_point_arm(&Shape::disc(1.0).unwrap()), 0.0);
    }

    #[test]
    fn rounds_down_to_three_digits() {
        assert_eq!(round_down_3(0.012_399), 0.0123);
        assert_eq!(round_down_3(1.239e-6), 1.23e-6);
        assert_eq!(round_down_3(0.05), 0.05);
    }

    #[test]
    fn area_levers_are_the_sampled_maxima_bit_for_bit() {
        // kappa: a needle-like polygon (0.05) ... the disc (0.5) ... a ring-like body (1);
        // mu beyond 1 too, where the damping lever's maximum moves inside (0, 1).
        for ik in 1..=20 {
            let kappa = 0.05 * ik as f64;
            for im in 0..=60 {
                let mu = 0.05 * im as f64;
                let elastic = max_on_unit(|u| {
                    let x = 1.0 - u;
                    u * (1.0 + (x * x + u * u / 3.0 + mu * x) / kappa)
                });
                let damping = max_on_unit(|u| {
                    let x = 1.0 - u;
                    u * (1.0 + x * (x + mu) / kappa)
                });
                let got = area_levers(true, mu, kappa);
                assert_eq!(got.0.to_bits(), elastic.to_bits(), "kappa {kappa} mu {mu}");
                assert_eq!(got.1.to_bits(), damping.to_bits(), "kappa {kappa} mu {mu}");
            }
        }
        assert_eq!(area_levers(false, 0.7, 0.5), (1.0, 1.0));
    }

    #[test]
    fn disc_rates_match_the_closed_forms() {
        // Disc, area law: omega_n = sqrt(E / (2 m)), lambda_n = gamma / (2 t_ref);
        // omega_t = sqrt(kt / mt) with mt = m / 3 and kt = 2 E / 7.
        let model = Model::new(&Scene::default()).unwrap();
        let rates = model.contact_rates();
        let t = model.t_ref;
        assert!((rates.normal * t - 0.5f64.sqrt()).abs() < 1e-12);
        assert!((rates.normal_damping * t - 0.33 / 2.0).abs() < 1e-12);
        assert!((rates.tangential * t - (6.0f64 / 7.0).sqrt()).abs() < 1e-12);
        assert!((rates.tangential_damping * t - 0.5 * (6.0f64 / 7.0).sqrt()).abs() < 1e-12);
    }
}
