//! How a closed loop plays and re-plans: [`ClosedLoopSettings`], the options a user gives
//! ([`ClosedLoopOptions`]) and their [`defaults`].

use crate::planning::execute::DRIFT;
use crate::planning::PlannerKind;

/// How a closed-loop execution plays and re-plans.
#[derive(Clone, Debug, PartialEq)]
pub struct ClosedLoopSettings {
    /// The planner of every re-plan (the plan's).
    pub planner: PlannerKind,
    /// Time limit of each re-planning search (s).
    pub replan_time: f64,
    /// Threads of each re-planning search: a re-plan is what the arm may wait on, and a
    /// search on two threads finds a plan in about half the time (BENCHMARKS.md, "Two
    /// threads against one").
    pub replan_threads: u32,
    /// Shortcutting budget of each re-planned path before its first control is played
    /// (s of work).
    pub replan_shortcut: f64,
    /// Shortcutting budget of each re-planned path while the arm plays it (s of work):
    /// the rest after the control being played is shortened from where that control is
    /// predicted to end, as much work per control as the control lasts (a robot's planner
    /// works while its arm moves), until this much is spent.
    pub polish: f64,
    /// Seed of the first re-plan; the next ones count up from it.
    pub seed: u64,
    /// Re-planning searches at most; then the execution stops.
    pub max_replans: usize,
    /// Time the re-planning searches of one execution may take in all, found or not (s):
    /// a search gets no more than what is left, and once it is spent the execution stops
    /// with a report: it bounds a trial whose searches cannot succeed. Hard scenes need
    /// minutes: benchmark 22's trials that reach the goal search up to 240 s in all, and
    /// at 120 s six of ten were stopped (BENCHMARKS.md, "The search budget").
    pub search_budget: f64,
    /// An object this far from its predicted position cuts its control short (m).
    pub tolerance: f64,
    /// How far ahead a leg aims (m; 0: no legs). Where no search from the observed state
    /// finds a way to the goal, the executor searches a leg: the goal object to a point
    /// this far ahead on its track in the last rest that reached the goal, within half
    /// this distance. A hard scene's search to the goal needs a million steps; one a
    /// decimetre along a way the model has already found takes milliseconds to seconds
    /// (dense 19: docs/notes/plans-in-the-world.md, "Legs along the track"). Farther from
    /// the goal disc than a leg (the leg's aim off the disc) the leg is searched first,
    /// and the goal only where no leg is found.
    pub leg: f64,
    /// Search a repair on a thread of its own while the arm plays the rest's valid part
    /// (the `ahead` module), instead of holding the arm while it searches; not where the valid part
    /// ends more than a leg from the goal (there the searches run at once from where the
    /// arm stands, and try a leg). A repair is found in a fraction of a second near the
    /// goal, and the arm need not stop for it (BENCHMARKS.md, "Repairs searched ahead").
    pub repair_ahead: bool,
    /// Work a mend of a rest that no longer reaches the goal may take before any search
    /// (s of work; 0: none): an edit where the rest fails, kept when it is valid and does
    /// the plan's work ([`crate::planning::mend`]).
    pub mend: f64,
}

/// The closed loop's options as a user gives them: `execute --closed-loop`'s flags, and the
/// C++ API's `ExecutorOptions` (the same names; their limits are in [`crate::limits`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ClosedLoopOptions {
    /// [`ClosedLoopSettings::replan_time`] (s).
    pub replan_time: f64,
    /// [`ClosedLoopSettings::replan_threads`].
    pub replan_threads: u32,
    /// [`ClosedLoopSettings::replan_shortcut`] (s of work).
    pub replan_shortcut: f64,
    /// [`ClosedLoopSettings::polish`] (s of work).
    pub replan_polish: f64,
    /// [`ClosedLoopSettings::mend`] (s of work).
    pub replan_mend: f64,
    /// [`ClosedLoopSettings::max_replans`].
    pub max_replans: usize,
    /// [`ClosedLoopSettings::search_budget`] (s).
    pub replan_budget: f64,
    /// [`ClosedLoopSettings::leg`] (m).
    pub replan_leg: f64,
    /// [`ClosedLoopSettings::repair_ahead`].
    pub repair_ahead: bool,
}

impl ClosedLoopOptions {
    /// The settings of a closed loop that re-plans a plan made with `planner` and `seed`
    /// as these options say; an object [`DRIFT`] off its predicted position cuts its
    /// control short.
    pub fn settings(&self, planner: PlannerKind, seed: u64) -> ClosedLoopSettings {
        ClosedLoopSettings {
            planner,
            replan_time: self.replan_time,
            replan_threads: self.replan_threads,
            replan_shortcut: self.replan_shortcut,
            polish: self.replan_polish,
            seed,
            max_replans: self.max_replans,
            search_budget: self.replan_budget,
            tolerance: DRIFT,
            leg: self.replan_leg,
            repair_ahead: self.repair_ahead,
            mend: self.replan_mend,
        }
    }
}

/// `execute --closed-loop`'s defaults, and the C++ API's `ExecutorOptions`'
/// ([`ClosedLoopSettings`] says what each does; the reasons are in `execute --help`).
pub mod defaults {
    /// [`super::ClosedLoopSettings::replan_time`] (s).
    pub const REPLAN_TIME: f64 = 2.0;
    /// [`super::ClosedLoopSettings::replan_shortcut`] (s of work): none, the polish
    /// shortens a re-plan while the arm plays it.
    pub const REPLAN_SHORTCUT: f64 = 0.0;
    /// [`super::ClosedLoopSettings::polish`] (s of work).
    pub const REPLAN_POLISH: f64 = 2.0;
    /// [`super::ClosedLoopSettings::max_replans`].
    pub const MAX_REPLANS: usize = 400;
    /// [`super::ClosedLoopSettings::search_budget`] (s).
    pub const REPLAN_BUDGET: f64 = 300.0;
    /// [`super::ClosedLoopSettings::leg`] (m).
    pub const REPLAN_LEG: f64 = 0.1;
    /// [`super::ClosedLoopSettings::repair_ahead`]: on. Side by side with the arm waiting
    /// on the dense set: 54 of 57 trials against 52 of 57, the arm's waits per trial 6.7 s
    /// against 9.6 s at the median (BENCHMARKS.md, "Repairs searched ahead").
    pub const REPAIR_AHEAD: bool = true;
    /// [`super::ClosedLoopSettings::mend`] (s of work): none. Side by side in MuJoCo on
    /// five hard dense scenes, in two runs, mends reached the goal in 16 of 24 trials and
    /// so did no mends (docs/notes/plans-in-the-world.md, "Mending the rest before
    /// searching").
    pub const REPLAN_MEND: f64 = 0.0;
}
