//! [`Scene::with_start`]: the scene from another start state, such as one observed while a
//! plan runs (re-planning from where the world is, not where the model said it would be).

use super::{Clearances, Scene};
use crate::error::{Error, Result};
use crate::robot::RobotKind;
use crate::state::State;
use std::path::Path;

impl Scene {
    /// This scene with `start` as its start state, checked as a scene file's start is:
    /// joint and object counts, finite values, an arm's tool brought onto its pushing plane
    /// (the tight tolerance of a scene's start, so that drift is measured from zero), joint
    /// limits, and every validity rule. Object yaws are wrapped to (-pi, pi]. The
    /// clearances are those of the new start (objects that stand close together may stay
    /// so). Errors name `source` (the file the state came from) and the field at fault.
    pub fn with_start(&self, start: &State, source: &Path) -> Result<Scene> {
        let invalid = |field: String, message: String| Error::Invalid {
            file: source.to_path_buf(),
            field,
            message,
        };
        let dof = self.robot.dof();
        if start.q.len() != dof {
            return Err(invalid(
                "q".into(),
                format!("{} joint values for a robot of {dof}", start.q.len()),
            ));
        }
        if start.objects.len() != self.objects.len() {
            return Err(invalid(
                "objects".into(),
                format!(
                    "{} object poses for a scene of {} objects",
                    start.objects.len(),
                    self.objects.len()
                ),
            ));
        }
        if let Some(i) = start.q.iter().position(|v| !v.is_finite()) {
            return Err(invalid(format!("q[{i}]"), "must be finite".into()));
        }
        let mut scene = self.clone();
        for (i, (pose, object)) in start.objects.iter().zip(&self.objects).enumerate() {
            let values = [pose.x, pose.y, pose.theta];
            if values.iter().any(|v| !v.is_finite()) {
                return Err(invalid(
                    format!("objects.{}", object.name),
                    format!("pose {values:?} must be finite"),
                ));
            }
            scene.start.objects[i] =
                crate::math::Pose2::new(pose.x, pose.y, crate::math::wrap_angle(pose.theta));
        }
        let mut q = start.q.clone();
        if self.robot.kind == RobotKind::Arm {
            self.robot.start_on_plane(&mut q).map_err(|failure| {
                invalid(
                    "q".into(),
                    format!(
                        "the tool cannot be brought onto its pushing plane from here: {failure}"
                    ),
                )
            })?;
        }
        if let Err(i) = self.robot.chain.within_limits(&q) {
            let joint = self.robot.chain.dof_joint(i);
            return Err(invalid(
                format!("q[{i}]"),
                format!(
                    "{} (on the pushing plane) is outside the limits [{}, {}] of joint '{}'",
                    q[i], joint.lower, joint.upper, joint.name
                ),
            ));
        }
        scene.start.q = q;
        scene.clearances = Clearances::at_start(&scene);
        crate::validity::check_state(&scene, &scene.start).map_err(|reason| {
            Error::InvalidStart {
                file: source.to_path_buf(),
                reason: reason.to_string(),
            }
        })?;
        Ok(scene)
    }
}
