//! Closed-loop execution: a plan played one control at a time. After each control the
//! world's object poses and the arm's joints are observed, as a robot's perception and
//! encoders would; the rest of the plan is re-simulated from there in the planning model
//! and kept if it still reaches the goal, else repaired or searched anew from the observed
//! state ([`Search::solve`] with a start), or, where no search finds the goal, a leg along
//! the goal object's way is searched. [`Executor`] makes these decisions for observations
//! from anywhere (the C++ API's `pushplan::Executor` holds one); [`ClosedLoop::execute`]
//! runs it against a 3D engine (rapier or MuJoCo), where a control whose objects leave
//! their predicted poses by more than a tolerance is cut short and the world observed
//! there. The planner never sees the world's own parameters (its masses and frictions may
//! differ from the scene's): only what it observes.

mod ahead;
mod tips;

use super::search::Search;
use crate::error::{Error, Overlap};
use crate::math::{wrap_angle, Pose2};
use crate::planning::execute::{trial_worlds, ExecuteSettings, DRIFT, TIPPED_TILT};
use crate::planning::execute::{Engine, EngineKind, STEP};
use crate::planning::mend::MendSettings;
use crate::planning::observed::ObservedState;
use crate::planning::path::{PathControl, SimulatedPath};
use crate::planning::rest::{RestFrom, REPAIR_SHARE};
use crate::planning::shortcut::{shortcut, ShortcutSettings, STEPS_PER_SECOND};
use crate::planning::trajectory::{Playback, Trajectory};
use crate::planning::{FinishSettings, PlannerKind, Problem, RunSettings};
use crate::propagate::Propagator;
use crate::scene::{Clearances, Goal, Scene};
use crate::state::State;
use crate::validity::Invalid;
use ahead::RepairAhead;
use nalgebra::{DVector, Vector2};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;
use std::time::{Duration, Instant};
use tips::Tips;
pub use tips::{TiltNeighbour, TiltOnset, TiltTouch, TILT_ONSET, TOUCH_DISTANCE};

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

/// Time the world gets after each control (or a control cut short) before it is observed:
/// the objects come to rest, as a robot would pause to look (s).
pub const OBSERVE_AFTER: f64 = 0.05;

/// Searches in a row that may find nothing while the arm waits, with nothing valid to
/// play, where legs are searched first (far from the goal disc): each gets 1, 2, 4, then 8
/// times `replan_time`, doubling with the failures in a row before it (30 to 64 s in all
/// with the default 2 s).
const WAITING_SEARCHES: u32 = 4;

/// The same near the goal disc (no leg searched first), where each such search gets 8
/// times `replan_time` from the first. A search stops at its first plan, so the long limit
/// costs only where it finds nothing; from the states where trials waited, searches of 2,
/// 4 and 8 s rarely found what one of 16 s finds (the dense set, MuJoCo: BENCHMARKS.md,
/// "Waiting searches near the disc").
const WAITING_SEARCHES_NEAR: u32 = 2;

/// The time a search from an observed state gets (s): `replan_time` doubled with each
/// search that found nothing in a row before it, up to 8 times; 8 times from the first for
/// one the arm waits on near the goal disc (`waiting_near`).
fn search_time(replan_time: f64, failures_in_a_row: u32, waiting_near: bool) -> f64 {
    let doublings = if waiting_near {
        3
    } else {
        failures_in_a_row.min(3)
    };
    replan_time * f64::from(1 << doublings)
}

/// One closed-loop execution.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClosedLoopTrial {
    /// The goal object ended upright with its centre inside the goal disc.
    pub reached: bool,
    /// Distance of the goal object's final centre from the disc's edge (m; negative inside).
    pub goal_distance: f64,
    /// Objects that tilted beyond [`TIPPED_TILT`] at some time.
    pub tipped: Vec<String>,
    /// For each of `tipped`, the control during or after which it first tilted beyond
    /// [`TIPPED_TILT`] (counted from 1 among the controls played, retraces included).
    pub tipped_during: Vec<usize>,
    /// Every object that tilted beyond [`TILT_ONSET`], tipped or not: when it started
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
    /// touch it instead ([`Scene::with_start`]: a soft contact's depth).
    pub separations: usize,
    /// Observations with a link further inside an object than an observation may be off,
    /// after which the arm retraced the control it had just played ([`Executor::step`]).
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
    /// ([`ClosedLoopSettings::leg`]).
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

/// What the searches after one observation brought ([`ClosedLoop::search`]).
enum Searched {
    /// A plan to the goal: the rest repaired (an ending added), or searched anew.
    Plan {
        controls: Vec<PathControl>,
        repair: bool,
    },
    /// A leg to `goal`, searched after a search to the goal that failed (why), or first,
    /// far from the goal disc (None).
    Leg {
        controls: Vec<PathControl>,
        goal: Goal,
        failure: Option<String>,
    },
    /// Nothing: why the search to the goal found nothing.
    Nothing(String),
}

impl Searched {
    /// Its kind, on the record: `goal` is the execution's.
    fn found(&self, goal: &Goal) -> SearchFound {
        match self {
            Searched::Plan { repair: true, .. } => SearchFound::Repair,
            Searched::Plan { .. } => SearchFound::Replan,
            Searched::Leg { failure: None, .. } => SearchFound::LegFirst,
            Searched::Leg { goal: leg, .. } if onto_the_disc(goal, leg) => {
                SearchFound::LegOntoTheDisc
            }
            Searched::Leg { .. } => SearchFound::Leg,
            Searched::Nothing(_) => SearchFound::Nothing,
        }
    }
}

/// A closed-loop executor: it plays trials as `execution` says (their count, worlds, pace
/// and the engine's effort) and re-plans with `search` as `settings` say, in the scene
/// the plan was made in, from each observed state (the scene loaded once: a re-plan does
/// not read its file again).
#[derive(Clone)]
pub struct ClosedLoop {
    /// The search of every re-plan (a repair's may run on a thread of its own beside the
    /// arm: [`ClosedLoopSettings::repair_ahead`]).
    pub search: &'static dyn Search,
    /// How it re-plans.
    pub settings: ClosedLoopSettings,
    /// How it plays, as open-loop execution does.
    pub execution: ExecuteSettings,
}

