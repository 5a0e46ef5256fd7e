//! One table of limits for every count, duration and rate a user gives pushplan: the
//! command line's options, the C++ API's `pushplan::Options` and the scene file's
//! `planner:` fields all check their values against the same [`Limit`], and a value
//! outside it is refused with its name and the limit, never taken as an allocation size
//! or a loop without end. docs/commands.md, "Input limits", lists them (a test keeps
//! the two alike).
//!
//! Counts are bounded by what a run can use (a thousand 3D trials of a plan take an hour);
//! durations by a day; rates are shares in [0, 1].

use std::fmt::Display;

/// The bounds on one value a user gives, and its names at each front door.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limit {
    /// The command-line option (`--k`).
    pub option: &'static str,
    /// The field of the C++ API's `pushplan::Options`, Rust's `RunSettings` and the plan
    /// file's `settings`, where it has one (`k`); else empty.
    pub field: &'static str,
    /// The least value allowed.
    pub least: f64,
    /// Whether the least value itself is refused (a duration must be positive).
    pub above_least: bool,
    /// The most allowed.
    pub most: f64,
    /// What it counts or measures, with its unit, for the message.
    pub what: &'static str,
}

/// Which front door a value came through, which names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Front {
    /// A command-line option.
    CommandLine,
    /// A field of the C++ API's `pushplan::Options`.
    CppOptions,
    /// A field of a plan file (its settings, as `plan` recorded them).
    PlanFile,
    /// A keyword argument of the Python module (named as the plan file's field).
    Python,
}

impl Limit {
    /// `value` if it lies within the limit; else why not, naming the value as `front`
    /// knows it.
    pub fn check<T: Copy + Display + Into<Number>>(
        &self,
        front: Front,
        value: T,
    ) -> Result<T, String> {
        let number = value.into();
        let within = match number {
            Number::Real(v) => {
                v.is_finite()
                    && (v > self.least || (!self.above_least && v == self.least))
                    && v <= self.most
            }
            // Compared as integers: 2^64 - 1 must not round to a limit.
            Number::Count(v) => {
                let least = self.least.ceil() as u64 + u64::from(self.above_least);
                v >= least && v <= self.most as u64
            }
        };
        match within {
            true => Ok(value),
            false => Err(format!(
                "{}: must be in {}, got {value} ({})",
                self.name(front),
                self.range(),
                self.what
            )),
        }
    }

    /// The name of the value at `front`.
    pub fn name(&self, front: Front) -> String {
        match front {
            Front::CommandLine => self.option.to_string(),
            Front::CppOptions | Front::PlanFile | Front::Python if self.field.is_empty() => {
                self.option.to_string()
            }
            Front::CppOptions => format!("Options::{}", self.field),
            Front::PlanFile | Front::Python => self.field.to_string(),
        }
    }

    /// The allowed range, written as intervals are (`[1, 10000]`, `(0, 86400]`).
    pub fn range(&self) -> String {
        let open = if self.above_least { '(' } else { '[' };
        format!("{open}{}, {}]", self.least, self.most)
    }
}

/// A value to check: a count or a real number.
#[derive(Clone, Copy, Debug)]
pub enum Number {
    /// A count.
    Count(u64),
    /// A real number.
    Real(f64),
}

impl From<u64> for Number {
    fn from(v: u64) -> Number {
        Number::Count(v)
    }
}

impl From<u32> for Number {
    fn from(v: u32) -> Number {
        Number::Count(v.into())
    }
}

impl From<usize> for Number {
    fn from(v: usize) -> Number {
        Number::Count(v as u64)
    }
}

impl From<f64> for Number {
    fn from(v: f64) -> Number {
        Number::Real(v)
    }
}

/// Largest coordinate or size in a scene or a robot (m; joint values and angles in rad
/// too): a kilometre. No table or arm comes near it, and within it squared distances keep
/// the millimetres the model works in (a table 10^308 m wide drew `-inf` into pictures).
pub const MAX_EXTENT: f64 = 1000.0;

