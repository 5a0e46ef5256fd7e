//! Forward kinematics against hand-computed poses, Jacobians against finite differences,
//! and the constraint projection (issue points 4 and 5).

use crate::common;
use nalgebra::{DVector, Isometry3, Point3, Vector3};

use pushplan_model::robot::urdf::load_urdf;
use pushplan_model::robot::{EeAction, KinematicChain, ProjectionFailure};
use pushplan_model::Scene;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::Path;

fn chain(file: &str, ee: &str) -> KinematicChain {
    load_urdf(Path::new(file), ee, Isometry3::identity()).unwrap()
}

fn random_q(chain: &KinematicChain, rng: &mut ChaCha8Rng) -> DVector<f64> {
    DVector::from_iterator(
        chain.dof(),
        chain
            .limits()
            .into_iter()
            .map(|(lo, hi)| rng.random_range(lo..hi)),
    )
}

#[test]
fn wam_at_zero_points_straight_up() {
    let wam = chain("robots/wam7.urdf", "hand");
    assert_eq!(wam.dof(), 7);
    let mut poses = Vec::new();
    wam.forward_kinematics(&DVector::zeros(7), &mut poses);
    let hand = poses[wam.link_index("hand").unwrap()];
    // 0.346 (base to shoulder) + 0.55 (upper arm) + 0.3 (forearm) + 0.14 (to hand centre);
    // the elbow offsets of +0.045 and -0.045 cancel.
    assert!((hand.translation.vector - Vector3::new(0.0, 0.0, 1.336)).norm() < 1e-12);
    assert!(hand.rotation.angle() < 1e-12);
    let elbow = poses[wam.link_index("wam_link4").unwrap()];
    assert!((elbow.translation.vector - Vector3::new(0.045, 0.0, 0.896)).norm() < 1e-12);
}

#[test]
fn wam_elbow_at_right_angle_puts_the_forearm_horizontal() {
    let wam = chain("robots/wam7.urdf", "hand");
    let mut poses = Vec::new();
    let mut q = DVector::zeros(7);
    q[3] = std::f64::consts::FRAC_PI_2;
    wam.forward_kinematics(&q, &mut poses);
    // j4 turns about the elbow's axis (world -y at zero): the forearm swings to +x.
    // Wrist = elbow + Ry(pi/2) (-0.045, 0, 0.3) = (0.045 + 0.3, 0, 0.896 + 0.045).
    let wrist = poses[wam.link_index("wam_link6").unwrap()];
    assert!(
        (wrist.translation.vector - Vector3::new(0.345, 0.0, 0.941)).norm() < 1e-9,
        "{:?}",
        wrist.translation
    );
}

#[test]
fn panda_at_zero_has_its_flange_at_the_published_position() {
    let panda = chain("robots/panda7.urdf", "tool");
    assert_eq!(panda.dof(), 7);
    let mut poses = Vec::new();
    panda.forward_kinematics(&DVector::zeros(7), &mut poses);
    let flange = poses[panda.link_index("panda_hand").unwrap()];
    // x = 0.0825 - 0.0825 + 0.088; z = 0.333 + 0.316 + 0.384 - 0.107, pointing down.
    assert!(
        (flange.translation.vector - Vector3::new(0.088, 0.0, 0.926)).norm() < 1e-9,
        "{:?}",
        flange.translation
    );
    assert!((flange.rotation * Vector3::z() - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-9);
}

#[test]
fn jacobians_match_finite_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for (file, ee) in [("robots/wam7.urdf", "hand"), ("robots/panda7.urdf", "tool")] {
        let c = chain(file, ee);
        let mut poses = Vec::new();
        let mut shifted = Vec::new();
        for _ in 0..50 {
            let q = random_q(&c, &mut rng);
            c.forward_kinematics(&q, &mut poses);
            // A point rigidly attached to a random link, off its origin.
            let link = rng.random_range(1..c.links.len());
            let local = Point3::new(
                rng.random_range(-0.1..0.1),
                rng.random_range(-0.1..0.1),
                rng.random_range(-0.1..0.1),
            );
            let jac = c.point_jacobian(&poses, link, &(poses[link] * local));
            let h = 1e-6;
            for i in 0..c.dof() {
                let mut qp = q.clone();
                qp[i] += h;
                let mut qm = q.clone();
                qm[i] -= h;
                c.forward_kinematics(&qp, &mut shifted);
                let (pp, rp) = (shifted[link] * local, shifted[link].rotation);
                c.forward_kinematics(&qm, &mut shifted);
                let (pm, rm) = (shifted[link] * local, shifted[link].rotation);
                let linear = (pp - pm) / (2.0 * h);
                let angular = (rp * rm.inverse()).scaled_axis() / (2.0 * h);
                for r in 0..3 {
                    assert!(
                        (jac[(r, i)] - linear[r]).abs() < 1e-7,
                        "{file} link {link} joint {i}"
                    );
                    assert!(
                        (jac[(3 + r, i)] - angular[r]).abs() < 1e-7,
                        "{file} link {link} joint {i}"
                    );
                }
            }
        }
    }
}

