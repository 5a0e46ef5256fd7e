//! Reach, grasp and place (issue 15): IK-BiRRT reaches a grasp behind a wall on a shipped
//! scene, push-then-grasp solves the default scene, both plans check and render, and bad
//! goals are clear errors.

use crate::common;

use nalgebra::DVector;
use pushplan::planning::plan_file::PlanFile;
use pushplan::planning::reach::{check_reach, grasp_distance, graspable_object};
use pushplan::planning::transit::check_transit;
use pushplan::robot::wgr::GRASP_TOLERANCE;
use pushplan::{Scene, State};
use std::path::Path;

/// The `pushplan` command run here: its exit code, stdout and stderr.
fn pushplan(args: &[&str]) -> (i32, String, String) {
    common::pushplan_in(Path::new("."), args)
}

/// The wall stands between the arm and the can: the straight joint-space line from the
/// start to the reach's end is not valid, the reach IK-BiRRT finds is (every segment, by
/// the model's Transit check), and it ends inside the can's grasp region.
#[test]
fn ik_birrt_reaches_a_grasp_behind_a_wall() {
    let scratch = common::Scratch::new("reach-wall");
    let plan_path = scratch.join("reach.json");
    let reach_into = |out: &std::path::Path| {
        pushplan(&[
            "plan",
            "scenes/grasp_behind_wall.yaml",
            "--goal",
            "grasp:can",
            "--seed",
            "1",
            "--time",
            "60",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ])
    };
    let (code, stdout, stderr) = reach_into(&plan_path);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let plan = PlanFile::read(&plan_path).unwrap();
    assert!(plan.solved && plan.controls.is_empty());
    let reach = plan.reach.as_ref().expect("the plan holds the reach");
    assert_eq!(reach.object, "can");

    let scene = Scene::load("scenes/grasp_behind_wall.yaml").unwrap();
    let can = graspable_object(&scene, "can").unwrap();
    let waypoints = plan.reach_waypoints();
    check_reach(&scene, &scene.start, can, &waypoints).unwrap();
    let end = State {
        q: waypoints.last().unwrap().clone(),
        objects: scene.start.objects.clone(),
    };
    assert!(grasp_distance(&scene, &end, can).unwrap() <= GRASP_TOLERANCE);
    assert!(
        check_transit(&scene, &scene.start, &end.q).is_err(),
        "the straight line to the grasp is free: the wall does not stand in the way"
    );
    // The hand ends level with the can's grasp frame, 13 cm from its axis.
    let tool = scene.robot.tool_pose(&scene.robot.link_poses(&end.q));
    let can_pose = scene.start.objects[can];
    let offset = tool.translation.vector.xy() - can_pose.translation();
    assert!((offset.norm() - 0.13).abs() < 2e-3, "{}", offset.norm());

    // `check` agrees; the trajectory plays the reach at the joints' limits and ends there.
    let (code, stdout, _) = pushplan(&["check", plan_path.to_str().unwrap()]);
    assert_eq!(code, 0, "{stdout}");
    let last = plan.trajectory.q.last().unwrap();
    assert_eq!(DVector::from_column_slice(last), end.q);
    // The same seed gives the same reach, byte for byte.
    let again = scratch.join("again.json");
    let (code, _, _) = reach_into(&again);
    assert_eq!(code, 0);
    assert_eq!(
        std::fs::read_to_string(&again).unwrap(),
        std::fs::read_to_string(&plan_path).unwrap()
    );
}

