//! Scene parameters: what the user chooses, validated, with the study's defaults, and the
//! derived constants (mass, inertia, time step, tangential spring) the contact law uses.

use crate::error::{ensure_param, finite, non_negative, positive, Error, Result};
use crate::geometry::{OverlapMethod, Shape};

/// The normal contact law.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum NormalLaw {
    /// Force proportional to the overlap area (the study's law): F = E A / L plus damping
    /// gamma sqrt(m E) (dA/dt) / L.
    #[default]
    Area,
    /// Linear spring-dashpot on the depth of the lowest point: F = kn delta + cn d(delta)/dt.
    Linear {
        /// Normal stiffness kn (Pa: force per depth per metre).
        kn: f64,
        /// Normal damping cn (Pa s).
        cn: f64,
    },
    /// Hertz point contact of a sphere (docs/model.md, section 14): F = 4/3 E* sqrt(R)
    /// delta^(3/2) plus the Tsuji dashpot calibrated to the head-on restitution `cor`.
    Hertz {
        /// Poisson's ratio of the particle.
        nu: f64,
        /// The plate's Young's modulus and Poisson's ratio; `None`: a rigid plate.
        plate: Option<(f64, f64)>,
        /// Head-on coefficient of restitution the dashpot is calibrated to, in [0.01, 1].
        cor: f64,
    },
}

/// The tangential law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TangentialModel {
    /// What the normal law implies: Mindlin for the Hertz law, else the linear spring.
    #[default]
    Auto,
    /// Cundall-Strack linear spring k_t with damping gamma_t (docs/model.md, section 5).
    Linear,
    /// Mindlin-Deresiewicz no-slip stiffness k_t = 8 G* sqrt(R delta), incremental in the
    /// force, with the Tsuji damping (Hertz law only; docs/model.md, section 14.4).
    Mindlin,
}

impl TangentialModel {
    /// Every tangential law, in code order (the consistency matrix runs them all).
    pub const ALL: [TangentialModel; 3] = [
        TangentialModel::Auto,
        TangentialModel::Linear,
        TangentialModel::Mindlin,
    ];
}

impl NormalLaw {
    /// Every normal law, in code order (the consistency matrix runs them all); the parameters
    /// shown are placeholders, set per scene by [`NormalLaw::with_scale`].
    pub const ALL: [NormalLaw; 3] = [
        NormalLaw::Area,
        NormalLaw::Linear { kn: 1.0, cn: 0.0 },
        NormalLaw::Hertz {
            nu: 0.3,
            plate: None,
            cor: 1.0,
        },
    ];

    /// The same law with its own parameters set from a stiffness scale `stiffness` (Pa) and a
    /// damping ratio `zeta` for a particle of mass `mass`: the linear law gets kn = stiffness
    /// and cn = 2 zeta sqrt(kn m); the area law has none (its damping is the scene's gamma);
    /// the Hertz law keeps its nu and plate and takes the restitution of a linear oscillator
    /// with damping ratio zeta, exp(-pi zeta / sqrt(1 - zeta^2)), as its `cor`.
    pub fn with_scale(self, stiffness: f64, zeta: f64, mass: f64) -> Self {
        match self {
            NormalLaw::Area => NormalLaw::Area,
            NormalLaw::Linear { .. } => NormalLaw::Linear {
                kn: stiffness,
                cn: 2.0 * zeta * (stiffness * mass).sqrt(),
            },
            NormalLaw::Hertz { nu, plate, .. } => NormalLaw::Hertz {
                nu,
                plate,
                cor: (-std::f64::consts::PI * zeta / (1.0 - zeta * zeta).max(1e-12).sqrt())
                    .exp()
                    .clamp(0.01, 1.0),
            },
        }
    }

    /// Public name, as in the Python API.
    pub fn name(self) -> &'static str {
        match self {
            NormalLaw::Area => "area",
            NormalLaw::Linear { .. } => "linear",
            NormalLaw::Hertz { .. } => "hertz",
        }
    }
}

/// Which moment of inertia the particle gets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum InertiaModel {
    /// From the shape (disc: m r^2 / 2; polygons: exact polygon formula).
    #[default]
    Shape,
    /// Sphere, I = 0.4 m r^2, for comparison with 3D codes (discs only).
    Sphere,
}

