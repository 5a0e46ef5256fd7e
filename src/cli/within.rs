//! Command-line values checked against the limits table ([`pushplan::limits`]) as they are
//! parsed: a count or a duration outside its limit is refused with the option and the
//! limit named, before any work (and before any allocation of its size).

use pushplan::limits::{Front, Limit};

/// A parser of a count within `limit` (as a `T`: `usize`, `u32`, `u64`).
pub fn count<T: TryFrom<u64>>(
    limit: &'static Limit,
) -> impl Fn(&str) -> Result<T, String> + Clone + Send + Sync + 'static {
    move |text: &str| {
        let value: u64 = text
            .parse()
            .map_err(|_| format!("{}: must be a whole number, got '{text}'", limit.option))?;
        limit.check(Front::CommandLine, value)?;
        T::try_from(value).map_err(|_| format!("{}: too large for this machine", limit.option))
    }
}

/// A parser of a real number within `limit`.
pub fn real(
    limit: &'static Limit,
) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |text: &str| {
        let value: f64 = text
            .parse()
            .map_err(|_| format!("{}: must be a number, got '{text}'", limit.option))?;
        limit.check(Front::CommandLine, value)
    }
}
