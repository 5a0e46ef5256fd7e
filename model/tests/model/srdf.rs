//! MoveIt SRDFs: `disable_collisions` pairs leave the self-collision checks, a chain group
//! names the arm (its tip the end effector, the joints above its base held), found beside
//! the URDF or named by the scene; what does not fit is an error naming the SRDF.

use crate::common::{self, HAND_NEAR};
use pushplan_model::robot::srdf::Srdf;
use pushplan_model::Scene;
use std::path::Path;

/// A WAM scene in `dir` (its URDF copied there as `wam7.urdf`), `robot_extra` added to
/// the robot's fields (after `start_joints`).
fn scene_yaml(start: &[f64], robot_extra: &str) -> String {
    format!(
        "robot:
  type: arm
  urdf: wam7.urdf
  base_pose: {{xyz: [0.1, 0.14, 0.346]}}
  start_joints: {start:?}
  pushing_plane: {{height: 0.08, orientation_rpy: [0, 2.0, 0]}}
{robot_extra}
table: {{height: 0.76, x: [0.27, 1.03], y: [-0.93, 0.93]}}
objects:
  - {{name: goal, shape: {{type: box, size: [0.102, 0.102, 0.215]}}, pose: [0.5, -0.6, 0.0], mass: 1.0, mu_g: 0.4, mu_c: 0.3}}
goal: {{object: goal, center: [0.7, -0.3], radius: 0.1}}"
    )
}

const SRDF: &str = r#"<?xml version="1.0"?>
<robot name="wam7">
  <group name="arm"><chain base_link="wam_base" tip_link="hand"/></group>
  <group name="forearm"><chain base_link="wam_link1" tip_link="hand"/></group>
  <group name="hand_only"><link name="hand"/></group>
  <group_state name="home" group="arm"><joint name="j1" value="0"/></group_state>
  <disable_collisions link1="wam_link3" link2="wam_link5" reason="Never"/>
  <disable_collisions link1="hand" link2="wam_link3" reason="Never"/>
</robot>
"#;

fn pair_checked(scene: &Scene, a: &str, b: &str) -> bool {
    let links = &scene.robot.chain.links;
    let index = |n: &str| links.iter().position(|l| l.name == n).unwrap();
    let (a, b) = (index(a), index(b));
    scene
        .robot
        .self_collision_pairs
        .contains(&(a.min(b), a.max(b)))
}

