//! Whole-arm pushing through the full pipeline: projection, 3D contacts, planar physics.

use crate::common;

use common::{herb_scene, object, parked_goal, HAND_FAR, HAND_NEAR};
use pushplan_model::{EeAction, Propagator, Scene};

const BOX: &str = "{type: box, size: [0.1, 0.1, 0.14]}";

#[test]
fn a_flat_hand_pushing_a_box_through_its_centre_translates_it() {
    // Planar hand (a 0.04 x 0.12 box) centred on a 0.1 m box, pushing along +x.
    let scene = Scene::load("scenes/planar_hand_single_object.yaml").unwrap();
    let mut propagator = Propagator::new(&scene);
    let run = propagator.propagate(&scene.start, &EeAction::planar(0.2, 0.0, 0.0), 1.0);
    assert!(run.stopped_by.is_none(), "{:?}", run.stopped_by);
    // Gap 0.6 - 0.05 - (0.4 + 0.02) = 0.13 m; the hand travels 0.2 m; the box 0.07 m.
    let pose = run.state.objects[0];
    assert!(
        (pose.x - 0.67).abs() < 1e-6 && pose.y.abs() < 1e-9 && pose.theta.abs() < 1e-9,
        "{pose:?}"
    );
}

#[test]
fn the_hand_pushes_a_box_along_the_analytic_steady_push() {
    // The WAM's hand, centred on a box ahead of it, pushes at 0.1 m/s along +x.
    let objects = parked_goal() + &object("box", BOX, [0.72, 0.15, 0.0]);
    let scene = herb_scene(HAND_NEAR, &objects, "").unwrap();
    let mut propagator = Propagator::new(&scene);
    let dt = scene.planner.step;
    let v = 0.1;
    let action = EeAction::planar(v, 0.0, 0.0);
    let mut state = scene.start.clone();
    let mut contact_at: Option<(usize, f64)> = None;
    for step in 0..250 {
        let run = propagator.propagate_steps(&state, &action, 1);
        assert!(
            run.stopped_by.is_none(),
            "step {step}: {:?}",
            run.stopped_by
        );
        state = run.state;
        let pose = state.objects[1];
        if contact_at.is_none() && !run.contacts[0].is_empty() {
            contact_at = Some((step, pose.x));
        }
        if let Some((first, x0)) = contact_at {
            // Steady centred push: the box moves with the hand, without turning.
            let expected = x0 + v * dt * (step - first) as f64;
            assert!(
                (pose.x - expected).abs() < 3e-3,
                "step {step}: x {} vs {expected}",
                pose.x
            );
            assert!(
                (pose.y - 0.15).abs() < 3e-3 && pose.theta.abs() < 0.01,
                "step {step}: {pose:?}"
            );
        }
    }
    let (first, _) = contact_at.expect("the hand reached the box");
    assert!(first < 150, "contact came late, at step {first}");
    assert!(
        state.objects[1].x > 0.78,
        "the box was pushed {:?}",
        state.objects[1]
    );
}

#[test]
fn a_forearm_sweep_moves_two_objects_in_one_propagation() {
    // The arm reaches out; two tall cylinders stand beside the sloping forearm. They
    // stand on a slippery patch (mu_g 0.08): with 0.4 the forearm's push, 0.2-0.3 m up,
    // would tip them (R / mu_g = 0.0875 m; 0.4375 m here, 0.306 m with the default
    // tipping margin).
    let tall = |name: &str, x: f64, y: f64| {
        object(
            name,
            "{type: cylinder, radius: 0.035, height: 0.35}",
            [x, y, 0.0],
        )
        .replace("mu_g: 0.4", "mu_g: 0.08")
    };
    let objects = parked_goal() + &tall("a", 0.60, 0.07) + &tall("b", 0.69, 0.06);
    let scene = herb_scene(HAND_FAR, &objects, "").unwrap();
    let forearm = scene.robot.chain.link_index("wam_link5").unwrap();
    let mut propagator = Propagator::new(&scene);
    let run = propagator.propagate(&scene.start, &EeAction::planar(0.0, -0.2, 0.0), 1.0);
    assert!(run.stopped_by.is_none(), "{:?}", run.stopped_by);
    for object in [1, 2] {
        let moved = (run.state.objects[object].translation()
            - scene.start.objects[object].translation())
        .norm();
        assert!(moved > 0.05, "object {object} moved {moved} m");
        assert!(
            run.contacts
                .iter()
                .flatten()
                .any(|p| p.link == forearm && p.object == object),
            "the forearm never pushed object {object}"
        );
    }
    // Both in contact with the forearm at the same time at some step.
    assert!(run.contacts.iter().any(|step| [1, 2]
        .iter()
        .all(|o| step.iter().any(|p| p.link == forearm && p.object == *o))));
    // The hand never touched them.
    let hand = scene.robot.ee_link;
    assert!(run.contacts.iter().flatten().all(|p| p.link != hand));
}

