//! The rest of a plan judged from a state observed while the plan runs: what closing the
//! loop does with it. Every front that closes the loop (the executor of `execute
//! --closed-loop`, the CLI's `replan`, C++'s `Planner::replan`) judges it here and acts on
//! the answer the same way:
//!
//! 1. the rest still reaches the goal from the observed state: it is kept whole, no search;
//! 2. it is valid for its first controls and then stops being valid, or is valid to its end
//!    and ends short of the goal: it is kept up to there and an ending is searched from
//!    where that part ends (a **repair**, with [`REPAIR_SHARE`] of a re-plan's time: the
//!    search starts where the plan had got to, most often close to the goal, and finds a
//!    short ending fast);
//! 3. its first control is not valid, or the repair finds nothing: the scene is searched
//!    anew from the observed state.
//!
//! The executor tries one thing before 2: the rest **mended** where it fails, with no
//! search ([`crate::planning::mend`], [`Problem::mend`]); a mend that is valid and reaches
//! the goal is played on. `replan` and `Planner::replan` do not mend: a re-plan file
//! records a rest kept, repaired or searched anew, which `check` makes again.

use super::path::{PathControl, SimulatedPath};
use super::Problem;
use crate::scene::Goal;
use crate::state::State;

/// The share of a re-plan's search time a repair's search gets: what a repair finds, it
/// finds fast; what it does not find is then searched anew, with the whole time.
pub const REPAIR_SHARE: f64 = 0.25;

/// What the rest of a plan does from an observed state (the start of the problem it is
/// judged in).
#[derive(Clone, Debug, PartialEq)]
pub enum RestFrom {
    /// It reaches the goal: kept whole.
    Reaches,
    /// Its first `valid` controls are valid (all of them when it ends short of the goal)
    /// and end in `end`: kept to there, an ending searched from `end`. `valid` is 0 when
    /// its first control is not valid, or it has none: then it is searched anew.
    EndsShort {
        /// Controls of the rest valid from the observed state.
        valid: usize,
        /// The state where they end (the observed state when `valid` is 0).
        end: State,
        /// Why the rest is not kept whole, in words (the control that stops and the rule
        /// it breaks, or how far the goal is missed).
        why: String,
    },
}

impl Problem {
    /// Re-simulates `rest` from the problem's start (the observed state) and judges it:
    /// `reaches` says whether a final state does the plan's work (the goal, or a goal
    /// with part of its margin spent, as the executor judges it). The re-simulation comes
    /// with the verdict.
    pub fn rest_from(
        &self,
        rest: &[PathControl],
        reaches: impl Fn(&State) -> bool,
    ) -> (RestFrom, SimulatedPath) {
        let simulated = self.simulate(rest, false);
        (self.verdict_on(&simulated, reaches), simulated)
    }

    /// The verdict on a rest already re-simulated from the problem's start (`simulated`,
    /// [`Problem::rest_from`]'s), by `reaches`: judging the same rest by another aim needs
    /// no second simulation.
    pub fn verdict_on(
        &self,
        simulated: &SimulatedPath,
        reaches: impl Fn(&State) -> bool,
    ) -> RestFrom {
        let end = simulated.final_state();
        match &simulated.stopped_by {
            None if reaches(end) => RestFrom::Reaches,
            None => RestFrom::EndsShort {
                valid: simulated.states.len() - 1,
                end: end.clone(),
                why: short_of(&self.scene().goal, end),
            },
            Some((k, reason)) => RestFrom::EndsShort {
                valid: *k,
                end: simulated.states[*k].clone(),
                why: format!("its control {k} stops: {reason}"),
            },
        }
    }
}

/// Why a rest that is valid to its end is not kept: how far its end misses the goal. An
/// object goal's end may lie inside the disc and still short of the goal region (the disc
/// less its margin) or of what the judge asks: that is said with both distances, not as a
/// miss of 0 mm.
fn short_of(goal: &Goal, end: &State) -> String {
    let task = goal.task_distance(end);
    match goal {
        Goal::ObjectInDisc { .. } if task <= 0.0 => format!(
            "the goal object ends {:.1} mm inside the disc's edge, {:.1} mm from the goal \
             region (the disc less its margin)",
            -1e3 * task,
            1e3 * goal.distance(end)
        ),
        _ => format!("the goal is missed by {:.1} mm", 1e3 * task.max(0.0)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planning::PlannerKind;
    use crate::robot::EeAction;
    use crate::Scene;

    /// The planar hand of `tests/data/hand_round_a_stick.yaml` (a box 0.04 m deep, its
    /// centre at x = 0.35 m) pushes the box (centre 0.7 m, 0.1 m wide) straight ahead,
    /// 0.04 m a control, and touches it after seven: the box's centre ends at
    /// 0.7 + 0.04 (pushes - 7) m. The goal disc: centre x = 0.85 m, radius 0.05 m, its
    /// margin 0.03 m (60 % of the radius at most).
    fn pushes(n: usize) -> Vec<PathControl> {
        let ahead = PathControl {
            action: EeAction::planar(0.2, 0.0, 0.0),
            steps: 20,
        };
        vec![ahead; n]
    }

    fn why_short(n: usize) -> String {
        let scene = Scene::load("tests/data/hand_round_a_stick.yaml").unwrap();
        let problem = Problem::new(scene.clone(), PlannerKind::PushKpiece);
        let (verdict, simulated) = problem.rest_from(&pushes(n), |s| scene.goal.is_satisfied(s));
        assert!(simulated.valid(), "{:?}", simulated.stopped_by);
        match verdict {
            RestFrom::EndsShort { why, .. } => why,
            RestFrom::Reaches => panic!("{n} pushes reach the goal"),
        }
    }

    #[test]
    fn a_rest_ending_inside_the_disc_short_of_its_margin_says_both_distances() {
        // Ten controls: the box's centre at 0.82 m, 30 mm from the disc's centre: 20 mm
        // inside its edge, 10 mm from the goal region (the 20 mm disc the margin leaves).
        assert_eq!(
            why_short(10),
            "the goal object ends 20.0 mm inside the disc's edge, 10.0 mm from the goal \
             region (the disc less its margin)"
        );
        // Nine: at 0.78 m, 70 mm from the centre, 20 mm outside the disc.
        assert_eq!(why_short(9), "the goal is missed by 20.0 mm");
    }
}
