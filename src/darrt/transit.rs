//! Transit: a straight line in configuration space with the objects held still.

use crate::state::State;
use crate::validity::{check_state, Invalid};
use crate::Scene;
use nalgebra::DVector;

/// The largest joint motion between two configurations checked along a line (rad, or m
/// for prismatic joints). At 1 m from the joint that is 2 cm.
pub const TRANSIT_RESOLUTION: f64 = 0.02;

/// The number of equal segments a line from `from` to `to` is checked in.
pub fn transit_segments(from: &DVector<f64>, to: &DVector<f64>) -> usize {
    let longest = (to - from).amax();
    ((longest / TRANSIT_RESOLUTION).ceil() as usize).max(1)
}

/// The configurations of the straight line from `from` to `to` after `from`, at
/// [`TRANSIT_RESOLUTION`]: [`transit_segments`] equal steps, `to` last.
pub fn transit_points<'a>(
    from: &'a DVector<f64>,
    to: &'a DVector<f64>,
) -> impl Iterator<Item = DVector<f64>> + 'a {
    let segments = transit_segments(from, to);
    (1..=segments).map(move |k| from.lerp(to, k as f64 / segments as f64))
}

/// Checks the straight joint-space line from `from.q` to `to` with the objects of `from`:
/// every configuration on it (at [`TRANSIT_RESOLUTION`]) after the first is valid.
pub fn check_transit(scene: &Scene, from: &State, to: &DVector<f64>) -> Result<(), Invalid> {
    let mut state = from.clone();
    for q in transit_points(&from.q, to) {
        state.q = q;
        check_state(scene, &state)?;
    }
    Ok(())
}
