//! The carry of a Push: the caged object moves along a straight line in SE(2), rigidly
//! with the tool, whose configuration follows by inverse kinematics step by step.

use super::{hand_links, Cage, PrimitiveFailure};
use crate::contact::arm_contacts;
use crate::math::{wrap_angle, Pose2};
use crate::robot::IkSettings;
use crate::state::State;
use crate::validity::{check_arm, check_arm_contacts, check_objects, Invalid};
use crate::Scene;

/// The longest object translation of one carry step (m).
pub const CARRY_STEP: f64 = 0.01;
/// The largest object rotation of one carry step (rad).
pub const CARRY_TURN: f64 = 0.05;
/// The largest joint motion of one carry step (rad, or m): more means the inverse
/// kinematics jumped (a singularity or another branch), not a continuous motion.
pub const CARRY_MAX_JOINT_STEP: f64 = 0.2;

/// The number of equal steps a carry from `from` to `to` takes.
pub fn carry_steps(from: &Pose2, to: &Pose2) -> usize {
    let travel = (to.translation() - from.translation()).norm() / CARRY_STEP;
    let turn = wrap_angle(to.theta - from.theta).abs() / CARRY_TURN;
    (travel.max(turn).ceil() as usize).max(1)
}

/// Carries the object of `cage` from its pose in `state` to `target` along a straight
/// line. `state` must hold the object in that cage (its hand where [`super::approach`]
/// put it). Returns the state after each step, the last with the object at `target`.
pub fn carry(
    scene: &Scene,
    state: &State,
    cage: &Cage,
    target: &Pose2,
) -> Result<Vec<State>, PrimitiveFailure> {
    let robot = &scene.robot;
    let from = state.objects[cage.object];
    let steps = carry_steps(&from, target);
    let settings = IkSettings::default();
    let mut states: Vec<State> = Vec::with_capacity(steps);
    let mut current = state.clone();
    for k in 1..=steps {
        let pose = from.lerp(target, k as f64 / steps as f64);
        let tool = robot.plane.tool_pose_at(&cage.tool_for(&pose));
        let q = robot
            .reach_tool_pose(&tool, &current.q, &settings)
            .ok_or(PrimitiveFailure::Unreachable)?;
        let (joint, step) = (&q - &current.q).abs().argmax();
        if step > CARRY_MAX_JOINT_STEP {
            return Err(PrimitiveFailure::JointJump { joint, step });
        }
        current.q = q;
        current.objects[cage.object] = pose;
        check_carrying(scene, &current, cage.object)?;
        states.push(current.clone());
    }
    Ok(states)
}

/// State validity while the hand carries `object`: every rule of
/// [`crate::validity::check_state`] except that the hand may overlap the object it cages.
pub fn check_carrying(scene: &Scene, state: &State, object: usize) -> Result<(), Invalid> {
    let (poses, bounds) = check_arm(scene, &state.q)?;
    let mut contacts = arm_contacts(
        scene,
        &poses,
        &bounds,
        &state.objects,
        scene.physics.contact_margin,
    );
    let hand = hand_links(&scene.robot);
    contacts.retain(|c| !(c.object == object && hand.contains(&c.link)));
    check_arm_contacts(scene, &contacts)?;
    check_objects(scene, &state.objects, |i| i == object)
}
