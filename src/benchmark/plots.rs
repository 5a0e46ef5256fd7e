//! The paper's plots from benchmark logs, as SVG drawn with `plotters`: success rate
//! against time budget (Fig. 7), over all scenes and per scene in panels (as Planner
//! Arena shows each problem), plan time of solved runs (Fig. 4b), manipulator path length
//! and object displacement before and after shortcutting (Fig. 8), and success against
//! the number of objects. Every plot says how many runs it shows and the spread of what
//! it summarises (quartiles, 95 % confidence intervals); time axes are logarithmic with
//! ticks at 1, 2 and 5 of each decade; planners carry the papers' names; an anytime
//! planner (SST, whose time is the whole budget) is marked.

use super::BenchmarkLog;
use crate::planning::PlannerKind;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// Picture size (px).
const SIZE: (u32, u32) = (900, 440);
/// Room right of the plot for the legend (px).
const LEGEND_WIDTH: u32 = 270;
/// Fastest time a log axis shows (s): solved times below it sit on the axis.
const MIN_TIME: f64 = 0.01;

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// A planner in the logs: its OMPL name and what the plots call it.
struct Planner {
    ompl: String,
    kind: Option<PlannerKind>,
}

impl Planner {
    fn name(&self) -> String {
        match self.kind {
            Some(kind) => kind.paper_name().to_string(),
            None => self
                .ompl
                .strip_prefix("control_")
                .unwrap_or(&self.ompl)
                .to_string(),
        }
    }

    /// The legend's entry: the name, marked when its time is the whole budget.
    fn label(&self, n: usize) -> String {
        let anytime = if self.kind.is_some_and(PlannerKind::is_anytime) {
            ", anytime: its time is the budget"
        } else {
            ""
        };
        format!("{} (n = {n}{anytime})", self.name())
    }

    /// One colour per planner kind, the same in every plot.
    fn colour(&self, index: usize) -> RGBColor {
        const COLOURS: [RGBColor; 9] = [
            RGBColor(0x1e, 0x7b, 0x1e),
            RGBColor(0x7b, 0x32, 0x94),
            RGBColor(0xd8, 0x45, 0x3b),
            RGBColor(0x3b, 0x6f, 0xd8),
            RGBColor(0xff, 0x7f, 0x00),
            RGBColor(0x17, 0xbe, 0xcf),
            RGBColor(0x55, 0x55, 0x55),
            RGBColor(0x8c, 0x56, 0x4b),
            RGBColor(0xe3, 0x77, 0xc2),
        ];
        let k = self
            .kind
            .and_then(|k| PlannerKind::ALL.iter().position(|&a| a == k))
            .unwrap_or(index);
        COLOURS[k % COLOURS.len()]
    }
}

/// The planners of the logs, in a stable order (as first seen).
fn planners(logs: &[BenchmarkLog]) -> Vec<Planner> {
    let mut names: Vec<String> = Vec::new();
    for p in logs.iter().flat_map(|l| &l.planners) {
        if !names.contains(&p.name) {
            names.push(p.name.clone());
        }
    }
    names
        .into_iter()
        .map(|ompl| Planner {
            kind: PlannerKind::from_ompl_name(&ompl),
            ompl,
        })
        .collect()
}

/// One run of a planner: its time, whether it solved, its scene's object count and the
/// row it came from.
struct Run<'a> {
    time: f64,
    solved: bool,
    objects: Option<usize>,
    row: &'a super::PlannerRuns,
    index: usize,
}

impl Run<'_> {
    fn value(&self, column: &str) -> Option<f64> {
        self.row.column(column)[self.index]
    }
}

/// All runs of a planner over all logs.
fn runs<'a>(logs: &'a [BenchmarkLog], planner: &Planner) -> Vec<Run<'a>> {
    let mut out = Vec::new();
    for log in logs {
        for p in log.planners.iter().filter(|p| p.name == planner.ompl) {
            let (time, solved) = (p.column("time"), p.column("solved"));
            for index in 0..p.runs.len() {
                out.push(Run {
                    time: time[index].unwrap_or(f64::INFINITY),
                    solved: solved[index] == Some(1.0),
                    objects: log.objects,
                    row: p,
                    index,
                });
            }
        }
    }
    out
}

