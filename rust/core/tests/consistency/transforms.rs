//! The transformations the consistency matrix checks an impact against (mirror image, ten
//! times the size), the records' comparison and the tolerance they are held to.

use super::common::bounds::corners_in_pair;
use restitution_core::{Initial, Integrator, NormalLaw, Partner, Record, Scene, Shape};

/// The mirror image of a shape about the vertical through its centroid (vertices x -> -x,
/// order reversed to stay counter-clockwise).
pub(crate) fn mirrored(shape: &Shape) -> Shape {
    match shape {
        Shape::Disc { .. } | Shape::Sphere { .. } => shape.clone(),
        Shape::Polygon(p) => {
            let v: Vec<[f64; 2]> = p.vertices().iter().rev().map(|q| [-q.x, q.y]).collect();
            Shape::convex_polygon(&v).unwrap()
        }
    }
}

pub(crate) fn mirror_init(init: &Initial) -> Initial {
    Initial {
        vx: -init.vx,
        omega: -init.omega,
        phi0: -init.phi0,
        partner_omega: -init.partner_omega,
        partner_phi0: -init.partner_phi0,
        ..*init
    }
}

/// The integrator's error in a velocity, relative to the impact speed, that the symmetry and
/// scaling checks allow (round-off amplified through the contact: the fixed steps repeat the
/// same operations, the reference converges to its tolerance).
pub(crate) fn symmetry_tol(scene: &Scene) -> f64 {
    match scene.integrator {
        // Its error control ends near-simultaneous events at slightly different points in a
        // mirrored, turned or rescaled scene (measured: up to 2.3e-7 on a turned pentagon
        // through parry; 5e-8 for a rescaled disc at mu 1e3).
        // A pair with corners: its corners' crossings and the contact's turns are not
        // located, and at mu 1e3 the stick/slip switches among them land apart (measured up
        // to 3.4e-6 over the long matrix at 10^5, a convex 7-gon on the big disc, mirrored;
        // twins within 1e-6. Before short chords took their exact normal, 1.05e-4).
        Integrator::Reference | Integrator::Adaptive if corners_in_pair(scene) => 5e-6,
        Integrator::Reference | Integrator::Adaptive => 1e-6,
        // The same operations on differently rounded corners: round-off, amplified by the
        // stick/slip switches of frictional polygons (measured: up to 1.7e-8) and by the
        // re-contacts of a tumbling triangle (9.5e-7 after a 120 deg turn, linear law), far
        // below the discretisation error at the default step (~1e-4 in e_T).
        _ => 2e-6,
    }
}

/// Records equal to `tol` in the velocities (relative to v, omega to v / r), with `sign`
/// applied to vx and omega (mirror: -1).
pub(crate) fn same_record(
    a: &Record,
    b: &Record,
    sign: f64,
    v: f64,
    r: f64,
    tol: f64,
) -> Option<String> {
    let d = [
        (a.vy_out - b.vy_out) / v,
        (a.vx_out - sign * b.vx_out) / v,
        (a.omega_out - sign * b.omega_out) * r / v,
    ];
    let worst = d.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    (worst > tol || worst.is_nan()).then(|| format!("differ by {worst:e}"))
}

/// The dimensionless outputs of an impact.
pub(crate) fn groups(rec: &Record, v: f64, r: f64) -> [f64; 4] {
    [
        rec.e_n,
        rec.e_t.unwrap_or(0.0),
        rec.e_kin,
        rec.omega_out * r / v,
    ]
}

/// `shape` ten times as large.
pub(crate) fn ten_times(shape: &Shape) -> Shape {
    match shape {
        Shape::Disc { r } => Shape::Disc { r: 10.0 * r },
        Shape::Sphere { r } => Shape::Sphere { r: 10.0 * r },
        Shape::Polygon(p) => {
            let v: Vec<[f64; 2]> = p
                .vertices()
                .iter()
                .map(|q| [10.0 * q.x, 10.0 * q.y])
                .collect();
            Shape::convex_polygon(&v).unwrap()
        }
    }
}

/// The same scene with r x 10, rho x 10 and E x 1000 (so v x 10 keeps E / (rho v^2)), and
/// the linear law's kn and cn scaled alike (kn / E and cn / sqrt(kn m) fixed).
pub(crate) fn scaled(scene: &Scene) -> Scene {
    let shape = ten_times(&scene.shape);
    let mass = 10.0 * scene.rho * shape.area();
    // A stiffness scales like E times a length per unit depth (Pa), like E times an area for a
    // sphere (N/m): kn / (E r) is fixed for a sphere, kn / E for a 2D body.
    let k_scale = if scene.shape.is_sphere() { 1e4 } else { 1e3 };
    let normal_law = match scene.normal_law {
        NormalLaw::Linear { kn, cn } => {
            let zeta = cn / (2.0 * (kn * scene.rho * scene.shape.area()).sqrt());
            scene.normal_law.with_scale(k_scale * kn, zeta, mass)
        }
        law => law,
    };
    let partner = scene.partner.clone().map(|p| Partner {
        shape: ten_times(&p.shape),
        rho: p.rho.map(|x| 10.0 * x),
        e_modulus: p.e_modulus.map(|x| 1000.0 * x),
        nu: p.nu,
    });
    Scene {
        shape,
        rho: 10.0 * scene.rho,
        e_modulus: 1000.0 * scene.e_modulus,
        normal_law,
        kt: scene.kt.map(|k| k_scale * k),
        partner,
        ..scene.clone()
    }
}
