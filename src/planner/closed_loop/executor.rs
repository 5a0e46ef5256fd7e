//! [`Executor`]: closed-loop execution one observation at a time, for a world it does not
//! own (an engine's, or a robot's perception and encoders).

use super::ahead::RepairAhead;
use super::searches::{leg_first, onto_the_disc, Searched, Track};
use super::{ClosedLoop, ClosedLoopTrial, SearchFound, SearchRecord};
use crate::error::{Error, Overlap};
use crate::math::{wrap_angle, Pose2};
use crate::planning::mend::MendSettings;
use crate::planning::observed::ObservedState;
use crate::planning::path::PathControl;
use crate::planning::rest::RestFrom;
use crate::planning::shortcut::{shortcut, ShortcutSettings, STEPS_PER_SECOND};
use crate::planning::trajectory::Trajectory;
use crate::planning::Problem;
use crate::propagate::Propagator;
use crate::scene::{Clearances, Goal, Scene};
use crate::state::State;
use crate::validity::Invalid;
use nalgebra::DVector;
use std::collections::BTreeMap;
use std::path::Path;
use std::time::{Duration, Instant};

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
/// ([`ClosedLoopSettings`](super::ClosedLoopSettings)). Made by [`ClosedLoop::executor`].
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
    /// The execution so far ([`Executor::trial`]); the engine's loop counts the controls it
    /// cuts short here.
    pub(super) trial: ClosedLoopTrial,
}

impl Executor {
    /// What to play after the world was observed in `observed` (the scene's joint and
    /// object orders; object poses in the world frame). The world must be at rest, as it
    /// is after a control and a short pause ([`OBSERVE_AFTER`](super::OBSERVE_AFTER)).
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

impl ClosedLoop {
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

#[cfg(test)]
mod tests {
    use super::{search_time, Moved, UNMOVED};
    use crate::math::Pose2;
    use crate::state::State;
    use nalgebra::DVector;

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
}
