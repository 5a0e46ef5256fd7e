//! The observed-state file (`pushplan replan --observed`): where the world is while a plan
//! runs, as a robot's joint encoders and perception report it, by name, so that any
//! simulator or robot stack can write one:
//!
//! ```json
//! {
//!   "format": "pushplan-observed/1",
//!   "joints": { "wam_j1": 0.12, "wam_j2": -1.05, "...": 0.0 },
//!   "objects": { "goal_box": [0.61, -0.02, 0.31], "bottle": [0.55, 0.18, 0.0] }
//! }
//! ```
//!
//! `joints`: every joint of the scene's robot (rad, or m for a prismatic joint; the planar
//! hand's are `x`, `y`, `yaw`). `objects`: every movable object's `[x, y, yaw]` on the
//! table (m, m, rad; world frame). Nothing may be missing or unknown.

use crate::planning::plan_file::read_json;
use crate::scene::Scene;
use crate::state::State;
use crate::Pose2;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// The `format` of an observed-state file.
pub const OBSERVED_FORMAT: &str = "pushplan-observed/1";

/// Observed-state files are small: a few numbers per joint and object.
const MAX_OBSERVED_BYTES: u64 = 1 << 20;

/// An observed state, by joint and object names.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObservedState {
    /// Always [`OBSERVED_FORMAT`].
    pub format: String,
    /// Every joint's value (rad or m).
    pub joints: BTreeMap<String, f64>,
    /// Every movable object's `[x, y, yaw]` (m, m, rad; world frame).
    pub objects: BTreeMap<String, [f64; 3]>,
}

impl ObservedState {
    /// `state` of `scene`, by name.
    pub fn of(scene: &Scene, state: &State) -> ObservedState {
        ObservedState {
            format: OBSERVED_FORMAT.into(),
            joints: (0..scene.robot.dof())
                .map(|i| (scene.robot.chain.dof_joint(i).name.clone(), state.q[i]))
                .collect(),
            objects: scene
                .objects
                .iter()
                .zip(&state.objects)
                .map(|(o, p)| (o.name.clone(), [p.x, p.y, p.theta]))
                .collect(),
        }
    }

    /// Reads an observed-state file; errors name the file and the field.
    pub fn read(path: &Path) -> Result<ObservedState, String> {
        let observed: ObservedState = read_json(path, MAX_OBSERVED_BYTES)?;
        if observed.format != OBSERVED_FORMAT {
            return Err(format!(
                "{}: format is '{}', expected '{OBSERVED_FORMAT}'",
                path.display(),
                crate::input::shorten_quoted(&observed.format)
            ));
        }
        Ok(observed)
    }

    /// The state in `scene`'s order: every joint and object named once, no other names.
    /// Not checked for validity: [`Scene::with_start`] does that. `path` names the file in
    /// errors.
    pub fn state(&self, scene: &Scene, path: &Path) -> Result<State, String> {
        let joint_names: Vec<&str> = (0..scene.robot.dof())
            .map(|i| scene.robot.chain.dof_joint(i).name.as_str())
            .collect();
        let object_names: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
        let unknown = |field: &str, name: &str, known: &[&str]| {
            format!(
                "{}: {field}: '{}' is not in the scene (it has {})",
                path.display(),
                crate::input::shorten_quoted(name),
                crate::input::name_list(known.iter().copied())
            )
        };
        if let Some(name) = self
            .joints
            .keys()
            .find(|n| !joint_names.contains(&n.as_str()))
        {
            return Err(unknown("joints", name, &joint_names));
        }
        if let Some(name) = self
            .objects
            .keys()
            .find(|n| !object_names.contains(&n.as_str()))
        {
            return Err(unknown("objects", name, &object_names));
        }
        let missing =
            |field: &str, name: &str| format!("{}: {field}: '{name}' is missing", path.display());
        let q = joint_names
            .iter()
            .map(|n| {
                self.joints
                    .get(*n)
                    .copied()
                    .ok_or_else(|| missing("joints", n))
            })
            .collect::<Result<Vec<f64>, String>>()?;
        let objects = object_names
            .iter()
            .map(|n| {
                let [x, y, yaw] = *self.objects.get(*n).ok_or_else(|| missing("objects", n))?;
                Ok(Pose2::new(x, y, yaw))
            })
            .collect::<Result<Vec<Pose2>, String>>()?;
        Ok(State {
            q: nalgebra::DVector::from_vec(q),
            objects,
        })
    }

    /// The file's text (pretty JSON, one trailing newline).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("observed states serialise") + "\n"
    }
}
