//! Reaching a grasp (issue 15): the arm moves through its joint space, every object a
//! static obstacle where it is, to a configuration inside one of an object's Workspace
//! Goal Regions (its scene `grasps`). IK-BiRRT (`cpp/planners/ik_birrt/ik_birrt.cpp`) searches; this module
//! is the model's side of it: sampling the regions' configurations by inverse kinematics,
//! the distance to them, and the check of a reach that plan files and the C++ API return.

use crate::planning::transit::check_transit;
use crate::planning::transit::transit_points;
use crate::random::SplitMix64;
use crate::robot::wgr::{distance_to_grasps, Wgr, GRASP_TOLERANCE};
use crate::scene::Scene;
use crate::state::State;
use crate::validity::{check_arm, check_state};
use nalgebra::DVector;

/// The grasp regions of `object` at its pose in `state` (world frame); an error naming
/// the object if it has none.
pub fn grasp_regions(scene: &Scene, state: &State, object: usize) -> Result<Vec<Wgr>, String> {
    let o = scene
        .objects
        .get(object)
        .ok_or_else(|| format!("no object {object}: the scene has {}", scene.objects.len()))?;
    if o.grasps.is_empty() {
        return Err(format!(
            "object '{}' has no grasps (objects[{object}].grasps in the scene)",
            o.name
        ));
    }
    Ok(o.grasps
        .iter()
        .map(|g| g.region(&state.objects[object], scene.table.top))
        .collect())
}

/// The index of the object named `name`, or an error listing the objects with grasps.
pub fn graspable_object(scene: &Scene, name: &str) -> Result<usize, String> {
    let graspable = scene
        .objects
        .iter()
        .filter(|o| !o.grasps.is_empty())
        .map(|o| o.name.as_str());
    let index = scene.objects.iter().position(|o| o.name == name);
    match index {
        Some(i) if !scene.objects[i].grasps.is_empty() => Ok(i),
        _ => Err(format!(
            "no object '{name}' with grasps in the scene (objects with grasps: {})",
            crate::input::name_list(graspable)
        )),
    }
}

/// The distance from `state`'s configuration to the nearest grasp region of `object`.
pub fn grasp_distance(scene: &Scene, state: &State, object: usize) -> Result<f64, String> {
    grasp_regions(scene, state, object)?;
    Ok(distance_to_grasps(
        &scene.robot,
        scene.table.top,
        &scene.objects[object].grasps,
        &state.objects[object],
        &state.q,
    ))
}

/// What a grasp sample must be valid against.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GraspSampling {
    /// The whole state, objects where they are (IK-BiRRT: they are obstacles).
    AmongObjects,
    /// The arm alone: joint limits, itself, the table and obstacles (a target of the
    /// pushing planner, which may push the objects out of the way).
    ArmOnly,
}

/// One IK sample of `object`'s grasp regions (ADDIKSOLUTIONS): a region drawn uniformly,
/// a displacement drawn uniformly in its bounds, solved by inverse kinematics from
/// `state`'s configuration; the configuration if it is valid as `sampling` says (objects
/// where `state` has them). All randomness comes from `seed`.
pub fn sample_grasp(
    scene: &Scene,
    state: &State,
    object: usize,
    seed: u64,
    sampling: GraspSampling,
) -> Result<Option<DVector<f64>>, String> {
    let regions = grasp_regions(scene, state, object)?;
    let mut rng = SplitMix64::new(seed);
    let region = &regions[rng.below(regions.len())];
    let valid = |q: &DVector<f64>| match sampling {
        GraspSampling::AmongObjects => check_state(
            scene,
            &State {
                q: q.clone(),
                objects: state.objects.clone(),
            },
        )
        .is_ok(),
        GraspSampling::ArmOnly => check_arm(scene, q).is_ok(),
    };
    Ok(region.sample_configuration(&scene.robot, &state.q, &mut rng, 1, valid))
}

/// Checks a reach of `object` from `from`: it starts at `from`'s configuration, every
/// straight joint-space segment between waypoints is valid with the objects where `from`
/// has them (checked as DARRT's Transit, at its resolution), and it ends inside a grasp
/// region of the object.
pub fn check_reach(
    scene: &Scene,
    from: &State,
    object: usize,
    waypoints: &[DVector<f64>],
) -> Result<(), String> {
    let first = waypoints.first().ok_or("a reach has no waypoints")?;
    if first != &from.q {
        return Err("the reach does not start where the arm is".into());
    }
    let dof = scene.robot.dof();
    if let Some(i) = waypoints.iter().position(|q| q.len() != dof) {
        return Err(format!(
            "waypoint {i} has {} values for {dof} joints",
            waypoints[i].len()
        ));
    }
    for (i, pair) in waypoints.windows(2).enumerate() {
        let start = State {
            q: pair[0].clone(),
            objects: from.objects.clone(),
        };
        check_transit(scene, &start, &pair[1])
            .map_err(|why| format!("waypoint {i} to {}: {why}", i + 1))?;
    }
    let end = State {
        q: waypoints.last().unwrap().clone(),
        objects: from.objects.clone(),
    };
    let distance = grasp_distance(scene, &end, object)?;
    if distance > GRASP_TOLERANCE {
        return Err(format!(
            "the reach ends {distance:.4} from the nearest grasp region of '{}'",
            scene.objects[object].name
        ));
    }
    Ok(())
}

/// The states along a reach at the Transit resolution (for trajectories and pictures):
/// `from` first, every waypoint included.
pub fn reach_states(from: &State, waypoints: &[DVector<f64>]) -> Vec<State> {
    let mut states = vec![from.clone()];
    for pair in waypoints.windows(2) {
        states.extend(transit_points(&pair[0], &pair[1]).map(|q| State {
            q,
            objects: from.objects.clone(),
        }));
    }
    states
}
