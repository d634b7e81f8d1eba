//! Grazing impacts whose overlap double precision cannot resolve are refused, not integrated
//! on round-off; the finest grazing angles that resolve end with finite records.

use restitution_core::{simulate, Error, Initial, Scene};

fn paper_disc() -> Scene {
    Scene::default()
}

#[test]
fn grazing_impacts_below_depth_resolution_are_refused_naming_v() {
    for theta in [1e-8, 1e-10, 1e-20] {
        let init = Initial::from_angle(0.0357, theta, 0.0, 0.0);
        match simulate(&paper_disc(), &init) {
            Err(Error::InvalidParameter { name, .. }) => assert_eq!(name, "v", "theta {theta}"),
            other => panic!("theta {theta}: expected an error naming v, got {other:?}"),
        }
    }
}

#[test]
fn finest_resolved_grazing_impacts_end_with_finite_physical_records() {
    // theta -> 0: the normal speed vanishes, so e_N -> 1 (the area law's damping ~ sqrt(depth)
    // weakens); the record stays finite and the audit closes.
    let mut last_e_n = 0.0;
    for theta in [1e-2, 1e-4, 1e-6, 1e-7] {
        let rec = simulate(&paper_disc(), &Initial::from_angle(0.0357, theta, 0.0, 0.0)).unwrap();
        assert!(rec.separated && !rec.timed_out, "theta {theta}");
        assert!(
            rec.contact_time.is_finite() && rec.contact_time > 0.0,
            "theta {theta}"
        );
        assert!(
            rec.e_n > last_e_n && rec.e_n < 1.0,
            "theta {theta}: e_n {}",
            rec.e_n
        );
        assert!(
            rec.energy_residual.abs() < 1e-6,
            "theta {theta}: {}",
            rec.energy_residual
        );
        last_e_n = rec.e_n;
    }
}

#[test]
fn a_modulus_too_stiff_to_resolve_the_overlap_is_refused() {
    let scene = Scene {
        e_modulus: 1e30,
        ..paper_disc()
    };
    let err = simulate(&scene, &Initial::from_angle(0.0357, 45.0, 0.0, 0.0)).unwrap_err();
    assert!(err.to_string().contains("lower E"), "{err}");
}
