//! One test per validity rule (issue point 7), each with a state built to break it and,
//! where contact is allowed, one that only touches.

use crate::common;

use common::{herb_scene, object, parked_goal, HAND_NEAR};
use nalgebra::Vector3;
use pushplan_model::contact::{arm_contacts, ArmBounds};
use pushplan_model::validity::check_state;
use pushplan_model::{EeAction, Invalid, Pose2, Propagator, Scene, State};
use std::path::Path;

const BOX: &str = "{type: box, size: [0.1, 0.1, 0.14]}";

fn herb() -> Scene {
    herb_with_box_at(0.8, -0.2, "")
}

/// The goal box parked, the 0.1 m box at (x, y), and `extra` scene lines (or "").
fn herb_with_box_at(x: f64, y: f64, extra: &str) -> Scene {
    herb_scene(
        HAND_NEAR,
        &(parked_goal() + &object("box", BOX, [x, y, 0.0])),
        extra,
    )
    .unwrap()
}

fn with_object(scene: &Scene, index: usize, pose: Pose2) -> State {
    let mut state = scene.start.clone();
    state.objects[index] = pose;
    state
}

#[test]
fn the_start_state_is_valid() {
    assert_eq!(check_state(&herb(), &herb().start), Ok(()));
}

#[test]
fn joints_outside_their_limits_are_invalid() {
    let scene = herb();
    let mut state = scene.start.clone();
    state.q[0] = 2.7; // j1 limit is 2.6
    assert!(
        matches!(check_state(&scene, &state), Err(Invalid::JointLimit { joint, .. }) if joint == "j1")
    );
}

#[test]
fn the_arm_folded_onto_itself_is_invalid_but_adjacent_links_are_not_checked() {
    let scene = herb();
    let mut state = scene.start.clone();
    state.q[3] = 3.08; // elbow folded: forearm onto upper arm
    assert!(matches!(
        check_state(&scene, &state),
        Err(Invalid::SelfCollision { link_a, link_b }) if link_a == "wam_link3" && link_b == "wam_link5"
    ));
    // The shoulder sphere overlaps the base column and the upper arm at every
    // configuration; they are adjacent (through the geometry-less link1), so not checked.
    let pairs: Vec<_> = scene
        .robot
        .self_collision_pairs
        .iter()
        .map(|&(a, b)| {
            (
                scene.robot.chain.links[a].name.as_str(),
                scene.robot.chain.links[b].name.as_str(),
            )
        })
        .collect();
    assert!(
        !pairs.contains(&("wam_base", "wam_link2")) && !pairs.contains(&("wam_link2", "wam_link3"))
    );
    assert!(pairs.contains(&("wam_link3", "wam_link5")) && pairs.contains(&("wam_link2", "hand")));
}

#[test]
fn the_arm_in_the_table_is_invalid() {
    // The planar hand lowered into the table top.
    let text = std::fs::read_to_string("scenes/planar_hand_single_object.yaml").unwrap();
    let scene = Scene::from_yaml(
        &text.replace("height: 0.05", "height: 0.03"),
        Path::new("scenes/x.yaml"),
    );
    assert!(
        matches!(
            scene,
            Err(pushplan_model::Error::InvalidStart {
                rule: Invalid::ArmHitsTable { .. },
                ..
            })
        ),
        "{scene:?}"
    );
    // The arm's shoulder pitched forward drives the hand down into the table.
    let scene = herb();
    let mut state = scene.start.clone();
    state.q[1] += 0.3;
    assert!(
        matches!(
            check_state(&scene, &state),
            Err(Invalid::ArmHitsTable { .. })
        ),
        "{:?}",
        check_state(&scene, &state)
    );
}

#[test]
fn the_arm_in_a_static_obstacle_is_invalid() {
    let obstacle = "obstacles:\n  - {name: post, shape: {type: cylinder, radius: 0.03, height: 0.5}, pose: {xyz: [0.55, 0.15, 1.0]}}";
    let scene = herb_scene(HAND_NEAR, &parked_goal(), obstacle);
    match scene {
        Err(pushplan_model::Error::InvalidStart { file, rule }) => {
            assert!(file.ends_with("test-scene.yaml"));
            assert_eq!(rule.to_string(), "link 'hand' hits obstacle 'post'");
        }
        other => panic!("{other:?}"),
    }
    let clear = "obstacles:\n  - {name: post, shape: {type: cylinder, radius: 0.03, height: 0.5}, pose: {xyz: [0.55, -0.4, 1.0]}}";
    assert!(herb_scene(HAND_NEAR, &parked_goal(), clear).is_ok());
}

