//! Executable trajectories: the plan's steps time-parameterised so that no joint exceeds
//! its URDF velocity limit, sampled at a fixed rate, with the object poses the model
//! predicts along it.
//!
//! Quasistatic pushing does not depend on speed, so stretching a step in time does not
//! change where the objects go.

use crate::math::wrap_angle;
use crate::robot::Robot;
use crate::state::State;
use nalgebra::DVector;
use serde::{Deserialize, Serialize};

/// Joint values and object poses sampled at `rate` Hz (the last sample is the end).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Trajectory {
    /// Samples per second.
    pub rate: f64,
    /// Sample times (s).
    pub times: Vec<f64>,
    /// Joint values at each sample.
    pub q: Vec<Vec<f64>>,
    /// Object poses `[x, y, yaw]` at each sample.
    pub objects: Vec<Vec<[f64; 3]>>,
}

/// The shortest time (s) in which the straight joint motion `from -> to` keeps every joint
/// within its URDF velocity limit.
pub fn joint_motion_time(robot: &Robot, from: &DVector<f64>, to: &DVector<f64>) -> f64 {
    (0..robot.dof())
        .map(|i| (to[i] - from[i]).abs() / robot.chain.dof_joint(i).max_velocity)
        .fold(0.0, f64::max)
}

/// Times each step `k -> k+1` so that every joint moves at most at its velocity limit
/// (and no faster than the plan's `dt`), then samples at `rate` Hz by linear interpolation.
pub fn time_parameterise(robot: &Robot, steps: &[State], dt: f64, rate: f64) -> Trajectory {
    let mut knots = vec![0.0];
    for w in steps.windows(2) {
        let slowest = joint_motion_time(robot, &w[0].q, &w[1].q).max(dt);
        knots.push(knots.last().unwrap() + slowest);
    }
    let end = *knots.last().unwrap();
    let mut trajectory = Trajectory {
        rate,
        times: vec![],
        q: vec![],
        objects: vec![],
    };
    let count = (end * rate).floor() as usize;
    let mut segment = 0;
    for m in 0..=count + 1 {
        let t = if m <= count { m as f64 / rate } else { end };
        if m == count + 1 && (t - trajectory.times.last().copied().unwrap_or(-1.0)).abs() < 1e-12 {
            break;
        }
        while segment + 1 < knots.len() - 1 && knots[segment + 1] < t {
            segment += 1;
        }
        let (a, b) = (&steps[segment], &steps[(segment + 1).min(steps.len() - 1)]);
        let span = knots.get(segment + 1).map_or(0.0, |k| k - knots[segment]);
        let s = if span > 0.0 {
            ((t - knots[segment]) / span).clamp(0.0, 1.0)
        } else {
            0.0
        };
        trajectory.times.push(t);
        trajectory.q.push(
            a.q.iter()
                .zip(b.q.iter())
                .map(|(x, y)| x + s * (y - x))
                .collect(),
        );
        trajectory.objects.push(
            a.objects
                .iter()
                .zip(&b.objects)
                .map(|(p, r)| {
                    [
                        p.x + s * (r.x - p.x),
                        p.y + s * (r.y - p.y),
                        wrap_angle(p.theta + s * wrap_angle(r.theta - p.theta)),
                    ]
                })
                .collect(),
        );
    }
    trajectory
}