impl ClosedLoop {
    /// Plays `plan` (from `scene`'s start) closed loop in a world built from `world_scene`
    /// (the same scene, its objects and parameters perturbed or changed), re-planning in
    /// `scene`: an [`Executor`] decides after each observation of the world what to play.
    pub fn execute(
        &self,
        scene: &Scene,
        plan: &[PathControl],
        world_scene: &Scene,
    ) -> Result<ClosedLoopTrial, String> {
        let began = Instant::now();
        let robot = &scene.robot;
        let objects = scene.objects.len();
        let mut poses = Vec::new();
        robot.chain.forward_kinematics(&scene.start.q, &mut poses);
        let mut world = self.execution.engine.world(
            world_scene,
            &world_scene.start.objects,
            &poses,
            &self.execution.solver,
        )?;
        let mut executor = self.executor(scene, plan);
        let mut tips = Tips::new(objects);
        let mut q = scene.start.q.clone();
        loop {
            let observed = observe(world.as_ref(), &q, objects);
            let Step::Play {
                trajectory,
                predicted,
                ..
            } = executor.step(&observed)
            else {
                break;
            };
            // After a whole control the arm is where the model's control ends (the
            // trajectory's last sample is interpolated onto it).
            tips.control = executor.trial.controls_played;
            if self.play(world.as_mut(), robot, &trajectory, &mut q, &mut tips) {
                executor.trial.cut_short += 1;
            } else {
                q.clone_from(&predicted.q);
            }
            settle(world.as_mut(), &mut tips, &q, OBSERVE_AFTER);
        }
        settle(
            world.as_mut(),
            &mut tips,
            &q,
            crate::planning::execute::SETTLE,
        );
        let mut trial = executor.trial;
        let end_state = observe(world.as_ref(), &q, objects);
        trial.goal_distance = scene.goal.task_distance(&end_state);
        let upright = scene
            .goal
            .object()
            .is_none_or(|object| world.object_tilt(object) < TIPPED_TILT);
        trial.reached = trial.goal_distance <= 0.0 && upright;
        (trial.tipped, trial.tipped_during) = (0..objects)
            .filter(|&i| !world.object_fell_off(i))
            .filter_map(|i| Some((scene.objects[i].name.clone(), tips.first[i]?)))
            .unzip();
        trial.tilt_onsets = tips.onsets(scene);
        trial.wall_time = began.elapsed().as_secs_f64();
        Ok(trial)
    }

    /// An executor of `plan` (from `scene`'s start) that re-plans in `scene` as this closed
    /// loop does, for observations from anywhere: this crate's engines, or a robot's
    /// perception and encoders.
    pub fn executor(&self, scene: &Scene, plan: &[PathControl]) -> Executor {
        Executor {
            closed_loop: self.clone(),
            scene: scene.clone(),
            // Every control played is followed by an observation; this bounds a loop that
            // re-plans without end (the search budget bounds the time spent searching).
            // Trials that re-plan often may still get there: scene 32's reached the goal
            // after up to 32 times the plan's controls (MuJoCo; 4 of 10 trials with a cap
            // of 10 times, 10 of 10 with 30 times).
            most_controls: 30 * plan.len() + 100,
            rest: plan.to_vec(),
            failures_in_a_row: 0,
            waiting_failures: 0,
            // The plan given was shortcut when it was made: only re-plans are polished.
            polish_left: 0.0,
            track: Track::of(
                &scene.goal,
                &Problem::new(scene.clone(), self.settings.planner).simulate(plan, false),
            ),
            leg: None,
            ahead: None,
            last_played: None,
            moved: Moved::default(),
            trial: ClosedLoopTrial {
                reached: false,
                goal_distance: f64::INFINITY,
                tipped: Vec::new(),
                tipped_during: Vec::new(),
                tilt_onsets: Vec::new(),
                controls_played: 0,
                cut_short: 0,
                kept: 0,
                invalid_rests: 0,
                invalid_rest_rules: BTreeMap::new(),
                invalid_rest_details: Vec::new(),
                separations: 0,
                backoffs: 0,
                backoffs_at: Vec::new(),
                replans: 0,
                repairs: 0,
                mends: 0,
                mend_time: 0.0,
                failed_replans: 0,
                legs: 0,
                last_failure: None,
                search_time: 0.0,
                latencies: Vec::new(),
                replan_latencies: Vec::new(),
                stopped: None,
                refused_observation: None,
                failed_search_from: None,
                searches: Vec::new(),
                wall_time: 0.0,
            },
        }
    }

    /// Drives the arm along `trajectory` (one control's, at the execution's pace) in
    /// `world`; `q` ends where the arm is. Stops early, and says so, when an object is
    /// further than the tolerance from its predicted position at the last sample passed.
    fn play(
        &self,
        world: &mut dyn Engine,
        robot: &crate::robot::Robot,
        trajectory: &Trajectory,
        q: &mut DVector<f64>,
        tips: &mut Tips,
    ) -> bool {
        let mut playback = Playback::new(trajectory);
        let end = playback.end();
        let mut poses = Vec::new();
        let mut t = 0.0;
        while t < end {
            t = (t + STEP * self.execution.speed).min(end);
            *q = playback.at(t);
            robot.chain.forward_kinematics(q, &mut poses);
            world.move_arm(&poses);
            world.step();
            tips.note(world, q);
            let predicted = &trajectory.objects[playback.segment()];
            let off = predicted.iter().enumerate().any(|(i, &[x, y, _])| {
                let p = world.object_pose2(i);
                (p.x - x).hypot(p.y - y) > self.settings.tolerance
            });
            if off {
                return true;
            }
        }
        false
    }