impl InertiaModel {
    /// Every inertia model, in code order (the consistency matrix runs them all).
    pub const ALL: [InertiaModel; 2] = [InertiaModel::Shape, InertiaModel::Sphere];

    /// Public name, as in the Python API.
    pub fn name(self) -> &'static str {
        match self {
            InertiaModel::Shape => "shape",
            InertiaModel::Sphere => "sphere",
        }
    }
}

/// The time integrator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Integrator {
    /// Gear 5th-order predictor-corrector (6 scaled Taylor terms), the study's integrator.
    #[default]
    Gear5,
    /// Velocity Verlet; velocity-dependent forces see the predicted velocity v + a dt.
    Verlet,
    /// High-accuracy reference: adaptive Dormand-Prince 5(4) with the contact's switches
    /// located (see [`crate::integrate::adaptive`]) at its tightest setting; `dt_factor` is its
    /// largest step in units of t_ref.
    Reference,
    /// The same adaptive path at the scene's [`Scene::tol`]: the target for the absolute error
    /// of e_N, e_T, e_kin and omega_out r / v; `dt_factor` is its largest step.
    Adaptive,
}

impl Integrator {
    /// Every integrator, in code order (the consistency matrix runs them all).
    pub const ALL: [Integrator; 4] = [
        Integrator::Gear5,
        Integrator::Verlet,
        Integrator::Reference,
        Integrator::Adaptive,
    ];

    /// Whether it is the adaptive Dormand-Prince path (`Reference` or `Adaptive`).
    pub fn is_adaptive(self) -> bool {
        matches!(self, Integrator::Reference | Integrator::Adaptive)
    }

    /// Largest accepted stiffness index h = dt * (fastest rate of the contact), the measured
    /// stability bound divided by a safety margin of 2 (and rounded down); see
    /// [`crate::model::stability`] for the rates.
    ///
    /// Measured by scanning h upward (`tests/stability.rs`, `measure`) over the disc, the
    /// 120-gon and a square (face and corner first), head-on and oblique, mu 0 and 1 (full
    /// stick), the area law with gamma 0 ... 1e3 and the linear law (disc) with zeta 0 ... 100,
    /// gamma_t 0 ... 100, at the preset speed and a deep impact (depth ~ 0.45 r), with the
    /// criteria of that file (finite, no energy gain, |energy_residual| <= 1e-2, and at the
    /// preset speed halving dt moves the result by <= 5 % of v). First failures:
    /// - Gear-5: h = 0.1355 (linear law, zeta = 1 and 10, full stick: r omega' moves by > 5 %
    ///   when dt halves); so 0.065.
    /// - Verlet: h = 0.2016 (undamped linear law head-on: energy error > 1 %); so 0.098.
    ///
    /// On the preset (fastest rate: the tangential spring, sqrt(6 / 7) / t_ref) that gives
    /// `dt_factor` <= 0.0702 (Gear-5) and 0.105 (Verlet), above the former fixed 0.03 and 0.1.
    /// `Reference` is adaptive: its `dt_factor` is only its largest step, at most 1.
    pub fn max_stiffness_index(self) -> f64 {
        match self {
            Integrator::Gear5 => 0.065,
            Integrator::Verlet => 0.098,
            Integrator::Reference | Integrator::Adaptive => f64::INFINITY,
        }
    }

    /// The `dt_factor` a scene gets when it names none (an unset, NaN, column): the study's
    /// step 0.01 t_ref for the fixed steps and the reference, and for the adaptive path a
    /// largest step of 1 t_ref, where its tolerance alone sets the steps (the disc's contact
    /// lasts ~19 t_ref: a cap of 0.01 would take over 1900 steps where tol 1e-6 needs ~74).
    pub fn default_dt_factor(self) -> f64 {
        match self {
            Integrator::Adaptive => 1.0,
            _ => 0.01,
        }
    }

    /// Public name, as in the Python API.
    pub fn name(self) -> &'static str {
        match self {
            Integrator::Gear5 => "gear5",
            Integrator::Verlet => "verlet",
            Integrator::Reference => "reference",
            Integrator::Adaptive => "adaptive",
        }
    }
}

/// Largest rim speed |omega_in| r accepted (m/s).
pub const MAX_RIM_SPEED: f64 = 1e6;

