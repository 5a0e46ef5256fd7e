//! `Scene::with_start`: a state observed while a plan runs becomes the start as a scene
//! file's start would: checked, an arm's tool brought onto its pushing plane, yaws
//! wrapped, and a wrong one refused with the file and field named.

use pushplan_model::{Error, Scene};
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
    // The box where the arm's base stands: not a valid start.
    let inside = refused(&|s| {
        s.objects[0].x = 0.1;
        s.objects[0].y = 0.14;
    });
    assert!(matches!(&inside, Error::InvalidStart { .. }), "{inside}");
}
