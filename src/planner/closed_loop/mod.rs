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
//!
//! Here: the loop against an engine ([`ClosedLoop::execute`], [`ClosedLoop::trials`]). Its
//! parts: `settings` (how it plays and re-plans, the defaults), `executor` (the decision
//! after each observation: the rest judged, kept, mended or searched), `searches` (the
//! repair, the new plan and the legs), `ahead` (a repair searched while the arm plays),
//! `tips` (tilts recorded in the engine) and `report` (what a trial and a run found).

mod ahead;
mod executor;
mod report;
mod searches;
mod settings;
mod tips;

use super::search::Search;
use crate::planning::execute::{trial_worlds, ExecuteSettings, TIPPED_TILT};
use crate::planning::execute::{Engine, STEP};
use crate::planning::path::PathControl;
use crate::planning::trajectory::{Playback, Trajectory};
use crate::scene::Scene;
use crate::state::State;
pub use executor::{Executor, Step};
use nalgebra::DVector;
use report::{quantile, sorted};
pub use report::{ClosedLoopReport, ClosedLoopTrial, SearchFound, SearchRecord};
pub use settings::{defaults, ClosedLoopOptions, ClosedLoopSettings};
use std::time::Instant;
use tips::Tips;
pub use tips::{TiltNeighbour, TiltOnset, TiltTouch, TILT_ONSET, TOUCH_DISTANCE};

/// Time the world gets after each control (or a control cut short) before it is observed:
/// the objects come to rest, as a robot would pause to look (s).
pub const OBSERVE_AFTER: f64 = 0.05;

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
