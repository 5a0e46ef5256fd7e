//! The bridge between the Rust model and the OMPL side (cxx). Thin on purpose: states and
//! controls cross as flat arrays, every call catches panics so none unwinds into C++,
//! and every failure crosses as an error (a C++ exception) with its message.
//!
//! Layouts:
//! - state: `[q_0 .. q_{n-1}, x_1, y_1, theta_1, .., x_M, y_M, theta_M]`;
//! - control: `[vx, vy, omega_z, z_0 .. z_{n-1}]` (end-effector velocity, null-space sample).

use crate::darrt;
use crate::distance::DistanceMetric;
use crate::math::Pose2;
use crate::path::{PathControl, SimulatedPath};
use crate::propagate::Propagator;
use crate::robot::EeAction;
use crate::scene::{Goal, Scene};
use crate::state::State;
use crate::static_clutter::StaticClutter;
use crate::validity::check_state;
use nalgebra::DVector;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

#[cxx::bridge(namespace = "pushplan::bridge")]
pub mod bridge {
    /// The planners pushplan runs ([`crate::planner::PlannerKind`]): C++'s
    /// `pushplan::PlannerKind` of `include/pushplan/pushplan.h`, checked against this
    /// list by cxx.
    #[namespace = "pushplan"]
    #[derive(Debug, Hash)]
    enum PlannerKind {
        PcRrt,
        StaticRrt,
        Darrt,
        Kpiece,
        Est,
        Pdst,
        Sst,
    }

    /// What the OMPL side needs to know about a scene.
    #[derive(Debug, Clone)]
    pub struct SceneInfo {
        pub name: String,
        pub dof: usize,
        pub objects: usize,
        pub joint_names: Vec<String>,
        pub joint_lower: Vec<f64>,
        pub joint_upper: Vec<f64>,
        pub object_names: Vec<String>,
        pub link_names: Vec<String>,
        /// Table extent (m).
        pub table_min_x: f64,
        pub table_max_x: f64,
        pub table_min_y: f64,
        pub table_max_y: f64,
        /// Planner parameters from the scene file.
        pub step: f64,
        pub min_duration: f64,
        pub max_duration: f64,
        pub max_ee_speed: f64,
        pub max_ee_turn_rate: f64,
        pub max_nullspace_speed: f64,
        pub k: u32,
        pub goal_bias: f64,
        pub time_limit: f64,
        pub seed: u64,
        /// Index of the goal object, or -1 for a configuration goal.
        pub goal_object: i64,
        pub goal_center_x: f64,
        pub goal_center_y: f64,
        pub goal_radius: f64,
        pub goal_configuration: Vec<f64>,
        pub start: Vec<f64>,
    }

    /// A link pushing an object during one step of a simulated plan.
    #[derive(Debug, Clone, PartialEq)]
    pub struct PlanContact {
        pub control: usize,
        pub step: usize,
        pub link: usize,
        pub object: usize,
        /// Normal force (N).
        pub force: f64,
    }

    /// A plan re-simulated by the model.
    #[derive(Debug, Clone)]
    pub struct Simulation {
        /// The state after each control, flat, starting with the start state.
        pub states: Vec<f64>,
        pub contacts: Vec<PlanContact>,
        /// Every step valid (no control stopped early).
        pub valid: bool,
        pub goal_reached: bool,
        /// Why the simulation is not valid, empty if it is.
        pub message: String,
    }

    /// The executable trajectory of a plan (see `trajectory::Trajectory`), flat: per
    /// sample the joint values (`q`) and the object poses x, y, yaw (`objects`, every
    /// object of the scene).
    #[derive(Debug, Clone)]
    pub struct TrajectoryOut {
        pub rate: f64,
        pub times: Vec<f64>,
        pub q: Vec<f64>,
        pub objects: Vec<f64>,
    }

    /// Metrics of a path (see `path::PathMetrics`).
    #[derive(Debug, Clone, Copy, Default)]
    pub struct Metrics {
        pub joint_length: f64,
        pub ee_length: f64,
        pub object_displacement: f64,
        pub objects_moved: usize,
        pub links_in_contact: usize,
        pub duration: f64,
    }

