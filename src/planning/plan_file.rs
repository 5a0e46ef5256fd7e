//! Plan files (JSON) and their independent check.
//!
//! A plan file holds what is needed to reproduce a plan: the scene reference, the planner
//! and its parameters and seed, the start state, and per control the action, its step
//! count, the state it reaches and the pushes during its steps. Nothing in it depends on
//! the machine or the clock, so the same scene, parameters and seed give the same bytes.

use crate::planning::path::{PathControl, PathMetrics, SimulatedPath};
use crate::planning::rest::RestFrom;
use crate::planning::robustness::Noise;
pub use crate::planning::trajectory::TRAJECTORY_RATE;
use crate::planning::trajectory::{executable, Trajectory};
use crate::planning::{
    unseen_seed, PlannerKind, Problem, RunSettings, DEFAULT_ROBUST_RATE, DEFAULT_ROBUST_SHORTCUT,
};
use crate::scene::Scene;
use crate::state::State;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The `format` of plan files this version writes and reads.
pub const FORMAT: &str = "pushplan-plan/1";

/// Most propagation steps a plan file may hold over all its controls (at the default
/// 0.01 s step, 2 000 s of motion): re-simulating, checking and drawing a plan take time
/// and memory in proportion.
pub const MAX_PLAN_STEPS: usize = 200_000;

/// How a plan was made (in the plan file, among its top-level fields).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSettings {
    /// The planner that searched.
    pub planner: PlannerKind,
    /// The seed of every random choice.
    pub seed: u64,
    /// Control samples per extension (Alg. 1's k).
    pub k: u32,
    /// Probability of sampling the goal region.
    pub goal_bias: f64,
    /// The time limit of the whole command (s).
    pub time_limit: f64,
    /// Shortcutting budget (s of work; 0 = none).
    pub shortcut: f64,
    /// Threads planned on (absent in files from before there were several: 1).
    #[serde(default = "one_search")]
    pub threads: u32,
    /// The search's first restart budget in propagation steps, 0: no restarts (absent in
    /// files from before there were restarts: 0).
    #[serde(default)]
    pub restart_steps: u64,
    /// Push KPIECE's patience before it falls back to PC RRT, in propagation steps, 0:
    /// never (absent in files from before the fallback: 0).
    #[serde(default)]
    pub fallback_steps: u64,
    /// Every propagation step added to the tree (OMPL RRT's intermediate states; written
    /// only when true).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub intermediate_states: bool,
}

impl PlanSettings {
    /// Each setting within the limits table ([`crate::limits`]) and the rules between
    /// them, as every front door checks them ([`RunSettings::check`]), named as the file
    /// names it (the robustness record is checked as its own part).
    fn check(&self) -> Result<(), String> {
        self.run_settings(None, self.time_limit)
            .check(crate::limits::Front::PlanFile)
    }

    /// The search settings these record, to make the plan again (`check`): robust as
    /// `robustness` records it (none without a record), with `time_limit` (s).
    pub fn run_settings(
        &self,
        robustness: Option<&RobustnessRecord>,
        time_limit: f64,
    ) -> RunSettings {
        RunSettings {
            planner: self.planner,
            intermediate_states: self.intermediate_states,
            k: self.k,
            threads: self.threads,
            robust_trials: robustness.map_or(0, |r| r.asked.unwrap_or(r.trials) as u32),
            robust_particles: robustness.map_or(0, |r| r.particles),
            time_limit,
            seed: self.seed,
            goal_bias: self.goal_bias,
            shortcut: self.shortcut,
            robust_rate: robustness.map_or(DEFAULT_ROBUST_RATE, |r| r.required_rate),
            robust_shortcut: robustness.map_or(DEFAULT_ROBUST_SHORTCUT, |r| r.shortcut),
            restart_steps: self.restart_steps,
            fallback_steps: self.fallback_steps,
        }
    }
}

fn one_search() -> u32 {
    1
}

impl From<&RunSettings> for PlanSettings {
    /// What a plan file records of the settings its search ran with (robust planning's
    /// are in its `robustness` record).
    fn from(run: &RunSettings) -> Self {
        PlanSettings {
            planner: run.planner,
            seed: run.seed,
            k: run.k,
            goal_bias: run.goal_bias,
            time_limit: run.time_limit,
            shortcut: run.shortcut,
            threads: run.threads,
            restart_steps: run.restart_steps,
            fallback_steps: run.fallback_steps,
            intermediate_states: run.intermediate_states,
        }
    }
}