/// Everything that defines an impact except the initial velocity and spin.
///
/// `Scene::default()` is the study's preset on an exact disc (docs/model.md, section 12).
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Particle shape (default: exact disc, r = 0.01 m).
    pub shape: Shape,
    /// Density rho (kg/m^3; default 2500).
    pub rho: f64,
    /// Young's modulus E of the area law (Pa; default 1e7). Sets t_ref = sqrt(m / E).
    pub e_modulus: f64,
    /// Normal damping gamma of the area law (dimensionless; default 0.33).
    pub gamma: f64,
    /// Tangential damping ratio gamma_t: c_t = gamma_t sqrt(k_t m_t) (default 0.5; 0 allowed).
    pub gamma_t: f64,
    /// Coulomb friction coefficient mu (default 0.5; 0: no tangential force).
    pub mu: f64,
    /// Tangential stiffness k_t (Pa); `None`: 2 E / 7 (area law) or 2 kn / 7 (linear law).
    pub kt: Option<f64>,
    /// Normal contact law (default: area).
    pub normal_law: NormalLaw,
    /// Moment of inertia model (default: from the shape).
    pub inertia: InertiaModel,
    /// Time integrator (default: Gear-5).
    pub integrator: Integrator,
    /// dt = dt_factor * t_ref (default 0.01).
    pub dt_factor: f64,
    /// How the overlap with the plate is computed (default: what the shape requires).
    pub overlap: OverlapMethod,
    /// The tangential law (default: what the normal law implies).
    pub tangential: TangentialModel,
    /// Most integration steps one impact may take (>= 1); past it the impact ends with
    /// `timed_out` and `stop = StepBudget`. `None`: the default budget, a fixed multiple of
    /// the contact's own number of steps ([`crate::impact::default_step_budget`]).
    pub max_steps: Option<u64>,
    /// Target for the absolute error of e_N, e_T, e_kin and omega_out r / v of the adaptive
    /// integrator (`Integrator::Adaptive`; default 1e-6, in [1e-12, 1e-2]). Ignored by the
    /// others (`Reference` runs at its tightest setting).
    pub tol: f64,
    /// Whether the fixed-step integrators estimate their own error (`Record::err_est`) by a
    /// second run at half the step (Richardson); the adaptive path always does, at no cost.
    pub error_estimate: bool,
}

/// The local tolerance per unit of the target error `Scene::tol` of the adaptive integrator.
/// Over the accuracy grid (`tests/adaptive.rs`: three shapes, theta 4..89, mu 0..1, three
/// spins, two tangential dampings, tol 1e-4 ... 1e-10, largest steps 0.2 ... 5) the largest
/// error of the four outputs is 1.70 tol at 0.5 (below the 3 tol promised), with 7 ... 21 %
/// fewer steps than at 0.15 (where it was 0.51 tol; at 0.05, 1.00 tol with a short stick phase
/// missed). At 0.5 `err_est` needs the factor 2.25
/// ([`crate::integrate::adaptive::ERR_EST_FACTOR`]): at 1.5 it covered the error in only
/// 92.5 % of one setting's impacts.
pub const LOCAL_TOL_PER_TARGET: f64 = 0.5;

/// The reference integrator's local tolerance per step: global errors come out at about
/// 20 times it.
pub const REFERENCE_LOCAL_TOL: f64 = 1e-12;

impl Scene {
    /// The local error tolerance per step of the adaptive path for this scene: the
    /// reference's for `Integrator::Reference`, the scene's target `tol` scaled for
    /// `Integrator::Adaptive`. (Here rather than in the adaptive path so that the step budget
    /// in `impact` can read it without depending on that path.)
    pub(crate) fn local_tol(&self) -> f64 {
        match self.integrator {
            Integrator::Adaptive => self.tol * LOCAL_TOL_PER_TARGET,
            _ => REFERENCE_LOCAL_TOL,
        }
    }
}

impl Default for Scene {
    fn default() -> Self {
        Scene {
            shape: Shape::Disc { r: 0.01 },
            rho: 2500.0,
            e_modulus: 1e7,
            gamma: 0.33,
            gamma_t: 0.5,
            mu: 0.5,
            kt: None,
            normal_law: NormalLaw::Area,
            inertia: InertiaModel::Shape,
            integrator: Integrator::Gear5,
            dt_factor: 0.01,
            overlap: OverlapMethod::Auto,
            tangential: TangentialModel::Auto,
            max_steps: None,
            tol: 1e-6,
            error_estimate: false,
        }
    }
}

