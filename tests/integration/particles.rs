//! Robust planning's perturbed worlds carried along the search (`planner::ParticleWorlds`
//! through the bridge's `Problem` and its parts): the planar hand pushes a box straight toward the goal disc
//! (tests/data/hand_push_straight.yaml: hand front at x 0.42, box 0.1 m wide centred at
//! 0.6, disc of radius 0.1 at 0.85, goal margin 0.06).

use pushplan::bridge::{Goal as GoalRegion, Problem, Propagator, ValidityChecker};
use pushplan::scene::Goal;
use pushplan::Scene;

const SCENE: &str = "tests/data/hand_push_straight.yaml";
/// Straight ahead at 0.2 m/s (vx, vy, omega, then the null-space sample of the hand's
/// three joints, which has none).
const PUSH: [f64; 6] = [0.2, 0.0, 0.0, 0.0, 0.0, 0.0];

/// A problem's parts, as the OMPL classes hold them.
struct Parts {
    problem: Problem,
    propagator: Box<Propagator>,
    validity: Box<ValidityChecker>,
    goal: Box<GoalRegion>,
}

fn parts(scene: Scene, worlds: usize) -> Parts {
    let mut problem = Problem::new(scene);
    problem.set_particles(worlds, 7).unwrap();
    Parts {
        propagator: Propagator::new(&problem),
        validity: ValidityChecker::new(&problem),
        goal: GoalRegion::new(&problem),
        problem,
    }
}

fn model(worlds: usize) -> (Scene, Parts) {
    let scene = Scene::load(SCENE).unwrap();
    (scene.clone(), parts(scene, worlds))
}

/// Holds `PUSH` step by step (as OMPL does) for up to `steps` steps; the last valid state
/// and worlds, the steps taken, and the nominal state the first invalid step tried.
fn push(
    propagator: &mut Propagator,
    mut x: Vec<f64>,
    mut p: Vec<f64>,
    steps: usize,
) -> (Vec<f64>, Vec<f64>, usize, Option<Vec<f64>>) {
    for taken in 0..steps {
        let (mut x2, mut p2) = (vec![0.0; x.len()], vec![0.0; p.len()]);
        if !propagator
            .propagate(&x, &p, &PUSH, 1, &mut x2, &mut p2)
            .unwrap()
        {
            return (x, p, taken, Some(x2));
        }
        (x, p) = (x2, p2);
    }
    (x, p, steps, None)
}

#[test]
fn perturbed_worlds_start_near_the_scene_and_follow_the_same_push() {
    let (scene, mut model) = model(4);
    let start = scene.start.to_flat();
    let worlds = model.problem.start_particles();
    assert_eq!(worlds.len(), 4 * 3);
    // Each world's box starts within the noise's ±5 mm per axis and ±0.05 rad, not exactly
    // where the scene puts it.
    for w in worlds.chunks(3) {
        assert!((w[0] - start[3]).abs() <= 0.005 && (w[1] - start[4]).abs() <= 0.005);
        assert!((w[2] - start[5]).abs() <= 0.05);
        assert_ne!(w, &start[3..6]);
    }
    // 1.4 s: 0.65 s to reach the box, then 0.15 m of pushing. Flat on through the middle,
    // the box goes straight along in every world, a few millimetres apart.
    let (x, p, taken, _) = push(&mut model.propagator, start.clone(), worlds.clone(), 140);
    assert_eq!(taken, 140);
    let nominal = [x[3], x[4]];
    assert!(
        nominal[0] > 0.7,
        "the nominal box was pushed to {nominal:?}"
    );
    for (w, before) in p.chunks(3).zip(worlds.chunks(3)) {
        assert!(w[0] - before[0] > 0.1, "a world's box was pushed too");
        assert!((w[0] - nominal[0]).hypot(w[1] - nominal[1]) < 0.01);
    }
    // The goal counts the worst world (whole disc) beside the nominal box (disc less the
    // margin): here the nominal one, 0.1 - 0.06 m from the centre, decides.
    let ((cx, cy), r, margin) = ((0.85, 0.0), 0.1, 0.06);
    let nominal_distance = (nominal[0] - cx).hypot(nominal[1] - cy) - (r - margin);
    let worst_world = p
        .chunks(3)
        .map(|w| (w[0] - cx).hypot(w[1] - cy) - r)
        .fold(f64::NEG_INFINITY, f64::max);
    let distance = model.goal.distance(&x, &p).unwrap();
    assert_eq!(distance, nominal_distance.max(worst_world));
    // One world's box moved 15 cm aside, off the disc: the goal is as far as it is.
    let mut aside = p.clone();
    aside[1] += 0.15;
    let expected = (aside[0] - cx).hypot(aside[1] - cy) - r;
    assert!((model.goal.distance(&x, &aside).unwrap() - expected).abs() < 1e-12);
    assert!(expected > 0.0);
}