/// A plan file. Unknown fields are refused ([`PlanFile::read`]): serde cannot deny them
/// on a struct with a flattened part, so they are gathered in `unknown` and checked.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlanFile {
    /// Always "pushplan-plan/1".
    pub format: String,
    /// The scene file, as given to the planner.
    pub scene: String,
    /// The scene's name.
    pub scene_name: String,
    /// How the plan was made.
    #[serde(flatten)]
    pub settings: PlanSettings,
    /// Propagation step (s).
    pub step: f64,
    /// How pushed objects moved: the scene's `physics.model` (quasistatic in files from
    /// before the semi-dynamic model).
    #[serde(default)]
    pub physics_model: crate::scene::file::PhysicsModel,
    /// Whether pushed objects pushed other objects along (the scene's
    /// `physics.object_pushing`; false in files from before it was recorded).
    #[serde(default)]
    pub object_pushing: bool,
    /// The reserves the plan was made with (absent in files from before they existed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub margins: Option<Margins>,
    /// True when the plan reaches the goal.
    pub solved: bool,
    /// The path before and after shortcutting.
    pub metrics: Metrics,
    /// The robot's joint names, in the configuration's order.
    pub joints: Vec<String>,
    /// The objects' names, in the state's order.
    pub objects: Vec<String>,
    /// The start state.
    pub start: StateRecord,
    /// The controls, each with the state it reaches.
    pub controls: Vec<ControlRecord>,
    /// The executable trajectory: joint values within the URDF's velocity limits and the
    /// predicted object poses, at `TRAJECTORY_RATE` Hz.
    pub trajectory: Trajectory,
    /// Robust planning's check of the plan (only when it was asked for).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub robustness: Option<RobustnessRecord>,
    /// A reach of a grasp after the controls (`plan --goal grasp:OBJECT`, or `--grasp`
    /// after pushing).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reach: Option<ReachRecord>,
    /// `plan --grasp`: the object a reach of a grasp was asked for after the controls (the
    /// goal object), found or not. The plan is solved only with a `reach`; without one
    /// (none found in time) `check` says so instead of finding `solved` at odds with
    /// controls that reach the goal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grasp_after: Option<String>,
    /// A plan for the rest of another, from a state observed while it ran (`replan`):
    /// its `start` is that state, not the scene's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub replanned: Option<ReplanRecord>,
    /// Fields this format does not have (an error when read).
    #[serde(flatten, skip_serializing)]
    unknown: std::collections::BTreeMap<String, serde::de::IgnoredAny>,
}

/// A reach of a grasp (issue 15): IK-BiRRT's path from where the controls leave the arm
/// to a configuration in a grasp region of the object, every object a static obstacle.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReachRecord {
    /// The object grasped.
    pub object: String,
    /// IK-BiRRT's P_sample.
    pub sample_probability: f64,
    /// Joint values, joined by straight lines: the first where the controls end, the
    /// last in a grasp region.
    pub waypoints: Vec<Vec<f64>>,
}

/// Where a re-planned plan comes from (`pushplan replan`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReplanRecord {
    /// The plan whose rest this plan is, as given to `replan`.
    pub plan: String,
    /// The control of that plan at whose start the world was observed.
    pub at: usize,
    /// The observation file, as given to `replan`.
    pub observed: String,
    /// True: that plan's remaining controls still reach the goal from the observed state,
    /// and are this plan's; false: this plan was repaired or searched anew from it.
    pub kept: bool,
    /// A repair: this many of that plan's remaining controls are valid from the observed
    /// state and begin this plan, and an ending searched from where they end follows (the
    /// settings are the ending's search's). Absent: kept whole, or searched anew.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub repaired: Option<usize>,
}

/// The reserves of the validity rules a plan keeps (see the scene's `goal.margin`,
/// `physics.object_clearance`, `physics.arm_clearance` and `physics.tipping_margin`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Margins {
    /// How far inside the goal disc's edge the goal object's centre ends (m).
    pub goal: f64,
    /// Smallest distance a moving object keeps from other objects and obstacles (m).
    pub object_clearance: f64,
    /// Smallest distance a moving object keeps from the table's edges (m; plans written
    /// before it existed read as 0).
    #[serde(default)]
    pub edge_clearance: f64,
    /// Fraction of the footprint kept free of the support's centre of pressure.
    pub tipping: f64,
    /// Smallest distance a link closing in on an object keeps from it where a sliding
    /// push would tip it (m; plans written before it existed read as 0).
    #[serde(default)]
    pub arm_clearance: f64,
}