/// Push, then grasp: the default scene's pushing plan brings the green box into its disc,
/// then IK-BiRRT reaches a grasp of it there; the plan file holds both, checks, and
/// `render` draws both (the film ends at the reach's last configuration).
#[test]
fn push_then_grasp_solves_the_default_scene() {
    let scratch = common::Scratch::new("push-then-grasp");
    let plan_path = scratch.join("plan.json");
    let scene_path = "scenes/herb_fig1_clutter.yaml";
    let (code, stdout, stderr) = pushplan(&[
        "plan",
        scene_path,
        "--grasp",
        "--seed",
        "1",
        "--threads",
        "1",
        "--shortcut",
        "0",
        // The first solution: a robust search that ends on the clock with the most robust
        // one found is a plan `check` cannot make again.
        "--robust",
        "0",
        "--time",
        "60",
        "--quiet",
        "--out",
        plan_path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(stdout.contains("then a grasp of 'green_box'"), "{stdout}");
    let plan = PlanFile::read(&plan_path).unwrap();
    assert!(plan.solved && !plan.controls.is_empty());
    assert_eq!(plan.grasp_after.as_deref(), Some("green_box"));
    let scene = Scene::load(scene_path).unwrap();
    let green = graspable_object(&scene, "green_box").unwrap();
    let end = plan.end_state();
    assert!(scene.goal.is_satisfied(&end));
    check_reach(&scene, &end, green, &plan.reach_waypoints()).unwrap();
    let (code, stdout, _) = pushplan(&["check", plan_path.to_str().unwrap()]);
    assert_eq!(code, 0, "{stdout}");
    assert!(
        stdout.contains("every segment valid, ending in a grasp region"),
        "{stdout}"
    );
    assert!(
        stdout.contains("the same plan, byte for byte"),
        "made again: {stdout}"
    );

    // A reach that ends outside the grasp region does not check.
    let mut broken = plan.clone();
    let reach = broken.reach.as_mut().unwrap();
    reach.waypoints.truncate(1);
    let report = broken.check(&plan_path).unwrap();
    assert!(!report.passed() && !report.reach_valid, "{report:?}");
    assert!(
        report.problems.iter().any(|p| p.starts_with("reach:")),
        "{report:?}"
    );

    // A grasp asked for and not found (as `plan --grasp` writes it when IK-BiRRT runs out
    // of time): the controls reach the goal, the plan is not solved, and `check` says why
    // (it said that `solved` differed from the re-simulation).
    let mut not_found = plan.clone();
    not_found.reach = None;
    not_found.solved = false;
    let report = not_found.check(&plan_path).unwrap();
    assert!(!report.passed() && !report.reach_valid, "{report:?}");
    assert_eq!(
        report.problems,
        [
            "reach: a grasp of 'green_box' after the controls was asked for (`plan --grasp`) and \
          none was found: the plan is not solved"
        ],
        "{report:?}"
    );

    let film = pushplan::render::Film::of(&plan, &plan_path).unwrap();
    let steps: usize = plan.controls.iter().map(|c| c.steps).sum();
    assert!(film.states.len() > steps + 1, "no reach frames");
    assert_eq!(
        film.states.last().unwrap().q,
        *plan.reach_waypoints().last().unwrap()
    );
    assert_eq!(film.states[steps].objects, end.objects);
    pushplan::render::render(&plan, &plan_path, &scratch.join("pictures"), &[]).unwrap();
}

#[test]
fn grasp_goals_name_what_is_wrong() {
    for (goal, expected) in [
        (
            "grasp:bowl",
            "no object 'bowl' with grasps in the scene (objects with grasps: 'green_box')",
        ),
        ("grasp:", "--goal must be grasp:OBJECT"),
        ("reach:green_box", "--goal must be grasp:OBJECT"),
    ] {
        let (code, stdout, stderr) = pushplan(&[
            "plan",
            "scenes/herb_fig1_clutter.yaml",
            "--goal",
            goal,
            "--quiet",
            "--out",
            "/dev/null",
        ]);
        assert_ne!(code, 0, "{goal}: {stdout}");
        assert!(stderr.contains(expected), "{goal}: {stderr}");
    }
    let (code, _, stderr) = pushplan(&[
        "plan",
        "scenes/grasp_behind_wall.yaml",
        "--goal",
        "grasp:can",
        "--sample-probability",
        "1.5",
        "--quiet",
        "--out",
        "/dev/null",
    ]);
    assert_ne!(code, 0);
    assert!(
        stderr.contains("--sample-probability must be in [0, 1]"),
        "{stderr}"
    );
}

/// A WGR goal for the pushing planner: PC RRT reaches a grasp of the blue box at the
/// pushing plane, pushing clutter aside on the way, the blue box itself unmoved (it must
/// stay); the plan checks and its last state is inside the region.
#[test]
fn pc_rrt_reaches_a_grasp_pushing_clutter_aside() {
    let scratch = common::Scratch::new("grasp-goal");
    let plan_path = scratch.join("plan.json");
    let scene_path = "scenes/grasp_through_clutter.yaml";
    let (code, stdout, stderr) = pushplan(&[
        "plan",
        scene_path,
        "--seed",
        "1",
        "--threads",
        "1",
        "--time",
        "60",
        "--quiet",
        "--out",
        plan_path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let plan = PlanFile::read(&plan_path).unwrap();
    assert!(plan.solved && !plan.controls.is_empty() && plan.reach.is_none());
    let scene = Scene::load(scene_path).unwrap();
    let blue = graspable_object(&scene, "blue_box").unwrap();
    let end = plan.end_state();
    assert!(grasp_distance(&scene, &end, blue).unwrap() <= GRASP_TOLERANCE);
    assert_eq!(
        end.objects[blue], scene.start.objects[blue],
        "the box to grasp moved"
    );
    // This seed's plan pushes clutter: the goal allows it.
    assert!(
        (0..end.objects.len()).any(|i| i != blue && end.objects[i] != scene.start.objects[i]),
        "no clutter pushed"
    );
    let (code, stdout, _) = pushplan(&["check", plan_path.to_str().unwrap()]);
    assert_eq!(code, 0, "{stdout}");
    // Drawn with the box to grasp as the goal object, and no goal region in the legend.
    let files =
        pushplan::render::render(&plan, &plan_path, &scratch.join("pictures"), &[]).unwrap();
    let svg = std::fs::read_to_string(files.snapshots).unwrap();
    assert!(svg.contains("goal object") && !svg.contains("goal region"));
}

/// The planar hand drives into the box it is to grasp: with `object_may_move: false`
/// (the default) the push is invalid as soon as the box moves; with true it goes on.
#[test]
fn the_object_to_grasp_stays_put_unless_it_may_move() {
    use pushplan::{EeAction, Invalid, Propagator};
    let text = std::fs::read_to_string("scenes/planar_hand_single_object.yaml").unwrap();
    let grasps =
        "    grasps: [{end_effector: {xyz: [-0.1, 0, 0.05]}, bounds: {yaw: [-3.14, 3.14]}}]\n";
    let with = |goal: &str| {
        let text = text.replace("    mu_c: 0.3\n", &format!("    mu_c: 0.3\n{grasps}"));
        let text = text.replace(
            "goal: {object: box, center: [0.85, 0.1], radius: 0.1}",
            goal,
        );
        Scene::from_yaml(&text, Path::new("scenes/x.yaml"))
    };
    let push = EeAction::planar(0.2, 0.0, 0.0);
    let stays = with("goal: {grasp: box}").unwrap();
    let run = Propagator::new(&stays).propagate(&stays.start, &push, 1.0);
    match run.stopped_by {
        Some(Invalid::MovesObjectToGrasp { ref object }) => assert_eq!(object, "box"),
        other => panic!("stopped by {other:?}"),
    }
    assert_eq!(run.state.objects[0], stays.start.objects[0]);
    let may = with("goal: {grasp: box, object_may_move: true}").unwrap();
    let run = Propagator::new(&may).propagate(&may.start, &push, 1.0);
    assert!(run.stopped_by.is_none(), "{:?}", run.stopped_by);
    assert!(run.state.objects[0].x > may.start.objects[0].x + 0.05);

    for (goal, field, message) in [
        (
            "goal: {grasp: hand}",
            "goal.grasp",
            "objects with grasps: 'box'",
        ),
        (
            "goal: {grasp: box, center: [0.8, 0]}",
            "goal",
            "a grasp goal has grasp and object_may_move only",
        ),
        (
            "goal: {object: box, center: [0.85, 0.1], radius: 0.1, object_may_move: true}",
            "goal.object_may_move",
            "applies to grasp goals only",
        ),
    ] {
        let error = with(goal).unwrap_err().to_string();
        assert!(
            error.contains(field) && error.contains(message),
            "{goal}: {error}"
        );
    }
}