/// A day (s): the longest duration any option takes.
const DAY: f64 = 86_400.0;

const fn count(
    option: &'static str,
    field: &'static str,
    least: u64,
    most: u64,
    what: &'static str,
) -> Limit {
    Limit {
        option,
        field,
        least: least as f64,
        above_least: false,
        most: most as f64,
        what,
    }
}

const fn seconds(
    option: &'static str,
    field: &'static str,
    above_zero: bool,
    most: f64,
    what: &'static str,
) -> Limit {
    Limit {
        option,
        field,
        least: 0.0,
        above_least: above_zero,
        most,
        what,
    }
}

const fn share(option: &'static str, field: &'static str, what: &'static str) -> Limit {
    Limit {
        option,
        field,
        least: 0.0,
        above_least: false,
        most: 1.0,
        what,
    }
}

// How one search runs (`RunSettings`: the CLI's search options, C++'s `Options`).

/// Control samples per extension (Alg. 1's k; the scene's `planner.k` too).
pub const K: Limit = count("--k", "k", 1, 10_000, "control samples per extension");
/// Threads of one search.
pub const THREADS: Limit = count("--threads", "threads", 1, 256, "threads");
/// Perturbed re-simulations of the robustness check.
pub const ROBUST_TRIALS: Limit = count(
    "--robust",
    "robust_trials",
    0,
    1_000,
    "perturbed re-simulations",
);
/// Perturbed worlds every tree state carries.
pub const ROBUST_PARTICLES: Limit = count(
    "--particles",
    "robust_particles",
    0,
    64,
    "perturbed worlds per state",
);
/// A search's time limit (s; the scene's `planner.time_limit` too).
pub const TIME_LIMIT: Limit = seconds("--time", "time_limit", true, DAY, "seconds");
/// Shortcutting after a solution (s of work).
pub const SHORTCUT: Limit = seconds("--shortcut", "shortcut", false, DAY, "seconds of work");
/// Shortcutting toward robustness (s of work).
pub const ROBUST_SHORTCUT: Limit = seconds(
    "--robust-shortcut",
    "robust_shortcut",
    false,
    DAY,
    "seconds of work",
);
/// The probability of sampling the goal (the scene's `planner.goal_bias` too).
pub const GOAL_BIAS: Limit = share("--goal-bias", "goal_bias", "a probability");
/// The share of perturbed re-simulations that must reach the goal.
pub const ROBUST_RATE: Limit = share(
    "--robust-rate",
    "robust_rate",
    "a share of the re-simulations",
);

// The commands' own counts and durations.

