//! [`Scene::with_start`]: the scene from another start state, such as one observed while a
//! plan runs (re-planning from where the world is, not where the model said it would be).
//!
//! A world the model only approximates leaves states the model would never reach itself,
//! and a robot must still go on from them: an object pushed partly over the table's edge
//! that still stands, an object the hand has sunk a few millimetres into, two objects
//! pressed a few millimetres into each other (a soft contact, or perception's error), a
//! joint a hair past its limit once the tool is brought back onto its plane. These are taken as they physically are, within bounds; anything
//! further is refused.

#![allow(non_snake_case)] // frame-named points: p_WL, a link's point in the world frame

use super::{Clearances, Scene};
use crate::contact::{
    find_arm_contacts, object_bounds, object_pair_contacts, ArmBounds, ArmContact,
    ObjectPairContact,
};
use crate::error::{Error, Overlap, Result};
use crate::math::Pose2;
use crate::robot::RobotKind;
use crate::state::State;
use nalgebra::{DVector, Vector2};
use std::path::Path;

/// The most an observed object inside the arm, or inside another object, is moved out to
/// touch it (m): a soft contact's depth or perception's error, not an object the arm
/// passes through or two objects standing in one place.
pub const MAX_SEPARATION: f64 = 0.02;

/// Passes of separating objects from each other and then from the arm, at most: each
/// pass halves the depth the last one left where an object is pressed between the arm and
/// a neighbour, and a pass that moves nothing ends them.
const SEPARATION_PASSES: usize = 8;

/// The most an observed joint may lie past its limit once the tool is on its plane (rad,
/// or m), to be put back on the limit: the plane projection's own step, not a joint
/// driven past it.
pub const LIMIT_SLACK: f64 = 1e-3;

