//! Reading OMPL benchmark logs (the files `ompl::tools::Benchmark` writes and
//! `ompl_benchmark_statistics` merges), and drawing the paper's plots from them.

pub mod grid;
pub mod merge;
pub mod plots;
pub mod run;

use std::path::Path;

/// One planner's runs on one experiment (scene).
#[derive(Clone, Debug, PartialEq)]
pub struct PlannerRuns {
    /// OMPL's name, e.g. `control_PCRRT`.
    pub name: String,
    /// Run property names (without their SQL type), e.g. `time`, `solved`.
    pub columns: Vec<String>,
    /// One row per run; `None` where the run has no value (no solution, say).
    pub runs: Vec<Vec<Option<f64>>>,
}

impl PlannerRuns {
    /// Values of one column over the runs.
    pub fn column(&self, name: &str) -> Vec<Option<f64>> {
        match self.columns.iter().position(|c| c == name) {
            Some(i) => self
                .runs
                .iter()
                .map(|r| r.get(i).copied().flatten())
                .collect(),
            None => vec![None; self.runs.len()],
        }
    }
}

/// One log: one experiment (scene) and its planners.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchmarkLog {
    /// The experiment's name (the scene's).
    pub experiment: String,
    /// The experiment's `objects` parameter (pushplan writes it).
    pub objects: Option<usize>,
    /// The time limit per run (s).
    pub time_limit: f64,
    /// Every planner's runs.
    pub planners: Vec<PlannerRuns>,
}

/// Parses an OMPL benchmark log.
pub fn read_log(path: &Path) -> Result<BenchmarkLog, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let bad = |what: &str| format!("{}: not an OMPL benchmark log ({what})", path.display());
    let lines: Vec<&str> = text.lines().collect();
    let count = |line: &str, suffix: &str| {
        line.strip_suffix(suffix)
            .and_then(|n| n.trim().parse::<usize>().ok())
    };
    let experiment = lines
        .iter()
        .find_map(|l| l.strip_prefix("Experiment "))
        .ok_or_else(|| bad("no experiment"))?
        .to_string();
    let objects = lines
        .iter()
        .find_map(|l| l.strip_prefix("objects INTEGER = "))
        .and_then(|v| v.trim().parse().ok());
    let time_limit = lines
        .iter()
        .find_map(|l| count(l, " seconds per run").map(|n| n as f64))
        .or_else(|| {
            lines.iter().find_map(|l| {
                l.strip_suffix(" seconds per run")
                    .and_then(|v| v.trim().parse().ok())
            })
        });
    let mut at = lines
        .iter()
        .position(|l| count(l, " planners").is_some())
        .ok_or_else(|| bad("no planners"))?;
    let planners_count = count(lines[at], " planners").unwrap();
    at += 1;
    let mut planners = Vec::with_capacity(planners_count);
    for _ in 0..planners_count {
        let name = lines
            .get(at)
            .ok_or_else(|| bad("truncated"))?
            .trim()
            .to_string();
        at += 1;
        let common = lines
            .get(at)
            .and_then(|l| count(l, " common properties"))
            .ok_or_else(|| bad("common properties"))?;
        at += 1 + common;
        let properties = lines
            .get(at)
            .and_then(|l| count(l, " properties for each run"))
            .ok_or_else(|| bad("run properties"))?;
        let columns: Vec<String> = lines[at + 1..at + 1 + properties]
            .iter()
            .map(|l| {
                l.rsplit_once(' ')
                    .map_or(*l, |(name, _type)| name)
                    .to_string()
            })
            .collect();
        at += 1 + properties;
        let run_count = lines
            .get(at)
            .and_then(|l| count(l, " runs"))
            .ok_or_else(|| bad("runs"))?;
        let runs = lines[at + 1..at + 1 + run_count]
            .iter()
            .map(|l| {
                l.split(';')
                    .take(properties)
                    .map(|v| v.trim().parse::<f64>().ok())
                    .collect()
            })
            .collect();
        at += 1 + run_count;
        // Skip progress properties, up to the planner's closing ".".
        while at < lines.len() && lines[at].trim() != "." {
            at += 1;
        }
        at += 1;
        planners.push(PlannerRuns {
            name,
            columns,
            runs,
        });
    }
    Ok(BenchmarkLog {
        experiment,
        objects,
        time_limit: time_limit.unwrap_or(f64::NAN),
        planners,
    })
}