/// The `p`-quantile (0 <= p <= 1) of sorted values, interpolated linearly between order
/// statistics (Hyndman and Fan's type 7, R's and NumPy's default): the median of four
/// values is the mean of the middle two.
pub fn quantile(sorted: &[f64], p: f64) -> f64 {
    let h = (sorted.len() - 1) as f64 * p.clamp(0.0, 1.0);
    let (lo, frac) = (h.floor() as usize, h - h.floor());
    match sorted.get(lo + 1) {
        Some(next) => sorted[lo] + frac * (next - sorted[lo]),
        None => sorted[lo],
    }
}

/// z of a two-sided 95 % interval of the normal distribution.
const Z95: f64 = 1.959_963_984_540_054;

/// The mean of `values` and the half-width of its 95 % confidence interval (normal
/// approximation, `z s / sqrt(n)` with the sample standard deviation; 0 for one value).
pub fn mean_interval(values: &[f64]) -> Option<(f64, f64)> {
    if values.is_empty() {
        return None;
    }
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    if values.len() == 1 {
        return Some((mean, 0.0));
    }
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    Some((mean, Z95 * (variance / n).sqrt()))
}

/// Wilson's 95 % score interval of a success rate: `successes` of `n` (n > 0), as
/// `(low, high)` fractions. Unlike the normal approximation it stays within [0, 1] and
/// is not empty at 0 or n successes.
pub fn wilson_interval(successes: usize, n: usize) -> (f64, f64) {
    let (n, p) = (n as f64, successes as f64 / n as f64);
    let z2 = Z95 * Z95;
    let centre = (p + z2 / (2.0 * n)) / (1.0 + z2 / n);
    let half = Z95 / (1.0 + z2 / n) * (p * (1.0 - p) / n + z2 / (4.0 * n * n)).sqrt();
    ((centre - half).max(0.0), (centre + half).min(1.0))
}

/// Ticks of a logarithmic axis from `low` to `high`: 1, 2 and 5 of every decade between,
/// and `high` itself (the time limit).
fn log_ticks(low: f64, high: f64) -> Vec<f64> {
    let mut ticks = Vec::new();
    let mut decade = 10f64.powf(low.log10().floor());
    while decade <= high {
        for m in [1.0, 2.0, 5.0] {
            let t = m * decade;
            if t >= low * (1.0 - 1e-9) && t <= high * 0.8 {
                ticks.push(t);
            }
        }
        decade *= 10.0;
    }
    ticks.push(high);
    ticks
}

/// A time axis label: the decimal digits the value has, no more (`0.01`, `0.5`, `2`, `60`).
fn time_label(t: &f64) -> String {
    let decimals = (-t.log10().floor()).max(0.0) as usize;
    let text = format!("{t:.decimals$}");
    match text.contains('.') {
        true => text.trim_end_matches('0').trim_end_matches('.').to_string(),
        false => text,
    }
}

fn plot_error(e: impl std::fmt::Display) -> String {
    format!("drawing a plot: {e}")
}

/// Draws into an SVG string of the usual size with `draw`.
fn svg(draw: impl FnOnce(&Area) -> Result<(), String>) -> Result<String, String> {
    svg_of_size(SIZE, draw)
}

/// Draws into an SVG string of `size` (px) with `draw`.
fn svg_of_size(
    size: (u32, u32),
    draw: impl FnOnce(&Area) -> Result<(), String>,
) -> Result<String, String> {
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, size).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        draw(&root)?;
        root.present().map_err(plot_error)?;
    }
    Ok(out)
}

/// The longest time any run may take: the time limit, or a solved run's time if a
/// planner overran it (SST does, slightly).
fn time_limit(logs: &[BenchmarkLog], all: &[Planner]) -> f64 {
    logs.iter()
        .map(|l| l.time_limit)
        .filter(|t| t.is_finite())
        .chain(
            all.iter()
                .flat_map(|p| runs(logs, p))
                .filter(|r| r.solved)
                .map(|r| r.time),
        )
        .fold(1.0, f64::max)
}

