//! The weighted distance metric (Sec. III-D).

use nalgebra::DVector;
use pushplan::{DistanceMetric, Pose2, Scene, State};
use std::f64::consts::PI;

#[test]
fn the_metric_weights_robot_objects_and_the_goal_object() {
    let scene = Scene::load("scenes/herb_fig1_clutter.yaml").unwrap();
    let metric = DistanceMetric::from_scene(&scene);
    // green_box (index 0) is the goal object: weight 5; the others 1.
    assert_eq!(metric.object_weights, vec![5.0, 1.0, 1.0, 1.0]);
    let a = scene.start.clone();
    let mut b = a.clone();
    b.q[2] += 0.3;
    b.q[4] -= 0.4; // |dq| = 0.5
    b.objects[0].x += 0.03;
    b.objects[0].y += 0.04; // 0.05 m, weight 5
    b.objects[2].theta += 0.2; // 0.2 rad = 0.02 m, weight 1
    let expected = 1.0 * 0.5 + 5.0 * 0.05 + 1.0 * 0.02;
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
