//! Executable trajectories: the plan's steps time-parameterised so that no joint exceeds
//! its URDF velocity limit or the scene's acceleration limit and no pushed object moves
//! faster than the scene allows, sampled at a fixed rate, with the object poses the model
//! predicts along it.

use crate::math::{wrap_angle, Pose2};
use crate::planning::path::PathControl;
use crate::propagate::SemiDynamic;
use crate::robot::Robot;
use crate::scene::file::PhysicsModel;
use crate::scene::{Scene, TrajectoryParams};
use crate::semi_dynamic::TracePoint;
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

impl Trajectory {
    /// The joint motion from `q` back to the trajectory's start, the way it came: `q` is
    /// where the arm stands on the trajectory (its end after a whole play, or where a play
    /// cut short left it), placed on the nearest of its segments, which it then runs
    /// backwards at the same pace, every object held at `objects` (a retreat pushes
    /// nothing the model knows of). Never a jump to a sample the arm did not reach.
    pub fn retraced(&self, q: &DVector<f64>, objects: &[Pose2]) -> Trajectory {
        let samples: Vec<DVector<f64>> = self
            .q
            .iter()
            .map(|s| DVector::from_column_slice(s))
            .collect();
        // The segment (j, j + 1) nearest `q`, and where on it `q` lies (0 at j, 1 at j + 1).
        let on_segment = |j: usize| {
            let along = &samples[j + 1] - &samples[j];
            let u = match along.norm_squared() {
                0.0 => 0.0,
                length => ((q - &samples[j]).dot(&along) / length).clamp(0.0, 1.0),
            };
            (u, (q - (&samples[j] + along * u)).norm())
        };
        let (j, u) = (0..samples.len().saturating_sub(1))
            .map(|j| (j, on_segment(j)))
            .min_by(|a, b| a.1 .1.total_cmp(&b.1 .1))
            .map_or((0, 0.0), |(j, (u, _))| (j, u));
        // From `q` to sample j (the part u of its segment), then back sample by sample;
        // no second sample where `q` is on sample j itself.
        let to_j = self
            .times
            .get(j + 1)
            .map_or(0.0, |t| u * (t - self.times[j]));
        let gaps =
            std::iter::once(to_j).chain((0..j).rev().map(|k| self.times[k + 1] - self.times[k]));
        let (mut times, mut path) = (vec![0.0], vec![q.iter().copied().collect::<Vec<f64>>()]);
        for (k, gap) in (0..=j).rev().zip(gaps).filter(|(_, gap)| *gap > 0.0) {
            times.push(times.last().expect("not empty") + gap);
            path.push(self.q[k].clone());
        }
        let held: Vec<[f64; 3]> = objects.iter().map(|p| [p.x, p.y, p.theta]).collect();
        Trajectory {
            rate: self.rate,
            objects: vec![held; times.len()],
            times,
            q: path,
        }
    }
}

/// A trajectory played as a controller plays it: the joint values at increasing times,
/// linearly interpolated between its samples and held at its end.
pub struct Playback<'a> {
    trajectory: &'a Trajectory,
    samples: Vec<DVector<f64>>,
    segment: usize,
}

