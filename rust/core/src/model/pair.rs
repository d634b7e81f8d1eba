//! Two bodies: the particle and a free partner in place of the plate (docs/model.md, section
//! 17). The pair is integrated in its centre-of-mass frame, so its contact acts on the relative
//! motion with the reduced mass m* and on each body's rotation with its own inertia. The laws
//! are the plate's, read with the pair's effective constants: this module derives them, as a
//! [`Model`] the laws evaluate (`Pair::law`), beside the two bodies' own masses and radii.
//!
//! The area law on a pair: F_el = E* A / L, F_d = gamma sqrt(m* E*) (dA/dt) / L with
//! E* = (1/E1 + 1/E2)^-1, m* = (1/m1 + 1/m2)^-1, R* = r1 r2 / (r1 + r2) and
//! L = 4 sqrt(R*) (sum_i (E*/E_i)^(2/3) r_i^(1/3))^(3/2): each body carries the plate's law on
//! its own side of the contact and the two act in series (exact at small overlap), so that two
//! identical bodies at +-v are exactly one body on the rigid plate at v (L = 4 r, E* = E / 2,
//! m* = m / 2), and a rigid partner (E2, r2 -> inf) gives back the plate's L = 4 r1.

use super::derived::{tangential_constants, Hertz, Model};
use super::scene::{InertiaModel, Integrator, NormalLaw, Partner, Scene, TangentialModel};
use crate::error::{ensure_param, positive, Error, Result};
use crate::geometry::{OverlapMethod, Shape};

/// The two bodies of a pair and the effective constants of their contact.
#[derive(Debug, Clone, PartialEq)]
pub struct Pair {
    /// The particle's own model (mass, inertia, radius; its plate constants are not used).
    pub particle: Model,
    /// The partner's mass (kg/m; kg for a sphere), moment of inertia and circumradius.
    pub m2: f64,
    /// See `m2`.
    pub i2: f64,
    /// See `m2`.
    pub r2: f64,
    /// The partner's shape in its body frame.
    pub partner_shape: Shape,
    /// Reduced mass m* = m1 m2 / (m1 + m2).
    pub m_star: f64,
    /// The contact's model as the laws read it: mass m*, the effective modulus (E* of the area
    /// law, or the Hertz constants), the pair's length L, damping, tangential spring, t_ref
    /// and dt of the pair, and the scene with the effective law (`normal_law` of the linear
    /// law with k*, c*). Its inertia and radius are those that bound the pair's rates.
    pub law: Model,
}

/// The partner's material, defaulted to the particle's.
struct Material {
    rho: f64,
    e: f64,
}

impl Pair {
    /// Derives the pair of a validated particle model whose scene has a partner (its time
    /// step not yet checked: see [`Pair::check_dt`]).
    pub fn new(particle: Model) -> Result<Self> {
        let scene = &particle.scene;
        let partner = scene
            .partner
            .as_ref()
            .ok_or_else(|| Error::invalid("partner", "None", "a partner for a pair"))?;
        check_pairing(scene, partner)?;
        let mat = Material {
            rho: partner.rho.unwrap_or(scene.rho),
            e: partner.e_modulus.unwrap_or(scene.e_modulus),
        };
        positive("partner_rho", mat.rho)?;
        positive("partner_E", mat.e)?;
        let r2 = partner.shape.circumradius();
        positive("partner_r", r2)?;
        let m2 = mat.rho * partner.shape.area();
        let i2 = match scene.inertia {
            InertiaModel::Shape => mat.rho * partner.shape.polar_moment(),
            InertiaModel::Sphere => 0.4 * m2 * r2 * r2,
        };
        let (m1, i1, r1) = (particle.mass, particle.inertia, particle.r);
        let m_star = 1.0 / (1.0 / m1 + 1.0 / m2);
        // The tangential mass at the contact point, both arms at the undeformed radii.
        let m_t = 1.0 / (1.0 / m1 + 1.0 / m2 + r1 * r1 / i1 + r2 * r2 / i2);
        let law = effective_law(&particle, partner, &mat, [r1, r2], (m_star, m_t))?;
        Ok(Pair {
            m2,
            i2,
            r2,
            partner_shape: partner.shape.clone(),
            particle,
            m_star,
            law,
        })
    }

    /// Refuses a `dt_factor` above the pair's own stability bound (its rates in units of its
    /// t_ref), naming the bound and its cause.
    pub fn check_dt(&self) -> Result<()> {
        self.law.check_dt()
    }

    /// The pair's largest accepted `dt_factor` (see [`Model::max_dt_factor`]).
    pub fn max_dt_factor(&self) -> f64 {
        self.law.max_dt_factor()
    }

