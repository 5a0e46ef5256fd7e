//! [`Finisher`]: what becomes of a path the search found (re-simulated, shortcut, made
//! robust: [`crate::planning::finish`]), and its executable trajectory.

use super::core::{guarded, Flat};
use super::ffi;
use super::Problem;
use crate::planning::rest::RestFrom;
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

    /// Re-simulates the rest of a plan from the problem's start (a state observed while the
    /// plan runs) and judges it ([`crate::planning::rest`]): it reaches the goal, or how far
    /// it is valid.
    pub fn rest_from(&self, controls: &[f64], steps: &[usize]) -> Result<ffi::RestFrom, String> {
        guarded("rest_from", || {
            let controls = Flat(self.problem.scene()).path_controls(controls, steps)?;
            let goal = &self.problem.scene().goal;
            let (verdict, simulated) = self.problem.rest_from(&controls, |s| goal.is_satisfied(s));
            let flat = |states: &[crate::State]| states.iter().flat_map(|s| s.to_flat()).collect();
            Ok(match verdict {
                RestFrom::Reaches => ffi::RestFrom {
                    reaches: true,
                    valid: controls.len(),
                    states: flat(&simulated.states),
                    why: String::new(),
                },
                RestFrom::EndsShort { valid, why, .. } => ffi::RestFrom {
                    reaches: false,
                    valid,
                    states: flat(&simulated.states[..=valid]),
                    why,
                },
            })
        })
    }
}