/// Fig. 7: the share of runs solved within each time budget, on a log time axis (most
/// runs finish in the first seconds), over every scene of the logs.
pub fn success_vs_time(logs: &[BenchmarkLog]) -> Result<String, String> {
    let all = planners(logs);
    let t_max = time_limit(logs, &all);
    svg(|root| {
        let chart = chart(root, "Runs solved within a time budget", true);
        let entries = success_curves(chart, logs, &all, t_max, true)?;
        side_legend(root, &entries)
    })
}

/// Fig. 7 per scene, in panels of four to a row as Planner Arena shows each problem: the
/// same curves and colours, each panel with its scene's name and run count, and one
/// legend for all.
pub fn success_vs_time_per_scene(logs: &[BenchmarkLog]) -> Result<String, String> {
    let all = planners(logs);
    let t_max = time_limit(logs, &all);
    let mut scenes: Vec<&str> = Vec::new();
    for log in logs {
        if !scenes.contains(&log.experiment.as_str()) {
            scenes.push(&log.experiment);
        }
    }
    let columns = scenes.len().clamp(1, 4);
    let rows = scenes.len().div_ceil(columns).max(1);
    let size = (SIZE.0 + 300, 40 + 230 * rows as u32);
    svg_of_size(size, |root| {
        root.titled(
            "Runs solved within a time budget, per scene",
            ("sans-serif", 17),
        )
        .map_err(plot_error)?;
        let (plots, _) = root.split_horizontally(size.0 - LEGEND_WIDTH);
        let plots = plots.margin(30, 0, 0, 0);
        let panels = plots.split_evenly((rows, columns));
        for (panel, scene) in panels.iter().zip(&scenes) {
            let of_scene: Vec<BenchmarkLog> = logs
                .iter()
                .filter(|l| l.experiment == *scene)
                .cloned()
                .collect();
            let runs = all
                .iter()
                .map(|p| runs(&of_scene, p).len())
                .max()
                .unwrap_or(0);
            let mut builder = ChartBuilder::on(panel);
            builder
                .caption(format!("{scene} (n = {runs})"), ("sans-serif", 13))
                .margin(6)
                .x_label_area_size(28)
                .y_label_area_size(36);
            success_curves(builder, &of_scene, &all, t_max, false)?;
        }
        let legend_x = size.0 as i32 - LEGEND_WIDTH as i32 + 8;
        let entries: Vec<(String, RGBColor, Glyph)> = all
            .iter()
            .enumerate()
            .map(|(k, p)| (p.name(), p.colour(k), Glyph::Line))
            .collect();
        side_legend_at(root, legend_x, &entries)
    })
}

/// Draws the success-vs-time curves of `logs` (one per planner of `all`, up to `t_max`)
/// in the chart `builder` makes, with axis names when `described`; returns the legend's
/// entries.
fn success_curves(
    mut builder: ChartBuilder<'_, '_, SVGBackend<'_>>,
    logs: &[BenchmarkLog],
    all: &[Planner],
    t_max: f64,
    described: bool,
) -> Result<Vec<(String, RGBColor, Glyph)>, String> {
    let mut chart = builder
        .build_cartesian_2d(
            (MIN_TIME..t_max)
                .log_scale()
                .with_key_points(log_ticks(MIN_TIME, t_max)),
            0.0..100.0,
        )
        .map_err(plot_error)?;
    let mut mesh = chart.configure_mesh();
    mesh.x_label_formatter(&time_label);
    if described {
        mesh.x_desc("time budget (s, log scale)")
            .y_desc("runs solved (%)");
    }
    mesh.draw().map_err(plot_error)?;
    let mut entries = Vec::new();
    for (k, planner) in all.iter().enumerate() {
        let runs = runs(logs, planner);
        let mut times: Vec<f64> = runs.iter().filter(|r| r.solved).map(|r| r.time).collect();
        times.sort_by(f64::total_cmp);
        let share = |i: usize| 100.0 * i as f64 / runs.len().max(1) as f64;
        let mut points = vec![(MIN_TIME, 0.0)];
        for (i, t) in times.iter().enumerate() {
            let t = t.max(MIN_TIME);
            points.push((t, share(i)));
            points.push((t, share(i + 1)));
        }
        points.push((t_max, share(times.len())));
        let colour = planner.colour(k);
        chart
            .draw_series(LineSeries::new(points, colour.stroke_width(2)))
            .map_err(plot_error)?;
        entries.push((planner.label(runs.len()), colour, Glyph::Line));
        // A marker where the curve ends: the share solved at the time limit.
        chart
            .draw_series(std::iter::once(Circle::new(
                (t_max, share(times.len())),
                4,
                colour.filled(),
            )))
            .map_err(plot_error)?;
    }
    Ok(entries)
}

