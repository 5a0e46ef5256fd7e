//! The weighted distance metric (Sec. III-D).

use nalgebra::DVector;
use pushplan_model::{DistanceMetric, Pose2, Scene, State};
use std::f64::consts::PI;

#[test]
fn the_metric_weights_robot_objects_and_the_goal_object() {
    let scene = Scene::load("scenes/herb_fig1_clutter.yaml").unwrap();
    let metric = DistanceMetric::from_scene(&scene);
    // green_box (index 0) is the goal object: weight 20 (the default); the others 1.
    assert_eq!(metric.object_weights, vec![20.0, 1.0, 1.0, 1.0]);
    let a = scene.start.clone();
    let mut b = a.clone();
    b.q[2] += 0.3;
    b.q[4] -= 0.4; // |dq| = 0.5
    b.objects[0].x += 0.03;
    b.objects[0].y += 0.04; // 0.05 m, weight 20
    b.objects[2].theta += 0.2; // 0.2 rad = 0.02 m, weight 1
    let expected = 1.0 * 0.5 + 20.0 * 0.05 + 1.0 * 0.02;
    assert!((metric.distance(&a, &b) - expected).abs() < 1e-12);
    assert!((metric.distance(&b, &a) - expected).abs() < 1e-12);
    assert_eq!(metric.distance(&a, &a), 0.0);
}

#[test]
fn object_angles_wrap_around() {
    let metric = DistanceMetric {
        robot_weight: 1.0,
        object_weights: vec![1.0],
        rotation_length: 1.0,
    };
    let near_pi = Pose2::new(0.0, 0.0, PI - 0.05);
    let near_minus_pi = Pose2::new(0.0, 0.0, -PI + 0.05);
    assert!((metric.object_distance(&near_pi, &near_minus_pi) - 0.1).abs() < 1e-12);
    let a = State {
        q: DVector::zeros(1),
        objects: vec![near_pi],
    };
    let b = State {
        q: DVector::zeros(1),
        objects: vec![near_minus_pi],
    };
    assert!((metric.distance(&a, &b) - 0.1).abs() < 1e-12);
}

#[test]
fn goals_measure_their_distance() {
    use pushplan_model::scene::Goal;
    let scene = Scene::load("scenes/herb_single_object.yaml").unwrap();
    // The box starts at (0.75, 0) and the disc is centred at (0.85, -0.25), r = 0.1; the
    // centre must end at least the default margin (0.06) inside the edge.
    let to_disc = (0.1f64.powi(2) + 0.25f64.powi(2)).sqrt() - 0.1;
    assert!((scene.goal.task_distance(&scene.start) - to_disc).abs() < 1e-12);
    assert!((scene.goal.distance(&scene.start) - (to_disc + 0.06)).abs() < 1e-12);
    assert!(!scene.goal.is_satisfied(&scene.start));
    let mut inside = scene.start.clone();
    inside.objects[0] = Pose2::new(0.87, -0.23, 1.0);
    assert!(scene.goal.is_satisfied(&inside));
    // In the disc but within the margin of its edge: the task is done, the goal not met.
    inside.objects[0] = Pose2::new(0.85 + 0.08, -0.25, 0.0);
    assert!(scene.goal.task_distance(&inside) < 0.0 && !scene.goal.is_satisfied(&inside));

    // A small disc keeps a target: the default margin is at most 60 % of its radius
    // (0.05 m: 0.03 m), and a margin the scene gives is taken as it is.
    let text = std::fs::read_to_string("scenes/herb_single_object.yaml").unwrap();
    let goal_line = "goal: {object: green_box, center: [0.85, -0.25], radius: 0.1}";
    // Half the radius: the disc's edge 0.05 m further off.
    let to_small_disc = to_disc + 0.05;
    for (goal, margin) in [
        ("radius: 0.05}", 0.03),
        ("radius: 0.05, margin: 0.01}", 0.01),
    ] {
        let small = text.replace(goal_line, &goal_line.replace("radius: 0.1}", goal));
        let scene = Scene::from_yaml(&small, std::path::Path::new("scenes/x.yaml")).unwrap();
        let distance = scene.goal.distance(&scene.start);
        assert!(
            (distance - (to_small_disc + margin)).abs() < 1e-12,
            "{goal}: {distance}"
        );
    }

    // A robot-configuration goal.
    let text = text.replace(
        goal_line,
        "goal: {configuration: [1.0, 0.9, -0.7, 1.8, 0.6, -0.4, 0.2], tolerance: 0.1}",
    );
    let scene = Scene::from_yaml(&text, std::path::Path::new("scenes/x.yaml")).unwrap();
    let Goal::Configuration { q, tolerance } = &scene.goal else {
        panic!("{:?}", scene.goal)
    };
    assert_eq!(*tolerance, 0.1);
    let mut at_goal = scene.start.clone();
    at_goal.q = q.clone();
    assert!(scene.goal.is_satisfied(&at_goal));
    assert!(
        (scene.goal.distance(&scene.start) - ((&scene.start.q - q).norm() - 0.1)).abs() < 1e-12
    );
}

#[test]
fn the_flat_distance_is_the_same_metric() {
    let scene = Scene::load("scenes/herb_fig1_clutter.yaml").unwrap();
    let metric = DistanceMetric::from_scene(&scene);
    let a = scene.start.clone();
    let mut b = a.clone();
    b.q[1] -= 0.2;
    b.objects[0] = Pose2::new(0.7, 0.1, -3.0);
    b.objects[3].theta = 3.1;
    let flat = State::to_flat;
    assert_eq!(
        metric.distance_flat(&flat(&a), &flat(&b)),
        metric.distance(&a, &b)
    );
}
