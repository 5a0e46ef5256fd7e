//! Deadlines: a time budget in seconds turned into an instant, one way for every search,
//! shortcutting and primitive that stops on the clock.

use std::time::Instant;

/// The instant `seconds` after `start`; `None` (no deadline) for an infinite or NaN span.
pub fn deadline(start: Instant, seconds: f64) -> Option<Instant> {
    let span = std::time::Duration::try_from_secs_f64(seconds.max(0.0)).ok()?;
    start.checked_add(span)
}

/// Whether `deadline` has come (never, without one).
pub fn passed(deadline: Option<Instant>) -> bool {
    deadline.is_some_and(|d| Instant::now() >= d)
}
