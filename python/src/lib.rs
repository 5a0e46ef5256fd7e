//! `import pushplan`: the library from Python (PyO3; `pip install .` at the repository
//! root builds it with maturin).
//!
//! ```python
//! import pushplan
//! scene = pushplan.Scene("scenes/herb_single_object.yaml")
//! plan = scene.plan(seed=2, threads=1)          # Push KPIECE, robust, shortcut: `pushplan plan`
//! plan.trajectory_q                              # NumPy (samples, joints), at 50 Hz
//! plan.check()["passed"], plan.save("plan.json")
//! ```
//!
//! A plan from Python is the plan `pushplan plan` writes for the same scene and settings,
//! byte for byte. Errors are `pushplan.Error`, with the file and field named as the CLI
//! names them; settings out of the limits table name the keyword argument.

use numpy::ndarray::{Array2, Array3};
use numpy::{PyArray1, PyArray2, PyArray3};
use pushplan::bridge::OmplSearch;
use pushplan::limits::Front;
use pushplan::planner::plan_scene::{plan_scene, PlanRequest};
use pushplan::planning::execute::{EngineKind, ExecuteSettings};
use pushplan::planning::export::ExportFormat;
use pushplan::planning::plan_file::PlanFile;
use pushplan::planning::{CommandDeadline, PlannerKind, RunSettings, PLAN_ROBUST_TRIALS};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};

pyo3::create_exception!(
    pushplan,
    Error,
    pyo3::exceptions::PyException,
    "Bad input or a plan that cannot be used: the message names the file and the field."
);

fn error(message: impl Into<String>) -> PyErr {
    Error::new_err(message.into())
}

/// `path` made absolute against the working directory (plans name their scene by it).
fn absolute(path: &Path) -> PyResult<PathBuf> {
    std::path::absolute(path).map_err(|e| error(format!("{}: {e}", path.display())))
}

/// `rows` (each of `width` values) as a 2D array.
fn matrix<'py>(py: Python<'py>, rows: Vec<Vec<f64>>, width: usize) -> Bound<'py, PyArray2<f64>> {
    let height = rows.len();
    let flat: Vec<f64> = rows.into_iter().flatten().collect();
    let array = Array2::from_shape_vec((height, width), flat).expect("rows of one width");
    PyArray2::from_owned_array(py, array)
}

/// Per sample, each object's `[x, y, yaw]`: an array (samples, objects, 3).
fn poses<'py>(
    py: Python<'py>,
    samples: &[Vec<[f64; 3]>],
    objects: usize,
) -> Bound<'py, PyArray3<f64>> {
    let flat: Vec<f64> = samples.iter().flatten().flatten().copied().collect();
    let array =
        Array3::from_shape_vec((samples.len(), objects, 3), flat).expect("a pose per object");
    PyArray3::from_owned_array(py, array)
}

/// A JSON text as Python's `json` module reads it (dicts, lists, floats).
fn from_json<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

/// A scene file, loaded and checked as `pushplan plan` loads it.
#[pyclass(module = "pushplan", frozen)]
struct Scene {
    path: PathBuf,
    scene: pushplan::Scene,
}

