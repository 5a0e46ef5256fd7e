//! A scene planned end to end into a plan file, as `pushplan plan` and the Python module
//! do: the search, then the one way a found path is finished (shortcut, re-simulated,
//! measured for robustness), written as a [`PlanFile`].

use crate::planner::{Found, ReachSettings, Reached, Search, SearchProgress};
use crate::planning::path::PathControl;
use crate::planning::plan_file::{
    PlanFile, PlanSettings, ReachRecord, RobustnessRecord, UnseenRate,
};
use crate::planning::shortcut::ShortcutProgress;
use crate::planning::{
    time_left, CommandDeadline, FinishSettings, FinishedPath, Problem, RobustRequirement,
    RunSettings,
};
use crate::scene::Scene;
use crate::state::State;
use std::path::Path;
use std::time::Instant;

/// What to plan and how.
pub struct PlanRequest<'a> {
    /// The scene, loaded, starting where the search starts (for a re-plan, where the plan
    /// starts: `Scene::with_start`).
    pub scene: &'a Scene,
    /// The settings; the search gets the time `deadline` leaves, not `time_limit`.
    pub options: &'a RunSettings,
    /// When the search and the finishing stop.
    pub deadline: Instant,
    /// The plan file's `scene` field ([`PlanFile::scene_reference`]).
    pub reference: &'a str,
    /// Progress reports of the search and of shortcutting, if wanted.
    pub search_progress: Option<fn(&SearchProgress, &str)>,
    /// See `search_progress`.
    pub shortcut_progress: Option<fn(&ShortcutProgress)>,
}

/// A planned scene: the plan file, and how the search and the finishing went.
pub struct Planned {
    /// The plan file (not yet written; no reach, no re-plan record).
    pub file: PlanFile,
    /// The search's answer: its summary, statistics and the path as found.
    pub found: Found,
    /// The path as finished.
    pub path: FinishedPath,
    /// The problem the path was finished in.
    pub problem: Problem,
}

/// Searches `request.scene` with `search` and finishes what it finds into a plan file. The
/// plan is robust when `options.robust_trials` > 0: a solution is kept when that share of
/// perturbed worlds reaches the goal, else the most robust one found by the deadline.
pub fn plan_scene(search: &dyn Search, request: &PlanRequest) -> Result<Planned, String> {
    let options = request.options;
    let found = search.solve(
        request.scene,
        &RunSettings {
            time_limit: time_left(request.deadline),
            ..*options
        },
        request.search_progress,
    )?;
    let problem = Problem::new(request.scene.clone(), options.planner);
    let finish_settings = FinishSettings {
        shortcut: options.shortcut,
        seed: options.seed,
        robust: (options.robust_trials > 0).then_some(RobustRequirement {
            trials: options.robust_trials as usize,
            rate: options.robust_rate,
        }),
        // The found solution is robust enough (or the most robust in time): shortened
        // first, kept only as robust.
        only_toward_robustness: false,
        // The rate the plan states is the check's, the luckiest of the run: measured
        // again in worlds the choice did not see.
        unseen_trials: options.robust_trials as usize,
        found_rate: found.robustness,
        deadline: Some(request.deadline),
        progress: request.shortcut_progress,
        threads: options.threads as usize,
    };
    let path = problem.finish(
        &found.controls,
        &found.states,
        found.summary.exact,
        &finish_settings,
    )?;
    let mut file = PlanFile::from_simulation(
        request.reference,
        request.scene,
        &PlanSettings::from(options),
        &path.controls,
        &path.simulation,
        Some(path.before),
    )?;
    file.robustness = path.robustness.map(|measured| RobustnessRecord {
        trials: measured.trials,
        required_rate: options.robust_rate,
        success_rate: measured.rate,
        particles: options.robust_particles,
        shortcut: options.robust_shortcut,
        asked: (measured.trials < options.robust_trials as usize)
            .then_some(options.robust_trials as usize),
        unseen: path.unseen.map(|u| UnseenRate {
            trials: u.trials,
            success_rate: u.rate,
        }),
    });
    Ok(Planned {
        file,
        found,
        path,
        problem,
    })
}

/// A repair of the rest of a plan ([`crate::planning::rest`]): `kept`, the rest's
/// controls valid from `from`'s start (the observed state) and ending in `end`, then an
/// ending searched from `end` and finished as `options` say, all within
/// `options.time_limit` s. `None` when the search finds no exact ending in that time; the
/// plan file (`reference`: its `scene` field) starts at the observed state and records the
/// ending's settings (no re-plan record).
pub fn repair_scene(
    search: &dyn Search,
    from: &Scene,
    options: &RunSettings,
    reference: &str,
    kept: &[PathControl],
    end: &State,
) -> Result<Option<PlanFile>, String> {
    let deadline = CommandDeadline::new(Instant::now(), options.time_limit, from, false);
    let at_end = from
        .with_start(end, Path::new("the end of the plan's valid part"))
        .map_err(|e| e.to_string())?;
    let ending = plan_scene(
        search,
        &PlanRequest {
            scene: &at_end,
            options,
            deadline: deadline.pushing,
            reference,
            search_progress: None,
            shortcut_progress: None,
        },
    )?;
    if !ending.found.summary.exact {
        return Ok(None);
    }
    let controls = [kept, &ending.file.path_controls()].concat();
    let file = PlanFile::build(
        reference,
        from.clone(),
        &ending.file.settings,
        &controls,
        None,
    )?;
    // The ending starts where the kept part ends, bit for bit (a valid state is taken as
    // it is), so the whole reaches the goal as the ending did.
    Ok(file.solved.then_some(file))
}

/// IK-BiRRT's reach of a grasp of `object` from `from` (`None`: the scene's start), with
/// `seed` and P_sample `sample_probability`, until `deadline`'s last part: what the plan
/// file records of it (`None` when none was found) and how the search went.
pub fn reach_grasp(
    search: &dyn Search,
    scene: &Scene,
    object: &str,
    from: Option<&State>,
    seed: u64,
    sample_probability: f64,
    deadline: &CommandDeadline,
) -> Result<(Option<ReachRecord>, Reached), String> {
    let settings = ReachSettings {
        time_limit: deadline.reach_time(),
        seed,
        sample_probability,
    };
    let found = search.reach(scene, object, from, &settings)?;
    let record = found.solved.then(|| ReachRecord {
        object: object.to_string(),
        sample_probability,
        waypoints: found
            .waypoints
            .iter()
            .map(|q| q.as_slice().to_vec())
            .collect(),
    });
    Ok((record, found))
}
