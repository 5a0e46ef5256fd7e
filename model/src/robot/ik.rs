//! Inverse kinematics of the tool: a configuration that puts the tool frame at a given
//! world pose, by damped least squares from a seed configuration. The DARRT baseline
//! uses it to place the hand at an object and to carry the object along a line.

use super::Robot;
use nalgebra::{DVector, Isometry3, Vector6};

/// Tolerances and limits of [`Robot::reach_tool_pose`].
#[derive(Clone, Debug)]
pub struct IkSettings {
    /// Accepted position error of the tool point (m).
    pub position_tolerance: f64,
    /// Accepted orientation error of the tool frame (rad).
    pub rotation_tolerance: f64,
    /// Damping of the pseudoinverse (m).
    pub damping: f64,
    /// Iterations before giving up.
    pub max_iterations: usize,
    /// Largest task-space correction per iteration (m, and rad for the rotation part):
    /// keeps the linearisation honest far from the target.
    pub max_correction: f64,
}

impl Default for IkSettings {
    fn default() -> Self {
        Self {
            position_tolerance: 1e-5,
            rotation_tolerance: 1e-5,
            damping: 1e-2,
            max_iterations: 200,
            max_correction: 0.1,
        }
    }
}

impl Robot {
    /// A configuration within the joint limits whose tool frame is at `target` (world),
    /// found by damped least squares from `seed`; `None` if it does not converge.
    pub fn reach_tool_pose(
        &self,
        target: &Isometry3<f64>,
        seed: &DVector<f64>,
        settings: &IkSettings,
    ) -> Option<DVector<f64>> {
        let limits = self.chain.limits();
        let empty = DVector::zeros(0);
        let mut q = seed.clone();
        let mut poses = Vec::with_capacity(self.chain.links.len());
        for _ in 0..=settings.max_iterations {
            self.chain.forward_kinematics(&q, &mut poses);
            let tool = self.tool_pose(&poses);
            let position = target.translation.vector - tool.translation.vector;
            let rotation = (target.rotation * tool.rotation.inverse()).scaled_axis();
            if !(position.iter().chain(rotation.iter())).all(|v| v.is_finite()) {
                return None;
            }
            if position.norm() <= settings.position_tolerance
                && rotation.norm() <= settings.rotation_tolerance
            {
                return self.chain.within_limits(&q).is_ok().then_some(q);
            }
            let mut error = Vector6::new(
                position.x, position.y, position.z, rotation.x, rotation.y, rotation.z,
            );
            let size = error.norm();
            if size > settings.max_correction {
                error *= settings.max_correction / size;
            }
            let dq = self
                .joint_velocity(&poses, &error, &empty, settings.damping)
                .ok()?;
            q += dq;
            for (value, (lower, upper)) in q.iter_mut().zip(&limits) {
                *value = value.clamp(*lower, *upper);
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;
    use crate::scene::Scene;

    fn herb() -> Scene {
        Scene::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../scenes/herb_single_object.yaml"
        ))
        .unwrap()
    }

    /// Poses of random configurations are reached again from a perturbed seed, to the
    /// tolerance, and the answer's forward kinematics (computed here) is the target.
    #[test]
    fn reaches_poses_of_random_configurations() {
        let scene = herb();
        let robot = &scene.robot;
        let limits = robot.chain.limits();
        let mut rng = SplitMix64::new(7);
        let settings = IkSettings::default();
        let mut reached = 0;
        for _ in 0..50 {
            let q: DVector<f64> = DVector::from_iterator(
                limits.len(),
                limits
                    .iter()
                    .map(|(l, u)| l + (u - l) * rng.uniform(0.1, 0.9)),
            );
            let target = robot.tool_pose(&robot.link_poses(&q));
            let seed = q.map(|v| v + rng.uniform(-0.1, 0.1));
            if let Some(found) = robot.reach_tool_pose(&target, &seed, &settings) {
                reached += 1;
                let tool = robot.tool_pose(&robot.link_poses(&found));
                let dp = (tool.translation.vector - target.translation.vector).norm();
                let dr = tool.rotation.angle_to(&target.rotation);
                assert!(dp <= 1e-5 && dr <= 1e-5, "error {dp} m, {dr} rad");
                assert!(robot.chain.within_limits(&found).is_ok());
            }
        }
        // Seeds within 0.1 rad per joint of a solution converge (singular poses aside).
        assert!(reached >= 45, "reached {reached} of 50");
    }

    #[test]
    fn an_unreachable_pose_is_refused() {
        let scene = herb();
        let robot = &scene.robot;
        let far = Isometry3::translation(5.0, 0.0, 1.0);
        assert!(robot
            .reach_tool_pose(&far, &scene.start.q, &IkSettings::default())
            .is_none());
    }
}
