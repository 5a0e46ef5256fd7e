//! The check of a DARRT path: every step is a Transit motion or a step of a Push, from
//! the scene's start; and its measures (those of PC RRT's paths, for the benchmark).

use super::carry::{carry_steps, check_carrying, CARRY_MAX_JOINT_STEP};
use super::transit::{check_transit, transit_segments};
use super::Cage;
use crate::path::PathMetrics;
use crate::state::State;
use crate::trajectory::joint_motion_time;
use crate::Scene;
use nalgebra::DVector;

/// How far the grip of a carried object may drift between steps (m, and rad): the inverse
/// kinematics is solved to 1e-5.
const GRIP_TOLERANCE: f64 = 1e-4;

/// A checked DARRT path.
#[derive(Clone, Debug, PartialEq)]
pub struct PrimitivePath {
    /// Joint length, tool travel, object displacement, objects moved; `links_in_contact`
    /// is the hand's links if the path carries an object; `duration` is the time at the
    /// joints' velocity limits.
    pub metrics: PathMetrics,
    /// Time (s) of each step at the joints' velocity limits.
    pub durations: Vec<f64>,
    pub goal_reached: bool,
}

/// Checks `states` as a DARRT path: it starts at the scene's start; between consecutive
/// states either no object moves and the arm's straight line is a valid Transit, or one
/// object moves by at most one carry step, held in the same cage, and the new state is
/// valid for carrying it with the tool on its plane. Errors say which step fails and why.
pub fn check_path(scene: &Scene, states: &[State]) -> Result<PrimitivePath, String> {
    let robot = &scene.robot;
    let first = states.first().ok_or("the path has no states")?;
    if first != &scene.start {
        return Err("the path does not start at the scene's start state".into());
    }
    let tool_at = |q: &DVector<f64>| robot.tool_pose(&robot.link_poses(q)).translation.vector;
    let mut metrics = PathMetrics::default();
    let mut durations = Vec::with_capacity(states.len());
    let mut travelled = vec![0.0; first.objects.len()];
    let mut carries = false;
    for (k, pair) in states.windows(2).enumerate() {
        let (a, b) = (&pair[0], &pair[1]);
        let step = |why: String| format!("step {k} -> {}: {why}", k + 1);
        let moved: Vec<usize> = (0..a.objects.len())
            .filter(|&i| a.objects[i] != b.objects[i])
            .collect();
        match moved[..] {
            [] => {
                check_transit(scene, a, &b.q).map_err(|e| step(format!("transit: {e}")))?;
                // The tool's travel along the line, at the resolution it was checked at.
                let segments = transit_segments(&a.q, &b.q);
                let mut at = tool_at(&a.q);
                for s in 1..=segments {
                    let next = tool_at(&a.q.lerp(&b.q, s as f64 / segments as f64));
                    metrics.ee_length += (next - at).norm();
                    at = next;
                }
            }
            [object] => {
                let (from, to) = (&a.objects[object], &b.objects[object]);
                if carry_steps(from, to) > 1 {
                    return Err(step("the object moves more than one carry step".into()));
                }
                let (grip_a, grip_b) = (
                    Cage::of_state(scene, a, object).grip,
                    Cage::of_state(scene, b, object).grip,
                );
                let drift = (grip_a.translation() - grip_b.translation())
                    .norm()
                    .max(crate::math::wrap_angle(grip_a.theta - grip_b.theta).abs());
                if drift > GRIP_TOLERANCE {
                    return Err(step(format!(
                        "the carried object slips in the hand by {drift:.2e}"
                    )));
                }
                let (joint, jump) = (&b.q - &a.q).abs().argmax();
                if jump > CARRY_MAX_JOINT_STEP {
                    return Err(step(format!("joint {joint} jumps {jump:.3}")));
                }
                let (height, tilt) = robot.plane.error(&robot.tool_pose(&robot.link_poses(&b.q)));
                if height.abs() > robot.projection.height_tolerance
                    || tilt > robot.projection.tilt_tolerance
                {
                    return Err(step("the tool leaves its plane while carrying".into()));
                }
                check_carrying(scene, b, object).map_err(|e| step(format!("push: {e}")))?;
                metrics.ee_length += (tool_at(&b.q) - tool_at(&a.q)).norm();
                carries = true;
            }
            _ => return Err(step(format!("{} objects move at once", moved.len()))),
        }
        for (i, t) in travelled.iter_mut().enumerate() {
            *t += (b.objects[i].translation() - a.objects[i].translation()).norm();
        }
        metrics.joint_length += (&b.q - &a.q).norm();
        durations.push(joint_motion_time(robot, &a.q, &b.q));
    }
    metrics.object_displacement = travelled.iter().sum();
    metrics.objects_moved = travelled.iter().filter(|&&d| d > 1e-3).count();
    metrics.links_in_contact = if carries {
        super::hand_links(robot).len()
    } else {
        0
    };
    metrics.duration = durations.iter().sum();
    let goal_reached = scene.goal.is_satisfied(states.last().expect("not empty"));
    Ok(PrimitivePath {
        metrics,
        durations,
        goal_reached,
    })
}
