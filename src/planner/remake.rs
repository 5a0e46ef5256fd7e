//! A plan file made again from what it records of how it was made: `check`'s proof of
//! the fields a re-simulation cannot confirm (the planner, its settings and seed, the
//! metrics before shortcutting, the robustness record, a re-plan's record).
//!
//! Every choice a search, shortcutting, a robustness check and a reach make is counted in
//! propagation steps and seeded from the file's seed, so the same scene, settings and seed
//! give the same plan, byte for byte, on any machine, unless the clock stopped one of them.
//! The plan is made again within the file's time limit, as `plan` made it; if that gives
//! another plan, once more with time to spare ([`remake_time`]): the same plan then says
//! that the clock of this machine, not the file, made the difference, and the plan is not
//! confirmed (nor refuted). A plan the clock did shape (unsolved, or the most robust
//! solution found by the time limit) cannot be made again, and says so.

use crate::planner::plan_scene::{plan_scene, reach_grasp, repair_scene, PlanRequest};
use crate::planner::Search;
use crate::planning::observed::ObservedState;
use crate::planning::plan_file::{first_difference, PlanFile};
use crate::planning::rest::RestFrom;
use crate::planning::CommandDeadline;
use std::path::Path;
use std::time::Instant;

/// What making a plan file again gave.
#[derive(Clone, Debug, PartialEq)]
pub enum Remade {
    /// The same plan file, byte for byte.
    Same,
    /// Another plan: the first field where the file differs from it (a path such as
    /// `metrics.before_shortcut.ee_length`), or what in the re-plan's record is not so.
    Differs(String),
    /// The file cannot be made again: why.
    Cannot(String),
}

/// The time a plan made within `time_limit` (s) gets when, made again within it, it
/// differs: twice as much, and at least 10 s more, for a slower or busier machine (a
/// search that finishes within its limit does the same steps with more time).
pub fn remake_time(time_limit: f64) -> f64 {
    (2.0 * time_limit).max(time_limit + 10.0)
}

/// Makes the plan file at `plan_path` (read as `plan`) again as `plan`, `replan` or
/// `plan --grasp` made it, from its scene, settings and seed, and compares the two. Errors
/// are those of loading its scene.
pub fn remake(search: &dyn Search, plan: &PlanFile, plan_path: &Path) -> Result<Remade, String> {
    if !plan.solved {
        return Ok(Remade::Cannot(
            "not solved: its search ran until the time limit, and where the clock stops a \
             search depends on the machine"
                .into(),
        ));
    }
    if let Some(r) = &plan.robustness {
        if let Some(asked) = r.asked {
            return Ok(Remade::Cannot(format!(
                "the time limit cut its robustness check short, at {} of the {asked} perturbed \
                 worlds asked, and where the clock stops it depends on the machine",
                r.trials
            )));
        }
        if r.unseen.as_ref().is_none_or(|u| u.trials < r.trials) {
            return Ok(Remade::Cannot(
                "its rate in other perturbed worlds is cut short or absent (the time limit \
                 came first, and where the clock stops depends on the machine; or the file is \
                 older than the record)"
                    .into(),
            ));
        }
        if r.success_rate < r.required_rate {
            return Ok(Remade::Cannot(format!(
                "its paths reach the goal in {:.0} % of the perturbed worlds, below the {:.0} % asked: \
                 the most robust solution found by the time limit, and where the clock stops a search \
                 depends on the machine",
                100.0 * r.success_rate,
                100.0 * r.required_rate
            )));
        }
    }
    let in_its_time = match made_again(search, plan, plan_path, plan.settings.time_limit)? {
        Ok(file) => file,
        Err(outcome) => return Ok(outcome),
    };
    let Some(field) = first_difference(plan, &in_its_time) else {
        return Ok(Remade::Same);
    };
    let limit = remake_time(plan.settings.time_limit);
    let with_time_to_spare = match made_again(search, plan, plan_path, limit)? {
        Ok(file) => file,
        Err(outcome) => return Ok(outcome),
    };
    Ok(match first_difference(plan, &with_time_to_spare) {
        None => Remade::Cannot(format!(
            "made again within its time limit of {:?} s, the plan differs ({field}); with {limit:?} s \
             it is the same: the clock stopped a part of it sooner on this machine than where it \
             was made",
            plan.settings.time_limit
        )),
        Some(field) => Remade::Differs(field),
    })
}

