//! `Scene::with_start`: a state observed while a plan runs becomes the start as a scene
//! file's start would: checked, an arm's tool brought onto its pushing plane, yaws
//! wrapped, and a wrong one refused with the file and field named.

use crate::common::{herb_scene, object, parked_goal, HAND_NEAR};
use pushplan_model::{Error, Overlap, Scene};
use std::path::Path;

fn herb() -> Scene {
    Scene::load("scenes/herb_single_object.yaml").unwrap()
}

/// The tool's height above its pushing plane in `scene`'s start (m).
fn height_off_plane(scene: &Scene, q: &nalgebra::DVector<f64>) -> f64 {
    let robot = &scene.robot;
    robot.plane.error(&robot.tool_pose(&robot.link_poses(q))).0
}

#[test]
fn a_scene_start_observed_again_is_the_same_start_bit_for_bit() {
    let scene = herb();
    let again = scene
        .with_start(&scene.start, Path::new("observed.json"))
        .unwrap();
    let bits = |s: &Scene| -> Vec<u64> { s.start.to_flat().iter().map(|v| v.to_bits()).collect() };
    assert_eq!(bits(&again), bits(&scene));
}

#[test]
fn an_arm_off_its_plane_is_brought_back_and_a_yaw_is_wrapped() {
    let scene = herb();
    let mut observed = scene.start.clone();
    // The shoulder a hundredth of a radian up: the tool leaves its plane by centimetres.
    observed.q[1] -= 0.01;
    observed.objects[0].theta += 4.0 * std::f64::consts::PI;
    let tight = 1e-3 * scene.robot.projection.height_tolerance;
    assert!(height_off_plane(&scene, &observed.q).abs() > 1e3 * tight);
    let from = scene
        .with_start(&observed, Path::new("observed.json"))
        .unwrap();
    assert!(
        height_off_plane(&from, &from.start.q).abs() <= tight,
        "on the plane within a scene start's tolerance"
    );
    let yaw = from.start.objects[0].theta - scene.start.objects[0].theta;
    assert!(yaw.abs() < 1e-9, "the yaw wrapped back: {yaw}");
}

#[test]
fn a_wrong_observation_names_its_file_and_field() {
    let scene = herb();
    let file = Path::new("observed.json");
    let refused = |change: &dyn Fn(&mut pushplan_model::State)| {
        let mut observed = scene.start.clone();
        change(&mut observed);
        let error = scene.with_start(&observed, file).unwrap_err();
        assert!(error.to_string().contains("observed.json"), "{error}");
        error
    };
    let short = refused(&|s| s.q = s.q.rows(0, 3).into_owned());
    assert!(
        matches!(&short, Error::Invalid { field, .. } if field == "q"),
        "{short}"
    );
    let nan = refused(&|s| s.objects[0].x = f64::NAN);
    assert!(
        matches!(&nan, Error::Invalid { field, .. } if field == "objects.green_box"),
        "{nan}"
    );
    let beyond = refused(&|s| s.q[3] = 100.0);
    assert!(matches!(&beyond, Error::Invalid { .. }), "{beyond}");
    // The box where the arm's base stands: off the table.
    let inside = refused(&|s| {
        s.objects[0].x = 0.1;
        s.objects[0].y = 0.14;
    });
    assert!(
        matches!(&inside, Error::Invalid { field, .. } if field == "objects.green_box"),
        "{inside}"
    );
}

fn planar_hand() -> Scene {
    Scene::load("scenes/planar_hand_single_object.yaml").unwrap()
}

/// The planar hand's start: a 4 x 12 cm box at (0.4, 0) facing +x, its front face at
/// x = 0.42; the 10 cm box ahead of it. The table ends at x = 1.03.
const HAND_FRONT_X: f64 = 0.42;
const BOX_HALF: f64 = 0.05;
const TABLE_END_X: f64 = 1.03;