    /// A shortcut path.
    #[derive(Debug, Clone)]
    pub struct Shortcut {
        pub controls: Vec<f64>,
        pub steps: Vec<usize>,
        pub before: Metrics,
        pub after: Metrics,
        pub attempts: usize,
        pub accepted: usize,
    }

    /// A DARRT path checked by the model (see `darrt::check_path`).
    #[derive(Debug, Clone)]
    pub struct PrimitiveCheck {
        pub valid: bool,
        pub goal_reached: bool,
        /// Why the path is invalid, empty if it is valid.
        pub message: String,
        pub metrics: Metrics,
        /// Time of each step at the joints' velocity limits (s).
        pub durations: Vec<f64>,
    }

    /// Options of one planning run (the CLI's).
    #[derive(Debug, Clone)]
    pub struct SolveOptions {
        pub time_limit: f64,
        pub seed: u64,
        pub k: u32,
        pub goal_bias: f64,
        pub planner: PlannerKind,
        pub intermediate_states: bool,
        pub progress: bool,
        /// Perturbed re-simulations a solution must survive (0: no robustness check).
        pub robust_trials: usize,
        /// The fraction of them that must reach the goal.
        pub robust_rate: f64,
    }

    /// The outcome of one planning run.
    #[derive(Debug, Clone)]
    pub struct SolveOutput {
        pub exact: bool,
        pub approximate: bool,
        pub planning_time: f64,
        pub tree_size: usize,
        pub propagation_steps: u64,
        /// States along the path (flat), controls (flat) and step counts per control.
        pub states: Vec<f64>,
        pub controls: Vec<f64>,
        pub steps: Vec<usize>,
        /// Fraction of the perturbed re-simulations that reached the goal (-1: not checked).
        pub robustness: f64,
    }

    /// Options of a benchmark of one scene.
    #[derive(Debug, Clone)]
    pub struct BenchOptions {
        pub planners: Vec<PlannerKind>,
        pub runs: u32,
        pub time_limit: f64,
        pub seed: u64,
        /// Shortcutting budget (s of work) measured after each solved run.
        pub shortcut: f64,
        /// Where the OMPL log goes.
        pub log: String,
    }

    extern "Rust" {
        type Model;
        fn load_model(path: &str, static_clutter: bool) -> Result<Box<Model>>;
        fn model_from_yaml(yaml: &str, source: &str, static_clutter: bool) -> Result<Box<Model>>;
        fn info(self: &Model) -> SceneInfo;
        fn propagate(
            self: &mut Model,
            state: &[f64],
            control: &[f64],
            steps: usize,
            result: &mut [f64],
        ) -> Result<bool>;
        fn is_valid(self: &mut Model, state: &[f64]) -> Result<bool>;
        fn distance(self: &Model, a: &[f64], b: &[f64]) -> Result<f64>;
        fn max_extent(self: &Model) -> f64;
        fn goal_distance(self: &Model, state: &[f64]) -> Result<f64>;
        fn simulate(self: &mut Model, controls: &[f64], steps: &[usize]) -> Result<Simulation>;
        fn trajectory(self: &mut Model, controls: &[f64], steps: &[usize])
            -> Result<TrajectoryOut>;
        fn robustness(
            self: &Model,
            controls: &[f64],
            steps: &[usize],
            trials: usize,
            seed: u64,
        ) -> Result<f64>;
        fn shortcut(
            self: &mut Model,
            controls: &[f64],
            steps: &[usize],
            seconds: f64,
            seed: u64,
        ) -> Result<Shortcut>;
        fn propagation_steps(self: &Model) -> u64;
        fn set_static_clutter(self: &mut Model, on: bool);
        fn static_clutter(self: &Model) -> bool;
        fn projection(self: &Model, state: &[f64]) -> Result<Vec<f64>>;
        fn darrt_transit(self: &Model, from: &[f64], to: &[f64]) -> Result<bool>;
        fn darrt_approach(
            self: &Model,
            state: &[f64],
            object: usize,
            target: &[f64],
            result: &mut [f64],
        ) -> Result<bool>;
        fn darrt_carry(
            self: &Model,
            state: &[f64],
            object: usize,
            target: &[f64],
        ) -> Result<Vec<f64>>;
        fn darrt_check(self: &Model, states: &[f64]) -> Result<PrimitiveCheck>;
        fn planner_name(kind: PlannerKind) -> &'static str;
        fn planner_kind(name: &str) -> Result<PlannerKind>;
    }

