//! The paper's plots from benchmark logs, as SVG: success rate against time budget
//! (Fig. 7), plan time of solved runs (Fig. 4b), manipulator path length and object
//! displacement before and after shortcutting (Fig. 8), and success against the number
//! of objects.

use super::BenchmarkLog;
use std::fmt::Write;
use std::path::{Path, PathBuf};

const COLOURS: [&str; 7] = [
    "#1e7b1e", "#7b3fb8", "#d8453b", "#3b6fd8", "#d89b3b", "#3bb3d8", "#555555",
];
// Picture size and the plot area within it (px).
const W: f64 = 640.0;
const H: f64 = 400.0;
const LEFT: f64 = 70.0;
const TOP: f64 = 40.0;
const PLOT_W: f64 = 420.0;
const PLOT_H: f64 = 300.0;

/// Planner names in a stable order (as first seen), without OMPL's `control_` prefix.
fn planner_names(logs: &[BenchmarkLog]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for p in logs.iter().flat_map(|l| &l.planners) {
        if !names.contains(&p.name) {
            names.push(p.name.clone());
        }
    }
    names
}

fn short(name: &str) -> &str {
    name.strip_prefix("control_").unwrap_or(name)
}

/// All runs of a planner over all logs: (time, solved, objects of the scene, row).
fn runs<'a>(
    logs: &'a [BenchmarkLog],
    planner: &str,
) -> Vec<(f64, bool, Option<usize>, &'a super::PlannerRuns, usize)> {
    let mut out = Vec::new();
    for log in logs {
        for p in log.planners.iter().filter(|p| p.name == planner) {
            let (time, solved) = (p.column("time"), p.column("solved"));
            for i in 0..p.runs.len() {
                out.push((
                    time[i].unwrap_or(f64::INFINITY),
                    solved[i] == Some(1.0),
                    log.objects,
                    p,
                    i,
                ));
            }
        }
    }
    out
}

fn frame(
    title: &str,
    x_label: &str,
    y_label: &str,
    x_max: f64,
    y_max: f64,
    x_ticks: &[f64],
    y_ticks: &[f64],
) -> String {
    let mut s = format!(
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">
<text x="{LEFT}" y="22" font-size="15">{title}</text>
<rect x="{LEFT}" y="{TOP}" width="{PLOT_W}" height="{PLOT_H}" fill="none" stroke="#444"/>
"##
    );
    for &t in x_ticks {
        let x = LEFT + t / x_max * PLOT_W;
        let _ = writeln!(
            s,
            r##"<line x1="{x:.1}" y1="{:.1}" x2="{x:.1}" y2="{:.1}" stroke="#888"/><text x="{x:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
            TOP + PLOT_H,
            TOP + PLOT_H + 5.0,
            TOP + PLOT_H + 18.0,
            fmt_tick(t)
        );
    }
    for &t in y_ticks {
        let y = TOP + PLOT_H - t / y_max * PLOT_H;
        let _ = writeln!(
            s,
            r##"<line x1="{LEFT}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#ddd"/><text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"##,
            LEFT + PLOT_W,
            LEFT - 6.0,
            y + 4.0,
            fmt_tick(t)
        );
    }
    let _ = writeln!(
        s,
        r##"<text x="{:.1}" y="{:.1}" text-anchor="middle">{x_label}</text>"##,
        LEFT + PLOT_W / 2.0,
        TOP + PLOT_H + 36.0
    );
    let _ = writeln!(
        s,
        r##"<text transform="translate(18,{:.1}) rotate(-90)" text-anchor="middle">{y_label}</text>"##,
        TOP + PLOT_H / 2.0
    );
    s
}

fn fmt_tick(t: f64) -> String {
    if (t - t.round()).abs() < 1e-9 {
        format!("{}", t.round())
    } else {
        format!("{t:.2}")
    }
}

fn legend(s: &mut String, names: &[String]) {
    for (i, n) in names.iter().enumerate() {
        let y = TOP + 10.0 + i as f64 * 18.0;
        let _ = writeln!(
            s,
            r##"<rect x="{:.1}" y="{:.1}" width="12" height="12" fill="{}"/><text x="{:.1}" y="{:.1}">{}</text>"##,
            LEFT + PLOT_W + 15.0,
            y,
            COLOURS[i % COLOURS.len()],
            LEFT + PLOT_W + 32.0,
            y + 10.0,
            short(n)
        );
    }
}