#[test]
fn a_push_whose_goal_object_scatters_across_the_worlds_is_cut_at_the_margin() {
    // A wide goal (disc of 0.3 m, margin 0.15 m) and a second world whose box stands
    // 12 cm aside, out of the hand's way (the hand spans y in [-0.06, 0.06]): 0.12 m from
    // the nominal box, within the margin. Pushing the nominal box leaves that one behind;
    // once they are more than the margin apart, a nominal box inside the disc less the
    // margin no longer means that world's inside the disc, and the push is cut there.
    let mut scene = Scene::load(SCENE).unwrap();
    let Goal::ObjectInDisc { object, center, .. } = scene.goal else {
        unreachable!()
    };
    let margin = 0.15;
    scene.goal = Goal::ObjectInDisc {
        object,
        center,
        radius: 0.3,
        margin,
    };
    let mut model = parts(scene.clone(), 2);
    let start = scene.start.to_flat();
    let mut worlds = model.problem.start_particles();
    worlds[3..6].copy_from_slice(&[start[3], start[4] + 0.12, start[5]]);
    let (x, p, taken, attempted) = push(&mut model.propagator, start.clone(), worlds.clone(), 300);
    let attempted = attempted.expect("the push is cut");
    let apart = |x: &[f64]| (x[3] - worlds[3]).hypot(x[4] - worlds[4]);
    assert!(
        apart(&x) <= margin,
        "the last valid step is within the margin"
    );
    assert!(
        apart(&attempted) > margin,
        "the cut step is the first beyond it"
    );
    assert!(x[3] - start[3] > 0.08, "cut after about 9 cm of pushing");
    assert_eq!(&p[3..6], &worlds[3..6], "the world aside never moved");
    assert!(taken > 65, "the hand reached the box first ({taken} steps)");
    assert_eq!(
        model
            .propagator
            .search_stats()
            .stopped
            .get("goal object diverges (in a perturbed world)"),
        Some(&1)
    );
    // Without worlds the same push goes on.
    let mut nominal = parts(scene, 0);
    let (_, _, taken, _) = push(&mut nominal.propagator, start, Vec::new(), 150);
    assert_eq!(taken, 150);
}

#[test]
fn a_world_in_which_the_state_is_invalid_makes_it_invalid() {
    let (scene, model) = model(2);
    let start = scene.start.to_flat();
    let mut worlds = model.problem.start_particles();
    assert!(model.validity.is_valid(&start, &worlds).unwrap());
    // The first world's box off the table (x beyond the table's 1.03 m edge).
    worlds[0] = 1.2;
    assert!(!model.validity.is_valid(&start, &worlds).unwrap());
}

#[test]
fn worlds_of_the_wrong_size_or_in_the_static_problem_are_refused() {
    let (scene, mut model) = model(3);
    let start = scene.start.to_flat();
    let mut out = vec![0.0; start.len()];
    let err = model
        .propagator
        .propagate(&start, &[0.0; 3], &PUSH, 1, &mut out, &mut [0.0; 3])
        .unwrap_err();
    assert!(
        err.contains("perturbed worlds have 3 values, this search needs 9"),
        "{err}"
    );
    assert!(model.goal.distance(&start, &[]).is_err());
    model.problem.set_static_clutter(true);
    let err = model.problem.set_particles(3, 1).unwrap_err();
    assert!(err.contains("pushing problem only"), "{err}");
}
