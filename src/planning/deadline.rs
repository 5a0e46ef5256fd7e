//! Deadlines: a time budget in seconds turned into an instant, one way for every search,
//! shortcutting and primitive that stops on the clock.

use std::time::Instant;

/// The instant `seconds` after `start`; `None` (no deadline) for an infinite or NaN span.
pub fn deadline(start: Instant, seconds: f64) -> Option<Instant> {
    let span = std::time::Duration::try_from_secs_f64(seconds.max(0.0)).ok()?;
    start.checked_add(span)
}

/// The time left until `until` (s): at least a millisecond, for a search to report on
/// what it had.
pub fn time_left(until: Instant) -> f64 {
    until
        .saturating_duration_since(Instant::now())
        .as_secs_f64()
        .max(1e-3)
}

/// Whether `deadline` has come (never, without one).
pub fn passed(deadline: Option<Instant>) -> bool {
    deadline.is_some_and(|d| Instant::now() >= d)
}

/// How a plan's time limit (`plan --time`) is spent: it bounds the whole command (loading,
/// search, robustness checks, shortcutting, a reach with `--grasp`, writing). Each part stops a reserve before the
/// limit, for what must follow it: re-simulating the path (the check every plan passes)
/// and writing it, whose cost grows with the path's steps. With `--grasp` the pushing has
/// half of the limit, the reach what is left.
pub struct CommandDeadline {
    /// When the pushing's search and finishing stop.
    pub pushing: Instant,
    /// When the last part (the reach, or the pushing without one) stops.
    pub last: Instant,
}

impl CommandDeadline {
    /// Propagation steps a second of re-simulating takes at least (a few times slower than
    /// this machine: BENCHMARKS.md, "Propagation").
    const STEPS_PER_SECOND: f64 = 50_000.0;

    /// The deadlines of a command started at `started` with `--time seconds` in `scene`,
    /// reaching a grasp after pushing if `then_reach`. The reserve is what ten of the
    /// scene's longest controls take to re-simulate, at most a fifth of the limit: 10 ms
    /// at the default `planner.step` and `max_duration`, and the fifth when a control has
    /// thousands of steps (a path of 24 000 steps of `step: 0.0001` took 0.29 s to
    /// re-simulate after a 1 s search).
    pub fn new(
        started: Instant,
        seconds: f64,
        scene: &crate::Scene,
        then_reach: bool,
    ) -> CommandDeadline {
        let longest = scene.planner.max_duration / scene.planner.step;
        let reserve = (10.0 * longest / Self::STEPS_PER_SECOND).min(0.2 * seconds);
        // `options.check` bounds `seconds` by a day: never `None`.
        let at = |seconds: f64| deadline(started, seconds).unwrap_or(started);
        let last = at(seconds - reserve);
        CommandDeadline {
            pushing: if then_reach {
                at(0.5 * seconds - reserve)
            } else {
                last
            },
            last,
        }
    }

    /// The time left for the pushing's search (s).
    pub fn search_time(&self) -> f64 {
        time_left(self.pushing)
    }

    /// The time left for a reach (s).
    pub fn reach_time(&self) -> f64 {
        time_left(self.last)
    }
}