/// A planner's curve through data points (x in [0, x_max], y in [0, y_max]).
fn curve(s: &mut String, name: &str, k: usize, points: &[(f64, f64)], x_max: f64, y_max: f64) {
    let px: Vec<String> = points
        .iter()
        .map(|(x, y)| {
            format!(
                "{:.1},{:.1}",
                LEFT + x / x_max * PLOT_W,
                TOP + PLOT_H - y / y_max * PLOT_H
            )
        })
        .collect();
    let _ = writeln!(
        s,
        r##"<polyline class="planner" data-planner="{}" points="{}" fill="none" stroke="{}" stroke-width="2"/>"##,
        short(name),
        px.join(" "),
        COLOURS[k % COLOURS.len()]
    );
}

/// Round tick values (steps of 1, 2 or 5 times a power of ten) from 0 to `max`.
fn ticks(max: f64, count: usize) -> Vec<f64> {
    let raw = max / count.max(1) as f64;
    let power = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * power)
        .find(|s| *s >= raw)
        .unwrap_or(raw);
    (0..)
        .map(|i| i as f64 * step)
        .take_while(|t| *t <= max + 1e-9)
        .collect()
}

/// Fig. 7: the share of runs solved within each time budget.
pub fn success_vs_time(logs: &[BenchmarkLog]) -> String {
    let names = planner_names(logs);
    // The time limit, or a solved run's time if a planner overran it (SST does, slightly).
    let solved_times: Vec<f64> = names
        .iter()
        .flat_map(|n| runs(logs, n))
        .filter(|r| r.1)
        .map(|r| r.0)
        .collect();
    let t_max = logs
        .iter()
        .map(|l| l.time_limit)
        .filter(|t| t.is_finite())
        .chain(solved_times)
        .fold(1.0, f64::max);
    let mut s = frame(
        "Success rate within a time budget",
        "time budget (s)",
        "runs solved (%)",
        t_max,
        100.0,
        &ticks(t_max, 6),
        &ticks(100.0, 5),
    );
    for (k, name) in names.iter().enumerate() {
        let all = runs(logs, name);
        let mut times: Vec<f64> = all.iter().filter(|r| r.1).map(|r| r.0).collect();
        times.sort_by(f64::total_cmp);
        let mut points = vec![(0.0, 0.0)];
        for (i, t) in times.iter().enumerate() {
            points.push((*t, points.last().unwrap().1));
            points.push((*t, 100.0 * (i + 1) as f64 / all.len().max(1) as f64));
        }
        points.push((t_max, points.last().unwrap().1));
        curve(&mut s, name, k, &points, t_max, 100.0);
    }
    legend(&mut s, &names);
    s + "</svg>\n"
}

/// Fig. 4b: plan time of the solved runs, as box plots (min, quartiles, median, max).
pub fn plan_time(logs: &[BenchmarkLog]) -> String {
    let names = planner_names(logs);
    let t_max = logs
        .iter()
        .map(|l| l.time_limit)
        .filter(|t| t.is_finite())
        .fold(1.0, f64::max);
    let mut s = frame(
        "Plan time of solved runs",
        "",
        "time (s)",
        names.len() as f64,
        t_max,
        &[],
        &ticks(t_max, 6),
    );
    for (k, name) in names.iter().enumerate() {
        let mut times: Vec<f64> = runs(logs, name)
            .iter()
            .filter(|r| r.1)
            .map(|r| r.0)
            .collect();
        let x = LEFT + (k as f64 + 0.5) / names.len() as f64 * PLOT_W;
        let _ = writeln!(
            s,
            r##"<text x="{x:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
            TOP + PLOT_H + 18.0,
            short(name)
        );
        if times.is_empty() {
            continue;
        }
        times.sort_by(f64::total_cmp);
        let q = |f: f64| times[((times.len() - 1) as f64 * f).round() as usize];
        let y = |t: f64| TOP + PLOT_H - t / t_max * PLOT_H;
        let colour = COLOURS[k % COLOURS.len()];
        let _ = writeln!(
            s,
            r##"<g class="box" data-planner="{}" data-median="{}"><line x1="{x:.1}" y1="{:.1}" x2="{x:.1}" y2="{:.1}" stroke="{colour}"/><rect x="{:.1}" y="{:.1}" width="30" height="{:.1}" fill="{colour}" fill-opacity="0.3" stroke="{colour}"/><line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{colour}" stroke-width="3"/></g>"##,
            short(name),
            q(0.5),
            y(q(0.0)),
            y(q(1.0)),
            x - 15.0,
            y(q(0.75)),
            (y(q(0.25)) - y(q(0.75))).max(1.0),
            x - 15.0,
            y(q(0.5)),
            x + 15.0,
            y(q(0.5))
        );
    }
    s + "</svg>\n"
}