impl<'a> Playback<'a> {
    /// `trajectory` (at least one sample) from its start.
    pub fn new(trajectory: &'a Trajectory) -> Playback<'a> {
        Playback {
            samples: trajectory
                .q
                .iter()
                .map(|q| DVector::from_column_slice(q))
                .collect(),
            trajectory,
            segment: 0,
        }
    }

    /// The joint values at `tau` (s into the trajectory; never earlier than the last call's).
    pub fn at(&mut self, tau: f64) -> DVector<f64> {
        let times = &self.trajectory.times;
        while self.segment + 2 < self.samples.len() && times[self.segment + 1] <= tau {
            self.segment += 1;
        }
        let k = self.segment;
        if self.samples.len() == 1 {
            return self.samples[0].clone();
        }
        let s = ((tau - times[k]) / (times[k + 1] - times[k])).clamp(0.0, 1.0);
        &self.samples[k] * (1.0 - s) + &self.samples[k + 1] * s
    }

    /// The sample at or before the last time asked for (its index).
    pub fn segment(&self) -> usize {
        self.segment
    }

    /// The trajectory's duration (s).
    pub fn end(&self) -> f64 {
        self.trajectory.times.last().copied().unwrap_or(0.0)
    }
}

/// The shortest time (s) in which the straight joint motion `from -> to` keeps every joint
/// within its URDF velocity limit.
pub fn joint_motion_time(robot: &Robot, from: &DVector<f64>, to: &DVector<f64>) -> f64 {
    (0..robot.dof())
        .map(|i| (to[i] - from[i]).abs() / robot.chain.dof_joint(i).max_velocity)
        .fold(0.0, f64::max)
}

/// Samples per second of executable trajectories.
pub const TRAJECTORY_RATE: f64 = 50.0;

/// The executable trajectory of `controls` in `scene`, whose every step's state is
/// `step_states` (the start first), at [`TRAJECTORY_RATE`]. Quasistatic pushing does not
/// depend on speed: the trajectory stops at each control's end, and its limits are the
/// scene's. Semi-dynamic pushing does: the trajectory keeps the plan's pace ([`paced`]).
pub fn executable(
    scene: &Scene,
    controls: &[PathControl],
    step_states: &[State],
) -> Result<Trajectory, String> {
    if scene.physics.model == PhysicsModel::SemiDynamic {
        let paced = paced(scene, step_states, TRAJECTORY_RATE)?;
        return Ok(Trajectory {
            rate: TRAJECTORY_RATE,
            times: paced.times,
            q: paced
                .states
                .iter()
                .map(|s| s.q.as_slice().to_vec())
                .collect(),
            objects: paced
                .states
                .iter()
                .map(|s| s.objects.iter().map(|p| [p.x, p.y, p.theta]).collect())
                .collect(),
        });
    }
    let radii: Vec<f64> = scene.objects.iter().map(|o| o.bounding_radius).collect();
    let stops: Vec<usize> = controls
        .iter()
        .scan(0, |step, c| {
            *step += c.steps;
            Some(*step)
        })
        .collect();
    Ok(time_parameterise(
        &scene.robot,
        &radii,
        step_states,
        &stops,
        scene.planner.step,
        &scene.trajectory,
        TRAJECTORY_RATE,
    ))
}

/// A semi-dynamic plan at its own pace, sampled at a fixed rate.
#[derive(Clone, Debug, Default)]
pub struct Paced {
    /// Sample times (s); the last is the plan's end.
    pub times: Vec<f64>,
    /// The arm and the objects at each sample.
    pub states: Vec<State>,
    /// The plan step (from step state k to k + 1) each sample falls in.
    pub steps: Vec<usize>,
    /// When each step starts (s), and the plan's end last.
    pub step_starts: Vec<f64>,
}

/// The plan of a semi-dynamic `scene` through `step_states` as the model has it happen,
/// sampled at `rate` Hz: each step's joint motion takes the plan's step `dt` at constant
/// joint speed (the pushers' speed is part of the model), then the arm holds still while
/// the objects come to rest; objects at the engine's poses, interpolated between its
/// steps. Stopping at once between steps is the model's too (actions are velocity steps).
/// An error if a step does not come to rest or does not reach the plan's next state.
pub fn paced(scene: &Scene, step_states: &[State], rate: f64) -> Result<Paced, String> {
    let mut model = SemiDynamic::of(scene).ok_or("the scene's physics is not semi_dynamic")?;
    let dt = scene.planner.step;
    let robot = &scene.robot;
    let mut paced = Paced::default();
    let Some(first) = step_states.first() else {
        return Ok(paced);
    };
    let mut from = robot.link_poses(&first.q);
    let (mut start, mut sample) = (0.0, 0usize);
    for (k, pair) in step_states.windows(2).enumerate() {
        let (a, b) = (&pair[0], &pair[1]);
        let to = robot.link_poses(&b.q);
        let rest = model
            .transition(scene, &a.objects, &from, &to, dt, true)
            .map_err(|u| {
                format!(
                    "step {k}: {} still moves at {:.3} m/s after t_max",
                    scene.objects[u.object].name, u.speed
                )
            })?;
        if rest.poses != b.objects {
            return Err(format!(
                "step {k}: the engine does not reach the plan's next state"
            ));
        }
        paced.step_starts.push(start);
        let end = start + rest.trace.last().map_or(dt, |p| p.time);
        while (sample as f64 / rate) < end {
            let t = sample as f64 / rate;
            let tau = t - start;
            let f = (tau / dt).min(1.0);
            paced.times.push(t);
            paced.states.push(State {
                q: &a.q + f * (&b.q - &a.q),
                objects: poses_at(&rest.trace, tau),
            });
            paced.steps.push(k);
            sample += 1;
        }
        from = to;
        start = end;
    }
    paced.step_starts.push(start);
    paced.times.push(start);
    paced.states.push(step_states.last().unwrap().clone());
    paced.steps.push(step_states.len().saturating_sub(2));
    Ok(paced)
}

/// The objects' poses at `time` in a trace, interpolated between its points.
fn poses_at(trace: &[TracePoint], time: f64) -> Vec<Pose2> {
    let after = trace.partition_point(|p| p.time <= time);
    match (after.checked_sub(1).map(|i| &trace[i]), trace.get(after)) {
        (Some(a), Some(b)) => {
            let f = (time - a.time) / (b.time - a.time);
            a.poses
                .iter()
                .zip(&b.poses)
                .map(|(p, q)| p.lerp(q, f))
                .collect()
        }
        (Some(a), None) => a.poses.clone(),
        (None, Some(b)) => b.poses.clone(),
        (None, None) => Vec::new(),
    }
}

/// Share of the acceleration limit spent on speeding up and slowing down along the path;
/// the rest is kept for the path's curvature (`q'' s'^2`).
const ALONG_PATH: f64 = 0.8;

/// Times the plan's steps and samples them at `rate` Hz.
///
/// The path is the sequence of step states, parameterised by the step index `s`; within
/// a control it is smooth, and at the controls' boundaries (`stops`, step indices) it has
/// kinks, where the arm comes to rest. A forward-backward pass over the squared path
/// speed `x = s'^2` (the phase-plane method of time-optimal path parameterisation)
/// finds the fastest profile that
/// - keeps every joint within its URDF velocity limit, every object point within
///   `max_object_speed`, and is no faster than the plan's own step `dt`;
/// - keeps every joint's acceleration `q' s'' + q'' s'^2` within
///   `max_joint_acceleration`: 80 % of it for `s''`, the rest for the curvature term;
/// - starts and ends at rest, and stops at every entry of `stops`.
///
/// Each step then takes `2 / (s'_k + s'_{k+1})` seconds with `s''` constant, and samples
/// interpolate along the path. Quasistatic pushing does not depend on speed, so the
/// predicted object poses along the path stay those of the plan.
pub fn time_parameterise(
    robot: &Robot,
    object_radii: &[f64],
    steps: &[State],
    stops: &[usize],
    dt: f64,
    limits: &TrajectoryParams,
    rate: f64,
) -> Trajectory {
    let profile = PathProfile::new(robot, object_radii, steps, stops, dt, limits, rate);
    let end = *profile.knots.last().unwrap();
    let mut trajectory = Trajectory {
        rate,
        times: vec![],
        q: vec![],
        objects: vec![],
    };
    let count = (end * rate).floor() as usize;
    let mut times: Vec<f64> = (0..=count).map(|m| m as f64 / rate).collect();
    if end - times.last().unwrap() > 1e-12 {
        times.push(end);
    }
    let mut segment = 0;
    for t in times {
        let knots = &profile.knots;
        while segment + 1 < knots.len() - 1 && knots[segment + 1] < t {
            segment += 1;
        }
        let s = if knots.len() > 1 {
            profile.progress(segment, t)
        } else {
            0.0
        };
        let (a, b) = (&steps[segment], &steps[(segment + 1).min(steps.len() - 1)]);
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
                    let at = p.lerp(r, s);
                    [at.x, at.y, at.theta]
                })
                .collect(),
        );
    }
    trajectory
}