#[pymethods]
impl Scene {
    /// Loads the scene file at `path` (YAML; its robot and meshes relative to it).
    #[new]
    fn new(path: PathBuf) -> PyResult<Self> {
        let path = absolute(&path)?;
        let scene = pushplan::Scene::load(&path).map_err(|e| error(e.to_string()))?;
        Ok(Scene { path, scene })
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> String {
        self.scene.name.clone()
    }

    /// The scene file (absolute).
    #[getter]
    fn path(&self) -> PathBuf {
        self.path.clone()
    }

    /// The arm's joint names, in the order of every joint array.
    #[getter]
    fn joints(&self) -> Vec<String> {
        let robot = &self.scene.robot;
        (0..robot.dof())
            .map(|i| robot.chain.dof_joint(i).name.clone())
            .collect()
    }

    /// The movable objects' names, in the order of every pose array.
    #[getter]
    fn objects(&self) -> Vec<String> {
        self.scene.objects.iter().map(|o| o.name.clone()).collect()
    }

    /// The start's joint values (rad, or m): an array (joints,).
    #[getter]
    fn start_q<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.scene.start.q.as_slice())
    }

    /// The start's object poses `[x, y, yaw]` (m, m, rad; world frame): (objects, 3).
    #[getter]
    fn start_objects<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let rows = self.scene.start.objects.iter();
        matrix(py, rows.map(|p| vec![p.x, p.y, p.theta]).collect(), 3)
    }

    /// The scene check's warnings (`pushplan check SCENE.yaml`): what cannot work or will
    /// be slow, with the numbers.
    fn warnings(&self) -> Vec<String> {
        pushplan::scene::check::check(&self.scene)
            .iter()
            .map(|w| w.to_string())
            .collect()
    }

    /// Plans the scene as `pushplan plan` does: `planner` (a name of `pushplan.PLANNERS`),
    /// the scene's `planner:` values for what is not given, robust with 20 perturbed
    /// worlds unless `robust_trials` says otherwise, on every core unless `threads`;
    /// `time_limit` (s) bounds the whole call. The GIL is released while it plans.
    #[pyo3(signature = (
        planner = "push_kpiece", *, time_limit = None, seed = None, threads = None, k = None,
        goal_bias = None, shortcut = None, robust_trials = None, robust_rate = None,
        robust_particles = None
    ))]
    #[allow(clippy::too_many_arguments)]
    fn plan(
        &self,
        py: Python<'_>,
        planner: &str,
        time_limit: Option<f64>,
        seed: Option<u64>,
        threads: Option<u32>,
        k: Option<u32>,
        goal_bias: Option<f64>,
        shortcut: Option<f64>,
        robust_trials: Option<u32>,
        robust_rate: Option<f64>,
        robust_particles: Option<u32>,
    ) -> PyResult<Plan> {
        let started = std::time::Instant::now();
        let kind: PlannerKind = planner.parse().map_err(error)?;
        if !kind.yields_controls() {
            return Err(error(format!(
                "planner '{planner}' yields primitive sequences, not a plan of controls (benchmark it with `pushplan bench`)"
            )));
        }
        let own = RunSettings::of_scene(kind, &self.scene.planner);
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get() as u32);
        let options = RunSettings {
            time_limit: time_limit.unwrap_or(own.time_limit),
            seed: seed.unwrap_or(own.seed),
            threads: threads.unwrap_or(cores),
            k: k.unwrap_or(own.k),
            goal_bias: goal_bias.unwrap_or(own.goal_bias),
            shortcut: shortcut.unwrap_or(own.shortcut),
            robust_trials: robust_trials.unwrap_or(PLAN_ROBUST_TRIALS),
            robust_rate: robust_rate.unwrap_or(own.robust_rate),
            robust_particles: robust_particles.unwrap_or(own.robust_particles),
            ..own
        };
        options.check(Front::Python).map_err(error)?;
        let deadline = CommandDeadline::new(started, options.time_limit, &self.scene, false);
        let reference = self.path.display().to_string();
        let planned = py.detach(|| {
            plan_scene(
                &OmplSearch,
                &PlanRequest {
                    scene: &self.scene,
                    options: &options,
                    deadline: deadline.pushing,
                    reference: &reference,
                    search_progress: None,
                    shortcut_progress: None,
                },
            )
        });
        let planned = planned.map_err(error)?;
        Ok(Plan {
            file: planned.file,
            path: self.path.with_file_name("plan.json"),
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "pushplan.Scene('{}': {} joints, {} objects)",
            self.scene.name,
            self.scene.robot.dof(),
            self.scene.objects.len()
        )
    }
}

/// A plan: the file `pushplan plan` writes, with its states and trajectory as NumPy arrays.
#[pyclass(module = "pushplan")]
struct Plan {
    file: PlanFile,
    /// Where the plan lives (or would): its scene reference resolves from this file's folder.
    path: PathBuf,
}

impl Plan {
    fn scene(&self) -> PyResult<pushplan::Scene> {
        self.file.load_scene(&self.path).map_err(error)
    }
}

#[pymethods]
impl Plan {
    /// Reads a plan file (`pushplan plan`'s JSON), checked as `pushplan check` reads it.
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Plan> {
        let path = absolute(&path)?;
        let file = PlanFile::read(&path).map_err(error)?;
        Ok(Plan { file, path })
    }

