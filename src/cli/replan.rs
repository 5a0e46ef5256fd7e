//! `pushplan replan`: the rest of a plan from a state observed while it ran. The plan's
//! remaining controls are re-simulated from the observed state first; if they still reach
//! the goal they are the new plan, else the scene is searched anew from that state.

use super::plan::{plan, ObservedStart, PlanOptions};
use super::SearchFlags;
use pushplan::planner::Search;
use pushplan::planning::observed::ObservedState;
use pushplan::planning::plan_file::{PlanFile, ReplanRecord};
use pushplan::{DistanceMetric, Scene};
use std::path::Path;
use std::process::ExitCode;

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
    let record = |kept| ReplanRecord {
        plan: PlanFile::scene_reference(plan_path, out),
        at,
        observed: PlanFile::scene_reference(observed_path, out),
        kept,
    };

    // The rest of the plan, as it is, from where the world is.
    let why_not = match old.rest_from(at, &from) {
        Ok(rest) => {
            let reference = PlanFile::scene_reference(&scene_path, out);
            let mut file = PlanFile::build(&reference, from, &old.settings, &rest, None)?;
            file.replanned = Some(record(true));
            pushplan::output::write_whole(out, file.to_json())?;
            println!(
                "kept: the plan's controls {at} to {} still reach the goal from the observed state ({} written)",
                count,
                out.display()
            );
            return Ok(ExitCode::SUCCESS);
        }
        Err(why_not) => why_not,
    };
    if !options.quiet {
        eprintln!("the rest of the plan from control {at} no longer works ({why_not}): searching from the observed state");
    }
    plan(
        search,
        &scene_path,
        &PlanOptions {
            search: options.search,
            quiet: options.quiet,
            grasp_goal: None,
            grasp_after: false,
            sample_probability: 0.0,
            from: Some(ObservedStart {
                state: observed,
                source: observed_path.to_path_buf(),
                record: record(false),
            }),
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