    /// The searches after an observation whose rest of the plan does not reach the goal
    /// (`from`'s start): a repair of the rest `kept` up to where it stops being valid
    /// (`kept.1`, its end), then, far from the goal disc, a leg along `track`, then a new
    /// plan to the goal, then (if no leg was searched) a leg. The repair gets
    /// [`REPAIR_SHARE`] of `time`, each search after it the whole `time`, no more than
    /// what is left of `budget_left` (counted from the call): a leg and a search to the
    /// goal may take twice `time` together. The `index`-th search of the execution.
    fn search(
        &self,
        from: &Scene,
        kept: (&[PathControl], &State),
        track: &Track,
        (time, budget_left): (f64, f64),
        index: usize,
    ) -> Searched {
        let began = Instant::now();
        let time_left = || time.min(budget_left - began.elapsed().as_secs_f64());
        // The rest is kept as far as it is valid (to its end if it ends short) and
        // an ending is searched from there (a warm start: the search begins where
        // the rest stops, most often close to the goal, and finds a short ending
        // fast); failing that, a new plan from the observed state.
        if !kept.0.is_empty() {
            if let Ok(controls) = self.repair(from, kept.0, kept.1, time, index) {
                return Searched::Plan {
                    controls,
                    repair: true,
                };
            }
        }
        // Far from the goal disc (a leg's aim off it) a leg is searched first and the
        // goal only where none is found: from there a search to the goal rarely finds
        // one in its seconds, and a leg takes a fraction of that (dense 16 and 19,
        // BENCHMARKS.md "Dense scenes, closed loop").
        let leg_goal = self.leg_goal(from, track);
        let far = leg_first(&from.goal, leg_goal.as_ref());
        if let (true, Some(goal)) = (far, &leg_goal) {
            if let Some(controls) = self.leg(from, goal, time_left(), index) {
                return Searched::Leg {
                    controls,
                    goal: goal.clone(),
                    failure: None,
                };
            }
        }
        let failure = match time_left() {
            left if left > 0.0 => {
                let problem = Problem::new(from.clone(), self.settings.planner);
                match self.replan(&problem, left, index) {
                    Ok(controls) => {
                        return Searched::Plan {
                            controls,
                            repair: false,
                        }
                    }
                    Err(failure) => failure,
                }
            }
            _ => "the search budget is spent".into(),
        };
        // None found: a leg along the track, with the time left (not twice).
        let leg = leg_goal.filter(|_| !far).and_then(|goal| {
            let controls = self.leg(from, &goal, time_left(), index)?;
            Some((controls, goal))
        });
        match leg {
            Some((controls, goal)) => Searched::Leg {
                controls,
                goal,
                failure: Some(failure),
            },
            None => Searched::Nothing(failure),
        }
    }

    /// `rest` (valid from `from`'s start, ending in `end`: short of the goal, or where the
    /// rest after it stops being valid) with an ending searched from `end`, with
    /// [`REPAIR_SHARE`] of `time` ([`ClosedLoop::replan`]).
    fn repair(
        &self,
        from: &Scene,
        rest: &[PathControl],
        end: &State,
        time: f64,
        index: usize,
    ) -> Result<Vec<PathControl>, String> {
        let ending = self.ending(from, end, time, index)?;
        Ok([rest, &ending].concat())
    }

    /// A repair's ending: a plan from `end` (a state the model predicts from `from`'s
    /// start) to `from`'s goal, searched with [`REPAIR_SHARE`] of `time`.
    fn ending(
        &self,
        from: &Scene,
        end: &State,
        time: f64,
        index: usize,
    ) -> Result<Vec<PathControl>, String> {
        let at_end = from
            .with_start(end, Path::new("the rest's end"))
            .map_err(|e| e.to_string())?;
        self.replan(
            &Problem::new(at_end, self.settings.planner),
            REPAIR_SHARE * time,
            index,
        )
    }

    /// The goal of a leg from `from`'s start (the observed state): the goal object to
    /// within half [`ClosedLoopSettings::leg`] of the point that far ahead on `track`.
    /// None for legs turned off, goals other than an object's disc, or a track that ends
    /// nearer than a leg (the goal itself is the next aim).
    fn leg_goal(&self, from: &Scene, track: &Track) -> Option<Goal> {
        let ahead = self.settings.leg;
        let Goal::ObjectInDisc { object, .. } = from.goal else {
            return None;
        };
        if ahead <= 0.0 {
            return None;
        }
        let center = track.waypoint(&from.start.objects[object].translation(), ahead)?;
        Some(Goal::ObjectInDisc {
            object,
            center,
            radius: 0.5 * ahead,
            margin: 0.0,
        })
    }

    /// A leg to `goal` from `from`'s start, searched for `time` seconds at most
    /// ([`ClosedLoop::replan`]); none found in the time: None.
    fn leg(&self, from: &Scene, goal: &Goal, time: f64, index: usize) -> Option<Vec<PathControl>> {
        if time <= 0.0 {
            return None;
        }
        let mut toward = from.clone();
        toward.goal = goal.clone();
        self.replan(&Problem::new(toward, self.settings.planner), time, index)
            .ok()
    }

    /// A new plan from `problem`'s start (the observed state): searched for `time` seconds
    /// at most, then finished (checked by re-simulation, shortcut). The `index`-th re-plan
    /// of the execution.
    fn replan(
        &self,
        problem: &Problem,
        time: f64,
        index: usize,
    ) -> Result<Vec<PathControl>, String> {
        let settings = &self.settings;
        let from = problem.scene();
        let run = RunSettings {
            time_limit: time,
            threads: settings.replan_threads,
            seed: settings.seed.wrapping_add(index as u64),
            shortcut: 0.0,
            ..RunSettings::of_scene(settings.planner, &from.planner)
        };
        let found = self
            .search
            .solve(from, &run, None)
            .map_err(|e| format!("re-planning failed: {e}"))?;
        if !found.summary.exact {
            return Err(format!(
                "no plan from the observed state within {time:.1} s"
            ));
        }
        let finish = FinishSettings {
            shortcut: settings.replan_shortcut,
            seed: run.seed,
            robust: None,
            only_toward_robustness: false,
            unseen_trials: 0,
            found_rate: None,
            deadline: None,
            progress: None,
            threads: 1,
        };
        Ok(problem
            .finish(&found.controls, &found.states, true, &finish)?
            .controls)
    }
}

/// What an [`Executor`] asks for after an observation.
#[derive(Clone, Debug, PartialEq)]
pub enum Step {
    /// Play `control` next: `trajectory` from the observed state (the arm's joints with
    /// its tool brought onto the pushing plane), at the plan's pace; the model predicts
    /// `predicted` after it. Then observe again.
    Play {
        /// The control.
        control: PathControl,
        /// Its executable trajectory (joint waypoints and times, the objects' predicted
        /// poses along it).
        trajectory: Trajectory,
        /// The state the model predicts at the control's end.
        predicted: State,
    },
    /// The plan is played to its end: nothing more to play.
    Finished,
    /// The execution cannot go on: why ([`ClosedLoopTrial::stopped`] holds the same).
    Stopped(String),
}

/// Closed-loop execution one observation at a time, for a world it does not own: after
/// each control the application observes the arm's joints and the objects' poses (a
/// robot's encoders and perception, or an engine, as [`ClosedLoop::execute`] does) and
/// asks [`Executor::step`] what to play next. The rest of the plan is re-simulated from
/// each observation and kept while it reaches the goal; else it is repaired, searched
/// anew, or, where no search finds the goal, a leg along the track is searched
/// ([`ClosedLoopSettings`]). Made by [`ClosedLoop::executor`].
pub struct Executor {
    closed_loop: ClosedLoop,
    /// The scene the plan was made in: every re-plan plans it from an observed state.
    scene: Scene,
    rest: Vec<PathControl>,
    most_controls: usize,
    failures_in_a_row: u32,
    /// Of those, the searches while the arm waited with nothing valid to play.
    waiting_failures: u32,
    polish_left: f64,
    /// The goal object's way in the model, legs aim along: first the plan's from the
    /// scene's start, then that of each rest found to reach the goal.
    track: Track,
    /// While a leg plays, the goal it aims at: the rest is judged by it.
    leg: Option<Goal>,
    /// A repair searching while the arm plays the rest's valid part.
    ahead: Option<RepairAhead>,
    /// The control played last and its trajectory, while the arm may retrace it.
    last_played: Option<(PathControl, Trajectory)>,
    /// The objects the world has moved so far.
    moved: Moved,
    trial: ClosedLoopTrial,
}

