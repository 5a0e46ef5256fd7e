//! What closed-loop executions report: each trial ([`ClosedLoopTrial`], its searches
//! [`SearchRecord`]) and a run of them ([`ClosedLoopReport`]).

use super::TiltOnset;
use crate::planning::execute::EngineKind;
use crate::planning::observed::ObservedState;
use serde::Serialize;
use std::collections::BTreeMap;

/// One closed-loop execution.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClosedLoopTrial {
    /// The goal object ended upright with its centre inside the goal disc.
    pub reached: bool,
    /// Distance of the goal object's final centre from the disc's edge (m; negative inside).
    pub goal_distance: f64,
    /// Objects that tilted beyond [`TIPPED_TILT`](crate::planning::execute::TIPPED_TILT) at some time.
    pub tipped: Vec<String>,
    /// For each of `tipped`, the control during or after which it first tilted beyond
    /// [`TIPPED_TILT`](crate::planning::execute::TIPPED_TILT) (counted from 1 among the controls played, retraces included).
    pub tipped_during: Vec<usize>,
    /// Every object that tilted beyond [`TILT_ONSET`](super::TILT_ONSET), tipped or not: when it started
    /// and the world then, so that a tip can be traced after the trial (the closed loop
    /// is not replayed bit for bit: its searches run on the clock).
    pub tilt_onsets: Vec<TiltOnset>,
    /// Controls played (whole or cut short).
    pub controls_played: usize,
    /// Controls cut short because an object left its predicted pose.
    pub cut_short: usize,
    /// Observations after which the rest of the plan still reached the goal.
    pub kept: usize,
    /// Observations after which the rest of the plan stopped being valid in the model
    /// before its end (an object tipped or too close, the arm in collision).
    pub invalid_rests: usize,
    /// Those observations by the rule the rest broke first ([`crate::validity::Invalid::kind`]:
    /// "objects too close", "object off table", ...): what a world unlike the model does
    /// to the plan.
    pub invalid_rest_rules: BTreeMap<String, usize>,
    /// Those observations' broken rules in full, in order: names and numbers (an object
    /// off the table with how far it reaches over), to trace which object a world unlike
    /// the model keeps breaking the rest on.
    pub invalid_rest_details: Vec<String>,
    /// Observations with an object inside the arm or inside another object, moved out to
    /// touch it instead ([`Scene::with_start`](crate::scene::Scene::with_start): a soft contact's depth).
    pub separations: usize,
    /// Observations with a link further inside an object than an observation may be off,
    /// after which the arm retraced the control it had just played ([`Executor::step`](super::Executor::step)).
    pub backoffs: usize,
    /// Those retraces, each by its number among the controls played.
    pub backoffs_at: Vec<usize>,
    /// Re-planning searches that found a plan.
    pub replans: usize,
    /// Of those, the searches from where the rest stopped being valid, or from its end
    /// where it ended short of the goal: the rest kept up to there, an ending added.
    pub repairs: usize,
    /// Observations after which the rest, no longer reaching the goal, was mended where it
    /// failed ([`crate::planning::mend`]) and played on with no search.
    pub mends: usize,
    /// Time the mends took in all, mended or not (s).
    pub mend_time: f64,
    /// Re-planning searches that found none in their time (the old rest played on), repairs
    /// searched ahead among them.
    pub failed_replans: usize,
    /// Legs found and played: after such a search, or, far from the goal disc, before any
    /// ([`ClosedLoopSettings::leg`](super::ClosedLoopSettings::leg)).
    pub legs: usize,
    /// Why the last of those found none.
    pub last_failure: Option<String>,
    /// Time the re-planning searches took in all, found or not, shortcutting included (s).
    pub search_time: f64,
    /// Time from each observation to the plan played next: the rest re-simulated, and the
    /// search and shortcutting when it re-planned (s).
    pub latencies: Vec<f64>,
    /// The same, of the observations that re-planned (or mended the rest) only (s).
    pub replan_latencies: Vec<f64>,
    /// Why the execution stopped before the plan's end, if it did.
    pub stopped: Option<String>,
    /// The observation the execution stopped on, if the model refused it as a start (in
    /// `replan --observed`'s format: `replan` and `check` on it say the same, so it can be
    /// replayed without the engine).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub refused_observation: Option<ObservedState>,
    /// The observation the last search that found nothing started from, if one did (in
    /// `replan --observed`'s format: `replan` on it judges the rest and searches from there
    /// again, without the engine, so a hard state met in a long run can be searched
    /// anew, with more time or other seeds, and traced).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failed_search_from: Option<ObservedState>,
    /// Every re-planning search in the order searched: where the goal object was, what
    /// it was given and what it found. Where a long trial's time went.
    pub searches: Vec<SearchRecord>,
    /// Wall-clock time the trial took: the engine's simulation, the re-simulations, the
    /// searches and the shortcutting (s).
    pub wall_time: f64,
}

