//! The bridge's second half: the C++ entry points Rust calls (the CLI's search and the
//! benchmark of a scene), declarations only. `cpp/api/solve.h` and `cpp/api/benchmark.h` declare
//! them on the C++ side.

/// The declarations cxx generates both sides from (`pushplan/src/bridge/entry.rs.h`).
#[allow(missing_docs)]
#[cxx::bridge(namespace = "pushplan::bridge")]
pub mod ffi {
    /// One search of the CLI (`plan`); the CLI finishes the path itself.
    #[derive(Debug, Clone)]
    pub struct SolveOptions {
        pub planner: PlannerKind,
        pub time_limit: f64,
        pub seed: u64,
        pub k: u32,
        pub goal_bias: f64,
        pub intermediate_states: bool,
        pub progress: bool,
        /// Robust planning: the search goes on until a solution keeps this robustness.
        pub robust_trials: usize,
        pub robust_rate: f64,
        /// Shortcutting budget (s of work) toward robustness for each solution not robust
        /// enough (pushplan::Options::robust_shortcut).
        pub robust_shortcut: f64,
        /// Perturbed worlds every tree state carries (pushplan::Options::robust_particles).
        pub robust_particles: u32,
        /// Threads to plan on (pushplan::Options::threads); at least 1.
        pub threads: u32,
        /// First restart budget in propagation steps (pushplan::Options::restart_steps);
        /// 0: never.
        pub restart_steps: u64,
        /// Push KPIECE's patience before it falls back to PC RRT, in propagation steps
        /// (pushplan::Options::fallback_steps); 0: never.
        pub fallback_steps: u64,
    }

    /// The outcome of one search and the path found: controls, their step counts and the
    /// states at the start and after each control, flat.
    #[derive(Debug, Clone)]
    pub struct SolveOutput {
        pub exact: bool,
        pub approximate: bool,
        pub planning_time: f64,
        pub tree_size: usize,
        pub propagation_steps: u64,
        pub search: SearchStats,
        /// Attempts started over for lack of a solution (pushplan::Plan::restarts).
        pub restarts: u64,
        /// Searches that fell back to PC RRT (pushplan::Plan::fallbacks).
        pub fallbacks: u64,
        pub controls: Vec<f64>,
        pub steps: Vec<usize>,
        pub states: Vec<f64>,
    }

    /// How far the CLI's search is (pushplan::Progress): once a second, or an event.
    #[derive(Debug, Clone)]
    pub struct SearchProgress {
        pub seconds: f64,
        pub propagation_steps: u64,
        pub steps_per_second: f64,
        /// Share of the time since the last report spent propagating.
        pub propagating: f64,
        /// States in all trees; 0 when the planner has none to count.
        pub tree_states: usize,
        pub searches: u32,
        /// Smallest goal distance reached (m, or rad for a configuration goal).
        pub closest_goal_distance: f64,
        /// Not empty: an event rather than a periodic report.
        pub note: String,
    }

    /// One run of one planner on one scene (`ompl::tools::Benchmark`), seeded from
    /// `seed` and `run` only; the OMPL log goes to `log`.
    #[derive(Debug, Clone)]
    pub struct BenchOptions {
        pub planner: PlannerKind,
        pub run: u32,
        pub time_limit: f64,
        pub seed: u64,
        /// Shortcutting budget (s of work) measured after a solved run.
        pub shortcut: f64,
        /// First restart budget in propagation steps; 0: never.
        pub restart_steps: u64,
        /// Push KPIECE's patience before it falls back to PC RRT (steps); 0: never.
        pub fallback_steps: u64,
        /// Threads of the run: one search whose propagations run on them (the planners
        /// that share one search), else 1.
        pub threads: u32,
        pub log: String,
    }

    /// Reaching a grasp (pushplan::ReachOptions): IK-BiRRT's time, seed and P_sample.
    #[derive(Debug, Clone)]
    pub struct ReachOptions {
        pub time_limit: f64,
        pub seed: u64,
        pub sample_probability: f64,
    }

    /// A reach (pushplan::Reach): waypoints flat, one configuration after another.
    #[derive(Debug, Clone)]
    pub struct ReachOutput {
        pub solved: bool,
        pub planning_time: f64,
        pub goal_samples: usize,
        pub tree_size: usize,
        pub waypoints: Vec<f64>,
    }

    unsafe extern "C++" {
        include!("pushplan/pushplan.h");
        #[namespace = "pushplan"]
        type PlannerKind = crate::planning::PlannerKind;
        include!("pushplan/src/bridge.rs.h");
        type SearchStats = crate::bridge::ffi::SearchStats;
        include!("pushplan/cpp/api/solve.h");
        /// Searches the scene file with OMPL (the CLI's entry point), telling `progress`
        /// how far it is when `options.progress` is set.
        fn solve(
            scene_path: &str,
            options: &SolveOptions,
            progress: fn(report: &SearchProgress),
        ) -> Result<SolveOutput>;
        /// Reaches a grasp of `object` with IK-BiRRT from the arm at `from_q` with the
        /// objects at `from_objects` (x, y, yaw each); from the scene's start if `from_q`
        /// is empty.
        fn reach(
            scene_path: &str,
            object: &str,
            from_q: &[f64],
            from_objects: &[f64],
            options: &ReachOptions,
        ) -> Result<ReachOutput>;
        include!("pushplan/cpp/api/benchmark.h");
        /// Runs one benchmark run with ompl::tools::Benchmark and writes its log.
        fn benchmark_scene(scene_path: &str, options: &BenchOptions) -> Result<()>;
    }
}

pub use ffi::{BenchOptions, ReachOptions, ReachOutput, SearchProgress, SolveOptions, SolveOutput};
use std::path::Path;

/// Searches a scene file with OMPL (the C++ side), as the CLI does.
pub fn solve(
    scene_path: &Path,
    options: &SolveOptions,
    progress: fn(&SearchProgress),
) -> Result<SolveOutput, String> {
    ffi::solve(&scene_path.to_string_lossy(), options, progress).map_err(|e| e.what().to_string())
}

/// Benchmarks one scene with OMPL's tooling, writing `options.log`.
pub fn benchmark_scene(scene_path: &Path, options: &BenchOptions) -> Result<(), String> {
    ffi::benchmark_scene(&scene_path.to_string_lossy(), options).map_err(|e| e.what().to_string())
}

/// Reaches a grasp of `object` with IK-BiRRT (the C++ side) from `from` (`None`: the
/// scene's start).
pub fn reach(
    scene_path: &Path,
    object: &str,
    from: Option<&crate::state::State>,
    options: &ReachOptions,
) -> Result<ReachOutput, String> {
    let (q, objects): (Vec<f64>, Vec<f64>) = match from {
        Some(s) => (
            s.q.as_slice().to_vec(),
            s.objects.iter().flat_map(|p| [p.x, p.y, p.theta]).collect(),
        ),
        None => (Vec::new(), Vec::new()),
    };
    ffi::reach(&scene_path.to_string_lossy(), object, &q, &objects, options)
        .map_err(|e| e.what().to_string())
}
