//! `pushplan bench` and `pushplan plots`: one `bench-scene` process per scene, a few at a
//! time, their OMPL logs merged into a database by `ompl_benchmark_statistics`, and the
//! paper's plots drawn from the logs.

use crate::planner::PlannerKind;
use crate::Scene;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// What every scene of a benchmark runs.
pub struct BenchSettings {
    pub planners: Vec<PlannerKind>,
    pub runs: u32,
    pub time: f64,
    pub shortcut: f64,
    pub seed: u64,
}

fn planner_list(planners: &[PlannerKind]) -> String {
    planners
        .iter()
        .map(|p| p.name())
        .collect::<Vec<_>>()
        .join(",")
}

/// Runs one `bench-scene` process per scene, `jobs` at a time, then merges the logs.
pub fn bench(
    scenes: &[PathBuf],
    settings: &BenchSettings,
    out: &Path,
    jobs: Option<usize>,
) -> Result<ExitCode, String> {
    if !(settings.time.is_finite() && settings.time > 0.0) || settings.runs == 0 {
        return Err("--time must be positive and --runs at least 1".into());
    }
    for scene in scenes {
        Scene::load(scene).map_err(|e| e.to_string())?; // bad scenes fail before anything runs
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let jobs = jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .max(1);
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let logs: Vec<PathBuf> = scenes
        .iter()
        .enumerate()
        .map(|(i, s)| {
            out.join(format!(
                "{i:03}_{}.log",
                s.file_stem().unwrap_or_default().to_string_lossy()
            ))
        })
        .collect();
    eprintln!(
        "benchmarking {} scenes x {} planners x {} runs, up to {} s each, {jobs} at a time",
        scenes.len(),
        settings.planners.len(),
        settings.runs,
        settings.time
    );
    let started = std::time::Instant::now();
    let mut pending: Vec<usize> = (0..scenes.len()).rev().collect();
    let mut running: Vec<(usize, std::process::Child, std::time::Instant)> = Vec::new();
    let (mut done, mut failed) = (0, Vec::new());
    while !pending.is_empty() || !running.is_empty() {
        while running.len() < jobs {
            let Some(i) = pending.pop() else { break };
            // The child's messages go to a file next to its log: a pipe nobody reads
            // until the child ends would block a child that writes much.
            let messages = std::fs::File::create(logs[i].with_extension("err"))
                .map_err(|e| format!("{}: {e}", logs[i].with_extension("err").display()))?;
            let child = std::process::Command::new(&exe)
                .arg("bench-scene")
                .arg(&scenes[i])
                .args(["--planners", &planner_list(&settings.planners)])
                .args([
                    "--runs",
                    &settings.runs.to_string(),
                    "--time",
                    &settings.time.to_string(),
                ])
                .args([
                    "--shortcut",
                    &settings.shortcut.to_string(),
                    "--seed",
                    &settings.seed.to_string(),
                ])
                .arg("--log")
                .arg(&logs[i])
                .stdout(std::process::Stdio::null())
                .stderr(messages)
                .spawn()
                .map_err(|e| format!("cannot start a benchmark process: {e}"))?;
            running.push((i, child, std::time::Instant::now()));
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
        let mut k = 0;
        while k < running.len() {
            if let Some(status) = running[k].1.try_wait().map_err(|e| e.to_string())? {
                let (i, _, since) = running.remove(k);
                done += 1;
                let stderr =
                    std::fs::read_to_string(logs[i].with_extension("err")).unwrap_or_default();
                let verdict = if status.success() {
                    "done".to_string()
                } else {
                    format!("FAILED: {}", stderr.trim())
                };
                eprintln!(
                    "[{done}/{}] {} {verdict} ({:.0} s, {:.0} s in all)",
                    scenes.len(),
                    scenes[i].display(),
                    since.elapsed().as_secs_f64(),
                    started.elapsed().as_secs_f64()
                );
                if !status.success() {
                    failed.push(i);
                }
            } else {
                k += 1;
            }
        }
    }
    let merged: Vec<&PathBuf> = logs
        .iter()
        .enumerate()
        .filter(|(i, l)| !failed.contains(i) && l.is_file())
        .map(|(_, l)| l)
        .collect();
    let db = out.join("results.db");
    let _ = std::fs::remove_file(&db);
    let status = std::process::Command::new("ompl_benchmark_statistics")
        .args(&merged)
        .arg("-d")
        .arg(&db)
        .stdout(std::process::Stdio::null())
        .status()
        .map_err(|e| format!("cannot run ompl_benchmark_statistics ({e}): install ompl-demos (bash .ci/install-packages)"))?;
    if !status.success() {
        return Err("ompl_benchmark_statistics failed".into());
    }
    println!("{} logs merged into {}", merged.len(), db.display());
    plots(out)?;
    Ok(if failed.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

pub fn plots(dir: &Path) -> Result<ExitCode, String> {
    let mut logs: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "log"))
        .collect();
    logs.sort();
    if logs.is_empty() {
        return Err(format!("{}: no OMPL benchmark logs (*.log)", dir.display()));
    }
    let logs = logs
        .iter()
        .map(|p| crate::benchmark::read_log(p))
        .collect::<Result<Vec<_>, _>>()?;
    for file in crate::benchmark::plots::write_plots(&logs, &dir.join("plots"))? {
        println!("wrote {}", file.display());
    }
    Ok(ExitCode::SUCCESS)
}
