//! Trajectories others read (issue 60): `pushplan export` writes a plan's trajectory as a
//! ROS `trajectory_msgs/JointTrajectory` that PyYAML (what `ros2 topic pub` parses
//! messages with) reads with the field types ROS declares, and as CSV; the plan files
//! `plan` and `replan` write match the shipped JSON Schema (`docs/plan.schema.json`),
//! checked by a validator that is not our reader (Python's `jsonschema`). Both use
//! Debian's Python and its packages (`python3-yaml`, `python3-jsonschema`).

use crate::common::{self, Scratch};
use pushplan::planning::observed::ObservedState;
use pushplan::planning::plan_file::PlanFile;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// Debian's Python, with the packages `.ci/install-packages` installs for it.
const DEBIAN_PYTHON: &str = "/usr/bin/python3";

fn pushplan(args: &[&str]) -> (i32, String, String) {
    common::pushplan_in(Path::new("."), args)
}

/// `builtin_interfaces/Time` and `Duration`.
#[derive(Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
struct RosTime {
    sec: i32,
    nanosec: u32,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Header {
    stamp: RosTime,
    frame_id: String,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Point {
    positions: Vec<f64>,
    velocities: Vec<f64>,
    accelerations: Vec<f64>,
    effort: Vec<f64>,
    time_from_start: RosTime,
}

/// `trajectory_msgs/JointTrajectory`'s fields as ROS 2 declares them.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct JointTrajectory {
    header: Header,
    joint_names: Vec<String>,
    points: Vec<Point>,
}

/// The message in `path` as PyYAML reads it, with ROS 2's Python type rules asserted
/// there (a float64 array holds floats, not integers; a duration's fields are integers).
fn ros_message(path: &Path) -> JointTrajectory {
    let script = r#"
import json, sys, yaml
m = yaml.safe_load(open(sys.argv[1]))
for p in m["points"]:
    for field in ("positions", "velocities", "accelerations", "effort"):
        assert all(type(v) is float for v in p[field]), (field, p[field])
    assert all(type(v) is int for v in p["time_from_start"].values())
assert all(type(n) is str for n in m["joint_names"])
print(json.dumps(m))
"#;
    let message = common::python_prints(DEBIAN_PYTHON, script, &[path.as_os_str()]);
    serde_json::from_str(&message).unwrap()
}

/// The time `d` stands for (s).
fn seconds(d: &RosTime) -> f64 {
    d.sec as f64 + d.nanosec as f64 * 1e-9
}

/// Trapezoid-rule integral of `rate` over `times`, from `start`: what a controller that
/// followed the rates would reach.
fn integrate(times: &[f64], start: f64, rate: impl Fn(usize) -> f64) -> Vec<f64> {
    let mut value = vec![start];
    for k in 1..times.len() {
        let last = value[k - 1];
        value.push(last + 0.5 * (rate(k) + rate(k - 1)) * (times[k] - times[k - 1]));
    }
    value
}

#[test]
fn a_plan_exports_as_a_ros_joint_trajectory_and_as_csv() {
    let scratch = Scratch::new("export-trajectory");
    let plan_path = scratch.join("plan.json");
    common::plan_solved(
        "scenes/herb_single_object.yaml",
        &plan_path,
        &["--threads", "1"],
    );
    let plan = PlanFile::read(&plan_path).unwrap();
    let scene = plan.load_scene(&plan_path).unwrap();
    let trajectory = &plan.trajectory;
    let yaml = scratch.join("trajectory.yaml");
    let (code, stdout, stderr) = pushplan(&[
        "export",
        plan_path.to_str().unwrap(),
        "--format",
        "joint-trajectory",
        "--out",
        yaml.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");

    let message = ros_message(&yaml);
    assert_eq!(message.header.stamp, RosTime { sec: 0, nanosec: 0 });
    assert_eq!(message.header.frame_id, "");
    assert_eq!(message.joint_names, plan.joints);
    assert_eq!(message.points.len(), trajectory.times.len());
    let times: Vec<f64> = message
        .points
        .iter()
        .map(|p| seconds(&p.time_from_start))
        .collect();
    for (k, p) in message.points.iter().enumerate() {
        assert!(p.time_from_start.nanosec < 1_000_000_000);
        assert!((times[k] - trajectory.times[k]).abs() <= 1e-9, "{k}");
        assert!(k == 0 || times[k] > times[k - 1], "time goes on at {k}");
        assert_eq!(p.positions, trajectory.q[k], "the positions are the plan's");
        assert!(p.effort.is_empty());
        // A mean velocity never exceeds the largest: within the URDF's limits.
        for (i, v) in p.velocities.iter().enumerate() {
            let limit = scene.robot.chain.dof_joint(i).max_velocity;
            assert!(
                v.abs() <= limit * (1.0 + 1e-9),
                "joint {i} at {k}: {v} > {limit}"
            );
        }
        // Within the scene's acceleration limit, but for the path's slight corners
        // between propagation steps (1.8 against 2.0 here).
        let limit = scene.trajectory.max_joint_acceleration;
        for a in &p.accelerations {
            assert!(a.abs() <= 1.05 * limit, "{a} at {k} (limit {limit})");
        }
    }
    let rest = vec![0.0; plan.joints.len()];
    assert_eq!(message.points[0].velocities, rest, "starts at rest");
    assert_eq!(
        message.points.last().unwrap().velocities,
        rest,
        "ends at rest"
    );
    // A controller following the velocities reaches the positions, and following the
    // accelerations the velocities (the trapezoid rule's error at 50 Hz).
    for i in 0..plan.joints.len() {
        let points = &message.points;
        let q = integrate(&times, points[0].positions[i], |k| points[k].velocities[i]);
        let v = integrate(&times, 0.0, |k| points[k].accelerations[i]);
        for k in 0..points.len() {
            assert!(
                (q[k] - points[k].positions[i]).abs() < 1e-3,
                "joint {i} at {k}"
            );
            assert!(
                (v[k] - points[k].velocities[i]).abs() < 0.02,
                "joint {i} at {k}"
            );
        }
    }

    // CSV: the same numbers, and the predicted object poses, under a header of names.
    let (code, csv, stderr) = pushplan(&["export", plan_path.to_str().unwrap(), "--format", "csv"]);
    assert_eq!(code, 0, "{stderr}");
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let dof = plan.joints.len();
    assert_eq!(header[0], "time");
    assert_eq!(header[1..=dof], plan.joints[..]);
    assert_eq!(header[1 + dof], format!("{}.velocity", plan.joints[0]));
    assert_eq!(
        header[1 + 2 * dof],
        format!("{}.acceleration", plan.joints[0])
    );
    assert_eq!(
        header[1 + 3 * dof..],
        ["green_box.x", "green_box.y", "green_box.yaw"]
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), message.points.len());
    for (k, (row, p)) in rows.iter().zip(&message.points).enumerate() {
        assert_eq!(row[0], trajectory.times[k]);
        assert_eq!(row[1..=dof], p.positions[..]);
        assert_eq!(row[1 + dof..1 + 2 * dof], p.velocities[..]);
        assert_eq!(row[1 + 2 * dof..1 + 3 * dof], p.accelerations[..]);
        assert_eq!(row[1 + 3 * dof..], trajectory.objects[k][0][..]);
    }

    // A trajectory that is not the one the plan's controls give is refused, named.
    let mut value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&plan_path).unwrap()).unwrap();
    let q = value["trajectory"]["q"][3][0].as_f64().unwrap();
    value["trajectory"]["q"][3][0] = serde_json::json!(q + 0.5);
    let tampered = scratch.join("tampered.json");
    std::fs::write(&tampered, value.to_string()).unwrap();
    let (code, _, stderr) = pushplan(&["export", tampered.to_str().unwrap(), "--format", "csv"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("tampered.json") && stderr.contains("trajectory: not the one"),
        "{stderr}"
    );
    let (code, _, stderr) = pushplan(&["export", plan_path.to_str().unwrap(), "--format", "urdf"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("joint-trajectory, csv"), "{stderr}");
}

/// Plan files of every kind the commands write: a robust pushing plan, a reach of a grasp,
/// a re-planned rest and a semi-dynamic plan.
fn written_plans(scratch: &Scratch) -> Vec<PathBuf> {
    let pushing = scratch.join("pushing.json");
    common::plan_solved(
        "scenes/herb_single_object.yaml",
        &pushing,
        &["--threads", "1"],
    );
    let reach = scratch.join("reach.json");
    let semi_dynamic = scratch.join("semi_dynamic.json");
    for (scene, out, extra) in [
        (
            "scenes/grasp_behind_wall.yaml",
            &reach,
            &["--goal", "grasp:can"][..],
        ),
        (
            "scenes/workshop/scene_1.yaml",
            &semi_dynamic,
            &["--robust", "0", "--threads", "1"][..],
        ),
    ] {
        let mut args = vec!["plan", scene, "--seed", "1", "--time", "60", "--quiet"];
        args.extend(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        let (code, stdout, stderr) = pushplan(&args);
        assert_eq!(code, 0, "{scene}: {stdout}{stderr}");
    }
    let plan = PlanFile::read(&pushing).unwrap();
    let scene = plan.load_scene(&pushing).unwrap();
    let observed = scratch.join("observed.json");
    let k = plan.controls.len() / 2;
    let state = plan.controls[k - 1].state.state();
    std::fs::write(&observed, ObservedState::of(&scene, &state).to_json()).unwrap();
    let replanned = scratch.join("replanned.json");
    let (code, stdout, stderr) = pushplan(&[
        "replan",
        pushing.to_str().unwrap(),
        "--observed",
        observed.to_str().unwrap(),
        "--quiet",
        "--out",
        replanned.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    vec![pushing, reach, replanned, semi_dynamic]
}

/// Python's `jsonschema` (Draft 2020-12) on each of `plans`: per file, the validator's
/// first error, or `None` when it is valid. The schema itself is checked against its
/// meta-schema first.
fn schema_errors(plans: &[PathBuf]) -> Vec<Option<String>> {
    let script = r#"
import json, sys
from jsonschema import Draft202012Validator
schema = json.load(open(sys.argv[1]))
Draft202012Validator.check_schema(schema)
validator = Draft202012Validator(schema)
for path in sys.argv[2:]:
    errors = sorted(validator.iter_errors(json.load(open(path))), key=str)
    print(json.dumps(errors[0].message if errors else None))
"#;
    let schema = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/plan.schema.json");
    let args: Vec<&std::ffi::OsStr> = std::iter::once(schema.as_os_str())
        .chain(plans.iter().map(|p| p.as_os_str()))
        .collect();
    common::python_prints(DEBIAN_PYTHON, script, &args)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

#[test]
fn written_plan_files_match_the_shipped_json_schema() {
    let scratch = Scratch::new("export-schema");
    let plans = written_plans(&scratch);
    assert_eq!(schema_errors(&plans), vec![None; plans.len()], "{plans:?}");
    let mut seen = std::collections::BTreeSet::new();
    for path in &plans {
        let value: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        seen.extend(value.as_object().unwrap().keys().cloned());
    }
    // Every optional record appears in one of them, so each part of the schema was used.
    for field in [
        "robustness",
        "reach",
        "replanned",
        "margins",
        "physics_model",
    ] {
        assert!(seen.contains(field), "{field}");
    }

    // What the reader refuses, the schema refuses; what older files leave out (their
    // defaults), both accept.
    let pushing: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&plans[0]).unwrap()).unwrap();
    type Edit = fn(&mut serde_json::Value);
    let refused: [(&str, Edit); 8] = [
        ("an unknown field", |v| v["colour"] = 1.into()),
        ("an unknown field in a control", |v| {
            v["controls"][0]["speed"] = 1.into()
        }),
        ("no trajectory", |v| {
            v.as_object_mut().unwrap().remove("trajectory");
        }),
        ("an unknown planner", |v| v["planner"] = "rrt_star".into()),
        ("another format", |v| v["format"] = "pushplan-plan/2".into()),
        ("a pose of two numbers", |v| {
            v["start"]["objects"][0] = serde_json::json!([0.5, 0.1])
        }),
        ("a negative seed", |v| v["seed"] = (-1).into()),
        ("a number as text", |v| v["step"] = "0.01".into()),
    ];
    let mut edited = Vec::new();
    for (i, (what, edit)) in refused.iter().enumerate() {
        let mut value = pushing.clone();
        edit(&mut value);
        let path = scratch.join(&format!("refused-{i}.json"));
        std::fs::write(&path, value.to_string()).unwrap();
        assert!(PlanFile::read(&path).is_err(), "the reader accepts {what}");
        edited.push(path);
    }
    let mut older = pushing.clone();
    for field in [
        "threads",
        "restart_steps",
        "fallback_steps",
        "physics_model",
        "object_pushing",
        "margins",
    ] {
        older.as_object_mut().unwrap().remove(field);
    }
    let older_path = scratch.join("older.json");
    std::fs::write(&older_path, older.to_string()).unwrap();
    PlanFile::read(&older_path).expect("the reader takes an older file");
    edited.push(older_path);
    let verdicts = schema_errors(&edited);
    for ((what, _), verdict) in refused.iter().zip(&verdicts) {
        assert!(verdict.is_some(), "the schema accepts {what}");
    }
    assert_eq!(
        verdicts.last().unwrap(),
        &None,
        "the schema refuses an older file"
    );
}