    /// Kinetic energy in the centre-of-mass frame at lane velocities `v` = (g_x, g_y,
    /// omega1, omega2): (m* |g|^2 + I1 omega1^2 + I2 omega2^2) / 2.
    pub fn kinetic_energy(&self, v: &[f64; 4]) -> f64 {
        0.5 * (self.m_star * (v[0] * v[0] + v[1] * v[1])
            + self.particle.inertia * v[2] * v[2]
            + self.i2 * v[3] * v[3])
    }

    /// Angular momentum about the centre of mass at lanes `q` = (x, y, phi1, phi2) and `v`:
    /// m* (r x g) + I1 omega1 + I2 omega2.
    pub fn angular_momentum(&self, q: &[f64; 4], v: &[f64; 4]) -> f64 {
        self.m_star * (q[0] * v[1] - q[1] * v[0]) + self.particle.inertia * v[2] + self.i2 * v[3]
    }

    /// The change of the lane velocities `v` at `q` that restores the angular momentum `l0`
    /// with the least kinetic energy: a rigid turn of the whole pair at the rate lambda,
    /// (-lambda y, lambda x, lambda, lambda), which leaves every relative velocity of the
    /// contact as it is (docs/model.md 17.2). The forces conserve the angular momentum at
    /// every instant, but a step's polynomial does not keep a product of position and
    /// velocity; this projection keeps it to round-off.
    pub fn restoring_turn(&self, q: &[f64; 4], v: &[f64; 4], l0: f64) -> [f64; 4] {
        // The whole pair's moment of inertia about its centre of mass: m* |r|^2 + I1 + I2.
        let moment = self.m_star * (q[0] * q[0] + q[1] * q[1]) + self.particle.inertia + self.i2;
        let lambda = (l0 - self.angular_momentum(q, v)) / moment;
        [-lambda * q[1], lambda * q[0], lambda, lambda]
    }
}

/// The pairings a pair has: discs and polygons with each other under the area or linear
/// law, a sphere with a sphere under the Hertz or linear law; no plate parameters.
fn check_pairing(scene: &Scene, partner: &Partner) -> Result<()> {
    let sphere = |s: &Shape| matches!(s, Shape::Sphere { .. });
    ensure_param!(
        sphere(&scene.shape) == sphere(&partner.shape),
        "partner",
        partner_name(&partner.shape),
        format!(
            "a Sphere partner for a Sphere particle, a Disc or polygon partner for a Disc or \
             polygon particle (found a {} particle)",
            partner_name(&scene.shape)
        )
    );
    ensure_param!(
        scene.overlap == OverlapMethod::Auto,
        "overlap",
        scene.overlap.name(),
        "\"auto\" for a pair (a pair's overlap is its pairing's own: the lens of two discs, \
         the disc-polygon clip or the convex clip of two polygons)"
    );
    // Corners' dashpots jump as they enter the other body, which Verlet cannot step over (as
    // on the plate); Gear-5 steps through them, the adaptive path locates them, holding the
    // vertex springs between their switches (docs/model.md 17.8).
    let corners = |s: &Shape| matches!(s, Shape::Polygon(_));
    let linear = matches!(scene.normal_law, NormalLaw::Linear { .. });
    ensure_param!(
        !(linear
            && (corners(&scene.shape) || corners(&partner.shape))
            && scene.integrator == Integrator::Verlet),
        "integrator",
        scene.integrator.name(),
        "\"adaptive\", \"reference\" or \"gear5\" for normal_law \"linear\" on a pair with \
         corners (Verlet cannot step over the jumps of a corner's dashpot as it enters the other \
         body; or use normal_law \"area\")"
    );
    if let NormalLaw::Hertz { plate, .. } = scene.normal_law {
        ensure_param!(
            plate.is_none(),
            "plate_E",
            plate.map_or(0.0, |p| p.0),
            "None for a pair (the partner's modulus is partner_E)"
        );
    }
    if let Some(nu) = partner.nu {
        super::derived::poisson("partner_nu", nu)?;
    }
    Ok(())
}

fn partner_name(shape: &Shape) -> &'static str {
    match shape {
        Shape::Disc { .. } => "Disc",
        Shape::Sphere { .. } => "Sphere",
        Shape::Polygon(_) => "polygon",
    }
}

