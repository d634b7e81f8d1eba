//! The constants derived from a validated scene (mass, inertia, time step, tangential spring,
//! the Hertz law's constants) that the contact law uses, and every rule a scene must meet.

use super::scene::{
    InertiaModel, Initial, Integrator, NormalLaw, Scene, TangentialHistory, TangentialModel,
    MAX_RIM_SPEED,
};
use crate::error::{ensure_param, finite, non_negative, positive, Result};
use crate::geometry::Shape;

/// Constants derived from a validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// The scene it was derived from.
    pub scene: Scene,
    /// Mass per unit depth (kg/m).
    pub mass: f64,
    /// Moment of inertia per unit depth (kg m).
    pub inertia: f64,
    /// Circumradius r (m).
    pub r: f64,
    /// Characteristic length L = 4 r for a plate (m).
    pub length: f64,
    /// Reference time t_ref = sqrt(m / E) (area law) or sqrt(m / kn) (linear law) (s).
    pub t_ref: f64,
    /// Time step (s).
    pub dt: f64,
    /// Tangential stiffness k_t (Pa).
    pub kt: f64,
    /// Tangential damping c_t (Pa s).
    pub ct: f64,
    /// Normal damping prefactor gamma sqrt(m E) / L of the area law (Pa s / m).
    pub area_damping: f64,
    /// The Hertz law's constants (`None` for the other laws).
    pub hertz: Option<Hertz>,
    /// Whether the tangential spring is Mindlin's (stiffness and damping grow with the depth).
    pub mindlin: bool,
    /// How Mindlin's spring keeps its history, `Auto` resolved (`Force`); `Auto` for the
    /// linear spring, which has one history only.
    pub history: TangentialHistory,
}

/// Constants of the Hertz law and the Mindlin spring of a sphere of radius R on the plate
/// (docs/model.md, section 14): with s = sqrt(delta), F_el = `k` delta s, F_d = `c` sqrt(s)
/// d(delta)/dt, k_t = `kt` s, c_t = `ct` sqrt(s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    /// Effective modulus E* (Pa): 1 / E* = (1 - nu^2) / E + (1 - nu_p^2) / E_p.
    pub e_star: f64,
    /// Effective shear modulus G* (Pa): 1 / G* = (2 - nu) / G + (2 - nu_p) / G_p.
    pub g_star: f64,
    /// Damping ratio beta (>= 0) calibrated so that the head-on e_N is `cor`.
    pub beta: f64,
    /// 4/3 E* sqrt(R) (N / m^1.5).
    pub k: f64,
    /// 2 sqrt(5/6) beta sqrt(2 E* sqrt(R) m) (N s / m^1.25).
    pub c: f64,
    /// 8 G* sqrt(R) (N / m^1.5).
    pub kt: f64,
    /// 2 sqrt(5/6) beta sqrt(8 G* sqrt(R) m) (N s / m^1.25).
    pub ct: f64,
}

impl Hertz {
    fn new(scene: &Scene, nu: f64, plate: Option<(f64, f64)>, cor: f64, mass: f64) -> Result<Self> {
        poisson("nu", nu)?;
        let e = scene.e_modulus;
        let g = e / (2.0 * (1.0 + nu));
        let (mut inv_e, mut inv_g) = ((1.0 - nu * nu) / e, (2.0 - nu) / g);
        if let Some((ep, nup)) = plate {
            positive("plate_E", ep)?;
            poisson("plate_nu", nup)?;
            let gp = ep / (2.0 * (1.0 + nup));
            inv_e += (1.0 - nup * nup) / ep;
            inv_g += (2.0 - nup) / gp;
        }
        let radius = scene.shape.circumradius();
        Self::from_moduli(1.0 / inv_e, 1.0 / inv_g, radius, mass, cor)
    }

    /// The constants of two elastic spheres `[(E1, nu1), (E2, nu2)]` in contact, with
    /// effective radius `r_star` and mass `m_star` (docs/model.md, section 17).
    pub(crate) fn of_pair(
        bodies: [(f64, f64); 2],
        r_star: f64,
        m_star: f64,
        cor: f64,
    ) -> Result<Self> {
        let (mut inv_e, mut inv_g) = (0.0, 0.0);
        for (e, nu) in bodies {
            let g = e / (2.0 * (1.0 + nu));
            inv_e += (1.0 - nu * nu) / e;
            inv_g += (2.0 - nu) / g;
        }
        Self::from_moduli(1.0 / inv_e, 1.0 / inv_g, r_star, m_star, cor)
    }

