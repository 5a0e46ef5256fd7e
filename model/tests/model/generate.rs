//! The benchmark scene generator (the paper's dataset design).

use crate::common;

use pushplan_model::scene::generate::{
    generate, generate_shipped, shipped_sets, Arm, Design, GOAL_CENTER, GOAL_RADIUS,
};
use pushplan_model::scene::Goal;
use pushplan_model::Scene;

/// A scene file's text without its URDF line (which depends on the output folder).
fn without_urdf(path: &std::path::Path) -> String {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.contains("urdf:"))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn generated_scenes_follow_the_dataset_design() {
    let scratch = common::Scratch::new("generate-generated_scenes_follow_the_dataset_design");
    let temp = |name: &str| scratch.join(name);
    let dir = temp("seven");
    let files = generate(Design::Paper, Arm::Wam, 7, (1, 7), 3, &dir).unwrap();
    let mut counts = Vec::new();
    let mut goal_starts = Vec::new();
    for file in &files {
        // Loading validates everything, the start state included.
        let scene = Scene::load(file).unwrap();
        counts.push(scene.objects.len());
        assert!(
            !scene.physics.object_pushing,
            "the paper's rule: objects keep apart"
        );
        let Goal::ObjectInDisc {
            object,
            center,
            radius,
            ..
        } = scene.goal
        else {
            panic!("object goal expected")
        };
        assert_eq!(
            (object, center.x, center.y, radius),
            (0, GOAL_CENTER[0], GOAL_CENTER[1], GOAL_RADIUS)
        );
        let goal = &scene.objects[0];
        assert_eq!(goal.name, "goal_box");
        assert!((goal.height - 0.215).abs() < 1e-12);
        let start = scene.start.objects[0];
        assert!(
            (start.translation() - center).norm() > GOAL_RADIUS,
            "the goal object starts outside the goal"
        );
        goal_starts.push(start);
    }
    assert_eq!(counts, vec![1, 2, 3, 4, 5, 6, 7]);
    assert!(
        goal_starts.windows(2).all(|w| w[0] != w[1]),
        "random goal-object start poses"
    );

    // Deterministic under the seed; another seed gives other scenes.
    let again = generate(Design::Paper, Arm::Wam, 7, (1, 7), 3, &temp("again")).unwrap();
    let other = generate(Design::Paper, Arm::Wam, 7, (1, 7), 4, &temp("other")).unwrap();
    assert!(files
        .iter()
        .zip(&again)
        .all(|(a, b)| without_urdf(a) == without_urdf(b)));
    assert!(files
        .iter()
        .zip(&other)
        .any(|(a, b)| without_urdf(a) != without_urdf(b)));
}

/// Scenes generated outside a project tree carry their robot with them (the built-in
/// WAM in `robots/` beside them); inside one they name the tree's identical copy.
#[test]
fn generated_scenes_name_a_robot_beside_them() {
    let scratch = common::Scratch::new("generate-generated_scenes_name_a_robot_beside_them");
    let dir = scratch.join("set");
    let files = generate(Design::Paper, Arm::Wam, 2, (1, 2), 1, &dir).unwrap();
    let text = std::fs::read_to_string(&files[0]).unwrap();
    assert!(text.contains("urdf: robots/wam7.urdf"), "{text}");
    assert_eq!(
        std::fs::read_to_string(dir.join("robots/wam7.urdf")).unwrap(),
        std::fs::read_to_string("robots/wam7.urdf").unwrap()
    );
    // Moved elsewhere as a folder, the set still loads.
    let moved = scratch.join("moved");
    std::fs::rename(&dir, &moved).unwrap();
    assert!(Scene::load(moved.join("scene_00.yaml")).is_ok());
    for committed in [
        "scenes/benchmark/scene_00.yaml",
        "scenes/dense/scene_00.yaml",
    ] {
        let text = std::fs::read_to_string(committed).unwrap();
        assert!(text.contains("urdf: ../../robots/wam7.urdf"), "{committed}");
    }
}

