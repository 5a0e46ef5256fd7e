//! `pushplan check`: re-simulate a plan file, optionally under parameter noise.

use pushplan::input::MAX_PLAN_BYTES;
use pushplan::planner::remake::{remake, Remade};
use pushplan::planner::Search;
use pushplan::planning::plan_file::PlanFile;
use pushplan::planning::robustness::Noise;
use pushplan::planning::Problem;
use pushplan::scene::Scene;
use std::path::Path;
use std::process::ExitCode;

/// Does the file say it is a `pick-place` path (its `format`)? Read as every input is
/// (a regular file of bounded size); what cannot be read is left to the plan reader's
/// error.
fn is_pick_place_file(path: &Path) -> bool {
    #[derive(serde::Deserialize)]
    struct Format {
        format: Option<String>,
    }
    pushplan::input::read_text(path, MAX_PLAN_BYTES)
        .ok()
        .and_then(|text| serde_json::from_str::<Format>(&text).ok())
        .and_then(|f| f.format)
        .is_some_and(|f| f == super::PICK_PLACE_FORMAT)
}

/// Is the file a scene (YAML, by its extension) rather than a plan?
fn is_scene_file(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("yaml") || e.eq_ignore_ascii_case("yml"))
}

/// `pushplan check SCENE.yaml`: loads the scene (every rule, the start's validity) and
/// prints the scene check's warnings. Exit 0 without warnings, 1 with some.
fn check_scene(path: &Path) -> Result<ExitCode, String> {
    let scene = Scene::load(path).map_err(|e| e.to_string())?;
    let warnings = pushplan::scene::check::check(&scene);
    println!(
        "{}: loads; the start is valid; {} object(s); {} warning(s)",
        path.display(),
        scene.objects.len(),
        warnings.len()
    );
    for warning in &warnings {
        println!("  warning: {warning}");
    }
    let blocking = warnings.iter().filter(|w| w.blocks()).count();
    println!(
        "{}",
        match (warnings.len(), blocking) {
            (0, _) => "scene OK".to_string(),
            (_, 0) => "scene OK, with warnings: it can be planned, perhaps slowly".to_string(),
            (_, n) => format!("scene CANNOT WORK as written: {n} warning(s) say a plan is unlikely to reach the goal"),
        }
    );
    Ok(match warnings.is_empty() {
        true => ExitCode::SUCCESS,
        false => ExitCode::FAILURE,
    })
}

/// `pushplan check PLAN`: re-simulates the plan (and with `noise`, perturbed worlds with
/// `seed`), then, unless `path_only`, makes it again with `search` from what it records of
/// how it was made. Exit 0 for "plan OK" (or "path OK" with `path_only`), 1 otherwise.
pub fn check(
    search: &dyn Search,
    path: &Path,
    noise: usize,
    seed: u64,
    path_only: bool,
) -> Result<ExitCode, String> {
    if is_scene_file(path) {
        if noise > 0 {
            return Err("--noise applies to plans, not to scene files".into());
        }
        return check_scene(path);
    }
    if is_pick_place_file(path) {
        if noise > 0 {
            return Err("--noise applies to pushing plans, not to pick-and-place paths".into());
        }
        return super::check_pick_place(path);
    }
    let plan = PlanFile::read(path)?;
    let report = plan.check(path)?;
    if noise > 0 {
        let scene = plan.load_scene(path)?;
        let r = Problem::new(scene, plan.settings.planner).robustness(
            &plan.path_controls(),
            &Noise::default(),
            noise,
            seed,
        );
        println!(
            "perturbed re-simulations: {} of {noise} reach the goal ({:.0} %); goal object's final centre {:.1} mm from the planned one on average (largest {:.1} mm), spread x {:.1} mm, y {:.1} mm, yaw {:.3} rad",
            r.trials.iter().filter(|t| t.reached).count(),
            100.0 * r.success_rate,
            1e3 * r.mean_deviation,
            1e3 * r.max_deviation,
            1e3 * r.std_xy_yaw[0],
            1e3 * r.std_xy_yaw[1],
            r.std_xy_yaw[2],
        );
        for (i, t) in r.trials.iter().enumerate().filter(|(_, t)| !t.reached) {
            match &t.failure {
                Some(why) => println!("  trial {i}: {why}"),
                None => println!(
                    "  trial {i}: the goal object ends {:.1} mm outside the disc",
                    1e3 * t.goal_distance
                ),
            }
        }
    }
    println!(
        "{}: {} controls; every state valid: {}; states reproduced: {}; goal reached: {}",
        path.display(),
        plan.controls.len(),
        yes(report.all_valid),
        yes(report.states_match),
        yes(report.goal_reached)
    );
    if let Some(reach) = &plan.reach {
        println!(
            "  then a reach of a grasp of '{}' through {} waypoints{}",
            reach.object,
            reach.waypoints.len(),
            if report.reach_valid {
                ", every segment valid, ending in a grasp region"
            } else {
                ""
            }
        );
    }
    for problem in &report.problems {
        println!("  {problem}");
    }
    let made = format!(
        "made by {} with seed {}, k {}, {:?} s, {} thread(s){}",
        plan.settings.planner.name(),
        plan.settings.seed,
        plan.settings.k,
        plan.settings.time_limit,
        plan.settings.threads,
        plan.robustness.as_ref().map_or(String::new(), |r| format!(
            ", {:.0} % of {} perturbed re-simulations required, {} perturbed worlds carried",
            100.0 * r.required_rate,
            r.trials,
            r.particles
        )),
    );
    if !report.passed() {
        println!("plan FAILED");
        return Ok(ExitCode::FAILURE);
    }
    if path_only {
        // What a re-simulation cannot confirm is said, not passed over.
        println!("  as recorded, not made again (--path-only): {made}");
        println!("path OK");
        return Ok(ExitCode::SUCCESS);
    }
    let started = std::time::Instant::now();
    let remade = remake(search, &plan, path)?;
    let took = started.elapsed().as_secs_f64();
    let (verdict, confirmed) = match remade {
        Remade::Same => {
            println!("  made again ({made}) in {took:.2} s: the same plan, byte for byte");
            ("plan OK", true)
        }
        Remade::Differs(field) => {
            println!(
                "  made again ({made}) in {took:.2} s: {field}: differs from the plan made again \
                 (the file was changed, or made by another version of pushplan)"
            );
            ("plan FAILED", false)
        }
        Remade::Cannot(why) => {
            println!("  not made again: {why}; how it was made ({made}) is not confirmed");
            ("path OK, plan not confirmed", false)
        }
    };
    println!("{verdict}");
    Ok(match confirmed {
        true => ExitCode::SUCCESS,
        false => ExitCode::FAILURE,
    })
}

fn yes(b: bool) -> &'static str {
    if b {
        "yes"
    } else {
        "no"
    }
}