/// The particle's state at first touch: velocity (m/s), spin (rad/s, counter-clockwise
/// positive) and orientation (rad).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Initial {
    /// Velocity along the plate (m/s).
    pub vx: f64,
    /// Velocity normal to the plate (m/s); must be < 0 (approaching).
    pub vy: f64,
    /// Spin before impact (rad/s, counter-clockwise positive).
    pub omega: f64,
    /// Orientation at first touch (rad; ignored for a disc).
    pub phi0: f64,
}

impl Initial {
    /// v (cos theta, -sin theta) with theta from the plate in degrees; cos is exactly 0 at 90.
    pub fn from_angle(v: f64, theta_deg: f64, omega: f64, phi0_deg: f64) -> Self {
        let (s, c) = sin_cos_deg(theta_deg);
        Initial {
            vx: v * c,
            vy: -v * s,
            omega,
            phi0: phi0_deg.to_radians(),
        }
    }
}

/// sin and cos of an angle in degrees, exact at multiples of 90 degrees.
pub fn sin_cos_deg(deg: f64) -> (f64, f64) {
    let r = deg.rem_euclid(360.0);
    if r == 0.0 {
        (0.0, 1.0)
    } else if r == 90.0 {
        (1.0, 0.0)
    } else if r == 180.0 {
        (0.0, -1.0)
    } else if r == 270.0 {
        (-1.0, 0.0)
    } else {
        deg.to_radians().sin_cos()
    }
}

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
        check_cor(cor)?;
        let beta = super::hertz::beta_for_cor(cor);
        let (e_star, g_star) = (1.0 / inv_e, 1.0 / inv_g);
        let sqrt_r = scene.shape.circumradius().sqrt();
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
fn tangential_constants(
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
fn poisson(name: &str, nu: f64) -> Result<()> {
    ensure_param!(
        nu.is_finite() && nu > -1.0 && nu <= 0.5,
        name,
        nu,
        "a Poisson's ratio in (-1, 0.5]"
    );
    Ok(())
}

/// The requested head-on restitution of the Hertz law: in [0.01, 1].
fn check_cor(cor: f64) -> Result<()> {
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
        model.check_dt()?;
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
        })
    }

    /// The tangential spring's coefficients at depth `depth` (> 0): (k_xi, rate, c_t) with the
    /// elastic force -k_xi xi, d(xi)/dt = rate v_t and the damping -c_t v_t. The linear spring:
    /// (k_t, 1, c_t); Mindlin's, incremental in the force: (1, k_t(delta), c_t(delta)), so
    /// that xi is minus the elastic force (N).
    #[inline(always)]
    pub fn spring(&self, depth: f64) -> (f64, f64, f64) {
        match self.hertz {
            Some(h) if self.mindlin => {
                let s = depth.max(0.0).sqrt();
                (1.0, h.kt * s, h.ct * s.sqrt())
            }
            _ => (self.kt, 1.0, self.ct),
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

/// The one schema of a scene's parameters as per-case columns, shared with every binding:
/// a binding reads these columns by name (all float64; a choice is the index of its name in
/// [`CHOICES`], an optional parameter is NaN when unset) and calls [`scene_from_columns`].
/// Adding a parameter means a field of [`Scene`], a name here and its line in
/// [`scene_from_columns`] (and the Python `Scene` field): nothing else.
pub const CASE_COLUMNS: [&str; 28] = [
    "theta_deg",
    "omega_in",
    "v",
    "mu",
    "gamma",
    "gamma_t",
    "E",
    "rho",
    "r",
    "phi0_deg",
    "dt_factor",
    "kn",
    "cn",
    "kt",
    "n",
    "integrator",
    "normal_law",
    "inertia",
    "overlap",
    "nu",
    "plate_E",
    "plate_nu",
    "cor",
    "tangential",
    "body",
    "max_steps",
    "tol",
    "error_estimate",
];

/// Public names of every choice, in code order: a choice column holds the index of its name.
/// `body`: "prism" is a 2D body per unit depth (the disc or polygon the column `n` names),
/// "sphere" a sphere of radius `r` (then `n` must be 0).
pub const CHOICES: [(&str, &[&str]); 6] = [
    ("integrator", &["gear5", "verlet", "reference", "adaptive"]),
    ("normal_law", &["area", "linear", "hertz"]),
    ("inertia", &["shape", "sphere"]),
    ("overlap", &["auto", "halfplane", "parry"]),
    ("tangential", &["auto", "linear", "mindlin"]),
    ("body", &["prism", "sphere"]),
];

/// The impact angle's rule, written once: in (0, 90] degrees, measured from the plate.
pub fn check_theta(theta_deg: f64) -> Result<()> {
    ensure_param!(
        theta_deg.is_finite() && theta_deg > 0.0 && theta_deg <= 90.0,
        "theta_deg",
        theta_deg,
        "in (0, 90] degrees, measured from the plate"
    );
    Ok(())
}

/// The orientation's rule, written once: any finite angle (degrees).
pub fn check_orientation(phi0_deg: f64) -> Result<()> {
    finite("phi0_deg", phi0_deg)
}

/// The index a choice column holds, checked against the names of [`CHOICES`].
fn choice(name: &str, code: f64) -> Result<usize> {
    let names = CHOICES
        .iter()
        .find(|(n, _)| *n == name)
        .map_or(&[][..], |c| c.1);
    if code.fract() == 0.0 && code >= 0.0 && (code as usize) < names.len() {
        return Ok(code as usize);
    }
    // The message lists the codes; formed only for a bad one (formed for every case, it took
    // most of a sweep's per-case set-up, ~1 us).
    let listed: Vec<String> = names
        .iter()
        .enumerate()
        .map(|(i, n)| format!("{i} ({n})"))
        .collect();
    Err(Error::invalid(
        name,
        code,
        format!("a code in {}", listed.join(", ")),
    ))
}

/// An optional parameter: NaN means unset.
fn optional(value: f64) -> Option<f64> {
    (!value.is_nan()).then_some(value)
}

/// A flag column: 0 or 1.
fn flag(name: &str, value: f64) -> Result<bool> {
    ensure_param!(
        value == 0.0 || value == 1.0,
        name,
        value,
        "0 (false) or 1 (true)"
    );
    Ok(value == 1.0)
}

/// The `max_steps` column: NaN for the default budget, else a whole number >= 1 (below
/// 2^63, exactly representable up to 2^53).
fn step_budget(value: f64) -> Result<Option<u64>> {
    if value.is_nan() {
        return Ok(None);
    }
    ensure_param!(
        value.fract() == 0.0 && (1.0..9.2e18).contains(&value),
        "max_steps",
        value,
        "a whole number >= 1 (or unset for the default budget)"
    );
    Ok(Some(value as u64))
}

/// The particle's shape from the columns `n` (0: exact disc, >= 3: regular n-gon) and `r`,
/// or from unit-circumradius `vertices` scaled by `r` (then `n` is ignored).
pub fn shape_from_columns(n: f64, r: f64, vertices: Option<&[[f64; 2]]>) -> Result<Shape> {
    if let Some(v) = vertices {
        positive("r", r)?;
        let scaled: Vec<[f64; 2]> = v.iter().map(|p| [p[0] * r, p[1] * r]).collect();
        return Shape::convex_polygon(&scaled);
    }
    ensure_param!(
        n.fract() == 0.0 && (n == 0.0 || (3.0..=1e7).contains(&n)),
        "n",
        n,
        "an integer >= 3, or 0 for an exact disc"
    );
    if n == 0.0 {
        Shape::disc(r)
    } else {
        Shape::regular_polygon(r, n as usize)
    }
}

/// One case (scene and initial state) from a row of [`CASE_COLUMNS`]. Checks the columns'
/// own rules (codes, shape, angle, speed); the scene's rules are [`Model::new`]'s, applied
/// when the case runs or by [`check_case`].
pub fn scene_from_columns(
    row: &[f64; CASE_COLUMNS.len()],
    vertices: Option<&[[f64; 2]]>,
) -> Result<(Scene, Initial)> {
    scene_from_columns_with(row, vertices, None)
}

/// Where in a row the columns that make a case's shape are: `n`, `r` and `body` (with the
/// sweep's vertices).
pub(crate) fn shape_columns() -> [usize; 3] {
    ["n", "r", "body"].map(|name| {
        CASE_COLUMNS
            .iter()
            .position(|c| *c == name)
            .expect("a case column")
    })
}

/// [`scene_from_columns`], with the shape already built from the same `n`, `r` and `body`
/// (and vertices) when `shape` is given.
pub(crate) fn scene_from_columns_with(
    row: &[f64; CASE_COLUMNS.len()],
    vertices: Option<&[[f64; 2]]>,
    shape: Option<Shape>,
) -> Result<(Scene, Initial)> {
    let [theta, omega, v, mu, gamma, gamma_t, e, rho, r, phi0, dtf, kn, cn, kt, n, integ, law, inertia, overlap, nu, plate_e, plate_nu, cor, tangential, body, max_steps, tol, error_estimate] =
        *row;
    check_theta(theta)?;
    positive("v", v)?;
    finite("omega_in", omega)?;
    check_orientation(phi0)?;
    // Set or not, whatever the law: a value the scene ignores must still be a valid one.
    optional(kn).map_or(Ok(()), |k| positive("kn", k))?;
    optional(cn).map_or(Ok(()), |c| non_negative("cn", c))?;
    let stiffness = optional(kn).unwrap_or(e);
    let integrator = Integrator::ALL[choice("integrator", integ)?];
    let normal_law = match choice("normal_law", law)? {
        0 => NormalLaw::Area,
        1 => NormalLaw::Linear {
            kn: stiffness,
            cn: optional(cn).unwrap_or(0.0),
        },
        _ => hertz_from_columns(nu, plate_e, plate_nu, cor)?,
    };
    optional(nu).map_or(Ok(()), |x| poisson("nu", x))?;
    optional(cor).map_or(Ok(()), check_cor)?;
    let shape = match shape {
        Some(shape) => shape,
        None if choice("body", body)? == 1 => {
            ensure_param!(
                n == 0.0 && vertices.is_none(),
                "n",
                n,
                "0 for a sphere (body \"sphere\")"
            );
            Shape::sphere(r)?
        }
        None => shape_from_columns(n, r, vertices)?,
    };
    let scene = Scene {
        shape,
        rho,
        e_modulus: e,
        gamma,
        gamma_t,
        mu,
        kt: optional(kt),
        normal_law,
        inertia: [InertiaModel::Shape, InertiaModel::Sphere][choice("inertia", inertia)?],
        integrator,
        dt_factor: optional(dtf).unwrap_or(integrator.default_dt_factor()),
        overlap: [
            OverlapMethod::Auto,
            OverlapMethod::HalfPlane,
            OverlapMethod::Parry,
        ][choice("overlap", overlap)?],
        tangential: [
            TangentialModel::Auto,
            TangentialModel::Linear,
            TangentialModel::Mindlin,
        ][choice("tangential", tangential)?],
        max_steps: step_budget(max_steps)?,
        tol,
        error_estimate: flag("error_estimate", error_estimate)?,
    };
    Ok((scene, Initial::from_angle(v, theta, omega, phi0)))
}

/// The Hertz law from its columns: `nu` and `cor` required, `plate_E` and `plate_nu` both
/// set (an elastic plate) or both unset (a rigid one).
fn hertz_from_columns(nu: f64, plate_e: f64, plate_nu: f64, cor: f64) -> Result<NormalLaw> {
    let required = "set for normal_law \"hertz\"";
    let nu = optional(nu).ok_or_else(|| Error::invalid("nu", "None", required))?;
    let cor = optional(cor).ok_or_else(|| Error::invalid("cor", "None", required))?;
    let plate = match (optional(plate_e), optional(plate_nu)) {
        (Some(ep), Some(nup)) => Some((ep, nup)),
        (None, None) => None,
        (Some(_), None) => {
            return Err(Error::invalid(
                "plate_nu",
                "None",
                "set with plate_E (the plate's Poisson's ratio)",
            ))
        }
        (None, Some(x)) => {
            return Err(Error::invalid(
                "plate_nu",
                x,
                "None without plate_E (a rigid plate has no Poisson's ratio)",
            ))
        }
    };
    Ok(NormalLaw::Hertz { nu, plate, cor })
}

/// Every rule a case must meet before it runs: the scene's ([`Model::new`], the time-step
/// bound included) and the initial state's.
pub fn check_case(scene: &Scene, init: &Initial) -> Result<()> {
    Model::new(scene)?.check_initial(init)
}
