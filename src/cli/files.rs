//! The small commands: `render`, `scenes generate`, `install`.

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
