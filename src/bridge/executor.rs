//! [`Executor`]: closed-loop execution for an application that observes its own world
//! ([`crate::planner::closed_loop::Executor`]), its re-plans searched by OMPL
//! ([`super::OmplSearch`]). The C++ API's `pushplan::Executor` holds one.

use super::core::{guarded, Flat};
use super::{ffi, OmplSearch, Problem};
use crate::limits::{Front, Limit, Number};
use crate::planner::closed_loop::{self, ClosedLoop, ClosedLoopOptions, ClosedLoopSettings, Step};
use crate::planning::execute::ExecuteSettings;
use crate::planning::path::PathControl;
use crate::scene::Scene;
use std::fmt::Display;

/// The search every bridged executor re-plans with: OMPL's, stateless.
static OMPL: OmplSearch = OmplSearch;

/// A plan's closed-loop executor, asked after each observation what to play.
pub struct Executor(closed_loop::Executor);

impl Executor {
    /// The executor of the plan `controls` / `steps` (flat, from `problem`'s start) in
    /// `problem`'s scene, re-planning as `settings` say (checked against the limits table
    /// first).
    pub fn new(
        problem: &Problem,
        controls: &[f64],
        steps: &[usize],
        settings: &ffi::ExecutorSettings,
    ) -> Result<Box<Executor>, String> {
        guarded("Executor", || {
            let (settings, speed) = settings_of(settings)?;
            let scene: &Scene = &problem.scene;
            let plan = Flat(scene).path_controls(controls, steps)?;
            let closed = ClosedLoop {
                search: &OMPL,
                settings,
                execution: ExecuteSettings {
                    speed,
                    ..ExecuteSettings::default()
                },
            };
            Ok(Box::new(Executor(closed.executor(scene, &plan))))
        })
    }

    /// What to play after the world was observed in the flat state `observed`.
    pub fn step(&mut self, observed: &[f64]) -> Result<ffi::ExecutorStep, String> {
        guarded("Executor::step", || {
            let observed = Flat(self.0.scene()).state(observed)?;
            Ok(match self.0.step(&observed) {
                Step::Play {
                    control,
                    trajectory,
                    predicted,
                } => {
                    let (control, steps) = PathControl::to_flat(std::slice::from_ref(&control));
                    ffi::ExecutorStep {
                        kind: ffi::ExecutorStepKind::Play,
                        control,
                        steps: steps[0],
                        trajectory: trajectory.into(),
                        predicted: predicted.to_flat(),
                        why: String::new(),
                    }
                }
                Step::Finished => ffi::ExecutorStep::other(ffi::ExecutorStepKind::Finished, ""),
                Step::Stopped(why) => {
                    ffi::ExecutorStep::other(ffi::ExecutorStepKind::Stopped, &why)
                }
            })
        })
    }

    /// The execution so far.
    pub fn report(&self) -> ffi::ExecutorReport {
        let t = self.0.trial();
        ffi::ExecutorReport {
            controls_played: t.controls_played,
            kept: t.kept,
            invalid_rests: t.invalid_rests,
            replans: t.replans,
            repairs: t.repairs,
            failed_replans: t.failed_replans,
            legs: t.legs,
            backoffs: t.backoffs,
            search_time: t.search_time,
            latencies: t.latencies.clone(),
            replan_latencies: t.replan_latencies.clone(),
            last_failure: t.last_failure.clone().unwrap_or_default(),
            stopped: t.stopped.clone().unwrap_or_default(),
        }
    }
}

impl ffi::ExecutorStep {
    /// A step that plays nothing.
    fn other(kind: ffi::ExecutorStepKind, why: &str) -> Self {
        ffi::ExecutorStep {
            kind,
            control: Vec::new(),
            steps: 0,
            trajectory: ffi::Trajectory {
                rate: 0.0,
                times: Vec::new(),
                q: Vec::new(),
                objects: Vec::new(),
            },
            predicted: Vec::new(),
            why: why.to_string(),
        }
    }
}

/// The closed loop's settings and the pace the application plays at, from the C++ side's
/// (each value checked against the limits table).
fn settings_of(s: &ffi::ExecutorSettings) -> Result<(ClosedLoopSettings, f64), String> {
    use crate::limits::*;
    let options = ClosedLoopOptions {
        replan_time: within(&REPLAN_TIME, s.replan_time)?,
        replan_threads: within(&REPLAN_THREADS, s.replan_threads)?,
        replan_shortcut: within(&REPLAN_SHORTCUT, s.replan_shortcut)?,
        replan_polish: within(&REPLAN_POLISH, s.replan_polish)?,
        replan_mend: within(&REPLAN_MEND, s.replan_mend)?,
        max_replans: within(&MAX_REPLANS, s.max_replans)?,
        replan_budget: within(&REPLAN_BUDGET, s.replan_budget)?,
        replan_leg: within(&REPLAN_LEG, s.replan_leg)?,
        repair_ahead: s.repair_ahead,
    };
    Ok((
        options.settings(s.planner, s.seed),
        within(&SPEED, s.speed)?,
    ))
}

/// `value` if it lies within `limit`; else why not, named as the C++ API's
/// `ExecutorOptions` names it: as the command-line option (`--replan-time` is
/// `ExecutorOptions::replan_time`).
fn within<T: Copy + Display + Into<Number>>(limit: &Limit, value: T) -> Result<T, String> {
    limit.check(Front::CommandLine, value).map_err(|e| {
        let field = limit.option.trim_start_matches("--").replace('-', "_");
        format!("ExecutorOptions::{field}{}", &e[limit.option.len()..])
    })
}
