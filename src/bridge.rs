//! The bridge between the Rust model and the OMPL side (cxx): one narrow opaque type per
//! OMPL concept the C++ side holds, each made from a [`Problem`] (a loaded scene and the
//! search it is set up for):
//!
//! | Rust type           | OMPL concept                         | C++ holder                     |
//! |---------------------|--------------------------------------|--------------------------------|
//! | [`Problem`]         | problem definition, space information | `detail::Model`                |
//! | [`Propagator`]      | `oc::StatePropagator`                | `PushStatePropagator`, searches |
//! | [`ValidityChecker`] | `ob::StateValidityChecker`           | `PushValidityChecker`          |
//! | [`Metric`], [`NearestTree`] | `ob::StateSpace::distance`, `NearestNeighbors` | `PushStateSpace`, `ModelNearestNeighbors` |
//! | [`Goal`]            | `ob::GoalSampleableRegion`           | `PushGoal`                     |
//! | [`Projection`]      | `ob::ProjectionEvaluator`, push headings | `PushProjection`, `PushControlSampler` |
//! | [`Finisher`]        | the path after the search            | `Planner::solve`               |
//! | [`Executor`]        | closed-loop execution (re-plans)     | `Executor`                     |
//! | [`Darrt`]           | DARRT's primitives                   | `Darrt`                        |
//! | [`Grasping`]        | grasp regions                        | `IkBiRrt`, `Planner::reach`    |
//!
//! The parts of one problem share its core state (the mode, the perturbed worlds,
//! the last propagation's result). Declarations and one-line delegations only here; the
//! types are in their files. States and controls cross in the flat layouts of
//! [`crate::state::State::to_flat`] and [`crate::robot::EeAction::from_flat`]. Failures
//! cross as errors (C++ exceptions) with their message; a panic becomes such an error.

mod convert;
mod core;
mod darrt;
pub mod entry;
mod executor;
mod finisher;
mod goal;
mod grasping;
mod metric;
mod problem;
mod projection;
mod propagator;
mod validity;

pub use darrt::Darrt;
pub use entry::OmplSearch;
pub use executor::Executor;
pub use finisher::Finisher;
pub use goal::Goal;
pub use grasping::Grasping;
pub use metric::Metric;
pub use problem::Problem;
pub use projection::Projection;
pub use propagator::Propagator;
pub use validity::ValidityChecker;

use crate::planner::NearestTree;
use crate::planning::PlannerKind;
use convert::{
    add_search_stats, check_run_settings, executor_defaults, plan_robust_trials,
    planner_cut_at_time_limit, planner_kind, planner_name, planner_shares_one_search,
    planner_yields_controls, repair_share, run_settings_of_scene, search_stats,
};
use metric::{tree_add, tree_nearest, tree_nearest_k, tree_nearest_r};

/// Binds Rust types to their C++ twins, which the bridge passes by value.
macro_rules! trivial_twins {
    ($($rust:ty => $cpp:literal),* $(,)?) => {$(
        // SAFETY: see the call.
        unsafe impl cxx::ExternType for $rust {
            type Id = cxx::type_id!($cpp);
            type Kind = cxx::kind::Trivial;
        }
    )*};
}

// SAFETY: each Rust type is `#[repr(..)]` with the layout of its C++ twin, a trivial
// type. `PlannerKind`: the values of `enum class PlannerKind : std::uint8_t`
// (tests/cpp/api_contract.cpp sends every kind through the bridge and back);
// `PathMetrics` (include/pushplan/pushplan.h): the same fields in the same order, checked
// by static_assert in cpp/problem/bridge_types.h. The rest: build.rs generates the C++
// twins from these declarations, and both compilers check the offsets it computed (the
// Rust side: twin_layout.rs, below).
trivial_twins! {
    PlannerKind => "pushplan::PlannerKind",
    crate::planning::path::PathMetrics => "pushplan::PathMetrics",
    crate::planning::RunSettings => "pushplan::detail::RunSettings",
    crate::planner::SearchProgress => "pushplan::detail::SearchProgress",
    crate::planner::SearchSummary => "pushplan::detail::SearchSummary",
    crate::planner::ReachSettings => "pushplan::detail::ReachSettings",
    PlannerParams => "pushplan::detail::PlannerParams",
}
include!(concat!(env!("OUT_DIR"), "/twin_layout.rs"));