/// A chart with its title, leaving room right of it for a legend if it has one.
fn chart<'a, 'b>(
    root: &'a Area<'b>,
    title: &str,
    legend: bool,
) -> ChartBuilder<'a, 'b, SVGBackend<'b>> {
    let mut builder = ChartBuilder::on(root);
    builder
        .caption(title, ("sans-serif", 17))
        .margin(12)
        .margin_right(if legend { LEGEND_WIDTH } else { 12 })
        .x_label_area_size(40)
        .y_label_area_size(60);
    builder
}

/// How a legend entry is drawn.
#[derive(Clone, Copy)]
enum Glyph {
    Line,
    Dot,
}

/// The legend in the room right of the plot (`LEGEND_WIDTH`), drawn on the whole
/// picture (a chart clips what lies outside its plot).
fn side_legend(root: &Area, entries: &[(String, RGBColor, Glyph)]) -> Result<(), String> {
    side_legend_at(root, SIZE.0 as i32 - LEGEND_WIDTH as i32 + 8, entries)
}

/// A legend whose entries start at `x` (px), one below the other.
fn side_legend_at(
    root: &Area,
    x: i32,
    entries: &[(String, RGBColor, Glyph)],
) -> Result<(), String> {
    for (i, (label, colour, glyph)) in entries.iter().enumerate() {
        let y = 50 + 20 * i as i32;
        match glyph {
            Glyph::Line => root.draw(&PathElement::new(
                vec![(x, y), (x + 20, y)],
                colour.stroke_width(2),
            )),
            Glyph::Dot => root.draw(&Circle::new((x + 10, y), 4, colour.filled())),
        }
        .map_err(plot_error)?;
        root.draw(&Text::new(
            label.clone(),
            (x + 28, y - 7),
            ("sans-serif", 12).into_font(),
        ))
        .map_err(plot_error)?;
    }
    Ok(())
}

/// Labels of categories along x: category `i` centred at `i`, labelled `names[i]`.
fn category_labels(names: Vec<String>) -> impl Fn(&f64) -> String {
    move |x: &f64| {
        let i = x.round();
        if (x - i).abs() < 1e-6 && i >= 0.0 {
            names.get(i as usize).cloned().unwrap_or_default()
        } else {
            String::new()
        }
    }
}

