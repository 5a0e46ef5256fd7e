//! `pushplan execute`: play a plan in the 3D engine, open loop or closed loop, and report
//! what happened.

use pushplan::planner::closed_loop::{
    ClosedLoop, ClosedLoopOptions, ClosedLoopReport, ClosedLoopTrial, TiltOnset,
};
use pushplan::planner::Search;
use pushplan::planning::execute::{EngineKind, ExecuteSettings, ExecutionReport};
use pushplan::planning::plan_file::PlanFile;
use pushplan::Scene;
use std::path::Path;
use std::process::ExitCode;

/// What `execute` is asked.
pub struct ExecuteOptions<'a> {
    /// Trials; the first is unperturbed.
    pub trials: usize,
    /// Pace relative to the plan's trajectory.
    pub speed: f64,
    /// Seed of the perturbations.
    pub seed: u64,
    /// The 3D engine.
    pub engine: EngineKind,
    /// Also write the report as JSON here.
    pub json: Option<&'a Path>,
    /// Write the nominal execution's animation into this folder (open loop).
    pub render: Option<&'a Path>,
    /// Closed loop, re-planning with this search, as the flags say.
    pub closed_loop: Option<(&'static dyn Search, ClosedLoopOptions)>,
}

pub fn execute(path: &Path, options: ExecuteOptions) -> Result<ExitCode, String> {
    let ExecuteOptions {
        trials,
        speed,
        seed,
        engine,
        json,
        render,
        closed_loop,
    } = options;
    // --trials, --speed and the re-planning options are within the limits table (parsed
    // so, `cli::within`).
    // The report's and the picture's files are tried before the trials, not after them.
    if let Some(json) = json {
        pushplan::output::check_writable(json)?;
    }
    if let Some(dir) = render {
        pushplan::output::check_writable(&dir.join("execution.html"))?;
    }
    let plan = PlanFile::read(path)?;
    let scene = plan.load_scene(path)?;
    plan.check_trajectory(&scene)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let execution = ExecuteSettings {
        trials,
        speed,
        seed,
        engine,
        record: render.is_some(),
        ..ExecuteSettings::default()
    };
    let (report, success_rate) = match closed_loop {
        Some((search, flags)) => {
            if render.is_some() {
                return Err("--render draws open-loop executions only".into());
            }
            if !plan.settings.planner.yields_controls() {
                return Err(format!(
                    "{}: closed loop re-plans with the plan's planner, {}, which yields no controls",
                    path.display(),
                    plan.settings.planner.name()
                ));
            }
            let closed = ClosedLoop {
                search,
                settings: flags.settings(plan.settings.planner, plan.settings.seed),
                execution,
            };
            // One line per finished trial on stderr, the report on stdout once all are done.
            let report = closed.trials_reporting(&scene, &plan.path_controls(), |i, t| {
                eprintln!("{}", closed_loop_trial_line(i, trials, t));
            })?;
            print_closed_loop(path, &report, speed, engine);
            (serde_json::to_string_pretty(&report), report.success_rate)
        }
        None => {
            let report = pushplan::planning::execute::execute(&scene, &plan, &execution)?;
            print_execution(path, &scene, &report);
            if let Some(dir) = render {
                let page =
                    pushplan::render::render_execution(&plan, path, &report.trials[0].frames, dir)?;
                println!("animation written to {}", page.display());
            }
            (serde_json::to_string_pretty(&report), report.success_rate)
        }
    };
    if let Some(json) = json {
        let text = report.expect("reports serialise") + "\n";
        pushplan::output::write_whole(json, text)?;
    }
    Ok(if success_rate > 0.0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn print_closed_loop(path: &Path, report: &ClosedLoopReport, speed: f64, engine: EngineKind) {
    let n = report.trials.len();
    println!(
        "{}: executed {n} times closed loop in 3D ({engine}) at {speed}x speed: {} reach the goal ({:.0} %); {} tip an object; {:.1} re-plans per trial; re-planning latency median {:.3} s, 95th percentile {:.3} s, searching on {} {} (from any observation to the plan played next: median {:.4} s)",
        path.display(),
        report.trials.iter().filter(|t| t.reached).count(),
        100.0 * report.success_rate,
        report.tipped_trials,
        report.replans_per_trial,
        report.replan_latency_median,
        report.replan_latency_p95,
        report.replan_threads,
        if report.replan_threads == 1 { "thread" } else { "threads" },
        report.decision_latency_median,
    );
    for (i, t) in report.trials.iter().enumerate() {
        println!("{}", closed_loop_trial_line(i, n, t));
    }
}

/// A closed-loop trial's line: outcome, controls, re-plans, time, and why it stopped.
fn closed_loop_trial_line(i: usize, n: usize, t: &ClosedLoopTrial) -> String {
    format!(
        "  {}; {} controls played ({} cut short{}), rest kept {} times (invalid {} times{}), {}{} re-plans ({} repairs){}{}, {:.1} s searching, {:.0} s in all{}{}{}",
        trial_outcome(i, n, t.reached, t.goal_distance),
        t.controls_played,
        t.cut_short,
        match t.backoffs {
            0 => String::new(),
            b => format!(
                ", {b} retraced: a link deep in an object (control {})",
                t.backoffs_at
                    .iter()
                    .map(usize::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        },
        t.kept,
        t.invalid_rests,
        match t.invalid_rests {
            0 => String::new(),
            _ => format!(
                ": {}",
                t.invalid_rest_rules
                    .iter()
                    .map(|(rule, count)| format!("{rule} {count}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        },
        match t.mends {
            0 => String::new(),
            m => format!("{m} mends ({:.1} s mending), ", t.mend_time),
        },
        t.replans,
        t.repairs,
        match t.failed_replans {
            0 => String::new(),
            f => format!(", {f} more found nothing in time"),
        },
        match t.legs {
            0 => String::new(),
            l => format!(", {l} legs along the way"),
        },
        t.search_time,
        t.wall_time,
        match t.separations {
            0 => String::new(),
            s => format!("; {s} observations had an object inside the arm or another object"),
        },
        tilts(t),
        t.stopped
            .as_ref()
            .map(|why| format!("; stopped: {why}"))
            .unwrap_or_default(),
    )
}

/// The objects a trial tipped, and those that started to tip and were not counted tipped
/// (they rocked back, or left the table): when they began, and the link and the other
/// object the model's geometry has nearest each then (`TiltOnset`).
fn tilts(t: &ClosedLoopTrial) -> String {
    let onset = |object: &str| t.tilt_onsets.iter().find(|o| o.object == object);
    let touch = |o: &TiltOnset| {
        let link = o.touching.first().map(|touch| {
            format!(
                ", {} at it {:.3} m above the table",
                touch.link, touch.height
            )
        });
        let neighbour = o
            .neighbours
            .first()
            .map(|n| format!(", {} {:.1} mm from it", n.object, 1e3 * n.gap));
        link.unwrap_or_default() + &neighbour.unwrap_or_default()
    };
    let tipped: Vec<String> = t
        .tipped
        .iter()
        .zip(&t.tipped_during)
        .map(|(object, control)| match onset(object) {
            Some(o) if o.control != *control => format!(
                "{object} (control {control}; tilting from control {}{})",
                o.control,
                touch(o)
            ),
            Some(o) => format!("{object} (control {control}{})", touch(o)),
            None => format!("{object} (control {control})"),
        })
        .collect();
    let stood: Vec<String> = t
        .tilt_onsets
        .iter()
        .filter(|o| !t.tipped.contains(&o.object))
        .map(|o| format!("{} (control {}{})", o.object, o.control, touch(o)))
        .collect();
    let mut said = String::new();
    if !tipped.is_empty() {
        said += &format!("; tipped: {}", tipped.join(", "));
    }
    if !stood.is_empty() {
        said += &format!("; started to tip, not tipped: {}", stood.join(", "));
    }
    said
}

fn print_execution(path: &Path, scene: &Scene, report: &ExecutionReport) {
    let n = report.trials.len();
    println!(
        "{}: executed {n} times in 3D ({}) at {}x speed: {} reach the goal ({:.0} %); {} tip an object; {} push one off the table; {} bring two objects into contact",
        path.display(),
        report.engine,
        report.speed,
        report.trials.iter().filter(|t| t.reached).count(),
        100.0 * report.success_rate,
        report.tipped_trials,
        report.fell_off_trials,
        report.object_contact_trials,
    );
    for (i, t) in report.trials.iter().enumerate() {
        let errors: Vec<String> = scene
            .objects
            .iter()
            .zip(&t.final_errors)
            .map(|(o, e)| format!("{} {:.0} mm", o.name, 1e3 * e))
            .collect();
        let divergence = match &t.first_divergence {
            None => "none".to_string(),
            Some(pushplan::planning::execute::Divergence::Tipped { object, time }) => {
                format!("{object} tips at {time:.2} s")
            }
            Some(pushplan::planning::execute::Divergence::ObjectContact {
                object_a,
                object_b,
                time,
            }) => format!("{object_a} touches {object_b} at {time:.2} s"),
            Some(pushplan::planning::execute::Divergence::Drift {
                object,
                time,
                error,
            }) => format!(
                "{object} {:.0} mm off its predicted path at {time:.2} s",
                1e3 * error
            ),
        };
        let mut upsets = String::new();
        if !t.tipped.is_empty() {
            upsets += &format!("; tipped: {}", t.tipped.join(", "));
        }
        if !t.fell_off.is_empty() {
            upsets += &format!("; off the table: {}", t.fell_off.join(", "));
        }
        println!(
            "  {}; final errors: {}{upsets}; first divergence: {divergence}",
            trial_outcome(i, n, t.reached, t.goal_distance),
            errors.join(", "),
        );
    }
}

/// "trial I (nominal): reached, goal object D mm inside the disc's edge" of trial `i` of `n`.
fn trial_outcome(i: usize, n: usize, reached: bool, goal_distance: f64) -> String {
    format!(
        "trial {i}{}: {}, goal object {:.0} mm {} the disc's edge",
        if i == 0 && n > 1 { " (nominal)" } else { "" },
        if reached { "reached" } else { "missed" },
        1e3 * goal_distance.abs(),
        if goal_distance <= 0.0 {
            "inside"
        } else {
            "outside"
        },
    )
}
