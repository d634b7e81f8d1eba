//! Bounded work (issue 14): the slow impacts of the issue's table end, separated, within a
//! few of their own contacts' steps; a step budget ends an impact as timed out with its reason;
//! a cancellation token interrupts one impact and a sweep.

use restitution_core::{
    contact_steps, estimate_max_depth, run_cases, run_cases_cancellable, simulate,
    simulate_cancellable, simulate_with_trace_cancellable, Cancel, Case, Error, Initial,
    Integrator, Model, Scene, Shape, StopReason, BUDGET_CONTACTS, BUDGET_SLACK_STEPS,
    MAX_ADAPTIVE_ATTEMPTS,
};
use std::time::Duration;

#[path = "common/slow_rows.rs"]
mod slow_rows;
use slow_rows::ROWS;

fn row_scene(row: usize) -> (Scene, f64, f64) {
    let (n, theta, mu, gamma, e, v) = ROWS[row];
    let scene = Scene {
        shape: Shape::regular_polygon(0.01, n).unwrap(),
        mu,
        gamma,
        e_modulus: e,
        ..Scene::default()
    };
    (scene, theta, v)
}

#[test]
fn the_issues_slow_impacts_separate_within_a_few_contacts_steps() {
    // Before: rows 0, 1, 3, 4 and 6 ran for 1e7 to 1e9 steps at some orientations (> 30 s),
    // stepping the slow free flight of a polygon that the contact had set spinning. The
    // flight is now jumped over: every row separates within 3 N_c steps (measured: at most
    // 1.4 N_c, row 6 at phi0 = 0 with a re-contact).
    for row in 0..ROWS.len() {
        let (scene, theta, v) = row_scene(row);
        for phi0 in [0.0, 7.0, 20.0, 33.0, 50.0] {
            let init = Initial::from_angle(v, theta, 0.0, phi0);
            let rec = simulate(&scene, &init).unwrap();
            let model = Model::new(&scene).unwrap();
            let n_c = contact_steps(&model, &init, estimate_max_depth(&model, &init).unwrap());
            let what = format!("row {row} phi0 {phi0}: {} steps, N_c {n_c:.3e}", rec.steps);
            assert_eq!(rec.stop, StopReason::Separated, "{what}");
            assert!(rec.separated && !rec.timed_out, "{what}");
            assert!((rec.steps as f64) < 3.0 * n_c, "{what}");
            let budget = BUDGET_CONTACTS as f64 * n_c.ceil() + BUDGET_SLACK_STEPS as f64;
            assert_eq!(rec.step_budget, budget as u64, "{what}");
            let gain = rec.energy_out / rec.energy_in - 1.0;
            assert!(
                gain < 1e-6 && rec.energy_residual.abs() < 1e-3,
                "{what}: {gain:e}"
            );
        }
    }
}

#[test]
fn a_step_budget_ends_the_impact_as_timed_out() {
    let (scene, theta, v) = row_scene(4);
    let init = Initial::from_angle(v, theta, 0.0, 20.0);
    for max_steps in [1, 1000, 100_000] {
        let rec = simulate(
            &Scene {
                max_steps: Some(max_steps),
                ..scene.clone()
            },
            &init,
        )
        .unwrap();
        assert_eq!(rec.steps, max_steps);
        assert_eq!(rec.step_budget, max_steps);
        assert_eq!(rec.stop, StopReason::StepBudget);
        assert!(rec.timed_out && !rec.separated);
        assert!(rec.e_n.is_finite() && rec.energy_out <= rec.energy_in * (1.0 + 1e-9));
    }
    let refused = simulate(
        &Scene {
            max_steps: Some(0),
            ..scene
        },
        &init,
    );
    assert!(matches!(refused, Err(Error::InvalidParameter { name, .. }) if name == "max_steps"));
}

