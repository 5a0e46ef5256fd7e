//! [`Projection`]: the projection of the projection-based planners
//! (`ob::ProjectionEvaluator`), and the push headings Push KPIECE's control sampler
//! steers by.

use super::core::{guarded, Flat, SharedCore};
use super::ffi::PushTarget;
use super::Problem;
use crate::math::Pose2;
use crate::planner::PushHeading;
use crate::scene::Scene;
use crate::state::poses_from_flat_into;
use nalgebra::{DVector, Vector2};
use std::cell::RefCell;
use std::sync::Arc;

/// Where the tool and the goal object are, how blocked the goal object's way is, and
/// which way the tool should go to push an object.
pub struct Projection {
    core: SharedCore,
    scene: Arc<Scene>,
    push_heading: Arc<PushHeading>,
    /// A state's object poses (called for every state of every motion: a kept buffer).
    objects: RefCell<Vec<Pose2>>,
}

impl Projection {
    /// The projection of `problem`.
    pub fn new(problem: &Problem) -> Box<Projection> {
        Box::new(Projection {
            core: problem.core.clone(),
            push_heading: problem.push_heading(),
            scene: problem.scene.clone(),
            objects: RefCell::new(Vec::new()),
        })
    }

    /// End-effector xy and goal-object xy (m), and how deep the objects in the goal
    /// object's way stand in it ([`PushHeading::blockage`], m): the projection of the
    /// projection-based planners (KPIECE1, Push KPIECE, EST, PDST). The goal object's xy
    /// is (0, 0) and the blockage 0 for a configuration goal. The blockage tells states
    /// whose way has been cleared from the rest: a planner that explores new cells of the
    /// projection goes on from them.
    pub fn project(&self, state: &[f64]) -> Result<Vec<f64>, String> {
        guarded("projection", || {
            Flat(&self.scene).check_state_len(state)?;
            let robot = &self.scene.robot;
            let (q, object_poses) = state.split_at(robot.dof());
            let recent = self.core.lock().recent_tools.get(state);
            let tool = recent.unwrap_or_else(|| {
                let q = DVector::from_column_slice(q);
                robot
                    .tool_pose(&robot.link_poses(&q))
                    .translation
                    .vector
                    .xy()
            });
            let mut objects = self.objects.borrow_mut();
            poses_from_flat_into(object_poses, &mut objects);
            let goal = match self.scene.goal.object() {
                Some(object) => objects[object].translation(),
                None => Vector2::zeros(),
            };
            let blockage = self.push_heading.blockage(&objects);
            Ok(vec![tool.x, tool.y, goal.x, goal.y, blockage])
        })
    }

    /// The push heading at a state for pushing `object` toward `target` (world xy, m):
    /// unit xy in the world frame (see [`PushHeading`]), or no values when the object is
    /// at the target.
    pub fn push_heading(
        &self,
        state: &[f64],
        object: usize,
        target: &[f64],
    ) -> Result<Vec<f64>, String> {
        guarded("push_heading", || {
            let state = Flat(&self.scene).state(state)?;
            if object >= state.objects.len() || target.len() != 2 {
                return Err(format!(
                    "push_heading: object {object} of {}, a target of {} values (needs 2)",
                    state.objects.len(),
                    target.len()
                ));
            }
            let robot = &self.scene.robot;
            let tool = robot.tool_pose(&robot.link_poses(&state.q)).translation;
            let target = Vector2::new(target[0], target[1]);
            Ok(self
                .push_heading
                .heading(&state, Vector2::new(tool.x, tool.y), object, target)
                .map_or_else(Vec::new, |h| vec![h.x, h.y]))
        })
    }

    /// The objects in the goal object's way at a state, each with a place out of it
    /// ([`PushHeading::blockers`]).
    pub fn push_blockers(&self, state: &[f64]) -> Result<Vec<PushTarget>, String> {
        guarded("push_blockers", || {
            let state = Flat(&self.scene).state(state)?;
            Ok(self
                .push_heading
                .blockers(&state)
                .into_iter()
                .map(|b| PushTarget {
                    object: b.object,
                    target: [b.target.x, b.target.y],
                })
                .collect())
        })
    }
}
