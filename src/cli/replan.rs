//! `pushplan replan`: the rest of a plan from a state observed while it ran. The plan's
//! remaining controls are re-simulated from the observed state first; if they still reach
//! the goal they are the new plan; if they are valid for a while, they are kept to there
//! and an ending is searched from where they end (a repair); else, or if the repair finds
//! nothing, the scene is searched anew from that state (`planning::rest`).

use super::plan::{plan_loaded, PlanOptions};
use super::SearchFlags;
use pushplan::limits::Front;
use pushplan::planner::plan_scene::repair_scene;
use pushplan::planner::Search;
use pushplan::planning::observed::ObservedState;
use pushplan::planning::plan_file::{PlanFile, ReplanRecord};
use pushplan::planning::rest::{RestFrom, REPAIR_SHARE};
use pushplan::{DistanceMetric, Scene};
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

/// What `replan` is asked.
pub struct ReplanOptions {
    /// The control at whose start the state was observed (`None`: the one after the
    /// plan's recorded state nearest the observation).
    pub at: Option<usize>,
    /// The new search's flags (the scene's `planner:` values where they are not given).
    pub search: SearchFlags,
    /// No progress output.
    pub quiet: bool,
}

/// `pushplan replan`: writes to `out` the plan for the rest of `plan_path` from the state
/// in `observed_path`.
pub fn replan(
    search: &dyn Search,
    plan_path: &Path,
    observed_path: &Path,
    options: ReplanOptions,
    out: &Path,
) -> Result<ExitCode, String> {
    let old = PlanFile::read(plan_path)?;
    // The plan's scene, checked against the plan (names, and a re-planned plan's own
    // start); where it starts does not matter: the observed state replaces its start.
    let scene = old.load_scene(plan_path)?;
    let scene_path = old.scene_path(plan_path);
    let observed = ObservedState::read(observed_path)?.state(&scene, observed_path)?;
    let from = scene
        .with_start(&observed, observed_path)
        .map_err(|e| e.to_string())?;
    let count = old.controls.len();
    let at = match options.at {
        Some(at) if at <= count => at,
        Some(at) => {
            return Err(format!(
                "--at {at}: the plan has {} controls (0 to {} may be given)",
                count, count
            ))
        }
        None => nearest_recorded_state(&old, &from),
    };
    let record = |kept, repaired| ReplanRecord {
        plan: PlanFile::scene_reference(plan_path, out),
        at,
        observed: PlanFile::scene_reference(observed_path, out),
        kept,
        repaired,
    };
    let reference = PlanFile::scene_reference(&scene_path, out);

    // The rest of the plan, as it is, from where the world is: kept whole if it still
    // reaches the goal, else repaired where it can be (`planning::rest`).
    let (rest, verdict) = old.rest_from(at, &from);
    let (valid, end, why_not) = match verdict {
        RestFrom::Reaches => {
            let mut file = PlanFile::build(&reference, from, &old.settings, &rest, None)?;
            file.replanned = Some(record(true, None));
            pushplan::output::write_whole(out, file.to_json())?;
            println!(
                "kept: the plan's controls {at} to {count} still reach the goal from the observed state ({} written)",
                out.display()
            );
            return Ok(ExitCode::SUCCESS);
        }
        RestFrom::EndsShort { valid, end, why } => (valid, end, why),
    };
    if valid > 0 {
        if !options.quiet {
            eprintln!(
                "the rest of the plan from control {at} no longer reaches the goal ({why_not}): \
                 keeping its controls {at} to {} and searching an ending from where they end",
                at + valid
            );
        }
        let mut settings = options.search.settings(&from.planner);
        settings.check(Front::CommandLine)?;
        settings.time_limit *= REPAIR_SHARE;
        let started = Instant::now();
        let repaired = repair_scene(search, &from, &settings, &reference, &rest[..valid], &end)?;
        if let Some(mut file) = repaired {
            file.replanned = Some(record(false, Some(valid)));
            pushplan::output::write_whole(out, file.to_json())?;
            println!(
                "repaired in {:.3} s: the plan's controls {at} to {} kept, then an ending of {} controls \
                 searched from where they end ({} written)",
                started.elapsed().as_secs_f64(),
                at + valid,
                file.controls.len() - valid,
                out.display()
            );
            return Ok(ExitCode::SUCCESS);
        }
    }
    if !options.quiet {
        eprintln!("the rest of the plan from control {at} no longer works ({why_not}): searching from the observed state");
    }
    plan_loaded(
        search,
        &from,
        &scene_path,
        Instant::now(),
        &PlanOptions {
            search: options.search,
            quiet: options.quiet,
            grasp_goal: None,
            grasp_after: false,
            sample_probability: 0.0,
            replanned: Some(record(false, None)),
        },
        out,
    )
}

/// The control at whose start the plan's recorded state is nearest the start of `from`
/// (the planner's metric); the control count if that is the final state.
fn nearest_recorded_state(plan: &PlanFile, from: &Scene) -> usize {
    let metric = DistanceMetric::from_scene(from);
    std::iter::once(&plan.start)
        .chain(plan.controls.iter().map(|c| &c.state))
        .map(|record| metric.distance(&record.state(), &from.start))
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(0, |(i, _)| i)
}
