//! The check of a DARRT path: every step is a Transit motion, a step of a Push or a part
//! of a PickPlace, from the scene's start; and its measures (those of PC RRT's paths, for
//! the benchmark).

use super::carry::{carry_steps, check_carrying, CARRY_MAX_JOINT_STEP};
use super::pick_place::PathState;
use super::Cage;
use crate::planning::manipulation::{carried_pose, holding_valid};
use crate::planning::path::PathMetrics;
use crate::planning::trajectory::joint_motion_time;
use crate::planning::transit::{check_transit, transit_points};
use crate::robot::wgr::distance_to_grasps;
use crate::state::State;
use crate::validity::check_state;
use crate::Scene;
use nalgebra::{DVector, Isometry3};

/// How far the grip of a carried object may drift between steps (m, and rad): the inverse
/// kinematics is solved to 1e-5.
const GRIP_TOLERANCE: f64 = 1e-4;

/// How far a grasp may lie outside the object's grasp regions, and a set-down object from
/// resting flat on the table (m and rad): the manipulation graph's own tolerance for a
/// held grasp.
const HOLD_TOLERANCE: f64 = 1e-3;

/// A pick-up: the hand takes `object` in the grasp `x_oe` (the tool in the object frame).
#[derive(Clone, Copy, Debug)]
struct Hold {
    object: usize,
    x_oe: Isometry3<f64>,
}

/// A checked DARRT path.
#[derive(Clone, Debug, PartialEq)]
pub struct PrimitivePath {
    /// Joint length, tool travel, object displacement, objects moved; `links_in_contact`
    /// is the hand's links if the path carries an object; `duration` is the time at the
    /// joints' velocity limits.
    pub metrics: PathMetrics,
    /// Time (s) of each step at the joints' velocity limits.
    pub durations: Vec<f64>,
    /// How many times the hand picks an object up (PickPlace).
    pub pick_places: usize,
    /// The path's last state satisfies the goal.
    pub goal_reached: bool,
}

/// Checks `path` as a DARRT path. It starts at the scene's start and ends with the hand
/// empty; between consecutive states:
/// - hand empty in both: no object moves and the arm's straight line is a valid Transit,
///   or one object moves by at most one carry step, held in the same cage, and the new
///   state is valid for carrying it with the tool on its plane (a Push step);
/// - the hand takes an object (PickPlace): nothing moves, and the tool lies in one of the
///   object's grasp regions where it rests;
/// - the hand carries it: only it moves, in the grasp taken, and the straight line is
///   valid holding it at the Transit resolution;
/// - the hand lets go: nothing moves, the object rests flat on the table where the state
///   says, and the state is valid.
///
/// Errors say which step fails and why.
pub fn check_path(scene: &Scene, path: &[PathState]) -> Result<PrimitivePath, String> {
    let first = path.first().ok_or("the path has no states")?;
    if first.state != scene.start {
        return Err("the path does not start at the scene's start state".into());
    }
    check_motion(scene, path)
}

