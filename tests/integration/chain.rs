//! Objects pushing objects (`physics::chain`) against Newton's laws for sliding rows and
//! against the single-object model (tested on its own against closed forms) where an
//! object without friction of its own only passes the arm's push on.

use nalgebra::{Vector2, Vector3};
use pushplan::physics::{
    cluster_motion, object_motion, ClusterContact, LimitSurface, PlanarContact, Pusher,
};

const DT: f64 = 0.01;
const G: f64 = 9.81;

/// A body's limit surface, its centre of friction in the world frame.
fn body(centre: [f64; 2], mass: f64, mu_g: f64) -> LimitSurface {
    LimitSurface {
        c: 0.038,
        f_max: mu_g * mass * G,
        centre: Vector2::new(centre[0], centre[1]),
    }
}

fn contact(
    body: usize,
    pusher: Pusher,
    point: [f64; 2],
    normal: [f64; 2],
    mu: f64,
) -> ClusterContact {
    ClusterContact {
        body,
        pusher,
        point: Vector2::new(point[0], point[1]),
        normal: Vector2::new(normal[0], normal[1]).normalize(),
        gap: 0.0,
        mu,
    }
}

/// A flat pusher moving along +x behind box A (half-width 0.05 m, at the origin), box B
/// face to face in front of it: both boxes slide at the pusher's speed without turning;
/// B is pushed with its own sliding friction `mu_g m g` and the pusher carries both.
fn row(mass_b: f64, mu_b: f64) {
    let v = Vector2::new(0.1, 0.0);
    let (mass_a, mu_a) = (1.0, 0.4);
    let bodies = [
        body([0.0, 0.0], mass_a, mu_a),
        body([0.1, 0.0], mass_b, mu_b),
    ];
    let arm = Pusher::Moving(v);
    let contacts = [
        contact(0, arm, [-0.05, -0.03], [1.0, 0.0], 0.5),
        contact(0, arm, [-0.05, 0.03], [1.0, 0.0], 0.5),
        contact(1, Pusher::Body(0), [0.05, -0.04], [1.0, 0.0], 0.5),
        contact(1, Pusher::Body(0), [0.05, 0.04], [1.0, 0.0], 0.5),
    ];
    let m = cluster_motion(&bodies, &contacts, DT).unwrap();
    for twist in &m.twists {
        assert!(
            (twist - Vector3::new(0.1, 0.0, 0.0)).norm() < 1e-9,
            "{twist:?}"
        );
    }
    let pusher: f64 = m.normal_forces[..2].iter().sum();
    let between: f64 = m.normal_forces[2..].iter().sum();
    let (f_a, f_b) = (mu_a * mass_a * G, mu_b * mass_b * G);
    assert!((between - f_b).abs() < 1e-6 * f_b, "{between} != {f_b}");
    assert!(
        (pusher - (f_a + f_b)).abs() < 1e-6 * f_a,
        "{pusher} != {}",
        f_a + f_b
    );
    assert!(m.friction_forces.iter().all(|f| f.abs() < 1e-9));
}

#[test]
fn a_pushed_row_slides_together_and_the_pusher_carries_both_frictions() {
    row(1.0, 0.4);
}

#[test]
fn a_heavier_box_ahead_takes_its_own_friction_from_the_one_behind() {
    row(2.5, 0.3);
}

#[test]
fn an_object_without_friction_passes_the_push_on_as_the_arm_would() {
    // A nearly weightless box A held by a grippy pusher (mu 2, sticks) pushes a cylinder
    // B (radius 0.05 m) at one point, obliquely, so friction at the touch turns B; A-B
    // friction 0.3. B must move as the single-object model moves it when the pusher
    // touches B directly at that point.
    let v = Vector2::new(0.1, 0.06);
    let (b_centre, mu) = ([0.1, 0.0], 0.3);
    let bodies = [body([0.0, 0.0], 1e-3, 0.4), body(b_centre, 1.0, 0.4)];
    let arm = Pusher::Moving(v);
    let between = [[0.05, 0.0]];
    let contacts = [
        contact(0, arm, [-0.05, -0.04], [1.0, 0.0], 2.0),
        contact(0, arm, [-0.05, 0.04], [1.0, 0.0], 2.0),
        contact(1, Pusher::Body(0), between[0], [1.0, 0.0], mu),
    ];
    let chain = cluster_motion(&bodies, &contacts, DT).unwrap();

    let direct: Vec<PlanarContact> = between
        .iter()
        .map(|p| PlanarContact {
            point: Vector2::new(p[0] - b_centre[0], p[1] - b_centre[1]),
            normal: Vector2::new(1.0, 0.0),
            pusher_velocity: v,
            gap: 0.0,
        })
        .collect();
    let surface = LimitSurface {
        centre: Vector2::zeros(),
        ..bodies[1]
    };
    let alone = object_motion(&direct, &surface, mu, DT).unwrap().twist;
    let want = Vector3::new(alone.vx, alone.vy, alone.omega);
    assert!(want.z.abs() > 0.1, "the off-centre push turns B: {want:?}");
    assert!(
        (chain.twists[1] - want).norm() < 1e-2 * want.norm(),
        "{:?} != {want:?}",
        chain.twists[1]
    );
    // A moves with the pusher (it sticks).
    assert!((chain.twists[0] - Vector3::new(v.x, v.y, 0.0)).norm() < 1e-3);
}