#[test]
fn halving_the_step_barely_changes_the_outcome() {
    // A push that turns the box: the hand yaws while it pushes.
    let objects = parked_goal() + &object("box", BOX, [0.72, 0.15, 0.0]);
    let scene = herb_scene(HAND_NEAR, &objects, "").unwrap();
    let action = EeAction::planar(0.15, 0.0, 0.3);
    let run = |dt: f64| {
        let mut p = Propagator::with_step(&scene, dt);
        // 1.5 s: the box stays wholly on the table.
        let r = p.propagate(&scene.start, &action, 1.5);
        assert!(r.stopped_by.is_none(), "dt {dt}: {:?}", r.stopped_by);
        r.state.objects[1]
    };
    let (coarse, fine) = (run(0.01), run(0.005));
    assert!(
        coarse.theta.abs() > 0.05,
        "the push should turn the box: {coarse:?}"
    );
    let dx = (coarse.translation() - fine.translation()).norm();
    let dtheta = (coarse.theta - fine.theta).abs();
    assert!(
        dx < 5e-3 && dtheta < 0.05,
        "dt 0.01 {coarse:?} vs dt 0.005 {fine:?}"
    );
}

#[test]
fn propagation_is_deterministic_and_resumable() {
    let objects = parked_goal() + &object("box", BOX, [0.72, 0.19, 0.0]);
    let scene = herb_scene(HAND_NEAR, &objects, "").unwrap();
    let action = EeAction {
        velocity: [0.15, -0.05, 0.2],
        nullspace: nalgebra::DVector::from_column_slice(&[0.1, -0.2, 0.3, 0.0, 0.1, -0.1, 0.2]),
    };
    let mut p = Propagator::new(&scene);
    let a = p.propagate_steps(&scene.start, &action, 150);
    let b = Propagator::new(&scene).propagate_steps(&scene.start, &action, 150);
    assert_eq!(a, b);
    assert!(
        a.contacts.iter().any(|s| !s.is_empty()),
        "the run should push the box"
    );
    // Stopping half way and resuming from the stored state gives the same bits: OMPL
    // re-propagates from stored states.
    let half = p.propagate_steps(&scene.start, &action, 75);
    let rest = p.propagate_steps(&half.state, &action, 75);
    assert_eq!(rest.state, a.state);
    assert_eq!([half.contacts, rest.contacts].concat(), a.contacts);
}

#[test]
fn objects_stop_when_the_push_stops() {
    let objects = parked_goal() + &object("box", BOX, [0.72, 0.15, 0.0]);
    let scene = herb_scene(HAND_NEAR, &objects, "").unwrap();
    let mut p = Propagator::new(&scene);
    let pushed = p.propagate(&scene.start, &EeAction::planar(0.2, 0.0, 0.0), 1.0);
    assert!(pushed.contacts.last().is_some_and(|s| !s.is_empty()));
    // Hold still, then pull back: the box stays where it was left.
    for action in [
        EeAction::planar(0.0, 0.0, 0.0),
        EeAction::planar(-0.2, 0.0, 0.0),
    ] {
        let after = p.propagate(&pushed.state, &action, 0.5);
        assert!(after.stopped_by.is_none());
        assert_eq!(after.state.objects, pushed.state.objects);
    }
}
