use restitution_core::*;
#[test]
fn probe() {
    let shape = Shape::disc(0.01).unwrap();
    let scene = Scene {
        shape,
        gamma: 0.33299,
        mu: 0.7,
        gamma_t: 0.0,
        ..Scene::default()
    };
    let init = Initial::from_angle(0.0357, 54.0, 0.0, 0.0);
    let tight = simulate_reference(
        &scene,
        &init,
        &ReferenceOptions {
            tol: 1e-13,
            max_step_factor: Some(0.2),
        },
    )
    .unwrap();
    for lt in [1e-13, 0.5e-4, 0.75e-4, 1e-4] {
        let (rec, tr) = simulate_reference_with_trace(
            &scene,
            &init,
            &ReferenceOptions {
                tol: lt,
                max_step_factor: Some(if lt < 1e-12 { 0.2 } else { 5.0 }),
            },
        )
        .unwrap();
        println!(
            "local {lt:e}: dist {:.3e} steps {} slips {} est {:?}",
            rec.accuracy_distance(&tight, 0.01, 0.0357),
            rec.steps,
            rec.slip_events,
            rec.err_est
        );
        if std::env::var("TRACE").is_ok() {
            let mut last = String::new();
            for i in 0..tr.t.len() {
                let r = tr.f_t[i] / (0.7 * tr.f_n[i]);
                let st = if r.abs() > 0.999999 { "slip" } else { "stick" };
                if st != last || lt > 1e-12 {
                    println!("  t {:.6e} ratio {:.6} {st}", tr.t[i], r);
                    last = st.to_string();
                }
            }
        }
    }
}
