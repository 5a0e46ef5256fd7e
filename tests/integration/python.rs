//! The Python module as a new user meets it (issue 60): `pip install .` into a fresh
//! virtual environment, then `import pushplan`: load a scene, plan it, read states and
//! trajectories as NumPy arrays, check, execute in the 3D engine, render, export; errors
//! are `pushplan.Error`. The plan it writes is the CLI's, byte for byte.

use crate::common::{self, Scratch};
use std::path::Path;
use std::process::Command;

const SCRIPT: &str = r#"
import sys, pathlib
import numpy as np
import pushplan

out = pathlib.Path(sys.argv[1])
scene = pushplan.Scene("scenes/herb_single_object.yaml")
assert scene.name == "herb-single-object", scene.name
assert scene.objects == ["green_box"] and len(scene.joints) == 7
assert scene.start_q.shape == (7,) and scene.start_objects.shape == (1, 3)
assert scene.warnings() == []
assert "push_kpiece" in pushplan.PLANNERS

plan = scene.plan(seed=2, threads=1)
assert plan.solved and plan.planner == "push_kpiece" and plan.seed == 2
n = plan.controls.shape[0]
assert plan.controls.shape == (n, 3 + 7) and plan.durations.shape == (n,)
assert plan.state_q.shape == (n + 1, 7) and plan.state_objects.shape == (n + 1, 1, 3)
samples = plan.trajectory_times.shape[0]
assert plan.trajectory_q.shape == (samples, 7)
assert plan.trajectory_objects.shape == (samples, 1, 3)
assert np.all(np.diff(plan.trajectory_times) > 0)
# The trajectory starts at the scene's start and ends where the last control does.
assert np.array_equal(plan.trajectory_q[0], scene.start_q)
assert np.array_equal(plan.trajectory_q[-1], plan.state_q[-1])
# The goal box ends inside the goal disc (0.85, -0.25; radius 0.1, margin 0.06).
x, y, _ = plan.state_objects[-1, 0]
assert np.hypot(x - 0.85, y + 0.25) <= 0.04 + 1e-9, (x, y)
assert plan.metrics["after_shortcut"]["objects_moved"] == 1

report = plan.check()
assert report["passed"] and report["problems"] == [] and report["remade"] == "same", report
assert plan.check(path_only=True)["remade"] is None
plan.save(out / "python.json")
again = pushplan.Plan.load(out / "python.json")
assert again.to_json() == plan.to_json()

executed = plan.execute("rapier", trials=2, seed=1)
assert len(executed["trials"]) == 2 and 0.0 <= executed["success_rate"] <= 1.0
files = plan.render(out / "pictures")
assert [f.name for f in files] == ["snapshots.svg", "timeline.svg", "animation.html"]
assert plan.export("csv").startswith("time,j1,")

def refused(call, *words):
    try:
        call()
    except pushplan.Error as e:
        assert all(w in str(e) for w in words), (str(e), words)
        return
    raise AssertionError(f"no pushplan.Error for {words}")

refused(lambda: scene.plan(k=0), "k", "[1, 10000]")
refused(lambda: scene.plan(time_limit=float("nan")), "time_limit")
refused(lambda: scene.plan("rrt_star"), "rrt_star")
refused(lambda: pushplan.Scene("no/such/scene.yaml"), "no/such/scene.yaml")
(out / "broken.yaml").write_text("name: [unclosed\n")
refused(lambda: pushplan.Scene(out / "broken.yaml"), "broken.yaml")
refused(lambda: plan.execute("bullet"), "bullet")
refused(lambda: plan.execute(trials=0), "trials")
refused(lambda: plan.export("urdf"), "urdf")
assert issubclass(pushplan.Error, Exception)
print("python OK")
"#;

#[test]
fn pip_install_gives_a_python_module_that_plans_as_the_cli_does() {
    let scratch = Scratch::new("python-module");
    let venv = scratch.join("venv");
    let run = |what: &str, command: &mut Command| {
        let out = command.output().unwrap_or_else(|e| panic!("{what}: {e}"));
        assert!(
            out.status.success(),
            "{what} failed:\n{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    run(
        "python3 -m venv",
        Command::new("python3").args(["-m", "venv"]).arg(&venv),
    );
    // From the repository root, as the README says; maturin builds in the workspace's
    // target folder, beside the rest.
    run(
        "pip install .",
        Command::new(venv.join("bin/pip"))
            .args(["install", "--quiet", "--disable-pip-version-check", "."])
            .current_dir(env!("CARGO_MANIFEST_DIR")),
    );
    let stdout = run(
        "the Python script",
        Command::new(venv.join("bin/python"))
            .args(["-c", SCRIPT])
            .arg(scratch.path())
            .current_dir(env!("CARGO_MANIFEST_DIR")),
    );
    assert!(stdout.contains("python OK"), "{stdout}");

    // The CLI's plan of the same scene and settings is the same file.
    let cli = scratch.join("cli.json");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/herb_single_object.yaml");
    let (code, out, err) = common::pushplan_in(
        Path::new("."),
        &[
            "plan",
            scene.to_str().unwrap(),
            "--seed",
            "2",
            "--threads",
            "1",
            "--quiet",
            "--out",
            cli.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{out}{err}");
    assert_eq!(
        std::fs::read_to_string(scratch.join("python.json")).unwrap(),
        std::fs::read_to_string(&cli).unwrap()
    );
}