/// How robust planning found the plan: the fraction of `trials` re-simulations from
/// perturbed scenes that reached the goal, and the fraction required.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobustnessRecord {
    /// Perturbed re-simulations of the check.
    pub trials: usize,
    /// Fraction of them required to reach the goal.
    pub required_rate: f64,
    /// Fraction that did.
    pub success_rate: f64,
    /// Perturbed worlds the search carried along its states (absent in older files: 0).
    #[serde(default)]
    pub particles: u32,
    /// Shortcutting budget toward robustness for each solution not robust enough (s of
    /// work, `plan --robust-shortcut`; absent in older files: 3, the default then).
    #[serde(default = "robust_shortcut_of_older_files")]
    pub shortcut: f64,
    /// The re-simulations asked for, when the time limit cut the check short of them
    /// (`trials` below it; absent otherwise: `trials` were asked).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub asked: Option<usize>,
    /// The plan's rate in as many perturbed worlds as the check has, drawn apart from the
    /// worlds every solution of the run was judged in (by `planning::finish`, from
    /// `planning::unseen_seed`): the check's rate is that of the solution chosen for
    /// passing it, the luckiest of the run; this one is not chosen on. Absent in older
    /// files, and when the time limit came before it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unseen: Option<UnseenRate>,
}

/// A rate measured after the plan was chosen ([`RobustnessRecord::unseen`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UnseenRate {
    /// Perturbed re-simulations run (fewer than the check's when the time limit cut them
    /// short).
    pub trials: usize,
    /// Fraction of them that reached the goal.
    pub success_rate: f64,
}

/// The budget older plan files were made with (the field is newer than it).
fn robust_shortcut_of_older_files() -> f64 {
    3.0
}

impl RobustnessRecord {
    /// Within the limits robust planning has (`check` measures the rate again over
    /// `trials`: a count from the file must not be a loop without end).
    fn check(&self) -> Result<(), String> {
        use crate::limits::{Front, ROBUST_PARTICLES, ROBUST_SHORTCUT, ROBUST_TRIALS};
        let named = |field: &str, e: String| format!("robustness.{field}: {e}");
        if ROBUST_SHORTCUT
            .check(Front::PlanFile, self.shortcut)
            .is_err()
        {
            return Err(named(
                "shortcut",
                format!(
                    "must be in {}, got {}",
                    ROBUST_SHORTCUT.range(),
                    self.shortcut
                ),
            ));
        }
        if !(1..=ROBUST_TRIALS.most as usize).contains(&self.trials) {
            return Err(named(
                "trials",
                format!(
                    "must be in [1, {}], got {}",
                    ROBUST_TRIALS.most, self.trials
                ),
            ));
        }
        if let Some(asked) = self.asked {
            if !(self.trials < asked && asked <= ROBUST_TRIALS.most as usize) {
                return Err(named(
                    "asked",
                    format!(
                        "must be in ({}, {}] (more than the trials run), got {asked}",
                        self.trials, ROBUST_TRIALS.most
                    ),
                ));
            }
        }
        if self.particles > ROBUST_PARTICLES.most as u32 {
            return Err(named(
                "particles",
                format!(
                    "must be in {}, got {}",
                    ROBUST_PARTICLES.range(),
                    self.particles
                ),
            ));
        }
        for (field, rate) in [
            ("required_rate", self.required_rate),
            ("success_rate", self.success_rate),
        ]
        .into_iter()
        .chain(
            self.unseen
                .as_ref()
                .map(|u| ("unseen.success_rate", u.success_rate)),
        ) {
            if !(0.0..=1.0).contains(&rate) {
                return Err(named(field, format!("must be in [0, 1], got {rate}")));
            }
        }
        if let Some(u) = &self.unseen {
            if !(1..=ROBUST_TRIALS.most as usize).contains(&u.trials) {
                return Err(named(
                    "unseen.trials",
                    format!("must be in [1, {}], got {}", ROBUST_TRIALS.most, u.trials),
                ));
            }
        }
        Ok(())
    }
}

/// The path's metrics as found and as written.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Metrics {
    /// As the search found it.
    pub before_shortcut: PathMetrics,
    /// After shortcutting (the plan's).
    pub after_shortcut: PathMetrics,
}