#[test]
fn stop_reasons_are_named_once() {
    let names: Vec<&str> = StopReason::ALL.iter().map(|s| s.name()).collect();
    assert_eq!(
        names,
        [
            "separated",
            "step_budget",
            "contact_time_budget",
            "non_finite"
        ]
    );
    for (i, s) in StopReason::ALL.iter().enumerate() {
        assert_eq!(s.code() as usize, i);
    }
    assert_eq!(StopReason::default(), StopReason::Separated);
}

/// An impact of ~3e7 steps (seconds): an over-damped creep at its own step bound, which
/// ends on its contact-time budget; only the token can end it early.
fn long_scene() -> (Scene, Initial) {
    let scene = Scene {
        gamma: 2000.0,
        ..Scene::default()
    };
    let scene = Scene {
        dt_factor: restitution_core::max_dt_factor(&scene).unwrap(),
        ..scene
    };
    (scene, Initial::from_angle(0.0357, 60.0, 0.0, 0.0))
}

#[test]
fn a_set_token_interrupts_every_entry_point() {
    let (scene, init) = long_scene();
    let cancel = Cancel::new();
    cancel.cancel();
    assert_eq!(
        simulate_cancellable(&scene, &init, &cancel),
        Err(Error::Interrupted)
    );
    assert_eq!(
        simulate_with_trace_cancellable(&scene, &init, &cancel).map(|_| ()),
        Err(Error::Interrupted)
    );
    let cases = vec![Case { scene, init }; 4];
    assert_eq!(
        run_cases_cancellable(&cases, 2, &cancel),
        Err((0, Error::Interrupted))
    );
    // A reset token lets a run finish.
    cancel.reset();
    let quick = Case {
        scene: Scene::default(),
        init: Initial::from_angle(0.0357, 45.0, 0.0, 0.0),
    };
    assert_eq!(
        run_cases_cancellable(std::slice::from_ref(&quick), 1, &cancel),
        run_cases(std::slice::from_ref(&quick), 1)
    );
}

#[test]
fn a_token_set_from_another_thread_stops_a_running_sweep() {
    let (scene, init) = long_scene();
    let cases = vec![Case { scene, init }; 8];
    let cancel = Cancel::new();
    let result = std::thread::scope(|s| {
        s.spawn(|| {
            std::thread::sleep(Duration::from_millis(200));
            cancel.cancel();
        });
        run_cases_cancellable(&cases, 2, &cancel)
    });
    assert!(matches!(result, Err((_, Error::Interrupted))), "{result:?}");
}

/// How often `stop_on_third_ask` has been asked.
static ASKED: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// A watch that asks to stop the third time it is asked.
fn stop_on_third_ask() -> bool {
    ASKED.fetch_add(1, std::sync::atomic::Ordering::Relaxed) >= 2
}

#[test]
fn a_watched_token_asks_its_watch_at_each_poll_and_stops_when_told() {
    // The long impact is in contact from its first step, one step at a time: polls at steps 0,
    // POLL_STEPS and 2 POLL_STEPS, the third of which is told to stop.
    let (scene, init) = long_scene();
    let cancel = Cancel::watched(stop_on_third_ask);
    assert_eq!(
        simulate_cancellable(&scene, &init, &cancel),
        Err(Error::Interrupted)
    );
    assert_eq!(ASKED.load(std::sync::atomic::Ordering::Relaxed), 3);
    assert!(cancel.is_cancelled());
    // A watch that never asks to stop leaves the record as it was, on either path.
    fn never() -> bool {
        false
    }
    for integrator in [Integrator::Gear5, Integrator::Adaptive] {
        let scene = Scene {
            integrator,
            ..Scene::default()
        };
        let init = Initial::from_angle(0.0357, 45.0, 0.0, 0.0);
        assert_eq!(
            simulate_cancellable(&scene, &init, &Cancel::watched(never)),
            simulate(&scene, &init)
        );
    }
}

