//! `pushplan plan`: search a scene with OMPL, finish the path, write the plan file.

use super::progress;
use super::SearchFlags;
use pushplan::limits::Front;
use pushplan::planner::plan_scene::{plan_scene, reach_grasp, PlanRequest, Planned};
use pushplan::planner::Search;
use pushplan::planning::plan_file::{PlanFile, PlanSettings, ReachRecord, ReplanRecord};
use pushplan::planning::shortcut::ShortcutProgress;
use pushplan::planning::{CommandDeadline, PlannerKind, RunSettings, PLAN_ROBUST_TRIALS};
use pushplan::state::State;
use pushplan::Scene;
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

/// The `plan` command's options: the search's settings as the flags set them, and what
/// the command does around the search.
pub struct PlanOptions {
    /// The search's flags (the scene's `planner:` values where they are not given).
    pub search: SearchFlags,
    /// No progress output.
    pub quiet: bool,
    /// `--goal grasp:OBJECT`: reach a grasp of this object instead of pushing.
    pub grasp_goal: Option<String>,
    /// `--grasp`: after pushing, reach a grasp of the goal object.
    pub grasp_after: bool,
    /// IK-BiRRT's P_sample.
    pub sample_probability: f64,
    /// A re-plan (`replan`): the scene's start is a state observed while a plan ran
    /// (as [`Scene::with_start`] makes it); the new plan's record of where it comes from.
    pub replanned: Option<ReplanRecord>,
}

/// The object of a `--goal` value `grasp:OBJECT`.
pub fn grasp_goal(goal: &str) -> Result<String, String> {
    match goal.strip_prefix("grasp:") {
        Some(object) if !object.is_empty() => Ok(object.to_string()),
        _ => Err(format!(
            "--goal must be grasp:OBJECT (an object with grasps in the scene), got '{goal}'"
        )),
    }
}

/// IK-BiRRT's reach of a grasp of `object` from `from` (`None`: the start), as the plan
/// file records it; `None` if no reach was found by `deadline` (with the search's seed:
/// `search_settings`).
fn reach(
    search: &dyn Search,
    scene: &Scene,
    object: &str,
    from: Option<&State>,
    run: &PlanOptions,
    search_settings: &RunSettings,
    deadline: &CommandDeadline,
) -> Result<Option<ReachRecord>, String> {
    if !(0.0..=1.0).contains(&run.sample_probability) {
        return Err(format!(
            "--sample-probability must be in [0, 1], got {}",
            run.sample_probability
        ));
    }
    let (record, found) = reach_grasp(
        search,
        scene,
        object,
        from,
        search_settings.seed,
        run.sample_probability,
        deadline,
    )?;
    if !run.quiet {
        eprintln!(
            "reaching a grasp of '{object}' with IK-BiRRT: {} in {:.2} s, {} IK solutions, trees of {} states",
            if found.solved { "found" } else { "not found" },
            found.planning_time,
            found.goal_samples,
            found.tree_size
        );
    }
    Ok(record)
}

/// `pushplan plan`: loads the scene at `scene_path` and plans it ([`plan_loaded`]).
pub fn plan(
    search: &dyn Search,
    scene_path: &Path,
    run: &PlanOptions,
    out: &Path,
) -> Result<ExitCode, String> {
    // --time bounds the whole command: loading, search, shortcutting and writing.
    let started = Instant::now();
    let scene = Scene::load(scene_path).map_err(|e| e.to_string())?;
    plan_loaded(search, &scene, scene_path, started, run, out)
}