impl Executor {
    /// What to play after the world was observed in `observed` (the scene's joint and
    /// object orders; object poses in the world frame). The world must be at rest, as it
    /// is after a control and a short pause ([`OBSERVE_AFTER`]).
    ///
    /// An observation with a link inside an object deeper than an observation may be off
    /// ([`Scene::with_start`] refuses it: no state of the model is near it) is met as a
    /// robot would meet it: the arm retraces the control it has just played, once, and
    /// the world is observed again ([`ClosedLoopTrial::backoffs`]). A kinematic arm driven
    /// into an object that cannot give way gets there (rapier, an arm link 6.5 mm into a
    /// bowl pinned by its neighbours), and so may perception.
    pub fn step(&mut self, observed: &State) -> Step {
        let mut observed = observed.clone();
        // A search that finds nothing with nothing valid to play leaves the arm waiting:
        // the objects at rest, the same state is searched from again.
        loop {
            match self.decide(&observed) {
                Ok(step) => return step,
                Err(waiting) => observed.q = waiting,
            }
        }
    }

    /// The execution so far: its counts, re-plans and latencies, and why it stopped if it
    /// did (the world's outcome, `reached` and the like, is the caller's to judge).
    pub fn trial(&self) -> &ClosedLoopTrial {
        &self.trial
    }