#[test]
fn projected_random_actions_keep_the_hand_on_its_plane() {
    let scene = Scene::load("scenes/herb_single_object.yaml").unwrap();
    let robot = &scene.robot;
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut q = scene.start.q.clone();
    let mut poses = robot.link_poses(&q);
    let (mut q_new, mut poses_new) = (q.clone(), Vec::new());
    let (mut taken, mut worst_height, mut worst_tilt) = (0, 0.0f64, 0.0f64);
    let mut action = EeAction::planar(0.0, 0.0, 0.0);
    for step in 0..1000 {
        if step % 20 == 0 {
            // A new random action (with a null-space sample) every 20 steps.
            action = EeAction {
                velocity: [
                    rng.random_range(-0.5..0.5),
                    rng.random_range(-0.5..0.5),
                    rng.random_range(-1.0..1.0),
                ],
                nullspace: DVector::from_fn(7, |_, _| rng.random_range(-0.5..0.5)),
            };
        }
        let ok = robot
            .project_step(&q, &poses, &action, 0.01, &mut q_new, &mut poses_new)
            .is_ok()
            && robot.chain.within_limits(&q_new).is_ok();
        if !ok {
            action.velocity = action.velocity.map(|v| -v); // turn back from limits and singularities
            continue;
        }
        q.copy_from(&q_new);
        std::mem::swap(&mut poses, &mut poses_new);
        taken += 1;
        let (h, t) = robot.plane.error(&robot.tool_pose(&poses));
        worst_height = worst_height.max(h.abs());
        worst_tilt = worst_tilt.max(t);
    }
    assert!(taken > 800, "only {taken} of 1000 steps were taken");
    assert!(worst_height < 1e-3, "height error {worst_height}");
    assert!(worst_tilt < 0.01, "tilt error {worst_tilt}");
}

#[test]
fn the_projected_tool_follows_the_commanded_velocity() {
    let scene = Scene::load("scenes/herb_single_object.yaml").unwrap();
    let robot = &scene.robot;
    let q = scene.start.q.clone();
    let poses = robot.link_poses(&q);
    let (mut q_new, mut poses_new) = (q.clone(), Vec::new());
    let action = EeAction::planar(0.2, -0.1, 0.3);
    robot
        .project_step(&q, &poses, &action, 0.01, &mut q_new, &mut poses_new)
        .unwrap();
    let (before, after) = (robot.tool_pose(&poses), robot.tool_pose(&poses_new));
    let moved = after.translation.vector - before.translation.vector;
    assert!(
        (moved.x - 0.002).abs() < 2e-5 && (moved.y + 0.001).abs() < 2e-5 && moved.z.abs() < 2e-5
    );
    let yaw = (after.rotation * before.rotation.inverse()).scaled_axis().z;
    assert!((yaw - 0.003).abs() < 1e-4);
}

#[test]
fn leaving_joint_limits_makes_the_step_invalid() {
    use pushplan_model::Invalid;
    // The planar hand's x joint spans the table, x in [0.27, 1.03]; it starts at x = 0.4.
    let scene = Scene::load("scenes/planar_hand_single_object.yaml").unwrap();
    let mut propagator = pushplan_model::Propagator::new(&scene);
    let run = propagator.propagate(&scene.start, &EeAction::planar(-0.3, 0.0, 0.0), 1.0);
    assert!(
        matches!(run.stopped_by, Some(Invalid::JointLimit { ref joint, .. }) if joint == "x"),
        "{:?}",
        run.stopped_by
    );
    // The last valid state is within a step (3 mm) of the limit.
    assert!(run.state.q[0] >= 0.27 && run.state.q[0] < 0.27 + 0.003 + 1e-9);

    // The arm: turning the hand on the spot about the vertical winds the wrist until a
    // joint reaches its limit.
    let scene = common::herb_scene(common::HAND_NEAR, &common::parked_goal(), "").unwrap();
    let mut propagator = pushplan_model::Propagator::new(&scene);
    for w in [1.0, -1.0] {
        let run = propagator.propagate(&scene.start, &EeAction::planar(0.0, 0.0, w), 6.0);
        assert!(
            matches!(run.stopped_by, Some(Invalid::JointLimit { .. })),
            "{:?}",
            run.stopped_by
        );
        assert!(run.steps > 0 && scene.robot.chain.within_limits(&run.state.q).is_ok());
    }
}