#[test]
fn the_committed_benchmark_set_is_what_the_command_generates() {
    let scratch =
        common::Scratch::new("generate-the_committed_benchmark_set_is_what_the_command_generates");
    let temp = |name: &str| scratch.join(name);
    let files = generate(Design::Paper, Arm::Wam, 35, (1, 7), 1, &temp("committed")).unwrap();
    for (i, file) in files.iter().enumerate() {
        let committed = std::path::PathBuf::from(format!("scenes/benchmark/scene_{i:02}.yaml"));
        assert_eq!(without_urdf(file), without_urdf(&committed), "{} differs: regenerate with `pushplan scenes generate --count 35 --objects 1..7 --seed 1 --out scenes/benchmark`", committed.display());
        assert!(Scene::load(&committed).is_ok());
    }
}

#[test]
fn bad_ranges_are_errors() {
    let scratch = common::Scratch::new("generate-bad_ranges_are_errors");
    let temp = |name: &str| scratch.join(name);
    assert!(
        generate(Design::Paper, Arm::Wam, 3, (0, 2), 1, &temp("bad"))
            .unwrap_err()
            .contains("range")
    );
    assert!(generate(Design::Paper, Arm::Wam, 3, (4, 2), 1, &temp("bad")).is_err());
}

#[test]
fn the_committed_dense_set_is_what_the_command_generates() {
    let scratch =
        common::Scratch::new("generate-the_committed_dense_set_is_what_the_command_generates");
    let temp = |name: &str| scratch.join(name);
    let files = generate(Design::Dense, Arm::Wam, 20, (8, 20), 1, &temp("dense")).unwrap();
    for (i, file) in files.iter().enumerate() {
        let committed = std::path::PathBuf::from(format!("scenes/dense/scene_{i:02}.yaml"));
        assert_eq!(without_urdf(file), without_urdf(&committed), "{} differs: regenerate with `pushplan scenes generate --design dense --count 20 --objects 8..20 --seed 1 --out scenes/dense`", committed.display());
    }
}

/// Distance (m) from `p` to the segment `a`-`b`.
fn to_segment(
    p: nalgebra::Vector2<f64>,
    a: nalgebra::Vector2<f64>,
    b: nalgebra::Vector2<f64>,
) -> f64 {
    let t = ((p - a).dot(&(b - a)) / (b - a).norm_squared()).clamp(0.0, 1.0);
    (a + t * (b - a) - p).norm()
}

#[test]
fn dense_scenes_are_dense_and_take_their_layouts_in_turn() {
    let scratch =
        common::Scratch::new("generate-dense_scenes_are_dense_and_take_their_layouts_in_turn");
    let temp = |name: &str| scratch.join(name);
    let files = generate(
        Design::Dense,
        Arm::Wam,
        9,
        (8, 20),
        5,
        &temp("dense-design"),
    )
    .unwrap();
    let mut counts = Vec::new();
    for (i, file) in files.iter().enumerate() {
        let scene = Scene::load(file).unwrap(); // valid, start state included
        counts.push(scene.objects.len());
        assert!(
            scene.physics.object_pushing,
            "dense clutter: objects push objects"
        );
        let goal_start = scene.start.objects[0].translation();
        let center = nalgebra::Vector2::new(GOAL_CENTER[0], GOAL_CENTER[1]);
        assert!((goal_start - center).norm() > GOAL_RADIUS + 0.15);
        let clutter = || {
            scene.objects[1..]
                .iter()
                .zip(&scene.start.objects[1..])
                .map(|(o, p)| (o.bounding_radius, p.translation()))
        };
        let text = std::fs::read_to_string(file).unwrap();
        match i % 3 {
            0 => assert!(text.contains("Scattered layout"), "{text}"),
            1 => {
                // Clutter overlaps the goal disc: it has to go before the goal object fits.
                assert!(text.contains("GoalCovered layout"));
                assert!(clutter().any(|(r, p)| (p - center).norm() < GOAL_RADIUS + r));
            }
            _ => {
                // The straight route of the goal box (half-width 0.051 m) is blocked.
                assert!(text.contains("Walled layout"));
                let blocked =
                    clutter().filter(|(r, p)| to_segment(*p, goal_start, center) < r + 0.051);
                assert!(blocked.count() >= 1, "{}", file.display());
            }
        }
    }
    assert_eq!(counts, vec![8, 9, 10, 12, 13, 15, 16, 18, 19]);
    assert!(
        generate(Design::Dense, Arm::Wam, 2, (8, 21), 1, &temp("bad"))
            .unwrap_err()
            .contains("1..20")
    );
    assert!(
        generate(Design::Paper, Arm::Wam, 2, (8, 13), 1, &temp("bad"))
            .unwrap_err()
            .contains("placed designs place up to 20")
    );
}