    /// The scene the plan was made in (observations are in its joint and object orders).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// One decision from `observed`; Err(the arm's configuration) where the arm waits and
    /// the same state is to be decided on again.
    fn decide(&mut self, observed: &State) -> Result<Step, DVector<f64>> {
        let started = Instant::now();
        // The arm's wait for a repair searched ahead (s, robot time), and the wall-clock
        // time spent on its thread here: the arm's wait counted in robot time, and, with an
        // engine faster than the clock, the time a robot would have spent playing.
        let (mut waited, mut joined) = (0.0, Duration::ZERO);
        let stop = |trial: &mut ClosedLoopTrial, why: String| {
            trial.stopped = Some(why.clone());
            Ok(Step::Stopped(why))
        };
        let from = match self
            .scene
            .with_start(observed, Path::new("the observed world"))
        {
            Ok(from) => from,
            Err(e) => {
                if let Some(back) = self.back_off(&e, observed, started) {
                    return Ok(back);
                }
                self.trial.refused_observation = Some(ObservedState::of(&self.scene, observed));
                return stop(
                    &mut self.trial,
                    format!("the observed state is no valid start: {e}"),
                );
            }
        };
        let moved = |(a, b): (&Pose2, &Pose2)| a.x != b.x || a.y != b.y;
        if from.start.objects.iter().zip(&observed.objects).any(moved) {
            self.trial.separations += 1;
        }
        // The rest is re-simulated, and played, with half the object clearance spent, and
        // half the arm clearance of objects the world has not moved.
        self.moved.note(observed);
        let playing = Problem::new(
            clearances_spent(&from, &self.moved),
            self.closed_loop.settings.planner,
        );
        let (mut verdict, mut broken, leg_ended) = self.judge(&playing, &from);
        // A repair searched ahead is taken up once it is due; where nothing valid is left
        // to play before, the arm waits for it.
        let mut replanned = false;
        let mut ahead_failed = false;
        if let Some(ahead) = &mut self.ahead {
            let nothing_to_play = matches!(verdict, RestFrom::EndsShort { valid: 0, .. });
            let joining = Instant::now();
            let take_up = ahead.due() || nothing_to_play;
            joined = joining.elapsed();
            if take_up {
                let ahead = self.ahead.take().expect("a repair searched ahead");
                let (repair, record) = ahead.take();
                (waited, joined) = (record.waited, joining.elapsed());
                self.trial.search_time += record.seconds;
                self.trial.searches.push(record);
                match repair {
                    // A rest that reaches the goal again (the world moved its way) is kept.
                    Ok(_) if verdict == RestFrom::Reaches => {}
                    Ok(repair) => {
                        self.rest = repair;
                        self.adopted(true);
                        replanned = true;
                        (verdict, broken, _) = self.judge(&playing, &from);
                    }
                    Err(failure) => {
                        ahead_failed = true;
                        self.trial.failed_replans += 1;
                        self.trial.last_failure = Some(failure);
                    }
                }
            }
        }
        // The arm's wait from the observation to what it plays next (s): for a repair
        // searched ahead, in robot time, then the decision's own work.
        let latency = || waited + (started.elapsed() - joined).as_secs_f64();
        let trial = &mut self.trial;
        if let Some(rule) = broken {
            trial.invalid_rests += 1;
            *trial
                .invalid_rest_rules
                .entry(rule.kind().to_string())
                .or_default() += 1;
            trial.invalid_rest_details.push(rule.to_string());
        }
        match verdict {
            RestFrom::Reaches => self.trial.kept += 1,
            // The repair is still searching: the arm plays the valid part meanwhile (there
            // is some, or it would have waited above).
            RestFrom::EndsShort { valid, .. } if self.ahead.is_some() => self.rest.truncate(valid),
            // A rest mended where it fails is played on, with no search ([`mend`]).
            RestFrom::EndsShort { .. } if self.mended(&playing, &from) => replanned = true,
            RestFrom::EndsShort { valid, end, why } => {
                let trial = &mut self.trial;
                let settings = &self.closed_loop.settings;
                if trial.replans + trial.failed_replans + trial.legs >= settings.max_replans {
                    return stop(
                        trial,
                        format!(
                            "the rest of the plan misses the goal after {} re-plans ({} found nothing)",
                            settings.max_replans, trial.failed_replans
                        ),
                    );
                }
                let budget_left = settings.search_budget - trial.search_time;
                if budget_left <= 0.0 {
                    return stop(
                        trial,
                        format!(
                            "the rest of the plan misses the goal and the {} s of search time \
                             are spent ({} re-plans, {} found nothing)",
                            settings.search_budget, trial.replans, trial.failed_replans
                        ),
                    );
                }
                // A search that found nothing is tried again at the next observation with
                // twice the time (up to 8 times), while the old rest is played on if it
                // can be: the world may have moved to where a plan is easier to find.
                // With nothing valid to play the arm waits (the objects are at rest) and
                // searches again from the same state, up to WAITING_SEARCHES times; near
                // the goal disc WAITING_SEARCHES_NEAR times, each at full length.
                let waiting_near = valid == 0
                    && !leg_first(
                        &from.goal,
                        self.closed_loop.leg_goal(&from, &self.track).as_ref(),
                    );
                let waiting_limit = if waiting_near {
                    WAITING_SEARCHES_NEAR
                } else {
                    WAITING_SEARCHES
                };
                let time = search_time(settings.replan_time, self.failures_in_a_row, waiting_near)
                    .min(budget_left);
                let index = trial.replans + trial.failed_replans + trial.legs;
                let record = SearchRecord {
                    after_controls: trial.controls_played,
                    goal_distance: from.goal.task_distance(&from.start),
                    rest_valid: valid,
                    rest_ends: why.clone(),
                    time,
                    seconds: 0.0,
                    ahead: false,
                    waited: 0.0,
                    found: SearchFound::Nothing,
                };
                // Where part of the rest is valid, its repair is searched while the arm
                // plays that part (not again right after one searched so failed, nor for a
                // leg's remainder that no longer reaches its aim: it has none left). Nor
                // where the valid part ends more than a leg from the goal: an ending from
                // there is a long search that often finds nothing, while the arm would
                // play on along a rest that misses; the searches from where the arm stands
                // go on to a leg at once (dense 19: repairs searched ahead from half a
                // metre short found nothing, and its trials were lost).
                let ends_far = || {
                    from.goal.task_distance(&end) > settings.leg
                        && self.closed_loop.leg_goal(&from, &self.track).is_some()
                };
                if settings.repair_ahead && valid > 0 && !ahead_failed && !leg_ended && !ends_far()
                {
                    let ahead = SearchRecord {
                        ahead: true,
                        ..record.clone()
                    };
                    let kept = (&self.rest[..valid], &end);
                    self.ahead =
                        RepairAhead::begin(&self.closed_loop, &from, kept, time, index, ahead);
                }
                if self.ahead.is_some() {
                    self.rest.truncate(valid);
                } else {
                    let kept = if ahead_failed { 0 } else { valid };
                    let searching = Instant::now();
                    let searched = self.closed_loop.search(
                        &from,
                        (&self.rest[..kept], &end),
                        &self.track,
                        (time, budget_left),
                        index,
                    );
                    let seconds = searching.elapsed().as_secs_f64();
                    let trial = &mut self.trial;
                    trial.search_time += seconds;
                    trial.searches.push(SearchRecord {
                        seconds,
                        waited: seconds,
                        found: searched.found(&from.goal),
                        ..record
                    });
                    match searched {
                        Searched::Plan { controls, repair } => {
                            self.rest = controls;
                            self.adopted(repair);
                            replanned = true;
                        }
                        Searched::Leg {
                            controls,
                            goal,
                            failure,
                        } => {
                            if let Some(failure) = failure {
                                trial.failed_replans += 1;
                                trial.failed_search_from =
                                    Some(ObservedState::of(&self.scene, observed));
                                trial.last_failure = Some(failure);
                            }
                            self.rest = controls;
                            // The searches from a leg's end start over at their shortest:
                            // the goal may be nearer. Not after a leg onto the goal disc:
                            // the last stretch, among the disc's blockers, is the goal
                            // search's work, and it needs its growing times (dense 10).
                            if !onto_the_disc(&from.goal, &goal) {
                                self.failures_in_a_row = 0;
                            }
                            self.leg = Some(goal);
                            trial.legs += 1;
                            // The polish shortens a path to the goal, which a leg is not.
                            self.polish_left = 0.0;
                            self.waiting_failures = 0;
                            replanned = true;
                        }
                        Searched::Nothing(failure) => {
                            trial.failed_replans += 1;
                            trial.failed_search_from =
                                Some(ObservedState::of(&self.scene, observed));
                            self.failures_in_a_row += 1;
                            // A rest no longer valid to its end is played up to where it
                            // stops being valid: the arm goes on the way the plan went
                            // (toward the goal), and the next search starts from there.
                            self.rest.truncate(valid);
                            let playable = !self.rest.is_empty();
                            self.waiting_failures += u32::from(!playable);
                            if self.waiting_failures >= waiting_limit {
                                return stop(
                                    trial,
                                    format!(
                                        "{failure} ({} searches found nothing while the arm \
                                         waited, the longest {time:.1} s: the rest of the plan \
                                         is no longer valid, {why})",
                                        self.waiting_failures
                                    ),
                                );
                            }
                            trial.last_failure = Some(failure);
                            if !playable {
                                trial.latencies.push(latency());
                                return Err(from.start.q);
                            }
                        }
                    }
                }
            }
        }
        let trial = &mut self.trial;
        let latency = latency();
        trial.latencies.push(latency);
        if replanned {
            trial.replan_latencies.push(latency);
        }
        if self.rest.is_empty() {
            return Ok(Step::Finished);
        }
        if trial.controls_played == self.most_controls {
            return stop(trial, format!("{} controls played", self.most_controls));
        }
        // The next control: its executable trajectory from the observed state.
        let (next, trajectory) = match playing.timed(&self.rest[..1]) {
            Ok(timed) => timed,
            Err(e) => return stop(trial, format!("internal error: {e}")),
        };
        let ClosedLoop {
            settings,
            execution,
            ..
        } = &self.closed_loop;
        let seconds = trajectory.times.last().copied().unwrap_or(0.0) / execution.speed;
        match &mut self.ahead {
            Some(ahead) => ahead.played(seconds),
            // The polish changes the rest, which a repair searched ahead carries on from.
            None if self.polish_left > 0.0 && self.rest.len() > 2 => {
                let seconds = seconds.min(self.polish_left);
                self.polish_left -= seconds;
                // The arm plays the control meanwhile: the work stops where the control
                // ends, in wall-clock time too. A step among many objects in contact costs
                // several times what `from_seconds` counts on (dense scenes), and a step
                // budget alone would hold the arm far longer than the control lasts.
                let polish = ShortcutSettings {
                    deadline: Some(Instant::now() + Duration::from_secs_f64(seconds)),
                    ..ShortcutSettings::from_seconds(
                        seconds,
                        settings.seed ^ trial.controls_played as u64,
                    )
                };
                let polished = shortcut(
                    &mut Propagator::new(from.clone()),
                    next.final_state(),
                    &self.rest[1..],
                    &polish,
                );
                self.rest.truncate(1);
                self.rest.extend(polished.controls);
            }
            None => {}
        }
        trial.controls_played += 1;
        let control = self.rest.remove(0);
        self.last_played = Some((control.clone(), trajectory.clone()));
        Ok(Step::Play {
            control,
            trajectory,
            predicted: next.final_state().clone(),
        })
    }

