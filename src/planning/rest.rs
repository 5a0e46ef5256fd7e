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
                why: format!(
                    "the goal is missed by {:.1} mm",
                    1e3 * self.scene().goal.task_distance(end).max(0.0)
                ),
            },
            Some((k, reason)) => RestFrom::EndsShort {
                valid: *k,
                end: simulated.states[*k].clone(),
                why: format!("its control {k} stops: {reason}"),
            },
        }
    }
}
