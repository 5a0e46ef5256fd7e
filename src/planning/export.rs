//! A plan's executable trajectory in formats other programs read (`pushplan export`):
//!
//! - [`ExportFormat::JointTrajectory`]: a ROS `trajectory_msgs/JointTrajectory` as YAML,
//!   the way `ros2 topic pub` takes a message, for a `joint_trajectory_controller` or
//!   MoveIt's execution;
//! - [`ExportFormat::Csv`]: one row per sample, for spreadsheets, NumPy and MATLAB.
//!
//! Both carry the trajectory's own samples (at [`crate::planning::trajectory::TRAJECTORY_RATE`]
//! Hz, the last at the trajectory's end) with joint velocities and accelerations estimated
//! from them ([`JointMotion`]).

use crate::planning::plan_file::PlanFile;
use crate::planning::trajectory::Trajectory;
use std::fmt::Write;

/// What `pushplan export` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportFormat {
    /// `trajectory_msgs/JointTrajectory` as YAML (`--format joint-trajectory`).
    JointTrajectory,
    /// Comma-separated values with a header row (`--format csv`).
    Csv,
}

impl ExportFormat {
    /// Every format, in the order the CLI lists them.
    pub const ALL: [ExportFormat; 2] = [ExportFormat::JointTrajectory, ExportFormat::Csv];

    /// The format's name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            ExportFormat::JointTrajectory => "joint-trajectory",
            ExportFormat::Csv => "csv",
        }
    }

    /// The exported text of `plan`'s trajectory.
    pub fn write(self, plan: &PlanFile) -> String {
        match self {
            ExportFormat::JointTrajectory => joint_trajectory_yaml(plan),
            ExportFormat::Csv => csv(plan),
        }
    }
}

impl std::str::FromStr for ExportFormat {
    type Err = String;

    fn from_str(name: &str) -> Result<Self, String> {
        crate::input::by_name(&ExportFormat::ALL, ExportFormat::name, "format", name)
    }
}

/// Joint velocities and accelerations along a trajectory's samples.
///
/// The trajectory is the planned path timed within the joints' limits and sampled; the
/// velocity at a sample is the slope of the chord through its two neighbours, i.e. the
/// mean joint velocity over that interval. A mean never exceeds the largest value, so a
/// trajectory within the URDF's velocity limits gives velocities within them. The
/// accelerations are the same chords taken of the velocities (one-sided at the ends). The
/// arm is at rest at the first and the last sample, as the trajectory starts and ends.
#[derive(Clone, Debug, PartialEq)]
pub struct JointMotion {
    /// Per sample, per joint (rad/s, or m/s for prismatic joints).
    pub velocities: Vec<Vec<f64>>,
    /// Per sample, per joint (rad/s², or m/s²).
    pub accelerations: Vec<Vec<f64>>,
}

impl JointMotion {
    /// The motion along `trajectory`'s samples (times strictly increasing, as written).
    pub fn of(trajectory: &Trajectory) -> JointMotion {
        let times = &trajectory.times;
        let n = times.len();
        let mut velocities = chords(times, &trajectory.q);
        if let Some(last) = n.checked_sub(1) {
            velocities[0].fill(0.0);
            velocities[last].fill(0.0);
        }
        let mut accelerations = chords(times, &velocities);
        if n >= 2 {
            // One-sided over two intervals where there are two: the last interval may be
            // a short remainder of the rate, over which the rest-to-rest chord would
            // overstate the stop.
            let (a, b) = (n.min(3) - 1, n - n.min(3));
            accelerations[0] = slope(&velocities[0], &velocities[a], times[a] - times[0]);
            accelerations[n - 1] =
                slope(&velocities[b], &velocities[n - 1], times[n - 1] - times[b]);
        }
        JointMotion {
            velocities,
            accelerations,
        }
    }
}

/// Per sample, the slope of `values` over the chord through its neighbours (the sample
/// itself at either end).
fn chords(times: &[f64], values: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let n = times.len();
    (0..n)
        .map(|k| {
            let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
            if a == b {
                vec![0.0; values[k].len()]
            } else {
                slope(&values[a], &values[b], times[b] - times[a])
            }
        })
        .collect()
}

fn slope(from: &[f64], to: &[f64], dt: f64) -> Vec<f64> {
    from.iter().zip(to).map(|(a, b)| (b - a) / dt).collect()
}

/// A real number as YAML reads a float: Rust's shortest round-trip digits, never in
/// exponent form, always with a decimal point (`1.0`, not `1`: ROS 2's Python messages
/// refuse an integer where a float64 is declared).
fn yaml_float(x: f64) -> String {
    let text = x.to_string();
    if text.contains('.') {
        text
    } else {
        text + ".0"
    }
}

/// A name as a single-quoted YAML scalar (any text).
fn yaml_string(name: &str) -> String {
    format!("'{}'", name.replace('\'', "''"))
}

fn yaml_list(values: &[f64]) -> String {
    let items: Vec<String> = values.iter().map(|v| yaml_float(*v)).collect();
    format!("[{}]", items.join(", "))
}

/// `builtin_interfaces/Duration` of `seconds` (>= 0): whole seconds and nanoseconds, the
/// nanoseconds below 10^9.
pub fn ros_duration(seconds: f64) -> (i32, u32) {
    let total = (seconds * 1e9).round() as i64;
    (
        (total / 1_000_000_000) as i32,
        (total % 1_000_000_000) as u32,
    )
}

