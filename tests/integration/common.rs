//! Helpers of the integration tests: plans and settings made through the planner,
//! benchmark databases read by another program, and the `pushplan` command run in a
//! folder. The model's scene helpers are the model crate's own test helpers.
#![allow(dead_code)]

#[path = "../../model/tests/model/common.rs"]
mod scenes;

pub use scenes::*;

use pushplan::Scene;
use std::path::Path;

/// The PC RRT plan of the default (Fig. 1) scene for `seed`, as controls (with the goal
/// margin of 0.06 m seed 2 solves in about 2 s, seed 5 in 29 s, seed 3 not in 30 s).
pub fn default_scene_plan(seed: u64) -> (Scene, Vec<pushplan::planning::path::PathControl>) {
    use pushplan::planner::Search;
    let settings = pushplan::planning::RunSettings {
        time_limit: 30.0,
        seed,
        k: 3,
        goal_bias: 0.05,
        restart_steps: 0,
        fallback_steps: 0,
        ..run_settings("pcrrt")
    };
    let scene = Scene::load("scenes/herb_fig1_clutter.yaml").unwrap();
    let out = pushplan::bridge::OmplSearch
        .solve(&scene, &settings, None)
        .unwrap();
    assert!(
        out.summary.exact,
        "seed {seed} should solve the default scene"
    );
    let controls = out.controls;
    (scene, controls)
}

/// The settings of `planner` with the default `planner:` parameters of a scene, on one
/// thread, without robust planning, with the planner's own restarts and fallback.
pub fn run_settings(planner: &str) -> pushplan::planning::RunSettings {
    let params = pushplan::scene::PlannerParams::default();
    pushplan::planning::RunSettings::of_scene(planner.parse().unwrap(), &params)
}

/// How a test's plan was made: k = 3, goal bias 0.05, 30 s, and the given shortcut budget.
pub fn plan_settings(
    planner: &str,
    seed: u64,
    shortcut: f64,
) -> pushplan::planning::plan_file::PlanSettings {
    pushplan::planning::plan_file::PlanSettings {
        planner: planner.parse().unwrap(),
        seed,
        k: 3,
        goal_bias: 0.05,
        time_limit: 30.0,
        shortcut,
        threads: 1,
        restart_steps: 0,
        fallback_steps: 0,
        intermediate_states: false,
    }
}

/// Every run of a benchmark database (`results.db`), one line each: experiment, its seed
/// and run count, planner, run index.
pub fn benchmark_runs(db: &Path) -> Vec<String> {
    query_database(
        r#"
import sqlite3, sys
c = sqlite3.connect(sys.argv[1])
for row in c.execute("""select e.name, e.seed, e.runcount, p.name, r.run from runs r
        join experiments e on e.id = r.experimentid join plannerConfigs p on p.id = r.plannerid
        order by 1, 4, 5"""):
    print(*row)
"#,
        db,
    )
}

/// What a Python `script` prints about the database `db` (its `sys.argv[1]`), line by
/// line: benchmark databases read by another program than the one that wrote them.
pub fn query_database(script: &str, db: &Path) -> Vec<String> {
    python_prints("python3", script, &[db.as_os_str()])
        .lines()
        .map(str::to_string)
        .collect()
}

/// What `script` prints, run by the Python interpreter `python` with `args` as its
/// `sys.argv[1:]`; the script must succeed.
pub fn python_prints(python: &str, script: &str, args: &[&std::ffi::OsStr]) -> String {
    let answer = std::process::Command::new(python)
        .args(["-c", script])
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("{python}: {e} (install it with .ci/install-packages)"));
    assert!(
        answer.status.success(),
        "{}",
        String::from_utf8_lossy(&answer.stderr)
    );
    String::from_utf8_lossy(&answer.stdout).into_owned()
}

/// Runs the `pushplan` command in `dir`: its exit code (-1 when a signal ended it),
/// stdout and stderr.
pub fn pushplan_in(dir: &Path, args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_pushplan"))
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Plans `scene` (seed 2, no shortcutting, up to 30 s) into `out` with `pushplan plan`;
/// the search must solve it.
pub fn plan_solved(scene: &str, out: &Path, extra: &[&str]) {
    let mut args = vec![
        "plan",
        scene,
        "--seed",
        "2",
        "--time",
        "30",
        "--shortcut",
        "0",
    ];
    args.extend(["--quiet", "--out", out.to_str().unwrap()]);
    args.extend(extra);
    let (code, stdout, stderr) = pushplan_in(Path::new("."), &args);
    assert_eq!(code, 0, "{stdout}{stderr}");
}
