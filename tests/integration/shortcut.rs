//! Shortcutting (Sec. IV), path metrics and the executable trajectory.

use pushplan::planning::path::{simulate, PathControl};
use pushplan::planning::plan_file::PlanFile;
use pushplan::planning::shortcut::{shortcut, ShortcutSettings};
use pushplan::{Propagator, Scene};
use std::path::Path;

const SCENE: &str = "scenes/herb_fig1_clutter.yaml";

use crate::common;

/// The PC RRT plan of the default scene for seed 2.
fn found_plan() -> (Scene, Vec<PathControl>) {
    common::default_scene_plan(2)
}

#[test]
fn shortcutting_shortens_the_manipulator_path_and_keeps_the_plan_valid() {
    let (scene, controls) = found_plan();
    let settings = ShortcutSettings::from_seconds(1.0, 2);
    let mut propagator = Propagator::new(&scene);
    let outcome = shortcut(&mut propagator, &scene.start, &controls, &settings);
    assert!(outcome.accepted > 0 && outcome.attempts >= outcome.accepted);
    assert!(
        outcome.after.joint_length < outcome.before.joint_length,
        "{:?} -> {:?}",
        outcome.before,
        outcome.after
    );

    // The shortcut plan simulates validly to the goal, and its measured length is the one reported.
    let path = simulate(&mut propagator, &scene.start, &outcome.controls, false);
    assert!(path.valid() && scene.goal.is_satisfied(path.final_state()));
    assert_eq!(path.metrics, outcome.after);

    // Deterministic under the seed (the budget counts work, not wall-clock time).
    let again = shortcut(
        &mut Propagator::new(&scene),
        &scene.start,
        &controls,
        &settings,
    );
    assert_eq!(again, outcome);

    // The plan file records both metrics and passes its check.
    let plan_settings = common::plan_settings("pcrrt", 2, 1.0);
    let plan = PlanFile::build(
        SCENE,
        scene.clone(),
        &plan_settings,
        &outcome.controls,
        Some(outcome.before),
    )
    .unwrap();
    assert_eq!(plan.metrics.before_shortcut, outcome.before);
    assert_eq!(plan.metrics.after_shortcut, outcome.after);
    assert!(plan.check(Path::new("plan.json")).unwrap().passed());
}

#[test]
fn shortcutting_stops_at_its_deadline_and_before_it_is_unchanged() {
    use std::time::{Duration, Instant};
    let (scene, controls) = found_plan();
    let budget = ShortcutSettings::from_seconds(0.2, 2);
    let run = |settings: &ShortcutSettings| {
        shortcut(
            &mut Propagator::new(&scene),
            &scene.start,
            &controls,
            settings,
        )
    };
    // A deadline already passed: the plan's time limit is used up.
    let passed = run(&ShortcutSettings {
        deadline: Some(Instant::now()),
        ..budget
    });
    assert!(passed.stopped_at_deadline && passed.attempts == 0);
    assert_eq!(passed.controls, controls);
    // A deadline the budget runs out before: the same as none, bit for bit.
    let far = run(&ShortcutSettings {
        deadline: Some(Instant::now() + Duration::from_secs(3600)),
        ..budget
    });
    let unlimited = run(&budget);
    assert!(!far.stopped_at_deadline && far.accepted > 0);
    assert_eq!(far, unlimited);
}

#[test]
fn a_zero_budget_changes_nothing() {
    let (scene, controls) = found_plan();
    let outcome = shortcut(
        &mut Propagator::new(&scene),
        &scene.start,
        &controls,
        &ShortcutSettings::from_seconds(0.0, 1),
    );
    assert_eq!(outcome.controls, controls);
    assert_eq!((outcome.attempts, outcome.before), (0, outcome.after));
}