impl Metrics {
    /// What can be checked of the metrics without the path as found, which the file does
    /// not hold: lengths, displacements and durations finite and not negative, no more
    /// objects moved than the scene has. (`check` compares the rest with the
    /// re-simulation: the metrics after shortcutting, and before it when the plan was not
    /// shortcut.)
    fn check(&self, objects: usize) -> Result<(), String> {
        for (name, m) in [
            ("before_shortcut", &self.before_shortcut),
            ("after_shortcut", &self.after_shortcut),
        ] {
            let lengths = [
                m.joint_length,
                m.ee_length,
                m.object_displacement,
                m.duration,
            ];
            if let Some(v) = lengths.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
                return Err(format!(
                    "metrics.{name}: a length or duration of {v}; they are finite and not negative"
                ));
            }
            if m.objects_moved > objects {
                return Err(format!(
                    "metrics.{name}.objects_moved: {} of {objects} objects",
                    m.objects_moved
                ));
            }
        }
        Ok(())
    }
}

/// Joint values and object poses `[x, y, yaw]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StateRecord {
    /// Joint values (rad or m).
    pub q: Vec<f64>,
    /// Object poses `[x, y, yaw]` (m, m, rad; world frame).
    pub objects: Vec<[f64; 3]>,
}

/// One control of the plan.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ControlRecord {
    /// (vx, vy) m/s and omega_z rad/s, world frame.
    pub ee_velocity: [f64; 3],
    /// Null-space sample (rad/s per joint).
    pub nullspace: Vec<f64>,
    /// Propagation steps; duration = steps * step.
    pub steps: usize,
    /// Its duration (s).
    pub duration: f64,
    /// The state reached at the end of the control.
    pub state: StateRecord,
    /// Links pushing objects during the control's steps.
    pub contacts: Vec<Contact>,
}

/// A [`crate::propagate::Contact`] as the plan file records it: by step and by names.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Contact {
    /// Step within the control.
    pub step: usize,
    /// The pushing link's name.
    pub link: String,
    /// The pushed object's name.
    pub object: String,
    /// Normal force (N).
    pub force: f64,
}

impl StateRecord {
    /// The record of `state`.
    pub fn from_state(state: &State) -> Self {
        StateRecord {
            q: state.q.as_slice().to_vec(),
            objects: state.objects.iter().map(|p| [p.x, p.y, p.theta]).collect(),
        }
    }

    /// The state in the flat layout ([`crate::State::to_flat`]).
    pub fn flat(&self) -> Vec<f64> {
        let mut out = self.q.clone();
        out.extend(self.objects.iter().flatten());
        out
    }

    /// The state recorded.
    pub fn state(&self) -> State {
        State::from_flat(&self.flat(), self.q.len())
    }
}

/// What re-simulating a plan found.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckReport {
    /// Every step of every control valid.
    pub all_valid: bool,
    /// The re-simulated states equal the plan's, bit for bit.
    pub states_match: bool,
    /// The last state satisfies the goal.
    pub goal_reached: bool,
    /// The reach after the controls, if the plan has one (`plan --grasp`), is valid and
    /// ends in a grasp region; false where one was asked for and none found.
    pub reach_valid: bool,
    /// Everything else the file records about the path agrees with the re-simulation.
    pub record_matches: bool,
    /// Human-readable details of any failure.
    pub problems: Vec<String>,
}

impl CheckReport {
    /// Did every check pass?
    pub fn passed(&self) -> bool {
        self.all_valid && self.states_match && self.goal_reached && self.record_matches
    }
}

/// The first field (a path such as `trajectory.q[10][0]`) where two plan files differ.
pub fn first_difference(a: &PlanFile, b: &PlanFile) -> Option<String> {
    use serde_json::Value;
    fn walk(a: &Value, b: &Value, field: String) -> Option<String> {
        match (a, b) {
            (Value::Object(x), Value::Object(y)) => {
                let keys: std::collections::BTreeSet<&String> = x.keys().chain(y.keys()).collect();
                keys.into_iter().find_map(|k| {
                    let name = if field.is_empty() {
                        k.clone()
                    } else {
                        format!("{field}.{k}")
                    };
                    match (x.get(k), y.get(k)) {
                        (Some(u), Some(v)) => walk(u, v, name),
                        _ => Some(name),
                    }
                })
            }
            (Value::Array(x), Value::Array(y)) if x.len() == y.len() => x
                .iter()
                .zip(y)
                .enumerate()
                .find_map(|(i, (u, v))| walk(u, v, format!("{field}[{i}]"))),
            _ if a == b => None,
            _ => Some(field),
        }
    }
    let value = |p: &PlanFile| serde_json::to_value(p).expect("plan files serialise");
    walk(&value(a), &value(b), String::new())
}

/// Every value of `values` finite, or an error naming `field`.
fn finite<'a>(field: &str, values: impl IntoIterator<Item = &'a f64>) -> Result<(), String> {
    match values.into_iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(format!("{field}: value {i} is not a finite number")),
    }
}

