//! The benchmark grid: every (scene, planner, run) cell of an experiment, and the share
//! of it a shard runs. Each cell runs in a process of its own, seeded from the grid's seed
//! and its run index only, so a cell is the same run whichever shard or machine runs it.

use crate::planning::{PlannerKind, RunSettings};
use crate::scene::PlannerParams;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The file in a benchmark folder that says which grid and which shard it holds.
pub const MANIFEST: &str = "grid.json";

/// What a benchmark runs: every planner on every scene, `runs` times.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Grid {
    /// Scene files, as given.
    pub scenes: Vec<PathBuf>,
    /// Planners, in the order their runs are made.
    pub planners: Vec<PlannerKind>,
    /// Runs of each planner on each scene.
    pub runs: u32,
    /// Time limit per run (s).
    pub time: f64,
    /// Shortcutting budget measured after each solved run (s of work).
    pub shortcut: f64,
    /// Every run's seeds derive from it and the run's index.
    pub seed: u64,
    /// Every planner's first restart budget (propagation steps; 0: never) instead of its
    /// own (`PlannerKind::restart_steps`). Absent in grids from before restarts: the
    /// planners' own.
    #[serde(default)]
    pub restart: Option<u64>,
    /// Push KPIECE's patience before it falls back to PC RRT (propagation steps; 0:
    /// never) instead of its own (`PlannerKind::fallback_steps`). Absent in grids from
    /// before the fallback: its own.
    #[serde(default)]
    pub fallback: Option<u64>,
    /// Threads of each run of the planners whose threads share one search
    /// ([`PlannerKind::shares_one_search`]: push_kpiece, kpiece), as `plan --threads`; the
    /// others run on one. Absent in grids from before: one.
    #[serde(default = "one_thread")]
    pub threads: u32,
}

fn one_thread() -> u32 {
    1
}

/// One run of one planner on one scene (indices into the grid's lists).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Cell {
    /// Index into the grid's scenes.
    pub scene: usize,
    /// Index into the grid's planners.
    pub planner: usize,
    /// The run's index (from 0): with the grid's seed, it seeds the run.
    pub run: u32,
}

/// Shard `index` of `count` (1-based, as Slurm's array task ids usually are).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shard {
    /// Which shard (from 1).
    pub index: usize,
    /// How many shards the grid is cut into.
    pub count: usize,
}

impl Shard {
    /// The whole grid.
    pub const ALL: Shard = Shard { index: 1, count: 1 };
}

impl std::str::FromStr for Shard {
    type Err = String;

    /// `K/N` with 1 <= K <= N.
    fn from_str(text: &str) -> Result<Shard, String> {
        let parsed = text
            .split_once('/')
            .and_then(|(k, n)| Some((k.trim().parse().ok()?, n.trim().parse().ok()?)));
        match parsed {
            Some((index, count)) if count >= 1 && (1..=count).contains(&index) => {
                Ok(Shard { index, count })
            }
            _ => Err(format!(
                "a shard is K/N with 1 <= K <= N (e.g. 2/8), got '{text}'"
            )),
        }
    }
}

impl Grid {
    /// Every cell, scene by scene, planner by planner, run by run.
    pub fn cells(&self) -> impl Iterator<Item = Cell> + '_ {
        (0..self.scenes.len()).flat_map(move |scene| {
            (0..self.planners.len()).flat_map(move |planner| {
                (0..self.runs).map(move |run| Cell {
                    scene,
                    planner,
                    run,
                })
            })
        })
    }

    /// The cells of `shard`: every `count`-th cell, from the `index`-th on, so that each
    /// shard gets a share of every scene and planner.
    pub fn shard(&self, shard: Shard) -> Vec<Cell> {
        self.cells()
            .enumerate()
            .filter(|(i, _)| i % shard.count == shard.index - 1)
            .map(|(_, c)| c)
            .collect()
    }

    /// The threads of each run of `planner`: the grid's where its threads share one
    /// search, else one.
    pub fn threads_of(&self, planner: PlannerKind) -> u32 {
        if planner.shares_one_search() {
            self.threads
        } else {
            1
        }
    }

    /// The settings of `cell`'s run, for its scene's `planner:` parameters: the grid's
    /// time limit, shortcut budget, seed (the run's own seeds derive from it and the run's
    /// index) and threads ([`Grid::threads_of`]), its restart budget instead of the
    /// planner's own, and its patience for push_kpiece (the others never fall back).
    pub fn run_settings(&self, cell: Cell, params: &PlannerParams) -> RunSettings {
        let planner = self.planners[cell.planner];
        let own = RunSettings::of_scene(planner, params);
        RunSettings {
            time_limit: self.time,
            seed: self.seed,
            shortcut: self.shortcut,
            threads: self.threads_of(planner),
            restart_steps: self.restart.unwrap_or(own.restart_steps),
            fallback_steps: match own.fallback_steps {
                0 => 0,
                patience => self.fallback.unwrap_or(patience),
            },
            ..own
        }
    }

    /// `cell` if it is a cell of this grid, else why not.
    pub fn checked(&self, cell: Cell) -> Result<Cell, String> {
        if cell.scene < self.scenes.len()
            && cell.planner < self.planners.len()
            && cell.run < self.runs
        {
            Ok(cell)
        } else {
            Err(format!(
                "cell (scene {}, planner {}, run {}) is outside the grid of {} scenes, {} planners and {} runs",
                cell.scene,
                cell.planner,
                cell.run,
                self.scenes.len(),
                self.planners.len(),
                self.runs
            ))
        }
    }

    /// The log of a scene's merged runs in the output folder.
    pub fn scene_log(&self, out: &Path, scene: usize) -> PathBuf {
        out.join(format!("{scene:03}_{}.log", self.scene_stem(scene)))
    }

    /// The log of one cell, under `out/cells/`.
    pub fn cell_log(&self, out: &Path, cell: Cell) -> PathBuf {
        out.join("cells")
            .join(format!("{:03}_{}", cell.scene, self.scene_stem(cell.scene)))
            .join(format!(
                "{}_{:04}.log",
                self.planners[cell.planner].name(),
                cell.run
            ))
    }

    fn scene_stem(&self, scene: usize) -> String {
        self.scenes[scene]
            .file_stem()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned()
    }
}

/// A benchmark folder's manifest: the grid and the shard whose cells it holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// The whole grid.
    pub grid: Grid,
    /// The shard this folder holds.
    pub shard: Shard,
}

impl Manifest {
    /// Writes the manifest into `dir`; an error names the file.
    pub fn write(&self, dir: &Path) -> Result<(), String> {
        let path = dir.join(MANIFEST);
        let text = serde_json::to_string_pretty(self).expect("a manifest serialises") + "\n";
        crate::output::write_whole(&path, text)
    }

    /// Reads the manifest of `dir`; an error names the file.
    pub fn read(dir: &Path) -> Result<Manifest, String> {
        let path = dir.join(MANIFEST);
        let text = std::fs::read_to_string(&path).map_err(|e| {
            format!(
                "{}: {e} (not a folder written by `pushplan bench`)",
                path.display()
            )
        })?;
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
    }
}