    /// The constants for effective moduli `e_star`, `g_star`, radius `radius` and mass `mass`,
    /// the damping calibrated to the head-on restitution `cor`.
    fn from_moduli(e_star: f64, g_star: f64, radius: f64, mass: f64, cor: f64) -> Result<Self> {
        check_cor(cor)?;
        let beta = super::hertz::beta_for_cor(cor);
        let sqrt_r = radius.sqrt();
        let damp = 2.0 * (5.0f64 / 6.0).sqrt() * beta;
        Ok(Hertz {
            e_star,
            g_star,
            beta,
            k: 4.0 / 3.0 * e_star * sqrt_r,
            c: damp * (2.0 * e_star * sqrt_r * mass).sqrt(),
            kt: 8.0 * g_star * sqrt_r,
            ct: damp * (8.0 * g_star * sqrt_r * mass).sqrt(),
        })
    }
}

/// k_t and c_t of the tangential spring. Mindlin's vary with the depth (`Hertz`): these are
/// then their values at the deepest accepted contact, r / 2 (for the rates only).
pub(super) fn tangential_constants(
    scene: &Scene,
    mindlin: Option<Hertz>,
    stiffness: f64,
    mt: f64,
) -> (f64, f64) {
    match mindlin {
        Some(h) => {
            let s = (0.5 * scene.shape.circumradius()).sqrt();
            (h.kt * s, h.ct * s.sqrt())
        }
        None => {
            let kt = scene.kt.unwrap_or(2.0 * stiffness / 7.0);
            (kt, scene.gamma_t * (kt * mt).sqrt())
        }
    }
}

/// A Poisson's ratio: in (-1, 0.5].
pub(crate) fn poisson(name: &str, nu: f64) -> Result<()> {
    ensure_param!(
        nu.is_finite() && nu > -1.0 && nu <= 0.5,
        name,
        nu,
        "a Poisson's ratio in (-1, 0.5]"
    );
    Ok(())
}

/// The requested head-on restitution of the Hertz law: in [0.01, 1].
pub(crate) fn check_cor(cor: f64) -> Result<()> {
    ensure_param!(
        cor.is_finite() && (super::hertz::MIN_COR..=1.0).contains(&cor),
        "cor",
        cor,
        format!(
            "in [{}, 1] (the head-on restitution the Hertz law's damping is calibrated to)",
            super::hertz::MIN_COR
        )
    );
    Ok(())
}

/// The pairings of shape, normal law and tangential law that the model has.
fn check_laws(scene: &Scene) -> Result<()> {
    let sphere = scene.shape.is_sphere();
    let hertz = matches!(scene.normal_law, NormalLaw::Hertz { .. });
    ensure_param!(
        !hertz || sphere,
        "normal_law",
        "hertz",
        "\"area\" or \"linear\" for a Disc or polygon (the Hertz law is a sphere's point \
         contact: use shape Sphere)"
    );
    ensure_param!(
        !(sphere && scene.normal_law == NormalLaw::Area),
        "normal_law",
        "area",
        "\"hertz\" or \"linear\" for a Sphere (the area law is a 2D law per unit depth)"
    );
    ensure_param!(
        !(scene.tangential == TangentialModel::Mindlin && !hertz),
        "tangential",
        "mindlin",
        "\"auto\" or \"linear\" unless normal_law is \"hertz\" (Mindlin's stiffness is the \
         Hertz contact's)"
    );
    // Each corner's dashpot force jumps as it crosses the plate. Gear-5 and the adaptive path
    // locate every crossing; Verlet's audit (the trapezoid of the powers) closes only for a
    // continuous force at a fixed step, so it can neither step over the jumps nor stop at
    // them (docs/consistency.md: residuals up to 5e-5, turned copies 9e-4 apart).
    let polygon = matches!(scene.shape, Shape::Polygon(_));
    let linear = matches!(scene.normal_law, NormalLaw::Linear { .. });
    ensure_param!(
        !(polygon && linear && scene.integrator == Integrator::Verlet),
        "integrator",
        "verlet",
        "\"gear5\" or \"adaptive\" for normal_law \"linear\" on a polygon (its corner \
         forces jump as corners cross the plate, and only these integrators locate the jumps; \
         or keep verlet with normal_law \"area\")"
    );
    let linear_t = scene.tangential == TangentialModel::Linear;
    ensure_param!(
        scene.tangential_history == TangentialHistory::Auto || (hertz && !linear_t),
        "tangential_history",
        scene.tangential_history.name(),
        "\"auto\" unless the tangential law is Mindlin's (normal_law \"hertz\" with tangential \
         \"auto\" or \"mindlin\"): the variants keep the history of a stiffness that grows \
         with the contact radius; the linear spring has one history, its elongation"
    );
    ensure_param!(
        !(hertz && linear_t && scene.kt.is_none() && scene.mu > 0.0),
        "kt",
        "None",
        "set (N/m) for tangential \"linear\" on the Hertz law (no default stiffness)"
    );
    Ok(())
}

