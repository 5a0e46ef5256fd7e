//! The bridge's second half: the C++ entry points of the applications (a search, a
//! reach, a benchmark run; declared in `cpp/api/solve.h` and `cpp/api/benchmark.h`), and
//! [`OmplSearch`], which offers them as [`crate::planner::Search`] in the model's types.

use super::Problem;
use crate::planner::{Found, ReachSettings, Reached, Search, SearchProgress, SearchStats};
use crate::planning::path::PathControl;
use crate::planning::{MeasuredRate, RunSettings};
use crate::scene::Scene;
use crate::state::State;
use nalgebra::DVector;
use std::cell::Cell;
use std::path::Path;

/// The declarations cxx generates both sides from (`pushplan/src/bridge/entry.rs.h`).
#[allow(missing_docs)]
#[cxx::bridge(namespace = "pushplan::bridge")]
pub mod ffi {
    /// `planner::Found` with the path flat: controls, their step counts and the states
    /// at the start and after each control (`dof` joints, `objects` poses each); the
    /// path's robustness over `robustness_trials` trials as robust planning measured it
    /// (-1: not measured).
    #[derive(Debug, Clone)]
    pub struct SolveOutput {
        pub summary: SearchSummary,
        pub search: SearchStats,
        pub robustness: f64,
        pub robustness_trials: usize,
        pub dof: usize,
        pub objects: usize,
        pub controls: Vec<f64>,
        pub steps: Vec<usize>,
        pub states: Vec<f64>,
    }

    /// A reach (pushplan::Reach): waypoints flat, one configuration of `dof` joints
    /// after another.
    #[derive(Debug, Clone)]
    pub struct ReachOutput {
        pub solved: bool,
        pub planning_time: f64,
        pub goal_samples: usize,
        pub tree_size: usize,
        pub dof: usize,
        pub waypoints: Vec<f64>,
    }

    unsafe extern "C++" {
        include!("pushplan/src/bridge.rs.h");
        type SearchStats = crate::bridge::ffi::SearchStats;
        type Problem = crate::bridge::Problem;
        include!("pushplan/cpp/problem/bridge_types.h");
        #[namespace = "pushplan::detail"]
        type RunSettings = crate::planning::RunSettings;
        #[namespace = "pushplan::detail"]
        type ReachSettings = crate::planner::ReachSettings;
        #[namespace = "pushplan::detail"]
        type SearchProgress = crate::planner::SearchProgress;
        #[namespace = "pushplan::detail"]
        type SearchSummary = crate::planner::SearchSummary;
        include!("pushplan/cpp/api/solve.h");
        /// Searches `problem`'s scene with OMPL from its start, every search and lane on
        /// a copy of it (`Problem::duplicate`), telling `progress` how far it is when
        /// `report` is set; the path comes back as found (not shortcut).
        fn solve(
            problem: &Problem,
            settings: &RunSettings,
            report: bool,
            progress: fn(report: &SearchProgress, note: &str),
        ) -> Result<SolveOutput>;
        /// Reaches a grasp of `object` in `problem`'s scene with IK-BiRRT from the flat
        /// state `from`; from the scene's start if `from` is empty.
        fn reach(
            problem: &Problem,
            object: &str,
            from: &[f64],
            settings: &ReachSettings,
        ) -> Result<ReachOutput>;
        include!("pushplan/cpp/api/benchmark.h");
        /// Runs one benchmark run with ompl::tools::Benchmark and writes its log.
        fn benchmark_scene(
            scene_path: &str,
            settings: &RunSettings,
            run: u32,
            log: &str,
        ) -> Result<()>;
    }
}

/// OMPL's planners (the C++ side), as the applications' [`Search`].
#[derive(Clone, Copy, Debug, Default)]
pub struct OmplSearch;

/// Where a search's reports go: a report, or an event's note.
type Progress = fn(&SearchProgress, &str);

thread_local! {
    /// Where this thread's search reports go: C++ calls back on the thread that called
    /// `solve`, through a plain function pointer.
    static PROGRESS: Cell<Option<Progress>> = const { Cell::new(None) };
}

/// The C++ search's report, passed on to this thread's progress function.
fn tell(report: &SearchProgress, note: &str) {
    if let Some(progress) = PROGRESS.with(Cell::get) {
        progress(report, note);
    }
}

impl Search for OmplSearch {
    fn solve(
        &self,
        scene: &Scene,
        settings: &RunSettings,
        progress: Option<Progress>,
    ) -> Result<Found, String> {
        let problem = Problem::new(scene.clone());
        PROGRESS.with(|p| p.set(progress));
        let out = ffi::solve(&problem, settings, progress.is_some(), tell);
        PROGRESS.with(|p| p.set(None));
        let out = out.map_err(|e| e.what().to_string())?;
        Ok(Found {
            summary: out.summary,
            search: SearchStats::from(&out.search),
            controls: PathControl::from_flat(&out.controls, &out.steps, out.dof)?,
            states: State::many_from_flat(&out.states, out.dof, out.objects)?,
            robustness: (out.robustness >= 0.0).then_some(MeasuredRate {
                rate: out.robustness,
                trials: out.robustness_trials,
            }),
        })
    }

    fn reach(
        &self,
        scene: &Scene,
        object: &str,
        from: Option<&State>,
        settings: &ReachSettings,
    ) -> Result<Reached, String> {
        let from = from.map(State::to_flat).unwrap_or_default();
        let out = ffi::reach(&Problem::new(scene.clone()), object, &from, settings)
            .map_err(|e| e.what().to_string())?;
        Ok(Reached {
            solved: out.solved,
            planning_time: out.planning_time,
            goal_samples: out.goal_samples,
            tree_size: out.tree_size,
            waypoints: out
                .waypoints
                .chunks(out.dof.max(1))
                .map(DVector::from_column_slice)
                .collect(),
        })
    }

    fn benchmark(
        &self,
        scene: &Path,
        settings: &RunSettings,
        run: u32,
        log: &Path,
    ) -> Result<(), String> {
        ffi::benchmark_scene(
            &scene.to_string_lossy(),
            settings,
            run,
            &log.to_string_lossy(),
        )
        .map_err(|e| e.what().to_string())
    }
}