#[test]
fn an_object_observed_inside_the_hand_is_taken_to_touch_it() {
    let scene = planar_hand();
    let mut observed = scene.start.clone();
    // The box's back face 5 mm behind the hand's front face: a soft contact's depth.
    observed.objects[0].x = HAND_FRONT_X + BOX_HALF - 0.005;
    observed.objects[0].y = 0.01;
    let from = scene
        .with_start(&observed, Path::new("observed.json"))
        .unwrap();
    let pose = from.start.objects[0];
    let back_face = pose.x - BOX_HALF;
    assert!(
        back_face >= HAND_FRONT_X - scene.physics.penetration_tolerance
            && back_face <= HAND_FRONT_X + 1e-3,
        "moved out along the face's normal to touch the hand: back face at {back_face}"
    );
    assert_eq!((pose.y, pose.theta), (0.01, 0.0), "and only along it");
    // 25 mm inside: not a contact's depth; refused, the object named.
    observed.objects[0].x = HAND_FRONT_X + BOX_HALF - 0.025;
    refused_naming_the_box(&scene, &observed, Some(Overlap::ArmAndObject));
}

/// `observed` is refused with the box named: as too deep an `overlap` where one is given
/// (what moving the arm back undoes, or not), else as a wrong value.
fn refused_naming_the_box(
    scene: &Scene,
    observed: &pushplan_model::State,
    overlap: Option<Overlap>,
) {
    let error = scene
        .with_start(observed, Path::new("observed.json"))
        .unwrap_err();
    let named = match (&error, overlap) {
        (Error::DeepOverlap { field, between, .. }, Some(overlap)) => {
            *between == overlap && field == "objects.box"
        }
        (Error::Invalid { field, .. }, None) => field == "objects.box",
        _ => false,
    };
    assert!(named, "{error:?}");
}

#[test]
fn an_object_observed_at_the_edge_may_hang_over_as_far_as_its_support_carries_a_push_and_no_other()
{
    // A 10 cm box (not the goal's) near the table's far edge (x = 1.03), the goal box
    // parked near its side edge (y = -0.93); no edge clearance, so that the room over the
    // edge is the observed start's alone (the clearance's own test: validity.rs).
    let objects = parked_goal()
        + &object(
            "box",
            "{type: box, size: [0.1, 0.1, 0.14]}",
            [0.7, -0.3, 0.0],
        );
    let scene = herb_scene(HAND_NEAR, &objects, "physics: {edge_clearance: 0}").unwrap();
    assert_eq!(scene.physics.tipping_margin, 0.3);
    let mut observed = scene.start.clone();
    // 5 mm of the box past the far edge, its centre 4.5 cm inside.
    observed.objects[1].x = TABLE_END_X - BOX_HALF + 0.005;
    let from = scene
        .with_start(&observed, Path::new("observed.json"))
        .unwrap();
    let at = |from: &Scene, i: usize, (x, y, yaw): (f64, f64, f64)| {
        let mut state = from.start.clone();
        state.objects[i].x = x;
        state.objects[i].y = y;
        state.objects[i].theta = yaw;
        pushplan_model::validity::check_state(from, &state)
    };
    let off_table = |from: &Scene, i: usize, pose: (f64, f64, f64)| {
        matches!(
            at(from, i, pose),
            Err(pushplan_model::validity::Invalid::ObjectOffTable { .. })
        )
    };
    let y = observed.objects[1].y;
    // The tipping check keeps the support pressure inside the footprint shrunk by the
    // 30 % margin about its centre, a 7 cm square: the box may go on over the edge until
    // that square's face reaches it (centre 3.5 cm inside, 15 mm of the box over).
    let shrunk_half = 0.7 * BOX_HALF;
    assert!(at(&from, 1, (TABLE_END_X - shrunk_half - 1e-4, y, 0.0)).is_ok());
    assert!(off_table(
        &from,
        1,
        (TABLE_END_X - shrunk_half + 1e-4, y, 0.0)
    ));
    // Turned 45 degrees, its corner leads: the shrunk square's half-diagonal.
    let corner = shrunk_half * std::f64::consts::SQRT_2;
    let quarter = std::f64::consts::FRAC_PI_4;
    assert!(at(&from, 1, (TABLE_END_X - corner - 1e-4, y, quarter)).is_ok());
    assert!(off_table(
        &from,
        1,
        (TABLE_END_X - corner + 1e-4, y, quarter)
    ));
    assert!(
        at(&from, 1, (observed.objects[1].x - 0.01, y, 0.0)).is_ok(),
        "pushed back"
    );
    // The scene file's own start keeps every footprint wholly on the table.
    assert!(off_table(
        &scene,
        1,
        (TABLE_END_X - BOX_HALF + 1e-4, y, 0.0)
    ));
    // Observed further over than that (2 cm): it may stay, or be pushed back, but not go
    // further out.
    observed.objects[1].x = TABLE_END_X - BOX_HALF + 0.02;
    let from = scene
        .with_start(&observed, Path::new("observed.json"))
        .unwrap();
    let x = observed.objects[1].x;
    assert!(at(&from, 1, (x, y, 0.0)).is_ok());
    assert!(at(&from, 1, (x - 0.01, y, 0.0)).is_ok(), "pushed back");
    assert!(off_table(&from, 1, (x + 1e-4, y, 0.0)));
    // The goal's object, observed 5 mm over the side edge, goes no further over: it must
    // end where the plan says, and the model spreads its support over the whole footprint.
    let goal_half = 0.051;
    let table_side_y = -0.93;
    observed.objects[1].x = 0.7;
    observed.objects[0].y = table_side_y + goal_half - 0.005;
    let from = scene
        .with_start(&observed, Path::new("observed.json"))
        .unwrap();
    let goal = (observed.objects[0].x, observed.objects[0].y, 0.0);
    assert!(at(&from, 0, goal).is_ok());
    assert!(off_table(&from, 0, (goal.0, goal.1 - 1e-4, 0.0)));
    // The box, observed 28 cm from the edge, gets no room over it: a re-plan keeps it
    // wholly on, as the scene file's start does.
    assert!(at(&from, 1, (TABLE_END_X - BOX_HALF - 1e-4, y, 0.0)).is_ok());
    assert!(off_table(&from, 1, (TABLE_END_X - BOX_HALF + 1e-4, y, 0.0)));
    // Observed 1 mm short of the edge (within what an observation may be off), it does.
    observed.objects[1].x = TABLE_END_X - BOX_HALF - 0.001;
    let from = scene
        .with_start(&observed, Path::new("observed.json"))
        .unwrap();
    assert!(at(&from, 1, (TABLE_END_X - shrunk_half - 1e-4, y, 0.0)).is_ok());
    // Its centre off the table: fallen, not standing; refused, the object named.
    let scene = planar_hand();
    let mut observed = scene.start.clone();
    observed.objects[0].x = TABLE_END_X + 0.01;
    refused_naming_the_box(&scene, &observed, None);
}