/// The plan file `plan`'s settings make (the search given `time_limit` s), or what stops
/// it being made: the file's other records (a re-plan's) are not so, or cannot be read.
fn made_again(
    search: &dyn Search,
    plan: &PlanFile,
    plan_path: &Path,
    time_limit: f64,
) -> Result<Result<PlanFile, Remade>, String> {
    let folder = plan_path.parent().unwrap_or(Path::new("."));
    Ok(Ok(match &plan.replanned {
        Some(record) => {
            // A re-plan is made again from the plan and the observation it names.
            let old_path = folder.join(&record.plan);
            let observed_path = folder.join(&record.observed);
            let (old, observed) = match read_replan_inputs(&old_path, &observed_path) {
                Ok(inputs) => inputs,
                Err(why) => return Ok(Err(Remade::Cannot(why))),
            };
            let scene = old.load_scene(&old_path)?;
            let observed = observed.state(&scene, &observed_path)?;
            let from = scene
                .with_start(&observed, &observed_path)
                .map_err(|e| e.to_string())?;
            if record.at > old.controls.len() {
                return Ok(Err(Remade::Differs(format!(
                    "replanned.at: control {} of a plan of {}",
                    record.at,
                    old.controls.len()
                ))));
            }
            let (rest, verdict) = old.rest_from(record.at, &from);
            let the_rest = format!(
                "the rest of {} from control {}",
                old_path.display(),
                record.at
            );
            let differs = |why: String| Ok(Err(Remade::Differs(why)));
            match (verdict, record.kept, record.repaired) {
                (_, true, Some(_)) => {
                    return differs("replanned: kept and repaired at once".into());
                }
                (RestFrom::Reaches, true, None) => {
                    let mut file = PlanFile::build(&plan.scene, from, &old.settings, &rest, None)?;
                    file.replanned = Some(record.clone());
                    file
                }
                (RestFrom::Reaches, false, _) => {
                    return differs(format!(
                        "replanned.kept: {the_rest} still reaches the goal from the observed state, and is kept"
                    ));
                }
                (RestFrom::EndsShort { why, .. }, true, _) => {
                    return differs(format!(
                        "replanned.kept: {the_rest} does not reach the goal from the observed state ({why})"
                    ));
                }
                (RestFrom::EndsShort { valid, end, .. }, false, Some(repaired)) => {
                    if repaired != valid || valid == 0 {
                        return differs(format!(
                            "replanned.repaired: {repaired} controls of {the_rest} kept, but {valid} are valid from the observed state"
                        ));
                    }
                    match repair_again(search, plan, &from, &rest[..valid], &end, time_limit)? {
                        Some(mut file) => {
                            file.replanned = Some(record.clone());
                            file
                        }
                        None => {
                            return differs(format!(
                                "replanned.repaired: no ending found from where the valid part of {the_rest} ends"
                            ))
                        }
                    }
                }
                (RestFrom::EndsShort { .. }, false, None) => {
                    let mut file = search_again(search, plan, &from, time_limit)?;
                    file.replanned = Some(record.clone());
                    file
                }
            }
        }
        None => {
            let scene = plan.load_scene(plan_path)?;
            search_again(search, plan, &scene, time_limit)?
        }
    }))
}

/// The plan and the observation a re-plan names, read; else why not.
fn read_replan_inputs(
    old_path: &Path,
    observed_path: &Path,
) -> Result<(PlanFile, ObservedState), String> {
    let unreadable = |e: String| {
        format!("replanned: the plan and observation it was made from must be read to make it again: {e}")
    };
    let old = PlanFile::read(old_path).map_err(unreadable)?;
    let observed = ObservedState::read(observed_path).map_err(unreadable)?;
    Ok((old, observed))
}

/// A repair as `replan` makes it ([`repair_scene`]): `kept`, the valid part of the old
/// plan's rest from `from`'s start (the observed state), then an ending searched from
/// `end` with the file's settings within `time_limit` s.
fn repair_again(
    search: &dyn Search,
    plan: &PlanFile,
    from: &crate::Scene,
    kept: &[crate::planning::path::PathControl],
    end: &crate::State,
    time_limit: f64,
) -> Result<Option<PlanFile>, String> {
    let options = plan
        .settings
        .run_settings(plan.robustness.as_ref(), time_limit);
    let repaired = repair_scene(search, from, &options, &plan.scene, kept, end)?;
    // What the settings record is what they were made with, not the time given here.
    Ok(repaired.map(|mut file| {
        file.settings.time_limit = plan.settings.time_limit;
        file
    }))
}

/// `plan`'s search and finishing (and reach of a grasp) as the file records them, in
/// `scene` (from its start: the scene file's, or where the plan starts), within
/// `time_limit` s.
fn search_again(
    search: &dyn Search,
    plan: &PlanFile,
    scene: &crate::Scene,
    time_limit: f64,
) -> Result<PlanFile, String> {
    let started = Instant::now();
    let options = plan
        .settings
        .run_settings(plan.robustness.as_ref(), time_limit);
    // `plan --goal grasp:OBJECT` has no controls and a reach; `plan --grasp` both.
    let grasp = plan.reach.as_ref();
    let grasp_only = grasp.is_some() && plan.controls.is_empty();
    let deadline = CommandDeadline::new(started, time_limit, scene, grasp.is_some() && !grasp_only);
    let reach = |from: Option<&crate::State>| {
        let record = grasp.expect("asked only with a reach");
        let (found, _) = reach_grasp(
            search,
            scene,
            &record.object,
            from,
            options.seed,
            record.sample_probability,
            &deadline,
        )?;
        Ok::<_, String>(found)
    };
    if grasp_only {
        let file = PlanFile::build(&plan.scene, scene.clone(), &plan.settings, &[], None)?;
        return match reach(None)? {
            Some(record) => file.with_reach(scene, record),
            None => Ok(file),
        };
    }
    let planned = plan_scene(
        search,
        &PlanRequest {
            scene,
            options: &options,
            deadline: deadline.pushing,
            reference: &plan.scene,
            search_progress: None,
            shortcut_progress: None,
        },
    )?;
    let mut file = planned.file;
    // What the settings record is what they were made with, not the time given here.
    file.settings.time_limit = plan.settings.time_limit;
    file.grasp_after.clone_from(&plan.grasp_after);
    if grasp.is_some() && planned.found.summary.exact {
        match reach(Some(&file.end_state()))? {
            Some(record) => file = file.with_reach(scene, record)?,
            None => file.solved = false,
        }
    }
    Ok(file)
}
