//! `plan`'s progress: one line that updates in place on a terminal (indicatif), and a
//! line a second when stderr is a file or a pipe. The search (in C++) and shortcutting
//! report through plain function pointers, so the line is one per process, here.

use indicatif::{ProgressBar, ProgressStyle};
use pushplan::planner::SearchProgress;
use pushplan::planning::shortcut::ShortcutProgress;
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

static LINE: Mutex<Option<Line>> = Mutex::new(None);

struct Line {
    /// The updating line; `None` when stderr is not a terminal.
    bar: Option<ProgressBar>,
    /// The unit of goal distances ("m" for a goal disc, "rad" for a configuration).
    goal_unit: &'static str,
    /// Plain lines: when the last shortcutting line was printed.
    last_plain: Option<Instant>,
}

/// Starts the progress line for a search whose goal distances are in `goal_unit`.
pub fn start(goal_unit: &'static str) {
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = ProgressBar::new_spinner();
        bar.set_style(
            ProgressStyle::with_template("{spinner} {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_spinner()),
        );
        bar.enable_steady_tick(Duration::from_millis(200));
        bar.set_message("searching");
        bar
    });
    if let Ok(mut line) = LINE.lock() {
        *line = Some(Line {
            bar,
            goal_unit,
            last_plain: None,
        });
    }
}

/// Clears the progress line (the summary follows on stdout).
pub fn finish() {
    if let Ok(mut line) = LINE.lock() {
        if let Some(bar) = line.take().and_then(|l| l.bar) {
            bar.finish_and_clear();
        }
    }
}

/// The search's report, or an event's `note` (passed to the C++ search as a function
/// pointer: must not panic).
pub fn search(report: &SearchProgress, note: &str) {
    let Ok(mut guard) = LINE.lock() else { return };
    let Some(line) = guard.as_mut() else { return };
    if !note.is_empty() {
        line.event(note);
        return;
    }
    let mut text = format!(
        "searching: {:5.1} s, {} propagation steps, {:.0} steps/s, {:.0} % propagating",
        report.seconds,
        report.propagation_steps,
        report.steps_per_second,
        100.0 * report.propagating
    );
    if report.tree_states > 0 {
        text += &format!(", tree of {} states", report.tree_states);
    }
    if report.searches > 1 {
        text += &format!(" in {} searches", report.searches);
    }
    if report.closest_goal_distance.is_finite() {
        text += &format!(
            ", closest to the goal {:.3} {}",
            report.closest_goal_distance.max(0.0),
            line.goal_unit
        );
    }
    line.show(text, true);
}

/// Shortcutting's report, before every attempt.
pub fn shortcut(report: &ShortcutProgress) {
    let Ok(mut guard) = LINE.lock() else { return };
    let Some(line) = guard.as_mut() else { return };
    let text = format!(
        "shortcutting: {:.0} % of the budget, {} of {} attempts accepted, path {:.2} s long",
        100.0 * report.work as f64 / report.budget.max(1) as f64,
        report.accepted,
        report.attempts,
        report.duration,
    );
    // Attempts come fast: plain lines at most once a second.
    let due = line
        .last_plain
        .is_none_or(|t| t.elapsed() >= Duration::from_secs(1));
    line.show(text, due);
}

impl Line {
    /// Shows `text` on the updating line, or prints it as a plain line when `due`.
    fn show(&mut self, text: String, due: bool) {
        match &self.bar {
            Some(bar) => bar.set_message(text),
            None if due => {
                eprintln!("  {text}");
                self.last_plain = Some(Instant::now());
            }
            None => {}
        }
    }

    /// A line of its own above the updating one.
    fn event(&self, text: &str) {
        match &self.bar {
            Some(bar) => bar.println(format!("  {text}")),
            None => eprintln!("  {text}"),
        }
    }
}