#[test]
fn non_finite_actions_are_refused_not_panicked_on() {
    use pushplan_model::Invalid;
    let scene = Scene::load("scenes/herb_single_object.yaml").unwrap();
    let mut propagator = pushplan_model::Propagator::new(&scene);
    for action in [
        EeAction::planar(f64::NAN, 0.0, 0.0),
        EeAction::planar(0.0, f64::INFINITY, 0.0),
        EeAction {
            velocity: [0.1, 0.0, 0.0],
            nullspace: DVector::from_element(7, f64::NAN),
        },
    ] {
        let run = propagator.propagate(&scene.start, &action, 0.1);
        assert_eq!(run.steps, 0);
        assert_eq!(
            run.stopped_by,
            Some(Invalid::Projection(
                pushplan_model::robot::ProjectionFailure::NotFinite
            ))
        );
        assert_eq!(run.state, scene.start);
    }
    // A NaN configuration is refused too.
    let mut broken = scene.start.clone();
    broken.q[2] = f64::NAN;
    let run = propagator.propagate(&broken, &EeAction::planar(0.1, 0.0, 0.0), 0.1);
    assert_eq!(run.steps, 0);
    assert!(run.stopped_by.is_some());
}

#[test]
fn the_tool_reaches_as_far_as_the_end_effector_it_is_fixed_to() {
    // The Panda's, the UR5e's and the iiwa's tool frames are links of their own, without
    // geometry, fixed below the pusher that carries it; the WAM's is its hand's centre.
    // Each pusher is a box centred on the tool's axis: it meets an object as far from the
    // tool point as its bounding sphere's radius, half its diagonal (box sizes from the
    // URDFs). The wrist flanges rigidly above them are narrower.
    let half_diagonal = |x: f64, y: f64, z: f64| 0.5 * (x * x + y * y + z * z).sqrt();
    for (arm, pusher) in [
        ("iiwa14", half_diagonal(0.12, 0.12, 0.15)),
        ("ur5e", half_diagonal(0.09, 0.09, 0.15)),
        ("panda", half_diagonal(0.06, 0.2, 0.08)),
        ("wam", half_diagonal(0.08, 0.12, 0.16)),
    ] {
        let scene = Scene::load(format!("scenes/{arm}/walls/scene_00.yaml")).unwrap();
        let reach = scene.robot.tool_reach();
        assert!(
            (reach - pusher).abs() < 1e-9,
            "{arm}: the tool reaches {reach} m, its pusher {pusher} m"
        );
    }
}

/// When (s) the hand, pushed at `velocity` (m/s, rad/s; world frame) from the scene's
/// start in steps of `dt`, is first refused as singular (`None`: not within 3 s), and how
/// often a joint turned back from one step to the next above 1 rad/s on the way.
fn time_to_singular(scene: &Scene, velocity: [f64; 3], dt: f64) -> (Option<f64>, usize) {
    let robot = &scene.robot;
    let mut q = scene.start.q.clone();
    let mut poses = robot.link_poses(&q);
    let (mut q_new, mut poses_new) = (q.clone(), Vec::new());
    let action = EeAction::planar(velocity[0], velocity[1], velocity[2]);
    let mut last: Option<DVector<f64>> = None;
    let mut reversals = 0;
    for n in 0..(3.0 / dt).round() as usize {
        match robot.project_step(&q, &poses, &action, dt, &mut q_new, &mut poses_new) {
            Ok(()) => {}
            Err(ProjectionFailure::JointTooFast { .. }) => return (Some(n as f64 * dt), reversals),
            Err(e) => panic!("dt {dt}: step {n}: {e}"),
        }
        let dq = &q_new - &q;
        if let Some(before) = &last {
            reversals += (0..dq.len())
                .filter(|&j| dq[j] * before[j] < 0.0 && dq[j].abs().min(before[j].abs()) / dt > 1.0)
                .count();
        }
        last = Some(dq);
        std::mem::swap(&mut q, &mut q_new);
        std::mem::swap(&mut poses, &mut poses_new);
    }
    (None, reversals)
}

/// A singularity is where the joints must move too fast, whatever the step: the hand
/// driven out to where the arm stretches straight is refused at the same moment at 10 ms,
/// 1 ms and 0.1 ms steps (within two 10 ms steps), and never chatters on the way. With a
/// limit per step (0.05 rad), 0.1 ms steps allowed 500 rad/s: a search on
/// `tests/data/fine_steps.yaml` kept a path whose joints turned back every step at up to
/// 190 rad/s for 0.14 s, which a real arm cannot follow (its trajectory, slowed to the
/// URDF limits, took 5948 s and its plan file 167 MB).
#[test]
fn a_singularity_stops_the_hand_at_the_same_moment_at_any_step() {
    let scene = Scene::load("scenes/herb_single_object.yaml").unwrap();
    for velocity in [[0.2, 0.0, 0.0], [0.0, 0.2, 0.0]] {
        let (coarse, _) = time_to_singular(&scene, velocity, 0.01);
        let coarse = coarse.expect("the outward push reaches a singularity within 3 s");
        for dt in [0.001, 0.0001] {
            let (fine, reversals) = time_to_singular(&scene, velocity, dt);
            let fine = fine.unwrap_or(f64::INFINITY);
            assert!(
                (fine - coarse).abs() <= 0.02 + 1e-9,
                "{velocity:?}: singular at {coarse} s in 10 ms steps, at {fine} s in {dt} s steps"
            );
            assert_eq!(reversals, 0, "{velocity:?}, {dt} s steps");
        }
    }
}