/// [`check_path`]'s rules for a path from any state with the hand empty (a primitive's
/// motion from a tree node).
pub fn check_motion(scene: &Scene, path: &[PathState]) -> Result<PrimitivePath, String> {
    let robot = &scene.robot;
    let top = scene.table.top;
    let first = path.first().ok_or("the path has no states")?;
    if first.held.is_some() {
        return Err("the path starts with the hand holding an object".into());
    }
    let tool = |q: &DVector<f64>| robot.tool_pose(&robot.link_poses(q));
    // The tool's travel along a straight joint line, at the resolution it is checked at.
    let travel = |from: &DVector<f64>, to: &DVector<f64>| {
        let mut at = tool(from).translation.vector;
        let mut length = 0.0;
        for q in transit_points(from, to) {
            let next = tool(&q).translation.vector;
            length += (next - at).norm();
            at = next;
        }
        length
    };
    let mut metrics = PathMetrics::default();
    let mut durations = Vec::with_capacity(path.len());
    let mut travelled = vec![0.0; first.state.objects.len()];
    let mut hand_used = false;
    let mut hold: Option<Hold> = None;
    let mut pick_places = 0;
    for (k, pair) in path.windows(2).enumerate() {
        let (a, b) = (&pair[0].state, &pair[1].state);
        let step = |why: String| format!("step {k} -> {}: {why}", k + 1);
        let moved: Vec<usize> = (0..a.objects.len())
            .filter(|&i| a.objects[i] != b.objects[i])
            .collect();
        match (pair[0].held, pair[1].held, hold) {
            (None, None, _) => match moved[..] {
                [] => {
                    check_transit(scene, a, &b.q).map_err(|e| step(format!("transit: {e}")))?;
                    metrics.ee_length += travel(&a.q, &b.q);
                }
                [object] => {
                    check_push_step(scene, a, b, object).map_err(step)?;
                    metrics.ee_length +=
                        (tool(&b.q).translation.vector - tool(&a.q).translation.vector).norm();
                    hand_used = true;
                }
                _ => return Err(step(format!("{} objects move at once", moved.len()))),
            },
            (None, Some(object), _) => {
                if a != b {
                    return Err(step("the hand takes an object while moving".into()));
                }
                let resting = &a.objects[object];
                let outside =
                    distance_to_grasps(robot, top, &scene.objects[object].grasps, resting, &a.q);
                if outside > HOLD_TOLERANCE {
                    return Err(step(format!(
                        "the hand takes '{}' {outside:.2e} outside its grasp regions",
                        scene.objects[object].name
                    )));
                }
                hold = Some(Hold {
                    object,
                    x_oe: resting.to_isometry(top).inverse() * tool(&a.q),
                });
                pick_places += 1;
            }
            (Some(i), Some(j), Some(h)) if i == j && h.object == i => {
                if moved.iter().any(|&m| m != i) {
                    return Err(step("an object the hand does not hold moves".into()));
                }
                let at = carried_pose(robot, &b.q, &h.x_oe);
                let slip = (at.translation() - b.objects[i].translation())
                    .norm()
                    .max(crate::math::wrap_angle(at.theta - b.objects[i].theta).abs());
                if slip > GRIP_TOLERANCE {
                    return Err(step(format!(
                        "the carried object is {slip:.2e} from where the hand holds it"
                    )));
                }
                let line = std::iter::once(a.q.clone()).chain(transit_points(&a.q, &b.q));
                for q in line {
                    if !holding_valid(scene, &a.objects, i, &h.x_oe, &q) {
                        return Err(step("the arm carrying the object hits something".into()));
                    }
                }
                metrics.ee_length += travel(&a.q, &b.q);
                hand_used = true;
            }
            (Some(i), None, Some(h)) if h.object == i => {
                if a != b {
                    return Err(step("the hand lets go while moving".into()));
                }
                let error = a.objects[i].to_isometry(top).inverse() * tool(&a.q) * h.x_oe.inverse();
                if error.translation.vector.norm() > HOLD_TOLERANCE
                    || error.rotation.angle() > HOLD_TOLERANCE
                {
                    return Err(step(format!(
                        "'{}' is let go of {:.2e} m above or off its resting pose",
                        scene.objects[i].name,
                        error.translation.vector.norm()
                    )));
                }
                check_state(scene, b).map_err(|e| step(format!("set down: {e}")))?;
                hold = None;
            }
            _ => {
                return Err(step(
                    "the hand changes what it holds without letting go".into(),
                ))
            }
        }
        for (i, t) in travelled.iter_mut().enumerate() {
            *t += (b.objects[i].translation() - a.objects[i].translation()).norm();
        }
        metrics.joint_length += (&b.q - &a.q).norm();
        durations.push(joint_motion_time(robot, &a.q, &b.q));
    }
    let last = path.last().expect("not empty");
    if last.held.is_some() {
        return Err("the path ends with the hand holding an object".into());
    }
    metrics.object_displacement = travelled.iter().sum();
    metrics.objects_moved = travelled.iter().filter(|&&d| d > 1e-3).count();
    metrics.links_in_contact = if hand_used {
        super::hand_links(robot).len()
    } else {
        0
    };
    metrics.duration = durations.iter().sum();
    let goal_reached = scene.goal.is_satisfied(&last.state);
    Ok(PrimitivePath {
        metrics,
        durations,
        pick_places,
        goal_reached,
    })
}

/// One step of a Push from `a` to `b`: `object` moves by at most one carry step, held in
/// the same cage, and `b` is valid for carrying it with the tool on its plane.
fn check_push_step(scene: &Scene, a: &State, b: &State, object: usize) -> Result<(), String> {
    let robot = &scene.robot;
    let (from, to) = (&a.objects[object], &b.objects[object]);
    if carry_steps(from, to) > 1 {
        return Err("the object moves more than one carry step".into());
    }
    let (grip_a, grip_b) = (
        Cage::of_state(scene, a, object).grip,
        Cage::of_state(scene, b, object).grip,
    );
    let drift = (grip_a.translation() - grip_b.translation())
        .norm()
        .max(crate::math::wrap_angle(grip_a.theta - grip_b.theta).abs());
    if drift > GRIP_TOLERANCE {
        return Err(format!(
            "the carried object slips in the hand by {drift:.2e}"
        ));
    }
    let (joint, jump) = (&b.q - &a.q).abs().argmax();
    if jump > CARRY_MAX_JOINT_STEP {
        return Err(format!("joint {joint} jumps {jump:.3}"));
    }
    let (height, tilt) = robot.plane.error(&robot.tool_pose(&robot.link_poses(&b.q)));
    if height.abs() > robot.projection.height_tolerance || tilt > robot.projection.tilt_tolerance {
        return Err("the tool leaves its plane while carrying".into());
    }
    check_carrying(scene, b, object).map_err(|e| format!("push: {e}"))
}
