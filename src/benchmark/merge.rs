//! Merging the logs of a scene's cells (one planner, one run each) into one OMPL
//! benchmark log of the scene, in the format `ompl::tools::Benchmark` writes and
//! `ompl_benchmark_statistics` reads: the planners in the grid's order, each with its runs
//! in run order and the union of their properties.

use std::collections::BTreeSet;
use std::path::Path;

/// One planner's part of a log, as text.
#[derive(Clone, Debug, PartialEq)]
struct PlannerPart {
    name: String,
    common: Vec<String>,
    /// Run property declarations, `name TYPE`.
    properties: Vec<String>,
    /// Per run, one value (as written) per property.
    runs: Vec<Vec<String>>,
    /// Progress property declarations, and per run its progress line.
    progress_properties: Vec<String>,
    progress: Vec<String>,
}

/// A log as text: everything before the planners, and the planners.
#[derive(Clone, Debug, PartialEq)]
struct LogText {
    header: Vec<String>,
    planners: Vec<PlannerPart>,
}

fn parse(path: &Path) -> Result<LogText, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let bad = |what: &str| format!("{}: not an OMPL benchmark log ({what})", path.display());
    let lines: Vec<&str> = text.lines().collect();
    let count = |at: usize, suffix: &str| -> Option<usize> {
        lines.get(at)?.strip_suffix(suffix)?.trim().parse().ok()
    };
    let planners_at = (0..lines.len())
        .find(|&i| count(i, " planners").is_some())
        .ok_or_else(|| bad("no planners"))?;
    let mut at = planners_at + 1;
    let take = |n: usize, at: &mut usize| -> Result<Vec<String>, String> {
        let part = lines
            .get(*at..*at + n)
            .ok_or_else(|| bad("truncated"))?
            .iter()
            .map(|l| l.to_string())
            .collect();
        *at += n;
        Ok(part)
    };
    let mut planners = Vec::new();
    for _ in 0..count(planners_at, " planners").unwrap() {
        let name = take(1, &mut at)?.remove(0);
        let n = count(at, " common properties").ok_or_else(|| bad("common properties"))?;
        at += 1;
        let common = take(n, &mut at)?;
        let n = count(at, " properties for each run").ok_or_else(|| bad("run properties"))?;
        at += 1;
        let properties = take(n, &mut at)?;
        let n = count(at, " runs").ok_or_else(|| bad("runs"))?;
        at += 1;
        let runs = take(n, &mut at)?
            .iter()
            .map(|l| {
                let mut values: Vec<String> = l.split("; ").map(str::to_string).collect();
                values.pop(); // each value ends with "; "
                values
            })
            .collect();
        let (mut progress_properties, mut progress) = (Vec::new(), Vec::new());
        if let Some(n) = count(at, " progress properties for each run") {
            at += 1;
            progress_properties = take(n, &mut at)?;
            let n = count(at, " runs").ok_or_else(|| bad("progress runs"))?;
            at += 1;
            progress = take(n, &mut at)?;
        }
        if lines.get(at).map(|l| l.trim()) != Some(".") {
            return Err(bad("a planner's part does not end with '.'"));
        }
        at += 1;
        planners.push(PlannerPart {
            name,
            common,
            properties,
            runs,
            progress_properties,
            progress,
        });
    }
    Ok(LogText {
        header: lines[..planners_at].iter().map(|l| l.to_string()).collect(),
        planners,
    })
}