    unsafe extern "C++" {
        include!("pushplan/pushplan.h");
        #[namespace = "pushplan"]
        type PlannerKind;
        include!("pushplan/cpp/solve.h");
        /// Plans the scene file with OMPL (the CLI's entry point).
        fn solve(scene_path: &str, options: &SolveOptions) -> Result<SolveOutput>;
        include!("pushplan/cpp/benchmark.h");
        /// Benchmarks a scene with ompl::tools::Benchmark and writes the log.
        fn benchmark_scene(scene_path: &str, options: &BenchOptions) -> Result<()>;
    }
}

use bridge::PlannerKind;
pub use bridge::{
    BenchOptions, Metrics, PlanContact, PrimitiveCheck, SceneInfo, Shortcut, Simulation,
    SolveOptions, SolveOutput, TrajectoryOut,
};

/// The model as the OMPL side holds it: a scene, its propagator and metric.
pub struct Model {
    propagator: Propagator,
    /// The Static RRT baseline's view of the same problem, used while `static_mode`.
    static_view: StaticClutter,
    static_mode: bool,
    metric: DistanceMetric,
    /// The last state `propagate` produced and whether it was valid: OMPL asks
    /// `isValid` of exactly that state next, and the propagation already knows.
    last_result: Option<(Vec<f64>, bool)>,
    steps_taken: u64,
}

fn planner_name(kind: PlannerKind) -> &'static str {
    kind.name()
}

fn planner_kind(name: &str) -> Result<PlannerKind, String> {
    name.parse()
}

/// Runs `f`, turning a panic into an error message: nothing unwinds into C++.
fn guarded<T>(what: &str, f: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(result) => result,
        Err(panic) => {
            let detail = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Err(format!("internal error in {what}: {detail}"))
        }
    }
}

fn load_model(path: &str, static_clutter: bool) -> Result<Box<Model>, String> {
    guarded("load_model", || {
        let scene = Scene::load(path).map_err(|e| e.to_string())?;
        Ok(Box::new(Model::new(scene, static_clutter)))
    })
}

fn model_from_yaml(yaml: &str, source: &str, static_clutter: bool) -> Result<Box<Model>, String> {
    guarded("model_from_yaml", || {
        let scene = Scene::from_yaml(yaml, Path::new(source)).map_err(|e| e.to_string())?;
        Ok(Box::new(Model::new(scene, static_clutter)))
    })
}

impl Model {
    pub fn new(scene: Scene, static_clutter: bool) -> Model {
        let scene = scene.planned_by(if static_clutter {
            PlannerKind::StaticRrt
        } else {
            PlannerKind::PcRrt
        });
        Model {
            metric: DistanceMetric::from_scene(&scene),
            static_view: StaticClutter::new(&scene),
            static_mode: false,
            propagator: Propagator::new(scene),
            last_result: None,
            steps_taken: 0,
        }
    }

    pub fn scene(&self) -> &Scene {
        self.propagator.scene()
    }

    fn state_len(&self) -> usize {
        self.scene().robot.dof() + 3 * self.scene().objects.len()
    }

    /// The state in a flat array, checking its length.
    fn unpack(&self, flat: &[f64]) -> Result<State, String> {
        if flat.len() != self.state_len() {
            return Err(format!(
                "a state has {} values, this scene needs {}",
                flat.len(),
                self.state_len()
            ));
        }
        Ok(unpack_state(flat, self.scene().robot.dof()))
    }

    fn action(&self, control: &[f64]) -> Result<EeAction, String> {
        let dof = self.scene().robot.dof();
        if control.len() != 3 + dof {
            return Err(format!(
                "a control has {} values, this scene needs {}",
                control.len(),
                3 + dof
            ));
        }
        Ok(EeAction {
            velocity: [control[0], control[1], control[2]],
            nullspace: DVector::from_column_slice(&control[3..]),
        })
    }

