//! [`Grasping`]: the grasp regions IK-BiRRT reaches (`cpp/planners/ik_birrt/`) and the
//! check of a reach.

use super::core::{guarded, Flat};
use super::Problem;
use crate::planning::reach::{self, GraspSampling};
use crate::scene::Scene;
use nalgebra::DVector;
use std::sync::Arc;

/// Grasp regions of one problem's objects.
pub struct Grasping {
    scene: Arc<Scene>,
}

impl Grasping {
    /// The grasp regions of `problem`'s objects.
    pub fn new(problem: &Problem) -> Box<Grasping> {
        Box::new(Grasping {
            scene: problem.scene.clone(),
        })
    }

    /// The index of the object named `name`, which must have grasps.
    pub fn graspable_object(&self, name: &str) -> Result<usize, String> {
        guarded("graspable_object", || {
            reach::graspable_object(&self.scene, name)
        })
    }

    /// One try at a configuration in a grasp region of `object` at its pose in `state`,
    /// valid among the objects (IK-BiRRT's ADDIKSOLUTIONS), drawn from `seed`. Empty if
    /// this try's inverse kinematics found none.
    pub fn sample(&self, state: &[f64], object: usize, seed: u64) -> Result<Vec<f64>, String> {
        guarded("grasp sample", || {
            let state = Flat(&self.scene).state(state)?;
            Ok(reach::sample_grasp(
                &self.scene,
                &state,
                object,
                seed,
                GraspSampling::AmongObjects,
            )?
            .map_or_else(Vec::new, |q| q.as_slice().to_vec()))
        })
    }

    /// The distance from `state`'s configuration to the nearest grasp region of `object`.
    pub fn distance(&self, state: &[f64], object: usize) -> Result<f64, String> {
        guarded("grasp distance", || {
            reach::grasp_distance(&self.scene, &Flat(&self.scene).state(state)?, object)
        })
    }

    /// Checks a reach of `object` from `from` (waypoints flat, one configuration after
    /// another): an empty string if it is valid, else why not ([`reach::check_reach`]).
    pub fn check_reach(
        &self,
        from: &[f64],
        object: usize,
        waypoints: &[f64],
    ) -> Result<String, String> {
        guarded("check_reach", || {
            let from = Flat(&self.scene).state(from)?;
            let dof = self.scene.robot.dof();
            if waypoints.len() % dof != 0 {
                return Err(format!(
                    "{} waypoint values for {dof} joints",
                    waypoints.len()
                ));
            }
            let waypoints: Vec<DVector<f64>> = waypoints
                .chunks(dof)
                .map(DVector::from_column_slice)
                .collect();
            Ok(reach::check_reach(&self.scene, &from, object, &waypoints)
                .err()
                .unwrap_or_default())
        })
    }
}
