//! Scenes built in code for tests: HERB's table and WAM with the given objects. The arm
//! is mounted lower here (base at z = 0.346) than in the shipped scenes (0.45): the
//! configurations below were chosen for that mounting.
#![allow(dead_code)]

use pushplan_model::Scene;
use std::path::Path;

/// Start joints with the hand at (0.55, 0.15).
pub const HAND_NEAR: [f64; 7] = [0.4168, 0.4078, -0.5623, 2.6434, -0.2157, -1.0298, 0.2641];
/// Start joints with the hand reaching out to (0.91, 0.15): the forearm slopes over the table.
pub const HAND_FAR: [f64; 7] = [0.1485, 0.7954, -0.2728, 1.4626, -0.4452, -0.2789, 0.5892];

/// A WAM scene on HERB's table; `objects` is the YAML list of objects (the first is the
/// goal object), `extra` is appended at the top level.
pub fn herb_scene(
    start: [f64; 7],
    objects: &str,
    extra: &str,
) -> Result<Scene, pushplan_model::Error> {
    herb_scene_with_robot("wam7.urdf", start, objects, extra)
}

/// [`herb_scene`] with another URDF of `robots/` (e.g. `wam7_mesh.urdf`).
pub fn herb_scene_with_robot(
    urdf: &str,
    start: [f64; 7],
    objects: &str,
    extra: &str,
) -> Result<Scene, pushplan_model::Error> {
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
    let yaml = thin_hand_yaml(name, shape, x, height, mu_g, extra);
    Scene::from_yaml(&yaml, Path::new("scenes/thin-hand-test.yaml")).unwrap()
}

/// [`thin_hand_scene`]'s scene file, for tests that write it out (`mu_c` 0.3).
pub fn thin_hand_yaml(
    name: &str,
    shape: &str,
    x: f64,
    height: f64,
    mu_g: f64,
    extra: &str,
) -> String {
    format!(
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
    )
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
