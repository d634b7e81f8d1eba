//! Scene parameters: what the user chooses, with the study's defaults (the choices as enums,
//! the `Scene`, the initial state). What follows from them is `derived.rs`; the scene as
//! per-case columns, `columns.rs`.

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

/// How Mindlin's tangential spring keeps its history: the variants of LAMMPS's `pair
/// granular` tangential models (docs/model.md, section 14.8). With a = sqrt(R delta) the
/// contact radius and k_t = 8 G* a, each sticking step adds -k_t v_t dt to the elastic force
/// (`Force`) or v_t dt to the displacement xi, the force then being -k_t xi (`Displacement`);
/// the `Rescale` variants also shrink the history by a / a_prev while the contact unloads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TangentialHistory {
    /// What the tangential law implies: `Force` for Mindlin's (today's law, bit for bit); the
    /// linear spring has one history only, its elongation.
    #[default]
    Auto,
    /// LAMMPS `mindlin`: the history is the displacement xi, F_el = -k_t(delta) xi, so the
    /// force follows the stiffness as the depth changes.
    Displacement,
    /// LAMMPS `mindlin/force`: the history is the elastic force, dF_el = -k_t(delta) v_t dt.
    Force,
    /// LAMMPS `mindlin_rescale`: `Displacement`, with xi scaled by a / a_prev on unloading.
    RescaleDisplacement,
    /// LAMMPS `mindlin_rescale/force`: `Force`, with F_el scaled by a / a_prev on unloading.
    RescaleForce,
}

impl TangentialHistory {
    /// Every history, in code order (the public names are [`crate::CHOICES`]').
    pub const ALL: [TangentialHistory; 5] = [
        TangentialHistory::Auto,
        TangentialHistory::Displacement,
        TangentialHistory::Force,
        TangentialHistory::RescaleDisplacement,
        TangentialHistory::RescaleForce,
    ];

    /// Public name, as in the Python API (LAMMPS's).
    pub fn name(self) -> &'static str {
        match self {
            TangentialHistory::Auto => "auto",
            TangentialHistory::Displacement => "mindlin",
            TangentialHistory::Force => "mindlin/force",
            TangentialHistory::RescaleDisplacement => "mindlin_rescale",
            TangentialHistory::RescaleForce => "mindlin_rescale/force",
        }
    }

    /// Whether the history is the elastic force (else the displacement).
    pub fn in_force(self) -> bool {
        matches!(
            self,
            TangentialHistory::Auto | TangentialHistory::Force | TangentialHistory::RescaleForce
        )
    }

    /// Whether the history shrinks with the contact radius as the contact unloads.
    pub fn rescales(self) -> bool {
        matches!(
            self,
            TangentialHistory::RescaleDisplacement | TangentialHistory::RescaleForce
        )
    }
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
    /// located (see [`crate::impact::adaptive`]) at its tightest setting; `dt_factor` is its
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
    /// How Mindlin's spring keeps its history (default: as the force, `mindlin/force`).
    pub tangential_history: TangentialHistory,
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
    /// What the particle hits: `None` the plate (default), else a second free particle
    /// (docs/model.md, section 17).
    pub partner: Option<Partner>,
}

/// A second free particle the particle collides with, in place of the plate (docs/model.md,
/// section 17). Its material defaults to the particle's own; its contact law, damping,
/// friction and numerics are the scene's.
#[derive(Debug, Clone, PartialEq)]
pub struct Partner {
    /// Its shape, in its body frame (a disc for a disc particle, a sphere for a sphere).
    pub shape: Shape,
    /// Its density (kg/m^3); `None`: the particle's.
    pub rho: Option<f64>,
    /// Its Young's modulus (Pa); `None`: the particle's.
    pub e_modulus: Option<f64>,
    /// Its Poisson's ratio (Hertz law); `None`: the particle's.
    pub nu: Option<f64>,
}

