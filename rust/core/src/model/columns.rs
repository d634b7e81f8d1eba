//! The one schema of a case as per-case columns (every binding reads these names), and the
//! case built from one row of them.

use super::derived::{check_cor, poisson};
use super::scene::{
    InertiaModel, Initial, Integrator, NormalLaw, Partner, Scene, TangentialHistory,
    TangentialModel,
};
use crate::error::{ensure_param, finite, non_negative, positive, Error, Result};
use crate::geometry::{OverlapMethod, Shape};

/// The one schema of a scene's parameters as per-case columns, shared with every binding:
/// a binding reads these columns by name (all float64; a choice is the index of its name in
/// [`CHOICES`], an optional parameter is NaN when unset) and calls [`scene_from_columns`].
/// Adding a parameter means a field of [`Scene`], a name here and its line in
/// [`scene_from_columns`] (and the Python `Scene` field): nothing else.
pub const CASE_COLUMNS: [&str; 37] = [
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
    "tangential_history",
    "body",
    "max_steps",
    "tol",
    "error_estimate",
    "partner_body",
    "partner_n",
    "partner_r",
    "partner_phi0_deg",
    "partner_rho",
    "partner_E",
    "partner_nu",
    "partner_omega_in",
];

/// How many of [`CASE_COLUMNS`], the last ones, describe the partner (`partner_*`).
const PARTNER_COLUMNS: usize = 8;

/// Public names of every choice, in code order: a choice column holds the index of its name.
/// `body`: "prism" is a 2D body per unit depth (the disc or polygon the column `n` names),
/// "sphere" a sphere of radius `r` (then `n` must be 0). `partner_body`: "plate" (no partner:
/// the `partner_*` columns are then ignored and must be unset, NaN, `partner_omega_in` 0), or
/// the partner's body as `body` says, with `partner_n`, `partner_r`, `partner_phi0_deg`.
pub const CHOICES: [(&str, &[&str]); 8] = [
    ("integrator", &["gear5", "verlet", "reference", "adaptive"]),
    ("normal_law", &["area", "linear", "hertz"]),
    ("inertia", &["shape", "sphere"]),
    ("overlap", &["auto", "halfplane", "parry"]),
    ("tangential", &["auto", "linear", "mindlin"]),
    (
        "tangential_history",
        &[
            "auto",
            "mindlin",
            "mindlin/force",
            "mindlin_rescale",
            "mindlin_rescale/force",
        ],
    ),
    ("body", &["prism", "sphere"]),
    ("partner_body", &["plate", "prism", "sphere"]),
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

/// The unit-circumradius vertices of a case's convex polygons, scaled by their `r` columns:
/// the particle's (in place of `n`) and the partner's (in place of `partner_n`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Templates<'a> {
    /// The particle's vertices, if it is a convex polygon.
    pub particle: Option<&'a [[f64; 2]]>,
    /// The partner's vertices, if it is a convex polygon.
    pub partner: Option<&'a [[f64; 2]]>,
}

/// One case (scene and initial state) from a row of [`CASE_COLUMNS`]. Checks the columns'
/// own rules (codes, shape, angle, speed); the scene's rules are [`super::derived::Model::new`]'s, applied
/// when the case runs or by [`super::derived::check_case`].
pub fn scene_from_columns(
    row: &[f64; CASE_COLUMNS.len()],
    templates: Templates,
) -> Result<(Scene, Initial)> {
    scene_from_columns_with(row, templates, None)
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
    templates: Templates,
    shape: Option<Shape>,
) -> Result<(Scene, Initial)> {
    let vertices = templates.particle;
    let (own, partner) = row.split_at(CASE_COLUMNS.len() - PARTNER_COLUMNS);
    let [theta, omega, v, mu, gamma, gamma_t, e, rho, r, phi0, dtf, kn, cn, kt, n, integ, law, inertia, overlap, nu, plate_e, plate_nu, cor, tangential, tangential_history, body, max_steps, tol, error_estimate] =
        own.try_into().expect("the scene's own columns");
    let (partner, partner_init) =
        partner_from_columns(partner.try_into().expect("8 columns"), templates.partner)?;
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
        tangential_history: TangentialHistory::ALL
            [choice("tangential_history", tangential_history)?],
        max_steps: step_budget(max_steps)?,
        tol,
        error_estimate: flag("error_estimate", error_estimate)?,
        partner,
    };
    let init = Initial::from_angle(v, theta, omega, phi0);
    Ok((scene, init.with_partner(partner_init.0, partner_init.1)))
}

/// The partner from its columns, and its spin and orientation (degrees): `None` for the plate,
/// whose columns must then be unset (a spin or shape given without a partner is a mistake).
fn partner_from_columns(
    cols: [f64; PARTNER_COLUMNS],
    vertices: Option<&[[f64; 2]]>,
) -> Result<(Option<Partner>, (f64, f64))> {
    let [body, n, r, phi0, rho, e, nu, omega] = cols;
    finite("partner_omega_in", omega)?;
    let body = choice("partner_body", body)?;
    ensure_param!(
        vertices.is_none() || body == 1,
        "partner",
        "ConvexPolygon",
        "a partner body \"prism\" for the partner's vertices"
    );
    if body == 0 {
        for (name, x) in [("partner_n", n), ("partner_r", r), ("partner_rho", rho)]
            .into_iter()
            .chain([
                ("partner_E", e),
                ("partner_nu", nu),
                ("partner_phi0_deg", phi0),
            ])
        {
            ensure_param!(
                x.is_nan(),
                name,
                x,
                "unset (NaN) without a partner (partner_body \"plate\")"
            );
        }
        ensure_param!(
            omega == 0.0,
            "partner_omega_in",
            omega,
            "0 without a partner (partner_body \"plate\")"
        );
        return Ok((None, (0.0, 0.0)));
    }
    let phi0 = optional(phi0).unwrap_or(0.0);
    check_orientation(phi0).map_err(|_| Error::invalid("partner_phi0_deg", phi0, "finite"))?;
    let shape = if body == 2 {
        ensure_param!(
            n == 0.0 || n.is_nan(),
            "partner_n",
            n,
            "0 for a sphere partner"
        );
        Shape::sphere(r).map_err(|e| e.renamed("partner_r"))?
    } else {
        shape_from_columns(optional(n).unwrap_or(0.0), r, vertices).map_err(|e| match e {
            Error::InvalidParameter { ref name, .. } if name == "n" => e.renamed("partner_n"),
            e => e.renamed("partner_r"),
        })?
    };
    let partner = Partner {
        shape,
        rho: optional(rho),
        e_modulus: optional(e),
        nu: optional(nu),
    };
    Ok((Some(partner), (omega, phi0)))
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