/// `check --noise`: perturbed re-simulations of a plan.
pub const NOISE: Limit = count("--noise", "", 0, 10_000, "perturbed re-simulations");
/// `execute --trials`: 3D trials of a plan.
pub const TRIALS: Limit = count("--trials", "", 1, 1_000, "3D trials");
/// `execute --speed`: the pace against the plan's.
pub const SPEED: Limit = Limit {
    option: "--speed",
    field: "",
    least: 0.0,
    above_least: true,
    most: 100.0,
    what: "times the plan's pace",
};
/// `execute --max-replans`: re-planning searches per closed-loop trial.
pub const MAX_REPLANS: Limit = count("--max-replans", "", 1, 10_000, "searches per trial");
/// `execute --replan-time`: one re-planning search's time (s).
pub const REPLAN_TIME: Limit = seconds("--replan-time", "", true, DAY, "seconds");
/// `execute --replan-budget`: a closed-loop trial's search time in all (s).
pub const REPLAN_BUDGET: Limit = seconds("--replan-budget", "", true, DAY, "seconds");
/// `execute --replan-leg`: how far ahead a closed-loop leg aims (m; 0: no legs).
pub const REPLAN_LEG: Limit = Limit {
    option: "--replan-leg",
    field: "",
    least: 0.0,
    above_least: false,
    most: MAX_EXTENT,
    what: "metres",
};
/// `execute --replan-threads`: threads of each re-planning search.
pub const REPLAN_THREADS: Limit = count("--replan-threads", "", 1, 256, "threads");
/// `execute --replan-shortcut`: shortcutting before a re-plan is played (s of work).
pub const REPLAN_SHORTCUT: Limit = seconds("--replan-shortcut", "", false, DAY, "seconds of work");
/// `execute --replan-polish`: shortcutting while a re-plan is played (s of work).
pub const REPLAN_POLISH: Limit = seconds("--replan-polish", "", false, DAY, "seconds of work");
/// `execute --replan-mend`: mending a rest that no longer reaches the goal (s of work).
pub const REPLAN_MEND: Limit = seconds("--replan-mend", "", false, DAY, "seconds of work");
/// `scenes generate --count`: scene files written.
pub const SCENES: Limit = count("--count", "", 1, 1_000, "scene files");
/// `pick-place --grasps`: grasps drawn per grasp region.
pub const GRASPS: Limit = count("--grasps", "", 1, 1_000, "grasps per region");
/// `pick-place --budget`: validity checks of the search.
pub const CHECK_BUDGET: Limit = count("--budget", "", 1, 100_000_000, "validity checks");
/// `robot --tries`: inverse-kinematics attempts.
pub const IK_TRIES: Limit = count("--tries", "", 1, 100_000, "attempts");
/// `robot --samples`: random configurations of `--allowed-collisions`.
pub const COLLISION_SAMPLES: Limit = count("--samples", "", 1, 1_000_000, "configurations");
/// `bench --runs`: runs per planner and scene.
pub const RUNS: Limit = count("--runs", "", 1, 10_000, "runs");
/// `bench --jobs`: runs at once.
pub const JOBS: Limit = count("--jobs", "", 1, 1_024, "processes");

/// Every limit, for the table in docs/commands.md and its test.
pub const ALL: [&Limit; 27] = [
    &K,
    &THREADS,
    &ROBUST_TRIALS,
    &ROBUST_PARTICLES,
    &TIME_LIMIT,
    &SHORTCUT,
    &ROBUST_SHORTCUT,
    &GOAL_BIAS,
    &ROBUST_RATE,
    &NOISE,
    &TRIALS,
    &SPEED,
    &MAX_REPLANS,
    &REPLAN_TIME,
    &REPLAN_BUDGET,
    &REPLAN_LEG,
    &REPLAN_THREADS,
    &REPLAN_SHORTCUT,
    &REPLAN_POLISH,
    &REPLAN_MEND,
    &SCENES,
    &GRASPS,
    &CHECK_BUDGET,
    &IK_TRIES,
    &COLLISION_SAMPLES,
    &RUNS,
    &JOBS,
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_and_reals_are_refused_outside_with_the_name_and_the_limit() {
        assert_eq!(K.check(Front::CommandLine, 3u32), Ok(3));
        let e = K.check(Front::CppOptions, 1_000_000_000u32).unwrap_err();
        assert_eq!(
            e,
            "Options::k: must be in [1, 10000], got 1000000000 (control samples per extension)"
        );
        assert!(TRIALS
            .check(Front::CommandLine, u64::MAX)
            .unwrap_err()
            .starts_with("--trials: must be in [1, 1000]"));
        assert!(TRIALS.check(Front::CommandLine, 0usize).is_err());
        // An integer just above a limit is not rounded onto it.
        assert!(CHECK_BUDGET
            .check(Front::CommandLine, 100_000_001u64)
            .is_err());
        assert!(TIME_LIMIT
            .check(Front::CommandLine, 0.0)
            .unwrap_err()
            .contains("(0, 86400]"));
        assert!(TIME_LIMIT.check(Front::CommandLine, f64::NAN).is_err());
        assert!(SHORTCUT.check(Front::CommandLine, 0.0).is_ok());
        assert!(ROBUST_RATE
            .check(Front::CppOptions, 1.5)
            .unwrap_err()
            .starts_with("Options::robust_rate"));
        // A command's own option keeps its name at every door.
        assert_eq!(NOISE.name(Front::CppOptions), "--noise");
    }
}
