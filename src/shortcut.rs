//! Path shortcutting (Sec. IV, Fig. 3 of the whole-arm paper).
//!
//! Repeatedly pick two states of the path, connect only their robot configurations by a
//! new constrained action (the end effector moves in a straight line along the plane
//! between the two end-effector poses; the null-space sample pulls the joints towards
//! the second configuration), propagate it through the physics, re-propagate every
//! remaining control from the new state, and keep the result when every state is valid,
//! the goal is still reached and the manipulator path is shorter (joint space).
//!
//! The budget is counted in propagation steps, not wall-clock time, so shortcutting is
//! deterministic under its seed; [`STEPS_PER_SECOND`] converts the user's seconds.

use crate::math::wrap_angle;
use crate::path::{simulate, PathControl, PathMetrics, SimulatedPath};
use crate::propagate::Propagator;
use crate::random::SplitMix64;
use crate::robot::EeAction;
use crate::state::State;
use nalgebra::DVector;
use std::time::Instant;

/// Propagation steps one second of shortcutting buys (about what this machine does:
/// see BENCHMARKS.md).
pub const STEPS_PER_SECOND: f64 = 200_000.0;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShortcutSettings {
    /// Work budget in propagation steps.
    pub budget_steps: u64,
    pub seed: u64,
    /// Wall-clock time at which shortcutting stops even if budget is left (the plan's
    /// time limit). Only then does the outcome depend on the machine's speed.
    pub deadline: Option<Instant>,
}

impl ShortcutSettings {
    /// A budget of about `seconds` of work.
    pub fn from_seconds(seconds: f64, seed: u64) -> Self {
        Self {
            budget_steps: (seconds.max(0.0) * STEPS_PER_SECOND) as u64,
            seed,
            deadline: None,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct ShortcutOutcome {
    pub controls: Vec<PathControl>,
    pub before: PathMetrics,
    pub after: PathMetrics,
    pub attempts: usize,
    pub accepted: usize,
    /// Shortcutting stopped at the deadline, with budget left.
    pub stopped_at_deadline: bool,
}

/// Shortcuts a valid path from `start` that reaches the scene's goal.
pub fn shortcut(
    propagator: &mut Propagator,
    start: &State,
    controls: &[PathControl],
    settings: &ShortcutSettings,
) -> ShortcutOutcome {
    let scene = propagator.shared_scene();
    let mut current = controls.to_vec();
    let mut path = simulate(propagator, start, &current, false);
    let before = path.metrics;
    let mut outcome = ShortcutOutcome {
        controls: vec![],
        before,
        after: before,
        attempts: 0,
        accepted: 0,
        stopped_at_deadline: false,
    };
    if !path.valid() || !scene.goal.is_satisfied(path.final_state()) {
        outcome.controls = current;
        return outcome;
    }
    let mut rng = SplitMix64::new(settings.seed ^ 0x5EED_5407_C0DE);
    let mut work = path.steps() as u64;
    while work < settings.budget_steps && current.len() >= 2 {
        if settings.deadline.is_some_and(|d| Instant::now() >= d) {
            outcome.stopped_at_deadline = true;
            break;
        }
        outcome.attempts += 1;
        // Two states i < j at least two controls apart; controls i..j are replaced.
        let n = current.len();
        let i = rng.below(n - 1);
        let j = i + 2 + rng.below(n - i - 1);
        let Some(connect) = connecting_control(propagator, &path, i, j) else {
            continue;
        };
        let mut candidate = current[..i].to_vec();
        candidate.push(connect);
        candidate.extend_from_slice(&current[j..]);
        let tail = simulate(propagator, &path.states[i], &candidate[i..], false);
        work += tail.steps() as u64 + 1;
        let length = path.joint_length_at[i] + tail.metrics.joint_length;
        if tail.valid()
            && scene.goal.is_satisfied(tail.final_state())
            && length < path.metrics.joint_length - 1e-9
        {
            current = candidate;
            path = simulate(propagator, start, &current, false);
            work += path.steps() as u64;
            outcome.accepted += 1;
        }
    }
    outcome.after = path.metrics;
    outcome.controls = current;
    outcome
}

/// The action that moves the end effector in a straight line (and turns it) from its pose
/// in state `i` to its pose in state `j` at the scene's speed bounds, pulling the joints
/// towards state `j`'s configuration through the null space.
fn connecting_control(
    propagator: &Propagator,
    path: &SimulatedPath,
    i: usize,
    j: usize,
) -> Option<PathControl> {
    let scene = propagator.scene();
    let robot = &scene.robot;
    let (a, b) = (&path.states[i], &path.states[j]);
    let (ta, tb) = (
        robot.tool_pose(&robot.link_poses(&a.q)),
        robot.tool_pose(&robot.link_poses(&b.q)),
    );
    let yaw = |t: &nalgebra::Isometry3<f64>| {
        (t.rotation * robot.plane.orientation.inverse())
            .euler_angles()
            .2
    };
    let (dx, dy) = (
        tb.translation.x - ta.translation.x,
        tb.translation.y - ta.translation.y,
    );
    let dyaw = wrap_angle(yaw(&tb) - yaw(&ta));
    let p = &scene.planner;
    let time = (dx.abs().max(dy.abs()) / p.max_ee_speed).max(dyaw.abs() / p.max_ee_turn_rate);
    let steps = ((time / p.step).ceil() as usize).max(1);
    let duration = steps as f64 * p.step;
    let pull: DVector<f64> = (&b.q - &a.q) / duration;
    pull.iter().all(|v| v.is_finite()).then(|| PathControl {
        action: EeAction {
            velocity: [dx / duration, dy / duration, dyaw / duration],
            nullspace: pull,
        },
        steps,
    })
}