/// One re-planning search of a closed-loop trial: the searches after one observation
/// together (a repair, legs, a new plan).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SearchRecord {
    /// Controls played before it.
    pub after_controls: usize,
    /// The goal's task distance in the observed state (m; for an object's disc, its centre
    /// from the disc's edge, negative inside).
    pub goal_distance: f64,
    /// Controls of the rest valid from the observed state (all of them when it ends short).
    pub rest_valid: usize,
    /// Why the rest was not kept: the control that stops and the rule it breaks, or how
    /// far the goal is missed.
    pub rest_ends: String,
    /// Its time limit (s).
    pub time: f64,
    /// The time it took, shortcutting included (s).
    pub seconds: f64,
    /// A repair searched while the arm played the rest's valid part (the `ahead` module); it is on
    /// the record where it was taken up, `after_controls` says where it began.
    pub ahead: bool,
    /// How long the arm waited for it (s, at the execution's pace): `seconds` for a search
    /// the arm waits on, what a repair searched ahead took beyond the controls played
    /// meanwhile.
    pub waited: f64,
    /// What it found.
    pub found: SearchFound,
}

/// What a re-planning search found ([`SearchRecord::found`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SearchFound {
    /// An ending of the rest kept up to where it stops being valid.
    Repair,
    /// A new plan from the observed state.
    Replan,
    /// Far from the goal disc, a leg along the track, searched before the goal (which
    /// was not searched).
    LegFirst,
    /// No way to the goal found, a leg along the track.
    Leg,
    /// No way to the goal found, a leg whose aim lies on the goal disc.
    LegOntoTheDisc,
    /// Nothing.
    Nothing,
}

/// What closed-loop trials found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClosedLoopReport {
    /// The engine the trials ran in.
    pub engine: EngineKind,
    /// Threads of each re-planning search ([`ClosedLoopSettings::replan_threads`](super::ClosedLoopSettings::replan_threads)): latencies
    /// depend on them.
    pub replan_threads: u32,
    /// Every trial, the nominal one first.
    pub trials: Vec<ClosedLoopTrial>,
    /// Fraction of trials that reached the goal.
    pub success_rate: f64,
    /// Trials in which some object tipped.
    pub tipped_trials: usize,
    /// Re-planning searches per trial, on average.
    pub replans_per_trial: f64,
    /// Median time from an observation to the plan played next (s), over every trial.
    pub decision_latency_median: f64,
    /// Median time of a re-plan: from the observation to the new plan, searched and
    /// shortcut (s), over every trial's re-plans.
    pub replan_latency_median: f64,
    /// Its 95th percentile (s).
    pub replan_latency_p95: f64,
}

pub(super) fn sorted(values: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut values: Vec<f64> = values.collect();
    values.sort_by(f64::total_cmp);
    values
}

/// The `q`-quantile of `sorted` (the smallest value with at least `q` of them at or below
/// it); 0 for none.
pub(super) fn quantile(sorted: &[f64], q: f64) -> f64 {
    match sorted.len() {
        0 => 0.0,
        n => sorted[((q * n as f64).ceil() as usize).clamp(1, n) - 1],
    }
}
