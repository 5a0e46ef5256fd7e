//! Running a benchmark: the cells of a shard, one `bench-scene` process each, a few at a
//! time; then merging shards into one log per scene, a Planner Arena database
//! (`ompl_benchmark_statistics`) and the plots.

use super::grid::{Cell, Grid, Manifest, Shard};
use super::merge::merge_scene;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// Runs the cells of `shard` of `grid` into `out/cells/` with `exe bench-scene` (the
/// `pushplan` binary), `jobs` at a time, and writes `out`'s manifest. With `resume`, `out`
/// must hold the same grid and shard, and the cells whose log is there are not run again.
/// Returns the cells whose process failed.
pub fn run_shard(
    exe: &Path,
    grid: &Grid,
    shard: Shard,
    out: &Path,
    jobs: usize,
    resume: bool,
) -> Result<Vec<Cell>, String> {
    let manifest = Manifest {
        grid: grid.clone(),
        shard,
    };
    if resume {
        let found = Manifest::read(out)?;
        if found != manifest {
            return Err(format!(
                "{} holds another benchmark or shard (scenes, planners, runs, time, shortcut, seed, restart, fallback, threads or shard differ): --resume goes on with the same one",
                out.display()
            ));
        }
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    manifest.write(out)?;
    let all = grid.shard(shard);
    // A log appears only once its run has ended (it is written under another name and
    // renamed), so a log found here is a whole run.
    let cells: Vec<Cell> = all
        .iter()
        .copied()
        .filter(|&cell| !(resume && grid.cell_log(out, cell).is_file()))
        .collect();
    eprintln!(
        "benchmarking {} of {} runs ({} scenes x {} planners x {} runs{}{}), up to {} s each, {jobs} at a time",
        cells.len(),
        grid.cells().count(),
        grid.scenes.len(),
        grid.planners.len(),
        grid.runs,
        if shard == Shard::ALL {
            String::new()
        } else {
            format!("; shard {}/{}", shard.index, shard.count)
        },
        if resume {
            format!("; {} kept from before", all.len() - cells.len())
        } else {
            String::new()
        },
        grid.time
    );
    let started = Instant::now();
    let mut pending: Vec<Cell> = cells.iter().rev().copied().collect();
    let mut running: Vec<(Cell, Child, Instant)> = Vec::new();
    let (mut done, mut failed) = (0, Vec::new());
    while !pending.is_empty() || !running.is_empty() {
        while running.len() < jobs.max(1) {
            let Some(cell) = pending.pop() else { break };
            running.push((cell, spawn_cell(exe, grid, cell, out)?, Instant::now()));
        }
        std::thread::sleep(Duration::from_millis(20));
        let mut k = 0;
        while k < running.len() {
            let Some(status) = running[k].1.try_wait().map_err(|e| e.to_string())? else {
                k += 1;
                continue;
            };
            let (cell, _, since) = running.remove(k);
            done += 1;
            let log = grid.cell_log(out, cell);
            let verdict = if status.success() {
                std::fs::rename(partial_log(&log), &log)
                    .map_err(|e| format!("{}: {e}", log.display()))?;
                "done".to_string()
            } else {
                failed.push(cell);
                let messages =
                    std::fs::read_to_string(log.with_extension("err")).unwrap_or_default();
                format!("FAILED: {}", messages.trim())
            };
            let spent = started.elapsed().as_secs_f64();
            eprintln!(
                "[{done}/{}] {} {} run {} {verdict} ({:.1} s, {spent:.0} s in all{})",
                cells.len(),
                grid.scenes[cell.scene].display(),
                grid.planners[cell.planner].name(),
                cell.run,
                since.elapsed().as_secs_f64(),
                time_left(spent, done, cells.len())
            );
        }
    }
    Ok(failed)
}

fn spawn_cell(exe: &Path, grid: &Grid, cell: Cell, out: &Path) -> Result<Child, String> {
    let log = grid.cell_log(out, cell);
    let folder = log.parent().expect("a cell log is in a folder");
    std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    // The child's messages go to a file next to its log: a pipe nobody reads until the
    // child ends would block a child that writes much.
    let messages = std::fs::File::create(log.with_extension("err"))
        .map_err(|e| format!("{}: {e}", log.with_extension("err").display()))?;
    Command::new(exe)
        .arg("bench-scene")
        // The cell's settings are the grid's, read from the manifest in `out`.
        .arg(out)
        .args(["--scene", &cell.scene.to_string()])
        .args(["--planner", &cell.planner.to_string()])
        .args(["--run", &cell.run.to_string()])
        .arg("--log")
        .arg(partial_log(&log))
        .stdout(Stdio::null())
        .stderr(messages)
        .spawn()
        .map_err(|e| format!("cannot start a benchmark process: {e}"))
}

/// `", about N min left"` (or s) at the pace so far (`spent` seconds for `done` of `all` runs),
/// or nothing once all are done.
fn time_left(spent: f64, done: usize, all: usize) -> String {
    if done == 0 || done >= all {
        return String::new();
    }
    let left = spent / done as f64 * (all - done) as f64;
    if left < 90.0 {
        format!(", about {:.0} s left", left.ceil())
    } else {
        format!(", about {:.0} min left", (left / 60.0).round())
    }
}

/// Where a run writes its log until it has ended.
fn partial_log(log: &Path) -> PathBuf {
    log.with_extension("log.partial")
}

/// What merging found.
#[derive(Clone, Debug, PartialEq)]
pub struct Merged {
    /// The database `ompl_benchmark_statistics` wrote (`results.db`).
    pub database: PathBuf,
    /// The merged OMPL log of each scene.
    pub scene_logs: Vec<PathBuf>,
    /// Cells with no log (their process failed), as `scene planner run`.
    pub missing: Vec<String>,
}

/// Merges benchmark folders (the shards of one grid, or one unsharded folder) into `out`:
/// one log per scene (`NNN_scene.log`), `results.db`. Every folder must hold the same
/// grid and together every shard of it, each once.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<Merged, String> {
    let manifests: Vec<Manifest> = dirs
        .iter()
        .map(|d| Manifest::read(d))
        .collect::<Result<_, _>>()?;
    let first = manifests.first().ok_or("no benchmark folders to merge")?;
    let grid = &first.grid;
    let count = first.shard.count;
    let mut by_shard: HashMap<usize, &Path> = HashMap::new();
    for (dir, m) in dirs.iter().zip(&manifests) {
        if &m.grid != grid {
            return Err(format!(
                "{} holds another benchmark than {} (scenes, planners, runs, time, shortcut or seed differ)",
                dir.display(),
                dirs[0].display()
            ));
        }
        if m.shard.count != count {
            return Err(format!(
                "{} is shard {}/{}, {} is of {count} shards",
                dir.display(),
                m.shard.index,
                m.shard.count,
                dirs[0].display()
            ));
        }
        if let Some(other) = by_shard.insert(m.shard.index, dir) {
            return Err(format!(
                "{} and {} are the same shard {}/{count}",
                other.display(),
                dir.display(),
                m.shard.index
            ));
        }
    }
    if let Some(k) = (1..=count).find(|k| !by_shard.contains_key(k)) {
        return Err(format!("shard {k}/{count} is missing"));
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    remove_scene_logs(out)?;
    let mut missing = Vec::new();
    let mut scene_logs = Vec::new();
    for scene in 0..grid.scenes.len() {
        let mut planners: Vec<Vec<PathBuf>> = vec![Vec::new(); grid.planners.len()];
        for (i, cell) in grid.cells().enumerate().filter(|(_, c)| c.scene == scene) {
            let log = grid.cell_log(by_shard[&(i % count + 1)], cell);
            if log.is_file() {
                planners[cell.planner].push(log);
            } else {
                missing.push(format!(
                    "{} {} run {}",
                    grid.scenes[scene].display(),
                    grid.planners[cell.planner].name(),
                    cell.run
                ));
            }
        }
        planners.retain(|p| !p.is_empty());
        if planners.is_empty() {
            continue;
        }
        let groups: Vec<Vec<&Path>> = planners
            .iter()
            .map(|p| p.iter().map(PathBuf::as_path).collect())
            .collect();
        let text = merge_scene(&groups, grid.seed, grid.runs)?;
        let path = grid.scene_log(out, scene);
        crate::output::write_whole(&path, text)?;
        scene_logs.push(path);
    }
    // A new database, not added to the old one, which stays until the new one is whole.
    let database = out.join("results.db");
    crate::output::write_whole_with(&database, |temporary| {
        let status = Command::new("ompl_benchmark_statistics")
            .args(&scene_logs)
            .arg("-d")
            .arg(temporary)
            .stdout(Stdio::null())
            .status()
            .map_err(|e| {
                std::io::Error::other(format!(
                    "cannot run ompl_benchmark_statistics ({e}): install ompl-demos \
                     (bash .ci/install-packages)"
                ))
            })?;
        match status.success() {
            true => Ok(()),
            false => Err(std::io::Error::other("ompl_benchmark_statistics failed")),
        }
    })?;
    Ok(Merged {
        database,
        scene_logs,
        missing,
    })
}

/// Removes the scene logs of an earlier merge, so that the plots, which read every log of
/// the folder, show this benchmark only.
fn remove_scene_logs(dir: &Path) -> Result<(), String> {
    let entries = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for path in entries.filter_map(|e| e.ok().map(|e| e.path())) {
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        let ours = name.len() > 4
            && name.as_bytes()[..3].iter().all(u8::is_ascii_digit)
            && name.as_bytes()[3] == b'_'
            && name.ends_with(".log");
        if ours {
            std::fs::remove_file(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        }
    }
    Ok(())
}