/// The scene's planner parameters as the bridge carries them: the model's type, whose
/// layout C++ shares (a wrapper because the model crate does not know cxx).
#[repr(transparent)]
#[derive(Clone, Copy, Debug)]
pub struct PlannerParams(pub crate::scene::PlannerParams);

/// The declarations cxx generates both sides from (`pushplan/src/bridge.rs.h`).
#[allow(missing_docs)]
#[cxx::bridge(namespace = "pushplan::bridge")]
pub mod ffi {
    /// What the OMPL side needs to know about a scene (lengths in m, angles in rad).
    pub struct SceneInfo {
        pub name: String,
        pub dof: usize,
        pub objects: usize,
        pub joint_names: Vec<String>,
        pub joint_lower: Vec<f64>,
        pub joint_upper: Vec<f64>,
        pub object_names: Vec<String>,
        pub link_names: Vec<String>,
        /// The table's extent: min x, max x, min y, max y.
        pub table: [f64; 4],
        /// The scene's planner parameters.
        pub planner: PlannerParams,
        /// The goal object's index, or -1 for a configuration goal.
        pub goal_object: i64,
        /// The disc the goal object's centre must reach (margin taken off), or the
        /// configuration goal's tolerance as `goal_radius`.
        pub goal_center: [f64; 2],
        pub goal_radius: f64,
        pub goal_configuration: Vec<f64>,
        /// The object whose grasp a grasp goal reaches, or -1.
        pub grasp_object: i64,
        pub start: Vec<f64>,
    }

    /// `propagate::Contact` with its control and step (force in N).
    pub struct Contact {
        pub control: usize,
        pub step: usize,
        pub link: usize,
        pub object: usize,
        pub force: f64,
    }

    /// `trajectory::Trajectory`, flat: per sample the joints, then every object's x, y, yaw.
    pub struct Trajectory {
        pub rate: f64,
        pub times: Vec<f64>,
        pub q: Vec<f64>,
        pub objects: Vec<f64>,
    }

    /// `planner::FinishSettings`; `robust_trials` 0 for no robustness requirement.
    pub struct FinishSettings {
        pub shortcut: f64,
        pub seed: u64,
        pub robust_trials: usize,
        pub robust_rate: f64,
        /// The whole budget toward robustness (a solution not robust enough yet), not
        /// shortening first: `planner::FinishSettings::only_toward_robustness`.
        pub only_toward_robustness: bool,
        /// `planner::FinishSettings::unseen_trials`: worlds no solution was chosen in that
        /// the finished path is measured in (0: none).
        pub unseen_trials: usize,
        /// The found path's rate, already measured with the same seed over `found_trials`
        /// trials (negative: not measured).
        pub found_rate: f64,
        pub found_trials: usize,
        /// Seconds from now at which shortcutting and robustness checks stop, budget left
        /// or not (infinite: never).
        pub time_left: f64,
        /// `planner::FinishSettings::threads` (0 counts as one).
        pub threads: usize,
    }

    /// `planner::FinishedPath`, flat; `robustness` -1 if not measured, else over
    /// `robustness_trials` perturbed re-simulations; `unseen_rate` likewise, over
    /// `unseen_trials`.
    pub struct FinishedPath {
        pub controls: Vec<f64>,
        pub steps: Vec<usize>,
        /// The state at the start and after each control.
        pub states: Vec<f64>,
        pub contacts: Vec<Contact>,
        pub before: PathMetrics,
        pub after: PathMetrics,
        pub shortcut_attempts: usize,
        pub shortcut_accepted: usize,
        pub shortcut_dropped_as_less_robust: bool,
        pub robustness: f64,
        pub robustness_trials: usize,
        pub unseen_rate: f64,
        pub unseen_trials: usize,
    }