impl Scene {
    /// This scene with `start` as its start state, checked as a scene file's start is:
    /// joint and object counts, finite values, an arm's tool brought onto its pushing plane
    /// (the tight tolerance of a scene's start, so that drift is measured from zero; an
    /// arm valid as observed and within the propagation's tolerance is kept as it is where
    /// the projection would press two links together), joint limits, and every validity
    /// rule. Object yaws are wrapped to (-pi, pi]. The
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
            self.start_on_plane_within_limits(&mut q)
                .map_err(|failure| invalid("q".into(), failure))?;
            // Bringing the tool onto its plane moves every joint a little: where two links
            // are a hair apart (the WAM's links 3 and 5 often are) it can press them into
            // each other. A state the propagation itself keeps (the tool within its
            // tolerances of the plane), valid as observed, is a state the model makes: it
            // is taken as it is rather than refused.
            // Only asked where the projected arm is refused: every other observation is
            // taken projected, without the observed arm's kinematics.
            let kept_as_observed = || {
                let robot = &self.robot;
                let (height, tilt) = robot
                    .plane
                    .error(&robot.tool_pose(&robot.link_poses(&start.q)));
                robot.projection.admits(height, tilt)
                    && crate::validity::check_arm(self, &start.q).is_ok()
            };
            if crate::validity::check_arm(self, &q).is_err() && kept_as_observed() {
                q.clone_from(&start.q);
            }
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
        for (i, object) in self.objects.iter().enumerate() {
            let pose = scene.start.objects[i];
            if !self.table.contains(pose.translation()) {
                return Err(invalid(
                    format!("objects.{}", object.name),
                    format!("centre ({}, {}) is off the table", pose.x, pose.y),
                ));
            }
        }
        // Moving an object out of the arm may take it into a neighbour, and moving two
        // objects apart may take one back into the arm: the two alternate until neither
        // moves an object (each halves what the other left), every object bounded by
        // MAX_SEPARATION from where it was observed.
        let observed = scene.start.objects.clone();
        let deep = |between: Overlap| {
            move |(object, message): (String, String)| Error::DeepOverlap {
                file: source.to_path_buf(),
                field: format!("objects.{object}"),
                between,
                message,
            }
        };
        for _ in 0..SEPARATION_PASSES {
            let before = scene.start.objects.clone();
            self.separate_objects(&mut scene.start, &observed)
                .map_err(deep(Overlap::Objects))?;
            self.separate_from_arm(&mut scene.start, &observed)
                .map_err(deep(Overlap::ArmAndObject))?;
            if scene.start.objects == before {
                break;
            }
        }
        scene.clearances = Clearances::at_start(&scene).with_start_overhangs(&scene);
        crate::validity::check_state(&scene, &scene.start).map_err(|rule| Error::InvalidStart {
            file: source.to_path_buf(),
            rule,
        })?;
        Ok(scene)
    }

    /// Brings the tool of `q` onto its pushing plane; a joint the projection takes past
    /// its limit by at most [`LIMIT_SLACK`] is put back on the limit and the tool brought
    /// back again (the other joints take up the difference), a few times at most.
    fn start_on_plane_within_limits(
        &self,
        q: &mut DVector<f64>,
    ) -> std::result::Result<(), String> {
        let chain = &self.robot.chain;
        for _ in 0..4 {
            self.robot.start_on_plane(q).map_err(|failure| {
                format!("the tool cannot be brought onto its pushing plane from here ({failure}); `pushplan robot SCENE --reach X,Y` prints starts on it")
            })?;
            let mut clamped = false;
            for i in 0..q.len() {
                let joint = chain.dof_joint(i);
                let within = q[i].clamp(joint.lower, joint.upper);
                if within != q[i] && (within - q[i]).abs() <= LIMIT_SLACK {
                    q[i] = within;
                    clamped = true;
                }
            }
            if !clamped {
                return Ok(());
            }
        }
        Ok(()) // what is left past a limit is refused by the caller, with the joint named
    }

    /// Moves apart every two objects of `state` whose footprints overlap beyond
    /// `physics.overlap_tolerance` (what the validity rules refuse), the deepest pair first,
    /// each by half the depth and a tenth of a millimetre along the contact's normal, until
    /// none does. An overlap deeper than [`MAX_SEPARATION`], or an object moved further than
    /// that from `start` (where it was observed; overlaps passed along a row of objects),
    /// is refused, both objects
    /// named. MuJoCo's soft contacts leave two objects pressed together a few millimetres
    /// into each other, and so may perception.
    fn separate_objects(
        &self,
        state: &mut State,
        start: &[Pose2],
    ) -> std::result::Result<(), (String, String)> {
        let tolerance = self.physics.overlap_tolerance;
        let (mut scratch, mut pairs) = (Vec::new(), Vec::new());
        // Rounds: moving two objects apart may take one into a third.
        for _ in 0..16 {
            pairs.clear();
            for i in 0..self.objects.len() {
                object_pair_contacts(self, &state.objects, i, 0.0, &mut scratch, &mut pairs);
            }
            // Each pair once (`from` the lower index), the first of the deepest.
            let deepest = pairs
                .iter()
                .filter(|c| c.from < c.into && c.gap < -tolerance)
                .min_by(|a, b| a.gap.total_cmp(&b.gap));
            let Some(&ObjectPairContact {
                from: i,
                into: j,
                normal,
                gap,
                ..
            }) = deepest
            else {
                return Ok(());
            };
            let (name_i, name_j) = (&self.objects[i].name, &self.objects[j].name);
            if -gap > MAX_SEPARATION {
                return Err((
                    name_j.clone(),
                    format!(
                        "object '{name_i}' overlaps it by {:.1} mm, further than the {} mm an \
                         observation may be off",
                        -gap * 1e3,
                        MAX_SEPARATION * 1e3
                    ),
                ));
            }
            // The normal points out of `i` toward `j`: each moves half the depth its way.
            let half = normal * (0.5 * (-gap + 1e-4));
            for (k, shift) in [(i, -half), (j, half)] {
                let pose = &mut state.objects[k];
                *pose = Pose2::new(pose.x + shift.x, pose.y + shift.y, pose.theta);
                let moved = (pose.translation() - start[k].translation()).norm();
                if moved > MAX_SEPARATION {
                    let (name, other) = if k == i {
                        (name_i, name_j)
                    } else {
                        (name_j, name_i)
                    };
                    return Err((
                        name.clone(),
                        format!(
                            "moved {:.1} mm in all to stand clear of the objects it overlaps \
                             (last '{other}'), further than the {} mm an observation may be off",
                            moved * 1e3,
                            MAX_SEPARATION * 1e3
                        ),
                    ));
                }
            }
        }
        Ok(()) // the validity check names what is left
    }

    /// Moves every object of `state` that the arm's links reach into beyond
    /// `physics.penetration_tolerance`, or rest on from above (a link within a millimetre
    /// of its top), out in the table's plane until the validity rules accept it, by
    /// [`MAX_SEPARATION`] at most: along the contact's normal when that is within 60
    /// degrees of horizontal, else straight away from the link's contact point in 2 mm
    /// steps. An object further in, or moved further than that from `start` (where it was
    /// observed), is refused (its name and why).
    fn separate_from_arm(
        &self,
        state: &mut State,
        start: &[Pose2],
    ) -> std::result::Result<(), (String, String)> {
        let tolerance = self.physics.penetration_tolerance;
        let vertical = self.physics.vertical_normal_angle.cos();
        let poses = self.robot.link_poses(&state.q);
        let mut bounds = ArmBounds::default();
        ArmBounds::compute(self, &poses, &mut bounds);
        let (mut boxes, mut contacts) = (Vec::new(), Vec::new());
        // Rounds: moving an object out of one link may take it into another, and an
        // object under a link moves out in steps.
        for _ in 0..16 {
            object_bounds(self, &state.objects, &mut boxes);
            contacts.clear();
            find_arm_contacts(
                self,
                &poses,
                &bounds,
                &state.objects,
                &boxes,
                self.physics.contact_margin,
                &mut contacts,
            );
            // What the validity rules refuse (`check_arm_contacts`).
            let from_above =
                |c: &ArmContact| c.point.distance <= 1e-3 && c.point.normal_a.z.abs() > vertical;
            let Some(worst) = contacts
                .iter()
                .filter(|c| c.point.distance < -tolerance || from_above(c))
                .min_by(|a, b| a.point.distance.total_cmp(&b.point.distance))
            else {
                return Ok(());
            };
            let i = worst.object;
            // The normal points out of the object towards the link: the object moves the
            // other way.
            let n = worst.point.normal_a;
            let horizontal = Vector2::new(n.x, n.y);
            let depth = (-worst.point.distance).max(0.0);
            let shift = if horizontal.norm() >= 0.5 {
                // Until the contact's depth is gone along the normal (a little over, so
                // that the tolerance is not met exactly).
                -horizontal * ((depth + 1e-4) / horizontal.norm_squared())
            } else {
                // The link's contact point, world frame.
                let p_WL = worst.point.point_b;
                let away = state.objects[i].translation() - Vector2::new(p_WL.x, p_WL.y);
                let away = match away.try_normalize(1e-9) {
                    Some(direction) => direction,
                    None => -horizontal.try_normalize(1e-9).unwrap_or(Vector2::x()),
                };
                away * 2e-3
            };
            let pose = &mut state.objects[i];
            *pose = Pose2::new(pose.x + shift.x, pose.y + shift.y, pose.theta);
            let moved = (pose.translation() - start[i].translation()).norm();
            if moved > MAX_SEPARATION {
                return Err((
                    self.objects[i].name.clone(),
                    format!(
                        "link '{}' reaches {:.1} mm into it{} after it was moved {:.1} mm \
                         from where it was observed, further than the {} mm an observation \
                         may be off",
                        self.robot.chain.links[worst.link].name,
                        depth * 1e3,
                        if from_above(worst) { " from above" } else { "" },
                        moved * 1e3,
                        MAX_SEPARATION * 1e3
                    ),
                ));
            }
        }
        Ok(()) // the validity check names what is left
    }
}