/// A 4096-gon spinning at 10^4 deg/s dropped head-on at 1e-6 m/s on a soft plate rattles from
/// corner to corner (~900 000 steps resolved to the tolerance, 3 s, without a ceiling): on the
/// adaptive path its default budget is capped at `MAX_ADAPTIVE_ATTEMPTS`, where it ends timed
/// out with a finite record that gains no energy; `max_steps` lifts the cap.
#[test]
fn the_adaptive_paths_default_budget_has_a_ceiling_that_max_steps_lifts() {
    let scene = Scene {
        shape: Shape::regular_polygon(0.01, 4096).unwrap(),
        mu: 1e-6,
        gamma: 0.0,
        e_modulus: 1e3,
        integrator: Integrator::Adaptive,
        ..Scene::default()
    };
    let init = Initial::from_angle(1e-6, 90.0, -1e4_f64.to_radians(), 332.3);
    let model = Model::new(&scene).unwrap();
    let n_c = contact_steps(&model, &init, estimate_max_depth(&model, &init).unwrap());
    assert!(
        BUDGET_CONTACTS as f64 * n_c > MAX_ADAPTIVE_ATTEMPTS as f64,
        "N_c {n_c:e}"
    );
    let rec = simulate(&scene, &init).unwrap();
    assert_eq!(rec.stop, StopReason::StepBudget);
    assert_eq!(rec.step_budget, MAX_ADAPTIVE_ATTEMPTS);
    assert!(rec.timed_out && rec.steps <= MAX_ADAPTIVE_ATTEMPTS);
    assert!(rec.e_n.is_finite() && rec.energy_out.is_finite());
    assert!(rec.energy_out <= rec.energy_in * (1.0 + 1e-6));
    let lifted = Scene {
        max_steps: Some(MAX_ADAPTIVE_ATTEMPTS + 1000),
        ..scene.clone()
    };
    let rec = simulate(&lifted, &init).unwrap();
    assert_eq!(rec.step_budget, MAX_ADAPTIVE_ATTEMPTS + 1000);
    // Gear-5 keeps its uncapped budget: the cap is the adaptive path's.
    let gear5 = Model::new(&Scene {
        integrator: Integrator::Gear5,
        ..scene
    })
    .unwrap();
    let n_gear5 = contact_steps(&gear5, &init, estimate_max_depth(&gear5, &init).unwrap());
    assert_eq!(
        restitution_core::default_step_budget(&gear5, &init).unwrap(),
        (BUDGET_CONTACTS as f64 * n_gear5.ceil()) as u64 + BUDGET_SLACK_STEPS
    );
}

/// How often `count_asks` has been asked.
static PAIR_ASKS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

fn count_asks() -> bool {
    PAIR_ASKS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    false
}

/// A step of two fine polygons costs hundreds of the plate's (their intersection is linear in
/// their corners: two 1024-gons ~0.2 ms a fixed step), so polled every `POLL_STEPS` steps as
/// the plate is, Ctrl-C would wait most of a second: a pair polls about as often in time, here
/// at least every 64 fixed steps and every 4 adaptive ones (an attempt evaluates the law at
/// least 7 times; a plate-like poll every 4096 steps asks once in these impacts), and the record is
/// the one the unwatched call returns.
#[test]
fn fine_polygon_pairs_poll_their_token_as_often_in_time_as_the_plate() {
    let gon = Shape::regular_polygon(0.01, 512).unwrap();
    for (integrator, stride) in [(Integrator::Gear5, 64), (Integrator::Adaptive, 4)] {
        let scene = Scene {
            shape: gon.clone(),
            partner: Some(restitution_core::Partner::of(gon.clone())),
            integrator,
            mu: 0.5,
            ..Scene::default()
        };
        let init = Initial::from_angle(1.0, 30.0, 0.0, 0.0);
        PAIR_ASKS.store(0, std::sync::atomic::Ordering::Relaxed);
        let rec = simulate_cancellable(&scene, &init, &Cancel::watched(count_asks)).unwrap();
        let asks = PAIR_ASKS.load(std::sync::atomic::Ordering::Relaxed);
        assert!(
            asks >= rec.steps / stride && rec.steps >= 4 * stride,
            "{integrator:?}: {asks} polls in {} steps",
            rec.steps
        );
        assert_eq!(Ok(rec), simulate(&scene, &init));
    }
}