#[test]
fn an_srdf_beside_the_urdf_disables_its_pairs_and_names_the_arm() {
    let scratch = common::Scratch::new("test-srdf");
    let dir = scratch.path();
    std::fs::copy("robots/wam7.urdf", dir.join("wam7.urdf")).unwrap();
    let load = |name: &str, yaml: String| {
        let path = dir.join(name);
        std::fs::write(&path, yaml).unwrap();
        Scene::load(&path)
    };
    // Without an SRDF the scene must name its end effector, and checks both pairs.
    let plain = load("plain.yaml", scene_yaml(&HAND_NEAR, "  end_effector: hand")).unwrap();
    assert!(pair_checked(&plain, "wam_link3", "wam_link5"));
    assert!(pair_checked(&plain, "hand", "wam_link3"));
    let message = load("none.yaml", scene_yaml(&HAND_NEAR, ""))
        .unwrap_err()
        .to_string();
    assert!(message.contains("robot.end_effector: missing"), "{message}");

    std::fs::write(dir.join("wam7.srdf"), SRDF).unwrap();
    // Beside the URDF: two chain groups, so one must be named.
    let message = load("two.yaml", scene_yaml(&HAND_NEAR, ""))
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("robot.group")
            && message.contains("wam7.srdf")
            && message.contains("'arm', 'forearm'"),
        "{message}"
    );
    let arm = load("arm.yaml", scene_yaml(&HAND_NEAR, "  group: arm")).unwrap();
    assert_eq!(arm.robot.chain.links[arm.robot.ee_link].name, "hand");
    assert_eq!(arm.robot.dof(), 7);
    assert!(!pair_checked(&arm, "wam_link3", "wam_link5"));
    assert!(!pair_checked(&arm, "hand", "wam_link3"));
    assert_eq!(
        arm.robot.self_collision_pairs.len() + 2,
        plain.robot.self_collision_pairs.len()
    );
    // The same start, the same model otherwise: the start state is the plain scene's.
    assert_eq!(arm.start.q, plain.start.q);
    // A named end effector with the SRDF beside: its pairs still apply, no group needed.
    let named = load("named.yaml", scene_yaml(&HAND_NEAR, "  end_effector: hand")).unwrap();
    assert!(!pair_checked(&named, "wam_link3", "wam_link5"));
    assert_eq!(named.robot.dof(), 7);
    // A group whose chain starts above the first joint holds that joint (at 0): six values,
    // the first joint's link where it is at j1 = 0 whatever the start.
    let path = dir.join("forearm.yaml");
    std::fs::write(&path, scene_yaml(&HAND_NEAR[1..], "  group: forearm")).unwrap();
    let (forearm, _) = Scene::load_any_start(&path).unwrap();
    assert_eq!(forearm.robot.dof(), 6);
    let link1 = forearm.robot.chain.link_index("wam_link1").unwrap();
    let poses = forearm.robot.link_poses(&forearm.start.q);
    let at_zero = plain.robot.link_poses(&nalgebra::DVector::from_row_slice(&[
        0.0, 0.1, 0.0, 1.0, 0.0, 0.0, 0.0,
    ]));
    assert!((poses[link1].rotation.angle_to(&at_zero[link1].rotation)) < 1e-12);
    let message = load("seven.yaml", scene_yaml(&HAND_NEAR, "  group: forearm"))
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("7 values given") && message.contains("6 joints"),
        "{message}"
    );
    // Groups that are no chain, or not there.
    for (group, says) in [
        ("hand_only", "not given as a <chain>"),
        ("legs", "no group named 'legs'"),
    ] {
        let message = load(
            "g.yaml",
            scene_yaml(&HAND_NEAR, &format!("  group: {group}")),
        )
        .unwrap_err()
        .to_string();
        assert!(
            message.contains("robot.group") && message.contains(says),
            "{message}"
        );
    }
}

#[test]
fn an_srdf_named_by_the_scene_is_read_and_one_that_does_not_fit_is_an_error_naming_it() {
    let scratch = common::Scratch::new("test-srdf-named");
    let dir = scratch.path();
    std::fs::copy("robots/wam7.urdf", dir.join("wam7.urdf")).unwrap();
    let load = |srdf: &str| {
        std::fs::write(dir.join("other.srdf"), srdf).unwrap();
        let path = dir.join("s.yaml");
        std::fs::write(&path, scene_yaml(&HAND_NEAR, "  srdf: other.srdf")).unwrap();
        Scene::load(&path)
    };
    let one_group = SRDF.replace(
        r#"<group name="forearm"><chain base_link="wam_link1" tip_link="hand"/></group>"#,
        "",
    );
    let scene = load(&one_group).unwrap();
    assert_eq!(scene.robot.chain.links[scene.robot.ee_link].name, "hand");
    assert!(!pair_checked(&scene, "wam_link3", "wam_link5"));

    let foreign = one_group.replace(r#"link2="wam_link5""#, r#"link2="panda_link5""#);
    let message = load(&foreign).unwrap_err().to_string();
    assert!(
        message.contains("other.srdf")
            && message.contains("disable_collisions[0].link2")
            && message.contains("no link named 'panda_link5'"),
        "{message}"
    );
    for (broken, says) in [
        (
            "<robot><disable_collisions link1='hand'/></robot>",
            "needs a link2 attribute",
        ),
        ("<robot><group", "not XML"),
        ("<srdf/>", "not <robot>"),
    ] {
        let message = load(broken).unwrap_err().to_string();
        assert!(
            message.contains("other.srdf") && message.contains(says),
            "{broken}: {message}"
        );
    }
    let path = dir.join("missing.yaml");
    std::fs::write(&path, scene_yaml(&HAND_NEAR, "  srdf: nowhere.srdf")).unwrap();
    let message = Scene::load(&path).unwrap_err().to_string();
    assert!(
        message.contains("robot.srdf") && message.contains("nowhere.srdf"),
        "{message}"
    );
    let parsed = Srdf::parse(SRDF, Path::new("x.srdf")).unwrap();
    assert_eq!(parsed.groups.len(), 3);
    assert_eq!(parsed.disabled[1].reason.as_deref(), Some("Never"));
}
