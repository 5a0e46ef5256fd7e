//! [`ValidityChecker`]: OMPL's state validity checker (`ob::StateValidityChecker`).

use super::core::{guarded, Flat, SharedCore};
use super::Problem;
use crate::scene::Scene;
use crate::validity::check_state;
use std::f64::consts::PI;
use std::sync::Arc;

/// Whether a state is valid in the problem's mode and in every perturbed world.
pub struct ValidityChecker {
    core: SharedCore,
    scene: Arc<Scene>,
}

impl ValidityChecker {
    /// The validity checker of `problem`.
    pub fn new(problem: &Problem) -> Box<ValidityChecker> {
        Box::new(ValidityChecker {
            core: problem.core.clone(),
            scene: problem.scene.clone(),
        })
    }

    /// Whether `state` is valid, in every perturbed world (their poses `particles`).
    pub fn is_valid(&self, state: &[f64], particles: &[f64]) -> Result<bool, String> {
        guarded("is_valid", || {
            let core = self.core.lock();
            if let Some(valid) = core.last_result_validity(state) {
                return Ok(valid);
            }
            core.check_particles(particles)?;
            let state = Flat(&self.scene).state(state)?;
            // OMPL's bounds, which its checker leaves to the model: the joint limits and the
            // table are rules below; a yaw outside [-pi, pi] is outside SO2's.
            if state.objects.iter().any(|p| !(-PI..=PI).contains(&p.theta)) {
                return Ok(false);
            }
            if !core.particles.all_valid(&state.q, particles) {
                return Ok(false);
            }
            if let Some(view) = &core.static_clutter {
                return Ok(view.clutter_in_place(&state)
                    && check_state(view.propagator.scene(), &view.reduce(&state)).is_ok());
            }
            Ok(check_state(&self.scene, &state).is_ok())
        })
    }
}
