//! [`SearchFlags`]: the command line's flags of one search, one per field of
//! [`RunSettings`] and named as it is (a short flag name where the field's is long). A flag
//! not given keeps the scene's value or the library's default ([`RunSettings::of_scene`]);
//! one given is checked against the limits table as it is parsed.

use super::within::{count, real};
use pushplan::limits;
use pushplan::planning::{PlannerKind, RunSettings};
use pushplan::scene::PlannerParams;

/// The flags of one search (`plan`'s).
#[derive(clap::Args, Clone, Debug)]
pub struct SearchFlags {
    /// push_kpiece (KPIECE1 guided by push headings), pcrrt (the paper's RRT), static
    /// (only the goal object moves), or one of OMPL's control planners on the same
    /// problem: kpiece, est, pdst, sst.
    #[arg(long, default_value_t = PlannerKind::PushKpiece)]
    pub planner: PlannerKind,
    /// Search time limit (s); default: the scene's planner.time_limit.
    #[arg(long = "time", value_name = "SECONDS", value_parser = real(&limits::TIME_LIMIT))]
    pub time_limit: Option<f64>,
    /// Random seed; default: the scene's planner.seed.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Control samples per extension; default: the scene's planner.k.
    #[arg(long, value_parser = count::<u32>(&limits::K))]
    pub k: Option<u32>,
    /// Probability of sampling the goal; default: the scene's planner.goal_bias.
    #[arg(long, value_parser = real(&limits::GOAL_BIAS))]
    pub goal_bias: Option<f64>,
    /// Shortcutting budget in seconds of work (0 turns it off) [default: 3].
    #[arg(long, value_parser = real(&limits::SHORTCUT))]
    pub shortcut: Option<f64>,
    /// Add every propagation step to the tree (OMPL RRT's intermediate_states; off by
    /// default, see BENCHMARKS.md).
    #[arg(long)]
    pub intermediate_states: bool,
    /// Keep a solution only if at least --robust-rate of this many re-simulations from
    /// perturbed scenes (as `check --noise`) reach the goal; search on otherwise, and when
    /// the time runs out first, write the most robust solution found, its rate stated
    /// [default: 20 for `plan`, 0 for `replan`; 0 takes the first solution as found].
    #[arg(long = "robust", value_name = "TRIALS", value_parser = count::<u32>(&limits::ROBUST_TRIALS))]
    pub robust_trials: Option<u32>,
    /// The fraction of --robust re-simulations that must reach the goal [default: 0.95:
    /// one perturbed world in 20 may miss; BENCHMARKS.md, "19 of 20 perturbed worlds"].
    #[arg(long, value_parser = real(&limits::ROBUST_RATE))]
    pub robust_rate: Option<f64>,
    /// Shortcutting budget (seconds of work) spent on each solution that is not robust
    /// enough, toward the path that reaches the goal in the most perturbed scenes, before
    /// it is dropped [default: 1.5].
    #[arg(long, value_parser = real(&limits::ROBUST_SHORTCUT))]
    pub robust_shortcut: Option<f64>,
    /// With --robust: perturbed worlds every tree state carries; an extension is kept
    /// only if it is valid in each, and the goal is reached only when it is reached in
    /// each [default: 0: none, only the check of each solution].
    #[arg(long = "particles", value_name = "WORLDS", value_parser = count::<u32>(&limits::ROBUST_PARTICLES))]
    pub robust_particles: Option<u32>,
    /// Threads to plan on: the KPIECE planners extend one search on all of them, the
    /// others run a search on each, in rounds of propagation steps (the same seed and
    /// thread count give the same plan); default: one per core.
    #[arg(long, value_parser = count::<u32>(&limits::THREADS))]
    pub threads: Option<u32>,
    /// A search that finds no solution within this many propagation steps starts over
    /// with a new tree, later attempts with Luby multiples (1, 1, 2, 1, 1, 2, 4, ...);
    /// 0: never. Default: the planner's (push_kpiece: 400000, about 2 s; the others
    /// never).
    #[arg(long = "restart", value_name = "STEPS")]
    pub restart_steps: Option<u64>,
    /// push_kpiece only: when this many propagation steps have not moved the goal
    /// object (the arm cannot get to it), PC RRT searches on from the start for the rest
    /// of the time, one independent search per thread; 0: never. Default: 1000000 (about
    /// 3 s in dense clutter).
    #[arg(long = "fallback", value_name = "STEPS")]
    pub fallback_steps: Option<u64>,
}

impl SearchFlags {
    /// The search's settings for a scene's `planner:` parameters: each flag's value where
    /// it is given, else the scene's or the library's (threads: one per core).
    pub fn settings(&self, params: &PlannerParams) -> RunSettings {
        let own = RunSettings::of_scene(self.planner, params);
        RunSettings {
            planner: self.planner,
            intermediate_states: self.intermediate_states,
            k: self.k.unwrap_or(own.k),
            threads: self.threads.unwrap_or_else(super::cores),
            robust_trials: self.robust_trials.unwrap_or(own.robust_trials),
            robust_particles: self.robust_particles.unwrap_or(own.robust_particles),
            time_limit: self.time_limit.unwrap_or(own.time_limit),
            seed: self.seed.unwrap_or(own.seed),
            goal_bias: self.goal_bias.unwrap_or(own.goal_bias),
            shortcut: self.shortcut.unwrap_or(own.shortcut),
            robust_rate: self.robust_rate.unwrap_or(own.robust_rate),
            robust_shortcut: self.robust_shortcut.unwrap_or(own.robust_shortcut),
            restart_steps: self.restart_steps.unwrap_or(own.restart_steps),
            fallback_steps: self.fallback_steps.unwrap_or(own.fallback_steps),
        }
    }
}