/// The JSON file at `path` (at most `max_bytes`, a regular file), parsed; errors name the
/// file, and the field where serde can say.
pub fn read_json<T: serde::de::DeserializeOwned>(path: &Path, max_bytes: u64) -> Result<T, String> {
    let text = crate::input::read_text(path, max_bytes)
        .map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| {
        format!(
            "{}: {}",
            path.display(),
            crate::input::shorten_quoted(&e.to_string())
        )
    })
}

impl PlanFile {
    /// Reads a plan file and checks its shape: the format, no unknown fields, step counts
    /// within [`MAX_PLAN_STEPS`], one value per joint and object everywhere, finite
    /// numbers. Errors name the file and the field.
    pub fn read(path: &Path) -> Result<PlanFile, String> {
        let plan: PlanFile = read_json(path, crate::input::MAX_PLAN_BYTES)?;
        if let Some(field) = plan.unknown.keys().next() {
            return Err(format!("{}: unknown field `{field}`", path.display()));
        }
        if plan.format != FORMAT {
            return Err(format!(
                "{}: format is '{}', expected '{FORMAT}'",
                path.display(),
                plan.format
            ));
        }
        plan.check_shape()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(plan)
    }

    /// The checks of [`PlanFile::read`] after parsing.
    fn check_shape(&self) -> Result<(), String> {
        let (dof, objects) = (self.joints.len(), self.objects.len());
        let state = |field: &str, q: &[f64], poses: &[[f64; 3]]| -> Result<(), String> {
            if q.len() != dof || poses.len() != objects {
                return Err(format!(
                    "{field}: {} joint values and {} object poses for {dof} joints and {objects} objects",
                    q.len(),
                    poses.len()
                ));
            }
            finite(field, q.iter().chain(poses.iter().flatten()))
        };
        finite("step", [&self.step])?;
        self.settings.check()?;
        self.metrics.check(self.objects.len())?;
        if let Some(r) = &self.robustness {
            r.check()?;
        }
        state("start", &self.start.q, &self.start.objects)?;
        let mut total = 0usize;
        for (i, c) in self.controls.iter().enumerate() {
            let field = |name: &str| format!("controls[{i}].{name}");
            total = total.saturating_add(c.steps);
            if c.steps == 0 || total > MAX_PLAN_STEPS {
                return Err(format!(
                    "{}: {} steps; a control has at least 1 and a plan at most {MAX_PLAN_STEPS} in all",
                    field("steps"),
                    c.steps
                ));
            }
            if c.nullspace.len() != dof {
                return Err(format!(
                    "{}: {} values for {dof} joints",
                    field("nullspace"),
                    c.nullspace.len()
                ));
            }
            finite(&field("ee_velocity"), &c.ee_velocity)?;
            finite(&field("nullspace"), &c.nullspace)?;
            state(&field("state"), &c.state.q, &c.state.objects)?;
        }
        let t = &self.trajectory;
        if t.q.len() != t.times.len() || t.objects.len() != t.times.len() {
            return Err(format!(
                "trajectory: {} times, {} joint samples and {} object samples",
                t.times.len(),
                t.q.len(),
                t.objects.len()
            ));
        }
        for (k, (q, poses)) in t.q.iter().zip(&t.objects).enumerate() {
            state(&format!("trajectory sample {k}"), q, poses)?;
        }
        finite("trajectory.times", &t.times)
    }