    /// `planning::rest::RestFrom`, flat: the rest of a plan judged from an observed state.
    /// `reaches`: it reaches the goal and `states` are its states (the start and after
    /// each control); else its first `valid` controls are valid and `states` are theirs,
    /// the last where they end (a repair searches from there), and `why` says why not.
    pub struct RestFrom {
        pub reaches: bool,
        pub valid: usize,
        pub states: Vec<f64>,
        pub why: String,
    }

    /// `planner::closed_loop::ClosedLoopSettings` as the C++ API's `ExecutorOptions` name
    /// them (the CLI's `execute --closed-loop` options), and the pace the application
    /// plays at (`--speed`).
    pub struct ExecutorSettings {
        pub planner: PlannerKind,
        pub seed: u64,
        pub replan_time: f64,
        pub replan_threads: u32,
        pub replan_shortcut: f64,
        pub replan_polish: f64,
        pub replan_mend: f64,
        pub max_replans: usize,
        pub replan_budget: f64,
        pub replan_leg: f64,
        pub repair_ahead: bool,
        pub speed: f64,
    }

    /// What an executor asks for (`planner::closed_loop::Step`).
    pub enum ExecutorStepKind {
        Play,
        Finished,
        Stopped,
    }

    /// `planner::closed_loop::Step`, flat: to `Play`, the control (`control`, held for
    /// `steps` steps), its trajectory and the state predicted at its end; `why` a stop's
    /// reason.
    pub struct ExecutorStep {
        pub kind: ExecutorStepKind,
        pub control: Vec<f64>,
        pub steps: usize,
        pub trajectory: Trajectory,
        pub predicted: Vec<f64>,
        pub why: String,
    }

    /// An execution so far (`planner::closed_loop::ClosedLoopTrial`'s counts; empty
    /// strings for none).
    pub struct ExecutorReport {
        pub controls_played: usize,
        pub kept: usize,
        pub invalid_rests: usize,
        pub replans: usize,
        pub repairs: usize,
        pub failed_replans: usize,
        pub legs: usize,
        pub backoffs: usize,
        pub search_time: f64,
        pub latencies: Vec<f64>,
        pub replan_latencies: Vec<f64>,
        pub last_failure: String,
        pub stopped: String,
    }

    /// Part of a DARRT path: flat states one after another, and what the hand holds in
    /// each (an object index, or -1).
    pub struct HeldStates {
        pub states: Vec<f64>,
        pub held: Vec<i64>,
    }

    /// `darrt::check_path`'s verdict; `message` says why an invalid path is invalid.
    pub struct PrimitiveCheck {
        pub valid: bool,
        pub goal_reached: bool,
        pub message: String,
        pub metrics: PathMetrics,
        pub durations: Vec<f64>,
        pub pick_places: usize,
    }

    /// `planner::PushTarget`: a push worth trying, `object` toward `target` (world xy, m).
    #[derive(Debug, Clone, Copy)]
    pub struct PushTarget {
        pub object: usize,
        pub target: [f64; 2],
    }

    /// `planner::SearchStats`; the reasons and their counts in the same order.
    #[derive(Debug, Clone)]
    pub struct SearchStats {
        pub propagations: u64,
        pub steps: u64,
        pub moved_goal_object: u64,
        pub moved_clutter: u64,
        pub stop_reasons: Vec<String>,
        pub stop_counts: Vec<u64>,
        /// Self-collision stops by link pair: two names per pair, flat.
        pub self_collision_links: Vec<String>,
        pub self_collision_counts: Vec<u64>,
    }