impl Model {
    /// Kinetic energy (translation and rotation) at velocity `v` = (vx, vy, omega): J/m, J
    /// for a sphere.
    #[inline]
    pub fn kinetic_energy(&self, v: &[f64; 3]) -> f64 {
        0.5 * self.mass * (v[0] * v[0] + v[1] * v[1]) + 0.5 * self.inertia * v[2] * v[2]
    }

    /// Validates the scene and derives the constants; refuses a `dt_factor` above the scene's
    /// stability bound ([`Model::max_dt_factor`]).
    pub fn new(scene: &Scene) -> Result<Self> {
        let model = Self::derive(scene)?;
        match scene.partner {
            None => model.check_dt()?,
            // A pair's step bound is its contact's, not the particle's on the plate.
            Some(_) => super::pair::Pair::new(model.clone())?.check_dt()?,
        }
        Ok(model)
    }

    /// Everything of [`Model::new`] except the checks of `dt_factor` and `dt`.
    pub(crate) fn derive(scene: &Scene) -> Result<Self> {
        positive("rho", scene.rho)?;
        positive("E", scene.e_modulus)?;
        non_negative("gamma", scene.gamma)?;
        non_negative("gamma_t", scene.gamma_t)?;
        non_negative("mu", scene.mu)?;
        if let Some(kt) = scene.kt {
            positive("kt", kt)?;
        }
        if let Some(n) = scene.max_steps {
            ensure_param!(
                n >= 1,
                "max_steps",
                n,
                ">= 1 (or unset for the default budget)"
            );
        }
        ensure_param!(
            (1e-12..=1e-2).contains(&scene.tol),
            "tol",
            scene.tol,
            "in [1e-12, 1e-2] (the target absolute error of e_N, e_T, e_kin, omega_out r / v)"
        );
        let r = scene.shape.circumradius();
        positive("r", r)?;
        scene.overlap.check_shape(&scene.shape)?;
        check_laws(scene)?;
        let mass = scene.rho * scene.shape.area();
        let inertia = match scene.inertia {
            InertiaModel::Shape => scene.rho * scene.shape.polar_moment(),
            InertiaModel::Sphere => {
                ensure_param!(
                    matches!(scene.shape, Shape::Disc { .. } | Shape::Sphere { .. }),
                    "inertia",
                    "sphere",
                    "\"shape\" for polygons (\"sphere\" applies to discs and spheres only)"
                );
                0.4 * mass * r * r
            }
        };
        let mut hertz = None;
        let stiffness = match scene.normal_law {
            NormalLaw::Area => scene.e_modulus,
            NormalLaw::Linear { kn, cn } => {
                positive("kn", kn)?;
                non_negative("cn", cn)?;
                kn
            }
            NormalLaw::Hertz { nu, plate, cor } => {
                let h = Hertz::new(scene, nu, plate, cor, mass)?;
                hertz = Some(h);
                // E* R (N/m): t_ref = sqrt(m / (E* R)) is ~1/12 of a contact (section 14.5).
                h.e_star * r
            }
        };
        let mindlin = hertz.is_some() && scene.tangential != TangentialModel::Linear;
        let history = match scene.tangential_history {
            TangentialHistory::Auto if mindlin => TangentialHistory::Force,
            chosen => chosen,
        };
        let t_ref = (mass / stiffness).sqrt();
        let mt = 1.0 / (1.0 / mass + r * r / inertia);
        let (kt, ct) = tangential_constants(scene, hertz.filter(|_| mindlin), stiffness, mt);
        let length = 4.0 * r;
        let area_damping = scene.gamma * (mass * scene.e_modulus).sqrt() / length;
        let dt = scene.dt_factor * t_ref;
        for (name, v) in [
            ("mass", mass),
            ("inertia", inertia),
            ("kt", kt),
            ("ct", ct),
            ("area_damping", area_damping),
        ] {
            ensure_param!(
                v.is_finite() && v >= 0.0 && (v > 0.0 || name == "ct" || name == "area_damping"),
                name,
                v,
                "finite and > 0 (check the magnitudes of r, rho and E)"
            );
        }
        Ok(Model {
            scene: scene.clone(),
            mass,
            inertia,
            r,
            length,
            t_ref,
            dt,
            kt,
            ct,
            area_damping,
            hertz,
            mindlin,
            history,
        })
    }

