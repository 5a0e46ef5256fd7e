//! PickPlace: the primitive the whole-arm paper suggests would strengthen DARRT (Sec. V-A).
//! The hand grasps an object where it rests, carries it through the air and sets it down
//! at a target placement, the other objects resting where they are. The way is found by
//! the manipulation graph's two-level Fuzzy PRM ([`crate::planning::manipulation`]): transit to a
//! grasp, transfer, and a transit and a new grasp if the first cannot place it.
//!
//! In a DARRT path the hand's hold is explicit: every state says which object the hand
//! carries, if any ([`PathState::held`]). A carried object's pose in the state is the
//! planar pose of its 3D pose seen from above; its grasp is the one the hand took when it
//! picked the object up.

use super::check::check_motion;
use super::PrimitiveFailure;
use crate::math::Pose2;
use crate::planning::manipulation::{
    carried_pose, ManipulationGraph, Motion, PickAndPlace, Settings,
};
use crate::scene::Scene;
use crate::state::State;
use std::time::Instant;

/// A state of a DARRT path and what the hand holds in it.
#[derive(Clone, Debug, PartialEq)]
pub struct PathState {
    /// The state.
    pub state: State,
    /// The object the hand carries (index into the scene's objects), if any.
    pub held: Option<usize>,
}

impl PathState {
    /// A state with every object resting on the table.
    pub fn resting(state: State) -> PathState {
        PathState { state, held: None }
    }
}

/// How hard PickPlace tries.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PickPlaceSettings {
    /// Grasps sampled from each of the object's grasp regions.
    pub grasps_per_region: usize,
    /// Validity checks the manipulation graph may spend.
    pub budget: usize,
    /// Longest time one PickPlace may take (s), as RRTTransit's cap: the graph's query
    /// loop can spend long between validity checks on a crowded roadmap.
    pub time_cap: f64,
}

impl Default for PickPlaceSettings {
    /// Four grasps per region, 20 000 validity checks and at most a second: mostly a few
    /// tens of milliseconds, so that a DARRT extension stays comparable to a Push.
    fn default() -> Self {
        PickPlaceSettings {
            grasps_per_region: 4,
            budget: 20_000,
            time_cap: 1.0,
        }
    }
}

/// PickPlace from `state`: `object` to `target`, the grasps and the graph's samples drawn
/// from `seed`, given up at `deadline` (the search's) or after the settings' time cap.
/// Returns the states after `state`, ending with the hand empty and the object at `target`
/// (to the inverse kinematics' tolerance).
pub fn pick_place(
    scene: &Scene,
    state: &State,
    object: usize,
    target: &Pose2,
    settings: &PickPlaceSettings,
    seed: u64,
    deadline: Option<Instant>,
) -> Result<Vec<PathState>, PrimitiveFailure> {
    let capped = crate::planning::deadline(Instant::now(), settings.time_cap);
    let deadline = match (deadline, capped) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    };
    let problem = PickAndPlace::new(
        scene,
        state,
        object,
        *target,
        settings.grasps_per_region,
        seed,
    )
    .map_err(|_| PrimitiveFailure::Unreachable)?;
    let mut graph = ManipulationGraph::new(
        problem,
        Settings {
            budget: settings.budget,
            seed,
            deadline,
            ..Settings::default()
        },
    );
    let segments = graph.solve().ok_or(PrimitiveFailure::NoPath)?;
    let problem = &graph.problem;
    let robot = &scene.robot;
    let mut path = vec![PathState::resting(state.clone())];
    let mut at = state.clone();
    for segment in &segments {
        match segment.motion {
            Motion::Transit { .. } => {
                for q in &segment.waypoints[1..] {
                    at.q = q.clone();
                    path.push(PathState::resting(at.clone()));
                }
            }
            Motion::Transfer { grasp, .. } => {
                let x_oe = problem.grasps[grasp];
                // Picked up where it rests, carried, set down.
                path.push(PathState {
                    state: at.clone(),
                    held: Some(object),
                });
                for q in &segment.waypoints[1..] {
                    at.q = q.clone();
                    at.objects[object] = carried_pose(robot, q, &x_oe);
                    path.push(PathState {
                        state: at.clone(),
                        held: Some(object),
                    });
                }
                path.push(PathState::resting(at.clone()));
            }
        }
    }
    // The graph checks its lines with the sampled grasp; the path check with the grasp
    // the hand took. A line that grazes something with the one and not the other is
    // refused here, not in the finished path.
    check_motion(scene, &path).map_err(PrimitiveFailure::Refused)?;
    path.remove(0);
    Ok(path)
}