    /// The control played last, retraced from `observed` back to where it began, if
    /// `observed` was `refused` for a link inside an object (or pressing on one from
    /// above), what moving the arm back undoes, and the arm has not retraced it already;
    /// the objects are predicted to stay where observed. The decision began at `started`.
    fn back_off(&mut self, refused: &Error, observed: &State, started: Instant) -> Option<Step> {
        let arm_in_object = matches!(
            refused,
            Error::DeepOverlap {
                between: Overlap::ArmAndObject,
                ..
            } | Error::InvalidStart {
                rule: Invalid::ArmPenetratesObject { .. } | Invalid::PressesOnTop { .. },
                ..
            }
        );
        if !arm_in_object {
            return None;
        }
        let (control, trajectory) = self.last_played.take()?;
        let back_to = DVector::from_column_slice(trajectory.q.first()?);
        let trial = &mut self.trial;
        trial.backoffs += 1;
        trial.controls_played += 1;
        trial.backoffs_at.push(trial.controls_played);
        trial.latencies.push(started.elapsed().as_secs_f64());
        Some(Step::Play {
            control: control.reversed(),
            predicted: State {
                q: back_to,
                objects: observed.objects.clone(),
            },
            trajectory: trajectory.retraced(&observed.q, &observed.objects),
        })
    }

    /// Re-simulates the rest from `from`'s start in `playing` and judges it: by the leg's
    /// goal while a leg plays and gets there, else by the goal. A rest that reaches the
    /// goal gives the track legs follow. Also the rule the rest broke, if it stopped being
    /// valid, and whether a leg ended here (played, or no longer reaching its aim).
    fn judge(&mut self, playing: &Problem, from: &Scene) -> (RestFrom, Option<Invalid>, bool) {
        let leg = &mut self.leg;
        let mut leg_ended = false;
        let (mut verdict, simulated) = playing.rest_from(&self.rest, |s| {
            still_reaches(leg.as_ref().unwrap_or(&from.goal), s)
        });
        if leg.is_some() && (self.rest.is_empty() || verdict != RestFrom::Reaches) {
            // The leg is played, or no longer gets there: the goal is the aim again.
            *leg = None;
            leg_ended = true;
            verdict = playing.verdict_on(&simulated, |s| still_reaches(&from.goal, s));
        }
        if leg.is_none() && verdict == RestFrom::Reaches {
            self.track = Track::of(&from.goal, &simulated);
        }
        let broken = simulated.stopped_by.map(|(_, rule)| rule);
        (verdict, broken, leg_ended)
    }

    /// Mends the rest, which does not reach the goal from `from`'s start, in `playing` (as
    /// it is judged), with [`ClosedLoopSettings::mend`] of work; a mended rest becomes the
    /// rest, and the searches start over at their shortest. Whether it was mended.
    fn mended(&mut self, playing: &Problem, from: &Scene) -> bool {
        let settings = &self.closed_loop.settings;
        if settings.mend <= 0.0 {
            return false;
        }
        let mending = Instant::now();
        // The arm waits on it: it stops when its seconds have passed on the clock, too
        // (in dense scenes its steps take several times what the budget counts on).
        let mend = MendSettings {
            budget_steps: (settings.mend * STEPS_PER_SECOND) as u64,
            seed: settings.seed ^ self.trial.controls_played as u64,
            deadline: Some(mending + Duration::from_secs_f64(settings.mend)),
        };
        let mended = playing.mend(&self.rest, |s| still_reaches(&from.goal, s), &mend);
        let trial = &mut self.trial;
        trial.mend_time += mending.elapsed().as_secs_f64();
        let Some(mended) = mended else {
            return false;
        };
        trial.mends += 1;
        self.rest = mended.controls;
        self.failures_in_a_row = 0;
        self.waiting_failures = 0;
        true
    }

    /// A plan to the goal found (a repair or not) becomes the rest: its searches start
    /// over at their shortest, and the polish shortens it while it plays.
    fn adopted(&mut self, repair: bool) {
        self.polish_left = self.closed_loop.settings.polish;
        self.trial.replans += 1;
        self.trial.repairs += usize::from(repair);
        self.failures_in_a_row = 0;
        self.waiting_failures = 0;
    }
}

/// The goal object's positions (m, world frame) at the states of a path that reaches an
/// object goal in the model: the way a leg follows when no search finds the goal.
#[derive(Clone, Debug, Default, PartialEq)]
struct Track(Vec<Vector2<f64>>);

impl Track {
    /// The goal object's track along `path`; empty for a goal that is not an object's.
    fn of(goal: &Goal, path: &SimulatedPath) -> Track {
        match goal.object() {
            Some(object) => Track(
                path.states
                    .iter()
                    .map(|s| s.objects[object].translation())
                    .collect(),
            ),
            None => Track::default(),
        }
    }

    /// Where a leg from `at` aims: past the track's point nearest `at` (the latest of
    /// equals, as an object held still between pushes leaves many), the first point
    /// `ahead` or farther from `at`. None where the track ends nearer.
    fn waypoint(&self, at: &Vector2<f64>, ahead: f64) -> Option<Vector2<f64>> {
        let distance = |p: &Vector2<f64>| (p - at).norm();
        let nearest = (0..self.0.len()).fold(None, |best: Option<usize>, i| match best {
            Some(b) if distance(&self.0[b]) < distance(&self.0[i]) => Some(b),
            _ => Some(i),
        })?;
        self.0[nearest..]
            .iter()
            .find(|p| distance(p) >= ahead)
            .copied()
    }
}

/// Is `leg` (a leg's goal, if there is one) searched before `goal`: far from the goal
/// disc, where the leg's aim lies off it.
fn leg_first(goal: &Goal, leg: Option<&Goal>) -> bool {
    leg.is_some_and(|leg| !onto_the_disc(goal, leg))
}

/// Does `leg` aim at a point on `goal`'s disc (both an object's disc)?
fn onto_the_disc(goal: &Goal, leg: &Goal) -> bool {
    match (goal, leg) {
        (Goal::ObjectInDisc { center, radius, .. }, Goal::ObjectInDisc { center: aim, .. }) => {
            (aim - center).norm() < *radius
        }
        _ => false,
    }
}