/// The length of two bodies `[(E_i, r_i)]` in series under a law whose stiffness at overlap
/// delta is E_i sqrt(delta^3 / r_i) per body: sqrt(R*) (sum_i (E*/E_i)^(2/3) r_i^(1/3))^(3/2),
/// E* = (sum 1/E_i)^-1. It is r for two identical bodies and r1 when the partner is rigid
/// and flat (E2, r2 -> inf): the area law's L is 4 times it.
fn series_length([(e1, r1), (e2, r2)]: [(f64, f64); 2]) -> f64 {
    let e_star = 1.0 / (1.0 / e1 + 1.0 / e2);
    let r_star = r1 * r2 / (r1 + r2);
    let sum = (e_star / e1).powf(2.0 / 3.0) * r1.cbrt() + (e_star / e2).powf(2.0 / 3.0) * r2.cbrt();
    r_star.sqrt() * sum.powf(1.5)
}

/// The contact's effective model: the pair's law constants in a [`Model`] whose mass is m*,
/// whose radius is the smaller body's (the lens's chord is at most its diameter) and whose
/// inertia gives the pair's tangential mass `m_t` at that radius, so that the plate's rate
/// bounds ([`Model::contact_rates`]) bound the pair's.
fn effective_law(
    particle: &Model,
    partner: &Partner,
    mat: &Material,
    [r1, r2]: [f64; 2],
    (m_star, m_t): (f64, f64),
) -> Result<Model> {
    let scene = &particle.scene;
    let e1 = scene.e_modulus;
    let r_star = r1 * r2 / (r1 + r2);
    let r_eff = r1.min(r2);
    let mut law_scene = Scene {
        shape: match scene.shape {
            Shape::Sphere { .. } => Shape::Sphere { r: r_eff },
            _ => Shape::Disc { r: r_eff },
        },
        partner: None,
        ..scene.clone()
    };
    let mut hertz = None;
    let (stiffness, length) = match scene.normal_law {
        NormalLaw::Area => {
            let e_star = 1.0 / (1.0 / e1 + 1.0 / mat.e);
            law_scene.e_modulus = e_star;
            (e_star, 4.0 * series_length([(e1, r1), (mat.e, r2)]))
        }
        NormalLaw::Linear { kn, cn } => {
            // Two equal springs (and dashpots) in series, one per body.
            law_scene.normal_law = NormalLaw::Linear {
                kn: 0.5 * kn,
                cn: 0.5 * cn,
            };
            (0.5 * kn, 4.0 * r_eff)
        }
        NormalLaw::Hertz { nu, cor, .. } => {
            let nu2 = partner.nu.unwrap_or(nu);
            let h = Hertz::of_pair([(e1, nu), (mat.e, nu2)], r_star, m_star, cor)?;
            hertz = Some(h);
            // t_ref = sqrt(m* / (E* l)) with the series length l of the bodies' plane-strain
            // moduli: r for two identical spheres, r1 for a rigid partner, so that both take
            // the plate's steps (Chung & Ooi's Test 1 on exactly Test 2's).
            let plane = |e: f64, nu: f64| e / (1.0 - nu * nu);
            let l = series_length([(plane(e1, nu), r1), (plane(mat.e, nu2), r2)]);
            (h.e_star * l, 4.0 * r_eff)
        }
    };
    let mindlin = hertz.is_some() && scene.tangential != TangentialModel::Linear;
    let area_damping = scene.gamma * (m_star * law_scene.e_modulus).sqrt() / length;
    // Bodies with corners under the area law: the potential's stiffness E* (1 + E_min / E_max)
    // / L (docs/model.md 17.8), folded into the length so that the force and the rate bound
    // read it; the damping keeps E* / L.
    let corners = |s: &Shape| matches!(s, Shape::Polygon(_));
    let length = if scene.normal_law == NormalLaw::Area
        && (corners(&scene.shape) || corners(&partner.shape))
    {
        length / (1.0 + e1.min(mat.e) / e1.max(mat.e))
    } else {
        length
    };
    let inertia = r_eff * r_eff / (1.0 / m_t - 1.0 / m_star);
    let (kt, ct) = tangential_constants(&law_scene, hertz.filter(|_| mindlin), stiffness, m_t);
    let t_ref = (m_star / stiffness).sqrt();
    for (name, v) in [("partner_rho", m_star), ("kt", kt), ("partner_E", t_ref)] {
        ensure_param!(
            v.is_finite() && v > 0.0,
            name,
            v,
            "finite and > 0 (check the magnitudes of the partner's r, rho and E)"
        );
    }
    Ok(Model {
        scene: law_scene,
        mass: m_star,
        inertia,
        r: r_eff,
        length,
        t_ref,
        dt: scene.dt_factor * t_ref,
        kt,
        ct,
        area_damping,
        hertz,
        mindlin,
        history: particle.history,
    })
}