/// `plan`'s trajectory as a `trajectory_msgs/JointTrajectory` in YAML: the header's stamp
/// zero (a controller starts it on receipt), the plan's joint names, and per sample its
/// positions, velocities, accelerations, no efforts, and its time from the start.
pub fn joint_trajectory_yaml(plan: &PlanFile) -> String {
    let t = &plan.trajectory;
    let motion = JointMotion::of(t);
    let names: Vec<String> = plan.joints.iter().map(|n| yaml_string(n)).collect();
    let mut yaml = String::new();
    let _ = writeln!(
        yaml,
        "# trajectory_msgs/msg/JointTrajectory: the executable trajectory of plan '{}' \
         (scene '{}'), {} samples at {} Hz, {} s.\n\
         # Velocities and accelerations are the positions' chord slopes (pushplan export).\n\
         # ros2 topic pub --once /CONTROLLER/joint_trajectory trajectory_msgs/msg/JointTrajectory \"$(cat FILE)\"",
        plan.scene_name.replace('\n', " "),
        plan.scene.replace('\n', " "),
        t.times.len(),
        t.rate,
        t.times.last().copied().unwrap_or(0.0)
    );
    yaml.push_str("header:\n  stamp: {sec: 0, nanosec: 0}\n  frame_id: ''\n");
    let _ = writeln!(yaml, "joint_names: [{}]", names.join(", "));
    if t.times.is_empty() {
        yaml.push_str("points: []\n");
        return yaml;
    }
    yaml.push_str("points:\n");
    for (k, time) in t.times.iter().enumerate() {
        let (sec, nanosec) = ros_duration(*time);
        let _ = write!(
            yaml,
            "  - positions: {}\n    velocities: {}\n    accelerations: {}\n    effort: []\n    \
             time_from_start: {{sec: {sec}, nanosec: {nanosec}}}\n",
            yaml_list(&t.q[k]),
            yaml_list(&motion.velocities[k]),
            yaml_list(&motion.accelerations[k]),
        );
    }
    yaml
}

/// A CSV field: quoted (RFC 4180) when it holds a comma, a quote or a line break.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// `plan`'s trajectory as CSV: a header row, then per sample the time (s), each joint's
/// position, velocity and acceleration (named `JOINT`, `JOINT.velocity`,
/// `JOINT.acceleration`), and each object's predicted pose (`OBJECT.x`, `OBJECT.y` in m,
/// `OBJECT.yaw` in rad; world frame).
pub fn csv(plan: &PlanFile) -> String {
    let t = &plan.trajectory;
    let motion = JointMotion::of(t);
    let mut header = vec!["time".to_string()];
    for suffix in ["", ".velocity", ".acceleration"] {
        header.extend(
            plan.joints
                .iter()
                .map(|j| csv_field(&format!("{j}{suffix}"))),
        );
    }
    for object in &plan.objects {
        for axis in ["x", "y", "yaw"] {
            header.push(csv_field(&format!("{object}.{axis}")));
        }
    }
    let mut csv = header.join(",") + "\n";
    for (k, time) in t.times.iter().enumerate() {
        let row = std::iter::once(*time)
            .chain(t.q[k].iter().copied())
            .chain(motion.velocities[k].iter().copied())
            .chain(motion.accelerations[k].iter().copied())
            .chain(t.objects[k].iter().flatten().copied());
        let fields: Vec<String> = row.map(|v| v.to_string()).collect();
        csv.push_str(&fields.join(","));
        csv.push('\n');
    }
    csv
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trajectory(times: &[f64], q: &[f64]) -> Trajectory {
        Trajectory {
            rate: 50.0,
            times: times.to_vec(),
            q: q.iter().map(|v| vec![*v]).collect(),
            objects: times.iter().map(|_| vec![]).collect(),
        }
    }

    #[test]
    fn a_parabola_gets_its_closed_form_velocity_and_acceleration() {
        // q = t^2 / 2 (acceleration 1) sampled every 0.1 s: the chord slope through the
        // neighbours is exactly q'(t) = t for a parabola; the chord of those is 1.
        let times: Vec<f64> = (0..=10).map(|k| k as f64 * 0.1).collect();
        let q: Vec<f64> = times.iter().map(|t| t * t / 2.0).collect();
        let motion = JointMotion::of(&trajectory(&times, &q));
        for (v, t) in motion.velocities.iter().zip(&times).take(10).skip(1) {
            assert!((v[0] - t).abs() < 1e-12, "{t}");
        }
        for k in 2..9 {
            assert!((motion.accelerations[k][0] - 1.0).abs() < 1e-9, "{k}");
        }
        assert_eq!(motion.velocities[0], [0.0]);
        assert_eq!(motion.velocities[10], [0.0]);
    }

    #[test]
    fn durations_split_into_seconds_and_nanoseconds() {
        assert_eq!(ros_duration(0.0), (0, 0));
        assert_eq!(ros_duration(0.02), (0, 20_000_000));
        assert_eq!(ros_duration(1.5), (1, 500_000_000));
        assert_eq!(ros_duration(2.9999999999), (3, 0));
    }

    #[test]
    fn floats_keep_a_decimal_point_and_names_are_quoted() {
        assert_eq!(yaml_float(1.0), "1.0");
        assert_eq!(yaml_float(-0.0), "-0.0");
        assert_eq!(yaml_float(1e-7), "0.0000001");
        assert_eq!(yaml_float(0.25), "0.25");
        assert_eq!(yaml_string("it's"), "'it''s'");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(csv_field("joint_1"), "joint_1");
    }
}