    pub fn info(&self) -> SceneInfo {
        let scene = self.scene();
        let chain = &scene.robot.chain;
        let limits = chain.limits();
        let (goal_object, center, radius, configuration) = match &scene.goal {
            Goal::ObjectInDisc {
                object,
                center,
                radius,
                margin,
            } => (*object as i64, *center, radius - margin, vec![]),
            Goal::Configuration { q, tolerance } => (
                -1,
                nalgebra::Vector2::zeros(),
                *tolerance,
                q.as_slice().to_vec(),
            ),
        };
        let p = &scene.planner;
        SceneInfo {
            name: scene.name.clone(),
            dof: scene.robot.dof(),
            objects: scene.objects.len(),
            joint_names: (0..chain.dof())
                .map(|i| chain.dof_joint(i).name.clone())
                .collect(),
            joint_lower: limits.iter().map(|l| l.0).collect(),
            joint_upper: limits.iter().map(|l| l.1).collect(),
            object_names: scene.objects.iter().map(|o| o.name.clone()).collect(),
            link_names: chain.links.iter().map(|l| l.name.clone()).collect(),
            table_min_x: scene.table.x.0,
            table_max_x: scene.table.x.1,
            table_min_y: scene.table.y.0,
            table_max_y: scene.table.y.1,
            step: p.step,
            min_duration: p.min_duration,
            max_duration: p.max_duration,
            max_ee_speed: p.max_ee_speed,
            max_ee_turn_rate: p.max_ee_turn_rate,
            max_nullspace_speed: p.max_nullspace_speed,
            k: p.k,
            goal_bias: p.goal_bias,
            time_limit: p.time_limit,
            seed: p.seed,
            goal_object,
            goal_center_x: center.x,
            goal_center_y: center.y,
            goal_radius: radius,
            goal_configuration: configuration,
            start: pack_state(&scene.start),
        }
    }

    /// Holds `control` for `steps` steps from `state`; writes the state reached (or, if a
    /// step was invalid, the invalid state it tried to reach) and says whether it is valid.
    pub fn propagate(
        &mut self,
        state: &[f64],
        control: &[f64],
        steps: usize,
        result: &mut [f64],
    ) -> Result<bool, String> {
        guarded("propagate", || {
            let start = self.unpack(state)?;
            let action = self.action(control)?;
            if result.len() != state.len() {
                return Err("the result state has the wrong length".into());
            }
            let (valid, taken, reached) = if self.static_mode {
                let view = &mut self.static_view;
                let run = view
                    .propagator
                    .propagate_steps(&view.reduce(&start), &action, steps);
                let valid = run.stopped_by.is_none();
                let reached = if valid {
                    run.state
                } else {
                    view.propagator.attempted_state()
                };
                (valid, run.steps, view.expand(&reached))
            } else {
                let run = self.propagator.propagate_steps(&start, &action, steps);
                let valid = run.stopped_by.is_none();
                let reached = if valid {
                    run.state
                } else {
                    self.propagator.attempted_state()
                };
                (valid, run.steps, reached)
            };
            self.steps_taken += taken as u64 + u64::from(!valid);
            write_state(&reached, result);
            self.last_result = Some((result.to_vec(), valid));
            Ok(valid)
        })
    }

    pub fn is_valid(&mut self, state: &[f64]) -> Result<bool, String> {
        guarded("is_valid", || {
            if let Some((last, valid)) = &self.last_result {
                if last.len() == state.len()
                    && last
                        .iter()
                        .zip(state)
                        .all(|(a, b)| a.to_bits() == b.to_bits())
                {
                    return Ok(*valid);
                }
            }
            let state = self.unpack(state)?;
            if self.static_mode {
                let view = &self.static_view;
                return Ok(view.clutter_in_place(&state)
                    && check_state(view.propagator.scene(), &view.reduce(&state)).is_ok());
            }
            Ok(check_state(self.scene(), &state).is_ok())
        })
    }

    pub fn distance(&self, a: &[f64], b: &[f64]) -> Result<f64, String> {
        guarded("distance", || {
            let n = self.state_len();
            if a.len() != n || b.len() != n {
                return Err(format!(
                    "states of {} and {} values, this scene needs {n}",
                    a.len(),
                    b.len()
                ));
            }
            Ok(self.metric.distance_flat(a, b))
        })
    }

    /// The largest distance between two states within the bounds.
    pub fn max_extent(&self) -> f64 {
        self.metric.max_extent(self.scene())
    }

