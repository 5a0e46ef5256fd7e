//! [`Search`]: the search the applications call (OMPL's planners in C++, behind the
//! bridge), in the model's types. The CLI names only this trait; `main` hands it the
//! bridge's implementation (`bridge::OmplSearch`), so nothing above the bridge imports it.

use super::SearchStats;
use crate::planning::path::PathControl;
use crate::planning::{MeasuredRate, RunSettings};
use crate::scene::Scene;
use crate::state::State;
use nalgebra::DVector;
use std::path::Path;

/// How far a search is (C++'s `pushplan::Progress`), once a second; an event comes with
/// a note of its own ([`Search::solve`]). Laid out as C++'s `pushplan::detail::SearchProgress`:
/// the bridge carries it as it is.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SearchProgress {
    /// Since the search started (s).
    pub seconds: f64,
    /// Propagation steps taken so far.
    pub propagation_steps: u64,
    /// Propagation steps per second since the last report.
    pub steps_per_second: f64,
    /// Share of the time since the last report spent propagating.
    pub propagating: f64,
    /// States in all trees; 0 when the planner has none to count.
    pub tree_states: usize,
    /// Smallest goal distance reached (m, or rad for a configuration goal).
    pub closest_goal_distance: f64,
    /// Searches running in parallel.
    pub searches: u32,
}

/// How a search went. Laid out as C++'s `pushplan::detail::SearchSummary`: the bridge
/// carries it as it is.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SearchSummary {
    /// An exact solution.
    pub exact: bool,
    /// Not exact, but a path toward the goal.
    pub approximate: bool,
    /// The search's wall time (s).
    pub planning_time: f64,
    /// States in all trees.
    pub tree_size: usize,
    /// Propagation steps taken.
    pub propagation_steps: u64,
    /// Attempts started over for lack of a solution.
    pub restarts: u64,
    /// Searches that fell back to PC RRT.
    pub fallbacks: u64,
    /// Times a fallen-back search handed the problem back to Push KPIECE from a state
    /// where PC RRT had moved the goal object nearer the goal.
    pub handed_back: u64,
    /// Lanes the one search's extensions ran on (0: one thread, or a planner that runs
    /// one search per thread).
    pub lanes: u32,
}

/// What a search found: how it went, and the path as found (not finished: the caller
/// finishes it, `planning::finish`).
#[derive(Clone, Debug, PartialEq)]
pub struct Found {
    /// How the search went.
    pub summary: SearchSummary,
    /// What its propagations did.
    pub search: SearchStats,
    /// The path's controls with their step counts.
    pub controls: Vec<PathControl>,
    /// The states at the start and after each control (none without a path).
    pub states: Vec<State>,
    /// The path's success rate under noise as robust planning measured it (with the
    /// run's seed), if it did.
    pub robustness: Option<MeasuredRate>,
}

/// Reaching a grasp with IK-BiRRT: its time limit (s), seed and P_sample (the
/// probability of sampling the grasp region). Laid out as C++'s
/// `pushplan::detail::ReachSettings`: the bridge carries it as it is.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReachSettings {
    /// IK-BiRRT's time limit (s).
    pub time_limit: f64,
    /// The seed of every random choice.
    pub seed: u64,
    /// The probability of sampling the grasp region (P_sample), in [0, 1].
    pub sample_probability: f64,
}

/// A reach of a grasp.
#[derive(Clone, Debug, PartialEq)]
pub struct Reached {
    /// Whether a reach was found.
    pub solved: bool,
    /// The search's wall time (s).
    pub planning_time: f64,
    /// Inverse-kinematics solutions in the grasp regions.
    pub goal_samples: usize,
    /// States in both trees.
    pub tree_size: usize,
    /// The configurations of the reach, from the start on.
    pub waypoints: Vec<DVector<f64>>,
}

/// The search behind the applications. Shared between threads: a closed loop searches a
/// repair on a thread of its own while the arm plays.
pub trait Search: Sync {
    /// Searches `scene` from its start as `settings` say (a start observed while a plan
    /// runs comes as `Scene::with_start` makes it). The scene is the one already loaded:
    /// a re-plan does not read and prepare its file again (for a dense scene that is
    /// 40-80 ms, most of it the objects' support grids, a share of every re-plan's
    /// latency). Its shortcut budget is the caller's to spend: the path comes back as
    /// found. Tells `progress` how far it is: a report once a second with an empty note,
    /// or an event (a note, with the totals so far).
    fn solve(
        &self,
        scene: &Scene,
        settings: &RunSettings,
        progress: Option<fn(&SearchProgress, &str)>,
    ) -> Result<Found, String>;

    /// Reaches a grasp of `object` in `scene` (the one already loaded, as for
    /// [`Search::solve`]) with IK-BiRRT from `from` (`None`: the scene's start).
    fn reach(
        &self,
        scene: &Scene,
        object: &str,
        from: Option<&State>,
        settings: &ReachSettings,
    ) -> Result<Reached, String>;

    /// One run of `settings.planner` on the scene with OMPL's benchmark tooling, seeded
    /// from `settings.seed` and `run` only; writes OMPL's log to `log`.
    fn benchmark(
        &self,
        scene: &Path,
        settings: &RunSettings,
        run: u32,
        log: &Path,
    ) -> Result<(), String>;
}
