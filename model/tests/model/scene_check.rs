//! The scene check (`scene::check`): each warning where the scene asks the impossible,
//! with numbers from closed forms computed here, and none on the shipped scenes.

use crate::common::HAND_NEAR;
use nalgebra::Vector2;
use pushplan_model::physics::tipping::{sliding_push_tips, ContactElevation};
use pushplan_model::physics::{Footprint, PlanarContact};
use pushplan_model::scene::check::{check, goal_object_beyond_reach};
use pushplan_model::scene::SceneWarning;
use pushplan_model::Scene;
use std::path::Path;

/// A planar hand (its tool point `height` above the table) and the goal object `shape`
/// (mu_g 0.4) at `pose`; other objects in `others` (YAML list items); the goal disc of
/// radius 0.1 (margin 0.03) at `center`.
fn hand_scene(shape: &str, pose: [f64; 3], height: f64, center: [f64; 2], others: &str) -> Scene {
    let yaml = format!(
        "robot:
  type: planar_hand
  shape: {{type: box, size: [0.04, 0.12, 0.01]}}
  start: [0.3, -0.5, 0.0]
  height: {height}
table: {{height: 0.76, x: [0.27, 1.03], y: [-0.6, 0.6]}}
objects:
  - {{name: goal, shape: {shape}, pose: {pose:?}, mass: 1.0, mu_g: 0.4, mu_c: 0.3}}
{others}
goal: {{object: goal, center: {center:?}, radius: 0.1, margin: 0.03}}"
    );
    Scene::from_yaml(&yaml, Path::new("scenes/check-test.yaml")).unwrap()
}

const SQUARE_BOX: &str = "{type: box, size: [0.08, 0.08, 0.15]}";

fn tipping(warnings: &[SceneWarning]) -> Vec<&SceneWarning> {
    warnings
        .iter()
        .filter(|w| matches!(w, SceneWarning::TipsAtPlaneHeight { .. }))
        .collect()
}

#[test]
fn half_widths_are_the_levers_about_the_footprints_edges() {
    let rectangle = Footprint::Polygon {
        vertices: vec![
            Vector2::new(-0.05, -0.1),
            Vector2::new(0.05, -0.1),
            Vector2::new(0.05, 0.1),
            Vector2::new(-0.05, 0.1),
        ],
    };
    let (least, greatest) = rectangle.half_widths();
    assert!((least - 0.05).abs() < 1e-12 && (greatest - 0.1).abs() < 1e-12);
    // A right triangle with legs of 0.3: centroid (0.1, 0.1), 0.1 from each leg and
    // |0.1 + 0.1 - 0.3| / sqrt(2) from the hypotenuse.
    let triangle = Footprint::Polygon {
        vertices: vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(0.3, 0.0),
            Vector2::new(0.0, 0.3),
        ],
    };
    let (least, greatest) = triangle.half_widths();
    assert!((least - 0.1 / 2f64.sqrt()).abs() < 1e-12, "{least}");
    assert!((greatest - 0.1).abs() < 1e-12, "{greatest}");
    assert_eq!(
        Footprint::Circle { radius: 0.04 }.half_widths(),
        (0.04, 0.04)
    );
}

#[test]
fn a_plane_above_b_over_mu_g_warns_that_the_tool_tips_the_object() {
    // 8 x 8 cm box, mu_g 0.4: a push that slides it tips it above 0.04 / 0.4 = 0.1 m.
    let low = hand_scene(SQUARE_BOX, [0.6, 0.0, 0.0], 0.09, [0.85, 0.3], "");
    assert!(tipping(&check(&low)).is_empty(), "{:?}", check(&low));
    let high = hand_scene(SQUARE_BOX, [0.6, 0.0, 0.0], 0.11, [0.85, 0.3], "");
    let warnings = check(&high);
    let found = tipping(&warnings);
    assert_eq!(found.len(), 1, "{warnings:?}");
    match found[0] {
        SceneWarning::TipsAtPlaneHeight {
            object,
            goal_object,
            plane_height,
            half_width,
            every_side,
            ..
        } => {
            assert_eq!(object, "goal");
            assert!(*goal_object && *every_side);
            assert!((plane_height - 0.11).abs() < 1e-9 && (half_width - 0.04).abs() < 1e-9);
        }
        _ => unreachable!(),
    }
    assert!(
        found[0].blocks(),
        "a goal object tipped from every side cannot be pushed"
    );
    let text = found[0].to_string();
    assert!(
        text.contains("0.100 m") && text.contains("0.110 m"),
        "{text}"
    );

    // The model's own moment balance agrees on either side of the closed form: a face-on
    // push through the centre line, sliding the box, at 0.09 and 0.11 m.
    let footprint = &high.objects[0].footprint;
    let contact = PlanarContact {
        point: Vector2::new(-0.04, 0.0),
        normal: Vector2::new(1.0, 0.0),
        pusher_velocity: Vector2::new(0.1, 0.0),
        gap: 0.0,
    };
    let at = |height| ContactElevation { height, slope: 0.0 };
    assert!(!sliding_push_tips(
        1.0,
        0.4,
        footprint,
        &contact,
        &at(0.09),
        0.0
    ));
    assert!(sliding_push_tips(
        1.0,
        0.4,
        footprint,
        &contact,
        &at(0.11),
        0.0
    ));
}

