//! The small commands: `render`, `export`, `scenes generate`, `install`.

use pushplan::planning::plan_file::PlanFile;
use std::path::Path;
use std::process::ExitCode;

pub fn draw(plan_path: &Path, dir: &Path, times: &[f64]) -> Result<ExitCode, String> {
    let plan = PlanFile::read(plan_path)?;
    let files = pushplan::render::render(&plan, plan_path, dir, times)?;
    for file in [&files.snapshots, &files.timeline, &files.animation] {
        println!("wrote {}", file.display());
    }
    Ok(ExitCode::SUCCESS)
}

/// `pushplan export PLAN --format F [--out FILE]`: the plan's trajectory, once it is
/// shown to be the one its controls give in its scene.
pub fn export(
    plan_path: &Path,
    format: pushplan::planning::export::ExportFormat,
    out: Option<&Path>,
) -> Result<ExitCode, String> {
    let plan = PlanFile::read(plan_path)?;
    let scene = plan.load_scene(plan_path)?;
    plan.check_trajectory(&scene)
        .map_err(|e| format!("{}: {e}", plan_path.display()))?;
    if !plan.solved {
        eprintln!(
            "warning: {}: the plan does not reach the goal (solved: false); exporting it as it is",
            plan_path.display()
        );
    }
    let text = format.write(&plan);
    match out {
        Some(out) => {
            pushplan::output::write_whole(out, text)?;
            eprintln!(
                "wrote {} ({} samples, {})",
                out.display(),
                plan.trajectory.times.len(),
                format.name()
            );
        }
        None => {
            use std::io::Write;
            match std::io::stdout().write_all(text.as_bytes()) {
                // A reader that stopped early (`| head`) wanted no more.
                Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
                    return Err(format!("standard output: {e}"))
                }
                _ => {}
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}

pub fn generate_scenes(
    design: pushplan::scene::generate::Design,
    arm: pushplan::scene::generate::Arm,
    count: usize,
    objects: &str,
    seed: u64,
    out: &Path,
) -> Result<ExitCode, String> {
    let range = objects
        .split_once("..")
        .and_then(|(a, b)| Some((a.trim().parse().ok()?, b.trim().parse().ok()?)))
        .ok_or_else(|| format!("--objects must look like 1..7, got '{objects}'"))?;
    let files = pushplan::scene::generate::generate(design, arm, count, range, seed, out)?;
    println!("wrote {} scenes to {}", files.len(), out.display());
    Ok(ExitCode::SUCCESS)
}

/// `scenes generate --shipped --out DIR`: every shipped set into DIR/ARM/DESIGN.
pub fn generate_shipped_scenes(out: &Path) -> Result<ExitCode, String> {
    let files = pushplan::scene::generate::generate_shipped(out)?;
    println!(
        "wrote {} scenes of {} sets to {}",
        files.len(),
        pushplan::scene::generate::shipped_sets().len(),
        out.display()
    );
    Ok(ExitCode::SUCCESS)
}

pub fn install(prefix: &Path) -> Result<ExitCode, String> {
    let binary = std::env::current_exe().map_err(|e| format!("the running binary: {e}"))?;
    let written = crate::install::install(prefix, &binary)?;
    println!(
        "installed {} files into {}",
        written.len(),
        prefix.display()
    );
    Ok(ExitCode::SUCCESS)
}