#[test]
fn the_trajectory_respects_velocity_acceleration_and_object_speed_limits_and_follows_the_plan() {
    let (scene, controls) = found_plan();
    let settings = common::plan_settings("pcrrt", 2, 0.0);
    let plan = PlanFile::build(SCENE, scene.clone(), &settings, &controls, None).unwrap();
    let t = &plan.trajectory;
    assert_eq!(t.rate, 50.0);
    assert!(t.times.len() > 10 && t.times.len() == t.q.len() && t.q.len() == t.objects.len());
    // Fixed rate, except the last sample, which is the end.
    for w in t.times[..t.times.len() - 1].windows(2) {
        assert!((w[1] - w[0] - 0.02).abs() < 1e-9);
    }
    // No joint faster than its URDF limit.
    let limits: Vec<f64> = (0..scene.robot.dof())
        .map(|i| scene.robot.chain.dof_joint(i).max_velocity)
        .collect();
    let mut fastest = 0.0f64;
    for k in 1..t.q.len() {
        let dt = t.times[k] - t.times[k - 1];
        for (i, limit) in limits.iter().enumerate() {
            let ratio = (t.q[k][i] - t.q[k - 1][i]).abs() / dt / limit;
            fastest = fastest.max(ratio);
        }
    }
    assert!(
        fastest <= 1.0 + 1e-9,
        "a joint reaches {fastest} times its limit"
    );
    assert!(
        fastest > 0.5,
        "the time scaling should use the limits ({fastest})"
    );
    // Joint accelerations by second differences at 50 Hz (at rest before and after), and
    // the objects' speeds, within the scene's trajectory limits (5 % for resampling).
    let a_max = scene.trajectory.max_joint_acceleration;
    let rest = |k: isize| -> usize { k.clamp(0, t.q.len() as isize - 1) as usize };
    let mut hardest = 0.0f64;
    for k in 0..t.q.len() as isize {
        let (a, b, c) = (rest(k - 1), rest(k), rest(k + 1));
        for i in 0..limits.len() {
            let acceleration = (t.q[c][i] - 2.0 * t.q[b][i] + t.q[a][i]) / (0.02 * 0.02);
            hardest = hardest.max(acceleration.abs() / a_max);
        }
    }
    assert!(
        hardest <= 1.05,
        "a joint accelerates at {hardest} times the limit"
    );
    assert!(
        hardest > 0.3,
        "the time scaling should use the acceleration limit ({hardest})"
    );
    let mut fastest_object = 0.0f64;
    for k in 1..t.objects.len() - 1 {
        for (a, b) in t.objects[k - 1].iter().zip(&t.objects[k]) {
            fastest_object = fastest_object.max((b[0] - a[0]).hypot(b[1] - a[1]) / 0.02);
        }
    }
    assert!(
        fastest_object <= scene.trajectory.max_object_speed * (1.0 + 1e-9),
        "an object moves at {fastest_object} m/s"
    );
    // It takes at least as long as the plan, and starts and ends at the plan's states.
    assert!(*t.times.last().unwrap() >= plan.metrics.after_shortcut.duration - 1e-9);
    assert_eq!(t.q[0], plan.start.q);
    assert_eq!(t.objects[0], plan.start.objects);
    let end = &plan.controls.last().unwrap().state;
    assert!(t
        .q
        .last()
        .unwrap()
        .iter()
        .zip(&end.q)
        .all(|(a, b)| (a - b).abs() < 1e-12));
    assert!(t
        .objects
        .last()
        .unwrap()
        .iter()
        .zip(&end.objects)
        .all(|(a, b)| (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12)));
}

#[test]
fn shortcutting_toward_robustness_keeps_every_world_it_reaches_and_holds_up_elsewhere() {
    use pushplan::planning::robustness::{reaches, PerturbedWorld};
    use pushplan::planning::shortcut::{shortcut_by, Criterion};
    use pushplan::planning::{finish, FinishSettings, RobustRequirement};
    let (scene, controls) = found_plan();
    let requirement = RobustRequirement {
        trials: 20,
        rate: 0.9,
    };
    let reached_in = |worlds: &mut [PerturbedWorld], controls: &[PathControl]| {
        let mut reached = 0;
        for w in worlds.iter_mut() {
            reached += usize::from(reaches(&scene.goal, &w.run(controls)));
        }
        reached
    };
    let on_threads = |threads| ShortcutSettings {
        threads,
        ..ShortcutSettings::from_seconds(3.0, 1)
    };
    let run_on = |threads, criterion: &mut Criterion| {
        let mut propagator = Propagator::new(&scene);
        shortcut_by(
            &mut propagator,
            &scene.start,
            &controls,
            &on_threads(threads),
            criterion,
        )
    };
    let run = |criterion: &mut Criterion| run_on(1, criterion);

    // Shortcutting toward robustness keeps the plan valid and never loses a world it
    // reaches the goal in; the same seed gives the same path.
    let mut worlds = requirement.shortcut_worlds(&scene, 1);
    assert_eq!(worlds.len(), 20);
    let reached_before = reached_in(&mut worlds, &controls);
    let mut criterion = Criterion::MoreRobust(worlds);
    let robust = run(&mut criterion);
    let Criterion::MoreRobust(mut worlds) = criterion else {
        unreachable!()
    };
    let path = simulate(
        &mut Propagator::new(&scene),
        &scene.start,
        &robust.controls,
        false,
    );
    assert!(path.valid() && scene.goal.is_satisfied(path.final_state()));
    let reached_after = reached_in(&mut worlds, &robust.controls);
    assert!(
        robust.accepted > 0 && reached_after >= reached_before,
        "{reached_before} -> {reached_after}"
    );
    let again = run(&mut Criterion::MoreRobust(
        requirement.shortcut_worlds(&scene, 1),
    ));
    assert_eq!(again, robust);
    // The worlds re-simulated on three threads at once (rounds of three and a last of
    // two): the same path, attempts and work, bit for bit.
    let on_three = run_on(
        3,
        &mut Criterion::MoreRobust(requirement.shortcut_worlds(&scene, 1)),
    );
    assert_eq!(on_three, robust);

    // In worlds it was not fitted to (the requirement's own), the final robust finishing
    // (shortening, then toward robustness) reaches the goal in more of them than the path
    // as found, and in about as many as shortening alone; the whole budget toward
    // robustness (a solution not robust enough yet) in clearly more: means over four
    // finishing seeds (this plan, seed 2 with the goal margin of 0.06 m: 0.64 against 0.20
    // as found and 0.61 shortened alone, 0.78 only toward robustness; seed 5's plan with the
    // margin of 0.03 m: 0.65, 0.25 and 0.68).
    let states = simulate(&mut Propagator::new(&scene), &scene.start, &controls, false).states;
    let rate = |controls: &[PathControl]| requirement.success_rate(&scene, controls, 1, None).rate;
    let finished_rate = |seed, robust, only_toward_robustness| {
        let settings = FinishSettings {
            shortcut: 3.0,
            seed,
            robust,
            only_toward_robustness,
            unseen_trials: 0,
            found_rate: None,
            deadline: None,
            progress: None,
            threads: 1,
        };
        rate(
            &finish(&scene, &controls, &states, true, &settings)
                .unwrap()
                .controls,
        )
    };
    let seeds = [1, 2, 3, 4];
    let mean = |f: &dyn Fn(u64) -> f64| seeds.map(f).iter().sum::<f64>() / seeds.len() as f64;
    let found = rate(&controls);
    let shortened = mean(&|seed| finished_rate(seed, None, false));
    let toward_robust = mean(&|seed| finished_rate(seed, Some(requirement), false));
    let only_toward_robust = mean(&|seed| finished_rate(seed, Some(requirement), true));
    // One world in 20 is 0.05.
    assert!(
        toward_robust >= found + 0.15
            && toward_robust >= shortened - 0.05
            && only_toward_robust >= toward_robust + 0.1,
        "found {found}, shortened {shortened}, toward robustness {toward_robust}, \
         only toward robustness {only_toward_robust}"
    );
}