#[test]
fn an_observed_joint_at_its_limit_stays_within_it_on_the_plane() {
    let scene = herb();
    let robot = &scene.robot;
    let chain = &robot.chain;
    let mut pushed_past = 0;
    for joint in 0..robot.dof() {
        let limits = chain.dof_joint(joint);
        for limit in [limits.lower, limits.upper] {
            let mut observed = scene.start.clone();
            observed.q[joint] = limit;
            observed.q[1] -= 0.01; // the tool off its plane
            let mut projected = observed.q.clone();
            if robot.start_on_plane(&mut projected).is_err() {
                continue;
            }
            pushed_past += usize::from(chain.within_limits(&projected).is_err());
            // A start may still be refused for a collision, never for the limit.
            if let Ok(from) = scene.with_start(&observed, Path::new("observed.json")) {
                assert!(chain.within_limits(&from.start.q).is_ok());
                assert!(
                    height_off_plane(&from, &from.start.q).abs()
                        <= 1e-3 * robot.projection.height_tolerance
                );
            }
        }
    }
    assert!(
        pushed_past > 0,
        "the projection alone takes some joint past its limit"
    );
}

#[test]
fn an_object_observed_under_the_hand_is_taken_to_stand_beside_it() {
    // A flat hand (4 x 12 x 2 cm, its centre 4.7 cm up: its underside at 3.7 cm) over the
    // rim of a 4 cm tall disc: 3 mm down into it, 1 cm in from the rim. No push along a
    // normal takes the disc out (the contact's normal is vertical): it is moved straight
    // away from the hand until the hand is clear of its top.
    let yaml = "robot: {type: planar_hand, shape: {type: box, size: [0.04, 0.12, 0.02]}, \
                start: [0.4, 0.0, 0.0], height: 0.047}
table: {height: 0.76, x: [0.27, 1.03], y: [-0.6, 0.6]}
objects:
  - {name: box, shape: {type: cylinder, radius: 0.05, height: 0.04}, pose: [0.6, 0.0, 0.0], \
     mass: 0.5, mu_g: 0.4, mu_c: 0.3}
goal: {object: box, center: [0.85, 0.1], radius: 0.1}";
    let scene = Scene::from_yaml(yaml, Path::new("under-the-hand.yaml")).unwrap();
    let mut observed = scene.start.clone();
    let hand_front = HAND_FRONT_X;
    observed.objects[0].x = hand_front + 0.05 - 0.01;
    let from = scene
        .with_start(&observed, Path::new("observed.json"))
        .unwrap();
    // Out until what is left of the 1 cm overlap is a side contact within the
    // penetration tolerance, in 2 mm steps.
    let moved = from.start.objects[0].x - observed.objects[0].x;
    let tolerance = scene.physics.penetration_tolerance;
    assert!(
        (0.01 - tolerance..=0.012).contains(&moved),
        "out by the 1 cm the hand overlaps it less the tolerance: {moved}"
    );
    let sideways = from.start.objects[0].y;
    assert!(
        sideways.abs() < 1e-3,
        "away from the hand, not sideways: {sideways}"
    );
    // 2.5 cm under the hand: further than an observation may be off.
    observed.objects[0].x = hand_front + 0.05 - 0.025;
    refused_naming_the_box(&scene, &observed, Some(Overlap::ArmAndObject));
}

