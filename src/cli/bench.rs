//! `pushplan bench`, `pushplan bench merge` and `pushplan plots`: the benchmark grid run
//! a cell per process (a shard of it, if asked), merged into a Planner Arena database, and
//! the paper's plots drawn from the logs.

use pushplan::benchmark::grid::{Cell, Grid, Manifest, Shard};
use pushplan::benchmark::run::{merge, run_shard};
use pushplan::planner::Search;
use pushplan::Scene;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Runs `shard` of `grid` into `out`, `jobs` processes at a time. The whole grid is merged
/// at once (`out/results.db`, the plots); a shard waits for `bench merge`. With `resume`,
/// the runs whose log is already in `out` (a benchmark of the same grid and shard) are kept.
pub fn bench(
    grid: &Grid,
    shard: Shard,
    out: &Path,
    jobs: Option<usize>,
    resume: bool,
) -> Result<ExitCode, String> {
    for scene in &grid.scenes {
        Scene::load(scene).map_err(|e| e.to_string())?; // bad scenes fail before anything runs
    }
    // --time, --runs, --threads and --shortcut are within the limits table (`cli::within`).
    let jobs = jobs
        .unwrap_or_else(|| (super::cores() / grid.threads) as usize)
        .max(1);
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let failed = run_shard(&exe, grid, shard, out, jobs, resume)?;
    if shard != Shard::ALL {
        println!(
            "shard {}/{} written to {}; merge every shard's folder with `pushplan bench merge DIR... --out DIR`",
            shard.index,
            shard.count,
            out.display()
        );
    } else {
        merge_into(&[out.to_path_buf()], out)?;
    }
    Ok(if failed.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// `bench-scene`: one cell of the grid whose manifest is in `out`, run in a process of
/// its own by [`bench`] with OMPL's benchmark tooling, its log written to `log`.
pub fn bench_scene(
    search: &dyn Search,
    out: &Path,
    cell: Cell,
    log: &Path,
) -> Result<ExitCode, String> {
    let grid = Manifest::read(out)?.grid;
    let cell = grid.checked(cell)?;
    let scene = &grid.scenes[cell.scene];
    let params = Scene::load(scene).map_err(|e| e.to_string())?.planner;
    search
        .benchmark(scene, &grid.run_settings(cell, &params), cell.run, log)
        .map(|_| ExitCode::SUCCESS)
}

/// `bench merge`: the shards in `dirs` into `out` (logs, database, plots).
pub fn bench_merge(dirs: &[PathBuf], out: &Path) -> Result<ExitCode, String> {
    let complete = merge_into(dirs, out)?;
    Ok(if complete {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// Merges and draws; false if runs are missing.
fn merge_into(dirs: &[PathBuf], out: &Path) -> Result<bool, String> {
    let merged = merge(dirs, out)?;
    for run in &merged.missing {
        eprintln!("missing (its process failed): {run}");
    }
    println!(
        "{} logs merged into {}",
        merged.scene_logs.len(),
        merged.database.display()
    );
    plots(out)?;
    Ok(merged.missing.is_empty())
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
        .map(|p| pushplan::benchmark::read_log(p))
        .collect::<Result<Vec<_>, _>>()?;
    for file in pushplan::benchmark::plots::write_plots(&logs, &dir.join("plots"))? {
        println!("wrote {}", file.display());
    }
    Ok(ExitCode::SUCCESS)
}