#[test]
fn arm_object_contact_is_allowed_but_penetration_is_not() {
    let scene = herb();
    // Slide the box towards the hand until the arm-object distance crosses zero.
    let tool = scene
        .robot
        .tool_pose(&scene.robot.link_poses(&scene.start.q))
        .translation;
    let place = |x: f64| with_object(&scene, 1, Pose2::new(x, tool.y, 0.0));
    let distance = |x: f64| {
        let mut contacts = Vec::new();
        let poses = scene.robot.link_poses(&scene.start.q);
        let mut bounds = pushplan_model::contact::ArmBounds::default();
        pushplan_model::contact::ArmBounds::compute(&scene, &poses, &mut bounds);
        let objects = place(x).objects;
        let mut boxes = Vec::new();
        pushplan_model::contact::object_bounds(&scene, &objects, &mut boxes);
        pushplan_model::contact::find_arm_contacts(
            &scene,
            &poses,
            &bounds,
            &objects,
            &boxes,
            0.05,
            &mut contacts,
        );
        contacts
            .iter()
            .map(|c| c.point.distance)
            .fold(f64::INFINITY, f64::min)
    };
    // Bisect for the touching position.
    let (mut lo, mut hi) = (tool.x, tool.x + 0.3); // penetrating .. apart
    for _ in 0..60 {
        let mid = (lo + hi) / 2.0;
        if distance(mid) < 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    assert_eq!(check_state(&scene, &place(hi)), Ok(()));
    assert_eq!(
        check_state(&scene, &place(hi - 0.002)),
        Ok(()),
        "2 mm is within the 3 mm tolerance"
    );
    assert!(matches!(
        check_state(&scene, &place(hi - 0.01)),
        Err(Invalid::ArmPenetratesObject { link, object, depth }) if link == "hand" && object == "box" && depth > 0.009
    ));
}

#[test]
fn overlapping_objects_are_invalid_touching_ones_are_not() {
    let scene = herb();
    let goal = scene.start.objects[0];
    // The box (0.1 wide) beside the goal box (0.102 wide): centres 0.101 apart touch,
    // which is closer than the clearance (1 cm) unless it is zero.
    let touching = with_object(&scene, 1, Pose2::new(goal.x + 0.101, goal.y, 0.0));
    assert!(matches!(
        check_state(&scene, &touching),
        Err(Invalid::TooClose { distance, .. }) if distance.abs() < 1e-9
    ));
    let mut no_clearance = scene.clone();
    no_clearance.physics.object_clearance = 0.0;
    no_clearance.clearances = pushplan_model::scene::Clearances::at_start(&no_clearance);
    assert_eq!(check_state(&no_clearance, &touching), Ok(()));
    let overlapping = with_object(&scene, 1, Pose2::new(goal.x + 0.09, goal.y, 0.0));
    assert!(matches!(
        check_state(&scene, &overlapping),
        Err(Invalid::ObjectsOverlap { .. })
    ));
}

#[test]
fn an_object_must_stand_wholly_on_the_table() {
    // The 0.1 m box near the table's far edge (x = 1.03): its footprint, not only its
    // centre, must be on the table, turned corners included (no edge clearance here: the
    // footprint rule alone).
    let scene = herb_with_box_at(0.8, -0.2, "physics: {edge_clearance: 0}");
    let off_table = |pose: Pose2| {
        matches!(
            check_state(&scene, &with_object(&scene, 1, pose)),
            Err(Invalid::ObjectOffTable { object, .. }) if object == "box"
        )
    };
    let inside = with_object(&scene, 1, Pose2::new(0.97, -0.2, 0.0)); // face at 1.02
    assert_eq!(check_state(&scene, &inside), Ok(()));
    assert!(
        off_table(Pose2::new(0.99, -0.2, 0.0)),
        "overhangs by 1 cm, centre on"
    );
    // Turned 45 degrees, a corner reaches 0.05 * sqrt(2) = 0.0707 m out: 1.0407.
    assert!(off_table(Pose2::new(
        0.97,
        -0.2,
        std::f64::consts::FRAC_PI_4
    )));
    assert!(!off_table(Pose2::new(
        0.955,
        -0.2,
        std::f64::consts::FRAC_PI_4
    )));
    assert!(off_table(Pose2::new(1.04, -0.2, 0.0)));
    // The verdict says how far over: the turned corner's reach less the edge's x.
    let turned = with_object(
        &scene,
        1,
        Pose2::new(0.97, -0.2, std::f64::consts::FRAC_PI_4),
    );
    match check_state(&scene, &turned) {
        Err(Invalid::ObjectOffTable { overhang, .. }) => {
            let corner = 0.97 + 0.05 * std::f64::consts::SQRT_2;
            assert!((overhang - (corner - 1.03)).abs() < 1e-12, "{overhang}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn an_object_in_a_static_obstacle_is_invalid() {
    let obstacle = "obstacles:\n  - {name: wall, shape: {type: box, size: [0.02, 0.5, 0.3]}, pose: {xyz: [0.95, -0.4, 0.91]}}";
    let scene = herb_with_box_at(0.8, -0.2, obstacle);
    let into_wall = with_object(&scene, 1, Pose2::new(0.92, -0.4, 0.0));
    assert!(
        matches!(check_state(&scene, &into_wall), Err(Invalid::ObjectHitsObstacle { object, obstacle }) if object == "box" && obstacle == "wall")
    );
}

#[test]
fn a_link_pressing_on_top_of_an_object_is_invalid() {
    // The planar hand's bottom face is 1 cm above the table; a 1.05 cm tall puck under it
    // is pressed from above (0.5 mm, within the penetration tolerance).
    let text = std::fs::read_to_string("scenes/planar_hand_single_object.yaml").unwrap();
    let scene = Scene::from_yaml(&text, Path::new("scenes/x.yaml")).unwrap();
    let puck = text.replace(
        "shape: {type: box, size: [0.1, 0.1, 0.14]}",
        "shape: {type: cylinder, radius: 0.03, height: 0.0105}",
    );
    let scene_puck = Scene::from_yaml(&puck, Path::new("scenes/x.yaml")).unwrap();
    let under_hand = with_object(&scene_puck, 0, Pose2::new(0.4, 0.0, 0.0));
    assert!(
        matches!(check_state(&scene_puck, &under_hand), Err(Invalid::PressesOnTop { link, object }) if link == "hand" && object == "box")
    );
    // The same hand beside the tall box touches its side: fine.
    let beside = with_object(&scene, 0, Pose2::new(0.4 + 0.02 + 0.05, 0.0, 0.0));
    assert_eq!(check_state(&scene, &beside), Ok(()));
}

#[test]
fn squeezing_an_object_between_two_fingers_jams_it() {
    let yaml = "robot:
  type: arm
  urdf: ../tests/data/gripper.urdf
  base_pose: {xyz: [0, 0, 0.81]}
  end_effector: finger
  start_joints: [0.6, 0.0, 0.0, 0.0]
  pushing_plane: {height: 0.05, orientation_rpy: [0, 0, 0]}
table: {height: 0.76, x: [0.27, 1.03], y: [-0.6, 0.6]}
objects:
  - {name: can, shape: {type: cylinder, radius: 0.04, height: 0.12}, pose: [0.6, 0.0, 0], mass: 0.5, mu_g: 0.4, mu_c: 0.3}
goal: {object: can, center: [0.8, 0.0], radius: 0.1}
";
    let scene = Scene::from_yaml(yaml, Path::new("scenes/gripper.yaml")).unwrap();
    let mut p = Propagator::new(&scene);
    // Hold the finger (the end effector) still and close the palm on it through the
    // null space: finger A moves in at 0.1 m/s, finger B stays.
    let squeeze = EeAction {
        velocity: [0.0; 3],
        nullspace: nalgebra::DVector::from_column_slice(&[0.0, 0.0, 0.0, 0.2]),
    };
    let run = p.propagate(&scene.start, &squeeze, 1.0);
    assert!(
        matches!(run.stopped_by, Some(Invalid::Jammed { ref object }) if object == "can"),
        "{:?}",
        run.stopped_by
    );
    // Before jamming, finger A pushed the can across the 2 cm gap onto finger B.
    assert!(
        run.state.objects[0].y < -0.015,
        "{:?}",
        run.state.objects[0]
    );
    // Moving the end effector sideways pushes the can with one finger: no jam. The
    // minimum-norm joint motion splits the 0.1 m/s between palm and slide, so finger A
    // moves at 0.05 m/s and, after the 2 cm gap, pushes the can 3 cm.
    let slide = p.propagate(&scene.start, &EeAction::planar(0.0, -0.1, 0.0), 1.0);
    assert!(slide.stopped_by.is_none(), "{:?}", slide.stopped_by);
    assert!(
        (slide.state.objects[0].y + 0.03).abs() < 2e-3,
        "{:?}",
        slide.state.objects[0]
    );
}

/// `allowed_collisions` lets exactly the named pairs touch: a pedestal around the base
/// column, the planar hand on the table top, the forearm folded onto the upper arm.
#[test]
fn allowed_collisions_let_the_named_pairs_touch_and_nothing_else() {
    let objects = parked_goal() + &object("box", BOX, [0.8, -0.2, 0.0]);
    // A pedestal around the base column (base at (0.1, 0.14, 0.346), column 0.3 m high).
    let pedestal = |height: f64| {
        format!(
            "obstacles: [{{name: pedestal, shape: {{type: box, size: [0.22, 0.22, {height}]}}, pose: {{xyz: [0.1, 0.14, {}]}}}}]\n",
            0.346 + height / 2.0
        )
    };
    let start_error = |extra: &str| match herb_scene(HAND_NEAR, &objects, extra) {
        Err(pushplan_model::Error::InvalidStart { rule, .. }) => rule.to_string(),
        other => panic!("expected an invalid start, got {:?}", other.map(|s| s.name)),
    };
    assert_eq!(
        start_error(&pedestal(0.2)),
        "link 'wam_base' hits obstacle 'pedestal'"
    );
    let allowed = "allowed_collisions: [[wam_base, pedestal]]\n";
    let scene = herb_scene(HAND_NEAR, &objects, &(pedestal(0.2) + allowed)).unwrap();
    assert_eq!(check_state(&scene, &scene.start), Ok(()));
    // Taller, it reaches the shoulder too: that pair is not allowed.
    assert_eq!(
        start_error(&(pedestal(0.36) + allowed)),
        "link 'wam_link2' hits obstacle 'pedestal'"
    );

    // The planar hand lowered into the table top, allowed to touch it.
    let text = std::fs::read_to_string("scenes/planar_hand_single_object.yaml").unwrap();
    let lowered = text.replace("height: 0.05", "height: 0.03");
    assert!(Scene::from_yaml(&lowered, Path::new("scenes/x.yaml")).is_err());
    let scene = Scene::from_yaml(
        &(lowered + "allowed_collisions: [[table, hand]]\n"),
        Path::new("scenes/x.yaml"),
    )
    .unwrap();
    assert_eq!(check_state(&scene, &scene.start), Ok(()));

    // The folded elbow: forearm onto upper arm, allowed; the pair leaves the checked ones.
    let scene = herb_scene(
        HAND_NEAR,
        &objects,
        "allowed_collisions: [[wam_link5, wam_link3]]\n",
    )
    .unwrap();
    let mut state = scene.start.clone();
    state.q[3] = 3.08;
    assert!(!matches!(
        check_state(&scene, &state),
        Err(Invalid::SelfCollision { link_a, link_b }) if link_a == "wam_link3" && link_b == "wam_link5"
    ));
    assert!(scene.robot.self_collision_pairs.len() == herb().robot.self_collision_pairs.len() - 1);
}

#[test]
fn allowed_collisions_name_what_there_is() {
    let objects = parked_goal() + &object("box", BOX, [0.8, -0.2, 0.0]);
    let error = |extra: &str| {
        herb_scene(HAND_NEAR, &objects, extra)
            .expect_err("the scene is refused")
            .to_string()
    };
    let message = error("allowed_collisions: [[wam_bse, table]]");
    assert!(
        message.contains("allowed_collisions[0][0]")
            && message.contains("'wam_bse'")
            && message.contains("'wam_base'")
            && message.contains("'hand'")
            && message.contains("the obstacles are none"),
        "{message}"
    );
    let message = error("allowed_collisions: [[hand, box]]");
    assert!(
        message.contains("allowed_collisions[0][1]") && message.contains("movable object"),
        "{message}"
    );
    let message = error(
        "obstacles: [{name: lamp, shape: {type: box, size: [0.1, 0.1, 0.1]}, pose: {xyz: [0.5, 0.9, 1.5]}}]\nallowed_collisions: [[lamp, table]]",
    );
    assert!(
        message.contains("allowed_collisions[0]") && message.contains("must be a link"),
        "{message}"
    );
    let message = error("allowed_collisions: [[hand]]");
    assert!(message.contains("allowed_collisions[0]"), "{message}");
    // The goal object's error lists the objects too.
    let message = herb_scene(
        HAND_NEAR,
        &objects.replace("name: goal", "name: goal_box"),
        "",
    )
    .err()
    .unwrap()
    .to_string();
    assert!(
        message.contains("goal.object") && message.contains("'goal_box', 'box'"),
        "{message}"
    );
}

#[test]
fn arm_bounds_kept_between_configurations_are_the_bounds_computed_afresh() {
    // One `ArmBounds` keeps the boxes of links that never move (the WAM's base column)
    // from its first computation; at every other configuration its boxes must still be
    // those a fresh computation gives, and every link's box must hold the link's shapes.
    use parry3d_f64::bounding_volume::BoundingVolume;
    use pushplan_model::contact::ArmBounds;
    let scene = Scene::load(Path::new("scenes/benchmark/scene_22.yaml")).unwrap();
    let mut kept = ArmBounds::default();
    let mut moved_links = 0;
    let mut q = scene.start.q.clone();
    let first = scene.robot.link_poses(&q);
    for k in 0..5 {
        for (i, v) in q.iter_mut().enumerate() {
            *v += 0.1 * (k as f64 + 1.0) * if i % 2 == 0 { 1.0 } else { -1.0 };
        }
        let poses = scene.robot.link_poses(&q);
        ArmBounds::compute(&scene, &poses, &mut kept);
        let mut fresh = ArmBounds::default();
        ArmBounds::compute(&scene, &poses, &mut fresh);
        assert_eq!(kept.links, fresh.links);
        assert_eq!(kept.all, fresh.all);
        for link in 0..scene.robot.chain.links.len() {
            let listed = kept.links.iter().find(|(l, _)| *l == link).map(|(_, b)| b);
            assert_eq!(kept.of(link), listed, "link {link}");
        }
        for (link, aabb) in &kept.links {
            for g in &scene.robot.chain.links[*link].geometry {
                let shape = g.shape.compute_aabb(&g.world_pose(&poses[*link]));
                assert!(aabb.contains(&shape), "link {link}");
            }
            moved_links += usize::from(poses[*link] != first[*link]);
        }
    }
    assert!(moved_links > 0, "the configurations move the arm");
}

#[test]
fn an_object_keeps_the_edge_clearance_from_the_table_s_edges_or_its_start_distance() {
    // `physics.edge_clearance` 1 cm, the default. The 0.1 m box starts with its face
    // 18 cm from the far edge (x = 1.03): it may come to 1 cm of it, no nearer.
    let at = |scene: &Scene, x: f64, y: f64| {
        check_state(scene, &with_object(scene, 1, Pose2::new(x, y, 0.0)))
    };
    let scene = herb_with_box_at(0.8, -0.2, "");
    assert_eq!(at(&scene, 0.97 - 1e-4, -0.2), Ok(()));
    match at(&scene, 0.97 + 1e-4, -0.2) {
        Err(invalid @ Invalid::ObjectOffTable { .. }) => assert!(
            invalid
                .to_string()
                .contains("comes 9.9 mm from the table's edge, closer than the clearance"),
            "{invalid}"
        ),
        other => panic!("{other:?}"),
    }
    // A side edge (y = -0.93) the same.
    assert_eq!(at(&scene, 0.8, -0.87 + 1e-4), Ok(()));
    assert!(matches!(
        at(&scene, 0.8, -0.87 - 1e-4),
        Err(Invalid::ObjectOffTable { .. })
    ));
    // Without it (0) an object may touch the edge, but not reach past it.
    let touching = herb_with_box_at(0.8, -0.2, "physics: {edge_clearance: 0}");
    assert_eq!(at(&touching, 0.98 - 1e-6, -0.2), Ok(()));
    assert!(matches!(
        at(&touching, 0.98 + 1e-4, -0.2),
        Err(Invalid::ObjectOffTable { .. })
    ));
    // A box that starts 4 mm from the edge may stay there, but not come nearer.
    let near = herb_with_box_at(0.976, -0.2, "");
    assert_eq!(check_state(&near, &near.start), Ok(()));
    assert!(matches!(
        at(&near, 0.976 + 1e-4, -0.2),
        Err(Invalid::ObjectOffTable { .. })
    ));
    // So does one observed 3 mm from it in the world (a re-plan's start).
    let observed = with_object(&scene, 1, Pose2::new(0.977, -0.2, 0.0));
    let from = scene
        .with_start(&observed, Path::new("observed.json"))
        .unwrap();
    assert_eq!(at(&from, 0.977, -0.2), Ok(()));
    assert_eq!(at(&from, 0.9, -0.2), Ok(()), "pushed back");
    assert!(matches!(
        at(&from, 0.977 + 1e-4, -0.2),
        Err(Invalid::ObjectOffTable { .. })
    ));
}

/// The WAM at [`HAND_NEAR`] with a 4 cm upright cylinder set beside its wrist ball
/// (`wam_link6`, radius 5 cm) so that the ball touches the cylinder's top rim with the
/// contact's normal `angle` (rad) from vertical, on the side away from the hand (-x); `extra` as in
/// [`herb_scene`]. Returns the scene (the cylinder parked), the state with the cylinder on
/// the wrist, and the normal out of the cylinder, in the world frame, from the geometry
/// alone: the ball's centre lies `r sin(angle)` beyond the rim
/// horizontally and `r cos(angle)` above the top, so the rim point under it is the
/// nearest point and the normal runs from it to the centre.
#[allow(non_snake_case)] // frame-named: p_WC, the ball's centre in the world frame
fn wrist_ball_on_a_rim(angle: f64, extra: &str) -> (Scene, State, Vector3<f64>) {
    let (r_ball, r_rim) = (0.05, 0.04);
    let arm = herb_scene(HAND_NEAR, &parked_goal(), "").unwrap();
    let wrist = arm
        .robot
        .chain
        .links
        .iter()
        .position(|l| l.name == "wam_link6");
    let p_WC = arm.robot.link_poses(&arm.start.q)[wrist.unwrap()]
        .translation
        .vector;
    let n_W = Vector3::new(angle.sin(), 0.0, angle.cos()); // rim point to the ball's centre
    let height = p_WC.z - r_ball * angle.cos() - arm.table.top;
    let x = p_WC.x - r_ball * angle.sin() - r_rim;
    let shape = format!("{{type: cylinder, radius: {r_rim}, height: {height}}}");
    // Loaded with the cylinder out of the way (a start pressing on top is refused at load).
    let objects = parked_goal() + &object("bowl", &shape, [0.8, -0.3, 0.0]);
    let scene = herb_scene(HAND_NEAR, &objects, extra).unwrap();
    let on_the_rim = with_object(&scene, 1, Pose2::new(x, p_WC.y, 0.0));
    (scene, on_the_rim, n_W)
}

#[test]
#[allow(non_snake_case)] // n_W, the contact's normal in the world frame
fn a_link_pressing_a_rim_down_is_invalid_pushing_it_sideways_is_not() {
    // A contact more vertical than horizontal loads the object into the table more than it
    // pushes it: not the planar push the model solves (in rapier, an upper arm pressing a
    // bowl's rim 34 degrees from vertical tipped it). `vertical_normal_angle` defaults to
    // 45 degrees.
    for degrees in [10.0, 34.0, 44.0, 46.0, 60.0, 80.0] {
        let angle = f64::to_radians(degrees);
        let (scene, state, n_W) = wrist_ball_on_a_rim(angle, "");
        let poses = scene.robot.link_poses(&state.q);
        let mut bounds = ArmBounds::default();
        ArmBounds::compute(&scene, &poses, &mut bounds);
        let contacts = arm_contacts(&scene, &poses, &bounds, &state.objects, 1e-3);
        // One contact, the ball on the rim, touching, with the normal of the geometry.
        assert_eq!(contacts.len(), 1, "{degrees} degrees: {contacts:?}");
        let c = &contacts[0];
        assert_eq!(scene.robot.chain.links[c.link].name, "wam_link6");
        assert!(
            c.point.distance.abs() < 1e-6,
            "{degrees}: {}",
            c.point.distance
        );
        assert!(
            (c.point.normal_a.into_inner() - n_W).norm() < 1e-4,
            "{degrees}: {:?}",
            c.point.normal_a
        );
        let verdict = check_state(&scene, &state);
        if degrees < 45.0 {
            assert!(
                matches!(&verdict, Err(Invalid::PressesOnTop { link, object }) if link == "wam_link6" && object == "bowl"),
                "{degrees} degrees: {verdict:?}"
            );
        } else {
            assert_eq!(verdict, Ok(()), "{degrees} degrees");
        }
    }
    // The rule, not something else, refuses it: at the old 20 degrees the 34-degree press
    // passes for a push.
    let (loose, state, _) = wrist_ball_on_a_rim(0.6, "physics: {vertical_normal_angle: 0.35}");
    assert_eq!(check_state(&loose, &state), Ok(()));
}