/// The timed path: the path speed at each step state and when each is reached.
struct PathProfile {
    /// `s'` at each step state (steps per second).
    speed: Vec<f64>,
    /// Time at each step state (s).
    knots: Vec<f64>,
}

impl PathProfile {
    fn new(
        robot: &Robot,
        object_radii: &[f64],
        steps: &[State],
        stops: &[usize],
        dt: f64,
        limits: &TrajectoryParams,
        rate: f64,
    ) -> PathProfile {
        let n = steps.len();
        if n < 2 {
            return PathProfile {
                speed: vec![0.0; n],
                knots: vec![0.0; n],
            };
        }
        let dof = robot.dof();
        let a_max = limits.max_joint_acceleration;
        let v_max: Vec<f64> = (0..dof)
            .map(|j| robot.chain.dof_joint(j).max_velocity)
            .collect();
        // q' on each segment k (per step).
        let dq: Vec<DVector<f64>> = steps.windows(2).map(|w| &w[1].q - &w[0].q).collect();
        // Squared-speed limits at each state: velocities on the neighbouring segments,
        // object speed, the plan's own pace, and the curvature's share of acceleration.
        let mut x_max = vec![(1.0 / dt).powi(2); n];
        for (k, d) in dq.iter().enumerate() {
            let object_travel = steps[k]
                .objects
                .iter()
                .zip(&steps[k + 1].objects)
                .zip(object_radii)
                .map(|((a, b), r)| {
                    (b.translation() - a.translation()).norm()
                        + r * wrap_angle(b.theta - a.theta).abs()
                })
                .fold(0.0, f64::max);
            let mut limit = (limits.max_object_speed / object_travel).powi(2);
            for j in 0..dof {
                limit = limit.min((v_max[j] / d[j].abs()).powi(2));
            }
            for i in [k, k + 1] {
                x_max[i] = x_max[i].min(limit);
            }
        }
        // At a state the path bends: q' jumps by the curvature q'' (per step). Over many
        // steps per sample that is an acceleration q'' s'^2; with a step longer than a
        // sample (s' < rate) the samples see the whole jump s' q'' within one sample
        // period: q'' s' max(s', rate) must stay within the curvature's share.
        for k in 1..n - 1 {
            let curvature = (&dq[k] - &dq[k - 1]).amax();
            let share = (1.0 - ALONG_PATH) * a_max / curvature;
            let x = if share <= rate * rate {
                (share / rate).powi(2)
            } else {
                share
            };
            x_max[k] = x_max[k].min(x);
        }
        x_max[0] = 0.0;
        x_max[n - 1] = 0.0;
        for &k in stops {
            if k < n {
                x_max[k] = 0.0;
            }
        }
        // Largest s'' on each segment.
        let u_max: Vec<f64> = dq
            .iter()
            .map(|d| {
                (0..dof)
                    .map(|j| ALONG_PATH * a_max / d[j].abs())
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        // Forward (speeding up) and backward (slowing down) passes: x_{k+1} <= x_k + 2 u.
        let mut x = x_max.clone();
        for k in 0..n - 1 {
            x[k + 1] = x[k + 1].min(x[k] + 2.0 * u_max[k]);
        }
        for k in (0..n - 1).rev() {
            x[k] = x[k].min(x[k + 1] + 2.0 * u_max[k]);
        }
        let speed: Vec<f64> = x.iter().map(|x| x.max(0.0).sqrt()).collect();
        let mut knots = vec![0.0];
        for k in 0..n - 1 {
            let duration = if speed[k] + speed[k + 1] > 0.0 {
                2.0 / (speed[k] + speed[k + 1])
            } else {
                // At rest at both ends (a one-step control): speed up for half the step,
                // slow down for the other half.
                2.0 / u_max[k].sqrt()
            };
            knots.push(knots[k] + duration.min(f64::MAX));
        }
        PathProfile { speed, knots }
    }

    /// How far along segment `k` (0..1) the path is at time `t`.
    fn progress(&self, k: usize, t: f64) -> f64 {
        let (t0, t1) = (self.knots[k], self.knots[k + 1]);
        let tau = (t - t0).clamp(0.0, t1 - t0);
        let (v0, v1) = (self.speed[k], self.speed[k + 1]);
        if v0 + v1 > 0.0 {
            // Constant s'' = (v1^2 - v0^2) / 2 over the unit step.
            let u = (v1 * v1 - v0 * v0) / 2.0;
            (v0 * tau + 0.5 * u * tau * tau).clamp(0.0, 1.0)
        } else {
            // Rest to rest within the step: s'' = +u for the first half, -u after.
            let half = 0.5 * (t1 - t0);
            let u = 1.0 / (half * half);
            if tau <= half {
                0.5 * u * tau * tau
            } else {
                1.0 - 0.5 * u * (t1 - t0 - tau).powi(2)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One joint from 0 to 0.3 rad in 0.3 s, sampled every 0.1 s.
    fn ramp() -> Trajectory {
        Trajectory {
            rate: 10.0,
            times: vec![0.0, 0.1, 0.2, 0.3],
            q: vec![vec![0.0], vec![0.1], vec![0.2], vec![0.3]],
            objects: vec![vec![[0.5, 0.0, 0.0]]; 4],
        }
    }

    fn close(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
    }

    #[test]
    fn a_retrace_runs_back_from_where_the_arm_stands_never_past_it() {
        let held = [Pose2::new(0.6, 0.1, 0.2)];
        let q = |v: f64| DVector::from_vec(vec![v]);
        // From the end, after a whole play: every sample backwards at the same pace.
        // Midway, where a play cut short left the arm: only the samples behind it. On a
        // sample: that sample once.
        for (at, path, times) in [
            (0.3, vec![0.3, 0.2, 0.1, 0.0], vec![0.0, 0.1, 0.2, 0.3]),
            (0.15, vec![0.15, 0.1, 0.0], vec![0.0, 0.05, 0.15]),
            (0.2, vec![0.2, 0.1, 0.0], vec![0.0, 0.1, 0.2]),
        ] {
            let back = ramp().retraced(&q(at), &held);
            let joint: Vec<f64> = back.q.iter().map(|s| s[0]).collect();
            assert!(close(&joint, &path), "from {at}: {joint:?}");
            assert!(close(&back.times, &times), "from {at}: {:?}", back.times);
            assert!(back.objects.iter().all(|o| o == &vec![[0.6, 0.1, 0.2]]));
        }
    }
}