    extern "Rust" {
        type Problem;
        #[Self = "Problem"]
        fn load(path: &str) -> Result<Box<Problem>>;
        #[Self = "Problem"]
        fn from_yaml(yaml: &str, source: &str) -> Result<Box<Problem>>;
        fn duplicate(self: &Problem) -> Box<Problem>;
        fn info(self: &Problem) -> SceneInfo;
        fn scene_warnings(self: &Problem) -> Vec<String>;
        fn set_start(self: &mut Problem, flat: &[f64]) -> Result<()>;
        fn set_static_clutter(self: &mut Problem, on: bool);
        fn static_clutter(self: &Problem) -> bool;
        fn set_particles(self: &mut Problem, count: usize, seed: u64) -> Result<()>;
        fn start_particles(self: &Problem) -> Vec<f64>;

        type Propagator;
        #[Self = "Propagator"]
        #[cxx_name = "make"]
        fn new(problem: &Problem) -> Box<Propagator>;
        fn propagate(
            self: &mut Propagator,
            x: &[f64],
            particles: &[f64],
            u: &[f64],
            steps: usize,
            out: &mut [f64],
            out_particles: &mut [f64],
        ) -> Result<bool>;
        fn set_time_limit(self: &mut Propagator, seconds: f64);
        fn past_time_limit(self: &Propagator) -> bool;
        fn steps(self: &Propagator) -> u64;
        fn seconds(self: &Propagator) -> f64;
        fn search_stats(propagator: &Propagator) -> SearchStats;
        fn add_search_stats(a: &SearchStats, b: &SearchStats) -> SearchStats;

        type ValidityChecker;
        #[Self = "ValidityChecker"]
        #[cxx_name = "make"]
        fn new(problem: &Problem) -> Box<ValidityChecker>;
        fn is_valid(self: &ValidityChecker, state: &[f64], particles: &[f64]) -> Result<bool>;

        type Metric;
        #[Self = "Metric"]
        #[cxx_name = "make"]
        fn new(problem: &Problem) -> Box<Metric>;
        fn distance(self: &Metric, a: &[f64], b: &[f64]) -> Result<f64>;
        fn max_extent(self: &Metric) -> f64;
        fn nearest_tree(self: &Metric) -> Box<NearestTree>;

        type NearestTree;
        fn tree_add(tree: &mut NearestTree, state: &[f64]) -> Result<usize>;
        fn remove(self: &mut NearestTree, id: usize) -> bool;
        fn clear(self: &mut NearestTree);
        fn len(self: &NearestTree) -> usize;
        fn tree_nearest(tree: &NearestTree, state: &[f64]) -> Result<i64>;
        fn tree_nearest_k(tree: &NearestTree, state: &[f64], k: usize) -> Result<Vec<usize>>;
        fn tree_nearest_r(tree: &NearestTree, state: &[f64], radius: f64) -> Result<Vec<usize>>;

        type Goal;
        #[Self = "Goal"]
        #[cxx_name = "make"]
        fn new(problem: &Problem) -> Box<Goal>;
        fn distance(self: &Goal, state: &[f64], particles: &[f64]) -> Result<f64>;
        /// The smallest goal distance of a state so far (progress reports).
        fn closest_distance(self: &Goal) -> f64;
        /// The largest goal distance of a state so far.
        fn farthest_distance(self: &Goal) -> f64;
        /// Forgets the distances met: the closest and farthest start over.
        fn forget_met(self: &Goal);
        fn sample_grasp(self: &Goal, state: &[f64], object: usize, seed: u64) -> Result<Vec<f64>>;

        type Projection;
        #[Self = "Projection"]
        #[cxx_name = "make"]
        fn new(problem: &Problem) -> Box<Projection>;
        fn project(self: &Projection, state: &[f64]) -> Result<Vec<f64>>;
        fn push_heading(
            self: &Projection,
            state: &[f64],
            object: usize,
            target: &[f64],
        ) -> Result<Vec<f64>>;
        fn push_blockers(self: &Projection, state: &[f64]) -> Result<Vec<PushTarget>>;

        type Finisher;
        #[Self = "Finisher"]
        #[cxx_name = "make"]
        fn new(problem: &Problem) -> Box<Finisher>;
        fn finish(
            self: &Finisher,
            u: &[f64],
            steps: &[usize],
            x: &[f64],
            solved: bool,
            settings: &FinishSettings,
        ) -> Result<FinishedPath>;
        fn trajectory(self: &Finisher, u: &[f64], steps: &[usize]) -> Result<Trajectory>;
        fn rest_from(self: &Finisher, u: &[f64], steps: &[usize]) -> Result<RestFrom>;

        type Executor;
        #[Self = "Executor"]
        #[cxx_name = "make"]
        fn new(
            problem: &Problem,
            u: &[f64],
            steps: &[usize],
            settings: &ExecutorSettings,
        ) -> Result<Box<Executor>>;
        fn step(self: &mut Executor, observed: &[f64]) -> Result<ExecutorStep>;
        fn report(self: &Executor) -> ExecutorReport;
        /// `execute --closed-loop`'s defaults (planner, seed and threads the caller's).
        fn executor_defaults() -> ExecutorSettings;

        type Darrt;
        #[Self = "Darrt"]
        #[cxx_name = "make"]
        fn new(problem: &Problem) -> Box<Darrt>;
        fn transit(self: &Darrt, from: &[f64], to: &[f64]) -> Result<bool>;
        fn approach(
            self: &Darrt,
            x: &[f64],
            object: usize,
            target: &[f64],
            out: &mut [f64],
        ) -> Result<bool>;
        fn carry(self: &Darrt, x: &[f64], object: usize, target: &[f64]) -> Result<Vec<f64>>;
        fn pick_place(
            self: &Darrt,
            x: &[f64],
            object: usize,
            target: &[f64],
            seed: u64,
        ) -> Result<HeldStates>;
        fn check(self: &Darrt, states: &[f64], held: &[i64]) -> Result<PrimitiveCheck>;

        type Grasping;
        #[Self = "Grasping"]
        #[cxx_name = "make"]
        fn new(problem: &Problem) -> Box<Grasping>;
        fn graspable_object(self: &Grasping, name: &str) -> Result<usize>;
        fn sample(self: &Grasping, state: &[f64], object: usize, seed: u64) -> Result<Vec<f64>>;
        fn distance(self: &Grasping, state: &[f64], object: usize) -> Result<f64>;
        fn check_reach(
            self: &Grasping,
            from: &[f64],
            object: usize,
            waypoints: &[f64],
        ) -> Result<String>;

        fn planner_name(kind: PlannerKind) -> &'static str;
        fn planner_yields_controls(kind: PlannerKind) -> bool;
        /// `planning::RunSettings::check`: a value outside the limits table, named as
        /// C++'s `Options` names it.
        fn check_run_settings(settings: &RunSettings) -> Result<()>;
        /// `planning::RunSettings::of_scene`: the settings no option changes.
        fn run_settings_of_scene(kind: PlannerKind, params: &PlannerParams) -> RunSettings;
        /// `planning::PLAN_ROBUST_TRIALS`: a plan's robustness check when none is asked for.
        fn plan_robust_trials() -> u32;
        /// `planning::rest::REPAIR_SHARE`: a repair's share of a re-plan's search time.
        fn repair_share() -> f64;
        fn planner_shares_one_search(kind: PlannerKind) -> bool;
        fn planner_cut_at_time_limit(kind: PlannerKind) -> bool;
        fn planner_kind(name: &str) -> Result<PlannerKind>;
    }

    unsafe extern "C++" {
        include!("pushplan/pushplan.h");
        #[namespace = "pushplan"]
        type PlannerKind = crate::planning::PlannerKind;
        #[namespace = "pushplan"]
        type PathMetrics = crate::planning::path::PathMetrics;
        include!("pushplan/cpp/problem/bridge_types.h");
        #[namespace = "pushplan::detail"]
        type PlannerParams = crate::bridge::PlannerParams;
        #[namespace = "pushplan::detail"]
        type RunSettings = crate::planning::RunSettings;
    }
}