    pub fn goal_distance(&self, state: &[f64]) -> Result<f64, String> {
        guarded("goal_distance", || {
            Ok(self.scene().goal.distance(&self.unpack(state)?))
        })
    }

    /// End-effector xy and goal-object xy (m); the goal object's xy is (0, 0) for a
    /// configuration goal.
    pub fn projection(&self, state: &[f64]) -> Result<Vec<f64>, String> {
        guarded("projection", || {
            let state = self.unpack(state)?;
            let robot = &self.scene().robot;
            let tool = robot.tool_pose(&robot.link_poses(&state.q)).translation;
            let goal = match self.scene().goal {
                Goal::ObjectInDisc { object, .. } => state.objects[object].translation(),
                Goal::Configuration { .. } => nalgebra::Vector2::zeros(),
            };
            Ok(vec![tool.x, tool.y, goal.x, goal.y])
        })
    }

    /// Switches to (or from) the Static RRT baseline: clutter objects become static
    /// obstacles at their start poses.
    pub fn set_static_clutter(&mut self, on: bool) {
        self.static_mode = on;
        self.last_result = None;
    }

    pub fn static_clutter(&self) -> bool {
        self.static_mode
    }

    pub fn propagation_steps(&self) -> u64 {
        self.steps_taken
    }

    /// Re-simulates a plan from the scene's start: each control (flat, one after another)
    /// held for its step count.
    pub fn simulate(&mut self, controls: &[f64], steps: &[usize]) -> Result<Simulation, String> {
        guarded("simulate", || {
            let controls = self.path_controls(controls, steps)?;
            let path = self.resimulate(&controls, false);
            let object_index = |i: usize| {
                if self.static_mode {
                    self.static_view.full_object(i)
                } else {
                    i
                }
            };
            let mut contacts = Vec::new();
            for (i, control) in path.pushes.iter().enumerate() {
                for (step, pushes) in control.iter().enumerate() {
                    contacts.extend(pushes.iter().map(|p| PlanContact {
                        control: i,
                        step,
                        link: p.link,
                        object: object_index(p.object),
                        force: p.force,
                    }));
                }
            }
            let full = |s: &State| {
                if self.static_mode {
                    self.static_view.expand(s)
                } else {
                    s.clone()
                }
            };
            let message = match &path.stopped_by {
                Some((i, reason)) => format!(
                    "control {i} stops after {} of {} steps: {reason}",
                    path.pushes[*i].len(),
                    steps[*i]
                ),
                None => String::new(),
            };
            Ok(Simulation {
                states: path
                    .states
                    .iter()
                    .flat_map(|s| pack_state(&full(s)))
                    .collect(),
                contacts,
                valid: path.valid(),
                goal_reached: self.scene().goal.is_satisfied(path.final_state()),
                message,
            })
        })
    }

    /// The executable trajectory of a plan, as plan files hold it (objects of the whole
    /// scene, Static RRT's clutter at rest).
    pub fn trajectory(
        &mut self,
        controls: &[f64],
        steps: &[usize],
    ) -> Result<TrajectoryOut, String> {
        guarded("trajectory", || {
            let controls = self.path_controls(controls, steps)?;
            let path = self.resimulate(&controls, true);
            if let Some((i, reason)) = &path.stopped_by {
                return Err(format!("the plan does not simulate: control {i}: {reason}"));
            }
            let scene = if self.static_mode {
                self.static_view.propagator.shared_scene()
            } else {
                self.propagator.shared_scene()
            };
            let t = crate::trajectory::executable(&scene, &controls, &path.step_states);
            let mut out = TrajectoryOut {
                rate: t.rate,
                times: t.times,
                q: t.q.into_iter().flatten().collect(),
                objects: Vec::new(),
            };
            for sample in &t.objects {
                let state = State {
                    q: nalgebra::DVector::zeros(0),
                    objects: sample
                        .iter()
                        .map(|p| Pose2::new(p[0], p[1], p[2]))
                        .collect(),
                };
                let full = if self.static_mode {
                    self.static_view.expand(&state)
                } else {
                    state
                };
                out.objects
                    .extend(full.objects.iter().flat_map(|p| [p.x, p.y, p.theta]));
            }
            Ok(out)
        })
    }

