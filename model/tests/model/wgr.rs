//! Workspace Goal Regions (issue 15, first part): the displacement convention against
//! nalgebra's own Euler angles, samples inside their bounds, the distance zero inside and
//! growing outside as the lecture defines it, and configurations sampled by inverse
//! kinematics that are valid and reach the region.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use pushplan_model::random::SplitMix64;
use pushplan_model::robot::wgr::{displacement, displacement_transform, Wgr};
use pushplan_model::validity::check_state;
use pushplan_model::{Scene, State};

/// A region whose frame and grasp offset both turn, so that frames matter.
fn region() -> Wgr {
    Wgr {
        x_0w: Isometry3::from_parts(
            Translation3::new(0.7, -0.2, 0.9),
            UnitQuaternion::from_euler_angles(0.1, -0.3, 1.2),
        ),
        x_se: Isometry3::from_parts(
            Translation3::new(0.0, 0.0, -0.08),
            UnitQuaternion::from_euler_angles(0.0, std::f64::consts::FRAC_PI_2, 0.0),
        ),
        bounds: [
            (-0.02, 0.02),
            (-0.01, 0.03),
            (0.0, 0.05),
            (0.0, 0.0),
            (-0.1, 0.1),
            (-std::f64::consts::PI, std::f64::consts::PI),
        ],
    }
}

#[test]
fn displacements_follow_the_lectures_convention() {
    let mut rng = SplitMix64::new(3);
    for _ in 0..1000 {
        let d = [
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-1.0, 1.0),
            rng.uniform(-3.1, 3.1),
            rng.uniform(-1.5, 1.5),
            rng.uniform(-3.1, 3.1),
        ];
        let x = displacement_transform(&d);
        let back = displacement(&x);
        // nalgebra's roll, pitch, yaw of the same rotation: another implementation.
        let (roll, pitch, yaw) = x.rotation.euler_angles();
        for (i, (a, b)) in back.iter().zip(&d).enumerate() {
            assert!((a - b).abs() < 1e-9, "coordinate {i}: {a} against {b}");
        }
        assert!((back[3] - roll).abs() < 1e-9 && (back[4] - pitch).abs() < 1e-9);
        assert!((back[5] - yaw).abs() < 1e-9);
    }
}

#[test]
fn samples_lie_in_the_region_and_the_distance_grows_outside_it() {
    let wgr = region();
    let mut rng = SplitMix64::new(7);
    for _ in 0..1000 {
        let d = wgr.sample_displacement(&mut rng);
        for (v, (lo, hi)) in d.iter().zip(&wgr.bounds) {
            assert!(v >= lo && v <= hi, "{v} outside [{lo}, {hi}]");
        }
        let pose = wgr.end_effector_pose(&d);
        assert!(wgr.distance_from_pose(&pose) < 1e-9);
    }

    // Outside: beyond x_max by 0.05 m in w's frame, beyond pitch's bound by 0.2 rad.
    let inside = [0.0, 0.0, 0.02, 0.0, 0.0, 0.5];
    let mut beyond_x = inside;
    beyond_x[0] = 0.02 + 0.05;
    assert!((wgr.distance_from_pose(&wgr.end_effector_pose(&beyond_x)) - 0.05).abs() < 1e-9);
    let mut beyond_pitch = inside;
    beyond_pitch[4] = -0.1 - 0.2;
    assert!((wgr.distance_from_pose(&wgr.end_effector_pose(&beyond_pitch)) - 0.2).abs() < 1e-9);
    let mut both = beyond_x;
    both[4] = beyond_pitch[4];
    let expected = (0.05f64.powi(2) + 0.2f64.powi(2)).sqrt();
    assert!((wgr.distance_from_pose(&wgr.end_effector_pose(&both)) - expected).abs() < 1e-9);

    // By hand: w at the origin turned a quarter about z, no grasp offset, x in
    // [-0.01, 0.01]: an end effector 0.05 m along world y is 0.05 m along w's x, 0.04 m
    // beyond the bound.
    let simple = Wgr {
        x_0w: Isometry3::from_parts(
            Translation3::identity(),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2),
        ),
        x_se: Isometry3::identity(),
        bounds: [
            (-0.01, 0.01),
            (0.0, 0.0),
            (0.0, 0.0),
            (0.0, 0.0),
            (0.0, 0.0),
            (-4.0, 4.0),
        ],
    };
    let pose = Isometry3::from_parts(
        Translation3::new(0.0, 0.05, 0.0),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.3),
    );
    assert!((simple.distance_from_pose(&pose) - 0.04).abs() < 1e-12);
}