    /// The tangential spring's coefficients at depth `depth` (> 0): (k_xi, rate, c_t) with the
    /// elastic force -k_xi xi, d(xi)/dt = rate v_t (plus [`Model::history_shrink`] xi) and
    /// the damping -c_t v_t. The linear spring: (k_t, 1, c_t); Mindlin's with its history as
    /// the force (the default): (1, k_t(delta), c_t(delta)), so that xi is minus the elastic
    /// force (N); as the displacement: (k_t(delta), 1, c_t(delta)), xi in m.
    #[inline(always)]
    pub fn spring(&self, depth: f64) -> (f64, f64, f64) {
        match self.hertz {
            Some(h) if self.mindlin => {
                let s = depth.max(0.0).sqrt();
                let (k_t, c_t) = (h.kt * s, h.ct * s.sqrt());
                // Selects, not a branch (0.6 % fewer instructions per sphere step). As the
                // displacement the stiffness is never zero: the elongation that carries a
                // force, -(F_t + c_t v_t) / k_t, stays finite (0 at touch, where F_t, c_t are).
                let force = self.history.in_force();
                let k_xi = if force {
                    1.0
                } else {
                    k_t.max(f64::MIN_POSITIVE)
                };
                (k_xi, if force { k_t } else { 1.0 }, c_t)
            }
            _ => (self.kt, 1.0, self.ct),
        }
    }

    /// The rate lambda at which the `mindlin_rescale` variants shrink their history xi while
    /// the contact unloads: the continuous form of xi <- xi a / a_prev with a = sqrt(R delta),
    /// lambda = d(ln a)/dt = d(delta)/dt / (2 delta), added to d(xi)/dt as lambda xi while
    /// sticking. Applied only from the deepest point on (the fixed steps compare the depths,
    /// the adaptive path switches its mode there); 0 for the other histories and out of contact.
    #[inline(always)]
    pub fn history_shrink(&self, depth: f64, depth_rate: f64) -> f64 {
        if self.history.rescales() && depth > 0.0 {
            0.5 * depth_rate / depth
        } else {
            0.0
        }
    }

    /// The relative rate at which the elastic force -k_xi xi of a sticking spring changes
    /// besides the contact point's motion: d(k_xi xi)/dt = k_xi rate v_t + kappa k_xi xi, with
    /// kappa the history's shrink ([`Model::history_shrink`], if `unloading`) plus, for a
    /// history kept as the displacement, the stiffness's own growth d(ln k_t)/dt =
    /// d(delta)/dt / (2 delta).
    #[inline(always)]
    pub fn elastic_drift(&self, depth: f64, depth_rate: f64, unloading: bool) -> f64 {
        let shrink = if unloading {
            self.history_shrink(depth, depth_rate)
        } else {
            0.0
        };
        if self.mindlin && !self.history.in_force() && depth > 0.0 {
            shrink + 0.5 * depth_rate / depth
        } else {
            shrink
        }
    }

    /// Validates an initial state for this model.
    pub fn check_initial(&self, init: &Initial) -> Result<()> {
        finite("vx", init.vx)?;
        finite("vy", init.vy)?;
        finite("omega_in", init.omega)?;
        finite("phi0", init.phi0)?;
        // Beyond this rim speed no material holds together (wave speeds are ~1e3-1e4 m/s) and
        // the kinetic energy of absurd spins would overflow: refuse instead of returning NaN.
        ensure_param!(
            init.omega.abs() * self.r <= MAX_RIM_SPEED,
            "omega_in",
            init.omega,
            format!(
                "with |omega_in| r <= {MAX_RIM_SPEED:e} m/s (r = {} m)",
                self.r
            )
        );
        ensure_param!(
            init.vy < 0.0,
            "vy",
            init.vy,
            "< 0 (the particle must approach the plate)"
        );
        Ok(())
    }
}

/// Every rule a case must meet before it runs: the scene's ([`Model::new`], the time-step
/// bound included) and the initial state's.
pub fn check_case(scene: &Scene, init: &Initial) -> Result<()> {
    Model::new(scene)?.check_initial(init)
}