    /// Fraction of `trials` perturbed re-simulations of a plan that reach the goal
    /// ([`crate::robustness`], default noise, drawn from `seed`).
    pub fn robustness(
        &self,
        controls: &[f64],
        steps: &[usize],
        trials: usize,
        seed: u64,
    ) -> Result<f64, String> {
        guarded("robustness", || {
            let controls = self.path_controls(controls, steps)?;
            let scene = if self.static_mode {
                self.scene().with_static_clutter()
            } else {
                self.scene().clone()
            };
            let noise = crate::robustness::Noise::default();
            Ok(crate::robustness::robustness(&scene, &controls, &noise, trials, seed).success_rate)
        })
    }

    /// Shortcuts a plan from the scene's start (Sec. IV) with a budget of about `seconds`
    /// of work; with 0 it only measures the plan.
    pub fn shortcut(
        &mut self,
        controls: &[f64],
        steps: &[usize],
        seconds: f64,
        seed: u64,
    ) -> Result<Shortcut, String> {
        guarded("shortcut", || {
            if !(seconds.is_finite() && seconds >= 0.0) {
                return Err(format!(
                    "the shortcut budget must be zero or positive, got {seconds}"
                ));
            }
            let controls = self.path_controls(controls, steps)?;
            let start = self.scene().start.clone();
            let settings = crate::shortcut::ShortcutSettings::from_seconds(seconds, seed);
            let outcome =
                crate::shortcut::shortcut(&mut self.propagator, &start, &controls, &settings);
            Ok(Shortcut {
                controls: outcome
                    .controls
                    .iter()
                    .flat_map(|c| {
                        c.action
                            .velocity
                            .into_iter()
                            .chain(c.action.nullspace.iter().copied())
                    })
                    .collect(),
                steps: outcome.controls.iter().map(|c| c.steps).collect(),
                before: Metrics::from(&outcome.before),
                after: Metrics::from(&outcome.after),
                attempts: outcome.attempts,
                accepted: outcome.accepted,
            })
        })
    }

    /// DARRT's Transit: is the straight joint-space line from `from` to `to` (same object
    /// poses) valid?
    pub fn darrt_transit(&self, from: &[f64], to: &[f64]) -> Result<bool, String> {
        guarded("darrt_transit", || {
            let (from, to) = (self.unpack(from)?, self.unpack(to)?);
            if from.objects != to.objects {
                return Err("a transit moves no object: the object poses differ".into());
            }
            Ok(darrt::check_transit(self.scene(), &from, &to.q).is_ok())
        })
    }

    /// DARRT's Push, first part: writes the state with the hand caging `object` (ready
    /// to carry it to `target`, `[x, y, yaw]`) and returns true, or false if none is found.
    pub fn darrt_approach(
        &self,
        state: &[f64],
        object: usize,
        target: &[f64],
        result: &mut [f64],
    ) -> Result<bool, String> {
        guarded("darrt_approach", || {
            let state = self.unpack(state)?;
            let (object, target) = self.object_target(object, target)?;
            if result.len() != self.state_len() {
                return Err("the result state has the wrong length".into());
            }
            match darrt::approach(self.scene(), &state, object, &target) {
                Ok(caged) => {
                    write_state(&caged, result);
                    Ok(true)
                }
                Err(_) => Ok(false),
            }
        })
    }

    /// DARRT's Push, second part: carries the object caged in `state` to `target`
    /// (`[x, y, yaw]`). Returns the states of the carry (flat, one after another), or none
    /// if the line is blocked.
    pub fn darrt_carry(
        &self,
        state: &[f64],
        object: usize,
        target: &[f64],
    ) -> Result<Vec<f64>, String> {
        guarded("darrt_carry", || {
            let state = self.unpack(state)?;
            let (object, target) = self.object_target(object, target)?;
            let cage = darrt::Cage::of_state(self.scene(), &state, object);
            Ok(darrt::carry(self.scene(), &state, &cage, &target)
                .map(|states| states.iter().flat_map(pack_state).collect())
                .unwrap_or_default())
        })
    }