/// A region above the table in front of the WAM, the hand tilted as the pushing plane
/// holds it, free to turn about the vertical: inverse kinematics lands on valid
/// configurations inside it.
#[test]
fn sampled_configurations_are_valid_and_reach_the_region() {
    let scene = Scene::load("scenes/herb_single_object.yaml").unwrap();
    let robot = &scene.robot;
    let wgr = Wgr {
        x_0w: Isometry3::from_parts(
            Translation3::new(0.6, 0.3, scene.table.top + 0.12),
            UnitQuaternion::identity(),
        ),
        x_se: Isometry3::from_parts(Translation3::identity(), robot.plane.orientation),
        bounds: [
            (-0.02, 0.02),
            (-0.02, 0.02),
            (-0.01, 0.01),
            (0.0, 0.0),
            (0.0, 0.0),
            (-0.3, 0.3),
        ],
    };
    let valid = |q: &nalgebra::DVector<f64>| {
        check_state(
            &scene,
            &State {
                q: q.clone(),
                objects: scene.start.objects.clone(),
            },
        )
        .is_ok()
    };
    let mut rng = SplitMix64::new(1);
    let mut found = 0;
    for _ in 0..5 {
        if let Some(q) = wgr.sample_configuration(robot, &scene.start.q, &mut rng, 20, valid) {
            assert!(valid(&q));
            assert!(
                wgr.distance(robot, &q) < 1e-4,
                "{}",
                wgr.distance(robot, &q)
            );
            found += 1;
        }
    }
    assert!(found >= 3, "only {found} of 5 regions' samples reached");
    // The start configuration is not in the region: its distance is positive.
    assert!(wgr.distance(robot, &scene.start.q) > 0.01);
}

/// Grasp regions in a scene file: side grasps of the goal box, the hand's approach axis
/// (its z) horizontal toward the box, free to go round it. The region follows the object;
/// malformed bounds name their field.
#[test]
fn scenes_give_objects_grasp_regions() {
    let text = std::fs::read_to_string("scenes/herb_single_object.yaml").unwrap();
    let grasps = "    grasps:
      - frame: {xyz: [0, 0, 0.1075]}
        end_effector: {xyz: [-0.131, 0, 0], rpy: [0, 1.5707963267948966, 0]}
        bounds: {z: [-0.03, 0.03], yaw: [-3.141592653589793, 3.141592653589793]}
";
    let with = text.replace("    mu_c: 0.3\n", &format!("    mu_c: 0.3\n{grasps}"));
    assert_ne!(with, text);
    let scene = Scene::from_yaml(&with, std::path::Path::new("scenes/x.yaml")).unwrap();
    let object = &scene.objects[0];
    assert_eq!(object.grasps.len(), 1);
    let region = object.grasps[0].region(&scene.start.objects[0], scene.table.top);
    // The box at (0.75, 0) on the table top: at zero displacement the hand's centre is
    // 0.131 m before the box's side-centre plane, at 0.1075 m up, its z pointing at it.
    let pose = region.end_effector_pose(&[0.0; 6]);
    let p = pose.translation.vector;
    let expected = Vector3::new(0.75 - 0.131, 0.0, scene.table.top + 0.1075);
    assert!((p - expected).norm() < 1e-9, "{p:?}");
    assert!(((pose.rotation * Vector3::z()) - Vector3::x()).norm() < 1e-9);
    assert!(region.distance_from_pose(&pose) < 1e-12);
    // From the other side (yaw pi) it is in the region too; 5 cm too high is 2 cm out.
    let behind = region.end_effector_pose(&[0.0, 0.0, 0.0, 0.0, 0.0, 3.0]);
    assert!(region.distance_from_pose(&behind) < 1e-12);
    let high = region.end_effector_pose(&[0.0, 0.0, 0.05, 0.0, 0.0, 0.0]);
    assert!((region.distance_from_pose(&high) - 0.02).abs() < 1e-9);

    for (bounds, field) in [
        ("{z: [0.03, -0.03]}", "objects[0].grasps[0].bounds.z"),
        ("{yaw: [-4, 0]}", "objects[0].grasps[0].bounds.yaw"),
        ("{x: [0, .nan]}", "objects[0].grasps[0].bounds.x"),
    ] {
        let bad = text.replace(
            "    mu_c: 0.3\n",
            &format!("    mu_c: 0.3\n    grasps: [{{bounds: {bounds}}}]\n"),
        );
        let message = Scene::from_yaml(&bad, std::path::Path::new("scenes/x.yaml"))
            .unwrap_err()
            .to_string();
        assert!(message.contains(field), "{message}");
    }
}
