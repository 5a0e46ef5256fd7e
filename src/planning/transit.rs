//! Transit: a straight line in configuration space with the objects held still (DARRT's
//! primitive; reaching a grasp and the manipulation graph move the arm the same way).

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
    (1..=segments).map(move |k| {
        let mut q = from.lerp(to, k as f64 / segments as f64);
        // A point of the line lies between its ends; rounding must not carry it past
        // them (a joint held at its limit along the line would leave its range).
        for ((x, a), b) in q.iter_mut().zip(from.iter()).zip(to.iter()) {
            *x = x.clamp(a.min(*b), a.max(*b));
        }
        q
    })
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_joint_held_at_its_limit_stays_exactly_there_along_a_line() {
        // (1 - t) (-1.6) + t (-1.6) rounds below -1.6 for many t: the lower limit of the
        // WAM's j6, where a PickPlace transit was once refused as "outside its limits".
        for end in 1..200 {
            let from = DVector::from_vec(vec![-1.6, 0.0]);
            let to = DVector::from_vec(vec![-1.6, 0.02 * end as f64]);
            for q in transit_points(&from, &to) {
                assert!(q[0] == -1.6, "{} on a line ending {end}", q[0]);
            }
        }
    }
}