#[test]
fn a_box_pushed_away_from_its_neighbour_leaves_it_behind() {
    let v = Vector2::new(-0.1, 0.0);
    let bodies = [body([0.0, 0.0], 1.0, 0.4), body([0.1, 0.0], 1.0, 0.4)];
    let contacts = [
        // The pusher pulls nothing: it pushes A's front face towards -x.
        contact(0, Pusher::Moving(v), [0.05, 0.0], [-1.0, 0.0], 0.5),
        contact(1, Pusher::Body(0), [0.05, 0.0], [1.0, 0.0], 0.5),
    ];
    let m = cluster_motion(&bodies, &contacts, DT).unwrap();
    assert!((m.twists[0] - Vector3::new(-0.1, 0.0, 0.0)).norm() < 1e-9);
    assert_eq!(m.twists[1], Vector3::zeros());
    assert_eq!(m.normal_forces[1], 0.0);
}

#[test]
fn a_box_squeezed_between_opposing_pushes_jams() {
    // A pushed at +x into B while B is pushed at -x into A: nothing satisfies both.
    let bodies = [body([0.0, 0.0], 1.0, 0.4), body([0.1, 0.0], 1.0, 0.4)];
    let contacts = [
        contact(
            0,
            Pusher::Moving(Vector2::new(0.1, 0.0)),
            [-0.05, 0.0],
            [1.0, 0.0],
            0.5,
        ),
        contact(
            1,
            Pusher::Moving(Vector2::new(-0.1, 0.0)),
            [0.15, 0.0],
            [-1.0, 0.0],
            0.5,
        ),
        contact(1, Pusher::Body(0), [0.05, -0.04], [1.0, 0.0], 0.5),
        contact(1, Pusher::Body(0), [0.05, 0.04], [1.0, 0.0], 0.5),
    ];
    assert!(cluster_motion(&bodies, &contacts, DT).is_err());
}

#[test]
fn a_box_pushed_into_another_moves_both_as_the_3d_engine_does() {
    use nalgebra::DVector;
    use pushplan::planning::execute::rapier::RapierWorld;
    use pushplan::planning::execute::Engine;
    use pushplan::planning::path::{simulate, PathControl};
    use pushplan::{EeAction, Propagator, Scene};
    use std::path::Path;
    // A flat hand (8 cm wide) pushes box A 0.15 m along +x into box B, which stands 2 mm
    // ahead and 7 cm to the side: B is pushed off its centre and turns (by 1.2 rad). The
    // 3D engine (rapier, objects as free bodies) is the oracle: within 12 mm and 0.05 rad
    // (8 mm and 0.013 rad when written).
    let scene = |object_pushing: bool| {
        let yaml = format!(
            "robot: {{type: planar_hand, shape: {{type: box, size: [0.01, 0.08, 0.03]}}, \
               start: [0.414, 0.0, 0.0], height: 0.05}}
table: {{height: 0.76, x: [0.27, 1.03], y: [-0.6, 0.6]}}
objects:
  - {{name: a, shape: {{type: box, size: [0.1, 0.1, 0.1]}}, pose: [0.47, 0.0, 0.0], \
      mass: 1.0, mu_g: 0.4, mu_c: 0.3}}
  - {{name: b, shape: {{type: box, size: [0.1, 0.1, 0.1]}}, pose: [0.572, 0.07, 0.0], \
      mass: 1.0, mu_g: 0.4, mu_c: 0.3}}
goal: {{object: b, center: [0.9, 0.3], radius: 0.1}}
physics: {{object_pushing: {object_pushing}}}"
        );
        Scene::from_yaml(&yaml, Path::new("tests/push-a-row.yaml")).unwrap()
    };
    let control = PathControl {
        action: EeAction::planar(0.1, 0.0, 0.0),
        steps: 150,
    };
    let rigid = scene(false);
    let path = simulate(
        &mut Propagator::new(&rigid),
        &rigid.start,
        std::slice::from_ref(&control),
        true,
    );
    assert!(!path.valid(), "without object pushing the touch is invalid");

    let pushing = scene(true);
    let path = simulate(
        &mut Propagator::new(&pushing),
        &pushing.start,
        &[control],
        true,
    );
    assert!(path.valid(), "{:?}", path.stopped_by);
    let end = path.final_state();
    let joints: Vec<DVector<f64>> = path.step_states.iter().map(|s| s.q.clone()).collect();
    let mut poses = Vec::new();
    pushing
        .robot
        .chain
        .forward_kinematics(&joints[0], &mut poses);
    let mut world = RapierWorld::new(&pushing, &pushing.start.objects, &poses);
    world.follow(&pushing.robot.chain, &joints, pushing.planner.step);
    for i in 0..2 {
        let (model, engine) = (end.objects[i], world.object_pose2(i));
        let start = pushing.start.objects[i];
        let travel = (engine.translation() - start.translation()).norm();
        assert!(travel > 0.05, "object {i} moved {travel} m in 3D");
        let off = (model.translation() - engine.translation()).norm();
        let turn = pushplan::math::wrap_angle(model.theta - engine.theta).abs();
        assert!(
            off < 0.012 && turn < 0.05,
            "object {i}: model {model:?}, engine {engine:?} ({:.1} mm, {turn:.3} rad apart)",
            1e3 * off
        );
    }
    assert!(
        world.object_pose2(1).theta.abs() > 0.5,
        "B turns in 3D: {:?}",
        world.object_pose2(1)
    );
}