#[test]
fn toward_robustness_a_push_that_ends_against_a_neighbour_is_stopped_earlier() {
    use pushplan::planning::robustness::{reaches, PerturbedWorld};
    use pushplan::planning::shortcut::{shortcut_by, Criterion};
    use pushplan::planning::RobustRequirement;
    use pushplan::EeAction;
    // A thin hand pushes a box along +x toward a second box that stands 1 mm in front of
    // a fixed block, with no clearance required; the one control pushes it as far as it
    // can go, up to the neighbour (the goal disc is reached all along). In perturbed
    // worlds the neighbour stands up to 5 mm further back: the box pushes it into the
    // block in some. No shortcut exists for one control; a nudge stops the push earlier.
    let yaml = "robot:
  type: planar_hand
  shape: {type: box, size: [0.04, 0.12, 0.01]}
  start: [0.4, 0.0, 0.0]
  height: 0.03
table: {height: 0.76, x: [0.27, 1.03], y: [-0.6, 0.6]}
objects:
  - {name: pushed, shape: {type: box, size: [0.1, 0.1, 0.1]}, pose: [0.5, 0.0, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}
  - {name: neighbour, shape: {type: box, size: [0.1, 0.1, 0.1]}, pose: [0.75, 0.0, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}
obstacles:
  - {name: block, shape: {type: box, size: [0.1, 0.1, 0.1]}, pose: {xyz: [0.851, 0.0, 0.81]}}
goal: {object: pushed, center: [0.62, 0.0], radius: 0.1, margin: 0.0}
physics: {object_clearance: 0.0}
";
    let scene = Scene::from_yaml(yaml, Path::new("scenes/nudge-test.yaml")).unwrap();
    let push = |steps| PathControl {
        action: EeAction::planar(0.1, 0.0, 0.0),
        steps,
    };
    let mut propagator = Propagator::new(&scene);
    let reaches_goal = |p: &mut Propagator, steps| {
        let path = simulate(p, &scene.start, &[push(steps)], false);
        path.valid() && scene.goal.is_satisfied(path.final_state())
    };
    let steps = (1..500)
        .take_while(|&n| n < 100 || reaches_goal(&mut propagator, n))
        .last()
        .unwrap();
    assert!(steps > 100 && reaches_goal(&mut propagator, steps));
    let controls = vec![push(steps)];
    let count = |worlds: &mut [PerturbedWorld], c: &[PathControl]| {
        worlds
            .iter_mut()
            .map(|w| reaches(&scene.goal, &w.run(c)))
            .filter(|&r| r)
            .count()
    };
    let requirement = RobustRequirement {
        trials: 20,
        rate: 0.9,
    };
    let mut worlds = requirement.shortcut_worlds(&scene, 1);
    let before = count(&mut worlds, &controls);
    assert!((2..=18).contains(&before), "{before} of 20 reach");
    let mut criterion = Criterion::MoreRobust(worlds);
    let outcome = shortcut_by(
        &mut propagator,
        &scene.start,
        &controls,
        &ShortcutSettings::from_seconds(0.5, 1),
        &mut criterion,
    );
    let Criterion::MoreRobust(mut worlds) = criterion else {
        unreachable!()
    };
    assert_eq!(outcome.controls.len(), 1);
    assert!(
        outcome.controls[0].steps < steps,
        "{steps}: {:?}",
        outcome.controls
    );
    let after = count(&mut worlds, &outcome.controls);
    assert!(after > before && after >= 18, "{before} -> {after} of 20");
}