/// Fig. 4b: plan time of the solved runs, as box plots on a log axis: the box spans the
/// quartiles, the thick line is the median, the whiskers reach the fastest and slowest
/// run (quantiles by [`quantile`]).
pub fn plan_time(logs: &[BenchmarkLog]) -> Result<String, String> {
    let all = planners(logs);
    let t_max = time_limit(logs, &all);
    let solved: Vec<Vec<f64>> = all
        .iter()
        .map(|p| {
            let mut t: Vec<f64> = runs(logs, p)
                .iter()
                .filter(|r| r.solved)
                .map(|r| r.time.max(MIN_TIME))
                .collect();
            t.sort_by(f64::total_cmp);
            t
        })
        .collect();
    let names: Vec<String> = all
        .iter()
        .zip(&solved)
        .map(|(p, t)| {
            let anytime = if p.kind.is_some_and(PlannerKind::is_anytime) {
                " (anytime)"
            } else {
                ""
            };
            format!("{}{anytime}, n = {}", p.name(), t.len())
        })
        .collect();
    let count = all.len().max(1);
    svg(|root| {
        let mut chart = chart(
            root,
            "Plan time of solved runs (n: solved runs; an anytime planner's is the budget)",
            false,
        )
        .build_cartesian_2d(
            -0.5..count as f64 - 0.5,
            (MIN_TIME..t_max * 1.2)
                .log_scale()
                .with_key_points(log_ticks(MIN_TIME, t_max)),
        )
        .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(count)
            .x_label_formatter(&category_labels(names))
            .y_label_formatter(&time_label)
            .y_desc("time (s, log scale)")
            .draw()
            .map_err(plot_error)?;
        for (k, (planner, times)) in all.iter().zip(&solved).enumerate() {
            if times.is_empty() {
                continue;
            }
            let x = k as f64;
            let colour = planner.colour(k);
            let q = |p: f64| quantile(times, p);
            let elements = vec![
                PathElement::new(vec![(x, q(0.0)), (x, q(0.25))], colour.stroke_width(1)),
                PathElement::new(vec![(x, q(0.75)), (x, q(1.0))], colour.stroke_width(1)),
                PathElement::new(
                    vec![(x - 0.12, q(0.0)), (x + 0.12, q(0.0))],
                    colour.stroke_width(1),
                ),
                PathElement::new(
                    vec![(x - 0.12, q(1.0)), (x + 0.12, q(1.0))],
                    colour.stroke_width(1),
                ),
            ];
            chart.draw_series(elements).map_err(plot_error)?;
            chart
                .draw_series([Rectangle::new(
                    [(x - 0.25, q(0.25)), (x + 0.25, q(0.75))],
                    colour.mix(0.3).filled(),
                )])
                .map_err(plot_error)?;
            chart
                .draw_series([Rectangle::new(
                    [(x - 0.25, q(0.25)), (x + 0.25, q(0.75))],
                    colour,
                )])
                .map_err(plot_error)?;
            chart
                .draw_series([PathElement::new(
                    vec![(x - 0.25, q(0.5)), (x + 0.25, q(0.5))],
                    colour.stroke_width(3),
                )])
                .map_err(plot_error)?;
        }
        Ok(())
    })
}

/// Fig. 8: the mean of a path measure over solved runs, before (dark) and after (light)
/// shortcutting, per planner, each bar with the 95 % confidence interval of its mean
/// ([`mean_interval`]). A planner whose paths are not shortcut (DARRT's primitive paths)
/// has the dark bar only.
pub fn shortcutting(
    logs: &[BenchmarkLog],
    before: &str,
    after: &str,
    title: &str,
    unit: &str,
) -> Result<String, String> {
    let all = planners(logs);
    let values = |planner: &Planner, column: &str| -> Vec<f64> {
        runs(logs, planner)
            .iter()
            .filter(|r| r.solved)
            .filter_map(|r| r.value(column))
            .collect()
    };
    let bars: Vec<[Option<(f64, f64)>; 2]> = all
        .iter()
        .map(|p| {
            [
                mean_interval(&values(p, before)),
                mean_interval(&values(p, after)),
            ]
        })
        .collect();
    let names: Vec<String> = all
        .iter()
        .map(|p| format!("{}, n = {}", p.name(), values(p, before).len()))
        .collect();
    let y_max = bars
        .iter()
        .flatten()
        .flatten()
        .fold(1e-9f64, |a, (mean, half)| a.max(mean + half))
        * 1.15;
    let count = all.len().max(1);
    svg(|root| {
        let mut chart = chart(root, title, false)
            .build_cartesian_2d(-0.5..count as f64 - 0.5, 0.0..y_max)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(count)
            .x_label_formatter(&category_labels(names))
            .y_desc(format!(
                "mean {unit}, 95 % confidence interval (n: solved runs)"
            ))
            .draw()
            .map_err(plot_error)?;
        for (k, (planner, b)) in all.iter().zip(&bars).enumerate() {
            let colour = planner.colour(k);
            for (j, bar) in b.iter().enumerate() {
                let Some((mean, half)) = *bar else { continue };
                let (x0, style) = if j == 0 {
                    (k as f64 - 0.35, colour.mix(0.9).filled())
                } else {
                    (k as f64, colour.mix(0.35).filled())
                };
                chart
                    .draw_series([Rectangle::new([(x0, 0.0), (x0 + 0.33, mean)], style)])
                    .map_err(plot_error)?;
                let (x, low, high) = (x0 + 0.165, (mean - half).max(0.0), mean + half);
                chart
                    .draw_series([
                        PathElement::new(vec![(x, low), (x, high)], BLACK.stroke_width(1)),
                        PathElement::new(
                            vec![(x - 0.05, low), (x + 0.05, low)],
                            BLACK.stroke_width(1),
                        ),
                        PathElement::new(
                            vec![(x - 0.05, high), (x + 0.05, high)],
                            BLACK.stroke_width(1),
                        ),
                    ])
                    .map_err(plot_error)?;
            }
        }
        Ok(())
    })
}