#[test]
fn a_plane_between_the_narrow_and_the_wide_sides_tipping_heights_warns_without_blocking() {
    // 8 x 16 cm: tipping heights 0.1 m (toward a long side) and 0.2 m (toward a short one).
    let scene = hand_scene(
        "{type: box, size: [0.16, 0.08, 0.3]}",
        [0.6, 0.0, 0.0],
        0.15,
        [0.85, 0.3],
        "",
    );
    let warnings = check(&scene);
    let found = tipping(&warnings);
    assert_eq!(found.len(), 1, "{warnings:?}");
    assert!(matches!(
        found[0],
        SceneWarning::TipsAtPlaneHeight {
            every_side: false,
            ..
        }
    ));
    assert!(!found[0].blocks());
}

#[test]
fn an_object_lower_than_the_plane_is_passed_over_not_tipped() {
    let scene = hand_scene(
        "{type: box, size: [0.08, 0.08, 0.05]}",
        [0.6, 0.0, 0.0],
        0.11,
        [0.85, 0.3],
        "",
    );
    assert!(tipping(&check(&scene)).is_empty());
}

#[test]
fn a_goal_region_on_the_tables_edge_is_measured_against_the_circular_segment() {
    // A disc of radius R = 0.05 stands wholly on the table only with its centre 0.05 from
    // the edge (y <= 0.55). The goal region (r = 0.07 about y = 0.58) past that line is a
    // circular segment: its area over pi r^2 is the share.
    let scene = hand_scene(
        "{type: cylinder, radius: 0.05, height: 0.1}",
        [0.6, 0.0, 0.0],
        0.05,
        [0.85, 0.58],
        "",
    );
    let (r, d): (f64, f64) = (0.07, 0.03);
    let beyond = r * r * (-d / r).acos() + d * (r * r - d * d).sqrt();
    let expected = beyond / (std::f64::consts::PI * r * r);
    let warnings = check(&scene);
    let share = warnings
        .iter()
        .find_map(|w| match w {
            SceneWarning::GoalOverTableEdge { share } => Some(*share),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no edge warning: {warnings:?}"));
    assert!((share - expected).abs() < 0.02, "{share} vs {expected}");
    assert!(expected > 0.5 && expected < 0.9, "{expected}");

    let inside = hand_scene(
        "{type: cylinder, radius: 0.05, height: 0.1}",
        [0.6, 0.0, 0.0],
        0.05,
        [0.85, 0.3],
        "",
    );
    assert!(!check(&inside)
        .iter()
        .any(|w| matches!(w, SceneWarning::GoalOverTableEdge { .. })));
}

#[test]
fn objects_on_the_goal_disc_are_named_with_the_room_left() {
    let bowl = |x: f64, y: f64| {
        format!(
            "  - {{name: bowl, shape: {{type: cylinder, radius: 0.08, height: 0.06}}, pose: [{x}, {y}, 0], mass: 0.5, mu_g: 0.4, mu_c: 0.3}}"
        )
    };
    let on_goal = |scene: &Scene| {
        check(scene).into_iter().find_map(|w| match w {
            SceneWarning::ObjectsOnGoal {
                objects,
                free_share,
            } => Some((objects, free_share)),
            _ => None,
        })
    };
    // On the goal's centre: the goal box (half-width 0.051) needs 0.08 + 0.051 + the
    // clearance from it, more than the region's 0.07 radius leaves anywhere.
    let centred = hand_scene(
        SQUARE_BOX,
        [0.5, -0.3, 0.0],
        0.05,
        [0.85, 0.3],
        &bowl(0.85, 0.3),
    );
    let (objects, free) = on_goal(&centred).expect("a bowl on the goal's centre is named");
    assert_eq!(objects, ["bowl"]);
    assert_eq!(free, 0.0);
    // Overlapping the disc's edge: some of the region is free, not all.
    let edge = hand_scene(
        SQUARE_BOX,
        [0.5, -0.3, 0.0],
        0.05,
        [0.85, 0.3],
        &bowl(0.85, 0.45),
    );
    let (_, free) = on_goal(&edge).expect("a bowl over the disc's edge is named");
    assert!(free > 0.0 && free < 1.0, "{free}");
    // Away from it: no warning.
    let away = hand_scene(
        SQUARE_BOX,
        [0.5, -0.3, 0.0],
        0.05,
        [0.85, 0.3],
        &bowl(0.5, 0.2),
    );
    assert!(on_goal(&away).is_none());
}

#[test]
fn a_goal_object_already_in_the_region_is_said() {
    let scene = hand_scene(SQUARE_BOX, [0.85, 0.3, 0.0], 0.05, [0.85, 0.3], "");
    assert!(check(&scene).contains(&SceneWarning::GoalReachedAtStart));
}

/// The WAM mounted low (its base 0.346 m up, under a table 2.6 m deep) starting with its
/// hand near the table, the goal box at `pose` (yaw 0) and the goal disc (radius 0.1) at
/// `center`: the reach tests' scene.
fn low_wam_scene(pose: [f64; 2], center: [f64; 2]) -> Scene {
    let yaml = format!(
        "robot:
  type: arm
  urdf: ../robots/wam7.urdf
  base_pose: {{xyz: [0.1, 0.14, 0.346]}}
  end_effector: hand
  start_joints: {HAND_NEAR:?}
  pushing_plane: {{height: 0.08, orientation_rpy: [0, 2.0, 0]}}
table: {{height: 0.76, x: [0.27, 2.6], y: [-0.93, 0.93]}}
objects:
  - {{name: goal, shape: {{type: box, size: [0.102, 0.102, 0.215]}}, pose: [{}, {}, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}}
goal: {{object: goal, center: {center:?}, radius: 0.1}}",
        pose[0], pose[1]
    );
    Scene::from_yaml(&yaml, Path::new("scenes/reach-test.yaml")).unwrap()
}

#[test]
fn a_goal_beyond_the_arms_reach_is_out_of_reach_and_one_within_it_is_not() {
    // The WAM's shoulder is 0.346 m above its base; upper arm, forearm and hand reach
    // about 1.1 m. On a table 2.6 m deep, (0.7, -0.3) is within reach, (2.5, 0) is not, nor
    // is (0.85, -0.6) with the arm mounted this low (`pushplan robot --reach` finds no
    // configuration there at any of 13 headings with 200 tries each).
    let scene = |center: [f64; 2]| low_wam_scene([0.5, -0.6], center);
    let out_of_reach = |center| {
        check(&scene(center))
            .into_iter()
            .find(|w| matches!(w, SceneWarning::GoalOutOfReach { .. }))
    };
    assert_eq!(out_of_reach([0.7, -0.3]), None);
    for center in [[2.5, 0.0], [0.85, -0.6]] {
        let out = out_of_reach(center).unwrap_or_else(|| panic!("{center:?} reached"));
        assert!(out.blocks());
        let named = format!("({:.3}, {:.3})", center[0], center[1]);
        assert!(out.to_string().contains(&named), "{out}");
    }
}

#[test]
fn the_shipped_scenes_ask_nothing_the_robot_cannot_do() {
    // Tipping and reach: none on any shipped scene, for every arm (objects on the goal
    // disc are part of some designs, the occupied goal's far disc reaches the edge, and
    // goal objects the hand cannot get behind are the hard scenes: 34, dense 06 and 19,
    // 16 of the 114 in the arms' sets).
    let mut folders: Vec<std::path::PathBuf> = [
        "scenes",
        "scenes/benchmark",
        "scenes/dense",
        "scenes/workshop",
    ]
    .iter()
    .map(std::path::PathBuf::from)
    .collect();
    for set in pushplan_model::scene::generate::shipped_sets() {
        folders.push(std::path::Path::new("scenes").join(set.folder()));
    }
    let mut scenes: Vec<std::path::PathBuf> = Vec::new();
    for folder in folders {
        for entry in std::fs::read_dir(folder).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "yaml") {
                scenes.push(path);
            }
        }
    }
    assert!(scenes.len() > 170, "{}", scenes.len());
    for path in scenes {
        let scene = Scene::load(&path).unwrap();
        let wrong: Vec<SceneWarning> = check(&scene)
            .into_iter()
            .filter(|w| {
                !matches!(
                    w,
                    SceneWarning::ObjectsOnGoal { .. }
                        | SceneWarning::GoalObjectBehindOutOfReach { .. }
                        | SceneWarning::GoalOverTableEdge { share: ..0.5 }
                )
            })
            .collect();
        assert!(wrong.is_empty(), "{}: {wrong:?}", path.display());
    }
}

#[test]
fn a_goal_object_the_hand_cannot_get_behind_is_named_and_one_it_can_is_not() {
    // The WAM of the reach test above, the goal disc at (0.7, -0.3) (within reach). The
    // goal object is placed so that the point behind it (away from the goal centre, its
    // bounding radius and the hand's reach from its centre) is (a) the start's own tool
    // point, which a configuration (the start) puts there, and (b) 2.4 m from the base,
    // beyond the arm's whole length (shoulder 0.346 m up, about 1.1 m of links).
    let center = Vector2::new(0.7, -0.3);
    let scene = |pose: Vector2<f64>| low_wam_scene([pose.x, pose.y], [center.x, center.y]);
    let behind = |scene: &Scene| {
        check(scene)
            .into_iter()
            .find(|w| matches!(w, SceneWarning::GoalObjectBehindOutOfReach { .. }))
    };
    let probe = scene(Vector2::new(0.5, 0.3));
    let robot = &probe.robot;
    let p_wt = robot
        .tool_pose(&robot.link_poses(&probe.start.q))
        .translation
        .vector
        .xy();
    let standoff = probe.objects[0].bounding_radius + robot.tool_reach();
    // (a) The object between the start's tool point and the goal, `standoff` short of the
    // tool point: the hand stands behind it where it starts.
    let toward_goal = (center - p_wt).normalize();
    let near = scene(p_wt + toward_goal * standoff);
    assert_eq!(behind(&near), None);
    // (b) The object 1.5 m along x from the goal: the point behind it is out of reach.
    let far = scene(Vector2::new(2.2, -0.3));
    let warning = behind(&far).expect("the point behind is beyond the arm's length");
    let SceneWarning::GoalObjectBehindOutOfReach {
        point, standoff: s, ..
    } = &warning
    else {
        unreachable!()
    };
    assert!((s - standoff).abs() < 1e-12);
    assert!(
        (point - Vector2::new(2.2 + standoff, -0.3)).norm() < 1e-9,
        "{point}"
    );
    assert!((point - Vector2::new(0.1, 0.14)).norm() > 2.2);
    // A warning that the search is slow, not that it cannot work.
    assert!(!warning.blocks());
    assert!(warning.to_string().contains("'goal'"), "{warning}");
}

#[test]
fn a_goal_object_that_must_come_in_from_beyond_the_reach_is_told_from_one_within() {
    // The low WAM of the reach tests (shoulder 0.346 m above its base at (0.1, 0.14), about
    // 1.1 m of links; its first joint turns about the base's vertical axis). The start
    // with that joint turned by 0.6 rad puts the tool point 0.6 rad round the base from
    // the start's: a witness that the point is within reach, found without inverse
    // kinematics. A goal object there, its goal disc halfway to the base, must come in.
    let p_wbase = Vector2::new(0.1, 0.14);
    let probe = low_wam_scene([0.5, 0.3], [0.7, -0.3]);
    let robot = &probe.robot;
    let tool_point = |q: &nalgebra::DVector<f64>| {
        robot
            .tool_pose(&robot.link_poses(q))
            .translation
            .vector
            .xy()
    };
    let mut turned = probe.start.q.clone();
    turned[0] -= 0.6;
    let from_base = tool_point(&probe.start.q) - p_wbase;
    let within = p_wbase + nalgebra::Rotation2::new(-0.6) * from_base;
    assert!((tool_point(&turned) - within).norm() < 1e-9);
    let beyond = |pose: Vector2<f64>, center: Vector2<f64>| {
        goal_object_beyond_reach(&low_wam_scene([pose.x, pose.y], [center.x, center.y]))
    };
    assert!(!beyond(within, p_wbase + (within - p_wbase) * 0.5));
    // 2.2 m out along x, past the arm's whole length: beyond reach, and it must come in.
    let far = Vector2::new(2.3, 0.14);
    assert!(beyond(far, Vector2::new(0.7, 0.14)));
    // The same object with the goal disc farther out still: it goes outward, as pushes from
    // its near side send it.
    assert!(!beyond(far, Vector2::new(2.5, 0.14)));
}