#[test]
fn two_objects_observed_pressed_into_each_other_are_moved_apart_as_far_as_they_overlap() {
    // Benchmark 25's glass_5 observed against glass_4 (both 35 mm discs), 3 mm into it:
    // a soft contact's depth. Each goes half the depth (and 0.05 mm) back along the line
    // between their centres, so their centres end 2 x 35 mm + 0.1 mm apart; nothing else
    // moves. 25 mm into it is more than an observation may be off: refused, both named.
    let scene = Scene::load("scenes/benchmark/scene_25.yaml").unwrap();
    let (a, b) = (4, 5);
    assert_eq!(
        (&*scene.objects[a].name, &*scene.objects[b].name),
        ("glass_4", "glass_5")
    );
    let pressed = |depth: f64| {
        let mut observed = scene.start.clone();
        let p = observed.objects[a];
        observed.objects[b] = pushplan_model::Pose2::new(p.x - (0.070 - depth), p.y, 0.3);
        observed
    };
    let observed = pressed(0.003);
    let from = scene
        .with_start(&observed, Path::new("observed.json"))
        .unwrap();
    let (pa, pb) = (from.start.objects[a], from.start.objects[b]);
    assert!(
        ((pa.x - pb.x) - (0.070 + 1e-4)).abs() < 1e-12,
        "{pa:?} {pb:?}"
    );
    assert!((pa.x - observed.objects[a].x - 0.00155).abs() < 1e-12);
    assert!(
        (pa.y - observed.objects[a].y).abs() < 1e-12
            && (pb.y - observed.objects[b].y).abs() < 1e-12
    );
    for (i, (now, seen)) in from.start.objects.iter().zip(&observed.objects).enumerate() {
        if i != a && i != b {
            assert_eq!(now, seen, "object {i} stays where it was observed");
        }
    }
    let error = scene
        .with_start(&pressed(0.025), Path::new("observed.json"))
        .unwrap_err();
    assert!(
        matches!(&error, Error::DeepOverlap { field, between: Overlap::Objects, message, .. }
            if field == "objects.glass_5" && message.contains("'glass_4' overlaps it by 25.0 mm")),
        "{error}"
    );
}