    /// Loads the scene the plan names (relative to the plan file's folder) and checks
    /// that the plan's joints and objects are the scene's, by name and in order. A
    /// re-planned plan's scene starts where the plan does ([`Scene::with_start`]).
    pub fn load_scene(&self, plan_path: &Path) -> Result<Scene, String> {
        let path = self.scene_path(plan_path);
        let is_yaml = path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("yaml") || e.eq_ignore_ascii_case("yml"));
        if !is_yaml {
            return Err(format!(
                "{}: scene: '{}' is not a scene file (.yaml or .yml)",
                plan_path.display(),
                crate::input::shorten_quoted(&self.scene)
            ));
        }
        let scene = Scene::load(&path).map_err(|e| e.to_string())?;
        let joints: Vec<&str> = (0..scene.robot.dof())
            .map(|i| scene.robot.chain.dof_joint(i).name.as_str())
            .collect();
        let objects: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
        if self.joints != joints {
            return Err(format!(
                "{}: joints: {:?} are not the scene's joints {joints:?}",
                plan_path.display(),
                self.joints
            ));
        }
        if self.objects != objects {
            return Err(format!(
                "{}: objects: {:?} are not the scene's objects {objects:?}",
                plan_path.display(),
                self.objects
            ));
        }
        match self.replanned {
            Some(_) => scene
                .with_start(&self.start.state(), plan_path)
                .map_err(|e| format!("{e} (the plan's start)")),
            None => Ok(scene),
        }
    }

    /// The plan file's text (pretty JSON, one trailing newline).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("plan files serialise") + "\n"
    }

    /// The scene file: the recorded path, relative to the plan file's folder.
    pub fn scene_path(&self, plan_path: &Path) -> PathBuf {
        plan_path
            .parent()
            .unwrap_or(Path::new("."))
            .join(&self.scene)
    }

    /// How a plan file written to `plan_path` names `scene_path`: relative to the plan
    /// file's folder, so the pair can be moved together and read from any folder; an
    /// absolute path stays absolute.
    pub fn scene_reference(scene_path: &Path, plan_path: &Path) -> String {
        if scene_path.is_absolute() {
            return scene_path.to_string_lossy().into_owned();
        }
        let folder = plan_path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        crate::input::relative_path(folder, scene_path)
            .unwrap_or_else(|_| scene_path.to_string_lossy().into_owned())
    }

    /// Builds a plan file by simulating `controls` in the planner's problem of `scene`:
    /// states, per-step contacts, metrics and the executable trajectory. `before` are the
    /// metrics before shortcutting (default: the same as after).
    pub fn build(
        scene_ref: &str,
        scene: Scene,
        settings: &PlanSettings,
        controls: &[PathControl],
        before: Option<PathMetrics>,
    ) -> Result<PlanFile, String> {
        let path = Problem::new(scene.clone(), settings.planner).simulate(controls, true);
        PlanFile::from_simulation(scene_ref, &scene, settings, controls, &path, before)
    }

    /// [`PlanFile::build`] from `path`, `controls` as simulated in `scene` with every step
    /// recorded (a finished path's [`crate::planning::FinishedPath::simulation`]), without
    /// simulating them again: after the search, a long path's simulations are what is
    /// left of the time limit.
    pub fn from_simulation(
        scene_ref: &str,
        scene: &Scene,
        settings: &PlanSettings,
        controls: &[PathControl],
        path: &SimulatedPath,
        before: Option<PathMetrics>,
    ) -> Result<PlanFile, String> {
        let steps: usize = controls.iter().map(|c| c.steps).sum();
        if path.states.len() != controls.len() + 1 || path.step_states.len() != steps + 1 {
            return Err(format!(
                "internal error: a simulation of {} states and {} step states for {} controls of {steps} steps",
                path.states.len(),
                path.step_states.len(),
                controls.len()
            ));
        }
        if let Some((i, reason)) = &path.stopped_by {
            return Err(format!("the plan does not simulate: control {i}: {reason}"));
        }
        let link_names: Vec<&str> = scene
            .robot
            .chain
            .links
            .iter()
            .map(|l| l.name.as_str())
            .collect();
        let records = controls
            .iter()
            .enumerate()
            .map(|(i, c)| ControlRecord {
                ee_velocity: c.action.velocity,
                nullspace: c.action.nullspace.as_slice().to_vec(),
                steps: c.steps,
                duration: c.steps as f64 * scene.planner.step,
                state: StateRecord::from_state(&path.states[i + 1]),
                contacts: path.contacts[i]
                    .iter()
                    .enumerate()
                    .flat_map(|(step, pushes)| pushes.iter().map(move |p| (step, p)))
                    .map(|(step, p)| Contact {
                        step,
                        link: link_names[p.link].to_string(),
                        object: scene.objects[p.object].name.clone(),
                        force: p.force,
                    })
                    .collect(),
            })
            .collect();
        let dof = scene.robot.dof();
        Ok(PlanFile {
            format: FORMAT.into(),
            scene: scene_ref.into(),
            scene_name: scene.name.clone(),
            settings: settings.clone(),
            step: scene.planner.step,
            physics_model: scene.physics.model,
            object_pushing: scene.physics.object_pushing,
            margins: Some(Margins {
                goal: match scene.goal {
                    crate::scene::Goal::ObjectInDisc { margin, .. } => margin,
                    crate::scene::Goal::Configuration { .. } | crate::scene::Goal::Grasp { .. } => {
                        0.0
                    }
                },
                object_clearance: scene.physics.object_clearance,
                edge_clearance: scene.physics.edge_clearance,
                tipping: scene.physics.tipping_margin,
                arm_clearance: scene.physics.arm_clearance,
            }),
            solved: scene.goal.is_satisfied(path.final_state()),
            metrics: Metrics {
                before_shortcut: before.unwrap_or(path.metrics),
                after_shortcut: path.metrics,
            },
            joints: (0..dof)
                .map(|i| scene.robot.chain.dof_joint(i).name.clone())
                .collect(),
            objects: scene.objects.iter().map(|o| o.name.clone()).collect(),
            start: StateRecord::from_state(&scene.start),
            controls: records,
            trajectory: executable(scene, controls, &path.step_states)?,
            robustness: None,
            reach: None,
            grasp_after: None,
            replanned: None,
            unknown: Default::default(),
        })
    }

    /// Checks that the plan's trajectory is the one its controls give in `scene` (the
    /// plan's scene, [`PlanFile::load_scene`]): what `execute` plays must be the plan, not
    /// an arbitrary list of samples.
    pub fn check_trajectory(&self, scene: &Scene) -> Result<(), String> {
        if self.rebuilt(scene.clone())?.trajectory != self.trajectory {
            return Err(
                "trajectory: not the one the plan's controls give (`pushplan check` names the difference)"
                    .into(),
            );
        }
        Ok(())
    }

    /// The plan file its controls give in `scene` (the plan's scene), with what cannot
    /// be re-derived from them (the metrics before shortcutting, unless the plan was not
    /// shortcut; robustness) copied over.
    fn rebuilt(&self, scene: Scene) -> Result<PlanFile, String> {
        let shortcut = self.settings.shortcut > 0.0;
        let mut rebuilt = PlanFile::build(
            &self.scene,
            scene.clone(),
            &self.settings,
            &self.path_controls(),
            shortcut.then_some(self.metrics.before_shortcut),
        )?;
        rebuilt.robustness.clone_from(&self.robustness);
        rebuilt.replanned.clone_from(&self.replanned);
        rebuilt.grasp_after.clone_from(&self.grasp_after);
        match &self.reach {
            Some(reach) => rebuilt.with_reach(&scene, reach.clone()),
            None => Ok(rebuilt),
        }
    }

    /// The state the controls end in.
    pub fn end_state(&self) -> State {
        self.controls
            .last()
            .map_or(&self.start, |c| &c.state)
            .state()
    }

    /// The reach's waypoints (none without a reach).
    pub fn reach_waypoints(&self) -> Vec<nalgebra::DVector<f64>> {
        self.reach.as_ref().map_or_else(Vec::new, |r| {
            r.waypoints
                .iter()
                .map(|q| nalgebra::DVector::from_column_slice(q))
                .collect()
        })
    }

    /// Adds a reach after the controls, checked in `scene` (the plan's): the plan is
    /// solved when the reach ends in a grasp region and, if there are controls, they
    /// reach the scene's goal; the trajectory goes on with the reach, timed within the
    /// joints' velocity and acceleration limits, at rest at both ends.
    pub fn with_reach(mut self, scene: &Scene, reach: ReachRecord) -> Result<PlanFile, String> {
        let object = crate::planning::reach::graspable_object(scene, &reach.object)?;
        self.reach = Some(reach);
        let from = self.end_state();
        let waypoints = self.reach_waypoints();
        crate::planning::reach::check_reach(scene, &from, object, &waypoints)
            .map_err(|why| format!("reach: {why}"))?;
        if self.controls.is_empty() {
            self.solved = true;
        }
        let states = crate::planning::reach::reach_states(&from, &waypoints);
        let radii: Vec<f64> = scene.objects.iter().map(|o| o.bounding_radius).collect();
        // The plan's own pace does not bound a reach: only the joints' limits do.
        let motion = crate::planning::trajectory::time_parameterise(
            &scene.robot,
            &radii,
            &states,
            &[],
            f64::MIN_POSITIVE,
            &scene.trajectory,
            self.trajectory.rate,
        );
        let t = &mut self.trajectory;
        let offset = t.times.last().copied().unwrap_or(0.0);
        for k in 1..motion.times.len() {
            t.times.push(offset + motion.times[k]);
            t.q.push(motion.q[k].clone());
            t.objects.push(motion.objects[k].clone());
        }
        Ok(self)
    }

    /// The plan's controls from `at` on (at most the control count), and what they do
    /// re-simulated from where `from` starts: reach its goal, or how far they are valid
    /// ([`crate::planning::rest`]). `replan` keeps them, repairs them or searches anew.
    pub fn rest_from(&self, at: usize, from: &Scene) -> (Vec<PathControl>, RestFrom) {
        let rest = self.path_controls().split_off(at.min(self.controls.len()));
        let problem = Problem::new(from.clone(), self.settings.planner);
        let (verdict, _) = problem.rest_from(&rest, |s| from.goal.is_satisfied(s));
        (rest, verdict)
    }

    /// The controls of the plan.
    pub fn path_controls(&self) -> Vec<PathControl> {
        self.controls
            .iter()
            .map(|c| PathControl {
                action: crate::robot::EeAction {
                    velocity: c.ee_velocity,
                    nullspace: nalgebra::DVector::from_column_slice(&c.nullspace),
                },
                steps: c.steps,
            })
            .collect()
    }

    /// Re-simulates the plan with the model from the scene's start, independently of the
    /// planner: every state valid, the recorded states reproduced, the goal reached, and
    /// everything else the file records about the path (start, contacts, durations,
    /// metrics after shortcutting, `solved`, margins, `step`, the trajectory) equal to
    /// what the re-simulation gives (the metrics before shortcutting too, when the plan
    /// was not shortcut), and the robustness record's rate measured again (the plan's
    /// seed, the record's trials). Not checkable here: how the plan was made (planner
    /// settings, seed; [`PlanFile::read`] checks them against their limits) and the
    /// metrics of a shortcut plan's path as found, which the file does not hold.
    pub fn check(&self, plan_path: &Path) -> Result<CheckReport, String> {
        let scene = self.load_scene(plan_path)?;
        let problem = Problem::new(scene.clone(), self.settings.planner);
        let mut problems = Vec::new();
        if self.start.flat() != problem.scene().start.to_flat() {
            problems.push("start: the plan's start state is not the scene's".to_string());
        }
        let sim = problem.simulate(&self.path_controls(), false);
        if let Some((i, reason)) = &sim.stopped_by {
            problems.push(format!(
                "control {i} stops after {} of {} steps: {reason}",
                sim.contacts[*i].len(),
                self.controls[*i].steps
            ));
        }
        let mut states_match = sim.states.len() == self.controls.len() + 1;
        for (i, c) in self.controls.iter().enumerate() {
            let simulated = sim.states.get(i + 1).map(State::to_flat);
            if simulated.map(|s| {
                s.iter()
                    .zip(c.state.flat())
                    .any(|(a, b)| a.to_bits() != b.to_bits())
            }) != Some(false)
            {
                states_match = false;
                problems.push(format!(
                    "control {i}: the re-simulated state differs from the recorded one"
                ));
                break;
            }
        }
        // A reach alone (`--goal grasp:OBJECT`) has the grasp as its goal.
        let grasp_only = self.reach.is_some() && self.controls.is_empty();
        let mut goal_reached = grasp_only || problem.scene().goal.is_satisfied(sim.final_state());
        if !goal_reached {
            problems.push("the goal is not reached".to_string());
        }
        let mut reach_valid = true;
        if let (Some(object), None) = (&self.grasp_after, &self.reach) {
            goal_reached = false;
            reach_valid = false;
            problems.push(format!(
                "reach: a grasp of '{object}' after the controls was asked for (`plan --grasp`) \
                 and none was found: the plan is not solved"
            ));
        }
        if let Some(reach) = &self.reach {
            let checked = crate::planning::reach::graspable_object(problem.scene(), &reach.object)
                .and_then(|object| {
                    crate::planning::reach::check_reach(
                        problem.scene(),
                        sim.final_state(),
                        object,
                        &self.reach_waypoints(),
                    )
                });
            if let Err(why) = checked {
                goal_reached = false;
                reach_valid = false;
                problems.push(format!("reach: {why}"));
            }
        }
        let mut record_matches = problems.is_empty();
        if record_matches {
            let mut rebuilt = self.rebuilt(scene)?;
            if let Some(record) = &mut rebuilt.robustness {
                let rate = |trials, seed| {
                    problem
                        .robustness(&self.path_controls(), &Noise::default(), trials, seed)
                        .success_rate
                };
                record.success_rate = rate(record.trials, self.settings.seed);
                if let Some(unseen) = &mut record.unseen {
                    unseen.success_rate = rate(unseen.trials, unseen_seed(self.settings.seed));
                }
            }
            if let Some(field) = first_difference(self, &rebuilt) {
                record_matches = false;
                problems.push(format!("{field}: differs from the re-simulation"));
            }
        }
        Ok(CheckReport {
            all_valid: sim.valid(),
            states_match,
            goal_reached,
            reach_valid,
            record_matches,
            problems,
        })
    }
}
