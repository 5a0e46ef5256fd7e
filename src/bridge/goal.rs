//! [`Goal`]: the problem's goal region (`ob::GoalSampleableRegion`): how far a state is
//! from it, and, for a grasp goal, samples in it.

use super::core::{guarded, Flat, SharedCore};
use super::Problem;
use crate::planning::reach::{sample_grasp, GraspSampling};
use crate::scene::Scene;
use std::cell::Cell;
use std::sync::Arc;

/// The goal, with the closest and farthest goal distances the search has met.
pub struct Goal {
    core: SharedCore,
    scene: Arc<Scene>,
    /// The smallest goal distance asked for so far (progress reports: how close the
    /// search has come).
    closest: Cell<f64>,
    /// The largest (with the smallest: whether any state has moved the goal object).
    farthest: Cell<f64>,
}

impl Goal {
    /// The goal of `problem`.
    pub fn new(problem: &Problem) -> Box<Goal> {
        Box::new(Goal {
            core: problem.core.clone(),
            scene: problem.scene.clone(),
            closest: Cell::new(f64::INFINITY),
            farthest: Cell::new(f64::NEG_INFINITY),
        })
    }

    /// How far `state` is from the goal (m or rad; zero or negative inside): the nominal
    /// state with the planning margin, every perturbed world (poses `particles`) without.
    pub fn distance(&self, state: &[f64], particles: &[f64]) -> Result<f64, String> {
        guarded("goal_distance", || {
            let core = self.core.lock();
            core.check_particles(particles)?;
            let state = Flat(&self.scene).state(state)?;
            let worlds = core.particles.goal_distance(&state.q, particles);
            let distance = self.scene.goal.distance(&state).max(worlds);
            self.closest.set(self.closest.get().min(distance));
            self.farthest.set(self.farthest.get().max(distance));
            Ok(distance)
        })
    }

    /// The smallest goal distance of a state so far (m or rad; infinite before any).
    pub fn closest_distance(&self) -> f64 {
        self.closest.get()
    }

    /// The largest goal distance of a state so far (m or rad; minus infinity before any).
    pub fn farthest_distance(&self) -> f64 {
        self.farthest.get()
    }

    /// Forgets the goal distances met so far: from here on the closest and farthest are
    /// those of the states asked about next.
    pub fn forget_met(&self) {
        self.closest.set(f64::INFINITY);
        self.farthest.set(f64::NEG_INFINITY);
    }

    /// A grasp goal's sample: one try at a configuration in a grasp region of `object`
    /// at its pose in `state`, valid for the arm alone (a target the pushing planner may
    /// clear the way to), drawn from `seed`. Empty if this try found none.
    pub fn sample_grasp(
        &self,
        state: &[f64],
        object: usize,
        seed: u64,
    ) -> Result<Vec<f64>, String> {
        guarded("sample_grasp", || {
            let state = Flat(&self.scene).state(state)?;
            Ok(
                sample_grasp(&self.scene, &state, object, seed, GraspSampling::ArmOnly)?
                    .map_or_else(Vec::new, |q| q.as_slice().to_vec()),
            )
        })
    }
}