/// `pushplan plan` on `scene`, loaded from `scene_path` (a re-plan's with its start
/// observed): searches it with `search`, finishes the path and writes the plan file to
/// `out`, all within the time limit counted from `started`.
pub fn plan_loaded(
    search: &dyn Search,
    scene: &Scene,
    scene_path: &Path,
    started: Instant,
    run: &PlanOptions,
    out: &Path,
) -> Result<ExitCode, String> {
    // A scene that loads may still ask the impossible (`check SCENE.yaml` prints the same);
    // a re-plan's start is the world's, not the user's choice.
    if run.replanned.is_none() {
        for warning in pushplan::scene::check::check(scene) {
            eprintln!("warning: {}: {warning}", scene_path.display());
        }
    }
    // The plan's folder is made and tried before the search, not found wanting after it.
    pushplan::output::check_writable(out)?;
    let mut options = run.search.settings(&scene.planner);
    // A plan is robust unless asked otherwise; a re-plan (`replan`) is wanted fast.
    if run.search.robust_trials.is_none() && run.replanned.is_none() {
        options.robust_trials = PLAN_ROBUST_TRIALS;
    }
    let (planner, quiet) = (options.planner, run.quiet);
    options.check(Front::CommandLine)?;
    if run.search.k.is_some() && !planner.takes_best_of_k() {
        let takers: Vec<&str> = PlannerKind::ALL
            .into_iter()
            .filter(|kind| kind.takes_best_of_k())
            .map(PlannerKind::name)
            .collect();
        eprintln!(
            "note: --k has no effect on {}: only {} choose each control as the best of k",
            planner.name(),
            takers.join(" and ")
        );
    }
    let settings = PlanSettings::from(&options);
    let deadline = CommandDeadline::new(started, options.time_limit, scene, run.grasp_after);
    let reference = PlanFile::scene_reference(scene_path, out);
    if let Some(object) = &run.grasp_goal {
        // Reaching a grasp only: no controls, the reach from the start.
        pushplan::planning::reach::graspable_object(scene, object)?;
        let found = reach(search, scene, object, None, run, &options, &deadline)?;
        let solved = found.is_some();
        let mut file = PlanFile::build(&reference, scene.clone(), &settings, &[], None)?;
        if let Some(record) = found {
            file = file.with_reach(scene, record)?;
        }
        return write_plan(&file, out, solved);
    }
    // `--grasp`: the goal object, grasped after the pushing (it must have grasps).
    let grasp_after = match (run.grasp_after, &scene.goal) {
        (false, _) => None,
        (true, pushplan::scene::Goal::ObjectInDisc { object, .. }) => {
            let name = &scene.objects[*object].name;
            pushplan::planning::reach::graspable_object(scene, name)?;
            Some(name.clone())
        }
        (true, _) => {
            return Err("--grasp needs an object goal (the object to grasp after pushing)".into())
        }
    };
    if !quiet {
        eprintln!(
            "planning '{}' with {} (k = {}, seed = {}, up to {} s, {})",
            scene.name,
            planner.name(),
            options.k,
            options.seed,
            options.time_limit,
            match options.threads {
                1 => "one search".to_string(),
                n if planner.shares_one_search() => format!("one search on {n} threads"),
                n => format!("{n} searches in parallel"),
            }
        );
    }
    if !quiet {
        progress::start(match scene.goal {
            pushplan::scene::Goal::ObjectInDisc { .. } => "m",
            pushplan::scene::Goal::Configuration { .. } => "rad",
            pushplan::scene::Goal::Grasp { .. } => "(m and rad)",
        });
    }
    let planned = plan_scene(
        search,
        &PlanRequest {
            scene,
            options: &options,
            deadline: deadline.pushing,
            reference: &reference,
            search_progress: (!quiet).then_some(progress::search as _),
            shortcut_progress: (!quiet).then_some(progress::shortcut as fn(&ShortcutProgress)),
        },
    );
    progress::finish();
    let Planned {
        mut file,
        found: solution,
        path,
        problem,
    } = planned?;
    let dof = scene.robot.dof();
    let found = &solution.controls;
    if !quiet && path.shortcut.attempts > 0 {
        eprintln!(
            "shortcutting: {} of {} attempts accepted",
            path.shortcut.accepted, path.shortcut.attempts
        );
        if path.shortcut.stopped_at_deadline {
            eprintln!("shortcutting: stopped at the time limit (--time) with budget left");
        }
        if path.shortcut.dropped_as_less_robust {
            eprintln!("shortcutting: the shortcut path is less robust; the path as found is kept");
        }
    }
    file.replanned = run.replanned.clone();
    file.grasp_after.clone_from(&grasp_after);
    let mut solved = solution.summary.exact;
    if let (Some(name), true) = (&grasp_after, solution.summary.exact) {
        let end = file.end_state();
        match reach(search, scene, name, Some(&end), run, &options, &deadline)? {
            Some(record) => file = file.with_reach(problem.scene(), record)?,
            None => {
                file.solved = false;
                solved = false;
            }
        }
    }
    pushplan::output::write_whole(out, file.to_json())?;

    let status = if solution.summary.exact {
        "solved"
    } else if solution.summary.approximate {
        "not solved (approximate path written)"
    } else {
        "not solved"
    };
    println!(
        "{status} in {:.3} s: tree of {} states, {} propagation steps ({:.0} steps/s){}{}{}{}",
        solution.summary.planning_time,
        solution.summary.tree_size,
        solution.summary.propagation_steps,
        solution.summary.propagation_steps as f64 / solution.summary.planning_time.max(1e-9),
        match solution.summary.lanes {
            0 => String::new(),
            n => format!(" on {n} lanes"),
        },
        match solution.summary.restarts {
            0 => String::new(),
            1 => ", 1 restart".to_string(),
            n => format!(", {n} restarts"),
        },
        match solution.summary.fallbacks {
            0 => "",
            _ => ", then PC RRT (the goal object had not moved)",
        },
        match solution.summary.handed_back {
            0 => String::new(),
            1 => ", then Push KPIECE from where PC RRT moved it".to_string(),
            n => format!(", then Push KPIECE from where PC RRT moved it ({n} times)"),
        }
    );
    if !solution.summary.exact && !found.is_empty() {
        let goal = &problem.scene().goal;
        let left = goal.distance(path.simulation.final_state());
        println!(
            "closest: {}",
            match goal {
                pushplan::scene::Goal::ObjectInDisc { .. } if left <= 0.0 && options.robust_particles > 0 => format!(
                    "the goal object ends {:.0} mm inside the goal region, but not in every perturbed world the search carried",
                    -1e3 * left
                ),
                pushplan::scene::Goal::ObjectInDisc { margin, .. } => format!(
                    "the goal object ends {:.0} mm from the goal region (the goal disc less its {:.0} mm margin)",
                    1e3 * left,
                    1e3 * margin
                ),
                pushplan::scene::Goal::Grasp { object, .. } => format!(
                    "the tool ends {:.3} (m and rad together, the lecture's d(q, WGR)) from the nearest grasp region of '{}'",
                    left + pushplan::robot::wgr::GRASP_TOLERANCE,
                    problem.scene().objects[*object].name
                ),
                pushplan::scene::Goal::Configuration { .. } => format!(
                    "the arm ends {left:.3} rad (joint-space distance) beyond the goal configuration's tolerance"
                ),
            }
        );
    }
    println!("search: {}", solution.search.report());
    if let Some(r) = &file.robustness {
        let asked = options.robust_trials as usize;
        let required = 100.0 * r.required_rate;
        println!(
            "robust: {:.0} % of {} perturbed re-simulations reach the goal ({})",
            100.0 * r.success_rate,
            r.trials,
            if r.trials < asked {
                format!(
                    "of {asked} asked: the time limit cut the check short, so the {required:.0} % \
                     required is not confirmed; more --time checks them all"
                )
            } else if r.success_rate >= r.required_rate {
                format!("at least {required:.0} % required")
            } else {
                format!(
                    "below the {required:.0} % asked: the most robust solution found in the time; \
                     more --time may find a more robust one"
                )
            }
        );
        // The check's rate is the chosen solution's in the worlds it was chosen in.
        match &r.unseen {
            Some(u) => println!(
                "robust, in {} other perturbed worlds (not chosen in): {:.0} % reach the goal",
                u.trials,
                100.0 * u.success_rate
            ),
            None => println!(
                "robust, in other perturbed worlds: not measured (the time limit came first)"
            ),
        }
    }
    let moved: Vec<&str> = file
        .objects
        .iter()
        .zip(
            file.start.objects.iter().zip(
                &file
                    .controls
                    .last()
                    .map_or(&file.start, |c| &c.state)
                    .objects,
            ),
        )
        .filter(|(_, (a, b))| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt() > 1e-3)
        .map(|(name, _)| name.as_str())
        .collect();
    let (b, a) = (&file.metrics.before_shortcut, &file.metrics.after_shortcut);
    println!(
        "path: {} controls, {:.2} s; objects moved: {}",
        file.controls.len(),
        a.duration,
        if moved.is_empty() {
            "none".to_string()
        } else {
            moved.join(", ")
        }
    );
    // The joint-space length sums |dq| over the joints: radians only if every joint
    // turns (the planar hand's slide in metres and turn in radians).
    let revolute = (0..dof).all(|i| {
        problem.scene().robot.chain.dof_joint(i).kind == pushplan::robot::JointKind::Revolute
    });
    let manipulator = if revolute {
        format!(
            "{:.2} rad / {:.2} m of end-effector travel (before shortcutting {:.2} rad / {:.2} m)",
            a.joint_length, a.ee_length, b.joint_length, b.ee_length
        )
    } else {
        format!(
            "{:.2} m of end-effector travel (before shortcutting {:.2} m)",
            a.ee_length, b.ee_length
        )
    };
    println!(
        "manipulator path: {manipulator}; object displacement {:.3} m (before {:.3} m); {} made contact",
        a.object_displacement,
        b.object_displacement,
        match a.links_in_contact {
            1 => "1 link".to_string(),
            n => format!("{n} links"),
        }
    );
    if let Some(r) = &file.reach {
        println!(
            "then a grasp of '{}': {} waypoints",
            r.object,
            r.waypoints.len()
        );
    } else if run.grasp_after && solution.summary.exact {
        println!("then a grasp of the goal object: not found (the plan is not solved)");
    }
    println!("plan written to {}", out.display());
    Ok(if solved {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// Writes a plan file of a reach alone and says how it went.
fn write_plan(file: &PlanFile, out: &Path, solved: bool) -> Result<ExitCode, String> {
    pushplan::output::write_whole(out, file.to_json())?;
    match &file.reach {
        Some(r) => println!(
            "solved: a grasp of '{}' reached through {} waypoints",
            r.object,
            r.waypoints.len()
        ),
        None => println!("not solved: no reach of a grasp found"),
    }
    println!("plan written to {}", out.display());
    Ok(if solved {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}
