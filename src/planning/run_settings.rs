//! [`RunSettings`]: how one search runs. One type for the CLI's flags, a benchmark
//! cell, the plan file's record ([`crate::planning::plan_file::PlanSettings`] is made from
//! it) and the C++ API's `pushplan::Options` (which resolves to it): the bridge carries
//! it as it is.

use super::PlannerKind;
use crate::limits::Front;
use crate::scene::PlannerParams;

/// How one search runs, every value resolved (no "the scene's default" left).
///
/// C++'s `pushplan::detail::RunSettings` is generated from this declaration (build.rs),
/// and C++'s `pushplan::Options` must have a field of each name: a new setting is a field
/// here, its default in [`RunSettings::of_scene`], a flag (`cli::SearchFlags`) and an
/// option (`include/pushplan/pushplan.h`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunSettings {
    /// The planner that searches.
    pub planner: PlannerKind,
    /// Add every propagation step to the tree (OMPL RRT's intermediate states).
    pub intermediate_states: bool,
    /// Control samples per extension (Alg. 1's k).
    pub k: u32,
    /// Threads to plan on: one search on all of them (the planners that share one
    /// search), else one search per thread.
    pub threads: u32,
    /// Robust planning: a solution is kept only if at least `robust_rate` of this many
    /// perturbed re-simulations reach the goal; 0: no such check.
    pub robust_trials: u32,
    /// Perturbed worlds every tree state carries in robust planning (0: none).
    pub robust_particles: u32,
    /// The time limit of the search (s).
    pub time_limit: f64,
    /// The seed of every random choice.
    pub seed: u64,
    /// Probability of sampling the goal region.
    pub goal_bias: f64,
    /// Shortcutting budget after a solution (s of work, counted in propagation steps).
    pub shortcut: f64,
    /// The share of perturbed re-simulations that must reach the goal, in [0, 1].
    pub robust_rate: f64,
    /// Shortcutting budget toward robustness for each solution not robust enough (s of
    /// work).
    pub robust_shortcut: f64,
    /// The first restart budget in propagation steps (attempt i gets Luby(i) times as
    /// many); 0: never.
    pub restart_steps: u64,
    /// Push KPIECE's patience before it falls back to PC RRT, in propagation steps; 0:
    /// never.
    pub fallback_steps: u64,
}

/// Perturbed re-simulations a plan is checked in when none are asked for: `plan` and C++'s
/// `Planner::solve` / `solveFrom` keep a solution only if [`RunSettings::robust_rate`] of
/// them reach the goal, and when none does in time, the most robust one found (robust by
/// default; `--robust 0` / `robust_trials = 0` takes the first solution as found).
/// Re-plans (`replan`, `Planner::replan`, the closed loop) and benchmark runs keep 0: a
/// re-plan is wanted fast, and a benchmark measures the search ([`RunSettings::of_scene`]).
pub const PLAN_ROBUST_TRIALS: u32 = 20;

/// Shortcutting toward robustness, per solution not robust enough, when none is asked for
/// (s of work). Half of the 3 s it was: more solutions finished in a search's time, each
/// less far, gave more robust plans within 30 s on the development scenes and seeds
/// (BENCHMARKS.md, "Robust finishing").
pub const DEFAULT_ROBUST_SHORTCUT: f64 = 1.5;

/// The share of perturbed re-simulations a robust plan must reach the goal in, when none
/// is asked for: one world in 20 may miss.
pub const DEFAULT_ROBUST_RATE: f64 = 0.95;

impl RunSettings {
    /// Refuses a value outside the limits table ([`crate::limits`]), or particles without
    /// a robustness check or a planner that pushes: named as `front` names it (`--k`,
    /// `Options::k`). The CLI's `plan` and C++'s `Planner` check the same way.
    pub fn check(&self, front: Front) -> Result<(), String> {
        use crate::limits::*;
        K.check(front, self.k)?;
        THREADS.check(front, self.threads)?;
        ROBUST_TRIALS.check(front, self.robust_trials)?;
        ROBUST_PARTICLES.check(front, self.robust_particles)?;
        TIME_LIMIT.check(front, self.time_limit)?;
        SHORTCUT.check(front, self.shortcut)?;
        ROBUST_SHORTCUT.check(front, self.robust_shortcut)?;
        GOAL_BIAS.check(front, self.goal_bias)?;
        ROBUST_RATE.check(front, self.robust_rate)?;
        self.planner.check_fallback(
            self.fallback_steps,
            match front {
                Front::CommandLine => "--fallback",
                Front::CppOptions => "Options::fallback_steps",
                Front::PlanFile | Front::Python => "fallback_steps",
            },
        )?;
        if self.robust_particles > 0
            && (self.robust_trials == 0 || self.planner == PlannerKind::StaticRrt)
        {
            return Err(format!(
                "{} {} needs {} above 0, and a planner that pushes (not {})",
                ROBUST_PARTICLES.name(front),
                self.robust_particles,
                ROBUST_TRIALS.name(front),
                PlannerKind::StaticRrt.name()
            ));
        }
        Ok(())
    }

    /// `planner` as the scene's `planner:` parameters say, with the planner's own restart
    /// and fallback budgets, on one thread, with the defaults of what no scene sets (3 s of
    /// shortcutting; no robust planning, and when it is asked for, 19 of 20 perturbed
    /// worlds with 3 s of shortcutting toward them): the front doors (the CLI's flags,
    /// C++'s `Options`, a benchmark grid) set the rest. The one place of these defaults.
    pub fn of_scene(planner: PlannerKind, params: &PlannerParams) -> RunSettings {
        RunSettings {
            planner,
            intermediate_states: false,
            k: params.k,
            threads: 1,
            robust_trials: 0,
            robust_particles: 0,
            time_limit: params.time_limit,
            seed: params.seed,
            goal_bias: params.goal_bias,
            shortcut: 3.0,
            robust_rate: DEFAULT_ROBUST_RATE,
            robust_shortcut: DEFAULT_ROBUST_SHORTCUT,
            restart_steps: planner.restart_steps(),
            fallback_steps: planner.fallback_steps(),
        }
    }
}
