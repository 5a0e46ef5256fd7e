//! [`Finisher`]: what becomes of a path the search found (re-simulated, shortcut, made
//! robust: [`crate::planning::finish`]), and its executable trajectory.

use super::core::{guarded, Flat, SharedCore};
use super::ffi;
use super::Problem;
use crate::planning::{PlannerKind, Problem as PlanningProblem};
use crate::scene::Scene;
use std::sync::Arc;

/// Finishes the paths of one problem, in its mode (pushing, or Static RRT's pinned
/// clutter).
pub struct Finisher {
    core: SharedCore,
    scene: Arc<Scene>,
}

impl Finisher {
    /// The finisher of `problem`.
    pub fn new(problem: &Problem) -> Box<Finisher> {
        Box::new(Finisher {
            core: problem.core.clone(),
            scene: problem.scene.clone(),
        })
    }

    /// The planning problem of the current mode.
    fn problem(&self) -> PlanningProblem {
        let kind = if self.core.lock().static_clutter.is_some() {
            PlannerKind::StaticRrt
        } else {
            PlannerKind::PcRrt
        };
        PlanningProblem::new((*self.scene).clone(), kind)
    }

    /// Finishes a found path: `controls` and `steps` as found, `states` the planner's
    /// states at the control boundaries.
    pub fn finish(
        &self,
        controls: &[f64],
        steps: &[usize],
        states: &[f64],
        solved: bool,
        settings: &ffi::FinishSettings,
    ) -> Result<ffi::FinishedPath, String> {
        guarded("finish", || {
            let settings = settings.try_into()?;
            let flat = Flat(&self.scene);
            let controls = flat.path_controls(controls, steps)?;
            let states = flat.states(states)?;
            self.problem()
                .finish(&controls, &states, solved, &settings)
                .map(ffi::FinishedPath::from)
        })
    }

    /// The executable trajectory of a plan, as plan files hold it.
    pub fn trajectory(&self, controls: &[f64], steps: &[usize]) -> Result<ffi::Trajectory, String> {
        guarded("trajectory", || {
            let controls = Flat(&self.scene).path_controls(controls, steps)?;
            self.problem()
                .trajectory(&controls)
                .map(ffi::Trajectory::from)
        })
    }
}