/// Does a path ending in `state` still do its work? For an object goal: the goal object
/// ends within half the planning margin of the goal disc less its margin, that is, the
/// margin may be half spent. The plan was made to end a margin inside the disc so that
/// errors in the world still leave the object in; a re-plan for every millimetre of that
/// error would thrash, and the next observation corrects what builds up. The object
/// clearance is spent the same way ([`clearances_spent`]).
fn still_reaches(goal: &crate::scene::Goal, state: &State) -> bool {
    match goal {
        crate::scene::Goal::ObjectInDisc { margin, .. } => goal.distance(state) <= 0.5 * margin,
        _ => goal.is_satisfied(state),
    }
}

/// `from` with half its object clearance spent (`physics.object_clearance`, and
/// `physics.edge_clearance` from the table's edges), and half the arm clearance of each
/// object the world has not moved (`moved`), as the rest of a plan is judged. Objects a
/// plan kept a clearance apart come closer in a world that is not the model; a re-plan
/// whenever the clearance is touched would thrash, and what is spent of it is still no
/// contact. Re-plans keep them whole.
///
/// The tipping reserves stay whole, the arm clearance where the world has moved the
/// object: they keep a push below the height where the object tips in a world that is not
/// the model. The tipping margin (`physics.tipping_margin`):
/// the model's own noise draws `mu_g` up to 1.2 times the scene's
/// ([`crate::planning::robustness::Noise`]), which lowers the tipping height r / `mu_g` to
/// 1 / 1.2 = 0.83 of the model's; half the default margin (0.3) spent would allow pushes
/// at 0.85 of it, and MuJoCo tipped a bottle the upper arm pushed there. The arm clearance
/// (`physics.arm_clearance`): a link the model has passing an object 5 to 10 mm off at a
/// height where a push would tip it met it in rapier, and the bottle tipped, in three
/// runs of the same trial; with the whole clearance none started to (BENCHMARKS.md,
/// "Dense scenes, closed loop"). That bottle had been pushed 25 cm before the upper arm
/// met it. An object the world has not moved stands where it was observed at the start,
/// which the arm clearance need not cover again: the whole of it there refused rests that
/// pass an untouched glass 9 mm off, and the searches from there found nothing (dense
/// 17). How far an object may hang over the table's edge stays
/// what re-plans allow ([`Clearances::with_start_overhangs`]): a rest a re-plan made is
/// not judged to leave the table where the re-plan kept it on.
fn clearances_spent(from: &Scene, moved: &Moved) -> Scene {
    let mut scene = from.clone();
    scene.physics.object_clearance *= 0.5;
    scene.physics.edge_clearance *= 0.5;
    let whole = scene.physics.arm_clearance;
    let arm = (0..scene.objects.len())
        .map(|i| if moved.get(i) { whole } else { 0.5 * whole })
        .collect();
    scene.clearances = Clearances::at_start(&scene)
        .with_start_overhangs(&scene)
        .with_arm_clearances(arm);
    scene
}

/// How far an observed object may be from where it was first observed (m, rad) and still
/// count as not moved by the world: what an engine's resting object drifts and an
/// observation may be off.
const UNMOVED: (f64, f64) = (0.002, 0.02);

/// Which objects the world has moved since the first observation of a trial: once moved,
/// an object counts as moved for the rest of the trial (it may still slide or rock).
#[derive(Clone, Debug, Default)]
struct Moved {
    first: Vec<Pose2>,
    moved: Vec<bool>,
}

impl Moved {
    /// Notes `observed`'s objects: the first call takes them as where they stand.
    fn note(&mut self, observed: &State) {
        if self.first.is_empty() {
            self.first.clone_from(&observed.objects);
            self.moved = vec![false; observed.objects.len()];
        }
        for ((moved, first), now) in self
            .moved
            .iter_mut()
            .zip(&self.first)
            .zip(&observed.objects)
        {
            let (distance, turn) = (
                (now.translation() - first.translation()).norm(),
                wrap_angle(now.theta - first.theta).abs(),
            );
            *moved |= distance > UNMOVED.0 || turn > UNMOVED.1;
        }
    }

    /// Has the world moved object `i`?
    fn get(&self, i: usize) -> bool {
        self.moved.get(i).copied().unwrap_or(false)
    }
}

/// What an observation sees: the arm at `q`, where it was driven, and the `objects`
/// objects where the world has them (planar poses).
fn observe(world: &dyn Engine, q: &DVector<f64>, objects: usize) -> State {
    State {
        q: q.clone(),
        objects: (0..objects).map(|i| world.object_pose2(i)).collect(),
    }
}

/// Steps the world `seconds` with the arm still at `q`.
fn settle(world: &mut dyn Engine, tips: &mut Tips, q: &DVector<f64>, seconds: f64) {
    for _ in 0..(seconds / STEP).round() as usize {
        world.step();
        tips.note(world, q);
    }
}

/// What closed-loop trials found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClosedLoopReport {
    /// The engine the trials ran in.
    pub engine: EngineKind,
    /// Threads of each re-planning search ([`ClosedLoopSettings::replan_threads`]): latencies
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

impl ClosedLoop {
    /// The execution's trials of `plan`, closed loop: the first in the scene as it is, the
    /// others in worlds perturbed by its noise, which the planner does not know.
    pub fn trials(&self, scene: &Scene, plan: &[PathControl]) -> Result<ClosedLoopReport, String> {
        self.trials_reporting(scene, plan, |_, _| {})
    }

    /// [`ClosedLoop::trials`], telling `finished` of each trial as it ends (its index and
    /// outcome): a dense scene's ten trials take minutes, and a run stopped before its
    /// report keeps what its finished trials found.
    pub fn trials_reporting(
        &self,
        scene: &Scene,
        plan: &[PathControl],
        mut finished: impl FnMut(usize, &ClosedLoopTrial),
    ) -> Result<ClosedLoopReport, String> {
        let mut done = Vec::with_capacity(self.execution.trials);
        for (trial, world) in trial_worlds(scene, &self.execution).enumerate() {
            let each = ClosedLoop {
                settings: ClosedLoopSettings {
                    seed: self.settings.seed.wrapping_add(1000 * trial as u64),
                    ..self.settings.clone()
                },
                execution: self.execution.clone(),
                ..*self
            };
            let outcome = each.execute(scene, plan, &world?)?;
            finished(trial, &outcome);
            done.push(outcome);
        }
        let decisions = sorted(done.iter().flat_map(|t| t.latencies.iter().copied()));
        let replans = sorted(done.iter().flat_map(|t| t.replan_latencies.iter().copied()));
        let n = done.len().max(1) as f64;
        Ok(ClosedLoopReport {
            engine: self.execution.engine,
            replan_threads: self.settings.replan_threads,
            success_rate: done.iter().filter(|t| t.reached).count() as f64 / n,
            tipped_trials: done.iter().filter(|t| !t.tipped.is_empty()).count(),
            replans_per_trial: done.iter().map(|t| t.replans).sum::<usize>() as f64 / n,
            decision_latency_median: quantile(&decisions, 0.5),
            replan_latency_median: quantile(&replans, 0.5),
            replan_latency_p95: quantile(&replans, 0.95),
            trials: done,
        })
    }
}