/// Success rate against the number of objects in the scene: a marker per measured
/// count with its 95 % Wilson interval ([`wilson_interval`]), lines only between
/// neighbouring counts that both have runs, planners spread a little apart so that equal
/// rates stay visible.
pub fn success_vs_objects(logs: &[BenchmarkLog]) -> Result<String, String> {
    let all = planners(logs);
    let most = logs
        .iter()
        .filter_map(|l| l.objects)
        .max()
        .unwrap_or(1)
        .max(1);
    let spread = |k: usize| (k as f64 - (all.len() as f64 - 1.0) / 2.0) * 0.06;
    svg(|root| {
        let mut chart = chart(
            root,
            "Runs solved by number of objects (n: runs per count; bars: 95 % Wilson intervals)",
            true,
        )
        .build_cartesian_2d(0.5..most as f64 + 0.5, -2.0..104.0)
        .map_err(plot_error)?;
        chart
            .configure_mesh()
            .x_labels(most)
            .x_label_formatter(&category_labels(
                (0..=most).map(|n| n.to_string()).collect(),
            ))
            .x_desc("movable objects")
            .y_desc("runs solved (%)")
            .draw()
            .map_err(plot_error)?;
        let mut entries = Vec::new();
        for (k, planner) in all.iter().enumerate() {
            let runs = runs(logs, planner);
            // Per object count: (count, % solved, runs, the interval's % low and high).
            let points: Vec<(usize, f64, usize, f64, f64)> = (1..=most)
                .filter_map(|n| {
                    let of_n: Vec<&Run> = runs.iter().filter(|r| r.objects == Some(n)).collect();
                    (!of_n.is_empty()).then(|| {
                        let solved = of_n.iter().filter(|r| r.solved).count();
                        let (low, high) = wilson_interval(solved, of_n.len());
                        let rate = 100.0 * solved as f64 / of_n.len() as f64;
                        (n, rate, of_n.len(), 100.0 * low, 100.0 * high)
                    })
                })
                .collect();
            let colour = planner.colour(k);
            let x = |n: usize| n as f64 + spread(k);
            let at = |p: &(usize, f64, usize, f64, f64)| (x(p.0), p.1);
            let intervals = points.iter().map(|p| {
                PathElement::new(
                    vec![(x(p.0), p.3), (x(p.0), p.4)],
                    colour.mix(0.6).stroke_width(1),
                )
            });
            chart.draw_series(intervals).map_err(plot_error)?;
            let segments = points
                .windows(2)
                .filter(|w| w[1].0 == w[0].0 + 1)
                .map(|w| PathElement::new(vec![at(&w[0]), at(&w[1])], colour.stroke_width(2)));
            chart.draw_series(segments).map_err(plot_error)?;
            let per_count: Vec<usize> = points.iter().map(|p| p.2).collect();
            let n = match (per_count.iter().min(), per_count.iter().max()) {
                (Some(a), Some(b)) if a == b => format!("{a}"),
                (Some(a), Some(b)) => format!("{a}-{b}"),
                _ => "0".into(),
            };
            chart
                .draw_series(
                    points
                        .iter()
                        .map(|p| Circle::new(at(p), 4, colour.filled())),
                )
                .map_err(plot_error)?;
            entries.push((format!("{} (n = {n})", planner.name()), colour, Glyph::Dot));
        }
        side_legend(root, &entries)
    })
}