#[test]
fn an_object_pressed_between_the_arm_and_a_neighbour_is_taken_to_touch_both() {
    // The planar hand's box observed 4 mm into the hand's front face, a second box of the
    // same size touching its front (0.5 mm gap): moving the first out of the hand takes it
    // 3.5 mm into the second, and moving those two apart takes it back into the hand. The
    // two separations alternate until each contact is within its tolerance; with one pass
    // of each (before), the objects were left overlapping and the observation refused.
    let text = std::fs::read_to_string("scenes/planar_hand_single_object.yaml").unwrap();
    let second = "  - name: second\n    shape: {type: box, size: [0.1, 0.1, 0.14]}\n    pose: [0.8, -0.3, 0.0]\n    mass: 1.0\n    mu_g: 0.4\n    mu_c: 0.3\ngoal:";
    let scene =
        Scene::from_yaml(&text.replacen("goal:", second, 1), Path::new("two.yaml")).unwrap();
    let mut observed = scene.start.clone();
    let first_x = HAND_FRONT_X + BOX_HALF - 0.004;
    observed.objects[0] = pushplan_model::Pose2::new(first_x, 0.0, 0.0);
    observed.objects[1] = pushplan_model::Pose2::new(first_x + 2.0 * BOX_HALF + 0.0005, 0.0, 0.0);
    let from = scene
        .with_start(&observed, Path::new("observed.json"))
        .unwrap();
    let (first, second) = (from.start.objects[0], from.start.objects[1]);
    let (physics, tolerance) = (&scene.physics, 1e-9);
    let in_hand = HAND_FRONT_X - (first.x - BOX_HALF);
    let overlap = (first.x + BOX_HALF) - (second.x - BOX_HALF);
    assert!(
        in_hand <= physics.penetration_tolerance + tolerance
            && overlap <= physics.overlap_tolerance + tolerance,
        "within both tolerances: {:.2} mm into the hand, {:.2} mm into the neighbour",
        in_hand * 1e3,
        overlap * 1e3
    );
    // Moved along x only, and no further than the depths asked: the first box at most its
    // 4 mm out of the hand, the second at most the 3.5 mm it was pushed into.
    assert_eq!(
        (first.y, first.theta, second.y, second.theta),
        (0.0, 0.0, 0.0, 0.0)
    );
    assert!(
        first.x >= first_x && first.x - first_x <= 0.004 + 1e-4,
        "{first:?}"
    );
    assert!(
        second.x >= observed.objects[1].x && second.x - observed.objects[1].x <= 0.0035 + 1e-4,
        "{second:?}"
    );
}

/// A WAM configuration the propagation keeps (the tool within its tolerances of the
/// plane, 0.01 rad, 1 mm) with links 3 and 5 a hair apart: bringing the tool onto the
/// plane with a start's tight tolerance moves every joint by up to 6e-5 rad and presses
/// the two links into each other. Found by sampling (8 such states in 44,005 valid ones);
/// closed-loop trials stopped on such observations in both engines ("links 'wam_link3'
/// and 'wam_link5' collide", with no control cut short). The state is taken as observed.
#[test]
fn an_arm_the_propagation_keeps_is_not_refused_for_links_the_plane_projection_presses_together() {
    use pushplan_model::validity::check_arm;
    let mut scene = Scene::load("scenes/benchmark/scene_28.yaml").unwrap();
    // The arm alone: this configuration reaches where the scene's objects stand.
    scene.objects.clear();
    scene.start.objects.clear();
    let mut observed = scene.start.clone();
    observed.q = nalgebra::DVector::from_vec(vec![
        0.7872774016414651,
        1.110200294159824,
        -1.4571827296739812,
        2.9663658560877697,
        -0.2771109058069029,
        0.13319494585213104,
        1.9342809797866924,
    ]);
    let robot = &scene.robot;
    let (height, tilt) = robot
        .plane
        .error(&robot.tool_pose(&robot.link_poses(&observed.q)));
    assert!(
        height.abs() <= robot.projection.height_tolerance
            && tilt <= robot.projection.tilt_tolerance
            && tilt > 1e-3 * robot.projection.tilt_tolerance,
        "off the plane within the propagation's tolerance, beyond a start's: {height} m, {tilt} rad"
    );
    check_arm(&scene, &observed.q).expect("valid as observed");
    let mut on_plane = observed.q.clone();
    robot.start_on_plane(&mut on_plane).unwrap();
    let pressed = check_arm(&scene, &on_plane).unwrap_err().to_string();
    assert!(
        pressed.contains("'wam_link3' and 'wam_link5' collide"),
        "{pressed}"
    );

    let from = scene
        .with_start(&observed, Path::new("observed.json"))
        .unwrap();
    assert_eq!(from.start.q, observed.q);
}