/// Fig. 8: the mean of a path measure over solved runs, before (dark) and after (light)
/// shortcutting, per planner. A planner whose paths are not shortcut (DARRT's primitive
/// paths) has the dark bar only.
pub fn shortcutting(
    logs: &[BenchmarkLog],
    before: &str,
    after: &str,
    title: &str,
    unit: &str,
) -> String {
    let names = planner_names(logs);
    let mean = |name: &str, column: &str| {
        let values: Vec<f64> = runs(logs, name)
            .iter()
            .filter(|r| r.1)
            .filter_map(|r| r.3.column(column)[r.4])
            .collect();
        (!values.is_empty()).then(|| values.iter().sum::<f64>() / values.len() as f64)
    };
    let bars: Vec<[Option<f64>; 2]> = names
        .iter()
        .map(|n| [mean(n, before), mean(n, after)])
        .collect();
    let y_max = bars
        .iter()
        .flatten()
        .flatten()
        .fold(1e-9f64, |a, b| a.max(*b))
        * 1.15;
    let mut s = frame(
        title,
        "",
        unit,
        names.len() as f64,
        y_max,
        &[],
        &ticks(y_max, 5),
    );
    for (k, (name, b)) in names.iter().zip(&bars).enumerate() {
        let x0 = LEFT + k as f64 / names.len() as f64 * PLOT_W + 10.0;
        let width = (PLOT_W / names.len() as f64 - 20.0) / 2.0;
        for (j, value) in b.iter().enumerate() {
            let Some(value) = value else { continue };
            let h = value / y_max * PLOT_H;
            let (series, opacity) = if j == 0 {
                ("before", 0.9)
            } else {
                ("after", 0.4)
            };
            let _ = writeln!(
                s,
                r##"<rect class="bar" data-planner="{}" data-series="{series}" data-value="{value}" x="{:.1}" y="{:.1}" width="{:.1}" height="{h:.1}" fill="{}" fill-opacity="{opacity}"/>"##,
                short(name),
                x0 + j as f64 * width,
                TOP + PLOT_H - h,
                width - 2.0,
                COLOURS[k % COLOURS.len()]
            );
        }
        let _ = writeln!(
            s,
            r##"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
            x0 + width,
            TOP + PLOT_H + 18.0,
            short(name)
        );
    }
    s + "</svg>\n"
}

/// Success rate against the number of objects in the scene.
pub fn success_vs_objects(logs: &[BenchmarkLog]) -> String {
    let names = planner_names(logs);
    let most = logs
        .iter()
        .filter_map(|l| l.objects)
        .max()
        .unwrap_or(1)
        .max(1);
    let mut s = frame(
        "Success rate by number of objects",
        "movable objects",
        "runs solved (%)",
        most as f64,
        100.0,
        &(1..=most).map(|n| n as f64).collect::<Vec<_>>(),
        &ticks(100.0, 5),
    );
    for (k, name) in names.iter().enumerate() {
        let all = runs(logs, name);
        let points: Vec<(f64, f64)> = (1..=most)
            .filter_map(|n| {
                let of_n: Vec<_> = all.iter().filter(|r| r.2 == Some(n)).collect();
                (!of_n.is_empty()).then(|| {
                    (
                        n as f64,
                        100.0 * of_n.iter().filter(|r| r.1).count() as f64 / of_n.len() as f64,
                    )
                })
            })
            .collect();
        curve(&mut s, name, k, &points, most as f64, 100.0);
    }
    legend(&mut s, &names);
    s + "</svg>\n"
}

/// Writes the five plots into `dir` from the logs; returns the files.
pub fn write_plots(logs: &[BenchmarkLog], dir: &Path) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let plots = [
        ("success_vs_time.svg", success_vs_time(logs)),
        ("plan_time.svg", plan_time(logs)),
        (
            "shortcut_path_length.svg",
            shortcutting(
                logs,
                "manipulator path length",
                "manipulator path length shortcut",
                "Manipulator path length before (dark) and after (light) shortcutting",
                "joint path (rad)",
            ),
        ),
        (
            "shortcut_object_displacement.svg",
            shortcutting(
                logs,
                "object displacement",
                "object displacement shortcut",
                "Object displacement before (dark) and after (light) shortcutting",
                "object displacement (m)",
            ),
        ),
        ("success_vs_objects.svg", success_vs_objects(logs)),
    ];
    plots
        .into_iter()
        .map(|(name, svg)| {
            let path = dir.join(name);
            std::fs::write(&path, svg).map_err(|e| format!("{}: {e}", path.display()))?;
            Ok(path)
        })
        .collect()
}