/// The merged log of one scene from its cells' logs, grouped by planner (in the grid's
/// order; each group's logs in run order). `seed` and `runs` are the grid's.
pub fn merge_scene(planners: &[Vec<&Path>], seed: u64, runs: u32) -> Result<String, String> {
    let logs: Vec<Vec<LogText>> = planners
        .iter()
        .map(|paths| paths.iter().map(|p| parse(p)).collect())
        .collect::<Result<_, _>>()?;
    let first = logs.iter().flatten().next().ok_or("a scene without runs")?;
    let experiment = |log: &LogText| {
        log.header
            .iter()
            .find(|l| l.starts_with("Experiment "))
            .cloned()
    };
    if let Some(other) = logs
        .iter()
        .flatten()
        .find(|l| experiment(l) != experiment(first))
    {
        return Err(format!(
            "the logs of one scene name different experiments: {:?} and {:?}",
            experiment(first),
            experiment(other)
        ));
    }
    let total_time: f64 = logs
        .iter()
        .flatten()
        .filter_map(|l| {
            l.header
                .iter()
                .find_map(|h| h.strip_suffix(" seconds spent to collect the data"))
                .and_then(|v| v.trim().parse::<f64>().ok())
        })
        .sum();
    let mut out = Vec::new();
    // The header of the first log, with the grid's seed and run count, the total time, and
    // every planner's specification in the setup block.
    let specs: Vec<String> = logs
        .iter()
        .filter_map(|group| group.first())
        .flat_map(|log| planner_specs(&log.header))
        .collect();
    let mut in_specs = false;
    for line in &first.header {
        if line.ends_with(" is the random seed") {
            out.push(format!("{seed} is the random seed"));
        } else if line.ends_with(" runs per planner") {
            out.push(format!("{runs} runs per planner"));
        } else if line.trim_end() == "OMPL version" {
            // Debian's OMPL leaves its version string empty (build.rs reads the numbers).
            out.push(format!("OMPL version {}", env!("PUSHPLAN_OMPL_VERSION")));
        } else if line.ends_with(" seconds spent to collect the data") {
            out.push(format!("{total_time} seconds spent to collect the data"));
        } else if line == "Properties of benchmarked planners:" {
            out.push(line.clone());
            out.extend(specs.iter().cloned());
            in_specs = true;
        } else if in_specs && line == "|>>>" {
            out.push(line.clone());
            in_specs = false;
        } else if !in_specs {
            out.push(line.clone());
        }
    }
    out.push(format!("{} planners", logs.len()));
    for group in &logs {
        out.extend(merge_planner(group)?);
    }
    Ok(out.join("\n") + "\n")
}

/// The "Planner NAME specs:" lines of a log's setup block.
fn planner_specs(header: &[String]) -> Vec<String> {
    let start = header
        .iter()
        .position(|l| l == "Properties of benchmarked planners:");
    let Some(start) = start else { return vec![] };
    header[start + 1..]
        .iter()
        .take_while(|l| *l != "|>>>")
        .cloned()
        .collect()
}

/// One planner's runs from several logs (each holding that planner only).
fn merge_planner(logs: &[LogText]) -> Result<Vec<String>, String> {
    let parts: Vec<&PlannerPart> = logs.iter().flat_map(|l| &l.planners).collect();
    let first = parts.first().ok_or("a planner without runs")?;
    if parts.iter().any(|p| p.name != first.name) {
        return Err(format!(
            "the logs of planner {} hold other planners",
            first.name
        ));
    }
    let properties: BTreeSet<&String> = parts.iter().flat_map(|p| &p.properties).collect();
    let progress_properties = parts
        .iter()
        .map(|p| &p.progress_properties)
        .find(|p| !p.is_empty())
        .cloned()
        .unwrap_or_default();
    let mut out = vec![
        first.name.clone(),
        format!("{} common properties", first.common.len()),
    ];
    out.extend(first.common.iter().cloned());
    out.push(format!("{} properties for each run", properties.len()));
    out.extend(properties.iter().map(|p| p.to_string()));
    let runs: usize = parts.iter().map(|p| p.runs.len()).sum();
    out.push(format!("{runs} runs"));
    for part in &parts {
        for run in &part.runs {
            let value = |name: &String| {
                let i = part.properties.iter().position(|p| p == name)?;
                run.get(i).cloned()
            };
            let row: String = properties
                .iter()
                .map(|name| value(name).unwrap_or_default() + "; ")
                .collect();
            out.push(row);
        }
    }
    if !progress_properties.is_empty() {
        out.push(format!(
            "{} progress properties for each run",
            progress_properties.len()
        ));
        out.extend(progress_properties.iter().cloned());
        out.push(format!("{runs} runs"));
        for part in &parts {
            if !part.progress_properties.is_empty()
                && part.progress_properties != progress_properties
            {
                return Err(format!(
                    "the runs of planner {} record different progress properties",
                    first.name
                ));
            }
            out.extend(part.progress.iter().cloned());
            out.extend((part.progress.len()..part.runs.len()).map(|_| String::new()));
        }
    }
    out.push(".".to_string());
    Ok(out)
}