/// Writes the six plots into `dir` from the logs; returns the files.
pub fn write_plots(logs: &[BenchmarkLog], dir: &Path) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let plots = [
        ("success_vs_time.svg", success_vs_time(logs)?),
        (
            "success_vs_time_per_scene.svg",
            success_vs_time_per_scene(logs)?,
        ),
        ("plan_time.svg", plan_time(logs)?),
        (
            "shortcut_path_length.svg",
            shortcutting(
                logs,
                "manipulator path length",
                "manipulator path length shortcut",
                "Manipulator path length before (dark) and after (light) shortcutting",
                "joint path (rad)",
            )?,
        ),
        (
            "shortcut_object_displacement.svg",
            shortcutting(
                logs,
                "object displacement",
                "object displacement shortcut",
                "Object displacement before (dark) and after (light) shortcutting",
                "object displacement (m)",
            )?,
        ),
        ("success_vs_objects.svg", success_vs_objects(logs)?),
    ];
    plots
        .into_iter()
        .map(|(name, svg)| {
            let path = dir.join(name);
            crate::output::write_whole(&path, svg)?;
            Ok(path)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{log_ticks, mean_interval, quantile, time_label, wilson_interval};

    /// Wilson's intervals as published tables give them (Newcombe 1998, Table I: 0 of 10
    /// and 5 of 10 at 95 %), to four places.
    #[test]
    fn wilson_intervals_match_the_published_values() {
        let round = |(a, b): (f64, f64)| ((a * 1e4).round() / 1e4, (b * 1e4).round() / 1e4);
        assert_eq!(round(wilson_interval(0, 10)), (0.0, 0.2775));
        assert_eq!(round(wilson_interval(5, 10)), (0.2366, 0.7634));
        assert_eq!(round(wilson_interval(10, 10)), (0.7225, 1.0));
    }

    /// 1..5: mean 3, sample standard deviation sqrt(2.5), so 1.96 sqrt(2.5 / 5) = 1.386.
    #[test]
    fn a_mean_comes_with_its_confidence_interval() {
        let (mean, half) = mean_interval(&[1.0, 2.0, 3.0, 4.0, 5.0]).unwrap();
        assert_eq!(mean, 3.0);
        assert!((half - 1.385_904).abs() < 1e-6, "{half}");
        assert_eq!(mean_interval(&[7.0]), Some((7.0, 0.0)));
        assert_eq!(mean_interval(&[]), None);
    }

    #[test]
    fn log_axes_are_ticked_at_1_2_and_5_and_labelled_without_noise() {
        let ticks: Vec<String> = log_ticks(0.01, 30.0).iter().map(time_label).collect();
        assert_eq!(
            ticks,
            ["0.01", "0.02", "0.05", "0.1", "0.2", "0.5", "1", "2", "5", "10", "20", "30"]
        );
        // The limit itself, without a tick crowding it.
        assert_eq!(log_ticks(0.01, 60.0).last(), Some(&60.0));
        assert!(!log_ticks(0.01, 60.0).contains(&50.0));
    }

    /// Type-7 quantiles computed by hand (R: quantile(x, type = 7)).
    #[test]
    fn quantiles_interpolate_between_order_statistics() {
        let four = [0.1, 0.3, 0.41, 0.9];
        assert!((quantile(&four, 0.5) - 0.355).abs() < 1e-12);
        assert!((quantile(&four, 0.25) - 0.25).abs() < 1e-12);
        assert!((quantile(&four, 0.75) - 0.5325).abs() < 1e-12);
        assert_eq!(quantile(&four, 0.0), 0.1);
        assert_eq!(quantile(&four, 1.0), 0.9);
        assert_eq!(quantile(&[2.0], 0.5), 2.0);
        assert_eq!(quantile(&[1.0, 2.0, 7.0], 0.5), 2.0);
    }
}
