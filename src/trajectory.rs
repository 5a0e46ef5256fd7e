//! Executable trajectories: the plan's steps time-parameterised so that no joint exceeds
//! its URDF velocity limit or the scene's acceleration limit and no pushed object moves
//! faster than the scene allows, sampled at a fixed rate, with the object poses the model
//! predicts along it.
//!
//! Quasistatic pushing does not depend on speed, so stretching a step in time does not
//! change where the objects go.

use crate::math::wrap_angle;
use crate::robot::Robot;
use crate::scene::TrajectoryParams;
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

/// Times the plan's steps and samples them at `rate` Hz by linear interpolation.
///
/// The algorithm is iterative time stretching (the idea of MoveIt's iterative parabolic
/// time parameterisation): the path is the sequence of step states; segment `k` first
/// takes the least time that keeps every joint within its URDF velocity limit, every
/// object point within `max_object_speed`, and no faster than the plan's `dt`. Then
/// each waypoint's joint acceleration, `(v_k - v_{k-1}) / min(dt_{k-1}, dt_k, 1 / rate)`
/// with the segments' joint velocities `v` (at rest before the start and after the end),
/// is brought within `max_joint_acceleration` by stretching both neighbouring segments,
/// sweeping until no waypoint exceeds it. (MoveIt divides by the mean of the two
/// segments; the shorter one, capped at the sample period, keeps the second differences
/// of the samples within the limit too.) Stretching only slows
/// the motion, so velocity limits stay met.
pub fn time_parameterise(
    robot: &Robot,
    object_radii: &[f64],
    steps: &[State],
    dt: f64,
    limits: &TrajectoryParams,
    rate: f64,
) -> Trajectory {
    let durations = segment_durations(robot, object_radii, steps, dt, limits, 1.0 / rate);
    let mut knots = vec![0.0];
    for d in &durations {
        knots.push(knots.last().unwrap() + d);
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

/// Segment durations (s) within the velocity, object-speed and acceleration limits.
fn segment_durations(
    robot: &Robot,
    object_radii: &[f64],
    steps: &[State],
    dt: f64,
    limits: &TrajectoryParams,
    sample_period: f64,
) -> Vec<f64> {
    let dof = robot.dof();
    let deltas: Vec<DVector<f64>> = steps.windows(2).map(|w| &w[1].q - &w[0].q).collect();
    let mut durations: Vec<f64> = steps
        .windows(2)
        .map(|w| {
            let object_travel = w[0]
                .objects
                .iter()
                .zip(&w[1].objects)
                .zip(object_radii)
                .map(|((a, b), r)| {
                    (b.translation() - a.translation()).norm()
                        + r * wrap_angle(b.theta - a.theta).abs()
                })
                .fold(0.0, f64::max);
            joint_motion_time(robot, &w[0].q, &w[1].q)
                .max(object_travel / limits.max_object_speed)
                .max(dt)
        })
        .collect();
    let n = durations.len();
    let a_max = limits.max_joint_acceleration;
    // Waypoint k joins segment k-1 and segment k; segments -1 and n are rest.
    let velocity = |durations: &[f64], k: isize, j: usize| -> f64 {
        if k < 0 || k as usize >= n {
            0.0
        } else {
            deltas[k as usize][j] / durations[k as usize]
        }
    };
    for _sweep in 0..100_000 {
        let mut worst: f64 = 1.0;
        for k in 0..=n {
            let before = k.checked_sub(1).map(|i| durations[i]);
            let after = durations.get(k).copied();
            let shortest = match (before, after) {
                (Some(b), Some(a)) => b.min(a),
                (b, a) => b.or(a).unwrap_or(sample_period),
            };
            // The jump in velocity at a waypoint is spread over the shorter neighbouring
            // segment, and over no more than one sample period: sampled at `rate`, the
            // second differences then stay within the limit.
            let capped = shortest >= sample_period;
            let span = shortest.min(sample_period);
            let ratio = (0..dof)
                .map(|j| {
                    let dv = velocity(&durations, k as isize, j)
                        - velocity(&durations, k as isize - 1, j);
                    dv.abs() / span / a_max
                })
                .fold(0.0, f64::max);
            if ratio > 1.0 {
                // Stretching both neighbours by f slows them by f and, unless the span is
                // capped, lengthens it by f. A hair more: rounding must not leave it over.
                let stretch = if capped { ratio } else { ratio.sqrt() } * (1.0 + 1e-9);
                if k > 0 {
                    durations[k - 1] *= stretch;
                }
                if k < n {
                    durations[k] *= stretch;
                }
            }
            worst = worst.max(ratio);
        }
        if worst <= 1.0 + 1e-6 {
            break;
        }
    }
    durations
}