#[test]
fn the_committed_arm_sets_are_what_the_command_generates() {
    let scratch = common::Scratch::new("generate-the_committed_arm_sets");
    let files = generate_shipped(scratch.path()).unwrap();
    let sets = shipped_sets();
    assert_eq!(files.len(), sets.iter().map(|s| s.count).sum::<usize>());
    // Four arms, five designs each (the WAM's paper and dense sets have folders of their own).
    assert_eq!(sets.len(), 4 * 5 - 2);
    for file in &files {
        let relative = file.strip_prefix(scratch.path()).unwrap();
        let committed = std::path::Path::new("scenes").join(relative);
        assert_eq!(
            without_urdf(file),
            without_urdf(&committed),
            "{} differs: regenerate with `pushplan scenes generate --shipped --out scenes`",
            committed.display()
        );
    }
}

/// The committed scenes of `arm`'s `design`, loaded.
fn committed(arm: Arm, design: Design) -> Vec<Scene> {
    let set = shipped_sets()
        .into_iter()
        .find(|s| s.arm == arm && s.design == design)
        .unwrap();
    (0..set.count)
        .map(|i| {
            let path = std::path::Path::new("scenes")
                .join(set.folder())
                .join(format!("scene_{i:02}.yaml"));
            Scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
        })
        .collect()
}

fn goal_disc(scene: &Scene) -> (nalgebra::Vector2<f64>, f64) {
    match scene.goal {
        Goal::ObjectInDisc { center, radius, .. } => (center, radius),
        _ => panic!("object goal expected"),
    }
}

#[test]
fn every_arm_has_an_occupied_goal_at_the_far_edge_in_every_other_scene() {
    use pushplan_model::collision::footprint::gap;
    use pushplan_model::physics::Footprint;
    for arm in Arm::ALL {
        let scenes = committed(arm, Design::OccupiedGoal);
        for (i, scene) in scenes.iter().enumerate() {
            let (center, radius) = goal_disc(scene);
            let disc = Footprint::Circle { radius };
            let at = pushplan_model::Pose2::new(center.x, center.y, 0.0);
            let on_disc = (1..scene.objects.len())
                .filter(|&k| {
                    gap(
                        &disc,
                        &at,
                        &scene.objects[k].footprint,
                        &scene.start.objects[k],
                    ) <= 0.0
                })
                .count();
            assert!(
                (1..=4).contains(&on_disc),
                "{} scene {i}: {on_disc} on the disc",
                arm.name()
            );
            assert!(scene.physics.object_pushing);
            // The far disc lies nearer the table's far edge than the usual one.
            let near_edge = scene.table.x.1 - center.x < 0.15;
            assert_eq!(
                near_edge,
                i % 2 == 1,
                "{} scene {i}: disc at {center}",
                arm.name()
            );
        }
    }
}

#[test]
fn every_arm_has_walls_with_a_narrow_passage_and_objects_of_mixed_heights() {
    for arm in Arm::ALL {
        for scene in committed(arm, Design::Walls) {
            assert_eq!(scene.obstacles.len(), 2, "{}", scene.name);
            let (a, b) = (&scene.obstacles[0].pose, &scene.obstacles[1].pose);
            // Two 0.3 m walls on one line: the passage is their centres' distance less 0.3.
            let passage = (a.translation.vector - b.translation.vector).xy().norm() - 0.3;
            assert!(
                (0.20 - 1e-9..=0.26 + 1e-9).contains(&passage),
                "{}: {passage}",
                scene.name
            );
            // Standing on the table.
            assert!((a.translation.z - (scene.table.top + 0.06)).abs() < 1e-9);
        }
        let kinds: Vec<String> = committed(arm, Design::MixedHeights)
            .iter()
            .flat_map(|s| s.objects.iter().map(|o| o.name.clone()))
            .collect();
        for kind in ["tall_bottle", "plate", "low_box"] {
            assert!(
                kinds.iter().any(|n| n.starts_with(kind)),
                "{}: no {kind} in the mixed heights set",
                arm.name()
            );
        }
    }
}