    /// Checks a DARRT path (flat states one after another) and measures it.
    pub fn darrt_check(&self, states: &[f64]) -> Result<PrimitiveCheck, String> {
        guarded("darrt_check", || {
            let n = self.state_len();
            if states.len() % n != 0 {
                return Err(format!(
                    "{} values are not whole states of {n}",
                    states.len()
                ));
            }
            let states: Vec<State> = states
                .chunks(n)
                .map(|s| unpack_state(s, self.scene().robot.dof()))
                .collect();
            Ok(match darrt::check_path(self.scene(), &states) {
                Ok(path) => PrimitiveCheck {
                    valid: true,
                    goal_reached: path.goal_reached,
                    message: String::new(),
                    metrics: Metrics::from(&path.metrics),
                    durations: path.durations,
                },
                Err(message) => PrimitiveCheck {
                    valid: false,
                    goal_reached: false,
                    message,
                    metrics: Metrics::default(),
                    durations: vec![],
                },
            })
        })
    }

    /// An object index and a target pose `[x, y, yaw]`, checked.
    fn object_target(&self, object: usize, target: &[f64]) -> Result<(usize, Pose2), String> {
        if object >= self.scene().objects.len() {
            return Err(format!(
                "object {object} does not exist ({} objects)",
                self.scene().objects.len()
            ));
        }
        match target {
            [x, y, yaw] if target.iter().all(|v| v.is_finite()) => {
                Ok((object, Pose2::new(*x, *y, *yaw)))
            }
            _ => Err(format!(
                "a target pose is [x, y, yaw], finite; got {target:?}"
            )),
        }
    }

    /// Controls in the flat layout, one after another, with their step counts.
    /// Simulates `controls` from the scene's start in the scene the planner searches
    /// (Static RRT: the reduced one).
    fn resimulate(&mut self, controls: &[PathControl], record_steps: bool) -> SimulatedPath {
        let start = self.scene().start.clone();
        let (propagator, start) = if self.static_mode {
            let reduced = self.static_view.reduce(&start);
            (&mut self.static_view.propagator, reduced)
        } else {
            (&mut self.propagator, start)
        };
        crate::path::simulate(propagator, &start, controls, record_steps)
    }

    fn path_controls(&self, controls: &[f64], steps: &[usize]) -> Result<Vec<PathControl>, String> {
        PathControl::from_flat(controls, steps, self.scene().robot.dof())
    }
}

impl From<&crate::path::PathMetrics> for Metrics {
    fn from(m: &crate::path::PathMetrics) -> Self {
        Metrics {
            joint_length: m.joint_length,
            ee_length: m.ee_length,
            object_displacement: m.object_displacement,
            objects_moved: m.objects_moved,
            links_in_contact: m.links_in_contact,
            duration: m.duration,
        }
    }
}

/// A state as a flat array (see the module docs for the layout).
pub fn pack_state(state: &State) -> Vec<f64> {
    let mut out = vec![0.0; state.q.len() + 3 * state.objects.len()];
    write_state(state, &mut out);
    out
}

fn write_state(state: &State, out: &mut [f64]) {
    let n = state.q.len();
    out[..n].copy_from_slice(state.q.as_slice());
    for (i, p) in state.objects.iter().enumerate() {
        out[n + 3 * i..n + 3 * i + 3].copy_from_slice(&[p.x, p.y, p.theta]);
    }
}

/// The state of a flat array for a robot with `dof` joints.
pub fn unpack_state(flat: &[f64], dof: usize) -> State {
    State {
        q: DVector::from_column_slice(&flat[..dof]),
        objects: flat[dof..]
            .chunks(3)
            .map(|c| Pose2::new(c[0], c[1], c[2]))
            .collect(),
    }
}

/// Plans a scene file with OMPL (the C++ side), as the CLI does.
pub fn solve(scene_path: &Path, options: &SolveOptions) -> Result<SolveOutput, String> {
    bridge::solve(&scene_path.to_string_lossy(), options).map_err(|e| e.what().to_string())
}

/// Benchmarks one scene with OMPL's tooling, writing `options.log`.
pub fn benchmark_scene(scene_path: &Path, options: &BenchOptions) -> Result<(), String> {
    bridge::benchmark_scene(&scene_path.to_string_lossy(), options)
        .map_err(|e| e.what().to_string())
}