fn sorted(values: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut values: Vec<f64> = values.collect();
    values.sort_by(f64::total_cmp);
    values
}

/// The `q`-quantile of `sorted` (the smallest value with at least `q` of them at or below
/// it); 0 for none.
fn quantile(sorted: &[f64], q: f64) -> f64 {
    match sorted.len() {
        0 => 0.0,
        n => sorted[((q * n as f64).ceil() as usize).clamp(1, n) - 1],
    }
}

#[cfg(test)]
mod tests {
    use super::{onto_the_disc, search_time, Moved, Track, UNMOVED};
    use crate::math::Pose2;
    use crate::scene::Goal;
    use crate::state::State;
    use nalgebra::{DVector, Vector2};

    /// An object counts as moved once it leaves where it was first observed by more than
    /// an observation may be off (2 mm, 0.02 rad), and stays moved when it comes back.
    #[test]
    fn an_object_counts_as_moved_once_the_world_takes_it_from_where_it_was_first_seen() {
        let seen = |poses: &[(f64, f64, f64)]| State {
            q: DVector::zeros(1),
            objects: poses.iter().map(|&(x, y, t)| Pose2::new(x, y, t)).collect(),
        };
        let (d, a) = UNMOVED;
        let mut moved = Moved::default();
        moved.note(&seen(&[(0.5, 0.0, 0.0), (0.6, 0.1, 3.1)]));
        assert!(!moved.get(0) && !moved.get(1));
        // Within the tolerance, the angle across +-pi.
        moved.note(&seen(&[
            (0.5 + 0.9 * d, 0.0, 0.0),
            (0.6, 0.1, 3.1 + 0.9 * a - std::f64::consts::TAU),
        ]));
        assert!(!moved.get(0) && !moved.get(1));
        moved.note(&seen(&[(0.5, 1.1 * d, 0.0), (0.6, 0.1, 3.1 + 1.1 * a)]));
        assert!(moved.get(0) && moved.get(1));
        moved.note(&seen(&[(0.5, 0.0, 0.0), (0.6, 0.1, 3.1)]));
        assert!(moved.get(0) && moved.get(1));
    }

    #[test]
    fn a_search_the_arm_waits_on_near_the_disc_gets_eight_times_the_replan_time_from_the_first() {
        // Elsewhere the time doubles with the searches that found nothing before it.
        let doubling: Vec<f64> = (0..6).map(|n| search_time(2.0, n, false)).collect();
        assert_eq!(doubling, [2.0, 4.0, 8.0, 16.0, 16.0, 16.0]);
        assert_eq!(search_time(2.0, 0, true), 16.0);
        assert_eq!(search_time(2.0, 5, true), 16.0);
    }

    fn track(points: &[[f64; 2]]) -> Track {
        Track(points.iter().map(|&[x, y]| Vector2::new(x, y)).collect())
    }

    /// A leg aims past the track's point nearest the object, at the first point a leg's
    /// length from it: along an L-shaped track, round the corner when the object stands
    /// near it, and nowhere when the track ends nearer.
    #[test]
    fn a_leg_aims_a_legs_length_ahead_of_the_nearest_point_of_the_track() {
        let l = track(&[
            [0.0, 0.0],
            [0.05, 0.0],
            [0.1, 0.0],
            [0.15, 0.0],
            [0.2, 0.0],
            [0.2, 0.05],
            [0.2, 0.1],
            [0.2, 0.15],
        ]);
        let at = |x, y| Vector2::new(x, y);
        // (0.1, 0) is 0.092 from (0.01, 0.02), (0.15, 0) 0.141.
        assert_eq!(l.waypoint(&at(0.01, 0.02), 0.1), Some(at(0.15, 0.0)));
        // Off the track's side: the nearest point is (0.15, 0); 0.1 from (0.16, 0.03) is
        // first passed round the corner, at (0.2, 0.15) ((0.2, 0.1) is 0.081 away).
        assert_eq!(l.waypoint(&at(0.16, 0.03), 0.1), Some(at(0.2, 0.15)));
        assert_eq!(l.waypoint(&at(0.2, 0.08), 0.1), None);
        // Standing far off the track, the leg goes back to its nearest point.
        assert_eq!(l.waypoint(&at(0.1, -0.3), 0.1), Some(at(0.1, 0.0)));
        assert_eq!(track(&[]).waypoint(&at(0.0, 0.0), 0.1), None);
    }

    /// An object held still while the hand goes round it leaves the same point many
    /// times: the leg counts from the last of them, not from an earlier visit.
    #[test]
    fn a_leg_counts_from_the_last_visit_of_the_nearest_point() {
        let back = track(&[[0.0, 0.0], [0.1, 0.0], [0.0, 0.0], [0.0, 0.1], [0.0, 0.2]]);
        let at = Vector2::new(0.0, 0.0);
        // From the first visit the leg would aim back at (0.1, 0).
        assert_eq!(back.waypoint(&at, 0.1), Some(Vector2::new(0.0, 0.1)));
    }

    /// A leg onto the goal disc is one whose aim lies on the disc (its margin aside); any
    /// other goal has no disc to aim onto.
    #[test]
    fn a_leg_is_onto_the_disc_when_its_aim_lies_on_it() {
        let disc = |x: f64, y: f64, radius: f64| Goal::ObjectInDisc {
            object: 0,
            center: Vector2::new(x, y),
            radius,
            margin: 0.03,
        };
        let goal = disc(0.85, -0.3, 0.1);
        // 0.09 from the centre: on the disc, though not inside its margin.
        assert!(onto_the_disc(&goal, &disc(0.85, -0.39, 0.05)));
        // 0.11 from the centre: off it, though the leg's own disc overlaps it.
        assert!(!onto_the_disc(&goal, &disc(0.85, -0.41, 0.05)));
        let configuration = Goal::Configuration {
            q: DVector::zeros(7),
            tolerance: 0.1,
        };
        assert!(!onto_the_disc(&configuration, &disc(0.85, -0.3, 0.05)));
    }
}