    /// Writes the plan file to `path` (whole or not at all), its scene named from there.
    fn save(&mut self, path: PathBuf) -> PyResult<()> {
        let path = absolute(&path)?;
        let mut file = self.file.clone();
        file.scene = PlanFile::scene_reference(&self.file.scene_path(&self.path), &path);
        pushplan::output::write_whole(&path, file.to_json()).map_err(error)?;
        (self.file, self.path) = (file, path);
        Ok(())
    }

    /// The plan file's text (JSON).
    fn to_json(&self) -> String {
        self.file.to_json()
    }

    /// True when the plan reaches the goal.
    #[getter]
    fn solved(&self) -> bool {
        self.file.solved
    }

    /// The planner's name.
    #[getter]
    fn planner(&self) -> &'static str {
        self.file.settings.planner.name()
    }

    /// The seed of every random choice.
    #[getter]
    fn seed(&self) -> u64 {
        self.file.settings.seed
    }

    /// The joint names, in the order of every joint array.
    #[getter]
    fn joints(&self) -> Vec<String> {
        self.file.joints.clone()
    }

    /// The object names, in the order of every pose array.
    #[getter]
    fn objects(&self) -> Vec<String> {
        self.file.objects.clone()
    }

    /// The controls: per control `[vx, vy, omega_z]` of the end effector (m/s, rad/s,
    /// world frame) and then the null-space sample per joint (rad/s): (controls, 3 + joints).
    #[getter]
    fn controls<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let width = 3 + self.file.joints.len();
        let rows = self
            .file
            .controls
            .iter()
            .map(|c| c.ee_velocity.iter().chain(&c.nullspace).copied().collect());
        matrix(py, rows.collect(), width)
    }

    /// Each control's duration (s): (controls,).
    #[getter]
    fn durations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let durations: Vec<f64> = self.file.controls.iter().map(|c| c.duration).collect();
        PyArray1::from_vec(py, durations)
    }

    /// The joint values at the start and after each control: (controls + 1, joints).
    #[getter]
    fn state_q<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let states =
            std::iter::once(&self.file.start).chain(self.file.controls.iter().map(|c| &c.state));
        matrix(
            py,
            states.map(|s| s.q.clone()).collect(),
            self.file.joints.len(),
        )
    }

    /// The object poses at the start and after each control: (controls + 1, objects, 3).
    #[getter]
    fn state_objects<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        let states =
            std::iter::once(&self.file.start).chain(self.file.controls.iter().map(|c| &c.state));
        let samples: Vec<Vec<[f64; 3]>> = states.map(|s| s.objects.clone()).collect();
        poses(py, &samples, self.file.objects.len())
    }

    /// The executable trajectory's sample times (s, 50 Hz): (samples,).
    #[getter]
    fn trajectory_times<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.file.trajectory.times)
    }

    /// The executable trajectory's joint values: (samples, joints).
    #[getter]
    fn trajectory_q<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        matrix(py, self.file.trajectory.q.clone(), self.file.joints.len())
    }

    /// The object poses the model predicts along the trajectory: (samples, objects, 3).
    #[getter]
    fn trajectory_objects<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        poses(py, &self.file.trajectory.objects, self.file.objects.len())
    }

    /// The path's metrics as found and after shortcutting (a dict).
    #[getter]
    fn metrics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let text = serde_json::to_string(&self.file.metrics).expect("metrics serialise");
        from_json(py, &text)
    }

    /// Re-simulates the plan from its scene's start, independently of the planner, then
    /// (unless `path_only`) makes it again from its scene, settings and seed, as
    /// `pushplan check` does: a dict of `passed` (the path checks, and the plan made again
    /// the same), `all_valid`, `states_match`, `goal_reached`, `record_matches`, the
    /// `problems` found, and `remade` (`"same"`, `"differs: FIELD"`, `"not made again:
    /// WHY"`, or None when the path fails or with `path_only`).
    #[pyo3(signature = (*, path_only = false))]
    fn check<'py>(&self, py: Python<'py>, path_only: bool) -> PyResult<Bound<'py, PyDict>> {
        use pushplan::planner::remake::{remake, Remade};
        let (report, remade) = py
            .detach(|| -> Result<_, String> {
                let report = self.file.check(&self.path)?;
                let remade = match report.passed() && !path_only {
                    true => Some(remake(&OmplSearch, &self.file, &self.path)?),
                    false => None,
                };
                Ok((report, remade))
            })
            .map_err(error)?;
        let dict = PyDict::new(py);
        let same = remade.as_ref().is_none_or(|r| *r == Remade::Same);
        dict.set_item("passed", report.passed() && same)?;
        dict.set_item("all_valid", report.all_valid)?;
        dict.set_item("states_match", report.states_match)?;
        dict.set_item("goal_reached", report.goal_reached)?;
        dict.set_item("record_matches", report.record_matches)?;
        dict.set_item("problems", report.problems)?;
        dict.set_item(
            "remade",
            remade.map(|r| match r {
                Remade::Same => "same".to_string(),
                Remade::Differs(field) => format!("differs: {field}"),
                Remade::Cannot(why) => format!("not made again: {why}"),
            }),
        )?;
        Ok(dict)
    }

    /// Plays the trajectory open loop in a 3D engine (`"rapier"` or `"mujoco"`), as
    /// `pushplan execute` does: `trials` worlds (the first nominal, the others perturbed),
    /// `speed` relative to the plan's pace. The report as a dict (`success_rate`, `trials`
    /// with each object's final error, ...).
    #[pyo3(signature = (engine = "rapier", *, trials = 10, seed = 1, speed = 1.0))]
    fn execute<'py>(
        &self,
        py: Python<'py>,
        engine: &str,
        trials: usize,
        seed: u64,
        speed: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        use pushplan::limits::{SPEED, TRIALS};
        let engine: EngineKind = engine.parse().map_err(error)?;
        TRIALS.check(Front::Python, trials).map_err(error)?;
        SPEED.check(Front::Python, speed).map_err(error)?;
        let scene = self.scene()?;
        self.file.check_trajectory(&scene).map_err(error)?;
        let settings = ExecuteSettings {
            trials,
            speed,
            seed,
            engine,
            ..ExecuteSettings::default()
        };
        let report = py
            .detach(|| pushplan::planning::execute::execute(&scene, &self.file, &settings))
            .map_err(error)?;
        from_json(
            py,
            &serde_json::to_string(&report).expect("reports serialise"),
        )
    }

    /// Draws the plan into the folder `out` as `pushplan render` does (snapshots at
    /// `times` (s), default four control boundaries; the contact timeline; the HTML
    /// animation): the files written.
    #[pyo3(signature = (out, times = Vec::new()))]
    fn render(&self, out: PathBuf, times: Vec<f64>) -> PyResult<Vec<PathBuf>> {
        let files =
            pushplan::render::render(&self.file, &self.path, &out, &times).map_err(error)?;
        Ok(vec![files.snapshots, files.timeline, files.animation])
    }

    /// The trajectory as `pushplan export` writes it: `"joint-trajectory"` (a ROS
    /// `trajectory_msgs/JointTrajectory` in YAML) or `"csv"`.
    fn export(&self, format: &str) -> PyResult<String> {
        let format: ExportFormat = format.parse().map_err(error)?;
        self.file.check_trajectory(&self.scene()?).map_err(error)?;
        Ok(format.write(&self.file))
    }

    fn __repr__(&self) -> String {
        format!(
            "pushplan.Plan('{}', {}, {}: {} controls, {:.2} s)",
            self.file.scene_name,
            self.file.settings.planner.name(),
            if self.file.solved {
                "solved"
            } else {
                "not solved"
            },
            self.file.controls.len(),
            self.file.metrics.after_shortcut.duration
        )
    }
}

/// pushplan: whole-arm rearrangement planning by quasistatic pushing.
#[pymodule]
#[pyo3(name = "pushplan")]
fn pushplan_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("Error", m.py().get_type::<Error>())?;
    m.add_class::<Scene>()?;
    m.add_class::<Plan>()?;
    let planners: Vec<&str> = PlannerKind::ALL
        .into_iter()
        .filter(|k| k.yields_controls())
        .map(PlannerKind::name)
        .collect();
    m.add("PLANNERS", planners)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
