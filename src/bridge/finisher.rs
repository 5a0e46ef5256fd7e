//! [`Finisher`]: what becomes of a path the search found (re-simulated, shortcut, made
//! robust: [`crate::planning::finish`]), and its executable trajectory.

use super::core::{guarded, Flat};
use super::ffi;
use super::Problem;
use crate::planning::{PlannerKind, Problem as PlanningProblem};

/// Finishes the paths of one problem, in the mode it had when the finisher was made
/// (pushing, or Static RRT's pinned clutter).
pub struct Finisher {
    problem: PlanningProblem,
}

impl Finisher {
    /// The finisher of `problem`, in its current mode.
    pub fn new(problem: &Problem) -> Box<Finisher> {
        let kind = if problem.static_clutter() {
            PlannerKind::StaticRrt
        } else {
            PlannerKind::PcRrt
        };
        Box::new(Finisher {
            problem: PlanningProblem::new((*problem.scene).clone(), kind),
        })
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
            let flat = Flat(self.problem.scene());
            let controls = flat.path_controls(controls, steps)?;
            let states = flat.states(states)?;
            self.problem
                .finish(&controls, &states, solved, &settings)
                .map(ffi::FinishedPath::from)
        })
    }

    /// The executable trajectory of a plan, as plan files hold it.
    pub fn trajectory(&self, controls: &[f64], steps: &[usize]) -> Result<ffi::Trajectory, String> {
        guarded("trajectory", || {
            let controls = Flat(self.problem.scene()).path_controls(controls, steps)?;
            self.problem
                .trajectory(&controls)
                .map(ffi::Trajectory::from)
        })
    }

    /// Re-simulates a path from the problem's start (such as an observed state): the state
    /// at the start and after each control, flat, if every step is valid and the goal is
    /// reached at the end; nothing if not (the path no longer does its work from there).
    pub fn resimulate(&self, controls: &[f64], steps: &[usize]) -> Result<Vec<f64>, String> {
        guarded("resimulate", || {
            let controls = Flat(self.problem.scene()).path_controls(controls, steps)?;
            let path = self.problem.simulate(&controls, false);
            let scene = self.problem.scene();
            if !(path.valid() && scene.goal.is_satisfied(path.final_state())) {
                return Ok(Vec::new());
            }
            Ok(path.states.iter().flat_map(|s| s.to_flat()).collect())
        })
    }
}
