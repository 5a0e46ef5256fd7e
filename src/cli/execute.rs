//! `pushplan execute`: play a plan in the 3D engine and report what happened.

use pushplan::planning::execute::{ExecuteSettings, ExecutionReport};
use pushplan::planning::plan_file::PlanFile;
use pushplan::Scene;
use std::path::Path;
use std::process::ExitCode;

pub fn execute(
    path: &Path,
    trials: usize,
    speed: f64,
    seed: u64,
    json: Option<&Path>,
    render: Option<&Path>,
) -> Result<ExitCode, String> {
    if !(speed.is_finite() && speed > 0.0) {
        return Err(format!("--speed: must be positive and finite, got {speed}"));
    }
    if trials == 0 {
        return Err("--trials: must be at least 1".into());
    }
    let plan = PlanFile::read(path)?;
    let scene = plan.load_scene(path)?;
    plan.check_trajectory(&scene)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let settings = ExecuteSettings {
        trials,
        speed,
        seed,
        record: render.is_some(),
        ..ExecuteSettings::default()
    };
    let report = pushplan::planning::execute::execute(&scene, &plan, &settings)?;
    print_execution(path, &scene, &report);
    if let Some(dir) = render {
        let page = pushplan::render::render_execution(&plan, path, &report.trials[0].frames, dir)?;
        println!("animation written to {}", page.display());
    }
    if let Some(json) = json {
        let text = serde_json::to_string_pretty(&report).expect("reports serialise") + "\n";
        std::fs::write(json, text).map_err(|e| format!("{}: {e}", json.display()))?;
    }
    Ok(if report.success_rate > 0.0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn print_execution(path: &Path, scene: &Scene, report: &ExecutionReport) {
    let n = report.trials.len();
    println!(
        "{}: executed {n} times in 3D (rapier) at {}x speed: {} reach the goal ({:.0} %); {} tip an object; {} push one off the table; {} bring two objects into contact",
        path.display(),
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
            "  trial {i}{}: {}, goal object {:.0} mm {} the disc's edge; final errors: {}{upsets}; first divergence: {divergence}",
            if i == 0 && n > 1 { " (nominal)" } else { "" },
            if t.reached { "reached" } else { "missed" },
            1e3 * t.goal_distance.abs(),
            if t.goal_distance <= 0.0 { "inside" } else { "outside" },
            errors.join(", "),
        );
    }
}
