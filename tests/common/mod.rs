//! Scenes built in code for tests: HERB's table and WAM with the given objects. The arm
//! is mounted lower here (base at z = 0.346) than in the shipped scenes (0.45): the
//! configurations below were chosen for that mounting.
#![allow(dead_code)]

use pushplan::Scene;
use std::path::Path;

/// Start joints with the hand at (0.55, 0.15).
pub const HAND_NEAR: [f64; 7] = [0.4168, 0.4078, -0.5623, 2.6434, -0.2157, -1.0298, 0.2641];
/// Start joints with the hand reaching out to (0.91, 0.15): the forearm slopes over the table.
pub const HAND_FAR: [f64; 7] = [0.1485, 0.7954, -0.2728, 1.4626, -0.4452, -0.2789, 0.5892];

/// A WAM scene on HERB's table; `objects` is the YAML list of objects (the first is the
/// goal object), `extra` is appended at the top level.
pub fn herb_scene(start: [f64; 7], objects: &str, extra: &str) -> Result<Scene, pushplan::Error> {
    herb_scene_with_robot("wam7.urdf", start, objects, extra)
}

/// [`herb_scene`] with another URDF of `robots/` (e.g. `wam7_mesh.urdf`).
pub fn herb_scene_with_robot(
    urdf: &str,
    start: [f64; 7],
    objects: &str,
    extra: &str,
) -> Result<Scene, pushplan::Error> {
    let yaml = format!(
        "robot:
  type: arm
  urdf: ../robots/{urdf}
  base_pose: {{xyz: [0.1, 0.14, 0.346]}}
  end_effector: hand
  start_joints: {start:?}
  pushing_plane: {{height: 0.08, orientation_rpy: [0, 2.0, 0]}}
table: {{height: 0.76, x: [0.27, 1.03], y: [-0.93, 0.93]}}
objects:
{objects}
goal: {{object: goal, center: [0.85, -0.6], radius: 0.1}}
{extra}"
    );
    Scene::from_yaml(&yaml, Path::new("scenes/test-scene.yaml"))
}

/// YAML for one object.
pub fn object(name: &str, shape: &str, pose: [f64; 3]) -> String {
    format!(
        "  - {{name: {name}, shape: {shape}, pose: {pose:?}, mass: 1.0, mu_g: 0.4, mu_c: 0.3}}\n"
    )
}

/// The goal box, parked out of the way.
pub fn parked_goal() -> String {
    object(
        "goal",
        "{type: box, size: [0.102, 0.102, 0.215]}",
        [0.5, -0.6, 0.0],
    )
}

/// The PC RRT plan of the default (Fig. 1) scene for `seed`, as controls (seed 5 solves in
/// about half a second, seed 2 in 15 s).
pub fn default_scene_plan(seed: u64) -> (Scene, Vec<pushplan::path::PathControl>) {
    let options = pushplan::ffi::SolveOptions {
        time_limit: 30.0,
        seed,
        k: 3,
        goal_bias: 0.05,
        planner: pushplan::planner::PlannerKind::PcRrt,
        intermediate_states: false,
        progress: false,
        robust_trials: 0,
        robust_rate: 0.9,
        robust_shortcut: 3.0,
        robust_particles: 0,
        threads: 1,
        restart_steps: 0,
        fallback_steps: 0,
    };
    let scene_file = "scenes/herb_fig1_clutter.yaml";
    let out = pushplan::ffi::solve(Path::new(scene_file), &options, |_| {}).unwrap();
    assert!(out.exact, "seed {seed} should solve the default scene");
    let scene = Scene::load(scene_file).unwrap();
    let controls =
        pushplan::path::PathControl::from_flat(&out.controls, &out.steps, scene.robot.dof())
            .unwrap();
    (scene, controls)
}

/// How a test's plan was made: k = 3, goal bias 0.05, 30 s, and the given shortcut budget.
pub fn plan_settings(planner: &str, seed: u64, shortcut: f64) -> pushplan::plan::PlanSettings {
    pushplan::plan::PlanSettings {
        planner: planner.parse().unwrap(),
        seed,
        k: 3,
        goal_bias: 0.05,
        time_limit: 30.0,
        shortcut,
        threads: 1,
        restart_steps: 0,
        fallback_steps: 0,
    }
}

/// A 1 cm tall planar hand (front face at x = 0.42) at `height` above the table, and one
/// object `name` of `shape` at (`x`, 0) on the line it pushes along, on a table with
/// support friction `mu_g`; `extra` is appended at the top level.
pub fn thin_hand_scene(
    name: &str,
    shape: &str,
    x: f64,
    height: f64,
    mu_g: f64,
    extra: &str,
) -> Scene {
    let yaml = format!(
        "robot:
  type: planar_hand
  shape: {{type: box, size: [0.04, 0.12, 0.01]}}
  start: [0.4, 0.0, 0.0]
  height: {height}
table: {{height: 0.76, x: [0.27, 1.03], y: [-0.6, 0.6]}}
objects:
  - {{name: {name}, shape: {shape}, pose: [{x}, 0.0, 0.0], mass: 1.0, mu_g: {mu_g}, mu_c: 0.3}}
goal: {{object: {name}, center: [0.9, 0.3], radius: 0.1}}
{extra}"
    );
    Scene::from_yaml(&yaml, Path::new("scenes/thin-hand-test.yaml")).unwrap()
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
    let answer = std::process::Command::new("python3")
        .args(["-c", script])
        .arg(db)
        .output()
        .expect("python3 runs");
    assert!(
        answer.status.success(),
        "{}",
        String::from_utf8_lossy(&answer.stderr)
    );
    String::from_utf8_lossy(&answer.stdout)
        .lines()
        .map(str::to_string)
        .collect()
}

/// A fresh folder `pushplan-{name}-{pid}` under the system temp dir, removed when dropped
/// (tests leave nothing behind, passed or failed).
pub struct Scratch(std::path::PathBuf);

impl Scratch {
    pub fn new(name: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("pushplan-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }

    pub fn path(&self) -> &Path {
        &self.0
    }

    pub fn join(&self, name: &str) -> std::path::PathBuf {
        self.0.join(name)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
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