impl Partner {
    /// The partners the consistency matrix pairs `shape` with, named: none (the plate), a twin
    /// of the particle, and a round body twice as large and three times as dense (a sphere for
    /// a sphere, else a disc: a polygon's "big" partner is the disc-polygon pairing).
    pub fn representatives(shape: &Shape) -> Vec<(String, Option<Partner>)> {
        let r = shape.circumradius();
        let big = match shape {
            Shape::Sphere { .. } => Shape::Sphere { r: 2.0 * r },
            _ => Shape::Disc { r: 2.0 * r },
        };
        vec![
            ("plate".to_string(), None),
            ("twin".to_string(), Some(Partner::of(shape.clone()))),
            (
                "big".to_string(),
                Some(Partner {
                    shape: big,
                    rho: Some(7500.0),
                    e_modulus: None,
                    nu: None,
                }),
            ),
        ]
    }

    /// A partner of shape `shape` of the particle's own material.
    pub fn of(shape: Shape) -> Self {
        Partner {
            shape,
            rho: None,
            e_modulus: None,
            nu: None,
        }
    }
}

/// The local tolerance per unit of the target error `Scene::tol` of the adaptive integrator,
/// for a body with corners on the plate and for every pair.
/// Over the accuracy grid (`tests/adaptive.rs`: three shapes, theta 4..89, mu 0..1, three
/// spins, two tangential dampings, tol 1e-4 ... 1e-10, largest steps 0.2 ... 5) the largest
/// error of the four outputs is 1.70 tol at 0.5 (below the 3 tol promised), with 7 ... 21 %
/// fewer steps than at 0.15 (where it was 0.51 tol; at 0.05, 1.00 tol with a short stick phase
/// missed). At 0.5 `err_est` needs the factor 2.25
/// ([`crate::impact::adaptive::ERR_EST_FACTOR`]): at 1.5 it covered the error in only
/// 92.5 % of one setting's impacts.
pub const LOCAL_TOL_PER_TARGET: f64 = 0.5;

/// [`LOCAL_TOL_PER_TARGET`] for a round body (disc, sphere) on the plate: no corner crosses the
/// plate, so fewer located switches add their errors to the steps'. (Not for pairs: two discs at
/// 0.75 erred 3.35 tol at tol 1e-8 in `adaptive_pairs_meet_their_tolerance`.) Over the same grid
/// the disc's largest error is 0.94 tol at 0.5, 1.41 tol at 0.75 (5 % fewer steps at tol 1e-6,
/// largest step 1) and 1.88 tol at 1.0, against the polygons' 1.70 tol at 0.5; at 1.0 a slip ->
/// stick switch of the disc at theta 54, mu 0.7 chattered into a spurious micro-stick at tol 1e-4
/// (`short_stick_and_slip_phases_are_not_lost`), and at 2.0 the error reached 3.8 tol.
pub const ROUND_LOCAL_TOL_PER_TARGET: f64 = 0.75;

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
            Integrator::Adaptive => self.tol * self.local_tol_per_target(),
            _ => REFERENCE_LOCAL_TOL,
        }
    }

    /// The adaptive path's local tolerance per unit of `tol`:
    /// [`ROUND_LOCAL_TOL_PER_TARGET`] for a disc or sphere on the plate,
    /// [`LOCAL_TOL_PER_TARGET`] otherwise.
    pub fn local_tol_per_target(&self) -> f64 {
        let round = matches!(self.shape, Shape::Disc { .. } | Shape::Sphere { .. });
        if round && self.partner.is_none() {
            ROUND_LOCAL_TOL_PER_TARGET
        } else {
            LOCAL_TOL_PER_TARGET
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
            tangential_history: TangentialHistory::Auto,
            max_steps: None,
            tol: 1e-6,
            error_estimate: false,
            partner: None,
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
    /// The partner's spin before impact (rad/s; a pair only, 0 for the plate).
    pub partner_omega: f64,
    /// The partner's orientation at first touch (rad; a pair only).
    pub partner_phi0: f64,
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
            partner_omega: 0.0,
            partner_phi0: 0.0,
        }
    }

    /// The same state with the partner's spin `omega` (rad/s) and orientation (degrees) set.
    pub fn with_partner(self, omega: f64, phi0_deg: f64) -> Self {
        Initial {
            partner_omega: omega,
            partner_phi0: phi0_deg.to_radians(),
            ..self
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
